/*
** bc_open.c: which boundary conditions of rho and U an open boundary of
** the isothermal model may take (bc.h, bc_check_open; doc/theory.md §9,
** "Open boundaries").
**
** The inviscid part of eq. 5.1 is hyperbolic; along the outward normal n
** its characteristic speeds are u_n - c, u_n (d - 1 times: the tangential
** velocity, carried with the flow) and u_n + c, with c = sqrt(RsT).  A
** boundary takes one condition per characteristic that enters the
** domain.  At a subsonic inflow (-c < u_n < 0) these are the acoustic
** wave u_n - c and the d - 1 tangential ones: d conditions, one per
** velocity component, so the tangential components count and fixedValue
** U supplies exactly d.  At a subsonic outflow (0 < u_n < c) only u_n - c
** enters: one condition, the density (the pressure p = RsT rho).  So
** exactly one of rho and U is fixed:
**
**     inflow   fixedValue U   (d conditions)   zeroGradient rho
**     outflow  fixedValue rho (1 condition)    zeroGradient U
**
** Both fixed is d + 1 conditions, one too many unless the inflow is
** supersonic (u_n <= -c, every characteristic enters), which the fixed
** values decide face by face; neither fixed is none, one too few unless
** the outflow is supersonic, which the model's low-Mach flows are not.
** A zero gradient is the extrapolation that supplies nothing: the
** viscous term wants a condition on every velocity component, and
** zeroGradient U is the one that leaves the outgoing waves free.
*/
#include "bc.h"

#include <math.h>
#include <stdio.h>

int bc_kind_open(BcKind k)
{
    return k == BC_FIXED_VALUE || k == BC_ZERO_GRADIENT || k == BC_CALCULATED;
}

/* A value given on the boundary (calculated is a fixed value, bc.h). */
static int fixed(BcKind k) { return k == BC_FIXED_VALUE || k == BC_CALCULATED; }

/* Every face of U's patch p an inflow at sound speed c or faster. */
static int supersonic_inflow(const Bc *U, int p, double c)
{
    const BcPatch *bp = &U->patch[p];
    const FvMesh *fm = U->fm;
    int any = 0;
    for (int j = 0; j < bp->size; j++) {
        int i = bp->start + j;
        if (fm->empty_face[i]) continue;
        const double *n = fm->nf + 3 * i, *u = bp->value + 3 * j;
        if (!(u[0] * n[0] + u[1] * n[1] + u[2] * n[2] <= -c)) return 0;
        any = 1;
    }
    return any;
}

/* "file:line" of patch p's entry in field f, for the message. */
static void where(const Field *f, int p, char *s, size_t n)
{
    const PatchField *pf = &f->pf[p];
    if (pf->file && pf->line > 0) snprintf(s, n, "%s:%d", pf->file, pf->line);
    else snprintf(s, n, "%s", pf->file ? pf->file : f->name);
}

int bc_check_open(const Bc *rho, const Bc *U, const Field *frho, const Field *fU, double c, Err *e)
{
    int d = U->fm->empty_axis >= 0 ? 2 : 3;
    for (int p = 0; p < U->npatches; p++) {
        BcKind ku = U->patch[p].kind, kr = rho->patch[p].kind;
        if (!bc_kind_open(ku) || fixed(ku) != fixed(kr) || (fixed(ku) && supersonic_inflow(U, p, c))) continue;
        const PatchField *pf = &frho->pf[p];
        const char *name = U->fm->m->patches[p].name;
        char at[600];
        where(fU, p, at, sizeof at);
        if (fixed(ku))
            return err_set(e, pf->file ? pf->file : frho->name, pf->line,
                           "patch '%s': rho (%s) and U (%s, %s) are both fixed: an open boundary of the isothermal "
                           "model takes %d conditions at a subsonic inflow (one per velocity component, the "
                           "tangential ones included) and 1 at a subsonic outflow, never %d (only a supersonic "
                           "inflow, u.n <= -sqrt(RsT) = %g at every face, does); use fixedValue U with zeroGradient "
                           "rho at an inflow, or fixedValue rho with zeroGradient U at an outflow",
                           name, bc_kind_name(kr), bc_kind_name(ku), at, d, d + 1, -c);
        return err_set(e, pf->file ? pf->file : frho->name, pf->line,
                       "patch '%s': neither rho (%s) nor U (%s, %s) is fixed: an open boundary of the isothermal "
                       "model needs %d conditions at a subsonic inflow and 1 (the density, i.e. the pressure RsT "
                       "rho) at a subsonic outflow, and gets none; use fixedValue rho with zeroGradient U at an "
                       "outflow, or fixedValue U with zeroGradient rho at an inflow",
                       name, bc_kind_name(kr), bc_kind_name(ku), at, d);
    }
    return 0;
}
