/*
** fuzz_mesh.c: libFuzzer harness for the polyMesh reader
** (mesh_read_stream: the "@file <name> <nbytes>" stream form that the grid
** tools pipe to each other; each file may be ascii, binary or gzipped).
**
** mesh_read_stream promises sizes and index ranges are checked, so on
** success everything that only needs those (mesh_cell_faces,
** mesh_geometry, mesh_bounds, mesh_face_patch, mesh_empty_axis,
** mesh_cell_spacing) must run cleanly even when mesh_check rejects the
** ordering.  The oracle beyond "no crash, no leak, no UB": a mesh that was
** read must write back (mesh_write_stream, ascii and binary) into a stream
** that reads again with the same counts.  FUZZ_NO_ROUNDTRIP=1 switches
** that check off.
**
** Build: tests/fuzz/run (clang -fsanitize=fuzzer,address,undefined).
*/
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "mesh.h"

static void fail(const char *what, const char *msg)
{
    fprintf(stderr, "%s: %s\n", what, msg);
    abort();
}

static void same_counts(const Mesh *a, const Mesh *b, const char *how)
{
    if (a->npoints != b->npoints || a->nfaces != b->nfaces || a->ninternal != b->ninternal ||
        a->ncells != b->ncells || a->npatches != b->npatches)
        fail(how, "counts differ after write and re-read");
    for (int p = 0; p < a->npatches; p++)
        if (a->patches[p].start != b->patches[p].start || a->patches[p].size != b->patches[p].size ||
            strcmp(a->patches[p].name, b->patches[p].name) != 0 ||
            strcmp(a->patches[p].type, b->patches[p].type) != 0)
            fail(how, "patches differ after write and re-read");
}

static void roundtrip(const Mesh *m, int binary)
{
    Err e;
    Buf b;
    Mesh m2;
    MeshWriteOpts o = {binary, 0};
    const char *how = binary ? "binary round trip" : "ascii round trip";
    buf_init(&b);
    mesh_init(&m2);
    if (mesh_write_stream(m, &b, &o, &e) != 0) fail(how, e.msg);
    if (mesh_read_stream(&m2, b.p, b.n, "roundtrip", &e) != 0) fail(how, e.msg);
    same_counts(m, &m2, how);
    mesh_free(&m2);
    buf_free(&b);
}

static void exercise(Mesh *m)
{
    Err e;
    double lo[3], hi[3], h[3];
    (void)mesh_check(m, &e);
    mesh_cell_faces(m);
    mesh_geometry(m);
    mesh_bounds(m, lo, hi);
    (void)mesh_empty_axis(m);
    for (int p = 0; p < m->npatches; p++) (void)mesh_patch(m, m->patches[p].name);
    if (m->nfaces > 0) {
        (void)mesh_face_patch(m, 0);
        (void)mesh_face_patch(m, m->nfaces - 1);
    }
    if (m->ncells > 0) {
        (void)mesh_cell_spacing(m, 0, h);
        (void)mesh_cell_spacing(m, m->ncells - 1, h);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int no_roundtrip = -1;
    if (no_roundtrip < 0) no_roundtrip = getenv("FUZZ_NO_ROUNDTRIP") != NULL;
    Err e;
    Mesh m;
    e.msg[0] = '\0';
    mesh_init(&m);
    if (mesh_read_stream(&m, (const char *)data, size, "fuzz", &e) != 0) {
        if (!e.msg[0]) fail("mesh_read_stream", "failed without a message");
        mesh_free(&m);
        return 0;
    }
    exercise(&m);
    if (!no_roundtrip) {
        roundtrip(&m, 0);
        roundtrip(&m, 1);
    }
    mesh_free(&m);
    return 0;
}
