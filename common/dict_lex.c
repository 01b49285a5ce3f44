/*
** dict_lex.c: the tokens of a dictionary: blanks and comments, words,
** "strings" and numbers.
**
** There is no token buffer: the parser peeks at raw characters (after
** dict_lex_ws) to decide what comes next, and each function here consumes
** one token.  Every routine works on [P->p, P->end) and never needs a NUL
** terminator, so binary data, embedded NUL bytes and truncated input are
** just more cases to report ("file:line: ...").
**
** Strings follow OpenFOAM: \" is a quote, backslash-newline continues the
** line, every other backslash is kept; the writer escapes only quotes, so
** write -> parse reproduces the text.  A word ends at blanks, ;{}[]" and
** NUL, and at a ')' that closes no '(' of the word, so "div(phi,U)" is one
** word.  A number is a token only when a delimiter ends it ("1e" is a
** word); one out of double range is an error, never inf.
*/
#include "dict_impl.h"
#include "foam.h"

#include <math.h>
#include <stdarg.h>

int dict_perr(Parser *P, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    err_setv(P->e, P->file, line, fmt, ap);
    va_end(ap);
    return -1;
}

int dict_is_digit(char c) { return c >= '0' && c <= '9'; }

/* Skips blanks and comments.  -1 on an unterminated comment. */
int dict_lex_ws(Parser *P)
{
    const char *p = P->p, *end = P->end;
    for (;;) {
        while (p < end && dict_is_space(*p)) {
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
                return dict_perr(P, line0, "unterminated comment");
            }
            p += 2;
            continue;
        }
        break;
    }
    P->p = p;
    return 0;
}

/* Length of the word at p: stops at blanks, ;{}[]" and NUL, and at a ')'
   that closes no '(' of the word, so "div(phi,U)" is one word. */
size_t dict_lex_word_len(const char *p, const char *end)
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
        } else if (dict_is_delim(q, end)) {
            break;
        }
        q++;
    }
    return (size_t)(q - p);
}

/* Reads a "string" at P->p (on the quote) into a new allocation. */
char *dict_lex_string(Parser *P)
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
            dict_perr(P, P->line, "NUL byte inside a string");
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
        dict_perr(P, line0, "unterminated string");
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
int dict_lex_number(Parser *P, double *x, int *is_int, size_t *len)
{
    char c = *P->p;
    if (!(dict_is_digit(c) || c == '-' || c == '+' || c == '.')) return 0;
    size_t n = foam_parse_number(P->p, P->end, x, is_int);
    if (n == 0 || !dict_is_delim(P->p + n, P->end)) return 0;
    if (!isfinite(*x)) return dict_perr(P, P->line, "number '%.*s' is out of range", (int)(n > 40 ? 40 : n), P->p);
    *len = n;
    P->p += n;
    return 1;
}
