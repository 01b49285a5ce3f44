/*
** mms_case.c: one grid level of the manufactured-solution study
** (mms.h): the grid built with the library as blockGrid, cutCells +
** mergeCells or voronoiGrid would, the fields at the exact state, the
** model with the source hook, the run to the steady state, the errors.
*/
#include "fixture.h"
#include "mms.h"
#include "quad.h"
#include "vgrid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mms_study_default(Study *s)
{
    memset(s, 0, sizeof *s);
    s->kind = "disc-cut";
    s->interp = "shepard";
    s->div = "upwind";
    s->dim = 2;
    s->layers = 2;
    s->mu = 0.1;
    s->RsT = 6;
    s->tol = 1e-7;
    s->tmax = 20;
    s->maxCo = 0.5;
    s->max_skewness = 4;
    for (int q = 0; q < MMS_NQ; q++) s->expect[q] = -1;
    /* the centre off the grid's symmetry lines, so that cut cells of all
       shapes occur; rho in [0.90, 1.13], |u| <= 0.56 (Mach 0.23) */
    MmsParams p = {{0.511, 0.493, 0.507}, 0.4, 0.15, 0.1, 0.125, 0.5};
    s->p = p;
    /* model granular (doc/validation.md, "Granular manufactured
       solutions"): c in [0.41, 0.51] above c0 = 0.3 (the yield terms act
       everywhere: p_y/p_k about 0.4 to 1.3), T in [0.16, 0.34], |u| <= 0.4
       (Mach 0.23); the heating K_T eta kappa:kappa (up to 2.5) is up to
       0.6 of the dissipation eps c T, so that s_T > 0 (1.1 to 7.6): a
       state whose heating is balanced by a fixed sink s_T < 0 is not
       stable (a cell that cools loses its heating: with eps0 = 1 and
       A = 0.06, heating/dissipation up to 28, the ball drifts to a cold
       wall cell and never settles) */
    GranCoeffs k = {.eta0 = 0.1, .lambda0 = 0.1, .eps0 = 20, .cmax = 0.8, .c0 = 0.3, .T0 = 0.5, .KT = 2.0 / 3};
    s->k = k;
    MmsGranParams pg = {{0.511, 0.493, 0.507}, 0.4, 0.45, 0.06, 0.05, 0.2, 0.06, 0.1, 0.04, 0.5};
    s->pg = pg;
}

void mms_exact(const Study *s, const double x[3], MmsPoint *o)
{
    if (s->dim == 2) mms_exact_2d(&s->p, x, o);
    else mms_exact_3d(&s->p, x, o);
}

void mms_gran_exact(const Study *s, const double x[3], MmsGranPoint *o)
{
    if (s->dim == 2) mms_gran_exact_2d(&s->pg, &s->k, x, o);
    else mms_gran_exact_3d(&s->pg, &s->k, x, o);
}

static void die(const char *what, const Err *e)
{
    printf("FAIL mms: %s: %s\n", what, e->msg);
    exit(1);
}

/* grid cut by the geometry of text and merged with M_V = 1/2 and the
   study's maxSkewness into m. */
static void cut_merge(const Study *s, const Mesh *grid, const char *text, Mesh *m)
{
    FixtureGeo G;
    Mesh cutm;
    CutStats cs;
    MergeOpts mo;
    MergeStats ms;
    Err e;
    if (fixture_geo(&G, text)) exit(1);
    if (cut_mesh(grid, &G.g, NULL, &cutm, &cs, &e)) die("cut_mesh", &e);
    merge_opts_default(&mo);
    mo.max_skewness = s->max_skewness;
    if (merge_mesh(&cutm, &mo, m, &ms, &e)) die("merge_mesh", &e);
    merge_stats_free(&ms);
    mesh_free(&cutm);
    fixture_geo_free(&G);
}

/* The grid of level N into m (cell faces and geometry filled). */
static void build_grid(const Study *s, int N, Mesh *m)
{
    Mesh grid;
    int n[3] = {N, N, s->dim == 3 ? N : 1};
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, s->dim == 3 ? 1 : 1.0 / N};
    fixture_block(&grid, n, lo, hi, s->dim == 3 ? -1 : 2);
    const double *c = s->granular ? s->pg.c : s->p.c, R = s->granular ? s->pg.R : s->p.R;
    char geo[256];
    if (s->dim == 2)
        snprintf(geo, sizeof geo,
                 "wall { type wall; flow inside; shape cylinder; point1 (%.17g %.17g -1); point2 (%.17g %.17g 2); "
                 "radius %.17g; }",
                 c[0], c[1], c[0], c[1], R);
    else
        snprintf(geo, sizeof geo,
                 "wall { type wall; flow inside; shape sphere; centre (%.17g %.17g %.17g); radius %.17g; }", c[0],
                 c[1], c[2], R);
    if (s->voronoi) {
        FixtureGeo G;
        SeedOpts o;
        VGridStats st;
        Err e;
        if (fixture_geo(&G, geo)) exit(1);
        seeds_opts_default(&o);
        o.layers = s->layers;
        if (vgrid_mesh(&grid, &G.g, &o, m, &st, &e)) die("vgrid_mesh", &e);
        fixture_geo_free(&G);
    } else {
        cut_merge(s, &grid, geo, m);
    }
    mesh_free(&grid);
    mesh_cell_faces(m);
    mesh_geometry(m);
}

/* quad_cells' integrand: rho, s_rho and s_m (mms_exact.h). */
static void integrand(void *ctx, const double x[3], double *val)
{
    const Study *s = ctx;
    MmsPoint o;
    mms_exact(s, x, &o);
    val[0] = o.rho;
    val[1] = o.src_rho;
    for (int k = 0; k < 3; k++) val[2 + k] = o.conv[k] - s->mu * o.lapu[k] + s->RsT * o.grad_rho[k];
}

/* quad_cells' integrand of model granular: c, s_c, s_m, s_T
   (mms_exact_gran.h). */
static void integrand_gran(void *ctx, const double x[3], double *val)
{
    MmsGranPoint o;
    mms_gran_exact(ctx, x, &o);
    val[0] = o.c;
    val[1] = o.src_c;
    for (int k = 0; k < 3; k++) val[2 + k] = o.src_m[k];
    val[5] = o.src_T;
}

/* The hook (newtonian.h): the steady integrals, computed once. */
static int source_steady(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, double *T_src,
                         Err *e)
{
    const MmsSource *s = ctx;
    (void)f, (void)t, (void)e;
    memcpy(rho_src, s->rho, sizeof(double) * (size_t)s->n);
    memcpy(mom_src, s->m, sizeof(double) * 3 * (size_t)s->n);
    if (T_src) memcpy(T_src, s->T, sizeof(double) * (size_t)s->n);
    return 0;
}

/* The initial state: rho the exact cell average, so that the discrete
   mass is the exact mass of the grid's domain, which the steady state
   keeps; u the exact node value; and the source integrals. */
static void initial_state(const Study *s, MmsCase *k)
{
    const FvMesh *f = &k->f;
    int n = f->ncells, nq = s->granular ? 6 : 5;
    double *q = mem_alloc(sizeof(double) * (size_t)nq * (size_t)n);
    quad_cells(f->m, nq, s->granular ? integrand_gran : integrand, (void *)s, q);
    k->src.n = n;
    k->src.rho = mem_alloc(sizeof(double) * (size_t)n);
    k->src.m = mem_alloc(sizeof(double) * 3 * (size_t)n);
    if (s->granular) k->src.T = mem_alloc(sizeof(double) * (size_t)n);
    for (int c = 0; c < n; c++) {
        const double *x = f->node + 3 * c, *qc = q + (size_t)nq * (size_t)c;
        MmsPoint o;
        MmsGranPoint og;
        const double *u = o.u;
        if (s->granular) {
            mms_gran_exact(s, x, &og);
            u = og.u;
            k->T.v[c] = og.T;
            k->src.T[c] = qc[5];
        } else {
            mms_exact(s, x, &o);
        }
        k->rho.v[c] = qc[0] / f->m->cell_vol[c];
        k->src.rho[c] = qc[1];
        for (int j = 0; j < 3; j++) {
            k->U.v[3 * c + j] = u[j];
            k->src.m[3 * c + j] = qc[2 + j];
        }
    }
    free(q);
}

static TvdScheme div_scheme(const char *name)
{
    TvdScheme d = {TVD_UPWIND, 1};
    if (!strcmp(name, "limitedLinear")) d.kind = TVD_LIMITED_LINEAR;
    else if (!strcmp(name, "vanLeer")) d.kind = TVD_VAN_LEER;
    return d;
}

static const char FVSOLUTION[] =
    "solvers { \"U.*|Theta\" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; } }";

/* Model granular's properties: the study's closures, no gravity, the
   solver's default limits (none acts: c and T stay far from them). */
static GranularProps gran_props(const Study *s)
{
    GranularProps pr = {.model = MODEL_GRANULAR, .k = s->k, .dc = 1e-6, .Tmin = 1e-12, .cmin = 1e-8};
    return pr;
}

void mms_case_init(MmsCase *k, const Study *s, int N)
{
    Err e;
    InterpOpts io;
    memset(k, 0, sizeof *k);
    build_grid(s, N, &k->m);
    if (fvmesh_init(&k->f, &k->m, &e)) die("fvmesh_init", &e);
    interp_opts_default(&io);
    io.method = strcmp(s->interp, "multilinear") ? INTERP_SHEPARD : INTERP_MULTILINEAR;
    if (interp_init(&k->ip, &k->f, &io, s->kind, &e)) die("interp_init", &e);
    double one = 1, zero[3] = {0, 0, 0};
    field_init(&k->rho, &k->m, s->granular ? "alpha" : "rho", 1, &one, "zeroGradient");
    field_init(&k->U, &k->m, "U", 3, zero, "noSlip");
    if (s->granular) field_init(&k->T, &k->m, "Theta", 1, &one, "zeroGradient");
    initial_state(s, k);
    GranularProps pr = {.model = MODEL_NEWTONIAN, .mu = s->mu, .RsT = s->RsT};
    if (s->granular) pr = gran_props(s);
    GranSchemes sch = {.div = {div_scheme(s->div), div_scheme(s->div), div_scheme(s->div)}, .gravity = GRAN_WELL_BALANCED,
                       .jacobian = s->jacobian};
    k->sol = dict_parse(FVSOLUTION, strlen(FVSOLUTION), "fvSolution", &e);
    if (!k->sol || gran_init(&k->g, &k->f, &k->ip, &pr, &sch, &k->rho, &k->U, s->granular ? &k->T : NULL, k->sol, &e))
        die("gran_init", &e);
    gran_alloc(&k->g);
    k->g.src = (GranSource){source_steady, &k->src};
}

void mms_case_free(MmsCase *k)
{
    gran_free(&k->g);
    dict_free(k->sol);
    free(k->src.rho);
    free(k->src.m);
    free(k->src.T);
    field_free(&k->rho);
    field_free(&k->U);
    if (k->T.v) field_free(&k->T);
    interp_free(&k->ip);
    fvmesh_free(&k->f);
    mesh_free(&k->m);
}

/* Largest change of the state since rho0, u0 (and T0, model granular),
   per unit time. */
static double change_rate(const Granular *g, const double *rho0, const double *u0, const double *T0, double dt)
{
    double r = 0;
    for (int c = 0; c < g->f->nowned; c++) {
        r = fmax(r, fabs(g->rho->v[c] - rho0[c]));
        for (int j = 0; j < 3; j++) r = fmax(r, fabs(g->U->v[3 * c + j] - u0[3 * c + j]));
        if (T0) r = fmax(r, fabs(g->gm.T->v[c] - T0[c]));
    }
    return r / dt;
}

void mms_steady(const Study *s, MmsCase *k, Level *lv)
{
    Granular *g = &k->g;
    size_t nc = (size_t)k->f.ncells;
    double *rho0 = mem_alloc(sizeof(double) * nc), *u0 = mem_alloc(sizeof(double) * 3 * nc), dt = 1e-4;
    double *T0 = s->granular ? mem_alloc(sizeof(double) * nc) : NULL;
    lv->rate = INFINITY;
    Err e;
    while (g->time < s->tmax && lv->rate > s->tol) {
        double mean;
        gran_flux(g);
        dt *= s->maxCo / gran_courant(g, dt, &mean); /* the Courant number is linear in dt */
        memcpy(rho0, g->rho->v, sizeof(double) * nc);
        memcpy(u0, g->U->v, sizeof(double) * 3 * nc);
        if (T0) memcpy(T0, g->gm.T->v, sizeof(double) * nc);
        if (gran_step(g, dt, &e)) die("gran_step", &e);
        lv->rate = change_rate(g, rho0, u0, T0, dt);
        lv->steps++;
    }
    lv->t = g->time;
    free(rho0);
    free(u0);
    free(T0);
}

void mms_errors(const Study *s, const MmsCase *k, Level *lv)
{
    const FvMesh *f = &k->f;
    double vol = 0;
    for (int q = 0; q < MMS_NQ; q++) lv->err[q] = 0;
    for (int c = 0; c < f->nowned; c++) {
        const double *x = f->node + 3 * c, *u = k->U.v + 3 * c, *ue;
        double V = f->m->cell_vol[c], e[3];
        MmsPoint o;
        MmsGranPoint og;
        if (s->granular) {
            mms_gran_exact(s, x, &og);
            e[0] = fabs(k->rho.v[c] - og.c), e[2] = fabs(k->T.v[c] - og.T), ue = og.u;
        } else {
            mms_exact(s, x, &o);
            e[0] = fabs(k->rho.v[c] - o.rho), e[2] = 0, ue = o.u;
        }
        e[1] = sqrt((u[0] - ue[0]) * (u[0] - ue[0]) + (u[1] - ue[1]) * (u[1] - ue[1]) + (u[2] - ue[2]) * (u[2] - ue[2]));
        vol += V;
        for (int q = 0; q < 3; q++) {
            lv->err[2 * q] += V * e[q];
            lv->err[2 * q + 1] = fmax(lv->err[2 * q + 1], e[q]);
        }
    }
    for (int q = 0; q < 3; q++) lv->err[2 * q] /= vol;
    lv->cells = f->nowned;
}
