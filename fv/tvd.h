/*
** tvd.h: second-order bounded convection, the schemes of divSchemes
** beyond the thesis's upwind (eq. 4.60): a face value that blends the
** upwind cell's value with the linear interpolation between the two cells
** by a TVD limiter of a gradient-based smoothness ratio, as OpenFOAM's
** limitedLinear and vanLeer (Jasak, Weller & Gosman 1999), with the
** far-upwind value bounded by the upwind cell's neighbourhood so that the
** face value obeys a local maximum principle on any grid (doc/theory.md,
** "Bounded second-order convection").
**
** For a face with flux phi (out of the owner) let U be the upwind cell, D
** the downwind one, x_U, x_D their values, d = node_D - node_U and w in
** [0, 1] the fraction of d at which the face centre projects (1/2 between
** equal Cartesian cells):
**
**   x_UU = clamp(x_D - 2 d . grad x_U,  [lo_U, hi_U])    virtual far-upwind
**   r    = (x_U - x_UU) / (x_D - x_U)                  = 2 d.grad/(x_D-x_U) - 1
**   x_f  = x_U + min(psi(r) w, 1) (x_D - x_U)
**
** grad x_U the least-squares gradient from the nodes of the face
** neighbours (weights 1/|d|^2; exact for linear fields on any grid), lo_U
** and hi_U the smallest and largest value of U, its face neighbours and
** its boundary values mirrored through their faces (2 x_b - x_U).  A
** cyclic face is an internal face of the periodic domain (fvmesh_across):
** its partner's owner is the cell across it, in the gradient, the bounds
** and the face value.  Limiters (Sweby's TVD region, psi <= 2r, psi = 0
** for r <= 0):
**
**   limitedLinear k:  psi = max(0, min(2r/k, 1))   (0 <= k <= 1; k = 1 most bounded)
**   vanLeer:          psi = (r + |r|) / (1 + |r|)
**
** Invariants, for every grid (cut, merged, Voronoi): x_f lies between x_U
** and x_D; a cell that is a local extremum of its neighbourhood
** (x_U <= lo_U or x_U >= hi_U) is upwinded (r <= 0), so an empty cell
** (x_U = 0 among values >= 0) emits nothing; and x_f - x_U <= (2w/k)
** (x_U - lo_U) <= (4w/k) x_U for values >= 0 (a mirror 2 x_b - x_U is
** >= -x_U), so a step keeps them >= 0 when dt/V sum_out phi (1 + 4w/k)
** <= 1 (vanLeer: k = 1; 1 + 2w/k away from the boundary).  Other
** boundary faces stay upwind: an inflow face takes the boundary state, an
** outflow face the cell's value (so the mass flow through a patch is the
** same product as with upwind).  Vectors are limited component by
** component.
*/
#ifndef KIESEL_TVD_H
#define KIESEL_TVD_H

#include "dict.h"
#include "err.h"
#include "fvmesh.h"

typedef enum { TVD_UPWIND, TVD_LIMITED_LINEAR, TVD_VAN_LEER } TvdKind;

typedef struct TvdScheme {
    TvdKind kind;
    double k;             /* limitedLinear's coefficient, 0 <= k <= 1 */
} TvdScheme;

/* The values of a divSchemes entry: "Gauss upwind", "Gauss limitedLinear
   k" or "Gauss vanLeer" (OpenFOAM's spelling).  Anything else, or k
   outside [0, 1], fails with the entry's file:line. */
int tvd_parse(const DictEntry *en, TvdScheme *s, Err *e);

/* The scheme as a divSchemes entry would spell it ("Gauss vanLeer"). */
void tvd_name(const TvdScheme *s, char *out, size_t n);

/* Per-grid data of the limited schemes, and their work space for up to
   ncomp values per cell. */
typedef struct Tvd {
    const FvMesh *f;
    int ncomp;            /* 0: upwind only, nothing allocated */
    double *ginv;         /* 9 ncells: inverse least-squares matrix (0 if singular) */
    double *wf;           /* nfaces: w of an internal or cyclic face seen
                             from its owner (0 on other faces) */
    double *grad;         /* 3 ncomp ncells */
    double *lo, *hi;      /* ncomp ncells */
} Tvd;

/* Sets up t on f for values of up to ncomp components (0: upwind only). */
void tvd_init(Tvd *t, const FvMesh *f, int ncomp);
void tvd_free(Tvd *t);

/* Least-squares gradients of xc (ncomp per cell, ncomp <= t->ncomp) into
   grad (3 per component per cell: grad[3 (ncomp c + k) + j]).  A cell whose
   neighbours' nodes do not span the grid's dimensions gets 0. */
void tvd_grad(const Tvd *t, const double *xc, int ncomp, double *grad);

/* The convection of xc (ncomp per cell; xb ncomp per boundary face) by the
   fluxes phi under scheme s: out[c] = sum over the faces of c of x_f phi_f
   (outward), as fvc_div_upwind, which it is for TVD_UPWIND. */
void tvd_div(Tvd *t, const TvdScheme *s, const double *phi, const double *xc, const double *xb, int ncomp,
             double *out);

#endif
