/*
** fvmatrix.h: the sparse matrix of an implicit system, in our own CSR
** arrays, with a sparsity pattern fixed once per grid (spec
** granular-model.md §4.3, eq. 4.66: one n_c x n_c system per implicit
** quantity, assembled anew every time step on the same pattern).
**
** Rows are the owned cells 0 .. nowned-1, columns all cells 0 .. ncells-1
** (halo cells after the owned ones).  The pattern of row C is the union of
**   - C itself (the diagonal, always present, so ILU/ICC find it),
**   - the cells across C's internal faces (the two-point part of every
**     face flux), and
**   - the cell sources of every Stencil row the caller names for C: the
**     interpolated (cu)^{m+1} at x_f +- n h_f puts an entry w_D/c^m on
**     every source cell D (spec §4.3; eq. 4.62-4.64), so the interpolation
**     stencils of C's faces widen C's row.  A boundary-face source puts
**     its face's owner in the pattern: the boundary condition decides
**     later whether it is a right-hand-side value (fixed value) or the
**     owner's unknown (zero gradient, slip).
** plus any single (row, column) a caller adds (a cyclic pair of faces).
** Columns are sorted and unique per row; diag[r] is the position of
** (r, r) and face_pos the positions of each internal face's two
** off-diagonal entries, so the assembly of a face flux adds by position
** without a search.  Other entries are found once (fvmatrix_pos, a binary
** search in the row, or fvmatrix_stencil_pos for a whole stencil row) and
** the positions kept by the caller for every later time step.
**
** Building: fvpattern_init, then fvpattern_couple / fvpattern_couple_stencil
** for the extra entries, then fvmatrix_init (which consumes the pattern).
** Per time step: fvmatrix_zero, then add to val[] and rhs[] by position.
** A system solved several times with the same values and new right-hand
** sides (the velocity components of eq. 4.66 without slip walls) zeroes
** and refills only the right-hand side (fvmatrix_zero_rhs) between the
** solves.  state counts the changes of the values (fvmatrix_zero and
** fvmatrix_zero_values bump it): a solver that follows it
** (linsolve_solve_tracked) rebuilds its preconditioner only when it moved.
**
** The arrays are the layout PETSc's MatCreateSeqAIJWithArrays takes
** (linsolve.h hands them over without copying), so off and col are int
** and the values double.
*/
#ifndef KIESEL_FVMATRIX_H
#define KIESEL_FVMATRIX_H

#include <stddef.h>

#include "fvmesh.h"
#include "stencil.h"

/* The extra couplings collected before the pattern is built. */
typedef struct FvPattern {
    const FvMesh *f;
    int *row, *col;  /* n pairs */
    size_t n, cap;
} FvPattern;

typedef struct FvMatrix {
    int nrows, ncols;  /* owned cells; all cells */
    int nnz;
    int *off;          /* nrows + 1: row r is off[r] .. off[r+1]-1 */
    int *col;          /* nnz, ascending and unique per row */
    int *diag;         /* nrows: position of (r, r) */
    int *face_pos;     /* 2 ninternal: [2i] is (owner, neighbour) of face i,
                          [2i+1] (neighbour, owner); -1 where that row is a
                          halo cell */
    double *val;       /* nnz */
    double *rhs;       /* nrows */
    unsigned long state;  /* bumped whenever val is zeroed for new values */
} FvMatrix;

void fvpattern_init(FvPattern *p, const FvMesh *f);
void fvpattern_free(FvPattern *p);
/* Adds column col (a cell, 0 .. ncells-1) to row row (an owned cell; a
   halo cell has no row, and its couplings are dropped). */
void fvpattern_couple(FvPattern *p, int row, int col);
/* Adds the sources of row r of s to row row: a cell source as itself, a
   boundary source ncells + b as the owner of face ninternal + b. */
void fvpattern_couple_stencil(FvPattern *p, int row, const Stencil *s, int r);

/* Builds the pattern (face neighbours and p's extra entries), with values
   and right-hand side zero; frees p. */
void fvmatrix_init(FvMatrix *M, FvPattern *p);
void fvmatrix_free(FvMatrix *M);

/* Zeroes the values and the right-hand side; the pattern stays. */
void fvmatrix_zero(FvMatrix *M);
/* Zeroes the values alone (state moves on), or the right-hand side alone. */
void fvmatrix_zero_values(FvMatrix *M);
void fvmatrix_zero_rhs(FvMatrix *M);

/* Position of (row, col), or -1 when it is not in the pattern. */
int fvmatrix_pos(const FvMatrix *M, int row, int col);

/* Positions, for row row, of the sources of row r of s: pos[j] for its
   entry j (stencil_row's order, a pair row's included); -1 for a
   boundary source (the boundary condition places it) or a cell the
   pattern lacks (the row was not named in fvpattern_couple_stencil).
   Returns the number of -1 entries for cell sources (0 when the pattern
   was built with this stencil row). */
int fvmatrix_stencil_pos(const FvMatrix *M, int row, const Stencil *s, int r, int *pos);

/* val[pos[j]] += a * w for each cell source of row r of s (j its index in
   the row, positions from fvmatrix_stencil_pos; boundary sources, pos -1,
   are the caller's). */
void fvmatrix_add_stencil(FvMatrix *M, const int *pos, const Stencil *s, int r, double a);

/* y = A x (x over ncols cells, y over nrows). */
void fvmatrix_mult(const FvMatrix *M, const double *x, double *y);

#endif
