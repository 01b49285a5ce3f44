/*
** props.h: the physical properties of solveGranular's case:
** constant/granularProperties (which model, its coefficients) and
** constant/g (gravity, OpenFOAM's uniformDimensionedVectorField).
**
**   model Newtonian;               // the isothermal compressible
**   NewtonianCoeffs                // Navier-Stokes equations, eq. 5.1
**   {
**       mu   0.25;                 // dynamic viscosity [kg m^-1 s^-1]
**       RsT  6;                    // p = RsT rho [J kg^-1] (eq. 5.1: 6)
**   }
**
**   model granular;                // the granular model of thesis ch. 2
**   granularCoeffs                 // (eq. 2.37-2.47, fv/closure.h)
**   {
**       eta0     0.00102573;       // eq. 2.21 [m]
**       lambda0  0.00034;          // eq. 2.22 [m]
**       epsilon0 216.649;          // eq. 2.23 [1/m], or instead:
**       // grainDiameter 1e-3; restitution 0.9;   (eq. 2.24)
**       cMax     0.8;              // c_max of g(c) = 1/(1 - c/c_max)
**       c0       0.3;              // onset of the yield terms
**       T0       0;                // yield temperature [m^2/s^2]
**       KT       0.666667;         // heating and conduction factor (2/3;
**                                  // 1.5 the thesis's displayed equations)
**       freezeT  no;               // yes: T stays as read (§5.2.1)
**       deltaC   1e-6;             // limits: c <= cMax - deltaC,
**       Tmin     1e-12;            //         T >= Tmin,
**       cMin     1e-8;             //         c floored to cMin in the
**   }                              //         matrices (safe velocity)
**
** constant/g is optional (no file: no gravity); it must have the
** dimensions of an acceleration.
*/
#ifndef KIESEL_PROPS_H
#define KIESEL_PROPS_H

#include "dict.h"
#include "closure.h"
#include "err.h"

enum { MODEL_NEWTONIAN, MODEL_GRANULAR };

typedef struct GranularProps {
    int model;         /* MODEL_* */
    double mu;         /* Newtonian: dynamic viscosity */
    double RsT;        /* Newtonian: p = RsT rho */
    GranCoeffs k;      /* granular: the closures' coefficients */
    int freezeT;       /* granular: T not solved */
    double dc, Tmin, cmin;   /* granular: the limits (deltaC, Tmin, cMin) */
    double g[3];       /* gravity, 0 without constant/g */
} GranularProps;

/* Keywords, for -help. */
extern const DictKey props_keys[];
extern const DictKey props_newtonian_keys[];
extern const DictKey props_granular_keys[];
extern const char *const props_models[];

/* Reads <case>/constant/granularProperties and <case>/constant/g. */
int props_read(GranularProps *p, const char *case_dir, Err *e);
/* The same from parsed dictionaries (g may be NULL: no gravity). */
int props_parse(GranularProps *p, const Dict *d, const Dict *g, Err *e);

#endif
