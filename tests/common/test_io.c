/*
** test_io.c: atomic writes, gzip round trips, .gz fallback, and errors of
** io.c; the Err message format of err.c; mem/buf basics.
*/
#include "buf.h"
#include "err.h"
#include "io.h"
#include "mem.h"
#include "test.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

static char *tmp_path(const char *name)
{
    static int k;
    char dir[512];
    snprintf(dir, sizeof dir, "%s/io_%d_%d", test_tmpdir(), (int)getpid(), k++);
    io_mkdir_p(dir, NULL);
    return io_join(dir, name);
}

TEST(err_format)
{
    Err e;
    err_set(&e, "system/controlDict", 12, "expected %s", "';'");
    EXPECT(!strcmp(e.msg, "system/controlDict:12: expected ';'"), "%s", e.msg);
    err_set(&e, "0/U", 0, "missing");
    EXPECT(!strcmp(e.msg, "0/U: missing"), "%s", e.msg);
    err_set(&e, NULL, 3, "plain");
    EXPECT(!strcmp(e.msg, "plain"), "%s", e.msg);
    EXPECT(err_set(NULL, "x", 1, "y") == -1, "err_set(NULL) must return -1");
}

TEST(buf_growth)
{
    Buf b;
    buf_init(&b);
    for (int i = 0; i < 100000; i++) buf_printf(&b, "%d,", i % 10);
    EXPECT(b.n == 200000, "n = %zu", b.n);
    EXPECT(b.p[b.n] == '\0', "not NUL terminated");
    EXPECT(b.p[0] == '0' && b.p[2] == '1', "content");
    buf_free(&b);
}

TEST(write_read_plain)
{
    char *p = tmp_path("a.txt");
    Err e;
    EXPECT(io_write_atomic(p, "hello\n", 6, 0, &e) == 0, "%s", e.msg);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0, "%s", e.msg);
    EXPECT(b.n == 6 && !memcmp(b.p, "hello\n", 6), "content");
    buf_free(&b);
    free(p);
}

TEST(gzip_round_trip_and_fallback)
{
    char *p = tmp_path("U");
    Err e;
    size_t n = 3000000;
    char *data = mem_alloc(n);
    for (size_t i = 0; i < n; i++) data[i] = (char)((i * 7919u) % 251u);
    EXPECT(io_write_atomic(p, data, n, 1, &e) == 0, "%s", e.msg);
    char *gz = mem_alloc(strlen(p) + 4);
    sprintf(gz, "%s.gz", p);
    EXPECT(io_exists(gz) && !io_exists(p), "gzip write must create only U.gz");
    Buf b;
    buf_init(&b);
    char *found = NULL;
    EXPECT(io_read_file(p, &b, &found, &e) == 0, "%s", e.msg);
    EXPECT(b.n == n && !memcmp(b.p, data, n), "gzip round trip differs (n = %zu)", b.n);
    EXPECT(found && !strcmp(found, gz), "found %s", found ? found : "(null)");
    free(found);
    /* writing uncompressed removes the stale .gz */
    EXPECT(io_write_atomic(p, "x", 1, 0, &e) == 0, "%s", e.msg);
    EXPECT(io_exists(p) && !io_exists(gz), "plain write must remove U.gz");
    buf_free(&b);
    free(gz);
    free(data);
    free(p);
}

TEST(gzip_corrupt_and_truncated)
{
    Buf z, out;
    buf_init(&z);
    buf_init(&out);
    Err e;
    const char *s = "FoamFile { version 2.0; } a 1; b 2; c 3; d 4; e 5;";
    EXPECT(io_gzip("t", s, strlen(s), &z, &e) == 0, "%s", e.msg);
    EXPECT(io_gunzip("t", z.p, z.n, &out, &e) == 0 && out.n == strlen(s), "%s", e.msg);
    EXPECT(io_gunzip("t.gz", z.p, z.n / 2, &out, &e) == -1, "truncated accepted");
    CONTAINS(e.msg, "t.gz: ");
    z.p[12] ^= 0x55;
    z.p[13] ^= 0x55;
    EXPECT(io_gunzip("t.gz", z.p, z.n, &out, &e) == -1, "corrupt accepted");
    buf_free(&z);
    buf_free(&out);
}

TEST(missing_file_message)
{
    Buf b;
    buf_init(&b);
    Err e;
    EXPECT(io_read_file("/nonexistent/dir/file", &b, NULL, &e) == -1, "read of missing file");
    EXPECT(!strncmp(e.msg, "/nonexistent/dir/file: cannot open file", 39), "%s", e.msg);
    buf_free(&b);
}

TEST(failed_write_keeps_old_file)
{
    if (geteuid() == 0) {
        /* root ignores directory permissions: use a missing directory */
        Err e;
        EXPECT(io_write_atomic("/nonexistent/dir/f", "x", 1, 0, &e) == -1, "write into missing dir");
        CONTAINS(e.msg, "/nonexistent/dir/f: cannot write file");
        return;
    }
    char *p = tmp_path("keep");
    Err e;
    EXPECT(io_write_atomic(p, "old", 3, 0, &e) == 0, "%s", e.msg);
    char *dir = mem_strndup(p, (size_t)(strrchr(p, '/') - p));
    chmod(dir, 0555);
    EXPECT(io_write_atomic(p, "new", 3, 0, &e) == -1, "write into read-only dir succeeded");
    chmod(dir, 0755);
    Buf b;
    buf_init(&b);
    io_read_file(p, &b, NULL, &e);
    EXPECT(b.n == 3 && !memcmp(b.p, "old", 3), "old file lost");
    buf_free(&b);
    free(dir);
    free(p);
}

TEST(full_disk_keeps_old_file)
{
    /* A file-size limit makes write() fail as a full disk does (EFBIG
       instead of ENOSPC): the error must be reported and the old file
       must survive, with no temporary file left behind. */
    char *p = tmp_path("big");
    Err e;
    EXPECT(io_write_atomic(p, "old", 3, 0, &e) == 0, "%s", e.msg);
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old;
    lim.rlim_cur = 4096;
    signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &lim);
    size_t n = 100000;
    char *data = mem_calloc(n, 1);
    int rc = io_write_atomic(p, data, n, 0, &e);
    setrlimit(RLIMIT_FSIZE, &old);
    EXPECT(rc == -1, "write beyond the size limit succeeded");
    CONTAINS(e.msg, "write failed");
    Buf b;
    buf_init(&b);
    io_read_file(p, &b, NULL, &e);
    EXPECT(b.n == 3 && !memcmp(b.p, "old", 3), "old file lost");
    char *dir = mem_strndup(p, (size_t)(strrchr(p, '/') - p));
    char **names;
    int k = io_list_dir(dir, &names, &e);
    EXPECT(k == 1, "%d entries left in the directory (temporary file not removed?)", k);
    io_free_list(names, k);
    buf_free(&b);
    free(dir);
    free(data);
    free(p);
}

TEST(mkdir_list_rm)
{
    char *p = tmp_path("tree/a/b");
    Err e;
    EXPECT(io_mkdir_p(p, &e) == 0, "%s", e.msg);
    EXPECT(io_is_dir(p), "not created");
    char *top = mem_strndup(p, strlen(p) - 4);
    char *f1 = io_join(top, "z");
    io_write_atomic(f1, "1", 1, 0, &e);
    char **names;
    int n = io_list_dir(top, &names, &e);
    EXPECT(n == 2 && !strcmp(names[0], "a") && !strcmp(names[1], "z"), "list n = %d", n);
    io_free_list(names, n);
    EXPECT(io_rm_rf(top, &e) == 0 && !io_exists(top), "rm_rf");
    free(f1);
    free(top);
    free(p);
}

TEST(commit_dir_replaces)
{
    char *a = tmp_path("new");
    char *b = mem_alloc(strlen(a) + 8);
    sprintf(b, "%s.dst", a);
    Err e;
    io_mkdir_p(a, &e);
    io_mkdir_p(b, &e);
    char *fa = io_join(a, "f"), *fb = io_join(b, "g");
    io_write_atomic(fa, "A", 1, 0, &e);
    io_write_atomic(fb, "B", 1, 0, &e);
    EXPECT(io_commit_dir(a, b, &e) == 0, "%s", e.msg);
    char *ff = io_join(b, "f"), *fg = io_join(b, "g");
    EXPECT(io_exists(ff) && !io_exists(fg) && !io_exists(a), "commit_dir result");
    free(ff);
    free(fg);
    free(fa);
    free(fb);
    free(a);
    free(b);
}

int main(void)
{
    RUN(err_format);
    RUN(buf_growth);
    RUN(write_read_plain);
    RUN(gzip_round_trip_and_fallback);
    RUN(gzip_corrupt_and_truncated);
    RUN(missing_file_message);
    RUN(failed_write_keeps_old_file);
    RUN(full_disk_keeps_old_file);
    RUN(mkdir_list_rm);
    RUN(commit_dir_replaces);
    return test_summary();
}
