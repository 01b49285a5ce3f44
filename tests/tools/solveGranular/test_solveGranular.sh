#!/usr/bin/env bash
# test_solveGranular.sh: solveGranular, model Newtonian (eq. 5.1, 4.66),
# end to end on small 2-D cases built with blockGrid, cutCells, mergeCells,
# voronoiGrid and setFields:
#   - -help lists every keyword of every dictionary it reads;
#   - rest: a closed box rotated 30 degrees to the grid (16 x 16, cut and
#     merged; and the same as a Voronoi grid), rho = 1, U = 0, noSlip, no
#     gravity: max |U| <= 1e-12 after 1000 steps (fixed deltaT 1e-3);
#   - conservation: the rotated box with a density jump (setFields: rho 2
#     in a disc), slip walls, 400 steps: the total mass changes by at most
#     1e-12 relative at every step (the log's "change since start");
#   - channel: 20 x 4 cells (L = 1), inflow fixedValue U (1 0 0) with
#     zeroGradient rho, outflow fixedValue rho 1 with zeroGradient U (the
#     well-posed pair, bc_check_open), slip walls, from the inflow state
#     with a density bump of 0.2 (0.3 < x < 0.5) to t = 8: both ends
#     reflect sound (a velocity node at the inlet, a pressure node at the
#     outlet), so the total mass rings in the quarter-wave mode of period
#     T = 4 L c/(c^2 - u^2) = 1.9596 (c^2 = RsT = 6, u = 1): the spacing of
#     its maxima after t = 1.5 within 3 % of T (measured 1.95-1.99), each
#     maximum above the mean lower than the one before (the mode decays),
#     and the bump gone: max |rho - 1| <= 0.035 at t = 8 (measured 0.028,
#     the mode's amplitude);
#   - bad input: a misspelt model keyword, an unknown boundary type, a
#     field without an entry for a patch of the grid, fvSolution with an
#     unknown solver, an unknown gravitySchemes entry, multilinear
#     interpolation on the Voronoi grid (refused, fv/interp_ml.c): each a
#     file:line message, exit 1, no time step run and no time directory
#     written;
#   - restart: 120 steps in one run against 60 steps (stopAt nextWrite,
#     binary) and a restart from there (startFrom latestTime): the last
#     time directories are identical (cmp of rho, U, p, uniform/time);
#   - a time step far too large (Courant number 3.5, adjustTimeStep off):
#     the density goes negative at t = 0.2; the run stops with exit 1 and
#     a message naming the cell, after writing the last good state (0.15);
#   - SIGINT 1 s into the steps of a long run: exit 0, "Stopped by signal" in the
#     log, and the last time directory holds rho, U, p and uniform/time.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf sg && mkdir sg && cd sg || exit 1

. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/cases.sh"

# setup DIR CONTROL UWALL: controlDict (CONTROL entries), schemes, solvers,
# properties, and fields rho = 1, U = 0 with U's walls of type UWALL
setup() {
    { H controlDict; echo "application solveGranular; startFrom latestTime; startTime 0; stopAt endTime; $2"; } \
        >"$1/system/controlDict"
    { H fvSchemes; echo 'divSchemes { default Gauss upwind; } interpolationSchemes { default shepard; }'; } \
        >"$1/system/fvSchemes"
    { H fvSolution; echo 'solvers { "U.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; } }'; } \
        >"$1/system/fvSolution"
    { H granularProperties; echo 'model Newtonian; NewtonianCoeffs { mu 0.01; RsT 6; }'; } \
        >"$1/constant/granularProperties"
    { H rho volScalarField; echo 'dimensions [1 -3 0 0 0 0 0]; internalField uniform 1;'
      echo 'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }'; } >"$1/0/rho"
    { H U volVectorField; echo 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);'
      echo "boundaryField { \".*\" { type $3; } frontAndBack { type empty; } }"; } >"$1/0/U"
}

# ---- -help ----
h=$("$BIN/solveGranular" -help 2>&1)
missing=
for k in startFrom endTime deltaT writeControl purgeWrite adjustTimeStep maxCo maxDeltaT model NewtonianCoeffs mu RsT \
    'div(phi,U)' 'div(phi,rho)' gravitySchemes wellBalanced cellSource shepardCoeffs beta radius boundarySources solver preconditioner tolerance relTol maxIter \
    petscOptions constant/g; do
    printf '%s\n' "$h" | grep -qF -- "$k" || missing="$missing $k"
done
[ -z "$missing" ] && pass solveGranular_help || fail solveGranular_help "missing:$missing"

# ---- rest: cut and merged, and Voronoi ----
for kind in cut voronoi; do
    c=rest_$kind
    if ! rotbox $c $kind; then fail rest_$kind "grid tools failed"; continue; fi
    setup $c 'endTime 1; deltaT 0.001; writeControl timeStep; writeInterval 1000; writeFormat ascii; writePrecision 17;' noSlip
    t0=$(date +%s.%N)
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    t1=$(date +%s.%N)
    steps=$(grep -c '^Time = ' $c/log)
    d=$(maxdev $c "$(lasttime $c)" U "0 0 0")
    if [ $rc -eq 0 ] && [ "$steps" -eq 1000 ] && le "$d" 1e-12; then
        pass rest_$kind "max |U| $d after $steps steps ($(awk -v a=$t0 -v b=$t1 'BEGIN{printf "%.1f", b-a}') s)"
    else
        fail rest_$kind "rc $rc, $steps steps, max |U| $d"
    fi
done

# ---- conservation: density jump, slip walls ----
c=cons
if rotbox $c; then
    setup $c 'endTime 1; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl timeStep; writeInterval 400; writeFormat ascii;' slip
    sed -i 's/endTime 1;/endTime 1000;/; s/stopAt endTime/stopAt nextWrite/' $c/system/controlDict
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( cylinderToCell { p1 (0.45 0.5 -1); p2 (0.45 0.5 1); radius 0.15;'
      echo '  fieldValues ( volScalarFieldValue rho 2 ); } );'; } >$c/system/setFieldsDict
    "$BIN/setFields" -case $c >$c/log.setFields 2>&1
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    worst=$(sed -n 's/.*change since start = \([^ ]*\) (relative)/\1/p' $c/log |
            awk '{ v = $1 < 0 ? -$1 : $1; if (v > m) m = v } END { printf "%.3e", m + 0 }')
    steps=$(grep -c '^Time = ' $c/log)
    u=$(maxdev $c "$(lasttime $c)" U "0 0 0")
    if [ $rc -eq 0 ] && [ "$steps" -eq 400 ] && le "$worst" 1e-12 && ! le "$u" 1e-3; then
        pass mass_conserved "largest relative change $worst over $steps steps (max |U| $u)"
    else
        fail mass_conserved "rc $rc, $steps steps, largest relative change $worst, max |U| $u"
    fi
else
    fail mass_conserved "grid tools failed"
fi

# ---- channel: inflow to outflow ----
c=chan
grid $c 20 4 1 0.2
"$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
setup $c 'endTime 8; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; writeInterval 2; writeFormat ascii; writePrecision 12;' slip
{ H rho volScalarField; echo 'dimensions [1 -3 0 0 0 0 0]; internalField uniform 1;'
  echo 'boundaryField { inlet { type zeroGradient; } outlet { type fixedValue; value uniform 1; } walls { type zeroGradient; } frontAndBack { type empty; } }'; } >$c/0/rho
{ H U volVectorField; echo 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);'
  echo 'boundaryField { inlet { type fixedValue; value uniform (1 0 0); } outlet { type zeroGradient; } walls { type slip; } frontAndBack { type empty; } }'; } >$c/0/U
sed -i 's/internalField uniform (0 0 0)/internalField uniform (1 0 0)/' $c/0/U
rm -rf chan0 && cp -r $c chan0   # the bad-input cases start from this
{ H setFieldsDict
  echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( boxToCell { box (0.3 -1 -1) (0.5 1 1);'
  echo '  fieldValues ( volScalarFieldValue rho 1.2 ); } );'; } >$c/system/setFieldsDict
"$BIN/setFields" -case $c >$c/log.setFields 2>&1
d0=$(maxdev $c 0 rho 1)
"$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
last=$(lasttime $c)
dr=$(maxdev $c "$last" rho 1)
# the maxima of the total mass (a parabola through each local maximum and
# its two neighbours): "count mean-spacing smallest-spacing largest-spacing decaying"
wave=$(awk '/^Time = /{t=$3} /^Total mass/{sub(",", "", $4); print t, $4}' $c/log | /usr/bin/python3 -c '
import sys
d = [tuple(map(float, l.split())) for l in sys.stdin]
peaks = []
for (t0, m0), (t1, m1), (t2, m2) in zip(d, d[1:], d[2:]):
    if m1 > m0 and m1 >= m2 and t1 > 1.5:
        den = (t0 - t1) * (t0 - t2) * (t1 - t2)
        a = (t2 * (m1 - m0) + t1 * (m0 - m2) + t0 * (m2 - m1)) / den
        b = (t2 * t2 * (m0 - m1) + t1 * t1 * (m2 - m0) + t0 * t0 * (m1 - m2)) / den
        peaks.append((-b / (2 * a), m1))
gaps = [q[0] - p[0] for p, q in zip(peaks, peaks[1:])]
decay = all(q[1] < p[1] for p, q in zip(peaks, peaks[1:]))
print("%d %.4f %.4f %.4f %d" % (len(peaks), sum(gaps) / max(len(gaps), 1), min(gaps or [0]), max(gaps or [0]), decay))')
read -r npk period gmin gmax decays <<<"$wave"
T=1.9596
if [ $rc -eq 0 ] && [ "$last" = 8 ] && le 0.19 "$d0" && [ "${npk:-0}" -ge 3 ] && [ "${decays:-0}" = 1 ] &&
    le "$(rel "$gmin" $T)" 0.03 && le "$(rel "$gmax" $T)" 0.03 && le "$dr" 0.035; then
    pass channel_quarter_wave "$npk maxima of the mass, spacing $gmin .. $gmax (mean $period; 4Lc/(c^2-u^2) = $T), decaying; t = 8: max |rho - 1| $dr"
else
    fail channel_quarter_wave "rc $rc, last time $last, $npk maxima, spacing $gmin .. $gmax (T = $T), decaying $decays, max |rho - 1| $dr"
fi

# ---- bad input ----
# bad NAME FILE SED PATTERN [CASE]: edits a copy of the channel case (or
# CASE) and expects PATTERN on stderr, exit 1, no step and no new time
# directory
bad() {
    local src=${5:-chan0}
    rm -rf bad_$1 && mkdir bad_$1 && cp -r $src/system $src/constant $src/0 bad_$1/
    sed -i "$3" bad_$1/$2
    before=$(listing bad_$1)
    "$BIN/solveGranular" -case bad_$1 >bad_$1.out 2>bad_$1.err; local rc=$?
    if [ $rc -eq 1 ] && grep -qE -- "$4" bad_$1.err && ! grep -q '^Time = ' bad_$1.out &&
        [ "$before" = "$(listing bad_$1)" ]; then
        pass bad_$1 "$(head -n 1 bad_$1.err)"
    else
        fail bad_$1 "rc $rc, stderr: $(head -n 2 bad_$1.err | tr '\n' ' ')"
    fi
}
bad model_keyword constant/granularProperties 's/^model Newtonian/modle Newtonian/' 'granularProperties:[0-9]+: .*modle'
bad model_word constant/granularProperties 's/^model Newtonian/model Newtonain/' 'granularProperties:[0-9]+: .*Newtonain'
bad boundary_type 0/U 's/type slip;/type slipp;/' '0/U:[0-9]+: .*slipp'
bad patch_missing 0/rho 's/outlet { type fixedValue; value uniform 1; }//' '0/rho(:[0-9]+)?: .*outlet'
bad solver system/fvSolution 's/PBiCGStab/PBiCGStabb/' 'fvSolution:[0-9]+: .*PBiCGStabb'
bad div_scheme system/fvSchemes 's/Gauss upwind/Gauss linear/' 'fvSchemes:[0-9]+: .*Gauss upwind'
bad gravity_scheme system/fvSchemes 's/interpolationSchemes/gravitySchemes { default wellBalancd; } interpolationSchemes/' \
    'fvSchemes:[0-9]+: .*wellBalancd'
bad multilinear_voronoi system/fvSchemes 's/default shepard/default multilinear/' \
    'fvSchemes:[0-9]+: interpolation scheme multilinear is not available on Voronoi grids .*choose shepard' rest_voronoi

# ---- restart: bit-identical continuation from binary output ----
c=rs
if rotbox $c; then
    setup $c 'endTime 1000; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl timeStep; writeInterval 60; writeFormat binary;' slip
    sed -i 's/stopAt endTime/stopAt nextWrite/' $c/system/controlDict
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( boxToCell { box (0.3 0.3 -1) (0.5 0.7 1);'
      echo '  fieldValues ( volScalarFieldValue rho 1.5 ); } );'; } >$c/system/setFieldsDict
    "$BIN/setFields" -case $c >$c/log.setFields 2>&1
    rm -rf rs2 && cp -r $c rs2
    sed -i 's/writeInterval 60/writeInterval 120/' $c/system/controlDict
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc1=$?      # 120 steps in one run
    "$BIN/solveGranular" -case rs2 >rs2/log1 2>&1; rc2=$?   # 60 steps
    sed -i 's/stopAt nextWrite/stopAt endTime/; s/endTime 1000/endTime '"$(lasttime $c)"'/' rs2/system/controlDict
    "$BIN/solveGranular" -case rs2 >rs2/log2 2>&1; rc3=$?   # restart, to the same end
    a=$(lasttime $c); b=$(lasttime rs2); same=yes
    for f in rho U p uniform/time; do cmp -s "$c/$a/$f" "rs2/$b/$f" || same="no ($f differs)"; done
    n2=$(grep -c '^Time = ' rs2/log2)
    if [ $rc1$rc2$rc3 = 000 ] && [ "$a" = "$b" ] && [ "$same" = yes ] && [ "$n2" -eq 60 ]; then
        pass restart_identical "time $a after 120 steps = 60 + 60 restarted, files identical"
    else
        fail restart_identical "rc $rc1 $rc2 $rc3, times $a and $b, $n2 steps after the restart, identical: $same"
    fi
else
    fail restart_identical "grid tools failed"
fi

# ---- a negative density stops the run after writing the last good state ----
rm -rf blow && mkdir blow && cp -r chan0/system chan0/constant chan0/0 blow/
sed -i 's/internalField uniform (1 0 0)/internalField uniform (0 0 0)/' blow/0/U
sed -i 's/adjustTimeStep yes;/adjustTimeStep no;/; s/deltaT 0.001;/deltaT 0.05;/; s/writeInterval 2;/writeInterval 0.1;/' \
    blow/system/controlDict
"$BIN/solveGranular" -case blow >blow/log 2>blow/err; rc=$?
if [ $rc -eq 1 ] && grep -q 'Time = 0.2: cell [0-9]* at .*density <= 0' blow/err &&
    grep -q 'last good state is in time 0.15' blow/err && [ -s blow/0.15/rho ] && [ -s blow/0.15/uniform/time ] &&
    [ ! -d blow/0.2 ]; then
    pass negative_density_stops "$(head -n 1 blow/err | cut -c1-120)"
else
    fail negative_density_stops "rc $rc, stderr: $(tr '\n' ' ' <blow/err)"
fi

# ---- SIGINT writes the current state and stops ----
c=sig
grid $c 64 64 1 1
"$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
setup $c 'endTime 1000; deltaT 0.0001; writeControl timeStep; writeInterval 100000; writeFormat binary;' noSlip
sed -i 's/inlet { type fixedValue; value uniform (1 0 0); }//' $c/0/U
"$BIN/solveGranular" -case $c >$c/log 2>&1 &
pid=$!
# the signal once the steps run (a slow start, as under the sanitizers,
# must not meet it before the handler is in place)
for _ in $(seq 600); do grep -q '^Time = ' $c/log 2>/dev/null && break; sleep 0.1; done
sleep 1
kill -INT $pid
wait $pid; rc=$?
last=$(lasttime $c); complete=yes
for f in rho U p uniform/time; do [ -s "$c/$last/$f" ] || complete="no ($f missing)"; done
if [ $rc -eq 0 ] && [ "$last" != 0 ] && [ "$complete" = yes ] && grep -q '^Stopped by signal 2' $c/log &&
    grep -q "^End" $c/log; then
    pass sigint_writes "stopped at time $last after $(grep -c '^Time = ' $c/log) steps, time directory complete"
else
    fail sigint_writes "rc $rc, last time $last, complete: $complete"
fi
