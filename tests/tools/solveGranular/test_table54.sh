#!/usr/bin/env bash
# test_table54.sh: the short version of thesis Table 5.4 (§5.2.1): the
# rotating granular disc with T frozen (tutorials/granular/rotatingDisc's
# case), cut cells (merged, M_V = 1/4, shepard) and the staircase
# Cartesian grid (cutCells method staircase, clamp c <= cMax - 0.01) at
# h = 1/25 and 1/50 against cut cells at h = 1/100, to t = 1 (the state is
# steady by then: the errors at t = 3 agree to 3 digits).
# tests/validation/rotatingDisc/disc.py checks
#   - the cut cells' L1 and Linf errors of c fall (measured 6.4e-5 ->
#     2.3e-5, order 1.50; 9.2e-4 -> 3.5e-4, order 1.41);
#   - the staircase's Linf does not (order < 0.3; measured 0.258 -> 0.380,
#     -0.56; the thesis's Cartesian Linf orders -0.50, -0.15, -0.09);
#   - the cut cells keep the mass to 1e-12 (measured 2.3e-14; the
#     staircase's corner piles reach the clamp and lose 5.7e-3 at 1/50);
#   - the cut cells' azimuthal spread is below the staircase's (5.9e-4
#     against 0.42 at 1/50).
# About 35 s of CPU (100 s on a loaded 2-core machine).
set -u
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
work=${KIESEL_TMP:-$(mktemp -d)}/table54
rm -rf "$work" && mkdir -p "$work" || exit 1
/usr/bin/python3 "$top/tests/validation/rotatingDisc/disc.py" "${KIESEL_BIN:-$top/bin}" "$work" \
    "$top/tutorials/granular/rotatingDisc" --levels 25,50 --ref 100 --end 1 --deltaC 1e-2 --quick
