/*
** sampleLine: samples fields along straight lines into CSV files, from
** system/sampleLineDict.  See doc/tools/sampleLine.md.
**
**   fields (alpha.s U);
**   interpolation cell;            // or linear
**   lines
**   {
**       centre { start (0 0.5 0.05); end (1 0.5 0.05); nPoints 101; }
**       column { start (0.5 0 0.05); end (0.5 1 0.05); mode cells; }
**   }
**
** Output: postProcessing/sampleLine/<time>/<line>.csv with the header
** distance,x,y,z,<scalar>,<vector>_x,<vector>_y,<vector>_z[,length]; or,
** with "-o -", the same CSV on stdout (banner and log on stderr).  The
** dictionary, every line and every field are checked before anything is
** written.
*/
#include "args.h"
#include "dict.h"
#include "err.h"
#include "field.h"
#include "foam.h"
#include "io.h"
#include "locate.h"
#include "mem.h"
#include "mesh.h"
#include "runtime.h"
#include "sample.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const DictKey top_keys[] = {
    {"fields", NULL, "fields to sample: (alpha.s U); vectors give columns U_x U_y U_z"},
    {"interpolation", "cell", "cell (the cell's value) | linear (cell value + least-squares gradient . (x - x_cell))"},
    {"lines", NULL, "{ NAME { start (x y z); end (x y z); nPoints N; mode uniform; } ... } or ( NAME { ... } ... )"},
    {0}};

static const DictKey line_keys[] = {
    {"start", NULL, "first point"},
    {"end", NULL, "last point"},
    {"mode", "uniform", "uniform (nPoints evenly spaced points) | cells (one sample per cell crossed)"},
    {"nPoints", "100", "number of points (uniform mode)"},
    {0}};

static const char help_note[] =
    "\nKeywords of each line (start, end [required]; mode [uniform]; nPoints [100]):\n"
    "  uniform: nPoints points from start to end, both included;\n"
    "  cells:   one sample per cell crossed, at the middle of the crossing, with\n"
    "           an extra column 'length' (the length of the crossing).\n"
    "Points outside the mesh are skipped (reported once per line).  Output:\n"
    "postProcessing/sampleLine/<time>/<line>.csv (or under -o DIR), columns\n"
    "distance,x,y,z,<fields>[,length].\n";

static const ArgOpt opts[] = {
    {"-o", "DIR", "output directory (default: postProcessing/sampleLine); '-' = CSV to stdout"},
    {"-line", "NAME", "sample only this line"},
    {0}};

static const ArgDict dicts[] = {{"system/sampleLineDict", top_keys, help_note}, {0}};

static const ToolInfo tool = {"sampleLine", "samples fields along lines to CSV", opts, dicts, 1};

typedef struct Line {
    const char *name;
    double a[3], b[3];
    int mode, npoints;
    int reported;       /* points outside the mesh already reported */
} Line;

typedef struct Setup {
    const char **fields;
    const char *fields_file;
    int fields_line;
    int nfields;
    int interp;
    Line *lines;
    int nlines;
} Setup;

static int parse_line(const Dict *d, const char *name, Line *l, Err *e)
{
    static const char *const modes[] = {"uniform", "cells", NULL};
    memset(l, 0, sizeof *l);
    l->name = name;
    if (dict_check_keys(d, line_keys, e) || dict_vector(d, "start", l->a, e) || dict_vector(d, "end", l->b, e) ||
        dict_choice_or(d, "mode", modes, SAMPLE_UNIFORM, &l->mode, e) ||
        dict_label_or(d, "nPoints", 100, &l->npoints, e))
        return -1;
    if (l->mode == SAMPLE_UNIFORM && (l->npoints < 1 || l->npoints > 10000000))
        return err_set(e, d->file, d->line, "line '%s': nPoints must be between 1 and 10000000, found %d", name,
                       l->npoints);
    if (l->mode == SAMPLE_CELLS && !(l->a[0] != l->b[0] || l->a[1] != l->b[1] || l->a[2] != l->b[2]))
        return err_set(e, d->file, d->line, "line '%s': start and end must differ in cells mode", name);
    for (const char *c = name; *c; c++)
        if (*c == '/' || *c == '\\')
            return err_set(e, d->file, d->line, "line name '%s' must not contain '/' (it names a file)", name);
    return 0;
}

static void add_line(Setup *s, Line *l)
{
    s->lines = mem_realloc(s->lines, sizeof *s->lines * (size_t)(s->nlines + 1));
    s->lines[s->nlines++] = *l;
}

static int parse_lines(Setup *s, const Dict *d, Err *e)
{
    const DictEntry *en = dict_find(d, "lines");
    if (!en) return err_set(e, d->file, 0, "keyword 'lines' missing");
    Line l;
    if (en->dict) {
        for (size_t i = 0; i < en->dict->n; i++) {
            const DictEntry *le = &en->dict->entries[i];
            if (!le->dict)
                return err_set(e, le->file, le->line, "lines: '%s' must be a dictionary { start ..; end ..; }",
                               le->key);
            if (parse_line(le->dict, le->key, &l, e)) return -1;
            add_line(s, &l);
        }
    } else {
        const DictNode *nd = en->nvals == 1 ? en->vals[0] : NULL;
        if (!nd || nd->kind != DN_LIST)
            return err_set(e, en->file, en->line, "lines: expected { NAME { ... } ... } or ( NAME { ... } ... )");
        for (size_t i = 0; i < nd->n; i += 2) {
            const DictNode *k = nd->items[i];
            if ((k->kind != DN_WORD && k->kind != DN_STRING) || i + 1 >= nd->n || nd->items[i + 1]->kind != DN_DICT)
                return err_set(e, k->file, k->line, "lines: expected NAME { start ..; end ..; }, found %s",
                               dict_node_kind_name(k));
            if (parse_line(nd->items[i + 1]->dict, k->text, &l, e)) return -1;
            add_line(s, &l);
        }
    }
    if (s->nlines == 0) return err_set(e, en->file, en->line, "lines: no line given");
    for (int i = 0; i < s->nlines; i++)
        for (int j = 0; j < i; j++)
            if (!strcmp(s->lines[i].name, s->lines[j].name))
                return err_set(e, en->file, en->line, "lines: line '%s' given twice", s->lines[i].name);
    return 0;
}

static int parse_setup(Setup *s, const Dict *d, Err *e)
{
    static const char *const interps[] = {"cell", "linear", NULL};
    memset(s, 0, sizeof *s);
    if (dict_check_keys(d, top_keys, e)) return -1;
    const DictEntry *en = dict_find(d, "fields");
    if (!en) return err_set(e, d->file, 0, "keyword 'fields' missing");
    const DictNode *nd = en->nvals == 1 && !en->dict ? en->vals[0] : NULL;
    if (!nd || nd->kind != DN_LIST || nd->n == 0)
        return err_set(e, en->file, en->line, "fields: expected a list of field names, e.g. (alpha.s U)");
    s->fields = MEM_NEW(const char *, nd->n);
    s->fields_file = en->file;
    s->fields_line = en->line;
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *w = nd->items[i];
        if (w->kind != DN_WORD && w->kind != DN_STRING)
            return err_set(e, w->file, w->line, "fields: expected a field name, found %s", dict_node_kind_name(w));
        for (int j = 0; j < s->nfields; j++)
            if (!strcmp(s->fields[j], w->text))
                return err_set(e, w->file, w->line, "fields: '%s' listed twice", w->text);
        s->fields[s->nfields++] = w->text;
    }
    if (dict_choice_or(d, "interpolation", interps, SAMPLE_CELL_VALUE, &s->interp, e)) return -1;
    return parse_lines(s, d, e);
}

/* Keeps only the line named by -line. */
static void pick_line(Setup *s, const char *name)
{
    for (int i = 0; i < s->nlines; i++)
        if (!strcmp(s->lines[i].name, name)) {
            s->lines[0] = s->lines[i];
            s->nlines = 1;
            return;
        }
    const char **names = MEM_NEW(const char *, s->nlines);
    for (int i = 0; i < s->nlines; i++) names[i] = s->lines[i].name;
    const char *near = dict_closest(name, names, (size_t)s->nlines);
    if (near) err_fatal("no line '%s' in the dictionary; did you mean '%s'?", name, near);
    err_fatal("no line '%s' in the dictionary", name);
}

/* ---- sampling one time ---- */

typedef struct Data {
    Field *f;
    double **grad;     /* per field, NULL for cell interpolation */
} Data;

static int read_fields(const Args *a, const Setup *s, const Mesh *m, const char *time, Data *d, Err *e)
{
    d->f = MEM_NEW(Field, s->nfields);
    d->grad = MEM_NEW(double *, s->nfields);
    for (int i = 0; i < s->nfields; i++) {
        char rel[4096];
        snprintf(rel, sizeof rel, "%s/%s", time, s->fields[i]);
        char *path = args_case_path(a, rel);
        int found = io_exists_gz(path);
        int rc = found ? field_read(&d->f[i], m, path, e)
                       : err_set(e, s->fields_file, s->fields_line, "field '%s' not found at time %s: %s does not exist",
                                 s->fields[i], time, path);
        free(path);
        if (rc) return -1;
        if (s->interp == SAMPLE_LINEAR) {
            size_t ng = (size_t)m->ncells * (size_t)d->f[i].width * 3;
            d->grad[i] = MEM_NEW(double, ng);
            sample_gradient(&d->f[i], m, d->grad[i]);
        }
    }
    return 0;
}

static void free_data(const Setup *s, Data *d)
{
    for (int i = 0; i < s->nfields && d->f; i++) {
        field_free(&d->f[i]);
        free(d->grad[i]);
    }
    free(d->f);
    free(d->grad);
}

static void put_num(Buf *b, double x)
{
    buf_putc(b, ',');
    foam_put_double(b, x, 0);
}

static void write_csv(const Setup *s, const Mesh *m, const Data *d, const SampleSet *ss, Buf *b)
{
    buf_puts(b, "distance,x,y,z");
    for (int i = 0; i < s->nfields; i++) {
        if (d->f[i].width == 1) buf_printf(b, ",%s", s->fields[i]);
        else buf_printf(b, ",%s_x,%s_y,%s_z", s->fields[i], s->fields[i], s->fields[i]);
    }
    if (ss->len) buf_puts(b, ",length");
    buf_putc(b, '\n');
    for (int p = 0; p < ss->n; p++) {
        foam_put_double(b, ss->dist[p], 0);
        for (int k = 0; k < 3; k++) put_num(b, ss->x[3 * p + k]);
        for (int i = 0; i < s->nfields; i++) {
            double v[3];
            sample_value(&d->f[i], m, d->grad[i], ss->cell[p], ss->x + 3 * p, v);
            for (int k = 0; k < d->f[i].width; k++) put_num(b, v[k]);
        }
        if (ss->len) put_num(b, ss->len[p]);
        buf_putc(b, '\n');
    }
}

static int sample_time(const Args *a, Setup *s, const Mesh *m, const Locator *L, const char *time, const char *outdir,
                       int blocks, Err *e)
{
    log_time(a, time);
    Data d = {NULL, NULL};
    int rc = read_fields(a, s, m, time, &d, e);
    char *dir = NULL;
    if (!rc && outdir) {
        dir = io_join(outdir, time);
        rc = io_mkdir_p(dir, e);
    }
    for (int i = 0; i < s->nlines && !rc; i++) {
        Line *l = &s->lines[i];
        SampleSet ss;
        if (l->mode == SAMPLE_CELLS) sample_cells(L, l->a, l->b, &ss);
        else sample_uniform(L, l->a, l->b, l->npoints, &ss);
        Buf b;
        buf_init(&b);
        if (!outdir && blocks > 1) buf_printf(&b, "# time %s line %s\n", time, l->name);
        write_csv(s, m, &d, &ss, &b);
        char *path = NULL;
        if (outdir) {
            char file[4096];
            snprintf(file, sizeof file, "%s.csv", l->name);
            path = io_join(dir, file);
        }
        rc = io_write_atomic(path ? path : "-", b.p, b.n, 0, e);
        fprintf(a->info, "    %s: %d samples%s%s\n", l->name, ss.n, path ? " -> " : "", path ? path : "");
        if (!l->reported && (ss.nskipped || ss.outside > 0)) {
            if (ss.nskipped) fprintf(a->info, "    %s: %d points outside the mesh skipped\n", l->name, ss.nskipped);
            else fprintf(a->info, "    %s: %.6g of its length lies outside the mesh\n", l->name, ss.outside);
            l->reported = 1;
        }
        free(path);
        buf_free(&b);
        sample_free(&ss);
    }
    fprintf(a->info, "\n");
    free(dir);
    free_data(s, &d);
    return rc;
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    const char *o = args_get(&a, &tool, "-o");
    int to_stdout = o && !strcmp(o, "-");
    if (to_stdout) args_info_to_stderr(&a);
    args_banner(&a, &tool);

    char *dpath = a.dict ? mem_strdup(a.dict) : args_case_path(&a, "system/sampleLineDict");
    Dict *d = dict_read(dpath, &e);
    Setup s;
    if (!d || parse_setup(&s, d, &e)) err_die(&e);
    const char *only = args_get(&a, &tool, "-line");
    if (only) pick_line(&s, only);

    TimeDir *t = NULL;
    int nt = runtime_list_times(a.case_dir, &t, &e);
    if (nt < 0) err_die(&e);
    int total = nt;
    nt = runtime_select(t, nt, a.time_spec, a.latest, a.nozero, &e);
    if (nt < 0) err_die(&e);
    if (nt == 0) err_fatal("%s: no time directory selected", a.case_dir);

    Mesh m;
    mesh_init(&m);
    char *mpath = args_case_path(&a, "constant/polyMesh");
    if (mesh_read(&m, mpath, &e)) err_die(&e);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    Locator L;
    locate_build(&L, &m);

    char *outdir = to_stdout ? NULL : o ? mem_strdup(o) : args_case_path(&a, "postProcessing/sampleLine");
    for (int i = 0; i < nt; i++)
        if (sample_time(&a, &s, &m, &L, t[i].name, outdir, nt * s.nlines, &e)) err_die(&e);

    log_exec(&a);
    log_end(&a);
    free(outdir);
    locate_free(&L);
    mesh_free(&m);
    runtime_free_times(t, total);
    free(s.lines);
    free(s.fields);
    dict_free(d);
    free(mpath);
    free(dpath);
    args_free(&a);
    return 0;
}
