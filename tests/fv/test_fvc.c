/*
** test_fvc.c: explicit operators (fv/fvc.h): a uniform state in a
** uniform flow has zero net outflow in every cell of a cut and merged
** grid (closure); the net outflows sum to the boundary flux (conservation,
** internal fluxes cancel); upwinding takes the upstream state; a uniform
** pressure exerts no force; the Courant number of a uniform flow on a
** block grid is |u| dt / h; with one sound speed for all faces
** (fvc_courant_uniform) it is that of an array of them, to the bit.
*/
#include "cut.h"
#include "fixture.h"
#include "fvc.h"
#include "merge.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void sphere_grid(Mesh *out, int n)
{
    Mesh grid;
    int nn[3] = {n, n, n};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    fixture_block(&grid, nn, lo, hi, -1);
    fixture_cut(out, &grid, "s { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }", 1, NULL);
    mesh_free(&grid);
}

/* phi of a uniform velocity u. */
static double *uniform_flux(const FvMesh *f, const double u[3])
{
    double *phi = calloc((size_t)f->nfaces + 1, sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        const double *S = f->m->face_area + 3 * i;
        phi[i] = u[0] * S[0] + u[1] * S[1] + u[2] * S[2];
    }
    return phi;
}

TEST(uniform_state_uniform_flow)
{
    Mesh m;
    sphere_grid(&m, 16);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    double u[3] = {0.3, -0.7, 0.2};
    double *phi = uniform_flux(&f, u), *xc = malloc(sizeof(double) * (size_t)f.ncells),
           *xb = malloc(sizeof(double) * ((size_t)f.nboundary + 1)), *out = malloc(sizeof(double) * (size_t)f.ncells);
    for (int c = 0; c < f.ncells; c++) xc[c] = 2.5;
    for (int b = 0; b < f.nboundary; b++) xb[b] = 2.5;
    fvc_div_upwind(&f, phi, xc, xb, 1, out);
    double worst = 0;
    for (int c = 0; c < f.ncells; c++) worst = fmax(worst, fabs(out[c]) / m.cell_vol[c]);
    printf("  merged sphere grid, %d cells: largest |div(rho u)| of a uniform state %.2e\n", f.ncells, worst);
    EXPECT(worst < 1e-12, "uniform state: net outflow %.3e per volume", worst);

    /* a non-uniform state: the outflows sum to the boundary flux */
    for (int c = 0; c < f.ncells; c++) xc[c] = 1 + f.node[3 * c] + 0.5 * f.node[3 * c + 1];
    for (int b = 0; b < f.nboundary; b++) xb[b] = 7;
    fvc_div_upwind(&f, phi, xc, xb, 1, out);
    double total = 0, bflux = 0;
    for (int c = 0; c < f.ncells; c++) total += out[c];
    for (int i = f.ninternal; i < f.nfaces; i++)
        bflux += phi[i] * (phi[i] >= 0 ? xc[m.owner[i]] : xb[i - f.ninternal]);
    NEAR(total, bflux, 1e-12 * fabs(bflux));

    double *pf = malloc(sizeof(double) * (size_t)f.nfaces), *force = malloc(sizeof(double) * 3 * (size_t)f.ncells);
    for (int i = 0; i < f.nfaces; i++) pf[i] = 6.0;
    fvc_pressure_force(&f, pf, force);
    worst = 0;
    for (int c = 0; c < 3 * f.ncells; c++) worst = fmax(worst, fabs(force[c]) / m.cell_vol[c / 3]);
    EXPECT(worst < 1e-11, "uniform pressure: force %.3e per volume", worst);
    free(phi), free(xc), free(xb), free(out), free(pf), free(force);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* 1-D flow along x on a block grid: each cell's outflow is the upstream
   state times the flux; the Courant number is |u| dt / h. */
TEST(upwind_and_courant)
{
    Mesh m;
    int n[3] = {10, 1, 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0.1, 0.1};
    fixture_block(&m, n, lo, hi, -1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    double u[3] = {2, 0, 0}, xc[10], xb[64], out[10], co[10];
    double *phi = uniform_flux(&f, u);
    for (int c = 0; c < 10; c++) xc[c] = c * c;
    for (int b = 0; b < f.nboundary; b++) xb[b] = -5;
    fvc_div_upwind(&f, phi, xc, xb, 1, out);
    double A = 0.01;
    for (int c = 0; c < 10; c++) {
        double in = c ? xc[c - 1] : -5;
        NEAR(out[c], 2 * A * (xc[c] - in), 1e-13);
    }
    double worst = fvc_courant(&f, phi, NULL, 0.01, co);
    NEAR(worst, 2 * 0.01 / 0.1, 1e-13);
    NEAR(fvc_total(&f, xc), 285 * 0.001, 1e-14);
    free(phi);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* A swirling flux through every face of m, for the Courant tests. */
static void swirl_flux(const Mesh *m, double *phi)
{
    for (int i = 0; i < m->nfaces; i++) {
        const double *x = m->face_centre + 3 * i, *S = m->face_area + 3 * i;
        phi[i] = sin(3 * x[1]) * S[0] - x[0] * S[1] + 0.1 * S[2];
    }
}

/* fvc_courant_uniform(c) against fvc_courant with c on every face, on a
   cut grid with a swirling flux: the same numbers bit for bit. */
TEST(courant_uniform)
{
    Mesh m;
    sphere_grid(&m, 8);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    double *phi = calloc((size_t)f.nfaces + 1, sizeof *phi), *cf = calloc((size_t)f.nfaces + 1, sizeof *cf);
    double *a = calloc((size_t)f.ncells + 1, sizeof *a), *b = calloc((size_t)f.ncells + 1, sizeof *b);
    const double c = sqrt(6.0);
    swirl_flux(&m, phi);
    for (int i = 0; i < f.nfaces; i++) cf[i] = c;
    double wa = fvc_courant(&f, phi, cf, 1e-3, a), wb = fvc_courant_uniform(&f, phi, c, 1e-3, b);
    EXPECT(wa == wb && memcmp(a, b, sizeof(double) * (size_t)f.ncells) == 0, "largest %.17g and %.17g", wa, wb);
    EXPECT(wa > 0, "no Courant number");
    free(phi);
    free(cf);
    free(a);
    free(b);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* fvc_courant_cells against fvc_courant with each face's larger cell
   speed (the owner's at boundary faces): bit for bit. */
TEST(courant_cells)
{
    Mesh m;
    sphere_grid(&m, 8);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    double *phi = calloc((size_t)f.nfaces + 1, sizeof *phi), *cf = calloc((size_t)f.nfaces + 1, sizeof *cf);
    double *cc = calloc((size_t)f.ncells + 1, sizeof *cc);
    double *a = calloc((size_t)f.ncells + 1, sizeof *a), *b = calloc((size_t)f.ncells + 1, sizeof *b);
    for (int c = 0; c < f.ncells; c++) cc[c] = 1 + 0.5 * sin(7.0 * c);
    swirl_flux(&m, phi);
    for (int i = 0; i < f.nfaces; i++) {
        double so = cc[m.owner[i]];
        cf[i] = i < f.ninternal && cc[m.neighbour[i]] > so ? cc[m.neighbour[i]] : so;
    }
    double wa = fvc_courant(&f, phi, cf, 1e-3, a), wb = fvc_courant_cells(&f, phi, cc, 1e-3, b);
    EXPECT(wa == wb && memcmp(a, b, sizeof(double) * (size_t)f.ncells) == 0, "largest %.17g and %.17g", wa, wb);
    EXPECT(wa > 0, "no Courant number");
    free(phi);
    free(cf);
    free(cc);
    free(a);
    free(b);
    fvmesh_free(&f);
    mesh_free(&m);
}

int main(void)
{
    RUN(uniform_state_uniform_flow);
    RUN(upwind_and_courant);
    RUN(courant_uniform);
    RUN(courant_cells);
    return test_summary();
}
