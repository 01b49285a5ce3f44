/*
** field_bc.c: boundary conditions of vol fields (field.h): which patch
** types carry a value, which are constraint types, and the face values a
** condition gives from the internal field.
**
** The types follow OpenFOAM v1912: fixedValue and calculated hold their
** face values (required in the file); zeroGradient, slip, noSlip and the
** constraint types (empty, cyclic, symmetry, symmetryPlane, wedge) hold
** none and are evaluated from the cells.  A mesh patch of a constraint
** type forces that type on its patch field (field_init, field_read).
**
** Evaluation (field_patch_values) is the first-order one the readers of
** face values need (sampleLine's least-squares gradient, writeVTK's
** patch surfaces): the owner cell's value, its tangential part for slip
** and symmetry vectors (u - (u.n) n, n the face's unit normal from its
** area vector, geom_face), the mean of the two cells across a cyclic
** pair, zero for noSlip.  A type it does not know gives the owner value.
*/
#include "field.h"

#include "geom.h"

#include <math.h>
#include <string.h>

static int type_is(const char *t, const char *name) { return t && strcmp(t, name) == 0; }

int field_type_needs_value(const char *t)
{
    return type_is(t, "fixedValue") || type_is(t, "calculated");
}

int field_type_valueless(const char *t)
{
    static const char *const names[] = {"zeroGradient", "slip",     "noSlip",        "empty",
                                        "cyclic",       "symmetry", "symmetryPlane", NULL};
    for (int i = 0; names[i]; i++)
        if (type_is(t, names[i])) return 1;
    return 0;
}

int field_type_constraint(const char *t)
{
    return type_is(t, "empty") || type_is(t, "cyclic") || type_is(t, "symmetry") ||
           type_is(t, "symmetryPlane") || type_is(t, "wedge");
}

/* u without its component along the unit normal of face fi: the mesh's
   area vector when its geometry is computed, else geom_face's. */
static void remove_normal(const Mesh *m, int fi, double *u)
{
    double S[3], C[3];
    if (m->face_area)
        memcpy(S, m->face_area + 3 * (size_t)fi, sizeof S);
    else
        geom_face(m->points, m->face_idx + m->face_off[fi], m->face_off[fi + 1] - m->face_off[fi], S, C);
    double a = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
    if (a == 0) return;
    double nrm[3] = {S[0] / a, S[1] / a, S[2] / a};
    double un = u[0] * nrm[0] + u[1] * nrm[1] + u[2] * nrm[2];
    for (int k = 0; k < 3; k++) u[k] -= un * nrm[k];
}

void field_patch_values(const Field *f, const Mesh *m, int p, double *out)
{
    const Patch *patch = &m->patches[p];
    const PatchField *pf = &f->pf[p];
    int w = f->width, n = patch->size;
    const char *t = pf->type;
    int partner = type_is(t, "cyclic") && patch->neighbour ? mesh_patch(m, patch->neighbour) : -1;
    if (partner >= 0 && m->patches[partner].size != n) partner = -1;
    for (int i = 0; i < n; i++) {
        int fi = patch->start + i;
        double *o = out + (size_t)i * w;
        const double *own = f->v + (size_t)m->owner[fi] * w;
        if (field_type_needs_value(t) && pf->value) {
            memcpy(o, pf->value + (size_t)i * w, (size_t)w * sizeof *o);
        } else if (type_is(t, "noSlip")) {
            for (int k = 0; k < w; k++) o[k] = 0;
        } else if (partner >= 0) {
            const double *nb = f->v + (size_t)m->owner[m->patches[partner].start + i] * w;
            for (int k = 0; k < w; k++) o[k] = 0.5 * (own[k] + nb[k]);
        } else {
            memcpy(o, own, (size_t)w * sizeof *o);
            if (w == 3 && (type_is(t, "slip") || type_is(t, "symmetry") || type_is(t, "symmetryPlane")))
                remove_normal(m, fi, o);
        }
    }
}
