/*
** geometry.h: the immersed geometry of a case (system/geometryDict): CSG
** trees of analytic shapes, STL surfaces and gmsh models, each surface a
** named boundary patch, and the flow domain they bound.
**
** The dictionary lists surfaces; each becomes one patch:
**
**   surfaces
**   {
**       cylinder                 // patch name
**       {
**           type    wall;        // patch type (default wall)
**           flow    outside;     // the flow is outside (default) or inside
**           shape   cylinder;    // a primitive (shape.h), stl, cad, or a
**           point1  (0 0 -1);    // CSG operation: union, intersection,
**           point2  (0 0 1);     // difference, whose operands are its
**           radius  0.25;        // sub-dictionaries in order
**       }
**   }
**
** Any shape dictionary may carry a transform, applied in this order:
** `scale s;` or `scale (sx sy sz);` about the origin, then
** `rotate { axis (0 0 1); angle 30; origin (0 0 0); }` (degrees, right
** hand), then `translate (dx dy dz);`.  Keywords of each shape kind are
** in geometry_keys (and -help).  See doc/tools/cutCells.md.
**
** The flow domain is the intersection, over surfaces, of the solid (flow
** inside) or its complement (flow outside), restricted to the grid's box.
** Internally it is one CSG tree whose leaves (primitives, STL surfaces,
** CAD models) are numbered 0..nleaves-1; each leaf knows its surface
** (patch) and the sign that turns its own outward normal into the flow
** domain's outward normal (into the solid).
**
** Queries are on the domain, so callers never see the tree:
**   geometry_fluid         is x in the flow domain (a point exactly on a
**                          surface may go either way: callers that care,
**                          like the cutter, decide by the crossings);
**   geometry_classify_line the same for many points on one grid line
**                          (STL leaves sweep the line once);
**   geometry_crossings     where a segment enters or leaves the domain,
**                          exact, with the leaf crossed;
**   geometry_normal        the exact outward normal of the domain at the
**                          surface point of a leaf nearest to x.
** Affine transforms keep segment parameters t, so crossings are computed in
** each leaf's own coordinates and need no conversion.
**
** 2-D grids: geometry_flatten(g, axis, c) makes every query use the
** section of the geometry by the plane x[axis] = c, extruded along axis
** (a sphere centred on the plane becomes a disc of the same radius).
**
** This header is the public face of three files: csg.c (the tree and
** every query on the domain), geometry_dict.c (reading the dictionary)
** and geometry_sample.c (points on the boundary); csg.h is the tree they
** share.  setFields uses the same Geometry for its regions (one solid,
** flow inside: geometry_of_shape, geometry_parse_solid), with the cell
** volume fractions of volfrac.h computed from geometry_level.
*/
#ifndef KIESEL_GEOMETRY_H
#define KIESEL_GEOMETRY_H

#include "dict.h"
#include "err.h"

typedef struct GeoNode GeoNode;   /* csg.h */
struct Cad;
struct Shape;
struct TriSurf;

/* One crossing of a segment with the domain boundary. */
typedef struct GeoCross {
    double t;      /* segment parameter in [0, 1] */
    int leaf;      /* leaf whose surface is crossed */
    int enter;     /* 1: the segment enters the flow domain here */
} GeoCross;

typedef struct GeoSurface {
    char *name;    /* patch name */
    char *type;    /* patch type */
    int flow_inside;
    int line;      /* line of its entry in the dictionary */
    GeoNode *root;
} GeoSurface;

typedef struct GeoLeaf {
    GeoNode *node;
    int surface;   /* index into surf */
    int sign;      /* +1: the leaf's outward normal is the domain's */
} GeoLeaf;

typedef struct Geometry {
    char *file;            /* the dictionary's path, for messages */
    int nsurf;
    GeoSurface *surf;
    int nleaves;
    GeoLeaf *leaves;
    int flat_axis;         /* -1: 3-D */
    double flat_coord;
} Geometry;

/* Dictionary keywords, for -help and dict_check_keys. */
extern const DictKey geometry_keys[];         /* top level */
extern const DictKey geometry_surface_keys[]; /* a surface entry */
extern const DictKey geometry_shape_keys[];   /* any shape (union of kinds) */
extern const char geometry_help_note[];

void geometry_init(Geometry *g);
void geometry_free(Geometry *g);

/* A geometry of one solid, flow inside: the shape s (copied; its poly
   array then belongs to g), named `name` for messages. */
void geometry_of_shape(Geometry *g, const struct Shape *s, const char *name);

/* A geometry of one solid, flow inside, from one shape dictionary d (its
   `shape` keyword and the kind's, transforms and CSG operands as in a
   surface entry of geometryDict, without type and flow); the keywords in
   extra (NULL: none) are allowed at d's top level for the caller to
   read.  File names inside are relative to case_dir. */
int geometry_parse_solid(Geometry *g, const Dict *d, const char *name, const char *case_dir, const DictKey *extra,
                         Err *e);

/* Reads <case>/system/geometryDict (or `path` when not NULL); file names
   inside (stl, cad) are relative to the case directory. */
int geometry_read(Geometry *g, const char *case_dir, const char *path, Err *e);
/* The same from a parsed dictionary; file is its name for messages. */
int geometry_parse(Geometry *g, const Dict *d, const char *file, const char *case_dir, Err *e);

void geometry_flatten(Geometry *g, int axis, double coord);

int geometry_fluid(const Geometry *g, const double x[3]);
void geometry_classify_line(const Geometry *g, int axis, const double p[3],
                            const double *c, int n, char *fluid);

/* Crossings of a -> b with the domain boundary, ascending t, each a change
   of the domain's inside state (a leaf crossing that does not change it,
   e.g. inside another union operand, is not reported).  Returns the
   number found (may exceed max; only max written). */
int geometry_crossings(const Geometry *g, const double a[3], const double b[3],
                       GeoCross *out, int max);

/* Outward unit normal of the flow domain (pointing into the solid) at
   the point of leaf `leaf`'s surface nearest to x: exact for primitives
   and CAD models, the nearest triangle's normal for STL surfaces. */
void geometry_normal(const Geometry *g, int leaf, const double x[3], double n[3]);

/* The leaf whose surface is nearest to x (by |level| for primitives and
   distance for triangulated leaves); used when a cut point carries no
   leaf. */
int geometry_nearest_leaf(const Geometry *g, const double x[3]);
/* The same among the leaves of one surface (surface < 0: all leaves). */
int geometry_nearest_leaf_of(const Geometry *g, int surface, const double x[3]);

/* A level function of the flow domain: negative inside, positive
   outside, zero on its boundary, and 1-Lipschitz (|level(x) - level(y)|
   <= |x - y|), so |level| never exceeds the distance to the boundary
   (built on shape_bound; the distance itself for an untransformed
   sphere or half-space). */
double geometry_level(const Geometry *g, const double x[3]);

/* A half-space n.x <= d. */
typedef struct GeoPlane {
    double n[3], d;
} GeoPlane;

/* When the domain is a convex polytope (one surface, flow inside, a box,
   a half-space or an intersection of them, any affine maps): writes its
   bounding half-spaces, in global coordinates (in 2-D: of the section,
   the flat-axis term moved into d; one with n = 0 and d < 0 holds
   nowhere) and returns their count (at most max); -1 otherwise. */
int geometry_planes(const Geometry *g, GeoPlane *pl, int max);

/* Exact volume of the flow domain inside the box lo..hi when it is known
   in closed form (one surface, one primitive, entirely inside the box,
   possibly transformed), else NAN.  In 2-D (flattened): the area of the
   section times (hi - lo) along the flat axis. */
double geometry_exact_volume(const Geometry *g, const double lo[3], const double hi[3]);

/* Points spread evenly over the flow domain's boundary, about h apart:
   every leaf's surface is sampled (shape_sample for primitives; the
   triangles, subdivided and relaxed, for STL and CAD leaves), mapped to
   global coordinates, and kept where it lies on the domain boundary (the
   domain changes across it).  Returns the count; *x (3 per point), *n
   (the domain's outward unit normal there, into the solid) and *leaf are
   new arrays.  In 2-D (flattened) the section's boundary is sampled in
   the mid-plane.  Used by voronoiGrid (seeds.h). */
int geometry_sample(const Geometry *g, double h, double **x, double **n, int **leaf);
/* The same, with unbounded leaves (half-spaces, infinite cylinders)
   sampled inside the box lo..hi only. */
int geometry_sample_box(const Geometry *g, double h, const double lo[3], const double hi[3], double **x,
                        double **n, int **leaf);

/* What a leaf is: an analytic shape (exact normals), a CAD model (exact
   normals through gmsh) or an STL surface (the triangles' normals). */
enum { GEO_LEAF_SHAPE, GEO_LEAF_CAD, GEO_LEAF_STL };
int geometry_leaf_kind(const Geometry *g, int leaf);

/* Points on the curves where the surfaces of two primitive leaves meet
   on an edge of the flow domain (CSG: a boss on a plate, a bore through
   it; 2-D: the corners of the section where two shapes meet), found from
   the samples px (leaves pl) within h of another leaf's surface by
   alternating projections onto the two surfaces.  Several samples reach
   the same stretch of curve: the points are not thinned.  Returns the
   count; *x (3 per point) and the two leaves *la, *lb are new arrays
   (NULL when none).  Used by voronoiGrid's edge rule (seeds.c). */
int geometry_sample_curves(const Geometry *g, double h, const double *px, const int *pl, int np, double **x,
                           int **la, int **lb);

/* Patch name and type of a leaf. */
const char *geometry_leaf_patch(const Geometry *g, int leaf);

#endif
