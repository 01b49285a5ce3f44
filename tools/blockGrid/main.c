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
#include "gridtool.h"
#include "mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-o", "DIR", "output polyMesh directory, '-' = stream to stdout (default: constant/polyMesh)"},
    {"-binary", NULL, "write binary files (default: writeFormat of system/controlDict, else ascii)"},
    {"-gzip", NULL, "gzip the files (default: writeCompression of system/controlDict, else off)"},
    {0}};

static const ArgDict dicts[] = {{"system/blockGridDict", block_keys, block_help_note}, {0}};

static const ToolInfo tool = {"blockGrid", "rectilinear (graded) 2-D/3-D block grid", opts, dicts, 0};

int main(int argc, char **argv)
{
    Args a;
    Err e;
    Case cs;
    GridTool io;
    gridtool_start(argc, argv, &tool, 0, &a, &cs, &io);
    char *dict_path = args_dict_path(&a, &cs, "system/blockGridDict", 0);

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
    gridtool_print_info(a.info, &m);
    gridtool_write(&a, &io, &m);

    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    block_free(&spec);
    dict_free(d);
    gridtool_free(&io);
    case_free(&cs);
    free(dict_path);
    args_free(&a);
    return 0;
}
