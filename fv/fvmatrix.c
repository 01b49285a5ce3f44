/*
** fvmatrix.c: the fixed sparsity pattern and values of an implicit system
** (fvmatrix.h).
**
** The pattern is built in two passes: every row's candidate columns
** (itself, its face neighbours, the extra couplings) are written into a
** scratch CSR with duplicates, then each row is sorted and its duplicates
** dropped while it is copied into the final arrays.  Both passes are
** linear in the entries but for the per-row sort, whose rows are short
** (7 in 3-D on a block grid, a few tens with interpolation stencils).
** Invariants after fvmatrix_init: off[0] = 0, col strictly ascending in
** each row, every row holds its diagonal.
*/
#include "fvmatrix.h"

#include <stdlib.h>
#include <string.h>

#include "mem.h"

void fvpattern_init(FvPattern *p, const FvMesh *f)
{
    memset(p, 0, sizeof *p);
    p->f = f;
}

void fvpattern_free(FvPattern *p)
{
    free(p->row);
    free(p->col);
    memset(p, 0, sizeof *p);
}

void fvpattern_couple(FvPattern *p, int row, int col)
{
    size_t cap = p->cap;
    mem_grow((void **)&p->row, &p->cap, p->n + 1, sizeof *p->row);
    if (p->cap != cap) p->col = mem_realloc(p->col, p->cap * sizeof *p->col);
    p->row[p->n] = row;
    p->col[p->n] = col;
    p->n++;
}

void fvpattern_couple_stencil(FvPattern *p, int row, const Stencil *s, int r)
{
    const FvMesh *f = p->f;
    StencilRow sr;
    stencil_row(s, r, &sr);
    for (int k = 0; k < sr.n; k++) {
        int q = sr.src[k];
        fvpattern_couple(p, row, q < f->ncells ? q : f->m->owner[f->ninternal + q - f->ncells]);
    }
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Candidate columns with duplicates: cnt[r+1] counts, then cand in CSR. */
static int *candidates(const FvPattern *p, int nrows, int *start)
{
    const FvMesh *f = p->f;
    const int *own = f->m->owner, *nei = f->m->neighbour;
    for (int r = 0; r <= nrows; r++) start[r] = r < nrows;
    for (int i = 0; i < f->ninternal; i++) {
        if (own[i] < nrows) start[own[i]]++;
        if (nei[i] < nrows) start[nei[i]]++;
    }
    for (size_t k = 0; k < p->n; k++)
        if (p->row[k] >= 0 && p->row[k] < nrows) start[p->row[k]]++;
    int total = 0;
    for (int r = 0; r <= nrows; r++) {
        int c = start[r];
        start[r] = total;
        total += c;
    }
    int *fill = mem_alloc(((size_t)nrows + 1) * sizeof *fill);
    memcpy(fill, start, ((size_t)nrows + 1) * sizeof *fill);
    int *cand = mem_alloc(((size_t)total + 1) * sizeof *cand);
    for (int r = 0; r < nrows; r++) cand[fill[r]++] = r;
    for (int i = 0; i < f->ninternal; i++) {
        if (own[i] < nrows) cand[fill[own[i]]++] = nei[i];
        if (nei[i] < nrows) cand[fill[nei[i]]++] = own[i];
    }
    for (size_t k = 0; k < p->n; k++)
        if (p->row[k] >= 0 && p->row[k] < nrows) cand[fill[p->row[k]]++] = p->col[k];
    free(fill);
    return cand;
}

/* Sorts each row of the candidates and keeps one of each column, in
   place (a row's unique columns never overtake its candidates); col is
   then the candidates cut to the unique ones (the candidates hold every
   face and stencil coupling with its repeats, about 3x nnz on a block
   grid). */
static void compress(FvMatrix *M, int *cand, const int *start)
{
    M->off = mem_alloc(((size_t)M->nrows + 1) * sizeof *M->off);
    int n = 0;
    for (int r = 0; r < M->nrows; r++) {
        int *c = cand + start[r], len = start[r + 1] - start[r];
        qsort(c, (size_t)len, sizeof *c, cmp_int);
        M->off[r] = n;
        for (int k = 0; k < len; k++)
            if (k == 0 || c[k] != c[k - 1]) cand[n++] = c[k];
    }
    M->off[M->nrows] = M->nnz = n;
    M->col = mem_realloc(cand, ((size_t)n + 1) * sizeof *M->col);
}

static void face_positions(FvMatrix *M, const FvMesh *f)
{
    const int *own = f->m->owner, *nei = f->m->neighbour;
    M->face_pos = mem_alloc(2 * ((size_t)f->ninternal + 1) * sizeof *M->face_pos);
    for (int i = 0; i < f->ninternal; i++) {
        M->face_pos[2 * i] = own[i] < M->nrows ? fvmatrix_pos(M, own[i], nei[i]) : -1;
        M->face_pos[2 * i + 1] = nei[i] < M->nrows ? fvmatrix_pos(M, nei[i], own[i]) : -1;
    }
}

void fvmatrix_init(FvMatrix *M, FvPattern *p)
{
    const FvMesh *f = p->f;
    memset(M, 0, sizeof *M);
    M->nrows = f->nowned;
    M->ncols = f->ncells;
    int *start = mem_alloc(((size_t)M->nrows + 1) * sizeof *start);
    compress(M, candidates(p, M->nrows, start), start);
    free(start);
    M->diag = mem_alloc(((size_t)M->nrows + 1) * sizeof *M->diag);
    for (int r = 0; r < M->nrows; r++) M->diag[r] = fvmatrix_pos(M, r, r);
    face_positions(M, f);
    M->val = mem_calloc((size_t)M->nnz + 1, sizeof *M->val);
    M->rhs = mem_calloc((size_t)M->nrows + 1, sizeof *M->rhs);
    fvpattern_free(p);
}

void fvmatrix_free(FvMatrix *M)
{
    free(M->off);
    free(M->col);
    free(M->diag);
    free(M->face_pos);
    free(M->val);
    free(M->rhs);
    memset(M, 0, sizeof *M);
}

void fvmatrix_zero(FvMatrix *M)
{
    fvmatrix_zero_values(M);
    fvmatrix_zero_rhs(M);
}

void fvmatrix_zero_values(FvMatrix *M)
{
    memset(M->val, 0, (size_t)M->nnz * sizeof *M->val);
    M->state++;
}

void fvmatrix_zero_rhs(FvMatrix *M) { memset(M->rhs, 0, (size_t)M->nrows * sizeof *M->rhs); }

int fvmatrix_pos(const FvMatrix *M, int row, int col)
{
    if (row < 0 || row >= M->nrows) return -1;
    int lo = M->off[row], hi = M->off[row + 1] - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (M->col[mid] == col) return mid;
        if (M->col[mid] < col) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

int fvmatrix_stencil_pos(const FvMatrix *M, int row, const Stencil *s, int r, int *pos)
{
    int missing = 0;
    StencilRow sr;
    stencil_row(s, r, &sr);
    for (int j = 0; j < sr.n; j++) {
        int q = sr.src[j];
        pos[j] = q < M->ncols ? fvmatrix_pos(M, row, q) : -1;
        missing += q < M->ncols && pos[j] < 0;
    }
    return missing;
}

void fvmatrix_add_stencil(FvMatrix *M, const int *pos, const Stencil *s, int r, double a)
{
    StencilRow sr;
    stencil_row(s, r, &sr);
    for (int k = 0; k < sr.n; k++)
        if (pos[k] >= 0) M->val[pos[k]] += a * sr.w[k];
}

void fvmatrix_mult(const FvMatrix *M, const double *x, double *y)
{
    for (int r = 0; r < M->nrows; r++) {
        double v = 0;
        for (int k = M->off[r]; k < M->off[r + 1]; k++) v += M->val[k] * x[M->col[k]];
        y[r] = v;
    }
}
