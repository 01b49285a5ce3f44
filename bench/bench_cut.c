/*
** bench_cut.c: times cut_mesh and merge_mesh on an N^3 unit-cube block
** grid built in memory, around three geometries:
**   sphere   flow outside a sphere of radius 0.3 at the centre;
**   csg      the flanged bush of doc/tools/cutCells.md (box, cylinders,
**            union and difference);
**   stl      the same part as gmsh's triangulation (the STL file of
**            tutorials/grids/stlPart, given as argument).
**
**   bench_cut <N> [stl file]
**
** Output lines "CUT <geometry> <N> <cells> <wall s> <cells/s> <cpu s>" and
** "MERGE <geometry> <N> <cells in> <wall s> <cells/s> <cpu s>".  The fluid
** volume is checked against the exact one (a fast wrong cutter fails).
*/
#include "block.h"
#include "cut.h"
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "merge.h"
#include "mesh.h"

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

static void grid(Mesh *m, int n)
{
    double *x[3];
    int nn[3] = {n, n, n};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc((size_t)(n + 1) * sizeof(double));
        for (int i = 0; i <= n; i++) x[k][i] = (double)i / n;
    }
    BlockSide side[BLOCK_NSIDES];
    for (int s = 0; s < BLOCK_NSIDES; s++) side[s] = (BlockSide){"walls", "wall", NULL};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, nn, side, NULL, "bench", NULL, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        exit(1);
    }
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

static void run(const char *name, const char *text, int n, double exact, double tol)
{
    Err e;
    Dict *d = dict_parse(text, strlen(text), name, &e);
    Geometry g;
    if (!d || geometry_parse(&g, d, name, ".", &e)) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        exit(1);
    }
    Mesh m, c, mm;
    grid(&m, n);
    CutOpts o;
    cut_opts_default(&o);
    CutStats st;
    double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (cut_mesh(&m, &g, &o, &c, &st, &e)) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        exit(1);
    }
    double w = now(CLOCK_MONOTONIC) - w0, cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    printf("CUT %s %d %d %.3f %.3g %.3f\n", name, n, st.ncart, w, st.ncart / w, cpu);
    if (fabs(st.vol_fluid - exact) > tol * exact) {
        fprintf(stderr, "%s: fluid volume %.12g, expected %.12g\n", name, st.vol_fluid, exact);
        exit(1);
    }
    MergeOpts mo;
    merge_opts_default(&mo);
    MergeStats ms;
    w0 = now(CLOCK_MONOTONIC);
    c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (merge_mesh(&c, &mo, &mm, &ms, &e)) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        exit(1);
    }
    w = now(CLOCK_MONOTONIC) - w0;
    cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    printf("MERGE %s %d %d %.3f %.3g %.3f\n", name, n, c.ncells, w, c.ncells / w, cpu);
    fflush(stdout);
    merge_stats_free(&ms);
    mesh_free(&mm);
    mesh_free(&c);
    mesh_free(&m);
    geometry_free(&g);
    dict_free(d);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_cut N [stl file]\n");
        return 2;
    }
    int n = atoi(argv[1]);
    double solid = 0.0525 + M_PI * 0.008025;
    run("sphere", "surfaces { ball { shape sphere; centre (0.5 0.5 0.5); radius 0.3; } }", n,
        1 - 4.0 / 3 * M_PI * 0.027, 1e-3);
    char buf[4096];
    snprintf(buf, sizeof buf, "surfaces { %s }", part);
    run("csg", buf, n, 1 - solid, 2e-3);
    if (argc > 2) {
        snprintf(buf, sizeof buf, "surfaces { part { shape stl; file \"%s\"; } }", argv[2]);
        run("stl", buf, n, 1 - solid, 5e-3);
    }
    return 0;
}
