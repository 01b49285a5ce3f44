/*
** geometry.c: the flow domain as one CSG tree over primitives, STL
** surfaces and CAD models (geometry.h).
**
** Tree.  Leaves are primitives (Shape), triangulated surfaces (TriSurf,
** from STL or gmsh) or nothing else; inner nodes are union, intersection
** and difference.  Each node may be complemented (`neg`): the domain root
** is the intersection of every surface's root, complemented where the
** flow is outside.  Transforms are pushed down to the leaves when the
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
** The sign of a leaf (geometry.h): the domain's outward normal points into
** the solid, so a leaf of a surface whose flow is outside enters with -1,
** and each subtracted operand of a difference flips it again.
*/
#include "geometry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cad.h"
#include "mem.h"
#include "shape.h"
#include "stl.h"
#include "trisurf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define GEO_TTOL 1e-14
#define GEO_STACK 64

enum { G_PRIM, G_TRI, G_UNION, G_INTER, G_DIFF };

struct GeoNode {
    int op;
    int neg;                 /* complement */
    int leaf;                /* leaf id (G_PRIM, G_TRI) */
    /* G_PRIM */
    Shape shape;
    int has_xf;
    double A[9], Ai[9], b[3];   /* global = A local + b; Ai = A^-1 */
    double det;
    /* G_TRI */
    TriSurf *tri;
    Cad *cad;
    /* inner nodes */
    int nkids;
    GeoNode **kids;
};

typedef struct Ev {
    double t;
    int leaf;
    int kid;
} Ev;

const DictKey geometry_keys[] = {
    {"surfaces", NULL, "one sub-dictionary per immersed surface; its name is the patch name"},
    {NULL, NULL, NULL}
};

const DictKey geometry_surface_keys[] = {
    {"type", "wall", "patch type of the surface's boundary faces"},
    {"flow", "outside", "inside | outside: where the flow domain is"},
    {"shape", NULL, "halfSpace box sphere cylinder cone torus polygon stl cad union intersection difference"},
    {NULL, NULL, NULL}
};

const DictKey geometry_shape_keys[] = {
    {"shape", NULL, "halfSpace box sphere cylinder cone torus polygon stl cad union intersection difference"},
    {"point", NULL, "halfSpace: a point on the plane"},
    {"normal", NULL, "halfSpace: outward normal (out of the solid)"},
    {"min", NULL, "box: min corner; polygon: start of the extrusion (default unbounded)"},
    {"max", NULL, "box: max corner; polygon: end of the extrusion (default unbounded)"},
    {"centre", NULL, "sphere, torus: centre"},
    {"radius", NULL, "sphere, cylinder: radius"},
    {"point1", NULL, "cylinder, cone: first axis end centre"},
    {"point2", NULL, "cylinder, cone: second axis end centre"},
    {"infinite", "no", "cylinder: unbounded along its axis (no end caps)"},
    {"radius1", NULL, "cone: radius at point1 (0 allowed)"},
    {"radius2", NULL, "cone: radius at point2 (0 allowed)"},
    {"axis", NULL, "torus: axis direction; polygon: extrusion axis x, y or z"},
    {"majorRadius", NULL, "torus: centre to tube centre"},
    {"minorRadius", NULL, "torus: tube radius"},
    {"points", NULL, "polygon: ((u v) ...) in the plane normal to axis: (y z), (z x) or (x y)"},
    {"file", NULL, "stl, cad: file name relative to the case directory"},
    {"allowOpen", "no", "stl, cad: cut a surface that is not closed (results are undefined near its holes)"},
    {"meshSize", "0", "cad: triangle size for the CAD surface triangulation (0: 1/50 of its diagonal)"},
    {"scale", "1", "transform: factor or (sx sy sz), about the origin, applied first"},
    {"rotate", "none", "transform: { axis (0 0 1); angle 30; origin (0 0 0); } in degrees, after scale"},
    {"translate", "(0 0 0)", "transform: displacement, applied last"},
    {"type", "wall", "(surface entry only) patch type"},
    {"flow", "outside", "(surface entry only) inside | outside"},
    {NULL, NULL, NULL}
};

const char geometry_help_note[] =
    "system/geometryDict: surfaces { <patch> { type wall; flow outside; shape <kind>; ... } ... }\n"
    "  union, intersection and difference take their operands from their sub-dictionaries\n"
    "  (difference: the first minus the others); any shape may carry scale, rotate, translate.\n";

/* ---- small linear algebra ---- */

static void mat_mul(const double A[9], const double B[9], double C[9])
{
    double T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
    memcpy(C, T, sizeof T);
}

static void mat_vec(const double A[9], const double x[3], double y[3])
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

/* Affine map x -> A x + b, stored as (A, b). */
typedef struct Xf {
    double A[9], b[3];
} Xf;

static const Xf xf_identity = {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};

/* outer o inner: x -> Ao (Ai x + bi) + bo */
static Xf xf_compose(const Xf *outer, const Xf *inner)
{
    Xf r;
    mat_mul(outer->A, inner->A, r.A);
    mat_vec(outer->A, inner->b, r.b);
    for (int k = 0; k < 3; k++) r.b[k] += outer->b[k];
    return r;
}

static int xf_is_identity(const Xf *x)
{
    return !memcmp(x, &xf_identity, sizeof *x);
}

/* ---- node construction and freeing ---- */

static GeoNode *node_new(int op)
{
    GeoNode *n = MEM_NEW(GeoNode, 1);
    n->op = op;
    n->leaf = -1;
    return n;
}

static void node_free(GeoNode *n)
{
    if (!n) return;
    for (int i = 0; i < n->nkids; i++) node_free(n->kids[i]);
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
        node_free(g->surf[s].root);
    }
    free(g->surf);
    free(g->leaves);
    free(g->file);
    geometry_init(g);
}

/* ---- parsing ---- */

typedef struct Parse {
    Geometry *g;
    const char *case_dir;
    int surface;
} Parse;

static int add_leaf(Parse *p, GeoNode *n, int sign)
{
    Geometry *g = p->g;
    g->leaves = mem_realloc(g->leaves, (size_t)(g->nleaves + 1) * sizeof *g->leaves);
    g->leaves[g->nleaves] = (GeoLeaf){n, p->surface, sign};
    n->leaf = g->nleaves++;
    return 0;
}

static int read_xf(const Dict *d, Xf *out, Err *e)
{
    Xf S = xf_identity, R = xf_identity, T = xf_identity;
    const DictEntry *en = dict_find(d, "scale");
    if (en) {
        const DictNode *v = dict_entry_value(en, e);
        if (!v) return -1;
        double s[3];
        if (v->kind == DN_NUMBER) {
            s[0] = s[1] = s[2] = v->num;
        } else if (dict_vector(d, "scale", s, e)) {
            return -1;
        }
        for (int k = 0; k < 3; k++) {
            if (!(s[k] != 0) || !isfinite(s[k]))
                return err_set(e, en->file, en->line, "scale factors must be finite and non-zero");
            S.A[4 * k] = s[k];
        }
    }
    const Dict *r = dict_subdict_opt(d, "rotate");
    if (r) {
        static const DictKey rk[] = {{"axis", NULL, ""}, {"angle", "(required)", ""},
                                     {"origin", "(0 0 0)", ""}, {NULL, NULL, NULL}};
        double ax[3], ang, o[3];
        static const double zero[3] = {0, 0, 0};
        if (dict_check_keys(r, rk, e) || dict_vector(r, "axis", ax, e) || dict_scalar(r, "angle", &ang, e)
            || dict_vector_or(r, "origin", zero, o, e))
            return -1;
        double len = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
        if (!(len > 0)) return err_set(e, r->file, r->line, "rotate: axis must be non-zero");
        for (int k = 0; k < 3; k++) ax[k] /= len;
        double th = ang * M_PI / 180, c = cos(th), s = sin(th), C = 1 - c;
        double x = ax[0], y = ax[1], z = ax[2];
        double M[9] = {c + x * x * C,     x * y * C - z * s, x * z * C + y * s,
                       y * x * C + z * s, c + y * y * C,     y * z * C - x * s,
                       z * x * C - y * s, z * y * C + x * s, c + z * z * C};
        memcpy(R.A, M, sizeof M);
        double Mo[3];
        mat_vec(M, o, Mo);
        for (int k = 0; k < 3; k++) R.b[k] = o[k] - Mo[k];
    } else if (dict_find(d, "rotate")) {
        const DictEntry *re = dict_find(d, "rotate");
        return err_set(e, re->file, re->line, "rotate must be a dictionary { axis (x y z); angle deg; origin (x y z); }");
    }
    static const double zero[3] = {0, 0, 0};
    if (dict_vector_or(d, "translate", zero, T.b, e)) return -1;
    Xf RS = xf_compose(&R, &S);
    *out = xf_compose(&T, &RS);
    return 0;
}

static int parse_node(Parse *p, const Dict *d, const Xf *outer, int sign, GeoNode **out, Err *e);

static int parse_csg(Parse *p, const Dict *d, int op, const Xf *xf, int sign, GeoNode *n, Err *e)
{
    for (size_t i = 0; i < d->n; i++) {
        const DictEntry *en = &d->entries[i];
        if (!en->dict || !strcmp(en->key, "rotate")) continue;
        int s = (op == G_DIFF && n->nkids > 0) ? -sign : sign;
        GeoNode *kid;
        if (parse_node(p, en->dict, xf, s, &kid, e)) return -1;
        n->kids = mem_realloc(n->kids, (size_t)(n->nkids + 1) * sizeof *n->kids);
        n->kids[n->nkids++] = kid;
    }
    if (n->nkids == 0)
        return err_set(e, d->file, d->line, "%s needs its operands as sub-dictionaries",
                       op == G_UNION ? "union" : op == G_INTER ? "intersection" : "difference");
    return 0;
}

static char *case_path(const char *case_dir, const char *f)
{
    if (f[0] == '/' || !case_dir || !*case_dir) return mem_strdup(f);
    size_t n = strlen(case_dir) + strlen(f) + 2;
    char *s = mem_alloc(n);
    snprintf(s, n, "%s/%s", case_dir, f);
    return s;
}

static int check_surface(const TriSurf *t, const char *name, int allow_open, const Dict *d, Err *e)
{
    TriTopo tp;
    trisurf_check(t, &tp);
    if (tp.nopen || tp.nnonmanifold) {
        if (allow_open) return 0;
        return err_set(e, d->file, d->line,
                       "%s is not watertight: %d open edge(s) (first at (%g %g %g)), %d non-manifold edge(s)%s; "
                       "repair it or set allowOpen yes",
                       name, tp.nopen, tp.open_at[0], tp.open_at[1], tp.open_at[2], tp.nnonmanifold,
                       tp.nnonmanifold ? "" : "");
    }
    return 0;
}

static int parse_tri(Parse *p, const Dict *d, int is_cad, const Xf *xf, GeoNode *n, Err *e)
{
    const char *f;
    int allow_open;
    double size;
    if (dict_word(d, "file", &f, e) || dict_switch_or(d, "allowOpen", 0, &allow_open, e)
        || dict_scalar_or(d, "meshSize", 0, &size, e))
        return -1;
    char *path = case_path(p->case_dir, f);
    n->tri = MEM_NEW(TriSurf, 1);
    Err e2 = {0};
    int rc;
    if (is_cad) {
        n->cad = cad_open(path, size, n->tri, &e2);
        rc = n->cad ? 0 : -1;
    } else {
        rc = stl_read(n->tri, path, &e2);
    }
    if (rc) {
        free(path);
        return err_set(e, d->file, d->line, "%s", e2.msg);
    }
    trisurf_drop_degenerate(n->tri);
    if (check_surface(n->tri, path, allow_open, d, e)) {
        free(path);
        return -1;
    }
    free(path);
    trisurf_orient(n->tri);
    if (!xf_is_identity(xf)) trisurf_transform(n->tri, xf->A, xf->b);
    if (trisurf_prepare(n->tri, &e2)) return err_set(e, d->file, d->line, "%s", e2.msg);
    return 0;
}

static int vec_or_nan(const Dict *d, const char *k, double v[3], Err *e)
{
    const double nan3[3] = {NAN, NAN, NAN};
    return dict_vector_or(d, k, nan3, v, e);
}

static int parse_prim(const Dict *d, int kind, GeoNode *n, Err *e)
{
    Shape *s = &n->shape;
    memset(s, 0, sizeof *s);
    s->kind = kind;
    int rc = 0;
    switch (kind) {
    case SHAPE_HALFSPACE: rc = dict_vector(d, "point", s->p, e) || dict_vector(d, "normal", s->q, e); break;
    case SHAPE_BOX: rc = dict_vector(d, "min", s->p, e) || dict_vector(d, "max", s->q, e); break;
    case SHAPE_SPHERE: rc = dict_vector(d, "centre", s->p, e) || dict_scalar(d, "radius", &s->r1, e); break;
    case SHAPE_CYLINDER:
        rc = dict_vector(d, "point1", s->p, e) || dict_vector(d, "point2", s->q, e)
          || dict_scalar(d, "radius", &s->r1, e) || dict_switch_or(d, "infinite", 0, &s->infinite, e);
        break;
    case SHAPE_CONE:
        rc = dict_vector(d, "point1", s->p, e) || dict_vector(d, "point2", s->q, e)
          || dict_scalar(d, "radius1", &s->r1, e) || dict_scalar(d, "radius2", &s->r2, e);
        break;
    case SHAPE_TORUS:
        rc = dict_vector(d, "centre", s->p, e) || dict_vector(d, "axis", s->q, e)
          || dict_scalar(d, "majorRadius", &s->r1, e) || dict_scalar(d, "minorRadius", &s->r2, e);
        break;
    case SHAPE_POLYGON: {
        static const char *const axes[] = {"x", "y", "z", NULL};
        if (dict_choice_or(d, "axis", axes, 2, &s->axis, e)) return -1;
        const DictEntry *en = dict_find(d, "points");
        if (!en) return err_set(e, d->file, d->line, "polygon needs 'points ((u v) ...)'");
        const DictNode *v = dict_entry_value(en, e);
        double *pts = NULL;
        size_t np = 0;
        if (!v || dict_node_scalars(v, 2, &pts, &np, e)) return -1;
        s->poly = pts;
        s->npoly = (int)np;
        double lo3[3], hi3[3];
        if (vec_or_nan(d, "min", lo3, e) || vec_or_nan(d, "max", hi3, e)) return -1;
        s->lo = isnan(lo3[s->axis]) ? -INFINITY : lo3[s->axis];
        s->hi = isnan(hi3[s->axis]) ? INFINITY : hi3[s->axis];
        break;
    }
    default: break;
    }
    if (rc) return -1;
    const char *msg = shape_check(s);
    if (msg) return err_set(e, d->file, d->line, "%s: %s", shape_kind_name(kind), msg);
    return 0;
}

/* dict_check_keys, except that a CSG node's operands are sub-dictionaries
   with names of the user's choice. */
static int check_keys(const Dict *d, int csg, Err *e)
{
    enum { NK = sizeof geometry_shape_keys / sizeof geometry_shape_keys[0] - 1 };
    const char *names[NK];
    for (int i = 0; i < NK; i++) names[i] = geometry_shape_keys[i].key;
    for (size_t i = 0; i < d->n; i++) {
        const DictEntry *en = &d->entries[i];
        if (!strcmp(en->key, "FoamFile") || (csg && en->dict && strcmp(en->key, "rotate"))) continue;
        int ok = 0;
        for (int k = 0; k < NK && !ok; k++) ok = !strcmp(en->key, names[k]);
        if (ok) continue;
        const char *near = dict_closest(en->key, names, NK);
        return err_set(e, en->file, en->line, "unknown keyword '%s' in a shape%s%s%s%s", en->key,
                       near ? "; did you mean '" : "", near ? near : "", near ? "'?" : "",
                       en->dict && !csg ? " (operands belong to union, intersection or difference)" : "");
    }
    return 0;
}

static int is_csg(const char *k)
{
    return !strcmp(k, "union") || !strcmp(k, "intersection") || !strcmp(k, "difference");
}

static int parse_node(Parse *p, const Dict *d, const Xf *outer, int sign, GeoNode **out, Err *e)
{
    *out = NULL;
    const char *kind;
    if (dict_word(d, "shape", &kind, e) || check_keys(d, is_csg(kind), e)) return -1;
    Xf local, xf;
    if (read_xf(d, &local, e)) return -1;
    xf = xf_compose(outer, &local);
    GeoNode *n;
    int rc = 0;
    if (is_csg(kind)) {
        int op = kind[0] == 'u' ? G_UNION : kind[0] == 'i' ? G_INTER : G_DIFF;
        n = node_new(op);
        rc = parse_csg(p, d, op, &xf, sign, n, e);
    } else if (!strcmp(kind, "stl") || !strcmp(kind, "cad")) {
        n = node_new(G_TRI);
        rc = parse_tri(p, d, kind[0] == 'c', &xf, n, e);
        if (!rc) add_leaf(p, n, sign);
    } else {
        int k = shape_kind(kind);
        if (k < 0) {
            const DictEntry *en = dict_find(d, "shape");
            return err_set(e, en->file, en->line,
                           "unknown shape '%s' (halfSpace, box, sphere, cylinder, cone, torus, polygon, stl, cad, "
                           "union, intersection, difference)", kind);
        }
        n = node_new(G_PRIM);
        rc = parse_prim(d, k, n, e);
        if (!rc) {
            memcpy(n->A, xf.A, sizeof xf.A);
            memcpy(n->b, xf.b, sizeof xf.b);
            n->has_xf = !xf_is_identity(&xf);
            n->det = mat_inv(n->A, n->Ai);
            add_leaf(p, n, sign);
        }
    }
    if (rc) {
        node_free(n);
        return -1;
    }
    *out = n;
    return 0;
}

int geometry_parse(Geometry *g, const Dict *d, const char *file, const char *case_dir, Err *e)
{
    geometry_init(g);
    g->file = mem_strdup(file ? file : "geometryDict");
    if (dict_check_keys(d, geometry_keys, e)) return -1;
    const Dict *surfs = dict_subdict(d, "surfaces", e);
    if (!surfs) return -1;
    Parse p = {g, case_dir, 0};
    for (size_t i = 0; i < surfs->n; i++) {
        const DictEntry *en = &surfs->entries[i];
        if (!en->dict) return err_set(e, en->file, en->line, "surface '%s' must be a dictionary", en->key);
        const Dict *sd = en->dict;
        const char *type;
        int flow;
        static const char *const flows[] = {"outside", "inside", NULL};
        if (dict_word_or(sd, "type", "wall", &type, e) || dict_choice_or(sd, "flow", flows, 0, &flow, e)) {
            geometry_free(g);
            return -1;
        }
        for (int s = 0; s < g->nsurf; s++)
            if (!strcmp(g->surf[s].name, en->key)) {
                geometry_free(g);
                return err_set(e, en->file, en->line, "surface '%s' is defined twice", en->key);
            }
        g->surf = mem_realloc(g->surf, (size_t)(g->nsurf + 1) * sizeof *g->surf);
        GeoSurface *gs = &g->surf[g->nsurf++];
        memset(gs, 0, sizeof *gs);
        gs->name = mem_strdup(en->key);
        gs->type = mem_strdup(type);
        gs->flow_inside = flow;
        gs->line = en->line;
        p.surface = g->nsurf - 1;
        if (parse_node(&p, sd, &xf_identity, flow ? 1 : -1, &gs->root, e)) {
            geometry_free(g);
            return -1;
        }
        gs->root->neg = !flow;
    }
    if (g->nsurf == 0) {
        geometry_free(g);
        return err_set(e, surfs->file, surfs->line, "no surfaces defined");
    }
    return 0;
}

int geometry_read(Geometry *g, const char *case_dir, const char *path, Err *e)
{
    char *own = NULL;
    if (!path) path = own = case_path(case_dir, "system/geometryDict");
    Dict *d = dict_read(path, e);
    int rc = -1;
    if (d) rc = geometry_parse(g, d, path, case_dir, e);
    dict_free(d);
    free(own);
    return rc;
}

void geometry_flatten(Geometry *g, int axis, double coord)
{
    g->flat_axis = axis;
    g->flat_coord = coord;
}

/* ---- point queries ---- */

static void to_local(const GeoNode *n, const double x[3], double l[3])
{
    if (!n->has_xf) {
        memcpy(l, x, 3 * sizeof *l);
        return;
    }
    double d[3] = {x[0] - n->b[0], x[1] - n->b[1], x[2] - n->b[2]};
    mat_vec(n->Ai, d, l);
}

static int node_inside(const GeoNode *n, const double x[3])
{
    int in = 0;
    switch (n->op) {
    case G_PRIM: {
        double l[3];
        to_local(n, x, l);
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
        to_local(n, a, la);
        to_local(n, b, lb);
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

static void unit(double n[3])
{
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++) n[k] /= l;
}

/* The leaf's own outward normal, in global coordinates. */
static void leaf_normal(const GeoNode *n, const double x[3], double nv[3])
{
    if (n->op == G_PRIM) {
        double l[3], nl[3];
        to_local(n, x, l);
        shape_normal(&n->shape, l, nl);
        if (!n->has_xf) {
            memcpy(nv, nl, 3 * sizeof *nv);
            return;
        }
        for (int i = 0; i < 3; i++)   /* A^-T nl */
            nv[i] = n->Ai[i] * nl[0] + n->Ai[3 + i] * nl[1] + n->Ai[6 + i] * nl[2];
        unit(nv);
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
    leaf_normal(L->node, x, n);
    for (int k = 0; k < 3; k++) n[k] *= L->sign;
    if (g->flat_axis >= 0) {
        n[g->flat_axis] = 0;
        unit(n);
    }
}

static double leaf_distance(const GeoNode *n, const double x[3])
{
    if (n->op == G_PRIM) {
        double l[3];
        to_local(n, x, l);
        double s = n->has_xf ? cbrt(fabs(n->det)) : 1;
        return fabs(shape_level(&n->shape, l)) * s;
    }
    double d;
    trisurf_nearest(n->tri, x, &d);
    return d;
}

int geometry_nearest_leaf(const Geometry *g, const double x0[3])
{
    double x[3];
    flat(g, x0, x);
    int best = 0;
    double bd = INFINITY;
    for (int i = 0; i < g->nleaves; i++) {
        double d = leaf_distance(g->leaves[i].node, x);
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

const char *geometry_leaf_patch(const Geometry *g, int leaf)
{
    return g->surf[g->leaves[leaf].surface].name;
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
        unit(ax);
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
        mat_vec(n->A, p, x);
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
