/*
** cut.c: cut cells of a block grid by a Geometry (cut.h, spec
** granular-model.md §2.2, thesis §3.2.2).
**
** Data.  Grid vertex (i,j,k) is v = i + (nx+1)*(j + (ny+1)*k); the grid
** edge from v along axis a is the key 3v + a.  Per vertex one byte (fluid
** or solid) and one lazily assigned mesh point; per Cartesian cell its new
** cell number.  Cut points exist only on mixed edges (fluid and solid
** end), so they live in an open-addressing hash table keyed by the edge:
** its size follows the boundary, not the grid.
**
** Crossings come from one geometry_crossings call per grid line (the whole
** line, not each edge): 3 (n+1)^2 calls instead of 3 (n+1)^3, and every
** crossing is seen, so thin features (crossings inside an edge whose ends
** agree) are counted.  nodd counts mixed edges with two or more
** crossings.  A crossing becomes a coordinate along the line; the other
** two coordinates of a cut point are the grid line's own, so cut points
** on grid planes lie exactly on them.
**
** Snapping (cut.h step 3).  Vertices on the surface (to snap x the edge
** length) are solid: a fluid vertex whose edge's cut point is that close
** turns solid, and so does one that lies on the surface only along a
** diagonal (a box's edge or corner on grid lines: no grid line through
** the vertex crosses the surface), found by testing the point snap x the
** way towards each solid corner of its cut cells.  Edges from a snapped
** vertex to fluid vertices get their cut point on it, except an edge lying
** in the surface (a grid line in a box face on a grid plane), whose real
** crossing is found on copies of the edge moved across it (offset_cut).
** Afterwards each fluid corner keeps a corner piece at least snap x (edge)
** wide, so no face or cell has zero size.  Vertices a crossing meets are
** on the surface too (mark_vertex_crossings), and so are those next to
** the surface whose cells' probes disagree (probe_corners: a corner of
** the geometry both of whose faces lie in grid planes through it, which
** no crossing meets).  Being solid for the grid,
** a vertex on the surface is then judged by each of its cells on its own
** (step 6, local_masks: a probe towards the cell's centre), so the cells
** on the fluid side of a face on a grid plane keep their whole volume
** (a cylinder's cap, flow inside a grid-aligned box).
**
** Each cell's own points (local_points).  Where a grid edge lies in a
** face of one part of the geometry and another part crosses it, the
** cells on the two sides of that face see different points on the edge;
** every cell that cuts an edge from a vertex on the surface keeps its own
** point (a CutView, cut_impl.h), from copies of the edge moved into the
** cell (own_point), and equal points are settled into one.
**
** Faces (cut_face.c).  A grid face polygon is walked round its corners in
** the order base, +u, +u+v, +v (normal +a, with u = a+1, v = a+2
** cyclically), emitting fluid corners and the cell's points on the edges
** (two diagonal fluid corners are joined: a hexagon); consecutive repeats
** of a point (cut points snapped onto one vertex) are dropped, and a side
** along a grid edge takes the edge's other points.  The same walk serves
** both cells of a face and both cyclic sides of a box (the min side
** reverses it keeping the first point, blockGrid's rule), so shared faces
** agree point for point; where two cells see a face differently, they
** share the part both see and keep the rest as walls.  Sides joining two
** cut points, reversed, are the boundary's edges
** in the cell: pairs running both ways (a zero-area spur where a snapped
** point sits on a cell edge) cancel, and the rest chain into simple loops.
** Every cut point enters and leaves the cell's grid faces equally often,
** so every edge of a cell is used by exactly two of its faces in opposite
** directions (closed cells, watertight boundary), whatever the loops'
** shape and however they are triangulated.
**
** Boundary faces.  A planar loop is one polygon (exact for plane cuts);
** any other is fanned about its centroid.  Cut cells need not be convex,
** and checkMesh wants every face to face away from the cell centroid
** (positive face pyramids): when a fan triangle would not, the loop is
** triangulated by its own points instead, choosing by dynamic programming
** the triangulation whose smallest pyramid on the resulting centroid is
** largest.  The body-diagonal case gets a band of six triangles zipping
** the two loops by angle about their axis, or the best of all 60 zips when
** that one has a bad pyramid.
**
** Order and sizes.  Cells are numbered in Cartesian order; each adds its
** faces towards its +x, +y, +z neighbours, so internal faces arrive
** almost in OpenFOAM's order, and box-side faces follow in the grid's own
** boundary-face order, which keeps cyclic pairs matched.  meshbuild keeps
** the order of addition within a patch, so the k-th face added to a patch
** is its k-th face: wall normals are stored in addition order and placed
** without a face map.  Cell volumes are summed while the faces are made
** (divergence theorem, tetrahedra of each face on the cell's centre: exact
** for closed surfaces of planar polygons), so no geometry pass is needed.
*/
#include "cut.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cartcells.h"
#include "cut_impl.h"
#include "geom.h"
#include "mem.h"
#include "meshbuild.h"

#ifndef M_SQRT2
#define M_SQRT2 1.41421356237309504880
#endif
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PLANAR_TOL 1e-12 /* loop planarity, relative to its size (cut.h) */
#define MAXS       96    /* boundary segments of one cell */
#define MAXSIDE    (6 * MAXP) /* sides of one cell's grid-face polygons */
#define EXTRA_SNAP 100   /* extrapolated crossings: snap distances to an end (settle) */
#define DEGENERATE 1e-12  /* a cell piece below this fraction of its cell is dropped */
#define OFFSET     (4 * EXTRA_SNAP) /* moved edge copies, in snap distances (offset_cut) */
#define PROBE      1000  /* corner probes, in snap distances (local_fluid) */

/* Corner probes go this much of the way along each axis (times PROBE x
   snap of the way to the cell's centre): 1, 1/phi and 1/sqrt(2) have no
   rational relation, so no plane with an integer normal (a half-space
   through the vertex, a prism's side along the cell's diagonal) holds a
   probe, which would leave the corner's class to round-off. */
static const double probe_w[3] = {1, 0.6180339887498949, 0.7071067811865476};
#define SKEW       0.6180339887498949 /* a cell's edge copies: second offset / first (side_point) */
#define END_RATE   1.2   /* a crossing closes on an end: distance ratio per doubled move (closes_on_end) */

typedef struct Seg {
    int a, b, la, lb;
} Seg;

void cut_opts_default(CutOpts *o)
{
    o->snap = CUT_SNAP;
    o->method = CUT_METHOD_CUT;
}

static const char *const cut_methods[] = {"cut", "staircase", NULL};

const DictKey cut_keys[] = {
    {"snapTolerance", "1e-08", "cut points closer than this fraction of an edge to a grid vertex move onto it"},
    {"method", "cut", "cut: exact cut cells; staircase: keep whole every Cartesian cell whose centre is in the fluid, "
                      "the wall a staircase of grid faces (the thesis's Cartesian runs)"},
    {NULL, NULL, NULL}};

int cut_read_opts(const char *path, CutOpts *o, Err *e)
{
    cut_opts_default(o);
    Dict *d = dict_read(path, e);
    int rc = !d || dict_check_keys(d, cut_keys, e) || dict_scalar_or(d, "snapTolerance", o->snap, &o->snap, e) ||
             dict_choice_or(d, "method", cut_methods, o->method, &o->method, e);
    /* snapping moves a point by at most a quarter edge, so neighbouring
       cut points on one edge can never swap */
    if (!rc && !(o->snap >= 0 && o->snap < 0.25)) {
        const DictEntry *en = dict_find(d, "snapTolerance");
        rc = err_set(e, path, en ? en->line : 0, "snapTolerance must be in [0, 0.25), found %g", o->snap);
    }
    dict_free(d);
    return rc ? -1 : 0;
}

/* ---- the cut-point table ---- */

static void tab_alloc(Ctx *c, size_t cap)
{
    c->cap = cap;
    c->tab = mem_alloc(cap * sizeof *c->tab);
    for (size_t i = 0; i < cap; i++) c->tab[i].key = -1;
}

static CutPt *cut_insert(Ctx *c, int64_t key)
{
    if (2 * (c->cnt + 1) > c->cap) {
        CutPt *old = c->tab;
        size_t oc = c->cap;
        tab_alloc(c, 2 * oc);
        for (size_t i = 0; i < oc; i++)
            if (old[i].key >= 0) {
                size_t j = cut_slot(c, old[i].key);
                while (c->tab[j].key >= 0) j = (j + 1) & (c->cap - 1);
                c->tab[j] = old[i];
            }
        free(old);
    }
    size_t i = cut_slot(c, key);
    while (c->tab[i].key >= 0 && c->tab[i].key != key) i = (i + 1) & (c->cap - 1);
    if (c->tab[i].key < 0) c->cnt++;
    c->tab[i] = (CutPt){key, 0, -1, -1, -1, -1, 0, 0};
    return &c->tab[i];
}

/* ---- vertices ---- */

int cut_point(Ctx *c, CutPt *p)
{
    int64_t v = p->key / 3;
    int a = (int)(p->key % 3);
    if (p->at >= 0) return cut_vertex_point(c, v + (p->at ? c->sv[a] : 0));
    if (p->pt < 0) {
        int ijk[3];
        cut_vertex_ijk(c, v, ijk);
        double x[3] = {c->x[0][ijk[0]], c->x[1][ijk[1]], c->x[2][ijk[2]]};
        x[a] = p->s;
        p->pt = meshbuild_point(&c->b, x);
    }
    return p->pt;
}

/* Step 1: one classify_line sweep per x-line. */
static void classify(Ctx *c)
{
    for (int k = 0; k < c->nv[2]; k++)
        for (int j = 0; j < c->nv[1]; j++) {
            double p[3] = {c->x[0][0], c->x[1][j], c->x[2][k]};
            char *out = c->cls + (int64_t)c->nv[0] * (j + (int64_t)c->nv[1] * k);
            geometry_classify_line(c->g, 0, p, c->x[0], c->nv[0], out);
            for (int i = 0; i < c->nv[0]; i++) out[i] = out[i] != 0;
        }
}

/* ---- step 2: cut points from the crossings of whole grid lines ---- */

typedef struct Line {
    GeoCross *cr;
    int ncr, cap;
    double *s; /* crossing coordinates */
} Line;

static void line_crossings(Ctx *c, Line *l, int a, const double p[3])
{
    double pa[3] = {p[0], p[1], p[2]}, pb[3] = {p[0], p[1], p[2]};
    const double *x = c->x[a];
    int n = c->n[a];
    pa[a] = x[0];
    pb[a] = x[n];
    int k = geometry_crossings(c->g, pa, pb, l->cr, l->cap);
    if (k > l->cap) {
        free(l->cr);
        free(l->s);
        l->cap = k;
        l->cr = mem_alloc(sizeof *l->cr * (size_t)k);
        l->s = mem_alloc(sizeof *l->s * (size_t)k);
        k = geometry_crossings(c->g, pa, pb, l->cr, l->cap);
        if (k > l->cap) k = l->cap;
    }
    l->ncr = k;
    for (int i = 0; i < k; i++) {
        double t = l->cr[i].t;
        l->s[i] = t >= 1 ? x[n] : t <= 0 ? x[0] : x[0] + t * (x[n] - x[0]);
    }
}

/* The crossing on the copy of edge (p0, along a to xhi) moved by off,
   nearest its fluid end, when the copy's ends are fluid and solid like
   the edge's. */
static int shifted_cut(const Ctx *c, int a, const double p0[3], double xhi, int fluid_lo, const double off[3],
                       double *s, int *leaf)
{
    double q0[3], q1[3];
    for (int k = 0; k < 3; k++) q0[k] = p0[k] + off[k];
    memcpy(q1, q0, sizeof q1);
    q1[a] = xhi;
    /* the ends are judged snap x (edge) in, well inside the offsets:
       an end may lie on another surface (a cone's base on a grid plane),
       and a crossing there is not the edge's */
    double t0[3], t1[3], eta = c->snap * (xhi - p0[a]);
    memcpy(t0, q0, sizeof t0);
    memcpy(t1, q1, sizeof t1);
    t0[a] += eta;
    t1[a] -= eta;
    if (geometry_fluid(c->g, t0) != fluid_lo || geometry_fluid(c->g, t1) == fluid_lo) return 0;
    GeoCross cr[8];
    int k = geometry_crossings(c->g, q0, q1, cr, 8), found = 0;
    double xf = fluid_lo ? p0[a] : xhi;
    for (int r = 0; r < k && r < 8; r++) {
        double x = p0[a] + cr[r].t * (xhi - p0[a]);
        if (x < t0[a] || x > t1[a]) continue;
        if (!found || fabs(x - xf) < fabs(*s - xf)) *s = x, *leaf = cr[r].leaf;
        found = 1;
    }
    return found;
}


/* The crossing on an unmoved edge from crossings s[0..2] on copies
   moved by 1, 2 and 4 times a small offset (n of them found): quadratic
   extrapolation where the crossing moves smoothly with the offset (a
   surface through the edge; the copies of one edge moved in different
   directions then agree to round-off), square-root extrapolation where
   it moves with its square root (a curved surface touching the edge: a
   circle tangent to a grid line), the crossing itself where it stays
   put. */
static double extrapolate(const double s[3], int n)
{
    if (n < 2 || s[1] == s[0]) return s[0];
    if (n < 3) return 2 * s[0] - s[1];
    double r = (s[2] - s[1]) / (s[1] - s[0]);
    if (fabs(r - M_SQRT2) < 0.1) return (M_SQRT2 * s[0] - s[1]) / (M_SQRT2 - 1);
    return (8 * s[0] - 6 * s[1] + s[2]) / 3;
}

/* An extrapolated crossing s on the edge xlo..xhi, put on an end it lies
   within EXTRA_SNAP snap distances of: extrapolation from crossings near
   a tangency is good to about the square root of the round-off only, and
   every computation of a point on the end must give the end itself. */
static double settle(const Ctx *c, double s, double xlo, double xhi)
{
    double tol = EXTRA_SNAP * c->snap * (xhi - xlo);
    return fabs(s - xlo) < tol ? xlo : fabs(s - xhi) < tol ? xhi : s;
}

/* The boundary crossing on an edge that lies in the surface (a grid line
   in a face of a box on a grid plane: its own crossings are not
   transversal).  The edge from vertex v along a is moved by snap x (cell
   width) and twice that in each of the four directions across it; copies
   whose ends are fluid and solid like the edge's give crossings, and the
   line through the two is extrapolated to no move at all: exact when the
   surface is planar there, whether the crossing stays put (a face ending
   at a side) or moves with the copy (a surface through the vertex).
   Returns 0 when no copy crosses. */
static int offset_cut(const Ctx *c, int a, int64_t v, int fluid_lo, double *s, int *leaf)
{
    int ijk[3], found = 0, u = (a + 1) % 3, w = (a + 2) % 3;
    cut_vertex_ijk(c, v, ijk);
    double p0[3] = {c->x[0][ijk[0]], c->x[1][ijk[1]], c->x[2][ijk[2]]};
    double xhi = c->x[a][ijk[a] + 1], xf = fluid_lo ? p0[a] : xhi, h[3] = {0, 0, 0};
    for (int b = 0; b < 3; b++) {
        int lo = ijk[b] < c->n[b] ? ijk[b] : ijk[b] - 1;
        h[b] = c->x[b][lo + 1] - c->x[b][lo];
    }
    /* four copies along the axes across the edge, then four along the
       diagonals (off both faces of a geometry edge lying on the grid
       line, where the axis copies stay in one face or the other) */
    for (int d = 0; d < 8; d++) {
        double off[3] = {0, 0, 0}, sk[3];
        if (d < 4) {
            int b = d < 2 ? u : w;
            off[b] = (d & 1 ? -1 : 1) * OFFSET * c->snap * h[b];
        } else {
            off[u] = (d & 1 ? -1 : 1) * OFFSET * c->snap * h[u];
            off[w] = (d & 2 ? -1 : 1) * OFFSET * c->snap * h[w];
        }
        if (d == 4 && found) break;
        int nk = 0, l1 = -1, l2;
        while (nk < 3 && shifted_cut(c, a, p0, xhi, fluid_lo, off, &sk[nk], nk ? &l2 : &l1)) {
            for (int b = 0; b < 3; b++) off[b] *= 2;
            nk++;
        }
        if (!nk) continue;
        double s1 = settle(c, extrapolate(sk, nk), p0[a], xhi);
        if (!found || fabs(s1 - xf) < fabs(*s - xf)) *s = s1, *leaf = l1;
        found = 1;
    }
    return found;
}

/* The cut point of edge i..i+1 of the line (first crossing index *lo,
   advanced past crossings left behind). */
static void edge_cut(Ctx *c, const Line *l, int a, int i, int64_t va, int *lo)
{
    const double *x = c->x[a];
    double h = x[i + 1] - x[i], tol = c->snap * h;
    while (*lo < l->ncr && l->s[*lo] < x[i] - tol) (*lo)++;
    int fa = c->cls[va], fb = c->cls[va + c->sv[a]];
    if (fa == fb) {
        for (int r = *lo; r < l->ncr && l->s[r] < x[i + 1] - tol; r++)
            if (l->s[r] > x[i] + tol) {
                c->st->nthin++;
                break;
            }
        return;
    }
    double xf = fa ? x[i] : x[i + 1];
    int best = -1, cnt = 0;
    for (int r = *lo; r < l->ncr && l->s[r] <= x[i + 1] + tol; r++, cnt++)
        if (best < 0 || fabs(l->s[r] - xf) < fabs(l->s[best] - xf)) best = r;
    CutPt *p = cut_insert(c, 3 * va + a);
    if (best < 0) {
        double so;
        int lf;
        if (c->snap > 0 && offset_cut(c, a, va, fa, &so, &lf)) {
            p->s = fmin(fmax(so, x[i]), x[i + 1]);
            p->leaf = lf;
            return;
        }
        c->st->ninconsistent++;
        p->s = fa ? x[i + 1] : x[i];
        return;
    }
    if (cnt >= 2) c->st->nodd++;
    p->s = settle(c, fmin(fmax(l->s[best], x[i]), x[i + 1]), x[i], x[i + 1]);
    p->leaf = l->cr[best].leaf;
}

/* Vertices of the line from v0 along a that a crossing meets (within
   the settle distance) lie on the surface, whatever their class: the
   corners of a layer of the geometry exactly one cell thick are crossed
   at both ends of their edges and nowhere in between, so no edge of
   theirs changes class and snapping alone would not find them. */
static void mark_vertex_crossings(Ctx *c, const Line *l, int a, int64_t v0)
{
    const double *x = c->x[a];
    int i = 0;
    for (int r = 0; r < l->ncr; r++) {
        while (i < c->n[a] && x[i + 1] <= l->s[r]) i++;
        for (int e = i; e <= i + 1 && e <= c->n[a]; e++) {
            int lo = e < c->n[a] ? e : e - 1;
            if (fabs(l->s[r] - x[e]) < EXTRA_SNAP * c->snap * (x[lo + 1] - x[lo])) c->onsurf[v0 + e * c->sv[a]] = 1;
        }
    }
}

static void cut_lines(Ctx *c)
{
    Line l = {0};
    l.cap = 64;
    l.cr = mem_alloc(sizeof *l.cr * (size_t)l.cap);
    l.s = mem_alloc(sizeof *l.s * (size_t)l.cap);
    for (int a = 0; a < 3; a++) {
        int u = (a + 1) % 3, w = (a + 2) % 3;
        for (int iw = 0; iw < c->nv[w]; iw++)
            for (int iu = 0; iu < c->nv[u]; iu++) {
                double p[3];
                p[u] = c->x[u][iu];
                p[w] = c->x[w][iw];
                p[a] = 0;
                int64_t v0 = iu * c->sv[u] + iw * c->sv[w];
                line_crossings(c, &l, a, p);
                mark_vertex_crossings(c, &l, a, iu * c->sv[u] + iw * c->sv[w]);
                int lo = 0, any = l.ncr > 0;
                for (int i = 0; i < c->n[a] && !any; i++)
                    any = c->cls[v0 + i * c->sv[a]] != c->cls[v0 + (i + 1) * c->sv[a]];
                if (!any) continue;
                for (int i = 0; i < c->n[a]; i++) edge_cut(c, &l, a, i, v0 + i * c->sv[a], &lo);
            }
    }
    free(l.cr);
    free(l.s);
}

/* ---- step 3: snapping ---- */

static double edge_len(const Ctx *c, const CutPt *p, double *xlo, double *xhi)
{
    int64_t v = p->key / 3;
    int a = (int)(p->key % 3), ijk[3];
    cut_vertex_ijk(c, v, ijk);
    *xlo = c->x[a][ijk[a]];
    *xhi = c->x[a][ijk[a] + 1];
    return *xhi - *xlo;
}

static int64_t cell_corner(const Ctx *c, int64_t v0, int q)
{
    return v0 + (q & 1) * c->sv[0] + ((q >> 1) & 1) * c->sv[1] + (q >> 2) * c->sv[2];
}

/* Fluid corners of cut cells that lie on the surface seen only along a
   cell or face diagonal (a box edge or corner on grid lines: no grid
   line through the vertex crosses the surface) turn solid too: the point
   snap x (diagonal) towards each solid corner of the cell is tested. */
/* Does corner q of cell (i, j, k) lie on the surface as seen towards a
   corner of class `to`: is the point snap x the way from q to such a
   corner of class `to` too (fluid when to is 1)? */
static int diagonal_touch(const Ctx *c, int i, int j, int k, const int64_t cv[8], int q, int to)
{
    const int ijk[3] = {i + (q & 1), j + ((q >> 1) & 1), k + (q >> 2)};
    /* no probe can reach the surface from a vertex farther from it than
       the longest probe, snap x the cell's diagonal; |level| is at most
       the distance (geometry.h), so it rules such vertices out with one
       query per vertex instead of one per probe */
    float *lv = &c->level[cv[q]];
    double diag2 = 0, x[3];
    for (int a = 0; a < 3; a++) {
        double h = c->x[a][(a == 0 ? i : a == 1 ? j : k) + 1] - c->x[a][a == 0 ? i : a == 1 ? j : k];
        diag2 += h * h;
        x[a] = c->x[a][ijk[a]];
    }
    if (*lv < 0) *lv = (float)fabs(geometry_level(c->g, x));
    if (*lv > 2 * c->snap * sqrt(diag2)) return 0;
    for (int r = 0; r < 8; r++) {
        if (c->cls[cv[r]] != to) continue;
        const int rk[3] = {i + (r & 1), j + ((r >> 1) & 1), k + (r >> 2)};
        for (int a = 0; a < 3; a++) x[a] = c->x[a][ijk[a]] + c->snap * (c->x[a][rk[a]] - c->x[a][ijk[a]]);
        if (geometry_fluid(c->g, x) == to) return 1;
    }
    return 0;
}

static size_t snap_diagonal(Ctx *c, int64_t **list, size_t nl, size_t *lcap)
{
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t v0 = i + c->nv[0] * (j + (int64_t)c->nv[1] * k), cv[8];
                int nf = 0, ns = 0;
                for (int q = 0; q < 8; q++) {
                    cv[q] = cell_corner(c, v0, q);
                    nf += c->cls[cv[q]] == 1;
                    ns += c->cls[cv[q]] == 0;
                }
                if (!nf || !ns) continue;
                for (int q = 0; q < 8; q++) {
                    if (c->cls[cv[q]] != 1 || !diagonal_touch(c, i, j, k, cv, q, 0)) continue;
                    c->cls[cv[q]] = 2;
                    mem_grow((void **)list, lcap, nl + 1, sizeof **list);
                    (*list)[nl++] = cv[q];
                }
            }
    return nl;
}

/* Does vertex v lie on the surface as the cells around it see it: do
   probes PROBE x snap of the way from v towards the centres of its eight
   cells disagree?  Beyond a side of the box the probe mirrors the cell
   inside, so a face of the geometry on a side of the box is seen too. */
static int probe_differs(const Ctx *c, int64_t v)
{
    int ijk[3], seen = -1;
    cut_vertex_ijk(c, v, ijk);
    double eta = fmin(PROBE * c->snap, 0.25);
    for (int q = 0; q < 8; q++) {
        double x[3];
        for (int a = 0; a < 3; a++) {
            int up = (q >> a) & 1, lo = ijk[a] - up, in = lo < 0 ? 0 : lo >= c->n[a] ? c->n[a] - 1 : lo;
            double w = c->x[a][in + 1] - c->x[a][in];
            x[a] = c->x[a][ijk[a]] + probe_w[a] * eta * (up ? -w : w) / 2;
        }
        int f = geometry_fluid(c->g, x);
        if (seen >= 0 && f != seen) return 1;
        seen = f;
    }
    return 0;
}

/* Does vertex v lie on the surface to snap x the diagonal of its largest
   cell, as far as |level| (at most the distance) tells? */
static int level_near(const Ctx *c, int64_t v)
{
    int ijk[3];
    cut_vertex_ijk(c, v, ijk);
    double x[3], d2 = 0;
    for (int a = 0; a < 3; a++) {
        int lo = ijk[a] > 0 ? ijk[a] - 1 : 0, hi = ijk[a] < c->n[a] ? ijk[a] + 1 : c->n[a];
        double w = fmax(c->x[a][ijk[a]] - c->x[a][lo], c->x[a][hi] - c->x[a][ijk[a]]);
        d2 += w * w;
        x[a] = c->x[a][ijk[a]];
    }
    float *lv = &c->level[v];
    if (*lv < 0) *lv = (float)fabs(geometry_level(c->g, x));
    return *lv <= 2 * c->snap * sqrt(d2);
}

/* Is vertex v an end of a grid edge whose ends differ? */
static int mixed_end(const Ctx *c, int64_t v)
{
    int ijk[3];
    cut_vertex_ijk(c, v, ijk);
    for (int a = 0; a < 3; a++)
        for (int dir = -1; dir <= 1; dir += 2)
            if (ijk[a] + dir >= 0 && ijk[a] + dir < c->nv[a] && !c->cls[v + dir * c->sv[a]] != !c->cls[v]) return 1;
    return 0;
}

/* The search of probe_corners: vertices seen, and the queue of those
   on the surface whose neighbours are still to be looked at. */
typedef struct Probe {
    char *seen;
    int64_t *queue;
    size_t nq, qcap;
} Probe;

static void probe_push(Probe *P, int64_t v)
{
    P->seen[v] = 1;
    mem_grow((void **)&P->queue, &P->qcap, P->nq + 1, sizeof *P->queue);
    P->queue[P->nq++] = v;
}

/* Vertex w joins the vertices on the surface when its cells' probes
   disagree (near: only when it lies on the surface to the snap distance
   as well): a fluid one joins the snapping list, a solid one is marked. */
static size_t probe_try(Ctx *c, Probe *P, int64_t w, int near, int64_t **list, size_t nl, size_t *lcap)
{
    if (P->seen[w] || (near && !level_near(c, w)) || !probe_differs(c, w)) return nl;
    if (c->cls[w] == 1) {
        c->cls[w] = 2;
        mem_grow((void **)list, lcap, nl + 1, sizeof **list);
        (*list)[nl++] = w;
    } else {
        c->onsurf[w] = 1;
    }
    probe_push(P, w);
    return nl;
}

/* Vertices on the surface that no crossing meets and no diagonal shows:
   a corner of the geometry whose two faces lie in the grid planes through
   the vertex (the rim of a slab thinner than a cell on a grid line, a
   prism's edge on a grid line), so every grid line through it lies in a
   face.  They are searched among the grid neighbours of the vertices
   already known on the surface, outwards while new ones turn up: a fluid
   one joins the snapping list, a solid one is marked; either way each of
   its cells then judges it by its own probe (local_masks).  The search
   starts as well from the ends of edges whose ends differ that lie on
   the surface to the snap distance: a vertex on a cone's rim or a
   prism's corner is solid for both flow sides (a point on a surface
   counts as solid), and so has fluid neighbours, and is found by
   snapping, on one side only; both sides have to find it for their
   cells to see complementary corners. */
static size_t probe_corners(Ctx *c, int64_t **list, size_t nl, size_t *lcap)
{
    int64_t nvt = c->sv[2] * c->nv[2];
    Probe P = {mem_calloc((size_t)nvt, 1), NULL, 0, 0};
    for (int64_t v = 0; v < nvt; v++)
        if (c->onsurf[v] || c->cls[v] == 2) probe_push(&P, v);
    for (int64_t v = 0; v < nvt; v++)
        if (mixed_end(c, v)) nl = probe_try(c, &P, v, 1, list, nl, lcap);
    for (size_t h = 0; h < P.nq; h++) {
        int ijk[3];
        cut_vertex_ijk(c, P.queue[h], ijk);
        for (int a = 0; a < 3; a++)
            for (int dir = -1; dir <= 1; dir += 2)
                if (ijk[a] + dir >= 0 && ijk[a] + dir < c->nv[a])
                    nl = probe_try(c, &P, P.queue[h] + dir * c->sv[a], 0, list, nl, lcap);
    }
    free(P.queue);
    free(P.seen);
    return nl;
}

static void snap(Ctx *c)
{
    int64_t *list = NULL;
    size_t nl = 0, lcap = 0;
    for (size_t i = 0; i < c->cap; i++) {
        CutPt *p = &c->tab[i];
        if (p->key < 0) continue;
        double xlo, xhi, h = edge_len(c, p, &xlo, &xhi);
        int64_t v = p->key / 3, w = v + c->sv[p->key % 3];
        int64_t f = c->cls[v] ? v : w;
        if (fabs(p->s - (f == v ? xlo : xhi)) < c->snap * h && c->cls[f] == 1) {
            c->cls[f] = 2;
            mem_grow((void **)&list, &lcap, nl + 1, sizeof *list);
            list[nl++] = f;
        }
    }
    /* fluid vertices that a crossing meets (mark_vertex_crossings) */
    for (int64_t v = 0; v < c->sv[2] * c->nv[2] && c->snap > 0; v++)
        if (c->onsurf[v] && c->cls[v] == 1) {
            c->cls[v] = 2;
            mem_grow((void **)&list, &lcap, nl + 1, sizeof *list);
            list[nl++] = v;
        }
    if (c->snap > 0) {
        nl = snap_diagonal(c, &list, nl, &lcap);
        nl = probe_corners(c, &list, nl, &lcap);
    }
    for (size_t i = 0; i < c->cap; i++) {
        CutPt *p = &c->tab[i];
        if (p->key < 0) continue;
        int64_t v = p->key / 3, w = v + c->sv[p->key % 3];
        if (c->cls[v] == 2 || c->cls[w] == 2) p->dead = 1;
    }
    for (size_t k = 0; k < nl; k++) {
        c->cls[list[k]] = 0;
        c->onsurf[list[k]] = 1;
    }
    c->st->nsnap += (int)nl;
    for (size_t k = 0; k < nl; k++) {
        int ijk[3];
        cut_vertex_ijk(c, list[k], ijk);
        for (int a = 0; a < 3; a++)
            for (int dir = -1; dir <= 1; dir += 2) {
                int ia = ijk[a] + dir;
                if (ia < 0 || ia >= c->nv[a]) continue;
                int64_t w = list[k] + dir * c->sv[a];
                if (c->cls[w] != 1) continue;
                int64_t lower = dir > 0 ? list[k] : w;
                CutPt *p = cut_insert(c, 3 * lower + a);
                p->at = dir > 0 ? 0 : 1;
                p->s = c->x[a][ijk[a]];
                double so, h = fabs(c->x[a][ia] - c->x[a][ijk[a]]);
                int lf;
                if (offset_cut(c, a, lower, dir < 0, &so, &lf) && fabs(so - p->s) >= c->snap * h) {
                    p->at = -1;
                    p->s = fmin(fmax(so, fmin(c->x[a][ia], p->s)), fmax(c->x[a][ia], p->s));
                    p->leaf = lf;
                }
            }
    }
    free(list);
    /* points on an end: on the solid end as snapping puts them, and on
       the fluid end where an extrapolated crossing (offset_cut) settled
       there; either way the end's own mesh point */
    for (size_t i = 0; i < c->cap; i++) {
        CutPt *p = &c->tab[i];
        if (p->key < 0 || p->dead || p->at >= 0) continue;
        double xlo, xhi, h = edge_len(c, p, &xlo, &xhi);
        int64_t v = p->key / 3;
        double xs = c->cls[v] ? xhi : xlo, xf = c->cls[v] ? xlo : xhi;
        if (fabs(p->s - xs) < c->snap * h || p->s == xf) {
            int up = fabs(p->s - xs) < c->snap * h ? c->cls[v] != 0 : !c->cls[v];
            p->at = (signed char)up;
            p->s = up ? xhi : xlo;
            c->onsurf[up ? v + c->sv[p->key % 3] : v] = 1;
            c->st->nsnap++;
        }
    }
}

/* ---- step 5: boundary loops (step 4, grid faces: cut_face.c) ---- */

/* Adds the sides of polygon p of a cell, reversed to run against the
   cell's outward normal; out = 1 when p's normal points out of the cell.
   Sides that two of the cell's faces share cancel (cancel_spurs): what
   is left is where the cell's grid-face polygons end, its boundary.  So
   a corner on the surface bounds the fluid wherever the face beside it
   holds no fluid, whether or not a cut point lies on it. */
static void poly_segments(const Poly *p, int out, Seg *s, int *ns)
{
    for (int i = 0; i < p->n; i++) {
        int j = (i + 1) % p->n;
        if (p->pt[i] == p->pt[j] || *ns >= MAXSIDE) continue;
        s[(*ns)++] = out ? (Seg){p->pt[j], p->pt[i], p->leaf[j], p->leaf[i]}
                         : (Seg){p->pt[i], p->pt[j], p->leaf[i], p->leaf[j]};
    }
}

/* Cancels segment pairs running both ways (zero-area spurs). */
static int cancel_spurs(Seg *s, int ns)
{
    for (int i = 0; i < ns; i++)
        for (int j = i + 1; j < ns; j++)
            if (s[i].a == s[j].b && s[i].b == s[j].a) {
                s[j] = s[--ns];
                s[i] = s[--ns];
                i--;
                break;
            }
    return ns;
}

typedef struct Loop {
    int n;
    int pt[MAXS], leaf[MAXS];
} Loop;

/* Chains the segments into simple loops: walking from a segment, a point
   met a second time closes the loop from its first visit (so a pinch
   point, where two loops touch, splits them).  Returns the loop count. */
static int chain(const Seg *s, int ns, Loop *loops, int maxl)
{
    char used[MAXS] = {0};
    int nl = 0;
    for (int st = 0; st < ns; st++) {
        if (used[st]) continue;
        int path[MAXS + 1], pl[MAXS + 1], np = 0, r = st;
        used[st] = 1;
        path[np] = s[st].a, pl[np++] = s[st].la;
        for (;;) {
            int b = s[r].b, lb = s[r].lb, k = 0;
            while (k < np && path[k] != b) k++;
            if (k < np) {
                if (nl < maxl) {
                    Loop *L = &loops[nl++];
                    L->n = np - k;
                    memcpy(L->pt, path + k, sizeof(int) * (size_t)L->n);
                    memcpy(L->leaf, pl + k, sizeof(int) * (size_t)L->n);
                }
                np = k;
                if (np == 0) break;
            }
            path[np] = b, pl[np++] = lb;
            r = -1;
            for (int q = 0; q < ns && r < 0; q++)
                if (!used[q] && s[q].a == b) r = q;
            if (r < 0) break;
            used[r] = 1;
        }
    }
    return nl;
}

/* The leaf of a boundary face: its points' leaves when every point has
   one and they agree, else the leaf nearest to its centre.  A point
   without a leaf is a grid vertex on the surface; a face on a grid plane
   may have its only tagged points on the edge where another surface meets
   it (a pipe's wall between its mouth, off the grid planes, and the next
   grid plane), and those points' leaf is not the face's. */
static int face_leaf(const Ctx *c, const int *leaf, int n, const double ctr[3])
{
    int lf = -1;
    for (int i = 0; i < n; i++) {
        if (leaf[i] < 0 || (lf >= 0 && leaf[i] != lf)) return geometry_nearest_leaf(c->g, ctr);
        lf = leaf[i];
    }
    return lf >= 0 ? lf : geometry_nearest_leaf(c->g, ctr);
}

void cut_push_wall(Ctx *c, int patch, const double n[3])
{
    mem_grow((void **)&c->wall, &c->wall_cap, c->nwall + 1, sizeof *c->wall);
    WallFace *w = &c->wall[c->nwall++];
    w->patch = patch;
    memcpy(w->n, n, sizeof w->n);
}

/* Adds the tetrahedra of the fan of polygon pt (about its first point;
   rev: the polygon's normal points into the cell) on the cell's reference
   point to the cell's volume: the divergence theorem, exact for any
   closed surface of planar polygons. */
static void poly_volume(Ctx *c, const int *pt, int n, int rev)
{
    for (int i = 1; i + 1 < n; i++) {
        double u[3], w[3], z[3], x[3];
        const double *a = cut_ptx(c, pt[0]), *b = cut_ptx(c, pt[rev ? i + 1 : i]), *d = cut_ptx(c, pt[rev ? i : i + 1]);
        for (int k = 0; k < 3; k++) {
            u[k] = a[k] - c->vref[k];
            w[k] = b[k] - c->vref[k];
            z[k] = d[k] - c->vref[k];
        }
        geom_cross(w, z, x);
        c->vacc += geom_dot(u, x) / 6;
    }
}

/* An immersed boundary face of cell `cell`. */
void cut_wall_face(Ctx *c, const int *pt, const int *leaf, int n, int cell)
{
    double S[3], C[3], nv[3];
    geom_face(c->b.points, pt, n, S, C);
    int lf = face_leaf(c, leaf, n, C);
    int patch = c->npatch_grid + c->g->leaves[lf].surface;
    meshbuild_face(&c->b, pt, n, cell, -1, patch);
    geometry_normal(c->g, lf, C, nv);
    double ln = geom_norm(nv), la = geom_norm(S);
    if (!(fabs(ln - 1) < 1e-6) && la > 0)
        /* no usable surface normal (a flattened leaf whose nearest face is
           parallel to the section plane): the face's own normal */
        for (int k = 0; k < 3; k++) nv[k] = S[k] / la;
    cut_push_wall(c, patch, nv);
    c->st->area_boundary += geom_norm(S);
    c->st->nboundary++;
}

/* An immersed boundary face of the cut cell being built, with its part
   of the cell's volume. */
static void add_wall(Ctx *c, const int *pt, const int *leaf, int n, int cell)
{
    cut_wall_face(c, pt, leaf, n, cell);
    poly_volume(c, pt, n, 0);
}

static void loop_centroid(const Ctx *c, const Loop *L, double m[3])
{
    m[0] = m[1] = m[2] = 0;
    for (int i = 0; i < L->n; i++)
        for (int k = 0; k < 3; k++) m[k] += cut_ptx(c, L->pt[i])[k];
    for (int k = 0; k < 3; k++) m[k] /= L->n;
}

/* Newell normal (unnormalised) of a loop about m. */
static void loop_normal(const Ctx *c, const Loop *L, const double m[3], double N[3])
{
    N[0] = N[1] = N[2] = 0;
    for (int i = 0; i < L->n; i++) {
        const double *p = cut_ptx(c, L->pt[i]), *q = cut_ptx(c, L->pt[(i + 1) % L->n]);
        double a[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
        double b[3] = {q[0] - m[0], q[1] - m[1], q[2] - m[2]}, x[3];
        geom_cross(a, b, x);
        for (int k = 0; k < 3; k++) N[k] += x[k];
    }
}

static int loop_planar(const Ctx *c, const Loop *L, const double m[3])
{
    double N[3], size = 0;
    loop_normal(c, L, m, N);
    double nn = geom_norm(N);
    if (!(nn > 0)) return 0;
    for (int i = 0; i < L->n; i++) {
        const double *p = cut_ptx(c, L->pt[i]);
        double d[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
        size = fmax(size, geom_norm(d));
    }
    for (int i = 0; i < L->n; i++) {
        const double *p = cut_ptx(c, L->pt[i]);
        double d[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
        if (fabs(geom_dot(d, N)) / nn > PLANAR_TOL * size) return 0;
    }
    return 1;
}

/* Adds the tetrahedron (r, a, b, d) to volume *v and moment mo. */
static void tet_add(const double r[3], const double *a, const double *b, const double *d, double *v,
                    double mo[3])
{
    double u[3], w[3], z[3], x[3];
    for (int k = 0; k < 3; k++) u[k] = a[k] - r[k], w[k] = b[k] - r[k], z[k] = d[k] - r[k];
    geom_cross(w, z, x);
    double t = geom_dot(u, x) / 6;
    *v += t;
    for (int k = 0; k < 3; k++) mo[k] += t * (r[k] + a[k] + b[k] + d[k]) / 4;
}

/* Volume and moment (about r, the average of their points, returned)
   of the tetrahedra of the cell's grid-face polygons (pu outward, pl
   inward), fanned about their first points. */
static void polys_moment(const Ctx *c, const Poly *pl, const Poly *pu, double r[3], double *v, double mo[3])
{
    int np = 0;
    r[0] = r[1] = r[2] = mo[0] = mo[1] = mo[2] = *v = 0;
    for (int a = 0; a < 3; a++)
        for (int h = 0; h < 2; h++) {
            const Poly *p = h ? &pu[a] : &pl[a];
            for (int i = 0; i < p->n; i++, np++)
                for (int k = 0; k < 3; k++) r[k] += cut_ptx(c, p->pt[i])[k];
        }
    for (int k = 0; k < 3 && np; k++) r[k] /= np;
    for (int a = 0; a < 3; a++)
        for (int h = 0; h < 2; h++) {
            const Poly *p = h ? &pu[a] : &pl[a];
            for (int i = 1; i + 1 < p->n; i++)
                tet_add(r, cut_ptx(c, p->pt[0]), cut_ptx(c, p->pt[h ? i : i + 1]), cut_ptx(c, p->pt[h ? i + 1 : i]), v,
                        mo);
        }
}

/* Pyramid (triangle centroid - o) . S of triangle (a, b, d): positive
   when the triangle faces away from o. */
static double pyramid(const double *a, const double *b, const double *d, const double o[3])
{
    double u[3], v[3], S[3], r[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = d[k] - a[k];
        r[k] = (a[k] + b[k] + d[k]) / 3 - o[k];
    }
    geom_cross(u, v, S);
    return geom_dot(r, S);
}

/* The triangulation of loop L (by its own points) whose smallest pyramid
   on o is largest: dynamic programming over sub-polygons i..j.  Writes
   the split point of each sub-polygon into split and returns that
   smallest pyramid. */
static double best_triangulation(const Ctx *c, const Loop *L, const double o[3], int split[MAXS][MAXS])
{
    static const double none = INFINITY;
    double q[MAXS][MAXS];
    int n = L->n;
    for (int len = 1; len < n; len++)
        for (int i = 0; i + len < n; i++) {
            int j = i + len;
            q[i][j] = len == 1 ? none : -INFINITY;
            for (int k = i + 1; k < j; k++) {
                double t = pyramid(cut_ptx(c, L->pt[i]), cut_ptx(c, L->pt[k]), cut_ptx(c, L->pt[j]), o);
                t = fmin(t, fmin(q[i][k], q[k][j]));
                if (t > q[i][j]) q[i][j] = t, split[i][j] = k;
            }
        }
    return q[0][n - 1];
}

static void emit_split(Ctx *c, const Loop *L, int split[MAXS][MAXS], int i, int j, int cell)
{
    if (j - i < 2) return;
    int k = split[i][j];
    int tri[3] = {L->pt[i], L->pt[k], L->pt[j]}, lf[3] = {L->leaf[i], L->leaf[k], L->leaf[j]};
    add_wall(c, tri, lf, 3, cell);
    emit_split(c, L, split, i, k, cell);
    emit_split(c, L, split, k, j, cell);
}

/* Tetrahedra on r of a triangulation (split) of sub-polygon i..j. */
static void split_moment(const Ctx *c, const Loop *L, int split[MAXS][MAXS], int i, int j, const double r[3],
                         double *v, double mo[3])
{
    if (j - i < 2) return;
    int k = split[i][j];
    tet_add(r, cut_ptx(c, L->pt[i]), cut_ptx(c, L->pt[k]), cut_ptx(c, L->pt[j]), v, mo);
    split_moment(c, L, split, i, k, r, v, mo);
    split_moment(c, L, split, k, j, r, v, mo);
}

static double split_quality(const Ctx *c, const Loop *L, int split[MAXS][MAXS], int i, int j,
                            const double o[3])
{
    if (j - i < 2) return INFINITY;
    int k = split[i][j];
    double q = pyramid(cut_ptx(c, L->pt[i]), cut_ptx(c, L->pt[k]), cut_ptx(c, L->pt[j]), o);
    return fmin(q, fmin(split_quality(c, L, split, i, k, o), split_quality(c, L, split, k, j, o)));
}

/* Fan of loop L about m: its tetrahedra on r added to v, mo. */
static void fan_moment(const Ctx *c, const Loop *L, const double m[3], const double r[3], double *v,
                       double mo[3])
{
    for (int i = 0; i < L->n; i++) tet_add(r, m, cut_ptx(c, L->pt[i]), cut_ptx(c, L->pt[(i + 1) % L->n]), v, mo);
}

/* A planar loop is one face; any other a fan of triangles about its
   centroid, unless some of those triangles would face into the cell (a
   saddle-shaped loop in a thin cell) and a triangulation by the loop's
   own points does better.  Triangles are judged by their pyramids on the
   centroid of the cell they close, as checkMesh judges face pyramids;
   the cell's other faces have volume vb and moment mb about r.  The best
   triangulation depends on that centroid, which depends on the
   triangulation, so the choice is repeated a few times. */
static void emit_loop(Ctx *c, const Loop *L, int cell, const double r[3], double vb, const double mb[3])
{
    double m[3];
    if (L->n < 3) return;
    loop_centroid(c, L, m);
    if (L->n == 3 || loop_planar(c, L, m)) {
        add_wall(c, L->pt, L->leaf, L->n, cell);
        return;
    }
    double v = vb, mo[3] = {mb[0], mb[1], mb[2]}, o[3], q0 = INFINITY;
    fan_moment(c, L, m, r, &v, mo);
    for (int k = 0; k < 3; k++) o[k] = v > 0 ? mo[k] / v : r[k];
    for (int i = 0; i < L->n; i++)
        q0 = fmin(q0, pyramid(m, cut_ptx(c, L->pt[i]), cut_ptx(c, L->pt[(i + 1) % L->n]), o));
    int split[MAXS][MAXS], best[MAXS][MAXS], have = 0;
    double qb = q0;
    for (int it = 0; it < 4 && !(qb > 0); it++) {
        best_triangulation(c, L, o, split);
        v = vb;
        memcpy(mo, mb, sizeof mo);
        split_moment(c, L, split, 0, L->n - 1, r, &v, mo);
        for (int k = 0; k < 3; k++) o[k] = v > 0 ? mo[k] / v : r[k];
        double q = split_quality(c, L, split, 0, L->n - 1, o);
        if (q > qb) qb = q, have = 1, memcpy(best, split, sizeof best);
    }
    if (have) {
        emit_split(c, L, best, 0, L->n - 1, cell);
        return;
    }
    int mp = meshbuild_point(&c->b, m);
    for (int i = 0; i < L->n; i++) {
        int j = (i + 1) % L->n;
        /* the centre point takes the rim's leaf where the rim agrees:
           face_leaf reads a point without a leaf as a grid vertex */
        int same = L->leaf[i] == L->leaf[j] ? L->leaf[i] : -1;
        int tri[3] = {mp, L->pt[i], L->pt[j]}, lf[3] = {same, L->leaf[i], L->leaf[j]};
        add_wall(c, tri, lf, 3, cell);
    }
}

/* Angle of p about axis (o, d) in the frame e1, e2, relative to t0, in
   [0, 2 pi). */
static double angle(const double *p, const double o[3], const double e1[3], const double e2[3], double t0)
{
    double r[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
    double t = atan2(geom_dot(r, e2), geom_dot(r, e1)) - t0;
    while (t < 0) t += 2 * M_PI;
    while (t >= 2 * M_PI) t -= 2 * M_PI;
    return t;
}

/* Triangle t (0..5) of the band joining rims A and B: steps are 0 (along
   A) or 1 (along B reversed, which winds round the axis like A); j0 is
   the point of B reversed facing A's first point. */
static void band_tri(const Loop *A, const Loop *B, int j0, const char *seq, int t, int tri[3], int lf[3])
{
    int i = 0, j = 0;
    for (int s = 0; s < t; s++) seq[s] ? j++ : i++;
    int b0 = (3 - (j0 + j) % 3) % 3, b1 = (3 - (j0 + j + 1) % 3) % 3, a0 = i % 3, a1 = (i + 1) % 3;
    if (!seq[t]) {
        tri[0] = A->pt[a0], tri[1] = A->pt[a1], tri[2] = B->pt[b0];
        lf[0] = A->leaf[a0], lf[1] = A->leaf[a1], lf[2] = B->leaf[b0];
    } else {
        tri[0] = B->pt[b1], tri[1] = B->pt[b0], tri[2] = A->pt[a0];
        lf[0] = B->leaf[b1], lf[1] = B->leaf[b0], lf[2] = A->leaf[a0];
    }
}

/* Smallest face pyramid of the band on the centroid of the cell it
   closes (grid faces: volume v0, moment m0 about r). */
static double band_quality(const Ctx *c, const Loop *A, const Loop *B, int j0, const char *seq,
                           const double r[3], double v0, const double m0[3])
{
    double v = v0, mo[3] = {m0[0], m0[1], m0[2]}, o[3], q = INFINITY;
    int tri[6][3], lf[3];
    for (int t = 0; t < 6; t++) {
        band_tri(A, B, j0, seq, t, tri[t], lf);
        tet_add(r, cut_ptx(c, tri[t][0]), cut_ptx(c, tri[t][1]), cut_ptx(c, tri[t][2]), &v, mo);
    }
    if (!(v > 0)) return -INFINITY;
    for (int k = 0; k < 3; k++) o[k] = mo[k] / v;
    for (int t = 0; t < 6; t++)
        q = fmin(q, pyramid(cut_ptx(c, tri[t][0]), cut_ptx(c, tri[t][1]), cut_ptx(c, tri[t][2]), o));
    return q;
}

/* The body-diagonal case: joins triangle loops A and B (normals facing
   each other) by a band of six triangles, each on one rim edge.  The
   band zips the rims in order of angle about the axis through their
   centroids; when one of its triangles would face into the cell (a
   skewed cell), every other zip (3 alignments x 20 orders) is tried and
   the one with the largest smallest pyramid kept.  Returns 0 when the
   loops do not wind as expected (the caller then keeps them apart). */
static int tunnel(Ctx *c, const Loop *A, const Loop *B, const Poly *pl, const Poly *pu, int cell)
{
    double ca[3], cb[3], na[3], nb[3], d[3], e1[3], e2[3];
    loop_centroid(c, A, ca);
    loop_centroid(c, B, cb);
    loop_normal(c, A, ca, na);
    loop_normal(c, B, cb, nb);
    for (int k = 0; k < 3; k++) d[k] = cb[k] - ca[k];
    if (!(geom_dot(na, d) > 0) || !(geom_dot(nb, d) < 0)) return 0;
    double dn = geom_norm(d);
    for (int k = 0; k < 3; k++) d[k] /= dn;
    int ax = fabs(d[0]) < fabs(d[1]) ? (fabs(d[0]) < fabs(d[2]) ? 0 : 2) : (fabs(d[1]) < fabs(d[2]) ? 1 : 2);
    double ref[3] = {0, 0, 0};
    ref[ax] = 1;
    geom_cross(d, ref, e1);
    double en = geom_norm(e1);
    for (int k = 0; k < 3; k++) e1[k] /= en;
    geom_cross(d, e1, e2);
    double t0 = angle(cut_ptx(c, A->pt[0]), ca, e1, e2, 0);
    double al[4], be[4], braw[3];
    for (int i = 0; i < 3; i++) al[i] = angle(cut_ptx(c, A->pt[i]), ca, e1, e2, t0);
    al[3] = 2 * M_PI;
    if (!(al[1] < al[2])) return 0;
    /* B reversed runs the same way round as A; start at its largest angle */
    int j0 = 0;
    for (int j = 0; j < 3; j++) {
        braw[j] = angle(cut_ptx(c, B->pt[(3 - j) % 3]), ca, e1, e2, t0);
        if (braw[j] > braw[j0]) j0 = j;
    }
    for (int j = 0; j < 4; j++) be[j] = j == 0 ? braw[j0] - 2 * M_PI : braw[(j0 + j) % 3];
    if (!(be[1] < be[2])) return 0;
    char seq[6];
    for (int i = 0, j = 0, t = 0; t < 6; t++) {
        seq[t] = (char)!(j == 3 || (i < 3 && al[i + 1] < be[j + 1]));
        seq[t] ? j++ : i++;
    }
    double r[3], v0, m0[3];
    polys_moment(c, pl, pu, r, &v0, m0);
    double best = band_quality(c, A, B, j0, seq, r, v0, m0);
    if (!(best > 0))
        for (int jj = 0; jj < 3; jj++)
            for (int bits = 0; bits < 64; bits++) {
                char sq[6];
                int na_ = 0;
                for (int t = 0; t < 6; t++) na_ += !(sq[t] = (char)((bits >> t) & 1));
                if (na_ != 3) continue;
                double q = band_quality(c, A, B, jj, sq, r, v0, m0);
                if (q > best) best = q, j0 = jj, memcpy(seq, sq, sizeof seq);
            }
    for (int t = 0; t < 6; t++) {
        int tri[3], lf[3];
        band_tri(A, B, j0, seq, t, tri, lf);
        add_wall(c, tri, lf, 3, cell);
    }
    c->st->ntunnel++;
    return 1;
}

/* ---- step 6: cells ---- */


/* Corners on the surface [our rule, doc/theory.md §6].  Snapping makes
   every vertex on the surface solid for the whole grid, which is right
   for the cells on the solid side of the surface there but not for those
   on its fluid side: a face of the geometry on a grid plane would lose
   the fluid next to it (the cells along a cylinder's cap on a grid plane
   would be chamfered to wedges), and flow inside a grid-aligned box
   would lose its edges and corners.  So each cell decides for itself
   whether its corners on the surface are fluid, by testing a point a
   little way (PROBE x the way) towards its centre: the cells on either
   side of a surface through a vertex see it on their own side, and the
   two flow sides of one geometry see complementary corners.  A grid face
   whose two cells see different fluid corners is split: the part both
   cells see is their shared face, the rest is a wall of the cell that
   sees it (the cap of the cylinder).  Before that, solid vertices lying
   on the surface but met by no grid line crossing (a box corner on a
   grid vertex) are found by testing the point snap x the way towards
   each fluid corner of every cell with fluid and solid corners. */
static void surface_corners(Ctx *c)
{
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t v0 = i + c->nv[0] * (j + (int64_t)c->nv[1] * k), cv[8];
                int nf = 0, nb = 0, ns;
                for (int q = 0; q < 8; q++) {
                    cv[q] = cell_corner(c, v0, q);
                    nf += c->cls[cv[q]] == 1;
                    nb += !c->cls[cv[q]] && c->onsurf[cv[q]];
                }
                ns = 8 - nf - nb;
                /* every cell with fluid and solid corners, as snap_diagonal
                   tests the fluid ones: the two flow sides of a geometry
                   then find the same vertices (a box corner on a grid
                   vertex whose grid lines all run along its edges) */
                if (!nf || !ns) continue;
                for (int q = 0; q < 8; q++)
                    if (!c->cls[cv[q]] && !c->onsurf[cv[q]] && diagonal_touch(c, i, j, k, cv, q, 1))
                        c->onsurf[cv[q]] = 1;
            }
}

/* Is corner q of cell (i, j, k), a vertex on the surface, fluid for
   that cell? */
static int local_fluid(const Ctx *c, int i, int j, int k, int q)
{
    const int ijk[3] = {i, j, k};
    double eta = fmin(PROBE * c->snap, 0.25), x[3];
    for (int a = 0; a < 3; a++) {
        double lo = c->x[a][ijk[a]], hi = c->x[a][ijk[a] + 1], v = (q >> a) & 1 ? hi : lo;
        x[a] = v + probe_w[a] * eta * ((lo + hi) / 2 - v);
    }
    return geometry_fluid(c->g, x);
}

/* Each cell's fluid corners: the fluid vertices, and the vertices on the
   surface whose probe towards the cell's centre is fluid. */
static void local_masks(Ctx *c)
{
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t v0 = cut_cell_base(c, i, j, k);
                int m = 0, on = 0;
                for (int q = 0; q < 8; q++) {
                    int64_t v = cell_corner(c, v0, q);
                    if (c->cls[v]) m |= 1 << q;
                    else on |= c->onsurf[v] << q;
                }
                for (int q = 0; q < 8 && c->snap > 0; q++)
                    if ((on >> q) & 1 && local_fluid(c, i, j, k, q)) m |= 1 << q;
                c->lmask[i + c->n[0] * (j + (int64_t)c->n[1] * k)] = (unsigned char)m;
            }
}


/* The crossings (coordinates along a, ascending, at most maxn) of the
   copy of edge (p0, along a to xhi) moved by off, and the classes of its
   ends, judged snap x (edge) in, as shifted_cut judges them. */
static int copy_crossings(const Ctx *c, int a, const double p0[3], double xhi, const double off[3], double *xs,
                          int *leaf, int maxn, int f[2])
{
    double q0[3], q1[3], eta = c->snap * (xhi - p0[a]);
    for (int k = 0; k < 3; k++) q0[k] = p0[k] + off[k];
    memcpy(q1, q0, sizeof q1);
    q1[a] = xhi;
    q0[a] += eta;
    q1[a] -= eta;
    f[0] = geometry_fluid(c->g, q0);
    f[1] = geometry_fluid(c->g, q1);
    GeoCross cr[8];
    int k = geometry_crossings(c->g, q0, q1, cr, 8), n = 0;
    for (int r = 0; r < k && r < 8 && n < maxn; r++, n++) {
        xs[n] = q0[a] + cr[r].t * (q1[a] - q0[a]);
        leaf[n] = cr[r].leaf;
    }
    return n;
}

/* Does a crossing at x[0], x[1], x[2] on copies moved 1, 2 and 4 times as
   far close on an end of the edge xlo..xhi as the copies close on the
   edge?  Its distance to that end shrinks with the move (in proportion,
   or with its square root at a tangency); a crossing of the edge itself
   stays put.  Returns 0 (no), 1 (the lower end) or 2 (the upper end). */
static int closes_on_end(const double x[3], double xlo, double xhi)
{
    for (int e = 0; e < 2; e++) {
        double d[3];
        for (int k = 0; k < 3; k++) d[k] = fabs(x[k] - (e ? xhi : xlo));
        if (d[1] > END_RATE * d[0] && d[2] > END_RATE * d[1]) return e + 1;
    }
    return 0;
}

/* The point of the edge as cell (i, j, k) sees it (side_point), from
   copies of the edge moved 1, 2 and 4 times off towards the cell: each
   crossing that closes on an end as the copies close on the edge belongs
   to a surface through that end (a cone's rim or a face of the geometry
   through the grid vertex), which the cell's view of the end already
   holds; the others are the edge's own.  One of those: the point,
   extrapolated to no move.  None: the edge is of one class inside, and
   the point is the end the cell sees otherwise (the fluid or solid there
   is a sliver thinner than any move).  Several (a feature thinner than
   the edge): the one nearest the fluid end, as edge_cut keeps.  Returns
   0 when the copies do not agree on their crossings. */
static int own_point(const Ctx *c, int a, const double p0[3], double xhi, int fluid_lo, const double off0[3],
                     double *s, int *leaf)
{
    double xs[3][8], off[3] = {off0[0], off0[1], off0[2]};
    int n[3], f[3][2], lv[3][8];
    for (int k = 0; k < 3; k++) {
        n[k] = copy_crossings(c, a, p0, xhi, off, xs[k], lv[k], 8, f[k]);
        if (k && (n[k] != n[0] || f[k][0] != f[0][0] || f[k][1] != f[0][1])) return 0;
        for (int b = 0; b < 3; b++) off[b] *= 2;
    }
    int lo = 0, hi = n[0], best = -1;
    double xf = fluid_lo ? p0[a] : xhi;
    while (lo < hi) {
        double t[3] = {xs[0][lo], xs[1][lo], xs[2][lo]};
        if (closes_on_end(t, p0[a], xhi) != 1) break;
        lo++;
    }
    while (hi > lo) {
        double t[3] = {xs[0][hi - 1], xs[1][hi - 1], xs[2][hi - 1]};
        if (closes_on_end(t, p0[a], xhi) != 2) break;
        hi--;
    }
    if (lo == hi) {
        /* inside the ends' surfaces the edge is of class f ^ (lo odd) */
        int inner = f[0][0] ^ (lo & 1);
        *s = inner != fluid_lo ? p0[a] : xhi;
        *leaf = -1;
        return 1;
    }
    for (int r = lo; r < hi; r++)
        if (best < 0 || fabs(xs[0][r] - xf) < fabs(xs[0][best] - xf)) best = r;
    double t[3] = {xs[0][best], xs[1][best], xs[2][best]};
    *s = settle(c, extrapolate(t, 3), p0[a], xhi);
    *leaf = lv[0][best];
    return 1;
}

/* The point of the edge from corner q of cell (i, j, k) along a, whose
   ends the cell sees differently though neither is fluid for the grid (an
   edge in a face of the geometry on a grid plane, from a corner on it to
   one beyond its rim), from copies of the edge moved towards the cell's
   centre (own_point); where those disagree, the crossing on copies whose
   ends the cell sees like the edge's, as offset_cut finds it; on the
   solid end when no copy crosses.  The copies move SKEW times as far
   along the second axis across the edge as along the first, so that they
   do not run in a plane of the geometry through the edge (planes with
   small integer normals, a cone's side): a copy in such a plane has no
   side to see. */
static void side_point(Ctx *c, const int ijk[3], int q, int a, int fluid_lo)
{
    int64_t v = cell_corner(c, cut_cell_base(c, ijk[0], ijk[1], ijk[2]), q);
    int vi[3];
    cut_vertex_ijk(c, v, vi);
    double p0[3] = {c->x[0][vi[0]], c->x[1][vi[1]], c->x[2][vi[2]]}, xhi = c->x[a][vi[a] + 1];
    double h = xhi - p0[a], off[3] = {0, 0, 0}, s1;
    for (int b = 0; b < 3; b++)
        if (b != a)
            off[b] = ((q >> b) & 1 ? -1 : 1) * (b == (a + 2) % 3 ? SKEW : 1) * OFFSET * c->snap *
                     (c->x[b][ijk[b] + 1] - c->x[b][ijk[b]]);
    int l1 = -1, at = -1, quad = ((q >> (a + 1) % 3) & 1) | ((q >> (a + 2) % 3) & 1) << 1;
    if (!own_point(c, a, p0, xhi, fluid_lo, off, &s1, &l1) && !offset_cut(c, a, v, fluid_lo, &s1, &l1)) {
        c->st->ninconsistent++;
        at = fluid_lo ? 1 : 0;
        s1 = fluid_lo ? xhi : p0[a];
    }
    s1 = fmin(fmax(s1, p0[a]), xhi);
    if (s1 == p0[a] || s1 - p0[a] < c->snap * h) at = 0, s1 = p0[a];
    else if (s1 == xhi || xhi - s1 < c->snap * h) at = 1, s1 = xhi;
    CutPt *p = cut_entry(c, 3 * v + a);
    if (!p || p->dead) {
        p = cut_insert(c, 3 * v + a);
        p->nodef = 1;
    }
    if (p->view < 0) {
        mem_grow((void **)&c->views, &c->views_cap, c->nviews + 1, sizeof *c->views);
        memset(&c->views[c->nviews], 0, sizeof *c->views);
        p->view = (int)c->nviews++;
    }
    CutView *V = &c->views[p->view];
    V->s[quad] = s1;
    V->at[quad] = (signed char)at;
    V->leaf[quad] = l1;
    V->pt[quad] = -1;
    V->has[quad] = 1;
}

/* Each cell's own points of the edges whose ends it sees differently and
   the grid does not, or that run from a vertex on the surface (where the
   grid line's crossings need not be what the cells on either side of a
   face of the geometry through the edge see): made before any face, so
   every face meets the same points.  A vertex counts as on the surface
   when snapping or the probes found it so, or when it lies on it to the
   snap distance by the level function: both flow sides then ask the same
   cells for their views (a vertex on a cap's rim where another part
   touches the cap is met by no crossing and no probe). */
static void local_points(Ctx *c)
{
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t v0 = cut_cell_base(c, i, j, k);
                int m = c->lmask[i + c->n[0] * (j + (int64_t)c->n[1] * k)];
                if (!m || m == 255) continue;
                const int ijk[3] = {i, j, k};
                for (int q = 0; q < 8; q++)
                    for (int a = 0; a < 3; a++) {
                        int r = q | 1 << a;
                        if ((q >> a) & 1 || !(((m >> q) ^ (m >> r)) & 1)) continue;
                        int64_t vq = cell_corner(c, v0, q), vr = cell_corner(c, v0, r);
                        if (cut_find(c, 3 * vq + a) && !c->onsurf[vq] && !c->onsurf[vr] && !level_near(c, vq) &&
                            !level_near(c, vr))
                            continue;
                        side_point(c, ijk, q, a, (m >> q) & 1);
                    }
            }
}

/* Where on its edge (lower end xlo, upper xhi) a point lies. */
static double point_at(double s, int at, double xlo, double xhi)
{
    return at < 0 ? s : at ? xhi : xlo;
}

/* Does cell quad of edge (v, a) exist and see the edge's ends
   differently? */
static int quad_cuts(const Ctx *c, int64_t v, int a, int quad)
{
    int u = (a + 1) % 3, w = (a + 2) % 3, ijk[3];
    cut_vertex_ijk(c, v, ijk);
    ijk[u] -= quad & 1;
    ijk[w] -= quad >> 1;
    if (ijk[u] < 0 || ijk[w] < 0 || ijk[u] >= c->n[u] || ijk[w] >= c->n[w] || ijk[a] >= c->n[a]) return 0;
    int m = c->lmask[ijk[0] + c->n[0] * (ijk[1] + (int64_t)c->n[1] * ijk[2])];
    int q = (quad & 1) << u | (quad >> 1) << w;
    return ((m >> q) ^ (m >> (q | 1 << a))) & 1;
}

/* The cells' views of one edge settled: a view within snap x (edge) of
   the grid's point is that point, views within it of one another are one
   point, and the grid's point is dropped when every cell that cuts the
   edge has a view of its own (it would be a point no cell bounds its
   fluid with). */
static void settle_views(Ctx *c, CutPt *p)
{
    CutView *V = &c->views[p->view];
    int64_t v = p->key / 3;
    int a = (int)(p->key % 3), ijk[3];
    cut_vertex_ijk(c, v, ijk);
    double xlo = c->x[a][ijk[a]], xhi = c->x[a][ijk[a] + 1], tol = c->snap * (xhi - xlo);
    int def = !p->dead && !p->nodef, used = 0;
    double ds = point_at(p->s, p->at, xlo, xhi);
    for (int k = 0; k < 4; k++) {
        if (!V->has[k]) continue;
        double vs = point_at(V->s[k], V->at[k], xlo, xhi);
        if (def && fabs(vs - ds) <= tol) {
            V->has[k] = 0;
            continue;
        }
        for (int j = 0; j < k; j++)
            if (V->has[j] && fabs(vs - point_at(V->s[j], V->at[j], xlo, xhi)) <= tol) {
                V->s[k] = V->s[j];
                V->at[k] = V->at[j];
                V->leaf[k] = V->leaf[j];
                break;
            }
    }
    for (int k = 0; k < 4; k++) used |= !V->has[k] && quad_cuts(c, v, a, k);
    if (def && !used) p->nodef = 1;
}

static void settle_all_views(Ctx *c)
{
    for (size_t i = 0; i < c->cap; i++)
        if (c->tab[i].key >= 0 && c->tab[i].view >= 0) settle_views(c, &c->tab[i]);
}

/* The mesh point of view k of edge entry p: the vertex it lies on, or one
   point for all the edge's views at one place. */
int cut_view_point(Ctx *c, const CutPt *p, int k)
{
    CutView *V = &c->views[p->view];
    int64_t v = p->key / 3;
    int a = (int)(p->key % 3);
    if (V->at[k] >= 0) return cut_vertex_point(c, v + (V->at[k] ? c->sv[a] : 0));
    if (V->pt[k] < 0) {
        for (int j = 0; j < 4 && V->pt[k] < 0; j++)
            if (j != k && V->has[j] && V->at[j] < 0 && V->s[j] == V->s[k]) V->pt[k] = V->pt[j];
        if (V->pt[k] < 0) {
            int ijk[3];
            cut_vertex_ijk(c, v, ijk);
            double x[3] = {c->x[0][ijk[0]], c->x[1][ijk[1]], c->x[2][ijk[2]]};
            x[a] = V->s[k];
            V->pt[k] = meshbuild_point(&c->b, x);
        }
    }
    return V->pt[k];
}

/* The point that cell quad of edge key bounds its fluid with: its own
   view, else the grid's point; -1 when there is none. */
int cut_cell_point(Ctx *c, int64_t key, int quad, int *leaf)
{
    CutPt *p = cut_entry(c, key);
    if (!p || p->dead) return -1;
    if (p->view >= 0 && c->views[p->view].has[quad]) {
        *leaf = c->views[p->view].leaf[quad];
        return cut_view_point(c, p, quad);
    }
    if (p->nodef) return -1;
    *leaf = p->leaf;
    return cut_point(c, p);
}

/* The boundary loops of a cell whose grid-face polygons are pl (lower
   faces) and pu (upper faces). */
static int cell_loops(const Poly *pl, const Poly *pu, Loop *loops, int maxl)
{
    Seg s[MAXSIDE];
    int ns = 0;
    for (int a = 0; a < 3; a++) {
        poly_segments(&pl[a], 0, s, &ns);
        poly_segments(&pu[a], 1, s, &ns);
    }
    ns = cancel_spurs(s, ns);
    if (ns > MAXS) ns = MAXS; /* a cell's boundary has at most 24 */
    return chain(s, ns, loops, maxl);
}

/* Cells with fluid corners but (next to) no fluid volume: a corner on
   the surface whose probe is fluid while every edge from it is cut at
   the corner itself (a narrow wedge of fluid along the cell's diagonal,
   thinner than the snap distance along the edges).  Their grid-face
   polygons and boundary loops enclose less than DEGENERATE of the cell;
   they are dropped before any face is made, so their neighbours close
   their faces towards them with walls. */
static void drop_degenerate(Ctx *c)
{
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t ci = i + c->n[0] * (j + (int64_t)c->n[1] * k), v0 = cut_cell_base(c, i, j, k);
                int mask = c->lmask[ci];
                if (!mask || mask == 255) continue;
                Poly pl[3], pu[3];
                double vol = 1;
                for (int a = 0; a < 3; a++) {
                    cut_face_poly(c, a, v0 + c->sv[a], cut_face_bits(mask, a, 1), 0, &pu[a]);
                    cut_face_poly(c, a, v0, cut_face_bits(mask, a, 0), 1, &pl[a]);
                }
                const int ijk[3] = {i, j, k};
                for (int a = 0; a < 3; a++) vol *= c->x[a][ijk[a] + 1] - c->x[a][ijk[a]];
                Loop loops[MAXS / 3 + 1];
                int nl = cell_loops(pl, pu, loops, MAXS / 3 + 1);
                double r[3], v, mo[3];
                polys_moment(c, pl, pu, r, &v, mo);
                for (int l = 0; l < nl; l++) {
                    double m[3];
                    loop_centroid(c, &loops[l], m);
                    fan_moment(c, &loops[l], m, r, &v, mo);
                }
                if (!(v > DEGENERATE * vol)) {
                    c->lmask[ci] = 0;
                    c->st->ndegenerate++;
                }
            }
}

static void boundary_faces(Ctx *c, Poly *pl, Poly *pu, int cell, int mask)
{
    Loop loops[MAXS / 3 + 1];
    int nl = cell_loops(pl, pu, loops, MAXS / 3 + 1);
    int diag = 0;
    for (int q = 0; q < 4; q++)
        if (mask == ((1 << q) | (1 << (7 - q)))) diag = 1;
    if (diag && nl == 2 && loops[0].n == 3 && loops[1].n == 3 &&
        (tunnel(c, &loops[0], &loops[1], pl, pu, cell) || tunnel(c, &loops[1], &loops[0], pl, pu, cell)))
        return;
    /* each loop is judged with the others fanned about their centroids */
    double r[3], v0, m0[3], vf[MAXS / 3 + 1], mf[MAXS / 3 + 1][3];
    polys_moment(c, pl, pu, r, &v0, m0);
    for (int l = 0; l < nl; l++) {
        double m[3];
        loop_centroid(c, &loops[l], m);
        vf[l] = mf[l][0] = mf[l][1] = mf[l][2] = 0;
        fan_moment(c, &loops[l], m, r, &vf[l], mf[l]);
    }
    for (int l = 0; l < nl; l++) {
        double vb = v0, mb[3] = {m0[0], m0[1], m0[2]};
        for (int q = 0; q < nl; q++)
            if (q != l) {
                vb += vf[q];
                for (int k = 0; k < 3; k++) mb[k] += mf[q][k];
            }
        emit_loop(c, &loops[l], cell, r, vb, mb);
    }
}

static void cell_faces(Ctx *c, int i, int j, int k)
{
    int ijk[3] = {i, j, k};
    int64_t ci = i + c->n[0] * (j + (int64_t)c->n[1] * k), v0 = cut_cell_base(c, i, j, k);
    int cell = c->cellid[ci], mask = c->lmask[ci];
    Poly pl[3], pu[3];
    double vol = 1;
    for (int a = 0; a < 3; a++) {
        cut_grid_face(c, ijk, ci, v0, a, 1, cell, &pu[a]);
        /* a whole cell's lower faces matter only where its lower
           neighbour sees less of them (the rest is that cell's to add) */
        if (mask != 255 || (ijk[a] > 0 && cut_face_bits(c->lmask[ci - c->sc[a]], a, 1) != 15))
            cut_grid_face(c, ijk, ci, v0, a, 0, cell, &pl[a]);
        c->vref[a] = (c->x[a][ijk[a]] + c->x[a][ijk[a] + 1]) / 2;
        vol *= c->x[a][ijk[a] + 1] - c->x[a][ijk[a]];
    }
    c->cvol[cell] = vol;
    if (mask == 255) return;
    c->vacc = 0;
    for (int a = 0; a < 3; a++) {
        poly_volume(c, pu[a].pt, pu[a].n, 0);
        poly_volume(c, pl[a].pt, pl[a].n, 1);
    }
    boundary_faces(c, pl, pu, cell, mask);
    c->cvol[cell] = c->vacc;
}

/* ---- assembly ---- */

int cut_check_grid(const Mesh *grid, const Geometry *g, Err *e)
{
    const CartGrid *cg = &grid->cart;
    if (cg->n[0] <= 0 || cg->n[1] <= 0 || cg->n[2] <= 0 || !cg->x[0] || !cg->x[1] || !cg->x[2])
        return err_set(e, NULL, 0, "the grid has no Cartesian extras (cartesianGrid): cut a blockGrid grid");
    if ((int64_t)cg->n[0] * cg->n[1] * cg->n[2] != grid->ncells)
        return err_set(e, NULL, 0, "the grid has %d cells but its cartesianGrid %d x %d x %d", grid->ncells,
                       cg->n[0], cg->n[1], cg->n[2]);
    for (int p = 0; p < grid->npatches; p++)
        for (int s = 0; s < g->nsurf; s++)
            if (!strcmp(grid->patches[p].name, g->surf[s].name))
                return err_set(e, g->file, g->surf[s].line, "surface '%s' has the name of the grid's patch %d",
                               g->surf[s].name, p);
    return 0;
}

static int setup(Ctx *c, const Mesh *grid, Err *e)
{
    const CartGrid *cg = &grid->cart;
    if (cut_check_grid(grid, c->g, e)) return -1;
    for (int k = 0; k < 3; k++) {
        c->n[k] = cg->n[k];
        c->nv[k] = cg->n[k] + 1;
        c->x[k] = cg->x[k];
    }
    c->sv[0] = c->sc[0] = 1;
    c->sv[1] = c->nv[0];
    c->sv[2] = (int64_t)c->nv[0] * c->nv[1];
    c->sc[1] = c->n[0];
    c->sc[2] = (int64_t)c->n[0] * c->n[1];
    int64_t nv = c->sv[2] * c->nv[2];
    c->cls = mem_alloc((size_t)nv);
    c->onsurf = mem_calloc((size_t)nv, 1);
    c->level = mem_alloc(sizeof(float) * (size_t)nv);
    for (int64_t v = 0; v < nv; v++) c->level[v] = -1;
    c->lmask = mem_alloc((size_t)grid->ncells);
    c->vpt = mem_alloc(sizeof(int) * (size_t)nv);
    memset(c->vpt, 0xff, sizeof(int) * (size_t)nv);
    c->cellid = mem_alloc(sizeof(int) * (size_t)grid->ncells);
    tab_alloc(c, 1024);
    meshbuild_init(&c->b);
    /* the cut grid is about the size of the block grid (fewer cells,
       some extra points and faces on the boundary) */
    meshbuild_reserve(&c->b, (size_t)grid->npoints + (size_t)grid->npoints / 8,
                      (size_t)grid->nfaces + (size_t)grid->nfaces / 8, 4 * (size_t)grid->nfaces + (size_t)grid->nfaces / 4);
    for (int p = 0; p < grid->npatches; p++) {
        const Patch *P = &grid->patches[p];
        meshbuild_patch(&c->b, P->name, P->type, P->neighbour, P->groups);
    }
    c->npatch_grid = grid->npatches;
    for (int s = 0; s < c->g->nsurf; s++)
        meshbuild_patch(&c->b, c->g->surf[s].name, c->g->surf[s].type, NULL, NULL);
    return 0;
}

static void ctx_free(Ctx *c)
{
    free(c->cls);
    free(c->onsurf);
    free(c->level);
    free(c->lmask);
    free(c->vpt);
    free(c->cellid);
    free(c->tab);
    free(c->views);
    free(c->cross);
    free(c->wall);
    free(c->cvol);
    meshbuild_free(&c->b);
}

static int number_cells(Ctx *c, int **parent)
{
    int nc = 0;
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                int64_t ci = i + c->n[0] * (j + (int64_t)c->n[1] * k);
                c->cellid[ci] = c->lmask[ci] ? nc++ : -1;
            }
    *parent = mem_alloc(sizeof(int) * (size_t)(nc ? nc : 1));
    for (int64_t ci = 0; ci < c->sc[2] * c->n[2]; ci++)
        if (c->cellid[ci] >= 0) (*parent)[c->cellid[ci]] = (int)ci;
    return nc;
}

/* Boundary normals in final face order: meshbuild keeps the order of
   addition within a patch, so the k-th face added to a patch is its k-th
   face. */
static void boundary_normals(Ctx *c, Mesh *m)
{
    int nb = m->nfaces - m->ninternal;
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)(nb ? nb : 1));
    int *next = mem_alloc(sizeof(int) * (size_t)m->npatches);
    for (int p = 0; p < m->npatches; p++) next[p] = m->patches[p].start;
    for (size_t w = 0; w < c->nwall; w++) {
        int f = next[c->wall[w].patch]++;
        memcpy(m->boundary_normal + 3 * (size_t)(f - m->ninternal), c->wall[w].n, 3 * sizeof(double));
    }
    free(next);
}

/* The cut-cell data contract (cartcells.h): a cell with all eight
   corners fluid is its whole Cartesian cell, every other one is cut; the
   volumes are the ones cell_faces computed. */
static void cart_cells(const Ctx *c, Mesh *m)
{
    unsigned char *whole = mem_alloc((size_t)m->ncells + 1);
    for (int cl = 0; cl < m->ncells; cl++) whole[cl] = c->lmask[m->cell_parent[cl]] == 255;
    cartcells_build(m, c->cvol, whole, &m->cartcells);
    free(whole);
}

static void stats(Ctx *c, const Mesh *m)
{
    CutStats *st = c->st;
    st->ncells = m->ncells;
    st->nsolid = st->ncart - m->ncells;
    st->frac_min = 1;
    st->frac_min_cell = -1;
    st->vol_box = 1;
    for (int k = 0; k < 3; k++) st->vol_box *= c->x[k][c->n[k]] - c->x[k][0];
    for (int cl = 0; cl < m->ncells; cl++) {
        int p = m->cell_parent[cl];
        int i = p % c->n[0], j = (p / c->n[0]) % c->n[1], k = p / (c->n[0] * c->n[1]);
        double pv =
            (c->x[0][i + 1] - c->x[0][i]) * (c->x[1][j + 1] - c->x[1][j]) * (c->x[2][k + 1] - c->x[2][k]);
        double fr = c->cvol[cl] / pv;
        st->vol_fluid += c->cvol[cl];
        if (fr < 1 - 1e-9) st->ncut++;
        if (fr < st->frac_min) st->frac_min = fr, st->frac_min_cell = cl;
    }
}

int cut_mesh(const Mesh *grid, const Geometry *g, const CutOpts *o, Mesh *out, CutStats *st, Err *e)
{
    CutOpts od;
    CutStats sd;
    if (!o) cut_opts_default(&od), o = &od;
    if (!st) st = &sd;
    memset(st, 0, sizeof *st);
    mesh_init(out);
    if (!(o->snap >= 0 && o->snap < 0.5))
        return err_set(e, NULL, 0, "snap distance %g outside [0, 0.5)", o->snap);
    if (o->method == CUT_METHOD_STAIRCASE) return cut_staircase(grid, g, out, st, e);
    Ctx c;
    memset(&c, 0, sizeof c);
    c.g = g;
    c.snap = o->snap;
    c.st = st;
    if (setup(&c, grid, e)) {
        ctx_free(&c);
        return -1;
    }
    st->ncart = grid->ncells;
    classify(&c);
    cut_lines(&c);
    snap(&c);
    if (c.snap > 0) surface_corners(&c);
    local_masks(&c);
    local_points(&c);
    settle_all_views(&c);
    drop_degenerate(&c);
    int *parent;
    int nc = number_cells(&c, &parent);
    if (nc == 0) {
        free(parent);
        ctx_free(&c);
        return err_set(e, g->file, 0, "no cell is left: the geometry leaves no fluid inside the grid");
    }
    c.cvol = mem_alloc(sizeof(double) * (size_t)nc);
    for (int k = 0; k < c.n[2]; k++)
        for (int j = 0; j < c.n[1]; j++)
            for (int i = 0; i < c.n[0]; i++)
                if (c.cellid[i + c.n[0] * (j + (int64_t)c.n[1] * k)] >= 0) cell_faces(&c, i, j, k);
    if (cut_box_faces(&c, grid, e) || meshbuild_finish(&c.b, out, NULL, NULL, e)) {
        free(parent);
        ctx_free(&c);
        mesh_free(out);
        mesh_init(out);
        return -1;
    }
    out->cell_parent = parent;
    mesh_copy_cart(&grid->cart, &out->cart);
    boundary_normals(&c, out);
    cart_cells(&c, out);
    stats(&c, out);
    ctx_free(&c);
    return 0;
}
