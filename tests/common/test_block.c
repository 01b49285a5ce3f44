/*
** test_block.c: block grids: counts, grading, face order, orientation,
** volumes, and blockGridDict validation messages.
*/
#include "block.h"
#include "geom.h"
#include "mesh.h"
#include "test.h"

/* Parses text as blockGridDict "test/blockGridDict" and builds the mesh;
   returns 0, or -1 with e filled. */
static int build(const char *text, Mesh *m, BlockSpec *s, Err *e)
{
    Dict *d = dict_parse(text, strlen(text), "test/blockGridDict", e);
    if (!d) return -1;
    int rc = block_read(s, d, e);
    mesh_init(m);
    if (!rc) rc = block_build(s, m, e);
    if (!rc) block_free(s);
    dict_free(d);
    return rc;
}

static const char *dict2d =
    "x { start -1; segments ((0 4 1) (2 6 3)); }\n"
    "y { segments ((1 5 1)); }\n"
    "z { segments ((0.1 1 1)); }\n"
    "boundary\n{\n"
    "    yMax { name top; type patch; }\n"
    "    zMin { name frontAndBack; type empty; }\n"
    "    zMax { name frontAndBack; type empty; }\n"
    "    xMin { name walls; }\n"
    "    xMax { name walls; type wall; }\n"
    "}\n";

TEST(counts_2d)
{
    Mesh m;
    BlockSpec s;
    Err e;
    EXPECT(!build(dict2d, &m, &s, &e), "%s", e.msg);
    if (test_failed_now) return;
    EXPECT(m.ncells == 50, "ncells %d", m.ncells);
    EXPECT(m.npoints == 11 * 6 * 2, "npoints %d", m.npoints);
    EXPECT(m.ninternal == 9 * 5 + 10 * 4, "ninternal %d", m.ninternal);
    EXPECT(m.nfaces == 85 + 2 * (5 + 10 + 50), "nfaces %d", m.nfaces);
    /* patch order: as listed (top, frontAndBack, walls), then yMin */
    EXPECT(m.npatches == 4, "npatches %d", m.npatches);
    const char *names[] = {"top", "frontAndBack", "walls", "yMin"};
    const int sizes[] = {10, 100, 10, 10};
    const char *types[] = {"patch", "empty", "wall", "wall"};
    for (int p = 0; p < 4 && p < m.npatches; p++) {
        EXPECT(!strcmp(m.patches[p].name, names[p]), "patch %d is %s", p, m.patches[p].name);
        EXPECT(!strcmp(m.patches[p].type, types[p]), "patch %d type %s", p, m.patches[p].type);
        EXPECT(m.patches[p].size == sizes[p], "patch %d size %d", p, m.patches[p].size);
    }
    EXPECT(mesh_empty_axis(&m) == 2, "empty axis %d", mesh_empty_axis(&m));
    EXPECT(m.cart.n[0] == 10 && m.cart.n[1] == 5 && m.cart.n[2] == 1, "cart n");
    NEAR(m.cart.x[0][0], -1, 0);
    NEAR(m.cart.x[0][4], 0, 0);
    NEAR(m.cart.x[0][10], 2, 0);
    mesh_free(&m);
}

static const char *dict3d = "scale 0.5;\n"
                            "x { segments ((1 4 2)); }\n"
                            "y { segments ((1 1 1) (3 2 0.5)); }\n"
                            "z { start 1; segments ((3 2 1)); }\n";

TEST(counts_3d_defaults)
{
    Mesh m;
    BlockSpec s;
    Err e;
    EXPECT(!build(dict3d, &m, &s, &e), "%s", e.msg);
    if (test_failed_now) return;
    EXPECT(m.ncells == 24 && m.npoints == 60, "ncells %d npoints %d", m.ncells, m.npoints);
    EXPECT(m.ninternal == 46 && m.nfaces == 98, "ninternal %d nfaces %d", m.ninternal, m.nfaces);
    EXPECT(m.npatches == 6, "npatches %d", m.npatches);
    const int sizes[] = {6, 6, 8, 8, 12, 12};
    for (int p = 0; p < 6 && p < m.npatches; p++) {
        EXPECT(!strcmp(m.patches[p].name, block_side_names[p]), "patch %d is %s", p, m.patches[p].name);
        EXPECT(!strcmp(m.patches[p].type, "wall"), "patch %d type %s", p, m.patches[p].type);
        EXPECT(m.patches[p].size == sizes[p], "patch %d size %d", p, m.patches[p].size);
    }
    EXPECT(mesh_empty_axis(&m) == -1, "3-D grid has empty axis");
    double lo[3], hi[3];
    mesh_bounds(&m, lo, hi);
    NEAR(lo[0], 0, 0);
    NEAR(hi[0], 0.5, 0);
    NEAR(lo[2], 0.5, 0);
    NEAR(hi[1], 1.5, 0);
    NEAR(hi[2], 1.5, 0);
    mesh_free(&m);
}

/* Widths of a graded segment: last/first = grading, sum = length. */
TEST(grading)
{
    const double g[] = {4, 0.25, 1, 1e3, 1 + 1e-13, 7};
    const int n[] = {10, 20, 7, 50, 30, 2};
    double t[64];
    for (int c = 0; c < 6; c++) {
        double len = 0.5 + c;
        block_grade(len, n[c], g[c], t);
        double sum = 0;
        for (int i = 0; i < n[c]; i++) sum += t[i + 1] - t[i];
        NEAR(sum, len, 1e-14 * len);
        NEAR(t[n[c]], len, 0);
        double r = (t[n[c]] - t[n[c] - 1]) / (t[1] - t[0]);
        NEAR(r / g[c], 1, 1e-14);
        /* constant ratio between neighbours: q = g^(1/(n-1)) */
        double q = pow(g[c], 1.0 / (n[c] - 1));
        for (int i = 1; i < n[c]; i++) NEAR((t[i + 1] - t[i]) / (t[i] - t[i - 1]), q, 1e-12);
    }
    block_grade(2, 1, 5, t);
    NEAR(t[1], 2, 0);
}

/* The same through a dictionary: graded x axis of the mesh. */
TEST(graded_axis)
{
    Mesh m;
    BlockSpec s;
    Err e;
    const char *txt = "x { start 0; segments ((0.5 10 1) (1 20 4)); }\n"
                      "y { segments ((1 3 1)); } z { segments ((1 2 0.2)); }\n";
    EXPECT(!build(txt, &m, &s, &e), "%s", e.msg);
    if (test_failed_now) return;
    const double *x = m.cart.x[0];
    EXPECT(m.cart.n[0] == 30, "nx %d", m.cart.n[0]);
    for (int i = 0; i < 10; i++) NEAR(x[i + 1] - x[i], 0.05, 1e-15);
    NEAR(x[10], 0.5, 0);
    NEAR(x[30], 1, 0);
    NEAR((x[30] - x[29]) / (x[11] - x[10]), 4, 4e-14);
    const double *z = m.cart.x[2];
    NEAR((z[2] - z[1]) / (z[1] - z[0]), 0.2, 1e-15);
    mesh_free(&m);
}

/* mesh_check, exact total volume, and the face order and orientation. */
TEST(invariants)
{
    Mesh m;
    BlockSpec s;
    Err e;
    const char *txt = "x { start -1; segments ((0 3 2) (2 4 0.5)); }\n"
                      "y { segments ((1 5 3)); } z { start 0.25; segments ((1 4 1)); }\n";
    EXPECT(!build(txt, &m, &s, &e), "%s", e.msg);
    if (test_failed_now) return;
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    EXPECT(!mesh_check(&m, &e), "mesh_check: %s", e.msg);
    double vol = 0;
    for (int c = 0; c < m.ncells; c++) vol += m.cell_vol[c];
    NEAR(vol, 3 * 1 * 0.75, 1e-14);
    int nx = 7, ny = 5;
    /* internal faces: owner c, neighbours c+1, c+nx, c+nx*ny in turn */
    for (int f = 0; f < m.ninternal; f++) {
        int o = m.owner[f], n = m.neighbour[f], d = n - o;
        EXPECT(d == 1 || d == nx || d == nx * ny, "face %d: %d -> %d", f, o, n);
        if (f) EXPECT(o > m.owner[f - 1] || (o == m.owner[f - 1] && n > m.neighbour[f - 1]),
                      "face %d out of order", f);
        const double *S = m.face_area + 3 * f;
        double dd[3] = {m.cell_centre[3 * n] - m.cell_centre[3 * o],
                        m.cell_centre[3 * n + 1] - m.cell_centre[3 * o + 1],
                        m.cell_centre[3 * n + 2] - m.cell_centre[3 * o + 2]};
        EXPECT(geom_dot(dd, S) > 0, "face %d points into its owner", f);
    }
    /* boundary faces point out along the side's axis; owners increase */
    for (int p = 0; p < m.npatches; p++) {
        int a = p / 2, sign = p % 2 ? 1 : -1;
        for (int f = m.patches[p].start; f < m.patches[p].start + m.patches[p].size; f++) {
            const double *S = m.face_area + 3 * f;
            EXPECT(S[a] * sign > 0 && S[(a + 1) % 3] == 0 && S[(a + 2) % 3] == 0,
                   "patch %d face %d: S = (%g %g %g)", p, f, S[0], S[1], S[2]);
            if (f > m.patches[p].start) EXPECT(m.owner[f] > m.owner[f - 1], "face %d owner order", f);
        }
    }
    for (int c = 0; c < m.ncells; c++) EXPECT(m.cell_parent[c] == c, "cellParent %d", c);
    mesh_free(&m);
}

TEST(cyclic)
{
    Mesh m;
    BlockSpec s;
    Err e;
    const char *txt = "x { segments ((1 3 1)); } y { segments ((2 4 2)); } z { segments ((1 1 1)); }\n"
                      "boundary {\n"
                      "  xMin { name left; type cyclic; neighbourPatch right; }\n"
                      "  xMax { name right; type cyclic; neighbourPatch left; }\n"
                      "  zMin { name fb; type empty; } zMax { name fb; type empty; }\n}\n";
    EXPECT(!build(txt, &m, &s, &e), "%s", e.msg);
    if (test_failed_now) return;
    EXPECT(m.npatches == 5, "npatches %d", m.npatches);
    int l = mesh_patch(&m, "left"), r = mesh_patch(&m, "right");
    EXPECT(l == 0 && r == 1, "left %d right %d", l, r);
    EXPECT(m.patches[l].size == 4 && m.patches[r].size == 4, "cyclic sizes");
    EXPECT(m.patches[l].neighbour && !strcmp(m.patches[l].neighbour, "right"), "left's neighbour");
    /* face i of left and right are the same y-interval, owners 2 apart */
    for (int i = 0; i < 4; i++) {
        int fl = m.patches[l].start + i, fr = m.patches[r].start + i;
        EXPECT(m.owner[fr] - m.owner[fl] == 2, "pair %d owners %d %d", i, m.owner[fl], m.owner[fr]);
    }
    mesh_free(&m);
}

/* Each bad dictionary: block_read fails with "file:line: text". */
static void bad(const char *txt, const char *expect)
{
    Mesh m;
    BlockSpec s;
    Err e;
    e.msg[0] = 0;
    int rc = build(txt, &m, &s, &e);
    EXPECT(rc == -1, "accepted: %s", txt);
    CONTAINS(e.msg, expect);
    if (rc == 0) mesh_free(&m);
}

#define AXES_YZ "y { segments ((1 1 1)); }\nz { segments ((1 1 1)); }\n"

TEST(bad_dicts)
{
    bad("x { segments ((1 2 1) (1 2 1)); }\n" AXES_YZ, "test/blockGridDict:1: x: segment 2 ends at 1");
    bad("x { start 2; segments ((1 2 1)); }\n" AXES_YZ, "test/blockGridDict:1: x: segment 1 ends at 1, not after 2");
    /* a list of numbers is stored compactly: its line is where it opens */
    bad("x { segments\n(\n(1 2 1)\n(2 0 1)\n); }\n" AXES_YZ, ":2: x: segment 2: cells must be an integer >= 1");
    bad("x { segments ((1 2.5 1)); }\n" AXES_YZ, ":1: x: segment 1: cells must be an integer");
    bad("x { segments ((1 2 0)); }\n" AXES_YZ, ":1: x: segment 1: grading must be > 0, found 0");
    bad("x { segments ((1 2 -1)); }\n" AXES_YZ, "grading must be > 0, found -1");
    bad("x { segments ((1 2)); }\n" AXES_YZ, "test/blockGridDict:1:");
    bad("x { segments (); }\n" AXES_YZ, ":1: x: segments is empty");
    bad("x { start 0; }\n" AXES_YZ, ":1: x: keyword 'segments' is missing");
    bad("x { segmnts ((1 1 1)); }\n" AXES_YZ, "did you mean 'segments'");
    bad(AXES_YZ, "'x'");
    bad("scale -1;\nx { segments ((1 1 1)); }\n" AXES_YZ, ":1: scale must be > 0");
    bad("scael 2;\nx { segments ((1 1 1)); }\n" AXES_YZ, "did you mean 'scale'");
    const char *axes = "x { segments ((1 2 1)); }\n" AXES_YZ;
    char txt[1024];
    snprintf(txt, sizeof txt, "%sboundary {\n xmin { type wall; }\n}\n", axes);
    bad(txt, ":5: unknown keyword 'xmin'");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { type wal; }\n}\n", axes);
    bad(txt, ":5:");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { name a; type wall; }\n yMin { name a; type patch; }\n}\n", axes);
    bad(txt, ":6: boundary yMin: patch 'a' is patch here but wall on side xMin");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { type empty; }\n xMax { type empty; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: empty side needs exactly 1 cell along x, found 2");
    snprintf(txt, sizeof txt, "%sboundary {\n zMin { type empty; }\n}\n", axes);
    bad(txt, ":5: boundary zMin: empty side needs zMax empty too");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { type cyclic; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: cyclic patch 'xMin' needs neighbourPatch");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { name l; type cyclic; neighbourPatch r; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: neighbourPatch 'r' of cyclic patch 'l' is not a patch");
    snprintf(txt, sizeof txt,
             "%sboundary {\n xMin { name l; type cyclic; neighbourPatch r; }\n"
             " yMin { name r; type cyclic; neighbourPatch l; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: cyclic patch 'l' must pair with the opposite side xMax, not yMin");
    snprintf(txt, sizeof txt,
             "%sboundary {\n xMin { name l; type cyclic; neighbourPatch r; }\n"
             " xMax { name r; type wall; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: partner 'r' (xMax) of cyclic patch 'l' must be cyclic");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { type wall; neighbourPatch r; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: neighbourPatch is only for cyclic patches");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { name \"a b\"; }\n}\n", axes);
    bad(txt, ":5: boundary xMin: invalid patch name 'a b'");
    snprintf(txt, sizeof txt, "%sboundary {\n xMin { nmae a; }\n}\n", axes);
    bad(txt, "did you mean 'name'");
}

/* block_mesh directly: validation without a dictionary. */
TEST(block_mesh_direct)
{
    double x0[] = {0, 1, 2}, x1[] = {0, 1}, x2[] = {0, 2, 1};
    double *x[3] = {x0, x1, x2};
    int n[3] = {2, 1, 2};
    BlockSide side[6];
    for (int k = 0; k < 6; k++) side[k] = (BlockSide){block_side_names[k], "wall", NULL};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "here", NULL, &e) == -1, "decreasing z accepted");
    CONTAINS(e.msg, "here: z: point 2 (1) does not follow point 1 (2)");
    x2[2] = 3;
    side[1].type = "bogus";
    EXPECT(block_mesh(&m, x, n, side, NULL, "here", NULL, &e) == -1, "bogus type accepted");
    CONTAINS(e.msg, "here: boundary xMax: unknown patch type 'bogus'");
    side[1].type = "symmetryPlane";
    EXPECT(!block_mesh(&m, x, n, side, NULL, NULL, NULL, &e), "%s", e.msg);
    EXPECT(m.ncells == 4 && m.nfaces == 4 + 2 * (2 + 4 + 2), "counts %d %d", m.ncells, m.nfaces);
    mesh_free(&m);
}

int main(void)
{
    RUN(counts_2d);
    RUN(counts_3d_defaults);
    RUN(grading);
    RUN(graded_axis);
    RUN(invariants);
    RUN(cyclic);
    RUN(bad_dicts);
    RUN(block_mesh_direct);
    return test_summary();
}
