/*
** stl.c: STL files, ascii and binary, into and out of a TriSurf.  See
** stl.h for the contract.
**
** Format detection.  A binary STL is an 80-byte header, a little-endian
** uint32 count n and n records of 50 bytes (normal, three corners as
** float32, a 16-bit attribute), so its size is exactly 84 + 50 n; that
** test decides first, because many binary exporters start the header with
** "solid".  Otherwise a file starting with "solid" and free of NUL bytes
** is ascii; anything else of at least 84 bytes is reported as a binary
** file of the wrong size (truncated), shorter ones as not STL.
**
** The ascii grammar, with keywords in any case and any whitespace
** (including line breaks) between tokens, as real exporters write it:
**     solid [name...]            name: the rest of the line, trimmed (up
**                                to a keyword of the facet grammar)
**       facet [normal nx ny nz]  three numbers (may be nan or inf), skipped
**         outer loop
**           vertex x y z         three times
**         endloop
**       endfacet
**     endsolid [name...]         the rest of the line is ignored
** repeated for several solids.  Every solid becomes a tag; solids with
** the same name share one (OpenFOAM regions), an unnamed one is called
** "solid<i>" after its position.  A file that ends inside a solid is an
** error (a truncated file would otherwise lose triangles silently).
**
** Strictness.  Numbers are decimal only (soup.h): "0x1p3", "1.0.0" or
** "1,5" are errors, and so is any other token where a number belongs
** ("facet normal 0 0 x"; "facet normal 1 2" followed by "outer");
** coordinates must be finite.  Since the grammar is a fixed sequence of
** tokens, anything extra ("vertex 1 2 3 4", "outer loop x", a fourth
** normal component) is reported where the next keyword was expected.
**
** Writing assembles the file in a Buf: binary corners are rounded to
** float32 (the format's precision) with a unit normal; ascii writes
** 17 significant digits, so an ascii round trip is exact, and one solid
** block per tag.  A path ending in ".gz" is gzipped by io_write_atomic.
*/
#include "stl.h"

#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "io.h"
#include "mem.h"
#include "soup.h"

/* ---------------------------------------------------------------- binary */

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static double lefloat(const unsigned char *p)
{
    uint32_t u = le32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static int parse_binary(TriSurf *s, const unsigned char *d, uint32_t n, const char *name, Err *e)
{
    Soup S = {0};
    for (uint32_t i = 0; i < n; i++) {
        const unsigned char *r = d + 84 + 50 * (size_t)i + 12;   /* skip the normal */
        double c[9];
        for (int k = 0; k < 9; k++) {
            c[k] = lefloat(r + 4 * k);
            if (!isfinite(c[k])) {
                soup_free(&S);
                return err_set(e, name, 0, "binary STL triangle %u has a non-finite coordinate", i + 1);
            }
        }
        soup_push(&S, c, 0);
    }
    return soup_finish(&S, s, 0, name, "no triangles in STL file", e);
}

/* ---------------------------------------------------------------- ascii */

typedef struct Lex {
    const char *p, *end, *name;
    int line;
    const char *tok;      /* current token */
    size_t len;
    int tok_line;
} Lex;

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

/* Next whitespace-delimited token; 0 at end of input. */
static int lex_next(Lex *L)
{
    while (L->p < L->end && is_space(*L->p)) {
        if (*L->p == '\n') L->line++;
        L->p++;
    }
    if (L->p == L->end) return 0;
    L->tok = L->p;
    L->tok_line = L->line;
    while (L->p < L->end && !is_space(*L->p)) L->p++;
    L->len = (size_t)(L->p - L->tok);
    return 1;
}

/* The rest of the current line, trimmed (the line break is left for
   lex_next, which counts it). */
static void lex_rest(Lex *L, const char **s, size_t *n)
{
    while (L->p < L->end && *L->p != '\n' && is_space(*L->p)) L->p++;
    const char *b = L->p;
    while (L->p < L->end && *L->p != '\n') L->p++;
    const char *q = L->p;
    while (q > b && is_space(q[-1])) q--;
    *s = b;
    *n = (size_t)(q - b);
}

static int tok_is(const Lex *L, const char *kw)
{
    size_t n = strlen(kw);
    if (L->len != n) return 0;
    for (size_t i = 0; i < n; i++)
        if (tolower((unsigned char)L->tok[i]) != kw[i]) return 0;
    return 1;
}

/* The current token for a message: at most 40 characters, binary bytes
   shown as '?'. */
static const char *tok_show(const Lex *L, char out[48])
{
    size_t n = L->len < 40 ? L->len : 40, i;
    for (i = 0; i < n; i++) {
        unsigned char c = (unsigned char)L->tok[i];
        out[i] = isprint(c) ? (char)c : '?';
    }
    if (L->len > 40) memcpy(out + i, "...", 3), i += 3;
    out[i] = '\0';
    return out;
}

static int expect(Lex *L, const char *kw, Err *e)
{
    char b[48];
    if (!lex_next(L))
        return err_set(e, L->name, L->tok_line, "unexpected end of file, expected '%s'", kw);
    if (!tok_is(L, kw))
        return err_set(e, L->name, L->tok_line, "expected '%s', found '%s'", kw, tok_show(L, b));
    return 0;
}

/* The next token as a number; what names the number in messages.  A
   coordinate must be finite (finite != 0); a facet normal may be nan or
   inf, which exporters write for degenerate facets, since it is skipped. */
static int number(Lex *L, double *x, int finite, const char *what, Err *e)
{
    char b[48];
    if (!lex_next(L)) return err_set(e, L->name, L->tok_line, "unexpected end of file, expected %s", what);
    int rc = soup_number(L->tok, L->len, x);
    if (rc < 0) return err_set(e, L->name, L->tok_line, "bad number '%s', expected %s", tok_show(L, b), what);
    if (rc == 0 && finite)
        return err_set(e, L->name, L->tok_line, "non-finite coordinate '%s'", tok_show(L, b));
    return 0;
}

static int parse_facet(Lex *L, Soup *S, int tag, Err *e)
{
    double c[9], nv;
    char b[48];
    if (!lex_next(L)) return err_set(e, L->name, L->tok_line, "unexpected end of file in facet");
    if (tok_is(L, "normal")) {
        for (int k = 0; k < 3; k++)
            if (number(L, &nv, 0, "a component of the facet normal (three numbers)", e)) return -1;
        if (!lex_next(L)) return err_set(e, L->name, L->tok_line, "unexpected end of file, expected 'outer'");
    }
    if (!tok_is(L, "outer"))
        return err_set(e, L->name, L->tok_line, "expected 'outer', found '%s'", tok_show(L, b));
    if (expect(L, "loop", e)) return -1;
    for (int v = 0; v < 3; v++) {
        if (expect(L, "vertex", e)) return -1;
        for (int k = 0; k < 3; k++)
            if (number(L, &c[3 * v + k], 1, "a coordinate", e)) return -1;
    }
    if (expect(L, "endloop", e) || expect(L, "endfacet", e)) return -1;
    soup_push(S, c, tag);
    return 0;
}

/* The name after "solid": the rest of its line, trimmed, but ending before
   a keyword of the facet grammar (facet, outer loop, vertex, endloop,
   endfacet, endsolid), so a file written on one line keeps its facets and
   a damaged keyword on a solid's line is reported, not taken as a name. */
static void solid_name(Lex *L, const char **nm, size_t *nn)
{
    const char *b = NULL, *q = NULL;
    for (;;) {
        while (L->p < L->end && *L->p != '\n' && is_space(*L->p)) L->p++;
        if (L->p == L->end || *L->p == '\n') break;
        const char *t = L->p;
        while (L->p < L->end && !is_space(*L->p)) L->p++;
        Lex k = *L;
        k.tok = t;
        k.len = (size_t)(L->p - t);
        int stop = tok_is(&k, "facet") || tok_is(&k, "endsolid") || tok_is(&k, "vertex") ||
                   tok_is(&k, "endloop") || tok_is(&k, "endfacet");
        if (!stop && tok_is(&k, "outer")) {   /* "outer loop", not a name "outer wall" */
            stop = lex_next(&k) && tok_is(&k, "loop");
        }
        if (stop) {
            L->p = t;
            break;
        }
        if (!b) b = t;
        q = L->p;
    }
    *nm = b;
    *nn = b ? (size_t)(q - b) : 0;
}

static int parse_solid(Lex *L, Soup *S, int index, Err *e)
{
    const char *nm;
    size_t nn;
    int start = L->tok_line;
    solid_name(L, &nm, &nn);
    char *name = nn ? mem_strndup(nm, nn) : NULL;
    if (!name) {
        name = mem_alloc(32);
        snprintf(name, 32, "solid%d", index);
    }
    int tag = soup_tag(S, name);
    for (;;) {
        char b[48];
        if (!lex_next(L)) {
            err_set(e, L->name, L->tok_line, "unexpected end of file: missing 'endsolid' for solid '%s' (line %d)",
                    name, start);
            free(name);
            return -1;
        }
        if (tok_is(L, "endsolid")) {
            lex_rest(L, &nm, &nn);
            free(name);
            return 0;
        }
        if (!tok_is(L, "facet")) {
            err_set(e, L->name, L->tok_line, "expected 'facet' or 'endsolid', found '%s'", tok_show(L, b));
            free(name);
            return -1;
        }
        if (parse_facet(L, S, tag, e)) {
            free(name);
            return -1;
        }
    }
}

static int parse_ascii(TriSurf *s, const char *d, size_t n, const char *name, Err *e)
{
    Lex L = {d, d + n, name, 1, NULL, 0, 0};
    Soup S = {0};
    for (int index = 0; lex_next(&L); index++) {
        char b[48];
        if (!tok_is(&L, "solid")) {
            soup_free(&S);
            return err_set(e, name, L.tok_line, "expected 'solid', found '%s'", tok_show(&L, b));
        }
        if (parse_solid(&L, &S, index, e)) {
            soup_free(&S);
            return -1;
        }
    }
    return soup_finish(&S, s, 1, name, "no triangles in STL file", e);
}

/* ---------------------------------------------------------------- read */

static int starts_solid(const char *d, size_t n)
{
    size_t i = 0;
    while (i < n && is_space(d[i])) i++;
    if (n - i < 5) return 0;
    for (int k = 0; k < 5; k++)
        if (tolower((unsigned char)d[i + k]) != "solid"[k]) return 0;
    return n - i == 5 || is_space(d[i + 5]);
}

int stl_is_binary(const char *data, size_t n)
{
    return n >= 84 && (uint64_t)84 + 50 * (uint64_t)le32((const unsigned char *)data + 80) == n;
}

int stl_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e)
{
    trisurf_init(s);
    if (!name) name = "<stl>";
    if (n == 0) return err_set(e, name, 0, "empty file");
    if (n >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0 && starts_solid(data + 3, n - 3))
        return parse_ascii(s, data + 3, n - 3, name, e);   /* a UTF-8 byte-order mark */
    const unsigned char *u = (const unsigned char *)data;
    if (stl_is_binary(data, n)) return parse_binary(s, u, le32(u + 80), name, e);
    int text = starts_solid(data, n) && !memchr(data, '\0', n < 4096 ? n : 4096);
    if (text) return parse_ascii(s, data, n, name, e);
    if (n >= 84) {
        uint32_t count = le32(u + 80);
        return err_set(e, name, 0,
                       "binary STL of %u triangles needs %llu bytes but the file has %zu (truncated or not STL)",
                       count, (unsigned long long)(84 + 50 * (uint64_t)count), n);
    }
    return err_set(e, name, 0, "not an STL file (%zu bytes, no 'solid' keyword, too short for binary)", n);
}

int stl_read(TriSurf *s, const char *path, Err *e)
{
    trisurf_init(s);
    Buf b;
    buf_init(&b);
    char *found = NULL;
    if (io_read_file(path, &b, &found, e)) return -1;
    int rc = stl_parse(s, b.p, b.n, found ? found : path, e);
    free(found);
    buf_free(&b);
    return rc;
}

/* ---------------------------------------------------------------- write */

static void put_le32(Buf *b, uint32_t v)
{
    unsigned char c[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                          (unsigned char)(v >> 24)};
    buf_put(b, c, 4);
}

static void put_float(Buf *b, double x)
{
    float f = (float)x;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_le32(b, u);
}

static int write_binary(const TriSurf *s, Buf *b, const char *path, Err *e)
{
    char head[80];
    memset(head, ' ', sizeof head);
    memcpy(head, "binary STL written by Kiesel", 28);
    buf_reserve(b, 84 + 50 * (size_t)s->ntris);
    buf_put(b, head, sizeof head);
    put_le32(b, (uint32_t)s->ntris);
    for (int t = 0; t < s->ntris; t++) {
        double n[3];
        trisurf_normal(s, t, n);
        for (int k = 0; k < 3; k++) put_float(b, n[k]);
        for (int m = 0; m < 3; m++)
            for (int k = 0; k < 3; k++) {
                double x = s->points[3 * (size_t)s->tris[3 * t + m] + k];
                if (!(fabs(x) <= FLT_MAX))
                    return err_set(e, path, 0, "coordinate %g of triangle %d does not fit a binary STL (float)",
                                   x, t + 1);
                put_float(b, x);
            }
        buf_put(b, "\0\0", 2);
    }
    return 0;
}

/* A solid's name on one line: line breaks become '_'. */
static void put_name(Buf *b, const char *nm)
{
    for (; *nm; nm++) buf_putc(b, *nm == '\n' || *nm == '\r' ? '_' : *nm);
}

static void write_facet(const TriSurf *s, int t, Buf *b)
{
    double n[3];
    trisurf_normal(s, t, n);
    buf_printf(b, "  facet normal %.9g %.9g %.9g\n    outer loop\n", n[0], n[1], n[2]);
    for (int m = 0; m < 3; m++) {
        const double *p = s->points + 3 * (size_t)s->tris[3 * t + m];
        buf_printf(b, "      vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    buf_puts(b, "    endloop\n  endfacet\n");
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* One solid per distinct tag, in ascending tag order, named from names[]
   where the tag has one. */
static void write_ascii(const TriSurf *s, Buf *b)
{
    int *tags = mem_alloc(((size_t)s->ntris + 1) * sizeof *tags), nt = 0;
    if (s->tag) {
        memcpy(tags, s->tag, (size_t)s->ntris * sizeof *tags);
        qsort(tags, (size_t)s->ntris, sizeof *tags, cmp_int);
        for (int i = 0; i < s->ntris; i++)
            if (i == 0 || tags[i] != tags[nt - 1]) tags[nt++] = tags[i];
    } else {
        tags[nt++] = 0;
    }
    for (int g = 0; g < nt; g++) {
        char def[32];
        const char *nm = def;
        if (tags[g] >= 0 && tags[g] < s->nnames && s->names && s->names[tags[g]])
            nm = s->names[tags[g]];
        else if (!s->tag)
            nm = "kiesel";
        else
            snprintf(def, sizeof def, "solid%d", tags[g]);
        buf_puts(b, "solid ");
        put_name(b, nm);
        buf_putc(b, '\n');
        for (int t = 0; t < s->ntris; t++)
            if (!s->tag || s->tag[t] == tags[g]) write_facet(s, t, b);
        buf_puts(b, "endsolid ");
        put_name(b, nm);
        buf_putc(b, '\n');
    }
    free(tags);
}

int stl_write(const TriSurf *s, const char *path, int binary, Err *e)
{
    Buf b;
    buf_init(&b);
    if (binary) {
        if (write_binary(s, &b, path, e)) {
            buf_free(&b);
            return -1;
        }
    } else {
        write_ascii(s, &b);
    }
    size_t l = strlen(path);
    int gz = l > 3 && strcmp(path + l - 3, ".gz") == 0;
    char *target = mem_strndup(path, gz ? l - 3 : l);   /* io_write_atomic adds ".gz" */
    int rc = io_write_atomic(target, b.p, b.n, gz, e);
    free(target);
    buf_free(&b);
    return rc;
}
