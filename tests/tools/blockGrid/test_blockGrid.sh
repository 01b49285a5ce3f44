#!/usr/bin/env bash
# test_blockGrid.sh: blockGrid on small 2-D/3-D cases: the Mesh Information
# numbers, the files, the pipeline stream against the files, -help, every
# bad dictionary (file:line, non-zero exit, old grid untouched), binary and
# gzip output, and OpenFOAM's checkMesh when it is installed.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

# ---- 2-D case (the design example) ----
mkdir -p c2d/system
case_system c2d blockGrid
cat >c2d/system/blockGridDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockGridDict; }
scale 1;
x { start 0; segments ( (0.5 10 1) (1 20 4) ); }
y { start 0; segments ( (1 20 1) ); }
z { start 0; segments ( (0.1 1 1) ); }
boundary
{
    xMin { name left;   type wall; }
    xMax { name right;  type patch; }
    yMin { name bottom; type wall; }
    yMax { name top;    type wall; }
    zMin { name frontAndBack; type empty; }
    zMax { name frontAndBack; type empty; }
}
EOF
cp c2d/system/blockGridDict good2d.dict
"$BIN/blockGrid" -case c2d >log2d 2>&1; rc=$?
check blockGrid_2d_runs test $rc -eq 0
grep -q '^  nPoints: 1302$' log2d && grep -q '^  nCells: 600$' log2d &&
    grep -q '^  nFaces: 2450$' log2d && grep -q '^  nInternalFaces: 1150$' log2d &&
    grep -q '^  boundingBox: (0 0 0) (1 1 0.1)$' log2d
check blockGrid_2d_counts test $? -eq 0
want="  patch 0 (start: 1150 size: 20) name: left
  patch 1 (start: 1170 size: 20) name: right
  patch 2 (start: 1190 size: 30) name: bottom
  patch 3 (start: 1220 size: 30) name: top
  patch 4 (start: 1250 size: 1200) name: frontAndBack"
got=$(grep '^  patch ' log2d)
check blockGrid_2d_patches test "$got" = "$want"
grep -q '^Built 600 cells in ' log2d && grep -q '^ExecutionTime = ' log2d && grep -q '^End$' log2d
check blockGrid_2d_log test $? -eq 0
pm=c2d/constant/polyMesh
ok=1
for f in points faces owner neighbour boundary cartesianGrid cellParent; do [ -f $pm/$f ] || ok=0; done
check blockGrid_2d_files test $ok -eq 1
# faces count, owner note, the cartesianGrid's graded x axis (last/first width = 4)
grep -qx '2450' $pm/faces && grep -qx '1150' $pm/neighbour && grep -qx '600' $pm/cellParent
check blockGrid_2d_file_sizes test $? -eq 0
ratio=$(/usr/bin/python3 - $pm/cartesianGrid <<'EOF'
import re, sys
t = open(sys.argv[1]).read()
m = re.search(r'\nx\s+(\d+)\s*\(([^)]*)\)', t)
x = [float(v) for v in m.group(2).split()]
w = [b - a for a, b in zip(x, x[1:])]
print(len(x), "%.12f %.12f %.15g" % (w[-1] / w[10], w[0], x[-1]))
EOF
)
check blockGrid_2d_grading test "$ratio" = "31 4.000000000000 0.050000000000 1"

# the grid passes checkGrid; the pipeline gives the same report
"$BIN/checkGrid" -case c2d >chk_files 2>&1
check checkGrid_on_blockGrid_2d grep -q '^Grid OK\.$' chk_files
"$BIN/blockGrid" -case c2d -o - 2>pipe_err | "$BIN/checkGrid" -i - >chk_pipe 2>&1
strip() { sed -n '/^Grid stats/,/^Grid OK/p' "$1"; }
if [ -n "$(strip chk_files)" ] && [ "$(strip chk_files)" = "$(strip chk_pipe)" ]; then
    pass pipe_equals_files
else
    fail pipe_equals_files "$(diff <(strip chk_files) <(strip chk_pipe) | head -5)"
fi
check pipe_log_on_stderr grep -q '^  nCells: 600$' pipe_err
grep -q 'Grid is 2-D' chk_files && grep -q 'Total volume = 0.1$' chk_files &&
    grep -q 'Cut cells: 0' chk_files && grep -q 'Max aspect ratio = ' chk_files
check checkGrid_2d_numbers test $? -eq 0

# ---- 3-D graded case, binary from controlDict, -o DIR, -gzip ----
mkdir -p c3d/system
case_system c3d blockGrid binary
cat >c3d/system/blockGridDict <<'EOF'
x { start -1; segments ( (1 4 2) ); }
y { segments ( (0.5 3 1) (1 2 0.5) ); }
z { segments ( (3 3 1) ); }
EOF
"$BIN/blockGrid" -case c3d >log3d 2>&1
grep -q '^  nPoints: 120$' log3d && grep -q '^  nCells: 60$' log3d &&
    grep -q '^  nFaces: 227$' log3d && grep -q '^  nInternalFaces: 133$' log3d
check blockGrid_3d_counts test $? -eq 0
want="  patch 0 (start: 133 size: 15) name: xMin
  patch 1 (start: 148 size: 15) name: xMax
  patch 2 (start: 163 size: 12) name: yMin
  patch 3 (start: 175 size: 12) name: yMax
  patch 4 (start: 187 size: 20) name: zMin
  patch 5 (start: 207 size: 20) name: zMax"
check blockGrid_3d_default_patches test "$(grep '^  patch ' log3d)" = "$want"
check blockGrid_binary_from_controlDict grep -q 'format *binary' c3d/constant/polyMesh/faces
"$BIN/checkGrid" -case c3d >chk3d 2>&1
grep -q '^Grid OK\.$' chk3d && grep -q 'Grid is 3-D' chk3d && grep -q 'Total volume = 6$' chk3d
check checkGrid_3d_binary test $? -eq 0
"$BIN/blockGrid" -case c3d -gzip -o outgz >/dev/null 2>&1
check blockGrid_gzip_o_dir test -f outgz/points.gz -a -f outgz/faces.gz -a ! -e outgz/points
"$BIN/checkGrid" -i outgz >chkgz 2>&1
check checkGrid_reads_gzip test "$(strip chkgz)" = "$(strip chk3d)"

# ---- -dict FILE; a 2-D grid in the y-z plane (empty x sides) ----
cat >yz.dict <<'EOF'
x { start 2; segments ( (2.5 1 1) ); }
y { segments ( (1 3 1) ); }
z { segments ( (2 4 1) ); }
boundary { xMin { name fb; type empty; } xMax { name fb; type empty; } }
EOF
"$BIN/blockGrid" -case c3d -dict yz.dict -o yz >logyz 2>&1 && "$BIN/checkGrid" -i yz >chkyz 2>&1
grep -q '^  nCells: 12$' logyz && grep -q 'Grid is 2-D (empty directions: 1 0 0)' chkyz &&
    grep -q 'Total volume = 1$' chkyz && grep -q '^Grid OK\.$' chkyz
check blockGrid_dict_option_empty_x test $? -eq 0

# ---- -help: every keyword with its default ----
"$BIN/blockGrid" -help >help 2>&1
ok=1
for pat in '^  scale  *1 ' '^  x  *\[required\]' '^  y  *\[required\]' '^  z  *\[required\]' \
    '^  boundary  *{} ' '^  start  *0 ' '^  segments  *\[required\]' '^  name  *<side> ' \
    '^  type  *wall ' '^  neighbourPatch ' '^  -o DIR' '^  -binary' '^  -gzip'; do
    grep -q -- "$pat" help || { ok=0; echo "  missing in -help: $pat"; }
done
check blockGrid_help_keywords test $ok -eq 1

# ---- bad dictionaries: file:line error, exit 1, grid untouched ----
before=$(cat c2d/constant/polyMesh/* | md5sum)
bad() { # name, expected-stderr-substring, dictionary text
    printf '%s\n' "$3" >c2d/system/blockGridDict
    "$BIN/blockGrid" -case c2d >bad_out 2>bad_err; local rc=$?
    local after; after=$(cat c2d/constant/polyMesh/* | md5sum)
    if [ $rc -ne 0 ] && grep -qF -- "$2" bad_err && [ "$after" = "$before" ] &&
        ! ls -d c2d/constant/polyMesh.tmp* >/dev/null 2>&1; then
        pass "bad_$1"
    else
        fail "bad_$1" "rc=$rc, stderr: $(head -c 300 bad_err)"
    fi
}
AX='y { segments ((1 2 1)); }
z { segments ((0.1 1 1)); }'
bad decreasing "system/blockGridDict:1: x: segment 2 ends at 0.5, not after 0.5" \
    "x { segments ((0.5 2 1) (0.5 2 1)); }
$AX"
bad zero_cells "system/blockGridDict:3: x: segment 1: cells must be an integer >= 1, found 0" \
    "x
{
    segments ((1 0 1));
}
$AX"
bad grading "system/blockGridDict:1: x: segment 1: grading must be > 0, found -2" \
    "x { segments ((1 2 -2)); }
$AX"
bad unknown_key "system/blockGridDict:2: unknown keyword 'strat'" \
    "x { segments ((1 2 1)); }
y { strat 0; segments ((1 2 1)); }
z { segments ((0.1 1 1)); }"
bad suggestion "did you mean 'start'" \
    "x { segments ((1 2 1)); }
y { strat 0; segments ((1 2 1)); }
z { segments ((0.1 1 1)); }"
bad missing_axis "z" "x { segments ((1 2 1)); }
y { segments ((1 2 1)); }"
bad empty_two_cells "system/blockGridDict:5: boundary zMin: empty side needs exactly 1 cell along z, found 2" \
    "x { segments ((1 2 1)); }
y { segments ((1 2 1)); }
z { segments ((1 2 1)); }
boundary {
    zMin { name fb; type empty; }
    zMax { name fb; type empty; }
}"
bad two_types "system/blockGridDict:5: boundary xMax: patch 'w' is patch here but wall on side xMin" \
    "x { segments ((1 2 1)); }
$AX
boundary {
    xMax { name w; type patch; }
    xMin { name w; type wall; }
}"
bad cyclic_partner "system/blockGridDict:4: boundary xMin: neighbourPatch 'right' of cyclic patch 'left' is not a patch on another side" \
    "x { segments ((1 2 1)); }
$AX
boundary { xMin { name left; type cyclic; neighbourPatch right; } }"
bad cyclic_opposite "boundary xMin: cyclic patch 'l' must pair with the opposite side xMax, not yMin" \
    "x { segments ((1 2 1)); }
$AX
boundary { xMin { name l; type cyclic; neighbourPatch r; } yMin { name r; type cyclic; neighbourPatch l; } }"
bad bad_type "system/blockGridDict:4:" \
    "x { segments ((1 2 1)); }
$AX
boundary { xMin { type wal; } }"
bad syntax "system/blockGridDict:" "x { segments ((1 2 1); }
$AX"

# ---- OpenFOAM's checkMesh (optional) ----
if command -v checkMesh >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    mkdir -p ofc/system
    case_system ofc blockGrid
    cat >ofc/system/blockGridDict <<'EOF'
x { segments ( (1 3 1) ); }
y { segments ( (2 4 2) ); }
z { segments ( (0.5 2 1) ); }
boundary
{
    xMin { name left;  type cyclic; neighbourPatch right; }
    xMax { name right; type cyclic; neighbourPatch left; }
}
EOF
    cp good2d.dict c2d/system/blockGridDict
    for c in c2d c3d ofc; do
        "$BIN/blockGrid" -case $c >/dev/null 2>&1 || true
        checkMesh -case $c >cm_$c 2>&1
        check "checkMesh_$c" grep -q '^Mesh OK\.' cm_$c
    done
    grep -q 'cells:  *600$' cm_c2d && grep -q 'Mesh non-orthogonality Max: 0 average: 0' cm_c2d
    check checkMesh_2d_counts test $? -eq 0
else
    echo "SKIP checkMesh: OpenFOAM's checkMesh is not installed"
fi
exit 0
