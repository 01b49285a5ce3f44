/*
** bc.c: boundary conditions parsed once (bc.h).
**
** bc_init works in three passes so that every refusal comes before any
** coefficient: the field against the grid (cell and patch counts, face
** counts, constraint types on both sides), each patch's type against the
** field's width, and the cyclic pairs against the geometry.  Then the
** coefficients that never change are written once (fixed values,
** Neumann faces, slip's diagonal, cyclic weights, a rotating wall's
** velocities) and bc_update writes the parts that follow the field: the
** explicit ones, and all of partialSlip's, whose nu (bc_wall.c, eq. 2.35)
** follows the flow and the wall state.  partialSlip is slip's split with
** nu in it: nu = 1 gives slip's numbers and nu = 0 movingWall's, to the
** bit, so fvm_same_matrix (fv/fvm.c) sees one matrix for all components
** wherever every partialSlip face sticks.
**
** The entries of partialSlip and rotatingWallVelocity other than type and
** value are the Field's extras (PatchField.extra, kept as text), so their
** refusals name the line of the patch's entry, as every refusal here.
**
** Cyclic pairing follows OpenFOAM: face i of a cyclic patch couples to
** face i of its neighbourPatch.  Nothing but order pairs them, so the
** order is checked: the two centres must differ by one translation for
** the whole patch (to 1e-9 of the grid's size), the areas agree and the
** normals be opposite.  A block grid's cyclic sides pass by
** construction; a cut grid's pass when the geometry is periodic along
** the pair, like the inclined channel of thesis §5.1.3.1 whose walls
** start and end at grid corners.
*/
#include "bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "mem.h"

static const char *const kind_names[BC_NKINDS] = {"fixedValue",  "zeroGradient",        "noSlip",
                                                  "movingWall",  "slip",                "symmetryPlane",
                                                  "cyclic",      "empty",               "calculated",
                                                  "partialSlip", "rotatingWallVelocity"};

static const double PI = 3.14159265358979323846;

const char *bc_kind_name(BcKind k) { return k >= 0 && k < BC_NKINDS ? kind_names[k] : "?"; }

/* The kind of a type keyword, or -1. */
static int kind_of(const char *t)
{
    if (!t) return -1;
    if (!strcmp(t, "movingWallVelocity")) return BC_MOVING_WALL;
    if (!strcmp(t, "symmetry")) return BC_SYMMETRY_PLANE;
    for (int k = 0; k < BC_NKINDS; k++)
        if (!strcmp(t, kind_names[k])) return k;
    return -1;
}

/* ---- messages: the file and line of a patch's entry ---- */

typedef struct Ctx {
    const Field *f;
    const FvMesh *fm;
    const Mesh *m;
    Bc *bc;
} Ctx;

static const char *where_file(const Ctx *c, int p)
{
    if (p >= 0 && p < c->f->npatches && c->f->pf[p].file) return c->f->pf[p].file;
    for (int q = 0; q < c->f->npatches; q++)
        if (c->f->pf[q].file) return c->f->pf[q].file;
    return c->f->name;
}

static int where_line(const Ctx *c, int p) { return p >= 0 && p < c->f->npatches ? c->f->pf[p].line : 0; }

#define PATCH_ERR(c, p, ...) err_set(e, where_file(c, p), where_line(c, p), __VA_ARGS__)

/* ---- pass 1: the field against the grid ---- */

static int check_counts(const Ctx *c, Err *e)
{
    const Field *f = c->f;
    const Mesh *m = c->m;
    if (f->ncells != m->ncells)
        return PATCH_ERR(c, -1, "field '%s' has %d cells, the grid %d: the field is not of this grid", f->name,
                         f->ncells, m->ncells);
    if (f->npatches != m->npatches)
        return PATCH_ERR(c, -1, "field '%s' has %d patches, the grid %d: the field is not of this grid", f->name,
                         f->npatches, m->npatches);
    for (int p = 0; p < m->npatches; p++)
        if (f->pf[p].n != m->patches[p].size)
            return PATCH_ERR(c, p, "patch '%s' of field '%s' has %d faces, the grid's %d", m->patches[p].name,
                             f->name, f->pf[p].n, m->patches[p].size);
    return 0;
}

/* Constraint types agree on both sides: a grid patch of type empty or
   cyclic needs that field type, and those field types need that grid
   patch type. */
static int check_constraint(const Ctx *c, int p, int kind, Err *e)
{
    const Patch *pa = &c->m->patches[p];
    const char *t = c->f->pf[p].type;
    int grid_empty = mesh_patch_is_empty(pa), grid_cyclic = pa->type && !strcmp(pa->type, "cyclic");
    if (grid_empty != (kind == BC_EMPTY))
        return PATCH_ERR(c, p, "patch '%s' is of type %s in the grid, of type %s in field '%s': %s", pa->name,
                         pa->type, t, c->f->name,
                         grid_empty ? "the front and back of a 2-D grid carry no values (type empty)"
                                    : "only an empty grid patch takes type empty");
    if (grid_cyclic != (kind == BC_CYCLIC))
        return PATCH_ERR(c, p, "patch '%s' is of type %s in the grid, of type %s in field '%s': %s", pa->name,
                         pa->type, t, c->f->name,
                         grid_cyclic ? "a cyclic grid patch needs type cyclic"
                                     : "type cyclic needs a cyclic grid patch with a neighbourPatch");
    return 0;
}

/* The wall normal of boundary face b: the geometry's exact one where the
   grid has it (a unit vector), else the face's. */
static void wall_normal(const FvMesh *fm, int b, double *n)
{
    const double *bn = fm->m->boundary_normal ? fm->m->boundary_normal + 3 * b : NULL;
    if (bn && fabs(geom_norm(bn) - 1) < 1e-6)
        memcpy(n, bn, 3 * sizeof *n);
    else
        memcpy(n, fm->nf + 3 * (fm->ninternal + b), 3 * sizeof *n);
}

/* ---- pass 2: each type against the field ---- */

static int vector_only(int kind)
{
    return kind == BC_NO_SLIP || kind == BC_MOVING_WALL || kind == BC_PARTIAL_SLIP || kind == BC_ROTATING_WALL;
}

/* Patch p's entry key other than type and value, or NULL. */
static const DictEntry *extra_entry(const Ctx *c, int p, const char *key)
{
    const Dict *x = c->f->pf[p].extra;
    return x ? dict_find(x, key) : NULL;
}

/* One finite number (function1: also OpenFOAM's `constant w`): 0, or -1
   when en is not one. */
static int entry_number(const DictEntry *en, int function1, double *out)
{
    const DictNode *nd = !en->dict && en->nvals == 1 ? en->vals[0] : NULL;
    if (function1 && !en->dict && en->nvals == 2 && en->vals[0]->kind == DN_WORD &&
        !strcmp(en->vals[0]->text, "constant"))
        nd = en->vals[1];
    if (!nd || nd->kind != DN_NUMBER || !isfinite(nd->num)) return -1;
    *out = nd->num;
    return 0;
}

/* Entry key of patch p as a finite vector (x y z): 1 absent, 0 read, -1
   not a vector. */
static int extra_vector(const Ctx *c, int p, const char *key, double out[3])
{
    if (!extra_entry(c, p, key)) return 1;
    Err scratch; /* its file:line would be the copy's: the caller names the entry's */
    if (dict_vector(c->f->pf[p].extra, key, out, &scratch)) return -1;
    return isfinite(out[0]) && isfinite(out[1]) && isfinite(out[2]) ? 0 : -1;
}

/* partialSlip's frictionAngle (required, 0..90 degrees) and wall velocity
   (wallVelocity, else the value entry, else 0). */
static int parse_partial_slip(const Ctx *c, int p, BcPatch *bp, Err *e)
{
    const char *name = c->m->patches[p].name, *fld = c->f->name;
    const DictEntry *en = extra_entry(c, p, "frictionAngle");
    if (!en)
        return PATCH_ERR(c, p,
                         "patch '%s' of field '%s': type partialSlip needs a frictionAngle entry (the wall friction "
                         "angle phi in degrees, 0 <= phi <= 90: 0 is slip, 90 no-slip)%s",
                         name, fld, extra_entry(c, p, "valueFraction") ? "; OpenFOAM's valueFraction is not read" : "");
    if (entry_number(en, 0, &bp->phi))
        return PATCH_ERR(c, p, "patch '%s' of field '%s': frictionAngle must be a number (degrees)", name, fld);
    if (!(bp->phi >= 0 && bp->phi <= 90))
        return PATCH_ERR(c, p,
                         "patch '%s' of field '%s': frictionAngle %g is out of range: the wall friction angle is "
                         "0 <= phi <= 90 degrees (0 slip, 90 no-slip)",
                         name, fld, bp->phi);
    bp->tan_phi = bp->phi == 90 ? INFINITY : tan(bp->phi * PI / 180);
    size_t n = (size_t)bp->size * 3;
    bp->us = MEM_NEW(double, n);
    double u[3];
    int rc = extra_vector(c, p, "wallVelocity", u);
    if (rc < 0)
        return PATCH_ERR(c, p, "patch '%s' of field '%s': wallVelocity must be a vector (ux uy uz)", name, fld);
    if (rc == 0)
        for (int i = 0; i < bp->size; i++) memcpy(bp->us + 3 * i, u, sizeof u);
    else if (c->f->pf[p].value)
        memcpy(bp->us, c->f->pf[p].value, n * sizeof *bp->us);
    return 0;
}

/* rotatingWallVelocity's origin, axis and omega (all required), and the
   face velocities they give (bc_rotating_velocity, without the normal
   component). */
static int parse_rotating(const Ctx *c, int p, BcPatch *bp, Err *e)
{
    const char *name = c->m->patches[p].name, *fld = c->f->name;
    double o[3], ax[3], w;
    const char *keys[2] = {"origin", "axis"};
    double *vec[2] = {o, ax};
    for (int j = 0; j < 2; j++) {
        int rc = extra_vector(c, p, keys[j], vec[j]);
        if (rc)
            return PATCH_ERR(c, p, "patch '%s' of field '%s': type rotatingWallVelocity needs %s (x y z)%s", name,
                             fld, keys[j], rc > 0 ? "" : ", a vector of three numbers");
    }
    if (geom_norm(ax) == 0)
        return PATCH_ERR(c, p, "patch '%s' of field '%s': rotatingWallVelocity's axis is (0 0 0)", name, fld);
    const DictEntry *en = extra_entry(c, p, "omega");
    if (!en || entry_number(en, 1, &w))
        return PATCH_ERR(c, p,
                         "patch '%s' of field '%s': type rotatingWallVelocity needs omega, the angular velocity in "
                         "rad/s (a number, or constant <number>)",
                         name, fld);
    bp->value = MEM_NEW(double, (size_t)bp->size * 3);
    for (int i = 0; i < bp->size; i++) {
        int f = bp->start + i;
        double n[3];
        wall_normal(c->fm, f - c->fm->ninternal, n);
        bc_rotating_velocity(o, ax, w, c->m->face_centre + 3 * f, n, bp->value + 3 * i);
    }
    return 0;
}

static int has_value(int kind) { return kind == BC_FIXED_VALUE || kind == BC_MOVING_WALL || kind == BC_CALCULATED; }

static int parse_patch(const Ctx *c, int p, Err *e)
{
    const PatchField *pf = &c->f->pf[p];
    const char *name = c->m->patches[p].name;
    int kind = kind_of(pf->type);
    if (kind < 0)
        return PATCH_ERR(c, p,
                         "patch '%s' of field '%s': unknown boundary condition type '%s' (known: fixedValue "
                         "zeroGradient noSlip movingWall slip symmetryPlane symmetry cyclic empty calculated "
                         "partialSlip rotatingWallVelocity)",
                         name, c->f->name, pf->type ? pf->type : "");
    if (vector_only(kind) && c->f->width != 3)
        return PATCH_ERR(c, p, "patch '%s': type %s is for vector fields; field '%s' is a scalar field", name,
                         pf->type, c->f->name);
    if (has_value(kind) && !pf->value)
        return PATCH_ERR(c, p, "patch '%s' of field '%s': type %s needs a value entry", name, c->f->name, pf->type);
    if (check_constraint(c, p, kind, e)) return -1;
    BcPatch *bp = &c->bc->patch[p];
    bp->kind = (BcKind)kind;
    bp->start = c->m->patches[p].start;
    bp->size = c->m->patches[p].size;
    bp->partner = -1;
    size_t nv = (size_t)bp->size * (size_t)c->f->width;
    if (has_value(kind)) {
        bp->value = MEM_NEW(double, nv);
        memcpy(bp->value, pf->value, nv * sizeof *bp->value);
    } else if (kind == BC_NO_SLIP) {
        bp->value = MEM_NEW(double, nv);
    } else if (kind == BC_PARTIAL_SLIP) {
        return parse_partial_slip(c, p, bp, e);
    } else if (kind == BC_ROTATING_WALL) {
        return parse_rotating(c, p, bp, e);
    }
    return 0;
}

/* ---- pass 3: cyclic pairs ---- */

static double grid_size(const Mesh *m)
{
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    return geom_norm(d);
}

static int find_partner(const Ctx *c, int p, Err *e)
{
    const Mesh *m = c->m;
    const Patch *pa = &m->patches[p];
    if (!pa->neighbour) return PATCH_ERR(c, p, "cyclic patch '%s' has no neighbourPatch in the grid", pa->name);
    int q = mesh_patch(m, pa->neighbour);
    if (q < 0)
        return PATCH_ERR(c, p, "cyclic patch '%s': its neighbourPatch '%s' is no patch of the grid", pa->name,
                         pa->neighbour);
    const Patch *qa = &m->patches[q];
    if (q == p || !qa->type || strcmp(qa->type, "cyclic") || !qa->neighbour || strcmp(qa->neighbour, pa->name))
        return PATCH_ERR(c, p, "cyclic patch '%s': its neighbourPatch '%s' is not a cyclic patch paired back with it",
                         pa->name, pa->neighbour);
    if (qa->size != pa->size)
        return PATCH_ERR(c, p, "cyclic patch '%s' has %d faces, its neighbourPatch '%s' %d: the faces cannot pair",
                         pa->name, pa->size, qa->name, qa->size);
    return q;
}

/* Face i of p and face i of q: one translation, equal areas, opposite
   normals. */
static int check_pairs(const Ctx *c, int p, int q, Err *e)
{
    const Mesh *m = c->m;
    const FvMesh *fm = c->fm;
    const Patch *pa = &m->patches[p], *qa = &m->patches[q];
    double tol = 1e-9 * grid_size(m), *T = c->bc->patch[p].shift;
    for (int i = 0; i < pa->size; i++) {
        int fp = pa->start + i, fq = qa->start + i;
        const double *cp = m->face_centre + 3 * fp, *cq = m->face_centre + 3 * fq;
        double d[3] = {cq[0] - cp[0], cq[1] - cp[1], cq[2] - cp[2]};
        if (i == 0) memcpy(T, d, sizeof d);
        double off[3] = {d[0] - T[0], d[1] - T[1], d[2] - T[2]};
        double dn = geom_dot(fm->nf + 3 * fp, fm->nf + 3 * fq);
        if (geom_norm(off) > tol)
            return PATCH_ERR(c, p,
                             "cyclic patch '%s': face %d (centre (%g %g %g)) and face %d of neighbourPatch '%s' "
                             "(centre (%g %g %g)) are %g apart from the translation (%g %g %g) of the first pair: "
                             "the faces do not pair",
                             pa->name, i, cp[0], cp[1], cp[2], i, qa->name, cq[0], cq[1], cq[2], geom_norm(off), T[0],
                             T[1], T[2]);
        if (fabs(fm->mag_sf[fp] - fm->mag_sf[fq]) > 1e-9 * fm->mag_sf[fp] || dn > -1 + 1e-9)
            return PATCH_ERR(c, p,
                             "cyclic patch '%s': face %d (area %g) and face %d of neighbourPatch '%s' (area %g) "
                             "differ in area or are not opposite (n.n = %g): the faces do not pair",
                             pa->name, i, fm->mag_sf[fp], i, qa->name, fm->mag_sf[fq], dn);
    }
    return 0;
}

static int pair_cyclic(const Ctx *c, int p, Err *e)
{
    int q = find_partner(c, p, e);
    if (q < 0 || check_pairs(c, p, q, e)) return -1;
    c->bc->patch[p].partner = q;
    return 0;
}

/* ---- coefficients ---- */

static int scalar_or_neumann(const Bc *bc, BcKind k)
{
    return k == BC_ZERO_GRADIENT || k == BC_EMPTY || ((k == BC_SLIP || k == BC_SYMMETRY_PLANE) && bc->width == 1);
}

/* The coefficients of face i of patch p that never change (partialSlip's
   all change: bc_update writes them). */
static void fill_static(Bc *bc, const BcPatch *bp, int i)
{
    const FvMesh *fm = bc->fm;
    int f = bp->start + i, b = f - fm->ninternal, s = bp->slot + i, w = bc->width;
    double h = bc->h[s] = fm->h[f];
    wall_normal(fm, b, bc->n + 3 * s);
    bc->nbr[s] = -1;
    bc->nu[s] = NAN;
    if (bp->kind == BC_PARTIAL_SLIP) return;
    for (int k = 0; k < w; k++) {
        int j = s * w + k;
        if (bp->value) {
            bc->a[j] = 0; /* eq. 4.61: xi_F, a Dirichlet value */
            bc->b[j] = bp->value[i * w + k];
        } else if (scalar_or_neumann(bc, bp->kind)) {
            bc->a[j] = 1;
            bc->b[j] = 0;
            bc->fixed_grad[s] = 1;
        } else if (bp->kind == BC_SLIP || bp->kind == BC_SYMMETRY_PLANE) {
            double nk = bc->n[3 * s + k];
            bc->a[j] = 1 - nk * nk; /* the diagonal of I - n n^T */
            bc->b[j] = 0;
        }
        /* eq. 4.63 with ht_f = 0: (xi_b - xi_in)/h_f */
        bc->ga[j] = bc->fixed_grad[s] ? 0 : (bc->a[j] - 1) / h;
        bc->gb[j] = bc->fixed_grad[s] ? 0 : bc->b[j] / h;
    }
}

/* A cyclic face: the partner's owner, its distance, the weights. */
static void fill_cyclic(Bc *bc, const BcPatch *bp, int i)
{
    const FvMesh *fm = bc->fm;
    const Mesh *m = fm->m;
    int f = bp->start + i, b = f - fm->ninternal, s = bp->slot + i, g = m->patches[bp->partner].start + i;
    int nb = m->owner[g];
    const double *x = fm->node + 3 * nb, *cg = m->face_centre + 3 * g;
    const double *xc = fm->node + 3 * m->owner[f], *cf = m->face_centre + 3 * f;
    double r[3] = {x[0] - cg[0], x[1] - cg[1], x[2] - cg[2]}, rc[3] = {xc[0] - cf[0], xc[1] - cf[1], xc[2] - cf[2]};
    double dc = fabs(geom_dot(rc, fm->nf + 3 * f)), dn = fabs(geom_dot(r, fm->nf + 3 * g));
    wall_normal(fm, b, bc->n + 3 * s);
    bc->h[s] = fm->h[f];
    bc->nbr[s] = nb;
    bc->nbr_d[s] = dn;
    bc->nbr_w[s] = dc / (dc + dn);
    bc->nu[s] = NAN;
    for (int k = 0; k < bc->width; k++) {
        int j = s * bc->width + k;
        bc->a[j] = dn / (dc + dn);
        bc->ga[j] = -1 / (dc + dn);
    }
}

/* Slip's explicit part: basicSymmetry, one component at a time,
   b_k = -n_k sum_{l != k} n_l u_l of the owner's u. */
static void update_slip(Bc *bc, const BcPatch *bp, const double *v)
{
    const int *owner = bc->fm->m->owner;
    for (int i = 0; i < bp->size; i++) {
        int s = bp->slot + i;
        const double *u = v + 3 * (size_t)owner[bp->start + i], *n = bc->n + 3 * s;
        for (int k = 0; k < 3; k++) {
            int j = s * 3 + k;
            bc->b[j] = -n[k] * (geom_dot(n, u) - n[k] * u[k]);
            bc->gb[j] = bc->b[j] / bc->h[s];
        }
    }
}

/* A cyclic face's periodic neighbour xi_N: b = w_N xi_N and the
   gradient's part (xi_N - xi_C) / (dC + dN). */
static void update_cyclic(Bc *bc, const BcPatch *bp, const double *v)
{
    int w = bc->width;
    for (int i = 0; i < bp->size; i++) {
        int s = bp->slot + i;
        for (int k = 0; k < w; k++) {
            int j = s * w + k;
            double xn = v[bc->nbr[s] * w + k];
            bc->b[j] = bc->nbr_w[s] * xn;
            bc->gb[j] = -bc->ga[j] * xn;
        }
    }
}

/* partialSlip: nu of eq. 2.35 from the owner's u (bc_coulomb_nu; 0
   without a wall state), then u_b = u_S + nu (I - n n^T)(u - u_S) split
   as slip's: a_k = nu (1 - n_k^2) on the diagonal, the rest
   b_k = u_S,k - nu (u_S,k - n_k n.u_S + n_k sum_{l != k} n_l u_l)
   explicit, the gradient (u_b - u)/h_f (eq. 4.63). */
static void update_partial_slip(Bc *bc, const BcPatch *bp, const double *v)
{
    const FvMesh *fm = bc->fm;
    int state = bc->p_b && bc->eta_b;
    for (int i = 0; i < bp->size; i++) {
        int f = bp->start + i, b = f - fm->ninternal, s = bp->slot + i;
        const double *u = v + 3 * (size_t)fm->m->owner[f], *n = bc->n + 3 * s, *us = bp->us + 3 * i;
        double d[3] = {u[0] - us[0], u[1] - us[1], u[2] - us[2]}, dn = geom_dot(n, d);
        double dt[3] = {d[0] - dn * n[0], d[1] - dn * n[1], d[2] - dn * n[2]}, h = bc->h[s];
        double nu = state ? bc_coulomb_nu(bc->p_b[b], bc->eta_b[b], bp->tan_phi, h, geom_norm(dt)) : 0;
        double nus = geom_dot(n, us);
        bc->nu[s] = nu;
        for (int k = 0; k < 3; k++) {
            int j = s * 3 + k;
            bc->a[j] = nu * (1 - n[k] * n[k]);
            bc->b[j] = us[k] - nu * (us[k] - n[k] * nus + n[k] * (geom_dot(n, u) - n[k] * u[k]));
            bc->ga[j] = (bc->a[j] - 1) / h;
            bc->gb[j] = bc->b[j] / h;
        }
    }
}

void bc_update(Bc *bc, const double *v)
{
    for (int p = 0; p < bc->npatches; p++) {
        const BcPatch *bp = &bc->patch[p];
        if (bp->slot < 0) continue;
        if ((bp->kind == BC_SLIP || bp->kind == BC_SYMMETRY_PLANE) && bc->width == 3)
            update_slip(bc, bp, v);
        else if (bp->kind == BC_CYCLIC)
            update_cyclic(bc, bp, v);
        else if (bp->kind == BC_PARTIAL_SLIP)
            update_partial_slip(bc, bp, v);
    }
}

/* The coefficients of the faces of the patches that are not empty
   (FvMesh.bslot: the empty patches are the grid's, pass 1 checked). */
static void allocate(Bc *bc, int w)
{
    const FvMesh *fm = bc->fm;
    int ns = bc->nslots = fm->nslots;
    for (int p = 0; p < bc->npatches; p++) {
        BcPatch *bp = &bc->patch[p];
        bp->slot = bp->kind == BC_EMPTY || bp->size == 0 ? -1 : fm->bslot[bp->start - fm->ninternal];
    }
    size_t n = (size_t)ns * (size_t)w;
    bc->a = MEM_NEW(double, n);
    bc->b = MEM_NEW(double, n);
    bc->ga = MEM_NEW(double, n);
    bc->gb = MEM_NEW(double, n);
    bc->fixed_grad = MEM_NEW(char, ns);
    bc->n = MEM_NEW(double, 3 * (size_t)ns);
    bc->h = MEM_NEW(double, ns);
    bc->nbr = MEM_NEW(int, ns);
    bc->nbr_w = MEM_NEW(double, ns);
    bc->nbr_d = MEM_NEW(double, ns);
    bc->nu = MEM_NEW(double, ns);
}

static int parse(Ctx *c, Err *e)
{
    if (check_counts(c, e)) return -1;
    for (int p = 0; p < c->m->npatches; p++)
        if (parse_patch(c, p, e)) return -1;
    for (int p = 0; p < c->m->npatches; p++)
        if (c->bc->patch[p].kind == BC_CYCLIC && pair_cyclic(c, p, e)) return -1;
    return 0;
}

int bc_init(Bc *bc, const Field *f, const FvMesh *fm, Err *e)
{
    memset(bc, 0, sizeof *bc);
    bc->fm = fm;
    bc->width = f->width;
    bc->npatches = fm->m->npatches;
    bc->nboundary = fm->nboundary;
    bc->patch = MEM_NEW(BcPatch, bc->npatches);
    Ctx c = {f, fm, fm->m, bc};
    if (parse(&c, e)) {
        bc_free(bc);
        return -1;
    }
    allocate(bc, f->width);
    for (int p = 0; p < bc->npatches; p++)
        for (int i = 0; i < bc->patch[p].size && bc->patch[p].slot >= 0; i++) {
            if (bc->patch[p].kind == BC_CYCLIC)
                fill_cyclic(bc, &bc->patch[p], i);
            else
                fill_static(bc, &bc->patch[p], i);
        }
    bc_update(bc, f->v);
    return 0;
}

void bc_free(Bc *bc)
{
    for (int p = 0; p < bc->npatches && bc->patch; p++) {
        free(bc->patch[p].value);
        free(bc->patch[p].us);
    }
    free(bc->patch);
    free(bc->a);
    free(bc->b);
    free(bc->ga);
    free(bc->gb);
    free(bc->fixed_grad);
    free(bc->n);
    free(bc->h);
    free(bc->nbr);
    free(bc->nbr_w);
    free(bc->nbr_d);
    free(bc->nu);
    memset(bc, 0, sizeof *bc);
}

/* ---- boundary values ---- */

/* Component k of the values of patch bp's faces into xb[b * stride], b
   the boundary index of each face: one loop per patch and kind, since
   these run over every boundary face several times a step (in 2-D the
   empty faces are two per cell). */
static void patch_values(const Bc *bc, const BcPatch *bp, const double *v, int k, double *xb, int stride)
{
    const FvMesh *fm = bc->fm;
    const int *owner = fm->m->owner + fm->ninternal;
    int w = bc->width, b0 = bp->start - fm->ninternal, s0 = bp->slot - b0;
    if (bp->slot < 0) return; /* empty */
    if (bp->value) {
        for (int j = 0; j < bp->size; j++) xb[(size_t)(b0 + j) * stride] = bp->value[j * w + k];
    } else if (bp->kind == BC_CYCLIC) {
        for (int b = b0; b < b0 + bp->size; b++) {
            double wn = bc->nbr_w[s0 + b];
            xb[(size_t)b * stride] = (1 - wn) * v[(size_t)owner[b] * w + k] + wn * v[(size_t)bc->nbr[s0 + b] * w + k];
        }
    } else if ((bp->kind == BC_SLIP || bp->kind == BC_SYMMETRY_PLANE) && w == 3) {
        for (int b = b0; b < b0 + bp->size; b++) {
            const double *n = bc->n + 3 * (s0 + b), *own = v + (size_t)owner[b] * 3;
            xb[(size_t)b * stride] = own[k] - geom_dot(n, own) * n[k];
        }
    } else if (bp->kind == BC_PARTIAL_SLIP) { /* u_S + nu (I - n n^T)(u - u_S) */
        for (int b = b0; b < b0 + bp->size; b++) {
            const double *n = bc->n + 3 * (s0 + b), *own = v + (size_t)owner[b] * 3, *us = bp->us + 3 * (b - b0);
            double d[3] = {own[0] - us[0], own[1] - us[1], own[2] - us[2]};
            xb[(size_t)b * stride] = us[k] + bc->nu[s0 + b] * (d[k] - geom_dot(n, d) * n[k]);
        }
    } else {
        for (int b = b0; b < b0 + bp->size; b++) xb[(size_t)b * stride] = v[(size_t)owner[b] * w + k];
    }
}

void bc_values_component(const Bc *bc, const double *v, int k, double *xb)
{
    for (int p = 0; p < bc->npatches; p++) patch_values(bc, &bc->patch[p], v, k, xb, 1);
}

void bc_values(const Bc *bc, const double *v, double *xb)
{
    for (int p = 0; p < bc->npatches; p++)
        for (int k = 0; k < bc->width; k++) patch_values(bc, &bc->patch[p], v, k, xb + k, bc->width);
}

void bc_states(const Bc *bc, const double *v, double *xb)
{
    bc_values(bc, v, xb);
    int w = bc->width;
    for (int p = 0; p < bc->npatches; p++) {
        const BcPatch *bp = &bc->patch[p];
        if (bp->kind != BC_CYCLIC) continue;
        for (int j = 0; j < bp->size; j++)
            memcpy(xb + (size_t)(bp->start - bc->fm->ninternal + j) * w, v + (size_t)bc->nbr[bp->slot + j] * w,
                   (size_t)w * sizeof *xb);
    }
}
