/*
** io.c: file input and atomic output.  See io.h for the contract.
**
** Big files are the common case (a 200^3 polyMesh is 900 MB), so no byte
** is copied more often than needed: a regular file is read straight into
** a buffer reserved to its size (no regrowth, no staging copy); a big one
** can be mapped instead (io_map_file) when the caller copies out of it
** anyway; a write takes the file as pieces (io_write_atomic_v) so a big
** array goes from its own memory to the kernel, and gzip output is
** deflated through a fixed buffer into the file rather than held whole.
** The gzip stream is the one io_gzip makes (same level, window and
** strategy, no flushes before the end), so files do not depend on how
** they were written.
**
** A directory (polyMesh) is replaced by io_commit_dir with an atomic
** exchange, so the case has a complete tree under its name at every
** instant; whatever a killed run leaves behind carries the run's pid in
** its name (or is dst.old~), and io_recover_dir, which every tool runs at
** start-up, removes it or puts it back.
*/
/* syscall(2) and flock(2) are outside POSIX: glibc declares them under
   _DEFAULT_SOURCE, which must come before the first system header. */
#define _DEFAULT_SOURCE

#include "io.h"
#include "mem.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>
#include <zlib.h>

/* Appends the rest of f to out, reading straight into the buffer: a
   regular file's size (hint) is reserved up front, so a big file is read
   with no intermediate copy and no regrowth. */
static int read_rest(FILE *f, const char *name, Buf *out, size_t hint, Err *e)
{
    buf_reserve(out, hint ? hint : 1 << 16);
    for (;;) {
        if (out->cap - out->n - 1 == 0) buf_reserve(out, out->cap);
        size_t room = out->cap - out->n - 1;
        size_t k = fread(out->p + out->n, 1, room, f);
        out->n += k;
        out->p[out->n] = '\0';
        if (k < room) break;
    }
    if (ferror(f)) return err_set(e, name, 0, "read error: %s", strerror(errno));
    return 0;
}

/* Reads all of a FILE* (already open) into out. */
static int io_read_stream(void *fp, const char *name, Buf *out, Err *e)
{
    buf_clear(out);
    return read_rest(fp, name, out, 0, e);
}

static int is_gzip(const Buf *b)
{
    return b->n >= 2 && (unsigned char)b->p[0] == 0x1f && (unsigned char)b->p[1] == 0x8b;
}

int io_gunzip(const char *name, const void *in, size_t n, Buf *out, Err *e)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    if (inflateInit2(&z, 15 + 32) != Z_OK) return err_set(e, name, 0, "cannot initialise zlib");
    buf_clear(out);
    buf_reserve(out, n * 4 + 1024);
    z.next_in = (Bytef *)in;
    z.avail_in = (uInt)0;
    size_t left = n;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        if (z.avail_in == 0 && left > 0) {
            uInt chunk = left > (1u << 30) ? (1u << 30) : (uInt)left;
            z.avail_in = chunk;
            left -= chunk;
        }
        buf_reserve(out, 1 << 16);
        z.next_out = (Bytef *)(out->p + out->n);
        z.avail_out = (uInt)(out->cap - out->n - 1);
        uInt before = z.avail_out;
        rc = inflate(&z, Z_NO_FLUSH);
        out->n += before - z.avail_out;
        if (rc == Z_STREAM_END) {
            /* concatenated gzip members are legal: continue with the next */
            if (z.avail_in > 0 || left > 0) {
                inflateReset(&z);
                rc = Z_OK;
            }
            continue;
        }
        if (rc != Z_OK && !(rc == Z_BUF_ERROR && z.avail_in == 0 && left == 0)) {
            inflateEnd(&z);
            return err_set(e, name, 0, "corrupt gzip data (%s)", z.msg ? z.msg : "inflate failed");
        }
        if (rc == Z_BUF_ERROR || (z.avail_in == 0 && left == 0 && before == z.avail_out)) {
            inflateEnd(&z);
            return err_set(e, name, 0, "truncated gzip data");
        }
    }
    inflateEnd(&z);
    out->p[out->n] = '\0';
    return 0;
}

int io_gzip(const char *name, const void *in, size_t n, Buf *out, Err *e)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    /* level 6 as gzip(1); window 15 + 16 selects the gzip wrapper */
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        return err_set(e, name, 0, "cannot initialise zlib");
    buf_clear(out);
    z.next_in = (Bytef *)in;
    size_t left = n;
    int rc;
    do {
        if (z.avail_in == 0 && left > 0) {
            uInt chunk = left > (1u << 30) ? (1u << 30) : (uInt)left;
            z.avail_in = chunk;
            left -= chunk;
        }
        buf_reserve(out, 1 << 16);
        z.next_out = (Bytef *)(out->p + out->n);
        z.avail_out = (uInt)(out->cap - out->n - 1);
        uInt before = z.avail_out;
        rc = deflate(&z, left == 0 ? Z_FINISH : Z_NO_FLUSH);
        out->n += before - z.avail_out;
        if (rc == Z_STREAM_ERROR) {
            deflateEnd(&z);
            return err_set(e, name, 0, "gzip compression failed");
        }
    } while (rc != Z_STREAM_END);
    deflateEnd(&z);
    out->p[out->n] = '\0';
    return 0;
}

int io_read_file(const char *path, Buf *out, char **found_path, Err *e)
{
    Buf raw;
    buf_init(&raw);
    const char *name = path;
    char *gz = NULL;
    if (strcmp(path, "-") == 0) {
        if (io_read_stream(stdin, "<stdin>", &raw, e)) return buf_free(&raw), -1;
        name = "<stdin>";
    } else {
        FILE *f = fopen(path, "rb");
        if (!f && errno == ENOENT) {
            size_t l = strlen(path);
            gz = mem_alloc(l + 4);
            memcpy(gz, path, l);
            memcpy(gz + l, ".gz", 4);
            f = fopen(gz, "rb");
            if (f) name = gz;
        }
        if (!f) {
            int en = errno;
            free(gz);
            return err_set(e, path, 0, "cannot open file: %s", strerror(en));
        }
        struct stat st;
        if (fstat(fileno(f), &st)) st.st_mode = 0;
        if (S_ISDIR(st.st_mode)) {
            fclose(f);
            free(gz);
            return err_set(e, path, 0, "is a directory, expected a file");
        }
        size_t hint = S_ISREG(st.st_mode) && st.st_size > 0 ? (size_t)st.st_size + 1 : 0;
        int rc = read_rest(f, name, &raw, hint, e);
        fclose(f);
        if (rc) {
            free(gz);
            buf_free(&raw);
            return -1;
        }
    }
    if (is_gzip(&raw)) {
        int rc = io_gunzip(name, raw.p, raw.n, out, e);
        buf_free(&raw);
        if (rc) {
            buf_free(out); /* a failed read leaves nothing for the caller to free */
            free(gz);
            return -1;
        }
    } else {
        buf_free(out);
        *out = raw;
    }
    if (found_path) *found_path = mem_strdup(name);
    free(gz);
    return 0;
}

void io_unmap(IoMap *m)
{
    if (m->map) munmap(m->map, m->maplen);
    buf_free(&m->own);
    m->map = NULL;
    m->maplen = 0;
    m->p = NULL;
    m->n = 0;
}

/* Maps the regular file at path when it is big and not gzip; returns 1
   when mapped, 0 when the caller should read it instead. */
static int try_map(const char *path, IoMap *m)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0) return 0;
    struct stat st;
    void *p = MAP_FAILED;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= (1 << 20))
        p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    if (p == MAP_FAILED) return 0;
    const unsigned char *c = p;
    if (c[0] == 0x1f && c[1] == 0x8b) {
        munmap(p, (size_t)st.st_size);
        return 0;
    }
    posix_madvise(p, (size_t)st.st_size, POSIX_MADV_WILLNEED);
    m->map = p;
    m->maplen = (size_t)st.st_size;
    m->p = p;
    m->n = m->maplen;
    return 1;
}

int io_map_file(const char *path, IoMap *m, char **found_path, Err *e)
{
    buf_init(&m->own);
    m->map = NULL;
    m->maplen = 0;
    if (strcmp(path, "-") != 0 && try_map(path, m)) {
        if (found_path) *found_path = mem_strdup(path);
        return 0;
    }
    if (io_read_file(path, &m->own, found_path, e)) return -1;
    m->p = m->own.p;
    m->n = m->own.n;
    return 0;
}

static int write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(fd, p, n > (1u << 30) ? (1u << 30) : n);
        if (k < 0) {
            if (errno == EINTR) continue;
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static char *dir_of(const char *path)
{
    const char *s = strrchr(path, '/');
    if (!s) return mem_strdup(".");
    if (s == path) return mem_strdup("/");
    return mem_strndup(path, (size_t)(s - path));
}

/* Deflates the pieces as one gzip stream (as io_gzip would) into fd,
   through a fixed output buffer, so the compressed file is never held in
   memory whole.  Returns 0, -1 with errno set (write error), or -2
   (zlib failure). */
static int gzip_to_fd(int fd, const IoPiece *pc, int np)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) return -2;
    enum { OUT = 1 << 18 };
    unsigned char *out = mem_alloc(OUT);
    int i = 0, rc = 0, zr = Z_OK;
    size_t left = 0;
    const char *at = NULL;
    while (zr != Z_STREAM_END) {
        while (z.avail_in == 0 && left == 0 && i < np) {
            at = pc[i].p;
            left = pc[i++].n;
        }
        if (z.avail_in == 0 && left > 0) {
            uInt chunk = left > (1u << 30) ? (1u << 30) : (uInt)left;
            z.next_in = (Bytef *)at;
            z.avail_in = chunk;
            at += chunk;
            left -= chunk;
        }
        int finish = i == np && left == 0;
        z.next_out = out;
        z.avail_out = OUT;
        zr = deflate(&z, finish ? Z_FINISH : Z_NO_FLUSH);
        if (zr == Z_STREAM_ERROR) {
            rc = -2;
            break;
        }
        if (write_all(fd, (const char *)out, OUT - z.avail_out)) {
            rc = -1;
            break;
        }
    }
    deflateEnd(&z);
    free(out);
    return rc;
}

static int write_pieces(int fd, const IoPiece *pc, int np)
{
    for (int i = 0; i < np; i++)
        if (write_all(fd, pc[i].p, pc[i].n)) return -1;
    return 0;
}

int io_write_atomic(const char *path, const void *data, size_t n, int gzip, Err *e)
{
    IoPiece one = {data, n};
    return io_write_atomic_v(path, &one, 1, gzip, e);
}

/* The temporary file beside the target (path, or path.gz with gzip) and
   the names a commit needs. */
static int stream_begin(IoStream *s, const char *path, int gzip, Err *e)
{
    size_t l = strlen(path);
    memset(s, 0, sizeof *s);
    s->target = mem_alloc(l + 4);
    memcpy(s->target, path, l + 1);
    if (gzip) memcpy(s->target + l, ".gz", 4);
    s->other = mem_alloc(l + 4);
    memcpy(s->other, path, l + 1);
    if (!gzip) memcpy(s->other + l, ".gz", 4);
    char *dir = dir_of(s->target);
    const char *base = strrchr(s->target, '/') ? strrchr(s->target, '/') + 1 : s->target;
    size_t tl = strlen(dir) + strlen(base) + 32;
    s->tmp = mem_alloc(tl);
    snprintf(s->tmp, tl, "%s/.%s.tmpXXXXXX", dir, base);
    free(dir);
    s->fd = mkstemp(s->tmp);
    if (s->fd >= 0) return 0;
    err_set(e, s->target, 0, "cannot write file: %s", strerror(errno));
    s->fd = -1;
    io_stream_abort(s);
    return -1;
}

int io_stream_open(IoStream *s, const char *path, Err *e) { return stream_begin(s, path, 0, e); }

void io_stream_put(IoStream *s, const void *p, size_t n)
{
    if (!s->failed && write_all(s->fd, p, n)) s->failed = errno ? errno : EIO;
}

void io_stream_abort(IoStream *s)
{
    if (s->fd >= 0) {
        close(s->fd);
        unlink(s->tmp);
    }
    free(s->tmp);
    free(s->target);
    free(s->other);
    memset(s, 0, sizeof *s);
    s->fd = -1;
}

int io_stream_close(IoStream *s, Err *e)
{
    int rc = -1;
    if (s->failed || fsync(s->fd)) {
        err_set(e, s->target, 0, "write failed: %s (old file kept)", strerror(s->failed ? s->failed : errno));
    } else {
        fchmod(s->fd, 0644);
        int fd = s->fd;
        s->fd = -1;
        if (close(fd)) {
            err_set(e, s->target, 0, "write failed: %s (old file kept)", strerror(errno));
            unlink(s->tmp);
        } else if (rename(s->tmp, s->target)) {
            err_set(e, s->target, 0, "cannot rename temporary file: %s", strerror(errno));
            unlink(s->tmp);
        } else {
            unlink(s->other);
            rc = 0;
        }
    }
    io_stream_abort(s);
    return rc;
}

int io_write_atomic_v(const char *path, const IoPiece *pieces, int npieces, int gzip, Err *e)
{
    if (strcmp(path, "-") == 0) {
        fflush(NULL); /* what the caller printed goes first */
        if (write_pieces(STDOUT_FILENO, pieces, npieces))
            return err_set(e, "<stdout>", 0, "write error: %s", strerror(errno));
        return 0;
    }
    IoStream s;
    if (stream_begin(&s, path, gzip, e)) return -1;
    int wr = gzip ? gzip_to_fd(s.fd, pieces, npieces) : write_pieces(s.fd, pieces, npieces);
    if (wr == -2) {
        err_set(e, path, 0, "gzip compression failed");
        io_stream_abort(&s);
        return -1;
    }
    if (wr) s.failed = errno ? errno : EIO;
    return io_stream_close(&s, e);
}

int io_mkdir_p(const char *path, Err *e)
{
    char *p = mem_strdup(path);
    size_t l = strlen(p);
    while (l > 1 && p[l - 1] == '/') p[--l] = '\0';
    for (char *s = p + 1; *s; s++) {
        if (*s != '/') continue;
        *s = '\0';
        if (mkdir(p, 0755) && errno != EEXIST) {
            err_set(e, p, 0, "cannot create directory: %s", strerror(errno));
            free(p);
            return -1;
        }
        *s = '/';
    }
    if (mkdir(p, 0755) && errno != EEXIST) {
        err_set(e, p, 0, "cannot create directory: %s", strerror(errno));
        free(p);
        return -1;
    }
    if (!io_is_dir(p)) {
        err_set(e, p, 0, "exists and is not a directory");
        free(p);
        return -1;
    }
    free(p);
    return 0;
}

int io_rm_rf(const char *path, Err *e)
{
    struct stat st;
    if (lstat(path, &st)) return errno == ENOENT ? 0 : err_set(e, path, 0, "cannot remove: %s", strerror(errno));
    if (S_ISDIR(st.st_mode)) {
        char **names;
        int n = io_list_dir(path, &names, e);
        if (n < 0) return -1;
        for (int i = 0; i < n; i++) {
            char *c = io_join(path, names[i]);
            int rc = io_rm_rf(c, e);
            free(c);
            if (rc) {
                io_free_list(names, n);
                return -1;
            }
        }
        io_free_list(names, n);
        if (rmdir(path)) return err_set(e, path, 0, "cannot remove directory: %s", strerror(errno));
        return 0;
    }
    if (unlink(path)) return err_set(e, path, 0, "cannot remove: %s", strerror(errno));
    return 0;
}

/* Linux's renameat2 flag that swaps two names in one step. */
#define IO_RENAME_EXCHANGE (1 << 1)

/* Swaps the directories a and b atomically: at every instant both names
   hold a complete tree.  Fails with EINVAL or ENOSYS where the kernel or
   the filesystem cannot (no renameat2, NFS, some FUSE). */
static int exchange(const char *a, const char *b)
{
#ifdef SYS_renameat2
    return (int)syscall(SYS_renameat2, AT_FDCWD, a, AT_FDCWD, b, IO_RENAME_EXCHANGE);
#else
    (void)a;
    (void)b;
    errno = ENOSYS;
    return -1;
#endif
}

/* Takes an exclusive lock on the directory that holds path, so that
   commits and recoveries of its entries by concurrent processes run one
   at a time; the kernel drops it when the process dies.  Returns the fd
   to pass to unlock_parent, or -1 where locking is not supported (the
   commit then goes ahead unlocked: it is still safe against kills). */
static int lock_parent(const char *path)
{
    char *dir = dir_of(path);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(dir);
    if (fd < 0) return -1;
    while (flock(fd, LOCK_EX)) {
        if (errno == EINTR) continue;
        close(fd);
        return -1;
    }
    return fd;
}

static void unlock_parent(int fd)
{
    if (fd >= 0) close(fd);
}

static char *aside_name(const char *dst)
{
    size_t l = strlen(dst) + 8;
    char *old = mem_alloc(l);
    snprintf(old, l, "%s.old~", dst);
    return old;
}

/* The replace for filesystems without an atomic exchange: dst moves to
   dst.old~, tmpdir to dst, and dst.old~ to tmpdir (removed by the
   caller).  A kill between the first two renames leaves dst.old~ without
   dst, which io_recover_dir renames back. */
static int replace_aside(const char *tmpdir, const char *dst, Err *e)
{
    char *old = aside_name(dst);
    int rc = -1;
    if (io_rm_rf(old, e)) goto done;
    if (rename(dst, old)) {
        err_set(e, dst, 0, "cannot move old directory aside: %s", strerror(errno));
        goto done;
    }
    if (rename(tmpdir, dst)) {
        err_set(e, dst, 0, "cannot rename directory: %s", strerror(errno));
        rename(old, dst);
        goto done;
    }
    rc = 0;
    if (rename(old, tmpdir)) io_rm_rf(old, NULL);
done:
    free(old);
    return rc;
}

/* Puts tmpdir at dst under the parent's lock.  Returns 0 when tmpdir is
   gone, 1 when tmpdir now holds the old tree, -1 on failure. */
static int commit_locked(const char *tmpdir, const char *dst, Err *e)
{
    /* rename over an absent or empty dst; ENOTEMPTY/EEXIST: a grid is there */
    if (rename(tmpdir, dst) == 0) return 0;
    if (errno != ENOTEMPTY && errno != EEXIST)
        return err_set(e, dst, 0, "cannot rename directory: %s", strerror(errno));
    if (exchange(tmpdir, dst) == 0) return 1;
    if (errno != EINVAL && errno != ENOSYS)
        return err_set(e, dst, 0, "cannot exchange directories: %s", strerror(errno));
    return replace_aside(tmpdir, dst, e) ? -1 : 1;
}

int io_commit_dir(const char *tmpdir, const char *dst, Err *e)
{
    int fd = lock_parent(dst);
    int rc = commit_locked(tmpdir, dst, e);
    unlock_parent(fd);
    /* outside the lock: the old tree is under our own temporary name */
    if (rc == 1) io_rm_rf(tmpdir, NULL);
    return rc < 0 ? -1 : 0;
}

/* The pid in name when name is base ".tmp" digits, else 0. */
static long tmp_pid(const char *name, const char *base)
{
    size_t l = strlen(base);
    if (strncmp(name, base, l) || strncmp(name + l, ".tmp", 4)) return 0;
    const char *d = name + l + 4;
    if (!*d || strspn(d, "0123456789") != strlen(d) || strlen(d) > 9) return 0;
    return atol(d);
}

/* A process is gone when kill(pid, 0) says there is no such process
   (EPERM means it runs as another user).  Our own pid counts as gone: a
   recovery runs before this process writes, so a directory with its pid
   is left by an earlier process that had the same pid (a container). */
static int pid_gone(long pid)
{
    if (pid == (long)getpid()) return 1;
    return kill((pid_t)pid, 0) && errno == ESRCH;
}

/* Removes dst.tmp<pid> of processes that are gone. */
static int recover_tmp(const char *dst, Buf *report, Err *e)
{
    char *dir = dir_of(dst);
    if (!io_is_dir(dir)) { /* no constant/ yet: nothing was ever written */
        free(dir);
        return 0;
    }
    const char *base = strrchr(dst, '/') ? strrchr(dst, '/') + 1 : dst;
    char **names;
    int n = io_list_dir(dir, &names, e), done = 0;
    for (int i = 0; i < n && done >= 0; i++) {
        long pid = tmp_pid(names[i], base);
        if (pid <= 0 || !pid_gone(pid)) continue;
        char *p = io_join(dir, names[i]);
        if (io_rm_rf(p, e)) {
            done = -1;
        } else {
            buf_printf(report, "%s: removed: left by process %ld, which is no longer running\n", p, pid);
            done++;
        }
        free(p);
    }
    if (n >= 0) io_free_list(names, n);
    free(dir);
    return n < 0 ? -1 : done;
}

/* dst.old~ with dst present is the previous tree: removed; without dst it
   is the only complete tree: renamed back. */
static int recover_aside(const char *dst, Buf *report, Err *e)
{
    char *old = aside_name(dst);
    int rc = 0;
    if (!io_is_dir(old)) {
        free(old);
        return 0;
    }
    if (io_exists(dst)) {
        rc = io_rm_rf(old, e);
        if (!rc) buf_printf(report, "%s: removed: the previous version, left by an interrupted replace\n", old);
    } else if (rename(old, dst)) {
        rc = err_set(e, old, 0, "cannot rename back to %s: %s", dst, strerror(errno));
    } else {
        buf_printf(report, "%s: restored from %s, where an interrupted replace had moved it\n", dst, old);
    }
    free(old);
    return rc ? -1 : 1;
}

int io_recover_dir(const char *dst, Buf *report, Err *e)
{
    int fd = lock_parent(dst);
    int a = recover_aside(dst, report, e);
    int t = a < 0 ? -1 : recover_tmp(dst, report, e);
    unlock_parent(fd);
    return a < 0 || t < 0 ? -1 : a + t;
}

int io_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

int io_exists_gz(const char *path)
{
    if (io_exists(path)) return 1;
    size_t l = strlen(path);
    char *gz = mem_alloc(l + 4);
    memcpy(gz, path, l);
    memcpy(gz + l, ".gz", 4);
    int r = io_exists(gz);
    free(gz);
    return r;
}

int io_is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

char *io_join(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    char *s = mem_alloc(la + lb + 2);
    memcpy(s, a, la);
    size_t k = la;
    if (la && a[la - 1] != '/') s[k++] = '/';
    memcpy(s + k, b, lb + 1);
    return s;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int io_list_dir(const char *path, char ***names, Err *e)
{
    DIR *d = opendir(path);
    if (!d) return err_set(e, path, 0, "cannot open directory: %s", strerror(errno));
    size_t n = 0, cap = 0;
    char **v = NULL;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        mem_grow((void **)&v, &cap, n + 1, sizeof *v);
        v[n++] = mem_strdup(de->d_name);
    }
    closedir(d);
    if (n) qsort(v, n, sizeof *v, cmp_str);
    *names = v;
    return (int)n;
}

void io_free_list(char **names, int n)
{
    for (int i = 0; i < n; i++) free(names[i]);
    free(names);
}
