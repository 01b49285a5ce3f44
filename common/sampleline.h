/*
** sampleline.h: sampleLine's dictionary (sampleLineDict): the fields and
** lines to sample, and the CSV files of one time.
**
**   fields (alpha.s U);
**   interpolation cell;            // or linear
**   lines
**   {
**       centre { start (0 0.5 0.05); end (1 0.5 0.05); nPoints 101; }
**       column { start (0.5 0 0.05); end (0.5 1 0.05); mode cells; }
**   }
**
** (lines may also be a list ( NAME { ... } ... ).)  Each line gives one
** CSV file per time, with the header
** distance,x,y,z,<scalar>,<vector>_x,<vector>_y,<vector>_z[,length]
** (numbers in shortest round-trip form), written to <outdir>/<time>/
** <line>.csv, or to stdout when outdir is NULL.  The sampling itself is
** linesample.h's.  Progress text goes into a Buf: the library never prints.
*/
#ifndef KIESEL_SAMPLELINE_H
#define KIESEL_SAMPLELINE_H

#include "buf.h"
#include "dict.h"
#include "err.h"
#include "field.h"
#include "locate.h"
#include "mesh.h"

typedef struct SampleLine {
    const char *name;   /* lives as long as the dictionary */
    double a[3], b[3];
    int mode, npoints;  /* SAMPLE_UNIFORM or SAMPLE_CELLS; points (uniform) */
    int reported;       /* points outside the mesh already reported */
} SampleLine;

typedef struct SampleLineDict {
    const char **fields;
    const char *fields_file;  /* where `fields` is, for missing-field errors */
    int fields_line;
    int nfields;
    int interp;               /* SAMPLE_CELL_VALUE or SAMPLE_LINEAR */
    SampleLine *lines;
    int nlines;
} SampleLineDict;

/* Top-level keywords and the help text on each line's keywords. */
extern const DictKey sampleline_keys[];
extern const char sampleline_help[];

/* Parses and checks the whole dictionary (s need not be initialised; it
   is always safe to sampleline_free afterwards). */
int sampleline_parse(SampleLineDict *s, const Dict *d, Err *e);
void sampleline_free(SampleLineDict *s);
/* Keeps only the line called name; the error (without location) suggests
   the closest name. */
int sampleline_pick(SampleLineDict *s, const char *name, Err *e);

/* One time being sampled: its fields (and gradients for linear
   interpolation) and output directory. */
typedef struct SampleLineTime {
    const SampleLineDict *s;
    const Mesh *m;
    const Locator *L;
    const char *time;
    char *dir;          /* <outdir>/<time>, or NULL for stdout */
    int nblocks;        /* CSV blocks on stdout in the whole run */
    Field *f;           /* nfields */
    double **grad;      /* per field, NULL for cell interpolation */
} SampleLineTime;

/* Reads the fields of time directory <case_dir>/<time> and creates
   <outdir>/<time> (outdir NULL: CSV to stdout, each block preceded by
   "# time T line L" when nblocks > 1).  sampleline_time_end is needed even
   after a failure. */
int sampleline_time_begin(SampleLineTime *t, const SampleLineDict *s, const Mesh *m, const Locator *L,
                          const char *case_dir, const char *time, const char *outdir, int nblocks, Err *e);
/* Samples line l and writes its CSV; appends the report to log (also when
   the write fails).  Written one line at a time so that, with CSV on
   stdout, the caller's log interleaves with the data. */
int sampleline_time_sample(SampleLineTime *t, SampleLine *l, Buf *log, Err *e);
void sampleline_time_end(SampleLineTime *t);

#endif
