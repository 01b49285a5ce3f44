/*
** merge.h: merging of small cut cells (spec granular-model.md §2.5,
** thesis §3.3).
**
** A slave is a cell with V <= M_V V_cart, where V_cart is the volume of
** its Cartesian parent (cell_parent, cart).  Its master is a face
** neighbour chosen by the Cartesian grid normal criterion (§3.3.2.1):
** n_S is the area-weighted inner normal of the slave's immersed boundary
** faces (boundary faces that do not lie on a plane of its parent
** Cartesian cell), the merge axis is j = argmax_i |n_i| (Approach 3, the
** default) or argmax_i |n_i h_i| (Approach 2), and the master is the
** neighbour across the slave's face(s) on the parent's side in direction
** sign(n_j).  Fallbacks [GAP in the thesis; ours, doc/theory.md]: the other
** axes in descending |n_i| (or |n_i h_i|), each in direction sign(n_i);
** among candidates a non-slave is preferred over a slave; a slave may
** take a slave (a chain).  Clusters are then re-examined: a cluster whose
** volume is still below M_V times the Cartesian volume of its largest
** member is treated as one slave with the cluster's immersed faces, and
** merged again, until every cluster meets the bound or has no neighbour
** left (at most max_iter rounds); such cells are reported with a reason.
**
** The merged cell is the union polyhedron: the faces shared inside a
** cluster are removed, all other faces are kept unchanged (eq. 4.59),
** its cell_parent is its largest member's, and its volume is V_M + V_S,
** its centroid the members' volume-weighted one.  Total volume is
** unchanged.
**
** Quality pass [ours, doc/theory.md §7]: after the volume rounds, a
** cluster with a face whose OpenFOAM skewness (quality.h; boundary faces
** by the face-normal projection) exceeds max_skewness is merged with the
** face neighbour whose union has the lowest maximum skewness over the
** faces that change (the union's faces, from the union's centroid), among
** the unions passing the face-pyramid check, when that lowers it; up to
** max_iter rounds; when no union with one neighbour lowers it, unions
** with two are tried.  Empty and cyclic faces are not measured.
** Skewness and the centres it is measured from are checkMesh's
** (quality.h: OpenFOAM's face and cell centres, not the centroids).
**
** Repair [ours, doc/theory.md §7]: a cluster that fails a checkMesh
** check the cut grid passed (a face skewness above max_skewness and above
** the face's in the cut grid, a face pyramid not positive, an internal
** face at 90 degrees or more, aspect ratio above 1000) is dissolved into
** its input cells, until none fails; then the cells below the bound
** merge again into passing unions only.  So with max_skewness in (0, 4]
** the output fails no checkMesh check the input passed, except where a
** cell below min_ratio has no passing union: it takes a sound one (face
** pyramids positive) and may leave a skewed face, because a solver runs
** with a skewed face but not with a cell 1e-6 of its neighbours.  A cluster still
** above max_skewness (a face the cut grid had) is reported with
** MERGE_SKEWNESS.
*/
#ifndef KIESEL_MERGE_H
#define KIESEL_MERGE_H

#include "dict.h"
#include "err.h"
#include "mesh.h"

enum { MERGE_NORMAL = 0, MERGE_NORMAL_H = 1 };   /* |n_i|, |n_i h_i| */
enum { MERGE_OK = 0, MERGE_NO_NEIGHBOUR, MERGE_ITER_LIMIT, MERGE_SKEWNESS };

typedef struct MergeOpts {
    double threshold;   /* M_V, default 0.5 */
    int criterion;      /* MERGE_NORMAL (default) or MERGE_NORMAL_H */
    int max_iter;       /* default 10; also bounds the quality rounds */
    double max_skewness;   /* quality pass limit, default 4 (QUALITY_SKEW_HIGH); 0 = off */
    double min_ratio;   /* below this V / V_cart a sound union is taken when no clean one is; default 0.01 */
} MergeOpts;

typedef struct MergeStats {
    int ncells_in, ncells_out;
    int nslaves;              /* cells below the bound before merging */
    int nclusters;            /* output cells made of more than one cell */
    int niter;
    double ratio_min_before;  /* min V / V_cart over cells */
    double ratio_min_after;   /* min V / V_cart(largest member) */
    int ratio_min_cell;       /* output cell of ratio_min_after */
    double aspect_max_before, aspect_max_after;   /* quality.h's measure */
    double vol_before, vol_after;
    int nunresolved;          /* output cells still below the bound */
    int *unresolved;          /* their output cell numbers */
    int *reason;              /* MERGE_* for each */
    int nskew_merged;         /* merges made by the quality pass */
    int nundone;              /* clusters the repair dissolved */
    int nclean_merged;        /* merges made after the repair */
    int nforced;              /* of those, sound but not clean (cells below min_ratio) */
    double skew_max_cut;      /* max face skewness of the input (OpenFOAM's, quality.h) */
    double skew_max_before;   /* after the volume rounds */
    double skew_max_after;    /* and in the output */
} MergeStats;

void merge_opts_default(MergeOpts *o);
/* Keywords of system/mergeCellsDict (for -help and checking). */
extern const DictKey merge_keys[];
/* Names of the criteria, by MERGE_*: "normal", "normalSpacing". */
extern const char *const merge_criteria[];
/* Reads the dictionary at path into o, over the defaults: fails with
   file:line on an unknown keyword or a value out of range. */
int merge_read_opts(const char *path, MergeOpts *o, Err *e);
const char *merge_reason_name(int reason);

/* Merges the small cells of in (cell_parent and cart required) into out
   (need not be initialised).  out->merge_map gets in's cell count
   entries: the output cell of each input cell.  boundary_normal, when
   present, follows the boundary faces.  out comes without cell faces and
   geometry (mesh_geometry computes them; the statistics come from the
   input).  Fills st (free with merge_stats_free). */
int merge_mesh(const Mesh *in, const MergeOpts *o, Mesh *out, MergeStats *st, Err *e);
void merge_stats_free(MergeStats *st);

#endif
