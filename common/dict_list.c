/*
** dict_list.c: ascii lists: "( ... )", sized "N( ... )" and uniform
** "N{value}", stored compactly (dict.h: DN_NUMS, DN_LABELS, DN_RAGGED).
**
** Big numeric lists (points, fields, faces) go through a fast path that
** scans numbers straight into flat arrays without creating nodes;
** anything unusual inside (a comment, a word, a nested dictionary) makes
** it give up and the general path parses the list into nodes, which are
** then compacted by the same rules, so the result never depends on which
** path ran.  Compaction rules: all numbers -> DN_LABELS when every one is
** an integer in int range (not "-0"), else DN_NUMS width 1; all
** equal-length numeric tuples -> DN_NUMS of that width; integer lists of
** different lengths -> DN_RAGGED, where an inner list counts as integers
** by value (1e1 as 10), since dict_write prints it so:
** write(parse(write(d))) == write(d) is what the fuzzer checks.
**
** Sizes: every size is checked against the items read; a list of
** name-dictionary pairs ("N ( name { } ... )") counts its pairs.  A
** uniform list is bounded (MAX_UNIFORM numbers), so "1000000000{0}"
** cannot exhaust memory.
*/
#include "dict_impl.h"
#include "foam.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_UNIFORM = 1 << 25 };   /* numbers created by an N{v} shorthand */

/* A number a DN_LABELS list may hold: "-0" is not one, as it would be
   written back as 0 and the list would not read back the same. */
static inline int label_value(double x, int is_int) { return is_int && dict_fits_int(x) && !(x == 0 && signbit(x)); }

/* ---- compaction ---- */

/* Items that make a width-w numeric tuple: a LABELS or NUMS width 1. */
static int tuple_len(const DictNode *nd)
{
    if ((nd->kind == DN_LABELS || (nd->kind == DN_NUMS && nd->width == 1)) && nd->n > 0 && nd->n <= INT_MAX)
        return (int)nd->n;
    return -1;
}

/* A list of integers: LABELS, or NUMS whose values all are labels (1e1
   is written back as 10, so it must compact the same way as 10). */
static int int_list(const DictNode *nd)
{
    if (nd->kind == DN_LABELS) return 1;
    if (nd->kind != DN_NUMS || nd->width != 1) return 0;
    for (size_t i = 0; i < nd->n; i++)
        if (!label_value(nd->v[i], 1)) return 0;
    return 1;
}

/* Numbers v[0..n) (taken) as DN_LABELS when every one is a label,
   else as DN_NUMS width 1. */
static DictNode *numbers_node(Parser *P, int line, double *v, size_t n, int labels)
{
    DictNode *nd;
    if (labels) {
        nd = dict_node_new(DN_LABELS, P->file, line);
        nd->iv = MEM_NEW(int, n);
        for (size_t i = 0; i < n; i++) nd->iv[i] = (int)v[i];
        free(v);
    } else {
        nd = dict_node_new(DN_NUMS, P->file, line);
        nd->width = 1;
        nd->v = v;
    }
    nd->n = n;
    return nd;
}

/* n numeric tuples of width w (tuple_len) as one DN_NUMS; NULL when too big. */
static DictNode *tuples_node(Parser *P, const DictNodeVec *it, int w, int line)
{
    size_t n = it->n;
    if ((size_t)w > SIZE_MAX / sizeof(double) / n) return NULL;
    DictNode *nd = dict_node_new(DN_NUMS, P->file, line);
    nd->width = w;
    size_t nw = n * (size_t)w;
    nd->v = MEM_NEW(double, nw);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < w; k++) {
            const DictNode *t = it->v[i];
            nd->v[i * (size_t)w + (size_t)k] = t->kind == DN_LABELS ? t->iv[k] : t->v[k];
        }
    nd->n = n;
    return nd;
}

/* Integer lists (int_list) of different lengths as one DN_RAGGED. */
static DictNode *ragged_node(Parser *P, const DictNodeVec *it, int line)
{
    size_t n = it->n, tot = 0;
    for (size_t i = 0; i < n; i++) tot += it->v[i]->n;
    if (tot > INT_MAX) return NULL;
    DictNode *nd = dict_node_new(DN_RAGGED, P->file, line);
    nd->off = MEM_NEW(int, n + 1);
    nd->iv = MEM_NEW(int, tot);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        const DictNode *t = it->v[i];
        nd->off[i] = (int)k;
        for (size_t j = 0; j < t->n; j++) nd->iv[k + j] = t->kind == DN_LABELS ? t->iv[j] : (int)t->v[j];
        k += t->n;
    }
    nd->off[n] = (int)k;
    nd->n = n;
    return nd;
}

/* Items that all are numeric tuples: equal widths or integer lists. */
static DictNode *compact_tuples(Parser *P, const DictNodeVec *it, int line)
{
    int w = tuple_len(it->v[0]), same = 1, all_ilist = 1;
    for (size_t i = 0; i < it->n && w > 0; i++) {
        int wi = tuple_len(it->v[i]);
        if (wi < 0) return NULL;
        if (wi != w) same = 0;
        if (!int_list(it->v[i])) all_ilist = 0;
    }
    if (w <= 0) return NULL;
    if (same) return tuples_node(P, it, w, line);
    return all_ilist ? ragged_node(P, it, line) : NULL;
}

/* Replaces items by a compact node when the rules at the top allow;
   returns the node (taking the items) or NULL (items untouched). */
static DictNode *compact(Parser *P, DictNodeVec *it, int line)
{
    size_t n = it->n;
    if (n == 0) return NULL;
    int all_num = 1, all_lab = 1;
    for (size_t i = 0; i < n && all_num; i++) {
        all_num = it->v[i]->kind == DN_NUMBER;
        if (all_num && !label_value(it->v[i]->num, it->v[i]->is_int)) all_lab = 0;
    }
    DictNode *nd;
    if (all_num) {
        double *v = MEM_NEW(double, n);
        for (size_t i = 0; i < n; i++) v[i] = it->v[i]->num;
        nd = numbers_node(P, line, v, n, all_lab);
    } else if (!(nd = compact_tuples(P, it, line))) {
        return NULL;
    }
    for (size_t i = 0; i < n; i++) dict_node_free(it->v[i]);
    it->n = 0;
    return nd;
}

/* The items as a compact node, or else as a DN_LIST (taking them). */
static DictNode *list_node(Parser *P, DictNodeVec *it, int line)
{
    DictNode *nd = compact(P, it, line);
    if (nd) {
        free(it->v);
        return nd;
    }
    nd = dict_node_new(DN_LIST, P->file, line);
    nd->n = it->n;
    nd->items = it->v;
    return nd;
}

/* ---- fast path for big numeric lists ---- */

typedef enum { UNSET, SCALARS, TUPLES, SIZED } FastMode;

/* What the fast path has read: every number in v, the start of every
   sized item in off; mode says which form the first item set. */
typedef struct Fast {
    double *v;
    size_t nv, cv;
    int *off;
    size_t noff, coff;
    int all_int;
    FastMode mode;
    int width;               /* of the tuples */
} Fast;

static void fast_free(Fast *f)
{
    free(f->v);
    free(f->off);
}

static inline void fast_push(Fast *f, double x, int is_int)
{
    if (f->nv == f->cv) mem_grow((void **)&f->v, &f->cv, f->nv + 1, sizeof *f->v);
    f->v[f->nv++] = x;
    if (!label_value(x, is_int)) f->all_int = 0;
}

static void fast_push_off(Fast *f, size_t k)
{
    if (f->noff == f->coff) mem_grow((void **)&f->off, &f->coff, f->noff + 1, sizeof *f->off);
    f->off[f->noff++] = (int)k;
}

/* Whether the sized items starting at off[0..noff) (the last ending at
   nv) all have the same positive length, returned in *width. */
static int equal_lengths(const int *off, size_t noff, size_t nv, int *width)
{
    if (noff == 0) return 0;
    size_t w = (noff > 1 ? (size_t)off[1] : nv) - (size_t)off[0];
    for (size_t i = 0; i < noff; i++) {
        size_t next = i + 1 < noff ? (size_t)off[i + 1] : nv;
        if (next - (size_t)off[i] != w) return 0;
    }
    if (w == 0 || w > INT_MAX) return 0;
    *width = (int)w;
    return 1;
}

/* Scans whitespace only (a comment makes the fast path give up). */
static inline const char *fast_ws(const char *p, const char *end, int *line)
{
    while (p < end && dict_is_space(*p)) {
        if (*p == '\n') (*line)++;
        p++;
    }
    return p;
}

/* One number ending at a delimiter, or NULL. */
static inline const char *fast_num(const char *p, const char *end, double *x, int *is_int)
{
    size_t n = foam_parse_number(p, end, x, is_int);
    if (n == 0 || !dict_is_delim(p + n, end) || !isfinite(*x)) return NULL;
    return p + n;
}

/* "(x y ...)" at p: pushes its numbers, *k their count; returns the end,
   or NULL to give up. */
static const char *fast_tuple(const char *p, const char *end, int *line, Fast *f, int *k)
{
    *k = 0;
    p++;
    for (;;) {
        p = fast_ws(p, end, line);
        if (p >= end) return NULL;
        if (*p == ')') return p + 1;
        double x;
        int is_int;
        if (!(p = fast_num(p, end, &x, &is_int))) return NULL;
        fast_push(f, x, is_int);
        (*k)++;
    }
}

/* "N(i j ...)" with q on the '(': pushes N labels; returns the end, or
   NULL to give up. */
static const char *fast_sized(const char *q, const char *end, int *line, Fast *f, double size)
{
    fast_push_off(f, f->nv);
    size_t k0 = f->nv, want = (size_t)size;
    const char *p = q + 1;
    for (;;) {
        p = fast_ws(p, end, line);
        if (p >= end) return NULL;
        if (*p == ')') break;
        double x;
        int is_int;
        if (!(p = fast_num(p, end, &x, &is_int)) || !label_value(x, is_int)) return NULL;
        fast_push(f, x, is_int);
    }
    if (f->nv - k0 != want || f->nv > INT_MAX) return NULL;
    return p + 1;
}

/* One item at p (a tuple, a sized list or a number), of the form the
   first item chose; returns the end, or NULL to give up. */
static const char *fast_item(const char *p, const char *end, int *line, Fast *f)
{
    if (*p == '(') {
        if (f->mode == UNSET) f->mode = TUPLES;
        if (f->mode != TUPLES) return NULL;
        int k;
        if (!(p = fast_tuple(p, end, line, f, &k))) return NULL;
        if (f->width == 0) f->width = k;
        return k == 0 || k != f->width ? NULL : p;
    }
    double x;
    int is_int;
    const char *q = fast_num(p, end, &x, &is_int);
    if (!q) return NULL;
    if (q < end && *q == '(') {
        if (f->mode == UNSET) f->mode = SIZED;
        if (f->mode != SIZED || !is_int || x < 0 || x > INT_MAX) return NULL;
        return fast_sized(q, end, line, f, x);
    }
    if (f->mode == UNSET) f->mode = SCALARS;
    if (f->mode != SCALARS) return NULL;
    fast_push(f, x, is_int);
    return q;
}

/* The node for n items the fast path read (taking f's arrays). */
static DictNode *fast_node(Parser *P, Fast *f, size_t n, int line)
{
    if (f->mode == SIZED && equal_lengths(f->off, f->noff, f->nv, &f->width)) {
        f->mode = TUPLES;   /* same rule as compact(): equal tuples -> DN_NUMS */
        free(f->off);
        f->off = NULL;
    }
    DictNode *nd;
    if (f->mode == SIZED) {
        fast_push_off(f, f->nv);
        nd = dict_node_new(DN_RAGGED, P->file, line);
        nd->off = f->off;
        nd->iv = MEM_NEW(int, f->nv);
        for (size_t i = 0; i < f->nv; i++) nd->iv[i] = (int)f->v[i];
        free(f->v);
        nd->n = n;
        return nd;
    }
    free(f->off);
    if (f->mode == SCALARS) return numbers_node(P, line, f->v, n, f->all_int);
    nd = dict_node_new(DN_NUMS, P->file, line);
    nd->width = f->width;
    nd->v = f->v;
    nd->n = n;
    return nd;
}

/* Tries to read the list at P->p ('(') as numbers, equal tuples or sized
   integer lists.  Returns the node and advances P, or NULL (P untouched)
   when the list needs the general path. */
static DictNode *fast_list(Parser *P, long size)
{
    const char *p = P->p + 1, *end = P->end;
    int line = P->line, line0 = P->line;
    Fast f = {NULL, 0, 0, NULL, 0, 0, 1, UNSET, 0};
    size_t n = 0;
    if (size > 0) {
        size_t want = (size_t)size, room = (size_t)(end - p) / 2 + 1;
        mem_grow((void **)&f.v, &f.cv, want < room ? want : room, sizeof *f.v);
    }
    for (;;) {
        p = fast_ws(p, end, &line);
        if (p < end && *p == ')') break;
        if (p >= end || !(p = fast_item(p, end, &line, &f))) {
            fast_free(&f);
            return NULL;
        }
        n++;
    }
    if (n == 0) {
        fast_free(&f);
        return NULL;
    }
    DictNode *nd = fast_node(P, &f, n, line0);
    P->p = p + 1;
    P->line = line;
    return nd;
}

/* ---- lists ---- */

/* "N ( name { ... } ... )" counts name-dictionary pairs (polyMesh
   boundary, blockMesh boundary). */
int dict_list_pairs(const DictNode *nd, size_t size)
{
    if (nd->kind != DN_LIST || nd->n != 2 * size) return 0;
    for (size_t i = 0; i < nd->n; i += 2)
        if ((nd->items[i]->kind != DN_WORD && nd->items[i]->kind != DN_STRING) || nd->items[i + 1]->kind != DN_DICT)
            return 0;
    return 1;
}

/* The item count a size prefix gives: a list of name-dictionary pairs
   counts its pairs, as OpenFOAM's PtrList<entry> does, every other list
   its items. */
size_t dict_list_counted(const DictNode *nd)
{
    if (nd->kind == DN_LIST && nd->n > 0 && nd->n % 2 == 0 && dict_list_pairs(nd, nd->n / 2)) return nd->n / 2;
    return dict_node_is_list(nd) ? nd->n : 0;
}

/* The error for a size prefix that does not count its list, after the
   prefix what ("keyword 'x': ", "internalField: " or ""). */
static int size_error(Parser *P, int line, const char *what, double size, const DictNode *nd)
{
    char pairs[80] = "";
    if (dict_list_counted(nd) != nd->n)
        snprintf(pairs, sizeof pairs, " (%zu name-dictionary pairs: the size counts the pairs)", dict_list_counted(nd));
    return dict_perr(P, line, "%slist size %.0f does not match the %zu items read%s", what, size, nd->n, pairs);
}

/* A size written apart from its list, "x 3 (1 2 3);" or "List<scalar> 3
   (1 2 3)": the values keep the number as a node of its own, because in
   "arc 1 5 (0 1 0)" it is one.  Where it can only be a size, as the whole
   value of an entry (whole: the values are an entry's) or right after a
   List<T> word, it must count the list, as OpenFOAM's List reader
   requires.  key names the entry in messages (NULL: none). */
int dict_list_check_sizes(Parser *P, const DictNodeVec *v, int whole, const char *key)
{
    for (size_t i = 0; i + 1 < v->n; i++) {
        const DictNode *a = v->v[i], *b = v->v[i + 1], *t = i > 0 ? v->v[i - 1] : NULL;
        int typed = t && t->kind == DN_WORD && strncmp(t->text, "List<", 5) == 0;
        if (!(typed || (whole && v->n == 2)) || a->kind != DN_NUMBER || !a->is_int || a->num < 0) continue;
        if (!dict_node_is_list(b)) continue;
        if (a->num == (double)dict_list_counted(b)) continue;
        char what[300] = "";
        if (key && key[0]) snprintf(what, sizeof what, typed ? "%.200s: " : "keyword '%.200s': ", key);
        return size_error(P, b->line, what, a->num, b);
    }
    return 0;
}

/* The general path for the list at P->p ('('): its items as nodes,
   compacted where the rules allow; NULL on error.  A word names the
   dictionary after it, for messages. */
static DictNode *general_list(Parser *P, Dict *d, int line0)
{
    DictNodeVec it = {NULL, 0, 0};
    P->p++;
    char *hint = NULL;
    for (;;) {
        if (dict_lex_ws(P)) goto fail;
        if (P->p >= P->end) {
            dict_perr(P, line0, "unterminated list started at line %d", line0);
            goto fail;
        }
        char c = *P->p;
        if (c == ')') break;
        if (c == ';' || c == '}') {
            dict_perr(P, P->line, "unexpected '%c' inside the list started at line %d", c, line0);
            goto fail;
        }
        size_t before = it.n;
        if (dict_parse_value(P, d, &it, hint)) goto fail;
        free(hint);
        hint = NULL;
        if (it.n == before + 1 && it.v[before]->kind == DN_WORD) hint = mem_strdup(it.v[before]->text);
    }
    free(hint);
    hint = NULL;
    P->p++;
    if (dict_list_check_sizes(P, &it, 0, NULL)) goto fail;
    return list_node(P, &it, line0);
fail:
    free(hint);
    dict_nv_free(&it);
    return NULL;
}

/* The list at P->p ('('); size < 0 when no size was given. */
int dict_list_parse(Parser *P, Dict *d, long size, int line, DictNodeVec *out)
{
    if (dict_parse_nest(P)) return -1;
    int line0 = P->line;
    DictNode *nd = fast_list(P, size);
    if (!nd && !(nd = general_list(P, d, line0))) return -1;
    P->depth--;
    if (size >= 0 && dict_list_counted(nd) != (size_t)size) {
        size_error(P, line, "", (double)size, nd);
        dict_node_free(nd);
        return -1;
    }
    dict_nv_push(out, nd);
    return 0;
}

/* ---- uniform lists N{value} ---- */

/* Whether n copies of v would pass the bound; span (the bytes of v's
   text) bounds the cost of copying a value that is no number. */
static int uniform_too_large(const DictNode *v, size_t n, size_t span)
{
    if (v->kind == DN_NUMBER) return n > MAX_UNIFORM;
    if (tuple_len(v) > 0) return n > MAX_UNIFORM / v->n;
    return n > 100000 || n * span > MAX_UNIFORM;
}

/* n copies of a number, stored as compact() would. */
static DictNode *uniform_number(Parser *P, const DictNode *v, size_t n, int line)
{
    DictNode *nd;
    if (label_value(v->num, v->is_int)) {
        nd = dict_node_new(DN_LABELS, P->file, line);
        nd->iv = MEM_NEW(int, n);
        for (size_t i = 0; i < n; i++) nd->iv[i] = (int)v->num;
    } else {
        nd = dict_node_new(DN_NUMS, P->file, line);
        nd->width = 1;
        nd->v = MEM_NEW(double, n);
        for (size_t i = 0; i < n; i++) nd->v[i] = v->num;
    }
    nd->n = n;
    return nd;
}

/* N{(x y z)}: n equal tuples, stored as compact() would. */
static DictNode *uniform_tuple(Parser *P, const DictNode *v, size_t n, int line)
{
    size_t w = v->n;
    double t[64];
    double *tv = w <= 64 ? t : MEM_NEW(double, w);
    for (size_t k = 0; k < w; k++) tv[k] = v->kind == DN_LABELS ? v->iv[k] : v->v[k];
    DictNode *nd = dict_node_new(DN_NUMS, P->file, line);
    nd->width = (int)w;
    size_t nw = n * w;
    nd->v = MEM_NEW(double, nw);
    for (size_t i = 0; i < n; i++) memcpy(nd->v + i * w, tv, w * sizeof(double));
    if (tv != t) free(tv);
    nd->n = n;
    return nd;
}

/* n copies of any other value, compacted as a list would be. */
static DictNode *uniform_copies(Parser *P, Dict *d, const DictNode *v, size_t n, int line)
{
    DictNodeVec it = {NULL, 0, 0};
    for (size_t i = 0; i < n; i++) dict_nv_push(&it, dict_node_copy(v, d));
    return list_node(P, &it, line);
}

/* N{value}: N copies of one value (P->p on the '{'). */
int dict_list_uniform(Parser *P, Dict *d, long size, int line, DictNodeVec *out)
{
    int line0 = P->line;
    P->p++;
    DictNodeVec one = {NULL, 0, 0};
    if (dict_lex_ws(P)) return -1;
    const char *v0 = P->p;
    if (P->p < P->end && *P->p != '}' && dict_parse_value(P, d, &one, NULL)) goto fail;
    size_t span = (size_t)(P->p - v0) + 1;   /* bounds the cost of copies */
    if (dict_lex_ws(P)) goto fail;
    if (P->p >= P->end || *P->p != '}' || one.n != 1) {
        dict_perr(P, line0, "expected one value and '}' in the uniform list %ld{...}", size);
        goto fail;
    }
    P->p++;
    const DictNode *v = one.v[0];
    size_t n = (size_t)size;
    if (uniform_too_large(v, n, span)) {
        dict_perr(P, line, "uniform list size %ld is too large", size);
        goto fail;
    }
    DictNode *nd = v->kind == DN_NUMBER  ? uniform_number(P, v, n, line)
                   : tuple_len(v) > 0 ? uniform_tuple(P, v, n, line)
                                      : uniform_copies(P, d, v, n, line);
    dict_nv_free(&one);
    dict_nv_push(out, nd);
    return 0;
fail:
    dict_nv_free(&one);
    return -1;
}
