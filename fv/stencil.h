/*
** stencil.h: sparse linear stencils: rows of weights over sources, the
** form every precomputed interpolation (spec granular-model.md §3, "PC:
** per-source weights can be precomputed") and every matrix row of the
** implicit terms take.
**
**   value(row r) = sum over k in off[r] .. off[r+1]-1 of  w[k] * x(src[k])
**
** Sources 0 .. ncells-1 are cells (their value at the node); a source
** ncells + b is boundary face ninternal + b (its boundary value, given by
** the field's boundary condition).  So a stencil that reaches a wall names
** the wall face, and the boundary condition decides later whether that is
** a fixed value (right-hand side) or, say, the owner's value (zero
** gradient: a matrix entry on the owner).
**
** Rows are appended in order (stencil_add, then stencil_end_row); the
** arrays grow as needed.
*/
#ifndef KIESEL_STENCIL_H
#define KIESEL_STENCIL_H

#include <stddef.h>

typedef struct Stencil {
    int nrows;
    int *off;          /* nrows + 1 */
    int *src;          /* off[nrows] entries */
    double *w;
    size_t cap, row_cap;
} Stencil;

void stencil_init(Stencil *s);
void stencil_free(Stencil *s);
/* Adds w x(src) to the row being built (a source already in the row has
   its weights summed). */
void stencil_add(Stencil *s, int src, double w);
/* Closes the row being built; returns its index. */
int stencil_end_row(Stencil *s);

/* Applies row r to cell values xc (ncells of them, stride 1) and boundary
   values xb (one per boundary face; NULL: a boundary source is an error
   the caller ruled out).  Inline: the solvers call it per face and
   component in their time loops. */
static inline double stencil_apply(const Stencil *s, int r, int ncells, const double *xc, const double *xb)
{
    double v = 0;
    for (int k = s->off[r]; k < s->off[r + 1]; k++) {
        int q = s->src[k];
        v += s->w[k] * (q < ncells ? xc[q] : xb[q - ncells]);
    }
    return v;
}

/* Sum of the weights of row r (1 for an interpolation exact on constants). */
double stencil_row_sum(const Stencil *s, int r);

#endif
