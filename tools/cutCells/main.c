/*
** cutCells: cuts the block grid with the immersed geometry of
** system/geometryDict into exact cut cells (ICCM^MC, spec §2.2; the method
** is described in common/cut.h) and writes the cut grid with its
** Cartesian parents and the exact wall normals.  See doc/tools/cutCells.md.
**
**   cutCells [-case DIR] [-i DIR|-] [-o DIR|-] [-binary] [-gzip]
**
** The input defaults to constant/polyMesh and is replaced (atomically) by
** the cut grid; "-" reads or writes the stream form, so
** "blockGrid -o - | cutCells -i - -o - | mergeCells -i -" works.
*/
#include "args.h"
#include "cut.h"
#include "dict.h"
#include "err.h"
#include "geometry.h"
#include "gridtool.h"
#include "mem.h"
#include "mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-i", "DIR", "input block grid, '-' = stream on stdin (default: constant/polyMesh)"},
    {"-o", "DIR", "output polyMesh directory, '-' = stream to stdout (default: the input directory)"},
    {"-geometry", "FILE", "geometry dictionary (default: system/geometryDict)"},
    {"-binary", NULL, "write binary files (default: writeFormat of system/controlDict, else ascii)"},
    {"-gzip", NULL, "gzip the files (default: writeCompression of system/controlDict, else off)"},
    {0}};

static const ArgDict dicts[] = {{"system/geometryDict", geometry_keys, NULL},
                                {"system/geometryDict, each entry of surfaces", geometry_surface_keys, NULL},
                                {"system/geometryDict, each shape", geometry_shape_keys, geometry_help_note},
                                {"system/cutCellsDict", cut_keys, "  optional; every keyword has a default\n"},
                                {0}};

static const ToolInfo tool = {"cutCells", "cuts a block grid with an immersed geometry into exact cut cells",
                              opts, dicts, 0};

static void report(FILE *f, const CutStats *s, const Geometry *g, const Mesh *m, int method)
{
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = m->cart.x[k][0];
        hi[k] = m->cart.x[k][m->cart.n[k]];
    }
    fprintf(f, method == CUT_METHOD_STAIRCASE
                   ? "Staircase cells (method staircase: every cell whose centre is in the fluid kept whole)\n"
                   : "Cut cells\n");
    fprintf(f, "  Cartesian cells:         %d\n", s->ncart);
    fprintf(f, "  cells kept:              %d (%d cut, %d solid cells dropped)\n", s->ncells, s->ncut, s->nsolid);
    fprintf(f, "  immersed boundary faces: %d, area %.12g\n", s->nboundary, s->area_boundary);
    fprintf(f, "  smallest volume fraction: %.6g (cell %d)\n", s->frac_min, s->frac_min_cell);
    fprintf(f, "  fluid volume:            %.15g of box %.15g\n", s->vol_fluid, s->vol_box);
    double ex = geometry_exact_volume(g, lo, hi);
    if (isfinite(ex))
        fprintf(f, "  exact fluid volume:      %.15g (relative error %.3e)\n", ex, (s->vol_fluid - ex) / ex);
    else
        fprintf(f, "  exact fluid volume:      not known in closed form for this geometry\n");
    fprintf(f, "  vertices snapped onto the surface: %d\n", s->nsnap);
    if (s->nthin) fprintf(f, "  edges crossed twice (feature thinner than the grid, dropped): %d\n", s->nthin);
    if (s->nodd) fprintf(f, "  edges crossed 3+ times (nearest crossing to the fluid kept): %d\n", s->nodd);
    if (s->ninconsistent) fprintf(f, "  edges with no crossing between differing vertices: %d\n", s->ninconsistent);
    if (s->ntunnel) fprintf(f, "  cells joined through a body diagonal (tunnel): %d\n", s->ntunnel);
    if (s->ndegenerate) fprintf(f, "  cells with fluid corners but no volume (dropped): %d\n", s->ndegenerate);
    fprintf(f, "\n");
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    Case cs;
    GridTool io;
    gridtool_start(argc, argv, &tool, 1, &a, &cs, &io);
    CutOpts co;
    cut_opts_default(&co);
    char *opts_path = args_dict_path(&a, &cs, "system/cutCellsDict", 1);
    if (opts_path && cut_read_opts(opts_path, &co, &e)) err_die(&e);

    const char *gpath = args_get(&a, &tool, "-geometry");
    char *geo_path = gpath ? mem_strdup(gpath) : case_path(&cs, "system/geometryDict");
    fprintf(a.info, "Reading geometry from %s\n", geo_path);
    Geometry g;
    if (geometry_read(&g, cs.dir, geo_path, &e)) err_die(&e);
    for (int s = 0; s < g.nsurf; s++)
        fprintf(a.info, "  surface %s (%s): flow %s\n", g.surf[s].name, g.surf[s].type,
                g.surf[s].flow_inside ? "inside" : "outside");

    Mesh grid;
    gridtool_read(&a, &io, &grid);
    int flat = mesh_empty_axis(&grid);
    if (flat >= 0 && grid.cart.n[0] > 0) {
        double mid = 0.5 * (grid.cart.x[flat][0] + grid.cart.x[flat][grid.cart.n[flat]]);
        geometry_flatten(&g, flat, mid);
        fprintf(a.info, "2-D grid: the geometry is cut by the plane %c = %g\n\n", "xyz"[flat], mid);
    }

    Mesh m;
    CutStats st;
    double t0 = args_wall(&a);
    if (cut_mesh(&grid, &g, &co, &m, &st, &e)) err_die(&e);
    double dt = args_wall(&a) - t0;
    fprintf(a.info, "Cut %d Cartesian cells in %.3f s (%.3g cells/s)\n\n", st.ncart, dt, dt > 0 ? st.ncart / dt : 0.0);
    report(a.info, &st, &g, &m, co.method);
    gridtool_print_info(a.info, &m);
    gridtool_write(&a, &io, &m);

    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    mesh_free(&grid);
    geometry_free(&g);
    free(geo_path);
    free(opts_path);
    gridtool_free(&io);
    case_free(&cs);
    args_free(&a);
    return 0;
}
