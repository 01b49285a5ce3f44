/*
** test_props.c: constant/granularProperties and constant/g (fv/props.h):
** the values read; every mistake stops with file and line.
*/
#include "props.h"
#include "test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define HEADER "FoamFile { version 2.0; format ascii; class dictionary; object granularProperties; }\n"
#define GHEAD "FoamFile { version 2.0; format ascii; class uniformDimensionedVectorField; object g; }\n"

static int parse(GranularProps *p, const char *props, const char *g, Err *e)
{
    Dict *d = dict_parse(props, strlen(props), "granularProperties", e), *gd = NULL;
    if (!d) return -1;
    if (g && !(gd = dict_parse(g, strlen(g), "g", e))) {
        dict_free(d);
        return -1;
    }
    int rc = props_parse(p, d, gd, e);
    dict_free(d);
    if (gd) dict_free(gd);
    return rc;
}

TEST(newtonian)
{
    GranularProps p;
    Err e;
    EXPECT(parse(&p, HEADER "model Newtonian;\nNewtonianCoeffs { mu 0.25; RsT 6; }\n",
                 GHEAD "dimensions [0 1 -2 0 0 0 0];\nvalue (0 -9.81 0);\n", &e) == 0,
           "%s", e.msg);
    EXPECT(p.model == MODEL_NEWTONIAN, "model %d", p.model);
    NEAR(p.mu, 0.25, 0);
    NEAR(p.RsT, 6, 0);
    NEAR(p.g[1], -9.81, 0);
    EXPECT(parse(&p, HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 2; }\n", NULL, &e) == 0, "%s", e.msg);
    NEAR(p.g[0] + p.g[1] + p.g[2], 0, 0);
    /* units words work as in fields */
    EXPECT(parse(&p, HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 2; }\n",
                 GHEAD "dimensions [m s^-2];\nvalue (1 2 3);\n", &e) == 0,
           "%s", e.msg);
    NEAR(p.g[2], 3, 0);
}

static void bad(const char *props, const char *g, const char *want)
{
    GranularProps p;
    Err e;
    int rc = parse(&p, props, g, &e);
    EXPECT(rc != 0, "accepted; wanted \"%s\"", want);
    if (rc) EXPECT(strstr(e.msg, want) != NULL, "message \"%s\", wanted \"%s\"", e.msg, want);
}

TEST(mistakes)
{
    bad(HEADER "model Newtonain;\nNewtonianCoeffs { mu 1; RsT 6; }\n", NULL, "granularProperties:2:");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 6; }\nmdoel x;\n", NULL, "did you mean 'model'");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; }\n", NULL, "RsT");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs {\n mu -1;\n RsT 6; }\n", NULL, "granularProperties:4: mu must be positive");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 6; nu 3; }\n", NULL, "unknown keyword 'nu'");
    bad(HEADER "NewtonianCoeffs { mu 1; RsT 6; }\n", NULL, "missing keyword 'model'");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 6; }\n", GHEAD "dimensions [0 1 -1 0 0 0 0];\nvalue (0 -9.81 0);\n",
        "g:2: gravity must have the dimensions of an acceleration");
    bad(HEADER "model Newtonian;\nNewtonianCoeffs { mu 1; RsT 6; }\n", GHEAD "dimensions [0 1 -2 0 0 0 0];\nvalue (0 -9.81);\n",
        "g:3:");
}

/* model granular: the coefficients, the defaults, epsilon0 from a grain
   (eq. 2.24), and its mistakes with file:line. */
TEST(granular)
{
    GranularProps p;
    Err e;
    EXPECT(parse(&p, HEADER "model granular;\ngranularCoeffs { eta0 0.00102573; lambda0 0.00034; epsilon0 216.649; "
                            "cMax 0.8; c0 0.3; T0 0.5; }\n",
                 NULL, &e) == 0,
           "%s", e.msg);
    EXPECT(p.model == MODEL_GRANULAR, "model %d", p.model);
    NEAR(p.k.eta0, 0.00102573, 0);
    NEAR(p.k.eps0, 216.649, 0);
    NEAR(p.k.cmax, 0.8, 0);
    NEAR(p.k.c0, 0.3, 0);
    NEAR(p.k.T0, 0.5, 0);
    NEAR(p.k.KT, 2.0 / 3.0, 0);
    NEAR(p.dc, 1e-6, 0);
    NEAR(p.Tmin, 1e-12, 0);
    NEAR(p.cmin, 1e-8, 0);
    EXPECT(!p.freezeT, "freezeT %d", p.freezeT);
    EXPECT(parse(&p, HEADER "model granular;\ngranularCoeffs { eta0 1e-3; lambda0 1e-3; grainDiameter 1e-3; restitution 0.9; "
                            "cMax 0.64; KT 1.5; freezeT yes; }\n",
                 NULL, &e) == 0,
           "%s", e.msg);
    NEAR(p.k.eps0, closure_eps0_from_grain(1e-3, 0.9), 0);
    EXPECT(p.k.eps0 > 0, "eps0 %g", p.k.eps0);
    NEAR(p.k.KT, 1.5, 0);
    NEAR(p.k.c0, 0, 0);
    EXPECT(p.freezeT, "freezeT %d", p.freezeT);
    const char *G = HEADER "model granular;\n";
    char buf[512];
    static const char *const cases[][2] = {
        {"granularCoeffs { eta0 1; lambda0 1; epsilon0 1; }", "cMax"},
        {"granularCoeffs { eta0 1; lambda0 1; cMax 0.6; }", "missing epsilon0"},
        {"granularCoeffs { eta0 1; lambda0 1; epsilon0 1; cMax 1.2; }", "cMax must be in (0, 1]"},
        {"granularCoeffs { eta0 1; lambda0 1; epsilon0 1; cMax 0.6; c0 0.6; }", "c0 must be below cMax"},
        {"granularCoeffs { eta0 1; lambda0 1; grainDiameter 1; restitution 1.5; cMax 0.6; }", "restitution must be in"},
        {"granularCoeffs { eta0 -1; lambda0 1; epsilon0 1; cMax 0.6; }", "eta0 must be in"},
        {"granularCoeffs { eta0 1; lambda0 1; epsilon0 1; cMax 0.6; KT 0; }", "KT must be in"},
        {"granularCoeffs { eta0 1; lambda0 1; epsilon0 1; cMax 0.6; mu 3; }", "unknown keyword 'mu'"},
        {"NewtonianCoeffs { mu 1; RsT 6; }", "granularCoeffs"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(buf, sizeof buf, "%s%s\n", G, cases[i][0]);
        bad(buf, NULL, cases[i][1]);
    }
}

/* From a case directory: constant/g is optional, granularProperties not. */
TEST(case_files)
{
    char dir[] = "/tmp/kiesel-props.XXXXXX", path[256];
    EXPECT(mkdtemp(dir) != NULL, "mkdtemp");
    snprintf(path, sizeof path, "%s/constant", dir);
    mkdir(path, 0755);
    GranularProps p;
    Err e;
    EXPECT(props_read(&p, dir, &e) != 0 && strstr(e.msg, "granularProperties") != NULL, "no file: %s", e.msg);
    snprintf(path, sizeof path, "%s/constant/granularProperties", dir);
    FILE *f = fopen(path, "w");
    fputs(HEADER "model Newtonian;\nNewtonianCoeffs { mu 0.5; RsT 6; }\n", f);
    fclose(f);
    EXPECT(props_read(&p, dir, &e) == 0, "%s", e.msg);
    NEAR(p.mu, 0.5, 0);
    NEAR(p.g[1], 0, 0);
    snprintf(path, sizeof path, "%s/constant/g", dir);
    f = fopen(path, "w");
    fputs(GHEAD "dimensions [0 1 -2 0 0 0 0];\nvalue (0 0 -1);\n", f);
    fclose(f);
    EXPECT(props_read(&p, dir, &e) == 0, "%s", e.msg);
    NEAR(p.g[2], -1, 0);
    unlink(path);
    snprintf(path, sizeof path, "%s/constant/granularProperties", dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/constant", dir);
    rmdir(path);
    rmdir(dir);
}

int main(void)
{
    RUN(case_files);
    RUN(newtonian);
    RUN(granular);
    RUN(mistakes);
    return test_summary();
}
