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
** Pair rows.  Most rows of the face stencils are trivial: on a face
** between two whole Cartesian cells (eq. 4.61) the three rows are the
** mean of the two cells, the neighbour alone and the owner alone.  Stored,
** they would cost four entries (48 bytes) a face, 150 bytes a cell of a
** 3-D block grid, for numbers the grid already holds.  So a stencil may
** name npairs pairs of sources (stencil_pairs: a[p], b[p], arrays the
** caller owns, such as a grid's owner and neighbour of its internal
** faces) with STENCIL_GROUP rows per pair, row r = STENCIL_GROUP p + j,
** and store such a row empty (stencil_pair_row): it then means
**   j = STENCIL_PAIR_MEAN   0.5 x(a[p]) + 0.5 x(b[p])
**   j = STENCIL_PAIR_B      x(b[p])
**   j = STENCIL_PAIR_A      x(a[p])
** with the entries in that order (a first), exactly as if they were
** stored, so every sum over a row is the same to the bit.  stencil_apply
** honours them; a reader that walks a row's entries takes them from
** stencil_row, which hands out the stored entries or makes the pair's.
** Any other empty row (no pairs named, or r beyond the pairs' rows) is a
** zero row.
**
** Rows are appended in order (stencil_add, then stencil_end_row); the
** arrays grow as needed.
*/
#ifndef KIESEL_STENCIL_H
#define KIESEL_STENCIL_H

#include <stddef.h>

enum { STENCIL_PAIR_MEAN, STENCIL_PAIR_B, STENCIL_PAIR_A, STENCIL_GROUP };

typedef struct Stencil {
    int nrows;
    int *off;          /* nrows + 1 */
    int *src;          /* off[nrows] entries */
    double *w;
    size_t cap, row_cap;
    const int *pa, *pb;  /* the pairs' sources (stencil_pairs), or NULL */
    int npairs;          /* rows 0 .. STENCIL_GROUP npairs - 1 may be pair rows */
} Stencil;

/* The entries of one row (stencil_row): n sources src[0 .. n-1] with
   weights w[...], pointing into the stencil or, for a pair row, into
   psrc and pw (so a StencilRow is filled in place, never copied). */
typedef struct StencilRow {
    int n;
    const int *src;
    const double *w;
    int psrc[2];
    double pw[2];
} StencilRow;

void stencil_init(Stencil *s);
void stencil_free(Stencil *s);
/* Adds w x(src) to the row being built (a source already in the row has
   its weights summed). */
void stencil_add(Stencil *s, int src, double w);
/* Closes the row being built; returns its index. */
int stencil_end_row(Stencil *s);

/* Gives back the room the arrays grew into beyond the rows built (rows
   may still be added later). */
void stencil_trim(Stencil *s);

/* Pair p (0 <= p < n) has sources a[p] and b[p] (the arrays must outlive s). */
void stencil_pairs(Stencil *s, const int *a, const int *b, int n);
/* Closes the row being built, which must be empty and row STENCIL_GROUP
   p + j of a pair, as that pair's row j; returns its index. */
int stencil_pair_row(Stencil *s);

/* Is row r a pair row (stored empty, a row of a pair)? */
static inline int stencil_is_pair(const Stencil *s, int r)
{
    return r < STENCIL_GROUP * s->npairs && s->off[r] == s->off[r + 1];
}

/* The entries of row r into *row. */
static inline void stencil_row(const Stencil *s, int r, StencilRow *row)
{
    int k = s->off[r];
    row->n = s->off[r + 1] - k;
    row->src = s->src + k;
    row->w = s->w + k;
    if (row->n || r >= STENCIL_GROUP * s->npairs) return;
    int p = r / STENCIL_GROUP, j = r - STENCIL_GROUP * p;
    if (j != STENCIL_PAIR_B) row->psrc[row->n] = s->pa[p], row->pw[row->n++] = j == STENCIL_PAIR_MEAN ? 0.5 : 1.0;
    if (j != STENCIL_PAIR_A) row->psrc[row->n] = s->pb[p], row->pw[row->n++] = j == STENCIL_PAIR_MEAN ? 0.5 : 1.0;
    row->src = row->psrc;
    row->w = row->pw;
}

/* Number of entries of row r (a pair row's 2 or 1). */
static inline int stencil_row_len(const Stencil *s, int r)
{
    int n = s->off[r + 1] - s->off[r];
    return n || r >= STENCIL_GROUP * s->npairs ? n : r % STENCIL_GROUP == STENCIL_PAIR_MEAN ? 2 : 1;
}

/* Applies row r to cell values xc (ncells of them, stride 1) and boundary
   values xb (one per boundary face; NULL: a boundary source is an error
   the caller ruled out).  Inline: the solvers call it per face and
   component in their time loops. */
static inline double stencil_apply(const Stencil *s, int r, int ncells, const double *xc, const double *xb)
{
    double v = 0;
    if (stencil_is_pair(s, r)) { /* the stored row's sum: 0, then a, then b */
        int p = r / STENCIL_GROUP, j = r - STENCIL_GROUP * p;
        double c = j == STENCIL_PAIR_MEAN ? 0.5 : 1.0;
        if (j != STENCIL_PAIR_B) v += c * xc[s->pa[p]];
        if (j != STENCIL_PAIR_A) v += c * xc[s->pb[p]];
        return v;
    }
    for (int k = s->off[r]; k < s->off[r + 1]; k++) {
        int q = s->src[k];
        v += s->w[k] * (q < ncells ? xc[q] : xb[q - ncells]);
    }
    return v;
}

/* Sum of the weights of row r (1 for an interpolation exact on constants). */
double stencil_row_sum(const Stencil *s, int r);

#endif
