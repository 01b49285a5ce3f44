/*
** seeds.c: Voronoi seeds for a boundary-conforming grid (seeds.h; spec
** granular-model.md §2.4, thesis §3.2.4, eq. 3.2-3.3).
**
** Spacings.  h is the smallest mean cell width of the block grid over its
** axes (the in-plane axes in 2-D): graded grids get one global spacing.
** The boundary is sampled with hs = spacing h, the seeds of a sample point
** are offset by multiples of hs/2, and a = min_spacing h.
**
** Order and rules, in the order seeds are considered (a seed is dropped
** when it is closer than a to a seed kept before it, or coincides with one
** when a = 0: a dense bucket grid of cells 2a or wider, so the kept set
** keeps every pair at least a apart):
**   1. boundary pairs: for every sample point p with normal n (out of the
**      flow, geometry_sample_box with the grid's box) the exterior seed
**      p + (hs/2) n, then the interior seed p - (hs/2) n (eq. 3.2-3.3,
**      i = 0); an exterior seed must lie outside the flow domain, an
**      interior one inside it and at least a/2 inside the grid's box (a
**      seed nearer a box side would have a cell thinner than the minimum
**      spacing promises);
**   2. boundary layers: p - (2i+1)(hs/2) n for i = 1..layers, layer by
**      layer over all sample points (so a deep layer never displaces a
**      shallower one), with the interior rules of 1;
**   3. Cartesian cell centres, in cell order, except those closer than a
**      to a kept seed and those in the boundary band [our rule for spec
**      §2.4's GAP]: with p, n the sample point nearest to the centre c,
**      the depth d = (p - c).n (c's signed distance from the tangent
**      plane at p, positive on the flow side) must satisfy
**      d >= (2 layers + 1) hs/2 + a/2 for a centre in the flow (beyond the
**      innermost layer by half the minimum spacing) and d <= -(hs/2 + a/2)
**      for a centre in the solid (beyond the exterior seeds).  Only
**      sample points within that band plus hs are looked at; a centre
**      with none nearer keeps its place.  Centres in the solid are kept
**      as exterior seeds (interior 0, the surface of the nearest leaf):
**      they close the exterior so no kept cell can reach through a part
**      of the boundary the sampling missed.
** Corners and edges (thesis Fig. 3.16): shape_sample and geometry_sample
** put sample points exactly on edges and corners with the normalised sum
** n of the faces' normals.  At a point on exactly two faces (normal n1 of
** the nearest face from geometry_normal, n2 = 2 (n.n1) n - n1, confirmed
** as the normal found just beside the edge on face 2's side) the pair is
** shared as in Fig. 3.16: one seed s at distance hs/2 from both faces,
** s = p -+ (hs/2) n / (n.n1), on the convex side (interior at a convex
** edge of the flow, exterior at a convex edge of the solid), and its
** mirror images s +- hs n_j across each face on the other side, so the
** bisector planes between them are the two faces.  Points on three or
** more faces (box corners) keep one pair along n: an approximation that
** lets the kept cells bulge out of the faces by up to about hs/3 right
** at the corner.  Measured on a box (0.48 x 0.39 x 0.43) in a grid of
** h = 0.1, by 40000 random points classified by their nearest seed: the
** region of kept cells differs from the flow domain in 0.69 % of the
** unit box (1.28 % with the mean-normal pair at the edges too), for the
** flow inside and outside alike.
** 2-D: geometry queries use the section at the grid's mid-plane (the
** geometry is flattened there for the queries) and every seed lies in that
** plane.  Samples outside the grid's box are ignored, so a geometry whose
** surfaces all lie outside the box gives exactly the Cartesian centres.
*/
#include "seeds.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "voronoi.h"

/* ---- bucket hash: items by cell of a uniform grid, unbounded extent ---- */

typedef struct Hash {
    double cell;
    size_t cap;        /* slots, a power of two */
    size_t used;
    uint64_t *key;     /* slot keys (0: empty) */
    int *head;         /* slot: last item inserted there */
    int *next;         /* item: the previous item in its cell, -1 */
    const double *x;   /* item coordinates (3 per item) */
    int64_t cmin[3], cmax[3];  /* range of occupied cells per axis: a
                                  query skips the empty layers beyond it
                                  (in 2-D every item is in one layer) */
} Hash;

static void hash_init(Hash *H, double cell, const double *x, int nmax)
{
    H->cell = cell;
    H->cap = 1024;
    H->used = 0;
    H->key = MEM_NEW(uint64_t, H->cap);
    H->head = MEM_NEW(int, H->cap);
    H->next = MEM_NEW(int, nmax);
    H->x = x;
    for (int k = 0; k < 3; k++) H->cmin[k] = INT64_MAX, H->cmax[k] = INT64_MIN;
}

static void hash_free(Hash *H)
{
    free(H->key);
    free(H->head);
    free(H->next);
}

static int64_t hash_coord(const Hash *H, double v)
{
    double c = floor(v / H->cell);
    return c < -1048000 ? -1048000 : c > 1048000 ? 1048000 : (int64_t)c;
}

/* Cell (i, j, k) as a non-zero key. */
static uint64_t hash_key(int64_t i, int64_t j, int64_t k)
{
    return ((uint64_t)(i + 1048576) << 42) | ((uint64_t)(j + 1048576) << 21) | (uint64_t)(k + 1048576);
}

static size_t hash_slot(const Hash *H, uint64_t key)
{
    uint64_t z = key * 0x9E3779B97F4A7C15ull;
    size_t s = (size_t)(z ^ (z >> 29)) & (H->cap - 1);
    while (H->key[s] && H->key[s] != key) s = (s + 1) & (H->cap - 1);
    return s;
}

static void hash_grow(Hash *H)
{
    uint64_t *key = H->key;
    int *head = H->head;
    size_t cap = H->cap;
    H->cap *= 2;
    H->key = MEM_NEW(uint64_t, H->cap);
    H->head = MEM_NEW(int, H->cap);
    for (size_t s = 0; s < cap; s++)
        if (key[s]) {
            size_t t = hash_slot(H, key[s]);
            H->key[t] = key[s];
            H->head[t] = head[s];
        }
    free(key);
    free(head);
}

static void hash_insert(Hash *H, int item)
{
    const double *x = H->x + 3 * (size_t)item;
    int64_t c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = hash_coord(H, x[k]);
        if (c[k] < H->cmin[k]) H->cmin[k] = c[k];
        if (c[k] > H->cmax[k]) H->cmax[k] = c[k];
    }
    uint64_t key = hash_key(c[0], c[1], c[2]);
    if (2 * (H->used + 1) > H->cap) hash_grow(H);
    size_t s = hash_slot(H, key);
    if (!H->key[s]) {
        H->key[s] = key;
        H->head[s] = -1;
        H->used++;
    }
    H->next[item] = H->head[s];
    H->head[s] = item;
}

/* The cells a query at x reaching r (r <= cell) must look at, per axis:
   those the interval [x - r, x + r] meets, inside the occupied range.
   Cells are visited in increasing order, so the nearest item among equals
   is the one found first, as when all 27 neighbours were visited. */
static void hash_range(const Hash *H, const double x[3], double r, int64_t lo[3], int64_t hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = hash_coord(H, x[k] - 1.001 * r);   /* margin: round-off of x +- r */
        hi[k] = hash_coord(H, x[k] + 1.001 * r);
        int64_t c = hash_coord(H, x[k]);
        if (lo[k] < c - 1) lo[k] = c - 1;
        if (hi[k] > c + 1) hi[k] = c + 1;
        if (lo[k] < H->cmin[k]) lo[k] = H->cmin[k];
        if (hi[k] > H->cmax[k]) hi[k] = H->cmax[k];
    }
}

/* The item nearest to x closer than r (r <= cell), or -1. */
static int hash_nearest(const Hash *H, const double x[3], double r)
{
    int64_t lo[3], hi[3];
    hash_range(H, x, r, lo, hi);
    int best = -1;
    double bd = r * r;
    for (int64_t i = lo[0]; i <= hi[0]; i++)
        for (int64_t j = lo[1]; j <= hi[1]; j++)
            for (int64_t k = lo[2]; k <= hi[2]; k++) {
                size_t s = hash_slot(H, hash_key(i, j, k));
                if (!H->key[s]) continue;
                for (int it = H->head[s]; it >= 0; it = H->next[it]) {
                    const double *y = H->x + 3 * (size_t)it;
                    double d = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1])
                             + (x[2] - y[2]) * (x[2] - y[2]);
                    if (d < bd) bd = d, best = it;
                }
            }
    return best;
}

/* ---- dense grid: the kept seeds ---- */

/* The kept seeds by cell of a dense grid over the box and a margin of one
   cell: neighbouring cells are neighbours in memory, where the hash above
   sends every probe to a random slot (most of seeds_make's time on big
   grids).  Seeds beyond the margin go to the border cells, which only
   makes them look nearer to the search than they are, so it stays exact.
   Cells are at least 2a wide, so a query of radius a meets at most 2 per
   axis; a box too elongated for the seed count gets wider cells. */
typedef struct Near {
    double cell;
    double base[3];    /* coordinate of the first cell's low side */
    int n[3];
    int *head;         /* per cell: last item inserted, -1 */
    int *next;         /* per item: the previous item in its cell, -1 */
    const double *x;
} Near;

static void near_init(Near *G, double cell, const double lo[3], const double hi[3], const double *x, int nmax)
{
    double total;
    for (;;) {
        total = 1;
        for (int k = 0; k < 3; k++) {
            G->base[k] = (floor(lo[k] / cell) - 1) * cell;
            G->n[k] = (int)fmin(ceil((hi[k] - G->base[k]) / cell) + 1, 1 << 20);
            total *= G->n[k];
        }
        if (total <= 4.0 * nmax + 4096) break;
        cell *= 2;
    }
    G->cell = cell;
    G->head = MEM_NEW(int, (size_t)total);
    memset(G->head, 0xff, sizeof(int) * (size_t)total);
    G->next = MEM_NEW(int, nmax > 0 ? nmax : 1);
    G->x = x;
}

static void near_free(Near *G)
{
    free(G->head);
    free(G->next);
}

static int near_axis(const Near *G, int k, double v)
{
    double t = floor((v - G->base[k]) / G->cell);
    return !(t > 0) ? 0 : t >= G->n[k] ? G->n[k] - 1 : (int)t;
}

static void near_insert(Near *G, int item)
{
    const double *x = G->x + 3 * (size_t)item;
    size_t c = (size_t)near_axis(G, 0, x[0])
             + (size_t)G->n[0] * ((size_t)near_axis(G, 1, x[1]) + (size_t)G->n[1] * (size_t)near_axis(G, 2, x[2]));
    G->next[item] = G->head[c];
    G->head[c] = item;
}

/* Is an item closer than r (r <= cell) to x? */
static int near_any(const Near *G, const double x[3], double r)
{
    int lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = near_axis(G, k, x[k] - 1.001 * r);   /* margin: round-off of x +- r */
        hi[k] = near_axis(G, k, x[k] + 1.001 * r);
    }
    for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
            for (int i = lo[0]; i <= hi[0]; i++)
                for (int it = G->head[i + (size_t)G->n[0] * (j + (size_t)G->n[1] * k)]; it >= 0; it = G->next[it]) {
                    const double *y = G->x + 3 * (size_t)it;
                    if ((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1])
                        + (x[2] - y[2]) * (x[2] - y[2]) < r * r)
                        return 1;
                }
    return 0;
}

/* ---- the seed set under construction ---- */

typedef struct Build {
    Seeds *s;
    int cap;
    Near kept;          /* kept seeds */
    double a;
    double dup;         /* seeds closer than this would be one point to
                           voronoi_mesh (VORONOI_MERGE x box size) */
    const Geometry *g;
    int flat;
    double lo[3], hi[3];
} Build;

static int fits_box(const Build *B, const double x[3], double margin)
{
    for (int k = 0; k < 3; k++)
        if (k != B->flat && !(x[k] >= B->lo[k] + margin && x[k] <= B->hi[k] - margin)) return 0;
    return 1;
}

/* Keeps x when no kept seed is closer than a. */
static int try_add(Build *B, const double x[3], int interior, int surface, int kind, const double n[3])
{
    if (near_any(&B->kept, x, fmax(B->a, B->dup))) return 0;
    Seeds *s = B->s;
    int i = s->n++;
    memcpy(s->x + 3 * (size_t)i, x, 3 * sizeof *x);
    s->interior[i] = (char)interior;
    s->surface[i] = surface;
    s->kind[i] = kind;
    for (int k = 0; k < 3; k++) s->normal[3 * (size_t)i + k] = n ? n[k] : 0;
    near_insert(&B->kept, i);
    return 1;
}

static void seeds_alloc(Seeds *s, int cap)
{
    memset(s, 0, sizeof *s);
    s->x = MEM_NEW(double, 3 * (size_t)cap);
    s->interior = MEM_NEW(char, cap);
    s->surface = MEM_NEW(int, cap);
    s->kind = MEM_NEW(int, cap);
    s->normal = MEM_NEW(double, 3 * (size_t)cap);
}

void seeds_opts_default(SeedOpts *o)
{
    o->layers = 0;
    o->spacing = 1;
    o->min_spacing = 0.5;
}

const DictKey seeds_keys[] = {
    {"layers", "0", "boundary layers b: interior seeds at depths (2i+1) h/2, i = 0..b (0..1000)"},
    {"spacing", "1", "boundary seed spacing as a multiple of the grid spacing h, in (0, 4]"},
    {"minSpacing", "0.5", "minimum seed spacing a as a multiple of h, in [0, spacing]: every cell's volume is "
                          "at least pi a^3/6 (2-D: pi a^2/4 per unit thickness)"},
    {NULL, NULL, NULL}};

static int bad_value(Err *e, const char *path, const Dict *d, const char *key, const char *what)
{
    const DictEntry *en = dict_find(d, key);
    return err_set(e, path, en ? en->line : 0, "%s", what);
}

static int check_dict_opts(const SeedOpts *o, const char *path, const Dict *d, Err *e)
{
    char msg[160];
    if (!(o->layers >= 0 && o->layers <= 1000)) {
        snprintf(msg, sizeof msg, "layers must be in 0..1000, found %d", o->layers);
        return bad_value(e, path, d, "layers", msg);
    }
    if (!(o->spacing > 0 && o->spacing <= 4)) {
        snprintf(msg, sizeof msg, "spacing must be in (0, 4], found %g", o->spacing);
        return bad_value(e, path, d, "spacing", msg);
    }
    if (!(o->min_spacing >= 0 && o->min_spacing <= o->spacing)) {
        snprintf(msg, sizeof msg, "minSpacing must be in [0, spacing = %g], found %g", o->spacing, o->min_spacing);
        return bad_value(e, path, d, "minSpacing", msg);
    }
    return 0;
}

int seeds_read_opts(const char *path, SeedOpts *o, Err *e)
{
    seeds_opts_default(o);
    Dict *d = dict_read(path, e);
    int rc = !d || dict_check_keys(d, seeds_keys, e) || dict_label_or(d, "layers", o->layers, &o->layers, e) ||
             dict_scalar_or(d, "spacing", o->spacing, &o->spacing, e) ||
             dict_scalar_or(d, "minSpacing", o->min_spacing, &o->min_spacing, e) || check_dict_opts(o, path, d, e);
    dict_free(d);
    return rc ? -1 : 0;
}

void seeds_free(Seeds *s)
{
    free(s->x);
    free(s->interior);
    free(s->surface);
    free(s->kind);
    free(s->normal);
    memset(s, 0, sizeof *s);
}

/* Boundary seeds of layer i (-1: exterior) for every sample point. */
static void boundary_layer(Build *B, int i, const double *px, const double *pn, const int *pl, int np, double hs,
                           const char *skip)
{
    for (int p = 0; p < np; p++) {
        if (skip && skip[p]) continue;
        const double *x = px + 3 * (size_t)p, *n = pn + 3 * (size_t)p;
        double off = i < 0 ? hs / 2 : -(2 * i + 1) * hs / 2, y[3];
        for (int k = 0; k < 3; k++) y[k] = x[k] + off * n[k];
        int fluid = geometry_fluid(B->g, y);
        if (i < 0) {
            if (!fluid) try_add(B, y, 0, B->g->leaves[pl[p]].surface, SEED_BOUNDARY, n);
        } else if (fluid && fits_box(B, y, B->a / 2)) {
            try_add(B, y, 1, -1, SEED_BOUNDARY, n);
        }
    }
}

/* The seeds of an edge between faces of normals n1, n2 (the domain's,
   into the solid; surfaces s1, s2 for the exterior seeds across each):
   one seed s at distance hs/2 from both faces on the convex side
   (interior at a convex edge of the flow, exterior at a convex edge of the
   solid) and its mirror images s +- hs n_f across each face, so the
   bisectors between them are the two faces (Fig. 3.16). */
static void edge_seeds(Build *B, const double x[3], const double n1[3], const double n2[3], int s1, int s2,
                       double hs)
{
    double n[3], si[3], y[3], eps = 1e-7 * hs;
    for (int k = 0; k < 3; k++) n[k] = n1[k] + n2[k];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] /= len;
    double c = n1[0] * n[0] + n1[1] * n[1] + n1[2] * n[2];
    /* on the flow side of face 1 and the solid side of face 2: fluid only
       at a convex edge of the solid.  sgn +1: convex edge of the flow
       (shared interior seed), -1: convex edge of the solid (shared
       exterior seed) */
    for (int k = 0; k < 3; k++) y[k] = x[k] - eps * n1[k] + eps * n2[k];
    double sgn = geometry_fluid(B->g, y) ? -1 : 1;
    for (int k = 0; k < 3; k++) si[k] = x[k] - sgn * hs / 2 / c * n[k];
    if (sgn < 0 && !geometry_fluid(B->g, si)) try_add(B, si, 0, s1, SEED_BOUNDARY, n);
    for (int f = 0; f < 2; f++) {
        const double *nf = f ? n2 : n1;
        double ye[3];
        for (int k = 0; k < 3; k++) ye[k] = si[k] + sgn * hs * nf[k];
        if (sgn > 0 && !geometry_fluid(B->g, ye)) try_add(B, ye, 0, f ? s2 : s1, SEED_BOUNDARY, n);
        if (sgn < 0 && geometry_fluid(B->g, ye) && fits_box(B, ye, B->a / 2)) try_add(B, ye, 1, -1, SEED_BOUNDARY, n);
    }
    if (sgn > 0 && geometry_fluid(B->g, si) && fits_box(B, si, B->a / 2)) try_add(B, si, 1, -1, SEED_BOUNDARY, n);
}

/* Is nf the normal of a face of leaf just beside x: at x + eps d or at
   x - eps d (towards the solid or the flow, whichever side the face is
   on), is the nearest face's normal nf?  Tells the faces meeting at an
   edge or corner point. */
static int face_beside(const Build *B, int leaf, const double x[3], const double d[3], double eps, const double nf[3])
{
    for (int sg = -1; sg <= 1; sg += 2) {
        double z[3], nz[3];
        for (int k = 0; k < 3; k++) z[k] = x[k] + sg * eps * d[k];
        geometry_normal(B->g, leaf, z, nz);
        if (fabs(nz[0] - nf[0]) + fabs(nz[1] - nf[1]) + fabs(nz[2] - nf[2]) < 1e-6) return 1;
    }
    return 0;
}

/* Fig. 3.16 at an edge of a primitive: x is on two faces when the
   normal n1 of the nearest face (geometry_normal) and its mirror n2 in
   the mean normal n, n2 = 2 (n.n1) n - n1, is confirmed as the normal
   just beside the edge on face 2's side; then edge_seeds.  Returns 0
   (nothing added) for points on one face or on three or more. */
static int convex_edge(Build *B, const double x[3], const double n[3], int leaf, double hs)
{
    double n1[3], n2[3], c;
    geometry_normal(B->g, leaf, x, n1);
    c = n1[0] * n[0] + n1[1] * n[1] + n1[2] * n[2];
    if (!(c > 0.1 && c < 1 - 1e-9)) return 0;
    double eps = 1e-7 * hs;
    for (int k = 0; k < 3; k++) n2[k] = 2 * c * n[k] - n1[k];
    /* n2 must be a face's normal there (else x is a corner of three or
       more faces): a point just beside the edge, off face 1 towards face
       2, has it as its nearest face's normal */
    double d[3] = {n2[0] - n1[0], n2[1] - n1[1], n2[2] - n1[2]};
    if (!face_beside(B, leaf, x, d, eps, n2)) return 0;
    int surf = B->g->leaves[leaf].surface;
    edge_seeds(B, x, n1, n2, surf, surf, hs);
    return 1;
}

/* Fig. 3.16 at a corner of three mutually orthogonal faces (boxes, turned
   or not): x is on three faces when its mean normal n makes 1/sqrt 3 with
   the nearest face's normal n1 and the other two, n2, n3, are unit,
   orthogonal, and sum with n1 to sqrt 3 n.  The seeds are the eight
   corners of the cube of side hs centred on x, the flow's corner
   interior: one seed on the flow's side of all three faces (convex corner
   of the flow) or on the solid's side (convex corner of the solid) and
   its mirror images across every set of faces, so the bisectors are the
   three faces.  Returns 0 (nothing added) elsewhere. */
static int orthogonal_corner(Build *B, const double x[3], const double n[3], int leaf, double hs)
{
    double nf[3][3], v[3], w[3];
    geometry_normal(B->g, leaf, x, nf[0]);
    double c = nf[0][0] * n[0] + nf[0][1] * n[1] + nf[0][2] * n[2];
    if (fabs(c - 1 / sqrt(3.0)) > 1e-9) return 0;
    for (int k = 0; k < 3; k++) v[k] = sqrt(3.0) * n[k] - nf[0][k];
    w[0] = nf[0][1] * v[2] - nf[0][2] * v[1];
    w[1] = nf[0][2] * v[0] - nf[0][0] * v[2];
    w[2] = nf[0][0] * v[1] - nf[0][1] * v[0];
    /* |n1 x v| = sqrt 2 for orthogonal faces, so w = n2 - n3 */
    for (int k = 0; k < 3; k++) {
        nf[1][k] = 0.5 * (v[k] + w[k]);
        nf[2][k] = 0.5 * (v[k] - w[k]);
    }
    /* each must be a face's normal: a point just beside the corner on
       face f, off the two others (towards the solid or the flow, as the
       corner is convex for one or the other), has it as its nearest
       face's normal */
    double eps = 1e-7 * hs;
    for (int f = 1; f < 3; f++) {
        double d[3];
        for (int k = 0; k < 3; k++) d[k] = nf[(f + 1) % 3][k] + nf[(f + 2) % 3][k];
        if (!face_beside(B, leaf, x, d, eps, nf[f])) return 0;
    }
    /* on the flow side of face 1 and the solid side of faces 2, 3: fluid
       only at a convex corner of the solid (flow around a box) */
    double y[3];
    for (int k = 0; k < 3; k++) y[k] = x[k] - eps * nf[0][k] + eps * (nf[1][k] + nf[2][k]);
    double sgn = geometry_fluid(B->g, y) ? -1 : 1;
    int surf = B->g->leaves[leaf].surface;
    for (int m = 0; m < 8; m++) {
        /* bit f of m: across face f from the shared seed */
        double s[3];
        for (int k = 0; k < 3; k++) s[k] = x[k];
        for (int f = 0; f < 3; f++) {
            int across = (m >> f) & 1;
            for (int k = 0; k < 3; k++) s[k] += (across ? 0.5 : -0.5) * sgn * hs * nf[f][k];
        }
        /* convex flow corner: only the shared seed (m = 0) is interior;
           convex solid corner: only the shared seed is exterior */
        int interior = sgn > 0 ? m == 0 : m != 0;
        if (interior) {
            if (geometry_fluid(B->g, s) && fits_box(B, s, B->a / 2)) try_add(B, s, 1, -1, SEED_BOUNDARY, n);
        } else if (!geometry_fluid(B->g, s)) {
            try_add(B, s, 0, surf, SEED_BOUNDARY, n);
        }
    }
    return 1;
}

/* Edges where two CSG operands meet (geometry_sample_curves), thinned
   to points about 3/4 hs apart, each with the edge rule of its two
   surfaces. */
static void csg_curves(Build *B, const double *px, const int *pl, int np, double hs)
{
    double *cx;
    int *la, *lb;
    int nc = geometry_sample_curves(B->g, hs, px, pl, np, &cx, &la, &lb);
    if (nc > 0) {
        Near G;
        near_init(&G, hs, B->lo, B->hi, cx, nc);
        for (int i = 0; i < nc; i++) {
            const double *q = cx + 3 * (size_t)i;
            if (near_any(&G, q, 0.75 * hs) || !fits_box(B, q, 0)) continue;
            near_insert(&G, i);
            double n1[3], n2[3];
            geometry_normal(B->g, la[i], q, n1);
            geometry_normal(B->g, lb[i], q, n2);
            edge_seeds(B, q, n1, n2, B->g->leaves[la[i]].surface, B->g->leaves[lb[i]].surface, hs);
        }
        near_free(&G);
    }
    free(cx);
    free(la);
    free(lb);
}

/* The first pass: corners, then edges, then each other point's exterior
   and interior seed.  Corners and edges first: their seeds replace the
   faces' first pairs, half a spacing from them (shape.c samp_box), not
   the other way round.  done[p] is set for corner and edge points: they
   get no layer seeds, since the layers of the faces' samples already
   form the lattice of nested layers around an edge (the samples half a
   spacing from it give the layers' seeds nearest to it). */
static void boundary_pairs(Build *B, const double *px, const double *pn, const int *pl, int np, double hs, char *done)
{
    for (int p = 0; p < np; p++) done[p] = (char)orthogonal_corner(B, px + 3 * (size_t)p, pn + 3 * (size_t)p, pl[p], hs);
    for (int p = 0; p < np; p++)
        if (!done[p]) done[p] = (char)convex_edge(B, px + 3 * (size_t)p, pn + 3 * (size_t)p, pl[p], hs);
    csg_curves(B, px, pl, np, hs);
    for (int p = 0; p < np; p++) {
        if (done[p]) continue;
        boundary_layer(B, -1, px + 3 * (size_t)p, pn + 3 * (size_t)p, pl + p, 1, hs, NULL);
        boundary_layer(B, 0, px + 3 * (size_t)p, pn + 3 * (size_t)p, pl + p, 1, hs, NULL);
    }
}

/* Rule 3's band test: 1 when centre c (fluid or not) keeps its place. */
static int outside_band(const Hash *samples, const double *pn, const double c[3], int fluid, double in_band,
                        double out_band, double reach)
{
    int p = hash_nearest(samples, c, reach);
    if (p < 0) return 1;
    const double *x = samples->x + 3 * (size_t)p, *n = pn + 3 * (size_t)p;
    double d = (x[0] - c[0]) * n[0] + (x[1] - c[1]) * n[1] + (x[2] - c[2]) * n[2];
    return fluid ? d >= in_band : d <= -out_band;
}

static void cartesian(Build *B, const Mesh *grid, const Hash *samples, const double *pn, double in_band,
                      double out_band, double reach, double mid)
{
    const CartGrid *cg = &grid->cart;
    for (int k = 0; k < cg->n[2]; k++)
        for (int j = 0; j < cg->n[1]; j++)
            for (int i = 0; i < cg->n[0]; i++) {
                int idx[3] = {i, j, k};
                double c[3];
                for (int a = 0; a < 3; a++) c[a] = 0.5 * (cg->x[a][idx[a]] + cg->x[a][idx[a] + 1]);
                if (B->flat >= 0) c[B->flat] = mid;
                int fluid = geometry_fluid(B->g, c);
                if (!outside_band(samples, pn, c, fluid, in_band, out_band, reach)) continue;
                int surf = fluid ? -1 : B->g->leaves[geometry_nearest_leaf(B->g, c)].surface;
                try_add(B, c, fluid, surf, SEED_CARTESIAN, NULL);
            }
}

/* With a = 0 (minSpacing 0) a Cartesian centre can fall exactly on a
   boundary seed (a surface on a grid plane, its interior seed h/2 inside,
   as the centres are), and voronoi_mesh rejects coincident seeds: such a
   seed is dropped like one closer than a.  The margin covers the strict
   test of near_any against voronoi_mesh's <=. */
static double dup_distance(const Build *B)
{
    double L = 0;
    for (int k = 0; k < 3; k++)
        if (k != B->flat) L = fmax(L, B->hi[k] - B->lo[k]);
    return 2 * VORONOI_MERGE * L;
}

static int check_opts(const SeedOpts *o, Err *e)
{
    if (o->layers < 0 || o->layers > 1000)
        return err_set(e, NULL, 0, "seeds: layers must be 0..1000, found %d", o->layers);
    if (!(o->spacing > 0) || !isfinite(o->spacing))
        return err_set(e, NULL, 0, "seeds: boundary spacing must be positive, found %g", o->spacing);
    if (!(o->min_spacing >= 0) || !isfinite(o->min_spacing))
        return err_set(e, NULL, 0, "seeds: minimum spacing must be non-negative, found %g", o->min_spacing);
    return 0;
}

/* Box, 2-D axis and spacing h of the block grid. */
static int grid_frame(const Mesh *grid, const Geometry *g, Build *B, double *h, Err *e)
{
    const CartGrid *cg = &grid->cart;
    if (cg->n[0] <= 0 || cg->n[1] <= 0 || cg->n[2] <= 0 || !cg->x[0] || !cg->x[1] || !cg->x[2])
        return err_set(e, NULL, 0, "seeds: the grid has no Cartesian extras (cartesianGrid): make it with blockGrid");
    B->flat = mesh_empty_axis(grid);
    if (B->flat < 0 && g->flat_axis >= 0)
        return err_set(e, g->file, 0, "seeds: the geometry is flattened but the grid is 3-D");
    *h = INFINITY;
    for (int k = 0; k < 3; k++) {
        B->lo[k] = cg->x[k][0];
        B->hi[k] = cg->x[k][cg->n[k]];
        if (k != B->flat) *h = fmin(*h, (B->hi[k] - B->lo[k]) / cg->n[k]);
    }
    if (!(*h > 0) || !isfinite(*h)) return err_set(e, NULL, 0, "seeds: the grid's cells have no positive width");
    return 0;
}

int seeds_make(const Mesh *grid, const Geometry *g, const SeedOpts *o, Seeds *s, Err *e)
{
    memset(s, 0, sizeof *s);
    Build B;
    memset(&B, 0, sizeof B);
    double h = 0;
    if (check_opts(o, e) || grid_frame(grid, g, &B, &h, e)) return -1;
    Geometry flat = *g;
    double mid = 0;
    if (B.flat >= 0) {
        mid = 0.5 * (B.lo[B.flat] + B.hi[B.flat]);
        flat.flat_axis = B.flat;
        flat.flat_coord = mid;
    }
    B.g = &flat;
    double hs = o->spacing * h;
    B.a = o->min_spacing * h;
    double *px, *pn;
    int *pl;
    int np = geometry_sample_box(&flat, hs, B.lo, B.hi, &px, &pn, &pl);
    int ncart = grid->cart.n[0] * grid->cart.n[1] * grid->cart.n[2];
    int cap = np * (o->layers + 2) + ncart;
    seeds_alloc(s, cap);
    B.s = s;
    B.dup = dup_distance(&B);
    near_init(&B.kept, fmax(2 * B.a, h), B.lo, B.hi, s->x, cap);
    char *edge = mem_calloc((size_t)(np > 0 ? np : 1), 1);
    boundary_pairs(&B, px, pn, pl, np, hs, edge);
    for (int i = 1; i <= o->layers; i++) boundary_layer(&B, i, px, pn, pl, np, hs, edge);
    free(edge);
    double in_band = (2 * o->layers + 1) * hs / 2 + B.a / 2, out_band = hs / 2 + B.a / 2;
    double reach = in_band + hs;
    Hash samples;
    hash_init(&samples, reach, px, np > 0 ? np : 1);
    for (int p = 0; p < np; p++) hash_insert(&samples, p);
    cartesian(&B, grid, &samples, pn, in_band, out_band, reach, mid);
    hash_free(&samples);
    near_free(&B.kept);
    free(px);
    free(pn);
    free(pl);
    int nin = 0;
    for (int i = 0; i < s->n; i++) nin += s->interior[i];
    if (nin == 0) {
        seeds_free(s);
        return err_set(e, g->file, 0, "seeds: no cell centre or boundary seed lies in the flow domain");
    }
    return 0;
}
