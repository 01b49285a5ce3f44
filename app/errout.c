/*
** errout.c: errors and warnings on stderr, exit status.  See errout.h.
*/
#include "errout.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

/* The program name is process-wide by nature (it names the process in
   its messages); it is the frame's one piece of global state and is
   written once at start-up. */
static const char *progname = "kiesel";

void err_progname(const char *name) { progname = name; }

void err_die(const Err *e)
{
    fflush(stdout);
    fprintf(stderr, "%s\n", e && e->msg[0] ? e->msg : "unknown error");
    fprintf(stderr, "%s: stopped.\n", progname);
    exit(ERR_EXIT);
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
    exit(ERR_EXIT);
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
