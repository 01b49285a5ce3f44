/*
** bench_io.c: field I/O throughput against plain copying.
**
**     bench_io SCRATCH_DIR [NCELLS]      (default NCELLS = 8000000 = 200^3)
**
** Writes and reads a volScalarField and a volVectorField of NCELLS cells
** with field_write / field_read: binary, ascii at the default precision 6
** and ascii at full precision (shortest exact, precision 0).  The baseline
** is plain copying of the same number of bytes as the binary file: memcpy
** into a Buf and io_write_atomic (write), io_read_file and memcpy out
** (read).  Binary I/O does the same system work plus the header and the
** boundary patches, so "binary / copy" measures the reader's and writer's
** own overhead; the target is at most 2.
**
** The mesh is only a shell: field I/O needs the cell count and the
** patches (names, types, sizes), not the faces, so the six sides of a
** 200^3 box are described without building 24 million faces.  Values are
** pseudo-random doubles with all 17 digits significant, the worst case for
** ascii.  Reads come from the page cache (the file was just written), as
** do the baseline reads, so both measure CPU work, not the disk; writes
** include io_write_atomic's fsync on both sides.
**
** Each measurement records wall time and CPU time (user + system of this
** process).  On a virtual machine whose memory is backed lazily, the first
** touch of fresh pages can cost more than the work itself, and wall time
** far above CPU time shows it; so the program first measures that cost
** alone: "MEM first_touch" is the rate at which 256 MB of fresh memory
** can be written once, the ceiling for anything that allocates its output.
**
** Output: one line per measurement,
**     IO <name> <megabytes> <wall s> <MB/s> <cpu s>
**     MEM first_touch <megabytes> <wall s> <MB/s> <cpu s>
** and  RATIO <name> <binary/copy wall time>;  bench/run makes the table.
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "buf.h"
#include "field.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_now(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static void die(const Err *e)
{
    fprintf(stderr, "bench_io: %s\n", e->msg);
    exit(1);
}

/* The six sides of an n^3 box as patches, after n^2 (3n - 3) internal faces. */
static void shell_mesh(Mesh *m, int ncells)
{
    static const char *const names[6] = {"left", "right", "bottom", "top", "back", "front"};
    int n = (int)lround(cbrt((double)ncells));
    int side = ncells / (n > 0 ? n : 1);   /* faces per side when ncells = n^3 */
    mesh_init(m);
    m->ncells = ncells;
    m->ninternal = 3 * ncells - 3 * side;
    m->npatches = 6;
    m->patches = MEM_NEW(Patch, 6);
    int start = m->ninternal;
    for (int p = 0; p < 6; p++) {
        m->patches[p].name = mem_strdup(names[p]);
        m->patches[p].type = mem_strdup(p < 4 ? "wall" : "patch");
        m->patches[p].start = start;
        m->patches[p].size = side;
        start += side;
    }
    m->nfaces = start;
}

static uint64_t rng = 0x9E3779B97F4A7C15ull;

static double random_value(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return 1e-3 + 1e3 * (double)(rng >> 11) / 9007199254740992.0;
}

static size_t file_size(const char *path)
{
    Buf b;
    Err e;
    buf_init(&b);
    if (io_read_file(path, &b, NULL, &e) != 0) die(&e);
    size_t n = b.n;
    buf_free(&b);
    return n;
}

static void report(const char *name, double bytes, double t, double cpu)
{
    printf("IO %s %.1f %.3f %.1f %.3f\n", name, bytes / 1e6, t, bytes / 1e6 / t, cpu);
    fflush(stdout);
}

/* Writing each page of fresh memory once: the machine's allocation ceiling. */
static void bench_first_touch(void)
{
    size_t n = (size_t)256 << 20;
    double t0 = now(), c0 = cpu_now();
    volatile char *p = mem_alloc(n);
    for (size_t i = 0; i < n; i += 4096) p[i] = (char)i;
    double t = now() - t0, c = cpu_now() - c0;
    free((void *)p);
    printf("MEM first_touch %.1f %.3f %.1f %.3f\n", (double)n / 1e6, t, (double)n / 1e6 / t, c);
}

/* Writes f in one format, reads it back, checks the values, reports both.
   Returns the file size. */
static size_t bench_format(const Field *f, const Mesh *m, const char *dir, const char *label,
                           int binary, int precision, double *t_write, double *t_read)
{
    double c0, c_write, c_read;
    Err e;
    char name[128];
    char *path = io_join(dir, f->name);
    FieldWriteOpts o = {binary, 0, precision, "0"};
    double t0 = now();
    c0 = cpu_now();
    if (field_write(f, m, path, &o, &e) != 0) die(&e);
    *t_write = now() - t0;
    c_write = cpu_now() - c0;
    size_t bytes = file_size(path);

    Field g;
    memset(&g, 0, sizeof g);
    t0 = now();
    c0 = cpu_now();
    if (field_read(&g, m, path, &e) != 0) die(&e);
    *t_read = now() - t0;
    c_read = cpu_now() - c0;
    size_t nv = (size_t)f->ncells * (size_t)f->width;
    double tol = precision > 0 ? 1e-5 : 0.0;
    for (size_t i = 0; i < nv; i++)
        if (fabs(g.v[i] - f->v[i]) > tol * fabs(f->v[i])) {
            fprintf(stderr, "bench_io: %s %s: value %zu read back as %.17g, written %.17g\n", f->name,
                    label, i, g.v[i], f->v[i]);
            exit(1);
        }
    field_free(&g);
    snprintf(name, sizeof name, "%s_%s_write", f->name, label);
    report(name, (double)bytes, *t_write, c_write);
    snprintf(name, sizeof name, "%s_%s_read", f->name, label);
    report(name, (double)bytes, *t_read, c_read);
    io_rm_rf(path, &e);
    free(path);
    return bytes;
}

/* The baseline: the same byte count copied out of and into the array. */
static void bench_copy(const Field *f, const char *dir, size_t bytes, double *t_write, double *t_read)
{
    Err e;
    char name[128];
    char *path = io_join(dir, "raw");
    size_t nv = (size_t)f->ncells * (size_t)f->width;
    size_t payload = nv * sizeof(double);
    Buf b;
    buf_init(&b);
    double t0 = now(), c0 = cpu_now();
    buf_reserve(&b, bytes);
    buf_put(&b, f->v, payload);
    memset(b.p + b.n, ' ', bytes - payload);   /* header-sized padding */
    b.n = bytes;
    if (io_write_atomic(path, b.p, b.n, 0, &e) != 0) die(&e);
    *t_write = now() - t0;
    double c_write = cpu_now() - c0;
    buf_free(&b);

    buf_init(&b);
    t0 = now();
    c0 = cpu_now();
    double *v = mem_alloc(payload);
    if (io_read_file(path, &b, NULL, &e) != 0) die(&e);
    memcpy(v, b.p, payload);
    *t_read = now() - t0;
    double c_read = cpu_now() - c0;
    if (memcmp(v, f->v, payload) != 0) {
        fprintf(stderr, "bench_io: raw copy differs\n");
        exit(1);
    }
    buf_free(&b);
    free(v);
    snprintf(name, sizeof name, "%s_copy_write", f->name);
    report(name, (double)bytes, *t_write, c_write);
    snprintf(name, sizeof name, "%s_copy_read", f->name);
    report(name, (double)bytes, *t_read, c_read);
    io_rm_rf(path, &e);
    free(path);
}

static void bench_field(const Mesh *m, const char *dir, const char *name, int width)
{
    Field f;
    double zero[3] = {0, 0, 0};
    field_init(&f, m, name, width, zero, "calculated");
    size_t nv = (size_t)f.ncells * (size_t)width;
    for (size_t i = 0; i < nv; i++) f.v[i] = random_value();
    for (int p = 0; p < f.npatches; p++)
        if (f.pf[p].value)
            for (size_t i = 0; i < (size_t)f.pf[p].n * (size_t)width; i++) f.pf[p].value[i] = random_value();

    double bw, br, cw, cr, aw, ar;
    size_t bytes = bench_format(&f, m, dir, "binary", 1, 0, &bw, &br);
    bench_copy(&f, dir, bytes, &cw, &cr);
    printf("RATIO %s_binary_write %.2f\n", name, bw / cw);
    printf("RATIO %s_binary_read %.2f\n", name, br / cr);
    bench_format(&f, m, dir, "ascii6", 0, 6, &aw, &ar);
    bench_format(&f, m, dir, "asciiFull", 0, 0, &aw, &ar);
    field_free(&f);
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: bench_io SCRATCH_DIR [NCELLS]\n");
        return 2;
    }
    int ncells = argc > 2 ? atoi(argv[2]) : 8000000;
    if (ncells < 8) {
        fprintf(stderr, "bench_io: NCELLS must be at least 8\n");
        return 2;
    }
    Err e;
    if (io_mkdir_p(argv[1], &e) != 0) die(&e);
    bench_first_touch();
    Mesh m;
    shell_mesh(&m, ncells);
    bench_field(&m, argv[1], "T", 1);
    bench_field(&m, argv[1], "U", 3);
    mesh_free(&m);
    return 0;
}
