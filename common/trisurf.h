/*
** trisurf.h: closed triangulated surfaces (from STL files or gmsh) as
** solids: topology checks, robust inside tests and exact segment
** crossings.
**
** Points are welded (one index per distinct position), triangles are
** index triples whose right-hand-rule normal points out of the solid
** (trisurf_orient makes it so).  A surface is usable as a solid when it is
** closed and manifold: every edge is shared by exactly two triangles that
** traverse it in opposite directions.
**
** Several shells.  A file may hold several closed shells (connected
** components): they may be nested (a cavity inside a solid, an island in
** the cavity) or overlap (parts of an assembly written one after the
** other).  The solid is where the winding number of the whole surface is
** positive, so overlapping outward shells make their union and an
** inward shell inside an outward one a cavity; trisurf_orient chooses the
** orientations (doc/theory.md, "Orientation and nesting").
**
** Robustness.  A query point or a grid line may hit a triangle edge or
** vertex exactly (a sphere STL cut by a grid through its poles, a box
** face on a grid plane).  Every predicate is evaluated per edge, with the
** edge's two endpoints in a canonical order (lower point index first) and
** the sign negated for the triangle that traverses it the other way, so
** two triangles sharing an edge always get opposite answers from the same
** floating-point value; signs are exact (floating-point filter, exact
** expansion arithmetic when it is inconclusive).  Zero values are broken
** by a fixed symbolic perturbation (simulation of simplicity): every
** query point is moved by delta = (e_x, e_y, e_z), e_x >> e_y >> e_z > 0,
** which moves an axis line by (eps, eps^2) in its projection plane (axes
** in increasing order).  The result: a line through an edge or vertex hits
** exactly one triangle of the fan around it, so hit counts have the right
** parity and the surface is watertight for every query (Woop, Benthin and
** Wald 2013 use the same argument); and a point exactly on the surface is
** classified as the point moved by delta (inside where the first non-zero
** component of the face's outward normal is negative: the unit cube is
** the box [0,1)^3), identically by every query on every axis, so the
** crossings of a segment always match the inside states of its ends.
**
** Acceleration: a uniform bucket grid per axis over the projection of the
** triangles onto the plane normal to that axis (built by trisurf_prepare),
** so a line along an axis visits only the triangles over its cell.
*/
#ifndef KIESEL_TRISURF_H
#define KIESEL_TRISURF_H

#include "err.h"

typedef struct TriBuckets TriBuckets;   /* private to trisurf.c */

typedef struct TriSurf {
    int npoints, ntris;
    double *points;        /* 3*npoints */
    int *tris;             /* 3*ntris point indices */
    int *tag;              /* ntris: region / CAD surface tag of each
                              triangle (STL: index of its `solid` block),
                              or NULL */
    int nnames;
    char **names;          /* names of the STL solids (tag -> name), or NULL */
    double lo[3], hi[3];   /* bounding box (set by trisurf_prepare) */
    TriBuckets *bk[3];     /* per-axis line buckets, NULL until prepared */
} TriSurf;

/* Topology report (trisurf_check). */
typedef struct TriTopo {
    int nedges;
    int nopen;             /* edges used by one triangle */
    int nnonmanifold;      /* edges used by three or more triangles */
    int nflipped;          /* edges whose two triangles run the same way */
    int ndegenerate;       /* triangles with zero area or repeated points */
    double open_at[3];     /* midpoint of the first edge of each kind */
    double nonmanifold_at[3];
    double flipped_at[3];
    double degenerate_at[3];
    double volume;         /* signed enclosed volume (divergence theorem) */
    double area;
} TriTopo;

void trisurf_init(TriSurf *s);
void trisurf_free(TriSurf *s);

/* Builds a surface from a triangle soup: xyz[9*i..9*i+8] are the three
   corners of triangle i.  Corners at bit-identical positions become one
   point (a hash on the coordinates).  tag may be NULL.  s need not be
   initialised; it is overwritten. */
void trisurf_from_soup(TriSurf *s, const double *xyz, int ntris, const int *tag);

/* Edge-based topology check; never fails (fills t). */
void trisurf_check(const TriSurf *s, TriTopo *t);

/* Makes the orientation consistent (flood fill over manifold edges) and
   right for the solid.  The given orientation of the shells is kept when
   it makes sense: no shell's triangles disagree, every shell with
   positive volume reaches outside the solid of the others (W <= 0 at one
   of its points at least, W the others' winding number) and every shell
   with negative volume lies inside it (W > 0 at all its points).  Else
   it is repaired: a shell held wholly by an odd number of others (a
   non-zero winding number of each about every point of the shell) is a
   cavity, turned inward, every other shell outward.  One ray per point
   tested, through line buckets along x: linear in the surface size.
   Returns the number of triangles flipped.  Only meaningful for closed
   manifold shells (open ones are oriented by the same rule). */
int trisurf_orient(TriSurf *s);

/* Drops zero-area triangles (repeated points). Returns how many. */
int trisurf_drop_degenerate(TriSurf *s);

/* Transforms every point: x' = A x + b (A row-major 3x3); flips the
   triangles when det A < 0 so they stay outward.  Call before prepare. */
void trisurf_transform(TriSurf *s, const double A[9], const double b[3]);

/* Builds the bounding box and line buckets.  Must be called once after
   the surface is final and before any query below. */
int trisurf_prepare(TriSurf *s, Err *e);

/* Inside test: winding number of the surface about x (positive: inside),
   counted along the ray from x in +x direction with the perturbation rule
   above; a point on the surface is the point moved by delta (see above). */
int trisurf_inside(const TriSurf *s, const double x[3]);

/* Classifies the n points p + (c[i] - p[axis]) e_axis (c ascending) at
   once by sweeping the line through p along `axis`: in[i] = 1 inside,
   0 outside.  For a closed surface, the same answers as trisurf_inside
   for every point, on the surface too (exact predicates, one
   perturbation); c must be non-decreasing. */
void trisurf_classify_line(const TriSurf *s, int axis, const double p[3],
                           const double *c, int n, char *in);

/* Crossings of the segment a->b with the boundary of the solid:
   parameters t in [0, 1], ascending, and the triangle hit (tri may be
   NULL).  Only crossings where the winding number changes between <= 0
   and > 0 are reported (not those inside an overlap of two shells), so
   they alternate entering and leaving, starting from inside(a).  Segments
   along an axis (a and b differ in one coordinate only) use the robust
   projected test above; other segments use orientation predicates with
   the same per-edge consistency.  The crossing point is the intersection
   of the segment with the triangle's plane, computed from the barycentric
   edge values (exact for a face normal to an axis segment and at
   vertices).  A crossing exactly at an end is reported when the segment
   moved by delta still crosses there, so for a closed surface the count's
   parity is always inside(a) != inside(b).  Returns the number found (may
   exceed max; only max written). */
int trisurf_crossings(const TriSurf *s, const double a[3], const double b[3],
                      double *t, int *tri, int max);

/* Nearest triangle to x and the distance to it (exact point-triangle
   distance, search through the buckets in growing rings). */
int trisurf_nearest(const TriSurf *s, const double x[3], double *dist);

/* Unit outward normal of triangle i. */
void trisurf_normal(const TriSurf *s, int i, double n[3]);

#endif
