#!/usr/bin/env bash
# test_sampleLine.sh: sampleLine on a graded 2-D blockGrid case holding the
# linear fields T = 1 + 2x - 3y and U = (x, 2y, 0.5) at cell centres:
# linear interpolation reproduces them exactly inside, cell interpolation
# gives the containing cell's value, cells mode gives one row per cell with
# lengths summing to the line length, points outside are skipped, "-o -"
# streams the same CSV, -latestTime, and bad dictionaries fail with
# file:line.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
PY=/usr/bin/python3
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

mkdir -p c/system c/0
cat >c/system/blockGridDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockGridDict; }
x { start 0; segments ( (0.4 8 1) (1 12 2) ); }
y { start 0; segments ( (1 10 1) ); }
z { start 0; segments ( (0.1 1 1) ); }
boundary
{
    xMin { name left; type wall; }
    xMax { name right; type patch; }
    yMin { name bottom; type wall; }
    yMax { name top; type wall; }
    zMin { name frontAndBack; type empty; }
    zMax { name frontAndBack; type empty; }
}
EOF
if ! "$BIN/blockGrid" -case c >log.blockGrid 2>&1; then
    fail sampleLine_case "blockGrid failed: $(tail -n 3 log.blockGrid)"
    exit 0
fi

# Grid axes and the analytic fields, shared by the checks below.
cat >grid.py <<'EOF'
import re
def axes(case):
    t = open(case + "/constant/polyMesh/cartesianGrid").read()
    return [[float(v) for v in re.search(r'\n' + a + r'\s+(\d+)\s*\(([^)]*)\)', t).group(2).split()]
            for a in "xyz"]
def T(x, y, z, s=1): return s * (1 + 2 * x - 3 * y)
def U(x, y, z, s=1): return (s * x, s * 2 * y, s * 0.5)
def centres(case):
    X, Y, Z = axes(case)
    return [((X[i] + X[i+1]) / 2, (Y[j] + Y[j+1]) / 2, (Z[k] + Z[k+1]) / 2)
            for k in range(len(Z) - 1) for j in range(len(Y) - 1) for i in range(len(X) - 1)]
def cell_centre(case, p):
    # the lowest numbered cell within sampleLine's tolerance (1e-9 of the
    # cell size) of p: the first index along each axis
    out = []
    for a, v in zip(axes(case), p):
        i = next(i for i in range(len(a) - 1) if v <= a[i+1] + 1e-9 * (a[i+1] - a[i]) or i == len(a) - 2)
        out.append((a[i] + a[i+1]) / 2)
    return out
def write_fields(case, time, s):
    C = centres(case)
    hdr = 'FoamFile { version 2.0; format ascii; class %s; object %s; }\ndimensions [0 0 0 0 0 0 0];\n'
    with open("%s/%s/T" % (case, time), "w") as f:
        f.write(hdr % ("volScalarField", "T"))
        f.write("internalField nonuniform List<scalar>\n%d\n(\n" % len(C))
        f.write("\n".join(repr(T(*c, s=s)) for c in C))
        f.write("\n);\nboundaryField { \".*\" { type zeroGradient; } frontAndBack { type empty; } }\n")
    with open("%s/%s/U" % (case, time), "w") as f:
        f.write(hdr % ("volVectorField", "U"))
        f.write("internalField nonuniform List<vector>\n%d\n(\n" % len(C))
        f.write("\n".join("(%r %r %r)" % U(*c, s=s) for c in C))
        f.write("\n);\nboundaryField { \".*\" { type zeroGradient; } frontAndBack { type empty; } }\n")
def read_csv(path):
    lines = [l for l in open(path).read().splitlines() if not l.startswith("#")]
    return lines[0].split(","), [[float(v) for v in l.split(",")] for l in lines[1:]]
EOF
$PY -c "import sys; sys.path.insert(0, '.'); import grid; grid.write_fields('c', '0', 1)"

cat >c/system/sampleLineDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object sampleLineDict; }
fields (T U);
interpolation linear;
lines
{
    inner   { start (0.2 0.35 0.05); end (0.8 0.65 0.05); nPoints 13; }
    column  { start (0.5 0 0.05); end (0.5 1 0.05); mode cells; }
    outside { start (-0.5 0.5 0.05); end (1 0.5 0.05); nPoints 16; }
}
EOF
"$BIN/sampleLine" -case c >log1 2>&1; rc=$?
check sampleLine_runs test $rc -eq 0
out=c/postProcessing/sampleLine/0
check sampleLine_files test -f $out/inner.csv -a -f $out/column.csv -a -f $out/outside.csv
check sampleLine_header test "$(head -n 1 $out/inner.csv)" = "distance,x,y,z,T,U_x,U_y,U_z"
check sampleLine_header_cells test "$(head -n 1 $out/column.csv)" = "distance,x,y,z,T,U_x,U_y,U_z,length"

# linear interpolation: exact for the linear fields inside (cells away
# from the zeroGradient walls)
err=$($PY - $out/inner.csv <<'EOF'
import sys, math; sys.path.insert(0, '.'); import grid
h, rows = grid.read_csv(sys.argv[1])
e = 0 if len(rows) == 13 else 1
for r in rows:
    d, x, y, z = r[:4]
    e = max(e, abs(d - math.hypot(x - 0.2, y - 0.35)), abs(r[4] - grid.T(x, y, z)))
    e = max([e] + [abs(a - b) for a, b in zip(r[5:8], grid.U(x, y, z))])
print("%.3g" % e)
EOF
)
echo "  linear interpolation, max error on 13 points: $err"
check sampleLine_linear_exact $PY -c "import sys; sys.exit(0 if float('$err') < 1e-12 else 1)"

# cells mode: 10 rows, lengths sum to 1, distances at the cell centres,
# values of the linear field at the midpoints
res=$($PY - $out/column.csv <<'EOF'
import sys; sys.path.insert(0, '.'); import grid
h, rows = grid.read_csv(sys.argv[1])
Y = grid.axes("c")[1]
ok = len(rows) == 10
ok = ok and abs(sum(r[8] for r in rows) - 1) < 1e-12
ok = ok and all(abs(r[0] - (Y[j] + Y[j+1]) / 2) < 1e-12 and abs(r[8] - (Y[j+1] - Y[j])) < 1e-12 for j, r in enumerate(rows))
ok = ok and all(abs(r[4] - grid.T(0.5, r[2], 0)) < 1e-12 for r in rows)
print("ok" if ok else "bad: %d rows, %r" % (len(rows), rows[:2]))
EOF
)
check sampleLine_cells_mode test "$res" = ok

# outside points: x = -0.5 + 0.1 i, i = 0..4 outside
check sampleLine_outside_rows test "$(($(wc -l <$out/outside.csv) - 1))" -eq 11
grep -q 'outside: 5 points outside the mesh skipped' log1
check sampleLine_outside_reported test $? -eq 0

# cell interpolation: the value of the containing cell
sed 's/interpolation linear;/interpolation cell;/' c/system/sampleLineDict >cell.dict
"$BIN/sampleLine" -case c -dict cell.dict -o cellout >log2 2>&1
res=$($PY - cellout/0/inner.csv <<'EOF'
import sys; sys.path.insert(0, '.'); import grid
h, rows = grid.read_csv(sys.argv[1])
e = 0
for r in rows:
    c = grid.cell_centre("c", r[1:4])
    e = max(e, abs(r[4] - grid.T(*c)), abs(r[5] - c[0]), abs(r[6] - 2 * c[1]))
print("ok" if e < 1e-13 and len(rows) == 13 else "bad %g" % e)
EOF
)
check sampleLine_cell_values test "$res" = ok

# -o -: the same CSV on stdout, banner on stderr
"$BIN/sampleLine" -case c -o - -line inner >stream.csv 2>stream.err; rc=$?
check sampleLine_stream test $rc -eq 0
check sampleLine_stream_same cmp -s stream.csv $out/inner.csv
grep -q 'sampleLine' stream.err
check sampleLine_stream_banner_stderr test $? -eq 0
"$BIN/sampleLine" -case c -o - >all.csv 2>/dev/null
check sampleLine_stream_blocks test "$(grep -c '^# time 0 line ' all.csv)" -eq 3

# -latestTime: only the newest time, with its own values (doubled fields)
mkdir -p c/0.5
$PY -c "import sys; sys.path.insert(0, '.'); import grid; grid.write_fields('c', '0.5', 2)"
rm -rf c/postProcessing
"$BIN/sampleLine" -case c -latestTime -line inner >log3 2>&1
res=$($PY - c/postProcessing/sampleLine/0.5/inner.csv <<'EOF'
import sys; sys.path.insert(0, '.'); import grid
h, rows = grid.read_csv(sys.argv[1])
print("ok" if all(abs(r[4] - grid.T(*r[1:4], s=2)) < 1e-12 for r in rows) else "bad")
EOF
)
check sampleLine_latest_time test "$res" = ok
check sampleLine_latest_only test ! -e c/postProcessing/sampleLine/0

# cells mode against OpenFOAM's midPoint set (when installed): OpenFOAM
# samples the crossings between two face intersections, i.e. all but the
# first and last of ours, at the same distances with the same cell values
# (it then adds one sample of its own near the end point, not compared)
ofpp=$(type -a -p postProcess 2>/dev/null | head -n 1)
if [ -n "$ofpp" ] && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} "$ofpp" -help 2>&1 | grep -q decomposeParDict; then
    mkdir -p of/system
    cp -r c/constant c/0 of/
    cat >of/system/controlDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application postProcess; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeControl timeStep; writeInterval 1; writeFormat ascii; writePrecision 15;
EOF
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\nddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\ndivSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\ninterpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n' >of/system/fvSchemes
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n' >of/system/fvSolution
    cat >of/system/sampleLine <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object sampleLine; }
type sets; libs ("libsampling.so"); interpolationScheme cell; setFormat raw; fields (T);
sets ( diag { type midPoint; axis distance; start (0.01 0.02 0.05); end (0.97 0.93 0.05); } );
EOF
    cat >of/system/sampleLineDict <<'EOF'
fields (T);
lines { diag { start (0.01 0.02 0.05); end (0.97 0.93 0.05); mode cells; } }
EOF
    (export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}; cd of && timeout 120 "$ofpp" -func sampleLine -time 0 >log.openfoam 2>&1)
    "$BIN/sampleLine" -case of -time 0 -o kiesel >log.of 2>&1
    res=$($PY - <<'EOF'
import sys; sys.path.insert(0, '.'); import grid
try:
    ref = [[float(v) for v in l.split()] for l in open("of/postProcessing/sampleLine/0/diag_T.xy") if l.strip()]
    h, rows = grid.read_csv("kiesel/0/diag.csv")
    inner = rows[1:-1]
    ok = len(ref) == len(inner) + 1 and len(inner) > 20 and all(abs(a[0] - b[0]) < 1e-12 and abs(a[1] - b[4]) < 1e-12 for a, b in zip(ref, inner))
    print("ok" if ok else "OpenFOAM %d rows, ours %d inner: %r / %r" % (len(ref), len(inner), ref[:2], inner[:2]))
except Exception as e:
    print("unreadable: %s" % e)
EOF
)
    check sampleLine_cells_match_openfoam_midpoint test "$res" = ok
else
    echo "SKIP sampleLine_cells_match_openfoam_midpoint: OpenFOAM's postProcess not installed"
fi

# bad input: file:line message and exit 1
bad() { # name expected-regex dict-text [extra args]
    printf '%s\n' "$3" >bad.dict
    local out rc
    out=$("$BIN/sampleLine" -case c -dict bad.dict -latestTime ${4:-} 2>&1 >/dev/null); rc=$?
    if [ $rc -ne 0 ] && grep -Eq "$2" <<<"$out"; then pass "$1"; else fail "$1" "rc=$rc, stderr: $(head -n 2 <<<"$out")"; fi
}
bad sampleLine_bad_keyword "bad.dict:2: unknown keyword 'nPoint'.*did you mean 'nPoints'\?" \
'fields (T);
lines { a { start (0 0 0); end (1 1 0); nPoint 3; } }'
bad sampleLine_bad_interpolation "bad.dict:1: .*interpolation.*(cell|linear)" \
'interpolation cubic; fields (T); lines { a { start (0 0 0); end (1 1 0); } }'
bad sampleLine_missing_field "bad.dict:1: field 'p' not found at time 0.5" \
'fields (T p);
lines { a { start (0 0 0); end (1 1 0); } }'
bad sampleLine_missing_start "bad.dict:[0-9]+: .*start" \
'fields (T);
lines { a { end (1 1 0); } }'
bad sampleLine_bad_mode "bad.dict:2: .*mode.*(uniform|cells)" \
'fields (T);
lines { a { start (0 0 0); end (1 1 0); mode cell; } }'
bad sampleLine_bad_npoints "bad.dict:2: line 'a': nPoints must be between 1 and 10000000, found 0" \
'fields (T);
lines { a { start (0 0 0); end (1 1 0); nPoints 0; } }'
bad sampleLine_bad_line_option "no line 'inne' in the dictionary; did you mean 'inner'\?" \
'fields (T); lines { inner { start (0 0 0); end (1 1 0); } }' "-line inne"

out=$("$BIN/sampleLine" -help 2>&1)
grep -q 'interpolation' <<<"$out" && grep -q 'nPoints' <<<"$out"
check sampleLine_help test $? -eq 0
