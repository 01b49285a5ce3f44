/*
** mms_check.c: the checks of make test (mms -check,
** tests/tools/solveGranular/test_mms.sh): the manufactured solution and
** the model's source hook (newtonian.h, "Sources").
**
**   exact_fd      the generated derivatives (mms_exact.c) against central
**                 differences of rho and u at 20 points of the disc and of
**                 the ball: grad rho, div(rho u u^T), lap u to 1e-5
**                 relative, div(rho u) = 0 to 1e-8; on the wall u = 0 and
**                 d rho/dn = 0 to 1e-12;
**   hook_none     a hook that returns zero integrals changes nothing: 30
**                 steps on the disc (N = 16) bit-identical to no hook;
**   hook_mass     a continuity source of 1 per unit volume (its integral
**                 V_c) on the closed disc: after 30 steps the mass grew by
**                 t x the volume and src_total says so, to 1e-12
**                 relative; the hook saw each step's start time and the
**                 model's time is the sum of the steps;
**   hook_fail     a hook that fails: gran_step fails with its message,
**                 the state and the time unchanged;
** model granular (mms_exact_gran.h):
**   gran_exact_fd   the generated sources against differences of fv/closure.h's
**                 closures (an independent evaluation of p, eta, lambda,
**                 eps) at 40 points of the disc and of the ball: s_m, s_T
**                 and the heating to 1e-5 relative, div(c u) = 0 to 1e-8;
**                 on the wall u = 0, dc/dn = dT/dn = 0 to 1e-8; c0 < c < cMax;
**   gran_hook_none  a zero hook (T_src included) changes nothing, bit for bit;
**   gran_hook_T   sources Q_c = 0.5 and Q_T = 1 per unit volume at rest
**                 with uniform c, T: one step gives c^1 = c + dt Q_c (to
**                 1e-14) and the implicit Euler T^1 = (c T^0/dt + Q_T)/
**                 (c^1/dt + eps c^1) in every cell to 1e-12, u stays 0;
**   gran_heat_cut the viscous heating of the face-based Jacobian at the exact
**                 state against K_T eta kappa:kappa on the disc cut and
**                 merged (N = 16, 32, 64; the heating is up to 2.5): the
**                 mean error over the cut cells <= 0.1 at N = 32 and
**                 falling by 0.7 to N = 64 (measured 0.061, 0.055, 0.030;
**                 eq. 4.65's alpha A_f/sum A_f weight: 0.30, 0.41, 0.40,
**                 not converging), over the whole cells halved (0.0053,
**                 0.0016).
*/
#include "mem.h"
#include "mms.h"
#include "test.h"

#include <math.h>

/* A pseudo-random number in [0, 1) (reproducible, no libc state). */
static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xffffff) / 16777216.0;
}

static void fd_rho_u(const Study *s, const double x[3], double *rho, double u[3])
{
    MmsPoint o;
    mms_exact(s, x, &o);
    *rho = o.rho;
    for (int k = 0; k < 3; k++) u[k] = o.u[k];
}

/* Relative difference, against a scale of at least 1. */
static double rdiff(double a, double b) { return fabs(a - b) / fmax(1, fabs(b)); }

/* Central differences at x against the generated values: the largest
   relative difference into *worst, the divergence of rho u into *div. */
static void fd_point(const Study *s, const double x[3], double *worst, double *div)
{
    const double h = 1e-4;
    MmsPoint o;
    mms_exact(s, x, &o);
    double conv[3] = {0, 0, 0}, lap[3] = {0, 0, 0}, rho0, u0[3];
    fd_rho_u(s, x, &rho0, u0);
    *div = 0;
    for (int j = 0; j < s->dim; j++) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, rp, rm, up[3], um[3];
        xp[j] += h;
        xm[j] -= h;
        fd_rho_u(s, xp, &rp, up);
        fd_rho_u(s, xm, &rm, um);
        *worst = fmax(*worst, rdiff((rp - rm) / (2 * h), o.grad_rho[j]));
        *div += (rp * up[j] - rm * um[j]) / (2 * h);
        for (int i = 0; i < 3; i++) {
            conv[i] += (rp * up[i] * up[j] - rm * um[i] * um[j]) / (2 * h);
            lap[i] += (up[i] - 2 * u0[i] + um[i]) / (h * h);
        }
    }
    for (int i = 0; i < 3; i++) *worst = fmax(*worst, fmax(rdiff(conv[i], o.conv[i]), rdiff(lap[i], o.lapu[i])));
}

TEST(exact_fd)
{
    unsigned seed = 7;
    for (int dim = 2; dim <= 3; dim++) {
        Study s;
        mms_study_default(&s);
        s.dim = dim;
        double worst = 0, divmax = 0, wall = 0;
        for (int i = 0; i < 20; i++) {
            double n[3] = {rnd(&seed) - 0.5, rnd(&seed) - 0.5, dim == 3 ? rnd(&seed) - 0.5 : 0}, r = 0.95 * rnd(&seed);
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), x[3], xw[3], div;
            for (int k = 0; k < 3; k++) {
                n[k] /= len;
                x[k] = s.p.c[k] + s.p.R * r * n[k];
                xw[k] = s.p.c[k] + s.p.R * n[k];
            }
            fd_point(&s, x, &worst, &div);
            divmax = fmax(divmax, fabs(div));
            MmsPoint o;
            mms_exact(&s, xw, &o);
            double dn = o.grad_rho[0] * n[0] + o.grad_rho[1] * n[1] + o.grad_rho[2] * n[2];
            wall = fmax(wall, fmax(fabs(dn), fabs(o.u[0]) + fabs(o.u[1]) + fabs(o.u[2])));
        }
        EXPECT(worst <= 1e-5, "%d-D: derivatives differ by %.2e", dim, worst);
        EXPECT(divmax <= 1e-8, "%d-D: div(rho u) = %.2e", dim, divmax);
        EXPECT(wall <= 1e-12, "%d-D: on the wall |u| or |d rho/dn| = %.2e", dim, wall);
        printf("  %d-D: finite differences within %.1e, div(rho u) %.1e, wall %.1e\n", dim, worst, divmax, wall);
    }
}

/* Runs k for n steps at a fixed dt. */
static int steps(MmsCase *k, int n, double dt, Err *e)
{
    for (int i = 0; i < n; i++) {
        gran_flux(&k->g);
        if (gran_step(&k->g, dt, e)) return -1;
    }
    return 0;
}

static int hook_zero(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src, Err *e)
{
    (void)ctx, (void)t, (void)e;
    memset(rho_src, 0, sizeof(double) * (size_t)f->ncells);
    memset(mom_src, 0, sizeof(double) * 3 * (size_t)f->ncells);
    if (T_src) memset(T_src, 0, sizeof(double) * (size_t)f->ncells);
    return 0;
}

TEST(hook_none)
{
    Study s;
    mms_study_default(&s);
    MmsCase a, b;
    Err e;
    mms_case_init(&a, &s, 16);
    mms_case_init(&b, &s, 16);
    a.g.src.fn = NULL;
    b.g.src = (GranSource){hook_zero, NULL};
    EXPECT(!steps(&a, 30, 2e-3, &e) && !steps(&b, 30, 2e-3, &e), "step: %s", e.msg);
    int n = a.f.ncells;
    EXPECT(!memcmp(a.rho.v, b.rho.v, sizeof(double) * (size_t)n) &&
               !memcmp(a.U.v, b.U.v, sizeof(double) * 3 * (size_t)n),
           "a zero source changed the state");
    mms_case_free(&a);
    mms_case_free(&b);
}

/* The hook of hook_mass: s_rho = 1, s_m = 0; records the times. */
typedef struct Recorder {
    int n;
    double t[64];
} Recorder;

static int hook_unit(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src, Err *e)
{
    Recorder *r = ctx;
    (void)e, (void)T_src;
    if (r->n < 64) r->t[r->n++] = t;
    for (int c = 0; c < f->ncells; c++) {
        rho_src[c] = f->m->cell_vol[c];
        mom_src[3 * c] = mom_src[3 * c + 1] = mom_src[3 * c + 2] = 0;
    }
    return 0;
}

TEST(hook_mass)
{
    Study s;
    mms_study_default(&s);
    MmsCase k;
    Err e;
    Recorder r = {0, {0}};
    mms_case_init(&k, &s, 16);
    k.g.src = (GranSource){hook_unit, &r};
    k.g.time = 0.5;
    double mass0 = gran_mass(&k.g), dt = 2e-3;
    EXPECT(!steps(&k, 30, dt, &e), "step: %s", e.msg);
    double vol = fvmesh_volume(&k.f), want = 30 * dt * vol, t = 0.5;
    NEAR((gran_mass(&k.g) - mass0) / want, 1, 1e-12);
    NEAR(k.g.src_total / want, 1, 1e-12);
    EXPECT(r.n == 30, "the hook was called %d times", r.n);
    for (int i = 0; i < r.n; i++) {
        EXPECT(r.t[i] == t, "step %d: the hook saw t = %.17g, not %.17g", i, r.t[i], t);
        t += dt;
    }
    EXPECT(k.g.time == t, "time %.17g, not %.17g", k.g.time, t);
    mms_case_free(&k);
}

static int hook_broken(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src,
                       Err *e)
{
    (void)ctx, (void)f, (void)rho_src, (void)mom_src, (void)T_src;
    return err_set(e, "hook", 1, "no source at t = %g", t);
}

TEST(hook_fail)
{
    Study s;
    mms_study_default(&s);
    MmsCase k;
    Err e;
    mms_case_init(&k, &s, 16);
    int n = k.f.ncells;
    double *rho = mem_alloc(sizeof(double) * (size_t)n), *u = mem_alloc(sizeof(double) * 3 * (size_t)n);
    EXPECT(!steps(&k, 3, 2e-3, &e), "step: %s", e.msg);
    memcpy(rho, k.rho.v, sizeof(double) * (size_t)n);
    memcpy(u, k.U.v, sizeof(double) * 3 * (size_t)n);
    double t = k.g.time, mass = gran_mass(&k.g);
    k.g.src = (GranSource){hook_broken, NULL};
    EXPECT(steps(&k, 1, 2e-3, &e) == -1, "the step did not fail");
    CONTAINS(e.msg, "no source at t = 0.006");
    EXPECT(!memcmp(rho, k.rho.v, sizeof(double) * (size_t)n) && !memcmp(u, k.U.v, sizeof(double) * 3 * (size_t)n),
           "the failed step changed the state");
    EXPECT(k.g.time == t && gran_mass(&k.g) == mass, "the failed step changed the time or the mass");
    free(rho);
    free(u);
    mms_case_free(&k);
}

/* ---- model granular ---- */

/* The closures at x by fv/closure.h (independent of the generated code):
   c, T, u and p, eta, lambda, eps. */
typedef struct GranFd {
    double c, T, u[3], p, eta, lam, eps;
} GranFd;

static void gfd(const Study *s, const double x[3], GranFd *o)
{
    MmsGranPoint q;
    GranClosure cl;
    mms_gran_exact(s, x, &q);
    closure_eval(&s->k, q.c, q.T, &cl);
    *o = (GranFd){q.c, q.T, {q.u[0], q.u[1], q.u[2]}, cl.p, cl.eta, cl.lambda, cl.eps};
}

static void shifted(const double x[3], int j, double h, double out[3])
{
    out[0] = x[0], out[1] = x[1], out[2] = x[2];
    out[j] += h;
}

/* The sources at x by differences of fv/closure.h's closures: s_m, s_T,
   the heating K_T eta kappa:kappa and div(c u), into m[3], *sT, *heat,
   *div. */
static void gran_fd_sources(const Study *s, const double x[3], double m[3], double *sT, double *heat, double *div)
{
    const double h = 2.5e-4;
    GranFd o;
    gfd(s, x, &o);
    double kk = 0, cond = 0, conv_T = 0;
    *div = 0;
    for (int i = 0; i < 3; i++) m[i] = 0;
    for (int j = 0; j < s->dim; j++) {
        double xp[3], xm[3], xph[3], xmh[3];
        GranFd p, q, ph, mh;
        shifted(x, j, h, xp), shifted(x, j, -h, xm), shifted(x, j, h / 2, xph), shifted(x, j, -h / 2, xmh);
        gfd(s, xp, &p), gfd(s, xm, &q), gfd(s, xph, &ph), gfd(s, xmh, &mh);
        *div += (p.c * p.u[j] - q.c * q.u[j]) / (2 * h);
        conv_T += (p.c * p.T * p.u[j] - q.c * q.T * q.u[j]) / (2 * h);
        cond += (ph.lam * (p.T - o.T) - mh.lam * (o.T - q.T)) / (h * h);
        m[j] += (p.p - q.p) / (2 * h);
        for (int i = 0; i < 3; i++) {
            double d = (p.u[i] - q.u[i]) / (2 * h);
            kk += d * d;
            m[i] += (p.c * p.u[i] * p.u[j] - q.c * q.u[i] * q.u[j]) / (2 * h) -
                    (ph.eta * (p.u[i] - o.u[i]) - mh.eta * (o.u[i] - q.u[i])) / (h * h);
        }
    }
    *heat = s->k.KT * o.eta * kk;
    *sT = conv_T - s->k.KT * (o.eta * kk + cond) + o.eps * o.c * o.T;
}

/* A random point of the disc or ball at radius fraction below 0.95 into
   x, the wall point in its direction into xw, the normal into n. */
static void random_point(const Study *s, unsigned *seed, double x[3], double xw[3], double n[3])
{
    n[0] = rnd(seed) - 0.5, n[1] = rnd(seed) - 0.5, n[2] = s->dim == 3 ? rnd(seed) - 0.5 : 0;
    double r = 0.95 * rnd(seed), len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) {
        n[k] /= len;
        x[k] = s->pg.c[k] + s->pg.R * r * n[k];
        xw[k] = s->pg.c[k] + s->pg.R * n[k];
    }
}

/* The normal derivatives of c and T at the wall point xw (normal n). */
static double wall_gradients(const Study *s, const double xw[3], const double n[3])
{
    const double h = 1e-6;
    double xp[3], xm[3];
    for (int k = 0; k < 3; k++) xp[k] = xw[k] + h * n[k], xm[k] = xw[k] - h * n[k];
    MmsGranPoint p, q;
    mms_gran_exact(s, xp, &p);
    mms_gran_exact(s, xm, &q);
    return fmax(fabs(p.c - q.c), fabs(p.T - q.T)) / (2 * h);
}

TEST(gran_exact_fd)
{
    unsigned seed = 11;
    for (int dim = 2; dim <= 3; dim++) {
        Study s;
        mms_study_default(&s);
        s.granular = 1, s.dim = dim;
        double worst = 0, divmax = 0, wall = 0, cmin = 1, cmax = 0, Tmin = 1e30;
        for (int i = 0; i < 40; i++) {
            double x[3], xw[3], n[3], m[3], sT, heat, div;
            random_point(&s, &seed, x, xw, n);
            MmsGranPoint o, w;
            mms_gran_exact(&s, x, &o);
            gran_fd_sources(&s, x, m, &sT, &heat, &div);
            for (int k = 0; k < 3; k++) worst = fmax(worst, rdiff(m[k], o.src_m[k]));
            worst = fmax(worst, fmax(rdiff(sT, o.src_T), rdiff(heat, o.heat)));
            divmax = fmax(divmax, fmax(fabs(div), fabs(o.src_c)));
            mms_gran_exact(&s, xw, &w);
            wall = fmax(wall, fmax(fabs(w.u[0]) + fabs(w.u[1]) + fabs(w.u[2]), wall_gradients(&s, xw, n)));
            cmin = fmin(cmin, fmin(o.c, w.c)), cmax = fmax(cmax, fmax(o.c, w.c)), Tmin = fmin(Tmin, fmin(o.T, w.T));
        }
        EXPECT(worst <= 1e-5, "%d-D: sources differ from fv/closure.h's by %.2e", dim, worst);
        EXPECT(divmax <= 1e-8, "%d-D: div(c u) = %.2e", dim, divmax);
        EXPECT(wall <= 1e-8, "%d-D: on the wall |u|, |dc/dn| or |dT/dn| = %.2e", dim, wall);
        EXPECT(cmin > s.k.c0 && cmax < s.k.cmax && Tmin > 0, "%d-D: c in [%g, %g], T >= %g", dim, cmin, cmax, Tmin);
        printf("  %d-D: sources within %.1e of fv/closure.h's by differences, div(c u) %.1e, wall %.1e, c in "
               "[%.3f, %.3f]\n",
               dim, worst, divmax, wall, cmin, cmax);
    }
}

/* The hook of gran_hook_T: s_c = Q[0] and s_T = Q[1] per unit volume,
   no momentum source. */
static int hook_T(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src, Err *e)
{
    const double *Q = ctx;
    (void)t, (void)e;
    memset(mom_src, 0, sizeof(double) * 3 * (size_t)f->ncells);
    for (int c = 0; c < f->ncells; c++) rho_src[c] = Q[0] * f->m->cell_vol[c], T_src[c] = Q[1] * f->m->cell_vol[c];
    return 0;
}

/* A granular case at N = 16 with uniform c and T at rest (s.pg's means). */
static void gran_rest(MmsCase *k, Study *s)
{
    mms_study_default(s);
    s->granular = 1;
    mms_case_init(k, s, 16);
    for (int c = 0; c < k->f.ncells; c++) {
        k->rho.v[c] = s->pg.cm, k->T.v[c] = s->pg.Tm;
        k->U.v[3 * c] = k->U.v[3 * c + 1] = k->U.v[3 * c + 2] = 0;
    }
    k->g.gm.fresh = 0;
}

TEST(gran_hook_T)
{
    Study s;
    MmsCase k;
    Err e;
    double Q[2] = {0.5, 1}, dt = 1e-2, worst = 0, cworst = 0, umax = 0;
    gran_rest(&k, &s);
    k.g.src = (GranSource){hook_T, Q};
    EXPECT(!steps(&k, 1, dt, &e), "step: %s", e.msg);
    /* c1 = c + dt Q_c; c1 T1 - c T0 = dt (-eps(c, T0) c1 T1 + Q_T): the
       implicit dissipation, no conduction, heating or convection at rest */
    double c = s.pg.cm, c1 = c + dt * Q[0], T0 = s.pg.Tm, eps = closure_eps(&s.k, c, T0);
    double want = (c * T0 / dt + Q[1]) / (c1 / dt + eps * c1);
    for (int i = 0; i < k.f.nowned; i++) {
        worst = fmax(worst, fabs(k.T.v[i] - want) / want);
        cworst = fmax(cworst, fabs(k.rho.v[i] - c1) / c1);
        for (int j = 0; j < 3; j++) umax = fmax(umax, fabs(k.U.v[3 * i + j]));
    }
    EXPECT(worst <= 1e-12, "T after one step off by %.2e relative (want %.17g)", worst, want);
    EXPECT(cworst <= 1e-14, "c after one step off by %.2e relative (want %.17g)", cworst, c1);
    EXPECT(umax <= 1e-14, "the rest state moved: |u| = %.2e", umax);
    printf("  c^1 = %.15g and T^1 = %.15g in every cell to %.1e, %.1e (|u| %.1e)\n", c1, want, cworst, worst, umax);
    mms_case_free(&k);
}

TEST(gran_hook_none)
{
    Study s;
    mms_study_default(&s);
    s.granular = 1;
    MmsCase a, b;
    Err e;
    mms_case_init(&a, &s, 16);
    mms_case_init(&b, &s, 16);
    a.g.src.fn = NULL;
    b.g.src = (GranSource){hook_zero, NULL};
    EXPECT(!steps(&a, 30, 2e-3, &e) && !steps(&b, 30, 2e-3, &e), "step: %s", e.msg);
    size_t n = (size_t)a.f.ncells;
    EXPECT(!memcmp(a.rho.v, b.rho.v, sizeof(double) * n) && !memcmp(a.U.v, b.U.v, sizeof(double) * 3 * n) &&
               !memcmp(a.T.v, b.T.v, sizeof(double) * n),
           "a zero source changed the state");
    mms_case_free(&a);
    mms_case_free(&b);
}

/* The mean |heat - exact| over the cut (and merged) cells and over the
   whole cells of level N after one step of 1e-9 from the exact state. */
static void heat_errors(int N, int jacobian, double err[2])
{
    Study s;
    mms_study_default(&s);
    s.granular = 1;
    s.jacobian = jacobian;
    MmsCase k;
    Err e;
    mms_case_init(&k, &s, N);
    EXPECT(!steps(&k, 1, 1e-9, &e), "step: %s", e.msg);
    double Vc = 1.0 / ((double)N * N * N);
    int cnt[2] = {0, 0};
    err[0] = err[1] = 0;
    for (int c = 0; c < k.f.nowned; c++) {
        MmsGranPoint o;
        mms_gran_exact(&s, k.f.node + 3 * c, &o);
        int cut = fabs(k.f.m->cell_vol[c] - Vc) > 1e-9 * Vc;
        err[cut] += fabs(k.g.gm.heat[c] - o.heat);
        cnt[cut]++;
    }
    err[0] /= cnt[0], err[1] /= cnt[1];
    mms_case_free(&k);
}

TEST(gran_heat_cut)
{
    static const char *const name[] = {"faceMetric", "leastSquares", "faceWeight", "faceDissipation"};
    for (int j = GRAN_JAC_FACE; j <= GRAN_JAC_DISS; j++) {
        double e16[2], e32[2], e64[2];
        heat_errors(16, j, e16);
        heat_errors(32, j, e32);
        heat_errors(64, j, e64);
        printf("  %s: mean |heating error|, whole cells: %.3e %.3e %.3e, cut cells: %.3e %.3e %.3e (N = 16, 32, "
               "64; heating up to 2.5)\n",
               name[j], e16[0], e32[0], e64[0], e16[1], e32[1], e64[1]);
        EXPECT(e64[0] <= 0.5 * e32[0], "%s whole cells: %.3e, %.3e", name[j], e32[0], e64[0]);
        if (j == GRAN_JAC_THESIS) /* eq. 4.65's weight: inconsistent off squares, the error stays */
            EXPECT(e64[1] >= 0.2 && e64[1] >= 0.7 * e32[1], "faceWeight cut cells: %.3e, %.3e", e32[1], e64[1]);
        else if (j == GRAN_JAC_DISS) /* consistent in sum only: bounded, a fifth of faceWeight's */
            EXPECT(e32[1] <= 0.12 && e64[1] <= 0.12, "faceDissipation cut cells: %.3e, %.3e", e32[1], e64[1]);
        else
            EXPECT(e32[1] <= 0.1 && e64[1] <= 0.7 * e32[1], "%s cut cells: %.3e, %.3e", name[j], e32[1], e64[1]);
    }
}

int mms_check(void)
{
    RUN(exact_fd);
    RUN(hook_none);
    RUN(hook_mass);
    RUN(hook_fail);
    RUN(gran_exact_fd);
    RUN(gran_hook_none);
    RUN(gran_hook_T);
    RUN(gran_heat_cut);
    return test_nfail;
}
