/*
** mms.h: the manufactured-solution study of tests/validation/mms
** (mms.c, the tables; mms_case.c, one grid level; mms_check.c, the
** checks of make test).  See mms.c for what is measured and how.
*/
#ifndef KIESEL_MMS_H
#define KIESEL_MMS_H

#include "mms_exact.h"
#include "mms_exact_gran.h"
#include "newtonian.h"

/* The error norms: L1 rho, Linf rho, L1 |u|, Linf |u| (model granular: c
   for rho) and, model granular only, L1 T, Linf T. */
enum { MMS_NQ = 6 };

typedef struct Study {
    const char *kind, *interp, *div;   /* mms.c's words */
    int granular;                      /* -model granular (else Newtonian) */
    int dim, voronoi, layers;
    int jacobian;                      /* the heating's (GRAN_JAC_FACE, ...) */
    double mu, RsT, tol, tmax, maxCo;
    double max_skewness;               /* mergeCells' maxSkewness */
    double expect[MMS_NQ];             /* expected orders by norm, < 0: none */
    MmsParams p;                       /* model Newtonian's solution */
    GranCoeffs k;                      /* model granular's closures */
    MmsGranParams pg;                  /* and its solution */
} Study;

/* The steady source integrals the hook hands the model (T: model
   granular's s_T). */
typedef struct MmsSource {
    int n;
    double *rho, *m, *T;
} MmsSource;

/* One grid level: the grid, the fields at the exact state, the model
   with the source hook. */
typedef struct MmsCase {
    Mesh m;
    FvMesh f;
    Interp ip;
    Field rho, U, T;                   /* T: model granular's Theta */
    Dict *sol;
    MmsSource src;
    Granular g;
} MmsCase;

typedef struct Level {
    int N, cells, steps;
    double t, rate, mass_change, secs;
    double err[MMS_NQ];
} Level;

/* The defaults of mms.c's options and the solution's parameters. */
void mms_study_default(Study *s);
/* The exact solution at x (2-D or 3-D), model Newtonian's and granular's. */
void mms_exact(const Study *s, const double x[3], MmsPoint *o);
void mms_gran_exact(const Study *s, const double x[3], MmsGranPoint *o);

/* Level N of study s: grid, fields, model.  A failure prints a FAIL line
   and ends the program. */
void mms_case_init(MmsCase *k, const Study *s, int N);
void mms_case_free(MmsCase *k);
/* Runs k at maxCo to the steady state (or tmax) into lv (steps, t, rate). */
void mms_steady(const Study *s, MmsCase *k, Level *lv);
/* The errors against the exact solution at the nodes into lv->err. */
void mms_errors(const Study *s, const MmsCase *k, Level *lv);

/* The checks of make test (mms -check); returns the number of FAILs. */
int mms_check(void);

#endif
