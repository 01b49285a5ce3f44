/*
** granular.h: what solveGranular's model granular adds to the shared
** compressible core of newtonian.h: the closures, the face viscosities and
** the granular temperature (thesis ch. 2 and eq. 4.66; spec
** granular-model.md §1 and §4).
**
** The unknowns are c (the field alpha), cu (U holds u) and cT (Theta holds
** T).  The core advances c and u as it advances rho and u in model
** Newtonian, with three differences that this module supplies:
**   pressure   p = p_k + p_y of fv/closure.h, not RsT rho;
**   viscosity  -div(eta grad u_i) with the face viscosity eta_f of eq.
**              4.61's face rule (spec correction 4): the mean of the two
**              cells between whole Cartesian cells, the interpolated cell
**              field (the face's CENTRE row) near cut cells, the boundary
**              value eta(c_b, T_b) at boundary faces;
**   gravity    with gravitySchemes wellBalanced (the default) each cell's
**              rest profile at its own T carried to the faces (fv/hydro.h's
**              barotropic profiles, restprofile.c): a packing at rest
**              stays at rest; with cellSource F = c g V, the thesis's.
** and, after the momentum solves, the temperature equation (eq. 4.66),
**   V (c^{m+1} T^{m+1} - (cT)^m) / dt + sum_f B((cT)^m, phi)
**       - sum_f K_T lambda_f |S_f| dT^{m+1}/dn + eps^m c^{m+1} T^{m+1} V
**       = K_T eta_C sum_ij (J^m_C)_ij^2 V  (+ S_T, the source hook's, newtonian.h),
** with T^{m+1} the unknown (the thesis's (cT)^{m+1}/c to O(dt), as the
** momentum's), implicit conduction and dissipation, explicit heating.
** J_C is the face-based Jacobian of §4.4 (eq. 4.57, 4.58, 4.65) with a
** metric [OURS] that makes it exact for a linear velocity on any cell:
**   J_C = (sum_f (du/dn_f) n_f^T A_f) M_C^-1,   M_C = sum_f n_f n_f^T A_f,
** over the cell's faces that are not empty, du/dn_f the face's normal
** derivative of eq. 4.62 from its PLUS and MINUS rows, with the wall
** velocity u_S at impermeable walls (slip and partialSlip walls included:
** "gradients at slip walls are completely included", spec §1.4).  On a
** square or cubic cell M_C = (sum_f A_f / alpha) I and this is eq. 4.65's
** alpha sum_f (du/dn_f)(n_f)_j A_f / sum_f A_f; on other cells (cut,
** merged, Voronoi, rectangular) eq. 4.65's weight is not consistent: it
** gives O(1) errors of the heating, which the granular manufactured
** solutions showed (doc/theory.md §12, doc/validation.md).  M_C is
** geometry, its inverse kept per cell.  The product (du/dn_f)(n_f)_j does
** not depend on the normal's orientation (spec correction 5), so each face
** adds the same term to its two cells.  fvSchemes' heatingSchemes
** { wallVelocity boundary; } (ours) takes U's boundary values u_B instead
** of u_S at the walls: the same at walls that stick, but at a sliding wall
** (slip, partialSlip beyond its Coulomb bound) the jump u_I - u_S over h_f
** heats the wall cell by eta ((u_I - u_S)/h_f)^2, a heat per wall area
** eta jump^2 / h that grows without bound as h -> 0 (the grid-aligned
** shear plate's T does not converge, doc/validation.md); with u_B it is
** the gradient inside the grain.  The boundary condition of T is
** zeroGradient at walls (spec §1.4); at an inflow with fixed c the
** advected state is c_F T_C.
**
** Limits (props.h: deltaC, Tmin, cMin), each counted per step and in all:
** c^{m+1} <= cMax - deltaC and T^{m+1} >= Tmin after each step, and c
** floored to cMin in the matrices' time-derivative and dissipation terms,
** so that an empty cell (c = 0 is kept by the upwind scheme) still gets a
** velocity and a temperature: the safe velocity of a vacuum.  A clamp of c
** changes the mass; the log reports the mass and the counts.
*/
#ifndef KIESEL_GRANULAR_H
#define KIESEL_GRANULAR_H

#include "bc.h"
#include "closure.h"
#include "field.h"
#include "fvm.h"
#include "linsolve.h"

struct Granular;

typedef struct GranLimits {
    long cmax, tmin, cmin;   /* cells limited: c clamped to cMax - deltaC,
                                T raised to Tmin, c floored to cMin */
} GranLimits;

typedef struct GranModel {
    Field *T;              /* Theta: the granular temperature T */
    Bc bc_T;
    double *eta_c, *lam_c, *eps_c;   /* ncells: eta, K_T lambda, eps at c^m, T^m */
    double *eta_f, *lam_f; /* nfaces: eta_f and K_T lambda_f (eq. 4.61's face rule) */
    double *speed_c;       /* ncells: the signal speed sqrt(dp/dc) (the Courant
                              number takes a face's larger one) */
    double *cb, *Tb;       /* nboundary: boundary values of c and T */
    double *etab, *lamb;   /* nboundary: eta and K_T lambda there */
    double *tb;            /* nboundary: scratch (a component, a state) */
    double *uk;            /* ncells: scratch (a component, c T^m) */
    double *pc;            /* ncells: the cell pressures p(c, T) */
    double *prof_v, *prof_p, *prof_theta;   /* ncells, gravitySchemes
                              wellBalanced only (restprofile.c): each cell's
                              logit of c, its pressure from it, and the
                              weight of its exact rest profile */
    double *grav;          /* 3 ncells, wellBalanced only: the gravity force
                              of the profiles (fv/hydro.h) */
    double *cfl;           /* ncells: c^{m+1} floored to cMin (the matrices) */
    double *T1;            /* ncells: the new temperature */
    double *heat;          /* ncells: K_T eta_C sum (J_C)_ij^2 (per volume) */
    double *jac;           /* 3 ncells: one row of the Jacobian's sums, then
                              the next (the core's work array force, not
                              owned: newtonian.c) */
    double *jmet;          /* 6 ncells: the inverse of M_C = sum_f n_f n_f^T A_f
                              over the non-empty faces (the Jacobian's
                              metric), symmetric: its upper triangle */
    double *lsq;           /* 3 nfaces, heatingSchemes jacobian leastSquares
                              only: d / |d|^2 to the point across each face */
    double *ub;            /* 3 nboundary: U's boundary values with u_S at walls */
    Fvm op;                /* on the core's matrix Granular.M (init_solver) */
    LinSettings set;
    LinSystem *L;
    LinStats st;
    int solved;            /* the temperature equation is solved (not frozen) */
    int fresh;             /* the closures are those of the current state */
    GranLimits last, total;
} GranModel;

/* Sets up the model's part on g (after the core's boundary conditions and
   matrix pattern exist): T's boundary conditions and checks, the
   heating's metric, the matrix and the solver of Theta from fvSolution (skipped with
   freezeT).  The initial c must lie in [0, cMax - deltaC] and T be
   positive and finite: else an error naming the field and the cell. */
int granmodel_init(struct Granular *g, Field *T, const Dict *fvsolution, Err *e);
/* The model's arrays that the steps write (closures, boundary values, the
   rest profiles), and partialSlip's wall state: by gran_alloc, after the
   core's work arrays. */
void granmodel_alloc(struct Granular *g);
void granmodel_free(GranModel *m);

/* The closures at the current state: cell values, boundary values, face
   viscosities, signal speeds and the cell pressures (into m->pc). */
void granmodel_closures(struct Granular *g);
/* The pressure of boundary face b that is not taken from the owner's
   neighbourhood: p(c_b, T_b) (after granmodel_closures). */
double granmodel_boundary_pressure(const struct Granular *g, int b);
/* After the explicit update of c (the core's rho1): c^{m+1} clamped to
   cMax - deltaC, and its copy floored to cMin for the matrices (m->cfl). */
void granmodel_limit_c(struct Granular *g);
/* The temperature step (after the momentum solves, before the state is
   committed): the new temperature into m->T1, Tmin applied; frozen T:
   T1 is T.  Fails (changing nothing) when the solve fails or T1 is not
   finite. */
int granmodel_temperature(struct Granular *g, double dt, Err *e);
/* gravitySchemes wellBalanced (restprofile.c): each cell's rest profile
   at the current state (after granmodel_closures), and the profile of
   source s at potential difference phi: the HydroProfile of fv/hydro.h,
   ctx the Granular (a boundary source reads the boundary pressures xbr). */
void granmodel_profiles(struct Granular *g);
double granmodel_profile_at(const void *ctx, int s, double phi);
/* The pressure of boundary face b that is its owner's (a wall, a zero
   gradient): the owner's profile at the face. */
double granmodel_owner_profile_pressure(const struct Granular *g, int b);
/* The commit: T1 into the field. */
void granmodel_commit(struct Granular *g);

#endif
