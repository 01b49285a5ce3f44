#!/usr/bin/env bash
# test_commit.sh: the grid on disk survives faults of the run that replaces it.
#   - kill during the replace: blockGrid replaces grid A (4x4) by grid B
#     (6x5) under strace, which kills it (SIGKILL) at the N-th rename, for
#     every N that a normal run reaches (the 7 files' renames in the
#     temporary directory, the rename onto the grid, the exchange), and at
#     the first removal after the last rename (the old grid's); after
#     each kill constant/polyMesh is byte for byte A or B, and the next
#     tool run (checkGrid) removes what was left, says so on stderr
#     ("recovery: ...") and leaves nothing but constant/polyMesh;
#   - the same where the filesystem has no atomic exchange (strace makes
#     renameat2 fail with EINVAL): each kill point, the 3 renames of the
#     aside replace included (a kill between the first two leaves only
#     polyMesh.old~), ends, after the next run's recovery, with A
#     or B in constant/polyMesh and nothing stale;
#   - concurrent writers: 4 blockGrid runs (4 grids) on one case at once,
#     5 times; then 3 cutCells runs at once that cut the same block grid
#     (-i constant/block -o constant/polyMesh), 3 times: every run
#     exits 0, the grid is one of theirs (blockGrid: byte for byte;
#     cutCells: checkGrid says "Grid OK."), nothing else is left in
#     constant/;
#   - full disk: a case on a 64 kB tmpfs (root only; SKIP otherwise) and a
#     write over ulimit -f: a clear message (No space left on device / File
#     too large), exit status 1 (not a signal), grid A untouched, no
#     temporary left.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

blockdict() { # file nx ny
    { header blockGridDict
      echo "x { segments ((1 $2 1)); }"
      echo "y { segments ((1 $3 1)); }"
      echo "z { start 0.45; segments ((0.55 1 1)); }"
      echo "boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; }"
      echo "  zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }"
    } >"$1"
}

# base: grid A in constant/polyMesh, dictionaries A..D in system/
mkdir -p base/system
blockdict base/system/blockGridDict 4 4
blockdict base/system/dictB 6 5
blockdict base/system/dictC 7 3
blockdict base/system/dictD 5 8
{ header geometryDict; echo 'surfaces { disc { shape cylinder; point1 (0.5 0.5 0); point2 (0.5 0.5 1); radius 0.3; } }'; } \
    >base/system/geometryDict
"$BIN/blockGrid" -case base >/dev/null 2>&1 || fail setup "blockGrid on the base case failed"
for d in B C D; do
    mkdir -p "ref$d"
    cp -r base/system "ref$d/"
    "$BIN/blockGrid" -case "ref$d" -dict "ref$d/system/dict$d" >/dev/null 2>&1 || fail setup "blockGrid -dict dict$d failed"
done

same() { diff -r -q "$1" "$2" >/dev/null 2>&1; }
which_grid() { # dir: prints A, B, C, D or "neither"
    if same "$1" base/constant/polyMesh; then echo A; return; fi
    for d in B C D; do
        if same "$1" "ref$d/constant/polyMesh"; then echo "$d"; return; fi
    done
    echo neither
}
leftovers() { ls -A "$1/constant" | grep -vx 'polyMesh\|block' | tr '\n' ' '; }

# fresh copy of the base case (grid A) in $1
fresh() { rm -rf "$1"; cp -r base "$1"; }

# ---- kill during the replace ---------------------------------------------------
if ! command -v strace >/dev/null 2>&1; then
    echo "SKIP kill_during_replace: strace is not installed (etc/install-deps installs it)"
    echo "SKIP kill_during_replace_no_exchange: strace is not installed"
elif ! strace -f -o /dev/null true 2>/dev/null; then
    echo "SKIP kill_during_replace: strace cannot trace here (ptrace not permitted)"
    echo "SKIP kill_during_replace_no_exchange: strace cannot trace here"
else
    # kill_points NAME STRACE-OPTIONS...: kills blockGrid at each kill
    # point of a normal run under the same options, then checks the grid,
    # the next run's recovery and its message.
    kill_points() {
        local name=$1; shift
        fresh count
        strace -f -o count.trace -e trace=rename,renameat,renameat2,unlink,unlinkat,rmdir "$@" \
            "$BIN/blockGrid" -case count -dict count/system/dictB >/dev/null 2>&1
        # kill points "syscall n": every rename, and the first removal
        # after the last one (the old grid's, once the new one is in place)
        local points
        points=$(awk '{ sc = $2; sub(/\(.*/, "", sc); k[sc]++
                        if (sc ~ /^rename/) { print sc, k[sc]; rm = "" }
                        else if (rm == "") rm = sc " " k[sc] }
                      END { if (rm != "") print rm }' count.trace)
        local errs="" nk=0 nleft=0 nmissing=0 ngrid="" sc n
        while read -r -u 3 sc n; do
            {
                fresh k
                bash -c '"$@"; true' _ strace -f -o /dev/null "$@" -e "inject=$sc:signal=SIGKILL:when=$n" \
                    "$BIN/blockGrid" -case k -dict k/system/dictB >/dev/null 2>&1
                nk=$((nk + 1))
                local left g
                left=$(leftovers k)
                [ -d k/constant/polyMesh ] || nmissing=$((nmissing + 1))
                if [ "$name" = kill_during_replace ]; then
                    g=$(which_grid k/constant/polyMesh)
                    case $g in A|B) ;; *) errs="$errs; $sc #$n: constant/polyMesh is not A or B after the kill";; esac
                fi
                "$BIN/checkGrid" -case k >k.out 2>k.err
                local rc=$?
                g=$(which_grid k/constant/polyMesh)
                ngrid="$ngrid$g"
                case $g in A|B) ;; *) errs="$errs; $sc #$n: constant/polyMesh is not A or B after the recovery";; esac
                [ "$rc" -eq 0 ] || errs="$errs; $sc #$n: checkGrid after the kill exited $rc: $(head -c 300 k.err)"
                [ -z "$(leftovers k)" ] || errs="$errs; $sc #$n: left after the next run: $(leftovers k)"
                if [ -n "$left" ]; then
                    nleft=$((nleft + 1))
                    local f
                    for f in $left; do
                        grep -q "^checkGrid: recovery: k/constant/$f: \\|^checkGrid: recovery: k/constant/polyMesh: restored from k/constant/$f" k.err ||
                            errs="$errs; $sc #$n: no recovery message for $f (stderr: $(head -c 300 k.err))"
                    done
                fi
            }
        done 3<<<"$points"
        local na=${ngrid//[^A]/} nb=${ngrid//[^B]/}
        [ "$nleft" -gt 0 ] || errs="$errs; no kill point left anything behind (the injection did not hit the replace)"
        [ -n "$na" ] && [ -n "$nb" ] || errs="$errs; expected both outcomes over the kill points, got '$ngrid'"
        if [ -z "$errs" ]; then
            pass "$name" "$nk kill points: grid A after ${#na}, B after ${#nb}, $nleft left a temporary (or polyMesh.old~) that the next run recovered and reported; constant/polyMesh missing right after $nmissing kill(s)"
        else
            fail "$name" "${errs#; }"
        fi
    }
    kill_points kill_during_replace
    kill_points kill_during_replace_no_exchange -e inject=renameat2:error=EINVAL
fi

# ---- concurrent writers ---------------------------------------------------------
errs="" seen=""
for round in 1 2 3 4 5; do
    fresh cc
    pids=()
    for d in blockGridDict dictB dictC dictD; do
        "$BIN/blockGrid" -case cc -dict "cc/system/$d" >"cc.$d.log" 2>&1 &
        pids+=($!)
    done
    i=0
    for p in "${pids[@]}"; do
        wait "$p" || errs="$errs; round $round: writer $i exited $?: $(grep -v '^ ' cc.*.log | grep -i 'error\|cannot' | head -2)"
        i=$((i + 1))
    done
    g=$(which_grid cc/constant/polyMesh)
    seen="$seen$g"
    [ "$g" != neither ] || errs="$errs; round $round: the grid is none of the four"
    [ -z "$(leftovers cc)" ] || errs="$errs; round $round: left in constant/: $(leftovers cc)"
done
[ -z "$errs" ] && pass concurrent_blockGrid "5 rounds of 4 writers, every run exit 0, final grids $seen, nothing left" ||
    fail concurrent_blockGrid "${errs#; }"

errs=""
for round in 1 2 3; do
    fresh cu
    cp -r cu/constant/polyMesh cu/constant/block
    pids=()
    for i in 1 2 3; do
        "$BIN/cutCells" -case cu -i cu/constant/block -o cu/constant/polyMesh >"cu.$i.log" 2>&1 &
        pids+=($!)
    done
    i=1
    for p in "${pids[@]}"; do
        wait "$p" || errs="$errs; round $round: cutCells $i exited $?: $(tail -n 2 "cu.$i.log")"
        i=$((i + 1))
    done
    "$BIN/checkGrid" -case cu >cu.check 2>&1 && grep -q 'Grid OK' cu.check ||
        errs="$errs; round $round: checkGrid: $(tail -n 3 cu.check)"
    [ -z "$(leftovers cu)" ] || errs="$errs; round $round: left in constant/: $(leftovers cu)"
done
[ -z "$errs" ] && pass concurrent_cutCells "3 rounds of 3 writers, every run exit 0, Grid OK, nothing left" ||
    fail concurrent_cutCells "${errs#; }"

# ---- full disk ----------------------------------------------------------------
# big_dict: a grid of about 500 kB, far over the limits below
big() { blockdict "$1/system/dictBig" 80 80; }

full_disk_check() { # name case rc log message
    local errs=""
    [ "$3" -eq 1 ] || errs="exit status $3, expected 1"
    grep -q "$5" "$4" || errs="$errs; no '$5' in the message: $(grep -v '^[A-Z/\\ -]' "$4" | head -c 300)"
    [ "$(which_grid "$2/constant/polyMesh")" = A ] || errs="$errs; grid A was not kept"
    [ -z "$(leftovers "$2")" ] || errs="$errs; left in constant/: $(leftovers "$2")"
    [ -z "$errs" ] && pass "$1" "exit 1, '$(grep -m1 "$5" "$4")', grid A kept, nothing left" || fail "$1" "${errs#; }"
}

if [ "$(id -u)" -ne 0 ]; then
    echo "SKIP disk_full_tmpfs: not root (mounting a small tmpfs needs root; file_size_limit covers EFBIG)"
else
    mkdir -p disk
    if mount -t tmpfs -o size=64k tmpfs disk 2>/dev/null; then
        trap 'umount "$PWD/disk" 2>/dev/null' EXIT
        cp -r base disk/c && big disk/c
        "$BIN/blockGrid" -case disk/c -dict disk/c/system/dictBig >disk.log 2>&1
        full_disk_check disk_full_tmpfs disk/c $? disk.log 'No space left on device'
        umount disk && trap - EXIT
    else
        echo "SKIP disk_full_tmpfs: cannot mount a tmpfs here (no privileges); file_size_limit covers EFBIG"
    fi
fi

fresh fs && big fs
(ulimit -f 64; exec "$BIN/blockGrid" -case fs -dict fs/system/dictBig) >fs.log 2>&1
full_disk_check file_size_limit fs $? fs.log 'File too large'
