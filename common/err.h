/*
** err.h: error reports that travel up to the tool's main.
**
** Library functions never print and never exit: a function that can fail
** takes an Err* as its last argument, fills it with a message of the form
** "file:line: message" (or "file: message" when there is no line) and
** returns a failure value (-1 or NULL).  Only a tool's main decides to
** print the message and exit: err_die is the application frame's
** (app/errout.h), above this library.  This keeps every reader usable
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

#endif
