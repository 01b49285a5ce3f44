/*
** io.h: whole-file reads and atomic writes, with transparent gzip.
**
** Reads: io_read_file accepts "-" for standard input; for a path that does
** not exist it tries path.gz (OpenFOAM's writeCompression convention), and
** any input that starts with the gzip magic bytes is inflated, whatever its
** name.  Writes: io_write_atomic writes to a temporary file in the target's
** directory, flushes it to disk and renames it over the target, so a run
** that is interrupted or hits a full disk leaves the old file intact.  With
** gzip set the file is written as path.gz and a stale uncompressed path is
** removed (and vice versa), so a time directory never holds both.
** io_write_atomic_v does the same for a file given as several pieces
** (header, big array, footer) without joining them first, and an IoStream
** for a file written in parts as it is made.
*/
#ifndef KIESEL_IO_H
#define KIESEL_IO_H

#include <stddef.h>

#include "buf.h"
#include "err.h"

/* Reads all of path (or stdin for "-") into out (cleared first).  On
   success, if found_path is not NULL, it receives the name actually read
   (path or path.gz; caller frees).  Returns 0 or -1; on failure out is
   left empty and freed, so the caller need not free it. */
int io_read_file(const char *path, Buf *out, char **found_path, Err *e);


/* A file's bytes for reading: either a read-only mapping of the file
   (map != NULL) or a Buf holding them.  p[0..n) is the content (inflated
   when the file is gzip); it is NOT NUL-terminated when mapped. */
typedef struct IoMap {
    const char *p;
    size_t n;
    Buf own;
    void *map;
    size_t maplen;
} IoMap;

/* Like io_read_file, but a big uncompressed regular file (>= 1 MB) is
   mapped rather than copied into fresh memory: for a parser that copies
   the data out anyway (binary lists) this saves a copy and the page
   faults of a buffer the size of the file.  The mapping stays valid if
   the file is replaced (io_write_atomic renames); truncating it in place
   while mapped is not supported.  io_unmap releases either form. */
int io_map_file(const char *path, IoMap *m, char **found_path, Err *e);
void io_unmap(IoMap *m);

/* Inflates gzip data in place of in; returns 0 or -1. */
int io_gunzip(const char *name, const void *in, size_t n, Buf *out, Err *e);
/* Deflates data as a gzip stream. */
int io_gzip(const char *name, const void *in, size_t n, Buf *out, Err *e);

/* Writes data atomically to path ("-" = stdout, not atomic).  gzip != 0
   writes path.gz instead.  Returns 0 or -1 (disk full, permission, ...). */
int io_write_atomic(const char *path, const void *data, size_t n, int gzip, Err *e);

/* One piece of a file written by io_write_atomic_v. */
typedef struct IoPiece {
    const void *p;
    size_t n;
} IoPiece;

/* io_write_atomic of the concatenation of npieces pieces, written (or
   gzipped) straight from each piece's memory: a file made of a short
   header, a big array and a footer need not be copied into one buffer
   first.  Same contract, same bytes on disk as io_write_atomic of the
   concatenation. */
int io_write_atomic_v(const char *path, const IoPiece *pieces, int npieces, int gzip, Err *e);

/* A file written atomically in parts, for output too big to assemble in
   memory first (a VTK file of a big grid): io_stream_open makes the
   temporary file beside path, io_stream_put appends bytes to it (a failed
   write is kept and reported by the close), io_stream_close flushes it to
   disk and renames it over path, with io_write_atomic's guarantees and
   messages, and io_stream_abort removes it.  Uncompressed; not "-".  The
   close and the abort free s. */
typedef struct IoStream {
    char *target, *other, *tmp;  /* the file, its other (.gz) name, the temporary */
    int fd;
    int failed;                  /* errno of the first failed write, or 0 */
} IoStream;

int io_stream_open(IoStream *s, const char *path, Err *e);
void io_stream_put(IoStream *s, const void *p, size_t n);
int io_stream_close(IoStream *s, Err *e);
void io_stream_abort(IoStream *s);

/* Creates a directory and its parents (like mkdir -p). */
int io_mkdir_p(const char *path, Err *e);
/* Writes a whole directory atomically: every file is written into a
   temporary sibling directory first (named dst.tmp<pid> by convention, so
   io_recover_dir knows whose it is); io_commit_dir puts it at dst.  An
   existing dst is swapped with tmpdir in one step (renameat2
   RENAME_EXCHANGE) and the old tree, now at tmpdir, removed; so dst is a
   complete tree at every instant, whenever the process is killed.  Where
   the filesystem cannot exchange (EINVAL, ENOSYS), dst is moved to
   dst.old~ first, and a kill between the two renames leaves dst.old~
   alone, which io_recover_dir renames back.  Commits and recoveries in
   one directory hold an flock on it, so concurrent writers of the same
   dst never fail spuriously: each commit replaces the previous one.
   tmpdir is gone on success; on failure it is left for the caller. */
int io_commit_dir(const char *tmpdir, const char *dst, Err *e);
/* Repairs what interrupted commits to dst left behind, and appends one
   line "path: what was done" per action to report:
     dst.tmp<pid> whose process is gone (kill(pid, 0) fails with ESRCH,
       or pid is this process's own): removed;
     dst.old~ while dst exists: removed (dst is complete);
     dst.old~ without dst: renamed back to dst.
   A dst.tmp<pid> of a running process (a concurrent writer) is left
   alone.  Call it before this process writes dst.  Returns the number of
   actions (0: nothing to do) or -1. */
int io_recover_dir(const char *dst, Buf *report, Err *e);
/* Removes a directory tree (used to purge old time directories). */
int io_rm_rf(const char *path, Err *e);

int io_exists(const char *path);     /* file or directory */
/* path or path.gz exists (what io_read_file would find). */
int io_exists_gz(const char *path);
int io_is_dir(const char *path);
/* path joined: returns a newly allocated "a/b". */
char *io_join(const char *a, const char *b);

/* Lists the entries of a directory (not "." or ".."), sorted by name.
   Returns the count or -1; *names is an allocated array of allocated
   strings (io_free_list). */
int io_list_dir(const char *path, char ***names, Err *e);
void io_free_list(char **names, int n);

#endif
