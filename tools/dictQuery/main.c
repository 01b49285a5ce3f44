/*
** dictQuery: prints an OpenFOAM dictionary as Kiesel reads it.
**
**     dictQuery FILE                      the whole dictionary (after #include
**                                         and $variable expansion)
**     dictQuery -entry a.b.c FILE         one entry ("a/b/c" also accepted)
**     dictQuery -entry a.b.c -value FILE  only its value
**     dictQuery [-entry d] -keywords FILE the keywords of a dictionary
**
** It mirrors OpenFOAM's foamDictionary closely enough that the two can be
** compared on the same files (tests/tools/dictQuery/test_foamDictionary.sh)
** and that scripts can read values, e.g. the application name from
** system/controlDict.  Warnings (#includeEtc ignored, ...) go to stderr.
*/
#include "args.h"
#include "case.h"
#include "buf.h"
#include "dict.h"
#include "err.h"
#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-entry", "NAME", "select the entry NAME (scoped with '.' or '/': boundaryField.inlet.type)"},
    {"-value", NULL, "print only the value of the selected entry"},
    {"-keywords", NULL, "list the keywords of the selected dictionary"},
    {0}};

static const ToolInfo tool = {"dictQuery", "dictQuery [options] FILE: print a dictionary FILE (or -dict FILE, - for stdin), an entry, its value or its keywords", opts, NULL,
                              0};

/* The entry named by a scoped name with '.' or '/' separators. */
static const DictEntry *select_entry(const Dict *d, const char *name)
{
    const DictEntry *en = dict_find_scoped(d, name);
    if (en || !strchr(name, '/')) return en;
    char *dots = mem_strdup(name);
    for (char *c = dots; *c; c++)
        if (*c == '/') *c = '.';
    en = dict_find_scoped(d, dots);
    free(dots);
    return en;
}

/* The value nodes of a primitive entry on one line (a long list keeps
   its own lines), without leading or trailing newlines. */
static void put_values(const DictEntry *en, Buf *out)
{
    Buf v;
    buf_init(&v);
    for (size_t i = 0; i < en->nvals; i++) {
        if (i) buf_putc(&v, ' ');
        dict_write_node(en->vals[i], &v);
    }
    size_t a = 0, b = v.n;
    while (a < b && v.p[a] == '\n') a++;
    while (b > a && v.p[b - 1] == '\n') b--;
    buf_put(out, v.p + a, b - a);
    buf_free(&v);
}

static void print_entry(const DictEntry *en, int value_only, Buf *out)
{
    if (en->dict) {
        if (!value_only) buf_printf(out, "%s\n", en->key);
        buf_puts(out, "{\n");
        dict_write_body(en->dict, out, 4);
        buf_puts(out, "}\n");
        return;
    }
    if (!value_only) buf_printf(out, "%-15s ", en->key);
    put_values(en, out);
    buf_puts(out, value_only ? "\n" : ";\n");
}

int main(int argc, char **argv)
{
    Args a;
    args_parse(argc, argv, &tool, &a);
    if (a.argc + (a.dict != NULL) != 1) err_fatal("expected one dictionary file (try -help)");
    const char *file = a.argc ? a.argv[0] : a.dict;
    const char *entry = args_get(&a, &tool, "-entry");
    int value = args_get(&a, &tool, "-value") != NULL;
    int keywords = args_get(&a, &tool, "-keywords") != NULL;
    if (value && keywords) err_fatal("-value and -keywords exclude each other");
    if (value && !entry) err_fatal("-value needs -entry");

    /* no controlDict: dictQuery may be what mends a broken one */
    Err e;
    Case cs;
    if (case_open(&cs, a.case_dir, CASE_NO_CONTROL, &e)) err_die(&e);
    char *path = strcmp(cs.dir, ".") && file[0] != '/' && strcmp(file, "-") ? case_path(&cs, file) : mem_strdup(file);
    Dict *d = dict_read(path, &e);
    if (!d) err_die(&e);
    for (size_t i = 0; i < dict_nwarnings(d); i++) err_warn("%s", dict_warning(d, i));

    const Dict *sel = d;
    const DictEntry *en = NULL;
    if (entry) {
        en = select_entry(d, entry);
        if (!en) {
            err_set(&e, path, 0, "entry '%s' not found", entry);
            err_die(&e);
        }
        sel = en->dict;
    }
    Buf out;
    buf_init(&out);
    if (keywords) {
        if (!sel) {
            err_set(&e, en->file, en->line, "entry '%s' is not a dictionary", entry);
            err_die(&e);
        }
        /* as foamDictionary: regex keys quoted, a value without keyword
           (polyMesh list) named entry0, entry1, ... */
        int bare = 0;
        for (size_t i = 0; i < sel->n; i++) {
            const DictEntry *k = &sel->entries[i];
            if (!k->key[0] && !k->is_regex) buf_printf(&out, "entry%d\n", bare++);
            else buf_printf(&out, k->is_regex ? "\"%s\"\n" : "%s\n", k->key);
        }
    } else if (en) {
        print_entry(en, value, &out);
    } else {
        dict_write(d, &out);
    }
    fwrite(out.p ? out.p : "", 1, out.n, stdout);
    buf_free(&out);
    dict_free(d);
    case_free(&cs);
    free(path);
    free(a.argv);
    return 0;
}
