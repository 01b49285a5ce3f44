/*
** linsolve.h: the linear solves of the implicit systems through PETSc's
** KSP, set up from system/fvSolution in OpenFOAM's style (spec
** granular-model.md §4.3: one sparse n_c x n_c system per velocity
** component and time step, eq. 4.66).
**
**   solvers
**   {
**       "U.*"  { solver PBiCGStab; preconditioner DILU; tolerance 1e-8; relTol 0; maxIter 1000; }
**       rho    { solver gmres; preconditioner hypre; petscOptions "-ksp_gmres_restart 50"; }
**   }
**
** A system's entry is found as OpenFOAM finds it: the literal key first,
** then the quoted regular expressions, the last match winning.  solver and
** preconditioner take OpenFOAM's names (mapped to PETSc: PCG -> cg,
** PBiCG and PBiCGStab -> bcgs, smoothSolver -> richardson with its
** smoother, GAMG -> richardson with PETSc's gamg; DIC, FDIC and DILU -> OpenFOAM's
** DILU, ours (dilu.h, a PETSc shell: one double a cell where PETSc's ilu
** and icc copy the matrix), GAMG -> gamg, diagonal -> jacobi, none) or
** PETSc's own
** type names (gmres, cg, bcgs, ...; hypre, gamg, ilu, sor, ...);
** petscOptions is passed to PETSc under the system's own options prefix
** ("-Ux_" for Ux), so one system's options never reach another, and it
** is applied last, so it overrides the entry's other keywords.  Names are
** checked against PETSc when the entry is read: a misspelt solver or a
** preconditioner this PETSc was built without is an error with the
** fvSolution file and line before any solve.
**
** Residuals are OpenFOAM's normalised residual with the 2-norm in place of
** the sum of magnitudes (see linsolve.c):
**     res = |b - A x|_2 / (|A x - A xbar|_2 + |b - A xbar|_2 + 1e-20),
** xbar the uniform field of the mean of the initial guess.  tolerance is
** an absolute bound on res, relTol a bound on res / res_initial (0: off);
** the solve stops at whichever is met first, or fails after maxIter.
**
** PETSc is initialised once per process (linsolve_init, called by the
** readers when needed), serially on PETSC_COMM_SELF without mpirun, with
** its error handler replaced so that it never prints and its signal
** handlers off, so that a solver's own SIGINT/SIGTERM handling stays
** its own.  linsolve_finalize ends it, once, at the end of a program.
*/
#ifndef KIESEL_LINSOLVE_H
#define KIESEL_LINSOLVE_H

#include "dict.h"
#include "err.h"
#include "fvmatrix.h"

/* One system's settings, as read from its fvSolution entry. */
typedef struct LinSettings {
    char *name;              /* the system solved for, e.g. "Ux" */
    char *file;              /* fvSolution and the line of the entry */
    int line;
    char solver[64], precon[64];  /* as written (or the defaults) */
    char ksp[64], pc[64];    /* the PETSc types they map to */
    double tol, reltol;
    int maxiter, miniter;
    char *options;           /* petscOptions, or NULL */
} LinSettings;

/* The solver log's numbers (OpenFOAM's "Solving for Ux, Initial residual
   = ..., Final residual = ..., No Iterations N"). */
typedef struct LinStats {
    double initial, final;
    int iters;
} LinStats;

typedef struct LinSystem LinSystem;

/* The keywords of a solvers entry with their defaults, for -help. */
extern const DictKey linsolve_keys[];

/* Starts PETSc once per process (later calls do nothing); fails when
   PETSc was already finalised or will not start. */
int linsolve_init(Err *e);
/* Ends PETSc (at the end of a program: it cannot be started again). */
void linsolve_finalize(void);

/* Reads the settings of system name from fvsol (system/fvSolution: its
   solvers dictionary), checking every keyword and every solver name. */
int linsolve_settings(LinSettings *s, const Dict *fvsol, const char *name, Err *e);
void linsolve_settings_free(LinSettings *s);

/* A solver for the matrix M (its arrays are shared with PETSc, not
   copied: M must outlive the LinSystem and keep its pattern). */
LinSystem *linsolve_new(const LinSettings *s, FvMatrix *M, Err *e);
/* A solver for the matrix of `with` that shares with's PETSc solver
   (KSP, preconditioner, work vectors: memory once, and a preconditioner
   built for one system's values serves the other's) when the two agree
   on solver, preconditioner, maxIter and petscOptions; otherwise its own,
   as linsolve_new.  Names, fvSolution lines and tolerances stay each
   system's own.  The systems may be freed in any order. */
LinSystem *linsolve_new_shared(const LinSettings *s, LinSystem *with, Err *e);
/* Do a and b share one PETSc solver? */
int linsolve_shares(const LinSystem *a, const LinSystem *b);
void linsolve_free(LinSystem *L);

/* Solves M x = M.rhs from the initial guess x (ncols values; serial, so
   ncols = nrows).  M's values may have changed since the last solve.  A
   solve that does not converge within maxIter, or breaks down, fails with
   the system's name, the residual reached and the fvSolution file and
   line of its entry; x then holds the last iterate. */
int linsolve_solve(LinSystem *L, double *x, LinStats *st, Err *e);
/* The same for a caller whose every change of M's values goes through
   fvmatrix_zero or fvmatrix_zero_values (which bump M->state): the
   preconditioner is rebuilt only when M->state moved since it was built,
   so systems that share a solver and a matrix (linsolve_new_shared) solve
   one after the other on one factorisation. */
int linsolve_solve_tracked(LinSystem *L, double *x, LinStats *st, Err *e);

/* Frees the preconditioner's factors and the Krylov work vectors (PETSc's
   KSPReset) until the next solve rebuilds them, so that a phase between
   solves (writing a time) can use their memory.  The next solve
   factorises anew; its result is the one it would have been. */
void linsolve_release(LinSystem *L);

/* "cg+DILU": the PETSc solver and preconditioner in use (after
   petscOptions). */
const char *linsolve_describe(const LinSystem *L);

#endif
