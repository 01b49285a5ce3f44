/*
** region.h: simple solid shapes and the volume fraction of a mesh cell
** inside them (setFields' regions).
**
** Every shape has a level set phi(x): phi <= 0 inside, phi > 0 outside,
** and |phi(x) - phi(y)| <= |x - y| (1-Lipschitz), so phi bounds the
** distance to the surface from below and a whole tetrahedron can be
** classified from its vertices (see region.c).
**
**   box        p = min corner, q = max corner
**   sphere     p = centre, r1 = radius
**   cylinder   p = p1, q = p2 (axis end centres), r1 = radius; finite,
**              closed by the two flat end discs
**   cone       p = p1, q = p2, r1 = radius at p1, r2 = radius at p2
**              (a truncated cone; r1 or r2 may be 0)
**   halfSpace  p = a point on the plane, q = outward normal (unit after
**              region_check): inside is where (x - p).q <= 0, i.e. the
**              normal points out of the region.
**
** Accuracy of region_fraction (measured in tests/common/test_region.c):
** box and halfSpace are exact to round-off (exact tetrahedron clipping by
** planes); sphere, cylinder and cone are second order in the cell size
** h, with an error about 4^-REGION_DEPTH of that of a single linear cut
** per tetrahedron: the relative error of a sphere's volume summed over a
** grid is about 4e-3 (h/R)^2 (4.3e-5 at h = R/9.6).
*/
#ifndef KIESEL_REGION_H
#define KIESEL_REGION_H

#include "mesh.h"

enum { REGION_BOX, REGION_SPHERE, REGION_CYLINDER, REGION_CONE, REGION_HALFSPACE };

/* Levels of 8-way refinement of a tetrahedron that may straddle a
   curved surface before the surface is replaced by its linear
   interpolant in that tetrahedron. */
#define REGION_DEPTH 3

typedef struct Region {
    int kind;          /* REGION_* */
    double p[3], q[3];
    double r1, r2;
    int flat;          /* 1: extruded along flat_axis (region_flatten) */
    int flat_axis;
} Region;

/* Names "box", "sphere", ...; kind from name, or -1. */
const char *region_kind_name(int kind);
int region_kind(const char *name);

/* Validates the parameters and normalises the halfSpace normal.  Returns
   NULL when the shape is usable, else a message without location ("radius
   must be positive, found -1") for the caller to prefix with file:line. */
const char *region_check(Region *r);

/* For 2-D meshes (one cell thick along axis): the shape becomes its
   section by the plane through its reference point (sphere centre, box
   middle, cylinder/cone axis middle, halfSpace point) normal to the axis,
   extruded along the axis, so a sphere, or a cylinder whose axis is the
   empty direction, sets a disc, and a cell's fraction is the fraction of
   its cross-section inside the section.  axis < 0 leaves the shape as it
   is. */
void region_flatten(Region *r, int axis);
/* Area of that section when it is simple (sphere: disc; box: rectangle;
   cylinder/cone along the axis: disc of the mean radius; in the plane:
   rectangle/trapezoid), else NAN; INFINITY for a halfSpace. */
double region_flat_area(const Region *r);

/* Level set (<= 0 inside, 1-Lipschitz). */
double region_level(const Region *r, const double x[3]);
int region_inside(const Region *r, const double x[3]);

/* Analytic volume of the shape (INFINITY for a halfSpace). */
double region_volume(const Region *r);

/* Fraction (0..1) of the volume of cell c inside the shape.  Needs the
   mesh's geometry and cell faces (mesh_geometry, mesh_cell_faces). */
double region_fraction(const Region *r, const Mesh *m, int c);

/* Volume inside the shape of the tetrahedron v[0..3] (unsigned). */
double region_tet_volume(const Region *r, const double v[4][3]);

#endif
