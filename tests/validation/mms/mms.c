/*
** mms.c: manufactured-solution convergence studies of solveGranular's
** model Newtonian (eq. 5.1 by eq. 4.66, tools/solveGranular/newtonian.h)
** and, with -model granular, of model granular (c, u, T with yield, eq.
** 2.37-2.39 by eq. 4.66, tools/solveGranular/granular.h) on
** cut-and-merged and Voronoi grids, 2-D and 3-D (issue 11).
**
**   mms [options] KIND INTERP DIV N...
**   mms -check
**
**   KIND    disc-cut       the disc |x - c| < 0.4 (2-D) cut from the block
**                          grid of [0,1]^2 (N x N cells) and merged (M_V 1/2)
**           disc-voronoi   the same disc as a Voronoi grid (-layers)
**           ball-cut       the ball |x - c| < 0.4 (3-D) cut from [0,1]^3
**                          (N^3 cells) and merged
**           ball-voronoi   the ball as a Voronoi grid
**   INTERP  shepard | multilinear        (interpolationSchemes; multilinear
**                                        is refused on the Voronoi grids)
**   DIV     upwind | limitedLinear | vanLeer   (divSchemes: Gauss upwind,
**           Gauss limitedLinear 1, Gauss vanLeer, for rho and U)
**   N...    the grid levels, coarse to fine
**
** options: -model Newtonian | granular (Newtonian; granular: the solution
** of mms_exact_gran.h, derived by derive_granular.py, with the closures'
** coefficients of mms_case.c; -KT K and -T0 T0 change two of them), -mu MU
** (0.1), -RsT R (6; both model Newtonian's), -layers L (Voronoi boundary layers,
** 2), -tol T (steady tolerance, 1e-7), -tmax T (20), -maxCo C (0.5),
** -maxSkewness S (mergeCells' quality pass, 4; 0 = off), -expect NAME=P
** (repeatable; NAME L1_rho, Linf_rho, L1_u or Linf_u, model
** granular L1_c, Linf_c, L1_u, Linf_u, L1_T or Linf_T: the order P expected
** of that norm between the last two levels; the program prints a PASS or
** FAIL line for each, FAIL also when the last level did not reach the
** steady state, and exits 1 on a FAIL).  -check runs the checks of make
** test (mms_check.c).
**
** The exact solution (mms_exact.h, derived by derive.py with sympy) is
** steady, with u = 0 and d rho/dn = 0 on the wall, so the boundary
** conditions are the solver's own (U noSlip, rho zeroGradient: the wall
** pressure is the owner's, newtonian.h) and need no time-dependent
** values.  Its source terms enter through the model's hook (GranSource)
** as cell integrals by fv/quad.h's degree-2 rule; rho starts as the cell
** average of the exact density (the same rule), so the discrete mass is
** the exact mass of the grid's domain, and u as the exact velocity at the
** node.  Each level runs at maxCo until the state stops changing: max
** over the cells of |rho^{m+1} - rho^m| and |u^{m+1} - u^m|, divided by
** dt, below -tol (else t reaches -tmax, and the table marks t with *).
** The errors are taken at the cell nodes (centroids; Voronoi seeds):
**     L1 = sum_c V_c |e_c| / sum_c V_c,   Linf = max_c |e_c|,
** e = rho - rho_exact for the density and |u - u_exact| for the velocity
** (model granular: c - c_exact, |u - u_exact| and T - T_exact; the steady
** test also takes T's change, and the hook hands the model the integrals
** of s_T too), and the observed order between levels N1 < N2 is
** log(e1/e2) / log(N2/N1).  Time is CPU time.
*/
#include "mem.h"
#include "mms.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double order(const Level *a, const Level *b, int q)
{
    return log(a->err[q] / b->err[q]) / log((double)b->N / a->N);
}

static void run_level(const Study *s, Level *lv)
{
    clock_t t0 = clock();
    MmsCase k;
    mms_case_init(&k, s, lv->N);
    double mass0 = gran_mass(&k.g);
    mms_steady(s, &k, lv);
    lv->mass_change = fabs(gran_mass(&k.g) - mass0) / mass0;
    mms_errors(s, &k, lv);
    mms_case_free(&k);
    lv->secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
}

static void print_head(const Study *s)
{
    printf("Manufactured solution, %s (%d-D), %s, Gauss %s%s: ", s->kind, s->dim, s->interp, s->div,
           strcmp(s->div, "limitedLinear") ? "" : " 1");
    if (s->granular)
        printf("model granular (eta0 %g, lambda0 %g, eps0 %g, cMax %g, c0 %g, T0 %g, KT %.6g)", s->k.eta0, s->k.lambda0,
               s->k.eps0, s->k.cmax, s->k.c0, s->k.T0, s->k.KT);
    else
        printf("mu %g, RsT %g", s->mu, s->RsT);
    printf(", steady to %g (t <= %g), maxCo %g", s->tol, s->tmax, s->maxCo);
    if (s->voronoi) printf(", %d boundary layers", s->layers);
    else printf(", merged with M_V 1/2, maxSkewness %g", s->max_skewness);
    printf("\n     N   cells  steps       t   change  L1 %-4s    order  Linf %-4s  order  L1 |u|     order  "
           "Linf |u|   order",
           s->granular ? "c" : "rho", s->granular ? "c" : "rho");
    if (s->granular) printf("  L1 T       order  Linf T     order");
    printf("  mass chg    time\n");
}

static void print_row(const Study *s, const Level *lv, const Level *prev)
{
    printf("  %4d %7d %6d %6.2f%s %8.1e", lv->N, lv->cells, lv->steps, lv->t, lv->rate > s->tol ? "*" : " ",
           lv->rate);
    for (int q = 0; q < (s->granular ? MMS_NQ : 4); q++) {
        printf("  %.3e", lv->err[q]);
        if (prev) printf(" %5.2f", order(prev, lv, q));
        else printf("     -");
    }
    printf("  %7.1e %6.1f s\n", lv->mass_change, lv->secs);
    fflush(stdout);
}

static const char *const qname_newt[MMS_NQ] = {"L1_rho", "Linf_rho", "L1_u", "Linf_u", NULL, NULL};
static const char *const qname_gran[MMS_NQ] = {"L1_c", "Linf_c", "L1_u", "Linf_u", "L1_T", "Linf_T"};
static const char *const *qnames(const Study *s) { return s->granular ? qname_gran : qname_newt; }

/* PASS/FAIL per expected order between the last two levels. */
static int verdict(const Study *s, const Level *lv, int n)
{
    int nfail = 0;
    const char *const *qname = qnames(s);
    for (int q = 0; q < MMS_NQ; q++) {
        double want = s->expect[q];
        if (want < 0 || n < 2) continue;
        double o = order(&lv[n - 2], &lv[n - 1], q);
        int steady = lv[n - 1].rate <= s->tol, ok = o >= want && steady;
        nfail += !ok;
        printf("%s mms_%s%s_%s_%s_%s: observed order %.2f between N = %d and %d (expected >= %.2f)%s\n",
               ok ? "PASS" : "FAIL", s->granular ? "granular_" : "", s->kind, s->interp, s->div, qname[q], o,
               lv[n - 2].N, lv[n - 1].N, want,
               steady ? "" : "; the last level is not steady");
    }
    return nfail;
}

static void usage(void)
{
    printf("usage: mms [-model Newtonian|granular] [-mu MU] [-RsT R] [-KT K] [-T0 T0] [-layers L] [-tol T] "
           "[-tmax T] [-maxCo C] [-maxSkewness S] "
           "[-expect L1_rho|Linf_rho|L1_c|Linf_c|L1_u|Linf_u|L1_T|Linf_T=P]... "
           "disc-cut|disc-voronoi|ball-cut|ball-voronoi shepard|multilinear upwind|limitedLinear|vanLeer N...\n"
           "       mms -check\n");
    exit(2);
}

/* -expect NAME=P: the order P expected of norm NAME (qnames of the
   model, which parse reads first). */
static void expect(Study *s, const char *arg)
{
    const char *const *qname = qnames(s);
    for (int q = 0; q < MMS_NQ; q++) {
        size_t n = qname[q] ? strlen(qname[q]) : 0;
        if (n && !strncmp(arg, qname[q], n) && arg[n] == '=') {
            s->expect[q] = atof(arg + n + 1);
            return;
        }
    }
    usage();
}

/* Options and the three words into s; returns the index of the first N. */
static int parse(int argc, char **argv, Study *s)
{
    static const char *const opt[] = {"-mu", "-RsT", "-KT", "-T0", "-tol", "-tmax", "-maxCo", "-maxSkewness"};
    double *dst[] = {&s->mu, &s->RsT, &s->k.KT, &s->k.T0, &s->tol, &s->tmax, &s->maxCo, &s->max_skewness};
    int i = 1, nopt = (int)(sizeof opt / sizeof opt[0]);
    for (int j = 1; j + 1 < argc && argv[j][0] == '-'; j += 2) /* the model first: -expect's names depend on it */
        if (!strcmp(argv[j], "-model")) s->granular = !strcmp(argv[j + 1], "granular");
    while (i + 1 < argc && argv[i][0] == '-') {
        int j = 0;
        while (j < nopt && strcmp(argv[i], opt[j])) j++;
        if (j < nopt) *dst[j] = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "-layers")) s->layers = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "-model") && (!strcmp(argv[i + 1], "granular") || !strcmp(argv[i + 1], "Newtonian")))
            s->granular = !strcmp(argv[i + 1], "granular");
        else if (!strcmp(argv[i], "-expect")) expect(s, argv[i + 1]);
        else usage();
        i += 2;
    }
    if (argc - i < 4) usage();
    s->kind = argv[i];
    s->interp = argv[i + 1];
    s->div = argv[i + 2];
    s->dim = !strncmp(s->kind, "ball", 4) ? 3 : 2;
    s->voronoi = strstr(s->kind, "voronoi") != NULL;
    if ((strncmp(s->kind, "disc", 4) && strncmp(s->kind, "ball", 4)) ||
        (strcmp(s->kind + 4, "-cut") && strcmp(s->kind + 4, "-voronoi")) ||
        (strcmp(s->interp, "shepard") && strcmp(s->interp, "multilinear")) ||
        (strcmp(s->div, "upwind") && strcmp(s->div, "limitedLinear") && strcmp(s->div, "vanLeer")))
        usage();
    return i + 3;
}

int main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "-check")) {
        int nfail = mms_check();
        linsolve_finalize();
        return nfail ? 1 : 0;
    }
    Study s;
    mms_study_default(&s);
    int first = parse(argc, argv, &s), n = argc - first;
    Level *lv = mem_calloc((size_t)n, sizeof(Level));
    print_head(&s);
    for (int i = 0; i < n; i++) {
        lv[i].N = atoi(argv[first + i]);
        if (lv[i].N < 2) usage();
        run_level(&s, &lv[i]);
        print_row(&s, &lv[i], i ? &lv[i - 1] : NULL);
    }
    int nfail = verdict(&s, lv, n);
    free(lv);
    linsolve_finalize();
    return nfail ? 1 : 0;
}
