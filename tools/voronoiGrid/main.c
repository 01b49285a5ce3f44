/*
** voronoiGrid: the boundary-conforming Voronoi grid of a block grid and
** the immersed geometry of system/geometryDict (ICCM^V, spec §2.4, thesis
** §3.2.4; common/vgrid.h).  Faces between the seed pairs placed across
** the boundary reproduce it in normal direction; no merging is needed.
** See doc/tools/voronoiGrid.md.
**
**   voronoiGrid [-case DIR] [-i DIR|-] [-o DIR|-] [-geometry FILE]
**               [-dict FILE] [-binary] [-gzip]
**
** The input block grid defaults to constant/polyMesh and is replaced
** (atomically) by the Voronoi grid, with each cell's seed in the extra
** constant/polyMesh/cellSeed and exact boundary normals in
** boundaryNormal.  Without a geometryDict the grid is the Voronoi grid of
** the block grid's cell centres.
*/
#include "args.h"
#include "dict.h"
#include "err.h"
#include "geometry.h"
#include "gridtool.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "seeds.h"
#include "vgrid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-i", "DIR", "input block grid, '-' = stream on stdin (default: constant/polyMesh)"},
    {"-o", "DIR", "output polyMesh directory, '-' = stream to stdout (default: the input directory)"},
    {"-geometry", "FILE", "geometry dictionary (default: system/geometryDict; none: no immersed boundary)"},
    {"-binary", NULL, "write binary files (default: writeFormat of system/controlDict, else ascii)"},
    {"-gzip", NULL, "gzip the files (default: writeCompression of system/controlDict, else off)"},
    {0}};

static const ArgDict dicts[] = {{"system/voronoiGridDict", seeds_keys, "  optional; every keyword has a default\n"},
                                {"system/geometryDict", geometry_keys, NULL},
                                {"system/geometryDict, each entry of surfaces", geometry_surface_keys, NULL},
                                {"system/geometryDict, each shape", geometry_shape_keys, geometry_help_note},
                                {0}};

static const ToolInfo tool = {"voronoiGrid", "boundary-conforming Voronoi grid of a block grid and a geometry", opts,
                              dicts, 0};

/* The geometry, or none (*have = 0) when the default dictionary is
   absent. */
static int read_geometry(const Args *a, const Case *c, Geometry *g, int *have, Err *e)
{
    const char *gpath = args_get(a, &tool, "-geometry");
    char *path = gpath ? mem_strdup(gpath) : case_path(c, "system/geometryDict");
    geometry_init(g);
    *have = gpath || io_exists(path) || io_exists_gz(path);
    int rc = 0;
    if (*have) {
        fprintf(a->info, "Reading geometry from %s\n", path);
        rc = geometry_read(g, c->dir, path, e);
        for (int s = 0; !rc && s < g->nsurf; s++)
            fprintf(a->info, "  surface %s (%s): flow %s\n", g->surf[s].name, g->surf[s].type,
                    g->surf[s].flow_inside ? "inside" : "outside");
        for (int l = 0; !rc && l < g->nleaves; l++)
            if (geometry_leaf_kind(g, l) == GEO_LEAF_STL)
                fprintf(stderr, "%s: warning: surface '%s' is an STL surface: its normals are the triangles', so "
                        "the seed pairs follow the facets and the grid gets spurious small faces (spec §2.4); "
                        "analytic shapes or a CAD model give exact normals\n",
                        path, geometry_leaf_patch(g, l));
    } else {
        fprintf(a->info, "No %s: the Voronoi grid of the block grid's cell centres\n", path);
    }
    free(path);
    return rc;
}

static const double PI_ = 3.14159265358979323846;
/* a surface face further than this from the exact normal (radians) is
   one of the small faces between seeds of neighbouring pairs */
#define NORMAL_TOL 0.05

static void report(FILE *f, const VGridStats *s, const Geometry *g, const Mesh *m, const Mesh *grid)
{
    const CartGrid *cg = &grid->cart;
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = cg->x[k][0];
        hi[k] = cg->x[k][cg->n[k]];
    }
    fprintf(f, "Voronoi grid\n");
    fprintf(f, "  grid spacing h:          %.6g, minimum seed spacing a: %.6g\n", s->h, s->a);
    fprintf(f, "  seeds:                   %d (%d boundary and layer seeds and %d cell centres kept, %d exterior)\n",
            s->nseeds, s->nboundary, s->ncartesian, s->nseeds - s->nboundary - s->ncartesian);
    fprintf(f, "  cells:                   %d\n", s->ncells);
    fprintf(f, "  surface faces:           %d\n", s->nsurface_faces);
    fprintf(f, "  smallest cell volume:    %.6g (bound from a: %.6g)\n", s->vol_min, s->vol_bound);
    fprintf(f, "  fluid volume:            %.15g\n", s->vol_total);
    if (g->nsurf) {
        double ex = geometry_exact_volume(g, lo, hi);
        if (isfinite(ex))
            fprintf(f, "  exact fluid volume:      %.15g (relative error %.3e)\n", ex, (s->vol_total - ex) / ex);
        else
            fprintf(f, "  exact fluid volume:      not known in closed form for this geometry\n");
        VGridNormals vn;
        vgrid_normals(m, grid->npatches, NORMAL_TOL, &vn);
        if (vn.nfaces)
            fprintf(f, "  surface faces within %g deg of the exact normal: %d of %d (%.4f%% of the area); largest "
                       "angle %.3g deg (face %d)\n",
                    NORMAL_TOL * 180 / PI_, vn.nfaces - vn.noff, vn.nfaces, 100 * (1 - vn.area_off), vn.max * 180 / PI_,
                    vn.face);
    }
    fprintf(f, "  largest angle between a face and its seed segment: %.3g deg\n",
            s->ortho_max * 180 / PI_);
    if (s->nfaces_dropped) fprintf(f, "  faces below the weld distance dropped: %d\n", s->nfaces_dropped);
    fprintf(f, "\n");
}

int main(int argc, char **argv)
{
    Args a;
    Err e;
    Case cs;
    GridTool io;
    gridtool_start(argc, argv, &tool, 1, &a, &cs, &io);
    SeedOpts so;
    seeds_opts_default(&so);
    char *opts_path = args_dict_path(&a, &cs, "system/voronoiGridDict", 1);
    if (opts_path && seeds_read_opts(opts_path, &so, &e)) err_die(&e);
    Geometry g;
    int have_geo;
    if (read_geometry(&a, &cs, &g, &have_geo, &e)) err_die(&e);
    fprintf(a.info, "Seeds: %d boundary layer(s), boundary spacing %g h, minimum spacing %g h\n", so.layers,
            so.spacing, so.min_spacing);

    Mesh grid;
    gridtool_read(&a, &io, &grid);
    int flat = mesh_empty_axis(&grid);
    if (flat >= 0 && grid.cart.n[0] > 0 && g.nsurf)
        fprintf(a.info, "2-D grid: the geometry is cut by the plane %c = %g\n\n", "xyz"[flat],
                0.5 * (grid.cart.x[flat][0] + grid.cart.x[flat][grid.cart.n[flat]]));
    if (flat >= 0 && g.nsurf) geometry_flatten(&g, flat, 0.5 * (grid.cart.x[flat][0] + grid.cart.x[flat][grid.cart.n[flat]]));

    Mesh m;
    VGridStats st;
    double t0 = args_wall(&a);
    if (vgrid_mesh(&grid, have_geo ? &g : NULL, &so, &m, &st, &e)) err_die(&e);
    double dt = args_wall(&a) - t0;
    fprintf(a.info, "Built %d Voronoi cells in %.3f s (%.3g cells/s)\n\n", st.ncells, dt, dt > 0 ? st.ncells / dt : 0.0);
    report(a.info, &st, &g, &m, &grid);
    gridtool_print_info(a.info, &m);
    gridtool_write(&a, &io, &m);

    log_exec(&a);
    log_end(&a);
    mesh_free(&m);
    mesh_free(&grid);
    geometry_free(&g);
    free(opts_path);
    gridtool_free(&io);
    case_free(&cs);
    args_free(&a);
    return 0;
}
