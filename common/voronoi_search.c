/*
** voronoi_search.c: the seeds that can cut a cell (voronoi.c, pass 1).
**
** The seeds are sorted into a uniform grid of buckets over the box, about
** one seed per bucket (a box much longer than wide has its finest axis
** halved until the count is sane).  A cell is clipped by the seeds of the
** buckets at Chebyshev index distance k = 0, 1, 2, ... from its own
** (voronoi_shell_collect), nearest first inside a shell; a seed at
** distance d can cut the cell only when d/2 < R, R the largest distance
** from the seed to a cell vertex, so voronoi.c's loop over the shells ends
** when the nearest unvisited shell (voronoi_shell_dist) is farther than
** 2R.  Rows and buckets of a shell wholly beyond that reach are skipped
** unread.  Seeds outside the box sit in the border buckets, which only
** makes them look nearer: the search stays exact.
*/
#include "voronoi_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int voronoi_bucket_axis(const Buckets *g, int a, double x)
{
    double t = (x - g->org[a]) / g->h[a];
    if (!(t > 0)) return 0;
    if (t >= g->n[a]) return g->n[a] - 1;
    return (int)t;
}

static int bucket_of(const Buckets *g, const double x[3])
{
    int b[3];
    for (int a = 0; a < 3; a++) b[a] = voronoi_bucket_axis(g, a, x[a]);
    return b[0] + g->n[0] * (b[1] + g->n[1] * b[2]);
}

void voronoi_buckets_build(Buckets *g, const VoronoiInput *in)
{
    int dims = in->flat_axis >= 0 ? 2 : 3;
    double vol = 1;
    for (int a = 0; a < 3; a++)
        if (a != in->flat_axis) vol *= in->hi[a] - in->lo[a];
    /* about one seed per bucket */
    double h = pow(vol / in->nseeds, 1.0 / dims);
    size_t total = 1;
    for (int a = 0; a < 3; a++) {
        double ext = in->hi[a] - in->lo[a];
        double n = a == in->flat_axis ? 1 : floor(ext / h + 0.5);
        if (n < 1) n = 1;
        if (n > 1 << 20) n = 1 << 20;
        g->n[a] = (int)n;
        g->org[a] = in->lo[a];
        g->h[a] = ext / n;
        total *= (size_t)g->n[a];
    }
    /* a box much longer than wide can round to many more buckets than
       seeds; halve the finest axis until the count is sane */
    while (total > 4 * (size_t)in->nseeds + 64) {
        int a = -1;
        for (int k = 0; k < 3; k++)
            if (g->n[k] > 1 && (a < 0 || g->n[k] > g->n[a])) a = k;
        total /= (size_t)g->n[a];
        g->n[a] = (g->n[a] + 1) / 2;
        g->h[a] = (in->hi[a] - in->lo[a]) / g->n[a];
        total *= (size_t)g->n[a];
    }
    g->start = mem_calloc(total + 1, sizeof(int));
    g->seed = mem_alloc(sizeof(int) * (size_t)in->nseeds);
    /* counting sort in place (no scratch arrays: fresh memory is dear):
       start[b + 1] is first the end of bucket b, then, filled from the
       last seed down, its beginning, which moves to start[b] */
    for (int i = 0; i < in->nseeds; i++) {
        double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
        if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
        g->start[bucket_of(g, x) + 1]++;
    }
    for (size_t b = 0; b < total; b++) g->start[b + 1] += g->start[b];
    for (int i = in->nseeds - 1; i >= 0; i--) {
        double x[3] = {in->x[3 * i], in->x[3 * i + 1], in->x[3 * i + 2]};
        if (in->flat_axis >= 0) x[in->flat_axis] = in->lo[in->flat_axis];
        g->seed[--g->start[bucket_of(g, x) + 1]] = i;
    }
    memmove(g->start, g->start + 1, sizeof(int) * total);
    g->start[total] = in->nseeds;
}

void voronoi_buckets_free(Buckets *g)
{
    free(g->start);
    free(g->seed);
}

/* Distance from x (in bucket b) to the nearest point of the buckets at
   index distance >= k from b; INFINITY when there are none. */
double voronoi_shell_dist(const Buckets *g, const int b[3], int k, const double x[3])
{
    double d = INFINITY;
    for (int a = 0; a < 3; a++) {
        if (b[a] - k >= 0) {
            double t = x[a] - (g->org[a] + (b[a] - k + 1) * g->h[a]);
            if (t < d) d = t;
        }
        if (b[a] + k < g->n[a]) {
            double t = g->org[a] + (b[a] + k) * g->h[a] - x[a];
            if (t < d) d = t;
        }
    }
    return d;
}

/* Squared distance along axis a from x to bucket column ia; border
   buckets reach to infinity (seeds outside the box are in them). */
static double bucket_gap2(const Buckets *g, int a, int ia, double x)
{
    double lo = g->org[a] + ia * g->h[a], hi = lo + g->h[a];
    if (ia > 0 && x < lo) return sq(lo - x);
    if (ia < g->n[a] - 1 && x > hi) return sq(x - hi);
    return 0;
}

/* Appends the seeds of the buckets of shell k around b (except self)
   closer than sqrt(r2max), sorted by distance.  Rows and buckets wholly
   farther than that are skipped unread: on a lattice shell 2 is searched
   (its nearest side is nearer than the cell's reach) but holds nothing in
   reach. */
void voronoi_shell_collect(Search *s, const Buckets *g, const VoronoiInput *in, int self, const int b[3],
                           int k, const double x[3], double r2max)
{
    s->n = 0;
    int flat = in->flat_axis;
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = b[a] - k < 0 ? 0 : b[a] - k;
        hi[a] = b[a] + k >= g->n[a] ? g->n[a] - 1 : b[a] + k;
    }
    for (int iz = lo[2]; iz <= hi[2]; iz++) {
        double gz = flat == 2 ? 0 : bucket_gap2(g, 2, iz, x[2]);
        if (gz > r2max) continue;
        for (int iy = lo[1]; iy <= hi[1]; iy++) {
            double gyz = gz + (flat == 1 ? 0 : bucket_gap2(g, 1, iy, x[1]));
            if (gyz > r2max) continue;
            int edge = abs(iz - b[2]) == k || abs(iy - b[1]) == k;
            int step = edge || k == 0 ? 1 : 2 * k;
            for (int ix = b[0] - k; ix <= b[0] + k; ix += step) {
                if (ix < 0 || ix >= g->n[0]) continue;
                if (gyz + (flat == 0 ? 0 : bucket_gap2(g, 0, ix, x[0])) > r2max) continue;
                int bk = ix + g->n[0] * (iy + g->n[1] * iz);
                for (int q = g->start[bk]; q < g->start[bk + 1]; q++) {
                    int j = g->seed[q];
                    if (j == self) continue;
                    const double *y = in->x + 3 * j;
                    double d2 = 0;
                    for (int a = 0; a < 3; a++)
                        if (a != flat) d2 += sq(y[a] - x[a]);
                    if (d2 > r2max) continue;
                    if (s->n >= s->cap) need(&s->cand, &s->cap, (size_t)s->n + 1, sizeof(Cand));
                    int p = s->n++;
                    while (p > 0 && s->cand[p - 1].d2 > d2) {
                        s->cand[p] = s->cand[p - 1];
                        p--;
                    }
                    s->cand[p] = (Cand){d2, j};
                }
            }
        }
    }
}
