/*
** cut_impl.h: what the pieces of the cut-cell module share; included
** only by common/cut*.c (callers use cut.h).
**
**   cut.c       vertices, cut points on the grid edges (the grid's own
**               and each cell's view), snapping, corners on the surface,
**               boundary loops, cells, the assembled polyMesh
**   cut_face.c  grid faces: each cell's marching-squares polygon on a
**               face, the part two cells share and the walls of the rest
**   cut_staircase.c  method staircase: whole cells by their centres
**
** Points on a grid edge.  Edge (v, a) is the key 3 v + a of the cut-point
** table.  Its entry holds the grid's own point (from the crossings of the
** grid line, or put by snapping) unless nodef, and, when cells round the
** edge see it otherwise (the edge lies in a face of one part of the
** geometry and another part crosses it), a CutView with each such cell's
** own point.  The four cells round the edge are told apart by their quad:
** bit 0 set when the cell lies below the edge along the first axis across
** it ((a + 1) % 3), bit 1 along the second ((a + 2) % 3).  Equal points
** are one point (cut.c settles them before any face is made), and every
** grid-face polygon holds every point of an edge that lies on one of its
** sides (cut_face.c), so faces that meet along an edge hold the same
** points whichever cell's view placed them.
*/
#ifndef KIESEL_CUT_IMPL_H
#define KIESEL_CUT_IMPL_H

#include <stdint.h>
#include <stddef.h>

#include "cut.h"
#include "meshbuild.h"

#define MAXP 32 /* points of one grid-face polygon (8, and each edge's other points and crossings) */

typedef struct CutPt {
    int64_t key;    /* 3 v + axis, -1: empty slot */
    double s;       /* coordinate along the axis */
    int leaf;       /* leaf crossed, -1: unknown */
    int pt;         /* mesh point, -1 until used */
    int view;       /* the cells' own points: index into Ctx.views, -1: none */
    signed char at; /* -1: inside the edge; 0/1: on the lower/upper vertex */
    char dead;      /* removed by snapping */
    char nodef;     /* no point of the grid's own (only the cells' views) */
} CutPt;

/* The points of one edge as the cells round it see it, by quad. */
typedef struct CutView {
    double s[4];
    int leaf[4], pt[4];
    signed char at[4], has[4];
} CutView;

/* A point where chords of two cells' polygons on one grid face cross
   (cut_face.c), by the mesh points at the chords' ends. */
typedef struct CutCross {
    int a0, a1, b0, b1, pt;
} CutCross;

typedef struct Poly {
    int n;
    int pt[MAXP];
    int leaf[MAXP]; /* leaf of a cut point, -1 */
} Poly;

typedef struct WallFace {
    int patch;
    double n[3];
} WallFace;

typedef struct Ctx {
    const Geometry *g;
    int n[3], nv[3];
    const double *x[3];
    int64_t sv[3]; /* vertex strides */
    int64_t sc[3]; /* cell strides */
    char *cls;     /* per vertex: 1 fluid, 0 solid (2: snapping) */
    char *onsurf;  /* per vertex: 1 when on the surface (within snap) */
    float *level;  /* per vertex: |geometry_level|, or -1 not yet known (diagonal_touch) */
    unsigned char *lmask; /* per Cartesian cell: its fluid corners (bit q), local_masks */
    int *vpt;      /* per vertex: mesh point or -1 */
    int *cellid;   /* per Cartesian cell: new cell or -1 */
    CutPt *tab;
    size_t cap, cnt;
    CutView *views; /* the cells' own points of edges (CutPt.view) */
    size_t nviews, views_cap;
    CutCross *cross; /* crossing chords on grid faces */
    size_t ncross, cross_cap;
    double snap;
    int npatch_grid;
    MeshBuild b;
    WallFace *wall; /* boundary faces in order of addition */
    size_t nwall, wall_cap;
    double *cvol;         /* per new cell: its volume */
    double vref[3], vacc; /* the cut cell being built: reference, volume */
    CutStats *st;
} Ctx;

static inline const double *cut_ptx(const Ctx *c, int pt)
{
    return c->b.points + 3 * (size_t)pt;
}

static inline void cut_vertex_ijk(const Ctx *c, int64_t v, int ijk[3])
{
    ijk[0] = (int)(v % c->nv[0]);
    ijk[1] = (int)((v / c->nv[0]) % c->nv[1]);
    ijk[2] = (int)(v / ((int64_t)c->nv[0] * c->nv[1]));
}

/* Base vertex of Cartesian cell (i, j, k). */
static inline int64_t cut_cell_base(const Ctx *c, int i, int j, int k)
{
    return i + c->nv[0] * (j + (int64_t)c->nv[1] * k);
}

/* The cut-point table: open addressing on the edge key. */
static inline size_t cut_slot(const Ctx *c, int64_t key)
{
    uint64_t h = (uint64_t)key * 0x9E3779B97F4A7C15ull;
    return (size_t)(h >> 17) & (c->cap - 1);
}

/* The entry of edge key, whatever it holds, or NULL. */
static inline CutPt *cut_entry(const Ctx *c, int64_t key)
{
    for (size_t i = cut_slot(c, key);; i = (i + 1) & (c->cap - 1)) {
        if (c->tab[i].key == key) return &c->tab[i];
        if (c->tab[i].key < 0) return NULL;
    }
}

/* The entry of edge key when it holds a point of the grid's own. */
static inline CutPt *cut_find(const Ctx *c, int64_t key)
{
    CutPt *p = cut_entry(c, key);
    return p && !p->dead && !p->nodef ? p : NULL;
}

/* The mesh point of vertex v, made on first use. */
static inline int cut_vertex_point(Ctx *c, int64_t v)
{
    if (c->vpt[v] < 0) {
        int ijk[3];
        cut_vertex_ijk(c, v, ijk);
        double x[3] = {c->x[0][ijk[0]], c->x[1][ijk[1]], c->x[2][ijk[2]]};
        c->vpt[v] = meshbuild_point(&c->b, x);
    }
    return c->vpt[v];
}

/* cut.c */
/* The grid is a block grid whose patch names no surface takes. */
int cut_check_grid(const Mesh *grid, const Geometry *g, Err *e);
int cut_point(Ctx *c, CutPt *p);
int cut_cell_point(Ctx *c, int64_t key, int quad, int *leaf);
int cut_view_point(Ctx *c, const CutPt *p, int k);
void cut_wall_face(Ctx *c, const int *pt, const int *leaf, int n, int cell);
void cut_push_wall(Ctx *c, int patch, const double n[3]);

/* cut_face.c */
int cut_face_bits(int mask, int a, int hi);
int cut_face_poly(Ctx *c, int a, int64_t v0, int bits, int up, Poly *p);
void cut_grid_face(Ctx *c, const int ijk[3], int64_t ci, int64_t v0, int a, int hi, int cell, Poly *p);
int cut_box_faces(Ctx *c, const Mesh *grid, Err *e);
/* The side of the box (2 axis + hi) boundary face f of grid lies on, -1
   none. */
int cut_box_side(const CartGrid *cg, const Mesh *grid, int f);

/* cut_staircase.c: cut_mesh's method staircase (cut.h). */
int cut_staircase(const Mesh *grid, const Geometry *g, Mesh *out, CutStats *st, Err *e);

#endif
