/*
** state.c: the start and the write times of solveGranular (state.h).
*/
#include "state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dict.h"
#include "io.h"
#include "runtime.h"
#include "vtkcase.h"

int state_start(Case *c, Start *s, Err *e)
{
    if (case_pick_times(c, NULL, 0, 0, e) < 0) return -1;
    const TimeDir *t = runtime_sel_time(&c->times, 0);
    snprintf(s->name, sizeof s->name, "%s", t->name);
    s->value = t->value;
    s->index = 0;
    s->dt = c->control.deltaT;
    char rel[128];
    snprintf(rel, sizeof rel, "%s/uniform/time", t->name);
    char *path = case_path(c, rel);
    int rc = 0;
    if (io_exists(path)) {
        Dict *d = dict_read(path, e);
        double index = 0, dt = s->dt;
        rc = !d || dict_scalar_or(d, "value", s->value, &s->value, e) || dict_scalar_or(d, "index", 0, &index, e) ||
                     dict_scalar_or(d, "deltaT", s->dt, &dt, e)
                 ? -1
                 : 0;
        /* as OpenFOAM's Time::setControls: the saved step only when the
           step adapts; a fixed step is controlDict's, so that a restart
           can change it */
        if (c->control.adjustTimeStep) s->dt = dt;
        s->index = (long)index;
        if (!rc && !(s->dt > 0)) rc = err_set(e, path, 0, "deltaT must be positive");
        dict_free(d);
    }
    free(path);
    return rc;
}

int state_read_field(Field *f, const Mesh *m, const Case *c, const char *time, const char *name, int width,
                     Err *e)
{
    char *path = NULL;
    int rc = field_read_time(f, m, c->dir, time, name, &path, e);
    if (rc == 1) rc = err_set(e, path, 0, "cannot find the field %s of time %s", name, time);
    else if (rc == 0 && f->width != width) {
        rc = err_set(e, path, 0, "%s must be a %s", name, width == 1 ? "volScalarField" : "volVectorField");
        field_free(f);
    }
    free(path);
    return rc;
}

int state_write(const Case *c, const Mesh *m, Field *const *f, int n, double t, long index, double dt, double dt0,
                char *name, Buf *log, Err *e)
{
    runtime_time_name(&c->control, t, name);
    char *dir = case_path(c, name);
    int rc = io_mkdir_p(dir, e);
    free(dir);
    FieldWriteOpts o;
    case_field_format(c, &o);
    o.location = name;
    for (int i = 0; i < n && !rc; i++) {
        char *path = field_time_path(c->dir, name, f[i]->name);
        rc = field_write(f[i], m, path, &o, e);
        free(path);
    }
    if (!rc) rc = runtime_write_uniform_time(c->dir, name, t, index, dt, dt0, e);
    if (!rc) rc = runtime_purge(&c->control, c->dir, e);
    return rc ? -1 : state_write_vtk(c, m, name, log, e);
}

int state_write_vtk(const Case *c, const Mesh *m, const char *name, Buf *log, Err *e)
{
    return c->control.writeVTK && vtkcase_sync(c->dir, m, name, log, e) < 0 ? -1 : 0;
}
