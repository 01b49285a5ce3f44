/*
** stencil.c: sparse linear stencils (stencil.h).
**
** The open row is off[nrows] .. off[nrows+1]-1: off always has room for
** nrows + 2 entries, so adding to the open row and closing it never
** reallocate twice.  A pair row is an empty row like any other; only the
** readers (stencil_row) tell it apart, by the pairs being named.
*/
#include "stencil.h"

#include <stdlib.h>
#include <string.h>

#include "mem.h"

void stencil_init(Stencil *s)
{
    memset(s, 0, sizeof *s);
    mem_grow((void **)&s->off, &s->row_cap, 2, sizeof *s->off);
    s->off[0] = s->off[1] = 0;
}

void stencil_free(Stencil *s)
{
    free(s->off);
    free(s->src);
    free(s->w);
    memset(s, 0, sizeof *s);
}

void stencil_add(Stencil *s, int src, double w)
{
    int a = s->off[s->nrows], end = s->off[s->nrows + 1];
    for (int k = a; k < end; k++)
        if (s->src[k] == src) {
            s->w[k] += w;
            return;
        }
    size_t cap = s->cap;
    mem_grow((void **)&s->src, &s->cap, (size_t)end + 1, sizeof *s->src);
    if (s->cap != cap) s->w = mem_realloc(s->w, s->cap * sizeof *s->w);
    s->src[end] = src;
    s->w[end] = w;
    s->off[s->nrows + 1] = end + 1;
}

int stencil_end_row(Stencil *s)
{
    int r = s->nrows++;
    mem_grow((void **)&s->off, &s->row_cap, (size_t)s->nrows + 2, sizeof *s->off);
    s->off[s->nrows + 1] = s->off[s->nrows];
    return r;
}

void stencil_trim(Stencil *s)
{
    size_t n = (size_t)s->off[s->nrows + 1];
    s->row_cap = (size_t)s->nrows + 2;
    s->off = mem_realloc(s->off, s->row_cap * sizeof *s->off);
    s->cap = n + 1;
    s->src = mem_realloc(s->src, (n + 1) * sizeof *s->src);
    s->w = mem_realloc(s->w, (n + 1) * sizeof *s->w);
}

void stencil_pairs(Stencil *s, const int *a, const int *b, int n)
{
    s->pa = a;
    s->pb = b;
    s->npairs = n;
}

int stencil_pair_row(Stencil *s) { return stencil_end_row(s); }

double stencil_row_sum(const Stencil *s, int r)
{
    StencilRow row;
    stencil_row(s, r, &row);
    double v = 0;
    for (int k = 0; k < row.n; k++) v += row.w[k];
    return v;
}
