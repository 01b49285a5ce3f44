#!/usr/bin/env bash
# test_cutCells.sh: the cutCells tool end to end.
#   - -help lists every keyword of geometryDict and cutCellsDict with its
#     default; -version;
#   - a sphere (analytic, r = 0.3) on a 32^3 grid: the fluid volume the log
#     reports is within 1e-3 of 1 - 4/3 pi r^3 (second-order cutting error
#     at h = r/9.6 is about 6e-4), checkGrid says "Grid OK.", and OpenFOAM's
#     checkMesh (when installed) finds no validity error on the unmerged
#     cut grid (quality flags of slivers are allowed and printed);
#   - the same sphere as an STL written by gmsh (tests/data/stl/sphere.stl.gz,
#     5k triangles): the cut volume differs from the analytic sphere's cut
#     volume by no more than the triangulation's own volume error
#     |V_poly - V_sphere| (computed here from the STL) plus 1e-4;
#   - an STL with a hole is refused with "not watertight" and the count of
#     open edges, as geometryDict:line; allowOpen yes accepts it;
#   - a STEP sphere goes through gmsh (tests/data/cad/sphere.step, r = 1,
#     scaled by 0.3 and moved to the centre) and cuts to the analytic
#     volume within 2e-3;
#   - 2-D: a disc on a 64^2 grid one cell thick, area error below 1e-3;
#   - a duct's wall on a grid plane next to its mouth off the grid planes:
#     each face goes to its own surface's patch (areas exact to 1e-12);
#   - pipes: blockGrid -o - | cutCells -i - -o - writes the same stream as
#     cutCells on the written grid;
#   - the VTK file of a cut grid read by VTK's own reader has the cell
#     count and total volume of the grid (volumes from each cell's faces by
#     the divergence theorem, so a missing or flipped face shows);
#   - malformed geometryDict and cutCellsDict: file:line messages, non-zero
#     exit, no crash, the grid on disk untouched.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

mkcase() { # dir n nz geometry-surfaces
    rm -rf "$1"
    unit_box "$1" "$2" "$3"
    geometry_dict "$1" "$4"
}

# ---- help and version ---------------------------------------------------------
h=$("$BIN/cutCells" -help 2>&1)
miss=""
for k in surfaces type flow shape centre radius point1 point2 infinite radius1 radius2 majorRadius minorRadius \
    points file allowOpen meshSize scale rotate translate snapTolerance; do
    grep -q -- "$k" <<<"$h" || miss="$miss $k"
done
[ -z "$miss" ] && pass cutCells_help || fail cutCells_help "missing keywords:$miss"
"$BIN/cutCells" -version 2>&1 | grep -q '[0-9]\.[0-9]' && pass cutCells_version || fail cutCells_version "no version"

# ---- analytic sphere ----------------------------------------------------------
mkcase sphere 32 32 'ball { shape sphere; centre (0.5 0.5 0.5); radius 0.3; }'
"$BIN/blockGrid" -case sphere >sphere/log.blockGrid 2>&1
if "$BIN/cutCells" -case sphere >sphere/log.cutCells 2>&1; then
    v=$(fluid sphere/log.cutCells)
    ex=$(awk 'BEGIN { printf "%.15g", 1 - 4 / 3 * 3.141592653589793 * 0.027 }')
    r=$(rel "$v" "$ex")
    le "$r" 1e-3 && pass cutCells_sphere_volume "fluid $v, exact $ex, relative error $r" ||
        fail cutCells_sphere_volume "fluid $v, exact $ex, relative error $r > 1e-3"
    grep -q 'relative error' sphere/log.cutCells && pass cutCells_sphere_reports_exact ||
        fail cutCells_sphere_reports_exact "log has no exact volume line"
else
    fail cutCells_sphere_volume "cutCells failed: $(tail -n 3 sphere/log.cutCells)"
fi
"$BIN/checkGrid" -case sphere >sphere/log.checkGrid 2>&1 && grep -q 'Grid OK' sphere/log.checkGrid &&
    pass cutCells_sphere_checkGrid || fail cutCells_sphere_checkGrid "$(tail -n 3 sphere/log.checkGrid)"
if command -v checkMesh >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    case_system sphere cutCells
    checkMesh -case sphere >sphere/log.checkMesh 2>&1
    errs=$(grep -E '^ *\*\*\*' sphere/log.checkMesh | grep -v -e 'skewness' -e 'aspect' -e 'non-orth')
    if grep -q 'cells:' sphere/log.checkMesh && [ -z "$errs" ]; then
        pass cutCells_sphere_checkMesh_valid "$(grep -h 'Max skewness' sphere/log.checkMesh | sed 's/^ *//')"
    else
        fail cutCells_sphere_checkMesh_valid "$errs $(grep FATAL sphere/log.checkMesh)"
    fi
else
    echo "SKIP cutCells_sphere_checkMesh_valid: OpenFOAM's checkMesh is not installed"
fi

# ---- STL sphere by gmsh ----------------------------------------------------------
stl=$TOP/tests/data/stl/sphere.stl.gz
mkcase stl 32 32 "ball { shape stl; file \"$stl\"; }"
"$BIN/blockGrid" -case stl >stl/log.blockGrid 2>&1
if "$BIN/cutCells" -case stl >stl/log.cutCells 2>&1; then
    vs=$(fluid stl/log.cutCells)
    va=$(fluid sphere/log.cutCells)
    # enclosed volume of the triangulation, by the divergence theorem
    vp=$(/usr/bin/python3 - "$stl" <<'EOF'
import gzip, struct, sys
d = gzip.open(sys.argv[1]).read()
n = struct.unpack_from('<I', d, 80)[0]
v = 0.0
for i in range(n):
    t = struct.unpack_from('<12f', d, 84 + 50 * i)
    a, b, c = t[3:6], t[6:9], t[9:12]
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
print("%.15g" % v)
EOF
)
    tol=$(awk -v p="$vp" 'BEGIN { d = p - 4 / 3 * 3.141592653589793 * 0.027; if (d < 0) d = -d; printf "%.6g", d + 1e-4 }')
    diff=$(awk -v a="$vs" -v b="$va" 'BEGIN { d = a - b; if (d < 0) d = -d; printf "%.6g", d }')
    le "$diff" "$tol" && pass cutCells_stl_sphere "STL cut $vs, analytic cut $va, |diff| $diff <= triangulation error + 1e-4 = $tol" ||
        fail cutCells_stl_sphere "STL cut $vs, analytic cut $va, |diff| $diff > $tol"
else
    fail cutCells_stl_sphere "cutCells failed: $(tail -n 3 stl/log.cutCells)"
fi

# ---- open STL refused ----------------------------------------------------------------
mkcase open 8 8 "ball { shape stl; file \"$PWD/open/holed.stl\"; }"
/usr/bin/python3 - "$stl" open/holed.stl <<'EOF'
import gzip, sys
d = bytearray(gzip.open(sys.argv[1]).read())
n = int.from_bytes(d[80:84], 'little')
d[80:84] = (n - 1).to_bytes(4, 'little')
open(sys.argv[2], 'wb').write(bytes(d[:84 + 50 * (n - 1)]))
EOF
"$BIN/blockGrid" -case open >/dev/null 2>&1
if "$BIN/cutCells" -case open >open/log 2>open/err; then
    fail cutCells_open_stl_refused "an STL with a hole was cut"
else
    grep -q 'geometryDict:[0-9]*: .*not watertight: 3 open edge' open/err &&
        pass cutCells_open_stl_refused "$(head -c 160 open/err)" || fail cutCells_open_stl_refused "message: $(cat open/err)"
fi
sed -i 's/file /allowOpen yes; file /' open/system/geometryDict
"$BIN/cutCells" -case open >open/log 2>&1 && pass cutCells_open_stl_allowed || fail cutCells_open_stl_allowed "$(tail -n 2 open/log)"

# ---- STEP through gmsh -------------------------------------------------------------
step=$TOP/tests/data/cad/sphere.step
if [ -f "$step" ]; then
    mkcase step 24 24 "ball { shape cad; file \"$step\"; meshSize 0.05; scale 0.3; translate (0.5 0.5 0.5); }"
    "$BIN/blockGrid" -case step >/dev/null 2>&1
    if "$BIN/cutCells" -case step >step/log.cutCells 2>&1; then
        v=$(fluid step/log.cutCells)
        ex=$(awk 'BEGIN { printf "%.15g", 1 - 4 / 3 * 3.141592653589793 * 0.027 }')
        r=$(rel "$v" "$ex")
        le "$r" 2e-3 && pass cutCells_step_sphere "fluid $v, exact $ex, relative error $r" ||
            fail cutCells_step_sphere "fluid $v, exact $ex, relative error $r > 2e-3"
    else
        fail cutCells_step_sphere "cutCells failed: $(tail -n 3 step/log.cutCells)"
    fi
else
    echo "SKIP cutCells_step_sphere: $step missing"
fi

# ---- 2-D disc --------------------------------------------------------------------------
mkcase disc 64 1 'disc { shape cylinder; point1 (0.5 0.5 0); point2 (0.5 0.5 1); radius 0.2; infinite yes; }'
"$BIN/blockGrid" -case disc >/dev/null 2>&1
if "$BIN/cutCells" -case disc >disc/log.cutCells 2>&1; then
    v=$(fluid disc/log.cutCells)
    ex=$(awk 'BEGIN { printf "%.15g", (1 - 3.141592653589793 * 0.04) * 0.02 }')
    r=$(rel "$v" "$ex")
    le "$r" 1e-3 && pass cutCells_disc_area "fluid $v, exact $ex, relative error $r" ||
        fail cutCells_disc_area "fluid $v, exact $ex, relative error $r > 1e-3"
else
    fail cutCells_disc_area "cutCells failed: $(tail -n 3 disc/log.cutCells)"
fi

# ---- the patch of a face on a grid plane ---------------------------------------------
# A square duct whose walls lie on grid planes (h = 1/8: y, z = 0.25, 0.75)
# and whose mouth, a plane of another surface, does not (x = 0.3).  The
# wall faces between the mouth and the next grid plane x = 0.375 have
# their only cut points on the mouth's edge; they are the duct's, not the
# mouth's: patch areas inlet 0.25 and duct 4 x 0.5 x 0.7 = 1.4 (before
# the fix, inlet had 0.25 + 4 x 0.5 x 0.075 = 0.4).
mkcase duct 8 8 'duct { type wall; flow inside; shape box; min (-1 0.25 0.25); max (2 0.75 0.75); }
inlet { type patch; flow outside; shape halfSpace; point (0.3 0 0); normal (1 0 0); }'
"$BIN/blockGrid" -case duct >duct/log.blockGrid 2>&1
if "$BIN/cutCells" -case duct >duct/log.cutCells 2>&1; then
    areas=$(/usr/bin/python3 - duct/constant/polyMesh <<'EOF'
import re, sys
def body(f):
    t = open(sys.argv[1] + '/' + f).read()
    t = re.sub(r'/\*.*?\*/', '', t, flags=re.S)
    return t[t.index('}', t.index('FoamFile')) + 1:]
pb = body('points')
pts = [[float(v) for v in m.split()] for m in re.findall(r'\(([^()]*)\)', pb[pb.index('(') + 1:])]
faces = [[int(v) for v in m.split()] for m in re.findall(r'\d+\(([^()]*)\)', body('faces'))]
area = {}
for name, n, start in re.findall(r'(\w+)\s*\{[^}]*?nFaces\s+(\d+);\s*startFace\s+(\d+);', body('boundary')):
    a = 0.0
    for f in faces[int(start):int(start) + int(n)]:
        S, x = [0.0, 0.0, 0.0], [pts[i] for i in f]
        for i in range(len(x)):
            p, q = x[i], x[(i + 1) % len(x)]
            S[0] += 0.5 * (p[1] * q[2] - p[2] * q[1])
            S[1] += 0.5 * (p[2] * q[0] - p[0] * q[2])
            S[2] += 0.5 * (p[0] * q[1] - p[1] * q[0])
        a += sum(v * v for v in S) ** 0.5
    area[name] = a
print('%.12g %.12g' % (area.get('inlet', -1), area.get('duct', -1)))
EOF
)
    read -r ai aw <<<"$areas"
    if le "$(absdiff "$ai" 0.25)" 1e-12 && le "$(absdiff "$aw" 1.4)" 1e-12; then
        pass cutCells_grid_plane_face_patch "inlet area $ai (exact 0.25), duct $aw (exact 1.4)"
    else
        fail cutCells_grid_plane_face_patch "inlet area $ai (exact 0.25), duct $aw (exact 1.4)"
    fi
else
    fail cutCells_grid_plane_face_patch "cutCells failed: $(tail -n 3 duct/log.cutCells)"
fi

# ---- pipes ---------------------------------------------------------------------------------
"$BIN/blockGrid" -case sphere -o - 2>/dev/null | "$BIN/cutCells" -case sphere -i - -o - >pipe.stream 2>pipe.err
"$BIN/blockGrid" -case sphere -o sphere/block >/dev/null 2>&1
"$BIN/cutCells" -case sphere -i sphere/block -o - >file.stream 2>/dev/null
if [ -s pipe.stream ] && cmp -s pipe.stream file.stream; then
    pass cutCells_pipe "$(wc -c <pipe.stream) bytes identical"
else
    fail cutCells_pipe "streams differ ($(wc -c <pipe.stream) / $(wc -c <file.stream) bytes): $(tail -n 2 pipe.err)"
fi

# ---- VTK reader -----------------------------------------------------------------------------
if "$BIN/writeVTK" -case sphere >sphere/log.writeVTK 2>&1; then
    f=$(ls sphere/VTK/*.vtk 2>/dev/null | head -1)
    out=$(/usr/bin/python3 "$TOP/tests/vtk_cells_volume.py" "$f" "$(fluid sphere/log.cutCells)" 2>&1)
    read -r n vol d <<<"$out"
    nc=$(sed -n 's/^ *nCells: *//p' sphere/log.cutCells | head -1)
    if [ "$n" = "$nc" ] && le "$d" 1e-9; then
        pass cutCells_vtk_reader "$n cells, volume $vol"
    else
        fail cutCells_vtk_reader "VTK: $out; grid: $nc cells"
    fi
else
    fail cutCells_vtk_reader "writeVTK failed: $(tail -n 3 sphere/log.writeVTK)"
fi

# ---- bad dictionaries -----------------------------------------------------------------------
bad() { # name text expected-substring
    mkcase bad 4 4 "$2"
    "$BIN/blockGrid" -case bad >/dev/null 2>&1
    "$BIN/cutCells" -case bad >bad/out 2>bad/err
    rc=$?
    if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q -- "$3" bad/err; then
        pass "cutCells_error_$1" "$(head -c 150 bad/err)"
    else
        fail "cutCells_error_$1" "status $rc, stderr: $(cat bad/err)"
    fi
}
bad unknown_shape 'b { shape sphre; centre (0 0 0); radius 1; }' "geometryDict:[0-9]*: unknown shape 'sphre'"
bad typo 'b { shape sphere; centre (0 0 0); raduis 1; }' "did you mean 'radius'"
bad negative_radius 'b { shape sphere; centre (0 0 0); radius -1; }' 'radius must be positive'
bad missing_stl 'b { shape stl; file "constant/triSurface/none.stl"; }' 'none.stl'
bad patch_clash 'walls { shape sphere; centre (0.5 0.5 0.5); radius 0.2; }' "walls"
bad unbalanced 'b { shape sphere; centre (0.5 0.5 0.5); radius 0.2; ' 'geometryDict'
bad nan_radius 'b { shape sphere; centre (0.5 0.5 0.5); radius nan; }' 'geometryDict'

# ---- bad cutCellsDict --------------------------------------------------------------------
mkcase opt 4 4 'b { shape sphere; centre (0.5 0.5 0.5); radius 0.2; }'
"$BIN/blockGrid" -case opt >/dev/null 2>&1
cp -r opt/constant/polyMesh opt/grid.orig
{ header cutCellsDict; echo; echo 'snapTolerance 0.5;'; } >opt/system/cutCellsDict
"$BIN/cutCells" -case opt >opt/out 2>opt/err; rc=$?
if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q 'cutCellsDict:3: snapTolerance must be in \[0, 0.25)' opt/err &&
    diff -r -q opt/grid.orig opt/constant/polyMesh >/dev/null; then
    pass cutCells_error_snapTolerance "$(head -c 120 opt/err); grid untouched"
else
    fail cutCells_error_snapTolerance "status $rc, stderr: $(cat opt/err)"
fi
{ header cutCellsDict; echo 'snapTolerence 1e-6;'; } >opt/system/cutCellsDict
"$BIN/cutCells" -case opt >opt/out 2>opt/err; rc=$?
[ $rc -ne 0 ] && grep -q "did you mean 'snapTolerance'" opt/err && pass cutCells_error_cutCellsDict_typo ||
    fail cutCells_error_cutCellsDict_typo "status $rc, stderr: $(cat opt/err)"
