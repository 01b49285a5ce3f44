/*
** block.c: rectilinear block grids (see block.h).
**
** Numbering.  Cell (i,j,k) is c = i + nx*(j + ny*k); point (i,j,k) is
** i + (nx+1)*(j + (ny+1)*k).  With these, the face between c and its +x, +y
** and +z neighbours has neighbour c+1 < c+nx < c+nx*ny, so visiting the
** cells in order and emitting their +x, +y, +z faces produces OpenFOAM's
** upper-triangular order directly: no sort, no per-face allocation.
**
** Face points.  For axis a with the two following axes u = a+1, v = a+2
** (cyclically), a face on the plane normal to a is
**     base, base+su, base+su+sv, base+sv          (normal +a)
** where su, sv are the point strides of u and v: (u x v = a).  Internal
** faces and the max sides use this order (normal out of the owner, which
** is the lower cell or the boundary cell); min sides use it reversed.
**
** Boundary.  Patches are the distinct side names in the order of
** `order` (the order the sides were listed in the boundary dictionary);
** a patch on two sides (frontAndBack) gets the faces of both, side by side
** in that order.  Within a side faces follow increasing owner cell, so the
** two sides of a cyclic pair list matching faces at the same index.
**
** Grading.  A segment of n cells with last/first width ratio g has widths
** w0 q^i with q = g^(1/(n-1)) (blockMesh's simpleGrading); the offsets
** t_i = L (q^i - 1)/(q^n - 1) are evaluated with expm1 so that q close to 1
** loses no digits, and t_n = L exactly.
*/
#include "block.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const block_side_names[BLOCK_NSIDES] = {"xMin", "xMax", "yMin", "yMax", "zMin", "zMax"};

static const char *const axis_names[3] = {"x", "y", "z"};

static const char *const patch_types[] = {"patch", "wall", "symmetry", "symmetryPlane", "empty",
                                          "cyclic", NULL};

const DictKey block_keys[] = {
    {"scale", "1", "multiplies every coordinate (like blockMesh's scale)"},
    {"x", NULL, "x axis: { start 0; segments ((end cells grading) ...); }"},
    {"y", NULL, "y axis: as x"},
    {"z", NULL, "z axis: as x (2-D: one cell, zMin/zMax empty)"},
    {"boundary", "{}", "side -> patch: xMin { name left; type wall; } ..."},
    {0}};

static const DictKey block_axis_keys[] = {
    {"start", "0", "coordinate of the first point of the axis"},
    {"segments", NULL, "list of (end cells grading); grading = last/first cell width"},
    {0}};

static const DictKey block_side_keys[] = {
    {"name", "<side>", "patch name (the same name on several sides = one patch)"},
    {"type", "wall", "patch | wall | symmetry | symmetryPlane | empty | cyclic"},
    {"neighbourPatch", "-", "cyclic only: name of the partner patch (opposite side)"},
    {0}};

/* The entries of boundary: the six sides. */
static const DictKey boundary_keys[] = {
    {"xMin", "wall xMin", "side x = x_start"}, {"xMax", "wall xMax", "side x = x_end"},
    {"yMin", "wall yMin", "side y = y_start"}, {"yMax", "wall yMax", "side y = y_end"},
    {"zMin", "wall zMin", "side z = z_start"}, {"zMax", "wall zMax", "side z = z_end"},
    {0}};

const char block_help_note[] =
    "\nAxis sub-dictionaries x, y, z:\n"
    "  start                  0              coordinate of the first point\n"
    "  segments               [required]     ((end cells grading) ...): end coordinate,\n"
    "                                        cells (>= 1), grading = last/first width (> 0)\n"
    "Sub-dictionary boundary: entries xMin xMax yMin yMax zMin zMax (default: each\n"
    "side a wall patch named after the side), each with\n"
    "  name                   <side>         patch name; one name on two sides = one patch\n"
    "  type                   wall           patch | wall | symmetry | symmetryPlane |\n"
    "                                        empty | cyclic\n"
    "  neighbourPatch         -              cyclic only: the partner patch (opposite side)\n"
    "2-D: zMin and zMax (or the x or y pair) empty, with one cell on that axis.\n";

/* ---- grading ---- */

void block_grade(double len, int n, double g, double *t)
{
    t[0] = 0;
    if (n == 1 || g == 1) {
        for (int i = 1; i < n; i++) t[i] = len * i / n;
    } else {
        double lq = log(g) / (n - 1);   /* log q */
        double den = expm1(n * lq);
        for (int i = 1; i < n; i++) t[i] = len * (expm1(i * lq) / den);
    }
    t[n] = len;
}

/* Point coordinates of one axis, scaled: returns n+1 values in a new array
   (*x) and the cell count in *n.  The last point of each segment is its end
   coordinate exactly. */
static void block_points(const BlockSpec *s, int axis, double **x, int *n)
{
    const BlockAxis *a = &s->axis[axis];
    int total = 0;
    for (int g = 0; g < a->nseg; g++) total += a->cells[g];
    double *p = mem_alloc(sizeof(double) * (size_t)(total + 1));
    double *t = mem_alloc(sizeof(double) * (size_t)(total + 1));
    double x0 = a->start;
    int at = 0;
    p[0] = s->scale * x0;
    for (int g = 0; g < a->nseg; g++) {
        int m = a->cells[g];
        block_grade(a->end[g] - x0, m, a->grading[g], t);
        for (int i = 1; i < m; i++) p[at + i] = s->scale * (x0 + t[i]);
        p[at + m] = s->scale * a->end[g];
        at += m;
        x0 = a->end[g];
    }
    free(t);
    *x = p;
    *n = total;
}

/* ---- side validation (shared by block_read and block_mesh) ---- */

static int valid_word(const char *w)
{
    if (!w[0]) return 0;
    for (const char *c = w; *c; c++)
        if (*c <= ' ' || *c == '"' || *c == '\'' || *c == '/' || *c == '\\' || *c == ';' ||
            *c == '{' || *c == '}' || *c == '(' || *c == ')' || *c == '$' || *c == '#' || *c == 127)
            return 0;
    return 1;
}

static int type_known(const char *t)
{
    for (int i = 0; patch_types[i]; i++)
        if (!strcmp(t, patch_types[i])) return 1;
    return 0;
}

/* The side holding cyclic patch `name`, or -1. */
static int side_of(const BlockSide *side, const char *name)
{
    for (int s = 0; s < BLOCK_NSIDES; s++)
        if (!strcmp(side[s].name, name)) return s;
    return -1;
}

static int check_cyclic(const BlockSide *side, const int n[3], int s, const char *file,
                        const int *line, Err *e)
{
    const char *sn = block_side_names[s], *nm = side[s].name;
    int ln = line ? line[s] : 0;
    if (!side[s].neighbour)
        return err_set(e, file, ln, "boundary %s: cyclic patch '%s' needs neighbourPatch", sn, nm);
    for (int t = 0; t < BLOCK_NSIDES; t++)
        if (t != s && !strcmp(side[t].name, nm))
            return err_set(e, file, ln,
                           "boundary %s: cyclic patch '%s' is also on side %s; a cyclic patch covers "
                           "one side",
                           sn, nm, block_side_names[t]);
    int p = side_of(side, side[s].neighbour);
    if (p < 0 || p == s)
        return err_set(e, file, ln, "boundary %s: neighbourPatch '%s' of cyclic patch '%s' is not a "
                       "patch on another side", sn, side[s].neighbour, nm);
    if (strcmp(side[p].type, "cyclic") || !side[p].neighbour || strcmp(side[p].neighbour, nm))
        return err_set(e, file, ln,
                       "boundary %s: partner '%s' (%s) of cyclic patch '%s' must be cyclic with "
                       "neighbourPatch %s",
                       sn, side[s].neighbour, block_side_names[p], nm, nm);
    if (p != (s ^ 1))
        return err_set(e, file, ln,
                       "boundary %s: cyclic patch '%s' must pair with the opposite side %s, not %s",
                       sn, nm, block_side_names[s ^ 1], block_side_names[p]);
    int a = s / 2, u = (a + 1) % 3, v = (a + 2) % 3, b = p / 2;
    long fs = (long)n[u] * n[v], fp = (long)n[(b + 1) % 3] * n[(b + 2) % 3];
    if (fs != fp)
        return err_set(e, file, ln, "boundary %s: cyclic patches '%s' and '%s' have %ld and %ld faces",
                       sn, nm, side[p].name, fs, fp);
    return 0;
}

static int check_sides(const BlockSide *side, const int n[3], const char *file, const int *line,
                       Err *e)
{
    for (int s = 0; s < BLOCK_NSIDES; s++) {
        const char *sn = block_side_names[s];
        int ln = line ? line[s] : 0;
        if (!side[s].name || !valid_word(side[s].name))
            return err_set(e, file, ln, "boundary %s: invalid patch name '%s'", sn,
                           side[s].name ? side[s].name : "");
        if (!side[s].type || !type_known(side[s].type))
            return err_set(e, file, ln,
                           "boundary %s: unknown patch type '%s' (valid: patch wall symmetry "
                           "symmetryPlane empty cyclic)",
                           sn, side[s].type ? side[s].type : "");
        int cyc = !strcmp(side[s].type, "cyclic");
        if (side[s].neighbour && !cyc)
            return err_set(e, file, ln, "boundary %s: neighbourPatch is only for cyclic patches, not %s",
                           sn, side[s].type);
        for (int t = 0; t < s; t++)
            if (!strcmp(side[t].name, side[s].name) && strcmp(side[t].type, side[s].type))
                return err_set(e, file, ln, "boundary %s: patch '%s' is %s here but %s on side %s", sn,
                               side[s].name, side[s].type, side[t].type, block_side_names[t]);
        if (mesh_type_is_empty(side[s].type)) {
            if (n[s / 2] != 1)
                return err_set(e, file, ln,
                               "boundary %s: empty side needs exactly 1 cell along %s, found %d", sn,
                               axis_names[s / 2], n[s / 2]);
            if (!mesh_type_is_empty(side[s ^ 1].type))
                return err_set(e, file, ln, "boundary %s: empty side needs %s empty too, found %s", sn,
                               block_side_names[s ^ 1], side[s ^ 1].type);
        }
        if (cyc && check_cyclic(side, n, s, file, line, e)) return -1;
    }
    return 0;
}

/* ---- reading blockGridDict ---- */

static int entry_line(const Dict *d, const char *key)
{
    const DictEntry *en = d ? dict_find(d, key) : NULL;
    return en ? en->line : (d ? d->line : 0);
}

static int segment_line(const DictNode *nd, size_t i)
{
    return nd->kind == DN_LIST && i < nd->n ? nd->items[i]->line : nd->line;
}

/* Segment i (end, cells, grading) after coordinate prev; total counts
   the axis's cells so far. */
static int check_segment(const char *an, size_t i, double prev, const double *sg, long *total,
                         const char *file, int ln, Err *e)
{
    double end = sg[0], c = sg[1], g = sg[2];
    if (!isfinite(end) || !(end > prev))
        return err_set(e, file, ln, "%s: segment %zu ends at %g, not after %g (coordinates must increase)",
                       an, i + 1, end, prev);
    if (!(c >= 1) || c != floor(c) || c > 1e8)
        return err_set(e, file, ln, "%s: segment %zu: cells must be an integer >= 1, found %g", an, i + 1, c);
    if (!(g > 0) || !isfinite(g))
        return err_set(e, file, ln, "%s: segment %zu: grading must be > 0, found %g", an, i + 1, g);
    if ((*total += (long)c) > 100000000L)
        return err_set(e, file, ln, "%s: more than 1e8 cells along the axis", an);
    return 0;
}

static int read_axis(BlockAxis *ax, const Dict *d, int k, Err *e)
{
    const char *an = axis_names[k];
    const Dict *sd = dict_subdict(d, an, e);
    if (!sd) return -1;
    if (dict_check_keys(sd, block_axis_keys, e)) return -1;
    if (dict_scalar_or(sd, "start", 0, &ax->start, e)) return -1;
    const DictEntry *en = dict_find(sd, "segments");
    if (!en) return err_set(e, sd->file, sd->line, "%s: keyword 'segments' is missing", an);
    const DictNode *nd = dict_entry_value(en, e);
    if (!nd) return -1;
    double *v;
    size_t ns;
    if (dict_node_scalars(nd, 3, &v, &ns, e)) return -1;
    if (ns == 0) {
        free(v);
        return err_set(e, en->file, en->line, "%s: segments is empty: give ((end cells grading) ...)", an);
    }
    ax->nseg = (int)ns;
    ax->end = mem_alloc(sizeof(double) * ns);
    ax->cells = mem_alloc(sizeof(int) * ns);
    ax->grading = mem_alloc(sizeof(double) * ns);
    double prev = ax->start;
    long total = 0;
    int rc = 0;
    for (size_t i = 0; i < ns && !rc; i++) {
        const double *sg = v + 3 * i;
        rc = check_segment(an, i, prev, sg, &total, en->file, segment_line(nd, i), e);
        ax->end[i] = sg[0];
        ax->cells[i] = rc ? 1 : (int)sg[1];
        ax->grading[i] = sg[2];
        prev = sg[0];
    }
    free(v);
    return rc;
}

static int read_side(BlockSpec *s, const Dict *bd, int k, Err *e)
{
    const char *sn = block_side_names[k];
    const Dict *sd = dict_subdict(bd, sn, e);
    if (!sd) return -1;
    if (dict_check_keys(sd, block_side_keys, e)) return -1;
    int t;
    BlockSide *side = &s->side[k];
    if (dict_word_or(sd, "name", sn, &side->name, e)) return -1;
    if (dict_choice_or(sd, "type", patch_types, 1, &t, e)) return -1;
    side->type = patch_types[t];
    const char *nb = NULL;
    if (dict_find(sd, "neighbourPatch") && dict_word(sd, "neighbourPatch", &nb, e)) return -1;
    side->neighbour = nb;
    s->side_line[k] = entry_line(bd, sn);
    return 0;
}

static int read_boundary(BlockSpec *s, const Dict *d, Err *e)
{
    int listed[BLOCK_NSIDES] = {0}, no = 0;
    for (int k = 0; k < BLOCK_NSIDES; k++) {
        s->side[k].name = block_side_names[k];
        s->side[k].type = "wall";
        s->side[k].neighbour = NULL;
        s->side_line[k] = 0;
    }
    const DictEntry *ben = dict_find(d, "boundary");
    if (ben) {
        const Dict *bd = dict_subdict(d, "boundary", e);
        if (!bd) return -1;
        if (dict_check_keys(bd, boundary_keys, e)) return -1;
        for (size_t i = 0; i < bd->n; i++)
            for (int k = 0; k < BLOCK_NSIDES; k++)
                if (!listed[k] && !strcmp(bd->entries[i].key, block_side_names[k])) {
                    if (read_side(s, bd, k, e)) return -1;
                    listed[k] = 1;
                    s->order[no++] = k;
                }
        for (int k = 0; k < BLOCK_NSIDES; k++)
            if (!listed[k]) s->side_line[k] = ben->line;
    }
    for (int k = 0; k < BLOCK_NSIDES; k++)
        if (!listed[k]) s->order[no++] = k;
    return 0;
}

static void spec_zero(BlockSpec *s)
{
    memset(s, 0, sizeof *s);
    s->scale = 1;
}

int block_read(BlockSpec *s, const Dict *d, Err *e)
{
    spec_zero(s);
    s->file = d->file;
    if (dict_check_keys(d, block_keys, e)) return -1;
    if (dict_scalar_or(d, "scale", 1, &s->scale, e)) return -1;
    if (!(s->scale > 0) || !isfinite(s->scale))
        return err_set(e, d->file, entry_line(d, "scale"), "scale must be > 0, found %g", s->scale);
    for (int k = 0; k < 3; k++)
        if (read_axis(&s->axis[k], d, k, e)) {
            block_free(s);
            return -1;
        }
    int n[3];
    for (int k = 0; k < 3; k++) {
        n[k] = 0;
        for (int g = 0; g < s->axis[k].nseg; g++) n[k] += s->axis[k].cells[g];
    }
    if (read_boundary(s, d, e) || check_sides(s->side, n, s->file, s->side_line, e)) {
        block_free(s);
        return -1;
    }
    return 0;
}

void block_free(BlockSpec *s)
{
    for (int k = 0; k < 3; k++) {
        free(s->axis[k].end);
        free(s->axis[k].cells);
        free(s->axis[k].grading);
    }
    spec_zero(s);
}

/* ---- building the mesh ---- */

/* Writes the 4 points of a face with base point b and in-plane strides
   su, sv; plus = normal along +axis. */
static inline void put_quad(int *q, int b, int su, int sv, int plus)
{
    q[0] = b;
    q[1] = plus ? b + su : b + sv;
    q[2] = b + su + sv;
    q[3] = plus ? b + sv : b + su;
}

static void fill_points(Mesh *m, double *const x[3], const int n[3])
{
    double *p = m->points;
    for (int k = 0; k <= n[2]; k++)
        for (int j = 0; j <= n[1]; j++)
            for (int i = 0; i <= n[0]; i++) {
                p[0] = x[0][i];
                p[1] = x[1][j];
                p[2] = x[2][k];
                p += 3;
            }
}

/* Internal faces in upper-triangular order; returns the count. */
static int fill_internal(Mesh *m, const int n[3])
{
    const int nx = n[0], ny = n[1], nz = n[2];
    const int sp[3] = {1, nx + 1, (nx + 1) * (ny + 1)}, sc[3] = {1, nx, nx * ny};
    int *q = m->face_idx, *own = m->owner, *nei = m->neighbour, f = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++) {
            int c = nx * (j + ny * k), b = sp[1] * j + sp[2] * k;
            for (int i = 0; i < nx; i++, c++, b++) {
                if (i + 1 < nx) {
                    put_quad(q, b + sp[0], sp[1], sp[2], 1);
                    q += 4, own[f] = c, nei[f++] = c + sc[0];
                }
                if (j + 1 < ny) {
                    put_quad(q, b + sp[1], sp[2], sp[0], 1);
                    q += 4, own[f] = c, nei[f++] = c + sc[1];
                }
                if (k + 1 < nz) {
                    put_quad(q, b + sp[2], sp[0], sp[1], 1);
                    q += 4, own[f] = c, nei[f++] = c + sc[2];
                }
            }
        }
    return f;
}

/* Faces of side s starting at face f; returns the next face index. */
static int fill_side(Mesh *m, const int n[3], int s, int f)
{
    const int sp[3] = {1, n[0] + 1, (n[0] + 1) * (n[1] + 1)}, sc[3] = {1, n[0], n[0] * n[1]};
    int a = s / 2, hi = s & 1, u = (a + 1) % 3, v = (a + 2) % 3;
    /* loop the higher-stride in-plane axis outside so owners increase */
    int lo_ax = u < v ? u : v, hi_ax = u < v ? v : u;
    int plane = hi ? n[a] : 0, cplane = hi ? n[a] - 1 : 0;
    int *q = m->face_idx + 4 * (size_t)f, *own = m->owner;
    for (int o = 0; o < n[hi_ax]; o++)
        for (int l = 0; l < n[lo_ax]; l++) {
            int b = plane * sp[a] + o * sp[hi_ax] + l * sp[lo_ax];
            put_quad(q, b, sp[u], sp[v], hi);
            q += 4;
            own[f++] = cplane * sc[a] + o * sc[hi_ax] + l * sc[lo_ax];
        }
    return f;
}

/* Patches and boundary faces in patch order. */
static void fill_boundary(Mesh *m, const int n[3], const BlockSide *side, const int *order, int f)
{
    int done[BLOCK_NSIDES] = {0};
    m->patches = MEM_NEW(Patch, BLOCK_NSIDES);
    m->npatches = 0;
    for (int oi = 0; oi < BLOCK_NSIDES; oi++) {
        int s = order[oi];
        if (done[s]) continue;
        Patch *p = &m->patches[m->npatches++];
        p->name = mem_strdup(side[s].name);
        p->type = mem_strdup(side[s].type);
        p->neighbour = side[s].neighbour ? mem_strdup(side[s].neighbour) : NULL;
        p->start = f;
        for (int oj = oi; oj < BLOCK_NSIDES; oj++) {
            int t = order[oj];
            if (!done[t] && !strcmp(side[t].name, side[s].name)) {
                f = fill_side(m, n, t, f);
                done[t] = 1;
            }
        }
        p->size = f - p->start;
    }
}

static int check_order(const int *order, const char *where, Err *e)
{
    int seen[BLOCK_NSIDES] = {0};
    for (int i = 0; i < BLOCK_NSIDES; i++) {
        if (order[i] < 0 || order[i] >= BLOCK_NSIDES || seen[order[i]])
            return err_set(e, where, 0, "side order is not a permutation of the six sides");
        seen[order[i]] = 1;
    }
    return 0;
}

int block_mesh(Mesh *m, double *const x[3], const int n[3], const BlockSide side[BLOCK_NSIDES],
               const int *order, const char *where, const int *line, Err *e)
{
    static const int side_order[BLOCK_NSIDES] = {0, 1, 2, 3, 4, 5};
    if (!order) order = side_order;
    for (int k = 0; k < 3; k++) {
        if (n[k] < 1) return err_set(e, where, 0, "%s: %d cells, need at least 1", axis_names[k], n[k]);
        for (int i = 0; i < n[k]; i++)
            if (!(x[k][i + 1] > x[k][i]))
                return err_set(e, where, 0, "%s: point %d (%g) does not follow point %d (%g)",
                               axis_names[k], i + 1, x[k][i + 1], i, x[k][i]);
    }
    if (check_order(order, where, e) || check_sides(side, n, where, line, e)) return -1;
    int64_t nx = n[0], ny = n[1], nz = n[2];
    int64_t nc = nx * ny * nz, np = (nx + 1) * (ny + 1) * (nz + 1);
    int64_t nin = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
    int64_t nf = nin + 2 * (ny * nz + nx * nz + nx * ny);
    if (4 * nf >= INT_MAX || 3 * np >= INT_MAX)
        return err_set(e, where, 0, "grid too large: %lld cells, %lld faces (32-bit labels)",
                       (long long)nc, (long long)nf);
    m->npoints = (int)np;
    m->ncells = (int)nc;
    m->nfaces = (int)nf;
    m->ninternal = (int)nin;
    m->points = mem_alloc(sizeof(double) * 3 * (size_t)np);
    m->face_off = mem_alloc(sizeof(int) * (size_t)(nf + 1));
    m->face_idx = mem_alloc(sizeof(int) * 4 * (size_t)nf);
    m->owner = mem_alloc(sizeof(int) * (size_t)nf);
    m->neighbour = mem_alloc(sizeof(int) * (size_t)(nin ? nin : 1));
    fill_points(m, x, n);
    for (int64_t f = 0; f <= nf; f++) m->face_off[f] = (int)(4 * f);
    int f = fill_internal(m, n);
    fill_boundary(m, n, side, order, f);
    for (int k = 0; k < 3; k++) {
        m->cart.n[k] = n[k];
        m->cart.x[k] = mem_alloc(sizeof(double) * (size_t)(n[k] + 1));
        memcpy(m->cart.x[k], x[k], sizeof(double) * (size_t)(n[k] + 1));
    }
    m->cell_parent = mem_alloc(sizeof(int) * (size_t)nc);
    for (int c = 0; c < (int)nc; c++) m->cell_parent[c] = c;
    return 0;
}

int block_build(const BlockSpec *s, Mesh *m, Err *e)
{
    double *x[3];
    int n[3];
    for (int k = 0; k < 3; k++) block_points(s, k, &x[k], &n[k]);
    int rc = block_mesh(m, x, n, s->side, s->order, s->file, s->side_line, e);
    for (int k = 0; k < 3; k++) free(x[k]);
    return rc;
}
