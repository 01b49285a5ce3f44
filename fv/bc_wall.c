/*
** bc_wall.c: the walls of bc.h: which kinds are impermeable, the Coulomb
** friction of partialSlip (thesis eq. 2.32-2.36, spec §1.4 and correction
** 3) and the velocity of a rotatingWallVelocity wall.
**
** Partial slip.  The thesis writes the tangential boundary velocity of
** the momentum diffusion as u_B,t = nu u_I,t + (1 - nu) u_S,t (eq. 2.32)
** with nu from Coulomb's law between the normal wall stress W^n = p
** (eq. 2.33) and the tangential one W^t = eta |u_I,t - u_S,t| / h (eq.
** 2.34, with the absolute value of correction 3):
**
**     u_B,t = u_I,t + (h/eta) min{W^n tan phi, W^t} sgn(u_S,t - u_I,t)   (eq. 2.35)
**
** While W^t <= W^n tan phi this is u_B,t = u_S,t (the wall sticks, nu =
** 0); beyond, the modified wall stress eta |u_I,t - u_B,t| / h is exactly
** W^n tan phi (eq. 2.36), i.e. nu = 1 - p tan phi h / (eta |u_I,t - u_S,t|).
** In 3-D "component-wise" would apply this to each Cartesian component of
** the tangential vector, which depends on the axes: a wall at 45 degrees
** would slide at another speed than the same wall along x.  Kiesel reads
** it as the vector rule along the direction of the slip, sgn(.) the unit
** vector of u_S,t - u_I,t and W^t the magnitude of the tangential stress
** (doc/theory.md): rotation invariant, and in 2-D, where the tangential
** space of a wall is one line, it is the thesis's rule exactly.
**
** The limits are taken where the quotient is not defined: at phi = 90
** degrees (tan phi infinite) the wall always sticks; a wall without
** friction (phi = 0, or no pressure) always slides, also where u_I,t =
** u_S,t, so that phi = 0 gives slip's coefficients whatever the flow.  A
** negative pressure is no pressure (a wall cannot pull the grains).
*/
#include "bc.h"

#include <math.h>

int bc_kind_wall(BcKind k)
{
    return k == BC_NO_SLIP || k == BC_MOVING_WALL || k == BC_SLIP || k == BC_SYMMETRY_PLANE ||
           k == BC_PARTIAL_SLIP || k == BC_ROTATING_WALL;
}

void bc_set_wall_state(Bc *bc, const double *p_b, const double *eta_b)
{
    bc->p_b = p_b;
    bc->eta_b = eta_b;
}

double bc_coulomb_nu(double p, double eta, double tan_phi, double h, double dut)
{
    if (!(tan_phi < INFINITY)) return 0; /* phi = 90 degrees: no-slip */
    double lim = (p < 0 ? 0 : p) * tan_phi * h; /* h W^n tan phi, eq. 2.33 */
    if (lim == 0) return 1;                     /* no friction: slip */
    double wt = eta * dut;                      /* h W^t, eq. 2.34 */
    if (!(wt > lim)) return 0;                  /* W^t <= W^n tan phi: sticks (and NaN) */
    return 1 - lim / wt;                        /* eq. 2.35-2.36 */
}

void bc_rotating_velocity(const double origin[3], const double axis[3], double omega, const double x[3],
                          const double *n, double u[3])
{
    double a = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    double w[3] = {omega * axis[0] / a, omega * axis[1] / a, omega * axis[2] / a};
    double r[3] = {x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]};
    u[0] = w[1] * r[2] - w[2] * r[1];
    u[1] = w[2] * r[0] - w[0] * r[2];
    u[2] = w[0] * r[1] - w[1] * r[0];
    if (!n) return;
    double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
    for (int k = 0; k < 3; k++) u[k] -= un * n[k];
}

int bc_slip_count(const Bc *bc, int *nfaces)
{
    int n = 0, slide = 0;
    for (int p = 0; p < bc->npatches; p++) {
        const BcPatch *bp = &bc->patch[p];
        if (bp->kind != BC_PARTIAL_SLIP || bp->slot < 0) continue;
        n += bp->size;
        for (int i = 0; i < bp->size; i++) slide += bc->nu[bp->slot + i] > 0;
    }
    if (nfaces) *nfaces = n;
    return slide;
}
