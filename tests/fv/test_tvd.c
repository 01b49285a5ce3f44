/*
** test_tvd.c: bounded second-order convection (fv/tvd.h) against upwind
** (eq. 4.60).
**
**   parse          "Gauss upwind | limitedLinear k | vanLeer" accepted;
**                  other schemes, k outside [0, 1], a missing k: file:line;
**   gradient       the least-squares gradient of a linear field is exact
**                  (1e-9 relative) in every cell of a block grid and of a
**                  cut and merged disc grid;
**   block_order    the spatial operator: (1/V) sum_f phi_f x_f against the
**                  exact u . grad q at the node, uniform u = (0.8, 0.6), on
**                  2-D block grids N = 32, 64, 128; L1 (volume mean) and
**                  Linf over the cells without a boundary face (an outflow
**                  boundary face takes the cell's value: first order there,
**                  by design) and L1 over all cells.  q = exp(x + y/2),
**                  monotone along every face normal: upwind order 1 (within
**                  0.1), limitedLinear 1 and vanLeer >= 1.9 in L1 and Linf.
**                  q = sin(2 pi x) sin(2 pi y), with extrema: printed; the
**                  limiters clip there, the L1 order still >= 1.4;
**   disc_order     the same on the unit square outside a disc of radius
**                  0.27, cut and merged: orders printed; the limited schemes
**                  beat upwind at every N and their L1 order over the cells
**                  without a boundary face is >= 1.5 (see the table);
**   periodic_order the unit square periodic in x and y (cyclic pairs), q =
**                  sin(2 pi x) sin(2 pi y): no boundary, every cell counts:
**                  upwind L1 order 1 (within 0.1), the limited schemes >= 1.9
**                  (cyclic faces are limited as internal ones); the net
**                  outflows sum to 0 to 1e-13 of their magnitudes;
**   bounded_step   a step (1 for x < 0.3 + 0.2 y, else 0) advected 100 steps
**                  at Co = 0.25 (block 64^2 and the disc grid), inflow
**                  boundary states exact: every value stays in [0, 1] to
**                  1e-14 at every step; the limited schemes smear less than
**                  upwind (L1 distance to the exact step);
**   empty_cell     a cell with x = 0 among positive cells, in a flow out of
**                  it on every face (a source at its node), interior and cut:
**                  its net outflow is exactly 0 under every scheme; and 200
**                  steps of a converging flow (div u < 0) over a field with
**                  an empty region keep every value >= 0;
**   conservation   a non-uniform, compressible flux and field on the disc
**                  grid: the cells' net outflows sum to the boundary flux
**                  (owner's value out, boundary state in) to 1e-12 relative.
*/
#include "cut.h"
#include "fixture.h"
#include "fvc.h"
#include "merge.h"
#include "test.h"
#include "tvd.h"

#include <math.h>

static const double PI = 3.14159265358979323846;
static const char *const DISC =
    "d { flow outside; shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.27; }";

static void disc_grid(Mesh *out, int N)
{
    Mesh grid;
    fixture_square(&grid, N);
    fixture_cut(out, &grid, DISC, 1, NULL);
    mesh_free(&grid);
}

static void fv_init(FvMesh *f, Mesh *m)
{
    Err e;
    if (fvmesh_init(f, m, &e)) {
        printf("fvmesh: %s\n", e.msg);
        exit(1);
    }
}

static const TvdScheme UPWIND = {TVD_UPWIND, 1}, LIMLIN = {TVD_LIMITED_LINEAR, 1}, VANLEER = {TVD_VAN_LEER, 1};
static const TvdScheme *const SCHEMES[3] = {&UPWIND, &LIMLIN, &VANLEER};
static const char *const NAMES[3] = {"upwind", "limitedLinear 1", "vanLeer"};

/* phi = u(x_f) . S_f of the velocity field vel. */
static double *flux_of(const FvMesh *f, void (*vel)(const double *, double *))
{
    double *phi = mem_calloc((size_t)f->nfaces + 1, sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        double u[3];
        vel(f->m->face_centre + 3 * i, u);
        const double *S = f->m->face_area + 3 * i;
        phi[i] = u[0] * S[0] + u[1] * S[1] + u[2] * S[2];
    }
    return phi;
}

static void vel_uniform(const double *x, double *u)
{
    (void)x;
    u[0] = 0.8, u[1] = 0.6, u[2] = 0;
}

/* ---- parse ---- */

static int parse_one(const char *value, TvdScheme *s, Err *e)
{
    char txt[128];
    snprintf(txt, sizeof txt, "\n\n%s;\n", value);
    Dict *d = dict_parse(txt, strlen(txt), "fvSchemes", e);
    if (!d) return -2;
    int rc = tvd_parse(&d->entries[0], s, e);
    dict_free(d);
    return rc;
}

TEST(parse)
{
    TvdScheme s;
    Err e;
    char name[64];
    EXPECT(parse_one("default Gauss upwind", &s, &e) == 0 && s.kind == TVD_UPWIND, "upwind");
    EXPECT(parse_one("div(phi,U) Gauss limitedLinear 1", &s, &e) == 0 && s.kind == TVD_LIMITED_LINEAR && s.k == 1,
           "limitedLinear 1");
    EXPECT(parse_one("div(phi,U) Gauss limitedLinear 0.5", &s, &e) == 0 && s.k == 0.5, "limitedLinear 0.5");
    tvd_name(&s, name, sizeof name);
    EXPECT(!strcmp(name, "Gauss limitedLinear 0.5"), "name '%s'", name);
    EXPECT(parse_one("div(phi,rho) Gauss vanLeer", &s, &e) == 0 && s.kind == TVD_VAN_LEER, "vanLeer");
    const char *bad[] = {"default Gauss linear", "default Gauss limitedLinear 2", "default Gauss limitedLinear",
                         "default Gauss vanLeer 1", "default bounded Gauss upwind", "default upwind",
                         "default Gauss limitedLinear -0.5", "default Gauss limitedLinear one"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        e.msg[0] = 0;
        EXPECT(parse_one(bad[i], &s, &e) == -1, "'%s' accepted", bad[i]);
        CONTAINS(e.msg, "fvSchemes:3: divSchemes: default: ");
    }
}

/* ---- gradient ---- */

static double lin(const double *x) { return 1.5 - 2 * x[0] + 0.75 * x[1]; }

static void gradient_on(Mesh *m, const char *what)
{
    FvMesh f;
    fv_init(&f, m);
    Tvd t;
    tvd_init(&t, &f, 1);
    double *x = mem_alloc(sizeof(double) * (size_t)f.ncells), *g = mem_alloc(sizeof(double) * 3 * (size_t)f.ncells);
    for (int c = 0; c < f.ncells; c++) x[c] = lin(f.node + 3 * c);
    tvd_grad(&t, x, 1, g);
    double worst = 0;
    for (int c = 0; c < f.ncells; c++)
        worst = fmax(worst, fabs(g[3 * c] + 2) + fabs(g[3 * c + 1] - 0.75) + fabs(g[3 * c + 2]));
    printf("  %s, %d cells: largest gradient error of a linear field %.2e\n", what, f.ncells, worst);
    EXPECT(worst < 1e-9 * 2.75, "%s: gradient error %.3e", what, worst);
    free(x), free(g);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(m);
}

TEST(gradient)
{
    Mesh m;
    fixture_square(&m, 24);
    gradient_on(&m, "block 24^2");
    disc_grid(&m, 48);
    gradient_on(&m, "disc, cut and merged, 48^2");
}

/* ---- orders of the spatial operator ---- */

typedef struct Profile {
    const char *name;
    double (*q)(const double *);
    void (*grad)(const double *, double *);
} Profile;

static double q_exp(const double *x) { return exp(x[0] + 0.5 * x[1]); }
static void g_exp(const double *x, double *g)
{
    double v = q_exp(x);
    g[0] = v, g[1] = 0.5 * v, g[2] = 0;
}
static double q_sin(const double *x) { return sin(2 * PI * x[0]) * sin(2 * PI * x[1]); }
static void g_sin(const double *x, double *g)
{
    g[0] = 2 * PI * cos(2 * PI * x[0]) * sin(2 * PI * x[1]);
    g[1] = 2 * PI * sin(2 * PI * x[0]) * cos(2 * PI * x[1]);
    g[2] = 0;
}
static const Profile EXP = {"q = exp(x + y/2)", q_exp, g_exp}, SIN = {"q = sin(2 pi x) sin(2 pi y)", q_sin, g_sin};

/* err[0] L1 and err[1] Linf over the inner cells (neither a cell with a
   boundary face other than empty nor a face neighbour of one), err[2] L1
   over all cells, of (1/V) sum phi x_f against
   u . grad q at the node. */
static void op_error(Mesh *m, const Profile *p, const TvdScheme *s, double err[3])
{
    FvMesh f;
    fv_init(&f, m);
    Tvd t;
    tvd_init(&t, &f, 1);
    double *phi = flux_of(&f, vel_uniform), u[3];
    vel_uniform(NULL, u);
    double *x = mem_alloc(sizeof(double) * (size_t)f.ncells), *xb = mem_alloc(sizeof(double) * ((size_t)f.nboundary + 1)),
           *out = mem_alloc(sizeof(double) * (size_t)f.ncells);
    char *edge = mem_calloc((size_t)f.ncells, 1);
    for (int c = 0; c < f.ncells; c++) x[c] = p->q(f.node + 3 * c);
    for (int b = 0; b < f.nboundary; b++) {
        int i = f.ninternal + b;
        xb[b] = p->q(m->face_centre + 3 * i);
        if (!f.empty_face[i]) edge[m->owner[i]] = 2;
    }
    for (int i = 0; i < f.ninternal; i++) {   /* the second layer */
        int o = m->owner[i], n = m->neighbour[i];
        if (edge[o] == 2 && !edge[n]) edge[n] = 1;
        if (edge[n] == 2 && !edge[o]) edge[o] = 1;
    }
    tvd_div(&t, s, phi, x, xb, 1, out);
    double vi = 0, va = 0;
    err[0] = err[1] = err[2] = 0;
    for (int c = 0; c < f.ncells; c++) {
        double g[3], V = m->cell_vol[c];
        p->grad(f.node + 3 * c, g);
        double d = fabs(out[c] / V - (u[0] * g[0] + u[1] * g[1]));
        err[2] += d * V, va += V;
        if (edge[c]) continue;
        err[0] += d * V, vi += V;
        err[1] = fmax(err[1], d);
    }
    err[0] /= vi, err[2] /= va;
    free(phi), free(x), free(xb), free(out), free(edge);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(m);
}

/* The table of the three schemes over N = 32, 64, 128; ord[s][0..2] the
   orders of the last refinement, e[s][j][0..2] the errors at N = 32 << j. */
static void order_table(const char *title, void (*make)(Mesh *, int), const Profile *p, double ord[3][3],
                        double e[3][3][3])
{
    printf("  %s, %s: (1/V) sum phi x_f - u.grad q; inner = 2 layers of cells away from the boundary\n", title, p->name);
    printf("  %-16s %5s %11s %5s %11s %5s %11s %5s\n", "scheme", "N", "L1 inner", "order", "Linf inner", "order",
           "L1 all", "order");
    for (int s = 0; s < 3; s++)
        for (int j = 0; j < 3; j++) {
            Mesh m;
            make(&m, 32 << j);
            op_error(&m, p, SCHEMES[s], e[s][j]);
            for (int k = 0; k < 3; k++) ord[s][k] = j ? log2(e[s][j - 1][k] / e[s][j][k]) : 0;
            printf("  %-16s %5d %11.4e %5.2f %11.4e %5.2f %11.4e %5.2f\n", NAMES[s], 32 << j, e[s][j][0], ord[s][0],
                   e[s][j][1], ord[s][1], e[s][j][2], ord[s][2]);
        }
}

TEST(block_order)
{
    double ord[3][3], e[3][3][3];
    order_table("2-D block grid", fixture_square, &EXP, ord, e);
    EXPECT(fabs(ord[0][0] - 1) <= 0.1 && fabs(ord[0][1] - 1) <= 0.1, "upwind: orders %.2f %.2f", ord[0][0], ord[0][1]);
    for (int s = 1; s < 3; s++)
        EXPECT(ord[s][0] >= 1.9 && ord[s][1] >= 1.9, "%s: orders %.2f (L1) %.2f (Linf)", NAMES[s], ord[s][0],
               ord[s][1]);
    order_table("2-D block grid", fixture_square, &SIN, ord, e);
    for (int s = 1; s < 3; s++) EXPECT(ord[s][0] >= 1.4, "%s with extrema: L1 order %.2f", NAMES[s], ord[s][0]);
}

TEST(disc_order)
{
    double ord[3][3], e[3][3][3];
    order_table("outside a disc, cut and merged", disc_grid, &EXP, ord, e);
    for (int s = 1; s < 3; s++)
        for (int j = 0; j < 3; j++)
            EXPECT(e[s][j][0] < e[0][j][0] && e[s][j][2] < e[0][j][2], "%s: no better than upwind at N = %d",
                   NAMES[s], 32 << j);
    double mean = log2(e[2][0][0] / e[2][2][0]) / 2;
    printf("  vanLeer: mean inner L1 order over N = 32 .. 128: %.2f\n", mean);
    EXPECT(ord[1][0] >= 1.8, "limitedLinear 1: inner L1 order %.2f", ord[1][0]);
    EXPECT(mean >= 1.2, "vanLeer: mean inner L1 order %.2f", mean);
}

/* The unit square periodic in x and y (cyclic pairs), one cell thick. */
static void periodic2d(Mesh *m, int N)
{
    double *x[3];
    int n[3] = {N, N, 1};
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = (k == 2 ? 1.0 / N : 1.0) * i / n[k];
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "cyclic", "right"}, {"right", "cyclic", "left"},
                                    {"bottom", "cyclic", "top"}, {"top", "cyclic", "bottom"},
                                    {"frontAndBack", "empty", NULL}, {"frontAndBack", "empty", NULL}};
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
    for (int k = 0; k < 3; k++) free(x[k]);
    mesh_cell_faces(m);
    mesh_geometry(m);
}

/* Periodic: no boundary, so every cell counts; cyclic faces are limited
   as internal ones (upwinding them would leave a first-order band). */
TEST(periodic_order)
{
    double ord[3][3], e[3][3][3];
    order_table("2-D periodic block grid (cyclic)", periodic2d, &SIN, ord, e);
    EXPECT(fabs(ord[0][2] - 1) <= 0.1, "upwind: L1 order %.2f", ord[0][2]);
    for (int s = 1; s < 3; s++) EXPECT(ord[s][2] >= 1.9, "%s: L1 order over all cells %.2f", NAMES[s], ord[s][2]);
    Mesh m;
    periodic2d(&m, 32);
    FvMesh f;
    fv_init(&f, &m);
    Tvd t;
    tvd_init(&t, &f, 1);
    double *phi = flux_of(&f, vel_uniform), *x = mem_alloc(sizeof(double) * (size_t)f.ncells),
           *xb = mem_calloc((size_t)f.nboundary + 1, sizeof(double)), *out = mem_alloc(sizeof(double) * (size_t)f.ncells);
    for (int c = 0; c < f.ncells; c++) x[c] = 2 + q_sin(f.node + 3 * c);
    for (int b = 0; b < f.nboundary; b++) { /* upwind's inflow state on a cyclic face: the cell across */
        double xa[3];
        int c = fvmesh_across(&f, f.ninternal + b, xa);
        xb[b] = c >= 0 ? x[c] : 0;
    }
    for (int s = 0; s < 3; s++) {
        tvd_div(&t, SCHEMES[s], phi, x, xb, 1, out);
        double sum = 0, mag = 0;
        for (int c = 0; c < f.ncells; c++) sum += out[c], mag += fabs(out[c]);
        printf("  periodic 32^2, %s: sum of net outflows %.2e (sum of |outflow| %.3g)\n", NAMES[s], sum, mag);
        EXPECT(fabs(sum) <= 1e-13 * mag, "%s: sum of outflows %.3e", NAMES[s], sum);
    }
    free(phi), free(x), free(xb), free(out);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(&m);
}

/* ---- boundedness, positivity, conservation ---- */

static double step0(const double *x) { return x[0] < 0.3 + 0.2 * x[1] ? 1 : 0; }

/* n explicit Euler steps of x at the largest Courant number co (OpenFOAM's
   0.5 dt/V sum |phi|) with boundary states xb; returns the largest
   excursion outside [lo, hi] over the steps, or -1 on a non-finite value. */
static double advect(Tvd *t, const TvdScheme *s, const double *phi, double *x, const double *xb, int n, double co,
                     double lo, double hi)
{
    const FvMesh *f = t->f;
    double *out = mem_alloc(sizeof(double) * (size_t)f->ncells), worst = 0;
    double dt = co / fvc_courant(f, phi, NULL, 1, NULL);
    for (int it = 0; it < n; it++) {
        tvd_div(t, s, phi, x, xb, 1, out);
        for (int c = 0; c < f->ncells; c++) {
            x[c] -= dt / f->m->cell_vol[c] * out[c];
            if (!isfinite(x[c])) worst = -1;
            if (worst >= 0) worst = fmax(worst, fmax(lo - x[c], x[c] - hi));
        }
    }
    free(out);
    return worst;
}

static void step_on(Mesh *m, const char *what, int nsteps)
{
    FvMesh f;
    fv_init(&f, m);
    Tvd t;
    tvd_init(&t, &f, 1);
    double *phi = flux_of(&f, vel_uniform), *x = mem_alloc(sizeof(double) * (size_t)f.ncells),
           *xb = mem_alloc(sizeof(double) * ((size_t)f.nboundary + 1)), u[3];
    vel_uniform(NULL, u);
    double dt = 0.25 / fvc_courant(&f, phi, NULL, 1, NULL), T = nsteps * dt, sm[3];
    for (int b = 0; b < f.nboundary; b++) xb[b] = step0(m->face_centre + 3 * (f.ninternal + b));
    for (int s = 0; s < 3; s++) {
        for (int c = 0; c < f.ncells; c++) x[c] = step0(f.node + 3 * c);
        double worst = advect(&t, SCHEMES[s], phi, x, xb, nsteps, 0.25, 0, 1), l1 = 0, vol = 0;
        for (int c = 0; c < f.ncells; c++) {
            const double *p = f.node + 3 * c, back[3] = {p[0] - u[0] * T, p[1] - u[1] * T, 0};
            l1 += fabs(x[c] - step0(back)) * m->cell_vol[c], vol += m->cell_vol[c];
        }
        sm[s] = l1 / vol;
        printf("  %s, %d steps at Co 0.25, %-16s: outside [0, 1] by at most %.2e; L1 distance to the exact step %.4f\n",
               what, nsteps, NAMES[s], fmax(worst, 0), sm[s]);
        EXPECT(worst >= 0 && worst <= 1e-14, "%s, %s: out of bounds by %.3e", what, NAMES[s], worst);
    }
    EXPECT(sm[1] < 0.8 * sm[0] && sm[2] < 0.8 * sm[0], "%s: smearing %.4f %.4f against upwind %.4f", what, sm[1], sm[2],
           sm[0]);
    free(phi), free(x), free(xb);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(m);
}

TEST(bounded_step)
{
    Mesh m;
    fixture_square(&m, 64);
    step_on(&m, "block 64^2", 100);
    disc_grid(&m, 64);
    step_on(&m, "disc 64^2", 100);
}

static double src_x0[3];
static void vel_source(const double *x, double *u)
{
    u[0] = x[0] - src_x0[0], u[1] = x[1] - src_x0[1], u[2] = 0;
}
static void vel_sink(const double *x, double *u)
{
    u[0] = 0.5 - x[0] + 0.3, u[1] = 0.5 - x[1] + 0.1, u[2] = 0;
}

static void empty_on(Mesh *m, const char *what)
{
    FvMesh f;
    fv_init(&f, m);
    Tvd t;
    tvd_init(&t, &f, 1);
    double *x = mem_alloc(sizeof(double) * (size_t)f.ncells), *xb = mem_alloc(sizeof(double) * ((size_t)f.nboundary + 1)),
           *out = mem_alloc(sizeof(double) * (size_t)f.ncells);
    /* an interior cell and a boundary cell (a cut cell at the disc on the
       disc grid, the first cell with a boundary face on the block) */
    int pick[2] = {-1, -1};
    for (int c = 0; c < f.ncells; c++) {
        const double *p = f.node + 3 * c;
        if (pick[0] < 0 && fabs(p[0] - 0.15) < 0.02 && fabs(p[1] - 0.15) < 0.02) pick[0] = c;
    }
    for (int i = f.ninternal; i < f.nfaces && pick[1] < 0; i++) {
        const double *p = m->face_centre + 3 * i;
        if (!f.empty_face[i] && hypot(p[0] - 0.5, p[1] - 0.5) < 0.3) pick[1] = m->owner[i];
    }
    for (int i = f.ninternal; i < f.nfaces && pick[1] < 0; i++)
        if (!f.empty_face[i]) pick[1] = m->owner[i];
    for (int b = 0; b < f.nboundary; b++) xb[b] = 2;
    for (int j = 0; j < 2; j++) {
        int c0 = pick[j];
        EXPECT(c0 >= 0, "%s: no cell picked", what);
        if (c0 < 0) break;
        for (int k = 0; k < 3; k++) src_x0[k] = f.node[3 * c0 + k];
        double *phi = flux_of(&f, vel_source);
        for (int c = 0; c < f.ncells; c++) x[c] = 1 + 3 * f.node[3 * c] + 2 * f.node[3 * c + 1];
        x[c0] = 0;
        for (int s = 0; s < 3; s++) {
            tvd_div(&t, SCHEMES[s], phi, x, xb, 1, out);
            EXPECT(out[c0] == 0, "%s, cell %d, %s: an empty cell emits %.3e", what, c0, NAMES[s], out[c0]);
        }
        free(phi);
    }
    /* a converging flow over an empty region: values stay >= 0 */
    double *phi = flux_of(&f, vel_sink), worst = 0;
    for (int s = 1; s < 3; s++) {
        for (int c = 0; c < f.ncells; c++) {
            const double *p = f.node + 3 * c;
            x[c] = hypot(p[0] - 0.75, p[1] - 0.8) < 0.12 ? 0 : 1 + 0.5 * sin(7 * p[0]) * cos(5 * p[1]);
        }
        for (int b = 0; b < f.nboundary; b++) xb[b] = 1;
        double w = advect(&t, SCHEMES[s], phi, x, xb, 200, 0.2, 0, INFINITY);
        worst = w < 0 ? INFINITY : fmax(worst, w);
    }
    printf("  %s: empty source cells emit nothing; 200 steps of a converging flow at Co 0.2: lowest value %.2e below 0\n",
           what, worst);
    EXPECT(worst <= 0, "%s: a value fell below 0 by %.3e", what, worst);
    free(phi), free(x), free(xb), free(out);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(m);
}

TEST(empty_cell)
{
    Mesh m;
    fixture_square(&m, 32);
    empty_on(&m, "block 32^2");
    disc_grid(&m, 32);
    empty_on(&m, "disc 32^2");
}

static void vel_swirl(const double *x, double *u)
{
    u[0] = 0.3 + sin(3 * x[1]) - 0.4 * x[0], u[1] = -0.2 + cos(2 * x[0]) * x[1], u[2] = 0;
}

TEST(conservation)
{
    Mesh m;
    disc_grid(&m, 48);
    FvMesh f;
    fv_init(&f, &m);
    Tvd t;
    tvd_init(&t, &f, 3);
    double *phi = flux_of(&f, vel_swirl), *x = mem_alloc(sizeof(double) * 3 * (size_t)f.ncells),
           *xb = mem_alloc(sizeof(double) * 3 * ((size_t)f.nboundary + 1)),
           *out = mem_alloc(sizeof(double) * 3 * (size_t)f.ncells);
    for (int c = 0; c < f.ncells; c++)
        for (int k = 0; k < 3; k++) x[3 * c + k] = 1 + (k + 1) * sin(4 * f.node[3 * c] + k) * f.node[3 * c + 1];
    for (int b = 0; b < 3 * f.nboundary; b++) xb[b] = 0.5 + 0.01 * b;
    double worst = 0;
    for (int s = 0; s < 3; s++) {
        tvd_div(&t, SCHEMES[s], phi, x, xb, 3, out);
        for (int k = 0; k < 3; k++) {
            double total = 0, bflux = 0;
            for (int c = 0; c < f.ncells; c++) total += out[3 * c + k];
            for (int i = f.ninternal; i < f.nfaces; i++) {
                if (f.empty_face[i]) continue;
                int b = i - f.ninternal;
                bflux += phi[i] * (phi[i] >= 0 ? x[3 * m.owner[i] + k] : xb[3 * b + k]);
            }
            worst = fmax(worst, fabs(total - bflux) / fabs(bflux));
        }
    }
    printf("  disc 48^2, 3 components, 3 schemes: sum of net outflows - boundary flux: %.2e relative\n", worst);
    EXPECT(worst <= 1e-12, "conservation: %.3e", worst);
    free(phi), free(x), free(xb), free(out);
    tvd_free(&t);
    fvmesh_free(&f);
    mesh_free(&m);
}

int main(void)
{
    RUN(parse);
    RUN(gradient);
    RUN(block_order);
    RUN(disc_order);
    RUN(periodic_order);
    RUN(bounded_step);
    RUN(empty_cell);
    RUN(conservation);
    return test_summary();
}
