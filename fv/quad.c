/*
** quad.c: cell integrals by the degree-2 rule on the tetrahedra of
** geom_cell's decomposition (quad.h).
*/
#include "quad.h"

#include <stdlib.h>

#include "mem.h"

#define QUAD_ALPHA 0.58541019662496845446   /* (5 + 3 sqrt 5) / 20 */
#define QUAD_BETA 0.13819660112501051518    /* (5 - sqrt 5) / 20 */

/* Mean of the n points pts[idx[..]]. */
static void point_mean(const double *pts, const int *idx, int n, double m[3])
{
    m[0] = m[1] = m[2] = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) m[k] += pts[3 * (size_t)idx[i] + k];
    for (int k = 0; k < 3; k++) m[k] /= n;
}

/* Adds sgn times the integral over the tetrahedron (d, a, b, c) to acc;
   val is scratch of ncomp numbers. */
static void tet_add(const double d[3], const double a[3], const double b[3], const double c[3], double sgn,
                    int ncomp, QuadFn fn, void *ctx, double *val, double *acc)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = a[k] - d[k];
        v[k] = b[k] - d[k];
        w[k] = c[k] - d[k];
    }
    double vol = sgn * (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                        u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
    const double *vert[4] = {d, a, b, c};
    for (int p = 0; p < 4; p++) {
        double x[3];
        for (int k = 0; k < 3; k++) {
            double s = 0;
            for (int q = 0; q < 4; q++) s += (q == p ? QUAD_ALPHA : QUAD_BETA) * vert[q][k];
            x[k] = s;
        }
        fn(ctx, x, val);
        for (int j = 0; j < ncomp; j++) acc[j] += 0.25 * vol * val[j];
    }
}

/* The integral over cell c into acc (ncomp numbers). */
static void cell_integral(const Mesh *m, int c, int ncomp, QuadFn fn, void *ctx, double *val, double *acc)
{
    const int *cf = m->cell_faces + m->cell_off[c];
    int nf = m->cell_off[c + 1] - m->cell_off[c];
    double d[3] = {0, 0, 0};
    for (int q = 0; q < nf; q++)
        for (int k = 0; k < 3; k++) d[k] += m->face_centre[3 * (size_t)cf[q] + k] / nf;
    for (int j = 0; j < ncomp; j++) acc[j] = 0;
    for (int q = 0; q < nf; q++) {
        int f = cf[q], n = m->face_off[f + 1] - m->face_off[f];
        const int *fi = m->face_idx + m->face_off[f];
        double sgn = m->owner[f] == c ? 1.0 : -1.0;
        if (n < 3) continue;
        if (n == 3) {
            tet_add(d, m->points + 3 * (size_t)fi[0], m->points + 3 * (size_t)fi[1], m->points + 3 * (size_t)fi[2],
                    sgn, ncomp, fn, ctx, val, acc);
            continue;
        }
        double mid[3];
        point_mean(m->points, fi, n, mid);
        for (int i = 0; i < n; i++)
            tet_add(d, m->points + 3 * (size_t)fi[i], m->points + 3 * (size_t)fi[(i + 1) % n], mid, sgn, ncomp, fn,
                    ctx, val, acc);
    }
}

void quad_cells(const Mesh *m, int ncomp, QuadFn fn, void *ctx, double *out)
{
    double *val = mem_alloc(sizeof(double) * (size_t)ncomp);
    for (int c = 0; c < m->ncells; c++) cell_integral(m, c, ncomp, fn, ctx, val, out + (size_t)ncomp * c);
    free(val);
}
