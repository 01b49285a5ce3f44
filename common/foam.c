/*
** foam.c: the pieces every OpenFOAM file shares: banner, FoamFile header,
** separator and footer lines, number formatting, numeric lists in ascii or
** binary, and the number parser the dictionary reader uses.  See foam.h.
**
** Formatting.  foam_fmt_double prints the shortest decimal that strtod
** reads back to the same bits: "%.15g" is exact for every decimal of at
** most 15 significant digits (and %g drops trailing zeros), so trying 15,
** then 16, then 17 digits finds the shortest string among those; 17 always
** round-trips.  Integral values below 1e15 take a short cut through an
** integer conversion, which yields the same text as "%.15g" and is much
** cheaper (fields are full of 0 and 1).
**
** Parsing.  foam_parse_number recognises [+-]digits[.digits][(e|E)[+-]digits]
** (also ".5" and "5."), exactly the decimal forms strtod accepts, and must
** return bit-for-bit what strtod returns.  Fast path (Clinger 1990): when
** the significant digits fit a uint64 that is <= 2^53 and the decimal
** exponent is within +-22, both the mantissa and 10^|e| are exact doubles
** and one IEEE multiplication or division rounds correctly.  Anything else
** (long mantissas, big exponents, subnormals) goes to strtod on a
** NUL-terminated copy of the token, so s need not be terminated.
**
** Binary lists are "N\n(" raw little-endian bytes ")"; labels int32,
** scalars float64, as the arch string "LSB;label=32;scalar=64" declares.
** An empty binary list is written as OpenFOAM does, "0" without brackets
** (its reader skips the block when the size is zero).
*/
#include "foam.h"
#include "mem.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char banner[] =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n"
    "| =========                 |                                                 |\n"
    "| \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox           |\n"
    "|  \\\\    /   O peration     | Version:  v1912                                 |\n"
    "|   \\\\  /    A nd           | Website:  www.openfoam.com                      |\n"
    "|    \\\\/     M anipulation  |                                                 |\n"
    "\\*---------------------------------------------------------------------------*/\n";

/* The "// * * * ... //" line that follows the header. */
static void foam_separator(Buf *b)
{
    buf_puts(b, "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n");
}

void foam_header(Buf *b, const char *cls, const char *location, const char *object,
                 int binary, const char *note)
{
    buf_puts(b, banner);
    buf_puts(b, "FoamFile\n{\n");
    buf_puts(b, "    version     2.0;\n");
    buf_printf(b, "    format      %s;\n", binary ? "binary" : "ascii");
    if (binary) buf_puts(b, "    arch        \"LSB;label=32;scalar=64\";\n");
    buf_printf(b, "    class       %s;\n", cls);
    if (note) buf_printf(b, "    note        \"%s\";\n", note);
    if (location) buf_printf(b, "    location    \"%s\";\n", location);
    buf_printf(b, "    object      %s;\n", object);
    buf_puts(b, "}\n");
    foam_separator(b);
}

void foam_footer(Buf *b)
{
    buf_puts(b, "\n// ************************************************************************* //\n");
}

/* ---- formatting ---- */

/* Decimal digits of an integer, most significant first; returns length. */
static int fmt_int64(char *s, int64_t v)
{
    char tmp[24];
    int k = 0, n = 0;
    uint64_t u = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    do {
        tmp[k++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) s[n++] = '-';
    while (k) s[n++] = tmp[--k];
    s[n] = '\0';
    return n;
}

int foam_fmt_double(char *s, double x, int precision)
{
    if (precision > 0) {
        if (precision > 17) precision = 17;
        return snprintf(s, 32, "%.*g", precision, x);
    }
    if (x == 0) return snprintf(s, 32, "%s", signbit(x) ? "-0" : "0");
    if (fabs(x) < 1e15 && x == (double)(int64_t)x) return fmt_int64(s, (int64_t)x);
    int n = 0;
    for (int p = 15; p <= 17; p++) {
        n = snprintf(s, 32, "%.*g", p, x);
        if (p == 17 || strtod(s, NULL) == x) break;
    }
    return n;
}

void foam_put_double(Buf *b, double x, int precision)
{
    char s[40];
    int n = foam_fmt_double(s, x, precision);
    buf_put(b, s, (size_t)n);
}

static void put_int(Buf *b, int v)
{
    char s[24];
    int n = fmt_int64(s, v);
    buf_put(b, s, (size_t)n);
}

/* ---- binary ---- */

static int host_is_little(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

/* Appends n items of size sz from p as little-endian bytes. */
static void put_le(Buf *b, const void *p, size_t n, size_t sz)
{
    if (host_is_little()) {
        buf_put(b, p, n * sz);
        return;
    }
    buf_reserve(b, n * sz);
    const unsigned char *src = p;
    unsigned char *dst = (unsigned char *)b->p + b->n;
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; k < sz; k++) dst[i * sz + k] = src[i * sz + sz - 1 - k];
    b->n += n * sz;
    b->p[b->n] = '\0';
}

/* "N\n(" bytes ")\n", or "0\n" for an empty list (see the top comment). */
static void put_binary(Buf *b, const void *p, size_t n, size_t sz)
{
    buf_printf(b, "%zu\n", n);
    if (n == 0) return;
    buf_putc(b, '(');
    put_le(b, p, n, sz);
    buf_puts(b, ")\n");
}

/* ---- lists ---- */

void foam_put_scalars(Buf *b, const double *v, size_t n, int width, int binary, int precision)
{
    if (width < 1) width = 1;
    size_t w = (size_t)width;
    if (binary) {
        put_binary(b, v, n, w * sizeof(double));
        return;
    }
    buf_printf(b, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++) {
        const double *x = v + i * w;
        if (w == 1) {
            foam_put_double(b, x[0], precision);
        } else {
            buf_putc(b, '(');
            for (size_t k = 0; k < w; k++) {
                if (k) buf_putc(b, ' ');
                foam_put_double(b, x[k], precision);
            }
            buf_putc(b, ')');
        }
        buf_putc(b, '\n');
    }
    buf_puts(b, ")\n");
}

/* Binary lists need int32 elements whatever sizeof(int) is. */
static void put_binary_ints(Buf *b, const int *v, size_t n)
{
    if (sizeof(int) == sizeof(int32_t)) {
        put_binary(b, v, n, sizeof(int32_t));
        return;
    }
    int32_t *t = MEM_NEW(int32_t, n);
    for (size_t i = 0; i < n; i++) t[i] = (int32_t)v[i];
    put_binary(b, t, n, sizeof(int32_t));
    free(t);
}

void foam_put_labels(Buf *b, const int *v, size_t n, int binary)
{
    if (binary) {
        put_binary_ints(b, v, n);
        return;
    }
    buf_printf(b, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++) {
        put_int(b, v[i]);
        buf_putc(b, '\n');
    }
    buf_puts(b, ")\n");
}

void foam_put_faces(Buf *b, const int *off, const int *idx, size_t n, int binary)
{
    if (binary) {
        put_binary_ints(b, off, n + 1);
        buf_putc(b, '\n');
        put_binary_ints(b, idx, (size_t)off[n]);
        return;
    }
    buf_printf(b, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++) {
        put_int(b, off[i + 1] - off[i]);
        buf_putc(b, '(');
        for (int k = off[i]; k < off[i + 1]; k++) {
            if (k > off[i]) buf_putc(b, ' ');
            put_int(b, idx[k]);
        }
        buf_puts(b, ")\n");
    }
    buf_puts(b, ")\n");
}

/* ---- parsing ---- */

static const double pow10_exact[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* strtod on a NUL-terminated copy of s[0..n). */
static double slow_strtod(const char *s, size_t n)
{
    char small[64];
    char *t = n < sizeof small ? small : mem_alloc(n + 1);
    memcpy(t, s, n);
    t[n] = '\0';
    double x = strtod(t, NULL);
    if (t != small) free(t);
    return x;
}

size_t foam_parse_number(const char *s, const char *end, double *x, int *is_int)
{
    const char *p = s;
    int neg = 0;
    if (p < end && (*p == '+' || *p == '-')) neg = (*p++ == '-');
    uint64_t m = 0;
    int ndig = 0;        /* significant digits accumulated into m */
    int dropped = 0;     /* significant digits beyond what m can hold */
    int exp10 = 0;       /* decimal exponent adjustment from the point */
    int nmant = 0;       /* mantissa digits seen, leading zeros included */
    int integral = 1;
    while (p < end && is_digit(*p)) {
        if (m || *p != '0') {
            if (ndig < 19) { m = m * 10 + (uint64_t)(*p - '0'); ndig++; }
            else { dropped = 1; exp10++; }
        }
        nmant++;
        p++;
    }
    if (p < end && *p == '.') {
        integral = 0;
        p++;
        while (p < end && is_digit(*p)) {
            if (m || *p != '0') {
                if (ndig < 19) { m = m * 10 + (uint64_t)(*p - '0'); ndig++; exp10--; }
                else dropped = 1;
            } else {
                exp10--;
            }
            nmant++;
            p++;
        }
    }
    if (nmant == 0) return 0;
    /* An exponent counts only when digits follow, as strtod requires. */
    if (p < end && (*p == 'e' || *p == 'E')) {
        const char *q = p + 1;
        int eneg = 0;
        if (q < end && (*q == '+' || *q == '-')) eneg = (*q++ == '-');
        if (q < end && is_digit(*q)) {
            long ev = 0;
            while (q < end && is_digit(*q)) {
                if (ev < 100000) ev = ev * 10 + (*q - '0');
                q++;
            }
            exp10 += (int)(eneg ? -ev : ev);
            integral = 0;
            p = q;
        }
    }
    size_t len = (size_t)(p - s);
    *is_int = integral;
    double v;
    if (m == 0 && !dropped)
        v = 0.0;
    else if (!dropped && m <= ((uint64_t)1 << 53) && exp10 >= -22 && exp10 <= 22)
        v = exp10 >= 0 ? (double)m * pow10_exact[exp10] : (double)m / pow10_exact[-exp10];
    else
        v = fabs(slow_strtod(s, len));
    *x = neg ? -v : v;
    return len;
}
