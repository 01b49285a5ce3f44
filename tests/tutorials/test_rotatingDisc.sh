#!/usr/bin/env bash
# tutorials/granular/rotatingDisc end to end (thesis §5.2.1, model
# granular with T frozen): copies the case, runs its Allrun and checks
#   - every log ends with End, the plot exists;
#   - radial symmetry: alpha and the speed along the x axis and along the
#     diagonal at the same radius agree within 2e-3 and 0.02 (measured
#     5.3e-4 and 9.8e-3 at t = 3; the speed's largest difference is at the
#     first cells off the centre);
#   - the rim drags the grain: the speed in the outermost sample within
#     10 % of the wall's 0.5 m/s times r/0.5, and the grain pushed
#     outwards: alpha at the rim above alpha at the centre (measured
#     0.4096 and 0.3889);
#   - the mass is kept: |change since start| <= 1e-12 at every step.
# Allclean must restore the case.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/granular/rotatingDisc
case=$PWD/rotatingDisc

fresh_copy "$src" "$case"
pristine=$(listing "$case")
out=$(cd / && timeout 120 "$case/Allrun" 2>&1); rc=$?
if [ "$rc" -ne 0 ]; then
    fail rotatingDisc_allrun "Allrun exited with status $rc"; printf '%s\n' "$out" | tail -n 20 | sed 's/^/  /'; exit 1
fi
pass rotatingDisc_allrun
bad=""
for app in blockGrid cutCells mergeCells solveGranular sampleLine; do
    [ "$(grep -v '^[[:space:]]*$' "$case/log.$app" 2>/dev/null | tail -n 1)" = End ] || bad="$bad $app"
done
[ -z "$bad" ] && pass rotatingDisc_logs || fail rotatingDisc_logs "no End in:$bad"
s=$case/postProcessing/sampleLine/3
if command -v gnuplot >/dev/null 2>&1; then check rotatingDisc_plot test -s "$s/rotatingDisc.png"; fi
read -r da ds <<<"$(sed -n 's/.*max |d alpha| \([^,]*\), max |d speed| \(.*\)/\1 \2/p' "$s/spread.txt")"
if [ -n "${da:-}" ] && le "$da" 2e-3 && le "$ds" 0.02; then pass rotatingDisc_symmetry "max |d alpha| $da, max |d speed| $ds"
else fail rotatingDisc_symmetry "max |d alpha| ${da:-?}, max |d speed| ${ds:-?}"; fi
read -r r sp arim acen <<<"$(awk -F, 'NR == 2 { a0 = $5 } NR > 1 { r = sqrt($2 * $2 + $3 * $3); s = sqrt($6 * $6 + $7 * $7); a = $5 }
    END { print r, s, a, a0 }' "$s/radiusX.csv")"
want=$(awk -v r="$r" 'BEGIN { print r }')
if awk -v s="$sp" -v w="$want" -v a="$arim" -v c="$acen" 'BEGIN { d = s - w; if (d < 0) d = -d; exit !(d <= 0.1 * w && a > c) }'; then
    pass rotatingDisc_spinup "speed $sp at r = $r (wall-driven $want), alpha rim $arim > centre $acen"
else fail rotatingDisc_spinup "speed $sp at r = $r (want $want +- 10 %), alpha rim $arim, centre $acen"; fi
worst=$(awk '/change since start/ { v = $9; if (v < 0) v = -v; if (v > w) w = v } END { printf "%.3e", w + 0 }' "$case/log.solveGranular")
le "$worst" 1e-12 && pass rotatingDisc_mass "worst relative change $worst" || fail rotatingDisc_mass "worst $worst"
"$case/Allclean" >/dev/null 2>&1
[ "$(listing "$case")" = "$pristine" ] && pass rotatingDisc_allclean || fail rotatingDisc_allclean "Allclean left files"
