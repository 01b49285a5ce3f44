/*
** cut_staircase.c: cutCells' method staircase (cut.h): the thesis's
** "Cartesian" grids (§5.2.1, Fig. 5.12 left, Table 5.4), which the
** cut-cell method is measured against.
**
** The rule: a Cartesian cell is kept, whole, when its centre is in the
** fluid (geometry_fluid; a centre exactly on the surface goes whichever
** way geometry_fluid says), and dropped otherwise.  Kept cells are boxes,
** so the cut-cell data contract (cartcells.h) has roles whole and
** outside only and every volume is its box's.  The boundary is the
** staircase of grid faces between a kept and a dropped cell: each goes to
** the patch of the surface nearest its centre (geometry_nearest_leaf),
** with the face's own axis-aligned normal as its boundary normal, since
** the staircase is the wall this grid has (a solver projecting a wall
** velocity on the wall's plane, rotatingWallVelocity, then projects it on
** the face's, as OpenFOAM does; doc/tools/cutCells.md).  Faces on the
** box's sides go to the grid's patches, in the grid's order, walked as
** cut_box_faces walks a whole face, so cyclic pairs stay matched when the
** geometry is periodic.
**
** Faces are added per kept cell in Cartesian order towards +x, +y, +z
** (internal, or a wall where the neighbour is dropped) and towards -x,
** -y, -z only as walls, so every internal face is added once.  The mesh is
** closed by construction: every face of a kept box is an internal face, a
** wall or a box face.  Kept cells may touch only along an edge or at a
** corner (a diagonal step in a concave staircase): they are then separate
** cells whose walls meet there, as the thesis's Cartesian solver has them.
*/
#include "cut_impl.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cartcells.h"
#include "geom.h"
#include "mem.h"
#include "meshbuild.h"

typedef struct Stair {
    const CartGrid *cg;
    const Geometry *g;
    int npatch_grid;
    int64_t sv[3], sc[3];
    unsigned char *keep; /* per Cartesian cell */
    int *cellid;         /* per Cartesian cell: new cell or -1 */
    int *vpt;            /* per grid vertex: mesh point or -1 */
    MeshBuild b;
    WallFace *wall;      /* boundary faces in order of addition */
    size_t nwall, wall_cap;
    CutStats *st;
} Stair;

static int stair_point(Stair *s, int64_t v)
{
    if (s->vpt[v] < 0) {
        int i = (int)(v % s->sv[1]), j = (int)((v / s->sv[1]) % (s->cg->n[1] + 1)), k = (int)(v / s->sv[2]);
        double x[3] = {s->cg->x[0][i], s->cg->x[1][j], s->cg->x[2][k]};
        s->vpt[v] = meshbuild_point(&s->b, x);
    }
    return s->vpt[v];
}

static void stair_push_wall(Stair *s, int patch, int a, int hi)
{
    mem_grow((void **)&s->wall, &s->wall_cap, s->nwall + 1, sizeof *s->wall);
    WallFace *w = &s->wall[s->nwall++];
    w->patch = patch;
    memset(w->n, 0, sizeof w->n);
    w->n[a] = hi ? 1 : -1;
}

/* The grid face normal to a at base vertex v0, walked base, +u, +u+w, +w
   (normal +a), or reversed keeping the first point (normal -a). */
static void stair_face(Stair *s, int a, int64_t v0, int hi, int pt[4])
{
    int u = (a + 1) % 3, w = (a + 2) % 3;
    int64_t cv[4] = {v0, v0 + s->sv[u], v0 + s->sv[u] + s->sv[w], v0 + s->sv[w]};
    for (int q = 0; q < 4; q++) pt[q] = stair_point(s, cv[hi || q == 0 ? q : 4 - q]);
}

/* A staircase wall: the face of cell `cell` normal to a on its side hi,
   on the patch of the surface nearest the face's centre. */
static void stair_wall(Stair *s, int a, int64_t v0, int hi, int cell)
{
    int pt[4];
    stair_face(s, a, v0, hi, pt);
    double S[3], C[3];
    geom_face(s->b.points, pt, 4, S, C);
    int lf = geometry_nearest_leaf(s->g, C);
    int patch = s->npatch_grid + (lf >= 0 ? s->g->leaves[lf].surface : 0);
    meshbuild_face(&s->b, pt, 4, cell, -1, patch);
    stair_push_wall(s, patch, a, hi);
    s->st->area_boundary += geom_norm(S);
    s->st->nboundary++;
}

static void stair_cell_faces(Stair *s, const int ijk[3])
{
    const int *n = s->cg->n;
    int64_t ci = ijk[0] + s->sc[1] * ijk[1] + s->sc[2] * ijk[2];
    int64_t v0 = ijk[0] + s->sv[1] * ijk[1] + s->sv[2] * ijk[2];
    int cell = s->cellid[ci];
    for (int a = 0; a < 3; a++) {
        if (ijk[a] + 1 < n[a]) {
            int other = s->cellid[ci + s->sc[a]];
            if (other >= 0) {
                int pt[4];
                stair_face(s, a, v0 + s->sv[a], 1, pt);
                meshbuild_face(&s->b, pt, 4, cell, other, -1);
            } else {
                stair_wall(s, a, v0 + s->sv[a], 1, cell);
            }
        }
        if (ijk[a] > 0 && s->cellid[ci - s->sc[a]] < 0) stair_wall(s, a, v0, 0, cell);
    }
}

/* The kept cells' faces on the box's sides, in the grid's order. */
static int stair_box_faces(Stair *s, const Mesh *grid, Err *e)
{
    const int *n = s->cg->n;
    for (int p = 0; p < grid->npatches; p++) {
        const Patch *P = &grid->patches[p];
        for (int f = P->start; f < P->start + P->size; f++) {
            int side = cut_box_side(s->cg, grid, f), oc = grid->owner[f];
            if (side < 0)
                return err_set(e, NULL, 0, "grid boundary face %d (patch %s) is not on a side of the box", f,
                               P->name);
            if (s->cellid[oc] < 0) continue;
            int a = side / 2, hi = side & 1, ijk[3] = {oc % n[0], (oc / n[0]) % n[1], oc / (n[0] * n[1])};
            ijk[a] = hi ? n[a] : 0;
            int pt[4];
            stair_face(s, a, ijk[0] + s->sv[1] * ijk[1] + s->sv[2] * ijk[2], hi, pt);
            meshbuild_face(&s->b, pt, 4, s->cellid[oc], -1, p);
            stair_push_wall(s, p, a, hi);
        }
    }
    return 0;
}

/* Which cells are kept (their centres in the fluid), numbered in
   Cartesian order; returns how many. */
static int stair_classify(Stair *s)
{
    const int *n = s->cg->n;
    int nc = 0;
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++) {
                int64_t ci = i + s->sc[1] * j + s->sc[2] * k;
                double x[3] = {(s->cg->x[0][i] + s->cg->x[0][i + 1]) / 2, (s->cg->x[1][j] + s->cg->x[1][j + 1]) / 2,
                               (s->cg->x[2][k] + s->cg->x[2][k + 1]) / 2};
                s->keep[ci] = geometry_fluid(s->g, x) != 0;
                s->cellid[ci] = s->keep[ci] ? nc++ : -1;
            }
    return nc;
}

static double box_vol(const CartGrid *cg, int64_t ci)
{
    int i = (int)(ci % cg->n[0]), j = (int)((ci / cg->n[0]) % cg->n[1]), k = (int)(ci / ((int64_t)cg->n[0] * cg->n[1]));
    return (cg->x[0][i + 1] - cg->x[0][i]) * (cg->x[1][j + 1] - cg->x[1][j]) * (cg->x[2][k + 1] - cg->x[2][k]);
}

/* The extras of the result: Cartesian parents, boundary normals in
   final face order (meshbuild keeps the order of addition within a
   patch), the contract with every cell whole, the statistics. */
static void stair_extras(Stair *s, int nc, Mesh *m)
{
    const CartGrid *cg = s->cg;
    m->cell_parent = mem_alloc(sizeof(int) * (size_t)nc);
    int64_t ncart = s->sc[2] * cg->n[2];
    for (int64_t ci = 0; ci < ncart; ci++)
        if (s->cellid[ci] >= 0) m->cell_parent[s->cellid[ci]] = (int)ci;
    mesh_copy_cart(cg, &m->cart);
    int nb = m->nfaces - m->ninternal;
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)(nb ? nb : 1));
    int *next = mem_alloc(sizeof(int) * (size_t)m->npatches);
    for (int p = 0; p < m->npatches; p++) next[p] = m->patches[p].start;
    for (size_t w = 0; w < s->nwall; w++) {
        int f = next[s->wall[w].patch]++;
        memcpy(m->boundary_normal + 3 * (size_t)(f - m->ninternal), s->wall[w].n, 3 * sizeof(double));
    }
    free(next);
    double *vol = mem_alloc(sizeof(double) * (size_t)nc);
    unsigned char *whole = mem_alloc((size_t)nc);
    CutStats *st = s->st;
    st->ncells = nc;
    st->nsolid = st->ncart - nc;
    st->frac_min = 1;
    st->frac_min_cell = 0;
    for (int c = 0; c < nc; c++) {
        vol[c] = box_vol(cg, m->cell_parent[c]);
        whole[c] = 1;
        st->vol_fluid += vol[c];
    }
    st->vol_box = 1;
    for (int k = 0; k < 3; k++) st->vol_box *= cg->x[k][cg->n[k]] - cg->x[k][0];
    cartcells_build(m, vol, whole, &m->cartcells);
    free(vol);
    free(whole);
}

static void stair_free(Stair *s)
{
    free(s->keep);
    free(s->cellid);
    free(s->vpt);
    free(s->wall);
    meshbuild_free(&s->b);
}

int cut_staircase(const Mesh *grid, const Geometry *g, Mesh *out, CutStats *st, Err *e)
{
    if (cut_check_grid(grid, g, e)) return -1;
    Stair s;
    memset(&s, 0, sizeof s);
    s.cg = &grid->cart;
    s.g = g;
    s.st = st;
    const int *n = s.cg->n;
    s.sv[0] = s.sc[0] = 1;
    s.sv[1] = n[0] + 1;
    s.sv[2] = s.sv[1] * (n[1] + 1);
    s.sc[1] = n[0];
    s.sc[2] = (int64_t)n[0] * n[1];
    int64_t nv = s.sv[2] * (n[2] + 1);
    s.keep = mem_alloc((size_t)grid->ncells);
    s.cellid = mem_alloc(sizeof(int) * (size_t)grid->ncells);
    s.vpt = mem_alloc(sizeof(int) * (size_t)nv);
    memset(s.vpt, 0xff, sizeof(int) * (size_t)nv);
    st->ncart = grid->ncells;
    int nc = stair_classify(&s);
    if (nc == 0) {
        stair_free(&s);
        return err_set(e, g->file, 0, "no cell is left: no Cartesian cell's centre is in the fluid");
    }
    meshbuild_init(&s.b);
    meshbuild_reserve(&s.b, (size_t)grid->npoints, (size_t)grid->nfaces, 4 * (size_t)grid->nfaces);
    for (int p = 0; p < grid->npatches; p++) {
        const Patch *P = &grid->patches[p];
        meshbuild_patch(&s.b, P->name, P->type, P->neighbour, P->groups);
    }
    s.npatch_grid = grid->npatches;
    for (int k = 0; k < g->nsurf; k++) meshbuild_patch(&s.b, g->surf[k].name, g->surf[k].type, NULL, NULL);
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++)
                if (s.keep[i + s.sc[1] * j + s.sc[2] * k]) stair_cell_faces(&s, (const int[3]){i, j, k});
    if (stair_box_faces(&s, grid, e) || meshbuild_finish(&s.b, out, NULL, NULL, e)) {
        stair_free(&s);
        mesh_free(out);
        mesh_init(out);
        return -1;
    }
    stair_extras(&s, nc, out);
    stair_free(&s);
    return 0;
}
