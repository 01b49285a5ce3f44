/*
** block.h: the rectilinear block grid that blockGrid writes.
**
** A block grid is the tensor product of three 1-D point distributions, one
** per axis.  Each axis runs from `start` through a list of segments; a
** segment ends at a coordinate, holds a number of cells, and is graded
** like blockMesh's simpleGrading: the ratio last/first cell width.  The
** six sides of the box (xMin, xMax, yMin, yMax, zMin, zMax) each become
** (part of) a named boundary patch.
**
** Two layers:
**   block_read  parses and validates system/blockGridDict into a
**               BlockSpec (every error "file:line: message");
**   block_mesh  fills a Mesh from point coordinates and side patches, in
**               OpenFOAM's face order, without per-face allocation.
** block_build = block_points + block_mesh for a BlockSpec.
*/
#ifndef KIESEL_BLOCK_H
#define KIESEL_BLOCK_H

#include "dict.h"
#include "err.h"
#include "mesh.h"

enum { BLOCK_XMIN, BLOCK_XMAX, BLOCK_YMIN, BLOCK_YMAX, BLOCK_ZMIN, BLOCK_ZMAX, BLOCK_NSIDES };

/* Side names in side order: "xMin", "xMax", "yMin", "yMax", "zMin", "zMax". */
extern const char *const block_side_names[BLOCK_NSIDES];

/* Keywords of blockGridDict (top level; those inside x/y/z and inside a
   boundary side are block.c's own, described by block_help_note). */
extern const DictKey block_keys[];
/* -help text describing the sub-dictionaries. */
extern const char block_help_note[];

/* One side of the box: patch name, type and (cyclic) neighbour patch. */
typedef struct BlockSide {
    const char *name;
    const char *type;
    const char *neighbour;   /* cyclic only, else NULL */
} BlockSide;

/* One axis: start, then nseg segments (end coordinate, cells, grading). */
typedef struct BlockAxis {
    double start;
    int nseg;
    double *end;
    int *cells;
    double *grading;
} BlockAxis;

typedef struct BlockSpec {
    double scale;
    BlockAxis axis[3];
    BlockSide side[BLOCK_NSIDES];
    int order[BLOCK_NSIDES];  /* sides in patch order (as listed in boundary) */
    const char *file;         /* the dictionary's file, for messages */
    int side_line[BLOCK_NSIDES];  /* line of each side's entry (0 = defaulted) */
} BlockSpec;

/* Parses and validates a blockGridDict (already read).  The spec keeps
   pointers into d, which must outlive it. */
int block_read(BlockSpec *s, const Dict *d, Err *e);
void block_free(BlockSpec *s);


/* Fills m (initialised with mesh_init) with the grid of the point
   coordinates x[k][0..n[k]] (strictly increasing) and the six sides, in
   patch order order[0..5] (NULL = side order).  Cells are numbered
   i + nx*(j + ny*k); the Cartesian extras (cart, cell_parent = identity)
   are filled too.  Validates the sides (types, cyclic partners, empty
   sides one cell thick) and the size limits; messages name file `where`
   and line[side] (either may be NULL). */
int block_mesh(Mesh *m, double *const x[3], const int n[3], const BlockSide side[BLOCK_NSIDES],
               const int *order, const char *where, const int *line, Err *e);

/* block_points for every axis, then block_mesh. */
int block_build(const BlockSpec *s, Mesh *m, Err *e);

/* Widths of a graded segment of length len in n cells with last/first
   ratio g: w[i] = w0 q^i, q = g^(1/(n-1)); writes the n+1 offsets from the
   segment start into t (t[0] = 0, t[n] = len exactly). */
void block_grade(double len, int n, double g, double *t);

#endif
