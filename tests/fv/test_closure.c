/*
** test_closure.c: the granular closures (fv/closure.h): hand-computed
** values in the kinetic and the yield regime, the closed forms against
** the thesis's multiplicative forms, the limits c -> 0 and T -> 0, the
** kink at c0, dp/dc against finite differences, eq. 2.24-2.25, and the
** homogeneous cooling: the GSL ODE against the closed forms and against
** t = integral of dT/(eps T) by GSL quadrature (code the ODE does not use);
** the rest profiles of the well-balanced gravity against the enthalpy
** integral of dp/c by GSL quadrature.
*/
#include "closure.h"
#include "test.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#define PI 3.14159265358979323846

/* Small numbers for hand computation: g(0.4) = 2, g(0.6) = 4, g(0.7) = 8. */
static const GranCoeffs HAND = {0.5, 0.25, 2, 0.8, 0.5, 1, 2.0 / 3};
/* thesis §5.2.2 (kinetic: T0 = 0) and §5.3.2 (yield) */
static const GranCoeffs S522 = {0.00102573, 0.00034, 216.649, 0.8, 0.3, 0, 2.0 / 3};
static const GranCoeffs S532 = {0.0035, 0.00034, 63.4921, 0.64, 0.3, 10, 2.0 / 3};

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* the largest relative error of expect_all's checks since the last reset */
static double hand_worst;

/* |a/b - 1| <= tol */
#define REL(a, b, tol)                                                                              \
    do {                                                                                            \
        double ra_ = (a), rb_ = (b);                                                                \
        hand_worst = fmax(hand_worst, rel(ra_, rb_));                                               \
        EXPECT(rel(ra_, rb_) <= (tol), "%s = %.17g, expected %.17g (rel %.2e > %g)", #a, ra_, rb_, \
               rel(ra_, rb_), (double)(tol));                                                       \
    } while (0)

/* closure_eval and the single functions against the expected values. */
static void expect_all(const GranCoeffs *k, double c, double T, double g, double pk, double py, double eta,
                       double lambda, double eps, double dpdc, double tol)
{
    GranClosure o;
    closure_eval(k, c, T, &o);
    REL(o.g, g, tol);
    REL(o.pk, pk, tol);
    if (py == 0) EXPECT(o.py == 0, "py = %g, expected 0", o.py);
    else REL(o.py, py, tol);
    REL(o.p, pk + py, tol);
    REL(o.eta, eta, tol);
    REL(o.lambda, lambda, tol);
    REL(o.eps, eps, tol);
    REL(o.dpdc, dpdc, tol);
    REL(closure_pressure(k, c, T), pk + py, tol);
    REL(closure_eta(k, c, T), eta, tol);
    REL(closure_lambda(k, c, T), lambda, tol);
    REL(closure_eps(k, c, T), eps, tol);
    REL(closure_sound_speed(k, c, T), sqrt(dpdc), tol);
}

/* c < c0: p = c g T, eta = eta0 sqrt(T) c g, eps = eps0 sqrt(T) g, dp/dc = T g^2 (relative 4e-16). */
TEST(values_kinetic)
{
    hand_worst = 0;
    /* c = 0.4, T = 1/4: g = 2 */
    expect_all(&HAND, 0.4, 0.25, 2, 0.2, 0, 0.2, 0.1, 2, 1, 4e-16);
    /* c = 0.2, T = 9: g = 4/3, p = 2.4, eta = 0.4, eps = 8, dp/dc = 16 */
    expect_all(&HAND, 0.2, 9, 4.0 / 3, 2.4, 0, 0.4, 0.2, 8, 16, 4e-16);
    /* above c0 with T0 = 0 (thesis §5.2.2): still kinetic; c = 0.4, T = 4, g = 2 */
    expect_all(&S522, 0.4, 4, 2, 3.2, 0, 0.00102573 * 2 * 0.4 * 2, 0.00034 * 2 * 0.4 * 2, 216.649 * 2 * 2, 16,
               4e-16);
    printf("  values_kinetic: largest relative error %.2e\n", hand_worst);
}

/* c > c0: py = T0 (c - c0) g, eta = eta0 g (c sqrt T + T0 (c - c0)/sqrt T),
   eps = eps0 g (sqrt T + T0 (c - c0)/(c sqrt T)); relative 4e-15: c - c0 amplifies the
   rounding of the decimal inputs by c/(c - c0) <= 3.5. */
TEST(values_yield)
{
    hand_worst = 0;
    /* c = 0.6, T = 1/4: g = 4, pk = 0.6, py = 0.4, eta = 2 (0.3 + 0.2) = 1,
       eps = 8 (1/2 + 1/3) = 20/3, dp/dc = 4 + 4 (1 + 0.5) = 10 */
    expect_all(&HAND, 0.6, 0.25, 4, 0.6, 0.4, 1, 0.5, 20.0 / 3, 10, 4e-15);
    /* c = 0.7, T = 4: g = 8, pk = 22.4, py = 1.6, eta = 4 (1.4 + 0.1) = 6,
       eps = 16 (2 + 1/7) = 240/7, dp/dc = 256 + 8 (1 + 2) = 280 */
    expect_all(&HAND, 0.7, 4, 8, 22.4, 1.6, 6, 3, 240.0 / 7, 280, 4e-15);
    /* thesis §5.3.2, c = 0.48, T = 0.01: g = 4, Y = 1.8, pk = 0.0192, py = 7.2,
       eta = 0.0035 * 4 (0.048 + 18), eps = 63.4921 * 4 (0.1 + 37.5),
       dp/dc = 0.16 + 40 (1 + 0.18 * 4/0.64) = 85.16 */
    expect_all(&S532, 0.48, 0.01, 4, 0.0192, 7.2, 0.014 * 18.048, 0.00136 * 18.048, 63.4921 * 4 * 37.6, 85.16,
               4e-15);
    printf("  values_yield: largest relative error %.2e\n", hand_worst);
}

/* The thesis's forms eta_k (1 + py/pk) etc., where pk > 0. */
static void naive(const GranCoeffs *k, double c, double T, GranClosure *o)
{
    double g = 1 / (1 - c / k->cmax);
    o->g = g;
    o->pk = c * g * T;
    o->py = (c > k->c0 ? 1 : 0) * k->T0 * (c - k->c0) * g;
    o->p = o->pk + o->py;
    o->eta = k->eta0 * sqrt(T) * c * g * (1 + o->py / o->pk);
    o->lambda = k->lambda0 * sqrt(T) * c * g * (1 + o->py / o->pk);
    o->eps = k->eps0 * sqrt(T) * g * (1 + o->py / o->pk);
}

/* Closed forms = multiplicative forms to relative 1e-14 over c in (0, cmax), T in [1e-8, 1e4]. */
TEST(closed_vs_naive)
{
    const GranCoeffs *ks[] = {&HAND, &S522, &S532};
    double worst = 0;
    int n = 0;
    for (int q = 0; q < 3; q++)
        for (int i = 1; i < 40; i++) {
            double c = ks[q]->cmax * i / 40.0;
            for (double T = 1e-8; T <= 1e4; T *= 10) {
                GranClosure a, b;
                closure_eval(ks[q], c, T, &a);
                naive(ks[q], c, T, &b);
                double d[] = {rel(a.p, b.p), rel(a.eta, b.eta), rel(a.lambda, b.lambda), rel(a.eps, b.eps)};
                for (int j = 0; j < 4; j++) {
                    EXPECT(d[j] <= 1e-14, "coefficient set %d, c = %g, T = %g: closure %d differs by %.2e", q, c,
                           T, j, d[j]);
                    worst = fmax(worst, d[j]);
                }
                n++;
            }
        }
    printf("  closed_vs_naive: %d points, largest relative difference %.2e\n", n, worst);
}

static int finite_all(const GranClosure *o)
{
    return isfinite(o->g) && isfinite(o->pk) && isfinite(o->py) && isfinite(o->p) && isfinite(o->eta) &&
           isfinite(o->lambda) && isfinite(o->eps) && isfinite(o->dpdc);
}

/* c = 0 exactly and c -> 0: finite, eta = lambda = 0, eps = eps0 sqrt T; with c0 = 0 the
   yield part of eps tends to eps0 T0/sqrt T (relative 1e-14). */
TEST(limit_c0)
{
    GranClosure o;
    closure_eval(&S532, 0, 0.25, &o);
    EXPECT(finite_all(&o), "not finite at c = 0");
    EXPECT(o.p == 0 && o.eta == 0 && o.lambda == 0, "p %g eta %g lambda %g at c = 0", o.p, o.eta, o.lambda);
    NEAR(o.eps, 63.4921 * 0.5, 1e-14 * 63.4921);
    NEAR(o.dpdc, 0.25, 1e-16);
    GranCoeffs k = S532;
    k.c0 = 0; /* yield from the first grain */
    closure_eval(&k, 0, 0.25, &o);
    EXPECT(finite_all(&o) && o.py == 0, "c0 = 0, c = 0: not finite or py = %g", o.py);
    closure_eval(&k, 1e-300, 0.25, &o);
    EXPECT(finite_all(&o), "c0 = 0, c = 1e-300: not finite");
    REL(o.eps, 63.4921 * (0.5 + 10 / 0.5), 1e-14);
    REL(o.eta, 0.0035 * 1e-300 * (0.5 + 10 / 0.5), 1e-14);
    EXPECT(closure_eps(&k, 1e-300, 0.25) == o.eps, "closure_eps differs from closure_eval");
}

/* T = 0 without yield: every closure 0 exactly, nothing NaN; T -> 0 like sqrt T.  With
   yield p and dp/dc stay finite at T = 0. */
TEST(limit_T0)
{
    GranClosure o;
    closure_eval(&HAND, 0.4, 0, &o);
    EXPECT(finite_all(&o) && o.p == 0 && o.eta == 0 && o.lambda == 0 && o.eps == 0 && o.dpdc == 0,
           "c < c0, T = 0: p %g eta %g lambda %g eps %g dpdc %g", o.p, o.eta, o.lambda, o.eps, o.dpdc);
    closure_eval(&S522, 0.7, 0, &o); /* c > c0 but T0 = 0 */
    EXPECT(finite_all(&o) && o.p == 0 && o.eta == 0 && o.lambda == 0 && o.eps == 0 && o.dpdc == 0,
           "T0 = 0, T = 0: p %g eta %g lambda %g eps %g dpdc %g", o.p, o.eta, o.lambda, o.eps, o.dpdc);
    closure_eval(&HAND, 0.4, 1e-300, &o);
    REL(o.eta, 0.5 * 2 * 0.4 * 1e-150, 1e-15);
    REL(o.eps, 2 * 2 * 1e-150, 1e-15);
    closure_eval(&HAND, 0.6, 0, &o);
    EXPECT(isfinite(o.p) && isfinite(o.dpdc), "yield, T = 0: p %g dpdc %g", o.p, o.dpdc);
    REL(o.p, 0.4, 1e-15);
    REL(o.dpdc, 6, 1e-15);
}

/* Continuity at c0: p, eta, lambda, eps within 1e-8 relative across c0 -+ 1e-10 and the
   values at c0 are the kinetic ones; dp/dc jumps by T0 g(c0) and takes the right value at c0. */
TEST(continuity_c0)
{
    const double T = 0.3, d = 1e-10, c0 = HAND.c0;
    GranClosure lo, at, hi;
    closure_eval(&HAND, c0 - d, T, &lo);
    closure_eval(&HAND, c0, T, &at);
    closure_eval(&HAND, c0 + d, T, &hi);
    double worst = 0;
    double pairs[][3] = {{lo.p, at.p, hi.p}, {lo.eta, at.eta, hi.eta}, {lo.lambda, at.lambda, hi.lambda},
                         {lo.eps, at.eps, hi.eps}};
    for (int j = 0; j < 4; j++) {
        worst = fmax(worst, fmax(rel(pairs[j][0], pairs[j][1]), rel(pairs[j][2], pairs[j][1])));
        EXPECT(rel(pairs[j][0], pairs[j][1]) <= 1e-8 && rel(pairs[j][2], pairs[j][1]) <= 1e-8,
               "closure %d jumps at c0: %.17g %.17g %.17g", j, pairs[j][0], pairs[j][1], pairs[j][2]);
    }
    double g0 = 1 / (1 - c0 / HAND.cmax);
    EXPECT(at.py == 0, "py(c0) = %g", at.py);
    REL(at.eta, HAND.eta0 * sqrt(T) * c0 * g0, 1e-15);
    REL(at.eps, HAND.eps0 * sqrt(T) * g0, 1e-15);
    REL(hi.dpdc - lo.dpdc, HAND.T0 * g0, 1e-6);
    REL(at.dpdc, T * g0 * g0 + HAND.T0 * g0, 1e-15);
    printf("  continuity_c0: largest relative change across c0 -+ 1e-10: %.2e; dp/dc jump %.10g (T0 g = %.10g)\n",
           worst, hi.dpdc - lo.dpdc, HAND.T0 * g0);
}

/* dp/dc against the centred difference of closure_pressure (h = 1e-6 cmax), relative 1e-6,
   away from c0 in both regimes. */
TEST(dpdc_fd)
{
    const GranCoeffs *ks[] = {&HAND, &S522, &S532};
    double worst = 0;
    for (int q = 0; q < 3; q++)
        for (int i = 1; i < 20; i++) {
            double c = ks[q]->cmax * i / 20.0, h = 1e-6 * ks[q]->cmax;
            if (fabs(c - ks[q]->c0) < 2 * h) continue;
            for (double T = 1e-3; T <= 1e3; T *= 10) {
                double fd = (closure_pressure(ks[q], c + h, T) - closure_pressure(ks[q], c - h, T)) / (2 * h);
                GranClosure o;
                closure_eval(ks[q], c, T, &o);
                EXPECT(rel(o.dpdc, fd) <= 1e-6, "set %d, c = %g, T = %g: dpdc %.12g, difference %.12g", q, c, T,
                       o.dpdc, fd);
                worst = fmax(worst, rel(o.dpdc, fd));
            }
        }
    printf("  dpdc_fd: largest relative difference %.2e\n", worst);
}

/* eq. 2.24: 0 for e = 1; hand values at e = 0, 1/2, 1/sqrt 2 (relative 1e-15). */
TEST(eps0_from_grain)
{
    const double d = 1e-3, pre = 8 / (sqrt(PI) * d);
    EXPECT(closure_eps0_from_grain(d, 1) == 0, "e = 1: %g", closure_eps0_from_grain(d, 1));
    REL(closure_eps0_from_grain(d, 0), pre * 28 / 27, 1e-15);           /* 1 + 3/81 */
    REL(closure_eps0_from_grain(d, 0.5), pre * 0.75 * 308 / 305, 1e-15); /* 1 + 0.75/76.25 */
    REL(closure_eps0_from_grain(d, sqrt(0.5)), pre * 0.5, 1e-15);       /* 1 - 2e^2 = 0 */
    REL(closure_eps0_from_grain(2 * d, 0.5), pre * 0.75 * 308 / 305 / 2, 1e-15);
}

/* eq. 2.25: atan(sqrt(eps0 eta0)); the thesis's §5.2.2 and §5.3.2 sets give atan(sqrt(2/9))
   to the printed digits (relative 1e-5). */
TEST(friction_angle)
{
    REL(closure_friction_angle(1, 1), PI / 4, 1e-15);
    REL(closure_friction_angle(3, 1), PI / 3, 1e-15);
    REL(closure_friction_angle(S522.eps0, S522.eta0), atan(sqrt(2.0 / 9)), 1e-5);
    REL(closure_friction_angle(S532.eps0, S532.eta0), atan(sqrt(2.0 / 9)), 1e-5);
    printf("  friction_angle: §5.2.2 %.9f rad, §5.3.2 %.9f rad, atan(sqrt(2/9)) = %.9f rad (%.4f deg)\n",
           closure_friction_angle(S522.eps0, S522.eta0), closure_friction_angle(S532.eps0, S532.eta0),
           atan(sqrt(2.0 / 9)), atan(sqrt(2.0 / 9)) * 180 / PI);
}

/* No yield: the ODE equals Tinit/(1 + eps0 g sqrt(Tinit) t/2)^2 to relative 1e-10, t from
   1e-4 to 1e6 (T down to 1e-16 Tinit). */
TEST(cooling_kinetic)
{
    struct { const GranCoeffs *k; double c, Ti; } cs[] = {
        {&S522, 0.3, 1}, {&S522, 0.7, 0.01}, {&HAND, 0.4, 2}, {&HAND, 0.5, 0.25}, {&S532, 0.1, 0.005}};
    double worst = 0;
    Err e;
    for (int q = 0; q < 5; q++)
        for (double t = 1e-4; t <= 1e6; t *= 10) {
            double T, g = 1 / (1 - cs[q].c / cs[q].k->cmax), r = 1 + cs[q].k->eps0 * g * sqrt(cs[q].Ti) * t / 2;
            EXPECT(closure_cooling_ode(cs[q].k, cs[q].c, cs[q].Ti, t, &T, &e) == 0, "%s", e.msg);
            REL(T, cs[q].Ti / (r * r), 1e-10);
            REL(closure_cooling_exact(cs[q].k, cs[q].c, cs[q].Ti, t), cs[q].Ti / (r * r), 1e-15);
            worst = fmax(worst, rel(T, cs[q].Ti / (r * r)));
        }
    double T = -1;
    EXPECT(closure_cooling_ode(&HAND, 0.4, 2, 0, &T, &e) == 0 && T == 2, "t = 0: T = %g", T);
    EXPECT(closure_cooling_ode(&HAND, 0.4, 0, 1, &T, &e) == 0 && T == 0, "Tinit = 0: T = %g", T);
    printf("  cooling_kinetic: ODE against the exact solution, largest relative error %.2e\n", worst);
}

/* t(T) = integral from T to Tinit of dT'/(eps T'), eps the thesis's form written here. */
typedef struct { const GranCoeffs *k; double c; } Quad;

static double inv_rate(double T, void *p)
{
    const Quad *x = p;
    const GranCoeffs *k = x->k;
    double g = 1 / (1 - x->c / k->cmax), pk = x->c * g * T, py = k->T0 * (x->c - k->c0) * g;
    return 1 / (k->eps0 * sqrt(T) * g * (1 + py / pk) * T);
}

static double time_to(const GranCoeffs *k, double c, double Tinit, double T)
{
    Quad x = {k, c};
    gsl_function F = {inv_rate, &x};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    double r = NAN, err;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int st = gsl_integration_qags(&F, T, Tinit, 0, 1e-13, 1000, w, &r, &err);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    return st == GSL_SUCCESS ? r : NAN;
}

/* With yield: T reaches 0 at t* = 2 atan(sqrt(Tinit/b))/(eps0 g sqrt b), b = T0 (c - c0)/c.
   Before t*: the ODE equals the closed form (relative 1e-10 up to 0.9 t*, absolute 1e-12 Tinit
   after) and both satisfy t = integral dT/(eps T) by GSL quadrature (relative 1e-8); after
   t*: T = 0 (absolute 1e-12 Tinit). */
TEST(cooling_yield)
{
    struct { const GranCoeffs *k; double c, Ti; } cs[] = {{&HAND, 0.6, 1}, {&HAND, 0.75, 0.01}, {&S532, 0.5, 0.005},
                                                         {&S532, 0.31, 2}};
    const double fr[] = {0.01, 0.1, 0.5, 0.9, 0.99, 0.999, 1.5, 3};
    double worst_exact = 0, worst_int = 0, worst_after = 0;
    Err e;
    for (int q = 0; q < 4; q++) {
        const GranCoeffs *k = cs[q].k;
        double c = cs[q].c, Ti = cs[q].Ti, g = 1 / (1 - c / k->cmax), b = k->T0 * (c - k->c0) / c;
        double ts = 2 * atan(sqrt(Ti / b)) / (k->eps0 * g * sqrt(b));
        for (int j = 0; j < 8; j++) {
            double t = fr[j] * ts, T = -1, Tx = closure_cooling_exact(k, c, Ti, t);
            EXPECT(closure_cooling_ode(k, c, Ti, t, &T, &e) == 0, "%s", e.msg);
            if (fr[j] > 1) {
                EXPECT(Tx == 0, "set %d: exact T(%g t*) = %g", q, fr[j], Tx);
                NEAR(T, 0, 1e-12 * Ti);
                worst_after = fmax(worst_after, T / Ti);
                continue;
            }
            if (fr[j] <= 0.9) {
                REL(T, Tx, 1e-10);
                worst_exact = fmax(worst_exact, rel(T, Tx));
            } else {
                NEAR(T, Tx, 1e-12 * Ti);
            }
            double ti = time_to(k, c, Ti, T), tx = time_to(k, c, Ti, Tx);
            REL(ti, t, 1e-8);
            REL(tx, t, 1e-8);
            worst_int = fmax(worst_int, fmax(rel(ti, t), rel(tx, t)));
        }
    }
    printf("  cooling_yield: ODE against the closed form %.2e (relative, t <= 0.9 t*); integral time of the ODE's and "
           "the closed form's T against t %.2e; T/Tinit after t* %.2e\n",
           worst_exact, worst_int, worst_after);
}

/* Bad input: -1 and a message naming the quantity. */
TEST(cooling_errors)
{
    double T = 7;
    Err e;
    GranCoeffs bad = HAND;
    bad.cmax = 0;
    EXPECT(closure_cooling_ode(&HAND, 0.8, 1, 1, &T, &e) == -1, "c = cmax accepted");
    CONTAINS(e.msg, "c = 0.8 is outside");
    EXPECT(closure_cooling_ode(&HAND, -0.1, 1, 1, &T, &e) == -1, "c < 0 accepted");
    EXPECT(closure_cooling_ode(&HAND, NAN, 1, 1, &T, &e) == -1, "c = NaN accepted");
    EXPECT(closure_cooling_ode(&HAND, 0.4, -1, 1, &T, &e) == -1, "Tinit < 0 accepted");
    CONTAINS(e.msg, "initial temperature");
    EXPECT(closure_cooling_ode(&HAND, 0.4, 1, -1, &T, &e) == -1, "t < 0 accepted");
    CONTAINS(e.msg, "end time");
    EXPECT(closure_cooling_ode(&HAND, 0.4, 1, INFINITY, &T, &e) == -1, "t = inf accepted");
    EXPECT(closure_cooling_ode(&bad, 0.4, 1, 1, &T, &e) == -1, "cmax = 0 accepted");
    CONTAINS(e.msg, "coefficients");
    EXPECT(T == 7, "T written on failure: %g", T);
}

/* The logit and the pressure through it against closure_pressure, and the
   pressure's inverse (relative 1e-13). */
TEST(logit)
{
    const GranCoeffs *ks[] = {&HAND, &S522, &S532};
    const double cs[] = {1e-9, 0.01, 0.2, 0.31, 0.45, 0.55, 0.62, 0.7, 0.79}, Ts[] = {1e-12, 1e-4, 0.5, 3};
    double worst = 0;
    for (int q = 0; q < 3; q++)
        for (int i = 0; i < 9; i++)
            for (int j = 0; j < 4; j++) {
                const GranCoeffs *k = ks[q];
                double c = cs[i] * k->cmax / 0.8, T = Ts[j], v = closure_logit(k, c), p = closure_pressure(k, c, T);
                REL(closure_c_of_logit(k, v), c, 1e-14);
                REL(closure_pressure_logit(k, v, T), p, 1e-13);
                REL(closure_logit_of_pressure(k, p, T), v, 1e-13 / fmin(1, fabs(v)) + 1e-13);
                if (fabs(c - k->c0) > 1e-3) REL(closure_dpdc_logit(k, v, T), pow(closure_sound_speed(k, c, T), 2), 1e-13);
                worst = fmax(worst, rel(closure_pressure_logit(k, v, T), p));
            }
    EXPECT(closure_logit(&HAND, 0) == -INFINITY && closure_c_of_logit(&HAND, -INFINITY) == 0, "c = 0");
    EXPECT(closure_pressure_logit(&HAND, -INFINITY, 1) == 0, "p(c = 0)");
    printf("  logit: p through the logit against closure_pressure %.2e (relative)\n", worst);
}

/* dp/c at fixed T from c to d by GSL quadrature (split at c0, the kink). */
static double enthalpy_gap(const GranCoeffs *k, double T, double c, double d);

typedef struct { const GranCoeffs *k; double T; } HParams;

static double h_integrand(double c, void *ctx)
{
    const HParams *h = ctx;
    double a = closure_sound_speed(h->k, c, h->T);
    return a * a / c;
}

static double enthalpy_gap(const GranCoeffs *k, double T, double c, double d)
{
    HParams hp = {k, T};
    gsl_function F = {h_integrand, &hp};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    double lo = fmin(c, d), hi = fmax(c, d), sum = 0;
    double cut[3] = {lo, k->c0, hi};
    int n = k->c0 > lo && k->c0 < hi ? 2 : 1;
    if (n == 1) cut[1] = hi;
    for (int j = 0; j < n; j++) {
        double r, err;
        gsl_integration_qags(&F, cut[j], cut[j + 1], 0, 1e-13, 200, w, &r, &err);
        sum += r;
    }
    gsl_integration_workspace_free(w);
    return d >= c ? sum : -sum;
}

/* The rest profile: from c the enthalpy integral dp/c up to the profile's
   c at potential phi equals phi (GSL quadrature, relative 1e-9), also
   across c0 both ways; profiles compose, v(v(phi1), phi2) = v(phi1 +
   phi2) (the property that makes two sources of one rest state agree:
   pressure relative 1e-14). */
TEST(rest_profile)
{
    struct { const GranCoeffs *k; double c, T; } cs[] = {{&S532, 0.5, 0.01},  {&S532, 0.2, 0.5},  {&HAND, 0.6, 0.1},
                                                          {&HAND, 0.45, 0.02}, {&S522, 0.3, 0.3},  {&S532, 0.62, 1e-12},
                                                          {&HAND, 0.3, 1e-6}};
    const double phis[] = {-1, -0.3, -0.05, -1e-4, 1e-4, 0.05, 0.3, 1};
    double worst = 0, worst_comp = 0;
    int crossed = 0;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    for (int q = 0; q < 7; q++)
        for (int j = 0; j < 8; j++) {
            const GranCoeffs *k = cs[q].k;
            double c = cs[q].c, T = cs[q].T, phi = phis[j] * (T < 1e-3 && c < k->c0 ? T : 1), v = closure_logit(k, c);
            double vf = closure_profile_logit(k, v, T, phi), cf = closure_c_of_logit(k, vf);
            if (cf < 1e-6 || cf > k->cmax * (1 - 1e-9)) continue; /* beyond quadrature's reach */
            crossed += (c - k->c0) * (cf - k->c0) < 0;
            double gap = enthalpy_gap(k, T, c, cf);
            double tol = 1e-9 + 4e-16 * c / fabs(cf - c); /* c's last bits against the step in c */
            EXPECT(rel(gap, phi) <= tol, "set %d phi %g: integral %.17g (c %g -> %g)", q, phi, gap, c, cf);
            if (fabs(cf - c) > 1e-5) worst = fmax(worst, rel(gap, phi));
            double v2 = closure_profile_logit(k, closure_profile_logit(k, v, T, 0.4 * phi), T, 0.6 * phi);
            double pa = closure_pressure_logit(k, v2, T), pb = closure_pressure_logit(k, vf, T);
            EXPECT(rel(pa, pb) <= 1e-14 + 1e-15 * fabs(phi) * c / fmax(pb, 1e-300), "set %d phi %g: composed %.17g, direct %.17g", q, phi, pa, pb);
            worst_comp = fmax(worst_comp, rel(pa, pb));
        }
    gsl_set_error_handler(old);
    EXPECT(crossed >= 4, "only %d profiles cross c0", crossed);
    EXPECT(closure_profile_logit(&S532, -INFINITY, 1, 0.5) == -INFINITY, "an empty cell's profile filled");
    printf("  rest_profile: enthalpy integral against phi %.2e (relative, |dc| > 1e-5), composition %.2e, %d across c0\n", worst,
           worst_comp, crossed);
}

int main(void)
{
    RUN(values_kinetic);
    RUN(values_yield);
    RUN(closed_vs_naive);
    RUN(limit_c0);
    RUN(limit_T0);
    RUN(continuity_c0);
    RUN(dpdc_fd);
    RUN(eps0_from_grain);
    RUN(friction_angle);
    RUN(cooling_kinetic);
    RUN(cooling_yield);
    RUN(cooling_errors);
    RUN(logit);
    RUN(rest_profile);
    return test_summary();
}
