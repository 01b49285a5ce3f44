/*
** geometry_dict.c: reading system/geometryDict into the CSG tree of a
** Geometry (geometry_read, geometry_parse; the tree is csg.h), and one
** shape dictionary into a Geometry of one solid (geometry_parse_solid,
** setFields' shapeToCell regions).
**
** Keywords: a surface entry is a shape dictionary plus its patch type and
** flow side; a shape dictionary names its kind (`shape`) and carries the
** kind's keywords (geometry_shape_keys, the union over kinds, for -help
** and for the nearest-keyword hint), or, for union, intersection and
** difference, its operands as sub-dictionaries with names of the user's
** choice.  Transforms are read at every level and composed on the way
** down (outer o inner), so every leaf gets one affine map: primitives
** keep it (csg_node_set_map), triangulated surfaces have their points
** moved.  File names (stl, obj, cad) are relative to the case directory.
*/
#include "csg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cad.h"
#include "io.h"
#include "mem.h"
#include "surface.h"
#include "trisurf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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
    csg_mat_vec(outer->A, inner->b, r.b);
    for (int k = 0; k < 3; k++) r.b[k] += outer->b[k];
    return r;
}

static int xf_is_identity(const Xf *x)
{
    return !memcmp(x, &xf_identity, sizeof *x);
}

/* ---- parsing ---- */

typedef struct Parse {
    Geometry *g;
    const char *case_dir;
    int surface;
    const Dict *top;           /* the shape dictionary that may carry extra */
    const DictKey *extra;      /* keywords of the caller's (NULL: none) */
} Parse;

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
        csg_mat_vec(M, o, Mo);
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
    char *path = f[0] == '/' || !p->case_dir ? mem_strdup(f) : io_join(p->case_dir, f);
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
static int check_keys(const Dict *d, int csg, const DictKey *extra, Err *e)
{
    enum { NK = sizeof geometry_shape_keys / sizeof geometry_shape_keys[0] - 1, NX = 8 };
    const char *names[NK + NX];
    int nk = 0;
    for (int i = 0; i < NK; i++) names[nk++] = geometry_shape_keys[i].key;
    for (int i = 0; extra && extra[i].key && i < NX; i++) names[nk++] = extra[i].key;
    for (size_t i = 0; i < d->n; i++) {
        const DictEntry *en = &d->entries[i];
        if (!strcmp(en->key, "FoamFile") || (csg && en->dict && strcmp(en->key, "rotate"))) continue;
        int ok = 0;
        for (int k = 0; k < nk && !ok; k++) ok = !strcmp(en->key, names[k]);
        if (ok) continue;
        const char *near = dict_closest(en->key, names, nk);
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
    if (dict_word(d, "shape", &kind, e) || check_keys(d, is_csg(kind), d == p->top ? p->extra : NULL, e)) return -1;
    Xf local, xf;
    if (read_xf(d, &local, e)) return -1;
    xf = xf_compose(outer, &local);
    GeoNode *n;
    int rc = 0;
    if (is_csg(kind)) {
        int op = kind[0] == 'u' ? G_UNION : kind[0] == 'i' ? G_INTER : G_DIFF;
        n = csg_node_new(op);
        rc = parse_csg(p, d, op, &xf, sign, n, e);
    } else if (!strcmp(kind, "surface") || !strcmp(kind, "stl") || !strcmp(kind, "obj") || !strcmp(kind, "cad")) {
        n = csg_node_new(G_TRI);
        rc = parse_tri(p, d, kind[0] == 'c', &xf, n, e);
        if (!rc) csg_add_leaf(p->g, n, p->surface, sign);
    } else {
        int k = shape_kind(kind);
        if (k < 0) {
            const DictEntry *en = dict_find(d, "shape");
            return err_set(e, en->file, en->line,
                           "unknown shape '%s' (halfSpace, box, sphere, cylinder, cone, torus, polygon, surface, "
                           "stl, obj, cad, union, intersection, difference)", kind);
        }
        n = csg_node_new(G_PRIM);
        rc = parse_prim(d, k, n, e);
        if (!rc) {
            csg_node_set_map(n, xf.A, xf.b);
            csg_add_leaf(p->g, n, p->surface, sign);
        }
    }
    if (rc) {
        csg_node_free(n);
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
    Parse p = {g, case_dir, 0, NULL, NULL};
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
        p.surface = csg_add_surface(g, en->key, type, flow, en->line);
        GeoSurface *gs = &g->surf[p.surface];
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
    if (!path) path = own = io_join(case_dir ? case_dir : "", "system/geometryDict");
    Dict *d = dict_read(path, e);
    int rc = -1;
    if (d) rc = geometry_parse(g, d, path, case_dir, e);
    dict_free(d);
    free(own);
    return rc;
}


int geometry_parse_solid(Geometry *g, const Dict *d, const char *name, const char *case_dir, const DictKey *extra,
                         Err *e)
{
    geometry_init(g);
    g->file = mem_strdup(d->file ? d->file : name);
    Parse p = {g, case_dir, 0, d, extra};
    p.surface = csg_add_surface(g, name, "wall", 1, d->line);
    if (parse_node(&p, d, &xf_identity, 1, &g->surf[p.surface].root, e)) {
        geometry_free(g);
        return -1;
    }
    return 0;
}
