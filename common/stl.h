/*
** stl.h: STL files, ascii and binary, optionally gzipped, read into and
** written from a TriSurf.
**
** Reading detects the format from the content (a binary file's size is
** 84 + 50 n; an ascii file starts with "solid" and holds "facet"), reads
** `file.gz` when `file` is absent, and welds bit-identical corners into
** shared points (trisurf_from_soup).  Every ascii `solid <name>` block
** becomes a tag with that name (OpenFOAM calls them regions).  Errors name
** the file and, for ascii, the line.  Facet normals must be three
** numbers (nan allowed) but are otherwise ignored: the orientation comes
** from the corner order.  OBJ files and the choice between the two
** formats: obj.h, surface.h.
*/
#ifndef KIESEL_STL_H
#define KIESEL_STL_H

#include <stddef.h>

#include "err.h"
#include "trisurf.h"

/* s need not be initialised; it is overwritten (and empty after a
   failure). */
int stl_read(TriSurf *s, const char *path, Err *e);
/* Parses an STL held in memory (name for messages). */
int stl_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e);
/* 1 when data has exactly the size of a binary STL (84 + 50 n bytes, n
   the count at byte 80): the test that decides before any other. */
int stl_is_binary(const char *data, size_t n);
/* Writes atomically; binary != 0 for binary STL; a path ending in ".gz"
   is gzipped. */
int stl_write(const TriSurf *s, const char *path, int binary, Err *e);

#endif
