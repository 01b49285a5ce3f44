/*
** test_linsolve.c: linear solves through PETSc (fv/linsolve.h) on
** matrices assembled with fv/fvmatrix.h.
**
** The problem: -lap(phi) = f on the unit square (2-D block grid, empty
** front and back) and the unit cube, Dirichlet walls, with the two-point
** flux |S_f| (phi_N - phi_C) / |x_N - x_C| (to the face centre at a wall),
** exact phi = sin(pi x) sin(pi y) [sin(pi z)] + x y^2 [z].  The scheme is
** second order on these uniform grids: the error tables print the
** observed orders, which must be >= 1.9.  Each fvSolution setting must
** reach its tolerance and give the same solution; iterations and times
** are printed per solver.  Then the settings themselves: OpenFOAM's regex
** look-up, the mapping of names, errors with file:line for unknown names
** and keywords, a solve stopped by maxIter, relTol, per-system PETSc
** options that do not leak, and a matrix whose values change between
** solves (a direct solve with stale factors would be wrong).
**
** KIESEL_LINSOLVE_BENCH=1 adds the comparison at 256^2 and 64^3 recorded
** in doc/performance.md ("Linear solvers").
*/
#include "fixture.h"
#include "fvmatrix.h"
#include "linsolve.h"
#include "test.h"

#include <math.h>
#include <petscconf.h>
#include <time.h>

static const char fvsolution[] =
    "solvers\n"                                                                                      /* 1 */
    "{\n"                                                                                            /* 2 */
    "    PCG_DIC        { solver PCG; preconditioner DIC; tolerance 1e-10; relTol 0; maxIter 5000; }\n" /* 3 */
    "    PBiCGStab_DILU { solver PBiCGStab; preconditioner DILU; tolerance 1e-10; maxIter 5000; }\n"  /* 4 */
    "    GAMG           { solver GAMG; smoother GaussSeidel; tolerance 1e-10; maxIter 1000; }\n"     /* 5 */
    "    PCG_GAMG       { solver PCG; preconditioner GAMG; tolerance 1e-10; maxIter 1000; }\n"      /* 6 */
    "    gmres_hypre    { solver gmres; preconditioner hypre; tolerance 1e-10; maxIter 1000; }\n"   /* 7 */
    "    smooth         { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; maxIter 100000; }\n" /* 8 */
    "    \"U.*\"          { solver PBiCG; preconditioner DILU; tolerance 1e-7; relTol 0.01; }\n"   /* 9 */
    "    Uz             { solver PCG; preconditioner none; }\n"                                     /* 10 */
    "    few            { solver PCG; preconditioner DIC; tolerance 1e-12; maxIter 1; }\n"          /* 11 */
    "    rel            { solver PCG; preconditioner diagonal; tolerance 0; relTol 0.1; }\n"        /* 12 */
    "    opts           { solver PCG; preconditioner DIC; petscOptions \"-ksp_type gmres -pc_type jacobi\"; }\n" /* 13 */
    "    direct         { solver preonly; preconditioner lu; }\n"                                   /* 14 */
    "    badSolver      { solver PCGG; preconditioner DIC; }\n"                                     /* 15 */
    "    badPrecon      { solver PCG;\n"                                                            /* 16 */
    "                     preconditioner DICX; }\n"                                                 /* 17 */
    "    badKey         { solver PCG; tolerence 1e-6; }\n"                                          /* 18 */
    "    PBiCGStab_ilu  { solver PBiCGStab; preconditioner ilu; tolerance 1e-10; maxIter 5000; }\n"  /* 19 */
    "    PCG_icc        { solver PCG; preconditioner icc; tolerance 1e-10; relTol 0; maxIter 5000; }\n" /* 20 */
    "    smoothDILU     { solver smoothSolver; smoother DILU; tolerance 1e-8; maxIter 100000; }\n"  /* 21 */
    "}\n";

static Dict *read_fvsolution(void)
{
    Err e;
    Dict *d = dict_parse(fvsolution, strlen(fvsolution), "system/fvSolution", &e);
    if (!d) {
        printf("fvSolution: %s\n", e.msg);
        exit(1);
    }
    return d;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- the Poisson problem ---- */

static int dim3;        /* 3-D exact solution (else 2-D) */
static double shift;    /* a time step's diagonal: + shift phi V / h^2 on both sides */

static double exact(const double *x)
{
    const double pi = 3.14159265358979323846;
    if (dim3) return sin(pi * x[0]) * sin(pi * x[1]) * sin(pi * x[2]) + x[0] * x[1] * x[1] * x[2];
    return sin(pi * x[0]) * sin(pi * x[1]) + x[0] * x[1] * x[1];
}

static double source(const double *x)   /* -lap(exact) */
{
    const double pi = 3.14159265358979323846;
    if (dim3) return 3 * pi * pi * sin(pi * x[0]) * sin(pi * x[1]) * sin(pi * x[2]) - 2 * x[0] * x[2];
    return 2 * pi * pi * sin(pi * x[0]) * sin(pi * x[1]) - 2 * x[0];
}

static double dist(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Two-point flux |S_f| / |x_N - x_C| through the face positions;
   Dirichlet walls with the exact value at the face centre. */
static void assemble(FvMatrix *M, const FvMesh *f)
{
    const Mesh *m = f->m;
    fvmatrix_zero(M);
    for (int i = 0; i < f->ninternal; i++) {
        int o = m->owner[i], n = m->neighbour[i];
        double a = f->mag_sf[i] / dist(f->node + 3 * o, f->node + 3 * n);
        M->val[M->diag[o]] += a;
        M->val[M->diag[n]] += a;
        M->val[M->face_pos[2 * i]] -= a;
        M->val[M->face_pos[2 * i + 1]] -= a;
    }
    for (int i = f->ninternal; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        int o = m->owner[i];
        const double *xf = m->face_centre + 3 * i;
        double a = f->mag_sf[i] / dist(f->node + 3 * o, xf);
        M->val[M->diag[o]] += a;
        M->rhs[o] += a * exact(xf);
    }
    for (int c = 0; c < f->nowned; c++) M->rhs[c] += source(f->node + 3 * c) * m->cell_vol[c];
}

/* A diffusion step of diffusion number nu dt / h^2 = 1 / shift: the
   mass term shift V / h^2 on the diagonal, and on the right-hand side
   times the exact solution, so that the exact solution stays exact. */
static void add_shift(FvMatrix *M, const FvMesh *f, int n)
{
    for (int c = 0; c < f->nowned; c++) {
        double a = shift * f->m->cell_vol[c] * n * n;
        M->val[M->diag[c]] += a;
        M->rhs[c] += a * exact(f->node + 3 * c);
    }
}

typedef struct Grid {
    Mesh m;
    FvMesh f;
    FvMatrix M;
} Grid;

static void grid_make(Grid *g, int n, int three)
{
    int nn[3] = {n, n, three ? n : 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, three ? 1 : 1.0 / n};
    fixture_block(&g->m, nn, lo, hi, three ? -1 : 2);
    Err e;
    if (fvmesh_init(&g->f, &g->m, &e)) {
        printf("fvmesh_init: %s\n", e.msg);
        exit(1);
    }
    FvPattern p;
    fvpattern_init(&p, &g->f);
    fvmatrix_init(&g->M, &p);
    dim3 = three;
    assemble(&g->M, &g->f);
    if (shift > 0) add_shift(&g->M, &g->f, n);
}

static void grid_free(Grid *g)
{
    fvmatrix_free(&g->M);
    fvmesh_free(&g->f);
    mesh_free(&g->m);
}

/* L2 (volume-weighted) and max errors against the exact solution. */
static void errors(const Grid *g, const double *phi, double *l2, double *linf)
{
    double s = 0, v = 0;
    *linf = 0;
    for (int c = 0; c < g->f.nowned; c++) {
        double d = phi[c] - exact(g->f.node + 3 * c), vol = g->m.cell_vol[c];
        s += vol * d * d;
        v += vol;
        *linf = fmax(*linf, fabs(d));
    }
    *l2 = sqrt(s / v);
}

typedef struct Run {
    LinStats st;
    double seconds, l2, linf;
    int ok;
    char desc[140], msg[ERR_MSG_MAX];
} Run;

/* Solves the grid's system with the fvSolution entry `name` from zero. */
static Run solve_with(Grid *g, const Dict *d, const char *name)
{
    Run r;
    memset(&r, 0, sizeof r);
    LinSettings s;
    Err e;
    if (linsolve_settings(&s, d, name, &e)) {
        snprintf(r.msg, sizeof r.msg, "%s", e.msg);
        return r;
    }
    double *phi = calloc((size_t)g->f.ncells, sizeof *phi);
    double t0 = now();
    LinSystem *L = linsolve_new(&s, &g->M, &e);
    if (L) {
        snprintf(r.desc, sizeof r.desc, "%s", linsolve_describe(L));
        r.ok = linsolve_solve(L, phi, &r.st, &e) == 0;
        linsolve_free(L);
    }
    r.seconds = now() - t0;
    if (!r.ok) snprintf(r.msg, sizeof r.msg, "%s", e.msg);
    errors(g, phi, &r.l2, &r.linf);
    free(phi);
    linsolve_settings_free(&s);
    return r;
}

/* The convergence table of one dimension with PCG+DIC; returns the last
   observed orders. */
static void convergence(const Dict *d, int three, const int *ns, int nn, double ord[2])
{
    double pl2 = 0, plinf = 0;
    printf("  %s Poisson, PCG+DIC, tolerance 1e-10:\n  %6s %12s %6s %12s %6s %5s\n", three ? "3-D" : "2-D", "N",
           "L2 error", "order", "max error", "order", "iters");
    for (int k = 0; k < nn; k++) {
        Grid g;
        grid_make(&g, ns[k], three);
        Run r = solve_with(&g, d, "PCG_DIC");
        EXPECT(r.ok, "%s", r.msg);
        ord[0] = k ? log(pl2 / r.l2) / log(2.0) : 0;
        ord[1] = k ? log(plinf / r.linf) / log(2.0) : 0;
        printf("  %6d %12.4e %6.3f %12.4e %6.3f %5d\n", ns[k], r.l2, ord[0], r.linf, ord[1], r.st.iters);
        pl2 = r.l2;
        plinf = r.linf;
        grid_free(&g);
    }
}

static const char *const solver_entries[] = {"PCG_DIC", "PBiCGStab_DILU", "GAMG", "PCG_GAMG", "gmres_hypre"};

/* Every setting on one grid: converged to its tolerance, the same
   solution as the first; iterations and seconds printed. */
static void compare(const Dict *d, int n, int three, int nsolvers)
{
    Grid g;
    grid_make(&g, n, three);
    printf("  %s %s %d^%d (%d cells), tolerance 1e-10, from zero:\n  %-15s %-18s %6s %9s %11s %11s\n",
           three ? "3-D" : "2-D", shift > 0 ? "diffusion step (nu dt/h^2 = 1)" : "Poisson", n, three ? 3 : 2, g.f.ncells, "fvSolution", "PETSc", "iters", "seconds",
           "initial", "final");
    double l2ref = 0;
    for (int k = 0; k < nsolvers; k++) {
#if !defined(PETSC_HAVE_HYPRE)
        if (strcmp(solver_entries[k], "gmres_hypre") == 0) {
            printf("SKIP gmres_hypre: this PETSc has no hypre\n");
            continue;
        }
#endif
        Run r = solve_with(&g, d, solver_entries[k]);
        EXPECT(r.ok, "%s: %s", solver_entries[k], r.msg);
        printf("  %-15s %-18s %6d %9.3f %11.3e %11.3e\n", solver_entries[k], r.desc, r.st.iters, r.seconds,
               r.st.initial, r.st.final);
        EXPECT(r.st.final <= 1e-10 * 1.01, "%s: final residual %.3e above its tolerance", solver_entries[k],
               r.st.final);
        if (k == 0) l2ref = r.l2;
        EXPECT(fabs(r.l2 - l2ref) <= 1e-3 * l2ref, "%s: L2 error %.6e, PCG's %.6e", solver_entries[k], r.l2, l2ref);
    }
    grid_free(&g);
}

TEST(poisson_2d)
{
    Dict *d = read_fvsolution();
    int ns[] = {16, 32, 64, 128};
    double ord[2];
    convergence(d, 0, ns, 4, ord);
    EXPECT(ord[0] >= 1.9 && ord[1] >= 1.9, "orders %.3f (L2), %.3f (max)", ord[0], ord[1]);
    compare(d, 128, 0, 5);
    dict_free(d);
}

TEST(poisson_3d)
{
    Dict *d = read_fvsolution();
    int ns[] = {8, 16, 32};
    double ord[2];
    convergence(d, 1, ns, 3, ord);
    EXPECT(ord[0] >= 1.9 && ord[1] >= 1.9, "orders %.3f (L2), %.3f (max)", ord[0], ord[1]);
    compare(d, 32, 1, 5);
    dict_free(d);
}

/* The measurement behind the defaults (doc/performance.md). */
static void bench(void)
{
    Dict *d = read_fvsolution();
    compare(d, 256, 0, 5);
    compare(d, 64, 1, 5);
    shift = 1;
    compare(d, 256, 0, 5);
    compare(d, 64, 1, 5);
    shift = 0;
    dict_free(d);
}

/* ---- the settings ---- */

TEST(settings)
{
    Dict *d = read_fvsolution();
    LinSettings s;
    Err e;
    EXPECT(linsolve_settings(&s, d, "Ux", &e) == 0, "%s", e.msg);
    EXPECT(strcmp(s.solver, "PBiCG") == 0 && strcmp(s.ksp, "bcgs") == 0 && strcmp(s.pc, "dilu") == 0,
           "Ux: %s %s -> %s %s", s.solver, s.precon, s.ksp, s.pc);
    NEAR(s.tol, 1e-7, 0);
    NEAR(s.reltol, 0.01, 0);
    EXPECT(s.maxiter == 1000 && s.line == 9, "maxIter %d, line %d", s.maxiter, s.line);
    linsolve_settings_free(&s);
    /* a literal key wins over the regex */
    EXPECT(linsolve_settings(&s, d, "Uz", &e) == 0, "%s", e.msg);
    EXPECT(strcmp(s.ksp, "cg") == 0 && strcmp(s.pc, "none") == 0 && s.line == 10, "Uz: %s %s line %d", s.ksp, s.pc,
           s.line);
    NEAR(s.tol, 1e-6, 0);
    linsolve_settings_free(&s);
    EXPECT(linsolve_settings(&s, d, "smooth", &e) == 0, "%s", e.msg);
    EXPECT(strcmp(s.ksp, "richardson") == 0 && strcmp(s.pc, "sor") == 0, "smooth: %s %s", s.ksp, s.pc);
    linsolve_settings_free(&s);
    EXPECT(linsolve_settings(&s, d, "GAMG", &e) == 0, "%s", e.msg);
    EXPECT(strcmp(s.ksp, "richardson") == 0 && strcmp(s.pc, "gamg") == 0, "GAMG: %s %s", s.ksp, s.pc);
    linsolve_settings_free(&s);
    EXPECT(linsolve_settings(&s, d, "p", &e) != 0, "no entry for p accepted");
    CONTAINS(e.msg, "system/fvSolution:1: solvers: no dictionary for 'p'");
    dict_free(d);
}

TEST(unknown_names)
{
    Dict *d = read_fvsolution();
    LinSettings s;
    Err e;
    EXPECT(linsolve_settings(&s, d, "badSolver", &e) != 0, "solver PCGG accepted");
    CONTAINS(e.msg, "system/fvSolution:15: solver 'PCGG' for 'badSolver' is neither OpenFOAM's");
    EXPECT(linsolve_settings(&s, d, "badPrecon", &e) != 0, "preconditioner DICX accepted");
    CONTAINS(e.msg, "system/fvSolution:17: preconditioner 'DICX' for 'badPrecon'");
    EXPECT(linsolve_settings(&s, d, "badKey", &e) != 0, "keyword tolerence accepted");
    CONTAINS(e.msg, "system/fvSolution:18: unknown keyword 'tolerence'");
    CONTAINS(e.msg, "tolerance");
    dict_free(d);
}

/* maxIter 1 cannot reach 1e-12: the error names the system, the residual
   and the entry's line. */
TEST(not_converged)
{
    Dict *d = read_fvsolution();
    Grid g;
    grid_make(&g, 32, 0);
    Run r = solve_with(&g, d, "few");
    EXPECT(!r.ok, "one PCG iteration reached 1e-12");
    CONTAINS(r.msg, "system/fvSolution:11: solving for few did not converge in 1 iterations (maxIter): residual ");
    EXPECT(r.st.iters == 1 && r.st.final > 1e-12 && r.st.final < r.st.initial, "iterations %d, residual %.3e",
           r.st.iters, r.st.final);
    printf("  %s\n", r.msg);
    grid_free(&g);
    dict_free(d);
}

/* relTol 0.1 (tolerance 0): stops as soon as the residual fell tenfold;
   a second solve from the solution takes no iteration. */
TEST(reltol_and_exact_guess)
{
    Dict *d = read_fvsolution();
    Grid g;
    grid_make(&g, 32, 0);
    Run r = solve_with(&g, d, "rel");
    EXPECT(r.ok, "%s", r.msg);
    EXPECT(r.st.final <= 0.1 * r.st.initial * 1.01 && r.st.iters > 1, "initial %.3e final %.3e after %d",
           r.st.initial, r.st.final, r.st.iters);
    LinSettings s;
    Err e;
    EXPECT(linsolve_settings(&s, d, "PCG_DIC", &e) == 0, "%s", e.msg);
    double *phi = calloc((size_t)g.f.ncells, sizeof *phi);
    LinSystem *L = linsolve_new(&s, &g.M, &e);
    EXPECT(L != NULL, "%s", e.msg);
    LinStats st;
    EXPECT(L && linsolve_solve(L, phi, &st, &e) == 0, "%s", e.msg);
    EXPECT(L && linsolve_solve(L, phi, &st, &e) == 0 && st.iters == 0 && st.initial <= 1e-10,
           "from the solution: %d iterations, initial %.3e", st.iters, st.initial);
    linsolve_free(L);
    free(phi);
    linsolve_settings_free(&s);
    grid_free(&g);
    dict_free(d);
}

/* petscOptions reach their own system only. */
TEST(options_prefix)
{
    Dict *d = read_fvsolution();
    Grid g;
    grid_make(&g, 16, 0);
    Run a = solve_with(&g, d, "opts"), b = solve_with(&g, d, "PCG_DIC");
    EXPECT(a.ok && b.ok, "%s", a.ok ? b.msg : a.msg);
    EXPECT(strcmp(a.desc, "gmres+jacobi") == 0, "opts uses %s", a.desc);
    EXPECT(strcmp(b.desc, "cg+DILU") == 0, "PCG_DIC uses %s", b.desc);
    /* smoothSolver: too slow for the comparisons, but it converges */
    Run c = solve_with(&g, d, "smooth");
    EXPECT(c.ok && strcmp(c.desc, "richardson+sor") == 0, "smooth: %s %s", c.desc, c.msg);
    printf("  smoothSolver (symGaussSeidel) on 16^2: %d iterations to %.3e\n", c.st.iters, c.st.final);
    grid_free(&g);
    dict_free(d);
}

/* Values changed between solves reach PETSc: a direct solve (LU) with
   the factors of the first matrix would miss the second system. */
TEST(values_change)
{
    Dict *d = read_fvsolution();
    Grid g;
    grid_make(&g, 24, 0);
    LinSettings s;
    Err e;
    EXPECT(linsolve_settings(&s, d, "direct", &e) == 0, "%s", e.msg);
    LinSystem *L = linsolve_new(&s, &g.M, &e);
    EXPECT(L != NULL, "%s", e.msg);
    double *phi = calloc((size_t)g.f.ncells, sizeof *phi);
    LinStats st;
    EXPECT(L && linsolve_solve(L, phi, &st, &e) == 0, "%s", e.msg);
    EXPECT(st.final < 1e-12, "first LU solve: residual %.3e", st.final);
    /* a Helmholtz shift: (A + 50 V) phi = b */
    for (int c = 0; c < g.f.ncells; c++) g.M.val[g.M.diag[c]] += 50 * g.m.cell_vol[c];
    memset(phi, 0, (size_t)g.f.ncells * sizeof *phi);
    EXPECT(L && linsolve_solve(L, phi, &st, &e) == 0, "%s", e.msg);
    EXPECT(st.final < 1e-12, "after the values changed: residual %.3e", st.final);
    linsolve_free(L);
    free(phi);
    linsolve_settings_free(&s);
    grid_free(&g);
    dict_free(d);
}

static const char shared_fvsolution[] =
    "solvers\n"
    "{\n"
    "    \"U.*\" { solver PBiCGStab; preconditioner DILU; tolerance 1e-10; maxIter 500; }\n"
    "    Uy    { solver PBiCGStab; preconditioner DILU; tolerance 1e-3; maxIter 500; }\n"
    "    Uz    { solver PBiCGStab; preconditioner DILU; maxIter 500; petscOptions \"-ksp_gmres_restart 40\"; }\n"
    "    Ua    { solver PBiCGStab; preconditioner DILU; tolerance 1e-10; maxIter 400; }\n"
    "    Ub    { solver PCG; preconditioner DIC; tolerance 1e-10; maxIter 500; }\n"
    "    Uc    { solver PBiCGStab; preconditioner DILU; tolerance 1e-6; maxIter 500; }\n"
    "    Uq    { solver PBiCGStab; preconditioner DILU; tolerance 1e-10; maxIter 500; }\n"
    "    lu    { solver preonly; preconditioner lu; }\n"
    "}\n";

static LinSystem *system_of(const Dict *d, const char *name, LinSystem *with, FvMatrix *M, LinSettings *s)
{
    Err e;
    if (linsolve_settings(s, d, name, &e)) {
        printf("%s: %s\n", name, e.msg);
        exit(1);
    }
    LinSystem *L = with ? linsolve_new_shared(s, with, &e) : linsolve_new(s, M, &e);
    if (!L) {
        printf("%s: %s\n", name, e.msg);
        exit(1);
    }
    return L;
}

/* Ux, Uy, Uz, Ua, Ub, Uc, Uq on one matrix, each but Ux made to share
   Ux's solver: Uy (another tolerance) shares it; Uz (petscOptions), Ua
   (maxIter), Ub (solver) do not, nor Uq, whose prefix PETSC_OPTIONS names
   (main sets "-Uq_ksp_type gmres" before PETSc starts).  Uy's solve on the shared solver after
   Ux's (tracked: the preconditioner kept) equals a fresh unshared Uy
   solve to the bit; Uc (shared) on a right-hand side with a NaN fails
   naming Uc and its line. */
TEST(shared_solver)
{
    Err e;
    Dict *d = dict_parse(shared_fvsolution, strlen(shared_fvsolution), "system/fvSolution", &e);
    EXPECT(d != NULL, "%s", d ? "" : e.msg);
    if (!d) return;
    Grid g;
    shift = 1;
    grid_make(&g, 32, 0);
    shift = 0;
    LinSettings s[8];
    static const char *const names[7] = {"Ux", "Uy", "Uz", "Ua", "Ub", "Uc", "Uq"};
    LinSystem *L[7];
    L[0] = system_of(d, names[0], NULL, &g.M, &s[0]);
    for (int j = 1; j < 7; j++) L[j] = system_of(d, names[j], L[0], &g.M, &s[j]);
    EXPECT(linsolve_shares(L[0], L[1]) && linsolve_shares(L[0], L[5]), "Uy, Uc do not share Ux's solver");
    EXPECT(!linsolve_shares(L[0], L[2]) && !linsolve_shares(L[0], L[3]) && !linsolve_shares(L[0], L[4]),
           "Uz, Ua or Ub shares Ux's solver");
    EXPECT(!linsolve_shares(L[0], L[6]) && strcmp(linsolve_describe(L[6]), "gmres+DILU") == 0,
           "Uq: %s, %s Ux's solver (PETSC_OPTIONS names its prefix)", linsolve_describe(L[6]),
           linsolve_shares(L[0], L[6]) ? "shares" : "does not share");
    int nc = g.f.ncells;
    double *x = calloc((size_t)nc, sizeof *x), *y = calloc((size_t)nc, sizeof *y), *y1 = calloc((size_t)nc, sizeof *y1);
    LinStats sx, sy, sy1, sc;
    EXPECT(linsolve_solve_tracked(L[0], x, &sx, &e) == 0, "%s", e.msg);
    EXPECT(linsolve_solve_tracked(L[1], y, &sy, &e) == 0, "%s", e.msg);
    EXPECT(sx.final <= 1e-10 && sy.final <= 1e-3 && sy.iters < sx.iters,
           "Ux: %.3e after %d, Uy: %.3e after %d (each its own tolerance)", sx.final, sx.iters, sy.final, sy.iters);
    LinSystem *Ly = system_of(d, "Uy", NULL, &g.M, &s[7]);
    EXPECT(linsolve_solve(Ly, y1, &sy1, &e) == 0, "%s", e.msg);
    EXPECT(memcmp(y, y1, sizeof(double) * (size_t)nc) == 0 && sy.iters == sy1.iters && sy.final == sy1.final,
           "Uy shared and alone differ: %d and %d iterations, %.17g and %.17g", sy.iters, sy1.iters, sy.final,
           sy1.final);
    memset(x, 0, sizeof(double) * (size_t)nc);
    double b0 = g.M.rhs[0];
    g.M.rhs[0] = NAN;
    EXPECT(linsolve_solve_tracked(L[5], x, &sc, &e) != 0 && strstr(e.msg, "fvSolution:8:") &&
               strstr(e.msg, "solving for Uc"),
           "Uc: %s (%d iterations, residual %.3e)", e.msg, sc.iters, sc.final);
    printf("  shared: Ux %d iterations to %.2e, Uy %d to %.2e; Uc: %s\n", sx.iters, sx.final, sy.iters, sy.final,
           e.msg);
    g.M.rhs[0] = b0;
    linsolve_free(L[0]); /* the others still use its solver */
    memset(y, 0, sizeof(double) * (size_t)nc);
    EXPECT(linsolve_solve_tracked(L[1], y, &sy, &e) == 0 && memcmp(y, y1, sizeof(double) * (size_t)nc) == 0,
           "Uy after Ux was freed: %s", e.msg);
    for (int j = 1; j < 7; j++) linsolve_free(L[j]);
    linsolve_free(Ly);
    for (int j = 0; j < 8; j++) linsolve_settings_free(&s[j]);
    free(x);
    free(y);
    free(y1);
    grid_free(&g);
    dict_free(d);
}

/* A direct solve (LU) through linsolve_solve_tracked: values changed
   without fvmatrix_zero keep the old factors (the state did not move: the
   solution is the old system's, its residual large); assembled anew after
   fvmatrix_zero the factors are rebuilt (exact again). */
TEST(tracked_preconditioner)
{
    Err e;
    Dict *d = dict_parse(shared_fvsolution, strlen(shared_fvsolution), "system/fvSolution", &e);
    EXPECT(d != NULL, "%s", d ? "" : e.msg);
    if (!d) return;
    Grid g;
    grid_make(&g, 24, 0);
    LinSettings s;
    LinSystem *L = system_of(d, "lu", NULL, &g.M, &s);
    int nc = g.f.ncells;
    double *phi = calloc((size_t)nc, sizeof *phi);
    LinStats st, stale, fresh;
    EXPECT(linsolve_solve_tracked(L, phi, &st, &e) == 0 && st.final < 1e-12, "first LU solve: %.3e %s", st.final,
           e.msg);
    for (int c = 0; c < nc; c++) g.M.val[g.M.diag[c]] += 50 * g.m.cell_vol[c];
    memset(phi, 0, sizeof(double) * (size_t)nc);
    EXPECT(linsolve_solve_tracked(L, phi, &stale, &e) == 0 && stale.final > 1e-6,
           "values changed, state kept: residual %.3e (the factors were rebuilt)", stale.final);
    assemble(&g.M, &g.f);
    for (int c = 0; c < nc; c++) g.M.val[g.M.diag[c]] += 50 * g.m.cell_vol[c];
    memset(phi, 0, sizeof(double) * (size_t)nc);
    EXPECT(linsolve_solve_tracked(L, phi, &fresh, &e) == 0 && fresh.final < 1e-12,
           "assembled after fvmatrix_zero: residual %.3e", fresh.final);
    printf("  LU: stale factors give residual %.2e, rebuilt %.2e\n", stale.final, fresh.final);
    linsolve_free(L);
    linsolve_settings_free(&s);
    free(phi);
    grid_free(&g);
    dict_free(d);
}

/* OpenFOAM's DILU and DIC (ours, dilu.h) against PETSc's ilu and icc:
   on block grids (no triangles in the coupling graph) they are the same
   factorisation, so the same iterations (within 5 % for BiCGStab, which
   amplifies the round-off) and the same solution to the tolerance; smoothSolver with the DILU smoother converges too. */
TEST(dilu_is_ilu0)
{
    Dict *d = read_fvsolution();
    static const char *const pairs[2][2] = {{"PBiCGStab_DILU", "PBiCGStab_ilu"}, {"PCG_DIC", "PCG_icc"}};
    for (int three = 0; three <= 1; three++) {
        Grid g;
        grid_make(&g, three ? 16 : 48, three);
        for (int k = 0; k < 2; k++) {
            Run a = solve_with(&g, d, pairs[k][0]), b = solve_with(&g, d, pairs[k][1]);
            EXPECT(a.ok && b.ok, "%s", a.ok ? b.msg : a.msg);
            printf("  %s %s: %s %d iterations, %s %d; L2 errors %.6e %.6e\n", three ? "3-D 16^3" : "2-D 48^2",
                   pairs[k][0], a.desc, a.st.iters, b.desc, b.st.iters, a.l2, b.l2);
            /* BiCGStab's iterations follow the round-off: a few apart */
            EXPECT(abs(a.st.iters - b.st.iters) <= 1 + b.st.iters / 20, "%s: %d iterations, %s: %d", pairs[k][0], a.st.iters,
                   pairs[k][1], b.st.iters);
            EXPECT(fabs(a.l2 - b.l2) <= 1e-6 * b.l2, "L2 errors %.9e and %.9e", a.l2, b.l2);
        }
        grid_free(&g);
    }
    Grid g;
    grid_make(&g, 16, 0);
    Run c = solve_with(&g, d, "smoothDILU");
    EXPECT(c.ok && strcmp(c.desc, "richardson+DILU") == 0, "smoothDILU: %s %s", c.desc, c.msg);
    printf("  smoothSolver (DILU) on 16^2: %d iterations to %.3e\n", c.st.iters, c.st.final);
    /* a zero pivot: the solve fails with the system, file and line */
    for (int k = g.M.off[7]; k <= g.M.diag[7]; k++) g.M.val[k] = 0;
    Run z = solve_with(&g, d, "PBiCGStab_DILU");
    EXPECT(!z.ok, "a zero pivot solved");
    CONTAINS(z.msg, "system/fvSolution:4: solving for PBiCGStab_DILU");
    CONTAINS(z.msg, "zero or non-finite pivot in DILU at row 7");
    grid_free(&g);
    dict_free(d);
}

/* linsolve_release drops the factors and work vectors; the next solve,
   tracked or not, rebuilds them and gives the same bits. */
TEST(release)
{
    Dict *d = read_fvsolution();
    Grid g;
    grid_make(&g, 32, 0);
    static const char *const names[] = {"PBiCGStab_DILU", "PBiCGStab_ilu", "GAMG"};
    for (int k = 0; k < 3; k++) {
        LinSettings s;
        Err e;
        EXPECT(linsolve_settings(&s, d, names[k], &e) == 0, "%s", e.msg);
        LinSystem *L = linsolve_new(&s, &g.M, &e);
        EXPECT(L != NULL, "%s", e.msg);
        size_t n = (size_t)g.f.ncells;
        double *x[3];
        LinStats st[3];
        for (int j = 0; j < 3; j++) {
            x[j] = calloc(n, sizeof *x[j]);
            if (!L) continue;
            if (j == 1) linsolve_release(L);
            int rc = j == 2 ? (linsolve_release(L), linsolve_solve_tracked(L, x[j], &st[j], &e))
                            : linsolve_solve(L, x[j], &st[j], &e);
            EXPECT(rc == 0, "%s solve %d: %s", names[k], j, e.msg);
        }
        EXPECT(memcmp(x[0], x[1], n * sizeof *x[0]) == 0 && memcmp(x[0], x[2], n * sizeof *x[0]) == 0 &&
                   st[0].iters == st[1].iters && st[0].iters == st[2].iters,
               "%s: a solve after linsolve_release differs (%d, %d, %d iterations)", names[k], st[0].iters,
               st[1].iters, st[2].iters);
        for (int j = 0; j < 3; j++) free(x[j]);
        linsolve_free(L);
        linsolve_settings_free(&s);
    }
    grid_free(&g);
    dict_free(d);
}

int main(void)
{
    setenv("PETSC_OPTIONS", "-Uq_ksp_type gmres", 1); /* read when PETSc starts: shared_solver */
    if (getenv("KIESEL_LINSOLVE_BENCH")) {
        bench();
        linsolve_finalize();
        return 0;
    }
    RUN(settings);
    RUN(unknown_names);
    RUN(poisson_2d);
    RUN(poisson_3d);
    RUN(not_converged);
    RUN(reltol_and_exact_guess);
    RUN(options_prefix);
    RUN(values_change);
    RUN(shared_solver);
    RUN(tracked_preconditioner);
    RUN(dilu_is_ilu0);
    RUN(release);
    linsolve_finalize();
    return test_summary();
}
