/*
** writeVTK: legacy VTK files of a case for ParaView, laid out as
** foamToVTK -legacy lays them out (see doc/tools/writeVTK.md):
**
**     VTK/<case>_<index>.vtk                 internal mesh, every vol field
**     VTK/<patch>/<patch>_<index>.vtk        each non-empty-type patch
**     VTK/<case>.vtk.series                  ParaView's time series (JSON)
**     VTK/<patch>/<patch>.vtk.series
**
** <case> is the base name of the absolute case path; <index> is the time
** step index of <time>/uniform/time, or, for a time without that file, its
** position in the sorted list of all time directories.  Should those
** numbers collide, every time takes its position instead, so one time never
** overwrites another's file.  A case without time directories is written
** as its mesh alone at time 0, index 0.
**
** Series files list every time of the case whose file exists in VTK/, not
** only the times converted by this run, so "writeVTK -latestTime" after a
** full conversion keeps the whole series.  Fields are the vol fields of
** each time (field_probe), in name order; -fields restricts them, and a
** listed field whose file is not a vol field is an error.
*/
#include "args.h"
#include "err.h"
#include "field.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "runtime.h"
#include "vtk.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const ArgOpt opts[] = {
    {"-ascii", NULL, "write ascii files (default: binary, big-endian)"},
    {"-pointData", NULL, "also write point data (volume-weighted average of the cells around a point)"},
    {"-noBoundary", NULL, "do not write the boundary patches"},
    {"-fields", "LIST", "only these fields, e.g. '(p U)' (default: every vol field)"},
    {"-overwrite", NULL, "remove the VTK directory first"},
    {0}};

static const ToolInfo tool = {"writeVTK", "legacy VTK files (.vtk, .vtk.series) of the mesh and vol fields",
                              opts, NULL, 1};

typedef struct Names {
    int n;
    char **v;
} Names;

static void names_free(Names *s)
{
    for (int i = 0; i < s->n; i++) free(s->v[i]);
    free(s->v);
    s->n = 0;
    s->v = NULL;
}

static int names_has(const Names *s, const char *x)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->v[i], x)) return 1;
    return 0;
}

/* "(p U)" or "p U" -> {p, U}. */
static Names parse_fields(const char *spec)
{
    Names s = {0, NULL};
    s.v = mem_alloc((strlen(spec) + 1) * sizeof(char *));
    for (const char *p = spec; *p;) {
        size_t k = strcspn(p, " \t\n(),");
        if (k == 0) {
            p++;
            continue;
        }
        char *w = mem_strndup(p, k);
        if (!names_has(&s, w)) s.v[s.n++] = w;
        else free(w);
        p += k;
    }
    return s;
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

static int has_field(const Field *f, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(f[i].name, name)) return 1;
    return 0;
}

/* The vol field in dir/file, if it is one we want: returns 1 when read into
   f, 0 when skipped, -1 on error (a wanted file that is no vol field). */
static int read_one(const Mesh *m, const char *dir, const char *file, const Names *want, Field *f,
                    int nread, Err *e)
{
    size_t l = strlen(file);
    char *name = l > 3 && !strcmp(file + l - 3, ".gz") ? mem_strndup(file, l - 3) : mem_strdup(file);
    char *path = io_join(dir, file), *cls = NULL;
    int requested = names_has(want, name), rc = 0;
    if (!io_is_dir(path) && (want->n == 0 || requested) && !has_field(f, nread, name)) {
        int w = field_probe(path, &cls, e);
        if (w < 0)
            rc = -1;
        else if (w == 0 && requested)
            rc = err_set(e, path, 0, "field '%s' is %s%s%s, not a volScalarField or volVectorField", name,
                         cls ? "of class '" : "not an OpenFOAM file with a class", cls ? cls : "",
                         cls ? "'" : "");
        else if (w > 0)
            rc = field_read(&f[nread], m, path, e) ? -1 : 1;
    }
    free(cls);
    free(path);
    free(name);
    return rc;
}

/* Reads the vol fields of a time directory (all, or those in want), in
   name order; returns their count. */
static int read_fields(const Mesh *m, const char *dir, const Names *want, Field **out, Err *e)
{
    char **files;
    int nf = io_list_dir(dir, &files, e);
    if (nf < 0) return -1;
    Field *f = MEM_NEW(Field, nf);
    int n = 0, rc = 0;
    for (int i = 0; i < nf && rc >= 0; i++) {
        rc = read_one(m, dir, files[i], want, f, n, e);
        if (rc > 0) n++;
    }
    io_free_list(files, nf);
    if (rc < 0) {
        for (int i = 0; i < n; i++) field_free(&f[i]);
        free(f);
        return -1;
    }
    *out = f;
    return n;
}

static void print_fields(const Args *a, const Field *f, int n)
{
    for (int w = 1; w <= 3; w += 2) {
        int any = 0;
        for (int i = 0; i < n; i++)
            if (f[i].width == w) {
                if (!any) fprintf(a->info, "    %s :", w == 1 ? "volScalar" : "volVector");
                fprintf(a->info, " %s", f[i].name);
                any = 1;
            }
        if (any) fprintf(a->info, "\n");
    }
}

/* "<dir>/<base>_<index>.vtk", relative to the case. */
static char *vtk_file(const char *dir, const char *base, long index)
{
    size_t l = strlen(dir) + strlen(base) + 32;
    char *s = mem_alloc(l);
    snprintf(s, l, "%s/%s_%ld.vtk", dir, base, index);
    return s;
}

static int write_time(const Args *a, const Mesh *m, const char *cname, long index, double t,
                      const Field *f, int nf, Err *e)
{
    VtkOpts o;
    vtk_opts_init(&o);
    o.binary = !args_get(a, &tool, "-ascii");
    o.point_data = args_get(a, &tool, "-pointData") != NULL;
    o.time = t;
    o.title = cname;
    char *rel = vtk_file("VTK", cname, index), *path = args_case_path(a, rel);
    int rc = vtk_write_internal(path, m, f, nf, &o, e);
    if (rc == 0) fprintf(a->info, "    Internal  : %s\n", rel);
    free(rel);
    free(path);
    for (int p = 0; p < m->npatches && rc == 0 && !args_get(a, &tool, "-noBoundary"); p++) {
        const Patch *pa = &m->patches[p];
        if (!strcmp(pa->type, "empty")) continue;
        char *dir = io_join("VTK", pa->name), *adir = args_case_path(a, dir);
        rel = vtk_file(dir, pa->name, index);
        path = args_case_path(a, rel);
        o.title = pa->name;
        rc = io_mkdir_p(adir, e);
        if (rc == 0) rc = vtk_write_patch(path, m, p, f, nf, &o, e);
        if (rc == 0) fprintf(a->info, "    Boundary  : %s\n", rel);
        free(dir);
        free(adir);
        free(rel);
        free(path);
    }
    return rc;
}

/* <dir>/<base>.vtk.series listing the times whose <base>_<index>.vtk exist. */
static int write_series(const Args *a, const char *dir, const char *base, const TimeDir *t,
                        const long *idx, int n, Err *e)
{
    VtkSeriesEntry *s = MEM_NEW(VtkSeriesEntry, n);
    char **names = MEM_NEW(char *, n);
    int k = 0;
    for (int i = 0; i < n; i++) {
        char *rel = vtk_file(dir, base, idx[i]), *path = args_case_path(a, rel);
        if (io_exists(path)) {
            names[k] = mem_strdup(strrchr(rel, '/') + 1);
            s[k].name = names[k];
            s[k].time = t[i].value;
            k++;
        }
        free(rel);
        free(path);
    }
    size_t l = strlen(dir) + strlen(base) + 16;
    char *rel = mem_alloc(l);
    snprintf(rel, l, "%s/%s.vtk.series", dir, base);
    char *path = args_case_path(a, rel);
    int rc = vtk_write_series(path, s, k, e);
    if (rc == 0) fprintf(a->info, "    Series    : %s (%d time%s)\n", rel, k, k == 1 ? "" : "s");
    for (int i = 0; i < k; i++) free(names[i]);
    free(names);
    free(s);
    free(rel);
    free(path);
    return rc;
}

/* Every time directory (or a lone time 0 when there is none), the selected
   ones in sel[0..nsel-1] as positions into all. */
static int list_times(const Args *a, TimeDir **all, int **sel, int *nsel, Err *e)
{
    int n = runtime_list_times(a->case_dir, all, e);
    if (n < 0) return -1;
    if (n == 0) {
        runtime_free_times(*all, 0);
        *all = MEM_NEW(TimeDir, 1);
        (*all)[0].value = 0;
        (*all)[0].name = mem_strdup("0");
        *sel = MEM_NEW(int, 1);
        *nsel = 1;
        return 1;
    }
    TimeDir *pick;
    int np = runtime_list_times(a->case_dir, &pick, e);
    if (np != n) return np < 0 ? -1 : err_set(e, a->case_dir, 0, "time directories changed while listing");
    int k = runtime_select(pick, np, a->time_spec, a->latest, a->nozero, e);
    if (k < 0) {
        runtime_free_times(pick, np);
        return -1;
    }
    *sel = MEM_NEW(int, k);
    for (int i = 0; i < k; i++)
        for (int j = 0; j < n; j++)
            if (!strcmp(pick[i].name, (*all)[j].name)) (*sel)[i] = j;
    *nsel = k;
    runtime_free_times(pick, np);
    if (k == 0)
        return err_set(e, a->case_dir, 0, "no time selected among %d time directories (%s to %s)", n,
                       (*all)[0].name, (*all)[n - 1].name);
    return n;
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc > 0) err_fatal("unexpected argument '%s'; try 'writeVTK -help'", a.argv[0]);
    args_banner(&a, &tool);
    Mesh m;
    mesh_init(&m);
    char *mdir = args_case_path(&a, "constant/polyMesh");
    if (mesh_read(&m, mdir, &e)) err_die(&e);
    free(mdir);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    const char *fspec = args_get(&a, &tool, "-fields");
    Names want = parse_fields(fspec ? fspec : "");
    if (fspec && want.n == 0) err_fatal("-fields '%s' names no field", fspec);
    TimeDir *all;
    int *sel, nsel, n = list_times(&a, &all, &sel, &nsel, &e);
    if (n < 0) err_die(&e);
    /* only now that the mesh and the time selection are known to be good */
    char *cname = case_name(a.case_dir), *vdir = args_case_path(&a, "VTK");
    if (args_get(&a, &tool, "-overwrite") && io_rm_rf(vdir, &e)) err_die(&e);
    if (io_mkdir_p(vdir, &e)) err_die(&e);
    long *idx = time_indices(a.case_dir, all, n);
    int *seen = MEM_NEW(int, want.n);
    for (int s = 0; s < nsel; s++) {
        const TimeDir *t = &all[sel[s]];
        log_time(&a, t->name);
        char *tdir = args_case_path(&a, t->name);
        Field *f = NULL;
        int nf = io_is_dir(tdir) ? read_fields(&m, tdir, &want, &f, &e) : 0;
        if (nf < 0) err_die(&e);
        for (int i = 0; i < want.n; i++)
            for (int j = 0; j < nf; j++) seen[i] |= !strcmp(want.v[i], f[j].name);
        print_fields(&a, f, nf);
        if (write_time(&a, &m, cname, idx[sel[s]], t->value, f, nf, &e)) err_die(&e);
        for (int j = 0; j < nf; j++) field_free(&f[j]);
        free(f);
        free(tdir);
        log_exec(&a);
    }
    for (int i = 0; i < want.n; i++)
        if (!seen[i]) err_warn("field '%s' was not found in any selected time", want.v[i]);

    if (write_series(&a, "VTK", cname, all, idx, n, &e)) err_die(&e);
    for (int p = 0; p < m.npatches && !args_get(&a, &tool, "-noBoundary"); p++) {
        if (!strcmp(m.patches[p].type, "empty")) continue;
        char *dir = io_join("VTK", m.patches[p].name);
        if (write_series(&a, dir, m.patches[p].name, all, idx, n, &e)) err_die(&e);
        free(dir);
    }
    fprintf(a.info, "\n");
    log_end(&a);
    free(seen);
    free(idx);
    free(sel);
    runtime_free_times(all, n);
    names_free(&want);
    free(cname);
    free(vdir);
    mesh_free(&m);
    args_free(&a);
    return 0;
}
