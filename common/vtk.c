/*
** vtk.c: legacy VTK files for ParaView, written without libvtk.  See vtk.h.
**
** Version line.  "# vtk DataFile Version 2.0", as foamToVTK -legacy writes.
** VTK 9's legacy reader accepts polyhedra (type 42) under every version
** line below 5.0 (checked with VTK 9.1 for 2.0, 3.0 and 4.2: one cube read
** back as 42 with 6 faces and volume 1); 5.1 would need the OFFSETS /
** CONNECTIVITY layout, which VTK < 9 (older ParaView) cannot read.
**
** Cells.  A file is built from a Grid: the points written (a subset of the
** mesh points for 2-D meshes and patches), and per cell a VTK type and its
** connectivity in written-point numbers.  Three shapes occur:
**   - 3-D cells that are exact hexahedra (six quadrilaterals, eight points,
**     joined like a cube) are VTK_HEXAHEDRON (12), as foamToVTK does: ParaView
**     slices, clips and renders hexahedra much faster than polyhedra and
**     every filter supports them.  Block grids are all hexahedra.  VTK reads
**     a hexahedron's faces as bilinear; ours are planar, so volumes agree.
**   - every other 3-D cell (cut, merged, split-face cells) is a
**     VTK_POLYHEDRON (42): connectivity "nFaces, then nPts and the point ids
**     of each face", faces ordered so that their normals point out of the
**     cell (OpenFOAM's order for owned faces, reversed for neighbour faces).
**   - 2-D meshes (one cell thick between empty patches, mesh_empty_axis >= 0)
**     are written as one VTK_POLYGON (7) per cell: the cell's face on the
**     lower empty side (the one whose outward normal points along -axis),
**     with its points reversed so that it turns counter-clockwise about
**     +axis.  Only the points of that side are written.  Patches are
**     POLYDATA POLYGONS in OpenFOAM's order (normals out of the domain).
**
** Data.  Every field is a FIELD array of doubles with 1 or 3 components
** (ParaView shows 3-component arrays as vectors: Magnitude/X/Y/Z colouring,
** glyph orientation).  SCALARS/VECTORS sections are not used because VTK's
** reader keeps only the first SCALARS and the first VECTORS section of a
** dataset unless told otherwise (checked: the second of each is dropped).
** TimeValue is dataset FieldData, as in foamToVTK.  Point data (optional)
** is the average of the values of the cells around each point weighted by
** cell volume (patches: face area), so tiny cut cells, whose values are the
** least reliable, weigh least; points that no cell of the file touches, or
** whose cells all have zero size, get 0.
**
** Writing.  A file goes to its temporary file a megabyte at a time (Out,
** an IoStream of io.h) and is renamed into place at the end, so the
** solvers' VTK output at their write times does not hold a copy of the
** file (about 100 bytes a cell of a 3-D grid) beside their state.
**
** Encoding.  Binary legacy files are big-endian: every int32 and float64 is
** assembled byte by byte from its most significant end, so the code is the
** same on any host.  Ascii numbers are the shortest decimal that reads back
** to the same double (foam_fmt_double), so ascii and binary files hold the
** same values.  Array names are percent-encoded where VTK's reader would
** split them (blanks, '%', non-ASCII), as VTK's own writer does.  Counts are
** int32 in the format: a mesh whose connectivity would exceed that is
** refused rather than written wrongly.
*/
#include "vtk.h"
#include "buf.h"
#include "foam.h"
#include "geom.h"
#include "io.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { VTK_POLYGON = 7, VTK_HEXAHEDRON = 12, VTK_POLYHEDRON = 42 };

/* What a file shows: points (indices into the mesh points), cells as
   connectivity runs conn[off[c]..off[c+1]-1] of written-point numbers, and
   the per-cell weights of the point average. */
typedef struct Grid {
    int np;
    int *pts;            /* np mesh point ids, or NULL: all mesh points in order */
    int nc;
    int *off;            /* nc+1 */
    int *conn;
    unsigned char *type; /* nc VTK cell types */
    double *w;           /* nc weights (volumes or areas), or NULL */
} Grid;

/* One data array: ntuples (= Grid.nc) tuples of width doubles. */
typedef struct Arr {
    const char *name;
    int width;
    const double *v;
} Arr;

static void grid_free(Grid *g)
{
    free(g->pts);
    free(g->off);
    free(g->conn);
    free(g->type);
    free(g->w);
    memset(g, 0, sizeof *g);
}

void vtk_opts_init(VtkOpts *o)
{
    o->binary = 1;
    o->point_data = 0;
    o->time = 0;
    o->title = NULL;
    o->mesh_name = NULL;
}

/* ---- encoding ---- */

static void put_int(Buf *b, long v)
{
    char s[24];
    int n = 0;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    do {
        s[sizeof s - 1 - n++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) s[sizeof s - 1 - n++] = '-';
    buf_put(b, s + sizeof s - n, (size_t)n);
}

static void put_be32(Buf *b, int32_t v)
{
    uint32_t u = (uint32_t)v;
    unsigned char c[4] = {(unsigned char)(u >> 24), (unsigned char)(u >> 16),
                          (unsigned char)(u >> 8), (unsigned char)u};
    buf_put(b, c, 4);
}

static void put_be64(Buf *b, double x)
{
    uint64_t u;
    memcpy(&u, &x, 8);
    unsigned char c[8];
    for (int k = 0; k < 8; k++) c[k] = (unsigned char)(u >> (56 - 8 * k));
    buf_put(b, c, 8);
}

/* ---- the file, a megabyte at a time ---- */

/* The file being written: its bytes gather in b and go to the stream s a
   megabyte at a time (out_check), so a big grid's file is never whole in
   memory (at 64^3 it would be about 100 bytes a cell). */
typedef struct Out {
    Buf b;
    IoStream *s;
} Out;

enum { OUT_CHUNK = 1 << 20 };

static void out_check(Out *o)
{
    if (o->b.n < OUT_CHUNK) return;
    io_stream_put(o->s, o->b.p, o->b.n);
    buf_clear(&o->b);
}

/* One tuple of width doubles: ascii on one line, binary raw. */
static void put_tuple(Out *o, const double *x, int width, int binary)
{
    Buf *b = &o->b;
    for (int k = 0; k < width; k++) {
        if (binary) {
            put_be64(b, x[k]);
        } else {
            if (k) buf_putc(b, ' ');
            foam_put_double(b, x[k], 0);
        }
    }
    if (!binary) buf_putc(b, '\n');
    out_check(o);
}

/* n tuples of width doubles: ascii one tuple per line, binary raw. */
static void put_doubles(Out *o, const double *v, size_t n, int width, int binary)
{
    for (size_t i = 0; i < n; i++) put_tuple(o, v + i * (size_t)width, width, binary);
    if (binary) buf_putc(&o->b, '\n');
}

/* Array names: VTK's reader splits at blanks and decodes %XX. */
static void put_name(Buf *b, const char *s)
{
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p <= ' ' || *p > '~' || *p == '%') buf_printf(b, "%%%02X", *p);
        else buf_putc(b, (char)*p);
    }
}

/* The title line may hold at most 255 characters and no newline. */
static void put_title(Buf *b, const char *t)
{
    if (!t || !*t) t = "Kiesel";
    size_t n = 0;
    for (const char *p = t; *p && n < 255; p++, n++)
        buf_putc(b, (*p == '\n' || *p == '\r') ? ' ' : *p);
    buf_putc(b, '\n');
}

/* ---- cells of a 3-D mesh ---- */

/* Cell -> face lists: the mesh's own (mesh_cell_faces) or made for the
   call, so the writer also works on a mesh that only has owner/neighbour. */
static void cell_faces(const Mesh *m, int **off, int **idx, int *own)
{
    *own = !(m->cell_off && m->cell_faces);
    if (*own) {
        mesh_cell_face_lists(m, off, idx);
        return;
    }
    *off = m->cell_off;
    *idx = m->cell_faces;
}

static int face_size(const Mesh *m, int f) { return m->face_off[f + 1] - m->face_off[f]; }

/* Points of face f (n of them) in the order whose normal points out of
   cell c (inward != 0: into it). */
static void face_loop(const Mesh *m, int f, int c, int inward, int *q)
{
    const int *p = m->face_idx + m->face_off[f];
    int n = face_size(m, f);
    int flip = (m->owner[f] == c) == (inward != 0);
    for (int i = 0; i < n; i++) q[i] = flip ? p[n - 1 - i] : p[i];
}

static int find4(const int *q, int x)
{
    for (int i = 0; i < 4; i++)
        if (q[i] == x) return i;
    return -1;
}

/* Side face q (4 points) joins bottom edge (b[i], b[i+1]) to the top: records
   the top points above b[i] and b[i+1], checking agreement with what other
   side faces said.  Returns 0 when q is not such a face. */
static int hex_side(const int *b, const int *q, int *t, int *covered)
{
    int i = -1;
    for (int k = 0; k < 4; k++) {
        int a = find4(q, b[k]), n = find4(q, b[(k + 1) % 4]);
        if (a >= 0 && n >= 0 && ((a + 1) % 4 == n || (n + 1) % 4 == a)) i = k;
    }
    if (i < 0 || covered[i]) return 0;
    covered[i] = 1;
    int j = (i + 1) % 4;
    int a = find4(q, b[i]), n = find4(q, b[j]);
    int dir = (a + 1) % 4 == n ? 1 : 3;            /* step from b[i] to b[j] in q */
    int ta = q[(a + 4 - dir) % 4], tn = q[(n + dir) % 4];
    if (find4(b, ta) >= 0 || find4(b, tn) >= 0) return 0;
    if ((t[i] >= 0 && t[i] != ta) || (t[j] >= 0 && t[j] != tn)) return 0;
    t[i] = ta;
    t[j] = tn;
    return 1;
}

/* VTK hexahedron points of cell c (faces cf[0..5]) into v[8], returning 1,
   or 0 when the cell is not an exact hexahedron.  Bottom = first face turned
   to face into the cell (VTK: bottom normal towards the top), top point i
   above bottom point i. */
static int hex_points(const Mesh *m, int c, const int *cf, int nf, int v[8])
{
    if (nf != 6) return 0;
    for (int k = 0; k < 6; k++)
        if (face_size(m, cf[k]) != 4) return 0;
    int b[4], t[4] = {-1, -1, -1, -1}, covered[4] = {0, 0, 0, 0}, top = -1;
    face_loop(m, cf[0], c, 1, b);
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (b[i] == b[j]) return 0;
    for (int k = 1; k < 6; k++) {
        int q[4], shared = 0;
        face_loop(m, cf[k], c, 0, q);
        for (int i = 0; i < 4; i++) shared += find4(b, q[i]) >= 0;
        if (shared == 0) {
            if (top >= 0) return 0;
            top = k;
        } else if (shared != 2 || !hex_side(b, q, t, covered)) {
            return 0;
        }
    }
    if (top < 0) return 0;
    int q[4];
    face_loop(m, cf[top], c, 0, q);
    int p = find4(q, t[0]);
    if (p < 0) return 0;
    int fwd = 1, bwd = 1;
    for (int i = 1; i < 4; i++) {
        fwd &= q[(p + i) % 4] == t[i];
        bwd &= q[(p + 4 - i) % 4] == t[i];
    }
    if (!fwd && !bwd) return 0;
    memcpy(v, b, sizeof b);
    memcpy(v + 4, t, sizeof t);
    return 1;
}

static int too_big(long n, const char *path, Err *e)
{
    if (n <= INT_MAX) return 0;
    err_set(e, path, 0, "mesh too large for the legacy VTK format (%ld connectivity entries)", n);
    return 1;
}

/* All mesh points; hexahedra and outward-oriented polyhedra.  The cells
   are classified first, so that the connectivity is allocated to its
   length (a hexahedron's 8 entries, not the 31 of its face stream). */
static int grid_3d(const Mesh *m, Grid *g, const char *path, Err *e)
{
    int *off, *idx, own, v[8];
    cell_faces(m, &off, &idx, &own);
    g->np = m->npoints;
    g->nc = m->ncells;
    g->off = mem_alloc(((size_t)m->ncells + 1) * sizeof(int));
    g->type = MEM_NEW(unsigned char, m->ncells);
    long total = 0;
    for (int c = 0; c < m->ncells; c++) {
        long len = 1;
        for (int k = off[c]; k < off[c + 1]; k++) len += 1 + face_size(m, idx[k]);
        g->type[c] = hex_points(m, c, idx + off[c], off[c + 1] - off[c], v) ? VTK_HEXAHEDRON : VTK_POLYHEDRON;
        total += g->type[c] == VTK_HEXAHEDRON ? 8 : len;
    }
    int rc = 0;
    if (too_big(total + m->ncells, path, e)) {
        rc = -1;
    } else {
        g->conn = MEM_NEW(int, total);
        int n = 0;
        g->off[0] = 0;
        for (int c = 0; c < m->ncells; c++) {
            const int *cf = idx + off[c];
            int nf = off[c + 1] - off[c];
            if (g->type[c] == VTK_HEXAHEDRON) {
                hex_points(m, c, cf, nf, g->conn + n);
                n += 8;
            } else {
                g->conn[n++] = nf;
                for (int k = 0; k < nf; k++) {
                    g->conn[n++] = face_size(m, cf[k]);
                    face_loop(m, cf[k], c, 0, g->conn + n);
                    n += face_size(m, cf[k]);
                }
            }
            g->off[c + 1] = n;
        }
    }
    if (own) {
        free(off);
        free(idx);
    }
    return rc;
}

/* ---- polygons: 2-D meshes and patches ---- */

/* Twice the area vector's component along axis (Newell's formula), enough
   to tell which way a face of an empty patch points. */
static double face_normal_along(const Mesh *m, int f, int axis)
{
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int *p = m->face_idx + m->face_off[f];
    int n = face_size(m, f);
    double s = 0;
    for (int i = 0; i < n; i++) {
        const double *a = m->points + 3 * (size_t)p[i], *b = m->points + 3 * (size_t)p[(i + 1) % n];
        s += (a[u] - b[u]) * (a[v] + b[v]);
    }
    return s;
}

/* Grid of polygons from faces[0..nc-1], reversed when rev; the points are
   those of the faces, numbered in mesh order. */
static int grid_polygons(const Mesh *m, const int *faces, int nc, int rev, Grid *g,
                         const char *path, Err *e)
{
    long total = 0;
    for (int c = 0; c < nc; c++) total += face_size(m, faces[c]);
    if (too_big(total + nc, path, e)) return -1;
    int *map = mem_alloc(((size_t)m->npoints + 1) * sizeof(int));
    for (int p = 0; p < m->npoints; p++) map[p] = -1;
    for (int c = 0; c < nc; c++)
        for (int k = m->face_off[faces[c]]; k < m->face_off[faces[c] + 1]; k++) map[m->face_idx[k]] = 0;
    g->np = 0;
    for (int p = 0; p < m->npoints; p++)
        if (map[p] == 0) map[p] = g->np++;
    g->pts = MEM_NEW(int, g->np);
    for (int p = 0; p < m->npoints; p++)
        if (map[p] >= 0) g->pts[map[p]] = p;
    g->nc = nc;
    g->off = mem_alloc(((size_t)nc + 1) * sizeof(int));
    g->type = MEM_NEW(unsigned char, nc);
    g->conn = MEM_NEW(int, total);
    int n = 0;
    g->off[0] = 0;
    for (int c = 0; c < nc; c++) {
        const int *p = m->face_idx + m->face_off[faces[c]];
        int np = face_size(m, faces[c]);
        for (int i = 0; i < np; i++) g->conn[n++] = map[p[rev ? np - 1 - i : i]];
        g->type[c] = VTK_POLYGON;
        g->off[c + 1] = n;
    }
    free(map);
    return 0;
}

/* Each cell's face on the lower empty side (outward normal along -axis).
   A cell without one, or with two, has a reversed face or misplaced
   points: the input is at fault, so the message names the mesh (where),
   not the file being written. */
static int grid_2d(const Mesh *m, int axis, Grid *g, const char *path, const char *where, Err *e)
{
    int *lower = mem_alloc(((size_t)m->ncells + 1) * sizeof(int));
    for (int c = 0; c < m->ncells; c++) lower[c] = -1;
    int rc = 0;
    for (int p = 0; p < m->npatches && rc == 0; p++) {
        const Patch *pa = &m->patches[p];
        if (!mesh_patch_is_empty(pa)) continue;
        for (int f = pa->start; f < pa->start + pa->size; f++) {
            if (face_normal_along(m, f, axis) >= 0) continue;
            int c = m->owner[f];
            if (lower[c] >= 0) {
                rc = err_set(e, where, 0,
                             "2-D mesh: cell %d has two faces (%d, %d) on the lower empty side (normal -%c): one "
                             "is reversed or its points are misplaced (checkGrid names it)",
                             c, lower[c], f, "xyz"[axis]);
                break;
            }
            lower[c] = f;
        }
    }
    for (int c = 0; c < m->ncells && rc == 0; c++)
        if (lower[c] < 0)
            rc = err_set(e, where, 0,
                         "2-D mesh: cell %d has no face on the lower empty side (normal -%c): one is reversed or "
                         "its points are misplaced (checkGrid names it)",
                         c, "xyz"[axis]);
    if (rc == 0) rc = grid_polygons(m, lower, m->ncells, 1, g, path, e);
    free(lower);
    return rc;
}

/* ---- writing ---- */

static void put_points(Out *o, const Mesh *m, const Grid *g, int binary)
{
    buf_printf(&o->b, "POINTS %d double\n", g->np);
    for (int i = 0; i < g->np; i++) put_tuple(o, m->points + 3 * (size_t)(g->pts ? g->pts[i] : i), 3, binary);
    if (binary) buf_putc(&o->b, '\n');
}

/* CELLS/POLYGONS: per cell its entry count, then the entries. */
static void put_cells(Out *o, const Grid *g, const char *keyword, int binary)
{
    Buf *b = &o->b;
    buf_printf(b, "%s %d %d\n", keyword, g->nc, g->nc + g->off[g->nc]);
    for (int c = 0; c < g->nc; c++, out_check(o)) {
        int n = g->off[c + 1] - g->off[c];
        const int *x = g->conn + g->off[c];
        if (binary) {
            put_be32(b, n);
            for (int i = 0; i < n; i++) put_be32(b, x[i]);
            continue;
        }
        put_int(b, n);
        for (int i = 0; i < n; i++) {
            buf_putc(b, ' ');
            put_int(b, x[i]);
        }
        buf_putc(b, '\n');
    }
    if (binary) buf_putc(b, '\n');
}

static void put_types(Out *o, const Grid *g, int binary)
{
    Buf *b = &o->b;
    buf_printf(b, "CELL_TYPES %d\n", g->nc);
    for (int c = 0; c < g->nc; c++, out_check(o)) {
        if (binary) {
            put_be32(b, g->type[c]);
        } else {
            put_int(b, g->type[c]);
            buf_putc(b, '\n');
        }
    }
    if (binary) buf_putc(b, '\n');
}

/* One FIELD array: its name, shape and ntuples tuples. */
static void put_array(Out *o, const Arr *a, int ntuples, int binary)
{
    put_name(&o->b, a->name);
    buf_printf(&o->b, " %d %d double\n", a->width, ntuples);
    put_doubles(o, a->v, (size_t)ntuples, a->width, binary);
}

static void put_arrays(Out *o, const Arr *a, int na, int ntuples, int binary)
{
    buf_printf(&o->b, "FIELD FieldData %d\n", na);
    for (int i = 0; i < na; i++) put_array(o, &a[i], ntuples, binary);
}

/* Distinct written points of cell c into out; returns their count.
   stamp[p] == c marks points already seen for this cell. */
static int cell_points(const Grid *g, int c, int *stamp, int *out)
{
    int n = 0, k = g->off[c], end = g->off[c + 1];
    if (g->type[c] != VTK_POLYHEDRON) {
        for (; k < end; k++)
            if (stamp[g->conn[k]] != c) stamp[g->conn[k]] = c, out[n++] = g->conn[k];
        return n;
    }
    int nf = g->conn[k++];
    for (int f = 0; f < nf; f++) {
        int np = g->conn[k++];
        for (int i = 0; i < np; i++, k++)
            if (stamp[g->conn[k]] != c) stamp[g->conn[k]] = c, out[n++] = g->conn[k];
    }
    return n;
}

/* Weighted average of the cell values around each point (see top). */
static double *point_average(const Grid *g, const Arr *a)
{
    size_t w = (size_t)a->width;
    size_t nacc = (size_t)g->np * w;
    double *acc = MEM_NEW(double, nacc);
    double *sum = MEM_NEW(double, g->np);
    int *stamp = MEM_NEW(int, g->np), *pts = NULL;
    int maxn = 0;
    for (int c = 0; c < g->nc; c++)
        if (g->off[c + 1] - g->off[c] > maxn) maxn = g->off[c + 1] - g->off[c];
    pts = MEM_NEW(int, maxn);
    for (int p = 0; p < g->np; p++) stamp[p] = -1;
    for (int c = 0; c < g->nc; c++) {
        int n = cell_points(g, c, stamp, pts);
        double wc = fabs(g->w[c]);
        for (int i = 0; i < n; i++) {
            sum[pts[i]] += wc;
            for (size_t k = 0; k < w; k++) acc[(size_t)pts[i] * w + k] += wc * a->v[(size_t)c * w + k];
        }
    }
    for (int p = 0; p < g->np; p++)
        if (sum[p] > 0)
            for (size_t k = 0; k < w; k++) acc[(size_t)p * w + k] /= sum[p];
    free(sum);
    free(stamp);
    free(pts);
    return acc;
}

/* ---- a file written one field at a time ---- */

struct VtkFile {
    IoStream s;
    Out out;
    Grid g;         /* its connectivity is freed once written, unless point data needs it */
    const Mesh *m;
    int patch;      /* -1: the internal mesh */
    int nfields, nput, binary, point_data;
    Arr *pa;        /* point data: the averages of the fields put so far (names and values owned) */
    char *path;     /* for messages */
};

static void file_free(VtkFile *f)
{
    grid_free(&f->g);
    buf_free(&f->out.b);
    for (int i = 0; i < f->nput && f->pa; i++) {
        free((char *)f->pa[i].name);
        free((double *)f->pa[i].v);
    }
    free(f->pa);
    free(f->path);
    free(f);
}

/* Opens path and writes the header, the points, the cells (and their
   types) and the heading of the cell data from g, which the file takes
   over; NULL with e filled when path cannot be opened. */
static VtkFile *file_begin(const char *path, const Mesh *m, int patch, Grid *g, int nfields, const VtkOpts *o,
                           Err *e)
{
    VtkFile *f = MEM_NEW(VtkFile, 1);
    f->g = *g;
    memset(g, 0, sizeof *g);
    f->m = m;
    f->patch = patch;
    f->nfields = nfields;
    f->binary = o->binary;
    f->point_data = o->point_data && nfields > 0;
    f->path = mem_strdup(path);
    if (io_stream_open(&f->s, path, e)) {
        file_free(f);
        return NULL;
    }
    f->out.s = &f->s;
    buf_init(&f->out.b);
    int bin = o->binary, polydata = patch >= 0;
    Buf *b = &f->out.b;
    buf_puts(b, "# vtk DataFile Version 2.0\n");
    put_title(b, o->title);
    buf_puts(b, bin ? "BINARY\n" : "ASCII\n");
    buf_puts(b, polydata ? "DATASET POLYDATA\n" : "DATASET UNSTRUCTURED_GRID\n");
    buf_puts(b, "FIELD FieldData 1\nTimeValue 1 1 double\n");
    put_doubles(&f->out, &o->time, 1, 1, bin);
    put_points(&f->out, m, &f->g, bin);
    put_cells(&f->out, &f->g, polydata ? "POLYGONS" : "CELLS", bin);
    if (!polydata) put_types(&f->out, &f->g, bin);
    if (nfields > 0) buf_printf(b, "CELL_DATA %d\nFIELD FieldData %d\n", f->g.nc, nfields);
    if (f->point_data) {
        f->pa = MEM_NEW(Arr, nfields);
    } else { /* the fields to come need only the count */
        int nc = f->g.nc;
        grid_free(&f->g);
        f->g.nc = nc;
    }
    return f;
}

static int check_field(const char *path, const Field *f, int index, int count, Err *e)
{
    if (!f->name || !f->name[0]) return err_set(e, path, 0, "field %d has no name", index);
    if (f->width != 1 && f->width != 3)
        return err_set(e, path, 0, "field '%s': width %d, expected 1 or 3", f->name, f->width);
    if (count >= 0 && f->ncells != count)
        return err_set(e, path, 0, "field '%s' has %d cells, the mesh %d", f->name, f->ncells, count);
    return 0;
}

static int check_fields(const char *path, const Field *f, int n, int count, Err *e)
{
    for (int i = 0; i < n; i++)
        if (check_field(path, &f[i], i, count, e)) return -1;
    return 0;
}

static const VtkOpts *opts_or_default(const VtkOpts *o, VtkOpts *def)
{
    if (o) return o;
    vtk_opts_init(def);
    return def;
}

VtkFile *vtk_begin_internal(const char *path, const Mesh *m, int nfields, const VtkOpts *o, Err *e)
{
    VtkOpts def;
    o = opts_or_default(o, &def);
    if (o->point_data && nfields > 0 && !m->cell_vol) {
        err_set(e, path, 0, "point data needs the cell volumes (mesh_geometry)");
        return NULL;
    }
    Grid g;
    memset(&g, 0, sizeof g);
    int axis = mesh_empty_axis(m);
    if (axis >= 0 ? grid_2d(m, axis, &g, path, o->mesh_name ? o->mesh_name : path, e) : grid_3d(m, &g, path, e)) {
        grid_free(&g);
        return NULL;
    }
    if (o->point_data && nfields > 0) {
        g.w = MEM_NEW(double, m->ncells);
        memcpy(g.w, m->cell_vol, (size_t)m->ncells * sizeof(double));
    }
    return file_begin(path, m, -1, &g, nfields, o, e);
}

VtkFile *vtk_begin_patch(const char *path, const Mesh *m, int patch, int nfields, const VtkOpts *o, Err *e)
{
    VtkOpts def;
    o = opts_or_default(o, &def);
    if (patch < 0 || patch >= m->npatches) {
        err_set(e, path, 0, "patch %d out of range (%d patches)", patch, m->npatches);
        return NULL;
    }
    if (o->point_data && nfields > 0 && !m->face_area) {
        err_set(e, path, 0, "point data needs the face areas (mesh_geometry)");
        return NULL;
    }
    const Patch *pa = &m->patches[patch];
    int *faces = MEM_NEW(int, pa->size);
    for (int i = 0; i < pa->size; i++) faces[i] = pa->start + i;
    Grid g;
    memset(&g, 0, sizeof g);
    int rc = grid_polygons(m, faces, pa->size, 0, &g, path, e);
    if (rc == 0 && o->point_data && nfields > 0) {
        g.w = MEM_NEW(double, pa->size);
        for (int i = 0; i < pa->size; i++) g.w[i] = geom_norm(m->face_area + 3 * (size_t)faces[i]);
    }
    free(faces);
    if (rc) {
        grid_free(&g);
        return NULL;
    }
    return file_begin(path, m, patch, &g, nfields, o, e);
}

int vtk_put_field(VtkFile *f, const Field *fl, Err *e)
{
    if (f->nput == f->nfields)
        return err_set(e, f->path, 0, "field '%s': the file has room for %d fields", fl->name ? fl->name : "",
                       f->nfields);
    if (check_field(f->path, fl, f->nput, f->patch < 0 ? f->m->ncells : -1, e)) return -1;
    double *pv = NULL;
    if (f->patch >= 0) {
        pv = MEM_NEW(double, (size_t)f->g.nc * (size_t)fl->width);
        field_patch_values(fl, f->m, f->patch, pv);
    }
    Arr a = {fl->name, fl->width, pv ? pv : fl->v};
    put_array(&f->out, &a, f->g.nc, f->binary);
    if (f->point_data) f->pa[f->nput] = (Arr){mem_strdup(fl->name), fl->width, point_average(&f->g, &a)};
    f->nput++;
    free(pv);
    return 0;
}

int vtk_end(VtkFile *f, Err *e)
{
    if (f->nput < f->nfields) {
        err_set(e, f->path, 0, "%d of the file's %d fields written", f->nput, f->nfields);
        vtk_abort(f);
        return -1;
    }
    if (f->point_data) {
        buf_printf(&f->out.b, "POINT_DATA %d\n", f->g.np);
        put_arrays(&f->out, f->pa, f->nfields, f->g.np, f->binary);
    }
    io_stream_put(&f->s, f->out.b.p, f->out.b.n);
    int rc = io_stream_close(&f->s, e);
    file_free(f);
    return rc;
}

void vtk_abort(VtkFile *f)
{
    io_stream_abort(&f->s);
    file_free(f);
}

/* All fields into a file begun (or NULL: its error is in e). */
static int write_all(VtkFile *f, const Field *fields, int n, Err *e)
{
    if (!f) return -1;
    for (int i = 0; i < n; i++)
        if (vtk_put_field(f, &fields[i], e)) {
            vtk_abort(f);
            return -1;
        }
    return vtk_end(f, e);
}

int vtk_write_internal(const char *path, const Mesh *m, const Field *fields, int nfields,
                       const VtkOpts *o, Err *e)
{
    if (check_fields(path, fields, nfields, m->ncells, e)) return -1;
    return write_all(vtk_begin_internal(path, m, nfields, o, e), fields, nfields, e);
}

int vtk_write_patch(const char *path, const Mesh *m, int patch, const Field *fields, int nfields,
                    const VtkOpts *o, Err *e)
{
    if (check_fields(path, fields, nfields, -1, e)) return -1;
    return write_all(vtk_begin_patch(path, m, patch, nfields, o, e), fields, nfields, e);
}

/* ---- series ---- */

static void put_json_string(Buf *b, const char *s)
{
    buf_putc(b, '"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\') {
            buf_putc(b, '\\');
            buf_putc(b, (char)*p);
        } else if (*p < 0x20) {
            buf_printf(b, "\\u%04x", *p);
        } else {
            buf_putc(b, (char)*p);
        }
    }
    buf_putc(b, '"');
}

int vtk_write_series(const char *path, const VtkSeriesEntry *v, int n, Err *e)
{
    for (int i = 0; i < n; i++) {
        if (!v[i].name) return err_set(e, path, 0, "series entry %d has no file name", i);
        if (!isfinite(v[i].time))
            return err_set(e, path, 0, "series entry '%s': time is not finite", v[i].name);
    }
    Buf b;
    buf_init(&b);
    buf_puts(&b, "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n");
    for (int i = 0; i < n; i++) {
        buf_puts(&b, "    { \"name\" : ");
        put_json_string(&b, v[i].name);
        buf_puts(&b, ", \"time\" : ");
        foam_put_double(&b, v[i].time == 0 ? 0.0 : v[i].time, 0);
        buf_puts(&b, i + 1 < n ? " },\n" : " }\n");
    }
    buf_puts(&b, "  ]\n}\n");
    int rc = io_write_atomic(path, b.p, b.n, 0, e);
    buf_free(&b);
    return rc;
}
