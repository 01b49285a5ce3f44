/*
** cad.h: geometry from any file gmsh opens (.geo, .step/.stp, .brep,
** .stl, .msh, ...) through gmsh's C API (gmshc.h).
**
** cad_open loads the file into a gmsh model of its own, makes a surface
** triangulation when the model has none (CAD files: gmsh generates a 2-D
** mesh with the requested element size), and returns it as a TriSurf whose
** tag per triangle is the gmsh surface entity it belongs to.  The model
** stays loaded so cad_normal can give the exact CAD normal at any point
** (gmshModelGetClosestPoint + gmshModelGetNormal on that entity) where
** the model has a parametrisation; for discrete surfaces (STL, MSH) it
** returns 0 and the caller uses the triangle normal.
**
** gmsh keeps global state; this module is the only place that touches it.
** Every Cad owns a distinct model name and selects it before each call,
** so several Cad objects can be open at once.  gmsh is initialised on the
** first cad_open (with its terminal output off) and finalised when the
** last Cad is closed.  Not thread-safe (gmsh is not).
*/
#ifndef KIESEL_CAD_H
#define KIESEL_CAD_H

#include "err.h"
#include "trisurf.h"

typedef struct Cad Cad;

/* Opens path; size = target triangle edge length for CAD models (<= 0:
   1/50 of the bounding-box diagonal); ignored for files that carry a
   triangulation.  Fills s (need not be initialised) with the welded
   triangulation (gmsh node tags define the welding), consistently
   oriented outward when closed.  Returns NULL with e set on failure
   (unreadable file, no surfaces, gmsh error text included). */
Cad *cad_open(const char *path, double size, TriSurf *s, Err *e);

/* Exact outward unit normal of CAD surface `tag` at the point of that
   surface nearest to x; sign chosen to agree with the triangulation's
   outward normal `ref`.  Returns 1 when exact, 0 when the surface has no
   parametrisation (n left untouched). */
int cad_normal(Cad *c, int tag, const double x[3], const double ref[3], double n[3]);

/* Surface point of entity `tag` nearest to x; 1 when exact, else 0. */
int cad_closest(Cad *c, int tag, const double x[3], double p[3]);

void cad_close(Cad *c);

#endif
