/*
** bench_parse.c: ascii parsing speed of big numeric lists via dict_parse.
**
**     bench_parse [NUMBERS]        (default 8000000 numbers per list)
**
** Builds, in memory, dictionaries holding one big list as solvers write
** them: "values N ( x x ... );" of scalars and "values N ( (x y z) ... );"
** of vectors, each once at precision 6 and once at full precision
** (shortest exact, foam_fmt_double with precision 0).  The numbers are
** pseudo-random with all digits significant, so the full-precision text is
** the slow case for the number parser.  The parsed list is checked
** against the numbers written.
**
** Each text is parsed twice.  The first ("cold") run pays for faulting in
** the fresh pages of the parsed arrays, which on a virtual machine with
** lazily backed memory can cost more than the parsing; glibc is told to
** keep freed memory (mallopt), so the second ("warm") run reuses those
** pages and measures the parser itself, as in a tool that reads many
** files.  Both are reported, with wall and CPU time.
**
** Output: "PARSE <name>_<cold|warm> <megabytes> <wall s> <MB/s> <cpu s>".
*/
#include <malloc.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "buf.h"
#include "dict.h"
#include "foam.h"
#include "mem.h"

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

static uint64_t rng = 0x2545F4914F6CDD1Dull;

static double random_value(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return -5e2 + 1e3 * (double)(rng >> 11) / 9007199254740992.0;
}

static void check(const Dict *d, const double *v, size_t n, int width, int precision, const char *name)
{
    Err e;
    /* "values N ( ... );" is two value nodes: the count and the list */
    const DictEntry *en = dict_find(d, "values");
    const DictNode *nd = en && en->nvals ? en->vals[en->nvals - 1] : NULL;
    double *got = NULL;
    size_t m = 0;
    if (!nd || dict_node_scalars(nd, width, &got, &m, &e) != 0 || m != n / (size_t)width) {
        fprintf(stderr, "bench_parse: %s: list not read back (%zu items)\n", name, m);
        exit(1);
    }
    double tol = precision > 0 ? 1e-5 : 0.0;
    for (size_t i = 0; i < n; i++)
        if (fabs(got[i] - v[i]) > tol * fabs(v[i])) {
            fprintf(stderr, "bench_parse: %s: item %zu read as %.17g, written %.17g\n", name, i, got[i], v[i]);
            exit(1);
        }
    free(got);
}

static void bench_list(const double *v, size_t n, int width, int precision, const char *name)
{
    Buf b;
    Err e;
    buf_init(&b);
    foam_header(&b, "dictionary", NULL, "values", 0, NULL);
    buf_puts(&b, "values ");
    foam_put_scalars(&b, v, n / (size_t)width, width, 0, precision);
    buf_puts(&b, ";\n");
    static const char *const runs[2] = {"cold", "warm"};
    for (int run = 0; run < 2; run++) {
        double t0 = now(), c0 = cpu_now();
        Dict *d = dict_parse(b.p, b.n, name, &e);
        double t = now() - t0, c = cpu_now() - c0;
        if (!d) {
            fprintf(stderr, "bench_parse: %s\n", e.msg);
            exit(1);
        }
        if (run == 0) check(d, v, n, width, precision, name);
        dict_free(d);
        printf("PARSE %s_%s %.1f %.3f %.1f %.3f\n", name, runs[run], (double)b.n / 1e6, t,
               (double)b.n / 1e6 / t, c);
        fflush(stdout);
    }
    buf_free(&b);
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? (size_t)atol(argv[1]) : 8000000;
    n -= n % 3;
    if (n < 3) {
        fprintf(stderr, "usage: bench_parse [NUMBERS >= 3]\n");
        return 2;
    }
    mallopt(M_MMAP_MAX, 0);               /* big blocks from the heap ... */
    mallopt(M_TRIM_THRESHOLD, -1);        /* ... which is never given back */
    double *v = mem_alloc(n * sizeof(double));
    for (size_t i = 0; i < n; i++) v[i] = random_value();
    bench_list(v, n, 1, 6, "scalars_ascii6");
    bench_list(v, n, 1, 0, "scalars_asciiFull");
    bench_list(v, n, 3, 6, "vectors_ascii6");
    bench_list(v, n, 3, 0, "vectors_asciiFull");
    free(v);
    return 0;
}
