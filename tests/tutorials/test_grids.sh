#!/usr/bin/env bash
# tutorials/grids/* end to end: copies each case to the scratch directory,
# runs its Allrun from another directory, and checks the logs, the output
# files and numbers in them against values computed here independently:
#
#   - the fluid volume that cutCells reports against the exact fluid volume
#     of the geometry:
#       discInBox    (1 - pi 0.2^2) h, h = 1/64 the thickness     rel. 1e-3
#       sphereInBox  1 - 4/3 pi 0.3^3                             rel. 1e-3
#       csgPart      1 - (0.0525 + pi 0.008025)                   rel. 2e-3
#       stepPart     the same (gmsh triangulation, meshSize 0.02) rel. 2e-3
#       stlPart      the same (STL triangulation, clmax 0.03)     rel. 5e-3
#     (the cut cells are exact to the piecewise-linear boundary, so the
#     error is second order in h, plus the triangulation's chord error for
#     STL and CAD; the measured error is printed in the PASS line);
#   - mergeCells: total volume unchanged (to 1e-12 relative) and equal to
#     cutCells' fluid volume, smallest volume ratio >= 0.5 after merging
#     or every cell still below it listed with a reason;
#   - the merged grid: checkGrid says "Grid OK.", counts the cells that
#     mergeCells reports and cutCells' fluid volume (to 1e-10, the digits
#     it prints); VTK's own reader reads VTK/<case>_0.vtk with that many
#     cells, and in 2-D the polygons' areas times the thickness add up to
#     the fluid volume (to 1e-12);
#   - when OpenFOAM is installed, its checkMesh says "Mesh OK." on the
#     merged grid and counts the same cells (else SKIP).
# Then Allclean must restore the case as it came.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
scratch=$PWD

if [ -z "${WM_PROJECT_DIR:-}" ] && [ -d /usr/share/openfoam ]; then
    export WM_PROJECT_DIR=/usr/share/openfoam
fi
have_openfoam=0
command -v checkMesh > /dev/null 2>&1 && have_openfoam=1

# run_case NAME EXACT_FLUID_VOLUME RELATIVE_TOLERANCE
run_case() {
    local name=$1 exact=$2 tol=$3
    local src=$top/tutorials/grids/$name case=$scratch/$name
    fresh_copy "$src" "$case"
    local pristine
    pristine=$(listing "$case")
    timed_allrun "grids_${name}_allrun" "$case"

    # Every log exists and ends with End; checkGrid's say Grid OK.
    local bad="" app log last
    for app in blockGrid cutCells checkGrid mergeCells checkGrid.merged writeVTK; do
        log=$case/log.$app
        if [ ! -s "$log" ]; then bad="$bad log.$app missing;"; continue; fi
        last=$(grep -v '^[[:space:]]*$' "$log" | tail -n 1)
        case $app in
            checkGrid*)
                grep -q '^Grid OK\.' "$log" || bad="$bad log.$app has no 'Grid OK.';"
                [ "$last" = End ] || [ "$last" = "Grid OK." ] || bad="$bad log.$app ends with '$last';"
                ;;
            *) [ "$last" = End ] || bad="$bad log.$app ends with '$last';" ;;
        esac
    done
    if [ -z "$bad" ]; then pass "grids_${name}_logs"; else fail "grids_${name}_logs" "$bad"; fi

    # The files the header promises.
    local missing="" f
    for f in constant/polyMesh/points constant/polyMesh/faces constant/polyMesh/owner \
        constant/polyMesh/neighbour constant/polyMesh/boundary constant/polyMesh/cartesianGrid \
        constant/polyMesh/cellParent constant/polyMesh/boundaryNormal constant/polyMesh/mergeMap \
        "VTK/${name}_0.vtk" "VTK/$name.vtk.series" VTK/part/part_0.vtk; do
        case $f in VTK/part/*) [ "$name" = discInBox ] && f=VTK/disc/disc_0.vtk
                               [ "$name" = sphereInBox ] && f=VTK/sphere/sphere_0.vtk ;; esac
        [ -s "$case/$f" ] || [ -s "$case/$f.gz" ] || missing="$missing $f"
    done
    if [ -z "$missing" ]; then pass "grids_${name}_files"; else fail "grids_${name}_files" "missing:$missing"; fi

    # The numbers: fluid volume, merging, VTK.
    PYTHONDONTWRITEBYTECODE=1 KIESEL_TESTS_PY="$top/tests/tutorials" /usr/bin/python3 - "$case" "$name" "$exact" "$tol" <<'PYEOF'
import os, re, sys

case, name, exact, tol = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])


sys.path.insert(0, os.environ["KIESEL_TESTS_PY"])
from gridcheck import Check

chk = Check("grids", case, name)
report, log, number = chk.report, chk.log, chk.number


# --- cutCells: the fluid volume against the exact one ------------------------
fluid = float("nan")
try:
    cut = log("cutCells")
    fluid = float(number(r"^\s*fluid volume:\s*(\S+)", cut, "fluid volume"))
    rel = abs(fluid - exact) / exact
    report("volume", rel <= tol,
           "fluid volume %.12g, exact %.12g: relative error %.3g > %g" % (fluid, exact, rel, tol),
           "fluid volume %.12g, exact %.12g, relative error %.3g (tolerance %g)" % (fluid, exact, rel, tol))
except (OSError, ValueError) as ex:
    report("volume", False, str(ex))

# --- mergeCells: volume unchanged, every cell at least half its parent --------
ncells = -1
try:
    mlog = log("mergeCells")
    nin = int(number(r"^\s*cells in:\s*(\d+)", mlog, "'cells in'"))
    ncells = int(number(r"^\s*cells out:\s*(\d+)", mlog, "'cells out'"))
    m = re.search(r"^\s*total volume:\s*before\s*([^,\s]+),\s*after\s*(\S+)", mlog, re.M)
    if not m:
        raise ValueError("no 'total volume: before V, after V' in log.mergeCells")
    vin, vout = float(m.group(1)), float(m.group(2))
    m = re.search(r"^\s*smallest volume ratio:\s*before\s*([^,\s]+),\s*after\s*(\S+)", mlog, re.M)
    if not m:
        raise ValueError("no 'smallest volume ratio: before r, after r' in log.mergeCells")
    rin, rout = float(m.group(1)), float(m.group(2))
    nunres = int(number(r"^\s*unresolved cells:\s*(\d+)", mlog, "'unresolved cells'"))
    listed = len(re.findall(r"^\s*cell \d+ \(parent \d+, volume ratio \S+\): \S", mlog, re.M))
    errs = []
    if abs(vout - vin) > 1e-12 * vin:
        errs.append("total volume %.17g -> %.17g" % (vin, vout))
    if abs(vin - fluid) > 1e-9 * fluid:
        errs.append("volume in %.15g is not cutCells' fluid volume %.15g" % (vin, fluid))
    if rout < 0.5 and (nunres == 0 or listed < nunres):
        errs.append("smallest volume ratio %.6g < 0.5 and %d unresolved cell(s), %d listed"
                    % (rout, nunres, listed))
    if ncells >= nin:
        errs.append("%d cells in, %d out: nothing merged" % (nin, ncells))
    report("merge", not errs, "; ".join(errs),
           "%d -> %d cells, volume ratio %.3g -> %.3g, total volume %.15g unchanged%s"
           % (nin, ncells, rin, rout, vout, (", %d unresolved (listed)" % nunres) if nunres else ""))
except (OSError, ValueError) as ex:
    report("merge", False, str(ex))

# --- checkGrid on the merged grid: the same cells, the same volume ------------
try:
    cg = log("checkGrid.merged")
    n = int(number(r"^\s*cells:\s*(\d+)", cg, "cell count"))
    v = float(number(r"^\s*Total volume\s*=\s*(\S+)", cg, "total volume"))
    errs = []
    if n != ncells:
        errs.append("checkGrid counts %d cells, mergeCells %d" % (n, ncells))
    if not abs(v - fluid) <= 1e-10 * fluid:   # printed to 12 digits
        errs.append("checkGrid's total volume %.12g is not cutCells' fluid volume %.15g" % (v, fluid))
    report("checkGrid_merged", not errs, "; ".join(errs))
except (OSError, ValueError) as ex:
    report("checkGrid_merged", False, str(ex))

# --- the VTK file, read by VTK's own reader ------------------------------------
chk.vtk_reader(ncells, fluid, 1 / 64 if name == "discInBox" else 0, "the merged grid")
PYEOF

    # OpenFOAM's checkMesh passes the merged grid (SKIP without OpenFOAM).
    if [ "$have_openfoam" = 0 ]; then
        echo "SKIP grids_${name}_openfoam: OpenFOAM's checkMesh not installed"
    elif [ ! -f "$case/log.mergeCells" ]; then
        fail "grids_${name}_openfoam" "no merged grid to check (mergeCells did not run)"
    else
        local cm ncm nmerged
        cm=$(checkMesh -case "$case" 2>&1)
        ncm=$(grep -E '^ +cells: +[0-9]+$' <<<"$cm" | head -n 1 | awk '{ print $2 }')
        nmerged=$(grep -E '^ *cells out: *[0-9]+' "$case/log.mergeCells" | awk '{ print $3 }')
        if ! grep -q '^Mesh OK\.' <<<"$cm"; then
            fail "grids_${name}_openfoam" "checkMesh: $(grep -E 'Failed|FATAL|\*\*\*' <<<"$cm" | head -n 4 | tr '\n' ' ')"
        elif [ "$ncm" != "$nmerged" ]; then
            fail "grids_${name}_openfoam" "checkMesh counts ${ncm:-no} cells, mergeCells ${nmerged:-no}"
        else
            pass "grids_${name}_openfoam" "Mesh OK., $ncm cells"
        fi
    fi

    # Allclean restores the pristine case.
    (cd / && "$case/Allclean" > /dev/null 2>&1)
    local now
    now=$(listing "$case")
    if [ "$now" = "$pristine" ]; then
        pass "grids_${name}_allclean"
    else
        fail "grids_${name}_allclean" "left: $(diff <(echo "$pristine") <(echo "$now") | grep '^[<>]' | head -n 5 | tr '\n' ' ')"
    fi
}

part=$(awk 'BEGIN { printf "%.17g", 1 - (0.0525 + atan2(0, -1) * 0.008025) }')
run_case discInBox "$(awk 'BEGIN { printf "%.17g", (1 - atan2(0, -1) * 0.04) / 64 }')" 1e-3
run_case sphereInBox "$(awk 'BEGIN { printf "%.17g", 1 - 4 / 3 * atan2(0, -1) * 0.027 }')" 1e-3
run_case csgPart "$part" 2e-3
run_case stlPart "$part" 5e-3
run_case stepPart "$part" 2e-3
