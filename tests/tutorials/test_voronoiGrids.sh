#!/usr/bin/env bash
# tutorials/grids/{hollowCylinder,discLayers,rotatedChannel} end to end: the
# Voronoi grid tutorials (voronoiGrid, ICCM^V, thesis §3.2.4).  Copies each
# case to the scratch directory, runs its Allrun from another directory, and
# checks the logs, the output files and numbers in them against values
# computed here independently:
#
#   - the fluid volume that voronoiGrid reports against the exact volume of
#     the flow domain (measured relative errors in brackets; the boundary is
#     the polyhedron of the pair faces, so the error is second order in h):
#       hollowCylinder  pi (0.35^2 1.1 - 0.15^2 0.7)   rel. 4e-4  (1.78e-4)
#       discLayers      (1 - pi 0.2^2) h, h = 1/64      rel. 2e-4  (7.4e-5)
#       rotatedChannel  1.0 x 0.3 x 0.3                 rel. 1e-5  (1.7e-6: the
#                                                     box's edges and corners
#                                                     are reproduced, Fig. 3.16)
#     (the measured error is printed in the PASS line);
#   - the smallest cell volume is at least the bound voronoiGrid prints, and
#     that bound is pi a^3/6 (2-D: pi a^2/4 x thickness) with a = h/2 (the
#     tutorials' minSpacing 0.5) and h known here (to 1e-5, the 6 digits
#     printed);
#   - the largest angle between a wall face and the exact normal that
#     voronoiGrid reports (measured in brackets):
#       hollowCylinder  50 deg    (46.6: small faces at the rims, between
#                                 the edge seeds and the caps' pairs)
#       discLayers      1e-3 deg  (1e-12 to 1e-6: in 2-D every wall face is
#                                 a pair face, normal to the circle)
#       rotatedChannel  50 deg    (41.6: small faces where the turned
#                                 box's samples do not fit its edges)
#     and, where the log gives it, the share of the wall area within its
#     angle of the exact normal (measured 99.98 %, 100 %, 99.96 %): at
#     least 99.9 % each;
#   - checkGrid says "Grid OK." and counts voronoiGrid's cells and fluid
#     volume (to 1e-10, the digits it prints); VTK's own reader reads
#     VTK/<case>_0.vtk with that many cells, and in 2-D the polygons' areas
#     times the thickness add up to the fluid volume (to 1e-12);
#   - when OpenFOAM is installed, its checkMesh says "Mesh OK." and counts
#     the same cells (else SKIP).
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

# run_case NAME EXACT_FLUID_VOLUME VOLUME_TOL H THICKNESS ANGLE_TOL_DEG MIN_AREA_PERCENT PATCHES...
#   THICKNESS: 0 for a 3-D case, else the 2-D case's cell thickness.
run_case() {
    local name=$1 exact=$2 tol=$3 h=$4 thick=$5 angtol=$6 minarea=$7
    shift 7
    local patches="$*"
    local src=$top/tutorials/grids/$name case=$scratch/$name
    fresh_copy "$src" "$case"
    local pristine
    pristine=$(listing "$case")
    timed_allrun "voronoi_${name}_allrun" "$case"

    # Every log exists and ends with End; checkGrid's says Grid OK.
    local bad="" app log last
    for app in blockGrid voronoiGrid checkGrid writeVTK; do
        log=$case/log.$app
        if [ ! -s "$log" ]; then bad="$bad log.$app missing;"; continue; fi
        last=$(grep -v '^[[:space:]]*$' "$log" | tail -n 1)
        case $app in
            checkGrid)
                grep -q '^Grid OK\.' "$log" || bad="$bad log.$app has no 'Grid OK.';"
                [ "$last" = End ] || [ "$last" = "Grid OK." ] || bad="$bad log.$app ends with '$last';"
                ;;
            *) [ "$last" = End ] || bad="$bad log.$app ends with '$last';" ;;
        esac
    done
    if [ -z "$bad" ]; then pass "voronoi_${name}_logs"; else fail "voronoi_${name}_logs" "$bad"; fi

    # The files the Allrun header promises.
    local missing="" f p
    for f in constant/polyMesh/points constant/polyMesh/faces constant/polyMesh/owner \
        constant/polyMesh/neighbour constant/polyMesh/boundary constant/polyMesh/cellSeed \
        constant/polyMesh/boundaryNormal "VTK/${name}_0.vtk" "VTK/$name.vtk.series"; do
        [ -s "$case/$f" ] || [ -s "$case/$f.gz" ] || missing="$missing $f"
    done
    for p in $patches; do
        [ -s "$case/VTK/$p/${p}_0.vtk" ] || missing="$missing VTK/$p/${p}_0.vtk"
    done
    if [ -z "$missing" ]; then pass "voronoi_${name}_files"; else fail "voronoi_${name}_files" "missing:$missing"; fi

    # The numbers: fluid volume, smallest cell, normals, checkGrid, VTK.
    PYTHONDONTWRITEBYTECODE=1 KIESEL_TESTS_PY="$top/tests/tutorials" /usr/bin/python3 - "$case" "$name" "$exact" "$tol" "$h" "$thick" "$angtol" "$minarea" <<'PYEOF'
import math, os, re, sys

case, name = sys.argv[1], sys.argv[2]
exact, tol, h, thick, angtol, minarea = (float(x) for x in sys.argv[3:9])


sys.path.insert(0, os.environ["KIESEL_TESTS_PY"])
from gridcheck import Check

chk = Check("voronoi", case, name)
report, log, number = chk.report, chk.log, chk.number


vlog = ""
try:
    vlog = log("voronoiGrid")
except OSError as ex:
    report("volume", False, str(ex))

# --- the fluid volume against the exact one ----------------------------------
fluid, ncells = float("nan"), -1
try:
    fluid = float(number(r"^\s*fluid volume:\s*(\S+)", vlog, "fluid volume"))
    ncells = int(number(r"^\s*cells:\s*(\d+)", vlog, "cell count"))
    rel = abs(fluid - exact) / exact
    report("volume", rel <= tol,
           "fluid volume %.12g, exact %.12g: relative error %.3g > %g" % (fluid, exact, rel, tol),
           "%d cells, fluid volume %.12g, exact %.12g, relative error %.3g (tolerance %g)"
           % (ncells, fluid, exact, rel, tol))
except ValueError as ex:
    report("volume", False, str(ex))

# --- the smallest cell against the bound from the minimum seed spacing -------
try:
    m = re.search(r"^\s*smallest cell volume:\s*(\S+)\s*\(bound from a:\s*([^)\s]+)\)", vlog, re.M)
    if not m:
        raise ValueError("no 'smallest cell volume: V (bound from a: B)' in log.voronoiGrid")
    vmin, bound = float(m.group(1)), float(m.group(2))
    a = 0.5 * h   # minSpacing 0.5 in every tutorial
    mine = math.pi * a ** 2 / 4 * thick if thick > 0 else math.pi * a ** 3 / 6
    errs = []
    if not vmin >= bound:
        errs.append("smallest cell volume %.6g < bound %.6g" % (vmin, bound))
    if not abs(bound - mine) <= 1e-5 * mine:
        errs.append("printed bound %.6g is not %s = %.6g" % (bound, "pi a^2/4 x thickness" if thick > 0
                                                             else "pi a^3/6", mine))
    report("min_volume", not errs, "; ".join(errs),
           "smallest %.6g >= bound %.6g (%.3g x)" % (vmin, bound, vmin / bound))
except ValueError as ex:
    report("min_volume", False, str(ex))

# --- the wall faces against the exact normals ----------------------------------
try:
    line = next((l for l in vlog.splitlines() if "exact normal" in l), None)
    if line is None:
        raise ValueError("no line on the exact normal in log.voronoiGrid")
    # "largest angle between a surface face and the exact normal: X deg" or
    # "... exact normal: n of N (P% of the area); largest angle X deg"
    m = re.search(r"(?:largest angle|exact normal:)\s*([-+0-9.eE]+)\s*deg", line)
    if not m:
        raise ValueError("no largest angle in %r" % line.strip())
    ang = float(m.group(1))
    errs = []
    note = "largest angle %.3g deg (tolerance %g)" % (ang, angtol)
    if not ang <= angtol:
        errs.append("largest angle between a wall face and the exact normal %.3g deg > %g" % (ang, angtol))
    m = re.search(r"\(([0-9.]+)% of the area\)", line)
    if m:
        share = float(m.group(1))
        note += ", %.2f%% of the wall area near the normal (at least %g%%)" % (share, minarea)
        if not share >= minarea:
            errs.append("%.2f%% of the wall area near the exact normal < %g%%" % (share, minarea))
    report("normals", not errs, "; ".join(errs), note)
except ValueError as ex:
    report("normals", False, str(ex))

# --- checkGrid: the same cells, the same volume ---------------------------------
try:
    cg = log("checkGrid")
    n = int(number(r"^\s*cells:\s*(\d+)", cg, "cell count"))
    v = float(number(r"^\s*Total volume\s*=\s*(\S+)", cg, "total volume"))
    errs = []
    if n != ncells:
        errs.append("checkGrid counts %d cells, voronoiGrid %d" % (n, ncells))
    if not abs(v - fluid) <= 1e-10 * fluid:   # printed to 12 digits
        errs.append("checkGrid's total volume %.12g is not voronoiGrid's fluid volume %.15g" % (v, fluid))
    report("checkGrid", not errs, "; ".join(errs))
except (OSError, ValueError) as ex:
    report("checkGrid", False, str(ex))

# --- the VTK file, read by VTK's own reader ------------------------------------
chk.vtk_reader(ncells, fluid, thick, "voronoiGrid")
PYEOF

    # OpenFOAM's checkMesh passes the Voronoi grid (SKIP without OpenFOAM).
    if [ "$have_openfoam" = 0 ]; then
        echo "SKIP voronoi_${name}_openfoam: OpenFOAM's checkMesh not installed"
    elif [ ! -s "$case/log.voronoiGrid" ]; then
        fail "voronoi_${name}_openfoam" "no Voronoi grid to check (voronoiGrid did not run)"
    else
        local cm ncm nvor
        cm=$(checkMesh -case "$case" 2>&1)
        ncm=$(grep -E '^ +cells: +[0-9]+$' <<<"$cm" | head -n 1 | awk '{ print $2 }')
        nvor=$(grep -E '^ *cells: *[0-9]+' "$case/log.voronoiGrid" | head -n 1 | awk '{ print $2 }')
        if ! grep -q '^Mesh OK\.' <<<"$cm"; then
            fail "voronoi_${name}_openfoam" "checkMesh: $(grep -E 'Failed|FATAL|\*\*\*' <<<"$cm" | head -n 4 | tr '\n' ' ')"
        elif [ "$ncm" != "$nvor" ]; then
            fail "voronoi_${name}_openfoam" "checkMesh counts ${ncm:-no} cells, voronoiGrid ${nvor:-no}"
        else
            pass "voronoi_${name}_openfoam" "Mesh OK., $ncm cells"
        fi
    fi

    # Allclean restores the pristine case.
    (cd / && "$case/Allclean" > /dev/null 2>&1)
    local now
    now=$(listing "$case")
    if [ "$now" = "$pristine" ]; then
        pass "voronoi_${name}_allclean"
    else
        fail "voronoi_${name}_allclean" "left: $(diff <(echo "$pristine") <(echo "$now") | grep '^[<>]' | head -n 5 | tr '\n' ' ')"
    fi
}

pi_times() { awk -v x="$1" 'BEGIN { printf "%.17g", atan2(0, -1) * x }'; }
run_case hollowCylinder "$(pi_times 0.119)" 4e-4 0.025 0 50 99.9 outerWall innerWall box
run_case discLayers "$(awk 'BEGIN { printf "%.17g", (1 - atan2(0, -1) * 0.04) / 64 }')" 2e-4 0.015625 0.015625 1e-3 99.9 disc walls
run_case rotatedChannel 0.09 1e-5 0.025 0 50 99.9 channel box
