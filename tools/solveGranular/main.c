/*
** solveGranular: continuum granular flow on cut-cell and Voronoi grids
** (ICCM, thesis ch. 4), by the semi-implicit Euler of eq. 4.66.  Model
** Newtonian: the compressible Navier-Stokes equations of eq. 5.1
** (newtonian.h; fields rho, U).  Model granular: volume fraction,
** momentum and granular temperature, eq. 2.37-2.47 (granular.h; fields
** alpha, U, Theta).  See doc/tools/solveGranular.md.
**
** Reads like OpenFOAM's scalarTransportFoam: the case, the properties,
** the schemes and solvers, the grid, the fields at the start time, then
** the time loop: Courant number, time step, one step of the model, the
** log, the writes.  Everything that can be wrong in the input is found
** before the first step; a step that fails (a solve, a NaN, a density
** <= 0) writes the last good state and stops with status 1; SIGINT or
** SIGTERM writes the current state and stops with status 0.
*/
#include "args.h"
#include "case.h"
#include "fvtime.h"
#include "newtonian.h"
#include "state.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const ArgDict dicts[] = {
    {"system/controlDict", runtime_control_keys, "adjustTimeStep and maxCo: the speed is |u.n| + sqrt(RsT) (explicit pressure); set maxCo 0.25"},
    {"constant/granularProperties", props_keys, "constant/g (optional, no file: no gravity): dimensions [0 1 -2 0 0 0 0]; value (gx gy gz);"},
    {"constant/granularProperties: NewtonianCoeffs", props_newtonian_keys, NULL},
    {"constant/granularProperties: granularCoeffs", props_granular_keys,
     "fields: alpha (volume fraction c), U, Theta (granular temperature T [m^2/s^2]); p is written"},
    {"system/fvSchemes: divSchemes", gran_div_keys, NULL},
    {"system/fvSchemes: gravitySchemes", gran_gravity_keys, NULL},
    {"system/fvSchemes: heatingSchemes", gran_heating_keys, NULL},
    {"system/fvSchemes: interpolationSchemes", interp_keys, NULL},
    {"system/fvSchemes: interpolationSchemes.shepardCoeffs", interp_shepard_keys, NULL},
    {"system/fvSolution: solvers.Ux, Uy, Uz (model granular: and Theta)", linsolve_keys, NULL},
    {0}};

static const ArgOpt opts[] = {
    {"-profile", NULL, "at the end, print where the steps' time went (flux, explicit terms, assembly, linear solves)"},
    {0}};

static const ToolInfo tool = {"solveGranular",
                              "continuum granular flow (ICCM, eq. 4.66): model Newtonian (eq. 5.1) | granular "
                              "(eq. 2.37-2.47, dense to dilute)",
                              opts, dicts, 0};

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig) { stop_signal = sig; }

static void catch_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

static Dict *read_system(const Case *c, const char *rel)
{
    Err e;
    char *path = case_path(c, rel);
    Dict *d = dict_read(path, &e);
    free(path);
    if (!d) err_die(&e);
    return d;
}

static void print_warnings(const Field *f)
{
    for (int i = 0; i < f->nwarn; i++) err_warn("%s", f->warn[i]);
}

/* The run's state and what writing it needs. */
typedef struct Run {
    Case cs;
    Mesh m;
    Field rho, U, T, p;   /* rho is alpha in model granular; T (Theta) only there */
    Granular g;
    TimeLoop tl;
    double written;    /* the last time on disk */
} Run;

/* The VTK line of state_write or state_write_vtk (a block of its own in
   the log), or the error. */
static void report_vtk(int rc, Buf *log, Err *e)
{
    if (rc) err_die(e);
    if (log->n) printf("%s\n", log->p);
    buf_free(log);
}

static void write_time(Run *r, double t)
{
    Err e;
    char name[64];
    Buf log;
    buf_init(&log);
    int gr = r->g.model == MODEL_GRANULAR;
    Field *f[4] = {&r->rho, &r->U, gr ? &r->T : &r->p, &r->p};
    gran_pressure(&r->g, &r->p);
    gran_release(&r->g);
    report_vtk(state_write(&r->cs, &r->m, f, gr ? 4 : 3, t, r->tl.index, r->tl.dt, r->tl.dt0, name, &log, &e), &log,
               &e);
    r->written = t;
}

static void log_solve(const LinSettings *s, const LinStats *st)
{
    printf("%s%s:  Solving for %s, Initial residual = %g, Final residual = %g, No Iterations %d\n",
           strcmp(s->precon, "none") ? s->precon : "", s->solver, s->name, st->initial, st->final, st->iters);
}

/* Model granular: the Theta solve and the limits that acted (granular.h). */
static void log_granular(const Granular *g)
{
    const GranModel *m = &g->gm;
    if (m->solved) log_solve(&m->set, &m->st);
    int nf, nslide = bc_slip_count(&g->bc_U, &nf);
    if (nf) printf("partialSlip: %d of %d wall faces slide (Coulomb, eq. 2.35)\n", nslide, nf);
    const GranLimits *l = &m->last, *t = &m->total;
    if (l->cmax || l->tmin || l->cmin || t->cmax || t->tmin || t->cmin)
        printf("Limits: c <= cMax - deltaC %ld (%ld in all), T >= Tmin %ld (%ld), c floored to cMin %ld (%ld)\n",
               l->cmax, t->cmax, l->tmin, t->tmin, l->cmin, t->cmin);
}

static void log_step(const Args *a, Run *r, double mass0)
{
    for (int j = 0; j < r->g.naxes; j++) log_solve(&r->g.set[j], &r->g.st[j]);
    if (r->g.model == MODEL_GRANULAR) log_granular(&r->g);
    double mass = gran_mass(&r->g);
    printf("Total mass = %.15g, change since start = %.3e (relative)\n", mass, (mass - mass0) / mass0);
    const char *sep = "Mass flow out:";
    for (int q = 0; q < r->m.npatches; q++)
        if (gran_open_patch(&r->g, q)) {
            printf("%s %s %.9g", sep, r->m.patches[q].name, r->g.patch_out[q]);
            sep = ",";
        }
    if (strcmp(sep, "Mass flow out:")) printf("; mass out since start = %.15g\n", r->g.out_total);
    log_exec(a);
    const Control *c = r->tl.c;
    double done = r->tl.value - r->tl.start, wall = args_wall(a);
    if (done > 0) printf("Estimated time to finish = %.3g s\n", wall / done * fmax(0, c->endTime - r->tl.value));
    printf("\n");
}

/* -profile: the time of the steps by part, and the cell-steps per second. */
static void print_profile(const Run *r, long steps)
{
    const Granular *g = &r->g;
    const char *name[5] = {"face fluxes and Courant number", "explicit terms (rho, convection, pressure)",
                           "assembly of the implicit systems", "linear solves", "checks and copies"};
    double t[5] = {g->t_flux, g->t_explicit, g->t_assembly, g->t_solve, g->t_update}, sum = 0;
    for (int i = 0; i < 5; i++) sum += t[i];
    printf("Step profile: %ld steps, %d cells, %.6g s in the steps\n", steps, r->g.f->nowned, sum);
    for (int i = 0; i < 5; i++)
        printf("  %-44s %10.4f s  %5.1f %%\n", name[i], t[i], sum > 0 ? 100 * t[i] / sum : 0);
    if (sum > 0) printf("  cell-steps per second %.4g\n", (double)steps * r->g.f->nowned / sum);
    printf("\n");
}

/* Model granular's coefficients, K_T among them, at the top of every log. */
static void print_model(const GranularProps *pr)
{
    const GranCoeffs *k = &pr->k;
    printf("Model granular: eta0 %g, lambda0 %g, epsilon0 %g, cMax %g, c0 %g, T0 %g\n", k->eta0, k->lambda0, k->eps0,
           k->cmax, k->c0, k->T0);
    printf("  K_T = %.6g (factor on viscous heating and conduction; 2/3 kinetic theory, 1.5 the thesis's displayed "
           "equations)%s\n",
           k->KT, pr->freezeT ? "; T frozen (freezeT yes)" : "");
    printf("  limits: c <= %g, T >= %g, c floored to %g in the matrices\n\n", k->cmax - pr->dc, pr->Tmin, pr->cmin);
}

static void read_case(Run *r, const Args *a, Interp *ip, FvMesh *fm, Start *st)
{
    Err e;
    if (case_open(&r->cs, a->case_dir, CASE_CONTROL_TIME, &e)) err_die(&e);
    GranularProps pr;
    if (props_read(&pr, r->cs.dir, &e)) err_die(&e);
    Dict *schemes = read_system(&r->cs, "system/fvSchemes"), *sol = read_system(&r->cs, "system/fvSolution");
    InterpOpts io;
    GranSchemes sch;
    if (gran_read_schemes(schemes, &sch, &e) || interp_read_opts(schemes, &io, &e) || state_start(&r->cs, st, &e))
        err_die(&e);
    char *mpath = case_path(&r->cs, "constant/polyMesh");
    if (mesh_read(&r->m, mpath, &e) || fvmesh_init(fm, &r->m, &e) || interp_init(ip, fm, &io, mpath, &e)) err_die(&e);
    int gr = pr.model == MODEL_GRANULAR;
    if (state_read_field(&r->rho, &r->m, &r->cs, st->name, gr ? "alpha" : "rho", 1, &e) ||
        state_read_field(&r->U, &r->m, &r->cs, st->name, "U", 3, &e) ||
        (gr && state_read_field(&r->T, &r->m, &r->cs, st->name, "Theta", 1, &e)))
        err_die(&e);
    print_warnings(&r->rho);
    print_warnings(&r->U);
    if (gr) print_warnings(&r->T);
    if (gran_init(&r->g, fm, ip, &pr, &sch, &r->rho, &r->U, gr ? &r->T : NULL, sol, &e)) err_die(&e);
    if (gr) print_model(&pr);
    fvmesh_end_setup(fm); /* the set-up's geometry, never read by the steps */
    gran_alloc(&r->g);
    r->g.time = st->value;
    double zero = 0;
    field_init(&r->p, &r->m, "p", 1, &zero, "calculated");
    r->p.dims[0] = 1, r->p.dims[1] = -1, r->p.dims[2] = -2;
    free(mpath);
    dict_free(schemes);
    dict_free(sol);
}

static long run(const Args *a, Run *r, const Start *st)
{
    long steps = 0;
    Err e;
    double mass0 = gran_mass(&r->g);
    timeloop_init(&r->tl, &r->cs.control, st->value, st->index, st->dt);
    r->written = st->value;
    Buf log;
    buf_init(&log);
    report_vtk(state_write_vtk(&r->cs, &r->m, st->name, &log, &e), &log, &e);
    printf("Starting time loop at Time = %s, total mass %.15g\n\n", st->name, mass0);
    while (timeloop_running(&r->tl) && !stop_signal) {
        int changed = runtime_reread(&r->cs.control, &e);
        if (changed < 0) err_warn("%s (keeping the old settings)", e.msg);
        if (changed > 0) timeloop_control_changed(&r->tl);
        double mean, co;
        gran_flux(&r->g);
        co = gran_courant(&r->g, r->tl.dt, &mean);
        printf("Courant Number mean: %g max: %g\n", mean, co);
        timeloop_courant(&r->tl, co);
        double t0 = r->tl.value;
        timeloop_advance(&r->tl, args_wall(a));
        char name[64];
        runtime_time_name(&r->cs.control, r->tl.value, name);
        printf("deltaT = %g\n", r->tl.dt);
        log_time(a, name);
        if (gran_step(&r->g, r->tl.dt, &e)) {
            fprintf(stderr, "solveGranular: Time = %s: %s\n", name, e.msg);
            if (r->written != t0) write_time(r, t0);
            runtime_time_name(&r->cs.control, t0, name);
            err_fatal("stopped; the last good state is in time %s", name);
        }
        steps++;
        log_step(a, r, mass0);
        if (r->tl.write_now) write_time(r, r->tl.value);
    }
    if (stop_signal) {
        if (r->written != r->tl.value) write_time(r, r->tl.value);
        printf("Stopped by signal %d at Time = %.15g; the state is written\n", (int)stop_signal, r->tl.value);
    }
    return steps;
}

int main(int argc, char **argv)
{
    Args a;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    args_banner(&a, &tool);
    Run r;
    FvMesh fm;
    Interp ip;
    Start st;
    memset(&r, 0, sizeof r);
    catch_signals(); /* before the set-up: a signal then stops before the first step */
    read_case(&r, &a, &ip, &fm, &st);
    long steps = run(&a, &r, &st);
    if (args_get(&a, &tool, "-profile")) print_profile(&r, steps);
    log_end(&a);
    gran_free(&r.g);
    interp_free(&ip);
    fvmesh_free(&fm);
    field_free(&r.p);
    field_free(&r.U);
    if (r.T.v) field_free(&r.T);
    field_free(&r.rho);
    mesh_free(&r.m);
    case_free(&r.cs);
    linsolve_finalize();
    args_free(&a);
    return 0;
}
