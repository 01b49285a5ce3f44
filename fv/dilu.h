/*
** dilu.h: OpenFOAM's DILU preconditioner (and DIC, the same on a
** symmetric matrix) on an FvMatrix's own arrays.
**
** With A = L + D_A + U (strict lower part, diagonal, strict upper part),
** DILU is the incomplete factorisation that modifies the diagonal only:
**     M = (D + L) D^-1 (D + U),
**     D_i = a_ii - sum_{j < i} a_ij a_ji / D_j,
** so that M's diagonal is A's.  It keeps one double a row (the
** reciprocals 1/D_i) and applies the factors from A's own values, where
** an ILU(0) factor is a second copy of the matrix.  On a grid whose
** coupling graph has no triangles (block grids: the 5- and 7-point
** stencils) the two are the same factorisation; where interpolation
** stencils couple a cell's neighbours to each other ILU(0) also updates
** those off-diagonal entries, DILU does not.
**
** Only the owned rows and columns (0 .. nrows-1) enter: a halo column is
** dropped, which makes the preconditioner block Jacobi over the ranks of
** a distributed run, as OpenFOAM's processor boundaries do.
*/
#ifndef KIESEL_DILU_H
#define KIESEL_DILU_H

#include "fvmatrix.h"

typedef struct Dilu {
    int n;       /* rows of rd */
    double *rd;  /* 1 / D_i */
} Dilu;

/* Builds rd from M's current values (allocating it on the first call).
   Returns 0, or the row + 1 of the first zero or non-finite D_i. */
int dilu_build(Dilu *p, const FvMatrix *M);

/* w = M^-1 r, and w = M^-T r; w may be r. */
void dilu_apply(const Dilu *p, const FvMatrix *M, const double *r, double *w);
void dilu_apply_transpose(const Dilu *p, const FvMatrix *M, const double *r, double *w);

void dilu_free(Dilu *p);

#endif
