/*
** quality.h: grid quality measures (checkMesh's, for Kiesel's grids).
**
** Per-face and per-cell measures use OpenFOAM's definitions
** (primitiveMeshTools.C, v1912), so numbers can be compared with checkMesh:
**   non-orthogonality  angle between d = C_N - C_P and the face area vector
**                      S; the maximum is over faces, the "average" is
**                      acos(mean cos), as checkMesh prints it;
**   skewness           |C_f - (intersection of d with the face plane)|
**                      normalised by the face's extent in that direction
**                      (boundary faces use the face-normal projection of
**                      C_f - C_P for d);
**   aspect ratio       max/min of the per-axis sums of |S_k| over the
**                      cell's faces (non-empty axes only), and in 3-D also
**                      (sum |S_k|)/6 / V^(2/3).
** Faces of a cyclic patch are measured as internal faces, with the partner
** cell's centre translated by the offset between the paired face centres.
**
** Non-orthogonality and skewness are measured on OpenFOAM's geometry, not
** on the exact one, so that they are checkMesh's face for face
** (primitiveMeshFaceCentresAndAreas.C, primitiveMeshCellCentresAndVols.C):
**   face centre  a triangle's centroid; a polygon's is the mean of the
**                centroids of the triangles (p_i, p_i+1, m) about its point
**                average m, weighted by their UNSIGNED areas |n_i| (geom.c
**                signs them: a planar face not star-shaped about m, as cut
**                and merged faces can be, has a different centre);
**   cell centre  the centres (3/4 C_f + 1/4 c_e) of the pyramids on the
**                cell's faces with apex c_e, the average of its face
**                centres, weighted by their signed volumes S_f.(C_f - c_e):
**                the exact centroid when every face is planar and C_f its
**                exact centroid, not otherwise (warped faces, or the face
**                centres above).
** Orientation and volumes stay on the exact geometry (geom.h).
**
** A grid is broken (quality_check fails) when a cell is not closed
** (|sum of outward S| > 1e-12 of the cell's surface), a face normal does
** not point from its owner's centre to the neighbour's (or out of a
** boundary cell), a cell volume is not positive, the polyMesh ordering
** invariants (mesh_check) fail, or the cut-cell data contract does
** (cartesianCells, mesh_check_cartesian).  Non-orthogonality > 70 deg, skewness > 4
** and aspect ratio > 1000 are only counted (cut cells can have them).
*/
#ifndef KIESEL_QUALITY_H
#define KIESEL_QUALITY_H

#include "buf.h"
#include "err.h"
#include "mesh.h"

#define QUALITY_CLOSED_TOL 1e-12
#define QUALITY_NONORTH_SEVERE 70.0
#define QUALITY_SKEW_HIGH 4.0
#define QUALITY_ASPECT_HIGH 1000.0

typedef struct Quality {
    int ndims;                 /* geometric dimensions (3 minus empty directions) */
    int empty[3];              /* 1 for an empty (2-D) direction */
    double lo[3], hi[3];       /* bounding box */

    double vol_total;
    double vol_min, vol_max;   /* and the cells holding them */
    int vol_min_cell, vol_max_cell;
    int has_parent;            /* Cartesian extras present */
    double vol_min_ratio, vol_max_ratio;  /* vol_min (vol_max) cell / its parent's volume */
    double frac_min, frac_max;            /* min / max over cells of volume / parent volume */
    int ncut;                  /* cells smaller than their parent */
    int nmerged;               /* cells reaching outside their parent cell */

    double open_max;           /* max |sum S| / sum |S| */
    int nopen, open_cell;      /* cells above QUALITY_CLOSED_TOL, first one */
    double open_first;         /* its value */

    int norient, orient_face, orient_cell;  /* faces pointing the wrong way, first */
    int nnegvol, negvol_cell;  /* cells with volume <= 0, first */

    double nonorth_max, nonorth_avg;  /* degrees */
    int nonorth_face;          /* face of the maximum */
    int nnonorth;              /* faces above QUALITY_NONORTH_SEVERE */
    double skew_max;
    int skew_face, nskew;      /* face of the maximum; faces above QUALITY_SKEW_HIGH */
    double aspect_max;
    int aspect_cell, naspect;  /* cell of the maximum; cells above QUALITY_ASPECT_HIGH */

    /* Voronoi grids (cellSeed present): internal faces against the
       segments between their cells' seeds, which they must be normal to
       and bisect (ICCM^V, spec §2.4) */
    int has_seed;
    double seed_angle_max;     /* degrees */
    int seed_angle_face;
    double seed_offset_max;    /* largest distance of a face point from its bisector plane */
    int nseed_outside;         /* seeds not strictly inside their own cell */
} Quality;

/* cos of the non-orthogonality angle of area vector S against d (OpenFOAM:
   d.S/(|d||S| + ROOTVSMALL)). */
double quality_ortho(const double d[3], const double S[3]);
/* OpenFOAM's area vector S and centre C of the face pts[idx[0..n-1]]
   (see the top of this file). */
void quality_foam_face(const double *pts, const int *idx, int n, double S[3], double C[3]);
/* OpenFOAM's centre of a cell with nf faces: SC holds 6 values per face
   (area vector, then centre, from quality_foam_face), sgn +1 where the
   face points out of the cell, -1 where it points in. */
void quality_foam_cell(int nf, const double *SC, const signed char *sgn, double cc[3]);
/* OpenFOAM's face area vectors fS, face centres fC (3 per face) and cell
   centres cc (3 per cell) of m, as checkMesh computes them. */
void quality_foam_geometry(const Mesh *m, double *fS, double *fC, double *cc);
/* OpenFOAM's skewness of the face pts[idx[0..n-1]] with area vector S and
   centre C between cell centres cown and cnei; cnei NULL for a boundary
   face (primitiveMeshTools::faceSkewness, boundaryFaceSkewness). */
double quality_face_skew(const double *pts, const int *idx, int n, const double S[3], const double C[3],
                         const double cown[3], const double cnei[3]);
/* Per-face skewness and cosine of the non-orthogonality angle (NAN for
   boundary faces that are not cyclic) on OpenFOAM's geometry, as
   checkMesh's skewFaces and nonOrthoFaces sets select them; either
   array (m->nfaces values) may be NULL. */
void quality_face_measures(const Mesh *m, double *skewness, double *cosn);
/* Skewness of face f (points, Sf, Cf of the mesh) between cell centres
   cown and cnei. */
double quality_skewness(const Mesh *m, int f, const double cown[3], const double cnei[3]);
/* Skewness of boundary face f of the cell with centre cown. */
double quality_boundary_skewness(const Mesh *m, int f, const double cown[3]);
/* The aspect ratio of quality_cell from a cell's per-axis sums of |S_k|
   over its faces and its volume (for cells assembled from parts, such as
   merged clusters, whose faces are known without a mesh). */
double quality_aspect(const double mag[3], double vol, const int empty[3]);

/* Computes every measure.  Computes the cell faces and the geometry of m
   first when they are missing. */
void quality_measure(Mesh *m, Quality *q);
/* 0 when the grid is sound; else -1 with e naming the first bad cell of
   the first failed check ("cell 17: not closed, |sum S| = 3e-04 of
   surface").  *nfailed (may be NULL) receives the number of failed checks. */
int quality_check(const Mesh *m, const Quality *q, int *nfailed, Err *e);
/* checkMesh-like report of q (counts, box, volumes, measures). */
void quality_report(const Mesh *m, const Quality *q, Buf *out);

#endif
