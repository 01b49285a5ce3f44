/*
** dict_directive.c: directives (#include, #remove, ...).
**
** #include "file" (relative to the including file; <case>, <system>,
** <constant> and $ENV variables expanded; $FOAM_CASE defaults to the top
** file's case) and #includeIfPresent read another file into the current
** dictionary; #includeEtc and #includeFunc are read and ignored with a
** warning kept in the Dict (dict_warnings); #remove removes entries by
** keyword or regex.  Every other directive (#codeStream, #calc, #eval,
** #if...) is refused: "file:line: directive #calc is not supported".
**
** An included file gets a Parser of its own that links to its includer,
** so that nesting is bounded (MAX_INCLUDE) and a cycle is caught by
** (device, inode); errors inside it say where it was included from.
*/
#include "dict_impl.h"
#include "io.h"
#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_INCLUDE = 16 };   /* nesting of #include */

int dict_directive_name(Parser *P, char *name, size_t cap)
{
    const char *s = P->p + 1;
    size_t n = 0;
    while (s + n < P->end && ((s[n] >= 'a' && s[n] <= 'z') || (s[n] >= 'A' && s[n] <= 'Z'))) n++;
    if (s < P->end && *s == '{') return dict_perr(P, P->line, "verbatim code blocks #{ ... #} are not supported");
    if (n == 0) return dict_perr(P, P->line, "expected a directive name after '#'");
    if (n >= cap) n = cap - 1;
    memcpy(name, s, n);
    name[n] = '\0';
    P->p = s + n;
    while (P->p < P->end && !dict_is_delim(P->p, P->end)) P->p++;
    return 0;
}

/* #remove key, #remove "regex" or #remove (key "regex" ...). */
static int remove_keys(Parser *P, Dict *d, const DictNode *a, int line)
{
    const DictNode *const *keys = a->kind == DN_LIST ? (const DictNode *const *)a->items : &a;
    size_t nk = a->kind == DN_LIST ? a->n : 1;
    for (size_t i = 0; i < nk; i++) {
        const DictNode *k = keys[i];
        if (k->kind == DN_WORD) dict_remove(d, k->text);
        else if (k->kind != DN_STRING) return dict_perr(P, line, "#remove expects a keyword or a list of keywords");
        else if (dict_remove_matching(d, k->text))
            return dict_perr(P, line, "#remove: invalid regular expression \"%s\"", k->text);
    }
    return 0;
}

static int parse_file(Parser *up, Dict *d, const char *path, int line, int optional);

/* A directive at keyword position (P->p on the '#'). */
int dict_directive(Parser *P, Dict *d)
{
    int line = P->line;
    char name[64];
    if (dict_directive_name(P, name, sizeof name)) return -1;
    int inc = strcmp(name, "include") == 0, opt = strcmp(name, "includeIfPresent") == 0;
    int etc = strcmp(name, "includeEtc") == 0, func = strcmp(name, "includeFunc") == 0;
    int rem = strcmp(name, "remove") == 0;
    if (!inc && !opt && !etc && !func && !rem) return dict_perr(P, line, "directive #%s is not supported", name);
    if (dict_lex_ws(P)) return -1;
    DictNodeVec args = {NULL, 0, 0};
    if (P->p >= P->end || *P->p == ';' || *P->p == '}' || *P->p == '$' || *P->p == '#')
        return dict_perr(P, line, "expected an argument after #%s", name);
    if (dict_parse_value(P, d, &args, NULL)) {
        dict_nv_free(&args);
        return -1;
    }
    const DictNode *a = args.v[0];
    int rc = 0;
    if (rem) {
        rc = remove_keys(P, d, a, line);
    } else if (a->kind != DN_STRING && a->kind != DN_WORD) {
        rc = dict_perr(P, line, "#%s expects a file name", name);
    } else if (etc || func) {
        dict_add_warning(P->root, P->file, line, "#%s %s ignored (OpenFOAM's etc files are not read)", name, a->text);
    } else {
        rc = parse_file(P, d, a->text, line, opt);
    }
    dict_nv_free(&args);
    return rc;
}

/* ---- #include ---- */

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
            dict_perr(P, line, "#include: environment variable $%s is not set", name);
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


/* The path of an included file: the <case>, <system> and <constant>
   tags, an absolute path or one from $FOAM_CASE as it is, any other
   relative to the including file.  NULL on error. */
static char *include_path(Parser *up, const char *arg, int line)
{
    char *name = expand_env(up, arg, line);
    if (!name) return NULL;
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
    return path;
}

/* The text of an included file, read into d by a Parser of its own; a
   file that includes itself (same device and inode) is refused. */
static int parse_included(Parser *up, Dict *d, const Buf *text, const char *path, const char *found, int line)
{
    Parser P;
    dict_parser_init(&P, text->p, text->n, dict_intern(up->root, path), up->root, up->e);
    dict_parser_identity(&P, found ? found : path);
    for (Parser *q = up; q && P.have_id; q = q->up)
        if (q->have_id && q->dev == P.dev && q->ino == P.ino)
            return dict_perr(up, line, "#include cycle: '%s' includes itself", P.file);
    P.up = up;
    P.nincl = up->nincl + 1;
    P.depth = P.depth0 = up->depth;
    int rc = dict_parse_entries(&P, d, 0, 1);
    if (rc && up->e) {
        size_t k = strlen(up->e->msg);
        snprintf(up->e->msg + k, sizeof up->e->msg - k, " (included from %s:%d)", up->file, line);
    }
    return rc;
}

static int parse_file(Parser *up, Dict *d, const char *arg, int line, int optional)
{
    if (up->nincl + 1 > MAX_INCLUDE) return dict_perr(up, line, "#include nested too deeply (limit %d)", MAX_INCLUDE);
    char *path = include_path(up, arg, line);
    if (!path) return -1;
    int exists = io_is_dir(path) ? -1 : io_exists_gz(path);
    if (exists <= 0) {
        int rc = optional && exists == 0 ? 0 : dict_perr(up, line, "cannot open included file '%s'", path);
        free(path);
        return rc;
    }
    Buf text;
    buf_init(&text);
    char *found = NULL;
    Err e2;
    int rc;
    if (io_read_file(path, &text, &found, &e2)) rc = dict_perr(up, line, "#include: %s", e2.msg);
    else rc = parse_included(up, d, &text, path, found, line);
    free(found);
    free(path);
    buf_free(&text);
    return rc;
}
