/*
** test_seeds.c: Voronoi seeds (seeds.c).
**
** Checked on small block grids: no two seeds closer than the minimum
** spacing a (brute force over all pairs); exterior seeds outside the flow
** domain, kept seeds inside it; boundary seeds on their sample's normal;
** exact counts for a plane with boundary layers (layer seeds at depths
** (2i+1) h/2, in layer order, and the Cartesian centres left by the band
** rule); 2-D seeds in the mid-plane; a geometry entirely outside the grid
** gives exactly the Cartesian centres; bad options and grids fail with a
** message.
*/
#include "test.h"
#include "fixture.h"

#include "block.h"
#include "geometry.h"
#include "mem.h"
#include "seeds.h"

static const double PI_ = 3.14159265358979323846;


static void grid(Mesh *m, const double lo[3], const double hi[3], const int n[3], int flat)
{
    fixture_block(m, n, lo, hi, flat);
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Smallest distance between two seeds (brute force). */
static double min_pair(const Seeds *s)
{
    double d = INFINITY;
    for (int i = 0; i < s->n; i++)
        for (int j = i + 1; j < s->n; j++) d = fmin(d, dist3(s->x + 3 * i, s->x + 3 * j));
    return d;
}

/* Kept seeds in the flow, exterior ones not; boundary seeds carry unit
   normals; returns the number of violations. */
static int count_misplaced(const Seeds *s, const Geometry *g)
{
    int bad = 0;
    for (int i = 0; i < s->n; i++) {
        const double *x = s->x + 3 * i, *n = s->normal + 3 * i;
        bad += geometry_fluid(g, x) != s->interior[i];
        bad += s->interior[i] ? s->surface[i] != -1 : s->surface[i] < 0 || s->surface[i] >= g->nsurf;
        if (s->kind[i] == SEED_BOUNDARY) bad += fabs(dist3(n, (double[3]){0, 0, 0}) - 1) > 1e-12;
        else bad += s->kind[i] != SEED_CARTESIAN || n[0] != 0 || n[1] != 0 || n[2] != 0;
    }
    return bad;
}

TEST(seeds_without_surfaces)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { far { shape sphere; centre (3 3 3); radius 0.5; } }", &e) == 0, "%s", e.msg);
    Mesh m;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0.6, 0.4};
    int n[3] = {10, 6, 4};
    grid(&m, lo, hi, n, -1);
    SeedOpts o;
    seeds_opts_default(&o);
    o.layers = 2;
    Seeds s;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == 0, "%s", e.msg);
    EXPECT(s.n == 240, "%d seeds, expected the 240 cell centres", s.n);
    int bad = 0;
    for (int c = 0; c < s.n && s.n == 240; c++) {
        int i = c % 10, j = c / 10 % 6, k = c / 60;
        double x[3] = {0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.05 + 0.1 * k};
        bad += dist3(s.x + 3 * c, x) > 1e-15 || !s.interior[c] || s.kind[c] != SEED_CARTESIAN || s.surface[c] != -1;
    }
    EXPECT(bad == 0, "%d seeds differ from the cell centres", bad);
    seeds_free(&s);
    mesh_free(&m);
    geometry_free(&g);
}

/* The plane z = 0.43 bounding the flow from above, two boundary layers:
   every count follows from the rules in seeds.c. */
TEST(seeds_plane_layers)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { top { flow inside; shape halfSpace; point (0 0 0.43); normal (0 0 1); } }", &e) == 0,
           "%s", e.msg);
    Mesh m;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, h = 0.1;
    int n[3] = {10, 10, 10};
    grid(&m, lo, hi, n, -1);
    SeedOpts o;
    seeds_opts_default(&o);
    o.layers = 2;
    Seeds s;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == 0, "%s", e.msg);
    int next = 0, nlayer[3] = {0, 0, 0}, ncart_in = 0, ncart_out = 0, order = 1, bad = 0, last = 0;
    for (int i = 0; i < s.n; i++) {
        const double *x = s.x + 3 * i;
        if (s.kind[i] == SEED_CARTESIAN) {
            ncart_in += s.interior[i], ncart_out += !s.interior[i];
            continue;
        }
        double d = 0.43 - x[2];   /* depth below the plane */
        if (!s.interior[i]) {
            next++;
            bad += fabs(d + h / 2) > 1e-12;
            continue;
        }
        int l = (int)floor(d / h);
        bad += l < 0 || l > 2 || fabs(d - (2 * l + 1) * h / 2) > 1e-12;
        if (l >= 0 && l <= 2) nlayer[l]++;
        order &= l >= last;
        last = l;
    }
    EXPECT(bad == 0, "%d boundary seeds off the depths -h/2, h/2, 3h/2, 5h/2", bad);
    EXPECT(order, "layer seeds out of layer order");
    /* 10 x 10 sample points at the cell centres' x, y (midpoints, half a
       spacing from the box sides), every pair kept */
    EXPECT(next == 100, "%d exterior seeds, expected 100", next);
    EXPECT(nlayer[0] == 100 && nlayer[1] == 100 && nlayer[2] == 100, "layers %d %d %d, expected 100 each",
           nlayer[0], nlayer[1], nlayer[2]);
    /* fluid centres deeper than 5h/2 + a/2 = 0.275: z = 0.05, 0.15, but
       z = 0.15 is 0.03 < a below the deepest layer seed (z = 0.18) and
       dropped; solid centres beyond h/2 + a/2 = 0.075 above: z = 0.55 ..
       0.95 */
    EXPECT(ncart_in == 100 && ncart_out == 500, "Cartesian seeds %d in the flow (expected 100), %d outside (500)",
           ncart_in, ncart_out);
    EXPECT(count_misplaced(&s, &g) == 0, "misplaced seeds");
    /* nearest pair: an exterior seed (z = 0.48) and the solid centre
       above it (z = 0.55) */
    NEAR(min_pair(&s), 0.07, 1e-12);
    seeds_free(&s);
    mesh_free(&m);
    geometry_free(&g);
}

/* A box with a cylindrical hole: every rule on a CSG part. */
TEST(seeds_csg_part)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { part { flow inside; shape difference;\n"
                     "  body { shape box; min (0.1 0.1 0.1); max (0.9 0.7 0.5); }\n"
                     "  hole { shape cylinder; point1 (0.4 0.4 0); point2 (0.4 0.4 0.6); radius 0.15; }\n"
                     "} }\n", &e) == 0, "%s", e.msg);
    Mesh m;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0.8, 0.6};
    int n[3] = {20, 16, 12};
    grid(&m, lo, hi, n, -1);
    SeedOpts o;
    seeds_opts_default(&o);
    o.layers = 1;
    Seeds s;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == 0, "%s", e.msg);
    double a = 0.5 * 0.05, dmin = min_pair(&s);
    EXPECT(dmin >= a, "two seeds %g apart, minimum spacing %g", dmin, a);
    EXPECT(count_misplaced(&s, &g) == 0, "misplaced seeds");
    /* every boundary seed lies on its sample's normal line at h/2, 3h/2:
       the exterior seeds of the hole are at distance r - h/2 from its
       axis, its interior ones at r + h/2 or r + 3h/2 */
    int nhole = 0, bad = 0, nbox_corner = 0;
    for (int i = 0; i < s.n; i++) {
        if (s.kind[i] != SEED_BOUNDARY) continue;
        const double *x = s.x + 3 * i, *v = s.normal + 3 * i;
        double r = hypot(x[0] - 0.4, x[1] - 0.4);
        /* the hole's seeds: normal towards its axis */
        if (fabs(v[0] * (x[0] - 0.4) + v[1] * (x[1] - 0.4) + r) < 1e-9 && r < 0.3) {
            nhole++;
            double dr = r - 0.15, want = s.interior[i] ? 0.025 : -0.025;
            bad += fabs(dr - want) > 1e-12 && fabs(dr - 3 * want) > 1e-12;
        }
        /* the corner (0.9 0.7 0.5), normal (1 1 1)/sqrt 3: the eight
           corners of the cube of side h about it, the one inside the box
           interior (Fig. 3.16 for three orthogonal faces) */
        double c[3] = {0.9, 0.7, 0.5};
        if (fabs(v[0] - 1 / sqrt(3)) < 1e-12 && fabs(v[1] - v[0]) < 1e-12 && fabs(v[2] - v[0]) < 1e-12) {
            int inside = 1;
            for (int k = 0; k < 3; k++) {
                bad += fabs(fabs(x[k] - c[k]) - 0.025) > 1e-12;
                inside &= x[k] < c[k];
            }
            bad += inside != s.interior[i];
            nbox_corner++;
        }
    }
    EXPECT(bad == 0, "%d boundary seeds off their normal lines", bad);
    EXPECT(nhole > 0, "no seeds for the hole");
    EXPECT(nbox_corner == 8, "%d seeds of the corner (0.9 0.7 0.5), expected 8", nbox_corner);
    seeds_free(&s);
    mesh_free(&m);
    geometry_free(&g);
}

TEST(seeds_2d_disc)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { disc { shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.2; } }",
                 &e) == 0, "%s", e.msg);
    Mesh m;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.1}, h = 0.05;
    int n[3] = {20, 20, 1};
    grid(&m, lo, hi, n, 2);
    SeedOpts o;
    seeds_opts_default(&o);
    o.layers = 2;
    Seeds s;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == 0, "%s", e.msg);
    int off = 0, next = 0, nin = 0, bad = 0;
    for (int i = 0; i < s.n; i++) {
        off += s.x[3 * i + 2] != 0.05;
        if (s.kind[i] != SEED_BOUNDARY) continue;
        double r = hypot(s.x[3 * i] - 0.5, s.x[3 * i + 1] - 0.5);
        if (!s.interior[i]) {
            next++;
            bad += fabs(r - (0.2 - h / 2)) > 1e-12;
        } else {
            nin++;
            double d = (r - 0.2) / (h / 2);   /* 1, 3 or 5 */
            bad += fabs(d - 1) > 1e-9 && fabs(d - 3) > 1e-9 && fabs(d - 5) > 1e-9;
        }
    }
    EXPECT(off == 0, "%d seeds off the mid-plane z = 0.05", off);
    EXPECT(bad == 0, "%d boundary seeds off their circles", bad);
    int m_ring = (int)floor(2 * PI_ * 0.2 / h + 0.5);
    /* the exterior ring (radius 0.175, spacing 0.044) keeps all; the
       layers grow outward */
    EXPECT(next == m_ring && nin == 3 * m_ring, "%d exterior and %d interior boundary seeds, expected %d and %d", next,
           nin, m_ring, 3 * m_ring);
    EXPECT(count_misplaced(&s, &g) == 0, "misplaced seeds");
    EXPECT(min_pair(&s) >= 0.5 * h, "seeds closer than a");
    seeds_free(&s);
    mesh_free(&m);
    geometry_free(&g);
}

/* Fraction of the box whose nearest seed's kept flag disagrees with the
   flow domain (fixed pseudo-random points). */
static double misclassified(const Seeds *s, const Geometry *g, int npts)
{
    unsigned long r = 12345;
    int wrong = 0;
    for (int t = 0; t < npts; t++) {
        double p[3];
        for (int k = 0; k < 3; k++) {
            r = r * 6364136223846793005ul + 1442695040888963407ul;
            p[k] = (double)(r >> 11) / 9007199254740992.0;
        }
        int b = 0;
        double bd = INFINITY;
        for (int i = 0; i < s->n; i++) {
            double d = dist3(p, s->x + 3 * i);
            if (d < bd) bd = d, b = i;
        }
        wrong += s->interior[b] != geometry_fluid(g, p);
    }
    return (double)wrong / npts;
}

/* Fig. 3.16's shared seeds at box edges: the Voronoi region of the kept
   seeds matches the flow domain but for the corners (1.28 % of the box
   with mean-normal pairs at the edges, 0.69 % with the shared seeds). */
TEST(seeds_box_edges)
{
    static const char *text[2] = {
        "surfaces { b { flow inside; shape box; min (0.23 0.27 0.31); max (0.71 0.66 0.74); } }",
        "surfaces { b { shape box; min (0.23 0.27 0.31); max (0.71 0.66 0.74); } }"};
    for (int c = 0; c < 2; c++) {
        Geometry g;
        Err e;
        EXPECT(fixture_geometry(&g, text[c], &e) == 0, "%s", e.msg);
        Mesh m;
        double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
        int n[3] = {10, 10, 10};
        grid(&m, lo, hi, n, -1);
        SeedOpts o;
        seeds_opts_default(&o);
        Seeds s;
        EXPECT(seeds_make(&m, &g, &o, &s, &e) == 0, "%s", e.msg);
        double f = misclassified(&s, &g, 20000);
        EXPECT(f < 0.009, "flow %s the box: %.4f of the box on the wrong side", c ? "outside" : "inside", f);
        EXPECT(count_misplaced(&s, &g) == 0, "misplaced seeds");
        EXPECT(min_pair(&s) >= 0.05, "seeds closer than a");
        seeds_free(&s);
        mesh_free(&m);
        geometry_free(&g);
    }
}

TEST(seeds_errors)
{
    Geometry g;
    Err e;
    EXPECT(fixture_geometry(&g, "surfaces { ball { shape sphere; centre (0.5 0.5 0.5); radius 0.2; } }", &e) == 0, "%s", e.msg);
    Mesh m;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    int n[3] = {4, 4, 4};
    grid(&m, lo, hi, n, -1);
    SeedOpts o;
    Seeds s;
    seeds_opts_default(&o);
    o.layers = -1;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == -1, "negative layers accepted");
    CONTAINS(e.msg, "layers must be 0..1000, found -1");
    seeds_opts_default(&o);
    o.spacing = 0;
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == -1, "zero spacing accepted");
    CONTAINS(e.msg, "spacing must be positive");
    seeds_opts_default(&o);
    Mesh bare = m;
    bare.cart.n[0] = 0;
    EXPECT(seeds_make(&bare, &g, &o, &s, &e) == -1, "grid without Cartesian extras accepted");
    CONTAINS(e.msg, "no Cartesian extras");
    geometry_free(&g);
    /* flow inside a ball that misses the grid */
    EXPECT(fixture_geometry(&g, "surfaces { ball { flow inside; shape sphere; centre (5 5 5); radius 0.2; } }", &e) == 0, "%s",
           e.msg);
    EXPECT(seeds_make(&m, &g, &o, &s, &e) == -1, "empty flow domain accepted");
    CONTAINS(e.msg, "geometryDict: seeds: no cell centre");
    mesh_free(&m);
    geometry_free(&g);
}

int main(void)
{
    RUN(seeds_without_surfaces);
    RUN(seeds_plane_layers);
    RUN(seeds_csg_part);
    RUN(seeds_2d_disc);
    RUN(seeds_box_edges);
    RUN(seeds_errors);
    return test_summary();
}
