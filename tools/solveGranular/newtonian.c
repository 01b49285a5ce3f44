/*
** newtonian.c: model Newtonian (newtonian.h): eq. 5.1 by eq. 4.66.
**
** The step computes the new state into its own arrays (rho1, and mom for
** the velocity) and copies it into the fields only when every solve
** converged and every value is finite with a positive density, so a
** failed step loses nothing.  Components are solved in order x, y, z on
** one matrix, assembled once a step and again only for a component whose
** boundary coefficients differ (slip), and with one PETSc solver when
** their fvSolution entries agree (fv/linsolve.h).  The velocity component
** along the empty axis of a 2-D grid is not solved and keeps its value,
** as OpenFOAM's solvers do.
**
** Memory: the step is memory-bound (doc/performance.md, "Roofline"), so
** its work arrays are few and each serves several things in turn:
**   force  the convection of rho (its first ncells), then of rho u, then
**          the pressure force; model granular (granular.c): after the
**          solves one row of the heating's Jacobian sums at a time, then
**          the convection of c T (its first ncells);
**   mom    rho u, then V (rho u)^m / dt minus its convection, the part of
**          the right-hand side that does not depend on the component's
**          matrix; once component k is assembled and solved its
**          solution replaces component k, so after the solves mom holds
**          u^{m+1};
**   x      the cell pressures RsT rho of the face pressures, then each
**          solve's unknown; the Courant number's cells before the step;
**   xb     U's boundary values (the fluxes), then its states times rho's
**          (the convection of rho u);
**   xbr    rho's boundary states (convection, mass flow), then the
**          boundary pressures.
** The boundary arrays' entries of empty faces are never written nor read
** (fv/bc.h skips empty patches).
** The face pressures go straight into the force (hydro_force), never
** into an array of faces.  The sums are the same, in the same order, as
** with an array for each (doc/performance.md: results bit for bit).
*/
#include "newtonian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fvc.h"
#include "mem.h"

const DictKey gran_div_keys[] = {
    {"default", "Gauss upwind",
     "convection of rho and rho u: Gauss upwind (eq. 4.60) | Gauss limitedLinear k (0 <= k <= 1) | Gauss vanLeer "
     "(bounded second order, doc/theory.md) | none (then both below are required)"},
    {"div(phi,rho)", "default", "convection in the continuity equation"},
    {"div(phi,U)", "default", "convection of momentum rho u"},
    {"div(phi,Theta)", "default", "model granular: convection of c T"},
    {NULL, NULL, NULL}};

const char *const gran_gravity_names[] = {"wellBalanced", "cellSource", NULL};

const DictKey gran_gravity_keys[] = {
    {"default", "wellBalanced",
     "pressure force and gravity: wellBalanced (each cell's hydrostatic profile carried to the faces, p = RsT rho "
     "exp(g.(x - x_C)/RsT), model granular its rest profile at its own T: a column or packing at rest stays at "
     "rest to round-off on every grid) | cellSource (the plain face pressure and rho_C g V_C, the thesis's: no "
     "rest state on cut and Voronoi grids); the same when g = 0"},
    {NULL, NULL, NULL}};

const char *const gran_heating_names[] = {"wall", "boundary", NULL};
static const char *const jacobian_names[] = {"faceMetric", "leastSquares", "faceWeight", "faceDissipation", NULL};

const DictKey gran_heating_keys[] = {
    {"wallVelocity", "wall",
     "model granular's viscous heating at walls: wall (the wall's own velocity u_S at slip and partialSlip walls, "
     "the thesis's: a sliding wall's jump heats its cells by eta (jump/h)^2, which grows without bound as h -> "
     "0) | boundary (the boundary value u_B the momentum diffusion uses: the same at sticking walls, the "
     "gradient inside the grain at sliding ones; ours)"},
    {"jacobian", "faceMetric",
     "the velocity gradient of the heating: faceMetric ((sum_f du/dn n^T A) M_C^-1, M_C = sum_f n n^T A, from "
     "the face derivatives of eq. 4.62: exact for a linear u on any cell; ours) | leastSquares (weighted least "
     "squares over the nodes across the faces and the boundary faces' centres, weights 1/d^2: exact for a "
     "linear u; ours) | faceWeight (eq. 4.65's weight alpha A_f / sum A: the thesis's, exact on squares and "
     "cubes only)"},
    {NULL, NULL, NULL}};

static int read_div(const Dict *fvschemes, TvdScheme div[3], Err *e)
{
    static const char *const keys[3] = {"div(phi,rho)", "div(phi,U)", "div(phi,Theta)"};
    TvdScheme def = {TVD_UPWIND, 1};
    div[0] = div[1] = div[2] = def;
    const Dict *d = dict_subdict_opt(fvschemes, "divSchemes");
    if (!d) return 0;
    if (dict_check_keys(d, gran_div_keys, e)) return -1;
    const DictEntry *en = dict_find(d, "default");
    int none = en && !en->dict && en->nvals == 1 && en->vals[0]->kind == DN_WORD && !strcmp(en->vals[0]->text, "none");
    if (en && !none && tvd_parse(en, &def, e)) return -1;
    for (int j = 0; j < 3; j++) {
        en = dict_find(d, keys[j]);
        div[j] = def;
        if (en && tvd_parse(en, &div[j], e)) return -1;
        if (!en && none && j < 2) /* div(phi,Theta) only matters to model granular: checked there */
            return err_set(e, d->file, d->line, "divSchemes: %s missing (default is none)", keys[j]);
    }
    return 0;
}

static int read_gravity(const Dict *fvschemes, GranSchemes *sch, Err *e)
{
    sch->gravity = GRAN_WELL_BALANCED;
    const Dict *d = dict_subdict_opt(fvschemes, "gravitySchemes");
    if (!d) return 0;
    if (dict_check_keys(d, gran_gravity_keys, e)) return -1;
    return dict_choice_or(d, "default", gran_gravity_names, GRAN_WELL_BALANCED, &sch->gravity, e);
}

static int read_heating(const Dict *fvschemes, GranSchemes *sch, Err *e)
{
    sch->heat_wall = GRAN_HEAT_WALL;
    sch->jacobian = GRAN_JAC_FACE;
    const Dict *d = dict_subdict_opt(fvschemes, "heatingSchemes");
    if (!d) return 0;
    if (dict_check_keys(d, gran_heating_keys, e) ||
        dict_choice_or(d, "wallVelocity", gran_heating_names, GRAN_HEAT_WALL, &sch->heat_wall, e))
        return -1;
    return dict_choice_or(d, "jacobian", jacobian_names, GRAN_JAC_FACE, &sch->jacobian, e);
}

int gran_read_schemes(const Dict *fvschemes, GranSchemes *sch, Err *e)
{
    sch->div[2].kind = TVD_UPWIND;
    return read_div(fvschemes, sch->div, e) || read_gravity(fvschemes, sch, e) || read_heating(fvschemes, sch, e)
               ? -1
               : 0;
}


/* Does the model carry barotropic rest profiles (model granular,
   wellBalanced)? */
static int profiled(const Granular *g) { return g->model == MODEL_GRANULAR && g->gravity == GRAN_WELL_BALANCED; }

/* Impermeable boundary faces of U: noSlip, movingWall, rotatingWallVelocity,
   slip, partialSlip, symmetryPlane (bc_kind_wall; granular.c's wall
   velocities follow the same list). */
static void mark_walls(Granular *g)
{
    const FvMesh *f = g->f;
    g->wall = mem_calloc((size_t)f->nboundary + 1, 1);
    for (int p = 0; p < g->bc_U.npatches; p++) {
        const BcPatch *bp = &g->bc_U.patch[p];
        int w = bc_kind_wall(bp->kind);
        for (int j = 0; j < bp->size; j++) g->wall[bp->start + j - f->ninternal] = (char)w;
    }
}

/* partialSlip is the granular model's Coulomb wall (eq. 2.35): its wall
   stress p tan(phi) needs the granular pressure; model Newtonian refuses
   it at the line of U's patch entry. */
static int check_partial_slip(const Granular *g, const Field *U, Err *e)
{
    for (int p = 0; p < g->bc_U.npatches; p++)
        if (g->bc_U.patch[p].kind == BC_PARTIAL_SLIP)
            return err_set(e, U->pf[p].file, U->pf[p].line,
                           "partialSlip is the granular model's Coulomb wall (model granular); model Newtonian takes "
                           "noSlip, slip or movingWall");
    return 0;
}

/* The work arrays, each used for several things in turn (the lifetimes
   at the top of the file): 9 doubles a cell and one a face. */
static void alloc_work(Granular *g)
{
    size_t nc = (size_t)g->f->ncells + 1, nf = (size_t)g->f->nfaces + 1, nb = (size_t)g->f->nboundary + 1;
    g->phi = mem_calloc(nf, sizeof(double));
    g->rho1 = mem_alloc(nc * sizeof(double));
    g->mom = mem_alloc(3 * nc * sizeof(double));
    g->force = mem_alloc(3 * nc * sizeof(double));
    g->x = mem_alloc(nc * sizeof(double));
    g->xb = mem_alloc(3 * nb * sizeof(double));
    g->xbr = mem_alloc(nb * sizeof(double));
    g->patch_out = mem_calloc((size_t)g->bc_rho.npatches + 1, sizeof(double));
}

/* The component u . S_f may leave out: in 2-D the empty axis, when no
   non-empty face's area has a component along it (that term would add an
   exact zero to every flux); else -1. */
static int flux_skip(const FvMesh *f)
{
    int e = f->empty_axis;
    for (int i = 0; i < f->nfaces && e >= 0; i++)
        if (!f->empty_face[i] && f->m->face_area[3 * i + e] != 0) return -1;
    return e;
}

/* The matrix, its diffusion positions and the solvers of the components. */
static int init_solvers(Granular *g, const Dict *fvsolution, Err *e)
{
    FvPattern pat;
    fvpattern_init(&pat, g->f);
    fvm_pattern(&pat, g->f, g->ip);
    fvmatrix_init(&g->M, &pat);
    if (fvm_init(&g->op, &g->M, g->f, g->ip, &g->bc_U, e)) return -1;
    static const char *const names[3] = {"Ux", "Uy", "Uz"};
    for (int k = 0; k < 3; k++)
        if (k != g->f->empty_axis) g->axis[g->naxes++] = k;
    for (int j = 0; j < g->naxes; j++) {
        if (linsolve_settings(&g->set[j], fvsolution, names[g->axis[j]], e)) return -1;
        /* one PETSc solver for all components when their settings agree */
        g->L[j] = j ? linsolve_new_shared(&g->set[j], g->L[j - 1], e) : linsolve_new(&g->set[j], &g->M, e);
        if (!g->L[j]) return -1;
    }
    return 0;
}

int gran_init(Granular *g, const FvMesh *f, const Interp *ip, const GranularProps *pr, const GranSchemes *sch,
              Field *rho, Field *U, Field *T, const Dict *fvsolution, Err *e)
{
    memset(g, 0, sizeof *g);
    g->model = pr->model;
    g->f = f;
    g->div_rho = sch->div[0];
    g->div_U = sch->div[1];
    g->div_T = sch->div[2];
    int upwind = sch->div[0].kind == TVD_UPWIND && sch->div[1].kind == TVD_UPWIND &&
                 (g->model != MODEL_GRANULAR || sch->div[2].kind == TVD_UPWIND);
    tvd_init(&g->tvd, f, upwind ? 0 : 3);
    g->ip = ip;
    g->pr = *pr;
    g->gravity = sch->gravity;
    g->heat_wall = sch->heat_wall;
    g->jacobian = sch->jacobian;
    static const double none[3] = {0, 0, 0};
    const double *gw = g->gravity == GRAN_WELL_BALANCED ? pr->g : none;
    if (profiled(g))
        hydro_init_profile(&g->hy, f, ip, gw);
    else
        hydro_init(&g->hy, f, ip, gw, g->model == MODEL_GRANULAR ? 1 : pr->RsT);
    g->rho = rho;
    g->U = U;
    if (bc_init(&g->bc_rho, rho, f, e)) return -1;
    if (bc_init(&g->bc_U, U, f, e)) return -1;
    /* the isothermal model's open-boundary rule (bc_open.c); the granular
       inflow fixes c and u both, as the thesis's (spec §1.4) */
    if (g->model != MODEL_GRANULAR &&
        (bc_check_open(&g->bc_rho, &g->bc_U, rho, U, sqrt(pr->RsT), e) || check_partial_slip(g, U, e)))
        return -1;
    mark_walls(g);
    g->flux_skip = flux_skip(f);
    if (linsolve_init(e) || init_solvers(g, fvsolution, e)) return -1;
    return g->model == MODEL_GRANULAR ? granmodel_init(g, T, fvsolution, e) : 0;
}

void gran_alloc(Granular *g)
{
    alloc_work(g);
    if (g->model == MODEL_GRANULAR) granmodel_alloc(g);
}

void gran_free(Granular *g)
{
    granmodel_free(&g->gm); /* its solver may share the components' (granular.c) */
    for (int j = 0; j < g->naxes; j++) {
        linsolve_free(g->L[j]);
        linsolve_settings_free(&g->set[j]);
    }
    if (g->op.dist) fvm_free(&g->op);
    if (g->M.off) fvmatrix_free(&g->M);
    if (g->bc_U.fm) bc_free(&g->bc_U);
    if (g->bc_rho.fm) bc_free(&g->bc_rho);
    tvd_free(&g->tvd);
    if (g->hy.f) hydro_free(&g->hy);
    void *arr[] = {g->wall, g->phi, g->rho1, g->mom, g->force, g->x, g->xb, g->xbr, g->patch_out};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) free(arr[i]);
    free(g->src_rho);
    free(g->src_m);
    free(g->src_T);
    memset(g, 0, sizeof *g);
}

/* Monotonic clock in seconds, for the step profile (granular.c keeps its own for its parts). */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int gran_open_patch(const Granular *g, int q) { return bc_kind_open(g->bc_U.patch[q].kind); }

/* The mass flow out of each open patch, the boundary part of the upwind
   divergence of rho (the same products fvc_div_upwind sums), and its
   running integral. */
static void mass_flow(Granular *g, const double *rho, double dt)
{
    const FvMesh *f = g->f;
    double net = 0;
    for (int q = 0; q < g->bc_rho.npatches; q++) {
        const BcPatch *bp = &g->bc_rho.patch[q];
        double s = 0;
        if (gran_open_patch(g, q))
            for (int i = bp->start; i < bp->start + bp->size; i++) {
                if (f->empty_face[i]) continue;
                double up = g->phi[i] >= 0 ? rho[f->m->owner[i]] : g->xbr[i - f->ninternal];
                s += up * g->phi[i];
            }
        g->patch_out[q] = s;
        net += s;
    }
    g->out_total += dt * net;
}

/* Component k of the vector field v (ncells * 3) into out. */
static void component(const FvMesh *f, const double *v, int k, double *out)
{
    for (int c = 0; c < f->ncells; c++) out[c] = v[3 * c + k];
}

/* u_f . S_f of face i (not empty, not a wall) from its CENTRE row over
   the cell velocities U and the boundary values ub (3 each), component
   skip left out: u_f = sum_s w_s u_s (eq. 4.61), summed as stencil_apply
   sums, and the products added component by component from 0. */
static inline double face_flux(const Stencil *s, int i, int nc, const double *U, const double *ub, const double *S,
                               int skip)
{
    double uf[3] = {0, 0, 0}, phi = 0;
    int r = interp_row(i, INTERP_CENTRE);
    if (stencil_is_pair(s, r)) { /* eq. 4.61: the mean of the two cells */
        const double *a = U + 3 * (size_t)s->pa[i], *b = U + 3 * (size_t)s->pb[i];
        for (int k = 0; k < 3; k++) uf[k] += 0.5 * a[k], uf[k] += 0.5 * b[k];
    } else {
        for (int j = s->off[r]; j < s->off[r + 1]; j++) {
            int q = s->src[j];
            const double *u = q < nc ? U + 3 * (size_t)q : ub + 3 * (size_t)(q - nc);
            for (int k = 0; k < 3; k++) uf[k] += s->w[j] * u[k];
        }
    }
    for (int k = 0; k < 3; k++)
        if (k != skip) phi += uf[k] * S[k];
    return phi;
}

void gran_flux(Granular *g)
{
    double t0 = now();
    const FvMesh *f = g->f;
    const double *U = g->U->v;
    bc_update(&g->bc_U, U);
    bc_values(&g->bc_U, U, g->xb);
    /* one pass over the stencils and the face areas for all components;
       walls and empty faces keep the zero flux phi was made with */
    for (int i = 0; i < f->nfaces; i++)
        if (!f->empty_face[i] && (i < f->ninternal || !g->wall[i - f->ninternal]))
            g->phi[i] = face_flux(&g->ip->face, i, f->ncells, U, g->xb, f->m->face_area + 3 * i, g->flux_skip);
    g->t_flux += now() - t0;
}

double gran_courant(Granular *g, double dt, double *mean)
{
    const FvMesh *f = g->f;
    double co, sum = 0;
    if (g->model == MODEL_GRANULAR) {
        granmodel_closures(g);
        co = fvc_courant_cells(f, g->phi, g->gm.speed_c, dt, g->x);
    } else {
        co = fvc_courant_uniform(f, g->phi, sqrt(g->pr.RsT), dt, g->x);
    }
    for (int c = 0; c < f->nowned; c++) sum += g->x[c];
    *mean = f->nowned ? sum / f->nowned : 0;
    return co;
}

double gran_mass(const Granular *g) { return fvc_total(g->f, g->rho->v); }

/* Does boundary face b take its owner's pressure (a wall, or a zero
   gradient of rho)? */
int gran_owner_pressure(const Granular *g, int b)
{
    return g->wall[b] || g->bc_rho.patch[g->f->face_patch[b]].kind == BC_ZERO_GRADIENT;
}

/* The pressures p = RsT rho of the cells into pc and of the boundary
   faces into g->xbr (newtonian.h): from the owner's neighbourhood
   (fv/hydro.h) at walls and zero-gradient faces, RsT rho_b elsewhere.
   With them hydro_face gives every face's p_f through its CENTRE row (a
   boundary face's row is its boundary value; with wellBalanced each
   source reconstructed to the face). */
static void pressures(Granular *g, double *pc)
{
    const FvMesh *f = g->f;
    double R = g->pr.RsT;
    int gr = g->model == MODEL_GRANULAR;
    if (gr) /* p(c, T) of granmodel_closures */
        memcpy(pc, g->gm.pc, sizeof(double) * (size_t)f->ncells);
    else
        for (int c = 0; c < f->ncells; c++) pc[c] = R * g->rho->v[c];
    bc_values(&g->bc_rho, g->rho->v, g->xbr);
    if (profiled(g)) granmodel_profiles(g);
    for (int b = 0; b < f->nboundary; b++)
        if (!f->empty_face[f->ninternal + b])
            g->xbr[b] = gran_owner_pressure(g, b) ? (profiled(g) ? granmodel_owner_profile_pressure(g, b)
                                                            : hydro_boundary(&g->hy, b, pc))
                        : gr                 ? granmodel_boundary_pressure(g, b)
                                             : R * g->xbr[b];
}

/* The explicit parts: new density, the momentum terms V (rho u)^m / dt
   minus its convection, pressure force (the arrays' lifetimes: top of
   the file). */
static void explicit_terms(Granular *g, double dt)
{
    const FvMesh *f = g->f;
    const double *rho = g->rho->v, *U = g->U->v;
    double *conv = g->force;
    bc_update(&g->bc_rho, rho);
    bc_states(&g->bc_rho, rho, g->xbr);
    tvd_div(&g->tvd, &g->div_rho, g->phi, rho, g->xbr, 1, conv); /* eq. 4.60, or bounded second order */
    mass_flow(g, rho, dt);
    for (int c = 0; c < f->ncells; c++) g->rho1[c] = rho[c] - dt / f->m->cell_vol[c] * conv[c];
    bc_states(&g->bc_U, U, g->xb);
    for (int b = 0; b < f->nboundary; b++) /* the states of rho u */
        if (!f->empty_face[f->ninternal + b])
            for (int k = 0; k < 3; k++) g->xb[3 * b + k] *= g->xbr[b];
    for (int c = 0; c < f->ncells; c++)
        for (int k = 0; k < 3; k++) g->mom[3 * c + k] = rho[c] * U[3 * c + k];
    tvd_div(&g->tvd, &g->div_U, g->phi, g->mom, g->xb, 3, conv);
    for (int c = 0; c < f->ncells; c++) {
        double V = f->m->cell_vol[c];
        for (int k = 0; k < 3; k++) g->mom[3 * c + k] = V * g->mom[3 * c + k] / dt - conv[3 * c + k];
    }
    pressures(g, g->x);
    if (profiled(g)) {
        HydroProfile q = {granmodel_profile_at, g};
        hydro_force_profile(&g->hy, &q, g->force);
        hydro_gravity_profile(&g->hy, &q, g->gm.grav);
    } else {
        hydro_force(&g->hy, g->x, g->xbr, g->force);
    }
}

/* Assembles and solves component k (solver j) into mom's component k.  The matrix is
   the previous component's unless their boundary coefficients differ
   (slip walls): then only the right-hand side is assembled, and a shared
   solver keeps its preconditioner (linsolve_solve_tracked). */
static int solve_component(Granular *g, int j, double dt, Err *e)
{
    const FvMesh *f = g->f;
    int k = g->axis[j];
    FvMatrix *M = &g->M;
    double t0 = now();
    int gr = g->model == MODEL_GRANULAR;
    if (gr && j == 0) /* partialSlip's nu from this step's wall pressure and eta_f (granular.h) */
        bc_update(&g->bc_U, g->U->v);
    if (j == 0 || !fvm_same_matrix(&g->op, g->axis[j - 1], k)) {
        fvmatrix_zero_values(M);
        fvm_ddt(M, f, gr ? g->gm.cfl : g->rho1, dt); /* granular: c floored (granular.h) */
        if (gr) /* eq. 4.62-4.64 with eta_f */
            fvm_laplacian_matrix_f(&g->op, M, k, g->gm.eta_f);
        else
            fvm_laplacian_matrix(&g->op, M, k, g->pr.mu);
    }
    fvmatrix_zero_rhs(M);
    if (gr)
        fvm_laplacian_rhs_f(&g->op, M, k, g->gm.eta_f);
    else
        fvm_laplacian_rhs(&g->op, M, k, g->pr.mu);
    for (int c = 0; c < M->nrows; c++) {
        double V = f->m->cell_vol[c], rho = g->rho->v[c];
        double F = g->gravity == GRAN_CELL_SOURCE ? rho * g->pr.g[k] * V
                   : gr                           ? g->gm.grav[3 * c + k] /* restprofile.c */
                   : g->hy.grav                   ? g->pr.RsT * rho * g->hy.grav[3 * c + k] /* fv/hydro.h */
                                                  : 0;
        M->rhs[c] += g->mom[3 * c + k] - g->force[3 * c + k] + F;
    }
    component(f, g->U->v, k, g->x);
    double t1 = now();
    g->t_assembly += t1 - t0;
    int rc = linsolve_solve_tracked(g->L[j], g->x, &g->st[j], e);
    g->t_solve += now() - t1;
    if (rc) return -1;
    for (int c = 0; c < f->ncells; c++) g->mom[3 * c + k] = g->x[c];
    return 0;
}

/* The hook's cell integrals at the step's start time (newtonian.h,
   "Sources"); the arrays are made at the first call, so a run without a
   hook carries none. */
static int source_eval(Granular *g, Err *e)
{
    size_t nc = (size_t)g->f->ncells + 1;
    if (!g->src_rho) {
        g->src_rho = mem_calloc(nc, sizeof(double));
        g->src_m = mem_calloc(3 * nc, sizeof(double));
        if (g->model == MODEL_GRANULAR) g->src_T = mem_calloc(nc, sizeof(double));
    }
    return g->src.fn(g->src.ctx, g->f, g->time, g->src_rho, g->src_m, g->src_T, e);
}

/* Adds the source integrals explicitly: dt/V S_rho to the new density,
   and S_m to the momentum right-hand side through the explicit force,
   which solve_component subtracts. */
static void source_add(Granular *g, double dt)
{
    const FvMesh *f = g->f;
    double sum = 0;
    for (int c = 0; c < f->ncells; c++) {
        g->rho1[c] += dt / f->m->cell_vol[c] * g->src_rho[c];
        for (int k = 0; k < 3; k++) g->force[3 * c + k] -= g->src_m[3 * c + k];
    }
    for (int c = 0; c < f->nowned; c++) sum += g->src_rho[c];
    g->src_total += dt * sum;
}

/* The first cell whose new state is not finite or whose density is not
   positive, or -1. */
static int bad_cell(const Granular *g)
{
    int gr = g->model == MODEL_GRANULAR; /* c = 0 is an empty cell, T1 is checked by granular.c */
    for (int c = 0; c < g->f->nowned; c++) {
        const double *u = g->mom + 3 * c;
        if (!(gr ? g->rho1[c] >= 0 : g->rho1[c] > 0) || !isfinite(g->rho1[c]) || !isfinite(u[0] + u[1] + u[2]))
            return c;
    }
    return -1;
}

int gran_step(Granular *g, double dt, Err *e)
{
    const FvMesh *f = g->f;
    double out0 = g->out_total, src0 = g->src_total, t0 = now();
    if (g->src.fn && source_eval(g, e)) return -1;
    if (g->model == MODEL_GRANULAR) granmodel_closures(g); /* at c^m, T^m */
    explicit_terms(g, dt);
    if (g->src.fn) source_add(g, dt);
    if (g->model == MODEL_GRANULAR) granmodel_limit_c(g);
    g->t_explicit += now() - t0;
    for (int j = 0; j < g->naxes; j++)
        if (solve_component(g, j, dt, e)) {
            g->out_total = out0;
            g->src_total = src0;
            return -1;
        }
    if (g->model == MODEL_GRANULAR && granmodel_temperature(g, dt, e)) {
        g->out_total = out0;
        g->src_total = src0;
        return -1;
    }
    t0 = now();
    if (f->empty_axis >= 0) /* not solved: keeps its value */
        for (int c = 0; c < f->ncells; c++) g->mom[3 * c + f->empty_axis] = g->U->v[3 * c + f->empty_axis];
    int c = bad_cell(g);
    if (c >= 0) {
        g->out_total = out0;
        g->src_total = src0;
        const double *x = f->node + 3 * c, *u = g->mom + 3 * c;
        return err_set(e, NULL, 0,
                       "cell %d at (%g %g %g): %s: density %g, velocity (%g %g %g) (time step %g too large for "
                       "the flow, or bad boundary conditions)",
                       c, x[0], x[1], x[2], isfinite(g->rho1[c]) && isfinite(u[0] + u[1] + u[2]) ? (g->model == MODEL_GRANULAR ? "volume fraction < 0" : "density <= 0") : "not a number",
                       g->rho1[c], u[0], u[1], u[2], dt);
    }
    memcpy(g->rho->v, g->rho1, sizeof(double) * (size_t)f->ncells);
    memcpy(g->U->v, g->mom, sizeof(double) * 3 * (size_t)f->ncells);
    if (g->model == MODEL_GRANULAR) granmodel_commit(g);
    g->time += dt;
    g->t_update += now() - t0;
    return 0;
}

void gran_release(Granular *g)
{
    for (int k = 0; k < 3; k++)
        if (g->L[k]) linsolve_release(g->L[k]);
    if (g->gm.L) linsolve_release(g->gm.L);
}

void gran_pressure(Granular *g, Field *p)
{
    const FvMesh *f = g->f;
    if (g->model == MODEL_GRANULAR) granmodel_closures(g);
    pressures(g, p->v);
    HydroProfile hq = {granmodel_profile_at, g};
    for (int q = 0; q < p->npatches; q++) {
        PatchField *pf = &p->pf[q];
        if (!pf->value) continue;
        int start = f->m->patches[q].start;
        for (int j = 0; j < pf->n; j++)
            pf->value[j] = f->empty_face[start + j] ? 0
                           : profiled(g)          ? hydro_face_profile(&g->hy, start + j, &hq)
                                                  : hydro_face(&g->hy, start + j, p->v, g->xbr);
    }
}
