/*
** fvc.h: explicit finite-volume operators (OpenFOAM's fvc: results from
** known values, no matrix), for the explicit terms of eq. 4.66: upwind
** convection of the advected states, the pressure force, the Courant
** number.
**
** Fluxes: phi[f] = u_f . S_f, the volumetric flux through face f along
** its area vector (out of the owner).  Face velocities come from the
** interpolation (the convective face velocity is interpolated, the
** advected state never is: spec §4.2, eq. 4.60), so these operators take
** phi as given.
**
** Values: xc holds ncomp numbers per cell (interleaved, as Field.v), xb
** ncomp per boundary face (the boundary condition's face values, from
** which an inflow face takes its state; a cyclic face's value is its
** partner's owner's).  Faces of empty patches carry nothing.
**
** Results are per cell and summed over its faces with outward normals:
** a cell's net outflow, so that the update reads
**   V (x^{m+1} - x^m) / dt = -div   (eq. 4.66 with inner normals: the same).
*/
#ifndef KIESEL_FVC_H
#define KIESEL_FVC_H

#include "fvmesh.h"

/* eq. 4.60: out[c] = sum over faces of B(x_C, x_F, phi_f): the outflow
   takes the cell's own state, the inflow the state upwind (neighbour cell
   or boundary value).  out has ncomp per cell and is overwritten. */
void fvc_div_upwind(const FvMesh *f, const double *phi, const double *xc, const double *xb, int ncomp,
                    double *out);

/* The force of a face pressure field: out[3c..3c+2] = sum over faces of
   p_f S_f (outward), so the momentum balance subtracts it (eq. 4.66's
   -sum p_f n_f A_f with inner normals).  pf has one value per face.  By
   closure (sum S_f = 0 over a closed cell) a uniform p gives no force. */
void fvc_pressure_force(const FvMesh *f, const double *pf, double *out);

/* Courant number of each cell for a step dt: 0.5 dt / V sum over faces
   of (|phi_f| + c_f |S_f|), c_f a signal speed per face (the speed of
   sound for the compressible model's explicit pressure; NULL: none), as
   OpenFOAM's CourantNo with the acoustic term added.  Returns the
   largest; co (may be NULL) receives each cell's. */
double fvc_courant(const FvMesh *f, const double *phi, const double *cf, double dt, double *co);
/* The same with c_f the larger of the signal speeds cc of the face's two
   cells (the owner's at a boundary face): no array of faces. */
double fvc_courant_cells(const FvMesh *f, const double *phi, const double *cc, double dt, double *co);
/* The same with one signal speed c on every face (no array of them). */
double fvc_courant_uniform(const FvMesh *f, const double *phi, double c, double dt, double *co);

/* Sum of x V over the owned cells (total mass for x = rho). */
double fvc_total(const FvMesh *f, const double *x);

#endif
