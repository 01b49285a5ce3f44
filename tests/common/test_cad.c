/*
** test_cad.c: gmsh-backed geometry (common/cad.c).
**
** Fixtures in tests/data/cad/ (made once with /usr/bin/gmsh from the .geo
** files beside them): sphere.step, the unit sphere, and boxhole.step, a
** 2 x 1 x 0.5 box with a through-hole of radius 0.25 along z.  They are
** found under $KIESEL_TOP (tests/run sets it), else under the current
** directory; the tests that need them SKIP when they are missing.
**
** Volume tolerances are the chordal error bound for a triangle whose
** corners lie on a sphere (or, in projection, a circle) of radius R with
** edges at most h: for y = sum l_i v_i, |y|^2 = R^2 - sum_{i<j} l_i l_j
** |v_i - v_j|^2 >= R^2 - h^2/3, so the triangulation stays within
** gap = R - sqrt(R^2 - h^2/3) of the surface, and the volume between them
** is at most (surface area) * gap.  h is the longest edge of the mesh.
*/
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include "cad.h"
#include "test.h"

static const double PI = 3.14159265358979323846;

/* Fixture paths, set by main. */
static char sphere_step[1024], boxhole_step[1024], boxhole_geo[1024];

static int fixture(const char *name, char *path, size_t n)
{
    const char *top = getenv("KIESEL_TOP");
    snprintf(path, n, "%s/tests/data/cad/%s", top ? top : ".", name);
    return access(path, R_OK) == 0;
}

/* Longest and mean triangle edge. */
static void edges(const TriSurf *s, double *longest, double *mean)
{
    double h = 0, sum = 0;
    for (int i = 0; i < s->ntris; i++)
        for (int k = 0; k < 3; k++) {
            const double *a = s->points + 3 * s->tris[3 * i + k];
            const double *b = s->points + 3 * s->tris[3 * i + (k + 1) % 3];
            double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
            h = fmax(h, d);
            sum += d;
        }
    *longest = h;
    *mean = s->ntris ? sum / (3.0 * s->ntris) : 0;
}

static double gap(double R, double h) { return R - sqrt(R * R - h * h / 3); }

/* Deterministic uniform numbers in [0, 1). */
static double urand(unsigned long long *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) / 9007199254740992.0;
}

/* A random point of triangle i and its right-hand normal. */
static void tri_point(const TriSurf *s, int i, unsigned long long *rng, double x[3], double nrm[3])
{
    double a = urand(rng), b = urand(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const double *p = s->points + 3 * s->tris[3 * i], *q = s->points + 3 * s->tris[3 * i + 1],
                 *r = s->points + 3 * s->tris[3 * i + 2];
    double u[3], v[3];
    for (int k = 0; k < 3; k++) {
        x[k] = p[k] + a * (q[k] - p[k]) + b * (r[k] - p[k]);
        u[k] = q[k] - p[k];
        v[k] = r[k] - p[k];
    }
    nrm[0] = u[1] * v[2] - u[2] * v[1];
    nrm[1] = u[2] * v[0] - u[0] * v[2];
    nrm[2] = u[0] * v[1] - u[1] * v[0];
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

TEST(sphere_step_mesh)
{
    const char *path = sphere_step;
    TriSurf s;
    Err e = {{0}};
    double t0 = now();
    Cad *c = cad_open(path, 0, &s, &e);
    double t1 = now();
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    TriTopo t;
    trisurf_check(&s, &t);
    double h, mean;
    edges(&s, &h, &mean);
    double exact = 4 * PI / 3, tol = 4 * PI * gap(1, h);
    printf("  sphere.step: open + mesh %.3f s, %d triangles, %d points, longest edge %.4f, "
           "mean %.4f, volume error %.3e (bound %.3e)\n",
           t1 - t0, s.ntris, s.npoints, h, mean, exact - t.volume, tol);
    EXPECT(t.nopen == 0 && t.nnonmanifold == 0 && t.nflipped == 0 && t.ndegenerate == 0,
           "open %d nonmanifold %d flipped %d degenerate %d", t.nopen, t.nnonmanifold,
           t.nflipped, t.ndegenerate);
    /* default size: diagonal / 50 of the box [-1, 1]^3; gmsh's edges
       scatter about the target, a few near the poles reach 2x */
    double size = 2 * sqrt(3.0) / 50;
    EXPECT(mean > 0.85 * size && mean < 1.15 * size, "mean edge %g, size %g", mean, size);
    EXPECT(h < 2 * size, "longest edge %g, size %g", h, size);
    EXPECT(t.volume < exact && exact - t.volume <= tol, "volume %.15g, exact %.15g, bound %g",
           t.volume, exact, tol);
    double worst = 0;
    for (int i = 0; i < s.npoints; i++) {
        const double *p = s.points + 3 * i;
        worst = fmax(worst, fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1));
    }
    EXPECT(worst <= 1e-12, "mesh nodes off the sphere by %g", worst);
    cad_close(c);
    trisurf_free(&s);
}

TEST(sphere_step_size)
{
    const char *path = sphere_step;
    TriSurf s;
    Err e = {{0}};
    Cad *c = cad_open(path, 0.2, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    double h, mean;
    edges(&s, &h, &mean);
    /* an equilateral mesh of the unit sphere with edge 0.2 has
       4 pi / (sqrt(3)/4 0.2^2) = 725 triangles */
    EXPECT(mean > 0.17 && mean < 0.23, "mean edge %g for size 0.2", mean);
    EXPECT(s.ntris > 500 && s.ntris < 1000, "%d triangles for size 0.2", s.ntris);
    cad_close(c);
    trisurf_free(&s);
}

TEST(sphere_step_normal)
{
    const char *path = sphere_step;
    TriSurf s;
    Err e = {{0}};
    Cad *c = cad_open(path, 0.3, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    unsigned long long rng = 42;
    int bad_sign = 0;
    double worst_n = 0, worst_p = 0, worst_r = 0;
    for (int k = 0; k < 500; k++) {
        int i = (int)(urand(&rng) * s.ntris);
        double x[3], ref[3], n[3], p[3];
        tri_point(&s, i, &rng, x, ref);
        double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (x[0] * ref[0] + x[1] * ref[1] + x[2] * ref[2] <= 0) bad_sign++;
        /* a point off the surface, inside or outside */
        double scale = 0.6 + 0.8 * urand(&rng), y[3] = {scale * x[0], scale * x[1], scale * x[2]};
        EXPECT(cad_normal(c, s.tag[i], y, ref, n) == 1, "cad_normal not exact");
        EXPECT(cad_closest(c, s.tag[i], y, p) == 1, "cad_closest not exact");
        for (int d = 0; d < 3; d++) {
            worst_n = fmax(worst_n, fabs(n[d] - x[d] / r));
            worst_p = fmax(worst_p, fabs(p[d] - x[d] / r));
        }
        worst_r = fmax(worst_r, fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1));
        /* the sign follows ref */
        double m[3], neg[3] = {-ref[0], -ref[1], -ref[2]};
        EXPECT(cad_normal(c, s.tag[i], y, neg, m) == 1 && m[0] == -n[0] && m[1] == -n[1] &&
                   m[2] == -n[2],
               "normal does not follow ref");
    }
    printf("  sphere normals: max |n - x/|x|| %.2e, max |p - x/|x|| %.2e, max ||p| - 1| %.2e\n",
           worst_n, worst_p, worst_r);
    EXPECT(bad_sign == 0, "%d triangles not oriented outward", bad_sign);
    EXPECT(worst_n <= 1e-8, "normal error %g", worst_n);
    EXPECT(worst_p <= 1e-8 && worst_r <= 1e-8, "closest point error %g, radius error %g", worst_p,
           worst_r);
    double n[3] = {7, 7, 7}, x[3] = {1, 0, 0};
    EXPECT(cad_normal(c, 12345, x, x, n) == 0 && n[0] == 7, "unknown tag gave a normal");
    cad_close(c);
    trisurf_free(&s);
}

/* Expected outward normal of boxhole's solid at a surface point x. */
static void boxhole_normal(const double x[3], double n[3])
{
    const double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 0.5};
    n[0] = n[1] = n[2] = 0;
    for (int d = 0; d < 3; d++) {
        if (fabs(x[d] - lo[d]) < 1e-9) { n[d] = -1; return; }
        if (fabs(x[d] - hi[d]) < 1e-9) { n[d] = 1; return; }
    }
    double dx = x[0] - 1, dy = x[1] - 0.5, r = sqrt(dx * dx + dy * dy);
    n[0] = -dx / r;   /* the hole: into the axis */
    n[1] = -dy / r;
}

static void check_boxhole(const char *path, double size)
{
    TriSurf s;
    Err e = {{0}};
    Cad *c = cad_open(path, size, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    TriTopo t;
    trisurf_check(&s, &t);
    double h, mean, r = 0.25, exact = 1 - PI / 32;
    edges(&s, &h, &mean);
    double tol = 2 * PI * r * 0.5 * gap(r, h);
    printf("  %s: %d triangles, longest edge %.4f, volume error %.3e (bound %.3e)\n", path,
           s.ntris, h, t.volume - exact, tol);
    EXPECT(t.nopen == 0 && t.nnonmanifold == 0 && t.nflipped == 0,
           "open %d nonmanifold %d flipped %d", t.nopen, t.nnonmanifold, t.nflipped);
    EXPECT(t.volume > exact && t.volume - exact <= tol, "volume %.15g, exact %.15g, bound %g",
           t.volume, exact, tol);
    int ntags = 0, seen[64] = {0};
    for (int i = 0; i < s.ntris; i++)
        if (s.tag[i] > 0 && s.tag[i] < 64 && !seen[s.tag[i]]) seen[s.tag[i]] = 1, ntags++;
    EXPECT(ntags == 7, "%d surface tags, expected 7 (6 planes and the hole)", ntags);
    /* exact normals at the centroid of every triangle */
    double worst = 0;
    for (int i = 0; i < s.ntris; i++) {
        double x[3] = {0, 0, 0}, p[3], n[3], want[3], ref[3];
        unsigned long long rng = (unsigned long long)i;
        tri_point(&s, i, &rng, x, ref);
        EXPECT(cad_closest(c, s.tag[i], x, p) == 1, "no closest point");
        boxhole_normal(p, want);
        EXPECT(cad_normal(c, s.tag[i], x, ref, n) == 1, "no normal");
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(n[d] - want[d]));
    }
    EXPECT(worst <= 1e-8, "normal error %g", worst);
    cad_close(c);
    trisurf_free(&s);
}

TEST(boxhole_step)
{
    check_boxhole(boxhole_step, 0);
}

TEST(boxhole_geo)
{
    check_boxhole(boxhole_geo, 0.05);
}

/* A .geo of gmsh's built-in kernel (no OpenCASCADE): a unit cube by
   extrusion, meshed at the given size, with exact face normals. */
TEST(geo_builtin_kernel)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/extruded.geo", test_tmpdir());
    FILE *f = fopen(path, "w");
    EXPECT(f, "cannot write %s", path);
    if (!f) return;
    fprintf(f, "Point(1) = {0, 0, 0, 0.1}; Point(2) = {1, 0, 0, 0.1};\n"
               "Point(3) = {1, 1, 0, 0.1}; Point(4) = {0, 1, 0, 0.1};\n"
               "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
               "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
               "Extrude {0, 0, 1} { Surface{1}; }\n");
    fclose(f);
    TriSurf s;
    Err e = {{0}};
    Cad *c = cad_open(path, 0.2, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    TriTopo t;
    trisurf_check(&s, &t);
    double h, mean;
    edges(&s, &h, &mean);
    EXPECT(t.nopen == 0 && t.nflipped == 0, "open %d flipped %d", t.nopen, t.nflipped);
    NEAR(t.volume, 1, 1e-14);
    /* size 0.2 overrides the points' 0.1 */
    EXPECT(mean > 0.17 && mean < 0.25, "mean edge %g for size 0.2", mean);
    double worst = 0;
    for (int i = 0; i < s.ntris; i++) {
        double x[3], ref[3], n[3], want[3] = {0, 0, 0};
        unsigned long long rng = (unsigned long long)i + 1;
        tri_point(&s, i, &rng, x, ref);
        EXPECT(cad_normal(c, s.tag[i], x, ref, n) == 1, "no normal on surface %d", s.tag[i]);
        for (int d = 0; d < 3; d++) {
            if (fabs(x[d]) < 1e-12) want[d] = -1;
            if (fabs(x[d] - 1) < 1e-12) want[d] = 1;
        }
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(n[d] - want[d]));
    }
    EXPECT(worst <= 1e-12, "normal error %g", worst);
    cad_close(c);
    trisurf_free(&s);
}

/* A unit cube as ascii STL with two facets written the wrong way round. */
static void write_cube_stl(const char *path)
{
    static const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "solid cube\n");
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 2; k++) {
            int v[3] = {q[i][0], q[i][1 + k], q[i][2 + k]};
            if (i == 3 && k == 1) v[1] = q[i][3], v[2] = q[i][2];
            if (i == 5 && k == 0) v[1] = q[i][2], v[2] = q[i][1];
            fprintf(f, " facet normal 0 0 0\n  outer loop\n");
            for (int j = 0; j < 3; j++)
                fprintf(f, "   vertex %d %d %d\n", v[j] & 1, (v[j] >> 1) & 1, (v[j] >> 2) & 1);
            fprintf(f, "  endloop\n endfacet\n");
        }
    fprintf(f, "endsolid cube\n");
    fclose(f);
}

TEST(stl_discrete)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/cube.stl", test_tmpdir());
    write_cube_stl(path);
    TriSurf s;
    Err e = {{0}};
    Cad *c = cad_open(path, 0.01, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (!c) return;
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(s.ntris == 12 && s.npoints == 8, "%d triangles, %d points (size must be ignored)",
           s.ntris, s.npoints);
    EXPECT(t.nopen == 0 && t.nflipped == 0, "open %d flipped %d", t.nopen, t.nflipped);
    NEAR(t.volume, 1, 1e-14);
    double x[3] = {0.5, 0.5, 1.2}, ref[3] = {0, 0, 1}, n[3] = {7, 7, 7}, p[3] = {7, 7, 7};
    EXPECT(cad_normal(c, s.tag[0], x, ref, n) == 0 && n[0] == 7, "discrete surface gave a normal");
    EXPECT(cad_closest(c, s.tag[0], x, p) == 0 && p[0] == 7, "discrete surface gave a point");
    cad_close(c);
    trisurf_free(&s);
}

/* Second-order quadrangles (a .geo that sets gmsh's global mesh options)
   come back as corner triangles, and the options do not leak into the
   next file: the sphere meshes the same before and after. */
TEST(quads_and_options)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/quadbox.geo", test_tmpdir());
    FILE *f = fopen(path, "w");
    EXPECT(f, "cannot write %s", path);
    if (!f) return;
    fprintf(f, "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
               "Transfinite Curve{:} = 5;\nTransfinite Surface{:};\n"
               "Mesh.RecombineAll = 1;\nMesh.ElementOrder = 2;\n");
    fclose(f);
    TriSurf s0, s, s1;
    Err e = {{0}};
    /* c0 stays open so that gmsh (and its options) stay alive */
    Cad *c0 = cad_open(sphere_step, 0.3, &s0, &e);
    EXPECT(c0, "%s", e.msg);
    Cad *c = cad_open(path, 0.25, &s, &e);
    EXPECT(c, "%s", e.msg);
    if (c) {
        TriTopo t;
        trisurf_check(&s, &t);
        EXPECT(t.nopen == 0 && t.nflipped == 0 && t.nnonmanifold == 0, "open %d flipped %d",
               t.nopen, t.nflipped);
        NEAR(t.volume, 1, 1e-14);
        NEAR(t.area, 6, 1e-14);
        /* 4 x 4 quadrangles per face, two triangles each, and the
           6 * 4^2 + 2 corner nodes (second-order nodes unused) */
        EXPECT(s.ntris == 6 * 16 * 2 && s.npoints == 6 * 16 + 2, "%d triangles, %d points",
               s.ntris, s.npoints);
        cad_close(c);
        trisurf_free(&s);
    }
    Cad *c1 = cad_open(sphere_step, 0.3, &s1, &e);
    EXPECT(c1, "%s", e.msg);
    cad_close(c1);
    cad_close(c0);
    if (c0 && c1)
        EXPECT(s0.ntris == s1.ntris && s0.npoints == s1.npoints &&
                   memcmp(s0.points, s1.points, 3 * sizeof(double) * (size_t)s0.npoints) == 0,
               "sphere meshed differently after quadbox.geo: %d / %d triangles", s0.ntris,
               s1.ntris);
    trisurf_free(&s0);
    trisurf_free(&s1);
}

/* Runs cad_open on path with stdout and stderr captured; returns the
   number of bytes gmsh wrote to them. */
static long open_quietly(const char *path, Cad **c, TriSurf *s, Err *e)
{
    char cap[1024];
    snprintf(cap, sizeof cap, "%s/captured.txt", test_tmpdir());
    fflush(stdout);
    fflush(stderr);
    int fd = open(cap, O_WRONLY | O_CREAT | O_TRUNC, 0644), o1 = dup(1), o2 = dup(2);
    dup2(fd, 1);
    dup2(fd, 2);
    *c = cad_open(path, 0, s, e);
    fflush(stdout);
    fflush(stderr);
    dup2(o1, 1);
    dup2(o2, 2);
    close(o1);
    close(o2);
    long n = lseek(fd, 0, SEEK_END);
    close(fd);
    return n;
}

static void write_file(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fwrite(text, 1, n, f);
    fclose(f);
}

static void expect_failure(const char *path, const char *want)
{
    TriSurf s;
    Err e = {{0}};
    Cad *c = NULL;
    long out = open_quietly(path, &c, &s, &e);
    EXPECT(!c, "%s opened", path);
    EXPECT(out == 0, "gmsh wrote %ld bytes for %s", out, path);
    EXPECT(s.ntris == 0 && s.points == NULL, "surface not empty after failure");
    EXPECT(strncmp(e.msg, path, strlen(path)) == 0, "message does not name the file: %s", e.msg);
    CONTAINS(e.msg, want);
    for (const char *m = e.msg; *m; m++)
        EXPECT(*m >= 32 && *m < 127, "unprintable byte %d in message", *m);
    if (c) {
        cad_close(c);
        trisurf_free(&s);
    }
}

TEST(bad_files)
{
    char path[1024];
    const char *dir = test_tmpdir();
    snprintf(path, sizeof path, "%s/missing.step", dir);
    expect_failure(path, "cannot open");
    snprintf(path, sizeof path, "%s/garbage.txt", dir);
    write_file(path, "}{ 1 2 this is no geometry\n", 27);
    expect_failure(path, "gmsh could not read it: ");
    snprintf(path, sizeof path, "%s/garbage.step", dir);
    write_file(path, "ISO-10303-21;\nnonsense\n", 23);
    expect_failure(path, "gmsh could not read it: ");
    snprintf(path, sizeof path, "%s/empty.geo", dir);
    write_file(path, "// nothing here\n", 16);
    expect_failure(path, "no surfaces");
    char bytes[1000];
    unsigned long long rng = 7;
    for (int i = 0; i < 1000; i++) bytes[i] = (char)(urand(&rng) * 256);
    snprintf(path, sizeof path, "%s/random.stl", dir);
    write_file(path, bytes, sizeof bytes);
    expect_failure(path, "gmsh could not read it: ");
    /* gmsh's .geo parser must still work after the syntax errors */
    snprintf(path, sizeof path, "%s/ok.geo", dir);
    const char *geo = "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 2, 3};\n";
    write_file(path, geo, strlen(geo));
    TriSurf s;
    Err e = {{0}};
    Cad *c = NULL;
    long out = open_quietly(path, &c, &s, &e);
    EXPECT(c, "%s", e.msg);
    EXPECT(out == 0, "gmsh wrote %ld bytes", out);
    if (!c) return;
    TriTopo t;
    trisurf_check(&s, &t);
    NEAR(t.volume, 6, 1e-12);
    cad_close(c);
    trisurf_free(&s);
}

TEST(two_at_once)
{
    const char *sphere = sphere_step, *boxhole = boxhole_step;
    TriSurf s1, s2;
    Err e = {{0}};
    Cad *a = cad_open(sphere, 0.3, &s1, &e);
    EXPECT(a, "%s", e.msg);
    Cad *b = a ? cad_open(boxhole, 0.2, &s2, &e) : NULL;
    EXPECT(b, "%s", e.msg);
    if (!b) {
        cad_close(a);
        if (a) trisurf_free(&s1);
        return;
    }
    /* interleaved queries go to the right model: the sphere's surface 1
       and the box's surfaces are different surfaces */
    double x[3] = {0.3, 0.4, 1.5}, y[3], ref[3], p[3], q[3], r[3], v[3];
    unsigned long long rng = 1;
    tri_point(&s2, 0, &rng, y, ref);
    EXPECT(cad_closest(a, 1, x, p) == 1, "sphere query failed");
    EXPECT(cad_closest(b, s2.tag[0], y, q) == 1, "box query failed");
    NEAR(fabs(q[0] - y[0]) + fabs(q[1] - y[1]) + fabs(q[2] - y[2]), 0, 1e-12);
    EXPECT(cad_closest(a, 1, x, r) == 1 && r[0] == p[0] && r[1] == p[1] && r[2] == p[2],
           "sphere query changed after a box query");
    NEAR(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1, 1e-12);
    cad_close(a);
    trisurf_free(&s1);
    EXPECT(cad_closest(b, s2.tag[0], y, v) == 1 && v[0] == q[0] && v[1] == q[1] && v[2] == q[2],
           "box query changed after the sphere closed");
    cad_close(b);
    trisurf_free(&s2);
    /* gmsh is finalised now; opening again initialises it again */
    Cad *c = cad_open(sphere, 0.5, &s1, &e);
    EXPECT(c, "reopen: %s", e.msg);
    if (c) {
        cad_close(c);
        trisurf_free(&s1);
    }
}

/* Runs a test when its fixture files exist, else says why not. */
#define RUN_WITH(name, ok, files)                                                    \
    do {                                                                             \
        if (ok)                                                                      \
            RUN(name);                                                               \
        else                                                                         \
            printf("SKIP %s: fixture %s missing (set KIESEL_TOP)\n", #name, files);   \
    } while (0)

int main(void)
{
    int sphere = fixture("sphere.step", sphere_step, sizeof sphere_step);
    int box = fixture("boxhole.step", boxhole_step, sizeof boxhole_step);
    int geo = fixture("boxhole.geo", boxhole_geo, sizeof boxhole_geo);
    RUN_WITH(sphere_step_mesh, sphere, sphere_step);
    RUN_WITH(sphere_step_size, sphere, sphere_step);
    RUN_WITH(sphere_step_normal, sphere, sphere_step);
    RUN_WITH(boxhole_step, box, boxhole_step);
    RUN_WITH(boxhole_geo, geo, boxhole_geo);
    RUN(geo_builtin_kernel);
    RUN(stl_discrete);
    RUN_WITH(quads_and_options, sphere, sphere_step);
    RUN(bad_files);
    RUN_WITH(two_at_once, sphere && box, "sphere.step, boxhole.step");
    return test_summary();
}
