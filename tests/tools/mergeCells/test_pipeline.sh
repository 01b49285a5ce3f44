#!/usr/bin/env bash
# test_pipeline.sh: blockGrid -> cutCells -> mergeCells on a 2-D disc and a
# 3-D sphere case.  The merged grids are checked against the cut grids with
# volumes computed here independently (divergence theorem on the ascii
# polyMesh files, in Python):
#   - every merged cell has V > M_V V_cart (V_cart from cartesianGrid and
#     cellParent) or is listed in the log as unresolved;
#   - the total volume is unchanged (1e-12 relative), and mergeMap sends
#     the cut cells' volumes to merged cells of exactly that volume
#     (1e-12 of a cell);
#   - in 2-D every merged cell keeps exactly two empty faces;
#   - checkGrid says "Grid OK."; OpenFOAM's checkMesh (when installed)
#     says "Mesh OK." (no validity error, and with the quality pass no
#     face skewness above 4: 5.32 before it in the sphere grid);
#   - the pipe "blockGrid -o - | cutCells -i - -o - | mergeCells -i -"
#     writes byte-identical files to the tools run one by one.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

if [ ! -x "$BIN/cutCells" ]; then
    echo "SKIP pipeline: $BIN/cutCells is not built"
    exit 0
fi

mkcase() { # dir nx nz zlo zhi geometry-body
    mkdir -p "$1/system"
    local zb
    if [ "$3" = 1 ]; then
        zb='zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; }'
    else
        zb='zMin { name walls; } zMax { name walls; }'
    fi
    { header blockGridDict
      echo "x { segments ((1 $2 1)); }"
      echo "y { segments ((1 $2 1)); }"
      echo "z { start $4; segments (($5 $3 1)); }"
      echo "boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; } $zb }"
    } >"$1/system/blockGridDict"
    { header geometryDict; echo "surfaces { body { type wall; flow outside; $6 } }"; } >"$1/system/geometryDict"
    case_system "$1" mergeCells
}

# volumes.py CUT MERGED LOG THRESHOLD: the independent checks; prints
# "ok <details>" or "bad <why>"
cat >volumes.py <<'EOF'
import re, sys
def body(d, n):
    t = re.sub(r"FoamFile\s*\{[^}]*\}", "", open(d + '/' + n).read())
    return t[t.index('(') + 1:t.rindex(')')]
def mesh(d):
    P = [tuple(map(float, s.split())) for s in re.findall(r"\(([^()]*)\)", body(d, 'points'))]
    F = [list(map(int, s.split())) for s in re.findall(r"\d+\(([^()]*)\)", body(d, 'faces'))]
    O = list(map(int, body(d, 'owner').split()))
    N = list(map(int, body(d, 'neighbour').split()))
    V = [0.0] * (max(O) + 1)
    for f, pts in enumerate(F):   # V = sum over faces of xbar . S / 3, exact for planar faces
        x0 = P[pts[0]]; s = 0.0
        for a, b in zip(pts[1:-1], pts[2:]):
            u = [P[a][k] - x0[k] for k in range(3)]; w = [P[b][k] - x0[k] for k in range(3)]
            S = (u[1]*w[2] - u[2]*w[1], u[2]*w[0] - u[0]*w[2], u[0]*w[1] - u[1]*w[0])
            s += sum((x0[k] + P[a][k] + P[b][k]) * S[k] for k in range(3)) / 18
        V[O[f]] += s
        if f < len(N): V[N[f]] -= s
    return V, O, N
def labels(d, n): return list(map(int, body(d, n).split()))
cut, merged, log, M = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
Vc, _, _ = mesh(cut)
Vm, Om, Nm = mesh(merged)
t = open(merged + '/cartesianGrid').read()
n = list(map(int, re.search(r"\nn\s*\((\d+) (\d+) (\d+)\)", t).groups()))
ax = [list(map(float, re.search(r"\n%s\s+\d+\s*\(([^)]*)\)" % a, t).group(1).split())) for a in 'xyz']
par = labels(merged, 'cellParent'); mm = labels(merged, 'mergeMap')
listed = set(int(c) for c in re.findall(r"^    cell (\d+) \(parent", open(log).read(), re.M))
why = []
for c, v in enumerate(Vm):
    p = par[c]; i, j, k = p % n[0], (p // n[0]) % n[1], p // (n[0] * n[1])
    vc = (ax[0][i+1] - ax[0][i]) * (ax[1][j+1] - ax[1][j]) * (ax[2][k+1] - ax[2][k])
    if not (v > M * vc) and c not in listed: why.append("cell %d: %g of %g" % (c, v, vc))
if len(mm) != len(Vc): why.append("mergeMap has %d entries for %d cells" % (len(mm), len(Vc)))
S = [0.0] * len(Vm)
for c, v in enumerate(Vc): S[mm[c]] += v
scale = max(Vc)
bad = [c for c in range(len(Vm)) if abs(S[c] - Vm[c]) > 1e-12 * scale]
if bad: why.append("cell %d: %.17g, members %.17g" % (bad[0], Vm[bad[0]], S[bad[0]]))
rel = abs(sum(Vm) - sum(Vc)) / sum(Vc)
if rel > 1e-12: why.append("total %.17g -> %.17g" % (sum(Vc), sum(Vm)))
print(("bad " + "; ".join(why[:3])) if why else "ok %d -> %d cells, %d listed, volume change %.1e" % (len(Vc), len(Vm), len(listed), rel))
EOF

run_case() { # name
    local c=$1
    "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1 &&
        "$BIN/cutCells" -case $c >$c/log.cutCells 2>&1 &&
        cp -r $c/constant/polyMesh $c/cut &&
        "$BIN/mergeCells" -case $c >$c/log.mergeCells 2>&1
    check ${c}_steps_run test $? -eq 0
    local r
    r=$(/usr/bin/python3 volumes.py $c/cut $c/constant/polyMesh $c/log.mergeCells 0.5 2>&1)
    if [ "${r%% *}" = ok ]; then pass ${c}_volumes "${r#ok }"; else fail ${c}_volumes "$r"; fi
    "$BIN/checkGrid" -case $c >$c/log.checkGrid 2>&1
    check ${c}_checkGrid grep -q '^Grid OK\.' $c/log.checkGrid
    grep -q 'relative difference' $c/log.mergeCells
    check ${c}_report test $? -eq 0

    # the same through pipes, into a copy of the case
    cp -r $c/system ${c}_pipe_system
    mkdir -p ${c}_pipe && mv ${c}_pipe_system ${c}_pipe/system
    "$BIN/blockGrid" -case ${c}_pipe -o - 2>${c}_pipe/log.b |
        "$BIN/cutCells" -case ${c}_pipe -i - -o - 2>${c}_pipe/log.c |
        "$BIN/mergeCells" -case ${c}_pipe -i - >${c}_pipe/log.m 2>&1
    local st=("${PIPESTATUS[@]}") same=1 f
    for f in $(ls $c/constant/polyMesh); do
        cmp -s $c/constant/polyMesh/$f ${c}_pipe/constant/polyMesh/$f || same=0
    done
    [ "$(ls $c/constant/polyMesh)" = "$(ls ${c}_pipe/constant/polyMesh)" ] || same=0
    check ${c}_pipe_identical test "${st[*]}" = "0 0 0" -a $same -eq 1

    if command -v checkMesh >/dev/null 2>&1; then
        export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
        checkMesh -case $c >$c/log.checkMesh 2>&1
        local errs
        errs=$(grep -E '^ *\*\*\*' $c/log.checkMesh | grep -v -e 'not divisible')
        if grep -q '^Mesh OK\.' $c/log.checkMesh && [ -z "$errs" ]; then
            pass ${c}_checkMesh_valid "$(grep -h -E 'Max skewness' $c/log.checkMesh | sed 's/^ *//')"
        else
            fail ${c}_checkMesh_valid "$errs $(grep -E 'FATAL' $c/log.checkMesh)"
        fi
    else
        echo "SKIP ${c}_checkMesh_valid: OpenFOAM's checkMesh is not installed"
    fi
}

mkcase disc 32 1 -0.015625 0.015625 'shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.23;'
run_case disc
# 2-D: two empty faces per merged cell
n2=$(/usr/bin/python3 - disc/constant/polyMesh <<'EOF'
import re, sys
t = open(sys.argv[1] + '/boundary').read()
m = re.search(r"frontAndBack\s*\{[^}]*nFaces\s+(\d+)", t)
o = open(sys.argv[1] + '/owner').read()
print(int(m.group(1)) - 2 * int(re.search(r"nCells:\s*(\d+)", o).group(1)))
EOF
)
check disc_two_empty_faces_per_cell test "$n2" = 0
grep -q '^  slaves (V <= M_V V_cart): [1-9]' disc/log.mergeCells
check disc_has_slaves test $? -eq 0

mkcase sphere 14 14 0 1 'shape sphere; centre (0.5 0.5 0.5); radius 0.3;'
run_case sphere
grep -q '^  slaves (V <= M_V V_cart): [1-9]' sphere/log.mergeCells
check sphere_has_slaves test $? -eq 0
exit 0
