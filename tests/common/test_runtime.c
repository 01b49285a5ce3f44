/*
** test_runtime.c: controlDict defaults and errors, re-reading, time names,
** time directories, -time selection, uniform/time, purgeWrite.
*/
#include "test.h"

#include "buf.h"
#include "io.h"
#include "mem.h"
#include "runtime.h"

#include <fcntl.h>
#include <sys/stat.h>

static char *scratch_case(const char *name)
{
    char *dir = io_join(test_tmpdir(), name);
    io_rm_rf(dir, NULL);
    char *sys = io_join(dir, "system");
    io_mkdir_p(sys, NULL);
    free(sys);
    return dir;
}

static void write_control(const char *dir, const char *text)
{
    char *p = io_join(dir, "system/controlDict");
    Err e;
    io_write_atomic(p, text, strlen(text), 0, &e);
    free(p);
}

static void set_mtime(const char *dir, time_t sec)
{
    char *p = io_join(dir, "system/controlDict");
    struct timespec ts[2] = {{sec, 0}, {sec, 0}};
    utimensat(AT_FDCWD, p, ts, 0);
    free(p);
}

static const char *head = "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
                          "    object controlDict;\n}\n";

static void control(const char *dir, const char *body)
{
    Buf b;
    buf_init(&b);
    buf_puts(&b, head);
    buf_puts(&b, body);
    buf_putc(&b, '\0');
    write_control(dir, b.p);
    buf_free(&b);
}

TEST(control_defaults)
{
    char *dir = scratch_case("rt_defaults");
    control(dir, "endTime 2.5;\ndeltaT 0.01;\n");
    Control c;
    Err e;
    int rc = runtime_read_control(&c, dir, &e);
    EXPECT(rc == 0, "%s", e.msg);
    EXPECT(c.startFrom == START_START && c.startTime == 0 && c.stopAt == STOP_END, "start/stop");
    EXPECT(c.endTime == 2.5 && c.deltaT == 0.01, "endTime %g deltaT %g", c.endTime, c.deltaT);
    EXPECT(c.writeControl == WRITE_TIMESTEP && c.writeInterval == 1 && c.purgeWrite == 0, "write control");
    EXPECT(c.writeVTK == 1, "writeVTK defaults to yes");
    EXPECT(c.writeBinary == 0 && c.writeCompression == 0 && c.writePrecision == 6, "write format");
    EXPECT(c.timeFormat == TIMEFMT_GENERAL && c.timePrecision == 6, "time format");
    EXPECT(c.runTimeModifiable == 1 && c.adjustTimeStep == 0 && c.maxCo == 1 && c.maxDeltaT == 1e15,
           "adjust: %d %d %g %g", c.runTimeModifiable, c.adjustTimeStep, c.maxCo, c.maxDeltaT);
    CONTAINS(c.path, "rt_defaults/system/controlDict");
    runtime_free_control(&c);
    free(dir);
}

TEST(control_cavity)
{
    char *dir = scratch_case("rt_cavity");
    control(dir, "application icoFoam;\nstartFrom latestTime;\nstartTime 0.1;\nstopAt writeNow;\n"
                 "endTime 0.5;\ndeltaT 0.005;\nwriteControl adjustableRunTime;\nwriteInterval 20;\n"
                 "purgeWrite 3;\nwriteVTK no;\nwriteFormat binary;\nwritePrecision 8;\nwriteCompression on;\n"
                 "timeFormat fixed;\ntimePrecision 4;\nrunTimeModifiable yes;\nadjustTimeStep on;\n"
                 "maxCo 0.9;\nmaxDeltaT 1;\nlibs (sampling);\nfunctions { probes { type probes; } }\n");
    Control c;
    Err e;
    int rc = runtime_read_control(&c, dir, &e);
    EXPECT(rc == 0, "%s", e.msg);
    EXPECT(c.startFrom == START_LATEST && c.startTime == 0.1 && c.stopAt == STOP_WRITENOW, "start/stop");
    EXPECT(c.writeControl == WRITE_ADJUSTABLE && c.writeInterval == 20 && c.purgeWrite == 3, "write control");
    EXPECT(c.writeVTK == 0, "writeVTK no read as %d", c.writeVTK);
    /* compression is off for binary files, as in OpenFOAM v1912 */
    EXPECT(c.writeBinary == 1 && c.writeCompression == 0 && c.writePrecision == 8, "format %d %d %d",
           c.writeBinary, c.writeCompression, c.writePrecision);
    EXPECT(c.timeFormat == TIMEFMT_FIXED && c.timePrecision == 4, "time format");
    EXPECT(c.adjustTimeStep == 1 && c.maxCo == 0.9 && c.maxDeltaT == 1, "adjust");
    runtime_free_control(&c);
    const char *words[][2] = {{"compressed", "1"}, {"uncompressed", "0"}, {"on", "1"},
                              {"yes", "1"},        {"no", "0"},           {"off", "0"}};
    for (int i = 0; i < 6; i++) {
        char body[200];
        snprintf(body, sizeof body, "endTime 1;\ndeltaT 1;\nwriteCompression %s;\n", words[i][0]);
        control(dir, body);
        rc = runtime_read_control(&c, dir, &e);
        EXPECT(rc == 0 && c.writeCompression == atoi(words[i][1]), "writeCompression %s -> %d (%s)", words[i][0],
               c.writeCompression, rc ? e.msg : "");
        runtime_free_control(&c);
    }
    free(dir);
}

TEST(control_errors)
{
    char *dir = scratch_case("rt_errors");
    Control c;
    Err e;
    /* head: 7 lines; the body starts on line 8 */
    control(dir, "endTme 1;\ndeltaT 0.1;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "endTme accepted");
    CONTAINS(e.msg, "controlDict:8:");
    CONTAINS(e.msg, "'endTme'");
    CONTAINS(e.msg, "did you mean 'endTime'");
    EXPECT(c.path == NULL, "path set on failure");
    control(dir, "deltaT 0.1;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "missing endTime accepted");
    CONTAINS(e.msg, "endTime");
    control(dir, "endTime 1;\ndeltaT 0;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "deltaT 0 accepted");
    CONTAINS(e.msg, "controlDict:9: deltaT must be greater than 0, found 0");
    control(dir, "endTime 1;\ndeltaT 0.1;\nwriteFormat binery;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "binery accepted");
    CONTAINS(e.msg, "controlDict:10:");
    CONTAINS(e.msg, "binary");
    control(dir, "endTime 1;\ndeltaT 0.1;\npurgeWrite -1;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "purgeWrite -1 accepted");
    CONTAINS(e.msg, "purgeWrite must be at least 0, found -1");
    control(dir, "endTime 1;\ndeltaT 0.1;\nrunTimeModifiable perhaps;\n");
    EXPECT(runtime_read_control(&c, dir, &e) == -1, "perhaps accepted");
    CONTAINS(e.msg, "runTimeModifiable");
    char *none = io_join(test_tmpdir(), "rt_no_case");
    EXPECT(runtime_read_control(&c, none, &e) == -1, "missing controlDict accepted");
    CONTAINS(e.msg, "rt_no_case/system/controlDict");
    free(none);
    free(dir);
}

TEST(control_reread)
{
    char *dir = scratch_case("rt_reread");
    control(dir, "endTime 1;\ndeltaT 0.1;\n");
    set_mtime(dir, 1000000000);
    Control c;
    Err e;
    EXPECT(runtime_read_control(&c, dir, &e) == 0, "%s", e.msg);
    EXPECT(runtime_reread(&c, &e) == 0, "unchanged file re-read");
    control(dir, "endTime 2;\ndeltaT 0.05;\n");
    set_mtime(dir, 1000000000);
    EXPECT(runtime_reread(&c, &e) == 0, "same mtime re-read");
    EXPECT(c.endTime == 1, "endTime %g", c.endTime);
    set_mtime(dir, 1000000010);
    EXPECT(runtime_reread(&c, &e) == 1, "changed file not re-read");
    EXPECT(c.endTime == 2 && c.deltaT == 0.05, "endTime %g deltaT %g", c.endTime, c.deltaT);
    EXPECT(runtime_reread(&c, &e) == 0, "second re-read");
    /* a typo keeps the old values and is reported once */
    control(dir, "endTime 3;\ndeltaT 0.05;\nwriteIntervall 5;\n");
    set_mtime(dir, 1000000020);
    EXPECT(runtime_reread(&c, &e) == -1, "typo accepted");
    CONTAINS(e.msg, "did you mean 'writeInterval'");
    EXPECT(c.endTime == 2 && c.path != NULL, "old values lost: endTime %g", c.endTime);
    EXPECT(runtime_reread(&c, &e) == 0, "same error reported twice");
    /* with runTimeModifiable off nothing is re-read */
    control(dir, "endTime 4;\ndeltaT 0.05;\nrunTimeModifiable false;\n");
    set_mtime(dir, 1000000030);
    EXPECT(runtime_reread(&c, &e) == 1 && c.endTime == 4 && c.runTimeModifiable == 0, "switch off");
    control(dir, "endTime 5;\ndeltaT 0.05;\n");
    set_mtime(dir, 1000000040);
    EXPECT(runtime_reread(&c, &e) == 0 && c.endTime == 4, "re-read although runTimeModifiable off");
    runtime_free_control(&c);
    free(dir);
}

TEST(time_names)
{
    char s[64];
    Control c;
    memset(&c, 0, sizeof c);
    c.timeFormat = TIMEFMT_GENERAL;
    c.timePrecision = 6;
    struct {
        double t;
        const char *want;
    } g[] = {{0.1, "0.1"},        {1e-5, "1e-05"},        {100, "100"},      {0.043813571, "0.0438136"},
             {-0.0, "0"},          {0.1 + 0.2, "0.3"},     {0.05, "0.05"},    {1234567, "1.23457e+06"},
             {2.5e-7, "2.5e-07"}, {0.30000049, "0.3"}};
    for (size_t i = 0; i < sizeof g / sizeof g[0]; i++) {
        runtime_time_name(&c, g[i].t, s);
        EXPECT(strcmp(s, g[i].want) == 0, "general %.17g -> '%s', expected '%s'", g[i].t, s, g[i].want);
    }
    c.timePrecision = 9;
    runtime_time_name(&c, 0.043813571, s);
    EXPECT(strcmp(s, "0.043813571") == 0, "precision 9: %s", s);
    c.timeFormat = TIMEFMT_FIXED;
    c.timePrecision = 6;
    runtime_time_name(&c, 0.1, s);
    EXPECT(strcmp(s, "0.100000") == 0, "fixed: %s", s);
    c.timeFormat = TIMEFMT_SCIENTIFIC;
    c.timePrecision = 3;
    runtime_time_name(&c, 0.1, s);
    EXPECT(strcmp(s, "1.000e-01") == 0, "scientific: %s", s);
    runtime_time_name(NULL, 0.25, s);
    EXPECT(strcmp(s, "0.25") == 0, "NULL control: %s", s);
}

static char *times_case(void)
{
    char *dir = scratch_case("rt_times");
    const char *dirs[] = {"0", "0.1", "1e-05", "0.05", "10", "2", "constant", "0.orig", "1e-05x", "nan", "0x10"};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        char *p = io_join(dir, dirs[i]);
        io_mkdir_p(p, NULL);
        free(p);
    }
    char *f = io_join(dir, "3");
    Err e;
    io_write_atomic(f, "x", 1, 0, &e); /* a file, not a directory */
    free(f);
    return dir;
}

static void names_of(const TimeDir *t, int n, char *out, size_t cap)
{
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        if (i) strncat(out, " ", cap - strlen(out) - 1);
        strncat(out, t[i].name, cap - strlen(out) - 1);
    }
}

static int select_names(const char *dir, const char *spec, int latest, int nozero, char *out, size_t cap, Err *e)
{
    TimeDir *t;
    int n = runtime_list_times(dir, &t, e);
    if (n < 0) return -1;
    int k = runtime_select(t, n, spec, latest, nozero, e);
    if (k >= 0) names_of(t, k, out, cap);
    runtime_free_times(t, n);
    return k;
}

TEST(list_times)
{
    char *dir = times_case();
    TimeDir *t;
    Err e;
    int n = runtime_list_times(dir, &t, &e);
    char s[256];
    names_of(t, n, s, sizeof s);
    EXPECT(n == 6 && strcmp(s, "0 1e-05 0.05 0.1 2 10") == 0, "times: %d '%s'", n, s);
    EXPECT(n == 6 && t[1].value == 1e-5 && t[5].value == 10, "values");
    runtime_free_times(t, n);
    char *none = io_join(dir, "missing");
    EXPECT(runtime_list_times(none, &t, &e) == -1, "missing case listed");
    free(none);
    free(dir);
}

TEST(select_times)
{
    char *dir = times_case();
    Err e;
    char s[256];
    struct {
        const char *spec;
        int latest, nozero;
        const char *want;
    } c[] = {{NULL, 0, 0, "0 1e-05 0.05 0.1 2 10"},
             {"0.1", 0, 0, "0.1"},
             {"0.1,10", 0, 0, "0.1 10"},
             {"0.1 10", 0, 0, "0.1 10"},
             {"0.05:2", 0, 0, "0.05 0.1 2"},
             {":0.05", 0, 0, "0 1e-05 0.05"},
             {"2:", 0, 0, "2 10"},
             {"0.1000000000001", 0, 0, "0.1"},
             {"0.10001", 0, 0, ""},
             {"1e-5", 0, 0, "1e-05"},
             {NULL, 1, 0, "10"},
             {"0.1", 1, 0, "0.1 10"},
             {NULL, 0, 1, "1e-05 0.05 0.1 2 10"},
             {":0.05", 0, 1, "1e-05 0.05"},
             {"0", 0, 1, ""}};
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        int k = select_names(dir, c[i].spec, c[i].latest, c[i].nozero, s, sizeof s, &e);
        EXPECT(k >= 0 && strcmp(s, c[i].want) == 0, "-time '%s' latest %d noZero %d: '%s', expected '%s'",
               c[i].spec ? c[i].spec : "(none)", c[i].latest, c[i].nozero, k >= 0 ? s : e.msg, c[i].want);
    }
    const char *bad[] = {"abc", "1:2:3", "0.1,,0.2", "", ":", "0.1,", "1e999", "0.1:x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int k = select_names(dir, bad[i], 0, 0, s, sizeof s, &e);
        EXPECT(k == -1, "-time '%s' accepted", bad[i]);
        CONTAINS(e.msg, "-time");
    }
    select_names(dir, "0.1,abc", 0, 0, s, sizeof s, &e);
    CONTAINS(e.msg, "'abc' is not a time or a range");
    free(dir);
}

TEST(uniform_time_file)
{
    char *dir = scratch_case("rt_uniform");
    Err e;
    EXPECT(runtime_write_uniform_time(dir, "0.01", 0.01, 2, 0.005, 0.005, &e) == 0, "%s", e.msg);
    char *p = io_join(dir, "0.01/uniform/time");
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0, "%s", e.msg);
    buf_putc(&b, '\0');
    /* what OpenFOAM v1912's icoFoam writes for the cavity at 0.01 */
    const char *want = "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n"
                       "    location    \"0.01/uniform\";\n    object      time;\n}\n"
                       "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n"
                       "value           0.0100000000000000002;\n\nname            \"0.01\";\n\n"
                       "index           2;\n\ndeltaT          0.005;\n\ndeltaT0         0.005;\n\n\n"
                       "// ************************************************************************* //\n";
    const char *s = b.p ? strstr(b.p, "FoamFile") : NULL;
    EXPECT(s && strcmp(s, want) == 0, "uniform/time:\n%s", s ? s : "(none)");
    buf_free(&b);
    free(p);
    EXPECT(runtime_read_index(dir, "0.01") == 2, "index %ld", runtime_read_index(dir, "0.01"));
    EXPECT(runtime_write_uniform_time(dir, "0.3", 0.1 + 0.2, 123456, 1e-3, 2e-3, &e) == 0, "%s", e.msg);
    EXPECT(runtime_read_index(dir, "0.3") == 123456, "index %ld", runtime_read_index(dir, "0.3"));
    p = io_join(dir, "0.3/uniform/time");
    buf_init(&b);
    io_read_file(p, &b, NULL, &e);
    buf_putc(&b, '\0');
    CONTAINS(b.p, "value           0.300000000000000044;\n");
    /* 18 digits restore the double exactly */
    EXPECT(strtod("0.300000000000000044", NULL) == 0.1 + 0.2, "18 digits not exact");
    buf_free(&b);
    free(p);
    EXPECT(runtime_read_index(dir, "7") == 0, "absent index not 0");
    free(dir);
}

TEST(purge)
{
    char *dir = scratch_case("rt_purge");
    const char *dirs[] = {"0", "0.1", "0.2", "0.3", "0.4"};
    for (int i = 0; i < 5; i++) {
        char *p = io_join(dir, dirs[i]);
        io_mkdir_p(p, NULL);
        free(p);
    }
    Control c;
    memset(&c, 0, sizeof c);
    c.purgeWrite = 2;
    Err e;
    EXPECT(runtime_purge(&c, dir, &e) == 0, "%s", e.msg);
    TimeDir *t;
    int n = runtime_list_times(dir, &t, &e);
    char s[256];
    names_of(t, n, s, sizeof s);
    EXPECT(strcmp(s, "0 0.3 0.4") == 0, "after purge: '%s'", s);
    runtime_free_times(t, n);
    c.purgeWrite = 0;
    EXPECT(runtime_purge(&c, dir, &e) == 0, "purgeWrite 0 failed");
    c.purgeWrite = 1;
    c.startTime = 0.3;
    EXPECT(runtime_purge(&c, dir, &e) == 0, "%s", e.msg);
    n = runtime_list_times(dir, &t, &e);
    names_of(t, n, s, sizeof s);
    EXPECT(strcmp(s, "0 0.3 0.4") == 0, "startTime dir removed: '%s'", s);
    runtime_free_times(t, n);
    free(dir);
}

TEST(keys_table)
{
    int n = 0, required = 0;
    for (const DictKey *k = runtime_control_keys; k->key; k++, n++) {
        EXPECT(k->help && k->help[0], "no help for %s", k->key);
        required += k->def == NULL;
    }
    EXPECT(n == 25 && required == 2, "%d keys, %d required", n, required);
}

int main(void)
{
    RUN(control_defaults);
    RUN(control_cavity);
    RUN(control_errors);
    RUN(control_reread);
    RUN(time_names);
    RUN(list_times);
    RUN(select_times);
    RUN(uniform_time_file);
    RUN(purge);
    RUN(keys_table);
    return test_summary();
}
