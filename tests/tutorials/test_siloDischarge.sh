#!/usr/bin/env bash
# tutorials/granular/siloDischarge end to end (a silo cut from a CAD part,
# constant/geometry/silo.geo through gmsh, discharging into a closed bin;
# model granular): copies the case, runs its Allrun as it is (to t = 1.2,
# about 15 s) and checks
#   - every log ends with End, no nan/inf in the log or the last fields,
#     the files the header promises exist (the plot with gnuplot);
#   - the grid is the part's section with z = 0: fluid volume within 2e-3
#     of the exact 0.625 x 0.02 (measured 6.5e-4 below: the triangulated
#     cone and cylinder, chamfered corners);
#   - the mass is kept: |change since start| <= 1e-12 at every step and c
#     never clamped (measured 1.1e-14, 0 clamps); hopperMass.py's total at
#     t = 0 is the solver's total mass over the thickness to 1e-10 (its
#     cell volumes), and its hopper content at t = 0 is 0.4 x the section's
#     area above the orifice, 0.185, to 1 % (measured 0.0737831 against
#     0.074: the cells along the orifice plane and the faceting);
#   - the discharge: the hopper below 1e-3 of its start by t = 1.2
#     (measured at t = 0.85) and everything in the bin; the rate W fitted
#     in the window 0.8 .. 0.2 of the start within 0.08 .. 0.14 m^2/s
#     (measured 0.110; the liquid-like orifice estimate c D sqrt(2 g H),
#     c = 0.4 .. 0.6, head H = 0.1 .. 0.4 above the orifice, gives 0.06 ..
#     0.17), its ratio to Beverloo's 2-D W_B (0.0220) printed and within
#     3 .. 8 (measured 5.0: the model is not mu(I)), and the rate falling
#     with the head (first half of the window > 1.05 x the second;
#     measured 0.119 against 0.104): a liquid's behaviour, not Beverloo's;
#   - VTK's reader (SKIP without VTK for python) reads the last VTK file:
#     the merged grid's cells (2-D: polygons), sum(alpha area) dz = the
#     solver's mass to 1e-10; the series lists the 25 written times.
# Allclean must restore the case.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/granular/siloDischarge
case=$PWD/siloDischarge

fresh_copy "$src" "$case"
pristine=$(listing "$case")
timed_allrun siloDischarge_allrun "$case"

bad=""
for app in blockGrid cutCells mergeCells checkGrid setFields solveGranular sampleLine; do
    [ "$(grep -v '^[[:space:]]*$' "$case/log.$app" 2>/dev/null | tail -n 1)" = End ] || bad="$bad $app"
done
[ -z "$bad" ] && pass siloDischarge_logs || fail siloDischarge_logs "no End in:$bad"
if grep -qiw -e nan -e inf "$case/log.solveGranular" "$case"/1.2/alpha "$case"/1.2/U "$case"/1.2/Theta 2>/dev/null \
    || [ ! -s "$case/1.2/alpha" ]; then
    fail siloDischarge_finite "nan or inf in the log or the fields at t = 1.2, or no 1.2/alpha"
else pass siloDischarge_finite; fi
missing=""
for f in constant/polyMesh/boundaryNormal constant/polyMesh/mergeMap 1.2/U 1.2/p 1.2/uniform/time \
    VTK/siloDischarge.vtk.series postProcessing/sampleLine/0.2/axis.csv postProcessing/sampleLine/1.2/floor.csv \
    postProcessing/discharge.dat postProcessing/discharge.txt; do
    [ -s "$case/$f" ] || missing="$missing $f"
done
if command -v gnuplot >/dev/null 2>&1; then [ -s "$case/postProcessing/siloDischarge.png" ] || missing="$missing postProcessing/siloDischarge.png"; fi
[ -z "$missing" ] && pass siloDischarge_files || fail siloDischarge_files "missing:$missing"

vf=$(fluid "$case/log.cutCells")
e=$(rel "${vf:-0}" 0.0125)
if [ -n "$vf" ] && le "$e" 2e-3; then pass siloDischarge_section "fluid volume $vf, exact 0.0125 (relative error $e)"
else fail siloDischarge_section "fluid volume ${vf:-?}, exact 0.0125 (relative error $e > 2e-3)"; fi

read -r worst clamps mass0 <<<"$(awk '/^Starting time loop/ { m0 = $NF }
    /^Limits/ { cl = $7 }
    /change since start/ { v = $9; if (v < 0) v = -v; if (v > w) w = v }
    END { printf "%.3e %d %.15g", w + 0, cl + 0, m0 }' "$case/log.solveGranular")"
if le "$worst" 1e-12 && [ "$clamps" -eq 0 ]; then pass siloDischarge_mass "worst relative change $worst, $clamps clamps of c"
else fail siloDischarge_mass "worst relative change $worst (want <= 1e-12), $clamps clamps of c (want 0)"; fi

dat=$case/postProcessing/discharge.dat
read -r h0 tot0 <<<"$(awk '!/^#/ { print $2, $4; exit }' "$dat")"
et=$(rel "${tot0:-0}" "$(awk -v m="$mass0" 'BEGIN { printf "%.15g", m / 0.02 }')")
eh=$(rel "${h0:-0}" 0.074)
if le "$et" 1e-10 && le "$eh" 1e-2; then pass siloDischarge_content "total $tot0 (solver's mass / dz to $et), hopper $h0 (0.4 x 0.185 to $eh)"
else fail siloDischarge_content "total ${tot0:-?} (relative to the solver's mass / dz $et, want 1e-10), hopper ${h0:-?} (to 0.074: $eh, want 1e-2)"; fi

read -r hl bl <<<"$(awk '!/^#/ { h = $2; b = $3 } END { print h, b }' "$dat")"
if le "$hl" "$(awk -v h="$h0" 'BEGIN { print 1e-3 * h }')" && [ "$(rel "$bl" "$tot0")" != "" ] && le "$(rel "$bl" "$tot0")" 1e-3; then
    pass siloDischarge_drained "hopper $hl, bin $bl at t = 1.2"
else fail siloDischarge_drained "hopper ${hl:-?} (want <= 1e-3 x $h0), bin ${bl:-?} (want the total $tot0)"; fi

txt=$case/postProcessing/discharge.txt
read -r W W1 W2 <<<"$(sed -n 's/^Discharge rate W = \([^ ]*\) m^2\/s (first half \([^,]*\), second half \([^)]*\))/\1 \2 \3/p' "$txt")"
WB=$(sed -n 's/^Beverloo 2-D: W_B = .* = \([^ ]*\) m^2.*/\1/p' "$txt")
ratio=$(sed -n 's/^Ratio W \/ W_B = //p' "$txt")
if [ -n "${W:-}" ] && [ -n "$WB" ] && awk -v w="$W" -v b="$WB" -v r="$ratio" 'BEGIN {
        exit !(w >= 0.08 && w <= 0.14 && r >= 3 && r <= 8 && (r - w / b < 0.01 && w / b - r < 0.01 * r)) }'; then
    pass siloDischarge_rate "W = $W m^2/s, Beverloo 2-D $WB, ratio $ratio"
else fail siloDischarge_rate "W = ${W:-?} m^2/s (want 0.08 .. 0.14), Beverloo ${WB:-?}, ratio ${ratio:-?} (want 3 .. 8)"; fi
if [ -n "${W2:-}" ] && awk -v a="$W1" -v b="$W2" 'BEGIN { exit !(a > 1.05 * b) }'; then
    pass siloDischarge_head "rate $W1 then $W2: falls with the head"
else fail siloDischarge_head "rate ${W1:-?} then ${W2:-?} (want the first > 1.05 x the second)"; fi

"${KIESEL_PYTHON:-/usr/bin/python3}" - "$case" "$mass0" <<'PYEOF'
import glob, json, os, sys
case, mass0 = sys.argv[1], float(sys.argv[2])
def report(name, ok, why):
    print("PASS %s" % name if ok else "FAIL %s: %s" % (name, why))
try:
    s = json.load(open(os.path.join(case, "VTK", "siloDischarge.vtk.series")))
    times = [f["time"] for f in s["files"]]
    want = [round(0.05 * i, 10) for i in range(25)]
    ok = len(times) == 25 and all(abs(a - b) < 1e-9 for a, b in zip(times, want))
    report("siloDischarge_vtk_series", ok, "times %s, expected 0, 0.05, ..., 1.2" % times)
    last = s["files"][-1]["name"]
except (OSError, ValueError, KeyError, IndexError) as ex:
    report("siloDischarge_vtk_series", False, str(ex))
    last = None
try:
    import vtk
    ncell = None
    for line in open(os.path.join(case, "log.mergeCells")):
        if line.strip().startswith("nCells:"):
            ncell = int(line.split()[1])
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(os.path.join(case, "VTK", last or "siloDischarge_0.vtk"))
    r.ReadAllFieldsOn()
    r.Update()
    grid = r.GetOutput()
    errs = []
    if grid.GetNumberOfCells() != ncell:
        errs.append("%d cells, log.mergeCells has %s" % (grid.GetNumberOfCells(), ncell))
    arr = grid.GetCellData().GetArray("alpha")
    if arr is None:
        errs.append("no cell array alpha")
    else:
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputData(grid)
        sizes.ComputeAreaOn()
        sizes.Update()
        cd = sizes.GetOutput().GetCellData()
        # a 2-D case's VTK cells are its polygons (area; the grid is 0.02 thick)
        area = cd.GetArray("Area")
        total = sum(arr.GetValue(i) * area.GetValue(i) for i in range(arr.GetNumberOfTuples())) * 0.02
        if not abs(total - mass0) <= 1e-10 * mass0:
            errs.append("sum(alpha V) = %.15g, the solver's mass %.15g" % (total, mass0))
    report("siloDischarge_vtk_reader", not errs, "; ".join(errs))
except ImportError as ex:
    print("SKIP siloDischarge_vtk_reader: no VTK module for python3 (%s)" % ex)
except Exception as ex:   # any failure of the reader is a failure of the file
    report("siloDischarge_vtk_reader", False, "%s: %s" % (type(ex).__name__, ex))
PYEOF

"$case/Allclean" >/dev/null 2>&1
[ "$(listing "$case")" = "$pristine" ] && pass siloDischarge_allclean || fail siloDischarge_allclean "Allclean left files"
