/*
** voronoi_write.c: the Mesh from the closed cells, in OpenFOAM's order.
**
** Each cell's own faces (those it does not take reversed from a lower
** cell) come sorted by label, and cells are numbered in seed order, so
** when every own internal face goes to a higher cell the internal faces
** arrive sorted by (owner, neighbour): the mesh is then written in place
** (voronoi_write_direct), each boundary face into its patch's range, which
** skips meshbuild's copies of every face and point.  Otherwise (an own
** face towards a lower cell that has no face back) meshbuild sorts
** (voronoi_write_meshbuild); the mesh is the same.  voronoi_plan_faces
** counts what goes where; voronoi_ortho_max measures the result.
*/
#include "voronoi_impl.h"
#include "meshbuild.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Counts the faces each cell hands on (dropping those of fewer than 3
   points) and whether they arrive in order. */
void voronoi_plan_faces(Assembly *A, Plan *pl)
{
    const Store *s = A->st;
    int np = A->in->npatches;
    memset(pl, 0, sizeof *pl);
    pl->direct = 1;
    pl->empty = -1;
    pl->pface = mem_calloc((size_t)np, sizeof(int));
    pl->pidx = mem_calloc((size_t)np, sizeof(size_t));
    for (int c = 0; c < s->ncells; c++) {
        int seen = 0;
        for (int f = s->cell_off[c]; f < s->cell_off[c + 1]; f++) {
            int g;
            if (voronoi_face_superseded(A, f, A->seed_of[c], &g)) {
                seen |= A->len[g] >= 3;
                continue;
            }
            if (A->len[f] < 3) {
                A->ndropped++;
                continue;
            }
            seen = 1;
            int o = voronoi_face_other(A, f);
            pl->nface++;
            pl->nidx += (size_t)A->len[f];
            if (o >= 0) {
                pl->nint++;
                pl->iint += (size_t)A->len[f];
                pl->direct &= o > c;
            } else {
                pl->pface[-1 - o]++;
                pl->pidx[-1 - o] += (size_t)A->len[f];
            }
        }
        if (!seen && pl->empty < 0) pl->empty = c;
    }
}

void voronoi_plan_free(Plan *pl)
{
    free(pl->pface);
    free(pl->pidx);
}

/* Allocates out's faces and patches from the plan. */
void voronoi_mesh_alloc(const VoronoiInput *in, const Plan *pl, int ncells, Mesh *out, Cursor *cur)
{
    out->ncells = ncells;
    out->nfaces = pl->nface;
    out->ninternal = pl->nint;
    out->face_off = mem_alloc(sizeof(int) * ((size_t)pl->nface + 1));
    out->face_idx = mem_alloc(sizeof(int) * (pl->nidx > 0 ? pl->nidx : 1));
    out->owner = mem_alloc(sizeof(int) * (size_t)(pl->nface > 0 ? pl->nface : 1));
    out->neighbour = mem_alloc(sizeof(int) * (size_t)(pl->nint > 0 ? pl->nint : 1));
    out->face_off[0] = 0;
    out->npatches = in->npatches;
    out->patches = mem_calloc((size_t)in->npatches, sizeof(Patch));
    cur->face = mem_alloc(sizeof(int) * ((size_t)in->npatches + 1));
    cur->idx = mem_alloc(sizeof(size_t) * ((size_t)in->npatches + 1));
    cur->face[0] = 0;
    cur->idx[0] = 0;
    int f = pl->nint;
    size_t i = pl->iint;
    for (int p = 0; p < in->npatches; p++) {
        const Patch *P = &in->patches[p];
        Patch *Q = &out->patches[p];
        mesh_patch_copy(P, Q);
        Q->start = f;
        Q->size = pl->pface[p];
        cur->face[p + 1] = f;
        cur->idx[p + 1] = i;
        f += pl->pface[p];
        i += pl->pidx[p];
    }
}

/* Writes cell c's own faces into their places and measures the cell. */
static void put_cell(Assembly *A, Mesh *m, Cursor *cur, int c, VoronoiStats *vs)
{
    voronoi_cell_face_list(A, c);   /* close_cells checked the edges */
    for (int k = 0; k < A->ncf; k++) {
        if (A->cf[k].rev) continue;
        int f = A->cf[k].f, o = voronoi_face_other(A, f), slot = o >= 0 ? 0 : -o, g = cur->face[slot]++;
        size_t at = cur->idx[slot];
        memcpy(m->face_idx + at, A->st->idx + A->beg[f], sizeof(int) * (size_t)A->len[f]);
        cur->idx[slot] = at + (size_t)A->len[f];
        m->face_off[g + 1] = (int)cur->idx[slot];
        m->owner[g] = c;
        if (o >= 0) m->neighbour[g] = o;
    }
    voronoi_measure_cell(A, c, vs);
}

/* The points: A's own array when every point is used (the usual case),
   else the used ones renumbered in order, as meshbuild does. */
static void mesh_points(Assembly *A, int np, Mesh *m, size_t nidx)
{
    char *used = mem_calloc((size_t)(np > 0 ? np : 1), 1);
    for (size_t k = 0; k < nidx; k++) used[m->face_idx[k]] = 1;
    int nu = 0;
    for (int p = 0; p < np; p++) nu += used[p];
    if (nu == np) {
        m->points = A->pts;
        A->pts = NULL;
    } else {
        int *pmap = mem_alloc(sizeof(int) * (size_t)np);
        m->points = mem_alloc(sizeof(double) * 3 * (size_t)(nu > 0 ? nu : 1));
        nu = 0;
        for (int p = 0; p < np; p++) {
            pmap[p] = used[p] ? nu : -1;
            if (used[p]) memcpy(m->points + 3 * (size_t)nu++, A->pts + 3 * (size_t)p, 3 * sizeof(double));
        }
        for (size_t k = 0; k < nidx; k++) m->face_idx[k] = pmap[m->face_idx[k]];
        free(pmap);
    }
    m->npoints = nu;
    free(used);
}

int voronoi_write_direct(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs)
{
    Cursor cur;
    voronoi_mesh_alloc(A->in, pl, A->st->ncells, out, &cur);
    for (int c = 0; c < A->st->ncells; c++) put_cell(A, out, &cur, c, vs);
    mesh_points(A, np, out, pl->nidx);
    free(cur.face);
    free(cur.idx);
    return 0;
}

/* Hands cell c's own faces to the builder and measures the cell. */
static void emit_cell(Assembly *A, MeshBuild *b, int c, VoronoiStats *vs)
{
    voronoi_cell_face_list(A, c);   /* close_cells checked the edges */
    for (int k = 0; k < A->ncf; k++) {
        int f = A->cf[k].f, o = voronoi_face_other(A, f);
        if (A->cf[k].rev) continue;
        if (o >= 0) meshbuild_face(b, A->st->idx + A->beg[f], A->len[f], c, o, -1);
        else meshbuild_face(b, A->st->idx + A->beg[f], A->len[f], c, -1, -1 - o);
    }
    voronoi_measure_cell(A, c, vs);
}

int voronoi_write_meshbuild(Assembly *A, const Plan *pl, int np, Mesh *out, VoronoiStats *vs, Err *e)
{
    const VoronoiInput *in = A->in;
    MeshBuild b;
    meshbuild_init(&b);
    meshbuild_reserve(&b, (size_t)np, (size_t)pl->nface, pl->nidx);
    for (int p = 0; p < in->npatches; p++)
        meshbuild_patch(&b, in->patches[p].name, in->patches[p].type, in->patches[p].neighbour,
                        in->patches[p].groups);
    for (int p = 0; p < np; p++) meshbuild_point(&b, A->pts + 3 * p);
    for (int c = 0; c < A->st->ncells; c++) emit_cell(A, &b, c, vs);
    int rc = meshbuild_finish(&b, out, NULL, NULL, e);
    meshbuild_free(&b);
    return rc;
}

/* Largest angle between an internal face's normal and its seed segment. */
double voronoi_ortho_max(const Mesh *m, const VoronoiInput *in, const int *seed_of)
{
    double worst = 0, tan_worst = 0;
    for (int f = 0; f < m->ninternal; f++) {
        double S[3];
        voronoi_poly_area(m->points, m->face_idx + m->face_off[f], m->face_off[f + 1] - m->face_off[f], 0, S);
        const double *a = in->x + 3 * seed_of[m->owner[f]], *bx = in->x + 3 * seed_of[m->neighbour[f]];
        double d[3] = {bx[0] - a[0], bx[1] - a[1], bx[2] - a[2]};
        if (in->flat_axis >= 0) d[in->flat_axis] = 0;
        double c[3] = {S[1] * d[2] - S[2] * d[1], S[2] * d[0] - S[0] * d[2], S[0] * d[1] - S[1] * d[0]};
        double c2 = sq(c[0]) + sq(c[1]) + sq(c[2]), dot = S[0] * d[0] + S[1] * d[1] + S[2] * d[2];
        /* atan2 only for angles that may beat worst: tan < 0.999 tan(worst) cannot */
        if (dot > 0 && c2 < sq(0.999 * tan_worst * dot)) continue;
        double ang = atan2(sqrt(c2), dot);
        if (ang > worst) {
            worst = ang;
            tan_worst = worst < 1.5 ? tan(worst) : 0;
        }
    }
    return worst;
}
