/*
** case.c: the case directory, its controlDict and selected times.  See
** case.h.
**
** The output format is decided here and only here: writeFormat binary
** makes grids and fields binary, writeCompression gzips both, and
** runtime.c has already switched compression off for binary files as
** OpenFOAM v1912 does.  Without a controlDict fields keep the shortest
** exact ascii numbers (precision 0), as they did before the Case.
*/
#include "case.h"

#include <stdlib.h>
#include <string.h>

#include "io.h"
#include "mem.h"

static int read_control(Case *c, int need, Err *e)
{
    if (need == CASE_NO_CONTROL) return 0;
    char *path = case_path(c, "system/controlDict");
    int rc = 0;
    if (need == CASE_CONTROL_TIME || io_exists(path)) {
        rc = runtime_load_control(&c->control, path, need == CASE_CONTROL_TIME, e);
        c->has_control = rc == 0;
    }
    free(path);
    return rc;
}

int case_open(Case *c, const char *dir, int need, Err *e)
{
    memset(c, 0, sizeof *c);
    if (!dir) dir = ".";
    if (!io_is_dir(dir)) return err_set(e, NULL, 0, "case directory '%s' does not exist", dir);
    c->dir = mem_strdup(dir);
    if (read_control(c, need, e)) {
        case_free(c);
        return -1;
    }
    return 0;
}

void case_free(Case *c)
{
    if (c->has_control) runtime_free_control(&c->control);
    runtime_free_sel(&c->times);
    free(c->dir);
    memset(c, 0, sizeof *c);
}

char *case_path(const Case *c, const char *rel) { return io_join(c->dir, rel); }

void case_mesh_format(const Case *c, MeshWriteOpts *w)
{
    w->binary = c->control.writeBinary;
    w->gzip = c->control.writeCompression;
}

void case_field_format(const Case *c, FieldWriteOpts *o)
{
    o->binary = c->control.writeBinary;
    o->gzip = c->control.writeCompression;
    o->precision = c->control.writePrecision;
    o->location = NULL;
}

int case_select_times(Case *c, const char *spec, int latest, int nozero, Err *e)
{
    runtime_free_sel(&c->times);
    return runtime_select_case(&c->times, c->dir, spec, latest, nozero, e);
}

int case_pick_times(Case *c, const char *spec, int latest, int nozero, Err *e)
{
    runtime_free_sel(&c->times);
    return runtime_pick_times(&c->times, c->dir, spec, latest, nozero, c->has_control ? &c->control : NULL, e);
}

const char *case_time(const Case *c, int i) { return runtime_sel_time(&c->times, i)->name; }
