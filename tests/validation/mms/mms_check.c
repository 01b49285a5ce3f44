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
**                 the state and the time unchanged.
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

int mms_check(void)
{
    RUN(exact_fd);
    RUN(hook_none);
    RUN(hook_mass);
    RUN(hook_fail);
    return test_nfail;
}
