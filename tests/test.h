/*
** test.h: the smallest unit-test harness that does the job.
**
**     TEST(dict_include) { EXPECT(x == 1, "x = %d", x); NEAR(v, 1.0, 1e-14); }
**     int main(void) { RUN(dict_include); return test_summary(); }
**
** Each test case prints one line, "PASS name" or "FAIL name: file:line:
** message" (the first failed expectation); tests/run counts those lines.
** A test program that crashes prints no PASS for its remaining cases and
** exits non-zero, which tests/run counts as a failure.
*/
#ifndef KIESEL_TEST_H
#define KIESEL_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int test_failed_now, test_npass, test_nfail;
static char test_msg[4096];

#define TEST(name) static void test_##name(void)

#define EXPECT(cond, ...)                                                                    \
    do {                                                                                     \
        if (!(cond) && !test_failed_now) {                                                   \
            int k_ = snprintf(test_msg, sizeof test_msg, "%s:%d: ", __FILE__, __LINE__);    \
            snprintf(test_msg + k_, sizeof test_msg - (size_t)k_, __VA_ARGS__);             \
            test_failed_now = 1;                                                             \
        }                                                                                    \
    } while (0)

/* |a - b| <= tol, printing both values on failure. */
#define NEAR(a, b, tol)                                                                      \
    do {                                                                                     \
        double a_ = (a), b_ = (b);                                                           \
        EXPECT(fabs(a_ - b_) <= (tol), "%s = %.17g, expected %.17g (tol %g)", #a, a_, b_,   \
               (double)(tol));                                                               \
    } while (0)

/* Expectation that a string contains a substring. */
#define CONTAINS(s, sub)                                                                     \
    EXPECT((s) && strstr((s), (sub)), "\"%s\" does not contain \"%s\"", (s) ? (s) : "(null)", (sub))

#define RUN(name)                                                                            \
    do {                                                                                     \
        test_failed_now = 0;                                                                 \
        test_##name();                                                                       \
        if (test_failed_now) {                                                               \
            printf("FAIL %s: %s\n", #name, test_msg);                                       \
            test_nfail++;                                                                    \
        } else {                                                                             \
            printf("PASS %s\n", #name);                                                     \
            test_npass++;                                                                    \
        }                                                                                    \
        fflush(stdout);                                                                      \
    } while (0)

static inline int test_summary(void) { return test_nfail ? 1 : 0; }

/* A scratch directory for the test (removed by tests/run afterwards). */
static inline const char *test_tmpdir(void)
{
    const char *d = getenv("KIESEL_TMP");
    return d ? d : "/tmp";
}

#endif
