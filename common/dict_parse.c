/*
** dict_parse.c: the grammar of a dictionary: values, entries, files.
**
** A file is a sequence of entries (dict.h).  The parser is recursive
** descent over one Parser per file (dict_impl.h); it peeks at the next
** raw character after dict_lex_ws and hands lists to dict_list.c or
** dict_binary.c, $variables to dict_var.c and #directives to
** dict_directive.c.  Recursion is bounded by DICT_MAX_DEPTH (nested
** dictionaries, lists and dimension sets together).
**
** $variables are expanded while reading, so they see exactly the entries
** defined above them, as in OpenFOAM; a value that is only "$d" for a
** dictionary d makes the entry a sub-dictionary copy.
**
** A value without a keyword at the start of an entry (a number or a list:
** "3 ( ... )" in a polyMesh file) is kept as an entry with the empty key "",
** holding every value up to ';', '}' or the end of the input; at the top
** of the top file its binary lists take their type from the FoamFile
** class.  The FoamFile header must come first (dict_header.c checks it);
** an included file's header is read for its format and then dropped.
*/
#include "dict_impl.h"
#include "foam.h"
#include "io.h"
#include "mem.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- values ---- */

int dict_parse_nest(Parser *P)
{
    if (++P->depth > DICT_MAX_DEPTH) return dict_perr(P, P->line, "nesting deeper than %d levels", DICT_MAX_DEPTH);
    return 0;
}

static DictNode *text_node(Parser *P, DictNodeKind kind, const char *s, size_t n, int line)
{
    DictNode *nd = dict_node_new(kind, P->file, line);
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

static int parse_dims(Parser *P, DictNodeVec *out)
{
    int line0 = P->line;
    DictNodeVec it = {NULL, 0, 0};
    P->p++;
    for (;;) {
        if (dict_lex_ws(P)) goto fail;
        if (P->p >= P->end) {
            dict_perr(P, line0, "unterminated dimension set started at line %d", line0);
            goto fail;
        }
        if (*P->p == ']') break;
        double x;
        int is_int, rc;
        size_t len;
        const char *s = P->p;
        if ((rc = dict_lex_number(P, &x, &is_int, &len)) < 0) goto fail;
        if (rc) {
            dict_nv_push(&it, number_node(P, s, len, x, is_int, P->line));
            continue;
        }
        size_t n = dict_lex_word_len(P->p, P->end);
        if (n == 0 || *P->p == '(' ) {
            dict_perr(P, P->line, "unexpected '%c' in the dimension set started at line %d", *P->p ? *P->p : '?',
                 line0);
            goto fail;
        }
        dict_nv_push(&it, text_node(P, DN_WORD, P->p, n, P->line));
        P->p += n;
    }
    P->p++;
    DictNode *nd = dict_node_new(DN_DIMS, P->file, line0);
    nd->n = it.n;
    nd->items = it.v;
    dict_nv_push(out, nd);
    return 0;
fail:
    for (size_t i = 0; i < it.n; i++) dict_node_free(it.v[i]);
    free(it.v);
    return -1;
}

/* Whether only blanks precede the token at s on its line. */
static int alone_on_line(const Parser *P, const char *s)
{
    while (s > P->start && (s[-1] == ' ' || s[-1] == '\t' || s[-1] == '\r')) s--;
    return s == P->start || s[-1] == '\n';
}

/* A number token as dict_lex_number read it. */
typedef struct NumTok {
    const char *s;
    size_t len;
    double x;
    int is_int;
} NumTok;

/* After a number: "N(" is a sized list, and so is "N" alone on its line
   followed by "(" on the next, as OpenFOAM writes long lists; "N{" is a
   uniform list.  "arc 1 5 (0.5 0.5 0)" is a number and a list.  In a
   binary file, after List<T> (lw, ll), "N" starts raw data. */
static int number_value(Parser *P, Dict *d, const NumTok *t, int lw, int ll, int line, DictNodeVec *out)
{
    const char *after = P->p, *q = P->p;
    int line_after = P->line, newline = 0;
    while (q < P->end && dict_is_space(*q)) newline |= *q++ == '\n';
    char nx = q < P->end ? *q : '\0';
    if (!((nx == '(' && (q == after || (newline && alone_on_line(P, t->s)))) || (nx == '{' && q == after)))
        nx = '\0';
    if (nx && dict_lex_ws(P)) return -1;
    if (t->is_int && t->x >= 0 && (nx == '(' || nx == '{')) {
        if (t->x > 1e18) return dict_perr(P, line, "list size %.*s is too large", (int)t->len, t->s);
        long size = (long)t->x;
        if (nx == '{') return dict_list_uniform(P, d, size, line, out);
        if (P->binary && lw) return dict_binary_list(P, size, lw, ll, line, out);
        return dict_list_parse(P, d, size, line, out);
    }
    if (P->binary && lw && t->is_int && t->x >= 0 && t->x <= 1e18) {
        if (dict_lex_ws(P)) return -1;
        return dict_binary_list(P, (long)t->x, lw, ll, line, out);
    }
    P->p = after;   /* keep the blanks for the caller's line count */
    P->line = line_after;
    dict_nv_push(out, number_node(P, t->s, t->len, t->x, t->is_int, line));
    return 0;
}

/* { entries } as a value (inside a list); hint names it for messages. */
static int subdict_value(Parser *P, Dict *d, const char *hint, int line, DictNodeVec *out)
{
    if (dict_parse_nest(P)) return -1;
    Dict *sub = dict_child(d, hint ? hint : "", P->file, line);
    P->p++;
    if (dict_parse_entries(P, sub, 1, line)) {
        dict_free_tree(sub);
        return -1;
    }
    P->depth--;
    DictNode *nd = dict_node_new(DN_DICT, P->file, line);
    nd->dict = sub;
    dict_nv_push(out, nd);
    return 0;
}

static int string_value(Parser *P, int line, DictNodeVec *out)
{
    char *s = dict_lex_string(P);
    if (!s) return -1;
    DictNode *nd = dict_node_new(DN_STRING, P->file, line);
    nd->text = s;
    dict_nv_push(out, nd);
    return 0;
}

/* A word; List<T> sets the element type of the list that follows. */
static int word_value(Parser *P, char c, int line, DictNodeVec *out)
{
    size_t n = dict_lex_word_len(P->p, P->end);
    if (n == 0) return dict_perr(P, line, "unexpected character '%c'", c);
    DictNode *nd = text_node(P, DN_WORD, P->p, n, line);
    P->p += n;
    P->list_w = dict_binary_type(nd->text, n, &P->list_label);
    dict_nv_push(out, nd);
    return 0;
}

/* Parses one value at P->p (blanks already skipped), appending its
   node(s) to out: a variable may expand to several. */
int dict_parse_value(Parser *P, Dict *d, DictNodeVec *out, const char *hint)
{
    int line = P->line;
    char c = *P->p;
    int lw = P->list_w, ll = P->list_label;
    P->list_w = P->list_label = 0;
    switch (c) {
    case '(':
        return dict_list_parse(P, d, -1, line, out);
    case '[':
        return parse_dims(P, out);
    case ')':
    case ']':
    case '}':
        return dict_perr(P, line, "unmatched '%c'", c);
    case '\0':
        return dict_perr(P, line, "unexpected NUL byte");
    case '{':
        return subdict_value(P, d, hint, line, out);
    case '"':
        return string_value(P, line, out);
    case '$':
        return dict_var_expand(P, d, out);
    case '#': {
        char name[64];
        if (dict_directive_name(P, name, sizeof name)) return -1;
        return dict_perr(P, line, "directive #%s is not supported%s", name,
                         strncmp(name, "include", 7) == 0 || strcmp(name, "remove") == 0 ? " inside a value" : "");
    }
    default:
        break;
    }
    NumTok t = {P->p, 0, 0, 0};
    int rc = dict_lex_number(P, &t.x, &t.is_int, &t.len);
    if (rc < 0) return -1;
    if (rc) return number_value(P, d, &t, lw, ll, line, out);
    return word_value(P, c, line, out);
}

/* Values up to ';' (primitive entry), '}' or the end for a keyword-less
   entry (bare > 0; bare == 2: binary lists typed by the FoamFile class).
   key is for messages. */
static int parse_values(Parser *P, Dict *d, DictNodeVec *vals, const char *key, int kline, int bare)
{
    for (;;) {
        if (dict_lex_ws(P)) return -1;
        if (P->p >= P->end || *P->p == '}') {
            if (bare) return dict_list_check_sizes(P, vals, 1, NULL);
            return dict_perr(P, kline, "expected ';' after value of keyword '%s'", key);
        }
        if (*P->p == ';') {
            P->p++;
            return dict_list_check_sizes(P, vals, 1, bare ? NULL : key);
        }
        if (bare == 2) dict_binary_class_type(P);
        if (dict_parse_value(P, d, vals, NULL)) return -1;
    }
}

/* ---- entries ---- */

/* A value where a keyword should be: a list, or a number (never a
   keyword), as in polyMesh files "3 ( ... )". */
static int is_bare_start(Parser *P)
{
    if (*P->p == '(') return 1;
    double x;
    int is_int;
    size_t n = foam_parse_number(P->p, P->end, &x, &is_int);
    return n > 0 && dict_is_delim(P->p + n, P->end);
}

/* Values without a keyword: the entry "". */
static int bare_entry(Parser *P, Dict *d, DictEntry *en, int line)
{
    DictNodeVec vals = {NULL, 0, 0};
    en->key = mem_strdup("");
    int typed_by_class = !P->up && P->depth == 0 && d->parent == NULL;
    if (parse_values(P, d, &vals, "", line, 1 + typed_by_class)) {
        dict_nv_free(&vals);
        return -1;
    }
    en->vals = vals.v;
    en->nvals = vals.n;
    dict_entry_add(d, en);
    return 0;
}

/* The keyword at P->p (c): a word, or a quoted regular expression. */
static int read_key(Parser *P, DictEntry *en, char c, int line)
{
    if (c == '"') {
        en->key = dict_lex_string(P);
        if (!en->key) return -1;
        en->is_regex = 1;
        char why[128];
        if (dict_key_compile(en, why, sizeof why))
            return dict_perr(P, line, "invalid regular expression \"%s\": %s", en->key, why);
        return 0;
    }
    if (c == '[' || c == '{') return dict_perr(P, line, "expected a keyword, found '%c'", c);
    size_t n = dict_lex_word_len(P->p, P->end);
    if (n == 0) return dict_perr(P, line, "unexpected character '%c'", c);
    en->key = mem_strndup(P->p, n);
    P->p += n;
    return 0;
}

/* "key { entries }"; a FoamFile header at the top level of a file is
   checked and sets the format (in an included file it is no entry). */
static int subdict_entry(Parser *P, Dict *d, DictEntry *en, int line)
{
    int brace = P->line;
    if (dict_parse_nest(P)) return -1;
    P->p++;
    en->dict = dict_child(d, en->key, P->file, line);
    if (dict_parse_entries(P, en->dict, 1, brace)) return -1;
    P->depth--;
    if (strcmp(en->key, "FoamFile") == 0 && P->depth == P->depth0) {
        if (P->ntop > 1)
            return dict_perr(P, line, "FoamFile header after other entries: it must come first, as OpenFOAM reads it");
        if (dict_header_check(P, en->dict)) return -1;
        dict_header_settings(P, en->dict);
        if (P->up) {
            dict_entry_clear(en);
            return 0;
        }
    }
    dict_entry_add(d, en);
    return 0;
}

/* "key values... ;" */
static int value_entry(Parser *P, Dict *d, DictEntry *en, int line)
{
    DictNodeVec vals = {NULL, 0, 0};
    if (strcmp(en->key, "FoamFile") == 0 && P->depth == P->depth0)
        return dict_perr(P, line,
                         "FoamFile header must be a dictionary { version 2.0; format ascii; class ...; object ...; }");
    if (parse_values(P, d, &vals, en->key, line, 0)) goto fail;
    if (vals.n > 1 && vals.v[0]->kind == DN_DICT) {
        /* "key $dict more;" could not be written back: "key {" starts
           a sub-dictionary */
        dict_perr(P, line, "keyword '%s': a dictionary variable cannot be followed by other values", en->key);
        goto fail;
    }
    if (vals.n == 1 && vals.v[0]->kind == DN_DICT) {
        /* "key $dict;" makes key a sub-dictionary */
        en->dict = vals.v[0]->dict;
        vals.v[0]->dict = NULL;
        dict_nv_free(&vals);
    } else {
        en->vals = vals.v;
        en->nvals = vals.n;
    }
    dict_entry_add(d, en);
    return 0;
fail:
    dict_nv_free(&vals);
    return -1;
}

/* One entry at P->p (c, on line): keyword-less values, a sub-dictionary
   or a primitive entry. */
static int parse_entry(Parser *P, Dict *d, char c, int line)
{
    DictEntry en;
    memset(&en, 0, sizeof en);
    en.line = line;
    en.file = P->file;
    int rc;
    if (is_bare_start(P)) rc = bare_entry(P, d, &en, line);
    else if (read_key(P, &en, c, line) || dict_lex_ws(P)) rc = -1;
    else if (P->p < P->end && *P->p == '{') rc = subdict_entry(P, d, &en, line);
    else rc = value_entry(P, d, &en, line);
    if (rc) dict_entry_clear(&en);
    return rc;
}

/* Parses entries into d until '}' (braced) or the end of the input. */
int dict_parse_entries(Parser *P, Dict *d, int braced, int line0)
{
    for (;;) {
        if (dict_lex_ws(P)) return -1;
        if (P->p >= P->end) {
            if (braced) return dict_perr(P, line0, "unterminated dictionary started at line %d", line0);
            return 0;
        }
        char c = *P->p;
        int line = P->line, rc;
        if (c == '}') {
            if (!braced) return dict_perr(P, line, "unmatched '}'");
            P->p++;
            return 0;
        }
        if (c == ';') {
            P->p++;
            continue;
        }
        if (P->depth == P->depth0) P->ntop++;   /* for the FoamFile-first rule */
        if (c == ')' || c == ']') return dict_perr(P, line, "unmatched '%c'", c);
        if (c == '\0') return dict_perr(P, line, "unexpected NUL byte");
        if (c == '#') rc = dict_directive(P, d);
        else if (c == '$') rc = dict_var_merge(P, d, line);
        else rc = parse_entry(P, d, c, line);
        if (rc) return -1;
    }
}

/* ---- files ---- */

void dict_parser_init(Parser *P, const char *text, size_t n, const char *file, struct DictRoot *root, Err *e)
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

void dict_parser_identity(Parser *P, const char *path)
{
    struct stat st;
    if (path && stat(path, &st) == 0) {
        P->have_id = 1;
        P->dev = st.st_dev;
        P->ino = st.st_ino;
    }
}

Dict *dict_parse(const char *text, size_t n, const char *name, Err *e)
{
    Dict *d = dict_new(name);
    Parser P;
    dict_parser_init(&P, text ? text : "", text ? n : 0, d->file, d->root, e);
    dict_parser_identity(&P, name);
    if (dict_parse_entries(&P, d, 0, 1)) {
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

/* ---- building: a value given as text ---- */

int dict_set(Dict *d, const char *key, const char *value_text, Err *e)
{
    Parser P;
    dict_parser_init(&P, value_text, strlen(value_text), d->file, d->root, e);
    DictNodeVec vals = {NULL, 0, 0};
    for (;;) {
        if (dict_lex_ws(&P)) goto fail;
        if (P.p >= P.end) break;
        if (*P.p == ';') {
            P.p++;
            if (dict_lex_ws(&P)) goto fail;
            if (P.p < P.end) {
                dict_perr(&P, P.line, "unexpected text after ';' in the value of '%s'", key);
                goto fail;
            }
            break;
        }
        if (dict_parse_value(&P, d, &vals, NULL)) goto fail;
    }
    if (dict_list_check_sizes(&P, &vals, 1, key)) goto fail;
    DictEntry en;
    memset(&en, 0, sizeof en);
    en.key = mem_strdup(key);
    en.file = d->file;
    en.vals = vals.v;
    en.nvals = vals.n;
    dict_entry_add(d, &en);
    return 0;
fail:
    dict_nv_free(&vals);
    return -1;
}
