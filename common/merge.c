/*
** merge.c: merging of small cut cells (merge.h; spec granular-model.md
** §2.5, thesis §3.3.2).
**
** Design.  Clusters are sets in a union-find forest over the input cells
** (path halving, union by size); each root holds the cluster's volume,
** first moment (sum of V x centroid) and largest member, and a circular
** linked list (`next`) threads the members so a cluster's faces can be
** walked without building lists.  (Cells' own volumes are kept in the
** working copy's cell_vol; cmom holds the first moments, and the
** OpenFOAM centres of clusters and cells are cached in fcc and cc0.)
** Merging runs in rounds.  A round takes
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
**   union's centre (OpenFOAM's, as checkMesh computes it) positive (OpenFOAM's face-pyramid check; a
**   non-convex union can put the centroid outside a face).  No sound
**   candidate: the cluster stays as it is and is reported.  (Preferring
**   unions with skewness <= 4 was tried and dropped: it steered slaves
**   away from their natural masters into clusters that later had no
**   sound neighbour, 24 unresolved cells in a 96^3 sphere grid against
**   none, for 6% fewer skewed faces.)  Skewness is dealt with after the
**   volume rounds instead, by the quality pass ("quality pass" below),
**   and what it cannot mend is undone by the repair ("repair" below).
**
** Cost.  Cut cells are a thin layer of a large grid, so the work avoids
** touching the regular cells' data: a cell that is its whole parent
** Cartesian cell (is_regular) gets the box's volume and centroid, face
** geometry is computed on first use (face_geo), the statistics come from
** the clusters (no output geometry), and the output is assembled directly
** in polyMesh order (what meshbuild would give, without its copies):
** the input is in that order already, so the kept internal faces need a
** counting sort on the new owner and a sort on the neighbour inside each
** owner's short run only.
**
** Output.  The merged cell is the union polyhedron: internal faces with
** both cells in one cluster are dropped, every other face is kept with
** its points and orientation (reversed when the renumbering swaps owner
** and neighbour), except that a 2-D cluster's empty faces on each side
** are joined into one polygon (see "empty faces" below).  Output cells
** are numbered in order of their smallest member, so the numbering stays
** close to Cartesian order.  cell_parent is the largest member's,
** boundary_normal follows the boundary faces (they keep their order), points
** no face uses any more are dropped (the others keep their order),
** merge_map records each input cell's output cell, and the cut-cell
** data contract (cartcells.h) is the input's with the clusters renamed:
** the member cell_parent names is master, the others slaves.  Everything
** is linear in the mesh size except the picks, which walk the faces of
** slave clusters and their candidates only.
*/
#include "merge.h"
#include "cartcells.h"
#include "geom.h"
#include "mem.h"
#include "quality.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PLANE_TOL 1e-12   /* relative: a point on a parent plane */
#define ZERO_NORMAL 1e-12 /* relative: a normal component taken as 0 */

void merge_opts_default(MergeOpts *o)
{
    o->threshold = 0.5;
    o->criterion = MERGE_NORMAL;
    o->max_iter = 10;
    o->max_skewness = QUALITY_SKEW_HIGH;
    o->min_ratio = 0.01;
}

const DictKey merge_keys[] = {
    {"threshold", "0.5", "M_V: cells with V <= M_V x (parent Cartesian volume) are merged, in (0, 1]"},
    {"criterion", "normal", "merge axis: normal = argmax |n_i|, normalSpacing = argmax |n_i h_i|"},
    {"maxIter", "10", "rounds of re-merging clusters still below the bound, and of the quality pass (>= 0)"},
    {"maxSkewness", "4", "quality pass: clusters with a face skewness above this merge further (0 = off, >= 0)"},
    {"minRatio", "0.01", "a cell below this V / V_cart that no checkMesh-clean union takes merges into a sound one (0 = never, < threshold)"},
    {NULL, NULL, NULL}};

const char *const merge_criteria[] = {"normal", "normalSpacing", NULL};

static int bad_value(Err *e, const char *path, const Dict *d, const char *key, const char *what)
{
    const DictEntry *en = dict_find(d, key);
    return err_set(e, path, en ? en->line : 0, "%s", what);
}

/* The ranges: a threshold of 0 merges nothing, above 1 every cell. */
static int check_opts(const MergeOpts *o, const char *path, const Dict *d, Err *e)
{
    char msg[128];
    if (!(o->threshold > 0 && o->threshold <= 1)) {
        snprintf(msg, sizeof msg, "threshold must be in (0, 1], found %g", o->threshold);
        return bad_value(e, path, d, "threshold", msg);
    }
    if (o->max_iter < 0) {
        snprintf(msg, sizeof msg, "maxIter must be >= 0, found %d", o->max_iter);
        return bad_value(e, path, d, "maxIter", msg);
    }
    if (!(o->min_ratio >= 0 && o->min_ratio < o->threshold)) {
        snprintf(msg, sizeof msg, "minRatio must be in [0, threshold), found %g", o->min_ratio);
        return bad_value(e, path, d, "minRatio", msg);
    }
    if (!(o->max_skewness >= 0)) {
        snprintf(msg, sizeof msg, "maxSkewness must be >= 0, found %g", o->max_skewness);
        return bad_value(e, path, d, "maxSkewness", msg);
    }
    return 0;
}

int merge_read_opts(const char *path, MergeOpts *o, Err *e)
{
    merge_opts_default(o);
    Dict *d = dict_read(path, e);
    int rc = !d || dict_check_keys(d, merge_keys, e) ||
             dict_scalar_or(d, "threshold", o->threshold, &o->threshold, e) ||
             dict_choice_or(d, "criterion", merge_criteria, o->criterion, &o->criterion, e) ||
             dict_label_or(d, "maxIter", o->max_iter, &o->max_iter, e) ||
             dict_scalar_or(d, "maxSkewness", o->max_skewness, &o->max_skewness, e) ||
             dict_scalar_or(d, "minRatio", o->min_ratio, &o->min_ratio, e) || check_opts(o, path, d, e);
    dict_free(d);
    return rc ? -1 : 0;
}

const char *merge_reason_name(int reason)
{
    switch (reason) {
    case MERGE_OK: return "ok";
    case MERGE_NO_NEIGHBOUR: return "no neighbour to merge with (none, or none giving a sound cell)";
    case MERGE_ITER_LIMIT: return "still below the bound after maxIter rounds";
    case MERGE_SKEWNESS: return "a face skewness above maxSkewness that no merge lowers";
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
    const Mesh *m;          /* input with cell faces and lazy geometry (below) */
    Mesh *g;                /* the same, writable: its cell_vol, cell_faces */
    int *fslot;             /* per face: 1 + its slot in fgeo, 0 before first use */
    double *fgeo;           /* per slot: area vector and centroid (6) */
    size_t nslot, slot_cap;
    const MergeOpts *o;
    int empty[3];           /* empty (2-D) directions */
    double *vcart;          /* parent volume per cell, 0 without a parent */
    int *uf, *size, *next;  /* union-find forest, member ring */
    double *cvol;           /* cluster volume, at roots */
    double *cmom;           /* 3 per cell: sum of V x centroid, at roots */
    int *big;               /* largest member, at roots */
    char *empty_patch;      /* per patch: 1 for type empty */
    char *skip_patch;       /* per patch: 1 for empty and cyclic (not skew-checked) */
    char *reg;              /* per cell: 1 for a whole Cartesian cell */
    Cand *cand;
    int ncand, cand_cap;
    int *order;             /* candidate roots in order of preference */
    double *fcc;            /* 3 per cell: OpenFOAM centre of a cluster of 2+ cells, at roots, */
    char *fcc_ok;           /* valid where fcc_ok (unite and dissolve clear it) */
    double *cc0;            /* 3 per cell: OpenFOAM centre of the input cell, */
    char *cc0_ok;           /* valid where cc0_ok (computed on first use) */
    double *sc;             /* scratch: area vector and centre (6) per face of a union */
    signed char *sg;        /* and +1 where the face points out of it, -1 in */
    size_t sc_cap, sg_cap;
    int norder, order_cap;
    const char *keep;       /* per cell, or NULL: the repair keeps sound clusters holding one */
    int nkept;              /* unclean clusters it kept for them */
} Work;

/* The skewness a merge must stay below: maxSkewness less 1e-9 of it, so
   that a union that reaches the limit to round-off (4.000000000000007 in
   checkMesh's arithmetic, 3.999999999999999 in ours) is not left for
   checkMesh to call highly skewed. */
static double skew_limit(const MergeOpts *o)
{
    return o->max_skewness * (1 - 1e-9);
}

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
    w->fcc_ok[a] = 0;
}

/* Face f's area vector and centroid (6 values), computed on first use
   and stored compactly: the merge looks at the faces of cut cells and
   their neighbours only, so most of a large grid's faces are never
   touched, and arrays indexed by face would be faulted in whole anyway
   (their pages hold thousands of faces).  The pointer is valid until the
   next call. */
static const double *face_geo(Work *w, int f)
{
    if (w->fslot[f]) return w->fgeo + 6 * (size_t)(w->fslot[f] - 1);
    const Mesh *m = w->m;
    mem_grow((void **)&w->fgeo, &w->slot_cap, 6 * (w->nslot + 1), sizeof(double));
    double *g = w->fgeo + 6 * w->nslot++;
    w->fslot[f] = (int)w->nslot;
    quality_foam_face(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], g, g + 3);
    return g;
}

/* Skewness of face f (quality.h's, OpenFOAM's) between cell centres cown
   and cnei, or of a boundary face when cnei is NULL. */
static double face_skew(Work *w, int f, const double *cown, const double *cnei)
{
    const Mesh *m = w->m;
    double SC[6];
    memcpy(SC, face_geo(w, f), sizeof SC);
    return quality_face_skew(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], SC,
                             SC + 3, cown, cnei);
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
    double lo[3], hi[3];
    const double *cen = w->cmom + 3 * (size_t)r;   /* sum of V x centroid */
    n[0] = n[1] = n[2] = 0;
    int c = r;
    do {
        if (parent_box(m, c, lo, hi) == 0)
            for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
                int f = m->cell_faces[i];
                if (f < m->ninternal || face_on_box(m, f, lo, hi)) continue;
                const double *S = face_geo(w, f);
                for (int k = 0; k < 3; k++) n[k] -= S[k];
            }
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
            add_cand(w, ro, geom_norm(face_geo(w, f)));
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

/* ---- unions of clusters ----
   A union of up to SET_MAX clusters is judged on OpenFOAM's geometry
   (quality.h): its centre is OpenFOAM's cell centre of its faces, those
   of the members except the ones shared inside it (the faces the merged
   cell will have; a 2-D union keeps its members' empty faces, where the
   output joins them into one polygon per side: the same pyramid sums
   whenever the joined polygon is star-shaped about its point average),
   and every face is measured as checkMesh measures it.  The centre of a
   cluster is kept at its root until the cluster changes (fcc), the
   centre of an input cell for good (cc0). */

enum { SET_MAX = 3 };

typedef struct Set {
    int root[SET_MAX], n;
} Set;

static int in_set(const Set *s, int r)
{
    for (int i = 0; i < s->n; i++)
        if (s->root[i] == r) return 1;
    return 0;
}

static void set_make(Set *s, int n, const int *roots)
{
    s->n = n;
    for (int i = 0; i < n; i++) s->root[i] = roots[i];
}

/* Appends face f (its area vector and centre) to the scratch of a
   union's faces, with its sign. */
static void push_face(Work *w, size_t *nf, int f, int out)
{
    mem_grow((void **)&w->sc, &w->sc_cap, 6 * (*nf + 1), sizeof(double));
    mem_grow((void **)&w->sg, &w->sg_cap, *nf + 1, 1);
    memcpy(w->sc + 6 * *nf, face_geo(w, f), 6 * sizeof(double));
    w->sg[(*nf)++] = (signed char)(out ? 1 : -1);
}

/* OpenFOAM's centre of input cell c alone (the cut grid's): a whole
   Cartesian cell's is its box centre (to round-off), without its faces. */
static const double *cell_centre0(Work *w, int c)
{
    const Mesh *m = w->m;
    double *C = w->cc0 + 3 * (size_t)c;
    if (w->cc0_ok[c]) return C;
    w->cc0_ok[c] = 1;
    double lo[3], hi[3];
    if (w->reg[c] && parent_box(m, c, lo, hi) == 0) {
        for (int k = 0; k < 3; k++) C[k] = 0.5 * (lo[k] + hi[k]);
        return C;
    }
    size_t nf = 0;
    for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++)
        push_face(w, &nf, m->cell_faces[q], m->owner[m->cell_faces[q]] == c);
    quality_foam_cell((int)nf, w->sc, w->sg, C);
    return C;
}

/* OpenFOAM's centre of the union s from its faces. */
static void union_centre(Work *w, const Set *s, double C[3])
{
    const Mesh *m = w->m;
    if (s->n == 1 && w->size[s->root[0]] == 1) {
        memcpy(C, cell_centre0(w, s->root[0]), 3 * sizeof(double));
        return;
    }
    size_t nf = 0;
    for (int i = 0; i < s->n; i++) {
        int c = s->root[i];
        do {
            for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
                int f = m->cell_faces[q], own = m->owner[f] == c;
                if (f < m->ninternal && in_set(s, find(w, own ? m->neighbour[f] : m->owner[f]))) continue;
                push_face(w, &nf, f, own);
            }
            c = w->next[c];
        } while (c != s->root[i]);
    }
    quality_foam_cell((int)nf, w->sc, w->sg, C);
}

/* OpenFOAM's centre of cluster r (a root). */
static const double *root_centre(Work *w, int r)
{
    if (w->size[r] == 1) return cell_centre0(w, r);
    if (!w->fcc_ok[r]) {
        union_centre(w, &(Set){{r}, 1}, w->fcc + 3 * (size_t)r);
        w->fcc_ok[r] = 1;
    }
    return w->fcc + 3 * (size_t)r;
}

/* Skewness of face f in the cut grid (between its input cells). */
static double cut_skew(Work *w, int f)
{
    const Mesh *m = w->m;
    const double *Co = cell_centre0(w, m->owner[f]);
    double C[3];
    memcpy(C, Co, sizeof C);
    return face_skew(w, f, C, f < m->ninternal ? cell_centre0(w, m->neighbour[f]) : NULL);
}

/* What set_eval checks besides the skewness. */
enum {
    EV_SOUND = 1,   /* every face pyramid on the centre positive (checkMesh's face pyramids) */
    EV_CLEAN = 2,   /* and nothing checkMesh fails that the cut grid passed: no face with
                       skewness above the limit and above its cut-grid value, no internal
                       face at 90 degrees or more, aspect ratio at most 1000 */
    EV_NOSKEW = 4   /* the checks only: no skewness */
};

#define ORTHO_MIN 1e-12   /* cos of the non-orthogonality: checkMesh fails <= 1e-15 */

/* Maximum skewness over the faces of the union s, or -1 when a check of
   `what` fails.  Empty faces are left out (a merged 2-D cell's joined
   empty face has its centre over the cell's, skewness 0), and so are
   faces of cyclic patches (measured against a partner cell the merge does
   not see).  Stops at the first face reaching cut (the caller's best so
   far), returning a value >= cut. */
static double set_eval(Work *w, const Set *s, int what, double cut)
{
    const Mesh *m = w->m;
    double smax = 0, C[3], mag[3] = {0, 0, 0}, V = 0, limit = skew_limit(w->o);
    if (s->n == 1) memcpy(C, root_centre(w, s->root[0]), sizeof C);
    else union_centre(w, s, C);
    for (int i = 0; i < s->n; i++) {
        int c = s->root[i];
        V += w->cvol[c];
        do {
            for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
                int f = m->cell_faces[q], own = m->owner[f] == c, ro = -1;
                if (f < m->ninternal) {
                    ro = find(w, own ? m->neighbour[f] : m->owner[f]);
                    if (in_set(s, ro)) continue;
                }
                double SC[6];
                memcpy(SC, face_geo(w, f), sizeof SC);
                for (int k = 0; k < 3; k++) mag[k] += fabs(SC[k]);
                if (f >= m->ninternal) {
                    int p = mesh_face_patch(m, f);
                    if (p >= 0 && w->skip_patch[p]) continue;
                }
                double d[3] = {SC[3] - C[0], SC[4] - C[1], SC[5] - C[2]}, sgn = own ? 1 : -1;
                if (what & (EV_SOUND | EV_CLEAN) && !(sgn * geom_dot(d, SC) > 0)) return -1;
                double Co[3];
                if (ro >= 0) {
                    memcpy(Co, root_centre(w, ro), sizeof Co);
                    for (int k = 0; k < 3; k++) d[k] = sgn * (Co[k] - C[k]);
                    if (what & EV_CLEAN && !(quality_ortho(d, SC) > ORTHO_MIN)) return -1;
                }
                if (what & EV_NOSKEW) continue;
                double sk = ro < 0 ? face_skew(w, f, C, NULL) : own ? face_skew(w, f, C, Co) : face_skew(w, f, Co, C);
                if (what & EV_CLEAN && limit > 0 && sk > limit && sk > cut_skew(w, f)) return -1;
                if (sk > smax) smax = sk;
                if (smax >= cut) return smax;
            }
            c = w->next[c];
        } while (c != s->root[i]);
    }
    if (what & EV_CLEAN && quality_aspect(mag, V, w->empty) > QUALITY_ASPECT_HIGH) return -1;
    return smax;
}

/* Whether the union of clusters r and t is a sound cell: every face's
   pyramid on the union's centre positive, i.e. the centre on the inner
   side of every face (OpenFOAM's face-pyramid check; a non-convex union
   can break it). */
static int sound_union(Work *w, int r, int t)
{
    Set s;
    set_make(&s, 2, (int[2]){r, t});
    return set_eval(w, &s, EV_SOUND | EV_NOSKEW, HUGE_VAL) >= 0;
}

/* The master cluster root for slave cluster r, or -1.  Candidates come
   in four groups: non-slaves in the merge directions, then slaves there,
   then any other neighbour, non-slaves first.  The first candidate, in
   that order, whose union with r is sound wins. */
static void candidates(Work *w, int r)
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
}

static void best_triple(Work *w, int r, const int *first, int n1, int what, double stop, int bounded, Set *bs,
                        double *best);

/* The clusters cluster r merges with into *bs (r first): the first sound
   pair in candidate order or, when no pair is sound, the sound triple of
   r, a candidate and a neighbour of the two with the lowest maximum skew.
   Around a chamfered 3-D edge a small piece often touches only cells
   whose union with it puts the centre behind one of its faces, and a
   third cell brings the centre back (24 of 29 such pieces stayed unmerged
   in tutorials/granular/rotatedChannel3D without it).  Returns whether
   there is one. */
static int choose(Work *w, int r, Set *bs)
{
    candidates(w, r);
    for (int i = 0; i < w->norder; i++)
        if (sound_union(w, r, w->order[i])) {
            set_make(bs, 2, (int[2]){r, w->order[i]});
            return 1;
        }
    int n1 = w->norder;
    int *first = mem_alloc(sizeof(int) * ((size_t)n1 + 1));
    memcpy(first, w->order, sizeof(int) * (size_t)n1);
    double best = HUGE_VAL;
    best_triple(w, r, first, n1, EV_SOUND, -1, 0, bs, &best);
    free(first);
    return best < HUGE_VAL;
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
            Set bs = {.n = 0};
            stuck[r] = !choose(w, r, &bs);
            if (stuck[r]) continue;
            for (int k = 1; k < bs.n; k++) unite(w, bs.root[0], bs.root[k]);
            stuck[find(w, r)] = 0;
            nmerge += bs.n - 1;
        }
        if (!nmerge) break;
        niter++;
    }
    free(sl);
    return niter;
}

/* ---- quality pass ----
   After the volume rounds a cluster can still have a face whose OpenFOAM
   skewness exceeds maxSkewness: a small cut piece's boundary face lies
   far, along the face, from the merged cell's centre.  Skewness of a
   face depends only on the centres of its two cells (one for a boundary
   face), and a cell's centre only on its own faces, so merging a set of
   clusters changes exactly the faces of the union: the pass evaluates
   those (set_eval, with the union's OpenFOAM centre) for the union of the
   worst cluster r with each face neighbour t, and takes the sound union
   (every face pyramid on its centre positive, as sound_union) with the
   smallest maximum.  When no such union lowers r's maximum it also tries
   each t with each neighbour u of r + t (around a curved wall the union
   with one neighbour often puts the centre behind a wall face, and a
   third cluster brings it back).  The merge is made when it lowers r's
   maximum.  (Trying the triples whenever the best pair stayed above the
   limit was worse: the larger clusters left 72 cells above it in a 64^3
   sphere grid, against 6.)  What the pass leaves above the limit the
   repair undoes (below). */

static double cluster_skew(Work *w, int r)
{
    return set_eval(w, &(Set){{r}, 1}, 0, HUGE_VAL);
}

/* Adds the neighbour clusters of the union s to w->cand. */
static void collect_set(Work *w, const Set *s)
{
    const Mesh *m = w->m;
    w->ncand = 0;
    for (int i = 0; i < s->n; i++) {
        int c = s->root[i];
        do {
            for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
                int f = m->cell_faces[q];
                if (f >= m->ninternal) continue;
                int ro = find(w, m->owner[f] == c ? m->neighbour[f] : m->owner[f]);
                if (!in_set(s, ro)) add_cand(w, ro, 0);
            }
            c = w->next[c];
        } while (c != s->root[i]);
    }
}

/* The union of cluster r, one of its neighbours first[0..n1) and a
   neighbour of those two whose set_eval (mode what) is lowest, into *bs
   and *best; neighbours are tried while *best is not below stop, each
   evaluation bounded by *best when bounded (choose_skew, choose_clean). */
static void best_triple(Work *w, int r, const int *first, int n1, int what, double stop, int bounded, Set *bs,
                        double *best)
{
    Set s;
    for (int i = 0; i < n1 && !(*best < stop); i++) {
        int three[3] = {r, first[i], -1};
        set_make(&s, 2, three);
        collect_set(w, &s);
        for (int k = 0; k < w->ncand; k++) {
            three[2] = w->cand[k].root;
            set_make(&s, 3, three);
            double sk = set_eval(w, &s, what, bounded ? *best : HUGE_VAL);
            if (sk >= 0 && sk < *best) *best = sk, *bs = s;
        }
    }
}

/* The union of cluster r with a neighbour whose maximum face skewness is
   lowest among the sound ones (*best; HUGE_VAL when none), or, when no
   such pair gets below cur (r's own maximum), the union with two; ties go
   to the first found, in the order the neighbours are met. */
static int choose_skew(Work *w, int r, double cur, Set *bs, double *best)
{
    Set s;
    set_make(&s, 1, &r);
    collect_set(w, &s);
    int n1 = w->ncand;
    int *first = mem_alloc(sizeof(int) * ((size_t)n1 + 1));
    for (int i = 0; i < n1; i++) first[i] = w->cand[i].root;
    *best = HUGE_VAL;
    for (int i = 0; i < n1; i++) {
        int two[2] = {r, first[i]};
        set_make(&s, 2, two);
        double sk = set_eval(w, &s, EV_SOUND, *best);
        if (sk >= 0 && sk < *best) *best = sk, *bs = s;
    }
    best_triple(w, r, first, n1, EV_SOUND, cur, 1, bs, best);
    free(first);
    return *best < HUGE_VAL;
}

/* Whether cluster r is worth evaluating: anything but a lone Cartesian
   cell, whose faces are skewed only towards irregular neighbours (and are
   then found from their side). */
static int irregular(const Work *w, int r)
{
    return w->size[r] > 1 || !w->reg[r];
}

/* The roots of the clusters above the limit into bad[] (worst first);
   returns their number, *smax the maximum over every cluster's faces. */
static int bad_clusters(Work *w, double limit, SlaveKey *bad, double *smax)
{
    int nb = 0;
    *smax = 0;
    for (int c = 0; c < w->m->ncells; c++)
        if (find(w, c) == c && irregular(w, c)) {
            double s = cluster_skew(w, c);
            if (s > *smax) *smax = s;
            if (limit > 0 && s > limit) bad[nb++] = (SlaveKey){-s, c};
        }
    qsort(bad, (size_t)nb, sizeof *bad, cmp_slave);
    return nb;
}

static int cmp_root(const void *a, const void *b)
{
    const SlaveKey *x = a, *y = b;
    return (x->root > y->root) - (x->root < y->root);
}

/* Makes the list of roots to[0..n-1] (any order, repeats, merged roots)
   the clusters above the limit among them, worst first; returns their
   number. */
static int rebad(Work *w, double limit, SlaveKey *to, int n)
{
    for (int i = 0; i < n; i++) to[i].root = find(w, to[i].root);
    qsort(to, (size_t)n, sizeof *to, cmp_root);
    int nb = 0;
    for (int i = 0; i < n; i++) {
        if (i && to[i].root == to[i - 1].root) continue;
        double s = cluster_skew(w, to[i].root);
        if (s > limit) to[nb++] = (SlaveKey){-s, to[i].root};
    }
    qsort(to, (size_t)nb, sizeof *to, cmp_slave);
    return nb;
}

/* Whether choose_skew's answer for root r can have changed since r last
   failed (seen[r] = 1 + the union count then): it depends only on r, its
   neighbours and theirs, and every union stamps itself and its
   neighbours (tstamp), so a neighbour of r stamped since then is what
   can change it. */
static int changed_since(Work *w, int r, const int *seen, const int *tstamp)
{
    if (!seen[r] || tstamp[r] >= seen[r]) return 1;
    Set s;
    set_make(&s, 1, &r);
    collect_set(w, &s);
    for (int k = 0; k < w->ncand; k++)
        if (tstamp[w->cand[k].root] >= seen[r]) return 1;
    return 0;
}

/* Runs the quality rounds, starting from the nb clusters bad[] above the
   limit (worst first; room for every cell); returns the merges made.
   The clusters a round leaves above the limit are among those it left
   alone and the unions it made with their neighbours (a merge changes
   the faces of the union only, which its neighbours share), so only
   those are measured again: the same lists as rescanning the grid.  A
   cluster that found no merge is tried again only when its neighbourhood
   changed (changed_since): the answer would be the same otherwise. */
static int skew_rounds(Work *w, double limit, int maxr, SlaveKey *bad, int nb)
{
    int nmerged = 0, nnext = 0, epoch = 0;
    size_t cap = 0;
    SlaveKey *next = NULL;
    /* written at few places: the calloc'd pages elsewhere are never faulted in */
    int *seen = MEM_NEW(int, (size_t)w->m->ncells), *tstamp = MEM_NEW(int, (size_t)w->m->ncells);
    for (int round = 0; round < maxr && nb; round++) {
        int nmerge = 0;
        nnext = 0;
        for (int i = 0; i < nb; i++) {
            int r = bad[i].root;
            if (find(w, r) != r) continue;   /* merged this round already: listed */
            double s = cluster_skew(w, r), best;
            if (!(s > limit)) continue;      /* fixed by an earlier merge */
            Set bs = {.n = 0};
            int fresh = changed_since(w, r, seen, tstamp);
            if (!fresh || !choose_skew(w, r, s, &bs, &best) || !(best < s)) {
                if (fresh) seen[r] = epoch + 1;
                mem_grow((void **)&next, &cap, (size_t)nnext + 1, sizeof *next);
                next[nnext++] = (SlaveKey){0, r};
                continue;
            }
            for (int k = 1; k < bs.n; k++) unite(w, bs.root[0], bs.root[k]);
            nmerge += bs.n - 1;
            epoch++;
            set_make(&bs, 1, (int[1]){find(w, r)});
            collect_set(w, &bs);
            tstamp[bs.root[0]] = epoch;
            for (int k = 0; k < w->ncand; k++) tstamp[w->cand[k].root] = epoch;
            mem_grow((void **)&next, &cap, (size_t)nnext + 1 + (size_t)w->ncand, sizeof *next);
            next[nnext++] = (SlaveKey){0, bs.root[0]};
            for (int k = 0; k < w->ncand; k++) next[nnext++] = (SlaveKey){0, w->cand[k].root};
        }
        nmerged += nmerge;
        if (!nmerge) break;
        memcpy(bad, next, sizeof *bad * (size_t)nnext);
        nb = rebad(w, limit, bad, nnext);
    }
    free(next);
    free(seen);
    free(tstamp);
    return nmerged;
}

/* The input's cell faces in a shallow copy, so in stays untouched.  Cell
   volumes go to g->cell_vol (work_init); face geometry is face_geo's;
   there are no cell centres: cmom holds V x centroid. */
static void input_geometry(const Mesh *in, Mesh *g)
{
    *g = *in;
    g->face_area = g->face_centre = g->cell_vol = g->cell_centre = NULL;
    g->cell_off = g->cell_faces = NULL;
    mesh_cell_faces(g);
    g->cell_vol = mem_alloc(sizeof(double) * ((size_t)g->ncells + 1));
}

static void free_input_geometry(Mesh *g)
{
    free(g->cell_vol);
    free(g->cell_off);
    free(g->cell_faces);
}

/* Whether cell c is its whole parent Cartesian cell [lo, hi]: six faces,
   each a quadrilateral of the parent's corners lying in one of its
   planes, one per plane.  Such a cell's volume and centroid are the box's
   (no face geometry needed). */
static int is_regular(const Mesh *m, int c, const double lo[3], const double hi[3])
{
    if (m->cell_off[c + 1] - m->cell_off[c] != 6) return 0;
    double tol[3];
    for (int k = 0; k < 3; k++) tol[k] = PLANE_TOL * (fmax(fabs(lo[k]), fabs(hi[k])) + hi[k] - lo[k]);
    int seen = 0;
    for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
        int f = m->cell_faces[i];
        if (m->face_off[f + 1] - m->face_off[f] != 4) return 0;
        int at[3] = {0, 0, 0};   /* per axis: bit 1 a point at lo, bit 2 a point at hi */
        for (int q = m->face_off[f]; q < m->face_off[f + 1]; q++) {
            const double *x = m->points + 3 * (size_t)m->face_idx[q];
            for (int k = 0; k < 3; k++) {
                /* exact first: grid points are the Cartesian coordinates */
                if (x[k] == lo[k] || fabs(x[k] - lo[k]) <= tol[k]) at[k] |= 1;
                else if (x[k] == hi[k] || fabs(x[k] - hi[k]) <= tol[k]) at[k] |= 2;
                else return 0;
            }
        }
        int plane = -1;
        for (int k = 0; k < 3 && plane < 0; k++)
            if (at[k] != 3) plane = 2 * k + (at[k] == 2);
        if (plane < 0 || (seen & 1 << plane)) return 0;
        seen |= 1 << plane;
    }
    return seen == 63;
}

/* Scratch for geom_cell on one cell: its faces renumbered 0..n-1. */
typedef struct CellScratch {
    int *faces, *off, *idx;
    char *flip;
    double *S, *C;
    size_t cap, idx_cap;
} CellScratch;

/* geom_cell of cell c, with its faces' geometry from face_geo. */
static void cell_geom(Work *w, int c, CellScratch *cs, double *V, double C[3])
{
    const Mesh *m = w->m;
    const int *cf = m->cell_faces + m->cell_off[c];
    int n = m->cell_off[c + 1] - m->cell_off[c];
    size_t cap = cs->cap, nidx = 0;
    mem_grow((void **)&cs->faces, &cs->cap, (size_t)n + 1, sizeof(int));
    if (cs->cap != cap) {
        cs->off = mem_realloc(cs->off, sizeof(int) * (cs->cap + 1));
        cs->flip = mem_realloc(cs->flip, cs->cap);
        cs->S = mem_realloc(cs->S, 3 * sizeof(double) * cs->cap);
        cs->C = mem_realloc(cs->C, 3 * sizeof(double) * cs->cap);
    }
    for (int k = 0; k < n; k++) nidx += (size_t)(m->face_off[cf[k] + 1] - m->face_off[cf[k]]);
    mem_grow((void **)&cs->idx, &cs->idx_cap, nidx + 1, sizeof(int));
    cs->off[0] = 0;
    for (int k = 0; k < n; k++) {
        int f = cf[k], len = m->face_off[f + 1] - m->face_off[f];
        const double *g = face_geo(w, f);
        memcpy(cs->S + 3 * k, g, 3 * sizeof(double));
        memcpy(cs->C + 3 * k, g + 3, 3 * sizeof(double));
        memcpy(cs->idx + cs->off[k], m->face_idx + m->face_off[f], sizeof(int) * (size_t)len);
        cs->off[k + 1] = cs->off[k] + len;
        cs->faces[k] = k;
        cs->flip[k] = (char)(m->owner[f] != c);
    }
    geom_cell(m->points, cs->off, cs->idx, cs->faces, cs->flip, n, cs->S, cs->C, V, C);
}

static void scratch_free(CellScratch *cs)
{
    free(cs->faces);
    free(cs->off);
    free(cs->idx);
    free(cs->flip);
    free(cs->S);
    free(cs->C);
}

/* Volume and first moment of cell c: the parent box's for a regular cell,
   else geom_cell's from its faces. */
static void cell_init(Work *w, int c, CellScratch *cs)
{
    const Mesh *m = w->m;
    double lo[3], hi[3], C[3], V;
    int hasbox = parent_box(m, c, lo, hi) == 0;
    w->vcart[c] = hasbox ? (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) : 0;
    w->reg[c] = (char)(hasbox && is_regular(m, c, lo, hi));
    if (w->reg[c]) {
        V = w->vcart[c];
        for (int k = 0; k < 3; k++) C[k] = 0.5 * (lo[k] + hi[k]);
    } else {
        cell_geom(w, c, cs, &V, C);
    }
    w->g->cell_vol[c] = w->cvol[c] = V;
    for (int k = 0; k < 3; k++) w->cmom[3 * (size_t)c + k] = V * C[k];
}

static void work_init(Work *w, Mesh *g, const MergeOpts *o)
{
    const Mesh *m = g;
    int nc = m->ncells;
    memset(w, 0, sizeof *w);
    w->m = m;
    w->g = g;
    w->o = o;
    w->fslot = MEM_NEW(int, (size_t)m->nfaces);
    w->vcart = mem_alloc(sizeof(double) * (size_t)nc);
    w->uf = mem_alloc(sizeof(int) * (size_t)nc);
    w->size = mem_alloc(sizeof(int) * (size_t)nc);
    w->next = mem_alloc(sizeof(int) * (size_t)nc);
    w->cvol = mem_alloc(sizeof(double) * (size_t)nc);
    w->cmom = mem_alloc(3 * sizeof(double) * (size_t)nc);
    w->big = mem_alloc(sizeof(int) * (size_t)nc);
    w->reg = mem_alloc((size_t)nc);
    w->empty_patch = MEM_NEW(char, (size_t)m->npatches);
    w->skip_patch = MEM_NEW(char, (size_t)m->npatches);
    /* written near cut cells only: the calloc'd pages elsewhere are never faulted in */
    w->fcc = MEM_NEW(double, 3 * (size_t)nc);
    w->fcc_ok = MEM_NEW(char, (size_t)nc);
    w->cc0 = MEM_NEW(double, 3 * (size_t)nc);
    w->cc0_ok = MEM_NEW(char, (size_t)nc);
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        w->empty_patch[p] = mesh_patch_is_empty(pa);
        w->skip_patch[p] = w->empty_patch[p] || !strncmp(pa->type, "cyclic", 6);
        /* quality_empty_dirs's rule: the largest component of each empty
           face's area vector is an empty direction */
        for (int f = pa->start; f < pa->start + pa->size && w->empty_patch[p]; f++) {
            const double *S = face_geo(w, f);
            int k = fabs(S[0]) >= fabs(S[1]) ? 0 : 1;
            if (fabs(S[2]) > fabs(S[k])) k = 2;
            w->empty[k] = 1;
        }
    }
    CellScratch cs = {0};
    for (int c = 0; c < nc; c++) {
        w->uf[c] = w->next[c] = w->big[c] = c;
        w->size[c] = 1;
        cell_init(w, c, &cs);
    }
    scratch_free(&cs);
}

static void work_free(Work *w)
{
    free(w->fslot);
    free(w->fgeo);
    free(w->vcart);
    free(w->uf);
    free(w->size);
    free(w->next);
    free(w->cvol);
    free(w->cmom);
    free(w->big);
    free(w->empty_patch);
    free(w->skip_patch);
    free(w->reg);
    free(w->cand);
    free(w->order);
    free(w->fcc);
    free(w->fcc_ok);
    free(w->cc0);
    free(w->cc0_ok);
    free(w->sc);
    free(w->sg);
}

/* ---- repair ----
   The volume rounds and the quality pass judge a merge by the faces of
   the union, but a later merge or a skewed union the quality pass could
   not mend can leave a cluster that checkMesh fails where the cut grid
   passed (set_eval's EV_CLEAN: a face skewness above maxSkewness that
   the cut grid did not have, a face pyramid or non-orthogonality error,
   an aspect ratio above 1000).  Such a cluster is dissolved into its
   input cells, which restores the cut grid's faces there; that changes
   the faces its neighbours share with it, so the clusters are examined
   again until none fails (each pass dissolves at least one cluster, or
   ends the loop).  Then the cells below the volume bound merge again in
   rounds as in merge_rounds, over the same candidates in the same order,
   but a union is taken only when it is clean (EV_CLEAN); when no union
   with one neighbour is, the clean union with two neighbours of lowest
   maximum skewness is taken.  A clean union changes only its own faces,
   all of which it checked, so the grid stays clean: merging never adds a
   checkMesh failure (with maxSkewness <= 4).  Cells no clean union takes
   stay small and are reported. */

/* Splits cluster r back into its input cells. */
static void dissolve(Work *w, int r, CellScratch *cs)
{
    int c = r;
    do {
        int nx = w->next[c];
        w->uf[c] = w->next[c] = w->big[c] = c;
        w->size[c] = 1;
        w->fcc_ok[c] = 0;
        cell_init(w, c, cs);
        c = nx;
    } while (c != r);
}

/* Dissolves the clusters that are not clean; returns their number. */
/* Whether cluster r holds a cell the repair keeps merged (w->keep). */
static int holds_kept(const Work *w, int r)
{
    if (!w->keep) return 0;
    int c = r;
    do {
        if (w->keep[c]) return 1;
        c = w->next[c];
    } while (c != r);
    return 0;
}

/* Whether the repair dissolves cluster c: it fails a check the cut grid
   passed, and it is not a sound cluster that keeps a cell of w->keep
   merged. */
static int dissolves(Work *w, int c)
{
    if (set_eval(w, &(Set){{c}, 1}, EV_CLEAN, HUGE_VAL) >= 0) return 0;
    if (holds_kept(w, c) && set_eval(w, &(Set){{c}, 1}, EV_SOUND | EV_NOSKEW, HUGE_VAL) >= 0) {
        w->nkept++;
        return 0;
    }
    return 1;
}

static int repair(Work *w)
{
    int nc = w->m->ncells, ndis = 0, again = 1;
    CellScratch cs = {0};
    while (again) {
        again = 0;
        w->nkept = 0;
        for (int c = 0; c < nc; c++)
            if (find(w, c) == c && w->size[c] > 1 && dissolves(w, c)) {
                dissolve(w, c, &cs);
                ndis++;
                again = 1;
            }
    }
    scratch_free(&cs);
    return ndis;
}

/* The clean union for slave cluster r (see above) into *bs; 0 if none. */
static int choose_clean(Work *w, int r, Set *bs)
{
    candidates(w, r);
    int n1 = w->norder;
    int *first = mem_alloc(sizeof(int) * ((size_t)n1 + 1));
    memcpy(first, w->order, sizeof(int) * (size_t)n1);
    Set s;
    double best = HUGE_VAL;
    for (int i = 0; i < n1 && best == HUGE_VAL; i++) {
        set_make(&s, 2, (int[2]){r, first[i]});
        if (set_eval(w, &s, EV_CLEAN, HUGE_VAL) >= 0) *bs = s, best = 0;
    }
    best_triple(w, r, first, n1, EV_CLEAN, HUGE_VAL, 0, bs, &best);
    free(first);
    return best < HUGE_VAL;
}

/* The volume rounds again with clean unions only (see above), except
   that a cell below min_ratio that no clean union takes gets a sound one
   (choose; counted in *nforced); stuck[r] as merge_rounds.  Returns the
   merges made. */
static int clean_rounds(Work *w, char *stuck, int *nforced)
{
    int nc = w->m->ncells, nmerged = 0;
    SlaveKey *sl = MEM_NEW(SlaveKey, (size_t)nc);
    for (int round = 0; round < w->o->max_iter; round++) {
        int ns = 0, nmerge = 0;
        for (int c = 0; c < nc; c++)
            if (find(w, c) == c && below(w, c)) sl[ns++] = (SlaveKey){w->cvol[c] / w->vcart[w->big[c]], c};
        qsort(sl, (size_t)ns, sizeof *sl, cmp_slave);
        for (int i = 0; i < ns; i++) {
            int r = sl[i].root;
            Set bs = {.n = 0};
            if (find(w, r) != r || !below(w, r)) continue;
            stuck[r] = !choose_clean(w, r, &bs);
            if (stuck[r] && w->cvol[r] < w->o->min_ratio * w->vcart[w->big[r]]) {
                stuck[r] = !choose(w, r, &bs);
                *nforced += !stuck[r];
            }
            if (stuck[r]) continue;
            for (int k = 1; k < bs.n; k++) unite(w, bs.root[0], bs.root[k]);
            stuck[find(w, r)] = 0;
            nmerge += bs.n - 1;
        }
        nmerged += nmerge;
        if (!nmerge) break;
    }
    free(sl);
    return nmerged;
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
    int *face;        /* per boundary face (f - ninternal): -1 kept, -2 dropped, else outline
                         index (the group's first face); NULL without empty patches */
    IntVec off, pts;  /* outlines: points pts[off[i]..off[i+1]-1] */
    IntVec grp, ea, eb, mark;   /* scratch */
} Joined;

static int is_empty_face(const Mesh *m, int f)
{
    int p = mesh_face_patch(m, f);
    return p >= 0 && mesh_patch_is_empty(&m->patches[p]);
}

static int point_on(const Mesh *m, int pt, int k, double v, double tol)
{
    return fabs(m->points[3 * (size_t)pt + k] - v) <= tol;
}

/* Plane of face f: axis of the largest area component, coordinate of its
   first point; -1 when some point is off that plane. */
static int face_plane(Work *w, int f, double tol_rel, double *v)
{
    const Mesh *m = w->m;
    const double *S = face_geo(w, f);
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
            if (f >= m->ninternal && j->mark.v[f - m->ninternal]) continue;
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
    for (int i = 0; i < j->grp.n; i++) j->face[j->grp.v[i] - m->ninternal] = -2;
    j->face[lead - m->ninternal] = j->off.n - 2;
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
        int k = f0 >= 0 ? face_plane(w, f0, PLANE_TOL, &v0) : -1;
        if (k < 0) continue;
        double tol = PLANE_TOL * (fabs(v0) + 1);
        j->grp.n = 0;
        for (int q = i; q < all.n; q++) {
            int f = all.v[q];
            if (f >= 0 && mesh_face_patch(m, f) == mesh_face_patch(m, f0) && face_plane(w, f, PLANE_TOL, &v) == k &&
                fabs(v - v0) <= tol) {
                iv_push(&j->grp, f);
                all.v[q] = -1;
            }
        }
        if (j->grp.n < 2) continue;
        for (int q = 0; q < j->grp.n; q++) j->mark.v[j->grp.v[q] - m->ninternal] = 1;
        join_group(w, j, r, k, v0, tol);
        for (int q = 0; q < j->grp.n; q++) j->mark.v[j->grp.v[q] - m->ninternal] = 0;
    }
    free(all.v);
}

static void join_empty(Work *w, Joined *j)
{
    const Mesh *m = w->m;
    int nb = m->nfaces - m->ninternal, any = 0;
    memset(j, 0, sizeof *j);
    for (int p = 0; p < m->npatches; p++) any |= w->empty_patch[p];
    if (!any) return;
    j->face = mem_alloc(sizeof(int) * ((size_t)nb + 1));
    for (int i = 0; i < nb; i++) j->face[i] = -1;
    j->mark.v = MEM_NEW(int, (size_t)nb);
    j->mark.n = j->mark.cap = nb;
    iv_push(&j->off, 0);
    for (int c = 0; c < m->ncells; c++)
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

/* Internal faces of out in polyMesh order: the input's internal faces
   whose cells are in different clusters, sorted by (lower, higher)
   output cell with ties in input order, as meshbuild_finish would give
   them.  Returns their number; ord gets the input faces, nei the higher
   output cells. */
static int internal_order(const Mesh *m, const int *newid, int nout, int *ord, int *nei)
{
    int *start = MEM_NEW(int, (size_t)nout + 1), n = 0;
    for (int f = 0; f < m->ninternal; f++) {
        int a = newid[m->owner[f]], b = newid[m->neighbour[f]];
        if (a != b) start[(a < b ? a : b) + 1]++, n++;
    }
    for (int C = 0; C < nout; C++) start[C + 1] += start[C];
    for (int f = 0; f < m->ninternal; f++) {
        int a = newid[m->owner[f]], b = newid[m->neighbour[f]];
        if (a == b) continue;
        int pos = start[a < b ? a : b]++;
        ord[pos] = f;
        nei[pos] = a < b ? b : a;
    }
    /* start[C] is now the end of C's faces: a stable insertion sort on the
       neighbour inside each owner's run (runs are short, mostly sorted) */
    for (int C = 0, s = 0; C < nout; s = start[C++])
        for (int i = s + 1; i < start[C]; i++) {
            int f = ord[i], b = nei[i], k = i;
            for (; k > s && nei[k - 1] > b; k--) {
                ord[k] = ord[k - 1];
                nei[k] = nei[k - 1];
            }
            ord[k] = f;
            nei[k] = b;
        }
    free(start);
    return n;
}

/* Appends the n points pts to out's face list (reversed when flip). */
static void put_face(Mesh *out, int g, const int *pts, int n, int flip)
{
    int *dst = out->face_idx + out->face_off[g];
    for (int k = 0; k < n; k++) dst[k] = flip ? pts[n - 1 - k] : pts[k];
    out->face_off[g + 1] = out->face_off[g] + n;
}

/* Keeps the points out's faces use, in their input order. */
static void out_points(const Mesh *m, Mesh *out)
{
    int *pmap = MEM_NEW(int, (size_t)m->npoints);
    int nidx = out->face_off[out->nfaces], np = 0;
    for (int k = 0; k < nidx; k++) pmap[out->face_idx[k]] = 1;
    for (int i = 0; i < m->npoints; i++) pmap[i] = pmap[i] ? np++ : -1;
    out->npoints = np;
    out->points = mem_alloc(3 * sizeof(double) * ((size_t)np + 1));
    if (np == m->npoints) {
        memcpy(out->points, m->points, 3 * sizeof(double) * (size_t)np);
    } else {
        for (int i = 0; i < m->npoints; i++)
            if (pmap[i] >= 0) memcpy(out->points + 3 * (size_t)pmap[i], m->points + 3 * (size_t)i, 3 * sizeof(double));
        for (int k = 0; k < nidx; k++) out->face_idx[k] = pmap[out->face_idx[k]];
    }
    free(pmap);
}

/* Assembles the union polyhedra of the clusters into out (nout cells);
   newid[c] is the output cell of input cell c.  This is what meshbuild
   would make of the faces (same order, orientation and points), built
   directly: the input is in polyMesh order already, so internal faces
   need a sort by owner only inside runs, and boundary faces keep their
   order. */
static void assemble(Work *w, const int *newid, int nout, Mesh *out)
{
    const Mesh *m = w->m;
    Joined j;
    join_empty(w, &j);
    /* the cell faces are not needed any more: their room (2 per internal
       face) takes the order; the neighbours go where they belong */
    int *ord = w->g->cell_faces;
    int *nei = mem_alloc(sizeof(int) * ((size_t)m->ninternal + 1));
    int ni = internal_order(m, newid, nout, ord, nei);
    size_t nidx = 0;
    int nf = ni;
    for (int i = 0; i < ni; i++) nidx += (size_t)(m->face_off[ord[i] + 1] - m->face_off[ord[i]]);
    for (int f = m->ninternal; f < m->nfaces; f++) {
        int jf = j.face ? j.face[f - m->ninternal] : -1;
        if (jf == -2) continue;
        nf++;
        nidx += (size_t)(jf >= 0 ? j.off.v[jf + 1] - j.off.v[jf] : m->face_off[f + 1] - m->face_off[f]);
    }
    out->ncells = nout;
    out->nfaces = nf;
    out->ninternal = ni;
    out->face_off = mem_alloc(sizeof(int) * ((size_t)nf + 1));
    out->face_idx = mem_alloc(sizeof(int) * (nidx + 1));
    out->owner = mem_alloc(sizeof(int) * ((size_t)nf + 1));
    out->face_off[0] = 0;
    for (int g = 0; g < ni; g++) {
        int f = ord[g], a = newid[m->owner[f]], b = newid[m->neighbour[f]];
        put_face(out, g, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], a > b);
        out->owner[g] = a < b ? a : b;
    }
    out->neighbour = nei;
    out->npatches = m->npatches;
    out->patches = MEM_NEW(Patch, (size_t)m->npatches);
    int g = ni;
    if (m->boundary_normal) out->boundary_normal = mem_alloc(3 * sizeof(double) * ((size_t)(nf - ni) + 1));
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        Patch *q = &out->patches[p];
        mesh_patch_copy(pa, q);
        q->start = g;
        for (int f = pa->start; f < pa->start + pa->size; f++) {
            int jf = j.face ? j.face[f - m->ninternal] : -1;
            if (jf == -2) continue;
            if (jf >= 0) put_face(out, g, j.pts.v + j.off.v[jf], j.off.v[jf + 1] - j.off.v[jf], 0);
            else put_face(out, g, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], 0);
            out->owner[g] = newid[m->owner[f]];
            if (m->boundary_normal)
                memcpy(out->boundary_normal + 3 * (size_t)(g - ni), m->boundary_normal + 3 * (size_t)(f - m->ninternal),
                       3 * sizeof(double));
            g++;
        }
        q->size = g - q->start;
    }
    joined_free(&j);
    out_points(m, out);
}

/* Aspect ratio (quality_cell's) of cluster r, from its members' faces
   and its volume: the faces shared inside are not the union's, the other
   ones are kept (a 2-D cluster's joined empty faces add up to the members'
   ones).  A lone regular cell's comes from its box; amemo keeps the last
   box's, the common case being a uniform grid. */
static double cluster_aspect(Work *w, int r, double amemo[4])
{
    const Mesh *m = w->m;
    double mag[3] = {0, 0, 0};
    if (w->size[r] == 1 && w->reg[r]) {
        double h[3];
        mesh_cell_spacing(m, r, h);
        if (h[0] == amemo[0] && h[1] == amemo[1] && h[2] == amemo[2]) return amemo[3];
        for (int k = 0; k < 3; k++) {
            amemo[k] = h[k];
            mag[k] = 2 * h[(k + 1) % 3] * h[(k + 2) % 3];
        }
        return amemo[3] = quality_aspect(mag, w->cvol[r], w->empty);
    }
    int c = r;
    do {
        for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
            int f = m->cell_faces[i];
            if (f < m->ninternal && find(w, m->owner[f]) == find(w, m->neighbour[f])) continue;
            const double *S = face_geo(w, f);
            for (int k = 0; k < 3; k++) mag[k] += fabs(S[k]);
        }
        c = w->next[c];
    } while (c != r);
    return quality_aspect(mag, w->cvol[r], w->empty);
}

static void stats_before(Work *w, MergeStats *st)
{
    const Mesh *m = w->m;
    double amemo[4] = {-1, -1, -1, 0};
    st->ncells_in = m->ncells;
    st->ratio_min_before = HUGE_VAL;
    for (int c = 0; c < m->ncells; c++) {
        st->vol_before += m->cell_vol[c];
        if (w->vcart[c] > 0) {
            double r = m->cell_vol[c] / w->vcart[c];
            if (r < st->ratio_min_before) st->ratio_min_before = r;
            if (r <= w->o->threshold) st->nslaves++;
        }
        double ar = cluster_aspect(w, c, amemo);
        if (ar > st->aspect_max_before) st->aspect_max_before = ar;
    }
}

/* Statistics of the output's nout cells from the clusters (no output
   geometry needed); root[C] is the root of output cell C. */
static void stats_after(Work *w, const int *root, const char *stuck, int nout, MergeStats *st)
{
    double amemo[4] = {-1, -1, -1, 0};
    st->ncells_out = nout;
    st->ratio_min_after = HUGE_VAL;
    st->ratio_min_cell = -1;
    st->unresolved = MEM_NEW(int, (size_t)nout);
    st->reason = MEM_NEW(int, (size_t)nout);
    for (int C = 0; C < nout; C++) {
        int r = root[C];
        st->vol_after += w->cvol[r];
        if (w->size[r] > 1) st->nclusters++;
        double vc = w->vcart[w->big[r]];
        if (vc > 0 && w->cvol[r] / vc < st->ratio_min_after) {
            st->ratio_min_after = w->cvol[r] / vc;
            st->ratio_min_cell = C;
        }
        double ar = cluster_aspect(w, r, amemo);
        if (ar > st->aspect_max_after) st->aspect_max_after = ar;
        double sk = irregular(w, r) ? cluster_skew(w, r) : 0;
        if (sk > st->skew_max_after) st->skew_max_after = sk;
        if (below(w, r)) {
            st->unresolved[st->nunresolved] = C;
            st->reason[st->nunresolved++] = stuck[r] ? MERGE_NO_NEIGHBOUR : MERGE_ITER_LIMIT;
        } else if (w->o->max_skewness > 0 && sk > skew_limit(w->o)) {
            st->unresolved[st->nunresolved] = C;
            st->reason[st->nunresolved++] = MERGE_SKEWNESS;
        }
    }
}

/* The cut-cell data contract of out (cartcells.h), composed with the
   input's; an input without one (a cut grid written before it existed)
   gets one from its cellParent and volumes first, when cellParent names
   one cell per Cartesian cell. */
static void merge_cart_cells(const Mesh *in, const double *vol, const int *newid, Mesh *out)
{
    CartCells base;
    const CartCells *cc = &in->cartcells;
    if (cc->n <= 0) {
        if (cartcells_build(in, vol, NULL, &base)) return;
        cc = &base;
    }
    cartcells_merge(cc, newid, out, &out->cartcells);
    if (cc == &base) cartcells_free(&base);
}

static int check_input(const Mesh *in, const MergeOpts *o, Err *e)
{
    if (!(o->threshold > 0 && o->threshold <= 1))
        return err_set(e, NULL, 0, "merge: threshold %g out of range (0, 1]", o->threshold);
    if (o->criterion != MERGE_NORMAL && o->criterion != MERGE_NORMAL_H)
        return err_set(e, NULL, 0, "merge: unknown criterion %d", o->criterion);
    if (o->max_iter < 0) return err_set(e, NULL, 0, "merge: maxIter %d is negative", o->max_iter);
    if (!(o->max_skewness >= 0)) return err_set(e, NULL, 0, "merge: maxSkewness %g is negative", o->max_skewness);
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

/* The merge rounds, the quality pass and the repair, with their counts
   in *st.  The repair restores the cut grid's cells where a cluster fails
   a checkMesh check the cut grid passed, and the clean rounds re-merge
   them into passing unions only; a cell that none takes stays as small as
   it was cut (1e-6 of its Cartesian cell, say), which no explicit solver
   survives.  So when the result has cells below min_ratio, merge_mesh
   runs this again with those cells in w->keep: the repair then keeps any
   sound cluster holding one (its skewness may be above maxSkewness, which
   checkMesh reports but a solver runs with), and the clean rounds give a
   cell below min_ratio that no clean union takes a sound one (choose). */
static void rounds(Work *w, char *stuck, MergeStats *st)
{
    const MergeOpts *o = w->o;
    int nc = w->m->ncells;
    SlaveKey *bad = mem_alloc(sizeof(SlaveKey) * (size_t)nc);
    st->nforced = st->nundone = st->nclean_merged = 0;
    memset(stuck, 0, (size_t)nc);
    st->niter = merge_rounds(w, stuck);
    int nbad = bad_clusters(w, skew_limit(o), bad, &st->skew_max_before);
    st->nskew_merged = skew_rounds(w, skew_limit(o), o->max_iter, bad, nbad);
    free(bad);
    if (o->max_skewness > 0) {
        st->nundone = repair(w);
        if (st->nundone) st->nclean_merged = clean_rounds(w, stuck, &st->nforced);
        st->nforced += w->nkept;
    }
}

/* The input cells of clusters below min_ratio after a repair that
   dissolved something, or NULL when there are none. */
static char *tiny_cells(Work *w)
{
    if (!(w->o->min_ratio > 0) || !(w->o->max_skewness > 0)) return NULL;
    int nc = w->m->ncells, n = 0;
    char *keep = MEM_NEW(char, (size_t)nc);
    for (int c = 0; c < nc; c++) {
        int r = find(w, c);
        if (w->vcart[w->big[r]] > 0 && w->cvol[r] < w->o->min_ratio * w->vcart[w->big[r]]) keep[c] = 1, n++;
    }
    if (n) return keep;
    free(keep);
    return NULL;
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
    SlaveKey *bad = mem_alloc(sizeof(SlaveKey) * (size_t)nc);
    bad_clusters(&w, 0, bad, &st->skew_max_cut);
    free(bad);
    rounds(&w, stuck, st);
    char *keep = tiny_cells(&w);
    if (keep) {   /* again, keeping the clusters that held them (see rounds) */
        work_free(&w);
        work_init(&w, &g, o);
        w.keep = keep;
        rounds(&w, stuck, st);
    }

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
    stats_after(&w, root, stuck, nout, st);
    assemble(&w, newid, nout, out);   /* last: it reuses g's cell faces */
    mesh_copy_cart(&in->cart, &out->cart);
    out->cell_parent = mem_alloc(sizeof(int) * (size_t)nout);
    for (int C = 0; C < nout; C++) out->cell_parent[C] = in->cell_parent[w.big[root[C]]];
    merge_cart_cells(in, g.cell_vol, newid, out);
    out->merge_map = newid;
    out->nmerge_old = nc;
    free(root);
    free(stuck);
    free(keep);
    work_free(&w);
    free_input_geometry(&g);
    return 0;
}
