/*
** field.c: volScalarField / volVectorField files.  See field.h.  What
** the patch types mean and the face values they give are in field_bc.c,
** the fields of a time directory in field_time.c.
**
** Reading goes through the dictionary parser (dict.c), which already
** handles ascii, binary and gzip, so this file only interprets entries:
** `dimensions` (7 or 5 exponents, or unit words such as [m s^-1]),
** `internalField` and each patch's `value` ("uniform X" or "nonuniform
** List<T> N(...)"), and the look-up of a patch's entry in boundaryField.
**
** Patch look-up follows OpenFOAM's GeometricBoundaryField::readField:
**   1. a literal key equal to the patch name;
**   2. a literal key naming a group of the patch (its inGroups, or its
**      type when that is wall or a constraint type), scanning the entries
**      from last to first so that the last group entry wins;
**   3. patches of a constraint type (empty, cyclic, symmetry,
**      symmetryPlane, wedge) take that type: OpenFOAM does so for empty,
**      and the usual #includeEtc "caseDicts/setConstraintTypes" (which
**      dict.c skips) does so for the others;
**   4. a regex key matching the name (the last matching one wins).
** Any patch still without an entry is an error naming the patch.  A basic
** type on a constraint patch (zeroGradient on empty) is refused, as in
** OpenFOAM.
**
** Every patch entry other than `type` and `value` is copied into `extra`
** (as text through dict_write_node and dict_set, so the copy owns its
** memory), and written back after type and value in the order read.  The
** value is kept for types that carry one: fixedValue and calculated (where
** it is required, as in OpenFOAM) and any unknown type that has it; the
** known value-less types (zeroGradient, slip, ...) drop a stray value,
** since OpenFOAM recomputes and never writes it for them.
**
** Nothing read is dropped on a rewrite.  OpenFOAM v1912's setFields
** writes only dimensions, internalField and one boundaryField entry per
** patch, silently losing user entries, #include'd values and entries for
** patches the mesh does not have; here every other top-level entry is
** kept in place (Field.keep) and every boundaryField entry that no patch
** took is kept after the patches (Field.keep_bf), by the same copy as the
** extras.  An entry that is used (a group or regex entry some patch
** takes) is written out per patch instead, as OpenFOAM does.  A kept
** literal entry that names no patch or group of the mesh is most likely a
** typo or a stale patch: it gets a warning (Field.warn), since OpenFOAM
** ignores it without a word.
**
** Writing mirrors OpenFOAM v1912 byte for byte in layout: a list is written
** "uniform" when all its items are bitwise equal (so -0 and 0 stay apart
** and every round trip is exact), binary lists are raw float64 after a
** List<T> tag, and numeric lists among the extras are written raw as well
** in binary files (OpenFOAM's binary reader expects every List<scalar>
** there in binary).
*/
#include "field.h"

#include "buf.h"
#include "foam.h"
#include "io.h"
#include "mem.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---- init / free ---- */

void field_init(Field *f, const Mesh *m, const char *name, int width, const double *uniform,
                const char *default_type)
{
    memset(f, 0, sizeof *f);
    f->name = mem_strdup(name);
    f->width = width;
    f->ncells = m->ncells;
    size_t nv = (size_t)m->ncells * (size_t)width;
    f->v = MEM_NEW(double, nv);
    for (int c = 0; c < m->ncells; c++)
        for (int k = 0; k < width; k++) f->v[(size_t)c * width + k] = uniform[k];
    f->npatches = m->npatches;
    f->pf = MEM_NEW(PatchField, m->npatches);
    for (int p = 0; p < m->npatches; p++) {
        PatchField *pf = &f->pf[p];
        const char *pt = m->patches[p].type;
        pf->type = mem_strdup(field_type_constraint(pt) ? pt : default_type);
        pf->n = m->patches[p].size;
        if (field_type_needs_value(pf->type)) {
            size_t npv = (size_t)pf->n * (size_t)width;
            pf->value = MEM_NEW(double, npv);
            for (int i = 0; i < pf->n; i++)
                for (int k = 0; k < width; k++) pf->value[(size_t)i * width + k] = uniform[k];
        }
    }
}

void field_free(Field *f)
{
    if (!f) return;
    for (int p = 0; p < f->npatches && f->pf; p++) {
        free(f->pf[p].type);
        free(f->pf[p].value);
        if (f->pf[p].extra) dict_free(f->pf[p].extra);
    }
    for (int k = 0; k < FIELD_NKEEP; k++)
        if (f->keep[k]) dict_free(f->keep[k]);
    if (f->keep_bf) dict_free(f->keep_bf);
    for (int i = 0; i < f->nwarn; i++) free(f->warn[i]);
    free(f->warn);
    free(f->pf);
    free(f->v);
    free(f->name);
    memset(f, 0, sizeof *f);
}

long field_first_nonfinite(const Field *f)
{
    size_t n = (size_t)f->ncells * (size_t)f->width;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(f->v[i])) return (long)(i / (size_t)f->width);
    return -1;
}

/* ---- dimensions ---- */

typedef struct Unit {
    const char *name;
    double dims[7];
} Unit;

/* OpenFOAM's SI unit set (etc/controlDict DimensionSets) without the
   scaled units (cm, mm, km), which OpenFOAM refuses in fields too. */
static const Unit units[] = {
    {"kg", {1, 0, 0, 0, 0, 0, 0}},           {"m", {0, 1, 0, 0, 0, 0, 0}},
    {"s", {0, 0, 1, 0, 0, 0, 0}},            {"K", {0, 0, 0, 1, 0, 0, 0}},
    {"mol", {0, 0, 0, 0, 1, 0, 0}},          {"A", {0, 0, 0, 0, 0, 1, 0}},
    {"Cd", {0, 0, 0, 0, 0, 0, 1}},           {"cd", {0, 0, 0, 0, 0, 0, 1}},
    {"Hz", {0, 0, -1, 0, 0, 0, 0}},          {"N", {1, 1, -2, 0, 0, 0, 0}},
    {"Pa", {1, -1, -2, 0, 0, 0, 0}},         {"J", {1, 2, -2, 0, 0, 0, 0}},
    {"W", {1, 2, -3, 0, 0, 0, 0}},           {"area", {0, 2, 0, 0, 0, 0, 0}},
    {"volume", {0, 3, 0, 0, 0, 0, 0}},       {"density", {1, -3, 0, 0, 0, 0, 0}},
    {"acceleration", {0, 1, -2, 0, 0, 0, 0}}, {"kinematicPressure", {0, 2, -2, 0, 0, 0, 0}},
    {NULL, {0}}};

/* Adds the factors of one unit word ("m", "s^-1", "kg/m^3", "N*m") to
   dims; sign is the exponent sign the first factor carries. */
static int add_unit_word(const char *w, double dims[7], const DictNode *nd, Err *e)
{
    double sign = 1;
    const char *s = w;
    while (*s) {
        const char *a = s;
        while (*s && *s != '^' && *s != '/' && *s != '*') s++;
        size_t len = (size_t)(s - a);
        double ex = 1;
        if (*s == '^') {
            char *end;
            ex = strtod(s + 1, &end);
            if (end == s + 1)
                return err_set(e, nd->file, nd->line, "bad exponent in unit '%s' of dimensions", w);
            s = end;
        }
        const Unit *u = NULL;
        for (int i = 0; units[i].name && len; i++)
            if (strlen(units[i].name) == len && strncmp(units[i].name, a, len) == 0) u = &units[i];
        if (!u)
            return err_set(e, nd->file, nd->line,
                           "unknown unit '%.*s' in dimensions (known: kg m s K mol A Cd Hz N Pa J "
                           "W, or 7 exponents)",
                           (int)len, a);
        for (int k = 0; k < 7; k++) dims[k] += sign * ex * u->dims[k];
        sign = 1;
        if (*s == '/' || *s == '*') {
            sign = *s == '/' ? -1 : 1;
            s++;
            if (!*s) return err_set(e, nd->file, nd->line, "unit '%s' of dimensions ends with an operator", w);
        } else if (*s) {
            return err_set(e, nd->file, nd->line, "bad unit '%s' in dimensions", w);
        }
    }
    return 0;
}

int field_read_dims(const Dict *d, const char *file, double dims[7], Err *e)
{
    const DictEntry *en = dict_find(d, "dimensions");
    if (!en) return err_set(e, file, 0, "missing keyword 'dimensions'");
    const DictNode *nd = dict_entry_value(en, e);
    if (!nd) return -1;
    if (nd->kind != DN_DIMS)
        return err_set(e, nd->file, nd->line, "dimensions: expected [kg m s K mol A cd] exponents, found %s",
                       dict_node_kind_name(nd));
    memset(dims, 0, 7 * sizeof *dims);
    size_t nnum = 0;
    for (size_t i = 0; i < nd->n; i++) nnum += nd->items[i]->kind == DN_NUMBER;
    if (nnum == nd->n) {
        if (nd->n != 7 && nd->n != 5)
            return err_set(e, nd->file, nd->line, "dimensions: expected 7 exponents, found %zu", nd->n);
        for (size_t i = 0; i < nd->n; i++) dims[i] = nd->items[i]->num;
        return 0;
    }
    for (size_t i = 0; i < nd->n; i++) {
        const DictNode *it = nd->items[i];
        if ((it->kind != DN_WORD && it->kind != DN_STRING) || !it->text)
            return err_set(e, it->file, it->line, "dimensions: mixes exponents and unit words (%s)",
                           dict_node_kind_name(it));
        if (add_unit_word(it->text, dims, it, e)) return -1;
    }
    return 0;
}

/* ---- values: "uniform X" / "nonuniform List<T> N(...)" ---- */

static long first_nonfinite(const double *v, size_t n, int width)
{
    for (size_t i = 0; i < n * (size_t)width; i++)
        if (!isfinite(v[i])) return (long)(i / (size_t)width);
    return -1;
}

/* What a value entry describes, for messages. */
typedef struct ValueCtx {
    const char *what;   /* "internalField", "boundaryField.inlet.value" */
    const char *whole;  /* "the mesh", "patch 'inlet'" */
    const char *unit;   /* "cells", "faces" */
} ValueCtx;

static int nonfinite_err(const DictNode *nd, const ValueCtx *c, long i, Err *e)
{
    return err_set(e, nd->file, nd->line, "%s has a non-finite value (nan or inf) at index %ld", c->what, i);
}

/* A value written nan or inf (a word to the parser, as to OpenFOAM, which
   refuses it: "expected scalar value, found word 'nan'"): named with its
   own line, its cell or face (all of them for a uniform value), and its
   text.  0 when there is none. */
static int nonfinite_word_err(const DictNode *nd, const ValueCtx *c, int uniform, Err *e)
{
    size_t i;
    const DictNode *w = dict_node_nonfinite(nd, &i);
    if (!w) return 0;
    int ul = (int)strlen(c->unit) - 1;   /* "cells" -> "cell" */
    if (uniform) return err_set(e, w->file, w->line, "%s has a non-finite value (nan or inf) at index 0: the uniform "
                                                     "value holds '%s', not a finite number", c->what, w->text);
    return err_set(e, w->file, w->line, "%s has a non-finite value (nan or inf) at index %zu: %.*s %zu is '%s', not a "
                                        "finite number", c->what, i, ul, c->unit, i, w->text);
}

/* The numbers of a uniform value: a number (width 1) or a tuple. */
static int uniform_value(const DictNode *nd, int width, const ValueCtx *c, double out[3], Err *e)
{
    if (nonfinite_word_err(nd, c, 1, e)) return -1;
    size_t n = 0;
    double *v = NULL;
    if (nd->kind == DN_NUMBER) {
        v = mem_alloc(sizeof *v);
        v[0] = nd->num;
        n = 1;
    } else if (nd->kind == DN_NUMS) {
        n = nd->n * (size_t)nd->width;
        v = MEM_NEW(double, n);
        memcpy(v, nd->v, n * sizeof *v);
    } else if (nd->kind == DN_LIST || nd->kind == DN_LABELS) {
        if (dict_node_scalars(nd, 1, &v, &n, e)) return -1;
    }
    if (n != (size_t)width) {
        free(v);
        return err_set(e, nd->file, nd->line, "%s: uniform value must be %s, found %s", c->what,
                       width == 1 ? "a number" : "a vector (x y z)", dict_node_kind_name(nd));
    }
    memcpy(out, v, n * sizeof *v);
    free(v);
    if (first_nonfinite(out, 1, width) >= 0) return nonfinite_err(nd, c, 0, e);
    return 0;
}

/* Reads a value entry into a new array of count*width numbers. */
static int read_values(const DictEntry *en, int width, int count, const ValueCtx *c, double **out, Err *e)
{
    const char *file = en->file;
    if (en->nvals < 2 || en->vals[0]->kind != DN_WORD)
        return err_set(e, file, en->line, "%s: expected 'uniform' or 'nonuniform' followed by values", c->what);
    const char *kw = en->vals[0]->text;
    size_t nv = (size_t)count * (size_t)width;
    if (strcmp(kw, "uniform") == 0) {
        if (en->nvals != 2) return err_set(e, file, en->line, "%s: one value expected after 'uniform'", c->what);
        double u[3];
        if (uniform_value(en->vals[1], width, c, u, e)) return -1;
        double *v = MEM_NEW(double, nv);
        for (size_t i = 0; i < (size_t)count; i++) memcpy(v + i * width, u, (size_t)width * sizeof *u);
        *out = v;
        return 0;
    }
    if (strcmp(kw, "nonuniform") != 0)
        return err_set(e, file, en->line, "%s: expected 'uniform' or 'nonuniform', found '%s'", c->what, kw);
    size_t k = 1;
    if (en->vals[k]->kind == DN_WORD && strncmp(en->vals[k]->text, "List<", 5) == 0) {
        const char *want = width == 1 ? "List<scalar>" : "List<vector>";
        if (strcmp(en->vals[k]->text, want) != 0)
            return err_set(e, file, en->vals[k]->line, "%s: expected %s, found %s", c->what, want,
                           en->vals[k]->text);
        k++;
    }
    /* "200 (" with the size and the list on one line: the parser keeps
       the size as a number of its own (in "arc 1 5 (x y z)" it is one), so
       the size is checked here, where a list is known to follow */
    const DictNode *size_nd = NULL;
    if (k + 2 == en->nvals && en->vals[k]->kind == DN_NUMBER && en->vals[k]->is_int)
        size_nd = en->vals[k++];
    if (k + 1 != en->nvals)
        return err_set(e, file, en->line, "%s: expected one list after 'nonuniform'", c->what);
    DictNode *nd = en->vals[k];
    if (size_nd && size_nd->num != (double)dict_node_len(nd))
        return err_set(e, file, size_nd->line, "%s: list size %.0f does not match the %zu items read", c->what,
                       size_nd->num, dict_node_len(nd));
    size_t n;
    if (nd->kind == DN_NUMBER && nd->is_int && nd->num == 0) {
        n = 0; /* a zero-size binary list is written as its size alone */
    } else if (nd->kind == DN_LIST || nd->kind == DN_NUMS || nd->kind == DN_LABELS) {
        n = dict_node_len(nd);
    } else {
        return err_set(e, nd->file, nd->line, "%s: expected a list after 'nonuniform', found %s", c->what,
                       dict_node_kind_name(nd));
    }
    if (n != (size_t)count)
        return err_set(e, file, en->line, "%s has %zu values, %s has %d %s", c->what, n, c->whole, count,
                       c->unit);
    if (nonfinite_word_err(nd, c, 0, e)) return -1;
    double *v = NULL;
    size_t got = 0;
    if (n == 0) {
        v = MEM_NEW(double, 1);
    } else if (dict_node_take_scalars(nd, width, &v, &got, e)) {
        return -1;
    } else if (got != n) {
        free(v);
        return err_set(e, nd->file, nd->line, "%s: expected %zu items of %d numbers", c->what, n, width);
    }
    long bad = first_nonfinite(v, n, width);
    if (bad >= 0) {
        free(v);
        return nonfinite_err(nd, c, bad, e);
    }
    *out = v;
    return 0;
}

/* ---- boundaryField look-up ---- */

/* True when patch p belongs to group g: listed in its inGroups (written
   "1(wall)" or "List<word> 2(wall a)"), or its type is g and that type is
   wall or a constraint type, which OpenFOAM adds to the groups itself. */
static int patch_in_group(const Patch *p, const char *g)
{
    if (p->type && strcmp(p->type, "patch") != 0 && strcmp(p->type, g) == 0) return 1;
    const char *s = p->groups;
    size_t gl = strlen(g);
    while (s && *s) {
        while (*s && (isspace((unsigned char)*s) || *s == '(' || *s == ')')) s++;
        const char *a = s;
        while (*s && !isspace((unsigned char)*s) && *s != '(' && *s != ')') s++;
        if ((size_t)(s - a) == gl && strncmp(a, g, gl) == 0) return 1;
    }
    return 0;
}

/* The entry of boundaryField for each patch; NULL for a patch of a
   constraint type that has no entry by name or group: it takes its own
   type, which is what OpenFOAM gives empty patches and, through the usual
   #includeEtc "caseDicts/setConstraintTypes" (ignored by dict.c), the
   other constraint types. */
static int match_patches(const Dict *bf, const Mesh *m, const char *file, const DictEntry **pe, int *set,
                         Err *e)
{
    int np = m->npatches;
    for (int p = 0; p < np; p++) {
        pe[p] = NULL;
        set[p] = 0;
        for (size_t i = 0; i < bf->n; i++) {
            const DictEntry *en = &bf->entries[i];
            if (en->dict && !en->is_regex && strcmp(en->key, m->patches[p].name) == 0) {
                pe[p] = en;
                set[p] = 1;
            }
        }
    }
    for (size_t i = bf->n; i-- > 0;) {
        const DictEntry *en = &bf->entries[i];
        if (!en->dict || en->is_regex) continue;
        for (int p = 0; p < np; p++)
            if (!set[p] && patch_in_group(&m->patches[p], en->key)) {
                pe[p] = en;
                set[p] = 1;
            }
    }
    for (int p = 0; p < np; p++) {
        if (set[p]) continue;
        if (field_type_constraint(m->patches[p].type)) {
            set[p] = 1;
            continue;
        }
        const DictEntry *en = dict_find(bf, m->patches[p].name);
        if (en && en->dict) {
            pe[p] = en;
            set[p] = 1;
            continue;
        }
        return err_set(e, file, 0, "boundaryField has no entry for patch '%s'", m->patches[p].name);
    }
    return 0;
}

/* ---- extras: entries copied verbatim ---- */

static void mark_regex(Dict *d, const char *key)
{
    for (size_t i = 0; i < d->n; i++)
        if (strcmp(d->entries[i].key, key) == 0) d->entries[i].is_regex = 1;
}

static int copy_entries(const Dict *src, Dict *dst, int skip_type_value, Err *e);

static int copy_entry(const DictEntry *en, Dict *dst, Err *e)
{
    if (en->dict) {
        if (copy_entries(en->dict, dict_add_subdict(dst, en->key), 0, e)) return -1;
    } else {
        Buf t;
        buf_init(&t);
        for (size_t k = 0; k < en->nvals; k++) {
            if (k) buf_putc(&t, ' ');
            dict_write_node(en->vals[k], &t);
        }
        buf_putc(&t, '\0');
        int rc = dict_set(dst, en->key, t.p, e);
        buf_free(&t);
        if (rc) return -1;
    }
    if (en->is_regex) mark_regex(dst, en->key);
    return 0;
}

static int copy_entries(const Dict *src, Dict *dst, int skip_type_value, Err *e)
{
    for (size_t i = 0; i < src->n; i++) {
        const DictEntry *en = &src->entries[i];
        if (skip_type_value && !en->is_regex && (!strcmp(en->key, "type") || !strcmp(en->key, "value")))
            continue;
        if (copy_entry(en, dst, e)) return -1;
    }
    return 0;
}

/* ---- kept entries: what a rewrite must not lose ---- */

static void add_warning(Field *f, const char *msg)
{
    f->warn = mem_realloc(f->warn, sizeof *f->warn * (size_t)(f->nwarn + 1));
    f->warn[f->nwarn++] = mem_strdup(msg);
}

static int keep_entry(Dict **dst, const DictEntry *en, const char *file, Err *e)
{
    if (!en->key[0] && !en->is_regex)
        return err_set(e, en->file, en->line, "a value without a keyword in a field file");
    if (!*dst) *dst = dict_new(file);
    return copy_entry(en, *dst, e);
}

/* Top-level entries other than FoamFile, dimensions, internalField and
   boundaryField, each in the place after as many of those three as came
   before it in the file. */
static int keep_top(Field *f, const Dict *d, const char *file, Err *e)
{
    static const char *const known[] = {"dimensions", "internalField", "boundaryField"};
    int place = 0;
    for (size_t i = 0; i < d->n; i++) {
        const DictEntry *en = &d->entries[i];
        if (!en->is_regex && !strcmp(en->key, "FoamFile")) continue;
        int k = 0;
        while (k < 3 && (en->is_regex || strcmp(en->key, known[k]) != 0)) k++;
        if (k < 3) place++;
        else if (keep_entry(&f->keep[place < FIELD_NKEEP ? place : FIELD_NKEEP - 1], en, file, e)) return -1;
    }
    return 0;
}

/* Whether name is a patch of the mesh or a group of one of its patches. */
static int names_patch(const Mesh *m, const char *name)
{
    for (int p = 0; p < m->npatches; p++)
        if (!strcmp(m->patches[p].name, name) || patch_in_group(&m->patches[p], name)) return 1;
    return 0;
}

/* The boundaryField entries no patch took (pe: each patch's entry). */
static int keep_unused(Field *f, const Dict *bf, const Mesh *m, const DictEntry *const *pe, const char *file, Err *e)
{
    for (size_t i = 0; i < bf->n; i++) {
        const DictEntry *en = &bf->entries[i];
        int used = 0;
        for (int p = 0; p < m->npatches && !used; p++) used = pe[p] == en;
        if (used) continue;
        if (keep_entry(&f->keep_bf, en, file, e)) return -1;
        if (!en->is_regex && !names_patch(m, en->key)) {
            char msg[600];
            snprintf(msg, sizeof msg,
                     "%s:%d: boundaryField entry '%.200s' names no patch or patch group of the mesh (a typo, or a "
                     "patch the mesh no longer has?): not used, and kept when the field is written back",
                     en->file, en->line, en->key);
            add_warning(f, msg);
        }
    }
    return 0;
}

/* ---- reading ---- */

static int read_patch(PatchField *pf, const Patch *patch, const DictEntry *en, int width, Err *e)
{
    pf->n = patch->size;
    if (!en) {
        pf->type = mem_strdup(patch->type);
        return 0;
    }
    const Dict *pd = en->dict;
    const char *type;
    if (dict_word(pd, "type", &type, e)) return -1;
    const DictEntry *tw = dict_find(pd, "type");
    const DictNode *tn = dict_entry_value(tw, NULL);
    if (!tn || tn->kind != DN_WORD) /* a quoted or numeric type could not be written back */
        return err_set(e, tw->file, tw->line, "patch '%s': type must be a word, found %s", patch->name,
                       tn ? dict_node_kind_name(tn) : "several values");
    /* OpenFOAM refuses a basic type on a constraint patch; unknown types
       may derive from the constraint (fan on cyclic) and are let through */
    if (field_type_constraint(patch->type) && strcmp(type, patch->type) != 0 &&
        (field_type_needs_value(type) || field_type_valueless(type))) {
        const DictEntry *te = dict_find(pd, "type");
        return err_set(e, te->file, te->line, "patch '%s' is of type %s in the mesh: its field type must be %s, found %s",
                       patch->name, patch->type, patch->type, type);
    }
    pf->type = mem_strdup(type);
    const DictEntry *ve = dict_find(pd, "value");
    if (ve && ve->dict) ve = NULL;
    if (!ve && field_type_needs_value(type))
        return err_set(e, en->file, en->line, "patch '%s': type %s needs a value entry", patch->name, type);
    if (ve && !field_type_valueless(type)) {
        char what[512];
        char whole[300];
        snprintf(what, sizeof what, "boundaryField.%s.value", patch->name);
        snprintf(whole, sizeof whole, "patch '%s'", patch->name);
        ValueCtx c = {what, whole, "faces"};
        if (read_values(ve, width, patch->size, &c, &pf->value, e)) return -1;
    }
    size_t nextra = 0;
    for (size_t i = 0; i < pd->n; i++)
        nextra += pd->entries[i].is_regex || (strcmp(pd->entries[i].key, "type") && strcmp(pd->entries[i].key, "value"));
    if (nextra) {
        pf->extra = dict_new(en->key);
        if (copy_entries(pd, pf->extra, 1, e)) return -1;
    }
    return 0;
}

static int read_class(const Dict *d, const char *file, int *width, Err *e)
{
    const char *cls = dict_header_class(d);
    const DictEntry *ce = dict_find_scoped(d, "FoamFile.class");
    int line = ce ? ce->line : 0;
    if (!cls) return err_set(e, file, 0, "no FoamFile class; expected volScalarField or volVectorField");
    if (strcmp(cls, "volScalarField") == 0)
        *width = 1;
    else if (strcmp(cls, "volVectorField") == 0)
        *width = 3;
    else
        return err_set(e, file, line, "expected volScalarField or volVectorField, found %s", cls);
    return 0;
}

static char *base_name(const char *path)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t l = strlen(b);
    if (l > 3 && strcmp(b + l - 3, ".gz") == 0) l -= 3;
    return mem_strndup(b, l);
}

static int read_body(Field *f, const Mesh *m, const Dict *d, const char *file, Err *e)
{
    if (read_class(d, file, &f->width, e)) return -1;
    const DictEntry *obj = dict_find_scoped(d, "FoamFile.object");
    const char *oname = obj && obj->nvals == 1 && obj->vals[0]->text ? obj->vals[0]->text : NULL;
    f->name = oname ? mem_strdup(oname) : base_name(file);
    if (field_read_dims(d, file, f->dims, e)) return -1;
    const DictEntry *ie = dict_find(d, "internalField");
    if (!ie || ie->dict) return err_set(e, file, 0, "missing keyword 'internalField'");
    ValueCtx c = {"internalField", "the mesh", "cells"};
    if (read_values(ie, f->width, m->ncells, &c, &f->v, e)) return -1;
    f->ncells = m->ncells;
    const Dict *bf = dict_subdict(d, "boundaryField", e);
    if (!bf) return -1;
    f->npatches = m->npatches;
    f->pf = MEM_NEW(PatchField, m->npatches);
    const DictEntry **pe = MEM_NEW(const DictEntry *, m->npatches);
    int *set = MEM_NEW(int, m->npatches);
    int rc = match_patches(bf, m, file, pe, set, e);
    for (int p = 0; p < m->npatches && rc == 0; p++)
        rc = read_patch(&f->pf[p], &m->patches[p], pe[p], f->width, e);
    if (rc == 0) rc = keep_unused(f, bf, m, pe, file, e);
    if (rc == 0) rc = keep_top(f, d, file, e);
    for (size_t i = 0; rc == 0 && i < dict_nwarnings(d); i++) add_warning(f, dict_warning(d, i));
    free(pe);
    free(set);
    return rc;
}

int field_read(Field *f, const Mesh *m, const char *path, Err *e)
{
    memset(f, 0, sizeof *f);
    Dict *d = dict_read(path, e);
    if (!d) return -1;
    const char *file = d->file ? d->file : path;
    int rc = read_body(f, m, d, file, e);
    dict_free(d);
    if (rc) field_free(f);
    return rc;
}

/* Skips blanks and C/C++ comments. */
static const char *skip_space(const char *s, const char *end)
{
    while (s < end) {
        if (isspace((unsigned char)*s)) {
            s++;
        } else if (s + 1 < end && s[0] == '/' && s[1] == '/') {
            while (s < end && *s != '\n') s++;
        } else if (s + 1 < end && s[0] == '/' && s[1] == '*') {
            const char *q = s + 2;
            while (q + 1 < end && !(q[0] == '*' && q[1] == '/')) q++;
            s = q + 1 < end ? q + 2 : end;
        } else {
            break;
        }
    }
    return s;
}

int field_probe(const char *path, char **cls, Err *e)
{
    *cls = NULL;
    Buf b;
    buf_init(&b);
    char *found = NULL;
    if (io_read_file(path, &b, &found, e)) return -1;
    /* Only the FoamFile block is parsed: the data may be large. */
    const char *end = b.p + b.n;
    const char *s = skip_space(b.p, end);
    int rc = 0;
    if ((size_t)(end - s) > 8 && strncmp(s, "FoamFile", 8) == 0) {
        const char *close = memchr(s, '}', (size_t)(end - s));
        Dict *d = close ? dict_parse(s, (size_t)(close + 1 - s), found, e) : NULL;
        if (!close) rc = err_set(e, found, 0, "unterminated FoamFile header");
        else if (!d) rc = -1;
        const char *c = d ? dict_header_class(d) : NULL;
        if (c) {
            *cls = mem_strdup(c);
            rc = !strcmp(c, "volScalarField") ? 1 : !strcmp(c, "volVectorField") ? 3 : 0;
        }
        if (d) dict_free(d);
    }
    free(found);
    buf_free(&b);
    return rc;
}

/* ---- writing ---- */

static int all_equal(const double *v, size_t n, int width)
{
    if (n == 0) return 0;
    for (size_t i = 1; i < n; i++)
        if (memcmp(v, v + i * (size_t)width, (size_t)width * sizeof *v) != 0) return 0;
    return 1;
}

/* OpenFOAM's layout: the keyword padded to 16 columns after the indent. */
static void put_keyword(Buf *b, int indent, const char *key, int quoted)
{
    for (int i = 0; i < indent; i++) buf_putc(b, ' ');
    buf_printf(b, quoted ? "\"%s\"" : "%s", key);
    int pad = 16 - ((int)strlen(key) + 2 * quoted);
    if (pad < 1) pad = 1;
    for (int i = 0; i < pad; i++) buf_putc(b, ' ');
}

static void put_tuple(Buf *b, const double *x, int width, int precision)
{
    if (width == 1) {
        foam_put_double(b, x[0], precision);
        return;
    }
    buf_putc(b, '(');
    for (int k = 0; k < width; k++) {
        if (k) buf_putc(b, ' ');
        foam_put_double(b, x[k], precision);
    }
    buf_putc(b, ')');
}

/* "uniform X" or "nonuniform List<T> N(...)" followed by ";\n". */
static void put_values(Buf *b, const double *v, size_t n, int width, const FieldWriteOpts *o)
{
    int prec = o->binary ? 0 : o->precision;
    if (all_equal(v, n, width)) {
        buf_puts(b, "uniform ");
        put_tuple(b, v, width, prec);
        buf_puts(b, ";\n");
        return;
    }
    const char *tag = width == 1 ? "List<scalar>" : "List<vector>";
    if (n == 0) {
        if (o->binary)
            buf_printf(b, "nonuniform %s 0;\n", tag);
        else
            buf_puts(b, "nonuniform 0();\n");
        return;
    }
    buf_printf(b, "nonuniform %s \n", tag);
    foam_put_scalars(b, v, n, width, o->binary, prec);
    /* OpenFOAM closes a binary list with ");" on the same line */
    if (o->binary && b->n && b->p[b->n - 1] == '\n') b->p[--b->n] = '\0';
    buf_puts(b, ";\n");
}

/* Numbers per item of a contiguous List<T> tag (0: not contiguous, -1:
   label), the element types OpenFOAM writes raw in binary files. */
static int tag_width(const char *tag)
{
    static const struct {
        const char *tag;
        int width;
    } t[] = {{"List<scalar>", 1},     {"List<vector>", 3},          {"List<symmTensor>", 6},
             {"List<tensor>", 9},     {"List<sphericalTensor>", 1}, {"List<vector2D>", 2},
             {"List<label>", -1},     {NULL, 0}};
    for (int i = 0; tag && t[i].tag; i++)
        if (strcmp(tag, t[i].tag) == 0) return t[i].width;
    return 0;
}

/* A numeric list raw (binary) when its shape allows; returns 0 when done. */
static int put_raw_list(Buf *b, const DictNode *nd, int w)
{
    if (nd->kind != DN_NUMS && nd->kind != DN_LIST && nd->kind != DN_LABELS) return -1;
    size_t n;
    if (w < 0) {
        int *iv;
        if (dict_node_labels(nd, &iv, &n, NULL)) return -1;
        buf_putc(b, '\n');
        foam_put_labels(b, iv, n, 1);
        free(iv);
        return 0;
    }
    double *v;
    if (dict_node_scalars(nd, w, &v, &n, NULL)) return -1;
    buf_putc(b, '\n');
    foam_put_scalars(b, v, n, w, 1, 0);
    free(v);
    return 0;
}

/* One primitive extra entry; in binary files numeric lists after a
   contiguous List<T> tag go raw, as OpenFOAM's binary reader expects. */
static void put_extra_value(Buf *b, const DictEntry *en, int binary)
{
    const char *tag = NULL;
    for (size_t k = 0; k < en->nvals; k++) {
        const DictNode *nd = en->vals[k];
        if (k) buf_putc(b, ' ');
        int w = tag_width(tag);
        tag = nd->kind == DN_WORD && nd->text && !strncmp(nd->text, "List<", 5) ? nd->text : NULL;
        if (binary && w && put_raw_list(b, nd, w) == 0) continue;
        dict_write_node(nd, b);
    }
}

static void put_entries(Buf *b, const Dict *d, int indent, int binary);

static void put_entry(Buf *b, const DictEntry *en, int indent, int binary)
{
    if (en->dict) {
        for (int s = 0; s < indent; s++) buf_putc(b, ' ');
        buf_printf(b, en->is_regex ? "\"%s\"\n" : "%s\n", en->key);
        for (int s = 0; s < indent; s++) buf_putc(b, ' ');
        buf_puts(b, "{\n");
        put_entries(b, en->dict, indent + 4, binary);
        for (int s = 0; s < indent; s++) buf_putc(b, ' ');
        buf_puts(b, "}\n");
        return;
    }
    put_keyword(b, indent, en->key, en->is_regex);
    put_extra_value(b, en, binary);
    buf_puts(b, ";\n");
}

static void put_entries(Buf *b, const Dict *d, int indent, int binary)
{
    for (size_t i = 0; i < d->n; i++) put_entry(b, &d->entries[i], indent, binary);
}

/* Kept top-level entries, each followed by a blank line as OpenFOAM
   lays out the top level. */
static void put_kept(Buf *b, const Dict *d, int binary)
{
    for (size_t i = 0; d && i < d->n; i++) {
        put_entry(b, &d->entries[i], 0, binary);
        buf_putc(b, '\n');
    }
}

static void put_patch(Buf *b, const Field *f, const Patch *patch, const PatchField *pf, const FieldWriteOpts *o)
{
    buf_printf(b, "    %s\n    {\n", patch->name);
    put_keyword(b, 8, "type", 0);
    buf_printf(b, "%s;\n", pf->type);
    if (pf->value && !mesh_type_is_empty(pf->type)) {
        put_keyword(b, 8, "value", 0);
        put_values(b, pf->value, (size_t)pf->n, f->width, o);
    }
    if (pf->extra) put_entries(b, pf->extra, 8, o->binary);
    buf_puts(b, "    }\n");
}

int field_write(const Field *f, const Mesh *m, const char *path, const FieldWriteOpts *o, Err *e)
{
    if (f->ncells != m->ncells || f->npatches != m->npatches)
        return err_set(e, path, 0, "field %s has %d cells and %d patches, the mesh %d and %d", f->name,
                       f->ncells, f->npatches, m->ncells, m->npatches);
    /* a file OpenFOAM (and field_read) would refuse is never written */
    for (int p = 0; p < f->npatches; p++)
        if (field_type_needs_value(f->pf[p].type) && !f->pf[p].value)
            return err_set(e, path, 0, "field %s, patch '%s': type %s has no value", f->name ? f->name : "",
                           m->patches[p].name, f->pf[p].type);
    Buf b;
    buf_init(&b);
    char *obj = f->name ? NULL : base_name(path);
    foam_header(&b, f->width == 3 ? "volVectorField" : "volScalarField", o->location, f->name ? f->name : obj,
                o->binary, NULL);
    free(obj);
    put_kept(&b, f->keep[0], o->binary);
    buf_puts(&b, "dimensions      [");
    for (int k = 0; k < 7; k++) {
        if (k) buf_putc(&b, ' ');
        foam_put_double(&b, f->dims[k], 0);
    }
    buf_puts(&b, "];\n\n\n");
    put_kept(&b, f->keep[1], o->binary);
    put_keyword(&b, 0, "internalField", 0);
    put_values(&b, f->v, (size_t)f->ncells, f->width, o);
    buf_putc(&b, '\n');
    put_kept(&b, f->keep[2], o->binary);
    buf_puts(&b, "boundaryField\n{\n");
    for (int p = 0; p < f->npatches; p++) put_patch(&b, f, &m->patches[p], &f->pf[p], o);
    if (f->keep_bf) put_entries(&b, f->keep_bf, 4, o->binary);
    buf_puts(&b, "}\n\n");
    put_kept(&b, f->keep[3], o->binary);
    foam_footer(&b);
    int rc = io_write_atomic(path, b.p, b.n, o->gzip, e);
    buf_free(&b);
    return rc;
}
