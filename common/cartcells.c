/*
** cartcells.c: building, composing and checking the cut-cell data
** contract (cartcells.h; the file itself is cartcells_io.c).
**
** Building is a few counting passes over flat arrays: the parents of a
** cell are found by a counting sort of the Cartesian cells by the cell
** they name, taken in ascending order, so every list comes out sorted and
** the result never depends on the order cells were made in.  Merging
** only renames cells (newid) and re-counts; the roles of the members of a
** new cluster follow cellParent, which merge.c takes from the largest
** member, so the master of a cluster merged again is the master of its
** largest input cluster (merging twice composes).  The check recomputes
** everything it compares from the other side (counts from the parents'
** side, volumes from the geometry), so a corrupt file cannot pass by
** agreeing with itself.
*/
#include "cartcells.h"
#include "mem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *cartcells_role_name(int role)
{
    static const char *const names[CART_NROLES] = {"outside", "whole", "cut", "master", "slave"};
    return role >= 0 && role < CART_NROLES ? names[role] : "?";
}

void cartcells_free(CartCells *cc)
{
    free(cc->role);
    free(cc->cell);
    free(cc->vol);
    free(cc->parent_off);
    free(cc->parent);
    memset(cc, 0, sizeof *cc);
}

static void *dup_array(const void *p, size_t bytes)
{
    void *q = mem_alloc(bytes ? bytes : 1);
    if (bytes) memcpy(q, p, bytes);
    return q;
}

/* Cartesian cells of grid g, or 0 when it has none. */
static long cart_count(const CartGrid *g)
{
    if (g->n[0] <= 0 || g->n[1] <= 0 || g->n[2] <= 0) return 0;
    return (long)g->n[0] * g->n[1] * g->n[2];
}

/* The box volume of Cartesian cell K. */
static double box_volume(const CartGrid *g, long K)
{
    long i = K % g->n[0], j = (K / g->n[0]) % g->n[1], k = K / ((long)g->n[0] * g->n[1]);
    return (g->x[0][i + 1] - g->x[0][i]) * (g->x[1][j + 1] - g->x[1][j]) * (g->x[2][k + 1] - g->x[2][k]);
}

static void alloc_cart(CartCells *cc, long n)
{
    cc->n = (int)n;
    cc->role = MEM_NEW(int, (size_t)n);
    cc->cell = MEM_NEW(int, (size_t)n);
    cc->vol = MEM_NEW(double, (size_t)n);
    for (long K = 0; K < n; K++) cc->cell[K] = -1;
}

/* parent_off/parent from cc->cell: the Cartesian cells naming each cell,
   ascending. */
static void parents_from_cells(CartCells *cc, int ncells)
{
    int *off = MEM_NEW(int, (size_t)ncells + 1);
    for (int K = 0; K < cc->n; K++)
        if (cc->cell[K] >= 0) off[cc->cell[K] + 1]++;
    for (int c = 0; c < ncells; c++) off[c + 1] += off[c];
    int *next = dup_array(off, (size_t)ncells * sizeof(int));
    cc->parent = mem_alloc(sizeof(int) * ((size_t)off[ncells] + 1));
    for (int K = 0; K < cc->n; K++)
        if (cc->cell[K] >= 0) cc->parent[next[cc->cell[K]]++] = K;
    free(next);
    cc->parent_off = off;
}

int cartcells_build(const Mesh *m, const double *vol, const unsigned char *whole, CartCells *cc)
{
    memset(cc, 0, sizeof *cc);
    long n = cart_count(&m->cart);
    if (n <= 0 || n > 0x7fffffffL || !m->cell_parent) return -1;
    alloc_cart(cc, n);
    for (int c = 0; c < m->ncells; c++) {
        long K = m->cell_parent[c];
        if (K < 0 || K >= n || cc->cell[K] >= 0) {
            cartcells_free(cc);
            return -1;
        }
        double vk = box_volume(&m->cart, K);
        int w = whole ? whole[c] != 0 : fabs(vol[c] - vk) <= CARTCELLS_TOL * vk;
        cc->cell[K] = c;
        cc->role[K] = w ? CART_WHOLE : CART_CUT;
        cc->vol[K] = vol[c];
    }
    parents_from_cells(cc, m->ncells);
    return 0;
}

void cartcells_merge(const CartCells *in, const int *newid, const Mesh *out, CartCells *cc)
{
    memset(cc, 0, sizeof *cc);
    alloc_cart(cc, in->n);
    memcpy(cc->role, in->role, sizeof(int) * (size_t)in->n);
    memcpy(cc->vol, in->vol, sizeof(double) * (size_t)in->n);
    for (int K = 0; K < in->n; K++)
        if (in->cell[K] >= 0) cc->cell[K] = newid[in->cell[K]];
    parents_from_cells(cc, out->ncells);
    for (int C = 0; C < out->ncells; C++) {
        int lo = cc->parent_off[C], hi = cc->parent_off[C + 1];
        if (hi - lo < 2) continue;
        /* the master is the member cellParent names (merge.c: the
           largest member's), or failing that the largest part */
        int master = cc->parent[lo];
        for (int k = lo; k < hi; k++)
            if (cc->vol[cc->parent[k]] > cc->vol[master]) master = cc->parent[k];
        for (int k = lo; k < hi; k++)
            if (out->cell_parent && cc->parent[k] == out->cell_parent[C]) master = cc->parent[k];
        for (int k = lo; k < hi; k++) cc->role[cc->parent[k]] = cc->parent[k] == master ? CART_MASTER : CART_SLAVE;
    }
}

/* Index of the cell of a sorted coordinate list x[0..n] holding v
   (clamped: a seed on the box's surface belongs to the cell inside). */
static int locate(const double *x, int n, double v)
{
    int lo = 0, hi = n;
    while (hi - lo > 1) {
        int mid = lo + (hi - lo) / 2;
        if (x[mid] <= v)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static long seed_host(const CartGrid *g, const double *s)
{
    int ijk[3];
    for (int k = 0; k < 3; k++) ijk[k] = locate(g->x[k], g->n[k], s[k]);
    return ijk[0] + (long)g->n[0] * (ijk[1] + (long)g->n[1] * ijk[2]);
}

static double dist2_centre(const CartGrid *g, long K, const double *s)
{
    long ijk[3] = {K % g->n[0], (K / g->n[0]) % g->n[1], K / ((long)g->n[0] * g->n[1])};
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
        double d = s[k] - 0.5 * (g->x[k][ijk[k]] + g->x[k][ijk[k] + 1]);
        d2 += d * d;
    }
    return d2;
}

void cartcells_voronoi(const Mesh *m, const unsigned char *centre_seed, CartCells *cc)
{
    memset(cc, 0, sizeof *cc);
    const CartGrid *g = &m->cart;
    alloc_cart(cc, cart_count(g));
    int *nheld = MEM_NEW(int, (size_t)cc->n);
    cc->parent_off = MEM_NEW(int, (size_t)m->ncells + 1);
    cc->parent = mem_alloc(sizeof(int) * ((size_t)m->ncells + 1));
    for (int c = 0; c < m->ncells; c++) {
        const double *s = m->cell_seed + 3 * (size_t)c;
        long K = seed_host(g, s);
        cc->parent_off[c + 1] = c + 1;
        cc->parent[c] = (int)K;
        nheld[K]++;
        cc->vol[K] += m->cell_vol[c];
        if (cc->cell[K] < 0 || dist2_centre(g, K, s) < dist2_centre(g, K, m->cell_seed + 3 * (size_t)cc->cell[K]))
            cc->cell[K] = c;
    }
    for (int K = 0; K < cc->n; K++) {
        double vk = box_volume(g, K);
        int c = cc->cell[K];
        if (c < 0)
            cc->role[K] = CART_OUTSIDE;
        else if (nheld[K] == 1 && centre_seed[c] && fabs(m->cell_vol[c] - vk) <= CARTCELLS_TOL * vk)
            cc->role[K] = CART_WHOLE;
        else
            cc->role[K] = CART_CUT;
    }
    free(nheld);
}

/* ---- checking ---- */

/* "Cartesian cell K (i j k)" for messages. */
static const char *cart_name(const CartGrid *g, long K, char buf[96])
{
    long nxy = (long)g->n[0] * g->n[1];
    snprintf(buf, 96, "Cartesian cell %ld (%ld %ld %ld)", K, K % g->n[0], (K / g->n[0]) % g->n[1], K / nxy);
    return buf;
}

/* Per Cartesian cell: role, cell and volume in range. */
static int check_roles(const Mesh *m, double tol, Err *e)
{
    const CartCells *cc = &m->cartcells;
    char nm[96];
    for (long K = 0; K < cc->n; K++) {
        int r = cc->role[K], c = cc->cell[K];
        double vk = box_volume(&m->cart, K), v = cc->vol[K];
        if (r < 0 || r >= CART_NROLES)
            return err_set(e, NULL, 0, "cartesianCells: %s has role %d (0..4 expected)", cart_name(&m->cart, K, nm), r);
        if ((r == CART_OUTSIDE) != (c < 0) || c >= m->ncells)
            return err_set(e, NULL, 0, "cartesianCells: %s is %s but names cell %d", cart_name(&m->cart, K, nm),
                           cartcells_role_name(r), c);
        if (!(v >= 0) || !isfinite(v) || (r == CART_OUTSIDE && v != 0))
            return err_set(e, NULL, 0, "cartesianCells: %s (%s) has volume %g", cart_name(&m->cart, K, nm),
                           cartcells_role_name(r), v);
        if (r == CART_WHOLE && fabs(v - vk) > tol * vk)
            return err_set(e, NULL, 0, "cartesianCells: %s is whole but its volume %.17g is not its box's %.17g",
                           cart_name(&m->cart, K, nm), v, vk);
        if (!m->cell_seed && v > vk * (1 + tol))
            return err_set(e, NULL, 0, "cartesianCells: %s has volume %.17g, more than its box's %.17g",
                           cart_name(&m->cart, K, nm), v, vk);
    }
    return 0;
}

/* The parent lists: ascending, in range, at least one per cell (exactly
   one on a Voronoi grid), each parent naming its cell (on a Voronoi grid:
   a held cell names a cell that the Cartesian cell holds). */
static int check_parents(const Mesh *m, Err *e)
{
    const CartCells *cc = &m->cartcells;
    const int *off = cc->parent_off;
    char nm[96];
    int voronoi = m->cell_seed != NULL;
    if (off[0] != 0) return err_set(e, NULL, 0, "cartesianCells: parent offsets start at %d", off[0]);
    for (int c = 0; c < m->ncells; c++) {
        int np = off[c + 1] - off[c];
        if (np < 1 || (voronoi && np != 1))
            return err_set(e, NULL, 0, "cartesianCells: cell %d has %d parents (%s)", c, np,
                           voronoi ? "one on a Voronoi grid" : "at least one");
        for (int k = off[c]; k < off[c + 1]; k++) {
            int K = cc->parent[k];
            if (K < 0 || K >= cc->n || (k > off[c] && K <= cc->parent[k - 1]))
                return err_set(e, NULL, 0, "cartesianCells: cell %d: parent %d out of range or order", c, K);
            if (cc->role[K] == CART_OUTSIDE || (!voronoi && cc->cell[K] != c))
                return err_set(e, NULL, 0, "cartesianCells: cell %d lists %s as a parent, which names cell %d (%s)",
                               c, cart_name(&m->cart, K, nm), cc->cell[K], cartcells_role_name(cc->role[K]));
        }
    }
    return 0;
}

/* Whether cell c lists K among its parents (they are ascending). */
static int lists_parent(const CartCells *cc, int c, int K)
{
    int lo = cc->parent_off[c], hi = cc->parent_off[c + 1];
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (cc->parent[mid] == K) return 1;
        if (cc->parent[mid] < K)
            lo = mid + 1;
        else
            hi = mid;
    }
    return 0;
}

/* Cut and merged grids: K names c only if c lists K (with check_parents:
   exactly), the roles of a cell's parents, and the volumes per cell. */
static int check_cells(const Mesh *m, double tol, Err *e)
{
    const CartCells *cc = &m->cartcells;
    char nm[96];
    int *count = MEM_NEW(int, (size_t)m->ncells);
    int rc = 0;
    for (long K = 0; K < cc->n; K++)
        if (cc->cell[K] >= 0) count[cc->cell[K]]++;
    for (int c = 0; c < m->ncells && !rc; c++) {
        int lo = cc->parent_off[c], hi = cc->parent_off[c + 1], nmaster = 0, nother = 0;
        double sum = 0, box = 0;
        for (int k = lo; k < hi; k++) {
            int r = cc->role[cc->parent[k]];
            nmaster += r == CART_MASTER;
            nother += hi - lo == 1 ? r != CART_WHOLE && r != CART_CUT : r != CART_MASTER && r != CART_SLAVE;
            sum += cc->vol[cc->parent[k]];
            box += box_volume(&m->cart, cc->parent[k]);
        }
        if (count[c] != hi - lo) {
            long K = 0;
            while (cc->cell[K] != c || lists_parent(cc, c, (int)K)) K++;
            rc = err_set(e, NULL, 0, "cartesianCells: %s names cell %d, which does not list it as a parent",
                         cart_name(&m->cart, K, nm), c);
        } else if (nother || (hi - lo > 1 && nmaster != 1)) {
            long K = cc->parent[lo];
            rc = err_set(e, NULL, 0, "cartesianCells: cell %d has %d parents (first %s) with %d masters and "
                         "roles that do not fit (one whole or cut, or one master and slaves)", c, hi - lo,
                         cart_name(&m->cart, K, nm), nmaster);
        } else if (fabs(sum - m->cell_vol[c]) > tol * box) {
            rc = err_set(e, NULL, 0, "cartesianCells: cell %d: its parents' volumes sum to %.17g, its volume is "
                         "%.17g", c, sum, m->cell_vol[c]);
        }
    }
    free(count);
    return rc;
}

/* Voronoi grids: a Cartesian cell names one of the cells it holds, holds
   one cell when whole, and its volume is theirs; no merging roles. */
static int check_voronoi(const Mesh *m, double tol, Err *e)
{
    const CartCells *cc = &m->cartcells;
    char nm[96];
    double *sum = MEM_NEW(double, (size_t)cc->n);
    int *nheld = MEM_NEW(int, (size_t)cc->n);
    for (int c = 0; c < m->ncells; c++) {
        sum[cc->parent[c]] += m->cell_vol[c];
        nheld[cc->parent[c]]++;
    }
    int rc = 0;
    for (long K = 0; K < cc->n && !rc; K++) {
        int r = cc->role[K], c = cc->cell[K];
        if (r == CART_MASTER || r == CART_SLAVE)
            rc = err_set(e, NULL, 0, "cartesianCells: %s is %s on a Voronoi grid (no merging)",
                         cart_name(&m->cart, K, nm), cartcells_role_name(r));
        else if ((r == CART_OUTSIDE) != (nheld[K] == 0) || (r == CART_WHOLE && nheld[K] != 1) ||
                 (c >= 0 && cc->parent[c] != K))
            rc = err_set(e, NULL, 0, "cartesianCells: %s is %s, names cell %d, but holds the seeds of %d cells",
                         cart_name(&m->cart, K, nm), cartcells_role_name(r), c, nheld[K]);
        else if (fabs(sum[K] - cc->vol[K]) > tol * box_volume(&m->cart, K))
            rc = err_set(e, NULL, 0, "cartesianCells: %s has volume %.17g, the cells it holds %.17g",
                         cart_name(&m->cart, K, nm), cc->vol[K], sum[K]);
    }
    free(sum);
    free(nheld);
    return rc;
}

int mesh_check_cartesian(const Mesh *m, double tol, Err *e)
{
    const CartCells *cc = &m->cartcells;
    long n = cart_count(&m->cart);
    if (cc->n <= 0) return err_set(e, NULL, 0, "cartesianCells: the grid has no Cartesian cells data");
    if (n != cc->n)
        return err_set(e, NULL, 0, "cartesianCells: %d Cartesian cells, but cartesianGrid has %ld", cc->n, n);
    if (!m->cell_vol) return err_set(e, NULL, 0, "cartesianCells: cell volumes needed (mesh_geometry)");
    if (check_roles(m, tol, e) || check_parents(m, e)) return -1;
    return m->cell_seed ? check_voronoi(m, tol, e) : check_cells(m, tol, e);
}
