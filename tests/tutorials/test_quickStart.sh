#!/usr/bin/env bash
# tutorials/basic/quickStart end to end: copies the case to the scratch
# directory, runs its Allrun, and checks the logs, the output files and
# numbers in them against values computed here independently:
#
#   - the grid's y points from blockMesh's grading formula
#     t_i = (q^i - 1)/(q^n - 1), q = g^(1/(n-1)), n = 40, g = 4;
#   - the bed (box, y <= 0.2, alpha.s = 0.6): the cell that the plane
#     y = 0.2 cuts holds 0.6 (0.2 - y_j)/(y_j+1 - y_j), to 1e-12 (box
#     fractions are exact up to round-off);
#   - the disc (cylinder, centre (0.5, 0.6), r = 0.15, alpha.s = 0.5,
#     U = (0 -1 0)): 0.5 and (0 -1 0) in the middle of the horizontal line
#     exactly, 0 away from it, rim values strictly between;
#   - the grains' volume sum(alpha.s V) over 0/alpha.s against
#     0.6*0.2*dz + 0.5*pi*0.15^2*dz (relative tolerance 1e-4: the disc's
#     cut-cell fractions are second-order approximations; measured error
#     is reported in the PASS line);
#   - the per-cell line: one sample per cell of the column (40), at the
#     cell's mid-height, lengths adding up to 1 (to 1e-12).
# VTK's own reader must read the VTK file with the same grain volume.
# When OpenFOAM is installed, its checkMesh must say "Mesh OK." and its
# foamToVTK must read both fields (else SKIP).  Then a second Allrun must
# change nothing, and Allclean must restore the case as it came.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
export KIESEL_DIR=$top
src=$top/tutorials/basic/quickStart
case=$PWD/quickStart

fresh_copy "$src" "$case"
pristine=$(listing "$case")

# Run from another directory, as `make tutorial` does.
out=$(cd / && timeout 120 "$case/Allrun" 2>&1); rc=$?
if [ "$rc" -ne 0 ]; then
    fail quickStart_allrun "Allrun exited with status $rc; output:"
    printf '%s\n' "$out" | tail -n 20 | sed 's/^/  /'
    exit 1
fi
pass quickStart_allrun

# Every log exists and ends with End; checkGrid's says Grid OK.
bad=""
for app in blockGrid checkGrid setFields writeVTK sampleLine; do
    log=$case/log.$app
    if [ ! -s "$log" ]; then bad="$bad log.$app missing;"; continue; fi
    last=$(grep -v '^[[:space:]]*$' "$log" | tail -n 1)
    if [ "$app" = checkGrid ]; then
        grep -q '^Grid OK\.' "$log" || bad="$bad log.checkGrid has no 'Grid OK.';"
    fi
    if [ "$last" != End ] && ! { [ "$app" = checkGrid ] && [ "$last" = "Grid OK." ]; }; then
        bad="$bad log.$app ends with '$last';"
    fi
done
if [ -z "$bad" ]; then pass quickStart_logs; else fail quickStart_logs "$bad"; fi

# The files the header promises.
missing=""
for f in constant/polyMesh/points constant/polyMesh/faces constant/polyMesh/owner \
    constant/polyMesh/neighbour constant/polyMesh/boundary constant/polyMesh/cartesianGrid \
    0/alpha.s 0/U VTK/quickStart_0.vtk VTK/quickStart.vtk.series \
    postProcessing/sampleLine/0/horizontal.csv postProcessing/sampleLine/0/vertical.csv \
    postProcessing/sampleLine/0/verticalCells.csv; do
    [ -s "$case/$f" ] || missing="$missing $f"
done
if command -v gnuplot > /dev/null 2>&1 && [ ! -s "$case/postProcessing/sampleLine/0/quickStart.png" ]; then
    missing="$missing postProcessing/sampleLine/0/quickStart.png"
fi
if [ -z "$missing" ]; then pass quickStart_files; else fail quickStart_files "missing:$missing"; fi

# The numbers.
"${KIESEL_PYTHON:-/usr/bin/python3}" - "$case" <<'PYEOF'
import csv, json, math, os, re, sys

case = sys.argv[1]
samples = os.path.join(case, "postProcessing", "sampleLine", "0")


def report(name, ok, why=""):
    print(("PASS %s" % name) if ok else ("FAIL %s: %s" % (name, why)))


def read_csv(name):
    with open(os.path.join(samples, name + ".csv"), newline="") as f:
        rows = list(csv.reader(f))
    head = [h.strip().lstrip("#").strip() for h in rows[0]]
    data = [[float(v) for v in r] for r in rows[1:] if r]
    return {h: [r[i] for r in data] for i, h in enumerate(head)}


def col(t, *names):
    for n in names:
        if n in t:
            return t[n]
    raise KeyError("none of %s in columns %s" % (names, sorted(t)))


# Grid points along y, independently of blockGrid: 40 cells, grading 4.
n, g = 40, 4.0
q = g ** (1.0 / (n - 1))
ys = [(q ** i - 1) / (q ** n - 1) for i in range(n + 1)]
dz = 0.025

# --- horizontal line through the disc centre (y = 0.6) ---------------------
try:
    h = read_csv("horizontal")
    x, a = col(h, "x"), col(h, "alpha.s")
    uy = col(h, "U_1", "U_y", "Uy", "U.y")
    ux = col(h, "U_0", "U_x", "Ux", "U.x")
    errs = []
    if len(x) != 101:
        errs.append("%d samples, expected 101" % len(x))
    for xi, ai, uxi, uyi in zip(x, a, ux, uy):
        if abs(xi - 0.5) <= 0.1:           # cells wholly inside the disc
            if abs(ai - 0.5) > 1e-12 or abs(uyi + 1) > 1e-12 or abs(uxi) > 1e-12:
                errs.append("x=%g: alpha.s=%.17g U=(%g %g), expected 0.5 (0 -1)" % (xi, ai, uxi, uyi))
        elif abs(xi - 0.5) >= 0.2:          # cells wholly outside
            if abs(ai) > 1e-12 or abs(uyi) > 1e-12:
                errs.append("x=%g: alpha.s=%.17g U_y=%g, expected 0" % (xi, ai, uyi))
        if not (-1e-12 <= ai <= 0.5 + 1e-12):
            errs.append("x=%g: alpha.s=%.17g outside [0, 0.5]" % (xi, ai))
    rim = [ai for ai in a if 1e-9 < ai < 0.5 - 1e-9]
    if len(rim) < 2:
        errs.append("only %d partly filled rim samples, expected at least 2" % len(rim))
    report("quickStart_disc_line", not errs, "; ".join(errs[:3]))
except (OSError, KeyError, ValueError, IndexError) as ex:
    report("quickStart_disc_line", False, str(ex))

# --- vertical line x = 0.5125: bed, its cut cell at y = 0.2, gap, disc -------
try:
    v = read_csv("vertical")
    y, a = col(v, "y"), col(v, "alpha.s")
    j = max(i for i in range(n) if ys[i] < 0.2)
    f = (0.2 - ys[j]) / (ys[j + 1] - ys[j])
    errs, hit = [], 0
    for yi, ai in zip(y, a):
        ks = [k for k in range(n) if ys[k] + 1e-12 < yi < ys[k + 1] - 1e-12]
        if not ks:
            continue                          # on a face: either cell may hold it
        k = ks[0]
        if k < j:
            want = 0.6                        # bed
        elif k == j:
            want, hit = 0.6 * f, hit + 1      # cut by the bed's top y = 0.2
        elif ys[k + 1] <= 0.449:
            want = 0.0                        # below the disc (bottom y = 0.45)
        elif ys[k] >= 0.46 and ys[k + 1] <= 0.74:
            want = 0.5                        # wholly inside the disc in this column
        elif ys[k] >= 0.751:
            want = 0.0                        # above the disc
        else:
            continue                          # the disc's rim
        if abs(ai - want) > 1e-12:
            errs.append("y=%g (cell %d): alpha.s=%.17g, expected %.17g" % (yi, k, ai, want))
    if not hit:
        errs.append("no sample in the cut cell %g < y < %g" % (ys[j], ys[j + 1]))
    report("quickStart_bed_cut_cell", not errs,
           "; ".join(errs[:3]) + " (cut cell %d, fraction %.6f)" % (j, f))
except (OSError, KeyError, ValueError, IndexError) as ex:
    report("quickStart_bed_cut_cell", False, str(ex))

# --- one sample per cell --------------------------------------------------------
try:
    c = read_csv("verticalCells")
    y, a = col(c, "y"), col(c, "alpha.s")
    ln = col(c, "length", "len", "cellLength")
    errs = []
    if len(y) != n:
        errs.append("%d samples, expected %d (one per cell)" % (len(y), n))
    else:
        for i in range(n):
            mid = 0.5 * (ys[i] + ys[i + 1])
            if abs(y[i] - mid) > 1e-12 or abs(ln[i] - (ys[i + 1] - ys[i])) > 1e-12:
                errs.append("cell %d: y=%.17g len=%.17g, expected %.17g and %.17g"
                            % (i, y[i], ln[i], mid, ys[i + 1] - ys[i]))
    if abs(sum(ln) - 1) > 1e-12:
        errs.append("lengths add up to %.17g, expected 1" % sum(ln))
    report("quickStart_cells_line", not errs, "; ".join(errs[:3]))
except (OSError, KeyError, ValueError, IndexError) as ex:
    report("quickStart_cells_line", False, str(ex))

# --- the grains' volume over the whole field --------------------------------------
total = float("nan")
try:
    text = open(os.path.join(case, "0", "alpha.s")).read()
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\((.*?)\)\s*;", text, re.S)
    if not m:
        raise ValueError("0/alpha.s: no ascii nonuniform internalField")
    vals = [float(t) for t in m.group(2).split()]
    if len(vals) != int(m.group(1)) or len(vals) != 40 * n:
        raise ValueError("0/alpha.s: %d values, expected %d" % (len(vals), 40 * n))
    dx = 1.0 / 40
    total = sum(vals[i + 40 * jj] * dx * (ys[jj + 1] - ys[jj]) * dz
                for jj in range(n) for i in range(40))
    want = 0.6 * 0.2 * dz + 0.5 * math.pi * 0.15 ** 2 * dz
    rel = abs(total - want) / want
    report("quickStart_grain_volume", rel <= 1e-4,
           "sum(alpha.s V) = %.12g, expected %.12g (relative error %.3g > 1e-4)" % (total, want, rel))
    if rel <= 1e-4:
        print("  grain volume %.12g, exact %.12g, relative error %.3g" % (total, want, rel))
except (OSError, ValueError) as ex:
    report("quickStart_grain_volume", False, str(ex))

# --- the VTK file, read by VTK's own reader ------------------------------------
try:
    import vtk
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(os.path.join(case, "VTK", "quickStart_0.vtk"))
    r.ReadAllFieldsOn()
    r.Update()
    grid = r.GetOutput()
    errs = []
    if grid.GetNumberOfCells() != 40 * n:
        errs.append("%d cells, expected %d" % (grid.GetNumberOfCells(), 40 * n))
    arr = grid.GetCellData().GetArray("alpha.s")
    if arr is None:
        errs.append("no cell array alpha.s")
    else:
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputData(grid)
        sizes.ComputeAreaOn()
        sizes.Update()
        area = sizes.GetOutput().GetCellData().GetArray("Area")
        alpha = [arr.GetValue(i) for i in range(arr.GetNumberOfTuples())]
        vtotal = sum(a * area.GetValue(i) for i, a in enumerate(alpha)) * dz
        if not abs(vtotal - total) <= 1e-12 * total:
            errs.append("sum(alpha.s area dz) = %.17g, 0/alpha.s gives %.17g" % (vtotal, total))
        if abs(max(alpha) - 0.6) > 1e-15:
            errs.append("max alpha.s %.17g, expected 0.6" % max(alpha))
    report("quickStart_vtk_reader", not errs, "; ".join(errs))
except ImportError as ex:
    print("SKIP quickStart_vtk_reader: no VTK module for python3 (%s)" % ex)
except Exception as ex:   # any failure of the reader is a failure of the file
    report("quickStart_vtk_reader", False, "%s: %s" % (type(ex).__name__, ex))

# --- the VTK series names the VTK file with time 0 ----------------------------
try:
    s = json.load(open(os.path.join(case, "VTK", "quickStart.vtk.series")))
    files = s["files"]
    ok = len(files) == 1 and files[0]["name"] == "quickStart_0.vtk" and files[0]["time"] == 0
    report("quickStart_vtk_series", ok, "files: %s" % files)
except (OSError, ValueError, KeyError) as ex:
    report("quickStart_vtk_series", False, str(ex))
PYEOF

# A second Allrun repeats nothing and changes nothing.
before=$(cd "$case" && find . -type f ! -name '*.png' -exec md5sum {} + | LC_ALL=C sort -k2)
out=$(timeout 60 "$case/Allrun" 2>&1); rc=$?
after=$(cd "$case" && find . -type f ! -name '*.png' -exec md5sum {} + | LC_ALL=C sort -k2)
refused=$(grep -c 'already run on' <<<"$out")
if [ "$rc" -ne 0 ]; then
    fail quickStart_rerun "second Allrun exited with status $rc"
elif [ "$refused" -ne 5 ]; then
    fail quickStart_rerun "$refused of 5 steps refused to re-run"
elif [ "$before" != "$after" ]; then
    fail quickStart_rerun "files changed: $(diff <(echo "$before") <(echo "$after") | head -n 4 | tr '\n' ' ')"
else
    pass quickStart_rerun
fi

# OpenFOAM reads the case: checkMesh passes the grid, foamToVTK reads both
# fields (Debian's OpenFOAM v1912; SKIP without it).
if [ -z "${WM_PROJECT_DIR:-}" ] && [ -d /usr/share/openfoam ]; then
    export WM_PROJECT_DIR=/usr/share/openfoam
fi
if command -v checkMesh > /dev/null 2>&1 && command -v foamToVTK > /dev/null 2>&1; then
    cm=$(checkMesh -case "$case" 2>&1)
    fv=$(foamToVTK -case "$case" -legacy -name openfoamVTK 2>&1); fvrc=$?
    rm -rf "$case/openfoamVTK"
    if ! grep -q '^Mesh OK\.' <<<"$cm"; then
        fail quickStart_openfoam "checkMesh: $(grep -E 'Failed|FATAL|\*\*\*' <<<"$cm" | head -n 3 | tr '\n' ' ')"
    elif ! grep -Eq 'cells: +1600$' <<<"$cm"; then
        fail quickStart_openfoam "checkMesh counts $(grep -E 'cells:' <<<"$cm" | head -n 1)"
    elif [ "$fvrc" -ne 0 ] || ! grep -q 'alpha\.s' <<<"$fv" || ! grep -Eq '(^|[ (])U([ )]|$)' <<<"$fv"; then
        fail quickStart_openfoam "foamToVTK (status $fvrc) did not read alpha.s and U: $(tail -n 3 <<<"$fv" | tr '\n' ' ')"
    else
        pass quickStart_openfoam
    fi
else
    echo "SKIP quickStart_openfoam: OpenFOAM's checkMesh/foamToVTK not installed"
fi

# Allclean restores the pristine case.
(cd / && "$case/Allclean" > /dev/null 2>&1)
now=$(listing "$case")
if [ "$now" = "$pristine" ]; then
    pass quickStart_allclean
else
    fail quickStart_allclean "left: $(diff <(echo "$pristine") <(echo "$now") | grep '^[<>]' | head -n 5 | tr '\n' ' ')"
fi
