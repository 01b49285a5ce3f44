/*
** shape.c: analytic solids with exact level, crossing, nearest-point,
** normal, volume and area queries.  See shape.h for the contract; surface
** sampling is shape_sample.c, and the helpers both use are shape_impl.h.
**
** Level functions.  Every kind's level is its exact signed distance
** (negative inside).  The box, the finite cylinder and the extruded
** polygon are products (of intervals; disc x interval; polygon x
** interval), whose signed distance combines the factors' (the larger one
** inside, the Euclidean shape_norm of the positive ones outside); the polygon's
** own is the distance to its nearest edge, signed by the winding number.
** The cone works in its (rho, s) half-plane, where its section is a
** convex trapezoid: the largest face-line distance inside, the distance
** to the nearest boundary segment outside.  The torus is the distance to
** its tube's centre circle minus the tube radius.  shape_inside is
** defined as level < 0, so the two can never disagree and a point on the
** surface (level 0) is outside.
**
** Crossings, in three steps (after the exit for segments shorter than
** an end's distance to the surface, which cannot cross it):
**   1. candidates: the roots of each smooth piece of the surface along the
**      line (a plane: linear; sphere, cylinder side, cone side: quadratic,
**      solved in the cancellation-free form t = tm +- sqrt(r^2 - |m|^2)/|d|
**      where m is the line's closest approach; torus: quartic, by
**      gsl_poly_complex_solve), curved ones polished by safeguarded Newton
**      steps on the piece's exact distance function.  A box contributes
**      just its slab entry and exit, so edge and corner hits are one value.
**   2. tidy: keep candidates in [0, 1] (with a 1e-12 margin, clamped),
**      sort, and merge those closer than the round-off of t (1e-14, more
**      when the coordinates are large compared with the segment), so a rim
**      hit found by the side and by the cap plane is one candidate.
**   3. select: walk the candidates with the inside state of the intervals
**      between them (inside(a) before the first, inside(b) after the last,
**      the midpoint's state in between) and report a candidate only where
**      the state changes.  Tangential touches, near-double roots (a complex
**      pair with a tiny imaginary part), roots on the far nappe of a cone
**      and plane hits outside a cap are thereby dropped without special
**      cases, and the count always has the parity of
**      inside(a) != inside(b).  Should no candidate exist where the state
**      changes (a failed root solve, or a segment lying in a tilted plane
**      whose points round to either side), the change is found by
**      bisection on the level sign.
**
** Nearest point and normal: exact per face; on an edge or corner the face
** chosen is the nearest, ties broken by x's signed distance to the face
** planes (the face x lies farthest beyond from outside, farthest behind
** from inside), then by the fixed order: box -x +x -y +y -z +z; cylinder
** and cone side, end at p, end at q; polygon walls by edge, then the lo
** and hi caps.  For the convex kinds all of this is the argmax of the
** face-plane distances (for an outside point a face's plane distance never
** exceeds the distance to the solid, with equality on its nearest faces);
** for the polygon's reflex vertices the nearest-edge search applies the
** rule itself.
*/
#include "shape.h"
#include "shape_impl.h"

#include "mem.h"

#include <float.h>
#include <stdarg.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static const char *const kind_names[SHAPE_NKINDS] = {
    "halfSpace", "box", "sphere", "cylinder", "cone", "torus", "polygon"};

const char *shape_kind_name(int kind)
{
    return kind >= 0 && kind < SHAPE_NKINDS ? kind_names[kind] : "unknown";
}

int shape_kind(const char *name)
{
    for (int k = 0; name && k < SHAPE_NKINDS; k++)
        if (strcmp(name, kind_names[k]) == 0) return k;
    return -1;
}

/* ---- small vector helpers ---- */

static void along(const double a[3], const double d[3], double t, double x[3])
{
    for (int k = 0; k < 3; k++) x[k] = a[k] + t * d[k];
}
static double clamp(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

/* A unit vector perpendicular to unit u (used where the radial direction
   of an axisymmetric shape is undefined: points on its axis). */
void shape_perp_unit(const double u[3], double e[3])
{
    int k = fabs(u[0]) <= fabs(u[1]) && fabs(u[0]) <= fabs(u[2]) ? 0 : fabs(u[1]) <= fabs(u[2]) ? 1 : 2;
    double ek[3] = {0, 0, 0};
    ek[k] = 1;
    for (int i = 0; i < 3; i++) e[i] = ek[i] - u[k] * u[i];
    double n = shape_norm(e);
    for (int i = 0; i < 3; i++) e[i] /= n;
}

/* Box-like combination of two signed face distances (a solid that is the
   intersection of two "slabs"): exact signed distance. */
static double combine2(double d1, double d2)
{
    if (d1 < 0 && d2 < 0) return d1 > d2 ? d1 : d2;
    double p1 = d1 > 0 ? d1 : 0, p2 = d2 > 0 ? d2 : 0;
    return sqrt(p1 * p1 + p2 * p2);
}

/* ---- axisymmetric frame: cylinder, cone, torus ---- */

typedef struct Axi {
    double u[3];    /* unit axis */
    double h;       /* axis length (cylinder, cone) */
    double s;       /* axial coordinate of x from p */
    double rho;     /* distance from the axis */
    double e[3];    /* unit radial direction of x (any when rho = 0) */
} Axi;

void shape_axi_frame(const Shape *s, double u[3], double *h)
{
    if (s->kind == SHAPE_TORUS) {
        for (int k = 0; k < 3; k++) u[k] = s->q[k];
        *h = 0;
        return;
    }
    shape_sub(s->q, s->p, u);
    *h = shape_norm(u);
    for (int k = 0; k < 3; k++) u[k] /= *h;
}

static void axi(const Shape *s, const double x[3], Axi *A)
{
    double w[3];
    shape_axi_frame(s, A->u, &A->h);
    shape_sub(x, s->p, w);
    A->s = shape_dot(w, A->u);
    for (int k = 0; k < 3; k++) A->e[k] = w[k] - A->s * A->u[k];
    A->rho = shape_norm(A->e);
    if (A->rho > 0)
        for (int k = 0; k < 3; k++) A->e[k] /= A->rho;
    else
        shape_perp_unit(A->u, A->e);
}

/* Point p + s u + rho e. */
static void axi_point(const Shape *s, const Axi *A, double sc, double rho, double c[3])
{
    for (int k = 0; k < 3; k++) c[k] = s->p[k] + sc * A->u[k] + rho * A->e[k];
}

/* ---- the cone's section: faces 0 side, 1 end at p, 2 end at q ---- */

/* Signed distances of (rho, s) to the lines of the cone's faces (outward
   positive); an end of radius 0 is no face and gets -INFINITY. */
static void cone_faces(const Shape *sh, double h, double rho, double s, double f[3])
{
    double k = (sh->r2 - sh->r1) / h, L = sqrt(1 + k * k);
    f[0] = (rho - sh->r1 - k * s) / L;
    f[1] = sh->r1 > 0 ? -s : -INFINITY;
    f[2] = sh->r2 > 0 ? s - h : -INFINITY;
}

/* Closest point (cr, cs) of segment (x0, y0)-(x1, y1) to (x, y); returns
   the squared distance. */
static double seg2(double x0, double y0, double x1, double y1, double x, double y, double *cx, double *cy)
{
    double ex = x1 - x0, ey = y1 - y0, ee = ex * ex + ey * ey;
    double l = ee > 0 ? ((x - x0) * ex + (y - y0) * ey) / ee : 0;
    /* Ends exactly, so two edges sharing a nearest vertex tie exactly; in
       between, the distance from the cross product, so a point on the
       segment (an axis-aligned one in particular) is at distance 0, not
       at the round-off of the interpolated foot. */
    if (!(l > 0)) *cx = x0, *cy = y0;
    else if (l >= 1) *cx = x1, *cy = y1;
    else {
        *cx = x0 + l * ex, *cy = y0 + l * ey;
        double cr = ex * (y - y0) - ey * (x - x0);
        return cr * cr / ee;
    }
    return (x - *cx) * (x - *cx) + (y - *cy) * (y - *cy);
}

/* Nearest boundary point (cr, cs) of the cone's section to (rho, s):
   the side and the end segments. */
static double cone_boundary(const Shape *sh, double h, double rho, double s, double *cr, double *cs)
{
    double seg[3][4] = {{sh->r1, 0, sh->r2, h}, {0, 0, sh->r1, 0}, {0, h, sh->r2, h}};
    double best = INFINITY;
    for (int i = 0; i < 3; i++) {
        double x, y, d2 = seg2(seg[i][0], seg[i][1], seg[i][2], seg[i][3], rho, s, &x, &y);
        if (d2 < best) best = d2, *cr = x, *cs = y;
    }
    return sqrt(best);
}

static int argmax3(const double f[3])
{
    return f[0] >= f[1] && f[0] >= f[2] ? 0 : f[1] >= f[2] ? 1 : 2;
}

/* ---- the polygon's plane ---- */


/* Outward signed distance of (u, v) to the line of edge i (CCW polygon:
   the interior is on the left). */
static double poly_line(const Shape *s, int i, double u, double v)
{
    const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % s->npoly);
    double eu = Q[0] - P[0], ev = Q[1] - P[1];
    return -(eu * (v - P[1]) - ev * (u - P[0])) / sqrt(eu * eu + ev * ev);
}

static int poly_winding(const Shape *s, double u, double v)
{
    int n = s->npoly, wn = 0;
    for (int i = 0; i < n; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % n);
        double isleft = (Q[0] - P[0]) * (v - P[1]) - (u - P[0]) * (Q[1] - P[1]);
        if (P[1] <= v) {
            if (Q[1] > v && isleft > 0) wn++;
        } else if (Q[1] <= v && isleft < 0) {
            wn--;
        }
    }
    return wn;
}

/* Edges equally near (those sharing the nearest vertex) are told apart by
   their signed line distance: from outside the edge x lies farthest
   beyond, from inside the one it lies farthest behind, i.e. the normal
   best aligned with the way from the surface to x. */
void shape_poly2(const Shape *s, double u, double v, ShapePoly2 *r)
{
    int n = s->npoly;
    double best = INFINITY, bestline = -INFINITY;
    r->inside = poly_winding(s, u, v) != 0;
    double sign = r->inside ? -1 : 1;
    r->edge = 0;
    r->cu = u, r->cv = v;
    for (int i = 0; i < n; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % n);
        double cu, cv, d2 = seg2(P[0], P[1], Q[0], Q[1], u, v, &cu, &cv);
        if (d2 > best) continue;
        double line = sign * poly_line(s, i, u, v);
        if (d2 < best || line > bestline) best = d2, bestline = line, r->edge = i, r->cu = cu, r->cv = cv;
    }
    r->dist = sqrt(best);
    r->sd = r->inside ? -r->dist : r->dist;
}

/* Outward unit normal of polygon wall i in 3-D. */
void shape_poly_wall_normal(const Shape *s, int i, double n[3])
{
    const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % s->npoly);
    double eu = Q[0] - P[0], ev = Q[1] - P[1], L = sqrt(eu * eu + ev * ev);
    n[s->axis] = 0;
    n[shape_poly_u(s)] = ev / L;
    n[shape_poly_v(s)] = -eu / L;
}

/* Signed distance to the lo/hi caps along the axis (-INFINITY when
   unbounded both ways). */
static double poly_axial(const Shape *s, double z)
{
    double a = s->lo - z, b = z - s->hi;
    return a > b ? a : b;
}

/* ---- level ---- */

static double level_box(const Shape *s, const double x[3])
{
    double m = -INFINITY, o = 0;
    for (int k = 0; k < 3; k++) {
        double d = fmax(s->p[k] - x[k], x[k] - s->q[k]);
        if (d > m) m = d;
        if (d > 0) o += d * d;
    }
    return m < 0 ? m : sqrt(o);
}

static double level_cone(const Shape *s, const double x[3])
{
    Axi A;
    double f[3], cr, cs;
    axi(s, x, &A);
    cone_faces(s, A.h, A.rho, A.s, f);
    int in = f[0] < 0 && f[1] < 0 && f[2] < 0 && A.s > 0 && A.s < A.h;
    if (in) return f[argmax3(f)];
    return cone_boundary(s, A.h, A.rho, A.s, &cr, &cs);
}

static double level_torus(const Shape *s, const double x[3])
{
    Axi A;
    axi(s, x, &A);
    return hypot(A.rho - s->r1, A.s) - s->r2;
}

static double level_polygon(const Shape *s, const double x[3])
{
    ShapePoly2 P;
    shape_poly2(s, x[shape_poly_u(s)], x[shape_poly_v(s)], &P);
    return combine2(P.sd, poly_axial(s, x[s->axis]));
}

double shape_level(const Shape *s, const double x[3])
{
    double w[3];
    switch (s->kind) {
    case SHAPE_HALFSPACE:
        shape_sub(x, s->p, w);
        return shape_dot(w, s->q);
    case SHAPE_BOX: return level_box(s, x);
    case SHAPE_SPHERE:
        shape_sub(x, s->p, w);
        return shape_norm(w) - s->r1;
    case SHAPE_CYLINDER: {
        Axi A;
        axi(s, x, &A);
        double side = A.rho - s->r1;
        return s->infinite ? side : combine2(side, fmax(-A.s, A.s - A.h));
    }
    case SHAPE_CONE: return level_cone(s, x);
    case SHAPE_TORUS: return level_torus(s, x);
    case SHAPE_POLYGON: return level_polygon(s, x);
    default: return NAN;
    }
}

int shape_inside(const Shape *s, const double x[3]) { return shape_level(s, x) < 0; }

/* ---- bound (the volume integrator's level, volfrac.c) ----
**
** Slab distances and the cone's side-line distance, without the
** Euclidean corner terms and nearest-point searches of shape_level; the
** arithmetic is the one setFields' shapes have always used (axial
** coordinate t = (x - p).(q - p) / L, rho^2 = |x - p|^2 - t^2), so the
** fields it sets stay the same to the last bit.
*/

static void bound_axis(const Shape *s, const double x[3], double *t, double *rho, double *len)
{
    double a[3], d[3];
    shape_sub(s->q, s->p, a);
    shape_sub(x, s->p, d);
    double L = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double sc = (d[0] * a[0] + d[1] * a[1] + d[2] * a[2]) / L;
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - sc * sc;
    *t = sc;
    *rho = sqrt(dd > 0 ? dd : 0);
    *len = L;
}

double shape_bound(const Shape *s, const double x[3])
{
    double t, rho, L, phi = -INFINITY;
    switch (s->kind) {
    case SHAPE_BOX:
        for (int k = 0; k < 3; k++) phi = fmax(phi, fmax(s->p[k] - x[k], x[k] - s->q[k]));
        return phi;
    case SHAPE_CYLINDER:
        bound_axis(s, x, &t, &rho, &L);
        return s->infinite ? rho - s->r1 : fmax(rho - s->r1, fmax(-t, t - L));
    case SHAPE_CONE: {
        bound_axis(s, x, &t, &rho, &L);
        double k = (s->r2 - s->r1) / L;
        /* rho - R(t) has gradient norm sqrt(1 + k^2) */
        return fmax((rho - (s->r1 + k * t)) / sqrt(1 + k * k), fmax(-t, t - L));
    }
    default: return shape_level(s, x);
    }
}

/* ---- nearest point and normal ---- */

static void near_box(const Shape *s, const double x[3], double c[3], double n[3])
{
    int f = 0;
    double best = -INFINITY;
    for (int i = 0; i < 6; i++) {
        int k = i / 2;
        double d = i % 2 ? x[k] - s->q[k] : s->p[k] - x[k];
        if (d > best) best = d, f = i;
    }
    int k = f / 2, outside = level_box(s, x) > 0;
    for (int j = 0; j < 3; j++) {
        c[j] = outside ? clamp(x[j], s->p[j], s->q[j]) : x[j];
        n[j] = 0;
    }
    if (!outside) c[k] = f % 2 ? s->q[k] : s->p[k];
    n[k] = f % 2 ? 1 : -1;
}

static void near_sphere(const Shape *s, const double x[3], double c[3], double n[3])
{
    double w[3];
    shape_sub(x, s->p, w);
    double r = shape_norm(w);
    for (int k = 0; k < 3; k++) n[k] = r > 0 ? w[k] / r : k == 0;
    for (int k = 0; k < 3; k++) c[k] = s->p[k] + s->r1 * n[k];
}

/* Cylinder and cone share the face logic in the (rho, s) half-plane. */
static void near_axi(const Shape *s, const double x[3], double c[3], double n[3])
{
    Axi A;
    double f[3], cr, cs;
    axi(s, x, &A);
    if (s->kind == SHAPE_CYLINDER) {
        f[0] = A.rho - s->r1;
        f[1] = s->infinite ? -INFINITY : -A.s;
        f[2] = s->infinite ? -INFINITY : A.s - A.h;
    } else {
        cone_faces(s, A.h, A.rho, A.s, f);
    }
    int face = argmax3(f);
    if (shape_level(s, x) > 0) {
        if (s->kind == SHAPE_CYLINDER) {
            cr = fmin(A.rho, s->r1);
            cs = s->infinite ? A.s : clamp(A.s, 0, A.h);
        } else {
            cone_boundary(s, A.h, A.rho, A.s, &cr, &cs);
        }
    } else if (face == 0) {
        double k = s->kind == SHAPE_CONE ? (s->r2 - s->r1) / A.h : 0, L2 = 1 + k * k;
        cr = A.rho - f[0] / sqrt(L2);
        cs = A.s + f[0] * k / sqrt(L2);
    } else {
        cr = A.rho;
        cs = face == 1 ? 0 : A.h;
    }
    axi_point(s, &A, cs, cr, c);
    if (face == 0) {
        double k = s->kind == SHAPE_CONE ? (s->r2 - s->r1) / A.h : 0, L = sqrt(1 + k * k);
        for (int j = 0; j < 3; j++) n[j] = (A.e[j] - k * A.u[j]) / L;
    } else {
        for (int j = 0; j < 3; j++) n[j] = face == 1 ? -A.u[j] : A.u[j];
    }
}

static void near_torus(const Shape *s, const double x[3], double c[3], double n[3])
{
    Axi A;
    double T[3], w[3];
    axi(s, x, &A);
    axi_point(s, &A, 0, s->r1, T);
    shape_sub(x, T, w);
    double r = shape_norm(w);
    for (int k = 0; k < 3; k++) n[k] = r > 0 ? w[k] / r : A.e[k];
    for (int k = 0; k < 3; k++) c[k] = T[k] + s->r2 * n[k];
}

static void near_polygon(const Shape *s, const double x[3], double c[3], double n[3])
{
    ShapePoly2 P;
    int a = s->axis, iu = shape_poly_u(s), iv = shape_poly_v(s);
    double z = x[a];
    shape_poly2(s, x[iu], x[iv], &P);
    double sa = poly_axial(s, z);
    int cap = s->lo - z > z - s->hi ? -1 : 1;   /* the cap sa refers to */
    for (int k = 0; k < 3; k++) c[k] = x[k];
    if (combine2(P.sd, sa) < 0) {
        /* Inside: the nearest of the wall and the caps. */
        if (P.dist <= -sa) {
            c[iu] = P.cu, c[iv] = P.cv;
            shape_poly_wall_normal(s, P.edge, n);
        } else {
            c[a] = cap < 0 ? s->lo : s->hi;
            n[iu] = n[iv] = 0, n[a] = cap;
        }
        return;
    }
    /* Outside or on: the solid is the product polygon x [lo, hi]. */
    if (P.sd > 0) c[iu] = P.cu, c[iv] = P.cv;
    c[a] = clamp(z, s->lo, s->hi);
    if (P.sd >= sa) {
        shape_poly_wall_normal(s, P.edge, n);
    } else {
        n[iu] = n[iv] = 0, n[a] = cap;
    }
}

static void nearest(const Shape *s, const double x[3], double c[3], double n[3])
{
    switch (s->kind) {
    case SHAPE_HALFSPACE: {
        double w[3];
        shape_sub(x, s->p, w);
        double d = shape_dot(w, s->q);
        for (int k = 0; k < 3; k++) c[k] = x[k] - d * s->q[k], n[k] = s->q[k];
        return;
    }
    case SHAPE_BOX: near_box(s, x, c, n); return;
    case SHAPE_SPHERE: near_sphere(s, x, c, n); return;
    case SHAPE_CYLINDER:
    case SHAPE_CONE: near_axi(s, x, c, n); return;
    case SHAPE_TORUS: near_torus(s, x, c, n); return;
    case SHAPE_POLYGON: near_polygon(s, x, c, n); return;
    default:
        for (int k = 0; k < 3; k++) c[k] = n[k] = NAN;
    }
}

/* Normals are renormalised: the radial direction of a point near an axis
   carries the round-off of |w| / rho, which would otherwise show in |n|. */
void shape_normal(const Shape *s, const double x[3], double n[3])
{
    double c[3];
    nearest(s, x, c, n);
    double l = shape_norm(n);
    if (l > 0)
        for (int k = 0; k < 3; k++) n[k] /= l;
}

void shape_closest(const Shape *s, const double x[3], double c[3])
{
    double n[3];
    nearest(s, x, c, n);
}

/* ---- crossings: candidates ---- */

/* Exact distance function of one smooth surface piece and its gradient,
   for Newton polishing: 0 sphere, 1 infinite cylinder side, 2 infinite
   cone side, 3 torus. */
enum { PIECE_SPHERE, PIECE_CYL, PIECE_CONE, PIECE_TORUS };

static double piece(const Shape *s, int kind, const double x[3], double g[3])
{
    double w[3];
    if (kind == PIECE_SPHERE) {
        shape_sub(x, s->p, w);
        double r = shape_norm(w);
        for (int k = 0; k < 3; k++) g[k] = w[k] / r;
        return r - s->r1;
    }
    Axi A;
    axi(s, x, &A);
    if (kind == PIECE_CYL) {
        for (int k = 0; k < 3; k++) g[k] = A.e[k];
        return A.rho - s->r1;
    }
    if (kind == PIECE_CONE) {
        double k = (s->r2 - s->r1) / A.h, L = sqrt(1 + k * k);
        for (int j = 0; j < 3; j++) g[j] = (A.e[j] - k * A.u[j]) / L;
        return (A.rho - s->r1 - k * A.s) / L;
    }
    double T[3];
    axi_point(s, &A, 0, s->r1, T);
    shape_sub(x, T, w);
    double r = shape_norm(w);
    for (int k = 0; k < 3; k++) g[k] = w[k] / r;
    return r - s->r2;
}

/* Newton steps on the piece's distance along the line, each kept only if
   it reduces |distance| and is small (a near-double root has a tiny slope
   and is left as found: the selection treats it as a touch). */
static double polish(const Shape *s, int kind, const double a[3], const double d[3], double t)
{
    double x[3], g[3];
    along(a, d, t, x);
    double f = piece(s, kind, x, g);
    for (int it = 0; it < 4 && f != 0; it++) {
        double slope = shape_dot(g, d);
        if (!(slope != 0)) break;
        double dt = -f / slope;
        if (!(fabs(dt) < 1e-3)) break;
        double g2[3];
        along(a, d, t + dt, x);
        double f2 = piece(s, kind, x, g2);
        if (!(fabs(f2) < fabs(f))) break;
        t += dt, f = f2;
        for (int k = 0; k < 3; k++) g[k] = g2[k];
    }
    return t;
}

/* Roots of A t^2 + 2 B t + C = 0 in the stable form; returns how many. */
static int quadratic(double A, double B, double C, double r[2])
{
    if (A == 0) {
        if (B == 0) return 0;
        r[0] = -C / (2 * B);
        return isfinite(r[0]);
    }
    double D = B * B - A * C;
    if (!(D >= 0)) return 0;
    double q = -(B + copysign(sqrt(D), B));
    if (q == 0) {
        r[0] = -B / A;
        return isfinite(r[0]);
    }
    /* A line nearly parallel to a generator: q / A overflows, C / q is
       the root that matters. */
    int n = 0;
    double t0 = q / A, t1 = C / q;
    if (isfinite(t0)) r[n++] = t0;
    if (isfinite(t1)) r[n++] = t1;
    return n;
}

/* Roots where the line w + t d (relative to a centre, already projected
   off the axis when on a cylinder) is at distance r: t = tm +- sqrt(r^2 -
   |m|^2) / |d|, with m the closest approach, free of the cancellation of
   B^2 - AC near tangency. */
static int radial(const double w[3], const double d[3], double r, double out[2])
{
    double A = shape_dot(d, d);
    if (!(A > 0)) return 0;
    double tm = -shape_dot(d, w) / A, m[3];
    along(w, d, tm, m);
    double mm = shape_norm(m), D = (r - mm) * (r + mm);
    if (!(D >= 0) || !isfinite(tm)) return 0;
    double h = sqrt(D / A);
    out[0] = tm - h, out[1] = tm + h;
    return h > 0 ? 2 : 1;
}

/* Parameter where the axial coordinate sa + t sd equals z. */
static int plane(double sa, double sd, double z, double *t)
{
    if (sd == 0 || !isfinite(z)) return 0;
    *t = (z - sa) / sd;
    return isfinite(*t);
}

static int cand_box(const Shape *s, const double a[3], const double d[3], double *c)
{
    double tin = -INFINITY, tout = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (!(a[k] > s->p[k] && a[k] < s->q[k])) return 0;
            continue;
        }
        double t0 = (s->p[k] - a[k]) / d[k], t1 = (s->q[k] - a[k]) / d[k];
        tin = fmax(tin, fmin(t0, t1));
        tout = fmin(tout, fmax(t0, t1));
    }
    if (!(tin < tout)) return 0;
    c[0] = tin, c[1] = tout;
    return 2;
}

static int cand_axi(const Shape *s, const double a[3], const double d[3], double *c)
{
    double u[3], h, w[3], wp[3], dp[3];
    shape_axi_frame(s, u, &h);
    shape_sub(a, s->p, w);
    double sa = shape_dot(w, u), sd = shape_dot(d, u);
    for (int k = 0; k < 3; k++) wp[k] = w[k] - sa * u[k], dp[k] = d[k] - sd * u[k];
    int n = 0, m;
    double r[2];
    if (s->kind == SHAPE_CYLINDER) {
        m = radial(wp, dp, s->r1, r);
        for (int i = 0; i < m; i++) c[n++] = polish(s, PIECE_CYL, a, d, r[i]);
        if (s->infinite) return n;
    } else {
        /* |w_perp|^2 = (r1 + k s)^2 along the line, factored where it
           cancels. */
        double k = (s->r2 - s->r1) / h, g0 = s->r1 + k * sa, g1 = k * sd;
        double ndp = shape_norm(dp), nwp = shape_norm(wp);
        double A = (ndp - fabs(g1)) * (ndp + fabs(g1));
        double B = shape_dot(dp, wp) - g0 * g1, C = (nwp - g0) * (nwp + g0);
        m = quadratic(A, B, C, r);
        for (int i = 0; i < m; i++) c[n++] = polish(s, PIECE_CONE, a, d, r[i]);
    }
    n += plane(sa, sd, 0, c + n);
    n += plane(sa, sd, h, c + n);
    return n;
}

/* The torus quartic |w|^2 + R^2 - r^2)^2 = 4 R^2 |w_perp|^2 in t, lengths
   scaled by R so the coefficients are O(1) for segments of the torus'
   size.  GSL's default error handler would abort on a failed solve;
   library code must not, so it is switched off around the call (and the
   caller's handler restored). */
static int cand_torus(const Shape *s, const double a[3], const double d[3], double *c)
{
    double w[3], dd[3], inv = 1 / s->r1, rr = s->r2 * inv;
    shape_sub(a, s->p, w);
    for (int k = 0; k < 3; k++) w[k] *= inv, dd[k] = d[k] * inv;
    double z0 = shape_dot(w, s->q), dz = shape_dot(dd, s->q), wp[3], dp[3];
    for (int k = 0; k < 3; k++) wp[k] = w[k] - z0 * s->q[k], dp[k] = dd[k] - dz * s->q[k];
    double al = shape_dot(dd, dd), be = shape_dot(dd, w), ga = shape_dot(w, w);
    double K = ga + (1 - rr) * (1 + rr);
    double coef[5] = {K * K - 4 * shape_dot(wp, wp), 4 * be * K - 8 * shape_dot(dp, wp),
                      4 * be * be + 2 * al * K - 4 * shape_dot(dp, dp), 4 * al * be, al * al};
    for (int i = 0; i < 5; i++)
        if (!isfinite(coef[i])) return 0;
    if (!(coef[4] > 0)) return 0;
    double mat[16], z[8];
    gsl_poly_complex_workspace ws = {4, mat};
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int st = gsl_poly_complex_solve(coef, 5, &ws, z);
    gsl_set_error_handler(old);
    if (st != GSL_SUCCESS) return 0;
    int n = 0;
    for (int i = 0; i < 4; i++) {
        double t = z[2 * i];
        if (!(t > -0.01 && t < 1.01)) continue;
        /* Real roots and near-double pairs (tiny imaginary part) are
           polished; the selection decides whether a pair is a touch. */
        c[n++] = fabs(z[2 * i + 1]) < 1e-6 ? polish(s, PIECE_TORUS, a, d, t) : t;
    }
    return n;
}

static int cand_polygon(const Shape *s, const double a[3], const double d[3], double *c)
{
    int iu = shape_poly_u(s), iv = shape_poly_v(s), n = 0, np = s->npoly;
    double au = a[iu], av = a[iv], du = d[iu], dv = d[iv];
    for (int i = 0; i < np; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % np);
        double eu = Q[0] - P[0], ev = Q[1] - P[1];
        double den = du * ev - dv * eu;
        if (den == 0) continue;
        double pu = P[0] - au, pv = P[1] - av;
        double t = (pu * ev - pv * eu) / den, l = (pu * dv - pv * du) / den;
        if (l >= -1e-12 && l <= 1 + 1e-12 && isfinite(t)) c[n++] = t;
    }
    n += plane(a[s->axis], d[s->axis], s->lo, c + n);
    n += plane(a[s->axis], d[s->axis], s->hi, c + n);
    return n;
}

static int candidates(const Shape *s, const double a[3], const double d[3], double *c)
{
    double w[3], r[2];
    switch (s->kind) {
    case SHAPE_HALFSPACE: {
        double f0 = shape_dot(d, s->q);
        shape_sub(a, s->p, w);
        return plane(shape_dot(w, s->q), f0, 0, c);
    }
    case SHAPE_BOX: return cand_box(s, a, d, c);
    case SHAPE_SPHERE: {
        shape_sub(a, s->p, w);
        int m = radial(w, d, s->r1, r);
        for (int i = 0; i < m; i++) c[i] = polish(s, PIECE_SPHERE, a, d, r[i]);
        return m;
    }
    case SHAPE_CYLINDER:
    case SHAPE_CONE: return cand_axi(s, a, d, c);
    case SHAPE_TORUS: return cand_torus(s, a, d, c);
    case SHAPE_POLYGON: return cand_polygon(s, a, d, c);
    default: return 0;
    }
}

/* ---- crossings: tidy and select ---- */

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Keeps candidates in [0, 1] (clamping a margin of 1e-12), sorts them and
   merges runs closer than tol into their middle. */
static int tidy(double *c, int n, double tol)
{
    int m = 0;
    for (int i = 0; i < n; i++)
        if (c[i] >= -1e-12 && c[i] <= 1 + 1e-12) c[m++] = clamp(c[i], 0, 1);
    qsort(c, (size_t)m, sizeof *c, cmp_double);
    int k = 0;
    for (int i = 0; i < m;) {
        int j = i;
        while (j + 1 < m && c[j + 1] - c[j] <= tol) j++;
        c[k++] = 0.5 * (c[i] + c[j]);
        i = j + 1;
    }
    return k;
}

static int inside_at(const Shape *s, const double a[3], const double d[3], double t)
{
    double x[3];
    along(a, d, t, x);
    return shape_inside(s, x);
}

/* The inside state changes between t = 0 and 1 with no candidate: the
   change found by bisection on the level sign. */
static double bisect(const Shape *s, const double a[3], const double d[3], int s0)
{
    double lo = 0, hi = 1;
    for (int it = 0; it < 200 && hi - lo > 1e-17; it++) {
        double mid = 0.5 * (lo + hi);
        if (inside_at(s, a, d, mid) == s0) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

int shape_crossings(const Shape *s, const double a[3], const double b[3], double *t, int max)
{
    double d[3];
    shape_sub(b, a, d);
    double len = shape_norm(d);
    if (!(len > 0)) return 0;
    /* Every level is the exact signed distance, so an end farther from
       the surface than the segment is long proves there is no crossing:
       the cheap exit for the many grid edges away from the surface. */
    double la = shape_level(s, a), lb = shape_level(s, b), far = len * (1 + 1e-9);
    if (fabs(la) > far || fabs(lb) > far) return 0;
    double buf[16], *c = buf;
    if (s->kind == SHAPE_POLYGON && s->npoly + 2 > 16) c = mem_alloc(sizeof *c * (size_t)(s->npoly + 2));
    /* Round-off of t: the coordinates' last bits over the segment length. */
    double M = 0;
    for (int k = 0; k < 3; k++) M = fmax(M, fmax(fabs(a[k]), fabs(b[k])));
    double tol = fmax(1e-14, 8 * DBL_EPSILON * M / len);
    int nc = tidy(c, candidates(s, a, d, c), tol);
    int prev = la < 0, last = lb < 0, n = 0;
    if (nc == 0 && prev != last) {
        if (max > 0) t[0] = bisect(s, a, d, prev);
        n = 1;
    }
    for (int i = 0; i < nc; i++) {
        int next = i + 1 < nc ? inside_at(s, a, d, 0.5 * (c[i] + c[i + 1])) : last;
        if (next != prev) {
            if (n < max) t[n] = c[i];
            n++;
        }
        prev = next;
    }
    if (c != buf) free(c);
    return n;
}

/* ---- bounds, volume, area ---- */

void shape_bounds(const Shape *s, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) lo[k] = -INFINITY, hi[k] = INFINITY;
    switch (s->kind) {
    case SHAPE_HALFSPACE:
        /* Bounded along an axis only when the plane is normal to it. */
        for (int k = 0; k < 3; k++) {
            if (fabs(s->q[k]) != 1) continue;
            if (s->q[k] > 0) hi[k] = s->p[k];
            else lo[k] = s->p[k];
        }
        return;
    case SHAPE_BOX:
        for (int k = 0; k < 3; k++) lo[k] = s->p[k], hi[k] = s->q[k];
        return;
    case SHAPE_SPHERE:
        for (int k = 0; k < 3; k++) lo[k] = s->p[k] - s->r1, hi[k] = s->p[k] + s->r1;
        return;
    case SHAPE_CYLINDER:
    case SHAPE_CONE: {
        double u[3], h;
        shape_axi_frame(s, u, &h);
        double r2 = s->kind == SHAPE_CYLINDER ? s->r1 : s->r2;
        for (int k = 0; k < 3; k++) {
            double e = sqrt(fmax(0, 1 - u[k] * u[k]));  /* a disc's half extent per radius */
            if (s->kind == SHAPE_CYLINDER && s->infinite && u[k] != 0) continue;
            lo[k] = fmin(s->p[k] - s->r1 * e, s->q[k] - r2 * e);
            hi[k] = fmax(s->p[k] + s->r1 * e, s->q[k] + r2 * e);
        }
        return;
    }
    case SHAPE_TORUS:
        for (int k = 0; k < 3; k++) {
            double e = s->r1 * sqrt(fmax(0, 1 - s->q[k] * s->q[k])) + s->r2;
            lo[k] = s->p[k] - e, hi[k] = s->p[k] + e;
        }
        return;
    case SHAPE_POLYGON: {
        int iu = shape_poly_u(s), iv = shape_poly_v(s);
        lo[iu] = lo[iv] = INFINITY, hi[iu] = hi[iv] = -INFINITY;
        for (int i = 0; i < s->npoly; i++) {
            lo[iu] = fmin(lo[iu], s->poly[2 * i]), hi[iu] = fmax(hi[iu], s->poly[2 * i]);
            lo[iv] = fmin(lo[iv], s->poly[2 * i + 1]), hi[iv] = fmax(hi[iv], s->poly[2 * i + 1]);
        }
        lo[s->axis] = s->lo, hi[s->axis] = s->hi;
        return;
    }
    default: return;
    }
}

static double poly_area(const Shape *s)
{
    double a = 0;
    for (int i = 0; i < s->npoly; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % s->npoly);
        a += P[0] * Q[1] - Q[0] * P[1];
    }
    return 0.5 * a;
}

static double poly_perimeter(const Shape *s)
{
    double l = 0;
    for (int i = 0; i < s->npoly; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % s->npoly);
        l += hypot(Q[0] - P[0], Q[1] - P[1]);
    }
    return l;
}

static double axis_length(const Shape *s)
{
    double w[3];
    shape_sub(s->q, s->p, w);
    return shape_norm(w);
}

double shape_volume(const Shape *s)
{
    double r = s->r1, r2 = s->r2;
    switch (s->kind) {
    case SHAPE_BOX: return (s->q[0] - s->p[0]) * (s->q[1] - s->p[1]) * (s->q[2] - s->p[2]);
    case SHAPE_SPHERE: return 4.0 / 3.0 * PI * r * r * r;
    case SHAPE_CYLINDER: return s->infinite ? INFINITY : PI * r * r * axis_length(s);
    case SHAPE_CONE: return PI * axis_length(s) / 3 * (r * r + r * r2 + r2 * r2);
    case SHAPE_TORUS: return 2 * PI * PI * r * r2 * r2;
    case SHAPE_POLYGON: return fabs(poly_area(s)) * (s->hi - s->lo);
    default: return INFINITY;
    }
}

double shape_area(const Shape *s)
{
    double r = s->r1, r2 = s->r2;
    switch (s->kind) {
    case SHAPE_BOX: {
        double a = s->q[0] - s->p[0], b = s->q[1] - s->p[1], c = s->q[2] - s->p[2];
        return 2 * (a * b + b * c + c * a);
    }
    case SHAPE_SPHERE: return 4 * PI * r * r;
    case SHAPE_CYLINDER: return s->infinite ? INFINITY : 2 * PI * r * (axis_length(s) + r);
    case SHAPE_CONE: {
        double h = axis_length(s), sl = hypot(h, r - r2);  /* slant height */
        return PI * (r + r2) * sl + PI * (r * r + r2 * r2);
    }
    case SHAPE_TORUS: return 4 * PI * PI * r * r2;
    case SHAPE_POLYGON:
        if (!isfinite(s->hi - s->lo)) return INFINITY;
        return 2 * fabs(poly_area(s)) + poly_perimeter(s) * (s->hi - s->lo);
    default: return INFINITY;
    }
}

/* ---- check ---- */

static const char *fail(Shape *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static const char *fail(Shape *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->msg, sizeof s->msg, fmt, ap);
    va_end(ap);
    return s->msg;
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

static const char *check_unit(Shape *s, const char *what)
{
    double n = shape_norm(s->q);
    if (!finite3(s->q) || !(n > 0)) return fail(s, "%s must be a finite non-zero vector", what);
    for (int k = 0; k < 3; k++) s->q[k] /= n;
    return NULL;
}

static const char *check_radius(Shape *s, const char *what, double r, int zero_ok)
{
    if (!isfinite(r) || r < 0 || (!zero_ok && r == 0))
        return fail(s, "%s must be %s, found %g", what, zero_ok ? "non-negative" : "positive", r);
    return NULL;
}

static const char *check_axis(Shape *s)
{
    if (!finite3(s->p) || !finite3(s->q)) return fail(s, "axis end points must be finite");
    if (!(axis_length(s) > 0))
        return fail(s, "axis end points must differ, both are (%g %g %g)", s->p[0], s->p[1], s->p[2]);
    return NULL;
}

/* Proper or touching intersection of segments p0-p1 and q0-q1 (2-D). */
static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int on_seg(const double *a, const double *b, const double *c)
{
    return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= c[1]
        && c[1] <= fmax(a[1], b[1]);
}

static int seg_meet(const double *p0, const double *p1, const double *q0, const double *q1)
{
    double d1 = orient(q0, q1, p0), d2 = orient(q0, q1, p1);
    double d3 = orient(p0, p1, q0), d4 = orient(p0, p1, q1);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 1;
    return (d1 == 0 && on_seg(q0, q1, p0)) || (d2 == 0 && on_seg(q0, q1, p1))
        || (d3 == 0 && on_seg(p0, p1, q0)) || (d4 == 0 && on_seg(p0, p1, q1));
}

static const char *check_polygon(Shape *s)
{
    int n = s->npoly;
    if (s->axis < 0 || s->axis > 2) return fail(s, "extrusion axis must be 0, 1 or 2, found %d", s->axis);
    if (n < 3 || !s->poly) return fail(s, "needs at least 3 points, found %d", n);
    if (isnan(s->lo) || isnan(s->hi) || !(s->lo < s->hi))
        return fail(s, "extent along the axis must have lo < hi, found lo %g, hi %g", s->lo, s->hi);
    for (int i = 0; i < n; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % n);
        if (!isfinite(P[0]) || !isfinite(P[1])) return fail(s, "point %d is not finite", i);
        if (P[0] == Q[0] && P[1] == Q[1]) return fail(s, "points %d and %d coincide: (%g %g)", i, (i + 1) % n, P[0], P[1]);
    }
    for (int i = 0; i < n; i++) {
        const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % n), *R = s->poly + 2 * ((i + 2) % n);
        double ax = Q[0] - P[0], ay = Q[1] - P[1], bx = R[0] - Q[0], by = R[1] - Q[1];
        if (ax * by - ay * bx == 0 && ax * bx + ay * by < 0)
            return fail(s, "polygon folds back on itself at point %d (%g %g)", (i + 1) % n, Q[0], Q[1]);
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1) continue;
            const double *P = s->poly + 2 * i, *Q = s->poly + 2 * ((i + 1) % n);
            const double *R = s->poly + 2 * j, *T = s->poly + 2 * ((j + 1) % n);
            if (seg_meet(P, Q, R, T))
                return fail(s, "polygon intersects itself: edges %d-%d and %d-%d meet", i, (i + 1) % n, j, (j + 1) % n);
        }
    double A = poly_area(s);
    if (!(A != 0)) return fail(s, "polygon has zero area");
    if (A < 0)
        for (int i = 0, j = n - 1; i < j; i++, j--)
            for (int k = 0; k < 2; k++) {
                double tmp = s->poly[2 * i + k];
                s->poly[2 * i + k] = s->poly[2 * j + k];
                s->poly[2 * j + k] = tmp;
            }
    return NULL;
}

const char *shape_check(Shape *s)
{
    const char *m = NULL;
    s->msg[0] = 0;
    switch (s->kind) {
    case SHAPE_HALFSPACE:
        if (!finite3(s->p)) return fail(s, "point must be finite");
        return check_unit(s, "normal");
    case SHAPE_BOX:
        if (!finite3(s->p) || !finite3(s->q)) return fail(s, "corners must be finite");
        for (int k = 0; k < 3; k++)
            if (!(s->q[k] > s->p[k]))
                return fail(s, "max corner must exceed min corner in %c, found min %g, max %g", "xyz"[k], s->p[k], s->q[k]);
        return NULL;
    case SHAPE_SPHERE:
        if (!finite3(s->p)) return fail(s, "centre must be finite");
        return check_radius(s, "radius", s->r1, 0);
    case SHAPE_CYLINDER:
        if ((m = check_radius(s, "radius", s->r1, 0))) return m;
        return check_axis(s);
    case SHAPE_CONE:
        if ((m = check_radius(s, "radius1", s->r1, 1)) || (m = check_radius(s, "radius2", s->r2, 1))) return m;
        if (s->r1 == 0 && s->r2 == 0) return fail(s, "radius1 and radius2 must not both be zero");
        return check_axis(s);
    case SHAPE_TORUS:
        if (!finite3(s->p)) return fail(s, "centre must be finite");
        if ((m = check_radius(s, "major radius", s->r1, 0)) || (m = check_radius(s, "minor radius", s->r2, 0)))
            return m;
        if (!(s->r2 < s->r1))
            return fail(s, "minor radius (%g) must be less than major radius (%g)", s->r2, s->r1);
        return check_unit(s, "axis");
    case SHAPE_POLYGON: return check_polygon(s);
    default: return fail(s, "unknown shape kind %d", s->kind);
    }
}

void shape_free(Shape *s)
{
    free(s->poly);
    s->poly = NULL;
    s->npoly = 0;
}
