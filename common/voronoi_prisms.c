/*
** voronoi_prisms.c: 2-D grids: the prisms written straight from the
** polygons (voronoi.c's third assembly path).
**
** A 2-D cell is its polygon in the plane at lo, extruded to hi along the
** flat axis: point 2p at lo and 2p+1 at hi for plane point p, a quad per
** edge, the back and front faces on the side patches of that axis.  A
** prism is closed by construction, so when no polygon lost a point to
** welding and every edge between kept cells is the reverse of the
** neighbour's (rings_regular, the usual case), the general assembly would
** change nothing and the faces are written straight into the Mesh;
** otherwise the polygons become prisms in the store (ring_store) and go
** through voronoi_assemble, which gives the same mesh in the regular case.
*/
#include "voronoi_impl.h"

#include <stdlib.h>
#include <string.h>

/* The prism of 2-D cell c as stored polygons (the general assembly's
   input): a quad per edge, base point p of the plane being point 2p at
   lo and 2p+1 at hi, and the back and front faces, sorted by label. */
static void ring_store(Build *B, int c)
{
    int fa = B->in->flat_axis, r0 = B->rg.off[c], n = B->rg.off[c + 1] - r0;
    const int *gid = B->rg.gid + r0, *lab = B->rg.lab + r0;
    need(&B->tmp, &B->tcap, 2 * (size_t)n + 4, sizeof(int));
    int f0 = B->st.nf;
    int *q = B->tmp;
    for (int k = 0; k < n; k++) {
        int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0];
        int quad[4] = {2 * a, 2 * b, 2 * b + 1, 2 * a + 1};
        voronoi_store_face(&B->st, lab[k], quad, 4, 0);
    }
    for (int k = 0; k < n; k++) q[k] = 2 * gid[k];
    voronoi_store_face(&B->st, -1 - 2 * fa, q, n, 1);
    for (int k = 0; k < n; k++) q[k] = 2 * gid[k] + 1;
    voronoi_store_face(&B->st, -1 - (2 * fa + 1), q, n, 0);
    voronoi_store_sort_cell(&B->st, f0, &B->tmp, &B->tcap);
}

/* Does the edge labelled l of a polygon (n points) go from a to b? */
static int ring_has(const int *gid, const int *lab, int n, int l, int a, int b)
{
    for (int k = 0; k < n; k++)
        if (lab[k] == l) return gid[k] == a && gid[k + 1 < n ? k + 1 : 0] == b;
    return 0;
}

/* Is the general assembly a no-op on the prisms?  It is when no polygon
   has two points welded into one (no face shrinks or drops, each edge of
   the prism is used once each way) and every edge between two kept
   cells is the reverse of the other
   cell's edge (the cells share that face and are closed, and each
   internal face goes from its lower cell to a higher one).  Then the
   mesh is written from the polygons; otherwise the prisms go through the
   general assembly (repairs, dropped faces), which gives the same mesh
   in the regular case. */
static int rings_regular(const Build *B, const int *cell_of, const int *seed_of)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    for (int c = 0; c < B->st.ncells; c++) {
        int r0 = r->off[c], n = r->off[c + 1] - r0, i = seed_of[c];
        const int *gid = r->gid + r0, *lab = r->lab + r0;
        for (int k = 0; k < n; k++) {
            int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0], j = lab[k];
            for (int m = 0; m < k; m++)
                if (gid[m] == a) return 0;
            if (j < 0 || !in->keep[j]) continue;
            int d = cell_of[j], s0 = r->off[d];
            if (!ring_has(r->gid + s0, r->lab + s0, r->off[d + 1] - s0, i, b, a)) return 0;
        }
    }
    return 1;
}

/* The faces of one prism in label order, as (label, edge) pairs; edge n
   is the back face (at lo), n + 1 the front face. */
static int prism_order(const Build *B, const int *lab, int n, int *ord)
{
    int fa = B->in->flat_axis;
    for (int k = 0; k < n + 2; k++) {
        int l = k < n ? lab[k] : k == n ? -1 - 2 * fa : -1 - (2 * fa + 1), q = k;
        while (q > 0 && ord[2 * (q - 1)] > l) {
            ord[2 * q] = ord[2 * (q - 1)];
            ord[2 * q + 1] = ord[2 * (q - 1) + 1];
            q--;
        }
        ord[2 * q] = l;
        ord[2 * q + 1] = k;
    }
    return n + 2;
}

/* The slot (0: internal, 1 + p: patch p) of a face labelled l of seed
   i's cell, or -1 when the lower cell across owns it. */
static int prism_slot(const VoronoiInput *in, int i, int l)
{
    if (l < 0) return 1 + in->side_patch[-1 - l];
    if (!in->keep[l]) return 1 + in->patch[l];
    return l > i ? 0 : -1;
}

/* Counts the faces and points of each slot (as voronoi_plan_faces). */
static void rings_plan(const Build *B, const int *seed_of, Plan *pl)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis;
    memset(pl, 0, sizeof *pl);
    pl->direct = 1;
    pl->empty = -1;
    pl->pface = mem_calloc((size_t)in->npatches, sizeof(int));
    pl->pidx = mem_calloc((size_t)in->npatches, sizeof(size_t));
    for (int c = 0; c < B->st.ncells; c++) {
        int r0 = r->off[c], n = r->off[c + 1] - r0, i = seed_of[c];
        for (int k = 0; k < n; k++) {
            int slot = prism_slot(in, i, r->lab[r0 + k]);
            if (slot < 0) continue;
            pl->nface++;
            pl->nidx += 4;
            if (slot == 0) {
                pl->nint++;
                pl->iint += 4;
            } else {
                pl->pface[slot - 1]++;
                pl->pidx[slot - 1] += 4;
            }
        }
        for (int s = 2 * fa; s <= 2 * fa + 1; s++) {
            pl->nface++;
            pl->nidx += (size_t)n;
            pl->pface[in->side_patch[s]]++;
            pl->pidx[in->side_patch[s]] += (size_t)n;
        }
    }
}

/* Writes cell c's own faces into their places (as put_cell) and its
   volume (area x thickness) into vs. */
static void put_prism(const Build *B, const int *cell_of, int c, int i, Mesh *m, Cursor *cur, int **ord,
                      int *ocap, VoronoiStats *vs)
{
    const Rings *r = &B->rg;
    const VoronoiInput *in = B->in;
    int r0 = r->off[c], n = r->off[c + 1] - r0;
    const int *gid = r->gid + r0, *lab = r->lab + r0;
    need(ord, ocap, 2 * (size_t)n + 4, sizeof(int));
    int nf = prism_order(B, lab, n, *ord);
    for (int q = 0; q < nf; q++) {
        int l = (*ord)[2 * q], k = (*ord)[2 * q + 1], slot = prism_slot(in, i, l);
        if (slot < 0) continue;
        int g = cur->face[slot]++;
        int *dst = m->face_idx + cur->idx[slot], len;
        if (k < n) {
            int a = gid[k], b = gid[k + 1 < n ? k + 1 : 0];
            dst[0] = 2 * a;
            dst[1] = 2 * b;
            dst[2] = 2 * b + 1;
            dst[3] = 2 * a + 1;
            len = 4;
        } else if (k == n) {
            for (int p = 0; p < n; p++) dst[p] = 2 * gid[n - 1 - p];
            len = n;
        } else {
            for (int p = 0; p < n; p++) dst[p] = 2 * gid[p] + 1;
            len = n;
        }
        cur->idx[slot] += (size_t)len;
        m->face_off[g + 1] = (int)cur->idx[slot];
        m->owner[g] = c;
        if (slot == 0) m->neighbour[g] = cell_of[l];
    }
    if (!vs) return;
    int ua = (in->flat_axis + 1) % 3, va = (in->flat_axis + 2) % 3;
    const double *p0 = B->w.pts + 6 * (size_t)gid[0];
    double area = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *pa = B->w.pts + 6 * (size_t)gid[k], *pb = B->w.pts + 6 * (size_t)gid[k + 1];
        area += (pa[ua] - p0[ua]) * (pb[va] - p0[va]) - (pa[va] - p0[va]) * (pb[ua] - p0[ua]);
    }
    double vol = 0.5 * area * (in->hi[in->flat_axis] - in->lo[in->flat_axis]);
    if (c == 0 || vol < vs->vol_min) vs->vol_min = vol;
    vs->vol_total += vol;
}

/* The mesh of regular prisms (rings_regular): every weld point is used
   (each is on its cell's back and front faces). */
static void write_rings(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs)
{
    const VoronoiInput *in = B->in;
    int fa = in->flat_axis, np = B->w.npts;
    Plan pl;
    Cursor cur;
    rings_plan(B, seed_of, &pl);
    voronoi_mesh_alloc(in, &pl, B->st.ncells, out, &cur);
    if (vs) memset(vs, 0, sizeof *vs);
    int *ord = NULL, ocap = 0;
    for (int c = 0; c < B->st.ncells; c++) put_prism(B, cell_of, c, seed_of[c], out, &cur, &ord, &ocap, vs);
    free(ord);
    /* the weld's points have room for their copies at hi */
    out->points = mem_realloc(B->w.pts, sizeof(double) * 6 * (size_t)(np > 0 ? np : 1));
    B->w.pts = NULL;
    for (int p = 0; p < np; p++) {
        double *x = out->points + 6 * (size_t)p;
        memcpy(x + 3, x, 3 * sizeof(double));
        x[3 + fa] = in->hi[fa];
    }
    out->npoints = 2 * np;
    free(cur.face);
    free(cur.idx);
    voronoi_plan_free(&pl);
    if (vs) {
        vs->ncells = B->st.ncells;
        vs->ortho_max = voronoi_ortho_max(out, in, seed_of);
    }
}

/* 2-D: the prisms, written directly when regular, else through the
   general assembly. */
int voronoi_assemble2(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e)
{
    if (rings_regular(B, cell_of, seed_of)) {
        write_rings(B, cell_of, seed_of, out, vs);
        return 0;
    }
    Store *s = &B->st;
    need(&s->lab, &s->lcap, (size_t)B->rg.n + 2 * (size_t)s->ncells, sizeof(int));
    need(&s->off, &s->ocap, (size_t)B->rg.n + 2 * (size_t)s->ncells + 1, sizeof(int));
    need(&s->idx, &s->icap, 6 * (size_t)B->rg.n, sizeof(int));
    for (int c = 0; c < s->ncells; c++) {
        ring_store(B, c);
        s->cell_off[c + 1] = s->nf;
    }
    return voronoi_assemble(B, cell_of, seed_of, out, vs, e);
}
