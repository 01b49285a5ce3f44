/*
** runtime.h: simulation time: system/controlDict, time directories and
** their names, uniform/time, and the selection of times by -time,
** -latestTime and -noZero.
**
** Time names follow OpenFOAM's "timeFormat general; timePrecision 6;":
** %.{timePrecision}g, so 0.1, 0.05, 100.  A time directory is any directory
** of the case whose name parses completely as a number.
*/
#ifndef KIESEL_RUNTIME_H
#define KIESEL_RUNTIME_H

#include <time.h>

#include "dict.h"
#include "err.h"

enum { START_FIRST, START_START, START_LATEST };
enum { STOP_END, STOP_WRITENOW, STOP_NOWRITENOW, STOP_NEXTWRITE };
enum { WRITE_TIMESTEP, WRITE_RUNTIME, WRITE_ADJUSTABLE, WRITE_CPUTIME, WRITE_CLOCKTIME };
enum { TIMEFMT_GENERAL, TIMEFMT_FIXED, TIMEFMT_SCIENTIFIC };

typedef struct Control {
    char *path;            /* system/controlDict */
    int startFrom;         /* START_* */
    double startTime;
    int stopAt;            /* STOP_* */
    double endTime;
    double deltaT;
    int writeControl;      /* WRITE_* */
    double writeInterval;
    int purgeWrite;        /* keep only the last N time dirs (0 = all) */
    int writeVTK;          /* solvers write VTK/ at each write time (default on) */
    int writeBinary;       /* writeFormat binary */
    int writeCompression;  /* gzip; always 0 with writeBinary (OpenFOAM v1912) */
    int writePrecision;    /* default 6 */
    int timeFormat;        /* TIMEFMT_* */
    int timePrecision;     /* default 6 */
    int runTimeModifiable;
    int adjustTimeStep;
    double maxCo, maxDeltaT;
    int need_time;         /* endTime and deltaT were required (re-read alike) */
    time_t mtime;          /* of controlDict when read */
    long mtime_ns;         /* nanoseconds of that mtime (edits within a second) */
} Control;

/* Keywords of controlDict with defaults, for -help and checking. */
extern const DictKey runtime_control_keys[];

/* The one controlDict reader (see runtime.c): reads path into c.  With
   need_time, endTime and deltaT are required (a solver); without, they
   default to 0 and 1 (tools that read only the output format).  Every
   other keyword is read and checked the same either way. */
int runtime_load_control(Control *c, const char *path, int need_time, Err *e);
/* runtime_load_control of <case>/system/controlDict with need_time. */
int runtime_read_control(Control *c, const char *case_dir, Err *e);
/* Re-reads the file when runTimeModifiable is on and its mtime changed;
   returns 1 when re-read, 0 when unchanged, -1 on error (the old values
   are kept and the error reported, so a typo mid-run does not kill it). */
int runtime_reread(Control *c, Err *e);
void runtime_free_control(Control *c);

/* Time name for t: "0.1" (into s, at least 64 bytes). */
void runtime_time_name(const Control *c, double t, char *s);

/* Time directories of a case, sorted by value. */
typedef struct TimeDir {
    double value;
    char *name;
} TimeDir;
int runtime_list_times(const char *case_dir, TimeDir **out, Err *e);
void runtime_free_times(TimeDir *t, int n);

/* Selects from a sorted list by a -time spec ("0.1", "0.1,0.5", "0.1:0.5",
   ":0.5", "0.2:"), -latestTime, -noZero; keeps the selected entries in
   place and returns their count, or -1 with e on a malformed spec.
   As in OpenFOAM the result is the union of the -time selection and the
   latest time; -noZero then drops time 0.  Values match within a relative
   1e-9.  The names of dropped entries are freed and set to NULL, so
   runtime_free_times works with either the old or the new count. */
int runtime_select(TimeDir *t, int n, const char *spec, int latest, int nozero, Err *e);

/* Writes <case>/<name>/uniform/time (value, name, index, deltaT, deltaT0). */
int runtime_write_uniform_time(const char *case_dir, const char *name, double value, long index,
                               double deltaT, double deltaT0, Err *e);
/* Reads index (time-step count) from <case>/<name>/uniform/time; 0 if absent. */
long runtime_read_index(const char *case_dir, const char *name);

/* Removes the oldest time dirs beyond purgeWrite (never startTime's). */
int runtime_purge(const Control *c, const char *case_dir, Err *e);

/* ---- times to process ---- */

/* Every time directory of a case (all[0..nall-1], sorted) and the ones a
   tool processes, as positions into all: sel[0..n-1]. */
typedef struct TimeSel {
    TimeDir *all;
    int nall;
    int *sel;
    int n;
} TimeSel;

/* Lists the case's times and selects by -time/-latestTime/-noZero (as
   runtime_select).  Returns the count selected (0 is not an error here), or
   -1 with e (and s empty). */
int runtime_select_case(TimeSel *s, const char *case_dir, const char *spec, int latest, int nozero, Err *e);
/* As OpenFOAM's setFields chooses: the selection when any of spec, latest,
   nozero is given (an empty one is an error), else the one start time of
   controlDict c (startFrom; c NULL means time 0).  Returns the count >= 1
   or -1 with e. */
int runtime_pick_times(TimeSel *s, const char *case_dir, const char *spec, int latest, int nozero, const Control *c,
                       Err *e);
/* The i-th selected time. */
const TimeDir *runtime_sel_time(const TimeSel *s, int i);
void runtime_free_sel(TimeSel *s);

#endif
