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
#include "dict.h"
#include "geometry.h"
#include "mem.h"
#include "mesh.h"

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

/* A geometry from the body of geometryDict's surfaces entry, and the
   dictionary it keeps pointers into. */
typedef struct FixtureGeo {
    Dict *d;
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
    geometry_init(&G->g);
    G->d = dict_parse(buf, strlen(buf), "geometryDict", &e);
    free(buf);
    if (!G->d) {
        printf("dict_parse: %s\n", e.msg);
        return -1;
    }
    if (geometry_parse(&G->g, G->d, "geometryDict", ".", &e)) {
        printf("geometry_parse: %s\n", e.msg);
        dict_free(G->d);
        return -1;
    }
    return 0;
}

static inline void fixture_geo_free(FixtureGeo *G)
{
    geometry_free(&G->g);
    dict_free(G->d);
}

#endif
