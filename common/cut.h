/*
** cut.h: cut cells (ICCM^MC, spec granular-model.md §2.2, thesis §3.2.2):
** cuts a rectilinear block grid with the flow domain of a Geometry.
**
** The method, as implemented in cut.c:
**  1. Classify every grid vertex: fluid or solid (geometry_classify_line,
**     one sweep per x-line).
**  2. On every grid edge whose two vertices differ, take the domain's
**     crossing nearest the fluid vertex (geometry_crossings: exact for
**     analytic shapes and triangles).  Edges whose vertices agree get no
**     cut point: a feature that crosses one edge twice is thinner than
**     the grid there and is dropped (counted in nthin); an edge crossed
**     three or more times keeps the crossing nearest its fluid vertex
**     (counted in nodd).  A classification the crossings contradict (no
**     crossing found) puts the cut point on the solid vertex (counted in
**     ninconsistent).
**  3. Snap: a cut point closer than snap x (edge length) to its fluid
**     vertex turns that vertex solid (it lies on the surface to within
**     the tolerance) and all cut points on its edges move onto it; a cut
**     point that close to its solid vertex moves onto the solid vertex.
**     Afterwards every cut point is a solid vertex or lies at least
**     snap x (edge length) from every fluid vertex, so no cell or face
**     degenerates to zero size; coincident cut points are one point.
**  4. Grid faces: each face of the grid with a fluid corner becomes the
**     polygon walked round its corners in order, emitting fluid corners
**     and the cut points of edges whose ends differ (marching squares).
**     With two diagonal fluid corners this joins them through the face (a
**     hexagon): the thesis's consistent ambiguity rule, which makes the
**     two cells sharing the face agree, so the boundary is watertight.
**     Corners on the surface are judged by each cell, and where an edge
**     lies in a face of the geometry each cell has its own point on it;
**     a face two cells see differently is split into the part both see
**     (shared) and walls (doc/theory.md §6, cut_impl.h).
**  5. Boundary faces: the polygon sides joining two cut points, taken in
**     reverse, chain into closed loops, one per connected piece of the
**     boundary in the cell.  A planar loop (within 1e-12 of its size)
**     becomes one polygon; any other loop becomes a fan of triangles
**     about its centroid.  A cell whose only fluid corners are two
**     opposite ends of a body diagonal gets a tube of triangles joining
**     its two loops, so the cell stays connected (the thesis's
**     alternative case 4); counted in ntunnel.
**  6. Number the cells that have a fluid corner in Cartesian order and
**     assemble the polyMesh (meshbuild.h).  Each surface of the geometry
**     becomes a patch after the grid's own patches (same order, names and
**     types; their faces are the fluid parts of the grid's boundary
**     faces; cyclic pairs stay matched when the geometry is periodic).
**     Every cut cell lies inside its Cartesian cell, there is at most one
**     per Cartesian cell, and cell_parent records it; the cut-cell data
**     contract (Mesh.cartcells, cartcells.h) calls a cell whole when all
**     eight corners are fluid, else cut, with the volume computed here.
**
** 2-D grids (one cell thick between empty patches) need the geometry
** flattened first (geometry_flatten at the grid's mid-plane); the cut
** cells are then prisms of the marching-squares polygons.
**
** method staircase (cut_staircase.c) is the thesis's "Cartesian" grid
** instead: every Cartesian cell whose centre is in the fluid is kept
** whole, the others dropped, and the boundary is the staircase of grid
** faces between kept and dropped cells.
*/
#ifndef KIESEL_CUT_H
#define KIESEL_CUT_H

#include "err.h"
#include "geometry.h"
#include "mesh.h"

enum { CUT_METHOD_CUT, CUT_METHOD_STAIRCASE };

typedef struct CutOpts {
    double snap;       /* relative snap distance (default CUT_SNAP) */
    int method;        /* CUT_METHOD_CUT (default) or CUT_METHOD_STAIRCASE */
} CutOpts;

#define CUT_SNAP 1e-8

typedef struct CutStats {
    int ncart;              /* Cartesian cells in the grid */
    int ncells;             /* cells kept */
    int nsolid;             /* Cartesian cells dropped (no fluid corner) */
    int ncut;               /* kept cells smaller than their parent */
    double frac_min;        /* smallest volume / parent volume */
    int frac_min_cell;
    double vol_fluid;       /* sum of kept cell volumes */
    double vol_box;         /* the grid's volume */
    double area_boundary;   /* area of the immersed boundary */
    int nboundary;          /* immersed boundary faces */
    int nthin, nodd, nsnap, ninconsistent, ntunnel;
    int ndegenerate;        /* cells with fluid corners but no volume, dropped */
} CutStats;

void cut_opts_default(CutOpts *o);
/* Keywords of system/cutCellsDict (for -help and checking). */
extern const DictKey cut_keys[];
/* Reads the dictionary at path into o, over the defaults: fails with
   file:line on an unknown keyword or a value out of range. */
int cut_read_opts(const char *path, CutOpts *o, Err *e);

/* Cuts grid (a block grid: cart extras present, cell i + nx*(j + ny*k)
   is Cartesian cell (i, j, k)) by g into out (need not be initialised).
   out gets the Cartesian extras, cell_parent and boundary_normal (mesh.h).
   Fails when the grid has no Cartesian extras, a surface's patch name
   clashes with a grid patch, or no cell is left.  With o->method
   CUT_METHOD_STAIRCASE every cell is whole (cut_staircase.c). */
int cut_mesh(const Mesh *grid, const Geometry *g, const CutOpts *o,
             Mesh *out, CutStats *st, Err *e);

#endif
