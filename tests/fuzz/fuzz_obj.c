/*
** fuzz_obj.c: libFuzzer harness for the OBJ reader and the choice between
** OBJ and STL (surface_parse), and the surface queries that run on
** whatever they accept.
**
** The first byte picks the name the data is parsed under ("fuzz.obj" when
** odd, "fuzz.stl" otherwise), so both the name rule and the content rules
** of surface.h are reached; the rest is the file.  On success the surface
** must be usable as fuzz_stl.c uses it: finite coordinates, point indices
** in range (the topology check, orientation, buckets and queries run
** cleanly on whatever came out of the ear clipping).  Oracles beyond "no
** crash, no leak, no UB": every coordinate is finite, every index is a
** point, and the message of a failure names the file.
**
** Build: tests/fuzz/run (clang -fsanitize=fuzzer,address,undefined).
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"
#include "trisurf.h"

static void fail(const char *msg)
{
    fprintf(stderr, "fuzz_obj: %s\n", msg);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) return 0;
    const char *name = data[0] & 1 ? "fuzz.obj" : "fuzz.stl";
    TriSurf s;
    Err e;
    if (surface_parse(&s, (const char *)data + 1, size - 1, name, &e)) {
        if (strncmp(e.msg, name, strlen(name)) != 0) fail("failed without a message naming the file");
        return 0;
    }
    for (int i = 0; i < 3 * s.npoints; i++)
        if (!isfinite(s.points[i])) fail("accepted a non-finite value");
    for (int i = 0; i < 3 * s.ntris; i++)
        if (s.tris[i] < 0 || s.tris[i] >= s.npoints) fail("point index out of range");
    TriTopo tp;
    trisurf_drop_degenerate(&s);
    if (s.ntris > 0) {
        trisurf_check(&s, &tp);
        if (!tp.nopen && !tp.nnonmanifold) trisurf_orient(&s);
        if (trisurf_prepare(&s, &e) == 0) {
            double c[3], d;
            for (int k = 0; k < 3; k++) c[k] = 0.5 * (s.lo[k] + s.hi[k]);
            (void)trisurf_inside(&s, c);
            (void)trisurf_nearest(&s, c, &d);
        }
    }
    trisurf_free(&s);
    return 0;
}
