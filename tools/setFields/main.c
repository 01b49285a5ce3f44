/*
** setFields: sets field values in regions of the domain, from
** system/setFieldsDict in OpenFOAM's syntax.  See doc/tools/setFields.md
** and common/setfields.h (the dictionary, the blending by volume
** fraction, 2-D meshes).  Boundary conditions are written back as read;
** nothing is written unless the dictionary and every field are good.
**
** Times: the -time/-latestTime/-noZero selection, else controlDict's start
** time (case_pick_times).  The output format is the case's
** (case_field_format), as for the grid tools.  The fields' warnings (a boundaryField entry
** naming no patch, kept and written back) go to stderr.
*/
#include "args.h"
#include "case.h"
#include "err.h"
#include "field.h"
#include "geometry.h"
#include "mesh.h"
#include "runtime.h"
#include "setfields.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgDict dicts[] = {{"system/setFieldsDict", setfields_keys, setfields_help},
                                {"system/setFieldsDict, a shapeToCell region", geometry_shape_keys, NULL},
                                {0}};

static const ToolInfo tool = {"setFields", "sets field values in regions: boxes, spheres, cylinders, cones, half-spaces, any geometryDict shape",
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
    Case cs;
    if (case_open(&cs, a.case_dir, CASE_CONTROL_FORMAT, &e)) err_die(&e);

    char *dpath = args_dict_path(&a, &cs, "system/setFieldsDict", 0);
    Dict *d = dict_read(dpath, &e);
    SetFields s;
    if (!d || setfields_parse(&s, d, cs.dir, &e)) err_die(&e);
    if (s.nfields == 0) err_fatal("%s: no field values to set", dpath);

    FieldWriteOpts wo;
    case_field_format(&cs, &wo);
    int nt = case_pick_times(&cs, a.time_spec, a.latest, a.nozero, &e);
    if (nt < 0) err_die(&e);

    Mesh m;
    char *mpath = case_path(&cs, "constant/polyMesh");
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
    for (int i = 0; i < nt; i++) {
        const char *time = case_time(&cs, i);
        log_time(&a, time);
        int rc = setfields_time(&s, &m, cs.dir, time, &wo, &log, &warn, &e);
        fwrite(log.p, 1, log.n, a.info);
        buf_clear(&log);
        print_warnings(&warn);
        if (rc) err_die(&e);
    }
    buf_free(&warn);

    log_exec(&a);
    log_end(&a);
    buf_free(&log);
    mesh_free(&m);
    setfields_free(&s);
    dict_free(d);
    case_free(&cs);
    free(mpath);
    free(dpath);
    args_free(&a);
    return 0;
}
