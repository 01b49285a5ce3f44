/*
** dict_regex.c: quoted keys, which are POSIX extended regular expressions
** matched against the whole key (OpenFOAM's "(U|k)Final", ".*", and the
** "(?i)" prefix for case-insensitive).
**
** A key is compiled once, as "^(re)$", when its entry is created (the
** bare key is compiled first so that "a)(b" is refused rather than
** accepted once anchored).  Before any compiling, regex_too_complex
** bounds what glibc's regcomp would build: it expands repetitions by
** copying, so a short hostile key could take seconds and gigabytes.
** #remove "re" uses the same anchoring and the same bound.
*/
#include "dict_impl.h"
#include "mem.h"

#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        if (c == '\\' && i + 1 < len && dict_is_digit(s[i + 1]))
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
                if (dict_is_digit(s[i])) {
                    double v = 0;
                    for (; i < len && dict_is_digit(s[i]); i++) v = v * 10 + (s[i] - '0');
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

/* Compiles "^(key)$" into re; regcomp's code. */
static int compile_whole(regex_t *re, const char *key, int flags)
{
    size_t n = strlen(key) + 5;
    char *pat = mem_alloc(n);
    snprintf(pat, n, "^(%s)$", key);
    int rc = regcomp(re, pat, flags);
    free(pat);
    return rc;
}

int dict_key_compile(DictEntry *en, char *why, size_t nwhy)
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
    en->re = mem_alloc(sizeof(regex_t));
    rc = compile_whole(en->re, key, flags);
    if (rc) {
        regerror(rc, en->re, why, nwhy);
        free(en->re);
        en->re = NULL;
        return -1;
    }
    return 0;
}


int dict_remove_matching(Dict *d, const char *re)
{
    regex_t r;
    char why[128];
    if (regex_too_complex(re, why, sizeof why) || compile_whole(&r, re, REG_EXTENDED | REG_NOSUB) != 0) return -1;
    for (size_t j = d->n; j-- > 0;)
        if (regexec(&r, d->entries[j].key, 0, NULL, 0) == 0) dict_remove_at(d, j);
    regfree(&r);
    return 0;
}
