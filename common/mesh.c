/*
** mesh.c: the polyMesh in memory: invariants, addressing, geometry.
** Reading and writing the files is in mesh_io.c.
**
** The invariants (mesh.h) are OpenFOAM's:
**   - faces 0..ninternal-1 are internal, owner[f] < neighbour[f], and they
**     are sorted by owner, then by neighbour (upper-triangular order; two
**     faces between the same pair of cells, as merged cut cells have, may
**     sit side by side);
**   - the right-hand-rule normal of a face points out of its owner, so
**     every cell has a positive volume and closed faces;
**   - boundary faces follow in patch order, each patch contiguous, the
**     patches together covering ninternal..nfaces-1;
**   - ncells = max(owner, neighbour) + 1.
** mesh_check tests all of them and names the first face or cell that
** breaks one; the orientation and closedness checks need the geometry
** (mesh_geometry) and are skipped without it.
**
** Everything here is linear in the mesh size and allocates whole arrays,
** never per item: the cell->face addressing is a counting sort of the
** owner/neighbour lists, so the faces of a cell come in increasing order.
*/
#include "mesh.h"
#include "cartcells.h"
#include "geom.h"
#include "mem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mesh_init(Mesh *m)
{
    memset(m, 0, sizeof *m);
}

static void free_geometry(Mesh *m)
{
    free(m->face_area);
    free(m->face_centre);
    free(m->cell_vol);
    free(m->cell_centre);
    m->face_area = m->face_centre = m->cell_vol = m->cell_centre = NULL;
}

void mesh_free(Mesh *m)
{
    free(m->points);
    free(m->face_off);
    free(m->face_idx);
    free(m->owner);
    free(m->neighbour);
    for (int p = 0; p < m->npatches; p++) {
        free(m->patches[p].name);
        free(m->patches[p].type);
        free(m->patches[p].neighbour);
        free(m->patches[p].groups);
    }
    free(m->patches);
    for (int k = 0; k < 3; k++) free(m->cart.x[k]);
    free(m->cell_parent);
    free(m->boundary_normal);
    free(m->merge_map);
    free(m->cell_seed);
    cartcells_free(&m->cartcells);
    free_geometry(m);
    free(m->cell_off);
    free(m->cell_faces);
    mesh_init(m);
}

/* ---- addressing ---- */

void mesh_cell_faces(Mesh *m)
{
    free(m->cell_off);
    free(m->cell_faces);
    mesh_cell_face_lists(m, &m->cell_off, &m->cell_faces);
}

void mesh_cell_face_lists(const Mesh *m, int **off_out, int **faces_out)
{
    int nc = m->ncells;
    int *off = MEM_NEW(int, (size_t)nc + 1);
    for (int f = 0; f < m->nfaces; f++) off[m->owner[f] + 1]++;
    for (int f = 0; f < m->ninternal; f++) off[m->neighbour[f] + 1]++;
    for (int c = 0; c < nc; c++) off[c + 1] += off[c];
    int *cf = MEM_NEW(int, (size_t)off[nc]);
    /* fill with a moving cursor per cell; faces arrive in increasing order */
    int *pos = MEM_NEW(int, (size_t)nc + 1);
    memcpy(pos, off, sizeof(int) * (size_t)nc);
    for (int f = 0; f < m->nfaces; f++) {
        cf[pos[m->owner[f]]++] = f;
        if (f < m->ninternal) cf[pos[m->neighbour[f]]++] = f;
    }
    free(pos);
    *off_out = off;
    *faces_out = cf;
}

/* ---- geometry ---- */

void mesh_geometry(Mesh *m)
{
    if (!m->cell_off) mesh_cell_faces(m);
    free_geometry(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    size_t nf3 = 3 * nf, nc3 = 3 * nc;
    m->face_area = MEM_NEW(double, nf3);
    m->face_centre = MEM_NEW(double, nf3);
    m->cell_vol = MEM_NEW(double, nc);
    m->cell_centre = MEM_NEW(double, nc3);
    for (size_t f = 0; f < nf; f++)
        geom_face(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f],
                  m->face_area + 3 * f, m->face_centre + 3 * f);
    int maxf = 0;
    for (size_t c = 0; c < nc; c++)
        if (m->cell_off[c + 1] - m->cell_off[c] > maxf) maxf = m->cell_off[c + 1] - m->cell_off[c];
    char *flip = MEM_NEW(char, (size_t)maxf);
    for (size_t c = 0; c < nc; c++) {
        const int *cf = m->cell_faces + m->cell_off[c];
        int n = m->cell_off[c + 1] - m->cell_off[c];
        for (int k = 0; k < n; k++) flip[k] = (char)(m->owner[cf[k]] != (int)c);
        geom_cell(m->points, m->face_off, m->face_idx, cf, flip, n, m->face_area, m->face_centre,
                  m->cell_vol + c, m->cell_centre + 3 * c);
    }
    free(flip);
}

void mesh_bounds(const Mesh *m, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = m->npoints ? m->points[k] : 0;
    for (size_t i = 0; i < (size_t)m->npoints; i++)
        for (int k = 0; k < 3; k++) {
            double x = m->points[3 * i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
}

/* ---- patches ---- */

int mesh_patch(const Mesh *m, const char *name)
{
    for (int p = 0; p < m->npatches; p++)
        if (strcmp(m->patches[p].name, name) == 0) return p;
    return -1;
}

void mesh_patch_copy(const Patch *p, Patch *q)
{
    q->name = mem_strdup(p->name);
    q->type = mem_strdup(p->type);
    q->neighbour = p->neighbour ? mem_strdup(p->neighbour) : NULL;
    q->groups = p->groups ? mem_strdup(p->groups) : NULL;
    q->start = p->start;
    q->size = p->size;
}

int mesh_type_is_empty(const char *type)
{
    return type && strcmp(type, "empty") == 0;
}

int mesh_patch_is_empty(const Patch *p)
{
    return mesh_type_is_empty(p->type);
}

int mesh_face_patch(const Mesh *m, int f)
{
    if (f < m->ninternal || f >= m->nfaces) return -1;
    /* patches are sorted by start: the last patch starting at or before f
       holds it (empty patches sharing its start come before it) */
    int lo = 0, hi = m->npatches - 1, best = -1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (m->patches[mid].start <= f) {
            best = mid;
            lo = mid + 1;
        } else {
            hi = mid - 1;
        }
    }
    if (best >= 0 && f < m->patches[best].start + m->patches[best].size) return best;
    /* not sorted (a mesh that fails mesh_check): plain search */
    for (int p = 0; p < m->npatches; p++)
        if (f >= m->patches[p].start && f < m->patches[p].start + m->patches[p].size) return p;
    return -1;
}

/* ---- Cartesian parents ---- */

int mesh_cell_spacing(const Mesh *m, int c, double h[3])
{
    const CartGrid *g = &m->cart;
    if (!m->cell_parent || g->n[0] <= 0 || c < 0 || c >= m->ncells) return -1;
    long p = m->cell_parent[c];
    long nxy = (long)g->n[0] * g->n[1];
    if (p < 0 || p >= nxy * g->n[2]) return -1;
    long ijk[3] = {p % g->n[0], (p / g->n[0]) % g->n[1], p / nxy};
    for (int k = 0; k < 3; k++) h[k] = g->x[k][ijk[k] + 1] - g->x[k][ijk[k]];
    return 0;
}

const double *mesh_cell_node(const Mesh *m, int c)
{
    if (c < 0 || c >= m->ncells) return NULL;
    if (m->cell_seed) return m->cell_seed + 3 * (size_t)c;
    return m->cell_centre ? m->cell_centre + 3 * (size_t)c : NULL;
}

/* ---- 2-D detection ---- */

/* Axis of a face normal when the other two components vanish to within
   1e-9 of its length; -1 otherwise. */
static int normal_axis(const double S[3])
{
    double n = geom_norm(S);
    if (!(n > 0)) return -1;
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        if (fabs(S[b]) <= 1e-9 * n && fabs(S[c]) <= 1e-9 * n) return a;
    }
    return -1;
}

/* Twice the area vector of polygon idx[0..n), about its first point: only
   its direction matters here, so no centroid (geom_face) is needed. */
static void newell_normal(const double *pts, const int *idx, int n, double S[3])
{
    const double *p0 = pts + 3 * (size_t)idx[0];
    S[0] = S[1] = S[2] = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *a = pts + 3 * (size_t)idx[k], *b = pts + 3 * (size_t)idx[k + 1];
        double u[3] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2]};
        double v[3] = {b[0] - p0[0], b[1] - p0[1], b[2] - p0[2]};
        S[0] += u[1] * v[2] - u[2] * v[1];
        S[1] += u[2] * v[0] - u[0] * v[2];
        S[2] += u[0] * v[1] - u[1] * v[0];
    }
}

int mesh_empty_axis(const Mesh *m)
{
    int axis = -1, nempty = 0;
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        if (!mesh_patch_is_empty(pa)) continue;
        for (int f = pa->start; f < pa->start + pa->size; f++) {
            if (f < 0 || f >= m->nfaces) return -1;
            double S[3];
            const double *Sp = S;
            if (m->face_area)
                Sp = m->face_area + 3 * (size_t)f;
            else
                newell_normal(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], S);
            int a = normal_axis(Sp);
            if (a < 0 || (axis >= 0 && a != axis)) return -1;
            axis = a;
            nempty++;
        }
    }
    if (axis < 0 || m->ncells == 0 || nempty != 2 * m->ncells) return -1;
    /* exactly two empty faces per cell (counted, since a total of
       2*ncells could still leave one cell with three) */
    unsigned char *cnt = MEM_NEW(unsigned char, (size_t)m->ncells);
    int ok = 1;
    for (int p = 0; p < m->npatches && ok; p++) {
        const Patch *pa = &m->patches[p];
        if (!mesh_patch_is_empty(pa)) continue;
        for (int f = pa->start; f < pa->start + pa->size && ok; f++) {
            int c = m->owner[f];
            if (c < 0 || c >= m->ncells || ++cnt[c] > 2) ok = 0;
        }
    }
    free(cnt);
    return ok ? axis : -1;
}

/* ---- checking ---- */

static int check_faces(const Mesh *m, Err *e)
{
    if (m->nfaces < 0 || m->npoints < 0 || m->ninternal < 0 || m->ninternal > m->nfaces)
        return err_set(e, NULL, 0, "mesh: bad sizes (%d points, %d faces, %d internal)", m->npoints,
                       m->nfaces, m->ninternal);
    if (!m->face_off) return m->nfaces ? err_set(e, NULL, 0, "mesh: no face point lists") : 0;
    if (m->face_off[0] != 0) return err_set(e, NULL, 0, "mesh: face 0: point list does not start at 0");
    for (int f = 0; f < m->nfaces; f++) {
        int n = m->face_off[f + 1] - m->face_off[f];
        if (n < 3) return err_set(e, NULL, 0, "mesh: face %d has %d points (at least 3 needed)", f, n);
        for (int k = m->face_off[f]; k < m->face_off[f + 1]; k++)
            if (m->face_idx[k] < 0 || m->face_idx[k] >= m->npoints)
                return err_set(e, NULL, 0, "mesh: face %d: point %d out of range 0..%d", f, m->face_idx[k],
                               m->npoints - 1);
    }
    return 0;
}

static int check_cells(const Mesh *m, Err *e)
{
    int maxc = -1;
    for (int f = 0; f < m->nfaces; f++) {
        if (m->owner[f] < 0)
            return err_set(e, NULL, 0, "mesh: face %d: owner %d is negative", f, m->owner[f]);
        if (m->owner[f] > maxc) maxc = m->owner[f];
    }
    for (int f = 0; f < m->ninternal; f++) {
        int o = m->owner[f], n = m->neighbour[f];
        if (n > maxc) maxc = n;
        if (n <= o)
            return err_set(e, NULL, 0, "mesh: face %d: owner %d is not less than neighbour %d", f, o, n);
        if (f > 0) {
            int po = m->owner[f - 1], pn = m->neighbour[f - 1];
            if (o < po || (o == po && n < pn))
                return err_set(e, NULL, 0,
                               "mesh: face %d (owner %d, neighbour %d) is out of upper-triangular order "
                               "after face %d (owner %d, neighbour %d)",
                               f, o, n, f - 1, po, pn);
        }
    }
    if (maxc + 1 != m->ncells)
        return err_set(e, NULL, 0, "mesh: %d cells recorded, but the largest cell label is %d", m->ncells, maxc);
    return 0;
}

static int check_patches(const Mesh *m, Err *e)
{
    int next = m->ninternal;
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        if (pa->size < 0) return err_set(e, NULL, 0, "mesh: patch '%s' has %d faces", pa->name, pa->size);
        if (pa->start != next)
            return err_set(e, NULL, 0,
                           "mesh: patch '%s' starts at face %d, but face %d follows the previous %s",
                           pa->name, pa->start, next, p ? "patch" : "internal faces");
        next += pa->size;
    }
    if (next != m->nfaces)
        return err_set(e, NULL, 0, "mesh: faces %d..%d belong to no patch", next, m->nfaces - 1);
    return 0;
}

/* Every cell needs at least 4 faces; with geometry, a positive volume
   (normals out of the owner) and closed faces (sum of outward Sf small
   against sum |Sf|, checkMesh's threshold 1e-6). */
static int check_closed(const Mesh *m, Err *e)
{
    if (!m->cell_off) return 0;
    for (int c = 0; c < m->ncells; c++) {
        int n = m->cell_off[c + 1] - m->cell_off[c];
        if (n < 4) return err_set(e, NULL, 0, "mesh: cell %d has %d faces (at least 4 needed)", c, n);
    }
    if (!m->face_area || !m->cell_vol) return 0;
    for (int c = 0; c < m->ncells; c++) {
        double s[3] = {0, 0, 0}, mag = 0;
        for (int k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
            int f = m->cell_faces[k];
            const double *S = m->face_area + 3 * (size_t)f;
            double sg = m->owner[f] == c ? 1 : -1;
            s[0] += sg * S[0];
            s[1] += sg * S[1];
            s[2] += sg * S[2];
            mag += geom_norm(S);
        }
        if (!(geom_norm(s) <= 1e-6 * mag))
            return err_set(e, NULL, 0, "mesh: cell %d is not closed (|sum Sf| / sum |Sf| = %.3g)", c,
                           geom_norm(s) / mag);
        if (!(m->cell_vol[c] > 0))
            return err_set(e, NULL, 0,
                           "mesh: cell %d has volume %g (its face normals do not point out of it)", c,
                           m->cell_vol[c]);
    }
    return 0;
}

int mesh_check(const Mesh *m, Err *e)
{
    if (check_faces(m, e) || check_cells(m, e) || check_patches(m, e) || check_closed(m, e)) return -1;
    return 0;
}

void mesh_copy_cart(const CartGrid *a, CartGrid *b)
{
    for (int k = 0; k < 3; k++) {
        b->n[k] = a->n[k];
        b->x[k] = NULL;
        if (a->x[k]) {
            b->x[k] = MEM_NEW(double, (size_t)a->n[k] + 1);
            memcpy(b->x[k], a->x[k], sizeof(double) * ((size_t)a->n[k] + 1));
        }
    }
}
