/*
** test_geometry.c: the flow domain of system/geometryDict (csg.c, geometry_dict.c):
** CSG crossings against a brute-force scan, transforms, normal signs,
** 2-D sections, exact volumes, STL leaves and dictionary errors.
*/
#include "geometry.h"
#include "io.h"
#include "mem.h"
#include "stl.h"
#include "test.h"
#include "fixture.h"
#include "trisurf.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif


static void lerp(const double a[3], const double b[3], double t, double x[3])
{
    for (int k = 0; k < 3; k++) x[k] = a[k] + t * (b[k] - a[k]);
}

TEST(sphere_outside)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { ball { shape sphere; centre (0.5 0.5 0.5); radius 0.25; } }", &e) == 0, "%s",
           e.msg);
    double c[3] = {0.5, 0.5, 0.5}, far[3] = {0.05, 0.1, 0.9};
    EXPECT(!geometry_fluid(&g, c) && geometry_fluid(&g, far), "sphere: centre must be solid, corner fluid");
    double a[3] = {0, 0.5, 0.5}, b[3] = {1, 0.5, 0.5};
    GeoCross x[8];
    int n = geometry_crossings(&g, a, b, x, 8);
    EXPECT(n == 2, "%d crossings through the centre, expected 2", n);
    if (n == 2) {
        NEAR(x[0].t, 0.25, 1e-15);
        NEAR(x[1].t, 0.75, 1e-15);
        EXPECT(x[0].enter == 0 && x[1].enter == 1, "enter flags %d %d, expected 0 1", x[0].enter, x[1].enter);
        double p[3], nv[3];
        lerp(a, b, x[0].t, p);
        geometry_normal(&g, x[0].leaf, p, nv);
        /* flow outside: the domain's outward normal points into the ball */
        NEAR(nv[0], 1, 1e-15);
        NEAR(nv[1], 0, 1e-15);
        EXPECT(!strcmp(geometry_leaf_patch(&g, x[0].leaf), "ball"), "patch %s", geometry_leaf_patch(&g, x[0].leaf));
    }
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    NEAR(geometry_exact_volume(&g, lo, hi), 1 - 4.0 / 3 * M_PI * 0.25 * 0.25 * 0.25, 1e-15);
    geometry_free(&g);
}

static const char *csg_text =
    "surfaces {\n"
    " part { flow inside; shape difference;\n"
    "   body { shape union;\n"
    "     a { shape box; min (0.1 0.1 0.1); max (0.7 0.6 0.8); rotate { axis (0 0 1); angle 20; origin (0.4 0.4 0); } }\n"
    "     b { shape cylinder; point1 (0.5 0.5 0.1); point2 (0.5 0.5 0.9); radius 0.3; }\n"
    "   }\n"
    "   hole { shape sphere; centre (0.5 0.5 0.5); radius 0.2; scale (1 1.2 1); translate (0 -0.1 0); }\n"
    "   ring { shape torus; centre (0.5 0.5 0.5); axis (1 0 0); majorRadius 0.3; minorRadius 0.08; }\n"
    " }\n"
    " cap { flow outside; shape halfSpace; point (0 0 0.85); normal (0 0 -1); }\n"
    "}\n";

/* Every reported crossing separates fluid from solid, and the parity
   matches the end states; compared with a fine scan of geometry_fluid. */
TEST(csg_crossings_random)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, csg_text, &e) == 0, "%s", e.msg);
    if (g.nsurf != 2) return;
    EXPECT(g.nleaves == 5, "%d leaves, expected 5", g.nleaves);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    int bad_sep = 0, bad_parity = 0, missed = 0, total = 0;
    for (int s = 0; s < 400; s++) {
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = gsl_rng_uniform(r);
            b[k] = gsl_rng_uniform(r);
        }
        GeoCross x[64];
        int n = geometry_crossings(&g, a, b, x, 64);
        total += n;
        for (int i = 0; i < n; i++) {
            double p[3], q[3];
            lerp(a, b, x[i].t - 1e-9, p);
            lerp(a, b, x[i].t + 1e-9, q);
            int fp = geometry_fluid(&g, p), fq = geometry_fluid(&g, q);
            if (fp == fq || fq != x[i].enter) bad_sep++;
            if (i && !(x[i].t >= x[i - 1].t)) bad_sep++;
        }
        if ((geometry_fluid(&g, a) != geometry_fluid(&g, b)) != (n & 1)) bad_parity++;
        /* scan: every change of state between samples must be reported */
        int prev = geometry_fluid(&g, a);
        for (int j = 1; j <= 2000; j++) {
            double p[3];
            lerp(a, b, j / 2000.0, p);
            int f = geometry_fluid(&g, p);
            if (f != prev) {
                int found = 0;
                for (int i = 0; i < n; i++) found |= x[i].t > (j - 1) / 2000.0 - 1e-12 && x[i].t < j / 2000.0 + 1e-12;
                missed += !found;
            }
            prev = f;
        }
    }
    printf("csg: %d crossings on 400 random segments\n", total);
    EXPECT(total > 400, "too few crossings (%d): the test geometry is wrong", total);
    EXPECT(bad_sep == 0, "%d crossings do not separate fluid from solid", bad_sep);
    EXPECT(bad_parity == 0, "%d segments with wrong crossing parity", bad_parity);
    EXPECT(missed == 0, "%d state changes of the scan not reported", missed);
    gsl_rng_free(r);
    geometry_free(&g);
}

TEST(classify_line_matches_points)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, csg_text, &e) == 0, "%s", e.msg);
    double c[101];
    char f[101];
    for (int i = 0; i <= 100; i++) c[i] = i / 100.0;
    int bad = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int l = 0; l < 50; l++) {
            double p[3] = {0.013 + l / 51.0, 0.5 + 0.37 * sin(l), 0.41 + 0.3 * cos(3.0 * l)};
            geometry_classify_line(&g, axis, p, c, 101, f);
            for (int i = 0; i <= 100; i++) {
                double x[3] = {p[0], p[1], p[2]};
                x[axis] = c[i];
                bad += f[i] != geometry_fluid(&g, x);
            }
        }
    EXPECT(bad == 0, "%d points classified differently along lines", bad);
    geometry_free(&g);
}

/* A box rotated by 30 degrees about z: inside tests and normals follow. */
TEST(transform_rotate_translate)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { b { flow inside; shape box; min (-1 -0.5 -0.5); max (1 0.5 0.5);\n"
                     " rotate { axis (0 0 1); angle 30; } translate (2 3 0); } }", &e) == 0, "%s", e.msg);
    double c = cos(M_PI / 6), s = sin(M_PI / 6);
    /* local (0.9, 0.4, 0) -> global */
    double in[3] = {2 + 0.9 * c - 0.4 * s, 3 + 0.9 * s + 0.4 * c, 0};
    double out[3] = {2 + 1.1 * c, 3 + 1.1 * s, 0};
    EXPECT(geometry_fluid(&g, in) && !geometry_fluid(&g, out), "rotated box inside test");
    /* segment along the local x axis: crossings at local x = -1, 1 */
    double a[3] = {2 - 2 * c, 3 - 2 * s, 0}, b[3] = {2 + 2 * c, 3 + 2 * s, 0};
    GeoCross x[4];
    int n = geometry_crossings(&g, a, b, x, 4);
    EXPECT(n == 2, "%d crossings", n);
    if (n == 2) {
        NEAR(x[0].t, 0.25, 1e-14);
        NEAR(x[1].t, 0.75, 1e-14);
        double p[3], nv[3];
        lerp(a, b, x[1].t, p);
        geometry_normal(&g, x[1].leaf, p, nv);
        NEAR(nv[0], c, 1e-14);
        NEAR(nv[1], s, 1e-14);
    }
    double lo[3] = {0, 0, -1}, hi[3] = {4, 6, 1};
    NEAR(geometry_exact_volume(&g, lo, hi), 2.0, 1e-14);
    geometry_free(&g);
}

TEST(difference_normal_sign)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { p { flow inside; shape difference;\n"
                     " o { shape sphere; centre (0 0 0); radius 1; }\n"
                     " i { shape sphere; centre (0 0 0); radius 0.5; } } }", &e) == 0, "%s", e.msg);
    double a[3] = {0, 0, 0}, b[3] = {2, 0, 0};
    GeoCross x[4];
    int n = geometry_crossings(&g, a, b, x, 4);
    EXPECT(n == 2, "%d crossings of the shell", n);
    if (n == 2) {
        NEAR(x[0].t, 0.25, 1e-15);
        NEAR(x[1].t, 0.5, 1e-15);
        EXPECT(x[0].enter == 1 && x[1].enter == 0, "enter flags");
        double p[3], nv[3];
        lerp(a, b, x[0].t, p);
        geometry_normal(&g, x[0].leaf, p, nv);
        NEAR(nv[0], -1, 1e-15);   /* out of the shell, into the hole */
        lerp(a, b, x[1].t, p);
        geometry_normal(&g, x[1].leaf, p, nv);
        NEAR(nv[0], 1, 1e-15);
    }
    geometry_free(&g);
}

/* 2-D: the section by z = 0.5, extruded. */
TEST(flatten_section)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { ball { shape sphere; centre (0.5 0.5 0.5); radius 0.25; } }", &e) == 0, "%s",
           e.msg);
    geometry_flatten(&g, 2, 0.5);
    double p[3] = {0.5, 0.7, 0.99}, q[3] = {0.5, 0.76, 0.5};
    EXPECT(!geometry_fluid(&g, p) && geometry_fluid(&g, q), "section of the sphere is the disc r = 0.25");
    double a[3] = {0.5, 0.5, 0}, b[3] = {0.5, 0.5, 1};
    GeoCross x[4];
    EXPECT(geometry_crossings(&g, a, b, x, 4) == 0, "a segment along the flat axis crosses nothing");
    double a2[3] = {0, 0.5, 0.9}, b2[3] = {1, 0.5, 0.9}, nv[3], pt[3] = {0.25, 0.5, 0.9};
    int n = geometry_crossings(&g, a2, b2, x, 4);
    EXPECT(n == 2, "%d crossings off the mid-plane", n);
    if (n == 2) NEAR(x[0].t, 0.25, 1e-15);
    geometry_normal(&g, 0, pt, nv);
    NEAR(nv[2], 0, 0);
    NEAR(nv[0], 1, 1e-15);
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.1};
    NEAR(geometry_exact_volume(&g, lo, hi), (1 - M_PI / 16) * 0.1, 1e-15);
    geometry_free(&g);
}

static void cube_soup(double *xyz)
{
    /* unit cube [0,1]^3, 12 outward triangles */
    static const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    int t = 0;
    for (int i = 0; i < 6; i++) {
        int q[4];
        for (int k = 0; k < 4; k++) q[k] = f[i][k];
        int tri[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
        for (int h = 0; h < 2; h++, t++)
            for (int v = 0; v < 3; v++) {
                int c = tri[h][v];
                xyz[9 * t + 3 * v] = c & 1;
                xyz[9 * t + 3 * v + 1] = (c >> 1) & 1;
                xyz[9 * t + 3 * v + 2] = (c >> 2) & 1;
            }
    }
}

TEST(stl_leaf)
{
    double xyz[12 * 9];
    cube_soup(xyz);
    TriSurf s;
    trisurf_init(&s);
    trisurf_from_soup(&s, xyz, 12, NULL);
    Err e;
    io_mkdir_p("geo_stl", &e);
    EXPECT(stl_write(&s, "geo_stl/cube.stl", 1, &e) == 0, "%s", e.msg);
    trisurf_free(&s);
    Geometry g;
    EXPECT(fixture_geometry(&g, "surfaces { cube { flow outside; shape stl; file \"geo_stl/cube.stl\"; scale 0.5;\n"
                     " translate (0.25 0.25 0.25); } }", &e) == 0, "%s", e.msg);
    if (g.nsurf != 1) return;
    double c[3] = {0.5, 0.5, 0.5}, o[3] = {0.1, 0.5, 0.5};
    EXPECT(!geometry_fluid(&g, c) && geometry_fluid(&g, o), "cube inside test");
    double a[3] = {0, 0.5, 0.5}, b[3] = {1, 0.5, 0.5};
    GeoCross x[4];
    int n = geometry_crossings(&g, a, b, x, 4);
    EXPECT(n == 2, "%d crossings through the cube", n);
    if (n == 2) {
        NEAR(x[0].t, 0.25, 1e-15);
        NEAR(x[1].t, 0.75, 1e-15);
        double p[3], nv[3];
        lerp(a, b, x[0].t, p);
        geometry_normal(&g, x[0].leaf, p, nv);
        NEAR(nv[0], 1, 1e-15);
    }
    /* a line through the cube's edges: the grazing case */
    double a2[3] = {0, 0.25, 0.25}, b2[3] = {1, 0.25, 0.25};
    n = geometry_crossings(&g, a2, b2, x, 4);
    EXPECT(n == 0 || n == 2, "a line along an edge crosses %d times (parity must be even)", n);
    geometry_free(&g);

    /* an open surface is refused unless allowed */
    trisurf_init(&s);
    trisurf_from_soup(&s, xyz, 11, NULL);
    EXPECT(stl_write(&s, "geo_stl/open.stl", 0, &e) == 0, "%s", e.msg);
    trisurf_free(&s);
    EXPECT(fixture_geometry(&g, "surfaces { c { shape stl; file \"geo_stl/open.stl\"; } }", &e) != 0, "open STL accepted");
    CONTAINS(e.msg, "not watertight");
    CONTAINS(e.msg, "3 open edge");
    CONTAINS(e.msg, "geometryDict:1:");
    EXPECT(fixture_geometry(&g, "surfaces { c { shape stl; file \"geo_stl/open.stl\"; allowOpen yes; } }", &e) == 0,
           "allowOpen yes: %s", e.msg);
    geometry_free(&g);
    io_rm_rf("geo_stl", NULL);
}

TEST(dictionary_errors)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { s { shape sphre; centre (0 0 0); radius 1; } }", &e) != 0, "bad shape accepted");
    CONTAINS(e.msg, "unknown shape 'sphre'");
    EXPECT(fixture_geometry(&g, "surfaces {\n s { shape sphere; centre (0 0 0); raduis 1; } }", &e) != 0, "typo accepted");
    CONTAINS(e.msg, "geometryDict:2:");
    CONTAINS(e.msg, "did you mean 'radius'");
    EXPECT(fixture_geometry(&g, "surfaces {\n\n s { shape sphere; centre (0 0 0); radius -1; } }", &e) != 0, "r < 0 accepted");
    CONTAINS(e.msg, "geometryDict:3:");
    EXPECT(fixture_geometry(&g, "surfaces { }", &e) != 0, "no surfaces accepted");
    CONTAINS(e.msg, "no surfaces");
    EXPECT(fixture_geometry(&g, "surfaces { u { shape union; } }", &e) != 0, "empty union accepted");
    CONTAINS(e.msg, "operands");
    EXPECT(fixture_geometry(&g, "surfaces { s { shape stl; file \"nowhere.stl\"; } }", &e) != 0, "missing file accepted");
    CONTAINS(e.msg, "nowhere.stl");
    EXPECT(fixture_geometry(&g, "surfaces { s { shape sphere; flow sideways; centre (0 0 0); radius 1; } }", &e) != 0,
           "bad flow accepted");
    CONTAINS(e.msg, "flow");
    EXPECT(fixture_geometry(&g, "surfaces { s { shape box; min (0 0 0); max (1 1 1); scale 0; } }", &e) != 0,
           "scale 0 accepted");
    CONTAINS(e.msg, "scale");
}

int main(void)
{
    RUN(sphere_outside);
    RUN(csg_crossings_random);
    RUN(classify_line_matches_points);
    RUN(transform_rotate_translate);
    RUN(difference_normal_sign);
    RUN(flatten_section);
    RUN(stl_leaf);
    RUN(dictionary_errors);
    return test_summary();
}
