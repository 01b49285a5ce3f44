/*
** shape_sample.c: points spread evenly over a primitive's surface, with
** their outward normals (shape_sample, shape.h), for the seeds of a
** Voronoi grid.  The queries themselves (level, crossings, normals) are
** shape.c's; the frame and polygon helpers both use are in shape_impl.h.
*/
#include "shape.h"
#include "shape_impl.h"

#include "mem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* ---- sampling (shape_sample) ----
**
** Structured point sets with exact normals, spacing at most h along every
** parametric direction (counts are ceil(length / h) intervals, so the
** ends of every edge are hit exactly):
**   sphere    latitude rings theta_i = i pi / nt, ring i with
**             round(2 pi r sin theta_i / h) points, every other ring
**             turned by half a step; the poles are single points;
**   cylinder  side rings at ceil(H / h) + 1 axial stations, the first and
**             last being the rims; end discs as concentric rings about
**             the centre point;
**   cone      rings along the slant line, rims and end discs as for the
**             cylinder, a zero radius end as one apex point;
**   torus     tube rings (angle v) with round(2 pi (R + r cos v) / h)
**             points each;
**   box       the boundary points of the (nx+1)(ny+1)(nz+1) lattice,
**             so each face is a grid and edges and corners lie exactly on
**             the box's edges and corners;
**   polygon   per side an (edge x axial) lattice, the polygon's vertices
**             as edge lines, cap rims as edge points; caps are the nodes
**             of a grid over the polygon's bounding rectangle that lie
**             inside it at least h/2 from its sides;
**   halfSpace a grid over the plane (frame shape_perp_unit), clipped to lo..hi;
**   unbounded cylinders and polygons: the same restricted to lo..hi.
** A point on several faces (edges, corners, rims, polygon vertices) gets
** the normalised sum of those faces' outward normals, so a seed offset
** along it stays equidistant from the faces (thesis Fig. 3.16).
*/

typedef struct Samp {
    int cnt, cap;
    double *x, *nv;
    const double *lo, *hi;   /* clip box (unbounded shapes), or NULL */
    double tol;              /* clip tolerance */
} Samp;

static void samp_add(Samp *S, const double x[3], const double n[3])
{
    if (S->lo)
        for (int k = 0; k < 3; k++)
            if (!(x[k] >= S->lo[k] - S->tol && x[k] <= S->hi[k] + S->tol)) return;
    if (S->cnt == S->cap) {
        S->cap = S->cap ? 2 * S->cap : 256;
        S->x = mem_realloc(S->x, (size_t)S->cap * 3 * sizeof *S->x);
        S->nv = mem_realloc(S->nv, (size_t)S->cap * 3 * sizeof *S->nv);
    }
    double l = shape_norm(n);
    for (int k = 0; k < 3; k++) {
        S->x[3 * S->cnt + k] = x[k];
        S->nv[3 * S->cnt + k] = n[k] / l;
    }
    S->cnt++;
}

/* Intervals of at most h on a length (at least one; bounded so that a
   tiny h cannot overflow). */
static int samp_steps(double len, double h)
{
    double k = ceil(len / h - 1e-9);
    return !(k >= 1) ? 1 : k > 1e7 ? 10000000 : (int)k;
}

static int samp_ring_count(double rho, double h)
{
    double m = rho > 0 ? floor(2 * PI * rho / h + 0.5) : 1;
    return !(m >= 1) ? 1 : m > 1e7 ? 10000000 : (int)m;
}

typedef struct Frame {
    double u[3], e1[3], e2[3];
} Frame;

static void frame_of(const double u[3], Frame *F)
{
    memcpy(F->u, u, sizeof F->u);
    shape_perp_unit(u, F->e1);
    F->e2[0] = u[1] * F->e1[2] - u[2] * F->e1[1];
    F->e2[1] = u[2] * F->e1[0] - u[0] * F->e1[2];
    F->e2[2] = u[0] * F->e1[1] - u[1] * F->e1[0];
}

/* m points c + rho e(phi_j), phi_j = 2 pi (j + phase) / m, with normals
   nr e(phi_j) + nu u; rho = 0 gives the one point c. */
static void samp_ring(Samp *S, const Frame *F, const double c[3], double rho, int m, double phase, double nr,
                      double nu)
{
    if (!(rho > 0)) m = 1;
    for (int j = 0; j < m; j++) {
        double ph = 2 * PI * (j + phase) / m, cs = cos(ph), sn = sin(ph), x[3], n[3];
        for (int k = 0; k < 3; k++) {
            double e = cs * F->e1[k] + sn * F->e2[k];
            x[k] = c[k] + rho * e;
            n[k] = nr * e + nu * F->u[k];
        }
        samp_add(S, x, n);
    }
}

/* End disc of radius r about c, normal sgn u: concentric rings inside the
   rim (which the side sampling owns). */
static void samp_disc(Samp *S, const Frame *F, const double c[3], double r, double h, double sgn)
{
    int nr = samp_steps(r, h);
    for (int k = 0; k < nr; k++) {
        double rho = r * k / nr;
        samp_ring(S, F, c, rho, samp_ring_count(rho, h), 0, 0, sgn);
    }
}

static void samp_sphere(Samp *S, const Shape *s, double h)
{
    static const double z[3] = {0, 0, 1};
    Frame F;
    frame_of(z, &F);
    int nt = samp_steps(PI * s->r1, h);
    for (int i = 0; i <= nt; i++) {
        double th = PI * i / nt, st = i == nt ? 0 : sin(th), ct = i == nt ? -1 : cos(th), c[3];
        for (int k = 0; k < 3; k++) c[k] = s->p[k] + s->r1 * ct * F.u[k];
        samp_ring(S, &F, c, s->r1 * st, samp_ring_count(s->r1 * st, h), 0.5 * (i % 2), st, ct);
    }
}

/* Cylinder and cone: rings along the slant line from the rim at p
   (radius r1) to the rim at q (radius r2), then the end discs. */
/* Coordinate of node i of n intervals on [a, b], the ends exact. */
static double samp_node(double a, double b, int i, int n)
{
    return i == n ? b : a + (b - a) * i / n;
}

/* Midpoint of interval i of n on [a, b]: where a surface leaves through
   the box, samples half a spacing from the box sides put the seeds of
   the boundary pairs inside the box, and the box side, a symmetry plane
   of the Voronoi diagram there, closes the pairs' cells exactly. */
static double samp_mid(double a, double b, int i, int n)
{
    return a + (b - a) * (i + 0.5) / n;
}

/* A finite cylinder's mantle: the two rims (edge points, Fig. 3.16) and
   ns rings at the midpoints of ns equal intervals between them, all
   aligned.  Aligned rings: the seed pairs of neighbouring rings meet only
   on the surface (staggered rings give Voronoi grids many small faces
   between a seed and the next ring's partner: 1.3 % of the area of a
   cylinder at h = r/7, against 0.1 % aligned).  Midpoints: the edge rule
   puts the mirror seeds of a rim half a spacing from it, where the first
   ring's seeds then are too, instead of closer than the minimum
   spacing. */
static void samp_cylinder_rings(Samp *S, const Shape *s, const Frame *F, int ns, int m)
{
    for (int i = 0; i <= ns + 1; i++) {
        double t = i == 0 ? 0 : i == ns + 1 ? 1 : samp_mid(0, 1, i - 1, ns), c[3];
        for (int j = 0; j < 3; j++) c[j] = i == ns + 1 ? s->q[j] : s->p[j] + t * (s->q[j] - s->p[j]);
        samp_ring(S, F, c, s->r1, m, 0, 1, i == 0 ? -1 : i == ns + 1 ? 1 : 0);
    }
}

static void samp_axi(Samp *S, const Shape *s, double h)
{
    double u[3], H, r1 = s->r1, r2 = s->kind == SHAPE_CONE ? s->r2 : s->r1;
    shape_axi_frame(s, u, &H);
    Frame F;
    frame_of(u, &F);
    double k = (r2 - r1) / H, L = sqrt(1 + k * k);
    int ns = samp_steps(hypot(H, r2 - r1), h);
    int m = samp_ring_count(fmax(r1, r2), h);
    if (s->kind == SHAPE_CYLINDER) {
        samp_cylinder_rings(S, s, &F, ns, m);
    } else {
        for (int i = 0; i <= ns; i++) {
            double t = (double)i / ns, rho = i == ns ? r2 : r1 + t * (r2 - r1), c[3];
            for (int j = 0; j < 3; j++) c[j] = i == ns ? s->q[j] : s->p[j] + t * (s->q[j] - s->p[j]);
            double nu = -k / L + (i == 0 ? -1 : i == ns ? 1 : 0);
            if (!(rho > 0)) {   /* apex: along the axis, away from the base */
                samp_ring(S, &F, c, 0, 1, 0, 0, k > 0 ? -1 : 1);
                continue;
            }
            samp_ring(S, &F, c, rho, samp_ring_count(rho, h), 0.5 * (i % 2), 1 / L, nu);
        }
    }
    if (r1 > 0) samp_disc(S, &F, s->p, r1, h, -1);
    if (r2 > 0) samp_disc(S, &F, s->q, r2, h, 1);
}

/* Axial range [*a, *b] (from p along unit u) of the box lo..hi. */
static void samp_box_range(const double p[3], const double u[3], const double lo[3], const double hi[3], double *a,
                           double *b)
{
    *a = INFINITY, *b = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]}, w[3];
        shape_sub(x, p, w);
        double t = shape_dot(w, u);
        *a = fmin(*a, t), *b = fmax(*b, t);
    }
}

static void samp_infinite_cylinder(Samp *S, const Shape *s, double h, const double lo[3], const double hi[3])
{
    double u[3], H, a, b;
    shape_axi_frame(s, u, &H);
    Frame F;
    frame_of(u, &F);
    samp_box_range(s->p, u, lo, hi, &a, &b);
    int ns = samp_steps(b - a, h), m = samp_ring_count(s->r1, h);
    for (int i = 0; i < ns; i++) {
        double t = samp_mid(a, b, i, ns), c[3];
        for (int j = 0; j < 3; j++) c[j] = s->p[j] + t * u[j];
        samp_ring(S, &F, c, s->r1, m, 0, 1, 0);   /* aligned: see samp_axi */
    }
}

static void samp_torus(Samp *S, const Shape *s, double h)
{
    Frame F;
    frame_of(s->q, &F);
    int nv = samp_ring_count(s->r2, h);
    if (nv < 3) nv = 3;
    for (int j = 0; j < nv; j++) {
        double v = 2 * PI * j / nv, rho = s->r1 + s->r2 * cos(v), c[3];
        for (int k = 0; k < 3; k++) c[k] = s->p[k] + s->r2 * sin(v) * F.u[k];
        int m = samp_ring_count(rho, h);
        samp_ring(S, &F, c, rho, m < 3 ? 3 : m, 0.5 * (j % 2), cos(v), sin(v));
    }
}


/* Node i of 0..n+1 across [a, b]: the ends (edge points), and between
   them the midpoints of n equal intervals (see samp_cylinder_rings). */
static double samp_edge_mid(double a, double b, int i, int n)
{
    return i == 0 ? a : i == n + 1 ? b : samp_mid(a, b, i - 1, n);
}

/* Every face a grid of the edges and the midpoints between them (as a
   cylinder's rings): the edge rule (Fig. 3.16) puts the mirror seeds of
   an edge half a spacing from it, where the first row of the faces'
   seeds then is too, so one replaces the other cleanly instead of
   standing a fraction of the minimum spacing apart. */
static void samp_box(Samp *S, const Shape *s, double h)
{
    int n[3];
    for (int k = 0; k < 3; k++) n[k] = samp_steps(s->q[k] - s->p[k], h);
    for (int i = 0; i <= n[0] + 1; i++)
        for (int j = 0; j <= n[1] + 1; j++) {
            int inner = i > 0 && i <= n[0] && j > 0 && j <= n[1];
            for (int l = 0; l <= n[2] + 1; l += inner ? n[2] + 1 : 1) {
                int idx[3] = {i, j, l};
                double x[3], nv[3];
                for (int k = 0; k < 3; k++) {
                    x[k] = samp_edge_mid(s->p[k], s->q[k], idx[k], n[k]);
                    nv[k] = idx[k] == 0 ? -1 : idx[k] == n[k] + 1 ? 1 : 0;
                }
                samp_add(S, x, nv);
            }
        }
}

/* Node j of 0..nz+1 along a polygon prism's axis: capped ends are edge
   points, and between them the midpoints of nz intervals (samp_box); an
   end on the box has no node (half an interval from it); NAN for no
   node. */
static double polygon_z(double za, double zb, int j, int nz, int cap_lo, int cap_hi)
{
    if ((j == 0 && !cap_lo) || (j == nz + 1 && !cap_hi)) return NAN;
    return samp_edge_mid(za, zb, j, nz);
}

/* The polygon's sides between z = za and zb (caps where cap_lo / cap_hi),
   then the caps. */
static void samp_polygon(Samp *S, const Shape *s, double h, double za, double zb, int cap_lo, int cap_hi)
{
    int a = s->axis, iu = shape_poly_u(s), iv = shape_poly_v(s), np = s->npoly;
    int nz = samp_steps(zb - za, h);
    for (int e = 0; e < np; e++) {
        const double *P = s->poly + 2 * e, *Q = s->poly + 2 * ((e + 1) % np);
        double ne[3], nprev[3];
        shape_poly_wall_normal(s, e, ne);
        shape_poly_wall_normal(s, (e + np - 1) % np, nprev);
        int m = samp_steps(hypot(Q[0] - P[0], Q[1] - P[1]), h);
        /* the vertex line (i = 0), then the midpoints of m intervals */
        for (int i = 0; i <= m; i++)
            for (int j = 0; j <= nz + 1; j++) {
                double x[3], nv[3], t = i == 0 ? 0 : (i - 0.5) / m;
                x[iu] = P[0] + (Q[0] - P[0]) * t;
                x[iv] = P[1] + (Q[1] - P[1]) * t;
                x[a] = polygon_z(za, zb, j, nz, cap_lo, cap_hi);
                if (!isfinite(x[a])) continue;
                for (int k = 0; k < 3; k++) nv[k] = ne[k] + (i == 0 ? nprev[k] : 0);
                if (j == 0) nv[a] -= 1;
                if (j == nz + 1) nv[a] += 1;
                samp_add(S, x, nv);
            }
    }
    if (!cap_lo && !cap_hi) return;
    double lo[3], hi[3];
    shape_bounds(s, lo, hi);
    int mu = samp_steps(hi[iu] - lo[iu], h), mv = samp_steps(hi[iv] - lo[iv], h);
    for (int i = 0; i <= mu; i++)
        for (int j = 0; j <= mv; j++) {
            double u = samp_node(lo[iu], hi[iu], i, mu), v = samp_node(lo[iv], hi[iv], j, mv);
            ShapePoly2 P;
            shape_poly2(s, u, v, &P);
            if (!P.inside || P.dist < 0.5 * h) continue;
            for (int c = 0; c < 2; c++) {
                if (!(c ? cap_hi : cap_lo)) continue;
                double x[3], nv[3] = {0, 0, 0};
                x[iu] = u, x[iv] = v, x[a] = c ? zb : za;
                nv[a] = c ? 1 : -1;
                samp_add(S, x, nv);
            }
        }
}

static void samp_halfspace(Samp *S, const Shape *s, double h, const double lo[3], const double hi[3])
{
    Frame F;
    frame_of(s->q, &F);
    double a0, a1, b0, b1;
    samp_box_range(s->p, F.e1, lo, hi, &a0, &a1);
    samp_box_range(s->p, F.e2, lo, hi, &b0, &b1);
    int na = samp_steps(a1 - a0, h), nb = samp_steps(b1 - b0, h);
    for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++) {
            double a = samp_mid(a0, a1, i, na), b = samp_mid(b0, b1, j, nb), x[3];
            for (int k = 0; k < 3; k++) x[k] = s->p[k] + a * F.e1[k] + b * F.e2[k];
            samp_add(S, x, s->q);
        }
}

int shape_sample(const Shape *s, double h, const double lo[3], const double hi[3], double **x, double **n)
{
    Samp S = {0, 0, NULL, NULL, NULL, NULL, 0};
    int unbounded = s->kind == SHAPE_HALFSPACE || (s->kind == SHAPE_CYLINDER && s->infinite)
                 || (s->kind == SHAPE_POLYGON && !(isfinite(s->lo) && isfinite(s->hi)));
    if (unbounded && lo && hi) {
        S.lo = lo, S.hi = hi;
        for (int k = 0; k < 3; k++) S.tol = fmax(S.tol, 1e-9 * (fabs(lo[k]) + fabs(hi[k])));
    }
    if (h > 0 && (!unbounded || S.lo)) {
        switch (s->kind) {
        case SHAPE_HALFSPACE: samp_halfspace(&S, s, h, lo, hi); break;
        case SHAPE_BOX: samp_box(&S, s, h); break;
        case SHAPE_SPHERE: samp_sphere(&S, s, h); break;
        case SHAPE_CYLINDER:
            if (s->infinite) samp_infinite_cylinder(&S, s, h, lo, hi);
            else samp_axi(&S, s, h);
            break;
        case SHAPE_CONE: samp_axi(&S, s, h); break;
        case SHAPE_TORUS: samp_torus(&S, s, h); break;
        case SHAPE_POLYGON: {
            int a = s->axis;
            double za = isfinite(s->lo) ? s->lo : lo[a], zb = isfinite(s->hi) ? s->hi : hi[a];
            if (S.lo) za = fmax(za, lo[a]), zb = fmin(zb, hi[a]);
            if (za < zb) samp_polygon(&S, s, h, za, zb, za == s->lo, zb == s->hi);
            break;
        }
        default: break;
        }
    }
    *x = S.x ? S.x : MEM_NEW(double, 1);
    *n = S.nv ? S.nv : MEM_NEW(double, 1);
    return S.cnt;
}
