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
}

void mms_exact(const Study *s, const double x[3], MmsPoint *o)
{
    if (s->dim == 2) mms_exact_2d(&s->p, x, o);
    else mms_exact_3d(&s->p, x, o);
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
    const double *c = s->p.c;
    char geo[256];
    if (s->dim == 2)
        snprintf(geo, sizeof geo,
                 "wall { type wall; flow inside; shape cylinder; point1 (%.17g %.17g -1); point2 (%.17g %.17g 2); "
                 "radius %.17g; }",
                 c[0], c[1], c[0], c[1], s->p.R);
    else
        snprintf(geo, sizeof geo,
                 "wall { type wall; flow inside; shape sphere; centre (%.17g %.17g %.17g); radius %.17g; }", c[0],
                 c[1], c[2], s->p.R);
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

/* The hook (newtonian.h): the steady integrals, computed once. */
static int source_steady(void *ctx, const FvMesh *f, double t, double *rho_src, double *mom_src, Err *e)
{
    const MmsSource *s = ctx;
    (void)f, (void)t, (void)e;
    memcpy(rho_src, s->rho, sizeof(double) * (size_t)s->n);
    memcpy(mom_src, s->m, sizeof(double) * 3 * (size_t)s->n);
    return 0;
}

/* The initial state: rho the exact cell average, so that the discrete
   mass is the exact mass of the grid's domain, which the steady state
   keeps; u the exact node value; and the source integrals. */
static void initial_state(const Study *s, MmsCase *k)
{
    const FvMesh *f = &k->f;
    int n = f->ncells;
    double *q = mem_alloc(sizeof(double) * 5 * (size_t)n);
    quad_cells(f->m, 5, integrand, (void *)s, q);
    k->src.n = n;
    k->src.rho = mem_alloc(sizeof(double) * (size_t)n);
    k->src.m = mem_alloc(sizeof(double) * 3 * (size_t)n);
    for (int c = 0; c < n; c++) {
        MmsPoint o;
        mms_exact(s, f->node + 3 * c, &o);
        k->rho.v[c] = q[5 * c] / f->m->cell_vol[c];
        k->src.rho[c] = q[5 * c + 1];
        for (int j = 0; j < 3; j++) {
            k->U.v[3 * c + j] = o.u[j];
            k->src.m[3 * c + j] = q[5 * c + 2 + j];
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
    "solvers { \"U.*\" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; } }";

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
    field_init(&k->rho, &k->m, "rho", 1, &one, "zeroGradient");
    field_init(&k->U, &k->m, "U", 3, zero, "noSlip");
    initial_state(s, k);
    GranularProps pr = {.model = MODEL_NEWTONIAN, .mu = s->mu, .RsT = s->RsT};
    GranSchemes sch = {.div = {div_scheme(s->div), div_scheme(s->div), div_scheme(s->div)}, .gravity = GRAN_WELL_BALANCED};
    k->sol = dict_parse(FVSOLUTION, strlen(FVSOLUTION), "fvSolution", &e);
    if (!k->sol || gran_init(&k->g, &k->f, &k->ip, &pr, &sch, &k->rho, &k->U, NULL, k->sol, &e)) die("gran_init", &e);
    k->g.src = (GranSource){source_steady, &k->src};
}

void mms_case_free(MmsCase *k)
{
    gran_free(&k->g);
    dict_free(k->sol);
    free(k->src.rho);
    free(k->src.m);
    field_free(&k->rho);
    field_free(&k->U);
    interp_free(&k->ip);
    fvmesh_free(&k->f);
    mesh_free(&k->m);
}

/* Largest change of the state since rho0, u0, per unit time. */
static double change_rate(const Granular *g, const double *rho0, const double *u0, double dt)
{
    double r = 0;
    for (int c = 0; c < g->f->nowned; c++) {
        r = fmax(r, fabs(g->rho->v[c] - rho0[c]));
        for (int j = 0; j < 3; j++) r = fmax(r, fabs(g->U->v[3 * c + j] - u0[3 * c + j]));
    }
    return r / dt;
}

void mms_steady(const Study *s, MmsCase *k, Level *lv)
{
    Granular *g = &k->g;
    size_t nc = (size_t)k->f.ncells;
    double *rho0 = mem_alloc(sizeof(double) * nc), *u0 = mem_alloc(sizeof(double) * 3 * nc), dt = 1e-4;
    lv->rate = INFINITY;
    Err e;
    while (g->time < s->tmax && lv->rate > s->tol) {
        double mean;
        gran_flux(g);
        dt *= s->maxCo / gran_courant(g, dt, &mean); /* the Courant number is linear in dt */
        memcpy(rho0, g->rho->v, sizeof(double) * nc);
        memcpy(u0, g->U->v, sizeof(double) * 3 * nc);
        if (gran_step(g, dt, &e)) die("gran_step", &e);
        lv->rate = change_rate(g, rho0, u0, dt);
        lv->steps++;
    }
    lv->t = g->time;
    free(rho0);
    free(u0);
}

void mms_errors(const Study *s, const MmsCase *k, Level *lv)
{
    const FvMesh *f = &k->f;
    double vol = 0;
    for (int q = 0; q < MMS_NQ; q++) lv->err[q] = 0;
    for (int c = 0; c < f->nowned; c++) {
        MmsPoint o;
        mms_exact(s, f->node + 3 * c, &o);
        const double *u = k->U.v + 3 * c;
        double V = f->m->cell_vol[c], er = fabs(k->rho.v[c] - o.rho);
        double eu = sqrt((u[0] - o.u[0]) * (u[0] - o.u[0]) + (u[1] - o.u[1]) * (u[1] - o.u[1]) +
                         (u[2] - o.u[2]) * (u[2] - o.u[2]));
        vol += V;
        lv->err[0] += V * er;
        lv->err[1] = fmax(lv->err[1], er);
        lv->err[2] += V * eu;
        lv->err[3] = fmax(lv->err[3], eu);
    }
    lv->err[0] /= vol;
    lv->err[2] /= vol;
    lv->cells = f->nowned;
}
