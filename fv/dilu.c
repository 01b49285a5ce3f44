/*
** dilu.c: OpenFOAM's DILU on CSR rows (dilu.h).
**
** OpenFOAM loops over faces (owner < neighbour, upper and lower values of
** one face side by side); on CSR the same sums run over rows: the
** forward sweep takes row i's entries left of the diagonal, the backward
** sweep those right of it.  The factorisation needs a_ji beside each
** a_ij of the lower part, found by fvmatrix_pos (a binary search in row
** j: columns are sorted, rows short); an entry the pattern lacks is zero.
*/
#include "dilu.h"

#include <math.h>
#include <stdlib.h>

#include "mem.h"

int dilu_build(Dilu *p, const FvMatrix *M)
{
    if (!p->rd || p->n != M->nrows) {
        free(p->rd);
        p->n = M->nrows;
        p->rd = mem_alloc(((size_t)p->n + 1) * sizeof *p->rd);
    }
    for (int i = 0; i < M->nrows; i++) {
        double d = M->val[M->diag[i]];
        for (int k = M->off[i]; k < M->diag[i]; k++) {
            int j = M->col[k], t = fvmatrix_pos(M, j, i);
            if (t >= 0) d -= M->val[k] * M->val[t] * p->rd[j];
        }
        if (d == 0 || !isfinite(d)) return i + 1;
        p->rd[i] = 1 / d;
    }
    return 0;
}

/* (D + L) y = r, then (I + D^-1 U) w = y. */
void dilu_apply(const Dilu *p, const FvMatrix *M, const double *r, double *w)
{
    const int n = M->nrows, *off = M->off, *col = M->col, *dg = M->diag;
    const double *v = M->val, *rd = p->rd;
    for (int i = 0; i < n; i++) {
        double s = r[i];
        for (int k = off[i]; k < dg[i]; k++) s -= v[k] * w[col[k]];
        w[i] = s * rd[i];
    }
    for (int i = n - 1; i >= 0; i--) {
        double s = 0;
        for (int k = dg[i] + 1; k < off[i + 1]; k++)
            if (col[k] < n) s += v[k] * w[col[k]];
        w[i] -= rd[i] * s;
    }
}

/* M^T = (D + U^T) D^-1 (D + L^T): both sweeps scatter along the rows. */
void dilu_apply_transpose(const Dilu *p, const FvMatrix *M, const double *r, double *w)
{
    const int n = M->nrows, *off = M->off, *col = M->col, *dg = M->diag;
    const double *v = M->val, *rd = p->rd;
    if (w != r)
        for (int i = 0; i < n; i++) w[i] = r[i];
    for (int i = 0; i < n; i++) {
        w[i] *= rd[i];
        for (int k = dg[i] + 1; k < off[i + 1]; k++)
            if (col[k] < n) w[col[k]] -= v[k] * w[i];
    }
    for (int i = n - 1; i >= 0; i--)
        for (int k = off[i]; k < dg[i]; k++) w[col[k]] -= rd[col[k]] * v[k] * w[i];
}

void dilu_free(Dilu *p)
{
    free(p->rd);
    p->rd = NULL;
    p->n = 0;
}
