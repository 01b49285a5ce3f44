#!/usr/bin/env bash
# test_mergeCells.sh: mergeCells on hand-made 2-D cut grids whose numbers
# are known exactly (written by the small exact cutter below, the same as
# tests/common/test_merge.c's): the statistics, the merged cell and its
# volume, mergeMap, checkGrid on the result, the stream form in and out
# against the files, the dictionary (every keyword, -help, bad values and
# unknown keywords as file:line with non-zero exit and the old grid
# untouched), unresolved cells listed with their reason, and OpenFOAM's
# checkMesh when it is installed.
#
# corner: 3x3 unit cells, fluid below y = 1.7 + 0.75 x: cell 6 = (0,2) is
#   the triangle (0.4,2) (1,2) (1,2.45) of area 0.135, merged into cell 3 =
#   (0,1), area 0.94, giving 1.075; 8 cells out; the smallest ratio after
#   is cell (1,2)'s 0.798333.
# chain: 3x1 unit cells, fluid below y = 0.1 + 0.05 x: slivers 0.125,
#   0.175, 0.225 chain into one cell of 0.525.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

# cutcase DIR NX NY "x0 x1 ..." "y0 y1 ..." c0 c1 c2: writes DIR/constant/polyMesh
# (with cartesianGrid, cellParent, boundaryNormal) and DIR/cut.stream
cutcase() {
    mkdir -p "$1/system" "$1/constant/polyMesh"
    /usr/bin/python3 - "$@" <<'EOF'
import sys, os
d, nx, ny = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
X = [float(v) for v in sys.argv[4].split()]
Y = [float(v) for v in sys.argv[5].split()]
c = [float(v) for v in sys.argv[6:9]]
Z = [0.0, 1.0]
side = lambda p: c[0] + c[1] * p[0] + c[2] * p[1]
def crossing(a, b):
    if a > b: a, b = b, a
    sa, sb = side(a), side(b); t = sa / (sa - sb)
    return (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
def clip(i, j):
    sq = [(X[i], Y[j]), (X[i+1], Y[j]), (X[i+1], Y[j+1]), (X[i], Y[j+1])]
    v, ty = [], []
    for k in range(4):
        p, q = sq[k], sq[(k+1) % 4]
        pin, qin = side(p) >= 0, side(q) >= 0
        if pin != qin: v.append(crossing(p, q)); ty.append(1 if pin else 2)
        if qin: v.append(q); ty.append(0)
    return (v, ty) if len(v) >= 3 else (None, None)
pts, pid = [], {}
def point(x, y, z):
    key = (round(x, 12), round(y, 12), z)
    if key not in pid: pid[key] = len(pts); pts.append((x, y, z))
    return pid[key]
ids, parent = {}, []
for j in range(ny):
    for i in range(nx):
        if clip(i, j)[0]: ids[(i, j)] = len(parent); parent.append(i + nx * j)
faces = []   # (owner, neighbour or -1-patch, points, normal)
L = (c[1] ** 2 + c[2] ** 2) ** 0.5
for j in range(ny):
    for i in range(nx):
        v, ty = clip(i, j)
        if not v: continue
        cc, n = ids[(i, j)], len(v)
        for k in range(n):
            a, b = v[k], v[(k+1) % n]
            f = [point(a[0], a[1], Z[0]), point(b[0], b[1], Z[0]), point(b[0], b[1], Z[1]), point(a[0], a[1], Z[1])]
            if ty[k] == 1 and ty[(k+1) % n] == 2:
                faces.append((cc, -2, f, (-c[1] / L, -c[2] / L, 0))); continue
            di = -1 if a[0] == b[0] == X[i] else 1 if a[0] == b[0] == X[i+1] else 0
            dj = 0 if di else (-1 if a[1] == b[1] == Y[j] else 1)
            nb = ids.get((i + di, j + dj), -1)
            if nb > cc: faces.append((cc, nb, f, None))
            elif nb < 0: faces.append((cc, -1, f, (di, dj, 0)))
        faces.append((cc, -3, [point(p[0], p[1], Z[0]) for p in reversed(v)], (0, 0, -1)))
        faces.append((cc, -3, [point(p[0], p[1], Z[1]) for p in v], (0, 0, 1)))
internal = sorted([f for f in faces if f[1] >= 0], key=lambda f: (f[0], f[1]))
bnd = [f for p in (-1, -2, -3) for f in faces if f[1] == p]
allf = internal + bnd
def hdr(cls, obj):
    return ('FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n'
            '    location "constant/polyMesh";\n    object %s;\n}\n' % (cls, obj))
g = lambda x: repr(float(x))
files = {}
files['points'] = hdr('vectorField', 'points') + '%d\n(\n' % len(pts) + ''.join(
    '(%s %s %s)\n' % tuple(g(x) for x in p) for p in pts) + ')\n'
files['faces'] = hdr('faceList', 'faces') + '%d\n(\n' % len(allf) + ''.join(
    '%d(%s)\n' % (len(f[2]), ' '.join(map(str, f[2]))) for f in allf) + ')\n'
files['owner'] = hdr('labelList', 'owner') + '%d\n(\n' % len(allf) + ''.join('%d\n' % f[0] for f in allf) + ')\n'
files['neighbour'] = hdr('labelList', 'neighbour') + '%d\n(\n' % len(internal) + ''.join(
    '%d\n' % f[1] for f in internal) + ')\n'
sizes = [sum(1 for f in bnd if f[1] == p) for p in (-1, -2, -3)]
starts = [len(internal), len(internal) + sizes[0], len(internal) + sizes[0] + sizes[1]]
pat = [('walls', 'wall'), ('body', 'wall'), ('frontAndBack', 'empty')]
files['boundary'] = hdr('polyBoundaryMesh', 'boundary') + '3\n(\n' + ''.join(
    '%s { type %s; nFaces %d; startFace %d; }\n' % (pat[k][0], pat[k][1], sizes[k], starts[k]) for k in range(3)) + ')\n'
files['cartesianGrid'] = hdr('dictionary', 'cartesianGrid') + 'n (%d %d 1);\nx %d(%s);\ny %d(%s);\nz 2(0 1);\n' % (
    nx, ny, len(X), ' '.join(map(g, X)), len(Y), ' '.join(map(g, Y)))
files['cellParent'] = hdr('labelList', 'cellParent') + '%d\n(\n' % len(parent) + ''.join('%d\n' % p for p in parent) + ')\n'
files['boundaryNormal'] = hdr('vectorField', 'boundaryNormal') + '%d\n(\n' % len(bnd) + ''.join(
    '(%s %s %s)\n' % tuple(g(x) for x in f[3]) for f in bnd) + ')\n'
stream = b''
for name, text in files.items():
    open(os.path.join(d, 'constant/polyMesh', name), 'w').write(text)
    stream += b'@file %s %d\n' % (name.encode(), len(text.encode())) + text.encode()
open(os.path.join(d, 'cut.stream'), 'wb').write(stream + b'@end\n')
EOF
}

# labels NAME FILE: the labelList of FILE, one per line
labels() { /usr/bin/python3 -c '
import re, sys
t = re.sub(r"FoamFile\s*\{[^}]*\}", "", open(sys.argv[1]).read())
m = re.search(r"(\d+)\s*\(([^)]*)\)", t)
print(" ".join(m.group(2).split()))' "$1"; }

# ---- corner triangle ----
cutcase corner 3 3 "0 1 2 3" "0 1 2 3" 1.7 0.75 -1
cp -r corner/constant/polyMesh corner_cut
"$BIN/mergeCells" -case corner >log_corner 2>&1; rc=$?
check corner_runs test $rc -eq 0
grep -q '^  cells in:  *9$' log_corner && grep -q '^  cells out:  *8$' log_corner &&
    grep -q '^  slaves (V <= M_V V_cart): 1$' log_corner && grep -q '^  clusters:  *1 (1 round)$' log_corner &&
    grep -q '^  smallest volume ratio:   before 0.135, after 0.798333 (cell 6)$' log_corner &&
    grep -q '^  worst aspect ratio:      before 1.33333, after 1.45$' log_corner &&
    grep -q '^  unresolved cells:  *0$' log_corner
check corner_statistics test $? -eq 0
rel=$(sed -n 's/^  total volume: .*relative difference \(.*\))$/\1/p' log_corner)
check corner_volume_unchanged /usr/bin/python3 -c "import sys; sys.exit(not abs(float('$rel')) <= 1e-12)"
check corner_merge_map test "$(labels corner/constant/polyMesh/mergeMap)" = "0 1 2 3 4 5 3 6 7"
check corner_parents test "$(labels corner/constant/polyMesh/cellParent)" = "0 1 2 3 4 5 7 8"
"$BIN/checkGrid" -case corner >cg_corner 2>&1
check corner_checkGrid grep -q '^Grid OK\.' cg_corner
# the merged cell 3: volume 0.94 + 0.135 (VTK's own reader is not needed: checkGrid's min/max)
vol=$(/usr/bin/python3 - corner/constant/polyMesh <<'EOF'
import re, sys
d = sys.argv[1]
def body(n):
    t = re.sub(r"FoamFile\s*\{[^}]*\}", "", open(d + '/' + n).read())
    return t[t.index('(') + 1:t.rindex(')')]
P = [tuple(map(float, s.split())) for s in re.findall(r"\(([^()]*)\)", body('points'))]
F = [list(map(int, s.split())) for s in re.findall(r"\d+\(([^()]*)\)", body('faces'))]
O = list(map(int, body('owner').split()))
N = list(map(int, body('neighbour').split()))
V = [0.0] * (max(O) + 1)
for f, pts in enumerate(F):   # V = sum over faces of x . S / 3 (exact for planar faces)
    s = 0.0
    x0 = P[pts[0]]
    for a, b in zip(pts[1:-1], pts[2:]):
        u = [P[a][k] - x0[k] for k in range(3)]; w = [P[b][k] - x0[k] for k in range(3)]
        S = (u[1]*w[2] - u[2]*w[1], u[2]*w[0] - u[0]*w[2], u[0]*w[1] - u[1]*w[0])
        s += sum((x0[k] + P[a][k] + P[b][k]) / 3 * S[k] for k in range(3)) / 6
    V[O[f]] += s
    if f < len(N): V[N[f]] -= s
print("%.15f" % V[3])
EOF
)
check corner_merged_volume test "$vol" = "1.075000000000000"

# ---- stream form: in from stdin, out to stdout, same bytes as the files ----
mkdir -p s1
"$BIN/mergeCells" -case s1 -i - -o s1/out <corner/cut.stream >log_s1 2>&1
"$BIN/mergeCells" -case s1 -i corner_cut -o - >s1/out.stream 2>log_s2; rc=$?
check stream_runs test $rc -eq 0
/usr/bin/python3 - s1/out.stream s1/split <<'EOF'
import os, sys
data = open(sys.argv[1], 'rb').read()
os.makedirs(sys.argv[2], exist_ok=True)
i = 0
while not data.startswith(b'@end\n', i):
    j = data.index(b'\n', i)
    _, name, n = data[i:j].split()
    open(os.path.join(sys.argv[2], name.decode()), 'wb').write(data[j + 1:j + 1 + int(n)])
    i = j + 1 + int(n)
EOF
same=1
for f in points faces owner neighbour boundary cartesianGrid cellParent boundaryNormal mergeMap; do
    cmp -s s1/out/$f corner/constant/polyMesh/$f || same=0
    cmp -s s1/split/$f corner/constant/polyMesh/$f || same=0
done
check stream_same_bytes test $same -eq 1
check stream_messages_on_stderr grep -q '^  cells out:  *8$' log_s2
"$BIN/checkGrid" -i - <s1/out.stream >cg_s1 2>&1
check stream_checkGrid grep -q '^Grid OK\.' cg_s1

# ---- dictionary ----
dict() { # case text
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object mergeCellsDict; }\n%s\n' "$2" \
        >"$1/system/mergeCellsDict"
}
cutcase d1 3 3 "0 1 2 3" "0 1 2 3" 1.7 0.75 -1
dict d1 'threshold 0.1;'
"$BIN/mergeCells" -case d1 >log_d1 2>&1
check threshold_keyword grep -q '^  cells out:  *9$' log_d1
# column 0 twice as wide: the slave (0,2) goes -y with normal, +x with normalSpacing
cutcase d2 3 3 "0 2 3 4" "0 1 2 3" 1.7 0.75 -1
dict d2 'criterion normalSpacing; maxIter 3;'
"$BIN/mergeCells" -case d2 >log_d2 2>&1
check criterion_normalSpacing test "$(labels d2/constant/polyMesh/mergeMap)" = "0 1 2 3 4 5 6 6 7"
grep -q 'criterion normalSpacing, maxIter 3' log_d2
check criterion_logged test $? -eq 0
cutcase d3 3 3 "0 2 3 4" "0 1 2 3" 1.7 0.75 -1
"$BIN/mergeCells" -case d3 >log_d3 2>&1
check criterion_normal test "$(labels d3/constant/polyMesh/mergeMap)" = "0 1 2 3 4 5 3 6 7"

bad() { # name expected-message dictionary-text
    mkdir -p "bad_$1"
    mkdir -p "bad_$1/system" "bad_$1/constant"
    cp -r corner_cut "bad_$1/constant/polyMesh"
    dict "bad_$1" "$3"
    "$BIN/mergeCells" -case "bad_$1" >"bad_$1/log" 2>&1; local rc=$?
    if [ $rc -ne 0 ] && grep -qF -- "$2" "bad_$1/log" && [ ! -e "bad_$1/constant/polyMesh/mergeMap" ]; then
        pass "bad_$1"
    else
        fail "bad_$1" "rc=$rc, expected '$2', got: $(tail -n 2 "bad_$1/log")"
    fi
}
bad unknown_keyword "system/mergeCellsDict:3: unknown keyword 'treshold'" $'\ntreshold 0.3;'
bad suggestion "did you mean 'threshold'?" 'treshold 0.3;'
bad threshold_range "system/mergeCellsDict:2: threshold must be in (0, 1], found 2" 'threshold 2;'
bad threshold_word "system/mergeCellsDict:2:" 'threshold half;'
bad criterion "system/mergeCellsDict:2:" 'criterion normals;'
bad criterion_choices "normalSpacing" 'criterion normals;'
bad maxiter "system/mergeCellsDict:3: maxIter must be >= 0, found -1" $'threshold 0.5;\nmaxIter -1;'
bad syntax "system/mergeCellsDict:" 'threshold 0.5'
bad minratio_range "system/mergeCellsDict:3: minRatio must be in [0, threshold), found 0.5" $'threshold 0.5;\nminRatio 0.5;'
bad minratio_negative "system/mergeCellsDict:2: minRatio must be in [0, threshold), found -0.1" 'minRatio -0.1;'

# a grid without Cartesian parents
mkdir -p np/system np/constant
cp -r corner_cut np/constant/polyMesh
rm np/constant/polyMesh/cellParent
"$BIN/mergeCells" -case np >log_np 2>&1; rc=$?
test $rc -ne 0 && grep -q "polyMesh: merge: the grid has no Cartesian parents" log_np
check no_parents test $? -eq 0
"$BIN/mergeCells" -case nonexistent >log_ne 2>&1
check missing_grid test $? -ne 0
"$BIN/mergeCells" -case corner extra >log_arg 2>&1
check extra_argument test $? -ne 0

"$BIN/mergeCells" -help >help 2>&1
grep -q '^  threshold  *0.5 ' help && grep -q '^  criterion  *normal ' help && grep -q '^  maxIter  *10 ' help &&
    grep -q '^  minRatio  *0.01 ' help
check help_keywords test $? -eq 0

# ---- chain, and unresolved cells listed ----
cutcase chain 3 1 "0 1 2 3" "0 1" 0.1 0.05 -1
"$BIN/mergeCells" -case chain >log_chain 2>&1
grep -q '^  cells out:  *1$' log_chain && grep -q '^  smallest volume ratio:   before 0.125, after 0.525 (cell 0)$' log_chain
check chain_merged test $? -eq 0
cutcase chain6 3 1 "0 1 2 3" "0 1" 0.1 0.05 -1
dict chain6 'threshold 0.6;'
"$BIN/mergeCells" -case chain6 >log_chain6 2>&1
grep -q '^  unresolved cells:  *1$' log_chain6 &&
    grep -q '^    cell 0 (parent 2, volume ratio 0.525): no neighbour to merge with (none, or none giving a sound cell)$' log_chain6
check unresolved_listed test $? -eq 0

# ---- bad input on stdin, binary and gzip output ----
printf 'not a grid\n' | "$BIN/mergeCells" -case corner -i - -o garbage_out >log_garbage 2>&1; rc=$?
test $rc -ne 0 && grep -q 'stdin' log_garbage && [ ! -e garbage_out ]
check garbage_stdin test $? -eq 0
"$BIN/mergeCells" -case corner -i corner_cut -o bin_out -binary -gzip >log_bin 2>&1; rc=$?
test $rc -eq 0 && [ -f bin_out/faces.gz ] && [ -f bin_out/mergeMap.gz ] && zcat bin_out/faces.gz | grep -q 'format *binary'
check binary_gzip_written test $? -eq 0
"$BIN/checkGrid" -i bin_out >cg_bin 2>&1
grep -q '^Grid OK\.' cg_bin && grep -q 'cells: *8$' cg_bin
check binary_gzip_checkGrid test $? -eq 0

# ---- a grid without slaves comes out unchanged (a block grid) ----
mkdir -p blk/system
cat >blk/system/blockGridDict <<'EOF'
x { segments ((1 4 1) (2 2 2)); }
y { segments ((1 3 1)); }
z { segments ((0.5 2 1)); }
EOF
"$BIN/blockGrid" -case blk >/dev/null 2>&1
cp -r blk/constant/polyMesh blk_orig
"$BIN/mergeCells" -case blk >log_blk 2>&1
same=1
for f in points faces owner neighbour boundary cartesianGrid cellParent; do
    cmp -s blk/constant/polyMesh/$f blk_orig/$f || same=0
done
check no_slaves_unchanged test $same -eq 1
check no_slaves_identity_map test "$(labels blk/constant/polyMesh/mergeMap)" = "$(seq -s ' ' 0 35)"

# ---- OpenFOAM's checkMesh (optional) ----
if command -v checkMesh >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    cat >corner/system/controlDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application mergeCells; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeControl timeStep; writeInterval 1; writeFormat ascii;
EOF
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\n%s\n' \
        'ddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {} interpolationSchemes {} snGradSchemes {}' \
        >corner/system/fvSchemes
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n' >corner/system/fvSolution
    checkMesh -case corner >cm_corner 2>&1
    check checkMesh_corner grep -q '^Mesh OK\.' cm_corner
    check checkMesh_corner_cells grep -q '^    cells: *8$' cm_corner
    # a merged 2-D cell keeps two empty faces, so the grid stays 2-D
    check checkMesh_corner_2d test -z "$(grep 'not divisible' cm_corner)"
else
    echo "SKIP checkMesh: OpenFOAM's checkMesh is not installed"
fi
exit 0
