/*
** test_bc.c: boundary conditions parsed once (fv/bc.h): every type's
** coefficients against hand values on a 2 x 2 grid; slip on a cut and
** merged sphere grid (zero normal velocity to round-off with the exact
** boundaryNormal); cyclic pairs on a graded periodic block grid and on the
** periodic inclined channel of thesis §5.1.3 (cut, and cut and merged);
** and every refusal with the field file and the line of the patch entry;
** the open boundaries an isothermal model may take (bc_check_open: one of
** rho and U fixed, both at a supersonic inflow), in 2-D and 3-D; the
** walls of bc_wall.c: partialSlip's Coulomb friction (eq. 2.35: its limits
** slip's and noSlip's to the bit, sticking and sliding by hand, rotation
** invariance in 3-D, the assembly on a cut disc) and rotatingWallVelocity
** (by hand, and on a cut disc: no normal part), with their refusals.
*/
#include "bc.h"
#include "cut.h"
#include "field.h"
#include "fixture.h"
#include "fvm.h"
#include "fvmesh.h"
#include "geom.h"
#include "interp.h"
#include "merge.h"
#include "test.h"

#include <math.h>

/* ---- grids and field files ---- */

/* A 2-D grid 2 x 2 x 1 on [0,1] x [0,0.5] x [0,0.1]: patches inlet (xMin),
   outlet (xMax), bottom (yMin), top (yMax), frontAndBack (empty), or on
   ny x nx cells with the given x points. */
static void grid_2d(Mesh *m, const double *xs, int nx, const double *ys, int ny)
{
    double z[2] = {0, 0.1};
    double *x[3] = {(double *)xs, (double *)ys, z};
    int n[3] = {nx, ny, 1};
    BlockSide side[BLOCK_NSIDES] = {{"inlet", "patch", NULL},  {"outlet", "patch", NULL},
                                    {"bottom", "wall", NULL},  {"top", "wall", NULL},
                                    {"frontAndBack", "empty", NULL}, {"frontAndBack", "empty", NULL}};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
    mesh_cell_faces(m);
    mesh_geometry(m);
}

static void grid_small(Mesh *m)
{
    static const double xs[] = {0, 0.5, 1}, ys[] = {0, 0.25, 0.5};
    grid_2d(m, xs, 2, ys, 2);
}

/* Writes a field file <tmp>/<name> whose boundaryField holds the given
   entries, one per line: the header takes lines 1-5, entry i is on line
   6 + i. */
static char *field_file(const char *name, int width, const char *const *entries, int n)
{
    static int serial;
    char *path = mem_alloc(512);
    snprintf(path, 512, "%s/test_bc_%d_%s", test_tmpdir(), serial++, name);
    FILE *fp = fopen(path, "w");
    if (!fp) {
        printf("cannot write %s\n", path);
        exit(1);
    }
    fprintf(fp, "FoamFile { version 2.0; format ascii; class %s; object %s; }\n",
            width == 1 ? "volScalarField" : "volVectorField", name);
    fprintf(fp, "dimensions [0 0 0 0 0 0 0];\n");
    fprintf(fp, "internalField uniform %s;\n", width == 1 ? "0" : "(0 0 0)");
    fprintf(fp, "boundaryField\n{\n");
    for (int i = 0; i < n; i++) fprintf(fp, "    %s\n", entries[i]);
    fprintf(fp, "}\n");
    fclose(fp);
    return path;
}

/* Reads the field and parses its conditions: 0, or -1 with e set. */
static int load(Bc *bc, Field *f, const FvMesh *fm, const char *path, Err *e)
{
    if (field_read(f, fm->m, path, e)) return -1;
    return bc_init(bc, f, fm, e);
}

/* Boundary face index b of face i of the named patch. */
static int bface(const FvMesh *fm, const char *patch, int i)
{
    const Patch *p = &fm->m->patches[mesh_patch(fm->m, patch)];
    return p->start + i - fm->ninternal;
}

/* Every boundary value is a x_C + b (after bc_update on v): the worst
   difference. */
static double affine_mismatch(const Bc *bc, const double *v)
{
    const FvMesh *fm = bc->fm;
    int w = bc->width;
    double *xb = mem_alloc(sizeof(double) * (size_t)(fm->nboundary * w + 1)), worst = 0;
    bc_values(bc, v, xb);
    for (int b = 0; b < fm->nboundary; b++)
        for (int k = 0; k < w && bc_slot(bc, b) >= 0; k++) { /* empty faces have no values */
            int j = bc_slot(bc, b) * w + k;
            double own = v[fm->m->owner[fm->ninternal + b] * w + k];
            worst = fmax(worst, fabs(bc->a[j] * own + bc->b[j] - xb[b * w + k]));
        }
    free(xb);
    return worst;
}

/* Expects face value and gradient coefficients of all faces of a patch
   (component k). */
#define EXPECT_FACES(bc, fm, patch, k, A, B, GA, GB)                                                       \
    do {                                                                                                   \
        const Patch *pp_ = &(fm)->m->patches[mesh_patch((fm)->m, patch)];                                  \
        for (int i_ = 0; i_ < pp_->size; i_++) {                                                           \
            int j_ = bc_slot(bc, bface(fm, patch, i_)) * (bc)->width + (k);                                \
            NEAR((bc)->a[j_], A, 1e-15);                                                                   \
            NEAR((bc)->b[j_], B, 1e-14);                                                                   \
            NEAR((bc)->ga[j_], GA, 1e-13);                                                                 \
            NEAR((bc)->gb[j_], GB, 1e-13);                                                                 \
        }                                                                                                  \
    } while (0)

/* ---- every type by hand ---- */

/* inlet fixedValue, outlet zeroGradient, bottom noSlip, top movingWall,
   front and back empty.  h_f: 0.25 on inlet and outlet, 0.125 on bottom
   and top (half the cell). */
TEST(vector_types)
{
    Mesh m;
    grid_small(&m);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ent[] = {"inlet { type fixedValue; value uniform (1 2 0); }", "outlet { type zeroGradient; }",
                         "bottom { type noSlip; }", "top { type movingWall; value uniform (3 0 0); }",
                         "frontAndBack { type empty; }"};
    char *path = field_file("U", 3, ent, 5);
    Field f;
    Bc bc;
    EXPECT(load(&bc, &f, &fm, path, &e) == 0, "%s", e.msg);
    if (!test_failed_now) {
        EXPECT(bc.patch[0].kind == BC_FIXED_VALUE && bc.patch[1].kind == BC_ZERO_GRADIENT &&
                   bc.patch[2].kind == BC_NO_SLIP && bc.patch[3].kind == BC_MOVING_WALL && bc.patch[4].kind == BC_EMPTY,
               "kinds %d %d %d %d %d", bc.patch[0].kind, bc.patch[1].kind, bc.patch[2].kind, bc.patch[3].kind,
               bc.patch[4].kind);
        EXPECT_FACES(&bc, &fm, "inlet", 0, 0, 1, -4, 4);
        EXPECT_FACES(&bc, &fm, "inlet", 1, 0, 2, -4, 8);
        EXPECT_FACES(&bc, &fm, "outlet", 0, 1, 0, 0, 0);
        EXPECT_FACES(&bc, &fm, "outlet", 2, 1, 0, 0, 0);
        EXPECT_FACES(&bc, &fm, "bottom", 1, 0, 0, -8, 0);
        EXPECT_FACES(&bc, &fm, "top", 0, 0, 3, -8, 24);
        EXPECT_FACES(&bc, &fm, "top", 1, 0, 0, -8, 0);
        EXPECT(bc.fixed_grad[bc_slot(&bc, bface(&fm, "outlet", 1))] && !bc.fixed_grad[bc_slot(&bc, bface(&fm, "inlet", 0))],
               "Neumann flags");
        /* the front and back: no coefficients at all */
        EXPECT(bc_slot(&bc, bface(&fm, "frontAndBack", 3)) == -1 && bc.nslots == fm.nboundary - 8,
               "empty faces have slots (%d of %d boundary faces)", bc.nslots, fm.nboundary);
        for (int c = 0; c < 4; c++)
            for (int k = 0; k < 3; k++) f.v[3 * c + k] = 10 * c + k + 1;
        bc_update(&bc, f.v);
        double *xb = mem_alloc(sizeof(double) * 3 * (size_t)fm.nboundary);
        bc_values(&bc, f.v, xb);
        int b = bface(&fm, "outlet", 1); /* owner: cell 3 */
        NEAR(xb[3 * b + 2], 33, 0);
        b = bface(&fm, "top", 0); /* the wall's velocity */
        NEAR(xb[3 * b], 3, 0);
        NEAR(affine_mismatch(&bc, f.v), 0, 1e-14);
        free(xb);
        bc_free(&bc);
    }
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* slip with an inclined exact normal (0.6 0.8 0) on top: a = 1 - n_k^2,
   b_k = -n_k sum_{l != k} n_l u_l; symmetryPlane on the bottom with the
   face normal (0 -1 0). */
TEST(slip_by_hand)
{
    Mesh m;
    grid_small(&m);
    int nb = m.nfaces - m.ninternal;
    m.boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)nb);
    for (int b = 0; b < nb; b++) {
        const double *S = m.face_area + 3 * (m.ninternal + b);
        double a = geom_norm(S);
        for (int k = 0; k < 3; k++) m.boundary_normal[3 * b + k] = S[k] / a;
    }
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const Patch *top = &m.patches[mesh_patch(&m, "top")];
    for (int i = 0; i < top->size; i++) {
        double *n = m.boundary_normal + 3 * (top->start + i - m.ninternal);
        n[0] = 0.6, n[1] = 0.8, n[2] = 0;
    }
    const char *ent[] = {"inlet { type fixedValue; value uniform (1 2 0); }", "outlet { type zeroGradient; }",
                         "bottom { type symmetryPlane; }", "top { type slip; }", "frontAndBack { type empty; }"};
    char *path = field_file("U", 3, ent, 5);
    Field f;
    Bc bc;
    EXPECT(load(&bc, &f, &fm, path, &e) == 0, "%s", e.msg);
    if (!test_failed_now) {
        for (int c = 0; c < 4; c++) f.v[3 * c] = 1, f.v[3 * c + 1] = 2, f.v[3 * c + 2] = 3;
        bc_update(&bc, f.v);
        EXPECT_FACES(&bc, &fm, "top", 0, 0.64, -0.96, -0.36 / 0.125, -0.96 / 0.125);
        EXPECT_FACES(&bc, &fm, "top", 1, 0.36, -0.48, -0.64 / 0.125, -0.48 / 0.125);
        EXPECT_FACES(&bc, &fm, "top", 2, 1, 0, 0, 0);
        EXPECT_FACES(&bc, &fm, "bottom", 0, 1, 0, 0, 0);
        EXPECT_FACES(&bc, &fm, "bottom", 1, 0, 0, -8, 0);
        double xb[3];
        int b = bface(&fm, "top", 1);
        for (int k = 0; k < 3; k++) {
            double *all = mem_alloc(sizeof(double) * (size_t)fm.nboundary);
            bc_values_component(&bc, f.v, k, all);
            xb[k] = all[b];
            free(all);
        }
        /* u - (u.n) n = (1 2 3) - 2.2 (0.6 0.8 0) */
        NEAR(xb[0], -0.32, 1e-15);
        NEAR(xb[1], 0.24, 1e-15);
        NEAR(xb[2], 3, 0);
        NEAR(affine_mismatch(&bc, f.v), 0, 1e-15);
        bc_free(&bc);
    }
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* A scalar: fixedValue, zeroGradient, slip and symmetryPlane (zero
   gradient), calculated (its value), empty. */
TEST(scalar_types)
{
    Mesh m;
    grid_small(&m);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ent[] = {"inlet { type fixedValue; value uniform 5; }", "outlet { type calculated; value uniform 7; }",
                         "bottom { type slip; }", "top { type symmetryPlane; }", "frontAndBack { type empty; }"};
    char *path = field_file("p", 1, ent, 5);
    Field f;
    Bc bc;
    EXPECT(load(&bc, &f, &fm, path, &e) == 0, "%s", e.msg);
    if (!test_failed_now) {
        EXPECT_FACES(&bc, &fm, "inlet", 0, 0, 5, -4, 20);
        EXPECT_FACES(&bc, &fm, "outlet", 0, 0, 7, -4, 28);
        EXPECT_FACES(&bc, &fm, "bottom", 0, 1, 0, 0, 0);
        EXPECT_FACES(&bc, &fm, "top", 0, 1, 0, 0, 0);
        EXPECT(bc.fixed_grad[bc_slot(&bc, bface(&fm, "bottom", 0))] && bc.fixed_grad[bc_slot(&bc, bface(&fm, "top", 1))],
               "Neumann flags");
        for (int c = 0; c < 4; c++) f.v[c] = c * c - 1.5;
        NEAR(affine_mismatch(&bc, f.v), 0, 1e-15);
        bc_free(&bc);
    }
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* ---- slip on a cut sphere ---- */

/* Flow outside a sphere cut from a 12^3 grid and merged: every patch
   slip; a smooth velocity.  The face value has no component along the
   exact normal (boundaryNormal) to round-off, while the faces' own
   normals differ from it (so the face normal would not do). */
TEST(slip_cut_sphere)
{
    Mesh grid, cutm, merged;
    int n[3] = {12, 12, 12};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&grid, n, lo, hi, -1);
    FixtureGeo G;
    EXPECT(fixture_geo(&G, "ball { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }") == 0, "geometry");
    Err e;
    CutStats cs;
    MergeOpts mo;
    MergeStats ms;
    merge_opts_default(&mo);
    EXPECT(cut_mesh(&grid, &G.g, NULL, &cutm, &cs, &e) == 0, "%s", e.msg);
    EXPECT(merge_mesh(&cutm, &mo, &merged, &ms, &e) == 0, "%s", e.msg);
    merge_stats_free(&ms);
    FvMesh fm;
    EXPECT(fvmesh_init(&fm, &merged, &e) == 0, "%s", e.msg);
    double zero[3] = {0, 0, 0};
    Field f;
    field_init(&f, &merged, "U", 3, zero, "slip");
    for (int c = 0; c < merged.ncells; c++) {
        const double *x = fm.node + 3 * c;
        f.v[3 * c] = sin(3 * x[0]) + x[1];
        f.v[3 * c + 1] = cos(2 * x[1]) * x[2] - 0.4;
        f.v[3 * c + 2] = x[0] * x[1] + 0.7;
    }
    Bc bc;
    EXPECT(bc_init(&bc, &f, &fm, &e) == 0, "%s", e.msg);
    if (!test_failed_now) {
        double *xb = mem_alloc(sizeof(double) * 3 * (size_t)fm.nboundary);
        bc_values(&bc, f.v, xb);
        const Patch *ball = &merged.patches[mesh_patch(&merged, "ball")];
        double worst = 0, angle = 0, facenormal = 0;
        for (int i = 0; i < ball->size; i++) {
            int b = ball->start + i - fm.ninternal;
            const double *nx = merged.boundary_normal + 3 * b, *nf = fm.nf + 3 * (ball->start + i);
            double *u = xb + 3 * b, umag = geom_norm(f.v + 3 * merged.owner[ball->start + i]);
            worst = fmax(worst, fabs(geom_dot(u, nx)) / umag);
            angle = fmax(angle, acos(fmin(1, geom_dot(nx, nf))));
            facenormal = fmax(facenormal, fabs(geom_dot(u, nf)) / umag);
        }
        printf("  sphere: %d slip faces, |u_b.n|/|u_C| <= %.2e with boundaryNormal (%.2e against the face "
               "normal; the normals differ by up to %.2f degrees)\n",
               ball->size, worst, facenormal, angle * 180 / 3.14159265358979323846);
        EXPECT(ball->size > 100, "%d sphere faces", ball->size);
        EXPECT(worst < 1e-15, "normal component %.3e", worst);
        EXPECT(angle > 1e-3, "the face normals are the exact ones (%.3e rad): the test shows nothing", angle);
        NEAR(affine_mismatch(&bc, f.v), 0, 1e-15);
        free(xb);
        bc_free(&bc);
    }
    field_free(&f);
    fvmesh_free(&fm);
    mesh_free(&merged);
    mesh_free(&cutm);
    mesh_free(&grid);
    fixture_geo_free(&G);
}

/* ---- cyclic ---- */

/* A graded 4 x 3 x 2 grid periodic in x: face i of left pairs with face
   i of right; the neighbour is the cell at the other end; the weights
   follow the two normal distances 0.05 and 0.2. */
TEST(cyclic_block)
{
    double xs[] = {0, 0.1, 0.3, 0.6, 1.0}, ys[] = {0, 0.3, 0.6, 0.9}, zs[] = {0, 0.5, 1};
    double *x[3] = {xs, ys, zs};
    int n[3] = {4, 3, 2};
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"},
                                    {"walls", "wall", NULL},     {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},     {"walls", "wall", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    FvMesh fm;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ent[] = {"left { type cyclic; }", "right { type cyclic; }", "walls { type noSlip; }"};
    char *path = field_file("U", 3, ent, 3);
    Field f;
    Bc bc;
    EXPECT(load(&bc, &f, &fm, path, &e) == 0, "%s", e.msg);
    if (!test_failed_now) {
        NEAR(bc.patch[0].shift[0], 1, 1e-15);
        NEAR(bc.patch[1].shift[0], -1, 1e-15);
        NEAR(fabs(bc.patch[0].shift[1]) + fabs(bc.patch[0].shift[2]), 0, 0);
        EXPECT(bc.patch[0].partner == 1 && bc.patch[1].partner == 0, "partners %d %d", bc.patch[0].partner,
               bc.patch[1].partner);
        int bad = 0;
        for (int i = 0; i < 6; i++) {
            int bl = bface(&fm, "left", i), br = bface(&fm, "right", i), sl = bc_slot(&bc, bl), sr = bc_slot(&bc, br);
            int cl = m.owner[fm.ninternal + bl], cr = m.owner[fm.ninternal + br];
            bad += cl % 4 != 0 || cr != cl + 3 || bc.nbr[sl] != cr || bc.nbr[sr] != cl;
            NEAR(bc.a[3 * sl], 0.8, 1e-15);
            NEAR(bc.nbr_w[sl], 0.2, 1e-15);
            NEAR(bc.ga[3 * sl + 1], -4, 1e-13);
            NEAR(bc.a[3 * sr + 2], 0.2, 1e-15);
            NEAR(bc.nbr_d[sr], 0.05, 1e-15);
        }
        EXPECT(bad == 0, "%d faces paired with the wrong cells", bad);
        /* both sides of a pair see one face value and opposite gradients */
        for (int c = 0; c < m.ncells; c++)
            for (int k = 0; k < 3; k++) f.v[3 * c + k] = sin(c + 0.3 * k);
        bc_update(&bc, f.v);
        double *xb = mem_alloc(sizeof(double) * 3 * (size_t)fm.nboundary), worst = 0, gworst = 0;
        bc_values(&bc, f.v, xb);
        for (int i = 0; i < 6; i++)
            for (int k = 0; k < 3; k++) {
                int bl = bface(&fm, "left", i), br = bface(&fm, "right", i);
                int jl = 3 * bc_slot(&bc, bl) + k, jr = 3 * bc_slot(&bc, br) + k;
                worst = fmax(worst, fabs(xb[3 * bl + k] - xb[3 * br + k]));
                double gl = bc.ga[jl] * f.v[3 * bc.nbr[jr / 3] + k] + bc.gb[jl];
                double gr = bc.ga[jr] * f.v[3 * bc.nbr[jl / 3] + k] + bc.gb[jr];
                gworst = fmax(gworst, fabs(gl + gr));
            }
        NEAR(worst, 0, 1e-15);
        NEAR(gworst, 0, 1e-13);
        /* the upwind state across a cyclic face: the neighbour's value */
        bc_states(&bc, f.v, xb);
        int bl = bface(&fm, "left", 2), br = bface(&fm, "right", 5);
        NEAR(xb[3 * bl + 1], f.v[3 * m.owner[fm.ninternal + bface(&fm, "right", 2)] + 1], 0);
        NEAR(xb[3 * br], f.v[3 * m.owner[fm.ninternal + bface(&fm, "left", 5)]], 0);
        int bw = bface(&fm, "walls", 0);
        NEAR(xb[3 * bw], 0, 0);
        NEAR(affine_mismatch(&bc, f.v), 0, 1e-15);
        free(xb);
        bc_free(&bc);
    }
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* The periodic inclined channel of thesis §5.1.3.1 on a 2-D grid of
   spacing 0.1: walls of slope rise/1 through (0, y0) and (0, y0 + 0.4),
   x periodic on [0, 1], cut (and merged when merge is set).  Returns
   bc_init's result for a field with cyclic ends and noSlip walls. */
static int channel(double y0, double rise, int merge, Mesh *out, char **path, Field *f, Bc *bc, FvMesh *fm,
                   Err *e)
{
    mesh_init(out);
    memset(f, 0, sizeof *f);
    memset(fm, 0, sizeof *fm);
    int n[3] = {10, 16, 1};
    double *x[3];
    for (int k = 0; k < 2; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = 0.1 * i;
    }
    double z[2] = {0, 0.1};
    x[2] = z;
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"},
                                    {"bottom", "wall", NULL},    {"top", "wall", NULL},
                                    {"frontAndBack", "empty", NULL}, {"frontAndBack", "empty", NULL}};
    Mesh grid, cutm;
    mesh_init(&grid);
    if (block_mesh(&grid, x, n, side, NULL, "test", NULL, e)) return -1;
    free(x[0]);
    free(x[1]);
    char txt[600];
    snprintf(txt, sizeof txt,
             "lower { flow inside; shape halfSpace; point (0 %.17g 0); normal (%.17g -1 0); }\n"
             "upper { flow inside; shape halfSpace; point (0 %.17g 0); normal (%.17g 1 0); }",
             y0, rise, y0 + 0.4, -rise);
    FixtureGeo G;
    if (fixture_geo(&G, txt)) return err_set(e, NULL, 0, "geometry");
    geometry_flatten(&G.g, 2, 0.05);
    CutStats cs;
    int rc = cut_mesh(&grid, &G.g, NULL, merge ? &cutm : out, &cs, e);
    fixture_geo_free(&G);
    mesh_free(&grid);
    if (rc) return -1;
    if (merge) {
        MergeOpts mo;
        MergeStats ms;
        merge_opts_default(&mo);
        rc = merge_mesh(&cutm, &mo, out, &ms, e);
        if (rc == 0) merge_stats_free(&ms);
        mesh_free(&cutm);
        if (rc) return -1;
    }
    if (fvmesh_init(fm, out, e)) return -1;
    const char *ent[] = {"left { type cyclic; }", "right { type cyclic; }", "\"(bottom|top|lower|upper)\" { type noSlip; }",
                         "frontAndBack { type empty; }"};
    *path = field_file("U", 3, ent, 4);
    if (field_read(f, out, *path, e)) return -1;
    return bc_init(bc, f, fm, e);
}

static void channel_free(Mesh *m, char *path, Field *f, FvMesh *fm)
{
    field_free(f);
    free(path);
    fvmesh_free(fm);
    mesh_free(m);
}

/* Slope 1/2 from the grid corner (0, 0.2) to (1, 0.7): both ends see the
   same four whole faces, paired by the translation (1, 0.5, 0). */
TEST(inclined_channel)
{
    for (int merge = 0; merge < 2; merge++) {
        Mesh m;
        FvMesh fm;
        Field f;
        Bc bc;
        Err e;
        char *path = NULL;
        EXPECT(channel(0.2, 0.5, merge, &m, &path, &f, &bc, &fm, &e) == 0, "%s", e.msg);
        if (test_failed_now) return;
        int l = mesh_patch(&m, "left"), r = mesh_patch(&m, "right");
        printf("  inclined channel, slope 1/2%s: %d cells, %d cyclic pairs, translation (%g %g %g)\n",
               merge ? ", merged" : "", m.ncells, m.patches[l].size, bc.patch[l].shift[0], bc.patch[l].shift[1],
               bc.patch[l].shift[2]);
        EXPECT(m.patches[l].size == 4, "%d faces on the left end", m.patches[l].size);
        NEAR(bc.patch[l].shift[0], 1, 1e-14);
        NEAR(bc.patch[l].shift[1], 0.5, 1e-14);
        NEAR(bc.patch[r].shift[1], -0.5, 1e-14);
        int bad = 0;
        for (int i = 0; i < 4; i++) {
            int bl = bface(&fm, "left", i), br = bface(&fm, "right", i), sl = bc_slot(&bc, bl), sr = bc_slot(&bc, br);
            bad += bc.nbr[sl] != m.owner[fm.ninternal + br] || bc.nbr[sr] != m.owner[fm.ninternal + bl];
            /* the periodic neighbour's node, moved back by the translation,
               lies across the face at its normal distance nbr_d */
            const double *xr = fm.node + 3 * bc.nbr[sl], *cf = m.face_centre + 3 * (fm.ninternal + bl);
            double d[3];
            for (int k = 0; k < 3; k++) d[k] = xr[k] - bc.patch[l].shift[k] - cf[k];
            NEAR(geom_dot(d, fm.nf + 3 * (fm.ninternal + bl)), bc.nbr_d[sl], 1e-14);
            EXPECT(bc.nbr_d[sl] > 0.01, "face %d: the partner's node at %g from its face", i, bc.nbr_d[sl]);
        }
        EXPECT(bad == 0, "%d faces paired with the wrong cells", bad);
        bc_free(&bc);
        channel_free(&m, path, &f, &fm);
    }
}

/* Ends that do not see identical faces: walls not through grid corners
   at the ends (y0 = 0.25, rise 0.52: five faces at each end, cut
   differently: the first is 0.05 high on the left, 0.03 on the right), and a rise of 0.55 (four whole faces against five).
   Both refused, naming the field file and the cyclic entry's line. */
TEST(inclined_channel_unpaired)
{
    Mesh m;
    FvMesh fm;
    Field f;
    Bc bc;
    Err e;
    char *path = NULL, want[600];
    EXPECT(channel(0.25, 0.52, 0, &m, &path, &f, &bc, &fm, &e) != 0, "ends cut differently accepted");
    printf("  %s\n", e.msg);
    snprintf(want, sizeof want, "%s:6: cyclic patch 'left': face 0 (area 0.005) and face 0 of neighbourPatch "
             "'right' (area 0.003) differ in area", path);
    CONTAINS(e.msg, want);
    CONTAINS(e.msg, "the faces do not pair");
    channel_free(&m, path, &f, &fm);
    EXPECT(channel(0.2, 0.55, 0, &m, &path, &f, &bc, &fm, &e) != 0, "ends of different face counts accepted");
    printf("  %s\n", e.msg);
    snprintf(want, sizeof want, "%s:6: cyclic patch 'left' has 4 faces, its neighbourPatch 'right' 5", path);
    CONTAINS(e.msg, want);
    channel_free(&m, path, &f, &fm);
}

/* ---- refusals ---- */

/* The message of bc_init for a field with the given entries on the small
   grid (or NULL when it succeeds). */
static void refused(const char *name, int width, const char *const *ent, char *msg, char *path_out)
{
    Mesh m;
    grid_small(&m);
    FvMesh fm;
    Err e;
    fvmesh_init(&fm, &m, &e);
    char *path = field_file(name, width, ent, 5);
    strcpy(path_out, path);
    Field f;
    Bc bc;
    if (load(&bc, &f, &fm, path, &e) == 0) {
        strcpy(msg, "(accepted)");
        bc_free(&bc);
    } else {
        strcpy(msg, e.msg);
    }
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

#define REFUSED(name, width, line, text, ...)                                                              \
    do {                                                                                                   \
        const char *ent_[] = {__VA_ARGS__};                                                                \
        char msg_[ERR_MSG_MAX], path_[512], want_[1024];                                                   \
        refused(name, width, ent_, msg_, path_);                                                           \
        snprintf(want_, sizeof want_, "%s:%d: %s", path_, line, text);                                     \
        const char *got_ = msg_;                                                                           \
        CONTAINS(got_, want_);                                                                             \
    } while (0)

TEST(errors)
{
    REFUSED("U", 3, 9, "patch 'top' of field 'U': unknown boundary condition type 'fixdValue'",
            "inlet { type fixedValue; value uniform (1 0 0); }", "outlet { type zeroGradient; }",
            "bottom { type noSlip; }", "top { type fixdValue; value uniform (0 0 0); }", "frontAndBack { type empty; }");
    REFUSED("p", 1, 8, "patch 'bottom': type noSlip is for vector fields; field 'p' is a scalar field",
            "inlet { type fixedValue; value uniform 1; }", "outlet { type zeroGradient; }", "bottom { type noSlip; }",
            "top { type zeroGradient; }", "frontAndBack { type empty; }");
    REFUSED("T", 1, 9, "patch 'top': type movingWall is for vector fields",
            "inlet { type fixedValue; value uniform 1; }", "outlet { type zeroGradient; }",
            "bottom { type zeroGradient; }", "top { type movingWall; value uniform 1; }", "frontAndBack { type empty; }");
    REFUSED("U", 3, 9, "patch 'top' of field 'U': type movingWall needs a value entry",
            "inlet { type fixedValue; value uniform (1 0 0); }", "outlet { type zeroGradient; }",
            "bottom { type noSlip; }", "top { type movingWall; }", "frontAndBack { type empty; }");
    REFUSED("U", 3, 6, "patch 'inlet' is of type patch in the grid, of type cyclic in field 'U': type cyclic needs a "
                       "cyclic grid patch",
            "inlet { type cyclic; }", "outlet { type zeroGradient; }", "bottom { type noSlip; }",
            "top { type noSlip; }", "frontAndBack { type empty; }");
    /* the entry found by a regex key: its own line */
    REFUSED("U", 3, 7, "patch 'outlet' of field 'U': unknown boundary condition type 'outflow'",
            "inlet { type fixedValue; value uniform (1 0 0); }", "\"(out.*|bottom)\" { type outflow; }",
            "bottom { type noSlip; }", "top { type noSlip; }", "frontAndBack { type empty; }");
}

/* A field of another grid: other cell count; same cells but other patch
   sizes (the entry's line named). */
TEST(errors_grid)
{
    Mesh a, b, c;
    grid_small(&a);
    static const double x4[] = {0, 0.25, 0.5, 0.75, 1}, y1[] = {0, 0.5}, y3[] = {0, 0.2, 0.4, 0.5};
    grid_2d(&b, x4, 4, y1, 1);
    grid_2d(&c, x4 + 2, 2, y3, 3);
    FvMesh fb, fc;
    Err e;
    EXPECT(fvmesh_init(&fb, &b, &e) == 0 && fvmesh_init(&fc, &c, &e) == 0, "%s", e.msg);
    const char *ent[] = {"inlet { type fixedValue; value uniform (1 0 0); }", "outlet { type zeroGradient; }",
                         "bottom { type noSlip; }", "top { type noSlip; }", "frontAndBack { type empty; }"};
    char *path = field_file("U", 3, ent, 5), want[700];
    Field f;
    Bc bc;
    EXPECT(field_read(&f, &a, path, &e) == 0, "%s", e.msg);
    EXPECT(bc_init(&bc, &f, &fb, &e) != 0, "a field of another grid accepted");
    snprintf(want, sizeof want, "%s:6: patch 'inlet' of field 'U' has 2 faces, the grid's 1", path);
    CONTAINS(e.msg, want);
    EXPECT(bc_init(&bc, &f, &fc, &e) != 0, "a field of another grid accepted");
    snprintf(want, sizeof want, "%s: field 'U' has 4 cells, the grid 6", path);
    CONTAINS(e.msg, want);
    field_free(&f);
    free(path);
    fvmesh_free(&fb);
    fvmesh_free(&fc);
    mesh_free(&a);
    mesh_free(&b);
    mesh_free(&c);
}

/* A cyclic patch whose neighbourPatch the grid does not have. */
TEST(errors_partner)
{
    double xs[] = {0, 0.5, 1}, ys[] = {0, 1}, zs[] = {0, 1};
    double *x[3] = {xs, ys, zs};
    int n[3] = {2, 1, 1};
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"},
                                    {"walls", "wall", NULL},     {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},     {"walls", "wall", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    free(m.patches[0].neighbour);
    m.patches[0].neighbour = mem_strdup("rigth");
    FvMesh fm;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ent[] = {"left { type cyclic; }", "right { type cyclic; }", "walls { type noSlip; }"};
    char *path = field_file("U", 3, ent, 3), want[700];
    Field f;
    Bc bc;
    EXPECT(load(&bc, &f, &fm, path, &e) != 0, "a missing partner accepted");
    snprintf(want, sizeof want, "%s:6: cyclic patch 'left': its neighbourPatch 'rigth' is no patch of the grid", path);
    CONTAINS(e.msg, want);
    field_free(&f);
    free(path);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* ---- walls: partialSlip (eq. 2.35) and rotatingWallVelocity ---- */

static const double PI = 3.14159265358979323846;

/* The grid's boundaryNormal: every boundary face's own unit normal. */
static void face_normals(Mesh *m)
{
    int nb = m->nfaces - m->ninternal;
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)nb);
    for (int b = 0; b < nb; b++) {
        const double *S = m->face_area + 3 * (m->ninternal + b);
        double a = geom_norm(S);
        for (int k = 0; k < 3; k++) m->boundary_normal[3 * b + k] = S[k] / a;
    }
}

/* The exact normal n of every face of the named patch. */
static void patch_normal(Mesh *m, const char *patch, const double *n)
{
    const Patch *p = &m->patches[mesh_patch(m, patch)];
    for (int i = 0; i < p->size; i++) memcpy(m->boundary_normal + 3 * (p->start + i - m->ninternal), n, 3 * sizeof *n);
}

/* Writes the n entries to a field file and reads it into f and bc: 0, or
   -1 with e set. */
static int load_entries(Bc *bc, Field *f, const FvMesh *fm, const char *name, int width, const char *const *ent, int n,
                        Err *e)
{
    char *path = field_file(name, width, ent, n);
    int rc = load(bc, f, fm, path, e);
    free(path);
    return rc;
}

/* The largest difference of a, b, ga, gb of two conditions of one grid on
   the named patch. */
static double coeff_diff(const Bc *x, const Bc *y, const FvMesh *fm, const char *patch)
{
    const Patch *p = &fm->m->patches[mesh_patch(fm->m, patch)];
    double d = 0;
    for (int i = 0; i < p->size; i++)
        for (int k = 0; k < 3; k++) {
            int j = bc_slot(x, bface(fm, patch, i)) * 3 + k;
            d = fmax(d, fmax(fabs(x->a[j] - y->a[j]), fabs(x->b[j] - y->b[j])));
            d = fmax(d, fmax(fabs(x->ga[j] - y->ga[j]), fabs(x->gb[j] - y->gb[j])));
        }
    return d;
}

/* An array of n copies of x. */
static double *filled(int n, double x)
{
    double *a = mem_alloc(sizeof(double) * (size_t)(n + 1));
    for (int i = 0; i < n; i++) a[i] = x;
    return a;
}

/* eq. 2.35's nu and its limits. */
TEST(coulomb_nu)
{
    double t30 = tan(PI / 6), p = 2, eta = 0.5, h = 0.1, lim = p * t30 * h;
    NEAR(bc_coulomb_nu(1, 1, INFINITY, h, 5), 0, 0);      /* 90 degrees: sticks */
    NEAR(bc_coulomb_nu(0, 1, INFINITY, h, 5), 0, 0);      /* ... even without pressure */
    NEAR(bc_coulomb_nu(3, 1, 0, h, 0), 1, 0);             /* 0 degrees: slides, also at rest */
    NEAR(bc_coulomb_nu(-2, 1, t30, h, 1), 1, 0);          /* no pressure: no friction */
    NEAR(bc_coulomb_nu(1, 1, t30, h, 0), 0, 0);           /* at rest with friction: sticks */
    NEAR(bc_coulomb_nu(NAN, 1, t30, h, 1), 0, 0);         /* NaN: sticks */
    NEAR(bc_coulomb_nu(1, NAN, t30, h, 1), 0, 0);
    NEAR(bc_coulomb_nu(p, eta, t30, h, 0.9 * lim / eta), 0, 0); /* W^t < W^n tan phi */
    NEAR(bc_coulomb_nu(p, eta, t30, h, 4 * lim / eta), 0.75, 1e-15);
    NEAR(bc_coulomb_nu(p, 0, t30, h, 1), 0, 0);           /* no viscosity: no stress to exceed */
}

/* On the 2 x 2 grid with the exact normal (0.6 0.8 0) on top: partialSlip
   with phi = 0 has slip's coefficients, with phi = 90 noSlip's, and
   without a wall state noSlip's, to the bit (phi = 0 under pressure,
   phi = 90 without: the limits do not depend on the state). */
TEST(partial_slip_limits)
{
    Mesh m;
    grid_small(&m);
    face_normals(&m);
    static const double n[3] = {0.6, 0.8, 0};
    patch_normal(&m, "top", n);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *tops[5] = {"top { type partialSlip; frictionAngle 0; }", "top { type slip; }",
                           "top { type partialSlip; frictionAngle 90; }", "top { type noSlip; }",
                           "top { type partialSlip; frictionAngle 30; }"};
    Field f[5];
    Bc bc[5];
    int ok = 0;
    for (int t = 0; t < 5; t++) {
        const char *ent[] = {"inlet { type fixedValue; value uniform (1 2 0); }", "outlet { type zeroGradient; }",
                             "bottom { type noSlip; }", tops[t], "frontAndBack { type empty; }"};
        ok += load_entries(&bc[t], &f[t], &fm, "U", 3, ent, 5, &e) == 0;
        EXPECT(ok == t + 1, "%s: %s", tops[t], e.msg);
    }
    if (ok == 5) {
        double *p2 = filled(fm.nboundary, 2), *p0 = filled(fm.nboundary, 0), *eta = filled(fm.nboundary, 0.5);
        bc_set_wall_state(&bc[0], p2, eta);
        bc_set_wall_state(&bc[2], p0, eta);
        double v[12];
        for (int c = 0; c < 4; c++) v[3 * c] = 1 + c, v[3 * c + 1] = 2 - 0.5 * c, v[3 * c + 2] = 0.3 * c;
        for (int t = 0; t < 5; t++) bc_update(&bc[t], v);
        NEAR(coeff_diff(&bc[0], &bc[1], &fm, "top"), 0, 0);
        NEAR(coeff_diff(&bc[2], &bc[3], &fm, "top"), 0, 0);
        NEAR(coeff_diff(&bc[4], &bc[3], &fm, "top"), 0, 0);
        int s = bc_slot(&bc[0], bface(&fm, "top", 1)), nf = 0;
        NEAR(bc[0].nu[s], 1, 0);
        NEAR(bc[2].nu[s], 0, 0);
        NEAR(bc[4].nu[s], 0, 0);
        EXPECT(isnan(bc[0].nu[bc_slot(&bc[0], bface(&fm, "bottom", 0))]), "nu on a noSlip face");
        EXPECT(bc_slip_count(&bc[0], &nf) == 2 && nf == 2, "phi = 0: %d of %d faces slide", bc_slip_count(&bc[0], NULL),
               nf);
        EXPECT(bc_slip_count(&bc[2], &nf) == 0 && nf == 2, "phi = 90: %d of %d faces slide",
               bc_slip_count(&bc[2], NULL), nf);
        EXPECT(bc_slip_count(&bc[1], &nf) == 0 && nf == 0, "slip has %d partialSlip faces", nf);
        /* the values: slip's and noSlip's */
        size_t nx = sizeof(double) * 3 * (size_t)fm.nboundary;
        double *x0 = mem_alloc(nx), *x1 = mem_alloc(nx);
        bc_values(&bc[0], v, x0);
        bc_values(&bc[1], v, x1);
        int b = bface(&fm, "top", 0);
        for (int k = 0; k < 3; k++) NEAR(x0[3 * b + k], x1[3 * b + k], 1e-15);
        bc_values(&bc[2], v, x0);
        for (int k = 0; k < 3; k++) NEAR(x0[3 * b + k], 0, 0);
        for (int t = 0; t < 5; t++) NEAR(affine_mismatch(&bc[t], v), 0, 1e-15);
        free(x0);
        free(x1);
        free(p0);
        free(p2);
        free(eta);
    }
    for (int t = 0; t < ok; t++) {
        bc_free(&bc[t]);
        field_free(&f[t]);
    }
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* The Coulomb wall by hand on the 2 x 2 grid: top with the exact normal
   n = (0.6 0.8 0), tangent t = (0.8 -0.6 0), moving at u_S = 0.5 t, eta
   0.7, h_f = 0.125; the owners' tangential velocities 1.8 and 2.9.
   p = 100 on both faces sticks (u_b = u_S); p = 5 on face 1 slides, and
   there the wall stress eta (u_I,t - u_b,t)/h is p tan 30 degrees, the
   value is eq. 2.35's, and so is the normal gradient the coefficients
   give.  The wall state's arrays are read through their pointers at each
   bc_update. */
TEST(partial_slip_regimes)
{
    Mesh m;
    grid_small(&m);
    face_normals(&m);
    static const double n[3] = {0.6, 0.8, 0}, t[3] = {0.8, -0.6, 0};
    patch_normal(&m, "top", n);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ent[] = {"inlet { type fixedValue; value uniform (1 2 0); }", "outlet { type zeroGradient; }",
                         "bottom { type noSlip; }",
                         "top { type partialSlip; frictionAngle 30; wallVelocity (0.4 -0.3 0); }",
                         "frontAndBack { type empty; }"};
    Field f;
    Bc bc;
    EXPECT(load_entries(&bc, &f, &fm, "U", 3, ent, 5, &e) == 0, "%s", e.msg);
    if (test_failed_now) return;
    double *p = filled(fm.nboundary, 100), *eta = filled(fm.nboundary, 0.7), v[12], xb[3 * 16];
    EXPECT(fm.nboundary <= 16, "%d boundary faces", fm.nboundary);
    for (int c = 0; c < 4; c++) v[3 * c] = 1 + c, v[3 * c + 1] = 2 - 0.5 * c, v[3 * c + 2] = 0;
    bc_set_wall_state(&bc, p, eta);
    bc_update(&bc, v);
    bc_values(&bc, v, xb);
    const double us[3] = {0.4, -0.3, 0}, tp = 5 * tan(PI / 6);
    for (int i = 0; i < 2; i++) {
        int b = bface(&fm, "top", i);
        for (int k = 0; k < 3; k++) NEAR(xb[3 * b + k], us[k], 1e-15);
        NEAR(bc.nu[bc_slot(&bc, b)], 0, 0);
    }
    EXPECT(bc_slip_count(&bc, NULL) == 0, "p = 100: %d faces slide", bc_slip_count(&bc, NULL));
    int b1 = bface(&fm, "top", 1), s1 = bc_slot(&bc, b1);
    p[b1] = 5;
    bc_update(&bc, v);
    bc_values(&bc, v, xb);
    EXPECT(bc_slip_count(&bc, NULL) == 1, "p = 5 on one face: %d faces slide", bc_slip_count(&bc, NULL));
    const double *ui = v + 3 * m.owner[fm.ninternal + b1], *ub = xb + 3 * b1;
    double h = bc.h[s1], uit = geom_dot(ui, t), ust = geom_dot(us, t), ubt = geom_dot(ub, t);
    NEAR(h, 0.125, 1e-15);
    NEAR(uit, 2.9, 1e-15);
    double stress = 0.7 * (uit - ubt) / h;
    printf("  partialSlip: W^t = %g > p tan phi = %g: nu = %.6f, wall stress %.15g\n", 0.7 * (uit - ust) / h, tp,
           bc.nu[s1], stress);
    EXPECT(bc.nu[s1] > 0 && bc.nu[s1] < 1, "nu = %g", bc.nu[s1]);
    NEAR(stress / tp, 1, 1e-12);
    /* eq. 2.35 as the thesis writes it, along t (2-D: one tangential direction) */
    double wt = 0.7 * fabs(uit - ust) / h, sg = ust > uit ? 1 : -1;
    NEAR(ubt, uit + h / 0.7 * fmin(tp, wt) * sg, 1e-12 * fabs(uit));
    NEAR(geom_dot(ub, n), geom_dot(us, n), 1e-15);
    NEAR(ub[2], 0, 0);
    /* the normal gradient the diffusion sees: ga u + gb = (u_b - u_I)/h */
    double g[3];
    for (int k = 0; k < 3; k++) g[k] = bc.ga[3 * s1 + k] * ui[k] + bc.gb[3 * s1 + k];
    NEAR(-0.7 * geom_dot(g, t) / tp, 1, 1e-12);
    NEAR(geom_dot(g, n), (geom_dot(us, n) - geom_dot(ui, n)) / h, 1e-13);
    NEAR(affine_mismatch(&bc, v), 0, 1e-15);
    /* the other face still sticks */
    int b0 = bface(&fm, "top", 0);
    for (int k = 0; k < 3; k++) NEAR(xb[3 * b0 + k], us[k], 1e-15);
    free(p);
    free(eta);
    bc_free(&bc);
    field_free(&f);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* R x for the rotation of angle w about the unit vector a (Rodrigues). */
static void rotate(const double a[3], double w, const double x[3], double y[3])
{
    double c = cos(w), s = sin(w), ax = geom_dot(a, x);
    double cr[3] = {a[1] * x[2] - a[2] * x[1], a[2] * x[0] - a[0] * x[2], a[0] * x[1] - a[1] * x[0]};
    for (int k = 0; k < 3; k++) y[k] = x[k] * c + cr[k] * s + a[k] * ax * (1 - c);
}

/* The Cartesian component-wise reading of eq. 2.35 (not Kiesel's): each
   component of the tangential vector on its own, plus the normal part. */
static void cartesian_rule(const double *ui, const double *us, const double *n, double p, double eta, double tanp,
                           double h, double *ub)
{
    double uin = geom_dot(ui, n), usn = geom_dot(us, n);
    for (int k = 0; k < 3; k++) {
        double it = ui[k] - uin * n[k], st = us[k] - usn * n[k], wt = eta * fabs(it - st) / h;
        ub[k] = it + h / eta * fmin(p * tanp, wt) * (st > it ? 1 : st < it ? -1 : 0) + usn * n[k];
    }
}

/* A 2 x 2 x 2 grid whose xMax wall has the exact normal n (sliding, 0 <
   nu < 1), the cells u and the wall u_S; then all three rotated by R:
   u_b is R u_b to round-off, nu the same, and u_b,t - u_I,t is along
   u_S,t - u_I,t.  The Cartesian component-wise reading moves by more
   than 1e-3 under the same rotation, so the test tells them apart. */
TEST(partial_slip_rotation_3d)
{
    double xs[] = {0, 0.5, 1};
    double *x[3] = {xs, xs, xs};
    int nc[3] = {2, 2, 2};
    double axis[3] = {1 / sqrt(14), 2 / sqrt(14), 3 / sqrt(14)}, ang = 0.9, P3 = 3;
    double n0[3] = {0.7, 0.2, -0.4}, us0[3] = {0.3, -0.5, 0.8}, d = geom_norm(n0), tanp = tan(25 * PI / 180);
    for (int k = 0; k < 3; k++) n0[k] /= d;
    double nr[3], usr[3], ub[2][3 * 64], u[2][3 * 8], cart_worst = 0, worst = 0, par = 0, nud = 0;
    rotate(axis, ang, n0, nr);
    rotate(axis, ang, us0, usr);
    Bc bc[2];
    Field f[2];
    Mesh m[2];
    FvMesh fm[2];
    Err e;
    double *p = NULL, *eta = NULL;
    for (int r = 0; r < 2; r++) {
        const double *n = r ? nr : n0, *us = r ? usr : us0;
        fixture_mesh(&m[r], x, nc);
        face_normals(&m[r]);
        patch_normal(&m[r], "xMax", n);
        EXPECT(fvmesh_init(&fm[r], &m[r], &e) == 0, "%s", e.msg);
        char wall[200];
        snprintf(wall, sizeof wall, "xMax { type partialSlip; frictionAngle 25; wallVelocity (%.17g %.17g %.17g); }",
                 us[0], us[1], us[2]);
        const char *ent[] = {wall, "\"(xMin|yMin|yMax|zMin|zMax)\" { type noSlip; }"};
        EXPECT(load_entries(&bc[r], &f[r], &fm[r], "U", 3, ent, 2, &e) == 0, "%s", e.msg);
        if (test_failed_now) return;
        if (!p) p = filled(fm[r].nboundary, P3), eta = filled(fm[r].nboundary, 1.1);
        for (int c = 0; c < 8; c++) {
            double u0[3] = {sin(c + 1.0), cos(2.0 * c) - 0.3, 0.5 * c - 1.2};
            if (r)
                rotate(axis, ang, u0, u[r] + 3 * c);
            else
                memcpy(u[r] + 3 * c, u0, sizeof u0);
        }
        bc_set_wall_state(&bc[r], p, eta);
        bc_update(&bc[r], u[r]);
        bc_values(&bc[r], u[r], ub[r]);
    }
    int nf = 0, slide = bc_slip_count(&bc[0], &nf);
    EXPECT(slide == 4 && nf == 4, "%d of %d faces slide", slide, nf);
    const Patch *wp = &m[0].patches[mesh_patch(&m[0], "xMax")];
    for (int i = 0; i < wp->size; i++) {
        int b = wp->start + i - fm[0].ninternal, s = bc_slot(&bc[0], b), own = m[0].owner[wp->start + i];
        double rb[3], c0[3], c1[3], rc[3];
        rotate(axis, ang, ub[0] + 3 * b, rb);
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(rb[k] - ub[1][3 * b + k]));
        nud = fmax(nud, fabs(bc[0].nu[s] - bc[1].nu[s]));
        EXPECT(bc[0].nu[s] > 0.05 && bc[0].nu[s] < 0.95, "face %d: nu = %g", i, bc[0].nu[s]);
        /* the slip's direction: u_b,t - u_I,t parallel to u_S,t - u_I,t */
        const double *ui = u[0] + 3 * own;
        double a1[3], a2[3], un = geom_dot(ui, n0), bn = geom_dot(ub[0] + 3 * b, n0), sn = geom_dot(us0, n0);
        for (int k = 0; k < 3; k++) {
            a1[k] = (ub[0][3 * b + k] - bn * n0[k]) - (ui[k] - un * n0[k]);
            a2[k] = (us0[k] - sn * n0[k]) - (ui[k] - un * n0[k]);
        }
        double cr[3] = {a1[1] * a2[2] - a1[2] * a2[1], a1[2] * a2[0] - a1[0] * a2[2], a1[0] * a2[1] - a1[1] * a2[0]};
        par = fmax(par, geom_norm(cr) / (geom_norm(a1) * geom_norm(a2)));
        NEAR(bn, sn, 1e-15);
        cartesian_rule(ui, us0, n0, P3, 1.1, tanp, bc[0].h[s], c0);
        cartesian_rule(u[1] + 3 * own, usr, nr, P3, 1.1, tanp, bc[1].h[s], c1);
        rotate(axis, ang, c0, rc);
        for (int k = 0; k < 3; k++) cart_worst = fmax(cart_worst, fabs(rc[k] - c1[k]));
    }
    printf("  rotated wall: |u_b(R) - R u_b| <= %.2e, nu differs by %.2e, slip direction off by %.2e; the "
           "Cartesian reading moves by %.3f\n",
           worst, nud, par, cart_worst);
    NEAR(worst, 0, 1e-14);
    NEAR(nud, 0, 1e-14);
    NEAR(par, 0, 1e-14);
    EXPECT(cart_worst > 1e-3, "the Cartesian reading is as invariant (%.3e): the test shows nothing", cart_worst);
    for (int r = 0; r < 2; r++) {
        NEAR(affine_mismatch(&bc[r], u[r]), 0, 1e-15);
        bc_free(&bc[r]);
        field_free(&f[r]);
        fvmesh_free(&fm[r]);
        mesh_free(&m[r]);
    }
    free(p);
    free(eta);
}

/* ---- partialSlip in the assembly (fv/fvm.c reads a, ga, b, gb) ---- */

static const char *const DISC =
    "d { flow outside; shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.27; }";

/* The unit square of N cells cut by DISC and merged. */
static void disc_grid(Mesh *out, int N)
{
    Mesh grid;
    fixture_square(&grid, N);
    fixture_cut(out, &grid, DISC, 1, NULL);
    mesh_free(&grid);
}

/* One condition of U on the disc's wall with its diffusion operator. */
typedef struct Op {
    Field f;
    Bc bc;
    FvMatrix M;
    Fvm d;
} Op;

static int op_init(Op *o, const FvMesh *fm, const Interp *ip, const char *wall, Err *e)
{
    const char *ent[] = {wall, "\"(xMin|xMax|yMin|yMax)\" { type noSlip; }"};
    if (load_entries(&o->bc, &o->f, fm, "U", 3, ent, 2, e)) return -1;
    FvPattern pat;
    fvpattern_init(&pat, fm);
    fvm_pattern(&pat, fm, ip);
    fvmatrix_init(&o->M, &pat);
    return fvm_init(&o->d, &o->M, fm, ip, &o->bc, e);
}

static void op_free(Op *o)
{
    fvm_free(&o->d);
    fvmatrix_free(&o->M);
    bc_free(&o->bc);
    field_free(&o->f);
}

/* The diffusion operator of component k of u assembled on o: its values
   and right-hand side into val, rhs. */
static void op_assemble(Op *o, const double *u, int k, double *val, double *rhs)
{
    bc_update(&o->bc, u);
    fvmatrix_zero(&o->M);
    fvm_laplacian(&o->d, &o->M, k, 0.7);
    memcpy(val, o->M.val, sizeof(double) * (size_t)o->M.nnz);
    memcpy(rhs, o->M.rhs, sizeof(double) * (size_t)o->M.nrows);
}

/* On the merged cut disc (Shepard's stencils, whose rows reach the wall
   faces as sources): partialSlip with phi = 30 and no pressure assembles
   slip's matrix and right-hand side to the bit, and fvm_same_matrix sees
   the components' matrices differ (the curved normals); under a pressure
   that makes every face stick, noSlip's, and one matrix for all. */
TEST(partial_slip_assembly)
{
    Mesh m;
    disc_grid(&m, 16);
    FvMesh fm;
    Interp ip;
    InterpOpts io;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    interp_opts_default(&io);
    EXPECT(interp_init(&ip, &fm, &io, "test", &e) == 0, "%s", e.msg);
    if (test_failed_now) return;
    const char *walls[3] = {"d { type partialSlip; frictionAngle 30; }", "d { type slip; }", "d { type noSlip; }"};
    Op op[3];
    for (int t = 0; t < 3; t++) EXPECT(op_init(&op[t], &fm, &ip, walls[t], &e) == 0, "%s: %s", walls[t], e.msg);
    if (test_failed_now) return;
    double *u = mem_alloc(sizeof(double) * 3 * (size_t)fm.ncells);
    for (int c = 0; c < fm.ncells; c++) {
        const double *x = fm.node + 3 * c;
        u[3 * c] = sin(3 * x[0]) + x[1], u[3 * c + 1] = cos(2 * x[1]) - 0.4, u[3 * c + 2] = 0;
    }
    size_t nv = (size_t)op[0].M.nnz, nr = (size_t)op[0].M.nrows;
    double *val[3], *rhs[3];
    for (int t = 0; t < 3; t++) val[t] = mem_alloc(sizeof(double) * nv), rhs[t] = mem_alloc(sizeof(double) * nr);
    double *p = filled(fm.nboundary, 0), *eta = filled(fm.nboundary, 0.7);
    bc_set_wall_state(&op[0].bc, p, eta);
    int nf = 0, bad = 0;
    for (int k = 0; k < 2; k++) {
        for (int t = 0; t < 2; t++) op_assemble(&op[t], u, k, val[t], rhs[t]);
        bad += memcmp(val[0], val[1], nv * sizeof(double)) != 0 || memcmp(rhs[0], rhs[1], nr * sizeof(double)) != 0;
    }
    int slide = bc_slip_count(&op[0].bc, &nf);
    printf("  disc: %d partialSlip faces; without pressure %d slide, same matrix for x and y: %s\n", nf, slide,
           fvm_same_matrix(&op[0].d, 0, 1) ? "yes" : "no");
    EXPECT(nf > 20 && slide == nf, "%d of %d faces slide", slide, nf);
    EXPECT(bad == 0, "%d components differ from slip's assembly", bad);
    EXPECT(!fvm_same_matrix(&op[0].d, 0, 1) && !fvm_same_matrix(&op[1].d, 0, 1), "one matrix on a curved slip wall");
    for (int b = 0; b < fm.nboundary; b++) p[b] = 1e6;
    bad = 0;
    for (int k = 0; k < 2; k++) {
        op_assemble(&op[0], u, k, val[0], rhs[0]);
        op_assemble(&op[2], u, k, val[2], rhs[2]);
        bad += memcmp(val[0], val[2], nv * sizeof(double)) != 0 || memcmp(rhs[0], rhs[2], nr * sizeof(double)) != 0;
    }
    slide = bc_slip_count(&op[0].bc, NULL);
    printf("  disc: under p = 1e6 %d slide, same matrix for x and y: %s\n", slide,
           fvm_same_matrix(&op[0].d, 0, 1) ? "yes" : "no");
    EXPECT(slide == 0, "%d faces slide under p = 1e6", slide);
    EXPECT(bad == 0, "%d components differ from noSlip's assembly", bad);
    EXPECT(fvm_same_matrix(&op[0].d, 0, 1), "every face sticks, yet the components' matrices differ");
    for (int t = 0; t < 3; t++) {
        free(val[t]);
        free(rhs[t]);
        op_free(&op[t]);
    }
    free(u);
    free(p);
    free(eta);
    interp_free(&ip);
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* ---- rotatingWallVelocity ---- */

/* By hand on the 2 x 2 grid, the top's face normal (0 1 0), about the z
   axis through (0.5 0 0) at omega 2: omega x r at the face centres
   (0.25 0.5) and (0.75 0.5) is (-1 -0.5 0) and (-1 0.5 0), without the
   normal part (-1 0 0); a Dirichlet wall.  omega as OpenFOAM's Function1
   `constant 2` and a value entry (ignored) give the same. */
TEST(rotating_wall_by_hand)
{
    Mesh m;
    grid_small(&m);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *tops[2] = {"top { type rotatingWallVelocity; origin (0.5 0 0); axis (0 0 1); omega 2; }",
                           "top { type rotatingWallVelocity; origin (0.5 0 0); axis (0 0 3); omega constant 2; "
                           "value uniform (9 9 9); }"};
    for (int t = 0; t < 2; t++) {
        const char *ent[] = {"inlet { type fixedValue; value uniform (1 2 0); }", "outlet { type zeroGradient; }",
                             "bottom { type noSlip; }", tops[t], "frontAndBack { type empty; }"};
        Field f;
        Bc bc;
        EXPECT(load_entries(&bc, &f, &fm, "U", 3, ent, 5, &e) == 0, "%s", e.msg);
        if (test_failed_now) return;
        EXPECT(bc.patch[3].kind == BC_ROTATING_WALL, "kind %d", bc.patch[3].kind);
        EXPECT_FACES(&bc, &fm, "top", 0, 0, -1, -8, -8);
        EXPECT_FACES(&bc, &fm, "top", 1, 0, 0, -8, 0);
        EXPECT_FACES(&bc, &fm, "top", 2, 0, 0, -8, 0);
        NEAR(affine_mismatch(&bc, f.v), 0, 0);
        bc_free(&bc);
        field_free(&f);
    }
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* The cut disc of radius 0.27 rotating at omega 5 about the z axis (given
   as (0 0 2)) through its centre, and through a point beside it: at every
   wall face u_b . n = 0 with the exact normal, the tangential part
   omega x r . t, no z part, to 1e-12.  About the centre the face centres
   (the midpoints of the cut chords) lie inside the circle, on the radius
   that is their exact normal, so omega x r is tangential already and u_b
   is it, slower than the wall's omega R.  About the point beside the
   centre omega x r has a normal part, which the condition removes. */
TEST(rotating_wall_disc)
{
    Mesh m;
    disc_grid(&m, 24);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    static const double origin[2][3] = {{0.5, 0.5, 0}, {0.53, 0.48, 0}};
    for (int o = 0; o < 2; o++) {
        char wall[200];
        snprintf(wall, sizeof wall, "d { type rotatingWallVelocity; origin (%g %g 0); axis (0 0 2); omega 5; }",
                 origin[o][0], origin[o][1]);
        const char *ent[] = {wall, "\"(xMin|xMax|yMin|yMax)\" { type noSlip; }"};
        Field f;
        Bc bc;
        EXPECT(load_entries(&bc, &f, &fm, "U", 3, ent, 2, &e) == 0, "%s", e.msg);
        if (test_failed_now) return;
        EXPECT(m.boundary_normal != NULL, "the cut grid has no boundaryNormal");
        double *xb = mem_alloc(sizeof(double) * 3 * (size_t)fm.nboundary);
        bc_values(&bc, f.v, xb);
        const Patch *d = &m.patches[mesh_patch(&m, "d")];
        double wn = 0, wt = 0, wz = 0, whole = 0, pump = 0, off = 0;
        for (int i = 0; i < d->size; i++) {
            int fi = d->start + i, b = fi - fm.ninternal;
            const double *n = m.boundary_normal + 3 * b, *x = m.face_centre + 3 * fi, *u = xb + 3 * b;
            double r[3] = {x[0] - origin[o][0], x[1] - origin[o][1], 0}, t[3] = {-n[1], n[0], 0};
            double wr[3] = {-5 * r[1], 5 * r[0], 0}, dw[3] = {u[0] - wr[0], u[1] - wr[1], u[2] - wr[2]};
            wn = fmax(wn, fabs(geom_dot(u, n)));
            wt = fmax(wt, fabs(geom_dot(u, t) - geom_dot(wr, t)));
            wz = fmax(wz, fabs(u[2]));
            whole = fmax(whole, geom_norm(dw));
            pump = fmax(pump, fabs(geom_dot(wr, n)));
            off = fmax(off, 0.27 - hypot(x[0] - 0.5, x[1] - 0.5));
        }
        printf("  rotating disc, axis through (%g %g): %d faces, |u.n| <= %.2e, tangential error %.2e; omega x r "
               "has a normal part up to %.2e, |u_b - omega x r| <= %.2e; face centres up to %.2e inside the circle\n",
               origin[o][0], origin[o][1], d->size, wn, wt, pump, whole, off);
        EXPECT(d->size > 40, "%d wall faces", d->size);
        NEAR(wn, 0, 1e-12);
        NEAR(wt, 0, 1e-12);
        NEAR(wz, 0, 1e-12);
        if (o == 0) {
            NEAR(whole, 0, 1e-12);
            EXPECT(off > 1e-4, "the face centres lie on the circle (%.2e): the test shows nothing", off);
        } else {
            EXPECT(pump > 1e-2, "omega x r is tangential (%.2e): the test shows nothing", pump);
        }
        NEAR(affine_mismatch(&bc, f.v), 0, 0);
        free(xb);
        bc_free(&bc);
        field_free(&f);
    }
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* Which kinds are walls, and their names. */
TEST(wall_kinds)
{
    static const int wall[BC_NKINDS] = {[BC_NO_SLIP] = 1,        [BC_MOVING_WALL] = 1,  [BC_SLIP] = 1,
                                        [BC_SYMMETRY_PLANE] = 1, [BC_PARTIAL_SLIP] = 1, [BC_ROTATING_WALL] = 1};
    for (int k = 0; k < BC_NKINDS; k++) {
        EXPECT(bc_kind_wall((BcKind)k) == wall[k], "%s: bc_kind_wall %d", bc_kind_name((BcKind)k),
               bc_kind_wall((BcKind)k));
        EXPECT(!(bc_kind_wall((BcKind)k) && bc_kind_open((BcKind)k)), "%s: a wall and open", bc_kind_name((BcKind)k));
    }
    CONTAINS(bc_kind_name(BC_PARTIAL_SLIP), "partialSlip");
    CONTAINS(bc_kind_name(BC_ROTATING_WALL), "rotatingWallVelocity");
}

TEST(errors_walls)
{
#define WALL_REFUSED(width, top, text)                                                                      \
    REFUSED(width == 1 ? "T" : "U", width, 9, text,                                                       \
            width == 1 ? "inlet { type fixedValue; value uniform 1; }"                                     \
                       : "inlet { type fixedValue; value uniform (1 0 0); }",                              \
            "outlet { type zeroGradient; }",                                                               \
            width == 1 ? "bottom { type zeroGradient; }" : "bottom { type noSlip; }",                          \
            top, "frontAndBack { type empty; }")
    WALL_REFUSED(3, "top { type partialSlip; }",
                 "patch 'top' of field 'U': type partialSlip needs a frictionAngle entry (the wall friction angle "
                 "phi in degrees, 0 <= phi <= 90: 0 is slip, 90 no-slip)");
    WALL_REFUSED(3, "top { type partialSlip; valueFraction uniform 0.5; }",
                 "patch 'top' of field 'U': type partialSlip needs a frictionAngle entry (the wall friction angle "
                 "phi in degrees, 0 <= phi <= 90: 0 is slip, 90 no-slip); OpenFOAM's valueFraction is not read");
    WALL_REFUSED(3, "top { type partialSlip; frictionAngle 100; }",
                 "patch 'top' of field 'U': frictionAngle 100 is out of range: the wall friction angle is "
                 "0 <= phi <= 90 degrees");
    WALL_REFUSED(3, "top { type partialSlip; frictionAngle -1; }",
                 "patch 'top' of field 'U': frictionAngle -1 is out of range");
    WALL_REFUSED(3, "top { type partialSlip; frictionAngle thirty; }",
                 "patch 'top' of field 'U': frictionAngle must be a number (degrees)");
    WALL_REFUSED(3, "top { type partialSlip; frictionAngle 30; wallVelocity (1 0); }",
                 "patch 'top' of field 'U': wallVelocity must be a vector (ux uy uz)");
    WALL_REFUSED(1, "top { type partialSlip; frictionAngle 30; }",
                 "patch 'top': type partialSlip is for vector fields; field 'T' is a scalar field");
    WALL_REFUSED(3, "top { type rotatingWallVelocity; origin (0 0 0); axis (0 0 1); }",
                 "patch 'top' of field 'U': type rotatingWallVelocity needs omega, the angular velocity in rad/s");
    WALL_REFUSED(3, "top { type rotatingWallVelocity; origin (0 0 0); axis (0 0 1); omega table ((0 1)); }",
                 "patch 'top' of field 'U': type rotatingWallVelocity needs omega, the angular velocity in rad/s (a "
                 "number, or constant <number>)");
    WALL_REFUSED(3, "top { type rotatingWallVelocity; axis (0 0 1); omega 1; }",
                 "patch 'top' of field 'U': type rotatingWallVelocity needs origin (x y z)");
    WALL_REFUSED(3, "top { type rotatingWallVelocity; origin (0 0 0); axis (0 0 0); omega 1; }",
                 "patch 'top' of field 'U': rotatingWallVelocity's axis is (0 0 0)");
    WALL_REFUSED(1, "top { type rotatingWallVelocity; origin (0 0 0); axis (0 0 1); omega 1; }",
                 "patch 'top': type rotatingWallVelocity is for vector fields; field 'T' is a scalar field");
#undef WALL_REFUSED
}

/* ---- open boundaries (bc_check_open) ---- */

/* bc_check_open on fm with rho's and U's entries (n each) and sound speed
   c: its return value, the message into msg. */
static int check_open(const FvMesh *fm, const char *const *rho_ent, const char *const *u_ent, int n, double c,
                      char *msg)
{
    char *pr = field_file("rho", 1, rho_ent, n), *pu = field_file("U", 3, u_ent, n);
    Field fr, fu;
    Bc br, bu;
    Err e;
    int rc = -2;
    msg[0] = 0;
    if (load(&br, &fr, fm, pr, &e) || load(&bu, &fu, fm, pu, &e)) {
        snprintf(msg, ERR_MSG_MAX, "%s", e.msg);
        return rc;
    }
    rc = bc_check_open(&br, &bu, &fr, &fu, c, &e);
    if (rc) snprintf(msg, ERR_MSG_MAX, "%s", e.msg);
    bc_free(&br);
    bc_free(&bu);
    field_free(&fr);
    field_free(&fu);
    free(pr);
    free(pu);
    return rc;
}

/* On the 2 x 2 grid (inlet xMin, outlet xMax; outward normals -x, +x),
   c = 2: the well-posed pairs pass, walls with a fixed rho pass, a
   supersonic inflow with both fixed passes, and each ill-posed pair is
   refused at rho's entry naming U's and the counts (2 and 1 in 2-D). */
TEST(open_boundaries)
{
    Mesh m;
    grid_small(&m);
    FvMesh fm;
    Err e;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *ok_r[] = {"inlet { type zeroGradient; }", "outlet { type fixedValue; value uniform 1; }",
                          "bottom { type fixedValue; value uniform 1; }", "top { type zeroGradient; }",
                          "frontAndBack { type empty; }"};
    const char *ok_u[] = {"inlet { type fixedValue; value uniform (1 0.5 0); }", "outlet { type zeroGradient; }",
                          "bottom { type noSlip; }", "top { type slip; }", "frontAndBack { type empty; }"};
    char msg[ERR_MSG_MAX];
    const char *got = msg;
    EXPECT(check_open(&fm, ok_r, ok_u, 5, 2, msg) == 0, "well-posed pairs refused: %s", msg);
    /* rho fixed on the inlet too: subsonic (|u.n| = 1 < 2) */
    const char *fix_r[] = {"inlet { type fixedValue; value uniform 1; }", ok_r[1], ok_r[2], ok_r[3], ok_r[4]};
    EXPECT(check_open(&fm, fix_r, ok_u, 5, 2, msg) == -1, "both fixed at a subsonic inflow accepted");
    CONTAINS(got, ":6: patch 'inlet': rho (fixedValue) and U (fixedValue, ");
    CONTAINS(got, "U:6) are both fixed");
    CONTAINS(got, "takes 2 conditions at a subsonic inflow");
    CONTAINS(got, "never 3");
    /* supersonic at both faces: accepted; at one face only: refused */
    const char *sup_u[] = {"inlet { type fixedValue; value uniform (2 7 0); }", ok_u[1], ok_u[2], ok_u[3], ok_u[4]};
    EXPECT(check_open(&fm, fix_r, sup_u, 5, 2, msg) == 0, "a supersonic inflow refused: %s", msg);
    const char *half_u[] = {"inlet { type fixedValue; value nonuniform List<vector> 2((2 0 0) (1.99 0 0)); }", ok_u[1],
                            ok_u[2], ok_u[3], ok_u[4]};
    EXPECT(check_open(&fm, fix_r, half_u, 5, 2, msg) == -1, "an inflow subsonic at one face accepted");
    /* supersonic outward (an outflow fixed both ways): refused */
    const char *out_u[] = {"inlet { type fixedValue; value uniform (-3 0 0); }", ok_u[1], ok_u[2], ok_u[3], ok_u[4]};
    EXPECT(check_open(&fm, fix_r, out_u, 5, 2, msg) == -1, "both fixed at a supersonic outflow accepted");
    /* neither fixed on the outlet; a symmetryPlane rho counts as a zero gradient */
    const char *free_r[] = {ok_r[0], "outlet { type symmetryPlane; }", ok_r[2], ok_r[3], ok_r[4]};
    EXPECT(check_open(&fm, free_r, ok_u, 5, 2, msg) == -1, "neither fixed accepted");
    CONTAINS(got, ":7: patch 'outlet': neither rho (symmetryPlane) nor U (zeroGradient, ");
    CONTAINS(got, "needs 2 conditions at a subsonic inflow and 1");
    CONTAINS(got, "use fixedValue rho with zeroGradient U at an outflow");
    /* calculated is a fixed value */
    const char *calc_u[] = {ok_u[0], "outlet { type calculated; value uniform (1 0 0); }", ok_u[2], ok_u[3], ok_u[4]};
    EXPECT(check_open(&fm, ok_r, calc_u, 5, 2, msg) == -1, "calculated U with fixed rho accepted");
    CONTAINS(got, "rho (fixedValue) and U (calculated, ");
    fvmesh_free(&fm);
    mesh_free(&m);
}

/* A 3-D grid: the counts are d = 3 at an inflow, never 4. */
TEST(open_boundaries_3d)
{
    double xs[] = {0, 0.5, 1}, ys[] = {0, 1}, zs[] = {0, 1};
    double *x[3] = {xs, ys, zs};
    int n[3] = {2, 1, 1};
    BlockSide side[BLOCK_NSIDES] = {{"inlet", "patch", NULL}, {"outlet", "patch", NULL}, {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},  {"walls", "wall", NULL},   {"walls", "wall", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    FvMesh fm;
    EXPECT(fvmesh_init(&fm, &m, &e) == 0, "%s", e.msg);
    const char *r[] = {"inlet { type fixedValue; value uniform 1; }", "outlet { type fixedValue; value uniform 1; }",
                       "walls { type zeroGradient; }"};
    const char *u[] = {"inlet { type fixedValue; value uniform (1 0 0); }", "outlet { type zeroGradient; }",
                       "walls { type noSlip; }"};
    char msg[ERR_MSG_MAX];
    const char *got = msg;
    EXPECT(check_open(&fm, r, u, 3, 2.5, msg) == -1, "both fixed accepted in 3-D");
    CONTAINS(got, "takes 3 conditions at a subsonic inflow");
    CONTAINS(got, "never 4");
    CONTAINS(got, "u.n <= -sqrt(RsT) = -2.5");
    fvmesh_free(&fm);
    mesh_free(&m);
}

int main(void)
{
    RUN(vector_types);
    RUN(slip_by_hand);
    RUN(scalar_types);
    RUN(slip_cut_sphere);
    RUN(cyclic_block);
    RUN(inclined_channel);
    RUN(inclined_channel_unpaired);
    RUN(errors);
    RUN(errors_grid);
    RUN(errors_partner);
    RUN(open_boundaries);
    RUN(open_boundaries_3d);
    RUN(coulomb_nu);
    RUN(partial_slip_limits);
    RUN(partial_slip_regimes);
    RUN(partial_slip_rotation_3d);
    RUN(partial_slip_assembly);
    RUN(rotating_wall_by_hand);
    RUN(rotating_wall_disc);
    RUN(wall_kinds);
    RUN(errors_walls);
    return test_summary();
}
