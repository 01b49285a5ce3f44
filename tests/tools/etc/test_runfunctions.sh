#!/usr/bin/env bash
# Tests of etc/RunFunctions, etc/CleanFunctions and etc/bashrc.
#
# Each check runs in its own case directory under the scratch cwd with small
# shell scripts standing in for tools, so the tests need no built tool except
# getApplication's dictQuery (SKIP when it is not built yet).
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
bin=${KIESEL_BIN:-$top/bin}
scratch=$PWD

# A fake application: prints to stdout and stderr, counts its runs in
# ./runs, exits with the status given as first argument.
mkdir -p "$scratch/fakebin"
cat > "$scratch/fakebin/fakeApp" <<'EOF'
#!/bin/sh
echo "out: $*"
echo "err: $*" 1>&2
echo x >> runs
exit "${1:-0}"
EOF
chmod +x "$scratch/fakebin/fakeApp"
export PATH="$scratch/fakebin:$PATH"

newcase() {   # newcase NAME: fresh empty case directory, cd into it
    rm -rf "${scratch:?}/${1:?}" && mkdir -p "$scratch/$1" && cd "$scratch/$1" || exit 1
}
nruns() { if [ -f runs ]; then wc -l < runs | tr -d ' '; else echo 0; fi; }

# shellcheck source=/dev/null
. "$top/etc/RunFunctions"
# shellcheck source=/dev/null
. "$top/etc/CleanFunctions"

# --- runApplication --------------------------------------------------------

newcase log
msg=$(runApplication fakeApp 0 hello); rc=$?
if [ "$rc" -ne 0 ]; then
    fail runApplication_log "status $rc, expected 0"
elif [ "$msg" != "Running fakeApp on $PWD" ]; then
    fail runApplication_log "printed '$msg'"
elif [ "$(cat log.fakeApp 2>/dev/null)" != "$(printf 'out: 0 hello\nerr: 0 hello')" ]; then
    fail runApplication_log "log.fakeApp holds '$(cat log.fakeApp 2>/dev/null)'"
else
    pass runApplication_log
fi

# Second run without -o/-a: refused, the app does not run, the log is kept.
before=$(cat log.fakeApp)
msg=$(runApplication fakeApp 0 again); rc=$?
expect="fakeApp already run on $PWD: remove log file 'log.fakeApp' to re-run"
if [ "$msg" != "$expect" ]; then
    fail runApplication_refuses "printed '$msg'"
elif [ "$(nruns)" -ne 1 ]; then
    fail runApplication_refuses "the app ran $(nruns) times, expected 1"
elif [ "$(cat log.fakeApp)" != "$before" ]; then
    fail runApplication_refuses "the log changed"
elif [ "$rc" -ne 0 ]; then
    fail runApplication_refuses "status $rc, expected 0 (as OpenFOAM)"
else
    pass runApplication_refuses
fi

runApplication -o fakeApp 0 third > /dev/null; rc=$?
if [ "$rc" -ne 0 ] || [ "$(nruns)" -ne 2 ] || [ "$(head -n 1 log.fakeApp)" != "out: 0 third" ] \
    || [ "$(wc -l < log.fakeApp)" -ne 2 ]; then
    fail runApplication_overwrite "rc=$rc runs=$(nruns) log='$(cat log.fakeApp)'"
else
    pass runApplication_overwrite
fi

runApplication -append fakeApp 0 fourth > /dev/null; rc=$?
if [ "$rc" -ne 0 ] || [ "$(nruns)" -ne 3 ] || [ "$(wc -l < log.fakeApp)" -ne 4 ] \
    || [ "$(sed -n 3p log.fakeApp)" != "out: 0 fourth" ]; then
    fail runApplication_append "rc=$rc runs=$(nruns) log='$(cat log.fakeApp)'"
else
    pass runApplication_append
fi

runApplication -s second fakeApp 0 > /dev/null; rc=$?
if [ "$rc" -ne 0 ] || [ ! -f log.fakeApp.second ] || [ "$(nruns)" -ne 4 ]; then
    fail runApplication_suffix "rc=$rc, log.fakeApp.second $( [ -f log.fakeApp.second ] && echo exists || echo missing)"
else
    pass runApplication_suffix
fi

# The app's exit status comes back, also through a path and with options.
newcase status
runApplication "$scratch/fakebin/fakeApp" 3 > /dev/null 2> err.txt; rc=$?
if [ "$rc" -ne 3 ]; then
    fail runApplication_status "status $rc, expected 3"
elif [ ! -f log.fakeApp ]; then
    fail runApplication_status "no log.fakeApp for an app given by path"
elif ! grep -q 'fakeApp failed (exit status 3)' err.txt; then
    fail runApplication_status "no failure note on stderr: '$(cat err.txt)'"
else
    pass runApplication_status
fi
runApplication -o fakeApp 0 > /dev/null; rc0=$?
runApplication -o -s x fakeApp 7 > /dev/null 2>&1; rc7=$?
if [ "$rc0" -ne 0 ] || [ "$rc7" -ne 7 ]; then
    fail runApplication_status_options "statuses $rc0 and $rc7, expected 0 and 7"
else
    pass runApplication_status_options
fi
# Under set -e an Allrun stops at the failing step.
out=$(bash -c ". '$top/etc/RunFunctions'; set -e; runApplication -o fakeApp 4; echo after" 2>/dev/null); rc=$?
if [ "$rc" -ne 4 ] || [ "${out##*$'\n'}" = after ]; then
    fail runApplication_set_e "status $rc, output '$out'"
else
    pass runApplication_set_e
fi

# A missing application: non-zero status, the log says why.
runApplication noSuchKieselApp > /dev/null 2>&1; rc=$?
if [ "$rc" -eq 0 ] || ! grep -q 'noSuchKieselApp' log.noSuchKieselApp 2>/dev/null; then
    fail runApplication_missing_app "status $rc"
else
    pass runApplication_missing_app
fi
runApplication -s > /dev/null 2>&1; rc=$?
if [ "$rc" -ne 2 ]; then fail runApplication_usage "status $rc, expected 2"; else pass runApplication_usage; fi

# --- restore0Dir, cloneCase -------------------------------------------------

newcase restore
mkdir -p 0.orig 0
echo pristine > 0.orig/alpha.s
echo modified > 0/alpha.s
echo stale > 0/extra
restore0Dir > /dev/null
if [ "$(cat 0/alpha.s)" != pristine ] || [ -e 0/extra ] || [ "$(cat 0.orig/alpha.s)" != pristine ]; then
    fail restore0Dir "0/: $(ls 0)"
else
    pass restore0Dir
fi

newcase clone
mkdir -p src/0 src/0.orig src/constant/polyMesh src/system
echo a > src/system/controlDict
echo b > src/constant/polyMesh/points
touch src/log.blockGrid
cloneCase src dst > /dev/null; rc=$?
if [ "$rc" -ne 0 ] || [ ! -f dst/system/controlDict ] || [ ! -f dst/constant/polyMesh/points ] \
    || [ ! -d dst/0.orig ] || [ -e dst/log.blockGrid ]; then
    fail cloneCase "rc=$rc, dst: $(cd dst 2>/dev/null && find . | sort | tr '\n' ' ')"
else
    cloneCase src dst > /dev/null 2>&1; rc=$?
    if [ "$rc" -eq 0 ]; then fail cloneCase "cloning onto an existing case succeeded"; else pass cloneCase; fi
fi

# --- cleanCase and friends --------------------------------------------------

mkcase() {   # a case with everything cleanCase knows about, plus user files
    newcase "$1"
    mkdir -p -- 0 0.orig 0.5 1e-05 100 -1 system constant/polyMesh postProcessing/sampleLine/0 \
        VTK processor0/0 processor1 dynamicCode notes 0.orig.bak
    touch -- 0/U 0.orig/U 0.5/U 100/U system/controlDict system/blockGridDict \
        constant/polyMesh/points constant/granularProperties log.blockGrid log.setFields \
        Allrun README notes/x VTK/a.vtk "logbook"
}
listing() { find . -mindepth 1 | LC_ALL=C sort | tr '\n' ' '; }

mkcase clean
cleanCase
got=$(listing)
want="./0 ./0.orig ./0.orig.bak ./0.orig/U ./0/U ./Allrun ./README ./constant ./constant/granularProperties ./logbook ./notes ./notes/x ./system ./system/blockGridDict ./system/controlDict "
if [ "$got" = "$want" ]; then pass cleanCase; else fail cleanCase "left '$got', expected '$want'"; fi

# Without a grid dictionary constant/polyMesh is user data and stays.
mkcase clean_keep_mesh
rm system/blockGridDict
cleanCase
if [ -f constant/polyMesh/points ]; then pass cleanCase_keeps_mesh; else fail cleanCase_keeps_mesh "constant/polyMesh removed"; fi

# constant/ that held only the generated grid goes with it.
newcase clean_empty_constant
mkdir -p system constant/polyMesh && touch system/blockGridDict constant/polyMesh/points
cleanCase
if [ ! -e constant ] && [ -f system/blockGridDict ]; then
    pass cleanCase_empty_constant
else
    fail cleanCase_empty_constant "left $(listing)"
fi

mkcase clean_times
cleanTimeDirectories
got=$(find . -mindepth 1 -maxdepth 1 -type d | sed "s|^\./||; s|$|/|" | LC_ALL=C sort | tr "\n" " ")
want="0.orig.bak/ 0.orig/ 0/ VTK/ constant/ dynamicCode/ notes/ postProcessing/ processor0/ processor1/ system/ "
if [ "$got" = "$want" ]; then pass cleanTimeDirectories; else fail cleanTimeDirectories "left '$got'"; fi

mkcase clean0
cleanCase0
if [ -e 0 ] || [ ! -f 0.orig/U ] || [ ! -f system/controlDict ]; then
    fail cleanCase0 "left $(listing)"
else
    rm -rf 0.orig && mkdir 0 && touch 0/U
    cleanCase0 2> err.txt
    if [ -f 0/U ] && grep -q 'keeping 0/' err.txt; then pass cleanCase0; else fail cleanCase0 "removed 0/ without 0.orig/"; fi
fi

# --- getApplication -----------------------------------------------------------

newcase getapp
mkdir system
cat > system/controlDict <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application     solveGranular;   // the solver
endTime 1;
EOF
if [ -x "$bin/dictQuery" ]; then
    app=$(PATH="$bin:$PATH" getApplication 2>&1)
    if [ "$app" = solveGranular ]; then pass getApplication; else fail getApplication "printed '$app'"; fi
else
    echo "SKIP getApplication: $bin/dictQuery is not built"
fi

# --- etc/bashrc ----------------------------------------------------------------

# Sourced from an unrelated directory through a relative path with "..".
newcase bashrc
rel=$(python3 -c 'import os,sys; print(os.path.relpath(sys.argv[1]))' "$top/etc/bashrc" 2>/dev/null || echo "$top/etc/bashrc")
out=$(cd "$scratch/bashrc" && env -u KIESEL_BIN -u KIESEL_DIR PATH=/usr/bin:/bin bash -c ". '$rel'; . '$rel'; echo \"\$KIESEL_DIR\"; echo \"\$PATH\"")
dir=$(sed -n 1p <<<"$out"); path=$(sed -n 2p <<<"$out")
real_top=$(cd "$top" && pwd -P)
count=$(tr ':' '\n' <<<"$path" | grep -cx "$real_top/bin")
if [ "$dir" != "$real_top" ]; then
    fail bashrc "KIESEL_DIR='$dir', expected '$real_top'"
elif [ "${path%%:*}" != "$real_top/bin" ] || [ "$count" -ne 1 ]; then
    fail bashrc "PATH starts '${path%%:*}', bin/ appears $count times"
else
    pass bashrc
fi
