#!/usr/bin/env bash
# tutorials/granular/inclinedChannel end to end: copies the case to the
# scratch directory, runs its Allrun (blockGrid, cutCells, mergeCells,
# solveGranular to the steady state t = 2, writing VTK too, sampleLine, the plot)
# and checks the velocity sampled across the channel against the exact
# plane Poiseuille profile u(eta) = g eta (W - eta)/(2 nu), W = 0.5,
# g = 9.81, nu = 0.25 (u_max = 1.22625):
#   - in the middle 60 % of the width (0.1 <= eta <= 0.4): within 0.03
#     (measured 0.020, h = 0.05: the sample is the cell value plus a
#     least-squares gradient, first order next to cut cells);
#   - the largest sampled speed within 2 % of u_max (measured 1.222,
#     0.4 %);
#   - the density on the line within 0.1 of rho0 = 1 (measured 0.046:
#     the first-order density error next to the cut walls, Table 5.1);
# every log ends with End, the plot exists, solveGranular's VTK series
# (internal, lowerWall, upperWall) list the write times 0 0.5 1 1.5 2 and
# their files exist.  Allclean must restore the case.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/granular/inclinedChannel
case=$PWD/inclinedChannel

fresh_copy "$src" "$case"
pristine=$(listing "$case")

t0=$(date +%s.%N)
out=$(cd / && timeout 120 "$case/Allrun" 2>&1); rc=$?
t1=$(date +%s.%N)
if [ "$rc" -ne 0 ]; then
    fail inclinedChannel_allrun "Allrun exited with status $rc; output:"
    printf '%s\n' "$out" | tail -n 20 | sed 's/^/  /'
    exit 1
fi
pass inclinedChannel_allrun "$(awk -v a=$t0 -v b=$t1 'BEGIN{printf "%.1f", b-a}') s"

bad=""
for app in blockGrid cutCells mergeCells solveGranular sampleLine; do
    last=$(grep -v '^[[:space:]]*$' "$case/log.$app" 2>/dev/null | tail -n 1)
    [ "$last" = End ] || bad="$bad log.$app ends with '$last';"
done
for f in VTK/inclinedChannel.vtk.series 2/U 2/rho postProcessing/sampleLine/2/across.csv; do
    [ -s "$case/$f" ] || bad="$bad $f missing;"
done
if command -v gnuplot > /dev/null 2>&1 && [ ! -s "$case/postProcessing/sampleLine/2/profile.png" ]; then
    bad="$bad profile.png missing;"
fi
for p in inclinedChannel lowerWall upperWall; do
    d=VTK/$p; [ $p = inclinedChannel ] && d=VTK
    ser=$case/$d/$p.vtk.series
    times=$(sed -n 's/.*"time" : \([^ ]*\) }.*/\1/p' "$ser" 2>/dev/null | tr '\n' ' ')
    [ "$times" = "0 0.5 1 1.5 2 " ] || bad="$bad $d/$p.vtk.series lists '$times';"
    for f in $(sed -n 's/.*"name" : "\([^"]*\)".*/\1/p' "$ser" 2>/dev/null); do
        [ -s "$case/$d/$f" ] || bad="$bad $d/$f missing;"
    done
done
if [ -z "$bad" ]; then pass inclinedChannel_files; else fail inclinedChannel_files "$bad"; fi

res=$(/usr/bin/python3 - "$case/postProcessing/sampleLine/2/across.csv" <<'PY'
import csv, math, sys
t = (13 / math.sqrt(698), 23 / math.sqrt(698))
rows = list(csv.DictReader(open(sys.argv[1])))
exact = lambda e: 9.81 / (2 * 0.25) * e * (0.5 - e)
print('  eta      u        exact    rho', file=sys.stderr)
mid, umax, drho = 0.0, 0.0, 0.0
for r in rows:
    e = float(r['distance']); u = float(r['U_x']) * t[0] + float(r['U_y']) * t[1]
    print('  %.3f  %.5f  %.5f  %.5f' % (e, u, exact(e), float(r['rho'])), file=sys.stderr)
    if 0.1 <= e <= 0.4: mid = max(mid, abs(u - exact(e)))
    umax = max(umax, u); drho = max(drho, abs(float(r['rho']) - 1))
print('%d %.4e %.5f %.4e' % (len(rows), mid, umax, drho))
PY
)
read -r n mid umax drho <<<"$res"
if [ "${n:-0}" -eq 51 ] && le "$mid" 0.03 && le "$(awk -v u="$umax" 'BEGIN{d=u-1.22625; print (d<0?-d:d)/1.22625}')" 0.02 \
    && le "$drho" 0.1; then
    pass inclinedChannel_poiseuille "max |u - exact| $mid (0.1 <= eta <= 0.4), u_max $umax (exact 1.22625), max |rho - 1| $drho"
else
    fail inclinedChannel_poiseuille "$n samples, max |u - exact| $mid, u_max $umax, max |rho - 1| $drho"
fi

"$case/Allclean" >/dev/null 2>&1
if [ "$(listing "$case")" = "$pristine" ]; then pass inclinedChannel_allclean; else fail inclinedChannel_allclean "case differs after Allclean"; fi
