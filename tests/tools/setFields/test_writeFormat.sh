#!/usr/bin/env bash
# test_writeFormat.sh: writeFormat and writeCompression of system/controlDict
# mean the same for the grid blockGrid writes and the fields setFields
# writes (one reader, common/case.h): ascii + on gzips both; binary + on
# writes both binary and uncompressed, as OpenFOAM v1912 does ("Disabled
# binary format compression"); every spelling OpenFOAM accepts
# (compressed, uncompressed, yes, true, ...) is accepted by both tools;
# a bad value stops both with controlDict:line.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1

# new_case C FORMAT COMPRESSION: a fresh case (controlDict line 4 holds
# the two keywords)
new_case() {
    rm -rf "$1"
    mkdir -p "$1/system" "$1/0"
    cat >"$1/system/controlDict" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application setFields;
startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeFormat $2; writeCompression $3;
EOF
    cat >"$1/system/blockGridDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockGridDict; }
x { start 0; segments ( (1 4 1) ); }
y { start 0; segments ( (1 3 1) ); }
z { start 0; segments ( (1 2 1) ); }
EOF
    cat >"$1/system/setFieldsDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object setFieldsDict; }
defaultFieldValues ( volScalarFieldValue alpha 0 );
regions ( boxToCell { box (0 0 0) (0.5 1 1); fieldValues ( volScalarFieldValue alpha 1 ); } );
EOF
    cat >"$1/0/alpha" <<'EOF'
FoamFile { version 2.0; format ascii; class volScalarField; object alpha; }
dimensions [0 0 0 0 0 0 0];
internalField uniform 0;
boundaryField { ".*" { type zeroGradient; } }
EOF
}

# run_both C: blockGrid then setFields; 0 when both succeed
run_both() {
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1 && "$BIN/setFields" -case "$1" >"$1/log.setFields" 2>&1
}

# format_of FILE: the header's format of FILE or FILE.gz
format_of() {
    if [ -f "$1.gz" ]; then zcat "$1.gz"; else cat "$1"; fi 2>/dev/null | head -c 2000 | tr -d '\0' |
        sed -n 's/^[[:space:]]*format[[:space:]]*\([a-z]*\);.*/\1/p' | head -n 1
}

# both_are C FORMAT GZ: the grid's points and the field alpha are both
# FORMAT, both gzipped (GZ 1) or both plain (GZ 0)
both_are() {
    local c=$1 fmt=$2 gz=$3 f
    for f in "$c/constant/polyMesh/points" "$c/0/alpha"; do
        if [ "$gz" = 1 ]; then
            [ -f "$f.gz" ] && [ ! -f "$f" ] && gzip -t "$f.gz" || return 1
        else
            [ -f "$f" ] && [ ! -f "$f.gz" ] || return 1
        fi
        [ "$(format_of "$f")" = "$fmt" ] || return 1
    done
}

new_case ascii_on ascii on
run_both ascii_on
check writeFormat_ascii_on_gzips_grid_and_fields both_are ascii_on ascii 1

new_case binary_on binary on
run_both binary_on
check writeFormat_binary_on_like_openfoam both_are binary_on binary 0

new_case binary_off binary off
run_both binary_off
check writeFormat_binary_off both_are binary_off binary 0

new_case ascii_off ascii off
run_both ascii_off
check writeFormat_ascii_off both_are ascii_off ascii 0

# every spelling OpenFOAM accepts, for both tools
for w in compressed yes true; do
    new_case "w_$w" ascii "$w"
    run_both "w_$w"
    check "writeCompression_${w}_accepted" both_are "w_$w" ascii 1
done
for w in uncompressed no false; do
    new_case "w_$w" ascii "$w"
    run_both "w_$w"
    check "writeCompression_${w}_accepted" both_are "w_$w" ascii 0
done

# a bad value: both tools stop with controlDict:4, nothing written
new_case bad ascii maybe
"$BIN/blockGrid" -case bad >bad.log 2>&1
rc=$?
check writeCompression_bad_blockGrid test "$rc" -eq 1 -a ! -e bad/constant/polyMesh
check writeCompression_bad_blockGrid_message grep -q 'bad/system/controlDict:4:.*writeCompression' bad.log
cp -r ascii_off/constant bad/
"$BIN/setFields" -case bad >bad2.log 2>&1
rc=$?
check writeCompression_bad_setFields test "$rc" -eq 1
check writeCompression_bad_setFields_message grep -q 'bad/system/controlDict:4:.*writeCompression' bad2.log
check writeCompression_bad_setFields_untouched grep -q 'internalField uniform 0;' bad/0/alpha
