/*
** geometry_sample.c: points spread evenly over the flow domain's
** boundary (geometry_sample, geometry_sample_box) and on the curves where
** two primitives' surfaces meet on an edge of the domain
** (geometry_sample_curves), for voronoiGrid's seeds (seeds.c).  The tree
** it walks is csg.h's; each leaf is sampled on its own (shape_sample for
** primitives) and the domain keeps the points on its boundary.
*/
#include "csg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cad.h"
#include "mem.h"
#include "trisurf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Is x on an edge of the domain between leaves a and b (normals na, nb,
   the domain's)?  The four points beside x, on either side of both
   surfaces, must show one fluid and three solid quarters, or three fluid
   and one solid, the odd one where both normals say so. */
static int curve_is_edge(const Geometry *g, const double x[3], const double na[3], const double nb[3], double eps)
{
    int f[4];
    for (int q = 0; q < 4; q++) {
        double sa = q & 1 ? 1 : -1, sb = q & 2 ? 1 : -1, y[3];
        for (int k = 0; k < 3; k++) y[k] = x[k] + eps * (sa * na[k] + sb * nb[k]);
        f[q] = geometry_fluid(g, y);
    }
    /* q = 0: the flow side of both; q = 3: the solid side of both */
    return f[0] && !f[3] && f[1] == f[2];
}

/* Alternating projections from x onto the surfaces of leaves a and b: a
   point on both (their intersection curve, where they cross) when they
   converge; 0 otherwise. */
static int curve_project(const Geometry *g, int a, int b, const double x[3], double tol, double q[3])
{
    const GeoNode *na = g->leaves[a].node, *nb = g->leaves[b].node;
    double y[3];
    memcpy(q, x, 3 * sizeof *q);
    for (int it = 0; it < 60; it++) {
        csg_leaf_closest(g, nb, q, y);
        csg_leaf_closest(g, na, y, q);
        if (csg_dist3(q, y) <= tol) return 1;
    }
    return 0;
}

int geometry_sample_curves(const Geometry *g, double h, const double *px, const int *pl, int np, double **x,
                           int **la, int **lb)
{
    int n = 0, cap = 0;
    *x = NULL;
    *la = *lb = NULL;
    double L = 0;
    for (int p = 0; p < np; p++)
        for (int k = 0; k < 3; k++) L = fmax(L, fabs(px[3 * (size_t)p + k]));
    double tol = 1e-12 * (L > 1 ? L : 1);
    for (int p = 0; p < np; p++) {
        int a = pl[p];
        if (g->leaves[a].node->op != G_PRIM) continue;
        const double *xp = px + 3 * (size_t)p;
        for (int b = 0; b < g->nleaves; b++) {
            if (b == a || g->leaves[b].node->op != G_PRIM) continue;
            double c[3], q[3], va[3], vb[3];
            csg_leaf_closest(g, g->leaves[b].node, xp, c);
            if (csg_dist3(c, xp) > h || !curve_project(g, a, b, xp, tol, q)) continue;
            /* the curve within reach of this sample only */
            if (csg_dist3(q, xp) > 2 * h) continue;
            geometry_normal(g, a, q, va);
            geometry_normal(g, b, q, vb);
            if (fabs(va[0] * vb[0] + va[1] * vb[1] + va[2] * vb[2]) > 0.985) continue;   /* tangent: no edge */
            if (!curve_is_edge(g, q, va, vb, 1e-7 * h)) continue;
            if (n == cap) {
                cap = cap ? 2 * cap : 64;
                *x = mem_realloc(*x, sizeof(double) * 3 * (size_t)cap);
                *la = mem_realloc(*la, sizeof(int) * (size_t)cap);
                *lb = mem_realloc(*lb, sizeof(int) * (size_t)cap);
            }
            memcpy(*x + 3 * (size_t)n, q, sizeof q);
            (*la)[n] = a;
            (*lb)[n] = b;
            n++;
        }
    }
    return n;
}

/* ---- boundary sampling (geometry_sample) ----
**
** Every leaf is sampled on its own: primitives through shape_sample in
** their own coordinates with the spacing divided by the transform's
** largest column norm (so mapped points stay at most about h apart),
** mapped by x -> A x + b with normals A^-T n; triangulated leaves by
** barycentric subdivision of each triangle into ceil(longest edge / h)
** steps (interior nodes per triangle, edge nodes once per edge, each
** vertex once), with the triangle's normal inside it, the exact CAD
** normal where the model has one, and the normalised sum of the adjacent
** triangles' normals on edges and at vertices (feature edges get the
** mean normal as box edges do).  Normals are multiplied by the leaf's
** sign, so they point out of the flow domain.  A point is kept when it
** lies on the domain's boundary: fluid at p - 1e-7 h n, solid at
** p + 1e-7 h n.  Along the mean normal of an edge point this test holds
** for convex and reflex edges alike, so edge points need no tolerance of
** their own.  Points outside the box (when one is given) are dropped.
**
** 2-D (flattened): the section by the plane x[flat_axis] = flat_coord is
** sampled directly where it is analytic, i.e. for primitives whose
** transform keeps the flat axis (A e_a = a e_a, no coupling): a sphere
** gives a circle, a cylinder or cone along the axis a circle, a box a
** rectangle, a polygon extruded along the axis the polygon, a half-space
** a line (clipped to the box); vertices of rectangles and polygons are
** edge points with the mean normal.  Every other leaf (oblique cylinders
** and cones, tori, triangulated surfaces, transforms that tilt the flat
** axis) falls back to the crossings of the leaf with grid lines of
** spacing h in the plane, along both in-plane axes, keeping a crossing
** only on the line the curve crosses most steeply (|n| along the line
** at least its other in-plane component): neighbouring kept points are
** then h to h sqrt 2 apart, without clusters where lines of both
** families cross the curve.
*/

typedef struct GSamp {
    int n, cap;
    double *x, *nv;
    int *leaf;
    const double *lo, *hi;
    double tol;
} GSamp;

static int gs_in_box(const GSamp *S, const Geometry *g, const double x[3])
{
    if (!S->lo) return 1;
    for (int k = 0; k < 3; k++)
        if (k != g->flat_axis && !(x[k] >= S->lo[k] - S->tol && x[k] <= S->hi[k] + S->tol)) return 0;
    return 1;
}

/* Adds x with domain normal n (unit) when it lies on the domain's
   boundary and in the box. */
static void gs_add(GSamp *S, const Geometry *g, double h, const double x[3], const double n[3], int leaf)
{
    double a[3], b[3], d = 1e-7 * h;
    for (int k = 0; k < 3; k++) a[k] = x[k] - d * n[k], b[k] = x[k] + d * n[k];
    if (!gs_in_box(S, g, x) || !geometry_fluid(g, a) || geometry_fluid(g, b)) return;
    if (S->n == S->cap) {
        S->cap = S->cap ? 2 * S->cap : 256;
        S->x = mem_realloc(S->x, (size_t)S->cap * 3 * sizeof *S->x);
        S->nv = mem_realloc(S->nv, (size_t)S->cap * 3 * sizeof *S->nv);
        S->leaf = mem_realloc(S->leaf, (size_t)S->cap * sizeof *S->leaf);
    }
    memcpy(S->x + 3 * S->n, x, 3 * sizeof *x);
    memcpy(S->nv + 3 * S->n, n, 3 * sizeof *n);
    S->leaf[S->n++] = leaf;
}

static int gs_steps(double len, double h)
{
    double k = ceil(len / h - 1e-9);
    return !(k >= 1) ? 1 : k > 1e7 ? 10000000 : (int)k;
}

/* Largest column norm of a primitive's map (1 without one): a length l
   in the leaf's coordinates is at most about this times l globally. */
static double gs_stretch(const GeoNode *n, int skip)
{
    if (!n->has_xf) return 1;
    double s = 0;
    for (int j = 0; j < 3; j++)
        if (j != skip) s = fmax(s, sqrt(n->A[j] * n->A[j] + n->A[3 + j] * n->A[3 + j] + n->A[6 + j] * n->A[6 + j]));
    return s;
}

/* Local point and leaf normal -> global point and domain normal. */
static void gs_map(const Geometry *g, const GeoLeaf *L, const double l[3], const double nl[3], double x[3],
                   double n[3])
{
    const GeoNode *nd = L->node;
    if (nd->has_xf) {
        csg_mat_vec(nd->A, l, x);
        for (int k = 0; k < 3; k++) x[k] += nd->b[k];
        for (int i = 0; i < 3; i++) n[i] = nd->Ai[i] * nl[0] + nd->Ai[3 + i] * nl[1] + nd->Ai[6 + i] * nl[2];
    } else {
        memcpy(x, l, 3 * sizeof *x);
        memcpy(n, nl, 3 * sizeof *n);
    }
    if (g->flat_axis >= 0) {
        x[g->flat_axis] = g->flat_coord;
        n[g->flat_axis] = 0;
    }
    csg_unit(n);
    for (int k = 0; k < 3; k++) n[k] *= L->sign;
}

/* Bounding box in the leaf's coordinates of the global box lo..hi. */
static void gs_local_box(const GeoNode *n, const double lo[3], const double hi[3], double llo[3], double lhi[3])
{
    for (int k = 0; k < 3; k++) llo[k] = INFINITY, lhi[k] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]}, l[3];
        csg_to_local(n, p, l);
        for (int k = 0; k < 3; k++) llo[k] = fmin(llo[k], l[k]), lhi[k] = fmax(lhi[k], l[k]);
    }
}

/* Global bounding box of a leaf (infinite extents stay infinite). */
static void gs_leaf_bounds(const GeoNode *n, double lo[3], double hi[3])
{
    if (n->op == G_TRI) {
        memcpy(lo, n->tri->lo, 3 * sizeof *lo);
        memcpy(hi, n->tri->hi, 3 * sizeof *hi);
        return;
    }
    double l[3], h[3];
    shape_bounds(&n->shape, l, h);
    if (!n->has_xf) {
        memcpy(lo, l, 3 * sizeof *lo);
        memcpy(hi, h, 3 * sizeof *hi);
        return;
    }
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? h[0] : l[0], c & 2 ? h[1] : l[1], c & 4 ? h[2] : l[2]}, x[3];
        for (int i = 0; i < 3; i++) {
            x[i] = n->b[i];
            for (int j = 0; j < 3; j++)
                if (n->A[3 * i + j] != 0) x[i] += n->A[3 * i + j] * p[j];
        }
        for (int k = 0; k < 3; k++) {
            if (isnan(x[k])) x[k] = INFINITY;
            lo[k] = fmin(lo[k], isinf(x[k]) ? -INFINITY : x[k]);
            hi[k] = fmax(hi[k], x[k]);
        }
    }
}

static void gs_prim(const Geometry *g, int leaf, double h, GSamp *S)
{
    const GeoLeaf *L = &g->leaves[leaf];
    const GeoNode *nd = L->node;
    double llo[3], lhi[3], *x, *nl;
    if (S->lo) gs_local_box(nd, S->lo, S->hi, llo, lhi);
    int k = shape_sample(&nd->shape, h / gs_stretch(nd, -1), S->lo ? llo : NULL, S->lo ? lhi : NULL, &x, &nl);
    for (int i = 0; i < k; i++) {
        double p[3], n[3];
        gs_map(g, L, x + 3 * i, nl + 3 * i, p, n);
        gs_add(S, g, h, p, n, leaf);
    }
    free(x);
    free(nl);
}

/* ---- triangulated leaves ---- */

typedef struct GsEdge {
    int a, b, tri;
} GsEdge;

static int gs_edge_cmp(const void *x, const void *y)
{
    const GsEdge *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return p->tri - q->tri;
}

/* Normal at a point of triangle t: the exact CAD normal of its surface
   when the model has one, else the triangle's. */
static void gs_tri_normal(const GeoNode *nd, int t, const double *tn, const double x[3], double n[3])
{
    memcpy(n, tn + 3 * t, 3 * sizeof *n);
    if (nd->cad && nd->tri->tag) cad_normal(nd->cad, nd->tri->tag[t], x, tn + 3 * t, n);
}

static void gs_emit_tri(const Geometry *g, int leaf, double h, const double x[3], const double n[3], GSamp *S)
{
    double nn[3] = {n[0], n[1], n[2]};
    csg_unit(nn);
    for (int k = 0; k < 3; k++) nn[k] *= g->leaves[leaf].sign;
    gs_add(S, g, h, x, nn, leaf);
}

static void gs_tri(const Geometry *g, int leaf, double h, GSamp *S)
{
    const GeoNode *nd = g->leaves[leaf].node;
    const TriSurf *t = nd->tri;
    int nt = t->ntris;
    double *tn = mem_alloc((size_t)nt * 3 * sizeof *tn);
    double *vn = MEM_NEW(double, 3 * (size_t)t->npoints);
    GsEdge *E = mem_alloc((size_t)nt * 3 * sizeof *E);
    for (int i = 0; i < nt; i++) {
        trisurf_normal(t, i, tn + 3 * i);
        for (int c = 0; c < 3; c++) {
            int a = t->tris[3 * i + c], b = t->tris[3 * i + (c + 1) % 3];
            for (int k = 0; k < 3; k++) vn[3 * a + k] += tn[3 * i + k];
            E[3 * i + c] = (GsEdge){a < b ? a : b, a < b ? b : a, i};
        }
    }
    /* interior nodes of each triangle */
    for (int i = 0; i < nt; i++) {
        const double *P[3];
        double len = 0;
        for (int c = 0; c < 3; c++) P[c] = t->points + 3 * t->tris[3 * i + c];
        for (int c = 0; c < 3; c++) {
            double d[3] = {P[c][0] - P[(c + 1) % 3][0], P[c][1] - P[(c + 1) % 3][1], P[c][2] - P[(c + 1) % 3][2]};
            len = fmax(len, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
        int m = gs_steps(len, h);
        for (int a = 1; a < m; a++)
            for (int b = 1; a + b < m; b++) {
                double x[3], n[3];
                for (int k = 0; k < 3; k++) x[k] = (a * P[0][k] + b * P[1][k] + (m - a - b) * P[2][k]) / m;
                gs_tri_normal(nd, i, tn, x, n);
                gs_emit_tri(g, leaf, h, x, n, S);
            }
    }
    /* edge nodes, once per edge (the triangles sharing it are adjacent
       after sorting) */
    qsort(E, (size_t)nt * 3, sizeof *E, gs_edge_cmp);
    for (int i = 0; i < 3 * nt;) {
        int j = i;
        double n[3] = {0, 0, 0};
        while (j < 3 * nt && E[j].a == E[i].a && E[j].b == E[i].b) {
            for (int k = 0; k < 3; k++) n[k] += tn[3 * E[j].tri + k];
            j++;
        }
        const double *A = t->points + 3 * E[i].a, *B = t->points + 3 * E[i].b;
        int m = gs_steps(sqrt((A[0] - B[0]) * (A[0] - B[0]) + (A[1] - B[1]) * (A[1] - B[1])
                              + (A[2] - B[2]) * (A[2] - B[2])), h);
        for (int s = 1; s < m; s++) {
            double x[3];
            for (int k = 0; k < 3; k++) x[k] = A[k] + (B[k] - A[k]) * s / m;
            gs_emit_tri(g, leaf, h, x, n, S);
        }
        i = j;
    }
    for (int p = 0; p < t->npoints; p++)
        if (vn[3 * p] != 0 || vn[3 * p + 1] != 0 || vn[3 * p + 2] != 0)
            gs_emit_tri(g, leaf, h, t->points + 3 * p, vn + 3 * p, S);
    free(tn);
    free(vn);
    free(E);
}

/* ---- 2-D sections ---- */

/* Does the leaf's map keep the flat axis a (no coupling with the other
   two)? */
static int gs_keeps_axis(const GeoNode *n, int a)
{
    if (!n->has_xf) return 1;
    for (int k = 0; k < 3; k++)
        if (k != a && (n->A[3 * k + a] != 0 || n->A[3 * a + k] != 0)) return 0;
    return n->A[4 * a] != 0;
}

/* A closed polygon (u, v) in the leaf's plane l[a] = lc, counter-clockwise:
   nodes at most hl apart, vertices with the mean normal. */
static void gs_poly2(const Geometry *g, int leaf, double h, double hl, const double *uv, int np, double lc, GSamp *S)
{
    int a = g->flat_axis, iu = (a + 1) % 3, iv = (a + 2) % 3;
    for (int e = 0; e < np; e++) {
        const double *P = uv + 2 * e, *Q = uv + 2 * ((e + 1) % np), *R = uv + 2 * ((e + np - 1) % np);
        double eu = Q[0] - P[0], ev = Q[1] - P[1], L = sqrt(eu * eu + ev * ev);
        double pu = P[0] - R[0], pv = P[1] - R[1], Lp = sqrt(pu * pu + pv * pv);
        /* the vertex P, then the midpoints of m intervals (shape.c
           samp_box: the edge rule's mirror seeds then replace the first
           pair cleanly) */
        int m = gs_steps(L, hl);
        for (int i = 0; i <= m; i++) {
            double l[3], nl[3], x[3], n[3], t = i == 0 ? 0 : (i - 0.5) / m;
            l[a] = lc, l[iu] = P[0] + eu * t, l[iv] = P[1] + ev * t;
            nl[a] = 0, nl[iu] = ev / L, nl[iv] = -eu / L;
            if (i == 0) nl[iu] += pv / Lp, nl[iv] -= pu / Lp;
            gs_map(g, &g->leaves[leaf], l, nl, x, n);
            gs_add(S, g, h, x, n, leaf);
        }
    }
}

static void gs_circle(const Geometry *g, int leaf, double h, double hl, double cu, double cv, double r, double lc,
                      GSamp *S)
{
    int a = g->flat_axis, iu = (a + 1) % 3, iv = (a + 2) % 3;
    double mm = floor(2 * M_PI * r / hl + 0.5);
    int m = mm < 3 ? 3 : mm > 1e7 ? 10000000 : (int)mm;
    for (int j = 0; j < m; j++) {
        double ph = 2 * M_PI * j / m, l[3], nl[3], x[3], n[3];
        nl[a] = 0, nl[iu] = cos(ph), nl[iv] = sin(ph);
        l[a] = lc, l[iu] = cu + r * nl[iu], l[iv] = cv + r * nl[iv];
        gs_map(g, &g->leaves[leaf], l, nl, x, n);
        gs_add(S, g, h, x, n, leaf);
    }
}

/* The section line of a half-space, clipped to the box. */
static void gs_line(const Geometry *g, int leaf, double h, double hl, double lc, GSamp *S)
{
    const GeoNode *nd = g->leaves[leaf].node;
    const Shape *s = &nd->shape;
    int a = g->flat_axis, iu = (a + 1) % 3, iv = (a + 2) % 3;
    double qu = s->q[iu], qv = s->q[iv], qq = qu * qu + qv * qv;
    if (!S->lo || !(qq > 1e-24)) return;
    double llo[3], lhi[3];
    gs_local_box(nd, S->lo, S->hi, llo, lhi);
    double off = -s->q[a] * (lc - s->p[a]) / qq, ql = sqrt(qq);
    double o[2] = {s->p[iu] + off * qu, s->p[iv] + off * qv}, d[2] = {-qv / ql, qu / ql};
    double t0 = -INFINITY, t1 = INFINITY;
    int ax[2] = {iu, iv};
    for (int k = 0; k < 2; k++) {
        if (d[k] == 0) {
            if (o[k] < llo[ax[k]] || o[k] > lhi[ax[k]]) return;
            continue;
        }
        double ta = (llo[ax[k]] - o[k]) / d[k], tb = (lhi[ax[k]] - o[k]) / d[k];
        t0 = fmax(t0, fmin(ta, tb)), t1 = fmin(t1, fmax(ta, tb));
    }
    if (!(t0 <= t1)) return;
    /* midpoints: the line leaves through the box sides, and samples half
       a spacing from them keep the seed pairs inside (shape.c samp_mid) */
    int m = gs_steps(t1 - t0, hl);
    for (int i = 0; i < m; i++) {
        double t = t0 + (t1 - t0) * (i + 0.5) / m, l[3], nl[3], x[3], n[3];
        l[a] = lc, l[iu] = o[0] + t * d[0], l[iv] = o[1] + t * d[1];
        nl[a] = 0, nl[iu] = qu / ql, nl[iv] = qv / ql;
        gs_map(g, &g->leaves[leaf], l, nl, x, n);
        gs_add(S, g, h, x, n, leaf);
    }
}

/* The analytic section of a primitive; 0 when there is none in closed
   form (the caller then marches grid lines). */
static int gs_section_exact(const Geometry *g, int leaf, double h, GSamp *S)
{
    const GeoNode *nd = g->leaves[leaf].node;
    const Shape *s = &nd->shape;
    int a = g->flat_axis, iu = (a + 1) % 3, iv = (a + 2) % 3;
    if (nd->op != G_PRIM || !gs_keeps_axis(nd, a)) return 0;
    double lc = nd->has_xf ? (g->flat_coord - nd->b[a]) / nd->A[4 * a] : g->flat_coord;
    double hl = h / gs_stretch(nd, a);
    switch (s->kind) {
    case SHAPE_SPHERE: {
        double d = lc - s->p[a];
        if (d * d < s->r1 * s->r1) gs_circle(g, leaf, h, hl, s->p[iu], s->p[iv], sqrt(s->r1 * s->r1 - d * d), lc, S);
        return 1;
    }
    case SHAPE_CYLINDER:
    case SHAPE_CONE: {
        double u[3] = {s->q[0] - s->p[0], s->q[1] - s->p[1], s->q[2] - s->p[2]};
        double H = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (fabs(u[a]) < H * (1 - 1e-12)) return 0;
        double t = (lc - s->p[a]) / u[a];
        int inf = s->kind == SHAPE_CYLINDER && s->infinite;
        double r = s->kind == SHAPE_CYLINDER ? s->r1 : s->r1 + t * (s->r2 - s->r1);
        if ((inf || (t > 0 && t < 1)) && r > 0) gs_circle(g, leaf, h, hl, s->p[iu], s->p[iv], r, lc, S);
        return 1;
    }
    case SHAPE_BOX: {
        double uv[8] = {s->p[iu], s->p[iv], s->q[iu], s->p[iv], s->q[iu], s->q[iv], s->p[iu], s->q[iv]};
        if (lc > s->p[a] && lc < s->q[a]) gs_poly2(g, leaf, h, hl, uv, 4, lc, S);
        return 1;
    }
    case SHAPE_POLYGON:
        if (s->axis != a) return 0;
        if (lc > s->lo && lc < s->hi) gs_poly2(g, leaf, h, hl, s->poly, s->npoly, lc, S);
        return 1;
    case SHAPE_HALFSPACE: gs_line(g, leaf, h, hl, lc, S); return 1;
    default: return 0;
    }
}

/* Crossings of leaf with the segment a -> b, with the leaf's own
   normals there. */
static int gs_leaf_cross(const GeoNode *nd, const double a[3], const double b[3], double *t, double *n, int max)
{
    int k;
    if (nd->op == G_PRIM) {
        double la[3], lb[3];
        csg_to_local(nd, a, la);
        csg_to_local(nd, b, lb);
        k = shape_crossings(&nd->shape, la, lb, t, max);
    } else {
        int tri[GEO_STACK];
        k = trisurf_crossings(nd->tri, a, b, t, tri, max);
        for (int i = 0; i < k && i < max; i++) trisurf_normal(nd->tri, tri[i], n + 3 * i);
    }
    if (k > max) k = max;
    for (int i = 0; i < k; i++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = a[j] + t[i] * (b[j] - a[j]);
        if (nd->op == G_PRIM || nd->cad) csg_leaf_normal(nd, x, n + 3 * i);
    }
    return k;
}

static void gs_section_march(const Geometry *g, int leaf, double h, GSamp *S)
{
    const GeoNode *nd = g->leaves[leaf].node;
    int a = g->flat_axis, ax[2] = {(a + 1) % 3, (a + 2) % 3};
    double lo[3], hi[3];
    gs_leaf_bounds(nd, lo, hi);
    for (int k = 0; k < 3; k++)
        if (S->lo) lo[k] = fmax(lo[k], S->lo[k]), hi[k] = fmin(hi[k], S->hi[k]);
    for (int k = 0; k < 2; k++)
        if (!isfinite(lo[ax[k]]) || !isfinite(hi[ax[k]]) || !(lo[ax[k]] <= hi[ax[k]])) return;
    for (int dir = 0; dir < 2; dir++) {
        int along = ax[dir], across = ax[1 - dir];
        int m = gs_steps(hi[across] - lo[across], h);
        double sp = (hi[across] - lo[across]) / m;
        for (int j = 0; j < m; j++) {
            double pa[3], pb[3], t[GEO_STACK], n[3 * GEO_STACK];
            pa[a] = pb[a] = g->flat_coord;
            pa[across] = pb[across] = lo[across] + (j + 0.5) * sp;
            pa[along] = lo[along] - h, pb[along] = hi[along] + h;
            int k = gs_leaf_cross(nd, pa, pb, t, n, GEO_STACK);
            for (int i = 0; i < k; i++) {
                double *ni = n + 3 * i, x[3];
                ni[a] = 0;
                if (dir == 0 ? fabs(ni[along]) < fabs(ni[across]) : fabs(ni[along]) <= fabs(ni[across])) continue;
                csg_unit(ni);
                for (int c = 0; c < 3; c++) x[c] = pa[c] + t[i] * (pb[c] - pa[c]), ni[c] *= g->leaves[leaf].sign;
                x[a] = g->flat_coord;
                gs_add(S, g, h, x, ni, leaf);
            }
        }
    }
}

/* Box of the bounded leaves, for half-spaces and other unbounded leaves
   when the caller gives none; 0 when no leaf is bounded. */
static int gs_default_box(const Geometry *g, double lo[3], double hi[3])
{
    int any = 0;
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int i = 0; i < g->nleaves; i++) {
        double l[3], u[3];
        gs_leaf_bounds(g->leaves[i].node, l, u);
        if (!isfinite(l[0] + l[1] + l[2] + u[0] + u[1] + u[2])) continue;
        any = 1;
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], l[k]), hi[k] = fmax(hi[k], u[k]);
    }
    return any;
}

int geometry_sample_box(const Geometry *g, double h, const double lo[3], const double hi[3], double **x, double **n,
                        int **leaf)
{
    GSamp S = {0, 0, NULL, NULL, NULL, lo, hi, 0};
    double dlo[3], dhi[3];
    if (!lo && gs_default_box(g, dlo, dhi)) S.lo = dlo, S.hi = dhi;
    if (S.lo)
        for (int k = 0; k < 3; k++) S.tol = fmax(S.tol, 1e-9 * (fabs(S.lo[k]) + fabs(S.hi[k])));
    for (int i = 0; h > 0 && i < g->nleaves; i++) {
        const GeoNode *nd = g->leaves[i].node;
        if (g->flat_axis >= 0) {
            if (!gs_section_exact(g, i, h, &S)) gs_section_march(g, i, h, &S);
        } else if (nd->op == G_PRIM) {
            gs_prim(g, i, h, &S);
        } else {
            gs_tri(g, i, h, &S);
        }
    }
    *x = S.x ? S.x : MEM_NEW(double, 1);
    *n = S.nv ? S.nv : MEM_NEW(double, 1);
    *leaf = S.leaf ? S.leaf : MEM_NEW(int, 1);
    return S.n;
}

int geometry_sample(const Geometry *g, double h, double **x, double **n, int **leaf)
{
    return geometry_sample_box(g, h, NULL, NULL, x, n, leaf);
}

