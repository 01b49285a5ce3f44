/*
** dict_impl.h: what the pieces of the dictionary module share; included
** only by common/dict*.c (callers use dict.h).
**
** The module is cut by concept, one file each:
**   dict.c           the tree: lifetime, merge-mode adding, copying, find
**   dict_regex.c     quoted (regular-expression) keys and their cost limit
**   dict_lex.c       tokens: blanks and comments, words, strings, numbers
**   dict_parse.c     the grammar: values, entries, dict_parse/read/set
**   dict_header.c    the FoamFile header: OpenFOAM's checks, arch sizes
**   dict_list.c      ascii lists: the fast path, compaction, sizes, N{v}
**   dict_binary.c    raw binary lists and their element types
**   dict_var.c       $variables: scoped look-up, expansion, copy budget
**   dict_directive.c #include, #remove and the other directives
**   dict_get.c       typed look-ups (dict_scalar, dict_word, ...)
**   dict_node.c      node accessors and descriptions for messages
**   dict_keys.c      keyword checking against a tool's table
**   dict_write.c     the writer
**
** Invariant shared by the reading pieces: every routine works on
** [P->p, P->end) of one Parser, never needs a NUL terminator, and leaves
** P->line counting the newlines it consumed (raw binary data excepted).
*/
#ifndef KIESEL_DICT_IMPL_H
#define KIESEL_DICT_IMPL_H

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <sys/types.h>

#include "dict.h"

/* Nesting of dictionaries, lists and dimension sets together. */
enum { DICT_MAX_DEPTH = 64 };

struct DictRoot {
    size_t copied;           /* items copied by $variables (bounded) */
    char **files;            /* interned file names; files[0] is the top file */
    size_t nfiles, cfiles;
    char **warn;
    size_t nwarn, cwarn;
};

/* A growing vector of value nodes (an entry's values, a list's items). */
typedef struct DictNodeVec {
    DictNode **v;
    size_t n, cap;
} DictNodeVec;

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

/* ---- dict.c: the tree ---- */
void dict_nv_push(DictNodeVec *a, DictNode *nd);
void dict_nv_free(DictNodeVec *v);
const char *dict_intern(struct DictRoot *r, const char *name);
void dict_add_warning(struct DictRoot *r, const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
DictNode *dict_node_new(DictNodeKind kind, const char *file, int line);
void dict_node_free(DictNode *nd);
DictNode *dict_node_copy(const DictNode *s, Dict *parent);
void *dict_dup_mem(const void *p, size_t n);
Dict *dict_child(Dict *parent, const char *key, const char *file, int line);
Dict *dict_copy(const Dict *s, Dict *parent, const char *key);
void dict_free_tree(Dict *d);
void dict_entry_clear(DictEntry *en);
/* Adds *en in OpenFOAM's merge mode, taking ownership (*en is cleared). */
void dict_entry_add(Dict *d, DictEntry *en);
DictEntry *dict_find_own(Dict *d, const char *key, int is_regex);
void dict_remove_at(Dict *d, size_t i);
/* The dictionary's name for messages: its scoped name, or its file. */
const char *dict_display_name(const Dict *d);

/* ---- dict_regex.c ---- */
/* Compiles en->key into en->re; -1 with the reason in why. */
int dict_key_compile(DictEntry *en, char *why, size_t nwhy);
/* Removes the entries of d whose key the regex matches; -1 if invalid. */
int dict_remove_matching(Dict *d, const char *re);

/* ---- dict_lex.c ---- */
int dict_perr(Parser *P, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
int dict_is_digit(char c);
int dict_lex_ws(Parser *P);
size_t dict_lex_word_len(const char *p, const char *end);
char *dict_lex_string(Parser *P);
int dict_lex_number(Parser *P, double *x, int *is_int, size_t *len);

/* Blank characters, and the characters that end a number or a word
   (comment starts included).  Inline: the list fast path calls them once
   a character. */
static inline int dict_is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

static inline int dict_is_delim(const char *p, const char *end)
{
    if (p >= end) return 1;
    char c = *p;
    if (dict_is_space(c) || c == ';' || c == '{' || c == '}' || c == '(' || c == ')' || c == '[' || c == ']' ||
        c == '"' || c == '\0')
        return 1;
    return c == '/' && p + 1 < end && (p[1] == '/' || p[1] == '*');
}

/* A double that is an int (in range, no fraction); inline for the same
   reason. */
static inline int dict_fits_int(double x) { return x >= INT_MIN && x <= INT_MAX && x == floor(x); }

/* ---- dict_parse.c ---- */
void dict_parser_init(Parser *P, const char *text, size_t n, const char *file, struct DictRoot *root, Err *e);
void dict_parser_identity(Parser *P, const char *path);
int dict_parse_nest(Parser *P);
int dict_parse_value(Parser *P, Dict *d, DictNodeVec *out, const char *hint);
int dict_parse_entries(Parser *P, Dict *d, int braced, int line0);

/* ---- dict_header.c ---- */
int dict_header_check(Parser *P, const Dict *h);
void dict_header_settings(Parser *P, const Dict *h);

/* ---- dict_list.c ---- */
int dict_list_parse(Parser *P, Dict *d, long size, int line, DictNodeVec *out);
int dict_list_uniform(Parser *P, Dict *d, long size, int line, DictNodeVec *out);
int dict_list_check_sizes(Parser *P, const DictNodeVec *v, int whole, const char *key);
size_t dict_list_counted(const DictNode *nd);
int dict_list_pairs(const DictNode *nd, size_t size);

/* ---- dict_binary.c ---- */
int dict_binary_list(Parser *P, long size, int w, int is_label, int line, DictNodeVec *out);
int dict_binary_type(const char *t, size_t n, int *is_label);
void dict_binary_class_type(Parser *P);

/* ---- dict_var.c ---- */
int dict_var_expand(Parser *P, Dict *d, DictNodeVec *out);
int dict_var_merge(Parser *P, Dict *d, int line);

/* ---- dict_directive.c ---- */
int dict_directive_name(Parser *P, char *name, size_t cap);
int dict_directive(Parser *P, Dict *d);

/* ---- dict_keys.c ---- */
/* words[0..n) joined by sep into buf (cut at cap), for messages that
   list the valid choices. */
void dict_join(char *buf, size_t cap, const char *const *words, size_t n, const char *sep);

/* ---- dict_node.c ---- */
/* The w numbers of a tuple-like node (LIST of numbers, NUMS width 1,
   LABELS) into out; -1 if it is not one. */
int dict_node_tuple(const DictNode *t, int w, double *out);
int dict_node_is_list(const DictNode *nd);
void dict_node_describe(const DictNode *nd, char *s, size_t n);

#endif
