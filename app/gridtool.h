/*
** gridtool.h: what every grid tool (blockGrid, cutCells, mergeCells,
** voronoiGrid) does around its grid in the application frame: the -i,
** -o, -binary and -gzip options, the banner, the case, and the "Mesh
** Information" summary.  Writing the grid itself is the library's
** (gridio_write, common/gridio.h).
*/
#ifndef KIESEL_GRIDTOOL_H
#define KIESEL_GRIDTOOL_H

#include <stdio.h>

#include "args.h"
#include "case.h"
#include "err.h"
#include "mesh.h"

/* A grid tool's input, output and format. */
typedef struct GridTool {
    char *in;          /* -i, default <case>/constant/polyMesh ("-": stdin) */
    char *out;         /* -o ("-": stdout) */
    int to_stdout;
    MeshWriteOpts w;
} GridTool;

void gridtool_free(GridTool *g);

/* A grid tool's start: parses the command line (no positional
   arguments) and settles the options the grid tools share: -i, -o
   (default: the input when out_is_in, else <case>/constant/polyMesh),
   -binary and -gzip over writeFormat/writeCompression of
   system/controlDict (case_mesh_format).  With "-o -" the banner and
   progress go to stderr; the banner is printed here, then the case is
   opened into c.  The -i and -o directories are recovered first
   (args_recover).  err_die on failure. */
void gridtool_start(int argc, char **argv, const ToolInfo *t, int out_is_in, Args *a, Case *c, GridTool *g);
/* "Reading grid from DIR" and the read of the -i grid into m; err_die
   on failure. */
void gridtool_read(const Args *a, const GridTool *g, Mesh *m);

/* Bounding box, counts and patches, as blockMesh prints them. */
void gridtool_print_info(FILE *f, const Mesh *m);
/* "Writing polyMesh to DIR (binary, gzip)" and the write; err_die on
   failure. */
void gridtool_write(const Args *a, const GridTool *g, const Mesh *m);

#endif
