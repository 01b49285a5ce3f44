/*
** volfrac.h: the fraction of a mesh cell's volume inside the flow domain
** of a Geometry (geometry.h); setFields' regions are such domains (one
** solid, flow inside), so every geometryDict shape, CSG and STL included,
** can set fields.
**
** Accuracy of volfrac_cell (measured in tests/common/test_volfrac.c): a
** convex polytope (box, half-space, their intersection, any affine map) is
** exact to round-off (exact tetrahedron clipping by planes); anything else
** is second order in the cell size h, with an error about 4^-VOLFRAC_DEPTH
** of that of a single linear cut per tetrahedron: the relative error of a
** sphere's volume summed over a grid is about 4e-3 (h/R)^2 (4.3e-5 at
** h = R/9.6), of a box minus a sphere under 1e-4 on a 24^3 grid.
*/
#ifndef KIESEL_VOLFRAC_H
#define KIESEL_VOLFRAC_H

#include "geometry.h"
#include "mesh.h"

/* Levels of 8-way refinement of a tetrahedron that may straddle a
   curved surface before the surface is replaced by its linear
   interpolant in that tetrahedron. */
#define VOLFRAC_DEPTH 3

/* Most bounding planes of a polytope clipped exactly. */
#define VOLFRAC_PLANES 36

/* Fraction (0..1) of the volume of cell c inside g's flow domain.  Needs
   the mesh's geometry and cell faces (mesh_geometry, mesh_cell_faces). */
double volfrac_cell(const Geometry *g, const Mesh *m, int c);

/* Closed inside test, level <= 0 (OpenFOAM's cell-centre rule counts a
   centre on the surface in). */
int volfrac_inside(const Geometry *g, const double x[3]);

#endif
