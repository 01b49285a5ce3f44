/*
** interp_ml.c: multilinear interpolation with reflection ghosts (spec
** granular-model.md §3.2 and correction 9, thesis §4.2.1, eq. 4.18-4.20).
**
** Sources are the Cartesian cell centres of the parent grid, not the
** cells' nodes: a point x lies in the box of 2^d neighbouring centres (d =
** 2 or 3, the empty axis of a 2-D grid left out), whose bi-/trilinear
** weights are the products of the per-axis fractions (eq. 4.18, the
** opposite-area form).  A centre whose Cartesian cell is whole, cut (not
** merged) or a master stands for its cell's value; the thesis accepts the
** O(h) shift between a cut cell's Cartesian centre and its node ("(✓)" in
** column CS of Table 4.1).  Corners of zero weight are skipped, so a point
** on a centre, or on a lattice line, uses only the centres it touches.
**
** A missing centre S (a slave, an outside Cartesian cell, or one beyond
** the box of the grid) is a ghost, reflected at the boundary (eq.
** 4.19/4.20, the spec's clean form): along the line from the master's
** point x_M to x_S, x_b = x_M + t_b (x_S - x_M) is where the line meets
** the local boundary plane, and
**     xi_S = xi_M + (xi_b - xi_M) / t_b
** so that the linear interpolant through x_M and x_S takes the boundary
** value at x_b (t_b < 1: S beyond the boundary; t_b > 1: S inside it).
** x_M is the master cell's node, where its value lives, not its Cartesian
** centre as the thesis draws it: then the ghost is exact for a linear
** function whatever the shift between the two (with the centre, a thin cut
** master's O(h) shift came back amplified by 1/t_b: max error 2.4e-1
** instead of 1.4e-1 on the merged sphere at N = 64, tests/fv/test_interp.c).
** The plane (correction 9) passes through the area-weighted centroid of a
** set of boundary faces with their area-weighted mean normal, and xi_b is
** their area-weighted mean boundary value (sources ncells + b):
**   - S a slave: M is S's own (merged) cell (thesis), the faces are that
**     cell's boundary faces whose centres lie in S's box (the slave's own
**     wall), else those of the cell facing S (S_f . (x_S - x_M) > 0);
**   - S outside (the thesis has no master there, a gap the spec lists):
**     M is the present corner of the same box nearest S (fewest differing
**     indices, then distance) whose cell has boundary faces facing S;
**     those faces make the plane;
**   - S beyond the box of the grid: one mirror image per side it lies
**     beyond, in that side, from the in-box centre S' next to it (its
**     Cartesian centre, the wall faces of its cell), summed as
**     xi_S = xi_S' + sum_a (ghost_a - xi_S'): exact for linear functions
**     at the walls of a block grid, corners and edges included; when S'
**     is missing, as an outside centre.
** A cyclic pair of patches on the two sides of the box along an axis k
** (the periodic inclined channel of thesis §5.1.3, whose translation is
** (L, rise, 0), not (L, 0, 0)) makes the lattice periodic: a centre beyond
** such a side is its image one translation away, found by a shift of
** lattice indices (n_k along k, the rise in cells along the others), when
** the translation maps grid lines onto grid lines.  A present image stands
** for its cell; a slave image is reflected in the image's own frame (its
** master, its wall); an outside image as an outside centre from the
** present corners of the box.  The stencil then sees the same cells at
** both ends of the period, as the solver's cyclic faces do; without it a
** cut channel's ends were mirrored at the box sides and the density error
** next to them was 0.24 at h = 0.1 instead of the interior's.
** Cyclic faces are no boundary: they never make a reflection plane.
** A reflection whose line is nearly parallel to the plane, or whose master
** centre lies on it (|t_b| < TB_MIN: weights 1/t_b would blow up), or that
** finds no faces, takes xi_S = xi_M instead (InterpStats.ndegenerate).
** A point whose 2^d corners are all missing (inside a thin solid between
** fluid regions, finer than the grid) takes modified Shepard's row
** (InterpStats.nfallback).
** Every row sums to 1: (1 - 1/t_b) + (1/t_b) sum a_b = 1 with sum a_b = 1.
** Voronoi grids are refused (interp_ml_check): a centre there stands for
** the cell holding its seed, whose node can be far from it, and the
** manufactured solutions came out O(1) wrong; shepard serves them.
*/
#include "interp_impl.h"

#include <math.h>
#include <string.h>

#include "geom.h"

#define TB_MIN 0.05   /* smallest |t_b| reflected */
#define SNAP 1e-12    /* a lattice fraction this close to 0 or 1 is 0 or 1 */

typedef struct Corner {
    int idx[3];    /* lattice indices (may be -1 or n: beyond the box) */
    int K;         /* Cartesian cell, or -1 beyond the box (its image's when img) */
    int img;       /* beyond a cyclic side: K, cell and iidx are its periodic image's */
    int iidx[3];   /* the image's lattice indices */
    int cell;      /* its cell when present, else -1 */
    double w;      /* multilinear weight */
} Corner;

/* Role of Cartesian cell K and its cell.  A block grid without the data
   contract: every Cartesian cell is whole and is the cell of its number. */
static int role_of(const Interp *ip, int K, int *cell)
{
    const CartCells *cc = &ip->f->m->cartcells;
    if (ip->ix->block) {
        *cell = K;
        return CART_WHOLE;
    }
    *cell = cc->cell[K];
    return cc->role[K];
}

static int present(int role) { return role == CART_WHOLE || role == CART_CUT || role == CART_MASTER; }

/* The coordinate of x[0..n] equal to v to tol, or -1. */
static int grid_line(const double *x, int n, double v, double tol)
{
    int i = interp_locate(x, n, v);
    if (fabs(x[i] - v) <= tol) return i;
    if (i + 1 <= n && fabs(x[i + 1] - v) <= tol) return i + 1;
    return -1;
}

/* Does every face of patch p lie on the plane x_k = v? */
static int on_plane(const Mesh *m, const Patch *pa, int k, double v, double tol)
{
    for (int i = 0; i < pa->size; i++)
        if (fabs(m->face_centre[3 * (pa->start + i) + k] - v) > tol) return 0;
    return pa->size > 0;
}

/* The lattice shift s along axis a of translation T_a: x[a][i + s] =
   x[a][i] + T_a for every i where both exist; 0 with *ok = 0 when none. */
static int lattice_shift(const CartGrid *g, int a, double Ta, double tol, int *ok)
{
    int n = g->n[a];
    if (fabs(Ta) <= tol) return 0;
    int j = Ta > 0 ? grid_line(g->x[a], n, g->x[a][0] + Ta, tol) : grid_line(g->x[a], n, g->x[a][n] + Ta, tol);
    if (j < 0) {
        *ok = 0;
        return 0;
    }
    int sh = Ta > 0 ? j : j - n;
    for (int i = 0; i <= n; i++)
        if (i + sh >= 0 && i + sh <= n && fabs(g->x[a][i + sh] - g->x[a][i] - Ta) > tol) *ok = 0;
    return sh;
}

/* Cyclic pairs spanning the box: per[k] and the lattice shift pshift[k]
   of each, from the first pair of faces (bc.c checks the rest). */
static void periodic_lattice(InterpIndex *ix, const Mesh *m)
{
    const CartGrid *g = &m->cart;
    double size = 0;
    for (int k = 0; k < 3; k++) size = fmax(size, g->x[k][g->n[k]] - g->x[k][0]);
    double tol = 1e-9 * size;
    memset(ix->per, 0, sizeof ix->per);
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        if (!pa->type || strcmp(pa->type, "cyclic") || !pa->neighbour) continue;
        int q = mesh_patch(m, pa->neighbour);
        if (q < 0 || m->patches[q].size != pa->size) continue;
        const Patch *qa = &m->patches[q];
        for (int k = 0; k < 3; k++) {
            if (!ix->active[k] || !on_plane(m, pa, k, g->x[k][0], tol) || !on_plane(m, qa, k, g->x[k][g->n[k]], tol))
                continue;
            int ok = 1;
            for (int a = 0; a < 3; a++) {
                double Ta = m->face_centre[3 * qa->start + a] - m->face_centre[3 * pa->start + a];
                ix->pshift[k][a] = ix->active[a] ? lattice_shift(g, a, Ta, tol, &ok) : 0;
            }
            ix->per[k] = ok && ix->pshift[k][k] == g->n[k];
        }
    }
}

int interp_ml_check(const Interp *ip, const char *grid, Err *e)
{
    const Mesh *m = ip->f->m;
    const char *g = grid ? grid : "the grid";
    if (m->cart.n[0] <= 0)
        return err_set(e, ip->o.file, ip->o.line,
                       "interpolation scheme multilinear needs the Cartesian parent grid (cartesianGrid) of %s, "
                       "which has none: choose shepard",
                       g);
    /* A Voronoi cell stands for the Cartesian centre holding its seed,
       whose node can be far from that centre: the mms study's steady disc
       had density 3.6 for 0.94 in a wall cell, the 3-D ball never became
       steady (doc/validation.md), while shepard converges there. */
    if (m->cell_seed)
        return err_set(e, ip->o.file, ip->o.line,
                       "interpolation scheme multilinear is not available on Voronoi grids (%s has cellSeed): "
                       "choose shepard",
                       g);
    periodic_lattice(ip->ix, m);
    if (m->cartcells.n > 0) return 0;
    long ncart = (long)m->cart.n[0] * m->cart.n[1] * m->cart.n[2];
    int block = ncart == m->ncells;
    for (int c = 0; block && m->cell_parent && c < m->ncells; c++) block = m->cell_parent[c] == c;
    if (!block)
        return err_set(e, ip->o.file, ip->o.line,
                       "interpolation scheme multilinear needs the cut-cell data contract (cartesianCells) of %s, "
                       "which has none: write the grid with cutCells or mergeCells, or choose shepard",
                       g);
    ip->ix->block = 1;
    return 0;
}

/* Lattice coordinate i along axis k: the Cartesian centre, or the mirror of
   the first or last one in the side of the box. */
static double centre(const CartGrid *g, int k, int i)
{
    int n = g->n[k];
    if (i < 0) return 1.5 * g->x[k][0] - 0.5 * g->x[k][1];
    if (i >= n) return 1.5 * g->x[k][n] - 0.5 * g->x[k][n - 1];
    return 0.5 * (g->x[k][i] + g->x[k][i + 1]);
}

static void lattice_point(const CartGrid *g, const int idx[3], double x[3])
{
    for (int k = 0; k < 3; k++) x[k] = centre(g, k, idx[k]);
}

/* Boundary face i of cell c counts for the plane: mode 0, its centre in
   the box lo..hi; mode 1, it faces direction dir. */
static int face_ok(const Interp *ip, int i, int mode, const double *lo, const double *hi, const double *dir)
{
    const Mesh *m = ip->f->m;
    if (i < m->ninternal || ip->f->empty_face[i] || ip->f->cyc_face[i - m->ninternal] >= 0) return 0;
    if (mode == 1) return geom_dot(m->face_area + 3 * i, dir) > 0;
    const double *x = m->face_centre + 3 * i;
    for (int k = 0; k < 3; k++) {
        double tol = 1e-9 * (hi[k] - lo[k]);
        if (x[k] < lo[k] - tol || x[k] > hi[k] + tol) return 0;
    }
    return 1;
}

typedef struct Plane {
    int mode;
    double lo[3], hi[3], dir[3];
    double p0[3], S[3], area;   /* centroid, sum of area vectors, sum of areas */
} Plane;

static void plane_of(const Interp *ip, int c, Plane *P)
{
    const Mesh *m = ip->f->m;
    memset(P->p0, 0, sizeof P->p0);
    memset(P->S, 0, sizeof P->S);
    P->area = 0;
    for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
        int i = m->cell_faces[q];
        if (!face_ok(ip, i, P->mode, P->lo, P->hi, P->dir)) continue;
        double a = ip->f->mag_sf[i];
        for (int k = 0; k < 3; k++) {
            P->p0[k] += a * m->face_centre[3 * i + k];
            P->S[k] += m->face_area[3 * i + k];
        }
        P->area += a;
    }
    if (P->area > 0)
        for (int k = 0; k < 3; k++) P->p0[k] /= P->area;
}

/* xi_S = (1 - 1/t_b) xi_M + (1/t_b) xi_b with weight w into s; 0 when
   the plane has no faces or the reflection is degenerate. */
static int reflect(Interp *ip, int c, const double *xM, const double *xS, Plane *P, double w, Stencil *s)
{
    plane_of(ip, c, P);
    double smag = geom_norm(P->S), d[3], r[3];
    if (!(P->area > 0) || !(smag > 1e-12 * P->area)) return 0;
    for (int k = 0; k < 3; k++) {
        d[k] = xS[k] - xM[k];
        r[k] = P->p0[k] - xM[k];
    }
    double den = geom_dot(d, P->S) / smag, tb = geom_dot(r, P->S) / smag / den;
    if (!(fabs(den) > 1e-3 * geom_norm(d)) || !(fabs(tb) >= TB_MIN)) return 0;
    const Mesh *m = ip->f->m;
    stencil_add(s, c, w * (1 - 1 / tb));
    for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
        int i = m->cell_faces[q];
        if (face_ok(ip, i, P->mode, P->lo, P->hi, P->dir))
            stencil_add(s, ip->f->ncells + i - m->ninternal, w / tb * ip->f->mag_sf[i] / P->area);
    }
    return 1;
}

/* S a slave: reflect at its own wall from its master's centre. */
static void ghost_slave(Interp *ip, const Corner *S, const double *xS, double w, Stencil *s)
{
    const Mesh *m = ip->f->m;
    const CartCells *cc = &m->cartcells;
    int c = cc->cell[S->K];
    const double *xM = ip->f->node + 3 * c;
    Plane P = {0};
    for (int k = 0; k < 3; k++) {
        P.lo[k] = m->cart.x[k][S->idx[k]];
        P.hi[k] = m->cart.x[k][S->idx[k] + 1];
        P.dir[k] = xS[k] - xM[k];
    }
    if (reflect(ip, c, xM, xS, &P, w, s)) return;
    P.mode = 1;
    if (reflect(ip, c, xM, xS, &P, w, s)) return;
    ip->st.ndegenerate++;
    stencil_add(s, c, w);
}

static int lattice_distance(const Corner *a, const Corner *b)
{
    int n = 0;
    for (int k = 0; k < 3; k++) n += a->idx[k] != b->idx[k];
    return n;
}

/* S outside or beyond the box: reflect from the nearest present corner
   whose cell has boundary faces facing S. */
static void ghost_outside(Interp *ip, const Corner *cs, int nc, const Corner *S, const double *xS, double w, Stencil *s)
{
    const CartGrid *g = &ip->f->m->cart;
    char tried[8] = {0};
    int first = -1;
    for (;;) {
        int best = -1;
        double bkey = INFINITY;
        for (int q = 0; q < nc; q++) {
            if (cs[q].cell < 0 || cs[q].img || tried[q]) continue;
            double x[3];
            lattice_point(g, cs[q].idx, x);
            double dd = (x[0] - xS[0]) * (x[0] - xS[0]) + (x[1] - xS[1]) * (x[1] - xS[1]) + (x[2] - xS[2]) * (x[2] - xS[2]);
            double key = lattice_distance(cs + q, S) * 1e300 + dd;
            if (best < 0 || key < bkey) {
                best = q;
                bkey = key;
            }
        }
        if (best < 0) break;
        if (first < 0) first = best;
        tried[best] = 1;
        const double *xM = ip->f->node + 3 * cs[best].cell;
        Plane P = {.mode = 1};
        for (int k = 0; k < 3; k++) P.dir[k] = xS[k] - xM[k];
        if (reflect(ip, cs[best].cell, xM, xS, &P, w, s)) return;
    }
    ip->st.ndegenerate++;
    stencil_add(s, cs[first].cell, w);
}

/* S beyond the box along the axes A (a side, an edge or a corner of the
   box): when the in-box centre S' next to it is present, one reflection
   per side, xi_S = xi_S' + sum_a (ghost_a - xi_S'), each ghost_a the
   mirror of S' in side a (exact for linear functions at the walls of a
   block grid); else as an outside centre. */
static void ghost_box(Interp *ip, const Corner *cs, int nc, const Corner *S, const double *xS, double w, Stencil *s)
{
    const CartGrid *g = &ip->f->m->cart;
    int in[3], cell = -1, K;
    for (int k = 0; k < 3; k++) in[k] = S->idx[k] < 0 ? 0 : S->idx[k] >= g->n[k] ? g->n[k] - 1 : S->idx[k];
    K = in[0] + g->n[0] * (in[1] + g->n[1] * in[2]);
    if (!present(role_of(ip, K, &cell))) {
        ghost_outside(ip, cs, nc, S, xS, w, s);
        return;
    }
    double xM[3], xa[3];
    lattice_point(g, in, xM);
    int m = 0;
    for (int a = 0; a < 3; a++) {
        if (S->idx[a] == in[a]) continue;
        m++;
        memcpy(xa, xM, sizeof xa);
        xa[a] = xS[a];
        Plane P = {.mode = 1};
        P.dir[a] = xa[a] - xM[a];
        if (!reflect(ip, cell, xM, xa, &P, w, s)) {
            ip->st.ndegenerate++;
            stencil_add(s, cell, w);
        }
    }
    stencil_add(s, cell, -(m - 1) * w);
}

/* Corner c beyond the box: its periodic image, when cyclic sides span the
   box along the axes it lies beyond and the image lies inside the box. */
static void periodic_image(const Interp *ip, Corner *c)
{
    const InterpIndex *ix = ip->ix;
    const CartGrid *g = &ip->f->m->cart;
    int j[3];
    memcpy(j, c->idx, sizeof j);
    for (int k = 0; k < 3; k++) {
        if (j[k] >= 0 && j[k] < g->n[k]) continue;
        if (!ix->per[k]) return;
        int sg = j[k] < 0 ? 1 : -1;
        for (int a = 0; a < 3; a++) j[a] += sg * ix->pshift[k][a];
    }
    for (int k = 0; k < 3; k++)
        if (j[k] < 0 || j[k] >= g->n[k]) return;
    c->img = 1;
    memcpy(c->iidx, j, sizeof j);
    c->K = j[0] + g->n[0] * (j[1] + g->n[1] * j[2]);
}

/* The 2^d corners of the lattice box around x; returns their number. */
static int corners(const Interp *ip, const double x[3], Corner *cs)
{
    const CartGrid *g = &ip->f->m->cart;
    int i0[3], nact = 0, axes[3];
    double t[3];
    for (int k = 0; k < 3; k++) {
        i0[k] = 0;
        t[k] = 0;
        if (!ip->ix->active[k]) continue;
        axes[nact++] = k;
        int i = interp_locate(g->x[k], g->n[k], x[k]);
        if (x[k] < centre(g, k, i)) i--;
        i0[k] = i;
        t[k] = (x[k] - centre(g, k, i)) / (centre(g, k, i + 1) - centre(g, k, i));
        if (fabs(t[k]) < SNAP) t[k] = 0; /* at a centre to round-off: CS */
        if (fabs(1 - t[k]) < SNAP) t[k] = 1;
    }
    int nc = 1 << nact;
    for (int q = 0; q < nc; q++) {
        Corner *c = cs + q;
        c->w = 1;
        memcpy(c->idx, i0, sizeof i0);
        for (int a = 0; a < nact; a++) {
            int k = axes[a], bit = (q >> a) & 1;
            c->idx[k] += bit;
            c->w *= bit ? t[k] : 1 - t[k];
        }
        int in = 1;
        for (int k = 0; k < 3; k++) in &= c->idx[k] >= 0 && c->idx[k] < g->n[k];
        c->K = in ? c->idx[0] + g->n[0] * (c->idx[1] + g->n[1] * c->idx[2]) : -1;
        c->img = 0;
        if (!in) periodic_image(ip, c);
        in = c->K >= 0;
        c->cell = -1;
        if (in && !present(role_of(ip, c->K, &c->cell))) c->cell = -1;
    }
    return nc;
}

void interp_multilinear(Interp *ip, const double x[3], Stencil *s)
{
    Corner cs[8];
    int nc = corners(ip, x, cs), any = 0;
    for (int q = 0; q < nc; q++) any |= cs[q].cell >= 0;
    if (!any) {
        ip->st.nfallback++;
        interp_shepard(ip, x, 1, s);
        return;
    }
    const Mesh *m = ip->f->m;
    for (int q = 0; q < nc; q++) {
        if (cs[q].w == 0) continue;
        if (cs[q].cell >= 0) {
            stencil_add(s, cs[q].cell, cs[q].w);
            continue;
        }
        double xS[3];
        lattice_point(&m->cart, cs[q].idx, xS);
        ip->st.nreflect++;
        if (cs[q].img && !ip->ix->block && m->cartcells.role[cs[q].K] == CART_SLAVE) {
            Corner I = cs[q];
            memcpy(I.idx, I.iidx, sizeof I.idx);
            lattice_point(&m->cart, I.idx, xS); /* the image's frame: its master, its wall */
            ghost_slave(ip, &I, xS, cs[q].w, s);
        } else if (cs[q].img)
            ghost_outside(ip, cs, nc, cs + q, xS, cs[q].w, s);
        else if (cs[q].K < 0)
            ghost_box(ip, cs, nc, cs + q, xS, cs[q].w, s);
        else if (!ip->ix->block && m->cartcells.role[cs[q].K] == CART_SLAVE)
            ghost_slave(ip, cs + q, xS, cs[q].w, s);
        else
            ghost_outside(ip, cs, nc, cs + q, xS, cs[q].w, s);
    }
}
