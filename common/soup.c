/*
** soup.c: triangle soups of the surface readers.  See soup.h.
**
** The arrays grow by doubling (a million-triangle file costs about twenty
** reallocations); names are owned by the soup until soup_finish moves
** them into the TriSurf.
*/
#include "soup.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "foam.h"
#include "mem.h"

void soup_free(Soup *S)
{
    free(S->xyz);
    free(S->tag);
    for (int i = 0; i < S->nnames; i++) free(S->names[i]);
    free(S->names);
    memset(S, 0, sizeof *S);
}

void soup_push(Soup *S, const double c[9], int tag)
{
    if (S->n == S->cap) {
        S->cap = S->cap ? 2 * S->cap : 1024;
        S->xyz = mem_realloc(S->xyz, S->cap * 9 * sizeof *S->xyz);
        S->tag = mem_realloc(S->tag, S->cap * sizeof *S->tag);
    }
    memcpy(S->xyz + 9 * S->n, c, 9 * sizeof *c);
    S->tag[S->n++] = tag;
}

int soup_tag(Soup *S, const char *name)
{
    for (int i = 0; i < S->nnames; i++)
        if (strcmp(S->names[i], name) == 0) return i;
    mem_grow((void **)&S->names, &S->names_cap, (size_t)S->nnames + 1, sizeof *S->names);
    S->names[S->nnames] = mem_strdup(name);
    return S->nnames++;
}

int soup_finish(Soup *S, TriSurf *s, int tagged, const char *name, const char *none, Err *e)
{
    trisurf_init(s);
    if (S->n == 0) {
        soup_free(S);
        return err_set(e, name, 0, "%s", none);
    }
    if (S->n > INT32_MAX / 3) {
        soup_free(S);
        return err_set(e, name, 0, "too many triangles (%zu)", S->n);
    }
    trisurf_from_soup(s, S->xyz, (int)S->n, tagged ? S->tag : NULL);
    if (tagged) {
        s->names = S->names;
        s->nnames = S->nnames;
        S->names = NULL;
        S->nnames = 0;
    }
    soup_free(S);
    return 0;
}

/* t[0..n) equals the lower-case word w, in any case. */
static int word_is(const char *t, size_t n, const char *w)
{
    if (strlen(w) != n) return 0;
    for (size_t i = 0; i < n; i++)
        if (tolower((unsigned char)t[i]) != w[i]) return 0;
    return 1;
}

/* Old MSVC runtimes print non-finite values as 1.#INF, -1.#IND00,
   1.#QNAN0 or 1.#SNAN, optionally with an exponent (-1.#IND00e+000). */
static int msvc_nonfinite(const char *t, size_t n)
{
    static const char *const kinds[] = {"inf", "ind", "qnan", "snan"};
    if (n < 3 || memcmp(t, "1.#", 3) != 0) return 0;
    size_t i = 3;
    int kind = 0;
    for (int k = 0; k < 4 && !kind; k++) {
        size_t m = strlen(kinds[k]);
        if (n - i >= m && word_is(t + i, m, kinds[k])) i += m, kind = 1;
    }
    if (!kind) return 0;
    while (i < n && isdigit((unsigned char)t[i])) i++;
    if (i < n && (t[i] == 'e' || t[i] == 'E')) {
        i++;
        if (i < n && (t[i] == '+' || t[i] == '-')) i++;
        if (i == n || !isdigit((unsigned char)t[i])) return 0;
        while (i < n && isdigit((unsigned char)t[i])) i++;
    }
    return i == n;
}

int soup_number(const char *t, size_t n, double *x)
{
    int is_int;
    if (n > 0 && foam_parse_number(t, t + n, x, &is_int) == n) return isfinite(*x) ? 1 : 0;
    int neg = n > 0 && t[0] == '-';
    size_t k = n > 0 && (t[0] == '-' || t[0] == '+');
    if (word_is(t + k, n - k, "nan") || msvc_nonfinite(t + k, n - k)) {
        *x = NAN;
        return 0;
    }
    if (word_is(t + k, n - k, "inf") || word_is(t + k, n - k, "infinity")) {
        *x = neg ? -INFINITY : INFINITY;
        return 0;
    }
    return -1;
}
