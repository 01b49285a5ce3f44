# tests/lib.sh: helpers shared by the shell tests, sourced first:
#     . "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
# (tests/run exports KIESEL_TOP, KIESEL_BIN, KIESEL_TESTBIN, KIESEL_TMP).
#
# Every test reports one line per check, the lines tests/run counts:
#     PASS name[: details]    FAIL name: why    SKIP name: why
# A script whose check has another shape (compares two strings, or has
# its own message) defines its own after sourcing this file.

pass() { echo "PASS $1${2:+: $2}"; }
fail() { echo "FAIL $1: $2"; }
skip() { echo "SKIP $1: $2"; }

# check NAME COMMAND...: PASS when the command succeeds, else FAIL naming it.
check() {
    local n=$1; shift
    if "$@"; then pass "$n"; else fail "$n" "$*"; fi
}

# ---- numbers (awk, so that "1e-3" and "-0.5" compare as numbers) ----

# rel A B: |A - B| / |B|, as %.3e
rel() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; printf "%.3e", d / (b < 0 ? -b : b) }'; }
# absdiff A B: |A - B|, as %.3g
absdiff() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; printf "%.3g", d }'; }
# le A B: succeeds when A <= B
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

# ---- logs and directories ----

# fluid LOG: the fluid volume a cutCells or voronoiGrid log reports
fluid() { sed -n 's/^  fluid volume: *\([0-9.eE+-]*\).*/\1/p' "$1"; }
# listing DIR: every path below DIR, sorted
listing() { (cd "$1" && find . | LC_ALL=C sort); }

# ---- cases ----

# header OBJECT: a one-line FoamFile header of class dictionary
header() { printf 'FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n' "$1"; }

# case_system DIR APP [FORMAT [EXTRA]]: DIR/system with a controlDict for
# APP (one step; writeFormat FORMAT, ascii by default; no compression;
# the EXTRA entries last) and the fvSchemes and fvSolution that OpenFOAM's
# checkMesh needs besides it.
case_system() {
    mkdir -p "$1/system"
    { header controlDict
      echo "application $2; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;"
      echo "writeControl timeStep; writeInterval 1; writeFormat ${3:-ascii}; writeCompression off;"
      if [ -n "${4:-}" ]; then echo "$4"; fi
    } >"$1/system/controlDict"
    printf '%s\n%s\n' "$(header fvSchemes)" \
        'ddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {} interpolationSchemes {} snGradSchemes {}' \
        >"$1/system/fvSchemes"
    header fvSolution >"$1/system/fvSolution"
}

# unit_box DIR N NZ: DIR/system/blockGridDict of the unit cube in N^3
# cells, every side patch 'walls'; with NZ = 1 the 2-D slab z in [0.49, 1]
# of N x N x 1 cells whose front and back are the empty 'frontAndBack'.
unit_box() {
    mkdir -p "$1/system"
    local zb='zMin { name walls; } zMax { name walls; }'
    [ "$3" = 1 ] && zb='zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; }'
    { header blockGridDict
      echo "x { segments ((1 $2 1)); }"
      echo "y { segments ((1 $2 1)); }"
      if [ "$3" = 1 ]; then echo "z { start 0.49; segments ((0.51 1 1)); }"; else echo "z { segments ((1 $2 1)); }"; fi
      echo "boundary { xMin { name walls; } xMax { name walls; } yMin { name walls; } yMax { name walls; } $zb }"
    } >"$1/system/blockGridDict"
}

# geometry_dict DIR SURFACES: DIR/system/geometryDict with the surfaces
# sub-dictionary SURFACES (entries of the form "name { shape ...; }")
geometry_dict() { { header geometryDict; printf 'surfaces\n{\n%s\n}\n' "$2"; } >"$1/system/geometryDict"; }

# ---- tutorials ----

# fresh_copy SRC CASE: the tutorial SRC copied to CASE as it is in the
# repository, without the outputs of a run there (its Allclean runs).
fresh_copy() {
    rm -rf "$2"
    cp -r "$1" "$2"
    (cd "$2" && ./Allclean > /dev/null 2>&1)
}

# timed_allrun NAME CASE: runs CASE/Allrun from another directory (120 s at
# most); PASS NAME with the time it took, or FAIL NAME with the end of its
# output.  A failed step fails this check only: the checks after it still
# run on what the steps before it left, so one failure hides no other.
timed_allrun() {
    local t0 t1 out rc
    t0=$(date +%s.%N)
    out=$(cd / && timeout 120 "$2/Allrun" 2>&1); rc=$?
    t1=$(date +%s.%N)
    if [ "$rc" -ne 0 ]; then
        fail "$1" "Allrun exited with status $rc; output:"
        printf '%s\n' "$out" | tail -n 8 | sed 's/^/  /'
    else
        pass "$1" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f s", b - a }')"
    fi
}
