/*
** fixture.h: the small rectilinear meshes unit tests build in memory.
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

#include "block.h"
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

#endif
