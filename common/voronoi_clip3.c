/*
** voronoi_clip3.c: the 3-D clipper: a convex polyhedron cut by half-spaces.
**
** The polyhedron is a vertex array and polygons of vertex indices, each
** polygon labelled (the seed across it, or -1 - side for a box side); it
** starts as the box (voronoi_poly_box) and is clipped into a second buffer,
** the two swapping.  Each vertex is in, on (within eps of the plane) or
** out; nothing happens unless a vertex is out.  New vertices are made only
** on edges from an in to an out vertex, once per edge and parametrised
** from the in end, so the two polygons sharing the edge get the same
** point; the new face is every on or new vertex, sorted by angle about the
** plane normal (a pseudo-angle, monotone, cheaper than atan2).  So a plane
** that only touches the cell adds nothing, and the result is closed: every
** edge is used by exactly two of its polygons.
*/
#include "voronoi_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void poly_reserve(Poly *p, int nv, int nf, int ni)
{
    need(&p->v, &p->vcap, 3 * (size_t)nv, sizeof(double));
    need(&p->lab, &p->fcap, (size_t)nf, sizeof(int));
    need(&p->off, &p->ocap, (size_t)nf + 1, sizeof(int));
    need(&p->idx, &p->icap, (size_t)ni, sizeof(int));
}

void voronoi_clip3_free(Clip *c)
{
    for (int k = 0; k < 2; k++) {
        free(c->p[k].v);
        free(c->p[k].lab);
        free(c->p[k].off);
        free(c->p[k].idx);
    }
    free(c->d);
    free(c->cls);
    free(c->vmap);
    free(c->edge);
    free(c->capv);
    free(c->capk);
}

/* The box as the starting polyhedron; vertex v has bit 0 set for x = hi,
   bit 1 for y, bit 2 for z; faces in side order, outward by the right
   hand rule. */
void voronoi_poly_box(Clip *c, const double lo[3], const double hi[3])
{
    static const int face[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    c->cur = 0;
    Poly *p = &c->p[0];
    poly_reserve(p, 8, 6, 24);
    for (int v = 0; v < 8; v++)
        for (int a = 0; a < 3; a++) p->v[3 * v + a] = (v >> a) & 1 ? hi[a] : lo[a];
    p->nv = 8;
    p->nf = 6;
    p->ni = 24;
    p->off[0] = 0;
    for (int s = 0; s < 6; s++) {
        p->lab[s] = -1 - s;
        memcpy(p->idx + 4 * s, face[s], sizeof face[s]);
        p->off[s + 1] = 4 * (s + 1);
    }
}

/* Monotone in the angle of (x, y), in [0, 4): cheaper than atan2. */
static double pseudo_angle(double x, double y)
{
    double r = x / (fabs(x) + fabs(y));
    return y < 0 ? 3 + r : 1 - r;
}

/* The vertex where the plane crosses edge (in, out) of P, made once. */
static int edge_vertex(Clip *c, const Poly *P, Poly *Q, int a, int b)
{
    int in = c->cls[a] < 0 ? a : b, out = in == a ? b : a;
    for (int k = 0; k < c->ne; k++)
        if (c->edge[3 * k] == in && c->edge[3 * k + 1] == out) return c->edge[3 * k + 2];
    double t = c->d[in] / (c->d[in] - c->d[out]);
    const double *vi = P->v + 3 * in, *vo = P->v + 3 * out;
    double *w = Q->v + 3 * Q->nv;
    for (int k = 0; k < 3; k++) w[k] = vi[k] + t * (vo[k] - vi[k]);
    need(&c->edge, &c->ecap, 3 * ((size_t)c->ne + 1), sizeof(int));
    c->edge[3 * c->ne] = in;
    c->edge[3 * c->ne + 1] = out;
    c->edge[3 * c->ne + 2] = Q->nv;
    c->ne++;
    return Q->nv++;
}

/* Appends to Q the face of the vertices capv[0..n) (all on the plane of
   unit normal nrm), ordered counter-clockwise about nrm. */
static void cap_face(Clip *c, Poly *Q, int n, const double nrm[3], int lab)
{
    double m[3] = {0, 0, 0};
    for (int k = 0; k < n; k++)
        for (int a = 0; a < 3; a++) m[a] += Q->v[3 * c->capv[k] + a] / n;
    /* u perpendicular to nrm, v = nrm x u, so (u, v, nrm) is right-handed */
    int ax = fabs(nrm[0]) < fabs(nrm[1]) ? (fabs(nrm[0]) < fabs(nrm[2]) ? 0 : 2)
                                         : (fabs(nrm[1]) < fabs(nrm[2]) ? 1 : 2);
    double e[3] = {0, 0, 0}, u[3], v[3];
    e[ax] = 1;
    u[0] = nrm[1] * e[2] - nrm[2] * e[1];
    u[1] = nrm[2] * e[0] - nrm[0] * e[2];
    u[2] = nrm[0] * e[1] - nrm[1] * e[0];
    v[0] = nrm[1] * u[2] - nrm[2] * u[1];
    v[1] = nrm[2] * u[0] - nrm[0] * u[2];
    v[2] = nrm[0] * u[1] - nrm[1] * u[0];
    need(&c->capk, &c->ckcap, (size_t)n, sizeof(double));
    for (int k = 0; k < n; k++) {
        const double *p = Q->v + 3 * c->capv[k];
        double r[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
        double key = pseudo_angle(r[0] * u[0] + r[1] * u[1] + r[2] * u[2], r[0] * v[0] + r[1] * v[1] + r[2] * v[2]);
        int vk = c->capv[k], q = k;
        while (q > 0 && c->capk[q - 1] > key) {
            c->capk[q] = c->capk[q - 1];
            c->capv[q] = c->capv[q - 1];
            q--;
        }
        c->capk[q] = key;
        c->capv[q] = vk;
    }
    memcpy(Q->idx + Q->ni, c->capv, sizeof(int) * (size_t)n);
    Q->ni += n;
    Q->lab[Q->nf] = lab;
    Q->off[++Q->nf] = Q->ni;
}

/* Clips the cell by the half-space nrm.x <= off (nrm a unit vector),
   labelling the new face lab; eps: on-plane tolerance.  Returns 1 when
   something was cut off. */
static int clip3(Clip *c, const double nrm[3], double off, double eps, int lab)
{
    Poly *P = &c->p[c->cur], *Q = &c->p[1 - c->cur];
    need(&c->d, &c->dcap, (size_t)P->nv, sizeof(double));
    need(&c->cls, &c->ccap, (size_t)P->nv, 1);
    need(&c->vmap, &c->mcap, (size_t)P->nv, sizeof(int));
    int nout = 0;
    for (int k = 0; k < P->nv; k++) {
        const double *v = P->v + 3 * k;
        double s = nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2] - off;
        c->d[k] = s;
        nout += s > eps;
    }
    /* most planes of a lattice's neighbours only touch the cell */
    if (!nout) return 0;
    for (int k = 0; k < P->nv; k++) c->cls[k] = c->d[k] > eps ? 1 : c->d[k] < -eps ? -1 : 0;
    /* new vertices: at most one per edge, ni/2 edges */
    poly_reserve(Q, P->nv + P->ni / 2 + 1, P->nf + 1, 3 * P->ni + P->nv + 3);
    int nk = 0;
    for (int k = 0; k < P->nv; k++) {
        if (c->cls[k] > 0) {
            c->vmap[k] = -1;
            continue;
        }
        memcpy(Q->v + 3 * nk, P->v + 3 * k, 3 * sizeof(double));
        c->vmap[k] = nk++;
    }
    Q->nv = nk;
    Q->nf = Q->ni = 0;
    Q->off[0] = 0;
    c->ne = 0;
    for (int f = 0; f < P->nf; f++) {
        int s = P->off[f], e = P->off[f + 1], start = Q->ni;
        for (int q = s; q < e; q++) {
            int a = P->idx[q], b = P->idx[q + 1 < e ? q + 1 : s];
            if (c->cls[a] <= 0) Q->idx[Q->ni++] = c->vmap[a];
            if (c->cls[a] * c->cls[b] < 0) {
                int w = edge_vertex(c, P, Q, a, b);
                Q->idx[Q->ni++] = w;
            }
        }
        if (Q->ni - start >= 3) {
            Q->lab[Q->nf] = P->lab[f];
            Q->off[++Q->nf] = Q->ni;
        } else {
            Q->ni = start;
        }
    }
    int ncap = 0;
    need(&c->capv, &c->cvcap, (size_t)Q->nv, sizeof(int));
    for (int k = 0; k < P->nv; k++)
        if (c->cls[k] == 0) c->capv[ncap++] = c->vmap[k];
    for (int k = nk; k < Q->nv; k++) c->capv[ncap++] = k;
    if (ncap >= 3) cap_face(c, Q, ncap, nrm, lab);
    c->cur = 1 - c->cur;
    return 1;
}

/* Squared distance from x to the farthest vertex of P. */
double voronoi_poly_radius3(const Poly *P, const double *x)
{
    double r2 = 0;
    for (int k = 0; k < P->nv; k++) {
        double d = sq(P->v[3 * k] - x[0]) + sq(P->v[3 * k + 1] - x[1]) + sq(P->v[3 * k + 2] - x[2]);
        if (d > r2) r2 = d;
    }
    return r2;
}

/* Clips the cell by the bisector half-space of xi (the cell's seed) and
   xj, labelling the new face lab.  Returns the cell's new squared radius
   about xi, or r2 when nothing was cut. */
double voronoi_clip3_bisector(Clip *c, const double *xi, const double *xj, double eps, int lab, double r2)
{
    double n[3], m[3], len = 0;
    for (int a = 0; a < 3; a++) {
        n[a] = xj[a] - xi[a];
        m[a] = 0.5 * (xi[a] + xj[a]);
        len += n[a] * n[a];
    }
    len = sqrt(len);
    for (int a = 0; a < 3; a++) n[a] /= len;
    if (!clip3(c, n, n[0] * m[0] + n[1] * m[1] + n[2] * m[2], eps, lab)) return r2;
    return voronoi_poly_radius3(&c->p[c->cur], xi);
}
