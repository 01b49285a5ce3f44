/*
** mesh_io.c: reading and writing constant/polyMesh, and its stream form.
**
** Files (mesh.h): points (vectorField), faces (faceList in ascii,
** faceCompactList in binary), owner and neighbour (labelList, with
** OpenFOAM's note "nPoints:..  nCells:..  nFaces:..  nInternalFaces:.."),
** boundary (polyBoundaryMesh, a list of patch dictionaries laid out as
** blockMesh v1912 writes them), and Kiesel's extras cartesianGrid
** (dictionary, always ascii: it is small and stays readable) and
** cellParent (labelList).  Ascii numbers are the shortest decimals that
** read back to the same bits, so ascii and binary round trips are exact.
**
** Reading goes through the dictionary parser (dict.h), which stores big
** lists flat.  A binary faceCompactList is two lists in a row (offsets
** nfaces+1, then the flat point labels); an ascii faceList is one list of
** lists.  Every size and index is checked before the arrays are accepted,
** and every message names the file (and the line of the offending list),
** because these files are edited by hand and produced by other programs.
** The ordering invariants are left to mesh_check.
**
** Stream form, for pipelines: each file as "@file <name> <nbytes>\n"
** followed by exactly nbytes bytes (the file as it would be on disk,
** gzipped when asked), then "@end\n".  The reader trusts nothing: every
** record header must parse, every size must fit in what is left, each
** known file may appear once, only blanks may follow "@end"; files with
** unknown names are skipped so that a newer writer's extras do not break
** an older reader.
**
** Writing: each file is assembled in a Buf (reserved to its final size,
** so a big mesh is not copied while the buffer grows) and handed to
** io_write_atomic_v.  In binary, on a host whose memory layout is the
** file's (little-endian, 32-bit int), the big arrays are not copied into
** the Buf: it holds the text around them (header, sizes, brackets,
** footer) and the arrays are written straight from the mesh as separate
** pieces, which halves the memory traffic of writing a big mesh; the
** bytes on disk are the same (the pieces mirror foam_put_scalars and
** foam_put_labels exactly, and the tests compare files byte for byte).  boundary says "format ascii" even in a binary mesh:
** it is text either way, and OpenFOAM reads both.  Patches with groups
** NULL get OpenFOAM's default inGroups (1(wall), 1(empty), ...), and the
** reader turns that default back into NULL.  Extras that the mesh lacks
** (cartesianGrid, cellParent, boundaryNormal, mergeMap, cellSeed,
** cartesianCells: cartcells_io.c) are removed from the directory, so a stale cellParent from an earlier
** mesh can never be read with a new one.
*/
#include "cartcells.h"
#include "dict.h"
#include "foam.h"
#include "io.h"
#include "mem.h"
#include "mesh.h"

#include <errno.h>
#include <math.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { F_POINTS, F_FACES, F_OWNER, F_NEIGHBOUR, F_BOUNDARY, F_CART, F_PARENT, F_BNORMAL, F_MERGEMAP, F_SEED, F_CARTCELLS, NFILES };

/* dictionaries, not bare lists: no blank line after the header */
#define IS_DICT(w) ((w) == F_CART || (w) == F_CARTCELLS)

#define IS_EXTRA(w) ((w) >= F_CART)

static const char *const file_names[NFILES] = {"points",   "faces",         "owner",     "neighbour",
                                               "boundary", "cartesianGrid", "cellParent",
                                               "boundaryNormal", "mergeMap", "cellSeed", "cartesianCells"};

/* ---- writing ---- */

/* Patch types whose own name OpenFOAM adds to inGroups (constraint types
   and wall), as blockMesh v1912 writes them. */
static int type_is_group(const char *type)
{
    static const char *const t[] = {"wall",       "empty",       "symmetryPlane", "symmetry",
                                    "cyclic",     "cyclicAMI",   "cyclicACMI",    "cyclicSlip",
                                    "wedge",      "processor",   "processorCyclic", NULL};
    for (int i = 0; t[i]; i++)
        if (strcmp(type, t[i]) == 0) return 1;
    return 0;
}

/* A patch or group name must be one word to survive the round trip. */
static int is_word(const char *s)
{
    if (!s || !*s) return 0;
    for (; *s; s++)
        if ((unsigned char)*s <= ' ' || strchr(";{}()[]\"'$#/\\", *s)) return 0;
    return 1;
}

static void put_key(Buf *b, const char *key)
{
    buf_printf(b, "        %-16s", key);
}

static void put_boundary(Buf *b, const Mesh *m)
{
    buf_printf(b, "%d\n(\n", m->npatches);
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        buf_printf(b, "    %s\n    {\n", pa->name);
        put_key(b, "type");
        buf_printf(b, "%s;\n", pa->type);
        if (pa->groups) {
            put_key(b, "inGroups");
            buf_printf(b, "%s;\n", pa->groups);
        } else if (type_is_group(pa->type)) {
            put_key(b, "inGroups");
            buf_printf(b, "1(%s);\n", pa->type);
        }
        put_key(b, "nFaces");
        buf_printf(b, "%d;\n", pa->size);
        put_key(b, "startFace");
        buf_printf(b, "%d;\n", pa->start);
        if (pa->neighbour) {
            if (strcmp(pa->type, "cyclic") == 0) {
                put_key(b, "matchTolerance");
                buf_puts(b, "0.0001;\n");
                put_key(b, "transform");
                buf_puts(b, "unknown;\n");
            }
            put_key(b, "neighbourPatch");
            buf_printf(b, "%s;\n", pa->neighbour);
        }
        buf_puts(b, "    }\n");
    }
    buf_puts(b, ")\n");
}

static void put_cart(Buf *b, const CartGrid *g)
{
    buf_printf(b, "%-16s(%d %d %d);\n", "n", g->n[0], g->n[1], g->n[2]);
    static const char axes[3][2] = {"x", "y", "z"};
    for (int k = 0; k < 3; k++) {
        buf_printf(b, "%-16s%d(", axes[k], g->n[k] + 1);
        for (int i = 0; i <= g->n[k]; i++) {
            if (i) buf_putc(b, ' ');
            foam_put_double(b, g->x[k][i], 0);
        }
        buf_puts(b, ");\n");
    }
}

static int has_file(const Mesh *m, int which)
{
    if (which == F_CART) return m->cart.n[0] > 0;
    if (which == F_PARENT) return m->cell_parent != NULL;
    if (which == F_BNORMAL) return m->boundary_normal != NULL;
    if (which == F_MERGEMAP) return m->merge_map != NULL;
    if (which == F_SEED) return m->cell_seed != NULL;
    if (which == F_CARTCELLS) return m->cartcells.n > 0;
    return 1;
}

/* Bytes of file `which` in binary, or a generous guess in ascii: the
   buffer is reserved once, so a big mesh is not copied while it grows. */
static size_t file_size_hint(const Mesh *m, int which, int binary)
{
    size_t np = (size_t)m->npoints, nf = (size_t)m->nfaces, ni = (size_t)m->ninternal;
    size_t nidx = m->face_off ? (size_t)m->face_off[nf] : 0;
    size_t sz = 0;
    switch (which) {
    case F_POINTS: sz = np * (binary ? 24 : 40); break;
    case F_FACES: sz = binary ? 4 * (nf + 1 + nidx) : 12 * nidx + 4 * nf; break;
    case F_OWNER: sz = nf * (binary ? 4 : 10); break;
    case F_NEIGHBOUR: sz = ni * (binary ? 4 : 10); break;
    case F_PARENT: sz = (size_t)m->ncells * (binary ? 4 : 10); break;
    case F_BNORMAL: sz = (nf - ni) * (binary ? 24 : 72); break;
    case F_MERGEMAP: sz = (size_t)m->nmerge_old * (binary ? 4 : 10); break;
    case F_SEED: sz = (size_t)m->ncells * (binary ? 24 : 72); break;
    case F_CARTCELLS: sz = cartcells_size_hint(m, binary); break;
    default: break;
    }
    return sz + 4096;
}

/* The big arrays of a binary file, left out of its assembled text: the
   file is text[0..at[0]), raw[0], text[at[0]..at[1]), raw[1], the rest
   of the text.  At most two (faceCompactList). */
typedef struct Holes {
    size_t at[2];
    IoPiece raw[2];
    int n;
} Holes;

/* The arrays can be written from memory as they are when the host's
   layout is the file's: little-endian, 32-bit int (foam.h). */
static int raw_is_file_layout(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1 && sizeof(int) == 4;
}

/* A binary list of n items of sz bytes at p, as foam_put_scalars and
   foam_put_labels write it ("N\n(" raw ")\n", an empty list "0\n"),
   with the raw bytes left as a hole in b. */
static void put_hole(Buf *b, Holes *h, const void *p, size_t n, size_t sz)
{
    buf_printf(b, "%zu\n", n);
    if (n == 0) return;
    buf_putc(b, '(');
    h->at[h->n] = b->n;
    h->raw[h->n].p = p;
    h->raw[h->n].n = n * sz;
    h->n++;
    buf_puts(b, ")\n");
}

static void put_labels(Buf *b, Holes *h, const int *v, size_t n, int bin)
{
    if (h)
        put_hole(b, h, v, n, sizeof(int));
    else
        foam_put_labels(b, v, n, bin);
}

/* Assembles file `which` of m into b (cleared first).  With h (binary
   only, and only when raw_is_file_layout) the big arrays are not copied
   into b but recorded in h. */
static void mesh_file(const Mesh *m, int which, int binary, Buf *b, Holes *h)
{
    static const char *const cls[NFILES] = {"vectorField", "faceList",   "labelList", "labelList",
                                            "polyBoundaryMesh", "dictionary", "labelList",
                                            "vectorField", "labelList", "vectorField", "dictionary"};
    char note[160];
    snprintf(note, sizeof note, "nPoints:%d  nCells:%d  nFaces:%d  nInternalFaces:%d", m->npoints,
             m->ncells, m->nfaces, m->ninternal);
    const char *c = which == F_FACES && binary ? "faceCompactList" : cls[which];
    /* the text-only files say "ascii" whatever the format: a reader that
       sees "binary" might take boundary's "N (" for a raw list */
    int bin = binary && which != F_CART && which != F_BOUNDARY;
    if (h) h->n = 0;
    if (!bin) h = NULL;
    buf_clear(b);
    buf_reserve(b, h ? 4096 : file_size_hint(m, which, bin));
    foam_header(b, c, "constant/polyMesh", file_names[which], bin,
                which == F_OWNER || which == F_NEIGHBOUR ? note : NULL);
    if (!IS_DICT(which) && which != F_BOUNDARY) buf_putc(b, '\n');
    switch (which) {
    case F_POINTS:
        if (h)
            put_hole(b, h, m->points, (size_t)m->npoints, 3 * sizeof(double));
        else
            foam_put_scalars(b, m->points, (size_t)m->npoints, 3, bin, 0);
        break;
    case F_FACES: {
        static const int no_faces[1] = {0};
        const int *off = m->face_off ? m->face_off : no_faces;
        if (h) {
            put_hole(b, h, off, (size_t)m->nfaces + 1, sizeof(int));
            buf_putc(b, '\n');
            put_hole(b, h, m->face_idx, (size_t)off[m->nfaces], sizeof(int));
        } else {
            foam_put_faces(b, off, m->face_idx, (size_t)m->nfaces, bin);
        }
        break;
    }
    case F_OWNER: put_labels(b, h, m->owner, (size_t)m->nfaces, bin); break;
    case F_NEIGHBOUR: put_labels(b, h, m->neighbour, (size_t)m->ninternal, bin); break;
    case F_BOUNDARY: put_boundary(b, m); break;
    case F_CART: put_cart(b, &m->cart); break;
    case F_PARENT: put_labels(b, h, m->cell_parent, (size_t)m->ncells, bin); break;
    case F_BNORMAL:
        if (h)
            put_hole(b, h, m->boundary_normal, (size_t)(m->nfaces - m->ninternal), 3 * sizeof(double));
        else
            foam_put_scalars(b, m->boundary_normal, (size_t)(m->nfaces - m->ninternal), 3, bin, 0);
        break;
    case F_MERGEMAP: put_labels(b, h, m->merge_map, (size_t)m->nmerge_old, bin); break;
    case F_SEED:
        if (h)
            put_hole(b, h, m->cell_seed, (size_t)m->ncells, 3 * sizeof(double));
        else
            foam_put_scalars(b, m->cell_seed, (size_t)m->ncells, 3, bin, 0);
        break;
    case F_CARTCELLS: cartcells_put(b, m, bin); break;
    }
    /* OpenFOAM leaves two blank lines after a list, one after boundary */
    if (which != F_BOUNDARY && !IS_DICT(which)) buf_putc(b, '\n');
    foam_footer(b);
}

/* The pieces of the file assembled in b with holes h; returns the count
   (at most 5) and the total size in *total. */
static int file_pieces(const Buf *b, const Holes *h, IoPiece pc[5], size_t *total)
{
    int np = 0;
    size_t from = 0;
    *total = b->n;
    for (int k = 0; h && k < h->n; k++) {
        pc[np].p = b->p + from;
        pc[np++].n = h->at[k] - from;
        pc[np++] = h->raw[k];
        from = h->at[k];
        *total += h->raw[k].n;
    }
    pc[np].p = b->p + from;
    pc[np++].n = b->n - from;
    return np;
}

/* What the writers rely on: sizes that index the arrays consistently and
   patch names that are single words. */
static int check_writable(const Mesh *m, Err *e)
{
    if (m->npoints < 0 || m->nfaces < 0 || m->ninternal < 0 || m->ninternal > m->nfaces || m->ncells < 0 ||
        m->npatches < 0)
        return err_set(e, NULL, 0, "mesh: inconsistent sizes, not written");
    if ((m->nfaces && (!m->face_off || !m->face_idx || !m->owner)) || (m->ninternal && !m->neighbour) ||
        (m->npoints && !m->points) || (m->npatches && !m->patches))
        return err_set(e, NULL, 0, "mesh: arrays missing, not written");
    if (m->face_off && m->face_off[0] != 0) return err_set(e, NULL, 0, "mesh: face offsets do not start at 0");
    for (int f = 0; m->face_off && f < m->nfaces; f++)
        if (m->face_off[f + 1] < m->face_off[f])
            return err_set(e, NULL, 0, "mesh: face %d has a negative point count", f);
    for (int p = 0; p < m->npatches; p++) {
        const Patch *pa = &m->patches[p];
        if (!is_word(pa->name) || !is_word(pa->type) || (pa->neighbour && !is_word(pa->neighbour)))
            return err_set(e, NULL, 0, "mesh: patch %d: name '%s', type '%s' must be single words", p,
                           pa->name ? pa->name : "", pa->type ? pa->type : "");
    }
    for (int k = 0; k < 3 && m->cart.n[0] > 0; k++)
        if (m->cart.n[k] <= 0 || !m->cart.x[k])
            return err_set(e, NULL, 0, "mesh: cartesian grid has %d cells along axis %d", m->cart.n[k], k);
    if (m->cartcells.n > 0 && (m->cart.n[0] <= 0 || (long)m->cart.n[0] * m->cart.n[1] * m->cart.n[2] != m->cartcells.n ||
                               !m->cartcells.parent_off))
        return err_set(e, NULL, 0, "mesh: %d Cartesian cells in cartesianCells do not fit the cartesian grid",
                       m->cartcells.n);
    return 0;
}

int mesh_write_stream(const Mesh *m, Buf *out, const MeshWriteOpts *o, Err *e)
{
    if (check_writable(m, e)) return -1;
    int binary = o && o->binary, gzip = o && o->gzip;
    Buf b, z;
    buf_init(&b);
    buf_init(&z);
    size_t total = 16;
    for (int w = 0; w < NFILES; w++)
        if (has_file(m, w)) total += file_size_hint(m, w, binary) + 64;
    buf_reserve(out, total);
    /* uncompressed binary files go from the mesh's arrays straight into
       out; gzip needs each file whole */
    Holes holes, *h = binary && !gzip && raw_is_file_layout() ? &holes : NULL;
    for (int w = 0; w < NFILES; w++) {
        if (!has_file(m, w)) continue;
        mesh_file(m, w, binary, &b, h);
        IoPiece pc[5];
        size_t size;
        int np = file_pieces(&b, h, pc, &size);
        if (gzip) {
            if (io_gzip(file_names[w], b.p, b.n, &z, e)) {
                buf_free(&b);
                buf_free(&z);
                return -1;
            }
            pc[0].p = z.p;
            pc[0].n = size = z.n;
            np = 1;
        }
        buf_printf(out, "@file %s%s %zu\n", file_names[w], gzip ? ".gz" : "", size);
        for (int k = 0; k < np; k++) buf_put(out, pc[k].p, pc[k].n);
    }
    buf_puts(out, "@end\n");
    buf_free(&b);
    buf_free(&z);
    return 0;
}

/* Removes dir/name and dir/name.gz if present (stale extras). */
static int remove_stale(const char *dir, const char *name, Err *e)
{
    char *p = io_join(dir, name);
    size_t l = strlen(p);
    char *gz = mem_alloc(l + 4);
    memcpy(gz, p, l);
    memcpy(gz + l, ".gz", 4);
    int rc = 0;
    if ((unlink(p) && errno != ENOENT) || (unlink(gz) && errno != ENOENT))
        rc = err_set(e, p, 0, "cannot remove stale file: %s", strerror(errno));
    free(p);
    free(gz);
    return rc;
}

int mesh_write(const Mesh *m, const char *dir, const MeshWriteOpts *o, Err *e)
{
    if (strcmp(dir, "-") == 0) {
        Buf s;
        buf_init(&s);
        int rc = mesh_write_stream(m, &s, o, e);
        if (!rc) rc = io_write_atomic("-", s.p, s.n, 0, e);
        buf_free(&s);
        return rc;
    }
    if (check_writable(m, e) || io_mkdir_p(dir, e)) return -1;
    int binary = o && o->binary;
    Buf b;
    buf_init(&b);
    /* binary: the big arrays are written from the mesh itself (holes), b
       holds only the text around them.  ascii: one buffer, sized for the
       largest file, serves them all: its pages are touched once rather
       than once per file */
    Holes holes, *h = binary && raw_is_file_layout() ? &holes : NULL;
    size_t big = 0;
    for (int w = 0; w < NFILES && !h; w++)
        if (has_file(m, w) && file_size_hint(m, w, binary) > big) big = file_size_hint(m, w, binary);
    buf_reserve(&b, big);
    int rc = 0;
    for (int w = 0; w < NFILES && !rc; w++) {
        if (!has_file(m, w)) {
            rc = remove_stale(dir, file_names[w], e);
            continue;
        }
        mesh_file(m, w, binary, &b, h);
        IoPiece pc[5];
        size_t size;
        int np = file_pieces(&b, h, pc, &size);
        char *path = io_join(dir, file_names[w]);
        rc = io_write_atomic_v(path, pc, np, o && o->gzip, e);
        free(path);
    }
    buf_free(&b);
    return rc;
}

/* ---- reading ---- */

/* One file's bytes (inside a stream, or owned after inflating, or read
   or mapped from a directory) and the name its messages carry. */
typedef struct Part {
    const char *p;
    size_t n;
    Buf own;
    IoMap file;
    char *name;
    int present;
} Part;

static void parts_free(Part *parts)
{
    for (int w = 0; w < NFILES; w++) {
        buf_free(&parts[w].own);
        io_unmap(&parts[w].file);
        free(parts[w].name);
    }
}

/* Big files are mapped rather than read (io_map_file): the parser copies
   the binary lists out of them anyway. */
static int load_dir(Part *parts, const char *dir, Err *e)
{
    for (int w = 0; w < NFILES; w++) {
        char *path = io_join(dir, file_names[w]);
        int optional = IS_EXTRA(w);
        int rc = 0;
        if (!optional || io_exists_gz(path)) {
            rc = io_map_file(path, &parts[w].file, &parts[w].name, e);
            parts[w].p = parts[w].file.p;
            parts[w].n = parts[w].file.n;
            parts[w].present = rc == 0;
        }
        free(path);
        if (rc) return -1;
    }
    return 0;
}

/* "@file <name> <nbytes>" (without the newline): name is one word of at
   most 63 characters, nbytes at most 15 digits. */
static int parse_record(const char *s, size_t ll, char name[64], size_t *nb)
{
    if (ll < 9 || memcmp(s, "@file ", 6) != 0) return -1;
    size_t i = 6, k = 0;
    while (i < ll && s[i] != ' ' && k < 63) name[k++] = s[i++];
    name[k] = '\0';
    if (k == 0 || i >= ll || s[i] != ' ') return -1;
    i++;
    size_t v = 0, nd = 0;
    for (; i < ll && s[i] >= '0' && s[i] <= '9' && nd < 15; i++, nd++) v = v * 10 + (size_t)(s[i] - '0');
    if (nd == 0 || i != ll) return -1;
    *nb = v;
    return 0;
}

/* Parses "@file <name> <nbytes>\n" records up to "@end\n". */
static int load_stream(Part *parts, const char *data, size_t n, const char *sname, Err *e)
{
    size_t at = 0;
    int line = 1;
    for (;;) {
        const char *nl = at < n ? memchr(data + at, '\n', n - at) : NULL;
        if (!nl) return err_set(e, sname, line, "mesh stream ends without '@end'");
        size_t ll = (size_t)(nl - (data + at));
        const char *s = data + at;
        if (ll == 4 && memcmp(s, "@end", 4) == 0) {
            at += 5;
            break;
        }
        char name[64];
        size_t nb;
        if (parse_record(s, ll, name, &nb))
            return err_set(e, sname, line, "expected '@file <name> <nbytes>' or '@end' in mesh stream, found '%.*s'",
                           (int)(ll < 60 ? ll : 60), s);
        at += ll + 1;
        line++;
        if (nb > n - at)
            return err_set(e, sname, line, "file '%s' in mesh stream: %zu bytes announced, %zu left", name, nb,
                           n - at);
        size_t nl2 = strlen(name);
        if (nl2 > 3 && strcmp(name + nl2 - 3, ".gz") == 0) name[nl2 - 3] = '\0';
        int w = 0;
        while (w < NFILES && strcmp(name, file_names[w]) != 0) w++;
        if (w < NFILES) {
            if (parts[w].present) return err_set(e, sname, line, "file '%s' appears twice in mesh stream", name);
            size_t len = strlen(sname) + strlen(name) + 2;
            parts[w].name = mem_alloc(len);
            snprintf(parts[w].name, len, "%s/%s", sname, name);
            parts[w].p = data + at;
            parts[w].n = (size_t)nb;
            parts[w].present = 1;
            if (nb >= 2 && (unsigned char)data[at] == 0x1f && (unsigned char)data[at + 1] == 0x8b) {
                if (io_gunzip(parts[w].name, data + at, (size_t)nb, &parts[w].own, e)) return -1;
                parts[w].p = parts[w].own.p;
                parts[w].n = parts[w].own.n;
            }
        }
        /* count the lines of the payload so later records report theirs */
        for (size_t k = at; k < at + nb; k++) line += data[k] == '\n';
        at += (size_t)nb;
    }
    for (; at < n; at++)
        if (data[at] != ' ' && data[at] != '\n' && data[at] != '\t' && data[at] != '\r')
            return err_set(e, sname, line, "data after '@end' in mesh stream");
    for (int w = 0; w < NFILES; w++)
        if (!parts[w].present && !IS_EXTRA(w))
            return err_set(e, sname, 0, "mesh stream has no file '%s'", file_names[w]);
    return 0;
}

/* The value nodes of a file's body (the list, or for a binary
   faceCompactList the two lists), the FoamFile header excluded. */
static int body(const Dict *d, const char *name, DictNode *const **vals, size_t *nvals, Err *e)
{
    for (size_t i = 0; i < d->n; i++) {
        const DictEntry *en = &d->entries[i];
        if (en->key && strcmp(en->key, "FoamFile") == 0) continue;
        if (en->dict || en->nvals == 0) break;
        *vals = en->vals;
        *nvals = en->nvals;
        return 0;
    }
    return err_set(e, name, 0, "no list found after the FoamFile header");
}

static int list_line(DictNode *const *vals)
{
    return vals[0]->line;
}

/* A size_t count that must fit the int-indexed arrays. */
static int fits_int(size_t n, const char *name, int line, Err *e)
{
    if (n > (size_t)INT_MAX - 1) return err_set(e, name, line, "list of %zu items is too long", n);
    return 0;
}

/* Big lists are taken over from the parser's node when it already holds
   them in the wanted flat form (the Dict is freed right after reading),
   which saves a copy of the largest arrays; otherwise the dict_node_*
   accessors convert. */
static int take_faces(DictNode *nd, int **off, int **idx, size_t *n, Err *e)
{
    if (nd->kind == DN_RAGGED && nd->off && nd->iv) {
        *off = nd->off;
        *idx = nd->iv;
        *n = nd->n;
        nd->off = nd->iv = NULL;
        nd->n = 0;
        return 0;
    }
    return dict_node_faces(nd, off, idx, n, e);
}

/* A coordinate written nan or inf (OpenFOAM writes them, and refuses
   them when reading: "expected scalar value, found word 'nan'"), named
   with its own line; without this the list would only be "not a list of
   3-tuples". */
static int nonfinite_item(const DictNode *nd, const char *name, const char *what, Err *e)
{
    size_t i;
    const DictNode *w = dict_node_nonfinite(nd, &i);
    if (!w) return 0;
    return err_set(e, name, w->line, "%s %zu: coordinate '%s' is not a finite number", what, i, w->text);
}

static int read_points(Mesh *m, const Dict *d, const char *name, Err *e)
{
    DictNode *const *v;
    size_t nv, n;
    if (body(d, name, &v, &nv, e)) return -1;
    if (nv != 1) return err_set(e, name, list_line(v), "expected one list of points, found %zu values", nv);
    if (nonfinite_item(v[0], name, "point", e)) return -1;
    if (dict_node_take_scalars(v[0], 3, &m->points, &n, e) || fits_int(n, name, list_line(v), e)) return -1;
    m->npoints = (int)n;
    return 0;
}

static int read_faces(Mesh *m, const Dict *d, const char *name, Err *e)
{
    DictNode *const *v;
    size_t nv, n;
    if (body(d, name, &v, &nv, e)) return -1;
    int line = list_line(v);
    if (nv == 1) {
        if (take_faces(v[0], &m->face_off, &m->face_idx, &n, e) || fits_int(n, name, line, e)) return -1;
    } else if (nv == 2) {
        /* faceCompactList: offsets (nfaces+1), then the flat point list */
        size_t no, ni;
        if (dict_node_take_labels(v[0], &m->face_off, &no, e) || dict_node_take_labels(v[1], &m->face_idx, &ni, e))
            return -1;
        if (fits_int(no, name, line, e) || fits_int(ni, name, line, e)) return -1;
        if (no == 0) {
            free(m->face_off);
            m->face_off = MEM_NEW(int, 1);
            no = 1;
        }
        n = no - 1;
        if (m->face_off[0] != 0) return err_set(e, name, line, "face offsets start at %d, not 0", m->face_off[0]);
        for (size_t f = 0; f < n; f++)
            if (m->face_off[f + 1] < m->face_off[f])
                return err_set(e, name, line, "face offsets decrease at face %zu", f);
        if ((size_t)m->face_off[n] != ni)
            return err_set(e, name, v[1]->line, "the offsets end at %d but the point list has %zu labels",
                           m->face_off[n], ni);
    } else {
        return err_set(e, name, line, "expected a face list, found %zu values", nv);
    }
    m->nfaces = (int)n;
    for (int f = 0; f < m->nfaces; f++) {
        int k = m->face_off[f + 1] - m->face_off[f];
        if (k < 3) return err_set(e, name, line, "face %d has %d points (at least 3 needed)", f, k);
        for (int i = m->face_off[f]; i < m->face_off[f + 1]; i++)
            if (m->face_idx[i] < 0 || m->face_idx[i] >= m->npoints)
                return err_set(e, name, line, "face %d uses point %d, but the points file has %d points", f,
                               m->face_idx[i], m->npoints);
    }
    return 0;
}

/* A label list of `want` items (want < 0: any length) with every label
   in [lo, hi]. */
static int read_labels(const Dict *d, const char *name, int **out, size_t *n, long want, int lo, int hi,
                       const char *what, Err *e)
{
    DictNode *const *v;
    size_t nv;
    if (body(d, name, &v, &nv, e)) return -1;
    int line = list_line(v);
    if (nv != 1) return err_set(e, name, line, "expected one list of labels, found %zu values", nv);
    if (dict_node_take_labels(v[0], out, n, e) || fits_int(*n, name, line, e)) return -1;
    if (want >= 0 && *n != (size_t)want)
        return err_set(e, name, line, "%zu labels, expected %ld (%s)", *n, want, what);
    for (size_t i = 0; i < *n; i++)
        if ((*out)[i] < lo || (*out)[i] > hi)
            return err_set(e, name, line, "label %zu is %d, outside %d..%d", i, (*out)[i], lo, hi);
    return 0;
}

static int read_owner_neighbour(Mesh *m, const Dict *dow, const char *now, const Dict *dnb, const char *nnb,
                                Err *e)
{
    size_t n;
    if (read_labels(dow, now, &m->owner, &n, m->nfaces, 0, INT_MAX - 1, "one per face", e)) return -1;
    if (read_labels(dnb, nnb, &m->neighbour, &n, -1, 0, INT_MAX - 1, "", e)) return -1;
    DictNode *const *v;
    size_t nv;
    body(dnb, nnb, &v, &nv, e);
    if (n > (size_t)m->nfaces)
        return err_set(e, nnb, list_line(v), "%zu neighbours for %d faces (at most one per face)", n, m->nfaces);
    m->ninternal = (int)n;
    int maxc = -1;
    for (int f = 0; f < m->nfaces; f++)
        if (m->owner[f] > maxc) maxc = m->owner[f];
    for (int f = 0; f < m->ninternal; f++)
        if (m->neighbour[f] > maxc) maxc = m->neighbour[f];
    /* a cell label beyond the number of face sides leaves cells without
       faces; refusing it also bounds every per-cell allocation by the
       input size */
    if ((long)maxc >= (long)m->nfaces + m->ninternal)
        return err_set(e, now, 0, "cell label %d, but %d faces can bound at most %ld cells (see also %s)", maxc,
                       m->nfaces, ((long)m->nfaces + m->ninternal) / 4, nnb);
    m->ncells = maxc + 1;
    return 0;
}

/* inGroups as text "N(a b c)" from a list of words. */
static char *groups_text(const DictNode *nd, const char *name, int line, Err *e)
{
    if (nd->kind != DN_LIST) {
        err_set(e, name, line, "inGroups: expected a list of words, found %s", dict_node_kind_name(nd));
        return NULL;
    }
    Buf b;
    buf_init(&b);
    buf_printf(&b, "%zu(", nd->n);
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *it = nd->items[i];
        if ((it->kind != DN_WORD && it->kind != DN_STRING) || !is_word(it->text)) {
            buf_free(&b);
            err_set(e, name, it->line, "inGroups: expected a word, found %s", dict_node_kind_name(it));
            return NULL;
        }
        if (i) buf_putc(&b, ' ');
        buf_puts(&b, it->text);
    }
    buf_putc(&b, ')');
    return b.p;
}

static int read_patch(Patch *pa, const char *pname, const Dict *pd, const char *name, Err *e)
{
    const char *type, *nb;
    pa->name = mem_strdup(pname);
    if (!is_word(pname)) return err_set(e, name, pd->line, "bad patch name '%s'", pname);
    if (dict_word(pd, "type", &type, e) || dict_label(pd, "nFaces", &pa->size, e) ||
        dict_label(pd, "startFace", &pa->start, e))
        return -1;
    pa->type = mem_strdup(type);
    if (!is_word(type)) return err_set(e, name, pd->line, "patch '%s': bad type '%s'", pname, type);
    const DictEntry *g = dict_find(pd, "inGroups");
    if (g) {
        const DictNode *nd = dict_entry_value(g, e);
        if (!nd || !(pa->groups = groups_text(nd, name, g->line, e))) return -1;
        /* the default groups read back as NULL, so that they follow the
           type if a tool changes it */
        char def[300];
        snprintf(def, sizeof def, "1(%s)", type);
        if ((type_is_group(type) && strcmp(pa->groups, def) == 0) || strcmp(pa->groups, "0()") == 0) {
            free(pa->groups);
            pa->groups = NULL;
        }
    }
    if (dict_find(pd, "neighbourPatch")) {
        if (dict_word(pd, "neighbourPatch", &nb, e)) return -1;
        pa->neighbour = mem_strdup(nb);
    }
    return 0;
}

/* The patch name of the dictionary item i of the boundary list: either
   a word item just before it, or the name the parser gave the dictionary
   (its scoped name, whose last component is the patch name). */
static const char *patch_name(const DictNode *l, size_t i)
{
    if (i > 0 && (l->items[i - 1]->kind == DN_WORD || l->items[i - 1]->kind == DN_STRING))
        return l->items[i - 1]->text;
    const char *nm = l->items[i]->dict->name;
    const char *dot = nm ? strrchr(nm, '.') : NULL;
    return dot ? dot + 1 : nm ? nm : "";
}

static int read_boundary(Mesh *m, const Dict *d, const char *name, Err *e)
{
    DictNode *const *v;
    size_t nv;
    if (body(d, name, &v, &nv, e)) return -1;
    int line = list_line(v);
    if (nv != 1 || (v[0]->kind != DN_LIST && dict_node_len(v[0]) != 0))
        return err_set(e, name, line, "expected a list of patches 'N ( name { ... } ... )'");
    const DictNode *l = v[0];
    size_t nl = v[0]->kind == DN_LIST ? l->n : 0;
    /* items: patch dictionaries, each preceded by its name as a word */
    size_t np = 0;
    for (size_t i = 0; i < nl; i++) {
        const DictNode *it = l->items[i];
        if (it->kind == DN_DICT)
            np++;
        else if (!((it->kind == DN_WORD || it->kind == DN_STRING) && i + 1 < nl && l->items[i + 1]->kind == DN_DICT))
            return err_set(e, name, it->line, "expected a patch name and its dictionary, found %s",
                           dict_node_kind_name(it));
    }
    if (fits_int(np, name, line, e)) return -1;
    m->patches = MEM_NEW(Patch, np);
    m->npatches = (int)np;
    int next = m->ninternal;
    size_t p = 0;
    for (size_t i = 0; i < nl; i++) {
        const DictNode *nd = l->items[i];
        if (nd->kind != DN_DICT) continue;
        Patch *pa = &m->patches[p];
        if (read_patch(pa, patch_name(l, i), nd->dict, name, e)) return -1;
        if (pa->size < 0) return err_set(e, name, nd->line, "patch '%s' has nFaces %d", pa->name, pa->size);
        if (pa->start != next)
            return err_set(e, name, nd->line, "patch '%s' has startFace %d, expected %d (after %s)", pa->name,
                           pa->start, next, p ? "the previous patch" : "the internal faces");
        if (pa->size > m->nfaces - next)
            return err_set(e, name, nd->line, "patch '%s' ends at face %ld, past the %d faces", pa->name,
                           (long)pa->start + pa->size - 1, m->nfaces);
        next += pa->size;
        p++;
    }
    if (next != m->nfaces)
        return err_set(e, name, line, "the patches cover faces up to %d, but there are %d faces", next - 1,
                       m->nfaces);
    return 0;
}

static int read_cart(Mesh *m, const Dict *d, const char *name, Err *e)
{
    CartGrid *g = &m->cart;
    const DictEntry *en = dict_find(d, "n");
    if (!en) return err_set(e, name, 0, "keyword 'n' missing");
    const DictNode *nd = dict_entry_value(en, e);
    int *n;
    size_t k3;
    if (!nd || dict_node_labels(nd, &n, &k3, e)) return -1;
    if (k3 != 3 || n[0] <= 0 || n[1] <= 0 || n[2] <= 0) {
        free(n);
        return err_set(e, name, en->line, "n: expected three positive cell counts (nx ny nz)");
    }
    static const char *const axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; k++) {
        const DictEntry *ax = dict_find(d, axes[k]);
        size_t len;
        if (!ax) {
            free(n);
            return err_set(e, name, 0, "keyword '%s' missing", axes[k]);
        }
        const DictNode *an = dict_entry_value(ax, e);
        if (!an || dict_node_scalars(an, 1, &g->x[k], &len, e)) {
            free(n);
            return -1;
        }
        g->n[k] = n[k];
        if (len != (size_t)n[k] + 1) {
            free(n);
            return err_set(e, name, ax->line, "%s: %zu coordinates for %d cells", axes[k], len, g->n[k]);
        }
        for (int i = 0; i < g->n[k]; i++)
            if (!(g->x[k][i] < g->x[k][i + 1])) {
                free(n);
                return err_set(e, name, ax->line, "%s: coordinates not increasing at %d", axes[k], i);
            }
    }
    free(n);
    return 0;
}

static int read_parent(Mesh *m, const Dict *d, const char *name, Err *e)
{
    long ncart = (long)m->cart.n[0] * m->cart.n[1] * m->cart.n[2];
    int hi = m->cart.n[0] > 0 && ncart <= INT_MAX ? (int)(ncart - 1) : INT_MAX - 1;
    size_t n;
    return read_labels(d, name, &m->cell_parent, &n, m->ncells, -1, hi, "one per cell", e);
}

static int read_bnormal(Mesh *m, const Dict *d, const char *name, Err *e)
{
    DictNode *const *v;
    size_t nv, n;
    if (body(d, name, &v, &nv, e)) return -1;
    if (nv != 1) return err_set(e, name, list_line(v), "expected one list of vectors, found %zu values", nv);
    if (nonfinite_item(v[0], name, "normal", e) || dict_node_take_scalars(v[0], 3, &m->boundary_normal, &n, e))
        return -1;
    if (n != (size_t)(m->nfaces - m->ninternal))
        return err_set(e, name, list_line(v), "%zu normals for %d boundary faces", n, m->nfaces - m->ninternal);
    for (size_t i = 0; i < 3 * n; i++)
        if (!isfinite(m->boundary_normal[i])) return err_set(e, name, list_line(v), "normal %zu is not finite", i / 3);
    return 0;
}

static int read_seed(Mesh *m, const Dict *d, const char *name, Err *e)
{
    DictNode *const *v;
    size_t nv, n;
    if (body(d, name, &v, &nv, e)) return -1;
    if (nv != 1) return err_set(e, name, list_line(v), "expected one list of vectors, found %zu values", nv);
    if (nonfinite_item(v[0], name, "seed", e) || dict_node_take_scalars(v[0], 3, &m->cell_seed, &n, e)) return -1;
    if (n != (size_t)m->ncells) return err_set(e, name, list_line(v), "%zu seeds for %d cells", n, m->ncells);
    for (size_t i = 0; i < 3 * n; i++)
        if (!isfinite(m->cell_seed[i])) return err_set(e, name, list_line(v), "seed %zu is not finite", i / 3);
    return 0;
}

/* The map's cells before merging are not known here; every entry must
   name a cell of this mesh. */
static int read_mergemap(Mesh *m, const Dict *d, const char *name, Err *e)
{
    size_t n;
    if (read_labels(d, name, &m->merge_map, &n, -1, 0, m->ncells - 1, "", e)) return -1;
    m->nmerge_old = (int)n;
    return 0;
}

/* The FoamFile class of file `which`, as OpenFOAM's readStream checks it:
   the file's own class, or "dictionary", which OpenFOAM accepts for any
   file.  A file without a header is read as before (older Kiesel
   pipelines and hand-made test grids have none), but a header without a
   class is refused, as OpenFOAM refuses it. */
static int check_class(const Dict *d, int which, const char *name, Err *e)
{
    static const char *const want[NFILES] = {"vectorField", "faceList", "labelList", "labelList",
                                             "polyBoundaryMesh", "dictionary", "labelList",
                                             "vectorField", "labelList", "vectorField", "dictionary"};
    const DictEntry *h = dict_find(d, "FoamFile");
    if (!h || !h->dict) return 0;
    const DictEntry *ce = dict_find(h->dict, "class");
    const char *cls = dict_header_class(d), *w = want[which];
    if (!cls)
        return err_set(e, name, h->line, "FoamFile header has no class (expected %s%s)", w,
                       which == F_FACES ? " or faceCompactList" : "");
    if (!strcmp(cls, w) || !strcmp(cls, "dictionary") || (which == F_FACES && !strcmp(cls, "faceCompactList")))
        return 0;
    return err_set(e, name, ce ? ce->line : h->line, "unexpected class %s in the FoamFile header, expected %s%s", cls,
                   w, which == F_FACES ? " or faceCompactList" : "");
}

static int build_mesh(Mesh *m, Part *parts, Err *e)
{
    Dict *d[NFILES] = {0};
    int rc = 0;
    for (int w = 0; w < NFILES && !rc; w++) {
        if (!parts[w].present) continue;
        d[w] = dict_parse(parts[w].p, parts[w].n, parts[w].name, e);
        rc = !d[w] || check_class(d[w], w, parts[w].name, e) ? -1 : 0;
    }
    if (!rc) rc = read_points(m, d[F_POINTS], parts[F_POINTS].name, e);
    if (!rc) rc = read_faces(m, d[F_FACES], parts[F_FACES].name, e);
    if (!rc)
        rc = read_owner_neighbour(m, d[F_OWNER], parts[F_OWNER].name, d[F_NEIGHBOUR], parts[F_NEIGHBOUR].name, e);
    if (!rc) rc = read_boundary(m, d[F_BOUNDARY], parts[F_BOUNDARY].name, e);
    if (!rc && d[F_CART]) rc = read_cart(m, d[F_CART], parts[F_CART].name, e);
    if (!rc && d[F_PARENT]) rc = read_parent(m, d[F_PARENT], parts[F_PARENT].name, e);
    if (!rc && d[F_BNORMAL]) rc = read_bnormal(m, d[F_BNORMAL], parts[F_BNORMAL].name, e);
    if (!rc && d[F_MERGEMAP]) rc = read_mergemap(m, d[F_MERGEMAP], parts[F_MERGEMAP].name, e);
    if (!rc && d[F_SEED]) rc = read_seed(m, d[F_SEED], parts[F_SEED].name, e);
    if (!rc && d[F_CARTCELLS]) rc = cartcells_read(m, d[F_CARTCELLS], parts[F_CARTCELLS].name, e);
    for (int w = 0; w < NFILES; w++)
        if (d[w]) dict_free(d[w]);
    return rc;
}

int mesh_read_stream(Mesh *m, const char *data, size_t n, const char *name, Err *e)
{
    Part parts[NFILES];
    memset(parts, 0, sizeof parts);
    mesh_init(m);
    int rc = load_stream(parts, data, n, name, e);
    if (!rc) rc = build_mesh(m, parts, e);
    parts_free(parts);
    if (rc) mesh_free(m);
    return rc;
}

int mesh_read(Mesh *m, const char *dir, Err *e)
{
    if (strcmp(dir, "-") == 0) {
        Buf s;
        buf_init(&s);
        int rc = io_read_file("-", &s, NULL, e);
        if (!rc) rc = mesh_read_stream(m, s.p, s.n, "<stdin>", e);
        buf_free(&s);
        return rc;
    }
    Part parts[NFILES];
    memset(parts, 0, sizeof parts);
    mesh_init(m);
    int rc = load_dir(parts, dir, e);
    if (!rc) rc = build_mesh(m, parts, e);
    parts_free(parts);
    if (rc) mesh_free(m);
    return rc;
}
