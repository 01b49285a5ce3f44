/*
** granular.c: model granular's closures, face viscosities, viscous heating
** and temperature equation (granular.h).
**
** Lifetimes: granmodel_closures evaluates everything at the state (c^m,
** T^m) once per step (gran_courant calls it; gran_step again only when the
** state changed since, m->fresh); the momentum solves read eta_f, the
** temperature step lam_f, eps_c, eta_c; granmodel_commit marks the state
** changed.  The temperature step computes into T1 and changes no field,
** so a failed step loses nothing (newtonian.c commits).
*/
#include "newtonian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

#include <time.h>

/* Monotonic clock in seconds, for the step profile (Granular.t_*). */
static double clock_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The unknowns' field names, for messages. */
#define C_NAME "alpha"
#define T_NAME "Theta"

static int check_initial(const Granular *g, Err *e)
{
    const FvMesh *f = g->f;
    const GranularProps *pr = &g->pr;
    const double *c = g->rho->v, *T = g->gm.T->v;
    for (int i = 0; i < f->nowned; i++) {
        const double *x = f->node + 3 * i;
        if (!(c[i] >= 0 && c[i] <= pr->k.cmax - pr->dc))
            return err_set(e, NULL, 0,
                           C_NAME " = %g in cell %d at (%g %g %g): the volume fraction must lie in [0, cMax - deltaC] = "
                           "[0, %g]",
                           c[i], i, x[0], x[1], x[2], pr->k.cmax - pr->dc);
        if (!(T[i] > 0 && isfinite(T[i])))
            return err_set(e, NULL, 0,
                           T_NAME " = %g in cell %d at (%g %g %g): the granular temperature must be positive "
                           "(Tmin %g is the floor the steps keep)",
                           T[i], i, x[0], x[1], x[2], pr->Tmin);
    }
    return 0;
}

/* The arrays the steps write; gran_alloc calls it after the set-up's
   geometry is freed, so that the two are never alive together. */
void granmodel_alloc(Granular *g)
{
    GranModel *m = &g->gm;
    size_t nc = (size_t)g->f->ncells + 1, nf = (size_t)g->f->nfaces + 1, nb = (size_t)g->f->nboundary + 1;
    double **cell[] = {&m->eta_c, &m->lam_c, &m->eps_c, &m->pc, &m->cfl, &m->T1, &m->heat, &m->uk, &m->speed_c};
    for (size_t i = 0; i < sizeof cell / sizeof cell[0]; i++) *cell[i] = mem_calloc(nc, sizeof(double));
    double **face[] = {&m->eta_f, &m->lam_f};
    for (size_t i = 0; i < sizeof face / sizeof face[0]; i++) *face[i] = mem_calloc(nf, sizeof(double));
    double **bnd[] = {&m->cb, &m->Tb, &m->etab, &m->lamb, &m->tb};
    for (size_t i = 0; i < sizeof bnd / sizeof bnd[0]; i++) *bnd[i] = mem_calloc(nb, sizeof(double));
    m->ub = mem_calloc(3 * nb, sizeof(double));
    m->jac = g->force; /* the core's work array, free when the heating runs (newtonian.c) */
    /* partialSlip's Coulomb bound (eq. 2.35): the wall pressure (the
       core's boundary pressures, g->xbr when the momentum is assembled)
       and the wall viscosity eta_f of the boundary faces */
    bc_set_wall_state(&g->bc_U, g->xbr, m->eta_f + g->f->ninternal);
    if (g->gravity != GRAN_WELL_BALANCED) return;
    double **prof[] = {&m->prof_v, &m->prof_p, &m->prof_theta};
    for (size_t i = 0; i < sizeof prof / sizeof prof[0]; i++) *prof[i] = mem_calloc(nc, sizeof(double));
    m->grav = mem_calloc(3 * nc, sizeof(double));
}

/* The inverse of 3x3 a (row-major) into b, restricted to the axes other
   than skip (-1: none; the rows and columns of skip are 0).  a is
   symmetric positive definite on those axes (a closed cell's normals span
   them); a cell without faces (a halo slot not yet filled) gets b = 0. */
static void inverse_sym(const double *a, int skip, double *b)
{
    memset(b, 0, 9 * sizeof(double));
    if (skip >= 0) {
        int i = skip == 0 ? 1 : 0, j = skip == 2 ? 1 : 2;
        double det = a[3 * i + i] * a[3 * j + j] - a[3 * i + j] * a[3 * j + i];
        if (!(det > 0)) return;
        b[3 * i + i] = a[3 * j + j] / det, b[3 * j + j] = a[3 * i + i] / det;
        b[3 * i + j] = -a[3 * i + j] / det, b[3 * j + i] = -a[3 * j + i] / det;
        return;
    }
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) { /* the cofactor of (c, r) */
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            b[3 * r + c] = a[3 * r1 + c1] * a[3 * r2 + c2] - a[3 * r1 + c2] * a[3 * r2 + c1];
        }
    double det = a[0] * b[0] + a[1] * b[3] + a[2] * b[6];
    for (int q = 0; q < 9; q++) b[q] = det > 0 ? b[q] / det : 0;
}

/* A symmetric 3x3 matrix (row-major) as its upper triangle, and back:
   the metric is symmetric to the bit (M_C's entries are products that
   commute, and so are inverse_sym's cofactors). */
static void sym_pack(const double *a, double *p)
{
    p[0] = a[0], p[1] = a[1], p[2] = a[2], p[3] = a[4], p[4] = a[5], p[5] = a[8];
}

static void sym_unpack(const double *p, double *a)
{
    a[0] = p[0], a[1] = a[3] = p[1], a[2] = a[6] = p[2];
    a[4] = p[3], a[5] = a[7] = p[4], a[8] = p[5];
}

/* The displacement d from the owner's node to the point across boundary
   or internal face i (the neighbour's node, a cyclic partner's node moved
   by the period, a boundary face's centre); returns the cell whose value
   sits there, or -1 for a boundary value. */
static int lsq_point(const FvMesh *f, int i, double d[3])
{
    double x[3];
    int n = fvmesh_across(f, i, x);
    if (n < 0) memcpy(x, f->m->face_centre + 3 * i, sizeof x);
    const double *o = f->node + 3 * f->m->owner[i];
    for (int a = 0; a < 3; a++) d[a] = x[a] - o[a];
    return n;
}

/* Each cell's metric of the heating's Jacobian (granular.h, by
   heatingSchemes' jacobian): faceMetric the inverse of M_C = sum_f n_f
   n_f^T A_f, leastSquares that of sum_f d d^T / |d|^2 (and each face's
   d / |d|^2 into lsq), faceWeight eq. 4.65's alpha / sum_f A_f on the
   plane's or space's axes, over the faces that are not empty. */
static void jacobian_metric(const Granular *g, double *jmet, double *lsq)
{
    const FvMesh *f = g->f;
    /* M_C's upper triangle accumulates in jmet itself, and each cell's
       inverse replaces it (no array of 9 a cell while the set-up's
       arrays are still alive: that was the run's peak) */
    static const int upper[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    memset(jmet, 0, sizeof(double) * 6 * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        double v[3], w;
        if (g->jacobian == GRAN_JAC_LSQ) {
            lsq_point(f, i, v);
            w = 1 / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int a = 0; a < 3; a++) lsq[3 * i + a] = v[a] * w;
        } else {
            memcpy(v, f->m->face_area + 3 * i, sizeof v);
            w = 1 / f->mag_sf[i];
        }
        int cells[2] = {f->m->owner[i], i < f->ninternal ? f->m->neighbour[i] : -1};
        for (int q = 0; q < 2 && cells[q] >= 0; q++)
            for (int u = 0; u < 6; u++) jmet[6 * cells[q] + u] += v[upper[u][0]] * v[upper[u][1]] * w;
    }
    for (int c = 0; c < f->ncells; c++) {
        double M[9], W[9];
        sym_unpack(jmet + 6 * c, M);
        if (g->jacobian != GRAN_JAC_THESIS) {
            inverse_sym(M, f->empty_axis, W);
        } else {
            /* trace(M_C) = sum_f A_f (unit normals) */
            double sum = M[0] + M[4] + M[8], alpha = f->empty_axis >= 0 ? 2 : 3;
            memset(W, 0, sizeof W);
            for (int a = 0; a < 3; a++)
                if (a != f->empty_axis && sum > 0) W[4 * a] = alpha / sum;
        }
        sym_pack(W, jmet + 6 * c);
    }
}

static int init_solver(Granular *g, const Dict *fvsolution, Err *e)
{
    GranModel *m = &g->gm;
    fvm_init_like(&m->op, &g->op, &m->bc_T);
    if (linsolve_settings(&m->set, fvsolution, T_NAME, e)) return -1;
    m->L = linsolve_new_shared(&m->set, g->L[0], e);
    return m->L ? 0 : -1;
}

int granmodel_init(Granular *g, Field *T, const Dict *fvsolution, Err *e)
{
    GranModel *m = &g->gm;
    m->T = T;
    if (bc_init(&m->bc_T, T, g->f, e)) return -1;
    m->jmet = mem_calloc(6 * ((size_t)g->f->ncells + 1), sizeof(double));
    if (g->jacobian == GRAN_JAC_LSQ) m->lsq = mem_calloc(3 * (size_t)g->f->nfaces + 1, sizeof(double));
    jacobian_metric(g, m->jmet, m->lsq);
    if (check_initial(g, e)) return -1;
    m->solved = !g->pr.freezeT;
    return m->solved ? init_solver(g, fvsolution, e) : 0;
}

void granmodel_free(GranModel *m)
{
    if (m->L) linsolve_free(m->L);
    if (m->set.name) linsolve_settings_free(&m->set);
    if (m->op.dist) fvm_free(&m->op);
    if (m->bc_T.fm) bc_free(&m->bc_T);
    void *arr[] = {m->eta_c, m->lam_c, m->eps_c, m->pc, m->cfl, m->T1, m->heat, m->uk, m->eta_f, m->lam_f,
                   m->speed_c, m->cb, m->Tb, m->etab, m->lamb, m->tb, m->ub, m->jmet, m->lsq,
                   m->prof_v, m->prof_p, m->prof_theta, m->grav};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) free(arr[i]);
    memset(m, 0, sizeof *m);
}

/* Face values by eq. 4.61's rule through each face's CENTRE row: the mean
   of the two cells between whole Cartesian cells, the interpolation near
   cut cells, the boundary value at boundary faces; never negative (a
   multilinear row with reflected sources may undershoot). */
static void face_values(const Granular *g, const double *xc, const double *xb, double *xf)
{
    const FvMesh *f = g->f;
    for (int i = 0; i < f->nfaces; i++)
        xf[i] = f->empty_face[i] ? 0 : fmax(0, stencil_apply(&g->ip->face, interp_row(i, INTERP_CENTRE), f->ncells, xc, xb));
}

void granmodel_closures(Granular *g)
{
    GranModel *m = &g->gm;
    if (m->fresh) return;
    double t0 = clock_s();
    const FvMesh *f = g->f;
    const GranCoeffs *k = &g->pr.k;
    const double *c = g->rho->v, *T = m->T->v;
    for (int i = 0; i < f->ncells; i++) {
        GranClosure cl;
        closure_eval(k, c[i], T[i], &cl);
        m->eta_c[i] = cl.eta, m->lam_c[i] = k->KT * cl.lambda, m->eps_c[i] = cl.eps, m->pc[i] = cl.p;
        m->speed_c[i] = sqrt(fmax(cl.dpdc, 0));
    }
    bc_values(&g->bc_rho, c, m->cb);
    bc_update(&m->bc_T, T);
    bc_values(&m->bc_T, T, m->Tb);
    for (int b = 0; b < f->nboundary; b++) {
        if (f->empty_face[f->ninternal + b]) continue;
        GranClosure cl;
        closure_eval(k, fmin(fmax(m->cb[b], 0), k->cmax - g->pr.dc), fmax(m->Tb[b], g->pr.Tmin), &cl);
        m->etab[b] = cl.eta, m->lamb[b] = k->KT * cl.lambda;
    }
    face_values(g, m->eta_c, m->etab, m->eta_f);
    face_values(g, m->lam_c, m->lamb, m->lam_f);
    m->fresh = 1;
    g->t_explicit += clock_s() - t0; /* the profile's "explicit terms" */
}

double granmodel_boundary_pressure(const Granular *g, int b)
{
    const GranModel *m = &g->gm;
    return closure_pressure(&g->pr.k, fmin(fmax(m->cb[b], 0), g->pr.k.cmax - g->pr.dc), fmax(m->Tb[b], g->pr.Tmin));
}

void granmodel_limit_c(Granular *g)
{
    GranModel *m = &g->gm;
    const GranularProps *pr = &g->pr;
    double top = pr->k.cmax - pr->dc;
    memset(&m->last, 0, sizeof m->last);
    for (int i = 0; i < g->f->ncells; i++) {
        double *c = &g->rho1[i];
        if (*c > top) *c = top, m->last.cmax += i < g->f->nowned;
        if (*c < pr->cmin) m->last.cmin += i < g->f->nowned;
        m->cfl[i] = fmax(*c, pr->cmin);
    }
}

/* U's boundary values with the wall velocity u_S at impermeable walls:
   slip walls are at rest (u_S = 0), partialSlip walls move at their
   wallVelocity, the others' values are their wall velocities already (granular.h: the heating sees the whole gradient).
   With heatingSchemes' wallVelocity boundary the boundary values u_B
   themselves (granular.h). */
static void wall_values(Granular *g)
{
    const FvMesh *f = g->f;
    double *ub = g->gm.ub;
    bc_values(&g->bc_U, g->U->v, ub);
    if (g->heat_wall == GRAN_HEAT_BOUNDARY) return;
    for (int b = 0; b < f->nboundary; b++) {
        if (f->empty_face[f->ninternal + b] || !g->wall[b]) continue;
        const BcPatch *bp = &g->bc_U.patch[f->face_patch[b]];
        if (bp->kind == BC_SLIP) ub[3 * b] = ub[3 * b + 1] = ub[3 * b + 2] = 0;
        if (bp->kind == BC_PARTIAL_SLIP) memcpy(ub + 3 * b, bp->us + 3 * (f->ninternal + b - bp->start), 3 * sizeof(double));
    }
}

/* The outward normal derivative of eq. 4.62 at face i of the cell values
   uc and the boundary values ubk (one component, stride 1); a Neumann face
   (zeroGradient) its given gradient. */
static double normal_derivative(const Granular *g, int i, int k, const double *uc, const double *ubk)
{
    const FvMesh *f = g->f;
    const Stencil *s = &g->ip->face;
    if (g->op.kind[i] == FVM_NEUMANN) {
        const Bc *bc = &g->bc_U;
        size_t bk = (size_t)bc_slot(bc, i - f->ninternal) * 3 + (size_t)k;
        double d = bc->gb[bk];
        if (bc->ga[bk] != 0) d += bc->ga[bk] * stencil_apply(s, interp_row(i, INTERP_MINUS), f->ncells, uc, ubk);
        return d;
    }
    double plus = stencil_apply(s, interp_row(i, INTERP_PLUS), f->ncells, uc, ubk);
    return (plus - stencil_apply(s, interp_row(i, INTERP_MINUS), f->ncells, uc, ubk)) / g->op.dist[i];
}

/* Component k's differences summed into m->jac (3 a cell: row k of the
   Jacobian's sums): (du/dn) n A per face (faceMetric, faceWeight: eq.
   4.65) or (u_across - u_C) d / |d|^2 (leastSquares).  Either is one
   number per face and component for both cells (granular.h). */
static void jacobian_sums(Granular *g, int k)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        double v[3], d;
        int o = f->m->owner[i];
        if (g->jacobian == GRAN_JAC_LSQ) {
            int n = fvmesh_across(f, i, v); /* the cell across (v: scratch) */
            memcpy(v, m->lsq + 3 * i, sizeof v);
            d = (n >= 0 ? m->uk[n] : m->tb[i - f->ninternal]) - m->uk[o];
        } else {
            memcpy(v, f->m->face_area + 3 * i, sizeof v);
            d = normal_derivative(g, i, k, m->uk, m->tb);
        }
        for (int j = 0; j < 3; j++) m->jac[3 * o + j] += d * v[j];
        if (i < f->ninternal)
            for (int j = 0; j < 3; j++) m->jac[3 * f->m->neighbour[i] + j] += d * v[j];
    }
}

/* Adds component k's energy loss to heat: sum_f w eta_f (du_k/dn)^2 A_f
   dist_f, the kinetic energy each face's diffusion flux (eq. 4.62) takes
   out, half to each cell of a two-sided face, all to the owner of a
   boundary face (faceDissipation, granular.h). */
static void dissipation_sums(Granular *g, int k)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        double d = normal_derivative(g, i, k, m->uk, m->tb);
        double e = m->eta_f[i] * d * d * f->mag_sf[i] * g->op.dist[i];
        if (fvmesh_two_sided(f, i)) e *= 0.5;
        m->heat[f->m->owner[i]] += e;
        if (i < f->ninternal) m->heat[f->m->neighbour[i]] += e;
    }
}

/* heat[c] = K_T eta_C sum_ij (J_C)_ij^2 with the Jacobian of u^m (eq.
   4.65, or its metric or least-squares forms), or K_T / V_C times the
   faces' energy loss (faceDissipation); granular.h. */
static void heating(Granular *g)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    int diss = g->jacobian == GRAN_JAC_DISS;
    wall_values(g);
    memset(m->heat, 0, sizeof(double) * (size_t)f->ncells);
    for (int k = 0; k < 3; k++) {
        if (k == f->empty_axis) continue; /* its row of J is zero */
        for (int c = 0; c < f->ncells; c++) m->uk[c] = g->U->v[3 * c + k];
        for (int b = 0; b < f->nboundary; b++) m->tb[b] = m->ub[3 * b + k];
        if (diss) {
            dissipation_sums(g, k);
            continue;
        }
        memset(m->jac, 0, sizeof(double) * 3 * (size_t)f->ncells);
        jacobian_sums(g, k);
        for (int c = 0; c < f->ncells; c++) { /* row k of J = D M_C^-1, squared into heat */
            const double *D = m->jac + 3 * c;
            double W[9];
            sym_unpack(m->jmet + 6 * c, W);
            for (int j = 0; j < 3; j++) {
                double Jkj = D[0] * W[j] + D[1] * W[3 + j] + D[2] * W[6 + j];
                m->heat[c] += Jkj * Jkj;
            }
        }
    }
    double w = g->pr.k.KT;
    for (int c = 0; c < f->ncells; c++) m->heat[c] *= diss ? w / f->m->cell_vol[c] : w * m->eta_c[c];
}

/* The convection of c T (eq. 4.60: the upwind state, or the scheme of
   div(phi,Theta)) into g->force's first ncells; c T^m into m->uk. */
static void convect_cT(Granular *g)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    const double *c = g->rho->v, *T = m->T->v;
    for (int i = 0; i < f->ncells; i++) m->uk[i] = c[i] * T[i];
    bc_states(&g->bc_rho, c, m->cb);
    bc_states(&m->bc_T, T, m->tb);
    for (int b = 0; b < f->nboundary; b++) m->tb[b] *= m->cb[b]; /* inflow with fixed c: c_F T_C */
    tvd_div(&g->tvd, &g->div_T, g->phi, m->uk, m->tb, 1, g->force);
    bc_values(&g->bc_rho, c, m->cb); /* back to the values granmodel_boundary_pressure reads */
}

/* V c^{m+1}/dt + eps^m c^{m+1} V - div(K_T lambda_f grad) on the matrix,
   V (cT)^m/dt - div(phi cT) + heat V on the right-hand side, and the
   source hook's integrals of s_T when there is a hook (newtonian.h). */
static void assemble_T(Granular *g, double dt)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    FvMatrix *M = &g->M; /* the momentum's, its components solved (init_solver) */
    fvmatrix_zero(M);
    fvm_ddt(M, f, m->cfl, dt);
    for (int r = 0; r < M->nrows; r++) M->val[M->diag[r]] += m->eps_c[r] * m->cfl[r] * f->m->cell_vol[r];
    fvm_laplacian_matrix_f(&m->op, M, 0, m->lam_f);
    fvm_laplacian_rhs_f(&m->op, M, 0, m->lam_f);
    for (int r = 0; r < M->nrows; r++) {
        double V = f->m->cell_vol[r];
        M->rhs[r] += V * m->uk[r] / dt - g->force[r] + m->heat[r] * V;
    }
    if (g->src.fn)
        for (int r = 0; r < M->nrows; r++) M->rhs[r] += g->src_T[r];
}

int granmodel_temperature(Granular *g, double dt, Err *e)
{
    GranModel *m = &g->gm;
    const FvMesh *f = g->f;
    memcpy(m->T1, m->T->v, sizeof(double) * (size_t)f->ncells);
    if (!m->solved) return 0;
    double t0 = clock_s();
    heating(g);
    convect_cT(g);
    assemble_T(g, dt);
    double t1 = clock_s();
    g->t_assembly += t1 - t0; /* the profile's "assembly": heating, convection of cT, the matrix */
    int rc = linsolve_solve_tracked(m->L, m->T1, &m->st, e);
    g->t_solve += clock_s() - t1;
    if (rc) return -1;
    for (int i = 0; i < f->ncells; i++) {
        if (!isfinite(m->T1[i])) {
            const double *x = f->node + 3 * i;
            return err_set(e, NULL, 0, "cell %d at (%g %g %g): " T_NAME " not a number (time step %g too large?)", i,
                           x[0], x[1], x[2], dt);
        }
        if (m->T1[i] < g->pr.Tmin) m->T1[i] = g->pr.Tmin, m->last.tmin += i < f->nowned;
    }
    return 0;
}

void granmodel_commit(Granular *g)
{
    GranModel *m = &g->gm;
    memcpy(m->T->v, m->T1, sizeof(double) * (size_t)g->f->ncells);
    m->total.cmax += m->last.cmax, m->total.tmin += m->last.tmin, m->total.cmin += m->last.cmin;
    m->fresh = 0;
}
