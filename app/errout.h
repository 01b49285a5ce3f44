/*
** errout.h: the application frame's side of Err (common/err.h): printing
** an error or a warning on stderr, and the exit status.
**
** The library fills an Err and returns; a tool's main decides.  Exit
** status: 0 on success, 1 on any error (input, output, usage), the same
** for every tool so that Allrun scripts can stop on the first failure.
** Messages go to stderr, prefixed by the tool's name, after stdout is
** flushed so that a log keeps the order in which things happened.
*/
#ifndef KIESEL_ERROUT_H
#define KIESEL_ERROUT_H

#include "err.h"

/* Exit status of a tool that stops on an error. */
#define ERR_EXIT 1

/* Prints e->msg and "<tool>: stopped." to stderr and exits with ERR_EXIT. */
void err_die(const Err *e)
#if defined(__GNUC__)
    __attribute__((noreturn))
#endif
    ;
/* printf-style fatal error: "tool: message" on stderr, exit ERR_EXIT. */
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
