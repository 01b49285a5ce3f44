/*
** gridtool.c: the grid tools' frame (gridtool.h).
**
** The output format is the case's (case_mesh_format: the same rule as
** for fields); -binary and -gzip switch binary or gzip on over it.  The
** grid tools recover their -i and -o directories at start-up besides
** the <case>/constant/polyMesh args_parse does.
*/
#include "gridtool.h"

#include <stdlib.h>
#include <string.h>

#include "errout.h"
#include "gridio.h"
#include "io.h"
#include "mem.h"

/* gridtool_start's work, failures in e. */
static int gridtool_args(Args *a, const ToolInfo *t, int out_is_in, Case *c, GridTool *g, Err *e)
{
    const char *in = args_get(a, t, "-i"), *out = args_get(a, t, "-o");
    g->in = in ? mem_strdup(in) : io_join(a->case_dir, "constant/polyMesh");
    g->out = out ? mem_strdup(out) : out_is_in ? mem_strdup(g->in) : io_join(a->case_dir, "constant/polyMesh");
    g->to_stdout = !strcmp(g->out, "-");
    /* args_parse recovered <case>/constant/polyMesh; -i and -o may name others */
    args_recover(t, g->in);
    if (strcmp(g->out, g->in)) args_recover(t, g->out);
    if (g->to_stdout) args_info_to_stderr(a);
    args_banner(a, t);
    if (case_open(c, a->case_dir, CASE_CONTROL_FORMAT, e)) return -1;
    case_mesh_format(c, &g->w);
    if (args_get(a, t, "-binary")) g->w.binary = 1;
    if (args_get(a, t, "-gzip")) g->w.gzip = 1;
    return 0;
}

void gridtool_start(int argc, char **argv, const ToolInfo *t, int out_is_in, Args *a, Case *c, GridTool *g)
{
    Err e;
    args_parse(argc, argv, t, a);
    if (a->argc) err_fatal("unexpected argument '%s'", a->argv[0]);
    if (gridtool_args(a, t, out_is_in, c, g, &e)) err_die(&e);
}

void gridtool_read(const Args *a, const GridTool *g, Mesh *m)
{
    Err e;
    fprintf(a->info, "Reading grid from %s\n\n", strcmp(g->in, "-") ? g->in : "stdin");
    mesh_init(m);
    if (mesh_read(m, g->in, &e)) err_die(&e);
}

void gridtool_free(GridTool *g)
{
    free(g->in);
    free(g->out);
    g->in = g->out = NULL;
}

void gridtool_print_info(FILE *f, const Mesh *m)
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

void gridtool_write(const Args *a, const GridTool *g, const Mesh *m)
{
    Err e;
    fprintf(a->info, "Writing polyMesh to %s (%s%s)\n\n", g->to_stdout ? "stdout" : g->out,
            g->w.binary ? "binary" : "ascii", g->w.gzip ? ", gzip" : "");
    if (gridio_write(m, g->out, &g->w, &e)) err_die(&e);
}
