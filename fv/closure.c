/*
** closure.c: the granular closures of thesis ch. 2 (closure.h).
**
** Closed forms.  The thesis defines the yield parts multiplicatively,
** eta = eta_k + eta_y = eta_k (1 + p_y/p_k) (eq. 2.17, 2.27), and likewise
** lambda and eps.  Evaluated so, c -> 0 and T -> 0 form 0/0 (p_k = c g T).
** With Y = Theta(c - c0) T0 (c - c0), so that p_y = Y g, the quotient
** p_y/p_k = Y/(c T) cancels against the factors of the kinetic parts:
**
**   eta    = eta0 g (c sqrt T + Y/sqrt T)
**   lambda = lambda0 g (c sqrt T + Y/sqrt T)
**   eps    = eps0 g (sqrt T + Y/(c sqrt T))
**
** The Y terms are added only when Y > 0, which implies c > c0 >= 0, so
** c = 0 gives finite values (eta = lambda = 0, eps = eps0 sqrt T), T = 0
** without yield gives 0, and nothing divides by zero anywhere in the
** domain of closure.h.  With yield the viscosities and eps diverge like
** 1/sqrt T as T -> 0: that is the physics (a resting pile is held by an
** infinite viscosity, thesis §2.2.4.2), and the solver clamps T >= T_min.
**
** eps_y.  eps_k p_y/p_k = eps0 Y g/(c sqrt T); eq. 2.29 prints
** eps0 Y g/sqrt T, without the 1/c.  We keep the multiplicative form
** eps = eps_k (1 + p_y/p_k), which the model overview repeats
** (spec §1.3 [?]), and so the sink eps c T = eps0 g sqrt T (c T + Y).
**
** dp/dc.  d(c g)/dc = g^2 (because g + c g' = g^2, g' = g^2/c_max) and
** d(Y g)/dc = T0 g (1 + (c - c0) g/c_max) above c0.  p is continuous at
** c0 but its derivative jumps by T0 g(c0); at c = c0 exactly we take the
** right-hand value, the larger, so that the sound speed (and a Courant
** number built on it) is never underestimated at the kink.
**
** Eq. 2.24 as extracted (seed L763-767) reads, numerators above
** denominators and the lone "2" the exponent of e in (1 - e^2):
**
**   eps0 = 8/(sqrt(pi) d) (1 - e^2) [1 + 3 (1 - e)(1 - 2 e^2) / (81 - 17 e + 30 e^2 (1 - e))]
**
** the Garzo-Dufty cooling rate (the bracket is 1 + (3/16) a2 with their
** a2 = 16 (1-e)(1-2e^2)/(81 - 17e + 30e^2(1-e))); units 1/m (spec
** correction 6).
**
** Homogeneous cooling [OURS: the thesis gives no solution].  With
** uniform c and u = 0 the temperature equation (eq. 2.39) is
** c dT/dt = -eps c T.  Write a = eps0 g, b = Y/c, s = sqrt T: then
** ds/dt = -(a/2)(s^2 + b).  With b = 0: s = s0/(1 + s0 a t/2).  With
** b > 0, q = tan(a sqrt(b) t/2)/sqrt(b):
**
**   s = (s0 - b q)/(1 + s0 q)       (-> the b = 0 form as b -> 0)
**
** until s reaches 0 at t* = 2 atan(s0/sqrt b)/(a sqrt b); afterwards T = 0
** (the yield stress arrests the grains in finite time: dT/dt = 0 at
** T = 0, and T = 0 is the solution that stays non-negative).  The ODE
** solver integrates dT/dt = -eps T through closure_eps with rk8pd to a
** relative tolerance of 1e-12; its right-hand side is 0 for T <= 0
** (stages that overshoot the arrest) and the result is clamped to >= 0.
** With yield the error control also has an absolute floor of 1e-20 Tinit:
** a purely relative one never lets a step cross the arrest, where T -> 0
** (GSL fails there).  Without yield T decays like 1/t^2 and never
** reaches 0, so the control stays purely relative.  The GSL error
** handler is switched off around the calls (GSL's default aborts), as in
** common/shape.c.
*/
#include "closure.h"

#include <float.h>
#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#define CLOSURE_PI 3.14159265358979323846
#define COOL_EPSREL 1e-12
#define COOL_EPSABS 1e-20 /* times Tinit, with yield only */
#define COOL_NMAX 1000000

/* eq. 2.15 */
static double gfac(const GranCoeffs *k, double c) { return k->cmax / (k->cmax - c); }

/* Y = p_y/g (eq. 2.26): 0 at and below c0. */
static double yield_part(const GranCoeffs *k, double c)
{
    return c > k->c0 ? k->T0 * (c - k->c0) : 0;
}

/* c sqrt T + Y/sqrt T: eta/(eta0 g) and lambda/(lambda0 g). */
static double visc_factor(double c, double T, double Y)
{
    double s = sqrt(T);
    return Y > 0 ? c * s + Y / s : c * s;
}

/* sqrt T + Y/(c sqrt T): eps/(eps0 g). */
static double eps_factor(double c, double T, double Y)
{
    double s = sqrt(T);
    return Y > 0 ? s + Y / (c * s) : s;
}

/* dp/dc at fixed T (right-hand value at c0). */
static double dpdc(const GranCoeffs *k, double c, double T, double g)
{
    double d = T * g * g;
    if (c >= k->c0) d += k->T0 * g * (1 + (c - k->c0) * g / k->cmax);
    return d;
}

void closure_eval(const GranCoeffs *k, double c, double T, GranClosure *out)
{
    double g = gfac(k, c), Y = yield_part(k, c), v = visc_factor(c, T, Y);
    out->g = g;
    out->pk = c * g * T;  /* eq. 2.20 */
    out->py = Y * g;      /* eq. 2.26 */
    out->p = out->pk + out->py;
    out->eta = k->eta0 * g * v;
    out->lambda = k->lambda0 * g * v;
    out->eps = k->eps0 * g * eps_factor(c, T, Y);
    out->dpdc = dpdc(k, c, T, g);
}

double closure_pressure(const GranCoeffs *k, double c, double T)
{
    return gfac(k, c) * (c * T + yield_part(k, c));
}

double closure_eta(const GranCoeffs *k, double c, double T)
{
    return k->eta0 * gfac(k, c) * visc_factor(c, T, yield_part(k, c));
}

double closure_lambda(const GranCoeffs *k, double c, double T)
{
    return k->lambda0 * gfac(k, c) * visc_factor(c, T, yield_part(k, c));
}

double closure_eps(const GranCoeffs *k, double c, double T)
{
    return k->eps0 * gfac(k, c) * eps_factor(c, T, yield_part(k, c));
}

double closure_sound_speed(const GranCoeffs *k, double c, double T)
{
    return sqrt(dpdc(k, c, T, gfac(k, c)));
}

/* The rest profile (closure.h).  Above and below c0 the enthalpy is linear
   in s(v) = v + e^v, with slopes T + B and T, so a potential difference
   moves s by phi over the slope, with a change of slope where the profile
   crosses c0; each case below is written as a difference from the source
   (never as h itself), so that nothing cancels when T is small. */
static int has_yield(const GranCoeffs *k) { return k->T0 > 0 && k->c0 < k->cmax; }

static double yield_B(const GranCoeffs *k) { return k->T0 * (1 - k->c0 / k->cmax); }

double closure_logit(const GranCoeffs *k, double c)
{
    if (c <= 0) return -INFINITY;
    return c < k->cmax ? log(c / (k->cmax - c)) : INFINITY;
}

double closure_c_of_logit(const GranCoeffs *k, double v) { return v == -INFINITY ? 0 : k->cmax / (1 + exp(-v)); }

static int above_c0(const GranCoeffs *k, double v) { return has_yield(k) && v > closure_logit(k, k->c0); }

double closure_pressure_logit(const GranCoeffs *k, double v, double T)
{
    if (v == -INFINITY) return 0;
    double ev = exp(v);
    return above_c0(k, v) ? k->cmax * (T + yield_B(k)) * ev - k->T0 * k->c0 : k->cmax * T * ev;
}

double closure_logit_of_pressure(const GranCoeffs *k, double p, double T)
{
    if (!(p > 0)) return -INFINITY;
    double v0 = closure_logit(k, k->c0);
    if (has_yield(k) && p > k->cmax * T * exp(v0)) return log((p + k->T0 * k->c0) / (k->cmax * (T + yield_B(k))));
    return T > 0 ? log(p / (k->cmax * T)) : -INFINITY;
}

double closure_dpdc_logit(const GranCoeffs *k, double v, double T)
{
    double g = 1 + exp(v);
    return g * g * (above_c0(k, v) ? T + yield_B(k) : T);
}

/* The v with v + e^v = s: Newton's method (v + e^v is convex and
   increasing, so from either side of the root the iterates converge)
   from a start that depends on s only. */
static double inverse_s(double s)
{
    if (!isfinite(s) || s < -700) return s; /* e^v below the last double */
    double v = s > 1 ? log(s) : s - 1;
    for (int it = 0; it < 64; it++) {
        double ev = exp(v), dv = (v + ev - s) / (1 + ev);
        v -= dv;
        if (fabs(dv) <= 2 * DBL_EPSILON * (1 + fabs(v))) break;
    }
    return v;
}

double closure_profile_logit(const GranCoeffs *k, double v, double T, double phi)
{
    if (v == -INFINITY || phi == 0) return v;
    double sv = v + exp(v), v0 = closure_logit(k, k->c0), s0 = v0 + exp(v0), A = T + yield_B(k);
    if (above_c0(k, v)) {
        if (phi >= -A * (sv - s0)) return inverse_s(sv + phi / A);
        return T > 0 ? inverse_s(s0 + (A * (sv - s0) + phi) / T) : -INFINITY;
    }
    if (has_yield(k) && phi >= T * (s0 - sv)) return inverse_s(s0 + (phi - T * (s0 - sv)) / A);
    return T > 0 ? inverse_s(sv + phi / T) : v;
}

/* eq. 2.24 */
double closure_eps0_from_grain(double d, double e)
{
    double bracket = 1 + 3 * (1 - e) * (1 - 2 * e * e) / (81 - 17 * e + 30 * e * e * (1 - e));
    return 8 / (sqrt(CLOSURE_PI) * d) * (1 - e * e) * bracket;
}

/* eq. 2.25 */
double closure_friction_angle(double eps0, double eta0) { return atan(sqrt(eps0 * eta0)); }

double closure_cooling_exact(const GranCoeffs *k, double c, double Tinit, double t)
{
    double a = k->eps0 * gfac(k, c), s0 = sqrt(Tinit), b = yield_part(k, c);
    if (!(b > 0)) {
        double r = 1 + a * s0 * t / 2;
        return Tinit / (r * r);
    }
    b /= c;
    double rb = sqrt(b), B = a * rb * t / 2;
    if (B >= atan2(s0, rb)) return 0;  /* t >= t*: arrested */
    double q = tan(B) / rb, s = (s0 - b * q) / (1 + s0 * q);
    return s > 0 ? s * s : 0;
}

typedef struct CoolCtx {
    const GranCoeffs *k;
    double c;
} CoolCtx;

/* dT/dt = -eps(c, T) T; 0 at T <= 0 (past the arrest). */
static int cool_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const CoolCtx *x = params;
    dydt[0] = y[0] > 0 ? -closure_eps(x->k, x->c, y[0]) * y[0] : 0;
    return GSL_SUCCESS;
}

/* The input of closure_cooling_ode, or -1 with e filled. */
static int cool_check(const GranCoeffs *k, double c, double Tinit, double t, Err *e)
{
    if (!(k->cmax > 0) || !(k->eps0 >= 0) || !(k->T0 >= 0) || !(k->c0 >= 0) || !isfinite(k->eps0) ||
        !isfinite(k->T0))
        return err_set(e, NULL, 0, "closure_cooling_ode: coefficients out of range (cmax %g, eps0 %g, c0 %g, T0 %g)",
                       k->cmax, k->eps0, k->c0, k->T0);
    if (!(c >= 0 && c < k->cmax))
        return err_set(e, NULL, 0, "closure_cooling_ode: c = %g is outside [0, cmax = %g)", c, k->cmax);
    if (!(Tinit >= 0) || !isfinite(Tinit))
        return err_set(e, NULL, 0, "closure_cooling_ode: initial temperature %g is not a finite T >= 0", Tinit);
    if (!(t >= 0) || !isfinite(t))
        return err_set(e, NULL, 0, "closure_cooling_ode: end time %g is not a finite t >= 0", t);
    return 0;
}

int closure_cooling_ode(const GranCoeffs *k, double c, double Tinit, double t, double *T, Err *e)
{
    if (cool_check(k, c, Tinit, t, e)) return -1;
    if (t == 0 || Tinit == 0) {
        *T = Tinit;
        return 0;
    }
    CoolCtx x = {k, c};
    gsl_odeiv2_system sys = {cool_rhs, NULL, 1, &x};
    /* purely relative without yield (T > 0 for ever); with yield an absolute
       floor far below, or the steps would shrink without end at the arrest */
    double epsabs = yield_part(k, c) > 0 ? Tinit * COOL_EPSABS : 0;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, t * 1e-3, epsabs, COOL_EPSREL);
    if (!d) {
        gsl_set_error_handler(old);
        return err_set(e, NULL, 0, "closure_cooling_ode: GSL could not allocate the ODE driver");
    }
    gsl_odeiv2_driver_set_nmax(d, COOL_NMAX);
    double t0 = 0, y = Tinit;
    int st = gsl_odeiv2_driver_apply(d, &t0, t, &y);
    gsl_odeiv2_driver_free(d);
    gsl_set_error_handler(old);
    if (st != GSL_SUCCESS)
        return err_set(e, NULL, 0, "closure_cooling_ode: GSL stopped at t = %g of %g: %s", t0, t, gsl_strerror(st));
    *T = y > 0 ? y : 0;
    return 0;
}
