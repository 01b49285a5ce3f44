/*
** gridio.c: output side of the grid tools (gridio.h).
**
** A grid is written into <dir>.tmp<pid> and committed with io_commit_dir,
** so an interrupted or failed write never leaves <dir> incomplete; the
** grid tools recover their -i and -o directories at start-up (the
** frame's args_recover, app/args.h, over io_recover_dir).
*/
#include "gridio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io.h"
#include "mem.h"

int gridio_write(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e)
{
    if (!strcmp(dir, "-")) return mesh_write(m, "-", w, e);
    /* "constant/polyMesh/" names the same directory; its temporary must
       be a sibling ("constant/polyMesh.tmp<pid>"), not a child */
    char *dst = mem_strdup(dir);
    for (size_t k = strlen(dst); k > 1 && dst[k - 1] == '/'; k--) dst[k - 1] = '\0';
    size_t l = strlen(dst) + 32;
    char *tmp = mem_alloc(l), *parent = mem_strdup(dst);
    /* the pid in the name lets io_recover_dir tell a dead run's leftovers
       from a concurrent writer's work in progress */
    snprintf(tmp, l, "%s.tmp%ld", dst, (long)getpid());
    char *slash = strrchr(parent, '/');
    int rc = 0;
    if (slash && slash != parent) {
        *slash = 0;
        rc = io_mkdir_p(parent, e);
    }
    io_rm_rf(tmp, NULL);
    if (!rc) rc = mesh_write(m, tmp, w, e);
    if (!rc) rc = io_commit_dir(tmp, dst, e);
    if (rc) io_rm_rf(tmp, NULL);
    free(tmp);
    free(parent);
    free(dst);
    return rc;
}
