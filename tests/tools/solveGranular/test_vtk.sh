#!/usr/bin/env bash
# test_vtk.sh: solveGranular writes VTK at its write times (controlDict
# writeVTK, default yes; common/vtkcase.h, vtkcase_sync): VTK/ must hold
# exactly what writeVTK (default options) writes for the same time
# directories, compared with diff -r against writeVTK's conversion of a
# copy of the case (same directory name, so the same file names), so an
# extra, missing or stale file or a differing byte fails.  On the 20 x 4
# channel of test_solveGranular.sh (well-posed inflow and outflow, a
# density bump):
#   - vtk_like_writeVTK: to t = 0.5, writes every 0.125 (adjustableRunTime):
#     identical to writeVTK's; the series lists the 5 times 0 ... 0.5; the
#     log has one "VTK:" line per write and one at the start;
#   - vtk_off: writeVTK no: no VTK directory, no "VTK:" line;
#   - vtk_purge: purgeWrite 2: the times left are 0, 0.375, 0.5 and VTK/
#     is writeVTK's of them (the purged times' files gone, the series of 3);
#   - vtk_restart: a fixed-step run to 0.5 (deltaT 0.002, writes every 50
#     steps: indices 50 ... 250), then a restart from 0.2 with deltaT 0.001
#     and writes every 100 steps: the new 0.3 has index 200, the old 0.4's,
#     so for one write every time takes its position (vtkcase.h), then the
#     indices part again; at the end VTK/ is writeVTK's conversion of the
#     case (0.5 replaced: its file VTK/<case>_400.vtk), nothing stale left;
#   - vtk_atomic (strace): no .vtk or .vtk.series file is opened for
#     writing under its own name; each arrives by a rename of a temporary
#     file (io_write_atomic);
#   - vtk_help: -help lists writeVTK with its default.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/channel.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf sgv && mkdir sgv && cd sgv || exit 1

# chan DIR CONTROL: the channel with a density bump and those controlDict entries
chan() { channel_case "$1" "startFrom latestTime; startTime 0; stopAt endTime; $2" && channel_bump "$1"; }

# same_as_writeVTK DIR: empty when DIR/VTK equals writeVTK's conversion of
# a copy of DIR (same base name), else what differs
same_as_writeVTK() {
    rm -rf ref && mkdir ref && cp -r "$1" ref/ && rm -rf "ref/$1/VTK"
    "$BIN/writeVTK" -case "ref/$1" >"ref/log.writeVTK" 2>&1 || { echo "writeVTK failed"; return; }
    diff -r "$1/VTK" "ref/$1/VTK" 2>&1 | head -n 3 | tr '\n' ' '
}

# series DIR: "name:time" of each entry of DIR/VTK/DIR.vtk.series
series() { sed -n 's/.*"name" : "\([^"]*\)", "time" : \([^ ]*\) }.*/\1:\2/p' "$1/VTK/$1.vtk.series" 2>/dev/null | tr '\n' ' '; }

# ---- like writeVTK ----
c=vlike
chan $c 'endTime 0.5; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; writeInterval 0.125; writeFormat ascii; writePrecision 12;'
"$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
d=$(same_as_writeVTK $c); s=$(series $c); nv=$(grep -c '^VTK: ' $c/log)
times=$(series $c | tr ' ' '\n' | sed 's/.*://' | tr '\n' ' ')
if [ $rc -eq 0 ] && [ -z "$d" ] && [ "$times" = "0 0.125 0.25 0.375 0.5 " ] && [ "$nv" -eq 5 ]; then
    pass vtk_like_writeVTK "VTK/ identical to writeVTK's; series $s; $nv VTK lines"
else
    fail vtk_like_writeVTK "rc $rc, differs: '$d', series '$s', $nv VTK lines"
fi

# ---- off ----
c=voff
chan $c 'endTime 0.05; deltaT 0.001; writeControl timeStep; writeInterval 25; writeVTK no;'
"$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
if [ $rc -eq 0 ] && [ ! -e $c/VTK ] && ! grep -q '^VTK' $c/log && [ -s $c/0.05/rho ]; then
    pass vtk_off "writeVTK no: no VTK/"
else
    fail vtk_off "rc $rc, VTK/ $(ls -d $c/VTK 2>/dev/null)"
fi

# ---- purgeWrite ----
c=vpurge
chan $c 'endTime 0.5; deltaT 0.001; adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; writeInterval 0.125; purgeWrite 2; writeFormat ascii;'
"$BIN/solveGranular" -case $c >$c/log 2>&1; rc=$?
d=$(same_as_writeVTK $c); s=$(series $c)
left=$(cd $c && ls -d [0-9]* | sort -g | tr '\n' ' ')
nfiles=$(ls $c/VTK/*.vtk $c/VTK/*/*.vtk 2>/dev/null | wc -l)
if [ $rc -eq 0 ] && [ -z "$d" ] && [ "$left" = "0 0.375 0.5 " ] && [ "$(echo "$s" | wc -w)" -eq 3 ] &&
    [ "$nfiles" -eq 12 ] && grep -q 'removed 4 stale files' $c/log; then
    pass vtk_purge "times $left; VTK/ identical to writeVTK's ($nfiles files); series $s"
else
    fail vtk_purge "rc $rc, times $left, differs: '$d', series '$s', $nfiles files"
fi

# ---- restart with another step: renumbered ----
c=vrestart
chan $c 'endTime 0.5; deltaT 0.002; writeControl timeStep; writeInterval 50; writeFormat ascii; writePrecision 12;'
"$BIN/solveGranular" -case $c >$c/log1 2>&1; rc1=$?
s1=$(series $c)
sed -i 's/startFrom latestTime; startTime 0;/startFrom startTime; startTime 0.2;/; s/deltaT 0.002;/deltaT 0.001;/; s/writeInterval 50;/writeInterval 100;/' \
    $c/system/controlDict
"$BIN/solveGranular" -case $c >$c/log2 2>&1; rc2=$?
d=$(same_as_writeVTK $c); s=$(series $c)
if [ $rc1$rc2 = 00 ] && [ -z "$d" ] && [ "$s" = "vrestart_0.vtk:0 vrestart_50.vtk:0.1 vrestart_100.vtk:0.2 vrestart_200.vtk:0.3 vrestart_300.vtk:0.4 vrestart_400.vtk:0.5 " ] &&
    grep -q 'other times (missing or renumbered)' $c/log2; then
    pass vtk_restart "first run: $s1; after the restart: $s, identical to writeVTK's"
else
    fail vtk_restart "rc $rc1 $rc2, differs: '$d', series after the first run '$s1', after the restart '$s'"
fi

# ---- atomic ----
if ! command -v strace >/dev/null 2>&1 || ! strace -f -o /dev/null true 2>/dev/null; then
    skip vtk_atomic "strace is not installed or cannot trace here"
else
    c=vatomic
    chan $c 'endTime 0.02; deltaT 0.001; writeControl timeStep; writeInterval 10;'
    # (LeakSanitizer cannot run under ptrace: off for a SANITIZE=1 build)
    ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 \
        strace -f -o $c.trace -e trace=openat,open,creat,rename,renameat,renameat2 "$BIN/solveGranular" -case $c >$c/log 2>&1
    rc=$?
    direct=$(grep -E 'open(at)?\(.*\.vtk(\.series)?", O_[A-Z|]*(O_WRONLY|O_RDWR)' $c.trace | grep -v '\.tmp' | head -n 2)
    nren=$(grep -cE 'rename(at2?)?\(.*\.tmp[^"]*", .*\.vtk(\.series)?"' $c.trace)
    nvtk=$(ls $c/VTK/*.vtk $c/VTK/*/*.vtk $c/VTK/*.vtk.series $c/VTK/*/*.vtk.series 2>/dev/null | wc -l)
    # 3 times x 4 files + 4 series, the series rewritten at each of the 3 writes
    if [ $rc -eq 0 ] && [ -z "$direct" ] && [ "$nren" -eq $((3 * 4 + 3 * 4)) ] && [ "$nvtk" -eq 16 ]; then
        pass vtk_atomic "$nren renames of temporary files onto .vtk/.vtk.series, none written in place"
    else
        fail vtk_atomic "rc $rc, written in place: '$direct', $nren renames, $nvtk files"
    fi
fi

# ---- -help ----
if "$BIN/solveGranular" -help 2>&1 | grep -q 'writeVTK.*yes'; then
    pass vtk_help
else
    fail vtk_help "-help does not list writeVTK with its default"
fi
