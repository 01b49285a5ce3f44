/*
** csg.c: the flow domain as one CSG tree over primitives, STL surfaces
** and CAD models, and its evaluation: the queries of geometry.h on the
** domain (inside, level, crossings, normals, nearest leaf, exact volume,
** bounding planes).  The node layout is csg.h; reading the tree from
** system/geometryDict is geometry_dict.c; sampling its boundary is
** geometry_sample.c.
**
** Tree.  Leaves are primitives (Shape) or triangulated surfaces
** (TriSurf, from STL or gmsh); inner nodes are union, intersection and
** difference.  Each node may be complemented (`neg`): the domain root is
** the intersection of every surface's root, complemented where the flow
** is outside.  Transforms are pushed down to the leaves when the
** dictionary is read: a triangulated leaf has its points moved (so
** axis-aligned line queries stay axis-aligned and robust), a primitive
** keeps the affine map x = A l + b and maps query points into its own
** coordinates.  Segment parameters t are invariant under affine maps, so
** crossings need no conversion; normals transform with A^-T.
**
** Crossings of an inner node are found from its operands' crossings: each
** operand reports its inside state at the segment start and the t where
** it toggles; events closer than GEO_TTOL are applied together and the
** node reports an event only when its own state changes.  This is exact:
** the node's state is a Boolean function of its operands' states, which
** change only at their events.
**
** Level (geometry_level): a primitive's shape_bound (shape.h: 1-Lipschitz,
** the exact distance for spheres and half-spaces), times 1/|A^-1|_2 when
** it is mapped (so it stays 1-Lipschitz), a triangulated
** surface's signed distance, min over a union's operands, max over an
** intersection's, max(first, -others) for a difference, negated by a
** complement.  Min and max keep the 1-Lipschitz bound, which is all the
** volume-fraction integrator (volfrac.c) relies on.
**
** The sign of a leaf (geometry.h): the domain's outward normal points into
** the solid, so a leaf of a surface whose flow is outside enters with -1,
** and each subtracted operand of a difference flips it again.
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

#define GEO_TTOL 1e-14

typedef struct Ev {
    double t;
    int leaf;
    int kid;
} Ev;

/* ---- small linear algebra ---- */

void csg_mat_vec(const double A[9], const double x[3], double y[3])
{
    double t[3];
    for (int i = 0; i < 3; i++) t[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
    memcpy(y, t, sizeof t);
}

static double mat_inv(const double A[9], double Ai[9])
{
    double det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6])
               + A[2] * (A[3] * A[7] - A[4] * A[6]);
    Ai[0] = (A[4] * A[8] - A[5] * A[7]) / det;
    Ai[1] = (A[2] * A[7] - A[1] * A[8]) / det;
    Ai[2] = (A[1] * A[5] - A[2] * A[4]) / det;
    Ai[3] = (A[5] * A[6] - A[3] * A[8]) / det;
    Ai[4] = (A[0] * A[8] - A[2] * A[6]) / det;
    Ai[5] = (A[2] * A[3] - A[0] * A[5]) / det;
    Ai[6] = (A[3] * A[7] - A[4] * A[6]) / det;
    Ai[7] = (A[1] * A[6] - A[0] * A[7]) / det;
    Ai[8] = (A[0] * A[4] - A[1] * A[3]) / det;
    return det;
}

/* ---- node construction and freeing ---- */

GeoNode *csg_node_new(int op)
{
    GeoNode *n = MEM_NEW(GeoNode, 1);
    n->op = op;
    n->leaf = -1;
    return n;
}

void csg_node_free(GeoNode *n)
{
    if (!n) return;
    for (int i = 0; i < n->nkids; i++) csg_node_free(n->kids[i]);
    free(n->kids);
    shape_free(&n->shape);
    if (n->tri) {
        trisurf_free(n->tri);
        free(n->tri);
    }
    if (n->cad) cad_close(n->cad);
    free(n);
}

void geometry_init(Geometry *g)
{
    memset(g, 0, sizeof *g);
    g->flat_axis = -1;
}

void geometry_free(Geometry *g)
{
    for (int s = 0; s < g->nsurf; s++) {
        free(g->surf[s].name);
        free(g->surf[s].type);
        csg_node_free(g->surf[s].root);
    }
    free(g->surf);
    free(g->leaves);
    free(g->file);
    geometry_init(g);
}

/* ---- building ---- */

/* Largest eigenvalue of the symmetric 3x3 matrix S (closed form through
   the trigonometric solution of its characteristic cubic). */
static double sym_max_eig(const double S[9])
{
    double p1 = S[1] * S[1] + S[2] * S[2] + S[5] * S[5], q = (S[0] + S[4] + S[8]) / 3;
    if (p1 == 0) return fmax(S[0], fmax(S[4], S[8]));
    double p2 = (S[0] - q) * (S[0] - q) + (S[4] - q) * (S[4] - q) + (S[8] - q) * (S[8] - q) + 2 * p1;
    double p = sqrt(p2 / 6), B[9];
    for (int i = 0; i < 9; i++) B[i] = (S[i] - (i % 4 == 0 ? q : 0)) / p;
    double r = (B[0] * (B[4] * B[8] - B[5] * B[7]) - B[1] * (B[3] * B[8] - B[5] * B[6])
                + B[2] * (B[3] * B[7] - B[4] * B[6])) / 2;
    double phi = r <= -1 ? M_PI / 3 : r >= 1 ? 0 : acos(r) / 3;
    return q + 2 * p * cos(phi);
}

void csg_node_set_map(GeoNode *n, const double A[9], const double b[3])
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    memcpy(n->A, A, sizeof n->A);
    memcpy(n->b, b, sizeof n->b);
    n->has_xf = memcmp(A, I, sizeof I) || memcmp(b, zero, sizeof zero);
    n->det = mat_inv(n->A, n->Ai);
    /* |Ai|_2^2 = largest eigenvalue of Ai^T Ai; the margin covers its
       round-off, so the scaled level never overstates the distance. */
    double S[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            S[3 * i + j] = n->Ai[i] * n->Ai[j] + n->Ai[3 + i] * n->Ai[3 + j] + n->Ai[6 + i] * n->Ai[6 + j];
    n->lip = n->has_xf ? 1 / sqrt(sym_max_eig(S) * (1 + 1e-9)) : 1;
}

int csg_add_surface(Geometry *g, const char *name, const char *type, int flow_inside, int line)
{
    g->surf = mem_realloc(g->surf, (size_t)(g->nsurf + 1) * sizeof *g->surf);
    GeoSurface *gs = &g->surf[g->nsurf];
    memset(gs, 0, sizeof *gs);
    gs->name = mem_strdup(name);
    gs->type = mem_strdup(type);
    gs->flow_inside = flow_inside;
    gs->line = line;
    return g->nsurf++;
}

void csg_add_leaf(Geometry *g, GeoNode *n, int surface, int sign)
{
    g->leaves = mem_realloc(g->leaves, (size_t)(g->nleaves + 1) * sizeof *g->leaves);
    g->leaves[g->nleaves] = (GeoLeaf){n, surface, sign};
    n->leaf = g->nleaves++;
}

void geometry_of_shape(Geometry *g, const Shape *s, const char *name)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    geometry_init(g);
    g->file = mem_strdup(name);
    int sf = csg_add_surface(g, name, "wall", 1, 0);
    GeoNode *n = csg_node_new(G_PRIM);
    n->shape = *s;
    csg_node_set_map(n, I, zero);
    csg_add_leaf(g, n, sf, 1);
    g->surf[sf].root = n;
}

void geometry_flatten(Geometry *g, int axis, double coord)
{
    g->flat_axis = axis;
    g->flat_coord = coord;
}

/* ---- point queries ---- */

void csg_to_local(const GeoNode *n, const double x[3], double l[3])
{
    if (!n->has_xf) {
        memcpy(l, x, 3 * sizeof *l);
        return;
    }
    double d[3] = {x[0] - n->b[0], x[1] - n->b[1], x[2] - n->b[2]};
    csg_mat_vec(n->Ai, d, l);
}

static int node_inside(const GeoNode *n, const double x[3])
{
    int in = 0;
    switch (n->op) {
    case G_PRIM: {
        double l[3];
        csg_to_local(n, x, l);
        in = shape_inside(&n->shape, l);
        break;
    }
    case G_TRI: in = trisurf_inside(n->tri, x); break;
    case G_UNION:
        for (int i = 0; i < n->nkids && !in; i++) in = node_inside(n->kids[i], x);
        break;
    case G_INTER:
        in = 1;
        for (int i = 0; i < n->nkids && in; i++) in = node_inside(n->kids[i], x);
        break;
    case G_DIFF:
        in = node_inside(n->kids[0], x);
        for (int i = 1; i < n->nkids && in; i++) in = !node_inside(n->kids[i], x);
        break;
    }
    return in ^ n->neg;
}

static void flat(const Geometry *g, const double x[3], double y[3])
{
    memcpy(y, x, 3 * sizeof *y);
    if (g->flat_axis >= 0) y[g->flat_axis] = g->flat_coord;
}

int geometry_fluid(const Geometry *g, const double x[3])
{
    double y[3];
    flat(g, x, y);
    for (int s = 0; s < g->nsurf; s++)
        if (!node_inside(g->surf[s].root, y)) return 0;
    return 1;
}

static void combine(int op, int first, char *acc, const char *in, int n)
{
    for (int i = 0; i < n; i++) {
        if (first) acc[i] = in[i];
        else if (op == G_UNION) acc[i] = acc[i] || in[i];
        else if (op == G_INTER) acc[i] = acc[i] && in[i];
        else acc[i] = acc[i] && !in[i];
    }
}

static void node_classify_line(const GeoNode *n, int axis, const double p[3], const double *c, int cnt, char *out)
{
    if (n->op == G_PRIM) {
        double x[3] = {p[0], p[1], p[2]};
        for (int i = 0; i < cnt; i++) {
            x[axis] = c[i];
            out[i] = (char)node_inside(n, x);
        }
        return;
    }
    if (n->op == G_TRI) {
        trisurf_classify_line(n->tri, axis, p, c, cnt, out);
    } else {
        char *tmp = mem_alloc((size_t)cnt);
        for (int k = 0; k < n->nkids; k++) {
            node_classify_line(n->kids[k], axis, p, c, cnt, tmp);
            combine(n->op, k == 0, out, tmp, cnt);
        }
        free(tmp);
    }
    if (n->neg)
        for (int i = 0; i < cnt; i++) out[i] = (char)!out[i];
}

void geometry_classify_line(const Geometry *g, int axis, const double p[3], const double *c, int n, char *fluid)
{
    if (n <= 0) return;
    double q[3];
    flat(g, p, q);
    if (axis == g->flat_axis) {
        int f = geometry_fluid(g, q);
        memset(fluid, f, (size_t)n);
        return;
    }
    memset(fluid, 1, (size_t)n);
    char *tmp = mem_alloc((size_t)n);
    for (int s = 0; s < g->nsurf; s++) {
        node_classify_line(g->surf[s].root, axis, q, c, n, tmp);
        for (int i = 0; i < n; i++) fluid[i] = (char)(fluid[i] && tmp[i]);
    }
    free(tmp);
}

/* ---- crossings ---- */

/* Growable event list with a stack buffer for the common short case. */
typedef struct EvList {
    Ev *v;
    int n, cap;
    Ev stack[GEO_STACK];
} EvList;

static void ev_init(EvList *l)
{
    l->v = l->stack;
    l->n = 0;
    l->cap = GEO_STACK;
}

static void ev_push(EvList *l, double t, int leaf, int kid)
{
    if (l->n == l->cap) {
        int cap = 2 * l->cap;
        Ev *v = mem_alloc((size_t)cap * sizeof *v);
        memcpy(v, l->v, (size_t)l->n * sizeof *v);
        if (l->v != l->stack) free(l->v);
        l->v = v;
        l->cap = cap;
    }
    l->v[l->n++] = (Ev){t, leaf, kid};
}

static void ev_free(EvList *l)
{
    if (l->v != l->stack) free(l->v);
    ev_init(l);
}

static int ev_cmp(const void *a, const void *b)
{
    const Ev *x = a, *y = b;
    if (x->t != y->t) return x->t < y->t ? -1 : 1;
    return x->kid - y->kid;
}

static int eval_op(int op, const char *st, int n)
{
    int in = st[0];
    for (int i = 1; i < n; i++) {
        if (op == G_UNION) in = in || st[i];
        else if (op == G_INTER) in = in && st[i];
        else in = in && !st[i];
    }
    return in;
}

/* Events of a leaf: every transversal crossing toggles it. */
static void leaf_events(const GeoNode *n, const double a[3], const double b[3], EvList *out)
{
    if (n->op == G_PRIM) {
        double la[3], lb[3], t[SHAPE_MAX_CROSS];
        csg_to_local(n, a, la);
        csg_to_local(n, b, lb);
        int k = shape_crossings(&n->shape, la, lb, t, SHAPE_MAX_CROSS);
        if (k > SHAPE_MAX_CROSS) k = SHAPE_MAX_CROSS;
        for (int i = 0; i < k; i++) ev_push(out, t[i], n->leaf, 0);
        return;
    }
    double ts[GEO_STACK];
    int k = trisurf_crossings(n->tri, a, b, ts, NULL, GEO_STACK);
    if (k <= GEO_STACK) {
        for (int i = 0; i < k; i++) ev_push(out, ts[i], n->leaf, 0);
        return;
    }
    double *t = mem_alloc((size_t)k * sizeof *t);
    k = trisurf_crossings(n->tri, a, b, t, NULL, k);
    for (int i = 0; i < k; i++) ev_push(out, t[i], n->leaf, 0);
    free(t);
}

/* Fills out with the t where node n's state toggles (ignoring neg, which
   does not move events) and returns its state at a (neg applied). */
static int node_events(const GeoNode *n, const double a[3], const double b[3], EvList *out)
{
    if (n->op == G_PRIM || n->op == G_TRI) {
        leaf_events(n, a, b, out);
        return node_inside(n, a);
    }
    char st_stack[16];
    char *st = n->nkids <= 16 ? st_stack : mem_alloc((size_t)n->nkids);
    EvList all;
    ev_init(&all);
    for (int k = 0; k < n->nkids; k++) {
        EvList kid;
        ev_init(&kid);
        st[k] = (char)node_events(n->kids[k], a, b, &kid);
        for (int i = 0; i < kid.n; i++) ev_push(&all, kid.v[i].t, kid.v[i].leaf, k);
        ev_free(&kid);
    }
    qsort(all.v, (size_t)all.n, sizeof *all.v, ev_cmp);
    int state = eval_op(n->op, st, n->nkids);
    int start = state;
    for (int i = 0; i < all.n;) {
        int j = i;
        while (j < all.n && all.v[j].t - all.v[i].t <= GEO_TTOL) {
            st[all.v[j].kid] = (char)!st[all.v[j].kid];
            j++;
        }
        int now = eval_op(n->op, st, n->nkids);
        if (now != state) {
            /* the leaf of the operand that made the change: the last one
               toggled in the group whose own state differs */
            ev_push(out, all.v[i].t, all.v[j - 1].leaf, 0);
            state = now;
        }
        i = j;
    }
    ev_free(&all);
    if (st != st_stack) free(st);
    return start ^ n->neg;
}

int geometry_crossings(const Geometry *g, const double a0[3], const double b0[3], GeoCross *out, int max)
{
    double a[3], b[3];
    flat(g, a0, a);
    flat(g, b0, b);
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) return 0;
    int ns = g->nsurf;
    char st_stack[16];
    char *st = ns <= 16 ? st_stack : mem_alloc((size_t)ns);
    EvList all;
    ev_init(&all);
    for (int s = 0; s < ns; s++) {
        EvList l;
        ev_init(&l);
        st[s] = (char)node_events(g->surf[s].root, a, b, &l);
        for (int i = 0; i < l.n; i++) ev_push(&all, l.v[i].t, l.v[i].leaf, s);
        ev_free(&l);
    }
    qsort(all.v, (size_t)all.n, sizeof *all.v, ev_cmp);
    int state = eval_op(G_INTER, st, ns), count = 0;
    for (int i = 0; i < all.n;) {
        int j = i;
        while (j < all.n && all.v[j].t - all.v[i].t <= GEO_TTOL) {
            st[all.v[j].kid] = (char)!st[all.v[j].kid];
            j++;
        }
        int now = eval_op(G_INTER, st, ns);
        if (now != state) {
            if (count < max) out[count] = (GeoCross){all.v[i].t, all.v[j - 1].leaf, now};
            count++;
            state = now;
        }
        i = j;
    }
    ev_free(&all);
    if (st != st_stack) free(st);
    return count;
}

/* ---- normals and nearest leaf ---- */

void csg_unit(double n[3])
{
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++) n[k] /= l;
}

/* The leaf's own outward normal, in global coordinates. */
void csg_leaf_normal(const GeoNode *n, const double x[3], double nv[3])
{
    if (n->op == G_PRIM) {
        double l[3], nl[3];
        csg_to_local(n, x, l);
        shape_normal(&n->shape, l, nl);
        if (!n->has_xf) {
            memcpy(nv, nl, 3 * sizeof *nv);
            return;
        }
        for (int i = 0; i < 3; i++)   /* A^-T nl */
            nv[i] = n->Ai[i] * nl[0] + n->Ai[3 + i] * nl[1] + n->Ai[6 + i] * nl[2];
        csg_unit(nv);
        return;
    }
    double d;
    int t = trisurf_nearest(n->tri, x, &d);
    double ref[3];
    trisurf_normal(n->tri, t, ref);
    memcpy(nv, ref, 3 * sizeof *nv);
    if (n->cad && n->tri->tag) cad_normal(n->cad, n->tri->tag[t], x, ref, nv);
}

void geometry_normal(const Geometry *g, int leaf, const double x0[3], double n[3])
{
    double x[3];
    flat(g, x0, x);
    const GeoLeaf *L = &g->leaves[leaf];
    csg_leaf_normal(L->node, x, n);
    for (int k = 0; k < 3; k++) n[k] *= L->sign;
    if (g->flat_axis >= 0) {
        n[g->flat_axis] = 0;
        csg_unit(n);
    }
}

static double leaf_distance(const GeoNode *n, const double x[3])
{
    if (n->op == G_PRIM) {
        double l[3];
        csg_to_local(n, x, l);
        double s = n->has_xf ? cbrt(fabs(n->det)) : 1;
        return fabs(shape_level(&n->shape, l)) * s;
    }
    double d;
    trisurf_nearest(n->tri, x, &d);
    return d;
}

double csg_dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Point of primitive leaf n's surface nearest to x (for a transformed
   leaf: the image of the nearest point in its own coordinates, a point of
   the surface near x). */
void csg_leaf_closest(const Geometry *g, const GeoNode *n, const double x[3], double c[3])
{
    double l[3], cl[3];
    csg_to_local(n, x, l);
    shape_closest(&n->shape, l, cl);
    if (n->has_xf) {
        csg_mat_vec(n->A, cl, c);
        for (int k = 0; k < 3; k++) c[k] += n->b[k];
    } else {
        memcpy(c, cl, sizeof cl);
    }
    if (g->flat_axis >= 0) c[g->flat_axis] = g->flat_coord;
}

int geometry_nearest_leaf(const Geometry *g, const double x0[3])
{
    return geometry_nearest_leaf_of(g, -1, x0);
}

int geometry_nearest_leaf_of(const Geometry *g, int surface, const double x0[3])
{
    double x[3];
    flat(g, x0, x);
    int best = 0;
    double bd = INFINITY;
    for (int i = 0; i < g->nleaves; i++) {
        if (surface >= 0 && g->leaves[i].surface != surface) continue;
        double d = leaf_distance(g->leaves[i].node, x);
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

int geometry_leaf_kind(const Geometry *g, int leaf)
{
    const GeoNode *n = g->leaves[leaf].node;
    return n->op == G_PRIM ? GEO_LEAF_SHAPE : n->cad ? GEO_LEAF_CAD : GEO_LEAF_STL;
}

const char *geometry_leaf_patch(const Geometry *g, int leaf)
{
    return g->surf[g->leaves[leaf].surface].name;
}

/* ---- level and planes (volume fractions, volfrac.c) ---- */

static double node_level(const GeoNode *n, const double x[3])
{
    double v = 0, d;
    switch (n->op) {
    case G_PRIM: {
        double l[3];
        csg_to_local(n, x, l);
        v = shape_bound(&n->shape, l);
        if (n->has_xf) v *= n->lip;
        break;
    }
    case G_TRI:
        trisurf_nearest(n->tri, x, &d);
        v = trisurf_inside(n->tri, x) ? -d : d;
        break;
    default:
        /* min and max of 1-Lipschitz functions are 1-Lipschitz */
        v = node_level(n->kids[0], x);
        for (int i = 1; i < n->nkids; i++) {
            double w = node_level(n->kids[i], x);
            v = n->op == G_UNION ? fmin(v, w) : n->op == G_INTER ? fmax(v, w) : fmax(v, -w);
        }
        break;
    }
    return n->neg ? -v : v;
}

double geometry_level(const Geometry *g, const double x[3])
{
    double y[3], v = -INFINITY;
    flat(g, x, y);
    for (int s = 0; s < g->nsurf; s++) v = fmax(v, node_level(g->surf[s].root, y));
    return v;
}

/* A box's six face planes (lo x, hi x, lo y, ...) or a half-space's
   one, in the primitive's own coordinates. */
static int prim_planes(const Shape *s, GeoPlane *pl)
{
    if (s->kind == SHAPE_HALFSPACE) {
        memcpy(pl[0].n, s->q, sizeof pl[0].n);
        pl[0].d = s->q[0] * s->p[0] + s->q[1] * s->p[1] + s->q[2] * s->p[2];
        return 1;
    }
    for (int k = 0; k < 3; k++) {
        GeoPlane *lo = &pl[2 * k], *hi = &pl[2 * k + 1];
        memset(lo, 0, sizeof *lo);
        memset(hi, 0, sizeof *hi);
        lo->n[k] = -1;
        lo->d = -s->p[k];
        hi->n[k] = 1;
        hi->d = s->q[k];
    }
    return 6;
}

/* n.l <= d in local coordinates, l = Ai (x - b): (Ai^T n).x <= d + (Ai^T n).b. */
static void plane_to_global(const GeoNode *nd, GeoPlane *p)
{
    double N[3];
    for (int i = 0; i < 3; i++) N[i] = nd->Ai[i] * p->n[0] + nd->Ai[3 + i] * p->n[1] + nd->Ai[6 + i] * p->n[2];
    memcpy(p->n, N, sizeof N);
    p->d += N[0] * nd->b[0] + N[1] * nd->b[1] + N[2] * nd->b[2];
}

/* Planes of a node that is a box, a half-space or an intersection of
   them, appended at pl + *np; -1 when it is anything else. */
static int node_planes(const GeoNode *n, GeoPlane *pl, int *np, int max)
{
    if (n->neg) return -1;
    if (n->op == G_INTER) {
        for (int i = 0; i < n->nkids; i++)
            if (node_planes(n->kids[i], pl, np, max)) return -1;
        return 0;
    }
    if (n->op != G_PRIM || (n->shape.kind != SHAPE_BOX && n->shape.kind != SHAPE_HALFSPACE) || *np + 6 > max)
        return -1;
    int k = prim_planes(&n->shape, pl + *np);
    for (int i = 0; i < k && n->has_xf; i++) plane_to_global(n, &pl[*np + i]);
    *np += k;
    return 0;
}

int geometry_planes(const Geometry *g, GeoPlane *pl, int max)
{
    int np = 0;
    if (g->nsurf != 1 || node_planes(g->surf[0].root, pl, &np, max)) return -1;
    if (g->flat_axis < 0) return np;
    /* the section plane: the flat-axis term moves into d */
    int a = g->flat_axis, k = 0;
    for (int i = 0; i < np; i++) {
        pl[i].d -= pl[i].n[a] * g->flat_coord;
        pl[i].n[a] = 0;
        if (pl[i].n[0] == 0 && pl[i].n[1] == 0 && pl[i].n[2] == 0 && pl[i].d >= 0) continue;   /* holds everywhere */
        pl[k++] = pl[i];
    }
    return k;
}

/* ---- exact volume ---- */

/* Section area of a primitive by the plane l[axis] = c in its own
   coordinates when the shape is an extrusion along that axis or a sphere;
   NAN otherwise. */
static double section_area(const Shape *s, int axis, double c)
{
    switch (s->kind) {
    case SHAPE_SPHERE: {
        double d = c - s->p[axis];
        return d * d < s->r1 * s->r1 ? M_PI * (s->r1 * s->r1 - d * d) : 0;
    }
    case SHAPE_CYLINDER: {
        double ax[3] = {s->q[0] - s->p[0], s->q[1] - s->p[1], s->q[2] - s->p[2]};
        csg_unit(ax);
        if (fabs(fabs(ax[axis]) - 1) > 1e-15) return NAN;
        double lo = fmin(s->p[axis], s->q[axis]), hi = fmax(s->p[axis], s->q[axis]);
        return (s->infinite || (c > lo && c < hi)) ? M_PI * s->r1 * s->r1 : 0;
    }
    case SHAPE_POLYGON: {
        if (s->axis != axis || !(c > s->lo && c < s->hi)) return NAN;
        double a = 0;
        for (int i = 0; i < s->npoly; i++) {
            int j = (i + 1) % s->npoly;
            a += s->poly[2 * i] * s->poly[2 * j + 1] - s->poly[2 * j] * s->poly[2 * i + 1];
        }
        return fabs(a) / 2;
    }
    case SHAPE_BOX:
        if (!(c > s->p[axis] && c < s->q[axis])) return 0;
        return (s->q[(axis + 1) % 3] - s->p[(axis + 1) % 3]) * (s->q[(axis + 2) % 3] - s->p[(axis + 2) % 3]);
    default: return NAN;
    }
}

static int bounds_inside(const GeoNode *n, const double lo[3], const double hi[3], int skip)
{
    double l[3], h[3];
    shape_bounds(&n->shape, l, h);
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? h[0] : l[0], c & 2 ? h[1] : l[1], c & 4 ? h[2] : l[2]}, x[3];
        if (skip >= 0) p[skip] = 0;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return 0;
        csg_mat_vec(n->A, p, x);
        for (int k = 0; k < 3; k++)
            if (k != skip && !(x[k] + n->b[k] >= lo[k] && x[k] + n->b[k] <= hi[k])) return 0;
    }
    return 1;
}

double geometry_exact_volume(const Geometry *g, const double lo[3], const double hi[3])
{
    if (g->nsurf != 1 || g->surf[0].root->op != G_PRIM) return NAN;
    const GeoNode *n = g->surf[0].root;
    double box = 1, v;
    int ax = g->flat_axis;
    for (int k = 0; k < 3; k++) box *= hi[k] - lo[k];
    if (ax < 0) {
        if (!bounds_inside(n, lo, hi, -1)) return NAN;
        v = shape_volume(&n->shape) * fabs(n->det);
    } else {
        /* the map must keep the flat axis: A e_ax = a e_ax */
        for (int k = 0; k < 3; k++)
            if (k != ax && (n->A[3 * k + ax] != 0 || n->A[3 * ax + k] != 0)) return NAN;
        double a = n->A[4 * ax];
        double lc = (g->flat_coord - n->b[ax]) / a;
        double sec = section_area(&n->shape, ax, lc);
        if (isnan(sec)) return NAN;
        if (!bounds_inside(n, lo, hi, ax)) return NAN;
        v = sec * fabs(n->det / a) * (hi[ax] - lo[ax]);
    }
    return g->surf[0].flow_inside ? v : box - v;
}

