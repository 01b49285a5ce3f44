/*
** voronoi.c: bounded Voronoi grids (voronoi.h).
**
** Design, in two passes.
**
** Pass 1, one kept seed at a time: the cell starts as the box (3-D: a
** convex polyhedron held as a vertex array and polygons of vertex indices,
** each polygon labelled with the seed across it, or -1 - side for a box
** side; 2-D: a convex polygon in the plane normal to flat_axis whose edges
** carry those labels) and is clipped by the bisector half-space of each
** seed that can still reach it.  Candidates come from a bucket grid over
** the box, shell by shell (buckets at Chebyshev index distance k), nearest
** first inside a shell; a seed at distance d can cut the cell only when
** d/2 < R, R the largest distance from the seed to a cell vertex, so the
** search ends when the nearest unvisited shell is farther than 2R.  On a
** Cartesian lattice that is the 26 (2-D: 8) lattice neighbours.
**
** Clipping classifies each vertex as in, on (within EPS_CLIP x box size
** of the plane) or out; nothing happens unless a vertex is out, new
** vertices are made only on edges from an in to an out vertex (once per
** edge, parametrised from the in end, so the two polygons sharing the
** edge get the same point), and the new face is every on or new vertex,
** sorted by angle about the plane normal.  So a plane that only touches
** the cell (the diagonal neighbours of a lattice) adds nothing, and each
** cell is a closed polyhedron: every edge is used by exactly two of its
** polygons.
**
** Each cell's vertices are then welded into the global point list.  A
** vertex on exactly 3 faces (2-D: 2 edges) is named by the sorted set of
** its seeds and box sides, the set every cell around it sees; the first
** cell to meet a name welds it by position, later cells get the same point
** by name, so welding stays consistent where positions are ill-conditioned
** (nearly cospherical seeds).  Welding by position: a point closer than
** VORONOI_MERGE x (box size) to an earlier one is that one (the nearest;
** an exact copy of an earlier query always gets the earlier answer).  The
** cell is stored as polygons of global point numbers, sorted by label.
** 2-D: the cell is stored as its polygon only (global points of the
** plane at lo, edge labels), and a vertex's name {i, a, b} is looked up
** in the polygons of the kept seeds among a and b made before i instead
** of a table of names: the same answer, without touching memory for every
** vertex (fresh memory is what big grids spend their time on).
**
** Pass 2: the face between kept seeds i < j is the polygon cell i stored;
** cell j uses its reverse, so the two cells see exactly the same points.
** 3-D faces of area below VORONOI_MERGE^2 x (box size)^2 whose points lie
** within a few merge distances of each other collapse to one point (a
** union of their points), so their neighbours in all cells lose the same
** points; thin faces longer than that stay (collapsing them would move
** far-apart points, dropping them alone would open the cells).  Repeated
** consecutive points are removed and faces left with fewer than 3 points
** dropped (nfaces_dropped).  Every cell is then checked to be closed (each
** edge used once in each direction).  A sliver that only one of the cells
** around an edge resolved, and that welding reduced to a segment, leaves a
** point inside that edge in some polygons and not in others (a
** T-junction); such points are inserted into the stored polygons that
** lack them, and the cells sharing a changed polygon are checked again.  A
** cell still open is an error naming its seed, never a silently broken
** grid.  The faces are then written straight into the Mesh, already in
** OpenFOAM's order (write_direct; meshbuild only when they are not).
** 2-D: a prism is closed by construction, so when no polygon lost a point
** to welding and every edge between kept cells is the reverse of the
** neighbour's (rings_regular, the usual case), the steps above change
** nothing and the prisms are written straight from the polygons
** (write_rings: side quads, back and front faces, point 2p at lo and
** 2p+1 at hi); otherwise the polygons become prisms in the store and go
** through the steps above, so the mesh is the same either way.
** Consequence of merging: face points lie on their bisector to round-off
** (1e-13 of the box) except near merged points, where they may be off by
** up to the merge distance.
**
** Invariants: cell c is the c-th kept seed; a face's label is the seed
** across it, so faces towards dropped seeds go to that seed's patch and
** box faces to side_patch; 2-D cells are prisms between lo and hi along
** flat_axis, their front and back faces on the side patches of that axis.
*/
#include "voronoi.h"
#include "mem.h"
#include "meshbuild.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* on-plane tolerance of the clipper, x box size: far above round-off of
   the vertex coordinates, far below the weld distance */
#define EPS_CLIP 1e-13
/* slack on the reach test d/2 < R */
#define REACH_SLACK (1.0 + 1e-9)

/* Grows *p (of *cap elements of size elem) to hold need elements. */
static void need(void *p, int *cap, size_t need_n, size_t elem)
{
    if (need_n <= (size_t)*cap) return;
    size_t c = *cap > 0 ? (size_t)*cap : 16;
    while (c < need_n) c += c / 2 + 16;
    *(void **)p = mem_realloc(*(void **)p, c * elem);
    *cap = (int)c;
}

static double sq(double x) { return x * x; }

/* ---- bucket grid ---------------------------------------------------- */

/* Seeds sorted into a uniform grid over the box; seeds outside the box go
   to the border buckets, which only puts them in a shell nearer than they
   are, so the search stays exact. */
typedef struct Buckets {
    int n[3];
    double org[3], h[3];
    int *start;   /* nbuckets+1 */
    int *seed;    /* nseeds, bucket by bucket, in seed order */
} Buckets;

static int bucket_axis(const Buckets *g, int a, double x)
{
    double t = (x - g->org[a]) / g->h[a];
    if (!(t > 0)) return 0;
    if (t >= g->n[a]) return g->n[a] - 1;
    return (int)t;
}

static int bucket_of(const Buckets *g, const double x[3])
{
    int b[3];
    for (int a = 0; a < 3; a++) b[a] = bucket_axis(g, a, x[a]);
    return b[0] + g->n[0] * (b[1] + g->n[1] * b[2]);
}

static void buckets_build(Buckets *g, const VoronoiInput *in)
{
    int dims = in->flat_axis >= 0 ? 2 : 3;
    double vol = 1;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis) vol *= in->hi[a] - in->lo[a];
    /* about one seed per bucket */
    double h = pow(vol / in->nseeds, 1.0 / dims);
    size_t total = 1;
    for (int a = 0; a < 3; a++) {
        double ext = in->hi[a] - in->lo[a];
        double n = a == in->flat_axis ? 1 : floor(ext / h + 0.5);
        if (n < 1) n = 1;
        if (n > 1 << 20) n = 1 << 20;
        g->n[a] = (int)n;
        g->org[a] = in->lo[a];
        g->h[a] = ext / n;
        total *= (size_t)g->n[a];
    }
    /* a box much longer than wide can round to many more buckets than
       seeds; halve the finest axis until the count is sane */
    while (total > 4 * (size_t)in->nseeds + 64) {
        int a = -1;
        for (int k = 0; k < 3; k++)
            if (g->n[k] > 1 && (a < 0 || g->n[k] > g->n[a])) a = k;
        total /= (size_t)g->n[a];
        g->n[a] = (g->n[a] + 1) / 2;
        g->h[a] = (in->hi[a] - in->lo[a]) / g->n[a];
        total *= (size_t)g->n[a];
    }
    g->start = mem_calloc(total + 1, sizeof(int));
    g->seed = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    /* counting sort in place (no scratch arrays: fresh memory is dear):
       start[b + 1] is first the end of bucket b, then, filled from the
       last seed down, its beginning, which moves to start[b] */
    for (int i = 0; i < in->nseeds; i++) {
        double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
        if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
        g->start[bucket_of(g, x) + 1]++;
    }
    for (size_t b = 0; b < total; b++) g->start[b + 1] += g->start[b];
    for (int i = in->nseeds - 1; i >= 0; i--) {
        double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
        if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
        g->seed[--g->start[bucket_of(g, x) + 1]] = i;
    }
    memmove(g->start, g->start + 1, sizeof(int) * total);
    g->start[total] = in->nseeds;
}

static void buckets_free(Buckets *g)
{
    free(g->start);
    free(g->seed);
}

/* Distance from x (in bucket b) to the nearest point of the buckets at
   index distance >= k from b; INFINITY when there are none. */
static double shell_dist(const Buckets *g, const int b[3], int k, const double x[3])
{
    double d = INFINITY;
    for (int a = 0; a < 3; a++) {
        if (b[a] - k >= 0) {
            double t = x[a] - (g->org[a] + (b[a] - k + 1) * g->h[a]);
            if (t < d) d = t;
        }
        if (b[a] + k < g->n[a]) {
            double t = g->org[a] + (b[a] + k) * g->h[a] - x[a];
            if (t < d) d = t;
        }
    }
    return d;
}

typedef struct Cand {
    double d2;
    int j;
} Cand;

/* The neighbour search of one seed; the clipper reads cand[0..n). */
typedef struct Search {
    Cand *cand;
    int n, cap;
} Search;

/* Squared distance along axis a from x to bucket column ia; border
   buckets reach to infinity (seeds outside the box are in them). */
static double bucket_gap2(const Buckets *g, int a, int ia, double x)
{
    double lo = g->org[a] + ia * g->h[a], hi = lo + g->h[a];
    if (ia > 0 && x < lo) return sq(lo - x);
    if (ia < g->n[a] - 1 && x > hi) return sq(x - hi);
    return 0;
}

/* Appends the seeds of the buckets of shell k around b (except self)
   closer than sqrt(r2max), sorted by distance.  Rows and buckets wholly
   farther than that are skipped unread: on a lattice shell 2 is searched
   (its nearest side is nearer than the cell's reach) but holds nothing in
   reach. */
static void shell_collect(Search *s, const Buckets *g, const VoronoiInput *in, int self, const int b[3],
                          int k, const double x[3], double r2max)
{
    s->n = 0;
    int flat = in->flat_axis;
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = b[a] - k < 0 ? 0 : b[a] - k;
        hi[a] = b[a] + k >= g->n[a] ? g->n[a] - 1 : b[a] + k;
    }
    for (int iz = lo[2]; iz <= hi[2]; iz++) {
        double gz = flat == 2 ? 0 : bucket_gap2(g, 2, iz, x[2]);
        if (gz > r2max) continue;
        for (int iy = lo[1]; iy <= hi[1]; iy++) {
            double gyz = gz + (flat == 1 ? 0 : bucket_gap2(g, 1, iy, x[1]));
            if (gyz > r2max) continue;
            int edge = abs(iz - b[2]) == k || abs(iy - b[1]) == k;
            int step = edge || k == 0 ? 1 : 2 * k;
            for (int ix = b[0] - k; ix <= b[0] + k; ix += step) {
                if (ix < 0 || ix >= g->n[0]) continue;
                if (gyz + (flat == 0 ? 0 : bucket_gap2(g, 0, ix, x[0])) > r2max) continue;
                int bk = ix + g->n[0] * (iy + g->n[1] * iz);
                for (int q = g->start[bk]; q < g->start[bk + 1]; q++) {
                    int j = g->seed[q];
                    if (j == self) continue;
                    const double *y = in->x + 3 * j;
                    double d2 = 0;
                    for (int a = 0; a < 3; a++)
                        if (a != flat) d2 += sq(y[a] - x[a]);
                    if (d2 > r2max) continue;
                    if (s->n >= s->cap) need(&s->cand, &s->cap, (size_t)s->n + 1, sizeof(Cand));
                    int p = s->n++;
                    while (p > 0 && s->cand[p - 1].d2 > d2) {
                        s->cand[p] = s->cand[p - 1];
                        p--;
                    }
                    s->cand[p] = (Cand){d2, j};
                }
            }
        }
    }
}

/* ---- 3-D clipper ---------------------------------------------------- */

typedef struct Poly {
    int nv, nf, ni;
    int vcap, fcap, ocap, icap;
    double *v;    /* 3*nv */
    int *lab;     /* nf: seed across the face, or -1 - side */
    int *off;     /* nf+1 */
    int *idx;
} Poly;

typedef struct Clip {
    Poly p[2];
    int cur;
    double *d;
    signed char *cls;
    int *vmap;
    int dcap, ccap, mcap;
    int *edge;    /* 3 per new vertex: the in end, the out end, the vertex */
    int ecap, ne;
    int *capv;    /* the new face's vertices */
    double *capk; /* and their angles */
    int cvcap, ckcap;
} Clip;

static void poly_reserve(Poly *p, int nv, int nf, int ni)
{
    need(&p->v, &p->vcap, 3 * (size_t)nv, sizeof(double));
    need(&p->lab, &p->fcap, (size_t)nf, sizeof(int));
    need(&p->off, &p->ocap, (size_t)nf + 1, sizeof(int));
    need(&p->idx, &p->icap, (size_t)ni, sizeof(int));
}

static void clip_free(Clip *c)
{
    for (int k = 0; k < 2; k++) {
        free(c->p[k].v);
        free(c->p[k].lab);
        free(c->p[k].off);
        free(c->p[k].idx);
    }
    free(c->d);
    free(c->cls);
    free(c->vmap);
    free(c->edge);
    free(c->capv);
    free(c->capk);
}

/* The box as the starting polyhedron; vertex v has bit 0 set for x = hi,
   bit 1 for y, bit 2 for z; faces in side order, outward by the right
   hand rule. */
static void poly_box(Clip *c, const double lo[3], const double hi[3])
{
    static const int face[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    c->cur = 0;
    Poly *p = &c->p[0];
    poly_reserve(p, 8, 6, 24);
    for (int v = 0; v < 8; v++)
        for (int a = 0; a < 3; a++) p->v[3 * v + a] = (v >> a) & 1 ? hi[a] : lo[a];
    p->nv = 8;
    p->nf = 6;
    p->ni = 24;
    p->off[0] = 0;
    for (int s = 0; s < 6; s++) {
        p->lab[s] = -1 - s;
        memcpy(p->idx + 4 * s, face[s], sizeof face[s]);
        p->off[s + 1] = 4 * (s + 1);
    }
}

/* Monotone in the angle of (x, y), in [0, 4): cheaper than atan2. */
static double pseudo_angle(double x, double y)
{
    double r = x / (fabs(x) + fabs(y));
    return y < 0 ? 3 + r : 1 - r;
}

/* The vertex where the plane crosses edge (in, out) of P, made once. */
static int edge_vertex(Clip *c, const Poly *P, Poly *Q, int a, int b)
{
    int in = c->cls[a] < 0 ? a : b, out = in == a ? b : a;
    for (int k = 0; k < c->ne; k++)
        if (c->edge[3 * k] == in && c->edge[3 * k + 1] == out) return c->edge[3 * k + 2];
    double t = c->d[in] / (c->d[in] - c->d[out]);
    const double *vi = P->v + 3 * in, *vo = P->v + 3 * out;
    double *w = Q->v + 3 * Q->nv;
    for (int k = 0; k < 3; k++) w[k] = vi[k] + t * (vo[k] - vi[k]);
    need(&c->edge, &c->ecap, 3 * ((size_t)c->ne + 1), sizeof(int));
    c->edge[3 * c->ne] = in;
    c->edge[3 * c->ne + 1] = out;
    c->edge[3 * c->ne + 2] = Q->nv;
    c->ne++;
    return Q->nv++;
}

/* Appends to Q the face of the vertices capv[0..n) (all on the plane of
   unit normal nrm), ordered counter-clockwise about nrm. */
static void cap_face(Clip *c, Poly *Q, int n, const double nrm[3], int lab)
{
    double m[3] = {0, 0, 0};
    for (int k = 0; k < n; k++)
        for (int a = 0; a < 3; a++) m[a] += Q->v[3 * c->capv[k] + a] / n;
    /* u perpendicular to nrm, v = nrm x u, so (u, v, nrm) is right-handed */
    int ax = fabs(nrm[0]) < fabs(nrm[1]) ? (fabs(nrm[0]) < fabs(nrm[2]) ? 0 : 2)
                                         : (fabs(nrm[1]) < fabs(nrm[2]) ? 1 : 2);
    double e[3] = {0, 0, 0}, u[3], v[3];
    e[ax] = 1;
    u[0] = nrm[1] * e[2] - nrm[2] * e[1];
    u[1] = nrm[2] * e[0] - nrm[0] * e[2];
    u[2] = nrm[0] * e[1] - nrm[1] * e[0];
    v[0] = nrm[1] * u[2] - nrm[2] * u[1];
    v[1] = nrm[2] * u[0] - nrm[0] * u[2];
    v[2] = nrm[0] * u[1] - nrm[1] * u[0];
    need(&c->capk, &c->ckcap, (size_t)n, sizeof(double));
    for (int k = 0; k < n; k++) {
        const double *p = Q->v + 3 * c->capv[k];
        double r[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
        double key = pseudo_angle(r[0] * u[0] + r[1] * u[1] + r[2] * u[2], r[0] * v[0] + r[1] * v[1] + r[2] * v[2]);
        int vk = c->capv[k], q = k;
        while (q > 0 && c->capk[q - 1] > key) {
            c->capk[q] = c->capk[q - 1];
            c->capv[q] = c->capv[q - 1];
            q--;
        }
        c->capk[q] = key;
        c->capv[q] = vk;
    }
    memcpy(Q->idx + Q->ni, c->capv, sizeof(int) * (size_t)n);
    Q->ni += n;
    Q->lab[Q->nf] = lab;
    Q->off[++Q->nf] = Q->ni;
}

/* Clips the cell by the half-space nrm.x <= off (nrm a unit vector),
   labelling the new face lab; eps: on-plane tolerance.  Returns 1 when
   something was cut off. */
static int clip3(Clip *c, const double nrm[3], double off, double eps, int lab)
{
    Poly *P = &c->p[c->cur], *Q = &c->p[1 - c->cur];
    need(&c->d, &c->dcap, (size_t)P->nv, sizeof(double));
    need(&c->cls, &c->ccap, (size_t)P->nv, 1);
    need(&c->vmap, &c->mcap, (size_t)P->nv, sizeof(int));
    int nout = 0;
    for (int k = 0; k < P->nv; k++) {
        const double *v = P->v + 3 * k;
        double s = nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2] - off;
        c->d[k] = s;
        nout += s > eps;
    }
    /* most planes of a lattice's neighbours only touch the cell */
    if (!nout) return 0;
    for (int k = 0; k < P->nv; k++) c->cls[k] = c->d[k] > eps ? 1 : c->d[k] < -eps ? -1 : 0;
    /* new vertices: at most one per edge, ni/2 edges */
    poly_reserve(Q, P->nv + P->ni / 2 + 1, P->nf + 1, 3 * P->ni + P->nv + 3);
    int nk = 0;
    for (int k = 0; k < P->nv; k++) {
        if (c->cls[k] > 0) {
            c->vmap[k] = -1;
            continue;
        }
        memcpy(Q->v + 3 * nk, P->v + 3 * k, 3 * sizeof(double));
        c->vmap[k] = nk++;
    }
    Q->nv = nk;
    Q->nf = Q->ni = 0;
    Q->off[0] = 0;
    c->ne = 0;
    for (int f = 0; f < P->nf; f++) {
        int s = P->off[f], e = P->off[f + 1], start = Q->ni;
        for (int q = s; q < e; q++) {
            int a = P->idx[q], b = P->idx[q + 1 < e ? q + 1 : s];
            if (c->cls[a] <= 0) Q->idx[Q->ni++] = c->vmap[a];
            if (c->cls[a] * c->cls[b] < 0) {
                int w = edge_vertex(c, P, Q, a, b);
                Q->idx[Q->ni++] = w;
            }
        }
        if (Q->ni - start >= 3) {
            Q->lab[Q->nf] = P->lab[f];
            Q->off[++Q->nf] = Q->ni;
        } else {
            Q->ni = start;
        }
    }
    int ncap = 0;
    need(&c->capv, &c->cvcap, (size_t)Q->nv, sizeof(int));
    for (int k = 0; k < P->nv; k++)
        if (c->cls[k] == 0) c->capv[ncap++] = c->vmap[k];
    for (int k = nk; k < Q->nv; k++) c->capv[ncap++] = k;
    if (ncap >= 3) cap_face(c, Q, ncap, nrm, lab);
    c->cur = 1 - c->cur;
    return 1;
}

/* ---- 2-D clipper ---------------------------------------------------- */

/* Convex polygon in the (u, v) plane, counter-clockwise; edge k runs from
   vertex k to k+1 and has label lab[k]. */
typedef struct Poly2 {
    int n, cap, lcap;
    double *x;    /* 2*n */
    int *lab;
} Poly2;

typedef struct Clip2 {
    Poly2 p[2];
    int cur;
    double *d;
    int dcap;
} Clip2;

static void poly2_reserve(Poly2 *p, int n)
{
    need(&p->x, &p->cap, 2 * (size_t)n, sizeof(double));
    need(&p->lab, &p->lcap, (size_t)n, sizeof(int));
}

static void clip2_free(Clip2 *c)
{
    for (int k = 0; k < 2; k++) {
        free(c->p[k].x);
        free(c->p[k].lab);
    }
    free(c->d);
}

static void poly2_push(Poly2 *Q, double u, double v, int lab)
{
    Q->x[2 * Q->n] = u;
    Q->x[2 * Q->n + 1] = v;
    Q->lab[Q->n++] = lab;
}

/* Clips by nrm.x <= off in the plane (nrm a unit 2-vector). */
static int clip2(Clip2 *c, const double nrm[2], double off, double eps, int lab)
{
    Poly2 *P = &c->p[c->cur], *Q = &c->p[1 - c->cur];
    need(&c->d, &c->dcap, (size_t)P->n, sizeof(double));
    int nout = 0;
    for (int k = 0; k < P->n; k++) {
        double s = nrm[0] * P->x[2 * k] + nrm[1] * P->x[2 * k + 1] - off;
        c->d[k] = s;
        nout += s > eps;
    }
    if (!nout) return 0;
    poly2_reserve(Q, P->n + 2);
    Q->n = 0;
    for (int k = 0; k < P->n; k++) {
        int k1 = k + 1 < P->n ? k + 1 : 0;
        double da = c->d[k], db = c->d[k1];
        int ca = da > eps ? 1 : da < -eps ? -1 : 0, cb = db > eps ? 1 : db < -eps ? -1 : 0;
        const double *a = P->x + 2 * k, *b = P->x + 2 * k1;
        if (ca <= 0) poly2_push(Q, a[0], a[1], ca == 0 && cb > 0 ? lab : P->lab[k]);
        if (ca < 0 && cb > 0) {
            double t = da / (da - db);
            poly2_push(Q, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), lab);
        } else if (ca > 0 && cb < 0) {
            double t = db / (db - da);
            poly2_push(Q, b[0] + t * (a[0] - b[0]), b[1] + t * (a[1] - b[1]), P->lab[k]);
        }
    }
    c->cur = 1 - c->cur;
    return 1;
}

/* ---- welding -------------------------------------------------------- */

/* Global points, found by position.  Every distinct coordinate triple
   handed in is kept as an entry with the point it became, chained in a
   uniform grid (the seed buckets shifted by half a bucket, so the corners
   of a Cartesian lattice's cells fall on bucket centres); a query within
   tol of a bucket's side also looks across it, so every entry within tol
   is seen.  The nearest entry wins, and an exact copy of an earlier query
   is at distance 0: a vertex computed bitwise identically by two cells
   always gets the same point, whatever was added in between.  Chains grow
   in the order cells are made, so a query touches memory made recently
   (a hash of the coordinates would miss the cache on every query). */
typedef struct Weld {
    double tol, org[3], h[3];
    int n[3];
    int *head;        /* per bucket: last entry, -1 */
    int *id, *next;   /* per entry: id >= 0, the point it made (its
                         coordinates are that point's); < 0, -1 - its
                         place among the extras */
    int nent, icap, ncap;
    double *xx;       /* extras (entries that joined an earlier point): 3 each */
    int *xid;         /* and that point */
    int nx, xxcap, xicap;
    double *pts;      /* stride per point (2-D: 6, the copy at hi filled later) */
    int stride, npts, pcap;
} Weld;

static void weld_init(Weld *w, const Buckets *g, double tol, int flat, int stride, size_t expect)
{
    memset(w, 0, sizeof *w);
    w->tol = tol;
    w->stride = stride;
    size_t nb = 1;
    for (int a = 0; a < 3; a++) {
        /* 2-D: every point is at lo along the flat axis: one layer */
        w->n[a] = a == flat ? 1 : g->n[a] + 1;
        w->h[a] = g->h[a];
        w->org[a] = g->org[a] - 0.5 * g->h[a];
        nb *= (size_t)w->n[a];
    }
    w->head = mem_alloc(sizeof(int) * nb);
    memset(w->head, 0xff, sizeof(int) * nb);
    need(&w->id, &w->icap, expect, sizeof(int));
    need(&w->next, &w->ncap, expect, sizeof(int));
    need(&w->pts, &w->pcap, (size_t)stride * expect, sizeof(double));
}

static void weld_free(Weld *w)
{
    free(w->head);
    free(w->id);
    free(w->next);
    free(w->xx);
    free(w->xid);
    free(w->pts);
}

static int weld_axis(const Weld *w, int a, double x)
{
    double t = (x - w->org[a]) / w->h[a];
    if (!(t > 0)) return 0;
    if (t >= w->n[a]) return w->n[a] - 1;
    return (int)t;
}

/* The number of the point at x (made when there is none within tol). */
static int weld_point(Weld *w, const double x[3])
{
    int k[3], lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        k[a] = weld_axis(w, a, x[a]);
        lo[a] = weld_axis(w, a, x[a] - w->tol);
        hi[a] = weld_axis(w, a, x[a] + w->tol);
    }
    int best = -1;
    double bd = w->tol * w->tol;
    for (int iz = lo[2]; iz <= hi[2]; iz++)
        for (int iy = lo[1]; iy <= hi[1]; iy++)
            for (int ix = lo[0]; ix <= hi[0]; ix++)
                for (int q = w->head[ix + w->n[0] * (iy + w->n[1] * iz)]; q >= 0; q = w->next[q]) {
                    int id = w->id[q];
                    const double *p;
                    if (id >= 0) {
                        p = w->pts + (size_t)w->stride * (size_t)id;
                    } else {
                        p = w->xx + 3 * (size_t)(-1 - id);
                        id = w->xid[-1 - id];
                    }
                    double d2 = sq(p[0] - x[0]) + sq(p[1] - x[1]) + sq(p[2] - x[2]);
                    if (d2 == 0) return id;
                    if (d2 <= bd) {
                        bd = d2;
                        best = id;
                    }
                }
    int q = w->nent++;
    need(&w->id, &w->icap, (size_t)w->nent, sizeof(int));
    need(&w->next, &w->ncap, (size_t)w->nent, sizeof(int));
    if (best < 0) {
        need(&w->pts, &w->pcap, (size_t)w->stride * ((size_t)w->npts + 1), sizeof(double));
        memcpy(w->pts + (size_t)w->stride * (size_t)w->npts, x, 3 * sizeof(double));
        best = w->npts++;
        w->id[q] = best;
    } else {
        need(&w->xx, &w->xxcap, 3 * ((size_t)w->nx + 1), sizeof(double));
        need(&w->xid, &w->xicap, (size_t)w->nx + 1, sizeof(int));
        memcpy(w->xx + 3 * (size_t)w->nx, x, 3 * sizeof(double));
        w->xid[w->nx] = best;
        w->id[q] = -1 - w->nx++;
    }
    int *head = &w->head[k[0] + w->n[0] * (k[1] + w->n[1] * k[2])];
    w->next[q] = *head;
    *head = q;
    return best;
}

/* Voronoi vertices by name: a vertex of seed i's cell on exactly dim
   faces (3 in 3-D, 2 in 2-D) is the vertex of the sorted set {i, labels},
   the same set every cell around it sees (unless the vertex is
   degenerate).  Naming them makes the welding consistent even where their
   positions are ill-conditioned (nearly cospherical seeds): the first cell
   to meet a vertex welds it by position, every later one gets the same
   point by name.  Names are chained on their lowest seed. */
typedef struct Names {
    int *head;        /* per seed: last entry, -1 */
    int32_t *key;     /* 4 per entry */
    int *id, *next;
    int nent, kcap, icap, ncap;
} Names;

static void names_init(Names *t, int nseeds, size_t expect)
{
    memset(t, 0, sizeof *t);
    t->head = mem_alloc(sizeof(int) * (size_t)nseeds);
    memset(t->head, 0xff, sizeof(int) * (size_t)nseeds);
    need(&t->key, &t->kcap, 4 * expect, sizeof(int32_t));
    need(&t->id, &t->icap, expect, sizeof(int));
    need(&t->next, &t->ncap, expect, sizeof(int));
}

static void names_free(Names *t)
{
    free(t->head);
    free(t->key);
    free(t->id);
    free(t->next);
}

/* The sorted name of the vertex of seed i on faces lab[0..dim); box sides
   are negative, so they sort first; unused places are INT32_MAX.  Returns
   the lowest seed of the name. */
static int vertex_name(int i, const int *lab, int dim, int32_t k[4])
{
    int n = 0;
    for (int q = -1; q < dim; q++) {
        int l = q < 0 ? i : lab[q], p = n++;
        while (p > 0 && k[p - 1] > l) {
            k[p] = k[p - 1];
            p--;
        }
        k[p] = l;
    }
    while (n < 4) k[n++] = INT32_MAX;
    int q = 0;
    while (k[q] < 0) q++;
    return k[q];
}

/* The point of a vertex: by name when it has one (k != NULL, lowest seed
   s), else by position. */
static int weld_vertex(Weld *w, Names *t, const int32_t *k, int s, const double x[3])
{
    if (!k) return weld_point(w, x);
    for (int q = t->head[s]; q >= 0; q = t->next[q])
        if (!memcmp(t->key + 4 * q, k, 4 * sizeof(int32_t))) return t->id[q];
    int id = weld_point(w, x), q = t->nent++;
    need(&t->key, &t->kcap, 4 * (size_t)t->nent, sizeof(int32_t));
    need(&t->id, &t->icap, (size_t)t->nent, sizeof(int));
    need(&t->next, &t->ncap, (size_t)t->nent, sizeof(int));
    memcpy(t->key + 4 * q, k, 4 * sizeof(int32_t));
    t->id[q] = id;
    t->next[q] = t->head[s];
    t->head[s] = q;
    return id;
}

/* ---- the cells as polygons of global points ------------------------- */

typedef struct Store {
    int ncells;
    int *cell_off;            /* ncells+1: faces of each cell */
    int nf, fcap, lcap, ocap;
    int *lab;                 /* per face, sorted inside a cell */
    int *off;                 /* nf+1 */
    int ni, icap;
    int *idx;
} Store;

static void store_free(Store *s)
{
    free(s->cell_off);
    free(s->lab);
    free(s->off);
    free(s->idx);
}

static void store_face(Store *s, int lab, const int *pts, int n, int rev)
{
    need(&s->lab, &s->lcap, (size_t)s->nf + 1, sizeof(int));
    need(&s->off, &s->ocap, (size_t)s->nf + 2, sizeof(int));
    need(&s->idx, &s->icap, (size_t)s->ni + (size_t)n, sizeof(int));
    if (s->nf == 0) s->off[0] = 0;
    for (int k = 0; k < n; k++) s->idx[s->ni + k] = rev ? pts[n - 1 - k] : pts[k];
    s->ni += n;
    s->lab[s->nf] = lab;
    s->off[++s->nf] = s->ni;
}

/* Sorts the last cell's faces (from face f0) by label; a cell has a few
   dozen faces, so insertion sort of an index permutation. */
static void store_sort_cell(Store *s, int f0, int **tmp, int *tcap)
{
    int nf = s->nf - f0, ni = s->ni - s->off[f0];
    need(tmp, tcap, (size_t)(3 * nf + ni + 1), sizeof(int));
    int *perm = *tmp, *lab = perm + nf, *off_old = lab + nf, *buf = off_old + nf + 1;
    int sorted = 1;
    for (int k = 0; k < nf; k++) {
        int l = s->lab[f0 + k], q = k;
        if (q > 0 && s->lab[f0 + k - 1] > l) sorted = 0;
        while (q > 0 && s->lab[f0 + perm[q - 1]] > l) {
            perm[q] = perm[q - 1];
            q--;
        }
        perm[q] = k;
    }
    if (sorted) return;
    int base = s->off[f0], o = 0;
    memcpy(buf, s->idx + base, sizeof(int) * (size_t)ni);
    for (int k = 0; k < nf; k++) lab[k] = s->lab[f0 + k];
    memcpy(off_old, s->off + f0, sizeof(int) * (size_t)(nf + 1));
    for (int k = 0; k < nf; k++) {
        int f = perm[k], a = off_old[f] - base, n = off_old[f + 1] - off_old[f];
        memcpy(s->idx + base + o, buf + a, sizeof(int) * (size_t)n);
        o += n;
        s->lab[f0 + k] = lab[f];
        s->off[f0 + k + 1] = base + o;
    }
}

/* 2-D cells as they come out of the clipper: for cell c the polygon's
   global 2-D points gid[off[c]..off[c+1]), counter-clockwise, and the
   label of the edge from each point to the next.  The prism's faces are
   made from these only when the mesh is written. */
typedef struct Rings {
    int *off;                 /* ncells+1 */
    int *gid, *lab;
    int n, gcap, lcap;
} Rings;

static void rings_free(Rings *r)
{
    free(r->off);
    free(r->gid);
    free(r->lab);
}

/* ---- pass 1: the cells ---------------------------------------------- */

typedef struct Build {
    const VoronoiInput *in;
    Buckets g;
    Search s;
    Clip c3;
    Clip2 c2;
    Weld w;
    Names names;
    Store st;
    double L, eps;
    int *gid;           /* global point of each cell vertex */
    int gcap;
    int *vlab;          /* per cell vertex: face count, three face labels */
    int vlcap;
    int *tmp;
    int tcap;
    Rings rg;           /* 2-D: the cells as polygons */
    const int *cell_of; /* per seed: its cell, or -1 */
} Build;

static int coincide(const VoronoiInput *in, int i, int j, Err *e)
{
    return err_set(e, NULL, 0, "voronoi: seeds %d and %d coincide (%g %g %g)", i, j, in->x[3 * i],
                   in->x[3 * i + 1], in->x[3 * i + 2]);
}

/* Bisector clipping of seed i's cell, shell by shell; clip(ctx, j, d2)
   returns the cell's new squared radius. */
static int cell_search(Build *B, int i, double r2, double (*clip)(Build *, int, int, double), Err *e)
{
    const VoronoiInput *in = B->in;
    double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
    if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
    int b[3];
    for (int a = 0; a < 3; a++) b[a] = bucket_axis(&B->g, a, x[a]);
    double dup2 = sq(VORONOI_MERGE * B->L);
    for (int k = 0;; k++) {
        if (k > 0) {
            double sd = shell_dist(&B->g, b, k, x);
            if (sd == INFINITY) break;
            if (sd > 0 && sd * sd > 4 * r2 * REACH_SLACK) break;
        }
        shell_collect(&B->s, &B->g, in, i, b, k, x, 4 * r2 * REACH_SLACK);
        for (int q = 0; q < B->s.n; q++) {
            Cand cd = B->s.cand[q];
            if (cd.d2 > 4 * r2 * REACH_SLACK) break;
            if (cd.d2 <= dup2) return coincide(in, i, cd.j, e);
            r2 = clip(B, i, cd.j, r2);
        }
    }
    return 0;
}

/* Squared distance from x to the farthest vertex of P. */
static double poly_radius3(const Poly *P, const double *x)
{
    double r2 = 0;
    for (int k = 0; k < P->nv; k++) {
        double d = sq(P->v[3 * k] - x[0]) + sq(P->v[3 * k + 1] - x[1]) + sq(P->v[3 * k + 2] - x[2]);
        if (d > r2) r2 = d;
    }
    return r2;
}

static double clip3_seed(Build *B, int i, int j, double r2)
{
    const double *xi = B->in->x + 3 * i, *xj = B->in->x + 3 * j;
    double n[3], m[3], len = 0;
    for (int a = 0; a < 3; a++) {
        n[a] = xj[a] - xi[a];
        m[a] = 0.5 * (xi[a] + xj[a]);
        len += n[a] * n[a];
    }
    len = sqrt(len);
    for (int a = 0; a < 3; a++) n[a] /= len;
    if (!clip3(&B->c3, n, n[0] * m[0] + n[1] * m[1] + n[2] * m[2], B->eps, j)) return r2;
    return poly_radius3(&B->c3.p[B->c3.cur], xi);
}

static int cell3(Build *B, int i, Err *e)
{
    const VoronoiInput *in = B->in;
    poly_box(&B->c3, in->lo, in->hi);
    if (cell_search(B, i, poly_radius3(&B->c3.p[0], in->x + 3 * i), clip3_seed, e)) return -1;
    Poly *P = &B->c3.p[B->c3.cur];
    if (P->nf < 4) return err_set(e, NULL, 0, "voronoi: the cell of seed %d is empty", i);
    need(&B->gid, &B->gcap, (size_t)P->nv, sizeof(int));
    need(&B->vlab, &B->vlcap, 4 * (size_t)P->nv, sizeof(int));
    for (int k = 0; k < P->nv; k++) B->gid[k] = B->vlab[4 * k] = 0;
    for (int f = 0; f < P->nf; f++)
        for (int q = P->off[f]; q < P->off[f + 1]; q++) {
            int *vl = B->vlab + 4 * P->idx[q];
            if (vl[0] < 3) vl[1 + vl[0]] = P->lab[f];
            vl[0]++;
        }
    for (int k = 0; k < P->nv; k++) B->gid[k] = -1;
    int f0 = B->st.nf;
    need(&B->tmp, &B->tcap, (size_t)P->ni, sizeof(int));
    int *pts = B->tmp;
    for (int f = 0; f < P->nf; f++) {
        int s = P->off[f], n = P->off[f + 1] - s;
        for (int q = 0; q < n; q++) {
            int v = P->idx[s + q];
            if (B->gid[v] < 0) {
                int32_t key[4];
                int named = B->vlab[4 * v] == 3, low = named ? vertex_name(i, B->vlab + 4 * v + 1, 3, key) : 0;
                B->gid[v] = weld_vertex(&B->w, &B->names, named ? key : NULL, low, P->v + 3 * v);
            }
            pts[q] = B->gid[v];
        }
        store_face(&B->st, P->lab[f], pts, n, 0);
    }
    store_sort_cell(&B->st, f0, &B->tmp, &B->tcap);
    return 0;
}

/* 2-D vertex names without a table: the vertex of seed i's cell between
   edges labelled a and b is named {i, a, b}, and the cells that can have
   met that name before are those of the kept seeds among a and b that
   come before i.  The point of cell l's vertex between its edges
   labelled i and o (in either order), or -1 when l has no cell yet or no
   such vertex. */
static int ring_vertex(const Build *B, int l, int i, int o)
{
    if (l < 0 || l > i || !B->in->keep[l]) return -1;
    const Rings *r = &B->rg;
    int c = B->cell_of[l], r0 = r->off[c], n = r->off[c + 1] - r0;
    const int *lab = r->lab + r0;
    for (int e = 0; e < n; e++) {
        if (lab[e] != i) continue;
        if (lab[e > 0 ? e - 1 : n - 1] == o) return r->gid[r0 + e];
        if (lab[e + 1 < n ? e + 1 : 0] == o) return r->gid[r0 + (e + 1 < n ? e + 1 : 0)];
        return -1;
    }
    return -1;
}

static double clip2_seed(Build *B, int i, int j, double r2)
{
    int ua = (B->in->flat_axis + 1) % 3, va = (B->in->flat_axis + 2) % 3;
    const double *xi = B->in->x + 3 * i, *xj = B->in->x + 3 * j;
    double n[2] = {xj[ua] - xi[ua], xj[va] - xi[va]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1]);
    n[0] /= len;
    n[1] /= len;
    double off = n[0] * 0.5 * (xi[ua] + xj[ua]) + n[1] * 0.5 * (xi[va] + xj[va]);
    if (!clip2(&B->c2, n, off, B->eps, j)) return r2;
    const Poly2 *P = &B->c2.p[B->c2.cur];
    r2 = 0;
    for (int k = 0; k < P->n; k++) {
        double d = sq(P->x[2 * k] - xi[ua]) + sq(P->x[2 * k + 1] - xi[va]);
        if (d > r2) r2 = d;
    }
    return r2;
}

static int cell2(Build *B, int i, Err *e)
{
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis, ua = (fa + 1) % 3, va = (fa + 2) % 3;
    Clip2 *c = &B->c2;
    c->cur = 0;
    Poly2 *P = &c->p[0];
    poly2_reserve(P, 4);
    P->n = 0;
    poly2_push(P, in->lo[ua], in->lo[va], -1 - (2 * va));
    poly2_push(P, in->hi[ua], in->lo[va], -1 - (2 * ua + 1));
    poly2_push(P, in->hi[ua], in->hi[va], -1 - (2 * va + 1));
    poly2_push(P, in->lo[ua], in->hi[va], -1 - (2 * ua));
    const double *xi = in->x + 3 * i;
    double r2 = 0;
    for (int k = 0; k < 4; k++) {
        double d = sq(P->x[2 * k] - xi[ua]) + sq(P->x[2 * k + 1] - xi[va]);
        if (d > r2) r2 = d;
    }
    if (cell_search(B, i, r2, clip2_seed, e)) return -1;
    P = &c->p[c->cur];
    if (P->n < 3) return err_set(e, NULL, 0, "voronoi: the cell of seed %d is empty", i);
    need(&B->gid, &B->gcap, (size_t)P->n, sizeof(int));
    for (int k = 0; k < P->n; k++) {
        double x[3];
        x[fa] = in->lo[fa];
        x[ua] = P->x[2 * k];
        x[va] = P->x[2 * k + 1];
        int l0 = P->lab[k > 0 ? k - 1 : P->n - 1], l1 = P->lab[k], g = ring_vertex(B, l0, i, l1);
        if (g < 0) g = ring_vertex(B, l1, i, l0);
        B->gid[k] = g >= 0 ? g : weld_point(&B->w, x);
    }
    Rings *r = &B->rg;
    need(&r->gid, &r->gcap, (size_t)r->n + (size_t)P->n, sizeof(int));
    need(&r->lab, &r->lcap, (size_t)r->n + (size_t)P->n, sizeof(int));
    memcpy(r->gid + r->n, B->gid, sizeof(int) * (size_t)P->n);
    memcpy(r->lab + r->n, P->lab, sizeof(int) * (size_t)P->n);
    r->n += P->n;
    return 0;
}

/* The prism of 2-D cell c as stored polygons (the general assembly's
   input): a quad per edge, base point p of the plane being point 2p at
   lo and 2p+1 at hi, and the back and front faces, sorted by label. */
static void ring_store(Build *B, int c)
{
    int fa = B->in->flat_axis, r0 = B->rg.off[c], n = B->rg.off[c + 1] - r0;
    const int *gid = B->rg.gid + r0, *lab = B->rg.lab + r0;
    need(&B->tmp, &B->tcap, 2 * (size_t)n + 4, sizeof(int));
    int f0 = B->st.nf;
    int *q = B->tmp;
    for (int k = 0; k < n; k++) {
        int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0];
        int quad[4] = {2 * a, 2 * b, 2 * b + 1, 2 * a + 1};
        store_face(&B->st, lab[k], quad, 4, 0);
    }
    for (int k = 0; k < n; k++) q[k] = 2 * gid[k];
    store_face(&B->st, -1 - 2 * fa, q, n, 1);
    for (int k = 0; k < n; k++) q[k] = 2 * gid[k] + 1;
    store_face(&B->st, -1 - (2 * fa + 1), q, n, 0);
    store_sort_cell(&B->st, f0, &B->tmp, &B->tcap);
}

/* ---- pass 2: assembly ----------------------------------------------- */

static int uf_find(int *uf, int a)
{
    while (uf[a] != a) {
        uf[a] = uf[uf[a]];
        a = uf[a];
    }
    return a;
}

/* Area vector of polygon idx[0..n) (points pts), reversed when rev. */
static void poly_area(const double *pts, const int *idx, int n, int rev, double S[3])
{
    const double *p0 = pts + 3 * idx[0];
    S[0] = S[1] = S[2] = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *a = pts + 3 * idx[k], *b = pts + 3 * idx[k + 1];
        double u[3] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2]};
        double v[3] = {b[0] - p0[0], b[1] - p0[1], b[2] - p0[2]};
        S[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
        S[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
        S[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
    }
    if (rev)
        for (int a = 0; a < 3; a++) S[a] = -S[a];
}

/* Face of cell c (seed i) labelled lab, or -1 (binary search). */
static int store_find(const Store *s, int c, int lab)
{
    int lo = s->cell_off[c], hi = s->cell_off[c + 1] - 1;
    while (lo <= hi) {
        int m = (lo + hi) / 2;
        if (s->lab[m] == lab) return m;
        if (s->lab[m] < lab) lo = m + 1;
        else hi = m - 1;
    }
    return -1;
}

/* The cell that stored face f (binary search; only repairs need it). */
static int store_cell(const Store *s, int f)
{
    int lo = 0, hi = s->ncells - 1;
    while (lo < hi) {
        int m = (lo + hi + 1) / 2;
        if (s->cell_off[m] <= f) lo = m;
        else hi = m - 1;
    }
    return lo;
}

/* Directed edges of one cell, counted in a small open hash: a closed cell
   uses each edge once in each direction. */
typedef struct Edges {
    uint64_t *key;
    int *cnt;       /* +1 per use a->b with a < b, +16 per use b->a */
    int *used;
    int cap, nused, ucap;
} Edges;

static void edges_clear(Edges *x, int nedge)
{
    for (int k = 0; k < x->nused; k++) x->cnt[x->used[k]] = 0;
    x->nused = 0;
    if (4 * nedge > x->cap) {
        int cap = 64;
        while (cap < 4 * nedge) cap *= 2;
        free(x->key);
        free(x->cnt);
        x->key = mem_alloc(sizeof(uint64_t) * (size_t)cap);
        x->cnt = mem_calloc((size_t)cap, sizeof(int));
        x->cap = cap;
    }
    need(&x->used, &x->ucap, (size_t)nedge, sizeof(int));
}

static void edges_add(Edges *x, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    uint64_t k = (uint64_t)(uint32_t)lo << 32 | (uint32_t)hi;
    uint64_t h = k * 0x9E3779B97F4A7C15u;
    int m = x->cap - 1, s = (int)(h >> 40) & m;
    while (x->cnt[s] && x->key[s] != k) s = (s + 1) & m;
    if (!x->cnt[s]) {
        x->key[s] = k;
        x->used[x->nused++] = s;
    }
    x->cnt[s] += a < b ? 1 : 16;
}

static int edges_closed(const Edges *x)
{
    for (int k = 0; k < x->nused; k++)
        if (x->cnt[x->used[k]] != 17) return 0;
    return 1;
}

static void edges_free(Edges *x)
{
    free(x->key);
    free(x->cnt);
    free(x->used);
}

/* One face of a cell as the assembly sees it: a stored polygon, reversed
   when the cell across stored it. */
typedef struct CFace {
    int f, rev;
} CFace;

typedef struct Assembly {
    const VoronoiInput *in;
    Store *st;
    const int *cell_of, *seed_of;
    double *pts;      /* coordinates of the final point numbers */
    int *beg, *len;   /* per stored face: its points idx[beg..beg+len) */
    double tol;       /* weld distance */
    Edges edges;
    CFace *cf;
    int ncf, cfcap;
    int *tpts, *ends; /* scratch: a polygon being repaired, unmatched ends */
    double *tt;
    int tcap, ecap, ttcap;
    int ndropped;
} Assembly;

/* Faces of area below amin whose points all lie within dmax of the first
   collapse to a point.  A thin face longer than that (a needle between two
   long edges) stays: collapsing it would move far-apart points together,
   and dropping it alone would open both cells. */
static void collapse_tiny(Assembly *A, int *uf, double amin, double dmax)
{
    Store *s = A->st;
    for (int c = 0; c < s->ncells; c++) {
        int i = A->seed_of[c];
        for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
            int lab = s->lab[f], n = s->off[f + 1] - s->off[f];
            if (lab >= 0 && A->in->keep[lab] && lab < i) continue;
            const int *idx = s->idx + s->off[f];
            double S[3];
            poly_area(A->pts, idx, n, 0, S);
            if (sq(S[0]) + sq(S[1]) + sq(S[2]) >= amin * amin) continue;
            const double *p0 = A->pts + 3 * idx[0];
            int small = 1;
            for (int k = 1; k < n && small; k++) {
                const double *p = A->pts + 3 * idx[k];
                small = sq(p[0] - p0[0]) + sq(p[1] - p0[1]) + sq(p[2] - p0[2]) <= dmax * dmax;
            }
            if (!small) continue;
            int r = uf_find(uf, idx[0]);
            for (int k = 1; k < n; k++) {
                int q = uf_find(uf, idx[k]);
                if (q != r) uf[q] = r;
            }
        }
    }
}

/* Renumbers through uf and drops repeated consecutive points. */
static void weld_faces(Assembly *A, int *uf)
{
    Store *s = A->st;
    for (int f = 0; f < s->nf; f++) {
        int *idx = s->idx + s->off[f], n = s->off[f + 1] - s->off[f], m = 0;
        for (int k = 0; k < n; k++) {
            int p = uf ? uf_find(uf, idx[k]) : idx[k];
            if (m == 0 || idx[m - 1] != p) idx[m++] = p;
        }
        while (m > 1 && idx[m - 1] == idx[0]) m--;
        A->beg[f] = s->off[f];
        A->len[f] = m;
    }
}

/* Is stored face f (of a cell with seed i) the one the cell uses?  Not
   when it faces a lower kept seed that stored the pair's face itself. */
static int face_superseded(const Assembly *A, int f, int i, int *g)
{
    int lab = A->st->lab[f];
    *g = -1;
    if (lab < 0 || !A->in->keep[lab] || lab > i) return 0;
    *g = store_find(A->st, A->cell_of[lab], i);
    return *g >= 0;
}

/* The faces of cell c (at least 3 points each) into A->cf; returns the
   number of their edges. */
static int cell_face_list(Assembly *A, int c)
{
    Store *s = A->st;
    int i = A->seed_of[c], nedge = 0;
    A->ncf = 0;
    need(&A->cf, &A->cfcap, (size_t)(s->cell_off[c + 1] - s->cell_off[c]), sizeof(CFace));
    for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
        int g;
        CFace cf = face_superseded(A, f, i, &g) ? (CFace){g, 1} : (CFace){f, 0};
        if (A->len[cf.f] < 3) continue;
        A->cf[A->ncf++] = cf;
        nedge += A->len[cf.f];
    }
    return nedge;
}

/* cell_face_list, and counts the faces' edges into A->edges.  Returns 1
   when the cell is closed. */
static int cell_faces(Assembly *A, int c)
{
    Store *s = A->st;
    edges_clear(&A->edges, cell_face_list(A, c));
    for (int k = 0; k < A->ncf; k++) {
        const int *idx = s->idx + A->beg[A->cf[k].f];
        int n = A->len[A->cf[k].f];
        for (int q = 0; q < n; q++) {
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            if (A->cf[k].rev) edges_add(&A->edges, b, a);
            else edges_add(&A->edges, a, b);
        }
    }
    return edges_closed(&A->edges);
}

static int edge_count(const Edges *x, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    uint64_t k = (uint64_t)(uint32_t)lo << 32 | (uint32_t)hi;
    int m = x->cap - 1, s = (int)((k * 0x9E3779B97F4A7C15u) >> 40) & m;
    while (x->cnt[s] && x->key[s] != k) s = (s + 1) & m;
    return x->cnt[s];
}

/* Repairs T-junctions of cell c (after cell_faces found it open): a thin
   face that welding reduced to a segment leaves its end points inside an
   edge of the neighbouring faces of the one cell that resolved it, but
   not of the other cells around that edge.  Each point that ends an
   unmatched edge and lies on another unmatched edge (within 4 tol, strictly
   between its ends) is inserted there, in the stored polygon, so every
   cell using that polygon sees it; those cells are returned in touched
   (at most 2 per repaired face).  Returns the number of insertions. */
static int cell_repair(Assembly *A, int c, int **touched, int *ntouched, int *tcap)
{
    Store *s = A->st;
    int nends = 0, nins = 0;
    for (int k = 0; k < A->ncf; k++) {
        const int *idx = s->idx + A->beg[A->cf[k].f];
        int n = A->len[A->cf[k].f];
        need(&A->ends, &A->ecap, (size_t)nends + 2 * (size_t)n, sizeof(int));
        for (int q = 0; q < n; q++) {
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            if (edge_count(&A->edges, a, b) == 17) continue;
            A->ends[nends++] = a;
            A->ends[nends++] = b;
        }
    }
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, n = A->len[f], m = 0;
        need(&A->tpts, &A->tcap, (size_t)n + (size_t)nends, sizeof(int));
        need(&A->tt, &A->ttcap, (size_t)nends + 1, sizeof(double));
        for (int q = 0; q < n; q++) {
            const int *idx = s->idx + A->beg[f];
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            A->tpts[m++] = a;
            if (edge_count(&A->edges, a, b) == 17) continue;
            const double *pa = A->pts + 3 * a, *pb = A->pts + 3 * b;
            double ab[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
            double l2 = sq(ab[0]) + sq(ab[1]) + sq(ab[2]);
            int m0 = m;
            for (int u = 0; u < nends; u++) {
                int p = A->ends[u], dup = p == a || p == b;
                for (int v = m0; v < m && !dup; v++) dup = A->tpts[v] == p;
                if (dup || !(l2 > 0)) continue;
                const double *pp = A->pts + 3 * p;
                double ap[3] = {pp[0] - pa[0], pp[1] - pa[1], pp[2] - pa[2]};
                double t = (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2;
                if (!(t > 0 && t < 1)) continue;
                double d2 = sq(ap[0] - t * ab[0]) + sq(ap[1] - t * ab[1]) + sq(ap[2] - t * ab[2]);
                if (d2 > 16 * A->tol * A->tol) continue;
                /* sorted along the edge */
                int v = m++;
                while (v > m0 && A->tt[v - m0 - 1] > t) {
                    A->tpts[v] = A->tpts[v - 1];
                    A->tt[v - m0] = A->tt[v - m0 - 1];
                    v--;
                }
                A->tpts[v] = p;
                A->tt[v - m0] = t;
            }
        }
        if (m == n) continue;
        nins += m - n;
        need(&s->idx, &s->icap, (size_t)s->ni + (size_t)m, sizeof(int));
        memcpy(s->idx + s->ni, A->tpts, sizeof(int) * (size_t)m);
        A->beg[f] = s->ni;
        A->len[f] = m;
        s->ni += m;
        int lab = s->lab[f], other[2] = {store_cell(s, f), lab >= 0 && A->in->keep[lab] ? A->cell_of[lab] : -1};
        for (int q = 0; q < 2; q++)
            if (other[q] >= 0 && other[q] != c) {
                need(touched, tcap, (size_t)*ntouched + 1, sizeof(int));
                (*touched)[(*ntouched)++] = other[q];
            }
    }
    return nins;
}

static int cell_not_closed(const Assembly *A, int c, Err *e)
{
    const double *x = A->in->x + 3 * A->seed_of[c];
    return err_set(e, NULL, 0,
                   "voronoi: the cell of seed %d at (%g %g %g) is not closed after welding its points "
                   "(seeds closer than %g of the box?)",
                   A->seed_of[c], x[0], x[1], x[2], VORONOI_MERGE);
}

/* Checks every cell, repairing T-junctions; cells whose faces a repair
   changed are checked again (a queue, each cell in it at most once). */
static int close_cells(Assembly *A, Err *e)
{
    int n = A->st->ncells, head = 0, count = n, budget = 4 * n + 64;
    if (n <= 0) return 0;
    int *queue = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    char *in_queue = mem_alloc((size_t)(n > 0 ? n : 1));
    for (int c = 0; c < n; c++) queue[c] = c;
    memset(in_queue, 1, (size_t)n);
    int *touched = NULL, ntouched = 0, tcap = 0, rc = 0;
    while (count > 0 && !rc) {
        int c = queue[head];
        head = (head + 1) % n;
        count--;
        in_queue[c] = 0;
        if (cell_faces(A, c)) continue;
        ntouched = 0;
        if (budget-- <= 0 || !cell_repair(A, c, &touched, &ntouched, &tcap)) {
            rc = cell_not_closed(A, c, e);
            break;
        }
        if (!cell_faces(A, c)) {
            rc = cell_not_closed(A, c, e);
            break;
        }
        for (int k = 0; k < ntouched; k++) {
            int d = touched[k];
            if (in_queue[d]) continue;
            in_queue[d] = 1;
            queue[(head + count++) % n] = d;
        }
    }
    free(queue);
    free(in_queue);
    free(touched);
    return rc;
}

/* Cell c's volume (its faces in A->cf, from cell_face_list) into vs. */
static void measure_cell(const Assembly *A, int c, VoronoiStats *vs)
{
    const double *xi = A->in->x + 3 * A->seed_of[c];
    double vol = 0;
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, n = A->len[f];
        const int *idx = A->st->idx + A->beg[f];
        double S[3];
        poly_area(A->pts, idx, n, A->cf[k].rev, S);
        const double *p0 = A->pts + 3 * idx[0];
        vol += (S[0] * (p0[0] - xi[0]) + S[1] * (p0[1] - xi[1]) + S[2] * (p0[2] - xi[2])) / 3;
    }
    if (vs) {
        if (c == 0 || vol < vs->vol_min) vs->vol_min = vol;
        vs->vol_total += vol;
    }
}

/* The cell across stored face f, or -1 - patch for a boundary face. */
static int face_other(const Assembly *A, int f)
{
    const VoronoiInput *in = A->in;
    int lab = A->st->lab[f];
    if (lab >= 0 && in->keep[lab]) return A->cell_of[lab];
    return -1 - (lab >= 0 ? in->patch[lab] : in->side_patch[-1 - lab]);
}

/* Hands cell c's own faces to the builder and measures the cell. */
static void emit_cell(Assembly *A, MeshBuild *b, int c, VoronoiStats *vs)
{
    cell_face_list(A, c);   /* close_cells checked the edges */
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, o = face_other(A, f);
        if (A->cf[k].rev) continue;
        if (o >= 0) meshbuild_face(b, A->st->idx + A->beg[f], A->len[f], c, o, -1);
        else meshbuild_face(b, A->st->idx + A->beg[f], A->len[f], c, -1, -1 - o);
    }
    measure_cell(A, c, vs);
}

/* ---- the mesh in OpenFOAM's order, without a builder ---------------- */

/* Each cell's own faces (those it does not take reversed from a lower
   cell) come sorted by label, and cells are numbered in seed order, so
   when every own internal face goes to a higher cell the internal faces
   arrive sorted by (owner, neighbour): the mesh can be written in place,
   each boundary face into its patch's range.  That skips meshbuild's
   copies of every face and point (on big 2-D grids, touching that much
   fresh memory costs more than making the cells).  Otherwise (an own face
   towards a lower cell that has no face back) meshbuild sorts. */
typedef struct Plan {
    int direct;        /* 1: internal faces arrive in order */
    int empty;         /* a cell without faces, or -1 */
    int nface, nint;   /* faces, internal faces */
    size_t nidx, iint; /* their points, those of internal faces */
    int *pface;        /* per patch: faces */
    size_t *pidx;      /* per patch: their points */
} Plan;

/* Counts the faces each cell hands on (dropping those of fewer than 3
   points) and whether they arrive in order. */
static void plan_faces(Assembly *A, Plan *pl)
{
    const Store *s = A->st;
    int np = A->in->npatches;
    memset(pl, 0, sizeof *pl);
    pl->direct = 1;
    pl->empty = -1;
    pl->pface = mem_calloc((size_t)np, sizeof(int));
    pl->pidx = mem_calloc((size_t)np, sizeof(size_t));
    for (int c = 0; c < s->ncells; c++) {
        int seen = 0;
        for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
            int g;
            if (face_superseded(A, f, A->seed_of[c], &g)) {
                seen |= A->len[g] >= 3;
                continue;
            }
            if (A->len[f] < 3) {
                A->ndropped++;
                continue;
            }
            seen = 1;
            int o = face_other(A, f);
            pl->nface++;
            pl->nidx += (size_t)A->len[f];
            if (o >= 0) {
                pl->nint++;
                pl->iint += (size_t)A->len[f];
                pl->direct &= o > c;
            } else {
                pl->pface[-1 - o]++;
                pl->pidx[-1 - o] += (size_t)A->len[f];
            }
        }
        if (!seen && pl->empty < 0) pl->empty = c;
    }
}

static void plan_free(Plan *pl)
{
    free(pl->pface);
    free(pl->pidx);
}

/* Where the next face goes: internal faces first, then patch by patch. */
typedef struct Cursor {
    int *face;         /* npatches + 1: next face of the internal faces, each patch */
    size_t *idx;       /* and its first point */
} Cursor;

/* Allocates out's faces and patches from the plan. */
static void mesh_alloc(const VoronoiInput *in, const Plan *pl, int ncells, Mesh *out, Cursor *cur)
{
    out->ncells = ncells;
    out->nfaces = pl->nface;
    out->ninternal = pl->nint;
    out->face_off = mem_alloc(sizeof(int) * ((size_t)pl->nface + 1));
    out->face_idx = mem_alloc(sizeof(int) * (pl->nidx > 0 ? pl->nidx : 1));
    out->owner = mem_alloc(sizeof(int) * (size_t)(pl->nface > 0 ? pl->nface : 1));
    out->neighbour = mem_alloc(sizeof(int) * (size_t)(pl->nint > 0 ? pl->nint : 1));
    out->face_off[0] = 0;
    out->npatches = in->npatches;
    out->patches = mem_calloc((size_t)in->npatches, sizeof(Patch));
    cur->face = mem_alloc(sizeof(int) * ((size_t)in->npatches + 1));
    cur->idx = mem_alloc(sizeof(size_t) * ((size_t)in->npatches + 1));
    cur->face[0] = 0;
    cur->idx[0] = 0;
    int f = pl->nint;
    size_t i = pl->iint;
    for (int p = 0; p < in->npatches; p++) {
        const Patch *P = &in->patches[p];
        Patch *Q = &out->patches[p];
        mesh_patch_copy(P, Q);
        Q->start = f;
        Q->size = pl->pface[p];
        cur->face[p + 1] = f;
        cur->idx[p + 1] = i;
        f += pl->pface[p];
        i += pl->pidx[p];
    }
}

/* Writes cell c's own faces into their places and measures the cell. */
static void put_cell(Assembly *A, Mesh *m, Cursor *cur, int c, VoronoiStats *vs)
{
    cell_face_list(A, c);   /* close_cells checked the edges */
    for (int k = 0; k < A->ncf; k++) {
        if (A->cf[k].rev) continue;
        int f = A->cf[k].f, o = face_other(A, f), slot = o >= 0 ? 0 : -o, g = cur->face[slot]++;
        size_t at = cur->idx[slot];
        memcpy(m->face_idx + at, A->st->idx + A->beg[f], sizeof(int) * (size_t)A->len[f]);
        cur->idx[slot] = at + (size_t)A->len[f];
        m->face_off[g + 1] = (int)cur->idx[slot];
        m->owner[g] = c;
        if (o >= 0) m->neighbour[g] = o;
    }
    measure_cell(A, c, vs);
}

/* The points: A's own array when every point is used (the usual case),
   else the used ones renumbered in order, as meshbuild does. */
static void mesh_points(Assembly *A, int np, Mesh *m, size_t nidx)
{
    char *used = mem_calloc((size_t)(np > 0 ? np : 1), 1);
    for (size_t k = 0; k < nidx; k++) used[m->face_idx[k]] = 1;
    int nu = 0;
    for (int p = 0; p < np; p++) nu += used[p];
    if (nu == np) {
        m->points = A->pts;
        A->pts = NULL;
    } else {
        int *pmap = mem_alloc(sizeof(int) * (size_t)np);
        m->points = mem_alloc(sizeof(double) * 3 * (size_t)(nu > 0 ? nu : 1));
        nu = 0;
        for (int p = 0; p < np; p++) {
            pmap[p] = used[p] ? nu : -1;
            if (used[p]) memcpy(m->points + 3 * (size_t)nu++, A->pts + 3 * (size_t)p, 3 * sizeof(double));
        }
        for (size_t k = 0; k < nidx; k++) m->face_idx[k] = pmap[m->face_idx[k]];
        free(pmap);
    }
    m->npoints = nu;
    free(used);
}

static int write_direct(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs)
{
    Cursor cur;
    mesh_alloc(A->in, pl, A->st->ncells, out, &cur);
    for (int c = 0; c < A->st->ncells; c++) put_cell(A, out, &cur, c, vs);
    mesh_points(A, np, out, pl->nidx);
    free(cur.face);
    free(cur.idx);
    return 0;
}

static int write_meshbuild(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs, Err *e)
{
    const VoronoiInput *in = A->in;
    MeshBuild b;
    meshbuild_init(&b);
    meshbuild_reserve(&b, (size_t)np, (size_t)pl->nface, pl->nidx);
    for (int p = 0; p < in->npatches; p++)
        meshbuild_patch(&b, in->patches[p].name, in->patches[p].type, in->patches[p].neighbour,
                        in->patches[p].groups);
    for (int p = 0; p < np; p++) meshbuild_point(&b, A->pts + 3 * p);
    for (int c = 0; c < A->st->ncells; c++) emit_cell(A, &b, c, vs);
    int rc = meshbuild_finish(&b, out, NULL, NULL, e);
    meshbuild_free(&b);
    return rc;
}

/* Largest angle between an internal face's normal and its seed segment. */
static double ortho_max(const Mesh *m, const VoronoiInput *in, const int *seed_of)
{
    double worst = 0, tan_worst = 0;
    for (int f = 0; f < m->ninternal; f++) {
        double S[3];
        poly_area(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], 0, S);
        const double *a = in->x + 3 * seed_of[m->owner[f]], *bx = in->x + 3 * seed_of[m->neighbour[f]];
        double d[3] = {bx[0] - a[0], bx[1] - a[1], bx[2] - a[2]};
        if (in->flat_axis >= 0) d[in->flat_axis] = 0;
        double c[3] = {S[1] * d[2] - S[2] * d[1], S[2] * d[0] - S[0] * d[2], S[0] * d[1] - S[1] * d[0]};
        double c2 = sq(c[0]) + sq(c[1]) + sq(c[2]), dot = S[0] * d[0] + S[1] * d[1] + S[2] * d[2];
        /* atan2 only for angles that may beat worst: tan < 0.999 tan(worst) cannot */
        if (dot > 0 && c2 < sq(0.999 * tan_worst * dot)) continue;
        double ang = atan2(sqrt(c2), dot);
        if (ang > worst) {
            worst = ang;
            tan_worst = worst < 1.5 ? tan(worst) : 0;
        }
    }
    return worst;
}

static int assemble(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e)
{
    const VoronoiInput *in = B->in;
    Store *s = &B->st;
    int flat = in->flat_axis;
    Assembly A = {0};
    A.in = in;
    A.st = s;
    A.cell_of = cell_of;
    A.seed_of = seed_of;
    int np = flat >= 0 ? 2 * B->w.npts : B->w.npts;
    A.pts = mem_alloc(sizeof(double) * 3 * (size_t)(np > 0 ? np : 1));
    if (flat >= 0) {
        for (int p = 0; p < B->w.npts; p++) {
            memcpy(A.pts + 6 * p, B->w.pts + 6 * p, 3 * sizeof(double));
            memcpy(A.pts + 6 * p + 3, B->w.pts + 6 * p, 3 * sizeof(double));
            A.pts[6 * p + 3 + flat] = in->hi[flat];
        }
    } else {
        memcpy(A.pts, B->w.pts, sizeof(double) * 3 * (size_t)np);
    }
    A.tol = VORONOI_MERGE * B->L;
    size_t nf1 = (size_t)(s->nf > 0 ? s->nf : 1);
    A.len = mem_alloc(sizeof(int) * nf1);
    A.beg = mem_alloc(sizeof(int) * nf1);
    int *uf = NULL;
    if (flat < 0) {
        uf = mem_alloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
        for (int p = 0; p < np; p++) uf[p] = p;
        collapse_tiny(&A, uf, sq(VORONOI_MERGE * B->L), 4 * VORONOI_MERGE * B->L);
    }
    weld_faces(&A, uf);
    free(uf);
    int rc = close_cells(&A, e);

    Plan pl;
    plan_faces(&A, &pl);
    if (vs) memset(vs, 0, sizeof *vs);
    if (!rc && pl.empty >= 0) rc = err_set(e, NULL, 0, "voronoi: the cell of seed %d has no face", seed_of[pl.empty]);
    if (!rc)
        rc = pl.direct ? write_direct(&A, &pl, np, out, vs) : write_meshbuild(&A, &pl, np, out, vs, e);
    plan_free(&pl);
    if (!rc && vs) {
        vs->ncells = s->ncells;
        vs->nfaces_dropped = A.ndropped;
        vs->ortho_max = ortho_max(out, in, seed_of);
    }
    free(A.pts);
    free(A.len);
    free(A.beg);
    free(A.cf);
    free(A.tpts);
    free(A.ends);
    free(A.tt);
    edges_free(&A.edges);
    return rc;
}

/* ---- 2-D: the prisms written straight from the polygons ------------- */

/* Does the edge labelled l of a polygon (n points) go from a to b? */
static int ring_has(const int *gid, const int *lab, int n, int l, int a, int b)
{
    for (int k = 0; k < n; k++)
        if (lab[k] == l) return gid[k] == a && gid[k + 1 < n ? k + 1 : 0] == b;
    return 0;
}

/* Is the general assembly a no-op on the prisms?  It is when no polygon
   has two points welded into one (no face shrinks or drops, each edge of
   the prism is used once each way) and every edge between two kept
   cells is the reverse of the other
   cell's edge (the cells share that face and are closed, and each
   internal face goes from its lower cell to a higher one).  Then the
   mesh is written from the polygons; otherwise the prisms go through the
   general assembly (repairs, dropped faces), which gives the same mesh
   in the regular case. */
static int rings_regular(const Build *B, const int *cell_of, const int *seed_of)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    for (int c = 0; c < B->st.ncells; c++) {
        int r0 = r->off[c], n = r->off[c + 1] - r0, i = seed_of[c];
        const int *gid = r->gid + r0, *lab = r->lab + r0;
        for (int k = 0; k < n; k++) {
            int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0], j = lab[k];
            for (int m = 0; m < k; m++)
                if (gid[m] == a) return 0;
            if (j < 0 || !in->keep[j]) continue;
            int d = cell_of[j], s0 = r->off[d];
            if (!ring_has(r->gid + s0, r->lab + s0, r->off[d + 1] - s0, i, b, a)) return 0;
        }
    }
    return 1;
}

/* The faces of one prism in label order, as (label, edge) pairs; edge n
   is the back face (at lo), n + 1 the front face. */
static int prism_order(const Build *B, const int *lab, int n, int *ord)
{
    int fa = B->in->flat_axis;
    for (int k = 0; k < n + 2; k++) {
        int l = k < n ? lab[k] : k == n ? -1 - 2 * fa : -1 - (2 * fa + 1), q = k;
        while (q > 0 && ord[2 * (q - 1)] > l) {
            ord[2 * q] = ord[2 * (q - 1)];
            ord[2 * q + 1] = ord[2 * (q - 1) + 1];
            q--;
        }
        ord[2 * q] = l;
        ord[2 * q + 1] = k;
    }
    return n + 2;
}

/* The slot (0: internal, 1 + p: patch p) of a face labelled l of seed
   i's cell, or -1 when the lower cell across owns it. */
static int prism_slot(const VoronoiInput *in, int i, int l)
{
    if (l < 0) return 1 + in->side_patch[-1 - l];
    if (!in->keep[l]) return 1 + in->patch[l];
    return l > i ? 0 : -1;
}

/* Counts the faces and points of each slot (as plan_faces). */
static void rings_plan(const Build *B, const int *seed_of, Plan *pl)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis;
    memset(pl, 0, sizeof *pl);
    pl->direct = 1;
    pl->empty = -1;
    pl->pface = mem_calloc((size_t)in->npatches, sizeof(int));
    pl->pidx = mem_calloc((size_t)in->npatches, sizeof(size_t));
    for (int c = 0; c < B->st.ncells; c++) {
        int r0 = r->off[c], n = r->off[c + 1] - r0, i = seed_of[c];
        for (int k = 0; k < n; k++) {
            int slot = prism_slot(in, i, r->lab[r0 + k]);
            if (slot < 0) continue;
            pl->nface++;
            pl->nidx += 4;
            if (slot == 0) {
                pl->nint++;
                pl->iint += 4;
            } else {
                pl->pface[slot - 1]++;
                pl->pidx[slot - 1] += 4;
            }
        }
        for (int s = 2 * fa; s <= 2 * fa + 1; s++) {
            pl->nface++;
            pl->nidx += (size_t)n;
            pl->pface[in->side_patch[s]]++;
            pl->pidx[in->side_patch[s]] += (size_t)n;
        }
    }
}

/* Writes cell c's own faces into their places (as put_cell) and its
   volume (area x thickness) into vs. */
static void put_prism(const Build *B, const int *cell_of, int c, int i, Mesh *m, Cursor *cur, int **ord,
                      int *ocap, VoronoiStats *vs)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    int r0 = r->off[c], n = r->off[c + 1] - r0;
    const int *gid = r->gid + r0, *lab = r->lab + r0;
    need(ord, ocap, 2 * (size_t)n + 4, sizeof(int));
    int nf = prism_order(B, lab, n, *ord);
    for (int q = 0; q < nf; q++) {
        int l = (*ord)[2 * q], k = (*ord)[2 * q + 1], slot = prism_slot(in, i, l);
        if (slot < 0) continue;
        int g = cur->face[slot]++;
        int *dst = m->face_idx + cur->idx[slot], len;
        if (k < n) {
            int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0];
            dst[0] = 2 * a;
            dst[1] = 2 * b;
            dst[2] = 2 * b + 1;
            dst[3] = 2 * a + 1;
            len = 4;
        } else if (k == n) {
            for (int p = 0; p < n; p++) dst[p] = 2 * gid[n - 1 - p];
            len = n;
        } else {
            for (int p = 0; p < n; p++) dst[p] = 2 * gid[p] + 1;
            len = n;
        }
        cur->idx[slot] += (size_t)len;
        m->face_off[g + 1] = (int)cur->idx[slot];
        m->owner[g] = c;
        if (slot == 0) m->neighbour[g] = cell_of[l];
    }
    if (!vs) return;
    int ua = (in->flat_axis + 1) % 3, va = (in->flat_axis + 2) % 3;
    const double *p0 = B->w.pts + 6 * (size_t)gid[0];
    double area = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *pa = B->w.pts + 6 * (size_t)gid[k], *pb = B->w.pts + 6 * (size_t)gid[k + 1];
        area += (pa[ua] - p0[ua]) * (pb[va] - p0[va]) - (pa[va] - p0[va]) * (pb[ua] - p0[ua]);
    }
    double vol = 0.5 * area * (in->hi[in->flat_axis] - in->lo[in->flat_axis]);
    if (c == 0 || vol < vs->vol_min) vs->vol_min = vol;
    vs->vol_total += vol;
}

/* The mesh of regular prisms (rings_regular): every weld point is used
   (each is on its cell's back and front faces). */
static void write_rings(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs)
{
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis, np = B->w.npts;
    Plan pl;
    Cursor cur;
    rings_plan(B, seed_of, &pl);
    mesh_alloc(in, &pl, B->st.ncells, out, &cur);
    if (vs) memset(vs, 0, sizeof *vs);
    int *ord = NULL, ocap = 0;
    for (int c = 0; c < B->st.ncells; c++) put_prism(B, cell_of, c, seed_of[c], out, &cur, &ord, &ocap, vs);
    free(ord);
    /* the weld's points have room for their copies at hi */
    out->points = mem_realloc(B->w.pts, sizeof(double) * 6 * (size_t)(np > 0 ? np : 1));
    B->w.pts = NULL;
    for (int p = 0; p < np; p++) {
        double *x = out->points + 6 * (size_t)p;
        memcpy(x + 3, x, 3 * sizeof(double));
        x[3 + fa] = in->hi[fa];
    }
    out->npoints = 2 * np;
    free(cur.face);
    free(cur.idx);
    plan_free(&pl);
    if (vs) {
        vs->ncells = B->st.ncells;
        vs->ortho_max = ortho_max(out, in, seed_of);
    }
}

/* 2-D: the prisms, written directly when regular, else through the
   general assembly. */
static int assemble2(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e)
{
    if (rings_regular(B, cell_of, seed_of)) {
        write_rings(B, cell_of, seed_of, out, vs);
        return 0;
    }
    Store *s = &B->st;
    need(&s->lab, &s->lcap, (size_t)B->rg.n + 2 * (size_t)s->ncells, sizeof(int));
    need(&s->off, &s->ocap, (size_t)B->rg.n + 2 * (size_t)s->ncells + 1, sizeof(int));
    need(&s->idx, &s->icap, 6 * (size_t)B->rg.n, sizeof(int));
    for (int c = 0; c < s->ncells; c++) {
        ring_store(B, c);
        s->cell_off[c + 1] = s->nf;
    }
    return assemble(B, cell_of, seed_of, out, vs, e);
}

/* ---- input ---------------------------------------------------------- */

static int check_input(const VoronoiInput *in, Err *e)
{
    if (in->nseeds <= 0 || !in->x || !in->keep) return err_set(e, NULL, 0, "voronoi: no seeds");
    if (in->flat_axis < -1 || in->flat_axis > 2)
        return err_set(e, NULL, 0, "voronoi: flat axis %d is not -1, 0, 1 or 2", in->flat_axis);
    for (int a = 0; a < 3; a++)
        if (!(in->lo[a] < in->hi[a]) || !isfinite(in->lo[a]) || !isfinite(in->hi[a]))
            return err_set(e, NULL, 0, "voronoi: empty box along axis %d: %g to %g", a, in->lo[a], in->hi[a]);
    if (in->npatches <= 0 || !in->patches) return err_set(e, NULL, 0, "voronoi: no patches");
    for (int s = 0; s < 6; s++)
        if (in->side_patch[s] < 0 || in->side_patch[s] >= in->npatches)
            return err_set(e, NULL, 0, "voronoi: box side %d has patch %d, not in 0..%d", s, in->side_patch[s],
                           in->npatches - 1);
    double L = 0;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis && in->hi[a] - in->lo[a] > L) L = in->hi[a] - in->lo[a];
    double tol = VORONOI_MERGE * L;
    int nkeep = 0;
    for (int i = 0; i < in->nseeds; i++) {
        const double *x = in->x + 3 * i;
        for (int a = 0; a < 3; a++)
            if (!isfinite(x[a])) return err_set(e, NULL, 0, "voronoi: seed %d is not finite", i);
        if (!in->keep[i]) {
            if (!in->patch || in->patch[i] < 0 || in->patch[i] >= in->npatches)
                return err_set(e, NULL, 0, "voronoi: dropped seed %d has patch %d, not in 0..%d", i,
                               in->patch ? in->patch[i] : -1, in->npatches - 1);
            continue;
        }
        nkeep++;
        for (int a = 0; a < 3; a++)
            if (a != in->flat_axis && (x[a] < in->lo[a] - tol || x[a] > in->hi[a] + tol))
                return err_set(e, NULL, 0, "voronoi: kept seed %d (%g %g %g) is outside the box", i, x[0], x[1],
                               x[2]);
    }
    if (!nkeep) return err_set(e, NULL, 0, "voronoi: no seed is kept");
    return 0;
}

int voronoi_mesh(const VoronoiInput *in, Mesh *out, int *seed_of, VoronoiStats *st, Err *e)
{
    mesh_init(out);
    if (check_input(in, e)) return -1;
    Build B;
    memset(&B, 0, sizeof B);
    B.in = in;
    B.L = 0;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis && in->hi[a] - in->lo[a] > B.L) B.L = in->hi[a] - in->lo[a];
    B.eps = EPS_CLIP * B.L;
    buckets_build(&B.g, in);
    int *cell_of = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    int *cells = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    int nc = 0;
    for (int i = 0; i < in->nseeds; i++) {
        cell_of[i] = in->keep[i] ? nc : -1;
        if (in->keep[i]) cells[nc++] = i;
    }
    size_t expect = (size_t)nc * (in->flat_axis >= 0 ? 2 : 7);
    weld_init(&B.w, &B.g, VORONOI_MERGE * B.L, in->flat_axis, in->flat_axis >= 0 ? 6 : 3, expect);
    if (in->flat_axis < 0) names_init(&B.names, in->nseeds, 4 * expect);
    B.cell_of = cell_of;
    B.st.ncells = nc;
    B.st.cell_off = mem_alloc(sizeof(int) * (size_t)(nc + 1));
    B.st.cell_off[0] = 0;
    int rc = 0;
    if (in->flat_axis >= 0) {
        B.rg.off = mem_alloc(sizeof(int) * (size_t)(nc + 1));
        B.rg.off[0] = 0;
        /* a lattice's polygons have 4 points */
        need(&B.rg.gid, &B.rg.gcap, 4 * (size_t)nc, sizeof(int));
        need(&B.rg.lab, &B.rg.lcap, 4 * (size_t)nc, sizeof(int));
        for (int c = 0; c < nc && !rc; c++) {
            rc = cell2(&B, cells[c], e);
            B.rg.off[c + 1] = B.rg.n;
        }
        if (!rc) rc = assemble2(&B, cell_of, cells, out, st, e);
    } else {
        /* 3-D cells have 6 (lattice) to about 16 faces (random), 4 to 6
           points each */
        size_t fpc = 10;
        need(&B.st.lab, &B.st.lcap, fpc * (size_t)nc, sizeof(int));
        need(&B.st.off, &B.st.ocap, fpc * (size_t)nc + 1, sizeof(int));
        need(&B.st.idx, &B.st.icap, 4 * fpc * (size_t)nc, sizeof(int));
        for (int c = 0; c < nc && !rc; c++) {
            rc = cell3(&B, cells[c], e);
            B.st.cell_off[c + 1] = B.st.nf;
        }
        if (!rc) rc = assemble(&B, cell_of, cells, out, st, e);
    }
    if (!rc && seed_of) memcpy(seed_of, cells, sizeof(int) * (size_t)nc);
    buckets_free(&B.g);
    free(B.s.cand);
    clip_free(&B.c3);
    clip2_free(&B.c2);
    weld_free(&B.w);
    names_free(&B.names);
    store_free(&B.st);
    rings_free(&B.rg);
    free(B.gid);
    free(B.vlab);
    free(B.tmp);
    free(cell_of);
    free(cells);
    if (rc) mesh_free(out);
    return rc;
}
