/*
** vgrid.c: the boundary-conforming Voronoi grid (vgrid.h): seeds, cells,
** patches, cell seeds, boundary normals and the cut-cell data contract
** (cartcells.h: each cell's parent is the Cartesian cell holding its seed).
*/
#include "vgrid.h"
#include "cartcells.h"
#include "geom.h"
#include "mem.h"
#include "voronoi.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI_ = 3.14159265358979323846;

/* The box side (0..5: xMin, xMax, yMin, ...) a boundary face lies on, or
   -1: the mean of its points within tol of the side's plane. */
static int face_side(const Mesh *m, int f, const double lo[3], const double hi[3], double tol)
{
    double c[3] = {0, 0, 0};
    int n = m->face_off[f + 1] - m->face_off[f];
    for (int q = m->face_off[f]; q < m->face_off[f + 1]; q++)
        for (int a = 0; a < 3; a++) c[a] += m->points[3 * (size_t)m->face_idx[q] + a];
    for (int a = 0; a < 3; a++) c[a] /= n;
    for (int a = 0; a < 3; a++) {
        if (fabs(c[a] - lo[a]) <= tol) return 2 * a;
        if (fabs(c[a] - hi[a]) <= tol) return 2 * a + 1;
    }
    return -1;
}

/* Distance within which a point is on a box side. */
static double side_tol(const double lo[3], const double hi[3])
{
    double tol = 0;
    for (int a = 0; a < 3; a++) tol = fmax(tol, 1e-9 * (hi[a] - lo[a]));
    return tol;
}

/* side_patch[s]: the grid's patch holding box side s; every boundary
   face of the block grid must be on a side, one patch per side. */
static int side_patches(const Mesh *grid, const double lo[3], const double hi[3], int side_patch[6], Err *e)
{
    double tol = side_tol(lo, hi);
    for (int s = 0; s < 6; s++) side_patch[s] = -1;
    for (int p = 0; p < grid->npatches; p++)
        for (int f = grid->patches[p].start; f < grid->patches[p].start + grid->patches[p].size; f++) {
            int s = face_side(grid, f, lo, hi, tol);
            if (s < 0)
                return err_set(e, NULL, 0, "grid boundary face %d (patch %s) is not on a side of the box", f,
                               grid->patches[p].name);
            if (side_patch[s] >= 0 && side_patch[s] != p)
                return err_set(e, NULL, 0,
                               "box side %s lies in two patches, %s and %s: voronoiGrid needs one patch per side",
                               "xMin\0xMax\0yMin\0yMax\0zMin\0zMax" + 5 * s, grid->patches[side_patch[s]].name,
                               grid->patches[p].name);
            side_patch[s] = p;
        }
    for (int s = 0; s < 6; s++)
        if (side_patch[s] < 0)
            return err_set(e, NULL, 0, "box side %s has no boundary face", "xMin\0xMax\0yMin\0yMax\0zMin\0zMax" + 5 * s);
    return 0;
}

static int check_names(const Mesh *grid, const Geometry *g, Err *e)
{
    for (int p = 0; p < grid->npatches; p++)
        for (int s = 0; s < g->nsurf; s++)
            if (!strcmp(grid->patches[p].name, g->surf[s].name))
                return err_set(e, g->file, g->surf[s].line, "surface '%s' has the name of the grid's patch %d",
                               g->surf[s].name, p);
    return 0;
}

/* Angle cosine between area vector S and unit normal n. */
static double cos_to(const double S[3], const double n[3])
{
    double s = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
    return s > 0 ? (S[0] * n[0] + S[1] * n[1] + S[2] * n[2]) / s : 1;
}

/* Area vector and centre of face f: only the boundary faces' are needed
   here, so the full mesh_geometry (its arrays are the largest part of a
   2-D grid's memory) is left to the caller. */
static void face_geom(const Mesh *m, int f, double S[3], double c[3])
{
    geom_face(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], S, c);
}

/* The exact normal of surface `surf` for face f: at the face centre,
   unless that is far (over 30 deg) from the face's own normal.  That
   happens next to an edge or corner, where the centre of a face on one
   wall can be nearer to the other wall; the normals at the face's
   points are then candidates too, and the one closest to the face's
   own normal wins (the wall the face lies on). */
static void surface_normal(const Mesh *m, const Geometry *g, int surf, int f, double n[3])
{
    double S[3], c[3];
    face_geom(m, f, S, c);
    geometry_normal(g, geometry_nearest_leaf_of(g, surf, c), c, n);
    double best = cos_to(S, n);
    if (best > cos(PI_ / 6)) return;
    for (int q = m->face_off[f]; q < m->face_off[f + 1]; q++) {
        const double *x = m->points + 3 * (size_t)m->face_idx[q];
        double v[3];
        geometry_normal(g, geometry_nearest_leaf_of(g, surf, x), x, v);
        double cv = cos_to(S, v);
        if (cv > best) {
            best = cv;
            memcpy(n, v, sizeof v);
        }
    }
}

/* Exact normals: surface faces from the geometry at their centres, box
   sides their axis.  Patch p >= nbox is surface p - nbox. */
/* The side of box face f of patch p: the patch's only side, or, for a
   patch on the two sides of one axis (frontAndBack), the one its first
   point is on; face_side otherwise (a point can lie on two sides). */
static int box_face_side(const Mesh *m, int f, int p, const int side_patch[6], const double lo[3],
                         const double hi[3], double tol)
{
    int cand[6], nc = 0;
    for (int s = 0; s < 6; s++)
        if (side_patch[s] == p) cand[nc++] = s;
    if (nc == 1) return cand[0];
    if (nc == 2 && cand[0] / 2 == cand[1] / 2) {
        int a = cand[0] / 2;
        double x = m->points[3 * (size_t)m->face_idx[m->face_off[f]] + a];
        return fabs(x - lo[a]) <= fabs(x - hi[a]) ? 2 * a : 2 * a + 1;
    }
    return face_side(m, f, lo, hi, tol);
}

static void boundary_normals(Mesh *m, const Geometry *g, int nbox, const int side_patch[6], const double lo[3],
                             const double hi[3])
{
    double tol = side_tol(lo, hi);
    int nb = m->nfaces - m->ninternal;
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)(nb > 0 ? nb : 1));
    for (int p = 0; p < m->npatches; p++) {
        const Patch *P = &m->patches[p];
        for (int f = P->start; f < P->start + P->size; f++) {
            double *n = m->boundary_normal + 3 * (size_t)(f - m->ninternal);
            if (p >= nbox) {
                surface_normal(m, g, p - nbox, f, n);
                continue;
            }
            /* a box side (checked by side_patches): its outward axis */
            int side = box_face_side(m, f, p, side_patch, lo, hi, tol);
            n[0] = n[1] = n[2] = 0;
            n[side / 2] = side & 1 ? 1 : -1;
        }
    }
}

void vgrid_normals(const Mesh *m, int first_surface_patch, double tol, VGridNormals *r)
{
    memset(r, 0, sizeof *r);
    r->max = -1;
    r->face = -1;
    if (!m->boundary_normal) return;
    double total = 0;
    for (int p = first_surface_patch; p < m->npatches; p++)
        for (int f = m->patches[p].start; f < m->patches[p].start + m->patches[p].size; f++) {
            const double *n = m->boundary_normal + 3 * (size_t)(f - m->ninternal);
            double S[3], c[3];
            face_geom(m, f, S, c);
            double area = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
            /* atan2 of |S x n| and S.n: acos loses half the digits near 0 */
            double x[3] = {S[1] * n[2] - S[2] * n[1], S[2] * n[0] - S[0] * n[2], S[0] * n[1] - S[1] * n[0]};
            double ang = atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), S[0] * n[0] + S[1] * n[1] + S[2] * n[2]);
            r->nfaces++;
            total += area;
            if (ang > tol) {
                r->noff++;
                r->area_off += area;
            }
            if (ang > r->max) {
                r->max = ang;
                r->face = f;
            }
        }
    if (total > 0) r->area_off /= total;
}

/* The parent grid and the cut-cell data contract of a Voronoi grid
   (cartcells.h: each cell's parent holds its seed); needs the volumes,
   so the geometry is filled here. */
static void voronoi_cart_cells(Mesh *out, const CartGrid *cg, const Seeds *s, const int *seed_of)
{
    mesh_copy_cart(cg, &out->cart);
    mesh_cell_faces(out);
    mesh_geometry(out);
    unsigned char *centre = mem_alloc((size_t)out->ncells + 1);
    for (int c = 0; c < out->ncells; c++) centre[c] = s->kind[seed_of[c]] == SEED_CARTESIAN;
    cartcells_voronoi(out, centre, &out->cartcells);
    free(centre);
}

static void count_seeds(const Seeds *s, VGridStats *st)
{
    st->nseeds = s->n;
    for (int i = 0; i < s->n; i++) {
        if (!s->interior[i]) continue;
        if (s->kind[i] == SEED_BOUNDARY) st->nboundary++;
        else st->ncartesian++;
    }
}

static void fill_stats(VGridStats *st, const VoronoiStats *vs, const Mesh *out, const Geometry *g,
                       const SeedOpts *o, const CartGrid *cg, int flat, int nbox)
{
    double h = INFINITY;
    for (int a = 0; a < 3; a++)
        if (a != flat) h = fmin(h, (cg->x[a][cg->n[a]] - cg->x[a][0]) / cg->n[a]);
    st->h = h;
    st->a = o->min_spacing * h;
    st->vol_bound = flat >= 0 ? PI_ * st->a * st->a / 4 * (cg->x[flat][cg->n[flat]] - cg->x[flat][0])
                              : PI_ * pow(st->a, 3) / 6;
    st->ncells = out->ncells;
    st->vol_min = vs->vol_min;
    st->vol_total = vs->vol_total;
    for (int p = nbox; p < out->npatches; p++) st->nsurface_faces += out->patches[p].size;
    st->ortho_max = vs->ortho_max;
    st->nfaces_dropped = vs->nfaces_dropped;
    for (int l = 0; l < g->nleaves; l++) st->nstl += geometry_leaf_kind(g, l) == GEO_LEAF_STL;
}

int vgrid_mesh(const Mesh *grid0, const Geometry *g0, const SeedOpts *o, Mesh *out, VGridStats *st, Err *e)
{
    mesh_init(out);
    memset(st, 0, sizeof *st);
    const CartGrid *cg = &grid0->cart;
    if (grid0->cell_seed)
        return err_set(e, NULL, 0, "the grid is already a Voronoi grid (it has cellSeed): run blockGrid first");
    if (cg->n[0] <= 0 || cg->n[1] <= 0 || cg->n[2] <= 0)
        return err_set(e, NULL, 0, "the grid has no Cartesian extras (cartesianGrid): start from a blockGrid grid");
    if ((long)cg->n[0] * cg->n[1] * cg->n[2] != grid0->ncells)
        return err_set(e, NULL, 0, "the grid has %d cells but its cartesianGrid %d x %d x %d: start from a "
                       "blockGrid grid", grid0->ncells, cg->n[0], cg->n[1], cg->n[2]);
    Geometry none;
    geometry_init(&none);
    Geometry g = g0 ? *g0 : none;
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = cg->x[a][0];
        hi[a] = cg->x[a][cg->n[a]];
    }
    int flat = mesh_empty_axis(grid0);
    if (flat >= 0) {
        g.flat_axis = flat;
        g.flat_coord = 0.5 * (lo[flat] + hi[flat]);
    }
    int side_patch[6];
    if (check_names(grid0, &g, e) || side_patches(grid0, lo, hi, side_patch, e)) return -1;

    Seeds s;
    if (seeds_make(grid0, &g, o, &s, e)) return -1;
    count_seeds(&s, st);
    int nbox = grid0->npatches, np = nbox + g.nsurf;
    Patch *pat = mem_calloc((size_t)np, sizeof(Patch));
    for (int p = 0; p < nbox; p++) pat[p] = grid0->patches[p];
    for (int k = 0; k < g.nsurf; k++) {
        pat[nbox + k].name = g.surf[k].name;
        pat[nbox + k].type = g.surf[k].type;
    }
    int *patch = mem_alloc(sizeof(int) * (size_t)(s.n > 0 ? s.n : 1));
    for (int i = 0; i < s.n; i++) patch[i] = s.interior[i] ? 0 : nbox + (s.surface[i] >= 0 ? s.surface[i] : 0);
    VoronoiInput in = {s.n, s.x, s.interior, patch, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, flat, np, pat,
                       {0}};
    memcpy(in.side_patch, side_patch, sizeof side_patch);
    int *seed_of = mem_alloc(sizeof(int) * (size_t)(s.n > 0 ? s.n : 1));
    VoronoiStats vs;
    int rc = voronoi_mesh(&in, out, seed_of, &vs, e);
    if (!rc) {
        out->cell_seed = mem_alloc(sizeof(double) * 3 * (size_t)out->ncells);
        for (int c = 0; c < out->ncells; c++) memcpy(out->cell_seed + 3 * c, s.x + 3 * seed_of[c], 3 * sizeof(double));
        boundary_normals(out, &g, nbox, side_patch, lo, hi);
        voronoi_cart_cells(out, cg, &s, seed_of);
        fill_stats(st, &vs, out, &g, o, cg, flat, nbox);
    }
    free(seed_of);
    free(patch);
    free(pat);
    seeds_free(&s);
    return rc;
}
