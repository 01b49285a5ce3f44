/*
** props.c: constant/granularProperties and constant/g (props.h).
*/
#include "props.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "field.h"
#include "io.h"

const char *const props_models[] = {"Newtonian", "granular", NULL};

const DictKey props_keys[] = {
    {"model", NULL,
     "the model: Newtonian (isothermal compressible Navier-Stokes, eq. 5.1) | granular (volume fraction, "
     "momentum and granular temperature, eq. 2.37-2.47)"},
    {"NewtonianCoeffs", NULL, "the Newtonian model's coefficients"},
    {"granularCoeffs", NULL, "the granular model's coefficients"},
    {NULL, NULL, NULL}};

const DictKey props_newtonian_keys[] = {
    {"mu", NULL, "dynamic viscosity [kg/(m s)] (thesis §5.1: 0.25)"},
    {"RsT", NULL, "p = RsT rho [J/kg] (thesis §5.1: 6)"},
    {NULL, NULL, NULL}};

const DictKey props_granular_keys[] = {
    {"eta0", NULL, "eta_k = eta0 sqrt(T) c g(c) [m] (eq. 2.21)"},
    {"lambda0", NULL, "lambda_k = lambda0 sqrt(T) c g(c) [m] (eq. 2.22)"},
    {"epsilon0", NULL, "eps_k = epsilon0 sqrt(T) g(c) [1/m] (eq. 2.23); or grainDiameter and restitution"},
    {"grainDiameter", NULL, "d of eq. 2.24 [m], with restitution, instead of epsilon0"},
    {"restitution", NULL, "e of eq. 2.24 (0 <= e <= 1), with grainDiameter"},
    {"cMax", NULL, "c_max of g(c) = 1/(1 - c/c_max) (eq. 2.15), 0 < cMax <= 1"},
    {"c0", "0", "volume fraction where the yield terms start (eq. 2.26-2.29), 0 <= c0 < cMax"},
    {"T0", "0", "yield temperature [m^2/s^2] (eq. 2.26): 0 switches the yield terms off"},
    {"KT", "0.666667", "factor on viscous heating and conduction: 2/3 (kinetic energy 3/2 c T) or 1.5 (the "
                       "thesis's displayed equations); printed in the log"},
    {"freezeT", "no", "yes: the granular temperature stays as read, its equation is not solved (thesis §5.2.1)"},
    {"deltaC", "1e-6", "limit c <= cMax - deltaC after each step (counted in the log)"},
    {"Tmin", "1e-12", "limit T >= Tmin after each step [m^2/s^2] (counted in the log)"},
    {"cMin", "1e-8", "c below this is taken as cMin in the implicit matrices, so that empty cells get a "
                     "velocity and a temperature (counted in the log)"},
    {NULL, NULL, NULL}};

/* A required positive coefficient of d. */
static int positive(const Dict *d, const char *key, double *out, Err *e)
{
    if (dict_scalar(d, key, out, e)) return -1;
    if (!(*out > 0) || !isfinite(*out)) {
        const DictEntry *en = dict_find(d, key);
        return err_set(e, en ? en->file : NULL, en ? en->line : 0, "%s must be positive, found %g", key, *out);
    }
    return 0;
}

static int gravity(GranularProps *p, const Dict *g, Err *e)
{
    memset(p->g, 0, sizeof p->g);
    if (!g) return 0;
    const char *cls = dict_header_class(g);
    const DictEntry *any = dict_find(g, "value");
    const char *file = any ? any->file : NULL;
    if (cls && strcmp(cls, "uniformDimensionedVectorField"))
        return err_set(e, file, 0, "constant/g: class %s, expected uniformDimensionedVectorField", cls);
    double dims[7];
    static const double accel[7] = {0, 1, -2, 0, 0, 0, 0};
    if (field_read_dims(g, file, dims, e)) return -1;
    if (memcmp(dims, accel, sizeof dims)) {
        const DictEntry *en = dict_find(g, "dimensions");
        return err_set(e, en->file, en->line, "gravity must have the dimensions of an acceleration [0 1 -2 0 0 0 0]");
    }
    return dict_vector(g, "value", p->g, e);
}

/* An optional coefficient of d in [lo, hi] (lo_open: > lo). */
static int ranged(const Dict *d, const char *key, double def, double lo, int lo_open, double hi, double *out, Err *e)
{
    if (dict_scalar_or(d, key, def, out, e)) return -1;
    if (!isfinite(*out) || *out < lo || (lo_open && *out == lo) || *out > hi) {
        const DictEntry *en = dict_find(d, key);
        return err_set(e, en ? en->file : d->file, en ? en->line : d->line, "%s must be in %s%g, %g], found %g", key,
                       lo_open ? "(" : "[", lo, hi, *out);
    }
    return 0;
}

/* epsilon0, or grainDiameter with restitution (eq. 2.24): exactly one. */
static int dissipation(const Dict *c, GranCoeffs *k, Err *e)
{
    const DictEntry *eps = dict_find(c, "epsilon0"), *d = dict_find(c, "grainDiameter"), *r = dict_find(c, "restitution");
    if (eps && (d || r))
        return err_set(e, eps->file, eps->line, "give either epsilon0 or grainDiameter and restitution, not both");
    if (eps) return ranged(c, "epsilon0", 0, 0, 0, INFINITY, &k->eps0, e);
    if (!d || !r)
        return err_set(e, c->file, c->line, "granularCoeffs: missing epsilon0 (or grainDiameter and restitution)");
    double dd, ee;
    if (positive(c, "grainDiameter", &dd, e) || ranged(c, "restitution", 0, 0, 0, 1, &ee, e)) return -1;
    k->eps0 = closure_eps0_from_grain(dd, ee);
    return 0;
}

static int granular(GranularProps *p, const Dict *c, Err *e)
{
    GranCoeffs *k = &p->k;
    if (dict_check_keys(c, props_granular_keys, e) || ranged(c, "eta0", 0, 0, 0, INFINITY, &k->eta0, e) ||
        ranged(c, "lambda0", 0, 0, 0, INFINITY, &k->lambda0, e) || dissipation(c, k, e))
        return -1;
    if (!dict_find(c, "eta0") || !dict_find(c, "lambda0") || !dict_find(c, "cMax"))
        return err_set(e, c->file, c->line, "granularCoeffs: eta0, lambda0 and cMax are required");
    if (ranged(c, "cMax", 0, 0, 1, 1, &k->cmax, e) || ranged(c, "c0", 0, 0, 0, k->cmax, &k->c0, e) ||
        ranged(c, "T0", 0, 0, 0, INFINITY, &k->T0, e) || ranged(c, "KT", 2.0 / 3.0, 0, 1, INFINITY, &k->KT, e) ||
        dict_switch_or(c, "freezeT", 0, &p->freezeT, e) || ranged(c, "deltaC", 1e-6, 0, 1, k->cmax, &p->dc, e) ||
        ranged(c, "Tmin", 1e-12, 0, 1, INFINITY, &p->Tmin, e) || ranged(c, "cMin", 1e-8, 0, 1, k->cmax, &p->cmin, e))
        return -1;
    if (k->c0 >= k->cmax) {
        const DictEntry *en = dict_find(c, "c0");
        return err_set(e, en->file, en->line, "c0 must be below cMax (%g), found %g", k->cmax, k->c0);
    }
    return 0;
}

int props_parse(GranularProps *p, const Dict *d, const Dict *g, Err *e)
{
    static const char *const coeffs[] = {"NewtonianCoeffs", "granularCoeffs"};
    memset(p, 0, sizeof *p);
    if (dict_check_keys(d, props_keys, e)) return -1;
    if (!dict_find(d, "model")) {
        const DictEntry *first = dict_find(d, "NewtonianCoeffs");
        if (!first) first = dict_find(d, "granularCoeffs");
        return err_set(e, first ? first->file : d->file, 0, "missing keyword 'model' (one of: Newtonian granular)");
    }
    if (dict_choice_or(d, "model", props_models, 0, &p->model, e)) return -1;
    const Dict *c = dict_subdict(d, coeffs[p->model], e);
    if (!c) return -1;
    if (p->model == MODEL_GRANULAR ? granular(p, c, e)
                                   : dict_check_keys(c, props_newtonian_keys, e) || positive(c, "mu", &p->mu, e) ||
                                         positive(c, "RsT", &p->RsT, e))
        return -1;
    return gravity(p, g, e);
}

int props_read(GranularProps *p, const char *case_dir, Err *e)
{
    char *pp = io_join(case_dir, "constant/granularProperties"), *gp = io_join(case_dir, "constant/g");
    Dict *d = dict_read(pp, e), *g = NULL;
    int rc = -1;
    if (d && (!(io_exists(gp) || io_exists_gz(gp)) || (g = dict_read(gp, e))))
        rc = props_parse(p, d, g, e);
    dict_free(d);
    dict_free(g);
    free(pp);
    free(gp);
    return rc;
}
