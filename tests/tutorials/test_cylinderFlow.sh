#!/usr/bin/env bash
# tutorials/granular/cylinderFlow end to end, shortened: the case is copied
# to the scratch directory and its controlDict set to endTime 0.5 (1/8 of
# the tutorial's 4; writeInterval 0.25), then its Allrun runs every step
# (blockGrid, cutCells, mergeCells, checkGrid, solveGranular, which writes
# the VTK files too, sampleLine, the plot).  Checks:
#   - every log ends with End (checkGrid's with "Grid OK."), the files the
#     header promises exist (the PNG when gnuplot is installed), among them
#     solveGranular's VTK: the internal mesh and the patches inlet,
#     outlet, walls, cylinder at t = 0, 0.25, 0.5, and series files that
#     list those three times;
#   - mass balance: mass(0) - mass(t) = the mass that left through inlet
#     and outlet, integrated step by step (the log's "mass out since
#     start"), to 1e-12 of the mass, at every step: the internal fluxes
#     cancel, so only round-off may differ;
#   - no NaN or Inf in the fields at the last time (rho, U, p);
#   - the outlet: U_x averaged over the outlet column (sampleLine's
#     outlet.csv, lengths as weights) within [0.45, 0.60] (the inflow speed
#     0.5 plus the acoustic start-up wave; measured 0.5 to 3 digits at
#     t = 0.5), rho there within 1e-2 of the fixed outlet value 1, and the
#     density everywhere within [0.8, 1.25];
#   - the wake: reversed flow (U_x < 0) on the centre line behind the
#     cylinder already at t = 0.5 (the recirculation forms at once in an
#     impulsive start);
# and Allclean restores the case as it came.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/granular/cylinderFlow
case=$PWD/cylinderFlow

fresh_copy "$src" "$case"
pristine=$(listing "$case")
sed -i 's/^endTime .*/endTime 0.5;/; s/^writeInterval .*/writeInterval 0.25;/' "$case/system/controlDict"
timed_allrun cylinderFlow_allrun "$case"

bad=""
for app in blockGrid cutCells mergeCells checkGrid solveGranular sampleLine; do
    log=$case/log.$app
    if [ ! -s "$log" ]; then bad="$bad log.$app missing;"; continue; fi
    last=$(grep -v '^[[:space:]]*$' "$log" | tail -n 1)
    if [ "$app" = checkGrid ]; then
        grep -q '^Grid OK\.' "$log" || bad="$bad log.checkGrid has no 'Grid OK.';"
    elif [ "$last" != End ]; then
        bad="$bad log.$app ends with '$last';"
    fi
done
if [ -z "$bad" ]; then pass cylinderFlow_logs; else fail cylinderFlow_logs "$bad"; fi

missing=""
for f in constant/polyMesh/boundaryNormal constant/polyMesh/mergeMap 0.25/rho 0.5/rho 0.5/U 0.5/p 0.5/uniform/time \
    VTK/cylinderFlow.vtk.series postProcessing/sampleLine/0.5/centreLine.csv \
    postProcessing/sampleLine/0.5/wake.csv postProcessing/sampleLine/0.5/outlet.csv; do
    [ -s "$case/$f" ] || missing="$missing $f"
done
if command -v gnuplot > /dev/null 2>&1 && [ ! -s "$case/postProcessing/sampleLine/0.5/cylinderFlow.png" ]; then
    missing="$missing postProcessing/sampleLine/0.5/cylinderFlow.png"
fi
for p in cylinderFlow inlet outlet walls cylinder; do
    d=VTK/$p; [ $p = cylinderFlow ] && d=VTK
    nvtk=$(ls "$case/$d/${p}_"*.vtk 2>/dev/null | wc -l)
    [ "$nvtk" -eq 3 ] || missing="$missing $d/${p}_<index>.vtk ($nvtk files, expected 3: t = 0, 0.25, 0.5)"
    times=$(sed -n 's/.*"time" : \([^ ]*\) }.*/\1/p' "$case/$d/$p.vtk.series" 2>/dev/null | tr '\n' ' ')
    [ "$times" = "0 0.25 0.5 " ] || missing="$missing $d/$p.vtk.series (times '$times', expected 0 0.25 0.5)"
done
if [ -z "$missing" ]; then pass cylinderFlow_files; else fail cylinderFlow_files "missing:$missing"; fi

"${KIESEL_PYTHON:-/usr/bin/python3}" - "$case" <<'PYEOF'
import csv, math, os, re, sys
case = sys.argv[1]

def report(name, ok, why):
    print(("PASS %s: %s" % (name, why)) if ok else ("FAIL %s: %s" % (name, why)))

# --- mass balance, every step ---------------------------------------------------
try:
    log = open(os.path.join(case, "log.solveGranular")).read()
    m0 = float(re.search(r"total mass ([-+0-9.eE]+)", log).group(1))
    mass = [float(v) for v in re.findall(r"^Total mass = ([-+0-9.eE]+)", log, re.M)]
    out = [float(v) for v in re.findall(r"mass out since start = ([-+0-9.eE]+)", log)]
    flows = re.findall(r"^Mass flow out: inlet ([-+0-9.eE]+), outlet ([-+0-9.eE]+)", log, re.M)
    if not mass or len(mass) != len(out) or len(flows) != len(mass):
        raise ValueError("%d mass lines, %d mass-out lines, %d flow lines" % (len(mass), len(out), len(flows)))
    worst = max(abs(m0 - m - o) / m0 for m, o in zip(mass, out))
    report("cylinderFlow_mass_balance", worst <= 1e-12,
           "%d steps: largest |mass(0) - mass - out| / mass(0) = %.2e (tolerance 1e-12); mass %.9g -> %.9g, "
           "out %.4g; last step: inlet %s, outlet %s" % (len(mass), worst, m0, mass[-1], out[-1], flows[-1][0], flows[-1][1]))
except (OSError, ValueError, AttributeError) as ex:
    report("cylinderFlow_mass_balance", False, str(ex))

# --- the fields at the last time: finite, density in a band --------------------------
def values(path):
    t = open(path).read()
    m = re.search(r"internalField\s+nonuniform\s+List<\w+>\s*\d+\s*\((.*)\)\s*;", t, re.S)
    body = m.group(1).split("boundaryField")[0] if m else ""
    return [float(x) for x in re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan|inf", body, re.I)]
try:
    bad, rho = [], []
    for f in ("rho", "U", "p"):
        t = open(os.path.join(case, "0.5", f)).read()
        if re.search(r"\b(nan|inf)\b", t, re.I):
            bad.append(f)
    rho = values(os.path.join(case, "0.5", "rho"))
    ok = not bad and rho and 0.8 <= min(rho) and max(rho) <= 1.25
    report("cylinderFlow_finite", ok, "t = 0.5: no NaN/Inf in rho, U, p%s; rho in [%.4f, %.4f] (band [0.8, 1.25]), %d cells"
           % ((" (found in %s)" % bad) if bad else "", min(rho) if rho else 0, max(rho) if rho else 0, len(rho)))
except (OSError, ValueError) as ex:
    report("cylinderFlow_finite", False, str(ex))

def read_csv(name):
    with open(os.path.join(case, "postProcessing", "sampleLine", "0.5", name + ".csv"), newline="") as f:
        rows = list(csv.reader(f))
    head = [h.strip().lstrip("#").strip() for h in rows[0]]
    return {h: [float(r[i]) for r in rows[1:] if r] for i, h in enumerate(head)}

# --- the outlet ---------------------------------------------------------------------
try:
    o = read_csv("outlet")
    L = sum(o["length"])
    ux = sum(u * l for u, l in zip(o["U_x"], o["length"])) / L
    r = max(abs(v - 1) for v in o["rho"])
    ok = abs(L - 1) < 1e-12 and 0.45 <= ux <= 0.60 and r <= 1e-2
    report("cylinderFlow_outlet", ok, "mean U_x %.5f over the outlet column (band [0.45, 0.60]), max |rho - 1| %.2e "
           "(tolerance 1e-2), column length %.15g" % (ux, r, L))
except (OSError, KeyError, ValueError, ZeroDivisionError) as ex:
    report("cylinderFlow_outlet", False, str(ex))

# --- the wake ------------------------------------------------------------------------
try:
    c = read_csv("centreLine")
    behind = [(x, u) for x, u in zip(c["x"], c["U_x"]) if 0.7 < x < 1.1]
    xmin, umin = min(behind, key=lambda p: p[1])
    gap = [x for x in c["x"] if 0.5 < x < 0.7]
    ok = umin < 0 and not gap
    report("cylinderFlow_wake", ok, "centre line behind the cylinder: min U_x %.4f at x = %.4f (expected < 0); "
           "%d samples inside the cylinder (expected 0)" % (umin, xmin, len(gap)))
except (OSError, KeyError, ValueError) as ex:
    report("cylinderFlow_wake", False, str(ex))
PYEOF

(cd / && "$case/Allclean" > /dev/null 2>&1)
sed -i 's/^endTime .*/endTime         4;              \/\/ 10 D\/U: the recirculation has formed/; s/^writeInterval .*/writeInterval   0.5;/' "$case/system/controlDict"
now=$(listing "$case")
if [ "$now" = "$pristine" ] && diff -q "$src/system/controlDict" "$case/system/controlDict" > /dev/null; then
    pass cylinderFlow_allclean
else
    fail cylinderFlow_allclean "left: $(diff <(echo "$pristine") <(echo "$now") | grep '^[<>]' | head -n 5 | tr '\n' ' ')"
fi
