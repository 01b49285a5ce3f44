/*
** test_trisurf.c: welding, topology, orientation, volumes, and the robust
** inside / line / crossing queries of trisurf.c on surfaces built here: a
** unit cube (12 triangles), an icosphere (5120 triangles, poles on the x
** axis) and a torus (4096 triangles).
**
** The cube is the exact reference for grazing queries: every query point
** is moved by the same infinitesimal delta = (e_x, e_y, e_z), e_x >> e_y >>
** e_z > 0 (trisurf.h), so the cube [0,1]^3 is classified exactly as the
** half-open box [0,1)^3, on every axis, for lines through its vertices,
** edges and faces.
*/
#include "test.h"

#include <stdint.h>
#include <time.h>

#include "mem.h"
#include "trisurf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---------------------------------------------------------------- shapes */

/* The 12 outward triangles of the box lo..hi. */
static void box_soup(double *xyz, const double lo[3], const double hi[3])
{
    int n = 0;
    for (int a = 0; a < 3; a++)
        for (int sd = 0; sd < 2; sd++) {
            int u = (a + 1) % 3, v = (a + 2) % 3;
            double q[4][3];
            static const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int c = 0; c < 4; c++) {
                int k = sd ? c : 3 - c;   /* reversed on the low side: outward */
                q[c][a] = sd ? hi[a] : lo[a];
                q[c][u] = uv[k][0] ? hi[u] : lo[u];
                q[c][v] = uv[k][1] ? hi[v] : lo[v];
            }
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int t = 0; t < 2; t++, n++)
                for (int m = 0; m < 3; m++) memcpy(xyz + 9 * n + 3 * m, q[tri[t][m]], 3 * sizeof(double));
        }
}

static void unit_cube(TriSurf *s)
{
    double xyz[108], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    trisurf_from_soup(s, xyz, 12, NULL);
}

static void unit(double *p)
{
    double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int i = 0; i < 3; i++) p[i] /= l;
}

/* Icosahedron with poles (+-1, 0, 0), each face split `levels` times into
   four with the midpoints pushed onto the unit sphere.  Midpoints are
   computed from the two ends only, so shared ones are bit-identical. */
static double *icosphere_soup(int levels, int *ntris)
{
    double v[12][3];
    v[0][0] = 1, v[0][1] = 0, v[0][2] = 0;
    v[11][0] = -1, v[11][1] = 0, v[11][2] = 0;
    for (int k = 0; k < 5; k++) {
        double a = 2 * M_PI * k / 5, b = a + M_PI / 5, h = 1 / sqrt(5.0), r = 2 / sqrt(5.0);
        v[1 + k][0] = h, v[1 + k][1] = r * cos(a), v[1 + k][2] = r * sin(a);
        v[6 + k][0] = -h, v[6 + k][1] = r * cos(b), v[6 + k][2] = r * sin(b);
    }
    v[1][2] = 0;   /* sin(0) is 0 anyway; keeps ring points on z = 0 */
    int n = 20;
    double *xyz = mem_alloc(9 * sizeof(double) * 20);
    int t = 0;
    for (int k = 0; k < 5; k++) {
        int k1 = (k + 1) % 5;
        int f[4][3] = {{0, 1 + k, 1 + k1}, {1 + k, 6 + k, 1 + k1}, {1 + k1, 6 + k, 6 + k1}, {11, 6 + k1, 6 + k}};
        for (int q = 0; q < 4; q++, t++) {
            double *o = xyz + 9 * t;
            for (int m = 0; m < 3; m++) memcpy(o + 3 * m, v[f[q][m]], 3 * sizeof(double));
            /* orient outward: the normal points away from the centre */
            double e1[3], e2[3], nn[3];
            for (int i = 0; i < 3; i++) e1[i] = o[3 + i] - o[i], e2[i] = o[6 + i] - o[i];
            nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
            nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
            nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
            if (nn[0] * o[0] + nn[1] * o[1] + nn[2] * o[2] < 0)
                for (int i = 0; i < 3; i++) {
                    double x = o[3 + i];
                    o[3 + i] = o[6 + i];
                    o[6 + i] = x;
                }
        }
    }
    for (int l = 0; l < levels; l++) {
        double *nx = mem_alloc(9 * sizeof(double) * 4 * (size_t)n);
        for (int i = 0; i < n; i++) {
            const double *a = xyz + 9 * i, *b = a + 3, *c = a + 6;
            double ab[3], bc[3], ca[3];
            for (int q = 0; q < 3; q++) {
                ab[q] = (a[q] + b[q]) * 0.5;
                bc[q] = (b[q] + c[q]) * 0.5;
                ca[q] = (c[q] + a[q]) * 0.5;
            }
            unit(ab), unit(bc), unit(ca);
            const double *tri[4][3] = {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}};
            for (int q = 0; q < 4; q++)
                for (int m = 0; m < 3; m++) memcpy(nx + 9 * (4 * i + q) + 3 * m, tri[q][m], 3 * sizeof(double));
        }
        free(xyz);
        xyz = nx;
        n *= 4;
    }
    *ntris = n;
    return xyz;
}

/* Distance from the centre to the nearest face plane (the insphere of the
   polyhedron): points closer than this are certainly inside. */
static double inradius(const TriSurf *s)
{
    double r = INFINITY;
    for (int t = 0; t < s->ntris; t++) {
        double n[3];
        trisurf_normal(s, t, n);
        const double *p = s->points + 3 * s->tris[3 * t];
        r = fmin(r, fabs(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]));
    }
    return r;
}

#define TR_R 1.0
#define TR_A 0.4
#define TR_NU 64
#define TR_NV 32

/* Torus about the z axis, major radius TR_R, minor TR_A, TR_NU x TR_NV
   quads split into two triangles each, oriented outward. */
static void torus(TriSurf *s)
{
    int n = 2 * TR_NU * TR_NV, t = 0;
    double *xyz = mem_alloc(9 * sizeof(double) * (size_t)n);
    for (int i = 0; i < TR_NU; i++)
        for (int j = 0; j < TR_NV; j++) {
            double P[4][3];
            for (int c = 0; c < 4; c++) {
                int ii = (i + (c == 1 || c == 2)) % TR_NU, jj = (j + (c >= 2)) % TR_NV;
                double a = 2 * M_PI * ii / TR_NU, b = 2 * M_PI * jj / TR_NV;
                P[c][0] = (TR_R + TR_A * cos(b)) * cos(a);
                P[c][1] = (TR_R + TR_A * cos(b)) * sin(a);
                P[c][2] = TR_A * sin(b);
            }
            /* (u along a, v along b): the normal u x v points outward */
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int q = 0; q < 2; q++, t++)
                for (int m = 0; m < 3; m++) memcpy(xyz + 9 * t + 3 * m, P[tri[q][m]], 3 * sizeof(double));
        }
    trisurf_from_soup(s, xyz, n, NULL);
    free(xyz);
}

/* Deterministic uniform numbers in [0, 1). */
static double rnd(uint64_t *st)
{
    *st = *st * 6364136223846793005u + 1442695040888963407u;
    return (double)(*st >> 11) / 9007199254740992.0;
}

static int cube_exact(const double x[3])
{
    return x[0] >= 0 && x[0] < 1 && x[1] >= 0 && x[1] < 1 && x[2] >= 0 && x[2] < 1;
}

static void prepared(TriSurf *s)
{
    Err e = {0};
    if (trisurf_prepare(s, &e)) {
        printf("prepare failed: %s\n", e.msg);
        exit(1);
    }
}

/* ---------------------------------------------------------------- topology */

TEST(cube_topology)
{
    TriSurf s;
    unit_cube(&s);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(s.npoints == 8, "npoints %d", s.npoints);
    EXPECT(t.nedges == 18 && t.nopen == 0 && t.nnonmanifold == 0 && t.nflipped == 0 && t.ndegenerate == 0,
           "edges %d open %d nonmanifold %d flipped %d degenerate %d", t.nedges, t.nopen, t.nnonmanifold,
           t.nflipped, t.ndegenerate);
    NEAR(t.volume, 1.0, 0);
    NEAR(t.area, 6.0, 0);
    trisurf_free(&s);
}

TEST(weld_signed_zero)
{
    /* -0 and +0 are one position: a cube written with -0 corners welds */
    double xyz[108], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    for (int i = 0; i < 108; i += 7)
        if (xyz[i] == 0) xyz[i] = -0.0;
    TriSurf s;
    trisurf_from_soup(&s, xyz, 12, NULL);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(s.npoints == 8 && t.nopen == 0, "npoints %d open %d", s.npoints, t.nopen);
    trisurf_free(&s);
}

TEST(open_cube)
{
    double xyz[108], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    TriSurf s;
    trisurf_from_soup(&s, xyz + 9, 11, NULL);   /* first triangle (face x = 0) removed */
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 3 && t.nnonmanifold == 0 && t.nflipped == 0, "open %d nonmanifold %d flipped %d",
           t.nopen, t.nnonmanifold, t.nflipped);
    EXPECT(t.nedges == 18, "edges %d", t.nedges);
    NEAR(t.open_at[0], 0.0, 0);   /* an edge of the removed triangle on x = 0 */
    EXPECT((t.open_at[1] == 0.5 || t.open_at[1] == 0 || t.open_at[1] == 1) &&
               (t.open_at[2] == 0.5 || t.open_at[2] == 0 || t.open_at[2] == 1),
           "open_at (%g %g %g)", t.open_at[0], t.open_at[1], t.open_at[2]);
    trisurf_free(&s);
}

TEST(duplicated_triangle)
{
    double xyz[117], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    memcpy(xyz + 108, xyz + 45, 9 * sizeof(double));
    TriSurf s;
    trisurf_from_soup(&s, xyz, 13, NULL);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nnonmanifold == 3 && t.nopen == 0, "nonmanifold %d open %d", t.nnonmanifold, t.nopen);
    const double *c = xyz + 45;
    int on = 0;   /* nonmanifold_at is the midpoint of an edge of that triangle */
    for (int m = 0; m < 3; m++) {
        const double *a = c + 3 * m, *b = c + 3 * ((m + 1) % 3);
        on |= (a[0] + b[0]) / 2 == t.nonmanifold_at[0] && (a[1] + b[1]) / 2 == t.nonmanifold_at[1] &&
              (a[2] + b[2]) / 2 == t.nonmanifold_at[2];
    }
    EXPECT(on, "nonmanifold_at (%g %g %g)", t.nonmanifold_at[0], t.nonmanifold_at[1], t.nonmanifold_at[2]);
    trisurf_free(&s);
}

TEST(flipped_triangle_and_repair)
{
    double xyz[108], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    double tmp[3];
    memcpy(tmp, xyz + 9 * 4 + 3, sizeof tmp);   /* reverse triangle 4 */
    memcpy(xyz + 9 * 4 + 3, xyz + 9 * 4 + 6, sizeof tmp);
    memcpy(xyz + 9 * 4 + 6, tmp, sizeof tmp);
    TriSurf s;
    trisurf_from_soup(&s, xyz, 12, NULL);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nflipped == 3 && t.nopen == 0 && t.nnonmanifold == 0, "flipped %d", t.nflipped);
    int f = trisurf_orient(&s);
    trisurf_check(&s, &t);
    EXPECT(f == 1, "orient flipped %d triangles, expected 1", f);
    EXPECT(t.nflipped == 0, "after orient: flipped %d", t.nflipped);
    NEAR(t.volume, 1.0, 0);
    trisurf_free(&s);
}

TEST(orient_inverted_and_cavity)
{
    /* an inside-out cube: all 12 turn */
    double xyz[216], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    for (int i = 0; i < 12; i++)
        for (int q = 0; q < 3; q++) {
            double x = xyz[9 * i + 3 + q];
            xyz[9 * i + 3 + q] = xyz[9 * i + 6 + q];
            xyz[9 * i + 6 + q] = x;
        }
    TriSurf s;
    trisurf_from_soup(&s, xyz, 12, NULL);
    int f = trisurf_orient(&s);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(f == 12, "flipped %d of 12", f);
    NEAR(t.volume, 1.0, 0);
    trisurf_free(&s);
    /* a hollow cube: both shells given outward on their own; the inner
       one bounds a cavity and must turn inward */
    box_soup(xyz, lo, hi);
    double lo2[3] = {0.25, 0.25, 0.25}, hi2[3] = {0.75, 0.75, 0.75};
    box_soup(xyz + 108, lo2, hi2);
    trisurf_from_soup(&s, xyz, 24, NULL);
    f = trisurf_orient(&s);
    trisurf_check(&s, &t);
    EXPECT(f == 12, "hollow cube: flipped %d, expected 12", f);
    NEAR(t.volume, 1.0 - 0.125, 1e-15);
    EXPECT(t.nflipped == 0 && t.nopen == 0, "flipped %d open %d", t.nflipped, t.nopen);
    prepared(&s);
    double in[3] = {0.1, 0.5, 0.5}, cav[3] = {0.5, 0.5, 0.5};
    EXPECT(trisurf_inside(&s, in) == 1 && trisurf_inside(&s, cav) == 0, "hollow inside %d cavity %d",
           trisurf_inside(&s, in), trisurf_inside(&s, cav));
    trisurf_free(&s);
}

/* ---------------------------------------------------------------- shells */

/* A file of several closed shells: each given as a box lo..hi, outward
   (+1) or inward (-1). */
typedef struct Shell {
    double lo[3], hi[3];
    int dir;
} Shell;

static void reverse_tris(double *xyz, int n)
{
    for (int i = 0; i < n; i++)
        for (int q = 0; q < 3; q++) {
            double x = xyz[9 * i + 3 + q];
            xyz[9 * i + 3 + q] = xyz[9 * i + 6 + q];
            xyz[9 * i + 6 + q] = x;
        }
}

static void shells(TriSurf *s, const Shell *sh, int n)
{
    double *xyz = mem_alloc(108 * sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++) {
        box_soup(xyz + 108 * i, sh[i].lo, sh[i].hi);
        if (sh[i].dir < 0) reverse_tris(xyz + 108 * i, 12);
    }
    trisurf_from_soup(s, xyz, 12 * n, NULL);
    free(xyz);
}

/* Solid volume from the crossing lists of N x N lines along `axis`
   through the cell centres of the unit square of the other two axes,
   from -0.5 to 1.5: each crossing toggles the state, which starts as
   trisurf_inside at the start and must end as trisurf_inside at the end
   (*bad counts lines where it does not, or where a crossing does not
   alternate entering and leaving by its triangle's normal). */
static double volume_by_crossings(const TriSurf *s, int axis, int N, int *bad)
{
    double V = 0, h = 1.0 / N;
    *bad = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double a[3], b[3], t[64];
            int tri[64];
            a[axis] = -0.5;
            b[axis] = 1.5;
            a[(axis + 1) % 3] = b[(axis + 1) % 3] = (i + 0.5) * h;
            a[(axis + 2) % 3] = b[(axis + 2) % 3] = (j + 0.5) * h;
            int k = trisurf_crossings(s, a, b, t, tri, 64), in = trisurf_inside(s, a);
            double len = 0, t0 = 0;
            for (int q = 0; q < k && q < 64; q++) {
                double n[3];
                trisurf_normal(s, tri[q], n);
                if ((n[axis] < 0) != !in) ++*bad;   /* entering through an inward face */
                if (in) len += t[q] - t0;
                in = !in;
                t0 = t[q];
            }
            if (in) len += 1 - t0;
            if (k > 64 || in != trisurf_inside(s, b)) ++*bad;
            V += 2 * len * h * h;
        }
    return V;
}

/* Solid volume counted on the N^3 cell centres of the unit cube with
   trisurf_classify_line along `axis`. */
static double volume_by_lines(const TriSurf *s, int axis, int N)
{
    double h = 1.0 / N, *c = mem_alloc((size_t)N * sizeof *c);
    char *in = mem_alloc((size_t)N);
    for (int i = 0; i < N; i++) c[i] = (i + 0.5) * h;
    long count = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double p[3];
            p[axis] = 0;
            p[(axis + 1) % 3] = c[i];
            p[(axis + 2) % 3] = c[j];
            trisurf_classify_line(s, axis, p, c, N, in);
            for (int q = 0; q < N; q++) count += in[q];
        }
    free(c);
    free(in);
    return (double)count * h * h * h;
}

static int in_box(const Shell *b, const double x[3])
{
    return x[0] > b->lo[0] && x[0] < b->hi[0] && x[1] > b->lo[1] && x[1] < b->hi[1] && x[2] > b->lo[2] &&
           x[2] < b->hi[2];
}

/* Random oblique segments: the state between consecutive crossings (and
   at the ends, by trisurf_inside) is `solid` at the midpoint; returns the
   number of segments where it is not. */
static int oblique_states(const TriSurf *s, int (*solid)(const double *), uint64_t seed)
{
    int bad = 0;
    for (int i = 0; i < 3000; i++) {
        double a[3], b[3], t[66];
        for (int q = 0; q < 3; q++) a[q] = -0.2 + 1.4 * rnd(&seed), b[q] = -0.2 + 1.4 * rnd(&seed);
        int k = trisurf_crossings(s, a, b, t + 1, NULL, 64), in = trisurf_inside(s, a), wrong = 0;
        if (k > 64) k = 64, wrong = 1;
        t[0] = 0;
        t[k + 1] = 1;
        wrong |= in != solid(a) || (in ^ (k % 2)) != trisurf_inside(s, b);
        for (int q = 0; q <= k; q++, in = !in) {
            double x[3];
            for (int c = 0; c < 3; c++) x[c] = a[c] + 0.5 * (t[q] + t[q + 1]) * (b[c] - a[c]);
            if (t[q + 1] - t[q] > 1e-9 && in != solid(x)) wrong = 1;
        }
        bad += wrong;
    }
    return bad;
}

static const Shell overlap_a = {{0.21, 0.21, 0.21}, {0.61, 0.61, 0.61}, 1};
static const Shell overlap_b = {{0.31, 0.31, 0.31}, {0.71, 0.71, 0.71}, 1};

static int overlap_union(const double *x) { return in_box(&overlap_a, x) || in_box(&overlap_b, x); }

/* Checks the solid volume V by crossings and by line classification on
   all three axes (exact to round-off: every face lies on a cell face of
   the 100^3 sampling grid). */
static void expect_volume(const TriSurf *s, double V, const char *what)
{
    for (int axis = 0; axis < 3; axis++) {
        int bad;
        double vc = volume_by_crossings(s, axis, 100, &bad), vl = volume_by_lines(s, axis, 100);
        EXPECT(bad == 0 && fabs(vc - V) < 1e-13 && fabs(vl - V) < 1e-12,
               "%s, axis %d: volume %.15g by crossings (%d bad lines), %.15g by lines, exact %.15g", what, axis,
               vc, bad, vl, V);
    }
}

/* Two overlapping outward cubes in one file: the solid is their union,
   0.4^3 + 0.4^3 - 0.3^3 = 0.101 (was their XOR, 0.074: the second cube's
   probe point lay in the first and it was turned into a cavity). */
TEST(overlapping_shells_union)
{
    Shell sh[2] = {overlap_a, overlap_b};
    TriSurf s;
    shells(&s, sh, 2);
    int f = trisurf_orient(&s);
    EXPECT(f == 0, "flipped %d triangles of two outward overlapping cubes", f);
    prepared(&s);
    expect_volume(&s, 0.101, "overlapping cubes");
    int bad = oblique_states(&s, overlap_union, 21);
    EXPECT(bad == 0, "%d of 3000 oblique segments with wrong states", bad);
    trisurf_free(&s);
    /* the same with one triangle of the second cube reversed: the
       orientation is repaired, by containment of whole shells */
    double xyz[216];
    box_soup(xyz, overlap_a.lo, overlap_a.hi);
    box_soup(xyz + 108, overlap_b.lo, overlap_b.hi);
    reverse_tris(xyz + 108 + 9 * 5, 1);
    trisurf_from_soup(&s, xyz, 24, NULL);
    f = trisurf_orient(&s);
    EXPECT(f == 1, "repair: flipped %d triangles, expected 1", f);
    prepared(&s);
    expect_volume(&s, 0.101, "overlapping cubes, repaired");
    trisurf_free(&s);
}

static const Shell hollow[3] = {{{0, 0, 0}, {1, 1, 1}, 1},
                                {{0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}, -1},
                                {{0.35, 0.35, 0.35}, {0.65, 0.65, 0.65}, 1}};

/* A cube with an inward cube inside is a hollow cube (kept as given), and
   so is the pair given both outward (the inner one repaired); three
   levels alternate solid, cavity, island in every orientation they are
   given in: 1 - 0.6^3 + 0.3^3 = 0.811. */
TEST(nested_shells)
{
    TriSurf s;
    shells(&s, hollow, 2);
    int f = trisurf_orient(&s);
    EXPECT(f == 0, "hollow cube given right: flipped %d", f);
    prepared(&s);
    expect_volume(&s, 1 - 0.216, "hollow cube");
    trisurf_free(&s);
    static const int dirs[4][3] = {{1, -1, 1}, {1, 1, 1}, {-1, -1, -1}, {-1, 1, -1}};
    static const int flips[4] = {0, 12, 24, 36};
    for (int c = 0; c < 4; c++) {
        Shell sh[3];
        memcpy(sh, hollow, sizeof sh);
        for (int i = 0; i < 3; i++) sh[i].dir = dirs[c][i];
        shells(&s, sh, 3);
        f = trisurf_orient(&s);
        EXPECT(f == flips[c], "three levels given (%d %d %d): flipped %d, expected %d", dirs[c][0], dirs[c][1],
               dirs[c][2], f, flips[c]);
        prepared(&s);
        expect_volume(&s, 1 - 0.216 + 0.027, "three levels");
        TriTopo t;
        trisurf_check(&s, &t);
        NEAR(t.volume, 0.811, 1e-15);
        trisurf_free(&s);
    }
}

/* Two overlapping cavities in a cube: 1 - 0.101 whether given inward
   (kept) or outward (repaired), and an island given outward in a cavity
   but reaching into its wall keeps its orientation: the solid is the
   hollow cube and the island, 1 - 0.216 + 0.3^3 = 0.811. */
TEST(overlapping_cavities)
{
    for (int dir = -1; dir <= 1; dir += 2) {
        Shell sh[3] = {{{0, 0, 0}, {1, 1, 1}, 1}, overlap_a, overlap_b};
        sh[1].dir = sh[2].dir = dir;
        TriSurf s;
        shells(&s, sh, 3);
        int f = trisurf_orient(&s);
        EXPECT(f == (dir > 0 ? 24 : 0), "cavities given %+d: flipped %d", dir, f);
        prepared(&s);
        expect_volume(&s, 1 - 0.101, "overlapping cavities");
        trisurf_free(&s);
    }
    Shell sh[3] = {hollow[0], hollow[1], {{0.1, 0.1, 0.1}, {0.5, 0.5, 0.5}, 1}};
    TriSurf s;
    shells(&s, sh, 3);
    int f = trisurf_orient(&s);
    EXPECT(f == 0, "island into the wall: flipped %d", f);
    prepared(&s);
    expect_volume(&s, 0.811, "island reaching into the wall");
    trisurf_free(&s);
}

/* Open surfaces (allowOpen) keep their meaning: a unit cube missing one
   triangle of its face x = 0, given inside out, is turned outward, and
   every point with x >= 0 (whose ray along +x leaves through the intact
   face x = 1) is classified as the half-open cube; with an outward cube
   [0.25, 0.75]^3 inside it, that one becomes a cavity: 1 - 0.125. */
TEST(open_surface_shells)
{
    double xyz[216], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, lo2[3] = {0.25, 0.25, 0.25}, hi2[3] = {0.75, 0.75, 0.75};
    box_soup(xyz, lo, hi);
    reverse_tris(xyz, 12);
    TriSurf s;
    trisurf_from_soup(&s, xyz + 9, 11, NULL);
    int f = trisurf_orient(&s);
    EXPECT(f == 11, "open cube inside out: flipped %d of 11", f);
    prepared(&s);
    uint64_t st = 17;
    int bad = 0;
    for (int i = 0; i < 20000; i++) {
        double x[3] = {1.5 * rnd(&st), -0.5 + 2 * rnd(&st), -0.5 + 2 * rnd(&st)};
        if (trisurf_inside(&s, x) != cube_exact(x)) bad++;
    }
    EXPECT(bad == 0, "open cube: %d of 20000 points with x >= 0 misclassified", bad);
    trisurf_free(&s);
    box_soup(xyz, lo, hi);
    box_soup(xyz + 108, lo2, hi2);
    trisurf_from_soup(&s, xyz + 9, 23, NULL);
    f = trisurf_orient(&s);
    EXPECT(f == 12, "open cube with a cube inside: flipped %d, expected 12", f);
    prepared(&s);
    double V = volume_by_lines(&s, 0, 20);
    NEAR(V, 0.875, 1e-14);
    trisurf_free(&s);
}

/* Thousands of small closed components: the nesting test must not be
   quadratic in their number.  A 40^3 lattice of tetrahedra (64000
   components, 256000 triangles) inside a cube, given outward, with every
   third one inward: all become cavities. */
TEST(many_components)
{
    enum { M = 40 };
    int n = M * M * M, nt = 4 * n + 12;
    double *xyz = mem_alloc(9 * sizeof(double) * (size_t)nt), h = 1.0 / M, Vt = 0;
    double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {1.5, 1.5, 1.5};
    box_soup(xyz, lo, hi);
    for (int c = 0; c < n; c++) {
        double o[3] = {(c % M + 0.25) * h, (c / M % M + 0.25) * h, (c / M / M + 0.25) * h}, e = 0.5 * h;
        double P[4][3] = {{o[0], o[1], o[2]}, {o[0] + e, o[1], o[2]}, {o[0], o[1] + e, o[2]}, {o[0], o[1], o[2] + e}};
        static const int F[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        for (int q = 0; q < 4; q++)
            for (int m = 0; m < 3; m++)
                memcpy(xyz + 9 * (12 + 4 * c + q) + 3 * m, P[F[q][c % 3 ? m : 2 - m]], 3 * sizeof(double));
        Vt += e * e * e / 6;
    }
    TriSurf s;
    trisurf_from_soup(&s, xyz, nt, NULL);
    free(xyz);
    clock_t t0 = clock();
    int f = trisurf_orient(&s);
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    double limit = 1;   /* 3.6 s with the pairwise nesting test it replaces */
#ifdef __SANITIZE_ADDRESS__
    limit *= 5;
#endif
    EXPECT(secs < limit, "orienting %d components took %.2f s (limit %g s)", n + 1, secs, limit);
    int want = 4 * (n - (n + 2) / 3);   /* the outward ones turn */
    EXPECT(f == want, "flipped %d, expected %d", f, want);
    TriTopo t;
    trisurf_check(&s, &t);
    NEAR(t.volume, 8 - Vt, 1e-10);   /* 256012 terms summed */
    trisurf_free(&s);
}

TEST(degenerate_triangles)
{
    double xyz[126], lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    box_soup(xyz, lo, hi);
    /* collinear corners (exactly, in binary) and a repeated corner */
    double col[9] = {0, 0, 0, 0.25, 0.5, 0.75, 0.5, 1, 1.5};
    double rep[9] = {1, 1, 1, 1, 1, 1, 0, 1, 1};
    memcpy(xyz + 108, col, sizeof col);
    memcpy(xyz + 117, rep, sizeof rep);
    int tag[14];
    for (int i = 0; i < 14; i++) tag[i] = i;
    TriSurf s;
    trisurf_from_soup(&s, xyz, 14, tag);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.ndegenerate == 2, "degenerate %d", t.ndegenerate);
    NEAR(t.degenerate_at[0], 0.25, 1e-16);
    NEAR(t.degenerate_at[1], 0.5, 1e-16);
    NEAR(t.degenerate_at[2], 0.75, 1e-16);
    int d = trisurf_drop_degenerate(&s);
    trisurf_check(&s, &t);
    EXPECT(d == 2 && s.ntris == 12 && t.ndegenerate == 0 && t.nopen == 0, "dropped %d, %d left", d, s.ntris);
    EXPECT(s.tag[11] == 11, "tags follow the triangles: %d", s.tag[11]);
    trisurf_free(&s);
}

TEST(transform_mirror)
{
    TriSurf s;
    unit_cube(&s);
    /* scale (2, 3, 0.5), mirror x, rotate 90 degrees about z, shift */
    double A[9] = {0, -3, 0, -2, 0, 0, 0, 0, 0.5}, b[3] = {10, -1, 2};
    trisurf_transform(&s, A, b);
    TriTopo t;
    trisurf_check(&s, &t);
    NEAR(t.volume, 3.0, 1e-14);
    EXPECT(t.nflipped == 0, "flipped %d", t.nflipped);
    prepared(&s);
    double x[3] = {10 - 1.5, -1 - 1, 2.25}, y[3] = {10.5, -1 - 1, 2.25};
    EXPECT(trisurf_inside(&s, x) && !trisurf_inside(&s, y), "transformed inside");
    trisurf_free(&s);
}

TEST(icosphere_volume_area)
{
    int n;
    double *xyz = icosphere_soup(4, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(n == 5120 && s.npoints == 2562, "ntris %d npoints %d", n, s.npoints);
    EXPECT(t.nopen == 0 && t.nflipped == 0 && t.nnonmanifold == 0 && t.ndegenerate == 0, "topology");
    EXPECT(s.npoints - t.nedges + s.ntris == 2, "Euler characteristic %d", s.npoints - t.nedges + s.ntris);
    /* exact polyhedron volume: tetrahedra about the centre in long double */
    long double V = 0, A = 0;
    for (int i = 0; i < s.ntris; i++) {
        const double *p = s.points + 3 * s.tris[3 * i], *q = s.points + 3 * s.tris[3 * i + 1],
                     *r = s.points + 3 * s.tris[3 * i + 2];
        long double c0 = (long double)q[1] * r[2] - (long double)q[2] * r[1];
        long double c1 = (long double)q[2] * r[0] - (long double)q[0] * r[2];
        long double c2 = (long double)q[0] * r[1] - (long double)q[1] * r[0];
        V += (p[0] * c0 + p[1] * c1 + p[2] * c2) / 6;
        long double e[2][3];
        for (int k = 0; k < 3; k++) e[0][k] = (long double)q[k] - p[k], e[1][k] = (long double)r[k] - p[k];
        long double nx = e[0][1] * e[1][2] - e[0][2] * e[1][1], ny = e[0][2] * e[1][0] - e[0][0] * e[1][2],
                    nz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        A += sqrtl(nx * nx + ny * ny + nz * nz) / 2;
    }
    NEAR(t.volume, (double)V, 1e-13);
    NEAR(t.area, (double)A, 1e-12);
    /* between the inscribed ball and the unit ball */
    double ri = inradius(&s);
    EXPECT(t.volume < 4 * M_PI / 3 && t.volume > 4 * M_PI / 3 * ri * ri * ri, "volume %.15g (ri %.15g)",
           t.volume, ri);
    EXPECT(t.area < 4 * M_PI && t.area > 4 * M_PI * ri * ri, "area %.15g", t.area);
    NEAR(t.volume, 4 * M_PI / 3, 4 * M_PI / 3 * 3 * (1 - ri));
    trisurf_free(&s);
}

/* ---------------------------------------------------------------- inside */

TEST(cube_inside_random)
{
    TriSurf s;
    unit_cube(&s);
    prepared(&s);
    uint64_t st = 1;
    int bad = 0;
    for (int i = 0; i < 20000; i++) {
        double x[3];
        for (int q = 0; q < 3; q++) x[q] = -0.5 + 2 * rnd(&st);
        if (i % 4 == 0) x[i / 4 % 3] = (double)(i % 3) * 0.5;   /* on face planes */
        if (trisurf_inside(&s, x) != cube_exact(x)) bad++;
    }
    EXPECT(bad == 0, "%d of 20000 points misclassified", bad);
    trisurf_free(&s);
}

/* Every grid line along each axis through the coordinates G (vertices,
   edges, faces and interior of the cube) classifies every point exactly
   as the half-open box, and agrees with trisurf_inside. */
TEST(cube_grazing_lines)
{
    TriSurf s;
    unit_cube(&s);
    prepared(&s);
    static const double G[] = {-0.5, 0, 0.25, 0.5, 1, 1.5};
    static const double C[] = {-1, -0.5, 0, 0.25, 0.5, 0.75, 1, 1.25, 2};
    int nC = 9, bad = 0, badin = 0, total = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int a = 0; a < 6; a++)
            for (int b = 0; b < 6; b++) {
                double p[3];
                p[axis] = 0.123;
                p[axis == 0 ? 1 : 0] = G[a];
                p[axis == 2 ? 1 : 2] = G[b];
                char in[9];
                trisurf_classify_line(&s, axis, p, C, nC, in);
                for (int i = 0; i < nC; i++) {
                    double x[3] = {p[0], p[1], p[2]};
                    x[axis] = C[i];
                    total++;
                    if (in[i] != cube_exact(x)) bad++;
                    if (trisurf_inside(&s, x) != cube_exact(x)) badin++;
                }
            }
    EXPECT(bad == 0 && badin == 0, "%d classify_line and %d inside misclassified of %d", bad, badin, total);
    trisurf_free(&s);
}

TEST(icosphere_inside_random)
{
    int n;
    double *xyz = icosphere_soup(4, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    prepared(&s);
    double ri = inradius(&s);
    uint64_t st = 7;
    int bad = 0, tested = 0, bad_line = 0;
    for (int i = 0; i < 20000; i++) {
        double x[3];
        for (int q = 0; q < 3; q++) x[q] = -1.3 + 2.6 * rnd(&st);
        double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        int in = trisurf_inside(&s, x);
        /* classify_line along each axis agrees with inside off the surface */
        for (int axis = 0; axis < 3; axis++) {
            char c;
            trisurf_classify_line(&s, axis, x, &x[axis], 1, &c);
            if (c != in) bad_line++;
        }
        if (r > ri - 1e-12 && r < 1 + 1e-12) continue;
        tested++;
        if (in != (r < ri)) bad++;
    }
    EXPECT(bad == 0 && bad_line == 0 && tested > 15000, "%d of %d misclassified, %d line disagreements", bad,
           tested, bad_line);
    trisurf_free(&s);
}

/* Lines along x, y and z through every vertex of the icosphere (and the
   poles, where the line along x runs through two vertices of degree 5):
   every point away from the surface gets the analytic answer. */
TEST(icosphere_lines_through_vertices)
{
    int n;
    double *xyz = icosphere_soup(4, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    prepared(&s);
    double ri = inradius(&s);
    enum { NC = 41 };
    double c[NC];
    for (int i = 0; i < NC; i++) c[i] = -1.25 + 2.5 * i / (NC - 1);
    int bad = 0, tested = 0, through_pole = 0;
    for (int v = 0; v < s.npoints; v++)
        for (int axis = 0; axis < 3; axis++) {
            const double *p = s.points + 3 * v;
            if (axis == 0 && p[1] == 0 && p[2] == 0) through_pole++;
            char in[NC];
            trisurf_classify_line(&s, axis, p, c, NC, in);
            for (int i = 0; i < NC; i++) {
                double x[3] = {p[0], p[1], p[2]};
                x[axis] = c[i];
                double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                if (r > ri - 1e-12 && r < 1 + 1e-12) continue;
                tested++;
                if (in[i] != (r < ri)) bad++;
                if (axis == 0 && trisurf_inside(&s, x) != in[i]) bad++;
            }
        }
    EXPECT(through_pole == 2, "lines through the poles: %d", through_pole);
    EXPECT(bad == 0, "%d of %d points misclassified", bad, tested);
    trisurf_free(&s);
}

/* Points exactly on the surface (the icosphere's vertices and edge
   midpoints as rounded) are classified the same by trisurf_inside and by
   classify_line on every axis, and segments from them along the axes and
   to random points cross the surface with the parity of the inside
   states of their ends. */
TEST(icosphere_points_on_surface)
{
    int n;
    double *xyz = icosphere_soup(3, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    prepared(&s);
    uint64_t st = 13;
    int bad_cls = 0, bad_par = 0, nin = 0, total = 0;
    for (int v = 0; v < s.npoints + s.ntris; v++) {
        double x[3];
        if (v < s.npoints)
            memcpy(x, s.points + 3 * v, sizeof x);
        else {   /* on an edge, as nearly as doubles allow */
            const int *ix = s.tris + 3 * (v - s.npoints);
            for (int q = 0; q < 3; q++) x[q] = (s.points[3 * ix[0] + q] + s.points[3 * ix[1] + q]) / 2;
        }
        int in = trisurf_inside(&s, x);
        nin += in;
        total++;
        for (int axis = 0; axis < 3; axis++) {
            char c;
            trisurf_classify_line(&s, axis, x, &x[axis], 1, &c);
            if (c != in) bad_cls++;
            double y[3] = {x[0], x[1], x[2]}, t[8];
            y[axis] = (v % 2 ? 1.5 : -1.5);
            int k = trisurf_crossings(&s, x, y, t, NULL, 8);
            if (k % 2 != in) bad_par++;
        }
        double z[3], t[8];
        for (int q = 0; q < 3; q++) z[q] = -1.5 + 3 * rnd(&st);
        int k = trisurf_crossings(&s, x, z, t, NULL, 8);
        if (k % 2 != (in ^ trisurf_inside(&s, z))) bad_par++;
    }
    EXPECT(bad_cls == 0 && bad_par == 0, "%d classify_line disagreements, %d wrong parities", bad_cls, bad_par);
    EXPECT(nin > total / 10 && nin < total * 9 / 10, "%d of %d surface points inside: expected a mix", nin, total);
    trisurf_free(&s);
}

TEST(torus_volume_inside)
{
    TriSurf s;
    torus(&s);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 0 && t.nflipped == 0 && t.nnonmanifold == 0, "topology open %d flipped %d", t.nopen,
           t.nflipped);
    EXPECT(s.npoints - t.nedges + s.ntris == 0, "Euler characteristic %d (genus 1)",
           s.npoints - t.nedges + s.ntris);
    double Vex = 2 * M_PI * M_PI * TR_R * TR_A * TR_A;
    /* the polyhedron is inscribed: slightly smaller, by O(h^2) */
    EXPECT(t.volume < Vex && t.volume > Vex * (1 - 0.01), "volume %.10g vs %.10g", t.volume, Vex);
    prepared(&s);
    uint64_t st = 3;
    int bad = 0, tested = 0;
    for (int i = 0; i < 20000; i++) {
        double x[3] = {-1.6 + 3.2 * rnd(&st), -1.6 + 3.2 * rnd(&st), -0.6 + 1.2 * rnd(&st)};
        if (i % 8 == 0) x[2] = 0;   /* lines through ring vertices */
        double rho = sqrt(x[0] * x[0] + x[1] * x[1]) - TR_R, d = sqrt(rho * rho + x[2] * x[2]);
        if (fabs(d - TR_A) < 0.02) continue;
        tested++;
        if (trisurf_inside(&s, x) != (d < TR_A)) bad++;
        char c;
        trisurf_classify_line(&s, 2, x, &x[2], 1, &c);
        if (c != (d < TR_A)) bad++;
    }
    EXPECT(bad == 0 && tested > 15000, "%d of %d misclassified", bad, tested);
    trisurf_free(&s);
}

/* ---------------------------------------------------------------- crossings */

TEST(cube_crossings_exact)
{
    TriSurf s;
    unit_cube(&s);
    prepared(&s);
    double t[4];
    int tri[4];
    double a[3] = {-0.5, 0.3, 0.7}, b[3] = {1.5, 0.3, 0.7};
    int k = trisurf_crossings(&s, a, b, t, tri, 4);
    EXPECT(k == 2, "axis segment: %d crossings", k);
    NEAR(t[0], 0.25, 1e-15);
    NEAR(t[1], 0.75, 1e-15);
    double n[3];
    trisurf_normal(&s, tri[0], n);
    EXPECT(n[0] == -1 && n[1] == 0 && n[2] == 0, "entry normal (%g %g %g)", n[0], n[1], n[2]);
    /* reversed: ascending t along b -> a */
    k = trisurf_crossings(&s, b, a, t, tri, 4);
    EXPECT(k == 2, "reversed: %d", k);
    NEAR(t[0], 0.25, 1e-15);
    NEAR(t[1], 0.75, 1e-15);
    trisurf_normal(&s, tri[0], n);
    EXPECT(n[0] == 1, "reversed entry normal x %g", n[0]);
    /* oblique, through the faces x = 0 at t = 0.2 and z = 1 */
    double c[3] = {-0.2, 0.1, 0.3}, d[3] = {0.8, 0.6, 1.7};
    k = trisurf_crossings(&s, c, d, t, NULL, 4);
    EXPECT(k == 2, "oblique: %d crossings", k);
    NEAR(t[0], 0.2, 1e-15);
    NEAR(t[1], 0.5, 1e-15);
    /* oblique through an edge (0, 0, z): exactly one crossing */
    double e1[3] = {-0.5, -0.5, 0.5}, e2[3] = {0.5, 0.5, 0.5};
    k = trisurf_crossings(&s, e1, e2, t, NULL, 4);
    EXPECT(k == 1, "through an edge: %d crossings", k);
    NEAR(t[0], 0.5, 1e-15);
    /* the main diagonal through two vertices */
    double v1[3] = {-1, -1, -1}, v2[3] = {2, 2, 2};
    k = trisurf_crossings(&s, v1, v2, t, NULL, 4);
    EXPECT(k == 2, "through vertices: %d crossings", k);
    NEAR(t[0], 1.0 / 3, 1e-15);
    NEAR(t[1], 2.0 / 3, 1e-15);
    /* a diagonal missing the cube past a vertex, and max = 1 */
    double w1[3] = {1, 2, 0.5}, w2[3] = {2, 1, 0.5};
    k = trisurf_crossings(&s, w1, w2, t, NULL, 4);
    EXPECT(k == 0, "touching: %d", k);
    k = trisurf_crossings(&s, v1, v2, t, NULL, 1);
    EXPECT(k == 2 && t[0] == 1.0 / 3, "max 1: %d, %g", k, t[0]);
    trisurf_free(&s);
}

/* Every segment between two points of the lattice {-0.5, 0, 0.5, 1, 1.5}^3
   (many on faces, edges and vertices of the cube) crosses the surface an
   odd number of times exactly when its ends are classified differently,
   and each crossing point lies on the cube's surface. */
TEST(cube_crossings_lattice)
{
    TriSurf s;
    unit_cube(&s);
    prepared(&s);
    static const double G[] = {-0.5, 0, 0.5, 1, 1.5};
    double P[125][3];
    for (int i = 0; i < 125; i++) P[i][0] = G[i % 5], P[i][1] = G[i / 5 % 5], P[i][2] = G[i / 25];
    int bad = 0, badpt = 0, pairs = 0;
    char msg[200] = "";
    for (int i = 0; i < 125; i++)
        for (int j = 0; j < 125; j++) {
            if (i == j) continue;
            double t[8];
            int k = trisurf_crossings(&s, P[i], P[j], t, NULL, 8);
            pairs++;
            if (k % 2 != (cube_exact(P[i]) ^ cube_exact(P[j])) || k > 2) {
                if (!bad++)
                    snprintf(msg, sizeof msg, "(%g %g %g)->(%g %g %g): %d crossings", P[i][0], P[i][1], P[i][2],
                             P[j][0], P[j][1], P[j][2], k);
            }
            for (int q = 0; q < k && q < 8; q++) {
                double x[3], dmin = INFINITY, out = 0;
                for (int c = 0; c < 3; c++) {
                    x[c] = P[i][c] + t[q] * (P[j][c] - P[i][c]);
                    dmin = fmin(dmin, fmin(fabs(x[c]), fabs(x[c] - 1)));
                    out = fmax(out, fmax(-x[c], x[c] - 1));
                }
                if (dmin > 1e-15 || out > 1e-15) badpt++;
            }
        }
    EXPECT(bad == 0 && badpt == 0, "%d of %d segments with wrong parity (first %s), %d points off the surface",
           bad, pairs, msg, badpt);
    trisurf_free(&s);
}

TEST(icosphere_crossings)
{
    int n;
    double *xyz = icosphere_soup(4, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    prepared(&s);
    double ri = inradius(&s);
    uint64_t st = 11;
    int bad = 0, badpt = 0;
    for (int i = 0; i < 4000; i++) {
        double a[3], b[3];
        for (int q = 0; q < 3; q++) a[q] = -1.4 + 2.8 * rnd(&st), b[q] = -1.4 + 2.8 * rnd(&st);
        if (i % 2) {   /* axis segments, half of them through vertices */
            int ax = i / 2 % 3;
            if (i % 4 == 1) memcpy(a, s.points + 3 * (i % s.npoints), sizeof a), a[ax] = -1.4;
            for (int q = 0; q < 3; q++)
                if (q != ax) b[q] = a[q];
        }
        double t[16];
        int k = trisurf_crossings(&s, a, b, t, NULL, 16);
        if (k % 2 != (trisurf_inside(&s, a) ^ trisurf_inside(&s, b)) || k > 16) bad++;
        for (int q = 0; q < k && q < 16; q++) {
            double x[3];
            for (int c = 0; c < 3; c++) x[c] = a[c] + t[q] * (b[c] - a[c]);
            double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
            if (r < ri - 1e-14 || r > 1 + 1e-14 || (q && t[q] < t[q - 1])) badpt++;
        }
    }
    EXPECT(bad == 0 && badpt == 0, "%d segments with wrong parity, %d bad crossing points", bad, badpt);
    trisurf_free(&s);
}

/* Lines along x a few ulps from the projection of icosphere edges: the
   floating-point orientation is unreliable there (it may miss both
   triangles of the edge or hit both); the exact predicates must give an
   even number of crossings, two when the line passes through the ball. */
TEST(icosphere_lines_near_edges)
{
    int n;
    double *xyz = icosphere_soup(4, &n);
    TriSurf s;
    trisurf_from_soup(&s, xyz, n, NULL);
    free(xyz);
    prepared(&s);
    double ri = inradius(&s);
    int bad = 0, lines = 0;
    for (int t = 0; t < s.ntris; t += 3)
        for (int m = 0; m < 3; m++) {
            const double *p = s.points + 3 * s.tris[3 * t + m], *q = s.points + 3 * s.tris[3 * t + (m + 1) % 3];
            double my = (p[1] + q[1]) / 2, mz = (p[2] + q[2]) / 2;
            for (int i = -2; i <= 2; i++)
                for (int j = -2; j <= 2; j++) {
                    double y = my, z = mz;
                    for (int r = 0; r < abs(i); r++) y = nextafter(y, i > 0 ? 2 : -2);
                    for (int r = 0; r < abs(j); r++) z = nextafter(z, j > 0 ? 2 : -2);
                    double a[3] = {-2, y, z}, b[3] = {2, y, z}, tt[8];
                    int k = trisurf_crossings(&s, a, b, tt, NULL, 8);
                    lines++;
                    if (k % 2 || (y * y + z * z < ri * ri * 0.99 && k != 2)) bad++;
                }
        }
    EXPECT(bad == 0, "%d of %d lines near edges with a wrong crossing count", bad, lines);
    trisurf_free(&s);
}

/* ---------------------------------------------------------------- nearest */

/* Reference point-triangle distance: the plane when the foot is inside,
   else the nearest edge (segment distance). */
static double seg_dist(const double *x, const double *a, const double *b)
{
    double d[3], w[3];
    for (int i = 0; i < 3; i++) d[i] = b[i] - a[i], w[i] = x[i] - a[i];
    double t = (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double r = 0;
    for (int i = 0; i < 3; i++) r += (w[i] - t * d[i]) * (w[i] - t * d[i]);
    return sqrt(r);
}

static double ref_dist(const TriSurf *s, int t, const double *x)
{
    const double *p[3];
    for (int m = 0; m < 3; m++) p[m] = s->points + 3 * s->tris[3 * t + m];
    double n[3];
    trisurf_normal(s, t, n);
    double h = 0;
    for (int i = 0; i < 3; i++) h += (x[i] - p[0][i]) * n[i];
    double f[3];
    for (int i = 0; i < 3; i++) f[i] = x[i] - h * n[i];
    int inside = 1;
    for (int m = 0; m < 3; m++) {
        const double *a = p[m], *b = p[(m + 1) % 3];
        double e[3], g[3], c[3];
        for (int i = 0; i < 3; i++) e[i] = b[i] - a[i], g[i] = f[i] - a[i];
        c[0] = e[1] * g[2] - e[2] * g[1], c[1] = e[2] * g[0] - e[0] * g[2], c[2] = e[0] * g[1] - e[1] * g[0];
        if (c[0] * n[0] + c[1] * n[1] + c[2] * n[2] < 0) inside = 0;
    }
    if (inside) return fabs(h);
    return fmin(seg_dist(x, p[0], p[1]), fmin(seg_dist(x, p[1], p[2]), seg_dist(x, p[2], p[0])));
}

TEST(nearest)
{
    TriSurf s;
    unit_cube(&s);
    prepared(&s);
    double d, x[3] = {0.5, 0.5, 2}, y[3] = {2, 2, 2}, z[3] = {0.5, 0.4, 0.45};
    int t = trisurf_nearest(&s, x, &d);
    double n[3];
    trisurf_normal(&s, t, n);
    NEAR(d, 1.0, 1e-15);
    EXPECT(n[2] == 1, "nearest face normal (%g %g %g)", n[0], n[1], n[2]);
    trisurf_nearest(&s, y, &d);
    NEAR(d, sqrt(3.0), 1e-15);
    trisurf_nearest(&s, z, &d);
    NEAR(d, 0.4, 1e-15);
    trisurf_free(&s);

    int nt;
    double *xyz = icosphere_soup(4, &nt);
    trisurf_from_soup(&s, xyz, nt, NULL);
    free(xyz);
    prepared(&s);
    uint64_t st = 5;
    double worst = 0;
    for (int i = 0; i < 300; i++) {
        double p[3];
        for (int q = 0; q < 3; q++) p[q] = -3 + 6 * rnd(&st);
        if (i % 3 == 0) unit(p);   /* on the sphere: the cutter's case */
        int k = trisurf_nearest(&s, p, &d);
        double best = INFINITY;
        for (int q = 0; q < s.ntris; q++) best = fmin(best, ref_dist(&s, q, p));
        worst = fmax(worst, fabs(d - best));
        worst = fmax(worst, fabs(ref_dist(&s, k, p) - d));
    }
    EXPECT(worst < 1e-13, "nearest distance differs from brute force by %g", worst);
    trisurf_free(&s);
}

TEST(prepare_errors)
{
    TriSurf s;
    trisurf_from_soup(&s, NULL, 0, NULL);
    Err e = {0};
    EXPECT(trisurf_prepare(&s, &e) == -1, "empty surface prepared");
    CONTAINS(e.msg, "no triangles");
    trisurf_free(&s);
    unit_cube(&s);
    s.points[4] = NAN;
    EXPECT(trisurf_prepare(&s, &e) == -1, "NaN prepared");
    CONTAINS(e.msg, "non-finite");
    trisurf_free(&s);
}

int main(void)
{
    RUN(cube_topology);
    RUN(weld_signed_zero);
    RUN(open_cube);
    RUN(duplicated_triangle);
    RUN(flipped_triangle_and_repair);
    RUN(orient_inverted_and_cavity);
    RUN(overlapping_shells_union);
    RUN(nested_shells);
    RUN(overlapping_cavities);
    RUN(many_components);
    RUN(open_surface_shells);
    RUN(degenerate_triangles);
    RUN(transform_mirror);
    RUN(icosphere_volume_area);
    RUN(cube_inside_random);
    RUN(cube_grazing_lines);
    RUN(icosphere_inside_random);
    RUN(icosphere_lines_through_vertices);
    RUN(icosphere_points_on_surface);
    RUN(torus_volume_inside);
    RUN(cube_crossings_exact);
    RUN(cube_crossings_lattice);
    RUN(icosphere_crossings);
    RUN(icosphere_lines_near_edges);
    RUN(nearest);
    RUN(prepare_errors);
    return test_summary();
}
