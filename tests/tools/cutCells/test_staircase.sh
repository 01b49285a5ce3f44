#!/usr/bin/env bash
# test_staircase.sh: cutCells' method staircase (common/cut_staircase.c).
#   - -help lists the keyword method with its default (cut);
#   - 2-D disc (r = 0.3 about (0.5, 0.5), 40^2 grid) and 3-D sphere (r =
#     0.3, 16^3): the fluid volume the log reports is the count of Cartesian
#     cell centres inside the shape (counted here, in awk) times the cell
#     volume, to 1e-12;
#   - every face of the wall patch is axis-aligned (all its points share
#     one coordinate to 1e-12) and lies on a grid plane, the patch has
#     exactly the faces between a kept and a dropped cell (counted here),
#     and every cell is a box (8 points);
#   - checkGrid: "Grid OK." with roles whole and outside only (cut 0,
#     master 0, slave 0); mergeCells leaves the grid as it is (nothing to
#     merge);
#   - OpenFOAM's checkMesh (when installed) says "Mesh OK." on the disc and
#     finds no validity error on the sphere;
#   - a bad method is refused with cutCellsDict:line and the choices.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

h=$("$BIN/cutCells" -help 2>&1)
grep -q 'method.*cut.*staircase' <<<"$h" && pass staircase_help || fail staircase_help "-help does not list method"

# centres N NZ: the number of Cartesian cell centres inside the shape
centres() {
    awk -v n="$1" -v nz="$2" 'BEGIN { c = 0
        for (i = 0; i < n; i++) for (j = 0; j < n; j++) for (k = 0; k < nz; k++) {
            x = (i + 0.5) / n - 0.5; y = (j + 0.5) / n - 0.5; z = nz > 1 ? (k + 0.5) / n - 0.5 : 0
            if (x * x + y * y + z * z < 0.09) c++ }
        print c }'
}

# faces_check DIR: the wall patch's faces against the grid (python reads
# the ascii polyMesh and cartesianGrid)
faces_check() {
    /usr/bin/python3 - "$1/constant/polyMesh" <<'EOF'
import re, sys
d = sys.argv[1]
def body(name):
    t = open(d + "/" + name).read()
    return t[t.index("}", t.index("FoamFile")) + 1:]
def lst(name):
    t = re.sub(r"//.*", "", body(name))
    m = re.search(r"(\d+)\s*\(", t)
    return t[m.end():]
pts = [tuple(map(float, p)) for p in re.findall(r"\(([-\d.eE+]+) ([-\d.eE+]+) ([-\d.eE+]+)\)", lst("points"))]
faces = [list(map(int, f.split())) for f in re.findall(r"\d+\(([\d ]+)\)", lst("faces"))]
own = list(map(int, re.findall(r"\d+", lst("owner"))))
bnd = body("boundary")
wall = re.search(r"wall\s*\{[^}]*startFace\s+(\d+);", bnd) or re.search(r"ball\s*\{[^}]*startFace\s+(\d+);", bnd)
nw = re.search(r"(?:wall|ball)\s*\{[^}]*nFaces\s+(\d+);", bnd)
start, n = int(wall.group(1)), int(nw.group(1))
cg = body("cartesianGrid")
xs = [list(map(float, re.search(k + r"\s+\d+\(([^)]*)\)", cg).group(1).split())) for k in "xyz"]
bad = 0
for f in range(start, start + n):
    p = [pts[i] for i in faces[f]]
    ok = False
    for a in range(3):
        if max(q[a] for q in p) - min(q[a] for q in p) < 1e-12 and min(abs(p[0][a] - x) for x in xs[a]) < 1e-12:
            ok = True
    bad += not ok
cells = {}
for f, o in enumerate(own):
    cells.setdefault(o, set()).update(faces[f])
nb = re.findall(r"\d+", lst("neighbour"))
for f, o in enumerate(map(int, nb)):
    cells.setdefault(o, set()).update(faces[f])
notbox = sum(len(s) != 8 for s in cells.values())
print(n, bad, notbox)
EOF
}

# walls N NZ: faces between a kept and a dropped Cartesian cell (inside the box)
walls() {
    awk -v n="$1" -v nz="$2" 'function kin(i, j, k) { x = (i + 0.5) / n - 0.5; y = (j + 0.5) / n - 0.5
            z = nz > 1 ? (k + 0.5) / n - 0.5 : 0; return x * x + y * y + z * z < 0.09 }
        BEGIN { c = 0
        for (i = 0; i < n; i++) for (j = 0; j < n; j++) for (k = 0; k < nz; k++) {
            if (i + 1 < n && kin(i, j, k) != kin(i + 1, j, k)) c++
            if (j + 1 < n && kin(i, j, k) != kin(i, j + 1, k)) c++
            if (nz > 1 && k + 1 < nz && kin(i, j, k) != kin(i, j, k + 1)) c++ }
        print c }'
}

run_case() { # name n nz shape
    local d=$1 n=$2 nz=$3
    rm -rf "$d"
    unit_box "$d" "$n" "$nz"
    geometry_dict "$d" "wall { flow inside; $4 }"
    printf '%s\nmethod staircase;\n' "$(header cutCellsDict)" >"$d/system/cutCellsDict"
    "$BIN/blockGrid" -case "$d" >"$d/log.blockGrid" 2>&1
    if ! "$BIN/cutCells" -case "$d" >"$d/log.cutCells" 2>&1; then
        fail "staircase_${d}_runs" "$(tail -n 3 "$d/log.cutCells")"
        return
    fi
    local k v ex r
    k=$(centres "$n" "$nz")
    v=$(fluid "$d/log.cutCells")
    ex=$(awk -v k="$k" -v n="$n" -v nz="$nz" 'BEGIN { printf "%.15g", k / (n * n) * (nz > 1 ? 1 / n : 0.02) }')
    r=$(rel "$v" "$ex")
    le "$r" 1e-12 && pass "staircase_${d}_volume" "$k centres inside, volume $v (count x cell $ex, rel $r)" ||
        fail "staircase_${d}_volume" "volume $v, $k centres x cell volume = $ex (rel $r)"
    local fc nwall nbad nbox w
    fc=$(faces_check "$d")
    read -r nwall nbad nbox <<<"$fc"
    w=$(walls "$n" "$nz")
    [ "$nbad" = 0 ] && [ "$nwall" = "$w" ] && [ "$nwall" -gt 0 ] &&
        pass "staircase_${d}_walls_axis_aligned" "$nwall wall faces, all on grid planes" ||
        fail "staircase_${d}_walls_axis_aligned" "$nwall wall faces (expected $w), $nbad not axis-aligned"
    [ "$nbox" = 0 ] && pass "staircase_${d}_cells_are_boxes" || fail "staircase_${d}_cells_are_boxes" "$nbox cells without 8 points"
    "$BIN/checkGrid" -case "$d" >"$d/log.checkGrid" 2>&1
    grep -q 'Grid OK' "$d/log.checkGrid" && grep -q "outside $((n * n * nz - k)), whole $k, cut 0, master 0, slave 0" "$d/log.checkGrid" &&
        pass "staircase_${d}_checkGrid_roles" "$(grep 'Cartesian cells:' "$d/log.checkGrid" | sed 's/^ *//')" ||
        fail "staircase_${d}_checkGrid_roles" "$(grep -e 'Cartesian cells:' -e 'Grid' "$d/log.checkGrid" | tr '\n' ' ')"
    if command -v checkMesh >/dev/null 2>&1; then
        export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
        case_system "$d" cutCells
        checkMesh -case "$d" >"$d/log.checkMesh" 2>&1
        if grep -q 'Mesh OK' "$d/log.checkMesh"; then
            pass "staircase_${d}_checkMesh" "Mesh OK."
        else
            fail "staircase_${d}_checkMesh" "$(grep -E '^ *\*\*\*|FATAL' "$d/log.checkMesh" | head -n 3 | tr '\n' ' ')"
        fi
    else
        skip "staircase_${d}_checkMesh" "OpenFOAM's checkMesh is not installed"
    fi
}

run_case disc 40 1 'shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 2); radius 0.3;'
run_case sphere 16 16 'shape sphere; centre (0.5 0.5 0.5); radius 0.3;'

# mergeCells finds nothing to merge: every cell is whole
if "$BIN/mergeCells" -case disc >disc/log.mergeCells 2>&1; then
    "$BIN/checkGrid" -case disc >disc/log.checkGrid2 2>&1
    grep -q 'cut 0, master 0, slave 0' disc/log.checkGrid2 && pass staircase_merge_nothing ||
        fail staircase_merge_nothing "$(grep 'Cartesian cells:' disc/log.checkGrid2)"
else
    fail staircase_merge_nothing "mergeCells failed: $(tail -n 2 disc/log.mergeCells)"
fi

# a bad method: file:line, the choices, non-zero exit
printf '%s\nmethod stairs;\n' "$(header cutCellsDict)" >disc/system/cutCellsDict
if "$BIN/cutCells" -case disc >disc/log.bad 2>&1; then
    fail staircase_bad_method "method stairs was accepted"
else
    grep -q 'cutCellsDict:2:.*cut.*staircase' disc/log.bad && pass staircase_bad_method "$(grep cutCellsDict disc/log.bad | head -n 1)" ||
        fail staircase_bad_method "$(tail -n 2 disc/log.bad)"
fi
