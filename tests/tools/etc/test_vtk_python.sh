#!/usr/bin/env bash
# test_vtk_python.sh: the tests find VTK's reader where ParaView provides it.
# A python3 without a vtk module is made by a PYTHONPATH entry whose vtk.py
# raises ImportError; a stand-in `pvpython` on PATH runs /usr/bin/python3
# (with its real VTK) and logs each call.  Then
#   - tests/vtkpython.py chooses pvpython when python3 has no VTK,
#     python3 when it has, python3 when neither (the checks then SKIP);
#   - tests/vtk_cells_volume.py run by the VTK-less python3 runs itself
#     under pvpython: a 3-D 4 x 4 x 1 grid of volume 0.1 gives 16 cells and
#     volume 0.1 within 1e-12;
#   - tests/tutorials/gridcheck.py's vtk_reader check, from the VTK-less
#     python3, reads the 2-D grid's file through pvpython and passes (16 cells, sum of
#     areas x thickness = 0.1 within 1e-12).
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

PY=/usr/bin/python3

if ! $PY -c 'import vtk' 2>/dev/null; then
    for n in choose_python vtk_cells_volume_via_pvpython gridcheck_via_pvpython; do
        echo "SKIP $n: /usr/bin/python3 has no VTK module to stand in for ParaView's"
    done
    exit 0
fi

mkdir -p blocker fake
echo 'raise ImportError("no VTK in this python (test blocker)")' >blocker/vtk.py
cat >fake/pvpython <<EOF
#!/bin/sh
echo "\$@" >> "$PWD/pvpython.log"
unset PYTHONPATH
exec $PY "\$@"
EOF
chmod +x fake/pvpython
export PYTHONDONTWRITEBYTECODE=1
unset KIESEL_PYTHON KIESEL_VTK_REEXEC

# ---- the choice --------------------------------------------------------------
with_pv=$(PYTHONPATH=$PWD/blocker PATH="$PWD/fake:$PATH" $PY "$TOP/tests/vtkpython.py")
with_vtk=$(PATH="$PWD/fake:$PATH" $PY "$TOP/tests/vtkpython.py")
neither=$(PYTHONPATH=$PWD/blocker PATH=/usr/bin:/bin $PY "$TOP/tests/vtkpython.py")
if [ "$with_pv" = "$PWD/fake/pvpython" ] && [ "$with_vtk" = "$PY" ] && [ "$neither" = "$PY" ]; then
    pass choose_python "no VTK in python3: pvpython; VTK in python3: python3; neither: python3"
else
    fail choose_python "no VTK: '$with_pv' (want pvpython), VTK: '$with_vtk', neither: '$neither' (want $PY)"
fi

# ---- grids of 16 cells, volume 0.1, as VTK: g 2-D (polygons), h 3-D ---------------
mkdir -p g/system
cat >g/system/blockGridDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockGridDict; }
x { segments ((1 4 1)); }
y { segments ((1 4 1)); }
z { segments ((0.1 1 1)); }
boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; }
  zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }
EOF
mkdir -p h/system
sed 's/type empty;//g' g/system/blockGridDict >h/system/blockGridDict
for c in g h; do
    "$BIN/blockGrid" -case $c >$c.log 2>&1 && "$BIN/writeVTK" -case $c >>$c.log 2>&1 ||
        fail setup "blockGrid/writeVTK on $c: $(tail -n 3 $c.log)"
done

# ---- vtk_cells_volume.py ---------------------------------------------------------
rm -f pvpython.log
out=$(PYTHONPATH=$PWD/blocker PATH="$PWD/fake:$PATH" $PY "$TOP/tests/vtk_cells_volume.py" h/VTK/h_0.vtk 0.1 2>&1)
read -r n vol err <<<"$out"
if [ "$n" = 16 ] && awk -v e="$err" 'BEGIN { exit !(e <= 1e-12) }' && grep -q vtk_cells_volume pvpython.log 2>/dev/null; then
    pass vtk_cells_volume_via_pvpython "16 cells, volume $vol (error $err) read by pvpython"
else
    fail vtk_cells_volume_via_pvpython "output '$out', pvpython calls: $(cat pvpython.log 2>/dev/null)"
fi

# ---- gridcheck.py ------------------------------------------------------------------
rm -f pvpython.log
out=$(PYTHONPATH="$PWD/blocker:$TOP/tests/tutorials" PATH="$PWD/fake:$PATH" $PY - <<'EOF' 2>&1
from gridcheck import Check
Check("t", "g", "g").vtk_reader(16, 0.1, 0.1, "blockGrid")
EOF
)
if grep -q '^PASS t_g_vtk_reader: 16 cells' <<<"$out" && grep -q gridcheck pvpython.log 2>/dev/null; then
    pass gridcheck_via_pvpython "$(sed 's/^PASS t_g_vtk_reader: //' <<<"$out")"
else
    fail gridcheck_via_pvpython "output '$out', pvpython calls: $(cat pvpython.log 2>/dev/null)"
fi
