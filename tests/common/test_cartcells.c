/*
** test_cartcells.c: the cut-cell data contract (cartcells.h) on grids cut
** and merged around a sphere and on a Voronoi grid: the roles partition
** the Cartesian grid and the volumes add up (mesh_check_cartesian),
** merging twice composes, the file round-trips exactly in every format,
** and a corrupted contract is caught and named.  Also mesh_cell_node.
**
** Numbers: a sphere of radius 0.3 in the unit box, flow outside, on
** 12^3 cells: every Cartesian cell is whole, cut or outside; merging at
** M_V = 1/2 and again at 0.9 makes masters and slaves, and the second
** merge's cells are the first's renamed by the second mergeMap.
*/
#include "cartcells.h"
#include "cut.h"
#include "fixture.h"
#include "io.h"
#include "merge.h"
#include "test.h"
#include "vgrid.h"

static const char sphere[] = "ball { flow outside; shape sphere; centre (0.5123 0.4871 0.5037); radius 0.3; }";

static void geometry_of(Mesh *m)
{
    mesh_cell_faces(m);
    mesh_geometry(m);
}

/* The grid of N^3 cells cut by the sphere (geometry filled). */
static void cut_sphere(Mesh *out, int N)
{
    Mesh grid;
    int n[3] = {N, N, N};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&grid, n, lo, hi, -1);
    FixtureGeo G;
    Err e;
    if (fixture_geo(&G, sphere) || cut_mesh(&grid, &G.g, NULL, out, NULL, &e)) exit(1);
    fixture_geo_free(&G);
    mesh_free(&grid);
    geometry_of(out);
}

static void merge_at(const Mesh *in, double threshold, Mesh *out)
{
    MergeOpts o;
    MergeStats st;
    Err e;
    merge_opts_default(&o);
    o.threshold = threshold;
    if (merge_mesh(in, &o, out, &st, &e)) {
        printf("merge_mesh: %s\n", e.msg);
        exit(1);
    }
    merge_stats_free(&st);
    geometry_of(out);
}

static void count_roles(const CartCells *cc, int count[CART_NROLES])
{
    memset(count, 0, sizeof(int) * CART_NROLES);
    for (int K = 0; K < cc->n; K++) count[cc->role[K]]++;
}

TEST(cut_contract)
{
    Mesh m;
    Err e;
    cut_sphere(&m, 12);
    const CartCells *cc = &m.cartcells;
    EXPECT(cc->n == 12 * 12 * 12, "%d Cartesian cells", cc->n);
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) == 0, "%s", e.msg);
    int count[CART_NROLES];
    count_roles(cc, count);
    EXPECT(count[CART_WHOLE] + count[CART_CUT] == m.ncells && count[CART_MASTER] + count[CART_SLAVE] == 0,
           "whole %d cut %d master %d slave %d for %d cells", count[CART_WHOLE], count[CART_CUT], count[CART_MASTER],
           count[CART_SLAVE], m.ncells);
    EXPECT(count[CART_OUTSIDE] > 0 && count[CART_CUT] > 0, "outside %d cut %d", count[CART_OUTSIDE], count[CART_CUT]);
    for (int c = 0; c < m.ncells; c++)
        EXPECT(cc->parent_off[c + 1] - cc->parent_off[c] == 1 && cc->parent[cc->parent_off[c]] == m.cell_parent[c],
               "cell %d: parents differ from cellParent", c);
    /* a cell with a face on the sphere is not whole */
    int ball = m.npatches - 1;
    for (int f = m.patches[ball].start; f < m.patches[ball].start + m.patches[ball].size; f++)
        EXPECT(cc->role[m.cell_parent[m.owner[f]]] == CART_CUT, "cell %d on the sphere is not cut", m.owner[f]);
    mesh_free(&m);
}

TEST(merge_twice_composes)
{
    Mesh cut, m1, m2;
    Err e;
    cut_sphere(&cut, 12);
    merge_at(&cut, 0.5, &m1);
    merge_at(&m1, 0.9, &m2);
    int c1[CART_NROLES], c2[CART_NROLES];
    count_roles(&m1.cartcells, c1);
    count_roles(&m2.cartcells, c2);
    EXPECT(mesh_check_cartesian(&m1, CARTCELLS_TOL, &e) == 0, "first merge: %s", e.msg);
    EXPECT(mesh_check_cartesian(&m2, CARTCELLS_TOL, &e) == 0, "second merge: %s", e.msg);
    EXPECT(c1[CART_MASTER] > 0 && c1[CART_SLAVE] >= c1[CART_MASTER], "first: %d masters, %d slaves", c1[CART_MASTER],
           c1[CART_SLAVE]);
    EXPECT(c2[CART_SLAVE] > c1[CART_SLAVE], "second merge made no new slaves (%d, %d)", c1[CART_SLAVE], c2[CART_SLAVE]);
    for (int K = 0; K < m2.cartcells.n; K++) {
        int a = m1.cartcells.cell[K], b = m2.cartcells.cell[K];
        EXPECT(a < 0 ? b < 0 : b == m2.merge_map[a], "Cartesian cell %d: cell %d then %d", K, a, b);
        if (m1.cartcells.role[K] == CART_SLAVE) EXPECT(m2.cartcells.role[K] == CART_SLAVE, "slave %d promoted", K);
        if (b >= 0 && m2.cartcells.role[K] == CART_MASTER)
            EXPECT(m2.cell_parent[b] == K, "master %d is not cellParent %d", K, m2.cell_parent[b]);
    }
    mesh_free(&cut);
    mesh_free(&m1);
    mesh_free(&m2);
}

static int same_cartcells(const Mesh *a, const Mesh *b)
{
    const CartCells *x = &a->cartcells, *y = &b->cartcells;
    size_t n = (size_t)x->n, nc = (size_t)a->ncells;
    return x->n == y->n && a->ncells == b->ncells && y->role && !memcmp(x->role, y->role, n * sizeof(int)) &&
           !memcmp(x->cell, y->cell, n * sizeof(int)) && !memcmp(x->vol, y->vol, n * sizeof(double)) &&
           !memcmp(x->parent_off, y->parent_off, (nc + 1) * sizeof(int)) &&
           !memcmp(x->parent, y->parent, (size_t)x->parent_off[nc] * sizeof(int));
}

static void round_trip(int binary, int gzip, int stream, const char *name)
{
    Mesh cut, m, r;
    Err e;
    cut_sphere(&cut, 8);
    merge_at(&cut, 0.5, &m);
    MeshWriteOpts o = {binary, gzip};
    int rc;
    mesh_init(&r);
    if (stream) {
        Buf b;
        buf_init(&b);
        rc = mesh_write_stream(&m, &b, &o, &e) || mesh_read_stream(&r, b.p, b.n, name, &e);
        buf_free(&b);
    } else {
        char *dir = io_join(test_tmpdir(), name), *f = io_join(dir, gzip ? "cartesianCells.gz" : "cartesianCells");
        rc = mesh_write(&m, dir, &o, &e) || !io_exists(f) || mesh_read(&r, dir, &e);
        free(dir);
        free(f);
    }
    EXPECT(!rc, "%s: %s", name, e.msg);
    EXPECT(!rc && same_cartcells(&m, &r), "%s: cartesianCells differ after the round trip", name);
    mesh_free(&cut);
    mesh_free(&m);
    mesh_free(&r);
}

TEST(round_trip_ascii) { round_trip(0, 0, 0, "cc_ascii"); }
TEST(round_trip_binary) { round_trip(1, 0, 0, "cc_binary"); }
TEST(round_trip_gzip) { round_trip(0, 1, 0, "cc_gzip"); }
TEST(round_trip_binary_gzip) { round_trip(1, 1, 0, "cc_binary_gzip"); }
TEST(round_trip_stream) { round_trip(0, 0, 1, "cc_stream"); }
TEST(round_trip_stream_binary_gzip) { round_trip(1, 1, 1, "cc_stream_bgz"); }

/* The first Cartesian cell of role r, or -1. */
static int first_of(const CartCells *cc, int r)
{
    for (int K = 0; K < cc->n; K++)
        if (cc->role[K] == r) return K;
    return -1;
}

/* Each corruption must fail the check with a message naming it. */
TEST(check_catches)
{
    Mesh cut, m;
    Err e;
    char want[64];
    cut_sphere(&cut, 8);
    merge_at(&cut, 0.5, &m);
    CartCells *cc = &m.cartcells;
    int S = first_of(cc, CART_SLAVE), W = first_of(cc, CART_WHOLE), M = first_of(cc, CART_MASTER);
    EXPECT(S >= 0 && W >= 0 && M >= 0, "roles missing: slave %d whole %d master %d", S, W, M);

    cc->role[S] = CART_CUT; /* a slave called cut */
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) != 0, "slave %d as cut passed", S);
    snprintf(want, sizeof want, "cell %d has", cc->cell[S]);
    CONTAINS(e.msg, want);
    cc->role[S] = CART_SLAVE;

    cc->role[M] = CART_SLAVE; /* a cluster without master */
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) != 0, "cluster without master passed");
    CONTAINS(e.msg, "0 masters");
    cc->role[M] = CART_MASTER;

    double vw = cc->vol[W];
    cc->vol[W] *= 1 - 1e-9; /* a whole part that is not its box */
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) != 0, "whole volume passed");
    snprintf(want, sizeof want, "Cartesian cell %d (", W);
    CONTAINS(e.msg, want);
    cc->vol[W] = vw;

    double vs = cc->vol[S];
    cc->vol[S] *= 0.5; /* parts that do not add up */
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) != 0, "wrong slave volume passed");
    CONTAINS(e.msg, "sum to");
    cc->vol[S] = vs;

    int c = cc->cell[W], other = cc->cell[M];
    cc->cell[W] = other; /* a Cartesian cell naming a cell that does not list it */
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) != 0, "wrong cell passed");
    cc->cell[W] = c;
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) == 0, "restored: %s", e.msg);
    mesh_free(&cut);
    mesh_free(&m);
}

/* A file with a role out of range is refused on reading, naming it. */
TEST(read_refuses_bad_role)
{
    Mesh m, r;
    Err e;
    cut_sphere(&m, 4);
    char *dir = io_join(test_tmpdir(), "cc_bad"), *f = io_join(dir, "cartesianCells");
    MeshWriteOpts o = {0, 0};
    EXPECT(mesh_write(&m, dir, &o, &e) == 0, "%s", e.msg);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(f, &b, NULL, &e) == 0, "%s", e.msg);
    char *p = strstr(b.p, "role");
    p = p ? strstr(p, "(\n") : NULL;
    EXPECT(p != NULL, "no role list");
    if (p) p[2] = '7';
    EXPECT(io_write_atomic(f, b.p, b.n, 0, &e) == 0, "%s", e.msg);
    mesh_init(&r);
    EXPECT(mesh_read(&r, dir, &e) != 0, "role 7 was read");
    CONTAINS(e.msg, "cartesianCells");
    CONTAINS(e.msg, "role: label 0 is 7");
    buf_free(&b);
    mesh_free(&m);
    mesh_free(&r);
    free(dir);
    free(f);
}

/* The sphere cut by the mid-plane, flow outside, on a 2-D Voronoi grid: one parent per cell,
   holding its seed; whole Cartesian cells hold their own centre. */
TEST(voronoi_contract)
{
    Mesh grid, v;
    Err e;
    int n[3] = {16, 16, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1.0 / 16};
    fixture_block(&grid, n, lo, hi, 2);
    FixtureGeo G;
    if (fixture_geo(&G, "disc { flow outside; shape sphere; centre (0.5123 0.4871 0.03125); radius 0.3; }")) exit(1);
    SeedOpts so;
    seeds_opts_default(&so);
    so.layers = 1;
    VGridStats st;
    EXPECT(vgrid_mesh(&grid, &G.g, &so, &v, &st, &e) == 0, "%s", e.msg);
    const CartCells *cc = &v.cartcells;
    EXPECT(cc->n == 256 && v.cart.n[0] == 16, "%d Cartesian cells", cc->n);
    EXPECT(mesh_check_cartesian(&v, CARTCELLS_TOL, &e) == 0, "%s", e.msg);
    int count[CART_NROLES];
    count_roles(cc, count);
    EXPECT(count[CART_WHOLE] > 0 && count[CART_CUT] > 0 && count[CART_OUTSIDE] > 0 && !count[CART_MASTER] &&
               !count[CART_SLAVE], "whole %d cut %d outside %d", count[CART_WHOLE], count[CART_CUT],
           count[CART_OUTSIDE]);
    for (int c = 0; c < v.ncells; c++) {
        int K = cc->parent[cc->parent_off[c]], i = K % 16, j = K / 16;
        const double *s = mesh_cell_node(&v, c);
        EXPECT(s == v.cell_seed + 3 * c, "cell %d: node is not its seed", c);
        EXPECT(s[0] >= i / 16.0 && s[0] <= (i + 1) / 16.0 && s[1] >= j / 16.0 && s[1] <= (j + 1) / 16.0,
               "cell %d: seed (%g %g) outside its parent %d", c, s[0], s[1], K);
        if (cc->role[K] == CART_WHOLE)
            EXPECT(fabs(s[0] - (i + 0.5) / 16) < 1e-15 && fabs(s[1] - (j + 0.5) / 16) < 1e-15,
                   "whole %d: seed off its centre", K);
    }
    fixture_geo_free(&G);
    mesh_free(&grid);
    mesh_free(&v);
}

TEST(cell_node_is_centroid_without_seeds)
{
    Mesh m;
    cut_sphere(&m, 4);
    EXPECT(!m.cell_seed, "a cut grid has seeds");
    for (int c = 0; c < m.ncells; c++) EXPECT(mesh_cell_node(&m, c) == m.cell_centre + 3 * c, "cell %d", c);
    EXPECT(mesh_cell_node(&m, -1) == NULL && mesh_cell_node(&m, m.ncells) == NULL, "out of range");
    mesh_free(&m);
}

int main(void)
{
    RUN(cut_contract);
    RUN(merge_twice_composes);
    RUN(round_trip_ascii);
    RUN(round_trip_binary);
    RUN(round_trip_gzip);
    RUN(round_trip_binary_gzip);
    RUN(round_trip_stream);
    RUN(round_trip_stream_binary_gzip);
    RUN(check_catches);
    RUN(read_refuses_bad_role);
    RUN(voronoi_contract);
    RUN(cell_node_is_centroid_without_seeds);
    return test_summary();
}
