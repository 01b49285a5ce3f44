/*
** test_stencil.c: sparse stencils (fv/stencil.h): rows built, repeated
** sources summed, applied to cell and boundary values.
*/
#include "stencil.h"
#include "test.h"

TEST(rows)
{
    Stencil s;
    stencil_init(&s);
    for (int r = 0; r < 1000; r++) {
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

int main(void)
{
    RUN(rows);
    return test_summary();
}
