/*
** voronoi_weld.c: the global points of the grid, found by position and by
** name (voronoi.c, pass 1).
**
** By position (Weld): a point closer than the weld distance to an earlier
** one is that one, the nearest; an exact copy of an earlier query is at
** distance 0 and always gets the earlier answer.  By name (Names, 3-D): a
** vertex on exactly three faces is named by the sorted set of its seed and
** the three labels, which every cell around it sees; the first cell to meet
** a name welds it by position, later cells get the same point by name, so
** welding stays consistent where positions are ill-conditioned (nearly
** cospherical seeds).  The data structures' own comments (voronoi_impl.h)
** say how the look-ups stay cache-friendly.
*/
#include "voronoi_impl.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void voronoi_weld_init(Weld *w, const Buckets *g, double tol, int flat, int stride, size_t expect)
{
    memset(w, 0, sizeof *w);
    w->tol = tol;
    w->stride = stride;
    size_t nb = 1;
    for (int a = 0; a < 3; a++) {
        /* 2-D: every point is at lo along the flat axis: one layer */
        w->n[a] = a == flat ? 1 : g->n[a] + 1;
        w->h[a] = g->h[a];
        w->org[a] = g->org[a] - 0.5 * g->h[a];
        nb *= (size_t)w->n[a];
    }
    w->head = mem_alloc(sizeof(int) * nb);
    memset(w->head, 0xff, sizeof(int) * nb);
    need(&w->id, &w->icap, expect, sizeof(int));
    need(&w->next, &w->ncap, expect, sizeof(int));
    need(&w->pts, &w->pcap, (size_t)stride * expect, sizeof(double));
}

void voronoi_weld_free(Weld *w)
{
    free(w->head);
    free(w->id);
    free(w->next);
    free(w->xx);
    free(w->xid);
    free(w->pts);
}

static int weld_axis(const Weld *w, int a, double x)
{
    double t = (x - w->org[a]) / w->h[a];
    if (!(t > 0)) return 0;
    if (t >= w->n[a]) return w->n[a] - 1;
    return (int)t;
}

/* The number of the point at x (made when there is none within tol). */
int voronoi_weld_point(Weld *w, const double x[3])
{
    int k[3], lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        k[a] = weld_axis(w, a, x[a]);
        lo[a] = weld_axis(w, a, x[a] - w->tol);
        hi[a] = weld_axis(w, a, x[a] + w->tol);
    }
    int best = -1;
    double bd = w->tol * w->tol;
    for (int iz = lo[2]; iz <= hi[2]; iz++)
        for (int iy = lo[1]; iy <= hi[1]; iy++)
            for (int ix = lo[0]; ix <= hi[0]; ix++)
                for (int q = w->head[ix + w->n[0] * (iy + w->n[1] * iz)]; q >= 0; q = w->next[q]) {
                    int id = w->id[q];
                    const double *p;
                    if (id >= 0) {
                        p = w->pts + (size_t)w->stride * (size_t)id;
                    } else {
                        p = w->xx + 3 * (size_t)(-1 - id);
                        id = w->xid[-1 - id];
                    }
                    double d2 = sq(p[0] - x[0]) + sq(p[1] - x[1]) + sq(p[2] - x[2]);
                    if (d2 == 0) return id;
                    if (d2 <= bd) {
                        bd = d2;
                        best = id;
                    }
                }
    int q = w->nent++;
    need(&w->id, &w->icap, (size_t)w->nent, sizeof(int));
    need(&w->next, &w->ncap, (size_t)w->nent, sizeof(int));
    if (best < 0) {
        need(&w->pts, &w->pcap, (size_t)w->stride * ((size_t)w->npts + 1), sizeof(double));
        memcpy(w->pts + (size_t)w->stride * (size_t)w->npts, x, 3 * sizeof(double));
        best = w->npts++;
        w->id[q] = best;
    } else {
        need(&w->xx, &w->xxcap, 3 * ((size_t)w->nx + 1), sizeof(double));
        need(&w->xid, &w->xicap, (size_t)w->nx + 1, sizeof(int));
        memcpy(w->xx + 3 * (size_t)w->nx, x, 3 * sizeof(double));
        w->xid[w->nx] = best;
        w->id[q] = -1 - w->nx++;
    }
    int *head = &w->head[k[0] + w->n[0] * (k[1] + w->n[1] * k[2])];
    w->next[q] = *head;
    *head = q;
    return best;
}

void voronoi_names_init(Names *t, int nseeds, size_t expect)
{
    memset(t, 0, sizeof *t);
    t->head = mem_alloc(sizeof(int) * (size_t)nseeds);
    memset(t->head, 0xff, sizeof(int) * (size_t)nseeds);
    need(&t->key, &t->kcap, 4 * expect, sizeof(int32_t));
    need(&t->id, &t->icap, expect, sizeof(int));
    need(&t->next, &t->ncap, expect, sizeof(int));
}

void voronoi_names_free(Names *t)
{
    free(t->head);
    free(t->key);
    free(t->id);
    free(t->next);
}

/* The sorted name of the vertex of seed i on faces lab[0..dim); box sides
   are negative, so they sort first; unused places are INT32_MAX.  Returns
   the lowest seed of the name. */
int voronoi_vertex_name(int i, const int *lab, int dim, int32_t k[4])
{
    int n = 0;
    for (int q = -1; q < dim; q++) {
        int l = q < 0 ? i : lab[q], p = n++;
        while (p > 0 && k[p - 1] > l) {
            k[p] = k[p - 1];
            p--;
        }
        k[p] = l;
    }
    while (n < 4) k[n++] = INT32_MAX;
    int q = 0;
    while (k[q] < 0) q++;
    return k[q];
}

/* The point of a vertex: by name when it has one (k != NULL, lowest seed
   s), else by position. */
int voronoi_weld_vertex(Weld *w, Names *t, const int32_t *k, int s, const double x[3])
{
    if (!k) return voronoi_weld_point(w, x);
    for (int q = t->head[s]; q >= 0; q = t->next[q])
        if (!memcmp(t->key + 4 * q, k, 4 * sizeof(int32_t))) return t->id[q];
    int id = voronoi_weld_point(w, x), q = t->nent++;
    need(&t->key, &t->kcap, 4 * (size_t)t->nent, sizeof(int32_t));
    need(&t->id, &t->icap, (size_t)t->nent, sizeof(int));
    need(&t->next, &t->ncap, (size_t)t->nent, sizeof(int));
    memcpy(t->key + 4 * q, k, 4 * sizeof(int32_t));
    t->id[q] = id;
    t->next[q] = t->head[s];
    t->head[s] = q;
    return id;
}
