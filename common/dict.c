/*
** dict.c: the dictionary tree: node, entry and dictionary lifetime,
** adding entries, copying, finding.  See dict.h for the data model and
** dict_impl.h for how the module is cut into files.
**
** Entries are added in file order with OpenFOAM's default "merge" mode: a
** sub-dictionary given twice is merged, any other duplicate replaces the
** earlier entry in place.  Every sub-dictionary carries its scoped name
** ("boundaryField.inlet") for messages; an entry moved or copied to a new
** place is renamed there.  File names are interned once per root and
** shared by every node and entry, so they live as long as the tree.
**
** Finding: a literal key first, then the regex keys, the last matching
** one winning (dict_regex.c compiles them); a scoped name "a.b.c" walks
** sub-dictionaries, trying every split at a dot, since keys may hold dots.
*/
#include "dict_impl.h"
#include "mem.h"

#include <regex.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- node vectors, interning, warnings ---- */

void dict_nv_push(DictNodeVec *a, DictNode *nd)
{
    if (a->n == a->cap) mem_grow((void **)&a->v, &a->cap, a->n + 1, sizeof *a->v);
    a->v[a->n++] = nd;
}

void dict_nv_free(DictNodeVec *v)
{
    for (size_t i = 0; i < v->n; i++) dict_node_free(v->v[i]);
    free(v->v);
    v->v = NULL;
    v->n = 0;
}

const char *dict_intern(struct DictRoot *r, const char *name)
{
    for (size_t i = 0; i < r->nfiles; i++)
        if (strcmp(r->files[i], name) == 0) return r->files[i];
    if (r->nfiles == r->cfiles) mem_grow((void **)&r->files, &r->cfiles, r->nfiles + 1, sizeof *r->files);
    r->files[r->nfiles] = mem_strdup(name);
    return r->files[r->nfiles++];
}

void dict_add_warning(struct DictRoot *r, const char *file, int line, const char *fmt, ...)
{
    char msg[512];
    int k = snprintf(msg, sizeof msg, "%s:%d: ", file, line);
    if (k < 0 || (size_t)k >= sizeof msg) k = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + k, sizeof msg - (size_t)k, fmt, ap);
    va_end(ap);
    if (r->nwarn == r->cwarn) mem_grow((void **)&r->warn, &r->cwarn, r->nwarn + 1, sizeof *r->warn);
    r->warn[r->nwarn++] = mem_strdup(msg);
}

/* ---- lifetime ---- */

void dict_node_free(DictNode *nd)
{
    if (!nd) return;
    free(nd->text);
    for (size_t i = 0; nd->items && i < nd->n; i++) dict_node_free(nd->items[i]);
    free(nd->items);
    if (nd->dict) dict_free_tree(nd->dict);
    free(nd->v);
    free(nd->iv);
    free(nd->off);
    free(nd);
}

DictNode *dict_node_new(DictNodeKind kind, const char *file, int line)
{
    DictNode *nd = MEM_NEW(DictNode, 1);
    nd->kind = kind;
    nd->file = file;
    nd->line = line;
    return nd;
}

void dict_entry_clear(DictEntry *en)
{
    free(en->key);
    if (en->dict) dict_free_tree(en->dict);
    for (size_t i = 0; i < en->nvals; i++) dict_node_free(en->vals[i]);
    free(en->vals);
    if (en->re) {
        regfree(en->re);
        free(en->re);
    }
    memset(en, 0, sizeof *en);
}

void dict_free_tree(Dict *d)
{
    for (size_t i = 0; i < d->n; i++) dict_entry_clear(&d->entries[i]);
    free(d->entries);
    free(d->name);
    free(d);
}

Dict *dict_child(Dict *parent, const char *key, const char *file, int line)
{
    Dict *d = MEM_NEW(Dict, 1);
    if (parent->name[0]) {
        size_t n = strlen(parent->name) + strlen(key) + 2;
        d->name = mem_alloc(n);
        snprintf(d->name, n, "%s.%s", parent->name, key);
    } else {
        d->name = mem_strdup(key);
    }
    d->file = file;
    d->line = line;
    d->parent = parent;
    d->root = parent->root;
    return d;
}

Dict *dict_new(const char *name)
{
    Dict *d = MEM_NEW(Dict, 1);
    d->root = MEM_NEW(struct DictRoot, 1);
    d->name = mem_strdup("");
    d->file = dict_intern(d->root, name ? name : "");
    return d;
}

void dict_free(Dict *d)
{
    if (!d) return;
    struct DictRoot *r = d->root;
    dict_free_tree(d);
    for (size_t i = 0; i < r->nfiles; i++) free(r->files[i]);
    free(r->files);
    for (size_t i = 0; i < r->nwarn; i++) free(r->warn[i]);
    free(r->warn);
    free(r);
}

size_t dict_nwarnings(const Dict *d) { return d->root->nwarn; }
const char *dict_warning(const Dict *d, size_t i) { return i < d->root->nwarn ? d->root->warn[i] : NULL; }

/* ---- copying ---- */

Dict *dict_copy(const Dict *s, Dict *parent, const char *key)
{
    Dict *d = dict_child(parent, key, s->file, s->line);
    d->entries = MEM_NEW(DictEntry, s->n);
    d->cap = s->n;
    for (size_t i = 0; i < s->n; i++) {
        const DictEntry *a = &s->entries[i];
        DictEntry *b = &d->entries[d->n++];
        b->key = mem_strdup(a->key);
        b->is_regex = a->is_regex;
        b->line = a->line;
        b->file = a->file;
        if (a->is_regex) {
            char why[128];
            dict_key_compile(b, why, sizeof why);
        }
        if (a->dict) b->dict = dict_copy(a->dict, d, a->key);
        b->nvals = a->nvals;
        b->vals = MEM_NEW(DictNode *, a->nvals);
        for (size_t k = 0; k < a->nvals; k++) b->vals[k] = dict_node_copy(a->vals[k], d);
    }
    return d;
}

void *dict_dup_mem(const void *p, size_t n)
{
    void *q = mem_alloc(n ? n : 1);
    if (n) memcpy(q, p, n);
    return q;
}

DictNode *dict_node_copy(const DictNode *s, Dict *parent)
{
    DictNode *d = dict_node_new(s->kind, s->file, s->line);
    d->text = s->text ? mem_strdup(s->text) : NULL;
    d->num = s->num;
    d->is_int = s->is_int;
    d->n = s->n;
    d->width = s->width;
    if (s->items) {
        d->items = MEM_NEW(DictNode *, s->n);
        for (size_t i = 0; i < s->n; i++) d->items[i] = dict_node_copy(s->items[i], parent);
    }
    if (s->dict) d->dict = dict_copy(s->dict, parent, s->dict->name);
    if (s->kind == DN_NUMS) d->v = dict_dup_mem(s->v, s->n * (size_t)s->width * sizeof(double));
    if (s->kind == DN_LABELS) d->iv = dict_dup_mem(s->iv, s->n * sizeof(int));
    if (s->kind == DN_RAGGED) {
        d->off = dict_dup_mem(s->off, (s->n + 1) * sizeof(int));
        d->iv = dict_dup_mem(s->iv, (size_t)s->off[s->n] * sizeof(int));
    }
    return d;
}

/* ---- adding entries: OpenFOAM's merge mode ---- */

DictEntry *dict_find_own(Dict *d, const char *key, int is_regex)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->entries[i].is_regex == is_regex && strcmp(d->entries[i].key, key) == 0) return &d->entries[i];
    return NULL;
}

static void dict_merge(Dict *dst, Dict *src);

void dict_remove_at(Dict *d, size_t i)
{
    dict_entry_clear(&d->entries[i]);
    memmove(d->entries + i, d->entries + i + 1, (d->n - i - 1) * sizeof *d->entries);
    d->n--;
}

/* Gives a moved or copied sub-dictionary (and its children) the scoped
   name of its new place, for messages. */
static void rename_dict(Dict *sub, const Dict *parent, const char *key, int depth)
{
    free(sub->name);
    size_t n = strlen(parent->name) + strlen(key) + 2;
    sub->name = mem_alloc(n);
    snprintf(sub->name, n, "%s%s%s", parent->name, parent->name[0] ? "." : "", key);
    for (size_t i = 0; i < sub->n && depth < DICT_MAX_DEPTH + 2; i++)
        if (sub->entries[i].dict) rename_dict(sub->entries[i].dict, sub, sub->entries[i].key, depth + 1);
}

void dict_entry_add(Dict *d, DictEntry *en)
{
    DictEntry *old = dict_find_own(d, en->key, en->is_regex);
    if (old && old->dict && en->dict) {
        dict_merge(old->dict, en->dict);
        en->dict = NULL;
        dict_entry_clear(en);
        return;
    }
    if (old) {
        dict_entry_clear(old);
        *old = *en;
    } else {
        if (d->n == d->cap) mem_grow((void **)&d->entries, &d->cap, d->n + 1, sizeof *d->entries);
        d->entries[d->n++] = *en;
    }
    if (en->dict) {
        en->dict->parent = d;
        rename_dict(en->dict, d, en->key, 0);
    }
    memset(en, 0, sizeof *en);
}

/* Moves the entries of src into dst (merging), then frees src. */
static void dict_merge(Dict *dst, Dict *src)
{
    for (size_t i = 0; i < src->n; i++) dict_entry_add(dst, &src->entries[i]);
    src->n = 0;
    dict_free_tree(src);
}

/* ---- finding ---- */

static const DictEntry *scoped_in(const Dict *d, const char *name, int depth)
{
    const DictEntry *en = dict_find(d, name);
    if (en || depth > DICT_MAX_DEPTH) return en;
    for (const char *dot = strchr(name, '.'); dot; dot = strchr(dot + 1, '.')) {
        char *head = mem_strndup(name, (size_t)(dot - name));
        const DictEntry *h = dict_find(d, head);
        free(head);
        if (h && h->dict && (en = scoped_in(h->dict, dot + 1, depth + 1))) return en;
    }
    return NULL;
}

const DictEntry *dict_find(const Dict *d, const char *key)
{
    if (!d || !key) return NULL;
    for (size_t i = 0; i < d->n; i++)
        if (!d->entries[i].is_regex && strcmp(d->entries[i].key, key) == 0) return &d->entries[i];
    for (size_t i = d->n; i-- > 0;) {
        const DictEntry *en = &d->entries[i];
        if (en->is_regex && en->re && regexec(en->re, key, 0, NULL, 0) == 0) return en;
    }
    return NULL;
}

const DictEntry *dict_find_scoped(const Dict *d, const char *scoped)
{
    if (!d || !scoped) return NULL;
    return scoped_in(d, scoped, 0);
}

const char *dict_display_name(const Dict *d) { return d->name[0] ? d->name : d->file; }

/* ---- building ---- */

Dict *dict_add_subdict(Dict *d, const char *key)
{
    DictEntry *old = dict_find_own(d, key, 0);
    if (old && old->dict) return old->dict;
    DictEntry en;
    memset(&en, 0, sizeof en);
    en.key = mem_strdup(key);
    en.file = d->file;
    en.dict = dict_child(d, key, d->file, 0);
    Dict *sub = en.dict;
    dict_entry_add(d, &en);
    return sub;
}

int dict_remove(Dict *d, const char *key)
{
    for (size_t i = 0; i < d->n; i++)
        if (strcmp(d->entries[i].key, key) == 0) {
            dict_remove_at(d, i);
            return 1;
        }
    return 0;
}
