/*
** test_hydro.c: the well-balanced face pressure and gravity (fv/hydro.h).
**
** Exact properties: at the discrete rest state rho_C = exp(a.x_C) every
** face pressure is RsT exp(a.x_f) and the pressure force of every cell
** equals its gravity vector to round-off, on a block grid, the box rotated
** 30 degrees cut and merged (shepard, multilinear), the same as a Voronoi
** grid, a cut sphere in 3-D and a block periodic in x; the old
** discretisation (plain face values, rho g V) is off there by half of
** rho g V or more in the wall cells (so the check can fail).  With g = 0 the weights are the CENTRE rows',
** bit for bit, each boundary row its owner alone and the gravity vectors
** zero.  The partner faces of a cyclic pair share p_f bit for bit, also
** with gravity along the period.  Measured: the gravity vector against
** rho g V (second order on block grids), and the boundary pressures of a
** uniform p (the inclined channel's state: second order with the
** neighbourhood rule, first order with the owner's profile alone).  The
** barotropic rows (hydro_init_profile) given the isothermal profile are
** the isothermal scheme, off a rest state, on every grid above.
*/
#include "fixture.h"
#include "fvc.h"
#include "fvmesh.h"
#include "hydro.h"
#include "interp.h"
#include "test.h"

#include <math.h>

static const double RST = 6;
static const char *const ROTBOX = "box { type wall; flow inside; shape box; min (-0.5 -0.5 -1); max (0.5 0.5 1);\n"
                                  "  rotate { axis (0 0 1); angle 30; } translate (0.75 0.75 0); }";
static const char *const SPHERE = "s { flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }";

/* The block grid [0,L]^3 (2-D: one cell of L/N along z), N per axis. */
static void block(Mesh *m, int N, double L, int flat)
{
    int n[3] = {N, N, flat ? 1 : N};
    double lo[3] = {0, 0, 0}, hi[3] = {L, L, flat ? L / N : L};
    fixture_block(m, n, lo, hi, flat ? 2 : -1);
}

/* The rotated unit box in [0,1.5]^2, 1.5 N cells a side: cut and merged,
   or a Voronoi grid. */
static void rotbox(Mesh *out, int N, int voronoi)
{
    Mesh grid;
    block(&grid, (int)lround(1.5 * N), 1.5, 1);
    if (!voronoi) {
        fixture_cut(out, &grid, ROTBOX, 1, NULL);
        mesh_free(&grid);
        return;
    }
    fixture_voronoi(out, &grid, ROTBOX);
    mesh_free(&grid);
}

/* The 6 x 4 block [0,1.2] x [0,0.8] periodic in x, walls at y = 0, 0.8. */
static void cyclic_block(Mesh *m)
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
    Err e;
    mesh_init(m);
    if (block_mesh(m, x, n, side, NULL, "test", NULL, &e)) {
        printf("block_mesh: %s\n", e.msg);
        exit(1);
    }
    mesh_cell_faces(m);
    mesh_geometry(m);
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* The grid's view, stencils and weights; exits on failure. */
typedef struct Setup {
    FvMesh f;
    Interp ip;
    Hydro h;
} Setup;

static void setup(Setup *s, Mesh *m, int method, const double g[3])
{
    Err e;
    InterpOpts o;
    interp_opts_default(&o);
    o.method = method;
    if (fvmesh_init(&s->f, m, &e) || interp_init(&s->ip, &s->f, &o, "test", &e)) {
        printf("setup: %s\n", e.msg);
        exit(1);
    }
    hydro_init(&s->h, &s->f, &s->ip, g, RST);
}

static void teardown(Setup *s)
{
    hydro_free(&s->h);
    interp_free(&s->ip);
    fvmesh_free(&s->f);
}

/* Face pressures of the cell pressures pc: every boundary face from its
   owner's neighbourhood (walls), then the faces' rows (empty faces 0). */
static double *face_pressures(const Setup *s, const double *pc)
{
    const FvMesh *f = &s->f;
    double *pb = mem_alloc(sizeof(double) * ((size_t)f->nboundary + 1));
    double *pf = mem_alloc(sizeof(double) * ((size_t)f->nfaces + 1));
    for (int b = 0; b < f->nboundary; b++) pb[b] = hydro_boundary(&s->h, b, pc);
    for (int i = 0; i < f->nfaces; i++) pf[i] = f->empty_face[i] ? 0 : hydro_face(&s->h, i, pc, pb);
    free(pb);
    return pf;
}

typedef struct Balance {
    double p;      /* largest |p_f / (RsT exp(a.x_f)) - 1| */
    double F;      /* largest |force - gravity| / |rho g V| over cells and
                      active components */
} Balance;

/* The rest state rho_C = exp(a.x_C) on s: face pressures and the cells'
   imbalance.  old: the plain discretisation instead (s built with g = 0,
   gravity rho g V). */
static Balance rest_balance(const Setup *s, const double g[3], int old)
{
    const FvMesh *f = &s->f;
    const Mesh *m = f->m;
    double a[3] = {g[0] / RST, g[1] / RST, g[2] / RST}, gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double *rho = mem_alloc(sizeof(double) * ((size_t)f->ncells + 1));
    double *pc = mem_alloc(sizeof(double) * ((size_t)f->ncells + 1));
    double *F = mem_alloc(sizeof(double) * 3 * ((size_t)f->ncells + 1));
    for (int c = 0; c < f->ncells; c++) {
        const double *x = f->node + 3 * c;
        rho[c] = exp(a[0] * x[0] + a[1] * x[1] + a[2] * x[2]);
        pc[c] = RST * rho[c];
    }
    double *pf = face_pressures(s, pc);
    Balance B = {0, 0};
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        const double *x = m->face_centre + 3 * i;
        B.p = fmax(B.p, fabs(pf[i] / (RST * exp(a[0] * x[0] + a[1] * x[1] + a[2] * x[2])) - 1));
    }
    fvc_pressure_force(f, pf, F);
    for (int c = 0; c < f->nowned; c++)
        for (int k = 0; k < 3; k++) {
            if (k == f->empty_axis) continue;
            double G = old ? rho[c] * g[k] * m->cell_vol[c] : RST * rho[c] * s->h.grav[3 * c + k];
            B.F = fmax(B.F, fabs(F[3 * c + k] - G) / (rho[c] * gn * m->cell_vol[c]));
        }
    free(pf);
    free(F);
    free(pc);
    free(rho);
    return B;
}

/* The rest state on grid m with method and gravity g: the new scheme to
   round-off, the old one off by more than 1e-4 (printed). */
static void check_rest(const char *name, Mesh *m, int method, const double g[3], double tolF)
{
    static const double none[3] = {0, 0, 0};
    Setup s, s0;
    setup(&s, m, method, g);
    setup(&s0, m, method, none);
    Balance B = rest_balance(&s, g, 0), B0 = rest_balance(&s0, g, 1);
    printf("  %-32s %5d cells: |p_f - p(x_f)|/p %.1e, |F - G|/(rho g V) %.1e (old discretisation %.1e)\n", name,
           s.f.nowned, B.p, B.F, B0.F);
    EXPECT(B.p <= 1e-13, "%s: face pressure off the rest state by %.3e", name, B.p);
    EXPECT(B.F <= tolF, "%s: pressure force and gravity differ by %.3e of rho g V", name, B.F);
    EXPECT(B0.F > 1e-4, "%s: the old discretisation balances to %.3e: the check cannot fail", name, B0.F);
    teardown(&s0);
    teardown(&s);
}

static const double G_TILT[3] = {2.5, -9.81, 0};

TEST(rest_state_block)
{
    Mesh m;
    block(&m, 16, 1, 1);
    check_rest("block 16 x 16", &m, INTERP_SHEPARD, G_TILT, 1e-12);
    mesh_free(&m);
}

TEST(rest_state_cut)
{
    Mesh m;
    rotbox(&m, 16, 0);
    check_rest("rotated box cut, shepard", &m, INTERP_SHEPARD, G_TILT, 1e-12);
    check_rest("rotated box cut, multilinear", &m, INTERP_MULTILINEAR, G_TILT, 1e-12);
    mesh_free(&m);
}

TEST(rest_state_voronoi)
{
    Mesh m;
    rotbox(&m, 16, 1);
    check_rest("rotated box Voronoi, shepard", &m, INTERP_SHEPARD, G_TILT, 1e-12);
    mesh_free(&m);
}

TEST(rest_state_3d)
{
    Mesh grid, m;
    block(&grid, 8, 1, 0);
    fixture_cut(&m, &grid, SPHERE, 1, NULL);
    static const double g[3] = {1.5, -9.81, 3.0};
    check_rest("3-D sphere cut, shepard", &m, INTERP_SHEPARD, g, 1e-12);
    check_rest("3-D sphere cut, multilinear", &m, INTERP_MULTILINEAR, g, 1e-12);
    mesh_free(&m);
    mesh_free(&grid);
}

/* Gravity across the period: a rest state; the partner faces share p_f
   bit for bit, also with gravity along the period (no rest state). */
TEST(rest_state_cyclic)
{
    Mesh m;
    cyclic_block(&m);
    static const double g[3] = {0, -9.81, 0}, along[3] = {4, -9.81, 0};
    check_rest("block periodic in x, shepard", &m, INTERP_SHEPARD, g, 1e-12);
    Setup s;
    setup(&s, &m, INTERP_SHEPARD, along);
    const FvMesh *f = &s.f;
    double *pc = mem_alloc(sizeof(double) * (size_t)f->ncells);
    for (int c = 0; c < f->ncells; c++) pc[c] = 1 + 0.1 * c + 0.3 * sin(c);
    double *pf = face_pressures(&s, pc);
    int ncyc = 0, bad = 0;
    for (int b = 0; b < f->nboundary; b++) {
        int pt = f->cyc_face[b];
        if (pt < 0) continue;
        ncyc++;
        bad += pf[f->ninternal + b] != pf[pt];
    }
    EXPECT(ncyc == 8 && bad == 0, "%d of %d cyclic faces differ from their partners", bad, ncyc);
    free(pf);
    free(pc);
    teardown(&s);
    mesh_free(&m);
}

/* g = 0: nothing stored (no weights, no wall rows, no gravity vectors);
   the face pressure is the CENTRE row's value and a wall's the owner's,
   bit for bit (as the stored weights, all exp(0) = 1 times the rows',
   gave them). */
TEST(zero_gravity)
{
    Mesh m;
    rotbox(&m, 8, 0);
    static const double none[3] = {0, 0, 0};
    Setup s;
    setup(&s, &m, INTERP_SHEPARD, none);
    const FvMesh *f = &s.f;
    double *pc = mem_alloc(sizeof(double) * (size_t)f->ncells), *pb = mem_alloc(sizeof(double) * (size_t)f->nboundary);
    for (int c = 0; c < f->ncells; c++) pc[c] = 1 + 0.1 * c + 0.3 * sin(c);
    for (int b = 0; b < f->nboundary; b++) pb[b] = 2 + cos(b);
    int bad = s.h.w != NULL || s.h.off != NULL || s.h.grav != NULL || s.h.wall.off != NULL;
    for (int i = 0; i < f->nfaces; i++) {
        double a = hydro_face(&s.h, i, pc, pb), b = stencil_apply(&s.ip.face, interp_row(i, INTERP_CENTRE), f->ncells, pc, pb);
        bad += memcmp(&a, &b, sizeof a) != 0;
    }
    for (int b = 0; b < f->nboundary; b++) {
        double a = hydro_boundary(&s.h, b, pc);
        bad += memcmp(&a, &pc[m.owner[f->ninternal + b]], sizeof a) != 0;
    }
    EXPECT(bad == 0, "%d face or wall pressures differ from g = 0's", bad);
    free(pc);
    free(pb);
    teardown(&s);
    mesh_free(&m);
}

/* Largest |RsT grav_C - g V_C| / (|g| V_C) over the owned cells. */
static double gravity_error(Mesh *m, const double g[3])
{
    Setup s;
    setup(&s, m, INTERP_SHEPARD, g);
    double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), worst = 0;
    for (int c = 0; c < s.f.nowned; c++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            if (k == s.f.empty_axis) continue;
            double d = RST * s.h.grav[3 * c + k] - g[k] * m->cell_vol[c];
            d2 += d * d;
        }
        worst = fmax(worst, sqrt(d2) / (gn * m->cell_vol[c]));
    }
    teardown(&s);
    return worst;
}

TEST(gravity_second_order)
{
    double e[3];
    int ns[3] = {8, 16, 32};
    for (int t = 0; t < 3; t++) {
        Mesh m;
        block(&m, ns[t], 1, 1);
        e[t] = gravity_error(&m, G_TILT);
        mesh_free(&m);
    }
    Mesh cut;
    rotbox(&cut, 16, 0);
    double ec = gravity_error(&cut, G_TILT);
    mesh_free(&cut);
    double o1 = log2(e[0] / e[1]), o2 = log2(e[1] / e[2]);
    printf("  RsT grav_C against rho g V_C: block N = 8, 16, 32: %.2e %.2e %.2e (orders %.2f %.2f); rotated box cut "
           "N = 16: %.2e\n", e[0], e[1], e[2], o1, o2, ec);
    EXPECT(o1 > 1.9 && o2 > 1.9, "orders %.2f %.2f, expected 2", o1, o2);
    EXPECT(ec < 1e-2, "cut cells' gravity off by %.3e", ec);
}

/* Uniform p with gravity along the walls' plane (the inclined channel's
   state): the boundary pressures from the owners' neighbourhoods are
   within O((a h)^2) of p; the owner's profile alone is off by O(a h).
   Largest |p_b/p - 1| over the non-empty boundary faces into *plain for
   the owner's profile. */
static double uniform_walls(Mesh *m, const double g[3], double *plain)
{
    Setup s;
    setup(&s, m, INTERP_MULTILINEAR, g);
    const FvMesh *f = &s.f;
    double a[3] = {g[0] / RST, g[1] / RST, g[2] / RST}, worst = 0;
    double *pc = mem_alloc(sizeof(double) * ((size_t)f->ncells + 1));
    for (int c = 0; c < f->ncells; c++) pc[c] = 1;
    *plain = 0;
    for (int b = 0; b < f->nboundary; b++) {
        int i = f->ninternal + b;
        if (f->empty_face[i]) continue;
        const double *xb = m->face_centre + 3 * i, *xp = f->node + 3 * m->owner[i];
        worst = fmax(worst, fabs(hydro_boundary(&s.h, b, pc) - 1));
        *plain = fmax(*plain, fabs(expm1(a[0] * (xb[0] - xp[0]) + a[1] * (xb[1] - xp[1]) + a[2] * (xb[2] - xp[2]))));
    }
    free(pc);
    teardown(&s);
    return worst;
}

TEST(uniform_pressure_at_walls)
{
    /* along the rotated box's walls at 30 degrees */
    const double g[3] = {9.81 * sqrt(3) / 2, 9.81 / 2, 0};
    double e[2], p[2];
    for (int t = 0; t < 2; t++) {
        Mesh m;
        rotbox(&m, 16 << t, 0);
        e[t] = uniform_walls(&m, g, &p[t]);
        mesh_free(&m);
    }
    printf("  uniform p, g along the walls: |p_b/p - 1| N = 16, 32: %.2e %.2e (order %.2f); the owner's profile "
           "alone %.2e %.2e (order %.2f)\n", e[0], e[1], log2(e[0] / e[1]), p[0], p[1], log2(p[0] / p[1]));
    EXPECT(log2(e[0] / e[1]) > 1.7, "order %.2f, expected 2", log2(e[0] / e[1]));
    EXPECT(e[1] < 0.2 * p[1], "neighbourhood %.3e against the owner's profile %.3e", e[1], p[1]);
}

/* The isothermal profile as a barotropic one: q_s(phi) = p_s exp(phi/RsT). */
typedef struct IsoCtx {
    int nc;
    const double *pc, *pb;
} IsoCtx;

static double iso_at(const void *ctx, int s, double phi)
{
    const IsoCtx *c = ctx;
    double p = s < c->nc ? c->pc[s] : c->pb[s - c->nc];
    return phi == 0 ? p : p * exp(phi / RST);
}

/* hydro_init_profile with the isothermal profile gives the isothermal
   scheme's boundary and face pressures, force and gravity (relative to
   the largest, 1e-13) on a state that is not at rest. */
static void check_barotropic(const char *name, Mesh *m, int method, const double g[3])
{
    Setup s, t;
    setup(&s, m, method, g);
    setup(&t, m, method, g);
    hydro_free(&t.h);
    hydro_init_profile(&t.h, &t.f, &t.ip, g);
    const FvMesh *f = &s.f;
    int nc = f->ncells, nb = f->nboundary;
    double *pc = mem_alloc(sizeof(double) * (size_t)(nc + 1)), *pb = mem_alloc(sizeof(double) * (size_t)(nb + 1));
    double *pb2 = mem_alloc(sizeof(double) * (size_t)(nb + 1));
    double *F1 = mem_alloc(sizeof(double) * 3 * (size_t)(nc + 1)), *F2 = mem_alloc(sizeof(double) * 3 * (size_t)(nc + 1));
    double *G2 = mem_alloc(sizeof(double) * 3 * (size_t)(nc + 1));
    for (int c = 0; c < nc; c++) {
        const double *x = f->node + 3 * c;
        pc[c] = RST * (1 + 0.3 * sin(5 * x[0] + 3 * x[1] + 2 * x[2]));
    }
    for (int b = 0; b < nb; b++) pb[b] = hydro_boundary(&s.h, b, pc);
    IsoCtx ctx = {nc, pc, pb2};
    HydroProfile q = {iso_at, &ctx};
    for (int b = 0; b < nb; b++) pb2[b] = hydro_boundary_profile(&t.h, b, &q);
    double pmax = 0, dp = 0, db = 0, df = 0, dg = 0, fmax_ = 0;
    for (int b = 0; b < nb; b++) db = fmax(db, fabs(pb2[b] - pb[b]));
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        double a = hydro_face(&s.h, i, pc, pb), b = hydro_face_profile(&t.h, i, &q);
        pmax = fmax(pmax, fabs(a));
        dp = fmax(dp, fabs(a - b));
    }
    hydro_force(&s.h, pc, pb, F1);
    hydro_force_profile(&t.h, &q, F2);
    hydro_gravity_profile(&t.h, &q, G2);
    for (int c = 0; c < nc; c++)
        for (int k = 0; k < 3; k++) {
            double G1 = pc[c] * s.h.grav[3 * c + k]; /* RsT rho_C grav_C */
            fmax_ = fmax(fmax_, fmax(fabs(F1[3 * c + k]), fabs(G1)));
            df = fmax(df, fabs(F1[3 * c + k] - F2[3 * c + k]));
            dg = fmax(dg, fabs(G1 - G2[3 * c + k]));
        }
    EXPECT(db <= 1e-13 * pmax && dp <= 1e-13 * pmax, "%s: boundary %.2e, faces %.2e of %.3g", name, db, dp, pmax);
    EXPECT(df <= 1e-13 * fmax_ && dg <= 1e-13 * fmax_, "%s: force %.2e, gravity %.2e of %.3g", name, df, dg, fmax_);
    printf("  barotropic %s: boundary %.1e, faces %.1e (of %.2g), force %.1e, gravity %.1e (of %.2g)\n", name, db, dp,
           pmax, df, dg, fmax_);
    void *arr[] = {pc, pb, pb2, F1, F2, G2};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) free(arr[i]);
    teardown(&s);
    teardown(&t);
}

TEST(barotropic_isothermal)
{
    Mesh m, grid;
    rotbox(&m, 16, 0);
    check_barotropic("rotated box cut, shepard", &m, INTERP_SHEPARD, G_TILT);
    check_barotropic("rotated box cut, multilinear", &m, INTERP_MULTILINEAR, G_TILT);
    mesh_free(&m);
    rotbox(&m, 16, 1);
    check_barotropic("rotated box Voronoi", &m, INTERP_SHEPARD, G_TILT);
    mesh_free(&m);
    block(&grid, 8, 1, 0);
    fixture_cut(&m, &grid, SPHERE, 1, NULL);
    static const double g3[3] = {1.5, -9.81, 3.0}, along[3] = {4, -9.81, 0};
    check_barotropic("3-D sphere cut, multilinear", &m, INTERP_MULTILINEAR, g3);
    mesh_free(&m);
    mesh_free(&grid);
    cyclic_block(&m);
    check_barotropic("block periodic in x, gravity along the period", &m, INTERP_SHEPARD, along);
    mesh_free(&m);
}

int main(void)
{
    RUN(rest_state_block);
    RUN(rest_state_cut);
    RUN(rest_state_voronoi);
    RUN(rest_state_3d);
    RUN(rest_state_cyclic);
    RUN(zero_gravity);
    RUN(gravity_second_order);
    RUN(uniform_pressure_at_walls);
    RUN(barotropic_isothermal);
    return test_summary();
}
