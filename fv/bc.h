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
**   partialSlip     the Coulomb wall of the granular model (thesis eq.
**                   2.32-2.36, spec §1.4 and correction 3; vector fields
**                   only): `frictionAngle phi;` in degrees, 0 <= phi <= 90
**                   (0 slip, 90 no-slip), required; the wall velocity u_S
**                   from `wallVelocity (ux uy uz);`, else the value entry,
**                   else 0 (BcPatch.us).  With n as slip's,
**                       u_b = u_S + nu (I - n n^T)(u_in - u_S):
**                   the normal part Dirichlet (u_S.n), the tangential part
**                   nu u_in,t + (1 - nu) u_S,t, nu of eq. 2.35 from the
**                   wall pressure and viscosity (bc_coulomb_nu,
**                   bc_set_wall_state), h = h_f.  nu is lagged: bc_update
**                   computes it from the current owner value (Bc.nu) and
**                   the condition is then linear as slip's, a_k =
**                   nu (1 - n_k^2) on the diagonal, the rest in b_k.  So
**                   bc_update changes a and ga of these faces (and only
**                   these): nu = 0 gives noSlip's (movingWall's)
**                   coefficients, nu = 1 with u_S = 0 slip's, to the bit.
**                   Without a wall state nu = 0.  In 3-D the rule acts on
**                   the tangential vector u_in,t - u_S,t, not on Cartesian
**                   components (doc/theory.md: rotation invariant; in 2-D
**                   the thesis's component-wise rule exactly).
**   rotatingWallVelocity  OpenFOAM's: `origin (x y z); axis (x y z);
**                   omega w;` (rad/s; also `omega constant w;`): u_b =
**                   omega (axis/|axis|) x (x_f - origin) at the face
**                   centre, less its component along n (the exact normal
**                   where the grid has it, else the face's, as OpenFOAM
**                   does), so a cut wall whose face centres are off the
**                   surface pumps no mass through it.  A fixed value
**                   computed once (vector fields only; a value entry is
**                   ignored, as OpenFOAM recomputes it).
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
    BC_PARTIAL_SLIP,
    BC_ROTATING_WALL,
    BC_NKINDS
} BcKind;

typedef struct BcPatch {
    BcKind kind;
    int start, size;   /* mesh faces start .. start+size-1 */
    int slot;          /* the slot of its first face (bc_slot); -1 empty */
    int partner;       /* cyclic: the neighbourPatch's index, else -1 */
    double shift[3];   /* cyclic: partner face centre - own face centre */
    double *value;     /* size*width fixed values (fixedValue, movingWall,
                          calculated, rotatingWallVelocity; noSlip:
                          zeros), else NULL */
    double *us;        /* partialSlip: size*3 wall velocities u_S, else NULL */
    double phi;        /* partialSlip: the friction angle in degrees */
    double tan_phi;    /* partialSlip: tan phi (INFINITY at 90 degrees) */
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
    double *nu;        /* partialSlip: the lagged nu of eq. 2.35 of the last
                          bc_update (0 sticks, 1 slips freely); NaN on the
                          slots of other types */
    /* bc_set_wall_state: the wall pressure and viscosity per boundary face
       b (nboundary numbers each, the caller's), or NULL */
    const double *p_b, *eta_b;
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

/* Refreshes the parts that depend on the cell values v (ncells*width):
   b, gb of slip's cross-components and of cyclic neighbours, and on
   partialSlip faces nu (from the owner's value, the wall state and h_f)
   with all four coefficients.  The other faces' coefficients never
   change; partialSlip's a and ga do, so a matrix assembled before a
   bc_update is not the new one's (the solver reassembles every step). */
void bc_update(Bc *bc, const double *v);

/* The boundary value of every boundary face from the cell values v:
   xb[b*width + k], exactly (slip: the owner's value with its normal part
   removed; partialSlip: u_S + nu (I - n n^T)(u_C - u_S) with the nu of the
   last bc_update; cyclic: the value between the two nodes).  After bc_update(bc,
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

/* ---- walls (bc_wall.c) ---- */

/* Is a patch whose U is of kind k an impermeable wall (no mass through
   it, phi_f = 0): noSlip, movingWall, slip, symmetryPlane, partialSlip,
   rotatingWallVelocity? */
int bc_kind_wall(BcKind k);

/* The wall state partialSlip needs (eq. 2.33-2.35): the wall pressure
   W^n = p_b[b] and the viscosity eta_b[b] at every boundary face b
   (nboundary numbers each; only the partialSlip faces are read).  The
   pointers are kept, not the numbers: fill the arrays before each
   bc_update.  NULL (either) is no state: partialSlip is then noSlip at
   u_S (nu = 0). */
void bc_set_wall_state(Bc *bc, const double *p_b, const double *eta_b);

/* nu of eq. 2.35 at one face: u_b,t = nu u_I,t + (1 - nu) u_S,t with
   dut = |u_I,t - u_S,t|, h = h_f, tan_phi of the friction angle
   (INFINITY: no-slip):
       nu = 0                              sticking, eta dut <= p tan_phi h
       nu = 1 - p tan_phi h / (eta dut)    sliding: the wall stress is p tan_phi
   A wall without friction (tan_phi = 0, or p <= 0) slips: nu = 1, also
   at dut = 0; a NaN sticks (nu = 0).  Always 0 <= nu <= 1. */
double bc_coulomb_nu(double p, double eta, double tan_phi, double h, double dut);

/* OpenFOAM's rotatingWallVelocity at a point x: omega (axis/|axis|) x
   (x - origin), less its component along the unit vector n (NULL: kept). */
void bc_rotating_velocity(const double origin[3], const double axis[3], double omega, const double x[3],
                          const double *n, double u[3]);

/* How many faces of the partialSlip patches slide (nu > 0 after the last
   bc_update); *nfaces (if not NULL) gets how many faces those patches
   have. */
int bc_slip_count(const Bc *bc, int *nfaces);

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
