/*
** shape_impl.h: the helpers shape.c shares with shape_sample.c, and with
** no other file (the primitives' public face is shape.h).
**
** The axisymmetric frame (cylinder, cone, torus: unit axis and length)
** and the polygon's plane (in-plane axes, the nearest edge and winding
** of a point, a wall's outward normal) are computed once, in shape.c,
** so that a sample point carries exactly the normal shape_normal gives
** there (test_shape_sample.c compares the two).
*/
#ifndef KIESEL_SHAPE_IMPL_H
#define KIESEL_SHAPE_IMPL_H

#include "shape.h"

#include <math.h>

static inline double shape_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline double shape_norm(const double a[3]) { return sqrt(shape_dot(a, a)); }
static inline void shape_sub(const double a[3], const double b[3], double c[3])
{
    for (int k = 0; k < 3; k++) c[k] = a[k] - b[k];
}

/* A unit vector perpendicular to unit u. */
void shape_perp_unit(const double u[3], double e[3]);

/* Unit axis u and axis length h of a cylinder or cone (p to q); a
   torus: u = q, h = 0. */
void shape_axi_frame(const Shape *s, double u[3], double *h);

/* The polygon's in-plane axes: (u, v) = x[shape_poly_u], x[shape_poly_v]. */
static inline int shape_poly_u(const Shape *s) { return (s->axis + 1) % 3; }
static inline int shape_poly_v(const Shape *s) { return (s->axis + 2) % 3; }

/* What the polygon's plane knows about a point (u, v). */
typedef struct ShapePoly2 {
    int inside;     /* winding number != 0 */
    double dist;    /* distance to the boundary */
    double sd;      /* signed distance (negative inside) */
    int edge;       /* nearest edge (ties: most facing, then first) */
    double cu, cv;  /* nearest boundary point */
} ShapePoly2;

void shape_poly2(const Shape *s, double u, double v, ShapePoly2 *r);

/* Outward unit normal of polygon wall i (edge i to i + 1) in 3-D. */
void shape_poly_wall_normal(const Shape *s, int i, double n[3]);

#endif
