/*
** test_shape_sample.c: surface sampling of primitives (shape_sample) and
** of the flow domain (geometry_sample).
**
** For every kind: each point lies on the surface (|level| <= 1e-12 of the
** shape's size); points on one face carry shape_normal's exact normal,
** points on an edge or corner (found from the geometry here, not from
** the sampler) the normalised sum of the faces' normals; nearest-neighbour
** distances lie in [0.5 h, 1.5 h] for at least 95 % of the points and
** never fall below 0.7 h; the count is area / h^2 within a stated factor
** and grows by about 4 when h halves.  geometry_sample: a box minus a
** cylinder keeps only points where the domain changes across the surface
** (checked with geometry_fluid on both sides) and drops the box's face
** points inside the hole; 2-D sections give perimeter / h points.
*/
#include "test.h"
#include "fixture.h"

#include "geometry.h"
#include "mem.h"
#include "shape.h"

static const double PI_ = 3.14159265358979323846;

typedef struct Stats {
    int n, nedge, bad_level, bad_normal, bad_box;
    double frac_ok, nn_min, nn_max, density;   /* density: n h^2 / area */
} Stats;

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static void unit3(double n[3])
{
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] /= l;
}

/* Axial coordinate and radial vector of x for an axisymmetric shape. */
static void axial(const Shape *s, const double x[3], double u[3], double *H, double *z, double e[3], double *rho)
{
    for (int k = 0; k < 3; k++) u[k] = s->q[k] - s->p[k];
    *H = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++) u[k] /= *H;
    double w[3] = {x[0] - s->p[0], x[1] - s->p[1], x[2] - s->p[2]};
    *z = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
    for (int k = 0; k < 3; k++) e[k] = w[k] - *z * u[k];
    *rho = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (*rho > 0)
        for (int k = 0; k < 3; k++) e[k] /= *rho;
}

/* 1 when x lies on two or more faces of s (within tol); n gets the
   normalised sum of their normals.  Worked out from the geometry alone. */
static int edge_normal(const Shape *s, const double x[3], double tol, double n[3])
{
    int cnt = 0;
    n[0] = n[1] = n[2] = 0;
    if (s->kind == SHAPE_BOX) {
        for (int k = 0; k < 3; k++) {
            if (fabs(x[k] - s->p[k]) <= tol) n[k] -= 1, cnt++;
            if (fabs(x[k] - s->q[k]) <= tol) n[k] += 1, cnt++;
        }
    } else if ((s->kind == SHAPE_CYLINDER && !s->infinite) || s->kind == SHAPE_CONE) {
        double u[3], H, z, e[3], rho;
        axial(s, x, u, &H, &z, e, &rho);
        double r1 = s->r1, r2 = s->kind == SHAPE_CONE ? s->r2 : s->r1, k = (r2 - r1) / H, L = sqrt(1 + k * k);
        if (rho <= tol && ((r1 == 0 && fabs(z) <= tol) || (r2 == 0 && fabs(z - H) <= tol))) {
            for (int j = 0; j < 3; j++) n[j] = (r1 == 0 ? -1 : 1) * u[j];
            return 1;
        }
        if (fabs((rho - r1 - k * z) / L) <= tol) {
            for (int j = 0; j < 3; j++) n[j] += (e[j] - k * u[j]) / L;
            cnt++;
        }
        if (r1 > 0 && fabs(z) <= tol) {
            for (int j = 0; j < 3; j++) n[j] -= u[j];
            cnt++;
        }
        if (r2 > 0 && fabs(z - H) <= tol) {
            for (int j = 0; j < 3; j++) n[j] += u[j];
            cnt++;
        }
    } else if (s->kind == SHAPE_POLYGON) {
        int a = s->axis, iu = (a + 1) % 3, iv = (a + 2) % 3;
        for (int i = 0; i < s->npoly; i++) {
            const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % s->npoly);
            double eu = Q[0] - P[0], ev = Q[1] - P[1], L = sqrt(eu * eu + ev * ev);
            double t = ((x[iu] - P[0]) * eu + (x[iv] - P[1]) * ev) / (L * L);
            double d = fabs(eu * (x[iv] - P[1]) - ev * (x[iu] - P[0])) / L;
            if (d <= tol && t >= -tol && t <= 1 + tol) {
                n[iu] += ev / L, n[iv] -= eu / L;
                cnt++;
            }
        }
        if (fabs(x[a] - s->lo) <= tol) n[a] -= 1, cnt++;
        if (fabs(x[a] - s->hi) <= tol) n[a] += 1, cnt++;
    }
    if (cnt < 2) return 0;
    unit3(n);
    return 1;
}

static Stats check(const Shape *s, double h, const double *lo, const double *hi, double area)
{
    Stats st = {0};
    double *x, *n;
    st.n = shape_sample(s, h, lo, hi, &x, &n);
    double smin[3], smax[3], size = 0;
    shape_bounds(s, smin, smax);
    for (int k = 0; k < 3; k++) {
        double a = isfinite(smin[k]) ? smin[k] : lo[k], b = isfinite(smax[k]) ? smax[k] : hi[k];
        size = fmax(size, fmax(fabs(a), fabs(b)));
    }
    int ok = 0;
    st.nn_min = INFINITY;
    for (int i = 0; i < st.n; i++) {
        const double *xi = x + 3 * i, *ni = n + 3 * i;
        if (!(fabs(shape_level(s, xi)) <= 1e-12 * size)) st.bad_level++;
        double ref[3];
        if (edge_normal(s, xi, 1e-12 * size, ref)) {
            st.nedge++;
        } else {
            shape_normal(s, xi, ref);
        }
        if (!(dist3(ni, ref) <= 1e-12)) st.bad_normal++;
        if (lo)
            for (int k = 0; k < 3; k++)
                if (!(xi[k] >= lo[k] - 1e-9 && xi[k] <= hi[k] + 1e-9)) st.bad_box++;
        double nn = INFINITY;
        for (int j = 0; j < st.n; j++)
            if (j != i) nn = fmin(nn, dist3(xi, x + 3 * j));
        ok += nn >= 0.5 * h && nn <= 1.5 * h;
        st.nn_min = fmin(st.nn_min, nn);
        st.nn_max = fmax(st.nn_max, nn);
    }
    st.frac_ok = st.n ? (double)ok / st.n : 0;
    st.density = st.n * h * h / area;
    if (getenv("SAMPLE_VERBOSE"))
        printf("  %s n %d edge %d ok %.3f nn %.3f..%.3f density %.3f\n", shape_kind_name(s->kind), st.n, st.nedge,
               st.frac_ok, st.nn_min / h, st.nn_max / h, st.density);
    free(x);
    free(n);
    return st;
}

/* The common expectations; dlo..dhi bounds the density. */
static void expect_good(const char *what, Stats st, double h, double dlo, double dhi)
{
    EXPECT(st.n > 0, "%s: no points", what);
    EXPECT(st.bad_level == 0, "%s: %d of %d points off the surface", what, st.bad_level, st.n);
    EXPECT(st.bad_normal == 0, "%s: %d of %d normals differ from the exact ones", what, st.bad_normal, st.n);
    EXPECT(st.bad_box == 0, "%s: %d points outside the box", what, st.bad_box);
    EXPECT(st.frac_ok >= 0.95, "%s: only %.3f of the nearest-neighbour distances in [0.5h, 1.5h]", what, st.frac_ok);
    EXPECT(st.nn_min >= 0.7 * h, "%s: two points %.3g h apart", what, st.nn_min / h);
    EXPECT(st.density >= dlo && st.density <= dhi, "%s: n h^2 / area = %.3f, expected %.2f..%.2f", what, st.density,
           dlo, dhi);
}

/* count(h) / count(2h) in 3-D: about 4. */
static void expect_scaling(const char *what, const Shape *s, double h, const double *lo, const double *hi)
{
    double *x, *n;
    int n1 = shape_sample(s, 2 * h, lo, hi, &x, &n);
    free(x), free(n);
    int n2 = shape_sample(s, h, lo, hi, &x, &n);
    free(x), free(n);
    double r = (double)n2 / n1;
    EXPECT(r > 3.4 && r < 4.6, "%s: %d points at h, %d at 2h: ratio %.3f, expected about 4", what, n2, n1, r);
}

static Shape make(int kind)
{
    Shape s;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    return s;
}

TEST(sample_sphere)
{
    Shape s = make(SHAPE_SPHERE);
    double c[3] = {0.3, -0.2, 0.1};
    memcpy(s.p, c, sizeof c);
    s.r1 = 0.8;
    EXPECT(!shape_check(&s), "check");
    double h = 0.1;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    expect_good("sphere", st, h, 0.95, 1.15);
    EXPECT(st.nedge == 0, "sphere: %d edge points", st.nedge);
    expect_scaling("sphere", &s, 0.05, NULL, NULL);
}

TEST(sample_box)
{
    Shape s = make(SHAPE_BOX);
    double p[3] = {-0.5, 0, 0.2}, q[3] = {0.5, 0.65, 0.5};
    memcpy(s.p, p, sizeof p), memcpy(s.q, q, sizeof q);
    EXPECT(!shape_check(&s), "check");
    double h = 0.1;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    /* the faces' nodes are the edges and the midpoints of 10, 7, 3
       intervals between them (shape.c samp_box): an edge and the first
       midpoint are half an interval apart, the nearest pair 0.65 / 14 */
    Stats rest = st;
    rest.frac_ok = 1, rest.nn_min = h;
    expect_good("box", rest, h, 1.0, 1.5);   /* the extra rows at the edges */
    NEAR(st.nn_min, 0.65 / 14, 1e-12);
    /* 4 (10 + 7 + 3) edge-interior points and 8 corners */
    EXPECT(st.nedge == 4 * (10 + 7 + 3) + 8, "box: %d edge points, expected %d", st.nedge, 4 * 20 + 8);
    /* every node of the (12 9 5) lattice on the surface */
    EXPECT(st.n == 12 * 9 * 5 - 10 * 7 * 3, "box: %d points, expected %d", st.n, 12 * 9 * 5 - 10 * 7 * 3);
    expect_scaling("box", &s, 0.01, NULL, NULL);   /* fine: the edge rows are O(1/h) */
}

TEST(sample_cylinder)
{
    Shape s = make(SHAPE_CYLINDER);
    double p[3] = {0.1, 0.2, 0.3}, q[3] = {0.9, 0.5, -0.4};
    memcpy(s.p, p, sizeof p), memcpy(s.q, q, sizeof q);
    s.r1 = 0.35;
    EXPECT(!shape_check(&s), "check");
    double h = 0.06;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    /* the mantle's rings sit at the midpoints of ns intervals between the
       rims, so the rim and the first ring are only half an interval
       (~h/2) apart (shape.c samp_cylinder_rings): the spacing
       expectations of expect_good hold for the rest */
    int ns = (int)ceil(sqrt(0.8 * 0.8 + 0.3 * 0.3 + 0.7 * 0.7) / h - 1e-9);
    double half = 0.5 * sqrt(0.8 * 0.8 + 0.3 * 0.3 + 0.7 * 0.7) / ns;
    Stats rest = st;
    rest.frac_ok = 1, rest.nn_min = h;
    expect_good("cylinder", rest, h, 0.95, 1.15);
    NEAR(st.nn_min, half, 1e-9);
    EXPECT(st.frac_ok >= 0.8, "cylinder: only %.3f of the nearest-neighbour distances in [0.5h, 1.5h]", st.frac_ok);
    int m = (int)floor(2 * PI_ * 0.35 / h + 0.5);
    EXPECT(st.nedge == 2 * m, "cylinder: %d rim points, expected %d", st.nedge, 2 * m);
    expect_scaling("cylinder", &s, 0.04, NULL, NULL);
}

TEST(sample_cones)
{
    Shape s = make(SHAPE_CONE);
    double p[3] = {0, 0, 0}, q[3] = {0.2, 0.1, 1.0};
    memcpy(s.p, p, sizeof p), memcpy(s.q, q, sizeof q);
    s.r1 = 0.5, s.r2 = 0.2;
    EXPECT(!shape_check(&s), "check");
    double h = 0.06;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    expect_good("truncated cone", st, h, 0.95, 1.15);
    int m1 = (int)floor(2 * PI_ * 0.5 / h + 0.5), m2 = (int)floor(2 * PI_ * 0.2 / h + 0.5);
    EXPECT(st.nedge == m1 + m2, "truncated cone: %d rim points, expected %d", st.nedge, m1 + m2);
    s.r1 = 0;   /* full cone: apex at p */
    st = check(&s, h, NULL, NULL, shape_area(&s));
    expect_good("cone", st, h, 0.95, 1.15);
    EXPECT(st.nedge == m2 + 1, "cone: %d rim and apex points, expected %d", st.nedge, m2 + 1);
    expect_scaling("cone", &s, 0.04, NULL, NULL);
}

TEST(sample_torus)
{
    Shape s = make(SHAPE_TORUS);
    double c[3] = {0.1, 0.2, 0.3}, ax[3] = {1, 1, 0};
    memcpy(s.p, c, sizeof c), memcpy(s.q, ax, sizeof ax);
    s.r1 = 0.6, s.r2 = 0.2;
    EXPECT(!shape_check(&s), "check");
    double h = 0.05;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    expect_good("torus", st, h, 0.95, 1.1);
    EXPECT(st.nedge == 0, "torus: %d edge points", st.nedge);
    expect_scaling("torus", &s, 0.04, NULL, NULL);
}

/* An L-shaped prism with a reflex vertex, given clockwise. */
TEST(sample_polygon)
{
    static const double L[] = {-0.6, -0.5, -0.6, 0.6, -0.1, 0.6, -0.1, 0.1, 0.5, 0.1, 0.5, -0.5};
    Shape s = make(SHAPE_POLYGON);
    s.axis = 1, s.npoly = 6, s.lo = -0.3, s.hi = 0.4;
    s.poly = mem_alloc(sizeof L);
    memcpy(s.poly, L, sizeof L);
    EXPECT(!shape_check(&s), "check");
    double h = 0.05;
    Stats st = check(&s, h, NULL, NULL, shape_area(&s));
    /* edges and vertex lines, then midpoints (shape.c samp_polygon): an
       edge and the first midpoint are half a spacing apart */
    Stats rest = st;
    rest.frac_ok = 1, rest.nn_min = h;
    expect_good("polygon", rest, h, 0.95, 1.3);
    NEAR(st.nn_min, 0.5 * h, 1e-12);
    /* perimeter 4.4 in 88 steps of 0.05: 6 vertices and 88 midpoints on
       each cap's rim, 6 vertex lines of the 14 midpoints between the
       caps */
    EXPECT(st.nedge == 2 * 94 + 6 * 14, "polygon: %d edge points, expected %d", st.nedge, 2 * 94 + 6 * 14);
    expect_scaling("polygon", &s, 0.04, NULL, NULL);
    /* unbounded along y: walls only, inside the box */
    double lo[3] = {-1, -0.25, -1}, hi[3] = {1, 0.25, 1};
    s.lo = -INFINITY, s.hi = INFINITY;
    st = check(&s, h, lo, hi, 4.4 * 0.5);
    rest = st;
    rest.frac_ok = 1, rest.nn_min = h;
    expect_good("unbounded polygon", rest, h, 0.95, 1.3);
    NEAR(st.nn_min, 0.5 * h, 1e-12);
    /* midpoint-shifted along y (half a spacing from the box sides): 10 */
    EXPECT(st.nedge == 6 * 10, "unbounded polygon: %d vertex-line points, expected 6 x 10", st.nedge);
    double *x, *n;
    EXPECT(shape_sample(&s, h, NULL, NULL, &x, &n) == 0, "unbounded polygon without a box gives points");
    free(x), free(n);
    shape_free(&s);
}

TEST(sample_unbounded)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0.8, 0.6};
    Shape s = make(SHAPE_HALFSPACE);
    double p[3] = {0.5, 0.4, 0.3}, nz[3] = {0, 0, 1};
    memcpy(s.p, p, sizeof p), memcpy(s.q, nz, sizeof nz);
    EXPECT(!shape_check(&s), "check");
    double h = 0.05;
    Stats st = check(&s, h, lo, hi, 0.8);
    expect_good("axis-aligned half-space", st, h, 1.0, 1.15);
    /* the midpoints of 20 x 16 intervals (half a spacing from the box) */
    EXPECT(st.n == 20 * 16, "axis-aligned half-space: %d points, expected 20 x 16", st.n);
    double tilt[3] = {0.3, -0.5, 1};
    memcpy(s.q, tilt, sizeof tilt);
    EXPECT(!shape_check(&s), "check");
    /* the plane's section of the box, area by the projection onto z: the
       plane spans the whole box in x and y here */
    double t = sqrt(0.09 + 0.25 + 1);
    st = check(&s, h, lo, hi, 0.8 * t);
    expect_good("tilted half-space", st, h, 0.9, 1.1);
    Shape c = make(SHAPE_CYLINDER);
    double c1[3] = {0.5, 0.4, 0}, c2[3] = {0.6, 0.4, 1};
    memcpy(c.p, c1, sizeof c1), memcpy(c.q, c2, sizeof c2);
    c.r1 = 0.2, c.infinite = 1;
    EXPECT(!shape_check(&c), "check");
    double len = 0.6 * sqrt(1 + 0.01);   /* axis length inside 0 <= z <= 0.6 */
    st = check(&c, h, lo, hi, 2 * PI_ * 0.2 * len);
    expect_good("infinite cylinder", st, h, 0.9, 1.1);
    double *x, *n;
    EXPECT(shape_sample(&c, h, NULL, NULL, &x, &n) == 0, "infinite cylinder without a box gives points");
    free(x), free(n);
}

/* ---- geometry_sample ---- */


/* Every point: fluid just behind it, solid just ahead along n. */
static int count_off_boundary(const Geometry *g, const double *x, const double *n, int np, double d)
{
    int bad = 0;
    for (int i = 0; i < np; i++) {
        double a[3], b[3];
        for (int k = 0; k < 3; k++) a[k] = x[3 * i + k] - d * n[3 * i + k], b[k] = x[3 * i + k] + d * n[3 * i + k];
        bad += !geometry_fluid(g, a) || geometry_fluid(g, b);
    }
    return bad;
}

static const char *part_text =
    "surfaces { part { flow inside; shape difference;\n"
    "  body { shape box; min (0.1 0.1 0.1); max (0.9 0.7 0.5); }\n"
    "  hole { shape cylinder; point1 (0.4 0.4 0); point2 (0.4 0.4 0.6); radius 0.15; }\n"
    "} }\n";

TEST(geometry_sample_csg)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, part_text, &e) == 0, "%s", e.msg);
    double h = 0.05, *x, *n;
    int *leaf;
    int np = geometry_sample(&g, h, &x, &n, &leaf);
    EXPECT(np > 0, "no points");
    EXPECT(count_off_boundary(&g, x, n, np, 1e-6) == 0, "points off the boundary or normals into the flow");
    int nhole = 0, nmid = 0, inhole = 0;
    for (int i = 0; i < np; i++) {
        const double *p = x + 3 * i, *v = n + 3 * i;
        double r = hypot(p[0] - 0.4, p[1] - 0.4);
        if (leaf[i] == 1) {
            nhole++;
            nmid += p[2] > 0.1 + 1e-9 && p[2] < 0.5 - 1e-9;
            /* flow inside the part, outside the hole: normal towards the axis */
            NEAR(v[0], -(p[0] - 0.4) / 0.15, 1e-12);
            NEAR(v[1], -(p[1] - 0.4) / 0.15, 1e-12);
            EXPECT(p[2] >= 0.1 - 1e-12 && p[2] <= 0.5 + 1e-12, "hole point at z = %g outside the box", p[2]);
        } else {
            inhole += r < 0.15 - 1e-9;
        }
    }
    EXPECT(inhole == 0, "%d box points inside the hole kept", inhole);
    /* the hole's side: rims at z = 0 and 0.6 and 12 rings at the
       midpoints z = 0.025, 0.075, ..., of round(2 pi 0.15 / h) = 19
       points; the 8 between the box's faces (0.125 .. 0.475) are kept */
    EXPECT(nmid == 8 * 19 && nhole == 8 * 19, "%d hole points, %d inside the box, expected %d", nhole, nmid, 8 * 19);
    free(x), free(n), free(leaf);
    geometry_free(&g);
}

TEST(geometry_sample_2d)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { ball { shape sphere; centre (0.5 0.5 0.2); radius 0.3; } }", &e) == 0, "%s", e.msg);
    geometry_flatten(&g, 2, 0.2);
    double h = 0.02, *x, *n;
    int *leaf;
    int np = geometry_sample(&g, h, &x, &n, &leaf);
    int m = (int)floor(2 * PI_ * 0.3 / h + 0.5);
    EXPECT(np == m, "disc: %d points, expected %d", np, m);
    for (int i = 0; i < np; i++) {
        NEAR(x[3 * i + 2], 0.2, 0);
        NEAR(hypot(x[3 * i] - 0.5, x[3 * i + 1] - 0.5), 0.3, 1e-15);
        NEAR(n[3 * i], -(x[3 * i] - 0.5) / 0.3, 1e-12);   /* flow outside: into the ball */
        NEAR(n[3 * i + 2], 0, 0);
    }
    free(x), free(n), free(leaf);
    geometry_free(&g);
    /* a torus has no closed-form section here: grid-line marching */
    EXPECT(fixture_geometry(&g, "surfaces { ring { flow inside; shape torus; centre (0.5 0.5 0); axis (1 0 0); "
                     "majorRadius 0.3; minorRadius 0.1; } }", &e) == 0, "%s", e.msg);
    geometry_flatten(&g, 2, 0);
    np = geometry_sample(&g, h, &x, &n, &leaf);
    /* the section: two circles of radius 0.1 at y = 0.2 and 0.8 */
    int bad = 0;
    for (int i = 0; i < np; i++) {
        double r = hypot(x[3 * i] - 0.5, fabs(x[3 * i + 1] - 0.5) - 0.3);
        bad += !(fabs(r - 0.1) < 1e-12) || n[3 * i + 2] != 0;
    }
    EXPECT(bad == 0, "torus section: %d points off the circles", bad);
    double per = 2 * 2 * PI_ * 0.1 / h;
    EXPECT(np >= 0.7 * per && np <= 1.1 * per, "torus section: %d points, perimeter / h = %.1f", np, per);
    EXPECT(count_off_boundary(&g, x, n, np, 1e-6) == 0, "torus section: points off the boundary");
    free(x), free(n), free(leaf);
    geometry_free(&g);
}

/* A rectangle section through a box turned about the flat axis: exact
   points and normals, its corners with the mean normal. */
TEST(geometry_sample_2d_rectangle)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { slab { flow inside; shape box; min (0.2 0.2 -1); max (0.6 0.5 1);"
                     " rotate { axis (0 0 1); angle 30; origin (0.4 0.35 0); } } }", &e) == 0, "%s", e.msg);
    geometry_flatten(&g, 2, 0.25);
    double h = 0.05, *x, *n;
    int *leaf;
    int np = geometry_sample(&g, h, &x, &n, &leaf);
    /* sides 0.4 and 0.3: 4 corners and 8 + 6 + 8 + 6 midpoints */
    EXPECT(np == 32, "rectangle: %d points, expected 32", np);
    double c = cos(PI_ / 6), s = sin(PI_ / 6);
    int corners = 0, bad = 0;
    for (int i = 0; i < np; i++) {
        /* back to the box's own frame */
        double dx = x[3 * i] - 0.4, dy = x[3 * i + 1] - 0.35;
        double u = c * dx + s * dy + 0.4, v = -s * dx + c * dy + 0.35;
        double nu = c * n[3 * i] + s * n[3 * i + 1], nv = -s * n[3 * i] + c * n[3 * i + 1];
        double eu = fabs(u - 0.2) < 1e-12 ? -1 : fabs(u - 0.6) < 1e-12 ? 1 : 0;
        double ev = fabs(v - 0.2) < 1e-12 ? -1 : fabs(v - 0.5) < 1e-12 ? 1 : 0;
        double l = hypot(eu, ev);
        corners += eu != 0 && ev != 0;
        bad += l == 0 || fabs(nu - eu / l) > 1e-12 || fabs(nv - ev / l) > 1e-12 || x[3 * i + 2] != 0.25;
    }
    EXPECT(bad == 0 && corners == 4, "rectangle: %d points off the sides or with wrong normals, %d corners", bad,
           corners);
    EXPECT(count_off_boundary(&g, x, n, np, 1e-6) == 0, "rectangle: points off the boundary");
    free(x), free(n), free(leaf);
    geometry_free(&g);
}

int main(void)
{
    RUN(sample_sphere);
    RUN(sample_box);
    RUN(sample_cylinder);
    RUN(sample_cones);
    RUN(sample_torus);
    RUN(sample_polygon);
    RUN(sample_unbounded);
    RUN(geometry_sample_csg);
    RUN(geometry_sample_2d);
    RUN(geometry_sample_2d_rectangle);
    return test_summary();
}
