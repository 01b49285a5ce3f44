/*
** bench_stream.c: the memory bandwidth of one core, STREAM's way (McCalpin:
** copy, scale, add, triad over three arrays of doubles), for the roofline
** of solveGranular's step (doc/performance.md, "Roofline").
**
**     bench_stream [MB]     (MB per array; default: the arrays together
**                            four times the last-level cache, at least
**                            3 x 128 MB, at most 3 x 1024 MB)
**
** Bytes are counted as STREAM counts them: 16 per element for copy and
** scale (one read, one write), 24 for add and triad; the write-allocate
** read of the stored line is not counted, so the numbers compare with
** published STREAM results and with a byte count of a code that counts
** each array it writes once.  Each kernel runs NTIMES times; the best
** time is reported (STREAM's rule), after the pages were touched once.
** The arrays are checked afterwards against the same sequence done on
** scalars.  (On a virtual machine the last-level cache sysfs reports is
** the host's, shared with other guests: on the 2-core VM of
** doc/performance.md a triad over 48 MB already runs at the memory's
** speed, so a multiple of the reported size is safely beyond it.)
**
** Output lines: "STREAM <kernel> <MB per array> <best s> <MB/s>".  One
** thread: run it pinned (taskset -c 0) on an otherwise idle machine.
*/
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define NTIMES 10

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The last-level cache in bytes (sysfs), or 32 MB when it cannot be read. */
static double llc_bytes(void)
{
    double best = 0;
    for (int i = 0; i < 8; i++) {
        char path[96], unit = 0;
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", i);
        FILE *f = fopen(path, "r");
        if (!f) continue;
        double v = 0;
        if (fscanf(f, "%lf%c", &v, &unit) >= 1) {
            v *= unit == 'K' ? 1024.0 : unit == 'M' ? 1048576.0 : 1.0;
            if (v > best) best = v;
        }
        fclose(f);
    }
    return best > 0 ? best : 32.0 * 1048576.0;
}

typedef struct Arrays {
    double *a, *b, *c;
    size_t n;
} Arrays;

/* The four kernels once; t[k] keeps each one's best time. */
static void kernels(Arrays *x, double s, double t[4])
{
    double *restrict a = x->a, *restrict b = x->b, *restrict c = x->c, t0;
    size_t n = x->n;
    t0 = now();
    for (size_t j = 0; j < n; j++) c[j] = a[j];
    t0 = now() - t0, t[0] = t0 < t[0] ? t0 : t[0];
    t0 = now();
    for (size_t j = 0; j < n; j++) b[j] = s * c[j];
    t0 = now() - t0, t[1] = t0 < t[1] ? t0 : t[1];
    t0 = now();
    for (size_t j = 0; j < n; j++) c[j] = a[j] + b[j];
    t0 = now() - t0, t[2] = t0 < t[2] ? t0 : t[2];
    t0 = now();
    for (size_t j = 0; j < n; j++) a[j] = b[j] + s * c[j];
    t0 = now() - t0, t[3] = t0 < t[3] ? t0 : t[3];
}

/* STREAM's check: the values every element must hold after ntimes
   rounds from a = 1, b = 2, c = 0. */
static int check(const Arrays *x, double s, int ntimes)
{
    double a = 1, b = 2, c = 0;
    for (int k = 0; k < ntimes; k++) {
        c = a;
        b = s * c;
        c = a + b;
        a = b + s * c;
    }
    for (size_t j = 0; j < x->n; j += x->n / 97 + 1)
        if (x->a[j] != a || x->b[j] != b || x->c[j] != c) return -1;
    return 0;
}

/* Runs the kernels on three arrays of mb megabytes; t[4] the best times. */
static int run(double mb, double t[4])
{
    Arrays x;
    x.n = (size_t)(mb * 1048576.0 / sizeof(double));
    x.a = malloc(x.n * sizeof(double));
    x.b = malloc(x.n * sizeof(double));
    x.c = malloc(x.n * sizeof(double));
    if (!x.a || !x.b || !x.c) {
        fprintf(stderr, "bench_stream: cannot allocate 3 x %.0f MB\n", mb);
        return -1;
    }
    for (size_t j = 0; j < x.n; j++) x.a[j] = 1, x.b[j] = 2, x.c[j] = 0;
    const double s = 3;
    for (int k = 0; k < 4; k++) t[k] = 1e30;
    for (int k = 0; k < NTIMES; k++) kernels(&x, s, t);
    int bad = check(&x, s, NTIMES);
    free(x.a);
    free(x.b);
    free(x.c);
    if (bad) fprintf(stderr, "bench_stream: wrong values after the kernels\n");
    return bad;
}

int main(int argc, char **argv)
{
    double mb = argc > 1 ? atof(argv[1]) : 4 * llc_bytes() / 1048576.0 / 3;
    if (argc <= 1) mb = mb < 128 ? 128 : mb > 1024 ? 1024 : mb;
    if (!(mb > 0)) {
        fprintf(stderr, "usage: bench_stream [MB per array]\n");
        return 2;
    }
    static const char *const name[4] = {"copy", "scale", "add", "triad"};
    static const double words[4] = {2, 2, 3, 3};
    double t[4];
    if (run(mb, t)) return 1;
    for (int k = 0; k < 4; k++)
        printf("STREAM %s %.0f %.6f %.0f\n", name[k], mb, t[k], words[k] * mb / t[k]);
    return 0;
}
