/*
** test_case.c: the Case and the one controlDict reader behind it: every
** spelling of writeFormat and writeCompression OpenFOAM v1912 accepts
** (Switch words and IOstreamOption's compressed/uncompressed), the same
** output format for grids and fields, binary switching compression off,
** bad values with file:line, endTime/deltaT optional except for solvers,
** the case without a controlDict, paths and times.
*/
#include "test.h"

#include "buf.h"
#include "case.h"
#include "io.h"
#include "mem.h"

static char *scratch_case(const char *name)
{
    char *dir = io_join(test_tmpdir(), name);
    io_rm_rf(dir, NULL);
    char *sys = io_join(dir, "system");
    io_mkdir_p(sys, NULL);
    free(sys);
    return dir;
}

/* head: 7 lines; the body starts on line 8 */
static void control(const char *dir, const char *body)
{
    Buf b;
    buf_init(&b);
    buf_puts(&b, "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
                 "    object controlDict;\n}\n");
    buf_puts(&b, body);
    char *p = io_join(dir, "system/controlDict");
    Err e;
    io_write_atomic(p, b.p, b.n, 0, &e);
    free(p);
    buf_free(&b);
}

/* Opens dir with a controlDict of body; *mw and *fw get the formats. */
static int open_with(const char *dir, const char *body, MeshWriteOpts *mw, FieldWriteOpts *fw, Err *e)
{
    control(dir, body);
    Case c;
    if (case_open(&c, dir, CASE_CONTROL_FORMAT, e)) return -1;
    case_mesh_format(&c, mw);
    case_field_format(&c, fw);
    case_free(&c);
    return 0;
}

TEST(case_compression_words)
{
    char *dir = scratch_case("case_words");
    static const char *const words[][2] = {{"on", "1"},  {"off", "0"},       {"yes", "1"},         {"no", "0"},
                                           {"true", "1"}, {"false", "0"},    {"y", "1"},           {"n", "0"},
                                           {"t", "1"},   {"f", "0"},         {"none", "0"},        {"compressed", "1"},
                                           {"uncompressed", "0"}};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        char body[128];
        snprintf(body, sizeof body, "writeFormat ascii;\nwriteCompression %s;\n", words[i][0]);
        MeshWriteOpts mw = {9, 9};
        FieldWriteOpts fw = {9, 9, 9, NULL};
        Err e;
        int rc = open_with(dir, body, &mw, &fw, &e);
        int want = atoi(words[i][1]);
        EXPECT(rc == 0, "writeCompression %s: %s", words[i][0], e.msg);
        EXPECT(mw.gzip == want && fw.gzip == want, "writeCompression %s: grid %d field %d, want %d", words[i][0],
               mw.gzip, fw.gzip, want);
        EXPECT(mw.binary == 0 && fw.binary == 0, "ascii read as binary");
    }
    free(dir);
}

TEST(case_format_grids_fields_alike)
{
    char *dir = scratch_case("case_format");
    MeshWriteOpts mw;
    FieldWriteOpts fw;
    Err e;
    EXPECT(open_with(dir, "writeFormat binary;\nwriteCompression off;\n", &mw, &fw, &e) == 0, "%s", e.msg);
    EXPECT(mw.binary == 1 && fw.binary == 1 && mw.gzip == 0 && fw.gzip == 0, "binary");
    /* OpenFOAM v1912: "Disabled binary format compression
       (inefficient/ineffective)", for grids and fields alike */
    EXPECT(open_with(dir, "writeFormat binary;\nwriteCompression on;\n", &mw, &fw, &e) == 0, "%s", e.msg);
    EXPECT(mw.binary == 1 && fw.binary == 1 && mw.gzip == 0 && fw.gzip == 0, "binary + on: grid %d/%d field %d/%d",
           mw.binary, mw.gzip, fw.binary, fw.gzip);
    EXPECT(open_with(dir, "writeFormat ascii;\nwriteCompression compressed;\nwritePrecision 9;\n", &mw, &fw, &e) == 0,
           "%s", e.msg);
    EXPECT(mw.binary == 0 && fw.binary == 0 && mw.gzip == 1 && fw.gzip == 1 && fw.precision == 9,
           "ascii + compressed");
    /* endTime and deltaT are a solver's: a grid tool's controlDict may lack them */
    EXPECT(open_with(dir, "application blockGrid;\n", &mw, &fw, &e) == 0, "%s", e.msg);
    EXPECT(mw.binary == 0 && mw.gzip == 0 && fw.precision == 6, "defaults");
    free(dir);
}

TEST(case_bad_values)
{
    char *dir = scratch_case("case_bad");
    MeshWriteOpts mw;
    FieldWriteOpts fw;
    Err e;
    EXPECT(open_with(dir, "writeFormat ascii;\nwriteCompression maybe;\n", &mw, &fw, &e) == -1, "maybe accepted");
    CONTAINS(e.msg, "case_bad/system/controlDict:9:");
    CONTAINS(e.msg, "writeCompression");
    EXPECT(open_with(dir, "writeFormat binery;\n", &mw, &fw, &e) == -1, "binery accepted");
    CONTAINS(e.msg, "case_bad/system/controlDict:8:");
    CONTAINS(e.msg, "binary");
    EXPECT(open_with(dir, "writeFromat binary;\n", &mw, &fw, &e) == -1, "writeFromat accepted");
    CONTAINS(e.msg, "controlDict:8:");
    CONTAINS(e.msg, "did you mean 'writeFormat'");
    EXPECT(open_with(dir, "deltaT 0;\n", &mw, &fw, &e) == -1, "deltaT 0 accepted");
    CONTAINS(e.msg, "controlDict:8: deltaT must be greater than 0");
    /* a solver needs endTime */
    control(dir, "deltaT 0.1;\n");
    Case c;
    EXPECT(case_open(&c, dir, CASE_CONTROL_TIME, &e) == -1, "missing endTime accepted");
    CONTAINS(e.msg, "endTime");
    EXPECT(c.dir == NULL && !c.has_control, "case left open on failure");
    free(dir);
}

TEST(case_without_control)
{
    char *dir = scratch_case("case_none");
    Case c;
    Err e;
    EXPECT(case_open(&c, dir, CASE_CONTROL_FORMAT, &e) == 0, "%s", e.msg);
    EXPECT(!c.has_control, "controlDict invented");
    MeshWriteOpts mw = {9, 9};
    FieldWriteOpts fw = {9, 9, 9, NULL};
    case_mesh_format(&c, &mw);
    case_field_format(&c, &fw);
    EXPECT(mw.binary == 0 && mw.gzip == 0 && fw.binary == 0 && fw.gzip == 0 && fw.precision == 0, "defaults");
    char *p = case_path(&c, "system/cutCellsDict"), *q = io_join(dir, "system/cutCellsDict");
    EXPECT(!strcmp(p, q), "case_path %s", p);
    free(p);
    free(q);
    case_free(&c);
    EXPECT(case_open(&c, dir, CASE_CONTROL_TIME, &e) == -1, "missing controlDict accepted by a solver");
    CONTAINS(e.msg, "case_none/system/controlDict");
    /* a broken controlDict does not stop a tool that does not read it */
    control(dir, "writeFormat {;\n");
    EXPECT(case_open(&c, dir, CASE_NO_CONTROL, &e) == 0, "%s", e.msg);
    case_free(&c);
    char *none = io_join(test_tmpdir(), "case_no_such_dir");
    EXPECT(case_open(&c, none, CASE_NO_CONTROL, &e) == -1, "missing case accepted");
    CONTAINS(e.msg, "case_no_such_dir");
    free(none);
    free(dir);
}

TEST(case_times)
{
    char *dir = scratch_case("case_times");
    const char *names[] = {"0", "0.5", "1", "constant"};
    for (int i = 0; i < 4; i++) {
        char *p = io_join(dir, names[i]);
        io_mkdir_p(p, NULL);
        free(p);
    }
    control(dir, "startFrom startTime;\nstartTime 0.5;\n");
    Case c;
    Err e;
    EXPECT(case_open(&c, dir, CASE_CONTROL_FORMAT, &e) == 0, "%s", e.msg);
    EXPECT(case_pick_times(&c, NULL, 0, 0, &e) == 1 && !strcmp(case_time(&c, 0), "0.5"), "start time");
    EXPECT(case_select_times(&c, NULL, 0, 1, &e) == 2 && !strcmp(case_time(&c, 1), "1"), "-noZero");
    EXPECT(case_select_times(&c, "0:0.5", 0, 0, &e) == 2 && !strcmp(case_time(&c, 0), "0"), "-time 0:0.5");
    case_free(&c);
    free(dir);
}

int main(void)
{
    RUN(case_compression_words);
    RUN(case_format_grids_fields_alike);
    RUN(case_bad_values);
    RUN(case_without_control);
    RUN(case_times);
    return test_summary();
}
