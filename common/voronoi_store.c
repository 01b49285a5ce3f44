/*
** voronoi_store.c: the cells as polygons of global points.
**
** Store: each cell's faces as polygons of global point numbers with their
** labels, cell after cell, the faces of a cell sorted by label, so the
** face of cell c towards seed l is found by binary search
** (voronoi_store_find) and the cell that stored a face likewise
** (voronoi_store_cell).  Rings (2-D): each cell's polygon as it came out of
** the clipper, turned into prisms only when the mesh is written.
*/
#include "voronoi_impl.h"

#include <stdlib.h>
#include <string.h>

void voronoi_store_free(Store *s)
{
    free(s->cell_off);
    free(s->lab);
    free(s->off);
    free(s->idx);
}

void voronoi_store_face(Store *s, int lab, const int *pts, int n, int rev)
{
    need(&s->lab, &s->lcap, (size_t)s->nf + 1, sizeof(int));
    need(&s->off, &s->ocap, (size_t)s->nf + 2, sizeof(int));
    need(&s->idx, &s->icap, (size_t)s->ni + (size_t)n, sizeof(int));
    if (s->nf == 0) s->off[0] = 0;
    for (int k = 0; k < n; k++) s->idx[s->ni + k] = rev ? pts[n - 1 - k] : pts[k];
    s->ni += n;
    s->lab[s->nf] = lab;
    s->off[++s->nf] = s->ni;
}

/* Sorts the last cell's faces (from face f0) by label; a cell has a few
   dozen faces, so insertion sort of an index permutation. */
void voronoi_store_sort_cell(Store *s, int f0, int **tmp, int *tcap)
{
    int nf = s->nf - f0, ni = s->ni - s->off[f0];
    need(tmp, tcap, (size_t)(3 * nf + ni + 1), sizeof(int));
    int *perm = *tmp, *lab = perm + nf, *off_old = lab + nf, *buf = off_old + nf + 1;
    int sorted = 1;
    for (int k = 0; k < nf; k++) {
        int l = s->lab[f0 + k], q = k;
        if (q > 0 && s->lab[f0 + k - 1] > l) sorted = 0;
        while (q > 0 && s->lab[f0 + perm[q - 1]] > l) {
            perm[q] = perm[q - 1];
            q--;
        }
        perm[q] = k;
    }
    if (sorted) return;
    int base = s->off[f0], o = 0;
    memcpy(buf, s->idx + base, sizeof(int) * (size_t)ni);
    for (int k = 0; k < nf; k++) lab[k] = s->lab[f0 + k];
    memcpy(off_old, s->off + f0, sizeof(int) * (size_t)(nf + 1));
    for (int k = 0; k < nf; k++) {
        int f = perm[k], a = off_old[f] - base, n = off_old[f + 1] - off_old[f];
        memcpy(s->idx + base + o, buf + a, sizeof(int) * (size_t)n);
        o += n;
        s->lab[f0 + k] = lab[f];
        s->off[f0 + k + 1] = base + o;
    }
}

/* Face of cell c (seed i) labelled lab, or -1 (binary search). */
int voronoi_store_find(const Store *s, int c, int lab)
{
    int lo = s->cell_off[c], hi = s->cell_off[c + 1] - 1;
    while (lo <= hi) {
        int m = (lo + hi) / 2;
        if (s->lab[m] == lab) return m;
        if (s->lab[m] < lab) lo = m + 1;
        else hi = m - 1;
    }
    return -1;
}

/* The cell that stored face f (binary search; only repairs need it). */
int voronoi_store_cell(const Store *s, int f)
{
    int lo = 0, hi = s->ncells - 1;
    while (lo < hi) {
        int m = (lo + hi + 1) / 2;
        if (s->cell_off[m] <= f) lo = m;
        else hi = m - 1;
    }
    return lo;
}

void voronoi_rings_free(Rings *r)
{
    free(r->off);
    free(r->gid);
    free(r->lab);
}
