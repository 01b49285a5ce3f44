/*
** dict_get.c: typed look-ups: sub-dictionaries, numbers, integers,
** vectors, words, switches and choices, and the single value of an entry.
**
** Every typed look-up has a plain form (the key is required) and an _or
** form (a default when the key is absent); both fail with
** "file:line: keyword 'k' in dictionary 'name': expected a number, found
** word 'abc'" when the value has the wrong type, the line being the
** value's own.  The getters share one body (lookup) that tells absent,
** found and wrong apart, so the messages are worded in one place.
*/
#include "dict_impl.h"

#include <stdio.h>
#include <string.h>

/* ---- sub-dictionaries and entries ---- */

const Dict *dict_subdict_opt(const Dict *d, const char *key)
{
    const DictEntry *en = dict_find(d, key);
    return en ? en->dict : NULL;
}

const Dict *dict_subdict(const Dict *d, const char *key, Err *e)
{
    const DictEntry *en = dict_find(d, key);
    if (!en) {
        err_set(e, d->file, d->line, "sub-dictionary '%s' is missing in dictionary '%s'", key, dict_display_name(d));
        return NULL;
    }
    if (!en->dict) {
        err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s' is not a sub-dictionary", key, dict_display_name(d));
        return NULL;
    }
    return en->dict;
}

const DictNode *dict_entry_value(const DictEntry *en, Err *e)
{
    if (en->dict) {
        err_set(e, en->file, en->line, "keyword '%s': expected a value, found a sub-dictionary", en->key);
        return NULL;
    }
    /* "x 41 (...)": the parser keeps a size separated from its list by a
       space as a value of its own (in "arc 1 5 (x y z)" it is one); where a
       single value is expected it can only be the list's size */
    if (en->nvals == 2 && en->vals[0]->kind == DN_NUMBER && en->vals[0]->is_int && en->vals[0]->num >= 0 &&
        dict_node_is_list(en->vals[1])) {
        if (en->vals[0]->num != (double)dict_list_counted(en->vals[1])) {
            err_set(e, en->file, en->vals[0]->line, "keyword '%s': list size %.0f does not match the %zu items read",
                    en->key, en->vals[0]->num, dict_node_len(en->vals[1]));
            return NULL;
        }
        return en->vals[1];
    }
    if (en->nvals != 1) {
        err_set(e, en->file, en->line, "keyword '%s': expected a single value, found %zu values", en->key,
                en->nvals);
        return NULL;
    }
    return en->vals[0];
}

/* ---- typed look-ups ---- */

/* The single value node of key for a typed look-up; *missing is set when
   absent (no error then). */
static const DictNode *typed(const Dict *d, const char *key, const char *want, int *missing,
                             const DictEntry **enp, Err *e)
{
    const DictEntry *en = dict_find(d, key);
    *missing = !en;
    *enp = en;
    if (!en) return NULL;
    if (en->dict) {
        err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s': expected %s, found a sub-dictionary", key,
                dict_display_name(d), want);
        return NULL;
    }
    if (en->nvals != 1) {
        err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s': expected %s, found %zu values", key,
                dict_display_name(d), want, en->nvals);
        return NULL;
    }
    return en->vals[0];
}

static int wrong(const Dict *d, const char *key, const DictNode *nd, const char *want, Err *e)
{
    char what[128];
    dict_node_describe(nd, what, sizeof what);
    return err_set(e, nd->file, nd->line, "keyword '%s' in dictionary '%s': expected %s, found %s", key, dict_display_name(d),
                   want, what);
}

static int missing_key(const Dict *d, const char *key, Err *e)
{
    return err_set(e, d->file, d->line, "keyword '%s' is missing in dictionary '%s'", key, dict_display_name(d));
}

/* Shared body of the typed look-ups: 1 = absent, 0 = *nd found, -1 error. */
static int lookup(const Dict *d, const char *key, const char *want, const DictNode **nd, Err *e)
{
    int missing;
    const DictEntry *en;
    *nd = typed(d, key, want, &missing, &en, e);
    if (missing) return 1;
    return *nd ? 0 : -1;
}

static int get_scalar(const Dict *d, const char *key, double *out, int required, Err *e)
{
    const DictNode *nd;
    int rc = lookup(d, key, "a number", &nd, e);
    if (rc == 1) return required ? missing_key(d, key, e) : 1;
    if (rc < 0) return -1;
    if (nd->kind != DN_NUMBER) return wrong(d, key, nd, "a number", e);
    *out = nd->num;
    return 0;
}

int dict_scalar(const Dict *d, const char *key, double *out, Err *e) { return get_scalar(d, key, out, 1, e); }

int dict_scalar_or(const Dict *d, const char *key, double def, double *out, Err *e)
{
    int rc = get_scalar(d, key, out, 0, e);
    if (rc == 1) *out = def;
    return rc < 0 ? -1 : 0;
}

static int get_label(const Dict *d, const char *key, int *out, int required, Err *e)
{
    const DictNode *nd;
    int rc = lookup(d, key, "an integer", &nd, e);
    if (rc == 1) return required ? missing_key(d, key, e) : 1;
    if (rc < 0) return -1;
    if (nd->kind != DN_NUMBER || !nd->is_int || !dict_fits_int(nd->num)) return wrong(d, key, nd, "an integer", e);
    *out = (int)nd->num;
    return 0;
}

int dict_label(const Dict *d, const char *key, int *out, Err *e) { return get_label(d, key, out, 1, e); }

int dict_label_or(const Dict *d, const char *key, int def, int *out, Err *e)
{
    int rc = get_label(d, key, out, 0, e);
    if (rc == 1) *out = def;
    return rc < 0 ? -1 : 0;
}

/* Three numbers from a vector-shaped node; -1 if it is not one. */
static int node_vector(const DictNode *nd, double out[3])
{
    if (nd->kind == DN_NUMS && nd->n == 1 && nd->width == 3) {
        memcpy(out, nd->v, 3 * sizeof(double));
        return 0;
    }
    return dict_node_tuple(nd, 3, out);
}

static int get_vector(const Dict *d, const char *key, double out[3], int required, Err *e)
{
    const DictNode *nd;
    int rc = lookup(d, key, "a vector (x y z)", &nd, e);
    if (rc == 1) return required ? missing_key(d, key, e) : 1;
    if (rc < 0) return -1;
    if (node_vector(nd, out)) return wrong(d, key, nd, "a vector (x y z)", e);
    return 0;
}

int dict_vector(const Dict *d, const char *key, double out[3], Err *e) { return get_vector(d, key, out, 1, e); }

int dict_vector_or(const Dict *d, const char *key, const double def[3], double out[3], Err *e)
{
    int rc = get_vector(d, key, out, 0, e);
    if (rc == 1) memcpy(out, def, 3 * sizeof(double));
    return rc < 0 ? -1 : 0;
}

static int get_word(const Dict *d, const char *key, const char **out, int required, Err *e)
{
    const DictNode *nd;
    int rc = lookup(d, key, "a word", &nd, e);
    if (rc == 1) return required ? missing_key(d, key, e) : 1;
    if (rc < 0) return -1;
    if (nd->kind != DN_WORD && nd->kind != DN_STRING) return wrong(d, key, nd, "a word", e);
    *out = nd->text;
    return 0;
}

int dict_word(const Dict *d, const char *key, const char **out, Err *e) { return get_word(d, key, out, 1, e); }

int dict_word_or(const Dict *d, const char *key, const char *def, const char **out, Err *e)
{
    int rc = get_word(d, key, out, 0, e);
    if (rc == 1) *out = def;
    return rc < 0 ? -1 : 0;
}

static int get_switch(const Dict *d, const char *key, int *out, int required, Err *e)
{
    static const char *const yes[] = {"on", "yes", "true", "y", "t"};
    static const char *const no[] = {"off", "no", "false", "n", "f", "none"};
    const char *want = "a switch (on/off, yes/no, true/false)";
    const DictNode *nd;
    int rc = lookup(d, key, want, &nd, e);
    if (rc == 1) return required ? missing_key(d, key, e) : 1;
    if (rc < 0) return -1;
    if (nd->kind == DN_NUMBER && nd->is_int) {
        *out = nd->num != 0;
        return 0;
    }
    if (nd->kind == DN_WORD) {
        for (size_t i = 0; i < sizeof yes / sizeof yes[0]; i++)
            if (strcmp(nd->text, yes[i]) == 0) return *out = 1, 0;
        for (size_t i = 0; i < sizeof no / sizeof no[0]; i++)
            if (strcmp(nd->text, no[i]) == 0) return *out = 0, 0;
    }
    return wrong(d, key, nd, want, e);
}

int dict_switch(const Dict *d, const char *key, int *out, Err *e) { return get_switch(d, key, out, 1, e); }

int dict_switch_or(const Dict *d, const char *key, int def, int *out, Err *e)
{
    int rc = get_switch(d, key, out, 0, e);
    if (rc == 1) *out = def;
    return rc < 0 ? -1 : 0;
}

int dict_choice_or(const Dict *d, const char *key, const char *const *choices, int def, int *out, Err *e)
{
    const char *w = NULL;
    int rc = get_word(d, key, &w, 0, e);
    if (rc < 0) return -1;
    if (rc == 1) {
        *out = def;
        return 0;
    }
    size_t n = 0;
    for (; choices[n]; n++)
        if (strcmp(choices[n], w) == 0) {
            *out = (int)n;
            return 0;
        }
    const DictEntry *en = dict_find(d, key);
    char list[512];
    dict_join(list, sizeof list, choices, n, ", ");
    const char *near = dict_closest(w, choices, n);
    return err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s': '%s' is not one of: %s%s%s%s", key,
                   dict_display_name(d), w, list, near ? "; did you mean '" : "", near ? near : "", near ? "'?" : "");
}
