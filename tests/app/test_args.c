/*
** test_args.c: the frame's command line (app/args.h): common and tool
** options, positional arguments, the tool dictionary's path (-dict, the
** case's file, an optional file that is absent) and the case it opens.
*/
#include "test.h"

#include "args.h"
#include "case.h"
#include "io.h"
#include "mem.h"

static const ArgOpt opts[] = {{"-o", "DIR", "output"}, {"-binary", NULL, "binary"}, {0}};
static const ToolInfo tool = {"testTool", "a tool for the test", opts, NULL, 1};

/* argv of n words (-Wwrite-strings: literals are const) */
static char **make_argv(int n, const char *const *w)
{
    char **v = mem_alloc(sizeof(char *) * (size_t)(n + 1));
    for (int i = 0; i < n; i++) v[i] = mem_strdup(w[i]);
    v[n] = NULL;
    return v;
}

static void free_argv(int n, char **v)
{
    for (int i = 0; i < n; i++) free(v[i]);
    free(v);
}

static char *scratch_case(const char *name)
{
    char *dir = io_join(test_tmpdir(), name);
    io_rm_rf(dir, NULL);
    char *sys = io_join(dir, "system");
    io_mkdir_p(sys, NULL);
    free(sys);
    return dir;
}

TEST(args_options)
{
    char *dir = scratch_case("args_case");
    const char *w[] = {"testTool", "-case", dir, "-o", "out", "-binary", "-latestTime", "-time", "0.1:0.5", "extra"};
    char **argv = make_argv(10, w);
    Args a;
    args_parse(10, argv, &tool, &a);
    EXPECT(!strcmp(a.case_dir, dir), "case %s", a.case_dir);
    EXPECT(!strcmp(args_get(&a, &tool, "-o"), "out") && args_get(&a, &tool, "-binary"), "tool options");
    EXPECT(a.latest == 1 && !a.nozero && !strcmp(a.time_spec, "0.1:0.5"), "time options");
    EXPECT(a.argc == 1 && !strcmp(a.argv[0], "extra"), "positional");
    EXPECT(args_get(&a, &tool, "-i") == NULL, "unknown option found");
    args_free(&a);
    free_argv(10, argv);
    free(dir);
}

TEST(args_dict_path)
{
    char *dir = scratch_case("args_dict");
    const char *w[] = {"testTool", "-case", dir};
    char **argv = make_argv(3, w);
    Args a;
    args_parse(3, argv, &tool, &a);
    Case c;
    Err e;
    EXPECT(case_open(&c, a.case_dir, CASE_CONTROL_FORMAT, &e) == 0, "%s", e.msg);
    char *want = io_join(dir, "system/cutCellsDict");
    char *p = args_dict_path(&a, &c, "system/cutCellsDict", 0);
    EXPECT(p && !strcmp(p, want), "required path %s", p ? p : "(null)");
    free(p);
    EXPECT(args_dict_path(&a, &c, "system/cutCellsDict", 1) == NULL, "absent optional dictionary");
    Err we;
    io_write_atomic(want, "a 1;\n", 5, 1, &we); /* only the .gz exists */
    p = args_dict_path(&a, &c, "system/cutCellsDict", 1);
    EXPECT(p && !strcmp(p, want), "gzipped optional dictionary not found");
    free(p);
    a.dict = "other/dict";
    p = args_dict_path(&a, &c, "system/cutCellsDict", 1);
    EXPECT(p && !strcmp(p, "other/dict"), "-dict ignored");
    free(p);
    free(want);
    case_free(&c);
    args_free(&a);
    free_argv(3, argv);
    free(dir);
}

int main(void)
{
    RUN(args_options);
    RUN(args_dict_path);
    return test_summary();
}
