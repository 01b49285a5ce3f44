/*
** test_voronoi.c: bounded Voronoi grids (voronoi.h), 3-D and 2-D.
**
**   - seeds at the cell centres of a rectilinear grid: the Voronoi grid is
**     the rectilinear grid whose points are the midpoints between
**     neighbouring centres (for a uniform grid: the grid itself, checked
**     against block_mesh cell by cell; for a graded one the midpoints are
**     not the original points, so the reference is block_mesh of the
**     midpoints).  Same cell count, per-patch face counts and internal
**     face count (the zero-area faces between diagonal neighbours of the
**     degenerate lattice are gone), volumes and centroids to 1e-12;
**   - random seeds (GSL, fixed seed) and lattices jittered by 1e-9 and
**     1e-3 of the spacing (near-degenerate): mesh_check and quality_check
**     pass, the volumes add up to the box to 1e-12, every internal face
**     is orthogonal to its seed segment (|n x d| <= 1e-10 |d|) and lies in
**     the bisector plane (1e-12 of the box), the two seeds of each face
**     are the nearest seeds to its centroid (no other seed closer by
**     1e-12 of the box), box faces' owners are the nearest seed;
**   - kept / dropped seeds (a sphere or disc of kept seeds): the wall
**     faces are exactly the faces between kept and dropped seeds, the
**     wall surface is closed (sum of area vectors 0) and the kept volume
**     equals (1/3) sum over the wall of x.S (divergence theorem);
**   - bad input fails with a message;
**   - timings of a 200^2 and a 50^3 lattice are printed (not asserted).
*/
#include "fixture.h"
#include "geom.h"
#include "mem.h"
#include "quality.h"
#include "test.h"
#include "voronoi.h"

#include <gsl/gsl_rng.h>
#include <time.h>

#define NPATCH 7
#define PI 3.14159265358979323846

/* Patch holds writable strings (the readers own theirs), so the names
   live in arrays rather than in string literals. */
static char patch_names[NPATCH][8] = {"xMin", "xMax", "yMin", "yMax", "zMin", "zMax", "wall"};
static char type_patch[] = "patch", type_wall[] = "wall", type_empty[] = "empty";

/* Patches with the two sides normal to flat (if >= 0) empty. */
static void side_patches(Patch p[NPATCH], int flat)
{
    for (int k = 0; k < NPATCH; k++)
        p[k] = (Patch){patch_names[k], k < 6 ? type_patch : type_wall, 0, 0, NULL, NULL};
    if (flat >= 0) p[2 * flat].type = p[2 * flat + 1].type = type_empty;
}

static VoronoiInput input(int n, const double *x, const char *keep, const int *patch, const double lo[3],
                          const double hi[3], int flat, const Patch *p)
{
    VoronoiInput in;
    memset(&in, 0, sizeof in);
    in.nseeds = n;
    in.x = x;
    in.keep = keep;
    in.patch = patch;
    for (int a = 0; a < 3; a++) {
        in.lo[a] = lo[a];
        in.hi[a] = hi[a];
    }
    in.flat_axis = flat;
    in.npatches = NPATCH;
    in.patches = p;
    for (int s = 0; s < 6; s++) in.side_patch[s] = s;
    return in;
}

static double now(clockid_t clk)
{
    struct timespec t;
    clock_gettime(clk, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double box_size(const VoronoiInput *in)
{
    double L = 0;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis && in->hi[a] - in->lo[a] > L) L = in->hi[a] - in->lo[a];
    return L;
}

/* Squared distance in the plane of a 2-D grid, or in space. */
static double dist2(const double *a, const double *b, int flat)
{
    double d = 0;
    for (int k = 0; k < 3; k++)
        if (k != flat) d += (a[k] - b[k]) * (a[k] - b[k]);
    return d;
}

/* Width of face f: area / diameter (its points' largest distance), the
   length over which an error in its points tilts its normal. */
static double face_width(const Mesh *m, int f)
{
    double dmax = 0;
    for (int a = m->face_off[f]; a < m->face_off[f + 1]; a++)
        for (int b = a + 1; b < m->face_off[f + 1]; b++) {
            double d = sqrt(dist2(m->points + 3 * m->face_idx[a], m->points + 3 * m->face_idx[b], -1));
            if (d > dmax) dmax = d;
        }
    return geom_norm(m->face_area + 3 * f) / dmax;
}

/* The checks every grid must pass, positions to ptol x box size (points
   on their bisector, centroids equidistant); returns 0 or writes why. */
static int check_grid(Mesh *m, const VoronoiInput *in, const int *seed_of, double ptol, double *ortho, char *why,
                      size_t nwhy)
{
    *ortho = 0;
    Err e;
    if (mesh_check(m, &e)) {
        snprintf(why, nwhy, "mesh_check: %s", e.msg);
        return -1;
    }
    Quality q;
    quality_measure(m, &q);
    if (quality_check(m, &q, NULL, &e)) {
        snprintf(why, nwhy, "quality_check: %s", e.msg);
        return -1;
    }
    int flat = in->flat_axis;
    double L = box_size(in), vbox = 1;
    for (int a = 0; a < 3; a++) vbox *= in->hi[a] - in->lo[a];
    double vol = 0;
    for (int c = 0; c < m->ncells; c++) vol += m->cell_vol[c];
    int all_kept = 1;
    for (int i = 0; i < in->nseeds; i++) all_kept &= in->keep[i] != 0;
    if (all_kept && fabs(vol - vbox) > 1e-12 * vbox) {
        snprintf(why, nwhy, "volume %.17g, box %.17g", vol, vbox);
        return -1;
    }
    for (int f = 0; f < m->nfaces; f++) {
        const double *S = m->face_area + 3 * f, *C = m->face_centre + 3 * f;
        double Sn = geom_norm(S);
        int a = seed_of[m->owner[f]], p = mesh_face_patch(m, f);
        const double *xa = in->x + 3 * a;
        double da = sqrt(dist2(C, xa, flat));
        if (p >= 0 && p < 6) {
            /* box face: on its side, the owner's seed nearest */
            if (fabs(C[p / 2] - (p % 2 ? in->hi[p / 2] : in->lo[p / 2])) > ptol * L) {
                snprintf(why, nwhy, "face %d of patch %d is off its box side", f, p);
                return -1;
            }
            if (p / 2 == flat) continue;
            for (int j = 0; j < in->nseeds; j++)
                if (sqrt(dist2(C, in->x + 3 * j, flat)) < da - ptol * L) {
                    snprintf(why, nwhy, "box face %d: seed %d nearer than owner seed %d", f, j, a);
                    return -1;
                }
            continue;
        }
        /* a bisector face: find the seed across it */
        int b = -1;
        if (f < m->ninternal) {
            b = seed_of[m->neighbour[f]];
        } else {
            double best = INFINITY;
            for (int j = 0; j < in->nseeds; j++) {
                if (j == a || in->keep[j]) continue;
                double d = fabs(sqrt(dist2(C, in->x + 3 * j, flat)) - da);
                if (d < best) best = d, b = j;
            }
        }
        const double *xb = in->x + 3 * b;
        double d[3], mid[3], cr[3];
        for (int k = 0; k < 3; k++) {
            d[k] = k == flat ? 0 : xb[k] - xa[k];
            mid[k] = 0.5 * (xa[k] + xb[k]);
        }
        geom_cross(S, d, cr);
        double dn = geom_norm(d);
        /* orthogonal to round-off: a face of size s whose points are
           within ptol L of the plane is tilted by up to about ptol L / w
           (w its width), so 1e-10 for faces wider than 1e-2 L when
           ptol = 1e-12 */
        double ang = geom_norm(cr) / (dn * Sn), lim = 4 * ptol * L / face_width(m, f);
        if (f < m->ninternal && ang > *ortho) *ortho = ang;
        if (geom_dot(S, d) <= 0 || ang > (lim > 1e-10 ? lim : 1e-10)) {
            snprintf(why, nwhy, "face %d (seeds %d %d) not orthogonal: |n x d| = %g |d|", f, a, b,
                     geom_norm(cr) / (dn * Sn));
            return -1;
        }
        for (int fp = m->face_off[f]; fp < m->face_off[f + 1]; fp++) {
            const double *P = m->points + 3 * m->face_idx[fp];
            double pm[3] = {P[0] - mid[0], P[1] - mid[1], P[2] - mid[2]};
            double off = geom_dot(d, pm) / dn;
            if (fabs(off) > ptol * L) {
                snprintf(why, nwhy, "face %d (seeds %d %d): point %d is %g off the bisector", f, a, b,
                         m->face_idx[fp], off);
                return -1;
            }
        }
        double db = sqrt(dist2(C, xb, flat));
        if (fabs(da - db) > ptol * L) {
            snprintf(why, nwhy, "face %d centroid not equidistant: %.17g %.17g", f, da, db);
            return -1;
        }
        for (int j = 0; j < in->nseeds; j++)
            if (sqrt(dist2(C, in->x + 3 * j, flat)) < da - ptol * L) {
                snprintf(why, nwhy, "face %d (seeds %d %d): seed %d is nearer", f, a, b, j);
                return -1;
            }
        if (f >= m->ninternal && p != in->patch[b]) {
            snprintf(why, nwhy, "face %d on patch %d, dropped seed %d has patch %d", f, p, b, in->patch[b]);
            return -1;
        }
    }
    return 0;
}

static void cell_centres(const Mesh *g, double **x, char **keep)
{
    *x = mem_alloc(sizeof(double) * 3 * (size_t)g->ncells);
    memcpy(*x, g->cell_centre, sizeof(double) * 3 * (size_t)g->ncells);
    *keep = mem_alloc((size_t)g->ncells);
    memset(*keep, 1, (size_t)g->ncells);
}

/* Rectilinear grid of per-axis points x (graded when graded); its Voronoi
   grid must be the grid of the midpoints between its cell centres. */
static void lattice_case(int nx, int ny, int nz, int graded, int flat)
{
    int n[3] = {nx, ny, nz};
    double *x[3], *mid[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        mid[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++)
            x[k][i] = -0.5 + 0.2 * k + (graded ? i * (1.0 + 0.07 * i) : (double)i) * (0.1 + 0.03 * k);
        mid[k][0] = x[k][0];
        mid[k][n[k]] = x[k][n[k]];
        for (int i = 1; i < n[k]; i++)
            mid[k][i] = 0.25 * (x[k][i - 1] + 2 * x[k][i] + x[k][i + 1]);
        if (!graded)
            for (int i = 0; i <= n[k]; i++) mid[k][i] = x[k][i];
    }
    Mesh g, ref, m;
    fixture_mesh(&g, x, n);
    fixture_mesh(&ref, mid, n);
    double *seed;
    char *keep;
    cell_centres(&g, &seed, &keep);
    Patch p[NPATCH];
    side_patches(p, flat);
    double lo[3] = {x[0][0], x[1][0], x[2][0]}, hi[3] = {x[0][nx], x[1][ny], x[2][nz]};
    VoronoiInput in = input(g.ncells, seed, keep, NULL, lo, hi, flat, p);
    int *seed_of = mem_alloc(sizeof(int) * (size_t)g.ncells);
    VoronoiStats st;
    Err e;
    int rc = voronoi_mesh(&in, &m, seed_of, &st, &e);
    EXPECT(rc == 0, "voronoi_mesh: %s", e.msg);
    if (rc == 0) {
        mesh_cell_faces(&m);
        mesh_geometry(&m);
        double L = box_size(&in);
        EXPECT(m.ncells == ref.ncells, "%d cells, expected %d", m.ncells, ref.ncells);
        EXPECT(m.ninternal == ref.ninternal, "%d internal faces, expected %d", m.ninternal, ref.ninternal);
        EXPECT(m.nfaces == ref.nfaces, "%d faces, expected %d", m.nfaces, ref.nfaces);
        EXPECT(m.npoints == ref.npoints, "%d points, expected %d", m.npoints, ref.npoints);
        for (int q = 0; q < 6; q++)
            EXPECT(m.patches[q].size == ref.patches[q].size, "patch %d: %d faces, expected %d", q,
                   m.patches[q].size, ref.patches[q].size);
        EXPECT(st.nfaces_dropped >= 0, "dropped %d", st.nfaces_dropped);
        EXPECT(st.ortho_max < 1e-12, "ortho_max %g", st.ortho_max);
        double vmax = 0;
        for (int c = 0; c < m.ncells && c < ref.ncells; c++) {
            EXPECT(seed_of[c] == c, "cell %d has seed %d", c, seed_of[c]);
            if (ref.cell_vol[c] > vmax) vmax = ref.cell_vol[c];
            NEAR(m.cell_vol[c], ref.cell_vol[c], 1e-12 * ref.cell_vol[c]);
            for (int a = 0; a < 3; a++) NEAR(m.cell_centre[3 * c + a], ref.cell_centre[3 * c + a], 1e-12 * L);
        }
        NEAR(st.vol_total, (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]), 1e-12 * vmax * m.ncells);
        char why[ERR_MSG_MAX + 128];
        double ortho;
        if (m.ncells == ref.ncells && check_grid(&m, &in, seed_of, 1e-12, &ortho, why, sizeof why))
            EXPECT(0, "%s", why);
        /* every neighbour pair of the reference grid is a face, and no other */
        for (int f = 0; f < m.ninternal && f < ref.ninternal; f++)
            EXPECT(m.owner[f] == ref.owner[f] && m.neighbour[f] == ref.neighbour[f],
                   "face %d: %d-%d, expected %d-%d", f, m.owner[f], m.neighbour[f], ref.owner[f],
                   ref.neighbour[f]);
    }
    mesh_free(&m);
    mesh_free(&g);
    mesh_free(&ref);
    free(seed);
    free(keep);
    free(seed_of);
    for (int k = 0; k < 3; k++) {
        free(x[k]);
        free(mid[k]);
    }
}

TEST(lattice_uniform_3d) { lattice_case(7, 5, 6, 0, -1); }
TEST(lattice_graded_3d) { lattice_case(6, 7, 5, 1, -1); }
TEST(lattice_uniform_2d) { lattice_case(9, 7, 1, 0, 2); }
TEST(lattice_graded_2d) { lattice_case(8, 9, 1, 1, 2); }
TEST(lattice_graded_2d_flat_x) { lattice_case(1, 8, 6, 1, 0); }

/* Runs voronoi_mesh on the seeds and applies check_grid. */
static void run_checked(int n, const double *x, const char *keep, const int *patch, const double lo[3],
                        const double hi[3], int flat, double ptol, Mesh *m, VoronoiStats *st, int **seed_of)
{
    Patch p[NPATCH];
    side_patches(p, flat);
    VoronoiInput in = input(n, x, keep, patch, lo, hi, flat, p);
    *seed_of = mem_alloc(sizeof(int) * (size_t)n);
    Err e;
    int rc = voronoi_mesh(&in, m, *seed_of, st, &e);
    EXPECT(rc == 0, "voronoi_mesh: %s", e.msg);
    if (rc) return;
    char why[ERR_MSG_MAX + 128];
    double ortho = 0;
    if (check_grid(m, &in, *seed_of, ptol, &ortho, why, sizeof why)) EXPECT(0, "%s", why);
    EXPECT(st->ncells == m->ncells, "stats %d cells, mesh %d", st->ncells, m->ncells);
    /* the statistic is the angle over internal faces from the polygons'
       fan triangulation; the test measured its sine with mesh_geometry's
       area vectors, which differ by round-off (relatively most on the
       thinnest faces) */
    NEAR(sin(st->ortho_max), ortho, 0.2 * ortho + 1e-13);
    double v = 0, vmin = INFINITY;
    for (int c = 0; c < m->ncells; c++) {
        v += m->cell_vol[c];
        if (m->cell_vol[c] < vmin) vmin = m->cell_vol[c];
    }
    NEAR(st->vol_total, v, 1e-12 * v);
    NEAR(st->vol_min, vmin, 1e-12 * v);
}

static void random_case(int n, int flat, unsigned long rseed)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, rseed);
    double lo[3] = {-1, 0, 0.5}, hi[3] = {1, 1.5, 1.7};
    double *x = mem_alloc(sizeof(double) * 3 * (size_t)n);
    char *keep = mem_alloc((size_t)n);
    memset(keep, 1, (size_t)n);
    for (int i = 0; i < 3 * n; i++) x[i] = lo[i % 3] + (hi[i % 3] - lo[i % 3]) * gsl_rng_uniform(r);
    Mesh m;
    VoronoiStats st;
    int *seed_of = NULL;
    run_checked(n, x, keep, NULL, lo, hi, flat, 1e-12, &m, &st, &seed_of);
    EXPECT(m.ncells == n, "%d cells of %d seeds", m.ncells, n);
    mesh_free(&m);
    free(seed_of);
    free(x);
    free(keep);
    gsl_rng_free(r);
}

TEST(random_3d) { random_case(600, -1, 42); }
TEST(random_3d_few) { random_case(5, -1, 7); }
TEST(random_2d) { random_case(2000, 2, 43); }
TEST(random_2d_flat_y) { random_case(500, 1, 44); }

/* A lattice of spacing h jittered by amp h, all kept.  Where the jitter
   is near the merge distance, points merged with a neighbour within
   VORONOI_MERGE x box size move by up to that much, so the faces lie on
   their bisectors to a few merge distances instead of 1e-12. */
static void jitter_case(int nl, int flat, double amp, unsigned long rseed)
{
    double ptol = amp < 1e-6 ? 4 * VORONOI_MERGE : 1e-12;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, rseed);
    int nz = flat >= 0 ? 1 : nl, n = nl * nl * nz;
    double h = 0.1, lo[3] = {0, 0, 0}, hi[3] = {nl * h, nl * h, nz * h};
    double *x = mem_alloc(sizeof(double) * 3 * (size_t)n);
    char *keep = mem_alloc((size_t)n);
    memset(keep, 1, (size_t)n);
    int i = 0;
    for (int k = 0; k < nz; k++)
        for (int jy = 0; jy < nl; jy++)
            for (int jx = 0; jx < nl; jx++, i++) {
                int ijk[3] = {jx, jy, k};
                for (int a = 0; a < 3; a++)
                    x[3 * i + a] = (ijk[a] + 0.5) * h + (a == flat ? 0 : amp * h * (2 * gsl_rng_uniform(r) - 1));
            }
    Mesh m;
    VoronoiStats st;
    int *seed_of = NULL;
    run_checked(n, x, keep, NULL, lo, hi, flat, ptol, &m, &st, &seed_of);
    EXPECT(m.ncells == n, "%d cells of %d seeds", m.ncells, n);
    printf("  jitter %g (%s): %d cells, %d faces, %d tiny faces dropped\n", amp, flat >= 0 ? "2-D" : "3-D",
           m.ncells, m.nfaces, st.nfaces_dropped);
    mesh_free(&m);
    free(seed_of);
    free(x);
    free(keep);
    gsl_rng_free(r);
}

TEST(jitter_1e9_3d) { jitter_case(8, -1, 1e-9, 1); }
TEST(jitter_1e3_3d) { jitter_case(8, -1, 1e-3, 2); }
TEST(jitter_1e14_3d) { jitter_case(6, -1, 1e-14, 3); }
TEST(jitter_1e10_3d) { jitter_case(8, -1, 1e-10, 6); }
TEST(jitter_1e11_3d) { jitter_case(8, -1, 1e-11, 7); }
TEST(jitter_1e10_2d) { jitter_case(20, 2, 1e-10, 8); }
TEST(jitter_1e9_2d) { jitter_case(20, 2, 1e-9, 4); }
TEST(jitter_1e3_2d) { jitter_case(20, 2, 1e-3, 5); }

/* A lattice rotated about z and x (kind 0) or with every other row
   shifted by half a spacing (kind 1), jittered by amp; seeds outside the
   box are dropped onto the wall.  Both have many nearly cospherical seeds
   whose cells meet in slivers the welding collapses (the cases that need
   vertex naming and T-junction repair). */
static void degenerate_case(int kind, int nl, int flat, double amp, unsigned long rseed)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, rseed);
    int nz = flat >= 0 ? 1 : nl, n = nl * nl * nz;
    double h = 1.0 / nl, lo[3] = {0, 0, 0}, hi[3] = {1, 1, nz * h};
    double *x = mem_alloc(sizeof(double) * 3 * (size_t)n);
    char *keep = mem_alloc((size_t)n);
    int *patch = mem_alloc(sizeof(int) * (size_t)n);
    double ct = cos(0.7), st_ = sin(0.7), cp = cos(0.4), sp = sin(0.4);
    int i = 0;
    for (int k = 0; k < nz; k++)
        for (int jy = 0; jy < nl; jy++)
            for (int jx = 0; jx < nl; jx++, i++) {
                double p[3] = {(jx + 0.5) * h, (jy + 0.5) * h, (k + 0.5) * h};
                if (kind == 0) {
                    double q[3] = {p[0] - 0.5, p[1] - 0.5, p[2] - 0.5};
                    double u[3] = {ct * q[0] - st_ * q[1], st_ * q[0] + ct * q[1], q[2]};
                    if (flat < 0) {
                        double w = cp * u[1] - sp * u[2];
                        u[2] = sp * u[1] + cp * u[2];
                        u[1] = w;
                    }
                    p[0] = 0.5 + 0.9 * u[0];
                    p[1] = 0.5 + 0.9 * u[1];
                    if (flat < 0) p[2] = 0.5 + 0.9 * u[2];
                } else if (jy % 2) {
                    p[0] += 0.5 * h;
                }
                for (int a = 0; a < 3; a++)
                    if (a != flat) p[a] += amp * h * (2 * gsl_rng_uniform(r) - 1);
                keep[i] = 1;
                for (int a = 0; a < 3; a++)
                    if (a != flat && (p[a] < lo[a] || p[a] > hi[a])) keep[i] = 0;
                memcpy(x + 3 * i, p, sizeof p);
                patch[i] = 6;
            }
    Mesh m;
    VoronoiStats st;
    int *seed_of = NULL;
    double ptol = amp > 0 && amp < 1e-6 ? 4 * VORONOI_MERGE : 1e-12;
    run_checked(n, x, keep, patch, lo, hi, flat, ptol, &m, &st, &seed_of);
    printf("  %s %s, jitter %g: %d cells, %d faces, %d tiny faces dropped\n", kind ? "shifted rows" : "rotated",
           flat >= 0 ? "2-D" : "3-D", amp, m.ncells, m.nfaces, st.nfaces_dropped);
    mesh_free(&m);
    free(seed_of);
    free(x);
    free(keep);
    free(patch);
    gsl_rng_free(r);
}

TEST(rotated_3d) { degenerate_case(0, 8, -1, 0, 1); }
TEST(rotated_jitter_1e12_3d) { degenerate_case(0, 8, -1, 1e-12, 501); }
TEST(rotated_jitter_1e10_3d) { degenerate_case(0, 8, -1, 1e-10, 803); }
TEST(shifted_jitter_1e11_3d) { degenerate_case(1, 8, -1, 1e-11, 601); }
TEST(shifted_jitter_3e11_3d) { degenerate_case(1, 8, -1, 3e-11, 701); }
TEST(rotated_2d) { degenerate_case(0, 20, 2, 0, 2); }
TEST(shifted_jitter_1e11_2d) { degenerate_case(1, 20, 2, 1e-11, 3); }

/* Lattice seeds in the box, those within radius rad of the centre kept,
   the others dropped onto patch 6 ("wall"). */
static void sphere_case(int nl, int flat, double rad, double amp)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 11);
    int nz = flat >= 0 ? 1 : nl, n = nl * nl * nz;
    double h = 1.0 / nl, lo[3] = {0, 0, 0}, hi[3] = {1, 1, nz * h}, c[3] = {0.5, 0.5, 0.5 * nz * h};
    double *x = mem_alloc(sizeof(double) * 3 * (size_t)n);
    char *keep = mem_alloc((size_t)n);
    int *patch = mem_alloc(sizeof(int) * (size_t)n);
    int nkeep = 0, i = 0;
    for (int k = 0; k < nz; k++)
        for (int jy = 0; jy < nl; jy++)
            for (int jx = 0; jx < nl; jx++, i++) {
                int ijk[3] = {jx, jy, k};
                for (int a = 0; a < 3; a++)
                    x[3 * i + a] = (ijk[a] + 0.5) * h + (a == flat ? 0 : amp * h * (2 * gsl_rng_uniform(r) - 1));
                keep[i] = dist2(x + 3 * i, c, flat) < rad * rad;
                patch[i] = 6;
                nkeep += keep[i];
            }
    Mesh m;
    VoronoiStats st;
    int *seed_of = NULL;
    run_checked(n, x, keep, patch, lo, hi, flat, 1e-12, &m, &st, &seed_of);
    if (m.ncells > 0) {
        EXPECT(m.ncells == nkeep, "%d cells, %d kept seeds", m.ncells, nkeep);
        const Patch *w = &m.patches[6];
        for (int q = 0; q < 6; q++)
            EXPECT(m.patches[q].size == (q / 2 == flat ? m.ncells : 0), "patch %d has %d faces", q,
                   m.patches[q].size);
        double S[3] = {0, 0, 0}, xs = 0, area = 0;
        for (int f = w->start; f < w->start + w->size; f++) {
            const double *Sf = m.face_area + 3 * f, *Cf = m.face_centre + 3 * f;
            for (int a = 0; a < 3; a++) S[a] += Sf[a];
            area += geom_norm(Sf);
            /* divergence theorem over the kept region: V = sum x.S / dims,
               with the empty faces' x.S added in 2-D */
            xs += geom_dot(Cf, Sf);
        }
        if (flat >= 0) {
            const Patch *pa[2] = {&m.patches[2 * flat], &m.patches[2 * flat + 1]};
            for (int s = 0; s < 2; s++)
                for (int f = pa[s]->start; f < pa[s]->start + pa[s]->size; f++)
                    xs += geom_dot(m.face_centre + 3 * f, m.face_area + 3 * f);
        }
        EXPECT(geom_norm(S) < 1e-12 * area, "wall not closed: |sum S| = %g of %g", geom_norm(S), area);
        NEAR(xs / 3, st.vol_total, 1e-12 * st.vol_total);
        /* the wall lies between the sphere and a shell one spacing out */
        double vs = flat >= 0 ? PI * rad * rad * (nz * h) : 4.0 / 3 * PI * rad * rad * rad;
        EXPECT(st.vol_total > 0.5 * vs && st.vol_total < 2 * vs, "kept volume %g, sphere %g", st.vol_total, vs);
        printf("  %s sphere: %d cells, wall %d faces, area %.6f, volume %.6f (ball %.6f)\n",
               flat >= 0 ? "2-D" : "3-D", m.ncells, w->size, area, st.vol_total, vs);
    }
    mesh_free(&m);
    free(seed_of);
    free(x);
    free(keep);
    free(patch);
    gsl_rng_free(r);
}

TEST(sphere_kept_3d) { sphere_case(12, -1, 0.37, 0); }
TEST(sphere_kept_jitter_3d) { sphere_case(12, -1, 0.37, 0.2); }
TEST(disc_kept_2d) { sphere_case(30, 2, 0.37, 0); }
TEST(disc_kept_jitter_2d) { sphere_case(30, 2, 0.37, 0.2); }

/* Seeds outside the box (dropped) and a kept cell touching the box. */
TEST(dropped_outside_box)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    /* the bisector of seeds 0 and 3 touches both cells' corner (0.5,
       0.05) along z; seed 4's bisector x = 1.025 misses the box */
    double x[] = {0.25, 0.5, 0.5, 0.75, 0.5, 0.5, 0.25, -0.4, 0.5, 0.75, -0.4, 0.5, 1.3, 0.5, 0.5};
    char keep[] = {1, 1, 0, 0, 0};
    int patch[] = {0, 0, 6, 6, 6};
    Mesh m;
    VoronoiStats st;
    int *seed_of = NULL;
    run_checked(5, x, keep, patch, lo, hi, -1, 1e-12, &m, &st, &seed_of);
    /* cells [0, 0.5] and [0.5, 1] in x, [0.05, 1] in y */
    NEAR(st.vol_total, 0.95, 1e-14);
    NEAR(st.vol_min, 0.475, 1e-14);
    EXPECT(m.ncells == 2 && m.ninternal == 1, "%d cells, %d internal", m.ncells, m.ninternal);
    EXPECT(m.patches[6].size == 2 && m.patches[1].size == 1 && m.patches[2].size == 0,
           "wall %d faces, xMax %d, yMin %d", m.patches[6].size, m.patches[1].size, m.patches[2].size);
    mesh_free(&m);
    free(seed_of);
}

static void expect_error(const VoronoiInput *in, const char *sub)
{
    Mesh m;
    Err e;
    e.msg[0] = 0;
    int rc = voronoi_mesh(in, &m, NULL, NULL, &e);
    EXPECT(rc == -1, "accepted bad input (%s)", sub);
    CONTAINS(e.msg, sub);
    mesh_free(&m);
}

TEST(bad_input)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    double x[] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.2, 0.2, 0.2};
    char keep[] = {1, 1, 0}, none[] = {0, 0, 0};
    int patch[] = {0, 0, 9};
    Patch p[NPATCH];
    side_patches(p, -1);
    VoronoiInput in = input(2, x, keep, patch, lo, hi, -1, p);
    expect_error(&in, "voronoi: seeds 0 and 1 coincide");
    in.nseeds = 3;
    expect_error(&in, "dropped seed 2 has patch 9");
    in.nseeds = 1;
    in.keep = none;
    expect_error(&in, "no seed is kept");
    in.keep = keep;
    in.flat_axis = 3;
    expect_error(&in, "flat axis 3");
    in.flat_axis = -1;
    in.side_patch[3] = 7;
    expect_error(&in, "box side 3 has patch 7");
    in.side_patch[3] = 3;
    in.hi[1] = 0;
    expect_error(&in, "empty box along axis 1");
    in.hi[1] = 1;
    double out[] = {1.5, 0.5, 0.5};
    in.x = out;
    expect_error(&in, "kept seed 0 (1.5 0.5 0.5) is outside the box");
    double bad[] = {NAN, 0.5, 0.5};
    in.x = bad;
    expect_error(&in, "seed 0 is not finite");
    in.nseeds = 0;
    expect_error(&in, "no seeds");
}

/* Rates on undisturbed lattices (printed, not asserted). */
static void timing(int nl, int flat)
{
    int nz = flat >= 0 ? 1 : nl, n = nl * nl * nz;
    double h = 1.0 / nl, lo[3] = {0, 0, 0}, hi[3] = {1, 1, nz * h};
    double *x = mem_alloc(sizeof(double) * 3 * (size_t)n);
    char *keep = mem_alloc((size_t)n);
    memset(keep, 1, (size_t)n);
    int i = 0;
    for (int k = 0; k < nz; k++)
        for (int jy = 0; jy < nl; jy++)
            for (int jx = 0; jx < nl; jx++, i++) {
                x[3 * i] = (jx + 0.5) * h;
                x[3 * i + 1] = (jy + 0.5) * h;
                x[3 * i + 2] = (k + 0.5) * h;
            }
    Patch p[NPATCH];
    side_patches(p, flat);
    VoronoiInput in = input(n, x, keep, NULL, lo, hi, flat, p);
    Mesh m;
    VoronoiStats st;
    Err e;
    double t0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    int rc = voronoi_mesh(&in, &m, NULL, &st, &e);
    double t = now(CLOCK_MONOTONIC) - t0, cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    EXPECT(rc == 0, "%s", e.msg);
    EXPECT(rc || m.ncells == n, "%d cells", m.ncells);
    EXPECT(rc || m.ninternal == (flat >= 0 ? 2 * nl * (nl - 1) : 3 * nl * nl * (nl - 1)), "%d internal faces",
           m.ninternal);
    printf("  %s lattice %d^%d: %d cells in %.3f s (cpu %.3f s): %.3g cells/s (cpu %.3g cells/s)\n",
           flat >= 0 ? "2-D" : "3-D", nl, flat >= 0 ? 2 : 3, n, t, cpu, n / t, n / cpu);
    mesh_free(&m);
    free(x);
    free(keep);
}

TEST(timing_2d) { timing(200, 2); }
TEST(timing_3d) { timing(50, -1); }

int main(void)
{
    RUN(lattice_uniform_3d);
    RUN(lattice_graded_3d);
    RUN(lattice_uniform_2d);
    RUN(lattice_graded_2d);
    RUN(lattice_graded_2d_flat_x);
    RUN(random_3d);
    RUN(random_3d_few);
    RUN(random_2d);
    RUN(random_2d_flat_y);
    RUN(jitter_1e9_3d);
    RUN(jitter_1e3_3d);
    RUN(jitter_1e14_3d);
    RUN(jitter_1e10_3d);
    RUN(jitter_1e11_3d);
    RUN(jitter_1e10_2d);
    RUN(jitter_1e9_2d);
    RUN(jitter_1e3_2d);
    RUN(rotated_3d);
    RUN(rotated_jitter_1e12_3d);
    RUN(rotated_jitter_1e10_3d);
    RUN(shifted_jitter_1e11_3d);
    RUN(shifted_jitter_3e11_3d);
    RUN(rotated_2d);
    RUN(shifted_jitter_1e11_2d);
    RUN(sphere_kept_3d);
    RUN(sphere_kept_jitter_3d);
    RUN(disc_kept_2d);
    RUN(disc_kept_jitter_2d);
    RUN(dropped_outside_box);
    RUN(bad_input);
    RUN(timing_2d);
    RUN(timing_3d);
    return test_summary();
}
