/*
** vgrid.h: the boundary-conforming Voronoi grid of a block grid and an
** immersed geometry (ICCM^V, spec granular-model.md §2.4, thesis §3.2.4):
** what voronoiGrid does, as one library call.
**
**   seeds (seeds.h) -> bounded Voronoi cells (voronoi.h) -> polyMesh with
**   the block grid's side patches, one patch per surface of the geometry,
**   each cell's seed (Mesh.cell_seed), exact boundary normals
**   (Mesh.boundary_normal), the block grid's cartesianGrid and the
**   cut-cell data contract (Mesh.cartcells, cartcells.h).
**
** Patches: the block grid's patches first, in its order (each side of the
** box must lie in one patch, as blockGrid makes them), then one per
** surface of the geometry, named and typed as in geometryDict.  A 2-D
** block grid (one cell thick, empty front and back) gives a 2-D Voronoi
** grid: prisms one cell thick, the geometry cut by the mid-plane.
**
** Boundary normals: on a surface patch, the exact outward normal of the
** geometry (into the solid) at the face centre, from the nearest leaf of
** that surface; on a box side, the side's normal.  The normal of a
** Voronoi boundary face itself is the direction between its two seeds,
** which the seeds make the sample point's normal: the two agree to the
** curvature error, which vgrid_normals measures, except on the small
** faces between seeds of neighbouring pairs.
*/
#ifndef KIESEL_VGRID_H
#define KIESEL_VGRID_H

#include "err.h"
#include "geometry.h"
#include "mesh.h"
#include "seeds.h"

typedef struct VGridStats {
    int nseeds;             /* all seeds, kept or exterior */
    int nboundary;          /* boundary seeds (pairs and layers), kept */
    int ncartesian;         /* Cartesian centres kept as interior seeds */
    int ncells;
    int nsurface_faces;     /* faces on the surfaces' patches */
    double vol_total, vol_min;
    double vol_bound;       /* pi a^3/6 (2-D: pi a^2/4 x thickness) */
    double h, a;            /* grid spacing, minimum seed spacing */
    double ortho_max;       /* radians, faces vs their seed segments */
    int nfaces_dropped;
    int nstl;               /* STL leaves (triangulated normals) */
} VGridStats;

/* Builds the Voronoi grid of `grid` (a block grid with its cartesianGrid
   extra) and g (NULL or no surfaces: the cell centres only) into out.
   out gets the block grid's cartesianGrid and the cut-cell data contract
   (cartcells.h: each cell's parent holds its seed), whose volumes need
   out's geometry, which is therefore filled; the volumes in st come from
   the cells as they are built. */
int vgrid_mesh(const Mesh *grid, const Geometry *g, const SeedOpts *o, Mesh *out, VGridStats *st, Err *e);

/* Boundary normals against the faces: the angle between each surface
   face's area vector and its exact normal (Mesh.boundary_normal). */
typedef struct VGridNormals {
    int nfaces;             /* surface faces */
    double max;             /* largest angle (radians), -1 without faces */
    int face;               /* where */
    int noff;               /* faces beyond the tolerance: the small
                               faces between seeds of neighbouring pairs
                               (spec §2.4) */
    double area_off;        /* their share of the surface area */
} VGridNormals;

/* Patches from first_surface_patch on are the surfaces; tol in radians. */
void vgrid_normals(const Mesh *m, int first_surface_patch, double tol, VGridNormals *r);

#endif
