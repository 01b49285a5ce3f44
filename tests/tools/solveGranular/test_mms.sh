#!/usr/bin/env bash
# test_mms.sh: the short version of the manufactured-solution study
# (tests/validation/mms, make validate; doc/validation.md): model
# Newtonian with its source hook (newtonian.h, "Sources"), a steady flow
# with noSlip walls run to the steady state on each level:
#   - mms -check: the generated exact solution against finite differences,
#     a zero source changes nothing bit for bit, a continuity source adds
#     exactly its mass, a failing hook fails the step and keeps the state;
#   - the disc cut and merged, shepard, Gauss upwind, N = 16, 32: observed
#     L1 orders of rho and |u| >= 0.8 (measured 1.52, 1.11) and L1 errors
#     at N = 32 below 2e-3 and 8e-3 (measured 1.41e-3, 5.51e-3; without the
#     source the flow runs down to rest: orders 0.00, errors 5.7e-2, 0.33);
#   - the same with Gauss limitedLinear 1: orders >= 1.2 (measured 1.55,
#     1.71);
#   - the disc as a Voronoi grid with two layers, upwind: orders >= 0.4
#     (measured 0.57, 1.21: the transition from the layers to the
#     Cartesian seeds is not linear-exact, see doc/validation.md);
#   - the ball cut and merged (3-D, maxSkewness 0), upwind, N = 8, 12:
#     orders >= 0.8 (measured 1.09, 1.46);
# model granular (c, u, T with yield; the sources of all three equations
# through the hook, T's included; doc/validation.md, "Granular
# manufactured solutions"):
#   - mms -check's gran_* checks: the sources against fv/closure.h, the
#     temperature hook, the heating of the face-based Jacobian on cut cells;
#   - the disc cut and merged, shepard, Gauss upwind, N = 16, 32: L1
#     orders of c, |u| and T >= 0.8 (measured 1.55, 1.66, 1.68) and the
#     errors of T at N = 32: L1 below 3.2e-3 and L-inf below 1.6e-2
#     (measured 2.25e-3, 9.72e-3; with eq. 4.65's Jacobian weight 4.60e-3
#     and 3.45e-2; without the hook's T source, s_T = 1.1 to 7.6, the
#     temperature falls far below the solution).
# About 15 s.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
MMS=${KIESEL_TESTBIN:-$(cd "$(dirname "$0")/../../.." && pwd)/build/release/tests}/mms
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
if [ ! -x "$MMS" ]; then fail mms "$MMS is missing (make)"; exit 1; fi

"$MMS" -check

# study NAME ARGS...: the program's own PASS/FAIL lines, and its table kept
# in NAME.out
study() {
    local name=$1; shift
    "$MMS" "$@" >"$name.out" 2>&1
    grep -E '^(PASS|FAIL)' "$name.out"
    grep -qE '^(PASS|FAIL)' "$name.out" || fail "$name" "no verdict: $(tail -n 3 "$name.out")"
}

study disc_upwind -expect L1_rho=0.8 -expect L1_u=0.8 disc-cut shepard upwind 16 32
# the L1 errors at N = 32: columns 6 (rho) and 10 (|u|) of the table
row=$(awk '$1 == 32' disc_upwind.out)
e_rho=$(awk '{ print $6 }' <<<"$row") e_u=$(awk '{ print $10 }' <<<"$row")
if [ -n "$row" ] && le "$e_rho" 2e-3 && le "$e_u" 8e-3; then
    pass mms_disc_errors "L1 rho $e_rho, L1 |u| $e_u at N = 32"
else
    fail mms_disc_errors "L1 rho '$e_rho' (<= 2e-3), L1 |u| '$e_u' (<= 8e-3) at N = 32"
fi
study disc_limited -expect L1_rho=1.2 -expect L1_u=1.2 disc-cut shepard limitedLinear 16 32
study disc_voronoi -expect L1_rho=0.4 -expect L1_u=0.4 disc-voronoi shepard upwind 16 32
study ball_upwind -maxSkewness 0 -expect L1_rho=0.8 -expect L1_u=0.8 ball-cut shepard upwind 8 12

# model granular
study gran_disc_upwind -model granular -expect L1_c=0.8 -expect L1_u=0.8 -expect L1_T=0.8 disc-cut shepard upwind 16 32
# the errors of T at N = 32: columns 14 (L1) and 16 (L-inf) of the table
row=$(awk '$1 == 32' gran_disc_upwind.out)
e_T=$(awk '{ print $14 }' <<<"$row") i_T=$(awk '{ print $16 }' <<<"$row")
if [ -n "$row" ] && le "$e_T" 3.2e-3 && le "$i_T" 1.6e-2; then
    pass mms_granular_disc_T "L1 T $e_T, L-inf T $i_T at N = 32"
else
    fail mms_granular_disc_T "L1 T '$e_T' (<= 3.2e-3), L-inf T '$i_T' (<= 1.6e-2) at N = 32"
fi
