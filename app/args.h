/*
** args.h: the command line every tool shares, the banner, and the log.
**
** Common options: -case DIR, -help, -version, -time SPEC, -latestTime,
** -noZero, -dict FILE (another dictionary than the default).  Each tool
** adds its own options through a table and names its dictionaries with
** their keyword tables, so that -help lists every keyword with its default.
**
** Output: the banner and progress go to stdout, unless the tool writes its
** data to stdout ("-o -"), in which case args_info_stream() is stderr.
** The log format mirrors OpenFOAM's solvers: "Time = 0.5" blocks and
** "ExecutionTime = 0.05 s  ClockTime = 0 s", ending with "End".
**
** Start-up repairs what an interrupted run left in the case (a grid moved
** aside, temporary directories of dead processes) before anything reads
** it, and says so on stderr: the library (io_recover_dir) only reports.
**
** This is the application frame (app/, doc/architecture.md): it prints
** and exits, the library below it (common/) never does.  A usage error
** exits with ERR_EXIT (errout.h), -help and -version with 0.
*/
#ifndef KIESEL_ARGS_H
#define KIESEL_ARGS_H

#include <stdio.h>

#include "case.h"
#include "dict.h"
#include "errout.h"

#define KIESEL_VERSION "0.1.0"

typedef struct ArgOpt {
    const char *name;  /* "-o" */
    const char *arg;   /* argument name ("FILE"), or NULL for a flag */
    const char *help;
} ArgOpt;

typedef struct ArgDict {
    const char *path;       /* "system/blockGridDict" */
    const DictKey *keys;    /* top-level keywords */
    const char *note;       /* optional extra help text (sub-dictionaries...) */
} ArgDict;

typedef struct ToolInfo {
    const char *name;       /* "blockGrid" */
    const char *summary;    /* one line */
    const ArgOpt *opts;     /* tool options, ends with {0} */
    const ArgDict *dicts;   /* dictionaries read, ends with {0} */
    int times;              /* accepts -time/-latestTime/-noZero */
} ToolInfo;

typedef struct Args {
    const char *case_dir;   /* "." by default */
    const char *time_spec;  /* -time or NULL */
    int latest, nozero;
    const char *dict;       /* -dict or NULL */
    int nset;               /* tool options: values in order of opts */
    const char *val[32];    /* value of each tool option (flag: "1"), NULL if absent */
    int argc;               /* remaining positional arguments */
    char **argv;
    FILE *info;             /* stdout, or stderr when data goes to stdout */
    double wall0;           /* wall clock at args_parse, for ClockTime */
} Args;

/* Parses argv; handles -help and -version (prints and exits 0); exits 1
   with a usage message on a bad option.  Then ignores SIGXFSZ (an
   over-size write fails with EFBIG instead) and recovers
   <case>/constant/polyMesh (args_recover). */
void args_parse(int argc, char **argv, const ToolInfo *t, Args *a);
/* Runs io_recover_dir on dir ("-" is skipped) and prints each action on
   stderr as "tool: recovery: path: what", so it lands in log.<tool>; a
   failed recovery is reported there too and the tool goes on. */
void args_recover(const ToolInfo *t, const char *dir);
/* Frees what args_parse allocated. */
void args_free(Args *a);
/* Value of tool option name, or NULL. */
const char *args_get(const Args *a, const ToolInfo *t, const char *name);
/* Sends the banner and progress to stderr from now on. */
void args_info_to_stderr(Args *a);
/* Prints the banner (tool, version, case, date, host, pid). */
void args_banner(const Args *a, const ToolInfo *t);
/* Path of the tool's dictionary: the -dict file, else "<case>/<rel>"
   (caller frees).  With optional, NULL when there is no -dict and
   neither <rel> nor <rel>.gz exists (the tool keeps its defaults). */
char *args_dict_path(const Args *a, const Case *c, const char *rel, int optional);

/* Log lines in OpenFOAM's format. */
void log_time(const Args *a, const char *time_name);  /* "Time = 0.5" */
void log_exec(const Args *a);   /* "ExecutionTime = 0.05 s  ClockTime = 0 s" */
void log_end(const Args *a);    /* "End" */
/* Seconds of wall clock since args_parse. */
double args_wall(const Args *a);

#endif
