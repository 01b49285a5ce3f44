/*
** csg.h: the CSG tree behind a Geometry (geometry.h), shared by the
** three files that implement geometry.h and by no other:
**   csg.c              the tree and its evaluation: inside, level,
**                      crossings, normals, nearest leaf, exact volume;
**   geometry_dict.c    reading system/geometryDict into a tree;
**   geometry_sample.c  points on the flow domain's boundary.
** Callers outside these see only geometry.h's queries on the domain.
**
** Leaves are primitives (Shape, in their own coordinates, with the
** affine map x = A l + b to global coordinates) or triangulated surfaces
** (TriSurf, from STL, OBJ or gmsh, already in global coordinates); inner
** nodes are union, intersection and difference (the first operand minus
** the others).  Any node may be complemented (neg).
*/
#ifndef KIESEL_CSG_H
#define KIESEL_CSG_H

#include "geometry.h"
#include "shape.h"

struct Cad;
struct TriSurf;

/* Crossings kept on the stack before a query allocates. */
#define GEO_STACK 64

enum { G_PRIM, G_TRI, G_UNION, G_INTER, G_DIFF };

struct GeoNode {
    int op;                  /* G_* */
    int neg;                 /* complement */
    int leaf;                /* leaf id (G_PRIM, G_TRI) */
    /* G_PRIM */
    Shape shape;
    int has_xf;
    double A[9], Ai[9], b[3];   /* global = A local + b; Ai = A^-1 */
    double det;
    double lip;              /* 1 / |Ai|_2: the local level times lip is
                                1-Lipschitz in global coordinates */
    /* G_TRI */
    struct TriSurf *tri;
    struct Cad *cad;
    /* inner nodes */
    int nkids;
    GeoNode **kids;
};

GeoNode *csg_node_new(int op);
void csg_node_free(GeoNode *n);
/* Sets a primitive's map x = A l + b (its inverse, determinant and
   Lipschitz factor with it). */
void csg_node_set_map(GeoNode *n, const double A[9], const double b[3]);

/* Appends a surface (returns its index) or a leaf of surface `surface`
   to g's lists. */
int csg_add_surface(Geometry *g, const char *name, const char *type, int flow_inside, int line);
void csg_add_leaf(Geometry *g, GeoNode *n, int surface, int sign);

void csg_mat_vec(const double A[9], const double x[3], double y[3]);
void csg_unit(double n[3]);
double csg_dist3(const double a[3], const double b[3]);

/* Global point -> a primitive's own coordinates. */
void csg_to_local(const GeoNode *n, const double x[3], double l[3]);
/* A leaf's own outward normal at (near) x, in global coordinates. */
void csg_leaf_normal(const GeoNode *n, const double x[3], double nv[3]);
/* Point of primitive leaf n's surface nearest to x, in global
   coordinates (flattened onto g's plane in 2-D). */
void csg_leaf_closest(const Geometry *g, const GeoNode *n, const double x[3], double c[3]);

#endif
