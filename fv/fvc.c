/*
** fvc.c: explicit finite-volume operators (fvc.h).
**
** One loop over faces each: internal faces add to both cells, boundary
** faces to their owner; owned cells only receive (halo cells are written
** but not used, so a distributed run needs no special case here).
*/
#include "fvc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

/* fvc_div_upwind's loop, inlined with ncomp a constant where it is 1 or 3
   so that the component loops unroll. */
static inline void div_upwind(const FvMesh *f, const double *phi, const double *xc, const double *xb, int ncomp,
                              double *out)
{
    const Mesh *m = f->m;
    memset(out, 0, sizeof(double) * (size_t)ncomp * (size_t)f->ncells);
    for (int i = 0; i < f->ninternal; i++) {
        int o = m->owner[i], n = m->neighbour[i];
        const double *up = xc + (size_t)ncomp * (size_t)(phi[i] >= 0 ? o : n);
        for (int k = 0; k < ncomp; k++) {
            double F = up[k] * phi[i];
            out[(size_t)ncomp * o + k] += F;
            out[(size_t)ncomp * n + k] -= F;
        }
    }
    for (int i = f->ninternal; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        int o = m->owner[i];
        const double *up = phi[i] >= 0 ? xc + (size_t)ncomp * o : xb + (size_t)ncomp * (size_t)(i - f->ninternal);
        for (int k = 0; k < ncomp; k++) out[(size_t)ncomp * o + k] += up[k] * phi[i];
    }
}

void fvc_div_upwind(const FvMesh *f, const double *phi, const double *xc, const double *xb, int ncomp,
                    double *out)
{
    if (ncomp == 1) div_upwind(f, phi, xc, xb, 1, out);
    else if (ncomp == 3) div_upwind(f, phi, xc, xb, 3, out);
    else div_upwind(f, phi, xc, xb, ncomp, out);
}

void fvc_pressure_force(const FvMesh *f, const double *pf, double *out)
{
    const Mesh *m = f->m;
    memset(out, 0, sizeof(double) * 3 * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        const double *S = m->face_area + 3 * i;
        double *fo = out + 3 * m->owner[i];
        for (int k = 0; k < 3; k++) fo[k] += pf[i] * S[k];
        if (i < f->ninternal) {
            double *fn = out + 3 * m->neighbour[i];
            for (int k = 0; k < 3; k++) fn[k] -= pf[i] * S[k];
        }
    }
}

/* fvc_courant with c_f = cf[f], or the larger of the cells' cc (the
   owner's at a boundary face) where cc is given, or c0. */
static double courant(const FvMesh *f, const double *phi, const double *cf, const double *cc, double c0, double dt,
                      double *co)
{
    const Mesh *m = f->m;
    double *sum = co ? co : mem_alloc(sizeof(double) * ((size_t)f->ncells + 1)), worst = 0;
    memset(sum, 0, sizeof(double) * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        double c = !cc                 ? (cf ? cf[i] : c0)
                   : i < f->ninternal ? fmax(cc[m->owner[i]], cc[m->neighbour[i]])
                                      : cc[m->owner[i]];
        double s = fabs(phi[i]) + c * f->mag_sf[i];
        sum[m->owner[i]] += s;
        if (i < f->ninternal) sum[m->neighbour[i]] += s;
    }
    for (int c = 0; c < f->nowned; c++) {
        sum[c] *= 0.5 * dt / m->cell_vol[c];
        worst = fmax(worst, sum[c]);
    }
    if (!co) free(sum);
    return worst;
}

double fvc_courant(const FvMesh *f, const double *phi, const double *cf, double dt, double *co)
{
    return courant(f, phi, cf, NULL, 0, dt, co);
}

double fvc_courant_cells(const FvMesh *f, const double *phi, const double *cc, double dt, double *co)
{
    return courant(f, phi, NULL, cc, 0, dt, co);
}

double fvc_courant_uniform(const FvMesh *f, const double *phi, double c, double dt, double *co)
{
    return courant(f, phi, NULL, NULL, c, dt, co);
}

double fvc_total(const FvMesh *f, const double *x)
{
    double s = 0;
    for (int c = 0; c < f->nowned; c++) s += x[c] * f->m->cell_vol[c];
    return s;
}
