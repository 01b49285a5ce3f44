/*
** linesample.h: sampling fields along straight lines: where the samples
** go and the field values there (sampleline.h reads the dictionary and
** writes the CSV files).
**
** Two ways of placing samples on the segment a-b:
**   uniform  n points a + (b - a) i/(n - 1); points outside the mesh are
**            dropped and counted;
**   cells    one sample per cell crossed, at the midpoint of the part of
**            the segment inside the cell, with that part's length.  The
**            crossing of a convex cell is found by clipping the segment
**            against its face planes; a neighbour sees the shared face
**            with the opposite normal and gets the same parameter to the
**            last bit, so crossings tile the segment and their lengths add
**            up to the length inside the mesh.  Where the segment runs
**            inside a face shared by two cells, the lower numbered cell
**            takes it.
** Values: the cell value ("cell"), or the cell value plus a least-squares
** gradient dotted with x - x_c ("linear").  The gradient fits the values
** of the face neighbours' centres and of boundary faces (their values as
** the boundary condition gives them, field_patch_values), weighted by
** 1/|d|^2: exact for a linear field.  On a 2-D mesh (empty patches) the
** empty direction is left out and its gradient component is zero.
*/
#ifndef KIESEL_LINESAMPLE_H
#define KIESEL_LINESAMPLE_H

#include "field.h"
#include "locate.h"
#include "mesh.h"

enum { SAMPLE_UNIFORM, SAMPLE_CELLS };
enum { SAMPLE_CELL_VALUE, SAMPLE_LINEAR };

typedef struct SampleSet {
    int n;             /* samples kept */
    double *x;         /* 3n positions */
    double *dist;      /* n distances from a */
    double *len;       /* n crossing lengths (cells mode), else NULL */
    int *cell;         /* n containing cells */
    int nskipped;      /* uniform: points outside the mesh */
    double outside;    /* cells: length of the segment outside the mesh */
} SampleSet;

/* npoints >= 2 (npoints 1 samples a only). */
void linesample_uniform(const Locator *L, const double a[3], const double b[3], int npoints, SampleSet *s);
void linesample_cells(const Locator *L, const double a[3], const double b[3], SampleSet *s);
void linesample_free(SampleSet *s);

/* Least-squares cell gradients: grad[(c*width + k)*3 + j] = d f_k / d x_j.
   grad has ncells*width*3 doubles. */
void linesample_gradient(const Field *f, const Mesh *m, double *grad);

/* Value of f at x in cell c (width numbers into out); grad NULL gives the
   cell value. */
void linesample_value(const Field *f, const Mesh *m, const double *grad, int c, const double x[3],
                  double *out);

#endif
