/*
** linesample.c: samples along a segment (their placement) and the cell or
** linear interpolation of a field at them.
**
** Cell crossings (cells mode) are Cyrus-Beck clips of the segment
** a + t (b - a) against the face planes (Cf, Sf_out) of each candidate
** cell from the locator.  Only the sign of Sf differs between the two
** cells of a face, and negation is exact, so t at a shared face is the
** same number for both cells: the intervals tile [0, 1] without gap or
** overlap.  Overlaps arise only when the segment lies in a face plane
** (both cells accept it); a sweep in t order then keeps the lower
** numbered cell, so each part of the segment is counted once; and as
** face parameters computed from different cells' faces in one plane may
** differ in the last bit, a sliver shorter than 1e-9 of the cell size is
** added to the previous crossing rather than reported as a cell.
**
** The least-squares gradient solves (sum w d d^T) g = sum w d (f_n - f_c)
** over neighbours n (cell centres through internal faces, face centres
** with the boundary condition's values on boundary faces), w = 1/|d|^2.
** For f linear, f_n - f_c = g.d exactly, so the solution is g itself
** whatever the weights.
*/
#include "linesample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

static void set_alloc(SampleSet *s, int n, int cells)
{
    memset(s, 0, sizeof *s);
    size_t n3 = 3 * (size_t)(n > 0 ? n : 1);
    s->x = MEM_NEW(double, n3);
    s->dist = MEM_NEW(double, n);
    s->cell = MEM_NEW(int, n);
    if (cells) s->len = MEM_NEW(double, n);
}

void linesample_free(SampleSet *s)
{
    free(s->x);
    free(s->dist);
    free(s->len);
    free(s->cell);
    memset(s, 0, sizeof *s);
}

static double seg_len(const double a[3], const double b[3])
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

void linesample_uniform(const Locator *L, const double a[3], const double b[3], int npoints, SampleSet *s)
{
    if (npoints < 1) npoints = 1;
    set_alloc(s, npoints, 0);
    double len = seg_len(a, b);
    for (int i = 0; i < npoints; i++) {
        double t = npoints > 1 ? (double)i / (npoints - 1) : 0, x[3];
        for (int k = 0; k < 3; k++) x[k] = i == npoints - 1 && npoints > 1 ? b[k] : a[k] + t * (b[k] - a[k]);
        int c = locate_cell(L, x);
        if (c < 0) {
            s->nskipped++;
            continue;
        }
        memcpy(s->x + 3 * s->n, x, sizeof x);
        s->dist[s->n] = t * len;
        s->cell[s->n] = c;
        s->n++;
    }
}

typedef struct Crossing {
    double t0, t1;
    int cell;
} Crossing;

typedef struct CrossCtx {
    const Locator *L;
    const double *a, *b;
    Crossing *v;
    size_t n, cap;
} CrossCtx;

/* Parameter interval of the segment inside cell c; returns 0 if empty. */
static int clip_segment(const Locator *L, int c, const double a[3], const double b[3], double *t0,
                        double *t1)
{
    const Mesh *m = L->m;
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double lo = 0, hi = 1;
    for (int j = m->cell_off[c]; j < m->cell_off[c + 1]; j++) {
        int f = m->cell_faces[j];
        const double *Cf = m->face_centre + 3 * f;
        double n[3];
        for (int k = 0; k < 3; k++) n[k] = m->owner[f] == c ? m->face_area[3 * f + k] : -m->face_area[3 * f + k];
        double num = (Cf[0] - a[0]) * n[0] + (Cf[1] - a[1]) * n[1] + (Cf[2] - a[2]) * n[2];
        double den = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if (den == 0) {
            double an = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (num < -1e-12 * an * L->size[c]) return 0;
            continue;
        }
        if (den > 0) hi = fmin(hi, num / den);
        else lo = fmax(lo, num / den);
        if (lo >= hi) return 0;
    }
    *t0 = lo;
    *t1 = hi;
    return 1;
}

static void add_crossing(int c, void *ctx)
{
    CrossCtx *x = ctx;
    double t0, t1;
    if (!clip_segment(x->L, c, x->a, x->b, &t0, &t1)) return;
    mem_grow((void **)&x->v, &x->cap, x->n + 1, sizeof *x->v);
    x->v[x->n++] = (Crossing){t0, t1, c};
}

static int cmp_crossing(const void *p, const void *q)
{
    const Crossing *a = p, *b = q;
    if (a->t0 != b->t0) return a->t0 < b->t0 ? -1 : 1;
    return (a->cell > b->cell) - (a->cell < b->cell);
}

void linesample_cells(const Locator *L, const double a[3], const double b[3], SampleSet *s)
{
    CrossCtx x = {L, a, b, NULL, 0, 0};
    double len = seg_len(a, b);
    if (len > 0) locate_segment_cells(L, a, b, add_crossing, &x);
    if (x.n) qsort(x.v, x.n, sizeof *x.v, cmp_crossing);
    set_alloc(s, (int)x.n, 1);
    double covered = 0, inside = 0;
    for (size_t i = 0; i < x.n; i++) {
        double t0 = fmax(x.v[i].t0, covered), t1 = x.v[i].t1;
        if (t1 <= t0) continue;
        if (s->n > 0 && (t1 - t0) * len <= 1e-9 * L->size[x.v[i].cell]) {
            /* A round-off sliver past a shared face: belongs to the last
               crossing. */
            s->len[s->n - 1] += (t1 - t0) * len;
            inside += (t1 - t0) * len;
            covered = t1;
            continue;
        }
        double tm = 0.5 * (t0 + t1);
        for (int k = 0; k < 3; k++) s->x[3 * s->n + k] = a[k] + tm * (b[k] - a[k]);
        s->dist[s->n] = tm * len;
        s->len[s->n] = (t1 - t0) * len;
        s->cell[s->n] = x.v[i].cell;
        inside += s->len[s->n];
        s->n++;
        covered = t1;
    }
    s->outside = fmax(0, len - inside);
    free(x.v);
}

/* ---- gradients ---- */

/* Solves the symmetric system A g = r in the axes listed in ax (na of
   them); returns 0 when singular. */
static int solve_sym(const double A[3][3], const double *r, const int *ax, int na, double *g)
{
    double M[3][3], b[3], scale = 0;
    for (int i = 0; i < na; i++) {
        b[i] = r[ax[i]];
        for (int j = 0; j < na; j++) M[i][j] = A[ax[i]][ax[j]];
        scale = fmax(scale, fabs(M[i][i]));
    }
    if (!(scale > 0)) return 0;
    /* Gaussian elimination with partial pivoting (na <= 3). */
    for (int k = 0; k < na; k++) {
        int p = k;
        for (int i = k + 1; i < na; i++)
            if (fabs(M[i][k]) > fabs(M[p][k])) p = i;
        if (fabs(M[p][k]) <= 1e-12 * scale) return 0;
        if (p != k) {
            for (int j = 0; j < na; j++) {
                double t = M[k][j];
                M[k][j] = M[p][j];
                M[p][j] = t;
            }
            double t = b[k];
            b[k] = b[p];
            b[p] = t;
        }
        for (int i = k + 1; i < na; i++) {
            double l = M[i][k] / M[k][k];
            for (int j = k; j < na; j++) M[i][j] -= l * M[k][j];
            b[i] -= l * b[k];
        }
    }
    double x[3] = {0, 0, 0};
    for (int i = na - 1; i >= 0; i--) {
        double s = b[i];
        for (int j = i + 1; j < na; j++) s -= M[i][j] * x[j];
        x[i] = s / M[i][i];
    }
    for (int i = 0; i < 3; i++) g[i] = 0;
    for (int i = 0; i < na; i++) g[ax[i]] = x[i];
    return 1;
}

/* Boundary face values of every patch, indexed by face - ninternal. */
static double *boundary_values(const Field *f, const Mesh *m)
{
    size_t nb = (size_t)(m->nfaces - m->ninternal) * (size_t)f->width;
    double *bv = MEM_NEW(double, nb);
    for (int p = 0; p < m->npatches; p++) {
        if (m->patches[p].size <= 0) continue;
        field_patch_values(f, m, p, bv + (size_t)(m->patches[p].start - m->ninternal) * f->width);
    }
    return bv;
}

static char *empty_faces(const Mesh *m)
{
    char *e = MEM_NEW(char, m->nfaces - m->ninternal);
    for (int p = 0; p < m->npatches; p++) {
        if (!mesh_patch_is_empty(&m->patches[p])) continue;
        for (int i = 0; i < m->patches[p].size; i++) e[m->patches[p].start + i - m->ninternal] = 1;
    }
    return e;
}

void linesample_gradient(const Field *f, const Mesh *m, double *grad)
{
    int w = f->width, eax = mesh_empty_axis(m), ax[3], na = 0;
    for (int k = 0; k < 3; k++)
        if (k != eax) ax[na++] = k;
    double *bv = boundary_values(f, m);
    char *isempty = empty_faces(m);
    for (int c = 0; c < m->ncells; c++) {
        const double *Cc = m->cell_centre + 3 * c;
        double A[3][3] = {{0}}, r[3][3] = {{0}};   /* r[k][j]: component k */
        for (int j = m->cell_off[c]; j < m->cell_off[c + 1]; j++) {
            int fc = m->cell_faces[j];
            const double *xn, *vn;
            if (fc < m->ninternal) {
                int o = m->owner[fc] == c ? m->neighbour[fc] : m->owner[fc];
                xn = m->cell_centre + 3 * o;
                vn = f->v + (size_t)o * w;
            } else {
                if (isempty[fc - m->ninternal]) continue;
                xn = m->face_centre + 3 * fc;
                vn = bv + (size_t)(fc - m->ninternal) * w;
            }
            double d[3] = {xn[0] - Cc[0], xn[1] - Cc[1], xn[2] - Cc[2]};
            double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (!(d2 > 0)) continue;
            double wt = 1 / d2;
            for (int p = 0; p < 3; p++)
                for (int q = 0; q < 3; q++) A[p][q] += wt * d[p] * d[q];
            for (int k = 0; k < w; k++) {
                double df = vn[k] - f->v[(size_t)c * w + k];
                for (int p = 0; p < 3; p++) r[k][p] += wt * d[p] * df;
            }
        }
        for (int k = 0; k < w; k++) {
            double *g = grad + ((size_t)c * w + k) * 3;
            if (!solve_sym((const double(*)[3])A, r[k], ax, na, g)) g[0] = g[1] = g[2] = 0;
        }
    }
    free(isempty);
    free(bv);
}

void linesample_value(const Field *f, const Mesh *m, const double *grad, int c, const double x[3],
                  double *out)
{
    int w = f->width;
    const double *Cc = m->cell_centre + 3 * c;
    for (int k = 0; k < w; k++) {
        out[k] = f->v[(size_t)c * w + k];
        if (!grad) continue;
        const double *g = grad + ((size_t)c * w + k) * 3;
        out[k] += g[0] * (x[0] - Cc[0]) + g[1] * (x[1] - Cc[1]) + g[2] * (x[2] - Cc[2]);
    }
}
