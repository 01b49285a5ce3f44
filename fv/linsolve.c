/*
** linsolve.c: PETSc's KSP on our CSR arrays (linsolve.h).
**
** No per-entry insertion: MatCreateSeqAIJWithArrays wraps FvMatrix's
** off, col and val as they are (PetscInt must be int and PetscScalar
** double, checked below at compile time), and the right-hand side and the
** unknowns are placed into PETSc vectors for the time of a solve
** (VecPlaceArray).  The pattern never changes; when the values do, a
** MatAssembly bumps the matrix's state, so the preconditioner is rebuilt
** for the new values.  linsolve_solve assembles before every solve;
** linsolve_solve_tracked only when FvMatrix.state moved since the
** preconditioner was built, so the second and third velocity components
** on the same values reuse the factors of the first (an ILU built twice
** from the same values is the same to the bit, so nothing changes but the
** time).
**
** DILU.  OpenFOAM's DILU and DIC are ours (dilu.h), given to PETSc as a
** PCSHELL whose set-up PETSc calls whenever the matrix's state moved,
** like its own preconditioners': one double a cell, where PETSc's ilu
** and icc copy the matrix.
**
** Sharing.  The PETSc objects (matrix wrapper, KSP with its
** preconditioner and work vectors: about 110 bytes a cell in 3-D for
** BiCGStab with DILU, 190 with PETSc's ILU(0)) live
** in a LinCore that several systems on one matrix may share
** (linsolve_new_shared): Ux, Uy and Uz with the same solver,
** preconditioner, maxIter and petscOptions need one, not three.  Each
** system keeps its own name, fvSolution line and tolerances (the
** convergence test reads them per solve); the core keeps the options
** prefix of the first system, so a system whose own prefix is named in
** PETSc's options database (PETSC_OPTIONS) gets a core of its own.
**
** Residual norm.  OpenFOAM divides |b - A x| by the normalisation factor
** |A x - A xbar| + |b - A xbar| (xbar: the uniform field of the mean of
** x), with |.| the sum of magnitudes over cells; the result does not
** depend on the scaling of the equations nor on the size of the grid,
** which is why a tolerance of 1e-6 means the same in every OpenFOAM case.
** We keep that normalisation but use the 2-norm throughout: PETSc tracks
** the 2-norm of the unpreconditioned residual b - A x at every iteration
** (KSP_NORM_UNPRECONDITIONED, the preconditioner moved to the side that
** allows it), so the convergence test costs nothing extra, whereas the
** sum of magnitudes would need the residual vector built each iteration.
** The preconditioned norm PETSc uses by default would make a tolerance
** mean something else for each preconditioner.  The initial and final
** residuals reported are recomputed exactly from x (one pass over the
** matrix each, the initial one together with the normalisation factor);
** for OpenFOAM's tolerances the two norms differ by a factor of order one.
**
** Errors: while our code calls PETSc, an error handler records PETSc's
** first message (it is pushed for the call, with the record on our
** stack), and the caller gets it in Err; outside those calls the handler
** is PetscReturnErrorHandler, so PETSc never prints.
*/
#include "linsolve.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <petscksp.h>

#include "dilu.h"
#include "mem.h"

#if defined(__SANITIZE_ADDRESS__)
/* Under AddressSanitizer (make SANITIZE=1): every program that solves
   through PETSc starts OpenMPI, whose start-up allocations outlive
   MPI_Finalize; LeakSanitizer's suppressions of them
   (etc/sanitize/lsan.c) only match full stacks, and the fast unwinder
   stops at the first frame of a library built without frame pointers.
   Defined here, next to the MPI start, so that exactly the programs
   that link this file pay for the slower unwinding. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "fast_unwind_on_malloc=0"; }
#endif

#if defined(PETSC_USE_64BIT_INDICES) || defined(PETSC_USE_COMPLEX) || !defined(PETSC_USE_REAL_DOUBLE)
#error "Kiesel needs PETSc with 32-bit indices and real double scalars (Debian's petsc-dev)"
#endif
_Static_assert(sizeof(PetscInt) == sizeof(int), "FvMatrix's int arrays are handed to PETSc as PetscInt");
_Static_assert(sizeof(PetscScalar) == sizeof(double), "FvMatrix's values are handed to PETSc as PetscScalar");

/* The defaults of a solvers entry (chosen by measurement:
   doc/performance.md, "Linear solvers"). */
#define DEFAULT_SOLVER "PBiCGStab"
#define DEFAULT_PRECON "DILU"

const DictKey linsolve_keys[] = {
    {"solver", DEFAULT_SOLVER, "OpenFOAM's PCG, PBiCG, PBiCGStab, smoothSolver, GAMG, or a PETSc KSP type"},
    {"preconditioner", DEFAULT_PRECON, "OpenFOAM's DIC, FDIC, DILU, GAMG, diagonal, none, or a PETSc PC type"},
    {"smoother", "GaussSeidel", "smoothSolver's: GaussSeidel, symGaussSeidel, DICGaussSeidel, DIC, DILU, or a PETSc PC type"},
    {"tolerance", "1e-6", "absolute bound on the normalised residual (2-norm)"},
    {"relTol", "0", "bound on the residual relative to the initial one (0: off)"},
    {"maxIter", "1000", "iterations before the solve fails"},
    {"minIter", "0", "iterations before convergence is tested"},
    {"petscOptions", "\"\"", "further PETSc options, under the system's prefix (\"-ksp_gmres_restart 50\")"},
    {"nSweeps", "1", "OpenFOAM's; accepted, no effect"},
    {"nPreSweeps", "0", "OpenFOAM's GAMG; accepted, no effect (tune gamg in petscOptions)"},
    {"nPostSweeps", "2", "OpenFOAM's GAMG; accepted, no effect"},
    {"nFinestSweeps", "2", "OpenFOAM's GAMG; accepted, no effect"},
    {"cacheAgglomeration", "true", "OpenFOAM's GAMG; accepted, no effect"},
    {"agglomerator", "faceAreaPair", "OpenFOAM's GAMG; accepted, no effect"},
    {"nCellsInCoarsestLevel", "10", "OpenFOAM's GAMG; accepted, no effect"},
    {"mergeLevels", "1", "OpenFOAM's GAMG; accepted, no effect"},
    {"directSolveCoarsest", "false", "OpenFOAM's GAMG; accepted, no effect"},
    {NULL, NULL, NULL},
};

/* OpenFOAM's DILU and DIC: ours (dilu.h), a PETSc PCSHELL. */
#define DILU_PC "dilu"

typedef struct NameMap {
    const char *foam, *petsc;
} NameMap;

static const NameMap solver_names[] = {
    {"PCG", "cg"},           {"PBiCG", "bcgs"}, {"PBiCGStab", "bcgs"},
    {"smoothSolver", "richardson"}, {"GAMG", "richardson"}, {NULL, NULL},
};
static const NameMap precon_names[] = {
    {"DIC", DILU_PC}, {"FDIC", DILU_PC}, {"DILU", DILU_PC}, {"GAMG", "gamg"}, {"diagonal", "jacobi"}, {"none", "none"},
    {NULL, NULL},
};
static const NameMap smoother_names[] = {
    {"GaussSeidel", "sor"}, {"symGaussSeidel", "sor"}, {"DICGaussSeidel", "sor"}, {"nonBlockingGaussSeidel", "sor"},
    {"DIC", DILU_PC},       {"DILU", DILU_PC},         {NULL, NULL},
};

static const char *map_name(const NameMap *t, const char *w)
{
    for (; t->foam; t++)
        if (strcmp(t->foam, w) == 0) return t->petsc;
    return NULL;
}

/* ---- PETSc's errors ---- */

typedef struct Capture {
    char msg[768];
    int set;
} Capture;

static PetscErrorCode capture(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n,
                              PetscErrorType p, const char *mess, void *ctx)
{
    Capture *c = ctx;
    (void)comm;
    (void)line;
    (void)file;
    if (p == PETSC_ERROR_INITIAL && !c->set) {
        const char *text = mess;
        if (!text || !*text) PetscErrorMessage(n, &text, NULL);
        snprintf(c->msg, sizeof c->msg, "%s (%s)", text ? text : "error", fun ? fun : "PETSc");
        c->set = 1;
    }
    return n;
}

static void capture_begin(Capture *c)
{
    c->msg[0] = 0;
    c->set = 0;
    PetscPushErrorHandler(capture, c);
}

static const char *capture_end(Capture *c, PetscErrorCode ierr)
{
    PetscPopErrorHandler();
    if (ierr && !c->set) snprintf(c->msg, sizeof c->msg, "error code %d", (int)ierr);
    return c->msg;
}

#define TRY(call)                                                                                                     \
    do {                                                                                                              \
        PetscErrorCode ierr_ = (call);                                                                                \
        if (ierr_) return ierr_;                                                                                      \
    } while (0)

/* ---- starting and ending PETSc ---- */

int linsolve_init(Err *e)
{
    PetscBool up = PETSC_FALSE, down = PETSC_FALSE;
    PetscInitialized(&up);
    if (up) return 0;
    PetscFinalized(&down);
    if (down) return err_set(e, NULL, 0, "PETSc was finalised and cannot be started again");
    /* PETSc keeps argv: static.  No signal handlers (the solvers catch
       SIGINT and SIGTERM themselves), no .petscrc files from the case
       directory, no "options left" report at the end. */
    static char a0[] = "kiesel", a1[] = "-no_signal_handler", a2[] = "-skip_petscrc", a3[] = "-options_left",
                a4[] = "no";
    static char *args[] = {a0, a1, a2, a3, a4, NULL};
    static char **argv = args;
    static int argc = 5;
    if (PetscInitialize(&argc, &argv, NULL, NULL)) return err_set(e, NULL, 0, "PETSc did not start");
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    return 0;
}

void linsolve_finalize(void)
{
    PetscBool up = PETSC_FALSE;
    PetscInitialized(&up);
    if (up) PetscFinalize();
}

/* ---- settings ---- */

/* The word of key k (default def), with the file and line it came from. */
static int word_at(const Dict *d, const char *k, const char *def, const char **w, int *line, Err *e)
{
    const DictEntry *en = dict_find(d, k);
    *line = en ? en->line : d->line;
    if (en && en->dict) return dict_word_or(en->dict, k, def, w, e);
    return dict_word_or(d, k, def, w, e);
}

/* Does PETSc know these types?  A throwaway KSP is given them. */
static PetscErrorCode try_types(const char *ksp, const char *pc, int *bad_ksp)
{
    KSP k;
    PC p;
    TRY(KSPCreate(PETSC_COMM_SELF, &k));
    *bad_ksp = 1;
    PetscErrorCode ierr = KSPSetType(k, ksp);
    if (!ierr) {
        *bad_ksp = 0;
        ierr = KSPGetPC(k, &p);
        if (!ierr) ierr = PCSetType(p, strcmp(pc, DILU_PC) ? pc : PCSHELL);
    }
    KSPDestroy(&k);
    return ierr;
}

static int check_types(const LinSettings *s, int sline, int pline, Err *e)
{
    Capture c;
    int bad_ksp = 0;
    capture_begin(&c);
    PetscErrorCode ierr = try_types(s->ksp, s->pc, &bad_ksp);
    const char *why = capture_end(&c, ierr);
    if (!ierr) return 0;
    if (bad_ksp)
        return err_set(e, s->file, sline,
                       "solver '%s' for '%s' is neither OpenFOAM's (PCG, PBiCG, PBiCGStab, smoothSolver, GAMG) "
                       "nor a PETSc KSP type (PETSc: %s)",
                       s->solver, s->name, why);
    return err_set(e, s->file, pline,
                   "preconditioner '%s' for '%s' is neither OpenFOAM's (DIC, FDIC, DILU, GAMG, diagonal, none) "
                   "nor a PETSc PC type of this PETSc (PETSc: %s)",
                   s->precon, s->name, why);
}

static void copy_word(char *dst, const char *src) { snprintf(dst, 64, "%s", src); }

/* solver, preconditioner (or smoother) and their PETSc types. */
static int read_types(LinSettings *s, const Dict *d, Err *e)
{
    const char *w, *pw;
    int sline, pline;
    if (word_at(d, "solver", DEFAULT_SOLVER, &w, &sline, e)) return -1;
    copy_word(s->solver, w);
    const char *ksp = map_name(solver_names, w);
    copy_word(s->ksp, ksp ? ksp : w);
    const char *pc;
    if (strcmp(w, "GAMG") == 0) {
        pline = sline;
        copy_word(s->precon, "GAMG");
        pc = "gamg";
    } else if (strcmp(w, "smoothSolver") == 0) {
        if (word_at(d, "smoother", "GaussSeidel", &pw, &pline, e)) return -1;
        copy_word(s->precon, pw);
        pc = map_name(smoother_names, pw);
        if (!pc) pc = pw;
    } else {
        if (word_at(d, "preconditioner", DEFAULT_PRECON, &pw, &pline, e)) return -1;
        copy_word(s->precon, pw);
        pc = map_name(precon_names, pw);
        if (!pc) pc = pw;
    }
    copy_word(s->pc, pc);
    return check_types(s, sline, pline, e);
}

static int read_numbers(LinSettings *s, const Dict *d, Err *e)
{
    if (dict_scalar_or(d, "tolerance", 1e-6, &s->tol, e) || dict_scalar_or(d, "relTol", 0, &s->reltol, e) ||
        dict_label_or(d, "maxIter", 1000, &s->maxiter, e) || dict_label_or(d, "minIter", 0, &s->miniter, e))
        return -1;
    const DictEntry *en = dict_find(d, "tolerance");
    if (!(s->tol >= 0) || !(s->reltol >= 0) || s->reltol >= 1)
        return err_set(e, s->file, en ? en->line : s->line,
                       "'%s': tolerance (%g) must be >= 0 and relTol (%g) in [0, 1)", s->name, s->tol, s->reltol);
    if (s->maxiter < 1 || s->miniter < 0)
        return err_set(e, s->file, s->line, "'%s': maxIter (%d) must be >= 1 and minIter (%d) >= 0", s->name,
                       s->maxiter, s->miniter);
    const char *opt;
    if (dict_word_or(d, "petscOptions", "", &opt, e)) return -1;
    s->options = *opt ? mem_strdup(opt) : NULL;
    return 0;
}

int linsolve_settings(LinSettings *s, const Dict *fvsol, const char *name, Err *e)
{
    memset(s, 0, sizeof *s);
    const Dict *solvers = dict_subdict(fvsol, "solvers", e);
    if (!solvers) return -1;
    const DictEntry *en = dict_find(solvers, name);
    if (!en || !en->dict)
        return err_set(e, en ? en->file : solvers->file, en ? en->line : solvers->line,
                       "solvers: no dictionary for '%s' (a key '%s' or a quoted regular expression matching it)",
                       name, name);
    s->name = mem_strdup(name);
    s->file = mem_strdup(en->file ? en->file : "fvSolution");
    s->line = en->line;
    if (dict_check_keys(en->dict, linsolve_keys, e) || linsolve_init(e) || read_types(s, en->dict, e) ||
        read_numbers(s, en->dict, e)) {
        linsolve_settings_free(s);
        return -1;
    }
    return 0;
}

void linsolve_settings_free(LinSettings *s)
{
    free(s->name);
    free(s->file);
    free(s->options);
    memset(s, 0, sizeof *s);
}

/* ---- systems ---- */

typedef struct Conv {
    double nf, tol, reltol, r0;
    int miniter;
} Conv;

/* The PETSc side of one or more systems on one matrix (linsolve.h,
   linsolve_new_shared): refs systems use it. */
typedef struct LinCore {
    int refs;
    FvMatrix *M;
    Mat A;
    KSP ksp;
    Vec b, x;
    Conv conv;
    Dilu dilu;             /* the DILU preconditioner's diagonal */
    int built;             /* a solve assembled A ... */
    unsigned long state;   /* ... from M's values at this M->state */
    char prefix[80];
    char desc[140];
} LinCore;

struct LinSystem {
    LinSettings s;
    LinCore *core;
};

/* OpenFOAM's tests with our norm (linsolve.c's header); rnorm is the
   2-norm of the unpreconditioned residual. */
static PetscErrorCode converged(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
    Conv *c = ctx;
    (void)ksp;
    *reason = KSP_CONVERGED_ITERATING;
    if (it == 0) c->r0 = rnorm;
    if (!isfinite(rnorm)) *reason = KSP_DIVERGED_NANORINF;
    else if (it < c->miniter) return 0;
    else if (rnorm <= c->tol * c->nf) *reason = KSP_CONVERGED_ATOL;
    else if (c->reltol > 0 && rnorm <= c->reltol * c->r0) *reason = KSP_CONVERGED_RTOL;
    return 0;
}

static void make_prefix(char *p, size_t n, const char *name)
{
    size_t k = 0;
    for (; name[k] && k + 2 < n; k++) {
        char ch = name[k];
        p[k] = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ? ch : '_';
    }
    p[k++] = '_';
    p[k] = 0;
}

static PetscErrorCode set_options(LinCore *C, const LinSettings *s)
{
    const char *o = s->options;
    if (o) {
        TRY(PetscOptionsPrefixPush(NULL, C->prefix));
        PetscErrorCode ierr = PetscOptionsInsertString(NULL, o);
        PetscOptionsPrefixPop(NULL);
        TRY(ierr);
    }
    TRY(KSPSetFromOptions(C->ksp));
    KSPType t;
    TRY(KSPGetType(C->ksp, &t));
    if (strcmp(t, KSPPREONLY) == 0) return KSPSetInitialGuessNonzero(C->ksp, PETSC_FALSE);
    if (!(o && strstr(o, "-ksp_norm_type"))) {
        TRY(KSPSetNormType(C->ksp, KSP_NORM_UNPRECONDITIONED));
        TRY(KSPSetConvergenceTest(C->ksp, converged, &C->conv, NULL));
    }
    return 0;
}

/* ---- the DILU preconditioner as a PETSc PCSHELL ---- */

static PetscErrorCode dilu_setup(PC pc)
{
    LinCore *C;
    TRY(PCShellGetContext(pc, &C));
    int bad = dilu_build(&C->dilu, C->M);
    if (bad) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "zero or non-finite pivot in DILU at row %d", bad - 1);
    return 0;
}

static PetscErrorCode dilu_run(PC pc, Vec x, Vec y, int transpose)
{
    LinCore *C;
    const PetscScalar *r;
    PetscScalar *w;
    TRY(PCShellGetContext(pc, &C));
    TRY(VecGetArrayRead(x, &r));
    TRY(VecGetArray(y, &w));
    if (transpose) dilu_apply_transpose(&C->dilu, C->M, r, w);
    else dilu_apply(&C->dilu, C->M, r, w);
    TRY(VecRestoreArray(y, &w));
    return VecRestoreArrayRead(x, &r);
}

static PetscErrorCode dilu_apply_pc(PC pc, Vec x, Vec y) { return dilu_run(pc, x, y, 0); }
static PetscErrorCode dilu_apply_pc_t(PC pc, Vec x, Vec y) { return dilu_run(pc, x, y, 1); }

static PetscErrorCode dilu_shell(PC pc, LinCore *C)
{
    TRY(PCSetType(pc, PCSHELL));
    TRY(PCShellSetContext(pc, C));
    TRY(PCShellSetSetUp(pc, dilu_setup));
    TRY(PCShellSetApply(pc, dilu_apply_pc));
    TRY(PCShellSetApplyTranspose(pc, dilu_apply_pc_t));
    return PCShellSetName(pc, "DILU");
}

static PetscErrorCode setup(LinCore *C, const LinSettings *s)
{
    FvMatrix *M = C->M;
    PC pc;
    TRY(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, M->nrows, M->ncols, M->off, M->col, M->val, &C->A));
    TRY(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, M->nrows, NULL, &C->b));
    TRY(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, M->ncols, NULL, &C->x));
    TRY(KSPCreate(PETSC_COMM_SELF, &C->ksp));
    TRY(KSPSetOptionsPrefix(C->ksp, C->prefix));
    TRY(KSPSetType(C->ksp, s->ksp));
    TRY(KSPGetPC(C->ksp, &pc));
    if (strcmp(s->pc, DILU_PC) == 0) TRY(dilu_shell(pc, C));
    else TRY(PCSetType(pc, s->pc));
    TRY(KSPSetTolerances(C->ksp, 0, 0, PETSC_DEFAULT, s->maxiter));
    TRY(KSPSetInitialGuessNonzero(C->ksp, PETSC_TRUE));
    TRY(set_options(C, s));
    TRY(KSPSetOperators(C->ksp, C->A, C->A));
    KSPType kt;
    PCType pt;
    TRY(KSPGetType(C->ksp, &kt));
    TRY(PCGetType(pc, &pt));
    const char *pn = pt;
    if (pt && strcmp(pt, PCSHELL) == 0) TRY(PCShellGetName(pc, &pn));
    snprintf(C->desc, sizeof C->desc, "%s+%s", kt, pn ? pn : "none");
    return 0;
}

static void settings_copy(LinSettings *d, const LinSettings *s)
{
    *d = *s;
    d->name = mem_strdup(s->name);
    d->file = mem_strdup(s->file);
    d->options = s->options ? mem_strdup(s->options) : NULL;
}

static void core_free(LinCore *C)
{
    if (!C || --C->refs > 0) return;
    Capture c;
    capture_begin(&c);
    KSPDestroy(&C->ksp);
    VecDestroy(&C->b);
    VecDestroy(&C->x);
    MatDestroy(&C->A);
    capture_end(&c, 0);
    dilu_free(&C->dilu);
    free(C);
}

static LinCore *core_new(const LinSettings *s, FvMatrix *M, Err *e)
{
    LinCore *C = MEM_NEW(LinCore, 1);
    C->refs = 1;
    C->M = M;
    make_prefix(C->prefix, sizeof C->prefix, s->name);
    Capture c;
    capture_begin(&c);
    PetscErrorCode ierr = setup(C, s);
    const char *why = capture_end(&c, ierr);
    if (ierr) {
        err_set(e, s->file, s->line, "setting up the solver of '%s' (%s, %s): PETSc: %s", s->name, s->solver,
                s->precon, why);
        core_free(C);
        return NULL;
    }
    return C;
}

LinSystem *linsolve_new(const LinSettings *s, FvMatrix *M, Err *e)
{
    if (linsolve_init(e)) return NULL;
    if (M->nrows != M->ncols) {
        err_set(e, s->file, s->line, "'%s': %d rows but %d columns: halo cells need a distributed solve", s->name,
                M->nrows, M->ncols);
        return NULL;
    }
    LinCore *C = core_new(s, M, e);
    if (!C) return NULL;
    LinSystem *L = MEM_NEW(LinSystem, 1);
    settings_copy(&L->s, s);
    L->core = C;
    return L;
}

/* Does PETSc's options database name an option under prefix p (a
   PETSC_OPTIONS environment variable, or another system's petscOptions
   of the same name)? */
static int prefix_used(const char *p)
{
    char *all = NULL, key[96];
    if (PetscOptionsGetAll(NULL, &all) || !all) return 1;
    snprintf(key, sizeof key, "-%s", p);
    const char *q = strstr(all, key);
    int used = q && (q == all || q[-1] == ' ');
    PetscFree(all);
    return used;
}

static int same_solver(const LinSettings *a, const LinSettings *b)
{
    return !strcmp(a->ksp, b->ksp) && !strcmp(a->pc, b->pc) && a->maxiter == b->maxiter &&
           (a->options ? b->options && !strcmp(a->options, b->options) : !b->options);
}

LinSystem *linsolve_new_shared(const LinSettings *s, LinSystem *with, Err *e)
{
    char p[80];
    make_prefix(p, sizeof p, s->name);
    if (!same_solver(s, &with->s) || (strcmp(p, with->core->prefix) && prefix_used(p)))
        return linsolve_new(s, with->core->M, e);
    LinSystem *L = MEM_NEW(LinSystem, 1);
    settings_copy(&L->s, s);
    L->core = with->core;
    L->core->refs++;
    return L;
}

int linsolve_shares(const LinSystem *a, const LinSystem *b) { return a->core == b->core; }

void linsolve_free(LinSystem *L)
{
    if (!L) return;
    core_free(L->core);
    linsolve_settings_free(&L->s);
    free(L);
}

const char *linsolve_describe(const LinSystem *L) { return L->core->desc; }

void linsolve_release(LinSystem *L)
{
    LinCore *C = L->core;
    Capture c;
    capture_begin(&c);
    KSPReset(C->ksp);
    capture_end(&c, 0);
    dilu_free(&C->dilu);
    C->built = 0;
}

/* |b - A x|_2, one pass over the matrix.  (The sums are those of a
   product into a vector and a second pass over it, term by term.) */
static double residual(const FvMatrix *M, const double *x)
{
    double s = 0;
    for (int r = 0; r < M->nrows; r++) {
        double ax = 0;
        for (int k = M->off[r]; k < M->off[r + 1]; k++) ax += M->val[k] * x[M->col[k]];
        s += (M->rhs[r] - ax) * (M->rhs[r] - ax);
    }
    return sqrt(s);
}

/* The same, and OpenFOAM's normalisation factor in the 2-norm
   (linsolve.c's header) into *nf, in the same pass. */
static double residual_and_factor(const FvMatrix *M, const double *x, double *nf)
{
    double xbar = 0;
    for (int r = 0; r < M->nrows; r++) xbar += x[r];
    xbar /= M->nrows > 0 ? M->nrows : 1;
    double s = 0, s1 = 0, s2 = 0;
    for (int r = 0; r < M->nrows; r++) {
        double ax = 0, rowsum = 0;
        for (int k = M->off[r]; k < M->off[r + 1]; k++) {
            ax += M->val[k] * x[M->col[k]];
            rowsum += M->val[k];
        }
        double xref = xbar * rowsum;
        s += (M->rhs[r] - ax) * (M->rhs[r] - ax);
        s1 += (ax - xref) * (ax - xref);
        s2 += (M->rhs[r] - xref) * (M->rhs[r] - xref);
    }
    *nf = sqrt(s1) + sqrt(s2) + 1e-20;
    return sqrt(s);
}

static PetscErrorCode run(LinCore *C, int assemble, double *x, PetscInt *its, KSPConvergedReason *reason)
{
    if (assemble) {
        /* the values changed in place: assembling bumps the matrix's
           state, so the preconditioner is rebuilt */
        TRY(MatAssemblyBegin(C->A, MAT_FINAL_ASSEMBLY));
        TRY(MatAssemblyEnd(C->A, MAT_FINAL_ASSEMBLY));
        TRY(KSPSetOperators(C->ksp, C->A, C->A));
    }
    TRY(VecPlaceArray(C->b, C->M->rhs));
    TRY(VecPlaceArray(C->x, x));
    PetscErrorCode ierr = KSPSolve(C->ksp, C->b, C->x);
    VecResetArray(C->b);
    VecResetArray(C->x);
    TRY(ierr);
    TRY(KSPGetIterationNumber(C->ksp, its));
    TRY(KSPGetConvergedReason(C->ksp, reason));
    return 0;
}

static int solve_failed(const LinSystem *L, KSPConvergedReason reason, const LinStats *st, Err *e)
{
    const LinSettings *s = &L->s;
    if (reason == KSP_DIVERGED_ITS)
        return err_set(e, s->file, s->line,
                       "solving for %s did not converge in %d iterations (maxIter): residual %.6g (initial %.6g, "
                       "tolerance %g, relTol %g; %s, %s)",
                       s->name, st->iters, st->final, st->initial, s->tol, s->reltol, s->solver, s->precon);
    return err_set(e, s->file, s->line,
                   "solving for %s failed after %d iterations (PETSc: %s): residual %.6g (initial %.6g; %s, %s)",
                   s->name, st->iters, KSPConvergedReasons[reason], st->final, st->initial, s->solver, s->precon);
}

/* Did a solve that PETSc stopped with a breakdown still converge?  Its
   final residual meets tolerance or relTol, or is round-off of the right
   side: a uniform field that solves its system to the last digits has
   a normalisation factor (linsolve.c's header) of round-off size too, and
   no Krylov step can do better (OpenFOAM's solvers return there without
   an error). */
static int converged_final(const LinSystem *L, const LinStats *st, double nf)
{
    const FvMatrix *M = L->core->M;
    if (!isfinite(st->final)) return 0;
    if (st->final <= L->s.tol || (L->s.reltol > 0 && st->final <= L->s.reltol * st->initial)) return 1;
    double b = 0;
    for (int r = 0; r < M->nrows; r++) b += M->rhs[r] * M->rhs[r];
    return st->final * nf <= 1e-12 * sqrt(b);
}

/* The solve; assemble 0 keeps A's state and with it the preconditioner. */
static int solve(LinSystem *L, int assemble, double *x, LinStats *st, Err *e)
{
    LinCore *C = L->core;
    const FvMatrix *M = C->M;
    double nf;
    double r0 = residual_and_factor(M, x, &nf);
    C->conv = (Conv){nf, L->s.tol, L->s.reltol, 0, L->s.miniter};
    st->initial = r0 / nf;
    st->iters = 0;
    PetscInt its = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    Capture c;
    capture_begin(&c);
    PetscErrorCode ierr = run(C, assemble, x, &its, &reason);
    const char *why = capture_end(&c, ierr);
    if (ierr) {
        C->built = 0;
        return err_set(e, L->s.file, L->s.line, "solving for %s (%s, %s): PETSc: %s", L->s.name, L->s.solver,
                       L->s.precon, why);
    }
    C->built = reason >= 0;
    C->state = M->state;
    st->iters = (int)its;
    st->final = residual(M, x) / nf;
    /* A Krylov solver stops with a breakdown when it hits the exact
       solution (BiCGStab's rho = 0 once the residual is 0), before asking
       the convergence test: what counts is the residual it left. */
    if (reason < 0 && !converged_final(L, st, nf)) return solve_failed(L, reason, st, e);
    return 0;
}

int linsolve_solve(LinSystem *L, double *x, LinStats *st, Err *e) { return solve(L, 1, x, st, e); }

int linsolve_solve_tracked(LinSystem *L, double *x, LinStats *st, Err *e)
{
    const LinCore *C = L->core;
    return solve(L, !C->built || C->state != C->M->state, x, st, e);
}
