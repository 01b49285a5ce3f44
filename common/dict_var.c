/*
** dict_var.c: $variables, expanded while reading.
**
** "$name" and "${name}" in a value copy the values of the entry found by
** OpenFOAM's scoped look-up ($a, $a.b, $:top.a, $..parent.a, $/a/b), so a
** variable sees exactly the entries defined above it.  A value that is
** only "$d" for a dictionary d makes the entry a sub-dictionary copy, and
** "$d;" at keyword position merges d's entries into the dictionary.
**
** Copies are bounded: every expansion adds its size to a budget kept in
** the root (MAX_COPIED items per parse) and its depth to the nesting, so
** chains like "b $a $a; c $b $b; ..." cannot grow exponentially.
*/
#include "dict_impl.h"
#include "mem.h"

#include <stdlib.h>
#include <string.h>

enum { MAX_COPIED = 1 << 25 };   /* items copied by $variables in one parse */

/* OpenFOAM's scoped variable look-up: "$a" and "$a.b" search this
   dictionary and then its parents; "$:a.b" starts at the top; "$.a" is
   this dictionary only and every further leading '.' goes one level up. */
static const DictEntry *var_lookup(const Dict *d, const char *name)
{
    if (strchr(name, '/')) {   /* slash scoping: "$/a/b" from the top */
        char *dots = mem_strdup(name);
        for (char *c = dots; *c; c++)
            if (*c == '/') *c = '.';
        if (dots[0] == '.') dots[0] = ':';
        const DictEntry *en = var_lookup(d, dots);
        free(dots);
        return en;
    }
    if (name[0] == ':') {
        while (d->parent) d = d->parent;
        return dict_find_scoped(d, name + 1);
    }
    if (name[0] == '.') {
        name++;
        while (name[0] == '.') {
            if (!d->parent) return NULL;
            d = d->parent;
            name++;
        }
        return dict_find_scoped(d, name);
    }
    for (; d; d = d->parent) {
        const DictEntry *en = dict_find_scoped(d, name);
        if (en) return en;
    }
    return NULL;
}

/* "$name" or "${name}" at P->p; the name in a new allocation. */
static char *lex_var(Parser *P)
{
    const char *s = P->p + 1;
    size_t n;
    if (s < P->end && *s == '{') {
        const char *q = s + 1;
        while (q < P->end && *q != '}' && *q != '\n' && *q != '\0') q++;
        if (q >= P->end || *q != '}' || q == s + 1) {
            dict_perr(P, P->line, "expected a name and '}' after '${'");
            return NULL;
        }
        P->p = q + 1;
        return mem_strndup(s + 1, (size_t)(q - s - 1));
    }
    n = dict_lex_word_len(s, P->end);
    if (n == 0) {
        dict_perr(P, P->line, "expected a variable name after '$'");
        return NULL;
    }
    P->p = s + n;
    return mem_strndup(s, n);
}

/* Size (items) and depth of what a variable would copy, so that chains
   like "b $a $a; c $b $b; ..." cannot grow exponentially. */
static void cost_dict(const Dict *d, int depth, size_t *cost, int *maxd);

static void cost_node(const DictNode *nd, int depth, size_t *cost, int *maxd)
{
    if (depth > *maxd) *maxd = depth;
    *cost += 1 + nd->n * (size_t)(nd->width > 1 ? nd->width : 1);
    if (nd->kind == DN_RAGGED) *cost += (size_t)nd->off[nd->n];
    for (size_t i = 0; nd->items && i < nd->n && *cost < MAX_COPIED; i++) cost_node(nd->items[i], depth + 1, cost, maxd);
    if (nd->dict) cost_dict(nd->dict, depth + 1, cost, maxd);
}

static void cost_dict(const Dict *d, int depth, size_t *cost, int *maxd)
{
    if (depth > *maxd) *maxd = depth;
    for (size_t i = 0; i < d->n && *cost < MAX_COPIED; i++) {
        const DictEntry *en = &d->entries[i];
        *cost += 1;
        if (en->dict) cost_dict(en->dict, depth + 1, cost, maxd);
        for (size_t k = 0; k < en->nvals; k++) cost_node(en->vals[k], depth + 1, cost, maxd);
    }
}

static int copy_budget(Parser *P, const Dict *d, const DictEntry *en, const char *name, int line)
{
    size_t cost = 0;
    int maxd = 0, here = 0;
    for (const Dict *q = d; q; q = q->parent) here++;
    if (en->dict) cost_dict(en->dict, 0, &cost, &maxd);
    for (size_t k = 0; k < en->nvals; k++) cost_node(en->vals[k], 0, &cost, &maxd);
    P->root->copied += cost;
    if (P->root->copied > MAX_COPIED) return dict_perr(P, line, "variable $%s: expansions copy too much data", name);
    if (here + P->depth + maxd > 4 * DICT_MAX_DEPTH)
        return dict_perr(P, line, "variable $%s: nesting deeper than %d levels", name, 4 * DICT_MAX_DEPTH);
    return 0;
}

int dict_var_expand(Parser *P, Dict *d, DictNodeVec *out)
{
    int line = P->line;
    char *name = lex_var(P);
    if (!name) return -1;
    const DictEntry *en = var_lookup(d, name);
    if (!en) {
        dict_perr(P, line, "undefined variable $%s", name);
        free(name);
        return -1;
    }
    if (copy_budget(P, d, en, name, line)) {
        free(name);
        return -1;
    }
    if (en->dict) {
        DictNode *nd = dict_node_new(DN_DICT, P->file, line);
        nd->dict = dict_copy(en->dict, d, en->key);
        dict_nv_push(out, nd);
    } else {
        for (size_t i = 0; i < en->nvals; i++) dict_nv_push(out, dict_node_copy(en->vals[i], d));
    }
    free(name);
    return 0;
}


/* "$p;" at keyword position: merges the entries of dictionary p. */
int dict_var_merge(Parser *P, Dict *d, int line)
{
    char *name = lex_var(P);
    if (!name) return -1;
    const DictEntry *en = var_lookup(d, name);
    if (!en || !en->dict) {
        dict_perr(P, line, en ? "variable $%s is not a dictionary and cannot be merged here" : "undefined variable $%s",
             name);
        free(name);
        return -1;
    }
    int rc = copy_budget(P, d, en, name, line);
    if (rc == 0 && P->depth == P->depth0 && dict_find_own(en->dict, "FoamFile", 0))
        rc = dict_perr(P, line, "$%s would bring a FoamFile header into the top level, where only the file's own "
                           "header may be", name);
    free(name);
    if (rc) return -1;
    Dict *copy = dict_copy(en->dict, d, "");
    for (size_t i = 0; i < copy->n; i++) dict_entry_add(d, &copy->entries[i]);
    copy->n = 0;
    dict_free_tree(copy);
    return 0;
}
