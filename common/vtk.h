/*
** vtk.h: legacy VTK output (no libvtk dependency).
**
** One UNSTRUCTURED_GRID file per time ("# vtk DataFile Version 2.0", as
** foamToVTK -legacy).  2-D meshes (one cell thick with empty patches) are
** written as the polygons of the lower empty side (VTK_POLYGON, type 7,
** counter-clockwise about +axis, coordinates of that side).  3-D meshes:
** cells that are exact hexahedra as VTK_HEXAHEDRON (type 12), every other
** cell as VTK_POLYHEDRON (type 42), which VTK >= 9 reads from legacy files
** (the cell connectivity holds the face stream: nFaces, then per face nPts
** and its point ids, normals pointing out of the cell).  Cell data: every
** field as a FIELD array of doubles (scalars 1 component, vectors 3);
** optional POINT_DATA (volume-weighted average of the cells around each
** point; patches: face-area weighted).  TimeValue is stored as FIELD
** FieldData.  Binary legacy files are big-endian, as VTK requires.
** Boundary patches go to separate POLYDATA files (POLYGONS, values from
** field_patch_values).  A .vtk.series file (JSON, ParaView's format) lists
** the files with their time values.  Every file is written atomically,
** as it is made (an IoStream, io.h: never whole in memory), and may be
** given its fields one at a time (VtkFile).
** Geometry: point data needs m->cell_vol (internal) or m->face_area
** (patches), from mesh_geometry; cell->face addressing is used when present
** and built internally otherwise.
*/
#ifndef KIESEL_VTK_H
#define KIESEL_VTK_H

#include "err.h"
#include "field.h"
#include "mesh.h"

typedef struct VtkOpts {
    int binary;        /* default 1 */
    int point_data;    /* also write cell->point interpolated data */
    double time;       /* TimeValue */
    const char *title; /* second header line */
    const char *mesh_name;  /* where the mesh was read from ("case/constant/polyMesh"): messages about a mesh
                               that cannot be written name it; NULL names the output file */
} VtkOpts;

/* Defaults: binary, no point data, time 0, title "Kiesel", no mesh name. */
void vtk_opts_init(VtkOpts *o);

/* The internal mesh with cell data. fields may be NULL when nfields == 0;
   o NULL means the defaults. */
int vtk_write_internal(const char *path, const Mesh *m, const Field *fields, int nfields,
                       const VtkOpts *o, Err *e);
/* One patch as POLYDATA with the boundary values of the fields. */
int vtk_write_patch(const char *path, const Mesh *m, int patch, const Field *fields, int nfields,
                    const VtkOpts *o, Err *e);

/* A file written one field at a time, so that a caller reading fields
   from disk holds one of them at once: vtk_begin_internal or
   vtk_begin_patch writes the geometry (and frees its connectivity unless
   point data needs it), vtk_put_field each of the nfields fields in turn,
   vtk_end renames the finished file into place (vtk_abort, or an error of
   vtk_end, removes it instead).  The files are those of
   vtk_write_internal / vtk_write_patch, byte for byte.  A begin returns
   NULL with e filled; after a failed vtk_put_field call vtk_abort. */
typedef struct VtkFile VtkFile;
VtkFile *vtk_begin_internal(const char *path, const Mesh *m, int nfields, const VtkOpts *o, Err *e);
VtkFile *vtk_begin_patch(const char *path, const Mesh *m, int patch, int nfields, const VtkOpts *o, Err *e);
int vtk_put_field(VtkFile *f, const Field *field, Err *e);
int vtk_end(VtkFile *f, Err *e);
void vtk_abort(VtkFile *f);

typedef struct VtkSeriesEntry {
    const char *name;  /* file name relative to the series file */
    double time;
} VtkSeriesEntry;
int vtk_write_series(const char *path, const VtkSeriesEntry *v, int n, Err *e);

#endif
