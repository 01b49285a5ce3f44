/*
** runtime.c: system/controlDict, time directories, uniform/time, -time.
** See runtime.h.
**
** controlDict is parsed into a scratch Control and copied over the
** caller's only when the whole file is valid, so runtime_reread can keep
** a run going on its old settings when a user saves a typo mid-run.  The
** modification time is remembered even when the re-read fails, so the
** error is reported once per edit rather than at every time step.
** Keywords and defaults are OpenFOAM's (Time::readDict); unknown keywords
** are errors with a suggestion, because a misspelt endTime silently
** falling back to a default is the worst kind of input error.
**
** This is the one controlDict reader of every tool (through case_open,
** common/case.h).  A solver needs endTime and deltaT; the grid and
** set-up tools read only the output format, so for them the two take
** defaults, as OpenFOAM's utilities run on a controlDict without them.
** writeFormat is ascii | binary; writeCompression is any of OpenFOAM's
** Switch words (on/off, yes/no, true/false, y/n, t/f, none) or
** compressed/uncompressed (IOstreamOption::compressionEnum).  As in
** OpenFOAM v1912 ("Disabled binary format compression
** (inefficient/ineffective)"), writeCompression is switched off for
** binary files: grids and fields alike (case_mesh_format,
** case_field_format).
**
** Time names are OpenFOAM's Time::timeName: the C++ stream formats
** general/fixed/scientific with timePrecision digits are printf's %g/%f/%e.
** A directory is a time directory when its whole name reads as a finite
** decimal number (so "0.orig", "constant" and "1e-05x" are not).
**
** uniform/time holds the time value with 18 significant digits (OpenFOAM's
** maxPrecision = 3 - log10(SMALL)), enough to restore the double exactly.
*/
#include "runtime.h"

#include "buf.h"
#include "foam.h"
#include "io.h"
#include "mem.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* OpenFOAM's GREAT: the default maxDeltaT. */
#define RUNTIME_GREAT 1e15

const DictKey runtime_control_keys[] = {
    {"application", "(none)", "solver the case was set up for (read by scripts; not used)"},
    {"startFrom", "startTime", "firstTime | startTime | latestTime"},
    {"startTime", "0", "time to start from when startFrom is startTime"},
    {"stopAt", "endTime", "endTime | writeNow | noWriteNow | nextWrite"},
    {"endTime", NULL, "time at which the run ends"},
    {"deltaT", NULL, "time step (the first one when adjustTimeStep is on)"},
    {"writeControl", "timeStep", "timeStep | runTime | adjustableRunTime | cpuTime | clockTime"},
    {"writeInterval", "1", "time steps (timeStep) or seconds between writes"},
    {"purgeWrite", "0", "keep only the last N written time directories (0 keeps all)"},
    {"writeVTK", "yes", "solvers: also write the legacy VTK files writeVTK would (VTK/, .vtk.series) at each write time"},
    {"writeFormat", "ascii", "ascii | binary"},
    {"writePrecision", "6", "significant digits of numbers in ascii files"},
    {"writeCompression", "off", "on | off (also compressed | uncompressed): gzip ascii files"},
    {"timeFormat", "general", "general | fixed | scientific: format of time directory names"},
    {"timePrecision", "6", "digits of time directory names"},
    {"runTimeModifiable", "true", "re-read controlDict when it changes during a run"},
    {"adjustTimeStep", "no", "adapt deltaT to keep the Courant number below maxCo"},
    {"maxCo", "1", "largest Courant number when adjustTimeStep is on"},
    {"maxDeltaT", "1e15", "largest time step when adjustTimeStep is on"},
    {"functions", "{}", "OpenFOAM function objects (ignored)"},
    {"libs", "()", "OpenFOAM libraries to load (ignored)"},
    {"graphFormat", "raw", "OpenFOAM's graph output format (ignored)"},
    {"DebugSwitches", "{}", "OpenFOAM debug switches (ignored)"},
    {"InfoSwitches", "{}", "OpenFOAM info switches (ignored)"},
    {"OptimisationSwitches", "{}", "OpenFOAM optimisation switches (ignored)"},
    {NULL, NULL, NULL}};

/* ---- controlDict ---- */

static int entry_line(const Dict *d, const char *key, const char **file)
{
    const DictEntry *en = dict_find(d, key);
    *file = en ? en->file : d->file;
    return en ? en->line : 0;
}

/* Fails unless v > lo (or >= lo when allow_equal). */
static int check_min(const Dict *d, const char *key, double v, double lo, int allow_equal, Err *e)
{
    if (v > lo || (allow_equal && v == lo)) return 0;
    const char *file;
    int line = entry_line(d, key, &file);
    return err_set(e, file, line, "%s must be %s %g, found %g", key, allow_equal ? "at least" : "greater than",
                   lo, v);
}

static int read_choice(const Dict *d, const char *key, const char *const *names, const int *values, int def,
                       int *out, Err *e)
{
    int i;
    if (dict_choice_or(d, key, names, def, &i, e)) return -1;
    *out = values[i];
    return 0;
}

static int read_compression(const Dict *d, int *out, Err *e)
{
    const DictEntry *en = dict_find(d, "writeCompression");
    const DictNode *nd = en && !en->dict && en->nvals == 1 ? en->vals[0] : NULL;
    if (nd && nd->kind == DN_WORD && strcmp(nd->text, "compressed") == 0) return *out = 1, 0;
    if (nd && nd->kind == DN_WORD && strcmp(nd->text, "uncompressed") == 0) return *out = 0, 0;
    return dict_switch_or(d, "writeCompression", 0, out, e);
}

/* endTime and deltaT: required when need_time, else defaults 0 and 1. */
static int read_times(Control *c, const Dict *d, int need_time, Err *e)
{
    if (need_time) return dict_scalar(d, "endTime", &c->endTime, e) || dict_scalar(d, "deltaT", &c->deltaT, e);
    return dict_scalar_or(d, "endTime", 0, &c->endTime, e) || dict_scalar_or(d, "deltaT", 1, &c->deltaT, e);
}

static int parse_control(Control *c, const Dict *d, int need_time, Err *e)
{
    static const char *const start_names[] = {"firstTime", "startTime", "latestTime", NULL};
    static const int start_vals[] = {START_FIRST, START_START, START_LATEST};
    static const char *const stop_names[] = {"endTime", "writeNow", "noWriteNow", "nextWrite", NULL};
    static const int stop_vals[] = {STOP_END, STOP_WRITENOW, STOP_NOWRITENOW, STOP_NEXTWRITE};
    static const char *const wc_names[] = {"timeStep", "runTime", "adjustableRunTime", "adjustable",
                                           "cpuTime", "clockTime", NULL};
    static const int wc_vals[] = {WRITE_TIMESTEP, WRITE_RUNTIME, WRITE_ADJUSTABLE,
                                  WRITE_ADJUSTABLE, WRITE_CPUTIME, WRITE_CLOCKTIME};
    static const char *const fmt_names[] = {"ascii", "binary", NULL};
    static const int fmt_vals[] = {0, 1};
    static const char *const tf_names[] = {"general", "fixed", "scientific", NULL};
    static const int tf_vals[] = {TIMEFMT_GENERAL, TIMEFMT_FIXED, TIMEFMT_SCIENTIFIC};

    if (dict_check_keys(d, runtime_control_keys, e)) return -1;
    if (read_choice(d, "startFrom", start_names, start_vals, 1, &c->startFrom, e) ||
        dict_scalar_or(d, "startTime", 0, &c->startTime, e) ||
        read_choice(d, "stopAt", stop_names, stop_vals, 0, &c->stopAt, e) ||
        read_times(c, d, need_time, e) ||
        read_choice(d, "writeControl", wc_names, wc_vals, 0, &c->writeControl, e) ||
        dict_scalar_or(d, "writeInterval", 1, &c->writeInterval, e) ||
        dict_label_or(d, "purgeWrite", 0, &c->purgeWrite, e) || dict_switch_or(d, "writeVTK", 1, &c->writeVTK, e) ||
        read_choice(d, "writeFormat", fmt_names, fmt_vals, 0, &c->writeBinary, e) ||
        dict_label_or(d, "writePrecision", 6, &c->writePrecision, e) || read_compression(d, &c->writeCompression, e) ||
        read_choice(d, "timeFormat", tf_names, tf_vals, 0, &c->timeFormat, e) ||
        dict_label_or(d, "timePrecision", 6, &c->timePrecision, e) ||
        dict_switch_or(d, "runTimeModifiable", 1, &c->runTimeModifiable, e) ||
        dict_switch_or(d, "adjustTimeStep", 0, &c->adjustTimeStep, e) ||
        dict_scalar_or(d, "maxCo", 1, &c->maxCo, e) ||
        dict_scalar_or(d, "maxDeltaT", RUNTIME_GREAT, &c->maxDeltaT, e))
        return -1;
    if (check_min(d, "deltaT", c->deltaT, 0, 0, e) || check_min(d, "writeInterval", c->writeInterval, 0, 0, e) ||
        check_min(d, "purgeWrite", c->purgeWrite, 0, 1, e) ||
        check_min(d, "writePrecision", c->writePrecision, 1, 1, e) ||
        check_min(d, "timePrecision", c->timePrecision, 1, 1, e) || check_min(d, "maxCo", c->maxCo, 0, 0, e) ||
        check_min(d, "maxDeltaT", c->maxDeltaT, 0, 0, e))
        return -1;
    /* %.Ng takes at most 17 useful digits; more only prints noise */
    if (c->writePrecision > 17) c->writePrecision = 17;
    if (c->timePrecision > 17) c->timePrecision = 17;
    if (c->writeBinary) c->writeCompression = 0;
    c->need_time = need_time;
    return 0;
}

/* Reads and parses path into c (path not set); fills mtime. */
static int load_control(Control *c, const char *path, int need_time, Err *e)
{
    struct stat st;
    if (stat(path, &st)) return err_set(e, path, 0, "cannot read controlDict: %s", strerror(errno));
    Dict *d = dict_read(path, e);
    if (!d) return -1;
    int rc = parse_control(c, d, need_time, e);
    dict_free(d);
    c->mtime = st.st_mtim.tv_sec;
    c->mtime_ns = st.st_mtim.tv_nsec;
    return rc;
}

int runtime_load_control(Control *c, const char *path, int need_time, Err *e)
{
    memset(c, 0, sizeof *c);
    Control t;
    memset(&t, 0, sizeof t);
    if (load_control(&t, path, need_time, e)) return -1;
    *c = t;
    c->path = mem_strdup(path);
    return 0;
}

int runtime_read_control(Control *c, const char *case_dir, Err *e)
{
    char *path = io_join(case_dir, "system/controlDict");
    int rc = runtime_load_control(c, path, 1, e);
    free(path);
    return rc;
}

int runtime_reread(Control *c, Err *e)
{
    if (!c->runTimeModifiable || !c->path) return 0;
    struct stat st;
    if (stat(c->path, &st))
        return err_set(e, c->path, 0, "cannot read controlDict: %s; keeping the old settings", strerror(errno));
    if (st.st_mtim.tv_sec == c->mtime && st.st_mtim.tv_nsec == c->mtime_ns) return 0;
    c->mtime = st.st_mtim.tv_sec;
    c->mtime_ns = st.st_mtim.tv_nsec;
    Control t;
    memset(&t, 0, sizeof t);
    if (load_control(&t, c->path, c->need_time, e)) return -1;
    t.path = c->path;
    *c = t;
    return 1;
}

void runtime_free_control(Control *c)
{
    free(c->path);
    memset(c, 0, sizeof *c);
}

/* ---- time names and directories ---- */

void runtime_time_name(const Control *c, double t, char *s)
{
    int p = c ? c->timePrecision : 6;
    int fmt = c ? c->timeFormat : TIMEFMT_GENERAL;
    if (t == 0) t = 0; /* "-0" is not a time name */
    if (fmt == TIMEFMT_FIXED)
        snprintf(s, 64, "%.*f", p, t);
    else if (fmt == TIMEFMT_SCIENTIFIC)
        snprintf(s, 64, "%.*e", p, t);
    else
        snprintf(s, 64, "%.*g", p, t);
}

/* A whole name that is a finite decimal number ("0", "0.1", "1e-05"). */
static int parse_time_name(const char *s, double *v)
{
    if (!*s || strspn(s, "0123456789.eE+-") != strlen(s)) return 0;
    char *end;
    *v = strtod(s, &end);
    return *end == '\0' && isfinite(*v);
}

static int cmp_time(const void *a, const void *b)
{
    const TimeDir *x = a, *y = b;
    if (x->value != y->value) return x->value < y->value ? -1 : 1;
    return strcmp(x->name, y->name);
}

int runtime_list_times(const char *case_dir, TimeDir **out, Err *e)
{
    char **names;
    int n = io_list_dir(case_dir, &names, e);
    *out = NULL;
    if (n < 0) return -1;
    TimeDir *t = MEM_NEW(TimeDir, n);
    int k = 0;
    for (int i = 0; i < n; i++) {
        double v;
        if (!parse_time_name(names[i], &v)) continue;
        char *p = io_join(case_dir, names[i]);
        int dir = io_is_dir(p);
        free(p);
        if (!dir) continue;
        t[k].value = v;
        t[k].name = mem_strdup(names[i]);
        k++;
    }
    io_free_list(names, n);
    if (k) qsort(t, (size_t)k, sizeof *t, cmp_time);
    *out = t;
    return k;
}

void runtime_free_times(TimeDir *t, int n)
{
    for (int i = 0; t && i < n; i++) free(t[i].name);
    free(t);
}

/* ---- -time selection ---- */

typedef struct Range {
    double lo, hi;
    int single;
} Range;

static int time_equal(double a, double b)
{
    return a == b || fabs(a - b) <= 1e-9 * fmax(fabs(a), fabs(b));
}

static int range_has(const Range *r, double t)
{
    if (r->single) return time_equal(t, r->lo);
    return (t >= r->lo || time_equal(t, r->lo)) && (t <= r->hi || time_equal(t, r->hi));
}

static int parse_bound(const char *s, size_t n, double *v)
{
    char tmp[64];
    if (n == 0 || n >= sizeof tmp) return -1;
    memcpy(tmp, s, n);
    tmp[n] = '\0';
    char *end;
    *v = strtod(tmp, &end);
    return *end == '\0' && isfinite(*v) ? 0 : -1;
}

/* One item "a", "a:b", ":b" or "a:". */
static int parse_range(const char *s, size_t n, const char *spec, Range *r, Err *e)
{
    const char *colon = memchr(s, ':', n);
    int bad = 0;
    if (!colon) {
        r->single = 1;
        bad = parse_bound(s, n, &r->lo);
        r->hi = r->lo;
    } else {
        size_t nl = (size_t)(colon - s), nh = n - nl - 1;
        r->single = 0;
        r->lo = -HUGE_VAL;
        r->hi = HUGE_VAL;
        if (memchr(colon + 1, ':', nh) || (nl == 0 && nh == 0)) bad = 1;
        if (!bad && nl) bad = parse_bound(s, nl, &r->lo);
        if (!bad && nh) bad = parse_bound(colon + 1, nh, &r->hi);
    }
    if (bad)
        return err_set(e, NULL, 0,
                       "-time '%s': '%.*s' is not a time or a range (0.1, 0.1:0.5, :0.5, 0.2:)", spec,
                       (int)n, s);
    return 0;
}

/* Items separated by commas or blanks; an empty item between commas is
   a mistake worth reporting ("0.1,,0.2"). */
static int parse_spec(const char *spec, Range **out, int *nr, Err *e)
{
    size_t cap = 0;
    Range *r = NULL;
    int n = 0;
    const char *s = spec;
    for (;;) {
        const char *comma = strchr(s, ',');
        const char *pend = comma ? comma : s + strlen(s);
        int items = 0;
        while (s < pend) {
            while (s < pend && (*s == ' ' || *s == '\t')) s++;
            const char *a = s;
            while (s < pend && *s != ' ' && *s != '\t') s++;
            if (s == a) continue;
            mem_grow((void **)&r, &cap, (size_t)n + 1, sizeof *r);
            if (parse_range(a, (size_t)(s - a), spec, &r[n], e)) {
                free(r);
                return -1;
            }
            n++;
            items++;
        }
        if (!items) {
            free(r);
            return err_set(e, NULL, 0, "-time '%s': empty item; expected a time or a range (0.1, 0.1:0.5, :0.5, 0.2:)",
                           spec);
        }
        if (!comma) break;
        s = comma + 1;
    }
    *out = r;
    *nr = n;
    return 0;
}

int runtime_select(TimeDir *t, int n, const char *spec, int latest, int nozero, Err *e)
{
    Range *r = NULL;
    int nr = 0;
    if (spec && parse_spec(spec, &r, &nr, e)) return -1;
    char *keep = MEM_NEW(char, n);
    for (int i = 0; i < n; i++) {
        keep[i] = !spec && !latest;
        for (int k = 0; k < nr && !keep[i]; k++) keep[i] = (char)range_has(&r[k], t[i].value);
    }
    if (latest && n > 0) keep[n - 1] = 1;
    if (nozero)
        for (int i = 0; i < n; i++)
            if (t[i].value == 0) keep[i] = 0;
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (keep[i]) {
            t[k++] = t[i];
        } else {
            free(t[i].name);
        }
    }
    for (int i = k; i < n; i++) t[i].name = NULL;
    free(keep);
    free(r);
    return k;
}

/* ---- uniform/time ---- */

int runtime_write_uniform_time(const char *case_dir, const char *name, double value, long index,
                               double deltaT, double deltaT0, Err *e)
{
    char *tdir = io_join(case_dir, name);
    char *udir = io_join(tdir, "uniform");
    char *path = io_join(udir, "time");
    size_t ll = strlen(name) + 16;
    char *loc = mem_alloc(ll);
    snprintf(loc, ll, "%s/uniform", name);
    int rc = io_mkdir_p(udir, e);
    if (rc == 0) {
        Buf b;
        buf_init(&b);
        foam_header(&b, "dictionary", loc, "time", 0, NULL);
        buf_printf(&b, "value           %.18g;\n\n", value);
        buf_printf(&b, "name            \"%s\";\n\n", name);
        buf_printf(&b, "index           %ld;\n\n", index);
        buf_puts(&b, "deltaT          ");
        foam_put_double(&b, deltaT, 0);
        buf_puts(&b, ";\n\ndeltaT0         ");
        foam_put_double(&b, deltaT0, 0);
        buf_puts(&b, ";\n\n");
        foam_footer(&b);
        rc = io_write_atomic(path, b.p, b.n, 0, e);
        buf_free(&b);
    }
    free(loc);
    free(path);
    free(udir);
    free(tdir);
    return rc;
}

long runtime_read_index(const char *case_dir, const char *name)
{
    char *tdir = io_join(case_dir, name);
    char *path = io_join(tdir, "uniform/time");
    Err e;
    Dict *d = io_exists_gz(path) ? dict_read(path, &e) : NULL;
    double v = 0;
    if (d && dict_scalar_or(d, "index", 0, &v, &e)) v = 0;
    if (d) dict_free(d);
    free(path);
    free(tdir);
    return (long)v;
}

/* ---- purgeWrite ---- */

int runtime_purge(const Control *c, const char *case_dir, Err *e)
{
    if (c->purgeWrite <= 0) return 0;
    TimeDir *t;
    int n = runtime_list_times(case_dir, &t, e);
    if (n < 0) return -1;
    /* Only directories after startTime are this run's; startTime's own
       directory holds the initial conditions and is never removed. */
    int first = 0;
    while (first < n && (t[first].value < c->startTime || time_equal(t[first].value, c->startTime))) first++;
    int rc = 0;
    for (int i = first; i < n - c->purgeWrite && rc == 0; i++) {
        char *p = io_join(case_dir, t[i].name);
        rc = io_rm_rf(p, e);
        free(p);
    }
    runtime_free_times(t, n);
    return rc;
}

/* ---- times to process ---- */

/* The list is selected on a copy, since runtime_select drops entries in
   place, and the positions of the kept names are looked up in the full
   list, which tools need for indices and series files. */
int runtime_select_case(TimeSel *s, const char *case_dir, const char *spec, int latest, int nozero, Err *e)
{
    memset(s, 0, sizeof *s);
    int n = runtime_list_times(case_dir, &s->all, e);
    if (n < 0) return -1;
    s->nall = n;
    TimeDir *pick = MEM_NEW(TimeDir, n);
    for (int i = 0; i < n; i++) pick[i] = (TimeDir){s->all[i].value, mem_strdup(s->all[i].name)};
    int k = runtime_select(pick, n, spec, latest, nozero, e);
    if (k >= 0) {
        s->sel = MEM_NEW(int, k);
        for (int i = 0; i < k; i++)
            for (int j = 0; j < n; j++)
                if (!strcmp(pick[i].name, s->all[j].name)) s->sel[i] = j;
        s->n = k;
    }
    runtime_free_times(pick, n);
    if (k < 0) runtime_free_sel(s);
    return k;
}

/* The start time as OpenFOAM's utilities take it by default: startFrom
   latestTime or firstTime, else the directory named like startTime (time 0
   without a controlDict). */
static int start_index(const Control *c, const TimeDir *t, int n, char name[64])
{
    strcpy(name, "0");
    if (c && c->startFrom == START_LATEST) return n - 1;
    if (c && c->startFrom == START_FIRST) return n ? 0 : -1;
    if (c) runtime_time_name(c, c->startTime, name);
    int pick = -1;
    for (int i = 0; i < n; i++)
        if (!strcmp(t[i].name, name)) pick = i;
    return pick;
}

int runtime_pick_times(TimeSel *s, const char *case_dir, const char *spec, int latest, int nozero, const Control *c,
                       Err *e)
{
    if (spec || latest || nozero) {
        int k = runtime_select_case(s, case_dir, spec, latest, nozero, e);
        if (k == 0) {
            runtime_free_sel(s);
            return err_set(e, case_dir, 0, "no time directory matches the selection");
        }
        return k;
    }
    memset(s, 0, sizeof *s);
    int n = runtime_list_times(case_dir, &s->all, e);
    if (n < 0) return -1;
    s->nall = n;
    char name[64];
    int pick = start_index(c, s->all, n, name);
    if (pick < 0) {
        runtime_free_sel(s);
        return err_set(e, case_dir, 0, "start time directory '%s' not found", name);
    }
    s->sel = MEM_NEW(int, 1);
    s->sel[0] = pick;
    s->n = 1;
    return 1;
}

const TimeDir *runtime_sel_time(const TimeSel *s, int i) { return &s->all[s->sel[i]]; }

void runtime_free_sel(TimeSel *s)
{
    runtime_free_times(s->all, s->nall);
    free(s->sel);
    memset(s, 0, sizeof *s);
}
