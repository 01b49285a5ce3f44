/*
** vtkcase.h: a case converted to legacy VTK files for ParaView, laid out
** as foamToVTK -legacy lays them out:
**
**     VTK/<case>_<index>.vtk                 internal mesh, every vol field
**     VTK/<patch>/<patch>_<index>.vtk        each non-empty-type patch
**     VTK/<case>.vtk.series                  ParaView's time series (JSON)
**     VTK/<patch>/<patch>.vtk.series
**
** <case> is the base name of the absolute case path; <index> is the time
** step index of <time>/uniform/time, or, for a time without that file, its
** position in the sorted list of all time directories.  Should those
** numbers collide, every time takes its position instead, so one time never
** overwrites another's file.  A case without time directories is written
** as its mesh alone at time 0, index 0.
**
** Series files list every time of the case whose file exists in VTK/, not
** only the times converted by this run, so converting the latest time
** after a full conversion keeps the whole series.  The file writing is
** vtk.h's; progress text goes into a Buf: the library never prints.
**
** A solver keeps VTK/ a mirror of its time directories (vtkcase_sync):
** after each write time (and purgeWrite) VTK/ holds exactly the files a
** full writeVTK conversion with default options would write, without
** converting everything again.  The old series file is the record of what
** is on disk: a time whose internal file exists under the name the series
** gives its time, and whose patch files exist, is current; every other
** time, and the one just written, is (re)converted from its directory, so
** the VTK values are the time directory's digits, as writeVTK's are.  A
** restart that changes the step indices (names) or makes them collide
** (every time then takes its position) is caught by the same test.
** Numbered files that no time on disk names any more (purgeWrite, or a
** renumbering) are removed, so purged times leave the series and the disk.
*/
#ifndef KIESEL_VTKCASE_H
#define KIESEL_VTKCASE_H

#include "buf.h"
#include "err.h"
#include "field.h"
#include "mesh.h"
#include "runtime.h"
#include "vtk.h"

typedef struct VtkCase {
    const char *case_dir;
    const Mesh *m;
    char *name;        /* <case> */
    TimeSel times;     /* every time, and those to convert */
    long *index;       /* per time of times.all */
    VtkOpts opts;      /* binary, point_data; time and title set per file; mesh_name is mesh_dir */
    char *mesh_dir;    /* <case>/constant/polyMesh, for messages about the mesh */
    int boundary;      /* write the patches */
} VtkCase;

/* Names the case, selects its times (-time/-latestTime/-noZero: spec,
   latest, nozero; an empty selection is an error) and numbers them.  opts
   and boundary are the caller's to set afterwards (defaults: vtk_opts_init,
   boundary on).  vtkcase_free is needed even after a failure. */
int vtkcase_open(VtkCase *v, const char *case_dir, const Mesh *m, const char *spec, int latest, int nozero,
                 Err *e);
void vtkcase_free(VtkCase *v);

/* Creates <case>/VTK, removing it first when overwrite is set. */
int vtkcase_mkdir(const VtkCase *v, int overwrite, Err *e);

/* Reads the vol fields of the i-th selected time (none when the time has
   no directory): all of them, or those named in want (field_read_dir).
   Appends "volScalar : a b" / "volVector : U" lines to log.  Returns the
   count or -1. */
int vtkcase_read_fields(const VtkCase *v, int i, const char *const *want, int nwant, Field **f, Buf *log, Err *e);
/* Writes the internal mesh and the patches of the i-th selected time. */
int vtkcase_write_time(const VtkCase *v, int i, const Field *f, int nf, Buf *log, Err *e);
/* Writes the series files of the internal mesh and of every patch. */
int vtkcase_write_series(const VtkCase *v, Buf *log, Err *e);

/* A solver's write time: VTK/ brought to the state a full writeVTK
   conversion of the case would leave (see the top): fresh, the name of
   the time directory just written (or NULL), is always converted, the
   other times only when not current; stale numbered files are removed;
   the series files rewritten.  Appends one line to log (the file of
   fresh, other times converted, files removed, the series' length).
   Returns the count of times converted or -1. */
int vtkcase_sync(const char *case_dir, const Mesh *m, const char *fresh, Buf *log, Err *e);

/* Field names of a -fields option, "(p U)" or "p U", without repeats, into
   a new array (io_free_list); returns the count. */
int vtkcase_field_names(const char *spec, char ***names);

#endif
