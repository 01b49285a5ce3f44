/*
** interp.h: ICCM interpolation (spec granular-model.md §3, thesis §4.2) as
** precomputed sparse stencils (stencil.h): for every face the three
** points the scheme evaluates (eq. 4.60-4.64), once per grid.
**
** Points of face f (row 3 f + k of Interp.face), with n_f the unit normal
** out of the owner (fvmesh.h):
**   INTERP_CENTRE  x_f             the convective face velocity (eq. 4.61)
**   INTERP_PLUS    x_f + n_f ht_f  the neighbour's side of the face
**   INTERP_MINUS   x_f - n_f h_f   the owner's side
** so that the outward normal derivative is
**   d xi/dn (x_f) = [xi(PLUS) - xi(MINUS)] / (h_f + ht_f)        (eq. 4.62)
** On an internal face h_f = ht_f and this is the thesis's symmetric
** difference.  On a boundary face ht_f = 0: PLUS is the face centre,
** whose value is the boundary value (source ncells + b), and MINUS lies
** inside the owner at distance h_f: the thesis's one-sided difference
** (eq. 4.63, written there with the inner normal of the owner).  A
** boundary face's CENTRE row is its boundary value as well (eq. 4.61: xi_F
** at a boundary).  A face of an empty patch (2-D front and back) carries
** no flux; its three rows are empty (zero), and nothing reads them.  A
** cyclic face is an
** internal face of the periodic domain (fvmesh.h: h_f = ht_f, the
** partner's owner across it): its PLUS point is taken at its periodic
** image x_f + n_f ht_f + T_f inside the box (interp_face_point), and the
** partner face's rows are its own with PLUS and MINUS swapped.
**
** Eq. 4.61's face rule comes first for every method: on a face between two
** whole Cartesian cells (FvMesh.cartesian_face) CENTRE is the mean of the
** two cells, PLUS the neighbour and MINUS the owner.  On an internal face
** these are stored as the stencil's pair rows (stencil.h: the pairs are
** the internal faces' owner and neighbour), which hold no entries: read
** the rows through stencil_row or stencil_apply, never off/src/w
** directly.  Elsewhere the method of system/fvSchemes decides:
**
**   interpolationSchemes
**   {
**       default          shepard;     // shepard | multilinear | none
**       shepardCoeffs
**       {
**           beta             2;       // exponent of the weights   [OURS]
**           radius           1;       // R of eq. 4.28, metric d_h
**           boundarySources  off;     // boundary-face centres as sources
**       }
**   }
**
** shepard      modified Shepard (eq. 4.28-4.32), the default;
** multilinear  bi-/trilinear over the Cartesian centres, missing ones
**              reflected at the boundary (eq. 4.18-4.20);
** none         piecewise constant: MINUS the owner, PLUS the neighbour,
**              CENTRE their mean (the scheme upwinds the advected state
**              itself, eq. 4.60; the mean is what a caller that wants one
**              value gets).
** The design and the choices the thesis leaves open: doc/fv.md,
** "Interpolation", and the top of interp.c.
*/
#ifndef KIESEL_INTERP_H
#define KIESEL_INTERP_H

#include "dict.h"
#include "err.h"
#include "fvmesh.h"
#include "stencil.h"

enum { INTERP_SHEPARD, INTERP_MULTILINEAR, INTERP_NONE };
enum { INTERP_CENTRE, INTERP_PLUS, INTERP_MINUS, INTERP_NPOINTS };

typedef struct InterpOpts {
    int method;            /* INTERP_SHEPARD, ... */
    double beta;           /* Shepard exponent, > 0 (default 2) */
    double radius;         /* Shepard R in the metric d_h, > 0 (default 1) */
    int boundary_sources;  /* boundary-face centres as Shepard sources */
    const char *file;      /* where the scheme was chosen (messages), or NULL */
    int line;
} InterpOpts;

/* The keywords of interpolationSchemes and of shepardCoeffs (for -help). */
extern const DictKey interp_keys[];
extern const DictKey interp_shepard_keys[];

/* Names of the methods, NULL-terminated, in enum order. */
extern const char *const interp_method_names[];

void interp_opts_default(InterpOpts *o);
/* Reads the interpolationSchemes sub-dictionary of fvSchemes (absent:
   the defaults).  An unknown method or keyword, or beta or radius not
   positive, fails with file and line. */
int interp_read_opts(const Dict *fvschemes, InterpOpts *o, Err *e);

typedef struct InterpStats {
    int nrows;             /* rows built (3 per face) */
    int ncartesian;        /* faces under eq. 4.61's mean rule */
    int ngrown;            /* Shepard points whose radius had to grow */
    double radius_max;     /* the largest radius used */
    int nreflect;          /* multilinear: missing sources reflected */
    int ndegenerate;       /* ... whose reflection line missed the
                              boundary plane (ghost = master value) */
    int nfallback;         /* multilinear points without any present
                              Cartesian source: Shepard's row instead */
    int nlin;              /* PLUS/MINUS rows next to walls corrected to
                              linear exactness (interp_lin.c) */
    int nlinskip;          /* ... left as they were: sources not spanning */
    double mean_size;      /* stencil size (entries per row, a pair row's
                              counted; rows of faces that carry flux): mean, max */
    int max_size;
} InterpStats;

typedef struct Interp {
    InterpOpts o;
    const FvMesh *f;
    Stencil face;          /* INTERP_NPOINTS rows per face */
    InterpStats st;
    struct InterpIndex *ix;  /* the search structures (interp.c) */
} Interp;

/* Builds the face stencils of f with method o.  grid names the grid in
   messages (NULL: "the grid").  Multilinear needs the Cartesian parent
   grid and the cut-cell data contract (Mesh.cartcells; a plain block grid,
   one whole cell per Cartesian cell, needs none): without them building
   fails, naming the grid and the scheme. */
int interp_init(Interp *ip, const FvMesh *f, const InterpOpts *o, const char *grid, Err *e);
void interp_free(Interp *ip);

/* Row of point k (INTERP_CENTRE ...) of face i in ip->face. */
static inline int interp_row(int i, int k) { return INTERP_NPOINTS * i + k; }

/* The point k of face i. */
void interp_face_point(const FvMesh *f, int i, int k, double x[3]);

/* Appends to s the row of the method at any point x of the domain (no
   face rule); need is the least number of Shepard sources (1 or 2).
   Returns the row's index. */
int interp_point(Interp *ip, const double x[3], int need, Stencil *s);

#endif
