/*
** err.c: formatting of error messages.  See err.h for the contract.
*/
#include "err.h"

#include <stdio.h>

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
