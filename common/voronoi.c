/*
** voronoi.c: bounded Voronoi grids (voronoi.h).
**
** Design, in two passes.
**
** Pass 1, one kept seed at a time: the cell starts as the box (3-D: a
** convex polyhedron held as a vertex array and polygons of vertex indices,
** each polygon labelled with the seed across it, or -1 - side for a box
** side; 2-D: a convex polygon in the plane normal to flat_axis whose edges
** carry those labels) and is clipped by the bisector half-space of each
** seed that can still reach it.  Candidates come from a bucket grid over
** the box, shell by shell (buckets at Chebyshev index distance k), nearest
** first inside a shell; a seed at distance d can cut the cell only when
** d/2 < R, R the largest distance from the seed to a cell vertex, so the
** search ends when the nearest unvisited shell is farther than 2R.  On a
** Cartesian lattice that is the 26 (2-D: 8) lattice neighbours.
**
** Clipping classifies each vertex as in, on (within EPS_CLIP x box size
** of the plane) or out; nothing happens unless a vertex is out, new
** vertices are made only on edges from an in to an out vertex (once per
** edge, parametrised from the in end, so the two polygons sharing the
** edge get the same point), and the new face is every on or new vertex,
** sorted by angle about the plane normal.  So a plane that only touches
** the cell (the diagonal neighbours of a lattice) adds nothing, and each
** cell is a closed polyhedron: every edge is used by exactly two of its
** polygons.
**
** Each cell's vertices are then welded into the global point list.  A
** vertex on exactly 3 faces (2-D: 2 edges) is named by the sorted set of
** its seeds and box sides, the set every cell around it sees; the first
** cell to meet a name welds it by position, later cells get the same point
** by name, so welding stays consistent where positions are ill-conditioned
** (nearly cospherical seeds).  Welding by position: a point closer than
** VORONOI_MERGE x (box size) to an earlier one is that one (the nearest;
** an exact copy of an earlier query always gets the earlier answer).  The
** cell is stored as polygons of global point numbers, sorted by label.
** 2-D: the cell is stored as its polygon only (global points of the
** plane at lo, edge labels), and a vertex's name {i, a, b} is looked up
** in the polygons of the kept seeds among a and b made before i instead
** of a table of names: the same answer, without touching memory for every
** vertex (fresh memory is what big grids spend their time on).
**
** Pass 2: the face between kept seeds i < j is the polygon cell i stored;
** cell j uses its reverse, so the two cells see exactly the same points.
** 3-D faces of area below VORONOI_MERGE^2 x (box size)^2 whose points lie
** within a few merge distances of each other collapse to one point (a
** union of their points), so their neighbours in all cells lose the same
** points; thin faces longer than that stay (collapsing them would move
** far-apart points, dropping them alone would open the cells).  Repeated
** consecutive points are removed and faces left with fewer than 3 points
** dropped (nfaces_dropped).  Every cell is then checked to be closed (each
** edge used once in each direction).  A sliver that only one of the cells
** around an edge resolved, and that welding reduced to a segment, leaves a
** point inside that edge in some polygons and not in others (a
** T-junction); such points are inserted into the stored polygons that
** lack them, and the cells sharing a changed polygon are checked again.  A
** cell still open is an error naming its seed, never a silently broken
** grid.  The faces are then written straight into the Mesh, already in
** OpenFOAM's order (voronoi_write_direct; meshbuild only when they are not).
** 2-D: a prism is closed by construction, so when no polygon lost a point
** to welding and every edge between kept cells is the reverse of the
** neighbour's (rings_regular, the usual case), the steps above change
** nothing and the prisms are written straight from the polygons
** (write_rings: side quads, back and front faces, point 2p at lo and
** 2p+1 at hi); otherwise the polygons become prisms in the store and go
** through the steps above, so the mesh is the same either way.
** Consequence of merging: face points lie on their bisector to round-off
** (1e-13 of the box) except near merged points, where they may be off by
** up to the merge distance.
**
** Files: voronoi.c (this: input, pass 1 and the driver), voronoi_search.c
** (the bucket grid and the neighbour search), voronoi_clip3.c and
** voronoi_clip2.c (the clippers), voronoi_weld.c (global points by
** position and by name), voronoi_store.c (the cells as polygons of global
** points), voronoi_assemble.c (pass 2: collapsing, welding and closing),
** voronoi_write.c (the Mesh in OpenFOAM's order, directly or through
** meshbuild), voronoi_prisms.c (2-D: the prisms straight from the
** polygons); voronoi_impl.h holds the types they share.
**
** Invariants: cell c is the c-th kept seed; a face's label is the seed
** across it, so faces towards dropped seeds go to that seed's patch and
** box faces to side_patch; 2-D cells are prisms between lo and hi along
** flat_axis, their front and back faces on the side patches of that axis.
*/
#include "voronoi_impl.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* on-plane tolerance of the clipper, x box size: far above round-off of
   the vertex coordinates, far below the weld distance */
#define EPS_CLIP 1e-13
/* slack on the reach test d/2 < R */
#define REACH_SLACK (1.0 + 1e-9)

static int coincide(const VoronoiInput *in, int i, int j, Err *e)
{
    return err_set(e, NULL, 0, "voronoi: seeds %d and %d coincide (%g %g %g)", i, j, in->x[3 * i],
                   in->x[3 * i + 1], in->x[3 * i + 2]);
}

/* Bisector clipping of seed i's cell, shell by shell; clip(ctx, j, d2)
   returns the cell's new squared radius. */
static int cell_search(Build *B, int i, double r2, double (*clip)(Build *, int, int, double), Err *e)
{
    const VoronoiInput *in = B->in;
    double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
    if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
    int b[3];
    for (int a = 0; a < 3; a++) b[a] = voronoi_bucket_axis(&B->g, a, x[a]);
    double dup2 = sq(VORONOI_MERGE * B->L);
    for (int k = 0;; k++) {
        if (k > 0) {
            double sd = voronoi_shell_dist(&B->g, b, k, x);
            if (sd == INFINITY) break;
            if (sd > 0 && sd * sd > 4 * r2 * REACH_SLACK) break;
        }
        voronoi_shell_collect(&B->s, &B->g, in, i, b, k, x, 4 * r2 * REACH_SLACK);
        for (int q = 0; q < B->s.n; q++) {
            Cand cd = B->s.cand[q];
            if (cd.d2 > 4 * r2 * REACH_SLACK) break;
            if (cd.d2 <= dup2) return coincide(in, i, cd.j, e);
            r2 = clip(B, i, cd.j, r2);
        }
    }
    return 0;
}

static double clip3_seed(Build *B, int i, int j, double r2)
{
    return voronoi_clip3_bisector(&B->c3, B->in->x + 3 * i, B->in->x + 3 * j, B->eps, j, r2);
}

static int cell3(Build *B, int i, Err *e)
{
    const VoronoiInput *in = B->in;
    voronoi_poly_box(&B->c3, in->lo, in->hi);
    if (cell_search(B, i, voronoi_poly_radius3(&B->c3.p[0], in->x + 3 * i), clip3_seed, e)) return -1;
    Poly *P = &B->c3.p[B->c3.cur];
    if (P->nf < 4) return err_set(e, NULL, 0, "voronoi: the cell of seed %d is empty", i);
    need(&B->gid, &B->gcap, (size_t)P->nv, sizeof(int));
    need(&B->vlab, &B->vlcap, 4 * (size_t)P->nv, sizeof(int));
    for (int k = 0; k < P->nv; k++) B->gid[k] = B->vlab[4 * k] = 0;
    for (int f = 0; f < P->nf; f++)
        for (int q = P->off[f]; q < P->off[f + 1]; q++) {
            int *vl = B->vlab + 4 * P->idx[q];
            if (vl[0] < 3) vl[1 + vl[0]] = P->lab[f];
            vl[0]++;
        }
    for (int k = 0; k < P->nv; k++) B->gid[k] = -1;
    int f0 = B->st.nf;
    need(&B->tmp, &B->tcap, (size_t)P->ni, sizeof(int));
    int *pts = B->tmp;
    for (int f = 0; f < P->nf; f++) {
        int s = P->off[f], n = P->off[f + 1] - s;
        for (int q = 0; q < n; q++) {
            int v = P->idx[s + q];
            if (B->gid[v] < 0) {
                int32_t key[4];
                int named = B->vlab[4 * v] == 3, low = named ? voronoi_vertex_name(i, B->vlab + 4 * v + 1, 3, key) : 0;
                B->gid[v] = voronoi_weld_vertex(&B->w, &B->names, named ? key : NULL, low, P->v + 3 * v);
            }
            pts[q] = B->gid[v];
        }
        voronoi_store_face(&B->st, P->lab[f], pts, n, 0);
    }
    voronoi_store_sort_cell(&B->st, f0, &B->tmp, &B->tcap);
    return 0;
}

/* 2-D vertex names without a table: the vertex of seed i's cell between
   edges labelled a and b is named {i, a, b}, and the cells that can have
   met that name before are those of the kept seeds among a and b that
   come before i.  The point of cell l's vertex between its edges
   labelled i and o (in either order), or -1 when l has no cell yet or no
   such vertex. */
static int ring_vertex(const Build *B, int l, int i, int o)
{
    if (l < 0 || l > i || !B->in->keep[l]) return -1;
    const Rings *r = &B->rg;
    int c = B->cell_of[l], r0 = r->off[c], n = r->off[c + 1] - r0;
    const int *lab = r->lab + r0;
    for (int e = 0; e < n; e++) {
        if (lab[e] != i) continue;
        if (lab[e > 0 ? e - 1 : n - 1] == o) return r->gid[r0 + e];
        if (lab[e + 1 < n ? e + 1 : 0] == o) return r->gid[r0 + (e + 1 < n ? e + 1 : 0)];
        return -1;
    }
    return -1;
}

static double clip2_seed(Build *B, int i, int j, double r2)
{
    int ua = (B->in->flat_axis + 1) % 3, va = (B->in->flat_axis + 2) % 3;
    return voronoi_clip2_bisector(&B->c2, B->in->x + 3 * i, B->in->x + 3 * j, ua, va, B->eps, j, r2);
}

static int cell2(Build *B, int i, Err *e)
{
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis, ua = (fa + 1) % 3, va = (fa + 2) % 3;
    Clip2 *c = &B->c2;
    c->cur = 0;
    Poly2 *P = &c->p[0];
    voronoi_poly2_reserve(P, 4);
    P->n = 0;
    voronoi_poly2_push(P, in->lo[ua], in->lo[va], -1 - (2 * va));
    voronoi_poly2_push(P, in->hi[ua], in->lo[va], -1 - (2 * ua + 1));
    voronoi_poly2_push(P, in->hi[ua], in->hi[va], -1 - (2 * va + 1));
    voronoi_poly2_push(P, in->lo[ua], in->hi[va], -1 - (2 * ua));
    const double *xi = in->x + 3 * i;
    double r2 = 0;
    for (int k = 0; k < 4; k++) {
        double d = sq(P->x[2 * k] - xi[ua]) + sq(P->x[2 * k + 1] - xi[va]);
        if (d > r2) r2 = d;
    }
    if (cell_search(B, i, r2, clip2_seed, e)) return -1;
    P = &c->p[c->cur];
    if (P->n < 3) return err_set(e, NULL, 0, "voronoi: the cell of seed %d is empty", i);
    need(&B->gid, &B->gcap, (size_t)P->n, sizeof(int));
    for (int k = 0; k < P->n; k++) {
        double x[3];
        x[fa] = in->lo[fa];
        x[ua] = P->x[2 * k];
        x[va] = P->x[2 * k + 1];
        int l0 = P->lab[k > 0 ? k - 1 : P->n - 1], l1 = P->lab[k], g = ring_vertex(B, l0, i, l1);
        if (g < 0) g = ring_vertex(B, l1, i, l0);
        B->gid[k] = g >= 0 ? g : voronoi_weld_point(&B->w, x);
    }
    Rings *r = &B->rg;
    need(&r->gid, &r->gcap, (size_t)r->n + (size_t)P->n, sizeof(int));
    need(&r->lab, &r->lcap, (size_t)r->n + (size_t)P->n, sizeof(int));
    memcpy(r->gid + r->n, B->gid, sizeof(int) * (size_t)P->n);
    memcpy(r->lab + r->n, P->lab, sizeof(int) * (size_t)P->n);
    r->n += P->n;
    return 0;
}

static int check_input(const VoronoiInput *in, Err *e)
{
    if (in->nseeds <= 0 || !in->x || !in->keep) return err_set(e, NULL, 0, "voronoi: no seeds");
    if (in->flat_axis < -1 || in->flat_axis > 2)
        return err_set(e, NULL, 0, "voronoi: flat axis %d is not -1, 0, 1 or 2", in->flat_axis);
    for (int a = 0; a < 3; a++)
        if (!(in->lo[a] < in->hi[a]) || !isfinite(in->lo[a]) || !isfinite(in->hi[a]))
            return err_set(e, NULL, 0, "voronoi: empty box along axis %d: %g to %g", a, in->lo[a], in->hi[a]);
    if (in->npatches <= 0 || !in->patches) return err_set(e, NULL, 0, "voronoi: no patches");
    for (int s = 0; s < 6; s++)
        if (in->side_patch[s] < 0 || in->side_patch[s] >= in->npatches)
            return err_set(e, NULL, 0, "voronoi: box side %d has patch %d, not in 0..%d", s, in->side_patch[s],
                           in->npatches - 1);
    double L = 0;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis && in->hi[a] - in->lo[a] > L) L = in->hi[a] - in->lo[a];
    double tol = VORONOI_MERGE * L;
    int nkeep = 0;
    for (int i = 0; i < in->nseeds; i++) {
        const double *x = in->x + 3 * i;
        for (int a = 0; a < 3; a++)
            if (!isfinite(x[a])) return err_set(e, NULL, 0, "voronoi: seed %d is not finite", i);
        if (!in->keep[i]) {
            if (!in->patch || in->patch[i] < 0 || in->patch[i] >= in->npatches)
                return err_set(e, NULL, 0, "voronoi: dropped seed %d has patch %d, not in 0..%d", i,
                               in->patch ? in->patch[i] : -1, in->npatches - 1);
            continue;
        }
        nkeep++;
        for (int a = 0; a < 3; a++)
            if (a != in->flat_axis && (x[a] < in->lo[a] - tol || x[a] > in->hi[a] + tol))
                return err_set(e, NULL, 0, "voronoi: kept seed %d (%g %g %g) is outside the box", i, x[0], x[1],
                               x[2]);
    }
    if (!nkeep) return err_set(e, NULL, 0, "voronoi: no seed is kept");
    return 0;
}

int voronoi_mesh(const VoronoiInput *in, Mesh *out, int *seed_of, VoronoiStats *st, Err *e)
{
    mesh_init(out);
    if (check_input(in, e)) return -1;
    Build B;
    memset(&B, 0, sizeof B);
    B.in = in;
    B.L = 0;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis && in->hi[a] - in->lo[a] > B.L) B.L = in->hi[a] - in->lo[a];
    B.eps = EPS_CLIP * B.L;
    voronoi_buckets_build(&B.g, in);
    int *cell_of = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    int *cells = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    int nc = 0;
    for (int i = 0; i < in->nseeds; i++) {
        cell_of[i] = in->keep[i] ? nc : -1;
        if (in->keep[i]) cells[nc++] = i;
    }
    size_t expect = (size_t)nc * (in->flat_axis >= 0 ? 2 : 7);
    voronoi_weld_init(&B.w, &B.g, VORONOI_MERGE * B.L, in->flat_axis, in->flat_axis >= 0 ? 6 : 3, expect);
    if (in->flat_axis < 0) voronoi_names_init(&B.names, in->nseeds, 4 * expect);
    B.cell_of = cell_of;
    B.st.ncells = nc;
    B.st.cell_off = mem_alloc(sizeof(int) * (size_t)(nc + 1));
    B.st.cell_off[0] = 0;
    int rc = 0;
    if (in->flat_axis >= 0) {
        B.rg.off = mem_alloc(sizeof(int) * (size_t)(nc + 1));
        B.rg.off[0] = 0;
        /* a lattice's polygons have 4 points */
        need(&B.rg.gid, &B.rg.gcap, 4 * (size_t)nc, sizeof(int));
        need(&B.rg.lab, &B.rg.lcap, 4 * (size_t)nc, sizeof(int));
        for (int c = 0; c < nc && !rc; c++) {
            rc = cell2(&B, cells[c], e);
            B.rg.off[c + 1] = B.rg.n;
        }
        if (!rc) rc = voronoi_assemble2(&B, cell_of, cells, out, st, e);
    } else {
        /* 3-D cells have 6 (lattice) to about 16 faces (random), 4 to 6
           points each */
        size_t fpc = 10;
        need(&B.st.lab, &B.st.lcap, fpc * (size_t)nc, sizeof(int));
        need(&B.st.off, &B.st.ocap, fpc * (size_t)nc + 1, sizeof(int));
        need(&B.st.idx, &B.st.icap, 4 * fpc * (size_t)nc, sizeof(int));
        for (int c = 0; c < nc && !rc; c++) {
            rc = cell3(&B, cells[c], e);
            B.st.cell_off[c + 1] = B.st.nf;
        }
        if (!rc) rc = voronoi_assemble(&B, cell_of, cells, out, st, e);
    }
    if (!rc && seed_of) memcpy(seed_of, cells, sizeof(int) * (size_t)nc);
    voronoi_buckets_free(&B.g);
    free(B.s.cand);
    voronoi_clip3_free(&B.c3);
    voronoi_clip2_free(&B.c2);
    voronoi_weld_free(&B.w);
    voronoi_names_free(&B.names);
    voronoi_store_free(&B.st);
    voronoi_rings_free(&B.rg);
    free(B.gid);
    free(B.vlab);
    free(B.tmp);
    free(cell_of);
    free(cells);
    if (rc) mesh_free(out);
    return rc;
}
