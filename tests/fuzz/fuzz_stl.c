/*
** fuzz_stl.c: libFuzzer harness for the STL reader (stl_parse: ascii with
** several solids, binary, either gzipped) and the surface queries that run
** on whatever it accepts.
**
** stl_parse promises a welded TriSurf with finite coordinates and valid
** point indices, so on success the topology check, orientation repair,
** bucket set-up and every query (inside, line classification, axis and
** oblique crossings, nearest triangle) must run cleanly whatever the
** triangles look like: degenerate, open, non-manifold, huge or tiny.
** The oracle beyond "no crash, no leak, no UB": crossings are returned
** in ascending order within [0, 1].
**
** Build: tests/fuzz/run (clang -fsanitize=fuzzer,address,undefined).
*/
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "stl.h"
#include "trisurf.h"

static void fail(const char *msg)
{
    fprintf(stderr, "fuzz_stl: %s\n", msg);
    abort();
}

static void check_sorted(const double *t, int n)
{
    for (int i = 0; i < n; i++) {
        if (!(t[i] >= 0 && t[i] <= 1)) fail("crossing outside [0, 1]");
        if (i && t[i] < t[i - 1]) fail("crossings not ascending");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    TriSurf s;
    Err e;
    if (stl_parse(&s, (const char *)data, size, "fuzz.stl", &e)) return 0;
    TriTopo tp;
    trisurf_check(&s, &tp);
    trisurf_drop_degenerate(&s);
    if (s.ntris > 0) {
        trisurf_check(&s, &tp);
        if (!tp.nopen && !tp.nnonmanifold) trisurf_orient(&s);
        if (trisurf_prepare(&s, &e) == 0) {
            double c[3], a[3], b[3], t[16], d;
            for (int k = 0; k < 3; k++) c[k] = 0.5 * (s.lo[k] + s.hi[k]);
            (void)trisurf_inside(&s, c);
            double xs[5];
            char in[5];
            for (int i = 0; i < 5; i++) xs[i] = s.lo[0] + (s.hi[0] - s.lo[0]) * i / 4;
            trisurf_classify_line(&s, 0, c, xs, 5, in);
            for (int k = 0; k < 3; k++) {
                a[k] = s.lo[k] - 1;
                b[k] = s.hi[k] + 1;
            }
            int n = trisurf_crossings(&s, a, b, t, NULL, 16);
            check_sorted(t, n < 16 ? n : 16);
            a[1] = b[1] = c[1];   /* along x through the centre */
            a[2] = b[2] = c[2];
            n = trisurf_crossings(&s, a, b, t, NULL, 16);
            check_sorted(t, n < 16 ? n : 16);
            (void)trisurf_nearest(&s, c, &d);
        }
    }
    trisurf_free(&s);
    return 0;
}
