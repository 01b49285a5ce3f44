/*
** randgeo.h: random geometries for the robustness studies of the grid
** tools (test_cut.c, test_vgrid.c): primitives at random positions in
** the unit box with random rotations and translations, and CSG trees of
** them, as geometryDict text.  A fixed xorshift generator, so every run
** sees the same cases.
*/
#ifndef KIESEL_TEST_RANDGEO_H
#define KIESEL_TEST_RANDGEO_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>

static uint64_t rng_state = 88172645463325252ull;

static double rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static double rr(double a, double b)
{
    return a + (b - a) * rnd();
}

/* A random primitive (with a random transform) as dictionary text. */
static int rand_prim(char *o, size_t n)
{
    double c[3] = {rr(0.1, 0.9), rr(0.1, 0.9), rr(0.1, 0.9)}, r = rr(0.05, 0.45);
    int k = 0;
    switch ((int)(rnd() * 7)) {
    case 6: {
        /* a box on grid planes for the 8^3 and 12^3 grids (whole cells) */
        double a[3], b[3];
        for (int q = 0; q < 3; q++) {
            a[q] = 0.25 * (int)(rnd() * 3);
            b[q] = a[q] + 0.25 * (1 + (int)(rnd() * (4 - a[q] / 0.25 - 1 + 0.999)));
        }
        k = snprintf(o, n, "shape box; min (%g %g %g); max (%g %g %g);", a[0], a[1], a[2], b[0], b[1], b[2]);
        return k;
    }
    case 0:
        k = snprintf(o, n, "shape sphere; centre (%.17g %.17g %.17g); radius %.17g;", c[0], c[1], c[2], r);
        break;
    case 1:
        k = snprintf(o, n, "shape box; min (%.17g %.17g %.17g); max (%.17g %.17g %.17g);", c[0] - r,
                     c[1] - rr(0.05, 0.4), c[2] - r, c[0] + rr(0.05, 0.4), c[1] + r, c[2] + rr(0.05, 0.4));
        break;
    case 2:
        k = snprintf(o, n,
                     "shape cylinder; point1 (%.17g %.17g %.17g); point2 (%.17g %.17g %.17g); radius %.17g;",
                     c[0], c[1], c[2], rr(0, 1), rr(0, 1), rr(0, 1), 0.6 * r);
        break;
    case 3:
        k = snprintf(o, n, "shape halfSpace; point (%.17g %.17g %.17g); normal (%.17g %.17g %.17g);", c[0],
                     c[1], c[2], rr(-1, 1), rr(-1, 1), rr(-1, 1));
        break;
    case 4:
        k = snprintf(o, n,
                     "shape cone; point1 (%.17g %.17g %.17g); point2 (%.17g %.17g %.17g); radius1 %.17g; "
                     "radius2 %.17g;",
                     c[0], c[1], c[2], rr(0, 1), rr(0, 1), rr(0, 1), r, rnd() < 0.5 ? 0.0 : 0.3 * r);
        break;
    case 5:
        k = snprintf(o, n,
                     "shape torus; centre (%.17g %.17g %.17g); axis (%.17g %.17g %.17g); majorRadius %.17g; "
                     "minorRadius %.17g;",
                     c[0], c[1], c[2], rr(-1, 1), rr(-1, 1), rr(0.1, 1), r, r * rr(0.2, 0.6));
        break;
    }
    if (rnd() < 0.4)
        k += snprintf(o + k, n - (size_t)k,
                      " rotate { axis (%.17g %.17g %.17g); angle %.17g; origin (0.5 0.5 0.5); }", rr(-1, 1),
                      rr(-1, 1), rr(0.1, 1), rr(0, 360));
    if (rnd() < 0.3)
        k += snprintf(o + k, n - (size_t)k, " translate (%.17g %.17g 0);", rr(-0.1, 0.1), rr(-0.1, 0.1));
    return k;
}

/* A random CSG tree of depth <= depth. */
static int rand_shape(char *o, size_t n, int depth)
{
    if (depth == 0 || rnd() < 0.4) return rand_prim(o, n);
    static const char *const ops[] = {"union", "intersection", "difference"};
    int k = snprintf(o, n, "shape %s;", ops[(int)(rnd() * 3)]);
    int m = 2 + (rnd() < 0.3);
    for (int i = 0; i < m; i++) {
        k += snprintf(o + k, n - (size_t)k, " op%d { ", i);
        k += rand_shape(o + k, n - (size_t)k, depth - 1);
        k += snprintf(o + k, n - (size_t)k, " }");
    }
    return k;
}

/* A random primitive placed on purpose on a grid of spacing g on the
   unit box: faces on grid planes, axes on grid lines, centres and apices
   on grid vertices, radii that make circles tangent to grid lines or run
   through grid vertices, planes through grid vertices with small integer
   normals, prisms with their vertices on grid vertices. */
static int aligned_kinds = 0x3f; /* bit k: primitive kind k may be drawn (box, sphere, cylinder, halfSpace, cone, polygon) */

static inline int rand_aligned_prim(char *o, size_t n, double g)
{
    int m = (int)(1 / g + 0.5);
#define RI(a, b) ((a) + (int)(rnd() * ((b) - (a) + 1)))
    int c[3] = {RI(1, m - 1), RI(1, m - 1), RI(1, m - 1)}, ax = RI(0, 2);
    double r = rnd() < 0.5 ? RI(1, m / 2) * g : sqrt((double)(RI(1, 3) * RI(1, 3) + RI(0, 2) * RI(0, 2))) * g;
    int kind;
    do
        kind = RI(0, 5);
    while (!((aligned_kinds >> kind) & 1));
    switch (kind) {
    case 0: {
        int a[3], b[3];
        for (int q = 0; q < 3; q++) a[q] = RI(0, m - 1), b[q] = RI(a[q] + 1, m);
        return snprintf(o, n, "shape box; min (%.17g %.17g %.17g); max (%.17g %.17g %.17g);", a[0] * g, a[1] * g,
                        a[2] * g, b[0] * g, b[1] * g, b[2] * g);
    }
    case 1:
        return snprintf(o, n, "shape sphere; centre (%.17g %.17g %.17g); radius %.17g;", c[0] * g, c[1] * g,
                        c[2] * g, r);
    case 2: {
        double p1[3] = {c[0] * g, c[1] * g, c[2] * g}, p2[3] = {p1[0], p1[1], p1[2]};
        p1[ax] = RI(0, m / 2) * g;
        p2[ax] = RI(m / 2 + 1, m) * g;
        return snprintf(o, n, "shape cylinder; point1 (%.17g %.17g %.17g); point2 (%.17g %.17g %.17g); radius %.17g;",
                        p1[0], p1[1], p1[2], p2[0], p2[1], p2[2], r);
    }
    case 3:
        return snprintf(o, n, "shape halfSpace; point (%.17g %.17g %.17g); normal (%d %d %d);", c[0] * g, c[1] * g,
                        c[2] * g, RI(-1, 1), RI(-2, 2), RI(1, 2) * (rnd() < 0.5 ? 1 : -1));
    case 4: {
        double p1[3] = {c[0] * g, c[1] * g, c[2] * g}, p2[3] = {p1[0], p1[1], p1[2]};
        p2[ax] = RI(0, m) * g;
        if (p2[ax] == p1[ax]) p2[ax] = p1[ax] < 0.5 ? 1 : 0;
        return snprintf(o, n,
                        "shape cone; point1 (%.17g %.17g %.17g); point2 (%.17g %.17g %.17g); radius1 %.17g; "
                        "radius2 0;",
                        p1[0], p1[1], p1[2], p2[0], p2[1], p2[2], r);
    }
    default: {
        static const char *const axes[] = {"x", "y", "z"};
        int u[3], v[3];
        do
            for (int q = 0; q < 3; q++) u[q] = RI(0, m), v[q] = RI(0, m);
        while ((u[1] - u[0]) * (v[2] - v[0]) == (u[2] - u[0]) * (v[1] - v[0]));
        return snprintf(o, n,
                        "shape polygon; axis %s; points ((%.17g %.17g) (%.17g %.17g) (%.17g %.17g)); min (%.17g %.17g "
                        "%.17g); max (%.17g %.17g %.17g);",
                        axes[ax], u[0] * g, v[0] * g, u[1] * g, v[1] * g, u[2] * g, v[2] * g, c[0] * g, c[0] * g,
                        c[0] * g, (c[0] + RI(1, m - c[0])) * g, (c[0] + RI(1, m - c[0])) * g,
                        (c[0] + RI(1, m - c[0])) * g);
    }
    }
#undef RI
}

/* A random CSG tree of grid-aligned primitives. */
static inline int rand_aligned_shape(char *o, size_t n, int depth, double g)
{
    if (depth == 0 || rnd() < 0.4) return rand_aligned_prim(o, n, g);
    static const char *const ops[] = {"union", "intersection", "difference"};
    int k = snprintf(o, n, "shape %s;", ops[(int)(rnd() * 3)]);
    for (int i = 0; i < 2; i++) {
        k += snprintf(o + k, n - (size_t)k, " op%d { ", i);
        k += rand_aligned_shape(o + k, n - (size_t)k, depth - 1, g);
        k += snprintf(o + k, n - (size_t)k, " }");
    }
    return k;
}

#endif
