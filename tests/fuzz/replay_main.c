/*
** replay_main.c: runs a libFuzzer harness on files, without libFuzzer.
**
** Linked with a tests/fuzz/fuzz_*.c harness by gcc, it feeds every file
** named on the command line to LLVMFuzzerTestOneInput once, so that the
** seed corpus and every stored reproducer (tests/fuzz/crashes/) are
** replayed by `make test` on machines without clang: a fixed reader bug
** stays fixed.  A harness signals failure by aborting.
*/
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv) __attribute__((weak));

static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0, k;
    unsigned char *p = malloc(cap);
    while (p && (k = fread(p + len, 1, cap - len, f)) > 0) {
        len += k;
        if (len == cap) p = realloc(p, cap *= 2);
    }
    fclose(f);
    *n = len;
    return p;
}

int main(int argc, char **argv)
{
    if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
    for (int i = 1; i < argc; i++) {
        size_t n = 0;
        unsigned char *p = slurp(argv[i], &n);
        if (!p) {
            fprintf(stderr, "%s: cannot read\n", argv[i]);
            return 2;
        }
        LLVMFuzzerTestOneInput(p, n);
        free(p);
    }
    printf("replayed %d inputs\n", argc - 1);
    return 0;
}
