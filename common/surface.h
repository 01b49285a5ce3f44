/*
** surface.h: triangulated surface files, STL or Wavefront OBJ, told
** apart by name and content and read into a TriSurf.
**
** The rule, in order:
**   1. data of exactly a binary STL's size (84 + 50 n bytes, n the count
**      in bytes 80-83) is STL;
**   2. a name ending in ".obj" (or ".obj.gz", any case) is OBJ;
**   3. data that looks like an OBJ (obj_sniff: text whose first
**      statement is an OBJ keyword) is OBJ, whatever the name;
**   4. anything else is STL (ascii "solid ...", or the STL reader's
**      message about what it found instead).
** An ascii OBJ is never taken for a binary STL: its bytes 80-83 are text
** (each at least 0x09), so rule 1 would need a file of more than 7.5 GB
** whose size matched by chance.  Rule 2 gives a damaged OBJ the OBJ
** reader's message (file:line) rather than the STL reader's.
*/
#ifndef KIESEL_SURFACE_H
#define KIESEL_SURFACE_H

#include <stddef.h>

#include "err.h"
#include "trisurf.h"

typedef enum { SURFACE_STL, SURFACE_OBJ } SurfaceFormat;

/* 1 when name ends in ".obj" or ".obj.gz" (any case): rule 2. */
int surface_obj_name(const char *name);
/* The format the rule above picks for data read from name. */
SurfaceFormat surface_format(const char *data, size_t n, const char *name);
/* Parses data held in memory (name for messages and rule 1). */
int surface_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e);
/* Reads path, or path.gz when path is absent (gzip data is inflated
   whatever the name; rule 1 looks at the name without ".gz").  s need
   not be initialised; it is empty after a failure. */
int surface_read(TriSurf *s, const char *path, Err *e);

#endif
