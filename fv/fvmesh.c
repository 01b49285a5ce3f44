/*
** fvmesh.c: the finite-volume view of a grid (fvmesh.h).
**
** Everything here is computed once per grid, so the time loop only reads
** arrays.  The checks refuse grids on which the scheme would divide by
** zero (a face of zero area, a cell of zero volume, a node on the plane
** of one of its faces) with the face or cell named, before a time step.
*/
#include "fvmesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "mem.h"

/* Is cell c a whole Cartesian cell (the box of one Cartesian cell)?  With
   the data contract: one parent, whole.  Without it, a block grid (one
   cell per Cartesian cell, numbered as they are) is whole everywhere; any
   other grid nowhere. */
static int whole_cell(const Mesh *m, int c)
{
    const CartCells *cc = &m->cartcells;
    if (cc->n > 0) {
        int a = cc->parent_off[c], b = cc->parent_off[c + 1];
        return b - a == 1 && cc->role[cc->parent[a]] == CART_WHOLE;
    }
    long ncart = (long)m->cart.n[0] * m->cart.n[1] * m->cart.n[2];
    return ncart > 0 && ncart == m->ncells && !m->cell_seed && (!m->cell_parent || m->cell_parent[c] == c);
}

static int face_vectors(FvMesh *f, Err *e)
{
    const Mesh *m = f->m;
    for (int i = 0; i < f->nfaces; i++) {
        const double *S = m->face_area + 3 * i;
        double a = geom_norm(S);
        if (!(a > 0)) return err_set(e, NULL, 0, "face %d has no area: the grid cannot carry fluxes", i);
        f->mag_sf[i] = a;
        for (int k = 0; k < 3; k++) f->nf[3 * i + k] = S[k] / a;
    }
    for (int c = 0; c < f->ncells; c++)
        if (!(m->cell_vol[c] > 0)) return err_set(e, NULL, 0, "cell %d has volume %g", c, m->cell_vol[c]);
    return 0;
}

/* Normal distance of node x from the plane of face i. */
static double plane_distance(const FvMesh *f, int i, const double *x)
{
    const double *C = f->m->face_centre + 3 * i, *n = f->nf + 3 * i;
    return fabs((x[0] - C[0]) * n[0] + (x[1] - C[1]) * n[1] + (x[2] - C[2]) * n[2]);
}

void fvmesh_cyclic_shift(const FvMesh *f, int i, double T[3])
{
    int p = f->face_patch[i - f->ninternal];
    memcpy(T, f->cyc_shift + 3 * ((size_t)f->cyc_base[p] + (size_t)(i - f->m->patches[p].start)), 3 * sizeof *T);
}

int fvmesh_across(const FvMesh *f, int i, double x[3])
{
    const Mesh *m = f->m;
    if (i < f->ninternal) {
        memcpy(x, f->node + 3 * m->neighbour[i], 3 * sizeof *x);
        return m->neighbour[i];
    }
    int g = f->cyc_face[i - f->ninternal];
    if (g < 0) return -1;
    double T[3];
    fvmesh_cyclic_shift(f, i, T);
    const double *xn = f->node + 3 * m->owner[g];
    for (int k = 0; k < 3; k++) x[k] = xn[k] - T[k];
    return m->owner[g];
}

/* Faces of a cyclic patch pair in order with its neighbourPatch's (the
   geometry is bc.c's to check); unpaired patches stay boundaries.  Each
   face's translation, partner centre - own centre, is kept: the face
   centres go at the end of the set-up. */
static void cyclic_pairs(FvMesh *f)
{
    const Mesh *m = f->m;
    int n = 0;
    f->cyc_base = mem_alloc(((size_t)m->npatches + 1) * sizeof(int));
    for (int b = 0; b < f->nboundary; b++) f->cyc_face[b] = -1;
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        f->cyc_base[p] = -1;
        if (!pa->type || strcmp(pa->type, "cyclic") || !pa->neighbour) continue;
        int q = mesh_patch(m, pa->neighbour);
        if (q < 0 || q == p || m->patches[q].size != pa->size) continue;
        for (int i = 0; i < pa->size; i++) f->cyc_face[pa->start + i - f->ninternal] = m->patches[q].start + i;
        f->cyc_base[p] = n;
        n += pa->size;
    }
    f->cyc_shift = mem_alloc(3 * ((size_t)n + 1) * sizeof(double));
    for (int p = 0; p < m->npatches; p++)
        for (int i = 0; i < m->patches[p].size && f->cyc_base[p] >= 0; i++) {
            int a = m->patches[p].start + i, b = f->cyc_face[a - f->ninternal];
            for (int k = 0; k < 3; k++)
                f->cyc_shift[3 * ((size_t)f->cyc_base[p] + (size_t)i) + (size_t)k] =
                    m->face_centre[3 * b + k] - m->face_centre[3 * a + k];
        }
}

/* eq. 4.62-4.63 */
static int distances(FvMesh *f, Err *e)
{
    const Mesh *m = f->m;
    for (int i = 0; i < f->nfaces; i++) {
        double dc = plane_distance(f, i, f->node + 3 * m->owner[i]), xn[3];
        if (fvmesh_across(f, i, xn) >= 0) {
            double dn = plane_distance(f, i, xn);
            f->h[i] = f->ht[i] = fmin(dc, dn);
        } else {
            f->h[i] = dc;
            f->ht[i] = 0;
        }
        if (!(f->h[i] > 0) && !f->empty_face[i])
            return err_set(e, NULL, 0, "face %d: the node of cell %d lies on its plane (h_f = 0, eq. 4.62)", i,
                           f->h[i] == dc ? m->owner[i] : fvmesh_across(f, i, xn));
    }
    return 0;
}

static void boundary_info(FvMesh *f)
{
    const Mesh *m = f->m;
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        for (int i = pa->start; i < pa->start + pa->size; i++) {
            f->face_patch[i - f->ninternal] = p;
            f->empty_face[i] = (char)mesh_patch_is_empty(pa);
        }
    }
    f->nslots = 0;
    for (int b = 0; b < f->nboundary; b++) f->bslot[b] = f->empty_face[f->ninternal + b] ? -1 : f->nslots++;
}

static void cartesian_info(FvMesh *f)
{
    const Mesh *m = f->m;
    char *whole = mem_alloc((size_t)f->ncells + 1);
    for (int c = 0; c < f->ncells; c++) whole[c] = (char)whole_cell(m, c);
    double x[3];
    for (int i = 0; i < f->nfaces; i++) {
        int n = fvmesh_across(f, i, x);
        f->cartesian_face[i] = (char)(n >= 0 && whole[m->owner[i]] && whole[n]);
    }
    free(whole);
    for (int k = 0; k < 3; k++) {
        f->hcart[k] = 0;
        for (int j = 0; j < m->cart.n[k]; j++) {
            double w = m->cart.x[k][j + 1] - m->cart.x[k][j];
            if (j == 0 || w < f->hcart[k]) f->hcart[k] = w;
        }
    }
}

int fvmesh_init(FvMesh *f, Mesh *m, Err *e)
{
    memset(f, 0, sizeof *f);
    if (!m->cell_off) mesh_cell_faces(m);
    if (!m->cell_vol) mesh_geometry(m);
    f->m = m;
    f->ncells = f->nowned = m->ncells;
    f->nfaces = m->nfaces;
    f->ninternal = m->ninternal;
    f->nboundary = m->nfaces - m->ninternal;
    f->empty_axis = mesh_empty_axis(m);
    size_t nf = (size_t)f->nfaces + 1;
    f->mag_sf = mem_alloc(nf * sizeof(double));
    f->nf = mem_alloc(3 * nf * sizeof(double));
    f->node = m->cell_seed ? m->cell_seed : m->cell_centre; /* mesh_cell_node's, not a copy */
    f->h = mem_alloc(nf * sizeof(double));
    f->ht = mem_alloc(nf * sizeof(double));
    f->face_patch = mem_alloc(((size_t)f->nboundary + 1) * sizeof(int));
    f->bslot = mem_alloc(((size_t)f->nboundary + 1) * sizeof(int));
    f->empty_face = mem_calloc(nf, 1);
    f->cartesian_face = mem_calloc(nf, 1);
    f->cyc_face = mem_alloc(((size_t)f->nboundary + 1) * sizeof(int));
    boundary_info(f);
    cyclic_pairs(f);
    cartesian_info(f);
    if (face_vectors(f, e) || distances(f, e)) {
        fvmesh_free(f);
        return -1;
    }
    return 0;
}

void fvmesh_free(FvMesh *f)
{
    free(f->mag_sf);
    free(f->nf);
    free(f->h);
    free(f->ht);
    free(f->face_patch);
    free(f->bslot);
    free(f->empty_face);
    free(f->cartesian_face);
    free(f->cyc_face);
    free(f->cyc_base);
    free(f->cyc_shift);
    memset(f, 0, sizeof *f);
}

void fvmesh_end_setup(FvMesh *f)
{
    Mesh *m = f->m;
    void *arr[] = {f->nf, f->h, f->ht, f->cartesian_face, m->face_centre, m->boundary_normal, m->cell_off, m->cell_faces};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) free(arr[i]);
    f->nf = f->h = f->ht = NULL;
    f->cartesian_face = NULL;
    m->face_centre = m->boundary_normal = NULL;
    m->cell_off = m->cell_faces = NULL;
}

int fvmesh_has_cartesian(const FvMesh *f) { return f->m->cart.n[0] > 0 && f->m->cartcells.n > 0; }

double fvmesh_volume(const FvMesh *f)
{
    double v = 0;
    for (int c = 0; c < f->nowned; c++) v += f->m->cell_vol[c];
    return v;
}
