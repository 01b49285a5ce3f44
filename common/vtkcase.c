/*
** vtkcase.c: the VTK/ directory of a case (see vtkcase.h).
**
** File names are built relative to the case ("VTK/p/p_3.vtk") because
** that is how the report names them; every file is then written through
** vtk.h at <case>/<relative name>.  Time indices are fixed once per run
** for all times of the case, converted or not, so that the series files
** can find the files of earlier runs.
*/
#include "vtkcase.h"

#include "io.h"
#include "mem.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Base name of the absolute case path: the last component of cwd/case
   once "." and ".." are resolved ("-case ." in .../cavity gives cavity). */
static char *case_name(const char *case_dir)
{
    char cwd[4096];
    const char *base = case_dir[0] == '/' || !getcwd(cwd, sizeof cwd) ? "" : cwd;
    char *full = io_join(base, case_dir);
    int ncomp = 0;
    char **comp = mem_alloc((strlen(full) + 1) * sizeof(char *));
    char *save = NULL;
    for (char *t = strtok_r(full, "/", &save); t; t = strtok_r(NULL, "/", &save)) {
        if (!strcmp(t, ".")) continue;
        if (!strcmp(t, "..")) ncomp -= ncomp > 0;
        else comp[ncomp++] = t;
    }
    char *name = mem_strdup(ncomp > 0 ? comp[ncomp - 1] : "case");
    free(comp);
    free(full);
    return name;
}

/* The selected times, or a lone time 0 when the case has none (whatever
   the selection asks for: there is only the mesh to write). */
static int select_times(TimeSel *s, const char *case_dir, const char *spec, int latest, int nozero, Err *e)
{
    TimeDir *t;
    int n = runtime_list_times(case_dir, &t, e);
    if (n < 0) return -1;
    runtime_free_times(t, n);
    if (n == 0) {
        s->all = MEM_NEW(TimeDir, 1);
        s->all[0] = (TimeDir){0, mem_strdup("0")};
        s->nall = 1;
        s->sel = MEM_NEW(int, 1);
        s->n = 1;
        return 1;
    }
    int k = runtime_select_case(s, case_dir, spec, latest, nozero, e);
    if (k == 0)
        return err_set(e, case_dir, 0, "no time selected among %d time directories (%s to %s)", s->nall,
                       s->all[0].name, s->all[s->nall - 1].name);
    return k;
}

/* Time step index of every time: uniform/time, else the list position;
   positions for all if those numbers are not distinct. */
static long *time_indices(const char *case_dir, const TimeDir *t, int n)
{
    long *idx = MEM_NEW(long, n);
    for (int i = 0; i < n; i++) {
        char *rel = io_join(t[i].name, "uniform/time"), *path = io_join(case_dir, rel);
        idx[i] = io_exists(path) ? runtime_read_index(case_dir, t[i].name) : i;
        free(rel);
        free(path);
    }
    int clash = 0;
    for (int i = 0; i < n && !clash; i++)
        for (int j = i + 1; j < n && !clash; j++) clash = idx[i] == idx[j];
    if (clash)
        for (int i = 0; i < n; i++) idx[i] = i;
    return idx;
}

int vtkcase_open(VtkCase *v, const char *case_dir, const Mesh *m, const char *spec, int latest, int nozero,
                 Err *e)
{
    memset(v, 0, sizeof *v);
    v->case_dir = case_dir;
    v->m = m;
    vtk_opts_init(&v->opts);
    v->boundary = 1;
    if (select_times(&v->times, case_dir, spec, latest, nozero, e) < 0) return -1;
    v->name = case_name(case_dir);
    v->index = time_indices(case_dir, v->times.all, v->times.nall);
    v->mesh_dir = io_join(case_dir, "constant/polyMesh");
    v->opts.mesh_name = v->mesh_dir;
    return 0;
}

void vtkcase_free(VtkCase *v)
{
    runtime_free_sel(&v->times);
    free(v->name);
    free(v->index);
    free(v->mesh_dir);
    memset(v, 0, sizeof *v);
}

int vtkcase_mkdir(const VtkCase *v, int overwrite, Err *e)
{
    char *dir = io_join(v->case_dir, "VTK");
    int rc = (overwrite && io_rm_rf(dir, e)) || io_mkdir_p(dir, e) ? -1 : 0;
    free(dir);
    return rc;
}

static void put_fields(Buf *log, const Field *f, int n)
{
    for (int w = 1; w <= 3; w += 2) {
        int any = 0;
        for (int i = 0; i < n; i++)
            if (f[i].width == w) {
                if (!any) buf_printf(log, "    %s :", w == 1 ? "volScalar" : "volVector");
                buf_printf(log, " %s", f[i].name);
                any = 1;
            }
        if (any) buf_putc(log, '\n');
    }
}

int vtkcase_read_fields(const VtkCase *v, int i, const char *const *want, int nwant, Field **f, Buf *log, Err *e)
{
    char *dir = io_join(v->case_dir, runtime_sel_time(&v->times, i)->name);
    *f = NULL;
    int n = io_is_dir(dir) ? field_read_dir(v->m, dir, want, nwant, f, e) : 0;
    free(dir);
    if (n > 0) put_fields(log, *f, n);
    return n;
}

/* "<dir>/<base>_<index>.vtk", relative to the case. */
static char *vtk_file(const char *dir, const char *base, long index)
{
    size_t l = strlen(dir) + strlen(base) + 32;
    char *s = mem_alloc(l);
    snprintf(s, l, "%s/%s_%ld.vtk", dir, base, index);
    return s;
}

/* Patch p gets a file of its own unless it is of type empty. */
static int patch_written(const VtkCase *v, int p) { return v->boundary && !mesh_patch_is_empty(&v->m->patches[p]); }

/* The fields of one time as the writer takes them: given in memory, or
   the files at path[k], read one at a time. */
typedef struct Source {
    const Field *given;
    char **path;
    const Mesh *m;
} Source;

/* Field k into *f (tmp holds a field read, to be freed by the caller). */
static int source_get(const Source *s, int k, Field *tmp, const Field **f, Err *e)
{
    if (s->given) {
        *f = &s->given[k];
        return 0;
    }
    if (field_read(tmp, s->m, s->path[k], e)) return -1;
    *f = tmp;
    return 0;
}

/* The relative names of time t's files: [0] the internal mesh, then one
   per written patch (its patch number into patch[]); the count. */
static int time_files(const VtkCase *v, int t, char **rel, int *patch)
{
    int n = 0;
    rel[n] = vtk_file("VTK", v->name, v->index[t]);
    patch[n++] = -1;
    for (int p = 0; p < v->m->npatches; p++) {
        if (!patch_written(v, p)) continue;
        char *dir = io_join("VTK", v->m->patches[p].name);
        rel[n] = vtk_file(dir, v->m->patches[p].name, v->index[t]);
        patch[n++] = p;
        free(dir);
    }
    return n;
}

/* Begins file k of time t (its patch directory made first). */
static VtkFile *begin_file(const VtkCase *v, const char *rel, int patch, int nf, const VtkOpts *o, Err *e)
{
    char *path = io_join(v->case_dir, rel);
    VtkFile *f = NULL;
    if (patch < 0) {
        f = vtk_begin_internal(path, v->m, nf, o, e);
    } else {
        char *dir = io_join("VTK", v->m->patches[patch].name), *adir = io_join(v->case_dir, dir);
        VtkOpts po = *o;
        po.title = v->m->patches[patch].name;
        if (!io_mkdir_p(adir, e)) f = vtk_begin_patch(path, v->m, patch, nf, &po, e);
        free(dir);
        free(adir);
    }
    free(path);
    return f;
}

/* Every file of the t-th time (the internal mesh, each patch that is not
   empty), all begun first and then given the fields one at a time: a
   time read from disk holds one field in memory, not all of them. */
static int write_files(const VtkCase *v, int t, const Source *src, int nf, Buf *log, Err *e)
{
    int np = v->m->npatches + 1, *patch = MEM_NEW(int, np);
    char **rel = MEM_NEW(char *, np);
    VtkFile **file = MEM_NEW(VtkFile *, np);
    int n = time_files(v, t, rel, patch), rc = 0, k = 0;
    VtkOpts o = v->opts;
    o.time = v->times.all[t].value;
    o.title = v->name;
    for (; k < n && (file[k] = begin_file(v, rel[k], patch[k], nf, &o, e)); k++) continue;
    rc = k < n ? -1 : 0;
    for (int i = 0; i < nf && rc == 0; i++) {
        Field tmp;
        const Field *f;
        if (source_get(src, i, &tmp, &f, e)) {
            rc = -1;
            break;
        }
        for (int j = 0; j < n && rc == 0; j++) rc = vtk_put_field(file[j], f, e);
        if (f == &tmp) field_free(&tmp);
    }
    for (int j = 0; j < k; j++) { /* after an error, the rest are removed */
        if (rc) {
            vtk_abort(file[j]);
            continue;
        }
        rc = vtk_end(file[j], e);
        if (rc == 0) buf_printf(log, "    %s: %s\n", patch[j] < 0 ? "Internal  " : "Boundary  ", rel[j]);
    }
    io_free_list(rel, n);
    free(patch);
    free(file);
    return rc;
}

int vtkcase_write_time(const VtkCase *v, int i, const Field *f, int nf, Buf *log, Err *e)
{
    Source src = {f, NULL, v->m};
    return write_files(v, v->times.sel[i], &src, nf, log, e);
}

/* <dir>/<base>.vtk.series listing the times whose <base>_<index>.vtk exist. */
static int write_series(const VtkCase *v, const char *dir, const char *base, Buf *log, Err *e)
{
    int n = v->times.nall;
    VtkSeriesEntry *s = MEM_NEW(VtkSeriesEntry, n);
    char **names = MEM_NEW(char *, n);
    int k = 0;
    for (int i = 0; i < n; i++) {
        char *rel = vtk_file(dir, base, v->index[i]), *path = io_join(v->case_dir, rel);
        if (io_exists(path)) {
            names[k] = mem_strdup(strrchr(rel, '/') + 1);
            s[k].name = names[k];
            s[k].time = v->times.all[i].value;
            k++;
        }
        free(rel);
        free(path);
    }
    size_t l = strlen(dir) + strlen(base) + 16;
    char *rel = mem_alloc(l);
    snprintf(rel, l, "%s/%s.vtk.series", dir, base);
    char *path = io_join(v->case_dir, rel);
    int rc = vtk_write_series(path, s, k, e);
    if (rc == 0) buf_printf(log, "    Series    : %s (%d time%s)\n", rel, k, k == 1 ? "" : "s");
    io_free_list(names, k);
    free(s);
    free(rel);
    free(path);
    return rc;
}

int vtkcase_write_series(const VtkCase *v, Buf *log, Err *e)
{
    int rc = write_series(v, "VTK", v->name, log, e);
    for (int p = 0; p < v->m->npatches && rc == 0; p++) {
        if (!patch_written(v, p)) continue;
        char *dir = io_join("VTK", v->m->patches[p].name);
        rc = write_series(v, dir, v->m->patches[p].name, log, e);
        free(dir);
    }
    return rc;
}

int vtkcase_field_names(const char *spec, char ***names)
{
    char **v = mem_alloc((strlen(spec) + 1) * sizeof(char *));
    int n = 0;
    for (const char *p = spec; *p;) {
        size_t k = strcspn(p, " \t\n(),");
        if (k == 0) {
            p++;
            continue;
        }
        char *w = mem_strndup(p, k);
        int dup = 0;
        for (int i = 0; i < n && !dup; i++) dup = !strcmp(v[i], w);
        if (dup) free(w);
        else v[n++] = w;
        p += k;
    }
    *names = v;
    return n;
}

/* ---- a solver's write times: VTK/ kept a mirror of the time directories ---- */

/* The entries of a series file as vtk_write_series writes them: names and
   times into new arrays; a missing or foreign file gives none. */
typedef struct Series {
    char **name;
    double *time;
    int n;
} Series;

static void series_free(Series *s)
{
    io_free_list(s->name, s->n);
    free(s->time);
    memset(s, 0, sizeof *s);
}

/* The JSON string at p (after its opening quote) into a new string, *end
   after the closing quote; NULL when it does not close. */
static char *json_string(const char *p, const char **end)
{
    Buf b;
    buf_init(&b);
    for (; *p && *p != '"'; p++) {
        if (*p == '\\' && p[1]) p++;
        buf_putc(&b, *p);
    }
    if (*p != '"') {
        buf_free(&b);
        return NULL;
    }
    *end = p + 1;
    char *s = mem_strdup(b.n ? b.p : "");
    buf_free(&b);
    return s;
}

/* After key ("name" or "time") at p: the position after its colon, or NULL. */
static const char *json_value(const char *p, const char *key)
{
    p = strstr(p, key);
    if (!p) return NULL;
    p += strlen(key);
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    if (*p != ':') return NULL;
    p++;
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    return p;
}

static void read_series(const char *path, Series *s)
{
    memset(s, 0, sizeof *s);
    Buf b;
    Err e;
    buf_init(&b);
    if (!io_exists(path) || io_read_file(path, &b, NULL, &e)) return;
    int cap = 16;
    s->name = MEM_NEW(char *, cap);
    s->time = MEM_NEW(double, cap);
    const char *p = b.p;
    while ((p = json_value(p, "\"name\"")) && *p == '"') {
        char *name = json_string(p + 1, &p), *end;
        const char *t = name ? json_value(p, "\"time\"") : NULL;
        double v = t ? strtod(t, &end) : 0;
        if (!t || end == t) {
            free(name);
            break;
        }
        if (s->n == cap) {
            cap *= 2;
            s->name = mem_realloc(s->name, (size_t)cap * sizeof *s->name);
            s->time = mem_realloc(s->time, (size_t)cap * sizeof *s->time);
        }
        s->name[s->n] = name;
        s->time[s->n++] = v;
        p = end;
    }
    buf_free(&b);
}

/* Does the old series give file name the time value t?  (Its times are
   written to round-trip, so they compare exactly but for a relative
   1e-12 of slack.) */
static int series_has(const Series *s, const char *name, double t)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->name[i], name)) return fabs(s->time[i] - t) <= 1e-12 * fabs(t);
    return 0;
}

/* Is time t of v already on disk as writeVTK would write it: the internal
   file listed in the old series under its time, and every patch file? */
static int time_current(const VtkCase *v, int t, const Series *old)
{
    char *rel = vtk_file("VTK", v->name, v->index[t]), *path = io_join(v->case_dir, rel);
    int ok = io_exists(path) && series_has(old, strrchr(rel, '/') + 1, v->times.all[t].value);
    free(rel);
    free(path);
    for (int p = 0; p < v->m->npatches && ok; p++) {
        if (!patch_written(v, p)) continue;
        char *dir = io_join("VTK", v->m->patches[p].name);
        rel = vtk_file(dir, v->m->patches[p].name, v->index[t]);
        path = io_join(v->case_dir, rel);
        ok = io_exists(path);
        free(dir);
        free(rel);
        free(path);
    }
    return ok;
}

/* Writes the files of the t-th time from its fields on disk, read one at
   a time (write_files). */
static int convert_time(const VtkCase *v, int t, Buf *scratch, Err *e)
{
    char *dir = io_join(v->case_dir, v->times.all[t].name), **names = NULL, **paths = NULL;
    int nf = io_is_dir(dir) ? field_list_dir(dir, NULL, 0, &names, &paths, e) : 0;
    free(dir);
    if (nf < 0) return -1;
    Source src = {NULL, paths, v->m};
    int rc = write_files(v, t, &src, nf, scratch, e);
    io_free_list(names, nf);
    io_free_list(paths, nf);
    return rc;
}

/* Is name "<base>_<digits>.vtk"?  Its number into *index. */
static int numbered_file(const char *name, const char *base, long *index)
{
    size_t l = strlen(base);
    if (strncmp(name, base, l) || name[l] != '_') return 0;
    const char *d = name + l + 1;
    size_t k = strspn(d, "0123456789");
    if (k == 0 || k > 18 || strcmp(d + k, ".vtk")) return 0;
    *index = strtol(d, NULL, 10);
    return 1;
}

/* Removes <dir>/<base>_<index>.vtk files whose index no time of v has. */
static int sweep_dir(const VtkCase *v, const char *dir, const char *base, int *nremoved, Err *e)
{
    char *adir = io_join(v->case_dir, dir), **names;
    int n = io_is_dir(adir) ? io_list_dir(adir, &names, e) : 0, rc = n < 0 ? -1 : 0;
    for (int i = 0; i < n && rc == 0; i++) {
        long idx;
        if (!numbered_file(names[i], base, &idx)) continue;
        int used = 0;
        for (int t = 0; t < v->times.nall && !used; t++) used = v->index[t] == idx;
        if (used) continue;
        char *path = io_join(adir, names[i]);
        if (remove(path)) rc = err_set(e, path, 0, "cannot remove: %s", strerror(errno));
        else (*nremoved)++;
        free(path);
    }
    if (n > 0) io_free_list(names, n);
    free(adir);
    return rc;
}

static int sweep(const VtkCase *v, int *nremoved, Err *e)
{
    int rc = sweep_dir(v, "VTK", v->name, nremoved, e);
    for (int p = 0; p < v->m->npatches && rc == 0; p++) {
        if (!patch_written(v, p)) continue;
        char *dir = io_join("VTK", v->m->patches[p].name);
        rc = sweep_dir(v, dir, v->m->patches[p].name, nremoved, e);
        free(dir);
    }
    return rc;
}

/* Converts fresh and every time not current; the count or -1. */
static int convert_stale(const VtkCase *v, const char *fresh, Buf *scratch, Err *e)
{
    char *spath = io_join(v->case_dir, "VTK"), *sname = mem_alloc(strlen(v->name) + 16);
    sprintf(sname, "%s.vtk.series", v->name);
    char *series = io_join(spath, sname);
    Series old;
    read_series(series, &old);
    int n = 0;
    for (int t = 0; t < v->times.nall && n >= 0; t++) {
        int is_fresh = fresh && !strcmp(v->times.all[t].name, fresh);
        if (!is_fresh && time_current(v, t, &old)) continue;
        n = convert_time(v, t, scratch, e) ? -1 : n + 1;
    }
    series_free(&old);
    free(series);
    free(sname);
    free(spath);
    return n;
}

/* One line for the solver's log: the file of fresh, what else changed. */
static void put_summary(const VtkCase *v, const char *fresh, int nconv, int nremoved, Buf *log)
{
    int t = 0, nother = nconv;
    while (fresh && t < v->times.nall && strcmp(v->times.all[t].name, fresh)) t++;
    buf_puts(log, "VTK:");
    if (fresh && t < v->times.nall) {
        char *rel = vtk_file("VTK", v->name, v->index[t]);
        buf_printf(log, " %s", rel);
        free(rel);
        nother--;
    }
    if (nother > 0)
        buf_printf(log, "%s %d other time%s (missing or renumbered)", nother < nconv ? " and" : "", nother,
                   nother > 1 ? "s" : "");
    if (nremoved > 0)
        buf_printf(log, "; removed %d stale file%s (times gone or renumbered)", nremoved, nremoved > 1 ? "s" : "");
    buf_printf(log, "; VTK/%s.vtk.series: %d time%s\n", v->name, v->times.nall, v->times.nall > 1 ? "s" : "");
}

int vtkcase_sync(const char *case_dir, const Mesh *m, const char *fresh, Buf *log, Err *e)
{
    VtkCase v;
    Buf scratch;
    buf_init(&scratch);
    int rc = vtkcase_open(&v, case_dir, m, NULL, 0, 0, e) || vtkcase_mkdir(&v, 0, e) ? -1 : 0;
    int nconv = rc ? -1 : convert_stale(&v, fresh, &scratch, e), nremoved = 0;
    rc = nconv < 0 || sweep(&v, &nremoved, e) || vtkcase_write_series(&v, &scratch, e) ? -1 : 0;
    if (rc == 0) put_summary(&v, fresh, nconv, nremoved, log);
    buf_free(&scratch);
    vtkcase_free(&v);
    return rc ? -1 : nconv;
}
