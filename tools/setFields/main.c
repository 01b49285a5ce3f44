/*
** setFields: sets field values in regions of the domain, from
** system/setFieldsDict in OpenFOAM's syntax.  See doc/tools/setFields.md.
**
**   defaultFieldValues ( volScalarFieldValue alpha.s 0 ... );
**   regions ( sphereToCell { centre (..); radius ..; fieldValues (..); } ... );
**
** Every cell first gets the default values; then each region, in order,
** blends its values in with the cell's volume fraction f inside the shape:
** v = (1 - f) v + f v_region (region.c; `fractional no;` uses OpenFOAM's
** rule instead: f = 1 when the cell centre is inside, else 0).  On a 2-D
** mesh (one cell thick between empty patches) each shape is replaced by
** its section through its centre, extruded (region_flatten), so spheres
** and cylinders along the empty axis set discs.  Boundary conditions are
** written back as read.
**
** The whole dictionary is checked and every field read before anything is
** written, and each field file is replaced atomically, so a bad dictionary
** or a missing field leaves the case untouched.
*/
#include "args.h"
#include "dict.h"
#include "err.h"
#include "field.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "region.h"
#include "runtime.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const DictKey top_keys[] = {
    {"defaultFieldValues", "()", "values set in every cell first: ( volScalarFieldValue NAME v volVectorFieldValue NAME (x y z) ... )"},
    {"regions", "()", "( <type>ToCell { <shape keywords> fieldValues (...); fractional yes; } ... ), applied in order"},
    {0}};

static const char help_note[] =
    "\nRegion types and their keywords (all take fieldValues [required] and\n"
    "fractional [yes]: yes blends by the cell's volume fraction inside the shape,\n"
    "no sets the cells whose centre is inside, as OpenFOAM does):\n"
    "  boxToCell        box (xmin ymin zmin) (xmax ymax zmax);\n"
    "  sphereToCell     centre (x y z); radius r;\n"
    "  cylinderToCell   p1 (x y z); p2 (x y z); radius r;        (finite, flat ends)\n"
    "  coneToCell       p1 (x y z); p2 (x y z); radius1 r1; radius2 r2;\n"
    "  halfSpaceToCell  point (x y z); normal (x y z);  (inside: (x - point).normal <= 0)\n"
    "On a 2-D mesh (empty patches) each shape is its section through its centre,\n"
    "extruded: a sphere, or a cylinder along the empty axis, sets a disc.\n";

static const ArgDict dicts[] = {{"system/setFieldsDict", top_keys, help_note}, {0}};

static const ToolInfo tool = {"setFields", "sets field values in boxes, spheres, cylinders, cones, half-spaces",
                              NULL, dicts, 1};

/* The region types: dictionary name, shape, keywords. */
typedef struct RegionType {
    const char *name;
    int kind;
    DictKey keys[7];
} RegionType;

static const RegionType region_types[] = {
    {"boxToCell", REGION_BOX,
     {{"box", NULL, "(min) (max) corners"}, {"fieldValues", NULL, "values"}, {"fractional", "yes", "volume fraction"}, {0}}},
    {"sphereToCell", REGION_SPHERE,
     {{"centre", NULL, "centre"}, {"radius", NULL, "radius"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
    {"cylinderToCell", REGION_CYLINDER,
     {{"p1", NULL, "axis start"}, {"p2", NULL, "axis end"}, {"radius", NULL, "radius"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
    {"coneToCell", REGION_CONE,
     {{"p1", NULL, "axis start"}, {"p2", NULL, "axis end"}, {"radius1", NULL, "radius at p1"},
      {"radius2", NULL, "radius at p2"}, {"fieldValues", NULL, "values"}, {"fractional", "yes", "volume fraction"}}},
    {"halfSpaceToCell", REGION_HALFSPACE,
     {{"point", NULL, "point on the plane"}, {"normal", NULL, "outward normal"}, {"fieldValues", NULL, "values"},
      {"fractional", "yes", "volume fraction"}, {0}}},
};
enum { NTYPES = sizeof region_types / sizeof region_types[0] };

/* One "volScalarFieldValue NAME value" item. */
typedef struct FieldValue {
    const char *name;
    int width;
    double v[3];
    int field;       /* index into the list of fields */
    const char *file;
    int line;
} FieldValue;

typedef struct SetRegion {
    const RegionType *type;
    Region shape;
    int fractional;
    FieldValue *vals;
    int nvals;
    const char *file;
    int line;
} SetRegion;

typedef struct Setup {
    FieldValue *defaults;
    int ndefaults;
    SetRegion *regions;
    int nregions;
    const char **fields;   /* distinct field names in order of first use */
    int *widths;
    const char **field_file;
    int *field_line;
    int nfields;
} Setup;

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

static int field_index(Setup *s, const FieldValue *fv, Err *e)
{
    for (int i = 0; i < s->nfields; i++) {
        if (strcmp(s->fields[i], fv->name)) continue;
        if (s->widths[i] != fv->width)
            return err_set(e, fv->file, fv->line, "field '%s' is set as a %s here but as a %s at line %d", fv->name,
                           fv->width == 1 ? "volScalarFieldValue" : "volVectorFieldValue",
                           s->widths[i] == 1 ? "volScalarFieldValue" : "volVectorFieldValue", s->field_line[i]);
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

/* Parses ( volScalarFieldValue a 0 volVectorFieldValue U (0 0 0) ). */
static int parse_values(Setup *s, const DictNode *nd, FieldValue **out, int *nout, Err *e)
{
    static const char *const types[] = {"volScalarFieldValue", "volVectorFieldValue"};
    if (nd->kind != DN_LIST && dict_node_len(nd) != 0)
        return err_set(e, nd->file, nd->line, "expected a list ( volScalarFieldValue NAME value ... ), found %s",
                       dict_node_kind_name(nd));
    size_t n = nd->kind == DN_LIST ? nd->n : 0;
    *out = MEM_NEW(FieldValue, n / 3 + 1);
    *nout = 0;
    for (size_t i = 0; i < n; i += 3) {
        const DictNode *t = nd->items[i];
        const char *tn;
        if (node_text(t, &tn))
            return err_set(e, t->file, t->line, "expected volScalarFieldValue or volVectorFieldValue, found %s",
                           dict_node_kind_name(t));
        int width = !strcmp(tn, types[0]) ? 1 : !strcmp(tn, types[1]) ? 3 : 0;
        if (!width) {
            const char *near = dict_closest(tn, types, 2);
            return err_set(e, t->file, t->line, "unknown field value type '%s'%s%s%s", tn,
                           near ? "; did you mean '" : " (volScalarFieldValue or volVectorFieldValue)",
                           near ? near : "", near ? "'?" : "");
        }
        if (i + 2 >= n) return err_set(e, t->file, t->line, "%s needs a field name and a value", tn);
        FieldValue *fv = &(*out)[(*nout)++];
        fv->width = width;
        fv->file = t->file;
        fv->line = t->line;
        if (node_text(nd->items[i + 1], &fv->name))
            return err_set(e, nd->items[i + 1]->file, nd->items[i + 1]->line, "%s: expected a field name, found %s",
                           tn, dict_node_kind_name(nd->items[i + 1]));
        int w = node_value(nd->items[i + 2], fv->v, e);
        if (w < 0) return -1;
        if (w != width)
            return err_set(e, t->file, t->line, "%s %s: expected %s, found %s", tn, fv->name,
                           width == 1 ? "a number" : "a vector (x y z)", dict_node_kind_name(nd->items[i + 2]));
        for (int k = 0; k < width; k++)
            if (!isfinite(fv->v[k])) return err_set(e, t->file, t->line, "%s %s: value is not finite", tn, fv->name);
        if ((fv->field = field_index(s, fv, e)) < 0) return -1;
    }
    return 0;
}

static int entry_values(Setup *s, const Dict *d, const char *key, int required, FieldValue **out, int *n, Err *e)
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
static int read_box(const Dict *d, Region *r, Err *e)
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

static int read_shape(const Dict *d, Region *r, Err *e)
{
    switch (r->kind) {
    case REGION_BOX:
        return read_box(d, r, e);
    case REGION_SPHERE:
        return dict_vector(d, "centre", r->p, e) || dict_scalar(d, "radius", &r->r1, e) ? -1 : 0;
    case REGION_CYLINDER:
        return dict_vector(d, "p1", r->p, e) || dict_vector(d, "p2", r->q, e) || dict_scalar(d, "radius", &r->r1, e)
                   ? -1 : 0;
    case REGION_CONE:
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

static int parse_region(Setup *s, const RegionType *rt, const Dict *d, SetRegion *sr, Err *e)
{
    memset(sr, 0, sizeof *sr);
    sr->type = rt;
    sr->file = d->file;
    sr->line = d->line;
    sr->shape.kind = rt->kind;
    if (dict_check_keys(d, rt->keys, e) || read_shape(d, &sr->shape, e) ||
        dict_switch_or(d, "fractional", 1, &sr->fractional, e) ||
        entry_values(s, d, "fieldValues", 1, &sr->vals, &sr->nvals, e))
        return -1;
    const char *msg = region_check(&sr->shape);
    if (msg) return err_set(e, d->file, d->line, "%s: %s", rt->name, msg);
    return 0;
}

static int parse_setup(Setup *s, const Dict *d, Err *e)
{
    memset(s, 0, sizeof *s);
    if (dict_check_keys(d, top_keys, e)) return -1;
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
        if (parse_region(s, rt, l->items[i + 1]->dict, &s->regions[s->nregions], e)) return -1;
        s->regions[s->nregions].line = l->items[i]->line;
        s->nregions++;
    }
    return 0;
}

static void free_setup(Setup *s)
{
    for (int i = 0; i < s->nregions; i++) free(s->regions[i].vals);
    free(s->regions);
    free(s->defaults);
    free(s->fields);
    free(s->widths);
    free(s->field_file);
    free(s->field_line);
}

/* ---- times ---- */

/* Names of the time directories to process: the -time/-latestTime
   selection, else controlDict's start time (0 without a controlDict). */
static int select_times(const Args *a, const Control *ctl, int have_ctl, char ***names, Err *e)
{
    TimeDir *t = NULL;
    int n = runtime_list_times(a->case_dir, &t, e);
    if (n < 0) return -1;
    int k;
    if (a->time_spec || a->latest || a->nozero) {
        k = runtime_select(t, n, a->time_spec, a->latest, a->nozero, e);
        if (k < 0) {
            runtime_free_times(t, n);
            return -1;
        }
        if (k == 0) {
            runtime_free_times(t, n);
            return err_set(e, a->case_dir, 0, "no time directory matches the selection");
        }
    } else {
        char name[64] = "0";
        int pick = -1;
        if (have_ctl && ctl->startFrom == START_LATEST) pick = n - 1;
        else if (have_ctl && ctl->startFrom == START_FIRST) pick = n ? 0 : -1;
        else {
            if (have_ctl) runtime_time_name(ctl, ctl->startTime, name);
            for (int i = 0; i < n; i++)
                if (!strcmp(t[i].name, name)) pick = i;
        }
        if (pick < 0) {
            runtime_free_times(t, n);
            return err_set(e, a->case_dir, 0, "start time directory '%s' not found", name);
        }
        TimeDir keep = t[pick];
        t[pick] = t[0];
        t[0] = keep;
        k = 1;
    }
    *names = MEM_NEW(char *, k);
    for (int i = 0; i < k; i++) (*names)[i] = mem_strdup(t[i].name);
    runtime_free_times(t, n);
    return k;
}

/* ---- applying ---- */

static void set_values(Field *f, int c, double frac, const FieldValue *fv)
{
    for (int k = 0; k < fv->width; k++) {
        double *v = f->v + (size_t)c * fv->width + k;
        *v = frac >= 1 ? fv->v[k] : (1 - frac) * *v + frac * fv->v[k];
    }
}

static void print_values(FILE *out, const FieldValue *fv, int n)
{
    for (int i = 0; i < n; i++) {
        if (fv[i].width == 1) fprintf(out, "        %s = %g\n", fv[i].name, fv[i].v[0]);
        else fprintf(out, "        %s = (%g %g %g)\n", fv[i].name, fv[i].v[0], fv[i].v[1], fv[i].v[2]);
    }
}

static void apply_region(const Args *a, const SetRegion *r, const Mesh *m, Field *fields)
{
    int touched = 0, partial = 0;
    double vol = 0;
    for (int c = 0; c < m->ncells; c++) {
        double f = r->fractional ? region_fraction(&r->shape, m, c)
                                 : (double)region_inside(&r->shape, m->cell_centre + 3 * c);
        if (f <= 0) continue;
        touched++;
        partial += f < 1;
        vol += f * m->cell_vol[c];
        for (int i = 0; i < r->nvals; i++) set_values(&fields[r->vals[i].field], c, f, &r->vals[i]);
    }
    fprintf(a->info, "    %s (%s:%d): %d cells touched, %d of them partly; volume set %.10g", r->type->name,
            r->file, r->line, touched, partial, vol);
    double exact = region_volume(&r->shape);
    if (r->shape.flat) {
        double lo[3], hi[3];
        mesh_bounds(m, lo, hi);
        int ax = r->shape.flat_axis;
        exact = region_flat_area(&r->shape) * (hi[ax] - lo[ax]);
    }
    if (isfinite(exact)) fprintf(a->info, " (shape %s %.10g)", r->shape.flat ? "section x thickness" : "volume", exact);
    fprintf(a->info, "\n");
    print_values(a->info, r->vals, r->nvals);
}

static int read_fields(const Args *a, const Setup *s, const Mesh *m, const char *time, Field *fields, Err *e)
{
    for (int i = 0; i < s->nfields; i++) {
        char rel[4096];
        snprintf(rel, sizeof rel, "%s/%s", time, s->fields[i]);
        char *path = args_case_path(a, rel);
        int found = io_exists_gz(path);
        if (!found) {
            err_set(e, s->field_file[i], s->field_line[i], "field '%s' not found: %s does not exist", s->fields[i],
                    path);
            free(path);
            return -1;
        }
        int rc = field_read(&fields[i], m, path, e);
        if (!rc && fields[i].width != s->widths[i])
            rc = err_set(e, s->field_file[i], s->field_line[i], "field '%s' is a %s, but is set with %s", s->fields[i],
                         fields[i].width == 1 ? "volScalarField" : "volVectorField",
                         s->widths[i] == 1 ? "volScalarFieldValue" : "volVectorFieldValue");
        free(path);
        if (rc) return -1;
    }
    return 0;
}

static int process_time(const Args *a, const Setup *s, const Mesh *m, const char *time, const FieldWriteOpts *wo,
                        Err *e)
{
    log_time(a, time);
    Field *fields = MEM_NEW(Field, s->nfields);
    int rc = read_fields(a, s, m, time, fields, e);
    if (!rc) {
        if (s->ndefaults) fprintf(a->info, "Setting field default values\n");
        print_values(a->info, s->defaults, s->ndefaults);
        for (int i = 0; i < s->ndefaults; i++)
            for (int c = 0; c < m->ncells; c++) set_values(&fields[s->defaults[i].field], c, 1, &s->defaults[i]);
        if (s->nregions) fprintf(a->info, "\nSetting field region values\n");
        for (int r = 0; r < s->nregions; r++) apply_region(a, &s->regions[r], m, fields);
        FieldWriteOpts o = *wo;
        o.location = time;
        for (int i = 0; i < s->nfields && !rc; i++) {
            char rel[4096];
            snprintf(rel, sizeof rel, "%s/%s", time, s->fields[i]);
            char *path = args_case_path(a, rel);
            rc = field_write(&fields[i], m, path, &o, e);
            if (!rc) fprintf(a->info, "\nWriting %s", path);
            free(path);
        }
        fprintf(a->info, "\n\n");
    }
    for (int i = 0; i < s->nfields; i++) field_free(&fields[i]);
    free(fields);
    return rc;
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    args_banner(&a, &tool);

    char *dpath = a.dict ? mem_strdup(a.dict) : args_case_path(&a, "system/setFieldsDict");
    Dict *d = dict_read(dpath, &e);
    Setup s;
    if (!d || parse_setup(&s, d, &e)) err_die(&e);
    if (s.nfields == 0) err_fatal("%s: no field values to set", dpath);

    Control ctl;
    memset(&ctl, 0, sizeof ctl);
    char *cpath = args_case_path(&a, "system/controlDict");
    int have_ctl = io_exists(cpath);
    if (have_ctl && runtime_read_control(&ctl, a.case_dir, &e)) err_die(&e);
    FieldWriteOpts wo = {0, 0, 0, NULL};
    if (have_ctl) wo = (FieldWriteOpts){ctl.writeBinary, ctl.writeCompression, ctl.writePrecision, NULL};

    char **times = NULL;
    int nt = select_times(&a, &ctl, have_ctl, &times, &e);
    if (nt < 0) err_die(&e);

    Mesh m;
    mesh_init(&m);
    char *mpath = args_case_path(&a, "constant/polyMesh");
    if (mesh_read(&m, mpath, &e)) err_die(&e);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    int flat = mesh_empty_axis(&m);
    fprintf(a.info, "Mesh: %d cells, %d faces, %d patches", m.ncells, m.nfaces, m.npatches);
    if (flat >= 0)
        fprintf(a.info, "; 2-D (empty along %c): each shape is its section through its centre, extruded",
                "xyz"[flat]);
    fprintf(a.info, "\n\n");
    for (int r = 0; r < s.nregions; r++) region_flatten(&s.regions[r].shape, flat);

    for (int i = 0; i < nt; i++)
        if (process_time(&a, &s, &m, times[i], &wo, &e)) err_die(&e);

    log_exec(&a);
    log_end(&a);
    for (int i = 0; i < nt; i++) free(times[i]);
    free(times);
    mesh_free(&m);
    free_setup(&s);
    dict_free(d);
    if (have_ctl) runtime_free_control(&ctl);
    free(mpath);
    free(cpath);
    free(dpath);
    args_free(&a);
    return 0;
}
