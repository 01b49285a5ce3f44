/*
** sampleline.c: sampleLine's dictionary (system/sampleLineDict) parsed
** into a SampleLineDict, and the CSV files of a time; the sampling itself
** is linesample.c's.
**
** Every line is checked when the dictionary is read (nPoints range, start
** != end in cells mode, a name usable as a file name, no name twice) and
** every field of a time is read before the first file is written, so a
** bad entry never leaves half the output.  With linear interpolation the
** least-squares gradient of each field is computed once per time, not per
** line.  Points outside the mesh are reported once per line over the
** whole run (SampleLine.reported), since the mesh does not change.
*/
#include "sampleline.h"

#include "field.h"
#include "foam.h"
#include "io.h"
#include "linesample.h"
#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const DictKey sampleline_keys[] = {
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

const char sampleline_help[] =
    "\nKeywords of each line (start, end [required]; mode [uniform]; nPoints [100]):\n"
    "  uniform: nPoints points from start to end, both included;\n"
    "  cells:   one sample per cell crossed, at the middle of the crossing, with\n"
    "           an extra column 'length' (the length of the crossing).\n"
    "Points outside the mesh are skipped (reported once per line).  Output:\n"
    "postProcessing/sampleLine/<time>/<line>.csv (or under -o DIR), columns\n"
    "distance,x,y,z,<fields>[,length].\n";

static int parse_line(const Dict *d, const char *name, SampleLine *l, Err *e)
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

static int add_line(SampleLineDict *s, const Dict *d, const char *name, Err *e)
{
    SampleLine l;
    if (parse_line(d, name, &l, e)) return -1;
    s->lines = mem_realloc(s->lines, sizeof *s->lines * (size_t)(s->nlines + 1));
    s->lines[s->nlines++] = l;
    return 0;
}

/* lines { NAME { ... } ... } */
static int parse_line_dict(SampleLineDict *s, const Dict *ld, Err *e)
{
    for (size_t i = 0; i < ld->n; i++) {
        const DictEntry *le = &ld->entries[i];
        if (!le->dict)
            return err_set(e, le->file, le->line, "lines: '%s' must be a dictionary { start ..; end ..; }", le->key);
        if (add_line(s, le->dict, le->key, e)) return -1;
    }
    return 0;
}

/* lines ( NAME { ... } ... ); */
static int parse_line_list(SampleLineDict *s, const DictEntry *en, Err *e)
{
    const DictNode *nd = en->nvals == 1 ? en->vals[0] : NULL;
    if (!nd || nd->kind != DN_LIST)
        return err_set(e, en->file, en->line, "lines: expected { NAME { ... } ... } or ( NAME { ... } ... )");
    for (size_t i = 0; i < nd->n; i += 2) {
        const DictNode *k = nd->items[i];
        if ((k->kind != DN_WORD && k->kind != DN_STRING) || i + 1 >= nd->n || nd->items[i + 1]->kind != DN_DICT)
            return err_set(e, k->file, k->line, "lines: expected NAME { start ..; end ..; }, found %s",
                           dict_node_kind_name(k));
        if (add_line(s, nd->items[i + 1]->dict, k->text, e)) return -1;
    }
    return 0;
}

static int parse_lines(SampleLineDict *s, const Dict *d, Err *e)
{
    const DictEntry *en = dict_find(d, "lines");
    if (!en) return err_set(e, d->file, 0, "keyword 'lines' missing");
    if (en->dict ? parse_line_dict(s, en->dict, e) : parse_line_list(s, en, e)) return -1;
    if (s->nlines == 0) return err_set(e, en->file, en->line, "lines: no line given");
    for (int i = 0; i < s->nlines; i++)
        for (int j = 0; j < i; j++)
            if (!strcmp(s->lines[i].name, s->lines[j].name))
                return err_set(e, en->file, en->line, "lines: line '%s' given twice", s->lines[i].name);
    return 0;
}

static int parse_fields(SampleLineDict *s, const Dict *d, Err *e)
{
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
    return 0;
}

int sampleline_parse(SampleLineDict *s, const Dict *d, Err *e)
{
    static const char *const interps[] = {"cell", "linear", NULL};
    memset(s, 0, sizeof *s);
    if (dict_check_keys(d, sampleline_keys, e) || parse_fields(s, d, e) ||
        dict_choice_or(d, "interpolation", interps, SAMPLE_CELL_VALUE, &s->interp, e))
        return -1;
    return parse_lines(s, d, e);
}

void sampleline_free(SampleLineDict *s)
{
    free(s->lines);
    free(s->fields);
    memset(s, 0, sizeof *s);
}

int sampleline_pick(SampleLineDict *s, const char *name, Err *e)
{
    for (int i = 0; i < s->nlines; i++)
        if (!strcmp(s->lines[i].name, name)) {
            s->lines[0] = s->lines[i];
            s->nlines = 1;
            return 0;
        }
    const char **names = MEM_NEW(const char *, s->nlines);
    for (int i = 0; i < s->nlines; i++) names[i] = s->lines[i].name;
    const char *near = dict_closest(name, names, (size_t)s->nlines);
    if (near) err_set(e, NULL, 0, "no line '%s' in the dictionary; did you mean '%s'?", name, near);
    else err_set(e, NULL, 0, "no line '%s' in the dictionary", name);
    free(names);
    return -1;
}

/* ---- sampling one time ---- */

static int read_data(SampleLineTime *t, const char *case_dir, Err *e)
{
    const SampleLineDict *s = t->s;
    t->f = MEM_NEW(Field, s->nfields);
    t->grad = MEM_NEW(double *, s->nfields);
    for (int i = 0; i < s->nfields; i++) {
        char *path;
        int rc = field_read_time(&t->f[i], t->m, case_dir, t->time, s->fields[i], &path, e);
        if (rc > 0)
            rc = err_set(e, s->fields_file, s->fields_line, "field '%s' not found at time %s: %s does not exist",
                         s->fields[i], t->time, path);
        free(path);
        if (rc) return -1;
        if (s->interp == SAMPLE_LINEAR) {
            t->grad[i] = MEM_NEW(double, (size_t)t->m->ncells * (size_t)t->f[i].width * 3);
            linesample_gradient(&t->f[i], t->m, t->grad[i]);
        }
    }
    return 0;
}

int sampleline_time_begin(SampleLineTime *t, const SampleLineDict *s, const Mesh *m, const Locator *L,
                          const char *case_dir, const char *time, const char *outdir, int nblocks, Err *e)
{
    *t = (SampleLineTime){s, m, L, time, NULL, nblocks, NULL, NULL};
    if (read_data(t, case_dir, e)) return -1;
    if (!outdir) return 0;
    t->dir = io_join(outdir, time);
    return io_mkdir_p(t->dir, e);
}

void sampleline_time_end(SampleLineTime *t)
{
    for (int i = 0; i < t->s->nfields && t->grad; i++) free(t->grad[i]);
    field_free_all(t->f, t->s->nfields);
    free(t->grad);
    free(t->dir);
    memset(t, 0, sizeof *t);
}

static void put_num(Buf *b, double x)
{
    buf_putc(b, ',');
    foam_put_double(b, x, 0);
}

static void put_csv(const SampleLineTime *t, const SampleSet *ss, Buf *b)
{
    const SampleLineDict *s = t->s;
    buf_puts(b, "distance,x,y,z");
    for (int i = 0; i < s->nfields; i++) {
        if (t->f[i].width == 1) buf_printf(b, ",%s", s->fields[i]);
        else buf_printf(b, ",%s_x,%s_y,%s_z", s->fields[i], s->fields[i], s->fields[i]);
    }
    if (ss->len) buf_puts(b, ",length");
    buf_putc(b, '\n');
    for (int p = 0; p < ss->n; p++) {
        foam_put_double(b, ss->dist[p], 0);
        for (int k = 0; k < 3; k++) put_num(b, ss->x[3 * p + k]);
        for (int i = 0; i < s->nfields; i++) {
            double v[3];
            linesample_value(&t->f[i], t->m, t->grad[i], ss->cell[p], ss->x + 3 * p, v);
            for (int k = 0; k < t->f[i].width; k++) put_num(b, v[k]);
        }
        if (ss->len) put_num(b, ss->len[p]);
        buf_putc(b, '\n');
    }
}

int sampleline_time_sample(SampleLineTime *t, SampleLine *l, Buf *log, Err *e)
{
    SampleSet ss;
    if (l->mode == SAMPLE_CELLS) linesample_cells(t->L, l->a, l->b, &ss);
    else linesample_uniform(t->L, l->a, l->b, l->npoints, &ss);
    Buf b;
    buf_init(&b);
    if (!t->dir && t->nblocks > 1) buf_printf(&b, "# time %s line %s\n", t->time, l->name);
    put_csv(t, &ss, &b);
    char *path = NULL;
    if (t->dir) {
        char file[4096];
        snprintf(file, sizeof file, "%s.csv", l->name);
        path = io_join(t->dir, file);
    }
    int rc = io_write_atomic(path ? path : "-", b.p, b.n, 0, e);
    buf_printf(log, "    %s: %d samples%s%s\n", l->name, ss.n, path ? " -> " : "", path ? path : "");
    if (!l->reported && (ss.nskipped || ss.outside > 0)) {
        if (ss.nskipped) buf_printf(log, "    %s: %d points outside the mesh skipped\n", l->name, ss.nskipped);
        else buf_printf(log, "    %s: %.6g of its length lies outside the mesh\n", l->name, ss.outside);
        l->reported = 1;
    }
    free(path);
    buf_free(&b);
    linesample_free(&ss);
    return rc;
}
