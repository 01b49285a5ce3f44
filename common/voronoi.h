/*
** voronoi.h: bounded Voronoi grids (ICCM^V, spec granular-model.md §2.4,
** thesis §3.2.4): the Voronoi cells of a set of seeds, clipped to a box,
** assembled into a polyMesh.
**
** Each kept seed's cell is computed exactly: the box, clipped by the
** bisector plane of the seed and every other seed that can matter (found
** through a uniform bucket grid in growing shells, stopping when the
** nearest unvisited shell is farther than twice the cell's current
** radius).  A face between two kept seeds is an internal face; a face
** between a kept seed and a dropped seed becomes a boundary face on that
** dropped seed's patch (the immersed boundary: faces between interior and
** exterior seeds); the parts of a kept cell on the box sides become faces
** of the box patches.  Faces are planar by construction, orthogonal to and
** bisecting the segment between their two seeds.
**
** Robustness: points of a cell closer than VORONOI_MERGE x (box size)
** are one point (vertices on three faces are also named by their seeds,
** so every cell around them gets the same point); a 3-D face of area
** below (VORONOI_MERGE x box size)^2 whose points all lie within a few
** merge distances collapses to one point in every cell (a thin face
** longer than that stays); the face between two cells is computed once
** and shared, so both cells see the same polygon and the mesh is
** watertight; every cell is checked closed, and an open one is an error
** naming its seed.  Degenerate input (four or more cospherical seeds: the
** Cartesian lattice) is the normal case.  Details in voronoi.c.
**
** 2-D: with flat_axis >= 0 the seeds' coordinate along that axis is
** ignored, the cells are prisms one cell thick between lo and hi along
** it, and the two box sides normal to it are the empty patches.
*/
#ifndef KIESEL_VORONOI_H
#define KIESEL_VORONOI_H

#include "err.h"
#include "mesh.h"

#define VORONOI_MERGE 1e-10

typedef struct VoronoiInput {
    int nseeds;
    const double *x;        /* 3*nseeds seed positions */
    const char *keep;       /* nseeds: 1 = its cell is part of the grid */
    const int *patch;       /* nseeds: for dropped seeds, the patch index
                               (into patches) of faces between a kept cell
                               and this seed; ignored for kept seeds */
    double lo[3], hi[3];    /* the box */
    int flat_axis;          /* -1: 3-D */
    int npatches;           /* patches: box sides first, then surfaces */
    const Patch *patches;   /* name, type (copied) */
    int side_patch[6];      /* patch of each box side xMin, xMax, yMin, ... */
} VoronoiInput;

typedef struct VoronoiStats {
    int ncells;
    double vol_min, vol_total;
    int nfaces_dropped;     /* tiny faces removed */
    double ortho_max;       /* max |angle| between a face normal and its
                               seed segment (radians), for checking */
} VoronoiStats;

/* Builds the grid into out (need not be initialised).  Cell c of out is
   the c-th kept seed in seed order; out->cell_parent is NULL (no
   Cartesian parents), out->boundary_normal NULL (the caller sets exact
   normals).  seed_of, when not NULL, gets ncells entries: the seed of each
   cell. */
int voronoi_mesh(const VoronoiInput *in, Mesh *out, int *seed_of, VoronoiStats *st, Err *e);

#endif
