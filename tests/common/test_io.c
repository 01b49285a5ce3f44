/*
** test_io.c: atomic writes (whole, in pieces, as a stream), gzip round
** trips, .gz fallback, and errors of io.c; directory commits (io_commit_dir) and the recovery rules of
** io_recover_dir; the Err message format of err.c; mem/buf basics.
*/
#include "buf.h"
#include "err.h"
#include "io.h"
#include "mem.h"
#include "test.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
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

/* A file written in parts (IoStream): the same bytes as one write, the
   stale .gz beside it removed; an aborted or failing stream keeps the old
   file and leaves no temporary file. */
TEST(stream_parts)
{
    char *p = tmp_path("s.txt"), *gz = mem_alloc(strlen(p) + 4);
    sprintf(gz, "%s.gz", p);
    Err e;
    EXPECT(io_write_atomic(gz, "stale", 5, 0, &e) == 0, "%s", e.msg);
    IoStream s;
    EXPECT(io_stream_open(&s, p, &e) == 0, "%s", e.msg);
    for (int i = 0; i < 1000; i++) io_stream_put(&s, "0123456789", 10);
    EXPECT(io_stream_close(&s, &e) == 0, "%s", e.msg);
    Buf b;
    buf_init(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0 && b.n == 10000 && !memcmp(b.p + 9990, "0123456789", 10), "content");
    EXPECT(!io_exists(gz), "the stale %s was kept", gz);
    /* aborted: the old file stays */
    EXPECT(io_stream_open(&s, p, &e) == 0, "%s", e.msg);
    io_stream_put(&s, "new", 3);
    io_stream_abort(&s);
    buf_clear(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0 && b.n == 10000, "an aborted stream replaced the file");
    /* a failing write (beyond a file-size limit, as a full disk): reported
       at the close, the old file kept */
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old;
    lim.rlim_cur = 4096;
    signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &lim);
    EXPECT(io_stream_open(&s, p, &e) == 0, "%s", e.msg);
    for (int i = 0; i < 1000; i++) io_stream_put(&s, "abcdefghij", 10);
    int rc = io_stream_close(&s, &e);
    setrlimit(RLIMIT_FSIZE, &old);
    EXPECT(rc == -1, "a stream beyond the size limit succeeded");
    CONTAINS(e.msg, "write failed");
    buf_clear(&b);
    EXPECT(io_read_file(p, &b, NULL, &e) == 0 && b.n == 10000 && b.p[0] == '0', "old file lost");
    char *dir = mem_strndup(p, (size_t)(strrchr(p, '/') - p));
    char **names;
    int k = io_list_dir(dir, &names, &e);
    EXPECT(k == 1, "%d entries left in the directory (temporary file not removed?)", k);
    io_free_list(names, k);
    free(dir);
    buf_free(&b);
    free(gz);
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

/* A directory path with one file "f" holding text. */
static void make_tree(const char *dir, const char *text)
{
    Err e;
    io_mkdir_p(dir, &e);
    char *f = io_join(dir, "f");
    io_write_atomic(f, text, strlen(text), 0, &e);
    free(f);
}

/* The text of dir/f, or "" (caller frees). */
static char *tree_text(const char *dir)
{
    char *f = io_join(dir, "f");
    Buf b;
    buf_init(&b);
    Err e;
    char *s = io_read_file(f, &b, NULL, &e) ? mem_strdup("") : mem_strdup(b.p);
    buf_free(&b);
    free(f);
    return s;
}

/* The pid of a child that has exited and been reaped: a dead process. */
static long dead_pid(void)
{
    pid_t p = fork();
    if (p == 0) _exit(0);
    waitpid(p, NULL, 0);
    return (long)p;
}

static char *sibling(const char *dst, const char *suffix)
{
    char *s = mem_alloc(strlen(dst) + strlen(suffix) + 1);
    sprintf(s, "%s%s", dst, suffix);
    return s;
}

TEST(commit_dir_new_and_empty_dst)
{
    char *dst = tmp_path("polyMesh");
    char *tmp = sibling(dst, ".tmp1");
    Err e;
    make_tree(tmp, "A");
    EXPECT(io_commit_dir(tmp, dst, &e) == 0, "%s", e.msg);
    char *t = tree_text(dst);
    EXPECT(!strcmp(t, "A") && !io_exists(tmp), "absent dst: '%s'", t);
    free(t);
    /* an empty directory at dst is simply replaced */
    char *dst2 = tmp_path("empty");
    io_mkdir_p(dst2, &e);
    make_tree(tmp, "B");
    EXPECT(io_commit_dir(tmp, dst2, &e) == 0, "%s", e.msg);
    t = tree_text(dst2);
    EXPECT(!strcmp(t, "B") && !io_exists(tmp), "empty dst: '%s'", t);
    free(t);
    free(dst2);
    free(tmp);
    free(dst);
}

TEST(commit_dir_leaves_nothing_beside)
{
    char *dst = tmp_path("polyMesh");
    char *tmp = sibling(dst, ".tmp7");
    Err e;
    make_tree(dst, "old");
    for (int k = 0; k < 3; k++) {
        char text[16];
        snprintf(text, sizeof text, "new%d", k);
        make_tree(tmp, text);
        EXPECT(io_commit_dir(tmp, dst, &e) == 0, "%s", e.msg);
        char *t = tree_text(dst);
        EXPECT(!strcmp(t, text), "round %d: '%s'", k, t);
        free(t);
    }
    char *dir = mem_strndup(dst, strlen(dst) - strlen("/polyMesh"));
    char **names;
    int n = io_list_dir(dir, &names, &e);
    EXPECT(n == 1 && !strcmp(names[0], "polyMesh"), "%d entries beside, first '%s'", n, n > 0 ? names[0] : "");
    io_free_list(names, n);
    free(dir);
    free(tmp);
    free(dst);
}

TEST(recover_rules)
{
    char *dst = tmp_path("polyMesh");
    char name[64];
    Err e;
    /* a dead process's temporary: removed; a running one's (our parent,
       standing in for a concurrent writer): kept; our own pid: removed */
    long dead = dead_pid();
    snprintf(name, sizeof name, ".tmp%ld", dead);
    char *tdead = sibling(dst, name);
    snprintf(name, sizeof name, ".tmp%ld", (long)getppid());
    char *tlive = sibling(dst, name);
    snprintf(name, sizeof name, ".tmp%ld", (long)getpid());
    char *town = sibling(dst, name);
    char *tother = sibling(dst, ".tmpXY"), *old = sibling(dst, ".old~");
    make_tree(dst, "cur");
    make_tree(tdead, "x");
    make_tree(tlive, "y");
    make_tree(town, "z");
    make_tree(tother, "w");
    make_tree(old, "prev");
    Buf r;
    buf_init(&r);
    int n = io_recover_dir(dst, &r, &e);
    EXPECT(n == 3, "%d actions (expected 3): %s", n, n < 0 ? e.msg : r.p);
    EXPECT(!io_exists(tdead) && !io_exists(town) && !io_exists(old), "stale entries left");
    EXPECT(io_exists(tlive) && io_exists(tother), "a running writer's or an unrelated directory was removed");
    char *t = tree_text(dst);
    EXPECT(!strcmp(t, "cur"), "dst changed: '%s'", t);
    free(t);
    snprintf(name, sizeof name, "left by process %ld, which is no longer running", dead);
    CONTAINS(r.p, name);
    CONTAINS(r.p, "polyMesh.old~: removed: the previous version");
    /* polyMesh.old~ without polyMesh: the only complete grid, put back */
    io_rm_rf(dst, &e);
    make_tree(old, "prev");
    buf_clear(&r);
    n = io_recover_dir(dst, &r, &e);
    t = tree_text(dst);
    EXPECT(n == 1 && !strcmp(t, "prev") && !io_exists(old), "restore: n = %d, dst '%s'", n, t);
    CONTAINS(r.p, "polyMesh: restored from ");
    free(t);
    /* nothing to do, and a parent that does not exist: 0 actions */
    buf_clear(&r);
    EXPECT(io_recover_dir(dst, &r, &e) == 0 && r.n == 0, "second recovery acted: %s", r.p);
    EXPECT(io_recover_dir("no/such/dir/polyMesh", &r, &e) == 0, "missing parent: %s", e.msg);
    buf_free(&r);
    io_rm_rf(tlive, &e);
    io_rm_rf(tother, &e);
    free(tdead);
    free(tlive);
    free(town);
    free(tother);
    free(old);
    free(dst);
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
    RUN(stream_parts);
    RUN(mkdir_list_rm);
    RUN(commit_dir_replaces);
    RUN(commit_dir_new_and_empty_dst);
    RUN(commit_dir_leaves_nothing_beside);
    RUN(recover_rules);
    return test_summary();
}
