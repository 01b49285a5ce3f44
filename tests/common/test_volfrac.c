/*
** test_volfrac.c: cell volume fractions inside solids (volfrac.c) of the
** shared primitives (geometry.h, shape.h), as setFields builds them: one
** shape (geometry_of_shape), CSG and transforms (geometry_parse_solid).
** These were test_region.c's, with region.c's shapes; the values and
** tolerances are theirs.
**
** Grids come from block_mesh (the blockGrid mesher) with graded,
** irregular spacing so that no shape face lines up with grid lines by
** accident.  The sum over cells of fraction * volume is compared with the
** analytic volume of the shape (or of its intersection with the domain).
*/
#include "fixture.h"
#include "test.h"

#include "block.h"
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "mesh.h"
#include "setfields.h"
#include "shape.h"
#include "volfrac.h"

#include <string.h>

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

static double set_volume(const Geometry *r, const Mesh *m)
{
    double s = 0;
    for (int c = 0; c < m->ncells; c++) s += volfrac_cell(r, m, c) * m->cell_vol[c];
    return s;
}

/* The solid of one shape, as setFields' ToCell regions make it; returns
   shape_check's message (NULL: usable). */
static Geometry *made[64];
static int nmade;

static const char *solid(Geometry *g, int kind, const double p[3], const double q[3], double r1, double r2)
{
    static Shape s;
    if (nmade < 64) made[nmade++] = g;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    memcpy(s.p, p, sizeof s.p);
    memcpy(s.q, q, sizeof s.q);
    s.r1 = r1;
    s.r2 = r2;
    const char *msg = shape_check(&s);
    geometry_of_shape(g, &s, "test");
    return msg;
}

static double mesh_volume(const Mesh *m)
{
    double s = 0;
    for (int c = 0; c < m->ncells; c++) s += m->cell_vol[c];
    return s;
}

/* Frees the solids made so far (their Geometry structs are the tests'
   locals: freed before each test returns). */
static void free_solids(void)
{
    for (int i = 0; i < nmade; i++) geometry_free(made[i]);
    nmade = 0;
}

/* Closed-form volume (3-D), or section area (flattened: thickness 1). */
static double solid_volume(const Geometry *g)
{
    double lo[3] = {-INFINITY, -INFINITY, -INFINITY}, hi[3] = {INFINITY, INFINITY, INFINITY};
    if (g->flat_axis >= 0) lo[g->flat_axis] = 0, hi[g->flat_axis] = 1;
    return geometry_exact_volume(g, lo, hi);
}

TEST(box_exact)
{
    Mesh m;
    make_grid(&m, (int[]){7, 5, 6}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.6);
    /* Box corners anywhere (cut cells on all six sides). */
    Geometry r;
    EXPECT(solid(&r, SHAPE_BOX, (double[]){0.137, 0.291, 0.0731}, (double[]){0.8123, 0.7777, 0.66}, 0, 0) == NULL, "box rejected");
    NEAR(set_volume(&r, &m), solid_volume(&r), 1e-12);
    /* A box sticking out of the domain: the intersection is counted. */
    Geometry out;
    EXPECT(solid(&out, SHAPE_BOX, (double[]){-0.5, 0.31, 0.2}, (double[]){0.43, 1.7, 0.9}, 0, 0) == NULL, "out rejected");
    NEAR(set_volume(&out, &m), 0.43 * 0.69 * 0.7, 1e-12);
    /* A box on grid lines: whole cells only. */
    Geometry on;
    EXPECT(solid(&on, SHAPE_BOX, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0, 0) == NULL, "on rejected");
    NEAR(set_volume(&on, &m), mesh_volume(&m), 1e-12);
    /* One cell cut by a box corner: product of the overlaps. */
    int c = 3 + 7 * (2 + 5 * 3);
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = m.cart.x[k][(int[]){3, 2, 3}[k]];
        hi[k] = m.cart.x[k][(int[]){3, 2, 3}[k] + 1];
    }
    Geometry corner;
    EXPECT(solid(&corner, SHAPE_BOX, (double[]){lo[0] + 0.3 * (hi[0] - lo[0]), lo[1] - 1, lo[2] + 0.75 * (hi[2] - lo[2])}, (double[]){hi[0] + 1, lo[1] + 0.4 * (hi[1] - lo[1]), hi[2] + 1}, 0, 0) == NULL, "corner rejected");
    NEAR(volfrac_cell(&corner, &m, c), 0.7 * 0.4 * 0.25, 1e-13);
    mesh_free(&m);
    free_solids();
}

TEST(half_space_exact)
{
    Mesh m;
    make_grid(&m, (int[]){6, 7, 5}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.5);
    /* x + y + z <= 1: the corner tetrahedron, volume 1/6. */
    Geometry t;
    EXPECT(solid(&t, SHAPE_HALFSPACE, (double[]){1, 0, 0}, (double[]){1, 1, 1}, 0, 0) == NULL, "halfSpace rejected");
    NEAR(set_volume(&t, &m), 1.0 / 6.0, 1e-12);
    /* x + y <= 1: half the cube. */
    Geometry p;
    EXPECT(solid(&p, SHAPE_HALFSPACE, (double[]){0.5, 0.5, 0.2}, (double[]){2, 2, 0}, 0, 0) == NULL, "p rejected");
    NEAR(set_volume(&p, &m), 0.5, 1e-12);
    /* Any plane through the cube's centre halves it (point symmetry). */
    Geometry s;
    EXPECT(solid(&s, SHAPE_HALFSPACE, (double[]){0.5, 0.5, 0.5}, (double[]){-1, 2, 3}, 0, 0) == NULL, "s rejected");
    NEAR(set_volume(&s, &m), 0.5, 1e-12);
    /* The normal points out of the region. */
    EXPECT(volfrac_inside(&s, (double[]){0.5, 0.4, 0.4}), "below the plane is inside");
    EXPECT(!volfrac_inside(&s, (double[]){0.5, 0.6, 0.6}), "above the plane is outside");
    mesh_free(&m);
    free_solids();
}

/* Sphere volume over N^3 grids: second-order convergence. */
TEST(sphere_convergence)
{
    Geometry r;
    EXPECT(solid(&r, SHAPE_SPHERE, (double[]){0.51, 0.47, 0.53}, (double[]){0, 0, 0}, 0.3, 0) == NULL, "r rejected");
    double exact = solid_volume(&r), err[3];
    int N[3] = {8, 16, 32};
    printf("  sphere r = 0.3, depth %d: N, |V - 4/3 pi r^3| / V, order\n", VOLFRAC_DEPTH);
    for (int i = 0; i < 3; i++) {
        Mesh m;
        make_grid(&m, (int[]){N[i], N[i], N[i]}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0);
        err[i] = fabs(set_volume(&r, &m) - exact) / exact;
        if (i) printf("  %3d  %.3e  %.2f\n", N[i], err[i], log2(err[i - 1] / err[i]));
        else printf("  %3d  %.3e\n", N[i], err[i]);
        mesh_free(&m);
    }
    double order = log2(err[0] / err[2]) / 2;
    printf("  observed order (8 -> 32): %.2f\n", order);
    EXPECT(order > 1.7, "observed order %.2f", order);
    EXPECT(err[2] < 6e-5, "finest relative error %.3e", err[2]);
    free_solids();
}

TEST(cylinder_cone_volume)
{
    Mesh m;
    make_grid(&m, (int[]){20, 20, 20}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.4);
    /* Oblique axes, ends inside the domain. */
    Geometry cyl;
    EXPECT(solid(&cyl, SHAPE_CYLINDER, (double[]){0.2, 0.25, 0.3}, (double[]){0.75, 0.7, 0.8}, 0.15, 0) == NULL, "cylinder rejected");
    double ec = fabs(set_volume(&cyl, &m) - solid_volume(&cyl)) / solid_volume(&cyl);
    Geometry cone;
    EXPECT(solid(&cone, SHAPE_CONE, (double[]){0.25, 0.2, 0.3}, (double[]){0.7, 0.8, 0.75}, 0.2, 0.05) == NULL, "cone rejected");
    double eo = fabs(set_volume(&cone, &m) - solid_volume(&cone)) / solid_volume(&cone);
    Geometry tip;
    EXPECT(solid(&tip, SHAPE_CONE, (double[]){0.5, 0.5, 0.1}, (double[]){0.5, 0.5, 0.9}, 0.3, 0) == NULL, "tip rejected");
    double et = fabs(set_volume(&tip, &m) - solid_volume(&tip)) / solid_volume(&tip);
    printf("  20^3 graded grid, relative volume errors: cylinder %.2e, cone %.2e, pointed cone %.2e\n",
           ec, eo, et);
    EXPECT(ec < 6e-4, "cylinder relative error %.3e", ec);
    EXPECT(eo < 6e-4, "cone relative error %.3e", eo);
    EXPECT(et < 6e-4, "pointed cone relative error %.3e", et);
    mesh_free(&m);
    free_solids();
}

/* 2-D: a flattened shape is its section extruded through the slab. */
TEST(flat_2d)
{
    double err[3];
    int N[3] = {10, 20, 40};
    Geometry r;
    EXPECT(solid(&r, SHAPE_SPHERE, (double[]){0.52, 0.47, 3.0}, (double[]){0, 0, 0}, 0.3, 0) == NULL, "r rejected");
    geometry_flatten(&r, 2, 3.0);
    double exact = solid_volume(&r) * 0.1;
    printf("  2-D disc r = 0.3 (sphere centre off the slab): N, relative error, order\n");
    for (int i = 0; i < 3; i++) {
        Mesh m;
        make_grid(&m, (int[]){N[i], N[i], 1}, (double[]){0, 0, 0}, (double[]){1, 1, 0.1}, 0.3);
        err[i] = fabs(set_volume(&r, &m) - exact) / exact;
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
    Geometry b;
    EXPECT(solid(&b, SHAPE_BOX, (double[]){0.123, 0.2, 0.02}, (double[]){0.77, 0.61, 0.03}, 0, 0) == NULL, "b rejected");
    geometry_flatten(&b, 2, 0.025);
    NEAR(set_volume(&b, &m), 0.647 * 0.41 * 0.1, 1e-14);
    NEAR(solid_volume(&b), 0.647 * 0.41, 1e-15);
    /* A half-space tilted out of the plane: its trace x + y <= 0.8. */
    Geometry h;
    EXPECT(solid(&h, SHAPE_HALFSPACE, (double[]){0.4, 0.4, 0.05}, (double[]){1, 1, 5}, 0, 0) == NULL, "h rejected");
    geometry_flatten(&h, 2, 0.05);
    NEAR(set_volume(&h, &m), 0.32 * 0.1, 1e-14);
    /* A cylinder lying in the plane: a rectangle 2r x L. */
    Geometry c;
    EXPECT(solid(&c, SHAPE_CYLINDER, (double[]){0.2, 0.3, 0.05}, (double[]){0.8, 0.3, 0.05}, 0.1, 0) == NULL, "c rejected");
    geometry_flatten(&c, 2, 0.05);
    /* Not exact: the level set is a max() of planes, curved near corners. */
    double ec = fabs(set_volume(&c, &m) - 0.012) / 0.012;
    printf("  in-plane cylinder (rectangle) on 13 x 11 cells: relative error %.2e\n", ec);
    EXPECT(ec < 1e-3, "in-plane cylinder (a rectangle) relative error %.3e", ec);
    /* OpenFOAM's 2-D idiom: a cylinder along the empty axis is a disc. */
    Geometry d;
    EXPECT(solid(&d, SHAPE_CYLINDER, (double[]){0.45, 0.55, -1}, (double[]){0.45, 0.55, 1}, 0.25, 0) == NULL, "d rejected");
    geometry_flatten(&d, 2, 0);
    NEAR(solid_volume(&d), PI_ * 0.0625, 1e-15);
    double ed = fabs(set_volume(&d, &m) - 0.1 * solid_volume(&d)) / (0.1 * solid_volume(&d));
    printf("  cylinder along the empty axis (disc r = 0.25) on 13 x 11 cells: relative error %.2e\n", ed);
    EXPECT(ed < 1e-3, "disc from a cylinder: relative error %.3e", ed);
    mesh_free(&m);
    free_solids();
}

TEST(fraction_bounds)
{
    Mesh m;
    make_grid(&m, (int[]){9, 9, 9}, (double[]){-1, -1, -1}, (double[]){1, 1, 1}, 0.3);
    Geometry r;
    EXPECT(solid(&r, SHAPE_SPHERE, (double[]){0.1, 0, -0.05}, (double[]){0, 0, 0}, 0.7, 0) == NULL, "r rejected");
    int nfull = 0, npart = 0, bad = 0;
    for (int c = 0; c < m.ncells; c++) {
        double f = volfrac_cell(&r, &m, c);
        if (f < 0 || f > 1) bad++;
        if (f == 1) nfull++;
        else if (f > 0) npart++;
        /* A cell whose centre is well inside or outside is whole. */
        double phi = geometry_level(&r, m.cell_centre + 3 * c);
        if (phi < -0.5 && f != 1) bad++;
        if (phi > 0.5 && f != 0) bad++;
    }
    EXPECT(bad == 0, "%d cells out of [0,1] or misclassified", bad);
    EXPECT(nfull > 0 && npart > 0, "full %d, partial %d", nfull, npart);
    mesh_free(&m);
    free_solids();
}

/* The ToCell types' messages (setfields.c checks them in their keywords'
   terms before shape_check). */
static const char *tocell_message(const char *text)
{
    static Err e;
    memset(&e, 0, sizeof e);
    Dict *d = dict_parse(text, strlen(text), "t", &e);
    SetFields s;
    int rc = !d || setfields_parse(&s, d, NULL, &e);
    if (d) setfields_free(&s);
    dict_free(d);
    return rc ? e.msg : "";
}

TEST(check_messages)
{
    CONTAINS(tocell_message("regions ( sphereToCell { centre (0 0 0); radius -1; fieldValues (); } );"),
             "radius must be positive");
    CONTAINS(tocell_message("regions ( cylinderToCell { p1 (1 1 1); p2 (1 1 1); radius 1; fieldValues (); } );"),
             "p1 and p2 must differ");
    CONTAINS(tocell_message("regions ( boxToCell { box (1 0 0) (0 1 1); fieldValues (); } );"), "minimum");
    CONTAINS(tocell_message("regions ( halfSpaceToCell { point (0 0 0); normal (0 0 0); fieldValues (); } );"),
             "normal");
    CONTAINS(tocell_message("regions ( coneToCell { p1 (0 0 0); p2 (0 0 1); radius1 0; radius2 0; fieldValues (); } );"),
             "radius1 or radius2");
    EXPECT(shape_kind("halfSpace") == SHAPE_HALFSPACE && shape_kind("ball") == -1, "kind names");
    /* Level sets: sign and the 1-Lipschitz scale on the axis. */
    Geometry s, r;
    solid(&s, SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 2}, 1, 0.5);
    solid(&r, SHAPE_SPHERE, (double[]){0, 0, 0}, (double[]){0, 0, 0}, -1, 0);
    /* Radius 0.75 at mid-height, slope -1/4: distance 0.75/sqrt(1 + 1/16). */
    NEAR(geometry_level(&s, (double[]){0, 0, 1}), -0.75 / sqrt(1.0625), 1e-15);
    NEAR(geometry_level(&s, (double[]){0, 0, 2.5}), 0.5, 1e-15);
    NEAR(geometry_level(&r, (double[]){0, 0, 0}), 1, 1e-15);
    free_solids();
}

/* A solid from shape-dictionary text, as setFields' shapeToCell reads it. */
static void solid_text(Geometry *g, const char *text)
{
    Err e;
    memset(&e, 0, sizeof e);
    Dict *d = dict_parse(text, strlen(text), "t", &e);
    EXPECT(d && !geometry_parse_solid(g, d, "test", NULL, NULL, &e), "solid not read: %s", e.msg);
    dict_free(d);
}

/* CSG: a box minus a sphere inside it, by the level refinement (the
   difference is no convex polytope); its kinks lie on the box's edges. */
TEST(csg_box_minus_sphere)
{
    Geometry g;
    solid_text(&g, "shape difference; a { shape box; min (0.1 0.15 0.12); max (0.85 0.9 0.8); }"
                   " b { shape sphere; centre (0.5 0.5 0.45); radius 0.3; }");
    GeoPlane pl[VOLFRAC_PLANES];
    EXPECT(geometry_planes(&g, pl, VOLFRAC_PLANES) == -1, "a difference is no polytope");
    double exact = 0.75 * 0.75 * 0.68 - 4.0 / 3.0 * PI_ * 0.027;
    Mesh m;
    make_grid(&m, (int[]){24, 24, 24}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.4);
    double err = fabs(set_volume(&g, &m) - exact) / exact;
    printf("  box minus sphere on a 24^3 graded grid: relative volume error %.2e\n", err);
    EXPECT(err < 1e-4, "box minus sphere relative error %.3e", err);
    /* the level: inside the box, outside the sphere, 1-Lipschitz */
    EXPECT(volfrac_inside(&g, (double[]){0.12, 0.2, 0.2}) && !volfrac_inside(&g, (double[]){0.5, 0.5, 0.45}),
           "inside/outside");
    NEAR(geometry_level(&g, (double[]){0.5, 0.5, 0.45}), 0.3, 1e-15);
    mesh_free(&m);
    geometry_free(&g);
}

/* A rotated, translated box is still a convex polytope: exact. */
TEST(transformed_box_exact)
{
    Geometry g;
    solid_text(&g, "shape box; min (-0.2 -0.1 -0.15); max (0.2 0.1 0.15);"
                   " rotate { axis (1 2 3); angle 37; } translate (0.5 0.45 0.55);");
    GeoPlane pl[VOLFRAC_PLANES];
    EXPECT(geometry_planes(&g, pl, VOLFRAC_PLANES) == 6, "a box has six planes");
    Mesh m;
    make_grid(&m, (int[]){9, 8, 7}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.5);
    NEAR(set_volume(&g, &m), 0.4 * 0.2 * 0.3, 1e-12);
    mesh_free(&m);
    geometry_free(&g);
}

/* A scaled sphere (an ellipsoid): the level is scaled to stay
   1-Lipschitz, so whole cells are still classified right. */
TEST(scaled_sphere)
{
    Geometry g;
    solid_text(&g, "shape sphere; centre (0 0 0); radius 0.2; scale (2 1 1.5); translate (0.5 0.5 0.5);");
    double exact = 4.0 / 3.0 * PI_ * 0.008 * 3;
    Mesh m;
    make_grid(&m, (int[]){20, 20, 20}, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0.3);
    double err = fabs(set_volume(&g, &m) - exact) / exact;
    printf("  ellipsoid (sphere scaled (2 1 1.5)) on 20^3 cells: relative volume error %.2e\n", err);
    EXPECT(err < 1e-3, "ellipsoid relative error %.3e", err);
    /* a point 0.3 beyond the tip of the long axis: level in (0, 0.3] */
    double l = geometry_level(&g, (double[]){0.5 + 0.4 + 0.3, 0.5, 0.5});
    EXPECT(l > 0 && l <= 0.3, "level %.17g beyond the long axis' tip", l);
    mesh_free(&m);
    geometry_free(&g);
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
    RUN(csg_box_minus_sphere);
    RUN(transformed_box_exact);
    RUN(scaled_sphere);
    return test_summary();
}
