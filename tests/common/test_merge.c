/*
** test_merge.c: merging of small cut cells on hand-made cut grids.
**
** The 2-D grids come from a tiny exact cutter in this file: every
** Cartesian cell of an nx x ny grid (one cell thick, empty front and
** back) is clipped by one or two half-planes c0 + c1 x + c2 y >= 0 (the
** fluid), the
** clipped polygons become prisms, polygon sides on the cut line go to
** patch "body" with the exact normal -(c1, c2)/|(c1, c2)| as wall normal.
** Crossing points are computed from the segment's endpoints in a fixed
** order, so two cells sharing a side get the same point.  Every check
** (check_merged) includes the 2-D rule: two empty faces per output cell.
**
** The cases and their exact numbers (thickness 1, so volume = area):
**   corner:  line y = 1.7 + 0.75 x on the unit 3x3 grid, fluid below.
**            Cell (0,2) keeps the triangle (0.4,2) (1,2) (1,2.45), area
**            0.135; its inner normal (0.6, -0.8) picks -y: cell (0,1),
**            the pentagon of area 1 - 0.4*0.3/2 = 0.94.  The cluster has
**            0.94 + 0.135 = 1.075 and (0,1)'s parent; the smallest ratio
**            after is cell (1,2)'s 1 - 0.2016667 (area above the line
**            in [1, 26/15] x [2, 3]).
**   spacing: the same line, column 0 twice as wide (x = 0 2 3 4): cell
**            (0,2) keeps 0.93333 of 2 (a slave at M_V = 1/2); Approach 3
**            takes -y (0.8 > 0.6), Approach 2 takes +x (0.6*2 > 0.8*1),
**            the full cell (1,2), whose parent the cluster then gets.
**   column:  line x = 0.7 + 0.1 y, fluid right: the left column keeps
**            trapezoids of 0.25, 0.15, 0.05, each merges +x.
**   wedge:   two lines (fluid 0.87 - 0.44x + 0.38y >= 0 and
**            2.26 - 0.59x - 0.74y >= 0): slave (2,1) (0.1324, inner
**            normal (-0.46, -0.58)) has the slave (2,0) (0.3929) on its
**            first side -y and the non-slave (1,1) (0.8168) on its second
**            side -x: it takes (1,1).  (Slaves go smallest first; the one
**            before it, (1,2) at 0.041, joins (1,1) too.)
**   chain:   line y = 0.1 + 0.05 x on a 3x1 grid, fluid below: three
**            slivers 0.125, 0.175, 0.225 whose -y side is the wall, so
**            they chain along +x into one cell of 0.525.
** 3-D: boxes clipped by one plane (plane_3d, numbers there), and a
** hand-built three-cell grid where the preferred master would make a
** cell with a face pyramid of negative volume (unsound_master_refused).
*/
#include "geom.h"
#include "mem.h"
#include "merge.h"
#include "meshbuild.h"
#include "quality.h"
#include "test.h"

typedef struct Cut2 {
    int nx, ny;
    const double *x, *y;   /* nx+1, ny+1 coordinates */
    double z0, z1;
    int nl;                /* 1 or 2 lines */
    double c[2][3];        /* fluid: c0 + c1 x + c2 y >= 0 for every line */
} Cut2;

static double side_of(const Cut2 *g, int l, const double p[2])
{
    return g->c[l][0] + g->c[l][1] * p[0] + g->c[l][2] * p[1];
}

/* Crossing of line l with segment a-b, from the endpoints in
   lexicographic order so both cells sharing the segment agree. */
static void crossing(const Cut2 *g, int l, const double a[2], const double b[2], double out[2])
{
    if (a[0] > b[0] || (a[0] == b[0] && a[1] > b[1])) {
        const double *t = a;
        a = b;
        b = t;
    }
    double sa = side_of(g, l, a), sb = side_of(g, l, b), t = sa / (sa - sb);
    out[0] = a[0] + t * (b[0] - a[0]);
    out[1] = a[1] + t * (b[1] - a[1]);
}

/* Clips the polygon v[0..n-1] (ccw) by line l; cls[k] is the class of
   edge k -> k+1: -1 a grid side, else the line it lies on.  Each inside
   vertex is kept with its edge's class; a crossing leaving the fluid
   starts an edge along line l, one entering it continues the old edge. */
static int clip_line(const Cut2 *g, int l, double v[12][2], int cls[12], int n)
{
    double w[12][2];
    int wc[12], m = 0;
    for (int k = 0; k < n; k++) {
        const double *p = v[k], *q = v[(k + 1) % n];
        int pin = side_of(g, l, p) >= 0, qin = side_of(g, l, q) >= 0;
        if (pin) {
            w[m][0] = p[0];
            w[m][1] = p[1];
            wc[m++] = cls[k];
        }
        if (pin != qin) {
            crossing(g, l, p, q, w[m]);
            wc[m++] = pin ? l : cls[k];
        }
    }
    memcpy(v, w, sizeof w);
    memcpy(cls, wc, sizeof wc);
    return m >= 3 ? m : 0;
}

/* The fluid polygon of cell (i, j) (ccw) and its edge classes; returns
   the vertex count, 0 when the cell has no fluid. */
static int clip(const Cut2 *g, int i, int j, double v[12][2], int cls[12])
{
    double sq[4][2] = {{g->x[i], g->y[j]}, {g->x[i + 1], g->y[j]}, {g->x[i + 1], g->y[j + 1]}, {g->x[i], g->y[j + 1]}};
    memcpy(v, sq, sizeof sq);
    int n = 4;
    for (int k = 0; k < 4; k++) cls[k] = -1;
    for (int l = 0; l < g->nl && n; l++) n = clip_line(g, l, v, cls, n);
    return n;
}

static int point_id(MeshBuild *b, double x, double y, double z)
{
    for (int i = 0; i < b->npoints; i++) {
        const double *p = b->points + 3 * i;
        if (fabs(p[0] - x) < 1e-12 && fabs(p[1] - y) < 1e-12 && p[2] == z) return i;
    }
    return meshbuild_point(b, (double[3]){x, y, z});
}

/* Cell number of Cartesian cell (i, j), -1 outside or without fluid. */
static int cell_at(const int *id, const Cut2 *g, int i, int j)
{
    return i < 0 || j < 0 || i >= g->nx || j >= g->ny ? -1 : id[i + g->nx * j];
}

static void add_normal(double **wn, int *cap, int face, const double n[3])
{
    if (face >= *cap) {
        *cap = 2 * face + 16;
        *wn = mem_realloc(*wn, sizeof(double) * 3 * (size_t)*cap);
    }
    memcpy(*wn + 3 * face, n, 3 * sizeof(double));
}

/* Side face of cell c for polygon edge a-b (ccw): internal, wall or body. */
static void side_face(MeshBuild *b, const Cut2 *g, const int *id, int i, int j, int c, const double *a, const double *pb,
                      int cls, double **wn, int *cap)
{
    int pts[4] = {point_id(b, a[0], a[1], g->z0), point_id(b, pb[0], pb[1], g->z0), point_id(b, pb[0], pb[1], g->z1),
                  point_id(b, a[0], a[1], g->z1)};
    double nrm[3] = {0, 0, 0};
    int nb = -1;
    if (cls >= 0) {
        double l = hypot(g->c[cls][1], g->c[cls][2]);
        nrm[0] = -g->c[cls][1] / l;
        nrm[1] = -g->c[cls][2] / l;
        add_normal(wn, cap, meshbuild_face(b, pts, 4, c, -1, 1), nrm);
        return;
    }
    int di = 0, dj = 0;
    if (a[0] == g->x[i] && pb[0] == g->x[i]) di = -1;
    else if (a[0] == g->x[i + 1] && pb[0] == g->x[i + 1]) di = 1;
    else if (a[1] == g->y[j] && pb[1] == g->y[j]) dj = -1;
    else dj = 1;
    nb = cell_at(id, g, i + di, j + dj);
    nrm[0] = di;
    nrm[1] = dj;
    if (nb > c) meshbuild_face(b, pts, 4, c, nb, -1);
    else if (nb < 0) add_normal(wn, cap, meshbuild_face(b, pts, 4, c, -1, 0), nrm);
}

static void cut2(Mesh *m, const Cut2 *g)
{
    MeshBuild b;
    Err e;
    meshbuild_init(&b);
    meshbuild_patch(&b, "walls", "wall", NULL, NULL);
    meshbuild_patch(&b, "body", "wall", NULL, NULL);
    meshbuild_patch(&b, "frontAndBack", "empty", NULL, NULL);
    int ncart = g->nx * g->ny, nc = 0, cap = 0;
    int *id = mem_alloc(sizeof(int) * (size_t)ncart), *parent = mem_alloc(sizeof(int) * (size_t)ncart);
    double v[12][2], *wn = NULL;
    int cls[12];
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            id[i + g->nx * j] = clip(g, i, j, v, cls) ? nc++ : -1;
            if (id[i + g->nx * j] >= 0) parent[id[i + g->nx * j]] = i + g->nx * j;
        }
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            int n = clip(g, i, j, v, cls), c = id[i + g->nx * j], lo[12], hi[12];
            if (!n) continue;
            for (int k = 0; k < n; k++) {
                lo[n - 1 - k] = point_id(&b, v[k][0], v[k][1], g->z0);
                hi[k] = point_id(&b, v[k][0], v[k][1], g->z1);
                side_face(&b, g, id, i, j, c, v[k], v[(k + 1) % n], cls[k], &wn, &cap);
            }
            add_normal(&wn, &cap, meshbuild_face(&b, lo, n, c, -1, 2), (double[3]){0, 0, -1});
            add_normal(&wn, &cap, meshbuild_face(&b, hi, n, c, -1, 2), (double[3]){0, 0, 1});
        }
    int nadd = b.nfaces;
    int *fmap = mem_alloc(sizeof(int) * (size_t)nadd);
    mesh_init(m);
    if (meshbuild_finish(&b, m, fmap, NULL, &e)) {
        printf("cut2: %s\n", e.msg);
        exit(1);
    }
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)(m->nfaces - m->ninternal));
    for (int f = 0; f < nadd; f++)
        if (fmap[f] >= m->ninternal) memcpy(m->boundary_normal + 3 * (fmap[f] - m->ninternal), wn + 3 * f, 3 * sizeof(double));
    m->cart.n[0] = g->nx;
    m->cart.n[1] = g->ny;
    m->cart.n[2] = 1;
    const double *ax[3] = {g->x, g->y, (double[2]){g->z0, g->z1}};
    for (int k = 0; k < 3; k++) {
        m->cart.x[k] = mem_alloc(sizeof(double) * (size_t)(m->cart.n[k] + 1));
        memcpy(m->cart.x[k], ax[k], sizeof(double) * (size_t)(m->cart.n[k] + 1));
    }
    m->cell_parent = mem_alloc(sizeof(int) * (size_t)nc);
    memcpy(m->cell_parent, parent, sizeof(int) * (size_t)nc);
    mesh_cell_faces(m);
    mesh_geometry(m);
    free(id);
    free(parent);
    free(wn);
    free(fmap);
}

/* ---- 3-D: boxes clipped by one plane ---- */

typedef struct Cut3 {
    int n[3];
    const double *x[3];
    double c[4];           /* fluid: c0 + c1 x + c2 y + c3 z >= 0 */
} Cut3;

static double side3(const Cut3 *g, const double p[3]) { return g->c[0] + g->c[1] * p[0] + g->c[2] * p[1] + g->c[3] * p[2]; }

static void crossing3(const Cut3 *g, const double *a, const double *b, double out[3])
{
    if (a[0] > b[0] || (a[0] == b[0] && (a[1] > b[1] || (a[1] == b[1] && a[2] > b[2])))) {
        const double *t = a;
        a = b;
        b = t;
    }
    double sa = side3(g, a), sb = side3(g, b), t = sa / (sa - sb);
    for (int k = 0; k < 3; k++) out[k] = a[k] + t * (b[k] - a[k]);
}

/* Corner offsets of the six box faces (-x, +x, -y, +y, -z, +z), each
   ordered so its right-hand normal points out of the box. */
static const int box_face[6][4][3] = {
    {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
    {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
    {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};

static int point3(MeshBuild *b, const double p[3])
{
    for (int i = 0; i < b->npoints; i++) {
        const double *q = b->points + 3 * i;
        if (fabs(p[0] - q[0]) < 1e-12 && fabs(p[1] - q[1]) < 1e-12 && fabs(p[2] - q[2]) < 1e-12) return i;
    }
    return meshbuild_point(b, p);
}

/* Face fi of box (i, j, k) clipped by the plane: point ids in pts;
   (ea[e], eb[e]) receive its edges along the plane.  Returns the count. */
static int clip_face(MeshBuild *b, const Cut3 *g, const int ijk[3], int fi, int pts[8], int *ea, int *eb, int *ne)
{
    double q[4][3];
    for (int v = 0; v < 4; v++)
        for (int k = 0; k < 3; k++) q[v][k] = g->x[k][ijk[k] + box_face[fi][v][k]];
    int n = 0, first_exit = -1;
    for (int v = 0; v < 4; v++) {
        const double *p = q[v], *r = q[(v + 1) % 4];
        int pin = side3(g, p) >= 0, rin = side3(g, r) >= 0;
        if (pin) pts[n++] = point3(b, p);
        if (pin != rin) {
            double x[3];
            crossing3(g, p, r, x);
            if (pin) first_exit = n;
            pts[n++] = point3(b, x);
        }
    }
    if (n < 3) return 0;
    if (first_exit >= 0) {
        ea[*ne] = pts[first_exit];
        eb[(*ne)++] = pts[(first_exit + 1) % n];
    }
    return n;
}

static void cut3(Mesh *m, const Cut3 *g)
{
    MeshBuild b;
    Err e;
    meshbuild_init(&b);
    meshbuild_patch(&b, "walls", "wall", NULL, NULL);
    meshbuild_patch(&b, "body", "wall", NULL, NULL);
    int nx = g->n[0], ny = g->n[1], ncart = nx * ny * g->n[2], nc = 0, cap = 0;
    int *id = mem_alloc(sizeof(int) * (size_t)ncart), *parent = mem_alloc(sizeof(int) * (size_t)ncart);
    double *wn = NULL, l = sqrt(g->c[1] * g->c[1] + g->c[2] * g->c[2] + g->c[3] * g->c[3]);
    for (int p = 0; p < ncart; p++) {
        int ijk[3] = {p % nx, (p / nx) % ny, p / (nx * ny)}, fluid = 0;
        for (int v = 0; v < 8; v++) {
            double x[3];
            for (int k = 0; k < 3; k++) x[k] = g->x[k][ijk[k] + ((v >> k) & 1)];
            fluid |= side3(g, x) > 0;
        }
        id[p] = fluid ? nc++ : -1;
        if (fluid) parent[id[p]] = p;
    }
    for (int p = 0; p < ncart; p++) {
        int ijk[3] = {p % nx, (p / nx) % ny, p / (nx * ny)}, c = id[p], ea[6], eb[6], ne = 0, pts[8];
        if (c < 0) continue;
        for (int fi = 0; fi < 6; fi++) {
            int n = clip_face(&b, g, ijk, fi, pts, ea, eb, &ne), ax = fi / 2, dir = fi % 2 ? 1 : -1;
            if (!n) continue;
            int nijk[3] = {ijk[0], ijk[1], ijk[2]};
            nijk[ax] += dir;
            int nb = nijk[ax] < 0 || nijk[ax] >= g->n[ax] ? -1 : id[nijk[0] + nx * (nijk[1] + ny * nijk[2])];
            double nrm[3] = {0, 0, 0};
            nrm[ax] = dir;
            if (nb > c) meshbuild_face(&b, pts, n, c, nb, -1);
            else if (nb < 0) add_normal(&wn, &cap, meshbuild_face(&b, pts, n, c, -1, 0), nrm);
        }
        if (ne < 3) continue;
        /* the cap passes the faces' plane edges the other way round */
        int loop[6], len = 0, cur = ea[0];
        do {
            int k = 0;
            while (k < ne && eb[k] != cur) k++;
            loop[len++] = cur;
            cur = ea[k];
        } while (cur != ea[0] && len < ne);
        double nrm[3] = {-g->c[1] / l, -g->c[2] / l, -g->c[3] / l};
        add_normal(&wn, &cap, meshbuild_face(&b, loop, len, c, -1, 1), nrm);
    }
    int nadd = b.nfaces;
    int *fmap = mem_alloc(sizeof(int) * (size_t)nadd);
    mesh_init(m);
    if (meshbuild_finish(&b, m, fmap, NULL, &e)) {
        printf("cut3: %s\n", e.msg);
        exit(1);
    }
    m->boundary_normal = mem_alloc(sizeof(double) * 3 * (size_t)(m->nfaces - m->ninternal));
    for (int f = 0; f < nadd; f++)
        if (fmap[f] >= m->ninternal) memcpy(m->boundary_normal + 3 * (fmap[f] - m->ninternal), wn + 3 * f, 3 * sizeof(double));
    for (int k = 0; k < 3; k++) {
        m->cart.n[k] = g->n[k];
        m->cart.x[k] = mem_alloc(sizeof(double) * (size_t)(g->n[k] + 1));
        memcpy(m->cart.x[k], g->x[k], sizeof(double) * (size_t)(g->n[k] + 1));
    }
    m->cell_parent = mem_alloc(sizeof(int) * (size_t)nc);
    memcpy(m->cell_parent, parent, sizeof(int) * (size_t)nc);
    mesh_cell_faces(m);
    mesh_geometry(m);
    free(id);
    free(parent);
    free(wn);
    free(fmap);
}

/* Input cell of Cartesian cell (i, j) of m. */
static int cell_of(const Mesh *m, int i, int j)
{
    for (int c = 0; c < m->ncells; c++)
        if (m->cell_parent[c] == i + m->cart.n[0] * j) return c;
    return -1;
}

/* Checks every property merge_mesh promises on any input. */
static void check_merged(const Mesh *in, Mesh *out, const MergeStats *st, double threshold)
{
    Err e;
    Quality q;
    quality_measure(out, &q);
    EXPECT(mesh_check(out, &e) == 0, "%s", e.msg);
    EXPECT(quality_check(out, &q, NULL, &e) == 0, "%s", e.msg);
    EXPECT(q.open_max <= 1e-14, "open %g", q.open_max);
    double vin = 0, vout = 0;
    for (int c = 0; c < in->ncells; c++) vin += in->cell_vol[c];
    for (int c = 0; c < out->ncells; c++) vout += out->cell_vol[c];
    NEAR(vout, vin, 1e-13 * vin);
    NEAR(st->vol_before, vin, 1e-13 * vin);
    NEAR(st->vol_after, vout, 1e-13 * vin);
    EXPECT(out->merge_map && out->nmerge_old == in->ncells, "merge map missing");
    if (test_failed_now) return;
    double *sum = MEM_NEW(double, (size_t)out->ncells);
    int ndropped = 0;
    for (int c = 0; c < in->ncells; c++) sum[out->merge_map[c]] += in->cell_vol[c];
    for (int c = 0; c < out->ncells; c++) NEAR(out->cell_vol[c], sum[c], 1e-13);
    for (int f = 0; f < in->ninternal; f++) ndropped += out->merge_map[in->owner[f]] == out->merge_map[in->neighbour[f]];
    /* 2-D: a merged cell's empty faces are joined, two per cell */
    int twod = mesh_empty_axis(in) == 2;
    int ein = twod ? in->patches[2].size : 0, eout = twod ? out->patches[2].size : 0;
    EXPECT(!twod || (eout == 2 * out->ncells && mesh_empty_axis(out) == 2), "%d empty faces for %d cells", eout,
           out->ncells);
    EXPECT(out->nfaces == in->nfaces - ndropped - (ein - eout), "%d faces, expected %d", out->nfaces,
           in->nfaces - ndropped - (ein - eout));
    /* every cell meets the bound or is listed */
    for (int c = 0; c < out->ncells; c++) {
        double h[3];
        EXPECT(mesh_cell_spacing(out, c, h) == 0, "cell %d has no parent", c);
        int listed = 0;
        for (int i = 0; i < st->nunresolved; i++) listed |= st->unresolved[i] == c;
        EXPECT(listed || out->cell_vol[c] > threshold * h[0] * h[1] * h[2], "cell %d: %g of %g, not listed", c,
               out->cell_vol[c], h[0] * h[1] * h[2]);
    }
    /* wall normals followed their faces: unit face normals, body exact */
    int body = mesh_patch(out, "body");
    for (int f = out->ninternal; f < out->nfaces; f++) {
        const double *S = out->face_area + 3 * f, *n = out->boundary_normal + 3 * (f - out->ninternal);
        double a = geom_norm(S);
        for (int k = 0; k < 3; k++) NEAR(n[k], S[k] / a, mesh_face_patch(out, f) == body ? 1e-12 : 1e-15);
    }
    free(sum);
}

static const double unit4[] = {0, 1, 2, 3}, unit5[] = {0, 1, 2, 3, 4};

TEST(corner_triangle)
{
    Cut2 g = {3, 3, unit4, unit4, 0, 1, 1, {{1.7, 0.75, -1}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    int tri = cell_of(&in, 0, 2), pent = cell_of(&in, 0, 1), c12 = cell_of(&in, 1, 2);
    EXPECT(in.ncells == 9 && tri >= 0, "%d cells", in.ncells);
    NEAR(in.cell_vol[tri], 0.135, 1e-15);
    NEAR(in.cell_vol[pent], 0.94, 1e-15);
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    if (test_failed_now) return;
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.ncells == 8 && st.ncells_in == 9 && st.ncells_out == 8, "%d cells", out.ncells);
    EXPECT(out.merge_map[tri] == out.merge_map[pent], "triangle went to cell %d, pentagon %d", out.merge_map[tri],
           out.merge_map[pent]);
    int C = out.merge_map[tri];
    NEAR(out.cell_vol[C], 1.075, 1e-14);
    EXPECT(out.cell_parent[C] == 0 + 3 * 1, "parent %d", out.cell_parent[C]);
    /* numbering in order of smallest member, so nothing else moved */
    for (int c = 0; c < in.ncells; c++)
        if (c != tri) EXPECT(out.merge_map[c] == c - (c > tri), "cell %d -> %d", c, out.merge_map[c]);
    EXPECT(st.nslaves == 1 && st.nclusters == 1 && st.niter == 1 && st.nunresolved == 0, "%d slaves %d clusters %d iter",
           st.nslaves, st.nclusters, st.niter);
    NEAR(st.ratio_min_before, 0.135, 1e-15);
    double xe = 26.0 / 15;   /* the line leaves the top at x = 1.3/0.75 */
    double a12 = 1 - (1.3 * (xe - 1) - 0.375 * (xe * xe - 1));   /* area of (1,2) below the line */
    NEAR(in.cell_vol[c12], a12, 1e-14);
    NEAR(st.ratio_min_after, a12, 1e-14);
    EXPECT(st.ratio_min_cell == out.merge_map[c12], "ratio_min_cell %d", st.ratio_min_cell);
    /* aspect (2-D: x/y sums of |S_k|): triangle 0.9 / 1.2; merged cell
       x 0.7+0.3+1+0.45+0.45 = 2.9 against y 1+0.4+0.6 = 2 */
    NEAR(st.aspect_max_before, 1.2 / 0.9, 1e-14);
    NEAR(st.aspect_max_after, 1.45, 1e-14);
    merge_stats_free(&st);
    mesh_free(&in);
    mesh_free(&out);
}

TEST(criterion_spacing)
{
    static const double x[] = {0, 2, 3, 4};
    Cut2 g = {3, 3, x, unit4, 0, 1, 1, {{1.7, 0.75, -1}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    int s = cell_of(&in, 0, 2), below_ = cell_of(&in, 0, 1), right = cell_of(&in, 1, 2);
    NEAR(in.cell_vol[s], 2 - (0.4 + 26.0 / 15) / 2, 1e-14);   /* 2 - trapezoid (0,2) (0.4,2) (26/15,3) (0,3) */
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.merge_map[s] == out.merge_map[below_], "normal: merged with %d", out.merge_map[s]);
    merge_stats_free(&st);
    mesh_free(&out);
    o.criterion = MERGE_NORMAL_H;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.merge_map[s] == out.merge_map[right], "normal*h: merged with %d", out.merge_map[s]);
    NEAR(out.cell_vol[out.merge_map[s]], in.cell_vol[s] + 1, 1e-14);
    /* the largest member is the full cell (1 > 0.933) */
    EXPECT(out.cell_parent[out.merge_map[s]] == 1 + 3 * 2, "parent %d", out.cell_parent[out.merge_map[s]]);
    merge_stats_free(&st);
    mesh_free(&out);
    mesh_free(&in);
}

TEST(column_of_slaves)
{
    Cut2 g = {3, 3, unit4, unit4, 0, 0.1, 1, {{-0.7, 1, -0.1}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.ncells == 6 && st.nslaves == 3 && st.nclusters == 3, "%d cells %d slaves", out.ncells, st.nslaves);
    const double area[3] = {0.25, 0.15, 0.05};
    for (int j = 0; j < 3; j++) {
        int a = cell_of(&in, 0, j), b = cell_of(&in, 1, j);
        NEAR(in.cell_vol[a], 0.1 * area[j], 1e-15);
        EXPECT(out.merge_map[a] == out.merge_map[b], "row %d: %d %d", j, out.merge_map[a], out.merge_map[b]);
        NEAR(out.cell_vol[out.merge_map[a]], 0.1 * (1 + area[j]), 1e-15);
        EXPECT(out.cell_parent[out.merge_map[a]] == 1 + 3 * j, "row %d parent %d", j, out.cell_parent[out.merge_map[a]]);
    }
    NEAR(st.ratio_min_before, 0.05, 1e-14);
    NEAR(st.ratio_min_after, 1, 1e-14);
    merge_stats_free(&st);
    mesh_free(&in);
    mesh_free(&out);
}

TEST(chain_and_unresolved)
{
    static const double y[] = {0, 1};
    Cut2 g = {3, 1, unit4, y, 0, 1, 1, {{0.1, 0.05, -1}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    EXPECT(in.ncells == 3, "%d cells", in.ncells);
    for (int c = 0; c < 3; c++) NEAR(in.cell_vol[c], 0.125 + 0.05 * c, 1e-15);
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.ncells == 1 && st.nclusters == 1 && st.nunresolved == 0 && st.niter == 1, "%d cells, %d unresolved",
           out.ncells, st.nunresolved);
    NEAR(out.cell_vol[0], 0.525, 1e-15);
    EXPECT(out.cell_parent[0] == 2, "parent %d", out.cell_parent[0]);
    merge_stats_free(&st);
    mesh_free(&out);

    /* M_V = 0.6: the chain is still small and has no neighbour left */
    o.threshold = 0.6;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.6);
    EXPECT(st.nunresolved == 1 && st.unresolved[0] == 0 && st.reason[0] == MERGE_NO_NEIGHBOUR, "%d unresolved, reason %d",
           st.nunresolved, st.nunresolved ? st.reason[0] : -1);
    merge_stats_free(&st);
    mesh_free(&out);

    /* one round allowed: it ends before the cluster is re-examined */
    o.max_iter = 1;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    EXPECT(st.nunresolved == 1 && st.reason[0] == MERGE_ITER_LIMIT, "%d unresolved, reason %d", st.nunresolved,
           st.nunresolved ? st.reason[0] : -1);
    CONTAINS(merge_reason_name(st.reason[0]), "maxIter");
    merge_stats_free(&st);
    mesh_free(&out);

    /* no rounds: the grid comes back unchanged, slaves listed */
    o.max_iter = 0;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    EXPECT(out.ncells == 3 && st.nunresolved == 3 && out.nfaces == in.nfaces, "%d cells", out.ncells);
    merge_stats_free(&st);
    mesh_free(&out);
    mesh_free(&in);
}

TEST(prefer_non_slave)
{
    Cut2 g = {3, 3, unit4, unit4, 0, 1, 2, {{0.87, -0.44, 0.38}, {2.26, -0.59, -0.74}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    int s = cell_of(&in, 2, 1), down = cell_of(&in, 2, 0), left = cell_of(&in, 1, 1);
    EXPECT(in.ncells == 8, "%d cells", in.ncells);
    /* areas from an independent shoelace computation */
    NEAR(in.cell_vol[s], 0.13238662391204747, 1e-15);
    NEAR(in.cell_vol[down], 0.39285609980954883, 1e-15);
    NEAR(in.cell_vol[left], 0.8167659184608338, 1e-15);
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    /* (2,1) took (1,1) across its second axis, not the slave (2,0) on
       its first; (2,0) went elsewhere */
    EXPECT(out.merge_map[s] == out.merge_map[left], "(2,1) -> %d, (1,1) -> %d", out.merge_map[s], out.merge_map[left]);
    EXPECT(out.merge_map[down] != out.merge_map[s], "(2,0) joined (2,1)");
    EXPECT(out.ncells == 5 && st.nslaves == 3 && st.nunresolved == 0, "%d cells, %d slaves", out.ncells, st.nslaves);
    merge_stats_free(&st);
    mesh_free(&in);
    mesh_free(&out);
}

/* 3-D: fluid above the plane z = 0.3 + 0.1 x + 0.05 y in a 4x4x3 grid of
   unit cubes.  The plane crosses every bottom cell from side to side, so
   cell (i, j, 0) keeps 1 - z_plane(centre) = 0.625 - 0.1 i - 0.05 j: a
   slave exactly when 2i + j >= 3 (12 cells, the smallest 0.175).  The
   inner normal (-0.1, -0.05, 1) picks +z: each slave joins the full cell
   above it.  The smallest ratio left is 0.525 (cells (0,2,0), (1,0,0)). */
TEST(plane_3d)
{
    static const double z[] = {0, 1, 2, 3};
    Cut3 g = {{4, 4, 3}, {unit5, unit5, z}, {-0.3, -0.1, -0.05, 1}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut3(&in, &g);
    EXPECT(in.ncells == 48 && mesh_check(&in, &e) == 0, "%d cells: %s", in.ncells, e.msg);
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    if (test_failed_now) return;
    check_merged(&in, &out, &st, 0.5);
    EXPECT(out.ncells == 36 && st.nslaves == 12 && st.nclusters == 12 && st.niter == 1, "%d cells %d slaves",
           out.ncells, st.nslaves);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            int a = in.cell_parent[i + 4 * j] == i + 4 * j ? i + 4 * j : -1, b = a + 16;
            double f = 0.625 - 0.1 * i - 0.05 * j;
            EXPECT(a >= 0 && in.cell_parent[b] == a + 16, "cell numbering");
            if (test_failed_now) break;
            NEAR(in.cell_vol[a], f, 1e-14);
            int merged = out.merge_map[a] == out.merge_map[b];
            EXPECT(merged == (2 * i + j >= 3), "(%d,%d,0): merged %d", i, j, merged);
            if (merged) {
                NEAR(out.cell_vol[out.merge_map[a]], 1 + f, 1e-14);
                EXPECT(out.cell_parent[out.merge_map[a]] == b, "parent %d", out.cell_parent[out.merge_map[a]]);
            }
        }
    NEAR(st.ratio_min_before, 0.175, 1e-14);
    NEAR(st.ratio_min_after, 0.525, 1e-14);
    merge_stats_free(&st);
    mesh_free(&in);
    mesh_free(&out);
}

/* Adds the polygon of the n points xyz (any orientation) to b, oriented
   along out (roughly the normal out of cell c). */
static void hand_face(MeshBuild *b, int c, int other, int patch, const double out[3], int n, const double *xyz)
{
    int pts[8];
    double S[3], C[3], P[24];
    for (int i = 0; i < n; i++) pts[i] = point3(b, xyz + 3 * i);
    memcpy(P, xyz, sizeof(double) * 3 * (size_t)n);
    int idx[8];
    for (int i = 0; i < n; i++) idx[i] = i;
    geom_face(P, idx, n, S, C);
    if (geom_dot(S, out) < 0)
        for (int i = 0; i < n / 2; i++) {
            int t = pts[i];
            pts[i] = pts[n - 1 - i];
            pts[n - 1 - i] = t;
        }
    meshbuild_face(b, pts, n, c, other, patch);
}

/* A grid where the preferred master gives an unsound cell.  Cells: M the
   unit cube (Cartesian cell (0,0,0)); S (parent (0,0,1), above M) a thin
   wedge in the corner x = y = 1, its triangle legs shrinking from 0.1 at
   z = 1 to 0.08 at z = 2, volume 0.5 (0.01 - 0.002 + 0.0004/3); T (parent
   (1,0,1)) the box [1,2]x[0.6,1]x[1,2], volume 0.4, sharing S's face
   x = 1.  S's immersed face has the inner normal (1, 1, -0.04)/|.|: +x
   offers the slave T, -z the non-slave M.  But S + M would put the
   centroid (near M's) outside S's wedge face, so S takes T (group 2);
   the cluster S + T (0.404) then has only M left, which is unsound as
   well: it stays, listed as having no neighbour (maxSkewness 0).  With
   the default maxSkewness 4 the repair undoes S + T as well: S's face
   y = 1, 0.9 <= x <= 1, lies 0.55 along x from the union's centre (about
   T's, (1.5, 0.8, 1.5)) but only 0.2 away in y, skewness about
   0.55 / max(0.4 x 0.2, 0.05) = 6.9 (6.81 exactly, and one more face
   above 4), where the cut grid has at most 4;
   no other union is clean, so with minRatio 0 S and T (0.4 of its
   parent) stay alone; with the default minRatio 0.01 S (0.0041) would be
   left far too small, and it merges into S + T again. */
TEST(unsound_master_refused)
{
    MeshBuild b;
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    meshbuild_init(&b);
    meshbuild_patch(&b, "walls", "wall", NULL, NULL);
    meshbuild_patch(&b, "body", "wall", NULL, NULL);
    enum { M, S, T };
    const double mx[3] = {-1, 0, 0}, px[3] = {1, 0, 0}, my[3] = {0, -1, 0}, py[3] = {0, 1, 0}, mz[3] = {0, 0, -1},
                 pz[3] = {0, 0, 1}, diag[3] = {-1, -1, 0.04};
    hand_face(&b, M, -1, 0, mx, 4, (double[]){0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1});
    hand_face(&b, M, -1, 0, px, 4, (double[]){1, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1});
    hand_face(&b, M, -1, 0, my, 4, (double[]){0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1});
    hand_face(&b, M, -1, 0, py, 4, (double[]){0, 1, 0, 1, 1, 0, 1, 1, 1, 0, 1, 1});
    hand_face(&b, M, -1, 0, mz, 4, (double[]){0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    hand_face(&b, M, -1, 0, pz, 5, (double[]){0, 0, 1, 1, 0, 1, 1, 0.9, 1, 0.9, 1, 1, 0, 1, 1});
    hand_face(&b, M, S, -1, pz, 3, (double[]){1, 0.9, 1, 1, 1, 1, 0.9, 1, 1});
    hand_face(&b, S, -1, 1, diag, 4, (double[]){0.9, 1, 1, 1, 0.9, 1, 1, 0.92, 2, 0.92, 1, 2});
    hand_face(&b, S, T, -1, px, 4, (double[]){1, 0.9, 1, 1, 1, 1, 1, 1, 2, 1, 0.92, 2});
    hand_face(&b, S, -1, 0, py, 4, (double[]){0.9, 1, 1, 1, 1, 1, 1, 1, 2, 0.92, 1, 2});
    hand_face(&b, S, -1, 0, pz, 3, (double[]){1, 0.92, 2, 1, 1, 2, 0.92, 1, 2});
    hand_face(&b, T, -1, 0, mx, 4, (double[]){1, 0.6, 1, 1, 0.9, 1, 1, 0.92, 2, 1, 0.6, 2});
    hand_face(&b, T, -1, 0, px, 4, (double[]){2, 0.6, 1, 2, 1, 1, 2, 1, 2, 2, 0.6, 2});
    hand_face(&b, T, -1, 1, my, 4, (double[]){1, 0.6, 1, 2, 0.6, 1, 2, 0.6, 2, 1, 0.6, 2});
    hand_face(&b, T, -1, 0, py, 4, (double[]){1, 1, 1, 2, 1, 1, 2, 1, 2, 1, 1, 2});
    hand_face(&b, T, -1, 0, mz, 4, (double[]){1, 0.6, 1, 2, 0.6, 1, 2, 1, 1, 1, 1, 1});
    hand_face(&b, T, -1, 0, pz, 4, (double[]){1, 0.6, 2, 2, 0.6, 2, 2, 1, 2, 1, 1, 2});
    mesh_init(&in);
    EXPECT(meshbuild_finish(&b, &in, NULL, NULL, &e) == 0, "%s", e.msg);
    static const double x[] = {0, 1, 2}, y[] = {0, 1}, z[] = {0, 1, 2};
    const double *ax[3] = {x, y, z};
    const int n[3] = {2, 1, 2};
    for (int k = 0; k < 3; k++) {
        in.cart.n[k] = n[k];
        in.cart.x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        memcpy(in.cart.x[k], ax[k], sizeof(double) * (size_t)(n[k] + 1));
    }
    in.cell_parent = mem_alloc(3 * sizeof(int));
    in.cell_parent[M] = 0;
    in.cell_parent[S] = 2;
    in.cell_parent[T] = 3;
    mesh_cell_faces(&in);
    mesh_geometry(&in);
    EXPECT(mesh_check(&in, &e) == 0, "%s", e.msg);
    NEAR(in.cell_vol[S], 0.5 * (0.01 - 0.002 + 0.0004 / 3), 1e-15);
    NEAR(in.cell_vol[T], 0.4, 1e-15);
    merge_opts_default(&o);
    o.max_skewness = 0;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    if (test_failed_now) return;
    Quality q;
    quality_measure(&out, &q);
    EXPECT(quality_check(&out, &q, NULL, &e) == 0, "%s", e.msg);
    EXPECT(q.nskew == 2 && q.skew_max > 6.8 && q.skew_max < 6.9, "%d skewed faces, max %g", q.nskew, q.skew_max);
    EXPECT(out.ncells == 2 && out.merge_map[S] == out.merge_map[T] && out.merge_map[M] != out.merge_map[S],
           "%d cells, map %d %d %d", out.ncells, out.merge_map[M], out.merge_map[S], out.merge_map[T]);
    EXPECT(st.nunresolved == 1 && st.unresolved[0] == out.merge_map[S] && st.reason[0] == MERGE_NO_NEIGHBOUR,
           "%d unresolved", st.nunresolved);
    NEAR(out.cell_vol[out.merge_map[S]], in.cell_vol[S] + 0.4, 1e-15);
    EXPECT(out.cell_parent[out.merge_map[S]] == 3, "parent %d", out.cell_parent[out.merge_map[S]]);
    merge_stats_free(&st);
    mesh_free(&out);

    /* the defaults: S (0.0041 of its parent, below minRatio 0.01) would
       come back alone, so after the repair undoes S + T the clean rounds
       take it again as the sound union it is (forced) */
    merge_opts_default(&o);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    quality_measure(&out, &q);
    EXPECT(out.ncells == 2 && out.merge_map[S] == out.merge_map[T] && st.nforced == 1 && st.nundone == 1,
           "%d cells, %d forced, %d undone", out.ncells, st.nforced, st.nundone);
    EXPECT(q.nskew == 2 && q.skew_max > 6.8 && q.skew_max < 6.9, "%d skewed faces, max %g", q.nskew, q.skew_max);
    EXPECT(st.ratio_min_after > 0.4, "smallest ratio %g", st.ratio_min_after);
    merge_stats_free(&st);
    mesh_free(&out);

    /* minRatio 0: no merge that checkMesh would fail, S and T alone */
    merge_opts_default(&o);
    o.min_ratio = 0;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    quality_measure(&out, &q);
    EXPECT(out.ncells == 3 && st.nundone == 1 && st.nclean_merged == 0, "%d cells, %d undone", out.ncells, st.nundone);
    EXPECT(q.nskew == 0 && q.skew_max <= st.skew_max_cut + 1e-12, "max skewness %g, cut grid %g", q.skew_max,
           st.skew_max_cut);
    NEAR(st.skew_max_after, q.skew_max, 1e-12);
    EXPECT(st.nunresolved == 2 && st.unresolved[0] == out.merge_map[S] && st.unresolved[1] == out.merge_map[T] &&
               st.reason[0] == MERGE_NO_NEIGHBOUR && st.reason[1] == MERGE_NO_NEIGHBOUR,
           "%d unresolved", st.nunresolved);
    merge_stats_free(&st);
    mesh_free(&in);
    mesh_free(&out);
}

TEST(bad_input)
{
    Cut2 g = {3, 3, unit4, unit4, 0, 1, 1, {{1.7, 0.75, -1}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Err e;
    cut2(&in, &g);
    merge_opts_default(&o);
    o.threshold = 0;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == -1, "threshold 0 accepted");
    CONTAINS(e.msg, "merge: threshold 0 out of range (0, 1]");
    mesh_free(&out);
    merge_opts_default(&o);
    o.criterion = 7;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == -1, "criterion 7 accepted");
    CONTAINS(e.msg, "merge: unknown criterion 7");
    mesh_free(&out);
    merge_opts_default(&o);
    o.max_skewness = -1;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == -1, "maxSkewness -1 accepted");
    CONTAINS(e.msg, "merge: maxSkewness -1 is negative");
    mesh_free(&out);
    merge_opts_default(&o);
    int keep = in.neighbour[0];
    in.neighbour[0] = in.owner[0];
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == -1, "broken ordering accepted");
    CONTAINS(e.msg, "merge: mesh: face 0: owner 0 is not less than neighbour 0");
    mesh_free(&out);
    in.neighbour[0] = keep;
    free(in.cell_parent);
    in.cell_parent = NULL;
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == -1, "no parents accepted");
    CONTAINS(e.msg, "merge: the grid has no Cartesian parents");
    mesh_free(&out);
    mesh_free(&in);
}


/* Quality pass: line 0.8 x + 0.6 y = 2.25 on a 4x4 grid of 1 x 0.25
   cells (0.1 thick), fluid right.  Cells (2,0) and (2,1) keep
   trapezoids of 0.28125 and 0.46875 of their parents: slaves, each
   merging +x into (3,0), (3,1).  The cluster (2,0)+(3,0) is the polygon
   (2.8125,0) (4,0) (4,0.25) (2.625,0.25); its bottom wall face from
   x = 2.8125 to 3 (centre 2.90625, half length 0.09375) lies far along
   the wall from the cluster's centroid: skewness |2.90625 - C_x| /
   max(0.4 C_y, 0.09375) = 4.82 (OpenFOAM's boundary-face rule).  The pass
   joins the two clusters (the union's centroid is twice as far from the
   wall, which halves the worst skewness to 3.85); with maxSkewness 0 the
   face stays.  A single row of such cells has no neighbour to merge
   with: the pass cannot mend the cluster (2,0)+(3,0), and since the cut
   grid's faces are all below 4 the repair undoes it; (2,0) then has no
   clean union and stays, reported. */
static void polygon_centroid(const double (*p)[2], int n, double c[2])
{
    double a = 0;
    c[0] = c[1] = 0;
    for (int i = 0; i < n; i++) {
        const double *u = p[i], *v = p[(i + 1) % n];
        double x = u[0] * v[1] - v[0] * u[1];
        a += x;
        c[0] += (u[0] + v[0]) * x;
        c[1] += (u[1] + v[1]) * x;
    }
    c[0] /= 3 * a;
    c[1] /= 3 * a;
}

TEST(skewness_pass)
{
    static const double y[] = {0, 0.25, 0.5, 0.75, 1};
    Cut2 g = {4, 4, unit5, y, 0, 0.1, 1, {{-2.25, 0.8, 0.6}}};
    Mesh in, out;
    MergeOpts o;
    MergeStats st;
    Quality q;
    Err e;
    cut2(&in, &g);
    int s0 = cell_of(&in, 2, 0), m0 = cell_of(&in, 3, 0), s1 = cell_of(&in, 2, 1), m1 = cell_of(&in, 3, 1);
    EXPECT(in.ncells == 8 && s0 >= 0 && s1 >= 0, "%d cells", in.ncells);
    NEAR(in.cell_vol[s0], 0.28125 * 0.025, 1e-16);
    NEAR(in.cell_vol[s1], 0.46875 * 0.025, 1e-16);
    static const double poly[4][2] = {{2.8125, 0}, {4, 0}, {4, 0.25}, {2.625, 0.25}};
    double C[2];
    polygon_centroid(poly, 4, C);
    double skew0 = fabs(2.90625 - C[0]) / fmax(0.4 * C[1], 0.09375);
    EXPECT(skew0 > 4.8 && skew0 < 4.9, "expected skewness %g", skew0);

    merge_opts_default(&o);
    o.max_skewness = 0;   /* off: the skewed face stays */
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    quality_measure(&out, &q);
    EXPECT(out.ncells == 6 && st.nskew_merged == 0 && st.nunresolved == 0, "%d cells", out.ncells);
    NEAR(q.skew_max, skew0, 1e-12);
    NEAR(st.skew_max_before, skew0, 1e-12);
    NEAR(st.skew_max_after, skew0, 1e-12);
    EXPECT(q.nskew == 1 && q.skew_face >= out.ninternal, "%d skewed faces", q.nskew);   /* the bottom wall face */
    merge_stats_free(&st);
    mesh_free(&out);

    merge_opts_default(&o);
    NEAR(o.max_skewness, 4, 0);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    quality_measure(&out, &q);
    EXPECT(out.ncells == 5 && st.nskew_merged == 1 && st.nunresolved == 0, "%d cells, %d skew merges", out.ncells,
           st.nskew_merged);
    int C0 = out.merge_map[s0];
    EXPECT(out.merge_map[m0] == C0 && out.merge_map[s1] == C0 && out.merge_map[m1] == C0, "clusters %d %d %d %d", C0,
           out.merge_map[m0], out.merge_map[s1], out.merge_map[m1]);
    NEAR(st.skew_max_before, skew0, 1e-12);
    NEAR(st.skew_max_after, q.skew_max, 1e-12);
    EXPECT(q.nskew == 0 && q.skew_max < 4, "%d skewed faces, max %g", q.nskew, q.skew_max);
    /* the union (2,0)+(3,0)+(2,1)+(3,1) and its bottom face */
    static const double poly2[5][2] = {{2.8125, 0}, {4, 0}, {4, 0.5}, {2.4375, 0.5}, {2.625, 0.25}};
    polygon_centroid(poly2, 5, C);
    NEAR(q.skew_max, fabs(2.90625 - C[0]) / fmax(0.4 * C[1], 0.09375), 1e-12);
    merge_stats_free(&st);
    mesh_free(&out);
    mesh_free(&in);

    /* one row: the cluster has no neighbour, so it is reported */
    Cut2 g1 = {4, 1, unit5, y, 0, 0.1, 1, {{-2.25, 0.8, 0.6}}};
    cut2(&in, &g1);
    EXPECT(merge_mesh(&in, &o, &out, &st, &e) == 0, "%s", e.msg);
    check_merged(&in, &out, &st, 0.5);
    quality_measure(&out, &q);
    EXPECT(out.ncells == 2 && st.nundone == 1 && st.nunresolved == 1 && st.reason[0] == MERGE_NO_NEIGHBOUR,
           "%d cells, %d unresolved", out.ncells, st.nunresolved);
    EXPECT(st.skew_max_cut < 4 && q.nskew == 0 && q.skew_max <= st.skew_max_cut + 1e-12, "max skewness %g, cut %g",
           q.skew_max, st.skew_max_cut);
    NEAR(st.skew_max_after, q.skew_max, 1e-12);
    CONTAINS(merge_reason_name(MERGE_SKEWNESS), "maxSkewness");
    merge_stats_free(&st);
    mesh_free(&out);
    mesh_free(&in);
}

int main(void)
{
    RUN(corner_triangle);
    RUN(criterion_spacing);
    RUN(column_of_slaves);
    RUN(chain_and_unresolved);
    RUN(prefer_non_slave);
    RUN(plane_3d);
    RUN(unsound_master_refused);
    RUN(skewness_pass);
    RUN(bad_input);
    return test_summary();
}
