/*
** meshbuild.h: assembles a polyMesh from faces given in any order.
**
** Grid generators (cutCells, mergeCells, voronoiGrid) produce faces as
** they find them: a polygon, the cell on each side, or a cell and a
** boundary patch.  meshbuild_finish turns that soup into OpenFOAM's order
** (mesh.h): each internal face is oriented out of its lower-numbered cell
** (the point order is reversed when the caller gave it the other way),
** internal faces are sorted by (owner, neighbour) (ties keep the order of
** addition), boundary faces are grouped by patch in patch order (keeping
** the order of addition inside a patch, which keeps cyclic pairs
** matched), and points no face uses are dropped.  Cells keep the numbers
** the caller gave (0..ncells-1); every cell must have a face.
**
** Faces must be planar polygons with at least 3 distinct points; the
** builder does not check geometry (quality_check does).
*/
#ifndef KIESEL_MESHBUILD_H
#define KIESEL_MESHBUILD_H

#include "err.h"
#include "mesh.h"

typedef struct MeshBuild {
    int npoints, point_cap;
    double *points;        /* 3*npoints */
    int nfaces, face_cap;
    int *face_off;         /* nfaces+1 */
    int idx_len, idx_cap;
    int *face_idx;
    int *owner;            /* cell the face's normal points out of */
    int *other;            /* cell on the other side, or -1 - patch */
    int ncells;            /* 1 + largest cell number seen */
    int npatches;
    Patch *patches;        /* owned strings */
} MeshBuild;

void meshbuild_init(MeshBuild *b);
void meshbuild_free(MeshBuild *b);

/* Reserves room for npoints points, nfaces faces and nidx face point
   indices in all, so a builder that knows its size up front (a cutter
   from its cell count, a merger from its input) avoids the copies of
   geometric growth.  Estimates are fine: the arrays still grow past them. */
void meshbuild_reserve(MeshBuild *b, size_t npoints, size_t nfaces, size_t nidx);

/* Adds a patch (name, type, neighbourPatch or NULL, inGroups or NULL);
   returns its index.  Strings are copied. */
int meshbuild_patch(MeshBuild *b, const char *name, const char *type,
                    const char *neighbour, const char *groups);
/* Adds a point; returns its index. */
int meshbuild_point(MeshBuild *b, const double x[3]);
/* Adds the polygon pts[0..n-1] (point indices) whose right-hand normal
   points out of cell `cell` into cell `other` (other >= 0) or out of the
   domain through patch `patch` (other < 0).  Returns the face's index in
   order of addition. */
int meshbuild_face(MeshBuild *b, const int *pts, int n, int cell, int other, int patch);

/* Moves the result into m (initialised with mesh_init; extras cart and
   cell_parent are left for the caller).  face_map, when not NULL, gets
   nfaces entries: the final index of each added face, so the caller can
   permute per-face data; point_map likewise (npoints, -1 for dropped
   points).  Fails when a cell has no face or a face has fewer than 3
   points.  b is emptied. */
int meshbuild_finish(MeshBuild *b, Mesh *m, int *face_map, int *point_map, Err *e);

#endif
