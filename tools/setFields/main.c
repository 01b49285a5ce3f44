/*
** setFields: sets field values in regions of the domain, from
** system/setFieldsDict in OpenFOAM's syntax.  See doc/tools/setFields.md
** and common/setfields.h (the dictionary, the blending by volume
** fraction, 2-D meshes).  Boundary conditions are written back as read;
** nothing is written unless the dictionary and every field are good.
**
** Times: the -time/-latestTime/-noZero selection, else controlDict's start
** time (runtime_pick_times).  The fields' warnings (a boundaryField entry
** naming no patch, kept and written back) go to stderr.
*/
#include "args.h"
#include "err.h"
#include "field.h"
#include "geometry.h"
#include "mem.h"
#include "mesh.h"
#include "runtime.h"
#include "setfields.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgDict dicts[] = {{"system/setFieldsDict", setfields_keys, setfields_help},
                                {"system/setFieldsDict, a shapeToCell region", geometry_shape_keys, NULL},
                                {0}};

static const ToolInfo tool = {"setFields", "sets field values in boxes, spheres, cylinders, cones, half-spaces",
                              NULL, dicts, 1};

/* The library's warnings, one per line, to stderr. */
static void print_warnings(Buf *warn)
{
    for (char *l = warn->p, *nl; l && *l; l = nl + 1) {
        nl = strchr(l, '\n');
        if (!nl) break;
        *nl = '\0';
        err_warn("%s", l);
    }
    buf_clear(warn);
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    args_banner(&a, &tool);

    char *dpath = a.dict ? mem_strdup(a.dict) : args_case_path(&a, "system/setFieldsDict");
    Dict *d = dict_read(dpath, &e);
    SetFields s;
    if (!d || setfields_parse(&s, d, a.case_dir, &e)) err_die(&e);
    if (s.nfields == 0) err_fatal("%s: no field values to set", dpath);

    Control ctl;
    int have_ctl = runtime_read_control_opt(&ctl, a.case_dir, &e);
    if (have_ctl < 0) err_die(&e);
    FieldWriteOpts wo = {ctl.writeBinary, ctl.writeCompression, ctl.writePrecision, NULL};
    TimeSel ts;
    if (runtime_pick_times(&ts, a.case_dir, a.time_spec, a.latest, a.nozero, have_ctl ? &ctl : NULL, &e) < 0)
        err_die(&e);

    Mesh m;
    char *mpath = args_case_path(&a, "constant/polyMesh");
    if (mesh_read(&m, mpath, &e)) err_die(&e);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    Buf log;
    buf_init(&log);
    setfields_on_mesh(&s, &m, &log);
    fwrite(log.p, 1, log.n, a.info);
    buf_clear(&log);

    Buf warn;
    buf_init(&warn);
    for (int i = 0; i < ts.n; i++) {
        const char *time = runtime_sel_time(&ts, i)->name;
        log_time(&a, time);
        int rc = setfields_time(&s, &m, a.case_dir, time, &wo, &log, &warn, &e);
        fwrite(log.p, 1, log.n, a.info);
        buf_clear(&log);
        print_warnings(&warn);
        if (rc) err_die(&e);
    }
    buf_free(&warn);

    log_exec(&a);
    log_end(&a);
    buf_free(&log);
    runtime_free_sel(&ts);
    mesh_free(&m);
    setfields_free(&s);
    dict_free(d);
    if (have_ctl) runtime_free_control(&ctl);
    free(mpath);
    free(dpath);
    args_free(&a);
    return 0;
}
