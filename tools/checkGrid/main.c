/*
** checkGrid: checkMesh's job for Kiesel's grids.  Reads constant/polyMesh
** (or "-i DIR", "-i -" for the stream on stdin), prints counts, bounding
** box, volumes against the Cartesian parents, closedness, orientation,
** non-orthogonality, skewness and aspect ratio (common/quality.c), and
** ends with "Grid OK." or, when the grid is broken, names the first bad
** cell on stderr and exits 1.  See doc/tools/checkGrid.md.
*/
#include "args.h"
#include "buf.h"
#include "err.h"
#include "mem.h"
#include "mesh.h"
#include "quality.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-i", "DIR", "polyMesh directory to check, '-' = stream on stdin (default: constant/polyMesh)"},
    {0}};

static const ArgDict dicts[] = {{0}};

static const ToolInfo tool = {"checkGrid", "checks a grid's topology and geometry, reports its quality",
                              opts, dicts, 0};

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    const char *in = args_get(&a, &tool, "-i");
    char *dir = in ? mem_strdup(in) : args_case_path(&a, "constant/polyMesh");
    args_banner(&a, &tool);
    fprintf(a.info, "Reading grid from %s\n\n", strcmp(dir, "-") ? dir : "stdin");

    Mesh m;
    mesh_init(&m);
    if (mesh_read(&m, dir, &e)) err_die(&e);
    Quality q;
    quality_measure(&m, &q);
    Buf b;
    buf_init(&b);
    quality_report(&m, &q, &b);
    fwrite(b.p, 1, b.n, a.info);
    buf_free(&b);

    int nfailed;
    int rc = quality_check(&m, &q, &nfailed, &e);
    if (rc) {
        fprintf(a.info, "\nFailed %d grid checks.\n\n", nfailed);
        err_die(&e);
    }
    fprintf(a.info, "\nGrid OK.\n\n");
    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    free(dir);
    args_free(&a);
    return 0;
}
