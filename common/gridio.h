/*
** gridio.h: writing a grid tool's output: the polyMesh directory,
** atomically, or the stream form on stdout.  The tools' options, banner
** and summary around it are the application frame's (app/gridtool.h).
*/
#ifndef KIESEL_GRIDIO_H
#define KIESEL_GRIDIO_H

#include "err.h"
#include "mesh.h"

/* Writes m to dir: "-" streams to stdout; otherwise the files go into
   the sibling dir.tmp<pid> that io_commit_dir then swaps with dir, so a
   failed or killed write leaves an existing grid untouched, and two
   concurrent writers each commit a complete grid (the last one stays). */
int gridio_write(const Mesh *m, const char *dir, const MeshWriteOpts *w, Err *e);

#endif
