/*
** test_bc.c: boundary conditions parsed once (fv/bc.h): every type's
** coefficients against hand values on a 2 x 2 grid; slip on a cut and
** merged sphere grid (zero normal velocity to round-off with the exact
** boundaryNormal); cyclic pairs on a graded periodic block grid and on the
** periodic inclined channel of thesis §5.1.3 (cut, and cut and merged);
** and every refusal with the field file and the line of the patch entry;
** the open boundaries an isothermal model may take (bc_check_open: one of
** rho and U fixed, both at a supersonic inflow), in 2-D and 3-D.
*/
#include "bc.h"
#include "cut.h"
#include "field.h"
#include "fixture.h"
#include "fvmesh.h"
#include "geom.h"
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
    return test_summary();
}
