/*
** trisurf.c: closed triangulated surfaces as solids.  See trisurf.h.
**
** Welding.  trisurf_from_soup hashes each corner's three coordinates
** (bit patterns, -0 folded onto +0) in an open-addressing table, so
** corners at bit-identical positions become one point, in order of first
** appearance.  Nothing is welded by tolerance: a surface whose triangles
** do not meet exactly is reported open by trisurf_check.
**
** Edges.  Every triangle side is an edge occurrence keyed by its lower
** point index; occurrences are grouped by that point (counting sort) and
** by the higher index inside each group.  trisurf_check counts groups of
** one (open), three or more (non-manifold) and pairs running the same way
** (flipped); trisurf_orient flood-fills over pairs to make each connected
** component (shell) consistent.
**
** Shells.  The solid is where the winding number is positive: the inside
** tests compare it with zero, and trisurf_crossings keeps only the
** crossings where it changes sign that way (from the winding number at
** the segment's start), so overlapping shells give their union to every
** query alike.  trisurf_orient keeps the given orientation when it is
** consistent (trisurf.h) and else sets each shell by the parity of the
** number of shells holding it whole.  Both tests ask for winding numbers
** about a shell's points, per other shell: one ray along +x through the
** line buckets (below) per point, counting only the shells whose bounding
** box holds the point (a closed shell's winding number is zero outside
** it), so the cost is linear in the surface, not quadratic in the number
** of shells (132055 of them in OpenFOAM's motorBike: about a second).  A
** shell inside nothing costs one ray; one whose first point is inside
** others is followed point by point only while some still hold it.
**
** Exact predicates.  Every decision of the queries is the sign of a 2-D
** or 3-D orientation determinant of the stored doubles: the float value
** with Shewchuk's error bound, and when that is inconclusive the exact
** sign of the expanded determinant (products split into pairs of doubles
** by fma and summed as a non-overlapping expansion; for orient3d from the
** differences when those are exact, the usual case of a tie on a grid,
** else from the raw coordinates).  So every sign is that of the real
** geometry, and a fan of triangles round a vertex is a true fan.
**
** The perturbation.  Every query point is moved by one fixed
** infinitesimal displacement delta = (e_x, e_y, e_z), e_x >> e_y >> e_z > 0
** (simulation of simplicity), the same for every query, axis and surface.
** An axis line has a depth axis k and projection axes u < v (the other
** two in lexicographic order: the frame is right-handed for k = 0, 2 and
** left-handed for k = 1, h_k), so delta moves it by (e_u, e_v), which is
** the header's (eps, eps^2); its edge function is the 2-D orientation of
** the trace against the projected edge.  A segment a->b that is not along
** an axis uses d . ((p - a) x (q - a)), d = b - a, for the edge p->q, tied
** by delta . (d x (q - p)).  Consequences:
**   - an edge function is never zero unless the edge is parallel to the
**     line (then every triangle on it is seen edge-on and never hit), so
**     the perturbed line hits exactly one triangle of each fan it passes
**     through, and hit counts are exact winding numbers;
**   - along the line, whether a point x lies before or after a crossing is
**     the rounded depth when x is outside the triangle's extent along k,
**     else the exact side of x against the triangle's plane; a point on
**     the plane goes by the sign of n . delta, the first non-zero
**     component of the exact normal: on the surface, a point counts as
**     inside where the normal's first non-zero component is negative.
**     The unit cube [0,1]^3 is therefore the half-open box [0,1)^3 for
**     every query, on every axis, and the crossings reported on a segment
**     are those of its perturbed copy, so their number always has the
**     parity of the inside states of its ends, even for ends on the
**     surface.
** Each edge function is evaluated once per triangle from the edge's two
** points in canonical order (lower index first) and negated for the
** triangle that runs it the other way, so the floating-point weights used
** for the crossing depth are also shared.  The depth is the barycentric
** combination of the three corners' k coordinates about the corner of
** largest weight: exact when the line passes through that corner or the
** triangle is normal to the line (a face on a grid plane).
**
** Buckets.  For each axis a uniform nu x nv grid over the bounding box's
** projection (about one cell per triangle, shaped like the box) lists the
** triangles whose projected bounding box touches each cell.  The cell of a
** coordinate is a monotone function of it, so a line whose trace lies in a
** triangle's projected box is always in one of the triangle's cells.  The
** total number of entries is capped (16 per triangle) by coarsening.
** A segment not along an axis visits the cells over its projection's box
** on the axis it moves most along, each triangle in the first of its cells
** there.  trisurf_nearest searches the cells of the axis of the thinnest
** extent in growing rings, pruning by each cell's box (its extent along k
** is stored) and each triangle's box; its cost grows with the distance
** from the surface (microseconds at and near it).
*/
#include "trisurf.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

/* min and max without libm's NaN rules: inlined (coordinates are finite
   once prepared). */
static inline double dmin(double a, double b) { return b < a ? b : a; }
static inline double dmax(double a, double b) { return b > a ? b : a; }

struct TriBuckets {
    int k, u, v;          /* depth axis, projection axes (u < v) */
    int nu, nv;
    double lo_u, lo_v, inv_u, inv_v, hu, hv;
    int *start;           /* nu*nv + 1 offsets into item */
    int *item;            /* triangle indices */
    double *klo, *khi;    /* per cell: extent along k of its triangles */
};

void trisurf_init(TriSurf *s) { memset(s, 0, sizeof *s); }

static void buckets_free(TriBuckets *b)
{
    if (!b) return;
    free(b->start);
    free(b->item);
    free(b->klo);
    free(b->khi);
    free(b);
}

static void drop_buckets(TriSurf *s)
{
    for (int a = 0; a < 3; a++) {
        buckets_free(s->bk[a]);
        s->bk[a] = NULL;
    }
}

void trisurf_free(TriSurf *s)
{
    free(s->points);
    free(s->tris);
    free(s->tag);
    for (int i = 0; i < s->nnames; i++) free(s->names[i]);
    free(s->names);
    drop_buckets(s);
    trisurf_init(s);
}

/* ---------------------------------------------------------------- exact */

static inline void two_sum(double a, double b, double *x, double *y)
{
    double s = a + b, bv = s - a, av = s - bv;
    *x = s;
    *y = (a - av) + (b - bv);
}

/* Sign of the exact sum of x[0..n) (n <= 96): grows a non-overlapping
   expansion (Shewchuk's Grow-Expansion with zero elimination); its
   largest component carries the sign. */
static int exact_sign(const double *x, int n)
{
    double h[97];
    int m = 0;
    for (int i = 0; i < n; i++) {
        double q = x[i];
        int k = 0;
        for (int j = 0; j < m; j++) {
            double hh;
            two_sum(q, h[j], &q, &hh);
            if (hh != 0) h[k++] = hh;
        }
        if (q != 0) h[k++] = q;
        m = k;
    }
    return m == 0 ? 0 : (h[m - 1] > 0 ? 1 : -1);
}

/* Appends a*b as two doubles whose sum is exact (fma gives the error). */
static inline int put_prod(double *x, int n, double a, double b)
{
    double p = a * b;
    x[n] = p;
    x[n + 1] = fma(a, b, -p);
    return n + 2;
}

/* Exact sign of (a_u - q_u)(b_v - q_v) - (a_v - q_v)(b_u - q_u). */
static int orient_exact(double au, double av, double bu, double bv, double qu, double qv)
{
    double x[12];
    int n = 0;
    n = put_prod(x, n, au, bv);
    n = put_prod(x, n, -au, qv);
    n = put_prod(x, n, -qu, bv);
    n = put_prod(x, n, -av, bu);
    n = put_prod(x, n, av, qu);
    n = put_prod(x, n, qv, bu);
    return exact_sign(x, n);
}

/* Sign of the orientation of q against the edge a->b (positive: q to the
   left), with its floating-point value in *det. */
static int orient(double au, double av, double bu, double bv, double qu, double qv, double *det)
{
    const double bound = (3.0 + 16.0 * DBL_EPSILON / 2) * DBL_EPSILON / 2;
    double l = (au - qu) * (bv - qv), r = (av - qv) * (bu - qu);
    double d = l - r;
    *det = d;
    if (d > bound * (fabs(l) + fabs(r))) return 1;
    if (-d > bound * (fabs(l) + fabs(r))) return -1;
    return orient_exact(au, av, bu, bv, qu, qv);
}

/* a - b and whether it is exact (Shewchuk's Two-Diff tail is zero). */
static inline int diff_exact(double a, double b, double *d)
{
    double x = a - b, bv = a - x, av = x + bv;
    *d = x;
    return (a - av) + (bv - b) == 0;
}

/* Appends the exact triple product a*b*c (four doubles). */
static inline int put_prod3(double *x, int n, double a, double b, double c)
{
    double p = a * b, e = fma(a, b, -p);
    n = put_prod(x, n, p, c);
    return put_prod(x, n, e, c);
}

/* Appends the terms of sg * det[p; q; r] (rows) as exact triple products. */
static int put_det3(double *x, int n, double sg, const double *p, const double *q, const double *r)
{
    n = put_prod3(x, n, sg * p[0], q[1], r[2]);
    n = put_prod3(x, n, -sg * p[0], q[2], r[1]);
    n = put_prod3(x, n, -sg * p[1], q[0], r[2]);
    n = put_prod3(x, n, sg * p[1], q[2], r[0]);
    n = put_prod3(x, n, sg * p[2], q[0], r[1]);
    return put_prod3(x, n, -sg * p[2], q[1], r[0]);
}

/* Sign of n . (x - a), n = (b - a) x (c - a): positive when x lies on the
   side the triangle a, b, c faces.  Float value with Shewchuk's bound,
   then the exact determinant: from the differences when they are exact
   (coordinates on a common grid: the usual tie), else from the raw
   coordinates, det[b-a; c-a; x-a] = |b c x| - |a c x| + |a b x| - |a b c|. */
static int orient3d(const double *a, const double *b, const double *c, const double *x, double *val)
{
    double u[3], v[3], w[3];
    int exact = 1;
    for (int i = 0; i < 3; i++) {
        exact &= diff_exact(b[i], a[i], &u[i]);
        exact &= diff_exact(c[i], a[i], &v[i]);
        exact &= diff_exact(x[i], a[i], &w[i]);
    }
    double t0 = v[1] * w[2], t1 = v[2] * w[1], t2 = v[2] * w[0], t3 = v[0] * w[2], t4 = v[0] * w[1],
           t5 = v[1] * w[0];
    double det = u[0] * (t0 - t1) + u[1] * (t2 - t3) + u[2] * (t4 - t5);
    double perm = fabs(u[0]) * (fabs(t0) + fabs(t1)) + fabs(u[1]) * (fabs(t2) + fabs(t3)) +
                  fabs(u[2]) * (fabs(t4) + fabs(t5));
    const double bound = (7.0 + 56.0 * DBL_EPSILON / 2) * DBL_EPSILON / 2;
    *val = det;
    if (det > bound * perm) return 1;
    if (-det > bound * perm) return -1;
    double terms[96];
    int n = 0;
    if (exact) {
        n = put_det3(terms, n, 1, u, v, w);
    } else {
        n = put_det3(terms, n, 1, b, c, x);
        n = put_det3(terms, n, -1, a, c, x);
        n = put_det3(terms, n, 1, a, b, x);
        n = put_det3(terms, n, -1, a, b, c);
    }
    return exact_sign(terms, n);
}

/* Exact sign of the component c of the normal of triangle t (the signed
   area of its projection onto the plane of the other two axes, taken in
   cyclic order so that the sign is that of the normal component). */
static int normal_sign(const TriSurf *s, int t, int c)
{
    int u = (c + 1) % 3, v = (c + 2) % 3;
    const double *p0 = s->points + 3 * s->tris[3 * t], *p1 = s->points + 3 * s->tris[3 * t + 1],
                 *p2 = s->points + 3 * s->tris[3 * t + 2];
    double d;
    return orient(p0[u], p0[v], p1[u], p1[v], p2[u], p2[v], &d);
}

/* Sign of n . delta: the first non-zero component of the exact normal. */
static int lex_normal_sign(const TriSurf *s, int t)
{
    for (int c = 0; c < 3; c++) {
        int g = normal_sign(s, t, c);
        if (g) return g;
    }
    return 0;
}

/* ---------------------------------------------------------------- weld */

static uint64_t coord_bits(double x)
{
    uint64_t b;
    if (x == 0) x = 0;   /* -0 and +0 are one position */
    memcpy(&b, &x, sizeof b);
    return b;
}

static uint64_t hash3(const double *p)
{
    uint64_t h = 0x9e3779b97f4a7c15u;
    for (int i = 0; i < 3; i++) {
        h ^= coord_bits(p[i]);
        h *= 0xff51afd7ed558ccdu;
        h ^= h >> 32;
    }
    return h;
}

void trisurf_from_soup(TriSurf *s, const double *xyz, int ntris, const int *tag)
{
    trisurf_init(s);
    if (ntris < 0) ntris = 0;
    size_t nc = 3 * (size_t)ntris, cap = 16;
    while (cap < 2 * nc) cap *= 2;
    int *table = mem_alloc(cap * sizeof *table);
    memset(table, 0xff, cap * sizeof *table);
    s->points = mem_alloc((nc ? nc : 1) * 3 * sizeof *s->points);
    s->tris = mem_alloc((nc ? nc : 1) * sizeof *s->tris);
    int np = 0;
    for (size_t c = 0; c < nc; c++) {
        const double *p = xyz + 3 * c;
        size_t h = (size_t)hash3(p) & (cap - 1);
        for (;;) {
            int q = table[h];
            if (q < 0) {
                memcpy(s->points + 3 * (size_t)np, p, 3 * sizeof *p);
                table[h] = q = np++;
            } else {
                const double *o = s->points + 3 * (size_t)q;
                if (!(o[0] == p[0] && o[1] == p[1] && o[2] == p[2])) {
                    h = (h + 1) & (cap - 1);
                    continue;
                }
            }
            s->tris[c] = q;
            break;
        }
    }
    free(table);
    s->npoints = np;
    s->ntris = ntris;
    s->points = mem_realloc(s->points, (np ? (size_t)np : 1) * 3 * sizeof *s->points);
    if (tag) {
        s->tag = mem_alloc((ntris ? (size_t)ntris : 1) * sizeof *s->tag);
        memcpy(s->tag, tag, (size_t)ntris * sizeof *tag);
    }
}

/* ---------------------------------------------------------------- edges */

/* Edge occurrences grouped by lower point, then by higher point. */
typedef struct Edges {
    int *start;    /* npoints + 1 */
    int *hi;       /* higher point of each occurrence */
    int *slot;     /* 3*tri + side (side m runs tris[m] -> tris[m+1]) */
} Edges;

static void edges_build(const TriSurf *s, Edges *E)
{
    int np = s->npoints, ne = 3 * s->ntris;
    E->start = mem_calloc((size_t)np + 1, sizeof *E->start);
    E->hi = mem_alloc((ne ? (size_t)ne : 1) * sizeof *E->hi);
    E->slot = mem_alloc((ne ? (size_t)ne : 1) * sizeof *E->slot);
    for (int j = 0; j < ne; j++) {
        int a = s->tris[j], b = s->tris[j - j % 3 + (j + 1) % 3];
        E->start[(a < b ? a : b) + 1]++;
    }
    for (int p = 0; p < np; p++) E->start[p + 1] += E->start[p];
    int *fill = mem_alloc(((size_t)np + 1) * sizeof *fill);
    memcpy(fill, E->start, ((size_t)np + 1) * sizeof *fill);
    for (int j = 0; j < ne; j++) {
        int a = s->tris[j], b = s->tris[j - j % 3 + (j + 1) % 3];
        int lo = a < b ? a : b, k = fill[lo]++;
        E->hi[k] = a < b ? b : a;
        E->slot[k] = j;
    }
    free(fill);
    /* insertion sort by higher point within each group (groups are short) */
    for (int p = 0; p < np; p++)
        for (int i = E->start[p] + 1; i < E->start[p + 1]; i++) {
            int h = E->hi[i], sl = E->slot[i], j = i - 1;
            while (j >= E->start[p] && (E->hi[j] > h || (E->hi[j] == h && E->slot[j] > sl))) {
                E->hi[j + 1] = E->hi[j];
                E->slot[j + 1] = E->slot[j];
                j--;
            }
            E->hi[j + 1] = h;
            E->slot[j + 1] = sl;
        }
}

static void edges_free(Edges *E)
{
    free(E->start);
    free(E->hi);
    free(E->slot);
}

/* Direction of occurrence slot j: +1 when it runs lower -> higher point. */
static int slot_dir(const TriSurf *s, int j)
{
    return s->tris[j] < s->tris[j - j % 3 + (j + 1) % 3] ? 1 : -1;
}

static void midpoint(const TriSurf *s, int a, int b, double m[3])
{
    for (int c = 0; c < 3; c++) m[c] = 0.5 * (s->points[3 * a + c] + s->points[3 * b + c]);
}

static int tri_degenerate(const TriSurf *s, int t)
{
    const int *ix = s->tris + 3 * t;
    if (ix[0] == ix[1] || ix[1] == ix[2] || ix[2] == ix[0]) return 1;
    return !normal_sign(s, t, 0) && !normal_sign(s, t, 1) && !normal_sign(s, t, 2);
}

/* Signed volume and area of each component (cid[t], or all triangles as
   component 0 when cid is NULL), about a reference point of the surface
   (less cancellation than about the origin). */
static void surface_integrals(const TriSurf *s, const int *cid, int ncomp, double *vol, double *area)
{
    double r[3] = {0, 0, 0};
    if (s->npoints) memcpy(r, s->points, sizeof r);
    for (int t = 0; t < s->ntris; t++) {
        int c = cid ? cid[t] : 0;
        double p[3][3], n[3];
        for (int m = 0; m < 3; m++)
            for (int q = 0; q < 3; q++) p[m][q] = s->points[3 * (size_t)s->tris[3 * t + m] + q] - r[q];
        n[0] = (p[1][1] - p[0][1]) * (p[2][2] - p[0][2]) - (p[1][2] - p[0][2]) * (p[2][1] - p[0][1]);
        n[1] = (p[1][2] - p[0][2]) * (p[2][0] - p[0][0]) - (p[1][0] - p[0][0]) * (p[2][2] - p[0][2]);
        n[2] = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
        if (vol) vol[c] += p[0][0] * n[0] + p[0][1] * n[1] + p[0][2] * n[2];
        if (area) area[c] += sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 2;
    }
    /* six times the volume is summed, so integer sums stay exact */
    for (int c = 0; c < ncomp && vol; c++) vol[c] /= 6;
}

void trisurf_check(const TriSurf *s, TriTopo *t)
{
    memset(t, 0, sizeof *t);
    Edges E;
    edges_build(s, &E);
    for (int p = 0; p < s->npoints; p++)
        for (int i = E.start[p]; i < E.start[p + 1];) {
            int j = i;
            while (j < E.start[p + 1] && E.hi[j] == E.hi[i]) j++;
            int n = j - i;
            t->nedges++;
            if (n == 1 && t->nopen++ == 0) midpoint(s, p, E.hi[i], t->open_at);
            if (n >= 3 && t->nnonmanifold++ == 0) midpoint(s, p, E.hi[i], t->nonmanifold_at);
            if (n == 2 && slot_dir(s, E.slot[i]) == slot_dir(s, E.slot[i + 1]) && t->nflipped++ == 0)
                midpoint(s, p, E.hi[i], t->flipped_at);
            i = j;
        }
    edges_free(&E);
    for (int k = 0; k < s->ntris; k++)
        if (tri_degenerate(s, k) && t->ndegenerate++ == 0)
            for (int c = 0; c < 3; c++) {
                const int *ix = s->tris + 3 * k;
                t->degenerate_at[c] = (s->points[3 * ix[0] + c] + s->points[3 * ix[1] + c] +
                                       s->points[3 * ix[2] + c]) / 3;
            }
    surface_integrals(s, NULL, 1, &t->volume, &t->area);
}

static void flip_tri(TriSurf *s, int t)
{
    int x = s->tris[3 * t + 1];
    s->tris[3 * t + 1] = s->tris[3 * t + 2];
    s->tris[3 * t + 2] = x;
}

int trisurf_drop_degenerate(TriSurf *s)
{
    int n = 0;
    for (int t = 0; t < s->ntris; t++) {
        if (tri_degenerate(s, t)) continue;
        memmove(s->tris + 3 * n, s->tris + 3 * t, 3 * sizeof *s->tris);
        if (s->tag) s->tag[n] = s->tag[t];
        n++;
    }
    int dropped = s->ntris - n;
    s->ntris = n;
    if (dropped) drop_buckets(s);
    return dropped;
}

void trisurf_transform(TriSurf *s, const double A[9], const double b[3])
{
    for (int i = 0; i < s->npoints; i++) {
        double *p = s->points + 3 * i, q[3];
        for (int r = 0; r < 3; r++) q[r] = A[3 * r] * p[0] + A[3 * r + 1] * p[1] + A[3 * r + 2] * p[2] + b[r];
        memcpy(p, q, sizeof q);
    }
    double det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
                 A[2] * (A[3] * A[7] - A[4] * A[6]);
    if (det < 0)
        for (int t = 0; t < s->ntris; t++) flip_tri(s, t);
    drop_buckets(s);   /* stale: prepare again */
}

/* ---------------------------------------------------------------- lines */

typedef struct Line {
    int k, u, v, h;       /* depth axis, projection axes (u < v), handedness */
    double qu, qv;        /* trace of an axis line in the (u, v) plane */
    const double *a, *b;  /* an oblique segment (NULL for an axis line) */
    double kmin, kmax;    /* only triangles reaching into this depth range */
} Line;

typedef struct Hit {
    double z;             /* depth (coordinate k) of the crossing */
    double zlo, zhi;      /* the triangle's extent along k: holds the crossing */
    int tri;
    int e;                /* +1 when the line leaves the solid there (going +k) */
} Hit;

static void line_axis(Line *L, int k, const double p[3])
{
    L->k = k;
    L->u = k == 0 ? 1 : 0;
    L->v = k == 2 ? 1 : 2;
    L->h = k == 1 ? -1 : 1;
    L->qu = p[L->u];
    L->qv = p[L->v];
    L->a = L->b = NULL;
    L->kmin = -INFINITY;
    L->kmax = INFINITY;
}

/* Sign of the edge function of the edge p -> q (p the lower point) for
   the line: axis lines use the 2-D orientation of the trace against the
   projected edge, tied by the coefficients of e_x >> e_y >> e_z in
   orient(p, q, trace + delta), i.e. (p_v - q_v) for e_u and (q_u - p_u)
   for e_v; an oblique segment a->b uses d . ((p - a) x (q - a)), d = b - a,
   tied by delta . (d x (q - p)).  *val is the floating-point value. */
static int edge_sign(const Line *L, const double *p, const double *q, double *val)
{
    if (!L->a) {
        int u = L->u, v = L->v;
        int g = orient(p[u], p[v], q[u], q[v], L->qu, L->qv, val);
        if (!g) g = (p[v] > q[v]) - (p[v] < q[v]);
        if (!g) g = (q[u] > p[u]) - (q[u] < p[u]);
        return g;
    }
    const double *a = L->a, *b = L->b;
    int g = orient3d(a, p, q, b, val);
    for (int c = 0; c < 3 && !g; c++) {
        /* (b - a)_u (q - p)_v - (b - a)_v (q - p)_u, exactly */
        int u = (c + 1) % 3, v = (c + 2) % 3;
        double x[16];
        int n = 0;
        n = put_prod(x, n, b[u], q[v]);
        n = put_prod(x, n, -b[u], p[v]);
        n = put_prod(x, n, -a[u], q[v]);
        n = put_prod(x, n, a[u], p[v]);
        n = put_prod(x, n, -b[v], q[u]);
        n = put_prod(x, n, b[v], p[u]);
        n = put_prod(x, n, a[v], q[u]);
        n = put_prod(x, n, -a[v], p[u]);
        g = exact_sign(x, n);
    }
    return g;
}

/* Tests triangle t against the perturbed line; fills h on a hit. */
static int tri_hit(const TriSurf *s, const Line *L, int t, Hit *h)
{
    const int *ix = s->tris + 3 * t;
    const double *P[3] = {s->points + 3 * (size_t)ix[0], s->points + 3 * (size_t)ix[1],
                          s->points + 3 * (size_t)ix[2]};
    int k = L->k;
    if ((P[0][k] < L->kmin && P[1][k] < L->kmin && P[2][k] < L->kmin) ||
        (P[0][k] > L->kmax && P[1][k] > L->kmax && P[2][k] > L->kmax))
        return 0;
    double w[3];
    int f = 0;
    for (int m = 0; m < 3; m++) {
        int a = m, b = m == 2 ? 0 : m + 1, sg;
        double det;
        if (ix[a] == ix[b]) return 0;
        int lo = ix[a] < ix[b] ? a : b, hi = a + b - lo;
        sg = edge_sign(L, P[lo], P[hi], &det);
        if (lo != a) {
            sg = -sg;
            det = -det;
        }
        if (!sg || (f && sg != f)) return 0;
        f = sg;
        /* barycentric weight of the opposite corner; a float value of the
           wrong sign (inside the error bound) counts as zero */
        w[m == 0 ? 2 : m - 1] = det * sg > 0 ? det * sg : 0;
    }
    int bse = 0;
    if (w[1] > w[bse]) bse = 1;
    if (w[2] > w[bse]) bse = 2;
    int j = bse == 2 ? 0 : bse + 1, l = j == 2 ? 0 : j + 1;
    double zb = P[bse][k], zj = P[j][k], zl = P[l][k];
    double W = w[0] + w[1] + w[2], z = zb;
    if (W > 0) z = zb + (w[j] * (zj - zb) + w[l] * (zl - zb)) / W;
    double zmin = dmin(zb, dmin(zj, zl)), zmax = dmax(zb, dmax(zj, zl));
    h->z = z < zmin ? zmin : (z > zmax ? zmax : z);
    h->zlo = zmin;
    h->zhi = zmax;
    h->tri = t;
    /* f is the sign of n . (u x v) for an axis line, of n . d for a segment */
    h->e = L->a ? (L->b[k] > L->a[k] ? f : -f) : f * L->h;
    return 1;
}

/* Where the perturbed point x (at depth c on the line) lies against the
   perturbed crossing h: +1 when the crossing is behind it along +k.  Exact:
   the rounded depth only decides when c is outside the triangle's extent;
   inside it the side of x against the triangle's plane does, and a point
   on the plane goes to the side n . delta says. */
static int side(const TriSurf *s, const Hit *h, double c, const double x[3])
{
    if (c < h->zlo) return -1;
    if (c > h->zhi) return 1;
    const int *ix = s->tris + 3 * h->tri;
    double val;
    int g = orient3d(s->points + 3 * (size_t)ix[0], s->points + 3 * (size_t)ix[1],
                     s->points + 3 * (size_t)ix[2], x, &val);
    if (!g) g = lex_normal_sign(s, h->tri);
    return g * h->e;
}

/* ---------------------------------------------------------------- buckets */

static inline int cell_of(double x, double lo, double inv, int n)
{
    double f = (x - lo) * inv;
    if (!(f >= 0)) return 0;
    if (f >= n) return n - 1;
    return (int)f;
}

static void tri_range(const TriSurf *s, const TriBuckets *b, int t, int r[4], double kr[2])
{
    const int *ix = s->tris + 3 * t;
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    kr[0] = INFINITY;
    kr[1] = -INFINITY;
    for (int m = 0; m < 3; m++) {
        const double *p = s->points + 3 * (size_t)ix[m];
        umin = dmin(umin, p[b->u]);
        umax = dmax(umax, p[b->u]);
        vmin = dmin(vmin, p[b->v]);
        vmax = dmax(vmax, p[b->v]);
        kr[0] = dmin(kr[0], p[b->k]);
        kr[1] = dmax(kr[1], p[b->k]);
    }
    r[0] = cell_of(umin, b->lo_u, b->inv_u, b->nu);
    r[1] = cell_of(umax, b->lo_u, b->inv_u, b->nu);
    r[2] = cell_of(vmin, b->lo_v, b->inv_v, b->nv);
    r[3] = cell_of(vmax, b->lo_v, b->inv_v, b->nv);
}

static void grid_shape(TriBuckets *b, const TriSurf *s, double cells)
{
    double Lu = s->hi[b->u] - s->lo[b->u], Lv = s->hi[b->v] - s->lo[b->v];
    double nu = 1, nv = 1;
    if (Lu > 0 && Lv > 0) {
        nu = sqrt(cells * Lu / Lv);
        nv = sqrt(cells * Lv / Lu);
    } else if (Lu > 0)
        nu = cells;
    else if (Lv > 0)
        nv = cells;
    b->nu = nu < 1 ? 1 : (nu > 1 << 20 ? 1 << 20 : (int)nu);
    b->nv = nv < 1 ? 1 : (nv > 1 << 20 ? 1 << 20 : (int)nv);
    b->lo_u = s->lo[b->u];
    b->lo_v = s->lo[b->v];
    b->hu = Lu > 0 ? Lu / b->nu : 1;
    b->hv = Lv > 0 ? Lv / b->nv : 1;
    b->inv_u = Lu > 0 ? b->nu / Lu : 0;
    b->inv_v = Lv > 0 ? b->nv / Lv : 0;
}

static TriBuckets *buckets_build(const TriSurf *s, int k)
{
    TriBuckets *b = MEM_NEW(TriBuckets, 1);
    b->k = k;
    b->u = k == 0 ? 1 : 0;
    b->v = k == 2 ? 1 : 2;
    double cells = s->ntris > 4 ? s->ntris : 4;
    size_t limit = 16 * (size_t)s->ntris + 1024, total;
    for (;;) {
        grid_shape(b, s, cells);
        total = 0;
        for (int t = 0; t < s->ntris; t++) {
            int r[4];
            double kr[2];
            tri_range(s, b, t, r, kr);
            total += (size_t)(r[1] - r[0] + 1) * (size_t)(r[3] - r[2] + 1);
        }
        if (total <= limit || (b->nu == 1 && b->nv == 1)) break;
        cells *= 0.25;   /* big triangles against a fine grid: coarsen */
    }
    size_t nc = (size_t)b->nu * (size_t)b->nv;
    b->start = mem_calloc(nc + 1, sizeof *b->start);
    b->item = mem_alloc((total ? total : 1) * sizeof *b->item);
    b->klo = mem_alloc(nc * sizeof *b->klo);
    b->khi = mem_alloc(nc * sizeof *b->khi);
    for (size_t c = 0; c < nc; c++) {
        b->klo[c] = INFINITY;
        b->khi[c] = -INFINITY;
    }
    for (int t = 0; t < s->ntris; t++) {
        int r[4];
        double kr[2];
        tri_range(s, b, t, r, kr);
        for (int j = r[2]; j <= r[3]; j++)
            for (int i = r[0]; i <= r[1]; i++) {
                size_t c = (size_t)j * (size_t)b->nu + (size_t)i;
                b->start[c + 1]++;
                b->klo[c] = dmin(b->klo[c], kr[0]);
                b->khi[c] = dmax(b->khi[c], kr[1]);
            }
    }
    for (size_t c = 0; c < nc; c++) b->start[c + 1] += b->start[c];
    int *fill = mem_alloc(nc * sizeof *fill);
    memcpy(fill, b->start, nc * sizeof *fill);
    for (int t = 0; t < s->ntris; t++) {
        int r[4];
        double kr[2];
        tri_range(s, b, t, r, kr);
        for (int j = r[2]; j <= r[3]; j++)
            for (int i = r[0]; i <= r[1]; i++) b->item[fill[(size_t)j * (size_t)b->nu + (size_t)i]++] = t;
    }
    free(fill);
    return b;
}

int trisurf_prepare(TriSurf *s, Err *e)
{
    drop_buckets(s);
    if (s->ntris <= 0) return err_set(e, NULL, 0, "surface has no triangles");
    for (int c = 0; c < 3; c++) {
        s->lo[c] = INFINITY;
        s->hi[c] = -INFINITY;
    }
    for (int t = 0; t < 3 * s->ntris; t++) {
        int p = s->tris[t];
        if (p < 0 || p >= s->npoints) return err_set(e, NULL, 0, "triangle %d refers to point %d of %d", t / 3, p, s->npoints);
        for (int c = 0; c < 3; c++) {
            double x = s->points[3 * (size_t)p + c];
            if (!isfinite(x))
                return err_set(e, NULL, 0, "point %d has a non-finite coordinate (triangle %d)", p, t / 3);
            s->lo[c] = dmin(s->lo[c], x);
            s->hi[c] = dmax(s->hi[c], x);
        }
    }
    for (int k = 0; k < 3; k++) s->bk[k] = buckets_build(s, k);
    return 0;
}

/* ---------------------------------------------------------------- queries */

/* Small growable list of hits, on the stack while it fits. */
typedef struct Hits {
    Hit *v, stack[64];
    int n, cap;
} Hits;

static void hits_init(Hits *H)
{
    H->v = H->stack;
    H->n = 0;
    H->cap = 64;
}

static void hits_push(Hits *H, const Hit *h)
{
    if (H->n == H->cap) {
        Hit *nv = mem_alloc(2 * (size_t)H->cap * sizeof *nv);
        memcpy(nv, H->v, (size_t)H->n * sizeof *nv);
        if (H->v != H->stack) free(H->v);
        H->v = nv;
        H->cap *= 2;
    }
    H->v[H->n++] = *h;
}

static void hits_free(Hits *H)
{
    if (H->v != H->stack) free(H->v);
}

static int hit_cmp(const void *a, const void *b)
{
    const Hit *x = a, *y = b;
    if (x->z != y->z) return x->z < y->z ? -1 : 1;
    return (x->tri > y->tri) - (x->tri < y->tri);
}

static void hits_sort(Hits *H)
{
    if (H->n > 24) {
        qsort(H->v, (size_t)H->n, sizeof *H->v, hit_cmp);
        return;
    }
    for (int i = 1; i < H->n; i++) {
        Hit x = H->v[i];
        int j = i - 1;
        while (j >= 0 && hit_cmp(&H->v[j], &x) > 0) {
            H->v[j + 1] = H->v[j];
            j--;
        }
        H->v[j + 1] = x;
    }
}

/* Every hit of the axis line L (buckets of axis L->k). */
static void axis_hits(const TriSurf *s, const Line *L, Hits *H)
{
    const TriBuckets *b = s->bk[L->k];
    if (!b) return;
    if (!(L->qu >= s->lo[L->u] && L->qu <= s->hi[L->u] && L->qv >= s->lo[L->v] && L->qv <= s->hi[L->v]))
        return;
    size_t c = (size_t)cell_of(L->qv, b->lo_v, b->inv_v, b->nv) * (size_t)b->nu +
               (size_t)cell_of(L->qu, b->lo_u, b->inv_u, b->nu);
    for (int i = b->start[c]; i < b->start[c + 1]; i++) {
        Hit h;
        if (tri_hit(s, L, b->item[i], &h)) hits_push(H, &h);
    }
}

/* Winding number of the surface about the perturbed point x: the sum of
   e over the crossings ahead of it on the ray along +x. */
static int winding(const TriSurf *s, const double x[3])
{
    Line L;
    line_axis(&L, 0, x);
    const TriBuckets *b = s->bk[0];
    if (!b || !(L.qu >= s->lo[L.u] && L.qu <= s->hi[L.u] && L.qv >= s->lo[L.v] && L.qv <= s->hi[L.v]))
        return 0;
    size_t c = (size_t)cell_of(L.qv, b->lo_v, b->inv_v, b->nv) * (size_t)b->nu +
               (size_t)cell_of(L.qu, b->lo_u, b->inv_u, b->nu);
    int wind = 0;
    for (int i = b->start[c]; i < b->start[c + 1]; i++) {
        Hit h;
        if (tri_hit(s, &L, b->item[i], &h) && side(s, &h, x[0], x) < 0) wind += h.e;
    }
    return wind;
}

int trisurf_inside(const TriSurf *s, const double x[3]) { return winding(s, x) > 0; }

void trisurf_classify_line(const TriSurf *s, int axis, const double p[3], const double *c, int n, char *in)
{
    Line L;
    line_axis(&L, axis, p);
    Hits H;
    hits_init(&H);
    axis_hits(s, &L, &H);
    hits_sort(&H);
    /* The winding number of a point is the sum of e over the crossings
       ahead of it.  Sorted by rounded depth, the crossings before index j
       (depth < c) are taken as behind; those whose triangle's extent holds
       c, all within `reach` of c in the order, are then settled exactly. */
    int total = 0, behind = 0, j = 0;
    double reach = 0, x[3] = {p[0], p[1], p[2]};
    for (int i = 0; i < H.n; i++) {
        total += H.v[i].e;
        reach = dmax(reach, dmax(H.v[i].z - H.v[i].zlo, H.v[i].zhi - H.v[i].z));
    }
    for (int i = 0; i < n; i++) {
        while (j < H.n && H.v[j].z < c[i]) behind += H.v[j++].e;
        int fix = 0;
        x[axis] = c[i];
        for (int q = j - 1; q >= 0 && H.v[q].z >= c[i] - reach; q--)
            if (c[i] <= H.v[q].zhi && side(s, &H.v[q], c[i], x) < 0) fix -= H.v[q].e;
        for (int q = j; q < H.n && H.v[q].z <= c[i] + reach; q++)
            if (c[i] >= H.v[q].zlo && side(s, &H.v[q], c[i], x) > 0) fix += H.v[q].e;
        in[i] = (char)(total - behind - fix > 0);
    }
    hits_free(&H);
}

/* Hits of an oblique line: the buckets of axis L->k over the box of the
   segment's projection; a triangle listed in several of those cells is
   tested in the first of them only (the corner of the overlap). */
static void oblique_hits(const TriSurf *s, const Line *L, const double a[3], const double b3[3], Hits *H)
{
    const TriBuckets *b = s->bk[L->k];
    if (!b) return;
    double umin = dmin(a[L->u], b3[L->u]), umax = dmax(a[L->u], b3[L->u]);
    double vmin = dmin(a[L->v], b3[L->v]), vmax = dmax(a[L->v], b3[L->v]);
    double kmin = dmin(a[L->k], b3[L->k]), kmax = dmax(a[L->k], b3[L->k]);
    if (umax < s->lo[L->u] || umin > s->hi[L->u] || vmax < s->lo[L->v] || vmin > s->hi[L->v] ||
        kmax < s->lo[L->k] || kmin > s->hi[L->k])
        return;
    int i0 = cell_of(umin, b->lo_u, b->inv_u, b->nu), i1 = cell_of(umax, b->lo_u, b->inv_u, b->nu);
    int j0 = cell_of(vmin, b->lo_v, b->inv_v, b->nv), j1 = cell_of(vmax, b->lo_v, b->inv_v, b->nv);
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) {
            size_t c = (size_t)j * (size_t)b->nu + (size_t)i;
            if (b->klo[c] > kmax || b->khi[c] < kmin) continue;
            for (int q = b->start[c]; q < b->start[c + 1]; q++) {
                int t = b->item[q], r[4];
                double kr[2];
                tri_range(s, b, t, r, kr);
                if ((r[0] > i0 ? r[0] : i0) != i || (r[2] > j0 ? r[2] : j0) != j) continue;
                if (kr[0] > kmax || kr[1] < kmin) continue;
                Hit h;
                if (tri_hit(s, L, t, &h)) hits_push(H, &h);
            }
        }
}

/* Keeps, of the crossings between the ends of a segment from a (H sorted
   by depth; dir = +1 when the segment runs along +k), those where the
   solid state changes: the winding number, starting from that about a,
   goes from <= 0 to > 0 or back.  Crossings at one depth count together
   (shells touching face to face, overlapping shells sharing a face); the
   one kept is the first of them that moves w the way the group does, so
   its triangle's normal is the boundary's.  Leaves them in H->v[0..m) in
   the order met along the segment and returns m. */
static int solid_changes(const TriSurf *s, Hits *H, const double a[3], int dir)
{
    int n = H->n, m = 0, w = winding(s, a);
    if (dir < 0)
        for (int i = 0; i < n / 2; i++) {
            Hit x = H->v[i];
            H->v[i] = H->v[n - 1 - i];
            H->v[n - 1 - i] = x;
        }
    /* passing a crossing along +k lowers w by e (e = +1 leaves the solid) */
    for (int i = 0; i < n;) {
        int j = i, dw = 0;
        while (j < n && H->v[j].z == H->v[i].z) dw -= dir * H->v[j++].e;
        if ((w > 0) != (w + dw > 0)) {
            int q = i;
            while (q < j - 1 && -dir * H->v[q].e * dw <= 0) q++;
            H->v[m++] = H->v[q];
        }
        w += dw;
        i = j;
    }
    return m;
}

int trisurf_crossings(const TriSurf *s, const double a[3], const double b[3], double *t, int *tri, int max)
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    int k = 0, naxes = 0;
    for (int c = 0; c < 3; c++) {
        if (d[c] != 0) naxes++;
        if (fabs(d[c]) > fabs(d[k])) k = c;
    }
    if (naxes == 0) return 0;
    Line L;
    line_axis(&L, k, a);
    L.kmin = dmin(a[k], b[k]);
    L.kmax = dmax(a[k], b[k]);
    Hits H;
    hits_init(&H);
    if (naxes == 1) {
        axis_hits(s, &L, &H);
    } else {
        L.a = a;
        L.b = b;
        oblique_hits(s, &L, a, b, &H);
    }
    /* keep the crossings between the perturbed ends, in order along a->b */
    int n = 0;
    for (int i = 0; i < H.n; i++) {
        int sa = side(s, &H.v[i], a[k], a), sb = side(s, &H.v[i], b[k], b);
        if (sa != sb) H.v[n++] = H.v[i];
    }
    H.n = n;
    hits_sort(&H);
    int m = n ? solid_changes(s, &H, a, d[k] > 0 ? 1 : -1) : 0;
    for (int i = 0; i < m && i < max; i++) {
        double tt = (H.v[i].z - a[k]) / d[k];
        t[i] = tt < 0 ? 0 : (tt > 1 ? 1 : tt);
        if (tri) tri[i] = H.v[i].tri;
    }
    hits_free(&H);
    return m;
}

/* ---------------------------------------------------------------- orient */

/* Labels the components (cid) and the per-triangle flips (fl) that make
   each consistent; returns the number of components. */
static int flood(const TriSurf *s, int *cid, char *fl)
{
    Edges E;
    edges_build(s, &E);
    int nt = s->ntris;
    int *nb = mem_alloc((3 * (size_t)nt + 1) * sizeof *nb);
    for (int j = 0; j < 3 * nt; j++) nb[j] = -1;
    for (int p = 0; p < s->npoints; p++)
        for (int i = E.start[p]; i < E.start[p + 1];) {
            int j = i;
            while (j < E.start[p + 1] && E.hi[j] == E.hi[i]) j++;
            if (j - i == 2) {
                nb[E.slot[i]] = E.slot[i + 1];
                nb[E.slot[i + 1]] = E.slot[i];
            }
            i = j;
        }
    edges_free(&E);
    for (int t = 0; t < nt; t++) cid[t] = -1;
    int *queue = mem_alloc(((size_t)nt + 1) * sizeof *queue), ncomp = 0;
    for (int seed = 0; seed < nt; seed++) {
        if (cid[seed] >= 0) continue;
        int head = 0, tail = 0;
        cid[seed] = ncomp;
        fl[seed] = 0;
        queue[tail++] = seed;
        while (head < tail) {
            int t = queue[head++];
            for (int m = 0; m < 3; m++) {
                int o = nb[3 * t + m];
                if (o < 0 || cid[o / 3] >= 0) continue;
                /* same direction of travel means one of the two must turn */
                int same = slot_dir(s, 3 * t + m) == slot_dir(s, o);
                cid[o / 3] = ncomp;
                fl[o / 3] = (char)(fl[t] ^ same);
                queue[tail++] = o / 3;
            }
        }
        ncomp++;
    }
    free(queue);
    free(nb);
    return ncomp;
}

/* The components and the index the nesting tests need: per component its
   triangles (start/list), bounding box and signed volume; the line
   buckets along x of the whole surface (its own when prepared, else built
   here), so that one ray from a point gives the winding number of every
   component about it; and scratch arrays for per-component sums. */
typedef struct Comps {
    int n;
    const int *cid;
    int *start, *list;
    double *box, *vol;
    TriSurf view;          /* s with a bounding box, for the buckets */
    const TriBuckets *bx;  /* NULL: no index (one component, non-finite points) */
    TriBuckets *own;
    int *w, *stamp, *touched, ntouched, ray;
    int *cand, *mark;      /* candidate containers; per point: last component visited */
    char *is_cand;
} Comps;

static void comps_build(const TriSurf *s, const int *cid, int ncomp, Comps *C)
{
    int nt = s->ntris;
    memset(C, 0, sizeof *C);
    C->n = ncomp;
    C->cid = cid;
    C->box = mem_alloc(6 * (size_t)ncomp * sizeof *C->box);
    C->vol = mem_calloc((size_t)ncomp, sizeof *C->vol);
    C->start = mem_calloc((size_t)ncomp + 1, sizeof *C->start);
    C->list = mem_alloc(((size_t)nt + 1) * sizeof *C->list);
    for (int c = 0; c < 6 * ncomp; c++) C->box[c] = c % 6 < 3 ? INFINITY : -INFINITY;
    for (int t = 0; t < nt; t++) {
        int c = cid[t];
        C->start[c + 1]++;
        double *B = C->box + 6 * c;
        for (int m = 0; m < 3; m++)
            for (int q = 0; q < 3; q++) {
                double x = s->points[3 * (size_t)s->tris[3 * t + m] + q];
                B[q] = dmin(B[q], x);
                B[3 + q] = dmax(B[3 + q], x);
            }
    }
    for (int c = 0; c < ncomp; c++) C->start[c + 1] += C->start[c];
    int *fill = mem_alloc(((size_t)ncomp + 1) * sizeof *fill);
    memcpy(fill, C->start, ((size_t)ncomp + 1) * sizeof *fill);
    for (int t = 0; t < nt; t++) C->list[fill[cid[t]]++] = t;
    free(fill);
    surface_integrals(s, cid, ncomp, C->vol, NULL);
}

/* Sets up the rays: only with two components or more and finite points
   (a surface with NaNs is refused by trisurf_prepare anyway). */
static void comps_index(const TriSurf *s, Comps *C)
{
    if (C->n < 2) return;
    C->view = *s;
    for (int c = 0; c < 3; c++) {
        C->view.lo[c] = INFINITY;
        C->view.hi[c] = -INFINITY;
    }
    for (int i = 0; i < C->n; i++)
        for (int c = 0; c < 3; c++) {
            C->view.lo[c] = dmin(C->view.lo[c], C->box[6 * i + c]);
            C->view.hi[c] = dmax(C->view.hi[c], C->box[6 * i + 3 + c]);
        }
    for (int c = 0; c < 3; c++)
        if (!isfinite(C->view.lo[c]) || !isfinite(C->view.hi[c])) return;
    for (int p = 0; p < 3 * s->npoints; p++)
        if (!isfinite(s->points[p])) return;
    C->bx = s->bk[0];
    if (!C->bx) C->bx = C->own = buckets_build(&C->view, 0);
    size_t n = (size_t)C->n;
    C->w = mem_calloc(n, sizeof *C->w);
    C->stamp = mem_calloc(n, sizeof *C->stamp);
    C->touched = mem_alloc(n * sizeof *C->touched);
    C->cand = mem_alloc(n * sizeof *C->cand);
    C->is_cand = mem_calloc(n, 1);
    C->mark = mem_alloc(((size_t)s->npoints + 1) * sizeof *C->mark);
    for (int p = 0; p < s->npoints; p++) C->mark[p] = -1;
}

static void comps_free(Comps *C)
{
    free(C->box);
    free(C->vol);
    free(C->start);
    free(C->list);
    buckets_free(C->own);
    free(C->w);
    free(C->stamp);
    free(C->touched);
    free(C->cand);
    free(C->is_cand);
    free(C->mark);
}

/* Whether box O holds box B (two corners of boxes: lo[3], hi[3]). */
static int box_holds(const double *O, const double *B)
{
    return O[0] <= B[0] && O[1] <= B[1] && O[2] <= B[2] && O[3] >= B[3] && O[4] >= B[4] && O[5] >= B[5];
}

/* One ray along +x from the perturbed point x: adds the winding number
   about x of each component but `self` whose bounding box holds the box
   `in` (of the candidates only, when `only`) to C->w, listing the
   components met in C->touched, and returns the sum.  A closed
   component's winding number is zero outside its box, so the box test
   spares most triangle tests (in a lattice of parts every ray runs along
   its neighbours' edges).  The caller clears C->w of the touched
   components. */
static int comps_ray(const TriSurf *s, Comps *C, int self, int only, const double in[6], const double x[3])
{
    const TriBuckets *b = C->bx;
    Line L;
    line_axis(&L, 0, x);
    size_t c = (size_t)cell_of(L.qv, b->lo_v, b->inv_v, b->nv) * (size_t)b->nu +
               (size_t)cell_of(L.qu, b->lo_u, b->inv_u, b->nu);
    int total = 0;
    C->ntouched = 0;
    C->ray++;
    for (int i = b->start[c]; i < b->start[c + 1]; i++) {
        int t = b->item[i], o = C->cid[t];
        if (o == self || (only ? !C->is_cand[o] : !box_holds(C->box + 6 * o, in))) continue;
        Hit h;
        if (!tri_hit(s, &L, t, &h) || side(s, &h, x[0], x) >= 0) continue;
        if (C->stamp[o] != C->ray) {
            C->stamp[o] = C->ray;
            C->touched[C->ntouched++] = o;
        }
        C->w[o] += h.e;
        total += h.e;
    }
    return total;
}

static void comps_clear(Comps *C)
{
    for (int i = 0; i < C->ntouched; i++) C->w[C->touched[i]] = 0;
}

/* The next point of component c not yet visited (its triangles' corners
   in order; *pos is the position in them), or NULL when all are done. */
static const double *comps_next_point(const TriSurf *s, Comps *C, int c, int *pos)
{
    for (; *pos < 3 * (C->start[c + 1] - C->start[c]); ++*pos) {
        int p = s->tris[3 * C->list[C->start[c] + *pos / 3] + *pos % 3];
        if (C->mark[p] == c) continue;
        C->mark[p] = c;
        return s->points + 3 * (size_t)p;
    }
    return NULL;
}

/* Whether component c's orientation as given makes sense with the others
   as given: W, the winding number of all the others, is > 0 where they
   are solid.  A component with positive volume adds solid: it must reach
   outside the others' solid (W <= 0 at one of its points at least, else
   it adds nothing: an outward shell inside another is taken for a cavity
   written the wrong way round).  One with negative volume removes solid:
   it must lie inside the others' solid (W > 0 at all its points). */
static int comps_consistent(const TriSurf *s, Comps *C, int c)
{
    int adds = !(C->vol[c] < 0), pos = 0;
    if (!C->bx) return adds;
    for (const double *x; (x = comps_next_point(s, C, c, &pos));) {
        double at[6] = {x[0], x[1], x[2], x[0], x[1], x[2]};
        int W = comps_ray(s, C, c, 0, at, x);
        comps_clear(C);
        if (W <= 0) return adds;
    }
    return !adds;
}

/* Number of other components whose solid holds the whole of component c:
   those with a non-zero winding number about every point of c (its
   bounding box inside theirs).  The first point's ray gives the
   candidates, each further point's ray drops those it is outside of, so a
   component inside nothing costs one ray. */
static int comps_depth(const TriSurf *s, Comps *C, int c)
{
    if (!C->bx) return 0;
    int pos = 0, ncand = 0;
    const double *x = comps_next_point(s, C, c, &pos), *B = C->box + 6 * c;
    if (!x) return 0;
    comps_ray(s, C, c, 0, B, x);
    for (int i = 0; i < C->ntouched; i++) {
        int o = C->touched[i];
        if (C->w[o] != 0) {
            C->cand[ncand++] = o;
            C->is_cand[o] = 1;
        }
    }
    comps_clear(C);
    while (ncand > 0 && (x = comps_next_point(s, C, c, &pos))) {
        comps_ray(s, C, c, 1, B, x);
        int k = 0;
        for (int i = 0; i < ncand; i++) {
            int o = C->cand[i];
            if (C->w[o] != 0) C->cand[k++] = o;
            else C->is_cand[o] = 0;
        }
        ncand = k;
        comps_clear(C);
    }
    for (int i = 0; i < ncand; i++) C->is_cand[C->cand[i]] = 0;
    return ncand;
}

int trisurf_orient(TriSurf *s)
{
    int nt = s->ntris;
    if (nt == 0) return 0;
    int *cid = mem_alloc((size_t)nt * sizeof *cid);
    char *fl = mem_alloc((size_t)nt);
    int ncomp = flood(s, cid, fl), repair = 0;
    for (int t = 0; t < nt; t++)
        if (fl[t]) {
            flip_tri(s, t);
            repair = 1;   /* triangles that disagree: the given orientation is not trusted */
        }
    Comps C;
    comps_build(s, cid, ncomp, &C);
    comps_index(s, &C);
    for (int c = 0; c < ncomp && !repair; c++) repair = !comps_consistent(s, &C, c);
    /* repaired: outward (positive volume) at even nesting depth, inward
       (a cavity) at odd depth */
    char *turn = mem_calloc((size_t)ncomp, 1);
    for (int p = 0; C.mark && p < s->npoints; p++) C.mark[p] = -1;   /* every point unvisited again */
    for (int c = 0; c < ncomp && repair; c++) {
        int want = comps_depth(s, &C, c) % 2 ? -1 : 1;
        turn[c] = (char)(C.vol[c] * want < 0);
    }
    int flipped = 0;
    for (int t = 0; t < nt; t++) {
        if (turn[cid[t]]) flip_tri(s, t);
        flipped += fl[t] ^ turn[cid[t]];
    }
    free(turn);
    comps_free(&C);
    free(fl);
    free(cid);
    return flipped;   /* buckets, if any, stay valid: they ignore corner order */
}

/* ---------------------------------------------------------------- nearest */

/* Distance from x to triangle t (closest point by Voronoi regions,
   Ericson, Real-Time Collision Detection, 5.1.5). */
static double tri_distance(const TriSurf *s, int t, const double x[3])
{
    const double *a = s->points + 3 * (size_t)s->tris[3 * t], *b = s->points + 3 * (size_t)s->tris[3 * t + 1],
                 *c = s->points + 3 * (size_t)s->tris[3 * t + 2];
    double ab[3], ac[3], ap[3], q[3];
    for (int i = 0; i < 3; i++) {
        ab[i] = b[i] - a[i];
        ac[i] = c[i] - a[i];
        ap[i] = x[i] - a[i];
    }
#define DOT(p, r) ((p)[0] * (r)[0] + (p)[1] * (r)[1] + (p)[2] * (r)[2])
    double d1 = DOT(ab, ap), d2 = DOT(ac, ap);
    double bp[3] = {x[0] - b[0], x[1] - b[1], x[2] - b[2]}, cp[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    double d3 = DOT(ab, bp), d4 = DOT(ac, bp), d5 = DOT(ab, cp), d6 = DOT(ac, cp);
#undef DOT
    double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    double u = 0, w = 0;   /* q = a + u ab + w ac */
    if (d1 <= 0 && d2 <= 0) {
    } else if (d3 >= 0 && d4 <= d3) {
        u = 1;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        u = d1 / (d1 - d3);
    } else if (d6 >= 0 && d5 <= d6) {
        w = 1;
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        w = d2 / (d2 - d6);
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        double g = (d4 - d3) / ((d4 - d3) + (d5 - d6));   /* on bc */
        u = 1 - g;
        w = g;
    } else {
        double den = va + vb + vc;
        if (den > 0) {
            u = vb / den;
            w = vc / den;
        }
    }
    for (int i = 0; i < 3; i++) q[i] = a[i] + u * ab[i] + w * ac[i] - x[i];
    return sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
}

static double gap(double x, double lo, double hi) { return x < lo ? lo - x : (x > hi ? x - hi : 0); }

/* Squared distance from x to triangle t's bounding box. */
static double box_gap2(const TriSurf *s, int t, const double x[3])
{
    const int *ix = s->tris + 3 * t;
    const double *a = s->points + 3 * (size_t)ix[0], *b = s->points + 3 * (size_t)ix[1],
                 *c = s->points + 3 * (size_t)ix[2];
    double g2 = 0;
    for (int q = 0; q < 3; q++) {
        double g = gap(x[q], dmin(a[q], dmin(b[q], c[q])), dmax(a[q], dmax(b[q], c[q])));
        g2 += g * g;
    }
    return g2;
}

typedef struct Near {
    const TriSurf *s;
    const TriBuckets *b;
    const double *x;
    double best;
    int tri;
} Near;

/* Tests the triangles of cell (i, j) unless its box is farther than the
   best distance so far (a cell's box holds the closest point of every
   triangle whose closest point projects into it). */
static void near_cell(Near *N, int i, int j)
{
    const TriBuckets *b = N->b;
    if (i < 0 || j < 0 || i >= b->nu || j >= b->nv) return;
    size_t c = (size_t)j * (size_t)b->nu + (size_t)i;
    if (b->start[c] == b->start[c + 1]) return;
    double gu = gap(N->x[b->u], b->lo_u + i * b->hu, b->lo_u + (i + 1) * b->hu);
    double gv = gap(N->x[b->v], b->lo_v + j * b->hv, b->lo_v + (j + 1) * b->hv);
    double gk = gap(N->x[b->k], b->klo[c], b->khi[c]);
    if (gu * gu + gv * gv + gk * gk > N->best * N->best) return;
    for (int q = b->start[c]; q < b->start[c + 1]; q++) {
        int t = b->item[q];
        if (box_gap2(N->s, t, N->x) > N->best * N->best) continue;
        double d = tri_distance(N->s, t, N->x);
        if (d < N->best || (d == N->best && t < N->tri)) {
            N->best = d;
            N->tri = t;
        }
    }
}

int trisurf_nearest(const TriSurf *s, const double x[3], double *dist)
{
    int k = 0;   /* the axis of the thinnest extent: tightest cell boxes */
    for (int c = 1; c < 3; c++)
        if (s->hi[c] - s->lo[c] < s->hi[k] - s->lo[k]) k = c;
    Near N = {s, s->bk[k], x, INFINITY, -1};
    const TriBuckets *b = N.b;
    if (b) {
        int ci = cell_of(x[b->u], b->lo_u, b->inv_u, b->nu), cj = cell_of(x[b->v], b->lo_v, b->inv_v, b->nv);
        for (int r = 0;; r++) {
            int i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
            for (int i = i0; i <= i1; i++) {
                near_cell(&N, i, j0);
                if (j1 != j0) near_cell(&N, i, j1);
            }
            for (int j = j0 + 1; j < j1; j++) {
                near_cell(&N, i0, j);
                if (i1 != i0) near_cell(&N, i1, j);
            }
            /* every cell outside the rings so far is at least this far */
            double lb = INFINITY;
            if (i0 > 0) lb = dmin(lb, x[b->u] - (b->lo_u + i0 * b->hu));
            if (i1 < b->nu - 1) lb = dmin(lb, b->lo_u + (i1 + 1) * b->hu - x[b->u]);
            if (j0 > 0) lb = dmin(lb, x[b->v] - (b->lo_v + j0 * b->hv));
            if (j1 < b->nv - 1) lb = dmin(lb, b->lo_v + (j1 + 1) * b->hv - x[b->v]);
            if (lb == INFINITY || N.best <= lb) break;
        }
    }
    if (dist) *dist = N.best;
    return N.tri;
}

void trisurf_normal(const TriSurf *s, int i, double n[3])
{
    const double *a = s->points + 3 * (size_t)s->tris[3 * i], *b = s->points + 3 * (size_t)s->tris[3 * i + 1],
                 *c = s->points + 3 * (size_t)s->tris[3 * i + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int q = 0; q < 3; q++) n[q] = l > 0 ? n[q] / l : 0;
}
