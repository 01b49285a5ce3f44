/*
** interp_impl.h: what interp.c (options, search index, modified Shepard,
** the face rows) shares with interp_ml.c (multilinear with reflection
** ghosts).  No other module includes it.
**
** The search index is a bucket grid: the Cartesian parent grid when the
** mesh has one (the data contract's grid is a bucket index of the nodes,
** cartcells.h), else a uniform grid of about one cell per bucket over the
** mesh's bounds.  Sources (cells 0 .. ncells-1, boundary faces ncells + b
** when boundarySources is on) sit in the bucket holding their position,
** so a query visits a bounded number of buckets and building is O(N).
** With cyclic patches a query also visits the windows of x + T for every
** translation T, so Shepard finds the sources across a periodic side.
*/
#ifndef KIESEL_INTERP_IMPL_H
#define KIESEL_INTERP_IMPL_H

#include "interp.h"

#define INTERP_MAXTRANS 6   /* three cyclic pairs, each patch its own way */

typedef struct InterpIndex {
    int nb[3];          /* buckets per axis */
    double *bx[3];      /* nb[k] + 1 bucket edges per axis */
    int *boff, *bsrc;   /* sources of bucket i + nb0 (j + nb1 k) */
    int ncells, nsrc;   /* cells; cells + boundary faces (ids as in stencil.h) */
    double *spos;       /* 3 nsrc: position of each source */
    double *sh;         /* 3 nsrc: its metric h_s (eq. 4.32) */
    char *is_src;       /* nsrc: is it a Shepard source? */
    double hmax[3];     /* largest h_s per axis (search window) */
    int active[3];      /* axes interpolated along (not the empty one) */
    int block;          /* multilinear on a block grid without cartesianCells */
    int per[3];         /* multilinear: a cyclic pair spans the box along axis k */
    int pshift[3][3];   /* its lattice shift from the min side's image to the max side */
    int ntrans;         /* cyclic translations (partner - own face centre) */
    double trans[INTERP_MAXTRANS][3];
    char *near_wall;    /* ncells: 2 a wall cell, 1 its face neighbour (interp_lin.c) */
    int *cand;          /* scratch of a query */
    double *cw;
    size_t ccap;
} InterpIndex;

/* Bucket (or lattice) interval of coordinate v on edges x[0..n]: the i in
   0 .. n-1 with x[i] <= v < x[i+1], clamped. */
int interp_locate(const double *x, int n, double v);

/* Appends Shepard's row at x (need: least number of sources) to s. */
void interp_shepard(Interp *ip, const double x[3], int need, Stencil *s);
/* Appends the multilinear row at x to s. */
void interp_multilinear(Interp *ip, const double x[3], Stencil *s);
/* The wall cells and their neighbours (ix->near_wall). */
void interp_lin_init(Interp *ip);
/* Are face i's PLUS and MINUS rows corrected to linear exactness? */
int interp_lin_wants(const Interp *ip, int i);
/* Corrects the row being built in ip->face, at point x of face i, to
   reproduce linear functions (interp_lin.c). */
void interp_lin_correct(Interp *ip, int i, const double x[3]);
/* Can multilinear run on this grid?  Else the reason in e. */
int interp_ml_check(const Interp *ip, const char *grid, Err *e);

#endif
