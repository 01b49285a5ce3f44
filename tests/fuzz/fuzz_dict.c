/*
** fuzz_dict.c: libFuzzer harness for the dictionary reader (dict_parse).
**
** Every input is parsed as a dictionary file.  When it parses, the harness
** walks the whole tree and calls every accessor on every entry (typed
** look-ups, scoped look-ups, the list converters with widths 1 and 3), so
** a tree the parser builds but an accessor cannot handle is found too.
** Then it checks the writer against the reader, the strongest oracle a
** text format has:
**     parse(write(d)) must succeed, and write(parse(write(d))) == write(d).
** The check is skipped for binary files (dict_write writes ascii lists
** under a header that still says "format binary") and can be switched off
** with FUZZ_NO_ROUNDTRIP=1 to hunt for crashes past a known round-trip bug.
** A failed parse must leave a message in Err (callers print nothing else).
**
** #include "inc" resolves relative to the input's name, which lives in a
** per-process scratch directory holding one small include file, so the
** include path is exercised without touching anything else (the directory
** is under $FUZZ_SCRATCH when set, which tests/fuzz/run removes).  Inputs that
** name device or kernel files (/dev, /proc, /sys) are skipped: reading
** /dev/zero forever is not a parser bug.
**
** Build: tests/fuzz/run (clang -fsanitize=fuzzer,address,undefined).
*/
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "buf.h"
#include "dict.h"

enum { MAX_DEPTH = 16 };

static char *scratch_name;   /* "<scratch>/fuzz.dict": the input's name */

/* A scratch directory under $FUZZ_SCRATCH (tests/fuzz/run sets it and
   removes it afterwards), else on tmpfs when there is one (fast, no disk). */
static char *fuzz_scratch_dir(const char *tag)
{
    const char *roots[] = {getenv("FUZZ_SCRATCH"), "/dev/shm", "/tmp"};
    for (size_t k = 0; k < 3; k++) {
        if (!roots[k]) continue;
        size_t n = strlen(roots[k]) + strlen(tag) + 16;
        char *dir = malloc(n);
        snprintf(dir, n, "%s/%s.XXXXXX", roots[k], tag);
        if (mkdtemp(dir)) return dir;
        free(dir);
    }
    abort();
}

static void fuzz_setup(void)
{
    char *dir = fuzz_scratch_dir("kiesel-fuzz-dict");
    size_t n = strlen(dir) + 16;
    char *inc = malloc(n);
    snprintf(inc, n, "%s/inc", dir);
    FILE *f = fopen(inc, "w");
    if (!f) abort();
    fputs("incA 1;\nincB { c (1 2 3); d 2(3(0 1 2) 4(0 1 2 3)); }\n", f);
    fclose(f);
    free(inc);
    scratch_name = malloc(n);
    snprintf(scratch_name, n, "%s/fuzz.dict", dir);
    free(dir);
}

static int names_system_file(const uint8_t *d, size_t n)
{
    static const char *const bad[] = {"/dev/", "/proc/", "/sys/"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        size_t m = strlen(bad[k]);
        for (size_t i = 0; i + m <= n; i++)
            if (memcmp(d + i, bad[k], m) == 0) return 1;
    }
    return 0;
}

/* Calls every converter on a value node; results are freed at once. */
static void poke_node(const DictNode *nd)
{
    Err e;
    double *v = NULL;
    int *iv = NULL, *off = NULL;
    size_t n = 0;
    (void)dict_node_kind_name(nd);
    (void)dict_node_len(nd);
    if (dict_node_scalars(nd, 1, &v, &n, &e) == 0) free(v);
    v = NULL;
    if (dict_node_scalars(nd, 3, &v, &n, &e) == 0) free(v);
    if (dict_node_labels(nd, &iv, &n, &e) == 0) free(iv);
    iv = NULL;
    if (dict_node_faces(nd, &off, &iv, &n, &e) == 0) {
        free(off);
        free(iv);
    }
    Buf b;
    buf_init(&b);
    dict_write_node(nd, &b);
    buf_free(&b);
}

/* Typed look-ups of one key: each either succeeds or fills e. */
static void poke_key(const Dict *d, const char *key)
{
    Err e;
    double x, vec[3];
    int i;
    const char *w;
    static const char *const choices[] = {"ascii", "binary", "on", NULL};
    (void)dict_find(d, key);
    (void)dict_scalar(d, key, &x, &e);
    (void)dict_label(d, key, &i, &e);
    (void)dict_vector(d, key, vec, &e);
    (void)dict_word(d, key, &w, &e);
    (void)dict_switch(d, key, &i, &e);
    (void)dict_choice_or(d, key, choices, 0, &i, &e);
    (void)dict_subdict(d, key, &e);
    (void)dict_subdict_opt(d, key);
}

static void walk(const Dict *d, int depth)
{
    Err e;
    if (depth > MAX_DEPTH) return;
    for (size_t k = 0; k < d->n; k++) {
        const DictEntry *en = &d->entries[k];
        poke_key(d, en->key);
        if (en->dict) {
            walk(en->dict, depth + 1);
            /* a scoped look-up through this sub-dictionary */
            for (size_t j = 0; j < en->dict->n && j < 4; j++) {
                size_t m = strlen(en->key) + strlen(en->dict->entries[j].key) + 2;
                char *s = malloc(m);
                snprintf(s, m, "%s.%s", en->key, en->dict->entries[j].key);
                (void)dict_find_scoped(d, s);
                free(s);
            }
            continue;
        }
        (void)dict_entry_value(en, &e);
        for (size_t j = 0; j < en->nvals; j++) {
            const DictNode *nd = en->vals[j];
            poke_node(nd);
            if (nd->kind == DN_DICT && nd->dict) walk(nd->dict, depth + 1);
            if (nd->kind == DN_LIST)
                for (size_t i = 0; i < nd->n; i++)
                    if (nd->items[i]->kind == DN_DICT && nd->items[i]->dict)
                        walk(nd->items[i]->dict, depth + 1);
        }
    }
}

static void roundtrip(const Dict *d)
{
    Err e;
    Buf a, b;
    buf_init(&a);
    buf_init(&b);
    dict_write(d, &a);
    Dict *d2 = dict_parse(a.p ? a.p : "", a.n, scratch_name, &e);
    if (!d2) {
        fprintf(stderr, "round trip: dict_write output does not parse: %s\n--- written:\n%.*s\n",
                e.msg, (int)(a.n < 4096 ? a.n : 4096), a.p ? a.p : "");
        abort();
    }
    dict_write(d2, &b);
    if (a.n != b.n || (a.n && memcmp(a.p, b.p, a.n) != 0)) {
        fprintf(stderr, "round trip: write(parse(write(d))) != write(d)\n--- first:\n%.*s\n--- second:\n%.*s\n",
                (int)(a.n < 4096 ? a.n : 4096), a.p ? a.p : "", (int)(b.n < 4096 ? b.n : 4096),
                b.p ? b.p : "");
        abort();
    }
    dict_free(d2);
    buf_free(&a);
    buf_free(&b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int no_roundtrip = -1;
    if (!scratch_name) fuzz_setup();
    if (no_roundtrip < 0) no_roundtrip = getenv("FUZZ_NO_ROUNDTRIP") != NULL;
    if (names_system_file(data, size)) return 0;
    Err e;
    e.msg[0] = '\0';
    Dict *d = dict_parse((const char *)data, size, scratch_name, &e);
    if (!d) {
        if (!e.msg[0]) {
            fprintf(stderr, "dict_parse failed without a message\n");
            abort();
        }
        return 0;
    }
    (void)dict_header_class(d);
    (void)dict_header_binary(d);
    for (size_t i = 0; i < dict_nwarnings(d); i++) (void)dict_warning(d, i);
    walk(d, 0);
    if (!no_roundtrip && !dict_header_binary(d)) roundtrip(d);
    dict_free(d);
    return 0;
}
