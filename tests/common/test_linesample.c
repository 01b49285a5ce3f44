/*
** test_linesample.c: point location (locate.c) and line sampling
** (linesample.c).
**
** Grids come from block_mesh with graded spacing; a point's expected
** cell follows from the axis coordinates (cart.x), cells being numbered
** i + nx*(j + ny*k).
*/
#include "fixture.h"
#include "test.h"

#include "block.h"
#include "field.h"
#include "locate.h"
#include "mem.h"
#include "mesh.h"
#include "linesample.h"

/* Graded coordinates: x_i = lo + (hi-lo) s^p with p per axis. */
static void make_grid(Mesh *m, const int n[3], const double lo[3], const double hi[3])
{
    double *x[3];
    const double p[3] = {1.3, 0.8, 1.5};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = lo[k] + (hi[k] - lo[k]) * pow((double)i / n[k], p[k]);
        x[k][n[k]] = hi[k];
    }
    fixture_mesh(m, x, n);
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* Index along axis k of the cell holding coordinate v; on a grid line
   the lower cell (lowest cell number). */
static int axis_cell(const Mesh *m, int k, double v)
{
    int n = m->cart.n[k];
    for (int i = 0; i < n; i++)
        if (v <= m->cart.x[k][i + 1]) return i;
    return -1;
}

static int expected_cell(const Mesh *m, const double x[3])
{
    int i = axis_cell(m, 0, x[0]), j = axis_cell(m, 1, x[1]), k = axis_cell(m, 2, x[2]);
    if (x[0] < m->cart.x[0][0] || x[1] < m->cart.x[1][0] || x[2] < m->cart.x[2][0]) return -1;
    if (i < 0 || j < 0 || k < 0) return -1;
    return i + m->cart.n[0] * (j + m->cart.n[1] * k);
}

static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffffff) / (double)0x1000000;
}

TEST(locate_points)
{
    Mesh m;
    make_grid(&m, (int[]){7, 5, 6}, (double[]){0, 0, 0}, (double[]){1, 2, 1});
    Locator L;
    locate_build(&L, &m);
    unsigned s = 7;
    int wrong = 0;
    for (int t = 0; t < 2000; t++) {
        double x[3] = {rnd(&s), 2 * rnd(&s), rnd(&s)};
        if (locate_cell(&L, x) != expected_cell(&m, x)) wrong++;
    }
    EXPECT(wrong == 0, "%d of 2000 random points in the wrong cell", wrong);
    /* Points on faces, edges and corners: the lowest numbered cell. */
    wrong = 0;
    for (int i = 0; i <= 7; i++)
        for (int j = 0; j <= 5; j++)
            for (int k = 0; k <= 6; k += 3) {
                double x[3] = {m.cart.x[0][i], m.cart.x[1][j], m.cart.x[2][k]};
                int got = locate_cell(&L, x), want = expected_cell(&m, x);
                if (got != want) {
                    if (!wrong) printf("  grid point %d %d %d: cell %d, expected %d\n", i, j, k, got, want);
                    wrong++;
                }
            }
    EXPECT(wrong == 0, "%d grid points in the wrong cell", wrong);
    double face[3] = {m.cart.x[0][3], 0.5 * (m.cart.x[1][2] + m.cart.x[1][3]), 0.5};
    EXPECT(locate_cell(&L, face) == expected_cell(&m, face), "point on an x face");
    EXPECT(locate_cell(&L, (double[]){1.0000001, 1, 0.5}) == -1, "outside +x");
    EXPECT(locate_cell(&L, (double[]){0.5, -1e-7, 0.5}) == -1, "outside -y");
    EXPECT(locate_cell(&L, (double[]){0.5, 1, 7}) == -1, "far outside");
    locate_free(&L);
    mesh_free(&m);
}

TEST(cells_mode_lengths)
{
    Mesh m;
    make_grid(&m, (int[]){9, 7, 8}, (double[]){0, 0, 0}, (double[]){1, 1, 1});
    Locator L;
    locate_build(&L, &m);
    double a[3] = {0.01, 0.02, 0.03}, b[3] = {0.97, 0.88, 0.91};
    double len = sqrt(0.96 * 0.96 + 0.86 * 0.86 + 0.88 * 0.88);
    SampleSet s;
    linesample_cells(&L, a, b, &s);
    double sum = 0;
    int bad = 0;
    for (int i = 0; i < s.n; i++) {
        sum += s.len[i];
        if (expected_cell(&m, s.x + 3 * i) != s.cell[i]) bad++;
        if (i && !(s.dist[i] > s.dist[i - 1])) bad++;
    }
    printf("  diagonal: %d cells crossed, sum of lengths - length = %.2e\n", s.n, sum - len);
    NEAR(sum, len, 1e-12);
    EXPECT(bad == 0, "%d samples in the wrong cell or out of order", bad);
    /* One more cell for each grid plane the line crosses. */
    int planes = 0;
    for (int k = 0; k < 3; k++)
        for (int i = 1; i < m.cart.n[k]; i++) planes += m.cart.x[k][i] > a[k] && m.cart.x[k][i] < b[k];
    EXPECT(s.n == planes + 1, "%d cells crossed, expected %d", s.n, planes + 1);
    linesample_free(&s);

    /* A line lying in a grid plane (y on a grid line): each cell once. */
    double y = m.cart.x[1][3];
    double a2[3] = {0, y, m.cart.x[2][2]}, b2[3] = {1, y, m.cart.x[2][2]};
    linesample_cells(&L, a2, b2, &s);
    sum = 0;
    for (int i = 0; i < s.n; i++) sum += s.len[i];
    EXPECT(s.n == 9, "%d crossings along a grid edge, expected 9", s.n);
    NEAR(sum, 1.0, 1e-12);
    linesample_free(&s);

    /* Half outside: the inside part only. */
    double a3[3] = {-1, 0.5, 0.5}, b3[3] = {0.6, 0.5, 0.5};
    linesample_cells(&L, a3, b3, &s);
    sum = 0;
    for (int i = 0; i < s.n; i++) sum += s.len[i];
    NEAR(sum, 0.6, 1e-12);
    NEAR(s.outside, 1.0, 1e-12);
    linesample_free(&s);
    locate_free(&L);
    mesh_free(&m);
}

TEST(uniform_mode)
{
    Mesh m;
    make_grid(&m, (int[]){5, 5, 5}, (double[]){0, 0, 0}, (double[]){1, 1, 1});
    Locator L;
    locate_build(&L, &m);
    SampleSet s;
    linesample_uniform(&L, (double[]){-0.5, 0.3, 0.3}, (double[]){1, 0.3, 0.3}, 16, &s);
    /* x = -0.5 + 0.1 i: i = 0..4 outside, 5 (x = 0) on the boundary. */
    EXPECT(s.n == 11 && s.nskipped == 5, "kept %d, skipped %d", s.n, s.nskipped);
    NEAR(s.dist[0], 0.5, 1e-12);
    NEAR(s.x[0], 0, 1e-12);
    linesample_free(&s);
    locate_free(&L);
    mesh_free(&m);
}

static double lin(const double x[3], int k) { return 1 + k + (2 - k) * x[0] - 3 * x[1] + (0.5 + k) * x[2]; }

TEST(linear_exact)
{
    Mesh m;
    make_grid(&m, (int[]){6, 5, 7}, (double[]){-0.5, 0, 0.2}, (double[]){1, 0.7, 1.3});
    double zero[3] = {0, 0, 0};
    Field fs, fv;
    field_init(&fs, &m, "T", 1, zero, "calculated");
    field_init(&fv, &m, "U", 3, zero, "calculated");
    for (int c = 0; c < m.ncells; c++) {
        fs.v[c] = lin(m.cell_centre + 3 * c, 0);
        for (int k = 0; k < 3; k++) fv.v[3 * c + k] = lin(m.cell_centre + 3 * c, k);
    }
    for (int p = 0; p < m.npatches; p++)
        for (int i = 0; i < m.patches[p].size; i++) {
            const double *Cf = m.face_centre + 3 * (m.patches[p].start + i);
            fs.pf[p].value[i] = lin(Cf, 0);
            for (int k = 0; k < 3; k++) fv.pf[p].value[3 * i + k] = lin(Cf, k);
        }
    size_t n3 = 3 * (size_t)m.ncells, n9 = 3 * n3;
    double *gs = MEM_NEW(double, n3), *gv = MEM_NEW(double, n9);
    linesample_gradient(&fs, &m, gs);
    linesample_gradient(&fv, &m, gv);
    Locator L;
    locate_build(&L, &m);
    unsigned s = 3;
    double worst = 0;
    for (int t = 0; t < 500; t++) {
        double x[3] = {-0.5 + 1.5 * rnd(&s), 0.7 * rnd(&s), 0.2 + 1.1 * rnd(&s)};
        int c = locate_cell(&L, x);
        double v, u[3];
        linesample_value(&fs, &m, gs, c, x, &v);
        linesample_value(&fv, &m, gv, c, x, u);
        worst = fmax(worst, fabs(v - lin(x, 0)));
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(u[k] - lin(x, k)));
    }
    printf("  linear field, 500 points: max error %.2e\n", worst);
    EXPECT(worst < 1e-12, "max error %.3e", worst);
    /* Cell interpolation returns the cell value. */
    double v;
    linesample_value(&fs, &m, NULL, 17, (double[]){0, 0, 0}, &v);
    NEAR(v, fs.v[17], 0);
    free(gs);
    free(gv);
    field_free(&fs);
    field_free(&fv);
    locate_free(&L);
    mesh_free(&m);
}

int main(void)
{
    RUN(locate_points);
    RUN(cells_mode_lengths);
    RUN(uniform_mode);
    RUN(linear_exact);
    return test_summary();
}
