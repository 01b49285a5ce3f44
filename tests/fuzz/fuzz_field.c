/*
** fuzz_field.c: libFuzzer harness for the field reader (field_read,
** field_probe).
**
** field_read needs a mesh and a path.  The mesh is built here, once, by
** filling the Mesh struct: a 3 x 2 x 1 hexahedral grid in OpenFOAM order
** (internal faces upper-triangular, normals out of the owner) with the
** patches a 2-D case has: left (patch), right (patch), bottom and top
** (wall, inGroups 1(wall)), frontAndBack (empty).  Building it by hand
** rather than reading it keeps this harness independent of the mesh
** reader, and mesh_check at start-up proves the construction.
**
** Each input is written (plain stdio: this is the harness, not the
** library) to "0/T" in a per-process scratch directory (under
** $FUZZ_SCRATCH, which tests/fuzz/run sets and removes, else on tmpfs when
** there is one) and read with field_read.  A field that reads must give
** finite values (the reader refuses NaN/Inf), answer field_patch_values
** on every patch, and survive a write/read round trip through field_write
** (binary, and ascii at full precision) with equal internal and patch
** values (no digit may be lost).  FUZZ_NO_ROUNDTRIP=1 switches the round trip off.
**
** Build: tests/fuzz/run (clang -fsanitize=fuzzer,address,undefined).
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "field.h"
#include "mesh.h"

enum { NX = 3, NY = 2 };

static Mesh mesh;
static char *in_path;    /* scratch/0/T: the fuzz input */
static char *out_path;   /* scratch/1/T: round-trip output */

static void fail(const char *what, const char *msg)
{
    fprintf(stderr, "%s: %s\n", what, msg);
    abort();
}

/* point index of grid node (i, j, k), k = 0 back, 1 front */
static int pt(int i, int j, int k) { return i + (NX + 1) * (j + (NY + 1) * k); }

static void add_face(int *nf, int a, int b, int c, int d, int own, int nei)
{
    int f = *nf;
    mesh.face_off[f] = 4 * f;
    mesh.face_idx[4 * f + 0] = a;
    mesh.face_idx[4 * f + 1] = b;
    mesh.face_idx[4 * f + 2] = c;
    mesh.face_idx[4 * f + 3] = d;
    mesh.owner[f] = own;
    if (nei >= 0) mesh.neighbour[f] = nei;
    *nf = f + 1;
}

/* Faces whose right-hand normal is +x, +y, +z at grid node (i, j, k). */
static void face_x(int *nf, int i, int j, int own, int nei, int flip)
{
    if (flip) add_face(nf, pt(i, j, 0), pt(i, j, 1), pt(i, j + 1, 1), pt(i, j + 1, 0), own, nei);
    else add_face(nf, pt(i, j, 0), pt(i, j + 1, 0), pt(i, j + 1, 1), pt(i, j, 1), own, nei);
}
static void face_y(int *nf, int i, int j, int own, int nei, int flip)
{
    if (flip) add_face(nf, pt(i, j, 0), pt(i + 1, j, 0), pt(i + 1, j, 1), pt(i, j, 1), own, nei);
    else add_face(nf, pt(i, j, 0), pt(i, j, 1), pt(i + 1, j, 1), pt(i + 1, j, 0), own, nei);
}
static void face_z(int *nf, int i, int j, int k, int own, int flip)
{
    if (flip) add_face(nf, pt(i, j, k), pt(i, j + 1, k), pt(i + 1, j + 1, k), pt(i + 1, j, k), own, -1);
    else add_face(nf, pt(i, j, k), pt(i + 1, j, k), pt(i + 1, j + 1, k), pt(i, j + 1, k), own, -1);
}

static void set_patch(int p, const char *name, const char *type, const char *groups, int start, int size)
{
    mesh.patches[p].name = strdup(name);
    mesh.patches[p].type = strdup(type);
    mesh.patches[p].groups = groups ? strdup(groups) : NULL;
    mesh.patches[p].neighbour = NULL;
    mesh.patches[p].start = start;
    mesh.patches[p].size = size;
}

static void build_mesh(void)
{
    mesh_init(&mesh);
    mesh.npoints = (NX + 1) * (NY + 1) * 2;
    mesh.ncells = NX * NY;
    mesh.ninternal = (NX - 1) * NY + NX * (NY - 1);
    mesh.nfaces = mesh.ninternal + 2 * NY + 2 * NX + 2 * NX * NY;
    mesh.npatches = 5;
    mesh.points = calloc(3 * (size_t)mesh.npoints, sizeof(double));
    mesh.face_off = calloc((size_t)mesh.nfaces + 1, sizeof(int));
    mesh.face_idx = calloc(4 * (size_t)mesh.nfaces, sizeof(int));
    mesh.owner = calloc((size_t)mesh.nfaces, sizeof(int));
    mesh.neighbour = calloc((size_t)mesh.ninternal, sizeof(int));
    mesh.patches = calloc((size_t)mesh.npatches, sizeof(Patch));
    for (int k = 0; k < 2; k++)
        for (int j = 0; j <= NY; j++)
            for (int i = 0; i <= NX; i++) {
                double *x = mesh.points + 3 * pt(i, j, k);
                x[0] = 0.1 * i;
                x[1] = 0.1 * j;
                x[2] = 0.1 * k;
            }
    int nf = 0;
    for (int j = 0; j < NY; j++)          /* internal, sorted by owner then neighbour */
        for (int i = 0; i < NX; i++) {
            int c = i + NX * j;
            if (i + 1 < NX) face_x(&nf, i + 1, j, c, c + 1, 0);
            if (j + 1 < NY) face_y(&nf, i, j + 1, c, c + NX, 0);
        }
    int s = nf;
    for (int j = 0; j < NY; j++) face_x(&nf, 0, j, NX * j, -1, 1);
    set_patch(0, "left", "patch", NULL, s, nf - s);
    s = nf;
    for (int j = 0; j < NY; j++) face_x(&nf, NX, j, NX - 1 + NX * j, -1, 0);
    set_patch(1, "right", "patch", NULL, s, nf - s);
    s = nf;
    for (int i = 0; i < NX; i++) face_y(&nf, i, 0, i, -1, 1);
    set_patch(2, "bottom", "wall", "1(wall)", s, nf - s);
    s = nf;
    for (int i = 0; i < NX; i++) face_y(&nf, i, NY, i + NX * (NY - 1), -1, 0);
    set_patch(3, "top", "wall", "1(wall)", s, nf - s);
    s = nf;
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            face_z(&nf, i, j, 0, i + NX * j, 1);
            face_z(&nf, i, j, 1, i + NX * j, 0);
        }
    set_patch(4, "frontAndBack", "empty", "1(empty)", s, nf - s);
    mesh.face_off[nf] = 4 * nf;
    Err e;
    if (nf != mesh.nfaces) fail("harness mesh", "face count");
    if (mesh_check(&mesh, &e) != 0) fail("harness mesh", e.msg);
    mesh_cell_faces(&mesh);
    mesh_geometry(&mesh);
}

static char *scratch_file(const char *dir, const char *sub)
{
    size_t n = strlen(dir) + strlen(sub) + 8;
    char *p = malloc(n);
    snprintf(p, n, "%s/%s", dir, sub);
    if (mkdir(p, 0700) != 0) abort();
    snprintf(p, n, "%s/%s/T", dir, sub);
    return p;
}

static void fuzz_setup(void)
{
    const char *roots[] = {getenv("FUZZ_SCRATCH"), "/dev/shm", "/tmp"};
    char dir[512] = "";
    for (size_t k = 0; k < 3 && !dir[0]; k++) {
        if (!roots[k]) continue;
        snprintf(dir, sizeof dir, "%s/kiesel-fuzz-field.XXXXXX", roots[k]);
        if (!mkdtemp(dir)) dir[0] = '\0';
    }
    if (!dir[0]) abort();
    in_path = scratch_file(dir, "0");
    out_path = scratch_file(dir, "1");
    build_mesh();
}

/* Equal as numbers: -0 and 0 are the same value, and any difference
   beyond that (a lost digit) is a real round-trip failure. */
static int same_values(const double *a, const double *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!(a[i] == b[i])) return 0;
    return 1;
}

static void compare(const Field *a, const Field *b, const char *how)
{
    if (a->width != b->width || a->ncells != b->ncells || a->npatches != b->npatches)
        fail(how, "shape differs after write and re-read");
    if (!same_values(a->v, b->v, (size_t)a->ncells * (size_t)a->width))
        fail(how, "internal values differ after write and re-read");
    for (int p = 0; p < a->npatches; p++) {
        const PatchField *x = &a->pf[p], *y = &b->pf[p];
        if (strcmp(x->type, y->type) != 0) fail(how, "patch type differs after write and re-read");
        if ((x->value == NULL) != (y->value == NULL) ||
            (x->value && !same_values(x->value, y->value, (size_t)x->n * (size_t)a->width)))
            fail(how, "patch values differ after write and re-read");
    }
}

static void roundtrip(const Field *f, int binary)
{
    Err e;
    Field g;
    FieldWriteOpts o = {binary, 0, 0, NULL};
    const char *how = binary ? "binary round trip" : "ascii round trip";
    memset(&g, 0, sizeof g);
    if (field_write(f, &mesh, out_path, &o, &e) != 0) fail(how, e.msg);
    if (field_read(&g, &mesh, out_path, &e) != 0) fail(how, e.msg);
    compare(f, &g, how);
    field_free(&g);
}

static void exercise(const Field *f)
{
    if (field_first_nonfinite(f) >= 0) fail("field_read", "accepted a non-finite value");
    double *out = calloc(3 * (size_t)mesh.nfaces + 1, sizeof(double));
    for (int p = 0; p < mesh.npatches; p++) field_patch_values(f, &mesh, p, out);
    free(out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int no_roundtrip = -1;
    if (!in_path) fuzz_setup();
    if (no_roundtrip < 0) no_roundtrip = getenv("FUZZ_NO_ROUNDTRIP") != NULL;
    FILE *fp = fopen(in_path, "wb");
    if (!fp) abort();
    if (size && fwrite(data, 1, size, fp) != size) abort();
    fclose(fp);

    Err e;
    char *cls = NULL;
    e.msg[0] = '\0';
    if (field_probe(in_path, &cls, &e) >= 0) free(cls);

    Field f;
    memset(&f, 0, sizeof f);
    e.msg[0] = '\0';
    if (field_read(&f, &mesh, in_path, &e) != 0) {
        if (!e.msg[0]) fail("field_read", "failed without a message");
        return 0;
    }
    exercise(&f);
    if (!no_roundtrip) {
        roundtrip(&f, 1);
        roundtrip(&f, 0);
    }
    field_free(&f);
    return 0;
}
