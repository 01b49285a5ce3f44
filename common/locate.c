/*
** locate.c: bucket grid over cell bounding boxes and the face-plane test.
**
** Invariants: every cell is listed in each bucket its bounding box
** (padded by 1e-9 of its size) overlaps, in ascending cell order, so a
** point on a bucket boundary finds every cell that touches it and the
** first passing cell is the lowest numbered one.  The grid has about one
** bucket per cell (at most 8 per cell), sized from the mean cell volume,
** so a query tests O(1) cells on a grid of even cells.
*/
#include "locate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

#define LOCATE_TOL 1e-9     /* inside tolerance, fraction of the cell size */
#define LOCATE_LOOSE 1e-6   /* accepted violation when no cell passes */

static void cell_box(const Mesh *m, int c, double *bb)
{
    for (int k = 0; k < 3; k++) {
        bb[k] = INFINITY;
        bb[3 + k] = -INFINITY;
    }
    for (int j = m->cell_off[c]; j < m->cell_off[c + 1]; j++) {
        int f = m->cell_faces[j];
        for (int i = m->face_off[f]; i < m->face_off[f + 1]; i++) {
            const double *p = m->points + 3 * m->face_idx[i];
            for (int k = 0; k < 3; k++) {
                bb[k] = fmin(bb[k], p[k]);
                bb[3 + k] = fmax(bb[3 + k], p[k]);
            }
        }
    }
}

static int clampi(long v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : (int)v; }

/* Bucket index range [i0, i1] along axis k covering [a, b]. */
static void bucket_range(const Locator *L, int k, double a, double b, int *i0, int *i1)
{
    *i0 = clampi((long)floor((a - L->lo[k]) / L->h[k]), 0, L->n[k] - 1);
    *i1 = clampi((long)floor((b - L->lo[k]) / L->h[k]), 0, L->n[k] - 1);
}

static void grid_size(Locator *L, int ncells)
{
    double ext[3], vol = 1, big = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = L->hi[k] - L->lo[k];
        big = fmax(big, ext[k]);
    }
    for (int k = 0; k < 3; k++) {
        if (ext[k] < 1e-12 * big) ext[k] = 1e-12 * big;
        vol *= ext[k];
    }
    double s = cbrt(vol / (ncells > 0 ? ncells : 1));
    for (;;) {
        double total = 1;
        for (int k = 0; k < 3; k++) {
            double nk = ceil(ext[k] / s);
            L->n[k] = nk < 1 ? 1 : nk > 4096 ? 4096 : (int)nk;
            total *= L->n[k];
        }
        if (total <= 8.0 * (ncells > 0 ? ncells : 1) + 8) break;
        s *= 1.25;
    }
    for (int k = 0; k < 3; k++) L->h[k] = (L->hi[k] - L->lo[k]) / L->n[k];
    for (int k = 0; k < 3; k++)
        if (!(L->h[k] > 0)) L->h[k] = 1;
}

void locate_build(Locator *L, const Mesh *m)
{
    memset(L, 0, sizeof *L);
    L->m = m;
    int nc = m->ncells;
    size_t nbb = 6 * (size_t)nc;
    L->bb = MEM_NEW(double, nbb);
    L->size = MEM_NEW(double, nc);
    for (int k = 0; k < 3; k++) {
        L->lo[k] = INFINITY;
        L->hi[k] = -INFINITY;
    }
    for (int c = 0; c < nc; c++) {
        double *bb = L->bb + 6 * c;
        cell_box(m, c, bb);
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            d2 += (bb[3 + k] - bb[k]) * (bb[3 + k] - bb[k]);
            L->lo[k] = fmin(L->lo[k], bb[k]);
            L->hi[k] = fmax(L->hi[k], bb[3 + k]);
        }
        L->size[c] = sqrt(d2);
    }
    if (nc == 0)
        for (int k = 0; k < 3; k++) L->lo[k] = L->hi[k] = 0;
    grid_size(L, nc);
    size_t nb = (size_t)L->n[0] * L->n[1] * L->n[2];
    L->off = MEM_NEW(int, nb + 1);
    for (int pass = 0; pass < 2; pass++) {
        int *fill = pass ? MEM_NEW(int, nb) : NULL;
        for (int c = 0; c < nc; c++) {
            const double *bb = L->bb + 6 * c;
            double pad = LOCATE_TOL * L->size[c];
            int r[3][2];
            for (int k = 0; k < 3; k++) bucket_range(L, k, bb[k] - pad, bb[3 + k] + pad, &r[k][0], &r[k][1]);
            for (int z = r[2][0]; z <= r[2][1]; z++)
                for (int y = r[1][0]; y <= r[1][1]; y++)
                    for (int x = r[0][0]; x <= r[0][1]; x++) {
                        size_t b = (size_t)x + (size_t)L->n[0] * ((size_t)y + (size_t)L->n[1] * z);
                        if (pass) L->cells[L->off[b] + fill[b]++] = c;
                        else L->off[b + 1]++;
                    }
        }
        if (!pass) {
            for (size_t b = 0; b < nb; b++) L->off[b + 1] += L->off[b];
            L->cells = MEM_NEW(int, L->off[nb]);
        }
        free(fill);
    }
}

void locate_free(Locator *L)
{
    free(L->off);
    free(L->cells);
    free(L->bb);
    free(L->size);
    memset(L, 0, sizeof *L);
}

/* Largest (x - Cf).n_out over the faces of cell c, divided by the cell
   size: <= 0 inside a convex cell, > 0 outside. */
static double locate_violation(const Locator *L, int c, const double x[3])
{
    const Mesh *m = L->m;
    double worst = -INFINITY;
    for (int j = m->cell_off[c]; j < m->cell_off[c + 1]; j++) {
        int f = m->cell_faces[j];
        const double *S = m->face_area + 3 * f, *Cf = m->face_centre + 3 * f;
        double a = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
        if (!(a > 0)) continue;
        double s = ((x[0] - Cf[0]) * S[0] + (x[1] - Cf[1]) * S[1] + (x[2] - Cf[2]) * S[2]) / a;
        if (m->owner[f] != c) s = -s;
        worst = fmax(worst, s);
    }
    return worst / (L->size[c] > 0 ? L->size[c] : 1);
}

static int in_box(const double *bb, const double x[3], double pad)
{
    for (int k = 0; k < 3; k++)
        if (x[k] < bb[k] - pad || x[k] > bb[3 + k] + pad) return 0;
    return 1;
}

int locate_cell(const Locator *L, const double x[3])
{
    if (!L->off) return -1;
    for (int k = 0; k < 3; k++) {
        double pad = 1e-9 * (L->hi[k] - L->lo[k]) + 1e-300;
        if (!(x[k] >= L->lo[k] - pad && x[k] <= L->hi[k] + pad)) return -1;
    }
    int i[3];
    for (int k = 0; k < 3; k++) bucket_range(L, k, x[k], x[k], &i[k], &i[k]);
    size_t b = (size_t)i[0] + (size_t)L->n[0] * ((size_t)i[1] + (size_t)L->n[1] * i[2]);
    int best = -1;
    double bestv = INFINITY;
    for (int j = L->off[b]; j < L->off[b + 1]; j++) {
        int c = L->cells[j];
        if (!in_box(L->bb + 6 * c, x, LOCATE_TOL * L->size[c])) continue;
        double v = locate_violation(L, c, x);
        if (v <= LOCATE_TOL) return c;
        if (v < bestv) {
            bestv = v;
            best = c;
        }
    }
    return bestv <= LOCATE_LOOSE ? best : -1;
}

/* Does segment a + t(b - a), t in [0, 1], meet box bb (padded)? */
static int segment_meets_box(const double a[3], const double b[3], const double *lo, const double *hi,
                             double pad)
{
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; k++) {
        double d = b[k] - a[k], l = lo[k] - pad, h = hi[k] + pad;
        if (d == 0) {
            if (a[k] < l || a[k] > h) return 0;
            continue;
        }
        double s0 = (l - a[k]) / d, s1 = (h - a[k]) / d;
        if (s0 > s1) {
            double t = s0;
            s0 = s1;
            s1 = t;
        }
        t0 = fmax(t0, s0);
        t1 = fmin(t1, s1);
        if (t0 > t1) return 0;
    }
    return 1;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

void locate_segment_cells(const Locator *L, const double a[3], const double b[3],
                          void (*fn)(int cell, void *ctx), void *ctx)
{
    if (!L->off || L->m->ncells == 0) return;
    int r[3][2];
    for (int k = 0; k < 3; k++) bucket_range(L, k, fmin(a[k], b[k]), fmax(a[k], b[k]), &r[k][0], &r[k][1]);
    char *seen = MEM_NEW(char, L->m->ncells);
    int *list = NULL;
    size_t n = 0, cap = 0;
    for (int z = r[2][0]; z <= r[2][1]; z++)
        for (int y = r[1][0]; y <= r[1][1]; y++)
            for (int x = r[0][0]; x <= r[0][1]; x++) {
                double blo[3] = {L->lo[0] + x * L->h[0], L->lo[1] + y * L->h[1], L->lo[2] + z * L->h[2]};
                double bhi[3] = {blo[0] + L->h[0], blo[1] + L->h[1], blo[2] + L->h[2]};
                if (!segment_meets_box(a, b, blo, bhi, 1e-9 * (L->h[0] + L->h[1] + L->h[2]))) continue;
                size_t bk = (size_t)x + (size_t)L->n[0] * ((size_t)y + (size_t)L->n[1] * z);
                for (int j = L->off[bk]; j < L->off[bk + 1]; j++) {
                    int c = L->cells[j];
                    if (seen[c]) continue;
                    const double *bb = L->bb + 6 * c;
                    if (!segment_meets_box(a, b, bb, bb + 3, LOCATE_TOL * L->size[c])) continue;
                    seen[c] = 1;
                    mem_grow((void **)&list, &cap, n + 1, sizeof *list);
                    list[n++] = c;
                }
            }
    if (n) qsort(list, n, sizeof *list, cmp_int);
    for (size_t i = 0; i < n; i++) fn(list[i], ctx);
    free(list);
    free(seen);
}
