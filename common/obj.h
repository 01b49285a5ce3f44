/*
** obj.h: Wavefront OBJ surfaces, optionally gzipped, read into a TriSurf.
**
** What is read: vertices (`v x y z`, with an optional weight w and/or
** the r g b colours some exporters append, all ignored), polygonal faces
** (`f`, corners written `v`, `v/vt`, `v/vt/vn` or `v//vn`, indices from
** 1, negative ones relative to the end of the list read so far), and the
** groups `g name` / `o name`.  Texture coordinates (`vt`), normals (`vn`),
** parameter vertices (`vp`), materials (`mtllib`, `usemtl`), smoothing
** groups (`s`), lines (`l`), points (`p`) and the other display
** statements are checked for form where they hold numbers, then ignored.
** Free-form geometry (`cstype`, `curv`, `surf`, ...) and `call` are
** refused: a surface that silently lost parts would be worse.
**
** Faces are triangulated by ear clipping in the plane of the face (its
** Newell normal), which reproduces OpenFOAM's fan from the first corner
** for every convex face and stays inside a non-convex planar one (an
** L-shaped face, say, where a fan would cover the notch); the triangles
** keep the face's corner order, hence its orientation.  Corners are
** then welded like an STL's (soup.h: bit-identical positions become one
** point), so files that repeat a vertex per face close up as well.
**
** Regions.  Each `g` or `o` statement starts a region named after its
** first name (OpenFOAM's triSurface takes the first name of `g` too);
** faces before any are in region "default" (the OBJ convention).  The
** regions become the TriSurf's tags and names, as STL solids do; a
** region that holds no face gets no tag.
**
** Errors name the file and line: an unknown statement, a malformed or
** non-finite coordinate, a face with fewer than 3 corners, an index 0 or
** out of range (positive indices may refer forward and are checked once
** the file is read), a malformed corner ("1/2/3/4", "1//"), a file with
** no faces.
*/
#ifndef KIESEL_OBJ_H
#define KIESEL_OBJ_H

#include <stddef.h>

#include "err.h"
#include "trisurf.h"

/* Reads path, or path.gz when path is absent; gzip data is inflated
   whatever the name.  s need not be initialised; it is empty after a
   failure. */
int obj_read(TriSurf *s, const char *path, Err *e);
/* Parses an OBJ held in memory (name for messages). */
int obj_parse(TriSurf *s, const char *data, size_t n, const char *name, Err *e);
/* 1 when data looks like an OBJ file: no NUL byte in its first 4 KB, and
   its first statement (after blank lines and # comments) is one of v,
   vt, vn, vp, f, g, o, s, l, p, mtllib, usemtl. */
int obj_sniff(const char *data, size_t n);

#endif
