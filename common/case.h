/*
** case.h: a case directory as every tool sees it: the directory, its
** system/controlDict (Control, runtime.h), the time directories a tool
** selected, and the paths of its files.
**
** One Case per run, opened once by the tool's main and passed down, so
** the case directory never travels as a bare string between the frame
** and the library.  controlDict is optional for the tools that only read
** its output format (a missing file means ascii, uncompressed); it is
** read by the one reader, runtime_load_control, whatever the tool.  Grid
** files and field files take writeFormat and writeCompression from the
** same two functions below, so the two can never disagree again.
*/
#ifndef KIESEL_CASE_H
#define KIESEL_CASE_H

#include "err.h"
#include "field.h"
#include "mesh.h"
#include "runtime.h"

typedef struct Case {
    char *dir;          /* the case directory, "." by default */
    Control control;    /* system/controlDict; all zero when has_control is 0 */
    int has_control;
    TimeSel times;      /* the times a tool selected (times.n 0 before) */
} Case;

/* How much of controlDict a tool needs. */
enum {
    CASE_NO_CONTROL,   /* none: dictQuery may be run to mend a broken one */
    CASE_CONTROL_FORMAT,  /* read when present, endTime/deltaT optional */
    CASE_CONTROL_TIME     /* required, with endTime and deltaT (solvers) */
};

/* Opens dir ("." when NULL): fails when it is not a directory, then
   reads system/controlDict as need says.  On failure c is left empty
   (case_free is safe). */
int case_open(Case *c, const char *dir, int need, Err *e);
void case_free(Case *c);

/* "<dir>/<rel>" (caller frees). */
char *case_path(const Case *c, const char *rel);

/* Output format of grid files / field files from writeFormat,
   writeCompression and writePrecision (fields only: grids keep their
   own exact formatting). */
void case_mesh_format(const Case *c, MeshWriteOpts *w);
void case_field_format(const Case *c, FieldWriteOpts *o);

/* Selects the times by -time/-latestTime/-noZero (runtime_select_case);
   returns the count, 0 when none matches. */
int case_select_times(Case *c, const char *spec, int latest, int nozero, Err *e);
/* As OpenFOAM's setFields picks them (runtime_pick_times): the selection
   when given, else controlDict's start time; returns the count >= 1. */
int case_pick_times(Case *c, const char *spec, int latest, int nozero, Err *e);
/* Name of the i-th selected time. */
const char *case_time(const Case *c, int i);

#endif
