/*
** hydro.c: the well-balanced face weights and gravity vectors (hydro.h).
**
** A source's position is taken at its periodic image nearest the face
** centre: the translations of the cyclic patches (each patch's own, so
** both directions) are applied one at a time while one brings the point
** closer, which also finds an image two translations away (a corner of a
** box periodic in two directions).  Sources lie within a stencil's reach
** of their face, far less than half a period, so the nearest image is the
** one the interpolation used.
**
** The boundary rows solve their least-squares problem in closed form (two
** constraints, sum and potential, over the owner and its face
** neighbours); a row is kept only while sum |c_j| <= 3, the bound
** interp_lin.c puts on its corrected rows, so that a nearly flat
** neighbourhood does not turn a wall pressure into a difference of large
** numbers.
*/
#include "hydro.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

enum { HYDRO_MAXTRANS = 6, HYDRO_MAXNB = 64 };
#define HYDRO_MAXL1 3.0   /* largest sum |c_j| of a boundary row */

typedef struct Images {
    int n;
    double T[HYDRO_MAXTRANS][3];
} Images;

static void images_init(Images *im, const FvMesh *f)
{
    const Mesh *m = f->m;
    im->n = 0;
    for (int p = 0; p < m->npatches && im->n < HYDRO_MAXTRANS; p++) {
        const Patch *pa = &m->patches[p];
        if (pa->size == 0 || pa->start < f->ninternal || f->cyc_face[pa->start - f->ninternal] < 0) continue;
        fvmesh_cyclic_shift(f, pa->start, im->T[im->n++]);
    }
}

static double dist2(const double p[3], const double x[3])
{
    return (p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) + (p[2] - x[2]) * (p[2] - x[2]);
}

/* Position of stencil source s (a cell's node, or a boundary face's
   centre) at its periodic image nearest x. */
static void source_at(const Images *im, const FvMesh *f, int s, const double x[3], double p[3])
{
    const double *p0 = s < f->ncells ? f->node + 3 * s : f->m->face_centre + 3 * (f->ninternal + s - f->ncells);
    memcpy(p, p0, 3 * sizeof *p);
    double best = dist2(p, x);
    for (int moved = 1; moved;) {
        moved = 0;
        for (int t = 0; t < im->n; t++) {
            double q[3] = {p[0] - im->T[t][0], p[1] - im->T[t][1], p[2] - im->T[t][2]}, d = dist2(q, x);
            if (d < best) {
                best = d;
                memcpy(p, q, sizeof q);
                moved = 1;
            }
        }
    }
}

/* a.(x - y): the potential difference (over RsT) from y to x. */
static double potential(const double a[3], const double x[3], const double y[3])
{
    return a[0] * (x[0] - y[0]) + a[1] * (x[1] - y[1]) + a[2] * (x[2] - y[2]);
}

/* exp(a.(x - y)): the hydrostatic profile from y to x. */
static double profile(const double a[3], const double x[3], const double y[3]) { return exp(potential(a, x, y)); }

/* The weights of every face's CENTRE row; a cyclic face's partner built
   first lends its weights, as the stencil's rows are copies too. */
static void face_weights(Hydro *h, const Images *im)
{
    const FvMesh *f = h->f;
    const Stencil *s = &h->ip->face;
    h->off = mem_alloc(sizeof(int) * ((size_t)f->nfaces + 1));
    h->off[0] = 0;
    for (int i = 0; i < f->nfaces; i++) h->off[i + 1] = h->off[i] + stencil_row_len(s, interp_row(i, INTERP_CENTRE));
    h->w = mem_alloc(sizeof(double) * ((size_t)h->off[f->nfaces] + 1));
    if (h->barotropic) h->phi = mem_alloc(sizeof(double) * ((size_t)h->off[f->nfaces] + 1));
    for (int i = 0; i < f->nfaces; i++) {
        int r = interp_row(i, INTERP_CENTRE), g = i >= f->ninternal ? f->cyc_face[i - f->ninternal] : -1;
        double *w = h->w + h->off[i];
        if (g >= 0 && g < i) {
            memcpy(w, h->w + h->off[g], sizeof(double) * (size_t)(h->off[i + 1] - h->off[i]));
            if (h->phi) memcpy(h->phi + h->off[i], h->phi + h->off[g], sizeof(double) * (size_t)(h->off[i + 1] - h->off[i]));
            continue;
        }
        const double *xf = f->m->face_centre + 3 * i;
        StencilRow sr;
        stencil_row(s, r, &sr);
        for (int k = 0; k < sr.n; k++) {
            double p[3];
            source_at(im, f, sr.src[k], xf, p);
            if (h->phi) {
                w[k] = sr.w[k];
                h->phi[h->off[i] + k] = potential(h->a, xf, p);
            } else {
                w[k] = sr.w[k] * profile(h->a, xf, p);
            }
        }
    }
}

/* Each cell's profile integrated over its faces. */
static void gravity_vectors(Hydro *h)
{
    const FvMesh *f = h->f;
    const Mesh *m = f->m;
    h->grav = mem_calloc(3 * ((size_t)f->ncells + 1), sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        const double *xf = m->face_centre + 3 * i, *S = m->face_area + 3 * i, *xo = f->node + 3 * m->owner[i];
        double eo = expm1(potential(h->a, xf, xo));
        for (int k = 0; k < 3; k++) h->grav[3 * m->owner[i] + k] += eo * S[k];
        if (i >= f->ninternal) continue;
        const double *xn = f->node + 3 * m->neighbour[i];
        double en = expm1(potential(h->a, xf, xn));
        for (int k = 0; k < 3; k++) h->grav[3 * m->neighbour[i] + k] -= en * S[k];
    }
}

/* The potentials of every face seen from its two cells, and each cell's
   largest (barotropic profiles). */
static void face_potentials(Hydro *h)
{
    const FvMesh *f = h->f;
    const Mesh *m = f->m;
    h->gphi = mem_calloc(2 * ((size_t)f->nfaces + 1), sizeof(double));
    h->reach = mem_calloc((size_t)f->ncells + 1, sizeof(double));
    for (int i = 0; i < f->nfaces; i++) {
        const double *xf = m->face_centre + 3 * i;
        int o = m->owner[i], n = i < f->ninternal ? m->neighbour[i] : -1;
        h->gphi[2 * i] = potential(h->a, xf, f->node + 3 * o);
        if (n >= 0) h->gphi[2 * i + 1] = potential(h->a, xf, f->node + 3 * n);
        if (f->empty_face[i]) continue;
        h->reach[o] = fmax(h->reach[o], fabs(h->gphi[2 * i]));
        if (n >= 0) h->reach[n] = fmax(h->reach[n], fabs(h->gphi[2 * i + 1]));
    }
}

/* Cell c and its face neighbours (across internal and cyclic faces), each
   once, with their nodes seen from c (a cyclic neighbour moved by the
   translation); returns how many, at most HYDRO_MAXNB. */
static int neighbourhood(const FvMesh *f, int c, int *cell, double (*x)[3])
{
    const Mesh *m = f->m;
    int n = 1;
    cell[0] = c;
    memcpy(x[0], f->node + 3 * c, sizeof x[0]);
    for (int j = m->cell_off[c]; j < m->cell_off[c + 1] && n < HYDRO_MAXNB; j++) {
        int i = m->cell_faces[j], nb;
        double y[3];
        if (f->empty_face[i]) continue;
        if (i < f->ninternal) {
            nb = m->owner[i] == c ? m->neighbour[i] : m->owner[i];
            memcpy(y, f->node + 3 * nb, sizeof y);
        } else if ((nb = fvmesh_across(f, i, y)) < 0) {
            continue;
        }
        int dup = 0;
        for (int q = 0; q < n; q++) dup |= cell[q] == nb;
        if (dup) continue;
        cell[n] = nb;
        memcpy(x[n++], y, sizeof y);
    }
    return n;
}

/* The weights c_j (summing to 1) of the owner P's neighbourhood whose
   nodes' mean potential is the face's, sum_j c_j a.x_j = a.x_b: the
   smallest change (sum of squares) of c = (1 at P, 0 elsewhere), i.e.
   c_j = [j = P] + lambda + mu psi_j, psi_j = a.(x_j - x_P).  0 when the
   neighbourhood does not spread in potential or the weights grow large
   (sum |c_j| > HYDRO_MAXL1): the caller keeps the owner alone. */
static int equipotential(int n, const double *psi, double phi, double *c)
{
    double s1 = 0, s2 = 0, l1 = 0;
    for (int j = 0; j < n; j++) {
        s1 += psi[j];
        s2 += psi[j] * psi[j];
    }
    double D = s2 - s1 * s1 / n;
    if (n < 2 || !(D > 1e-10 * (s2 + phi * phi))) return 0;
    double mu = phi / D, lambda = -mu * s1 / n;
    for (int j = 0; j < n; j++) {
        c[j] = (j == 0) + lambda + mu * psi[j];
        l1 += fabs(c[j]);
    }
    return l1 <= HYDRO_MAXL1;
}

/* The row of boundary face b: its owner's neighbourhood at the face's
   potential, each node carried to the face along its profile. */
static void wall_row(Hydro *h, int b, size_t *wcap)
{
    const FvMesh *f = h->f;
    int i = f->ninternal + b, P = f->m->owner[i], cell[HYDRO_MAXNB], n = 1;
    const double *xb = f->m->face_centre + 3 * i, *xp = f->node + 3 * P, *a = h->a;
    double x[HYDRO_MAXNB][3], psi[HYDRO_MAXNB], c[HYDRO_MAXNB] = {1};
    double phi = potential(a, xb, xp);
    cell[0] = P;
    memcpy(x[0], xp, sizeof x[0]);
    if (phi != 0 && !f->empty_face[i] && f->cyc_face[b] < 0) {
        int m = neighbourhood(f, P, cell, x);
        for (int j = 0; j < m; j++) psi[j] = potential(a, x[j], xp);
        if (equipotential(m, psi, phi, c)) n = m;
        else c[0] = 1;
    }
    for (int j = 0; j < n; j++) {
        if (!h->barotropic) {
            stencil_add(&h->wall, cell[j], c[j] * profile(a, xb, x[j]));
            continue;
        }
        int at = h->wall.off[h->wall.nrows + 1]; /* the cells are distinct: each adds an entry */
        stencil_add(&h->wall, cell[j], c[j]);
        mem_grow((void **)&h->wphi, wcap, (size_t)at + 1, sizeof *h->wphi);
        h->wphi[at] = potential(a, xb, x[j]);
    }
    stencil_end_row(&h->wall);
}

static void init(Hydro *h, const FvMesh *f, const Interp *ip, const double a[3], int barotropic)
{
    memset(h, 0, sizeof *h);
    h->f = f;
    h->ip = ip;
    memcpy(h->a, a, sizeof h->a);
    if (h->a[0] == 0 && h->a[1] == 0 && h->a[2] == 0) return; /* the plain rows; nothing to store */
    h->barotropic = barotropic;
    Images im;
    images_init(&im, f);
    face_weights(h, &im);
    if (barotropic)
        face_potentials(h);
    else
        gravity_vectors(h);
    stencil_init(&h->wall);
    size_t wcap = 0;
    for (int b = 0; b < f->nboundary; b++) wall_row(h, b, &wcap);
    stencil_trim(&h->wall);
}

void hydro_init(Hydro *h, const FvMesh *f, const Interp *ip, const double g[3], double RsT)
{
    double a[3] = {g[0] / RsT, g[1] / RsT, g[2] / RsT};
    init(h, f, ip, a, 0);
}

void hydro_init_profile(Hydro *h, const FvMesh *f, const Interp *ip, const double g[3]) { init(h, f, ip, g, 1); }

void hydro_free(Hydro *h)
{
    free(h->off);
    free(h->w);
    stencil_free(&h->wall);
    free(h->grav);
    free(h->phi);
    free(h->wphi);
    free(h->gphi);
    free(h->reach);
    memset(h, 0, sizeof *h);
}

double hydro_face(const Hydro *h, int i, const double *pc, const double *pb)
{
    int r = interp_row(i, INTERP_CENTRE), nc = h->f->ncells;
    if (!h->w) return stencil_apply(&h->ip->face, r, nc, pc, pb);
    StencilRow sr;
    stencil_row(&h->ip->face, r, &sr);
    const double *w = h->w + h->off[i];
    double v = 0;
    for (int k = 0; k < sr.n; k++) {
        int q = sr.src[k];
        v += w[k] * (q < nc ? pc[q] : pb[q - nc]);
    }
    return v;
}

/* p S_f of face i onto its owner, minus onto its neighbour (outward). */
static void add_face_force(const FvMesh *f, int i, double p, double *out)
{
    const double *S = f->m->face_area + 3 * i;
    double *fo = out + 3 * f->m->owner[i];
    for (int k = 0; k < 3; k++) fo[k] += p * S[k];
    if (i >= f->ninternal) return;
    double *fn = out + 3 * f->m->neighbour[i];
    for (int k = 0; k < 3; k++) fn[k] -= p * S[k];
}

void hydro_force(const Hydro *h, const double *pc, const double *pb, double *out)
{
    const FvMesh *f = h->f;
    memset(out, 0, sizeof(double) * 3 * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        add_face_force(f, i, hydro_face(h, i, pc, pb), out);
    }
}

double hydro_boundary(const Hydro *h, int b, const double *pc)
{
    if (!h->wall.off) return 0.0 + pc[h->f->m->owner[h->f->ninternal + b]]; /* the row's sum, 0 + 1 p_P */
    return stencil_apply(&h->wall, b, h->f->ncells, pc, NULL);
}

double hydro_face_profile(const Hydro *h, int i, const HydroProfile *q)
{
    StencilRow sr;
    stencil_row(&h->ip->face, interp_row(i, INTERP_CENTRE), &sr);
    double v = 0;
    if (!h->w) { /* g = 0: the row's own weights on the sources' pressures */
        for (int k = 0; k < sr.n; k++) v += sr.w[k] * q->at(q->ctx, sr.src[k], 0);
        return v;
    }
    const double *w = h->w + h->off[i], *phi = h->phi + h->off[i];
    for (int k = 0; k < sr.n; k++) v += w[k] * q->at(q->ctx, sr.src[k], phi[k]);
    return fmax(v, 0);
}

void hydro_force_profile(const Hydro *h, const HydroProfile *q, double *out)
{
    const FvMesh *f = h->f;
    memset(out, 0, sizeof(double) * 3 * (size_t)f->ncells);
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) continue;
        add_face_force(f, i, hydro_face_profile(h, i, q), out);
    }
}

double hydro_boundary_profile(const Hydro *h, int b, const HydroProfile *q)
{
    int P = h->f->m->owner[h->f->ninternal + b];
    if (!h->wall.off) return q->at(q->ctx, P, 0);
    double v = 0;
    for (int k = h->wall.off[b]; k < h->wall.off[b + 1]; k++) v += h->wall.w[k] * q->at(q->ctx, h->wall.src[k], h->wphi[k]);
    return v;
}

/* Each cell's own profile over its closed surface, empty faces too, less
   its own pressure (sum_f S_f = 0: the differences keep the sum small
   where the profile is nearly flat). */
void hydro_gravity_profile(const Hydro *h, const HydroProfile *q, double *grav)
{
    const FvMesh *f = h->f;
    const Mesh *m = f->m;
    memset(grav, 0, sizeof(double) * 3 * (size_t)f->ncells);
    if (!h->gphi) return;
    for (int i = 0; i < f->nfaces; i++) {
        const double *S = m->face_area + 3 * i;
        int o = m->owner[i];
        double d = q->at(q->ctx, o, h->gphi[2 * i]) - q->at(q->ctx, o, 0);
        for (int k = 0; k < 3; k++) grav[3 * o + k] += d * S[k];
        if (i >= f->ninternal) continue;
        int n = m->neighbour[i];
        d = q->at(q->ctx, n, h->gphi[2 * i + 1]) - q->at(q->ctx, n, 0);
        for (int k = 0; k < 3; k++) grav[3 * n + k] -= d * S[k];
    }
}
