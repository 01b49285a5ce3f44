/*
** newtonian.h: solveGranular's model Newtonian, the isothermal
** compressible Navier-Stokes equations of eq. 5.1,
**     d_t rho + div(rho u) = 0,
**     d_t(rho u) + div(rho u u^T) - div(mu grad u) + grad p = rho g,
**     p = RsT rho,
** advanced by the semi-implicit Euler of eq. 4.66: explicit upwind
** convection with the interpolated face velocity (eq. 4.60-4.61; or,
** beyond the thesis, the bounded second-order face values of fv/tvd.h
** chosen in divSchemes), explicit
** pressure, implicit diffusion one velocity component at a time.
**
** One step from (rho^m, u^m) over dt:
**   phi_f = u_f . S_f, u_f the CENTRE row of the face (0 on walls: noSlip,
**           slip, movingWall and symmetryPlane are impermeable)
**   rho^{m+1} = rho^m - dt/V sum_f B(rho, phi)              (eq. 4.60)
**   V (rho^{m+1} u^{m+1} - (rho u)^m) / dt
**       = -sum_f B(rho u, phi) - sum_f p_f S_f + sum_f mu |S_f| du^{m+1}/dn
**         + F_C                                              (eq. 4.66 [OURS])
** with the pressure force and gravity F_C chosen in fvSchemes'
** gravitySchemes (fv/hydro.h, doc/theory.md):
**   wellBalanced (default)  each source of a face's pressure is
**       reconstructed to the face along its own hydrostatic profile,
**       p_{s->f} = RsT rho_s exp(g.(x_f - x_s)/RsT), before the weights act,
**       and F_C = sum over all faces of C of RsT rho_C exp(g.(x_f - x_C)/RsT)
**       S_f (outward): the discrete rest state rho_C = c exp(g.x_C/RsT) is
**       kept to round-off on every grid;
**   cellSource  p_f of the plain values and F_C = rho_C g V_C, the
**       thesis's, which has no rest state on cut and Voronoi grids.
** Model granular's profiles are its rest profiles at each cell's T
** (restprofile.c, granular.h).
** Both take p_f as the mean of the two cells on a face between whole
** Cartesian cells (eq. 4.61), the interpolated CENTRE value on the other
** internal faces (cyclic faces are internal faces of the periodic domain,
** fvmesh.h), the owner's at a wall and at a zero-gradient open face (zero
** normal gradient, spec §4.3; wellBalanced: the owner's neighbourhood at
** the face's potential, each node along its profile, fv/hydro.h) and RsT
** times the density's boundary value elsewhere; with g = 0 the two are
** one scheme, bit for bit.  The unknown is u
** itself with the new density on the diagonal (doc/theory.md: the same as
** the thesis's (rho u)^{m+1} / rho^m to O(dt), boundary conditions stay in
** u, momentum is conserved).  A step that fails (a linear solve, a NaN, a
** density <= 0) leaves the state as it was, so the caller can write the
** last good one.
**
** Sources: a caller may add given source terms to the two equations,
**     d_t rho + ... = s_rho,     d_t(rho u) + ... = s_m,
** and in model granular to the temperature equation (granular.h),
**     d_t(c T) + ... = s_T,
** through the hook Granular.src (GranSource below; manufactured solutions,
** tests/validation/mms; later fvOptions).  Each step asks it for the
** integrals of s_rho, s_m (and s_T) over every cell at the step's start
** time t^m, and adds them explicitly, as the other explicit terms:
**   rho^{m+1} += dt/V S_rho,   the momentum right-hand side += S_m,
**   the temperature's right-hand side += S_T (not with freezeT).
** Integrals, not point values, so that the hook chooses the quadrature:
** the centroid rule is second order on any cell (it integrates linear
** functions exactly), fv/quad.h's degree-2 rule third order (doc/theory.md).
** Without a hook (src.fn NULL, as gran_init leaves it) nothing changes.
** solveGranular's main frees the set-up's geometry before the steps
** (fvmesh_end_setup: face centres, cell face lists), which fv/quad.h
** reads: a hook that integrates with it runs where that is kept (the
** studies of tests/validation/mms), or takes its integrals before.
*/
#ifndef KIESEL_NEWTONIAN_H
#define KIESEL_NEWTONIAN_H

#include "bc.h"
#include "dict.h"
#include "field.h"
#include "fvm.h"
#include "granular.h"
#include "hydro.h"
#include "interp.h"
#include "linsolve.h"
#include "props.h"
#include "tvd.h"

enum { GRAN_WELL_BALANCED, GRAN_CELL_SOURCE };
enum { GRAN_HEAT_WALL, GRAN_HEAT_BOUNDARY };   /* heatingSchemes' wallVelocity (granular.h) */
enum { GRAN_JAC_FACE, GRAN_JAC_LSQ, GRAN_JAC_THESIS, GRAN_JAC_DISS };   /* heatingSchemes' jacobian (granular.h) */

/* The schemes of fvSchemes the model reads. */
typedef struct GranSchemes {
    TvdScheme div[3];      /* divSchemes' div(phi,rho), div(phi,U) and
                              div(phi,Theta) (model granular: of c T) */
    int gravity;           /* gravitySchemes: GRAN_WELL_BALANCED, ... */
    int heat_wall;         /* heatingSchemes' wallVelocity: GRAN_HEAT_WALL
                              (u_S, the thesis's) or GRAN_HEAT_BOUNDARY (u_B) */
    int jacobian;          /* heatingSchemes' jacobian: GRAN_JAC_FACE, ... */
} GranSchemes;

/* A source hook: fn fills, for each of the f->ncells cells c, rho_src[c]
   = the integral of s_rho over cell c and mom_src[3 c + k] = that of
   component k of s_m, at time t (units: kg/s and N), and in model
   granular T_src[c] = that of s_T, the source of the c T equation (T_src
   is NULL in model Newtonian).  It returns 0, or -1 with e filled (the
   step then fails and changes nothing).  ctx is the caller's. */
typedef struct GranSource {
    int (*fn)(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src, Err *e);
    void *ctx;
} GranSource;

typedef struct Granular {
    int model;             /* MODEL_NEWTONIAN or MODEL_GRANULAR (props.h) */
    const FvMesh *f;
    const Interp *ip;
    GranularProps pr;
    Field *rho, *U;        /* the state (the caller's fields, updated in place) */
    Bc bc_rho, bc_U;
    TvdScheme div_rho, div_U, div_T;   /* divSchemes' div(phi,rho), div(phi,U), div(phi,Theta) */
    Tvd tvd;               /* their grid data (nothing when both are upwind) */
    int gravity;           /* GRAN_WELL_BALANCED or GRAN_CELL_SOURCE */
    int heat_wall;         /* GRAN_HEAT_WALL or GRAN_HEAT_BOUNDARY */
    int jacobian;          /* GRAN_JAC_FACE, GRAN_JAC_LSQ or GRAN_JAC_THESIS */
    Hydro hy;              /* the face pressure weights and gravity vectors
                              (g = 0 in them for GRAN_CELL_SOURCE) */
    FvMatrix M;
    Fvm op;
    int naxes, axis[3];    /* the velocity components solved (2 in 2-D) */
    LinSettings set[3];
    LinSystem *L[3];
    LinStats st[3];        /* of the last step */
    char *wall;            /* nboundary: 1 on an impermeable face */
    int flux_skip;         /* the velocity component the fluxes leave out:
                              the empty axis of a 2-D grid whose faces'
                              areas have no component along it, else -1 */
    double *phi;           /* nfaces: flux */
    double *rho1;          /* ncells: the new density */
    double *mom;           /* 3 ncells: the explicit momentum terms
                              V (rho u)^m / dt - div(phi rho u); component k
                              becomes the new velocity once it is solved, so
                              that after the solves this is u^{m+1} */
    double *force;         /* 3 ncells: the pressure force (before that, the
                              convection terms) */
    double *x;             /* ncells: the solve's unknown; scratch before */
    double *xb, *xbr;      /* boundary values: 3 and 1 per boundary face */
    double *patch_out;     /* npatches: mass flow out of each patch in the
                              last step, sum_f B(rho, phi) (eq. 4.60) */
    double out_total;      /* sum over the steps of dt x the net mass flow
                              out: mass(start) - mass = out_total to
                              round-off (the internal fluxes cancel) */
    GranSource src;        /* the source hook, or fn NULL (none) */
    double time;           /* the state's time t^m, the hook's argument:
                              0 after gran_init, set by the caller at the
                              start, advanced by each gran_step */
    double *src_rho, *src_m;   /* ncells, 3 ncells: the hook's integrals */
    double *src_T;         /* ncells, model granular: the hook's s_T
                              integrals (granular.c adds them) */
    double src_total;      /* sum over the steps of dt x the integrated
                              continuity source: mass - mass(start) =
                              src_total - out_total to round-off */
    GranModel gm;          /* model granular's part (granular.h); zero for
                              model Newtonian */
    double t_flux, t_explicit, t_assembly, t_solve, t_update;   /* seconds
                              spent in each part of the steps (GranProfile) */
} Granular;

/* Keywords of divSchemes and gravitySchemes, for -help. */
extern const DictKey gran_div_keys[];
extern const DictKey gran_gravity_keys[];
extern const char *const gran_gravity_names[];
extern const DictKey gran_heating_keys[];
extern const char *const gran_heating_names[];

/* fvSchemes' schemes into sch: divSchemes into div[0] (div(phi,rho)) and
   div[1] (div(phi,U)), each entry "Gauss upwind", "Gauss limitedLinear k"
   or "Gauss vanLeer" (fv/tvd.h), a missing one taking default's (default
   Gauss upwind; default none requires both); gravitySchemes' default
   wellBalanced | cellSource (absent: wellBalanced); heatingSchemes'
   wallVelocity wall | boundary (absent: wall).  Another scheme or
   keyword fails with file:line. */
int gran_read_schemes(const Dict *fvschemes, GranSchemes *sch, Err *e);

/* Sets up the model on f with the interpolation ip and the schemes sch
   (gran_read_schemes): the boundary conditions of rho and U, the face
   pressure weights, the matrix, the solvers of Ux, Uy (, Uz) from
   fvSolution.  Model granular (pr->model): rho is the volume fraction
   alpha and T the granular temperature Theta (granular.h); model
   Newtonian: T is NULL. */
int gran_init(Granular *g, const FvMesh *f, const Interp *ip, const GranularProps *pr, const GranSchemes *sch,
              Field *rho, Field *U, Field *T, const Dict *fvsolution, Err *e);
/* The arrays the steps write: the work arrays and model granular's state
   (closures, boundary values, rest profiles).  Call it once after
   gran_init and fvmesh_end_setup, before the first step: those arrays and
   the set-up's geometry are then never alive together (together they were
   the run's peak in 3-D, doc/performance.md, "Memory of model granular in
   3-D"). */
void gran_alloc(Granular *g);
void gran_free(Granular *g);

/* The face fluxes phi of the current velocity. */
void gran_flux(Granular *g);
/* Courant number of the fluxes for step dt with the sound speed
   (pressure is explicit): sqrt(RsT), or model granular's sqrt(dp/dc) of
   the faces' cells; the largest, and the mean into *mean. */
double gran_courant(Granular *g, double dt, double *mean);
/* One step of eq. 4.66 over dt from the fluxes of gran_flux. */
int gran_step(Granular *g, double dt, Err *e);
/* Does patch q carry mass (not a wall, not empty, not cyclic)? */
int gran_open_patch(const Granular *g, int q);
/* Does boundary face b take its pressure from the cells (a wall, or a
   zero gradient of rho)? */
int gran_owner_pressure(const Granular *g, int b);
/* Total mass sum rho V. */
double gran_mass(const Granular *g);
/* The derived pressure p = RsT rho, or model granular's p(c, T) (cells
   and, as calculated values, the boundary faces) into p, a field made
   with field_init. */
void gran_pressure(Granular *g, Field *p);

/* Frees the linear solvers' factors and work vectors until the next step
   rebuilds them (linsolve_release), so that writing a time reuses their
   memory: the write is the peak otherwise (doc/performance.md, "Memory of
   model granular in 3-D").  The next step's results are unchanged. */
void gran_release(Granular *g);

#endif
