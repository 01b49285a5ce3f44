/*
** checkGrid: checkMesh's job for Kiesel's grids.  Reads constant/polyMesh
** (or "-i DIR", "-i -" for the stream on stdin), prints counts, bounding
** box, volumes against the Cartesian parents, closedness, orientation,
** non-orthogonality, skewness and aspect ratio (common/quality.c), and
** ends with "Grid OK." or, when the grid is broken, names the first bad
** cell on stderr and exits 1.  With -writeSets it also writes the
** faces above checkMesh's skewness and non-orthogonality limits as
** faceSets (constant/polyMesh/sets/skewFaces, nonOrthoFaces), the sets
** checkMesh writes, so the two can be compared face for face.  See
** doc/tools/checkGrid.md.
*/
#include "args.h"
#include "case.h"
#include "buf.h"
#include "err.h"
#include "foam.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "quality.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-i", "DIR", "polyMesh directory to check, '-' = stream on stdin (default: constant/polyMesh)"},
    {"-writeSets", NULL, "write faceSets skewFaces (skewness > 4) and nonOrthoFaces (> 70 degrees) to constant/polyMesh/sets"},
    {0}};

static const ArgDict dicts[] = {{0}};

/* Writes the faces of m whose value v[f] is above lim (NAN: not
   measured) as faceSet `name` in dir, atomically; returns their number,
   or -1. */
static int write_set(const char *dir, const char *name, const Mesh *m, const double *v, double lim, Err *e)
{
    int *faces = MEM_NEW(int, (size_t)m->nfaces), n = 0;
    for (int f = 0; f < m->nfaces; f++)
        if (v[f] > lim) faces[n++] = f;
    Buf b;
    buf_init(&b);
    foam_header(&b, "faceSet", "constant/polyMesh/sets", name, 0, NULL);
    foam_put_labels(&b, faces, (size_t)n, 0);
    foam_footer(&b);
    char *path = io_join(dir, name);
    int rc = io_write_atomic(path, b.p, b.n, 0, e);
    free(path);
    buf_free(&b);
    free(faces);
    return rc ? -1 : n;
}

/* The -writeSets sets, in <case>/constant/polyMesh/sets. */
static void write_sets(const Args *a, const Case *c, const Mesh *m)
{
    Err e;
    double *skew = mem_alloc(sizeof(double) * ((size_t)m->nfaces + 1));
    double *cosn = mem_alloc(sizeof(double) * ((size_t)m->nfaces + 1));
    quality_face_measures(m, skew, cosn);
    /* non-orthogonality above the limit is cos below cos(limit) */
    double lim = -cos(QUALITY_NONORTH_SEVERE * 3.14159265358979323846 / 180);
    for (int f = 0; f < m->nfaces; f++) cosn[f] = -cosn[f];
    char *dir = case_path(c, "constant/polyMesh/sets");
    int ns, no;
    if (io_mkdir_p(dir, &e) || (ns = write_set(dir, "skewFaces", m, skew, QUALITY_SKEW_HIGH, &e)) < 0 ||
        (no = write_set(dir, "nonOrthoFaces", m, cosn, lim, &e)) < 0)
        err_die(&e);
    fprintf(a->info, "    Wrote %d faces to set skewFaces, %d to set nonOrthoFaces (%s)\n", ns, no, dir);
    free(dir);
    free(skew);
    free(cosn);
}

static const ToolInfo tool = {"checkGrid", "checks a grid's topology and geometry, reports its quality",
                              opts, dicts, 0};

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    args_banner(&a, &tool);
    Case cs;
    if (case_open(&cs, a.case_dir, CASE_CONTROL_FORMAT, &e)) err_die(&e);
    const char *in = args_get(&a, &tool, "-i");
    char *dir = in ? mem_strdup(in) : case_path(&cs, "constant/polyMesh");
    fprintf(a.info, "Reading grid from %s\n\n", strcmp(dir, "-") ? dir : "stdin");

    Mesh m;
    mesh_init(&m);
    if (mesh_read(&m, dir, &e)) err_die(&e);
    Quality q;
    quality_measure(&m, &q);
    Buf b;
    buf_init(&b);
    quality_report(&m, &q, &b);
    fwrite(b.p, 1, b.n, a.info);
    buf_free(&b);
    if (args_get(&a, &tool, "-writeSets")) write_sets(&a, &cs, &m);

    int nfailed;
    int rc = quality_check(&m, &q, &nfailed, &e);
    if (rc) {
        fprintf(a.info, "\nFailed %d grid checks.\n\n", nfailed);
        err_die(&e);
    }
    fprintf(a.info, "\nGrid OK.\n\n");
    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    case_free(&cs);
    free(dir);
    args_free(&a);
    return 0;
}
