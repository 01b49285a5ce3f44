/*
** gridio.h: what every grid tool (blockGrid, cutCells, mergeCells,
** voronoiGrid) does around its grid: choose the output format, write the
** polyMesh directory atomically or stream it to stdout, and print the
** "Mesh Information" summary.
*/
#ifndef KIESEL_GRIDIO_H
#define KIESEL_GRIDIO_H

#include <stdio.h>

#include "args.h"
#include "err.h"
#include "mesh.h"

/* A grid tool's input, output and format. */
typedef struct GridIO {
    char *in;          /* -i, default <case>/constant/polyMesh ("-": stdin) */
    char *out;         /* -o ("-": stdout) */
    int to_stdout;
    MeshWriteOpts w;
} GridIO;

/* The options the grid tools share: -i, -o (default: the input when
   out_is_in, else <case>/constant/polyMesh), -binary and -gzip over
   writeFormat/writeCompression of system/controlDict.  With "-o -" the
   banner and progress go to stderr; the banner is printed here.  The -i
   and -o directories are recovered first (args_recover). */
int gridio_args(Args *a, const ToolInfo *t, int out_is_in, GridIO *g, Err *e);
void gridio_free(GridIO *g);

/* Format from writeFormat / writeCompression of <case>/system/controlDict
   when that file exists; w is left as it is otherwise. */
int gridio_control_format(const char *case_dir, MeshWriteOpts *w, Err *e);

/* Writes m to dir: "-" streams to stdout; otherwise the files go into
   the sibling dir.tmp<pid> that io_commit_dir then swaps with dir, so a
   failed or killed write leaves an existing grid untouched, and two
   concurrent writers each commit a complete grid (the last one stays). */
int gridio_write(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e);

/* Bounding box, counts and patches, as blockMesh prints them. */
void gridio_print_info(FILE *f, const Mesh *m);

#endif
