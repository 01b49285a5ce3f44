/*
** writeVTK: legacy VTK files of a case for ParaView, laid out as
** foamToVTK -legacy lays them out: see doc/tools/writeVTK.md and
** common/vtkcase.h (file names, time indices, series files).
**
** Fields are the vol fields of each time (field_read_dir), in name order;
** -fields restricts them, and a listed field whose file is not a vol field
** is an error; the fields' warnings (a boundaryField entry naming no
** patch, ...) go to stderr.  The VTK directory is touched only once the
** mesh and the time selection are known to be good.
*/
#include "args.h"
#include "case.h"
#include "err.h"
#include "field.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "vtkcase.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-ascii", NULL, "write ascii files (default: binary, big-endian)"},
    {"-pointData", NULL, "also write point data (volume-weighted average of the cells around a point)"},
    {"-noBoundary", NULL, "do not write the boundary patches"},
    {"-fields", "LIST", "only these fields, e.g. '(p U)' (default: every vol field)"},
    {"-overwrite", NULL, "remove the VTK directory first"},
    {0}};

static const ToolInfo tool = {"writeVTK", "legacy VTK files (.vtk, .vtk.series) of the mesh and vol fields",
                              opts, NULL, 1};

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc > 0) err_fatal("unexpected argument '%s'; try 'writeVTK -help'", a.argv[0]);
    args_banner(&a, &tool);
    Case cs;
    if (case_open(&cs, a.case_dir, CASE_CONTROL_FORMAT, &e)) err_die(&e);
    Mesh m;
    char *mdir = case_path(&cs, "constant/polyMesh");
    if (mesh_read(&m, mdir, &e)) err_die(&e);
    free(mdir);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    const char *fspec = args_get(&a, &tool, "-fields");
    char **want;
    int nwant = vtkcase_field_names(fspec ? fspec : "", &want);
    if (fspec && nwant == 0) err_fatal("-fields '%s' names no field", fspec);
    VtkCase v;
    if (vtkcase_open(&v, cs.dir, &m, a.time_spec, a.latest, a.nozero, &e) ||
        vtkcase_mkdir(&v, args_get(&a, &tool, "-overwrite") != NULL, &e))
        err_die(&e);
    v.opts.binary = !args_get(&a, &tool, "-ascii");
    v.opts.point_data = args_get(&a, &tool, "-pointData") != NULL;
    v.boundary = !args_get(&a, &tool, "-noBoundary");

    Buf log;
    buf_init(&log);
    int *seen = MEM_NEW(int, nwant);
    for (int s = 0; s < v.times.n; s++) {
        log_time(&a, runtime_sel_time(&v.times, s)->name);
        Field *f;
        int nf = vtkcase_read_fields(&v, s, (const char *const *)want, nwant, &f, &log, &e);
        if (nf < 0) err_die(&e);
        for (int j = 0; j < nf; j++)
            for (int k = 0; k < f[j].nwarn; k++) err_warn("%s", f[j].warn[k]);
        for (int i = 0; i < nwant; i++)
            for (int j = 0; j < nf; j++) seen[i] |= !strcmp(want[i], f[j].name);
        int rc = vtkcase_write_time(&v, s, f, nf, &log, &e);
        fwrite(log.p, 1, log.n, a.info);
        buf_clear(&log);
        if (rc) err_die(&e);
        field_free_all(f, nf);
        log_exec(&a);
    }
    for (int i = 0; i < nwant; i++)
        if (!seen[i]) err_warn("field '%s' was not found in any selected time", want[i]);
    int rc = vtkcase_write_series(&v, &log, &e);
    fwrite(log.p, 1, log.n, a.info);
    buf_clear(&log);
    if (rc) err_die(&e);
    fprintf(a.info, "\n");
    log_end(&a);

    buf_free(&log);
    free(seen);
    io_free_list(want, nwant);
    vtkcase_free(&v);
    mesh_free(&m);
    case_free(&cs);
    args_free(&a);
    return 0;
}
