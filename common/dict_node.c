/*
** dict_node.c: value nodes: their descriptions for messages, and the
** accessors that turn a list node into a C array.
**
** The parser chooses the storage of a list (dict.h: DN_LIST of nodes, or
** compact DN_NUMS, DN_LABELS, DN_RAGGED); the accessors accept every
** storage that can hold what is asked for, so callers never care which
** one the parser chose: 10 integers as doubles, equal tuples as faces,
** a list of nodes item by item.  Errors name the first bad item with its
** own line ("item 3 of the list: expected a number, found word 'nan'").
** The _take forms hand over a compact array instead of copying it.
*/
#include "dict_impl.h"
#include "mem.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---- descriptions for messages ---- */

const char *dict_node_kind_name(const DictNode *nd)
{
    switch (nd->kind) {
    case DN_WORD: return "word";
    case DN_STRING: return "string";
    case DN_NUMBER: return "number";
    case DN_PUNCT: return "punctuation";
    case DN_LIST: return "list";
    case DN_DIMS: return "dimension set";
    case DN_DICT: return "dictionary";
    case DN_NUMS: return "list of numbers";
    case DN_LABELS: return "list of integers";
    case DN_RAGGED: return "list of integer lists";
    }
    return "value";
}

/* "word 'abc'", "list of 3 items": a description for messages. */
void dict_node_describe(const DictNode *nd, char *s, size_t n)
{
    switch (nd->kind) {
    case DN_WORD:
    case DN_STRING:
    case DN_NUMBER:
    case DN_PUNCT:
        snprintf(s, n, "%s '%.60s'", dict_node_kind_name(nd), nd->text ? nd->text : "");
        break;
    case DN_DICT:
    case DN_DIMS:
        snprintf(s, n, "%s", dict_node_kind_name(nd));
        break;
    case DN_NUMS:
        if (nd->width > 1) {
            snprintf(s, n, "list of %zu %d-tuples", nd->n, nd->width);
            break;
        }
        /* fall through */
    default:
        snprintf(s, n, "list of %zu items", nd->n);
        break;
    }
}

/* ---- lists to arrays ---- */

int dict_node_is_list(const DictNode *nd)
{
    return nd->kind == DN_LIST || nd->kind == DN_NUMS || nd->kind == DN_LABELS || nd->kind == DN_RAGGED;
}

size_t dict_node_len(const DictNode *nd)
{
    switch (nd->kind) {
    case DN_LIST:
    case DN_NUMS:
    case DN_LABELS:
    case DN_RAGGED:
        return nd->n;
    default:
        return 0;
    }
}

static int node_err(const DictNode *nd, const char *want, Err *e)
{
    char what[128];
    dict_node_describe(nd, what, sizeof what);
    return err_set(e, nd->file, nd->line, "expected %s, found %s", want, what);
}

int dict_node_tuple(const DictNode *t, int w, double *out)
{
    if (t->kind == DN_NUMS && t->width == 1 && t->n == (size_t)w) {
        memcpy(out, t->v, (size_t)w * sizeof(double));
        return 0;
    }
    if (t->kind == DN_LABELS && t->n == (size_t)w) {
        for (int k = 0; k < w; k++) out[k] = t->iv[k];
        return 0;
    }
    if (t->kind == DN_LIST && t->n == (size_t)w) {
        for (int k = 0; k < w; k++) {
            if (t->items[k]->kind != DN_NUMBER) return -1;
            out[k] = t->items[k]->num;
        }
        return 0;
    }
    return -1;
}

/* A word spelling a number that is not finite: OpenFOAM writes nan and
   inf (any case, signed) but reads them as words, and so does the parser. */
static int nonfinite_word(const DictNode *t)
{
    if (t->kind != DN_WORD || !t->text) return 0;
    const char *s = t->text + (t->text[0] == '-' || t->text[0] == '+');
    return strcasecmp(s, "nan") == 0 || strcasecmp(s, "inf") == 0 || strcasecmp(s, "infinity") == 0;
}

const DictNode *dict_node_nonfinite(const DictNode *nd, size_t *item)
{
    *item = 0;
    if (nonfinite_word(nd)) return nd;
    if (nd->kind != DN_LIST) return NULL;
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *t = nd->items[i];
        const DictNode *w = nonfinite_word(t) ? t : NULL;
        for (size_t k = 0; !w && t->kind == DN_LIST && k < t->n; k++)
            if (nonfinite_word(t->items[k])) w = t->items[k];
        if (w) {
            *item = i;
            return w;
        }
    }
    return NULL;
}

/* The error for item i (t) of a list that should hold numbers or
   tuples (want: "a list of 3-tuples"); a non-finite word is named. */
static int item_error(const DictNode *nd, size_t i, const DictNode *t, int width, const char *want, Err *e)
{
    size_t k;
    const DictNode *nf = dict_node_nonfinite(nd, &k);
    if (nf && k == i)
        return err_set(e, nf->file, nf->line, "item %zu of the list: '%s' is not a finite number", i, nf->text);
    char what[128];
    dict_node_describe(t, what, sizeof what);
    return err_set(e, t->file, t->line, "item %zu of the list: expected %s, found %s", i,
                   width == 1 ? "a number" : want + 10, what);
}

/* dict_node_scalars of a DN_LIST: numbers, or tuples of width. */
static int scalars_from_list(const DictNode *nd, int width, const char *want, double **out, size_t *n, Err *e)
{
    size_t w = (size_t)width;
    if (nd->n > SIZE_MAX / sizeof(double) / w) return node_err(nd, want, e);
    size_t nw = nd->n * w;
    double *v = MEM_NEW(double, nw);
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *t = nd->items[i];
        int bad = w == 1 ? t->kind != DN_NUMBER : dict_node_tuple(t, width, v + i * w) != 0;
        if (bad) {
            free(v);
            return item_error(nd, i, t, width, want, e);
        }
        if (w == 1) v[i] = t->num;
    }
    *out = v;
    *n = nd->n;
    return 0;
}

int dict_node_scalars(const DictNode *nd, int width, double **out, size_t *n, Err *e)
{
    char want[64];
    if (width < 1) width = 1;
    size_t w = (size_t)width;
    if (width == 1) snprintf(want, sizeof want, "a list of numbers");
    else snprintf(want, sizeof want, "a list of %d-tuples", width);
    if (nd->kind == DN_NUMS && (size_t)nd->width == w) {
        *out = dict_dup_mem(nd->v, nd->n * w * sizeof(double));
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_LABELS && w == 1) {
        double *v = MEM_NEW(double, nd->n);
        for (size_t i = 0; i < nd->n; i++) v[i] = nd->iv[i];
        *out = v;
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_RAGGED && w > 1) {
        for (size_t i = 0; i < nd->n; i++)
            if ((size_t)(nd->off[i + 1] - nd->off[i]) != w) return node_err(nd, want, e);
        size_t nw = nd->n * w;
        double *v = MEM_NEW(double, nw);
        for (size_t i = 0; i < nw; i++) v[i] = nd->iv[i];
        *out = v;
        *n = nd->n;
        return 0;
    }
    if (nd->kind != DN_LIST) return node_err(nd, want, e);
    return scalars_from_list(nd, width, want, out, n, e);
}

static int int_item(const DictNode *t, int *out)
{
    if (t->kind != DN_NUMBER || !t->is_int || !dict_fits_int(t->num)) return -1;
    *out = (int)t->num;
    return 0;
}

int dict_node_labels(const DictNode *nd, int **out, size_t *n, Err *e)
{
    if (nd->kind == DN_LABELS) {
        *out = dict_dup_mem(nd->iv, nd->n * sizeof(int));
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_NUMS && nd->width == 1) {
        for (size_t i = 0; i < nd->n; i++)
            if (!dict_fits_int(nd->v[i])) return node_err(nd, "a list of integers", e);
        int *v = MEM_NEW(int, nd->n);
        for (size_t i = 0; i < nd->n; i++) v[i] = (int)nd->v[i];
        *out = v;
        *n = nd->n;
        return 0;
    }
    if (nd->kind != DN_LIST) return node_err(nd, "a list of integers", e);
    int *v = MEM_NEW(int, nd->n);
    for (size_t i = 0; i < nd->n; i++)
        if (int_item(nd->items[i], &v[i])) {
            free(v);
            return node_err(nd->items[i], "an integer", e);
        }
    *out = v;
    *n = nd->n;
    return 0;
}

/* dict_node_faces of equal tuples (DN_NUMS width > 1) of integers. */
static int faces_from_nums(const DictNode *nd, int **off, int **idx, size_t *n, Err *e)
{
    size_t w = (size_t)nd->width;
    if (nd->n * w > INT_MAX) return node_err(nd, "a list of integer lists", e);
    for (size_t i = 0; i < nd->n * w; i++)
        if (!dict_fits_int(nd->v[i])) return node_err(nd, "a list of integer lists", e);
    if (w == 1 && nd->n) return node_err(nd, "a list of integer lists", e);
    size_t nw = nd->n * w;
    int *o = MEM_NEW(int, nd->n + 1), *x = MEM_NEW(int, nw);
    for (size_t i = 0; i <= nd->n; i++) o[i] = (int)(i * w);
    for (size_t i = 0; i < nd->n * w; i++) x[i] = (int)nd->v[i];
    *off = o;
    *idx = x;
    *n = nd->n;
    return 0;
}

/* Item j of an integer list t into *x; -1 when it is no int. */
static int face_item(const DictNode *t, size_t j, int *x)
{
    if (t->kind == DN_LABELS) {
        *x = t->iv[j];
        return 0;
    }
    if (t->kind == DN_NUMS) {
        int bad = !dict_fits_int(t->v[j]);
        *x = bad ? 0 : (int)t->v[j];
        return bad ? -1 : 0;
    }
    return int_item(t->items[j], x);
}

/* dict_node_faces of a DN_LIST of integer lists. */
static int faces_from_list(const DictNode *nd, int **off, int **idx, size_t *n, Err *e)
{
    size_t tot = 0;
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *t = nd->items[i];
        if (t->kind != DN_LABELS && t->kind != DN_LIST && !(t->kind == DN_NUMS && t->width == 1))
            return node_err(t, "an integer list", e);
        tot += t->n;
    }
    if (tot > INT_MAX) return node_err(nd, "a list of integer lists", e);
    int *o = MEM_NEW(int, nd->n + 1), *x = MEM_NEW(int, tot);
    size_t k = 0;
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *t = nd->items[i];
        o[i] = (int)k;
        for (size_t j = 0; j < t->n; j++, k++)
            if (face_item(t, j, &x[k])) {
                free(o);
                free(x);
                return node_err(t->kind == DN_LIST ? t->items[j] : t, "an integer", e);
            }
    }
    o[nd->n] = (int)k;
    *off = o;
    *idx = x;
    *n = nd->n;
    return 0;
}

int dict_node_faces(const DictNode *nd, int **off, int **idx, size_t *n, Err *e)
{
    if (nd->kind == DN_RAGGED) {
        *off = dict_dup_mem(nd->off, (nd->n + 1) * sizeof(int));
        *idx = dict_dup_mem(nd->iv, (size_t)nd->off[nd->n] * sizeof(int));
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_NUMS) return faces_from_nums(nd, off, idx, n, e);
    if (nd->kind != DN_LIST) return node_err(nd, "a list of integer lists", e);
    return faces_from_list(nd, off, idx, n, e);
}

int dict_node_take_scalars(DictNode *nd, int width, double **out, size_t *n, Err *e)
{
    if (nd->kind == DN_NUMS && nd->width == width && nd->v) {
        *out = nd->v;
        *n = nd->n;
        nd->v = NULL;
        nd->n = 0;
        return 0;
    }
    return dict_node_scalars(nd, width, out, n, e);
}

int dict_node_take_labels(DictNode *nd, int **out, size_t *n, Err *e)
{
    if (nd->kind == DN_LABELS && nd->iv) {
        *out = nd->iv;
        *n = nd->n;
        nd->iv = NULL;
        nd->n = 0;
        return 0;
    }
    return dict_node_labels(nd, out, n, e);
}
