/*
** blockGrid: writes the rectilinear (graded) block grid described by
** system/blockGridDict as constant/polyMesh, plus Kiesel's Cartesian
** extras (cartesianGrid, cellParent).  See doc/tools/blockGrid.md.
**
** The whole dictionary is validated before anything is written, and the
** polyMesh directory is assembled beside the target and renamed over it,
** so a bad dictionary or a failed write leaves an existing grid untouched.
** "-o -" sends the grid as a stream to stdout (for "| cutCells -i -");
** the banner and the log then go to stderr.
*/
#include "args.h"
#include "block.h"
#include "dict.h"
#include "err.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const ArgOpt opts[] = {
    {"-o", "DIR", "output polyMesh directory, '-' = stream to stdout (default: constant/polyMesh)"},
    {"-binary", NULL, "write binary files (default: writeFormat of system/controlDict, else ascii)"},
    {"-gzip", NULL, "gzip the files (default: writeCompression of system/controlDict, else off)"},
    {0}};

static const ArgDict dicts[] = {{"system/blockGridDict", block_keys, block_help_note}, {0}};

static const ToolInfo tool = {"blockGrid", "rectilinear (graded) 2-D/3-D block grid", opts, dicts, 0};

/* writeFormat / writeCompression of system/controlDict, when present. */
static void control_format(const Args *a, MeshWriteOpts *w)
{
    static const char *const fmts[] = {"ascii", "binary", NULL};
    char *path = args_case_path(a, "system/controlDict");
    Err e;
    if (io_exists(path)) {
        Dict *d = dict_read(path, &e);
        int bin = 0, gz = 0;
        if (!d || dict_choice_or(d, "writeFormat", fmts, 0, &bin, &e) ||
            dict_switch_or(d, "writeCompression", 0, &gz, &e))
            err_die(&e);
        w->binary = bin;
        w->gzip = gz;
        dict_free(d);
    }
    free(path);
}

static void print_info(FILE *f, const Mesh *m)
{
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    fprintf(f, "----------------\nMesh Information\n----------------\n");
    fprintf(f, "  boundingBox: (%g %g %g) (%g %g %g)\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    fprintf(f, "  nPoints: %d\n  nCells: %d\n  nFaces: %d\n  nInternalFaces: %d\n", m->npoints,
            m->ncells, m->nfaces, m->ninternal);
    fprintf(f, "----------------\nPatches\n----------------\n");
    for (int p = 0; p < m->npatches; p++)
        fprintf(f, "  patch %d (start: %d size: %d) name: %s\n", p, m->patches[p].start,
                m->patches[p].size, m->patches[p].name);
    fprintf(f, "\n");
}

/* Writes into a sibling temporary directory, then renames it over dir. */
static int write_dir(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e)
{
    size_t l = strlen(dir) + 32;
    char *tmp = mem_alloc(l), *parent = mem_strdup(dir);
    snprintf(tmp, l, "%s.tmp%ld", dir, (long)getpid());
    char *slash = strrchr(parent, '/');
    int rc = 0;
    if (slash && slash != parent) {
        *slash = 0;
        rc = io_mkdir_p(parent, e);
    }
    io_rm_rf(tmp, NULL);
    if (!rc) rc = mesh_write(m, tmp, w, e);
    if (!rc) rc = io_commit_dir(tmp, dir, e);
    if (rc) io_rm_rf(tmp, NULL);
    free(tmp);
    free(parent);
    return rc;
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    const char *out = args_get(&a, &tool, "-o");
    int to_stdout = out && !strcmp(out, "-");
    if (to_stdout) args_info_to_stderr(&a);
    args_banner(&a, &tool);

    char *dict_path = a.dict ? mem_strdup(a.dict) : args_case_path(&a, "system/blockGridDict");
    MeshWriteOpts w = {0, 0};
    control_format(&a, &w);
    if (args_get(&a, &tool, "-binary")) w.binary = 1;
    if (args_get(&a, &tool, "-gzip")) w.gzip = 1;

    fprintf(a.info, "Creating block grid from \"%s\"\n\n", dict_path);
    Dict *d = dict_read(dict_path, &e);
    BlockSpec spec;
    if (!d || block_read(&spec, d, &e)) err_die(&e);

    Mesh m;
    mesh_init(&m);
    double t0 = args_wall(&a);
    if (block_build(&spec, &m, &e)) err_die(&e);
    double dt = args_wall(&a) - t0;
    fprintf(a.info, "Built %d cells in %.3f s (%.3g cells/s)\n\n", m.ncells, dt,
            dt > 0 ? m.ncells / dt : 0.0);
    print_info(a.info, &m);

    char *dir = out ? mem_strdup(out) : args_case_path(&a, "constant/polyMesh");
    fprintf(a.info, "Writing polyMesh to %s (%s%s)\n\n", to_stdout ? "stdout" : dir,
            w.binary ? "binary" : "ascii", w.gzip ? ", gzip" : "");
    if (to_stdout ? mesh_write(&m, "-", &w, &e) : write_dir(&m, dir, &w, &e)) err_die(&e);

    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    block_free(&spec);
    dict_free(d);
    free(dir);
    free(dict_path);
    args_free(&a);
    return 0;
}
