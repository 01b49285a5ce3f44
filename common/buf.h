/*
** buf.h: growable byte buffer.
**
** Files Kiesel writes are assembled in a Buf and handed to io_write_atomic,
** which puts them on disk in one rename (big binary arrays skip the copy
** through io_write_atomic_v).  The buffer keeps
** a terminating NUL after the data (not counted in n) so text can be
** parsed in place.
*/
#ifndef KIESEL_BUF_H
#define KIESEL_BUF_H

#include <stddef.h>

typedef struct Buf {
    char *p;
    size_t n, cap;
} Buf;

void buf_init(Buf *b);
void buf_free(Buf *b);
void buf_clear(Buf *b);
void buf_reserve(Buf *b, size_t extra);
void buf_put(Buf *b, const void *data, size_t n);
void buf_puts(Buf *b, const char *s);
void buf_putc(Buf *b, char c);
void buf_printf(Buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
