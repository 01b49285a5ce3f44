/*
** field_time.c: the vol fields of a time directory (field.h): the path of
** a field in <case>/<time>, reading one field there, and reading all of
** them (or those asked for) in name order, or listing them to be read
** one at a time.
**
** A field file may be gzipped: "U" and "U.gz" are one field, the first
** in name order wins (io_list_dir sorts).  Files of other classes are
** skipped by a look at the header (field_probe) before any data is read,
** unless the caller asked for them by name, which is an error naming the
** class found.  A missing field is not an error here (field_read_time
** returns 1): the caller names the dictionary entry that asked for it.
*/
#include "field.h"

#include "io.h"
#include "mem.h"

#include <stdlib.h>
#include <string.h>

/* "<case>/<time>/<name>", joined as the tools have always joined it so
   that messages naming the file do not change. */
char *field_time_path(const char *case_dir, const char *time, const char *name)
{
    char *rel = io_join(time, name), *path = io_join(case_dir, rel);
    free(rel);
    return path;
}

int field_read_time(Field *f, const Mesh *m, const char *case_dir, const char *time, const char *name, char **path,
                    Err *e)
{
    char *p = field_time_path(case_dir, time, name);
    int rc = !io_exists_gz(p) ? 1 : field_read(f, m, p, e) ? -1 : 0;
    if (path) *path = p;
    else free(p);
    return rc;
}

static int name_listed(const char *const *names, int n, const char *x)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], x)) return 1;
    return 0;
}

/* Is dir/file a vol field that is wanted and not yet listed?  1 with its
   name and path into *name and *path, 0 when skipped, -1 on error (a file
   asked for by name that is no vol field).  "U" and "U.gz" are one field:
   the first listed wins. */
static int dir_entry(const char *dir, const char *file, const char *const *want, int nwant, char *const *seen,
                     int nseen, char **name_out, char **path_out, Err *e)
{
    size_t l = strlen(file);
    char *name = l > 3 && !strcmp(file + l - 3, ".gz") ? mem_strndup(file, l - 3) : mem_strdup(file);
    char *path = io_join(dir, file), *cls = NULL;
    int requested = name_listed(want, nwant, name), rc = 0;
    if (!io_is_dir(path) && (nwant == 0 || requested) && !name_listed((const char *const *)seen, nseen, name)) {
        int w = field_probe(path, &cls, e);
        if (w < 0)
            rc = -1;
        else if (w == 0 && requested)
            rc = err_set(e, path, 0, "field '%s' is %s%s%s, not a volScalarField or volVectorField", name,
                         cls ? "of class '" : "not an OpenFOAM file with a class", cls ? cls : "", cls ? "'" : "");
        else if (w > 0)
            rc = 1;
    }
    free(cls);
    if (rc == 1) {
        *name_out = name;
        *path_out = path;
        return 1;
    }
    free(path);
    free(name);
    return rc;
}

int field_list_dir(const char *dir, const char *const *want, int nwant, char ***names, char ***paths, Err *e)
{
    char **files;
    int nf = io_list_dir(dir, &files, e);
    if (nf < 0) return -1;
    char **nm = MEM_NEW(char *, nf), **pt = MEM_NEW(char *, nf);
    int n = 0, rc = 0;
    for (int i = 0; i < nf && rc >= 0; i++) {
        rc = dir_entry(dir, files[i], want, nwant, nm, n, &nm[n], &pt[n], e);
        if (rc > 0) n++;
    }
    io_free_list(files, nf);
    if (rc < 0) {
        io_free_list(nm, n);
        io_free_list(pt, n);
        return -1;
    }
    *names = nm;
    *paths = pt;
    return n;
}

int field_read_dir(const Mesh *m, const char *dir, const char *const *want, int nwant, Field **out, Err *e)
{
    char **names, **paths;
    int n = field_list_dir(dir, want, nwant, &names, &paths, e), k = 0;
    if (n < 0) return -1;
    Field *f = MEM_NEW(Field, n);
    while (k < n && !field_read(&f[k], m, paths[k], e)) k++;
    io_free_list(names, n);
    io_free_list(paths, n);
    if (k < n) {
        field_free_all(f, k);
        return -1;
    }
    *out = f;
    return n;
}

void field_free_all(Field *f, int n)
{
    for (int i = 0; i < n && f; i++) field_free(&f[i]);
    free(f);
}
