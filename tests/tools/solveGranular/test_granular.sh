#!/usr/bin/env bash
# test_granular.sh: solveGranular, model granular (thesis eq. 2.37-2.47 by
# eq. 4.66; tools/solveGranular/granular.h), end to end on small 2-D cases:
#   - -help lists the granular keywords;
#   - homogeneous cooling without yield: a closed 4 x 4 box, c = 0.3,
#     u = 0, T = 1, epsilon0 = 1, cMax 0.64 (c0 0.5 above c): T(1) against
#     T_init / (1 + eps0 g(c) sqrt(T_init) t / 2)^2 at deltaT 0.04 ... 0.005;
#     the implicit dissipation is first order in time: observed orders
#     within 0.05 of 1 (measured 1.000), error at 0.005 <= 4.5e-4
#     (measured 4.27e-4), T uniform to 1e-13, U at round-off;
#   - homogeneous cooling with yield (c = 0.55 > c0 = 0.5, T0 = 1): against
#     an RK4 solution of dT/dt = -eps(c, T) T written here (4e5 steps), the
#     same orders (measured 0.991, 0.994, 0.996), error at 0.005 <= 7e-4
#     (measured 6.19e-4);
#   - viscous heating (eq. 4.65): plane shear u = (gamma y, 0) on an 8 x 8
#     block grid (noSlip floor, movingWall lid at gamma, zeroGradient
#     sides), no conduction and no dissipation (lambda0 = epsilon0 = 0),
#     one step of 1e-6: T^1 - T^0 = dt K_T eta gamma^2 / c in every cell to
#     1e-9 relative (the face-based Jacobian is exact for a linear field on
#     whole cells, wall cells included), for K_T = 2/3 and 1.5; and on
#     8 x 4 rectangular cells (h_x = h_y/2), where eq. 4.65's weight
#     alpha A_f / sum A_f gives (2/3)^2 of the heating (heatingSchemes
#     jacobian faceWeight; granular.h: the metrics of faceMetric and
#     leastSquares make it exact on any cell);
#   - rest: the closed box rotated 30 degrees to the grid, cut and merged,
#     and as a Voronoi grid, c = 0.4 uniform with yield (c0 0.3), T = 0.01,
#     no gravity: max |U| <= 1e-12 after 400 steps (measured 3.7e-21 and
#     1.7e-20);
#   - conservation: the rotated box with c 0.5 in a disc and 0.2 outside,
#     slip walls, 300 steps: the mass changes by at most 1e-12 relative at
#     every step and no limit acts;
#   - limits: a packing pushed to cMax by gravity against a wall: the log
#     counts the clamps ("Limits: c <= cMax - deltaC ...") and the run
#     finishes with c <= cMax - deltaC everywhere;
#   - partialSlip (eq. 2.35): a lid moving at 1 m/s over a dilute layer
#     (c 0.1, T 0.01) with Coulomb walls of 30 degrees everywhere: the run
#     finishes, the log counts the sliding faces and some slide (the wall
#     stress reaches p tan 30 under the lid); with frictionAngle 90 none
#     slide;
#   - restart: 40 steps against 20 + a restart (binary): alpha, U, Theta
#     and p identical;
#   - bad input: a missing cMax, c0 >= cMax, epsilon0 with grainDiameter,
#     alpha above cMax, Theta <= 0, fvSolution
#     without Theta, no Theta file, an unknown heatingSchemes wallVelocity
#     or jacobian:
#     each an error, exit 1, nothing written.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf gr && mkdir gr && cd gr || exit 1
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/cases.sh"

# gcase DIR CONTROL COEFFS C T UWALL: controlDict entries, granularCoeffs
# entries, uniform c and T, U = 0 with walls of type UWALL
gcase() {
    { H controlDict; echo "application solveGranular; startFrom latestTime; startTime 0; stopAt endTime; $2"; } \
        >"$1/system/controlDict"
    { H fvSchemes; echo 'divSchemes { default Gauss upwind; } interpolationSchemes { default shepard; }'; } \
        >"$1/system/fvSchemes"
    { H fvSolution; echo 'solvers { "U.*|Theta" { solver PBiCGStab; preconditioner DILU; tolerance 1e-14; relTol 0; } }'; } \
        >"$1/system/fvSolution"
    { H granularProperties; echo "model granular; granularCoeffs { $3 }"; } >"$1/constant/granularProperties"
    { H alpha volScalarField; echo "dimensions [0 0 0 0 0 0 0]; internalField uniform $4;"
      echo 'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }'; } >"$1/0/alpha"
    { H Theta volScalarField; echo "dimensions [0 2 -2 0 0 0 0]; internalField uniform $5;"
      echo 'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }'; } >"$1/0/Theta"
    { H U volVectorField; echo 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);'
      echo "boundaryField { \".*\" { type $6; } frontAndBack { type empty; } }"; } >"$1/0/U"
}

# cooling DIR DT COEFFS C: the closed 4 x 4 box to t = 1 with step DT
cooling() {
    grid "$1" 4 4 1 1 && "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1 || return 1
    gcase "$1" "endTime 1; deltaT $2; writeControl runTime; writeInterval 1; writeFormat ascii; writePrecision 17;" \
        "$3" "$4" 1 noSlip
    "$BIN/solveGranular" -case "$1" >"$1/log" 2>&1
}

# spread DIR TIME FIELD: max - min of a scalar field (ascii)
spread() {
    /usr/bin/python3 - "$1/$2/$3" <<'EOF'
import re, sys
t = open(sys.argv[1]).read().split('internalField', 1)[1]
m = re.match(r'\s*uniform', t)
v = [0.0] if m else [float(x) for x in re.search(r'\(([^()]*)\)', t).group(1).split()]
print('%.3e' % (max(v) - min(v)))
EOF
}

# order E1 E2: log2(E1/E2)
order() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", log(a / b) / log(2) }'; }

# cooling_study NAME COEFFS C EXACT MAXERR
cooling_study() {
    local name=$1 prev= worst=1 err= orders= dt
    for dt in 0.04 0.02 0.01 0.005; do
        local c=${name}_$dt
        if ! cooling $c $dt "$2" "$3"; then fail $name "run at deltaT $dt failed: $(tail -n 2 $c/log)"; return; fi
        err=$(maxdev $c 1 Theta "$4")
        local spread; spread=$(spread $c 1 Theta)
        le "$spread" 1e-13 || worst=0
        if [ -n "$prev" ]; then
            local o; o=$(order "$prev" "$err")
            orders="$orders $o"
            awk -v o="$o" 'BEGIN { exit !(o > 0.95 && o < 1.05) }' || worst=0
        fi
        echo "  $name: deltaT $dt  |T - T_ref| $err${prev:+  order $(order "$prev" "$err")}"
        prev=$err
    done
    if [ $worst = 1 ] && le "$err" "$5"; then pass $name "orders$orders, error $err at deltaT 0.005"
    else fail $name "orders$orders, error $err at deltaT 0.005 (want <= $5, orders 1 +- 0.05, T uniform)"; fi
}

# ---- -help ----
h=$("$BIN/solveGranular" -help 2>&1)
missing=
for k in granularCoeffs eta0 lambda0 epsilon0 grainDiameter restitution cMax c0 T0 KT freezeT deltaC Tmin cMin \
    'div(phi,Theta)' Theta alpha; do
    printf '%s\n' "$h" | grep -qF -- "$k" || missing="$missing $k"
done
[ -z "$missing" ] && pass granular_help || fail granular_help "missing:$missing"

# ---- homogeneous cooling ----
K='eta0 0.001; lambda0 0.00034; epsilon0 1; cMax 0.64; c0 0.5; T0 1;'
exact=$(awk 'BEGIN { g = 1 / (1 - 0.3 / 0.64); a = 1 + 0.5 * g; printf "%.17g", 1 / (a * a) }')
cooling_study cooling_kinetic "$K" 0.3 "$exact" 4.5e-4
# with yield: eps = eps0 g (sqrt(T) + T0 (c - c0) / (c sqrt(T))), RK4 here
ref=$(awk 'function f(T) { return -g * (T * sqrt(T) + (c - c0) / c * sqrt(T)) }
    BEGIN { c = 0.55; c0 = 0.5; g = 1 / (1 - c / 0.64); T = 1; n = 400000; h = 1 / n
            for (i = 0; i < n; i++) { k1 = f(T); k2 = f(T + h / 2 * k1); k3 = f(T + h / 2 * k2); k4 = f(T + h * k3)
                                      T += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4) }
            printf "%.17g", T }')
echo "  cooling_yield: T(1) by RK4 = $ref"
cooling_study cooling_yield "$K" 0.55 "$ref" 7e-4
grep -q 'K_T = 0.666667' cooling_yield_0.01/log && pass granular_log_KT || fail granular_log_KT "K_T not in the log"

# ---- viscous heating of a plane shear ----
# square cells (8 x 8) for both K_T, and rectangular ones (8 x 4: h_x = h_y / 2)
# with each heatingSchemes jacobian: faceMetric and leastSquares exact,
# faceWeight (eq. 4.65's alpha A_f / sum A_f) (2/3)^2 = 4/9 of it
for run in "0.666666666666666667 8 8 faceMetric 1" "1.5 8 8 faceMetric 1" "0.666666666666666667 8 4 faceMetric 1" \
           "0.666666666666666667 8 4 leastSquares 1" "0.666666666666666667 8 4 faceWeight 0.444444444444444444" \
           "0.666666666666666667 8 8 leastSquares 1" "0.666666666666666667 8 8 faceWeight 1"; do
    read -r kt nx ny jac share <<<"$run"
    c=shear_${kt}_${ny}_$jac
    name=granular_heating_KT$kt
    [ "$ny" = "$nx" ] || name=granular_heating_rect
    [ "$jac" = faceMetric ] || name=${name}_$jac
    mkdir -p $c && grid $c $nx $ny 1 1 && "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
    gcase $c 'endTime 1e-6; deltaT 1e-6; writeControl timeStep; writeInterval 1; writeFormat ascii; writePrecision 17;' \
        "eta0 0.01; lambda0 0; epsilon0 0; cMax 0.64; c0 0.5; T0 0; KT $kt;" 0.3 1 noSlip
    echo "heatingSchemes { jacobian $jac; }" >>$c/system/fvSchemes
    /usr/bin/python3 - $c/0/U $nx $ny <<'EOF'
import sys
gamma, nx, ny = 2.0, int(sys.argv[2]), int(sys.argv[3])
cells = ' '.join('(%.17g 0 0)' % (gamma * (j + 0.5) / ny) for j in range(ny) for i in range(nx))
t = open(sys.argv[1]).read().replace('internalField uniform (0 0 0);', 'internalField nonuniform List<vector> %d (%s);' % (nx * ny, cells))
t = t.replace('boundaryField {', 'boundaryField { inlet { type zeroGradient; } outlet { type zeroGradient; } '
              'walls { type movingWall; value uniform (2 0 0); } floor { type noSlip; }')
open(sys.argv[1], 'w').write(t)
EOF
    sed -i 's/yMin { name walls; type wall; }/yMin { name floor; type wall; }/' $c/system/blockGridDict
    "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    want=$(awk -v kt=$kt -v s=$share 'BEGIN { c = 0.3; g = 1 / (1 - c / 0.64); eta = 0.01 * c * g; printf "%.17g", 1 + s * 1e-6 * kt * eta * 4 / c }')
    d=$(maxdev $c 1e-06 Theta "$want")
    rl=$(awk -v d=$d -v w=$want 'BEGIN { printf "%.3e", d / (w - 1) }')
    if [ $rc -eq 0 ] && le "$rl" 1e-9; then pass $name "T^1 - T^0 within $rl of $share dt K_T eta gamma^2 / c ($nx x $ny cells, jacobian $jac)"
    else fail $name "rc $rc, relative error $rl ($nx x $ny cells, jacobian $jac); $(tail -n 2 $c/log)"; fi
done

# ---- rest: cut and merged, and Voronoi ----
for kind in cut voronoi; do
    c=rest_$kind
    if ! rotbox $c $kind; then fail granular_rest_$kind "grid tools failed"; continue; fi
    gcase $c 'endTime 0.4; deltaT 0.001; writeControl timeStep; writeInterval 400; writeFormat ascii; writePrecision 17;' \
        'eta0 0.0035; lambda0 0.00034; epsilon0 63.4921; cMax 0.64; c0 0.3; T0 0.5;' 0.4 0.01 noSlip
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    steps=$(grep -c '^Time = ' $c/log)
    d=$(maxdev $c "$(lasttime $c)" U "0 0 0")
    if [ $rc -eq 0 ] && [ "$steps" -eq 400 ] && le "$d" 1e-12; then pass granular_rest_$kind "max |U| $d after $steps steps"
    else fail granular_rest_$kind "rc $rc, $steps steps, max |U| $d"; fi
done

# ---- conservation ----
c=cons
if rotbox $c; then
    gcase $c 'endTime 1000; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl timeStep; writeInterval 300; writeFormat ascii;' \
        'eta0 0.0035; lambda0 0.00034; epsilon0 63.4921; cMax 0.64; c0 0.3; T0 0.5;' 0.2 0.01 slip
    sed -i 's/stopAt endTime/stopAt nextWrite/' $c/system/controlDict
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue alpha 0.2 ); regions ( cylinderToCell { p1 (0.45 0.5 -1); p2 (0.45 0.5 1); radius 0.15;'
      echo '  fieldValues ( volScalarFieldValue alpha 0.5 ); } );'; } >$c/system/setFieldsDict
    "$BIN/setFields" -case $c >$c/log.setFields 2>&1
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    worst=$(awk '/change since start/ { v = $NF; sub(/\(.*/, "", v); v = $9; if (v < 0) v = -v; if (v > w) w = v } END { printf "%.3e", w + 0 }' $c/log)
    steps=$(grep -c '^Time = ' $c/log)
    if [ $rc -eq 0 ] && [ "$steps" -eq 300 ] && le "$worst" 1e-12 && ! grep -q '^Limits' $c/log; then
        pass granular_conservation "worst relative mass change $worst over $steps steps"
    else fail granular_conservation "rc $rc, $steps steps, worst $worst"; fi
fi

# ---- limits: gravity packs a dense column against the floor ----
c=pack
mkdir -p $c && grid $c 4 8 0.1 0.2 && "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
gcase $c 'endTime 0.3; deltaT 1e-4; adjustTimeStep yes; maxCo 0.25; writeControl runTime; writeInterval 0.3; writeFormat ascii; writePrecision 17;' \
    'eta0 0.0001; lambda0 0.00034; epsilon0 10; cMax 0.64; c0 0.5; T0 0; deltaC 0.02;' 0.6 1 noSlip
{ H g uniformDimensionedVectorField; echo 'dimensions [0 1 -2 0 0 0 0]; value (0 -50 0);'; } >$c/constant/g
"$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
cmax=$(maxdev $c "$(lasttime $c)" alpha 0)
if [ $rc -eq 0 ] && grep -q '^Limits: c <= cMax - deltaC' $c/log && le "$cmax" 0.62000000001; then
    pass granular_limits "$(grep '^Limits' $c/log | tail -n 1), max c $cmax"
else fail granular_limits "rc $rc, max c $cmax, $(grep -c '^Limits' $c/log) limit lines; $(tail -n 2 $c/log)"; fi

# ---- partialSlip ----
for ang in 30 90; do
    c=pslip_$ang
    mkdir -p $c && grid $c 8 8 1 1 && "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
    gcase $c 'endTime 0.05; deltaT 1e-3; writeControl runTime; writeInterval 0.05; writeFormat ascii;' \
        'eta0 0.0035; lambda0 0.00034; epsilon0 63.4921; cMax 0.64; c0 0.3; T0 0.5;' 0.1 0.01 noSlip
    sed -i "s/\".\*\" { type noSlip; }/\".*\" { type partialSlip; frictionAngle $ang; } walls { type partialSlip; frictionAngle $ang; wallVelocity (1 0 0); }/" $c/0/U
    sed -i 's/yMin { name walls; type wall; }/yMin { name floor; type wall; }/; s/xMin { name inlet; }/xMin { name floor; type wall; }/; s/xMax { name outlet; }/xMax { name floor; type wall; }/' $c/system/blockGridDict
    "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
    "$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
    slides=$(awk '/^partialSlip:/ { if ($2 > m) m = $2 } END { print m + 0 }' $c/log)
    lines=$(grep -c '^partialSlip:' $c/log)
    want=$([ $ang = 30 ] && echo '-gt' || echo '-eq')
    if [ $rc -eq 0 ] && [ "$lines" -eq 50 ] && [ "$slides" $want 0 ]; then
        pass granular_partialSlip_$ang "at most $slides wall faces slide in a step ($(grep -m1 '^partialSlip:' $c/log))"
    else fail granular_partialSlip_$ang "rc $rc, $lines log lines, at most $slides sliding; $(tail -n 2 $c/log)"; fi
done

# ---- restart, binary ----
for c in once twice; do
    mkdir -p $c && grid $c 6 6 1 1 && "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1
    gcase $c 'endTime 1; deltaT 0.002; writeControl timeStep; writeInterval 20; writeFormat binary;' \
        'eta0 0.0035; lambda0 0.00034; epsilon0 63.4921; cMax 0.64; c0 0.3; T0 0.5;' 0.35 0.05 noSlip
    { H g uniformDimensionedVectorField; echo 'dimensions [0 1 -2 0 0 0 0]; value (0 -9.81 0);'; } >$c/constant/g
done
sed -i 's/endTime 1;/endTime 0.08;/' once/system/controlDict
sed -i 's/endTime 1;/endTime 0.04;/' twice/system/controlDict
"$BIN/solveGranular" -case once >once/log 2>&1
"$BIN/solveGranular" -case twice >twice/log 2>&1
sed -i 's/endTime 0.04;/endTime 0.08;/' twice/system/controlDict
"$BIN/solveGranular" -case twice >>twice/log 2>&1
t1=$(lasttime once) t2=$(lasttime twice) same=1
for f in alpha U Theta p; do cmp -s once/$t1/$f twice/$t2/$f || same=0; done
[ "$t1" = "$t2" ] && [ $same = 1 ] && pass granular_restart "time $t1: alpha, U, Theta, p identical" ||
    fail granular_restart "times $t1 and $t2, identical $same"

# ---- bad input ----
base=badbase
mkdir -p $base && grid $base 4 4 1 1 && "$BIN/blockGrid" -case $base >$base/log.blockGrid 2>&1
gcase $base 'endTime 0.1; deltaT 0.01; writeControl timeStep; writeInterval 1;' "$K" 0.3 1 noSlip
bad() {   # NAME EDIT PATTERN
    rm -rf $1 && cp -r $base $1 && (cd $1 && eval "$2")
    "$BIN/solveGranular" -case $1 >$1/log 2>&1; local rc=$?
    local extra; extra=$(cd $1 && ls -d [0-9]* | grep -vx 0)
    if [ $rc -eq 1 ] && grep -q -- "$3" $1/log && [ -z "$extra" ]; then pass $1 "$(grep -m1 -- "$3" $1/log)"
    else fail $1 "rc $rc, times '$extra', log: $(tail -n 2 $1/log)"; fi
}
bad bad_no_cmax "sed -i 's/cMax 0.64;//' constant/granularProperties" 'granularProperties.*cMax'
bad bad_c0 "sed -i 's/c0 0.5;/c0 0.7;/' constant/granularProperties" 'granularProperties:[0-9]*: c0 must be'
bad bad_eps_twice "sed -i 's/epsilon0 1;/epsilon0 1; grainDiameter 0.001; restitution 0.9;/' constant/granularProperties" 'either epsilon0 or grainDiameter'
bad bad_alpha_high "sed -i 's/uniform 0.3;/uniform 0.7;/' 0/alpha" 'alpha = 0.7 in cell'
bad bad_theta_zero "sed -i 's/uniform 1;/uniform 0;/' 0/Theta" 'Theta = 0 in cell'
bad bad_no_theta_solver "sed -i 's/\"U.\\*|Theta\"/\"U.*\"/' system/fvSolution" 'Theta'
bad bad_no_theta_file "rm 0/Theta" 'Theta'
bad bad_heating "echo 'heatingSchemes { wallVelocity interior; }' >>system/fvSchemes" 'fvSchemes:[0-9]*:.*interior'
bad bad_jacobian "echo 'heatingSchemes { jacobian greenGauss; }' >>system/fvSchemes" 'fvSchemes:[0-9]*:.*greenGauss'
