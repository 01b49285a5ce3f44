/*
** cartcells.h: the cut-cell data contract: what every Cartesian cell of
** the parent grid (cartesianGrid) became, and what every cell is made of
** (Mesh.cartcells, file constant/polyMesh/cartesianCells).
**
** Why: the interpolated cut-cell method takes its multilinear sources at
** the Cartesian cell centres and must know which are missing (slave or
** outside centres are filled by reflection, spec granular-model.md §3.2,
** eq. 4.19/4.20); modified Shepard takes the centroids of non-slave cells,
** a merged cluster counting once (§3.2, §2.5).  cellParent keeps one
** parent per cell and mergeMap only the last merge; this keeps it all.
**
** Roles of a Cartesian cell K (codes as written in the file):
**   0 outside  no cell: solid (cut grids), or holds no seed (Voronoi);
**   1 whole    a grid cell by itself, uncut: its cell is the box K;
**   2 cut      a cut cell that took no slaves (Voronoi: holds seeds but
**              is not one box-shaped cell, see below);
**   3 master   the part of a merged cell named by cellParent (its largest
**              member, the one that took the slaves, spec §2.5);
**   4 slave    merged into a master's cell.
** Each K stores its cell (-1 outside) and the fluid volume of its part;
** each cell c lists its parents, the Cartesian cells of its parts, in
** ascending order (a compact list-of-lists: parent_off, parent).
**
** Invariants on cut and merged grids (mesh_check_cartesian): every
** Cartesian cell has one role; K names c exactly when K is among c's
** parents; a cell with one parent has it whole or cut, a cell with more
** has one master and slaves only; a whole part's volume is its box's; the
** parents' volumes sum to the cell's volume.  Merging composes: the
** members of a new cluster keep their Cartesian cells, the one cellParent
** names becomes master, every other one a slave.
**
** On a Voronoi grid (cell_seed present; ICCM^V, spec §2.4, no merging) a
** Cartesian cell is not a piece of a cell: the grid is a bucket index of
** the cells' nodes, which is what a Shepard stencil search needs.  Each
** cell has exactly one parent, the Cartesian cell holding its seed; a
** Cartesian cell holding several seeds (boundary layers) names the cell
** whose seed is nearest its centre and stores the summed volume of all
** the cells it holds.  whole: it holds one seed, its own centre (a kept
** Cartesian seed), and that cell is its box (so its centre is a source
** of a multilinear stencil); cut: it holds seeds otherwise; outside: no
** seed (solid, or covered by boundary cells: a missing source).  The
** volumes add up per Cartesian cell instead of per cell.
*/
#ifndef KIESEL_CARTCELLS_H
#define KIESEL_CARTCELLS_H

#include "err.h"
#include "mesh.h"

enum { CART_OUTSIDE, CART_WHOLE, CART_CUT, CART_MASTER, CART_SLAVE, CART_NROLES };

/* Relative volume tolerance of the builders and of checkGrid: a whole
   part's volume, and a sum of parts, agree with the cells to this times
   the Cartesian cells' volume. */
#define CARTCELLS_TOL 1e-12

/* "outside", "whole", ... ("?" for a bad code). */
const char *cartcells_role_name(int role);

void cartcells_free(CartCells *cc);

/* From m->cell_parent with one cell per Cartesian cell (a cut grid):
   vol[c] each cell's fluid volume; whole[c] != 0 marks uncut cells, or
   whole NULL: a cell is whole when its volume is its box's to
   CARTCELLS_TOL.  Returns -1 (cc left empty) when m has no cartesianGrid
   or cell_parent, or cell_parent is not one cell per Cartesian cell. */
int cartcells_build(const Mesh *m, const double *vol, const unsigned char *whole, CartCells *cc);

/* The contract of a merged grid out (ncells, cell_parent, cart set) from
   its input's, in (one input cell per Cartesian cell), and newid[c], the
   output cell of input cell c. */
void cartcells_merge(const CartCells *in, const int *newid, const Mesh *out, CartCells *cc);

/* The contract of a Voronoi grid m (cart, cell_seed, cell_vol set):
   centre_seed[c] != 0 when cell c's seed is a kept Cartesian centre. */
void cartcells_voronoi(const Mesh *m, const unsigned char *centre_seed, CartCells *cc);

/* Checks the invariants above with relative volume tolerance tol; needs
   m->cell_vol (mesh_geometry).  The message names the first Cartesian
   cell (index and i j k) or cell that breaks one. */
int mesh_check_cartesian(const Mesh *m, double tol, Err *e);

/* The file, for mesh_io.c: the body of cartesianCells (after the FoamFile
   header), ascii or binary; and reading it back (sizes and ranges
   checked, the invariants left to mesh_check_cartesian).  Needs m's
   cartesianGrid and cell count. */
struct Buf;
struct Dict;
void cartcells_put(struct Buf *b, const Mesh *m, int binary);
size_t cartcells_size_hint(const Mesh *m, int binary);
int cartcells_read(Mesh *m, const struct Dict *d, const char *name, Err *e);

#endif
