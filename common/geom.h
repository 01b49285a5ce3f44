/*
** geom.h: exact geometry of polygons and polyhedra.
**
** Faces are polygons given by point indices; cells are closed sets of
** faces.  A face's area vector and centroid are computed by splitting it
** into triangles about the average of its points (OpenFOAM's rule): exact
** for planar polygons, and the same definition OpenFOAM uses for warped
** ones.  A cell's volume and centroid come from the tetrahedra formed by
** each face triangle and an interior estimate point (the average of the
** face centroids): exact for any closed polyhedron with planar faces,
** convex or not, because the signed tetrahedra sum to the divergence
** theorem's integrals.
*/
#ifndef KIESEL_GEOM_H
#define KIESEL_GEOM_H

#include <stddef.h>

/* Area vector (right-hand rule over the point order; |Sf| = area) and
   centroid of the polygon pts[idx[0..n-1]] (pts is xyz-interleaved). */
void geom_face(const double *pts, const int *idx, int n, double Sf[3], double Cf[3]);

/* Volume and centroid of a cell bounded by nf faces.  faces[k] is a face
   index into off/idx (face point lists), flip[k] is nonzero when that face's
   normal points into the cell (the cell is the face's neighbour).  Cf and
   Sf are the faces' centroids and area vectors (from geom_face). */
void geom_cell(const double *pts, const int *off, const int *idx,
               const int *faces, const char *flip, int nf,
               const double *Sf, const double *Cf, double *vol, double C[3]);

/* Small vector helpers used across the library. */
static inline double geom_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline void geom_cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
double geom_norm(const double a[3]);

#endif
