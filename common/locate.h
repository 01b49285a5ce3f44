/*
** locate.h: point location: which cell of a mesh contains a point.
**
** A uniform bucket grid over the mesh bounds lists, per bucket, the cells
** whose bounding box overlaps it (about one cell per bucket).  A query
** tests the cells of the point's bucket with the face-plane test: x is in
** cell c when (x - Cf).Sf_out <= tol*|Sf| for every face of c, tol a
** 1e-9 fraction of the cell size, exact for convex cells with planar
** faces.  A point on a face or edge is in several cells; the lowest
** numbered one is returned, so the answer does not depend on the bucket
** layout.  When no cell passes (a warped face), the candidate with the
** smallest violation is accepted if that violation is below 1e-6 of the
** cell size.
*/
#ifndef KIESEL_LOCATE_H
#define KIESEL_LOCATE_H

#include "mesh.h"

typedef struct Locator {
    const Mesh *m;     /* needs geometry and cell faces */
    double lo[3], hi[3];
    int n[3];          /* buckets per axis */
    double h[3];       /* bucket size */
    int *off;          /* n0*n1*n2+1 offsets into cells */
    int *cells;        /* cell lists, ascending per bucket */
    double *bb;        /* 6*ncells: cell bounding boxes lo, hi */
    double *size;      /* ncells: cell length scale (bounding-box diagonal) */
} Locator;

/* Builds the locator of a mesh with geometry and cell faces. */
void locate_build(Locator *L, const Mesh *m);
void locate_free(Locator *L);

/* The cell containing x, or -1 when x is outside the mesh. */
int locate_cell(const Locator *L, const double x[3]);


/* Calls fn(cell, ctx) once for every cell whose bounding box meets the
   segment a-b (candidates for line crossings), in ascending cell order. */
void locate_segment_cells(const Locator *L, const double a[3], const double b[3],
                          void (*fn)(int cell, void *ctx), void *ctx);

#endif
