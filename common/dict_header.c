/*
** dict_header.c: the FoamFile header, checked as OpenFOAM checks it, and
** the settings it gives the rest of the file.
**
** The header must be the first entry (dict_parse.c enforces that); its
** format (ascii or binary) and object must be present, and version,
** format, class, object and arch must each be exactly one token, so that
** a missing ';' is caught here rather than as a confusing error later.
** The arch string gives the sizes of binary labels and scalars (32 or 64
** bits; default label=32;scalar=64) and the byte order: big-endian
** binary files are refused.  Its format and class set how dict_binary.c
** reads raw lists.
*/
#include "dict_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One header entry as OpenFOAM's IOobject::readHeader reads it
   (dictionary::get<T> in v1912): present when required, a single token
   (more is "Entry 'version' has 1 excess tokens", usually a missing ';'),
   of the kind asked for (a number, or a word or string). */
static int header_entry(Parser *P, const Dict *h, const char *key, int number, int required)
{
    const DictEntry *en = NULL;
    for (size_t i = 0; i < h->n && !en; i++)
        if (!h->entries[i].is_regex && strcmp(h->entries[i].key, key) == 0) en = &h->entries[i];
    const char *want = number ? "one number" : "one word";
    if (!en)
        return required ? dict_perr(P, h->line, "FoamFile header: entry '%s' is missing", key) : 0;
    if (en->dict) return dict_perr(P, en->line, "FoamFile header: '%s' must be %s, found a sub-dictionary", key, want);
    if (en->nvals == 0) return dict_perr(P, en->line, "FoamFile header: '%s' has no value", key);
    char what[128];
    if (en->nvals > 1) {
        dict_node_describe(en->vals[1], what, sizeof what);
        return dict_perr(P, en->line, "FoamFile header: entry '%s' has %zu excess token%s (%s...), expected %s; a "
                                 "missing ';'?", key, en->nvals - 1, en->nvals > 2 ? "s" : "", what, want);
    }
    const DictNode *nd = en->vals[0];
    if (number ? nd->kind == DN_NUMBER : nd->kind == DN_WORD || nd->kind == DN_STRING) return 0;
    dict_node_describe(nd, what, sizeof what);
    return dict_perr(P, nd->line, "FoamFile header: '%s' must be %s, found %s", key, want, what);
}

/* "label=N" or "scalar=N" in the arch string: absent, 32 or 64. */
static int arch_bits(Parser *P, int line, const char *arch, const char *key)
{
    const char *s = strstr(arch, key);
    if (!s) return 0;
    s += strlen(key);
    if (strncmp(s, "32", 2) == 0 && !dict_is_digit(s[2])) return 0;
    if (strncmp(s, "64", 2) == 0 && !dict_is_digit(s[2])) return 0;
    return dict_perr(P, line, "FoamFile header: arch \"%s\": %s must be 32 or 64", arch, key);
}

/* The checks OpenFOAM makes on a header, and the arch sizes this reader
   can decode.  Every entry present must have the right form; format and
   object must be present.  version may be absent (v1912 requires it, the
   Foundation's releases default it, nothing here depends on it), and so
   may class: the readers whose files have a class check it themselves
   (field_read, field_probe, the polyMesh reader), with messages that say
   which class they expected.  OpenFOAM only warns about an unknown format
   and reads the file as ascii; here it is an error, since a misspelt
   "binary" would make every raw list unreadable. */
int dict_header_check(Parser *P, const Dict *h)
{
    if (header_entry(P, h, "version", 1, 0) || header_entry(P, h, "format", 0, 1) ||
        header_entry(P, h, "class", 0, 0) || header_entry(P, h, "object", 0, 1) ||
        header_entry(P, h, "arch", 0, 0))
        return -1;
    const DictEntry *f = dict_find(h, "format");
    const char *fmt = f->vals[0]->text;
    if (strcmp(fmt, "ascii") != 0 && strcmp(fmt, "binary") != 0)
        return dict_perr(P, f->line, "FoamFile header: format '%s' is neither ascii nor binary", fmt);
    const DictEntry *a = dict_find(h, "arch");
    if (!a || a->is_regex) return 0;
    const char *arch = a->vals[0]->text;
    if (arch_bits(P, a->line, arch, "label=") || arch_bits(P, a->line, arch, "scalar=")) return -1;
    if (strcmp(fmt, "binary") == 0 && strstr(arch, "MSB"))
        return dict_perr(P, a->line, "FoamFile header: arch \"%s\": big-endian binary files are not supported", arch);
    return 0;
}

void dict_header_settings(Parser *P, const Dict *h)
{
    const char *s;
    Err e;
    if (dict_word_or(h, "format", "ascii", &s, &e) == 0) P->binary = strcmp(s, "binary") == 0;
    if (dict_word_or(h, "class", "", &s, &e) == 0) snprintf(P->cls, sizeof P->cls, "%s", s);
    if (dict_word_or(h, "arch", "", &s, &e) == 0) {
        const char *l = strstr(s, "label="), *r = strstr(s, "scalar=");
        if (l && atoi(l + 6) == 64) P->label_bytes = 8;
        if (r && atoi(r + 7) == 32) P->scalar_bytes = 4;
    }
}

/* ---- public conveniences ---- */

const char *dict_header_class(const Dict *d)
{
    const Dict *h = dict_subdict_opt(d, "FoamFile");
    const char *s;
    Err e;
    return h && dict_word_or(h, "class", NULL, &s, &e) == 0 ? s : NULL;
}

int dict_header_binary(const Dict *d)
{
    const Dict *h = dict_subdict_opt(d, "FoamFile");
    const char *s;
    Err e;
    return h && dict_word_or(h, "format", "ascii", &s, &e) == 0 && s && strcmp(s, "binary") == 0;
}
