/*
** test_mesh.c: polyMesh round trips (ascii, binary, gzip, stream), the
** reader's error messages, mesh_check's invariants, geometry of a graded
** box, 2-D detection, and OpenFOAM's own cavity mesh when blockMesh is
** installed.
**
** The meshes are built here by a small hex-grid builder that follows
** OpenFOAM's ordering (internal faces upper-triangular, normals out of the
** owner, patches xmin xmax ymin ymax zmin zmax or, in 2-D, the four sides
** and one empty frontAndBack patch).
*/
#include "buf.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"
#include "test.h"

#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- builder ---- */

typedef struct Grid {
    int n[3];
    double *x[3];
} Grid;

static int gp(const Grid *g, int i, int j, int k)
{
    return i + (g->n[0] + 1) * (j + (g->n[1] + 1) * k);
}

static int gc(const Grid *g, int i, int j, int k)
{
    return i + g->n[0] * (j + g->n[1] * k);
}

typedef struct Builder {
    Mesh *m;
    int nf, ni;
    int *cnt; /* faces per patch-slot while counting */
} Builder;

/* The quad of the face normal to axis a at point (i, j, k), oriented
   along +a (cyclic order of the two other axes). */
static void quad(const Grid *g, int a, int i, int j, int k, int q[4])
{
    int b = (a + 1) % 3, c = (a + 2) % 3;
    int p[3] = {i, j, k};
    int ub[3] = {0, 0, 0}, uc[3] = {0, 0, 0};
    ub[b] = 1;
    uc[c] = 1;
    q[0] = gp(g, p[0], p[1], p[2]);
    q[1] = gp(g, p[0] + ub[0], p[1] + ub[1], p[2] + ub[2]);
    q[2] = gp(g, p[0] + ub[0] + uc[0], p[1] + ub[1] + uc[1], p[2] + ub[2] + uc[2]);
    q[3] = gp(g, p[0] + uc[0], p[1] + uc[1], p[2] + uc[2]);
}

static void add_face(Mesh *m, int *f, const int q[4], int reverse, int own, int nei)
{
    int o = m->face_off[*f];
    for (int t = 0; t < 4; t++) m->face_idx[o + t] = reverse ? q[3 - t] : q[t];
    m->face_off[*f + 1] = o + 4;
    m->owner[*f] = own;
    if (nei >= 0) m->neighbour[*f] = nei;
    (*f)++;
}

static void set_patch(Patch *p, const char *name, const char *type, int start, int size)
{
    p->name = mem_strdup(name);
    p->type = mem_strdup(type);
    p->start = start;
    p->size = size;
    p->neighbour = NULL;
    p->groups = NULL;
}

/* Hex grid over the given axis coordinates.  two_d: the z sides form one
   empty patch "frontAndBack". */
static void build(Mesh *m, const Grid *g, int two_d)
{
    mesh_init(m);
    int nx = g->n[0], ny = g->n[1], nz = g->n[2];
    m->npoints = (nx + 1) * (ny + 1) * (nz + 1);
    m->ncells = nx * ny * nz;
    m->ninternal = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
    m->nfaces = m->ninternal + 2 * (ny * nz + nx * nz + nx * ny);
    size_t np3 = 3 * (size_t)m->npoints, nidx = 4 * (size_t)m->nfaces;
    m->points = MEM_NEW(double, np3);
    for (int k = 0; k <= nz; k++)
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++) {
                double *p = m->points + 3 * gp(g, i, j, k);
                p[0] = g->x[0][i];
                p[1] = g->x[1][j];
                p[2] = g->x[2][k];
            }
    m->face_off = MEM_NEW(int, m->nfaces + 1);
    m->face_idx = MEM_NEW(int, nidx);
    m->owner = MEM_NEW(int, m->nfaces);
    m->neighbour = MEM_NEW(int, m->ninternal);
    int f = 0, q[4];
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                int c = gc(g, i, j, k);
                if (i + 1 < nx) quad(g, 0, i + 1, j, k, q), add_face(m, &f, q, 0, c, gc(g, i + 1, j, k));
                if (j + 1 < ny) quad(g, 1, i, j + 1, k, q), add_face(m, &f, q, 0, c, gc(g, i, j + 1, k));
                if (k + 1 < nz) quad(g, 2, i, j, k + 1, q), add_face(m, &f, q, 0, c, gc(g, i, j, k + 1));
            }
    static const char *names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    static const char *types[6] = {"wall", "patch", "symmetryPlane", "wall", "wall", "patch"};
    m->npatches = two_d ? 5 : 6;
    m->patches = MEM_NEW(Patch, 6);
    for (int s = 0; s < 6; s++) {
        int a = s / 2, hi = s % 2, b = (a + 1) % 3, c = (a + 2) % 3;
        int start = f;
        for (int u = 0; u < g->n[c]; u++)
            for (int v = 0; v < g->n[b]; v++) {
                int ijk[3];
                ijk[a] = hi ? g->n[a] : 0;
                ijk[b] = v;
                ijk[c] = u;
                quad(g, a, ijk[0], ijk[1], ijk[2], q);
                int cl[3] = {ijk[0], ijk[1], ijk[2]};
                if (hi) cl[a]--;
                add_face(m, &f, q, !hi, gc(g, cl[0], cl[1], cl[2]), -1);
            }
        if (two_d && s == 5)
            m->patches[4].size += f - start;
        else if (two_d && s == 4)
            set_patch(&m->patches[4], "frontAndBack", "empty", start, f - start);
        else
            set_patch(&m->patches[s], names[s], types[s], start, f - start);
    }
}

static double xs[4] = {0, 0.25, 0.625, 1.5};
static double ys[3] = {-1, -0.5, 0.75};
static double zs[3] = {2, 2.125, 2.5};

static void build_small(Mesh *m)
{
    Grid g = {{3, 2, 2}, {xs, ys, zs}};
    build(m, &g, 0);
    free(m->patches[0].groups);
    m->patches[0].groups = mem_strdup("2(inlets wall)");
}

/* adds the Cartesian extras: the parent grid is the mesh itself */
static void add_extras(Mesh *m)
{
    double *ax[3] = {xs, ys, zs};
    int n[3] = {3, 2, 2};
    for (int k = 0; k < 3; k++) {
        m->cart.n[k] = n[k];
        m->cart.x[k] = MEM_NEW(double, n[k] + 1);
        memcpy(m->cart.x[k], ax[k], sizeof(double) * (size_t)(n[k] + 1));
    }
    m->cell_parent = MEM_NEW(int, m->ncells);
    for (int c = 0; c < m->ncells; c++) m->cell_parent[c] = c == 5 ? -1 : c;
    int nb = m->nfaces - m->ninternal;
    m->boundary_normal = MEM_NEW(double, 3 * nb);
    for (int i = 0; i < 3 * nb; i++) m->boundary_normal[i] = sin(0.37 * i + 0.1) / 3;
    m->nmerge_old = m->ncells + 3;
    m->merge_map = MEM_NEW(int, m->nmerge_old);
    for (int i = 0; i < m->nmerge_old; i++) m->merge_map[i] = i % m->ncells;
}

/* ---- comparison ---- */

static int same_str(const char *a, const char *b)
{
    return (!a && !b) || (a && b && strcmp(a, b) == 0);
}

/* Empty string when a and b are identical, else what differs. */
static const char *mesh_diff(const Mesh *a, const Mesh *b)
{
    static char why[256];
    why[0] = 0;
    if (a->npoints != b->npoints || a->nfaces != b->nfaces || a->ninternal != b->ninternal ||
        a->ncells != b->ncells || a->npatches != b->npatches)
        snprintf(why, sizeof why, "sizes differ: %d/%d points %d/%d faces %d/%d internal %d/%d cells %d/%d patches",
                 a->npoints, b->npoints, a->nfaces, b->nfaces, a->ninternal, b->ninternal, a->ncells, b->ncells,
                 a->npatches, b->npatches);
    else if (memcmp(a->points, b->points, sizeof(double) * 3 * (size_t)a->npoints))
        snprintf(why, sizeof why, "points differ");
    else if (memcmp(a->face_off, b->face_off, sizeof(int) * ((size_t)a->nfaces + 1)) ||
             memcmp(a->face_idx, b->face_idx, sizeof(int) * (size_t)a->face_off[a->nfaces]))
        snprintf(why, sizeof why, "faces differ");
    else if (memcmp(a->owner, b->owner, sizeof(int) * (size_t)a->nfaces))
        snprintf(why, sizeof why, "owner differs");
    else if (a->ninternal && memcmp(a->neighbour, b->neighbour, sizeof(int) * (size_t)a->ninternal))
        snprintf(why, sizeof why, "neighbour differs");
    for (int p = 0; !why[0] && p < a->npatches; p++) {
        const Patch *x = &a->patches[p], *y = &b->patches[p];
        if (!same_str(x->name, y->name) || !same_str(x->type, y->type) || x->start != y->start ||
            x->size != y->size || !same_str(x->neighbour, y->neighbour) || !same_str(x->groups, y->groups))
            snprintf(why, sizeof why, "patch %d differs: %s %s %d %d %s %s / %s %s %d %d %s %s", p, x->name,
                     x->type, x->start, x->size, x->neighbour ? x->neighbour : "-", x->groups ? x->groups : "-",
                     y->name, y->type, y->start, y->size, y->neighbour ? y->neighbour : "-",
                     y->groups ? y->groups : "-");
    }
    if (!why[0] && (!a->cell_parent) != (!b->cell_parent)) snprintf(why, sizeof why, "cellParent presence differs");
    if (!why[0] && a->cell_parent && memcmp(a->cell_parent, b->cell_parent, sizeof(int) * (size_t)a->ncells))
        snprintf(why, sizeof why, "cellParent differs");
    int nb = a->nfaces - a->ninternal;
    if (!why[0] && (!a->boundary_normal) != (!b->boundary_normal)) snprintf(why, sizeof why, "boundaryNormal presence differs");
    if (!why[0] && a->boundary_normal && memcmp(a->boundary_normal, b->boundary_normal, sizeof(double) * 3 * (size_t)nb))
        snprintf(why, sizeof why, "boundaryNormal differs");
    if (!why[0] && (a->nmerge_old != b->nmerge_old || (!a->merge_map) != (!b->merge_map)))
        snprintf(why, sizeof why, "mergeMap size differs");
    if (!why[0] && a->merge_map && memcmp(a->merge_map, b->merge_map, sizeof(int) * (size_t)a->nmerge_old))
        snprintf(why, sizeof why, "mergeMap differs");
    for (int k = 0; !why[0] && k < 3; k++) {
        if (a->cart.n[k] != b->cart.n[k])
            snprintf(why, sizeof why, "cartesianGrid n[%d] differs: %d / %d", k, a->cart.n[k], b->cart.n[k]);
        else if (a->cart.n[k] && memcmp(a->cart.x[k], b->cart.x[k], sizeof(double) * (size_t)(a->cart.n[k] + 1)))
            snprintf(why, sizeof why, "cartesianGrid axis %d differs", k);
    }
    return why;
}

static char *tmp_path(const char *name)
{
    return io_join(test_tmpdir(), name);
}

/* ---- round trips ---- */

static void round_trip(int binary, int gzip, int extras, const char *dirname)
{
    Mesh m, r;
    Err e;
    build_small(&m);
    if (extras) add_extras(&m);
    MeshWriteOpts o = {binary, gzip};
    char *dir = tmp_path(dirname);
    int rc = mesh_write(&m, dir, &o, &e);
    EXPECT(rc == 0, "write: %s", e.msg);
    char *pts = io_join(dir, gzip ? "points.gz" : "points");
    EXPECT(io_exists(pts), "%s missing", pts);
    free(pts);
    mesh_init(&r);
    rc = mesh_read(&r, dir, &e);
    EXPECT(rc == 0, "read: %s", e.msg);
    if (rc == 0) {
        const char *d = mesh_diff(&m, &r);
        EXPECT(!*d, "%s", d);
        EXPECT(mesh_check(&r, &e) == 0, "check: %s", e.msg);
    }
    mesh_free(&m);
    mesh_free(&r);
    free(dir);
}

TEST(round_trip_ascii) { round_trip(0, 0, 0, "rt_ascii"); }
TEST(round_trip_binary) { round_trip(1, 0, 0, "rt_binary"); }
TEST(round_trip_gzip) { round_trip(0, 1, 1, "rt_gzip"); }
TEST(round_trip_binary_gzip_extras) { round_trip(1, 1, 1, "rt_binary_gzip"); }

static int read_text(const char *path, Buf *b)
{
    Err e;
    return io_read_file(path, b, NULL, &e);
}

TEST(ascii_binary_ascii)
{
    Mesh m, r1, r2;
    Err e;
    build_small(&m);
    add_extras(&m);
    char *a = tmp_path("aba_a"), *b = tmp_path("aba_b"), *c = tmp_path("aba_c");
    MeshWriteOpts asc = {0, 0}, bin = {1, 0};
    EXPECT(mesh_write(&m, a, &asc, &e) == 0, "%s", e.msg);
    mesh_init(&r1);
    EXPECT(mesh_read(&r1, a, &e) == 0, "%s", e.msg);
    EXPECT(mesh_write(&r1, b, &bin, &e) == 0, "%s", e.msg);
    mesh_init(&r2);
    EXPECT(mesh_read(&r2, b, &e) == 0, "%s", e.msg);
    EXPECT(mesh_write(&r2, c, &asc, &e) == 0, "%s", e.msg);
    static const char *files[] = {"points", "faces", "owner", "neighbour", "boundary", "cartesianGrid", "cellParent"};
    for (int i = 0; i < 7; i++) {
        char *pa = io_join(a, files[i]), *pc = io_join(c, files[i]);
        Buf x, y;
        buf_init(&x);
        buf_init(&y);
        EXPECT(read_text(pa, &x) == 0 && read_text(pc, &y) == 0, "cannot read %s", files[i]);
        EXPECT(x.n == y.n && memcmp(x.p, y.p, x.n) == 0, "%s differs after ascii->binary->ascii", files[i]);
        buf_free(&x);
        buf_free(&y);
        free(pa);
        free(pc);
    }
    const char *d = mesh_diff(&m, &r2);
    EXPECT(!*d, "%s", d);
    mesh_free(&m);
    mesh_free(&r1);
    mesh_free(&r2);
    free(a);
    free(b);
    free(c);
}

TEST(owner_note_and_boundary_layout)
{
    Mesh m;
    Err e;
    build_small(&m);
    MeshWriteOpts asc = {0, 0};
    char *dir = tmp_path("layout");
    EXPECT(mesh_write(&m, dir, &asc, &e) == 0, "%s", e.msg);
    char *po = io_join(dir, "owner"), *pb = io_join(dir, "boundary");
    Buf b;
    buf_init(&b);
    EXPECT(read_text(po, &b) == 0, "read owner");
    CONTAINS(b.p, "note        \"nPoints:36  nCells:12  nFaces:52  nInternalFaces:20\";");
    CONTAINS(b.p, "class       labelList;");
    EXPECT(read_text(pb, &b) == 0, "read boundary");
    CONTAINS(b.p, "    xmin\n    {\n        type            wall;\n        inGroups        2(inlets wall);\n"
                  "        nFaces          4;\n        startFace       20;\n    }\n");
    CONTAINS(b.p, "    xmax\n    {\n        type            patch;\n        nFaces          4;\n");
    CONTAINS(b.p, "    ymin\n    {\n        type            symmetryPlane;\n        inGroups        1(symmetryPlane);\n");
    CONTAINS(b.p, "    zmin\n    {\n        type            wall;\n        inGroups        1(wall);\n");
    buf_free(&b);
    free(po);
    free(pb);
    free(dir);
    mesh_free(&m);
}

TEST(cyclic_patches)
{
    Mesh m, r;
    Err e;
    build_small(&m);
    for (int s = 0; s < 2; s++) {
        free(m.patches[s].type);
        free(m.patches[s].groups);
        m.patches[s].type = mem_strdup("cyclic");
        m.patches[s].groups = NULL;
        m.patches[s].neighbour = mem_strdup(s ? "xmin" : "xmax");
    }
    MeshWriteOpts asc = {0, 0};
    char *dir = tmp_path("cyclic");
    EXPECT(mesh_write(&m, dir, &asc, &e) == 0, "%s", e.msg);
    mesh_init(&r);
    EXPECT(mesh_read(&r, dir, &e) == 0, "%s", e.msg);
    EXPECT(r.npatches == 6 && same_str(r.patches[0].neighbour, "xmax") && same_str(r.patches[1].neighbour, "xmin"),
           "neighbourPatch not read back");
    /* the default group 1(cyclic) reads back as NULL */
    EXPECT(r.npatches == 6 && !r.patches[0].groups, "groups '%s'",
           r.npatches && r.patches[0].groups ? r.patches[0].groups : "-");
    char *pb = io_join(dir, "boundary");
    Buf b;
    buf_init(&b);
    EXPECT(read_text(pb, &b) == 0, "read boundary");
    CONTAINS(b.p, "        startFace       24;\n        matchTolerance  0.0001;\n        transform       unknown;\n"
                  "        neighbourPatch  xmin;\n");
    buf_free(&b);
    free(pb);
    free(dir);
    mesh_free(&m);
    mesh_free(&r);
}

TEST(stale_extras_removed)
{
    Mesh m, r;
    Err e;
    build_small(&m);
    add_extras(&m);
    MeshWriteOpts asc = {0, 0};
    char *dir = tmp_path("stale");
    EXPECT(mesh_write(&m, dir, &asc, &e) == 0, "%s", e.msg);
    free(m.cell_parent);
    m.cell_parent = NULL;
    for (int k = 0; k < 3; k++) {
        free(m.cart.x[k]);
        m.cart.x[k] = NULL;
        m.cart.n[k] = 0;
    }
    free(m.boundary_normal);
    free(m.merge_map);
    m.boundary_normal = NULL;
    m.merge_map = NULL;
    m.nmerge_old = 0;
    EXPECT(mesh_write(&m, dir, &asc, &e) == 0, "%s", e.msg);
    mesh_init(&r);
    EXPECT(mesh_read(&r, dir, &e) == 0, "%s", e.msg);
    EXPECT(!r.cell_parent && r.cart.n[0] == 0 && !r.boundary_normal && !r.merge_map, "stale extras were read back");
    free(dir);
    mesh_free(&m);
    mesh_free(&r);
}

/* ---- stream ---- */

TEST(stream_round_trip)
{
    for (int gz = 0; gz < 2; gz++)
        for (int bin = 0; bin < 2; bin++) {
            Mesh m, r;
            Err e;
            build_small(&m);
            add_extras(&m);
            Buf s;
            buf_init(&s);
            MeshWriteOpts o = {bin, gz};
            EXPECT(mesh_write_stream(&m, &s, &o, &e) == 0, "%s", e.msg);
            EXPECT(strncmp(s.p, "@file points", 12) == 0, "stream starts with '%.20s'", s.p);
            EXPECT(s.n > 5 && memcmp(s.p + s.n - 5, "@end\n", 5) == 0, "stream does not end with @end");
            mesh_init(&r);
            int rc = mesh_read_stream(&r, s.p, s.n, "<pipe>", &e);
            EXPECT(rc == 0, "binary=%d gzip=%d: %s", bin, gz, e.msg);
            if (rc == 0) {
                const char *d = mesh_diff(&m, &r);
                EXPECT(!*d, "binary=%d gzip=%d: %s", bin, gz, d);
            }
            buf_free(&s);
            mesh_free(&m);
            mesh_free(&r);
        }
}

/* mesh_write(m, "-") and mesh_read(m, "-") through a file put in place
   of the standard output and input descriptors. */
TEST(stdio_stream)
{
    Mesh m, r;
    Err e;
    build_small(&m);
    char *path = tmp_path("stdio.stream");
    FILE *f = fopen(path, "wb");
    EXPECT(f != NULL, "cannot create %s", path);
    if (!f) return;
    fflush(stdout);
    int saved = dup(1);
    dup2(fileno(f), 1);
    MeshWriteOpts o = {1, 0};
    int rc = mesh_write(&m, "-", &o, &e);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    fclose(f);
    EXPECT(rc == 0, "write to stdout: %s", e.msg);
    f = fopen(path, "rb");
    saved = dup(0);
    dup2(fileno(f), 0);
    clearerr(stdin);
    mesh_init(&r);
    rc = mesh_read(&r, "-", &e);
    dup2(saved, 0);
    close(saved);
    fclose(f);
    EXPECT(rc == 0, "read from stdin: %s", e.msg);
    if (rc == 0) {
        const char *d = mesh_diff(&m, &r);
        EXPECT(!*d, "%s", d);
    }
    mesh_free(&m);
    mesh_free(&r);
    free(path);
}

/* Every truncation and a few thousand byte corruptions of a stream must
   give an error or a mesh, never a crash (run under ASan as well). */
TEST(stream_garbage)
{
    Mesh m;
    Err e;
    build_small(&m);
    add_extras(&m);
    Buf s;
    buf_init(&s);
    MeshWriteOpts o = {1, 0};
    EXPECT(mesh_write_stream(&m, &s, &o, &e) == 0, "%s", e.msg);
    int nerr = 0;
    for (size_t n = 0; n < s.n; n += 1 + n / 64) {
        Mesh r;
        mesh_init(&r);
        e.msg[0] = 0;
        if (mesh_read_stream(&r, s.p, n, "<pipe>", &e)) {
            nerr++;
            EXPECT(strstr(e.msg, "<pipe>") != NULL, "truncated at %zu: message without the stream name: %s", n,
                   e.msg);
        }
        mesh_free(&r);
    }
    EXPECT(nerr > 0, "no truncation was detected");
    uint32_t seed = 12345;
    char *copy = mem_alloc(s.n);
    for (int t = 0; t < 2000; t++) {
        memcpy(copy, s.p, s.n);
        for (int k = 0; k < 1 + t % 4; k++) {
            seed = seed * 1664525u + 1013904223u;
            size_t at = (seed >> 8) % s.n;
            seed = seed * 1664525u + 1013904223u;
            copy[at] = (char)(seed >> 24);
        }
        Mesh r;
        mesh_init(&r);
        if (mesh_read_stream(&r, copy, s.n, "<pipe>", &e) == 0) mesh_check(&r, &e);
        mesh_free(&r);
    }
    free(copy);
    static const char *bad[] = {"", "@end", "@file points 99999999999999999999\n", "@file points -1\n",
                                "@file points 3\nabc", "@file\n", "garbage\n@end\n", "@file points 0\n@end\n"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        Mesh r;
        mesh_init(&r);
        EXPECT(mesh_read_stream(&r, bad[i], strlen(bad[i]), "<pipe>", &e) != 0, "'%s' accepted", bad[i]);
        CONTAINS(e.msg, "<pipe>");
        mesh_free(&r);
    }
    buf_free(&s);
    mesh_free(&m);
}

/* ---- reader errors ---- */

static void write_bytes(const char *path, const char *p, size_t n)
{
    Err e;
    EXPECT(io_write_atomic(path, p, n, 0, &e) == 0, "%s", e.msg);
}

/* Writes the small mesh into dir, then replaces `file` by its first
   `keep` bytes (keep < 0: by the text `repl`), and reads. */
static int read_altered(const char *dirname, int binary, const char *file, long keep, const char *repl, Err *e)
{
    Mesh m, r;
    build_small(&m);
    MeshWriteOpts o = {binary, 0};
    char *dir = tmp_path(dirname);
    mesh_write(&m, dir, &o, e);
    char *p = io_join(dir, file);
    if (keep >= 0) {
        Buf b;
        buf_init(&b);
        read_text(p, &b);
        write_bytes(p, b.p, (size_t)keep < b.n ? (size_t)keep : b.n);
        buf_free(&b);
    } else {
        write_bytes(p, repl, strlen(repl));
    }
    mesh_init(&r);
    int rc = mesh_read(&r, dir, e);
    mesh_free(&r);
    mesh_free(&m);
    free(p);
    free(dir);
    return rc;
}

static const char hdr_labels[] = "FoamFile { version 2.0; format ascii; class labelList; object x; }\n";

TEST(truncated_binary)
{
    Err e;
    EXPECT(read_altered("trunc_pts", 1, "points", 900, NULL, &e) != 0, "truncated points accepted");
    CONTAINS(e.msg, "points");
    EXPECT(read_altered("trunc_faces", 1, "faces", 1000, NULL, &e) != 0, "truncated faces accepted");
    CONTAINS(e.msg, "faces");
    EXPECT(read_altered("trunc_own", 1, "owner", 700, NULL, &e) != 0, "truncated owner accepted");
    CONTAINS(e.msg, "owner");
}

TEST(wrong_counts)
{
    Err e;
    char txt[512];
    /* owner one short */
    snprintf(txt, sizeof txt, "%s51(", hdr_labels);
    for (int i = 0; i < 51; i++) snprintf(txt + strlen(txt), sizeof txt - strlen(txt), "0 ");
    snprintf(txt + strlen(txt), sizeof txt - strlen(txt), ")\n");
    EXPECT(read_altered("cnt_own", 0, "owner", -1, txt, &e) != 0, "short owner accepted");
    CONTAINS(e.msg, "owner");
    CONTAINS(e.msg, "51 labels, expected 52");
    /* more neighbours than faces */
    snprintf(txt, sizeof txt, "%s53(", hdr_labels);
    for (int i = 0; i < 53; i++) snprintf(txt + strlen(txt), sizeof txt - strlen(txt), "1 ");
    snprintf(txt + strlen(txt), sizeof txt - strlen(txt), ")\n");
    EXPECT(read_altered("cnt_nei", 0, "neighbour", -1, txt, &e) != 0, "53 neighbours for 52 faces accepted");
    CONTAINS(e.msg, "neighbour");
    CONTAINS(e.msg, "53 neighbours for 52 faces");
    snprintf(txt, sizeof txt, "%s2(1 -2)\n", hdr_labels);
    EXPECT(read_altered("cnt_nei2", 0, "neighbour", -1, txt, &e) != 0, "negative neighbour accepted");
    CONTAINS(e.msg, "neighbour");
    /* a patch overlapping the internal faces */
    const char *bnd = "FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }\n"
                      "1 ( all { type wall; nFaces 33; startFace 19; } )\n";
    EXPECT(read_altered("cnt_bnd", 0, "boundary", -1, bnd, &e) != 0, "bad startFace accepted");
    CONTAINS(e.msg, "boundary");
    bnd = "FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }\n"
          "1 ( all { type wall; nFaces 30; startFace 20; } )\n";
    EXPECT(read_altered("cnt_bnd2", 0, "boundary", -1, bnd, &e) != 0, "uncovered faces accepted");
    CONTAINS(e.msg, "boundary");
    /* a face with a point out of range, and a face with two points */
    const char *fc = "FoamFile { version 2.0; format ascii; class faceList; object faces; }\n"
                     "1(4(0 1 2 60))\n";
    EXPECT(read_altered("cnt_faces", 0, "faces", -1, fc, &e) != 0, "point 60 accepted");
    CONTAINS(e.msg, "faces");
    CONTAINS(e.msg, "60");
    EXPECT(read_altered("miss", 0, "points", -1, "FoamFile { version 2.0; format ascii; class vectorField; "
                                                  "object points; }\n2((0 0 0) (1 1 1))\n", &e) != 0,
           "2 points accepted for a mesh using 60");
    CONTAINS(e.msg, "points");
}

/* The small mesh's points file with point k's line replaced by `line`:
   header on line 1, the size on 2, '(' on 3, point k on line 4 + k. */
static void points_text(Buf *b, const char *cls, int k, const char *line)
{
    Mesh m;
    build_small(&m);
    buf_printf(b, "FoamFile { version 2.0; format ascii; class %s; object points; }\n%d\n(\n", cls, m.npoints);
    for (int i = 0; i < m.npoints; i++) {
        if (i == k) buf_printf(b, "%s\n", line);
        else buf_printf(b, "(%.17g %.17g %.17g)\n", m.points[3 * i], m.points[3 * i + 1], m.points[3 * i + 2]);
    }
    buf_puts(b, ")\n");
    mesh_free(&m);
}

/* issue 9: a point coordinate written nan or inf is named with the file,
   its line and the point; a polyMesh file of the wrong class is refused
   as OpenFOAM refuses it; a header error names the polyMesh file. */
TEST(nonfinite_points_and_classes)
{
    Err e;
    Buf b;
    buf_init(&b);
    points_text(&b, "vectorField", 5, "(nan 0 0)");
    EXPECT(read_altered("nan_pts", 0, "points", -1, b.p, &e) != 0, "nan point accepted");
    CONTAINS(e.msg, "/nan_pts/points:9: point 5: coordinate 'nan' is not a finite number");
    buf_clear(&b);
    points_text(&b, "vectorField", 0, "(0 -Inf 0)");
    EXPECT(read_altered("inf_pts", 0, "points", -1, b.p, &e) != 0, "inf point accepted");
    CONTAINS(e.msg, "/inf_pts/points:4: point 0: coordinate '-Inf' is not a finite number");
    buf_clear(&b);
    points_text(&b, "labelList", 0, "(0 0 0)");
    EXPECT(read_altered("cls_pts", 0, "points", -1, b.p, &e) != 0, "points of class labelList accepted");
    CONTAINS(e.msg, "/cls_pts/points:1: unexpected class labelList in the FoamFile header, expected vectorField");
    buf_clear(&b);
    points_text(&b, "dictionary", -1, "");
    EXPECT(read_altered("dict_pts", 0, "points", -1, b.p, &e) == 0, "class dictionary refused (OpenFOAM accepts "
                                                                    "it): %s", e.msg);
    buf_free(&b);
    const char *own = "FoamFile\n{\n    version 2.0 nan;\n    format ascii;\n    class labelList;\n    object owner;\n}\n"
                      "0()\n";
    EXPECT(read_altered("hdr_own", 0, "owner", -1, own, &e) != 0, "bad header accepted");
    CONTAINS(e.msg, "/hdr_own/owner:3: FoamFile header: entry 'version' has 1 excess token");
    own = "FoamFile { version 2.0; format ascii; object owner; }\n0()\n";
    EXPECT(read_altered("nocls_own", 0, "owner", -1, own, &e) != 0, "header without class accepted");
    CONTAINS(e.msg, "/nocls_own/owner:1: FoamFile header has no class (expected labelList)");
}

TEST(missing_dir)
{
    Mesh r;
    Err e;
    mesh_init(&r);
    char *dir = tmp_path("does_not_exist");
    EXPECT(mesh_read(&r, dir, &e) != 0, "read of a missing directory succeeded");
    CONTAINS(e.msg, "does_not_exist/points");
    free(dir);
    mesh_free(&r);
}

/* ---- mesh_check ---- */

TEST(check_invariants)
{
    Mesh m;
    Err e;
    build_small(&m);
    EXPECT(mesh_check(&m, &e) == 0, "valid mesh rejected: %s", e.msg);

    /* owner > neighbour on face 5 */
    int t = m.owner[5];
    m.owner[5] = m.neighbour[5];
    m.neighbour[5] = t;
    EXPECT(mesh_check(&m, &e) != 0, "owner > neighbour accepted");
    CONTAINS(e.msg, "face 5:");
    m.neighbour[5] = m.owner[5];
    m.owner[5] = t;

    /* faces 7 and 8 swapped: 8 comes first in the wrong order */
    int o7 = m.owner[7], n7 = m.neighbour[7];
    m.owner[7] = m.owner[8];
    m.neighbour[7] = m.neighbour[8];
    m.owner[8] = o7;
    m.neighbour[8] = n7;
    EXPECT(mesh_check(&m, &e) != 0, "wrong order accepted");
    CONTAINS(e.msg, "face 8 ");
    m.owner[8] = m.owner[7];
    m.neighbour[8] = m.neighbour[7];
    m.owner[7] = o7;
    m.neighbour[7] = n7;

    /* a bad point index in face 11 */
    int k = m.face_off[11] + 2, old = m.face_idx[k];
    m.face_idx[k] = m.npoints;
    EXPECT(mesh_check(&m, &e) != 0, "bad index accepted");
    CONTAINS(e.msg, "face 11:");
    m.face_idx[k] = old;

    /* non-contiguous patches: ymin starts one face late */
    m.patches[2].start++;
    m.patches[2].size--;
    EXPECT(mesh_check(&m, &e) != 0, "gap between patches accepted");
    CONTAINS(e.msg, "patch 'ymin' starts at face 29");
    m.patches[2].start--;
    m.patches[2].size++;

    /* a negative owner on a boundary face */
    int o40 = m.owner[40];
    m.owner[40] = -1;
    EXPECT(mesh_check(&m, &e) != 0, "negative owner accepted");
    CONTAINS(e.msg, "face 40:");
    m.owner[40] = o40;

    EXPECT(mesh_check(&m, &e) == 0, "restored mesh rejected: %s", e.msg);

    /* a boundary face turned inside out: closedness fails for its cell */
    int a = m.face_off[30], b = m.face_off[31] - 1;
    while (a < b) {
        int s = m.face_idx[a];
        m.face_idx[a++] = m.face_idx[b];
        m.face_idx[b--] = s;
    }
    mesh_geometry(&m);
    EXPECT(mesh_check(&m, &e) != 0, "inverted face accepted");
    char want[64];
    snprintf(want, sizeof want, "cell %d is not closed", m.owner[30]);
    CONTAINS(e.msg, want);
    mesh_free(&m);
}

TEST(check_inverted_cell)
{
    /* one cell whose every face is reversed: closed but negative volume */
    Grid g = {{1, 1, 1}, {xs, ys, zs}};
    Mesh m;
    Err e;
    build(&m, &g, 0);
    for (int f = 0; f < m.nfaces; f++) {
        int a = m.face_off[f], b = m.face_off[f + 1] - 1;
        while (a < b) {
            int s = m.face_idx[a];
            m.face_idx[a++] = m.face_idx[b];
            m.face_idx[b--] = s;
        }
    }
    mesh_geometry(&m);
    EXPECT(mesh_check(&m, &e) != 0, "inverted cell accepted");
    CONTAINS(e.msg, "cell 0 has volume -");
    mesh_free(&m);
}

/* ---- geometry ---- */

TEST(geometry_box)
{
    Mesh m;
    build_small(&m);
    mesh_geometry(&m);
    double total = 0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 3; i++) {
                int c = i + 3 * (j + 2 * k);
                double dx = xs[i + 1] - xs[i], dy = ys[j + 1] - ys[j], dz = zs[k + 1] - zs[k];
                double V = dx * dy * dz;
                NEAR(m.cell_vol[c], V, 1e-15 * V);
                NEAR(m.cell_centre[3 * c], 0.5 * (xs[i] + xs[i + 1]), 1e-15 * 2);
                NEAR(m.cell_centre[3 * c + 1], 0.5 * (ys[j] + ys[j + 1]), 1e-15 * 2);
                NEAR(m.cell_centre[3 * c + 2], 0.5 * (zs[k] + zs[k + 1]), 1e-15 * 3);
                total += m.cell_vol[c];
            }
    NEAR(total, 1.5 * 1.75 * 0.5, 1e-15 * 1.3125);
    double worst = 0;
    for (int c = 0; c < m.ncells; c++) {
        double s[3] = {0, 0, 0}, mag = 0;
        for (int k = m.cell_off[c]; k < m.cell_off[c + 1]; k++) {
            int f = m.cell_faces[k];
            double sg = m.owner[f] == c ? 1 : -1;
            for (int d = 0; d < 3; d++) s[d] += sg * m.face_area[3 * f + d];
            mag += sqrt(m.face_area[3 * f] * m.face_area[3 * f] + m.face_area[3 * f + 1] * m.face_area[3 * f + 1] +
                        m.face_area[3 * f + 2] * m.face_area[3 * f + 2]);
        }
        double r = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / mag;
        if (r > worst) worst = r;
    }
    EXPECT(worst < 1e-15, "closedness |sum Sf|/sum|Sf| = %g", worst);
    /* face 0 is the +x face between cells 0 and 1 at x = 0.25 */
    NEAR(m.face_area[0], 0.5 * 0.125, 1e-17);
    NEAR(m.face_centre[0], 0.25, 0);
    EXPECT(m.cell_off[1] - m.cell_off[0] == 6, "cell 0 has %d faces", m.cell_off[1] - m.cell_off[0]);
    mesh_free(&m);
}

TEST(empty_axis)
{
    double z1[2] = {0, 0.01};
    Grid g = {{3, 2, 1}, {xs, ys, z1}};
    Mesh m;
    build(&m, &g, 1);
    Err e;
    EXPECT(mesh_check(&m, &e) == 0, "%s", e.msg);
    EXPECT(mesh_empty_axis(&m) == 2, "2-D mesh: axis %d", mesh_empty_axis(&m));
    mesh_geometry(&m);
    EXPECT(mesh_empty_axis(&m) == 2, "2-D mesh with geometry: axis %d", mesh_empty_axis(&m));
    free(m.patches[4].type);
    m.patches[4].type = mem_strdup("wall");
    EXPECT(mesh_empty_axis(&m) == -1, "no empty patch: axis %d", mesh_empty_axis(&m));
    mesh_free(&m);
    /* two cells thick: empty faces exist but cells have one each */
    double z2[3] = {0, 0.01, 0.02};
    Grid g2 = {{3, 2, 2}, {xs, ys, z2}};
    build(&m, &g2, 1);
    EXPECT(mesh_empty_axis(&m) == -1, "two cells thick: axis %d", mesh_empty_axis(&m));
    mesh_free(&m);
    build_small(&m);
    EXPECT(mesh_empty_axis(&m) == -1, "3-D mesh: axis %d", mesh_empty_axis(&m));
    mesh_free(&m);
}

TEST(patch_lookup_and_spacing)
{
    Mesh m;
    build_small(&m);
    add_extras(&m);
    EXPECT(mesh_patch(&m, "ymax") == 3 && mesh_patch(&m, "nope") == -1, "mesh_patch");
    int bad = -2;
    for (int f = 0; f < m.nfaces && bad == -2; f++) {
        int want = -1;
        for (int p = 0; p < m.npatches; p++)
            if (f >= m.patches[p].start && f < m.patches[p].start + m.patches[p].size) want = p;
        if (mesh_face_patch(&m, f) != want) bad = f;
    }
    EXPECT(bad == -2, "mesh_face_patch wrong for face %d", bad);
    double h[3];
    EXPECT(mesh_cell_spacing(&m, 7, h) == 0, "cell 7 has no spacing");
    /* cell 7 = (1, 0, 1) */
    NEAR(h[0], 0.375, 0);
    NEAR(h[1], 0.5, 0);
    NEAR(h[2], 0.375, 0);
    EXPECT(mesh_cell_spacing(&m, 5, h) == -1, "cell 5 has no parent");
    double lo[3], hi[3];
    mesh_bounds(&m, lo, hi);
    EXPECT(lo[0] == 0 && lo[1] == -1 && lo[2] == 2 && hi[0] == 1.5 && hi[1] == 0.75 && hi[2] == 2.5,
           "bounds (%g %g %g) (%g %g %g)", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    mesh_free(&m);
}

/* ---- OpenFOAM's blockMesh ---- */

static int run(const char *cmd)
{
    int rc = system(cmd);
    return rc;
}

static const char cavity_src[] = "/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity";

static int have_openfoam(void)
{
    return run("command -v blockMesh >/dev/null 2>&1") == 0 && io_is_dir(cavity_src);
}

/* blockMesh on a copy of the cavity tutorial: 20 x 20 x 1 cells of a
   0.1 x 0.1 x 0.01 box (scale 0.1) */
TEST(openfoam_cavity)
{
    const char *src = cavity_src;
    char cmd[2048];
    const char *t = test_tmpdir();
    snprintf(cmd, sizeof cmd,
             "cd '%s' && rm -rf ofcav && cp -r '%s' ofcav && cd ofcav && "
             "find . -name '*.gz' -exec gunzip -f {} + && "
             "WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh >log.blockMesh 2>&1",
             t, src);
    int rc = run(cmd);
    EXPECT(rc == 0, "blockMesh failed (see %s/ofcav/log.blockMesh)", t);
    Mesh m;
    Err e;
    mesh_init(&m);
    char *dir = tmp_path("ofcav/constant/polyMesh");
    rc = mesh_read(&m, dir, &e);
    EXPECT(rc == 0, "%s", e.msg);
    if (rc == 0) {
        EXPECT(m.ncells == 400 && m.nfaces == 1640 && m.npoints == 882 && m.ninternal == 760,
               "%d cells %d faces %d points %d internal", m.ncells, m.nfaces, m.npoints, m.ninternal);
        EXPECT(mesh_check(&m, &e) == 0, "%s", e.msg);
        mesh_geometry(&m);
        EXPECT(mesh_check(&m, &e) == 0, "%s", e.msg);
        double V = 0;
        for (int c = 0; c < m.ncells; c++) V += m.cell_vol[c];
        NEAR(V, 0.1 * 0.1 * 0.01, 1e-14 * 1e-4);
        EXPECT(mesh_empty_axis(&m) == 2, "cavity empty axis %d", mesh_empty_axis(&m));
        EXPECT(m.npatches == 3 && !strcmp(m.patches[2].name, "frontAndBack") &&
                   !m.patches[0].groups && m.patches[2].start == 840 &&
                   m.patches[2].size == 800,
               "patches not as blockMesh wrote them");
        /* our writer reproduces blockMesh's files except the banner */
        char *ours = tmp_path("ofcav_ours");
        MeshWriteOpts asc = {0, 0};
        EXPECT(mesh_write(&m, ours, &asc, &e) == 0, "%s", e.msg);
        snprintf(cmd, sizeof cmd, "cd '%s' && for f in points faces owner neighbour boundary; do "
                 "tail -n +8 ofcav/constant/polyMesh/$f >theirs && tail -n +8 ofcav_ours/$f >ours && "
                 "cmp -s theirs ours || { echo \"  $f differs\"; exit 1; }; done",
                 t);
        EXPECT(run(cmd) == 0, "our polyMesh files differ from blockMesh's beyond the banner");
        free(ours);
    }
    free(dir);
    mesh_free(&m);
}

TEST(openfoam_cavity_binary)
{
    const char *t = test_tmpdir();
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && rm -rf ofcavb && cp -r ofcav ofcavb && cd ofcavb && rm -rf constant/polyMesh && "
             "sed -i 's/^writeFormat .*/writeFormat binary;/' system/controlDict && "
             "WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh >log.blockMesh 2>&1",
             t);
    EXPECT(run(cmd) == 0, "blockMesh (binary) failed");
    Mesh a, b;
    Err e;
    mesh_init(&a);
    mesh_init(&b);
    char *da = tmp_path("ofcav/constant/polyMesh"), *db = tmp_path("ofcavb/constant/polyMesh");
    EXPECT(mesh_read(&a, da, &e) == 0, "%s", e.msg);
    EXPECT(mesh_read(&b, db, &e) == 0, "%s", e.msg);
    /* the ascii points carry 6 digits (writePrecision 6), the binary ones
       all 17: compare those to 5e-7 relative, everything else exactly */
    double worst = 0;
    for (int i = 0; i < 3 * a.npoints && a.npoints == b.npoints; i++) {
        double d = fabs(a.points[i] - b.points[i]);
        if (d > worst) worst = d;
    }
    EXPECT(a.npoints == b.npoints && worst <= 0.1 * 5e-7, "points differ by %g", worst);
    if (a.npoints == b.npoints) memcpy(b.points, a.points, sizeof(double) * 3 * (size_t)a.npoints);
    const char *d = mesh_diff(&a, &b);
    EXPECT(!*d, "ascii and binary blockMesh output differ: %s", d);
    free(da);
    free(db);
    mesh_free(&a);
    mesh_free(&b);
}

int main(void)
{
    RUN(round_trip_ascii);
    RUN(round_trip_binary);
    RUN(round_trip_gzip);
    RUN(round_trip_binary_gzip_extras);
    RUN(ascii_binary_ascii);
    RUN(owner_note_and_boundary_layout);
    RUN(cyclic_patches);
    RUN(stale_extras_removed);
    RUN(stream_round_trip);
    RUN(stdio_stream);
    RUN(stream_garbage);
    RUN(truncated_binary);
    RUN(wrong_counts);
    RUN(nonfinite_points_and_classes);
    RUN(missing_dir);
    RUN(check_invariants);
    RUN(check_inverted_cell);
    RUN(geometry_box);
    RUN(empty_axis);
    RUN(patch_lookup_and_spacing);
    if (have_openfoam()) {
        RUN(openfoam_cavity);
        RUN(openfoam_cavity_binary);
    } else {
        printf("SKIP openfoam_cavity: OpenFOAM's blockMesh or the cavity tutorial is not installed\n");
    }
    return test_summary();
}
