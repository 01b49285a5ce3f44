/*
** fvm.h: implicit finite-volume operators (OpenFOAM's fvm: coefficients
** of the unknown on an FvMatrix), for the implicit terms of eq. 4.66: the
** time derivative and the diffusion of one velocity component.
**
** Diffusion (eq. 4.62-4.64).  For every face f that is not empty, with
** D_f = Gamma |S_f| / (h_f + ht_f) (fvmesh.h), the outward normal
** derivative from the face stencils of interp.h,
**     du/dn = [u(PLUS) - u(MINUS)] / (h_f + ht_f)            (eq. 4.62)
** gives the face flux F_f = D_f [u(PLUS) - u(MINUS)] out of the owner.
** It enters  -sum_f Gamma |S_f| du/dn  (the operator's sign on the left-
** hand side) with minus sign in the owner's row and plus sign in the
** neighbour's: both rows see the same number, so sum over all rows of
** (A u - rhs) is the boundary flux alone and momentum is conserved to
** round-off.  On a face between two whole Cartesian cells the PLUS and
** MINUS rows are the two nodes themselves, so there the distance is the
** true node distance |(x_N - x_C) . n_f| (on a graded grid it differs
** from 2 h_f).  A stencil's boundary source ncells + b stands for the
** boundary value a u_in + b of bc.h: a goes on the column of the face's
** owner, b to the right-hand side.  A boundary face of a Neumann type
** (fixed_grad) contributes its flux Gamma |S_f| (ga u(MINUS) + gb) (gb the
** given gradient, ga 0 for zeroGradient); empty faces contribute nothing.
** A cyclic face is an internal face of the periodic domain (fvmesh.h):
** its PLUS row interpolates at the periodic image of x_f + n h_f, and the
** partner face's rows are its own with PLUS and MINUS swapped
** (interp.c), so each of the two faces adds the flux to its owner's row
** alone and the two fluxes cancel.
**
** The pattern (fvm_pattern) couples every cell with the sources of its
** faces' PLUS and MINUS rows (across the period for cyclic faces); the positions
** of every source in both rows (fvm_init) are found once and kept, so an
** assembly per time step adds by position without a search (a face whose
** rows are its two cells with weight 1 keeps none: the diagonals and
** FvMatrix.face_pos are its positions).
**
** The matrix values depend on the boundary conditions only through a and
** ga (bc.h), which bc_update changes only on partialSlip faces (its lagged
** slip fraction), the right-hand side through b
** and gb; so the values and the right-hand side are assembled apart
** (fvm_laplacian_matrix, fvm_laplacian_rhs), and the components of a
** vector whose a and ga agree (everywhere but on slip walls) share one
** matrix (fvm_same_matrix).  The right-hand side touches only the faces
** whose PLUS or MINUS rows reach a boundary source, and the Neumann faces:
** fvm_init lists them (rhs_face), so a component's right-hand side costs
** the boundary, not the grid.  Each of the three adds its terms in the
** order fvm_laplacian always did, so the sums are the same to the bit.
*/
#ifndef KIESEL_FVM_H
#define KIESEL_FVM_H

#include "bc.h"
#include "fvmatrix.h"
#include "fvmesh.h"
#include "interp.h"

enum { FVM_TWO_POINT = 1, FVM_NEUMANN = 2 };

/* The positions of the diffusion operator's entries on one matrix. */
typedef struct Fvm {
    const FvMesh *f;
    const Interp *ip;
    const Bc *bc;
    double *dist;   /* nfaces: the distance dividing PLUS - MINUS */
    char *kind;     /* nfaces: FVM_TWO_POINT (PLUS the neighbour, MINUS the
                       owner, weights 1: faces between whole Cartesian
                       cells; the entries are diag and FvMatrix.face_pos),
                       FVM_NEUMANN (a boundary face whose gradient is
                       given), or 0 */
    int *pos_off;   /* nfaces + 1: the other faces' PLUS then MINUS
                       entries have their positions at pos_own[pos_off[i]
                       ...], pos_nbr[...] */
    int *pos_own;   /* position of an entry in the row of its face's owner
                       (a boundary source: of the source face's owner), -1
                       when that row is not ours */
    int *pos_nbr;   /* ... in the row of its face's neighbour */
    int *rhs_face;  /* the faces with right-hand-side terms, ascending */
    int nrhs_face;
    int shared;     /* dist and the positions are another Fvm's (fvm_init_like) */
} Fvm;

/* Adds to p the couplings of the diffusion operator on f with the face
   stencils of ip. */
void fvm_pattern(FvPattern *p, const FvMesh *f, const Interp *ip);

/* Finds the positions on M (built from a pattern fvm_pattern filled);
   fails when an entry is missing from the pattern. */
int fvm_init(Fvm *d, const FvMatrix *M, const FvMesh *f, const Interp *ip, const Bc *bc, Err *e);
/* The operator of another field with boundary conditions bc on base's
   matrix, mesh and stencils: it shares base's distances and positions
   (which the boundary conditions do not change) and keeps its own Neumann
   faces and right-hand-side faces.  base must outlive it. */
void fvm_init_like(Fvm *d, const Fvm *base, const Bc *bc);
void fvm_free(Fvm *d);

/* Adds -sum_f Gamma |S_f| du/dn of component k (of bc's field, whose
   coefficients bc_update has refreshed) to M: matrix entries and the
   right-hand side. */
void fvm_laplacian(const Fvm *d, FvMatrix *M, int k, double gamma);
/* The same in two parts: the matrix entries alone, the right-hand side
   alone (fvm_laplacian is the two). */
void fvm_laplacian_matrix(const Fvm *d, FvMatrix *M, int k, double gamma);
void fvm_laplacian_rhs(const Fvm *d, FvMatrix *M, int k, double gamma);
/* Do components k1 and k2 of bc's field have the same matrix entries
   (the same a and ga on every boundary face)? */
int fvm_same_matrix(const Fvm *d, int k1, int k2);
/* The same three with a coefficient per face, gamma_f[i] for face i
   (nfaces numbers; a variable viscosity or conductivity: the granular
   model's eta_f and lambda_f of eq. 4.61's face rule).  With every
   gamma_f[i] = gamma they are the constant forms to the bit. */
void fvm_laplacian_matrix_f(const Fvm *d, FvMatrix *M, int k, const double *gamma_f);
void fvm_laplacian_rhs_f(const Fvm *d, FvMatrix *M, int k, const double *gamma_f);

/* The face fluxes F_f = Gamma |S_f| du/dn (out of the owner) of component
   k of the cell values u (ncells * width, interleaved) with their
   boundary values from bc (as the assembly takes them): flux[nfaces]. */
void fvm_face_flux(const Fvm *d, const double *u, int k, double gamma, double *flux);
void fvm_face_flux_f(const Fvm *d, const double *u, int k, const double *gamma_f, double *flux);

/* Adds V c[C] / dt to the diagonal (the unknown's coefficient of the
   time derivative; c the new density, eq. 4.66 [OURS], doc/theory.md). */
void fvm_ddt(FvMatrix *M, const FvMesh *f, const double *c, double dt);

#endif
