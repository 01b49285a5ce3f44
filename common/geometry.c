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
#include "surface.h"
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
    {"shape", NULL, "halfSpace box sphere cylinder cone torus polygon surface stl obj cad union intersection difference"},
    {NULL, NULL, NULL}
};

const DictKey geometry_shape_keys[] = {
    {"shape", NULL, "halfSpace box sphere cylinder cone torus polygon surface stl obj cad union intersection difference"},
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
    {"file", NULL, "surface, cad: file name relative to the case directory (surface: STL or OBJ, maybe .gz)"},
    {"allowOpen", "no", "surface, cad: cut a surface that is not closed (results are undefined near its holes)"},
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
    if (is_cad && !surface_obj_name(path)) {   /* gmsh reads no OBJ: ours does */
        n->cad = cad_open(path, size, n->tri, &e2);
        rc = n->cad ? 0 : -1;
    } else {
        rc = surface_read(n->tri, path, &e2);
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
    } else if (!strcmp(kind, "surface") || !strcmp(kind, "stl") || !strcmp(kind, "obj") || !strcmp(kind, "cad")) {
        n = node_new(G_TRI);
        rc = parse_tri(p, d, kind[0] == 'c', &xf, n, e);
        if (!rc) add_leaf(p, n, sign);
    } else {
        int k = shape_kind(kind);
        if (k < 0) {
            const DictEntry *en = dict_find(d, "shape");
            return err_set(e, en->file, en->line,
                           "unknown shape '%s' (halfSpace, box, sphere, cylinder, cone, torus, polygon, surface, "
                           "stl, obj, cad, union, intersection, difference)", kind);
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

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Point of primitive leaf n's surface nearest to x (for a transformed
   leaf: the image of the nearest point in its own coordinates, a point of
   the surface near x). */
static void leaf_closest(const Geometry *g, const GeoNode *n, const double x[3], double c[3])
{
    double l[3], cl[3];
    to_local(n, x, l);
    shape_closest(&n->shape, l, cl);
    if (n->has_xf) {
        mat_vec(n->A, cl, c);
        for (int k = 0; k < 3; k++) c[k] += n->b[k];
    } else {
        memcpy(c, cl, sizeof cl);
    }
    if (g->flat_axis >= 0) c[g->flat_axis] = g->flat_coord;
}

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
        leaf_closest(g, nb, q, y);
        leaf_closest(g, na, y, q);
        if (dist3(q, y) <= tol) return 1;
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
            leaf_closest(g, g->leaves[b].node, xp, c);
            if (dist3(c, xp) > h || !curve_project(g, a, b, xp, tol, q)) continue;
            /* the curve within reach of this sample only */
            if (dist3(q, xp) > 2 * h) continue;
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
        mat_vec(nd->A, l, x);
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
    unit(n);
    for (int k = 0; k < 3; k++) n[k] *= L->sign;
}

/* Bounding box in the leaf's coordinates of the global box lo..hi. */
static void gs_local_box(const GeoNode *n, const double lo[3], const double hi[3], double llo[3], double lhi[3])
{
    for (int k = 0; k < 3; k++) llo[k] = INFINITY, lhi[k] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]}, l[3];
        to_local(n, p, l);
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
    unit(nn);
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
        to_local(nd, a, la);
        to_local(nd, b, lb);
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
        if (nd->op == G_PRIM || nd->cad) leaf_normal(nd, x, n + 3 * i);
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
                unit(ni);
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
