/*
** err.c: formatting of error messages.  See err.h for the contract.
*/
#include "err.h"

#include <stdio.h>
#include <stdlib.h>

/* The program name is process-wide by nature (it names the process in
   its messages); it is the one piece of global state in the library and
   is written once at start-up. */
static const char *progname = "kiesel";

void err_progname(const char *name) { progname = name; }

int err_setv(Err *e, const char *file, int line, const char *fmt, va_list ap)
{
    if (!e) return -1;
    int n = 0;
    if (file && line > 0)
        n = snprintf(e->msg, sizeof e->msg, "%s:%d: ", file, line);
    else if (file)
        n = snprintf(e->msg, sizeof e->msg, "%s: ", file);
    if (n < 0 || (size_t)n >= sizeof e->msg) n = 0;
    vsnprintf(e->msg + n, sizeof e->msg - (size_t)n, fmt, ap);
    return -1;
}

int err_set(Err *e, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    err_setv(e, file, line, fmt, ap);
    va_end(ap);
    return -1;
}

void err_die(const Err *e)
{
    fflush(stdout);
    fprintf(stderr, "%s\n", e && e->msg[0] ? e->msg : "unknown error");
    fprintf(stderr, "%s: stopped.\n", progname);
    exit(1);
}

void err_fatal(const char *fmt, ...)
{
    va_list ap;
    fflush(stdout);
    fprintf(stderr, "%s: ", progname);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    exit(1);
}

void err_warn(const char *fmt, ...)
{
    va_list ap;
    fflush(stdout);
    fprintf(stderr, "Warning: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}
