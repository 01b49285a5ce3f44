/*
** merge.c: merging of small cut cells (merge.h; spec granular-model.md
** §2.5, thesis §3.3.2).
**
** Design.  Clusters are sets in a union-find forest over the input cells
** (path halving, union by size); each root holds the cluster's volume,
** first moment (sum of V x centroid) and largest member, and a circular
** linked list (`next`) threads the members so a cluster's faces can be
** walked without building lists.  Merging runs in rounds.  A round takes
** the clusters below the bound (volume <= M_V x the Cartesian volume of
** their largest member) in order of increasing volume ratio (then cell
** number, so the result is deterministic) and lets each, if it is still
** below the bound when its turn comes, pick a master and merge at once:
** the smallest cells choose first, and later picks see the clusters as
** they are.  A slave that picks a slave forms a chain.  Rounds stop when
** no cluster is below the bound, when no pick was possible, or after
** max_iter rounds.
**
** The pick (Cartesian grid normal criterion, thesis §3.3.2.1):
**   n_S = minus the sum of the outward area vectors of the cluster's
**   immersed faces, i.e. its boundary faces that lie in none of the six
**   planes of their cell's parent Cartesian cell (within 1e-12 relative),
**   which is the area-weighted inner normal up to a positive factor.
**   Axes are ranked by |n_i| (Approach 3) or |n_i h_i| (Approach 2, h of
**   the largest member's parent); each axis with n_i != 0 (above 1e-12
**   |n|) gives the direction sign(n_i), and a candidate master is a cell
**   across an internal face of a member lying in the plane of that
**   member's parent on that side.  A cluster without immersed faces uses
**   the offset of its centroid from its parent cell's centre as n_S (it
**   points away from the cut-off part).  The empty direction of a 2-D
**   grid is never a merge direction.
**   Candidates come in four groups [ours, doc/tools/mergeCells.md]:
**     1. non-slaves in the merge directions, in rank order;
**     2. slaves in the merge directions (a chain);
**     3. any other face neighbour that is not a slave;
**     4. any other face neighbour;
**   inside a direction, the larger shared face area first.  The first
**   candidate whose union is sound wins: every face pyramid on the
**   union's centroid positive (OpenFOAM's face-pyramid check; a
**   non-convex union can put the centroid outside a face).  No sound
**   candidate: the cluster stays as it is and is reported.  (Preferring
**   unions with skewness <= 4 was tried and dropped: it steered slaves
**   away from their natural masters into clusters that later had no
**   sound neighbour, 24 unresolved cells in a 96^3 sphere grid against
**   none, for 6% fewer skewed faces.)
**
** Output.  The merged cell is the union polyhedron: internal faces with
** both cells in one cluster are dropped, every other face is kept with
** its points and orientation (meshbuild flips it when the renumbering
** swaps owner and neighbour), except that a 2-D cluster's empty faces
** on each side are joined into one polygon (see "empty faces" below).
** Output cells are numbered in order of their smallest member, so the
** numbering stays close to Cartesian order.  cell_parent is the largest
** member's, wall_normal follows the boundary faces through meshbuild's
** face map, merge_map records each input cell's output cell.  Everything
** is linear in the mesh size except the picks, which walk the faces of
** slave clusters and their candidates only.
*/
#include "merge.h"
#include "geom.h"
#include "mem.h"
#include "meshbuild.h"
#include "quality.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PLANE_TOL 1e-12   /* relative: a point on a parent plane */
#define ZERO_NORMAL 1e-12 /* relative: a normal component taken as 0 */

void merge_opts_default(MergeOpts *o)
{
    o->threshold = 0.5;
    o->criterion = MERGE_NORMAL;
    o->max_iter = 10;
}

const char *merge_reason_name(int reason)
{
    switch (reason) {
    case MERGE_OK: return "ok";
    case MERGE_NO_NEIGHBOUR: return "no neighbour to merge with (none, or none giving a sound cell)";
    case MERGE_ITER_LIMIT: return "still below the bound after maxIter rounds";
    default: return "unknown";
    }
}

void merge_stats_free(MergeStats *st)
{
    free(st->unresolved);
    free(st->reason);
    st->unresolved = st->reason = NULL;
    st->nunresolved = 0;
}

/* A candidate master: a cluster root and the face area it shares. */
typedef struct Cand {
    int root;
    double area;
} Cand;

typedef struct Work {
    const Mesh *m;          /* input with cell faces and geometry */
    const MergeOpts *o;
    int empty[3];           /* empty (2-D) directions */
    double *vcart;          /* parent volume per cell, 0 without a parent */
    int *uf, *size, *next;  /* union-find forest, member ring */
    double *cvol;           /* cluster volume, at roots */
    double *cmom;           /* 3 per cell: sum of V x centroid, at roots */
    int *big;               /* largest member, at roots */
    char *empty_patch;      /* per patch: 1 for type empty */
    Cand *cand;
    int ncand, cand_cap;
    int *order;             /* candidate roots in order of preference */
    int norder, order_cap;
} Work;

static int find(Work *w, int c)
{
    while (w->uf[c] != c) {
        w->uf[c] = w->uf[w->uf[c]];
        c = w->uf[c];
    }
    return c;
}

static void unite(Work *w, int a, int b)
{
    a = find(w, a);
    b = find(w, b);
    if (a == b) return;
    if (w->size[a] < w->size[b]) {
        int t = a;
        a = b;
        b = t;
    }
    w->uf[b] = a;
    w->size[a] += w->size[b];
    w->cvol[a] += w->cvol[b];
    for (int k = 0; k < 3; k++) w->cmom[3 * (size_t)a + k] += w->cmom[3 * (size_t)b + k];
    const double *V = w->m->cell_vol;
    int ba = w->big[a], bb = w->big[b];
    if (V[bb] > V[ba] || (V[bb] == V[ba] && bb < ba)) w->big[a] = bb;
    /* splice the two member rings */
    int t = w->next[a];
    w->next[a] = w->next[b];
    w->next[b] = t;
}

/* Parent Cartesian cell of c: lower and upper corner; -1 without one. */
static int parent_box(const Mesh *m, int c, double lo[3], double hi[3])
{
    const CartGrid *g = &m->cart;
    if (!m->cell_parent || g->n[0] <= 0) return -1;
    long p = m->cell_parent[c], nxy = (long)g->n[0] * g->n[1];
    if (p < 0 || p >= nxy * g->n[2]) return -1;
    long ijk[3] = {p % g->n[0], (p / g->n[0]) % g->n[1], p / nxy};
    for (int k = 0; k < 3; k++) {
        lo[k] = g->x[k][ijk[k]];
        hi[k] = g->x[k][ijk[k] + 1];
    }
    return 0;
}

/* Whether every point of face f has x_k = v (within PLANE_TOL of the
   coordinate's size and the cell width h). */
static int face_in_plane(const Mesh *m, int f, int k, double v, double h)
{
    double tol = PLANE_TOL * (fabs(v) + h);
    for (int i = m->face_off[f]; i < m->face_off[f + 1]; i++)
        if (fabs(m->points[3 * (size_t)m->face_idx[i] + k] - v) > tol) return 0;
    return 1;
}

static int face_on_box(const Mesh *m, int f, const double lo[3], const double hi[3])
{
    for (int k = 0; k < 3; k++) {
        double h = hi[k] - lo[k];
        if (face_in_plane(m, f, k, lo[k], h) || face_in_plane(m, f, k, hi[k], h)) return 1;
    }
    return 0;
}

static int below(const Work *w, int r)
{
    double vc = w->vcart[w->big[r]];
    return vc > 0 && w->cvol[r] <= w->o->threshold * vc;
}

/* Inner normal of cluster r (unnormalised): minus the outward area
   vectors of its immersed faces, or the fallback of the header. */
static void cluster_normal(Work *w, int r, double n[3])
{
    const Mesh *m = w->m;
    double lo[3], hi[3], cen[3] = {0, 0, 0};
    n[0] = n[1] = n[2] = 0;
    int c = r;
    do {
        if (parent_box(m, c, lo, hi) == 0)
            for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
                int f = m->cell_faces[i];
                if (f < m->ninternal || face_on_box(m, f, lo, hi)) continue;
                for (int k = 0; k < 3; k++) n[k] -= m->face_area[3 * (size_t)f + k];
            }
        for (int k = 0; k < 3; k++) cen[k] += m->cell_vol[c] * m->cell_centre[3 * (size_t)c + k];
        c = w->next[c];
    } while (c != r);
    for (int k = 0; k < 3; k++)
        if (w->empty[k]) n[k] = 0;
    if (geom_norm(n) > 0 || parent_box(m, w->big[r], lo, hi)) return;
    for (int k = 0; k < 3; k++) n[k] = w->empty[k] ? 0 : cen[k] / w->cvol[r] - 0.5 * (lo[k] + hi[k]);
}

/* Merge directions (axis, side: 1 = upper plane) in order of preference;
   returns their number. */
static int directions(Work *w, int r, int axis[6], int side[6])
{
    double n[3], h[3] = {1, 1, 1}, wt[3];
    cluster_normal(w, r, n);
    if (w->o->criterion == MERGE_NORMAL_H) mesh_cell_spacing(w->m, w->big[r], h);
    double nn = geom_norm(n);
    int ord[3] = {0, 1, 2}, nd = 0;
    for (int k = 0; k < 3; k++) wt[k] = fabs(n[k] * h[k]);
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && wt[ord[j]] > wt[ord[j - 1]]; j--) {
            int t = ord[j];
            ord[j] = ord[j - 1];
            ord[j - 1] = t;
        }
    for (int i = 0; i < 3; i++) {
        int k = ord[i];
        if (w->empty[k] || !(fabs(n[k]) > ZERO_NORMAL * nn)) continue;
        axis[nd] = k;
        side[nd++] = n[k] > 0;
    }
    return nd;
}

static void add_cand(Work *w, int root, double area)
{
    for (int i = 0; i < w->ncand; i++)
        if (w->cand[i].root == root) {
            w->cand[i].area += area;
            return;
        }
    if (w->ncand == w->cand_cap) {
        w->cand_cap = w->cand_cap ? 2 * w->cand_cap : 16;
        w->cand = mem_realloc(w->cand, sizeof(Cand) * (size_t)w->cand_cap);
    }
    w->cand[w->ncand++] = (Cand){root, area};
}

/* Collects the clusters across internal faces of cluster r's members that
   lie in the parent plane (axis, side); axis < 0 takes every face. */
static void collect(Work *w, int r, int axis, int side)
{
    const Mesh *m = w->m;
    double lo[3], hi[3];
    w->ncand = 0;
    int c = r;
    do {
        int hasbox = parent_box(m, c, lo, hi) == 0;
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1] && (hasbox || axis < 0); i++) {
            int f = m->cell_faces[i];
            if (f >= m->ninternal) continue;
            int o = m->owner[f] == c ? m->neighbour[f] : m->owner[f];
            int ro = find(w, o);
            if (ro == find(w, r)) continue;
            if (axis >= 0 && !face_in_plane(m, f, axis, side ? hi[axis] : lo[axis], hi[axis] - lo[axis]))
                continue;
            add_cand(w, ro, geom_norm(m->face_area + 3 * (size_t)f));
        }
        c = w->next[c];
    } while (c != r);
}

/* Appends the candidates of w->cand not yet listed to w->order, largest
   shared area first (then lower root); slaves only when allow_slave. */
static void rank(Work *w, int allow_slave)
{
    for (;;) {
        int best = -1;
        double barea = 0;
        for (int i = 0; i < w->ncand; i++) {
            const Cand *k = &w->cand[i];
            if (!allow_slave && below(w, k->root)) continue;
            int listed = 0;
            for (int j = 0; j < w->norder && !listed; j++) listed = w->order[j] == k->root;
            if (listed) continue;
            if (best < 0 || k->area > barea || (k->area == barea && k->root < best)) {
                best = k->root;
                barea = k->area;
            }
        }
        if (best < 0) return;
        if (w->norder == w->order_cap) {
            w->order_cap = w->order_cap ? 2 * w->order_cap : 16;
            w->order = mem_realloc(w->order, sizeof(int) * (size_t)w->order_cap);
        }
        w->order[w->norder++] = best;
    }
}

/* Whether the union of clusters r and t is a sound cell: every face's
   pyramid on the union's centroid positive, i.e. the centroid on the
   inner side of every face (OpenFOAM's face-pyramid check; a non-convex
   union can break it).  Empty faces are left out: a merged 2-D cell gets
   one joined empty face per side (assemble), whose pyramid is positive. */
static int sound_union(Work *w, int r, int t)
{
    const Mesh *m = w->m;
    double V = w->cvol[r] + w->cvol[t], C[3];
    for (int k = 0; k < 3; k++) C[k] = (w->cmom[3 * (size_t)r + k] + w->cmom[3 * (size_t)t + k]) / V;
    for (int pass = 0; pass < 2; pass++) {
        int start = pass ? t : r, c = start;
        do {
            for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
                int f = m->cell_faces[i], own = m->owner[f] == c;
                if (f < m->ninternal) {
                    int ro = find(w, own ? m->neighbour[f] : m->owner[f]);
                    if (ro == r || ro == t) continue;
                } else {
                    int p = mesh_face_patch(m, f);
                    if (p >= 0 && w->empty_patch[p]) continue;
                }
                const double *S = m->face_area + 3 * (size_t)f, *Cf = m->face_centre + 3 * (size_t)f;
                double d[3] = {Cf[0] - C[0], Cf[1] - C[1], Cf[2] - C[2]};
                if (!((own ? 1 : -1) * geom_dot(d, S) > 0)) return 0;
            }
            c = w->next[c];
        } while (c != start);
    }
    return 1;
}

/* The master cluster root for slave cluster r, or -1.  Candidates come
   in four groups: non-slaves in the merge directions, then slaves there,
   then any other neighbour, non-slaves first.  The first candidate, in
   that order, whose union with r is sound wins. */
static int choose(Work *w, int r)
{
    int axis[6], side[6];
    int nd = directions(w, r, axis, side);
    w->norder = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int d = 0; d < nd; d++) {
            collect(w, r, axis[d], side[d]);
            rank(w, pass);
        }
    collect(w, r, -1, 0);
    rank(w, 0);
    rank(w, 1);
    for (int i = 0; i < w->norder; i++)
        if (sound_union(w, r, w->order[i])) return w->order[i];
    return -1;
}

typedef struct SlaveKey {
    double ratio;
    int root;
} SlaveKey;

static int cmp_slave(const void *a, const void *b)
{
    const SlaveKey *x = a, *y = b;
    if (x->ratio != y->ratio) return x->ratio < y->ratio ? -1 : 1;
    return (x->root > y->root) - (x->root < y->root);
}

/* Runs the merge rounds; stuck[r] = 1 for roots that found no master in
   the last round they were examined in.  Returns the rounds that merged. */
static int merge_rounds(Work *w, char *stuck)
{
    int nc = w->m->ncells, niter = 0;
    SlaveKey *sl = MEM_NEW(SlaveKey, (size_t)nc);
    while (niter < w->o->max_iter) {
        int ns = 0, nmerge = 0;
        for (int c = 0; c < nc; c++)
            if (find(w, c) == c && below(w, c)) sl[ns++] = (SlaveKey){w->cvol[c] / w->vcart[w->big[c]], c};
        qsort(sl, (size_t)ns, sizeof *sl, cmp_slave);
        for (int i = 0; i < ns; i++) {
            int r = sl[i].root;
            if (find(w, r) != r || !below(w, r)) continue;   /* grown by an earlier pick */
            int t = choose(w, r);
            stuck[r] = t < 0;
            if (t < 0) continue;
            unite(w, r, t);
            stuck[find(w, r)] = 0;
            nmerge++;
        }
        if (!nmerge) break;
        niter++;
    }
    free(sl);
    return niter;
}

/* The input's cell faces and geometry, computed into a shallow copy so
   in stays untouched. */
static void input_geometry(const Mesh *in, Mesh *g)
{
    *g = *in;
    g->face_area = g->face_centre = g->cell_vol = g->cell_centre = NULL;
    g->cell_off = g->cell_faces = NULL;
    mesh_cell_faces(g);
    mesh_geometry(g);
}

static void free_input_geometry(Mesh *g)
{
    free(g->face_area);
    free(g->face_centre);
    free(g->cell_vol);
    free(g->cell_centre);
    free(g->cell_off);
    free(g->cell_faces);
}

static void work_init(Work *w, const Mesh *m, const MergeOpts *o)
{
    int nc = m->ncells;
    memset(w, 0, sizeof *w);
    w->m = m;
    w->o = o;
    quality_empty_dirs(m, w->empty);
    w->vcart = MEM_NEW(double, (size_t)nc);
    w->uf = MEM_NEW(int, (size_t)nc);
    w->size = MEM_NEW(int, (size_t)nc);
    w->next = MEM_NEW(int, (size_t)nc);
    w->cvol = MEM_NEW(double, (size_t)nc);
    w->cmom = MEM_NEW(double, 3 * (size_t)nc);
    w->big = MEM_NEW(int, (size_t)nc);
    w->empty_patch = MEM_NEW(char, (size_t)m->npatches);
    for (int p = 0; p < m->npatches; p++) w->empty_patch[p] = !strcmp(m->patches[p].type, "empty");
    for (int c = 0; c < nc; c++) {
        double h[3];
        w->vcart[c] = mesh_cell_spacing(m, c, h) == 0 ? h[0] * h[1] * h[2] : 0;
        w->uf[c] = w->next[c] = w->big[c] = c;
        w->size[c] = 1;
        w->cvol[c] = m->cell_vol[c];
        for (int k = 0; k < 3; k++) w->cmom[3 * (size_t)c + k] = m->cell_vol[c] * m->cell_centre[3 * (size_t)c + k];
    }
}

static void work_free(Work *w)
{
    free(w->vcart);
    free(w->uf);
    free(w->size);
    free(w->next);
    free(w->cvol);
    free(w->cmom);
    free(w->big);
    free(w->empty_patch);
    free(w->cand);
    free(w->order);
}

static void copy_cart(const CartGrid *a, CartGrid *b)
{
    for (int k = 0; k < 3; k++) {
        b->n[k] = a->n[k];
        b->x[k] = NULL;
        if (a->x[k]) {
            b->x[k] = MEM_NEW(double, (size_t)a->n[k] + 1);
            memcpy(b->x[k], a->x[k], sizeof(double) * ((size_t)a->n[k] + 1));
        }
    }
}

/* ---- empty faces of merged cells ----
   A merged cell of a 2-D grid would keep one empty face per member on
   each side, but 2-D detection (OpenFOAM's and mesh_empty_axis) wants
   exactly two per cell.  So a cluster's empty faces in one plane (same
   patch) become one polygon: the union of the members' polygons, whose
   boundary is traced from the cluster's other faces.  Two faces of a
   closed oriented surface pass a shared edge in opposite directions, so
   the outline's directed edges are the reversed in-plane edges of those
   faces (oriented out of the cluster).  Every point of those edges stays
   on the outline, so the grid stays conforming.  When the edges do not
   form one simple loop (a cluster ringing a hole), the faces are kept. */

typedef struct IntVec {
    int *v;
    int n, cap;
} IntVec;

static void iv_push(IntVec *a, int x)
{
    if (a->n == a->cap) {
        a->cap = a->cap ? 2 * a->cap : 64;
        a->v = mem_realloc(a->v, sizeof(int) * (size_t)a->cap);
    }
    a->v[a->n++] = x;
}

typedef struct Joined {
    int *face;        /* per face: -1 kept, -2 dropped, else outline index (the group's first face) */
    IntVec off, pts;  /* outlines: points pts[off[i]..off[i+1]-1] */
    IntVec grp, ea, eb, mark;   /* scratch */
} Joined;

static int is_empty_face(const Mesh *m, int f)
{
    int p = mesh_face_patch(m, f);
    return p >= 0 && !strcmp(m->patches[p].type, "empty");
}

static int point_on(const Mesh *m, int pt, int k, double v, double tol)
{
    return fabs(m->points[3 * (size_t)pt + k] - v) <= tol;
}

/* Plane of face f: axis of the largest area component, coordinate of its
   first point; -1 when some point is off that plane. */
static int face_plane(const Mesh *m, int f, double tol_rel, double *v)
{
    const double *S = m->face_area + 3 * (size_t)f;
    int k = fabs(S[0]) >= fabs(S[1]) ? 0 : 1;
    if (fabs(S[2]) > fabs(S[k])) k = 2;
    *v = m->points[3 * (size_t)m->face_idx[m->face_off[f]] + k];
    double tol = tol_rel * (fabs(*v) + 1);
    for (int i = m->face_off[f]; i < m->face_off[f + 1]; i++)
        if (!point_on(m, m->face_idx[i], k, *v, tol)) return -1;
    return k;
}

/* Chains the directed edges ea[i] -> eb[i] into one simple loop appended
   to j->pts; 0, or -1 when they do not form exactly one. */
static int chain(Joined *j)
{
    int n = j->ea.n, *ea = j->ea.v, *eb = j->eb.v;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++)
            if (ea[a] == ea[b]) return -1;
    int start = ea[0], cur = eb[0], len = 1, base = j->pts.n;
    iv_push(&j->pts, start);
    while (cur != start && len < n) {
        int next = -1;
        for (int a = 0; a < n && next < 0; a++)
            if (ea[a] == cur) next = a;
        if (next < 0) break;
        iv_push(&j->pts, cur);
        cur = eb[next];
        len++;
    }
    if (cur != start || len != n || n < 3) {
        j->pts.n = base;
        return -1;
    }
    iv_push(&j->off, j->pts.n);
    return 0;
}

/* Outline of cluster r in plane (k, v) of the faces grp (marked in
   j->mark with `tag`); on success the group's faces are joined. */
static void join_group(Work *w, Joined *j, int r, int k, double v, double tol)
{
    const Mesh *m = w->m;
    j->ea.n = j->eb.n = 0;
    int c = r;
    do {
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
            int f = m->cell_faces[i];
            if (j->mark.v[f]) continue;
            int own = m->owner[f] == c;
            if (f < m->ninternal && find(w, own ? m->neighbour[f] : m->owner[f]) == r) continue;
            const int *p = m->face_idx + m->face_off[f];
            int n = m->face_off[f + 1] - m->face_off[f];
            for (int q = 0; q < n; q++) {
                int a = own ? p[q] : p[n - 1 - q], b = own ? p[(q + 1) % n] : p[(2 * n - 2 - q) % n];
                if (point_on(m, a, k, v, tol) && point_on(m, b, k, v, tol)) {
                    iv_push(&j->ea, b);
                    iv_push(&j->eb, a);
                }
            }
        }
        c = w->next[c];
    } while (c != r);
    if (chain(j)) return;
    int lead = j->grp.v[0];
    for (int i = 1; i < j->grp.n; i++)
        if (j->grp.v[i] < lead) lead = j->grp.v[i];
    for (int i = 0; i < j->grp.n; i++) j->face[j->grp.v[i]] = -2;
    j->face[lead] = j->off.n - 2;
}

/* Groups cluster r's empty faces by patch and plane and joins each group
   of two or more. */
static void join_cluster(Work *w, Joined *j, int r)
{
    const Mesh *m = w->m;
    IntVec all = {0};
    int c = r;
    do {
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++)
            if (m->cell_faces[i] >= m->ninternal && is_empty_face(m, m->cell_faces[i])) iv_push(&all, m->cell_faces[i]);
        c = w->next[c];
    } while (c != r);
    for (int i = 0; i < all.n; i++) {
        int f0 = all.v[i];
        double v0, v;
        int k = f0 >= 0 ? face_plane(m, f0, PLANE_TOL, &v0) : -1;
        if (k < 0) continue;
        double tol = PLANE_TOL * (fabs(v0) + 1);
        j->grp.n = 0;
        for (int q = i; q < all.n; q++) {
            int f = all.v[q];
            if (f >= 0 && mesh_face_patch(m, f) == mesh_face_patch(m, f0) && face_plane(m, f, PLANE_TOL, &v) == k &&
                fabs(v - v0) <= tol) {
                iv_push(&j->grp, f);
                all.v[q] = -1;
            }
        }
        if (j->grp.n < 2) continue;
        for (int q = 0; q < j->grp.n; q++) j->mark.v[j->grp.v[q]] = 1;
        join_group(w, j, r, k, v0, tol);
        for (int q = 0; q < j->grp.n; q++) j->mark.v[j->grp.v[q]] = 0;
    }
    free(all.v);
}

static void join_empty(Work *w, Joined *j)
{
    const Mesh *m = w->m;
    memset(j, 0, sizeof *j);
    j->face = MEM_NEW(int, (size_t)m->nfaces);
    for (int f = 0; f < m->nfaces; f++) j->face[f] = -1;
    j->mark.v = MEM_NEW(int, (size_t)m->nfaces);
    j->mark.n = j->mark.cap = m->nfaces;
    iv_push(&j->off, 0);
    int any = 0;
    for (int p = 0; p < m->npatches; p++) any |= !strcmp(m->patches[p].type, "empty");
    for (int c = 0; c < m->ncells && any; c++)
        if (find(w, c) == c && w->size[c] > 1) join_cluster(w, j, c);
}

static void joined_free(Joined *j)
{
    free(j->face);
    free(j->off.v);
    free(j->pts.v);
    free(j->grp.v);
    free(j->ea.v);
    free(j->eb.v);
    free(j->mark.v);
}

/* Assembles the union polyhedra of the clusters into out; newid[c] is
   the output cell of input cell c. */
static int assemble(Work *w, const int *newid, Mesh *out, Err *e)
{
    const Mesh *m = w->m;
    Joined j;
    join_empty(w, &j);
    MeshBuild b;
    meshbuild_init(&b);
    meshbuild_reserve(&b, (size_t)m->npoints, (size_t)m->nfaces, (size_t)m->face_off[m->nfaces]);
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        meshbuild_patch(&b, pa->name, pa->type, pa->neighbour, pa->groups);
    }
    for (int i = 0; i < m->npoints; i++) meshbuild_point(&b, m->points + 3 * (size_t)i);
    int nb = m->nfaces - m->ninternal;
    int *added = MEM_NEW(int, (size_t)nb);   /* added index of each boundary face, -1 dropped */
    int p = 0;
    for (int f = 0; f < m->nfaces; f++) {
        const int *pts = m->face_idx + m->face_off[f];
        int n = m->face_off[f + 1] - m->face_off[f], o = newid[m->owner[f]];
        if (f < m->ninternal) {
            int nb2 = newid[m->neighbour[f]];
            if (nb2 != o) meshbuild_face(&b, pts, n, o, nb2, -1);
            continue;
        }
        while (p + 1 < m->npatches && f >= m->patches[p].start + m->patches[p].size) p++;
        int jf = j.face[f];
        if (jf >= 0) {
            pts = j.pts.v + j.off.v[jf];
            n = j.off.v[jf + 1] - j.off.v[jf];
        }
        added[f - m->ninternal] = jf == -2 ? -1 : meshbuild_face(&b, pts, n, o, -1, p);
    }
    joined_free(&j);
    int *fmap = MEM_NEW(int, (size_t)b.nfaces);
    mesh_init(out);
    int rc = meshbuild_finish(&b, out, fmap, NULL, e);
    if (rc == 0 && m->wall_normal) {
        out->wall_normal = MEM_NEW(double, 3 * (size_t)(out->nfaces - out->ninternal));
        for (int i = 0; i < nb; i++)
            if (added[i] >= 0)
                memcpy(out->wall_normal + 3 * (size_t)(fmap[added[i]] - out->ninternal),
                       m->wall_normal + 3 * (size_t)i, 3 * sizeof(double));
    }
    free(added);
    free(fmap);
    return rc;
}

static double max_aspect(const Mesh *m)
{
    int empty[3];
    double amax = 0;
    quality_empty_dirs(m, empty);
    for (int c = 0; c < m->ncells; c++) {
        double open, ar;
        quality_cell(m, c, empty, &open, &ar);
        if (ar > amax) amax = ar;
    }
    return amax;
}

static void stats_before(const Work *w, MergeStats *st)
{
    const Mesh *m = w->m;
    st->ncells_in = m->ncells;
    st->ratio_min_before = HUGE_VAL;
    for (int c = 0; c < m->ncells; c++) {
        st->vol_before += m->cell_vol[c];
        if (w->vcart[c] > 0) {
            double r = m->cell_vol[c] / w->vcart[c];
            if (r < st->ratio_min_before) st->ratio_min_before = r;
            if (r <= w->o->threshold) st->nslaves++;
        }
    }
    st->aspect_max_before = max_aspect(m);
}

/* Statistics of out; root[C] is a member root of output cell C. */
static void stats_after(Work *w, const int *root, const char *stuck, Mesh *out, MergeStats *st)
{
    st->ncells_out = out->ncells;
    st->ratio_min_after = HUGE_VAL;
    st->ratio_min_cell = -1;
    st->unresolved = MEM_NEW(int, (size_t)out->ncells);
    st->reason = MEM_NEW(int, (size_t)out->ncells);
    for (int C = 0; C < out->ncells; C++) {
        int r = root[C];
        st->vol_after += out->cell_vol[C];
        if (w->size[r] > 1) st->nclusters++;
        double vc = w->vcart[w->big[r]];
        if (vc > 0 && out->cell_vol[C] / vc < st->ratio_min_after) {
            st->ratio_min_after = out->cell_vol[C] / vc;
            st->ratio_min_cell = C;
        }
        if (below(w, r)) {
            st->unresolved[st->nunresolved] = C;
            st->reason[st->nunresolved++] = stuck[r] ? MERGE_NO_NEIGHBOUR : MERGE_ITER_LIMIT;
        }
    }
    st->aspect_max_after = max_aspect(out);
}

static int check_input(const Mesh *in, const MergeOpts *o, Err *e)
{
    if (!(o->threshold > 0 && o->threshold <= 1))
        return err_set(e, NULL, 0, "merge: threshold %g out of range (0, 1]", o->threshold);
    if (o->criterion != MERGE_NORMAL && o->criterion != MERGE_NORMAL_H)
        return err_set(e, NULL, 0, "merge: unknown criterion %d", o->criterion);
    if (o->max_iter < 0) return err_set(e, NULL, 0, "merge: maxIter %d is negative", o->max_iter);
    if (!in->cell_parent || in->cart.n[0] <= 0)
        return err_set(e, NULL, 0,
                       "merge: the grid has no Cartesian parents (cellParent, cartesianGrid); "
                       "merge the output of cutCells");
    if (in->ncells <= 0) return err_set(e, NULL, 0, "merge: the grid has no cells");
    /* the walks below trust the polyMesh invariants */
    Err ec;
    if (mesh_check(in, &ec)) return err_set(e, NULL, 0, "merge: %s", ec.msg);
    return 0;
}

int merge_mesh(const Mesh *in, const MergeOpts *o, Mesh *out, MergeStats *st, Err *e)
{
    memset(st, 0, sizeof *st);
    mesh_init(out);
    if (check_input(in, o, e)) return -1;
    Mesh g;
    Work w;
    input_geometry(in, &g);
    work_init(&w, &g, o);
    stats_before(&w, st);
    int nc = g.ncells;
    char *stuck = MEM_NEW(char, (size_t)nc);
    st->niter = merge_rounds(&w, stuck);

    int *newid = MEM_NEW(int, (size_t)nc), *root = MEM_NEW(int, (size_t)nc);
    for (int c = 0; c < nc; c++) newid[c] = -1;
    int nout = 0;
    for (int c = 0; c < nc; c++) {
        int r = find(&w, c);
        if (newid[r] < 0) {
            root[nout] = r;
            newid[r] = nout++;
        }
        newid[c] = newid[r];
    }
    int rc = assemble(&w, newid, out, e);
    if (rc == 0) {
        copy_cart(&in->cart, &out->cart);
        out->cell_parent = MEM_NEW(int, (size_t)nout);
        for (int C = 0; C < nout; C++) out->cell_parent[C] = in->cell_parent[w.big[root[C]]];
        out->merge_map = newid;
        out->nmerge_old = nc;
        newid = NULL;
        mesh_cell_faces(out);
        mesh_geometry(out);
        stats_after(&w, root, stuck, out, st);
    }
    free(newid);
    free(root);
    free(stuck);
    work_free(&w);
    free_input_geometry(&g);
    return rc;
}
