/*
** bench_mesh.c: times the mesh I/O path on an N^3 unit-cube grid built in
** memory (block_mesh): mesh_write (binary, then ascii unless
** KIESEL_BENCH_NOASCII is set), mesh_read of each, and mesh_geometry.
**
**   bench_mesh <scratch dir> <N>
**
** Output lines "MESH <what> <MB> <wall s> <MB/s> <cpu s>" (MB of the
** polyMesh files involved; 0 for mesh_geometry).  The mesh read back is
** compared with the one written (sizes and every array, bit for bit), so a
** fast wrong reader or writer cannot pass.
*/
#include "block.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static double now(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Total bytes of the regular files in dir. */
static double dir_mb(const char *dir)
{
    char **names;
    int n = io_list_dir(dir, &names, NULL);
    double sum = 0;
    for (int i = 0; i < n; i++) {
        char *p = io_join(dir, names[i]);
        struct stat st;
        if (stat(p, &st) == 0) sum += (double)st.st_size;
        free(p);
    }
    if (n >= 0) io_free_list(names, n);
    return sum / 1e6;
}

static void report(const char *what, double mb, double w0, double c0)
{
    double w = now(CLOCK_MONOTONIC) - w0, c = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    printf("MESH %s %.1f %.3f %.1f %.3f\n", what, mb, w, mb > 0 ? mb / w : 0, c);
    fflush(stdout);
}

static int same(const Mesh *a, const Mesh *b)
{
    if (a->npoints != b->npoints || a->nfaces != b->nfaces || a->ninternal != b->ninternal ||
        a->ncells != b->ncells || a->npatches != b->npatches)
        return 0;
    size_t nf = (size_t)a->nfaces;
    return !memcmp(a->points, b->points, 3 * sizeof(double) * (size_t)a->npoints) &&
           !memcmp(a->face_off, b->face_off, sizeof(int) * (nf + 1)) &&
           !memcmp(a->face_idx, b->face_idx, sizeof(int) * (size_t)a->face_off[nf]) &&
           !memcmp(a->owner, b->owner, sizeof(int) * nf) &&
           !memcmp(a->neighbour, b->neighbour, sizeof(int) * (size_t)a->ninternal) &&
           !memcmp(a->cell_parent, b->cell_parent, sizeof(int) * (size_t)a->ncells);
}

static int run(const Mesh *m, const char *dir, int binary, const char *tag)
{
    char what[64];
    Err e = {{0}};
    MeshWriteOpts o = {binary, 0};
    double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (mesh_write(m, dir, &o, &e)) return fprintf(stderr, "bench_mesh: %s\n", e.msg), -1;
    snprintf(what, sizeof what, "mesh_write_%s", tag);
    report(what, dir_mb(dir), w0, c0);
    Mesh r;
    w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (mesh_read(&r, dir, &e)) return fprintf(stderr, "bench_mesh: %s\n", e.msg), -1;
    snprintf(what, sizeof what, "mesh_read_%s", tag);
    report(what, dir_mb(dir), w0, c0);
    int ok = same(m, &r);
    if (ok && binary) {
        w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        mesh_geometry(&r);
        report("mesh_geometry", 0, w0, c0);
    }
    mesh_free(&r);
    if (!ok) return fprintf(stderr, "bench_mesh: %s mesh read back differs\n", tag), -1;
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) return fprintf(stderr, "usage: bench_mesh <scratch dir> <N>\n"), 2;
    int n = atoi(argv[2]);
    if (n < 1 || n > 1000) return fprintf(stderr, "bench_mesh: N must be 1..1000\n"), 2;
    Err e = {{0}};
    double *x[3];
    int nn[3] = {n, n, n};
    for (int k = 0; k < 3; k++) {
        x[k] = MEM_NEW(double, (size_t)n + 1);
        for (int i = 0; i <= n; i++) x[k][i] = (double)i / n;
    }
    BlockSide side[BLOCK_NSIDES] = {{"left", "wall", NULL},  {"right", "wall", NULL}, {"bottom", "wall", NULL},
                                    {"top", "wall", NULL},   {"back", "patch", NULL}, {"front", "patch", NULL}};
    Mesh m;
    mesh_init(&m);
    if (block_mesh(&m, x, nn, side, NULL, NULL, NULL, &e)) return fprintf(stderr, "bench_mesh: %s\n", e.msg), 1;
    char *dir = io_join(argv[1], "polyMesh");
    int rc = run(&m, dir, 1, "binary");
    if (!rc && !getenv("KIESEL_BENCH_NOASCII")) rc = run(&m, dir, 0, "ascii");
    io_rm_rf(dir, NULL);
    free(dir);
    mesh_free(&m);
    for (int k = 0; k < 3; k++) free(x[k]);
    return rc ? 1 : 0;
}
