/*
** volfrac.c: the volume of a mesh cell inside a Geometry's flow domain
** (volfrac.h), by tetrahedra.
**
** A cell is split into tetrahedra: each face triangle (face point average,
** p_k, p_k+1) joined to the cell centre.  Their signed volumes add up to
** the cell volume for any closed cell (divergence theorem), so the
** fraction is sum(sign_t * inside_t) / sum(signed_t) and lies in [0, 1]
** up to round-off for convex and star-shaped cells.
**
** Convex polytopes (geometry_planes: a box, a half-space, an intersection
** of them, under any affine map): a tetrahedron clipped by one plane is a
** tetrahedron or a triangular prism (three tetrahedra), so clipping plane
** after plane keeps a list of exact tetrahedra: the inside volume is
** exact up to round-off.
**
** Everything else (curved primitives, CSG, triangulated surfaces): the
** level phi = geometry_level is 1-Lipschitz, so over a tetrahedron of
** longest edge e, phi(x) lies within e of phi at any vertex.  A
** tetrahedron whose vertex values are all <= -e is inside, all >= e
** outside; any other one may straddle the surface and is split into eight
** (edge midpoints) down to VOLFRAC_DEPTH levels, where the surface is
** replaced by the zero plane of phi's linear interpolant (the same exact
** clip as for planes).  The linearisation error per tetrahedron of size h
** is O(kappa h^2) per unit area of surface, so the volume error is
** O(kappa (h/2^D)^2 * area): second order in the cell size.  Along edges
** and corners of the solid (a box's, a CSG difference's rim) phi has kinks
** where the linear interpolant errs at first order over one small
** tetrahedron, a line's worth of them: the error stays O(h^2 / 4^D) per
** unit length of edge.
**
** Flattened geometries (2-D meshes): geometry_level and geometry_planes
** evaluate the section plane's (geometry_flatten), which keeps phi
** 1-Lipschitz, so the same code computes the extruded section's share of
** the cell.
*/
#include "volfrac.h"

#include <math.h>
#include <string.h>

static double dist3(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* ---- exact tetrahedron clipping ---- */

typedef double Tet[4][3];

static double tet_vol(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

static void set_tet(Tet t, const double *a, const double *b, const double *c, const double *d)
{
    memcpy(t[0], a, sizeof t[0]);
    memcpy(t[1], b, sizeof t[1]);
    memcpy(t[2], c, sizeof t[2]);
    memcpy(t[3], d, sizeof t[3]);
}

/* Point where phi crosses zero on edge a (phi <= 0) - b (phi > 0). */
static void cut(const double a[3], double fa, const double b[3], double fb, double out[3])
{
    double s = fa / (fa - fb);
    for (int k = 0; k < 3; k++) out[k] = a[k] + s * (b[k] - a[k]);
}

/* Prism with triangles A, B and edges A_i-B_i as three tetrahedra. */
static int prism(Tet *out, const double *a0, const double *a1, const double *a2, const double *b0,
                 const double *b1, const double *b2)
{
    set_tet(out[0], a0, a1, a2, b2);
    set_tet(out[1], a0, a1, b1, b2);
    set_tet(out[2], a0, b0, b1, b2);
    return 3;
}

/* The part of tetrahedron v where the linear interpolant of the vertex
   values f is <= 0, as 0 to 3 tetrahedra; returns the count, or 4 when the
   whole tetrahedron is inside (out untouched). */
static int clip_tet(const Tet v, const double f[4], Tet *out)
{
    int in[4], out_[4], ni = 0, no = 0;
    for (int i = 0; i < 4; i++) {
        if (f[i] <= 0) in[ni++] = i;
        else out_[no++] = i;
    }
    if (ni == 4) return 4;
    if (ni == 0) return 0;
    if (ni == 1) {
        int a = in[0];
        double p[3][3];
        for (int j = 0; j < 3; j++) cut(v[a], f[a], v[out_[j]], f[out_[j]], p[j]);
        set_tet(out[0], v[a], p[0], p[1], p[2]);
        return 1;
    }
    if (ni == 2) {
        int a = in[0], b = in[1], c = out_[0], d = out_[1];
        double ac[3], ad[3], bc[3], bd[3];
        cut(v[a], f[a], v[c], f[c], ac);
        cut(v[a], f[a], v[d], f[d], ad);
        cut(v[b], f[b], v[c], f[c], bc);
        cut(v[b], f[b], v[d], f[d], bd);
        return prism(out, v[a], ac, ad, v[b], bc, bd);
    }
    int a = in[0], b = in[1], c = in[2], d = out_[0];
    double ad[3], bd[3], cd[3];
    cut(v[a], f[a], v[d], f[d], ad);
    cut(v[b], f[b], v[d], f[d], bd);
    cut(v[c], f[c], v[d], f[d], cd);
    return prism(out, v[a], v[b], v[c], ad, bd, cd);
}

static double clip_volume(const Tet v, const double f[4])
{
    Tet piece[3];
    int n = clip_tet(v, f, piece);
    if (n == 4) return fabs(tet_vol(v[0], v[1], v[2], v[3]));
    double s = 0;
    for (int i = 0; i < n; i++) s += fabs(tet_vol(piece[i][0], piece[i][1], piece[i][2], piece[i][3]));
    return s;
}

/* ---- plane-bounded shapes ---- */

static double planes_volume(const Tet v, const GeoPlane *pl, int np)
{
    if (np == 0) return fabs(tet_vol(v[0], v[1], v[2], v[3]));
    double f[4];
    for (int i = 0; i < 4; i++) f[i] = pl->n[0] * v[i][0] + pl->n[1] * v[i][1] + pl->n[2] * v[i][2] - pl->d;
    Tet piece[3];
    int n = clip_tet(v, f, piece);
    if (n == 4) return planes_volume(v, pl + 1, np - 1);
    double s = 0;
    for (int i = 0; i < n; i++) s += planes_volume((const double(*)[3])piece[i], pl + 1, np - 1);
    return s;
}

/* ---- curved shapes ---- */

static double max_edge(const Tet v)
{
    double e = 0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++) e = fmax(e, dist3(v[i], v[j]));
    return e;
}

static double curved_volume(const Geometry *g, const Tet v, const double f[4], int depth)
{
    double e = max_edge(v), lo = fmin(fmin(f[0], f[1]), fmin(f[2], f[3]));
    double hi = fmax(fmax(f[0], f[1]), fmax(f[2], f[3]));
    if (hi <= -e) return fabs(tet_vol(v[0], v[1], v[2], v[3]));
    if (lo >= e) return 0;
    if (depth == 0) return clip_volume(v, f);
    /* Midpoints m[i][j] of edge ij and their level values. */
    double m[4][4][3], fm[4][4];
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++) {
            for (int k = 0; k < 3; k++) m[i][j][k] = m[j][i][k] = 0.5 * (v[i][k] + v[j][k]);
            fm[i][j] = fm[j][i] = geometry_level(g, m[i][j]);
        }
    double s = 0;
    Tet c;
    double fc[4];
    /* Four corner tetrahedra. */
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            if (j == i) {
                memcpy(c[j], v[i], sizeof c[j]);
                fc[j] = f[i];
            } else {
                memcpy(c[j], m[i][j], sizeof c[j]);
                fc[j] = fm[i][j];
            }
        }
        s += curved_volume(g, (const double(*)[3])c, fc, depth - 1);
    }
    /* The inner octahedron about its diagonal m02-m13, whose four other
       vertices m01, m12, m23, m03 form a cycle around it. */
    static const int ring[4][2] = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
    for (int k = 0; k < 4; k++) {
        const int *p = ring[k], *q = ring[(k + 1) % 4];
        memcpy(c[0], m[0][2], sizeof c[0]);
        memcpy(c[1], m[1][3], sizeof c[1]);
        memcpy(c[2], m[p[0]][p[1]], sizeof c[2]);
        memcpy(c[3], m[q[0]][q[1]], sizeof c[3]);
        fc[0] = fm[0][2];
        fc[1] = fm[1][3];
        fc[2] = fm[p[0]][p[1]];
        fc[3] = fm[q[0]][q[1]];
        s += curved_volume(g, (const double(*)[3])c, fc, depth - 1);
    }
    return s;
}

/* Inside volume of tetrahedron v: exact clipping by the planes when
   np >= 0, else the refinement on the level function. */
static double tet_volume(const Geometry *g, const GeoPlane *pl, int np, const double v[4][3])
{
    if (np >= 0) return planes_volume(v, pl, np);
    double f[4];
    for (int i = 0; i < 4; i++) f[i] = geometry_level(g, v[i]);
    return curved_volume(g, v, f, VOLFRAC_DEPTH);
}

int volfrac_inside(const Geometry *g, const double x[3]) { return geometry_level(g, x) <= 0; }

/* ---- cells ---- */

double volfrac_cell(const Geometry *g, const Mesh *m, int c)
{
    const double *C = m->cell_centre + 3 * c;
    /* Quick classification from the centre: phi is 1-Lipschitz. */
    double R = 0;
    for (int k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
        int f = m->cell_faces[k];
        for (int i = m->face_off[f]; i < m->face_off[f + 1]; i++)
            R = fmax(R, dist3(C, m->points + 3 * m->face_idx[i]));
    }
    double phi = geometry_level(g, C);
    if (phi <= -R) return 1;
    if (phi >= R) return 0;

    GeoPlane pl[VOLFRAC_PLANES];
    int np = geometry_planes(g, pl, VOLFRAC_PLANES);
    double vin = 0, vtot = 0;
    for (int k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
        int f = m->cell_faces[k], i0 = m->face_off[f], n = m->face_off[f + 1] - i0;
        const int *idx = m->face_idx + i0;
        double Fa[3] = {0, 0, 0};
        for (int i = 0; i < n; i++)
            for (int d = 0; d < 3; d++) Fa[d] += m->points[3 * idx[i] + d] / n;
        int own = m->owner[f] == c;
        for (int i = 0; i < n; i++) {
            const double *a = m->points + 3 * idx[i], *b = m->points + 3 * idx[(i + 1) % n];
            Tet t;
            /* Ordered so that the signed volume is positive for an
               outward face triangle. */
            if (own) set_tet(t, C, Fa, a, b);
            else set_tet(t, C, Fa, b, a);
            double sv = tet_vol(t[0], t[1], t[2], t[3]);
            if (sv == 0) continue;
            vtot += sv;
            double in = tet_volume(g, pl, np, (const double(*)[3])t);
            vin += sv > 0 ? in : -in;
        }
    }
    if (!(vtot > 0)) return volfrac_inside(g, C);
    double frac = vin / vtot;
    return frac < 0 ? 0 : frac > 1 ? 1 : frac;
}
