/*
** meshbuild.c: a polyMesh from faces given in any order (meshbuild.h).
**
** Design: the builder only appends.  Points, face point lists and the
** owner/other pair of each face go into arrays that grow geometrically
** (x1.5), so adding n faces costs O(n) amortised and nothing is allocated
** per face.  Orientation is normalised as faces arrive: an internal face
** given from its higher-numbered cell has its point list reversed in place
** and the cells swapped, so from then on owner < other for every internal
** face.
**
** meshbuild_finish orders the faces with counting sorts only, so it is
** O(faces + cells + patches):
**   - internal faces: an LSD radix sort on the pair (owner, neighbour), a
**     stable counting sort on the neighbour followed by a stable counting
**     sort on the owner.  Both passes are stable, so faces between the
**     same pair of cells (merged cut cells have such pairs) keep their
**     order of addition;
**   - boundary faces: one stable counting sort on the patch.
** Points no face uses are dropped; the others keep their relative order,
** so a builder fed a mesh's own points in order gives them back unchanged.
**
** Invariant of the builder between calls: face f has points
** face_idx[face_off[f]..face_off[f+1]-1], owner[f] >= 0 unless the caller
** gave a negative cell (reported by finish), and other[f] is either a cell
** > owner[f], or -1 - patch, or NO_PATCH for a boundary face given with a
** negative patch (reported by finish).
*/
#include "meshbuild.h"
#include "mem.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* other[f] of a boundary face added with a negative patch number */
#define NO_PATCH INT_MIN

void meshbuild_init(MeshBuild *b)
{
    memset(b, 0, sizeof *b);
}

void meshbuild_free(MeshBuild *b)
{
    free(b->points);
    free(b->face_off);
    free(b->face_idx);
    free(b->owner);
    free(b->other);
    for (int p = 0; p < b->npatches; p++) {
        free(b->patches[p].name);
        free(b->patches[p].type);
        free(b->patches[p].neighbour);
        free(b->patches[p].groups);
    }
    free(b->patches);
    meshbuild_init(b);
}

/* Makes *p (of *cap elements) hold at least need elements, growing by half
   again each time so appends are amortised O(1). */
static void grow(void **p, int *cap, size_t need, size_t elem)
{
    if (need <= (size_t)*cap) return;
    size_t c = *cap > 0 ? (size_t)*cap : 16;
    while (c < need) c += c / 2 + 16;
    if (c > 0x7fffffff) c = 0x7fffffff;
    *p = mem_realloc(*p, c * elem);
    *cap = (int)c;
}

void meshbuild_reserve(MeshBuild *b, size_t npoints, size_t nfaces, size_t nidx)
{
    int cap = b->face_cap;
    grow((void **)&b->points, &b->point_cap, 3 * npoints, sizeof(double));
    grow((void **)&b->face_off, &b->face_cap, nfaces + 1, sizeof(int));
    if (b->face_cap != cap) {
        b->owner = mem_realloc(b->owner, sizeof(int) * (size_t)b->face_cap);
        b->other = mem_realloc(b->other, sizeof(int) * (size_t)b->face_cap);
    }
    grow((void **)&b->face_idx, &b->idx_cap, nidx, sizeof(int));
}

int meshbuild_patch(MeshBuild *b, const char *name, const char *type, const char *neighbour,
                    const char *groups)
{
    b->patches = mem_realloc(b->patches, sizeof(Patch) * ((size_t)b->npatches + 1));
    Patch *p = &b->patches[b->npatches];
    p->name = mem_strdup(name);
    p->type = mem_strdup(type);
    p->neighbour = neighbour ? mem_strdup(neighbour) : NULL;
    p->groups = groups ? mem_strdup(groups) : NULL;
    p->start = p->size = 0;
    return b->npatches++;
}

int meshbuild_point(MeshBuild *b, const double x[3])
{
    /* point_cap counts doubles (3 per point) */
    grow((void **)&b->points, &b->point_cap, 3 * ((size_t)b->npoints + 1), sizeof(double));
    memcpy(b->points + 3 * (size_t)b->npoints, x, 3 * sizeof(double));
    return b->npoints++;
}

int meshbuild_face(MeshBuild *b, const int *pts, int n, int cell, int other, int patch)
{
    int f = b->nfaces;
    int cap = b->face_cap;
    grow((void **)&b->face_off, &b->face_cap, (size_t)f + 2, sizeof(int));
    if (b->face_cap != cap) {
        /* owner and other share face_off's capacity */
        b->owner = mem_realloc(b->owner, sizeof(int) * (size_t)b->face_cap);
        b->other = mem_realloc(b->other, sizeof(int) * (size_t)b->face_cap);
    }
    if (f == 0) b->face_off[0] = 0;
    int len = n > 0 ? n : 0;
    grow((void **)&b->face_idx, &b->idx_cap, (size_t)b->idx_len + (size_t)len, sizeof(int));
    int *dst = b->face_idx + b->idx_len;
    int flip = other >= 0 && other < cell;
    for (int k = 0; k < len; k++) dst[k] = flip ? pts[len - 1 - k] : pts[k];
    b->idx_len += len;
    b->face_off[f + 1] = b->idx_len;
    b->owner[f] = flip ? other : cell;
    b->other[f] = other >= 0 ? (flip ? cell : other) : patch >= 0 ? -1 - patch : NO_PATCH;
    int top = cell > other ? cell : other;
    if (top + 1 > b->ncells) b->ncells = top + 1;
    return b->nfaces++;
}

/* The sizes and labels finish relies on; the message names the face in
   order of addition. */
static int check_input(const MeshBuild *b, Err *e)
{
    for (int f = 0; f < b->nfaces; f++) {
        int n = b->face_off[f + 1] - b->face_off[f];
        if (n < 3) return err_set(e, NULL, 0, "meshbuild: face %d has %d points (at least 3 needed)", f, n);
        for (int k = b->face_off[f]; k < b->face_off[f + 1]; k++)
            if (b->face_idx[k] < 0 || b->face_idx[k] >= b->npoints)
                return err_set(e, NULL, 0, "meshbuild: face %d: point %d out of range 0..%d", f,
                               b->face_idx[k], b->npoints - 1);
        if (b->owner[f] < 0) return err_set(e, NULL, 0, "meshbuild: face %d: cell %d is negative", f, b->owner[f]);
        int o = b->other[f];
        if (o >= 0 && o == b->owner[f])
            return err_set(e, NULL, 0, "meshbuild: face %d has cell %d on both sides", f, o);
        if (o == NO_PATCH) return err_set(e, NULL, 0, "meshbuild: face %d: boundary face without a patch", f);
        if (o < 0 && -1 - o >= b->npatches)
            return err_set(e, NULL, 0, "meshbuild: face %d: patch %d out of range 0..%d", f, -1 - o,
                           b->npatches - 1);
    }
    return 0;
}

/* Stable counting sort of the faces in[0..n-1] by key[face] in 0..nkey-1
   into out. */
static void counting_sort(const int *in, int n, const int *key, int nkey, int *out)
{
    int *cnt = MEM_NEW(int, (size_t)nkey + 1);
    for (int i = 0; i < n; i++) cnt[key[in[i]] + 1]++;
    for (int k = 0; k < nkey; k++) cnt[k + 1] += cnt[k];
    for (int i = 0; i < n; i++) out[cnt[key[in[i]]]++] = in[i];
    free(cnt);
}

/* order[0..nfaces-1]: added face numbers in final order; returns the
   number of internal faces. */
static int face_order(const MeshBuild *b, int *order)
{
    int nf = b->nfaces, ni = 0;
    int *tmp = MEM_NEW(int, (size_t)nf);
    int *key = MEM_NEW(int, (size_t)nf);
    for (int f = 0; f < nf; f++)
        if (b->other[f] >= 0) tmp[ni++] = f;
    int nb = 0;
    for (int f = 0; f < nf; f++)
        if (b->other[f] < 0) order[ni + nb++] = f;
    /* LSD radix on (owner, neighbour): neighbour pass, then owner pass */
    counting_sort(tmp, ni, b->other, b->ncells, order);
    counting_sort(order, ni, b->owner, b->ncells, tmp);
    memcpy(order, tmp, sizeof(int) * (size_t)ni);
    for (int f = 0; f < nf; f++) key[f] = b->other[f] < 0 ? -1 - b->other[f] : 0;
    counting_sort(order + ni, nb, key, b->npatches, tmp);
    memcpy(order + ni, tmp, sizeof(int) * (size_t)nb);
    free(tmp);
    free(key);
    return ni;
}

static int check_cells(const MeshBuild *b, Err *e)
{
    char *seen = MEM_NEW(char, (size_t)b->ncells);
    for (int f = 0; f < b->nfaces; f++) {
        seen[b->owner[f]] = 1;
        if (b->other[f] >= 0) seen[b->other[f]] = 1;
    }
    int c = 0;
    while (c < b->ncells && seen[c]) c++;
    free(seen);
    if (c < b->ncells) return err_set(e, NULL, 0, "meshbuild: cell %d has no face", c);
    return 0;
}

/* Renumbers the used points in their original order; fills pmap (-1 for
   unused) and returns the count. */
static int point_numbers(const MeshBuild *b, int *pmap)
{
    for (int i = 0; i < b->npoints; i++) pmap[i] = -1;
    for (int k = 0; k < b->idx_len; k++) pmap[b->face_idx[k]] = 0;
    int np = 0;
    for (int i = 0; i < b->npoints; i++)
        if (pmap[i] == 0) pmap[i] = np++;
    return np;
}

int meshbuild_finish(MeshBuild *b, Mesh *m, int *face_map, int *point_map, Err *e)
{
    if (check_input(b, e) || check_cells(b, e)) {
        meshbuild_free(b);
        return -1;
    }
    int nf = b->nfaces;
    int *order = MEM_NEW(int, (size_t)nf);
    int ni = face_order(b, order);
    int *pmap = MEM_NEW(int, (size_t)b->npoints);
    int np = point_numbers(b, pmap);

    m->npoints = np;
    m->points = MEM_NEW(double, 3 * (size_t)np);
    for (int i = 0; i < b->npoints; i++)
        if (pmap[i] >= 0) memcpy(m->points + 3 * (size_t)pmap[i], b->points + 3 * (size_t)i, 3 * sizeof(double));
    m->nfaces = nf;
    m->ninternal = ni;
    m->ncells = b->ncells;
    m->face_off = MEM_NEW(int, (size_t)nf + 1);
    m->face_idx = MEM_NEW(int, (size_t)b->idx_len);
    m->owner = MEM_NEW(int, (size_t)nf);
    m->neighbour = MEM_NEW(int, (size_t)ni);
    int pos = 0;
    for (int g = 0; g < nf; g++) {
        int f = order[g];
        for (int k = b->face_off[f]; k < b->face_off[f + 1]; k++) m->face_idx[pos++] = pmap[b->face_idx[k]];
        m->face_off[g + 1] = pos;
        m->owner[g] = b->owner[f];
        if (g < ni) m->neighbour[g] = b->other[f];
        if (face_map) face_map[f] = g;
    }
    m->npatches = b->npatches;
    m->patches = b->patches;
    b->patches = NULL;
    int start = ni;
    for (int p = 0; p < m->npatches; p++) {
        m->patches[p].start = start;
        m->patches[p].size = 0;
    }
    for (int g = ni; g < nf; g++) m->patches[-1 - b->other[order[g]]].size++;
    for (int p = 0; p < m->npatches; p++) {
        m->patches[p].start = start;
        start += m->patches[p].size;
    }
    if (point_map) memcpy(point_map, pmap, sizeof(int) * (size_t)b->npoints);
    free(order);
    free(pmap);
    b->npatches = 0;
    meshbuild_free(b);
    return 0;
}
