/*
** args.c: shared command line, banner and OpenFOAM-style log lines.
** See args.h.  A bad option or a missing case directory ends the tool
** here, before anything is read.
*/
#include "args.h"
#include "err.h"
#include "errout.h"
#include "io.h"
#include "mem.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

static double wall_now(void);

static void print_help(const ToolInfo *t)
{
    printf("Usage: %s [OPTIONS]\n\n%s\n\nOptions:\n", t->name, t->summary);
    printf("  %-22s %s\n", "-case DIR", "case directory (default: .)");
    if (t->times) {
        printf("  %-22s %s\n", "-time SPEC", "times to process: 0.1 | 0.1,0.5 | 0.1:0.5 | :0.5 | 0.2:");
        printf("  %-22s %s\n", "-latestTime", "process the latest time only");
        printf("  %-22s %s\n", "-noZero", "skip the 0 directory");
    }
    printf("  %-22s %s\n", "-dict FILE", "read this dictionary instead of the default");
    for (const ArgOpt *o = t->opts; o && o->name; o++) {
        char s[64];
        snprintf(s, sizeof s, "%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
        printf("  %-22s %s\n", s, o->help);
    }
    printf("  %-22s %s\n", "-help", "print this help and exit");
    printf("  %-22s %s\n", "-version", "print the version and exit");
    for (const ArgDict *d = t->dicts; d && d->path; d++) {
        printf("\nKeywords of %s (default in brackets; [required] has none):\n", d->path);
        for (const DictKey *k = d->keys; k && k->key; k++)
            printf("  %-22s %-14s %s\n", k->key, k->def ? k->def : "[required]", k->help);
        if (d->note) printf("%s\n", d->note);
    }
}

static int opt_index(const ToolInfo *t, const char *name)
{
    int i = 0;
    for (const ArgOpt *o = t->opts; o && o->name; o++, i++)
        if (!strcmp(o->name, name)) return i;
    return -1;
}

static void usage_error(const ToolInfo *t, const char *fmt, const char *what)
{
    fprintf(stderr, "%s: ", t->name);
    fprintf(stderr, fmt, what);
    fprintf(stderr, "\nTry '%s -help'.\n", t->name);
    exit(ERR_EXIT);
}

void args_parse(int argc, char **argv, const ToolInfo *t, Args *a)
{
    memset(a, 0, sizeof *a);
    a->case_dir = ".";
    a->info = stdout;
    a->wall0 = wall_now();
    err_progname(t->name);
    char **pos = mem_alloc(sizeof(char *) * (size_t)(argc + 1));
    int npos = 0;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (s[0] != '-' || !strcmp(s, "-")) {
            pos[npos++] = argv[i];
            continue;
        }
        if (s[1] == '-' && s[2]) s++; /* accept --help as -help */
        if (!strcmp(s, "-help") || !strcmp(s, "-h")) {
            print_help(t);
            exit(0);
        }
        if (!strcmp(s, "-version")) {
            printf("%s (Kiesel) %s\n", t->name, KIESEL_VERSION);
            exit(0);
        }
        int k = opt_index(t, s);
        int takes = k >= 0 ? t->opts[k].arg != NULL
                           : (!strcmp(s, "-case") || !strcmp(s, "-dict") || (t->times && !strcmp(s, "-time")));
        if (k < 0 && strcmp(s, "-case") && strcmp(s, "-dict") &&
            !(t->times && (!strcmp(s, "-time") || !strcmp(s, "-latestTime") || !strcmp(s, "-noZero"))))
            usage_error(t, "unknown option '%s'", argv[i]);
        if (takes && !next) usage_error(t, "option '%s' needs an argument", argv[i]);
        if (takes) i++;
        if (k >= 0) a->val[k] = takes ? next : "1";
        else if (!strcmp(s, "-case")) a->case_dir = next;
        else if (!strcmp(s, "-dict")) a->dict = next;
        else if (!strcmp(s, "-time")) a->time_spec = next;
        else if (!strcmp(s, "-latestTime")) a->latest = 1;
        else if (!strcmp(s, "-noZero")) a->nozero = 1;
    }
    pos[npos] = NULL;
    a->argc = npos;
    a->argv = pos;
    if (!io_is_dir(a->case_dir)) {
        fprintf(stderr, "%s: case directory '%s' does not exist\n", t->name, a->case_dir);
        exit(ERR_EXIT);
    }
    /* a file that outgrows ulimit -f must fail with EFBIG (reported, old
       file kept), not kill the tool with SIGXFSZ halfway through */
    signal(SIGXFSZ, SIG_IGN);
    char *mesh = io_join(a->case_dir, "constant/polyMesh");
    args_recover(t, mesh);
    free(mesh);
}

void args_recover(const ToolInfo *t, const char *dir)
{
    if (!strcmp(dir, "-")) return;
    Buf report;
    buf_init(&report);
    Err e;
    int n = io_recover_dir(dir, &report, &e);
    for (char *line = report.p, *nl; line && (nl = strchr(line, '\n')); line = nl + 1)
        fprintf(stderr, "%s: recovery: %.*s\n", t->name, (int)(nl - line), line);
    if (n < 0) fprintf(stderr, "%s: recovery failed: %s\n", t->name, e.msg);
    fflush(stderr);
    buf_free(&report);
}

void args_free(Args *a)
{
    free(a->argv);
    a->argv = NULL;
    a->argc = 0;
}

const char *args_get(const Args *a, const ToolInfo *t, const char *name)
{
    int k = opt_index(t, name);
    return k >= 0 ? a->val[k] : NULL;
}

void args_info_to_stderr(Args *a) { a->info = stderr; }

void args_banner(const Args *a, const ToolInfo *t)
{
    char host[256] = "unknown", date[64] = "";
    gethostname(host, sizeof host - 1);
    time_t now = time(NULL);
    strftime(date, sizeof date, "%b %d %Y %H:%M:%S", localtime(&now));
    char cwd[4096] = ".";
    if (!getcwd(cwd, sizeof cwd)) strcpy(cwd, ".");
    FILE *f = a->info;
    fprintf(f, "/*---------------------------------------------------------------------------*\\\n");
    fprintf(f, "  Kiesel %-8s | %s: %s\n", KIESEL_VERSION, t->name, t->summary);
    fprintf(f, "\\*---------------------------------------------------------------------------*/\n");
    fprintf(f, "Date     : %s\nHost     : %s\nPID      : %ld\nCase     : %s%s%s\n", date, host,
            (long)getpid(), a->case_dir[0] == '/' ? "" : cwd, a->case_dir[0] == '/' ? "" : "/",
            a->case_dir);
    fprintf(f, "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n");
    fflush(f);
}

char *args_dict_path(const Args *a, const Case *c, const char *rel, int optional)
{
    if (a->dict) return mem_strdup(a->dict);
    char *path = case_path(c, rel);
    if (optional && !io_exists(path) && !io_exists_gz(path)) {
        free(path);
        return NULL;
    }
    return path;
}

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double args_wall(const Args *a) { return wall_now() - a->wall0; }

void log_time(const Args *a, const char *time_name)
{
    fprintf(a->info, "Time = %s\n\n", time_name);
    fflush(a->info);
}

void log_exec(const Args *a)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    double cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
                 (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    fprintf(a->info, "ExecutionTime = %.2f s  ClockTime = %.0f s\n\n", cpu, args_wall(a));
    fflush(a->info);
}

void log_end(const Args *a)
{
    fprintf(a->info, "End\n\n");
    fflush(a->info);
}
