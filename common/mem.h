/*
** mem.h: allocation that cannot return NULL.
**
** Running out of memory is not an input error the caller can repair, so
** these functions print "out of memory (N bytes)" and exit.  Everything
** else in the library allocates through them.
*/
#ifndef KIESEL_MEM_H
#define KIESEL_MEM_H

#include <stddef.h>

void *mem_alloc(size_t n);
void *mem_calloc(size_t count, size_t size);
void *mem_realloc(void *p, size_t n);
char *mem_strdup(const char *s);
char *mem_strndup(const char *s, size_t n);
/* Grows *p (of *cap elements of size elem) so it holds at least need. */
void mem_grow(void **p, size_t *cap, size_t need, size_t elem);

#define MEM_NEW(T, n) ((T *)mem_calloc((size_t)(n) > 0 ? (size_t)(n) : 1, sizeof(T)))

#endif
