/*
** cut_face.c: the grid faces of cut cells (cut.h step 4, cut_impl.h).
**
** Each cell sees a grid face as the marching-squares polygon of its own
** fluid corners (local_masks in cut.c) and of its own points on the
** face's edges (its view where it has one, else the grid's point): the
** polygon walked round the corners base, +u, +u+w, +w (normal +a, with
** u = a+1, w = a+2 cyclically), emitting fluid corners and the points of
** edges whose ends differ; two diagonal fluid corners are joined through
** the face (a hexagon).  Such a polygon is the face's rectangle cut by
** straight chords, so it is convex.  A side of it that runs along a grid
** edge then takes every other point of that edge lying on it (refine),
** so that all faces that meet along an edge hold the same points there,
** whichever cell put them: the cells' boundaries close up.
**
** Two cells that see a face alike share it.  Otherwise (a face of the
** geometry lies in the face's plane, and the cells on its two sides see
** different corners or different points) the part both see is their
** shared face and the rest of each cell's polygon is a wall of that
** cell.  Where only the corners differ, the shared part is the polygon of
** the corners both see.  Where the cells' points differ, it is the
** intersection of the two convex polygons: first the crossings of one
** cell's chords with the other's become points of both polygons (one
** mesh point per pair of chords, CutCross), then the lower cell's
** polygon is clipped by the lines of the upper one's chords.  Every
** vertex of the intersection is then a point of both polygons, in their
** order, and the walls are the runs of a polygon's points that the
** shared part skips, closed by its side (face_rest).  The same split is
** computed for both cells from the same two polygons, so they agree.
*/
#include <math.h>
#include <string.h>

#include "cut_impl.h"
#include "mem.h"

#define SIDE_TOL  1e-9  /* box-side recognition, relative to the box */
#define CROSS_EPS 1e-9  /* chords crossing this near an end (fraction of the chord) meet at the end */
#define CLIP_TOL  1e-10 /* a point this near a chord's line (times the face's size squared) lies on it */

/* The frame of the grid face normal to a with base vertex v0: corners,
   its edges q (corner q to q+1) by axis and lower vertex, and the face's
   extent along u and w. */
typedef struct Face {
    int a, u, w, eax[4];
    int64_t cv[4], elo[4];
    double lo[2], hi[2];
} Face;

static void face_frame(const Ctx *c, int a, int64_t v0, Face *F)
{
    int ijk[3], u = (a + 1) % 3, w = (a + 2) % 3;
    cut_vertex_ijk(c, v0, ijk);
    F->a = a, F->u = u, F->w = w;
    F->cv[0] = v0, F->cv[1] = v0 + c->sv[u], F->cv[2] = v0 + c->sv[u] + c->sv[w], F->cv[3] = v0 + c->sv[w];
    F->eax[0] = u, F->eax[1] = w, F->eax[2] = u, F->eax[3] = w;
    F->elo[0] = F->cv[0], F->elo[1] = F->cv[1], F->elo[2] = F->cv[3], F->elo[3] = F->cv[0];
    F->lo[0] = c->x[u][ijk[u]], F->hi[0] = c->x[u][ijk[u] + 1];
    F->lo[1] = c->x[w][ijk[w]], F->hi[1] = c->x[w][ijk[w] + 1];
}

/* Does mesh point pt lie on the line of face edge q?  Points on grid
   edges carry the grid's coordinates exactly, so the test is exact. */
static int on_edge(const Ctx *c, const Face *F, int q, int pt)
{
    const double *x = cut_ptx(c, pt);
    switch (q) {
    case 0: return x[F->w] == F->lo[1];
    case 1: return x[F->u] == F->hi[0];
    case 2: return x[F->w] == F->hi[1];
    default: return x[F->u] == F->lo[0];
    }
}

/* The face edge along which the side pa -> pb runs, or -1 (a chord). */
static int side_edge(const Ctx *c, const Face *F, int pa, int pb)
{
    for (int q = 0; q < 4; q++)
        if (on_edge(c, F, q, pa) && on_edge(c, F, q, pb)) return q;
    return -1;
}

/* A repeated point is dropped, keeping the leaf of a cut point that
   falls on a corner (a corner on the surface that is fluid for the cell). */
static inline void poly_add(Poly *p, int pt, int leaf)
{
    if (p->n > 0 && p->pt[p->n - 1] == pt) {
        if (p->leaf[p->n - 1] < 0) p->leaf[p->n - 1] = leaf;
        return;
    }
    if (p->n == MAXP) return;
    p->pt[p->n] = pt;
    p->leaf[p->n++] = leaf;
}

/* Does polygon p on a grid face normal to a have no area: all its points
   on one side of the face (a cell that sees two corners fluid while the
   points of the edges towards its other corners sit on those two)? */
static int poly_flat(const Ctx *c, int a, const Poly *p)
{
    for (int k = 1; k <= 2; k++) {
        int b = (a + k) % 3, i = 1;
        while (i < p->n && cut_ptx(c, p->pt[i])[b] == cut_ptx(c, p->pt[0])[b]) i++;
        if (i == p->n) return 1;
    }
    return 0;
}

/* The points of edge entry e (the grid's and the cells' views, one each
   per place) strictly between s0 and s1 along it, added to r in order
   from s0 to s1. */
static void edge_between(Ctx *c, CutPt *e, double s0, double s1, Poly *r)
{
    double s[5], lo = fmin(s0, s1), hi = fmax(s0, s1);
    int k[5], n = 0;
    if (!e->nodef && e->at < 0 && e->s > lo && e->s < hi) s[n] = e->s, k[n++] = -1;
    for (int j = 0; j < 4 && e->view >= 0; j++) {
        const CutView *V = &c->views[e->view];
        int dup = 0;
        for (int i = 0; i < n; i++) dup |= s[i] == V->s[j];
        if (V->has[j] && V->at[j] < 0 && V->s[j] > lo && V->s[j] < hi && !dup) s[n] = V->s[j], k[n++] = j;
    }
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && (s0 < s1 ? s[j] < s[j - 1] : s[j] > s[j - 1]); j--) {
            double t = s[j];
            int kk = k[j];
            s[j] = s[j - 1], k[j] = k[j - 1];
            s[j - 1] = t, k[j - 1] = kk;
        }
    for (int i = 0; i < n; i++)
        poly_add(r, k[i] < 0 ? cut_point(c, e) : cut_view_point(c, e, k[i]),
                 k[i] < 0 ? e->leaf : c->views[e->view].leaf[k[i]]);
}

/* Every side of p that runs along a grid edge takes the edge's other
   points lying on it (cut_impl.h). */
static void poly_refine(Ctx *c, const Face *F, Poly *p)
{
    Poly r;
    r.n = 0;
    for (int i = 0; i < p->n; i++) {
        int j = (i + 1) % p->n, q = side_edge(c, F, p->pt[i], p->pt[j]);
        poly_add(&r, p->pt[i], p->leaf[i]);
        if (q < 0) continue;
        int64_t lo = F->elo[q];
        int ax = F->eax[q];
        /* an edge between two fluid vertices of the grid has no point */
        if (c->cls[lo] == 1 && c->cls[lo + c->sv[ax]] == 1) continue;
        CutPt *e = cut_entry(c, 3 * lo + ax);
        if (e && !e->dead) edge_between(c, e, cut_ptx(c, p->pt[i])[ax], cut_ptx(c, p->pt[j])[ax], &r);
    }
    *p = r;
}

int cut_face_poly(Ctx *c, int a, int64_t v0, int bits, int up, Poly *p)
{
    int u = (a + 1) % 3, w = (a + 2) % 3;
    const int64_t cv[4] = {v0, v0 + c->sv[u], v0 + c->sv[u] + c->sv[w], v0 + c->sv[w]};
    const int eax[4] = {u, w, u, w};
    const int64_t elo[4] = {cv[0], cv[1], cv[3], cv[0]};
    /* the cell's quad (cut_impl.h) for each edge of the face */
    const int nu = !up, quad[4] = {nu << 1, nu | 2, 1 | nu << 1, nu};
    int views = 0, refine = 0;
    p->n = 0;
    if (!bits) return 0;
    for (int q = 0; q < 4; q++) {
        int fq = (bits >> q) & 1, fn = (bits >> ((q + 1) & 3)) & 1;
        int64_t key = 3 * elo[q] + eax[q];
        if (fq) poly_add(p, cut_vertex_point(c, cv[q]), -1);
        /* an edge between two fluid vertices of the grid has no point */
        if (c->cls[cv[q]] == 1 && c->cls[cv[(q + 1) & 3]] == 1) continue;
        const CutPt *e = cut_entry(c, key);
        if (!e || e->dead) continue;
        views |= e->view >= 0;
        int lf = -1, pt = fq != fn ? cut_cell_point(c, key, quad[q], &lf) : -1;
        if (pt >= 0) poly_add(p, pt, lf);
        /* a point of the grid's that this cell does not cut with may lie
           on a side of its polygon (refine) */
        refine |= fq == fn && !e->nodef && e->at < 0;
    }
    while (p->n > 1 && p->pt[p->n - 1] == p->pt[0]) {
        if (p->leaf[0] < 0) p->leaf[0] = p->leaf[p->n - 1];
        p->n--;
    }
    if (p->n >= 3 && (refine || views)) {
        Face F;
        face_frame(c, a, v0, &F);
        poly_refine(c, &F, p);
    }
    if (p->n >= 3 && poly_flat(c, a, p)) p->n = 0;
    return views;
}

/* Corner r (face order) of a cell's face normal to a (hi: its upper
   face) as a corner of the cell (bit k: the upper end along axis k). */
static int face_corner(int a, int hi, int r)
{
    int u = (a + 1) % 3, w = (a + 2) % 3;
    return hi << a | (r == 1 || r == 2) << u | (r >= 2) << w;
}

int cut_face_bits(int mask, int a, int hi)
{
    int b = 0;
    for (int r = 0; r < 4; r++) b |= ((mask >> face_corner(a, hi, r)) & 1) << r;
    return b;
}

/* ---- two polygons of one face: crossings and the shared part ---- */

/* (q - p) x (r - p) in the face's (u, w) plane. */
static double orient(const Ctx *c, const Face *F, int p, int q, int r)
{
    const double *x = cut_ptx(c, p), *y = cut_ptx(c, q), *z = cut_ptx(c, r);
    return (y[F->u] - x[F->u]) * (z[F->w] - x[F->w]) - (y[F->w] - x[F->w]) * (z[F->u] - x[F->u]);
}

/* The mesh point where chord a0 a1 crosses chord b0 b1 at parameter t of
   the first: one point for each pair of chords. */
static int cross_point(Ctx *c, int a0, int a1, int b0, int b1, double t)
{
    int k[4] = {a0 < a1 ? a0 : a1, a0 < a1 ? a1 : a0, b0 < b1 ? b0 : b1, b0 < b1 ? b1 : b0};
    if (k[2] < k[0] || (k[2] == k[0] && k[3] < k[1])) {
        int t0 = k[0], t1 = k[1];
        k[0] = k[2], k[1] = k[3], k[2] = t0, k[3] = t1;
    }
    for (size_t i = 0; i < c->ncross; i++) {
        const CutCross *x = &c->cross[i];
        if (x->a0 == k[0] && x->a1 == k[1] && x->b0 == k[2] && x->b1 == k[3]) return x->pt;
    }
    const double *p = cut_ptx(c, a0), *q = cut_ptx(c, a1);
    double y[3];
    for (int d = 0; d < 3; d++) y[d] = p[d] + t * (q[d] - p[d]);
    mem_grow((void **)&c->cross, &c->cross_cap, c->ncross + 1, sizeof *c->cross);
    int pt = meshbuild_point(&c->b, y);
    c->cross[c->ncross++] = (CutCross){k[0], k[1], k[2], k[3], pt};
    return pt;
}

/* Crossing points to insert into a polygon: after its point i, at
   parameter t along the side. */
typedef struct Ins {
    int i, pt;
    double t;
} Ins;

static void poly_insert(Poly *p, Ins *ins, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && (ins[j].i < ins[j - 1].i || (ins[j].i == ins[j - 1].i && ins[j].t < ins[j - 1].t)); j--) {
            Ins t = ins[j];
            ins[j] = ins[j - 1], ins[j - 1] = t;
        }
    Poly r;
    r.n = 0;
    for (int i = 0, k = 0; i < p->n; i++) {
        poly_add(&r, p->pt[i], p->leaf[i]);
        for (; k < n && ins[k].i == i; k++) poly_add(&r, ins[k].pt, -1);
    }
    while (r.n > 1 && r.pt[r.n - 1] == r.pt[0]) r.n--;
    *p = r;
}

/* The crossings of A's chords with B's become points of both. */
static void chord_crossings(Ctx *c, const Face *F, Poly *A, Poly *B)
{
    Ins ia[MAXP], ib[MAXP];
    int na = 0, nb = 0;
    for (int i = 0; i < A->n; i++) {
        int a0 = A->pt[i], a1 = A->pt[(i + 1) % A->n];
        if (side_edge(c, F, a0, a1) >= 0) continue;
        for (int j = 0; j < B->n; j++) {
            int b0 = B->pt[j], b1 = B->pt[(j + 1) % B->n];
            if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1 || side_edge(c, F, b0, b1) >= 0) continue;
            double d = orient(c, F, a0, a1, b1) - orient(c, F, a0, a1, b0);
            if (d == 0) continue;
            /* t along a0 a1 and s along b0 b1 where they meet */
            double s = -orient(c, F, a0, a1, b0) / d, t = orient(c, F, b0, b1, a0) / (orient(c, F, b0, b1, a0) - orient(c, F, b0, b1, a1));
            if (!(t > CROSS_EPS && t < 1 - CROSS_EPS && s > CROSS_EPS && s < 1 - CROSS_EPS)) continue;
            if (na == MAXP || nb == MAXP) continue;
            int x = cross_point(c, a0, a1, b0, b1, t);
            ia[na++] = (Ins){i, x, t};
            ib[nb++] = (Ins){j, x, s};
        }
    }
    if (na) poly_insert(A, ia, na);
    if (nb) poly_insert(B, ib, nb);
}

/* Clips polygon q by the line of chord b0 -> b1 of polygon B (keeping
   its left, B's side).  A side that leaves the line's side crosses it at
   a point of B (a chord's end on the face's rim, or a crossing already
   made); returns 0 when there is none. */
static int clip_chord(const Ctx *c, const Face *F, Poly *q, const Poly *B, int b0, int b1, double tol)
{
    double d[MAXP];
    Poly r;
    r.n = 0;
    for (int i = 0; i < q->n; i++) {
        d[i] = q->pt[i] == b0 || q->pt[i] == b1 ? 0 : orient(c, F, b0, b1, q->pt[i]);
        if (fabs(d[i]) <= tol) d[i] = 0;
    }
    for (int i = 0; i < q->n; i++) {
        int j = (i + 1) % q->n;
        if (d[i] >= 0) poly_add(&r, q->pt[i], q->leaf[i]);
        if (!((d[i] > 0 && d[j] < 0) || (d[i] < 0 && d[j] > 0))) continue;
        const double *x = cut_ptx(c, q->pt[i]), *y = cut_ptx(c, q->pt[j]);
        double du = y[F->u] - x[F->u], dw = y[F->w] - x[F->w], len2 = du * du + dw * dw;
        int best = -1;
        double bo = tol;
        for (int k = 0; k < B->n; k++) {
            const double *z = cut_ptx(c, B->pt[k]);
            double along = (z[F->u] - x[F->u]) * du + (z[F->w] - x[F->w]) * dw;
            double off = fabs(orient(c, F, q->pt[i], q->pt[j], B->pt[k]));
            double on = fabs(orient(c, F, b0, b1, B->pt[k]));
            if (along > 0 && along < len2 && on <= tol && off <= bo) bo = off, best = k;
        }
        if (best < 0) return 0;
        poly_add(&r, B->pt[best], B->leaf[best]);
    }
    while (r.n > 1 && r.pt[r.n - 1] == r.pt[0]) r.n--;
    *q = r;
    return 1;
}

/* Is q a part of h: its points points of h, in h's (cyclic) order? */
static int poly_within(const Poly *q, const Poly *h)
{
    int at[MAXP], descents = 0;
    for (int r = 0; r < q->n; r++) {
        at[r] = 0;
        while (at[r] < h->n && h->pt[at[r]] != q->pt[r]) at[r]++;
        if (at[r] == h->n) return 0;
    }
    for (int r = 0; r < q->n; r++) descents += at[(r + 1) % q->n] < at[r];
    return descents == 1;
}

/* The part q of the face that the cells below (lo) and above (hi) it both
   see, when their polygons differ in points: crossings of their chords
   are inserted into both, then lo is clipped by hi's chords.  q starts at
   the point of lo that comes first (the walk's order, as the marching-
   squares polygons start); it is empty when there is no such part. */
static void face_split(Ctx *c, int a, int64_t v0, Poly *lo, Poly *hi, Poly *q)
{
    Face F;
    q->n = 0;
    if (lo->n < 3 || hi->n < 3) return;
    face_frame(c, a, v0, &F);
    double L2 = (F.hi[0] - F.lo[0]) * (F.hi[0] - F.lo[0]) + (F.hi[1] - F.lo[1]) * (F.hi[1] - F.lo[1]);
    double tol = CLIP_TOL * L2, area = 0;
    chord_crossings(c, &F, lo, hi);
    *q = *lo;
    for (int j = 0; j < hi->n && q->n >= 3; j++) {
        int b0 = hi->pt[j], b1 = hi->pt[(j + 1) % hi->n];
        if (side_edge(c, &F, b0, b1) < 0 && !clip_chord(c, &F, q, hi, b0, b1, tol)) q->n = 0;
    }
    for (int i = 1; i + 1 < q->n; i++) area += orient(c, &F, q->pt[0], q->pt[i], q->pt[i + 1]);
    if (q->n < 3 || !(area > tol)) {
        q->n = 0;
        return;
    }
    int first = 0, best = MAXP;
    for (int r = 0; r < q->n; r++) {
        int k = 0;
        while (k < lo->n && lo->pt[k] != q->pt[r]) k++;
        if (k < best) best = k, first = r;
    }
    Poly r = *q;
    for (int i = 0; i < q->n; i++) q->pt[i] = r.pt[(first + i) % r.n], q->leaf[i] = r.leaf[(first + i) % r.n];
    if (!poly_within(q, lo) || !poly_within(q, hi)) q->n = 0;
}

/* ---- the faces a cell adds ---- */

/* A wall of the cell on a grid face: polygon p, reversed when rev (a
   lower face of the cell). */
static void face_wall(Ctx *c, Poly *p, int rev, int cell)
{
    if (rev)
        for (int l = 0, r = p->n - 1; l < r; l++, r--) {
            int t = p->pt[l], lf = p->leaf[l];
            p->pt[l] = p->pt[r], p->leaf[l] = p->leaf[r];
            p->pt[r] = t, p->leaf[r] = lf;
        }
    cut_wall_face(c, p->pt, p->leaf, p->n, cell);
}

/* The walls of a cell on a grid face it sees as polygon h, of which its
   neighbour shares the part q (a polygon on points of h, in h's order):
   one wall for each run of h's points that q skips, closed by q's side
   across it (with two diagonal corners h may be a hexagon and q a corner
   of it, so the rest is not a marching-squares polygon of its own).
   Returns 0, adding nothing, when q is not such a part of h. */
static int face_rest(Ctx *c, const Poly *h, const Poly *q, int rev, int cell)
{
    char in[MAXP] = {0};
    if (q->n >= 3 && !poly_within(q, h)) return 0;
    if (q->n < 3) {
        Poly w = *h;
        face_wall(c, &w, rev, cell);
        return 1;
    }
    for (int r = 0; r < q->n; r++) {
        int k = 0;
        while (h->pt[k] != q->pt[r]) k++;
        in[k] = 1;
    }
    for (int i = 0; i < h->n; i++) {
        if (!in[i] || in[(i + 1) % h->n]) continue;
        Poly w;
        w.n = 0;
        int j = i;
        do {
            w.pt[w.n] = h->pt[j];
            w.leaf[w.n++] = h->leaf[j];
            j = (j + 1) % h->n;
        } while (!in[j] && w.n < MAXP - 1);
        w.pt[w.n] = h->pt[j];
        w.leaf[w.n++] = h->leaf[j];
        if (w.n >= 3) face_wall(c, &w, rev, cell);
    }
    return 1;
}

static int poly_same(const Poly *p, const Poly *q)
{
    if (p->n != q->n) return 0;
    for (int i = 0; i < p->n; i++)
        if (p->pt[i] != q->pt[i]) return 0;
    return 1;
}

/* Grid face (a, hi) of Cartesian cell ci (new cell `cell`): its polygon
   p as the cell sees it (for the cell's volume and boundary loops), and
   what of it the cell adds: the face it shares with its upper neighbour
   (each shared face is added by its lower cell), and the part of p the
   neighbour does not see, as a wall.  Box sides are cut_box_faces's. */
void cut_grid_face(Ctx *c, const int ijk[3], int64_t ci, int64_t v0, int a, int hi, int cell, Poly *p)
{
    int fa = cut_face_bits(c->lmask[ci], a, hi), nb = ijk[a] + (hi ? 1 : -1);
    int64_t fv = hi ? v0 + c->sv[a] : v0;
    int views = cut_face_poly(c, a, fv, fa, !hi, p);
    if (nb < 0 || nb >= c->n[a] || p->n < 3) return;
    int64_t cn = ci + (hi ? 1 : -1) * c->sc[a];
    int fb = cut_face_bits(c->lmask[cn], a, !hi);
    Poly q;
    if (!views) {
        /* both cells see the face's points alike: the corners decide */
        if (fa == fb) {
            if (hi) meshbuild_face(&c->b, p->pt, p->n, cell, c->cellid[cn], 0);
            return;
        }
        cut_face_poly(c, a, fv, fa & fb, !hi, &q);
    } else {
        Poly pn;
        cut_face_poly(c, a, fv, fb, hi, &pn);
        if (poly_same(p, &pn)) {
            if (hi) meshbuild_face(&c->b, p->pt, p->n, cell, c->cellid[cn], 0);
            return;
        }
        face_split(c, a, fv, hi ? p : &pn, hi ? &pn : p, &q);
    }
    if (hi && q.n >= 3) meshbuild_face(&c->b, q.pt, q.n, cell, c->cellid[cn], 0);
    if (!face_rest(c, p, &q, !hi, cell) && (fa & ~fb)) {
        cut_face_poly(c, a, fv, fa & ~fb, !hi, &q);
        if (q.n >= 3) face_wall(c, &q, !hi, cell);
    }
}

/* Side (0..5) of boundary face f of the grid, or -1. */
int cut_box_side(const CartGrid *cg, const Mesh *grid, int f)
{
    for (int a = 0; a < 3; a++)
        for (int hi = 0; hi < 2; hi++) {
            double xs = cg->x[a][hi ? cg->n[a] : 0], tol = SIDE_TOL * (cg->x[a][cg->n[a]] - cg->x[a][0]);
            int on = 1;
            for (int q = grid->face_off[f]; q < grid->face_off[f + 1] && on; q++)
                on = fabs(grid->points[3 * (size_t)grid->face_idx[q] + a] - xs) <= tol;
            if (on) return 2 * a + hi;
        }
    return -1;
}

/* The fluid parts of the grid's boundary faces, on the grid's patches in
   the grid's order (which keeps cyclic pairs matched). */
int cut_box_faces(Ctx *c, const Mesh *grid, Err *e)
{
    for (int p = 0; p < grid->npatches; p++) {
        const Patch *P = &grid->patches[p];
        for (int f = P->start; f < P->start + P->size; f++) {
            int side = cut_box_side(&grid->cart, grid, f), oc = grid->owner[f];
            if (side < 0)
                return err_set(e, NULL, 0, "grid boundary face %d (patch %s) is not on a side of the box", f,
                               P->name);
            int a = side / 2, hi = side & 1,
                ijk[3] = {oc % c->n[0], (oc / c->n[0]) % c->n[1], oc / (c->n[0] * c->n[1])};
            ijk[a] = hi ? c->n[a] : 0;
            Poly q;
            cut_face_poly(c, a, cut_cell_base(c, ijk[0], ijk[1], ijk[2]), cut_face_bits(c->lmask[oc], a, hi), !hi,
                          &q);
            if (q.n < 3 || c->cellid[oc] < 0) continue;
            if (!hi)
                for (int l = 1, r = q.n - 1; l < r; l++, r--) {
                    int t = q.pt[l];
                    q.pt[l] = q.pt[r];
                    q.pt[r] = t;
                }
            meshbuild_face(&c->b, q.pt, q.n, c->cellid[oc], -1, p);
            double nv[3] = {0, 0, 0};
            nv[a] = hi ? 1 : -1;
            cut_push_wall(c, p, nv);
        }
    }
    return 0;
}
