#!/usr/bin/env bash
# test_shells.sh: STL files holding several closed shells (boxes), cut end
# to end by blockGrid and cutCells (flow outside the solid) on a 20^3 grid
# of the unit cube.  Each case is cut twice:
#   - on grid planes: every face of the shells lies on a grid plane, cells
#     are kept or dropped whole, and the fluid volume must be exact to
#     1e-9;
#   - moved by 0.01 along x: the x faces cut cells; the fluid volume must
#     be within 1e-3 of exact and of the cut of the same solid written as
#     a CSG of analytic boxes (the cutter's own error at box edges is
#     about 1e-4; the mistakes tested for are 0.025 and more).
# Cases (A = [0.2, 0.6]^3, B = [0.3, 0.7]^3, O = [0.1, 0.9]^3 on planes):
#   - A and B outward: the solid is their union, 0.4^3 + 0.4^3 - 0.3^3 =
#     0.101, fluid 0.899 (it was their XOR, fluid 0.926: B's probe point
#     lay in A and B was taken for a cavity);
#   - the same with one triangle of B reversed (orientation repaired);
#   - O outward with B inward inside it: a cavity, kept; solid 0.512 -
#     0.064, fluid 0.552;
#   - O and B both outward: B is repaired into a cavity, fluid 0.552.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

# DIR/shells.stl (ascii) from "lo hi dir [flip]" lines on stdin: the box
# [lo + dx, hi + dx] x [lo, hi]^2, outward (dir 1) or inward (-1), with its
# triangle number `flip` reversed
stl() { # dir, dx
    /usr/bin/python3 -c '
import sys
dx = float(sys.argv[2])
out = ["solid shells"]
for line in sys.stdin:
    w = line.split()
    if not w:
        continue
    lo, hi, d = float(w[0]), float(w[1]), int(w[2])
    flip = int(w[3]) if len(w) > 3 else -1
    tris = []
    for a in range(3):
        for side in (0, 1):
            u, v = (a + 1) % 3, (a + 2) % 3
            q = []
            for k in ([0, 1, 2, 3] if side else [3, 2, 1, 0]):
                c = [0] * 3
                c[a] = side
                c[u] = 1 if k in (1, 2) else 0
                c[v] = 1 if k in (2, 3) else 0
                q.append([(hi if c[0] else lo) + dx] + [hi if b else lo for b in c[1:]])
            tris += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    for i, t in enumerate(tris):
        if (d < 0) != (i == flip):
            t = [t[0], t[2], t[1]]
        out.append("facet normal 0 0 0\nouter loop")
        out += ["vertex %r %r %r" % tuple(p) for p in t]
        out.append("endloop\nendfacet")
out.append("endsolid shells")
open(sys.argv[1], "w").write("\n".join(out) + "\n")
' "$1/shells.stl" "$2"
}

mkcase() { # dir, surface entry
    rm -rf "$1"
    mkdir -p "$1/system"
    { header blockGridDict
      for a in x y z; do echo "$a { segments ((1 20 1)); }"; done
      echo "boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; }"
      echo "           zMin { name walls; } zMax { name walls; } }"
    } >"$1/system/blockGridDict"
    { header geometryDict; echo "surfaces { part { $2 } }"; } >"$1/system/geometryDict"
}

box() { # name lo hi dx
    awk -v n="$1" -v lo="$2" -v hi="$3" -v dx="$4" \
        'BEGIN { printf "%s { shape box; min (%.17g %s %s); max (%.17g %s %s); }", n, lo + dx, lo, lo, hi + dx, hi, hi }'
}


cut() { # dir: prints the fluid volume, nothing when a tool fails
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1 && "$BIN/cutCells" -case "$1" >"$1/log.cutCells" 2>&1 &&
        fluid "$1/log.cutCells"
}

near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

check() { # name, exact fluid volume, what, CSG operation, operand names and boxes, shells
    local name=$1 ex=$2 what=$3 op=$4 n1=$5 b1=$6 n2=$7 b2=$8 shells=$9 v c
    mkcase "$name" 'shape stl; file "shells.stl";'
    printf '%s\n' "$shells" | stl "$name" 0
    v=$(cut "$name")
    if [ -n "$v" ] && near "$v" "$ex" 1e-9; then
        pass "$name" "$what on grid planes: fluid $v, exact $ex"
    else
        fail "$name" "$what on grid planes: fluid '$v', exact $ex (tolerance 1e-9) $(tail -q -n 1 "$name"/log.* | tr '\n' ' ')"
    fi
    mkcase "${name}_moved" 'shape stl; file "shells.stl";'
    printf '%s\n' "$shells" | stl "${name}_moved" 0.01
    # shellcheck disable=SC2086
    mkcase "${name}_csg" "shape $op; $(box "$n1" $b1 0.01) $(box "$n2" $b2 0.01)"
    v=$(cut "${name}_moved")
    c=$(cut "${name}_csg")
    if [ -n "$v" ] && [ -n "$c" ] && near "$v" "$ex" 1e-3 && near "$v" "$c" 1e-3; then
        pass "${name}_moved" "$what off grid planes: fluid $v, CSG $c, exact $ex"
    else
        fail "${name}_moved" "$what off grid planes: fluid '$v', CSG '$c', exact $ex (tolerance 1e-3)"
    fi
}

A='0.2 0.6'
B='0.3 0.7'
O='0.1 0.9'
check cutCells_shells_union 0.899 "overlapping outward cubes" union a "$A" b "$B" "$A 1
$B 1"
check cutCells_shells_union_repaired 0.899 "overlapping cubes, a triangle reversed" union a "$A" b "$B" "$A 1
$B 1 5"
check cutCells_shells_cavity 0.552 "inward cube in a cube" difference o "$O" c "$B" "$O 1
$B -1"
check cutCells_shells_cavity_repaired 0.552 "outward cube in a cube" difference o "$O" c "$B" "$O 1
$B 1"
