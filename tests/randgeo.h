/*
** randgeo.h: random geometries for the robustness studies of the grid
** tools (test_cut.c, test_vgrid.c): primitives at random positions in
** the unit box with random rotations and translations, and CSG trees of
** them, as geometryDict text.  A fixed xorshift generator, so every run
** sees the same cases.
*/
#ifndef KIESEL_TEST_RANDGEO_H
#define KIESEL_TEST_RANDGEO_H

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

#endif
