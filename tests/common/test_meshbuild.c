/*
** test_meshbuild.c: meshbuild rebuilds a graded block mesh exactly from
** its faces fed in shuffled order with random orientation, and reports
** malformed input.
**
** The block mesh (fixture.h) is in OpenFOAM's order, and its internal
** faces have distinct (owner, neighbour) pairs, so the rebuilt mesh must
** equal it array for array: the same points (all used, added in order),
** face lists, owners, neighbours and patch ranges.  Internal faces given
** from the other side have their point order reversed by the caller, and
** the builder must reverse them back, which gives the identical list.
** Boundary faces must keep their order of addition inside a patch, so the
** shuffle keeps each patch's faces in their original relative order.
*/
#include "fixture.h"
#include "mem.h"
#include "meshbuild.h"
#include "quality.h"
#include "test.h"

/* xorshift, state kept by the caller */
static unsigned rnd(unsigned *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void graded_block(Mesh *m, int nx, int ny, int nz)
{
    int n[3] = {nx, ny, nz};
    double *x[3];
    for (int k = 0; k < 3; k++) {
        x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        for (int i = 0; i <= n[k]; i++) x[k][i] = -1.0 + 0.3 * k + i * (1.0 + 0.05 * i) / (k + 1);
    }
    fixture_mesh(m, x, n);
    for (int k = 0; k < 3; k++) free(x[k]);
}

/* Added-order permutation of m's faces: a random shuffle in which the
   boundary faces of each patch keep their relative order. */
static int *shuffled_faces(const Mesh *m, unsigned *seed)
{
    int nf = m->nfaces;
    int *perm = mem_alloc(sizeof(int) * (size_t)nf);
    for (int f = 0; f < nf; f++) perm[f] = f;
    for (int f = nf - 1; f > 0; f--) {
        int j = (int)(rnd(seed) % (unsigned)(f + 1)), t = perm[f];
        perm[f] = perm[j];
        perm[j] = t;
    }
    for (int p = 0; p < m->npatches; p++) {
        int next = m->patches[p].start;
        for (int s = 0; s < nf; s++) {
            int f = perm[s];
            if (f >= m->patches[p].start && f < m->patches[p].start + m->patches[p].size) perm[s] = next++;
        }
    }
    return perm;
}

/* Feeds m's faces to b in the order perm, internal faces flipped at
   random; returns the number of flipped faces. */
static int feed(MeshBuild *b, const Mesh *m, const int *perm, unsigned *seed)
{
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        EXPECT(meshbuild_patch(b, pa->name, pa->type, pa->neighbour, pa->groups) == p, "patch %d", p);
    }
    for (int i = 0; i < m->npoints; i++) meshbuild_point(b, m->points + 3 * i);
    int nflip = 0, pts[16];
    for (int s = 0; s < m->nfaces; s++) {
        int f = perm[s], n = m->face_off[f + 1] - m->face_off[f];
        const int *idx = m->face_idx + m->face_off[f];
        int id;
        if (f < m->ninternal && rnd(seed) % 2) {
            for (int k = 0; k < n; k++) pts[k] = idx[n - 1 - k];
            id = meshbuild_face(b, pts, n, m->neighbour[f], m->owner[f], -1);
            nflip++;
        } else if (f < m->ninternal) {
            id = meshbuild_face(b, idx, n, m->owner[f], m->neighbour[f], -1);
        } else {
            id = meshbuild_face(b, idx, n, m->owner[f], -1, mesh_face_patch(m, f));
        }
        EXPECT(id == s, "face %d added as %d", s, id);
    }
    return nflip;
}

static void expect_same(const Mesh *a, const Mesh *b)
{
    EXPECT(a->npoints == b->npoints && a->nfaces == b->nfaces && a->ninternal == b->ninternal &&
               a->ncells == b->ncells && a->npatches == b->npatches,
           "sizes %d %d %d %d vs %d %d %d %d", a->npoints, a->nfaces, a->ninternal, a->ncells, b->npoints,
           b->nfaces, b->ninternal, b->ncells);
    if (test_failed_now) return;
    EXPECT(!memcmp(a->points, b->points, sizeof(double) * 3 * (size_t)a->npoints), "points differ");
    EXPECT(!memcmp(a->face_off, b->face_off, sizeof(int) * ((size_t)a->nfaces + 1)), "face sizes differ");
    EXPECT(!memcmp(a->face_idx, b->face_idx, sizeof(int) * (size_t)a->face_off[a->nfaces]), "face points differ");
    EXPECT(!memcmp(a->owner, b->owner, sizeof(int) * (size_t)a->nfaces), "owners differ");
    EXPECT(!memcmp(a->neighbour, b->neighbour, sizeof(int) * (size_t)a->ninternal), "neighbours differ");
    for (int p = 0; p < a->npatches; p++) {
        const Patch *x = &a->patches[p], *y = &b->patches[p];
        EXPECT(!strcmp(x->name, y->name) && !strcmp(x->type, y->type) && x->start == y->start &&
                   x->size == y->size,
               "patch %d: %s %s %d %d vs %s %s %d %d", p, x->name, x->type, x->start, x->size, y->name,
               y->type, y->start, y->size);
    }
}

static void rebuild(int nx, int ny, int nz, unsigned seed)
{
    Mesh m, r;
    Err e;
    MeshBuild b;
    graded_block(&m, nx, ny, nz);
    int *perm = shuffled_faces(&m, &seed);
    meshbuild_init(&b);
    int nflip = feed(&b, &m, perm, &seed);
    EXPECT(nflip > m.ninternal / 3 && nflip < 2 * m.ninternal / 3 + 1, "%d of %d flipped", nflip, m.ninternal);
    int *fmap = mem_alloc(sizeof(int) * (size_t)m.nfaces);
    int *pmap = mem_alloc(sizeof(int) * (size_t)m.npoints);
    mesh_init(&r);
    EXPECT(meshbuild_finish(&b, &r, fmap, pmap, &e) == 0, "%s", e.msg);
    EXPECT(b.nfaces == 0 && b.npoints == 0 && b.face_idx == NULL, "builder not emptied");
    expect_same(&m, &r);
    for (int s = 0; s < m.nfaces; s++) EXPECT(fmap[s] == perm[s], "face_map[%d] = %d, expected %d", s, fmap[s], perm[s]);
    for (int i = 0; i < m.npoints; i++) EXPECT(pmap[i] == i, "point_map[%d] = %d", i, pmap[i]);
    EXPECT(mesh_check(&r, &e) == 0, "%s", e.msg);
    Quality q;
    quality_measure(&r, &q);
    EXPECT(quality_check(&r, &q, NULL, &e) == 0, "%s", e.msg);
    EXPECT(q.nopen == 0 && q.open_max <= 1e-14, "open cells %d, max %g", q.nopen, q.open_max);
    for (int c = 0; c < r.ncells; c++) NEAR(r.cell_vol[c], m.cell_vol[c], 1e-15 * m.cell_vol[c]);
    free(perm);
    free(fmap);
    free(pmap);
    mesh_free(&m);
    mesh_free(&r);
}

TEST(rebuild_small) { rebuild(3, 2, 4, 12345u); }
TEST(rebuild_2d_slab) { rebuild(7, 5, 1, 777u); }
TEST(rebuild_large) { rebuild(40, 30, 20, 99u); }

/* Two faces between cells 0 and 1 (a merged pair), added in the order
   B, A: they must stay in that order; an unused point is dropped; faces
   of patches added out of patch order come out grouped. */
TEST(ties_and_unused_points)
{
    /* cells: 0 = [0,1]^3; 1 = [1,2]x[0,1]^2 split face x=1 in two halves */
    static const double P[] = {
        0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1,   /* 0..7 cube */
        2, 0, 0, 2, 1, 0, 2, 0, 1, 2, 1, 1,                                         /* 8..11 */
        1, 0.5, 0, 1, 0.5, 1,                                                       /* 12,13 split */
        9, 9, 9                                                                     /* 14 unused */
    };
    MeshBuild b;
    Mesh m;
    Err e;
    meshbuild_init(&b);
    int wall = meshbuild_patch(&b, "walls", "wall", NULL, NULL);
    int top = meshbuild_patch(&b, "top", "patch", NULL, NULL);
    for (int i = 0; i < 15; i++) meshbuild_point(&b, P + 3 * i);
    const int upperhalf[] = {12, 3, 7, 13}, lowerhalf[] = {1, 12, 13, 5};
    const int ztop0[] = {4, 5, 13, 7, 6}, ztop1[] = {5, 10, 11, 7, 13};
    const int xmin[] = {0, 4, 6, 2}, ylo0[] = {0, 1, 5, 4}, yhi0[] = {2, 6, 7, 3}, zlo0[] = {0, 2, 3, 12, 1};
    const int xmax[] = {8, 9, 11, 10}, ylo1[] = {1, 8, 10, 5}, yhi1[] = {3, 7, 11, 9}, zlo1[] = {1, 12, 3, 9, 8};
    meshbuild_face(&b, ztop1, 5, 1, -1, top);
    meshbuild_face(&b, upperhalf, 4, 0, 1, -1);    /* B */
    meshbuild_face(&b, xmin, 4, 0, -1, wall);
    int rev[4];                                    /* lowerhalf given from cell 1 */
    for (int k = 0; k < 4; k++) rev[k] = lowerhalf[3 - k];
    meshbuild_face(&b, rev, 4, 1, 0, -1);          /* A */
    meshbuild_face(&b, ylo0, 4, 0, -1, wall);
    meshbuild_face(&b, ztop0, 5, 0, -1, top);
    meshbuild_face(&b, yhi0, 4, 0, -1, wall);
    meshbuild_face(&b, zlo0, 5, 0, -1, wall);
    meshbuild_face(&b, xmax, 4, 1, -1, wall);
    meshbuild_face(&b, ylo1, 4, 1, -1, wall);
    meshbuild_face(&b, yhi1, 4, 1, -1, wall);
    meshbuild_face(&b, zlo1, 5, 1, -1, wall);
    int fmap[12], pmap[15];
    mesh_init(&m);
    EXPECT(meshbuild_finish(&b, &m, fmap, pmap, &e) == 0, "%s", e.msg);
    EXPECT(m.ncells == 2 && m.ninternal == 2 && m.nfaces == 12 && m.npoints == 14, "sizes %d %d %d %d", m.ncells,
           m.ninternal, m.nfaces, m.npoints);
    EXPECT(fmap[1] == 0 && fmap[3] == 1, "internal faces at %d %d", fmap[1], fmap[3]);
    EXPECT(m.face_idx[4] == 1 && m.face_idx[5] == 12 && m.face_idx[6] == 13 && m.face_idx[7] == 5,
           "second internal face not reversed back");
    EXPECT(pmap[14] == -1 && pmap[13] == 13, "point_map %d %d", pmap[14], pmap[13]);
    EXPECT(m.patches[0].start == 2 && m.patches[0].size == 8 && m.patches[1].start == 10 && m.patches[1].size == 2,
           "patches %d+%d %d+%d", m.patches[0].start, m.patches[0].size, m.patches[1].start, m.patches[1].size);
    EXPECT(fmap[0] == 10 && fmap[5] == 11 && fmap[2] == 2 && fmap[11] == 9, "boundary order %d %d %d %d", fmap[0],
           fmap[5], fmap[2], fmap[11]);
    EXPECT(mesh_check(&m, &e) == 0, "%s", e.msg);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    EXPECT(mesh_check(&m, &e) == 0, "%s", e.msg);
    NEAR(m.cell_vol[0], 1, 1e-15);
    NEAR(m.cell_vol[1], 1, 1e-15);
    NEAR(m.cell_centre[3], 1.5, 1e-15);
    mesh_free(&m);
}

static void expect_fail(MeshBuild *b, const char *msg)
{
    Mesh m;
    Err e;
    mesh_init(&m);
    EXPECT(meshbuild_finish(b, &m, NULL, NULL, &e) == -1, "accepted, expected \"%s\"", msg);
    CONTAINS(e.msg, msg);
    EXPECT(b->nfaces == 0 && b->patches == NULL, "builder not emptied after failure");
    mesh_free(&m);
}

TEST(bad_input)
{
    static const double P[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int tri[] = {0, 1, 2}, bad[] = {0, 1, 7};
    MeshBuild b;

    meshbuild_init(&b);
    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_patch(&b, "w", "wall", NULL, NULL);
    meshbuild_face(&b, tri, 2, 0, -1, 0);
    expect_fail(&b, "meshbuild: face 0 has 2 points (at least 3 needed)");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_patch(&b, "w", "wall", NULL, NULL);
    meshbuild_face(&b, tri, 3, 0, -1, 0);
    meshbuild_face(&b, tri, 3, 2, -1, 0);
    expect_fail(&b, "meshbuild: cell 1 has no face");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_face(&b, tri, 3, 0, -1, 3);
    expect_fail(&b, "meshbuild: face 0: patch 3 out of range 0..-1");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_face(&b, bad, 3, 0, 1, -1);
    expect_fail(&b, "meshbuild: face 0: point 7 out of range 0..3");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_face(&b, tri, 3, 1, 1, -1);
    expect_fail(&b, "meshbuild: face 0 has cell 1 on both sides");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_face(&b, tri, 3, 0, -1, -1);
    expect_fail(&b, "meshbuild: face 0: boundary face without a patch");

    for (int i = 0; i < 4; i++) meshbuild_point(&b, P + 3 * i);
    meshbuild_face(&b, tri, 3, -2, -1, 0);
    expect_fail(&b, "meshbuild: face 0: cell -2 is negative");
    meshbuild_free(&b);
}

int main(void)
{
    RUN(rebuild_small);
    RUN(rebuild_2d_slab);
    RUN(rebuild_large);
    RUN(ties_and_unused_points);
    RUN(bad_input);
    return test_summary();
}
