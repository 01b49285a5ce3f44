/*
** test_obj.c: Wavefront OBJ surfaces (obj.c) and the choice between OBJ
** and STL (surface.c).
**
** Measured: the unit cube of quadrangles (tests/data/obj/cube.obj, every
** corner form) closes with volume 1 to 1e-15; the L-shaped prism of
** non-convex hexagons (lprism.obj, negative indices) has volume 3 and
** every cap triangle faces the cap's way (a fan from the first corner
** would fold over the notch); ear clipping of planar polygons tilted in
** space gives n - 2 triangles whose unsigned areas add up to the
** polygon's area (1e-12), the fan itself for convex ones; a closed
** surface read as OBJ and as STL gives the same TriSurf and volume;
** gzip; malformed files give file:line messages; the OpenFOAM example
** surfaces read with one triangle per triangle of their faces (SKIP when
** the examples are not installed); no prefix or one-byte change of a
** file crashes the reader.
*/
#include "test.h"

#include <dirent.h>
#include <stdint.h>
#include <sys/stat.h>

#include "buf.h"
#include "fixture.h"
#include "io.h"
#include "mem.h"
#include "obj.h"
#include "stl.h"
#include "surface.h"
#include "trisurf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char *data_path(const char *name)
{
    const char *top = getenv("KIESEL_TOP");
    size_t n = strlen(top ? top : ".") + strlen(name) + 32;
    char *p = mem_alloc(n);
    snprintf(p, n, "%s/tests/data/%s", top ? top : ".", name);
    return p;
}

static char *tmp(const char *name) { return io_join(test_tmpdir(), name); }

static int parse(TriSurf *s, const char *text, Err *e) { return obj_parse(s, text, strlen(text), "t.obj", e); }

static double tri_area(const TriSurf *s, int t, const double nrm[3])
{
    const double *a = s->points + 3 * s->tris[3 * t], *b = s->points + 3 * s->tris[3 * t + 1],
                 *c = s->points + 3 * s->tris[3 * t + 2];
    double u[3], v[3], x[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    x[0] = u[1] * v[2] - u[2] * v[1];
    x[1] = u[2] * v[0] - u[0] * v[2];
    x[2] = u[0] * v[1] - u[1] * v[0];
    if (nrm) return 0.5 * (x[0] * nrm[0] + x[1] * nrm[1] + x[2] * nrm[2]);
    return 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

TEST(cube_quads)
{
    TriSurf s;
    Err e = {0};
    char *p = data_path("obj/cube.obj");
    EXPECT(obj_read(&s, p, &e) == 0, "%s", e.msg);
    EXPECT(s.ntris == 12 && s.npoints == 8, "ntris %d npoints %d", s.ntris, s.npoints);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 0 && t.nnonmanifold == 0 && t.nflipped == 0, "open %d nonmanifold %d flipped %d", t.nopen,
           t.nnonmanifold, t.nflipped);
    NEAR(t.volume, 1.0, 1e-15);
    NEAR(t.area, 6.0, 1e-15);
    static const char *nm[3] = {"bottom", "top", "sides"};
    EXPECT(s.nnames == 3 && s.tag, "nnames %d", s.nnames);
    for (int i = 0; i < 3 && s.nnames == 3; i++) EXPECT(strcmp(s.names[i], nm[i]) == 0, "name %d '%s'", i, s.names[i]);
    for (int i = 0; i < 12 && s.tag; i++) {
        int want = i < 2 ? 0 : i < 4 ? 1 : 2;
        EXPECT(s.tag[i] == want, "tag of triangle %d: %d, expected %d", i, s.tag[i], want);
    }
    /* the first quad "1 4 3 2" is the fan (1 4 3), (1 3 2) */
    if (s.ntris == 12) {
        const double *a = s.points + 3 * s.tris[0], *c = s.points + 3 * s.tris[2], *d = s.points + 3 * s.tris[5];
        EXPECT(a[0] == 0 && a[1] == 0 && c[0] == 1 && c[1] == 1 && d[0] == 1 && d[1] == 0,
               "quad not split as the fan from its first corner");
    }
    trisurf_free(&s);
    free(p);
}

/* The L prism: closed, volume 3, and both caps' triangles face the cap's
   normal (+z for the top, written first, -z for the bottom) with areas
   adding to 3. */
TEST(nonconvex_prism)
{
    TriSurf s;
    Err e = {0};
    char *p = data_path("obj/lprism.obj");
    EXPECT(obj_read(&s, p, &e) == 0, "%s", e.msg);
    EXPECT(s.ntris == 2 * 4 + 6 * 2 && s.npoints == 12, "ntris %d npoints %d", s.ntris, s.npoints);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 0 && t.nflipped == 0, "open %d flipped %d", t.nopen, t.nflipped);
    NEAR(t.volume, 3.0, 1e-15);
    double up[3] = {0, 0, 1}, abs_sum[2] = {0, 0}, min_signed = 1;
    for (int i = 0; i < 8 && s.ntris == 20; i++) {
        double sg = tri_area(&s, i, up) * (i < 4 ? 1 : -1);   /* top cap first */
        abs_sum[i / 4] += tri_area(&s, i, NULL);
        if (sg < min_signed) min_signed = sg;
    }
    EXPECT(min_signed > 0, "a cap triangle faces the wrong way (signed area %g): folded over the notch", min_signed);
    NEAR(abs_sum[0], 3.0, 1e-15);
    NEAR(abs_sum[1], 3.0, 1e-15);
    /* the inside test agrees: the notch is outside, the L inside */
    EXPECT(trisurf_prepare(&s, &e) == 0, "%s", e.msg);
    double notch[3] = {1.5, 1.5, 0.5}, in[3] = {0.5, 1.5, 0.5};
    EXPECT(!trisurf_inside(&s, notch) && trisurf_inside(&s, in), "inside test in the notch / the L");
    trisurf_free(&s);
    free(p);
}

/* One planar face with the 2-D corners q (n of them) placed on a tilted
   plane; returns 0 when triangulated into n - 2 triangles that do not
   overlap (unsigned areas add up to |area|) and keep the polygon's
   orientation. */
static int polygon_ok(const double *q, int n, int expect_fan)
{
    const double o[3] = {0.3, -1.7, 2.2};
    double u[3] = {0.36, 0.48, 0.8}, w[3] = {0.8, -0.6, 0}, nrm[3];
    nrm[0] = u[1] * w[2] - u[2] * w[1];
    nrm[1] = u[2] * w[0] - u[0] * w[2];
    nrm[2] = u[0] * w[1] - u[1] * w[0];
    Buf b;
    buf_init(&b);
    double area = 0;
    for (int i = 0; i < n; i++) {
        const double *a = q + 2 * i, *c = q + 2 * ((i + 1) % n);
        area += 0.5 * (a[0] * c[1] - a[1] * c[0]);
        buf_printf(&b, "v %.17g %.17g %.17g\n", o[0] + a[0] * u[0] + a[1] * w[0], o[1] + a[0] * u[1] + a[1] * w[1],
                   o[2] + a[0] * u[2] + a[1] * w[2]);
    }
    buf_puts(&b, "f");
    for (int i = 0; i < n; i++) buf_printf(&b, " %d", i + 1);
    buf_puts(&b, "\n");
    TriSurf s;
    Err e = {0};
    int rc = obj_parse(&s, b.p, b.n, "poly.obj", &e), bad = 0;
    double sum = 0, sgn = area > 0 ? 1 : -1;
    if (rc || s.ntris != n - 2) {
        printf("  %d corners: rc %d %s, %d triangles\n", n, rc, e.msg, rc ? 0 : s.ntris);
        bad = 1;
    }
    for (int t = 0; !bad && t < s.ntris; t++) {
        double a = tri_area(&s, t, nrm) * sgn;
        if (a < -1e-12 * fabs(area)) bad = 1;
        sum += tri_area(&s, t, NULL);
        if (expect_fan) {
            /* triangle t of the fan: corners 0, t + 1, t + 2 (welded
               point indices follow the corners' first appearance) */
            int *c = s.tris + 3 * t;
            if (c[0] != 0 || c[1] != t + 1 || c[2] != t + 2) bad = 1;
        }
    }
    if (!bad && fabs(sum - fabs(area)) > 1e-12 * fabs(area)) {
        printf("  %d corners: triangle areas add to %.17g, polygon area %.17g\n", n, sum, fabs(area));
        bad = 1;
    }
    trisurf_free(&s);
    buf_free(&b);
    return bad;
}

TEST(ear_clipping)
{
    static const double hexagon[] = {1, 0, 0.5, 0.87, -0.5, 0.87, -1, 0, -0.5, -0.87, 0.5, -0.87};
    static const double ell[] = {2, 0, 2, 1, 1, 1, 1, 2, 0, 2, 0, 0};
    static const double u_shape[] = {0, 0, 3, 0, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
    static const double comb[] = {0, 0, 7, 0, 7, 3, 6, 3, 6, 1, 5, 1, 5, 3, 4, 3, 4, 1, 3, 1, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
    static const double midpoints[] = {0, 0, 1, 0, 2, 0, 2, 1, 2, 2, 1, 2, 0, 2, 0, 1};
    static const double arrow[] = {4, 0, 0, 3, 1, 0, 0, -3};   /* reflex at (1, 0), first corner convex */
    double star[20], spiral[40], cw[12];
    for (int i = 0; i < 10; i++) {
        double r = i % 2 ? 0.4 : 1, a = 0.3 + 2 * M_PI * i / 10;
        star[2 * i] = r * cos(a);
        star[2 * i + 1] = r * sin(a);
    }
    for (int i = 0; i < 10; i++) {   /* a spiral strip: an outer and an inner arc */
        double a = 3.0 * i / 9;
        spiral[2 * i] = (1 + a) * cos(a);
        spiral[2 * i + 1] = (1 + a) * sin(a);
        spiral[38 - 2 * i] = (0.6 + a) * cos(a);
        spiral[39 - 2 * i] = (0.6 + a) * sin(a);
    }
    for (int i = 0; i < 6; i++) {   /* the L backwards: clockwise */
        cw[2 * i] = ell[10 - 2 * i];
        cw[2 * i + 1] = ell[11 - 2 * i];
    }
    EXPECT(!polygon_ok(hexagon, 6, 1), "convex hexagon (must be the fan)");
    EXPECT(!polygon_ok(ell, 6, 0), "L");
    EXPECT(!polygon_ok(cw, 6, 0), "clockwise L");
    EXPECT(!polygon_ok(u_shape, 8, 0), "U");
    EXPECT(!polygon_ok(comb, 16, 0), "comb");
    EXPECT(!polygon_ok(midpoints, 8, 0), "square with edge midpoints");
    EXPECT(!polygon_ok(arrow, 4, 0), "arrow");
    EXPECT(!polygon_ok(star, 10, 0), "star");
    EXPECT(!polygon_ok(spiral, 20, 0), "spiral");
}

TEST(negative_indices_and_forms)
{
    /* every face repeats its own corners and points at them backwards;
       faces come before the vertices they name; a statement continues
       over a backslash; CRLF, a byte-order mark, comments at line ends */
    static const char text[] =
        "\xEF\xBB\xBF# forward references\r\n"
        "f 1 2 \\\r\n  3\r\n"
        "v 0 0 0   # a comment\r\n"
        "v 1 0 0 0.5 0.5 0.5\r\n"
        "v 0 1 0\r\n"
        "o second\n"
        "v 0 0 0\nv 0 0 1\nv 1 0 0\n"
        "f -3 -2 -1\n"
        "g third part\n"
        "v 0 0 0\nv 0 1 0\nv 0 0 1\n"
        "vt 0 0\nvn 1 0 0\n"
        "f -3/-1/-1 -2/1/1 -1//-1\n"
        "l 1 2\np 1\ns off\nusemtl x\n"
        "v 1 0 0\nv 0 1 0\nv 0 0 1\n"
        "g\n"
        "f 12 11 10\n";
    TriSurf s;
    Err e = {0};
    EXPECT(parse(&s, text, &e) == 0, "%s", e.msg);
    EXPECT(s.ntris == 4 && s.npoints == 4, "ntris %d npoints %d (welded tetrahedron)", s.ntris, s.npoints);
    TriTopo t;
    trisurf_check(&s, &t);
    EXPECT(t.nopen == 0 && t.nflipped == 0, "open %d flipped %d", t.nopen, t.nflipped);
    NEAR(t.volume, -1.0 / 6, 1e-16);   /* every face turned inward: the orientation is the file's */
    static const char *nm[4] = {"default", "second", "third", "default"};
    EXPECT(s.nnames == 3, "nnames %d", s.nnames);
    for (int i = 0; i < 4 && s.tag && s.nnames == 3; i++)
        EXPECT(strcmp(s.names[s.tag[i]], nm[i]) == 0, "region of face %d: '%s'", i, s.names[s.tag[i]]);
    trisurf_free(&s);
}

static int fails_with(const char *text, const char *want)
{
    TriSurf s;
    Err e = {0};
    int rc = parse(&s, text, &e);
    int ok = rc == -1 && strstr(e.msg, want) && s.ntris == 0 && s.points == NULL;
    if (!ok) printf("  got rc %d, message \"%s\", expected \"%s\"\n", rc, e.msg, want);
    trisurf_free(&s);
    return ok;
}

TEST(malformed)
{
    static const char tri[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    struct {
        const char *tail, *want;
    } bad[] = {
        {"f 1 2 4\n", "t.obj:4: vertex index 4 out of range: the file has 3 vertices"},
        {"f 1 2 3\nf 1 2 9\nv 1 1 1\n", "t.obj:5: vertex index 9 out of range: the file has 4 vertices"},
        {"f -1 -2 -4\n", "t.obj:4: vertex index -4 out of range: 3 vertices read so far"},
        {"f 0 1 2\n", "t.obj:4: vertex index 0 (OBJ indices start at 1)"},
        {"f 1 2 99999999999999999999\n", "t.obj:4: vertex index"},
        {"f 1/1 2/1 3/1\n", "t.obj:4: texture coordinate index 1 out of range: the file has 0 texture coordinates"},
        {"vn 0 0 1\nf 1//1 2//1 3//2\n", "t.obj:5: normal index 2 out of range: the file has 1 normal"},
        {"f 1 2\n", "t.obj:4: face with 2 corners (needs at least 3)"},
        {"f\n", "t.obj:4: face with 0 corners"},
        {"f 1 2 3/\n", "t.obj:4: bad face corner '3/'"},
        {"f 1 2 3//\n", "t.obj:4: bad face corner '3//'"},
        {"f 1 2 1/2/3/4\n", "t.obj:4: bad face corner '1/2/3/4'"},
        {"f 1 2 x\n", "t.obj:4: bad face corner 'x'"},
        {"f 1 2 3.0\n", "t.obj:4: bad face corner '3.0'"},
        {"v 1 2 1.0.0\n", "t.obj:4: bad number '1.0.0' in 'v'"},
        {"v 1 2\n", "t.obj:4: 'v' needs 3 numbers, found 2"},
        {"v 1 2 3 4 5\n", "t.obj:4: 'v' takes x y z [w] [r g b], found 5 numbers"},
        {"v 1 2 3 4 5 6 7 8\n", "t.obj:4: 'v' takes at most 7 numbers"},
        {"v 1 nan 3\n", "t.obj:4: non-finite coordinate 'nan' in 'v'"},
        {"v 1 2 -inf\n", "t.obj:4: non-finite coordinate '-inf' in 'v'"},
        {"v 1e999 2 3\n", "t.obj:4: non-finite coordinate '1e999' in 'v'"},
        {"v 0x1p3 2 3\n", "t.obj:4: bad number '0x1p3' in 'v'"},
        {"vn 0 0 x\n", "t.obj:4: bad number 'x' in 'vn'"},
        {"vn 0 0 1 1\n", "t.obj:4: 'vn' takes at most 3 numbers"},
        {"facet 1 2 3\n", "t.obj:4: unknown OBJ statement 'facet'"},
        {"V 1 2 3\n", "t.obj:4: unknown OBJ statement 'V'"},
        {"cstype bspline\n", "t.obj:4: free-form geometry ('cstype') is not supported"},
        {"call other.obj\n", "t.obj:4: 'call' is not supported"},
        {"v 1 2 \\\n 3 4 5\n", "t.obj:5: 'v' takes x y z [w] [r g b], found 5 numbers"},
        {"l 1 2\n", "t.obj: no faces in OBJ file"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, "%s%s", tri, bad[i].tail);
        EXPECT(fails_with(text, bad[i].want), "case %zu: %s", i, bad[i].tail);
    }
    EXPECT(fails_with("", "t.obj: no faces"), "empty file");
    TriSurf s;
    Err e = {0};
    char *p = tmp("absent.obj");
    EXPECT(obj_read(&s, p, &e) == -1 && strstr(e.msg, "absent.obj"), "absent file: %s", e.msg);
    trisurf_free(&s);
    free(p);
}

/* The same closed surface as OBJ and as STL: same triangles, points and
   volume.  The surface is tests/data/stl/sphere.stl.gz (gmsh, r = 0.3,
   5k triangles), written back as an OBJ with 17 digits. */
TEST(same_as_stl)
{
    TriSurf a, b;
    Err e = {0};
    char *p = data_path("stl/sphere.stl.gz");
    EXPECT(stl_read(&a, p, &e) == 0, "%s", e.msg);
    free(p);
    if (a.ntris == 0) return;
    Buf o;
    buf_init(&o);
    buf_puts(&o, "# sphere.stl.gz as OBJ\ng sphere\n");
    for (int i = 0; i < a.npoints; i++)
        buf_printf(&o, "v %.17g %.17g %.17g\n", a.points[3 * i], a.points[3 * i + 1], a.points[3 * i + 2]);
    for (int t = 0; t < a.ntris; t++)
        buf_printf(&o, "f %d %d %d\n", a.tris[3 * t] + 1, a.tris[3 * t + 1] + 1, a.tris[3 * t + 2] + 1);
    char *q = tmp("sphere.obj");
    EXPECT(io_write_atomic(q, o.p, o.n, 0, &e) == 0, "%s", e.msg);
    EXPECT(surface_read(&b, q, &e) == 0, "%s", e.msg);
    EXPECT(a.ntris == b.ntris && a.npoints == b.npoints, "STL %d/%d, OBJ %d/%d triangles/points", a.ntris, a.npoints,
           b.ntris, b.npoints);
    int same = a.ntris == b.ntris;
    for (int t = 0; same && t < 3 * a.ntris; t++)
        for (int k = 0; k < 3; k++)
            same &= a.points[3 * a.tris[t] + k] == b.points[3 * b.tris[t] + k];
    EXPECT(same, "the OBJ's triangles differ from the STL's");
    TriTopo ta, tb;
    trisurf_check(&a, &ta);
    trisurf_check(&b, &tb);
    EXPECT(tb.nopen == 0 && tb.nnonmanifold == 0, "OBJ sphere open %d", tb.nopen);
    EXPECT(ta.volume == tb.volume, "volumes: STL %.17g OBJ %.17g", ta.volume, tb.volume);
    EXPECT(fabs(tb.volume - 4.0 / 3 * M_PI * 0.027) < 1e-3, "sphere volume %.6f is not about 4/3 pi 0.3^3",
           tb.volume);
    trisurf_free(&a);
    trisurf_free(&b);
    buf_free(&o);
    free(q);
}

TEST(gzip)
{
    TriSurf a, b, c;
    Err e = {0};
    char *p = data_path("obj/cube.obj");
    Buf d;
    buf_init(&d);
    EXPECT(io_read_file(p, &d, NULL, &e) == 0, "%s", e.msg);
    char *q = tmp("zcube.obj");   /* written as zcube.obj.gz */
    EXPECT(io_write_atomic(q, d.p, d.n, 1, &e) == 0, "%s", e.msg);
    char *qz = tmp("zcube.obj.gz");
    struct stat st;
    EXPECT(stat(q, &st) != 0 && stat(qz, &st) == 0, "zcube.obj.gz not written alone");
    EXPECT(obj_read(&a, p, &e) == 0, "%s", e.msg);
    EXPECT(obj_read(&b, qz, &e) == 0, "%s", e.msg);
    EXPECT(surface_read(&c, q, &e) == 0, "name without .gz: %s", e.msg);
    EXPECT(b.ntris == 12 && c.ntris == 12 && b.npoints == 8 && c.nnames == 3, "gzip: %d/%d triangles", b.ntris,
           c.ntris);
    for (int i = 0; i < 24 && b.npoints == 8 && c.npoints == 8; i++)
        EXPECT(a.points[i] == b.points[i] && a.points[i] == c.points[i], "point coordinate %d differs", i);
    trisurf_free(&a);
    trisurf_free(&b);
    trisurf_free(&c);
    buf_free(&d);
    free(p);
    free(q);
    free(qz);
}

/* surface_format: binary STL by size first, then the name, then the
   content; an OBJ is never read as a binary STL. */
TEST(format_choice)
{
    static const char objtext[] = "# made by hand\n\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    static const char stltext[] = "solid x\nfacet outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet\n"
                                  "endsolid x\n";
    size_t no = sizeof objtext - 1, ns = sizeof stltext - 1;
    EXPECT(surface_format(objtext, no, "part.obj") == SURFACE_OBJ, "OBJ named .obj");
    EXPECT(surface_format(objtext, no, "part.stl") == SURFACE_OBJ, "OBJ content named .stl");
    EXPECT(surface_format(objtext, no, "part.OBJ.gz") == SURFACE_OBJ, "OBJ named .OBJ.gz");
    EXPECT(surface_format(stltext, ns, "part.stl") == SURFACE_STL, "ascii STL");
    EXPECT(surface_format("garbage", 7, "part.obj") == SURFACE_OBJ, "garbage named .obj goes to the OBJ reader");
    EXPECT(surface_format("garbage", 7, "part.stl") == SURFACE_STL, "garbage named .stl goes to the STL reader");
    /* a binary STL of one triangle, named .obj, whose header is OBJ text */
    unsigned char bin[134];
    memset(bin, 0, sizeof bin);
    memcpy(bin, "v 0 0 0\n", 8);
    bin[80] = 1;
    EXPECT(surface_format((const char *)bin, sizeof bin, "x.obj") == SURFACE_STL, "binary STL named .obj");
    /* an OBJ that is a few bytes longer than a binary STL would be if
       bytes 80-83 counted triangles: still OBJ (those bytes are text) */
    Buf b;
    buf_init(&b);
    while (b.n < 200) buf_puts(&b, "v 0 0 0\n");
    buf_puts(&b, "f 1 2 3\n");
    EXPECT(!stl_is_binary(b.p, b.n) && surface_format(b.p, b.n, "x.stl") == SURFACE_OBJ, "OBJ text as STL");
    TriSurf s;
    Err e = {0};
    EXPECT(surface_parse(&s, b.p, b.n, "x.stl", &e) == 0 && s.ntris == 1, "OBJ named .stl: %s", e.msg);
    trisurf_free(&s);
    EXPECT(surface_parse(&s, "solid x\nfacet\n", 14, "x.obj", &e) == -1, "ascii STL named .obj");
    CONTAINS(e.msg, "x.obj:1: unknown OBJ statement 'solid'");
    buf_free(&b);
}

/* The geometry layer takes OBJ files under shape surface, obj and stl,
   and under cad too (gmsh reads no OBJ; geometry_dict.c hands it to ours). */
TEST(geometry_shapes)
{
    char *p = data_path("obj/lprism.obj");
    static const char *const kinds[] = {"surface", "obj", "stl", "cad"};
    for (int k = 0; k < 4; k++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "surfaces { l { flow outside; shape %s; file \"%s\"; scale 0.25; translate (0.2 0.2 0.3); } }",
                 kinds[k], p);
        Geometry g;
        Err e = {0};
        EXPECT(fixture_geometry(&g, text, &e) == 0, "shape %s: %s", kinds[k], e.msg);
        if (e.msg[0]) continue;
        double in[3] = {0.3, 0.5, 0.5}, notch[3] = {0.6, 0.6, 0.5};
        EXPECT(!geometry_fluid(&g, in) && geometry_fluid(&g, notch), "shape %s: inside tests", kinds[k]);
        geometry_free(&g);
    }
    free(p);
}

/* Every *.obj / *.obj.gz surface of the OpenFOAM examples reads, with
   n - 2 triangles per face of n corners (counted here from the text), or
   is refused for having no faces (a curve of 'l' lines). */
static int count_faces(const Buf *d, long *tris)
{
    *tris = 0;
    long nf = 0;
    const char *p = d->p, *end = d->p + d->n;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        if (!nl) nl = end;
        if (nl - p > 2 && p[0] == 'f' && p[1] == ' ') {
            int k = 0;
            for (const char *q = p + 1; q < nl; q++)
                if (*q != ' ' && *q != '\r' && (q[-1] == ' ')) k++;
            *tris += k - 2;
            nf++;
        }
        p = nl + 1;
    }
    return nf > 0;
}

static void walk(const char *dir, int *nread, int *nbad, long *ntris)
{
    DIR *dp = opendir(dir);
    if (!dp) return;
    struct dirent *de;
    while ((de = readdir(dp))) {
        if (de->d_name[0] == '.') continue;
        char *p = io_join(dir, de->d_name);
        struct stat st;
        if (stat(p, &st) == 0 && S_ISDIR(st.st_mode)) {
            walk(p, nread, nbad, ntris);
        } else {
            size_t n = strlen(p);
            int obj = (n > 4 && !strcmp(p + n - 4, ".obj")) || (n > 7 && !strcmp(p + n - 7, ".obj.gz"));
            /* the motorbikes and buildings (4 MB each) add seconds, not coverage */
            if (obj && st.st_size < 1000000) {
                Buf d;
                buf_init(&d);
                Err e = {0};
                long want = 0;
                TriSurf s;
                int faces = io_read_file(p, &d, NULL, &e) == 0 && count_faces(&d, &want);
                int rc = obj_read(&s, p, &e);
                int ok = faces ? rc == 0 && s.ntris == want : rc == -1 && strstr(e.msg, "no faces");
                if (!ok) {
                    printf("  %s: rc %d, %d triangles, expected %ld: %s\n", p, rc, rc ? 0 : s.ntris, want, e.msg);
                    (*nbad)++;
                }
                (*nread)++;
                *ntris += rc ? 0 : s.ntris;
                trisurf_free(&s);
                buf_free(&d);
            }
        }
        free(p);
    }
    closedir(dp);
}

static const char examples[] = "/usr/share/doc/openfoam-examples/examples";

TEST(openfoam_examples)
{
    int nread = 0, nbad = 0;
    long ntris = 0;
    walk(examples, &nread, &nbad, &ntris);
    EXPECT(nread >= 10 && nbad == 0, "%d OBJ files read, %d wrong", nread, nbad);
    /* two closed ones with known volumes: a rotated unit cube and the
       rotorDisk case's cylinder (3 regions) */
    char p[256];
    TriSurf s;
    Err e = {0};
    snprintf(p, sizeof p, "%s/mesh/snappyHexMesh/distributedTriSurfaceMesh/constant/triSurface/box_12.obj", examples);
    if (obj_read(&s, p, &e) == 0) {
        TriTopo t;
        trisurf_check(&s, &t);
        EXPECT(t.nopen == 0 && s.ntris == 12, "box_12: open %d, %d triangles", t.nopen, s.ntris);
        NEAR(t.volume, 1.0, 1e-5);   /* a rotated unit cube, 6 digits */
        trisurf_free(&s);
    }
    snprintf(p, sizeof p, "%s/incompressible/simpleFoam/rotorDisk/constant/triSurface/fixed.obj.gz", examples);
    EXPECT(obj_read(&s, p, &e) == 0, "%s", e.msg);
    if (s.ntris) {
        TriTopo t;
        trisurf_check(&s, &t);
        EXPECT(t.nopen == 0 && s.nnames == 3, "fixed.obj: open %d, %d regions", t.nopen, s.nnames);
        /* a polygonal cylinder, r = 1.25, length 4: pi r^2 L within the
           polygon's error */
        NEAR(t.volume, M_PI * 1.25 * 1.25 * 4, 2e-3);
        trisurf_free(&s);
    }
}

/* Every prefix and every one-byte change of a valid file parses or fails
   with a message naming the file; none may crash (run under ASan). */
TEST(truncations_and_mutations)
{
    char *p = data_path("obj/cube.obj");
    Buf d;
    buf_init(&d);
    Err e = {0};
    EXPECT(io_read_file(p, &d, NULL, &e) == 0, "%s", e.msg);
    free(p);
    size_t n = d.n;
    char *buf = mem_alloc(n + 1);
    int unnamed = 0, wrong = 0;
    for (size_t k = 0; k <= n; k++) {
        TriSurf s;
        memcpy(buf, d.p, k);
        int rc = obj_parse(&s, buf, k, "m.obj", &e);
        if (rc && strncmp(e.msg, "m.obj", 5) != 0) unnamed++;
        if (rc == 0 && (s.ntris < 1 || s.ntris > 12)) wrong++;
        trisurf_free(&s);
    }
    static const char subst[] = {'\0', ' ', '\n', '#', '\\', '/', '-', '9', 'x', '.'};
    for (size_t k = 0; k < n; k++)
        for (size_t q = 0; q < sizeof subst; q++) {
            TriSurf s;
            memcpy(buf, d.p, n);
            buf[k] = subst[q];
            int rc = obj_parse(&s, buf, n, "m.obj", &e);
            if (rc && strncmp(e.msg, "m.obj", 5) != 0) unnamed++;
            if (rc == 0 && (s.ntris < 1 || s.ntris > 14)) wrong++;
            trisurf_free(&s);
        }
    EXPECT(unnamed == 0 && wrong == 0, "%d messages without the file, %d surfaces with a wrong triangle count",
           unnamed, wrong);
    free(buf);
    buf_free(&d);
}

int main(void)
{
    RUN(cube_quads);
    RUN(nonconvex_prism);
    RUN(ear_clipping);
    RUN(negative_indices_and_forms);
    RUN(malformed);
    RUN(same_as_stl);
    RUN(gzip);
    RUN(format_choice);
    RUN(geometry_shapes);
    struct stat st;
    if (stat(examples, &st) == 0)
        RUN(openfoam_examples);
    else
        printf("SKIP openfoam_examples: %s not installed\n", examples);
    RUN(truncations_and_mutations);
    return test_summary();
}
