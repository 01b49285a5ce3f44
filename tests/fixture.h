/*
** fixture.h: the small rectilinear meshes and geometries unit tests
** build in memory.
**
** fixture_mesh turns per-axis point coordinates into a Mesh with every
** side a plain patch, its cell-face lists and its geometry, through the
** same block_mesh the blockGrid tool uses; a failure ends the test
** program (tests/run counts that as a failure).
*/
#ifndef KIESEL_FIXTURE_H
#define KIESEL_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>

#include <string.h>

#include "block.h"
#include "cut.h"
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "merge.h"
#include "mesh.h"
#include "vgrid.h"

static inline void fixture_mesh(Mesh *m, double *const x[3], const int n[3])
{
    BlockSide side[BLOCK_NSIDES];
    for (int s = 0; s < BLOCK_NSIDES; s++) side[s] = (BlockSide){block_side_names[s], "patch", NULL};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
    mesh_cell_faces(m);
    mesh_geometry(m);
}

/* A uniform block grid of n cells per axis on lo..hi; flat >= 0 makes
   the two sides normal to that axis empty (2-D, n[flat] = 1).  Only the
   mesh: no cell-face lists or geometry. */
static inline void fixture_block(Mesh *m, const int n[3], const double lo[3], const double hi[3], int flat)
{
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = i == n[k] ? hi[k] : lo[k] + (hi[k] - lo[k]) * i / n[k];
    }
    BlockSide side[BLOCK_NSIDES];
    for (int s = 0; s < BLOCK_NSIDES; s++)
        side[s] = (BlockSide){block_side_names[s], s / 2 == flat ? "empty" : "patch", NULL};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* A geometry from the whole text of a geometryDict ("surfaces { ... }");
   returns -1 with the message in e on a bad text. */
static inline int fixture_geometry(Geometry *g, const char *text, Err *e)
{
    geometry_init(g);
    Dict *d = dict_parse(text, strlen(text), "geometryDict", e);
    if (!d) return -1;
    int rc = geometry_parse(g, d, "geometryDict", ".", e);
    dict_free(d);
    return rc;
}

/* A geometry from the body of geometryDict's surfaces entry. */
typedef struct FixtureGeo {
    Geometry g;
} FixtureGeo;

/* Parses "surfaces { <text> }"; prints the message and returns -1 on a
   bad text. */
static inline int fixture_geo(FixtureGeo *G, const char *text)
{
    size_t n = strlen(text) + 32;
    char *buf = mem_alloc(n);
    snprintf(buf, n, "surfaces\n{\n%s\n}\n", text);
    Err e;
    int rc = fixture_geometry(&G->g, buf, &e);
    free(buf);
    if (rc) printf("geometry: %s\n", e.msg);
    return rc;
}

static inline void fixture_geo_free(FixtureGeo *G)
{
    geometry_free(&G->g);
}

/* grid cut by the geometry of text (fixture_geo's form) and, when merge
   is set, merged with mergeCells' defaults, into out; the cut fluid
   volume in *vol when vol is not NULL.  A failure ends the test program,
   as fixture_mesh's. */
static inline void fixture_cut(Mesh *out, const Mesh *grid, const char *text, int merge, double *vol)
{
    FixtureGeo G;
    if (fixture_geo(&G, text)) exit(1);
    Mesh cutm;
    CutStats cs;
    Err e;
    if (cut_mesh(grid, &G.g, NULL, merge ? &cutm : out, &cs, &e)) {
        printf("cut_mesh: %s\n", e.msg);
        exit(1);
    }
    if (vol) *vol = cs.vol_fluid;
    if (merge) {
        MergeOpts mo;
        MergeStats ms;
        merge_opts_default(&mo);
        if (merge_mesh(&cutm, &mo, out, &ms, &e)) {
            printf("merge_mesh: %s\n", e.msg);
            exit(1);
        }
        merge_stats_free(&ms);
        mesh_free(&cutm);
    }
    fixture_geo_free(&G);
}

/* The Voronoi grid of the grid's box and the geometry of text
   (fixture_geo's form) with voronoiGrid's default seeds, into out.  A
   failure ends the test program. */
static inline void fixture_voronoi(Mesh *out, const Mesh *grid, const char *text)
{
    FixtureGeo G;
    if (fixture_geo(&G, text)) exit(1);
    SeedOpts so;
    seeds_opts_default(&so);
    VGridStats st;
    Err e;
    if (vgrid_mesh(grid, &G.g, &so, out, &st, &e)) {
        printf("vgrid_mesh: %s\n", e.msg);
        exit(1);
    }
    fixture_geo_free(&G);
}

/* The unit square, N x N cells one cell (1/N) thick, with its cell faces
   and geometry. */
static inline void fixture_square(Mesh *m, int N)
{
    int n[3] = {N, N, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1.0 / N};
    fixture_block(m, n, lo, hi, 2);
    mesh_cell_faces(m);
    mesh_geometry(m);
}

#endif
