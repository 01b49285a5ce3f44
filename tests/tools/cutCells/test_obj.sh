#!/usr/bin/env bash
# test_obj.sh: cutCells on Wavefront OBJ surfaces, end to end.
#   - the unit cube of quadrangles (tests/data/obj/cube.obj), scaled to
#     0.4, rotated 30 degrees about (1 2 3) and centred, on a 24^3 grid
#     (shape obj): the fluid volume equals the cut of the same rotated
#     analytic box to 1e-12, and the exact 1 - 0.4^3 within 2e-3 (the
#     cutting error at the cube's edges, second order: 2.8e-3 at 16^3,
#     7.4e-4 at 32^3);
#   - the same cube gzipped (cube.obj.gz, named without .gz in
#     geometryDict, under shape surface), and written as an ascii STL
#     (shape stl): the same fluid volume to 1e-12;
#   - the L-shaped prism of non-convex hexagons (lprism.obj, negative
#     indices), scaled 0.2 and rotated: the fluid volume equals the cut of
#     the CSG union of its two boxes to 1e-12 and the cut points agree to
#     1e-12; exact 1 - 3 * 0.2^3 within 2e-3;
#   - OpenFOAM's own OBJ reader (surfaceConvert, when installed) turns
#     gap_detection's mech_test.obj into an STL; cutCells on the OBJ and on
#     that STL give the same fluid volume to 1e-12 (integer coordinates,
#     so the STL is exact);
#   - a damaged OBJ (a face naming vertex 9 of 8) stops cutCells with
#     geometryDict:line and the OBJ's file:line; an open OBJ surface is
#     refused as not watertight.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

mkcase() { # dir n geometry-surfaces
    rm -rf "$1"
    mkdir -p "$1/system" "$1/constant/triSurface"
    { header blockGridDict
      for a in x y z; do echo "$a { segments ((1 $2 1)); }"; done
      echo "boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; }"
      echo "           zMin { name walls; } zMax { name walls; } }"
    } >"$1/system/blockGridDict"
    { header geometryDict; printf 'surfaces\n{\n%s\n}\n' "$3"; } >"$1/system/geometryDict"
}

# runs blockGrid and cutCells on a case; prints the fluid volume or nothing
cut() {
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1 &&
        "$BIN/cutCells" -case "$1" >"$1/log.cutCells" 2>&1 &&
        sed -n 's/^  fluid volume: *\([0-9.eE+-]*\) .*/\1/p' "$1/log.cutCells"
}
check() { # name value reference tolerance what
    if [ -z "$2" ] || [ -z "$3" ]; then
        fail "$1" "cutCells failed (fluid '$2', reference '$3')"
        return
    fi
    local d
    d=$(absdiff "$2" "$3")
    le "$d" "$4" && pass "$1" "fluid $2, $5 $3, |diff| $d <= $4" || fail "$1" "fluid $2, $5 $3, |diff| $d > $4"
}

obj=$TOP/tests/data/obj
CUBE_XF='scale 0.4; translate (-0.2 -0.2 -0.2); rotate { axis (1 2 3); angle 30; } translate (0.5 0.5 0.5);'
L_XF='scale 0.2; translate (-0.2 -0.2 -0.1); rotate { axis (1 2 3); angle 30; } translate (0.5 0.5 0.5);'

# ---- cube of quadrangles vs the analytic box and the exact volume -----------------
mkcase cube 24 "cube { shape obj; file \"constant/triSurface/cube.obj\"; $CUBE_XF }"
cp "$obj/cube.obj" cube/constant/triSurface/
mkcase box 24 "cube { shape box; min (0 0 0); max (1 1 1); $CUBE_XF }"
vc=$(cut cube)
vb=$(cut box)
check cutCells_obj_cube_vs_box "$vc" "$vb" 1e-12 "analytic box"
check cutCells_obj_cube_exact "$vc" 0.936 2e-3 exact

# ---- gzip and the same cube as STL ----------------------------------------------------
mkcase gz 24 "cube { shape surface; file \"constant/triSurface/cube.obj\"; $CUBE_XF }"
gzip -c "$obj/cube.obj" >gz/constant/triSurface/cube.obj.gz
check cutCells_obj_gzip "$(cut gz)" "$vc" 1e-12 "plain OBJ"
mkcase stl 24 "cube { shape stl; file \"constant/triSurface/cube.stl\"; $CUBE_XF }"
/usr/bin/python3 - "$obj/cube.obj" stl/constant/triSurface/cube.stl <<'EOF'
import sys
v, out = [], ["solid cube"]
for line in open(sys.argv[1]):
    w = line.split()
    if not w: continue
    if w[0] == "v": v.append(w[1:4])
    if w[0] == "f":
        c = [v[int(t.split("/")[0]) - 1] for t in w[1:]]
        for i in range(1, len(c) - 1):   # fan: the cube's faces are convex
            out += ["facet normal 0 0 0", "outer loop"] + ["vertex " + " ".join(p) for p in (c[0], c[i], c[i + 1])] + ["endloop", "endfacet"]
open(sys.argv[2], "w").write("\n".join(out + ["endsolid cube"]) + "\n")
EOF
check cutCells_obj_same_as_stl "$(cut stl)" "$vc" 1e-12 "STL"

# ---- non-convex faces: the L prism vs the CSG union of two boxes ---------------------
mkcase lprism 24 "l { shape obj; file \"constant/triSurface/lprism.obj\"; $L_XF }"
cp "$obj/lprism.obj" lprism/constant/triSurface/
mkcase union 24 "l { shape union; a { shape box; min (0 0 0); max (2 1 1); } b { shape box; min (0 0 0); max (1 2 1); } $L_XF }"
vl=$(cut lprism)
vu=$(cut union)
check cutCells_obj_lprism_vs_csg "$vl" "$vu" 1e-12 "CSG union"
check cutCells_obj_lprism_exact "$vl" 0.976 2e-3 exact
dp=$(/usr/bin/python3 - lprism/constant/polyMesh/points union/constant/polyMesh/points <<'EOF'
import re, sys
def read(f):
    return [tuple(map(float, m.groups())) for m in
            (re.match(r'^\(([-0-9.eE+]+) ([-0-9.eE+]+) ([-0-9.eE+]+)\)$', l.strip()) for l in open(f)) if m]
a, b = read(sys.argv[1]), read(sys.argv[2])
print("%d %d %.3g" % (len(a), len(b), max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q)) if a and len(a) == len(b) else 1))
EOF
)
read -r na nb d <<<"$dp"
[ "$na" = "$nb" ] && le "$d" 1e-12 && pass cutCells_obj_lprism_points "$na points, max difference $d" ||
    fail cutCells_obj_lprism_points "points $na / $nb, max difference $d"

# ---- OpenFOAM's OBJ reader: surfaceConvert to STL ------------------------------------------
mech=/usr/share/doc/openfoam-examples/examples/mesh/snappyHexMesh/gap_detection/constant/triSurface/mech_test.obj
if command -v surfaceConvert >/dev/null 2>&1 && [ -f "$mech" ]; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    # mech_test spans (-100 0 -300) .. (100 300 0)
    MXF='scale 0.0025; translate (0.5 0.1 0.9);'
    mkcase mech 24 "part { shape obj; file \"constant/triSurface/mech_test.obj\"; $MXF }"
    cp "$mech" mech/constant/triSurface/
    mkcase mechstl 24 "part { shape stl; file \"constant/triSurface/mech_test.stl\"; $MXF }"
    { header controlDict; echo 'application cutCells; startFrom startTime; startTime 0; stopAt endTime; endTime 1;'
      echo 'deltaT 1; writeControl timeStep; writeInterval 1; writeFormat ascii; writeCompression off;'
    } >mechstl/system/controlDict
    if surfaceConvert -case mechstl "$PWD/mech/constant/triSurface/mech_test.obj" \
        "$PWD/mechstl/constant/triSurface/mech_test.stl" >mechstl/log.surfaceConvert 2>&1; then
        check cutCells_obj_vs_openfoam "$(cut mech)" "$(cut mechstl)" 1e-12 "OpenFOAM's STL"
    else
        fail cutCells_obj_vs_openfoam "surfaceConvert failed: $(tail -n 3 mechstl/log.surfaceConvert)"
    fi
else
    echo "SKIP cutCells_obj_vs_openfoam: OpenFOAM's surfaceConvert or its gap_detection example is not installed"
fi

# ---- errors ---------------------------------------------------------------------------------
mkcase bad 8 "cube { shape obj; file \"constant/triSurface/bad.obj\"; }"
sed 's/^f 3 4 8 7$/f 3 4 9 7/' "$obj/cube.obj" >bad/constant/triSurface/bad.obj
"$BIN/blockGrid" -case bad >/dev/null 2>&1
if "$BIN/cutCells" -case bad >bad/log 2>bad/err; then
    fail cutCells_obj_bad_index "a face naming vertex 9 of 8 was accepted"
else
    grep -q 'geometryDict:4: .*bad.obj:36: vertex index 9 out of range: the file has 8 vertices' bad/err &&
        pass cutCells_obj_bad_index "$(head -n 1 bad/err)" || fail cutCells_obj_bad_index "message: $(cat bad/err)"
fi
mkcase open 8 "cube { shape obj; file \"constant/triSurface/open.obj\"; }"
grep -v '^f 3 4 8 7$' "$obj/cube.obj" >open/constant/triSurface/open.obj
"$BIN/blockGrid" -case open >/dev/null 2>&1
if "$BIN/cutCells" -case open >open/log 2>open/err; then
    fail cutCells_obj_open "an open OBJ was cut"
else
    grep -q 'geometryDict:4: .*open.obj is not watertight: 4 open edge' open/err &&
        pass cutCells_obj_open "$(head -c 160 open/err)" || fail cutCells_obj_open "message: $(cat open/err)"
fi
