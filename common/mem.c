/*
** mem.c: checked allocation.  See mem.h.
*/
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

/* The one exit below app/ (doc/architecture.md): callers never test for
   NULL.  The message goes out with write(2), which needs no memory. */
static void oom(size_t n)
{
    char msg[64];
    int k = snprintf(msg, sizeof msg, "out of memory (%zu bytes)\n", n);
    fflush(NULL);
    if (k > 0) {
        ssize_t w = write(STDERR_FILENO, msg, (size_t)k);
        (void)w; /* nothing left to report a failure to */
    }
    exit(1);
}

/* Big arrays (a mesh's points, faces, fields) are written once, front to
   back; on a fresh mapping of 4 KiB pages the page faults alone cost more
   than filling them (about 13 us each on the reference VM, see
   doc/performance.md), so blocks of 8 MiB or more ask for transparent huge
   pages.  The hint is harmless where unsupported, and the memory stays
   plain malloc'ed memory released by free(). */
static void *huge_hint(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
    const uintptr_t H = (uintptr_t)2 << 20;
    if (n >= 4 * H) {
        uintptr_t a = ((uintptr_t)p + H - 1) & ~(H - 1), b = ((uintptr_t)p + n) & ~(H - 1);
        if (b > a) madvise((void *)a, b - a, MADV_HUGEPAGE);
    }
#endif
    return p;
}

void *mem_alloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) oom(n);
    return huge_hint(p, n);
}

void *mem_calloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p) oom(count * size);
    return huge_hint(p, count * size);
}

void *mem_realloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q) oom(n);
    return huge_hint(q, n);
}

char *mem_strdup(const char *s) { return mem_strndup(s, strlen(s)); }

char *mem_strndup(const char *s, size_t n)
{
    char *d = mem_alloc(n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

void mem_grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return;
    size_t c = *cap ? *cap : 16;
    while (c < need) c += c / 2 + 16;
    *p = mem_realloc(*p, c * elem);
    *cap = c;
}
