/*
** vtk.h: legacy VTK output (no libvtk dependency).
**
** One UNSTRUCTURED_GRID file per time: 2-D meshes (one cell thick with
** empty patches) are written as the polygons of one empty side (VTK_POLYGON,
** type 7, z of that side), 3-D meshes as VTK_POLYHEDRON (type 42) for every
** cell, which VTK >= 9 reads from legacy files (the cell connectivity holds
** the face stream: nFaces, then per face nPts and its point ids).  Cell
** data: every field (scalars as SCALARS-free FIELD arrays, vectors with 3
** components) in double precision; optional POINT_DATA (inverse-volume
** weighted average of the cells around each point).  TimeValue is stored as
** FIELD FieldData.  Binary legacy files are big-endian, as VTK requires.
** Boundary patches go to separate POLYDATA files.  A .vtk.series file (JSON,
** ParaView's format) lists the files with their time values.
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
} VtkOpts;

/* The internal mesh with cell data. fields may be NULL when nfields == 0. */
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
