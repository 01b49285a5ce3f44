/*
** gridio.h: what every grid tool (blockGrid, cutCells, mergeCells,
** voronoiGrid) does around its grid: choose the output format, write the
** polyMesh directory atomically or stream it to stdout, and print the
** "Mesh Information" summary.
*/
#ifndef KIESEL_GRIDIO_H
#define KIESEL_GRIDIO_H

#include <stdio.h>

#include "err.h"
#include "mesh.h"

/* Format from writeFormat / writeCompression of <case>/system/controlDict
   when that file exists; w is left as it is otherwise. */
int gridio_control_format(const char *case_dir, MeshWriteOpts *w, Err *e);

/* Writes m to dir: "-" streams to stdout; otherwise the files go into a
   sibling temporary directory that is then renamed over dir, so a failed
   write leaves an existing grid untouched. */
int gridio_write(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e);

/* Bounding box, counts and patches, as blockMesh prints them. */
void gridio_print_info(FILE *f, const Mesh *m);

#endif
