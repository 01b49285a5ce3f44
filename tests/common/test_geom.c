/*
** test_geom.c: face and cell geometry against values worked out by hand.
**
** Each polyhedron is given by its points and outward-oriented faces; the
** test computes Sf/Cf with geom_face and V/C with geom_cell and compares
** with the exact volume and centroid to 1e-14 (relative to the volume,
** and to the body's size or distance from the origin for the centroid).
*/
#include "geom.h"
#include "test.h"

#define TOL 1e-14

typedef struct Poly {
    int npts, nfaces;
    double pts[3 * 64];
    int off[33];
    int idx[256];
} Poly;

static void poly_init(Poly *p)
{
    p->npts = p->nfaces = 0;
    p->off[0] = 0;
}

static int poly_point(Poly *p, double x, double y, double z)
{
    p->pts[3 * p->npts] = x;
    p->pts[3 * p->npts + 1] = y;
    p->pts[3 * p->npts + 2] = z;
    return p->npts++;
}

static void poly_face(Poly *p, int n, const int *v)
{
    int o = p->off[p->nfaces];
    for (int i = 0; i < n; i++) p->idx[o + i] = v[i];
    p->off[++p->nfaces] = o + n;
}

/* Prism over the polygon (x[i], y[i]) (counter-clockwise seen from +z)
   between z0 and z1: bottom reversed, top as given, sides outward. */
static void poly_extrude(Poly *p, int n, const double *x, const double *y, double z0, double z1)
{
    poly_init(p);
    for (int i = 0; i < n; i++) poly_point(p, x[i], y[i], z0);
    for (int i = 0; i < n; i++) poly_point(p, x[i], y[i], z1);
    int f[32] = {0};
    for (int i = 0; i < n; i++) f[i] = n - 1 - i;
    poly_face(p, n, f);
    for (int i = 0; i < n; i++) f[i] = n + i;
    poly_face(p, n, f);
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        int s[4] = {i, j, n + j, n + i};
        poly_face(p, 4, s);
    }
}

/* Volume and centroid of p; with reverse set, every face is stored with
   its points reversed and flagged as flipped (the cell is its neighbour). */
static void poly_measure(Poly *p, int reverse, double *V, double C[3])
{
    if (reverse) {
        for (int f = 0; f < p->nfaces; f++) {
            int a = p->off[f], b = p->off[f + 1] - 1;
            while (a < b) {
                int t = p->idx[a];
                p->idx[a++] = p->idx[b];
                p->idx[b--] = t;
            }
        }
    }
    double Sf[3 * 32], Cf[3 * 32];
    int faces[32];
    char flip[32];
    for (int f = 0; f < p->nfaces; f++) {
        geom_face(p->pts, p->idx + p->off[f], p->off[f + 1] - p->off[f], Sf + 3 * f, Cf + 3 * f);
        faces[f] = f;
        flip[f] = (char)reverse;
    }
    geom_cell(p->pts, p->off, p->idx, faces, flip, p->nfaces, Sf, Cf, V, C);
}

/* Largest |sum of outward Sf| component relative to the largest |Sf|. */
static double poly_closure(const Poly *p)
{
    double s[3] = {0, 0, 0}, big = 0;
    for (int f = 0; f < p->nfaces; f++) {
        double Sf[3], Cf[3];
        geom_face(p->pts, p->idx + p->off[f], p->off[f + 1] - p->off[f], Sf, Cf);
        for (int k = 0; k < 3; k++) s[k] += Sf[k];
        if (geom_norm(Sf) > big) big = geom_norm(Sf);
    }
    return geom_norm(s) / big;
}

static int check_poly(Poly *p, double Vex, const double Cex[3], double size, char *why, size_t nwhy)
{
    for (int reverse = 0; reverse < 2; reverse++) {
        double V, C[3];
        poly_measure(p, reverse, &V, C);
        double scale = size;
        for (int k = 0; k < 3; k++)
            if (fabs(Cex[k]) > scale) scale = fabs(Cex[k]);
        double dc = 0;
        for (int k = 0; k < 3; k++)
            if (fabs(C[k] - Cex[k]) > dc) dc = fabs(C[k] - Cex[k]);
        if (fabs(V - Vex) > TOL * Vex || dc > TOL * scale) {
            snprintf(why, nwhy, "reverse=%d: V = %.17g (exact %.17g, rel err %.3g), C = (%.17g %.17g %.17g) "
                     "(exact (%.17g %.17g %.17g), err %.3g)",
                     reverse, V, Vex, fabs(V - Vex) / Vex, C[0], C[1], C[2], Cex[0], Cex[1], Cex[2],
                     dc / scale);
            return 0;
        }
    }
    if (poly_closure(p) > 1e-15) {
        snprintf(why, nwhy, "faces not closed: |sum Sf|/max|Sf| = %.3g", poly_closure(p));
        return 0;
    }
    return 1;
}

#define CHECK_POLY(p, V, C, size)                                                            \
    do {                                                                                     \
        char why_[1024];                                                                     \
        EXPECT(check_poly(p, V, C, size, why_, sizeof why_), "%s", why_);                    \
    } while (0)

TEST(triangle_face)
{
    double pts[9] = {1, 2, 3, 4, 2, 3, 1, 5, 3};
    int idx[3] = {0, 1, 2};
    double Sf[3], Cf[3];
    geom_face(pts, idx, 3, Sf, Cf);
    /* right triangle with legs 3 and 3 in the plane z = 3: area 4.5, +z */
    NEAR(Sf[0], 0, 0);
    NEAR(Sf[1], 0, 0);
    NEAR(Sf[2], 4.5, 0);
    NEAR(Cf[0], 2, 1e-15 * 2);
    NEAR(Cf[1], 3, 1e-15 * 3);
    NEAR(Cf[2], 3, 0);
}

TEST(nonconvex_face)
{
    /* An L whose point average (4/3, 4/3) lies outside it, in the notch:
       a fan about that point folds back, so only signed weights give
       the exact area 5 and centroid (1.1, 1.1). */
    double pts[18] = {0, 0, 7, 3, 0, 7, 3, 1, 7, 1, 1, 7, 1, 3, 7, 0, 3, 7};
    int idx[6] = {0, 1, 2, 3, 4, 5};
    double Sf[3], Cf[3];
    geom_face(pts, idx, 6, Sf, Cf);
    NEAR(Sf[0], 0, 0);
    NEAR(Sf[1], 0, 0);
    NEAR(Sf[2], 5, 5 * TOL);
    NEAR(Cf[0], 1.1, 1.1 * TOL);
    NEAR(Cf[1], 1.1, 1.1 * TOL);
    NEAR(Cf[2], 7, 0);
}

TEST(warped_face_is_openfoam_rule)
{
    /* A warped quad: all four fan triangles about m face the same way, so
       geom_face must give OpenFOAM's |n|-weighted result; recompute
       OpenFOAM's formula here literally. */
    double pts[12] = {0, 0, 0, 1, 0, 0.2, 1.1, 1, 0, 0, 0.9, 0.3};
    int idx[4] = {0, 1, 2, 3};
    double Sf[3], Cf[3];
    geom_face(pts, idx, 4, Sf, Cf);
    double m[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) m[k] += pts[3 * i + k] / 4;
    double sN[3] = {0, 0, 0}, sA = 0, sAc[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const double *p = pts + 3 * i, *q = pts + 3 * ((i + 1) % 4);
        double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double v[3] = {m[0] - p[0], m[1] - p[1], m[2] - p[2]};
        double n[3];
        geom_cross(u, v, n);
        double a = geom_norm(n);
        for (int k = 0; k < 3; k++) {
            sN[k] += n[k];
            sAc[k] += a * (p[k] + q[k] + m[k]);
        }
        sA += a;
    }
    for (int k = 0; k < 3; k++) {
        NEAR(Sf[k], 0.5 * sN[k], 1e-15);
        NEAR(Cf[k], sAc[k] / (3 * sA), 1e-15);
    }
}

TEST(degenerate_face)
{
    double pts[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 0, 0};
    int idx[4] = {0, 1, 2, 3};
    double Sf[3], Cf[3];
    geom_face(pts, idx, 4, Sf, Cf);
    EXPECT(Sf[0] == 0 && Sf[1] == 0 && Sf[2] == 0, "Sf = (%g %g %g)", Sf[0], Sf[1], Sf[2]);
    NEAR(Cf[0], 1, 0);
}

TEST(unit_cube)
{
    Poly p;
    double x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 1, 1};
    poly_extrude(&p, 4, x, y, 0, 1);
    double C[3] = {0.5, 0.5, 0.5};
    CHECK_POLY(&p, 1, C, 1);
}

TEST(rotated_box)
{
    /* 1 x 2 x 3 box rotated by R = Rz(0.7) Rx(0.3), moved by t */
    Poly p;
    double x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 2, 2};
    poly_extrude(&p, 4, x, y, 0, 3);
    double cz = cos(0.7), sz = sin(0.7), cx = cos(0.3), sx = sin(0.3);
    double R[3][3] = {{cz, -sz * cx, sz * sx}, {sz, cz * cx, -cz * sx}, {0, sx, cx}};
    double t[3] = {10, -20, 30};
    for (int i = 0; i < p.npts; i++) {
        double *q = p.pts + 3 * i, r[3];
        for (int k = 0; k < 3; k++) r[k] = R[k][0] * q[0] + R[k][1] * q[1] + R[k][2] * q[2] + t[k];
        q[0] = r[0];
        q[1] = r[1];
        q[2] = r[2];
    }
    double c0[3] = {0.5, 1, 1.5}, C[3];
    for (int k = 0; k < 3; k++) C[k] = R[k][0] * c0[0] + R[k][1] * c0[1] + R[k][2] * c0[2] + t[k];
    CHECK_POLY(&p, 6, C, 3);
}

TEST(tetrahedron)
{
    /* corner tetrahedron with legs 1, 2, 3: V = 1*2*3/6, C = mean of corners */
    Poly p;
    poly_init(&p);
    poly_point(&p, 5, 5, 5);
    poly_point(&p, 6, 5, 5);
    poly_point(&p, 5, 7, 5);
    poly_point(&p, 5, 5, 8);
    int f0[3] = {0, 2, 1}, f1[3] = {0, 1, 3}, f2[3] = {0, 3, 2}, f3[3] = {1, 2, 3};
    poly_face(&p, 3, f0);
    poly_face(&p, 3, f1);
    poly_face(&p, 3, f2);
    poly_face(&p, 3, f3);
    double C[3] = {5.25, 5.5, 5.75};
    CHECK_POLY(&p, 1, C, 3);
}

TEST(square_pyramid)
{
    /* base 2 x 2 at z = 0, apex at height 3 above the base centre:
       V = 4*3/3 = 4, centroid a quarter of the height up */
    Poly p;
    poly_init(&p);
    poly_point(&p, 0, 0, 0);
    poly_point(&p, 2, 0, 0);
    poly_point(&p, 2, 2, 0);
    poly_point(&p, 0, 2, 0);
    poly_point(&p, 1, 1, 3);
    int b[4] = {0, 3, 2, 1};
    poly_face(&p, 4, b);
    for (int i = 0; i < 4; i++) {
        int s[3] = {i, (i + 1) % 4, 4};
        poly_face(&p, 3, s);
    }
    double C[3] = {1, 1, 0.75};
    CHECK_POLY(&p, 4, C, 3);
}

TEST(triangular_prism)
{
    /* right triangle with legs 1, 1, height 2: V = 1, C = (1/3, 1/3, 1) */
    Poly p;
    double x[3] = {0, 1, 0}, y[3] = {0, 0, 1};
    poly_extrude(&p, 3, x, y, 0, 2);
    double C[3] = {1.0 / 3, 1.0 / 3, 1};
    CHECK_POLY(&p, 1, C, 2);
}

TEST(hexagonal_prism)
{
    /* regular hexagon of circumradius 1 centred at (3, -2), height 0.5.
       Its y coordinates -2 +- sqrt(3)/2 are rounded when stored, so use
       the stored half-heights hu, hl (exact differences: Sterbenz): the
       upper and lower trapezoids (widths 2 and 1) have areas 1.5 hu and
       1.5 hl and centroids 4h/9 from the wide side. */
    Poly p;
    double s = sqrt(3.0) / 2;
    double x[6] = {4, 3.5, 2.5, 2, 2.5, 3.5}, y[6] = {-2, -2 + s, -2 + s, -2, -2 - s, -2 - s};
    poly_extrude(&p, 6, x, y, 1, 1.5);
    double hu = y[1] - y[0], hl = y[0] - y[4];
    double C[3] = {3, -2 + 4.0 / 9 * (hu - hl), 1.25};
    CHECK_POLY(&p, 1.5 * (hu + hl) * 0.5, C, 2);
}

TEST(l_shaped_prism)
{
    /* the L of nonconvex_face, extruded from z = 0 to 1: V = 5,
       C = (1.1, 1.1, 0.5); the estimate point d lies outside the cell */
    Poly p;
    double x[6] = {0, 3, 3, 1, 1, 0}, y[6] = {0, 0, 1, 1, 3, 3};
    poly_extrude(&p, 6, x, y, 0, 1);
    double C[3] = {1.1, 1.1, 0.5};
    CHECK_POLY(&p, 5, C, 3);
}

TEST(split_faces)
{
    /* A 2 x 1 x 1 box whose top face is split at x = 0.3 into two quads,
       as a cut cell's face is split by its neighbours; the front and
       back faces then carry the hanging points as pentagons. */
    Poly p;
    poly_init(&p);
    poly_point(&p, 0, 0, 0);   /* 0 */
    poly_point(&p, 2, 0, 0);   /* 1 */
    poly_point(&p, 2, 1, 0);   /* 2 */
    poly_point(&p, 0, 1, 0);   /* 3 */
    poly_point(&p, 0, 0, 1);   /* 4 */
    poly_point(&p, 2, 0, 1);   /* 5 */
    poly_point(&p, 2, 1, 1);   /* 6 */
    poly_point(&p, 0, 1, 1);   /* 7 */
    poly_point(&p, 0.3, 0, 1); /* 8 */
    poly_point(&p, 0.3, 1, 1); /* 9 */
    int bottom[4] = {0, 3, 2, 1};
    int top1[4] = {4, 8, 9, 7}, top2[4] = {8, 5, 6, 9};
    int front[5] = {0, 1, 5, 8, 4}, back[5] = {2, 3, 7, 9, 6};
    int right[4] = {1, 2, 6, 5}, left[4] = {3, 0, 4, 7};
    poly_face(&p, 4, bottom);
    poly_face(&p, 4, top1);
    poly_face(&p, 4, top2);
    poly_face(&p, 5, front);
    poly_face(&p, 5, back);
    poly_face(&p, 4, right);
    poly_face(&p, 4, left);
    double C[3] = {1, 0.5, 0.5};
    CHECK_POLY(&p, 2, C, 2);
}

TEST(mixed_flip)
{
    /* the same cube with half of its faces stored reversed and flagged */
    Poly p;
    double x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 1, 1};
    poly_extrude(&p, 4, x, y, 0, 1);
    double Sf[18], Cf[18];
    int faces[6] = {0, 1, 2, 3, 4, 5};
    char flip[6] = {0, 1, 0, 1, 1, 0};
    for (int f = 0; f < 6; f++) {
        if (flip[f]) {
            int a = p.off[f], b = p.off[f + 1] - 1;
            while (a < b) {
                int t = p.idx[a];
                p.idx[a++] = p.idx[b];
                p.idx[b--] = t;
            }
        }
        geom_face(p.pts, p.idx + p.off[f], 4, Sf + 3 * f, Cf + 3 * f);
    }
    double V, C[3];
    geom_cell(p.pts, p.off, p.idx, faces, flip, 6, Sf, Cf, &V, C);
    NEAR(V, 1, TOL);
    for (int k = 0; k < 3; k++) NEAR(C[k], 0.5, TOL);
}

int main(void)
{
    RUN(triangle_face);
    RUN(nonconvex_face);
    RUN(warped_face_is_openfoam_rule);
    RUN(degenerate_face);
    RUN(unit_cube);
    RUN(rotated_box);
    RUN(tetrahedron);
    RUN(square_pyramid);
    RUN(triangular_prism);
    RUN(hexagonal_prism);
    RUN(l_shaped_prism);
    RUN(split_faces);
    RUN(mixed_flip);
    return test_summary();
}
