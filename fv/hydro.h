/*
** hydro.h: a well-balanced face pressure and gravity force for an
** isothermal gas p = RsT rho under uniform gravity g (doc/theory.md,
** "Well-balanced pressure and gravity").
**
** The continuous rest state is rho = C exp(a.x), a = g / RsT: grad p =
** rho g.  Written with its equilibrium variable w = rho exp(-a.x), which
** is constant at rest (hydrostatic reconstruction with equilibrium
** variables: Kaeppeli & Mishra 2014, "Well-balanced schemes for the Euler
** equations with gravitation", J. Comput. Phys. 259), every cell C
** carries its own hydrostatic profile through its node x_C:
**
**   p_C(x) = RsT rho_C exp(a.(x - x_C)).
**
** Face pressure: each source s of the face's CENTRE row (interp.h; the two
** cells of a Cartesian face, the stencil elsewhere) is reconstructed to
** the face centre x_f along its own profile before the weights act,
**
**   p_f = sum_s w_s exp(a.(x_f - x_s)) p_s,
**
** x_s the source's node (a boundary source: its face centre) at the
** periodic image nearest x_f, so only displacements of the order of the
** stencil enter, never exp(a.x) itself (no overflow on large domains; on
** a cyclic face the node across is moved by the translation).  The
** partner of a cyclic face repeats that face's weights, so the two share
** p_f and the pressure force conserves momentum as before.
**
** Boundary face b whose pressure comes from the cells (a wall, a zero
** gradient): from the owner P and its face neighbours j,
**
**   p_b = sum_j c_j exp(a.(x_b - x_j)) p_j,   sum_j c_j = 1,
**   sum_j c_j a.x_j = a.x_b,
**
** c the smallest change (least squares) of the owner alone (c_P = 1) that
** puts the weighted nodes at the face's potential.  Any c summing to one
** keeps the rest state; the potential condition also keeps a pressure
** that is uniform along gravity to O((a h)^2) where the owner's profile
** alone, p_P exp(a.(x_b - x_P)), is off by a.(x_b - x_P) = O(a h): the
** inclined channel, whose gravity along the walls is carried by the wall
** shear, not by the pressure, lost a third of its density accuracy that
** way.  With a = 0, or a neighbourhood that does not spread in potential,
** or weights beyond sum |c_j| = 3, c is the owner alone.
**
** Gravity: the force on cell C is its own profile integrated over its
** closed surface (every face, empty ones too, S_f outward),
**
**   F_C = sum_f p_C(x_f) S_f = RsT rho_C sum_f expm1(a.(x_f - x_C)) S_f
**
** (sum_f S_f = 0), which is rho_C g V_C to second order (divergence
** theorem) and equals sum_f p_f S_f exactly when rho_C exp(-a.x_C) is one
** constant: the discrete rest state of every grid.  Since the weights of
** a row sum to one, p_f = RsT C exp(a.x_f) on every face there, whatever
** the stencil.  With a = 0 the weights are the CENTRE row's, bit for
** bit, and the gravity vectors are zero: with g = 0 nothing is stored
** (w, off, grav NULL, no wall rows), hydro_face is the CENTRE row itself
** and hydro_boundary the owner's pressure, the same numbers as the stored
** weights gave.
**
** Memory (g != 0): one double per entry of the CENTRE rows (a pair row,
** stencil.h, counts its two), nfaces + 1 offsets, three doubles per cell
** and a row of the owner's neighbourhood per boundary face; none with
** g = 0 (about 85 bytes a cell of a 3-D block grid).
**
** Barotropic profiles (hydro_init_profile; model granular, doc/theory.md
** "Well-balanced granular gravity").  Where the rest profile is not an
** exponential, the caller evaluates it: a HydroProfile gives the pressure
** q_s(phi) at potential difference phi = g.(x - x_s) along source s's own
** rest profile (q_s(0) its pressure).  The rows are then stored as the
** weights themselves and, beside each, its potential g.(x_f - x_s), and
**   p_f = max(0, sum_s w_s q_s(g.(x_f - x_s))),
**   p_b = sum_j c_j q_j(g.(x_b - x_j))         (the same rows c as above),
**   F_C = sum_f (q_C(g.(x_f - x_C)) - q_C(0)) S_f,
** with the same discrete rest state: where the profiles of all cells are
** one profile, every source gives the same p_f and F_C = sum_f p_f S_f.
** A face pressure is never negative (a granular medium takes no tension):
** where sources with profiles of different kinds meet at a free surface
** (model granular's linear profiles p_s + c_s phi, negative above a
** half-empty cell), a negative p_f would pull the grains into the vacuum.
** Memory: two doubles an entry of the CENTRE rows and of the wall rows,
** three a face and one a cell.
*/
#ifndef KIESEL_HYDRO_H
#define KIESEL_HYDRO_H

#include "fvmesh.h"
#include "interp.h"

typedef struct Hydro {
    const FvMesh *f;
    const Interp *ip;
    double a[3];       /* g / RsT */
    int *off;          /* nfaces + 1: face i's weights are w[off[i] ..
                          off[i+1]-1], one per source of its CENTRE row, in
                          stencil_row's order; NULL when g = 0 */
    double *w;         /* the CENTRE rows' weights times exp(a.(x_f - x_s));
                          NULL when g = 0 (the rows' own weights) */
    Stencil wall;      /* nboundary rows: the pressure of boundary face b
                          from the cells (walls, zero gradient); none (off
                          NULL) when g = 0: the owner's */
    double *grav;      /* 3 ncells: sum_f expm1(a.(x_f - x_C)) S_f; NULL
                          when g = 0 (zero) or barotropic */
    int barotropic;    /* hydro_init_profile: w and wall hold the rows'
                          own weights, the potentials below beside them */
    double *phi;       /* off[nfaces]: g.(x_f - x_s) of each entry of w */
    double *wphi;      /* the wall rows' entries' g.(x_b - x_j) */
    double *gphi;      /* 2 nfaces: g.(x_f - x_owner), g.(x_f - x_neighbour) */
    double *reach;     /* ncells: max |g.(x_f - x_C)| over C's faces that
                          are not empty (how far a profile is carried) */
} Hydro;

/* A barotropic rest profile: at(ctx, s, phi) is the pressure at potential
   difference phi along source s's profile (s < ncells a cell, else
   boundary face s - ncells), at(ctx, s, 0) its own pressure. */
typedef struct HydroProfile {
    double (*at)(const void *ctx, int s, double phi);
    const void *ctx;
} HydroProfile;

/* The weights of the grid f and the face stencils ip for gravity g and
   p = RsT rho (g = 0: today's face weights, no gravity). */
void hydro_init(Hydro *h, const FvMesh *f, const Interp *ip, const double g[3], double RsT);
/* The rows and potentials of f and ip for gravity g and profiles given at
   each use (g = 0: as hydro_init with g = 0). */
void hydro_init_profile(Hydro *h, const FvMesh *f, const Interp *ip, const double g[3]);
void hydro_free(Hydro *h);

/* p_f of face i from the cell pressures pc (ncells) and the boundary
   pressures pb (one per boundary face). */
double hydro_face(const Hydro *h, int i, const double *pc, const double *pb);

/* The force of the face pressures p_f = hydro_face on every cell:
   out[3c .. 3c+2] = sum over the faces of c (empty ones aside) of p_f S_f,
   outward.  fvc_pressure_force of those p_f, the same sums in the same
   order, without an array of them (8 bytes a face). */
void hydro_force(const Hydro *h, const double *pc, const double *pb, double *out);

/* The pressure of boundary face b taken from the cells (a wall, a zero
   gradient) from the cell pressures pc. */
double hydro_boundary(const Hydro *h, int b, const double *pc);

/* The same three with barotropic profiles (hydro_init_profile), and the
   gravity force F_C into grav (3 ncells). */
double hydro_face_profile(const Hydro *h, int i, const HydroProfile *q);
void hydro_force_profile(const Hydro *h, const HydroProfile *q, double *out);
double hydro_boundary_profile(const Hydro *h, int b, const HydroProfile *q);
void hydro_gravity_profile(const Hydro *h, const HydroProfile *q, double *grav);

#endif
