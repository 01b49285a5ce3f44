/*
** dict_keys.c: checking a tool's dictionary against its table of valid
** keywords (DictKey, which -help prints too).
**
** The first unknown keyword stops the check with a suggestion: the
** closest valid keyword by edit distance when it is close (at most a
** third of the word's length, at least 2, and less than the whole word),
** else the list of valid keywords.  A misspelt keyword is the commonest
** error in a case, and a silent default would hide it.
*/
#include "dict_impl.h"
#include "mem.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static size_t edit_distance(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    if (na > 64 || nb > 64) return SIZE_MAX;
    size_t row[65];
    for (size_t j = 0; j <= nb; j++) row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            size_t up = row[j];
            size_t sub = diag + (a[i - 1] != b[j - 1]);
            size_t best = up + 1 < row[j - 1] + 1 ? up + 1 : row[j - 1] + 1;
            row[j] = sub < best ? sub : best;
            diag = up;
        }
    }
    return row[nb];
}

const char *dict_closest(const char *word, const char *const *cands, size_t n)
{
    const char *best = NULL;
    size_t bd = SIZE_MAX;
    for (size_t i = 0; i < n; i++) {
        size_t dd = edit_distance(word, cands[i]);
        if (dd < bd) {
            bd = dd;
            best = cands[i];
        }
    }
    size_t len = strlen(word);
    size_t limit = len / 3 > 2 ? len / 3 : 2;
    return best && bd <= limit && bd < len ? best : NULL;
}

void dict_join(char *buf, size_t cap, const char *const *words, size_t n, const char *sep)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < n && k < cap; i++) {
        int m = snprintf(buf + k, cap - k, "%s%s", i ? sep : "", words[i]);
        if (m < 0) break;
        k += (size_t)m;
    }
}

/* The error for an unknown key: the closest valid one, or all of them. */
static int unknown_key(const Dict *d, const DictEntry *en, const char *const *names, size_t nk, Err *e)
{
    const char *near = dict_closest(en->key, names, nk);
    if (near)
        return err_set(e, en->file, en->line, "unknown keyword '%s' in %s; did you mean '%s'?", en->key,
                       dict_display_name(d), near);
    char list[768];
    dict_join(list, sizeof list, names, nk, " ");
    return err_set(e, en->file, en->line, "unknown keyword '%s' in %s; valid keywords: %s", en->key,
                   dict_display_name(d), list);
}

int dict_check_keys(const Dict *d, const DictKey *keys, Err *e)
{
    size_t nk = 0;
    while (keys[nk].key) nk++;
    const char **names = MEM_NEW(const char *, nk);
    for (size_t i = 0; i < nk; i++) names[i] = keys[i].key;
    int rc = 0;
    for (size_t i = 0; i < d->n && rc == 0; i++) {
        const DictEntry *en = &d->entries[i];
        if (strcmp(en->key, "FoamFile") == 0) continue;
        if (!en->key[0] && !en->is_regex) {
            rc = err_set(e, en->file, en->line, "value without a keyword in dictionary '%s'", dict_display_name(d));
            break;
        }
        size_t k = 0;
        while (k < nk && strcmp(names[k], en->key) != 0) k++;
        if (k < nk) continue;
        rc = unknown_key(d, en, names, nk, e);
    }
    free(names);
    return rc;
}
