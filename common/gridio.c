/*
** gridio.c: output side of the grid tools (gridio.h).
**
** A grid is written into <dir>.tmp<pid> and committed with io_commit_dir,
** so an interrupted or failed write never leaves <dir> incomplete; the
** grid tools recover their -i and -o directories at start-up
** (args_recover) besides the <case>/constant/polyMesh args_parse does.
*/
#include "gridio.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dict.h"
#include "io.h"
#include "mem.h"

int gridio_control_format(const char *case_dir, MeshWriteOpts *w, Err *e)
{
    static const char *const fmts[] = {"ascii", "binary", NULL};
    char *path = io_join(case_dir ? case_dir : ".", "system/controlDict");
    int rc = 0;
    if (io_exists(path)) {
        Dict *d = dict_read(path, e);
        int bin = 0, gz = 0;
        if (!d || dict_choice_or(d, "writeFormat", fmts, 0, &bin, e) ||
            dict_switch_or(d, "writeCompression", 0, &gz, e)) {
            rc = -1;
        } else {
            w->binary = bin;
            w->gzip = gz;
        }
        dict_free(d);
    }
    free(path);
    return rc;
}

int gridio_args(Args *a, const ToolInfo *t, int out_is_in, GridIO *g, Err *e)
{
    const char *in = args_get(a, t, "-i"), *out = args_get(a, t, "-o");
    g->in = in ? mem_strdup(in) : args_case_path(a, "constant/polyMesh");
    g->out = out ? mem_strdup(out) : out_is_in ? mem_strdup(g->in) : args_case_path(a, "constant/polyMesh");
    g->to_stdout = !strcmp(g->out, "-");
    /* args_parse recovered <case>/constant/polyMesh; -i and -o may name others */
    args_recover(t, g->in);
    if (strcmp(g->out, g->in)) args_recover(t, g->out);
    if (g->to_stdout) args_info_to_stderr(a);
    args_banner(a, t);
    g->w.binary = g->w.gzip = 0;
    if (gridio_control_format(a->case_dir, &g->w, e)) return -1;
    if (args_get(a, t, "-binary")) g->w.binary = 1;
    if (args_get(a, t, "-gzip")) g->w.gzip = 1;
    return 0;
}

void gridio_free(GridIO *g)
{
    free(g->in);
    free(g->out);
    g->in = g->out = NULL;
}

int gridio_write(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e)
{
    if (!strcmp(dir, "-")) return mesh_write(m, "-", w, e);
    /* "constant/polyMesh/" names the same directory; its temporary must
       be a sibling ("constant/polyMesh.tmp<pid>"), not a child */
    char *dst = mem_strdup(dir);
    for (size_t k = strlen(dst); k > 1 && dst[k - 1] == '/'; k--) dst[k - 1] = '\0';
    size_t l = strlen(dst) + 32;
    char *tmp = mem_alloc(l), *parent = mem_strdup(dst);
    /* the pid in the name lets io_recover_dir tell a dead run's leftovers
       from a concurrent writer's work in progress */
    snprintf(tmp, l, "%s.tmp%ld", dst, (long)getpid());
    char *slash = strrchr(parent, '/');
    int rc = 0;
    if (slash && slash != parent) {
        *slash = 0;
        rc = io_mkdir_p(parent, e);
    }
    io_rm_rf(tmp, NULL);
    if (!rc) rc = mesh_write(m, tmp, w, e);
    if (!rc) rc = io_commit_dir(tmp, dst, e);
    if (rc) io_rm_rf(tmp, NULL);
    free(tmp);
    free(parent);
    free(dst);
    return rc;
}

void gridio_print_info(FILE *f, const Mesh *m)
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
