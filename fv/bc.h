/*
** bc.h: boundary conditions of one field on one grid, parsed once (spec
** granular-model.md §1.4, §4.2; thesis §2.2.5, eq. 4.60-4.64).
**
** A Bc is read from a Field's patch types and values (common/field.h) and
** the grid (FvMesh) before any time step: an unknown type, a type the
** field cannot take, a missing value, a cyclic patch without its partner
** or with faces that do not pair, a field whose patches are not the
** grid's: each is an error naming the field file and the line of the
** patch's entry, never a silent zero gradient.  Afterwards the solver only
** reads arrays.
**
** Every boundary face b (face ninternal + b) and component k gets
**
**   the face value       xi_b        = a  xi_in + b          (eq. 4.60-4.61: xi_F at a wall)
**   the normal gradient  dxi/dn_out  = ga xi_in + gb         (eq. 4.63 with ht_f = 0)
**
** xi_in being the interior value: the owner's, or the interpolated value
** at the gradient point x_f - n_out h_f of eq. 4.63.  So the assembly puts
** a (or ga |S_f| Gamma_f) on the matrix row of the owner and b (gb) on the
** right-hand side.  The normal gradient of a Dirichlet face is the
** one-sided difference (xi_b - xi_in) / h_f, i.e. ga = (a - 1)/h_f and
** gb = b/h_f; a Neumann face (fixed_grad[b] = 1) has its gradient given
** (ga = 0, gb = the gradient: 0 for zeroGradient), so its flux is known.
**
** Types (keywords as OpenFOAM's):
**   fixedValue      xi_b = value                    (inflow; a = 0)
**   zeroGradient    dxi/dn = 0, xi_b = xi_in        (outflow; Neumann)
**   noSlip          u_b = 0                         (vector fields only)
**   movingWall      u_b = value, the wall velocity  (vector fields only;
**                   also spelt movingWallVelocity, as OpenFOAM's, which on
**                   a grid at rest is its value entry)
**   slip            u_b = (I - n n^T) u_in: zero normal component, zero
**                   tangential gradient; n the exact outward normal of the
**                   geometry (Mesh.boundary_normal) where the grid has it,
**                   else the face's.  One component at a time, as
**                   OpenFOAM's basicSymmetry: a_k = 1 - n_k^2 on the
**                   diagonal, b_k = -n_k sum_{j != k} n_j u_j explicit from
**                   the current values (bc_update).  A scalar: zero
**                   gradient.
**   symmetryPlane   as slip (and OpenFOAM's symmetry likewise)
**   cyclic          the patch's faces paired in order with its
**                   neighbourPatch's: face i couples its owner C to the
**                   owner N of partner face i, a periodic neighbour whose
**                   node sits at node[N] - shift (shift = partner centre -
**                   own centre, one translation for the whole patch).  The
**                   face value is linear along the normal between the two
**                   nodes, a = dN/(dC + dN) with b = dC/(dC + dN) xi_N, the
**                   gradient (xi_N - xi_C)/(dC + dN) (dC, dN the two
**                   nodes' normal distances from their faces): the value
**                   a boundary source of a stencil or an explicit term
**                   reads.  The solvers' face rows do not use them: a
**                   cyclic face is an internal face of the periodic
**                   domain there (fvmesh.h, interp.h).
**   empty           the front and back of a 2-D grid: no flux, no
**                   coefficients (bc_slot -1), no values (the terms and
**                   the assembly skip them)
**   calculated      a value the solver derives (p = R_s T rho): taken as a
**                   fixed value, the value entry required
*/
#ifndef KIESEL_BC_H
#define KIESEL_BC_H

#include "err.h"
#include "field.h"
#include "fvmesh.h"

typedef enum BcKind {
    BC_FIXED_VALUE,
    BC_ZERO_GRADIENT,
    BC_NO_SLIP,
    BC_MOVING_WALL,
    BC_SLIP,
    BC_SYMMETRY_PLANE,
    BC_CYCLIC,
    BC_EMPTY,
    BC_CALCULATED,
    BC_NKINDS
} BcKind;

typedef struct BcPatch {
    BcKind kind;
    int start, size;   /* mesh faces start .. start+size-1 */
    int slot;          /* the slot of its first face (bc_slot); -1 empty */
    int partner;       /* cyclic: the neighbourPatch's index, else -1 */
    double shift[3];   /* cyclic: partner face centre - own face centre */
    double *value;     /* size*width fixed values (fixedValue, movingWall,
                          calculated; noSlip: zeros), else NULL */
} BcPatch;

typedef struct Bc {
    const FvMesh *fm;
    int width;         /* 1 scalar, 3 vector */
    int npatches, nboundary;
    int nslots;        /* the boundary faces that are not empty */
    BcPatch *patch;    /* one per mesh patch, in mesh order */
    /* per slot s = bc_slot(bc, b) of boundary face b and component k, at
       s*width + k: */
    double *a, *b;     /* face value xi_b = a xi_in + b */
    double *ga, *gb;   /* outward normal gradient = ga xi_in + gb */
    /* per slot: */
    char *fixed_grad;  /* 1 where the normal gradient is given (Neumann) */
    double *n;         /* 3 per slot: the wall normal slip uses (outward) */
    double *h;         /* h_f of eq. 4.63 (slip's gradient b/h_f) */
    int *nbr;          /* cyclic: the partner face's owner cell, else -1 */
    double *nbr_w;     /* cyclic: weight of xi_N in the face value, else 0 */
    double *nbr_d;     /* cyclic: dN, the partner owner's normal distance */
} Bc;

/* Where boundary face b's coefficients are: its index among the faces of
   the patches that are not empty (FvMesh.bslot), or -1 for a face of an
   empty patch, which carries no coefficients (the front and back of a 2-D
   grid are two faces a cell: 440 bytes a cell of coefficients no term
   reads). */
static inline int bc_slot(const Bc *bc, int b) { return bc->fm->bslot[b]; }

/* The keyword of a kind ("fixedValue", ...). */
const char *bc_kind_name(BcKind k);

/* Parses f's boundary conditions on the grid fm (fm must outlive bc) and
   fills the coefficients from f's current cell values.  Errors name the
   field's file and the line of the patch's entry (PatchField.file, line;
   the field's name when it was not read from a file). */
int bc_init(Bc *bc, const Field *f, const FvMesh *fm, Err *e);
void bc_free(Bc *bc);

/* Refreshes the explicit parts b, gb that depend on the cell values v
   (ncells*width): slip's cross-components and cyclic neighbours.  The
   other faces' coefficients never change. */
void bc_update(Bc *bc, const double *v);

/* The boundary value of every boundary face from the cell values v:
   xb[b*width + k], exactly (slip: the owner's value with its normal part
   removed; cyclic: the value between the two nodes).  After bc_update(bc,
   v) this is a xi_C + b, with xi_C the owner's value.  The boundary
   sources of stencils (fv/stencil.h) read one component of it.  Faces of
   empty patches are skipped: their entries of xb are left as they were
   (no term reads them). */
void bc_values(const Bc *bc, const double *v, double *xb);

/* The state across every boundary face, as the upwind convection of eq.
   4.60 takes it (fv/fvc.h: B(xi_C, xi_F, u.n) with xi_F this): the
   boundary value of bc_values, except that a cyclic face gives the
   periodic neighbour's own value xi_N. */
void bc_states(const Bc *bc, const double *v, double *xb);

/* Does a patch whose U is of kind k carry mass: fixedValue, zeroGradient
   or calculated (not a wall, not empty, not cyclic)? */
int bc_kind_open(BcKind k);

/* The open patches of an isothermal compressible model (bc_open.c): at
   each, exactly one of rho and U fixed (inflow: fixedValue U,
   zeroGradient rho; outflow: fixedValue rho, zeroGradient U), both fixed
   only where every face is a supersonic inflow (u.n <= -c, c the speed of
   sound, from U's fixed values).  Otherwise an error at the file and line
   of rho's patch entry (frho, fU: the fields the conditions came from)
   that says which is wrong and what to use. */
int bc_check_open(const Bc *rho, const Bc *U, const Field *frho, const Field *fU, double c, Err *e);

/* Component k of the boundary values (stride 1, nboundary numbers), the
   form stencil_apply takes (empty faces skipped, as bc_values). */
void bc_values_component(const Bc *bc, const double *v, int k, double *xb);

#endif
