/*
** fvmesh.h: the finite-volume view of a grid: every derived quantity the
** discretisation needs, computed once per grid (spec granular-model.md
** §2.6, §4.2).
**
** Layout: flat arrays indexed by cell and by face, as the Mesh's.  Owned
** cells come first (0 .. nowned-1) and halo cells after (nowned .. ncells-1),
** so a distributed run (PETSc, MPI) only appends halo cells and the loops
** over owned cells stay as they are; a serial run has no halo cells.
**
** Conventions: face normals point out of the owner (OpenFOAM's); the
** thesis writes its fluxes with the inner normal of the cell C at hand
** (spec §2.6, "sign convention"), which the assembly takes care of.  The
** node of a cell is the point its unknowns live at: its Voronoi seed on a
** Voronoi grid (ICCM^V), its centroid otherwise (mesh_cell_node).
**
** Distances of eq. 4.62-4.63: h_f = min(|(x_C - x_f).n_f|, |(x_F - x_f).n_f|)
** on an internal face (C, F its two nodes), the owner's normal distance on
** a boundary face; ht_f = h_f on internal faces and 0 on boundary faces, so
** the face-normal derivative is [xi(x_f + n h_f) - xi(x_f - n ht_f)] /
** (h_f + ht_f), symmetric inside and one-sided at a boundary.
**
** Cyclic faces are internal faces of the periodic domain: face i of a
** cyclic patch pairs with face i of its neighbourPatch (OpenFOAM's rule;
** fv/bc.c checks the geometry), the owner N of the partner face is the
** periodic neighbour, and its node moved back by the translation T_f =
** x_partner - x_f lies across the face (fvmesh_across).  Such a face gets
** h_f = ht_f = the smaller of the two nodes' normal distances, and
** cartesian_face when both cells are whole, exactly as an internal face.
*/
#ifndef KIESEL_FVMESH_H
#define KIESEL_FVMESH_H

#include "cartcells.h"
#include "err.h"
#include "mesh.h"

typedef struct FvMesh {
    Mesh *m;              /* the grid; geometry and cell faces are filled */
    int ncells, nowned;   /* all cells, the owned ones first */
    int nfaces, ninternal, nboundary;
    int empty_axis;       /* 0..2 for a 2-D grid (empty front and back), else -1 */
    double *mag_sf;       /* nfaces: |S_f| */
    double *nf;           /* 3 nfaces: unit normal, out of the owner */
    const double *node;   /* 3 ncells: the cell's node (seed or centroid):
                             the Mesh's cell_seed or cell_centre itself */
    double *h, *ht;       /* nfaces: h_f and ht_f of eq. 4.62-4.63 */
    int *face_patch;      /* nboundary: patch of boundary face ninternal + i */
    int nslots;           /* boundary faces that are not empty */
    int *bslot;           /* nboundary: boundary face b's index among those
                             (in face order), -1 for an empty face: where
                             per-face boundary data without the empty
                             faces keep it (fv/bc.h) */
    char *empty_face;     /* nfaces: 1 on faces of empty patches (no flux) */
    char *cartesian_face; /* nfaces: 1 between two whole Cartesian cells
                             (eq. 4.61: the face value is the mean),
                             cyclic faces included */
    int *cyc_face;        /* nboundary: the partner face of a cyclic face,
                             else -1 */
    int *cyc_base;        /* npatches: where a cyclic patch's translations
                             start in cyc_shift, else -1 */
    double *cyc_shift;    /* 3 per face of a cyclic patch: its periodic
                             translation (fvmesh_cyclic_shift) */
    double hcart[3];      /* smallest Cartesian spacing per axis, or 0 */
} FvMesh;

/* Builds the view of m (geometry and cell faces computed when missing).
   Fails, with the reason in e, on a grid with a degenerate face or cell
   (zero area or volume) or a node on a face's plane. */
int fvmesh_init(FvMesh *f, Mesh *m, Err *e);
void fvmesh_free(FvMesh *f);

/* The end of the set-up: frees what only building the scheme reads, once
   every builder has run (bc_init, bc_check_open, interp_init, hydro_init,
   fvm_pattern and fvm_init, tvd_init): FvMesh's nf, h, ht and
   cartesian_face, and the Mesh's face_centre, boundary_normal and cell
   face lists (cell_off, cell_faces), all then NULL: about 220 bytes a
   cell of a 3-D block grid.  What the time steps and the writers read
   stays: the areas, volumes, nodes, owner and neighbour, the faces and
   points, the flags, the periodic translations (fvmesh_across and
   fvmesh_cyclic_shift keep working).  interp_point, which builds at the
   points of the faces, cannot be called afterwards. */
void fvmesh_end_setup(FvMesh *f);

/* Cartesian data contract present (cartesianGrid and cartesianCells)? */
int fvmesh_has_cartesian(const FvMesh *f);

/* The cell across face i and its node, moved by the periodic translation
   for a cyclic face (the neighbour's node on an internal face); -1 on
   other boundary faces (x untouched). */
int fvmesh_across(const FvMesh *f, int i, double x[3]);

/* Is face i coupled to a cell across it (internal or cyclic)? */
static inline int fvmesh_two_sided(const FvMesh *f, int i)
{
    return i < f->ninternal || f->cyc_face[i - f->ninternal] >= 0;
}

/* The periodic translation of cyclic face i: partner centre - own centre. */
void fvmesh_cyclic_shift(const FvMesh *f, int i, double T[3]);

/* Total volume of the owned cells. */
double fvmesh_volume(const FvMesh *f);

#endif
