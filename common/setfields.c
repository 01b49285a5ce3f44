/*
** setfields.c: setFieldsDict parsed into SetFields, and applied.
**
** Parsing keeps the file and line of every value, so that a field missing
** from the time directory, or read with the other width, is reported at
** the dictionary line that asked for it.  A field set in several places
** gets one index (SetValue.field) at its first use; setting it once as a
** scalar and once as a vector is an error there and then.
**
** Regions are solids of the one library of primitives cutCells uses: each
** is a Geometry of one surface, flow inside (geometry.h), and its cells'
** volume fractions come from volfrac.h.  The OpenFOAM-style types
** (boxToCell, sphereToCell, ...) keep their keywords and are built with
** geometry_of_shape; shapeToCell takes any geometryDict shape, CSG and
** transforms included, through geometry_parse_solid.  A type's checks
** speak of its own keywords (p1, p2) before shape_check's.
**
** Application order is the dictionary's: defaults in every cell, then the
** regions one after the other, each blending into what the previous ones
** left (see setfields.h).  Fields are read in full before the first one is
** written.
*/
#include "setfields.h"

#include "io.h"
#include "mem.h"
#include "shape.h"
#include "volfrac.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const DictKey setfields_keys[] = {
    {"defaultFieldValues", "()", "values set in every cell first: ( volScalarFieldValue NAME v volVectorFieldValue NAME (x y z) ... )"},
    {"regions", "()", "( <type>ToCell { <shape keywords> fieldValues (...); fractional yes; } ... ), applied in order"},
    {0}};

const char setfields_help[] =
    "\nRegion types and their keywords (all take fieldValues [required] and\n"
    "fractional [yes]: yes blends by the cell's volume fraction inside the shape,\n"
    "no sets the cells whose centre is inside, as OpenFOAM does):\n"
    "  boxToCell        box (xmin ymin zmin) (xmax ymax zmax);\n"
    "  sphereToCell     centre (x y z); radius r;\n"
    "  cylinderToCell   p1 (x y z); p2 (x y z); radius r;        (finite, flat ends)\n"
    "  coneToCell       p1 (x y z); p2 (x y z); radius1 r1; radius2 r2;\n"
    "  halfSpaceToCell  point (x y z); normal (x y z);  (inside: (x - point).normal <= 0)\n"
    "  shapeToCell      shape <kind>; and the kind's keywords: any geometryDict shape\n"
    "                   (halfSpace box sphere cylinder cone torus polygon surface stl\n"
    "                   obj cad union intersection difference; operands as named\n"
    "                   sub-dictionaries; scale, rotate, translate), keywords below\n"
    "On a 2-D mesh (empty patches) each shape is its section through its centre\n"
    "(shapeToCell: through the mesh's mid-plane), extruded: a sphere, or a cylinder\n"
    "along the empty axis, sets a disc.\n";

/* The region types: dictionary name, shape kind (-1: shapeToCell, any
   geometryDict shape), keywords. */
typedef struct RegionType {
    const char *name;
    int kind;
    DictKey keys[7];
} RegionType;

static const RegionType region_types[] = {
    {"boxToCell", SHAPE_BOX,
     {{"box", NULL, "(min) (max) corners"}, {"fieldValues", NULL, "values"}, {"fractional", "yes", "volume fraction"}, {0}}},
    {"sphereToCell", SHAPE_SPHERE,
     {{"centre", NULL, "centre"}, {"radius", NULL, "radius"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
    {"cylinderToCell", SHAPE_CYLINDER,
     {{"p1", NULL, "axis start"}, {"p2", NULL, "axis end"}, {"radius", NULL, "radius"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
    {"coneToCell", SHAPE_CONE,
     {{"p1", NULL, "axis start"}, {"p2", NULL, "axis end"}, {"radius1", NULL, "radius at p1"},
      {"radius2", NULL, "radius at p2"}, {"fieldValues", NULL, "values"}, {"fractional", "yes", "volume fraction"}}},
    {"halfSpaceToCell", SHAPE_HALFSPACE,
     {{"point", NULL, "point on the plane"}, {"normal", NULL, "outward normal"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
    {"shapeToCell", -1, {{"fieldValues", NULL, "values"}, {"fractional", "yes", "volume fraction"}, {0}}},
};
enum { NTYPES = sizeof region_types / sizeof region_types[0] };

static const char *value_type(int width) { return width == 1 ? "volScalarFieldValue" : "volVectorFieldValue"; }

static int node_text(const DictNode *nd, const char **s)
{
    if (nd->kind != DN_WORD && nd->kind != DN_STRING) return -1;
    *s = nd->text;
    return 0;
}

/* A number or a (x y z) list into v; returns the width or -1. */
static int node_value(const DictNode *nd, double v[3], Err *e)
{
    if (nd->kind == DN_NUMBER) {
        v[0] = nd->num;
        return 1;
    }
    double *x = NULL;
    size_t n = 0;
    if (dict_node_scalars(nd, 1, &x, &n, e)) return -1;
    if (n != 3) {
        free(x);
        return err_set(e, nd->file, nd->line, "expected a vector (x y z), found a list of %zu numbers", n);
    }
    memcpy(v, x, 3 * sizeof *v);
    free(x);
    return 3;
}

static int field_index(SetFields *s, const SetValue *fv, Err *e)
{
    for (int i = 0; i < s->nfields; i++) {
        if (strcmp(s->fields[i], fv->name)) continue;
        if (s->widths[i] != fv->width)
            return err_set(e, fv->file, fv->line, "field '%s' is set as a %s here but as a %s at line %d", fv->name,
                           value_type(fv->width), value_type(s->widths[i]), s->field_line[i]);
        return i;
    }
    int n = s->nfields++;
    s->fields = mem_realloc(s->fields, sizeof *s->fields * (size_t)s->nfields);
    s->widths = mem_realloc(s->widths, sizeof *s->widths * (size_t)s->nfields);
    s->field_file = mem_realloc(s->field_file, sizeof *s->field_file * (size_t)s->nfields);
    s->field_line = mem_realloc(s->field_line, sizeof *s->field_line * (size_t)s->nfields);
    s->fields[n] = fv->name;
    s->widths[n] = fv->width;
    s->field_file[n] = fv->file;
    s->field_line[n] = fv->line;
    return n;
}

/* The "TYPE NAME value" triple at items[i..i+2] of list nd into fv. */
static int parse_value(SetFields *s, const DictNode *nd, size_t i, SetValue *fv, Err *e)
{
    static const char *const types[] = {"volScalarFieldValue", "volVectorFieldValue"};
    const DictNode *t = nd->items[i];
    const char *tn;
    if (node_text(t, &tn))
        return err_set(e, t->file, t->line, "expected volScalarFieldValue or volVectorFieldValue, found %s",
                       dict_node_kind_name(t));
    int width = !strcmp(tn, types[0]) ? 1 : !strcmp(tn, types[1]) ? 3 : 0;
    if (!width) {
        const char *near = dict_closest(tn, types, 2);
        return err_set(e, t->file, t->line, "unknown field value type '%s'%s%s%s", tn,
                       near ? "; did you mean '" : " (volScalarFieldValue or volVectorFieldValue)", near ? near : "",
                       near ? "'?" : "");
    }
    if (i + 2 >= nd->n) return err_set(e, t->file, t->line, "%s needs a field name and a value", tn);
    fv->width = width;
    fv->file = t->file;
    fv->line = t->line;
    if (node_text(nd->items[i + 1], &fv->name))
        return err_set(e, nd->items[i + 1]->file, nd->items[i + 1]->line, "%s: expected a field name, found %s", tn,
                       dict_node_kind_name(nd->items[i + 1]));
    int w = node_value(nd->items[i + 2], fv->v, e);
    if (w < 0) return -1;
    if (w != width)
        return err_set(e, t->file, t->line, "%s %s: expected %s, found %s", tn, fv->name,
                       width == 1 ? "a number" : "a vector (x y z)", dict_node_kind_name(nd->items[i + 2]));
    for (int k = 0; k < width; k++)
        if (!isfinite(fv->v[k])) return err_set(e, t->file, t->line, "%s %s: value is not finite", tn, fv->name);
    return (fv->field = field_index(s, fv, e)) < 0 ? -1 : 0;
}

/* Parses ( volScalarFieldValue a 0 volVectorFieldValue U (0 0 0) ). */
static int parse_values(SetFields *s, const DictNode *nd, SetValue **out, int *nout, Err *e)
{
    if (nd->kind != DN_LIST && dict_node_len(nd) != 0)
        return err_set(e, nd->file, nd->line, "expected a list ( volScalarFieldValue NAME value ... ), found %s",
                       dict_node_kind_name(nd));
    size_t n = nd->kind == DN_LIST ? nd->n : 0;
    *out = MEM_NEW(SetValue, n / 3 + 1);
    *nout = 0;
    for (size_t i = 0; i < n; i += 3)
        if (parse_value(s, nd, i, &(*out)[(*nout)++], e)) return -1;
    return 0;
}

static int entry_values(SetFields *s, const Dict *d, const char *key, int required, SetValue **out, int *n, Err *e)
{
    const DictEntry *en = dict_find(d, key);
    *out = NULL;
    *n = 0;
    if (!en) return required ? err_set(e, d->file, d->line, "keyword '%s' missing in dictionary '%s'", key, d->name) : 0;
    if (en->dict || en->nvals != 1)
        return err_set(e, en->file, en->line, "keyword '%s': expected a list ( volScalarFieldValue NAME value ... )", key);
    return parse_values(s, en->vals[0], out, n, e);
}

/* box (x y z) (x y z); */
static int read_box(const Dict *d, Shape *r, Err *e)
{
    const DictEntry *en = dict_find(d, "box");
    if (!en) return err_set(e, d->file, d->line, "keyword 'box' missing in dictionary '%s'", d->name);
    if (en->dict || en->nvals != 2)
        return err_set(e, en->file, en->line, "box: expected two corners (xmin ymin zmin) (xmax ymax zmax)");
    for (int i = 0; i < 2; i++) {
        double v[3];
        int w = node_value(en->vals[i], v, e);
        if (w < 0) return -1;
        if (w != 3) return err_set(e, en->file, en->line, "box: corner %d is not a vector (x y z)", i + 1);
        memcpy(i ? r->q : r->p, v, sizeof v);
    }
    return 0;
}

static int read_shape(const Dict *d, Shape *r, Err *e)
{
    switch (r->kind) {
    case SHAPE_BOX:
        return read_box(d, r, e);
    case SHAPE_SPHERE:
        return dict_vector(d, "centre", r->p, e) || dict_scalar(d, "radius", &r->r1, e) ? -1 : 0;
    case SHAPE_CYLINDER:
        return dict_vector(d, "p1", r->p, e) || dict_vector(d, "p2", r->q, e) || dict_scalar(d, "radius", &r->r1, e)
                   ? -1 : 0;
    case SHAPE_CONE:
        return dict_vector(d, "p1", r->p, e) || dict_vector(d, "p2", r->q, e) ||
                       dict_scalar(d, "radius1", &r->r1, e) || dict_scalar(d, "radius2", &r->r2, e)
                   ? -1 : 0;
    default:
        return dict_vector(d, "point", r->p, e) || dict_vector(d, "normal", r->q, e) ? -1 : 0;
    }
}

static const RegionType *region_type(const DictNode *t, Err *e)
{
    const char *name;
    if (node_text(t, &name))
        return err_set(e, t->file, t->line, "expected a region type (boxToCell, sphereToCell, ...), found %s",
                       dict_node_kind_name(t)), NULL;
    const char *names[NTYPES];
    for (int i = 0; i < NTYPES; i++) {
        names[i] = region_types[i].name;
        if (!strcmp(name, names[i])) return &region_types[i];
    }
    const char *near = dict_closest(name, names, NTYPES);
    if (near) err_set(e, t->file, t->line, "unknown region type '%s'; did you mean '%s'?", name, near);
    else
        err_set(e, t->file, t->line,
                "unknown region type '%s' (boxToCell, sphereToCell, cylinderToCell, coneToCell, halfSpaceToCell)", name);
    return NULL;
}

/* The checks of the ToCell types, in their keywords' terms; NULL when
   shape_check may go on. */
static const char *tocell_check(const Shape *r)
{
    double a[3] = {r->q[0] - r->p[0], r->q[1] - r->p[1], r->q[2] - r->p[2]};
    int axis = a[0] != 0 || a[1] != 0 || a[2] != 0;
    switch (r->kind) {
    case SHAPE_BOX:
        for (int k = 0; k < 3; k++)
            if (!(r->q[k] >= r->p[k])) return "box: the first corner must be the minimum and the second the maximum";
        return NULL;
    case SHAPE_SPHERE:
        return r->r1 > 0 ? NULL : "radius must be positive";
    case SHAPE_CYLINDER:
        if (!(r->r1 > 0)) return "radius must be positive";
        return axis ? NULL : "p1 and p2 must differ";
    case SHAPE_CONE:
        if (!(r->r1 >= 0 && r->r2 >= 0)) return "radius1 and radius2 must not be negative";
        if (!(r->r1 > 0 || r->r2 > 0)) return "radius1 or radius2 must be positive";
        return axis ? NULL : "p1 and p2 must differ";
    default:
        return r->q[0] != 0 || r->q[1] != 0 || r->q[2] != 0 ? NULL : "normal must be a non-zero vector";
    }
}

/* The region's solid: a ToCell type's shape, or shapeToCell's. */
static int region_solid(const RegionType *rt, const Dict *d, const char *case_dir, SetRegion *sr, Err *e)
{
    if (rt->kind < 0) return geometry_parse_solid(&sr->solid, d, rt->name, case_dir, rt->keys, e);
    Shape sh;
    memset(&sh, 0, sizeof sh);
    sh.kind = rt->kind;
    if (dict_check_keys(d, rt->keys, e) || read_shape(d, &sh, e)) return -1;
    const char *msg = tocell_check(&sh);
    if (!msg) msg = shape_check(&sh);
    if (msg) return err_set(e, d->file, d->line, "%s: %s", rt->name, msg);
    geometry_of_shape(&sr->solid, &sh, rt->name);
    /* 2-D: the section through the shape's centre (box middle,
       cylinder/cone axis middle, sphere centre, half-space point) */
    int mid = sh.kind == SHAPE_BOX || sh.kind == SHAPE_CYLINDER || sh.kind == SHAPE_CONE;
    for (int k = 0; k < 3; k++) sr->centre[k] = mid ? 0.5 * (sh.p[k] + sh.q[k]) : sh.p[k];
    sr->centred = 1;
    return 0;
}

static int parse_region(SetFields *s, const RegionType *rt, const Dict *d, const char *case_dir, SetRegion *sr,
                        Err *e)
{
    memset(sr, 0, sizeof *sr);
    sr->type = rt->name;
    sr->file = d->file;
    sr->line = d->line;
    if (region_solid(rt, d, case_dir, sr, e)) return -1;
    if (dict_switch_or(d, "fractional", 1, &sr->fractional, e) ||
        entry_values(s, d, "fieldValues", 1, &sr->vals, &sr->nvals, e))
        return -1;
    return 0;
}

int setfields_parse(SetFields *s, const Dict *d, const char *case_dir, Err *e)
{
    memset(s, 0, sizeof *s);
    if (dict_check_keys(d, setfields_keys, e)) return -1;
    if (entry_values(s, d, "defaultFieldValues", 0, &s->defaults, &s->ndefaults, e)) return -1;
    const DictEntry *en = dict_find(d, "regions");
    if (!en) return 0;
    if (en->dict || en->nvals != 1 || (en->vals[0]->kind != DN_LIST && dict_node_len(en->vals[0]) != 0))
        return err_set(e, en->file, en->line, "regions: expected a list ( boxToCell { ... } ... )");
    const DictNode *l = en->vals[0];
    size_t n = l->kind == DN_LIST ? l->n : 0;
    s->regions = MEM_NEW(SetRegion, n / 2 + 1);
    for (size_t i = 0; i < n; i += 2) {
        const RegionType *rt = region_type(l->items[i], e);
        if (!rt) return -1;
        if (i + 1 >= n || l->items[i + 1]->kind != DN_DICT)
            return err_set(e, l->items[i]->file, l->items[i]->line, "%s: expected a dictionary { ... } after it",
                           rt->name);
        SetRegion *sr = &s->regions[s->nregions++];
        if (parse_region(s, rt, l->items[i + 1]->dict, case_dir, sr, e)) return -1;
        sr->line = l->items[i]->line;
    }
    return 0;
}

void setfields_free(SetFields *s)
{
    for (int i = 0; i < s->nregions; i++) {
        free(s->regions[i].vals);
        geometry_free(&s->regions[i].solid);
    }
    free(s->regions);
    free(s->defaults);
    free(s->fields);
    free(s->widths);
    free(s->field_file);
    free(s->field_line);
    memset(s, 0, sizeof *s);
}

void setfields_on_mesh(SetFields *s, const Mesh *m, Buf *log)
{
    int flat = mesh_empty_axis(m);
    buf_printf(log, "Mesh: %d cells, %d faces, %d patches", m->ncells, m->nfaces, m->npatches);
    if (flat >= 0)
        buf_printf(log, "; 2-D (empty along %c): each shape is its section through its centre, extruded", "xyz"[flat]);
    buf_puts(log, "\n\n");
    if (flat < 0) return;
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    for (int r = 0; r < s->nregions; r++) {
        SetRegion *sr = &s->regions[r];
        geometry_flatten(&sr->solid, flat, sr->centred ? sr->centre[flat] : 0.5 * (lo[flat] + hi[flat]));
    }
}

/* ---- applying ---- */

static void set_values(Field *f, int c, double frac, const SetValue *fv)
{
    for (int k = 0; k < fv->width; k++) {
        double *v = f->v + (size_t)c * fv->width + k;
        *v = frac >= 1 ? fv->v[k] : (1 - frac) * *v + frac * fv->v[k];
    }
}

static void put_values(Buf *log, const SetValue *fv, int n)
{
    for (int i = 0; i < n; i++) {
        if (fv[i].width == 1) buf_printf(log, "        %s = %g\n", fv[i].name, fv[i].v[0]);
        else buf_printf(log, "        %s = (%g %g %g)\n", fv[i].name, fv[i].v[0], fv[i].v[1], fv[i].v[2]);
    }
}

/* The solid's own volume when known in closed form (one primitive), to
   compare with the volume set: on a 2-D mesh its section times the mesh
   thickness; NAN otherwise. */
static double solid_volume(const Geometry *g, const Mesh *m)
{
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    for (int k = 0; k < 3; k++)
        if (k != g->flat_axis) lo[k] = -INFINITY, hi[k] = INFINITY;
    return geometry_exact_volume(g, lo, hi);
}

static void apply_region(const SetRegion *r, const Mesh *m, Field *fields, Buf *log)
{
    int touched = 0, partial = 0;
    double vol = 0;
    for (int c = 0; c < m->ncells; c++) {
        double f = r->fractional ? volfrac_cell(&r->solid, m, c)
                                 : (double)volfrac_inside(&r->solid, m->cell_centre + 3 * c);
        if (f <= 0) continue;
        touched++;
        partial += f < 1;
        vol += f * m->cell_vol[c];
        for (int i = 0; i < r->nvals; i++) set_values(&fields[r->vals[i].field], c, f, &r->vals[i]);
    }
    buf_printf(log, "    %s (%s:%d): %d cells touched, %d of them partly; volume set %.10g", r->type, r->file,
               r->line, touched, partial, vol);
    double exact = solid_volume(&r->solid, m);
    if (isfinite(exact))
        buf_printf(log, " (shape %s %.10g)", r->solid.flat_axis >= 0 ? "section x thickness" : "volume", exact);
    buf_putc(log, '\n');
    put_values(log, r->vals, r->nvals);
}

static void apply(const SetFields *s, const Mesh *m, Field *fields, Buf *log)
{
    if (s->ndefaults) buf_puts(log, "Setting field default values\n");
    put_values(log, s->defaults, s->ndefaults);
    for (int i = 0; i < s->ndefaults; i++)
        for (int c = 0; c < m->ncells; c++) set_values(&fields[s->defaults[i].field], c, 1, &s->defaults[i]);
    if (s->nregions) buf_puts(log, "\nSetting field region values\n");
    for (int r = 0; r < s->nregions; r++) apply_region(&s->regions[r], m, fields, log);
}

/* Field i, checked against the width the dictionary sets it with. */
static int read_field(const SetFields *s, int i, const Mesh *m, const char *case_dir, const char *time, Field *f,
                      Err *e)
{
    char *path;
    int rc = field_read_time(f, m, case_dir, time, s->fields[i], &path, e);
    if (rc > 0)
        rc = err_set(e, s->field_file[i], s->field_line[i], "field '%s' not found: %s does not exist", s->fields[i],
                     path);
    else if (!rc && f->width != s->widths[i])
        rc = err_set(e, s->field_file[i], s->field_line[i], "field '%s' is a %s, but is set with %s", s->fields[i],
                     f->width == 1 ? "volScalarField" : "volVectorField", value_type(s->widths[i]));
    free(path);
    return rc;
}

static int write_fields(const SetFields *s, const Mesh *m, const char *case_dir, const char *time,
                        const FieldWriteOpts *wo, const Field *fields, Buf *log, Err *e)
{
    FieldWriteOpts o = *wo;
    o.location = time;
    int rc = 0;
    for (int i = 0; i < s->nfields && !rc; i++) {
        char *path = field_time_path(case_dir, time, s->fields[i]);
        rc = field_write(&fields[i], m, path, &o, e);
        if (!rc) buf_printf(log, "\nWriting %s", path);
        free(path);
    }
    buf_puts(log, "\n\n");
    return rc;
}

int setfields_time(const SetFields *s, const Mesh *m, const char *case_dir, const char *time,
                   const FieldWriteOpts *o, Buf *log, Buf *warn, Err *e)
{
    Field *fields = MEM_NEW(Field, s->nfields);
    int rc = 0;
    for (int i = 0; i < s->nfields && !rc; i++) {
        rc = read_field(s, i, m, case_dir, time, &fields[i], e);
        for (int k = 0; !rc && k < fields[i].nwarn; k++) buf_printf(warn, "%s\n", fields[i].warn[k]);
    }
    if (!rc) {
        apply(s, m, fields, log);
        rc = write_fields(s, m, case_dir, time, o, fields, log, e);
    }
    field_free_all(fields, s->nfields);
    return rc;
}
