/*
** surface.c: STL or OBJ, by name and content.  See surface.h for the
** rule; the readers themselves are stl.c and obj.c.
**
** The file is read once (io_read_file, which inflates gzip) and the
** bytes go to the reader the rule picks: rules 1, 3 and 4 look at the
** inflated content, rule 2 at the name actually read.
*/
#include "surface.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "io.h"
#include "obj.h"
#include "stl.h"

/* name ends in suffix, in any case. */
static int ends_with(const char *name, size_t n, const char *suffix)
{
    size_t m = strlen(suffix);
    if (n < m) return 0;
    for (size_t i = 0; i < m; i++)
        if (tolower((unsigned char)name[n - m + i]) != suffix[i]) return 0;
    return 1;
}

int surface_obj_name(const char *name)
{
    size_t n = strlen(name);
    if (ends_with(name, n, ".gz")) n -= 3;
    return ends_with(name, n, ".obj");
}

SurfaceFormat surface_format(const char *data, size_t n, const char *name)
{
    if (stl_is_binary(data, n)) return SURFACE_STL;
    if (name && surface_obj_name(name)) return SURFACE_OBJ;
    if (obj_sniff(data, n)) return SURFACE_OBJ;
    return SURFACE_STL;
}

int surface_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e)
{
    if (surface_format(data, n, name) == SURFACE_OBJ) return obj_parse(s, data, n, name, e);
    return stl_parse(s, data, n, name, e);
}

int surface_read(TriSurf *s, const char *path, Err *e)
{
    trisurf_init(s);
    Buf b;
    buf_init(&b);
    char *found = NULL;
    if (io_read_file(path, &b, &found, e)) return -1;
    int rc = surface_parse(s, b.p, b.n, found ? found : path, e);
    free(found);
    buf_free(&b);
    return rc;
}
