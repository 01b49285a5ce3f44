#!/usr/bin/env bash
# test_quality.sh: the quality pass of mergeCells (maxSkewness) on the
# grids of the tutorials sphereInBox (unit cube, 32^3, flow outside a
# sphere of radius 0.3 at the centre) and discInBox (unit square, 64 x 64,
# one cell thick, flow outside a disc of radius 0.2), run through
# blockGrid -> cutCells -> mergeCells.  The dictionaries are copied from
# tutorials/grids/<case>/system when present, else written here.
#   - with the default maxSkewness 4, OpenFOAM's checkMesh says "Mesh OK."
#     (when installed; without it, checkGrid's "Max skewness" is <= 4) and
#     the merge log's "after" skewness is checkGrid's;
#   - with maxSkewness 0 (pass off) checkGrid finds faces above 4 (8.16 in
#     the sphere grid, 7.04 in the disc grid), so the pass is what fixes
#     them;
#   - a negative maxSkewness is refused with file:line.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

for t in blockGrid cutCells mergeCells checkGrid; do
    if [ ! -x "$BIN/$t" ]; then
        echo "SKIP quality: $BIN/$t is not built"
        exit 0
    fi
done

# mkcase name: the tutorial's system directory, or the same grid written here
mkcase() {
    local c=$1
    if [ -d "$TOP/tutorials/grids/$c/system" ]; then
        mkdir -p $c && cp -r "$TOP/tutorials/grids/$c/system" $c/
        rm -f $c/system/mergeCellsDict
        return
    fi
    mkdir -p $c/system
    local n z zb body
    if [ $c = discInBox ]; then
        n=64 z='start -0.0078125; segments ((0.0078125 1 1));'
        zb='zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; }'
        body='disc { type wall; flow outside; shape cylinder; point1 (0.5 0.5 -1); point2 (0.5 0.5 1); radius 0.2; }'
    else
        n=32 z='segments ((1 32 1));'
        zb='zMin { name walls; type wall; } zMax { name walls; type wall; }'
        body='sphere { type wall; flow outside; shape sphere; centre (0.5 0.5 0.5); radius 0.3; }'
    fi
    { header blockGridDict
      echo "x { segments ((1 $n 1)); } y { segments ((1 $n 1)); } z { $z }"
      echo "boundary { xMin { name walls; type wall; } xMax { name walls; type wall; }"
      echo "  yMin { name walls; type wall; } yMax { name walls; type wall; } $zb }"
    } >$c/system/blockGridDict
    { header geometryDict; echo "surfaces { $body }"; } >$c/system/geometryDict
    case_system $c mergeCells
}

# max skewness from a checkGrid log
maxskew() { sed -n 's/^ *Max skewness = \([0-9.e+-]*\).*/\1/p' "$1"; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 <= b + 0) }'; }

run() { # case: merges with the default pass and with it off
    local c=$1
    mkcase $c
    if ! { "$BIN/blockGrid" -case $c >$c/log.blockGrid 2>&1 && "$BIN/cutCells" -case $c >$c/log.cutCells 2>&1; }; then
        fail ${c}_cut "blockGrid or cutCells failed: $(tail -2 $c/log.cutCells)"
        return
    fi
    cp -r $c/constant/polyMesh $c/cut

    { header mergeCellsDict; echo 'maxSkewness 0;'; } >$c/system/mergeCellsDict
    "$BIN/mergeCells" -case $c -o off >$c/log.mergeCells.off 2>&1 &&
        mkdir -p ${c}_off/system ${c}_off/constant && cp $c/system/* ${c}_off/system/ && mv off ${c}_off/constant/polyMesh &&
        "$BIN/checkGrid" -case ${c}_off >$c/log.checkGrid.off 2>&1
    local s0
    s0=$(maxskew $c/log.checkGrid.off)
    if [ -n "$s0" ] && ! le "$s0" 4; then pass ${c}_skewed_without_pass "max skewness $s0"; else
        fail ${c}_skewed_without_pass "max skewness '$s0' with maxSkewness 0"; fi

    rm $c/system/mergeCellsDict
    if ! "$BIN/mergeCells" -case $c >$c/log.mergeCells 2>&1; then
        fail ${c}_merge "$(tail -2 $c/log.mergeCells)"
        return
    fi
    "$BIN/checkGrid" -case $c >$c/log.checkGrid 2>&1
    local s1 after
    s1=$(maxskew $c/log.checkGrid)
    after=$(sed -n 's/^  max skewness: .*, after \([0-9.e+-]*\) (.*/\1/p' $c/log.mergeCells)
    if le "$s1" 4 && grep -q '^Grid OK\.' $c/log.checkGrid; then pass ${c}_skewness "max skewness $s0 -> $s1"; else
        fail ${c}_skewness "checkGrid: max skewness '$s1'"; fi
    if [ -n "$after" ] && awk -v a="$after" -v b="$s1" 'BEGIN { exit !(a - b < 1e-5 * b && b - a < 1e-5 * b) }'; then
        pass ${c}_reported "log says $after"; else fail ${c}_reported "log '$after', checkGrid '$s1'"; fi
    if grep -q '^  unresolved cells: *0$' $c/log.mergeCells; then pass ${c}_none_unresolved; else
        fail ${c}_none_unresolved "$(grep -A3 unresolved $c/log.mergeCells)"; fi

    if command -v checkMesh >/dev/null 2>&1; then
        export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
        checkMesh -case $c >$c/log.checkMesh 2>&1
        if grep -q '^Mesh OK\.' $c/log.checkMesh; then
            pass ${c}_checkMesh "$(grep -h 'Max skewness' $c/log.checkMesh | sed 's/^ *//')"
        else
            fail ${c}_checkMesh "$(grep -E '^ *\*\*\*|Failed' $c/log.checkMesh | head -3)"
        fi
    else
        echo "SKIP ${c}_checkMesh: OpenFOAM's checkMesh is not installed (checkGrid's max skewness checked above)"
    fi
}

run sphereInBox
run discInBox

# a negative limit is refused with the dictionary's file and line
{ header mergeCellsDict; echo 'threshold 0.5;'; echo 'maxSkewness -2;'; } >discInBox/system/mergeCellsDict
msg=$("$BIN/mergeCells" -case discInBox -i discInBox/cut -o neg 2>&1)
st=$?
if [ $st -ne 0 ] && [[ $msg == *"system/mergeCellsDict:3: maxSkewness must be >= 0, found -2"* ]]; then
    pass negative_limit_refused; else fail negative_limit_refused "status $st: $msg"; fi
exit 0
