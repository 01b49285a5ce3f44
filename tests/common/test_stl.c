/*
** test_stl.c: STL reading and writing: ascii, binary and gzip round trips
** (exact for ascii, float32 for binary), multi-solid ascii files as real
** exporters write them, and malformed files, which must give a message
** naming the file (and the line for ascii) and never crash.
*/
#include "test.h"

#include <ctype.h>
#include <stdint.h>

#include "buf.h"
#include "io.h"
#include "mem.h"
#include "stl.h"
#include "trisurf.h"

/* The 12 outward triangles of the unit cube, each face a tag 0..5. */
static void cube(TriSurf *s, int tagged)
{
    double xyz[108];
    int tag[12], n = 0;
    for (int a = 0; a < 3; a++)
        for (int sd = 0; sd < 2; sd++) {
            int u = (a + 1) % 3, v = (a + 2) % 3;
            static const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            double q[4][3];
            for (int c = 0; c < 4; c++) {
                int k = sd ? c : 3 - c;
                q[c][a] = sd;
                q[c][u] = uv[k][0];
                q[c][v] = uv[k][1];
            }
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int t = 0; t < 2; t++, n++) {
                tag[n] = 2 * a + sd;
                for (int m = 0; m < 3; m++) memcpy(xyz + 9 * n + 3 * m, q[tri[t][m]], 3 * sizeof(double));
            }
        }
    trisurf_from_soup(s, xyz, 12, tagged ? tag : NULL);
}

/* A rotated, shifted cube: coordinates that are not floats. */
static void odd_cube(TriSurf *s)
{
    cube(s, 0);
    double c = cos(0.3), n = sin(0.3);
    double A[9] = {c, -n, 0, n, c, 0, 0, 0, 1}, b[3] = {0.1, 1.0 / 3, -2.7};
    trisurf_transform(s, A, b);
}

static char *tmp(const char *name)
{
    return io_join(test_tmpdir(), name);
}

/* Same triangles, corner for corner; as_float compares with the corners
   of a rounded to float. */
static int same_surface(const TriSurf *a, const TriSurf *b, int as_float)
{
    if (a->ntris != b->ntris || a->npoints != b->npoints) return 0;
    for (int t = 0; t < a->ntris; t++)
        for (int m = 0; m < 3; m++)
            for (int k = 0; k < 3; k++) {
                double x = a->points[3 * a->tris[3 * t + m] + k], y = b->points[3 * b->tris[3 * t + m] + k];
                if (as_float) x = (float)x;
                if (x != y) return 0;
            }
    return 1;
}

TEST(ascii_round_trip_exact)
{
    TriSurf s, r;
    odd_cube(&s);
    char *p = tmp("odd.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 0, &e) == 0, "write: %s", e.msg);
    EXPECT(stl_read(&r, p, &e) == 0, "read: %s", e.msg);
    EXPECT(same_surface(&s, &r, 0), "ascii round trip is not exact");
    EXPECT(r.nnames == 1 && r.tag && r.tag[11] == 0, "one solid, tag %d", r.tag ? r.tag[11] : -1);
    TriTopo t;
    trisurf_check(&r, &t);
    NEAR(t.volume, 1.0, 1e-14);
    trisurf_free(&s);
    trisurf_free(&r);
    free(p);
}

TEST(ascii_tags_round_trip)
{
    TriSurf s, r;
    cube(&s, 1);
    s.nnames = 6;
    s.names = mem_alloc(6 * sizeof *s.names);
    static const char *nm[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    for (int i = 0; i < 6; i++) s.names[i] = mem_strdup(nm[i]);
    char *p = tmp("tags.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 0, &e) == 0, "write: %s", e.msg);
    EXPECT(stl_read(&r, p, &e) == 0, "read: %s", e.msg);
    EXPECT(r.ntris == 12 && r.npoints == 8 && r.nnames == 6, "ntris %d npoints %d nnames %d", r.ntris, r.npoints,
           r.nnames);
    for (int i = 0; i < 6 && r.nnames == 6; i++) EXPECT(strcmp(r.names[i], nm[i]) == 0, "name %d %s", i, r.names[i]);
    for (int t = 0; t < 12 && r.tag; t++) EXPECT(r.tag[t] == t / 2, "tag of %d: %d", t, r.tag[t]);
    TriTopo tp;
    trisurf_check(&r, &tp);
    EXPECT(tp.nopen == 0 && tp.nflipped == 0, "solids weld into one closed surface: open %d", tp.nopen);
    trisurf_free(&s);
    trisurf_free(&r);
    free(p);
}

TEST(binary_round_trip)
{
    TriSurf s, r;
    odd_cube(&s);
    char *p = tmp("odd_bin.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 1, &e) == 0, "write: %s", e.msg);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0, "%s", e.msg);
    EXPECT(b.n == 84 + 50 * 12, "binary size %zu", b.n);
    EXPECT(b.n < 5 || memcmp(b.p, "solid", 5) != 0, "binary header starts with solid");
    buf_free(&b);
    EXPECT(stl_read(&r, p, &e) == 0, "read: %s", e.msg);
    EXPECT(same_surface(&s, &r, 1), "binary round trip differs from the float-rounded corners");
    EXPECT(r.tag == NULL && r.nnames == 0, "binary STL has no solids");
    trisurf_free(&r);
    trisurf_free(&s);
    /* the unit cube is exact in float */
    cube(&s, 0);
    EXPECT(stl_write(&s, p, 1, &e) == 0, "write: %s", e.msg);
    EXPECT(stl_read(&r, p, &e) == 0, "read: %s", e.msg);
    EXPECT(same_surface(&s, &r, 0), "unit cube binary round trip not exact");
    trisurf_free(&r);
    trisurf_free(&s);
    free(p);
}

TEST(gzip_round_trip)
{
    TriSurf s, r;
    odd_cube(&s);
    Err e = {0};
    for (int binary = 0; binary < 2; binary++) {
        char *p = tmp(binary ? "g_bin.stl.gz" : "g_asc.stl.gz");
        EXPECT(stl_write(&s, p, binary, &e) == 0, "write: %s", e.msg);
        FILE *f = fopen(p, "rb");
        unsigned char m[2] = {0, 0};
        if (f) {
            EXPECT(fread(m, 1, 2, f) == 2, "short file");
            fclose(f);
        }
        EXPECT(m[0] == 0x1f && m[1] == 0x8b, "%s is not gzip", p);
        EXPECT(stl_read(&r, p, &e) == 0, "read: %s", e.msg);
        EXPECT(same_surface(&s, &r, binary), "gzip round trip (binary %d)", binary);
        trisurf_free(&r);
        /* the name without .gz finds the gzipped file */
        p[strlen(p) - 3] = '\0';
        EXPECT(stl_read(&r, p, &e) == 0, "read without .gz: %s", e.msg);
        EXPECT(r.ntris == 12, "ntris %d", r.ntris);
        trisurf_free(&r);
        free(p);
    }
    trisurf_free(&s);
}

/* Two solids in the styles of different exporters: upper-case keywords,
   tabs, CRLF line ends, a facet without normal, a "nan" normal, names
   with spaces, a repeated name, an unnamed solid, several tokens per line. */
static const char multi[] =
    "solid part one\r\n"
    "  facet normal 0 0 -1\r\n"
    "    outer loop\r\n"
    "      vertex 0 0 0\r\n"
    "      vertex 0 1 0\r\n"
    "      vertex 1 0 0\r\n"
    "    endloop\r\n"
    "  endfacet\r\n"
    "endsolid part one\r\n"
    "SOLID Lid\n"
    "\tFACET NORMAL nan nan nan\n"
    "\t\tOUTER LOOP\n"
    "\t\t\tVERTEX 0 0 0\n"
    "\t\t\tVERTEX 1 0 0\n"
    "\t\t\tVERTEX 0 0 1\n"
    "\t\tENDLOOP\n"
    "\tENDFACET\n"
    "ENDSOLID\n"
    "solid part one\n"
    "facet outer loop vertex 0 0 0 vertex 0 0 1 vertex 0 1 0 endloop endfacet\n"
    "endsolid\n"
    "solid\n"
    "facet normal 1 1 1 outer loop\n"
    " vertex 1e0 0 0\n vertex +0.0 1.0E+00 0\n vertex 0 0 1.\n"
    "endloop endfacet\n"
    "endsolid   \n";

TEST(ascii_multi_solid)
{
    TriSurf s;
    Err e = {0};
    EXPECT(stl_parse(&s, multi, sizeof multi - 1, "multi.stl", &e) == 0, "parse: %s", e.msg);
    EXPECT(s.ntris == 4 && s.npoints == 4, "ntris %d npoints %d", s.ntris, s.npoints);
    EXPECT(s.nnames == 3, "nnames %d", s.nnames);
    if (s.nnames == 3 && s.tag) {
        EXPECT(strcmp(s.names[0], "part one") == 0, "name 0 '%s'", s.names[0]);
        EXPECT(strcmp(s.names[1], "Lid") == 0, "name 1 '%s'", s.names[1]);
        EXPECT(strcmp(s.names[2], "solid3") == 0, "name 2 '%s'", s.names[2]);
        EXPECT(s.tag[0] == 0 && s.tag[1] == 1 && s.tag[2] == 0 && s.tag[3] == 2, "tags %d %d %d %d", s.tag[0],
               s.tag[1], s.tag[2], s.tag[3]);
    }
    /* the four facets close a tetrahedron, outward */
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 0 && t.nflipped == 0, "open %d flipped %d", t.nopen, t.nflipped);
    NEAR(t.volume, 1.0 / 6, 1e-16);
    trisurf_free(&s);
    /* a name may hold words of the grammar that cannot start a facet */
    static const char one[] = "solid outer wall loop\nfacet outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 "
                              "endloop endfacet endsolid outer wall loop\n";
    EXPECT(stl_parse(&s, one, sizeof one - 1, "one.stl", &e) == 0, "parse: %s", e.msg);
    EXPECT(s.ntris == 1 && s.nnames == 1 && strcmp(s.names[0], "outer wall loop") == 0, "name '%s'",
           s.nnames ? s.names[0] : "");
    trisurf_free(&s);
}

/* A binary file whose header starts with "solid" (SolidWorks does that) is
   still binary, by its size. */
TEST(binary_header_solid)
{
    TriSurf s, r;
    cube(&s, 0);
    char *p = tmp("sw.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 1, &e) == 0, "write: %s", e.msg);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0, "%s", e.msg);
    memcpy(b.p, "solid part", 10);
    EXPECT(stl_parse(&r, b.p, b.n, p, &e) == 0, "parse: %s", e.msg);
    EXPECT(r.ntris == 12, "ntris %d", r.ntris);
    trisurf_free(&r);
    buf_free(&b);
    trisurf_free(&s);
    free(p);
}

static int fails_with(const char *text, size_t n, const char *want)
{
    TriSurf s;
    Err e = {0};
    int rc = stl_parse(&s, text, n, "bad.stl", &e);
    int ok = rc == -1 && strstr(e.msg, want) && s.ntris == 0 && s.points == NULL;
    if (!ok) printf("  got rc %d, message \"%s\", expected \"%s\"\n", rc, e.msg, want);
    trisurf_free(&s);
    return ok;
}

TEST(malformed)
{
    EXPECT(fails_with("", 0, "bad.stl: empty file"), "empty file");
    EXPECT(fails_with("hello", 5, "bad.stl: not an STL file"), "garbage");
    static const char kw[] = "solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                             "   vertex 1 0 0\n   vertx 0 1 0\n";
    EXPECT(fails_with(kw, sizeof kw - 1, "bad.stl:6: expected 'vertex', found 'vertx'"), "bad keyword");
    static const char num[] = "solid a\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1.0.0 0\n";
    EXPECT(fails_with(num, sizeof num - 1, "bad.stl:6: bad number '1.0.0'"), "bad number");
    static const char inf[] = "solid a\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 inf\n";
    EXPECT(fails_with(inf, sizeof inf - 1, "bad.stl:5: non-finite coordinate"), "inf");
    static const char noend[] = "solid a\nfacet outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet\n";
    EXPECT(fails_with(noend, sizeof noend - 1, "bad.stl:2: unexpected end of file: missing 'endsolid'"),
           "missing endsolid");
    static const char cut[] = "solid a\nfacet outer loop vertex 0 0 0 vertex 1 0";
    EXPECT(fails_with(cut, sizeof cut - 1, "bad.stl:2: unexpected end of file, expected a coordinate"),
           "cut in a vertex");
    static const char junk[] = "solid a\nendsolid a\ngarbage\n";
    EXPECT(fails_with(junk, sizeof junk - 1, "bad.stl:3: expected 'solid', found 'garbage'"), "junk after");
    static const char none[] = "solid a\nendsolid a\n";
    EXPECT(fails_with(none, sizeof none - 1, "bad.stl: no triangles"), "no triangles");
    static const char many[] = "solid a\nfacet outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 vertex 1 1 1\n";
    EXPECT(fails_with(many, sizeof many - 1, "bad.stl:2: expected 'endloop', found 'vertex'"), "four vertices");
}

/* Issue 9 item 8: the facet normal was skipped as any three tokens, so
   garbage there was accepted or reported as a confusing missing 'outer';
   every number of the ascii grammar is now strictly decimal. */
static char *facet_with(char *buf, size_t n, const char *normal, const char *v2)
{
    snprintf(buf, n, "solid a\nfacet %s\nouter loop\nvertex 0 0 0\nvertex %s\nvertex 0 1 0\n"
             "endloop\nendfacet\nendsolid a\n", normal, v2);
    return buf;
}

TEST(strict_numbers)
{
    char t[512];
    struct {
        const char *normal, *v2, *want;
    } bad[] = {
        {"normal 0 0 x", "1 0 0", "bad.stl:2: bad number 'x', expected a component of the facet normal"},
        {"normal 1 2", "1 0 0", "bad.stl:3: bad number 'outer', expected a component of the facet normal"},
        {"normal 0 0 1 junk", "1 0 0", "bad.stl:2: expected 'outer', found 'junk'"},
        {"normal 0 0 1 0", "1 0 0", "bad.stl:2: expected 'outer', found '0'"},
        {"normal 0 0 1e", "1 0 0", "bad.stl:2: bad number '1e'"},
        {"normal 0 0 0x1", "1 0 0", "bad.stl:2: bad number '0x1'"},
        {"normal 0 0 1", "0x1p0 0 0", "bad.stl:5: bad number '0x1p0', expected a coordinate"},
        {"normal 0 0 1", "1,0 0 0", "bad.stl:5: bad number '1,0'"},
        {"normal 0 0 1", "1 0 0 0", "bad.stl:5: expected 'vertex', found '0'"},
        {"normal 0 0 1", "1 0", "bad.stl:6: bad number 'vertex', expected a coordinate"},
        {"normal 0 0 1", "nan 0 0", "bad.stl:5: non-finite coordinate 'nan'"},
        {"normal 0 0 1", "1 -inf 0", "bad.stl:5: non-finite coordinate '-inf'"},
        {"normal 0 0 1", "1 0 1e999", "bad.stl:5: non-finite coordinate '1e999'"},
        {"normal 0 0 1", "1 0 infinity", "bad.stl:5: non-finite coordinate 'infinity'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        facet_with(t, sizeof t, bad[i].normal, bad[i].v2);
        EXPECT(fails_with(t, strlen(t), bad[i].want), "case %zu: %s / %s", i, bad[i].normal, bad[i].v2);
    }
    /* what exporters really write is still read: non-finite normals
       (glibc's -nan, old MSVC's -1.#IND00), signs, "5." and ".5" */
    static const char *const good[] = {"normal nan nan nan", "normal -nan NaN INF", "normal -1.#IND00 1.#QNAN0 1.#INF",
                                       "normal -1.#IND00e+000 0 0", "normal +0 -0. .5", "normal 1E-3 -2e+2 3.e1", ""};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        TriSurf s;
        Err e = {0};
        facet_with(t, sizeof t, good[i], "1. +0 -.0e0");
        EXPECT(stl_parse(&s, t, strlen(t), "good.stl", &e) == 0 && s.ntris == 1, "'%s': %s", good[i], e.msg);
        trisurf_free(&s);
    }
}

TEST(malformed_binary)
{
    TriSurf s;
    cube(&s, 0);
    char *p = tmp("t.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 1, &e) == 0, "write: %s", e.msg);
    trisurf_free(&s);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0, "%s", e.msg);
    EXPECT(fails_with(b.p, b.n - 10, "bad.stl: binary STL of 12 triangles needs 684 bytes but the file has 674"),
           "truncated binary");
    /* a NaN corner */
    unsigned char nan[4] = {0, 0, 0xc0, 0x7f};
    memcpy(b.p + 84 + 50 * 3 + 12 + 4, nan, 4);
    EXPECT(fails_with(b.p, b.n, "bad.stl: binary STL triangle 4 has a non-finite coordinate"), "NaN");
    /* zero triangles */
    memset(b.p + 80, 0, 4);
    EXPECT(fails_with(b.p, 84, "no triangles"), "empty binary");
    buf_free(&b);
    TriSurf r;
    char *q = tmp("absent.stl");
    EXPECT(stl_read(&r, q, &e) == -1 && strstr(e.msg, "absent.stl"), "absent file: %s", e.msg);
    trisurf_free(&r);
    free(q);
    free(p);
}

TEST(write_errors)
{
    TriSurf s;
    cube(&s, 0);
    s.points[0] = 1e300;
    char *p = tmp("big.stl");
    Err e = {0};
    EXPECT(stl_write(&s, p, 1, &e) == -1, "1e300 written as float");
    CONTAINS(e.msg, "does not fit a binary STL");
    EXPECT(!io_exists(p), "a failed write left a file");
    EXPECT(stl_write(&s, "/nonexistent-dir/x.stl", 0, &e) == -1, "write into a missing directory");
    trisurf_free(&s);
    free(p);
}

static int strncasecmp_ascii(const char *a, const char *kw)
{
    for (; *kw; a++, kw++)
        if (tolower((unsigned char)*a) != *kw) return 1;
    return 0;
}

/* Every prefix of a valid file and every single-byte change of it parse
   or fail with a message naming the file; none may crash (run under ASan). */
TEST(truncations_and_mutations)
{
    size_t n = sizeof multi - 1;
    char *buf = mem_alloc(n + 1);
    int ok = 0, lost = 0, unnamed = 0;
    for (size_t k = 0; k <= n; k++) {
        memcpy(buf, multi, k);
        TriSurf s;
        Err e = {0};
        int rc = stl_parse(&s, buf, k, "m.stl", &e);
        if (rc == 0) {
            /* a prefix parses only when it ends in an endsolid line, with
               every facet it holds */
            int facets = 0;
            for (size_t i = 0; i + 8 <= k; i++) facets += strncasecmp_ascii(buf + i, "endfacet") == 0;
            ok++;
            if (s.ntris != facets) lost++;
        } else if (strncmp(e.msg, "m.stl:", 6) != 0)
            unnamed++;
        trisurf_free(&s);
    }
    EXPECT(ok >= 4 && lost == 0 && unnamed == 0,
           "prefixes: %d parsed, %d lost facets, %d messages without the file", ok, lost, unnamed);
    static const char subst[] = {'\0', ' ', '\n', 'x', '9', '-', 'e', '.'};
    for (size_t k = 0; k < n; k++)
        for (size_t q = 0; q < sizeof subst; q++) {
            memcpy(buf, multi, n);
            buf[k] = subst[q];
            TriSurf s;
            Err e = {0};
            int rc = stl_parse(&s, buf, n, "m.stl", &e);
            if (rc && strncmp(e.msg, "m.stl", 5) != 0) unnamed++;
            if (rc == 0 && (s.ntris != 4 || s.nnames < 1)) unnamed++;
            trisurf_free(&s);
        }
    EXPECT(unnamed == 0, "%d mutations gave a message without the file or a wrong surface", unnamed);
    free(buf);
}

int main(void)
{
    RUN(ascii_round_trip_exact);
    RUN(ascii_tags_round_trip);
    RUN(binary_round_trip);
    RUN(gzip_round_trip);
    RUN(ascii_multi_solid);
    RUN(binary_header_solid);
    RUN(malformed);
    RUN(strict_numbers);
    RUN(malformed_binary);
    RUN(write_errors);
    RUN(truncations_and_mutations);
    return test_summary();
}
