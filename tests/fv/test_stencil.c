/*
** test_stencil.c: sparse stencils (fv/stencil.h): rows built, repeated
** sources summed, applied to cell and boundary values; pair rows, which
** store nothing and give what the stored rows give, to the bit.
*/
#include <string.h>

#include "stencil.h"
#include "test.h"

TEST(rows)
{
    Stencil s;
    stencil_init(&s);
    for (int r = 0; r < 1000; r++) {
        if (r == 500) stencil_trim(&s); /* rows go on after a trim */
        stencil_add(&s, r % 7, 0.25);
        stencil_add(&s, 7 + r % 3, 0.5);
        stencil_add(&s, r % 7, 0.25);
        EXPECT(stencil_end_row(&s) == r, "row index");
    }
    stencil_end_row(&s);
    EXPECT(s.nrows == 1001 && s.off[1000] == 2000 && s.off[1001] == 2000, "rows %d, entries %d", s.nrows,
           s.off[s.nrows]);
    double xc[7] = {1, 2, 3, 4, 5, 6, 7}, xb[3] = {10, 20, 30};
    for (int r = 0; r < 1000; r++) {
        NEAR(stencil_row_sum(&s, r), 1.0, 0);
        NEAR(stencil_apply(&s, r, 7, xc, xb), 0.5 * xc[r % 7] + 0.5 * xb[r % 3], 1e-15);
    }
    NEAR(stencil_apply(&s, 1000, 7, xc, xb), 0.0, 0);
    stencil_free(&s);
}

/* The same rows stored and as pair rows: entries, lengths, sums and
   values (bit for bit, signed zeros included) agree; the pair rows hold
   no entries. */
TEST(pair_rows)
{
    enum { NP = 50 };
    int a[NP], b[NP];
    Stencil st, pr;
    stencil_init(&st);
    stencil_init(&pr);
    stencil_pairs(&pr, a, b, NP);
    for (int p = 0; p < NP; p++) {
        a[p] = p % 7;
        b[p] = (3 * p + 1) % 7;
        if (b[p] == a[p]) b[p] = (a[p] + 1) % 7;
        stencil_add(&st, a[p], 0.5);
        stencil_add(&st, b[p], 0.5);
        stencil_end_row(&st);
        stencil_add(&st, b[p], 1.0);
        stencil_end_row(&st);
        stencil_add(&st, a[p], 1.0);
        stencil_end_row(&st);
        if (p % 5 == 4) { /* a stored group among pair rows */
            for (int j = 0; j < STENCIL_GROUP; j++) {
                stencil_add(&pr, 7 + j, 1.0);
                stencil_end_row(&pr);
            }
            continue;
        }
        for (int j = 0; j < STENCIL_GROUP; j++) EXPECT(stencil_pair_row(&pr) == STENCIL_GROUP * p + j, "row index");
    }
    EXPECT(pr.off[pr.nrows] == 3 * (NP / 5), "pair rows store %d entries", pr.off[pr.nrows] - 3 * (NP / 5));
    double xc[7] = {1.5, -0.0, 3e-300, -4, 5.25, 1e300, -7}, xb[3] = {10, 20, 30};
    int bad = 0;
    for (int r = 0; r < st.nrows; r++) {
        if (r / STENCIL_GROUP % 5 == 4) continue;
        StencilRow x, y;
        stencil_row(&st, r, &x);
        stencil_row(&pr, r, &y);
        bad += !stencil_is_pair(&pr, r) || stencil_is_pair(&st, r) || x.n != y.n || stencil_row_len(&pr, r) != x.n;
        for (int k = 0; k < x.n && k < y.n; k++) bad += x.src[k] != y.src[k] || x.w[k] != y.w[k];
        double u = stencil_apply(&st, r, 7, xc, xb), v = stencil_apply(&pr, r, 7, xc, xb);
        double su = stencil_row_sum(&st, r), sv = stencil_row_sum(&pr, r);
        bad += memcmp(&u, &v, sizeof u) != 0 || su != sv;
    }
    EXPECT(bad == 0, "%d pair rows differ from the stored ones", bad);
    for (int r = 0; r < pr.nrows; r++)
        if (r / STENCIL_GROUP % 5 == 4)
            bad += stencil_is_pair(&pr, r) || stencil_apply(&pr, r, 7, xc, xb) != xb[r % STENCIL_GROUP];
    EXPECT(bad == 0, "%d stored rows among the pair rows misread", bad);
    stencil_free(&st);
    stencil_free(&pr);
}

int main(void)
{
    RUN(rows);
    RUN(pair_rows);
    return test_summary();
}
