#!/usr/bin/env bash
# test_checkGrid.sh: a good grid passes; broken grids (a flipped face, a
# missing face, faces out of order, a bad point index) fail with the cell
# or face named; a hand-made skewed grid gives checkMesh's numbers (when
# OpenFOAM is installed).
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

case_system good checkGrid
cat >good/system/blockGridDict <<'EOF'
x { segments ( (1 4 2) ); }
y { segments ( (1 3 1) ); }
z { segments ( (0.1 1 1) ); }
boundary { zMin { name fb; type empty; } zMax { name fb; type empty; } }
EOF
"$BIN/blockGrid" -case good >/dev/null 2>&1 || fail blockGrid "could not make the grid"

"$BIN/checkGrid" -case good >out 2>err; rc=$?
check good_grid_passes test $rc -eq 0
grep -q '^Grid OK\.$' out && grep -q 'cells:            12$' out && grep -q 'internal faces:   17$' out &&
    grep -q 'Grid is 2-D' out && grep -q 'Total volume = 0.1$' out &&
    grep -q 'Volume / parent volume: min 1 max 1' out && grep -q 'Non-orthogonality Max: 0 average: 0' out
check good_grid_numbers test $? -eq 0

# Copies the good case to $1, then runs the python edit $2 on its polyMesh.
broken() {
    rm -rf "$1"; cp -r good "$1"
    /usr/bin/python3 - "$1/constant/polyMesh" "$2" <<'EOF'
import sys
d, what = sys.argv[1], sys.argv[2]
def load(name):
    lines = open(d + "/" + name).read().split("\n")
    i = next(k for k, l in enumerate(lines) if l.strip() == "(")
    n = int(lines[i - 1])
    return lines, i + 1, n
def save(name, lines):
    open(d + "/" + name, "w").write("\n".join(lines))
faces, f0, nf = load("faces")
owner, o0, _ = load("owner")
if what == "flip":          # reverse internal face 5
    l = faces[f0 + 5]; k = l.index("(")
    pts = l[k + 1:-1].split()
    faces[f0 + 5] = l[:k] + "(" + " ".join(reversed(pts)) + ")"
    save("faces", faces)
    print(owner[o0 + 5])
elif what == "missing":     # remove the last boundary face
    last = nf - 1
    print(owner[o0 + last])
    del faces[f0 + last]; del owner[o0 + last]
    faces[f0 - 2] = str(nf - 1); owner[o0 - 2] = str(nf - 1)
    save("faces", faces); save("owner", owner)
    b = open(d + "/boundary").read()
    k = b.rindex("nFaces"); e = b.index(";", k)
    n = int(b[k + 6:e].strip())
    open(d + "/boundary", "w").write(b[:k] + "nFaces " + str(n - 1) + b[e:])
elif what == "order":       # swap internal faces 0 and 1 (both lists)
    nei, n0, _ = load("neighbour")
    for L, s in ((faces, f0), (owner, o0), (nei, n0)):
        L[s], L[s + 1] = L[s + 1], L[s]
    save("faces", faces); save("owner", owner); save("neighbour", nei)
elif what == "range":       # a point index beyond the points
    faces[f0 + 2] = "4(0 1 99999 3)"
    save("faces", faces)
EOF
}

cell=$(broken flip flip)
"$BIN/checkGrid" -case flip >out 2>err; rc=$?
if [ $rc -ne 0 ] && grep -q "^cell $cell: not closed, |sum S| = " err && grep -q '^Failed [1-9] grid checks' out &&
    ! grep -q 'Grid OK' out; then pass flipped_face_fails; else fail flipped_face_fails "rc=$rc cell=$cell $(cat err)"; fi

cell=$(broken missing missing)
"$BIN/checkGrid" -case missing >out 2>err; rc=$?
if [ $rc -ne 0 ] && grep -q "^cell $cell: not closed, |sum S| = 0.1.* of surface (1 open cells)$" err; then
    pass missing_face_fails; else fail missing_face_fails "rc=$rc cell=$cell $(cat err)"; fi

broken order order
"$BIN/checkGrid" -case order >out 2>err; rc=$?
if [ $rc -ne 0 ] && grep -q "face 1 .*upper-triangular" err; then
    pass face_order_fails; else fail face_order_fails "rc=$rc $(cat err)"; fi

broken range range
"$BIN/checkGrid" -case range >out 2>err; rc=$?
if [ $rc -ne 0 ] && grep -q "faces" err && ! grep -qi "sanitizer\|segmentation" err; then
    pass bad_index_fails; else fail bad_index_fails "rc=$rc $(cat err)"; fi

"$BIN/checkGrid" -case nowhere >out 2>err; rc=$?
check missing_case_fails test $rc -ne 0
"$BIN/checkGrid" -i good/constant/polyMesh >out2 2>&1
check input_option grep -q '^Grid OK\.$' out2

# ---- hand-made skewed grid: two cells, the second sheared by s = 1 ----
mkdir -p skew/system skew/constant/polyMesh
cp good/system/controlDict good/system/fvSchemes good/system/fvSolution skew/system/
/usr/bin/python3 - skew/constant/polyMesh <<'EOF'
import sys
d = sys.argv[1]
P = [(0,0,0),(1,0,0),(0,1,0),(1,1,0),(0,0,1),(1,0,1),(0,1,1),(1,1,1),(2,1,0),(2,2,0),(2,1,1),(2,2,1)]
F = [(1,3,7,5),(0,4,6,2),(0,1,5,4),(2,6,7,3),(0,2,3,1),(4,5,7,6),
     (8,9,11,10),(1,8,10,5),(3,7,11,9),(1,3,9,8),(5,10,11,7)]
O = [0,0,0,0,0,0,1,1,1,1,1]
def head(cls, obj):
    return "FoamFile { version 2.0; format ascii; class %s; location \"constant/polyMesh\"; object %s; }\n" % (cls, obj)
open(d+"/points","w").write(head("vectorField","points")+"%d\n(\n%s\n)\n" % (len(P), "\n".join("(%g %g %g)" % p for p in P)))
open(d+"/faces","w").write(head("faceList","faces")+"%d\n(\n%s\n)\n" % (len(F), "\n".join("4(%d %d %d %d)" % f for f in F)))
open(d+"/owner","w").write(head("labelList","owner")+"%d\n(\n%s\n)\n" % (len(O), "\n".join(map(str,O))))
open(d+"/neighbour","w").write(head("labelList","neighbour")+"1\n(\n1\n)\n")
open(d+"/boundary","w").write(head("polyBoundaryMesh","boundary")+"1\n(\n walls { type wall; inGroups 1(wall); nFaces 10; startFace 1; }\n)\n")
EOF
"$BIN/checkGrid" -case skew >sk 2>&1; rc=$?
grep -q '^Grid OK\.$' sk && grep -q 'Non-orthogonality Max: 26.5651 average: 26.5651 (face 0)' sk &&
    grep -q 'Max skewness = 1 (face 6)' sk && grep -q 'Max aspect ratio = 2 (cell 1)' sk &&
    grep -q 'Total volume = 2$' sk
check skewed_grid_numbers test $? -eq 0
if command -v checkMesh >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    checkMesh -case skew >cm 2>&1
    # checkMesh's max non-orthogonality, average, skewness, aspect ratio
    ours=$(sed -n 's/.*Non-orthogonality Max: \([^ ]*\) average: \([^ ]*\) .*/\1 \2/p; s/.*Max skewness = \([^ ]*\) .*/\1/p; s/.*Max aspect ratio = \([^ ]*\) .*/\1/p' sk | tr '\n' ' ')
    theirs=$(sed -n 's/.*Mesh non-orthogonality Max: \([^ ]*\) average: \([^ ]*\).*/\1 \2/p; s/.*Max skewness = \([^ ]*\) .*/\1/p; s/.*Max aspect ratio = \([^ ]*\) .*/\1/p' cm | tr '\n' ' ')
    # checkMesh order: aspect, non-orth, skewness; ours: non-orth, skewness, aspect
    if [ -n "$theirs" ] && [ "$(echo $ours | awk '{print $4, $1, $2, $3}')" = "$(echo $theirs)" ]; then
        pass skewed_matches_checkMesh
    else
        fail skewed_matches_checkMesh "ours: $ours theirs: $theirs"
    fi
else
    echo "SKIP skewed_matches_checkMesh: OpenFOAM's checkMesh is not installed"
fi
exit 0
