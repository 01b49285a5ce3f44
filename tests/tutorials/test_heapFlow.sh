#!/usr/bin/env bash
# tutorials/granular/heapFlow end to end (thesis §5.3.1 in 2-D, model
# granular with yield): copies the case, runs its Allrun (to t = 0.3,
# about 5 s) and checks
#   - every log ends with End, no nan/inf in the log or the last fields,
#     the plot exists;
#   - the mass is kept: |change since start| <= 1e-12 at every step
#     before the first clamp of c to cMax - deltaC (measured 3.9e-15), and
#     <= 1e-7 after it (the clamp removes mass; measured 5.7e-9 after 11
#     clamps, first at t = 0.295);
#   - the grains drain: along the funnel's axis x = 0.3 the alpha-weighted
#     mean height falls from 0.74 (at t = 0) to below 0.45 (measured
#     0.399), and the grains pack on the floor under the outlet: alpha at
#     y < 0.1 on the axis above 0.6 (measured 0.632; cMax 0.64), and along
#     the floor line y = 0.05 the peak lies under the outlet,
#     0.25 <= x <= 0.35, above 0.4 (measured 0.46 at x = 0.297).
# Allclean must restore the case.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/granular/heapFlow
case=$PWD/heapFlow

fresh_copy "$src" "$case"
pristine=$(listing "$case")
out=$(cd / && timeout 180 "$case/Allrun" 2>&1); rc=$?
if [ "$rc" -ne 0 ]; then
    fail heapFlow_allrun "Allrun exited with status $rc"; printf '%s\n' "$out" | tail -n 20 | sed 's/^/  /'; exit 1
fi
pass heapFlow_allrun
bad=""
for app in blockGrid cutCells mergeCells checkGrid setFields solveGranular sampleLine; do
    [ "$(grep -v '^[[:space:]]*$' "$case/log.$app" 2>/dev/null | tail -n 1)" = End ] || bad="$bad $app"
done
[ -z "$bad" ] && pass heapFlow_logs || fail heapFlow_logs "no End in:$bad"
if grep -qiw -e nan -e inf "$case/log.solveGranular" "$case"/0.3/alpha "$case"/0.3/U "$case"/0.3/Theta; then
    fail heapFlow_finite "nan or inf in the log or the fields at t = 0.3"
else pass heapFlow_finite; fi
s=$case/postProcessing/sampleLine/0.3
if command -v gnuplot >/dev/null 2>&1; then check heapFlow_plot test -s "$s/heapFlow.png"; fi
read -r before after <<<"$(awk '/^Limits/ { if ($7 + 0 > 0) cl = 1 }
    /change since start/ { v = $9; if (v < 0) v = -v; if (cl) { if (v > wa) wa = v } else if (v > wb) wb = v }
    END { printf "%.3e %.3e", wb + 0, wa + 0 }' "$case/log.solveGranular")"
if le "$before" 1e-12 && le "$after" 1e-7; then
    pass heapFlow_mass "worst relative change $before before the first c clamp, $after after"
else fail heapFlow_mass "worst relative change $before before the first c clamp (want 1e-12), $after after (want 1e-7)"; fi
read -r ymean afloor <<<"$(awk -F, 'NR > 1 { s += $5; sy += $5 * $3; if ($3 < 0.1 && $5 > m) m = $5 } END { printf "%.4f %.4f", sy / s, m }' "$s/axis.csv")"
if [ -n "${ymean:-}" ] && le "$ymean" 0.45 && awk -v a="$afloor" 'BEGIN { exit !(a > 0.6) }'; then
    pass heapFlow_drain "mean height on the axis $ymean (0.74 at t = 0), alpha on the floor $afloor"
else fail heapFlow_drain "mean height on the axis ${ymean:-?} (want <= 0.45), alpha on the floor ${afloor:-?} (want > 0.6)"; fi
read -r xp ap <<<"$(awk -F, 'NR > 1 && $5 > m { m = $5; x = $2 } END { printf "%.4f %.4f", x, m }' "$s/floor.csv")"
if [ -n "${xp:-}" ] && awk -v x="$xp" -v a="$ap" 'BEGIN { exit !(x >= 0.25 && x <= 0.35 && a > 0.4) }'; then
    pass heapFlow_pile "peak alpha $ap at x = $xp on the floor line y = 0.05"
else fail heapFlow_pile "peak alpha ${ap:-?} at x = ${xp:-?} (want > 0.4 at 0.25 <= x <= 0.35)"; fi
"$case/Allclean" >/dev/null 2>&1
[ "$(listing "$case")" = "$pristine" ] && pass heapFlow_allclean || fail heapFlow_allclean "Allclean left files"
