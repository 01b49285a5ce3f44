/*
** mergeCells: merges small cut cells into face neighbours (spec §2.5,
** thesis §3.3; the method is described in common/merge.h) and writes the
** merged grid with its Cartesian parents, wall normals and the map from
** the cut cells to the merged ones.  See doc/tools/mergeCells.md.
**
**   mergeCells [-case DIR] [-i DIR|-] [-o DIR|-] [-binary] [-gzip]
**
** Input and output default to constant/polyMesh of the case; "-" reads or
** writes the stream form, so "blockGrid -o - | cutCells -i - -o - |
** mergeCells -i -" works (with "-o -" the messages go to stderr).  The
** optional system/mergeCellsDict is validated completely before the grid
** is read, and the output is written atomically.
*/
#include "args.h"
#include "dict.h"
#include "err.h"
#include "gridtool.h"
#include "merge.h"
#include "mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-i", "DIR", "input cut grid, '-' = stream on stdin (default: constant/polyMesh)"},
    {"-o", "DIR", "output polyMesh directory, '-' = stream to stdout (default: constant/polyMesh)"},
    {"-binary", NULL, "write binary files (default: writeFormat of system/controlDict, else ascii)"},
    {"-gzip", NULL, "gzip the files (default: writeCompression of system/controlDict, else off)"},
    {0}};

static const ArgDict dicts[] = {{"system/mergeCellsDict", merge_keys, "  optional; every keyword has a default\n"},
                                {0}};

static const ToolInfo tool = {"mergeCells", "merges small cut cells into face neighbours", opts, dicts, 0};

static void report(FILE *f, const MergeStats *s, const Mesh *m)
{
    double rel = s->vol_before != 0 ? (s->vol_after - s->vol_before) / s->vol_before : 0;
    fprintf(f, "Merged cells\n");
    fprintf(f, "  cells in:                %d\n", s->ncells_in);
    fprintf(f, "  cells out:               %d\n", s->ncells_out);
    fprintf(f, "  slaves (V <= M_V V_cart): %d\n", s->nslaves);
    fprintf(f, "  clusters:                %d (%d round%s)\n", s->nclusters, s->niter, s->niter == 1 ? "" : "s");
    fprintf(f, "  smallest volume ratio:   before %.6g, after %.6g (cell %d)\n", s->ratio_min_before,
            s->ratio_min_after, s->ratio_min_cell);
    fprintf(f, "  max skewness:            cut grid %.10g, after the volume rounds %.10g, after %.10g (checkMesh's)\n",
            s->skew_max_cut, s->skew_max_before, s->skew_max_after);
    fprintf(f, "  quality merges:          %d (quality pass), %d clusters undone, %d merges after them\n",
            s->nskew_merged, s->nundone, s->nclean_merged);
    if (s->nforced)
        fprintf(f, "  forced merges:           %d (clusters kept or made with a face checkMesh calls skewed, so that no cell below minRatio stays alone)\n",
                s->nforced);
    fprintf(f, "  worst aspect ratio:      before %.6g, after %.6g\n", s->aspect_max_before, s->aspect_max_after);
    fprintf(f, "  total volume:            before %.15g, after %.15g (relative difference %.3e)\n", s->vol_before,
            s->vol_after, rel);
    fprintf(f, "  unresolved cells:        %d\n", s->nunresolved);
    for (int i = 0; i < s->nunresolved; i++) {
        int c = s->unresolved[i];
        double h[3];
        double ratio = mesh_cell_spacing(m, c, h) == 0 ? m->cell_vol[c] / (h[0] * h[1] * h[2]) : NAN;
        fprintf(f, "    cell %d (parent %d, volume ratio %.6g): %s\n", c, m->cell_parent[c], ratio,
                merge_reason_name(s->reason[i]));
    }
    fprintf(f, "\n");
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    Case cs;
    GridTool io;
    gridtool_start(argc, argv, &tool, 0, &a, &cs, &io);
    MergeOpts mo;
    merge_opts_default(&mo);
    char *opts_path = args_dict_path(&a, &cs, "system/mergeCellsDict", 1);
    if (opts_path && merge_read_opts(opts_path, &mo, &e)) err_die(&e);
    fprintf(a.info, "Merging cells with V <= %g V_cart (criterion %s, maxIter %d, maxSkewness %g)\n", mo.threshold,
            merge_criteria[mo.criterion], mo.max_iter, mo.max_skewness);

    Mesh grid, m;
    gridtool_read(&a, &io, &grid);
    MergeStats st;
    double t0 = args_wall(&a);
    if (merge_mesh(&grid, &mo, &m, &st, &e)) {
        Err e2;
        err_set(&e2, strcmp(io.in, "-") ? io.in : "stdin", 0, "%s", e.msg);
        err_die(&e2);
    }
    double dt = args_wall(&a) - t0;
    /* the merged grid's own geometry: an independent check of the volume
       the merge reports from its members */
    mesh_geometry(&m);
    st.vol_after = 0;
    for (int c = 0; c < m.ncells; c++) st.vol_after += m.cell_vol[c];
    fprintf(a.info, "Merged %d cells in %.3f s (%.3g cells/s)\n\n", grid.ncells, dt, dt > 0 ? grid.ncells / dt : 0.0);
    report(a.info, &st, &m);
    gridtool_print_info(a.info, &m);
    gridtool_write(&a, &io, &m);

    log_exec(&a);
    log_end(&a);
    merge_stats_free(&st);
    mesh_free(&m);
    mesh_free(&grid);
    free(opts_path);
    gridtool_free(&io);
    case_free(&cs);
    args_free(&a);
    return 0;
}
