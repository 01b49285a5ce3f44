#!/usr/bin/env bash
# test_voronoiGrid.sh: the voronoiGrid tool end to end.
#   - -help lists every keyword of voronoiGridDict and geometryDict with
#     its default; -version;
#   - no geometryDict: the grid is the block grid (same cell, face and
#     point counts, same total volume to 1e-12 relative, same patches);
#   - a sphere (r = 0.3) on a 24^3 grid: fluid volume within 1.5e-3 of
#     1 - 4/3 pi r^3 (measured 5.3e-4: second-order error at h = r/7.2),
#     smallest cell volume >= pi a^3/6 as printed, checkGrid "Grid OK."
#     and its Voronoi line (faces within 1e-6 deg of the seed segments,
#     points within 1e-12 of the bisectors, every seed in its cell),
#     checkMesh (when installed) "Mesh OK.", cellSeed with one seed per
#     cell and boundaryNormal with one unit normal per boundary face;
#   - the sphere as a STEP model through gmsh (exact CAD normals): no STL
#     warning, volume within 2e-3;
#   - the sphere as an STL surface: accepted with a warning on stderr that
#     names the surface, volume within 5e-3;
#   - 2-D disc with 2 boundary layers (voronoiGridDict): area within 1e-3
#     of the exact (1 - pi 0.2^2) x thickness;
#   - pipes: blockGrid -o - | voronoiGrid -i - -o - gives the same stream
#     as voronoiGrid on the written grid; -binary -gzip output reads back;
#   - VTK's own reader: cell count and total volume of the grid (volumes
#     from each cell's faces, so a missing or flipped face shows);
#   - malformed voronoiGridDict and geometryDict: file:line messages,
#     non-zero exit, the grid on disk untouched.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

mkcase() { # dir n nz geometry-surfaces (empty: no geometryDict)
    rm -rf "$1"
    unit_box "$1" "$2" "$3"
    [ -n "$4" ] && geometry_dict "$1" "$4"
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1
}

vmin() { sed -n 's/^  smallest cell volume: *\([0-9.eE+-]*\) (bound from a: \([0-9.eE+-]*\)).*/\1 \2/p' "$1"; }
ncells() { sed -n 's/^ *nCells: *//p' "$1" | head -1; }
sphere_exact=$(awk 'BEGIN { printf "%.15g", 1 - 4 / 3 * 3.141592653589793 * 0.027 }')

# volume check: name log exact tolerance
volume() {
    local v r
    v=$(fluid "$2")
    r=$(rel "${v:-0}" "$3")
    le "$r" "$4" && pass "$1" "fluid $v, exact $3, relative error $r" ||
        fail "$1" "fluid $v, exact $3, relative error $r > $4"
}

# ---- help and version ---------------------------------------------------------
h=$("$BIN/voronoiGrid" -help 2>&1)
miss=""
for k in layers spacing minSpacing surfaces type flow shape centre radius file scale rotate translate; do
    grep -q -- "$k" <<<"$h" || miss="$miss $k"
done
[ -z "$miss" ] && pass voronoiGrid_help || fail voronoiGrid_help "missing keywords:$miss"
"$BIN/voronoiGrid" -version 2>&1 | grep -q '[0-9]\.[0-9]' && pass voronoiGrid_version || fail voronoiGrid_version "no version"

# ---- no geometry: the block grid ---------------------------------------------------
mkcase plain 7 5 ''
"$BIN/checkGrid" -case plain >plain/log.checkGrid.block 2>&1
if "$BIN/voronoiGrid" -case plain >plain/log.voronoiGrid 2>&1; then
    "$BIN/checkGrid" -case plain >plain/log.checkGrid 2>&1
    a=$(grep -E 'nPoints|nCells|nFaces|nInternalFaces|Total volume|patch [0-9]' plain/log.checkGrid.block)
    b=$(grep -E 'nPoints|nCells|nFaces|nInternalFaces|Total volume|patch [0-9]' plain/log.checkGrid)
    [ -n "$a" ] && [ "$a" = "$b" ] && pass voronoiGrid_no_geometry_is_block_grid "$(echo $b | head -c 160)" ||
        fail voronoiGrid_no_geometry_is_block_grid "block: $a / voronoi: $b"
else
    fail voronoiGrid_no_geometry_is_block_grid "$(tail -n 3 plain/log.voronoiGrid)"
fi

# ---- analytic sphere ------------------------------------------------------------
mkcase sphere 24 24 'ball { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }'
if "$BIN/voronoiGrid" -case sphere >sphere/log.voronoiGrid 2>sphere/err; then
    volume voronoiGrid_sphere_volume sphere/log.voronoiGrid "$sphere_exact" 1.5e-3
    read -r m bnd <<<"$(vmin sphere/log.voronoiGrid)"
    le "$bnd" "$m" && pass voronoiGrid_sphere_min_volume "smallest $m >= pi a^3/6 = $bnd" ||
        fail voronoiGrid_sphere_min_volume "smallest $m < $bnd"
    nc=$(ncells sphere/log.voronoiGrid)
    out=$(/usr/bin/python3 - sphere/constant/polyMesh "$nc" <<'EOF' 2>&1
import math, re, sys
d, nc = sys.argv[1], int(sys.argv[2])
def vecs(name):
    t = open(d + "/" + name).read()
    t = t[t.index("\n(", t.index("}")) - 12:]
    n = int(re.search(r"(\d+)\s*\(", t).group(1))
    v = re.findall(r"\(([-0-9.eE+]+) ([-0-9.eE+]+) ([-0-9.eE+]+)\)", t)
    return n, [tuple(map(float, x)) for x in v]
n, s = vecs("cellSeed")
bn, b = vecs("boundaryNormal")
bad = sum(1 for x in b if abs(math.sqrt(sum(c * c for c in x)) - 1) > 1e-12)
print(n, len(s), bn, len(b), bad)
EOF
)
    read -r n1 n2 bn1 bn2 bad <<<"$out"
    nb=$(awk '/nFaces/ { f = $2 } /nInternalFaces/ { i = $2 } END { print f - i }' sphere/log.voronoiGrid)
    [ "$n1" = "$nc" ] && [ "$n2" = "$nc" ] && [ "$bn1" = "$nb" ] && [ "$bn2" = "$nb" ] && [ "$bad" = 0 ] &&
        pass voronoiGrid_sphere_extras "cellSeed $n1 seeds, boundaryNormal $bn1 unit normals" ||
        fail voronoiGrid_sphere_extras "cells $nc, boundary faces $nb; read: $out"
    grep -q 'warning' sphere/err && fail voronoiGrid_sphere_no_warning "$(cat sphere/err)" || pass voronoiGrid_sphere_no_warning
else
    fail voronoiGrid_sphere_volume "voronoiGrid failed: $(tail -n 3 sphere/err)"
fi
"$BIN/checkGrid" -case sphere >sphere/log.checkGrid 2>&1 && grep -q 'Grid OK' sphere/log.checkGrid &&
    pass voronoiGrid_sphere_checkGrid || fail voronoiGrid_sphere_checkGrid "$(tail -n 3 sphere/log.checkGrid)"
# checkGrid's Voronoi line: faces normal to and bisecting the seed segments
vl=$(grep 'Voronoi seeds' sphere/log.checkGrid)
va=$(sed -n 's/.*seed segments Max: \([0-9.eE+-]*\) degrees.*/\1/p' <<<"$vl")
vo=$(sed -n 's/.*bisector Max: \([0-9.eE+-]*\),.*/\1/p' <<<"$vl")
if [ -n "$va" ] && le "$va" 1e-6 && le "$vo" 1e-12 && grep -q 'outside their cells: 0$' <<<"$vl"; then
    pass voronoiGrid_checkGrid_seeds "$(sed 's/^ *//' <<<"$vl")"
else
    fail voronoiGrid_checkGrid_seeds "line: $vl"
fi
if command -v checkMesh >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    header controlDict >sphere/system/controlDict
    echo 'application voronoiGrid; startTime 0; endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;' >>sphere/system/controlDict
    printf '%s\nddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {} interpolationSchemes {} snGradSchemes {}\n' \
        "$(header fvSchemes)" >sphere/system/fvSchemes
    header fvSolution >sphere/system/fvSolution
    checkMesh -case sphere >sphere/log.checkMesh 2>&1
    nom=$(sed -n 's/^ *cells: *//p' sphere/log.checkMesh)
    if grep -q '^Mesh OK' sphere/log.checkMesh && [ "$nom" = "$(ncells sphere/log.voronoiGrid)" ]; then
        pass voronoiGrid_sphere_checkMesh "Mesh OK., $nom cells; $(grep -h 'non-orthogonality Max' sphere/log.checkMesh | sed 's/^ *//')"
    else
        fail voronoiGrid_sphere_checkMesh "$(grep -E '^ *\*\*\*|FATAL' sphere/log.checkMesh | head -5)"
    fi
else
    echo "SKIP voronoiGrid_sphere_checkMesh: OpenFOAM's checkMesh is not installed"
fi

# ---- STEP through gmsh: exact CAD normals --------------------------------------------
step=$TOP/tests/data/cad/sphere.step
if [ -f "$step" ]; then
    mkcase step 24 24 "ball { type wall; flow outside; shape cad; file \"$step\"; meshSize 0.05; scale 0.3; translate (0.5 0.5 0.5); }"
    if "$BIN/voronoiGrid" -case step >step/log.voronoiGrid 2>step/err; then
        volume voronoiGrid_step_sphere step/log.voronoiGrid "$sphere_exact" 2e-3
        grep -q 'warning' step/err && fail voronoiGrid_step_no_warning "$(cat step/err)" || pass voronoiGrid_step_no_warning
    else
        fail voronoiGrid_step_sphere "voronoiGrid failed: $(tail -n 3 step/err)"
    fi
else
    echo "SKIP voronoiGrid_step_sphere: $step missing"
fi

# ---- STL: accepted with a warning -------------------------------------------------------
stl=$TOP/tests/data/stl/sphere.stl.gz
mkcase stl 24 24 "ball { type wall; flow outside; shape stl; file \"$stl\"; }"
if "$BIN/voronoiGrid" -case stl >stl/log.voronoiGrid 2>stl/err; then
    grep -q "warning: surface 'ball' is an STL surface" stl/err &&
        pass voronoiGrid_stl_warning "$(head -c 140 stl/err)" || fail voronoiGrid_stl_warning "stderr: $(cat stl/err)"
    volume voronoiGrid_stl_sphere stl/log.voronoiGrid "$sphere_exact" 5e-3
else
    fail voronoiGrid_stl_warning "voronoiGrid failed: $(tail -n 3 stl/err)"
fi

# ---- 2-D disc with boundary layers --------------------------------------------------------
mkcase disc 64 1 'disc { type wall; flow outside; shape cylinder; point1 (0.5 0.5 0); point2 (0.5 0.5 1); radius 0.2; infinite yes; }'
{ header voronoiGridDict; echo 'layers 2;'; } >disc/system/voronoiGridDict
if "$BIN/voronoiGrid" -case disc >disc/log.voronoiGrid 2>&1; then
    volume voronoiGrid_disc_layers disc/log.voronoiGrid "$(awk 'BEGIN { printf "%.15g", (1 - 3.141592653589793 * 0.04) * 0.02 }')" 1e-3
    grep -q '2 boundary layer' disc/log.voronoiGrid && pass voronoiGrid_disc_layers_read ||
        fail voronoiGrid_disc_layers_read "log does not show 2 layers"
else
    fail voronoiGrid_disc_layers "voronoiGrid failed: $(tail -n 3 disc/log.voronoiGrid)"
fi

# ---- pipes and formats -----------------------------------------------------------------------
mkcase pipe 12 12 'ball { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }'
"$BIN/blockGrid" -case pipe -o - 2>/dev/null | "$BIN/voronoiGrid" -case pipe -i - -o - >pipe.stream 2>pipe.err
"$BIN/voronoiGrid" -case pipe -o - >file.stream 2>/dev/null
if [ -s pipe.stream ] && cmp -s pipe.stream file.stream; then
    pass voronoiGrid_pipe "$(wc -c <pipe.stream) bytes identical"
else
    fail voronoiGrid_pipe "streams differ ($(wc -c <pipe.stream) / $(wc -c <file.stream) bytes): $(tail -n 2 pipe.err)"
fi
if "$BIN/voronoiGrid" -case pipe -binary -gzip >pipe/log.voronoiGrid 2>&1 && [ -f pipe/constant/polyMesh/cellSeed.gz ] &&
    "$BIN/checkGrid" -case pipe >pipe/log.checkGrid 2>&1 && grep -q 'Grid OK' pipe/log.checkGrid &&
    [ "$(sed -n 's/^ *cells: *//p' pipe/log.checkGrid)" = "$(ncells pipe/log.voronoiGrid)" ]; then
    pass voronoiGrid_binary_gzip "$(ncells pipe/log.voronoiGrid) cells read back"
else
    fail voronoiGrid_binary_gzip "$(tail -n 3 pipe/log.voronoiGrid pipe/log.checkGrid 2>&1)"
fi

# ---- VTK reader -----------------------------------------------------------------------------
if "$BIN/writeVTK" -case sphere >sphere/log.writeVTK 2>&1; then
    f=$(ls sphere/VTK/*.vtk 2>/dev/null | head -1)
    out=$(/usr/bin/python3 "$TOP/tests/vtk_cells_volume.py" "$f" "$(fluid sphere/log.voronoiGrid)" 2>&1)
    read -r n vol d <<<"$out"
    nc=$(ncells sphere/log.voronoiGrid)
    if [ "$n" = "$nc" ] && le "$d" 1e-9; then
        pass voronoiGrid_vtk_reader "$n cells, volume $vol"
    else
        fail voronoiGrid_vtk_reader "VTK: $out; grid: $nc cells"
    fi
else
    fail voronoiGrid_vtk_reader "writeVTK failed: $(tail -n 3 sphere/log.writeVTK)"
fi

# ---- bad dictionaries ---------------------------------------------------------------------------
mkcase opt 4 4 'b { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.2; }'
cp -r opt/constant/polyMesh opt/grid.orig
badopt() { # name dictionary-body expected-substring
    { header voronoiGridDict; echo; echo "$2"; } >opt/system/voronoiGridDict
    "$BIN/voronoiGrid" -case opt >opt/out 2>opt/err
    rc=$?
    if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q -- "$3" opt/err && diff -r -q opt/grid.orig opt/constant/polyMesh >/dev/null; then
        pass "voronoiGrid_error_$1" "$(head -c 120 opt/err); grid untouched"
    else
        fail "voronoiGrid_error_$1" "status $rc, stderr: $(cat opt/err)"
    fi
}
badopt layers 'layers -1;' 'voronoiGridDict:3: layers must be in 0..1000'
badopt minSpacing 'spacing 1; minSpacing 2;' 'voronoiGridDict:3: minSpacing must be in \[0, spacing'
badopt spacing 'spacing 0;' 'voronoiGridDict:3: spacing must be in (0, 4\]'
badopt typo 'layer 2;' "did you mean 'layers'"
badopt word 'layers two;' 'voronoiGridDict:3'
rm -f opt/system/voronoiGridDict
{ header geometryDict; echo 'surfaces { b { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); raduis 0.2; } }'; } >opt/system/geometryDict
"$BIN/voronoiGrid" -case opt >opt/out 2>opt/err; rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "geometryDict:[0-9]*:.*did you mean 'radius'" opt/err &&
    diff -r -q opt/grid.orig opt/constant/polyMesh >/dev/null && pass voronoiGrid_error_geometry "$(head -c 120 opt/err)" ||
    fail voronoiGrid_error_geometry "status $rc, stderr: $(cat opt/err)"
{ header geometryDict; echo 'surfaces { walls { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.2; } }'; } >opt/system/geometryDict
"$BIN/voronoiGrid" -case opt >opt/out 2>opt/err; rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "has the name of the grid's patch" opt/err &&
    pass voronoiGrid_error_patch_clash "$(head -c 120 opt/err)" || fail voronoiGrid_error_patch_clash "status $rc, stderr: $(cat opt/err)"
