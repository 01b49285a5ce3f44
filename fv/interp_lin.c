/*
** interp_lin.c: the linear-exactness correction of the gradient points
** of faces next to walls (interp_impl.h, doc/fv.md "Linear exactness at
** walls").
**
** Eq. 4.62-4.63 divide the difference of two interpolated values by
** h + ht (h alone at a wall), so an interpolation error of O(h) at the
** MINUS or PLUS point is an O(1) error of the normal derivative.  Neither
** method is exact for linear functions next to a cut wall: multilinear's
** sources are Cartesian centres standing for cut and merged cells whose
** nodes lie O(h) away (the "(✓)" of Table 4.1), Shepard reproduces only
** constants.  So the PLUS and MINUS rows of a face next to a wall (not a
** Cartesian face, with its owner or neighbour a wall cell or a face
** neighbour of one) are corrected by constrained least squares: the
** smallest change dw of the weights, in the norm sum dw_j^2 / m_j, such
** that the row reproduces 1 and x (the active axes) at the point x:
**     A (w + dw) = (1, 0),   A_j = (1, (x_j - x) / L),
**     dw = M A^T (A M A^T)^{-1} (e0 - A w),
** over the row's own sources and the boundary faces of its cells and of
** the face's owner (sources ncells + b, their boundary values).  x_j is a
** cell's node (where its value lives) or a face centre, taken at the
** periodic image nearest x; L is the owner's cell size.  The mobility
** m_j = 1 / (1 + |x_j - x|^2 / L^2) makes near sources carry the change,
** so a row stays close to the method's and its largest weights stay
** where they were.  When the sources do not span the active axes (a
** pivot below 1e-10 of the diagonal) or the corrected row's sum |w|
** exceeds LIN_MAXL1 (nearly degenerate sources: large weights of both
** signs, poor diagonals), the face neighbours of the row's cells and
** their wall faces join them once and the smaller sum |w| wins; when
** neither is acceptable the row stays as it was (InterpStats.nlinskip).  The change sums to 0, so a row's sum stays 1.
*/
#include "interp_impl.h"

#include <math.h>
#include <string.h>

#include "mem.h"

#define LIN_MAXSRC 256
#define LIN_MAXL1 3.0   /* largest sum |w| of a corrected row */

typedef struct LinSet {
    int n;
    int src[LIN_MAXSRC];
    double w[LIN_MAXSRC];
} LinSet;

static void set_add(LinSet *S, int src, double w)
{
    for (int q = 0; q < S->n; q++)
        if (S->src[q] == src) {
            S->w[q] += w;
            return;
        }
    if (S->n == LIN_MAXSRC) return;
    S->src[S->n] = src;
    S->w[S->n++] = w;
}

static double l1(const LinSet *S)
{
    double v = 0;
    for (int q = 0; q < S->n; q++) v += fabs(S->w[q]);
    return v;
}

/* Boundary faces of cell c that carry a boundary value (not empty, not
   cyclic) into S with weight 0. */
static void add_walls(const FvMesh *f, int c, LinSet *S)
{
    const Mesh *m = f->m;
    for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
        int i = m->cell_faces[q];
        if (i >= f->ninternal && !f->empty_face[i] && f->cyc_face[i - f->ninternal] < 0)
            set_add(S, f->ncells + i - f->ninternal, 0);
    }
}

/* Face neighbours of cell c (across internal and cyclic faces). */
static void add_neighbours(const FvMesh *f, int c, LinSet *S)
{
    const Mesh *m = f->m;
    for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
        int i = m->cell_faces[q], nb;
        double x[3];
        if (f->empty_face[i]) continue;
        if (i < f->ninternal) nb = m->owner[i] == c ? m->neighbour[i] : m->owner[i];
        else if (m->owner[i] == c && (nb = fvmesh_across(f, i, x)) >= 0) {
        } else continue;
        set_add(S, nb, 0);
    }
}

/* Position of source s, at its periodic image nearest x. */
static void source_at(const InterpIndex *ix, const FvMesh *f, int s, const double *x, double p[3])
{
    const double *p0 = s < f->ncells ? f->node + 3 * s : f->m->face_centre + 3 * (f->ninternal + s - f->ncells);
    double best = INFINITY;
    for (int t = -1; t < ix->ntrans; t++) {
        double q[3], d = 0;
        for (int k = 0; k < 3; k++) {
            q[k] = p0[k] - (t >= 0 ? ix->trans[t][k] : 0);
            d += (q[k] - x[k]) * (q[k] - x[k]);
        }
        if (d < best) {
            best = d;
            memcpy(p, q, sizeof q);
        }
    }
}

/* Solves the n x n system G y = r (n <= 4) in place by Cholesky; 0 when
   a pivot falls below 1e-10 of its diagonal (the sources do not span). */
static int spd_solve(int n, double G[4][4], double *r)
{
    for (int j = 0; j < n; j++) {
        double d = G[j][j];
        for (int k = 0; k < j; k++) d -= G[j][k] * G[j][k];
        if (!(d > 1e-10 * G[j][j])) return 0;
        G[j][j] = sqrt(d);
        for (int i = j + 1; i < n; i++) {
            double v = G[i][j];
            for (int k = 0; k < j; k++) v -= G[i][k] * G[j][k];
            G[i][j] = v / G[j][j];
        }
    }
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < i; k++) r[i] -= G[i][k] * r[k];
        r[i] /= G[i][i];
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int k = i + 1; k < n; k++) r[i] -= G[k][i] * r[k];
        r[i] /= G[i][i];
    }
    return 1;
}

/* The correction of S at x (see the top); 0 when the sources do not span. */
static int correct(const Interp *ip, const double *x, double L, LinSet *S)
{
    const InterpIndex *ix = ip->ix;
    int ax[3], na = 0;
    for (int k = 0; k < 3; k++)
        if (ix->active[k]) ax[na++] = k;
    int n = na + 1;
    double G[4][4] = {{0}}, r[4] = {1, 0, 0, 0}, A[LIN_MAXSRC][4], mob[LIN_MAXSRC];
    for (int q = 0; q < S->n; q++) {
        double p[3], d2 = 0;
        source_at(ix, ip->f, S->src[q], x, p);
        A[q][0] = 1;
        for (int a = 0; a < na; a++) {
            A[q][a + 1] = (p[ax[a]] - x[ax[a]]) / L;
            d2 += A[q][a + 1] * A[q][a + 1];
        }
        mob[q] = 1 / (1 + d2);
        for (int a = 0; a < n; a++) {
            r[a] -= A[q][a] * S->w[q];
            for (int b = 0; b < n; b++) G[a][b] += mob[q] * A[q][a] * A[q][b];
        }
    }
    double res = 0;
    for (int a = 0; a < n; a++) res = fmax(res, fabs(r[a]));
    if (res < 1e-14) return 1;
    if (!spd_solve(n, G, r)) return 0;
    for (int q = 0; q < S->n; q++) {
        double dw = 0;
        for (int a = 0; a < n; a++) dw += A[q][a] * r[a];
        S->w[q] += mob[q] * dw;
    }
    return 1;
}

void interp_lin_init(Interp *ip)
{
    const FvMesh *f = ip->f;
    const Mesh *m = f->m;
    InterpIndex *ix = ip->ix;
    ix->near_wall = mem_calloc((size_t)f->ncells + 1, 1);
    for (int b = 0; b < f->nboundary; b++) {
        int i = f->ninternal + b;
        if (!f->empty_face[i] && f->cyc_face[b] < 0) ix->near_wall[m->owner[i]] = 2;
    }
    for (int i = 0; i < f->ninternal; i++) {
        int o = m->owner[i], n = m->neighbour[i];
        if (ix->near_wall[o] == 2 && !ix->near_wall[n]) ix->near_wall[n] = 1;
        if (ix->near_wall[n] == 2 && !ix->near_wall[o]) ix->near_wall[o] = 1;
    }
}

int interp_lin_wants(const Interp *ip, int i)
{
    const FvMesh *f = ip->f;
    if (f->empty_axis < 0 || f->empty_face[i] || f->cartesian_face[i] || ip->o.method == INTERP_NONE) return 0;
    double x[3];
    int nb = fvmesh_across(f, i, x);
    return ip->ix->near_wall[f->m->owner[i]] || (nb >= 0 && ip->ix->near_wall[nb]);
}

void interp_lin_correct(Interp *ip, int i, const double x[3])
{
    Stencil *s = &ip->face;
    const FvMesh *f = ip->f;
    int own = f->m->owner[i], a = s->off[s->nrows], end = s->off[s->nrows + 1];
    LinSet S;
    S.n = 0;
    for (int q = a; q < end; q++) set_add(&S, s->src[q], s->w[q]);
    int nrow = S.n;
    for (int q = 0; q < nrow; q++)
        if (S.src[q] < f->ncells) add_walls(f, S.src[q], &S);
    add_walls(f, own, &S);
    const double *h = ip->ix->sh + 3 * own;
    double L = 0;
    for (int k = 0; k < 3; k++)
        if (ip->ix->active[k]) L = fmax(L, h[k]);
    LinSet T = S, U = S;
    int okT = correct(ip, x, L, &T);
    if (!okT || l1(&T) > LIN_MAXL1) {
        int n0 = U.n;
        for (int q = 0; q < n0; q++)
            if (U.src[q] < f->ncells) add_neighbours(f, U.src[q], &U);
        add_neighbours(f, own, &U);
        int n1 = U.n;
        for (int q = n0; q < n1; q++)
            if (U.src[q] < f->ncells) add_walls(f, U.src[q], &U);
        int okU = correct(ip, x, L, &U);
        if (okU && (!okT || l1(&U) < l1(&T))) T = U, okT = 1;
    }
    if (!okT || l1(&T) > LIN_MAXL1) {
        ip->st.nlinskip++;
        return;
    }
    ip->st.nlin++;
    s->off[s->nrows + 1] = a;
    for (int q = 0; q < T.n; q++)
        if (T.w[q] != 0) stencil_add(s, T.src[q], T.w[q]);
}
