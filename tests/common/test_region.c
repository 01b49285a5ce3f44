/*
** test_region.c: shapes and cell volume fractions (region.c).
**
** Grids come from block_mesh (the blockGrid mesher) with graded,
** irregular spacing so that no shape face lines up with grid lines by
** accident.  The sum over cells of fraction * volume is compared with the
** analytic volume of the shape (or of its intersection with the domain).
*/
#include "fixture.h"
#include "test.h"

#include "block.h"
#include "mem.h"
#include "mesh.h"
#include "region.h"

static const double PI_ = 3.14159265358979323846;

/* Grid of n[k] cells per axis on [lo, hi], point k spaced with a smooth
   grading (stretch = 0 gives uniform spacing). */
static void make_grid(Mesh *m, const int n[3], const double lo[3], const double hi[3], double stretch)
{
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) {
            double s = (double)i / n[k];
            s += stretch * s * (1 - s) * (1 + 0.3 * k);
            x[k][i] = lo[k] + (hi[k] - lo[k]) * s;
        }
        x[k][n[k]] = hi[k];
    }
    fixture_mesh(m, x, n);
    for (int k = 0; k < 3; k++) free(x[k]);
}

static double shape_volume(const Region *r, const Mesh *m)
{
    double s = 0;
    for (int c = 0; c < m->ncells; c++) s += region_fraction(r, m, c) * m->cell_vol[c];
    return s;
}

static double mesh_volume(const Mesh *m)
{
    double s = 0;
    for (int c = 0; c < m->ncells; c++) s += m->cell_vol[c];
    return s;
}

TEST(box_exact)
{
    Mesh m;
    make_grid(&m, (int[]){7, 5, 6}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.6);
    /* Box corners anywhere (cut cells on all six sides). */
    Region r = {REGION_BOX, {0.137, 0.291, 0.0731}, {0.8123, 0.7777, 0.66}, 0, 0, 0, 0};
    EXPECT(region_check(&r) == NULL, "box rejected");
    NEAR(shape_volume(&r, &m), region_volume(&r), 1e-12);
    /* A box sticking out of the domain: the intersection is counted. */
    Region out = {REGION_BOX, {-0.5, 0.31, 0.2}, {0.43, 1.7, 0.9}, 0, 0, 0, 0};
    NEAR(shape_volume(&out, &m), 0.43 * 0.69 * 0.7, 1e-12);
    /* A box on grid lines: whole cells only. */
    Region on = {REGION_BOX, {0, 0, 0}, {1, 1, 1}, 0, 0, 0, 0};
    NEAR(shape_volume(&on, &m), mesh_volume(&m), 1e-12);
    /* One cell cut by a box corner: product of the overlaps. */
    int c = 3 + 7 * (2 + 5 * 3);
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = m.cart.x[k][(int[]){3, 2, 3}[k]];
        hi[k] = m.cart.x[k][(int[]){3, 2, 3}[k] + 1];
    }
    Region corner = {REGION_BOX,
                     {lo[0] + 0.3 * (hi[0] - lo[0]), lo[1] - 1, lo[2] + 0.75 * (hi[2] - lo[2])},
                     {hi[0] + 1, lo[1] + 0.4 * (hi[1] - lo[1]), hi[2] + 1}, 0, 0, 0, 0};
    NEAR(region_fraction(&corner, &m, c), 0.7 * 0.4 * 0.25, 1e-13);
    mesh_free(&m);
}

TEST(half_space_exact)
{
    Mesh m;
    make_grid(&m, (int[]){6, 7, 5}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.5);
    /* x + y + z <= 1: the corner tetrahedron, volume 1/6. */
    Region t = {REGION_HALFSPACE, {1, 0, 0}, {1, 1, 1}, 0, 0, 0, 0};
    EXPECT(region_check(&t) == NULL, "halfSpace rejected");
    NEAR(shape_volume(&t, &m), 1.0 / 6.0, 1e-12);
    /* x + y <= 1: half the cube. */
    Region p = {REGION_HALFSPACE, {0.5, 0.5, 0.2}, {2, 2, 0}, 0, 0, 0, 0};
    region_check(&p);
    NEAR(shape_volume(&p, &m), 0.5, 1e-12);
    /* Any plane through the cube's centre halves it (point symmetry). */
    Region s = {REGION_HALFSPACE, {0.5, 0.5, 0.5}, {-1, 2, 3}, 0, 0, 0, 0};
    region_check(&s);
    NEAR(shape_volume(&s, &m), 0.5, 1e-12);
    /* The normal points out of the region. */
    EXPECT(region_inside(&s, (double[]){0.5, 0.4, 0.4}), "below the plane is inside");
    EXPECT(!region_inside(&s, (double[]){0.5, 0.6, 0.6}), "above the plane is outside");
    mesh_free(&m);
}

/* Sphere volume over N^3 grids: second-order convergence. */
TEST(sphere_convergence)
{
    Region r = {REGION_SPHERE, {0.51, 0.47, 0.53}, {0, 0, 0}, 0.3, 0, 0, 0};
    double exact = region_volume(&r), err[3];
    int N[3] = {8, 16, 32};
    printf("  sphere r = 0.3, depth %d: N, |V - 4/3 pi r^3| / V, order\n", REGION_DEPTH);
    for (int i = 0; i < 3; i++) {
        Mesh m;
        make_grid(&m, (int[]){N[i], N[i], N[i]}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0);
        err[i] = fabs(shape_volume(&r, &m) - exact) / exact;
        if (i) printf("  %3d  %.3e  %.2f\n", N[i], err[i], log2(err[i - 1] / err[i]));
        else printf("  %3d  %.3e\n", N[i], err[i]);
        mesh_free(&m);
    }
    double order = log2(err[0] / err[2]) / 2;
    printf("  observed order (8 -> 32): %.2f\n", order);
    EXPECT(order > 1.7, "observed order %.2f", order);
    EXPECT(err[2] < 6e-5, "finest relative error %.3e", err[2]);
}

TEST(cylinder_cone_volume)
{
    Mesh m;
    make_grid(&m, (int[]){20, 20, 20}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.4);
    /* Oblique axes, ends inside the domain. */
    Region cyl = {REGION_CYLINDER, {0.2, 0.25, 0.3}, {0.75, 0.7, 0.8}, 0.15, 0, 0, 0};
    EXPECT(region_check(&cyl) == NULL, "cylinder rejected");
    double ec = fabs(shape_volume(&cyl, &m) - region_volume(&cyl)) / region_volume(&cyl);
    Region cone = {REGION_CONE, {0.25, 0.2, 0.3}, {0.7, 0.8, 0.75}, 0.2, 0.05, 0, 0};
    EXPECT(region_check(&cone) == NULL, "cone rejected");
    double eo = fabs(shape_volume(&cone, &m) - region_volume(&cone)) / region_volume(&cone);
    Region tip = {REGION_CONE, {0.5, 0.5, 0.1}, {0.5, 0.5, 0.9}, 0.3, 0, 0, 0};
    region_check(&tip);
    double et = fabs(shape_volume(&tip, &m) - region_volume(&tip)) / region_volume(&tip);
    printf("  20^3 graded grid, relative volume errors: cylinder %.2e, cone %.2e, pointed cone %.2e\n",
           ec, eo, et);
    EXPECT(ec < 6e-4, "cylinder relative error %.3e", ec);
    EXPECT(eo < 6e-4, "cone relative error %.3e", eo);
    EXPECT(et < 6e-4, "pointed cone relative error %.3e", et);
    mesh_free(&m);
}

/* 2-D: a flattened shape is its section extruded through the slab. */
TEST(flat_2d)
{
    double err[3];
    int N[3] = {10, 20, 40};
    Region r = {REGION_SPHERE, {0.52, 0.47, 3.0}, {0, 0, 0}, 0.3, 0, 0, 0};
    region_flatten(&r, 2);
    double exact = region_flat_area(&r) * 0.1;
    printf("  2-D disc r = 0.3 (sphere centre off the slab): N, relative error, order\n");
    for (int i = 0; i < 3; i++) {
        Mesh m;
        make_grid(&m, (int[]){N[i], N[i], 1}, (double[]){0, 0, 0}, (double[]){1, 1, 0.1}, 0.3);
        err[i] = fabs(shape_volume(&r, &m) - exact) / exact;
        if (i) printf("  %3d  %.3e  %.2f\n", N[i], err[i], log2(err[i - 1] / err[i]));
        else printf("  %3d  %.3e\n", N[i], err[i]);
        mesh_free(&m);
    }
    double order = log2(err[0] / err[2]) / 2;
    EXPECT(order > 1.7, "observed order %.2f", order);
    EXPECT(err[2] < 1e-4, "finest relative error %.3e", err[2]);

    Mesh m;
    make_grid(&m, (int[]){13, 11, 1}, (double[]){0, 0, 0}, (double[]){1, 1, 0.1}, 0.4);
    /* A box thinner than the slab still covers it: area x thickness. */
    Region b = {REGION_BOX, {0.123, 0.2, 0.02}, {0.77, 0.61, 0.03}, 0, 0, 0, 0};
    region_flatten(&b, 2);
    NEAR(shape_volume(&b, &m), 0.647 * 0.41 * 0.1, 1e-14);
    NEAR(region_flat_area(&b), 0.647 * 0.41, 1e-15);
    /* A half-space tilted out of the plane: its trace x + y <= 0.8. */
    Region h = {REGION_HALFSPACE, {0.4, 0.4, 0.05}, {1, 1, 5}, 0, 0, 0, 0};
    region_check(&h);
    region_flatten(&h, 2);
    NEAR(shape_volume(&h, &m), 0.32 * 0.1, 1e-14);
    /* A cylinder lying in the plane: a rectangle 2r x L. */
    Region c = {REGION_CYLINDER, {0.2, 0.3, 0.05}, {0.8, 0.3, 0.05}, 0.1, 0, 0, 0};
    region_flatten(&c, 2);
    NEAR(region_flat_area(&c), 0.12, 1e-15);
    /* Not exact: the level set is a max() of planes, curved near corners. */
    double ec = fabs(shape_volume(&c, &m) - 0.012) / 0.012;
    printf("  in-plane cylinder (rectangle) on 13 x 11 cells: relative error %.2e\n", ec);
    EXPECT(ec < 1e-3, "in-plane cylinder (a rectangle) relative error %.3e", ec);
    /* OpenFOAM's 2-D idiom: a cylinder along the empty axis is a disc. */
    Region d = {REGION_CYLINDER, {0.45, 0.55, -1}, {0.45, 0.55, 1}, 0.25, 0, 0, 0};
    region_flatten(&d, 2);
    NEAR(region_flat_area(&d), PI_ * 0.0625, 1e-15);
    double ed = fabs(shape_volume(&d, &m) - 0.1 * region_flat_area(&d)) / (0.1 * region_flat_area(&d));
    printf("  cylinder along the empty axis (disc r = 0.25) on 13 x 11 cells: relative error %.2e\n", ed);
    EXPECT(ed < 1e-3, "disc from a cylinder: relative error %.3e", ed);
    mesh_free(&m);
}

TEST(fraction_bounds)
{
    Mesh m;
    make_grid(&m, (int[]){9, 9, 9}, (double[]){-1, -1, -1}, (double[]){1, 1, 1}, 0.3);
    Region r = {REGION_SPHERE, {0.1, 0, -0.05}, {0, 0, 0}, 0.7, 0, 0, 0};
    int nfull = 0, npart = 0, bad = 0;
    for (int c = 0; c < m.ncells; c++) {
        double f = region_fraction(&r, &m, c);
        if (f < 0 || f > 1) bad++;
        if (f == 1) nfull++;
        else if (f > 0) npart++;
        /* A cell whose centre is well inside or outside is whole. */
        double phi = region_level(&r, m.cell_centre + 3 * c);
        if (phi < -0.5 && f != 1) bad++;
        if (phi > 0.5 && f != 0) bad++;
    }
    EXPECT(bad == 0, "%d cells out of [0,1] or misclassified", bad);
    EXPECT(nfull > 0 && npart > 0, "full %d, partial %d", nfull, npart);
    mesh_free(&m);
}

TEST(check_messages)
{
    Region r = {REGION_SPHERE, {0, 0, 0}, {0, 0, 0}, -1, 0, 0, 0};
    CONTAINS(region_check(&r), "radius must be positive");
    Region c = {REGION_CYLINDER, {1, 1, 1}, {1, 1, 1}, 1, 0, 0, 0};
    CONTAINS(region_check(&c), "p1 and p2 must differ");
    Region b = {REGION_BOX, {1, 0, 0}, {0, 1, 1}, 0, 0, 0, 0};
    CONTAINS(region_check(&b), "minimum");
    Region h = {REGION_HALFSPACE, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0};
    CONTAINS(region_check(&h), "normal");
    Region k = {REGION_CONE, {0, 0, 0}, {0, 0, 1}, 0, 0, 0, 0};
    CONTAINS(region_check(&k), "radius1 or radius2");
    EXPECT(region_kind("halfSpace") == REGION_HALFSPACE && region_kind("ball") == -1, "kind names");
    /* Level sets: sign and the 1-Lipschitz scale on the axis. */
    Region s = {REGION_CONE, {0, 0, 0}, {0, 0, 2}, 1, 0.5, 0, 0};
    region_check(&s);
    /* Radius 0.75 at mid-height, slope -1/4: distance 0.75/sqrt(1 + 1/16). */
    NEAR(region_level(&s, (double[]){0, 0, 1}), -0.75 / sqrt(1.0625), 1e-15);
    NEAR(region_level(&s, (double[]){0, 0, 2.5}), 0.5, 1e-15);
    NEAR(region_level(&r, (double[]){0, 0, 0}), 1, 1e-15);
}

int main(void)
{
    RUN(box_exact);
    RUN(half_space_exact);
    RUN(sphere_convergence);
    RUN(cylinder_cone_volume);
    RUN(flat_2d);
    RUN(fraction_bounds);
    RUN(check_messages);
    return test_summary();
}
