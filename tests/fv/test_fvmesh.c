/*
** test_fvmesh.c: the finite-volume view of a grid (fv/fvmesh.h): unit
** normals and areas, the distances h_f and ht_f of eq. 4.62-4.63, the
** faces between whole Cartesian cells (eq. 4.61), the nodes, on a block
** grid, a cut and merged grid around a sphere, and a 2-D block grid; and
** the refusal of a grid the scheme would divide by zero on.
*/
#include "cut.h"
#include "fixture.h"
#include "fvmesh.h"
#include "merge.h"
#include "test.h"

#include <math.h>

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

int main(void)
{
    RUN(block_grid);
    RUN(two_d);
    RUN(cut_sphere);
    RUN(degenerate_face);
    return test_summary();
}
