/*
** dict.h: OpenFOAM dictionaries: reading, look-up, writing.
**
** A dictionary file is a sequence of entries.  An entry is either
**     keyword value... ;          (a "primitive" entry: one or more nodes)
**     keyword { entries }          (a sub-dictionary)
** Keywords may be quoted regular expressions ("(U|k)Final" or ".*"),
** matched (POSIX extended, whole key) when no literal key matches; the last
** matching regex wins, as in OpenFOAM.
**
** Values are trees of DictNode.  Numbers, words, strings, dimension sets
** [0 1 -1 0 0 0 0], lists N( ... ) or ( ... ) and dictionaries nested in
** lists (the polyMesh boundary file is "N ( name { ... } ... )").
** Big homogeneous lists are stored compactly, never as one node per item:
**     DN_NUMS   flat doubles, `width` numbers per item: (1 2 3) has width 1,
**               ((x y z) (x y z)) has width 3;
**     DN_LABELS flat ints (every item an integer written without '.'/'e');
**     DN_RAGGED a list of integer lists, like faces: 4(1 2 3 4) 3(4 5 6);
**               stored as off[n+1] and idx[off[n]].
** Accessors (dict_node_scalars, dict_node_labels, dict_node_faces) convert
** between these forms, so callers never care which one the parser chose.
**
** Binary format (FoamFile { format binary; }): a list written as N then '('
** then raw little-endian bytes then ')'.  The element type comes from a
** preceding List<T> word (scalar, vector, label, ...) in the same entry, or
** else from the FoamFile class (vectorField, labelList, faceCompactList,
** scalarField) for a value without keyword; other lists are ascii even in
** binary files (inGroups 1(wall)), as OpenFOAM writes them.  label and
** scalar sizes come from the arch string (default label=32;scalar=64).
** An empty binary list is "0" without brackets (OpenFOAM's form).
**
** Values without a keyword (polyMesh files: "3 ( ... )"; faceCompactList:
** two lists) form one entry with the empty key "" holding every value up
** to ';', '}' or the end; dict_find(d, "") returns it.  "N(" and N alone
** on its line followed by "(" are sized lists; "arc 1 5 (0 1 0)" on one
** line is the number 5 and a list.  "N ( name { } ... )" counts pairs.
** Every size is checked while parsing: of a sized list, of a binary list,
** and of a number written apart from its list where it can only be a
** size: the whole value of an entry ("x 3 (1 2 3);") or right after a
** List<T> word ("List<scalar> 3 (1 2 3)").
**
** The FoamFile header, when there is one, must be the first entry and is
** checked as OpenFOAM checks it: format (ascii or binary) and object
** present; version (a number), format, class, object (words or strings)
** and arch (a string with label= and scalar= 32 or 64) each exactly one
** token ("file:line: FoamFile header: entry 'version' has 1 excess token
** ..."), so a missing ';' is caught.  A file without a header is read.
**
** Directives: #include "file" (relative to the including file),
** #includeEtc and #includeFunc are read and ignored with a warning kept in
** the Dict (dict_warnings); #remove key removes an entry; every other
** directive (#codeStream, #calc, #eval, #if...) is refused with
** "file:line: directive #calc is not supported".  $var and $scope.var
** (and $:top.var, $..parent.var) substitute the entry found by the usual
** scoped look-up: a sub-dictionary entry `$p;` alone merges p's entries.
**
** Every node and entry records its file and line, so every look-up error
** can say "file:line: ...".  Errors from the parser name the exact line.
*/
#ifndef KIESEL_DICT_H
#define KIESEL_DICT_H

#include <stddef.h>

#include "buf.h"
#include "err.h"

typedef struct Dict Dict;
typedef struct DictNode DictNode;
typedef struct DictEntry DictEntry;

typedef enum {
    DN_WORD,     /* text: bare word, e.g. uniform, List<scalar>, wall */
    DN_STRING,   /* text: contents of "..." without the quotes */
    DN_NUMBER,   /* num; is_int set when written as an integer */
    DN_PUNCT,    /* text: a lone punctuation character that is a value */
    DN_LIST,     /* items[n]: heterogeneous list */
    DN_DIMS,     /* items[n]: [ ... ] dimension set (numbers or unit words) */
    DN_DICT,     /* dict: { ... } inside a list or value */
    DN_NUMS,     /* v[n*width] */
    DN_LABELS,   /* iv[n] */
    DN_RAGGED    /* off[n+1], iv[off[n]] */
} DictNodeKind;

struct DictNode {
    DictNodeKind kind;
    int line;
    const char *file;  /* interned, owned by the root dictionary */
    char *text;        /* DN_WORD, DN_STRING, DN_PUNCT; number literal for DN_NUMBER */
    double num;        /* DN_NUMBER */
    int is_int;        /* DN_NUMBER */
    size_t n;          /* items: DN_LIST/DN_DIMS count, DN_NUMS/LABELS/RAGGED item count */
    DictNode **items;  /* DN_LIST, DN_DIMS */
    Dict *dict;        /* DN_DICT */
    int width;         /* DN_NUMS */
    double *v;         /* DN_NUMS */
    int *iv;           /* DN_LABELS, DN_RAGGED */
    int *off;          /* DN_RAGGED */
};

struct DictEntry {
    char *key;
    int is_regex;     /* key was a quoted string: matched as a regex */
    int line;
    const char *file;
    Dict *dict;       /* sub-dictionary entry, else NULL */
    DictNode **vals;  /* primitive entry: the value nodes before ';' */
    size_t nvals;
    void *re;         /* compiled regex (regex_t*), lazily */
};

struct Dict {
    char *name;       /* scoped name: "boundaryField.inlet"; "" at top */
    const char *file;
    int line;
    Dict *parent;
    DictEntry *entries;
    size_t n, cap;
    struct DictRoot *root;  /* shared by the whole tree: file names, options */
};

/* ---- reading ---- */

/* Reads and parses a file (gzip and .gz fallback through io_read_file,
   "-" for stdin).  Returns NULL and fills e on error. */
Dict *dict_read(const char *path, Err *e);
/* Parses text of length n; name is used in messages and to resolve
   #include paths.  The text needs no NUL terminator. */
Dict *dict_parse(const char *text, size_t n, const char *name, Err *e);
Dict *dict_new(const char *name);   /* empty root dictionary */
void dict_free(Dict *d);            /* frees a root dictionary and its tree */

/* FoamFile header conveniences (NULL or 0 when absent). */
const char *dict_header_class(const Dict *d);
int dict_header_binary(const Dict *d);   /* format binary */

/* ---- look-up ---- */

/* Literal key first, then regex keys (last match wins); NULL if absent.
   Keys may be scoped ("a.b.c") only through dict_find_scoped. */
const DictEntry *dict_find(const Dict *d, const char *key);
const DictEntry *dict_find_scoped(const Dict *d, const char *scoped);
/* Sub-dictionary, or NULL (and e filled: missing, or not a dictionary). */
const Dict *dict_subdict(const Dict *d, const char *key, Err *e);
/* Sub-dictionary if present, NULL silently otherwise. */
const Dict *dict_subdict_opt(const Dict *d, const char *key);

/* Typed look-ups.  The plain form requires the key; the _or form returns
   the default when the key is absent.  Both fail (return -1, fill e with
   "file:line: keyword 'k' in dictionary 'name': expected a number, found
   'abc'") when the value has the wrong type. */
int dict_scalar(const Dict *d, const char *key, double *out, Err *e);
int dict_scalar_or(const Dict *d, const char *key, double def, double *out, Err *e);
int dict_label(const Dict *d, const char *key, int *out, Err *e);
int dict_label_or(const Dict *d, const char *key, int def, int *out, Err *e);
int dict_vector(const Dict *d, const char *key, double out[3], Err *e);
int dict_vector_or(const Dict *d, const char *key, const double def[3], double out[3], Err *e);
/* Word or string value; the returned pointer lives as long as the dict. */
int dict_word(const Dict *d, const char *key, const char **out, Err *e);
int dict_word_or(const Dict *d, const char *key, const char *def, const char **out, Err *e);
/* on/off/yes/no/true/false/y/n/t/f/none(=off) */
int dict_switch(const Dict *d, const char *key, int *out, Err *e);
int dict_switch_or(const Dict *d, const char *key, int def, int *out, Err *e);
/* Word chosen from a NULL-terminated list; *out is its index.  The error
   lists the valid choices. */
int dict_choice_or(const Dict *d, const char *key, const char *const *choices, int def, int *out, Err *e);

/* ---- nodes ---- */

/* The single value node of a primitive entry (error if none or several).
   A size followed by a list ("x 41 (...)") counts as that list, and the
   size must match. */
const DictNode *dict_entry_value(const DictEntry *en, Err *e);
/* Number of items of any list-like node (LIST, NUMS, LABELS, RAGGED). */
size_t dict_node_len(const DictNode *nd);
/* Copies a list node into a new array of n*width doubles; accepts LIST of
   numbers or of width-tuples, NUMS, LABELS.  Fails with file:line when an
   item has the wrong shape. */
int dict_node_scalars(const DictNode *nd, int width, double **out, size_t *n, Err *e);
/* As dict_node_scalars, but a compact list of that width hands over its
   array instead of copying it (the node is left empty): readers of big
   lists (points, internalField) avoid a copy of the whole list. */
int dict_node_take_scalars(DictNode *nd, int width, double **out, size_t *n, Err *e);
/* The word that spells a non-finite number (nan, inf or infinity, in any
   case, signed or not): nd itself (*item 0), or the first such item of a
   list or of one of its tuples (*item its index).  OpenFOAM writes these
   values but reads them as words, as the parser does, so a reader can
   name them.  NULL when there is none. */
const DictNode *dict_node_nonfinite(const DictNode *nd, size_t *item);
/* Copies a list of integers into a new int array. */
int dict_node_labels(const DictNode *nd, int **out, size_t *n, Err *e);
/* As dict_node_labels, handing over a compact label list's array. */
int dict_node_take_labels(DictNode *nd, int **out, size_t *n, Err *e);
/* Copies a list of integer lists (RAGGED, or a LIST of LABELS/LIST) into
   off[n+1], idx[off[n]]. */
int dict_node_faces(const DictNode *nd, int **off, int **idx, size_t *n, Err *e);
/* Name of the node's kind for messages: "word", "list of numbers", ...
   (the look-up errors add the value: "found word 'abc'"). */
const char *dict_node_kind_name(const DictNode *nd);

/* ---- keyword checking and help ---- */

/* The valid keywords of a tool's dictionary: each with its default as
   text (NULL = required) and a one-line description.  A table ends with
   a zero entry.  -help prints these tables. */
typedef struct DictKey {
    const char *key;
    const char *def;
    const char *help;
} DictKey;

/* Fails on the first keyword of d (FoamFile excluded) not in keys:
   "file:line: unknown keyword 'endTme' in system/controlDict; did you
   mean 'endTime'?" (closest by edit distance, suggested when close). */
int dict_check_keys(const Dict *d, const DictKey *keys, Err *e);
/* Closest of the candidates by edit distance, or NULL if none is close. */
const char *dict_closest(const char *word, const char *const *cands, size_t n);

/* ---- building and writing ---- */

/* Adds (or replaces) an entry whose value is the given text, parsed as
   dictionary syntax ("uniform (0 0 0)", "2(a b)"). Returns 0 or -1. */
int dict_set(Dict *d, const char *key, const char *value_text, Err *e);
/* Adds (or returns the existing) sub-dictionary. */
Dict *dict_add_subdict(Dict *d, const char *key);
/* Removes an entry; returns 1 when one was removed. */
int dict_remove(Dict *d, const char *key);

/* Writes the entries of d (ascii, OpenFOAM layout: keyword padded to 16
   columns, 4-space indentation).  Numeric lists are written with
   the shortest representation that reads back bit-exactly. */
void dict_write(const Dict *d, Buf *out);
/* Writes the entries of d as the body of a sub-dictionary: every line
   indented by `indent` spaces, no blank lines between entries. */
void dict_write_body(const Dict *d, Buf *out, int indent);
/* Writes one primitive value node (as in "value <node>;"). */
void dict_write_node(const DictNode *nd, Buf *out);

/* Warnings collected while parsing (#includeEtc ignored, ...). */
size_t dict_nwarnings(const Dict *d);
const char *dict_warning(const Dict *d, size_t i);

#endif
