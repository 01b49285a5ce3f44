/*
** cartcells_io.c: the file constant/polyMesh/cartesianCells (cartcells.h),
** a dictionary that mesh_io.c writes and reads beside the other extras:
**
**   n            (nx ny nz);                  cartesianGrid's counts
**   role         List<label> N(...);          per Cartesian cell
**   cell         List<label> N(...);          i + nx*(j + ny*k)
**   volume       List<scalar> N(...);
**   parentStart  List<label> ncells+1(...);   compact list-of-lists:
**   parents      List<label> M(...);          cell c's parents are
**                parents[parentStart[c] .. parentStart[c+1]-1]
**
** A dictionary of tagged lists, like a field's "nonuniform List<scalar>",
** because its lists differ in length and type: the parser reads the
** lists raw in a binary file (the List<T> tag says what they hold), and
** OpenFOAM skips the file as it skips every unknown polyMesh file.  Ascii
** numbers are the shortest decimals that read back to the same bits, so
** both formats round-trip exactly.  Reading checks sizes and ranges and
** names the file and line; the invariants between the lists are
** mesh_check_cartesian's (checkGrid), as the polyMesh ordering is
** mesh_check's.
*/
#include "buf.h"
#include "cartcells.h"
#include "dict.h"
#include "foam.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* "key List<T> " then the list, closed by ";" as OpenFOAM closes a
   binary list (on the line of its ')'). */
static void put_tag(Buf *b, const char *key, const char *tag)
{
    buf_printf(b, "%-13s%s ", key, tag);
}

static void end_list(Buf *b)
{
    if (b->n && b->p[b->n - 1] == '\n') b->n--;
    buf_puts(b, ";\n\n");
}

size_t cartcells_size_hint(const Mesh *m, int binary)
{
    size_t n = (size_t)m->cartcells.n, nc = (size_t)m->ncells;
    return (binary ? 16 * n + 8 * nc : 48 * n + 20 * nc) + 4096;
}

void cartcells_put(Buf *b, const Mesh *m, int binary)
{
    const CartCells *cc = &m->cartcells;
    size_t n = (size_t)cc->n, nc = (size_t)m->ncells;
    buf_puts(b, "// roles: 0 outside, 1 whole, 2 cut, 3 master, 4 slave (doc/file-formats.md)\n\n");
    buf_printf(b, "%-13s(%d %d %d);\n\n", "n", m->cart.n[0], m->cart.n[1], m->cart.n[2]);
    put_tag(b, "role", "List<label>");
    foam_put_labels(b, cc->role, n, binary);
    end_list(b);
    put_tag(b, "cell", "List<label>");
    foam_put_labels(b, cc->cell, n, binary);
    end_list(b);
    put_tag(b, "volume", "List<scalar>");
    foam_put_scalars(b, cc->vol, n, 1, binary, 0);
    end_list(b);
    put_tag(b, "parentStart", "List<label>");
    foam_put_labels(b, cc->parent_off, nc + 1, binary);
    end_list(b);
    put_tag(b, "parents", "List<label>");
    foam_put_labels(b, cc->parent, (size_t)cc->parent_off[nc], binary);
    end_list(b);
}

/* The list node of entry `key`: "[List<T>] [N] list", or a lone 0 (an
   empty binary list); *empty set for that. */
static int find_list(const Dict *d, const char *key, const char *tag, const char *name, DictNode **nd,
                     int *empty, Err *e)
{
    const DictEntry *en = dict_find(d, key);
    if (!en || en->dict || en->nvals == 0) return err_set(e, name, 0, "keyword '%s' missing", key);
    size_t k = 0;
    if (en->vals[0]->kind == DN_WORD) {
        if (strcmp(en->vals[0]->text, tag) != 0)
            return err_set(e, name, en->line, "%s: expected %s, found '%s'", key, tag, en->vals[0]->text);
        k++;
    }
    const DictNode *size_nd = NULL;
    if (k + 2 == en->nvals && en->vals[k]->kind == DN_NUMBER && en->vals[k]->is_int) size_nd = en->vals[k++];
    if (k + 1 != en->nvals) return err_set(e, name, en->line, "%s: expected one list", key);
    *nd = en->vals[k];
    *empty = (*nd)->kind == DN_NUMBER && (*nd)->is_int && (*nd)->num == 0;
    if (!*empty && (*nd)->kind != DN_LIST && (*nd)->kind != DN_LABELS && (*nd)->kind != DN_NUMS)
        return err_set(e, name, en->line, "%s: expected a list, found %s", key, dict_node_kind_name(*nd));
    if (size_nd && size_nd->num != (double)(*empty ? 0 : dict_node_len(*nd)))
        return err_set(e, name, size_nd->line, "%s: list size %.0f does not match the items read", key, size_nd->num);
    return 0;
}

/* A label list of `want` items, each in lo..hi. */
static int read_labels(const Dict *d, const char *key, const char *name, long want, int lo, int hi, int **out,
                       Err *e)
{
    DictNode *nd;
    int empty;
    size_t n = 0;
    if (find_list(d, key, "List<label>", name, &nd, &empty, e)) return -1;
    if (empty)
        *out = MEM_NEW(int, 1);
    else if (dict_node_take_labels(nd, out, &n, e))
        return -1;
    if ((long)n != want)
        return err_set(e, name, nd->line, "%s: %zu labels, expected %ld", key, n, want);
    for (size_t i = 0; i < n; i++)
        if ((*out)[i] < lo || (*out)[i] > hi)
            return err_set(e, name, nd->line, "%s: label %zu is %d, outside %d..%d", key, i, (*out)[i], lo, hi);
    return 0;
}

static int read_volumes(const Dict *d, const char *name, long want, double **out, Err *e)
{
    DictNode *nd;
    int empty;
    size_t n = 0;
    if (find_list(d, "volume", "List<scalar>", name, &nd, &empty, e)) return -1;
    if (!empty && dict_node_nonfinite(nd, &n))
        return err_set(e, name, nd->line, "volume %zu is not a finite number", n);
    n = 0;
    if (empty)
        *out = MEM_NEW(double, 1);
    else if (dict_node_take_scalars(nd, 1, out, &n, e))
        return -1;
    if ((long)n != want) return err_set(e, name, nd->line, "volume: %zu values, expected %ld", n, want);
    for (size_t i = 0; i < n; i++)
        if (!((*out)[i] >= 0) || !isfinite((*out)[i]))
            return err_set(e, name, nd->line, "volume %zu is %g (a volume is finite and not negative)", i, (*out)[i]);
    return 0;
}

/* n must be cartesianGrid's. */
static int read_counts(const Mesh *m, const Dict *d, const char *name, Err *e)
{
    const DictEntry *en = dict_find(d, "n");
    if (!en) return err_set(e, name, 0, "keyword 'n' missing");
    if (m->cart.n[0] <= 0) return err_set(e, name, en->line, "cartesianCells needs cartesianGrid, which is missing");
    const DictNode *nd = dict_entry_value(en, e);
    int *n;
    size_t k;
    if (!nd || dict_node_labels(nd, &n, &k, e)) return -1;
    int same = k == 3 && n[0] == m->cart.n[0] && n[1] == m->cart.n[1] && n[2] == m->cart.n[2];
    free(n);
    if (!same)
        return err_set(e, name, en->line, "n: expected cartesianGrid's (%d %d %d)", m->cart.n[0], m->cart.n[1],
                       m->cart.n[2]);
    return 0;
}

int cartcells_read(Mesh *m, const Dict *d, const char *name, Err *e)
{
    CartCells *cc = &m->cartcells;
    if (read_counts(m, d, name, e)) return -1;
    long n = (long)m->cart.n[0] * m->cart.n[1] * m->cart.n[2];
    if (n > INT_MAX - 1) return err_set(e, name, 0, "%ld Cartesian cells are too many", n);
    cc->n = (int)n;
    if (read_labels(d, "role", name, n, 0, CART_NROLES - 1, &cc->role, e) ||
        read_labels(d, "cell", name, n, -1, m->ncells - 1, &cc->cell, e) || read_volumes(d, name, n, &cc->vol, e) ||
        read_labels(d, "parentStart", name, (long)m->ncells + 1, 0, INT_MAX - 1, &cc->parent_off, e))
        return -1;
    for (int c = 0; c < m->ncells; c++)
        if (cc->parent_off[c + 1] < cc->parent_off[c])
            return err_set(e, name, 0, "parentStart decreases at cell %d", c);
    if (cc->parent_off[0] != 0) return err_set(e, name, 0, "parentStart starts at %d, not 0", cc->parent_off[0]);
    return read_labels(d, "parents", name, cc->parent_off[m->ncells], 0, (int)n - 1, &cc->parent, e);
}
