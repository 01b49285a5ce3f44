/*
** tvd.c: bounded second-order convection (tvd.h).
**
** Per grid: the least-squares normal matrix of each cell, sum over its
** internal faces of d d^T / |d|^2, inverted once (on a 2-D grid over the
** two in-plane axes), and each internal face's w.  Per call: gradients,
** the bounds lo/hi, then one loop over faces as fvc_div_upwind's, with the
** limited face value on internal faces and upwind on boundary faces.
*/
#include "tvd.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fvc.h"
#include "mem.h"

int tvd_parse(const DictEntry *en, TvdScheme *s, Err *e)
{
    const DictNode *const *v = (const DictNode *const *)en->vals;
    size_t n = en->nvals;
    int gauss = !en->dict && n >= 2 && v[0]->kind == DN_WORD && !strcmp(v[0]->text, "Gauss") && v[1]->kind == DN_WORD;
    const char *name = gauss ? v[1]->text : "";
    s->k = 1;
    if (gauss && n == 2 && !strcmp(name, "upwind")) s->kind = TVD_UPWIND;
    else if (gauss && n == 2 && !strcmp(name, "vanLeer")) s->kind = TVD_VAN_LEER;
    else if (gauss && n == 3 && !strcmp(name, "limitedLinear") && v[2]->kind == DN_NUMBER) {
        s->kind = TVD_LIMITED_LINEAR;
        s->k = v[2]->num;
        if (!(s->k >= 0 && s->k <= 1))
            return err_set(e, en->file, en->line, "divSchemes: %s: limitedLinear's coefficient %g is not in [0, 1]",
                           en->key, s->k);
    } else
        return err_set(e, en->file, en->line,
                       "divSchemes: %s: unknown scheme; known: 'Gauss upwind' (eq. 4.60), 'Gauss limitedLinear k' "
                       "(0 <= k <= 1), 'Gauss vanLeer'",
                       en->key);
    return 0;
}

void tvd_name(const TvdScheme *s, char *out, size_t n)
{
    if (s->kind == TVD_LIMITED_LINEAR) snprintf(out, n, "Gauss limitedLinear %g", s->k);
    else snprintf(out, n, "Gauss %s", s->kind == TVD_VAN_LEER ? "vanLeer" : "upwind");
}

/* Inverse of the symmetric matrix G (3x3, row major) over the axes other
   than skip (-1: all three) into inv; 0 rows and columns elsewhere.  A
   matrix whose determinant is below 1e-10 of its scale (the nodes of the
   neighbours nearly on a line or plane) gives inv = 0. */
static void invert(const double G[9], int skip, double inv[9])
{
    memset(inv, 0, 9 * sizeof(double));
    if (skip >= 0) {
        int a = (skip + 1) % 3, b = (skip + 2) % 3;
        double p = G[3 * a + a], q = G[3 * a + b], r = G[3 * b + b], det = p * r - q * q, tr = p + r;
        if (!(det > 1e-10 * 0.25 * tr * tr)) return;
        inv[3 * a + a] = r / det, inv[3 * b + b] = p / det;
        inv[3 * a + b] = inv[3 * b + a] = -q / det;
        return;
    }
    double c[9] = {G[4] * G[8] - G[5] * G[7], G[2] * G[7] - G[1] * G[8], G[1] * G[5] - G[2] * G[4],
                   G[5] * G[6] - G[3] * G[8], G[0] * G[8] - G[2] * G[6], G[2] * G[3] - G[0] * G[5],
                   G[3] * G[7] - G[4] * G[6], G[1] * G[6] - G[0] * G[7], G[0] * G[4] - G[1] * G[3]};
    double det = G[0] * c[0] + G[1] * c[3] + G[2] * c[6], tr = (G[0] + G[4] + G[8]) / 3;
    if (!(det > 1e-10 * tr * tr * tr)) return;
    for (int i = 0; i < 9; i++) inv[i] = c[i] / det;
}

/* The cell across face i (internal, or cyclic: fvmesh_across) into *n, d
   = its node (moved back by the periodic translation) minus the owner's;
   returns 1 / |d|^2, or 0 when nothing is across. */
static double across(const FvMesh *f, int i, int *n, double d[3])
{
    double x[3];
    *n = f->empty_face[i] ? -1 : fvmesh_across(f, i, x);
    if (*n < 0) return 0;
    const double *xo = f->node + 3 * f->m->owner[i];
    for (int j = 0; j < 3; j++) d[j] = x[j] - xo[j];
    return 1 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Faces are visited once each: an internal face adds to both cells, a
   cyclic face to its owner only (its partner face adds to the other). */
void tvd_init(Tvd *t, const FvMesh *f, int ncomp)
{
    memset(t, 0, sizeof *t);
    t->f = f;
    t->ncomp = ncomp;
    if (ncomp <= 0) return;
    const Mesh *m = f->m;
    size_t nc = (size_t)f->ncells + 1;
    double *G = mem_calloc(9 * nc, sizeof(double));
    t->ginv = mem_alloc(9 * nc * sizeof(double));
    t->wf = mem_calloc((size_t)f->nfaces + 1, sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        int o = m->owner[i], n;
        double d[3], w = across(f, i, &n, d), s = 0;
        if (n < 0) continue;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                G[9 * o + 3 * a + b] += w * d[a] * d[b];
                if (i < f->ninternal) G[9 * n + 3 * a + b] += w * d[a] * d[b];
            }
        for (int j = 0; j < 3; j++) s += (m->face_centre[3 * i + j] - f->node[3 * o + j]) * d[j];
        t->wf[i] = fmin(1, fmax(0, s * w));
    }
    for (int c = 0; c < f->ncells; c++) invert(G + 9 * c, f->empty_axis, t->ginv + 9 * c);
    free(G);
    t->grad = mem_alloc(3 * (size_t)ncomp * nc * sizeof(double));
    t->lo = mem_alloc((size_t)ncomp * nc * sizeof(double));
    t->hi = mem_alloc((size_t)ncomp * nc * sizeof(double));
}

void tvd_free(Tvd *t)
{
    free(t->ginv);
    free(t->wf);
    free(t->grad);
    free(t->lo);
    free(t->hi);
    memset(t, 0, sizeof *t);
}

void tvd_grad(const Tvd *t, const double *xc, int ncomp, double *grad)
{
    const FvMesh *f = t->f;
    const Mesh *m = f->m;
    size_t nk = (size_t)ncomp;
    /* grad first gathers the right-hand sides sum w d (x_N - x_C) */
    memset(grad, 0, 3 * nk * (size_t)f->ncells * sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        int o = m->owner[i], n;
        double d[3], w = across(f, i, &n, d);
        if (n < 0) continue;
        for (size_t k = 0; k < nk; k++) {
            double dx = w * (xc[nk * (size_t)n + k] - xc[nk * (size_t)o + k]);
            double *go = grad + 3 * (nk * (size_t)o + k), *gn = grad + 3 * (nk * (size_t)n + k);
            for (int j = 0; j < 3; j++) {
                go[j] += dx * d[j];
                if (i < f->ninternal) gn[j] += dx * d[j];
            }
        }
    }
    for (int c = 0; c < f->ncells; c++) {
        const double *A = t->ginv + 9 * c;
        for (size_t k = 0; k < nk; k++) {
            double *g = grad + 3 * (nk * (size_t)c + k), b[3] = {g[0], g[1], g[2]};
            for (int j = 0; j < 3; j++) g[j] = A[3 * j] * b[0] + A[3 * j + 1] * b[1] + A[3 * j + 2] * b[2];
        }
    }
}

/* lo and hi of every cell: the extremes of its value, the values across
   its internal and cyclic faces and, for each other boundary face, the
   value mirrored through the face, 2 x_b - x_C (the boundary value is
   half a cell away; the mirror stands where a neighbour would, so a
   smooth profile is not clipped at a boundary).  A mirror keeps the
   invariants of tvd.h: x_C - (2 x_b - x_C) = 2 (x_C - x_b) <= 2 x_C when
   x_b >= 0. */
static void bounds(Tvd *t, const double *xc, const double *xb, int ncomp)
{
    const FvMesh *f = t->f;
    const Mesh *m = f->m;
    size_t nk = (size_t)ncomp, nv = nk * (size_t)f->ncells;
    memcpy(t->lo, xc, nv * sizeof(double));
    memcpy(t->hi, xc, nv * sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        size_t o = nk * (size_t)m->owner[i];
        double x[3];
        int c = fvmesh_across(f, i, x);
        if (c >= 0) {
            size_t n = nk * (size_t)c;
            for (size_t k = 0; k < nk; k++) {
                t->lo[o + k] = fmin(t->lo[o + k], xc[n + k]), t->hi[o + k] = fmax(t->hi[o + k], xc[n + k]);
                if (i >= f->ninternal) continue;
                t->lo[n + k] = fmin(t->lo[n + k], xc[o + k]), t->hi[n + k] = fmax(t->hi[n + k], xc[o + k]);
            }
        } else {
            const double *v = xb + nk * (size_t)(i - f->ninternal);
            for (size_t k = 0; k < nk; k++) {
                double g = 2 * v[k] - xc[o + k];
                t->lo[o + k] = fmin(t->lo[o + k], g), t->hi[o + k] = fmax(t->hi[o + k], g);
            }
        }
    }
}

/* psi(r) of the limiter; r is finite. */
static double limiter(const TvdScheme *s, double r)
{
    if (s->kind == TVD_VAN_LEER) return r > 0 ? 2 * r / (1 + r) : 0;
    return fmax(0, fmin(2 / fmax(s->k, 1e-15) * r, 1));
}

/* The limited face value between xu (upwind) and xd with the upwind
   gradient's component along d, g_d = d . grad x_U, and the fraction w. */
static double face_value(const TvdScheme *s, double xu, double xd, double gd, double lo, double hi, double w)
{
    double delta = xd - xu;
    if (delta == 0) return xu;
    double xuu = fmin(hi, fmax(lo, xd - 2 * gd)), r = (xu - xuu) / delta;
    if (!(fabs(r) < 1e6)) r = r > 0 ? 1e6 : -1e6; /* a tiny delta: the limiter's far end */
    return xu + fmin(limiter(s, r) * w, 1) * delta;
}

void tvd_div(Tvd *t, const TvdScheme *s, const double *phi, const double *xc, const double *xb, int ncomp,
             double *out)
{
    const FvMesh *f = t->f;
    if (s->kind == TVD_UPWIND) {
        fvc_div_upwind(f, phi, xc, xb, ncomp, out);
        return;
    }
    const Mesh *m = f->m;
    size_t nk = (size_t)ncomp;
    tvd_grad(t, xc, ncomp, t->grad);
    bounds(t, xc, xb, ncomp);
    memset(out, 0, sizeof(double) * nk * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        int o = m->owner[i], n;
        double d[3];
        across(f, i, &n, d);
        if (n < 0) { /* a boundary: upwind (eq. 4.60) */
            const double *up = phi[i] >= 0 ? xc + nk * (size_t)o : xb + nk * (size_t)(i - f->ninternal);
            for (size_t k = 0; k < nk; k++) out[nk * (size_t)o + k] += up[k] * phi[i];
            continue;
        }
        int fwd = phi[i] >= 0, u = fwd ? o : n, dn = fwd ? n : o;
        double w = fwd ? t->wf[i] : 1 - t->wf[i], sg = fwd ? 1 : -1;
        for (size_t k = 0; k < nk; k++) {
            size_t iu = nk * (size_t)u + k;
            const double *g = t->grad + 3 * iu;
            double gd = sg * (g[0] * d[0] + g[1] * d[1] + g[2] * d[2]);
            double F = phi[i] * face_value(s, xc[iu], xc[nk * (size_t)dn + k], gd, t->lo[iu], t->hi[iu], w);
            out[nk * (size_t)o + k] += F;
            if (i < f->ninternal) out[nk * (size_t)n + k] -= F;
        }
    }
}
