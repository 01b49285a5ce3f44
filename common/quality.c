/*
** quality.c: grid quality measures and soundness checks (see quality.h).
**
** One pass over the faces gives orientation, non-orthogonality and
** skewness; one pass over the cells (through the cell -> face addressing)
** gives closedness, aspect ratio, volumes and the Cartesian-parent
** comparisons.  Nothing is allocated per face or per cell beyond the
** mesh's own geometry arrays.
**
** Closedness is measured against the cell's whole surface sum |S_f| (not
** per component, as OpenFOAM does) so that the 1e-12 threshold means "the
** faces close to round-off", whatever the cell's orientation.
**
** Cut and merged cells need the Cartesian extras: a cell is cut when its
** volume is below its parent's by more than 1e-9 relative, and merged when
** one of its points lies outside its parent's box by more than 1e-9 of
** the parent's size (a merged cell spans several parents; its cellParent
** names only one of them).
*/
#include "quality.h"
#include "cartcells.h"
#include "geom.h"
#include "mem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ROOTVSMALL 1e-150
#define VSMALL 1e-300
#define PARENT_TOL 1e-9
#define RAD2DEG (180.0 / 3.14159265358979323846)

static void sub3(const double *a, const double *b, double *c)
{
    c[0] = a[0] - b[0];
    c[1] = a[1] - b[1];
    c[2] = a[2] - b[2];
}

double quality_ortho(const double d[3], const double S[3])
{
    return geom_dot(d, S) / (geom_norm(d) * geom_norm(S) + ROOTVSMALL);
}

void quality_foam_face(const double *pts, const int *idx, int n, double S[3], double C[3])
{
    if (n == 3) {
        const double *a = pts + 3 * (size_t)idx[0], *b = pts + 3 * (size_t)idx[1], *c = pts + 3 * (size_t)idx[2];
        double u[3], v[3];
        sub3(b, a, u);
        sub3(c, a, v);
        geom_cross(u, v, S);
        for (int k = 0; k < 3; k++) {
            S[k] *= 0.5;
            C[k] = (a[k] + b[k] + c[k]) / 3.0;
        }
        return;
    }
    double m[3] = {0, 0, 0};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) m[k] += pts[3 * (size_t)idx[i] + k];
    for (int k = 0; k < 3; k++) m[k] /= n;
    /* relative to m: the weights and the sum are OpenFOAM's, the digits
       are kept when the face lies far from the origin */
    double sumN[3] = {0, 0, 0}, sumA = 0, sumAc[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        double u[3], v[3], t[3];
        sub3(pts + 3 * (size_t)idx[i], m, u);
        sub3(pts + 3 * (size_t)idx[(i + 1) % n], m, v);
        geom_cross(u, v, t);
        double a = geom_norm(t);
        for (int k = 0; k < 3; k++) {
            sumN[k] += t[k];
            sumAc[k] += a * (u[k] + v[k]);
        }
        sumA += a;
    }
    for (int k = 0; k < 3; k++) {
        S[k] = sumA < ROOTVSMALL ? 0 : 0.5 * sumN[k];
        C[k] = sumA < ROOTVSMALL ? m[k] : m[k] + sumAc[k] / (3 * sumA);
    }
}

void quality_foam_cell(int nf, const double *SC, const signed char *sgn, double cc[3])
{
    double est[3] = {0, 0, 0}, v = 0, s[3] = {0, 0, 0};
    for (int i = 0; i < nf; i++)
        for (int k = 0; k < 3; k++) est[k] += SC[6 * i + 3 + k];
    for (int k = 0; k < 3; k++) est[k] /= nf > 0 ? nf : 1;
    for (int i = 0; i < nf; i++) {
        const double *S = SC + 6 * i, *C = S + 3;
        double d[3];
        sub3(C, est, d);
        double p = sgn[i] * geom_dot(S, d);   /* 3 x the pyramid's volume */
        v += p;
        for (int k = 0; k < 3; k++) s[k] += p * 0.75 * d[k];   /* pyramid centre - est = 3/4 d */
    }
    for (int k = 0; k < 3; k++) cc[k] = fabs(v) > VSMALL ? est[k] + s[k] / v : est[k];
}

void quality_foam_geometry(const Mesh *m, double *fS, double *fC, double *cc)
{
    int nc = m->ncells;
    int *nface = MEM_NEW(int, (size_t)nc + 1);
    double *est = MEM_NEW(double, 3 * (size_t)nc + 1), *vol = MEM_NEW(double, (size_t)nc + 1);
    for (int f = 0; f < m->nfaces; f++) {
        quality_foam_face(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f],
                          fS + 3 * (size_t)f, fC + 3 * (size_t)f);
        for (int side = 0; side < (f < m->ninternal ? 2 : 1); side++) {
            int c = side ? m->neighbour[f] : m->owner[f];
            nface[c]++;
            for (int k = 0; k < 3; k++) est[3 * (size_t)c + k] += fC[3 * (size_t)f + k];
        }
    }
    for (int c = 0; c < nc; c++)
        for (int k = 0; k < 3; k++) {
            est[3 * (size_t)c + k] /= nface[c] ? nface[c] : 1;
            cc[3 * (size_t)c + k] = 0;
        }
    for (int f = 0; f < m->nfaces; f++)
        for (int side = 0; side < (f < m->ninternal ? 2 : 1); side++) {
            int c = side ? m->neighbour[f] : m->owner[f];
            double d[3];
            sub3(fC + 3 * (size_t)f, est + 3 * (size_t)c, d);
            double p = (side ? -1 : 1) * geom_dot(fS + 3 * (size_t)f, d);
            vol[c] += p;
            for (int k = 0; k < 3; k++) cc[3 * (size_t)c + k] += p * 0.75 * d[k];
        }
    for (int c = 0; c < nc; c++)
        for (int k = 0; k < 3; k++) {
            double e = est[3 * (size_t)c + k];
            cc[3 * (size_t)c + k] = fabs(vol[c]) > VSMALL ? e + cc[3 * (size_t)c + k] / vol[c] : e;
        }
    free(nface);
    free(est);
    free(vol);
}

/* OpenFOAM's normalised skewness of the face (points idx[0..n-1], area
   vector S, centre Cf), given its d vector and the vector Cpf from the
   owner centre to the face centre; fd0 is the lower bound of the
   normalising distance (0.2|d| inside, 0.4|d| on the boundary). */
static double skew(const double *pts, const int *idx, int n, const double S[3], const double Cf[3],
                   const double Cpf[3], const double d[3], double fd0)
{
    double r = geom_dot(S, Cpf) / (geom_dot(S, d) + ROOTVSMALL), sv[3];
    for (int k = 0; k < 3; k++) sv[k] = Cpf[k] - r * d[k];
    double msv = geom_norm(sv), hat[3];
    for (int k = 0; k < 3; k++) hat[k] = sv[k] / (msv + ROOTVSMALL);
    double fd = fd0 + ROOTVSMALL;
    for (int i = 0; i < n; i++) {
        double r2[3];
        sub3(pts + 3 * (size_t)idx[i], Cf, r2);
        double t = fabs(geom_dot(hat, r2));
        if (t > fd) fd = t;
    }
    return msv / fd;
}

double quality_face_skew(const double *pts, const int *idx, int n, const double S[3], const double Cf[3],
                         const double cown[3], const double cnei[3])
{
    double Cpf[3], d[3];
    sub3(Cf, cown, Cpf);
    if (cnei) {
        sub3(cnei, cown, d);
        return skew(pts, idx, n, S, Cf, Cpf, d, 0.2 * geom_norm(d));
    }
    double ms = geom_norm(S) + ROOTVSMALL, nrm[3];
    for (int k = 0; k < 3; k++) nrm[k] = S[k] / ms;
    double dn = geom_dot(nrm, Cpf);
    for (int k = 0; k < 3; k++) d[k] = nrm[k] * dn;
    return skew(pts, idx, n, S, Cf, Cpf, d, 0.4 * geom_norm(d));
}

double quality_skewness(const Mesh *m, int f, const double cown[3], const double cnei[3])
{
    return quality_face_skew(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f],
                             m->face_area + 3 * (size_t)f, m->face_centre + 3 * (size_t)f, cown, cnei);
}

double quality_boundary_skewness(const Mesh *m, int f, const double cown[3])
{
    return quality_skewness(m, f, cown, NULL);
}

/* Closedness |sum S| / sum |S| (outward S) and aspect ratio of cell c;
   empty[k] marks empty directions (NULL: none). */
static void quality_cell(const Mesh *m, int c, const int empty[3], double *open, double *aspect)
{
    double sum[3] = {0, 0, 0}, mag[3] = {0, 0, 0}, surf = 0;
    for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
        int f = m->cell_faces[i];
        const double *S = m->face_area + 3 * (size_t)f;
        double s = m->owner[f] == c ? 1 : -1;
        for (int k = 0; k < 3; k++) {
            sum[k] += s * S[k];
            mag[k] += fabs(S[k]);
        }
        surf += geom_norm(S);
    }
    *open = geom_norm(sum) / (surf + ROOTVSMALL);
    *aspect = quality_aspect(mag, m->cell_vol[c], empty);
}

double quality_aspect(const double mag[3], double vol, const int empty[3])
{
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    int nd = 0;
    for (int k = 0; k < 3; k++)
        if (!empty || !empty[k]) {
            nd++;
            if (mag[k] < lo) lo = mag[k];
            if (mag[k] > hi) hi = mag[k];
        }
    double ar = nd ? hi / (lo + ROOTVSMALL) : 1;
    if (nd == 3) {
        double v = vol > ROOTVSMALL ? vol : ROOTVSMALL;
        double a3 = (mag[0] + mag[1] + mag[2]) / 6 / pow(v, 2.0 / 3.0);
        if (a3 > ar) ar = a3;
    }
    return ar;
}

/* Directions normal to the faces of empty patches (OpenFOAM's geometricD). */
static void quality_empty_dirs(const Mesh *m, int empty[3])
{
    empty[0] = empty[1] = empty[2] = 0;
    for (int p = 0; p < m->npatches; p++) {
        if (!mesh_patch_is_empty(&m->patches[p])) continue;
        for (int f = m->patches[p].start; f < m->patches[p].start + m->patches[p].size; f++) {
            const double *S = m->face_area + 3 * (size_t)f;
            int k = fabs(S[0]) >= fabs(S[1]) ? 0 : 1;
            if (fabs(S[2]) > fabs(S[k])) k = 2;
            empty[k] = 1;
        }
    }
}

/* OpenFOAM's geometry of a mesh (quality_foam_geometry), which the
   non-orthogonality and skewness are measured on. */
typedef struct FoamGeo {
    double *S, *C, *cc;   /* face area vectors, face centres, cell centres */
} FoamGeo;

static void foam_geo(const Mesh *m, FoamGeo *g)
{
    g->S = mem_alloc(3 * sizeof(double) * ((size_t)m->nfaces + 1));
    g->C = mem_alloc(3 * sizeof(double) * ((size_t)m->nfaces + 1));
    g->cc = mem_alloc(3 * sizeof(double) * ((size_t)m->ncells + 1));
    quality_foam_geometry(m, g->S, g->C, g->cc);
}

static void foam_geo_free(FoamGeo *g)
{
    free(g->S);
    free(g->C);
    free(g->cc);
}

/* Centre of the cell across face f when f is on a cyclic patch with a
   partner of equal size (translated to this side), else NULL. */
static const double *cyclic_centre(const Mesh *m, const FoamGeo *g, int f, double out[3])
{
    int p = mesh_face_patch(m, f);
    if (p < 0 || strcmp(m->patches[p].type, "cyclic") || !m->patches[p].neighbour) return NULL;
    int q = mesh_patch(m, m->patches[p].neighbour);
    if (q < 0 || m->patches[q].size != m->patches[p].size) return NULL;
    int h = m->patches[q].start + (f - m->patches[p].start);
    const double *Cn = g->cc + 3 * (size_t)m->owner[h];
    const double *Cf = g->C + 3 * (size_t)f, *Ch = g->C + 3 * (size_t)h;
    for (int k = 0; k < 3; k++) out[k] = Cn[k] + (Cf[k] - Ch[k]);
    return out;
}

/* Skewness of face f and the cosine of its non-orthogonality angle (NAN
   for a boundary face that is not cyclic); *Cn the centre across f, or
   NULL. */
static double face_measures(const Mesh *m, const FoamGeo *g, int f, double tmp[3], const double **Cn, double *cosn)
{
    const double *S = g->S + 3 * (size_t)f, *Cp = g->cc + 3 * (size_t)m->owner[f];
    *Cn = f < m->ninternal ? g->cc + 3 * (size_t)m->neighbour[f] : cyclic_centre(m, g, f, tmp);
    *cosn = NAN;
    if (*Cn) {
        double d[3];
        sub3(*Cn, Cp, d);
        *cosn = quality_ortho(d, S);
    }
    return quality_face_skew(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], S,
                             g->C + 3 * (size_t)f, Cp, *Cn);
}

void quality_face_measures(const Mesh *m, double *skewness, double *cosn)
{
    FoamGeo g;
    foam_geo(m, &g);
    for (int f = 0; f < m->nfaces; f++) {
        double tmp[3], c;
        const double *Cn;
        double sk = face_measures(m, &g, f, tmp, &Cn, &c);
        if (skewness) skewness[f] = sk;
        if (cosn) cosn[f] = c;
    }
    foam_geo_free(&g);
}

static void measure_faces(const Mesh *m, Quality *q)
{
    double cos_min = 2, cos_sum = 0;
    long ncos = 0;
    double sev = cos(QUALITY_NONORTH_SEVERE / RAD2DEG);
    FoamGeo g;
    foam_geo(m, &g);
    for (int f = 0; f < m->nfaces; f++) {
        const double *S = m->face_area + 3 * (size_t)f, *Cf = m->face_centre + 3 * (size_t)f;
        const double *Cp = m->cell_centre + 3 * (size_t)m->owner[f];
        double tmp[3], c;
        const double *Cn;
        double sk = face_measures(m, &g, f, tmp, &Cn, &c);
        if (Cn) {
            if (c < cos_min) cos_min = c, q->nonorth_face = f;
            cos_sum += c;
            ncos++;
            if (c < sev) q->nnonorth++;
        }
        /* orientation on the exact geometry: a grid is broken by it, not
           by OpenFOAM's approximation of it */
        double out[3];
        if (f < m->ninternal) sub3(m->cell_centre + 3 * (size_t)m->neighbour[f], Cp, out);
        else sub3(Cf, Cp, out);
        if (!(geom_dot(out, S) > 0) && q->norient++ == 0) q->orient_face = f, q->orient_cell = m->owner[f];
        if (sk > q->skew_max) q->skew_max = sk, q->skew_face = f;
        if (sk > QUALITY_SKEW_HIGH) q->nskew++;
    }
    foam_geo_free(&g);
    if (ncos) {
        q->nonorth_max = acos(fmin(1, fmax(-1, cos_min))) * RAD2DEG;
        q->nonorth_avg = acos(fmin(1, fmax(-1, cos_sum / (double)ncos))) * RAD2DEG;
    }
}

/* Parent box of cell c (lo, hi) from the Cartesian extras; 0 if none. */
static int parent_box(const Mesh *m, int c, double lo[3], double hi[3])
{
    const CartGrid *g = &m->cart;
    if (!m->cell_parent || g->n[0] <= 0 || g->n[1] <= 0 || g->n[2] <= 0) return 0;
    int p = m->cell_parent[c];
    if (p < 0 || p >= g->n[0] * g->n[1] * g->n[2]) return 0;
    int ijk[3] = {p % g->n[0], (p / g->n[0]) % g->n[1], p / (g->n[0] * g->n[1])};
    for (int k = 0; k < 3; k++) {
        lo[k] = g->x[k][ijk[k]];
        hi[k] = g->x[k][ijk[k] + 1];
    }
    return 1;
}

static int outside_box(const Mesh *m, int c, const double lo[3], const double hi[3])
{
    for (int i = m->cell_off[c]; i < m->cell_off[c + 1]; i++) {
        int f = m->cell_faces[i];
        for (int j = m->face_off[f]; j < m->face_off[f + 1]; j++) {
            const double *x = m->points + 3 * (size_t)m->face_idx[j];
            for (int k = 0; k < 3; k++) {
                double tol = PARENT_TOL * (hi[k] - lo[k]);
                if (x[k] < lo[k] - tol || x[k] > hi[k] + tol) return 1;
            }
        }
    }
    return 0;
}

static void measure_parent(const Mesh *m, Quality *q, int c)
{
    double lo[3], hi[3];
    if (!parent_box(m, c, lo, hi)) return;
    double pv = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    double fr = m->cell_vol[c] / pv;
    q->has_parent = 1;
    if (fr < q->frac_min) q->frac_min = fr;
    if (fr > q->frac_max) q->frac_max = fr;
    if (c == q->vol_min_cell) q->vol_min_ratio = fr;
    if (c == q->vol_max_cell) q->vol_max_ratio = fr;
    if (fr < 1 - PARENT_TOL) q->ncut++;
    if (outside_box(m, c, lo, hi)) q->nmerged++;
}

static void measure_cells(const Mesh *m, Quality *q)
{
    q->vol_min = HUGE_VAL;
    q->vol_max = -HUGE_VAL;
    for (int c = 0; c < m->ncells; c++) {
        double v = m->cell_vol[c], open, ar;
        q->vol_total += v;
        if (v < q->vol_min) q->vol_min = v, q->vol_min_cell = c;
        if (v > q->vol_max) q->vol_max = v, q->vol_max_cell = c;
        if (!(v > 0) && q->nnegvol++ == 0) q->negvol_cell = c;
        quality_cell(m, c, q->empty, &open, &ar);
        if (open > q->open_max) q->open_max = open;
        if (!(open <= QUALITY_CLOSED_TOL) && q->nopen++ == 0) q->open_cell = c, q->open_first = open;
        if (ar > q->aspect_max) q->aspect_max = ar, q->aspect_cell = c;
        if (ar > QUALITY_ASPECT_HIGH) q->naspect++;
    }
    if (m->ncells == 0) q->vol_min = q->vol_max = 0;
    q->frac_min = HUGE_VAL;
    q->frac_max = -HUGE_VAL;
    q->vol_min_ratio = q->vol_max_ratio = NAN;
    for (int c = 0; c < m->ncells; c++) measure_parent(m, q, c);
    if (!q->has_parent) q->frac_min = q->frac_max = NAN;
}

/* Angle (degrees) between area vector S and direction d: atan2 of the
   cross and dot products, exact near 0 where acos is not. */
static double angle_deg(const double S[3], const double d[3])
{
    double x[3] = {S[1] * d[2] - S[2] * d[1], S[2] * d[0] - S[0] * d[2], S[0] * d[1] - S[1] * d[0]};
    return atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), S[0] * d[0] + S[1] * d[1] + S[2] * d[2]) * RAD2DEG;
}

static void measure_seeds(const Mesh *m, Quality *q)
{
    if (!m->cell_seed) return;
    q->has_seed = 1;
    for (int f = 0; f < m->ninternal; f++) {
        const double *a = m->cell_seed + 3 * (size_t)m->owner[f], *b = m->cell_seed + 3 * (size_t)m->neighbour[f];
        double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double ang = angle_deg(m->face_area + 3 * (size_t)f, d);
        if (ang > q->seed_angle_max) q->seed_angle_max = ang, q->seed_angle_face = f;
        for (int k = m->face_off[f]; k < m->face_off[f + 1] && len > 0; k++) {
            const double *p = m->points + 3 * (size_t)m->face_idx[k];
            double off = 0;
            for (int j = 0; j < 3; j++) off += (p[j] - 0.5 * (a[j] + b[j])) * d[j] / len;
            q->seed_offset_max = fmax(q->seed_offset_max, fabs(off));
        }
    }
    for (int c = 0; c < m->ncells; c++) {
        const double *x = m->cell_seed + 3 * (size_t)c;
        int in = 1;
        for (int k = m->cell_off[c]; k < m->cell_off[c + 1] && in; k++) {
            int f = m->cell_faces[k];
            const double *fc = m->face_centre + 3 * (size_t)f, *S = m->face_area + 3 * (size_t)f;
            double t = (x[0] - fc[0]) * S[0] + (x[1] - fc[1]) * S[1] + (x[2] - fc[2]) * S[2];
            in = (m->owner[f] == c ? t : -t) < 0;
        }
        q->nseed_outside += !in;
    }
}

void quality_measure(Mesh *m, Quality *q)
{
    memset(q, 0, sizeof *q);
    if (!m->cell_off) mesh_cell_faces(m);
    if (!m->cell_vol) mesh_geometry(m);
    mesh_bounds(m, q->lo, q->hi);
    quality_empty_dirs(m, q->empty);
    q->ndims = 3 - q->empty[0] - q->empty[1] - q->empty[2];
    measure_faces(m, q);
    measure_cells(m, q);
    measure_seeds(m, q);
}

int quality_check(const Mesh *m, const Quality *q, int *nfailed, Err *e)
{
    Err first, tmp;
    int nf = 0;
    first.msg[0] = 0;
    if (q->nopen && nf++ == 0)
        err_set(&first, NULL, 0, "cell %d: not closed, |sum S| = %.3g of surface (%d open cells)",
                q->open_cell, q->open_first, q->nopen);
    if (q->norient && nf++ == 0)
        err_set(&first, NULL, 0,
                "cell %d: face %d points into the cell, not towards its %s (%d such faces)",
                q->orient_cell, q->orient_face, q->orient_face < m->ninternal ? "neighbour" : "outside",
                q->norient);
    if (q->nnegvol && nf++ == 0)
        err_set(&first, NULL, 0, "cell %d: volume %.6g is not positive (%d such cells)", q->negvol_cell,
                m->cell_vol[q->negvol_cell], q->nnegvol);
    /* mesh_check without the geometry: ordering and topology only (its
       own closedness test would count the open cells a second time) */
    Mesh topo = *m;
    topo.face_area = topo.cell_vol = NULL;
    if (mesh_check(&topo, &tmp) && nf++ == 0) first = tmp;
    if (m->cartcells.n > 0 && mesh_check_cartesian(m, CARTCELLS_TOL, &tmp) && nf++ == 0) first = tmp;
    if (nfailed) *nfailed = nf;
    if (!nf) return 0;
    if (e) *e = first;
    return -1;
}

static const char *dims_name(const Quality *q)
{
    return q->ndims == 3 ? "3-D" : q->ndims == 2 ? "2-D" : q->ndims == 1 ? "1-D" : "0-D";
}

static void report_volumes(const Quality *q, Buf *out)
{
    buf_printf(out, "    Total volume = %.12g\n", q->vol_total);
    buf_printf(out, "    Min volume = %.6g (cell %d)", q->vol_min, q->vol_min_cell);
    if (q->has_parent) buf_printf(out, ", %.6g of its parent cell", q->vol_min_ratio);
    buf_printf(out, "\n    Max volume = %.6g (cell %d)", q->vol_max, q->vol_max_cell);
    if (q->has_parent) buf_printf(out, ", %.6g of its parent cell", q->vol_max_ratio);
    buf_printf(out, "\n");
    if (q->has_parent)
        buf_printf(out, "    Volume / parent volume: min %.6g max %.6g\n", q->frac_min, q->frac_max);
    buf_printf(out, "    Cut cells: %d\n    Merged cells: %d\n", q->ncut, q->nmerged);
}

/* The roles of the Cartesian cells (cartesianCells), when present; the
   check itself is quality_check's (mesh_check_cartesian). */
static void report_cartesian(const Mesh *m, Buf *out)
{
    const CartCells *cc = &m->cartcells;
    if (cc->n <= 0) return;
    int count[CART_NROLES] = {0};
    for (int K = 0; K < cc->n; K++)
        if (cc->role[K] >= 0 && cc->role[K] < CART_NROLES) count[cc->role[K]]++;
    buf_printf(out, "    Cartesian cells: %d (", cc->n);
    for (int r = 0; r < CART_NROLES; r++) buf_printf(out, "%s%s %d", r ? ", " : "", cartcells_role_name(r), count[r]);
    buf_printf(out, ")\n");
}

void quality_report(const Mesh *m, const Quality *q, Buf *out)
{
    buf_printf(out, "Grid stats\n    points:           %d\n    faces:            %d\n", m->npoints,
               m->nfaces);
    buf_printf(out, "    internal faces:   %d\n    cells:            %d\n", m->ninternal, m->ncells);
    buf_printf(out, "    boundary patches: %d\n\n    Patch                Faces\n", m->npatches);
    for (int p = 0; p < m->npatches; p++)
        buf_printf(out, "    %-20s %d  (%s)\n", m->patches[p].name, m->patches[p].size,
                   m->patches[p].type);
    buf_printf(out, "\nChecking geometry...\n");
    buf_printf(out, "    Overall domain bounding box (%.15g %.15g %.15g) (%.15g %.15g %.15g)\n", q->lo[0],
               q->lo[1], q->lo[2], q->hi[0], q->hi[1], q->hi[2]);
    buf_printf(out, "    Grid is %s (empty directions: %d %d %d)\n", dims_name(q), q->empty[0],
               q->empty[1], q->empty[2]);
    report_volumes(q, out);
    report_cartesian(m, out);
    buf_printf(out, "    Max closedness |sum S|/surface = %.3g (open cells: %d)\n", q->open_max, q->nopen);
    buf_printf(out, "    Wrongly oriented faces: %d\n    Non-positive volumes: %d\n", q->norient,
               q->nnegvol);
    buf_printf(out, "    Non-orthogonality Max: %.6g average: %.6g (face %d)\n", q->nonorth_max,
               q->nonorth_avg, q->nonorth_face);
    if (q->has_seed)
        buf_printf(out, "    Voronoi seeds: faces against seed segments Max: %.3g degrees (face %d), face points off "
                        "the bisector Max: %.3g, seeds outside their cells: %d\n",
                   q->seed_angle_max, q->seed_angle_face, q->seed_offset_max, q->nseed_outside);
    buf_printf(out, "    Severely non-orthogonal (> %g degrees) faces: %d\n", QUALITY_NONORTH_SEVERE,
               q->nnonorth);
    buf_printf(out, "    Max skewness = %.10g (face %d), highly skew (> %g) faces: %d\n", q->skew_max,
               q->skew_face, QUALITY_SKEW_HIGH, q->nskew);
    buf_printf(out, "    Max aspect ratio = %.6g (cell %d), high (> %g) cells: %d\n", q->aspect_max,
               q->aspect_cell, QUALITY_ASPECT_HIGH, q->naspect);
}
