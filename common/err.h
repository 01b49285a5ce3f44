/*
** err.h: error reports that travel up to the tool's main.
**
** Library functions never print and never exit: a function that can fail
** takes an Err* as its last argument, fills it with a message of the form
** "file:line: message" (or "file: message" when there is no line) and
** returns a failure value (-1 or NULL).  Only a tool's main decides to
** print the message and exit (err_die).  This keeps every reader usable
** from the fuzz harness and from tests that assert on the exact message.
*/
#ifndef KIESEL_ERR_H
#define KIESEL_ERR_H

#include <stdarg.h>

#define ERR_MSG_MAX 2048

typedef struct Err {
    char msg[ERR_MSG_MAX];
} Err;

/* Sets e->msg to "file:line: <fmt>"; line <= 0 omits the line, file NULL
   omits the location.  e may be NULL (the message is dropped).  Returns -1
   so that "return err_set(...)" reads naturally. */
int err_set(Err *e, const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
int err_setv(Err *e, const char *file, int line, const char *fmt, va_list ap);

/* Prints e->msg to stderr (prefixed by the tool name if set via
   err_progname) and exits with status 1. */
void err_die(const Err *e)
#if defined(__GNUC__)
    __attribute__((noreturn))
#endif
    ;
/* printf-style fatal error: "tool: message" on stderr, exit 1. */
void err_fatal(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((noreturn, format(printf, 1, 2)))
#endif
    ;
/* Warning on stderr ("Warning: ..."), never exits. */
void err_warn(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* Name used as prefix by err_die/err_fatal; set once by args_parse. */
void err_progname(const char *name);

#endif
