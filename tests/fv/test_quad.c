/*
** test_quad.c: cell integrals by the degree-2 tetrahedral rule (fv/quad.h).
**
**   block_exact     every cell of a 3 x 4 x 5 block grid: the integrals of
**                   1, x, y^2, x y + 3 y z and a quadratic in all three
**                   against the exact box integrals (1e-15 absolute);
**   moments         a ball cut from a block grid and merged (non-convex
**                   merged cells): the integral of 1 is the cell volume and
**                   that of x is V times the centroid, in every cell, to
**                   1e-13 relative;
**   inside_outside  a ball cut once with the flow inside and once outside
**                   on the same grid: the integrals of a quadratic over the
**                   two sides' cells add up to its integral over the box
**                   (1e-12 relative; measured 9e-16); the centroid rule
**                   misses by 3e-4, so the check tells the degree; the
**                   merged inside grid gives the same sum as the cut one.
*/
#include "fixture.h"
#include "quad.h"
#include "test.h"

#include <math.h>

static const char *const BALL_IN = "b { flow inside; shape sphere; centre (0.51 0.47 0.53); radius 0.33; }";
static const char *const BALL_OUT = "b { flow outside; shape sphere; centre (0.51 0.47 0.53); radius 0.33; }";

/* 1, x, y^2, x y + 3 y z, and q = x^2 - 2 x z + y z + 0.5 y - 3. */
static void poly(void *ctx, const double x[3], double *v)
{
    (void)ctx;
    v[0] = 1;
    v[1] = x[0];
    v[2] = x[1] * x[1];
    v[3] = x[0] * x[1] + 3 * x[1] * x[2];
    v[4] = x[0] * x[0] - 2 * x[0] * x[2] + x[1] * x[2] + 0.5 * x[1] - 3;
}

/* The same integrals over the box [a, b] exactly. */
static void poly_box(const double a[3], const double b[3], double *v)
{
    double I1[3], Ix[3], Ixx[3];
    for (int k = 0; k < 3; k++) {
        I1[k] = b[k] - a[k];
        Ix[k] = (b[k] * b[k] - a[k] * a[k]) / 2;
        Ixx[k] = (b[k] * b[k] * b[k] - a[k] * a[k] * a[k]) / 3;
    }
    v[0] = I1[0] * I1[1] * I1[2];
    v[1] = Ix[0] * I1[1] * I1[2];
    v[2] = I1[0] * Ixx[1] * I1[2];
    v[3] = Ix[0] * Ix[1] * I1[2] + 3 * I1[0] * Ix[1] * Ix[2];
    v[4] = Ixx[0] * I1[1] * I1[2] - 2 * Ix[0] * I1[1] * Ix[2] + I1[0] * Ix[1] * Ix[2] + 0.5 * I1[0] * Ix[1] * I1[2] -
           3 * v[0];
}

static void ready(Mesh *m)
{
    mesh_cell_faces(m);
    mesh_geometry(m);
}

TEST(block_exact)
{
    Mesh m;
    int n[3] = {3, 4, 5};
    double lo[3] = {0.1, -0.2, 0.3}, hi[3] = {1.3, 0.6, 0.8};
    fixture_block(&m, n, lo, hi, -1);
    ready(&m);
    double *out = mem_alloc(sizeof(double) * 5 * (size_t)m.ncells);
    quad_cells(&m, 5, poly, NULL, out);
    for (int c = 0; c < m.ncells && !test_failed_now; c++) {
        int ijk[3] = {c % n[0], c / n[0] % n[1], c / (n[0] * n[1])};
        double a[3], b[3], ex[5];
        for (int k = 0; k < 3; k++) {
            double h = (hi[k] - lo[k]) / n[k];
            a[k] = lo[k] + h * ijk[k];
            b[k] = a[k] + h;
        }
        poly_box(a, b, ex);
        for (int j = 0; j < 5; j++) NEAR(out[5 * c + j], ex[j], 1e-15);
    }
    free(out);
    mesh_free(&m);
}

TEST(moments)
{
    Mesh grid, m;
    int n[3] = {12, 12, 12};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&grid, n, lo, hi, -1);
    fixture_cut(&m, &grid, BALL_IN, 1, NULL);
    ready(&m);
    double *out = mem_alloc(sizeof(double) * 5 * (size_t)m.ncells);
    quad_cells(&m, 5, poly, NULL, out);
    for (int c = 0; c < m.ncells && !test_failed_now; c++) {
        double V = m.cell_vol[c];
        NEAR(out[5 * c] / V, 1, 1e-13);
        NEAR(out[5 * c + 1] / V, m.cell_centre[3 * c], 1e-13);
    }
    free(out);
    mesh_free(&m);
    mesh_free(&grid);
}

/* Sum of component 4 (q) over the cells of m; by the centroid rule too. */
static double q_sum(Mesh *m, double *centroid_rule)
{
    ready(m);
    double *out = mem_alloc(sizeof(double) * 5 * (size_t)m->ncells), s = 0, sc = 0, v[5];
    quad_cells(m, 5, poly, NULL, out);
    for (int c = 0; c < m->ncells; c++) {
        s += out[5 * c + 4];
        poly(NULL, m->cell_centre + 3 * c, v);
        sc += v[4] * m->cell_vol[c];
    }
    free(out);
    if (centroid_rule) *centroid_rule = sc;
    return s;
}

TEST(inside_outside)
{
    Mesh grid, in, out, merged;
    int n[3] = {10, 10, 10};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, ex[5];
    fixture_block(&grid, n, lo, hi, -1);
    fixture_cut(&in, &grid, BALL_IN, 0, NULL);
    fixture_cut(&out, &grid, BALL_OUT, 0, NULL);
    fixture_cut(&merged, &grid, BALL_IN, 1, NULL);
    poly_box(lo, hi, ex);
    double ci, co;
    double si = q_sum(&in, &ci), so = q_sum(&out, &co), sm = q_sum(&merged, NULL);
    NEAR((si + so) / ex[4], 1, 1e-12);
    EXPECT(fabs((ci + co) / ex[4] - 1) > 1e-7, "the centroid rule is as exact: %.3e",
           fabs((ci + co) / ex[4] - 1));
    NEAR(sm / si, 1, 1e-12);
    printf("  box integral of q %.15g: quad %.3e, centroid rule %.3e (relative errors)\n", ex[4],
           fabs((si + so) / ex[4] - 1), fabs((ci + co) / ex[4] - 1));
    mesh_free(&in);
    mesh_free(&out);
    mesh_free(&merged);
    mesh_free(&grid);
}

int main(void)
{
    RUN(block_exact);
    RUN(moments);
    RUN(inside_outside);
    return test_summary();
}
