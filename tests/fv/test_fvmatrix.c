/*
** test_fvmatrix.c: the fixed sparsity pattern of fv/fvmatrix.h: sorted
** unique columns, the diagonal found, symmetric for the face-neighbour
** pattern, one entry per distinct pair of neighbours (merged cells share
** several faces), the face positions, the extra sources of interpolation
** stencils (spec §4.3), on a block grid, a 2-D block grid and a cut and
** merged grid; the values (zeroing, adding a stencil row, the product);
** zeroing the values and the right-hand side apart, and the state that
** counts the changes of the values (what linsolve_solve_tracked follows).
*/
#include "cut.h"
#include "fixture.h"
#include "fvmatrix.h"
#include "merge.h"
#include "test.h"

#include <math.h>

/* Invariants of any pattern: errors counted, first described in why. */
static int check_sorted(const FvMatrix *M, char *why, size_t n)
{
    int bad = 0;
    for (int r = 0; r < M->nrows; r++) {
        for (int k = M->off[r] + 1; k < M->off[r + 1]; k++)
            if (M->col[k] <= M->col[k - 1] && !bad++) snprintf(why, n, "row %d not ascending at %d", r, k);
        if ((M->diag[r] < M->off[r] || M->diag[r] >= M->off[r + 1] || M->col[M->diag[r]] != r) && !bad++)
            snprintf(why, n, "row %d: diagonal position %d wrong", r, M->diag[r]);
    }
    return bad;
}

static int check_symmetric(const FvMatrix *M)
{
    int bad = 0;
    for (int r = 0; r < M->nrows; r++)
        for (int k = M->off[r]; k < M->off[r + 1]; k++) bad += fvmatrix_pos(M, M->col[k], r) < 0;
    return bad;
}

/* Face positions name the right entries; the number of distinct
   neighbour pairs, counted independently of the pattern. */
static int check_faces(const FvMatrix *M, const FvMesh *f, int *npairs)
{
    const int *own = f->m->owner, *nei = f->m->neighbour;
    int bad = 0;
    *npairs = 0;
    for (int i = 0; i < f->ninternal; i++) {
        int a = M->face_pos[2 * i], b = M->face_pos[2 * i + 1];
        bad += a < M->off[own[i]] || a >= M->off[own[i] + 1] || M->col[a] != nei[i];
        bad += b < M->off[nei[i]] || b >= M->off[nei[i] + 1] || M->col[b] != own[i];
        int first = 1;
        for (int j = 0; j < i && first; j++)
            first = !((own[j] == own[i] && nei[j] == nei[i]) || (own[j] == nei[i] && nei[j] == own[i]));
        *npairs += first;
    }
    return bad;
}

static void face_pattern(FvMatrix *M, const FvMesh *f)
{
    FvPattern p;
    fvpattern_init(&p, f);
    fvmatrix_init(M, &p);
}

TEST(block_pattern)
{
    Mesh m;
    int n[3] = {4, 5, 6};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    FvMatrix M;
    face_pattern(&M, &f);
    char why[200] = "";
    int npairs;
    EXPECT(check_sorted(&M, why, sizeof why) == 0, "%s", why);
    EXPECT(check_symmetric(&M) == 0, "pattern not symmetric");
    EXPECT(check_faces(&M, &f, &npairs) == 0, "face positions wrong");
    EXPECT(npairs == f.ninternal && M.nnz == f.ncells + 2 * f.ninternal, "nnz %d, cells %d, internal faces %d",
           M.nnz, f.ncells, f.ninternal);
    /* an interior cell (1,1,1) has 6 neighbours, a corner 3 */
    int c = 1 + 4 * (1 + 5 * 1);
    EXPECT(M.off[c + 1] - M.off[c] == 7 && M.off[1] - M.off[0] == 4, "row lengths %d and %d",
           M.off[c + 1] - M.off[c], M.off[1] - M.off[0]);
    EXPECT(fvmatrix_pos(&M, 0, 119) == -1 && fvmatrix_pos(&M, 0, 1) >= 0, "position of absent/present entries");
    fvmatrix_free(&M);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* 2-D: empty faces carry no flux and couple nothing: 5-point rows. */
TEST(two_d_pattern)
{
    Mesh m;
    int n[3] = {6, 5, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.1};
    fixture_block(&m, n, lo, hi, 2);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    FvMatrix M;
    face_pattern(&M, &f);
    int longest = 0;
    for (int r = 0; r < M.nrows; r++) longest = M.off[r + 1] - M.off[r] > longest ? M.off[r + 1] - M.off[r] : longest;
    EXPECT(longest == 5, "longest row %d, expected 5", longest);
    EXPECT(M.nnz == 30 + 2 * f.ninternal, "nnz %d", M.nnz);
    fvmatrix_free(&M);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Stencil rows named for a cell add their sources (a boundary source its
   face's owner); the values of a stencil row land where they belong. */
TEST(stencil_sources)
{
    Mesh m;
    int n[3] = {4, 5, 6};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    Stencil s;
    stencil_init(&s);
    int bface = f.nboundary - 1, bowner = m.owner[f.ninternal + bface];
    stencil_add(&s, 57, 0.25);
    stencil_add(&s, 118, 0.5);
    stencil_add(&s, f.ncells + bface, 0.125);
    stencil_add(&s, 1, 0.125);
    stencil_end_row(&s);
    FvPattern p;
    fvpattern_init(&p, &f);
    fvpattern_couple_stencil(&p, 0, &s, 0);
    fvpattern_couple(&p, 7, 100);
    FvMatrix M;
    fvmatrix_init(&M, &p);
    char why[200] = "";
    EXPECT(check_sorted(&M, why, sizeof why) == 0, "%s", why);
    EXPECT(fvmatrix_pos(&M, 0, 57) >= 0 && fvmatrix_pos(&M, 0, 118) >= 0, "stencil sources missing in row 0");
    EXPECT(fvmatrix_pos(&M, 0, bowner) >= 0, "the owner %d of the boundary source missing", bowner);
    EXPECT(fvmatrix_pos(&M, 7, 100) >= 0 && fvmatrix_pos(&M, 100, 7) < 0, "a single coupling is one entry");
    /* row 0: diagonal, 3 face neighbours, 57, 118, bowner; 1 is a neighbour */
    EXPECT(M.off[1] - M.off[0] == 7, "row 0 has %d entries, expected 7", M.off[1] - M.off[0]);
    EXPECT(M.nnz == f.ncells + 2 * f.ninternal + 4, "nnz %d", M.nnz);
    int pos[4];
    EXPECT(fvmatrix_stencil_pos(&M, 0, &s, 0, pos) == 0, "row 0 lacks a source");
    EXPECT(pos[2] == -1, "a boundary source has no position");
    /* row 5 was not named: 57 and 118 are missing, 1 is its face neighbour */
    EXPECT(fvmatrix_stencil_pos(&M, 5, &s, 0, pos) == 2 && pos[3] >= 0, "row 5: missing sources miscounted");
    fvmatrix_stencil_pos(&M, 0, &s, 0, pos);
    for (int k = 0; k < M.nnz; k++) M.val[k] = 1;
    fvmatrix_zero(&M);
    fvmatrix_add_stencil(&M, pos, &s, 0, 8.0);
    double sum = 0;
    for (int k = 0; k < M.nnz; k++) sum += M.val[k];
    NEAR(M.val[fvmatrix_pos(&M, 0, 57)], 2.0, 0);
    NEAR(M.val[fvmatrix_pos(&M, 0, 118)], 4.0, 0);
    NEAR(M.val[fvmatrix_pos(&M, 0, 1)], 1.0, 0);
    NEAR(sum, 7.0, 0);
    EXPECT(M.nnz == f.ncells + 2 * f.ninternal + 4, "zeroing changed the pattern");
    fvmatrix_free(&M);
    stencil_free(&s);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* A cut and merged grid: merged cells share several faces with one
   neighbour, which give one entry. */
TEST(cut_merged_pattern)
{
    Mesh grid, merged;
    int n[3] = {12, 12, 12};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&grid, n, lo, hi, -1);
    fixture_cut(&merged, &grid, "s { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", 1, NULL);
    Err e;
    FvMesh f;
    EXPECT(fvmesh_init(&f, &merged, &e) == 0, "%s", e.msg);
    FvMatrix M;
    face_pattern(&M, &f);
    char why[200] = "";
    int npairs;
    EXPECT(check_sorted(&M, why, sizeof why) == 0, "%s", why);
    EXPECT(check_symmetric(&M) == 0, "pattern not symmetric");
    EXPECT(check_faces(&M, &f, &npairs) == 0, "face positions wrong");
    printf("  merged sphere grid: %d cells, %d internal faces, %d neighbour pairs, nnz %d\n", f.ncells, f.ninternal,
           npairs, M.nnz);
    EXPECT(M.nnz == f.ncells + 2 * npairs, "nnz %d, expected %d", M.nnz, f.ncells + 2 * npairs);
    EXPECT(npairs < f.ninternal, "no merged cell shares two faces with a neighbour: the case tests nothing");
    fvmatrix_free(&M);
    fvmesh_free(&f);
    mesh_free(&merged);
    mesh_free(&grid);
}

/* y = A x against the dense product. */
TEST(product)
{
    Mesh m;
    int n[3] = {3, 4, 2};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    FvMatrix M;
    face_pattern(&M, &f);
    int nc = f.ncells;
    double *dense = calloc((size_t)nc * nc, sizeof *dense), x[24], y[24], worst = 0;
    for (int r = 0; r < nc; r++) x[r] = sin(1.0 + r);
    for (int r = 0; r < nc; r++)
        for (int k = M.off[r]; k < M.off[r + 1]; k++) dense[r * nc + M.col[k]] = M.val[k] = cos(0.3 * k + r);
    fvmatrix_mult(&M, x, y);
    for (int r = 0; r < nc; r++) {
        double v = 0;
        for (int c = 0; c < nc; c++) v += dense[r * nc + c] * x[c];
        worst = fmax(worst, fabs(v - y[r]));
    }
    EXPECT(worst < 1e-14, "product off by %.3g", worst);
    free(dense);
    fvmatrix_free(&M);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* fvmatrix_zero_values and fvmatrix_zero_rhs each zero their part only;
   zeroing the values moves the state on, the right-hand side does not. */
TEST(zero_parts_and_state)
{
    Mesh m;
    int n[3] = {4, 3, 2};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    FvMatrix M;
    face_pattern(&M, &f);
    unsigned long s0 = M.state;
    for (int k = 0; k < M.nnz; k++) M.val[k] = 1;
    for (int r = 0; r < M.nrows; r++) M.rhs[r] = 2;
    fvmatrix_zero_rhs(&M);
    double sv = 0, sr = 0;
    for (int k = 0; k < M.nnz; k++) sv += M.val[k];
    for (int r = 0; r < M.nrows; r++) sr += fabs(M.rhs[r]);
    EXPECT(sv == M.nnz && sr == 0 && M.state == s0, "zero_rhs: values sum %g, |rhs| %g, state %lu -> %lu", sv, sr,
           s0, M.state);
    for (int r = 0; r < M.nrows; r++) M.rhs[r] = 2;
    fvmatrix_zero_values(&M);
    sv = sr = 0;
    for (int k = 0; k < M.nnz; k++) sv += fabs(M.val[k]);
    for (int r = 0; r < M.nrows; r++) sr += M.rhs[r];
    EXPECT(sv == 0 && sr == 2.0 * M.nrows && M.state == s0 + 1, "zero_values: |values| %g, rhs sum %g, state %lu",
           sv, sr, M.state);
    fvmatrix_zero(&M);
    EXPECT(M.state == s0 + 2, "fvmatrix_zero: state %lu, expected %lu", M.state, s0 + 2);
    fvmatrix_free(&M);
    fvmesh_free(&f);
    mesh_free(&m);
}

int main(void)
{
    RUN(block_pattern);
    RUN(two_d_pattern);
    RUN(stencil_sources);
    RUN(cut_merged_pattern);
    RUN(product);
    RUN(zero_parts_and_state);
    return test_summary();
}
