/*
** test_cut.c: cut cells (cut.h) against exact geometry.
**
** Every cut grid is checked for validity: mesh_check (ordering),
** quality_check (closed cells to 1e-12 of the surface, orientation,
** positive volumes) and a topological watertightness test: for each cell
** every directed edge of its outward faces appears exactly once reversed
** (checkMesh's "cells zipped up"), which makes the immersed boundary and
** the grid faces one closed surface per cell.  Volumes are compared with
** closed forms: plane cuts and boxes on grid lines exactly (1e-12), the
** sphere and the disc by their second-order convergence.  The geometry
** is always the real one, parsed from a dictionary string.
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "block.h"
#include "cartcells.h"
#include "cut.h"
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "mesh.h"
#include "quality.h"
#include "test.h"
#include "fixture.h"
#include "randgeo.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- helpers ---- */


/* A block grid of the coordinates x[k][0..n[k]]; 2-D (z empty) when twod. */
static void grid_make(Mesh *m, double *const x[3], const int n[3], int twod)
{
    BlockSide side[BLOCK_NSIDES];
    for (int s = 0; s < BLOCK_NSIDES; s++)
        side[s] = (BlockSide){block_side_names[s], twod && s >= 4 ? "empty" : "patch", NULL};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
}

/* Uniform grid of n cells per axis on lo..hi. */
static void grid_box(Mesh *m, const int n[3], const double lo[3], const double hi[3], int twod)
{
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = i == n[k] ? hi[k] : lo[k] + (hi[k] - lo[k]) * i / n[k];
    }
    grid_make(m, x, n, twod);
    for (int k = 0; k < 3; k++) free(x[k]);
}

static void grid_unit(Mesh *m, int n)
{
    int nn[3] = {n, n, n};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    grid_box(m, nn, lo, hi, 0);
}

static int cmp64(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : x > y;
}

/* Each directed edge of a cell's outward faces appears once, reversed
   once.  Returns the first bad cell or -1. */
static int zipped(const Mesh *m)
{
    size_t cap = 64;
    int64_t *e = mem_alloc(cap * sizeof *e);
    int bad = -1;
    for (int c = 0; c < m->ncells && bad < 0; c++) {
        size_t ne = 0;
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
            int f = m->cell_faces[i], o = m->face_off[f], n = m->face_off[f + 1] - o;
            int rev = m->owner[f] != c;
            for (int q = 0; q < n; q++) {
                int a = m->face_idx[o + q], b = m->face_idx[o + (q + 1) % n];
                if (rev) {
                    int t = a;
                    a = b;
                    b = t;
                }
                mem_grow((void **)&e, &cap, ne + 1, sizeof *e);
                e[ne++] = (int64_t)a * m->npoints + b;
            }
        }
        qsort(e, ne, sizeof *e, cmp64);
        for (size_t i = 0; i < ne && bad < 0; i++) {
            int64_t a = e[i] / m->npoints, b = e[i] % m->npoints, r = b * m->npoints + a;
            if ((i + 1 < ne && e[i + 1] == e[i]) || a == b || !bsearch(&r, e, ne, sizeof *e, cmp64)) bad = c;
        }
    }
    free(e);
    return bad;
}

/* Full validity check of a cut grid; fills why and returns 0 when sound. */
static int check_grid(Mesh *m, char *why, size_t nwhy)
{
    Err e;
    if (mesh_check(m, &e)) {
        snprintf(why, nwhy, "mesh_check: %s", e.msg);
        return -1;
    }
    Quality q;
    quality_measure(m, &q);
    if (quality_check(m, &q, NULL, &e)) {
        snprintf(why, nwhy, "quality_check: %s", e.msg);
        return -1;
    }
    int c = zipped(m);
    if (c >= 0) {
        snprintf(why, nwhy, "cell %d is not zipped up (parent %d)", c, m->cell_parent[c]);
        return -1;
    }
    int nb = m->nfaces - m->ninternal;
    for (int f = 0; f < nb; f++) {
        double l = sqrt(m->boundary_normal[3 * f] * m->boundary_normal[3 * f] +
                        m->boundary_normal[3 * f + 1] * m->boundary_normal[3 * f + 1] +
                        m->boundary_normal[3 * f + 2] * m->boundary_normal[3 * f + 2]);
        if (fabs(l - 1) > 1e-12) {
            snprintf(why, nwhy, "boundary face %d: wall normal of length %g", f + m->ninternal, l);
            return -1;
        }
    }
    return 0;
}

/* Cuts grid by G; on failure prints the message and returns -1. */
static int cut(const Mesh *grid, FixtureGeo *G, double snap, Mesh *out, CutStats *st)
{
    CutOpts o;
    cut_opts_default(&o);
    if (snap >= 0) o.snap = snap;
    Err e;
    if (cut_mesh(grid, &G->g, &o, out, st, &e)) {
        printf("cut_mesh: %s\n", e.msg);
        return -1;
    }
    return 0;
}

/* Cuts, checks and returns the fluid volume (NAN on failure, with why). */
static double cut_check(const Mesh *grid, const char *text, CutStats *st, char *why, size_t nwhy)
{
    FixtureGeo G;
    snprintf(why, nwhy, "geometry failed");
    if (fixture_geo(&G, text)) return NAN;
    Mesh m;
    double v = NAN;
    snprintf(why, nwhy, "cut failed");
    if (!cut(grid, &G, -1, &m, st)) {
        if (!check_grid(&m, why, nwhy)) v = st->vol_fluid;
        mesh_free(&m);
    }
    fixture_geo_free(&G);
    return v;
}

/* Volume of the unit cube below the plane n.x = d (n > 0 componentwise). */
static double cube_below_plane(const double n[3], double d)
{
    double v = 0;
    for (int c = 0; c < 8; c++) {
        double s = d - n[0] * (c & 1) - n[1] * ((c >> 1) & 1) - n[2] * (c >> 2);
        int sg = ((c & 1) + ((c >> 1) & 1) + (c >> 2)) & 1 ? -1 : 1;
        if (s > 0) v += sg * s * s * s;
    }
    return v / (6 * n[0] * n[1] * n[2]);
}

/* ---- tests ---- */

/* A half-space at an arbitrary angle on a graded grid: exact volume, and
   the complementary flow side fills the rest of the box. */
TEST(cut_halfspace_exact)
{
    int n[3] = {9, 11, 10};
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = pow((double)i / n[k], 1.3 + 0.1 * k);
    }
    Mesh grid;
    grid_make(&grid, x, n, 0);
    double nn[3] = {0.3, 0.5, 0.8}, l = sqrt(0.98);
    for (int k = 0; k < 3; k++) nn[k] /= l;
    const double p[3] = {0.45, 0.52, 0.61};
    double d = nn[0] * p[0] + nn[1] * p[1] + nn[2] * p[2], exact = cube_below_plane(nn, d);
    char txt[512], why[2100];
    CutStats s1, s2;
    snprintf(txt, sizeof txt,
             "plane { flow inside; shape halfSpace; point (%.17g %.17g %.17g); normal (%.17g %.17g %.17g); }",
             p[0], p[1], p[2], nn[0], nn[1], nn[2]);
    double v1 = cut_check(&grid, txt, &s1, why, sizeof why);
    EXPECT(!isnan(v1), "inside: %s", why);
    snprintf(
        txt, sizeof txt,
        "plane { flow outside; shape halfSpace; point (%.17g %.17g %.17g); normal (%.17g %.17g %.17g); }",
        p[0], p[1], p[2], nn[0], nn[1], nn[2]);
    double v2 = cut_check(&grid, txt, &s2, why, sizeof why);
    EXPECT(!isnan(v2), "outside: %s", why);
    NEAR(v1, exact, 1e-12);
    NEAR(v1 + v2, 1.0, 1e-12);
    EXPECT(s1.ncut > 0 && s1.nboundary > 0, "ncut %d nboundary %d", s1.ncut, s1.nboundary);
    NEAR(s1.vol_box, 1.0, 1e-15);
    /* the cut plane's area inside the cube, from both sides */
    NEAR(s1.area_boundary, s2.area_boundary, 1e-12);
    mesh_free(&grid);
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* A solid box rotated 30 degrees about z whose corners sit on grid lines
   and whose top and bottom lie on grid planes: every cell meets at most
   one face plane, so the cut is exact. */
TEST(cut_rotated_box_exact)
{
    const double L = 0.5, c = cos(30 * M_PI / 180), s = sin(30 * M_PI / 180), x0 = 0.35, y0 = 0.1;
    double kx[] = {0, x0 - L * s, x0, x0 + L * c - L * s, x0 + L * c, 1};
    double ky[] = {0, y0, y0 + L * s, y0 + L * c, y0 + L * s + L * c, 1};
    double kz[] = {0, 0.2, 0.8, 1};
    double *kk[3] = {kx, ky, kz};
    int nk[3] = {6, 6, 4}, n[3];
    double *x[3];
    for (int a = 0; a < 3; a++) {
        x[a] = mem_alloc(sizeof(double) * 64);
        n[a] = 0;
        x[a][0] = kk[a][0];
        for (int i = 0; i + 1 < nk[a]; i++) {
            int m = (int)ceil((kk[a][i + 1] - kk[a][i]) / 0.07);
            for (int j = 1; j <= m; j++)
                x[a][++n[a]] = j == m ? kk[a][i + 1] : kk[a][i] + (kk[a][i + 1] - kk[a][i]) * j / m;
        }
    }
    Mesh grid;
    grid_make(&grid, x, n, 0);
    char why[2100];
    CutStats st;
    double v = cut_check(&grid,
                         "box { flow outside; shape box; min (0 0 0.2); max (0.5 0.5 0.8);"
                         " rotate { axis (0 0 1); angle 30; origin (0 0 0); } translate (0.35 0.1 0); }",
                         &st, why, sizeof why);
    EXPECT(!isnan(v), "%s", why);
    NEAR(v, 1 - L * L * 0.6, 1e-12);
    /* the box's surface: four sides and the two ends */
    NEAR(st.area_boundary, 4 * L * 0.6 + 2 * L * L, 1e-12);
    mesh_free(&grid);
    for (int a = 0; a < 3; a++) free(x[a]);
}

/* An axis-aligned solid box whose faces lie on grid planes: vertices on
   its surface are solid, the cut is exact; the plane x = 0.5 through grid
   vertices, the plane x + y = 1 through grid edges and face diagonals and
   x + y + z = 1.5 through vertices too. */
TEST(cut_on_grid_planes)
{
    Mesh grid;
    grid_unit(&grid, 10);
    char why[2100];
    CutStats st;
    double v =
        cut_check(&grid, "box { shape box; min (0.2 0.3 0.4); max (0.7 0.8 0.9); }", &st, why, sizeof why);
    EXPECT(!isnan(v), "box: %s", why);
    NEAR(v, 1 - 0.125, 1e-12);
    NEAR(st.area_boundary, 6 * 0.25, 1e-12);
    EXPECT(st.nsnap > 0, "nsnap %d", st.nsnap);
    /* flow inside it: the cells along its edges and in its corners are
       whole cells (cut.c, "Whole cells"), not chamfered */
    v = cut_check(&grid, "box { flow inside; shape box; min (0.2 0.3 0.4); max (0.7 0.8 0.9); }", &st, why,
                  sizeof why);
    EXPECT(!isnan(v), "box, flow inside: %s", why);
    NEAR(v, 0.125, 1e-12);
    EXPECT(st.ncells == 125 && st.ncut == 0, "ncells %d ncut %d", st.ncells, st.ncut);
    NEAR(st.area_boundary, 6 * 0.25, 1e-12);
    /* an L-shaped flow domain (union of two aligned boxes): convex and
       concave edges on grid lines, both exact */
    v = cut_check(&grid,
                  "l { flow inside; shape union; a { shape box; min (0.1 0.1 0.1); max (0.9 0.4 0.6); }\n"
                  "  b { shape box; min (0.1 0.1 0.1); max (0.4 0.9 0.6); } }",
                  &st, why, sizeof why);
    EXPECT(!isnan(v), "L, flow inside: %s", why);
    NEAR(v, (0.8 * 0.3 + 0.3 * 0.5) * 0.5, 1e-12);
    EXPECT(st.ncut == 0, "L: %d cut cells", st.ncut);
    /* its complement: flow round the L */
    v = cut_check(&grid,
                  "l { flow outside; shape union; a { shape box; min (0.1 0.1 0.1); max (0.9 0.4 0.6); }\n"
                  "  b { shape box; min (0.1 0.1 0.1); max (0.4 0.9 0.6); } }",
                  &st, why, sizeof why);
    EXPECT(!isnan(v), "L, flow outside: %s", why);
    NEAR(v, 1 - (0.8 * 0.3 + 0.3 * 0.5) * 0.5, 1e-12);
    /* a box whose faces lie on grid planes and a sphere that cuts it: whole
       cells next to cut ones */
    v = cut_check(&grid,
                  "p { flow inside; shape difference; a { shape box; min (0.2 0.2 0.2); max (0.8 0.8 0.8); }\n"
                  "  b { shape sphere; centre (0.8 0.8 0.8); radius 0.33; } }",
                  &st, why, sizeof why);
    EXPECT(!isnan(v), "box minus sphere: %s", why);
    /* the cut cells at the sphere chamfer the box's edges they touch, so
       the error is second order, not round-off: 3.9e-3 at h = 0.1, 8.2e-4
       at h = 0.05 (4.8e-5 at h = 1/80) */
    double ex = 0.216 - M_PI * 0.33 * 0.33 * 0.33 / 6;
    NEAR(v, ex, 5e-3);
    Mesh g20;
    grid_unit(&g20, 20);
    double v20 = cut_check(&g20,
                           "p { flow inside; shape difference; a { shape box; min (0.2 0.2 0.2); max (0.8 0.8 0.8); }\n"
                           "  b { shape sphere; centre (0.8 0.8 0.8); radius 0.33; } }",
                           &st, why, sizeof why);
    EXPECT(!isnan(v20), "box minus sphere, h = 0.05: %s", why);
    NEAR(v20, ex, 1.2e-3);
    EXPECT(fabs(v - ex) / fabs(v20 - ex) > 3, "error ratio %g: not second order", fabs(v - ex) / fabs(v20 - ex));
    mesh_free(&g20);
    v = cut_check(&grid, "p { flow inside; shape halfSpace; point (0.5 0 0); normal (1 0 0); }", &st, why,
                  sizeof why);
    EXPECT(!isnan(v), "x = 0.5: %s", why);
    NEAR(v, 0.5, 1e-12);
    EXPECT(st.ncells == 500 && st.ncut == 0, "ncells %d ncut %d", st.ncells, st.ncut);
    NEAR(st.area_boundary, 1.0, 1e-12);
    v = cut_check(&grid, "p { flow inside; shape halfSpace; point (0.5 0.5 0); normal (1 1 0); }", &st, why,
                  sizeof why);
    EXPECT(!isnan(v), "x + y = 1: %s", why);
    NEAR(v, 0.5, 1e-12);
    NEAR(st.area_boundary, sqrt(2.0), 1e-12);
    v = cut_check(&grid, "p { flow inside; shape halfSpace; point (0.5 0.5 0.5); normal (1 1 1); }", &st, why,
                  sizeof why);
    EXPECT(!isnan(v), "x + y + z = 1.5: %s", why);
    NEAR(v, 0.5, 1e-12);
    mesh_free(&grid);
}

/* Sphere volume and surface area converge at second order. */
TEST(cut_sphere_convergence)
{
    const double R = 0.3, V = 4 * M_PI * R * R * R / 3, A = 4 * M_PI * R * R;
    const int ns[4] = {8, 16, 32, 64};
    double ev[4], ea[4];
    char why[2100], txt[256];
    snprintf(txt, sizeof txt, "ball { flow inside; shape sphere; centre (0.5123 0.4871 0.5037); radius %g; }",
             R);
    printf("   n   volume error   order   area error   order\n");
    for (int r = 0; r < 4; r++) {
        Mesh grid;
        grid_unit(&grid, ns[r]);
        CutStats st;
        double v = cut_check(&grid, txt, &st, why, sizeof why);
        EXPECT(!isnan(v), "n = %d: %s", ns[r], why);
        ev[r] = fabs(v - V) / V;
        ea[r] = fabs(st.area_boundary - A) / A;
        printf("  %3d  %.4e  %6.3f   %.4e  %6.3f\n", ns[r], ev[r], r ? log2(ev[r - 1] / ev[r]) : 0.0, ea[r],
               r ? log2(ea[r - 1] / ea[r]) : 0.0);
        mesh_free(&grid);
    }
    double ov = log2(ev[1] / ev[3]) / 2, oa = log2(ea[1] / ea[3]) / 2;
    printf("  observed order (16 -> 64): volume %.3f, area %.3f\n", ov, oa);
    EXPECT(ov > 1.8, "volume order %g", ov);
    EXPECT(oa > 1.8, "area order %g", oa);
    EXPECT(ev[3] < 2e-3, "volume error %g at 64", ev[3]);
}

/* 2-D: the disc (a flattened sphere) converges at second order; the cells
   are prisms between the empty patches. */
TEST(cut_disc_convergence)
{
    const double R = 0.31, Aex = M_PI * R * R * 0.1;
    const int ns[4] = {8, 16, 32, 64};
    double ev[4];
    char why[2100];
    printf("   n   area error   order\n");
    for (int r = 0; r < 4; r++) {
        int n[3] = {ns[r], ns[r], 1};
        double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.1};
        Mesh grid;
        grid_box(&grid, n, lo, hi, 1);
        FixtureGeo G;
        EXPECT(!fixture_geo(&G, "disc { flow inside; shape sphere; centre (0.5071 0.4933 0.05); radius 0.31; }"),
               "geometry");
        geometry_flatten(&G.g, 2, 0.05);
        Mesh m;
        CutStats st;
        EXPECT(!cut(&grid, &G, -1, &m, &st), "cut");
        EXPECT(!check_grid(&m, why, sizeof why), "n = %d: %s", ns[r], why);
        EXPECT(mesh_empty_axis(&m) == 2, "empty axis %d", mesh_empty_axis(&m));
        for (int f = m.ninternal; f < m.nfaces; f++) {
            int p = mesh_face_patch(&m, f);
            if (p == 4 || p == 5)
                EXPECT(fabs(m.face_area[3 * f + 2]) > 0 && m.face_area[3 * f] == 0, "front face");
        }
        ev[r] = fabs(st.vol_fluid - Aex) / Aex;
        printf("  %3d  %.4e  %6.3f\n", ns[r], ev[r], r ? log2(ev[r - 1] / ev[r]) : 0.0);
        mesh_free(&m);
        fixture_geo_free(&G);
        mesh_free(&grid);
    }
    double o = log2(ev[1] / ev[3]) / 2;
    printf("  observed order (16 -> 64): %.3f\n", o);
    EXPECT(o > 1.8, "order %g", o);
}

/* Inside and outside flow of one sphere fill the box exactly, and the
   boundary is the same surface seen from both sides. */
TEST(cut_sphere_complement)
{
    Mesh grid;
    grid_unit(&grid, 16);
    char why[2100];
    CutStats s1, s2;
    double v1 = cut_check(&grid, "b { flow inside; shape sphere; centre (0.47 0.52 0.5); radius 0.33; }", &s1,
                          why, sizeof why);
    EXPECT(!isnan(v1), "inside: %s", why);
    double v2 = cut_check(&grid, "b { flow outside; shape sphere; centre (0.47 0.52 0.5); radius 0.33; }",
                          &s2, why, sizeof why);
    EXPECT(!isnan(v2), "outside: %s", why);
    NEAR(v1 + v2, 1.0, 1e-12);
    NEAR(s1.area_boundary, s2.area_boundary, 1e-12);
    EXPECT(s1.nboundary > 0 && s1.ntunnel == 0, "nboundary %d ntunnel %d", s1.nboundary, s1.ntunnel);
    mesh_free(&grid);
}

/* The sphere shifted by fractions of a cell: every volume within 1.5
   times the error of the convergence study at 16 cells (2.1e-2). */
TEST(cut_sphere_shifted)
{
    Mesh grid;
    grid_unit(&grid, 16);
    const double R = 0.3, V = 4 * M_PI * R * R * R / 3;
    double worst = 0;
    char why[2100], txt[256];
    for (int s = 0; s < 8; s++) {
        double d = s / 8.0 / 16;
        snprintf(txt, sizeof txt, "b { flow inside; shape sphere; centre (%.17g %.17g %.17g); radius 0.3; }",
                 0.5 + d, 0.5 + 0.7 * d, 0.5 + 0.3 * d);
        CutStats st;
        double v = cut_check(&grid, txt, &st, why, sizeof why);
        EXPECT(!isnan(v), "shift %d: %s", s, why);
        worst = fmax(worst, fabs(v - V) / V);
    }
    printf("  worst relative volume error over 8 shifts: %.3e\n", worst);
    EXPECT(worst < 3e-2, "worst %g", worst);
    mesh_free(&grid);
}

/* Degenerate positions: a sphere through grid vertices, spheres tangent
   to a grid plane at a vertex and at an edge midpoint, a slab thinner
   than a cell. */
TEST(cut_degenerate)
{
    Mesh grid;
    grid_unit(&grid, 10);
    char why[2100];
    CutStats st;
    const double V = 4 * M_PI * 0.027 / 3;
    /* radius 0.3 about a vertex: (0.8,0.5,0.5), (0.7,0.7,0.6), ... lie on it */
    double v = cut_check(&grid, "b { flow inside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", &st,
                         why, sizeof why);
    EXPECT(!isnan(v), "through vertices, inside: %s", why);
    EXPECT(fabs(v - V) < 0.1 * V, "volume %g vs %g", v, V);
    EXPECT(st.nsnap > 0, "nsnap %d", st.nsnap);
    v = cut_check(&grid, "b { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", &st, why,
                  sizeof why);
    EXPECT(!isnan(v), "through vertices, outside: %s", why);
    EXPECT(fabs(1 - v - V) < 0.1 * V, "volume %g vs %g", 1 - v, V);
    /* tangent to x = 0.2 at the vertex (0.2, 0.5, 0.5) */
    v = cut_check(&grid, "b { shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", &st, why, sizeof why);
    EXPECT(!isnan(v), "tangent at a vertex: %s", why);
    /* tangent to x = 0.2 at the midpoint of a z edge */
    v = cut_check(&grid, "b { shape sphere; centre (0.5 0.5 0.55); radius 0.3; }", &st, why, sizeof why);
    EXPECT(!isnan(v), "tangent at an edge: %s", why);
    /* infinite cylinder along z tangent to the grid lines x = 0.2 */
    v = cut_check(&grid,
                  "c { shape cylinder; point1 (0.5 0.5 0); point2 (0.5 0.5 1); radius 0.3; infinite yes; }",
                  &st, why, sizeof why);
    EXPECT(!isnan(v), "cylinder tangent to grid lines: %s", why);
    /* a slab between grid planes, thinner than a cell: dropped, counted */
    v = cut_check(&grid, "s { shape box; min (0.43 -1 -1); max (0.46 2 2); }", &st, why, sizeof why);
    EXPECT(!isnan(v), "thin slab: %s", why);
    NEAR(v, 1.0, 1e-12);
    EXPECT(st.nthin == 11 * 11, "nthin %d", st.nthin);
    /* a slab with one face on a grid plane, thinner than a cell: its
       vertices on that plane lie on the surface (a crossing meets them),
       so the slab is cut exactly (it was dropped before issue 9; the
       count of edges crossed twice is taken before snapping, as before) */
    v = cut_check(&grid, "s { shape box; min (0.4 -1 -1); max (0.43 2 2); }", &st, why, sizeof why);
    EXPECT(!isnan(v), "thin slab on a grid plane: %s", why);
    NEAR(v, 0.97, 1e-12);
    EXPECT(st.nthin == 11 * 11, "nthin %d", st.nthin);
    mesh_free(&grid);
}

/* Two balls at opposite corners of one cell: that cell's only fluid
   corners are a body diagonal, and the tunnel keeps it one cell. */
TEST(cut_tunnel)
{
    Mesh grid;
    grid_unit(&grid, 4);
    char why[2100];
    CutStats st;
    double v = cut_check(&grid,
                         "u { flow inside; shape union;"
                         " a { shape sphere; centre (0.25 0.25 0.25); radius 0.1; }"
                         " b { shape sphere; centre (0.5 0.5 0.5); radius 0.1; } }",
                         &st, why, sizeof why);
    EXPECT(!isnan(v), "%s", why);
    EXPECT(st.ntunnel == 1, "ntunnel %d", st.ntunnel);
    EXPECT(st.ncells == 15, "ncells %d", st.ncells);
    mesh_free(&grid);
}

/* Box-side patches keep their names and types, cyclic pairs stay matched
   face for face, the surfaces' patches follow; clashing names and empty
   results are refused. */
TEST(cut_patches)
{
    int n[3] = {6, 5, 4};
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = (double)i / n[k];
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"},
                                    {"walls", "wall", NULL},     {"walls", "wall", NULL},
                                    {"bottom", "patch", NULL},   {"top", "patch", NULL}};
    Mesh grid;
    mesh_init(&grid);
    Err e;
    EXPECT(!block_mesh(&grid, x, n, side, NULL, "test", NULL, &e), "%s", e.msg);
    FixtureGeo G;
    EXPECT(!fixture_geo(&G, "pipe { shape cylinder; point1 (-1 0.5 0.5); point2 (2 0.5 0.5); radius 0.3; "
                         "infinite yes; flow inside; }"),
           "geometry");
    Mesh m;
    CutStats st;
    EXPECT(!cut(&grid, &G, -1, &m, &st), "cut");
    char why[2100];
    EXPECT(!check_grid(&m, why, sizeof why), "%s", why);
    EXPECT(m.npatches == grid.npatches + 1, "npatches %d", m.npatches);
    for (int p = 0; p < grid.npatches && p < m.npatches; p++) {
        EXPECT(!strcmp(m.patches[p].name, grid.patches[p].name), "patch %d name %s", p, m.patches[p].name);
        EXPECT(!strcmp(m.patches[p].type, grid.patches[p].type), "patch %d type %s", p, m.patches[p].type);
    }
    EXPECT(!strcmp(m.patches[m.npatches - 1].name, "pipe") && !strcmp(m.patches[m.npatches - 1].type, "wall"),
           "pipe");
    int l = mesh_patch(&m, "left"), r = mesh_patch(&m, "right");
    EXPECT(l >= 0 && r >= 0 && m.patches[l].size == m.patches[r].size && m.patches[l].size > 0,
           "cyclic sizes");
    for (int i = 0; l >= 0 && r >= 0 && i < m.patches[l].size && i < m.patches[r].size; i++) {
        int fl = m.patches[l].start + i, fr = m.patches[r].start + i;
        int nl = m.face_off[fl + 1] - m.face_off[fl], nr = m.face_off[fr + 1] - m.face_off[fr];
        EXPECT(nl == nr, "cyclic face %d: %d and %d points", i, nl, nr);
        for (int q = 0; q < nl && nl == nr; q++) {
            const double *a = m.points + 3 * m.face_idx[m.face_off[fl] + q];
            const double *b = m.points + 3 * m.face_idx[m.face_off[fr] + (nr - q) % nr];
            EXPECT(fabs(a[1] - b[1]) < 1e-15 && fabs(a[2] - b[2]) < 1e-15 && a[0] == 0 && b[0] == 1,
                   "cyclic face %d point %d: (%g %g %g) vs (%g %g %g)", i, q, a[0], a[1], a[2], b[0], b[1],
                   b[2]);
        }
        NEAR(m.face_area[3 * fl] + m.face_area[3 * fr], 0, 1e-15);
    }
    /* the wall normal of the pipe is radial, pointing into the solid */
    int pp = m.npatches - 1;
    for (int f = m.patches[pp].start; f < m.patches[pp].start + m.patches[pp].size; f++) {
        const double *w = m.boundary_normal + 3 * (f - m.ninternal), *C = m.face_centre + 3 * f;
        double ry = C[1] - 0.5, rz = C[2] - 0.5, rl = sqrt(ry * ry + rz * rz);
        EXPECT(fabs(w[0]) < 1e-12 && fabs(w[1] - ry / rl) < 1e-12 && fabs(w[2] - rz / rl) < 1e-12,
               "normal of face %d", f);
    }
    for (int c = 0; c < m.ncells; c++) EXPECT(m.cell_parent[c] >= 0 && m.cell_parent[c] < 120, "parent");
    EXPECT(m.cart.n[0] == 6 && m.cart.n[1] == 5 && m.cart.n[2] == 4, "cart");
    mesh_free(&m);
    fixture_geo_free(&G);

    EXPECT(!fixture_geo(&G, "walls { shape sphere; centre (0.5 0.5 0.5); radius 0.2; }"), "geometry");
    EXPECT(cut_mesh(&grid, &G.g, NULL, &m, &st, &e) == -1, "name clash accepted");
    CONTAINS(e.msg, "geometryDict:");
    CONTAINS(e.msg, "walls");
    fixture_geo_free(&G);
    EXPECT(!fixture_geo(&G, "all { shape sphere; centre (0.5 0.5 0.5); radius 5; }"), "geometry");
    EXPECT(cut_mesh(&grid, &G.g, NULL, &m, &st, &e) == -1, "empty result accepted");
    CONTAINS(e.msg, "no cell is left");
    fixture_geo_free(&G);
    mesh_free(&m);
    Mesh plain;
    mesh_init(&plain);
    plain.ncells = 1;
    EXPECT(!fixture_geo(&G, "b { shape sphere; centre (0.5 0.5 0.5); radius 0.2; }"), "geometry");
    EXPECT(cut_mesh(&plain, &G.g, NULL, &m, &st, &e) == -1, "grid without cart accepted");
    CONTAINS(e.msg, "Cartesian");
    fixture_geo_free(&G);
    mesh_free(&m);
    mesh_free(&grid);
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* ---- random robustness ---- */

/* Is point x on a grid plane (a cut point on a grid line, or where two
   cells' chords cross on a grid face), not a fan centre? */
static int on_grid_plane(const CartGrid *g, const double *x)
{
    int on = 0;
    for (int k = 0; k < 3; k++)
        for (int i = 0; i <= g->n[k]; i++)
            if (x[k] == g->x[k][i]) {
                on++;
                break;
            }
    return on >= 1;
}

/* Per Cartesian cell: the sum of the cut volumes of the two flow sides;
   odd[parent] is set where a non-planar boundary loop was triangulated by
   its own points (no fan centre off the grid planes): cut.c does that only
   to keep face pyramids positive, judged for each side on its own, so
   the two sides' surfaces may differ there. */
static void add_parent_vol(const Mesh *m, double *pv, char *odd)
{
    int ngrid = 6;
    for (int c = 0; c < m->ncells; c++) {
        pv[m->cell_parent[c]] += m->cell_vol[c];
        int nimm = 0, off = 0;
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
            int f = m->cell_faces[i];
            if (f < m->ninternal || mesh_face_patch(m, f) < ngrid) continue;
            nimm++;
            for (int j = m->face_off[f]; j < m->face_off[f + 1]; j++)
                if (!on_grid_plane(&m->cart, m->points + 3 * m->face_idx[j])) off = 1;
        }
        if (nimm >= 2 && !off) odd[m->cell_parent[c]] = 1;
    }
}

/* Is Cartesian cell ci one where both flow sides must add up exactly?
   Not when a face has two diagonal fluid corners (the ambiguity rule
   joins the fluid of either side), the fluid corners are a body diagonal
   for either side (tunnel), or an edge's crossings are odd in number,
   contradict its ends, or lie near a vertex (snapping). */
static int regular_cell(const Geometry *g, const Mesh *grid, int ci)
{
    const CartGrid *cg = &grid->cart;
    int ijk[3] = {ci % cg->n[0], (ci / cg->n[0]) % cg->n[1], ci / (cg->n[0] * cg->n[1])};
    double p[8][3];
    int f[8], mask = 0;
    for (int q = 0; q < 8; q++) {
        for (int k = 0; k < 3; k++) p[q][k] = cg->x[k][ijk[k] + ((q >> k) & 1)];
        f[q] = geometry_fluid(g, p[q]);
        mask |= f[q] << q;
    }
    for (int q = 0; q < 4; q++)
        if (mask == ((1 << q) | (1 << (7 - q))) || (255 & ~mask) == ((1 << q) | (1 << (7 - q)))) return 0;
    /* a corner on the surface (within 1e-9 of the cell size, any direction)
       is snapped, and then whole cells and chamfers (cut.c) make the two
       sides' cuts differ by design */
    for (int q = 0; q < 8; q++)
        for (int d = 0; d < 27; d++) {
            double y[3] = {p[q][0], p[q][1], p[q][2]};
            for (int k = 0, dd = d; k < 3; k++, dd /= 3)
                y[k] += (dd % 3 - 1) * 1e-9 * (cg->x[k][ijk[k] + 1] - cg->x[k][ijk[k]]);
            if (geometry_fluid(g, y) != f[q]) return 0;
        }
    static const int fc[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    for (int s = 0; s < 6; s++) {
        const int *c = fc[s];
        if (f[c[0]] == f[c[2]] && f[c[1]] == f[c[3]] && f[c[0]] != f[c[1]]) return 0;
    }
    for (int q = 0; q < 8; q++)
        for (int k = 0; k < 3; k++) {
            if ((q >> k) & 1) continue;
            int w = q | (1 << k);
            GeoCross cr[8];
            int nc = geometry_crossings(g, p[q], p[w], cr, 8);
            if (nc != (f[q] != f[w])) return 0;
            for (int i = 0; i < nc && i < 8; i++)
                if (cr[i].t < 1e-6 || cr[i].t > 1 - 1e-6) return 0;
        }
    return 1;
}

/* One random geometry cut with the flow inside (side 0) and outside
   (side 1) on grid: each side's geometry, grid and statistics; ok when
   the grid is sound, empty when nothing was left (acceptable). */
typedef struct TwoSides {
    FixtureGeo G[2];
    Mesh m[2];
    CutStats st[2];
    int ok[2], made[2], empty[2];
} TwoSides;

/* Cuts both sides of shape (case it) and returns the failures, printed. */
static int two_sides(TwoSides *s, const Mesh *grid, const char *shape, int twod, int nn, int it)
{
    char txt[8192], why[2100];
    int nfail = 0;
    memset(s->ok, 0, sizeof s->ok);
    memset(s->made, 0, sizeof s->made);
    memset(s->empty, 0, sizeof s->empty);
    mesh_init(&s->m[0]);
    mesh_init(&s->m[1]);
    for (int side = 0; side < 2; side++) {
        snprintf(txt, sizeof txt, "s { flow %s; %s }", side ? "outside" : "inside", shape);
        if (fixture_geo(&s->G[side], txt)) {
            printf("bad random geometry: %s\n", txt);
            return nfail + 1;
        }
        s->made[side] = 1;
        if (twod) geometry_flatten(&s->G[side].g, 2, 0.5 / nn);
        CutOpts o;
        cut_opts_default(&o);
        Err e;
        if (cut_mesh(grid, &s->G[side].g, &o, &s->m[side], &s->st[side], &e)) {
            /* the only acceptable failure: nothing left */
            if (!strstr(e.msg, "no cell is left")) {
                printf("case %d side %d: %s\n  %s\n", it, side, e.msg, txt);
                nfail++;
            } else
                s->empty[side] = 1;
            continue;
        }
        if (check_grid(&s->m[side], why, sizeof why)) {
            printf("case %d side %d: %s\n  %s\n", it, side, why, txt);
            nfail++;
            continue;
        }
        s->ok[side] = 1;
    }
    return nfail;
}

static void two_sides_free(TwoSides *s)
{
    for (int side = 0; side < 2; side++) {
        mesh_free(&s->m[side]);
        if (s->made[side]) fixture_geo_free(&s->G[side]);
    }
}

TEST(cut_random)
{
    /* CUT_RANDOM_CASES=n runs a longer study */
    const char *env = getenv("CUT_RANDOM_CASES");
    int ncase = env ? atoi(env) : 500, nfail = 0, nreg = 0, nirr = 0, ncells = 0;
    double worst = 0;
    char shape[7000];
    int it;
    for (it = 0; it < ncase && nfail < 3; it++) {
        /* every fourth case in 2-D: one cell thick, empty front and back */
        int nn = 8 + it % 5, twod = it % 4 == 3, n3[3] = {nn, nn, twod ? 1 : nn};
        double lo[3] = {0, 0, 0}, hi[3] = {1, 1, twod ? 1.0 / nn : 1};
        Mesh grid;
        grid_box(&grid, n3, lo, hi, twod);
        rand_shape(shape, sizeof shape, 2);
        TwoSides S;
        nfail += two_sides(&S, &grid, shape, twod, nn, it);
        for (int side = 0; side < 2; side++)
            if (S.ok[side]) ncells += S.m[side].ncells;
        if (nfail == 0 && S.made[0]) {
            int nc = grid.ncells;
            double *pv = MEM_NEW(double, nc);
            char *odd = MEM_NEW(char, nc);
            for (int side = 0; side < 2; side++)
                if (S.ok[side]) add_parent_vol(&S.m[side], pv, odd);
            double h3 = hi[2] / ((double)nn * nn * n3[2]);
            for (int c = 0; c < nc; c++) {
                if (odd[c] || !regular_cell(&S.G[0].g, &grid, c)) {
                    nirr++;
                    continue;
                }
                nreg++;
                double err = fabs(pv[c] - h3) / h3;
                if (err > worst) worst = err;
                if (err > 1e-12 && nfail++ < 3)
                    printf("case %d: cell %d: volumes add to %.17g of the cell\n  %s\n", it, c, pv[c] / h3,
                           shape);
            }
            free(pv);
            free(odd);
        }
        two_sides_free(&S);
        mesh_free(&grid);
    }
    printf("  %d random cases run of %d (a quarter 2-D; the study stops at 3 failures), %d cells; volume identity "
           "on %d regular cells (worst %.2e), %d irregular skipped\n",
           it, ncase, ncells, nreg, worst, nirr);
    EXPECT(nfail == 0, "%d failures in the first %d cases", nfail, it);
    EXPECT(nreg > it * 300, "only %d regular cells checked", nreg);
}

/* Issue 9, defect 1: a cylinder whose caps lie on grid planes lost the
   fluid along the caps (the cells there came out as wedges): 9.0 % below
   the exact volume against 5.5 % with the caps moved off the planes by
   1e-7, and inside + outside fell 1.2 % short of the box.  Now the two
   flow sides add up to every Cartesian cell to round-off, and the
   aligned run is no worse than the shifted one. */
TEST(cut_cap_on_grid_plane)
{
    Mesh grid;
    grid_unit(&grid, 10);
    double pv[1000] = {0}, err[2], box = 0;
    char odd[1000] = {0};
    const char *caps[2] = {"point1 (0.5 0.5 0.2); point2 (0.5 0.5 0.8);",
                           "point1 (0.5 0.5 0.2000001); point2 (0.5 0.5 0.8000001);"};
    double exact = M_PI * 0.09 * 0.6;
    for (int shifted = 0; shifted < 2; shifted++)
        for (int side = 0; side < 2; side++) {
            char txt[256], why[256];
            snprintf(txt, sizeof txt, "c { flow %s; shape cylinder; %s radius 0.3; }", side ? "outside" : "inside",
                     caps[shifted]);
            FixtureGeo G;
            Mesh m;
            CutStats st;
            EXPECT(fixture_geo(&G, txt) == 0, "geometry");
            EXPECT(cut(&grid, &G, CUT_SNAP, &m, &st) == 0, "cut failed");
            EXPECT(check_grid(&m, why, sizeof why) == 0, "%s: %s", txt, why);
            if (!side) err[shifted] = (st.vol_fluid - exact) / exact;
            if (!shifted) {
                add_parent_vol(&m, pv, odd);
                box += st.vol_fluid;
            }
            mesh_free(&m);
            fixture_geo_free(&G);
        }
    double worst = 0;
    for (int c = 0; c < 1000; c++) worst = fmax(worst, fabs(pv[c] / 1e-3 - 1));
    printf("  inside volume error: caps on grid planes %.3e, shifted by 1e-7 %.3e; inside + outside = box %.17g, "
           "worst Cartesian cell %.2e\n",
           err[0], err[1], box, worst);
    EXPECT(fabs(box - 1) < 1e-13, "inside + outside = %.17g of the box", box);
    EXPECT(worst < 1e-12, "a Cartesian cell's two sides add to %.3e off", worst);
    EXPECT(fabs(err[0]) <= fabs(err[1]) + 1e-3, "aligned caps error %.3e worse than shifted %.3e", err[0], err[1]);
    mesh_free(&grid);
}

/* A slab a quarter of a cell thin whose broad face lies on a side of the
   box and whose rims lie on grid lines (a prism's section, found by the
   grid-aligned study): the corners of its rim are met by no crossing, as
   every grid line through them lies in one of its faces, so both flow
   sides took them for their own (the inside got triangles of half the
   slab's cells, the outside whole cells) until probe_corners.  In 2-D
   and 3-D, each flow side must give the slab's exact volume and its
   complement, cell by cell. */
TEST(cut_thin_slab_rim)
{
    for (int twod = 0; twod < 2; twod++) {
        int n3[3] = {9, 9, twod ? 1 : 9};
        double lo[3] = {0, 0, 0}, hi[3] = {1, 1, twod ? 1.0 / 9 : 1}, h = 1.0 / 9, cellv = h * h * hi[2] / n3[2];
        Mesh grid;
        grid_box(&grid, n3, lo, hi, twod);
        double *pv = MEM_NEW(double, grid.ncells), vin = 0, worst = 0;
        char *odd = MEM_NEW(char, grid.ncells);
        for (int side = 0; side < 2; side++) {
            char txt[256];
            snprintf(txt, sizeof txt, "s { flow %s; shape box; min (0 %.17g %.17g); max (%.17g %.17g %.17g); }",
                     side ? "outside" : "inside", 4 * h, twod ? -1.0 : 4 * h, 0.25 * h, 6 * h, twod ? 2.0 : 6 * h);
            FixtureGeo G;
            Mesh m;
            CutStats st;
            EXPECT(fixture_geo(&G, txt) == 0, "geometry");
            if (twod) geometry_flatten(&G.g, 2, 0.5 * hi[2]);
            char why[2100];
            EXPECT(cut(&grid, &G, CUT_SNAP, &m, &st) == 0, "cut failed");
            EXPECT(check_grid(&m, why, sizeof why) == 0, "%s: %s", txt, why);
            add_parent_vol(&m, pv, odd);
            if (!side) vin = st.vol_fluid;
            mesh_free(&m);
            fixture_geo_free(&G);
        }
        for (int c = 0; c < grid.ncells; c++) worst = fmax(worst, fabs(pv[c] / cellv - 1));
        double exact = 0.25 * h * 2 * h * (twod ? hi[2] : 2 * h);
        printf("  %s: slab volume %.17g (exact %.17g), worst Cartesian cell %.2e\n", twod ? "2-D" : "3-D", vin, exact,
               worst);
        EXPECT(fabs(vin - exact) < 1e-14, "%s slab volume %.17g, exact %.17g", twod ? "2-D" : "3-D", vin, exact);
        EXPECT(worst < 1e-12, "%s: a Cartesian cell's two sides add to %.3e off", twod ? "2-D" : "3-D", worst);
        free(pv);
        free(odd);
        mesh_free(&grid);
    }
}

/* Corner classes as cut.c's cells see them: a corner on the surface
   (within 1e-9 of the cell size) takes the class of a point a little way
   towards the cell's centre, skewed as cut.c's probes are. */
static int aligned_mask(const Geometry *g, const CartGrid *cg, const int ijk[3])
{
    int mask = 0;
    for (int q = 0; q < 8; q++) {
        double p[3], y[3], h[3];
        int on = 0;
        for (int k = 0; k < 3; k++) {
            p[k] = cg->x[k][ijk[k] + ((q >> k) & 1)];
            h[k] = cg->x[k][ijk[k] + 1] - cg->x[k][ijk[k]];
        }
        int f = geometry_fluid(g, p);
        for (int d = 0; d < 27 && !on; d++) {
            for (int k = 0, dd = d; k < 3; k++, dd /= 3) y[k] = p[k] + (dd % 3 - 1) * 1e-9 * h[k];
            on = geometry_fluid(g, y) != f;
        }
        static const double w[3] = {1, 0.6180339887498949, 0.7071067811865476}; /* cut.c's probe_w */
        if (on)
            for (int k = 0; k < 3; k++) y[k] = p[k] + w[k] * 1e-5 * (cg->x[k][ijk[k]] + h[k] / 2 - p[k]);
        mask |= (on ? geometry_fluid(g, y) : f) << q;
    }
    return mask;
}

/* Cells where the two flow sides need not add up, by design: a face
   with two diagonal fluid corners (either side joins its own fluid), a
   body diagonal (tunnel), an edge crossed twice or more inside, on the
   edge itself or as the cell sees it (a feature thinner than the cell
   crossing an edge that lies in a face of another part). */
static int aligned_irregular(const Geometry *g, const Mesh *grid, int ci)
{
    const CartGrid *cg = &grid->cart;
    int ijk[3] = {ci % cg->n[0], (ci / cg->n[0]) % cg->n[1], ci / (cg->n[0] * cg->n[1])};
    int mask = aligned_mask(g, cg, ijk);
    for (int q = 0; q < 4; q++)
        if (mask == ((1 << q) | (1 << (7 - q))) || (255 & ~mask) == ((1 << q) | (1 << (7 - q)))) return 1;
    static const int fc[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    for (int s = 0; s < 6; s++) {
        const int *c = fc[s];
        int f[4];
        for (int r = 0; r < 4; r++) f[r] = (mask >> c[r]) & 1;
        if (f[0] == f[2] && f[1] == f[3] && f[0] != f[1]) return 1;
    }
    for (int q = 0; q < 8; q++)
        for (int k = 0; k < 3; k++) {
            if ((q >> k) & 1) continue;
            double a[3], b[3];
            for (int d = 0; d < 3; d++) {
                a[d] = cg->x[d][ijk[d] + ((q >> d) & 1)];
                b[d] = cg->x[d][ijk[d] + (((q | 1 << k) >> d) & 1)];
            }
            GeoCross cr[8];
            int nc = geometry_crossings(g, a, b, cr, 8), inner = 0;
            for (int i = 0; i < nc && i < 8; i++) inner += cr[i].t > 1e-6 && cr[i].t < 1 - 1e-6;
            if (inner >= 2) return 1;
            /* as the cell sees the edge: a copy moved a little towards its
               centre, less along one axis than the other so as not to run
               in a plane of the geometry (an edge in a face of the
               geometry crosses nothing itself); crossings that close on
               an end as the copy closes on the edge, a surface through the
               end, are left out */
            for (int d = 0; d < 3; d++) {
                double mid = cg->x[d][ijk[d]] + (cg->x[d][ijk[d] + 1] - cg->x[d][ijk[d]]) / 2;
                double w = d == k ? 0 : d == (k + 2) % 3 ? 0.618e-7 : 1e-7;
                a[d] += w * (mid - a[d]);
                b[d] += w * (mid - b[d]);
            }
            nc = geometry_crossings(g, a, b, cr, 8), inner = 0;
            for (int i = 0; i < nc && i < 8; i++) inner += cr[i].t > 1e-3 && cr[i].t < 1 - 1e-3;
            if (inner >= 2) return 1;
        }
    return 0;
}

/* Index of x among grid coordinates g[1..n-1] (an inner grid plane), or -1. */
static int inner_plane(const double *g, int n, double x)
{
    for (int i = 1; i < n; i++)
        if (x == g[i]) return i;
    return -1;
}

/* Adds, for each inner grid face, the area of the faces of m that lie in
   it: a face between two cells whole, a wall half (acc[3 * (cell below
   the face) + axis]).  Over the two flow sides every grid face then sums
   to its area: the part both cells see fluid is shared on one side, the
   part both see solid on the other, and the rest is a wall of one cell on
   each side, so a wall where the cells should share the face (or a face
   they should not share) shows. */
static void add_plane_faces(Mesh *m, double *acc)
{
    const CartGrid *g = &m->cart;
    if (!m->face_area) mesh_geometry(m);
    for (int f = 0; f < m->nfaces; f++) {
        int wall = f >= m->ninternal;
        if (wall && mesh_face_patch(m, f) < 6) continue;
        int o = m->face_off[f], n = m->face_off[f + 1] - o;
        for (int a = 0; a < 3; a++) {
            double x = m->points[3 * (size_t)m->face_idx[o] + a];
            int i = inner_plane(g->x[a], g->n[a], x), same = i >= 0;
            for (int q = 1; q < n && same; q++) same = m->points[3 * (size_t)m->face_idx[o + q] + a] == x;
            if (!same) continue;
            double c[3] = {0, 0, 0};
            int ijk[3];
            for (int q = 0; q < n; q++)
                for (int d = 0; d < 3; d++) c[d] += m->points[3 * (size_t)m->face_idx[o + q] + d] / n;
            for (int d = 0; d < 3; d++) {
                ijk[d] = 0;
                while (ijk[d] + 1 < g->n[d] && g->x[d][ijk[d] + 1] <= c[d]) ijk[d]++;
            }
            ijk[a] = i - 1;
            const double *S = m->face_area + 3 * (size_t)f;
            acc[3 * (ijk[0] + g->n[0] * (ijk[1] + g->n[1] * ijk[2])) + a] +=
                sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]) * (wall ? 0.5 : 1);
        }
    }
}

/* The grid-aligned study: ncase random CSG trees of depth `depth` of
   grid-aligned primitives (rand_aligned_shape), each cut with the flow on
   both sides on a 6^3 ... 12^3 grid (every fourth 2-D); it stops after
   maxfail failures (a grid that fails a check, or a regular cell whose
   two sides do not add up to it to 1e-12). */
typedef struct AlignedStudy {
    int ncase, depth, maxfail;                 /* in */
    int it, nfail, nreg, nirr, nclean;         /* out: cases run, failures, cells */
    double worst, worst_total, worst_face;
} AlignedStudy;

static void aligned_study(AlignedStudy *A)
{
    char shape[7000];
    A->nfail = A->nreg = A->nirr = A->nclean = 0;
    A->worst = A->worst_total = A->worst_face = 0;
    for (A->it = 0; A->it < A->ncase && A->nfail < A->maxfail; A->it++) {
        int it = A->it, nn = 6 + it % 7, twod = it % 4 == 3, n3[3] = {nn, nn, twod ? 1 : nn};
        double lo[3] = {0, 0, 0}, hi[3] = {1, 1, twod ? 1.0 / nn : 1};
        Mesh grid;
        grid_box(&grid, n3, lo, hi, twod);
        rand_aligned_shape(shape, sizeof shape, A->depth, 1.0 / nn);
        TwoSides S;
        A->nfail += two_sides(&S, &grid, shape, twod, nn, it);
        if (S.made[0] && S.made[1] && (S.ok[0] || S.empty[0]) && (S.ok[1] || S.empty[1])) {
            int nc = grid.ncells, irr = 0;
            double *pv = MEM_NEW(double, nc), h3 = hi[2] / ((double)nn * nn * n3[2]), total = 0;
            double *acc = MEM_NEW(double, 3 * nc);
            char *odd = MEM_NEW(char, nc), *bad = MEM_NEW(char, nc);
            for (int side = 0; side < 2; side++)
                if (S.ok[side]) {
                    add_parent_vol(&S.m[side], pv, odd);
                    add_plane_faces(&S.m[side], acc);
                }
            for (int c = 0; c < nc; c++) {
                total += pv[c];
                bad[c] = odd[c] || aligned_irregular(&S.G[0].g, &grid, c);
                if (bad[c]) {
                    A->nirr++, irr++;
                    continue;
                }
                A->nreg++;
                double err = fabs(pv[c] - h3) / h3;
                A->worst = fmax(A->worst, err);
                if (err > 1e-12 && A->nfail++ < A->maxfail)
                    printf("case %d: cell %d: volumes add to %.17g of the cell\n  %s\n", it, c, pv[c] / h3, shape);
            }
            for (int c = 0; c < nc; c++)
                for (int a = 0, st = 1; a < 3; a++, st *= nn) {
                    if ((c / st) % nn + 1 >= n3[a] || bad[c] || bad[c + st]) continue;
                    double fa = a == 2 ? 1.0 / (nn * nn) : hi[2] / n3[2] / nn, err = fabs(acc[3 * c + a] - fa) / fa;
                    A->worst_face = fmax(A->worst_face, err);
                    if (err > 1e-12 && A->nfail++ < A->maxfail)
                        printf("case %d: face %d of cell %d: shared faces and walls add to %.17g of it\n  %s\n", it,
                               a, c, acc[3 * c + a] / fa, shape);
                }
            free(acc);
            free(bad);
            if (!irr) {
                A->nclean++;
                A->worst_total = fmax(A->worst_total, fabs(total / (hi[2]) - 1));
            }
            free(pv);
            free(odd);
        }
        two_sides_free(&S);
        mesh_free(&grid);
    }
    printf("  %d grid-aligned cases of %d (kinds 0x%x, CSG depth %d, stops at %d failures): %d regular cells add up "
           "(worst %.2e), and the grid faces between them (worst %.2e), %d irregular by design skipped; %d cases "
           "without irregular cells: inside + outside = box to %.2e\n",
           A->it, A->ncase, aligned_kinds, A->depth, A->maxfail, A->nreg, A->worst, A->worst_face, A->nirr,
           A->nclean, A->worst_total);
    EXPECT(A->nfail == 0, "%d failures in the first %d cases", A->nfail, A->it);
    EXPECT(A->nreg > A->it * 100, "only %d regular cells checked", A->nreg);
    EXPECT(A->worst_total < 1e-12, "inside + outside off the box by %.2e", A->worst_total);
}

/* Inside + outside = the box, for geometries placed on grid planes, grid
   lines and grid vertices on purpose (rand_aligned_shape): every
   Cartesian cell that is not irregular by design gets its whole volume
   from the two flow sides, and the grids are sound.  make test draws
   single boxes, spheres, cylinders, half-spaces, cones and prisms (faces
   on grid planes, circles tangent to grid lines, spheres and planes
   through grid vertices, apices and prism vertices on grid vertices);
   make validate (tests/validation/cutAligned) runs 1000 CSG trees of
   depth 1 and 2 through the same test (CUT_ALIGNED_CASES, _KINDS, _DEPTH,
   _MAXFAIL). */
TEST(cut_random_aligned)
{
    const char *env = getenv("CUT_ALIGNED_CASES");
    const char *envf = getenv("CUT_ALIGNED_MAXFAIL"), *envk = getenv("CUT_ALIGNED_KINDS");
    const char *envd = getenv("CUT_ALIGNED_DEPTH");
    aligned_kinds = envk ? (int)strtol(envk, NULL, 0) : 0x3f;
    AlignedStudy A = {env ? atoi(env) : 300, envd ? atoi(envd) : 0, envf ? atoi(envf) : 3, 0, 0, 0, 0, 0, 0, 0, 0};
    aligned_study(&A);
}

/* The same for CSG trees of depth 1 (unions, intersections, differences
   of two aligned primitives, their parts meeting on grid planes, lines
   and vertices), 300 cases from a fixed seed: each cell sees the points
   of its own edges from its own side (issue 9's last part). */
TEST(cut_random_aligned_csg)
{
    uint64_t saved = rng_state;
    rng_state = 88172645463325252ull;
    aligned_kinds = 0x3f;
    AlignedStudy A = {300, 1, 3, 0, 0, 0, 0, 0, 0, 0, 0};
    aligned_study(&A);
    rng_state = saved;
}

/* One grid-aligned CSG case (found by the studies) cut with the flow on
   both sides on an nn^3 grid: both grids pass the checks, every
   Cartesian cell that is not irregular by design, cell `must` among them
   (the one that failed), gets its whole volume from the two sides to
   1e-12, and every grid face between two such cells its area
   (add_plane_faces). */
static void csg_case(const char *name, int nn, const char *shape, int must)
{
    int n3[3] = {nn, nn, nn};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, h3 = 1.0 / ((double)nn * nn * nn), worst = 0;
    Mesh grid;
    grid_box(&grid, n3, lo, hi, 0);
    TwoSides S;
    int nfail = two_sides(&S, &grid, shape, 0, nn, -1), nreg = 0, checked = must < 0;
    EXPECT(nfail == 0 && S.ok[0] && S.ok[1], "%s: a grid failed", name);
    double worst_face = 0;
    if (S.ok[0] && S.ok[1]) {
        double *pv = MEM_NEW(double, grid.ncells), *acc = MEM_NEW(double, 3 * grid.ncells), h2 = 1.0 / (nn * nn);
        char *odd = MEM_NEW(char, grid.ncells), *irr = MEM_NEW(char, grid.ncells);
        for (int side = 0; side < 2; side++) {
            add_parent_vol(&S.m[side], pv, odd);
            add_plane_faces(&S.m[side], acc);
        }
        for (int c = 0; c < grid.ncells; c++) {
            irr[c] = odd[c] || aligned_irregular(&S.G[0].g, &grid, c);
            if (irr[c]) continue;
            nreg++;
            checked |= c == must;
            worst = fmax(worst, fabs(pv[c] - h3) / h3);
        }
        /* inner grid faces between two regular cells */
        for (int c = 0; c < grid.ncells; c++)
            for (int a = 0, st = 1; a < 3; a++, st *= nn)
                if ((c / st) % nn + 1 < nn && !irr[c] && !irr[c + st])
                    worst_face = fmax(worst_face, fabs(acc[3 * c + a] - h2) / h2);
        free(pv);
        free(acc);
        free(odd);
        free(irr);
    }
    printf("  %s: %d regular cells add up to %.2e, their faces to %.2e\n", name, nreg, worst, worst_face);
    EXPECT(worst <= 1e-12, "%s: a Cartesian cell's two sides add to %.3e off", name, worst);
    EXPECT(worst_face <= 1e-12, "%s: a grid face's shared faces and walls add to %.3e off", name, worst_face);
    EXPECT(checked, "%s: cell %d is not checked", name, must);
    two_sides_free(&S);
    mesh_free(&grid);
}

/* A cell that sees both ends of a grid edge solid while the edge's point
   sits on them, and so sees the edge's point as a side of its polygon on
   a face that other cells cut: sides along a whole edge take its point,
   and a polygon on one side of its face is dropped (the cut left wall
   triangles of zero area, "face points into the cell"). */
TEST(cut_csg_zero_area_walls)
{
    csg_case("half-space and prism", 9,
             "shape union; op0 { shape halfSpace; point (0.22222222222222221 0.1111111111111111 "
             "0.1111111111111111); normal (0 1 -1); } op1 { shape polygon; axis z; points ((0.22222222222222221 1) "
             "(0.77777777777777768 0.1111111111111111) (0.1111111111111111 0.44444444444444442)); min "
             "(0.55555555555555558 0.55555555555555558 0.55555555555555558); max (0.88888888888888884 "
             "0.66666666666666663 0.77777777777777768); }",
             -1);
}

/* A cone's base on a grid plane with its rim through a grid vertex, its
   side running along a cell's diagonal, a cylinder crossing the base:
   copies of the edge moved into the cell meet the cone's side next to
   the vertex, a crossing that closes on the vertex as the copies close
   on the edge; it belongs to the vertex, and the edge's point is the
   cylinder's crossing (both flow sides took the edge whole). */
TEST(cut_csg_crossing_at_end)
{
    csg_case("cone minus cylinder", 6,
             "shape difference; op0 { shape cone; point1 (0.16666666666666666 0.33333333333333331 "
             "0.33333333333333331); point2 (0.16666666666666666 0.33333333333333331 0.66666666666666663); radius1 "
             "0.47140452079103168; radius2 0; } op1 { shape cylinder; point1 (0.16666666666666666 0.16666666666666666 "
             "0.5); point2 (1 0.16666666666666666 0.5); radius 0.44095855184409843; }",
             92);
}

/* A half-space whose plane holds a grid edge and the diagonal of the cell
   beside it, a sphere tangent to the edge's end: copies of the edge moved
   along the cell's diagonal stay in the plane and see nothing, so they
   move less along one axis than along the other; and a copy of one class
   throughout puts the point on the end the cell sees otherwise. */
TEST(cut_csg_copy_in_plane)
{
    csg_case("cylinder and sphere minus half-space", 7,
             "shape difference; op0 { shape intersection; op0 { shape cylinder; point1 (0.5714285714285714 "
             "0.2857142857142857 0); point2 (0.5714285714285714 0.2857142857142857 0.5714285714285714); radius "
             "0.2857142857142857; } op1 { shape sphere; centre (0.71428571428571419 0.2857142857142857 "
             "0.5714285714285714); radius 0.2857142857142857; } } op1 { shape halfSpace; point (0.14285714285714285 "
             "0.2857142857142857 0.8571428571428571); normal (1 0 1); }",
             157);
}

/* A prism's corner on a grid vertex that every grid line through it
   meets along the prism's faces: solid for both flow sides, it was found
   on the surface by one of them only (by snapping its fluid neighbour);
   the probes now start from the ends of every mixed edge. */
TEST(cut_csg_corner_found_by_both)
{
    csg_case("sphere and prism", 11,
             "shape union; op0 { shape sphere; centre (0.54545454545454541 0.63636363636363635 0.18181818181818182); "
             "radius 0.22268088570756164; } op1 { shape polygon; axis x; points ((0.36363636363636365 "
             "0.18181818181818182) (0.90909090909090917 0.27272727272727271) (0.63636363636363635 "
             "0.54545454545454541)); min (0.45454545454545459 0.45454545454545459 0.45454545454545459); max "
             "(0.54545454545454541 0.90909090909090917 0.54545454545454541); }",
             291);
}

/* A prism's side through two corners of a cell along its diagonal: the
   corner probes towards the cell's centre lay in that side and took
   their class from round-off, so the two flow sides saw a face with two
   diagonal fluid corners each; the probes are skewed. */
TEST(cut_csg_probe_in_plane)
{
    csg_case("prism minus cone", 6,
             "shape difference; op0 { shape polygon; axis y; points ((0.83333333333333326 0.16666666666666666) "
             "(0.33333333333333331 0) (1 0.66666666666666663)); min (0.33333333333333331 0.33333333333333331 "
             "0.33333333333333331); max (0.66666666666666663 0.66666666666666663 0.5); } op1 { shape cone; point1 "
             "(0.66666666666666663 0.66666666666666663 0.83333333333333326); point2 (0.66666666666666663 "
             "0.66666666666666663 0.16666666666666666); radius1 0.33333333333333331; radius2 0; }",
             84);
}

/* A cone's base on a grid plane and a sphere crossing it: an edge in the
   base needs the sphere's crossing for the cells outside the cone and
   its rim end for those inside, one point per edge gave one of them the
   other's; each cell now has its own point, and the grid faces in the
   base are split between the two cells' polygons. */
TEST(cut_csg_per_cell_points)
{
    csg_case("sphere minus cone", 8,
             "shape difference; op0 { shape sphere; centre (0.5 0.875 0.125); radius 0.5; } op1 { shape cone; "
             "point1 (0.375 0.375 0.375); point2 (0.25 0.375 0.375); radius1 0.27950849718747373; radius2 0; }",
             26);
}

/* Two cylinders, one's cap on a grid plane, the other touching that cap
   along a grid line: the vertex where they meet is met by no crossing
   and by no probe, but lies on the surface by the level function, so its
   cells see their edges from their own sides on both flow sides. */
TEST(cut_csg_touching_cap)
{
    csg_case("two cylinders", 10,
             "shape union; op0 { shape cylinder; point1 (0.20000000000000001 0.30000000000000004 "
             "0.10000000000000001); point2 (0.20000000000000001 0.70000000000000007 0.10000000000000001); radius "
             "0.17320508075688773; } op1 { shape cylinder; point1 (0.20000000000000001 0.80000000000000004 "
             "0.20000000000000001); point2 (0.60000000000000009 0.80000000000000004 0.20000000000000001); radius "
             "0.10000000000000001; }",
             -1);
}

/* A prism's end on a grid plane between two cylinders: the cells below
   and above a grid face in that plane (Cartesian cells 156 and 256 of
   the 10^3 grid) see chords that cross inside the face.  The crossing is
   a point of both polygons and of the face they share (without it the
   two cells would not share the face at all, each keeping its whole
   polygon as a wall). */
TEST(cut_csg_crossing_chords)
{
    const char *shape =
        "shape difference; op0 { shape union; op0 { shape cylinder; point1 (0.20000000000000001 0 "
        "0.10000000000000001); point2 (0.20000000000000001 0.60000000000000009 0.10000000000000001); radius 0.5; "
        "} op1 { shape cylinder; point1 (0.70000000000000007 0.60000000000000009 0.20000000000000001); point2 "
        "(0.70000000000000007 0.60000000000000009 0.70000000000000007); radius 0.30000000000000004; } } op1 { "
        "shape polygon; axis x; points ((0.30000000000000004 1) (0.60000000000000009 0.10000000000000001) (0 "
        "0.70000000000000007)); min (0.60000000000000009 0.60000000000000009 0.60000000000000009); max "
        "(0.70000000000000007 1 0.70000000000000007); }";
    csg_case("cylinders minus prism", 10, shape, -1);
    Mesh grid, m;
    grid_unit(&grid, 10);
    char txt[2048];
    snprintf(txt, sizeof txt, "s { flow inside; %s }", shape);
    FixtureGeo G;
    CutStats st;
    EXPECT(fixture_geo(&G, txt) == 0, "geometry");
    EXPECT(cut(&grid, &G, CUT_SNAP, &m, &st) == 0, "cut failed");
    int shared = 0, crossing = 0;
    for (int f = 0; f < m.ninternal; f++) {
        int lo = m.cell_parent[m.owner[f]], hi = m.cell_parent[m.neighbour[f]];
        if (!((lo == 156 && hi == 256) || (lo == 256 && hi == 156))) continue;
        shared++;
        for (int j = m.face_off[f]; j < m.face_off[f + 1]; j++) {
            const double *x = m.points + 3 * (size_t)m.face_idx[j];
            crossing |= fabs(x[0] * 10 - round(x[0] * 10)) > 1e-9 && fabs(x[1] * 10 - round(x[1] * 10)) > 1e-9;
        }
    }
    printf("  cells 156 and 256 share %d face(s), %s the chords' crossing\n", shared, crossing ? "with" : "without");
    EXPECT(shared == 1 && crossing, "cells 156 and 256 share %d faces, crossing %d", shared, crossing);
    mesh_free(&m);
    fixture_geo_free(&G);
    mesh_free(&grid);
}

/* ---- method staircase (cut_staircase.c) ---- */

/* The staircase grid of text on grid: each cell is a kept Cartesian
   cell's box, the kept cells are exactly those whose centre the geometry
   calls fluid, every wall face lies between a kept and a dropped cell
   with its own axis-aligned normal as boundary normal, and the contract
   has roles whole and outside only. */
static void staircase_case(const Mesh *grid, const char *text, int *nkept)
{
    FixtureGeo G;
    EXPECT(fixture_geo(&G, text) == 0, "geometry");
    if (grid->cart.n[2] == 1) geometry_flatten(&G.g, 2, 0.5 * (grid->cart.x[2][0] + grid->cart.x[2][1]));
    CutOpts o;
    cut_opts_default(&o);
    o.method = CUT_METHOD_STAIRCASE;
    Mesh m;
    CutStats st;
    Err e;
    int rc = cut_mesh(grid, &G.g, &o, &m, &st, &e);
    EXPECT(rc == 0, "cut_mesh: %s", rc ? e.msg : "");
    if (rc) {
        fixture_geo_free(&G);
        return;
    }
    char why[256];
    EXPECT(check_grid(&m, why, sizeof why) == 0, "%s", why);
    if (!m.face_area) mesh_geometry(&m);
    EXPECT(mesh_check_cartesian(&m, CARTCELLS_TOL, &e) == 0, "contract: %s", e.msg);
    const CartGrid *cg = &m.cart;
    int nc = cg->n[0] * cg->n[1] * cg->n[2], kept = 0;
    char *in = mem_alloc((size_t)nc);
    for (int K = 0; K < nc; K++) {
        int i = K % cg->n[0], j = (K / cg->n[0]) % cg->n[1], k = K / (cg->n[0] * cg->n[1]);
        double x[3] = {(cg->x[0][i] + cg->x[0][i + 1]) / 2, (cg->x[1][j] + cg->x[1][j + 1]) / 2,
                       (cg->x[2][k] + cg->x[2][k + 1]) / 2};
        in[K] = geometry_fluid(&G.g, x) != 0;
        kept += in[K];
        int role = m.cartcells.role[K];
        EXPECT(role == (in[K] ? CART_WHOLE : CART_OUTSIDE), "Cartesian cell %d: role %d, centre %s", K, role,
               in[K] ? "inside" : "outside");
    }
    EXPECT(m.ncells == kept && st.ncells == kept && st.ncut == 0, "%d cells, %d centres inside", m.ncells, kept);
    double vsum = 0;
    for (int c = 0; c < m.ncells; c++) vsum += m.cell_vol[c];
    NEAR(st.vol_fluid, vsum, 1e-12 * vsum);
    int nwall = 0, wall_patch = m.npatches - 1;
    for (int f = m.patches[wall_patch].start; f < m.patches[wall_patch].start + m.patches[wall_patch].size; f++) {
        const double *S = m.face_area + 3 * f, *bn = m.boundary_normal + 3 * (f - m.ninternal);
        double a = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
        int ax = fabs(S[0]) > 0.5 * a ? 0 : fabs(S[1]) > 0.5 * a ? 1 : 2;
        EXPECT(fabs(fabs(S[ax]) - a) <= 1e-12 * a, "wall face %d is not axis-aligned", f);
        for (int k = 0; k < 3; k++) NEAR(bn[k], S[k] / a, 1e-15);
        /* the Cartesian cell across the face is a dropped one */
        int K = m.cell_parent[m.owner[f]], step = ax == 0 ? 1 : ax == 1 ? cg->n[0] : cg->n[0] * cg->n[1];
        int across = K + (S[ax] > 0 ? step : -step);
        EXPECT(across >= 0 && across < nc && !in[across], "wall face %d: the cell across is kept", f);
        nwall++;
    }
    EXPECT(nwall == st.nboundary && nwall > 0, "%d wall faces, %d reported", nwall, st.nboundary);
    *nkept = kept;
    free(in);
    mesh_free(&m);
    fixture_geo_free(&G);
}

TEST(cut_staircase_disc_and_sphere)
{
    Mesh g2, g3;
    fixture_block(&g2, (const int[3]){24, 24, 1}, (const double[3]){-0.6, -0.6, 0}, (const double[3]){0.6, 0.6, 0.05}, 2);
    fixture_block(&g3, (const int[3]){12, 12, 12}, (const double[3]){-0.6, -0.6, -0.6}, (const double[3]){0.6, 0.6, 0.6},
                  -1);
    int k2 = 0, k3 = 0;
    staircase_case(&g2, "wall { flow inside; shape cylinder; point1 (0 0 -1); point2 (0 0 1); radius 0.5; }", &k2);
    staircase_case(&g3, "wall { flow inside; shape sphere; centre (0 0 0); radius 0.5; }", &k3);
    /* lattice counts: centres (a, b) h/2 with a, b odd, inside r = 0.5:
       a^2 + b^2 < 400 at h = 0.05 (2-D); a^2 + b^2 + c^2 < 100 at h = 0.1 */
    int c2 = 0, c3 = 0;
    for (int a = -23; a <= 23; a += 2)
        for (int b = -23; b <= 23; b += 2) {
            c2 += a * a + b * b < 400;
            for (int c = -11; c <= 11 && abs(a) <= 11 && abs(b) <= 11; c += 2) c3 += a * a + b * b + c * c < 100;
        }
    EXPECT(k2 == c2 && k3 == c3, "kept %d and %d cells, lattice counts %d and %d", k2, k3, c2, c3);
    printf("  disc: %d whole cells; sphere: %d\n", k2, k3);
    mesh_free(&g2);
    mesh_free(&g3);
}

TEST(cut_staircase_opts)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/kiesel_test_cutCellsDict.%ld", (long)getpid());
    FILE *f = fopen(path, "w");
    fprintf(f, "method staircase;\n");
    fclose(f);
    CutOpts o;
    Err e;
    EXPECT(cut_read_opts(path, &o, &e) == 0 && o.method == CUT_METHOD_STAIRCASE, "method staircase not read");
    f = fopen(path, "w");
    fprintf(f, "\nmethod steps;\n");
    fclose(f);
    EXPECT(cut_read_opts(path, &o, &e) != 0, "method steps accepted");
    CONTAINS(e.msg, ":2:");
    CONTAINS(e.msg, "staircase");
    cut_opts_default(&o);
    EXPECT(o.method == CUT_METHOD_CUT, "default method is not cut");
    remove(path);
}

int main(void)
{
    RUN(cut_halfspace_exact);
    RUN(cut_rotated_box_exact);
    RUN(cut_on_grid_planes);
    RUN(cut_sphere_convergence);
    RUN(cut_disc_convergence);
    RUN(cut_sphere_complement);
    RUN(cut_sphere_shifted);
    RUN(cut_degenerate);
    RUN(cut_tunnel);
    RUN(cut_patches);
    RUN(cut_random);
    RUN(cut_cap_on_grid_plane);
    RUN(cut_thin_slab_rim);
    RUN(cut_random_aligned);
    RUN(cut_random_aligned_csg);
    RUN(cut_csg_zero_area_walls);
    RUN(cut_csg_crossing_at_end);
    RUN(cut_csg_copy_in_plane);
    RUN(cut_csg_corner_found_by_both);
    RUN(cut_csg_probe_in_plane);
    RUN(cut_csg_per_cell_points);
    RUN(cut_csg_touching_cap);
    RUN(cut_csg_crossing_chords);
    RUN(cut_staircase_disc_and_sphere);
    RUN(cut_staircase_opts);
    return test_summary();
}
