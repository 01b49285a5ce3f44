/*
** bench_voronoi.c: times the boundary-conforming Voronoi grid (vgrid.h) on
** unit-square and unit-cube block grids built in memory, on one core:
**   disc     2-D, N x N x 1, flow outside a disc of radius 0.2 (a cylinder
**            along z) at the centre;
**   sphere   3-D, N^3, flow outside a sphere of radius 0.3 at the centre;
**   csg      3-D, N^3, flow around the flanged bush of bench_cut.c.
**
**   bench_voronoi <geometry> <N> [<geometry> <N> ...]
**
** Output, per case, lines
**   "VGRID <geometry> <N> <cells> <wall s> <cells/s> <cpu s>"   vgrid_mesh
**   "SEEDS <geometry> <N> <cells> <wall s> <cells/s> <cpu s>"   seeds_make
**   "VORONOI <geometry> <N> <cells> <wall s> <cells/s> <cpu s>" voronoi_mesh
**   "CHECK <geometry> <N> <cells> <points> <faces> <fluid volume>"
** where cells/s is Voronoi cells made per second of wall time.  The fluid
** volume is checked against the exact one (a fast wrong grid fails), and
** seeds + voronoi_mesh must give the grid vgrid_mesh gave.
*/
#include "block.h"
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "mesh.h"
#include "seeds.h"
#include "vgrid.h"
#include "voronoi.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double now(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void die(const char *what, const Err *e)
{
    fprintf(stderr, "bench_voronoi: %s: %s\n", what, e->msg);
    exit(1);
}

/* The unit cube (2-D: the unit square, one cell h thick about z = 0),
   each side its own patch so that patch s is box side s. */
static void grid(Mesh *m, int n, int flat)
{
    double *x[3];
    int nn[3] = {n, n, flat ? 1 : n};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc((size_t)(nn[k] + 1) * sizeof(double));
        for (int i = 0; i <= nn[k]; i++) x[k][i] = (double)i / n;
    }
    if (flat) x[2][0] = -0.5 / n, x[2][1] = 0.5 / n;
    BlockSide side[BLOCK_NSIDES];
    for (int s = 0; s < BLOCK_NSIDES; s++)
        side[s] = (BlockSide){block_side_names[s], flat && s >= BLOCK_ZMIN ? "empty" : "wall", NULL};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, nn, side, NULL, "bench", NULL, &e)) die("block_mesh", &e);
    for (int k = 0; k < 3; k++) free(x[k]);
}

static const char *part =
    "part { shape difference;\n"
    " body { shape union;\n"
    "  plate { shape box; min (0.15 0.25 0.2); max (0.85 0.75 0.35); }\n"
    "  boss { shape cylinder; point1 (0.5 0.5 0.2); point2 (0.5 0.5 0.75); radius 0.18; } }\n"
    " bore { shape cylinder; point1 (0.5 0.5 0.1); point2 (0.5 0.5 0.9); radius 0.09; }\n"
    " bolt1 { shape cylinder; point1 (0.25 0.5 0.1); point2 (0.25 0.5 0.5); radius 0.04; }\n"
    " bolt2 { shape cylinder; point1 (0.75 0.5 0.1); point2 (0.75 0.5 0.5); radius 0.04; } }\n";

static void report(const char *kind, const char *name, int n, int cells, double w, double cpu)
{
    printf("%s %s %d %d %.3f %.3g %.3f\n", kind, name, n, cells, w, w > 0 ? cells / w : 0, cpu);
    fflush(stdout);
}

/* seeds_make + voronoi_mesh as vgrid_mesh calls them (patches: the six
   sides, then the surface), timed apart. */
static void parts(const char *name, int n, const Mesh *m, const Geometry *g0, const SeedOpts *o, const Mesh *ref)
{
    Geometry g = *g0;
    int flat = mesh_empty_axis(m);
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) lo[a] = m->cart.x[a][0], hi[a] = m->cart.x[a][m->cart.n[a]];
    if (flat >= 0) g.flat_axis = flat, g.flat_coord = 0.5 * (lo[flat] + hi[flat]);
    Err e;
    Seeds s;
    double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (seeds_make(m, &g, o, &s, &e)) die("seeds_make", &e);
    double w = now(CLOCK_MONOTONIC) - w0, cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    int nkeep = 0;
    for (int i = 0; i < s.n; i++) nkeep += s.interior[i];
    report("SEEDS", name, n, nkeep, w, cpu);
    int np = m->npatches + g.nsurf;
    Patch *pat = mem_calloc((size_t)np, sizeof(Patch));
    for (int p = 0; p < m->npatches; p++) pat[p] = m->patches[p];
    for (int k = 0; k < g.nsurf; k++) {
        pat[m->npatches + k].name = g.surf[k].name;
        pat[m->npatches + k].type = g.surf[k].type;
    }
    int *patch = mem_alloc(sizeof(int) * (size_t)s.n);
    for (int i = 0; i < s.n; i++) patch[i] = s.interior[i] ? 0 : m->npatches + (s.surface[i] >= 0 ? s.surface[i] : 0);
    VoronoiInput in = {s.n, s.x, s.interior, patch, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, flat, np, pat,
                       {0, 1, 2, 3, 4, 5}};
    Mesh out;
    VoronoiStats vs;
    w0 = now(CLOCK_MONOTONIC);
    c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (voronoi_mesh(&in, &out, NULL, &vs, &e)) die("voronoi_mesh", &e);
    w = now(CLOCK_MONOTONIC) - w0;
    cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    report("VORONOI", name, n, out.ncells, w, cpu);
    if (out.ncells != ref->ncells || out.npoints != ref->npoints || out.nfaces != ref->nfaces) {
        fprintf(stderr, "bench_voronoi: %s: voronoi_mesh and vgrid_mesh differ\n", name);
        exit(1);
    }
    mesh_free(&out);
    free(patch);
    free(pat);
    seeds_free(&s);
}

static void run(const char *name, const char *text, int n, int flat, double exact, double tol)
{
    Err e;
    Dict *d = dict_parse(text, strlen(text), name, &e);
    Geometry g;
    if (!d || geometry_parse(&g, d, name, ".", &e)) die(name, &e);
    Mesh m, out;
    grid(&m, n, flat);
    SeedOpts o;
    seeds_opts_default(&o);
    VGridStats st;
    double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (vgrid_mesh(&m, &g, &o, &out, &st, &e)) die(name, &e);
    double w = now(CLOCK_MONOTONIC) - w0, cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    report("VGRID", name, n, out.ncells, w, cpu);
    double thick = flat ? 1.0 / n : 1;
    printf("CHECK %s %d %d %d %d %.15g\n", name, n, out.ncells, out.npoints, out.nfaces, st.vol_total);
    if (fabs(st.vol_total - exact * thick) > tol * exact * thick) {
        fprintf(stderr, "bench_voronoi: %s: fluid volume %.12g, expected %.12g\n", name, st.vol_total, exact * thick);
        exit(1);
    }
    parts(name, n, &m, &g, &o, &out);
    mesh_free(&out);
    mesh_free(&m);
    geometry_free(&g);
    dict_free(d);
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc % 2 == 0) {
        fprintf(stderr, "usage: bench_voronoi disc|sphere|csg N [disc|sphere|csg N ...]\n");
        return 2;
    }
    char buf[4096];
    for (int k = 1; k + 1 < argc; k += 2) {
        const char *name = argv[k];
        int n = atoi(argv[k + 1]);
        if (n < 4 || n > 8192) {
            fprintf(stderr, "bench_voronoi: N must be 4..8192, found %s\n", argv[k + 1]);
            return 2;
        }
        if (!strcmp(name, "disc")) {
            run(name, "surfaces { disc { shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.2; } }", n,
                1, 1 - M_PI * 0.04, 1e-3);
        } else if (!strcmp(name, "sphere")) {
            run(name, "surfaces { ball { shape sphere; centre (0.5 0.5 0.5); radius 0.3; } }", n, 0,
                1 - 4.0 / 3 * M_PI * 0.027, 2e-3);
        } else if (!strcmp(name, "csg")) {
            snprintf(buf, sizeof buf, "surfaces { %s }", part);
            run(name, buf, n, 0, 1 - (0.0525 + M_PI * 0.008025), 5e-3);
        } else {
            fprintf(stderr, "bench_voronoi: unknown geometry '%s'\n", name);
            return 2;
        }
    }
    return 0;
}
