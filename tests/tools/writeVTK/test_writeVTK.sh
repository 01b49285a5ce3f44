#!/usr/bin/env bash
# test_writeVTK.sh: writeVTK's command line, time selection, output layout
# and errors, on cases written by test_vtk_reader.py's case writer (a
# graded 3x2x2 box with one merged cell; times 0, 0.1 (index 10), 0.25
# (index 25)).  VTK's reader checks of the file contents are in
# test_vtk_reader.py.  If OpenFOAM's foamToVTK is installed, its -legacy
# output is compared with ours (file layout and cell count); SKIP otherwise.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
HERE=$TOP/tests/tools/writeVTK
TOOL=$BIN/writeVTK
PY=/usr/bin/python3
export PYTHONDONTWRITEBYTECODE=1   # the case writer is imported from the source tree

check() { # name condition-message; runs the remaining args as the test
    local name=$1 why=$2; shift 2
    if "$@"; then pass "$name"; else fail "$name" "$why"; fi
}

if [ ! -x "$TOOL" ]; then
    fail writeVTK_built "$TOOL is missing"
    exit 1
fi

mkcase() { # dir [2d]
    "$PY" - "$1" "${2:-3d}" <<EOF
import sys
sys.path.insert(0, "$HERE")
import test_vtk_reader as t
two_d = sys.argv[2] == "2d"
xs, ys = t.graded(3, 0.0, 1.0, 1.2), t.graded(2, 0.0, 0.5, 1.0)
zs = [0.0, 0.1] if two_d else t.graded(2, 0.0, 0.4, 0.5)
t.write_case(sys.argv[1], t.Box(xs, ys, zs, two_d=two_d, merge=[] if two_d else [(0, 0, 0)]))
EOF
}

vtk_files() { # case: the .vtk files under VTK, relative, sorted
    (cd "$1/VTK" && find . -name '*.vtk' | sed 's|^\./||' | sort | tr '\n' ' ')
}

# ---- -help ----
out=$("$TOOL" -help 2>&1); rc=$?
missing=""
for o in -case -time -latestTime -noZero -ascii -pointData -noBoundary -fields -overwrite -help -version; do
    grep -q -- "^  $o" <<<"$out" || missing="$missing $o"
done
check help_lists_options "rc $rc, missing:$missing" test "$rc" -eq 0 -a -z "$missing"

out=$("$TOOL" -bogus 2>&1); rc=$?
check unknown_option "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep -- "unknown option '-bogus'" <<<"$out")"

# ---- -latestTime writes the last time only ----
mkcase c3
out=$("$TOOL" -case c3 -latestTime 2>&1); rc=$?
files=$(vtk_files c3)
want="c3_25.vtk left/left_25.vtk right/right_25.vtk frontAndBack/frontAndBack_25.vtk walls/walls_25.vtk "
want=$(tr ' ' '\n' <<<"$want" | sed '/^$/d' | sort | tr '\n' ' ')
check latestTime_files "rc $rc, files: $files" test "$rc" -eq 0 -a "$files" = "$want"
check latestTime_log "log: $out" test "$(grep -c '^Time = ' <<<"$out")" -eq 1 \
    -a -n "$(grep -x 'Time = 0.25' <<<"$out")" -a -n "$(grep -x '    Internal  : VTK/c3_25.vtk' <<<"$out")" \
    -a -n "$(grep -x '    Boundary  : VTK/left/left_25.vtk' <<<"$out")" -a -n "$(grep '^ExecutionTime = ' <<<"$out")" \
    -a "$(tail -n 1 <<<"$out")" = "End"
series=$(tr -d ' \n' < c3/VTK/c3.vtk.series)
check latestTime_series "$series" test "$series" = '{"file-series-version":"1.0","files":[{"name":"c3_25.vtk","time":0.25}]}'

# a full run afterwards: the series lists every time
"$TOOL" -case c3 >/dev/null 2>&1; rc=$?
series=$(tr -d ' \n' < c3/VTK/c3.vtk.series)
check full_series "rc $rc: $series" test "$rc" -eq 0 -a "$series" = \
    '{"file-series-version":"1.0","files":[{"name":"c3_0.vtk","time":0},{"name":"c3_10.vtk","time":0.1},{"name":"c3_25.vtk","time":0.25}]}'
series=$(tr -d ' \n' < c3/VTK/walls/walls.vtk.series)
check patch_series "$series" test "$series" = \
    '{"file-series-version":"1.0","files":[{"name":"walls_0.vtk","time":0},{"name":"walls_10.vtk","time":0.1},{"name":"walls_25.vtk","time":0.25}]}'

# ---- -time, -noZero, -noBoundary, -fields, -ascii, -overwrite ----
mkcase t1
"$TOOL" -case t1 -time 0.1 -noBoundary >/dev/null 2>&1; rc=$?
files=$(vtk_files t1)
check time_and_noBoundary "rc $rc, files: $files" test "$rc" -eq 0 -a "$files" = "t1_10.vtk "
touch t1/VTK/stale.vtk
"$TOOL" -case t1 -noZero -noBoundary -overwrite -ascii -fields '(p)' >/dev/null 2>&1; rc=$?
files=$(vtk_files t1)
check noZero_overwrite "rc $rc, files: $files" test "$rc" -eq 0 -a "$files" = "t1_10.vtk t1_25.vtk "
# 3*2*2 = 12 cells, two of them merged: 11; only p in the cell data
data=$(sed -n '/^CELL_DATA/,$p' t1/VTK/t1_25.vtk | grep -E '^[A-Za-z]' | tr '\n' '|')
check fields_ascii "cell data: $data" test "$data" = "CELL_DATA 11|FIELD FieldData 1|p 1 11 double|"
check ascii_header "$(sed -n 3p t1/VTK/t1_25.vtk)" test "$(sed -n 3p t1/VTK/t1_25.vtk)" = ASCII

# gzipped field files (writeCompression on) are read like the others
gzip t1/0.25/U
"$TOOL" -case t1 -latestTime -noBoundary -ascii >/dev/null 2>&1; rc=$?
data=$(grep -a -E '^(p|U) ' t1/VTK/t1_25.vtk | tr '\n' '|')
check gzipped_field "rc $rc: $data" test "$rc" -eq 0 -a "$data" = "U 3 11 double|p 1 11 double|"

# a case without time directories: the mesh alone at time 0
mkcase nt
rm -rf nt/0 nt/0.1 nt/0.25
"$TOOL" -case nt >/dev/null 2>&1; rc=$?
files=$(vtk_files nt)
check no_time_dirs "rc $rc, files: $files" test "$rc" -eq 0 -a -n "$(grep -w nt_0.vtk <<<"$files")" \
    -a -z "$(grep -a '^CELL_DATA' nt/VTK/nt_0.vtk)"

# 2-D: polygons, no empty patch
mkcase c2 2d
"$TOOL" -case c2 -latestTime >/dev/null 2>&1; rc=$?
files=$(vtk_files c2)
check two_d_layout "rc $rc, files: $files" test "$rc" -eq 0 -a "$files" = \
    "c2_25.vtk left/left_25.vtk right/right_25.vtk walls/walls_25.vtk " -a -n "$(grep -a -x 'CELLS 6 30' c2/VTK/c2_25.vtk)"

# ---- errors ----
out=$("$TOOL" -case no/such/case 2>&1); rc=$?
check bad_case_dir "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep "case directory 'no/such/case' does not exist" <<<"$out")"

mkdir -p empty/system
out=$("$TOOL" -case empty 2>&1); rc=$?
check no_mesh "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep 'empty/constant/polyMesh' <<<"$out")" -a ! -d empty/VTK

mkcase bad
printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    object q;\n}\nvalue 1;\n' > bad/0/q
out=$("$TOOL" -case bad -time 0 -fields '(q p)' 2>&1); rc=$?
check field_without_class "rc $rc: $out" test "$rc" -ne 0 \
    -a -n "$(grep "bad/0/q: field 'q' is not an OpenFOAM file with a class, not a volScalarField or volVectorField" <<<"$out")"
sed -i 's/object q;/class surfaceScalarField;\n    object q;/' bad/0/q
out=$("$TOOL" -case bad -time 0 -fields '(q)' 2>&1); rc=$?
check field_wrong_class "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep "field 'q' is of class 'surfaceScalarField'" <<<"$out")"
# without -fields a surface field is skipped, as foamToVTK does
out=$("$TOOL" -case bad -time 0 -ascii 2>&1); rc=$?
data=$(grep -a -E '^(p|U|q) ' bad/VTK/bad_0.vtk | tr '\n' '|')
check other_classes_skipped "rc $rc: $data" test "$rc" -eq 0 -a "$data" = "U 3 11 double|p 1 11 double|"
# a -time that selects nothing is an error, and -overwrite then keeps VTK/
out=$("$TOOL" -case bad -time 7 -overwrite 2>&1); rc=$?
check time_selects_nothing "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep 'no time selected among 3 time directories (0 to 0.25)' <<<"$out")" \
    -a -f bad/VTK/bad_0.vtk
# a field that names no file: warning, not an error
out=$("$TOOL" -case bad -time 0 -fields '(nosuch p)' 2>&1); rc=$?
check unknown_field_warns "rc $rc: $out" test "$rc" -eq 0 -a -n "$(grep "field 'nosuch' was not found" <<<"$out")"

# a broken field file: file:line message, the earlier output of that time kept intact
"$TOOL" -case bad -time 0.1 >/dev/null 2>&1
cp bad/VTK/bad_10.vtk before.vtk
sed -i '0,/^11$/s//12/' bad/0.1/p
out=$("$TOOL" -case bad -time 0.1 2>&1); rc=$?
check broken_field "rc $rc: $out" test "$rc" -ne 0 -a -n "$(grep -E 'bad/0.1/p:[0-9]+: ' <<<"$out")"
check broken_field_keeps_output "bad_10.vtk changed" cmp -s before.vtk bad/VTK/bad_10.vtk

# ---- broken input points: the message names the input, not the output (issue 9) ----
mkcase bp 2d
pts=bp/constant/polyMesh/points
cp $pts points.orig
# point 12, (0 0 0.1), moved so that cell 0's front face turns to -z: two lower faces
ln=$(grep -n '^(0 0 0.1' $pts | head -n 1 | cut -d: -f1)
sed -i "${ln}s/.*/(0.5 0.4 0.1)/" $pts
out=$("$TOOL" -case bp 2>&1); rc=$?
check broken_points_name_input "rc $rc: $out" test "$rc" -ne 0 \
    -a -n "$(grep -F 'bp/constant/polyMesh: 2-D mesh: cell 0 has two faces (' <<<"$out")" -a -z "$(grep -F 'VTK/' <<<"$out")"
# a coordinate written nan: the points file, its line and the point
cp points.orig $pts
ln=$(grep -n '^(0 0 0)$' $pts | head -n 1 | cut -d: -f1)
sed -i "${ln}s/.*/(nan 0 0)/" $pts
out=$("$TOOL" -case bp 2>&1); rc=$?
check nan_point_names_line "rc $rc: $out" test "$rc" -ne 0 \
    -a -n "$(grep -F "bp/constant/polyMesh/points:$ln: point 0: coordinate 'nan' is not a finite number" <<<"$out")"
# NaN in a field's internalField: the field file, the line of the value and the cell
cp points.orig $pts
ln=$(( $(grep -n '^internalField' bp/0.1/U | cut -d: -f1) + 3 ))
sed -i "${ln}s/.*/(0.1 NaN 0)/" bp/0.1/U
out=$("$TOOL" -case bp -time 0.1 2>&1); rc=$?
check nan_field_names_line "rc $rc: $out" test "$rc" -ne 0 \
    -a -n "$(grep -F "bp/0.1/U:$ln: internalField has a non-finite value (nan or inf) at index 0: cell 0 is 'NaN', not a finite number" <<<"$out")"

# ---- foamToVTK -legacy: same layout and cell count ----
if command -v foamToVTK >/dev/null 2>&1; then
    mkcase of
    cp -r of ours
    ( export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}; cd of && foamToVTK -legacy >log.foamToVTK 2>&1 ); frc=$?
    "$TOOL" -case ours >/dev/null 2>&1; rc=$?
    theirs=$(vtk_files of | sed 's/\bof_/X_/g'); mine=$(vtk_files ours | sed 's/\bours_/X_/g')
    check foamToVTK_layout "foamToVTK rc $frc ($theirs), ours rc $rc ($mine)" test "$frc" -eq 0 -a "$rc" -eq 0 -a "$theirs" = "$mine"
    tc=$(grep -a '^CELLS' of/VTK/of_25.vtk | awk '{print $2}'); mc=$(grep -a '^CELLS' ours/VTK/ours_25.vtk | awk '{print $2}')
    check foamToVTK_cells "foamToVTK $tc cells, ours $mc" test -n "$tc" -a "$tc" = "$mc"
    tp=$(grep -a '^POINTS' of/VTK/of_25.vtk | awk '{print $2}'); mp=$(grep -a '^POINTS' ours/VTK/ours_25.vtk | awk '{print $2}')
    check foamToVTK_points "foamToVTK $tp points, ours $mp" test -n "$tp" -a "$tp" = "$mp"
else
    echo "SKIP foamToVTK_layout: foamToVTK (OpenFOAM) not installed"
fi
