/*
** test_shape.c: analytic primitives (shape.c).
**
** Crossings are checked three ways on thousands of random segments per
** kind (fixed-seed Mersenne twister, so failures reproduce): the count has
** the parity of inside(a) != inside(b); the level vanishes at every
** reported t and the inside state differs just before and after it; and a
** brute-force scan of the inside state at 256 points along the segment
** agrees interval by interval (odd number of reported crossings exactly
** where the scanned state changes), with single crossings located by
** bisection on the level sign to 1e-12.  Degenerate hits (box corners and
** edges, cylinder and cone rims, the cone apex, tangent spheres and tori,
** polygon vertices) are checked against exact answers.  Normals and
** nearest points are compared with analytic ones; volumes with exact
** values and with quasi-Monte Carlo (Sobol) estimates.
*/
#include "test.h"

#include "mem.h"
#include "shape.h"

#include <float.h>
#include <gsl/gsl_qrng.h>
#include <gsl/gsl_rng.h>

static const double PI_ = 3.14159265358979323846;

/* ---- the shapes under test ---- */

static double L_shape[] = {-0.6, -0.5, 0.5, -0.5, 0.5, 0.1, -0.1, 0.1, -0.1, 0.6, -0.6, 0.6};
/* A star with reflex vertices, given clockwise (shape_check turns it). */
static double star_cw[20];
/* A 15-pointed star (30 points: more than the crossing code keeps on its
   stack). */
static double star30[60];

static void make_star(void)
{
    for (int i = 0; i < 10; i++) {
        double r = i % 2 ? 0.3 : 0.7, a = -2 * PI_ * i / 10 + 0.1;
        star_cw[2 * i] = 0.05 + r * cos(a);
        star_cw[2 * i + 1] = -0.02 + r * sin(a);
    }
    for (int i = 0; i < 30; i++) {
        double r = i % 2 ? 0.45 : 0.75, a = 2 * PI_ * i / 30;
        star30[2 * i] = r * cos(a);
        star30[2 * i + 1] = r * sin(a);
    }
}

static Shape poly_shape(int axis, const double *pts, int n, double lo, double hi)
{
    Shape s;
    memset(&s, 0, sizeof s);
    s.kind = SHAPE_POLYGON;
    s.axis = axis;
    s.npoly = n;
    s.poly = mem_alloc(sizeof(double) * 2 * (size_t)n);
    memcpy(s.poly, pts, sizeof(double) * 2 * (size_t)n);
    s.lo = lo, s.hi = hi;
    return s;
}

static Shape prim(int kind, const double p[3], const double q[3], double r1, double r2, int inf)
{
    Shape s;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    for (int k = 0; k < 3; k++) s.p[k] = p[k], s.q[k] = q[k];
    s.r1 = r1, s.r2 = r2, s.infinite = inf;
    return s;
}

#define NSHAPES 18
static Shape shapes[NSHAPES];

static void make_shapes(void)
{
    make_star();
    int n = 0;
    shapes[n++] = prim(SHAPE_HALFSPACE, (double[]){0.1, 0.2, 0.3}, (double[]){1, 2, -0.5}, 0, 0, 0);
    shapes[n++] = prim(SHAPE_BOX, (double[]){-0.3, -0.2, -0.4}, (double[]){0.5, 0.7, 0.35}, 0, 0, 0);
    shapes[n++] = prim(SHAPE_SPHERE, (double[]){0.1, -0.05, 0.2}, (double[]){0, 0, 0}, 0.6, 0, 0);
    shapes[n++] = prim(SHAPE_CYLINDER, (double[]){-0.2, -0.3, -0.4}, (double[]){0.3, 0.4, 0.5}, 0.35, 0, 0);
    shapes[n++] = prim(SHAPE_CYLINDER, (double[]){-0.2, -0.3, -0.4}, (double[]){0.3, 0.4, 0.5}, 0.3, 0, 1);
    shapes[n++] = prim(SHAPE_CYLINDER, (double[]){0, 0, -0.5}, (double[]){0, 0, 0.5}, 0.5, 0, 0);
    shapes[n++] = prim(SHAPE_CONE, (double[]){-0.3, 0.1, -0.4}, (double[]){0.4, -0.2, 0.45}, 0.5, 0.2, 0);
    shapes[n++] = prim(SHAPE_CONE, (double[]){0.1, -0.4, 0.2}, (double[]){-0.1, 0.5, -0.3}, 0, 0.6, 0);
    shapes[n++] = prim(SHAPE_CONE, (double[]){0, 0, -0.5}, (double[]){0, 0, 0.6}, 0.7, 0, 0);
    shapes[n++] = prim(SHAPE_TORUS, (double[]){0.05, 0.1, -0.02}, (double[]){0.3, -0.5, 0.8}, 0.6, 0.2, 0);
    shapes[n++] = prim(SHAPE_TORUS, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 0.5, 0.45, 0);
    /* Far from the origin: round-off grows with the coordinates. */
    shapes[n++] = prim(SHAPE_TORUS, (double[]){30, -20, 10}, (double[]){-0.2, 0.1, 1}, 0.7, 0.1, 0);
    shapes[n++] = prim(SHAPE_CONE, (double[]){30.3, -20.1, 9.6}, (double[]){29.8, -19.5, 10.3}, 0.45, 0.05, 0);
    shapes[n++] = poly_shape(2, L_shape, 6, -0.5, 0.4);
    shapes[n++] = poly_shape(0, star_cw, 10, -INFINITY, INFINITY);
    shapes[n++] = poly_shape(1, star_cw, 10, -0.3, 0.6);
    shapes[n++] = poly_shape(1, L_shape, 6, -INFINITY, 0.2);
    shapes[n++] = poly_shape(2, star30, 30, -0.2, 0.3);
    for (int i = 0; i < n; i++) {
        const char *m = shape_check(&shapes[i]);
        if (m) {
            printf("FAIL setup: shape %d rejected: %s\n", i, m);
            exit(1);
        }
    }
}

/* ---- helpers ---- */

static void at(const double a[3], const double b[3], double t, double x[3])
{
    for (int k = 0; k < 3; k++) x[k] = a[k] + t * (b[k] - a[k]);
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static int inside_t(const Shape *s, const double a[3], const double b[3], double t)
{
    double x[3];
    at(a, b, t, x);
    return shape_inside(s, x);
}

/* Region the random segments are drawn from: the shape's bounds widened
   by 0.25, unbounded extents cut to [-1.2, 1.2]. */
static void sample_box(const Shape *s, double lo[3], double hi[3])
{
    shape_bounds(s, lo, hi);
    for (int k = 0; k < 3; k++) {
        lo[k] = isfinite(lo[k]) ? lo[k] - 0.25 : -1.2;
        hi[k] = isfinite(hi[k]) ? hi[k] + 0.25 : 1.2;
    }
}

/* Random segment: long ones across the box, short ones (1e-3 .. 1e-1)
   anywhere in it. */
static void random_segment(gsl_rng *r, const double lo[3], const double hi[3], double a[3], double b[3])
{
    for (int k = 0; k < 3; k++) a[k] = lo[k] + (hi[k] - lo[k]) * gsl_rng_uniform(r);
    if (gsl_rng_uniform(r) < 0.5) {
        for (int k = 0; k < 3; k++) b[k] = lo[k] + (hi[k] - lo[k]) * gsl_rng_uniform(r);
        return;
    }
    double len = pow(10, -5 + 4 * gsl_rng_uniform(r)), d[3], n;
    do {
        for (int k = 0; k < 3; k++) d[k] = 2 * gsl_rng_uniform(r) - 1;
        n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (n > 1 || n < 0.1);
    for (int k = 0; k < 3; k++) b[k] = a[k] + len * d[k] / n;
}

/* Statistics of one random run, printed for the record. */
typedef struct Stats {
    long segs, cross, scanned, tangent;
    double worst_level;   /* max |level(x(t))| / segment length */
    double worst_bisect;  /* max |t - t_bisection| */
    double worst_ulp;     /* max |level(x(t))| / (eps (|x|_1 + 1)) */
} Stats;

#define NSCAN 256

/* Checks one segment; returns a message or NULL. */
static const char *check_segment(const Shape *s, const double a[3], const double b[3], Stats *st, char *buf,
                                 size_t nbuf)
{
    double t[SHAPE_MAX_CROSS], len = dist3(a, b);
    int n = shape_crossings(s, a, b, t, SHAPE_MAX_CROSS);
    int ia = shape_inside(s, a), ib = shape_inside(s, b);
    st->segs++;
    st->cross += n;
    if (n > SHAPE_MAX_CROSS) return "too many crossings";
    if (n % 2 != (ia != ib)) {
        snprintf(buf, nbuf, "%d crossings, inside(a) %d inside(b) %d", n, ia, ib);
        return buf;
    }
    for (int i = 0; i < n; i++) {
        if (!(t[i] >= 0 && t[i] <= 1) || (i && !(t[i] > t[i - 1]))) return "t not ascending in [0, 1]";
        double x[3];
        at(a, b, t[i], x);
        double lv = fabs(shape_level(s, x));
        if (lv / len > st->worst_level) st->worst_level = lv / len;
        /* Round-off scale of the level at x: the coordinates' last bit. */
        double ulp = DBL_EPSILON * (fabs(x[0]) + fabs(x[1]) + fabs(x[2]) + 1);
        if (lv / ulp > st->worst_ulp) st->worst_ulp = lv / ulp;
        if (lv > 4 * ulp) {
            snprintf(buf, nbuf, "level %.3g = %.1f eps at t = %.17g: not exact to round-off", lv, lv / ulp, t[i]);
            return buf;
        }
        if (lv > 1e-12) {
            snprintf(buf, nbuf, "level %.3g at t = %.17g", lv, t[i]);
            return buf;
        }
        /* State just before and after (closer than any neighbour). */
        double gap = 1e-7;
        if (i > 0) gap = fmin(gap, (t[i] - t[i - 1]) / 3);
        if (i + 1 < n) gap = fmin(gap, (t[i + 1] - t[i]) / 3);
        double t0 = t[i] - gap, t1 = t[i] + gap;
        int s0 = t0 < 0 ? ia : inside_t(s, a, b, t0), s1 = t1 > 1 ? ib : inside_t(s, a, b, t1);
        /* A segment that runs within round-off of the surface (in a
           tilted plane, say) has a round-off state on both sides. */
        double x0[3], x1[3];
        at(a, b, t0, x0);
        at(a, b, t1, x1);
        int hugging = fmax(fabs(shape_level(s, x0)), fabs(shape_level(s, x1))) <= 1e-15;
        if (s0 == s1 && gap * len > 1e-12 && !hugging) {
            snprintf(buf, nbuf, "state %d on both sides of t = %.17g (gap %.3g)", s0, t[i], gap);
            return buf;
        }
    }
    /* Brute-force scan; the samples are offset by an irrational fraction
       of the spacing so that lattice-aligned segments do not put them on
       the surface. */
    int prev = ia, k = 0, prevfuzzy = fabs(shape_level(s, a)) <= 1e-15;
    double tp = 0;
    for (int j = 0; j <= NSCAN; j++) {
        double tj = j == NSCAN ? 1 : (j + 0.6180339887498949) / (NSCAN + 1);
        double xs[3];
        at(a, b, tj, xs);
        double lv = j == NSCAN ? shape_level(s, b) : shape_level(s, xs);
        int cur = lv < 0, m = 0, first = k;
        int fuzzy = fabs(lv) <= 1e-15;   /* a sample on the surface to round-off */
        while (k < n && t[k] <= tj) k++, m++;
        if (fuzzy || prevfuzzy) {
            prev = cur, tp = tj, prevfuzzy = fuzzy;
            continue;
        }
        if (m % 2 != (cur != prev)) {
            snprintf(buf, nbuf, "scan interval [%g, %g]: %d crossings, states %d -> %d", tp, tj, m, prev, cur);
            return buf;
        }
        if (m == 1) {
            double lo = tp, hi = tj;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi);
                if (inside_t(s, a, b, mid) == prev) lo = mid;
                else hi = mid;
            }
            double e = fabs(0.5 * (lo + hi) - t[first]), xb[3];
            at(a, b, 0.5 * (lo + hi), xb);
            /* A tangential end (the segment touches the surface at an end
               from inside) is a double root: the level sign is round-off
               over ~1e-8 of t, so bisection only finds a point where the
               level vanishes to round-off. */
            if (e > 1e-12 && fabs(shape_level(s, xb)) <= 1e-15) {
                st->tangent++;
                e = 0;
            }
            if (e > st->worst_bisect) st->worst_bisect = e;
            /* 1e-12, or the round-off of t for a short segment far out. */
            double tol = fmax(1e-12, 64 * DBL_EPSILON * (fabs(xb[0]) + fabs(xb[1]) + fabs(xb[2]) + 1) / len);
            if (e > tol) {
                snprintf(buf, nbuf, "crossing %.17g, bisection %.17g", t[first], 0.5 * (lo + hi));
                return buf;
            }
            st->scanned++;
        }
        prev = cur, tp = tj, prevfuzzy = fuzzy;
    }
    return NULL;
}

/* Random segments against every shape of one kind. */
static void random_kind(int kind, int nseg)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 12345 + (unsigned long)kind);
    Stats st = {0, 0, 0, 0, 0, 0, 0};
    char buf[256];
    int nsh = 0;
    for (int i = 0; i < NSHAPES; i++) nsh += shapes[i].kind == kind;
    for (int i = 0; i < NSHAPES && !test_failed_now; i++) {
        const Shape *s = &shapes[i];
        if (s->kind != kind) continue;
        double lo[3], hi[3], a[3], b[3];
        sample_box(s, lo, hi);
        for (int j = 0; j < nseg / nsh; j++) {
            random_segment(r, lo, hi, a, b);
            const char *m = check_segment(s, a, b, &st, buf, sizeof buf);
            EXPECT(!m, "shape %d segment %d (%.17g %.17g %.17g)-(%.17g %.17g %.17g): %s", i, j, a[0], a[1], a[2],
                   b[0], b[1], b[2], m);
            if (m) break;
        }
    }
    printf("  %-9s %ld segments, %ld crossings (%ld bisected): max |level|/length %.2e, max |level|/eps(|x|+1) "
           "%.1f, max |t - t_bisect| %.2e\n",
           shape_kind_name(kind), st.segs, st.cross, st.scanned, st.worst_level, st.worst_ulp, st.worst_bisect);
    EXPECT(st.cross > st.segs / 5, "only %ld crossings in %ld segments", st.cross, st.segs);
    gsl_rng_free(r);
}

#define NSEG 12000
TEST(random_halfspace) { random_kind(SHAPE_HALFSPACE, NSEG); }
TEST(random_box) { random_kind(SHAPE_BOX, NSEG); }
TEST(random_sphere) { random_kind(SHAPE_SPHERE, NSEG); }
TEST(random_cylinder) { random_kind(SHAPE_CYLINDER, NSEG); }
TEST(random_cone) { random_kind(SHAPE_CONE, NSEG); }
TEST(random_torus) { random_kind(SHAPE_TORUS, NSEG); }
TEST(random_polygon) { random_kind(SHAPE_POLYGON, NSEG); }

/* Shapes whose faces, edges, corners, rims, apex and tangent planes lie on
   the lattice {-0.75, -0.625, ..., 0.75}^3, as a cutter's grid would meet
   them: edges in faces, through corners, ending on the surface. */
static double grid_L[] = {-0.5, -0.5, 0.5, -0.5, 0.5, 0, 0, 0, 0, 0.5, -0.5, 0.5};

static void grid_shapes(Shape *g)
{
    g[0] = prim(SHAPE_BOX, (double[]){-0.5, -0.25, -0.375}, (double[]){0.375, 0.5, 0.25}, 0, 0, 0);
    g[1] = prim(SHAPE_SPHERE, (double[]){0, 0, 0}, (double[]){0, 0, 0}, 0.5, 0, 0);
    g[2] = prim(SHAPE_CYLINDER, (double[]){0, 0, -0.5}, (double[]){0, 0, 0.5}, 0.5, 0, 0);
    g[3] = prim(SHAPE_CONE, (double[]){0, 0, -0.5}, (double[]){0, 0, 0.5}, 0, 0.5, 0);
    g[4] = prim(SHAPE_TORUS, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 0.5, 0.25, 0);
    g[5] = poly_shape(2, grid_L, 6, -0.5, 0.5);
    g[6] = prim(SHAPE_HALFSPACE, (double[]){0.125, 0.125, 0}, (double[]){1, 1, 1}, 0, 0, 0);
    g[7] = prim(SHAPE_CONE, (double[]){0, -0.5, 0}, (double[]){0, 0.5, 0}, 0.5, 0.25, 0);
    for (int i = 0; i < 8; i++) shape_check(&g[i]);
}

TEST(grid_degenerate)
{
    Shape g[8];
    grid_shapes(g);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 4242);
    char buf[256];
    const int N = 13;
    for (int i = 0; i < 8 && !test_failed_now; i++) {
        Stats st = {0, 0, 0, 0, 0, 0, 0};
        const char *m = NULL;
        double a[3], b[3];
        /* Every lattice edge along each axis. */
        for (int ax = 0; ax < 3 && !m; ax++)
            for (int j = 0; j < N * N * (N - 1) && !m; j++) {
                int idx[3] = {j % (N - 1), j / (N - 1) % N, j / (N - 1) / N};
                for (int k = 0; k < 3; k++) a[(ax + k) % 3] = b[(ax + k) % 3] = -0.75 + 0.125 * idx[k];
                b[ax] += 0.125;
                m = check_segment(&g[i], a, b, &st, buf, sizeof buf);
            }
        /* Segments between random lattice points (diagonals through
           corners, rims, vertices). */
        for (int j = 0; j < 3000 && !m; j++) {
            for (int k = 0; k < 3; k++) {
                a[k] = -0.75 + 0.125 * (double)gsl_rng_uniform_int(r, N);
                b[k] = -0.75 + 0.125 * (double)gsl_rng_uniform_int(r, N);
            }
            m = check_segment(&g[i], a, b, &st, buf, sizeof buf);
        }
        EXPECT(!m, "%s: segment (%.17g %.17g %.17g)-(%.17g %.17g %.17g): %s", shape_kind_name(g[i].kind), a[0],
               a[1], a[2], b[0], b[1], b[2], m);
        printf("  %-9s %ld lattice segments, %ld crossings (%ld tangential), max |level|/eps(|x|+1) %.1f\n",
               shape_kind_name(g[i].kind), st.segs, st.cross, st.tangent, st.worst_ulp);
    }
    shape_free(&g[5]);
    gsl_rng_free(r);
}

/* Crossings of a -> b, expected exactly (count and values to tol). */
static void expect_cross(const Shape *s, const double a[3], const double b[3], int n, const double *t, double tol,
                         const char *what)
{
    double got[SHAPE_MAX_CROSS];
    int m = shape_crossings(s, a, b, got, SHAPE_MAX_CROSS);
    EXPECT(m == n, "%s: %d crossings, expected %d (first %.17g)", what, m, n, m ? got[0] : -1.0);
    for (int i = 0; i < n && i < m; i++)
        EXPECT(fabs(got[i] - t[i]) <= tol, "%s: crossing %d at %.17g, expected %.17g", what, i, got[i], t[i]);
}

TEST(box_corners_edges)
{
    Shape s = prim(SHAPE_BOX, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 0, 0, 0);
    EXPECT(!shape_check(&s), "box rejected");
    /* Body diagonal: in through corner (0,0,0), out through (1,1,1). */
    expect_cross(&s, (double[]){-1, -1, -1}, (double[]){2, 2, 2}, 2, (double[]){1.0 / 3, 2.0 / 3}, 1e-15,
                 "diagonal");
    /* Grazing a corner from outside to outside. */
    expect_cross(&s, (double[]){-1, 1, -1}, (double[]){1, -1, 1}, 0, NULL, 0, "corner touch");
    /* Along an edge, and inside a face plane. */
    expect_cross(&s, (double[]){-1, 0, 0}, (double[]){2, 0, 0}, 0, NULL, 0, "along edge");
    expect_cross(&s, (double[]){-1, 0.5, 1}, (double[]){2, 0.3, 1}, 0, NULL, 0, "in face plane");
    /* Across an edge into the box, ending on the opposite edge (on the
       surface, so outside): two crossings, the second at t = 1. */
    expect_cross(&s, (double[]){-1, -1, 0.5}, (double[]){1, 1, 0.5}, 2, (double[]){0.5, 1}, 1e-15, "edge to edge");
    /* Starting on a face going in, ending on a face going... out. */
    expect_cross(&s, (double[]){0, 0.5, 0.5}, (double[]){2, 0.5, 0.5}, 2, (double[]){0, 0.5}, 1e-15, "face start");
    expect_cross(&s, (double[]){0, 0.5, 0.5}, (double[]){-2, 0.5, 0.5}, 0, NULL, 0, "face start outward");
    /* Degenerate segment. */
    expect_cross(&s, (double[]){0.5, 0.5, 0.5}, (double[]){0.5, 0.5, 0.5}, 0, NULL, 0, "a == b");
    /* More crossings than room: the count is still right. */
    double t1[1];
    EXPECT(shape_crossings(&s, (double[]){-1, 0.5, 0.5}, (double[]){2, 0.5, 0.5}, t1, 1) == 2, "count beyond max");
    NEAR(t1[0], 1.0 / 3, 1e-15);
}

TEST(sphere_exact)
{
    Shape s = prim(SHAPE_SPHERE, (double[]){0, 0, 0}, (double[]){0, 0, 0}, 1, 0, 0);
    EXPECT(!shape_check(&s), "sphere rejected");
    expect_cross(&s, (double[]){-2, 0, 0}, (double[]){2, 0, 0}, 2, (double[]){0.25, 0.75}, 1e-16, "through centre");
    expect_cross(&s, (double[]){-2, 1, 0}, (double[]){2, 1, 0}, 0, NULL, 0, "tangent");
    expect_cross(&s, (double[]){0, -2, 1}, (double[]){0, 2, 1}, 0, NULL, 0, "tangent (y)");
    /* Chord at height 0.6: x = +-0.8. */
    expect_cross(&s, (double[]){-1, 0.6, 0}, (double[]){1, 0.6, 0}, 2, (double[]){0.1, 0.9}, 1e-15, "chord");
    /* Far from the origin: a large sphere, a short segment across its
       surface (relative accuracy in t is what the cutter needs). */
    Shape big = prim(SHAPE_SPHERE, (double[]){3, 4, 5}, (double[]){0, 0, 0}, 10, 0, 0);
    shape_check(&big);
    double a[3] = {3 + 10 - 0.0005, 4, 5}, b[3] = {3 + 10 + 0.0005, 4, 5};
    expect_cross(&big, a, b, 1, (double[]){0.5}, 2e-12, "short edge on a big sphere");
}

TEST(cylinder_cone_rims)
{
    Shape c = prim(SHAPE_CYLINDER, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 1, 0, 0);
    EXPECT(!shape_check(&c), "cylinder rejected");
    expect_cross(&c, (double[]){0, 0, 2}, (double[]){2, 0, 0}, 0, NULL, 0, "rim touch");
    expect_cross(&c, (double[]){1.5, 0, 1.5}, (double[]){0.5, 0, 0.5}, 1, (double[]){0.5}, 1e-15, "through rim");
    expect_cross(&c, (double[]){0.5, 0, -1}, (double[]){0.5, 0, 3}, 2, (double[]){0.25, 0.5}, 1e-15, "through caps");
    expect_cross(&c, (double[]){1, 0, -1}, (double[]){1, 0, 3}, 0, NULL, 0, "along the side");
    expect_cross(&c, (double[]){-2, 1, 0.5}, (double[]){2, 1, 0.5}, 0, NULL, 0, "tangent to the side");
    Shape inf = c;
    inf.infinite = 1;
    expect_cross(&inf, (double[]){0.5, 0, -1}, (double[]){0.5, 0, 3}, 0, NULL, 0, "infinite: along axis");
    expect_cross(&inf, (double[]){-3, 0, 7}, (double[]){3, 0, 9}, 2, (double[]){1.0 / 3, 2.0 / 3}, 1e-15,
                 "infinite: across");
    /* Cone, apex at the origin, radius 1 at z = 1. */
    Shape k = prim(SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 0, 1, 0);
    EXPECT(!shape_check(&k), "cone rejected");
    expect_cross(&k, (double[]){0, 0, -1}, (double[]){0, 0, 0.5}, 1, (double[]){2.0 / 3}, 1e-15, "into the apex");
    expect_cross(&k, (double[]){-0.5, 0, -1}, (double[]){0.5, 0, 1}, 2, (double[]){0.5, 1}, 1e-15,
                 "through the apex to the top disc");
    expect_cross(&k, (double[]){-1, 0, -1}, (double[]){1, 0, 1}, 0, NULL, 0, "along a generator");
    expect_cross(&k, (double[]){1.5, 0, 1.1}, (double[]){0.5, 0, 0.9}, 1, (double[]){0.5}, 1e-15, "through rim");
    expect_cross(&k, (double[]){0, 0, 2}, (double[]){2, 0, 0}, 0, NULL, 0, "rim touch");
    expect_cross(&k, (double[]){-0.5, 0, 0.5}, (double[]){0.5, 0, 0.5}, 2, (double[]){0, 1}, 1e-15,
                 "chord ending on the side");
    /* Parallel to a generator: the quadratic degenerates to linear. */
    expect_cross(&k, (double[]){-0.5, 0, 0.2}, (double[]){0.3, 0, 1}, 2, (double[]){0.1875, 1}, 1e-15,
                 "parallel to a generator");
    /* Truncated cone, radius 1 at z = 0 and 0.5 at z = 1: the side at
       height 0.5 has radius 0.75. */
    Shape f = prim(SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 1, 0.5, 0);
    shape_check(&f);
    expect_cross(&f, (double[]){-1, 0, 0.5}, (double[]){1, 0, 0.5}, 2, (double[]){0.125, 0.875}, 1e-15, "frustum");
    expect_cross(&f, (double[]){1.5, 0, -0.4}, (double[]){0.5, 0, 0.4}, 1, (double[]){0.5}, 1e-15, "frustum bottom rim");
}

TEST(torus_exact)
{
    Shape s = prim(SHAPE_TORUS, (double[]){0, 0, 0}, (double[]){0, 0, 2}, 1, 0.25, 0);
    EXPECT(!shape_check(&s), "torus rejected");
    NEAR(s.q[2], 1, 0);
    expect_cross(&s, (double[]){0, 0, -2}, (double[]){0, 0, 2}, 0, NULL, 0, "along the axis");
    expect_cross(&s, (double[]){-2, 0, 0}, (double[]){2, 0, 0}, 4, (double[]){0.1875, 0.3125, 0.6875, 0.8125}, 1e-15,
                 "through both tube sections");
    expect_cross(&s, (double[]){1, -1, 0}, (double[]){1, 1, 0}, 2, (double[]){0.5 - sqrt(0.5625) / 2, 0.5 + sqrt(0.5625) / 2},
                 1e-15, "line x = 1 across the ring");
    expect_cross(&s, (double[]){-2, 0, 0.25}, (double[]){2, 0, 0.25}, 0, NULL, 0, "tangent to the top");
    expect_cross(&s, (double[]){1, 0, -1}, (double[]){1, 0, 1}, 2, (double[]){0.375, 0.625}, 1e-15,
                 "through the tube vertically");
    /* Rotated and shifted: through the tube along its axis direction. */
    Shape r = prim(SHAPE_TORUS, (double[]){1, 2, 3}, (double[]){1, 1, 0}, 2, 0.5, 0);
    shape_check(&r);
    double e[3] = {1 / sqrt(2.0), -1 / sqrt(2.0), 0};   /* radial, in the torus plane */
    double a[3], b[3];
    for (int k = 0; k < 3; k++) a[k] = r.p[k] + 2 * e[k] - r.q[k];
    for (int k = 0; k < 3; k++) b[k] = a[k] + 2 * r.q[k];
    expect_cross(&r, a, b, 2, (double[]){0.25, 0.75}, 1e-14, "rotated, through the tube");
}

TEST(polygon_vertices)
{
    /* Unit square with a notch: (0,0) (2,0) (2,2) (1,1) (0,2), extruded
       along z between 0 and 1. */
    double pts[] = {0, 0, 2, 0, 2, 2, 1, 1, 0, 2};
    Shape s = poly_shape(2, pts, 5, 0, 1);
    EXPECT(!shape_check(&s), "polygon rejected");
    /* The diagonal y = x enters at vertex (0,0) and leaves at the reflex
       vertex (1,1), beyond which it runs along the wall (1,1)-(2,2). */
    expect_cross(&s, (double[]){-1, -1, 0.5}, (double[]){3, 3, 0.5}, 2, (double[]){0.25, 0.5}, 1e-15,
                 "diagonal through two vertices");
    /* Horizontal line y = 2 touches vertices (0,2) and (2,2) only. */
    expect_cross(&s, (double[]){-1, 2, 0.5}, (double[]){3, 2, 0.5}, 0, NULL, 0, "touching two vertices");
    /* Horizontal line through the reflex vertex: y = 1 enters at x = 0,
       touches (1,1) from inside, leaves at x = 2. */
    expect_cross(&s, (double[]){-1, 1, 0.5}, (double[]){3, 1, 0.5}, 2, (double[]){0.25, 0.75}, 1e-15,
                 "touching the reflex vertex from inside");
    /* Along a wall (x = 0): outside throughout. */
    expect_cross(&s, (double[]){0, -1, 0.5}, (double[]){0, 3, 0.5}, 0, NULL, 0, "along a wall");
    /* Through a rim: the vertex (2,0) at z = 1 from above-outside. */
    expect_cross(&s, (double[]){2.5, -0.5, 1.5}, (double[]){1.5, 0.5, 0.5}, 1, (double[]){0.5}, 1e-15, "through a rim corner");
    /* Vertical through the caps at an interior point. */
    expect_cross(&s, (double[]){0.5, 0.3, -1}, (double[]){0.5, 0.3, 3}, 2, (double[]){0.25, 0.5}, 1e-15, "caps");
    shape_free(&s);
}

/* ---- normals and nearest points ---- */

static void expect_normal(const Shape *s, const double x[3], const double n[3], const char *what)
{
    double g[3];
    shape_normal(s, x, g);
    double e = fmax(fabs(g[0] - n[0]), fmax(fabs(g[1] - n[1]), fabs(g[2] - n[2])));
    EXPECT(e <= 1e-14, "%s: normal (%.17g %.17g %.17g), expected (%.17g %.17g %.17g)", what, g[0], g[1], g[2], n[0],
           n[1], n[2]);
}

static void expect_closest(const Shape *s, const double x[3], const double c[3], const char *what)
{
    double g[3];
    shape_closest(s, x, g);
    EXPECT(dist3(g, c) <= 1e-14, "%s: closest (%.17g %.17g %.17g), expected (%.17g %.17g %.17g)", what, g[0], g[1],
           g[2], c[0], c[1], c[2]);
}

TEST(normals_analytic)
{
    double s2 = 1 / sqrt(2.0);
    Shape h = prim(SHAPE_HALFSPACE, (double[]){0, 0, 1}, (double[]){0, 3, 4}, 0, 0, 0);
    shape_check(&h);
    expect_normal(&h, (double[]){5, 7, -2}, (double[]){0, 0.6, 0.8}, "halfSpace");
    expect_closest(&h, (double[]){1, 0, 2}, (double[]){1, -0.48, 1.36}, "halfSpace");
    Shape b = prim(SHAPE_BOX, (double[]){0, 0, 0}, (double[]){1, 2, 3}, 0, 0, 0);
    shape_check(&b);
    expect_normal(&b, (double[]){0.5, 1, 2.9}, (double[]){0, 0, 1}, "box inside near +z");
    expect_normal(&b, (double[]){-0.5, 1, 1}, (double[]){-1, 0, 0}, "box outside -x");
    expect_normal(&b, (double[]){1.5, 2.2, 1}, (double[]){1, 0, 0}, "box outside off the +x+y edge");
    expect_normal(&b, (double[]){0, 0, 0}, (double[]){-1, 0, 0}, "box corner tie: first face");
    expect_closest(&b, (double[]){1.5, 2.2, 1}, (double[]){1, 2, 1}, "box edge");
    expect_closest(&b, (double[]){0.5, 1.9, 1.5}, (double[]){0.5, 2, 1.5}, "box inside");
    Shape sp = prim(SHAPE_SPHERE, (double[]){1, 1, 1}, (double[]){0, 0, 0}, 2, 0, 0);
    shape_check(&sp);
    expect_normal(&sp, (double[]){1 + 2 * s2, 1, 1 + 2 * s2}, (double[]){s2, 0, s2}, "sphere");
    expect_closest(&sp, (double[]){1, 4, 1}, (double[]){1, 3, 1}, "sphere outside");
    Shape c = prim(SHAPE_CYLINDER, (double[]){0, 0, 0}, (double[]){0, 0, 2}, 1, 0, 0);
    shape_check(&c);
    expect_normal(&c, (double[]){s2, s2, 1}, (double[]){s2, s2, 0}, "cylinder side");
    expect_normal(&c, (double[]){0.2, 0.1, 1.95}, (double[]){0, 0, 1}, "cylinder near top");
    expect_normal(&c, (double[]){0.2, 0.1, -0.01}, (double[]){0, 0, -1}, "cylinder below");
    expect_closest(&c, (double[]){3, 0, 3}, (double[]){1, 0, 2}, "cylinder rim");
    expect_closest(&c, (double[]){0.5, 0, 1}, (double[]){1, 0, 1}, "cylinder inside");
    /* Cone radius 1 at z = 0, 0 at z = 1: side normal (1, 0, 1)/sqrt 2. */
    Shape k = prim(SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 1, 0, 0);
    shape_check(&k);
    expect_normal(&k, (double[]){0, 0.5, 0.5}, (double[]){0, s2, s2}, "cone side");
    expect_normal(&k, (double[]){0, 0.6, 0.6}, (double[]){0, s2, s2}, "cone outside side");
    expect_normal(&k, (double[]){0.1, 0, 0.05}, (double[]){0, 0, -1}, "cone near base");
    expect_closest(&k, (double[]){0, 1, 1}, (double[]){0, 0.5, 0.5}, "cone outside");
    expect_closest(&k, (double[]){0, 0, 2}, (double[]){0, 0, 1}, "cone above apex");
    expect_closest(&k, (double[]){2, 0, -1}, (double[]){1, 0, 0}, "cone below rim");
    Shape t = prim(SHAPE_TORUS, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 1, 0.25, 0);
    shape_check(&t);
    expect_normal(&t, (double[]){1.25, 0, 0}, (double[]){1, 0, 0}, "torus outer");
    expect_normal(&t, (double[]){0, 0.75, 0}, (double[]){0, -1, 0}, "torus inner");
    expect_normal(&t, (double[]){s2, s2, 0.25}, (double[]){0, 0, 1}, "torus top");
    expect_closest(&t, (double[]){0, 3, 1}, (double[]){0, 1 + 0.25 * 2 / sqrt(5.0), 0.25 / sqrt(5.0)},
                   "torus outside");
    double sq[] = {0, 0, 2, 0, 2, 2, 0, 2};
    Shape p = poly_shape(0, sq, 4, -1, 1);   /* (u, v) = (y, z) */
    shape_check(&p);
    expect_normal(&p, (double[]){0, 1, 1.95}, (double[]){0, 0, 1}, "polygon wall");
    expect_normal(&p, (double[]){0.95, 1, 1}, (double[]){1, 0, 0}, "polygon hi cap");
    expect_normal(&p, (double[]){0, -0.5, 1}, (double[]){0, -1, 0}, "polygon outside wall");
    expect_closest(&p, (double[]){2, 3, 3}, (double[]){1, 2, 2}, "polygon corner");
    expect_closest(&p, (double[]){0.2, 1, 0.1}, (double[]){0.2, 1, 0}, "polygon inside");
    shape_free(&p);
    /* Points where the direction is undefined (a sphere's centre, an
       axis): still a unit normal and a surface point at distance
       |level|. */
    Shape inf = c;
    inf.infinite = 1;
    const Shape *deg[] = {&sp, &c, &inf, &k, &t};
    const double xs[][3] = {{1, 1, 1}, {0, 0, 1.2}, {0, 0, 7}, {0, 0, 0.3}, {0, 0, 0.5}};
    for (int i = 0; i < 5; i++) {
        double n[3], cl[3];
        shape_normal(deg[i], xs[i], n);
        shape_closest(deg[i], xs[i], cl);
        NEAR(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1, 1e-15);
        NEAR(shape_level(deg[i], cl), 0, 1e-15);
        NEAR(dist3(xs[i], cl), fabs(shape_level(deg[i], xs[i])), 1e-15);
    }
}

/* Random points: the nearest point is on the surface, at distance
   |level|, and a smooth face's normal points from it to x. */
TEST(closest_random)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 777);
    double worst_on = 0, worst_d = 0, worst_n = 0;
    for (int i = 0; i < NSHAPES; i++) {
        const Shape *s = &shapes[i];
        double lo[3], hi[3], x[3], c[3], n[3];
        sample_box(s, lo, hi);
        for (int j = 0; j < 2000; j++) {
            for (int k = 0; k < 3; k++) x[k] = lo[k] + (hi[k] - lo[k]) * gsl_rng_uniform(r);
            shape_closest(s, x, c);
            shape_normal(s, x, n);
            double lv = shape_level(s, x), d = dist3(x, c);
            double ulp = DBL_EPSILON * (fabs(x[0]) + fabs(x[1]) + fabs(x[2]) + 1);   /* round-off at x */
            worst_on = fmax(worst_on, fabs(shape_level(s, c)) / ulp);
            worst_d = fmax(worst_d, fabs(d - fabs(lv)) / ulp);
            NEAR(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1, 1e-15);
            EXPECT(fabs(shape_level(s, c)) <= 4 * ulp, "shape %d: level %.3g at the nearest point", i,
                   shape_level(s, c));
            EXPECT(fabs(d - fabs(lv)) <= 4 * ulp, "shape %d: |x - c| %.17g, |level| %.17g", i, d, fabs(lv));
            /* n . (x - c) = level when the nearest point is inside the
               face whose normal is returned: always for smooth kinds, and
               for inside points of convex ones.  Otherwise (an edge, a
               corner, a polygon's reflex vertex) n still points from the
               solid towards x's side. */
            double nd = n[0] * (x[0] - c[0]) + n[1] * (x[1] - c[1]) + n[2] * (x[2] - c[2]);
            int smooth = s->kind == SHAPE_SPHERE || s->kind == SHAPE_TORUS || s->kind == SHAPE_HALFSPACE;
            if (smooth || (lv < 0 && s->kind != SHAPE_POLYGON)) {
                worst_n = fmax(worst_n, fabs(nd - lv) / ulp);
                EXPECT(fabs(nd - lv) <= 4 * ulp, "shape %d: n.(x - c) %.17g, level %.17g", i, nd, lv);
            } else {
                EXPECT(lv < 0 ? nd <= 1e-15 : nd >= -1e-15, "shape %d: n.(x - c) %.3g, level %.3g", i, nd, lv);
            }
        }
    }
    printf("  in units of eps (|x|_1 + 1): max |level(closest)| %.2f, max | |x - c| - |level| | %.2f, max "
           "|n.(x-c) - level| %.2f\n",
           worst_on, worst_d, worst_n);
    gsl_rng_free(r);
}

/* ---- volume, area, bounds ---- */

/* Sobol estimate of the volume inside a box lo..hi; returns the estimate
   and its one-sigma binomial error in *sig (QMC is better than that). */
static double qmc_volume(const Shape *s, const double lo[3], const double hi[3], int n, double *sig)
{
    gsl_qrng *q = gsl_qrng_alloc(gsl_qrng_sobol, 3);
    double u[3], x[3];
    long in = 0;
    for (int i = 0; i < n; i++) {
        gsl_qrng_get(q, u);
        for (int k = 0; k < 3; k++) x[k] = lo[k] + (hi[k] - lo[k]) * u[k];
        in += shape_inside(s, x);
    }
    gsl_qrng_free(q);
    double V = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]), f = (double)in / n;
    *sig = V * sqrt(f * (1 - f) / n);
    return V * f;
}

TEST(volume_qmc)
{
    printf("  kind      exact V      Sobol 2^16   |diff|/sigma\n");
    for (int i = 0; i < NSHAPES; i++) {
        const Shape *s = &shapes[i];
        double lo[3], hi[3], sig;
        shape_bounds(s, lo, hi);
        if (!isfinite(shape_volume(s))) continue;
        for (int k = 0; k < 3; k++) {   /* a margin, so a box does not fill it */
            double m = 0.05 * (hi[k] - lo[k]);
            lo[k] -= m, hi[k] += m;
        }
        double V = shape_volume(s), q = qmc_volume(s, lo, hi, 1 << 16, &sig);
        printf("  %-9s %.6f  %.6f  %.2f\n", shape_kind_name(s->kind), V, q, fabs(V - q) / sig);
        EXPECT(fabs(V - q) <= 3 * sig, "shape %d (%s): volume %.17g, Sobol %.17g, sigma %.3g", i,
               shape_kind_name(s->kind), V, q, sig);
    }
}

/* Surface area from the volume of the shell |level| < eps (level is the
   signed distance): A = (V(level < eps) - V(level < -eps)) / (2 eps) +
   O(eps^2); checked for smooth kinds to 3 %. */
TEST(area_shell)
{
    const double eps = 0.02;
    for (int i = 0; i < NSHAPES; i++) {
        const Shape *s = &shapes[i];
        if (s->kind != SHAPE_SPHERE && s->kind != SHAPE_TORUS) continue;
        double lo[3], hi[3], u[3], x[3];
        shape_bounds(s, lo, hi);
        for (int k = 0; k < 3; k++) lo[k] -= eps, hi[k] += eps;
        gsl_qrng *q = gsl_qrng_alloc(gsl_qrng_sobol, 3);
        long shell = 0;
        int n = 1 << 17;
        for (int j = 0; j < n; j++) {
            gsl_qrng_get(q, u);
            for (int k = 0; k < 3; k++) x[k] = lo[k] + (hi[k] - lo[k]) * u[k];
            shell += fabs(shape_level(s, x)) < eps;
        }
        gsl_qrng_free(q);
        double V = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
        double A = V * (double)shell / n / (2 * eps);
        printf("  %-9s area %.6f, shell estimate %.6f\n", shape_kind_name(s->kind), shape_area(s), A);
        EXPECT(fabs(A - shape_area(s)) <= 0.03 * shape_area(s), "shape %d: area %.6g, shell %.6g", i, shape_area(s),
               A);
    }
}

TEST(exact_values)
{
    Shape b = prim(SHAPE_BOX, (double[]){0, 0, 0}, (double[]){1, 2, 3}, 0, 0, 0);
    NEAR(shape_volume(&b), 6, 0);
    NEAR(shape_area(&b), 22, 0);
    Shape sp = prim(SHAPE_SPHERE, (double[]){0, 0, 0}, (double[]){0, 0, 0}, 2, 0, 0);
    NEAR(shape_volume(&sp), 32 * PI_ / 3, 1e-14);
    NEAR(shape_area(&sp), 16 * PI_, 1e-14);
    Shape c = prim(SHAPE_CYLINDER, (double[]){0, 0, 0}, (double[]){0, 3, 4}, 2, 0, 0);
    NEAR(shape_volume(&c), 20 * PI_, 1e-13);
    NEAR(shape_area(&c), 2 * PI_ * 2 * 5 + 8 * PI_, 1e-13);
    c.infinite = 1;
    EXPECT(isinf(shape_volume(&c)) && isinf(shape_area(&c)), "infinite cylinder is unbounded");
    /* Frustum r1 = 3, r2 = 0 over h = 4: slant 5. */
    Shape k = prim(SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 4}, 3, 0, 0);
    NEAR(shape_volume(&k), 12 * PI_, 1e-13);
    NEAR(shape_area(&k), 15 * PI_ + 9 * PI_, 1e-13);
    Shape f = prim(SHAPE_CONE, (double[]){0, 0, 0}, (double[]){0, 0, 4}, 4, 1, 0);
    NEAR(shape_volume(&f), PI_ * 4 / 3 * 21, 1e-13);
    NEAR(shape_area(&f), PI_ * 5 * 5 + 17 * PI_, 1e-13);
    Shape t = prim(SHAPE_TORUS, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 3, 1, 0);
    NEAR(shape_volume(&t), 6 * PI_ * PI_, 1e-13);
    NEAR(shape_area(&t), 12 * PI_ * PI_, 1e-13);
    double tri[] = {0, 0, 4, 0, 0, 3};
    Shape p = poly_shape(2, tri, 3, 1, 3);
    NEAR(shape_volume(&p), 12, 1e-14);
    NEAR(shape_area(&p), 12 + 12 * 2, 1e-14);
    p.hi = INFINITY;
    EXPECT(isinf(shape_volume(&p)) && isinf(shape_area(&p)), "open prism is unbounded");
    shape_free(&p);
    Shape h = prim(SHAPE_HALFSPACE, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 0, 0, 0);
    EXPECT(isinf(shape_volume(&h)), "halfSpace volume");
}

TEST(bounds)
{
    double lo[3], hi[3];
    Shape t = prim(SHAPE_TORUS, (double[]){1, 2, 3}, (double[]){0, 0, 1}, 2, 0.5, 0);
    shape_check(&t);
    shape_bounds(&t, lo, hi);
    NEAR(lo[0], -1.5, 1e-15);
    NEAR(hi[1], 4.5, 1e-15);
    NEAR(lo[2], 2.5, 1e-15);
    NEAR(hi[2], 3.5, 1e-15);
    Shape c = prim(SHAPE_CYLINDER, (double[]){0, 0, 0}, (double[]){0, 0, 1}, 1, 0, 1);
    shape_check(&c);
    shape_bounds(&c, lo, hi);
    EXPECT(lo[0] == -1 && hi[1] == 1 && isinf(lo[2]) && isinf(hi[2]), "infinite cylinder bounds");
    Shape h = prim(SHAPE_HALFSPACE, (double[]){0, 0, 2}, (double[]){0, 0, 1}, 0, 0, 0);
    shape_check(&h);
    shape_bounds(&h, lo, hi);
    EXPECT(hi[2] == 2 && isinf(lo[2]) && isinf(hi[0]), "halfSpace bounds");
    /* Every random surface point of every shape lies within its bounds. */
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 99);
    for (int i = 0; i < NSHAPES; i++) {
        double x[3], cl[3], slo[3], shi[3];
        shape_bounds(&shapes[i], lo, hi);
        sample_box(&shapes[i], slo, shi);
        for (int j = 0; j < 500; j++) {
            for (int k = 0; k < 3; k++) x[k] = slo[k] + (shi[k] - slo[k]) * gsl_rng_uniform(r);
            shape_closest(&shapes[i], x, cl);
            for (int k = 0; k < 3; k++)
                EXPECT(cl[k] >= lo[k] - 1e-14 && cl[k] <= hi[k] + 1e-14, "shape %d: surface point outside bounds", i);
        }
    }
    gsl_rng_free(r);
}

/* ---- validation ---- */

static void expect_bad(Shape s, const char *sub)
{
    const char *m = shape_check(&s);
    EXPECT(m != NULL, "accepted, expected \"%s\"", sub);
    CONTAINS(m, sub);
    shape_free(&s);
}

TEST(check_messages)
{
    double z[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    expect_bad(prim(SHAPE_HALFSPACE, z, z, 0, 0, 0), "normal must be a finite non-zero vector");
    expect_bad(prim(SHAPE_BOX, one, z, 0, 0, 0), "max corner must exceed min corner in x, found min 1, max 0");
    expect_bad(prim(SHAPE_SPHERE, z, z, -1, 0, 0), "radius must be positive, found -1");
    expect_bad(prim(SHAPE_SPHERE, z, z, NAN, 0, 0), "radius must be positive, found nan");
    expect_bad(prim(SHAPE_CYLINDER, one, one, 1, 0, 0), "axis end points must differ, both are (1 1 1)");
    expect_bad(prim(SHAPE_CONE, z, one, 0, 0, 0), "radius1 and radius2 must not both be zero");
    expect_bad(prim(SHAPE_CONE, z, one, 1, -2, 0), "radius2 must be non-negative, found -2");
    expect_bad(prim(SHAPE_TORUS, z, one, 1, 1, 0), "minor radius (1) must be less than major radius (1)");
    expect_bad(prim(SHAPE_TORUS, z, z, 2, 1, 0), "axis must be a finite non-zero vector");
    expect_bad(prim(42, z, z, 1, 1, 0), "unknown shape kind 42");
    double bow[] = {0, 0, 1, 1, 1, 0, 0, 1};
    expect_bad(poly_shape(2, bow, 4, 0, 1), "polygon intersects itself: edges 0-1 and 2-3 meet");
    double two[] = {0, 0, 1, 1};
    expect_bad(poly_shape(2, two, 2, 0, 1), "needs at least 3 points, found 2");
    double line[] = {0, 0, 1, 0, 2, 0};
    expect_bad(poly_shape(2, line, 3, 0, 1), "folds back on itself at point 2 (2 0)");
    double dup[] = {0, 0, 1, 0, 1, 0, 0, 1};
    expect_bad(poly_shape(2, dup, 4, 0, 1), "points 1 and 2 coincide");
    double tri[] = {0, 0, 1, 0, 0, 1};
    expect_bad(poly_shape(2, tri, 3, 1, 1), "extent along the axis must have lo < hi");
    expect_bad(poly_shape(3, tri, 3, 0, 1), "extrusion axis must be 0, 1 or 2, found 3");
    double nan[] = {0, 0, NAN, 0, 1, 1};
    expect_bad(poly_shape(2, nan, 3, 0, 1), "point 1 is not finite");
    expect_bad(poly_shape(2, tri, 3, NAN, 1), "extent along the axis must have lo < hi, found lo nan");
    double fold[] = {0, 0, 2, 0, 1, 0, 1, 1};
    expect_bad(poly_shape(2, fold, 4, 0, 1), "folds back on itself at point 1 (2 0)");
    /* A clockwise polygon is turned; the area stays. */
    double cw[] = {0, 0, 0, 1, 1, 1, 1, 0};
    Shape p = poly_shape(2, cw, 4, 0, 1);
    EXPECT(!shape_check(&p), "clockwise square rejected");
    double a = 0;
    for (int i = 0; i < 4; i++) a += p.poly[2 * i] * p.poly[2 * ((i + 1) % 4) + 1] - p.poly[2 * ((i + 1) % 4)] * p.poly[2 * i + 1];
    EXPECT(a > 0, "polygon still clockwise");
    NEAR(shape_volume(&p), 1, 0);
    shape_free(&p);
    /* Names. */
    for (int k = 0; k < SHAPE_NKINDS; k++) EXPECT(shape_kind(shape_kind_name(k)) == k, "name of kind %d", k);
    EXPECT(shape_kind("pyramid") == -1, "unknown name");
}

int main(void)
{
    make_shapes();
    RUN(random_halfspace);
    RUN(random_box);
    RUN(random_sphere);
    RUN(random_cylinder);
    RUN(random_cone);
    RUN(random_torus);
    RUN(random_polygon);
    RUN(grid_degenerate);
    RUN(box_corners_edges);
    RUN(sphere_exact);
    RUN(cylinder_cone_rims);
    RUN(torus_exact);
    RUN(polygon_vertices);
    RUN(normals_analytic);
    RUN(closest_random);
    RUN(volume_qmc);
    RUN(area_shell);
    RUN(exact_values);
    RUN(bounds);
    RUN(check_messages);
    for (int i = 0; i < NSHAPES; i++) shape_free(&shapes[i]);
    return test_summary();
}
