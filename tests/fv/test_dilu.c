/*
** test_dilu.c: OpenFOAM's DILU preconditioner (fv/dilu.h) on its own.
**
** The matrix: a 2-D block grid's face couplings plus the diagonal
** neighbours of every cell (triangles in the coupling graph, as the
** interpolation stencils of cut cells make them) and one coupling with
** no transpose entry; values random (GSL), diagonally dominant,
** non-symmetric.  Checked against the definition M = (D + L) D^-1 (D + U):
**   - M's diagonal is A's (the property that defines DILU's D);
**   - dilu_apply inverts M: M (M^-1 r) = r to round-off, for M built
**     explicitly from D and A's strict parts;
**   - dilu_apply_transpose is its transpose: <M^-1 x, y> = <x, M^-T y>;
**   - on the face couplings alone (no triangles) DILU is ILU(0): D
**     equals the pivots of a dense Gaussian elimination restricted to
**     the pattern, computed here independently;
**   - a zero pivot is reported with its row.
*/
#include "dilu.h"
#include "fixture.h"
#include "fvmatrix.h"
#include "test.h"

#include <gsl/gsl_rng.h>

typedef struct Sys {
    Mesh m;
    FvMesh f;
    FvMatrix M;
    gsl_rng *rng;
} Sys;

/* nx x ny cells; diagonal neighbours when wide; random values from seed. */
static void sys_make(Sys *s, int nx, int ny, int wide, unsigned long seed)
{
    gsl_rng *rng = s->rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, seed);
    int n[3] = {nx, ny, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.1};
    fixture_block(&s->m, n, lo, hi, 2);
    Err e;
    if (fvmesh_init(&s->f, &s->m, &e)) {
        printf("fvmesh_init: %s\n", e.msg);
        exit(1);
    }
    FvPattern p;
    fvpattern_init(&p, &s->f);
    if (wide) {
        for (int c = 0; c < s->f.ncells; c++) {
            int i = c % nx, j = c / nx;
            if (i + 1 < nx && j + 1 < ny) {
                fvpattern_couple(&p, c, c + nx + 1);
                fvpattern_couple(&p, c + nx + 1, c);
            }
            if (i > 0 && j + 1 < ny) fvpattern_couple(&p, c + nx - 1, c);
        }
        fvpattern_couple(&p, 0, nx * ny - 1); /* no transpose entry */
    }
    fvmatrix_init(&s->M, &p);
    for (int r = 0; r < s->M.nrows; r++) {
        double sum = 0;
        for (int k = s->M.off[r]; k < s->M.off[r + 1]; k++)
            if (k != s->M.diag[r]) sum += fabs(s->M.val[k] = gsl_rng_uniform(rng) - 0.7);
        s->M.val[s->M.diag[r]] = sum * (1.05 + gsl_rng_uniform(rng));
    }
}

static void sys_free(Sys *s)
{
    gsl_rng_free(s->rng);
    fvmatrix_free(&s->M);
    fvmesh_free(&s->f);
    mesh_free(&s->m);
}

/* a_ij, 0 outside the pattern. */
static double entry(const FvMatrix *M, int i, int j)
{
    int k = fvmatrix_pos(M, i, j);
    return k < 0 ? 0 : M->val[k];
}

/* y = (D + L) D^-1 (D + U) x, from the definition. */
static void apply_m(const Dilu *p, const FvMatrix *M, const double *x, double *y)
{
    int n = M->nrows;
    double *t = malloc((size_t)n * sizeof *t);
    for (int i = 0; i < n; i++) {
        double s = x[i] / p->rd[i];
        for (int k = M->diag[i] + 1; k < M->off[i + 1]; k++) s += M->val[k] * x[M->col[k]];
        t[i] = s * p->rd[i];
    }
    for (int i = 0; i < n; i++) {
        double s = t[i] / p->rd[i];
        for (int k = M->off[i]; k < M->diag[i]; k++) s += M->val[k] * t[M->col[k]];
        y[i] = s;
    }
    free(t);
}

TEST(definition)
{
    Sys s;
    sys_make(&s, 9, 7, 1, 7);
    const FvMatrix *M = &s.M;
    int n = M->nrows;
    Dilu p = {0, NULL};
    EXPECT(dilu_build(&p, M) == 0, "a pivot failed");
    /* M_ii = D_i + sum_{j<i} a_ij a_ji / D_j = a_ii */
    double worst = 0;
    for (int i = 0; i < n; i++) {
        double m = 1 / p.rd[i];
        for (int k = M->off[i]; k < M->diag[i]; k++) m += M->val[k] * entry(M, M->col[k], i) * p.rd[M->col[k]];
        worst = fmax(worst, fabs(m - M->val[M->diag[i]]) / fabs(M->val[M->diag[i]]));
    }
    EXPECT(worst < 1e-14, "diag(M) differs from diag(A) by %.3e", worst);
    double *r = malloc((size_t)n * sizeof *r), *w = malloc((size_t)n * sizeof *w), *y = malloc((size_t)n * sizeof *y);
    double *v = malloc((size_t)n * sizeof *v);
    for (int i = 0; i < n; i++) r[i] = gsl_rng_uniform(s.rng) - 0.5, v[i] = gsl_rng_uniform(s.rng) - 0.5;
    dilu_apply(&p, M, r, w);
    apply_m(&p, M, w, y);
    double err = 0, rmax = 0;
    for (int i = 0; i < n; i++) err = fmax(err, fabs(y[i] - r[i])), rmax = fmax(rmax, fabs(r[i]));
    EXPECT(err < 1e-13 * rmax, "|M M^-1 r - r| = %.3e", err);
    /* in place gives the same bits */
    memcpy(y, r, (size_t)n * sizeof *y);
    dilu_apply(&p, M, y, y);
    EXPECT(memcmp(y, w, (size_t)n * sizeof *y) == 0, "dilu_apply in place differs");
    /* <M^-1 r, v> = <r, M^-T v> */
    dilu_apply_transpose(&p, M, v, y);
    double a = 0, b = 0, mag = 0;
    for (int i = 0; i < n; i++) a += w[i] * v[i], b += r[i] * y[i], mag += fabs(w[i] * v[i]);
    EXPECT(fabs(a - b) < 1e-13 * mag, "<M^-1 r, v> = %.17g, <r, M^-T v> = %.17g", a, b);
    memcpy(w, v, (size_t)n * sizeof *w);
    dilu_apply_transpose(&p, M, w, w);
    EXPECT(memcmp(w, y, (size_t)n * sizeof *y) == 0, "dilu_apply_transpose in place differs");
    printf("  9x7 with diagonal couplings: |diag M - diag A| %.1e, |M M^-1 r - r| %.1e, transpose %.1e\n", worst,
           err, fabs(a - b));
    free(r), free(w), free(y), free(v);
    dilu_free(&p);
    sys_free(&s);
}

/* ILU(0) by elimination on a dense copy, updating only the pattern's
   entries; its pivots are DILU's D where the graph has no triangles. */
TEST(ilu0_on_faces)
{
    Sys s;
    sys_make(&s, 6, 5, 0, 11);
    const FvMatrix *M = &s.M;
    int n = M->nrows;
    double *a = calloc((size_t)n * (size_t)n, sizeof *a);
    for (int i = 0; i < n; i++)
        for (int k = M->off[i]; k < M->off[i + 1]; k++) a[(size_t)i * n + M->col[k]] = M->val[k];
    for (int j = 0; j < n; j++)
        for (int i = j + 1; i < n; i++) {
            if (fvmatrix_pos(M, i, j) < 0) continue;
            double l = a[(size_t)i * n + j] /= a[(size_t)j * n + j];
            for (int k = j + 1; k < n; k++)
                if (fvmatrix_pos(M, i, k) >= 0) a[(size_t)i * n + k] -= l * a[(size_t)j * n + k];
        }
    Dilu p = {0, NULL};
    EXPECT(dilu_build(&p, M) == 0, "a pivot failed");
    double worst = 0;
    for (int i = 0; i < n; i++) worst = fmax(worst, fabs(1 / p.rd[i] - a[(size_t)i * n + i]) / fabs(a[(size_t)i * n + i]));
    EXPECT(worst < 1e-14, "DILU's D and ILU(0)'s pivots differ by %.3e", worst);
    free(a);
    dilu_free(&p);
    sys_free(&s);
}

TEST(zero_pivot)
{
    Sys s;
    sys_make(&s, 4, 4, 0, 3);
    Dilu p = {0, NULL};
    /* row 5's D is zero: its diagonal and its lower part are */
    for (int k = s.M.off[5]; k <= s.M.diag[5]; k++) s.M.val[k] = 0;
    EXPECT(dilu_build(&p, &s.M) == 6, "zero pivot at row 5 not reported");
    s.M.val[s.M.diag[5]] = NAN;
    EXPECT(dilu_build(&p, &s.M) == 6, "NaN pivot at row 5 not reported");
    dilu_free(&p);
    sys_free(&s);
}

int main(void)
{
    RUN(definition);
    RUN(ilu0_on_faces);
    RUN(zero_pivot);
    return test_summary();
}
