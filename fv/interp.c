/*
** interp.c: ICCM interpolation stencils (interp.h): the options of
** system/fvSchemes, the search index, modified Shepard, piecewise
** constant, and the three rows of every face.  Multilinear is in
** interp_ml.c.
**
** Modified Shepard (spec §3.2, thesis §4.2.7, eq. 4.28-4.32):
**   w_s(x) = max(0, 1/d_s(x_s, x) - 1/R)^beta,   value = sum w_s xi_s / sum w_s
**   d_s(x, y)^2 = sum_i ((x_i - y_i) / h_{s,i})^2     (eq. 4.29-4.31)
** with eq. 4.32's variant: h_s are the sizes of the source cell s, taken
** as the extent of the union of its Cartesian parents' boxes (a merged
** cluster reaches as far as the Cartesian cells it is made of; a cut cell
** as far as its whole box; a Voronoi cell as its seed's Cartesian cell);
** without Cartesian parents, the extent of the cell's own points.  On a
** uniform grid this is the thesis's d_h with the grid spacings; on a
** graded grid a face centre still sees its two cells at d = 1/2 each, so
** Shepard gives their plain mean there too.  A boundary-face source
** (boundarySources on) takes its owner's h.
** Sources are the nodes of the cells (a merged cluster is one cell, so it
** counts once: correction 2 of the spec); boundary-face centres only when
** boundarySources is on (default off).  A point within 1e-12 (in d) of a
** source takes that source alone (CS, §4.3).  A point with fewer than
** `need` sources inside R (2 for the points of an internal face, 1 for a
** boundary face's inner point: thesis L3133-3136) searches again with R
** grown by 3/2 until it has them; InterpStats counts those points and
** the largest R.
** Piecewise constant at an arbitrary point: the cell whose node is
** nearest in d_s.
*/
#include "interp_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

/* A face's rows are a stencil pair's rows (stencil.h): owner a, neighbour b. */
_Static_assert((int)INTERP_CENTRE == (int)STENCIL_PAIR_MEAN && (int)INTERP_PLUS == (int)STENCIL_PAIR_B &&
                   (int)INTERP_MINUS == (int)STENCIL_PAIR_A && (int)INTERP_NPOINTS == (int)STENCIL_GROUP,
               "interp.h's points are stencil.h's pair rows");

const char *const interp_method_names[] = {"shepard", "multilinear", "none", NULL};

const DictKey interp_keys[] = {
    {"default", "shepard", "interpolation of face values and gradient points: shepard | multilinear | none"},
    {"shepardCoeffs", "{}", "modified Shepard's coefficients (beta, radius, boundarySources)"},
    {NULL, NULL, NULL}};

const DictKey interp_shepard_keys[] = {
    {"beta", "2", "exponent of the weights max(0, 1/d - 1/R)^beta"},
    {"radius", "1", "R: the reach of a source in its own cell sizes (eq. 4.32)"},
    {"boundarySources", "off", "boundary-face centres as extra sources (with their boundary values)"},
    {NULL, NULL, NULL}};

void interp_opts_default(InterpOpts *o)
{
    memset(o, 0, sizeof *o);
    o->method = INTERP_SHEPARD;
    o->beta = 2;
    o->radius = 1;
}

static int read_shepard(const Dict *c, InterpOpts *o, Err *e)
{
    if (dict_check_keys(c, interp_shepard_keys, e) || dict_scalar_or(c, "beta", 2, &o->beta, e) ||
        dict_scalar_or(c, "radius", 1, &o->radius, e) ||
        dict_switch_or(c, "boundarySources", 0, &o->boundary_sources, e))
        return -1;
    const char *bad = !(o->beta > 0) ? "beta" : !(o->radius > 0) ? "radius" : NULL;
    if (bad) {
        const DictEntry *en = dict_find(c, bad);
        return err_set(e, en->file, en->line, "%s must be positive in %s", bad, c->name);
    }
    return 0;
}

int interp_read_opts(const Dict *fvschemes, InterpOpts *o, Err *e)
{
    interp_opts_default(o);
    const Dict *d = dict_subdict_opt(fvschemes, "interpolationSchemes");
    if (!d) return 0;
    if (dict_check_keys(d, interp_keys, e)) return -1;
    const DictEntry *en = dict_find(d, "default");
    o->file = en ? en->file : d->file;
    o->line = en ? en->line : d->line;
    if (dict_choice_or(d, "default", interp_method_names, INTERP_SHEPARD, &o->method, e)) return -1;
    const Dict *c = dict_subdict_opt(d, "shepardCoeffs");
    return c ? read_shepard(c, o, e) : 0;
}

int interp_locate(const double *x, int n, double v)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (x[mid] <= v) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

/* ---- the search index ---- */

static void box_union(double lo[3], double hi[3], const double *a, const double *b)
{
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(lo[k], a[k]);
        hi[k] = fmax(hi[k], b[k]);
    }
}

/* Box of Cartesian cell K. */
static void cart_box(const CartGrid *g, int K, double lo[3], double hi[3])
{
    int ijk[3] = {K % g->n[0], (K / g->n[0]) % g->n[1], K / (g->n[0] * g->n[1])};
    for (int k = 0; k < 3; k++) {
        lo[k] = g->x[k][ijk[k]];
        hi[k] = g->x[k][ijk[k] + 1];
    }
}

/* h_s of cell c (see the top of the file). */
static void cell_sizes(const Mesh *m, int c, double h[3])
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, a[3], b[3];
    const CartCells *cc = &m->cartcells;
    if (cc->n > 0 && cc->parent_off[c + 1] > cc->parent_off[c]) {
        for (int q = cc->parent_off[c]; q < cc->parent_off[c + 1]; q++) {
            cart_box(&m->cart, cc->parent[q], a, b);
            box_union(lo, hi, a, b);
        }
    } else if (m->cell_parent && m->cart.n[0] > 0 && m->cell_parent[c] >= 0) {
        cart_box(&m->cart, m->cell_parent[c], lo, hi);
    } else {
        for (int q = m->cell_off[c]; q < m->cell_off[c + 1]; q++) {
            int f = m->cell_faces[q];
            for (int p = m->face_off[f]; p < m->face_off[f + 1]; p++) {
                const double *x = m->points + 3 * m->face_idx[p];
                box_union(lo, hi, x, x);
            }
        }
    }
    for (int k = 0; k < 3; k++) h[k] = hi[k] - lo[k];
}

static void bucket_axes(InterpIndex *ix, const FvMesh *f)
{
    const Mesh *m = f->m;
    if (m->cart.n[0] > 0) {
        for (int k = 0; k < 3; k++) {
            ix->nb[k] = m->cart.n[k];
            ix->bx[k] = mem_alloc(sizeof(double) * (size_t)(ix->nb[k] + 1));
            memcpy(ix->bx[k], m->cart.x[k], sizeof(double) * (size_t)(ix->nb[k] + 1));
        }
        return;
    }
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    int dim = f->empty_axis >= 0 ? 2 : 3;
    double hmean = 1;
    for (int k = 0; k < 3; k++)
        if (k != f->empty_axis) hmean *= hi[k] - lo[k];
    hmean = pow(hmean / f->ncells, 1.0 / dim);
    for (int k = 0; k < 3; k++) {
        double nk = k == f->empty_axis ? 1 : floor((hi[k] - lo[k]) / hmean);
        ix->nb[k] = nk < 1 ? 1 : nk > 4096 ? 4096 : (int)nk;
        ix->bx[k] = mem_alloc(sizeof(double) * (size_t)(ix->nb[k] + 1));
        for (int i = 0; i <= ix->nb[k]; i++) ix->bx[k][i] = lo[k] + (hi[k] - lo[k]) * i / ix->nb[k];
    }
}

static int bucket_of(const InterpIndex *ix, const double *x)
{
    int i[3];
    for (int k = 0; k < 3; k++) i[k] = interp_locate(ix->bx[k], ix->nb[k], x[k]);
    return i[0] + ix->nb[0] * (i[1] + ix->nb[1] * i[2]);
}

static void sources(InterpIndex *ix, const FvMesh *f, int boundary_sources)
{
    const Mesh *m = f->m;
    ix->ncells = f->ncells;
    ix->nsrc = f->ncells + f->nboundary;
    ix->spos = mem_alloc(3 * sizeof(double) * (size_t)(ix->nsrc + 1));
    ix->sh = mem_alloc(3 * sizeof(double) * (size_t)(ix->nsrc + 1));
    ix->is_src = mem_calloc((size_t)ix->nsrc + 1, 1);
    for (int c = 0; c < f->ncells; c++) {
        memcpy(ix->spos + 3 * c, f->node + 3 * c, 3 * sizeof(double));
        cell_sizes(m, c, ix->sh + 3 * c);
        ix->is_src[c] = 1;
    }
    for (int b = 0; b < f->nboundary; b++) {
        int i = f->ninternal + b, s = f->ncells + b;
        memcpy(ix->spos + 3 * s, m->face_centre + 3 * i, 3 * sizeof(double));
        memcpy(ix->sh + 3 * s, ix->sh + 3 * m->owner[i], 3 * sizeof(double));
        ix->is_src[s] = (char)(boundary_sources && !f->empty_face[i] && f->cyc_face[b] < 0);
    }
    for (int k = 0; k < 3; k++) {
        ix->active[k] = k != f->empty_axis;
        ix->hmax[k] = 0;
        for (int s = 0; s < ix->nsrc; s++)
            if (ix->is_src[s]) ix->hmax[k] = fmax(ix->hmax[k], ix->sh[3 * s + k]);
    }
}

/* The translations of the cyclic pairs, both ways: a source at x_s also
   stands at x_s - T for each (its periodic images next to the box). */
static void translations(InterpIndex *ix, const FvMesh *f)
{
    const Mesh *m = f->m;
    ix->ntrans = 0;
    for (int p = 0; p < m->npatches && ix->ntrans < INTERP_MAXTRANS; p++) {
        const Patch *pa = &m->patches[p];
        if (pa->size == 0 || f->cyc_face[pa->start - f->ninternal] < 0) continue;
        fvmesh_cyclic_shift(f, pa->start, ix->trans[ix->ntrans++]);
    }
}

static void index_build(InterpIndex *ix, const FvMesh *f, int boundary_sources)
{
    bucket_axes(ix, f);
    sources(ix, f, boundary_sources);
    translations(ix, f);
    int nb = ix->nb[0] * ix->nb[1] * ix->nb[2];
    ix->boff = mem_calloc((size_t)nb + 1, sizeof(int));
    int *where = mem_alloc(sizeof(int) * (size_t)(ix->nsrc + 1));
    for (int s = 0; s < ix->nsrc; s++) {
        where[s] = ix->is_src[s] ? bucket_of(ix, ix->spos + 3 * s) : -1;
        if (where[s] >= 0) ix->boff[where[s] + 1]++;
    }
    for (int b = 0; b < nb; b++) ix->boff[b + 1] += ix->boff[b];
    ix->bsrc = mem_alloc(sizeof(int) * (size_t)(ix->boff[nb] + 1));
    int *fill = mem_alloc(sizeof(int) * (size_t)(nb + 1));
    memcpy(fill, ix->boff, sizeof(int) * (size_t)nb);
    for (int s = 0; s < ix->nsrc; s++)
        if (where[s] >= 0) ix->bsrc[fill[where[s]]++] = s;
    free(fill);
    free(where);
}

static void index_free(InterpIndex *ix)
{
    for (int k = 0; k < 3; k++) free(ix->bx[k]);
    free(ix->boff);
    free(ix->bsrc);
    free(ix->spos);
    free(ix->sh);
    free(ix->is_src);
    free(ix->cand);
    free(ix->cw);
    free(ix->near_wall);
}

/* ---- modified Shepard ---- */

/* d_s(x_s, x) of eq. 4.32 over the active axes. */
static double metric(const InterpIndex *ix, int s, const double *x)
{
    double d = 0;
    for (int k = 0; k < 3; k++)
        if (ix->active[k]) {
            double t = (x[k] - ix->spos[3 * s + k]) / ix->sh[3 * s + k];
            d += t * t;
        }
    return sqrt(d);
}

static void cand_push(InterpIndex *ix, int n, int s, double w)
{
    if ((size_t)n + 1 > ix->ccap) {
        mem_grow((void **)&ix->cand, &ix->ccap, (size_t)n + 1, sizeof *ix->cand);
        ix->cw = mem_realloc(ix->cw, ix->ccap * sizeof *ix->cw);
    }
    ix->cand[n] = s;
    ix->cw[n] = w;
}

/* What a search within R h_max of x found. */
typedef struct Gather {
    int n;          /* sources with positive weight, in ix->cand/cw */
    int exact;      /* a source at x, or -1 */
    int nearest;    /* the nearest cell in d, or -1 */
    double dnear;
} Gather;

static void gather_bucket(InterpIndex *ix, int b, const double *x, double R, double beta, Gather *g)
{
    for (int q = ix->boff[b]; q < ix->boff[b + 1]; q++) {
        int s = ix->bsrc[q];
        double d = metric(ix, s, x);
        if (d < 1e-12 && g->exact < 0) g->exact = s;
        if (s < ix->ncells && d < g->dnear) {
            g->dnear = d;
            g->nearest = s;
        }
        if (d < R && d >= 1e-12) cand_push(ix, g->n++, s, pow(1 / d - 1 / R, beta));
    }
}

/* The buckets within R h_max of the query q into g; none when the window
   misses the bucket grid (a periodic image far from the box). */
static void gather_window(InterpIndex *ix, const double *q, double R, double beta, Gather *g)
{
    int lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        if (ix->active[k] && (q[k] + R * ix->hmax[k] < ix->bx[k][0] || q[k] - R * ix->hmax[k] > ix->bx[k][ix->nb[k]]))
            return;
        lo[k] = interp_locate(ix->bx[k], ix->nb[k], q[k] - R * ix->hmax[k]);
        hi[k] = interp_locate(ix->bx[k], ix->nb[k], q[k] + R * ix->hmax[k]);
    }
    for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
            for (int i = lo[0]; i <= hi[0]; i++) gather_bucket(ix, i + ix->nb[0] * (j + ix->nb[1] * k), q, R, beta, g);
}

/* Sources within R of x, and their periodic images: a source s seen
   across a cyclic side, at x_s - T, is s found from the query x + T. */
static void gather(InterpIndex *ix, const double *x, double R, double beta, Gather *g)
{
    g->n = 0;
    g->exact = g->nearest = -1;
    g->dnear = INFINITY;
    gather_window(ix, x, R, beta, g);
    for (int t = 0; t < ix->ntrans; t++) {
        double q[3] = {x[0] + ix->trans[t][0], x[1] + ix->trans[t][1], x[2] + ix->trans[t][2]};
        gather_window(ix, q, R, beta, g);
    }
}

/* Does the window of radius R cover every bucket? */
static int covers_all(const InterpIndex *ix, const double *x, double R)
{
    for (int k = 0; k < 3; k++)
        if (x[k] - R * ix->hmax[k] > ix->bx[k][0] || x[k] + R * ix->hmax[k] < ix->bx[k][ix->nb[k]]) return 0;
    return 1;
}

void interp_shepard(Interp *ip, const double x[3], int need, Stencil *s)
{
    InterpIndex *ix = ip->ix;
    double R = ip->o.radius;
    Gather g;
    for (;;) {
        gather(ix, x, R, ip->o.beta, &g);
        if (g.exact >= 0 || g.n >= need || covers_all(ix, x, R)) break;
        R *= 1.5;
    }
    if (R > ip->o.radius) ip->st.ngrown++;
    ip->st.radius_max = fmax(ip->st.radius_max, R);
    if (g.exact >= 0 || g.n == 0) {
        stencil_add(s, g.exact >= 0 ? g.exact : g.nearest, 1.0);
        return;
    }
    double sum = 0;
    for (int q = 0; q < g.n; q++) sum += ix->cw[q];
    for (int q = 0; q < g.n; q++) stencil_add(s, ix->cand[q], ix->cw[q] / sum);
}

/* Piecewise constant at x: the nearest cell node in d_s. */
static void nearest_cell(Interp *ip, const double x[3], Stencil *s)
{
    InterpIndex *ix = ip->ix;
    Gather g;
    double R = ip->o.radius;
    do {
        gather(ix, x, R, 1, &g);
        R *= 2;
    } while (g.nearest < 0 && !covers_all(ix, x, R / 2));
    stencil_add(s, g.nearest, 1.0);
}

/* ---- the rows of the faces ---- */

void interp_face_point(const FvMesh *f, int i, int k, double x[3])
{
    const double *c = f->m->face_centre + 3 * i, *n = f->nf + 3 * i;
    double t = k == INTERP_PLUS ? f->ht[i] : k == INTERP_MINUS ? -f->h[i] : 0, T[3] = {0, 0, 0};
    if (k == INTERP_PLUS && i >= f->ninternal && f->cyc_face[i - f->ninternal] >= 0) fvmesh_cyclic_shift(f, i, T);
    for (int a = 0; a < 3; a++) x[a] = c[a] + t * n[a] + T[a];
}

/* One row of the method at point k of face i. */
static void method_row(Interp *ip, int i, int k)
{
    const FvMesh *f = ip->f;
    Stencil *s = &ip->face;
    double x[3];
    int own = f->m->owner[i], nb = fvmesh_across(f, i, x);
    if (nb < 0 && k != INTERP_MINUS) {
        stencil_add(s, f->ncells + i - f->ninternal, 1.0); /* eq. 4.61: xi_F */
    } else if ((ip->o.method == INTERP_NONE || f->cartesian_face[i]) && i < f->ninternal) {
        stencil_pair_row(s); /* the same two-point rows as below, not stored */
        return;
    } else if (ip->o.method == INTERP_NONE || f->cartesian_face[i]) {
        if (k != INTERP_PLUS) stencil_add(s, own, k == INTERP_CENTRE ? 0.5 : 1.0);
        if (k != INTERP_MINUS) stencil_add(s, nb, k == INTERP_CENTRE ? 0.5 : 1.0);
    } else {
        interp_face_point(f, i, k, x);
        if (ip->o.method == INTERP_MULTILINEAR) interp_multilinear(ip, x, s);
        else interp_shepard(ip, x, nb < 0 ? 1 : 2, s);
        if (interp_lin_wants(ip, i)) interp_lin_correct(ip, i, x);
    }
    stencil_end_row(s);
}

/* Row r of s appended again as a new row. */
static void copy_row(Stencil *s, int r)
{
    for (int j = s->off[r]; j < s->off[r + 1]; j++) stencil_add(s, s->src[j], s->w[j]);
    stencil_end_row(s);
}

static void face_rows(Interp *ip)
{
    const FvMesh *f = ip->f;
    for (int i = 0; i < f->nfaces; i++) {
        if (f->empty_face[i]) { /* no flux: zero rows, which nothing reads */
            for (int k = 0; k < INTERP_NPOINTS; k++) stencil_end_row(&ip->face);
            continue;
        }
        ip->st.ncartesian += f->cartesian_face[i];
        int g = i >= f->ninternal ? f->cyc_face[i - f->ninternal] : -1;
        if (g >= 0 && g < i) {
            /* the partner's points, seen from this side: its MINUS is our
               PLUS and the reverse, so the two fluxes cancel exactly */
            copy_row(&ip->face, interp_row(g, INTERP_CENTRE));
            copy_row(&ip->face, interp_row(g, INTERP_MINUS));
            copy_row(&ip->face, interp_row(g, INTERP_PLUS));
            continue;
        }
        for (int k = 0; k < INTERP_NPOINTS; k++) method_row(ip, i, k);
    }
    Stencil *s = &ip->face;
    ip->st.nrows = s->nrows;
    long entries = 0, rows = 0;
    for (int r = 0; r < s->nrows; r++) {
        if (f->empty_face[r / INTERP_NPOINTS]) continue;
        int n = stencil_row_len(s, r);
        entries += n;
        rows++;
        if (n > ip->st.max_size) ip->st.max_size = n;
    }
    ip->st.mean_size = rows ? (double)entries / rows : 0;
}

/* The search index and what hangs on it (multilinear's lattice, the wall
   cells of interp_lin.c).  It is needed while the face rows are built and
   by interp_point only, so interp_init frees it when the rows are done
   (about 60 bytes a cell) and interp_point builds it again on its first
   call. */
static int index_make(Interp *ip, const char *grid, Err *e)
{
    ip->ix = mem_calloc(1, sizeof *ip->ix);
    index_build(ip->ix, ip->f, ip->o.boundary_sources);
    if (ip->o.method == INTERP_MULTILINEAR && interp_ml_check(ip, grid, e)) return -1;
    interp_lin_init(ip);
    return 0;
}

static void index_drop(Interp *ip)
{
    if (ip->ix) index_free(ip->ix);
    free(ip->ix);
    ip->ix = NULL;
}

int interp_point(Interp *ip, const double x[3], int need, Stencil *s)
{
    Err e;
    if (!ip->ix) index_make(ip, NULL, &e); /* interp_init passed its checks */
    if (ip->o.method == INTERP_MULTILINEAR) interp_multilinear(ip, x, s);
    else if (ip->o.method == INTERP_NONE) nearest_cell(ip, x, s);
    else interp_shepard(ip, x, need, s);
    return stencil_end_row(s);
}

int interp_init(Interp *ip, const FvMesh *f, const InterpOpts *o, const char *grid, Err *e)
{
    memset(ip, 0, sizeof *ip);
    ip->o = *o;
    ip->f = f;
    ip->st.radius_max = o->radius;
    if (index_make(ip, grid, e)) {
        interp_free(ip);
        return -1;
    }
    stencil_init(&ip->face);
    stencil_pairs(&ip->face, f->m->owner, f->m->neighbour, f->ninternal);
    face_rows(ip);
    stencil_trim(&ip->face);
    index_drop(ip);
    return 0;
}

void interp_free(Interp *ip)
{
    index_drop(ip);
    stencil_free(&ip->face);
    memset(ip, 0, sizeof *ip);
}
