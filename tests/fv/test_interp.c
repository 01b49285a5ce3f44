/*
** test_interp.c: ICCM interpolation stencils (fv/interp.h).
**
** Exact properties: every row sums to 1 (EC) for every method on block,
** cut and merged (sphere, CSG) and 2-D Voronoi grids (multilinear
** refused there, shepard's accuracy measured instead); a point at a source
** returns it (CS); modified Shepard at a face centre of a block grid, even
** a graded one, is the plain mean of the two cells (spec §3.2); eq. 4.61's
** rule on Cartesian faces; multilinear is exact for linear functions on a
** block grid (the box walls reflected) and in the Cartesian region of a
** cut grid.  Measured: multilinear on linear functions near a cut
** boundary (first order, from the centre-versus-node shift the thesis
** accepts), and the convergence of every method on a smooth function at
** the three points of every face of cut sphere grids, with the stencil
** sizes (LI, spec §4.3).  Bad input: an unknown scheme names the file
** and line; multilinear without the cut-cell data names the grid.
*/
#include "cut.h"
#include "fixture.h"
#include "fvmesh.h"
#include "interp.h"
#include "merge.h"
#include "test.h"

#include <math.h>

static const char *const SPHERE = "s { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }";
static const char *const CSG =
    "p { flow inside; shape difference; a { shape box; min (0.2 0.2 0.2); max (0.8 0.8 0.8); }\n"
    "  b { shape sphere; centre (0.8 0.8 0.8); radius 0.33; } }";
static const char *const DISC = "d { flow outside; shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.27; }";

/* Unit-box block grid, N per axis (2-D: one cell of 1/N along flat). */
static void unit_block(Mesh *m, int N, int flat)
{
    int n[3] = {N, N, N};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    if (flat >= 0) {
        n[flat] = 1;
        hi[flat] = 1.0 / N;
    }
    fixture_block(m, n, lo, hi, flat);
}

/* A cut (and, when merge, merged) grid of the unit box; exits on failure. */
static void cut_grid(Mesh *out, int N, int flat, const char *geo, int merge)
{
    Mesh grid;
    unit_block(&grid, N, flat);
    fixture_cut(out, &grid, geo, merge, NULL);
    mesh_free(&grid);
}

static void voronoi_grid(Mesh *out, int N, const char *geo)
{
    Mesh grid;
    unit_block(&grid, N, 2);
    fixture_voronoi(out, &grid, geo);
    mesh_free(&grid);
}

static void opts(InterpOpts *o, int method)
{
    interp_opts_default(o);
    o->method = method;
}

/* Largest |row sum - 1| over every row of the face stencils (empty
   faces' rows are zero rows: |sum|). */
static double worst_sum(const Interp *ip)
{
    double w = 0;
    for (int r = 0; r < ip->face.nrows; r++) {
        int empty = ip->f->empty_face[r / INTERP_NPOINTS]; /* no flux: zero rows */
        w = fmax(w, fabs(stencil_row_sum(&ip->face, r) - !empty));
    }
    return w;
}

typedef double (*Fn)(const double *x);

/* Cell values f(node) and boundary values f(face centre). */
static void sample(const FvMesh *f, Fn fn, double **xc, double **xb)
{
    *xc = mem_alloc(sizeof(double) * (size_t)(f->ncells + 1));
    *xb = mem_alloc(sizeof(double) * (size_t)(f->nboundary + 1));
    for (int c = 0; c < f->ncells; c++) (*xc)[c] = fn(f->node + 3 * c);
    for (int b = 0; b < f->nboundary; b++) (*xb)[b] = fn(f->m->face_centre + 3 * (f->ninternal + b));
}

/* Largest error of the face rows (empty faces carry nothing) against fn
   at their points; rows whose sources are all whole cells go to *cart
   (NULL: not split). */
static double mean_error; /* of the last face_error: the mean over its points */

static double face_error(const Interp *ip, Fn fn, double *cart, int *ncart)
{
    double sum = 0;
    int npts = 0;
    const FvMesh *f = ip->f;
    double *xc, *xb, worst = 0;
    sample(f, fn, &xc, &xb);
    if (cart) *cart = 0, *ncart = 0;
    const CartCells *cc = &f->m->cartcells;
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        for (int k = 0; k < INTERP_NPOINTS; k++) {
            int r = interp_row(i, k);
            double x[3];
            interp_face_point(f, i, k, x);
            double err = fabs(stencil_apply(&ip->face, r, f->ncells, xc, xb) - fn(x));
            sum += err;
            npts++;
            int whole = 1;
            StencilRow row;
            stencil_row(&ip->face, r, &row);
            for (int q = 0; q < row.n && cart; q++) {
                int c = row.src[q];
                whole &= c < f->ncells && cc->parent_off[c + 1] - cc->parent_off[c] == 1 &&
                         cc->role[cc->parent[cc->parent_off[c]]] == CART_WHOLE;
            }
            if (cart && whole) {
                *cart = fmax(*cart, err);
                (*ncart)++;
            } else {
                worst = fmax(worst, err);
            }
        }
    }
    free(xc);
    free(xb);
    mean_error = npts ? sum / npts : 0;
    return worst;
}

static double linear(const double *x) { return 1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2]; }
static double smooth(const double *x) { return sin(2 * x[0]) * cos(3 * x[1]) * exp(x[2]); }

/* Every method on one grid: rows sum to 1; returns the worst. */
static double sums(Mesh *m, const char *name)
{
    FvMesh f;
    Err e;
    double worst = 0;
    if (fvmesh_init(&f, m, &e)) {
        printf("fvmesh_init: %s\n", e.msg);
        return INFINITY;
    }
    for (int meth = 0; meth < 3; meth++) {
        if (meth == INTERP_MULTILINEAR && m->cell_seed) continue; /* refused: voronoi_multilinear */
        InterpOpts o;
        opts(&o, meth);
        Interp ip;
        if (interp_init(&ip, &f, &o, name, &e)) {
            printf("  %s, %s: %s\n", name, interp_method_names[meth], e.msg);
            worst = INFINITY;
            continue;
        }
        double w = worst_sum(&ip);
        printf("  %-22s %-11s rows %7d  |sum-1| %.1e  size mean %.2f max %2d  grown %d reflected %d degenerate %d "
               "fallback %d\n",
               name, interp_method_names[meth], ip.st.nrows, w, ip.st.mean_size, ip.st.max_size, ip.st.ngrown,
               ip.st.nreflect, ip.st.ndegenerate, ip.st.nfallback);
        worst = fmax(worst, w);
        interp_free(&ip);
    }
    fvmesh_free(&f);
    return worst;
}

TEST(row_sums)
{
    Mesh m;
    int n[3] = {5, 4, 3};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    fixture_block(&m, n, lo, hi, -1);
    double w = sums(&m, "block 5x4x3");
    mesh_free(&m);
    EXPECT(w < 1e-14, "block: |sum - 1| = %.3e", w);
    cut_grid(&m, 12, -1, SPHERE, 1);
    w = sums(&m, "sphere 12^3 merged");
    mesh_free(&m);
    EXPECT(w < 1e-12, "sphere: |sum - 1| = %.3e", w);
    cut_grid(&m, 10, -1, CSG, 1);
    w = sums(&m, "box-sphere CSG merged");
    mesh_free(&m);
    EXPECT(w < 1e-12, "CSG: |sum - 1| = %.3e", w);
    voronoi_grid(&m, 16, DISC);
    w = sums(&m, "2-D Voronoi disc 16");
    mesh_free(&m);
    EXPECT(w < 1e-12, "Voronoi: |sum - 1| = %.3e", w);
}

/* CS: a point at a source returns that source alone. */
TEST(at_sources)
{
    Mesh m;
    cut_grid(&m, 10, -1, SPHERE, 1);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    for (int meth = 0; meth < 3; meth++) {
        InterpOpts o;
        opts(&o, meth);
        Interp ip;
        EXPECT(interp_init(&ip, &f, &o, "sphere", &e) == 0, "%s", e.msg);
        Stencil s;
        stencil_init(&s);
        int bad = 0, tested = 0;
        for (int c = 0; c < f.ncells; c++) {
            const CartCells *cc = &m.cartcells;
            int K = cc->parent[cc->parent_off[c]];
            /* multilinear's sources are the Cartesian centres of whole,
               cut and master cells: test it at whole cells' */
            if (meth == INTERP_MULTILINEAR && (cc->parent_off[c + 1] - cc->parent_off[c] != 1 || cc->role[K] != CART_WHOLE))
                continue;
            int r = interp_point(&ip, f.node + 3 * c, 2, &s);
            tested++;
            bad += s.off[r + 1] - s.off[r] != 1 || s.src[s.off[r]] != c || s.w[s.off[r]] != 1.0;
        }
        EXPECT(bad == 0 && tested > 100, "%s: %d of %d nodes not their own value", interp_method_names[meth], bad, tested);
        stencil_free(&s);
        interp_free(&ip);
    }
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Spec §3.2: on a rectilinear grid a face centre sees exactly its two
   adjacent centres, at d = 1/2 each, so modified Shepard is the plain mean;
   with eq. 4.32's own-cell metric this holds on a graded grid too.  The
   face rows follow eq. 4.61 (single-source gradient points). */
TEST(shepard_block_mean)
{
    double *x[3];
    int n[3] = {6, 5, 4};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        x[k][0] = 0;
        for (int i = 0; i < n[k]; i++) x[k][i + 1] = x[k][i] + 0.1 * pow(1.3, i) * (k + 1);
    }
    Mesh m;
    fixture_mesh(&m, x, n);
    for (int k = 0; k < 3; k++) free(x[k]);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    InterpOpts o;
    opts(&o, INTERP_SHEPARD);
    Interp ip;
    EXPECT(interp_init(&ip, &f, &o, "graded block", &e) == 0, "%s", e.msg);
    Stencil s;
    stencil_init(&s);
    int bad = 0, badrule = 0;
    for (int i = 0; i < f.nfaces; i++) {
        int r = interp_point(&ip, m.face_centre + 3 * i, 1, &s), nb = s.off[r + 1] - s.off[r];
        if (i < f.ninternal) {
            for (int q = s.off[r]; q < s.off[r + 1]; q++)
                bad += fabs(s.w[q] - 0.5) > 1e-15 || (s.src[q] != m.owner[i] && s.src[q] != m.neighbour[i]);
            bad += nb != 2;
        } else {
            bad += nb != 1 || s.src[s.off[r]] != m.owner[i];
        }
        StencilRow rp, rm;
        stencil_row(&ip.face, interp_row(i, INTERP_PLUS), &rp);
        stencil_row(&ip.face, interp_row(i, INTERP_MINUS), &rm);
        badrule += rm.n != 1 || rm.src[0] != m.owner[i] || rm.w[0] != 1.0;
        badrule += rp.n != 1 || rp.src[0] != (i < f.ninternal ? m.neighbour[i] : f.ncells + i - f.ninternal) ||
                   rp.w[0] != 1.0;
        /* eq. 4.61's rows of an internal face are the stencil's pair rows:
           nothing stored */
        badrule += i < f.ninternal && !stencil_is_pair(&ip.face, interp_row(i, INTERP_CENTRE));
    }
    EXPECT(bad == 0, "%d face centres not the plain mean of their cells", bad);
    EXPECT(badrule == 0, "%d gradient rows not single-source (eq. 4.61)", badrule);
    EXPECT(ip.st.ngrown == 0 && ip.st.ncartesian == f.ninternal, "grown %d, Cartesian faces %d of %d", ip.st.ngrown,
           ip.st.ncartesian, f.ninternal);
    stencil_free(&s);
    interp_free(&ip);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Multilinear on a block grid is exact for a linear function anywhere in
   the box, the walls reflected with Dirichlet values (eq. 4.19/4.20). */
TEST(multilinear_block_linear)
{
    double *x[3];
    int n[3] = {5, 4, 6};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        x[k][0] = -0.5;
        for (int i = 0; i < n[k]; i++) x[k][i + 1] = x[k][i] + 0.2 * pow(1.2, i);
    }
    Mesh m;
    fixture_mesh(&m, x, n);
    FvMesh f;
    Err e;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    InterpOpts o;
    opts(&o, INTERP_MULTILINEAR);
    Interp ip;
    EXPECT(interp_init(&ip, &f, &o, "graded block", &e) == 0, "%s", e.msg);
    double *xc, *xb, worst = 0;
    sample(&f, linear, &xc, &xb);
    Stencil s;
    stencil_init(&s);
    unsigned seed = 12345;
    for (int t = 0; t < 2000; t++) {
        double p[3];
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            p[k] = x[k][0] + (x[k][n[k]] - x[k][0]) * ((seed >> 8) & 0xffff) / 65535.0;
        }
        int r = interp_point(&ip, p, 2, &s);
        worst = fmax(worst, fabs(stencil_apply(&s, r, f.ncells, xc, xb) - linear(p)));
    }
    printf("  graded block, 2000 random points: largest error %.2e, %d ghosts reflected\n", worst, ip.st.nreflect);
    EXPECT(worst < 1e-12, "multilinear off a linear function by %.3e", worst);
    EXPECT(ip.st.nreflect > 100 && ip.st.ndegenerate == 0, "reflected %d, degenerate %d", ip.st.nreflect,
           ip.st.ndegenerate);
    for (int k = 0; k < 3; k++) free(x[k]);
    free(xc);
    free(xb);
    stencil_free(&s);
    interp_free(&ip);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Cyclic faces are internal faces of the periodic domain.  On the 6 x 4
   block periodic in x (column values a_i (1 + y)): every cyclic face has
   h_f = ht_f = half a cell and the face rule of eq. 4.61 (both cells
   whole), its PLUS row is the cell at the other end and its partner's
   rows are its own with PLUS and MINUS swapped; Shepard at a point on a
   cyclic side finds the far column through the periodic image, so on the
   side between two centres it returns the mean of the two end columns. */
static const double column_a[6];

TEST(cyclic_faces)
{
    double *x[3];
    int n[3] = {6, 4, 1};
    double lo[3] = {0, 0, -0.1}, hi[3] = {1.2, 0.8, 0.1};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = lo[k] + (hi[k] - lo[k]) * i / n[k];
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"}, {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},     {"fb", "empty", NULL},          {"fb", "empty", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    FvMesh f;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    InterpOpts o;
    opts(&o, INTERP_SHEPARD);
    Interp ip;
    EXPECT(interp_init(&ip, &f, &o, "cyclic block", &e) == 0, "%s", e.msg);
    const Patch *pl = &m.patches[mesh_patch(&m, "left")], *pr = &m.patches[mesh_patch(&m, "right")];
    int bad = 0;
    for (int i = 0; i < pl->size; i++) {
        int fl = pl->start + i, fr = pr->start + i, cl = m.owner[fl], cr = m.owner[fr];
        StencilRow lp, lm, rp, rm;
        stencil_row(&ip.face, interp_row(fl, INTERP_PLUS), &lp);
        stencil_row(&ip.face, interp_row(fl, INTERP_MINUS), &lm);
        stencil_row(&ip.face, interp_row(fr, INTERP_PLUS), &rp);
        stencil_row(&ip.face, interp_row(fr, INTERP_MINUS), &rm);
        bad += f.cyc_face[fl - f.ninternal] != fr || !f.cartesian_face[fl] || fabs(f.h[fl] - 0.1) > 1e-15 ||
               fabs(f.ht[fl] - 0.1) > 1e-15;
        bad += lp.n != 1 || lp.src[0] != cr;
        bad += rm.n != 1 || rm.src[0] != cr;
        bad += lm.src[0] != cl || rp.src[0] != cl;
    }
    EXPECT(bad == 0, "%d wrong cyclic face quantities or rows", bad);
    double *xc = mem_alloc(sizeof(double) * (size_t)f.ncells), *xb = mem_alloc(sizeof(double) * (size_t)f.nboundary);
    for (int c = 0; c < f.ncells; c++) xc[c] = column_a[(int)(f.node[3 * c] / 0.2)] * (1 + f.node[3 * c + 1]);
    for (int b = 0; b < f.nboundary; b++) xb[b] = 1e3;
    Stencil s;
    stencil_init(&s);
    double worst = 0;
    for (int j = 0; j < 4; j++)
        for (int side2 = 0; side2 < 2; side2++) {
            double p[3] = {side2 ? 1.2 : 0, 0.1 + 0.2 * j, 0};
            int r = interp_point(&ip, p, 2, &s);
            worst = fmax(worst, fabs(stencil_apply(&s, r, f.ncells, xc, xb) - 0.5 * (column_a[0] + column_a[5]) * (1 + p[1])));
        }
    printf("  cyclic block 6 x 4: %d cyclic faces as internal faces; Shepard on the sides off the mean of the end "
           "columns by %.2e\n", pl->size, worst);
    EXPECT(worst < 1e-14, "Shepard across the cyclic sides off by %.3e", worst);
    for (int k = 0; k < 3; k++) free(x[k]);
    free(xc);
    free(xb);
    stencil_free(&s);
    interp_free(&ip);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Multilinear across a cyclic pair of sides: the lattice is periodic, so a
   point within half a cell of a side takes the centre beyond it from the
   far column.  Cell values a_i (1 + y), a_i arbitrary per column: next to
   either side the value must be the linear blend of the last and the
   first column's a, times (1 + y), to round-off (the boundary values, set
   far off, are never used); without the periodic lattice the centre
   beyond the side was mirrored at it from the boundary value. */
static const double column_a[6] = {3, -1, 2, 5, 0, 7};

TEST(multilinear_cyclic)
{
    double *x[3];
    int n[3] = {6, 4, 1};
    double lo[3] = {0, 0, -0.1}, hi[3] = {1.2, 0.8, 0.1};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = lo[k] + (hi[k] - lo[k]) * i / n[k];
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"}, {"walls", "wall", NULL},
                                    {"walls", "wall", NULL},     {"fb", "empty", NULL},          {"fb", "empty", NULL}};
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(block_mesh(&m, x, n, side, NULL, "test", NULL, &e) == 0, "%s", e.msg);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    FvMesh f;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    InterpOpts o;
    opts(&o, INTERP_MULTILINEAR);
    Interp ip;
    EXPECT(interp_init(&ip, &f, &o, "cyclic block", &e) == 0, "%s", e.msg);
    double *xc = mem_alloc(sizeof(double) * (size_t)f.ncells), *xb = mem_alloc(sizeof(double) * (size_t)f.nboundary);
    for (int c = 0; c < f.ncells; c++) xc[c] = column_a[(int)(f.node[3 * c] / 0.2)] * (1 + f.node[3 * c + 1]);
    for (int b = 0; b < f.nboundary; b++) xb[b] = 1e3;
    Stencil s;
    stencil_init(&s);
    double worst = 0;
    int far = 0;
    for (int t = 0; t <= 20; t++) {
        /* along both cyclic sides, within half a cell, between the y centres */
        double p[3] = {t % 2 ? 1.2 - 0.005 * t : 0.005 * t, 0.1 + 0.03 * t, 0};
        int r = interp_point(&ip, p, 2, &s);
        double tx = p[0] < 0.6 ? (p[0] + 0.1) / 0.2 : (p[0] - 1.1) / 0.2;
        double want = ((1 - tx) * column_a[5] + tx * column_a[0]) * (1 + p[1]);
        worst = fmax(worst, fabs(stencil_apply(&s, r, f.ncells, xc, xb) - want));
        for (int q = s.off[r]; q < s.off[r + 1]; q++) {
            int c = s.src[q];
            far += c < f.ncells && fabs(f.node[3 * c] - p[0]) > 0.6;
        }
    }
    printf("  cyclic block 6 x 4: largest error %.2e at 21 points next to the cyclic sides, %d far-column sources\n",
           worst, far);
    EXPECT(worst < 1e-12, "multilinear across the cyclic sides off by %.3e", worst);
    EXPECT(far > 0, "no source from the far column");
    for (int k = 0; k < 3; k++) free(x[k]);
    free(xc);
    free(xb);
    stencil_free(&s);
    interp_free(&ip);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* Multilinear on a cut sphere grid: exact for a linear function where all
   sources are whole cells; near the cut boundary, with Dirichlet values of
   the function, first order (the thesis's sources are Cartesian centres,
   a cut or merged cell's node is O(h) away): the largest error over
   |grad f| h, measured 0.61 at N = 16 and 0.86 at N = 32 (3-D sphere,
   merged) and 0.42, 0.20 (2-D disc), is asserted below 1.5. */
TEST(multilinear_cut_linear)
{
    int ns[2] = {16, 32};
    for (int flat = -1; flat <= 2; flat += 3)
        for (int t = 0; t < 2; t++) {
            Mesh m;
            cut_grid(&m, ns[t], flat, flat < 0 ? SPHERE : DISC, 1);
            FvMesh f;
            Err e;
            EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
            InterpOpts o;
            opts(&o, INTERP_MULTILINEAR);
            Interp ip;
            EXPECT(interp_init(&ip, &f, &o, "sphere", &e) == 0, "%s", e.msg);
            double cart;
            int ncart;
            double err = face_error(&ip, linear, &cart, &ncart);
            double h = 1.0 / ns[t];
            double G = sqrt(4 + 9 + (flat < 0 ? 0.25 : 0));
            printf("  %s N = %2d: whole-cell rows %6d error %.1e; rows near the boundary: error %.3e = %.2f |grad f| h\n",
                   flat < 0 ? "3-D sphere" : "2-D disc  ", ns[t], ncart, cart, err, err / (G * h));
            EXPECT(cart < 1e-12 && ncart > 500, "whole-cell rows: %d, error %.3e", ncart, cart);
            EXPECT(err < 1.5 * G * h, "error %.3e > 1.5 |grad f| h near the cut boundary", err);
            /* 2-D: the rows next to walls are corrected (interp_lin.c) */
            if (flat >= 0) EXPECT(err < 1e-12, "2-D disc near the wall: linear error %.3e, not round-off", err);
            interp_free(&ip);
            fvmesh_free(&f);
            mesh_free(&m);
        }
}

/* Multilinear on a Voronoi grid is refused (interp_ml_check): each
   Cartesian centre holding a seed stands for that Voronoi cell, whose node
   can be far from it, and the mms study found O(1) errors (a wall cell's
   density 3.6 for 0.94 on the steady disc).  The face rows alone did not
   show it: measured before the refusal on the 2-D disc, largest error at
   the face points, linear and sin(2x) cos(3y) e^z,
       N = 16  shepard 2.0e-15, 6.2e-3   multilinear 3.8e-15, 6.5e-3
       N = 32  shepard 4.3e-15, 1.7e-3   multilinear 1.8e-15, 4.4e-3
   (linear exact: interp_lin.c corrects the wall rows; multilinear's smooth
   error converges at order 0.6 against shepard's 1.8).  Asserted: the
   refusal with file:line, and shepard's accuracy there. */
TEST(voronoi_multilinear)
{
    double smo[2];
    for (int t = 0; t < 2; t++) {
        Mesh m;
        int N = 16 << t;
        voronoi_grid(&m, N, DISC);
        FvMesh f;
        Err e;
        EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
        const char *txt = "interpolationSchemes\n{\n    default multilinear;\n}\n";
        Dict *d = dict_parse(txt, strlen(txt), "system/fvSchemes", &e);
        EXPECT(d != NULL, "%s", e.msg);
        InterpOpts o;
        EXPECT(interp_read_opts(d, &o, &e) == 0, "%s", e.msg);
        Interp ip;
        EXPECT(interp_init(&ip, &f, &o, "constant/polyMesh", &e) != 0, "multilinear built on a Voronoi grid");
        CONTAINS(e.msg, "system/fvSchemes:3: interpolation scheme multilinear is not available on Voronoi grids");
        CONTAINS(e.msg, "constant/polyMesh");
        CONTAINS(e.msg, "choose shepard");
        dict_free(d);
        opts(&o, INTERP_SHEPARD);
        EXPECT(interp_init(&ip, &f, &o, "voronoi", &e) == 0, "%s", e.msg);
        double lin = face_error(&ip, linear, NULL, NULL);
        smo[t] = face_error(&ip, smooth, NULL, NULL);
        printf("  Voronoi disc N = %2d shepard: linear max %.1e, smooth max %.2e\n", N, lin, smo[t]);
        EXPECT(lin < 1e-12, "shepard on the Voronoi disc: linear error %.3e", lin);
        interp_free(&ip);
        fvmesh_free(&f);
        mesh_free(&m);
    }
    double order = log2(smo[0] / smo[1]);
    EXPECT(smo[1] < 2.5e-3 && order > 1.5, "shepard smooth error %.2e, order %.2f", smo[1], order);
}

/* Convergence at the three points of every face on cut sphere grids:
   sin(2x) cos(3y) e^z, cells at their nodes, Dirichlet boundary values;
   largest and mean error over the points. */
static double maxerr[3]; /* merged, N = 64 */

static void convergence_on(int merge, double order[3][2])
{
    int ns[3] = {16, 32, 64};
    double err[3][3], mean[3][3], size[3][3];
    int maxsize[3][3];
    for (int t = 0; t < 3; t++) {
        Mesh m;
        cut_grid(&m, ns[t], -1, SPHERE, merge);
        FvMesh f;
        Err e;
        EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
        for (int meth = 0; meth < 3; meth++) {
            InterpOpts o;
            opts(&o, meth);
            Interp ip;
            EXPECT(interp_init(&ip, &f, &o, "sphere", &e) == 0, "%s", e.msg);
            err[meth][t] = face_error(&ip, smooth, NULL, NULL);
            mean[meth][t] = mean_error;
            size[meth][t] = ip.st.mean_size;
            maxsize[meth][t] = ip.st.max_size;
            interp_free(&ip);
        }
        fvmesh_free(&f);
        mesh_free(&m);
    }
    printf("  sin(2x)cos(3y)e^z at the face points, outside a sphere r = 0.3, %s\n", merge ? "cut and merged" : "cut");
    printf("  %-11s %4s %11s %6s %11s %6s %9s %4s\n", "method", "N", "max error", "order", "mean error", "order",
           "size mean", "max");
    for (int meth = 0; meth < 3; meth++) {
        for (int t = 0; t < 3; t++) {
            char o1[16] = "", o2[16] = "";
            if (t > 0) {
                snprintf(o1, sizeof o1, "%.2f", log(err[meth][t - 1] / err[meth][t]) / log(2.0));
                snprintf(o2, sizeof o2, "%.2f", log(mean[meth][t - 1] / mean[meth][t]) / log(2.0));
            }
            printf("  %-11s %4d %11.3e %6s %11.3e %6s %9.2f %4d\n", interp_method_names[meth], ns[t], err[meth][t], o1,
                   mean[meth][t], o2, size[meth][t], maxsize[meth][t]);
        }
        order[meth][0] = log(err[meth][0] / err[meth][2]) / log(4.0);
        if (merge) maxerr[meth] = err[meth][2];
        order[meth][1] = log(mean[meth][0] / mean[meth][2]) / log(4.0);
    }
}

TEST(convergence)
{
    double p[2][3][2];
    for (int merge = 0; merge < 2; merge++) convergence_on(merge, p[merge]);
    for (int meth = 0; meth < 3; meth++)
        printf("  %-11s observed orders N = 16 to 64: cut max %.2f mean %.2f; merged max %.2f mean %.2f\n",
               interp_method_names[meth], p[0][meth][0], p[0][meth][1], p[1][meth][0], p[1][meth][1]);
    for (int meth = 0; meth < 3; meth++) {
        const char *nm = interp_method_names[meth];
        EXPECT(p[0][meth][0] > 0.7, "%s on cut grids: max-error order %.2f, expected about 1", nm, p[0][meth][0]);
        EXPECT(p[0][meth][1] > 1.5 && p[1][meth][1] > 1.5, "%s: mean-error orders %.2f, %.2f, expected about 2", nm,
               p[0][meth][1], p[1][meth][1]);
        EXPECT(maxerr[meth] < 15.0 / 64, "%s on the merged N = 64 grid: max error %.3e above 15 h", nm, maxerr[meth]);
    }
}

TEST(bad_input)
{
    const char *txt = "interpolationSchemes\n{\n    default shepherd;\n}\n";
    Err e;
    Dict *d = dict_parse(txt, strlen(txt), "system/fvSchemes", &e);
    EXPECT(d != NULL, "%s", e.msg);
    InterpOpts o;
    EXPECT(interp_read_opts(d, &o, &e) != 0, "an unknown scheme accepted");
    CONTAINS(e.msg, "system/fvSchemes:3");
    CONTAINS(e.msg, "shepherd");
    dict_free(d);
    txt = "interpolationSchemes\n{\n    default multilinear;\n    shepardCoeffs { beta 3; radius 1.5; boundarySources on; }\n}\n";
    d = dict_parse(txt, strlen(txt), "system/fvSchemes", &e);
    EXPECT(interp_read_opts(d, &o, &e) == 0, "%s", e.msg);
    EXPECT(o.method == INTERP_MULTILINEAR && o.beta == 3 && o.radius == 1.5 && o.boundary_sources && o.line == 3,
           "read method %d beta %g radius %g boundarySources %d line %d", o.method, o.beta, o.radius,
           o.boundary_sources, o.line);
    /* multilinear without the cut-cell data contract */
    Mesh m;
    cut_grid(&m, 8, -1, SPHERE, 0);
    cartcells_free(&m.cartcells);
    FvMesh f;
    EXPECT(fvmesh_init(&f, &m, &e) == 0, "%s", e.msg);
    Interp ip;
    EXPECT(interp_init(&ip, &f, &o, "constant/polyMesh", &e) != 0, "multilinear built without cartesianCells");
    CONTAINS(e.msg, "system/fvSchemes:3: interpolation scheme multilinear");
    CONTAINS(e.msg, "constant/polyMesh");
    dict_free(d);
    d = dict_parse("", 0, "system/fvSchemes", &e);
    EXPECT(interp_read_opts(d, &o, &e) == 0 && o.method == INTERP_SHEPARD && o.beta == 2 && o.radius == 1 &&
               !o.boundary_sources,
           "defaults");
    /* boundary-face sources: every row still sums to 1 */
    o.boundary_sources = 1;
    EXPECT(interp_init(&ip, &f, &o, "sphere", &e) == 0, "%s", e.msg);
    EXPECT(worst_sum(&ip) < 1e-12, "boundarySources on: |sum - 1| = %.3e", worst_sum(&ip));
    interp_free(&ip);
    dict_free(d);
    fvmesh_free(&f);
    mesh_free(&m);
}


int main(void)
{
    RUN(row_sums);
    RUN(at_sources);
    RUN(shepard_block_mean);
    RUN(multilinear_block_linear);
    RUN(multilinear_cyclic);
    RUN(cyclic_faces);
    RUN(multilinear_cut_linear);
    RUN(voronoi_multilinear);
    RUN(convergence);
    RUN(bad_input);
    return test_summary();
}
