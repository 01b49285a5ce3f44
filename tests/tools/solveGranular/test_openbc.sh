#!/usr/bin/env bash
# test_openbc.sh: solveGranular refuses ill-posed open boundaries before
# any step (fv/bc_open.c, bc_check_open; doc/theory.md §9 "Open
# boundaries").  On the 20 x 4 channel of test_solveGranular.sh, whose
# well-posed pair is inflow fixedValue U with zeroGradient rho and outflow
# fixedValue rho with zeroGradient U, each rejected combination on one
# patch:
#   - inlet_both_fixed      rho fixedValue, U fixedValue (subsonic, 1 m/s)
#   - inlet_both_free       rho zeroGradient, U zeroGradient
#   - outlet_both_free      rho zeroGradient, U zeroGradient
#   - outlet_both_fixed     rho fixedValue, U fixedValue
#   - outlet_calculated     rho calculated (a fixed value), U fixedValue
#   - outlet_slip_rho       rho slip (a zero gradient for a scalar), U
#                           zeroGradient
#   - inlet_transonic       rho fixedValue, U fixedValue (2.4, 1) whose
#                           normal part 2.4 is below sqrt(RsT) = 2.449
# each: exit 1, stderr "<case>/0/rho:<line of the patch's entry>: patch
# '<name>': ..." naming both conditions, U's file:line and the remedy, no
# step run, nothing written (the case's listing unchanged); and accepted:
#   - supersonic_inflow     rho and U fixed at an inflow of 3 m/s > c:
#                           every characteristic enters, both are due; runs;
#   - walls_not_open        noSlip U with fixedValue rho on the walls: a
#                           wall is not an open boundary; runs.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/channel.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf sgo && mkdir sgo && cd sgo || exit 1

channel_case base 'startFrom startTime; startTime 0; stopAt endTime; endTime 0.02; deltaT 0.001; writeControl timeStep;
writeInterval 10; writeFormat ascii;' || fail openbc_grid "blockGrid failed"

# fields DIR RHO_INLET RHO_OUTLET RHO_WALLS U_INLET U_OUTLET U_WALLS: 0/rho
# and 0/U with one patch entry per line: inlet on line 5, outlet on 6,
# walls on 7.
fields() {
    { H rho volScalarField
      echo 'dimensions [1 -3 0 0 0 0 0];'
      echo 'internalField uniform 1;'
      echo 'boundaryField {'
      echo "inlet { $2 }"
      echo "outlet { $3 }"
      echo "walls { $4 }"
      echo 'frontAndBack { type empty; } }'; } >"$1/0/rho"
    { H U volVectorField
      echo 'dimensions [0 1 -1 0 0 0 0];'
      echo 'internalField uniform (1 0 0);'
      echo 'boundaryField {'
      echo "inlet { $5 }"
      echo "outlet { $6 }"
      echo "walls { $7 }"
      echo 'frontAndBack { type empty; } }'; } >"$1/0/U"
}

ZG='type zeroGradient;'
RF='type fixedValue; value uniform 1;'
UF='type fixedValue; value uniform (1 0 0);'

# bad NAME PATTERN FIELDS...: expects exit 1, PATTERN on stderr, no step,
# nothing written
bad() {
    local n=$1 pat=$2; shift 2
    rm -rf "$n" && cp -r base "$n" && fields "$n" "$@"
    local before; before=$(listing "$n")
    "$BIN/solveGranular" -case "$n" >"$n.out" 2>"$n.err"; local rc=$?
    if [ $rc -eq 1 ] && grep -qE -- "$pat" "$n.err" && ! grep -q '^Time = ' "$n.out" &&
        [ "$before" = "$(listing "$n")" ]; then
        pass "openbc_$n" "$(head -n 1 "$n.err" | cut -c1-160)..."
    else
        fail "openbc_$n" "rc $rc, nothing written: $([ "$before" = "$(listing "$n")" ] && echo yes || echo no), stderr: $(head -n 2 "$n.err" | tr '\n' ' ')"
    fi
}

FIX='use fixedValue U with zeroGradient rho at an inflow, or fixedValue rho with zeroGradient U at an outflow'
FREE='use fixedValue rho with zeroGradient U at an outflow, or fixedValue U with zeroGradient rho at an inflow'
bad inlet_both_fixed "^inlet_both_fixed/0/rho:5: patch 'inlet': rho \(fixedValue\) and U \(fixedValue, inlet_both_fixed/0/U:5\) are both fixed: .*2 conditions at a subsonic inflow .*never 3 .*$FIX" \
    "$RF" "$RF" "$ZG" "$UF" "$ZG" 'type slip;'
bad inlet_both_free "^inlet_both_free/0/rho:5: patch 'inlet': neither rho \(zeroGradient\) nor U \(zeroGradient, inlet_both_free/0/U:5\) is fixed: .*$FREE" \
    "$ZG" "$RF" "$ZG" "$ZG" "$ZG" 'type slip;'
bad outlet_both_free "^outlet_both_free/0/rho:6: patch 'outlet': neither rho \(zeroGradient\) nor U \(zeroGradient, outlet_both_free/0/U:6\) is fixed" \
    "$ZG" "$ZG" "$ZG" "$UF" "$ZG" 'type slip;'
bad outlet_both_fixed "^outlet_both_fixed/0/rho:6: patch 'outlet': rho \(fixedValue\) and U \(fixedValue, outlet_both_fixed/0/U:6\) are both fixed" \
    "$ZG" "$RF" "$ZG" "$UF" "$UF" 'type slip;'
bad outlet_calculated "^outlet_calculated/0/rho:6: patch 'outlet': rho \(calculated\) and U \(fixedValue, outlet_calculated/0/U:6\) are both fixed" \
    "$ZG" 'type calculated; value uniform 1;' "$ZG" "$UF" "$UF" 'type slip;'
bad outlet_slip_rho "^outlet_slip_rho/0/rho:6: patch 'outlet': neither rho \(slip\) nor U \(zeroGradient, outlet_slip_rho/0/U:6\) is fixed" \
    "$ZG" 'type slip;' "$ZG" "$UF" "$ZG" 'type slip;'
bad inlet_transonic "^inlet_transonic/0/rho:5: patch 'inlet': rho \(fixedValue\) and U \(fixedValue, inlet_transonic/0/U:5\) are both fixed: .*u.n <= -sqrt\(RsT\) = -2.449" \
    "$RF" "$RF" "$ZG" 'type fixedValue; value uniform (2.4 1 0);' "$ZG" 'type slip;'

# good NAME FIELDS...: runs to the end (20 steps)
good() {
    local n=$1; shift
    rm -rf "$n" && cp -r base "$n" && fields "$n" "$@"
    "$BIN/solveGranular" -case "$n" >"$n.out" 2>"$n.err"; local rc=$?
    local steps; steps=$(grep -c '^Time = ' "$n.out")
    if [ $rc -eq 0 ] && [ "$steps" -eq 20 ]; then
        pass "openbc_$n" "$steps steps"
    else
        fail "openbc_$n" "rc $rc, $steps steps, stderr: $(head -n 2 "$n.err" | tr '\n' ' ')"
    fi
}
good supersonic_inflow "$RF" "$RF" "$ZG" 'type fixedValue; value uniform (3 0 0);' "$ZG" 'type slip;'
good walls_not_open "$ZG" "$RF" "$RF" "$UF" "$ZG" 'type noSlip;'

# steady_channel: the well-posed pair on the channel already in its steady
# state (rho 1, U (1 0 0) everywhere), adapting steps to t = 0.5: each
# solve starts at the solution, so its normalisation factor is round-off
# and PBiCGStab meets a breakdown at the exact solution; the run must treat
# that as converged (fv/linsolve.c) and keep the state to 1e-12.
rm -rf steady && channel_case steady 'startFrom startTime; startTime 0; stopAt endTime; endTime 0.5; deltaT 0.001;
adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; writeInterval 0.5; writeFormat ascii; writePrecision 17;'
"$BIN/solveGranular" -case steady >steady.out 2>steady.err; rc=$?
steps=$(grep -c '^Time = ' steady.out)
dev=$(awk '/^internalField/ { f = 1; next } f && /^\([-+0-9.]/ { gsub(/[()]/, ""); d = ($1 - 1) < 0 ? 1 - $1 : $1 - 1
      if ($2 < 0) $2 = -$2; if ($2 > d) d = $2; if (d > m) m = d } f && /^\)/ { exit } END { print m + 0 }' steady/0.5/U 2>/dev/null)
if [ $rc -eq 0 ] && [ "$steps" -gt 100 ] && awk -v d="${dev:-1}" 'BEGIN { exit !(d <= 1e-12) }'; then
    pass openbc_steady_channel "$steps steps, max |U - (1 0 0)| = $dev"
else
    fail openbc_steady_channel "rc $rc, $steps steps, max dev ${dev:-?}, stderr: $(head -n 2 steady.err | tr '\n' ' ')"
fi
