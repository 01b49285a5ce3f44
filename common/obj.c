/*
** obj.c: Wavefront OBJ surfaces into a TriSurf.  See obj.h for what is
** read and how faces are triangulated.
**
** Two passes.  The statements are read first: vertex positions into one
** array, face corners (0-based vertex indices) into another with an
** offset per face, and a region tag per face.  Positive indices may
** refer to vertices further down the file, so the largest one (and its
** line) is remembered and checked against the final count; negative
** ones are relative to the vertices read so far and resolved on the
** spot.  Only then, with every position known, are the faces
** triangulated into a Soup, which welds the corners (soup.h).
**
** Lexing.  A statement is one line; a backslash at the end of a line
** continues it on the next; '#' at the start of a token begins a
** comment that runs to the end of the line.  Keywords are case-sensitive,
** as in the format's specification.
**
** Ear clipping.  The face is projected onto the coordinate plane most
** nearly parallel to it (dropping the largest component of its Newell
** normal, which also gives its orientation in that plane).  The corners
** form a circular list; starting at the second corner, a corner is
** clipped when it is convex and no other remaining corner lies in the
** closed triangle it forms with its neighbours; the scan then continues
** with its successor.  On a convex face every corner qualifies, so the
** triangles are the fan from the first corner.  A face that is not
** simple (self-intersecting, collinear runs, repeated corners) may leave
** no such ear: after a fruitless round the containment test is dropped,
** after another the convexity test too, so the loop always ends with
** n - 2 triangles; degenerate ones among them are dropped later with the
** other zero-area triangles (trisurf_drop_degenerate).
*/
#include "obj.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "io.h"
#include "mem.h"
#include "soup.h"

typedef struct Obj {
    const char *p, *end, *name;
    int line;
    double *v;                /* 3 per vertex */
    size_t nv, vcap;
    size_t nvt, nvn;          /* texture coordinates and normals read */
    int *corner;              /* 0-based vertex index per face corner */
    size_t ncorner, ccap;
    size_t *fofs;             /* face f: corners fofs[f] .. fofs[f+1]-1 */
    int *ftag;
    size_t nface, ocap, tcap;
    long long vmax, vtmax, vnmax;   /* largest positive index of each kind */
    int vmax_line, vtmax_line, vnmax_line;
    char *group;              /* current region's name; NULL: "default" */
    int tag;                  /* its tag, -1 until it holds a face */
    Soup S;
} Obj;

static void obj_free(Obj *O)
{
    free(O->v);
    free(O->corner);
    free(O->fofs);
    free(O->ftag);
    free(O->group);
    soup_free(&O->S);
}

/* ---------------------------------------------------------------- lexing */

static int blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/* At a backslash: when only blanks follow it on its line, steps past the
   line break (the statement continues) and returns 1. */
static int continuation(Obj *O)
{
    const char *q = O->p + 1;
    while (q < O->end && blank(*q)) q++;
    if (q < O->end && *q != '\n') return 0;
    O->p = q < O->end ? q + 1 : q;
    O->line++;
    return 1;
}

/* The next token of the current statement in [*t, *t + *n); 0 at its end
   (a line break, a comment or the end of the data, not consumed). */
static int tok(Obj *O, const char **t, size_t *n)
{
    for (;;) {
        while (O->p < O->end && blank(*O->p)) O->p++;
        if (O->p < O->end && *O->p == '\\' && continuation(O)) continue;
        break;
    }
    if (O->p == O->end || *O->p == '\n' || *O->p == '#') return 0;
    *t = O->p;
    while (O->p < O->end && !blank(*O->p) && *O->p != '\n') {
        if (*O->p == '\\' && O->p > *t) {
            const char *keep = O->p;
            int line = O->line;
            if (continuation(O)) {   /* "3\" at a line's end: the token ends */
                O->p = keep;
                O->line = line;
                break;
            }
        }
        O->p++;
    }
    *n = (size_t)(O->p - *t);
    return 1;
}

/* Skips the rest of the statement (comment, continuation lines and all)
   and its line break. */
static void skip_statement(Obj *O)
{
    const char *t;
    size_t n;
    while (tok(O, &t, &n)) {}
    while (O->p < O->end && *O->p != '\n') O->p++;
    if (O->p < O->end) {
        O->p++;
        O->line++;
    }
}

/* A token for a message: at most 40 characters, control and non-ASCII
   bytes shown as '?'. */
static const char *show(const char *t, size_t n, char out[48])
{
    size_t m = n < 40 ? n : 40, i;
    for (i = 0; i < m; i++) out[i] = t[i] >= 0x20 && t[i] < 0x7f ? t[i] : '?';
    if (n > 40) memcpy(out + i, "...", 3), i += 3;
    out[i] = '\0';
    return out;
}

static int is(const char *t, size_t n, const char *kw) { return strlen(kw) == n && memcmp(t, kw, n) == 0; }

static int in_list(const char *t, size_t n, const char *const *list)
{
    for (; *list; list++)
        if (is(t, n, *list)) return 1;
    return 0;
}

/* ---------------------------------------------------------------- statements */

/* Tokens after the keyword as numbers, between lo and hi of them; the
   first nfinite must be finite.  Returns the count or -1. */
static int numbers(Obj *O, const char *kw, double *x, int lo, int hi, int nfinite, Err *e)
{
    const char *t;
    size_t n;
    char b[48];
    int k = 0;
    while (tok(O, &t, &n)) {
        double y;
        int rc = soup_number(t, n, &y);
        if (rc < 0) return err_set(e, O->name, O->line, "bad number '%s' in '%s'", show(t, n, b), kw);
        if (k >= hi) return err_set(e, O->name, O->line, "'%s' takes at most %d numbers, found more", kw, hi);
        if (rc == 0 && k < nfinite)
            return err_set(e, O->name, O->line, "non-finite coordinate '%s' in '%s'", show(t, n, b), kw);
        if (x) x[k] = y;
        k++;
    }
    if (k < lo) return err_set(e, O->name, O->line, "'%s' needs %d numbers, found %d", kw, lo, k);
    return k;
}

static int vertex(Obj *O, Err *e)
{
    double x[7];
    int k = numbers(O, "v", x, 3, 7, 3, e);
    if (k < 0) return -1;
    if (k == 5) return err_set(e, O->name, O->line, "'v' takes x y z [w] [r g b], found 5 numbers");
    if (O->nv == (size_t)INT_MAX) return err_set(e, O->name, O->line, "too many vertices");
    mem_grow((void **)&O->v, &O->vcap, 3 * (O->nv + 1), sizeof *O->v);
    memcpy(O->v + 3 * O->nv++, x, 3 * sizeof *x);
    return 0;
}

/* vt, vn, vp: numbers of any value (normals may be nan), counted in
   *count where faces index them. */
static int attribute(Obj *O, const char *kw, int lo, int hi, size_t *count, Err *e)
{
    if (numbers(O, kw, NULL, lo, hi, 0, e) < 0) return -1;
    if (count) (*count)++;
    return 0;
}

/* A signed decimal index at *p (moved past it); 0 when there is none. */
static int index_at(const char **p, const char *end, long long *v)
{
    const char *q = *p;
    int neg = q < end && *q == '-';
    if (q < end && (*q == '-' || *q == '+')) q++;
    if (q == end || *q < '0' || *q > '9') return 0;
    long long x = 0;
    for (; q < end && *q >= '0' && *q <= '9'; q++)
        if (x <= INT_MAX) x = 10 * x + (*q - '0');   /* saturates past INT_MAX: out of range anyway */
    *v = neg ? -x : x;
    *p = q;
    return 1;
}

/* The three lists a face corner indexes. */
typedef struct Kind {
    const char *one, *many;
} Kind;

static const Kind K_V = {"vertex", "vertices"}, K_VT = {"texture coordinate", "texture coordinates"},
                  K_VN = {"normal", "normals"};

/* Resolves index v into a list that holds `have` entries so far to
   0-based; positive indices are checked at the end (they may refer
   forward), so only the largest is kept, with its line. */
static int resolve(Obj *O, long long v, size_t have, const Kind *k, long long *max, int *max_line, long long *out,
                   Err *e)
{
    if (v == 0) return err_set(e, O->name, O->line, "%s index 0 (OBJ indices start at 1)", k->one);
    if (v > INT_MAX || v < -(long long)INT_MAX)
        return err_set(e, O->name, O->line, "%s index %lld out of range", k->one, v);
    if (v < 0) {
        if ((size_t)-v > have)
            return err_set(e, O->name, O->line, "%s index %lld out of range: %zu %s read so far", k->one, v, have,
                           have == 1 ? k->one : k->many);
        *out = (long long)have + v;
        return 0;
    }
    if (v > *max) {
        *max = v;
        *max_line = O->line;
    }
    *out = v - 1;
    return 0;
}

/* One face corner "v", "v/vt", "v/vt/vn" or "v//vn". */
static int corner(Obj *O, const char *t, size_t n, Err *e)
{
    const char *p = t, *end = t + n;
    long long v, vt = 0, vn = 0, k;
    int has_vt = 0, has_vn = 0;
    char b[48];
    int ok = index_at(&p, end, &v);
    if (ok && p < end && *p == '/') {
        p++;
        if (p < end && *p != '/') {
            ok = index_at(&p, end, &vt);
            has_vt = 1;
        }
        if (ok && p < end && *p == '/') {
            p++;
            ok = index_at(&p, end, &vn);
            has_vn = 1;
        } else if (!has_vt) {
            ok = 0;   /* "1/" */
        }
    }
    if (!ok || p != end)
        return err_set(e, O->name, O->line, "bad face corner '%s' (v, v/vt, v/vt/vn or v//vn)", show(t, n, b));
    if (resolve(O, v, O->nv, &K_V, &O->vmax, &O->vmax_line, &k, e)) return -1;
    mem_grow((void **)&O->corner, &O->ccap, O->ncorner + 1, sizeof *O->corner);
    O->corner[O->ncorner++] = (int)k;
    if (has_vt && resolve(O, vt, O->nvt, &K_VT, &O->vtmax, &O->vtmax_line, &k, e)) return -1;
    if (has_vn && resolve(O, vn, O->nvn, &K_VN, &O->vnmax, &O->vnmax_line, &k, e)) return -1;
    return 0;
}

static int face(Obj *O, Err *e)
{
    const char *t;
    size_t n, first = O->ncorner;
    int line = O->line;
    while (tok(O, &t, &n))
        if (corner(O, t, n, e)) return -1;
    size_t m = O->ncorner - first;
    if (m < 3) return err_set(e, O->name, line, "face with %zu corner%s (needs at least 3)", m, m == 1 ? "" : "s");
    if (O->tag < 0) O->tag = soup_tag(&O->S, O->group ? O->group : "default");
    mem_grow((void **)&O->fofs, &O->ocap, O->nface + 2, sizeof *O->fofs);
    mem_grow((void **)&O->ftag, &O->tcap, O->nface + 1, sizeof *O->ftag);
    O->fofs[O->nface] = first;
    O->ftag[O->nface++] = O->tag;
    O->fofs[O->nface] = O->ncorner;
    return 0;
}

static void group(Obj *O)
{
    const char *t;
    size_t n;
    free(O->group);
    O->group = tok(O, &t, &n) ? mem_strndup(t, n) : NULL;
    O->tag = -1;
}

/* Statements that carry nothing a solid needs (display attributes, lines,
   points), and free-form geometry, which would need evaluating. */
static const char *const ignored[] = {"l",        "p",      "s",      "mtllib",     "usemtl",    "mg",
                                      "lod",      "bevel",  "usemap", "maplib",     "c_interp",  "d_interp",
                                      "ctech",    "stech",  "shadow_obj", "trace_obj", NULL};
static const char *const freeform[] = {"cstype", "deg",  "bmat", "step", "curv", "curv2", "surf",
                                       "parm",   "trim", "hole", "scrv", "sp",   "end",   "con",  NULL};

/* One statement (a line and its continuations), consumed whole. */
static int statement(Obj *O, Err *e)
{
    const char *t;
    size_t n;
    char b[48];
    int rc = 0;
    if (!tok(O, &t, &n))
        rc = 0;
    else if (is(t, n, "v"))
        rc = vertex(O, e);
    else if (is(t, n, "f") || is(t, n, "fo"))
        rc = face(O, e);
    else if (is(t, n, "vt"))
        rc = attribute(O, "vt", 1, 3, &O->nvt, e);
    else if (is(t, n, "vn"))
        rc = attribute(O, "vn", 3, 3, &O->nvn, e);
    else if (is(t, n, "vp"))
        rc = attribute(O, "vp", 1, 3, NULL, e);
    else if (is(t, n, "g") || is(t, n, "o"))
        group(O);
    else if (in_list(t, n, ignored))
        rc = 0;
    else if (in_list(t, n, freeform))
        rc = err_set(e, O->name, O->line, "free-form geometry ('%s') is not supported: export the surface as polygons",
                     show(t, n, b));
    else if (is(t, n, "call") || is(t, n, "csh"))
        rc = err_set(e, O->name, O->line, "'%s' is not supported", show(t, n, b));
    else
        rc = err_set(e, O->name, O->line, "unknown OBJ statement '%s'", show(t, n, b));
    if (!rc) skip_statement(O);
    return rc;
}

static int check_max(const Obj *O, long long max, int line, size_t have, const Kind *k, Err *e)
{
    if (max <= (long long)have) return 0;
    return err_set(e, O->name, line, "%s index %lld out of range: the file has %zu %s", k->one, max, have,
                   have == 1 ? k->one : k->many);
}

/* ---------------------------------------------------------------- triangulation */

typedef struct Ring {
    double *q;          /* 2 per corner: the projection */
    int *prev, *next;
    size_t cap;
} Ring;

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int same2(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* Corner b (neighbours a, c) is an ear at this level: 0 convex and no
   other corner in the closed triangle, 1 convex or flat, 2 always. */
static int ear(const Ring *R, int b, double sgn, int level)
{
    int a = R->prev[b], c = R->next[b];
    const double *qa = R->q + 2 * a, *qb = R->q + 2 * b, *qc = R->q + 2 * c;
    double turn = sgn * orient2(qa, qb, qc);
    if (level == 2) return 1;
    if (level == 1) return turn >= 0;
    if (turn <= 0) return 0;
    for (int p = R->next[c]; p != a; p = R->next[p]) {
        const double *qp = R->q + 2 * p;
        if (same2(qp, qa) || same2(qp, qb) || same2(qp, qc)) continue;
        if (sgn * orient2(qa, qb, qp) >= 0 && sgn * orient2(qb, qc, qp) >= 0 && sgn * orient2(qc, qa, qp) >= 0)
            return 0;
    }
    return 1;
}

static void push_tri(Soup *S, const double *P, int i, int j, int k, int tag)
{
    double c[9];
    memcpy(c, P + 3 * (size_t)i, 3 * sizeof *c);
    memcpy(c + 3, P + 3 * (size_t)j, 3 * sizeof *c);
    memcpy(c + 6, P + 3 * (size_t)k, 3 * sizeof *c);
    soup_push(S, c, tag);
}

/* The face with corners idx[0..n) into n - 2 triangles of the soup. */
static void triangulate(Soup *S, const double *P, const int *idx, int n, int tag, Ring *R)
{
    double N[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {   /* Newell's normal */
        const double *a = P + 3 * (size_t)idx[i], *b = P + 3 * (size_t)idx[(i + 1) % n];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    int k = fabs(N[0]) >= fabs(N[1]) && fabs(N[0]) >= fabs(N[2]) ? 0 : fabs(N[1]) >= fabs(N[2]) ? 1 : 2;
    int u = (k + 1) % 3, w = (k + 2) % 3;
    double sgn = N[k] > 0 ? 1 : N[k] < 0 ? -1 : 0;
    if (n == 3 || sgn == 0) {   /* a triangle, or no area to keep inside of: the fan */
        for (int i = 1; i + 1 < n; i++) push_tri(S, P, idx[0], idx[i], idx[i + 1], tag);
        return;
    }
    if ((size_t)n > R->cap) {
        R->cap = (size_t)n;
        R->q = mem_realloc(R->q, 2 * R->cap * sizeof *R->q);
        R->prev = mem_realloc(R->prev, R->cap * sizeof *R->prev);
        R->next = mem_realloc(R->next, R->cap * sizeof *R->next);
    }
    for (int i = 0; i < n; i++) {
        R->q[2 * i] = P[3 * (size_t)idx[i] + u];
        R->q[2 * i + 1] = P[3 * (size_t)idx[i] + w];
        R->prev[i] = (i + n - 1) % n;
        R->next[i] = (i + 1) % n;
    }
    int left = n, cur = 1, misses = 0, level = 0;
    while (left > 3) {
        if (ear(R, cur, sgn, level)) {
            int a = R->prev[cur], c = R->next[cur];
            push_tri(S, P, idx[a], idx[cur], idx[c], tag);
            R->next[a] = c;
            R->prev[c] = a;
            left--;
            cur = c;
            misses = level = 0;
        } else {
            cur = R->next[cur];
            if (++misses >= left) {
                misses = 0;
                level++;
            }
        }
    }
    push_tri(S, P, idx[R->prev[cur]], idx[cur], idx[R->next[cur]], tag);
}

/* ---------------------------------------------------------------- parse */

int obj_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e)
{
    trisurf_init(s);
    if (!name) name = "<obj>";
    if (n >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) data += 3, n -= 3;   /* a UTF-8 byte-order mark */
    Obj O;
    memset(&O, 0, sizeof O);
    O.p = data;
    O.end = data + n;
    O.name = name;
    O.line = 1;
    O.tag = -1;
    while (O.p < O.end)
        if (statement(&O, e)) {
            obj_free(&O);
            return -1;
        }
    if (check_max(&O, O.vmax, O.vmax_line, O.nv, &K_V, e) || check_max(&O, O.vtmax, O.vtmax_line, O.nvt, &K_VT, e)
        || check_max(&O, O.vnmax, O.vnmax_line, O.nvn, &K_VN, e)) {
        obj_free(&O);
        return -1;
    }
    Ring R = {0};
    for (size_t f = 0; f < O.nface; f++)
        triangulate(&O.S, O.v, O.corner + O.fofs[f], (int)(O.fofs[f + 1] - O.fofs[f]), O.ftag[f], &R);
    free(R.q);
    free(R.prev);
    free(R.next);
    int rc = soup_finish(&O.S, s, 1, name, "no faces in OBJ file (a surface needs 'f' statements)", e);
    obj_free(&O);
    return rc;
}

int obj_read(TriSurf *s, const char *path, Err *e)
{
    trisurf_init(s);
    Buf b;
    buf_init(&b);
    char *found = NULL;
    if (io_read_file(path, &b, &found, e)) return -1;
    int rc = obj_parse(s, b.p, b.n, found ? found : path, e);
    free(found);
    buf_free(&b);
    return rc;
}

/* ---------------------------------------------------------------- sniff */

int obj_sniff(const char *data, size_t n)
{
    static const char *const first[] = {"v", "vt", "vn", "vp", "f", "g", "o", "s", "l", "p", "mtllib", "usemtl", NULL};
    if (memchr(data, '\0', n < 4096 ? n : 4096)) return 0;
    Obj O;
    memset(&O, 0, sizeof O);
    O.p = data;
    O.end = data + n;
    if (n >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) O.p += 3;
    while (O.p < O.end) {
        const char *t;
        size_t m;
        if (tok(&O, &t, &m)) return in_list(t, m, first);
        skip_statement(&O);
    }
    return 0;
}
