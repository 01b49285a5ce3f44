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
** The granular model of thesis ch. 2 (eq. 2.37-2.47) joins `model` in the
** next issue; until then the word is refused with the valid choices.
** constant/g is optional (no file: no gravity); it must have the
** dimensions of an acceleration.
*/
#ifndef KIESEL_PROPS_H
#define KIESEL_PROPS_H

#include "dict.h"
#include "err.h"

enum { MODEL_NEWTONIAN };

typedef struct GranularProps {
    int model;         /* MODEL_* */
    double mu;         /* Newtonian: dynamic viscosity */
    double RsT;        /* Newtonian: p = RsT rho */
    double g[3];       /* gravity, 0 without constant/g */
} GranularProps;

/* Keywords, for -help. */
extern const DictKey props_keys[];
extern const DictKey props_newtonian_keys[];
extern const char *const props_models[];

/* Reads <case>/constant/granularProperties and <case>/constant/g. */
int props_read(GranularProps *p, const char *case_dir, Err *e);
/* The same from parsed dictionaries (g may be NULL: no gravity). */
int props_parse(GranularProps *p, const Dict *d, const Dict *g, Err *e);

#endif
