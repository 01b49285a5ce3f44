/*
** shape.h: analytic solid primitives with exact surface queries.
**
** A Shape is a closed solid given by a few parameters.  For every shape
** the library answers, exactly up to floating-point round-off:
**   - inside or not (the sign of a level function, negative inside);
**   - where a straight segment crosses the surface (roots of the segment's
**     parametrisation: linear for planes, quadratic for spheres, cylinders
**     and cones, quartic for the torus, polished by Newton steps on the
**     exact function);
**   - the outward unit normal at the surface point nearest to a point;
**   - exact volume and surface area (for the convergence tests).
** The cut-cell generator builds on these (spec granular-model.md §2.2: the
** cut points on grid edges are the exact crossings of the analytic
** boundary), so their accuracy bounds the accuracy of every cut cell.
**
** Parameters by kind (vectors in global coordinates; transforms and CSG
** live one level up, in geometry.h):
**   SHAPE_HALFSPACE  p = a point on the plane, q = outward unit normal:
**                    inside is (x - p).q < 0
**   SHAPE_BOX        p = min corner, q = max corner (axis-aligned; rotate
**                    it with a transform)
**   SHAPE_SPHERE     p = centre, r1 = radius
**   SHAPE_CYLINDER   p, q = the two axis end centres, r1 = radius;
**                    infinite != 0: unbounded along the line through p, q
**                    (no end caps)
**   SHAPE_CONE       p, q = axis end centres, r1 = radius at p, r2 = radius
**                    at q (r1 or r2 may be 0: a full cone; both > 0: a
**                    truncated cone), closed by flat end discs
**   SHAPE_TORUS      p = centre, q = unit axis, r1 = major radius (centre
**                    to tube centre), r2 = minor (tube) radius, r2 < r1
**   SHAPE_POLYGON    a simple polygon in the plane normal to `axis`,
**                    extruded along it between lo and hi (lo = -INFINITY,
**                    hi = INFINITY: unbounded).  npoly vertices, poly[2i],
**                    poly[2i+1] = the two in-plane coordinates (u, v) =
**                    (y, z) for axis 0, (z, x) for axis 1, (x, y) for axis
**                    2; either orientation; it must not self-intersect.
**
** Conventions shared by all queries:
**   - inside is strict (level < 0); a point exactly on the surface is
**     outside.  Callers that need a tolerance (the cutter) apply it to the
**     crossings, not to the classification.
**   - shape_level is negative inside, positive outside, zero on the
**     surface; it is the exact signed distance to the surface for every
**     kind (so |level(x)| = |x - shape_closest(x)|, and shape_crossings
**     uses it to skip segments shorter than an end's distance).
*/
#ifndef KIESEL_SHAPE_H
#define KIESEL_SHAPE_H

enum {
    SHAPE_HALFSPACE, SHAPE_BOX, SHAPE_SPHERE, SHAPE_CYLINDER, SHAPE_CONE,
    SHAPE_TORUS, SHAPE_POLYGON, SHAPE_NKINDS
};

/* Crossings one segment can have with one primitive (a torus: 4, a box:
   2, a polygon with n edges: up to n + 2). */
#define SHAPE_MAX_CROSS 64

typedef struct Shape {
    int kind;          /* SHAPE_* */
    double p[3], q[3];
    double r1, r2;
    int infinite;      /* cylinder only */
    int axis;          /* polygon: extrusion axis 0, 1, 2 */
    double lo, hi;     /* polygon: extent along axis */
    int npoly;         /* polygon vertices */
    double *poly;      /* 2*npoly, owned (mem_alloc); NULL for other kinds */
    char msg[160];     /* shape_check's message, kept here so that it may
                          quote the offending values without global state */
} Shape;

/* Name "halfSpace", "box", "sphere", "cylinder", "cone", "torus",
   "polygon" <-> kind (-1 when unknown). */
const char *shape_kind_name(int kind);
int shape_kind(const char *name);

/* Validates the parameters (positive radii, p != q, r2 < r1 for a torus,
   a polygon with >= 3 vertices, non-zero area and no self-intersection,
   lo < hi, ...) and normalises (unit normal / axis, polygon turned
   counter-clockwise in (u, v)).  Returns NULL when usable, else a message
   without location ("radius must be positive, found -1") for the caller
   to prefix with file:line. */
const char *shape_check(Shape *s);
void shape_free(Shape *s);   /* frees poly */

double shape_level(const Shape *s, const double x[3]);
int shape_inside(const Shape *s, const double x[3]);   /* level < 0 */

/* A cheaper level for the volume-fraction integrator (volfrac.c): the
   same sign and zero set as shape_level, 1-Lipschitz, |bound| <=
   |level|; the larger slab distance for boxes and cylinder/cone ends (no
   Euclidean corner term), the side-line distance for cones; shape_level
   itself for the other kinds. */
double shape_bound(const Shape *s, const double x[3]);

/* Parameters t in [0, 1], ascending, at which the segment
   x(t) = a + t (b - a) crosses the surface transversally (the inside state
   changes there).  Tangential touches (double roots) are not reported;
   roots closer together than 1e-14 are treated as one double root.  Edge
   and corner hits of boxes, cones and polygons are reported once.  Writes
   at most max values into t; returns the number found (which may exceed
   max: then only the first max are written).  a == b gives 0. */
int shape_crossings(const Shape *s, const double a[3], const double b[3], double *t, int max);

/* Outward unit normal of the surface at the surface point nearest to x
   (for x on the surface: the exact normal there; on an edge or corner of
   a box, cylinder, cone or polygon: the normal of the nearest face; faces
   equally near, e.g. both faces at an edge nearest to an outside point,
   are told apart by x's signed distance to their planes (largest for x
   outside, smallest for x inside: the normal best aligned with the way
   from the surface to x), then by the first face in a fixed order: box
   -x +x -y +y -z +z; cylinder and cone side, end at p, end at q; polygon
   walls by edge, then the lo and hi caps). */
void shape_normal(const Shape *s, const double x[3], double n[3]);

/* Surface point nearest to x (exact for half-space, box, sphere,
   cylinder and torus; for cones and polygons too). */
void shape_closest(const Shape *s, const double x[3], double c[3]);

/* Points spread evenly over the surface, about h apart, from a
   structured parametrisation (latitude rings on a sphere, rings and
   generators on cylinders and cones, a grid on each box face and
   polygon side, a torus grid); edges and corners of boxes, cylinders,
   cones and polygons get points of their own, exactly on them, so a
   Voronoi grid can reproduce them (thesis Fig. 3.16).  Returns the count;
   *x and *n (outward unit normals; at an edge or corner point the mean of
   the faces' normals, normalised) are new arrays of 3 per point.
   Unbounded shapes are sampled inside the box lo..hi only.  In
   shape_sample.c. */
int shape_sample(const Shape *s, double h, const double lo[3], const double hi[3], double **x, double **n);

/* Axis-aligned bounding box (infinite extents as +-INFINITY). */
void shape_bounds(const Shape *s, double lo[3], double hi[3]);

/* Exact volume and surface area (INFINITY when unbounded). */
double shape_volume(const Shape *s);
double shape_area(const Shape *s);

#endif
