/*
** fvm.c: implicit operators (fvm.h).
**
** The face rows PLUS and MINUS of interp.h are read entry by entry: a
** cell source adds its weight on its own column, a boundary source
** ncells + b adds a[b] on the column of face b's owner and b[b] times its
** weight to the right-hand side (bc.h), so the boundary condition is
** applied wherever a stencil reaches the boundary, not only at the face
** itself.  Each entry's positions in the owner's and the neighbour's rows
** are kept in two arrays parallel to the stencil's, so the assembly of a
** time step is one pass over the stencil entries.
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

/* Positions of the PLUS and MINUS rows' entries of face i; returns the
   number of missing ones. */
static int face_positions(Fvm *d, const FvMatrix *M, int i)
{
    const FvMesh *f = d->f;
    const Stencil *s = &d->ip->face;
    int o = f->m->owner[i], n = face_nbr(f, i), missing = 0;
    for (int k = INTERP_PLUS; k <= INTERP_MINUS; k++) {
        int r = interp_row(i, k);
        for (int j = s->off[r]; j < s->off[r + 1]; j++) {
            d->pos_own[j] = source_pos(M, f, o, s->src[j]);
            d->pos_nbr[j] = source_pos(M, f, n, s->src[j]);
            missing += (o < M->nrows && d->pos_own[j] < 0) + (n >= 0 && n < M->nrows && d->pos_nbr[j] < 0);
        }
    }
    return missing;
}

int fvm_init(Fvm *d, const FvMatrix *M, const FvMesh *f, const Interp *ip, const Bc *bc, Err *e)
{
    memset(d, 0, sizeof *d);
    d->f = f;
    d->ip = ip;
    d->bc = bc;
    size_t nent = (size_t)ip->face.off[ip->face.nrows] + 1;
    d->dist = mem_alloc(sizeof(double) * ((size_t)f->nfaces + 1));
    d->pos_own = mem_alloc(sizeof(int) * nent);
    d->pos_nbr = mem_alloc(sizeof(int) * nent);
    int missing = 0;
    for (int i = 0; i < f->nfaces; i++) {
        d->dist[i] = face_dist(f, i);
        if (!f->empty_face[i]) missing += face_positions(d, M, i);
    }
    if (missing) {
        fvm_free(d);
        return err_set(e, NULL, 0, "fvm_init: %d entries of the diffusion operator are not in the matrix pattern",
                       missing);
    }
    return 0;
}

void fvm_free(Fvm *d)
{
    free(d->dist);
    free(d->pos_own);
    free(d->pos_nbr);
    memset(d, 0, sizeof *d);
}

/* Adds c * (row r's value) to the matrix row whose positions are pos
   (boundary sources through the boundary condition's a and b). */
static void add_row(FvMatrix *M, const Fvm *d, const int *pos, int row, int r, int k, double c)
{
    const Stencil *s = &d->ip->face;
    const Bc *bc = d->bc;
    int nc = d->f->ncells;
    for (int j = s->off[r]; j < s->off[r + 1]; j++) {
        double w = c * s->w[j];
        int src = s->src[j];
        if (src < nc) {
            M->val[pos[j]] += w;
            continue;
        }
        size_t bk = (size_t)(src - nc) * (size_t)bc->width + (size_t)k;
        M->val[pos[j]] += w * bc->a[bk];
        M->rhs[row] -= w * bc->b[bk];
    }
}

/* A Neumann boundary face: F = G |S| (ga u(MINUS) + gb). */
static void neumann_face(const Fvm *d, FvMatrix *M, int i, int k, double gamma)
{
    const FvMesh *f = d->f;
    const Bc *bc = d->bc;
    int b = i - f->ninternal, o = f->m->owner[i];
    size_t bk = (size_t)b * (size_t)bc->width + (size_t)k;
    double G = gamma * f->mag_sf[i];
    M->rhs[o] += G * bc->gb[bk];
    if (bc->ga[bk] != 0) add_row(M, d, d->pos_own, o, interp_row(i, INTERP_MINUS), k, -G * bc->ga[bk]);
}

void fvm_laplacian(const Fvm *d, FvMatrix *M, int k, double gamma)
{
    const FvMesh *f = d->f;
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        int o = f->m->owner[i], n = face_nbr(f, i);
        if (i >= f->ninternal && d->bc->fixed_grad[i - f->ninternal]) {
            if (o < M->nrows) neumann_face(d, M, i, k, gamma);
            continue;
        }
        double D = gamma * f->mag_sf[i] / d->dist[i];
        int rp = interp_row(i, INTERP_PLUS), rm = interp_row(i, INTERP_MINUS);
        if (o < M->nrows) { /* -F in the owner's row */
            add_row(M, d, d->pos_own, o, rp, k, -D);
            add_row(M, d, d->pos_own, o, rm, k, D);
        }
        if (n >= 0 && n < M->nrows) { /* +F in the neighbour's */
            add_row(M, d, d->pos_nbr, n, rp, k, D);
            add_row(M, d, d->pos_nbr, n, rm, k, -D);
        }
    }
}

/* Value of row r on component k of u (boundary sources: a u_owner + b). */
static double row_value(const Fvm *d, const double *u, int r, int k)
{
    const Stencil *s = &d->ip->face;
    const Bc *bc = d->bc;
    const FvMesh *f = d->f;
    int nc = f->ncells, wd = bc->width;
    double v = 0;
    for (int j = s->off[r]; j < s->off[r + 1]; j++) {
        int src = s->src[j];
        if (src < nc) {
            v += s->w[j] * u[(size_t)src * wd + k];
            continue;
        }
        size_t bk = (size_t)(src - nc) * (size_t)wd + (size_t)k;
        v += s->w[j] * (bc->a[bk] * u[(size_t)f->m->owner[f->ninternal + src - nc] * wd + k] + bc->b[bk]);
    }
    return v;
}

void fvm_face_flux(const Fvm *d, const double *u, int k, double gamma, double *flux)
{
    const FvMesh *f = d->f;
    const Bc *bc = d->bc;
    int wd = bc->width;
    for (int i = 0; i < f->nfaces; i++) {
        flux[i] = 0;
        if (f->empty_face[i]) continue;
        double G = gamma * f->mag_sf[i];
        int b = i - f->ninternal;
        if (i >= f->ninternal && bc->fixed_grad[b]) {
            size_t bk = (size_t)b * (size_t)wd + (size_t)k;
            flux[i] = G * (bc->gb[bk] + (bc->ga[bk] != 0 ? bc->ga[bk] * row_value(d, u, interp_row(i, INTERP_MINUS), k) : 0));
        } else {
            flux[i] = G / d->dist[i] *
                      (row_value(d, u, interp_row(i, INTERP_PLUS), k) - row_value(d, u, interp_row(i, INTERP_MINUS), k));
        }
    }
}

void fvm_ddt(FvMatrix *M, const FvMesh *f, const double *c, double dt)
{
    for (int r = 0; r < M->nrows; r++) M->val[M->diag[r]] += f->m->cell_vol[r] * c[r] / dt;
}
