/*
** test_fvmesh.c: the finite-volume view of a grid (fv/fvmesh.h): unit
** normals and areas, the distances h_f and ht_f of eq. 4.62-4.63, the
** faces between whole Cartesian cells (eq. 4.61), the nodes, on a block
** grid, a cut and merged grid around a sphere, and a 2-D block grid; and
** the refusal of a grid the scheme would divide by zero on; the end of
** the set-up (fvmesh_end_setup) on a periodic grid.
*/
#include "block.h"
#include "cut.h"
#include "fixture.h"
#include "fvmesh.h"
#include "mem.h"
#include "merge.h"
#include "test.h"

#include <math.h>
#include <string.h>

TEST(block_grid)
{
    Mesh m;
    int n[3] = {4, 5, 6};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    EXPECT(f.nowned == 120 && f.ncells == 120, "cells %d owned %d", f.ncells, f.nowned);
    NEAR(fvmesh_volume(&f), 6.0, 1e-13);
    int ncart = 0;
    double worst = 0;
    for (int i = 0; i < f.nfaces; i++) {
        const double *nv = f.nf + 3 * i;
        worst = fmax(worst, fabs(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2] - 1));
        /* every cell is 0.25 x 0.4 x 0.5: h_f is half the spacing along the normal */
        int a = fabs(nv[0]) > 0.5 ? 0 : fabs(nv[1]) > 0.5 ? 1 : 2;
        double half = 0.5 * (hi[a] - lo[a]) / n[a];
        worst = fmax(worst, fabs(f.h[i] - half) / half);
        worst = fmax(worst, fabs(f.ht[i] - (i < f.ninternal ? half : 0)) / half);
        ncart += f.cartesian_face[i];
    }
    EXPECT(worst < 1e-14, "normals or distances off by %.3e", worst);
    EXPECT(ncart == f.ninternal, "%d of %d internal faces Cartesian", ncart, f.ninternal);
    EXPECT(fvmesh_has_cartesian(&f) == 0, "a block grid has no cut-cell data");
    NEAR(f.hcart[0], 0.25, 1e-15);
    NEAR(f.hcart[2], 0.5, 1e-15);
    fvmesh_free(&f);
    mesh_free(&m);
}

TEST(two_d)
{
    Mesh m;
    int n[3] = {8, 8, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.125};
    fixture_block(&m, n, lo, hi, 2);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    EXPECT(f.empty_axis == 2, "empty axis %d", f.empty_axis);
    int nempty = 0;
    for (int i = 0; i < f.nfaces; i++) nempty += f.empty_face[i];
    EXPECT(nempty == 128, "%d empty faces, expected 2 x 64", nempty);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* A cut grid merged: cut and merged cells are not Cartesian; the face
   flags follow the data contract, and every h_f is positive. */
TEST(cut_sphere)
{
    Mesh grid, merged;
    int n[3] = {12, 12, 12};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, vol_fluid;
    fixture_block(&grid, n, lo, hi, -1);
    fixture_cut(&merged, &grid, "s { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", 1, &vol_fluid);
    Err e;
    FvMesh f;
    EXPECT(fvmesh_init(&f, &merged, &e) == 0, "%s", e.msg);
    EXPECT(fvmesh_has_cartesian(&f), "the merged grid carries its cut-cell data");
    const CartCells *cc = &merged.cartcells;
    int bad = 0, ncart = 0;
    for (int i = 0; i < f.ninternal; i++) {
        int c[2] = {merged.owner[i], merged.neighbour[i]}, whole = 1;
        for (int s = 0; s < 2; s++) {
            int a = cc->parent_off[c[s]], b = cc->parent_off[c[s] + 1];
            whole &= b - a == 1 && cc->role[cc->parent[a]] == CART_WHOLE;
        }
        bad += whole != f.cartesian_face[i];
        ncart += f.cartesian_face[i];
    }
    double hmin = INFINITY;
    for (int i = 0; i < f.nfaces; i++) hmin = fmin(hmin, f.h[i]);
    printf("  merged sphere grid: %d cells, %d of %d internal faces between whole cells, smallest h_f %.3g\n",
           f.ncells, ncart, f.ninternal, hmin);
    EXPECT(bad == 0, "%d faces flagged against the contract", bad);
    EXPECT(ncart > 0 && ncart < f.ninternal, "%d Cartesian faces", ncart);
    EXPECT(hmin > 0, "h_f %.3g", hmin);
    NEAR(fvmesh_volume(&f), vol_fluid, 1e-13);
    fvmesh_free(&f);
    mesh_free(&merged);
    mesh_free(&grid);
}

/* A face of zero area cannot carry a flux: refused, naming it. */
TEST(degenerate_face)
{
    Mesh m;
    int n[3] = {2, 1, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&m, n, lo, hi, -1);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    for (int k = 0; k < 3; k++) m.face_area[k] = 0;
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) != 0, "a zero-area face accepted");
    EXPECT(strstr(e.msg, "face 0 has no area") != NULL, "message: %s", e.msg);
    mesh_free(&m);
}

/* fvmesh_end_setup frees the set-up's geometry and keeps what the steps
   read: across a cyclic side the cell and its moved node are the same,
   to the bit, as before; the freed pointers are NULL; the slots number
   the faces that are not empty. */
TEST(end_setup)
{
    double *x[3];
    int n[3] = {6, 4, 1};
    double lo[3] = {0, 0, -0.1}, hi[3] = {1.2, 0.8, 0.1};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = lo[k] + (hi[k] - lo[k]) * i / n[k];
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"}, {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},     {"fb", "empty", NULL},          {"fb", "empty", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    for (int k = 0; k < 3; k++) free(x[k]);
    FvMesh f;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    double *before = mem_alloc(sizeof(double) * 4 * (size_t)f.nfaces), T[3];
    for (int i = 0; i < f.nfaces; i++) before[4 * i] = fvmesh_across(&f, i, before + 4 * i + 1);
    int ncyc = 0, bad = 0, nslots = 0;
    fvmesh_end_setup(&f);
    for (int i = 0; i < f.nfaces; i++) {
        double y[3] = {before[4 * i + 1], before[4 * i + 2], before[4 * i + 3]};
        int c = fvmesh_across(&f, i, y);
        bad += c != before[4 * i] || memcmp(y, before + 4 * i + 1, sizeof y) != 0;
        if (i >= f.ninternal && f.cyc_face[i - f.ninternal] >= 0) {
            ncyc++;
            fvmesh_cyclic_shift(&f, i, T);
            bad += fabs(fabs(T[0]) - 1.2) > 1e-15 || fabs(T[1]) > 1e-15 || fabs(T[2]) > 1e-15;
        }
    }
    for (int b = 0; b < f.nboundary; b++) {
        int want = f.empty_face[f.ninternal + b] ? -1 : nslots++;
        bad += f.bslot[b] != want;
    }
    EXPECT(ncyc == 8 && bad == 0 && nslots == f.nslots && nslots == 8 + 12, "%d cyclic faces, %d differ", ncyc, bad);
    EXPECT(!f.nf && !f.h && !f.ht && !f.cartesian_face && !m.face_centre && !m.cell_off && !m.cell_faces &&
               m.face_area && m.cell_vol && f.mag_sf && f.node,
           "what the set-up alone reads is not freed, or the steps' data is");
    free(before);
    fvmesh_free(&f);
    mesh_free(&m);
}

int main(void)
{
    RUN(block_grid);
    RUN(two_d);
    RUN(cut_sphere);
    RUN(degenerate_face);
    RUN(end_setup);
    return test_summary();
}
