#!/usr/bin/env bash
# test_limited.sh: solveGranular's bounded second-order convection
# (divSchemes Gauss limitedLinear k | Gauss vanLeer, fv/tvd.h) end to end
# on the 20 x 4 channel of test_solveGranular.sh (inflow fixedValue U
# (1 0 0) with zeroGradient rho, outflow fixedValue rho 1 with
# zeroGradient U, slip walls, a density bump of 0.2 for 0.3 < x < 0.5):
#   - limited_bump: div(phi,rho) Gauss limitedLinear 1, div(phi,U) Gauss
#     vanLeer, to t = 0.25: the total variation of rho along x is > 1.1 x
#     that of the same run with Gauss upwind (less numerical diffusion;
#     measured 1.24);
#   - limited_channel: the same to t = 4, and upwind to t = 4: what is left
#     of the bump then is the channel's quarter-wave acoustic mode (both
#     ends reflect, test_solveGranular.sh channel_quarter_wave), which the
#     limited schemes damp less: the swing of the total mass over 2 <= t
#     <= 4 > 1.05 x upwind's (measured 1.18); U within 0.1 of (1 0 0) and
#     rho within 0.06 of 1 (measured 0.079, 0.044: the mode), the largest
#     deviations not in the first column (no inlet layer: with the
#     ill-posed fixedValue rho and U at the inlet of earlier versions the
#     limited schemes left a steady one-cell layer there, 4e-2 against
#     5e-3 beyond); and at every step mass(start) - mass = mass out since
#     start (the log) to 1e-12 relative (the outflow faces stay upwind, so
#     the patch flows are exact);
#   - bad input: limitedLinear 2, a missing coefficient, QUICK, and
#     default none with div(phi,U) missing: each a file:line message naming
#     the entry (or divSchemes), exit 1, no step run.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/channel.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf sgl && mkdir sgl && cd sgl || exit 1

# chan DIR ENDTIME DIVSCHEMES: the channel with a density bump, writes every 0.25
chan() {
    channel_case "$1" "startFrom startTime; startTime 0; stopAt endTime; endTime $2; deltaT 0.001; adjustTimeStep yes;
maxCo 0.25; writeControl adjustableRunTime; writeInterval 0.25; writeFormat ascii; writePrecision 12;" "$3" &&
        channel_bump "$1"
}

# fieldstat DIR TIME FIELD REF: "max maxdev tv maxdev1" of an ascii field's
# internal values on the 20 x 4 grid: the largest first component, the
# largest |value - REF|, the total variation of the first component along x
# (summed over the rows) and the largest |value - REF| beyond the first
# column
fieldstat() {
    /usr/bin/python3 - "$1/$2/$3" "$4" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
ref = [float(v) for v in sys.argv[2].split()]
m = re.search(r'internalField\s+nonuniform\s+List<\w+>\s*\d+\s*\((.*?)\)\s*;', t, re.S)
body = m.group(1)
vals = [[float(x) for x in g.split()] for g in re.findall(r'\(([^()]*)\)', body)] if '(' in body \
    else [[float(x)] for x in body.split()]
tv = sum(abs(vals[i + 1][0] - vals[i][0]) for i in range(len(vals) - 1) if (i + 1) % 20)
dev = [sum((a - b) ** 2 for a, b in zip(v, ref)) ** 0.5 for v in vals]
print('%.6e %.3e %.6e %.3e' % (max(v[0] for v in vals), max(dev), tv, max(d for i, d in enumerate(dev) if i % 20)))
PY
}

LIM='div(phi,rho) Gauss limitedLinear 1; div(phi,U) Gauss vanLeer;'

# ---- the bump's peak, upwind against limited ----
chan up 0.25 'default Gauss upwind;'
chan lim 0.25 "default none; $LIM"
"$BIN/solveGranular" -case up >up/log 2>&1; rc1=$?
"$BIN/solveGranular" -case lim >lim/log 2>&1; rc2=$?
pu=$(fieldstat up 0.25 rho 1 | cut -d' ' -f3); pl=$(fieldstat lim 0.25 rho 1 | cut -d' ' -f3)
if [ $rc1$rc2 = 00 ] && awk -v u="$pu" -v l="$pl" 'BEGIN { exit !(l > 1.1 * u) }'; then
    pass limited_bump "t = 0.25: total variation of rho along x $pl (limitedLinear 1 / vanLeer) against $pu (upwind)"
else
    fail limited_bump "rc $rc1 $rc2, total variation of rho along x $pl (limited) against $pu (upwind)"
fi

# ---- to t = 4: the acoustic mode, no inlet layer, the mass balance at every step ----
chan full 4 "$LIM"
chan fullup 4 'default Gauss upwind;'
"$BIN/solveGranular" -case full >full/log 2>&1; rc=$?
"$BIN/solveGranular" -case fullup >fullup/log 2>&1; rc2=$?
read -r _ su _ su1 < <(fieldstat full 4 U "1 0 0"); read -r _ sr _ sr1 < <(fieldstat full 4 rho 1)
bal=$(awk '/^Starting time loop/ { m0 = $NF } /^Total mass = / { m = $4; sub(",", "", m) }
           /mass out since start = / { o = $NF; d = (m0 - m) - o; if (d < 0) d = -d; d /= m0; if (d > w) w = d; n++ }
           END { printf "%.3e %d", w + 0, n }' full/log)
# swing LOG: max - min of the total mass over 2 <= t <= 4
swing() { awk '/^Time = /{ t = $3 } /^Total mass = /{ m = $4; sub(",", "", m); if (t >= 2) { if (lo == "" || m < lo) lo = m; if (m > hi) hi = m } }
               END { printf "%.4e", hi - lo }' "$1"; }
wl=$(swing full/log); wu=$(swing fullup/log)
if [ $rc$rc2 = 00 ] && le "$su" 0.1 && le "$sr" 0.06 && le "$su" "$su1" && le "$sr" "$sr1" && le "${bal% *}" 1e-12 &&
    [ "${bal#* }" -gt 100 ] && awk -v l="$wl" -v u="$wu" 'BEGIN { exit !(l > 1.05 * u) }'; then
    pass limited_channel "t = 4: max |U - (1 0 0)| $su (beyond the first column $su1), max |rho - 1| $sr ($sr1); mass swing over 2 <= t <= 4 $wl against upwind's $wu; mass balance to ${bal% *} over ${bal#* } steps"
else
    fail limited_channel "rc $rc $rc2, max |U - (1 0 0)| $su ($su1), max |rho - 1| $sr ($sr1), mass swing $wl (upwind $wu), mass balance ${bal% *} over ${bal#* } steps"
fi

# ---- bad input ----
bad() {   # NAME DIVSCHEMES PATTERN
    chan bad_$1 0.25 "$2"
    "$BIN/solveGranular" -case bad_$1 >bad_$1.out 2>bad_$1.err; local rc=$?
    if [ $rc -eq 1 ] && grep -qE -- "$3" bad_$1.err && ! grep -q '^Time = ' bad_$1.out && [ ! -d bad_$1/0.25 ]; then
        pass bad_$1 "$(head -n 1 bad_$1.err)"
    else
        fail bad_$1 "rc $rc, stderr: $(head -n 2 bad_$1.err | tr '\n' ' ')"
    fi
}
bad limitedLinear_k 'default Gauss limitedLinear 2;' 'fvSchemes:[0-9]+: divSchemes: default: .*2 is not in \[0, 1\]'
bad limitedLinear_nok 'div(phi,U) Gauss limitedLinear;' 'fvSchemes:[0-9]+: divSchemes: div\(phi,U\): unknown scheme'
bad quick 'div(phi,rho) Gauss QUICK;' 'fvSchemes:[0-9]+: divSchemes: div\(phi,rho\): unknown scheme'
bad none_missing 'default none; div(phi,rho) Gauss vanLeer;' 'fvSchemes:[0-9]+: divSchemes: div\(phi,U\) missing'
