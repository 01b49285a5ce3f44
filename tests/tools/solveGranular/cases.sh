# tests/tools/solveGranular/cases.sh: grids and field readers the
# solveGranular tests share, sourced after tests/lib.sh (BIN set):
#     . "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/cases.sh"

H() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "${2:-dictionary}" "$1"; }

# grid DIR NX NY LX LY: the 2-D block grid [0,LX] x [0,LY], one cell thick
grid() {
    mkdir -p "$1/system" "$1/constant" "$1/0"
    { H blockGridDict
      echo "x { segments (($4 $2 1)); } y { segments (($5 $3 1)); } z { start -0.025; segments ((0.05 1 1)); }"
      echo 'boundary { xMin { name inlet; } xMax { name outlet; } yMin { name walls; type wall; } yMax { name walls; type wall; }'
      echo '  zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }'
    } >"$1/system/blockGridDict"
}

# rotbox DIR [voronoi]: the box 0.6 x 0.6 rotated 30 degrees in the unit square, cut and merged (or Voronoi)
rotbox() {
    grid "$1" 16 16 1 1
    { H geometryDict
      echo 'surfaces { box { type wall; flow inside; shape box; min (-0.3 -0.3 -1); max (0.3 0.3 1);'
      echo '  rotate { axis (0 0 1); angle 30; } translate (0.5 0.5 0); } }'
    } >"$1/system/geometryDict"
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1 || return 1
    if [ "${2:-}" = voronoi ]; then
        "$BIN/voronoiGrid" -case "$1" >"$1/log.voronoiGrid" 2>&1
    else
        "$BIN/cutCells" -case "$1" >"$1/log.cutCells" 2>&1 && "$BIN/mergeCells" -case "$1" >"$1/log.mergeCells" 2>&1
    fi
}

# maxfield DIR TIME FIELD: the largest |value - REF| over the cells (ascii
# fields); REF from $REF, "0 0 0" or "1" style, default 0
maxdev() {
    /usr/bin/python3 - "$1/$2/$3" "${4:-0}" <<'EOF'
import re, sys
t = open(sys.argv[1]).read()
ref = [float(v) for v in sys.argv[2].split()]
m = re.search(r'internalField\s+(uniform|nonuniform)\s+(?:List<\w+>\s*\d+\s*)?\((.*?)\)\s*;', t, re.S)
if m and m.group(1) == 'nonuniform':
    body = m.group(2)
    vals = [[float(x) for x in g.split()] for g in re.findall(r'\(([^()]*)\)', body)] if '(' in body \
        else [[float(x)] for x in body.split()]
else:
    u = re.search(r'internalField\s+uniform\s+\(?([^;()]*)\)?\s*;', t)
    vals = [[float(x) for x in u.group(1).split()]]
print('%.3e' % max(sum((a - b) ** 2 for a, b in zip(v, ref)) ** 0.5 for v in vals))
EOF
}
lasttime() { (cd "$1" && ls -d [0-9]* | sort -g | tail -n 1); }

