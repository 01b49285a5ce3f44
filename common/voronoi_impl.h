/*
** voronoi_impl.h: what the files of the Voronoi grid builder share: its
** types and the functions one file calls in another.  Not part of the
** library's interface (that is voronoi.h): only voronoi*.c include it.
** The design is described in voronoi.c, each part in its own file.
*/
#ifndef KIESEL_VORONOI_IMPL_H
#define KIESEL_VORONOI_IMPL_H

#include "mem.h"
#include "voronoi.h"

#include <stddef.h>
#include <stdint.h>

/* Grows *p (of *cap elements of size elem) to hold need elements. */
static inline void need(void *p, int *cap, size_t need_n, size_t elem)
{
    if (need_n <= (size_t)*cap) return;
    size_t c = *cap > 0 ? (size_t)*cap : 16;
    while (c < need_n) c += c / 2 + 16;
    *(void **)p = mem_realloc(*(void **)p, c * elem);
    *cap = (int)c;
}

static inline double sq(double x) { return x * x; }

/* ---- types ---- */

/* Seeds sorted into a uniform grid over the box; seeds outside the box go
   to the border buckets, which only puts them in a shell nearer than they
   are, so the search stays exact. */
typedef struct Buckets {
    int n[3];
    double org[3], h[3];
    int *start;   /* nbuckets+1 */
    int *seed;    /* nseeds, bucket by bucket, in seed order */
} Buckets;

typedef struct Cand {
    double d2;
    int j;
} Cand;

/* The neighbour search of one seed; the clipper reads cand[0..n). */
typedef struct Search {
    Cand *cand;
    int n, cap;
} Search;

typedef struct Poly {
    int nv, nf, ni;
    int vcap, fcap, ocap, icap;
    double *v;    /* 3*nv */
    int *lab;     /* nf: seed across the face, or -1 - side */
    int *off;     /* nf+1 */
    int *idx;
} Poly;

typedef struct Clip {
    Poly p[2];
    int cur;
    double *d;
    signed char *cls;
    int *vmap;
    int dcap, ccap, mcap;
    int *edge;    /* 3 per new vertex: the in end, the out end, the vertex */
    int ecap, ne;
    int *capv;    /* the new face's vertices */
    double *capk; /* and their angles */
    int cvcap, ckcap;
} Clip;

/* Convex polygon in the (u, v) plane, counter-clockwise; edge k runs from
   vertex k to k+1 and has label lab[k]. */
typedef struct Poly2 {
    int n, cap, lcap;
    double *x;    /* 2*n */
    int *lab;
} Poly2;

typedef struct Clip2 {
    Poly2 p[2];
    int cur;
    double *d;
    int dcap;
} Clip2;

/* Global points, found by position.  Every distinct coordinate triple
   handed in is kept as an entry with the point it became, chained in a
   uniform grid (the seed buckets shifted by half a bucket, so the corners
   of a Cartesian lattice's cells fall on bucket centres); a query within
   tol of a bucket's side also looks across it, so every entry within tol
   is seen.  The nearest entry wins, and an exact copy of an earlier query
   is at distance 0: a vertex computed bitwise identically by two cells
   always gets the same point, whatever was added in between.  Chains grow
   in the order cells are made, so a query touches memory made recently
   (a hash of the coordinates would miss the cache on every query). */
typedef struct Weld {
    double tol, org[3], h[3];
    int n[3];
    int *head;        /* per bucket: last entry, -1 */
    int *id, *next;   /* per entry: id >= 0, the point it made (its
                         coordinates are that point's); < 0, -1 - its
                         place among the extras */
    int nent, icap, ncap;
    double *xx;       /* extras (entries that joined an earlier point): 3 each */
    int *xid;         /* and that point */
    int nx, xxcap, xicap;
    double *pts;      /* stride per point (2-D: 6, the copy at hi filled later) */
    int stride, npts, pcap;
} Weld;

/* Voronoi vertices by name: a vertex of seed i's cell on exactly dim
   faces (3 in 3-D, 2 in 2-D) is the vertex of the sorted set {i, labels},
   the same set every cell around it sees (unless the vertex is
   degenerate).  Naming them makes the welding consistent even where their
   positions are ill-conditioned (nearly cospherical seeds): the first cell
   to meet a vertex welds it by position, every later one gets the same
   point by name.  Names are chained on their lowest seed. */
typedef struct Names {
    int *head;        /* per seed: last entry, -1 */
    int32_t *key;     /* 4 per entry */
    int *id, *next;
    int nent, kcap, icap, ncap;
} Names;

typedef struct Store {
    int ncells;
    int *cell_off;            /* ncells+1: faces of each cell */
    int nf, fcap, lcap, ocap;
    int *lab;                 /* per face, sorted inside a cell */
    int *off;                 /* nf+1 */
    int ni, icap;
    int *idx;
} Store;

/* 2-D cells as they come out of the clipper: for cell c the polygon's
   global 2-D points gid[off[c]..off[c+1]), counter-clockwise, and the
   label of the edge from each point to the next.  The prism's faces are
   made from these only when the mesh is written. */
typedef struct Rings {
    int *off;                 /* ncells+1 */
    int *gid, *lab;
    int n, gcap, lcap;
} Rings;

typedef struct Build {
    const VoronoiInput *in;
    Buckets g;
    Search s;
    Clip c3;
    Clip2 c2;
    Weld w;
    Names names;
    Store st;
    double L, eps;
    int *gid;           /* global point of each cell vertex */
    int gcap;
    int *vlab;          /* per cell vertex: face count, three face labels */
    int vlcap;
    int *tmp;
    int tcap;
    Rings rg;           /* 2-D: the cells as polygons */
    const int *cell_of; /* per seed: its cell, or -1 */
} Build;

/* Directed edges of one cell, counted in a small open hash: a closed cell
   uses each edge once in each direction. */
typedef struct Edges {
    uint64_t *key;
    int *cnt;       /* +1 per use a->b with a < b, +16 per use b->a */
    int *used;
    int cap, nused, ucap;
} Edges;

/* One face of a cell as the assembly sees it: a stored polygon, reversed
   when the cell across stored it. */
typedef struct CFace {
    int f, rev;
} CFace;

typedef struct Assembly {
    const VoronoiInput *in;
    Store *st;
    const int *cell_of, *seed_of;
    double *pts;      /* coordinates of the final point numbers */
    int *beg, *len;   /* per stored face: its points idx[beg..beg+len) */
    double tol;       /* weld distance */
    Edges edges;
    CFace *cf;
    int ncf, cfcap;
    int *tpts, *ends; /* scratch: a polygon being repaired, unmatched ends */
    double *tt;
    int tcap, ecap, ttcap;
    int ndropped;
} Assembly;

/* Each cell's own faces (those it does not take reversed from a lower
   cell) come sorted by label, and cells are numbered in seed order, so
   when every own internal face goes to a higher cell the internal faces
   arrive sorted by (owner, neighbour): the mesh can be written in place,
   each boundary face into its patch's range.  That skips meshbuild's
   copies of every face and point (on big 2-D grids, touching that much
   fresh memory costs more than making the cells).  Otherwise (an own face
   towards a lower cell that has no face back) meshbuild sorts. */
typedef struct Plan {
    int direct;        /* 1: internal faces arrive in order */
    int empty;         /* a cell without faces, or -1 */
    int nface, nint;   /* faces, internal faces */
    size_t nidx, iint; /* their points, those of internal faces */
    int *pface;        /* per patch: faces */
    size_t *pidx;      /* per patch: their points */
} Plan;

/* Where the next face goes: internal faces first, then patch by patch. */
typedef struct Cursor {
    int *face;         /* npatches + 1: next face of the internal faces, each patch */
    size_t *idx;       /* and its first point */
} Cursor;

/* ---- voronoi_search.c ---- */

void voronoi_buckets_build(Buckets *g, const VoronoiInput *in);
void voronoi_buckets_free(Buckets *g);
int voronoi_bucket_axis(const Buckets *g, int a, double x);
double voronoi_shell_dist(const Buckets *g, const int b[3], int k, const double x[3]);
void voronoi_shell_collect(Search *s, const Buckets *g, const VoronoiInput *in, int self, const int b[3], int k,
                           const double x[3], double r2max);

/* ---- voronoi_clip3.c ---- */

void voronoi_clip3_free(Clip *c);
void voronoi_poly_box(Clip *c, const double lo[3], const double hi[3]);
double voronoi_poly_radius3(const Poly *P, const double *x);
double voronoi_clip3_bisector(Clip *c, const double *xi, const double *xj, double eps, int lab, double r2);

/* ---- voronoi_clip2.c ---- */

void voronoi_poly2_reserve(Poly2 *p, int n);
void voronoi_clip2_free(Clip2 *c);
void voronoi_poly2_push(Poly2 *Q, double u, double v, int lab);
double voronoi_clip2_bisector(Clip2 *c, const double *xi, const double *xj, int ua, int va, double eps, int lab,
                              double r2);

/* ---- voronoi_weld.c ---- */

void voronoi_weld_init(Weld *w, const Buckets *g, double tol, int flat, int stride, size_t expect);
void voronoi_weld_free(Weld *w);
int voronoi_weld_point(Weld *w, const double x[3]);
void voronoi_names_init(Names *t, int nseeds, size_t expect);
void voronoi_names_free(Names *t);
int voronoi_vertex_name(int i, const int *lab, int dim, int32_t k[4]);
int voronoi_weld_vertex(Weld *w, Names *t, const int32_t *k, int s, const double x[3]);

/* ---- voronoi_store.c ---- */

void voronoi_store_free(Store *s);
void voronoi_store_face(Store *s, int lab, const int *pts, int n, int rev);
void voronoi_store_sort_cell(Store *s, int f0, int **tmp, int *tcap);
int voronoi_store_find(const Store *s, int c, int lab);
int voronoi_store_cell(const Store *s, int f);
void voronoi_rings_free(Rings *r);

/* ---- voronoi_assemble.c ---- */

void voronoi_poly_area(const double *pts, const int *idx, int n, int rev, double S[3]);
int voronoi_face_superseded(const Assembly *A, int f, int i, int *g);
int voronoi_cell_face_list(Assembly *A, int c);
void voronoi_measure_cell(const Assembly *A, int c, VoronoiStats *vs);
int voronoi_face_other(const Assembly *A, int f);
int voronoi_assemble(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e);

/* ---- voronoi_write.c ---- */

void voronoi_plan_faces(Assembly *A, Plan *pl);
void voronoi_plan_free(Plan *pl);
void voronoi_mesh_alloc(const VoronoiInput *in, const Plan *pl, int ncells, Mesh *out, Cursor *cur);
int voronoi_write_direct(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs);
int voronoi_write_meshbuild(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs, Err *e);
double voronoi_ortho_max(const Mesh *m, const VoronoiInput *in, const int *seed_of);

/* ---- voronoi_prisms.c ---- */

int voronoi_assemble2(Build *B, const int *cell_of, const int *seed_of, Mesh *out, VoronoiStats *vs, Err *e);

#endif
