/*
** cad.c: CAD and mesh files through gmsh's C API.  See cad.h for the
** contract.
**
** gmsh state.  gmsh is one process-wide library: its initialisation, its
** options and its list of models are global.  This file is the only
** place that touches it, and keeps the two pieces of state that follow
** from that: the number of live Cad objects (gmsh is initialised when it
** goes 0 -> 1 and finalised when it goes back to 0) and a serial number
** that gives every Cad a model name of its own ("kiesel-cad-N").  Every
** public function selects its model first, so interleaved Cads never see
** each other's entities.
**
** Errors.  gmsh's C API reports failures through `ierr` when the option
** General.AbortOnError is 2 (its default under the API: errors become
** exceptions that the C wrapper catches).  That is what we use everywhere
** except around gmshMerge: an exception thrown from inside the .geo
** parser skips the parser's clean-up and leaves the rest of the bad file
** in the lexer's buffer, so every later .geo parse in the process fails
** ("line 0: syntax error").  So merges run with AbortOnError 0, which lets
** the parser recover, and their errors are collected from gmsh's logger
** instead.  General.Terminal 0 keeps gmsh off stdout/stderr; verbosity 1
** keeps errors (and only errors) flowing to the logger.  OpenCASCADE's
** STEP reader prints its own diagnostics to stdout whatever gmsh's
** options say, so during reading and meshing descriptors 1 and 2 point to
** a temporary file, whose first line joins the error message.
**
** Options.  gmsh's options are global too, and a .geo file may set mesh
** options (Mesh.RecombineAll, Mesh.ElementOrder, ...).  The ones that
** shape the triangulation are reset to gmsh's defaults before every file
** is read, so one file's settings never leak into the next Cad.
**
** Triangulation.  Surface entities (dimension 2) that have no elements
** are meshed by gmsh with a uniform target size (Mesh.MeshSizeMin = Max =
** size, so the result does not depend on characteristic lengths written
** for other purposes in the file); entities that carry elements (STL,
** MSH) are taken as they are.  Triangles of any order contribute their
** three corner nodes, quadrangles are split along their shorter diagonal.
** Points are welded by gmsh node tag: two surfaces share a node exactly
** where gmsh's topology says they touch, so a closed CAD solid gives a
** closed TriSurf.  gmsh orients each surface by its own parametrisation,
** so orientations need not agree; trisurf_orient makes them consistent
** and outward when the surface is closed and manifold.
**
** Exact normals.  cad_normal projects x on the entity (gmshModelGet-
** ClosestPoint, an OpenCASCADE projection for STEP/BREP/OCC .geo models),
** inverts the parametrisation at the projected point (gmsh 4.8 returns
** no parameters from the projection) and evaluates the normal there.
** The inversion works inside the face's parameter range (to a small
** tolerance), which holds for points of the face's own triangles (the
** tests check every triangle of their models); farther outside a trimmed
** face it fails and the functions return 0, as they do for discrete
** entities (gmsh type
** "Discrete surface": STL, MSH), which have no parametrisation at all and
** are recognised once at open without asking gmsh each time.
*/
#include "cad.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gmshc.h>

#include "mem.h"

struct Cad {
    char model[40];    /* this Cad's gmsh model name */
    int nsurf;
    int *surf;         /* surface entity tags, ascending */
    char *exact;       /* per surf entry: has a parametrisation */
};

static int cad_nopen;          /* live Cad objects */
static unsigned cad_serial;    /* model names already handed out */

/* Copies gmsh's text into dst with control and non-ASCII bytes (a
   binary file's name field in an STL message) replaced by '?'. */
static void clean(char *dst, size_t n, const char *src)
{
    size_t k = 0;
    for (; src && src[k] && k + 1 < n; k++)
        dst[k] = (unsigned char)src[k] < 32 || (unsigned char)src[k] > 126 ? '?' : src[k];
    if (n) dst[k] = 0;
}

/* Copies gmsh's last error text into buf. */
static void last_error(char *buf, size_t n)
{
    char *m = NULL;
    int ierr = 0;
    gmshLoggerGetLastError(&m, &ierr);
    clean(buf, n, m && *m ? m : "unknown gmsh error");
    gmshFree(m);
}

static int gmsh_start(Err *e)
{
    int ierr = 0;
    if (cad_nopen++ > 0) return 0;
    gmshInitialize(0, NULL, 0, &ierr);
    if (!ierr) gmshOptionSetNumber("General.Terminal", 0, &ierr);
    if (!ierr) gmshOptionSetNumber("General.Verbosity", 1, &ierr);
    if (!ierr) gmshOptionSetNumber("General.AbortOnError", 2, &ierr);
    if (ierr) {
        cad_nopen--;
        return err_set(e, NULL, 0, "gmsh could not be initialised");
    }
    return 0;
}

static void gmsh_stop(void)
{
    int ierr = 0;
    if (--cad_nopen == 0) gmshFinalize(&ierr);
}

static int select_model(const Cad *c)
{
    int ierr = 0;
    gmshModelSetCurrent(c->model, &ierr);
    return ierr ? -1 : 0;
}

/* OpenCASCADE writes some diagnostics (the STEP reader's syntax errors)
   straight to stdout.  While a gmsh call that may reach it runs, file
   descriptors 1 and 2 point to a temporary file; the first line caught
   becomes part of the error message. */
typedef struct Quiet {
    FILE *tmp;
    int saved[2];
} Quiet;

static void quiet_begin(Quiet *q)
{
    fflush(NULL); /* every stream, stdout and stderr among them */
    q->saved[0] = q->saved[1] = -1;
    q->tmp = tmpfile();
    if (!q->tmp) return;
    for (int k = 0; k < 2; k++) {
        q->saved[k] = dup(k + 1);
        if (q->saved[k] >= 0) dup2(fileno(q->tmp), k + 1);
    }
}

/* Restores the descriptors; text gets the first non-blank line caught,
   without terminal colour codes and decoration. */
static void quiet_end(Quiet *q, char *text, size_t n)
{
    text[0] = 0;
    if (!q->tmp) return;
    fflush(NULL);
    for (int k = 0; k < 2; k++)
        if (q->saved[k] >= 0) {
            dup2(q->saved[k], k + 1);
            close(q->saved[k]);
        }
    rewind(q->tmp);
    size_t len = 0;
    int c, esc = 0;
    while ((c = getc(q->tmp)) != EOF && len + 1 < n) {
        if (c == '\033') esc = 1;
        else if (esc) esc = !(c == 'm');
        else if (c == '\n' && len > 0) break;
        else if (c != '*' && c != '\n' && c != '\r' && !(c == ' ' && len == 0))
            text[len++] = (char)c;
    }
    while (len > 0 && text[len - 1] == ' ') len--;
    text[len] = 0;
    fclose(q->tmp);
}

/* The first error line of gmsh's log, or NULL. */
static const char *log_error(char **log, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (strncmp(log[i], "Error: ", 7) == 0) return log[i] + 7;
    return NULL;
}

/* Mesh options a .geo file may change; they are global in gmsh, so they
   are reset to gmsh's defaults before every file is read, so that one
   file's settings never leak into the next Cad (the file itself may still
   set them). */
static const struct {
    const char *name;
    double value;
} mesh_defaults[] = {
    {"Mesh.ElementOrder", 1},      {"Mesh.RecombineAll", 0},
    {"Mesh.Algorithm", 6},         {"Mesh.MeshSizeFactor", 1},
    {"Mesh.MeshSizeFromPoints", 1}, {"Mesh.MeshSizeFromCurvature", 0},
    {"Mesh.MeshSizeExtendFromBoundary", 1},
};

static void reset_options(void)
{
    int ierr = 0;
    for (size_t i = 0; i < sizeof mesh_defaults / sizeof *mesh_defaults; i++)
        gmshOptionSetNumber(mesh_defaults[i].name, mesh_defaults[i].value, &ierr);
}

/* Merges path into the current model (see the top comment for why the
   errors come from the logger here). */
static int merge_file(const char *path, Err *e)
{
    int ierr = 0, rc = 0;
    char **log = NULL, said[512];
    size_t nlog = 0;
    Quiet q;
    reset_options();
    gmshOptionSetNumber("General.AbortOnError", 0, &ierr);
    gmshLoggerStart(&ierr);
    quiet_begin(&q);
    gmshMerge(path, &ierr);
    quiet_end(&q, said, sizeof said);
    int merge_ierr = ierr;
    gmshLoggerGet(&log, &nlog, &ierr);
    gmshLoggerStop(&ierr);
    gmshOptionSetNumber("General.AbortOnError", 2, &ierr);
    const char *msg = log_error(log, nlog);
    if (msg || merge_ierr) {
        char text[ERR_MSG_MAX / 2];
        clean(text, sizeof text, msg ? msg : "unknown gmsh error");
        clean(said, sizeof said, said);
        rc = err_set(e, path, 0, "gmsh could not read it: %s%s%s%s", text, said[0] ? " (" : "",
                     said, said[0] ? ")" : "");
    }
    for (size_t i = 0; i < nlog; i++) gmshFree(log[i]);
    gmshFree(log);
    return rc;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Lists the surface entities and whether each has a parametrisation. */
static int list_surfaces(Cad *c, const char *path, Err *e)
{
    int *dt = NULL, ierr = 0;
    size_t n = 0;
    gmshModelGetEntities(&dt, &n, 2, &ierr);
    if (ierr || n == 0) {
        gmshFree(dt);
        return err_set(e, path, 0, "no surfaces in the model");
    }
    c->nsurf = (int)(n / 2);
    c->surf = MEM_NEW(int, c->nsurf);
    c->exact = MEM_NEW(char, c->nsurf);
    for (int i = 0; i < c->nsurf; i++) c->surf[i] = dt[2 * i + 1];
    gmshFree(dt);
    qsort(c->surf, (size_t)c->nsurf, sizeof *c->surf, cmp_int);
    for (int i = 0; i < c->nsurf; i++) {
        char *type = NULL;
        gmshModelGetType(2, c->surf[i], &type, &ierr);
        c->exact[i] = !ierr && type && !strstr(type, "Discrete");
        gmshFree(type);
    }
    return 0;
}

static int has_elements(int tag)
{
    int *types = NULL, ierr = 0;
    size_t n = 0;
    gmshModelMeshGetElementTypes(&types, &n, 2, tag, &ierr);
    gmshFree(types);
    return !ierr && n > 0;
}

/* Generates the 2-D mesh when some surface has none. */
static int mesh_surfaces(const Cad *c, const char *path, double size, Err *e)
{
    int need = 0, ierr = 0;
    for (int i = 0; i < c->nsurf && !need; i++) need = !has_elements(c->surf[i]);
    if (!need) return 0;
    if (!(size > 0)) {
        double lo[3], hi[3];
        gmshModelGetBoundingBox(-1, -1, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2], &ierr);
        double d = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                        (hi[2] - lo[2]) * (hi[2] - lo[2]));
        if (ierr || !(d > 0) || !isfinite(d))
            return err_set(e, path, 0, "the model has no finite bounding box");
        size = d / 50;
    }
    char said[512] = "";
    gmshOptionSetNumber("Mesh.MeshSizeMax", size, &ierr);
    if (!ierr) gmshOptionSetNumber("Mesh.MeshSizeMin", size, &ierr);
    if (!ierr) {
        Quiet q;
        quiet_begin(&q);
        gmshModelMeshGenerate(2, &ierr);
        quiet_end(&q, said, sizeof said);
        clean(said, sizeof said, said);
    }
    if (ierr) {
        char msg[ERR_MSG_MAX / 2];
        last_error(msg, sizeof msg);
        return err_set(e, path, 0, "gmsh could not mesh the surfaces: %s%s%s%s", msg,
                       said[0] ? " (" : "", said, said[0] ? ")" : "");
    }
    return 0;
}

/* Surface elements as gmsh node tags: triangles (fourth node 0, which
   is no gmsh tag) and quadrangles, with their entity tags. */
typedef struct Soup {
    size_t *node;      /* 4 per element */
    int *tag;
    size_t n, ntris, cap_node, cap_tag;
} Soup;

static void soup_add(Soup *s, const size_t *v, int nv, int tag)
{
    mem_grow((void **)&s->node, &s->cap_node, 4 * (s->n + 1), sizeof *s->node);
    mem_grow((void **)&s->tag, &s->cap_tag, s->n + 1, sizeof *s->tag);
    for (int k = 0; k < 4; k++) s->node[4 * s->n + k] = k < nv ? v[k] : 0;
    s->tag[s->n++] = tag;
    s->ntris += (size_t)nv - 2;
}

/* Adds the elements of one type on surface `tag` by their corner nodes
   (gmsh lists the primary nodes first, in cyclic order). */
static int add_elements(Soup *s, int type, int tag, const char *path, Err *e)
{
    char *name = NULL;
    double *local = NULL;
    size_t nlocal = 0, *etags = NULL, ne = 0, *nodes = NULL, nn = 0;
    int dim, order, nnodes, nprimary, ierr = 0, rc = 0;
    gmshModelMeshGetElementProperties(type, &name, &dim, &order, &nnodes, &local, &nlocal,
                                      &nprimary, &ierr);
    if (!ierr) gmshModelMeshGetElementsByType(type, &etags, &ne, &nodes, &nn, tag, 0, 1, &ierr);
    if (ierr || (nprimary != 3 && nprimary != 4) || nnodes < nprimary || nn != ne * (size_t)nnodes)
        rc = err_set(e, path, 0, "surface %d: unsupported element type %d (%s)", tag, type,
                     name ? name : "?");
    for (size_t k = 0; k < ne && !rc; k++) soup_add(s, nodes + k * (size_t)nnodes, nprimary, tag);
    gmshFree(name);
    gmshFree(local);
    gmshFree(etags);
    gmshFree(nodes);
    return rc;
}

static int collect(const Cad *c, Soup *s, const char *path, Err *e)
{
    for (int i = 0; i < c->nsurf; i++) {
        int *types = NULL, ierr = 0;
        size_t nt = 0;
        gmshModelMeshGetElementTypes(&types, &nt, 2, c->surf[i], &ierr);
        if (ierr) nt = 0;
        int rc = ierr ? err_set(e, path, 0, "surface %d: gmsh could not list its elements",
                                c->surf[i])
                      : 0;
        for (size_t k = 0; k < nt && !rc; k++) rc = add_elements(s, types[k], c->surf[i], path, e);
        gmshFree(types);
        if (rc) return -1;
    }
    if (s->n == 0) return err_set(e, path, 0, "no surface triangles in the model");
    if (s->ntris > (size_t)INT_MAX / 3)
        return err_set(e, path, 0, "too many triangles (%zu)", s->ntris);
    return 0;
}

/* gmsh node tag with its position in gmsh's node arrays. */
typedef struct NodeRef {
    size_t tag, at;
} NodeRef;

static int cmp_noderef(const void *a, const void *b)
{
    size_t x = ((const NodeRef *)a)->tag, y = ((const NodeRef *)b)->tag;
    return (x > y) - (x < y);
}

/* Turns the soup's node tags into point indices (corner[k], -1 for an
   absent fourth node) and fills s->points with the nodes used, in the
   order first met. */
static int map_nodes(const Soup *soup, int *corner, TriSurf *s, const char *path, Err *e)
{
    size_t *tags = NULL, ntags = 0, ncoord = 0, npar = 0;
    double *coord = NULL, *par = NULL;
    int ierr = 0, rc = 0;
    gmshModelMeshGetNodes(&tags, &ntags, &coord, &ncoord, &par, &npar, -1, -1, 0, 0, &ierr);
    if (ierr || ncoord != 3 * ntags || ntags == 0 || ntags > (size_t)INT_MAX) {
        rc = err_set(e, path, 0, "gmsh could not list the mesh nodes");
        goto out;
    }
    NodeRef *ref = MEM_NEW(NodeRef, ntags);
    for (size_t i = 0; i < ntags; i++) ref[i] = (NodeRef){tags[i], i};
    qsort(ref, ntags, sizeof *ref, cmp_noderef);
    int *index = MEM_NEW(int, ntags);   /* sorted position -> point, -1 unused */
    for (size_t i = 0; i < ntags; i++) index[i] = -1;
    s->points = MEM_NEW(double, 3 * ntags);
    for (size_t k = 0; k < 4 * soup->n && !rc; k++) {
        NodeRef key = {soup->node[k], 0};
        NodeRef *r = key.tag ? bsearch(&key, ref, ntags, sizeof *ref, cmp_noderef) : NULL;
        corner[k] = -1;
        if (!key.tag) continue;
        if (!r) {
            rc = err_set(e, path, 0, "element node %zu has no coordinates", key.tag);
            break;
        }
        size_t pos = (size_t)(r - ref);
        if (index[pos] < 0) {
            index[pos] = s->npoints;
            memcpy(s->points + 3 * s->npoints++, coord + 3 * r->at, 3 * sizeof(double));
        }
        corner[k] = index[pos];
    }
    free(index);
    free(ref);
out:
    gmshFree(tags);
    gmshFree(coord);
    gmshFree(par);
    return rc;
}

static double dist2(const double *p, int a, int b)
{
    double d = 0;
    for (int k = 0; k < 3; k++) d += (p[3 * a + k] - p[3 * b + k]) * (p[3 * a + k] - p[3 * b + k]);
    return d;
}

static void add_tri(TriSurf *s, int a, int b, int d, int tag)
{
    s->tris[3 * s->ntris] = a;
    s->tris[3 * s->ntris + 1] = b;
    s->tris[3 * s->ntris + 2] = d;
    s->tag[s->ntris++] = tag;
}

/* Fills s from the soup; quadrangles are split along their shorter
   diagonal (the better pair of triangles for a warped quadrangle). */
static int weld(const Soup *soup, TriSurf *s, const char *path, Err *e)
{
    int *v = MEM_NEW(int, 4 * soup->n);
    int rc = map_nodes(soup, v, s, path, e);
    if (!rc) {
        s->tris = MEM_NEW(int, 3 * soup->ntris);
        s->tag = MEM_NEW(int, soup->ntris);
    }
    for (size_t i = 0; i < soup->n && !rc; i++) {
        const int *c = v + 4 * i;
        int tag = soup->tag[i];
        if (c[3] < 0) {
            add_tri(s, c[0], c[1], c[2], tag);
        } else if (dist2(s->points, c[0], c[2]) <= dist2(s->points, c[1], c[3])) {
            add_tri(s, c[0], c[1], c[2], tag);
            add_tri(s, c[0], c[2], c[3], tag);
        } else {
            add_tri(s, c[0], c[1], c[3], tag);
            add_tri(s, c[1], c[2], c[3], tag);
        }
    }
    free(v);
    return rc;
}

/* Consistent outward orientation, when the surface bounds a solid. */
static void orient(TriSurf *s)
{
    TriTopo t;
    trisurf_check(s, &t);
    if (t.nopen == 0 && t.nnonmanifold == 0) trisurf_orient(s);
}

static int load(Cad *c, const char *path, double size, TriSurf *s, Err *e)
{
    int ierr = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return err_set(e, path, 0, "cannot open: %s", strerror(errno));
    fclose(f);
    snprintf(c->model, sizeof c->model, "kiesel-cad-%u", ++cad_serial);
    gmshModelAdd(c->model, &ierr);
    if (ierr) return err_set(e, path, 0, "gmsh could not create a model");
    if (merge_file(path, e) || list_surfaces(c, path, e) || mesh_surfaces(c, path, size, e))
        return -1;
    Soup soup = {0};
    int rc = collect(c, &soup, path, e);
    if (!rc) rc = weld(&soup, s, path, e);
    free(soup.node);
    free(soup.tag);
    if (!rc) orient(s);
    return rc;
}

Cad *cad_open(const char *path, double size, TriSurf *s, Err *e)
{
    trisurf_init(s);
    if (gmsh_start(e)) return NULL;
    Cad *c = MEM_NEW(Cad, 1);
    if (load(c, path, size, s, e) == 0) return c;
    trisurf_free(s);
    trisurf_init(s);
    if (c->model[0] && select_model(c) == 0) {
        int ierr = 0;
        gmshModelRemove(&ierr);
    }
    free(c->surf);
    free(c->exact);
    free(c);
    gmsh_stop();
    return NULL;
}

/* Index of surface `tag` in c->surf, or -1. */
static int find_surface(const Cad *c, int tag)
{
    const int *p = bsearch(&tag, c->surf, (size_t)c->nsurf, sizeof *c->surf, cmp_int);
    return p ? (int)(p - c->surf) : -1;
}

/* Closest point of surface `tag` to x and its parameters (u, v).  gmsh
   4.8's getClosestPoint returns (0, 0) as parameters of OpenCASCADE
   faces, so they are recomputed from the point (getParametrization, an
   exact inversion for points on the surface). */
static int project(Cad *c, int tag, const double x[3], double p[3], double uv[2])
{
    int i = find_surface(c, tag);
    if (i < 0 || !c->exact[i] || select_model(c)) return 0;
    double q[3] = {x[0], x[1], x[2]}, *cp = NULL, *pc = NULL, *par = NULL;
    size_t ncp = 0, npc = 0, npar = 0;
    int ierr = 0, ok;
    gmshModelGetClosestPoint(2, tag, q, 3, &cp, &ncp, &pc, &npc, &ierr);
    ok = !ierr && ncp == 3 && isfinite(cp[0]) && isfinite(cp[1]) && isfinite(cp[2]);
    if (ok) gmshModelGetParametrization(2, tag, cp, 3, &par, &npar, &ierr);
    ok = ok && !ierr && npar == 2 && isfinite(par[0]) && isfinite(par[1]);
    if (ok) {
        memcpy(p, cp, 3 * sizeof(double));
        memcpy(uv, par, 2 * sizeof(double));
    }
    gmshFree(cp);
    gmshFree(pc);
    gmshFree(par);
    return ok;
}

int cad_closest(Cad *c, int tag, const double x[3], double p[3])
{
    double q[3], uv[2];
    if (!project(c, tag, x, q, uv)) return 0;
    memcpy(p, q, sizeof q);
    return 1;
}

int cad_normal(Cad *c, int tag, const double x[3], const double ref[3], double n[3])
{
    double p[3], uv[2], *nn = NULL;
    size_t nnn = 0;
    int ierr = 0;
    if (!project(c, tag, x, p, uv)) return 0;
    gmshModelGetNormal(tag, uv, 2, &nn, &nnn, &ierr);
    double len = !ierr && nnn == 3 ? sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]) : 0;
    int ok = len > 0 && isfinite(len);
    if (ok) {
        double sign = nn[0] * ref[0] + nn[1] * ref[1] + nn[2] * ref[2] < 0 ? -1 : 1;
        for (int k = 0; k < 3; k++) n[k] = sign * nn[k] / len;
    }
    gmshFree(nn);
    return ok;
}

void cad_close(Cad *c)
{
    if (!c) return;
    if (select_model(c) == 0) {
        int ierr = 0;
        gmshModelRemove(&ierr);
    }
    free(c->surf);
    free(c->exact);
    free(c);
    gmsh_stop();
}
