/*
** quad.h: integrals of a given function over every cell of a grid, for
** source terms (newtonian.h's hook, the manufactured solutions of
** tests/validation/mms) and cell averages of a known field.
**
** A cell is split into the signed tetrahedra geom_cell measures its
** volume with (common/geom.h): apex the mean of the face centroids, base
** each face's fan triangle about the mean of its points.  The signed
** tetrahedra of any closed cell, convex or not (a merged cell), add up to
** the cell, so a rule exact on each tetrahedron is exact on the cell; the
** integral of 1 is Mesh.cell_vol and that of x is V times cell_centre, to
** round-off.  On each tetrahedron the rule is the symmetric four-point
** rule of degree 2 (barycentric (alpha, beta, beta, beta), alpha =
** (5 + 3 sqrt 5)/20, beta = (5 - sqrt 5)/20, weight V/4; Keast 1986):
** exact for quadratics, so the cell average of a smooth function has an
** error O(h^3) against the centroid rule's O(h^2) (doc/theory.md, "Source
** terms").
*/
#ifndef KIESEL_QUAD_H
#define KIESEL_QUAD_H

#include "mesh.h"

/* The integrand: its ncomp values at x into val. */
typedef void (*QuadFn)(void *ctx, const double x[3], double *val);

/* out[ncomp c + j] = the integral of component j of fn over cell c, for
   every cell of m (geometry and cell faces filled). */
void quad_cells(const Mesh *m, int ncomp, QuadFn fn, void *ctx, double *out);

#endif
