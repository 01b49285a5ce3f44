/*
** restprofile.c: model granular's rest profiles for gravitySchemes
** wellBalanced (granular.h; fv/hydro.h "Barotropic profiles"; doc/theory.md
** "Well-balanced granular gravity").
**
** Each source s carries the rest profile at its own temperature through
** its state (fv/closure.h, closure_profile_logit):
**   q_s(phi) = theta_s p(v_s(phi), T_s) + (1 - theta_s)(p_s + c_s phi).
** The exact profile is a consistent gravity only while it is resolved: its
** relative change of c over the cell, eps = reach / (dp/dc) (the granular
** a.h of the isothermal scheme), must be small.  A cold, dilute cell (T
** at T_min, c below c0) has a scale height T/|g| far below h: its exact
** profile packs the cell's lower faces to c_max and would pull it with a
** weight it does not have.  There the linear profile p_s + c_s phi takes
** over, whose integral over the cell is exactly c_C g V_C (the divergence
** theorem with face centroids) and which is itself the exact rest profile
** of a uniform c.  theta is 1 for eps <= 1/4, 0 for eps >= 1/2 and a
** smooth step between, so the scheme is a continuous function of the
** state; a dense packing (c above c0: dp/dc >= T0 (1 - c0/c_max)
** g(c0)^2) and a hot gas are resolved on any useful grid, and keep their
** rest state to round-off.
**
** A boundary face whose pressure is its owner's (a wall, a zero gradient)
** takes its owner's profile, p_b = q_P(g.(x_b - x_P)), and as a source of
** a CENTRE row carries it on: q_P(phi + g.(x_b - x_P)).  Not fv/hydro.h's
** least-squares wall rows: at a free surface they combine the profiles of
** packed and empty neighbours with weights of both signs (measured in
** doc/validation.md: the collapse's near-vacuum speeds grow tenfold with
** them), and the profile through such a p_b at a cold T_b would name a c
** that is not there.  A face with a fixed c carries its
** own state (c_b, T_b) with its owner's theta.
*/
#include "newtonian.h"

#include <math.h>

#define PROFILE_EPS_EXACT 0.25  /* eps up to which the exact profile acts alone */
#define PROFILE_EPS_LINEAR 0.5  /* eps from which the linear profile acts alone */

/* 1 up to PROFILE_EPS_EXACT, 0 from PROFILE_EPS_LINEAR, smooth (C^1) between. */
static double blend(double eps)
{
    if (!(eps > PROFILE_EPS_EXACT)) return eps >= 0 ? 1 : 0; /* NaN: linear */
    if (eps >= PROFILE_EPS_LINEAR) return 0;
    double x = (eps - PROFILE_EPS_EXACT) / (PROFILE_EPS_LINEAR - PROFILE_EPS_EXACT);
    return 1 - x * x * (3 - 2 * x);
}

void granmodel_profiles(Granular *g)
{
    GranModel *m = &g->gm;
    const GranCoeffs *k = &g->pr.k;
    const double *c = g->rho->v, *T = m->T->v;
    for (int i = 0; i < g->f->ncells; i++) {
        double v = closure_logit(k, c[i]), r = g->hy.reach ? g->hy.reach[i] : 0;
        /* dp/dc is smallest at the top of the reach, where c is */
        double d = closure_dpdc_logit(k, closure_profile_logit(k, v, T[i], -r), T[i]);
        m->prof_v[i] = v;
        m->prof_p[i] = closure_pressure_logit(k, v, T[i]);
        m->prof_theta[i] = blend(r > 0 ? r / d : 0);
    }
}

/* q_s(phi) from the logit v, pressure p, volume fraction c, temperature T
   and weight th. */
static double profile(const GranCoeffs *k, double v, double p, double c, double T, double th, double phi)
{
    if (phi == 0) return p;
    double q = th > 0 ? closure_pressure_logit(k, closure_profile_logit(k, v, T, phi), T) : 0;
    return th >= 1 ? q : th * q + (1 - th) * (p + c * phi);
}

double granmodel_profile_at(const void *ctx, int s, double phi)
{
    const Granular *g = ctx;
    const GranModel *m = &g->gm;
    const GranCoeffs *k = &g->pr.k;
    const FvMesh *f = g->f;
    int nc = f->ncells;
    if (s < nc) return profile(k, m->prof_v[s], m->prof_p[s], g->rho->v[s], m->T->v[s], m->prof_theta[s], phi);
    int b = s - nc, i = f->ninternal + b, P = f->m->owner[i];
    if (gran_owner_pressure(g, b)) /* the owner's profile, from the owner's node */
        return granmodel_profile_at(ctx, P, phi + (g->hy.gphi ? g->hy.gphi[2 * i] : 0));
    double c = fmin(fmax(m->cb[b], 0), k->cmax - g->pr.dc), T = fmax(m->Tb[b], g->pr.Tmin);
    return profile(k, closure_logit(k, c), g->xbr[b], c, T, m->prof_theta[P], phi);
}

double granmodel_owner_profile_pressure(const Granular *g, int b)
{
    int i = g->f->ninternal + b;
    return granmodel_profile_at(g, g->f->m->owner[i], g->hy.gphi ? g->hy.gphi[2 * i] : 0);
}
