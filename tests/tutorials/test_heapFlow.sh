#!/usr/bin/env bash
# tutorials/granular/heapFlow end to end (thesis §5.3.1 in 2-D, model
# granular with yield): copies the case, runs its Allrun (to t = 1.2,
# about 10 s) and checks
#   - every log ends with End, no nan/inf in the log or the last fields,
#     the plot exists;
#   - the mass is kept: |change since start| <= 1e-12 at every step
#     before any clamp of c to cMax - deltaC (measured 6.6e-15, no clamp
#     in this run), and <= 1e-7 after one (a clamp removes mass);
#   - the funnel has drained: alpha <= 0.02 on its axis above the lid
#     (y > 0.5; measured 0.0002), and the grains have reached the step:
#     alpha >= 0.5 in the floor line's last samples, x > 0.55, against the
#     step's face (measured 0.573, 0.602);
#   - a pile: the free surface (alpha = cMax/2) under the outlet, x = 0.3,
#     above the surface at x = 0.1 and x = 0.5 with slopes between 0.03
#     and 0.2, about the friction slope tan(phi) = sqrt(eps0 eta0) = 0.154
#     of eq. 2.25 (measured 0.089 and 0.094: flatter than tan(phi) at
#     t = 1.2), every surface within 0.1 .. 0.25 (measured 0.178, 0.196,
#     0.177).
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
if grep -qiw -e nan -e inf "$case/log.solveGranular" "$case"/1.2/alpha "$case"/1.2/U "$case"/1.2/Theta; then
    fail heapFlow_finite "nan or inf in the log or the fields at t = 1.2"
else pass heapFlow_finite; fi
s=$case/postProcessing/sampleLine/1.2
if command -v gnuplot >/dev/null 2>&1; then check heapFlow_plot test -s "$s/heapFlow.png"; fi
read -r before after <<<"$(awk '/^Limits/ { if ($7 + 0 > 0) cl = 1 }
    /change since start/ { v = $9; if (v < 0) v = -v; if (cl) { if (v > wa) wa = v } else if (v > wb) wb = v }
    END { printf "%.3e %.3e", wb + 0, wa + 0 }' "$case/log.solveGranular")"
if le "$before" 1e-12 && le "$after" 1e-7; then
    pass heapFlow_mass "worst relative change $before before any c clamp, $after after"
else fail heapFlow_mass "worst relative change $before before any c clamp (want 1e-12), $after after (want 1e-7)"; fi
funnel=$(awk -F, 'NR > 1 && $3 > 0.5 && $5 > m { m = $5 } END { printf "%.4g", m + 0 }' "$s/axis.csv")
step=$(awk -F, 'NR > 1 && $2 > 0.55 { if (m == "" || $5 < m) m = $5 } END { printf "%.4g", m + 0 }' "$s/floor.csv")
if le "$funnel" 0.02 && awk -v a="$step" 'BEGIN { exit !(a >= 0.5) }'; then
    pass heapFlow_drained "alpha in the funnel <= $funnel, at the step's face >= $step"
else fail heapFlow_drained "alpha in the funnel $funnel (want <= 0.02), at the step's face $step (want >= 0.5)"; fi
read -r hl ha hr <<<"$(sed -n 's/^Free surface at t = [^:]*: \([^ ]*\) (x = 0.1), \([^ ]*\) (x = 0.3), \([^ ]*\) (x = 0.5)$/\1 \2 \3/p' "$s/heap.txt")"
if [ -n "${hr:-}" ] && awk -v l="$hl" -v a="$ha" -v r="$hr" 'BEGIN { sl = (a - l) / 0.2; sr = (a - r) / 0.2
        exit !(sl > 0.03 && sl < 0.2 && sr > 0.03 && sr < 0.2 && l > 0.1 && l < 0.25 && a > 0.1 && a < 0.25 && r > 0.1 && r < 0.25) }'; then
    pass heapFlow_pile "free surface $hl, $ha, $hr at x = 0.1, 0.3, 0.5"
else fail heapFlow_pile "free surface ${hl:-?}, ${ha:-?}, ${hr:-?} at x = 0.1, 0.3, 0.5 (want a pile, slopes 0.03 .. 0.2)"; fi
"$case/Allclean" >/dev/null 2>&1
[ "$(listing "$case")" = "$pristine" ] && pass heapFlow_allclean || fail heapFlow_allclean "Allclean left files"
