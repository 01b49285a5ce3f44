/*
** dict_write.c: writing dictionaries in OpenFOAM's ascii layout.
**
** Keywords are padded to KEY_COLUMN columns, sub-dictionaries indented by
** 4 spaces, and the top level has a blank line between entries.  Short
** flat lists go on one line, long ones one item a line after their size
** (a list of name-dictionary pairs counts the pairs, as OpenFOAM does).
** Numbers are written with the shortest representation that reads back
** bit-exactly (foam_put_double), and number literals as they were read.
**
** The invariant is that what is written parses back to the same tree:
** write(parse(write(d))) == write(d), which the fuzzer checks.  Hence
** the quoting of keys that are no plain words, the size before a list
** that follows an integer on its own line, and the blank before a ')'
** that would otherwise join an unclosed word ("h(a").
*/
#include "dict_impl.h"
#include "foam.h"

#include <string.h>

enum { KEY_COLUMN = 16 };   /* dict_write pads keywords to this width */

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
    int sized = prev && prev->kind == DN_NUMBER && prev->is_int && prev->num >= 0 && dict_node_is_list(nd);
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
    buf_printf(out, "\n%zu\n(\n", nd->n % 2 == 0 && dict_list_pairs(nd, nd->n / 2) ? nd->n / 2 : nd->n);
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
    return dict_lex_word_len(s, s + strlen(s)) == strlen(s);
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
