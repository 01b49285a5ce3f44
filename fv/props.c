/*
** props.c: constant/granularProperties and constant/g (props.h).
*/
#include "props.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "field.h"
#include "io.h"

const char *const props_models[] = {"Newtonian", NULL};

const DictKey props_keys[] = {
    {"model", NULL, "the model: Newtonian (isothermal compressible Navier-Stokes, eq. 5.1)"},
    {"NewtonianCoeffs", NULL, "the Newtonian model's coefficients"},
    {NULL, NULL, NULL}};

const DictKey props_newtonian_keys[] = {
    {"mu", NULL, "dynamic viscosity [kg/(m s)] (thesis §5.1: 0.25)"},
    {"RsT", NULL, "p = RsT rho [J/kg] (thesis §5.1: 6)"},
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

int props_parse(GranularProps *p, const Dict *d, const Dict *g, Err *e)
{
    memset(p, 0, sizeof *p);
    if (dict_check_keys(d, props_keys, e)) return -1;
    if (!dict_find(d, "model")) {
        const DictEntry *first = dict_find(d, "NewtonianCoeffs");
        return err_set(e, first ? first->file : NULL, 0, "missing keyword 'model' (one of: Newtonian)");
    }
    if (dict_choice_or(d, "model", props_models, 0, &p->model, e)) return -1;
    const Dict *c = dict_subdict(d, "NewtonianCoeffs", e);
    if (!c || dict_check_keys(c, props_newtonian_keys, e) || positive(c, "mu", &p->mu, e) ||
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
