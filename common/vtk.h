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
** as it is made (an IoStream, io.h: never whole in memory).
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

typedef struct VtkSeriesEntry {
    const char *name;  /* file name relative to the series file */
    double time;
} VtkSeriesEntry;
int vtk_write_series(const char *path, const VtkSeriesEntry *v, int n, Err *e);

#endif
