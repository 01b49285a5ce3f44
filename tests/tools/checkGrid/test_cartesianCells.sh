#!/usr/bin/env bash
# test_cartesianCells.sh: the cut-cell data contract (constant/polyMesh/
# cartesianCells, doc/file-formats.md) as the tools write it, checked by
# checkGrid (mesh_check_cartesian: the roles partition the Cartesian grid,
# the parents' volumes add up to each cell's, tolerance 1e-12 of the
# Cartesian cells' volume).
#   sphere  analytic sphere r = 0.3, flow outside, 16^3 cells;
#   csg     tutorials/grids/csgPart's part (a plate and a boss minus a bore
#           and two bolt holes), 24^3 cells;
#   stl     tests/data/stl/sphere.stl.gz, flow outside, 16^3 cells;
# each: blockGrid, cutCells (whole, cut and outside only), mergeCells
# (masters and slaves), mergeCells again at threshold 0.9 from the merged
# grid through the stream form (it composes: more slaves, still a
# partition), checkGrid "Grid OK." after every step.
#   voronoi 2-D disc with one boundary layer: whole, cut and outside, no
#           masters or slaves, checkGrid OK.
# A test that can fail: one slave's role turned whole in the file, and one
# whole part's volume halved, must each make checkGrid fail, naming that
# Cartesian cell.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

# mkcase DIR N "geometry body" [flat]: a unit box of N^3 cells (flat: N^2 x 1, empty z)
mkcase() {
    mkdir -p $1/system
    local zn=$2 zt=1 zside=wall
    if [ -n "${4:-}" ]; then zn=1; zt=$(python3 -c "print(1/$2)"); zside=empty; fi
    { header blockGridDict
      echo "x { start 0; segments ((1 $2 1)); } y { start 0; segments ((1 $2 1)); }"
      echo "z { start 0; segments (($zt $zn 1)); }"
      echo "boundary { xMin { name walls; type wall; } xMax { name walls; type wall; }"
      echo "  yMin { name walls; type wall; } yMax { name walls; type wall; }"
      echo "  zMin { name fb; type $zside; } zMax { name fb; type $zside; } }"
    } >$1/system/blockGridDict
    { header geometryDict; echo "surfaces { $3 }"; } >$1/system/geometryDict
    { header controlDict; echo "application cutCells;"; } >$1/system/controlDict
}

# roles LOG: "outside whole cut master slave" from checkGrid's report
roles() {
    sed -n 's/.*Cartesian cells: [0-9]* (outside \([0-9]*\), whole \([0-9]*\), cut \([0-9]*\), master \([0-9]*\), slave \([0-9]*\)).*/\1 \2 \3 \4 \5/p' "$1"
}

checkgrid() { # case log [args]: 0 when "Grid OK."
    local c=$1 l=$2; shift 2
    "$BIN/checkGrid" -case $c "$@" >$l 2>&1 && grep -q 'Grid OK.' $l
}

cutmerge() { # name
    local c=$1 r
    if ! "$BIN/blockGrid" -case $c >$c.log 2>&1 || ! "$BIN/cutCells" -case $c >>$c.log 2>&1; then
        fail ${c}_cut "$(tail -3 $c.log)"; return
    fi
    if ! [ -f $c/constant/polyMesh/cartesianCells ]; then fail ${c}_cut "no cartesianCells"; return; fi
    if checkgrid $c $c.cut.chk; then
        read -r o w k m s <<<"$(roles $c.cut.chk)"
        if [ "${w:-0}" -gt 0 ] && [ "${k:-0}" -gt 0 ] && [ "${o:-0}" -gt 0 ] && [ "$m" = 0 ] && [ "$s" = 0 ]; then
            pass ${c}_cut
        else fail ${c}_cut "roles $o $w $k $m $s"; fi
    else fail ${c}_cut "$(grep -i 'cartesian\|fail' $c.cut.chk | head -3)"; fi
    if ! "$BIN/mergeCells" -case $c >>$c.log 2>&1; then fail ${c}_merge "$(tail -3 $c.log)"; return; fi
    if checkgrid $c $c.merge.chk; then
        read -r o w k m s <<<"$(roles $c.merge.chk)"
        if [ "${m:-0}" -gt 0 ] && [ "${s:-0}" -ge "$m" ]; then pass ${c}_merge
        else fail ${c}_merge "roles $o $w $k $m $s"; fi
    else fail ${c}_merge "$(grep -i 'cartesian\|fail' $c.merge.chk | head -3)"; fi
    local s1=$s
    # merging twice, through the stream form: threshold 0.9
    { header mergeCellsDict; echo "threshold 0.9;"; } >$c/system/merge2
    if "$BIN/mergeCells" -case $c -dict $c/system/merge2 -i $c/constant/polyMesh -o - 2>>$c.log |
        "$BIN/checkGrid" -case $c -i - >$c.merge2.chk 2>&1 && grep -q 'Grid OK.' $c.merge2.chk; then
        read -r o w k m s <<<"$(roles $c.merge2.chk)"
        if [ "${s:-0}" -gt "$s1" ]; then pass ${c}_merge_twice
        else fail ${c}_merge_twice "slaves $s1 then ${s:-none}"; fi
    else fail ${c}_merge_twice "$(tail -2 $c.log; grep -i 'cartesian\|fail' $c.merge2.chk | head -3)"; fi
}

mkcase sphere 16 "ball { type wall; flow outside; shape sphere; centre (0.5123 0.4871 0.5037); radius 0.3; }"
cutmerge sphere
mkcase csg 24 "part { type wall; flow outside; shape difference;
  body { shape union; plate { shape box; min (0.15 0.25 0.2); max (0.85 0.75 0.35); }
         boss { shape cylinder; point1 (0.5 0.5 0.2); point2 (0.5 0.5 0.75); radius 0.18; } }
  bore { shape cylinder; point1 (0.5 0.5 0.1); point2 (0.5 0.5 0.9); radius 0.09; }
  bolt1 { shape cylinder; point1 (0.25 0.5 0.1); point2 (0.25 0.5 0.5); radius 0.04; }
  bolt2 { shape cylinder; point1 (0.75 0.5 0.1); point2 (0.75 0.5 0.5); radius 0.04; } }"
cutmerge csg
mkcase stl 16 "ball { type wall; flow outside; shape stl; file \"$TOP/tests/data/stl/sphere.stl.gz\"; }"
cutmerge stl

# Voronoi: a disc in a 2-D box, one boundary layer
mkcase vor 24 "disc { type wall; flow outside; shape sphere; centre (0.5123 0.4871 0.02); radius 0.3; }" flat
{ header voronoiGridDict; echo "layers 1;"; } >vor/system/voronoiGridDict
if "$BIN/blockGrid" -case vor >vor.log 2>&1 && "$BIN/voronoiGrid" -case vor >>vor.log 2>&1 && checkgrid vor vor.chk; then
    read -r o w k m s <<<"$(roles vor.chk)"
    if [ "${w:-0}" -gt 0 ] && [ "${k:-0}" -gt 0 ] && [ "${o:-0}" -gt 0 ] && [ "$m" = 0 ] && [ "$s" = 0 ]; then
        pass voronoi
    else fail voronoi "roles $o $w $k $m $s"; fi
else fail voronoi "$(tail -3 vor.log; grep -i 'cartesian\|fail' vor.chk 2>/dev/null | head -3)"; fi

# corruption: the first slave (role 4) made whole (1); the first whole
# part's volume halved; checkGrid must fail and name the Cartesian cell
corrupt() { # name what(role|volume) expected-message-part
    rm -rf bad && cp -r sphere bad
    K=$(python3 - "$2" <<'EOF'
import re, sys
p = 'bad/constant/polyMesh/cartesianCells'
s = open(p).read()
def lst(key):
    m = re.search(r'\n' + key + r'\s+List<\w+>\s*\d+\s*\(\n(.*?)\n\)', s, re.S)
    return m, m.group(1).split('\n')
m, role = lst('role')
if sys.argv[1] == 'role':
    k = role.index('4'); role[k] = '1'
    s = s[:m.start(1)] + '\n'.join(role) + s[m.end(1):]
else:
    k = role.index('1')
    m2, vol = lst('volume')
    vol[k] = repr(float(vol[k]) / 2)
    s = s[:m2.start(1)] + '\n'.join(vol) + s[m2.end(1):]
open(p, 'w').write(s)
print(k)
EOF
)
    if checkgrid bad bad.chk; then fail $1 "checkGrid passed"
    elif grep -q "Cartesian cell $K (" bad.chk || grep -q "$3" bad.chk; then pass $1
    else fail $1 "K=$K: $(grep -i error bad.chk | head -2)"; fi
}
corrupt corrupt_role role "with 0 masters"
corrupt corrupt_volume volume "is whole but its volume"
