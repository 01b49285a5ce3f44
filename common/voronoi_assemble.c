/*
** voronoi_assemble.c: pass 2 of voronoi.c: from the stored polygons to
** closed cells.
**
** The face between kept seeds i < j is the polygon cell i stored; cell j
** uses it reversed, so both see the same points.  3-D faces of area below
** (VORONOI_MERGE x box size)^2 whose points lie within a few merge
** distances collapse to one point (a union of their points) in every cell;
** thin faces longer than that stay.  Repeated consecutive points go, and
** faces left with fewer than 3 points are dropped.  Every cell is then
** checked closed (each edge once in each direction, counted in a small
** hash); a T-junction left by a sliver that only one cell resolved is
** repaired by inserting the point into the stored polygons that lack it,
** and the cells sharing a changed polygon are checked again.  A cell still
** open is an error naming its seed.  voronoi_assemble ends by writing the
** mesh (voronoi_write.c).
*/
#include "voronoi_impl.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int uf_find(int *uf, int a)
{
    while (uf[a] != a) {
        uf[a] = uf[uf[a]];
        a = uf[a];
    }
    return a;
}

/* Area vector of polygon idx[0..n) (points pts), reversed when rev. */
void voronoi_poly_area(const double *pts, const int *idx, int n, int rev, double S[3])
{
    const double *p0 = pts + 3 * idx[0];
    S[0] = S[1] = S[2] = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *a = pts + 3 * idx[k], *b = pts + 3 * idx[k + 1];
        double u[3] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2]};
        double v[3] = {b[0] - p0[0], b[1] - p0[1], b[2] - p0[2]};
        S[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
        S[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
        S[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
    }
    if (rev)
        for (int a = 0; a < 3; a++) S[a] = -S[a];
}

static void edges_clear(Edges *x, int nedge)
{
    for (int k = 0; k < x->nused; k++) x->cnt[x->used[k]] = 0;
    x->nused = 0;
    if (4 * nedge > x->cap) {
        int cap = 64;
        while (cap < 4 * nedge) cap *= 2;
        free(x->key);
        free(x->cnt);
        x->key = mem_alloc(sizeof(uint64_t) * (size_t)cap);
        x->cnt = mem_calloc((size_t)cap, sizeof(int));
        x->cap = cap;
    }
    need(&x->used, &x->ucap, (size_t)nedge, sizeof(int));
}

static void edges_add(Edges *x, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    uint64_t k = (uint64_t)(uint32_t)lo << 32 | (uint32_t)hi;
    uint64_t h = k * 0x9E3779B97F4A7C15u;
    int m = x->cap - 1, s = (int)(h >> 40) & m;
    while (x->cnt[s] && x->key[s] != k) s = (s + 1) & m;
    if (!x->cnt[s]) {
        x->key[s] = k;
        x->used[x->nused++] = s;
    }
    x->cnt[s] += a < b ? 1 : 16;
}

static int edges_closed(const Edges *x)
{
    for (int k = 0; k < x->nused; k++)
        if (x->cnt[x->used[k]] != 17) return 0;
    return 1;
}

static void edges_free(Edges *x)
{
    free(x->key);
    free(x->cnt);
    free(x->used);
}

static int edge_count(const Edges *x, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    uint64_t k = (uint64_t)(uint32_t)lo << 32 | (uint32_t)hi;
    int m = x->cap - 1, s = (int)((k * 0x9E3779B97F4A7C15u) >> 40) & m;
    while (x->cnt[s] && x->key[s] != k) s = (s + 1) & m;
    return x->cnt[s];
}

/* Faces of area below amin whose points all lie within dmax of the first
   collapse to a point.  A thin face longer than that (a needle between two
   long edges) stays: collapsing it would move far-apart points together,
   and dropping it alone would open both cells. */
static void collapse_tiny(Assembly *A, int *uf, double amin, double dmax)
{
    Store *s = A->st;
    for (int c = 0; c < s->ncells; c++) {
        int i = A->seed_of[c];
        for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
            int lab = s->lab[f], n = s->off[f + 1] - s->off[f];
            if (lab >= 0 && A->in->keep[lab] && lab < i) continue;
            const int *idx = s->idx + s->off[f];
            double S[3];
            voronoi_poly_area(A->pts, idx, n, 0, S);
            if (sq(S[0]) + sq(S[1]) + sq(S[2]) >= amin * amin) continue;
            const double *p0 = A->pts + 3 * idx[0];
            int small = 1;
            for (int k = 1; k < n && small; k++) {
                const double *p = A->pts + 3 * idx[k];
                small = sq(p[0] - p0[0]) + sq(p[1] - p0[1]) + sq(p[2] - p0[2]) <= dmax * dmax;
            }
            if (!small) continue;
            int r = uf_find(uf, idx[0]);
            for (int k = 1; k < n; k++) {
                int q = uf_find(uf, idx[k]);
                if (q != r) uf[q] = r;
            }
        }
    }
}

/* Renumbers through uf and drops repeated consecutive points. */
static void weld_faces(Assembly *A, int *uf)
{
    Store *s = A->st;
    for (int f = 0; f < s->nf; f++) {
        int *idx = s->idx + s->off[f], n = s->off[f + 1] - s->off[f], m = 0;
        for (int k = 0; k < n; k++) {
            int p = uf ? uf_find(uf, idx[k]) : idx[k];
            if (m == 0 || idx[m - 1] != p) idx[m++] = p;
        }
        while (m > 1 && idx[m - 1] == idx[0]) m--;
        A->beg[f] = s->off[f];
        A->len[f] = m;
    }
}

/* Is stored face f (of a cell with seed i) the one the cell uses?  Not
   when it faces a lower kept seed that stored the pair's face itself. */
int voronoi_face_superseded(const Assembly *A, int f, int i, int *g)
{
    int lab = A->st->lab[f];
    *g = -1;
    if (lab < 0 || !A->in->keep[lab] || lab > i) return 0;
    *g = voronoi_store_find(A->st, A->cell_of[lab], i);
    return *g >= 0;
}

/* The faces of cell c (at least 3 points each) into A->cf; returns the
   number of their edges. */
int voronoi_cell_face_list(Assembly *A, int c)
{
    Store *s = A->st;
    int i = A->seed_of[c], nedge = 0;
    A->ncf = 0;
    need(&A->cf, &A->cfcap, (size_t)(s->cell_off[c + 1] - s->cell_off[c]), sizeof(CFace));
    for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
        int g;
        CFace cf = voronoi_face_superseded(A, f, i, &g) ? (CFace){g, 1} : (CFace){f, 0};
        if (A->len[cf.f] < 3) continue;
        A->cf[A->ncf++] = cf;
        nedge += A->len[cf.f];
    }
    return nedge;
}

/* cell_face_list, and counts the faces' edges into A->edges.  Returns 1
   when the cell is closed. */
static int cell_faces(Assembly *A, int c)
{
    Store *s = A->st;
    edges_clear(&A->edges, voronoi_cell_face_list(A, c));
    for (int k = 0; k < A->ncf; k++) {
        const int *idx = s->idx + A->beg[A->cf[k].f];
        int n = A->len[A->cf[k].f];
        for (int q = 0; q < n; q++) {
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            if (A->cf[k].rev) edges_add(&A->edges, b, a);
            else edges_add(&A->edges, a, b);
        }
    }
    return edges_closed(&A->edges);
}

/* Repairs T-junctions of cell c (after cell_faces found it open): a thin
   face that welding reduced to a segment leaves its end points inside an
   edge of the neighbouring faces of the one cell that resolved it, but
   not of the other cells around that edge.  Each point that ends an
   unmatched edge and lies on another unmatched edge (within 4 tol, strictly
   between its ends) is inserted there, in the stored polygon, so every
   cell using that polygon sees it; those cells are returned in touched
   (at most 2 per repaired face).  Returns the number of insertions. */
static int cell_repair(Assembly *A, int c, int **touched, int *ntouched, int *tcap)
{
    Store *s = A->st;
    int nends = 0, nins = 0;
    for (int k = 0; k < A->ncf; k++) {
        const int *idx = s->idx + A->beg[A->cf[k].f];
        int n = A->len[A->cf[k].f];
        need(&A->ends, &A->ecap, (size_t)nends + 2 * (size_t)n, sizeof(int));
        for (int q = 0; q < n; q++) {
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            if (edge_count(&A->edges, a, b) == 17) continue;
            A->ends[nends++] = a;
            A->ends[nends++] = b;
        }
    }
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, n = A->len[f], m = 0;
        need(&A->tpts, &A->tcap, (size_t)n + (size_t)nends, sizeof(int));
        need(&A->tt, &A->ttcap, (size_t)nends + 1, sizeof(double));
        for (int q = 0; q < n; q++) {
            const int *idx = s->idx + A->beg[f];
            int a = idx[q], b = idx[q + 1 < n ? q + 1 : 0];
            A->tpts[m++] = a;
            if (edge_count(&A->edges, a, b) == 17) continue;
            const double *pa = A->pts + 3 * a, *pb = A->pts + 3 * b;
            double ab[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
            double l2 = sq(ab[0]) + sq(ab[1]) + sq(ab[2]);
            int m0 = m;
            for (int u = 0; u < nends; u++) {
                int p = A->ends[u], dup = p == a || p == b;
                for (int v = m0; v < m && !dup; v++) dup = A->tpts[v] == p;
                if (dup || !(l2 > 0)) continue;
                const double *pp = A->pts + 3 * p;
                double ap[3] = {pp[0] - pa[0], pp[1] - pa[1], pp[2] - pa[2]};
                double t = (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2;
                if (!(t > 0 && t < 1)) continue;
                double d2 = sq(ap[0] - t * ab[0]) + sq(ap[1] - t * ab[1]) + sq(ap[2] - t * ab[2]);
                if (d2 > 16 * A->tol * A->tol) continue;
                /* sorted along the edge */
                int v = m++;
                while (v > m0 && A->tt[v - m0 - 1] > t) {
                    A->tpts[v] = A->tpts[v - 1];
                    A->tt[v - m0] = A->tt[v - m0 - 1];
                    v--;
                }
                A->tpts[v] = p;
                A->tt[v - m0] = t;
            }
        }
        if (m == n) continue;
        nins += m - n;
        need(&s->idx, &s->icap, (size_t)s->ni + (size_t)m, sizeof(int));
        memcpy(s->idx + s->ni, A->tpts, sizeof(int) * (size_t)m);
        A->beg[f] = s->ni;
        A->len[f] = m;
        s->ni += m;
        int lab = s->lab[f], other[2] = {voronoi_store_cell(s, f), lab >= 0 && A->in->keep[lab] ? A->cell_of[lab] : -1};
        for (int q = 0; q < 2; q++)
            if (other[q] >= 0 && other[q] != c) {
                need(touched, tcap, (size_t)*ntouched + 1, sizeof(int));
                (*touched)[(*ntouched)++] = other[q];
            }
    }
    return nins;
}

static int cell_not_closed(const Assembly *A, int c, Err *e)
{
    const double *x = A->in->x + 3 * A->seed_of[c];
    return err_set(e, NULL, 0,
                   "voronoi: the cell of seed %d at (%g %g %g) is not closed after welding its points "
                   "(seeds closer than %g of the box?)",
                   A->seed_of[c], x[0], x[1], x[2], VORONOI_MERGE);
}

/* Checks every cell, repairing T-junctions; cells whose faces a repair
   changed are checked again (a queue, each cell in it at most once). */
static int close_cells(Assembly *A, Err *e)
{
    int n = A->st->ncells, head = 0, count = n, budget = 4 * n + 64;
    if (n <= 0) return 0;
    int *queue = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    char *in_queue = mem_alloc((size_t)(n > 0 ? n : 1));
    for (int c = 0; c < n; c++) queue[c] = c;
    memset(in_queue, 1, (size_t)n);
    int *touched = NULL, ntouched = 0, tcap = 0, rc = 0;
    while (count > 0 && !rc) {
        int c = queue[head];
        head = (head + 1) % n;
        count--;
        in_queue[c] = 0;
        if (cell_faces(A, c)) continue;
        ntouched = 0;
        if (budget-- <= 0 || !cell_repair(A, c, &touched, &ntouched, &tcap)) {
            rc = cell_not_closed(A, c, e);
            break;
        }
        if (!cell_faces(A, c)) {
            rc = cell_not_closed(A, c, e);
            break;
        }
        for (int k = 0; k < ntouched; k++) {
            int d = touched[k];
            if (in_queue[d]) continue;
            in_queue[d] = 1;
            queue[(head + count++) % n] = d;
        }
    }
    free(queue);
    free(in_queue);
    free(touched);
    return rc;
}

/* Cell c's volume (its faces in A->cf, from cell_face_list) into vs. */
void voronoi_measure_cell(const Assembly *A, int c, VoronoiStats *vs)
{
    const double *xi = A->in->x + 3 * A->seed_of[c];
    double vol = 0;
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, n = A->len[f];
        const int *idx = A->st->idx + A->beg[f];
        double S[3];
        voronoi_poly_area(A->pts, idx, n, A->cf[k].rev, S);
        const double *p0 = A->pts + 3 * idx[0];
        vol += (S[0] * (p0[0] - xi[0]) + S[1] * (p0[1] - xi[1]) + S[2] * (p0[2] - xi[2])) / 3;
    }
    if (vs) {
        if (c == 0 || vol < vs->vol_min) vs->vol_min = vol;
        vs->vol_total += vol;
    }
}

/* The cell across stored face f, or -1 - patch for a boundary face. */
int voronoi_face_other(const Assembly *A, int f)
{
    const VoronoiInput *in = A->in;
    int lab = A->st->lab[f];
    if (lab >= 0 && in->keep[lab]) return A->cell_of[lab];
    return -1 - (lab >= 0 ? in->patch[lab] : in->side_patch[-1 - lab]);
}

int voronoi_assemble(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e)
{
    const VoronoiInput *in = B->in;
    Store *s = &B->st;
    int flat = in->flat_axis;
    Assembly A = {0};
    A.in = in;
    A.st = s;
    A.cell_of = cell_of;
    A.seed_of = seed_of;
    int np = flat >= 0 ? 2 * B->w.npts : B->w.npts;
    A.pts = mem_alloc(sizeof(double) * 3 * (size_t)(np > 0 ? np : 1));
    if (flat >= 0) {
        for (int p = 0; p < B->w.npts; p++) {
            memcpy(A.pts + 6 * p, B->w.pts + 6 * p, 3 * sizeof(double));
            memcpy(A.pts + 6 * p + 3, B->w.pts + 6 * p, 3 * sizeof(double));
            A.pts[6 * p + 3 + flat] = in->hi[flat];
        }
    } else {
        memcpy(A.pts, B->w.pts, sizeof(double) * 3 * (size_t)np);
    }
    A.tol = VORONOI_MERGE * B->L;
    size_t nf1 = (size_t)(s->nf > 0 ? s->nf : 1);
    A.len = mem_alloc(sizeof(int) * nf1);
    A.beg = mem_alloc(sizeof(int) * nf1);
    int *uf = NULL;
    if (flat < 0) {
        uf = mem_alloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
        for (int p = 0; p < np; p++) uf[p] = p;
        collapse_tiny(&A, uf, sq(VORONOI_MERGE * B->L), 4 * VORONOI_MERGE * B->L);
    }
    weld_faces(&A, uf);
    free(uf);
    int rc = close_cells(&A, e);

    Plan pl;
    voronoi_plan_faces(&A, &pl);
    if (vs) memset(vs, 0, sizeof *vs);
    if (!rc && pl.empty >= 0) rc = err_set(e, NULL, 0, "voronoi: the cell of seed %d has no face", seed_of[pl.empty]);
    if (!rc)
        rc = pl.direct ? voronoi_write_direct(&A, &pl, np, out, vs) : voronoi_write_meshbuild(&A, &pl, np, out, vs, e);
    voronoi_plan_free(&pl);
    if (!rc && vs) {
        vs->ncells = s->ncells;
        vs->nfaces_dropped = A.ndropped;
        vs->ortho_max = voronoi_ortho_max(out, in, seed_of);
    }
    free(A.pts);
    free(A.len);
    free(A.beg);
    free(A.cf);
    free(A.tpts);
    free(A.ends);
    free(A.tt);
    edges_free(&A.edges);
    return rc;
}
