/*
** test_foam.c: number formatting and parsing exactness, headers, lists.
*/
#include "foam.h"
#include "buf.h"

#include "test.h"

#include <stdint.h>

/* xorshift64*: a deterministic generator, so failures reproduce. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint64_t rnd(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 2685821657736338717ull;
}

/* A finite double with random bits: all exponents, subnormals, signs. */
static double rnd_double(void)
{
    for (;;) {
        uint64_t u = rnd();
        double x;
        memcpy(&x, &u, sizeof x);
        if (isfinite(x)) return x;
    }
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* foam_parse_number agrees with strtod on value bits and consumed length. */
static int check_parse(const char *s, char *why, size_t nwhy)
{
    char *endp;
    double ref = strtod(s, &endp);
    double x = 12345;
    int is_int = -1;
    size_t len = foam_parse_number(s, s + strlen(s), &x, &is_int);
    if (len != (size_t)(endp - s)) {
        snprintf(why, nwhy, "'%s': consumed %zu, strtod %zu", s, len, (size_t)(endp - s));
        return 0;
    }
    if (len && !same_bits(x, ref)) {
        snprintf(why, nwhy, "'%s': got %.17g, strtod %.17g", s, x, ref);
        return 0;
    }
    return 1;
}

TEST(parse_matches_strtod_random)
{
    char s[64], why[200];
    long bad = 0, n = 0;
    for (int i = 0; i < 1000000 && !bad; i++) {
        double x = rnd_double();
        /* Three printings: full precision, short (so long mantissas are
           rounded into the fast path), and our shortest form. */
        snprintf(s, sizeof s, "%.17g", x);
        if (!check_parse(s, why, sizeof why)) bad++;
        snprintf(s, sizeof s, "%.6g", x);
        if (!check_parse(s, why, sizeof why)) bad++;
        foam_fmt_double(s, x, 0);
        if (!check_parse(s, why, sizeof why)) bad++;
        n += 3;
    }
    EXPECT(bad == 0, "%s", why);
    EXPECT(n == 3000000, "n = %ld", n);
}

TEST(parse_matches_strtod_moderate)
{
    /* Values of the size that fields hold: mostly the fast path. */
    char s[64], why[200];
    int bad = 0;
    for (int i = 0; i < 300000 && !bad; i++) {
        double x = ((double)(rnd() >> 11) / 9007199254740992.0 - 0.5) * pow(10, (int)(rnd() % 13) - 6);
        snprintf(s, sizeof s, "%.*g", 1 + (int)(rnd() % 17), x);
        if (!check_parse(s, why, sizeof why)) bad++;
        snprintf(s, sizeof s, "%.*e", (int)(rnd() % 20), x);
        if (!check_parse(s, why, sizeof why)) bad++;
    }
    EXPECT(!bad, "%s", why);
}

TEST(parse_forms)
{
    static const char *forms[] = {
        "0", "-0", "+0", "1", "-1", "+7", "0.5", ".5", "5.", "-.5", "1e5", "1E-5", "1e+5", "1e",
        "1e+", "1.5e", "2.e3", "00012", "0.000", "123456789012345678901234567890",
        "0.1234567890123456789012345", "1e308", "1e309", "-1e400", "1e-320", "4.9e-324",
        "2.2250738585072011e-308", "9007199254740993", "9007199254740992", "18446744073709551617",
        "1e22", "1e23", "3.14159265358979323846", "1e-22", "123e-22", "7e-10", "1.7976931348623157e308",
        "0e99999999999", "1e-99999999999", ".", "-", "+", "e5", "-e", ".e1", "1.2.3", "12abc",
        NULL};
    char why[200] = "";
    int ok = 1;
    for (int i = 0; forms[i] && ok; i++) ok = check_parse(forms[i], why, sizeof why);
    EXPECT(ok, "%s", why);
}

TEST(parse_is_int_and_bounds)
{
    double x = 0;
    int is_int = 0;
    EXPECT(foam_parse_number("42", (const char *)"42" + 2, &x, &is_int) == 2 && is_int && x == 42,
           "42: x %g is_int %d", x, is_int);
    EXPECT(foam_parse_number("-3;", (const char *)"-3;" + 3, &x, &is_int) == 2 && is_int && x == -3,
           "-3");
    foam_parse_number("4.0", (const char *)"4.0" + 3, &x, &is_int);
    EXPECT(!is_int && x == 4, "4.0 is_int %d", is_int);
    foam_parse_number("4e0", (const char *)"4e0" + 3, &x, &is_int);
    EXPECT(!is_int, "4e0 is_int");
    /* The end bound is respected: no NUL needed. */
    const char txt[] = "12345";
    size_t n = foam_parse_number(txt, txt + 3, &x, &is_int);
    EXPECT(n == 3 && x == 123, "bounded: n %zu x %g", n, x);
    const char ex[] = "1e57";
    n = foam_parse_number(ex, ex + 2, &x, &is_int);
    EXPECT(n == 1 && x == 1, "'1e' bounded: n %zu x %g", n, x);
    EXPECT(foam_parse_number("abc", (const char *)"abc" + 3, &x, &is_int) == 0, "abc is no number");
    EXPECT(foam_parse_number("nan", (const char *)"nan" + 3, &x, &is_int) == 0, "nan is a word");
    EXPECT(foam_parse_number("inf", (const char *)"inf" + 3, &x, &is_int) == 0, "inf is a word");
    n = foam_parse_number("0x10", (const char *)"0x10" + 4, &x, &is_int);
    EXPECT(n == 1 && x == 0, "no hex floats: n %zu x %g", n, x);
    n = foam_parse_number(" 1", (const char *)" 1" + 2, &x, &is_int);
    EXPECT(n == 0, "no leading blanks");
}

/* Significant digits of a %g-style string (sign, point, exponent,
   leading and trailing zeros excluded). */
static int sig_digits(const char *s)
{
    char d[40];
    int n = 0;
    for (const char *c = s; *c && *c != 'e'; c++)
        if (*c >= '0' && *c <= '9' && (n || *c != '0')) d[n++] = *c;
    while (n > 0 && d[n - 1] == '0') n--;
    return n;
}

TEST(fmt_shortest_round_trip)
{
    char s[40], t[40];
    int bad = 0;
    double badx = 0;
    for (int i = 0; i < 100000 && !bad; i++) {
        double x = i % 2 ? rnd_double() : (double)(int64_t)(rnd() >> (rnd() % 64)) * pow(10, (int)(rnd() % 9) - 8);
        int n = foam_fmt_double(s, x, 0);
        if (n <= 0 || n > 31 || (size_t)n != strlen(s) || !same_bits(strtod(s, NULL), x)) { bad++; badx = x; }
        /* the fewest digits that round-trip, found by brute force */
        int p = 1;
        for (; p <= 17; p++) {
            snprintf(t, sizeof t, "%.*g", p, x);
            if (same_bits(strtod(t, NULL), x)) break;
        }
        /* Subnormals have fewer than 15 significant digits of precision,
           so there "%.15g" is exact but not the shortest: skip them. */
        if (fabs(x) >= 2.2250738585072014e-308 && sig_digits(s) != sig_digits(t)) { bad++; badx = x; }
    }
    EXPECT(bad == 0, "%d failures, e.g. %.17g", bad, badx);
}

TEST(fmt_examples)
{
    static const struct { double x; const char *s; } ex[] = {
        {0.005, "0.005"}, {0.1, "0.1"}, {1.0 / 3.0, "0.3333333333333333"}, {0, "0"}, {-0.0, "-0"},
        {1, "1"}, {-20, "-20"}, {1e15, "1e+15"}, {123456789012345.0, "123456789012345"},
        {0.1 + 0.2, "0.30000000000000004"}, {1e-300, "1e-300"}, {2.5e-5, "2.5e-05"},
        {5e-324, "4.94065645841247e-324"}, {1.7976931348623157e308, "1.7976931348623157e+308"},
        {100.5, "100.5"}, {-1e14, "-100000000000000"}};
    char s[40];
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        foam_fmt_double(s, ex[i].x, 0);
        EXPECT(strcmp(s, ex[i].s) == 0, "%.17g -> '%s', expected '%s'", ex[i].x, s, ex[i].s);
    }
    foam_fmt_double(s, 1.0 / 3.0, 6);
    EXPECT(strcmp(s, "0.333333") == 0, "precision 6: '%s'", s);
    foam_fmt_double(s, 0.5, 6);
    EXPECT(strcmp(s, "0.5") == 0, "precision 6: '%s'", s);
}

TEST(header_layout)
{
    Buf b;
    buf_init(&b);
    foam_header(&b, "volScalarField", "0.5", "p", 0, NULL);
    CONTAINS(b.p, "| =========                 |");
    CONTAINS(b.p, "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
                  "    class       volScalarField;\n    location    \"0.5\";\n"
                  "    object      p;\n}\n// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n");
    EXPECT(!strstr(b.p, "arch"), "ascii header has no arch");
    buf_clear(&b);
    foam_header(&b, "labelList", NULL, "owner", 1, "nPoints:8 nCells:1");
    CONTAINS(b.p, "    format      binary;\n    arch        \"LSB;label=32;scalar=64\";\n"
                  "    class       labelList;\n    note        \"nPoints:8 nCells:1\";\n"
                  "    object      owner;\n}\n");
    EXPECT(!strstr(b.p, "location"), "no location");
    buf_clear(&b);
    foam_footer(&b);
    EXPECT(strcmp(b.p, "\n// ************************************************************************* //\n") == 0,
           "footer '%s'", b.p);
    buf_free(&b);
}

TEST(ascii_lists)
{
    Buf b;
    buf_init(&b);
    const double v[] = {0, 0.005, -1, 1e-20, 2, 3};
    foam_put_scalars(&b, v, 2, 3, 0, 0);
    EXPECT(strcmp(b.p, "2\n(\n(0 0.005 -1)\n(1e-20 2 3)\n)\n") == 0, "vectors '%s'", b.p);
    buf_clear(&b);
    foam_put_scalars(&b, v, 3, 1, 0, 0);
    EXPECT(strcmp(b.p, "3\n(\n0\n0.005\n-1\n)\n") == 0, "scalars '%s'", b.p);
    buf_clear(&b);
    foam_put_scalars(&b, v, 0, 1, 0, 0);
    EXPECT(strcmp(b.p, "0\n(\n)\n") == 0, "empty '%s'", b.p);
    buf_clear(&b);
    const int l[] = {3, -1, 2147483647};
    foam_put_labels(&b, l, 3, 0);
    EXPECT(strcmp(b.p, "3\n(\n3\n-1\n2147483647\n)\n") == 0, "labels '%s'", b.p);
    buf_clear(&b);
    const int off[] = {0, 4, 7}, idx[] = {1, 22, 463, 442, 4, 5, 6};
    foam_put_faces(&b, off, idx, 2, 0);
    EXPECT(strcmp(b.p, "2\n(\n4(1 22 463 442)\n3(4 5 6)\n)\n") == 0, "faces '%s'", b.p);
    buf_free(&b);
}

TEST(binary_lists)
{
    Buf b;
    buf_init(&b);
    const double v[] = {1.5, -2};
    foam_put_scalars(&b, v, 2, 1, 1, 0);
    EXPECT(b.n == 3 + 16 + 2 && memcmp(b.p, "2\n(", 3) == 0 && memcmp(b.p + 19, ")\n", 2) == 0,
           "scalar framing (n %zu)", b.n);
    /* 1.5 = 0x3FF8000000000000 little-endian */
    const unsigned char e15[8] = {0, 0, 0, 0, 0, 0, 0xF8, 0x3F};
    EXPECT(b.n >= 11 && memcmp(b.p + 3, e15, 8) == 0, "1.5 bytes");
    buf_clear(&b);
    const int l[] = {1, -2, 0x01020304};
    foam_put_labels(&b, l, 3, 1);
    const unsigned char el[] = {'3', '\n', '(', 1, 0, 0, 0, 0xFE, 0xFF, 0xFF, 0xFF, 4, 3, 2, 1, ')', '\n'};
    EXPECT(b.n == sizeof el && memcmp(b.p, el, sizeof el) == 0, "label bytes (n %zu)", b.n);
    buf_clear(&b);
    foam_put_labels(&b, l, 0, 1);
    EXPECT(strcmp(b.p, "0\n") == 0, "empty binary '%s'", b.p);
    buf_clear(&b);
    const int off[] = {0, 3}, idx[] = {7, 8, 9};
    foam_put_faces(&b, off, idx, 1, 1);
    EXPECT(b.n == (3 + 8 + 2) + 1 + (3 + 12 + 2), "faceCompactList size %zu", b.n);
    EXPECT(b.n >= 16 && memcmp(b.p + 13, "\n3\n(", 4) == 0, "second list header");
    buf_free(&b);
}

int main(void)
{
    RUN(parse_forms);
    RUN(parse_is_int_and_bounds);
    RUN(parse_matches_strtod_random);
    RUN(parse_matches_strtod_moderate);
    RUN(fmt_examples);
    RUN(fmt_shortest_round_trip);
    RUN(header_layout);
    RUN(ascii_lists);
    RUN(binary_lists);
    return test_summary();
}
