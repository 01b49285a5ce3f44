/*
** test_quality.c: quality measures on a hand-made two-cell mesh whose
** angles are known in closed form, and the checks that find broken cells.
**
** Cell A is the unit cube; cell B shares A's face x = 1 and is the
** parallelepiped whose far face x = 2 is shifted by s along y.  Then
**   centre of B = (1.5, 0.5 + s/2, 0.5), d = (1, s/2, 0), S = (1, 0, 0):
**   non-orthogonality = atan(s/2);
**   skewness: internal face s/2, B's far face s, B's slanted faces
**   s/(1+s^2)  (OpenFOAM's normalisation, fd = 0.5 for s <= 4);
**   aspect ratio of B = (2 + 2s)/2 = 1 + s (> 1 + s/3, the 3-D term).
*/
#include <math.h>
#include <string.h>

#include "mem.h"
#include "mesh.h"
#include "quality.h"
#include "test.h"

#define PI 3.14159265358979323846

static void two_cells(Mesh *m, double s, double xfar)
{
    const double P[12][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1},
                             {0, 1, 1}, {1, 1, 1}, {xfar, s, 0}, {xfar, 1 + s, 0}, {xfar, s, 1},
                             {xfar, 1 + s, 1}};
    static const int F[11][4] = {
        {1, 3, 7, 5},                                                              /* internal */
        {0, 4, 6, 2}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6},      /* A */
        {8, 9, 11, 10}, {1, 8, 10, 5}, {3, 7, 11, 9}, {1, 3, 9, 8}, {5, 10, 11, 7}  /* B */
    };
    static const int own[11] = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
    mesh_init(m);
    m->npoints = 12;
    m->nfaces = 11;
    m->ninternal = 1;
    m->ncells = 2;
    m->points = mem_alloc(sizeof P);
    memcpy(m->points, P, sizeof P);
    m->face_off = mem_alloc(sizeof(int) * 12);
    m->face_idx = mem_alloc(sizeof F);
    for (int f = 0; f <= 11; f++) m->face_off[f] = 4 * f;
    memcpy(m->face_idx, F, sizeof F);
    m->owner = mem_alloc(sizeof own);
    memcpy(m->owner, own, sizeof own);
    m->neighbour = mem_alloc(sizeof(int));
    m->neighbour[0] = 1;
    m->npatches = 1;
    m->patches = MEM_NEW(Patch, 1);
    m->patches[0].name = mem_strdup("walls");
    m->patches[0].type = mem_strdup("wall");
    m->patches[0].start = 1;
    m->patches[0].size = 10;
}

static void with_parents(Mesh *m)
{
    static const double x[] = {0, 1, 2}, y[] = {0, 1}, z[] = {0, 1};
    const double *ax[3] = {x, y, z};
    for (int k = 0; k < 3; k++) {
        m->cart.n[k] = k ? 1 : 2;
        m->cart.x[k] = mem_alloc(sizeof(double) * (size_t)(m->cart.n[k] + 1));
        memcpy(m->cart.x[k], ax[k], sizeof(double) * (size_t)(m->cart.n[k] + 1));
    }
    m->cell_parent = mem_alloc(2 * sizeof(int));
    m->cell_parent[0] = 0;
    m->cell_parent[1] = 1;
}

TEST(skewed_angles)
{
    const double ss[] = {0.5, 1, 2};
    for (int i = 0; i < 3; i++) {
        double s = ss[i];
        Mesh m;
        Quality q;
        Err e;
        two_cells(&m, s, 2);
        quality_measure(&m, &q);
        NEAR(m.cell_centre[4], 0.5 + s / 2, 1e-15);
        NEAR(q.nonorth_max, atan(s / 2) * 180 / PI, 1e-12);
        NEAR(q.nonorth_avg, atan(s / 2) * 180 / PI, 1e-12);
        EXPECT(q.nonorth_face == 0 && q.nnonorth == 0, "nonorth face %d count %d", q.nonorth_face, q.nnonorth);
        NEAR(quality_skewness(&m, 0, m.cell_centre, m.cell_centre + 3), s / 2, 1e-14);
        NEAR(quality_boundary_skewness(&m, 6, m.cell_centre + 3), s, 1e-14);
        NEAR(quality_boundary_skewness(&m, 7, m.cell_centre + 3), s / (1 + s * s), 1e-14);
        NEAR(quality_boundary_skewness(&m, 1, m.cell_centre), 0, 1e-15);
        NEAR(q.skew_max, s, 1e-14);
        EXPECT(q.skew_face == 6, "skew face %d", q.skew_face);
        NEAR(q.aspect_max, 1 + s, 1e-14);
        EXPECT(q.aspect_cell == 1, "aspect cell %d", q.aspect_cell);
        NEAR(q.vol_total, 2, 1e-14);
        NEAR(q.open_max, 0, 1e-15);
        EXPECT(q.ndims == 3 && !q.has_parent && q.ncut == 0 && q.nmerged == 0, "dims/parents");
        EXPECT(!quality_check(&m, &q, NULL, &e), "check: %s", e.msg);
        mesh_free(&m);
    }
}

/* d . S = 0 exactly: a 90-degree face, counted severe, orientation error. */
TEST(severe)
{
    Mesh m;
    Quality q;
    two_cells(&m, 3, 2);
    quality_measure(&m, &q);
    NEAR(q.nonorth_max, atan(1.5) * 180 / PI, 1e-12);
    EXPECT(q.nnonorth == 0, "56 deg counted severe");
    mesh_free(&m);
    two_cells(&m, 6, 2);
    quality_measure(&m, &q);
    NEAR(q.nonorth_max, atan(3.0) * 180 / PI, 1e-12);
    EXPECT(q.nnonorth == 1, "71.6 deg not counted severe (%d)", q.nnonorth);
    mesh_free(&m);
}

TEST(parents)
{
    Mesh m;
    Quality q;
    two_cells(&m, 1, 2);
    with_parents(&m);
    quality_measure(&m, &q);
    EXPECT(q.has_parent && q.ncut == 0 && q.nmerged == 1, "cut %d merged %d", q.ncut, q.nmerged);
    NEAR(q.frac_min, 1, 1e-14);
    mesh_free(&m);
    two_cells(&m, 0, 1.25);
    with_parents(&m);
    quality_measure(&m, &q);
    EXPECT(q.ncut == 1 && q.nmerged == 0, "cut %d merged %d", q.ncut, q.nmerged);
    NEAR(q.vol_min, 0.25, 1e-15);
    EXPECT(q.vol_min_cell == 1, "min cell %d", q.vol_min_cell);
    NEAR(q.vol_min_ratio, 0.25, 1e-15);
    NEAR(q.vol_max_ratio, 1, 1e-15);
    NEAR(q.frac_min, 0.25, 1e-15);
    NEAR(q.frac_max, 1, 1e-15);
    mesh_free(&m);
}

static void reverse_face(Mesh *m, int f)
{
    int *p = m->face_idx + m->face_off[f], n = m->face_off[f + 1] - m->face_off[f];
    for (int i = 0; i < n / 2; i++) {
        int t = p[i];
        p[i] = p[n - 1 - i];
        p[n - 1 - i] = t;
    }
}

TEST(broken)
{
    Mesh m;
    Quality q;
    Err e;
    int nf;
    two_cells(&m, 1, 2);
    reverse_face(&m, 8);   /* B's top face flipped */
    quality_measure(&m, &q);
    EXPECT(quality_check(&m, &q, &nf, &e) == -1, "flipped face passes");
    CONTAINS(e.msg, "cell 1: not closed, |sum S| = ");
    EXPECT(q.nopen == 1 && q.norient == 1 && q.orient_face == 8, "open %d orient %d face %d", q.nopen,
           q.norient, q.orient_face);
    mesh_free(&m);

    /* every face of A flipped (B removed): closed, but inside out */
    two_cells(&m, 0, 2);
    for (int f = 0; f < 6; f++) reverse_face(&m, f);
    m.ninternal = 0;
    m.nfaces = 6;
    m.ncells = 1;
    m.patches[0].start = 0;
    m.patches[0].size = 6;
    quality_measure(&m, &q);
    EXPECT(quality_check(&m, &q, &nf, &e) == -1, "inside-out cell passes");
    CONTAINS(e.msg, "cell 0: face 0 points into the cell");
    EXPECT(q.nopen == 0 && q.norient == 6 && q.nnegvol == 1 && nf >= 2, "open %d orient %d neg %d nf %d",
           q.nopen, q.norient, q.nnegvol, nf);
    NEAR(q.vol_total, -1, 1e-15);
    mesh_free(&m);
}

/* OpenFOAM's geometry on a prism whose cross-section is the chevron
   (0,0) (6,0) (6,6) (3,1) (0,6), area 21, extruded over 0 <= z <= 1.  The
   chevron is not star-shaped about its point average m = (3, 2.6): the
   fan triangles (6,6) (3,1) m and (3,1) (0,6) m fold back.  By hand, in
   exact fractions:
     exact centroid of the chevron          (3, 43/21)
     OpenFOAM's centre (weights |n_i|)      (3, 1843/765)
     OpenFOAM's cell centre of the prism    (3, 11449/5355, 1/2)
       (c_e = mean of the 7 face centres; pyramid centres 3/4 C_f + 1/4 c_e
       weighted by S_f.(C_f - c_e); the side rectangles' centres are their
       point averages)
     boundary skewness of the top face      1452/19229
       (C_f - C_P = (0, 1452/5355, 1/2); the normal part is d, the rest is
       sv = (0, 1452/5355, 0); fd = 6 - 1843/765 = 19229/5355, the top
       face's extent in y from its centre) */
static void chevron_prism(Mesh *m)
{
    static const double xy[5][2] = {{0, 0}, {6, 0}, {6, 6}, {3, 1}, {0, 6}};
    mesh_init(m);
    m->npoints = 10;
    m->points = mem_alloc(30 * sizeof(double));
    for (int i = 0; i < 10; i++) {
        m->points[3 * i] = xy[i % 5][0];
        m->points[3 * i + 1] = xy[i % 5][1];
        m->points[3 * i + 2] = i / 5;
    }
    m->nfaces = 7;
    m->ncells = 1;
    m->face_off = mem_alloc(8 * sizeof(int));
    m->face_idx = mem_alloc(30 * sizeof(int));
    int n = 0;
    m->face_off[0] = 0;
    for (int i = 4; i >= 0; i--) m->face_idx[n++] = i;   /* bottom, outward -z */
    m->face_off[1] = n;
    for (int i = 0; i < 5; i++) m->face_idx[n++] = 5 + i;   /* top */
    m->face_off[2] = n;
    for (int i = 0; i < 5; i++) {
        int j = (i + 1) % 5;
        m->face_idx[n++] = i;
        m->face_idx[n++] = j;
        m->face_idx[n++] = 5 + j;
        m->face_idx[n++] = 5 + i;
        m->face_off[3 + i] = n;
    }
    m->owner = MEM_NEW(int, 7);
    m->npatches = 1;
    m->patches = MEM_NEW(Patch, 1);
    m->patches[0].name = mem_strdup("walls");
    m->patches[0].type = mem_strdup("wall");
    m->patches[0].size = 7;
}

TEST(foam_geometry_nonconvex)
{
    Mesh m;
    chevron_prism(&m);
    double S[3], C[3], fS[21], fC[21], cc[3], sk[7];
    quality_foam_face(m.points, m.face_idx + m.face_off[1], 5, S, C);
    NEAR(S[0], 0, 1e-15);
    NEAR(S[1], 0, 1e-15);
    NEAR(S[2], 21, 1e-13);
    NEAR(C[0], 3, 1e-15);
    NEAR(C[1], 1843.0 / 765, 1e-14);
    NEAR(C[2], 1, 1e-15);
    quality_foam_geometry(&m, fS, fC, cc);
    NEAR(cc[0], 3, 1e-14);
    NEAR(cc[1], 11449.0 / 5355, 1e-14);
    NEAR(cc[2], 0.5, 1e-14);
    quality_face_measures(&m, sk, NULL);
    NEAR(sk[1], 1452.0 / 19229, 1e-14);
    Quality q;
    quality_measure(&m, &q);
    /* the exact geometry is unchanged: the centroid, not OpenFOAM's centre */
    NEAR(m.face_centre[4], 43.0 / 21, 1e-14);
    NEAR(m.cell_centre[1], 43.0 / 21, 1e-14);
    NEAR(q.vol_total, 21, 1e-13);
    EXPECT(q.skew_max >= 1452.0 / 19229 - 1e-14, "max skewness %.17g", q.skew_max);
    /* quality_foam_cell from the faces gives the mesh-wide centre */
    double SC[42], c1[3];
    signed char sg[7];
    for (int f = 0; f < 7; f++) {
        memcpy(SC + 6 * f, fS + 3 * f, 3 * sizeof(double));
        memcpy(SC + 6 * f + 3, fC + 3 * f, 3 * sizeof(double));
        sg[f] = 1;
    }
    quality_foam_cell(7, SC, sg, c1);
    for (int k = 0; k < 3; k++) NEAR(c1[k], cc[k], 1e-15);
    mesh_free(&m);
}

/* A warped quadrilateral (0,0,0) (1,0,0) (1,1,1) (0,1,0): point average
   m = (1/2, 1/2, 1/4); the two fan triangles at the origin have
   |n| = sqrt5/4, the two at the lifted corner 3/4, and the corner sums
   about m of the first pair add up to -(1, 1, 1), of the second to
   +(1, 1, 1), so OpenFOAM's centre is
   m + (3/4 - sqrt5/4) / (3 (2 sqrt5/4 + 2 3/4)) (1, 1, 1)
     = m + (3 - sqrt5) / (6 (3 + sqrt5)) (1, 1, 1),
   and S = (-1/2, -1/2, 1). */
TEST(foam_face_warped)
{
    const double P[12] = {0, 0, 0, 1, 0, 0, 1, 1, 1, 0, 1, 0};
    const int idx[4] = {0, 1, 2, 3};
    double S[3], C[3], t = (3 - sqrt(5.0)) / (6 * (3 + sqrt(5.0)));
    quality_foam_face(P, idx, 4, S, C);
    NEAR(S[0], -0.5, 1e-15);
    NEAR(S[1], -0.5, 1e-15);
    NEAR(S[2], 1, 1e-15);
    NEAR(C[0], 0.5 + t, 1e-15);
    NEAR(C[1], 0.5 + t, 1e-15);
    NEAR(C[2], 0.25 + t, 1e-15);
}

int main(void)
{
    RUN(skewed_angles);
    RUN(severe);
    RUN(parents);
    RUN(broken);
    RUN(foam_geometry_nonconvex);
    RUN(foam_face_warped);
    return test_summary();
}
