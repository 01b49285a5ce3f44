/*
** voronoi_clip2.c: the 2-D clipper: a convex polygon cut by half-planes.
**
** The polygon lies in the plane normal to the flat axis, counter-clockwise,
** and each edge carries a label (the seed across it, or -1 - side).  As in
** 3-D (voronoi_clip3.c) a vertex is in, on (within eps) or out, nothing
** happens unless one is out, and the new edge, labelled with the cutting
** seed, joins the crossing points (or on vertices); edges that survive keep
** their labels.
*/
#include "voronoi_impl.h"

#include <math.h>
#include <stdlib.h>

void voronoi_poly2_reserve(Poly2 *p, int n)
{
    need(&p->x, &p->cap, 2 * (size_t)n, sizeof(double));
    need(&p->lab, &p->lcap, (size_t)n, sizeof(int));
}

void voronoi_clip2_free(Clip2 *c)
{
    for (int k = 0; k < 2; k++) {
        free(c->p[k].x);
        free(c->p[k].lab);
    }
    free(c->d);
}

void voronoi_poly2_push(Poly2 *Q, double u, double v, int lab)
{
    Q->x[2 * Q->n] = u;
    Q->x[2 * Q->n + 1] = v;
    Q->lab[Q->n++] = lab;
}

/* Clips by nrm.x <= off in the plane (nrm a unit 2-vector). */
static int clip2(Clip2 *c, const double nrm[2], double off, double eps, int lab)
{
    Poly2 *P = &c->p[c->cur], *Q = &c->p[1 - c->cur];
    need(&c->d, &c->dcap, (size_t)P->n, sizeof(double));
    int nout = 0;
    for (int k = 0; k < P->n; k++) {
        double s = nrm[0] * P->x[2 * k] + nrm[1] * P->x[2 * k + 1] - off;
        c->d[k] = s;
        nout += s > eps;
    }
    if (!nout) return 0;
    voronoi_poly2_reserve(Q, P->n + 2);
    Q->n = 0;
    for (int k = 0; k < P->n; k++) {
        int k1 = k + 1 < P->n ? k + 1 : 0;
        double da = c->d[k], db = c->d[k1];
        int ca = da > eps ? 1 : da < -eps ? -1 : 0, cb = db > eps ? 1 : db < -eps ? -1 : 0;
        const double *a = P->x + 2 * k, *b = P->x + 2 * k1;
        if (ca <= 0) voronoi_poly2_push(Q, a[0], a[1], ca == 0 && cb > 0 ? lab : P->lab[k]);
        if (ca < 0 && cb > 0) {
            double t = da / (da - db);
            voronoi_poly2_push(Q, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), lab);
        } else if (ca > 0 && cb < 0) {
            double t = db / (db - da);
            voronoi_poly2_push(Q, b[0] + t * (a[0] - b[0]), b[1] + t * (a[1] - b[1]), P->lab[k]);
        }
    }
    c->cur = 1 - c->cur;
    return 1;
}

/* Clips the cell by the bisector half-plane of xi (the cell's seed) and xj
   (3-D points; ua, va the axes of the plane), labelling the new edge lab.
   Returns the cell's new squared radius about xi, or r2 when nothing was
   cut. */
double voronoi_clip2_bisector(Clip2 *c, const double *xi, const double *xj, int ua, int va, double eps, int lab,
                              double r2)
{
    double n[2] = {xj[ua] - xi[ua], xj[va] - xi[va]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1]);
    n[0] /= len;
    n[1] /= len;
    double off = n[0] * 0.5 * (xi[ua] + xj[ua]) + n[1] * 0.5 * (xi[va] + xj[va]);
    if (!clip2(c, n, off, eps, lab)) return r2;
    const Poly2 *P = &c->p[c->cur];
    r2 = 0;
    for (int k = 0; k < P->n; k++) {
        double d = sq(P->x[2 * k] - xi[ua]) + sq(P->x[2 * k + 1] - xi[va]);
        if (d > r2) r2 = d;
    }
    return r2;
}
