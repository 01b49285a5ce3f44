/*
** seeds.h: Voronoi seeds for a boundary-conforming grid (ICCM^V, spec
** granular-model.md §2.4, thesis §3.2.4, eq. 3.2-3.3).
**
** From a block grid (its Cartesian cell centres) and a Geometry:
**   1. boundary sample points p with outward unit normal n (out of the
**      flow, into the solid) spread evenly over every surface, spacing
**      about the local grid spacing h: a structured parametrisation for
**      primitives (shape_sample), a relaxed distribution on triangulated
**      surfaces; points of a primitive's surface that are not on the flow
**      domain's boundary (inside another CSG operand) are dropped;
**   2. for each p an exterior seed p + (h/2) n and interior seeds
**      p - (2i+1)(h/2) n, i = 0..layers (eq. 3.2-3.3);
**   3. corners and edges (where the normal jumps) are reproduced by shared
**      seeds as in thesis Fig. 3.16: the sample points of the faces
**      meeting there share their interior (convex corner) or exterior
**      (concave corner) seed;
**   4. seeds closer than min_spacing a to an earlier seed are dropped
**      (boundary seeds first, so the boundary wins);
**   5. Cartesian cell centres are dropped [our rule, spec §2.4 GAP] when
**      closer than a to any boundary seed, outside the flow domain, or
**      between the boundary and the innermost layer (closer to the
**      surface than layers + 1 half-spacings).
** Every kept seed is at least a from every other, so every cell's volume
** is at least pi a^3 / 6 (2-D: pi a^2 / 4).
*/
#ifndef KIESEL_SEEDS_H
#define KIESEL_SEEDS_H

#include "err.h"
#include "geometry.h"
#include "mesh.h"

typedef struct SeedOpts {
    int layers;          /* b: boundary layers (default 0) */
    double spacing;      /* boundary point spacing / h (default 1) */
    double min_spacing;  /* a / h (default 0.5) */
} SeedOpts;

typedef struct Seeds {
    int n;
    double *x;           /* 3*n */
    char *interior;      /* 1: cell kept */
    int *surface;        /* exterior seeds: surface index in the Geometry
                            (the patch of faces towards them); -1 otherwise */
    int *kind;           /* SEED_CARTESIAN, SEED_BOUNDARY */
    double *normal;      /* 3*n: boundary seeds' sample normal, else 0 */
} Seeds;

enum { SEED_CARTESIAN, SEED_BOUNDARY };

void seeds_opts_default(SeedOpts *o);
/* Keywords of system/voronoiGridDict (for -help and checking). */
extern const DictKey seeds_keys[];
/* Reads the dictionary at path into o, over the defaults: fails with
   file:line on an unknown keyword or a value out of range. */
int seeds_read_opts(const char *path, SeedOpts *o, Err *e);
/* grid: a block grid (cart extras); g may have no surfaces' worth of
   fluid everywhere: without surfaces the seeds are the cell centres. */
int seeds_make(const Mesh *grid, const Geometry *g, const SeedOpts *o, Seeds *s, Err *e);
void seeds_free(Seeds *s);

#endif
