/*
** mesh.h: polyMesh: OpenFOAM's face-based mesh, read, written, measured.
**
** Invariants (OpenFOAM's, checked by mesh_check and kept by every writer):
**   - internal faces come first: faces 0..ninternal-1 have a neighbour;
**   - owner[f] < neighbour[f] for internal faces, and internal faces are in
**     upper-triangular order (sorted by owner, then by neighbour);
**   - a face's right-hand-rule normal points out of its owner;
**   - boundary faces follow, grouped by patch in the order of `patches`,
**     patch p covering faces start..start+size-1 contiguously;
**   - the number of cells is max(owner, neighbour) + 1 (OpenFOAM keeps no
**     cell list).
** Storage is flat arrays indexed by point, face and cell (no per-cell
** objects), so a later MPI decomposition only adds halo cells.
**
** Files: constant/polyMesh/{points,faces,owner,neighbour,boundary} in
** ascii or binary (faces as faceList or faceCompactList), each optionally
** gzipped.  Kiesel's extras live beside them, ignored by OpenFOAM:
**   cartesianGrid   dictionary: the parent rectilinear grid ("n (nx ny nz);
**                   x N(...); y N(...); z N(...);" point coordinates per axis)
**   cellParent      labelList: each cell's parent Cartesian cell
**                   i + nx*(j + ny*k), or -1 (absent file = no parents).
**   boundaryNormal  vectorField, one per boundary face (in face order,
**                   starting at face ninternal): the exact outward unit
**                   normal of the geometry at the face centre (cutCells,
**                   voronoiGrid), which slip walls need.
**   mergeMap        labelList, one per cell of the grid before merging:
**                   the merged cell it became (mergeCells).
**   cellSeed        vectorField, one per cell: the Voronoi seed the cell
**                   belongs to (voronoiGrid), the point the solvers use as
**                   the cell's node (ICCM^V, spec §2.4).
** Stream form ("-" as path, for pipelines): the same files one after the
** other, each preceded by a line "@file <name> <nbytes>\n", ended by a line
** "@end\n"; see doc/file-formats.md.
*/
#ifndef KIESEL_MESH_H
#define KIESEL_MESH_H

#include <stddef.h>

#include "err.h"

typedef struct Patch {
    char *name;
    char *type;        /* patch, wall, empty, symmetry, symmetryPlane, cyclic, ... */
    int start, size;   /* face range */
    char *neighbour;   /* cyclic: neighbourPatch, else NULL */
    char *groups;      /* inGroups as written, e.g. "1(wall)", or NULL */
                       /* (NULL stands for the default: "1(<type>)" for wall
                          and constraint types, none for patch; the reader
                          turns the default back into NULL) */
} Patch;

typedef struct CartGrid {
    int n[3];          /* cells per axis; n[k] = 0 when absent */
    double *x[3];      /* n[k]+1 point coordinates per axis */
} CartGrid;

typedef struct Mesh {
    int npoints, nfaces, ninternal, ncells, npatches;
    double *points;    /* 3*npoints */
    int *face_off;     /* nfaces+1: face f has points face_idx[face_off[f]..face_off[f+1]-1] */
    int *face_idx;
    int *owner;        /* nfaces */
    int *neighbour;    /* ninternal */
    Patch *patches;

    /* extras (may be absent: cart.n[0] == 0, cell_parent, wall_normal,
       merge_map, cell_seed NULL) */
    CartGrid cart;
    int *cell_parent;  /* ncells */
    double *wall_normal;  /* 3*(nfaces - ninternal), or NULL */
    int *merge_map;    /* nmerge_old entries, or NULL */
    int nmerge_old;
    double *cell_seed;    /* 3*ncells, or NULL */

    /* geometry, filled by mesh_geometry */
    double *face_area;    /* 3*nfaces, area vectors Sf */
    double *face_centre;  /* 3*nfaces */
    double *cell_vol;     /* ncells */
    double *cell_centre;  /* 3*ncells */

    /* cell -> face addressing, filled by mesh_cell_faces */
    int *cell_off;        /* ncells+1 */
    int *cell_faces;      /* face indices of each cell */
} Mesh;

typedef struct MeshWriteOpts {
    int binary;        /* faces as faceCompactList, lists raw */
    int gzip;          /* files as points.gz, ... */
} MeshWriteOpts;

void mesh_init(Mesh *m);
void mesh_free(Mesh *m);

/* Reads <dir>/{points,faces,owner,neighbour,boundary} (+ extras when
   present); dir "-" reads the stream form from stdin.  Checks sizes and
   index ranges (every error names the file and line); does not check the
   ordering invariants (mesh_check does). */
/* (m need not be initialised; it is overwritten, and left empty after a
   failure, so mesh_free is always safe.) */
int mesh_read(Mesh *m, const char *dir, Err *e);
/* Writes the files into dir (created if needed), each atomically; dir "-"
   writes the stream form to stdout. */
int mesh_write(const Mesh *m, const char *dir, const MeshWriteOpts *o, Err *e);
/* Serialises to / parses from a memory buffer in stream form. */
struct Buf;
int mesh_write_stream(const Mesh *m, struct Buf *out, const MeshWriteOpts *o, Err *e);
int mesh_read_stream(Mesh *m, const char *data, size_t n, const char *name, Err *e);

/* Computes face and cell geometry (geom.h). Needs cell faces. */
void mesh_geometry(Mesh *m);
/* Builds cell_off/cell_faces from owner/neighbour. */
void mesh_cell_faces(Mesh *m);
/* The same lists into new arrays *off (ncells+1) and *faces, for a mesh
   that is only read (the caller frees them). */
void mesh_cell_face_lists(const Mesh *m, int **off, int **faces);

/* Checks the ordering and range invariants listed above; the message
   names the first offending face. */
int mesh_check(const Mesh *m, Err *e);

/* 2-D detection: returns the normal axis (0, 1, 2) when the mesh is one
   cell thick between empty patches, -1 for a 3-D mesh. */
int mesh_empty_axis(const Mesh *m);

/* Patch index by name, or -1. */
int mesh_patch(const Mesh *m, const char *name);
/* Deep copy of patch p into q (new strings; start and size copied). */
void mesh_patch_copy(const Patch *p, Patch *q);
/* Is the patch of OpenFOAM's type empty (the front and back of a 2-D
   case, which carry no values)?  mesh_type_is_empty for a bare type
   name; a NULL type is not empty. */
int mesh_patch_is_empty(const Patch *p);
int mesh_type_is_empty(const char *type);
/* Patch index of boundary face f, or -1 for an internal face. */
int mesh_face_patch(const Mesh *m, int f);

/* Cartesian parent spacing of cell c (h[k] = width along axis k), from
   cart and cell_parent; returns -1 when the cell has no parent. */
int mesh_cell_spacing(const Mesh *m, int c, double h[3]);

/* Copies the Cartesian parent grid a into b (b's arrays are new). */
void mesh_copy_cart(const CartGrid *a, CartGrid *b);

/* Bounding box of all points. */
void mesh_bounds(const Mesh *m, double lo[3], double hi[3]);

#endif
