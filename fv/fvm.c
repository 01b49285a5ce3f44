/*
** fvm.c: implicit operators (fvm.h).
**
** The face rows PLUS and MINUS of interp.h are read entry by entry: a
** cell source adds its weight on its own column, a boundary source
** ncells + b adds a[b] on the column of face b's owner and b[b] times its
** weight to the right-hand side (bc.h), so the boundary condition is
** applied wherever a stencil reaches the boundary, not only at the face
** itself.  Each entry's positions in the owner's and the neighbour's rows
** are kept (pos_own, pos_nbr), so the assembly of a time step is one pass
** over the stencil entries; the faces between whole Cartesian cells, whose
** rows are the two cells themselves with weight 1 (FVM_TWO_POINT), keep no
** positions: theirs are the diagonals and the matrix's face positions.
** That keeps 8 bytes per PLUS and MINUS entry off most faces of a cut
** grid (97 bytes a cell on a 3-D block grid).  One body, face_terms,
** adds a face's terms for the three passes (both parts, the matrix alone,
** the right-hand side alone): inlined with `what` a constant, each pass
** does only its part's work, in the order of the others.
*/
#include "fvm.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

static int face_nbr(const FvMesh *f, int i) { return i < f->ninternal ? f->m->neighbour[i] : -1; }

void fvm_pattern(FvPattern *p, const FvMesh *f, const Interp *ip)
{
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        int o = f->m->owner[i], n = face_nbr(f, i);
        for (int k = INTERP_PLUS; k <= INTERP_MINUS; k++) {
            if (stencil_is_pair(&ip->face, interp_row(i, k))) continue; /* o and n: in the pattern already */
            fvpattern_couple_stencil(p, o, &ip->face, interp_row(i, k));
            if (n >= 0) fvpattern_couple_stencil(p, n, &ip->face, interp_row(i, k));
        }
    }
}

/* Position of the column of source s (a cell, or a boundary face's owner)
   in row `row` (-1: a halo row, none). */
static int source_pos(const FvMatrix *M, const FvMesh *f, int row, int s)
{
    if (row < 0 || row >= M->nrows) return -1;
    int col = s < f->ncells ? s : f->m->owner[f->ninternal + s - f->ncells];
    return fvmatrix_pos(M, row, col);
}

/* The distance of face i's difference (fvm.h): the node distance on
   Cartesian faces (cyclic ones across the period), h + ht elsewhere. */
static double face_dist(const FvMesh *f, int i)
{
    double xn[3];
    if (f->cartesian_face[i] && fvmesh_across(f, i, xn) >= 0) {
        const double *xo = f->node + 3 * f->m->owner[i], *n = f->nf + 3 * i;
        return fabs((xn[0] - xo[0]) * n[0] + (xn[1] - xo[1]) * n[1] + (xn[2] - xo[2]) * n[2]);
    }
    return f->h[i] + f->ht[i];
}

/* Is face i's difference the plain two-point one: an internal face
   whose PLUS row is the neighbour alone and MINUS row the owner alone,
   both weight 1, and both rows ours?  (Eq. 4.61's faces between whole
   Cartesian cells, and every face of the scheme none.)  Its entries are
   the diagonals and the matrix's face positions. */
static int two_point(const FvMatrix *M, const FvMesh *f, const Stencil *s, int i)
{
    if (i >= f->ninternal || f->empty_face[i]) return 0;
    int o = f->m->owner[i], n = f->m->neighbour[i];
    StencilRow p, q;
    stencil_row(s, interp_row(i, INTERP_PLUS), &p);
    stencil_row(s, interp_row(i, INTERP_MINUS), &q);
    return o < M->nrows && n < M->nrows && M->face_pos[2 * i] >= 0 && M->face_pos[2 * i + 1] >= 0 && p.n == 1 &&
           p.src[0] == n && p.w[0] == 1.0 && q.n == 1 && q.src[0] == o && q.w[0] == 1.0;
}

/* Entries of face i's PLUS and MINUS rows. */
static int face_entries(const Stencil *s, int i)
{
    return stencil_row_len(s, interp_row(i, INTERP_PLUS)) + stencil_row_len(s, interp_row(i, INTERP_MINUS));
}

/* Positions of the PLUS and MINUS rows' entries of face i, from
   pos_off[i] on; returns the number of missing ones. */
static int face_positions(Fvm *d, const FvMatrix *M, int i)
{
    const FvMesh *f = d->f;
    const Stencil *s = &d->ip->face;
    int o = f->m->owner[i], n = face_nbr(f, i), missing = 0, q = d->pos_off[i];
    for (int k = INTERP_PLUS; k <= INTERP_MINUS; k++) {
        StencilRow row;
        stencil_row(s, interp_row(i, k), &row);
        for (int j = 0; j < row.n; j++, q++) {
            d->pos_own[q] = source_pos(M, f, o, row.src[j]);
            d->pos_nbr[q] = source_pos(M, f, n, row.src[j]);
            missing += (o < M->nrows && d->pos_own[q] < 0) + (n >= 0 && n < M->nrows && d->pos_nbr[q] < 0);
        }
    }
    return missing;
}

/* Is face i a boundary face whose gradient d's boundary condition gives? */
static int is_neumann(const Fvm *d, int i)
{
    const FvMesh *f = d->f;
    return i >= f->ninternal && !f->empty_face[i] && d->bc->fixed_grad[bc_slot(d->bc, i - f->ninternal)];
}

/* Which faces are two-point, and where the others' positions go. */
static void face_layout(Fvm *d, const FvMatrix *M)
{
    const FvMesh *f = d->f;
    const Stencil *s = &d->ip->face;
    d->kind = mem_calloc((size_t)f->nfaces + 1, 1);
    d->pos_off = mem_alloc(sizeof(int) * ((size_t)f->nfaces + 1));
    int q = 0;
    for (int i = 0; i < f->nfaces; i++) {
        d->pos_off[i] = q;
        d->kind[i] = (char)(two_point(M, f, s, i) ? FVM_TWO_POINT : 0);
        if (is_neumann(d, i)) d->kind[i] = FVM_NEUMANN;
        if (!f->empty_face[i] && d->kind[i] != FVM_TWO_POINT) q += face_entries(s, i);
    }
    d->pos_off[f->nfaces] = q;
    d->pos_own = mem_alloc(sizeof(int) * ((size_t)q + 1));
    d->pos_nbr = mem_alloc(sizeof(int) * ((size_t)q + 1));
}

/* Has face i right-hand-side terms: a Neumann face, or a PLUS or MINUS
   row with a boundary source? */
static int face_has_rhs(const Fvm *d, int i)
{
    const FvMesh *f = d->f;
    const Stencil *s = &d->ip->face;
    if (d->kind[i] == FVM_NEUMANN) return 1;
    for (int k = INTERP_PLUS; k <= INTERP_MINUS; k++) {
        StencilRow row;
        stencil_row(s, interp_row(i, k), &row);
        for (int j = 0; j < row.n; j++)
            if (row.src[j] >= f->ncells) return 1;
    }
    return 0;
}

static void list_rhs_faces(Fvm *d)
{
    const FvMesh *f = d->f;
    int n = 0;
    for (int i = 0; i < f->nfaces; i++) n += !f->empty_face[i] && face_has_rhs(d, i);
    d->rhs_face = mem_alloc(sizeof(int) * ((size_t)n + 1));
    for (int i = 0; i < f->nfaces; i++)
        if (!f->empty_face[i] && face_has_rhs(d, i)) d->rhs_face[d->nrhs_face++] = i;
}

int fvm_init(Fvm *d, const FvMatrix *M, const FvMesh *f, const Interp *ip, const Bc *bc, Err *e)
{
    memset(d, 0, sizeof *d);
    d->f = f;
    d->ip = ip;
    d->bc = bc;
    d->dist = mem_alloc(sizeof(double) * ((size_t)f->nfaces + 1));
    face_layout(d, M);
    int missing = 0;
    for (int i = 0; i < f->nfaces; i++) {
        d->dist[i] = face_dist(f, i);
        if (!f->empty_face[i] && d->kind[i] != FVM_TWO_POINT) missing += face_positions(d, M, i);
    }
    if (missing) {
        fvm_free(d);
        return err_set(e, NULL, 0, "fvm_init: %d entries of the diffusion operator are not in the matrix pattern",
                       missing);
    }
    list_rhs_faces(d);
    return 0;
}

/* Boundary faces are never two-point (two_point), so the layout and the
   distances do not depend on the boundary condition: only the Neumann
   faces and the right-hand-side faces do. */
void fvm_init_like(Fvm *d, const Fvm *base, const Bc *bc)
{
    const FvMesh *f = base->f;
    *d = *base;
    d->bc = bc;
    d->shared = 1;
    d->kind = mem_alloc((size_t)f->nfaces + 1);
    for (int i = 0; i < f->nfaces; i++)
        d->kind[i] = (char)(is_neumann(d, i) ? FVM_NEUMANN : i < f->ninternal ? base->kind[i] : 0);
    d->rhs_face = NULL;
    d->nrhs_face = 0;
    list_rhs_faces(d);
}

void fvm_free(Fvm *d)
{
    if (!d->shared) {
        free(d->dist);
        free(d->pos_own);
        free(d->pos_nbr);
        free(d->pos_off);
    }
    free(d->kind);
    free(d->rhs_face);
    memset(d, 0, sizeof *d);
}

/* What an assembly pass adds: matrix entries, right-hand side, or both. */
enum { FVM_MATRIX = 1, FVM_RHS = 2 };

/* Adds c * (row r's value) to matrix row `row`, pos the positions of
   r's entries in it (boundary sources through the boundary condition's a
   and b): the parts `what` asks for.  Not a pair row (face_terms). */
static inline void add_row(FvMatrix *M, const Fvm *d, const int *pos, int row, int r, int k, double c, int what)
{
    const Stencil *s = &d->ip->face;
    const Bc *bc = d->bc;
    int nc = d->f->ncells, j0 = s->off[r];
    for (int j = j0; j < s->off[r + 1]; j++) {
        double w = c * s->w[j];
        int src = s->src[j];
        if (src < nc) {
            if (what & FVM_MATRIX) M->val[pos[j - j0]] += w;
            continue;
        }
        size_t bk = (size_t)bc_slot(bc, src - nc) * (size_t)bc->width + (size_t)k;
        if (what & FVM_MATRIX) M->val[pos[j - j0]] += w * bc->a[bk];
        if (what & FVM_RHS) M->rhs[row] -= w * bc->b[bk];
    }
}

/* The number of entries of face i's PLUS row (its MINUS row's positions
   follow them). */
static inline int plus_len(const Fvm *d, int i) { return stencil_row_len(&d->ip->face, interp_row(i, INTERP_PLUS)); }

/* A Neumann boundary face: F = G |S| (ga u(MINUS) + gb). */
static inline void neumann_face(const Fvm *d, FvMatrix *M, int i, int k, double gamma, int what)
{
    const FvMesh *f = d->f;
    const Bc *bc = d->bc;
    int o = f->m->owner[i];
    size_t bk = (size_t)bc_slot(bc, i - f->ninternal) * (size_t)bc->width + (size_t)k;
    double G = gamma * f->mag_sf[i];
    if (what & FVM_RHS) M->rhs[o] += G * bc->gb[bk];
    if (bc->ga[bk] != 0)
        add_row(M, d, d->pos_own + d->pos_off[i] + plus_len(d, i), o, interp_row(i, INTERP_MINUS), k, -G * bc->ga[bk],
                what);
}

/* The terms of a face whose rows are a stencil pair's (stencil.h) but
   not FVM_TWO_POINT, because one of its cells is not a row of ours (a
   halo cell): cells only, so matrix entries only, F = D (u_N - u_C). */
static void pair_face_terms(const Fvm *d, FvMatrix *M, int i, double D)
{
    const Stencil *s = &d->ip->face;
    int o = d->f->m->owner[i], n = face_nbr(d->f, i), q = d->pos_off[i];
    double sgn[2] = {-D, D}; /* PLUS (the neighbour), MINUS (the owner) in the owner's row */
    for (int k = INTERP_PLUS; k <= INTERP_MINUS; k++, q++) {
        StencilRow sr;
        stencil_row(s, interp_row(i, k), &sr);
        double c = sgn[k - INTERP_PLUS] * sr.w[0];
        if (o < M->nrows) M->val[d->pos_own[q]] += c;
        if (n >= 0 && n < M->nrows) M->val[d->pos_nbr[q]] -= c;
    }
}

/* Face i's terms (not an empty face). */
static inline void face_terms(const Fvm *d, FvMatrix *M, int i, int k, double gamma, int what)
{
    const FvMesh *f = d->f;
    int o = f->m->owner[i], n = face_nbr(f, i);
    if (d->kind[i] == FVM_NEUMANN) {
        if (o < M->nrows) neumann_face(d, M, i, k, gamma, what);
        return;
    }
    double D = gamma * f->mag_sf[i] / d->dist[i];
    if (d->kind[i] == FVM_TWO_POINT) { /* the general case below with weights 1 */
        if (what & FVM_MATRIX) {
            M->val[M->face_pos[2 * i]] += -D;
            M->val[M->diag[o]] += D;
            M->val[M->diag[n]] += D;
            M->val[M->face_pos[2 * i + 1]] += -D;
        }
        return;
    }
    int rp = interp_row(i, INTERP_PLUS), rm = interp_row(i, INTERP_MINUS), np = plus_len(d, i);
    if (stencil_is_pair(&d->ip->face, rp)) {
        if (what & FVM_MATRIX) pair_face_terms(d, M, i, D);
        return;
    }
    const int *po = d->pos_own + d->pos_off[i], *pn = d->pos_nbr + d->pos_off[i];
    if (o < M->nrows) { /* -F in the owner's row */
        add_row(M, d, po, o, rp, k, -D, what);
        add_row(M, d, po + np, o, rm, k, D, what);
    }
    if (n >= 0 && n < M->nrows) { /* +F in the neighbour's */
        add_row(M, d, pn, n, rp, k, D, what);
        add_row(M, d, pn + np, n, rm, k, -D, what);
    }
}

void fvm_laplacian(const Fvm *d, FvMatrix *M, int k, double gamma)
{
    fvm_laplacian_matrix(d, M, k, gamma);
    fvm_laplacian_rhs(d, M, k, gamma);
}

/* Gamma of face i: the array's where there is one, else the constant. */
static inline double face_gamma(double gamma, const double *gamma_f, int i) { return gamma_f ? gamma_f[i] : gamma; }

static void laplacian_matrix(const Fvm *d, FvMatrix *M, int k, double gamma, const double *gamma_f)
{
    const FvMesh *f = d->f;
    for (int i = 0; i < f->nfaces; i++)
        if (!f->empty_face[i]) face_terms(d, M, i, k, face_gamma(gamma, gamma_f, i), FVM_MATRIX);
}

static void laplacian_rhs(const Fvm *d, FvMatrix *M, int k, double gamma, const double *gamma_f)
{
    for (int j = 0; j < d->nrhs_face; j++) {
        int i = d->rhs_face[j];
        face_terms(d, M, i, k, face_gamma(gamma, gamma_f, i), FVM_RHS);
    }
}

void fvm_laplacian_matrix(const Fvm *d, FvMatrix *M, int k, double gamma) { laplacian_matrix(d, M, k, gamma, NULL); }
void fvm_laplacian_rhs(const Fvm *d, FvMatrix *M, int k, double gamma) { laplacian_rhs(d, M, k, gamma, NULL); }
void fvm_laplacian_matrix_f(const Fvm *d, FvMatrix *M, int k, const double *gamma_f)
{
    laplacian_matrix(d, M, k, 0, gamma_f);
}
void fvm_laplacian_rhs_f(const Fvm *d, FvMatrix *M, int k, const double *gamma_f) { laplacian_rhs(d, M, k, 0, gamma_f); }

int fvm_same_matrix(const Fvm *d, int k1, int k2)
{
    const Bc *bc = d->bc;
    size_t w = (size_t)bc->width;
    for (int s = 0; s < bc->nslots; s++) /* empty faces have none: never assembled, never a source */
        if (bc->a[s * w + (size_t)k1] != bc->a[s * w + (size_t)k2] || bc->ga[s * w + (size_t)k1] != bc->ga[s * w + (size_t)k2])
            return 0;
    return 1;
}

/* Value of row r on component k of u (boundary sources: a u_owner + b). */
static double row_value(const Fvm *d, const double *u, int r, int k)
{
    const Bc *bc = d->bc;
    const FvMesh *f = d->f;
    int nc = f->ncells, wd = bc->width;
    StencilRow sr;
    stencil_row(&d->ip->face, r, &sr);
    double v = 0;
    for (int j = 0; j < sr.n; j++) {
        int src = sr.src[j];
        if (src < nc) {
            v += sr.w[j] * u[(size_t)src * wd + k];
            continue;
        }
        size_t bk = (size_t)bc_slot(bc, src - nc) * (size_t)wd + (size_t)k;
        v += sr.w[j] * (bc->a[bk] * u[(size_t)f->m->owner[f->ninternal + src - nc] * wd + k] + bc->b[bk]);
    }
    return v;
}

static void face_flux(const Fvm *d, const double *u, int k, double gamma, const double *gamma_f, double *flux)
{
    const FvMesh *f = d->f;
    const Bc *bc = d->bc;
    int wd = bc->width;
    for (int i = 0; i < f->nfaces; i++) {
        flux[i] = 0;
        if (f->empty_face[i]) continue;
        double G = face_gamma(gamma, gamma_f, i) * f->mag_sf[i];
        int s = i >= f->ninternal ? bc_slot(bc, i - f->ninternal) : -1;
        if (s >= 0 && bc->fixed_grad[s]) {
            size_t bk = (size_t)s * (size_t)wd + (size_t)k;
            flux[i] = G * (bc->gb[bk] + (bc->ga[bk] != 0 ? bc->ga[bk] * row_value(d, u, interp_row(i, INTERP_MINUS), k) : 0));
        } else {
            flux[i] = G / d->dist[i] *
                      (row_value(d, u, interp_row(i, INTERP_PLUS), k) - row_value(d, u, interp_row(i, INTERP_MINUS), k));
        }
    }
}

void fvm_face_flux(const Fvm *d, const double *u, int k, double gamma, double *flux)
{
    face_flux(d, u, k, gamma, NULL, flux);
}

void fvm_face_flux_f(const Fvm *d, const double *u, int k, const double *gamma_f, double *flux)
{
    face_flux(d, u, k, 0, gamma_f, flux);
}

void fvm_ddt(FvMatrix *M, const FvMesh *f, const double *c, double dt)
{
    for (int r = 0; r < M->nrows; r++) M->val[M->diag[r]] += f->m->cell_vol[r] * c[r] / dt;
}
