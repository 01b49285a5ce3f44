/*
** geom.c: exact geometry of polygons and polyhedra.  See geom.h.
**
** Faces.  A triangle uses the direct formulas Sf = (b-a)x(c-a)/2,
** Cf = (a+b+c)/3.  A polygon with n > 3 points is split into the n
** triangles (p_i, p_i+1, m) about the average m of its points, OpenFOAM's
** rule (primitiveMeshFaceCentresAndAreas.C): Sf is the sum of the triangle
** area vectors and Cf the area-weighted mean of the triangle centroids.
** OpenFOAM weights each triangle by |n_i|; we give that weight the sign
** of n_i . N (N = sum of n_i).  For a warped face whose triangles all face
** the same way as N (the usual case) this is OpenFOAM's definition to the
** bit; for a planar polygon that is not star-shaped about m (a non-convex
** cut face), the folded-back triangles are subtracted instead of added,
** which makes Cf the true centroid where |n_i| would be wrong.
**
** Cells.  Every face is fanned into the same triangles about its point
** average (a triangle face is one triangle), and each triangle forms a
** tetrahedron with the cell's estimate point d (the average of its face
** centroids).  The signed volumes and volume-weighted centroids of these
** tetrahedra are the divergence-theorem integrals over the closed
** triangulated surface, so the result is exact for any closed polyhedron,
** convex or not, whether d lies inside or not; and for planar faces the
** triangulated surface is the polyhedron itself.
**
** Speed: the small helpers are inline (a big mesh calls them hundreds of
** millions of times); inlining changes no result, since every operation
** and its order stay as written.
**
** Round-off: everything is computed relative to a local origin (m for a
** face, d for a cell), so translating a body far from the origin does not
** cost digits.
*/
#include "geom.h"

#include <math.h>
#include <string.h>

double geom_norm(const double a[3])
{
    return sqrt(geom_dot(a, a));
}

static inline void sub(const double *a, const double *b, double c[3])
{
    c[0] = a[0] - b[0];
    c[1] = a[1] - b[1];
    c[2] = a[2] - b[2];
}

static inline void point_average(const double *pts, const int *idx, int n, double m[3])
{
    m[0] = m[1] = m[2] = 0;
    for (int i = 0; i < n; i++) {
        const double *p = pts + 3 * (size_t)idx[i];
        m[0] += p[0];
        m[1] += p[1];
        m[2] += p[2];
    }
    m[0] /= n;
    m[1] /= n;
    m[2] /= n;
}

static void triangle(const double *pts, const int *idx, double Sf[3], double Cf[3])
{
    const double *a = pts + 3 * (size_t)idx[0], *b = pts + 3 * (size_t)idx[1],
                 *c = pts + 3 * (size_t)idx[2];
    double u[3], v[3];
    sub(b, a, u);
    sub(c, a, v);
    geom_cross(u, v, Sf);
    for (int k = 0; k < 3; k++) {
        Sf[k] *= 0.5;
        /* a + ((b-a) + (c-a))/3 keeps digits when the triangle is far
           from the origin */
        Cf[k] = a[k] + (u[k] + v[k]) / 3.0;
    }
}

/* Doubled area vector of the fan triangle (p_i, p_i+1, m), and the sum
   u + v of its corners relative to m (3 x its centroid offset). */
static inline void fan(const double *pts, const int *idx, int n, int i, const double m[3], double t[3], double uv[3])
{
    double u[3], v[3];
    sub(pts + 3 * (size_t)idx[i], m, u);
    sub(pts + 3 * (size_t)idx[i + 1 < n ? i + 1 : 0], m, v);
    geom_cross(u, v, t);
    uv[0] = u[0] + v[0];
    uv[1] = u[1] + v[1];
    uv[2] = u[2] + v[2];
}

enum { FAN_CACHE = 16 };

void geom_face(const double *pts, const int *idx, int n, double Sf[3], double Cf[3])
{
    if (n == 3) {
        triangle(pts, idx, Sf, Cf);
        return;
    }
    double m[3];
    point_average(pts, idx, n, m);
    /* First pass: N = sum of the doubled triangle area vectors, which
       fixes the sign of each triangle's weight in the second pass; the
       triangles of small faces are kept rather than recomputed. */
    double N[3] = {0, 0, 0}, tc[FAN_CACHE][3], uvc[FAN_CACHE][3];
    for (int i = 0; i < n; i++) {
        double t[3], uv[3];
        fan(pts, idx, n, i, m, t, uv);
        if (i < FAN_CACHE) {
            memcpy(tc[i], t, sizeof t);
            memcpy(uvc[i], uv, sizeof uv);
        }
        N[0] += t[0];
        N[1] += t[1];
        N[2] += t[2];
    }
    Sf[0] = 0.5 * N[0];
    Sf[1] = 0.5 * N[1];
    Sf[2] = 0.5 * N[2];
    Cf[0] = m[0];
    Cf[1] = m[1];
    Cf[2] = m[2];
    if (N[0] == 0 && N[1] == 0 && N[2] == 0) return; /* degenerate: centre at m */
    double sa = 0, sc[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        double tb[3], uvb[3];
        const double *t = tb, *uv = uvb;
        if (i < FAN_CACHE) {
            t = tc[i];
            uv = uvc[i];
        } else {
            fan(pts, idx, n, i, m, tb, uvb);
        }
        double a = geom_dot(t, N) >= 0 ? geom_norm(t) : -geom_norm(t);
        sa += a;
        sc[0] += a * uv[0];
        sc[1] += a * uv[1];
        sc[2] += a * uv[2];
    }
    if (sa != 0) {
        Cf[0] = m[0] + sc[0] / (3 * sa);
        Cf[1] = m[1] + sc[1] / (3 * sa);
        Cf[2] = m[2] + sc[2] / (3 * sa);
    }
}

/* Adds the tetrahedron (d, a, b, c) with a, b, c given relative to d:
   6 x signed volume, and 6V times the centroid offset times 4. */
static inline void tet(const double a[3], const double b[3], const double c[3], double sgn,
                double *v6, double s[3])
{
    double t[3];
    geom_cross(b, c, t);
    double w = sgn * geom_dot(a, t);
    *v6 += w;
    s[0] += w * (a[0] + b[0] + c[0]);
    s[1] += w * (a[1] + b[1] + c[1]);
    s[2] += w * (a[2] + b[2] + c[2]);
}

void geom_cell(const double *pts, const int *off, const int *idx,
               const int *faces, const char *flip, int nf,
               const double *Sf, const double *Cf, double *vol, double C[3])
{
    /* The area vectors are implied by the fan triangles, which carry them
       exactly; only the centroids enter (through d). */
    (void)Sf;
    double d[3] = {0, 0, 0};
    for (int k = 0; k < nf; k++) {
        const double *c = Cf + 3 * (size_t)faces[k];
        d[0] += c[0];
        d[1] += c[1];
        d[2] += c[2];
    }
    if (nf > 0) {
        d[0] /= nf;
        d[1] /= nf;
        d[2] /= nf;
    }
    double v6 = 0, s[3] = {0, 0, 0};
    for (int k = 0; k < nf; k++) {
        int f = faces[k];
        const int *fi = idx + off[f];
        int n = off[f + 1] - off[f];
        double sgn = flip[k] ? -1.0 : 1.0;
        if (n < 3) continue;
        if (n == 3) {
            double a[3], b[3], c[3];
            sub(pts + 3 * (size_t)fi[0], d, a);
            sub(pts + 3 * (size_t)fi[1], d, b);
            sub(pts + 3 * (size_t)fi[2], d, c);
            tet(a, b, c, sgn, &v6, s);
            continue;
        }
        double m[3];
        point_average(pts, fi, n, m);
        m[0] -= d[0];
        m[1] -= d[1];
        m[2] -= d[2];
        double a[3], b[3];
        sub(pts + 3 * (size_t)fi[0], d, a);
        for (int i = 0; i < n; i++) {
            sub(pts + 3 * (size_t)fi[i + 1 < n ? i + 1 : 0], d, b);
            tet(a, b, m, sgn, &v6, s);
            a[0] = b[0];
            a[1] = b[1];
            a[2] = b[2];
        }
    }
    *vol = v6 / 6.0;
    C[0] = d[0];
    C[1] = d[1];
    C[2] = d[2];
    if (v6 != 0) {
        C[0] += s[0] / (4 * v6);
        C[1] += s[1] / (4 * v6);
        C[2] += s[2] / (4 * v6);
    }
}
