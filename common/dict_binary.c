/*
** dict_binary.c: lists of raw binary data (FoamFile format binary).
**
** "N(" is raw data when the element type is known: the word List<T> just
** before it (dict_binary_type), or for a value without a keyword
** (polyMesh files) the FoamFile class (dict_binary_class_type).  Other
** lists are ascii even in binary files (inGroups 1(wall)), as OpenFOAM
** writes them.  Newlines inside raw data are not counted in line numbers
** (OpenFOAM does not either).  An empty binary list is "0" with no
** brackets.  Label and scalar sizes come from the header's arch string.
**
** On a little-endian host, label=32 and scalar=64 lists (what Kiesel and
** OpenFOAM write) are copied in one block and then checked in one pass
** (non-finite scalars); other layouts are decoded item by item.  Both
** give the same values and the same messages.
*/
#include "dict_impl.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

static const char *type_name(int w, int is_label)
{
    if (is_label) return "labels";
    switch (w) {
    case 1: return "scalars";
    case 2: return "vector2Ds";
    case 3: return "vectors";
    case 6: return "symmTensors";
    case 9: return "tensors";
    default: return "items";
    }
}

static uint64_t get_le(const unsigned char *s, int nbytes)
{
    uint64_t u = 0;
    for (int k = nbytes - 1; k >= 0; k--) u = (u << 8) | s[k];
    return u;
}

static int host_is_little(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

/* Index of the first inf or nan in v[0..n), or n.  A double is not
   finite when its exponent bits are all ones; the loop ORs a whole block
   of those tests so that it runs without a branch per item. */
static size_t first_non_finite(const double *v, size_t n)
{
    const uint64_t expo = 0x7ff0000000000000u;
    size_t i = 0;
    for (; i + 64 <= n; i += 64) {
        int any = 0;
        for (size_t k = 0; k < 64; k++) {
            uint64_t u;
            memcpy(&u, v + i + k, 8);
            any |= (u & expo) == expo;
        }
        if (any) break;
    }
    for (; i < n; i++)
        if (!isfinite(v[i])) return i;
    return n;
}

/* The nd->n labels of esz bytes at s into nd->iv. */
static int decode_labels(Parser *P, DictNode *nd, const unsigned char *s, size_t esz, int line)
{
    size_t n = nd->n;
    nd->iv = MEM_NEW(int, n);
    if (esz == 4 && sizeof(int) == 4 && host_is_little()) {
        /* the file's layout is the host's: every int32 fits an int */
        if (n) memcpy(nd->iv, s, n * 4);
        return 0;
    }
    for (size_t i = 0; i < n; i++) {
        uint64_t u = get_le(s + i * esz, (int)esz);
        int64_t v = esz == 4 ? (int64_t)(int32_t)(uint32_t)u : (int64_t)u;
        if (v < INT_MIN || v > INT_MAX)
            return dict_perr(P, line, "label %lld in binary list is out of range", (long long)v);
        nd->iv[i] = (int)v;
    }
    return 0;
}

/* One little-endian scalar of esz (4 or 8) bytes. */
static double get_scalar(const unsigned char *s, size_t esz)
{
    uint64_t u = get_le(s, (int)esz);
    double x;
    if (esz == 8) {
        memcpy(&x, &u, 8);
    } else {
        uint32_t u32 = (uint32_t)u;
        float fl;
        memcpy(&fl, &u32, 4);
        x = fl;
    }
    return x;
}

/* The nd->n items of per scalars of esz bytes at s into nd->v; every
   value must be finite. */
static int decode_scalars(Parser *P, DictNode *nd, const unsigned char *s, size_t esz, size_t per, const char *what,
                          int line)
{
    size_t n = nd->n, nper = n * per;
    nd->v = MEM_NEW(double, nper);
    if (esz == 8 && host_is_little()) {
        if (nper) memcpy(nd->v, s, nper * 8);
        size_t bad = first_non_finite(nd->v, nper);
        if (bad < nper)
            return dict_perr(P, line, "binary list of %zu %s holds a non-finite value (item %zu)", n, what, bad / per);
        return 0;
    }
    for (size_t i = 0; i < nper; i++) {
        double x = get_scalar(s + i * esz, esz);
        if (!isfinite(x))
            return dict_perr(P, line, "binary list of %zu %s holds a non-finite value (item %zu)", n, what, i / per);
        nd->v[i] = x;
    }
    return 0;
}

/* Raw data of `size` items after "N" (P->p after the number).  On a
   little-endian host the usual layouts (label 32, scalar 64 bits) are
   copied whole and then checked; other layouts are decoded item by
   item. */
int dict_binary_list(Parser *P, long size, int w, int is_label, int line, DictNodeVec *out)
{
    const char *what = type_name(w, is_label);
    if (dict_lex_ws(P)) return -1;
    size_t n = (size_t)size;
    DictNode *nd = dict_node_new(is_label ? DN_LABELS : DN_NUMS, P->file, line);
    if (!is_label) nd->width = w;
    nd->n = n;
    if (n == 0 && (P->p >= P->end || *P->p != '(')) {
        dict_nv_push(out, nd);
        return 0;
    }
    if (P->p >= P->end || *P->p != '(') {
        dict_node_free(nd);
        return dict_perr(P, P->line, "expected '(' after the size of a binary list of %zu %s", n, what);
    }
    P->p++;
    size_t esz = (size_t)(is_label ? P->label_bytes : P->scalar_bytes);
    size_t per = is_label ? 1 : (size_t)w;
    size_t left = (size_t)(P->end - P->p);
    if (n > SIZE_MAX / per / esz || n * per * esz > left) {
        dict_node_free(nd);
        if (n > SIZE_MAX / per / esz)
            return dict_perr(P, line, "binary list of %zu %s is too large", n, what);
        return dict_perr(P, line, "binary list of %zu %s truncated (needs %zu bytes, %zu left)", n, what, n * per * esz,
                    left);
    }
    const unsigned char *s = (const unsigned char *)P->p;
    if (is_label ? decode_labels(P, nd, s, esz, line) : decode_scalars(P, nd, s, esz, per, what, line)) {
        dict_node_free(nd);
        return -1;
    }
    P->p += n * per * esz;
    if (P->p >= P->end || *P->p != ')') {
        dict_node_free(nd);
        return dict_perr(P, line, "expected ')' after binary list of %zu %s", n, what);
    }
    P->p++;
    dict_nv_push(out, nd);
    return 0;
}

/* Element type of List<T>: width in doubles (or label); 0 if unknown. */
int dict_binary_type(const char *t, size_t n, int *is_label)
{
    static const struct { const char *name; int w, label; } types[] = {
        {"scalar", 1, 0}, {"vector", 3, 0}, {"label", 1, 1}, {"symmTensor", 6, 0}, {"tensor", 9, 0},
        {"sphericalTensor", 1, 0}, {"vector2D", 2, 0}};
    *is_label = 0;
    if (n < 7 || memcmp(t, "List<", 5) != 0 || t[n - 1] != '>') return 0;
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strlen(types[i].name) == n - 6 && memcmp(t + 5, types[i].name, n - 6) == 0) {
            *is_label = types[i].label;
            return types[i].w;
        }
    return 0;
}

/* The element type of a keyword-less binary list from the file class. */
void dict_binary_class_type(Parser *P)
{
    static const struct { const char *cls; int w, label; } cl[] = {
        {"vectorField", 3, 0}, {"scalarField", 1, 0}, {"labelList", 1, 1}, {"labelField", 1, 1},
        {"faceCompactList", 1, 1}, {"symmTensorField", 6, 0}, {"tensorField", 9, 0}};
    for (size_t i = 0; i < sizeof cl / sizeof cl[0]; i++)
        if (strcmp(P->cls, cl[i].cls) == 0) {
            P->list_w = cl[i].w;
            P->list_label = cl[i].label;
        }
}
