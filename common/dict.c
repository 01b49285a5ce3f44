/*
** dict.c: OpenFOAM dictionaries: lexer, parser, look-up, writer.  See
** dict.h for the data model.
**
** Reading is one pass over the bytes with no token buffer: the parser
** peeks at raw characters (after skipping blanks and comments) to decide
** what comes next, and the lexer functions consume one token each.  Every
** routine works on [p, end) and never needs a NUL terminator, so binary
** data, embedded NUL bytes and truncated input are just more cases to
** report ("file:line: ...").  Recursion is bounded by MAX_DEPTH (nested
** dictionaries, lists and dimension sets together) and #include nesting
** by MAX_INCLUDE, with cycle detection on (device, inode).
**
** Entries are added in file order with OpenFOAM's default "merge" mode: a
** sub-dictionary given twice is merged, any other duplicate replaces the
** earlier entry in place.  $variables are expanded while reading, so they
** see exactly the entries defined above them, as in OpenFOAM; a value that
** is only "$d" for a dictionary d makes the entry a sub-dictionary copy.
**
** Lists.  Big numeric lists (points, fields, faces) go through a fast path
** that scans numbers straight into flat arrays (DN_NUMS, DN_LABELS,
** DN_RAGGED) without creating nodes; anything unusual inside (a comment, a
** word, a nested dictionary) makes it give up and the general path parses
** the list into nodes, which are then compacted by the same rules, so the
** result never depends on which path ran.  Compaction rules: all numbers
** -> DN_LABELS when every one is an integer in int range (not "-0"), else
** DN_NUMS width 1; all equal-length numeric tuples -> DN_NUMS of that
** width; integer lists of different lengths -> DN_RAGGED, where an inner
** list counts as integers by value (1e1 as 10), since dict_write prints it
** so: write(parse(write(d))) == write(d) is what the fuzzer checks.
**
** Binary (FoamFile format binary): "N(" is raw data when the element type
** is known: the word List<T> just before it, or for a value without a
** keyword (polyMesh files) the FoamFile class.  Other lists are ascii even
** in binary files (inGroups 1(wall)), as OpenFOAM writes them.  Newlines
** inside raw data are not counted in line numbers (OpenFOAM does not
** either).  An empty binary list is "0" with no brackets.  On a
** little-endian host, label=32 and scalar=64 lists (what Kiesel and
** OpenFOAM write) are copied in one block and then checked in one pass
** (non-finite scalars); other layouts are decoded item by item.  Both give
** the same values and the same messages.
**
** Strings follow OpenFOAM: \" is a quote, backslash-newline continues the
** line, every other backslash is kept; the writer escapes only quotes, so
** write -> parse reproduces the text.  Quoted keywords are POSIX extended
** regular expressions matched against the whole key (compiled once, as
** "^(re)$", when the entry is created).
**
** A value without a keyword at the start of an entry (a number or a list:
** "3 ( ... )" in a polyMesh file) is kept as an entry with the empty key "",
** holding every value up to ';', '}' or the end of the input.
*/
#include "dict.h"
#include "foam.h"
#include "io.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <regex.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

enum {
    MAX_DEPTH = 64,          /* nesting of dictionaries, lists, dimension sets */
    MAX_INCLUDE = 16,        /* nesting of #include */
    MAX_UNIFORM = 1 << 25,   /* numbers created by an N{v} shorthand */
    MAX_COPIED = 1 << 25,    /* items copied by $variables in one parse */
    KEY_COLUMN = 16          /* dict_write pads keywords to this width */
};

struct DictRoot {
    size_t copied;           /* items copied by $variables (bounded) */
    char **files;            /* interned file names */
    size_t nfiles, cfiles;
    char **warn;
    size_t nwarn, cwarn;
};

/* ======================================================================
** Small helpers: node vectors, interning, node and dictionary lifetime
** ====================================================================== */

static int is_digit_c(char c);

typedef struct NodeVec {
    DictNode **v;
    size_t n, cap;
} NodeVec;

static void nv_push(NodeVec *a, DictNode *nd)
{
    if (a->n == a->cap) mem_grow((void **)&a->v, &a->cap, a->n + 1, sizeof *a->v);
    a->v[a->n++] = nd;
}

static const char *intern(struct DictRoot *r, const char *name)
{
    for (size_t i = 0; i < r->nfiles; i++)
        if (strcmp(r->files[i], name) == 0) return r->files[i];
    if (r->nfiles == r->cfiles) mem_grow((void **)&r->files, &r->cfiles, r->nfiles + 1, sizeof *r->files);
    r->files[r->nfiles] = mem_strdup(name);
    return r->files[r->nfiles++];
}

static void add_warning(struct DictRoot *r, const char *file, int line, const char *fmt, ...)
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

static void dict_free_tree(Dict *d);

static void node_free(DictNode *nd)
{
    if (!nd) return;
    free(nd->text);
    for (size_t i = 0; nd->items && i < nd->n; i++) node_free(nd->items[i]);
    free(nd->items);
    if (nd->dict) dict_free_tree(nd->dict);
    free(nd->v);
    free(nd->iv);
    free(nd->off);
    free(nd);
}

static DictNode *node_new(DictNodeKind kind, const char *file, int line)
{
    DictNode *nd = MEM_NEW(DictNode, 1);
    nd->kind = kind;
    nd->file = file;
    nd->line = line;
    return nd;
}

static void entry_clear(DictEntry *en)
{
    free(en->key);
    if (en->dict) dict_free_tree(en->dict);
    for (size_t i = 0; i < en->nvals; i++) node_free(en->vals[i]);
    free(en->vals);
    if (en->re) {
        regfree(en->re);
        free(en->re);
    }
    memset(en, 0, sizeof *en);
}

static void dict_free_tree(Dict *d)
{
    for (size_t i = 0; i < d->n; i++) entry_clear(&d->entries[i]);
    free(d->entries);
    free(d->name);
    free(d);
}

static Dict *dict_child(Dict *parent, const char *key, const char *file, int line)
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
    d->file = intern(d->root, name ? name : "");
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

/* Compiles a regex key as "^(key)$" for whole-key matching; the bare key
   is compiled first so "a)(b" is rejected rather than accepted anchored. */
/* glibc's regcomp expands repetitions by copying the repeated part
   ("a+" is "aa*", "a{3}" is "aaa"), so nested or stacked repetitions
   ("((a+)+)+", "a++++", "a{99}{99}") grow exponentially.  This estimates
   the expanded size and refuses patterns a dictionary key never needs. */
static int regex_too_complex(const char *s, char *why, size_t nwhy)
{
    enum { MAXLEN = 512, LIMIT = 20000 };
    size_t len = strlen(s);
    if (len > MAXLEN) return snprintf(why, nwhy, "longer than %d characters", MAXLEN), 1;
    double sum[MAXLEN + 2], last = 0;
    int top = 0;
    sum[0] = 0;
    for (size_t i = 0; i < len; i++) {
        char c = s[i];
        double k = 1;
        if (c == '\\' && i + 1 < len && is_digit_c(s[i + 1]))
            return snprintf(why, nwhy, "back-references are not supported"), 1;
        if (c == '(') {
            sum[++top] = 0;
            continue;
        }
        if (c == ')' && top > 0) {
            last = sum[top--];
            sum[top] += last;
        } else if (c == '+') {
            k = 2;
        } else if (c == '{') {
            double m = 0;
            for (i++; i < len && s[i] != '}'; i++)
                if (is_digit_c(s[i])) {
                    double v = 0;
                    for (; i < len && is_digit_c(s[i]); i++) v = v * 10 + (s[i] - '0');
                    if (v > m) m = v;
                    i--;
                }
            k = m + 1;
        } else if (c != '*' && c != '?' && c != '|') {
            if (c == '[') {   /* a bracket expression is one atom */
                size_t j = i + 1;
                if (j < len && s[j] == '^') j++;
                if (j < len && s[j] == ']') j++;
                while (j < len && s[j] != ']') j++;
                i = j;
            } else if (c == '\\') {
                i++;
            }
            last = 1;
            sum[top] += 1;
        }
        if (k > 1) {
            sum[top] += last * (k - 1);
            last *= k;
        }
        if (sum[top] > LIMIT || last > LIMIT) return snprintf(why, nwhy, "repetitions too deeply nested"), 1;
    }
    return 0;
}

static int compile_key(DictEntry *en, char *why, size_t nwhy)
{
    if (regex_too_complex(en->key, why, nwhy)) return -1;
    /* OpenFOAM's "(?i)" prefix: case-insensitive */
    int icase = strncmp(en->key, "(?i)", 4) == 0, flags = REG_EXTENDED | REG_NOSUB | (icase ? REG_ICASE : 0);
    const char *key = en->key + (icase ? 4 : 0);
    regex_t test;
    int rc = regcomp(&test, key, flags);
    if (rc) {
        regerror(rc, &test, why, nwhy);
        regfree(&test);
        return -1;
    }
    regfree(&test);
    size_t n = strlen(key) + 5;
    char *pat = mem_alloc(n);
    snprintf(pat, n, "^(%s)$", key);
    en->re = mem_alloc(sizeof(regex_t));
    rc = regcomp(en->re, pat, flags);
    free(pat);
    if (rc) {
        regerror(rc, en->re, why, nwhy);
        free(en->re);
        en->re = NULL;
        return -1;
    }
    return 0;
}

static DictNode *node_copy(const DictNode *s, Dict *parent);

static Dict *dict_copy(const Dict *s, Dict *parent, const char *key)
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
            compile_key(b, why, sizeof why);
        }
        if (a->dict) b->dict = dict_copy(a->dict, d, a->key);
        b->nvals = a->nvals;
        b->vals = MEM_NEW(DictNode *, a->nvals);
        for (size_t k = 0; k < a->nvals; k++) b->vals[k] = node_copy(a->vals[k], d);
    }
    return d;
}

static int is_digit_c(char c) { return c >= '0' && c <= '9'; }

static void *dup_mem(const void *p, size_t n)
{
    void *q = mem_alloc(n ? n : 1);
    if (n) memcpy(q, p, n);
    return q;
}

static DictNode *node_copy(const DictNode *s, Dict *parent)
{
    DictNode *d = node_new(s->kind, s->file, s->line);
    d->text = s->text ? mem_strdup(s->text) : NULL;
    d->num = s->num;
    d->is_int = s->is_int;
    d->n = s->n;
    d->width = s->width;
    if (s->items) {
        d->items = MEM_NEW(DictNode *, s->n);
        for (size_t i = 0; i < s->n; i++) d->items[i] = node_copy(s->items[i], parent);
    }
    if (s->dict) d->dict = dict_copy(s->dict, parent, s->dict->name);
    if (s->kind == DN_NUMS) d->v = dup_mem(s->v, s->n * (size_t)s->width * sizeof(double));
    if (s->kind == DN_LABELS) d->iv = dup_mem(s->iv, s->n * sizeof(int));
    if (s->kind == DN_RAGGED) {
        d->off = dup_mem(s->off, (s->n + 1) * sizeof(int));
        d->iv = dup_mem(s->iv, (size_t)s->off[s->n] * sizeof(int));
    }
    return d;
}

/* ---- adding entries: OpenFOAM's merge mode ---- */

static DictEntry *find_own(Dict *d, const char *key, int is_regex)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->entries[i].is_regex == is_regex && strcmp(d->entries[i].key, key) == 0) return &d->entries[i];
    return NULL;
}

static void dict_merge(Dict *dst, Dict *src);

static void remove_at(Dict *d, size_t i)
{
    entry_clear(&d->entries[i]);
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
    for (size_t i = 0; i < sub->n && depth < MAX_DEPTH + 2; i++)
        if (sub->entries[i].dict) rename_dict(sub->entries[i].dict, sub, sub->entries[i].key, depth + 1);
}

/* Takes ownership of *en (which is cleared). */
static void entry_add(Dict *d, DictEntry *en)
{
    DictEntry *old = find_own(d, en->key, en->is_regex);
    if (old && old->dict && en->dict) {
        dict_merge(old->dict, en->dict);
        en->dict = NULL;
        entry_clear(en);
        return;
    }
    if (old) {
        entry_clear(old);
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
    for (size_t i = 0; i < src->n; i++) entry_add(dst, &src->entries[i]);
    src->n = 0;
    dict_free_tree(src);
}

/* ======================================================================
** Lexer
** ====================================================================== */

typedef struct Parser {
    const char *p, *end;
    const char *start;       /* the whole text (for looking back on a line) */
    const char *file;        /* interned */
    int line;
    struct DictRoot *root;
    struct Parser *up;       /* includer, for cycle detection */
    int have_id;             /* dev/ino of this file are known */
    dev_t dev;
    ino_t ino;
    int nincl;               /* #include nesting */
    int depth;               /* nesting of values and dictionaries */
    int depth0;              /* depth at the top level of this file */
    int ntop;                /* entries and directives read at that level */
    int binary, label_bytes, scalar_bytes;
    char cls[64];            /* FoamFile class */
    int list_w;              /* element type of the next list from List<T>: */
    int list_label;          /* width in doubles, or label; 0 = unknown */
    Err *e;
} Parser;

static int perr(Parser *P, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int perr(Parser *P, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    err_setv(P->e, P->file, line, fmt, ap);
    va_end(ap);
    return -1;
}

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* Skips blanks and comments.  -1 on an unterminated comment. */
static int skip_ws(Parser *P)
{
    const char *p = P->p, *end = P->end;
    for (;;) {
        while (p < end && is_space(*p)) {
            if (*p == '\n') P->line++;
            p++;
        }
        if (p + 1 < end && p[0] == '/' && p[1] == '/') {
            while (p < end && *p != '\n') p++;
            continue;
        }
        if (p + 1 < end && p[0] == '/' && p[1] == '*') {
            int line0 = P->line;
            p += 2;
            while (p + 1 < end && !(p[0] == '*' && p[1] == '/')) {
                if (*p == '\n') P->line++;
                p++;
            }
            if (p + 1 >= end) {
                P->p = end;
                return perr(P, line0, "unterminated comment");
            }
            p += 2;
            continue;
        }
        break;
    }
    P->p = p;
    return 0;
}

/* A character that ends a number or a word (comment starts included). */
static int is_delim(const char *p, const char *end)
{
    if (p >= end) return 1;
    char c = *p;
    if (is_space(c) || c == ';' || c == '{' || c == '}' || c == '(' || c == ')' || c == '[' || c == ']' ||
        c == '"' || c == '\0')
        return 1;
    return c == '/' && p + 1 < end && (p[1] == '/' || p[1] == '*');
}

/* Length of the word at p: stops at blanks, ;{}[]" and NUL, and at a ')'
   that closes no '(' of the word, so "div(phi,U)" is one word. */
static size_t word_len(const char *p, const char *end)
{
    const char *q = p;
    int depth = 0;
    while (q < end) {
        char c = *q;
        if (c == ')') {
            if (depth == 0) break;
            depth--;
        } else if (c == '(') {
            depth++;
        } else if (is_delim(q, end)) {
            break;
        }
        q++;
    }
    return (size_t)(q - p);
}

/* Reads a "string" at P->p (on the quote) into a new allocation. */
static char *lex_string(Parser *P)
{
    int line0 = P->line;
    const char *p = P->p + 1, *end = P->end;
    Buf b;
    buf_init(&b);
    int escaped = 0;
    for (; p < end; p++) {
        char c = *p;
        if (c == '\0') {
            buf_free(&b);
            perr(P, P->line, "NUL byte inside a string");
            return NULL;
        }
        if (c == '"' && !escaped) break;
        if (c == '\n') P->line++;
        if (escaped && (c == '"' || c == '\n')) {
            b.n--;   /* drop the backslash; a newline is a line continuation */
            if (c == '"') buf_putc(&b, c);
            else b.p[b.n] = '\0';
            escaped = 0;
            continue;
        }
        escaped = c == '\\' ? !escaped : 0;
        buf_putc(&b, c);
    }
    if (p >= end) {
        buf_free(&b);
        P->p = end;
        perr(P, line0, "unterminated string");
        return NULL;
    }
    P->p = p + 1;
    if (!b.p) {
        buf_reserve(&b, 0);
        b.p[0] = '\0';
    }
    return b.p;
}

/* A number token at P->p if one ends at a delimiter: 1 (consumed), 0 (not
   a number), -1 (error: out of range). */
static int lex_number(Parser *P, double *x, int *is_int, size_t *len)
{
    char c = *P->p;
    if (!(is_digit(c) || c == '-' || c == '+' || c == '.')) return 0;
    size_t n = foam_parse_number(P->p, P->end, x, is_int);
    if (n == 0 || !is_delim(P->p + n, P->end)) return 0;
    if (!isfinite(*x)) return perr(P, P->line, "number '%.*s' is out of range", (int)(n > 40 ? 40 : n), P->p);
    *len = n;
    P->p += n;
    return 1;
}

/* ======================================================================
** Parser
** ====================================================================== */

static int parse_entries(Parser *P, Dict *d, int braced, int line0);
static int parse_value(Parser *P, Dict *d, NodeVec *out, const char *hint);

static int nest(Parser *P)
{
    if (++P->depth > MAX_DEPTH) return perr(P, P->line, "nesting deeper than %d levels", MAX_DEPTH);
    return 0;
}

static DictNode *text_node(Parser *P, DictNodeKind kind, const char *s, size_t n, int line)
{
    DictNode *nd = node_new(kind, P->file, line);
    nd->text = mem_strndup(s, n);
    return nd;
}

static DictNode *number_node(Parser *P, const char *s, size_t n, double x, int is_int, int line)
{
    DictNode *nd = text_node(P, DN_NUMBER, s, n, line);
    nd->num = x;
    nd->is_int = is_int;
    return nd;
}

static int fits_int(double x) { return x >= INT_MIN && x <= INT_MAX && x == floor(x); }

/* A number a DN_LABELS list may hold: "-0" is not one, as it would be
   written back as 0 and the list would not read back the same. */
static int label_value(double x, int is_int) { return is_int && fits_int(x) && !(x == 0 && signbit(x)); }

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

/* Replaces items by a compact node when the rules at the top allow;
   returns the node (taking the items) or NULL (items untouched). */
static DictNode *compact(Parser *P, NodeVec *it, int line)
{
    size_t n = it->n;
    if (n == 0) return NULL;
    int all_num = 1, all_lab = 1;
    for (size_t i = 0; i < n && all_num; i++) {
        all_num = it->v[i]->kind == DN_NUMBER;
        if (all_num && !label_value(it->v[i]->num, it->v[i]->is_int)) all_lab = 0;
    }
    DictNode *nd = NULL;
    if (all_num) {
        if (all_lab) {
            nd = node_new(DN_LABELS, P->file, line);
            nd->iv = MEM_NEW(int, n);
            for (size_t i = 0; i < n; i++) nd->iv[i] = (int)it->v[i]->num;
        } else {
            nd = node_new(DN_NUMS, P->file, line);
            nd->width = 1;
            nd->v = MEM_NEW(double, n);
            for (size_t i = 0; i < n; i++) nd->v[i] = it->v[i]->num;
        }
        nd->n = n;
    } else {
        int w = tuple_len(it->v[0]), same = 1, all_ilist = 1;
        for (size_t i = 0; i < n && w > 0; i++) {
            int wi = tuple_len(it->v[i]);
            if (wi < 0) return NULL;
            if (wi != w) same = 0;
            if (!int_list(it->v[i])) all_ilist = 0;
        }
        if (w <= 0) return NULL;
        if (same) {
            if ((size_t)w > SIZE_MAX / sizeof(double) / n) return NULL;
            nd = node_new(DN_NUMS, P->file, line);
            nd->width = w;
            size_t nw = n * (size_t)w;
            nd->v = MEM_NEW(double, nw);
            for (size_t i = 0; i < n; i++)
                for (int k = 0; k < w; k++) {
                    const DictNode *t = it->v[i];
                    nd->v[i * (size_t)w + (size_t)k] = t->kind == DN_LABELS ? t->iv[k] : t->v[k];
                }
        } else if (all_ilist) {
            size_t tot = 0;
            for (size_t i = 0; i < n; i++) tot += it->v[i]->n;
            if (tot > INT_MAX) return NULL;
            nd = node_new(DN_RAGGED, P->file, line);
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
        } else {
            return NULL;
        }
        nd->n = n;
    }
    for (size_t i = 0; i < n; i++) node_free(it->v[i]);
    it->n = 0;
    return nd;
}

/* ---- fast path for big numeric lists ---- */

typedef struct Fast {
    double *v;
    size_t nv, cv;
    int *off;
    size_t noff, coff;
    int all_int;
} Fast;

static void fast_free(Fast *f)
{
    free(f->v);
    free(f->off);
}

static void fast_push(Fast *f, double x, int is_int)
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
static const char *fast_ws(const char *p, const char *end, int *line)
{
    while (p < end && is_space(*p)) {
        if (*p == '\n') (*line)++;
        p++;
    }
    return p;
}

/* One number ending at a delimiter, or NULL. */
static const char *fast_num(const char *p, const char *end, double *x, int *is_int)
{
    size_t n = foam_parse_number(p, end, x, is_int);
    if (n == 0 || !is_delim(p + n, end) || !isfinite(*x)) return NULL;
    return p + n;
}

/* Tries to read the list at P->p ('(') as numbers, equal tuples or sized
   integer lists.  Returns the node and advances P, or NULL (P untouched)
   when the list needs the general path. */
static DictNode *fast_list(Parser *P, long size)
{
    const char *p = P->p + 1, *end = P->end;
    int line = P->line, line0 = P->line;
    Fast f = {NULL, 0, 0, NULL, 0, 0, 1};
    enum { UNSET, SCALARS, TUPLES, SIZED } mode = UNSET;
    size_t n = 0;
    int width = 0;
    if (size > 0) {
        size_t want = (size_t)size, room = (size_t)(end - p) / 2 + 1;
        mem_grow((void **)&f.v, &f.cv, want < room ? want : room, sizeof *f.v);
    }
    for (;;) {
        p = fast_ws(p, end, &line);
        if (p >= end) goto give_up;
        if (*p == ')') break;
        double x;
        int is_int;
        if (*p == '(') {
            if (mode == UNSET) mode = TUPLES;
            if (mode != TUPLES) goto give_up;
            int k = 0;
            p++;
            for (;;) {
                p = fast_ws(p, end, &line);
                if (p >= end) goto give_up;
                if (*p == ')') break;
                if (!(p = fast_num(p, end, &x, &is_int))) goto give_up;
                fast_push(&f, x, is_int);
                k++;
            }
            p++;
            if (width == 0) width = k;
            if (k == 0 || k != width) goto give_up;
        } else {
            const char *q = fast_num(p, end, &x, &is_int);
            if (!q) goto give_up;
            if (q < end && *q == '(') {
                if (mode == UNSET) mode = SIZED;
                if (mode != SIZED || !is_int || x < 0 || x > INT_MAX) goto give_up;
                fast_push_off(&f, f.nv);
                size_t k0 = f.nv, want = (size_t)x;
                p = q + 1;
                for (;;) {
                    p = fast_ws(p, end, &line);
                    if (p >= end) goto give_up;
                    if (*p == ')') break;
                    if (!(p = fast_num(p, end, &x, &is_int)) || !label_value(x, is_int)) goto give_up;
                    fast_push(&f, x, is_int);
                }
                p++;
                if (f.nv - k0 != want || f.nv > INT_MAX) goto give_up;
            } else {
                if (mode == UNSET) mode = SCALARS;
                if (mode != SCALARS) goto give_up;
                fast_push(&f, x, is_int);
                p = q;
            }
        }
        n++;
    }
    if (n == 0) goto give_up;
    DictNode *nd;
    if (mode == SIZED && equal_lengths(f.off, f.noff, f.nv, &width)) {
        mode = TUPLES;   /* same rule as compact(): equal tuples -> DN_NUMS */
        free(f.off);
        f.off = NULL;
    }
    if (mode == SIZED) {
        fast_push_off(&f, f.nv);
        nd = node_new(DN_RAGGED, P->file, line0);
        nd->off = f.off;
        nd->iv = MEM_NEW(int, f.nv);
        for (size_t i = 0; i < f.nv; i++) nd->iv[i] = (int)f.v[i];
        free(f.v);
    } else if (mode == SCALARS && f.all_int) {
        nd = node_new(DN_LABELS, P->file, line0);
        nd->iv = MEM_NEW(int, n);
        for (size_t i = 0; i < n; i++) nd->iv[i] = (int)f.v[i];
        free(f.v);
    } else {
        nd = node_new(DN_NUMS, P->file, line0);
        nd->width = mode == TUPLES ? width : 1;
        nd->v = f.v;
        free(f.off);
    }
    nd->n = n;
    P->p = p + 1;
    P->line = line;
    return nd;
give_up:
    fast_free(&f);
    return NULL;
}

/* ---- binary lists ---- */

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

/* Raw data of `size` items after "N" (P->p after the number).  On a
   little-endian host the usual layouts (label 32, scalar 64 bits) are
   copied whole and then checked; other layouts are decoded item by
   item. */
static int binary_list(Parser *P, long size, int w, int is_label, int line, NodeVec *out)
{
    const char *what = type_name(w, is_label);
    if (skip_ws(P)) return -1;
    size_t n = (size_t)size;
    DictNode *nd = node_new(is_label ? DN_LABELS : DN_NUMS, P->file, line);
    if (!is_label) nd->width = w;
    nd->n = n;
    if (n == 0 && (P->p >= P->end || *P->p != '(')) {
        nv_push(out, nd);
        return 0;
    }
    if (P->p >= P->end || *P->p != '(') {
        node_free(nd);
        return perr(P, P->line, "expected '(' after the size of a binary list of %zu %s", n, what);
    }
    P->p++;
    size_t esz = (size_t)(is_label ? P->label_bytes : P->scalar_bytes);
    size_t per = is_label ? 1 : (size_t)w;
    size_t left = (size_t)(P->end - P->p);
    if (n > SIZE_MAX / per / esz || n * per * esz > left) {
        node_free(nd);
        if (n > SIZE_MAX / per / esz)
            return perr(P, line, "binary list of %zu %s is too large", n, what);
        return perr(P, line, "binary list of %zu %s truncated (needs %zu bytes, %zu left)", n, what, n * per * esz,
                    left);
    }
    const unsigned char *s = (const unsigned char *)P->p;
    if (is_label && esz == 4 && sizeof(int) == 4 && host_is_little()) {
        /* the file's layout is the host's: every int32 fits an int */
        nd->iv = MEM_NEW(int, n);
        if (n) memcpy(nd->iv, s, n * 4);
    } else if (!is_label && esz == 8 && host_is_little()) {
        size_t nper = n * per;
        nd->v = MEM_NEW(double, nper);
        if (nper) memcpy(nd->v, s, nper * 8);
        size_t bad = first_non_finite(nd->v, nper);
        if (bad < nper) {
            node_free(nd);
            return perr(P, line, "binary list of %zu %s holds a non-finite value (item %zu)", n, what, bad / per);
        }
    } else if (is_label) {
        nd->iv = MEM_NEW(int, n);
        for (size_t i = 0; i < n; i++) {
            uint64_t u = get_le(s + i * esz, (int)esz);
            int64_t v = esz == 4 ? (int64_t)(int32_t)(uint32_t)u : (int64_t)u;
            if (v < INT_MIN || v > INT_MAX) {
                node_free(nd);
                return perr(P, line, "label %lld in binary list is out of range", (long long)v);
            }
            nd->iv[i] = (int)v;
        }
    } else {
        size_t nper = n * per;
        nd->v = MEM_NEW(double, nper);
        for (size_t i = 0; i < n * per; i++) {
            uint64_t u = get_le(s + i * esz, (int)esz);
            double x;
            if (esz == 8) {
                memcpy(&x, &u, 8);
            } else {
                uint32_t u32 = (uint32_t)u;
                float fl;
                memcpy(&fl, &u32, 4);
                x = fl;
            }
            if (!isfinite(x)) {
                node_free(nd);
                return perr(P, line, "binary list of %zu %s holds a non-finite value (item %zu)", n, what, i / per);
            }
            nd->v[i] = x;
        }
    }
    P->p += n * per * esz;
    if (P->p >= P->end || *P->p != ')') {
        node_free(nd);
        return perr(P, line, "expected ')' after binary list of %zu %s", n, what);
    }
    P->p++;
    nv_push(out, nd);
    return 0;
}

/* Element type of List<T>: width in doubles (or label); 0 if unknown. */
static int list_type(const char *t, size_t n, int *is_label)
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

/* ---- lists ---- */

/* "N ( name { ... } ... )" counts name-dictionary pairs (polyMesh
   boundary, blockMesh boundary). */
static int dict_pairs(const DictNode *nd, size_t size)
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
static size_t counted_items(const DictNode *nd)
{
    if (nd->kind == DN_LIST && nd->n > 0 && nd->n % 2 == 0 && dict_pairs(nd, nd->n / 2)) return nd->n / 2;
    return nd->kind == DN_LIST || nd->kind == DN_NUMS || nd->kind == DN_LABELS || nd->kind == DN_RAGGED ? nd->n : 0;
}

/* The error for a size prefix that does not count its list, after the
   prefix what ("keyword 'x': ", "internalField: " or ""). */
static int size_error(Parser *P, int line, const char *what, double size, const DictNode *nd)
{
    char pairs[80] = "";
    if (counted_items(nd) != nd->n)
        snprintf(pairs, sizeof pairs, " (%zu name-dictionary pairs: the size counts the pairs)", counted_items(nd));
    return perr(P, line, "%slist size %.0f does not match the %zu items read%s", what, size, nd->n, pairs);
}

/* A size written apart from its list, "x 3 (1 2 3);" or "List<scalar> 3
   (1 2 3)": the values keep the number as a node of its own, because in
   "arc 1 5 (0 1 0)" it is one.  Where it can only be a size, as the whole
   value of an entry (whole: the values are an entry's) or right after a
   List<T> word, it must count the list, as OpenFOAM's List reader
   requires.  key names the entry in messages (NULL: none). */
static int check_sizes(Parser *P, const NodeVec *v, int whole, const char *key)
{
    for (size_t i = 0; i + 1 < v->n; i++) {
        const DictNode *a = v->v[i], *b = v->v[i + 1], *t = i > 0 ? v->v[i - 1] : NULL;
        int typed = t && t->kind == DN_WORD && strncmp(t->text, "List<", 5) == 0;
        if (!(typed || (whole && v->n == 2)) || a->kind != DN_NUMBER || !a->is_int || a->num < 0) continue;
        if (b->kind != DN_LIST && b->kind != DN_NUMS && b->kind != DN_LABELS && b->kind != DN_RAGGED) continue;
        if (a->num == (double)counted_items(b)) continue;
        char what[300] = "";
        if (key && key[0]) snprintf(what, sizeof what, typed ? "%.200s: " : "keyword '%.200s': ", key);
        return size_error(P, b->line, what, a->num, b);
    }
    return 0;
}

/* The list at P->p ('('); size < 0 when no size was given. */
static int parse_list(Parser *P, Dict *d, long size, int line, NodeVec *out)
{
    if (nest(P)) return -1;
    int line0 = P->line;
    DictNode *nd = fast_list(P, size);
    if (!nd) {
        NodeVec it = {NULL, 0, 0};
        P->p++;
        char *hint = NULL;
        for (;;) {
            if (skip_ws(P)) goto fail;
            if (P->p >= P->end) {
                perr(P, line0, "unterminated list started at line %d", line0);
                goto fail;
            }
            char c = *P->p;
            if (c == ')') break;
            if (c == ';' || c == '}') {
                perr(P, P->line, "unexpected '%c' inside the list started at line %d", c, line0);
                goto fail;
            }
            size_t before = it.n;
            if (parse_value(P, d, &it, hint)) goto fail;
            free(hint);
            hint = NULL;
            if (it.n == before + 1 && it.v[before]->kind == DN_WORD) hint = mem_strdup(it.v[before]->text);
        }
        free(hint);
        hint = NULL;
        P->p++;
        if (check_sizes(P, &it, 0, NULL)) goto fail;
        nd = compact(P, &it, line0);
        if (!nd) {
            nd = node_new(DN_LIST, P->file, line0);
            nd->n = it.n;
            nd->items = it.v;
        } else {
            free(it.v);
        }
        goto done;
    fail:
        free(hint);
        for (size_t i = 0; i < it.n; i++) node_free(it.v[i]);
        free(it.v);
        return -1;
    }
done:
    P->depth--;
    if (size >= 0 && counted_items(nd) != (size_t)size) {
        size_error(P, line, "", (double)size, nd);
        node_free(nd);
        return -1;
    }
    nv_push(out, nd);
    return 0;
}

/* N{value}: N copies of one value. */
static int parse_uniform(Parser *P, Dict *d, long size, int line, NodeVec *out)
{
    int line0 = P->line;
    P->p++;
    NodeVec one = {NULL, 0, 0};
    if (skip_ws(P)) return -1;
    const char *v0 = P->p;
    if (P->p < P->end && *P->p != '}' && parse_value(P, d, &one, NULL)) goto fail;
    size_t span = (size_t)(P->p - v0) + 1;   /* bounds the cost of copies */
    if (skip_ws(P)) goto fail;
    if (P->p >= P->end || *P->p != '}' || one.n != 1) {
        perr(P, line0, "expected one value and '}' in the uniform list %ld{...}", size);
        goto fail;
    }
    P->p++;
    const DictNode *v = one.v[0];
    DictNode *nd;
    size_t n = (size_t)size;
    if (v->kind == DN_NUMBER) {
        if (n > MAX_UNIFORM) {
            perr(P, line, "uniform list size %ld is too large", size);
            goto fail;
        }
        if (label_value(v->num, v->is_int)) {
            nd = node_new(DN_LABELS, P->file, line);
            nd->iv = MEM_NEW(int, n);
            for (size_t i = 0; i < n; i++) nd->iv[i] = (int)v->num;
        } else {
            nd = node_new(DN_NUMS, P->file, line);
            nd->width = 1;
            nd->v = MEM_NEW(double, n);
            for (size_t i = 0; i < n; i++) nd->v[i] = v->num;
        }
        nd->n = n;
    } else if (tuple_len(v) > 0) {
        /* N{(x y z)}: equal tuples, stored as compact() would */
        size_t w = v->n;
        if (n > MAX_UNIFORM / w) {
            perr(P, line, "uniform list size %ld is too large", size);
            goto fail;
        }
        double t[64];
        double *tv = w <= 64 ? t : MEM_NEW(double, w);
        for (size_t k = 0; k < w; k++) tv[k] = v->kind == DN_LABELS ? v->iv[k] : v->v[k];
        nd = node_new(DN_NUMS, P->file, line);
        nd->width = (int)w;
        size_t nw = n * w;
        nd->v = MEM_NEW(double, nw);
        for (size_t i = 0; i < n; i++) memcpy(nd->v + i * w, tv, w * sizeof(double));
        if (tv != t) free(tv);
        nd->n = n;
    } else {
        if (n > 100000 || n * span > MAX_UNIFORM) {
            perr(P, line, "uniform list size %ld is too large", size);
            goto fail;
        }
        NodeVec it = {NULL, 0, 0};
        for (size_t i = 0; i < n; i++) nv_push(&it, node_copy(v, d));
        nd = compact(P, &it, line);
        if (!nd) {
            nd = node_new(DN_LIST, P->file, line);
            nd->n = it.n;
            nd->items = it.v;
        } else {
            free(it.v);
        }
    }
    node_free(one.v[0]);
    free(one.v);
    nv_push(out, nd);
    return 0;
fail:
    for (size_t i = 0; i < one.n; i++) node_free(one.v[i]);
    free(one.v);
    return -1;
}

static int parse_dims(Parser *P, NodeVec *out)
{
    int line0 = P->line;
    NodeVec it = {NULL, 0, 0};
    P->p++;
    for (;;) {
        if (skip_ws(P)) goto fail;
        if (P->p >= P->end) {
            perr(P, line0, "unterminated dimension set started at line %d", line0);
            goto fail;
        }
        if (*P->p == ']') break;
        double x;
        int is_int, rc;
        size_t len;
        const char *s = P->p;
        if ((rc = lex_number(P, &x, &is_int, &len)) < 0) goto fail;
        if (rc) {
            nv_push(&it, number_node(P, s, len, x, is_int, P->line));
            continue;
        }
        size_t n = word_len(P->p, P->end);
        if (n == 0 || *P->p == '(' ) {
            perr(P, P->line, "unexpected '%c' in the dimension set started at line %d", *P->p ? *P->p : '?',
                 line0);
            goto fail;
        }
        nv_push(&it, text_node(P, DN_WORD, P->p, n, P->line));
        P->p += n;
    }
    P->p++;
    DictNode *nd = node_new(DN_DIMS, P->file, line0);
    nd->n = it.n;
    nd->items = it.v;
    nv_push(out, nd);
    return 0;
fail:
    for (size_t i = 0; i < it.n; i++) node_free(it.v[i]);
    free(it.v);
    return -1;
}

/* ---- variables ---- */

static const DictEntry *scoped_in(const Dict *d, const char *name, int depth)
{
    const DictEntry *en = dict_find(d, name);
    if (en || depth > MAX_DEPTH) return en;
    for (const char *dot = strchr(name, '.'); dot; dot = strchr(dot + 1, '.')) {
        char *head = mem_strndup(name, (size_t)(dot - name));
        const DictEntry *h = dict_find(d, head);
        free(head);
        if (h && h->dict && (en = scoped_in(h->dict, dot + 1, depth + 1))) return en;
    }
    return NULL;
}

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
        return scoped_in(d, name + 1, 0);
    }
    if (name[0] == '.') {
        name++;
        while (name[0] == '.') {
            if (!d->parent) return NULL;
            d = d->parent;
            name++;
        }
        return scoped_in(d, name, 0);
    }
    for (; d; d = d->parent) {
        const DictEntry *en = scoped_in(d, name, 0);
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
            perr(P, P->line, "expected a name and '}' after '${'");
            return NULL;
        }
        P->p = q + 1;
        return mem_strndup(s + 1, (size_t)(q - s - 1));
    }
    n = word_len(s, P->end);
    if (n == 0) {
        perr(P, P->line, "expected a variable name after '$'");
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
    if (P->root->copied > MAX_COPIED) return perr(P, line, "variable $%s: expansions copy too much data", name);
    if (here + P->depth + maxd > 4 * MAX_DEPTH)
        return perr(P, line, "variable $%s: nesting deeper than %d levels", name, 4 * MAX_DEPTH);
    return 0;
}

static int expand_var(Parser *P, Dict *d, NodeVec *out)
{
    int line = P->line;
    char *name = lex_var(P);
    if (!name) return -1;
    const DictEntry *en = var_lookup(d, name);
    if (!en) {
        perr(P, line, "undefined variable $%s", name);
        free(name);
        return -1;
    }
    if (copy_budget(P, d, en, name, line)) {
        free(name);
        return -1;
    }
    if (en->dict) {
        DictNode *nd = node_new(DN_DICT, P->file, line);
        nd->dict = dict_copy(en->dict, d, en->key);
        nv_push(out, nd);
    } else {
        for (size_t i = 0; i < en->nvals; i++) nv_push(out, node_copy(en->vals[i], d));
    }
    free(name);
    return 0;
}

/* ---- values ---- */

static int directive_name(Parser *P, char *name, size_t cap)
{
    const char *s = P->p + 1;
    size_t n = 0;
    while (s + n < P->end && ((s[n] >= 'a' && s[n] <= 'z') || (s[n] >= 'A' && s[n] <= 'Z'))) n++;
    if (s < P->end && *s == '{') return perr(P, P->line, "verbatim code blocks #{ ... #} are not supported");
    if (n == 0) return perr(P, P->line, "expected a directive name after '#'");
    if (n >= cap) n = cap - 1;
    memcpy(name, s, n);
    name[n] = '\0';
    P->p = s + n;
    while (P->p < P->end && !is_delim(P->p, P->end)) P->p++;
    return 0;
}

/* Whether only blanks precede the token at s on its line. */
static int alone_on_line(const Parser *P, const char *s)
{
    while (s > P->start && (s[-1] == ' ' || s[-1] == '\t' || s[-1] == '\r')) s--;
    return s == P->start || s[-1] == '\n';
}

/* Parses one value at P->p (blanks already skipped), appending its
   node(s) to out: a variable may expand to several. */
static int parse_value(Parser *P, Dict *d, NodeVec *out, const char *hint)
{
    int line = P->line;
    char c = *P->p;
    int lw = P->list_w, ll = P->list_label;
    P->list_w = P->list_label = 0;
    switch (c) {
    case '(':
        return parse_list(P, d, -1, line, out);
    case '[':
        return parse_dims(P, out);
    case ')':
    case ']':
    case '}':
        return perr(P, line, "unmatched '%c'", c);
    case '\0':
        return perr(P, line, "unexpected NUL byte");
    case '{': {
        if (nest(P)) return -1;
        Dict *sub = dict_child(d, hint ? hint : "", P->file, line);
        P->p++;
        if (parse_entries(P, sub, 1, line)) {
            dict_free_tree(sub);
            return -1;
        }
        P->depth--;
        DictNode *nd = node_new(DN_DICT, P->file, line);
        nd->dict = sub;
        nv_push(out, nd);
        return 0;
    }
    case '"': {
        char *s = lex_string(P);
        if (!s) return -1;
        DictNode *nd = node_new(DN_STRING, P->file, line);
        nd->text = s;
        nv_push(out, nd);
        return 0;
    }
    case '$':
        return expand_var(P, d, out);
    case '#': {
        char name[64];
        if (directive_name(P, name, sizeof name)) return -1;
        return perr(P, line, "directive #%s is not supported%s", name,
                    strncmp(name, "include", 7) == 0 || strcmp(name, "remove") == 0 ? " inside a value" : "");
    }
    default:
        break;
    }
    double x;
    int is_int;
    size_t len;
    const char *s = P->p;
    int rc = lex_number(P, &x, &is_int, &len);
    if (rc < 0) return -1;
    if (rc) {
        /* "N(" is a sized list, and so is "N" alone on its line followed
           by "(" on the next, as OpenFOAM writes long lists; "N{" is a
           uniform list.  "arc 1 5 (0.5 0.5 0)" is a number and a list. */
        const char *after = P->p, *q = P->p;
        int line_after = P->line, newline = 0;
        while (q < P->end && is_space(*q)) newline |= *q++ == '\n';
        char nx = q < P->end ? *q : '\0';
        if (!((nx == '(' && (q == after || (newline && alone_on_line(P, s)))) || (nx == '{' && q == after)))
            nx = '\0';
        if (nx && skip_ws(P)) return -1;
        if (is_int && x >= 0 && (nx == '(' || nx == '{')) {
            if (x > 1e18) return perr(P, line, "list size %.*s is too large", (int)len, s);
            long size = (long)x;
            if (nx == '{') return parse_uniform(P, d, size, line, out);
            if (P->binary && lw) return binary_list(P, size, lw, ll, line, out);
            return parse_list(P, d, size, line, out);
        }
        if (P->binary && lw && is_int && x >= 0 && x <= 1e18) {
            if (skip_ws(P)) return -1;
            return binary_list(P, (long)x, lw, ll, line, out);
        }
        P->p = after;   /* keep the blanks for the caller's line count */
        P->line = line_after;
        nv_push(out, number_node(P, s, len, x, is_int, line));
        return 0;
    }
    size_t n = word_len(P->p, P->end);
    if (n == 0) return perr(P, line, "unexpected character '%c'", c);
    DictNode *nd = text_node(P, DN_WORD, P->p, n, line);
    P->p += n;
    P->list_w = list_type(nd->text, n, &P->list_label);
    nv_push(out, nd);
    return 0;
}

/* ---- entries ---- */

static void free_nodes(NodeVec *v)
{
    for (size_t i = 0; i < v->n; i++) node_free(v->v[i]);
    free(v->v);
    v->v = NULL;
    v->n = 0;
}

static void class_list_type(Parser *P);

/* Values up to ';' (primitive entry), '}' or the end for a keyword-less
   entry (bare > 0; bare == 2: binary lists typed by the FoamFile class).
   key is for messages. */
static int parse_values(Parser *P, Dict *d, NodeVec *vals, const char *key, int kline, int bare)
{
    for (;;) {
        if (skip_ws(P)) return -1;
        if (P->p >= P->end || *P->p == '}') {
            if (bare) return check_sizes(P, vals, 1, NULL);
            return perr(P, kline, "expected ';' after value of keyword '%s'", key);
        }
        if (*P->p == ';') {
            P->p++;
            return check_sizes(P, vals, 1, bare ? NULL : key);
        }
        if (bare == 2) class_list_type(P);
        if (parse_value(P, d, vals, NULL)) return -1;
    }
}

/* ---- the FoamFile header ---- */

static void describe(const DictNode *nd, char *s, size_t n);

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
        return required ? perr(P, h->line, "FoamFile header: entry '%s' is missing", key) : 0;
    if (en->dict) return perr(P, en->line, "FoamFile header: '%s' must be %s, found a sub-dictionary", key, want);
    if (en->nvals == 0) return perr(P, en->line, "FoamFile header: '%s' has no value", key);
    char what[128];
    if (en->nvals > 1) {
        describe(en->vals[1], what, sizeof what);
        return perr(P, en->line, "FoamFile header: entry '%s' has %zu excess token%s (%s...), expected %s; a "
                                 "missing ';'?", key, en->nvals - 1, en->nvals > 2 ? "s" : "", what, want);
    }
    const DictNode *nd = en->vals[0];
    if (number ? nd->kind == DN_NUMBER : nd->kind == DN_WORD || nd->kind == DN_STRING) return 0;
    describe(nd, what, sizeof what);
    return perr(P, nd->line, "FoamFile header: '%s' must be %s, found %s", key, want, what);
}

/* "label=N" or "scalar=N" in the arch string: absent, 32 or 64. */
static int arch_bits(Parser *P, int line, const char *arch, const char *key)
{
    const char *s = strstr(arch, key);
    if (!s) return 0;
    s += strlen(key);
    if (strncmp(s, "32", 2) == 0 && !is_digit_c(s[2])) return 0;
    if (strncmp(s, "64", 2) == 0 && !is_digit_c(s[2])) return 0;
    return perr(P, line, "FoamFile header: arch \"%s\": %s must be 32 or 64", arch, key);
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
static int check_header(Parser *P, const Dict *h)
{
    if (header_entry(P, h, "version", 1, 0) || header_entry(P, h, "format", 0, 1) ||
        header_entry(P, h, "class", 0, 0) || header_entry(P, h, "object", 0, 1) ||
        header_entry(P, h, "arch", 0, 0))
        return -1;
    const DictEntry *f = dict_find(h, "format");
    const char *fmt = f->vals[0]->text;
    if (strcmp(fmt, "ascii") != 0 && strcmp(fmt, "binary") != 0)
        return perr(P, f->line, "FoamFile header: format '%s' is neither ascii nor binary", fmt);
    const DictEntry *a = dict_find(h, "arch");
    if (!a || a->is_regex) return 0;
    const char *arch = a->vals[0]->text;
    if (arch_bits(P, a->line, arch, "label=") || arch_bits(P, a->line, arch, "scalar=")) return -1;
    if (strcmp(fmt, "binary") == 0 && strstr(arch, "MSB"))
        return perr(P, a->line, "FoamFile header: arch \"%s\": big-endian binary files are not supported", arch);
    return 0;
}

static void header_settings(Parser *P, const Dict *h)
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

/* The element type of a keyword-less binary list from the file class. */
static void class_list_type(Parser *P)
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

/* A value where a keyword should be: a list, or a number (never a
   keyword), as in polyMesh files "3 ( ... )". */
static int is_bare_start(Parser *P)
{
    if (*P->p == '(') return 1;
    double x;
    int is_int;
    size_t n = foam_parse_number(P->p, P->end, &x, &is_int);
    return n > 0 && is_delim(P->p + n, P->end);
}

static int parse_file(Parser *up, Dict *d, const char *path, int line, int optional);

static int directive(Parser *P, Dict *d)
{
    int line = P->line;
    char name[64];
    if (directive_name(P, name, sizeof name)) return -1;
    int inc = strcmp(name, "include") == 0, opt = strcmp(name, "includeIfPresent") == 0;
    int etc = strcmp(name, "includeEtc") == 0, func = strcmp(name, "includeFunc") == 0;
    int rem = strcmp(name, "remove") == 0;
    if (!inc && !opt && !etc && !func && !rem) return perr(P, line, "directive #%s is not supported", name);
    if (skip_ws(P)) return -1;
    NodeVec args = {NULL, 0, 0};
    if (P->p >= P->end || *P->p == ';' || *P->p == '}' || *P->p == '$' || *P->p == '#')
        return perr(P, line, "expected an argument after #%s", name);
    if (parse_value(P, d, &args, NULL)) {
        free_nodes(&args);
        return -1;
    }
    const DictNode *a = args.v[0];
    int rc = 0;
    if (rem) {
        const DictNode *const *keys = a->kind == DN_LIST ? (const DictNode *const *)a->items : &a;
        size_t nk = a->kind == DN_LIST ? a->n : 1;
        for (size_t i = 0; i < nk && rc == 0; i++) {
            const DictNode *k = keys[i];
            if (k->kind == DN_WORD) {
                dict_remove(d, k->text);
            } else if (k->kind == DN_STRING) {
                regex_t re;
                size_t m = strlen(k->text) + 5;
                char *pat = mem_alloc(m);
                snprintf(pat, m, "^(%s)$", k->text);
                char why[128];
                if (!regex_too_complex(k->text, why, sizeof why) && regcomp(&re, pat, REG_EXTENDED | REG_NOSUB) == 0) {
                    for (size_t j = d->n; j-- > 0;)
                        if (regexec(&re, d->entries[j].key, 0, NULL, 0) == 0) remove_at(d, j);
                    regfree(&re);
                } else {
                    rc = perr(P, line, "#remove: invalid regular expression \"%s\"", k->text);
                }
                free(pat);
            } else {
                rc = perr(P, line, "#remove expects a keyword or a list of keywords");
            }
        }
    } else if (a->kind != DN_STRING && a->kind != DN_WORD) {
        rc = perr(P, line, "#%s expects a file name", name);
    } else if (etc || func) {
        add_warning(P->root, P->file, line, "#%s %s ignored (OpenFOAM's etc files are not read)", name, a->text);
    } else {
        rc = parse_file(P, d, a->text, line, opt);
    }
    free_nodes(&args);
    return rc;
}

/* "$p;" at keyword position: merges the entries of dictionary p. */
static int merge_var(Parser *P, Dict *d, int line)
{
    char *name = lex_var(P);
    if (!name) return -1;
    const DictEntry *en = var_lookup(d, name);
    if (!en || !en->dict) {
        perr(P, line, en ? "variable $%s is not a dictionary and cannot be merged here" : "undefined variable $%s",
             name);
        free(name);
        return -1;
    }
    int rc = copy_budget(P, d, en, name, line);
    if (rc == 0 && P->depth == P->depth0 && find_own(en->dict, "FoamFile", 0))
        rc = perr(P, line, "$%s would bring a FoamFile header into the top level, where only the file's own "
                           "header may be", name);
    free(name);
    if (rc) return -1;
    Dict *copy = dict_copy(en->dict, d, "");
    for (size_t i = 0; i < copy->n; i++) entry_add(d, &copy->entries[i]);
    copy->n = 0;
    dict_free_tree(copy);
    return 0;
}

/* Parses entries into d until '}' (braced) or the end of the input. */
static int parse_entries(Parser *P, Dict *d, int braced, int line0)
{
    for (;;) {
        if (skip_ws(P)) return -1;
        if (P->p >= P->end) {
            if (braced) return perr(P, line0, "unterminated dictionary started at line %d", line0);
            return 0;
        }
        char c = *P->p;
        int line = P->line;
        if (c == '}') {
            if (!braced) return perr(P, line, "unmatched '}'");
            P->p++;
            return 0;
        }
        if (c == ';') {
            P->p++;
            continue;
        }
        if (P->depth == P->depth0) P->ntop++;   /* for the FoamFile-first rule */
        if (c == '#') {
            if (directive(P, d)) return -1;
            continue;
        }
        if (c == '$') {
            if (merge_var(P, d, line)) return -1;
            continue;
        }
        if (c == ')' || c == ']') return perr(P, line, "unmatched '%c'", c);
        if (c == '\0') return perr(P, line, "unexpected NUL byte");
        DictEntry en;
        memset(&en, 0, sizeof en);
        en.line = line;
        en.file = P->file;
        NodeVec vals = {NULL, 0, 0};
        if (is_bare_start(P)) {
            en.key = mem_strdup("");
            int typed_by_class = !P->up && P->depth == 0 && d->parent == NULL;
            if (parse_values(P, d, &vals, "", line, 1 + typed_by_class)) goto fail;
            en.vals = vals.v;
            en.nvals = vals.n;
            entry_add(d, &en);
            continue;
        }
        if (c == '"') {
            en.key = lex_string(P);
            if (!en.key) return -1;
            en.is_regex = 1;
            char why[128];
            if (compile_key(&en, why, sizeof why)) {
                perr(P, line, "invalid regular expression \"%s\": %s", en.key, why);
                goto fail;
            }
        } else {
            if (c == '[' || c == '{')
                return perr(P, line, "expected a keyword, found '%c'", c);
            size_t n = word_len(P->p, P->end);
            if (n == 0) return perr(P, line, "unexpected character '%c'", c);
            en.key = mem_strndup(P->p, n);
            P->p += n;
        }
        if (skip_ws(P)) goto fail;
        if (P->p < P->end && *P->p == '{') {
            int brace = P->line;
            if (nest(P)) goto fail;
            P->p++;
            en.dict = dict_child(d, en.key, P->file, line);
            if (parse_entries(P, en.dict, 1, brace)) goto fail;
            P->depth--;
            if (strcmp(en.key, "FoamFile") == 0 && P->depth == P->depth0) {
                if (P->ntop > 1) {
                    perr(P, line, "FoamFile header after other entries: it must come first, as OpenFOAM reads it");
                    goto fail;
                }
                if (check_header(P, en.dict)) goto fail;
                header_settings(P, en.dict);
                if (P->up) {   /* an included file's header is not an entry */
                    entry_clear(&en);
                    continue;
                }
            }
            entry_add(d, &en);
            continue;
        }
        if (strcmp(en.key, "FoamFile") == 0 && P->depth == P->depth0) {
            perr(P, line, "FoamFile header must be a dictionary { version 2.0; format ascii; class ...; object ...; }");
            goto fail;
        }
        if (parse_values(P, d, &vals, en.key, line, 0)) goto fail;
        if (vals.n > 1 && vals.v[0]->kind == DN_DICT) {
            /* "key $dict more;" could not be written back: "key {" starts
               a sub-dictionary */
            perr(P, line, "keyword '%s': a dictionary variable cannot be followed by other values", en.key);
            goto fail;
        }
        if (vals.n == 1 && vals.v[0]->kind == DN_DICT) {
            /* "key $dict;" makes key a sub-dictionary */
            en.dict = vals.v[0]->dict;
            vals.v[0]->dict = NULL;
            free_nodes(&vals);
        } else {
            en.vals = vals.v;
            en.nvals = vals.n;
        }
        entry_add(d, &en);
        continue;
    fail:
        free_nodes(&vals);
        entry_clear(&en);
        return -1;
    }
}

/* ---- files ---- */

/* The case directory of the top file (its directory's parent), for
   <case>, <system>, <constant> and an unset $FOAM_CASE in #include. */
static char *case_dir(const Parser *P)
{
    const char *top = P->root->files[0];
    const char *slash = strrchr(top, '/');
    if (!slash) return mem_strdup("..");
    char *dir = mem_strndup(top, (size_t)(slash - top));
    char *s2 = strrchr(dir, '/');
    if (s2) {
        *s2 = '\0';
        if (!dir[0]) strcpy(dir, "/");
        return dir;
    }
    free(dir);
    return mem_strdup(".");
}

/* $VAR and ${VAR} from the environment in an #include path. */
static char *expand_env(Parser *P, const char *s, int line)
{
    Buf b;
    buf_init(&b);
    while (*s) {
        if (*s != '$') {
            buf_putc(&b, *s++);
            continue;
        }
        s++;
        const char *a = s, *z;
        if (*s == '{') {
            a = ++s;
            while (*s && *s != '}') s++;
            z = s;
            if (*s) s++;
        } else {
            while (*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9'))
                s++;
            z = s;
        }
        char *name = mem_strndup(a, (size_t)(z - a));
        const char *v = getenv(name);
        if (!v && strcmp(name, "FOAM_CASE") == 0) {
            char *c = case_dir(P);
            buf_puts(&b, c);
            free(c);
            free(name);
            continue;
        }
        if (!v) {
            perr(P, line, "#include: environment variable $%s is not set", name);
            free(name);
            buf_free(&b);
            return NULL;
        }
        free(name);
        buf_puts(&b, v);
    }
    if (!b.p) {
        buf_reserve(&b, 0);
        b.p[0] = '\0';
    }
    return b.p;
}

static void parser_init(Parser *P, const char *text, size_t n, const char *file, struct DictRoot *root, Err *e)
{
    memset(P, 0, sizeof *P);
    P->p = text;
    P->start = text;
    P->end = text + n;
    P->file = file;
    P->line = 1;
    P->root = root;
    P->label_bytes = 4;
    P->scalar_bytes = 8;
    P->e = e;
}

static void set_identity(Parser *P, const char *path)
{
    struct stat st;
    if (path && stat(path, &st) == 0) {
        P->have_id = 1;
        P->dev = st.st_dev;
        P->ino = st.st_ino;
    }
}

static int parse_file(Parser *up, Dict *d, const char *arg, int line, int optional)
{
    if (up->nincl + 1 > MAX_INCLUDE) return perr(up, line, "#include nested too deeply (limit %d)", MAX_INCLUDE);
    char *name = expand_env(up, arg, line);
    if (!name) return -1;
    char *path;
    const char *slash = strrchr(up->file, '/');
    static const char *const tags[] = {"<case>", "<system>", "<constant>"};
    int tag = -1;
    for (int k = 0; k < 3; k++)
        if (strncmp(name, tags[k], strlen(tags[k])) == 0) tag = k;
    if (tag >= 0) {
        char *c = case_dir(up);
        size_t m = strlen(c) + strlen(name) + 16;
        path = mem_alloc(m);
        snprintf(path, m, "%s%s%s", c, tag == 0 ? "" : tag == 1 ? "/system" : "/constant",
                 name + strlen(tags[tag]));
        free(c);
    } else if (name[0] == '/' || !slash || strncmp(arg, "$FOAM_CASE", 10) == 0 ||
               strncmp(arg, "${FOAM_CASE}", 12) == 0) {
        path = mem_strdup(name);
    } else {
        size_t m = (size_t)(slash - up->file) + strlen(name) + 2;
        path = mem_alloc(m);
        snprintf(path, m, "%.*s/%s", (int)(slash - up->file), up->file, name);
    }
    free(name);
    int exists = io_is_dir(path) ? -1 : io_exists_gz(path);
    if (exists <= 0) {
        int rc = optional && exists == 0 ? 0 : perr(up, line, "cannot open included file '%s'", path);
        free(path);
        return rc;
    }
    Buf text;
    buf_init(&text);
    char *found = NULL;
    Err e2;
    if (io_read_file(path, &text, &found, &e2)) {
        perr(up, line, "#include: %s", e2.msg);
        buf_free(&text);
        free(path);
        return -1;
    }
    Parser P;
    parser_init(&P, text.p, text.n, intern(up->root, path), up->root, up->e);
    set_identity(&P, found ? found : path);
    free(found);
    free(path);
    for (Parser *q = up; q && P.have_id; q = q->up)
        if (q->have_id && q->dev == P.dev && q->ino == P.ino) {
            buf_free(&text);
            return perr(up, line, "#include cycle: '%s' includes itself", P.file);
        }
    P.up = up;
    P.nincl = up->nincl + 1;
    P.depth = P.depth0 = up->depth;
    int rc = parse_entries(&P, d, 0, 1);
    buf_free(&text);
    if (rc && up->e) {
        size_t k = strlen(up->e->msg);
        snprintf(up->e->msg + k, sizeof up->e->msg - k, " (included from %s:%d)", up->file, line);
    }
    return rc;
}

Dict *dict_parse(const char *text, size_t n, const char *name, Err *e)
{
    Dict *d = dict_new(name);
    Parser P;
    parser_init(&P, text ? text : "", text ? n : 0, d->file, d->root, e);
    set_identity(&P, name);
    if (parse_entries(&P, d, 0, 1)) {
        dict_free(d);
        return NULL;
    }
    return d;
}

Dict *dict_read(const char *path, Err *e)
{
    Buf b;
    buf_init(&b);
    char *found = NULL;
    if (io_read_file(path, &b, &found, e)) {
        buf_free(&b);
        return NULL;
    }
    Dict *d = dict_parse(b.p, b.n, found ? found : path, e);
    free(found);
    buf_free(&b);
    return d;
}

/* ======================================================================
** Look-up
** ====================================================================== */

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

static const char *dname(const Dict *d) { return d->name[0] ? d->name : d->file; }

const Dict *dict_subdict_opt(const Dict *d, const char *key)
{
    const DictEntry *en = dict_find(d, key);
    return en ? en->dict : NULL;
}

const Dict *dict_subdict(const Dict *d, const char *key, Err *e)
{
    const DictEntry *en = dict_find(d, key);
    if (!en) {
        err_set(e, d->file, d->line, "sub-dictionary '%s' is missing in dictionary '%s'", key, dname(d));
        return NULL;
    }
    if (!en->dict) {
        err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s' is not a sub-dictionary", key, dname(d));
        return NULL;
    }
    return en->dict;
}

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
static void describe(const DictNode *nd, char *s, size_t n)
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

static int is_listlike(const DictNode *nd)
{
    return nd->kind == DN_LIST || nd->kind == DN_NUMS || nd->kind == DN_LABELS || nd->kind == DN_RAGGED;
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
        is_listlike(en->vals[1])) {
        if (en->vals[0]->num != (double)counted_items(en->vals[1])) {
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
                dname(d), want);
        return NULL;
    }
    if (en->nvals != 1) {
        err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s': expected %s, found %zu values", key,
                dname(d), want, en->nvals);
        return NULL;
    }
    return en->vals[0];
}

static int wrong(const Dict *d, const char *key, const DictNode *nd, const char *want, Err *e)
{
    char what[128];
    describe(nd, what, sizeof what);
    return err_set(e, nd->file, nd->line, "keyword '%s' in dictionary '%s': expected %s, found %s", key, dname(d),
                   want, what);
}

static int missing_key(const Dict *d, const char *key, Err *e)
{
    return err_set(e, d->file, d->line, "keyword '%s' is missing in dictionary '%s'", key, dname(d));
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
    if (nd->kind != DN_NUMBER || !nd->is_int || !fits_int(nd->num)) return wrong(d, key, nd, "an integer", e);
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
    if (nd->kind == DN_NUMS && ((nd->n == 3 && nd->width == 1) || (nd->n == 1 && nd->width == 3))) {
        memcpy(out, nd->v, 3 * sizeof(double));
        return 0;
    }
    if (nd->kind == DN_LABELS && nd->n == 3) {
        for (int k = 0; k < 3; k++) out[k] = nd->iv[k];
        return 0;
    }
    if (nd->kind == DN_LIST && nd->n == 3) {
        for (int k = 0; k < 3; k++) {
            if (nd->items[k]->kind != DN_NUMBER) return -1;
            out[k] = nd->items[k]->num;
        }
        return 0;
    }
    return -1;
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
    const char *w;
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
    char list[512] = "";
    size_t k = 0;
    for (size_t i = 0; i < n && k < sizeof list; i++) {
        int m = snprintf(list + k, sizeof list - k, "%s%s", i ? ", " : "", choices[i]);
        if (m < 0) break;
        k += (size_t)m;
    }
    const char *near = dict_closest(w, choices, n);
    return err_set(e, en->file, en->line, "keyword '%s' in dictionary '%s': '%s' is not one of: %s%s%s%s", key,
                   dname(d), w, list, near ? "; did you mean '" : "", near ? near : "", near ? "'?" : "");
}

/* ======================================================================
** Nodes
** ====================================================================== */

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
    describe(nd, what, sizeof what);
    return err_set(e, nd->file, nd->line, "expected %s, found %s", want, what);
}

/* Item i of a tuple-like node (LIST of numbers, NUMS width 1, LABELS). */
static int tuple_get(const DictNode *t, int w, double *out)
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

int dict_node_scalars(const DictNode *nd, int width, double **out, size_t *n, Err *e)
{
    char want[64];
    if (width < 1) width = 1;
    size_t w = (size_t)width;
    if (width == 1) snprintf(want, sizeof want, "a list of numbers");
    else snprintf(want, sizeof want, "a list of %d-tuples", width);
    if (nd->kind == DN_NUMS && (size_t)nd->width == w) {
        *out = dup_mem(nd->v, nd->n * w * sizeof(double));
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
    if (nd->n > SIZE_MAX / sizeof(double) / w) return node_err(nd, want, e);
    size_t nw = nd->n * w;
    double *v = MEM_NEW(double, nw);
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *t = nd->items[i];
        int bad = w == 1 ? t->kind != DN_NUMBER : tuple_get(t, width, v + i * w) != 0;
        if (bad) {
            free(v);
            size_t k;
            const DictNode *nf = dict_node_nonfinite(nd, &k);
            if (nf && k == i)
                return err_set(e, nf->file, nf->line, "item %zu of the list: '%s' is not a finite number", i,
                               nf->text);
            char what[128];
            describe(t, what, sizeof what);
            return err_set(e, t->file, t->line, "item %zu of the list: expected %s, found %s", i,
                           w == 1 ? "a number" : want + 10, what);
        }
        if (w == 1) v[i] = t->num;
    }
    *out = v;
    *n = nd->n;
    return 0;
}

static int int_item(const DictNode *t, int *out)
{
    if (t->kind != DN_NUMBER || !t->is_int || !fits_int(t->num)) return -1;
    *out = (int)t->num;
    return 0;
}

int dict_node_labels(const DictNode *nd, int **out, size_t *n, Err *e)
{
    if (nd->kind == DN_LABELS) {
        *out = dup_mem(nd->iv, nd->n * sizeof(int));
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_NUMS && nd->width == 1) {
        for (size_t i = 0; i < nd->n; i++)
            if (!fits_int(nd->v[i])) return node_err(nd, "a list of integers", e);
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

int dict_node_faces(const DictNode *nd, int **off, int **idx, size_t *n, Err *e)
{
    if (nd->kind == DN_RAGGED) {
        *off = dup_mem(nd->off, (nd->n + 1) * sizeof(int));
        *idx = dup_mem(nd->iv, (size_t)nd->off[nd->n] * sizeof(int));
        *n = nd->n;
        return 0;
    }
    if (nd->kind == DN_NUMS) {
        size_t w = (size_t)nd->width;
        if (nd->n * w > INT_MAX) return node_err(nd, "a list of integer lists", e);
        for (size_t i = 0; i < nd->n * w; i++)
            if (!fits_int(nd->v[i])) return node_err(nd, "a list of integer lists", e);
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
    if (nd->kind != DN_LIST) return node_err(nd, "a list of integer lists", e);
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
        for (size_t j = 0; j < t->n; j++, k++) {
            int bad = 0;
            if (t->kind == DN_LABELS) x[k] = t->iv[j];
            else if (t->kind == DN_NUMS) bad = !fits_int(t->v[j]), x[k] = bad ? 0 : (int)t->v[j];
            else bad = int_item(t->items[j], &x[k]);
            if (bad) {
                free(o);
                free(x);
                return node_err(t->kind == DN_LIST ? t->items[j] : t, "an integer", e);
            }
        }
    }
    o[nd->n] = (int)k;
    *off = o;
    *idx = x;
    *n = nd->n;
    return 0;
}

/* ======================================================================
** Keyword checking
** ====================================================================== */

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
            rc = err_set(e, en->file, en->line, "value without a keyword in dictionary '%s'", dname(d));
            break;
        }
        size_t k = 0;
        while (k < nk && strcmp(names[k], en->key) != 0) k++;
        if (k < nk) continue;
        const char *near = dict_closest(en->key, names, nk);
        if (near) {
            rc = err_set(e, en->file, en->line, "unknown keyword '%s' in %s; did you mean '%s'?", en->key, dname(d),
                         near);
        } else {
            char list[768] = "";
            size_t m = 0;
            for (size_t j = 0; j < nk && m < sizeof list; j++) {
                int w = snprintf(list + m, sizeof list - m, "%s%s", j ? " " : "", names[j]);
                if (w < 0) break;
                m += (size_t)w;
            }
            rc = err_set(e, en->file, en->line, "unknown keyword '%s' in %s; valid keywords: %s", en->key, dname(d),
                         list);
        }
    }
    free(names);
    return rc;
}

/* ======================================================================
** Building
** ====================================================================== */

int dict_set(Dict *d, const char *key, const char *value_text, Err *e)
{
    Parser P;
    parser_init(&P, value_text, strlen(value_text), d->file, d->root, e);
    NodeVec vals = {NULL, 0, 0};
    for (;;) {
        if (skip_ws(&P)) goto fail;
        if (P.p >= P.end) break;
        if (*P.p == ';') {
            P.p++;
            if (skip_ws(&P)) goto fail;
            if (P.p < P.end) {
                perr(&P, P.line, "unexpected text after ';' in the value of '%s'", key);
                goto fail;
            }
            break;
        }
        if (parse_value(&P, d, &vals, NULL)) goto fail;
    }
    if (check_sizes(&P, &vals, 1, key)) goto fail;
    DictEntry en;
    memset(&en, 0, sizeof en);
    en.key = mem_strdup(key);
    en.file = d->file;
    en.vals = vals.v;
    en.nvals = vals.n;
    entry_add(d, &en);
    return 0;
fail:
    free_nodes(&vals);
    return -1;
}

Dict *dict_add_subdict(Dict *d, const char *key)
{
    DictEntry *old = find_own(d, key, 0);
    if (old && old->dict) return old->dict;
    DictEntry en;
    memset(&en, 0, sizeof en);
    en.key = mem_strdup(key);
    en.file = d->file;
    en.dict = dict_child(d, key, d->file, 0);
    Dict *sub = en.dict;
    entry_add(d, &en);
    return sub;
}

int dict_remove(Dict *d, const char *key)
{
    for (size_t i = 0; i < d->n; i++)
        if (strcmp(d->entries[i].key, key) == 0) {
            remove_at(d, i);
            return 1;
        }
    return 0;
}

/* ======================================================================
** Writing
** ====================================================================== */

static void write_dict(const Dict *d, Buf *out, int indent, int blank);
static void write_node(const DictNode *nd, Buf *out, int indent);

static void put_indent(Buf *out, int indent)
{
    for (int i = 0; i < indent; i++) buf_putc(out, ' ');
}

static void put_quoted(Buf *out, const char *s)
{
    buf_putc(out, '"');
    for (; *s; s++) {
        if (*s == '"') buf_putc(out, '\\');
        buf_putc(out, *s);
    }
    buf_putc(out, '"');
}

/* A list short and flat enough for one line: "(1 2 3)", "(wall)". */
static int inline_ok(const DictNode *nd)
{
    switch (nd->kind) {
    case DN_NUMS:
        return nd->n * (size_t)nd->width <= 10 && nd->n <= 10;
    case DN_LABELS:
        return nd->n <= 10;
    case DN_RAGGED:
        return nd->n <= 4 && nd->off[nd->n] <= 16;
    case DN_LIST:
        if (nd->n > 10) return 0;
        for (size_t i = 0; i < nd->n; i++) {
            DictNodeKind k = nd->items[i]->kind;
            if (k == DN_DICT || ((k == DN_LIST || k == DN_NUMS || k == DN_LABELS || k == DN_RAGGED) &&
                                 !inline_ok(nd->items[i])))
                return 0;
        }
        return 1;
    default:
        return 1;
    }
}

static void put_label_tuple(Buf *out, const int *v, size_t n)
{
    buf_putc(out, '(');
    for (size_t k = 0; k < n; k++) {
        if (k) buf_putc(out, ' ');
        buf_printf(out, "%d", v[k]);
    }
    buf_putc(out, ')');
}

/* Item i of a compact list. */
static void write_item(const DictNode *nd, size_t i, Buf *out, int indent)
{
    switch (nd->kind) {
    case DN_NUMS:
        if (nd->width == 1) {
            foam_put_double(out, nd->v[i], 0);
        } else {
            buf_putc(out, '(');
            for (int k = 0; k < nd->width; k++) {
                if (k) buf_putc(out, ' ');
                foam_put_double(out, nd->v[i * (size_t)nd->width + (size_t)k], 0);
            }
            buf_putc(out, ')');
        }
        break;
    case DN_LABELS:
        buf_printf(out, "%d", nd->iv[i]);
        break;
    case DN_RAGGED:
        buf_printf(out, "%d", nd->off[i + 1] - nd->off[i]);
        put_label_tuple(out, nd->iv + nd->off[i], (size_t)(nd->off[i + 1] - nd->off[i]));
        break;
    default:
        write_node(nd->items[i], out, indent);
        break;
    }
}

static int is_listy(const DictNode *nd)
{
    return nd->kind == DN_LIST || nd->kind == DN_NUMS || nd->kind == DN_LABELS || nd->kind == DN_RAGGED;
}

static void write_list(const DictNode *nd, Buf *out, int indent, int sized);

/* A word with a '(' it does not close ("h(a"): a ')' right after it would
   be read as part of it. */
static int word_open(const DictNode *nd)
{
    if (nd->kind != DN_WORD || !nd->text) return 0;
    int depth = 0;
    for (const char *c = nd->text; *c; c++) {
        if (*c == '(') depth++;
        if (*c == ')' && depth > 0) depth--;
    }
    return depth > 0;
}

/* Writes nd on a new line after prev: a one-line list after an integer
   gets its size ("4\n2((1 2) (3 4))"), else "4\n((1 2) (3 4))" would
   read back as a sized list "4(...)" of the wrong length. */
static void write_after(const DictNode *prev, const DictNode *nd, Buf *out, int indent)
{
    int sized = prev && prev->kind == DN_NUMBER && prev->is_int && prev->num >= 0 && is_listy(nd);
    if (sized) write_list(nd, out, indent, 1);
    else write_node(nd, out, indent);
}

static void write_list(const DictNode *nd, Buf *out, int indent, int sized)
{
    if (nd->n == 0) {
        buf_puts(out, "0()");
        return;
    }
    if (inline_ok(nd)) {
        if (sized) buf_printf(out, "%zu", nd->n);
        buf_putc(out, '(');
        for (size_t i = 0; i < nd->n; i++) {
            if (i) buf_putc(out, ' ');
            write_item(nd, i, out, indent);
        }
        /* "h(a" then ')' would read back as the one word "h(a)" */
        if (nd->kind == DN_LIST && word_open(nd->items[nd->n - 1])) buf_putc(out, ' ');
        buf_putc(out, ')');
        return;
    }
    /* lists of name-dictionary pairs count the pairs, as OpenFOAM does */
    buf_printf(out, "\n%zu\n(\n", nd->n % 2 == 0 && dict_pairs(nd, nd->n / 2) ? nd->n / 2 : nd->n);
    for (size_t i = 0; i < nd->n; i++) {
        put_indent(out, nd->kind == DN_LIST ? indent + 4 : 0);
        if (nd->kind == DN_LIST) write_after(i ? nd->items[i - 1] : NULL, nd->items[i], out, indent + 4);
        else write_item(nd, i, out, indent + 4);
        buf_putc(out, '\n');
    }
    buf_puts(out, ")\n");
}

static void write_node(const DictNode *nd, Buf *out, int indent)
{
    switch (nd->kind) {
    case DN_WORD:
    case DN_PUNCT:
        buf_puts(out, nd->text ? nd->text : "");
        break;
    case DN_NUMBER:
        if (nd->text) buf_puts(out, nd->text);
        else foam_put_double(out, nd->num, 0);
        break;
    case DN_STRING:
        put_quoted(out, nd->text ? nd->text : "");
        break;
    case DN_DIMS:
        buf_putc(out, '[');
        for (size_t i = 0; i < nd->n; i++) {
            if (i) buf_putc(out, ' ');
            write_node(nd->items[i], out, indent);
        }
        buf_putc(out, ']');
        break;
    case DN_DICT:
        buf_puts(out, "{\n");
        write_dict(nd->dict, out, indent + 4, 0);
        put_indent(out, indent);
        buf_putc(out, '}');
        break;
    case DN_LIST:
    case DN_NUMS:
    case DN_LABELS:
    case DN_RAGGED:
        write_list(nd, out, indent, 0);
        break;
    }
}

void dict_write_node(const DictNode *nd, Buf *out) { write_node(nd, out, 0); }

static int is_plain_word(const char *s)
{
    if (!*s || *s == '"' || *s == '$' || *s == '#' || *s == '(' || *s == '[' || *s == '{') return 0;
    double x;
    int is_int;
    size_t n = foam_parse_number(s, s + strlen(s), &x, &is_int);
    if (n && s[n] == '\0') return 0;
    return word_len(s, s + strlen(s)) == strlen(s);
}

static void write_entry(const DictEntry *en, Buf *out, int indent, int last)
{
    put_indent(out, indent);
    if (!en->key[0] && !en->is_regex && !en->dict) {   /* a value without keyword */
        for (size_t i = 0; i < en->nvals; i++) {
            if (i) buf_putc(out, ' ');
            write_node(en->vals[i], out, indent);
        }
        buf_puts(out, last ? "\n" : "\n;\n");
        return;
    }
    size_t klen = strlen(en->key);
    if (en->is_regex || !is_plain_word(en->key)) {
        put_quoted(out, en->key);
        klen += 2;
    } else {
        buf_puts(out, en->key);
    }
    if (en->dict) {
        buf_putc(out, '\n');
        put_indent(out, indent);
        buf_puts(out, "{\n");
        write_dict(en->dict, out, indent + 4, 0);
        put_indent(out, indent);
        buf_puts(out, "}\n");
        return;
    }
    if (en->nvals) {
        for (size_t k = klen; k < KEY_COLUMN; k++) buf_putc(out, ' ');
        if (klen >= KEY_COLUMN) buf_putc(out, ' ');
    }
    for (size_t i = 0; i < en->nvals; i++) {
        if (i) buf_putc(out, ' ');
        write_node(en->vals[i], out, indent);
    }
    buf_puts(out, ";\n");
}

/* blank: a blank line between entries, as OpenFOAM writes the top level */
static void write_dict(const Dict *d, Buf *out, int indent, int blank)
{
    for (size_t i = 0; i < d->n; i++) {
        write_entry(&d->entries[i], out, indent, i + 1 == d->n);
        if (blank && i + 1 < d->n) buf_putc(out, '\n');
    }
}

void dict_write(const Dict *d, Buf *out) { write_dict(d, out, 0, 1); }

void dict_write_body(const Dict *d, Buf *out, int indent) { write_dict(d, out, indent, 0); }

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
