#!/usr/bin/env bash
# test_dictQuery.sh: dictQuery prints dictionaries, entries, values and
# keywords as read (after #include and $ expansion), and reports bad input
# as file:line with exit status 1.  Runs in a scratch directory.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
DQ="$BIN/dictQuery"
if [ ! -x "$DQ" ]; then
    echo "FAIL dictQuery_exists: $DQ not built"
    exit 1
fi

# check NAME EXPECTED ACTUAL
check() { if [ "$2" = "$3" ]; then pass "$1"; else fail "$1" "expected '$2', got '$3'"; fi; }

mkdir -p case/system case/0
cat >case/system/controlDict <<'EOF'
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      controlDict;
}
// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //
#include "settings"

application     solveGranular;
endTime         $tEnd;
deltaT          0.005;   // comment
"write.*"       20;
writeControl    timeStep;
functions
{
    probes { type probes; fields (p U); }
}
EOF
cat >case/system/settings <<'EOF'
tEnd 0.5;
EOF
cat >case/0/U <<'EOF'
FoamFile { version 2.0; format ascii; class volVectorField; object U; }
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    movingWall { type fixedValue; value uniform (1 0 0); }
    fixedWalls { type noSlip; }
}
EOF

out=$("$DQ" -entry application -value case/system/controlDict 2>&1)
check value_word "solveGranular" "$out"
out=$("$DQ" -entry endTime -value case/system/controlDict 2>&1)
check value_from_include_and_variable "0.5" "$out"
out=$("$DQ" -entry writeInterval -value case/system/controlDict 2>&1)
check value_through_regex "20" "$out"
out=$("$DQ" -entry functions.probes.fields -value case/system/controlDict 2>&1)
check value_scoped_list "(p U)" "$out"
out=$("$DQ" -entry functions/probes/type -value case/system/controlDict 2>&1)
check value_slash_scoped "probes" "$out"
out=$("$DQ" -keywords case/system/controlDict 2>&1 | tr '\n' ' ')
check keywords 'FoamFile tEnd application endTime deltaT "write.*" writeControl functions ' "$out"
out=$("$DQ" -entry boundaryField -keywords case/0/U 2>&1 | tr '\n' ' ')
check keywords_of_subdict "movingWall fixedWalls " "$out"
out=$("$DQ" -entry boundaryField.movingWall.value -value case/0/U 2>&1)
check vector_value "uniform (1 0 0)" "$out"
out=$("$DQ" -entry dimensions case/0/U 2>&1)
check entry_line "dimensions      [0 1 -1 0 0 0 0];" "$out"
out=$(cd case && "$DQ" -entry deltaT -value system/controlDict 2>&1)
check relative_path "0.005" "$out"
out=$("$DQ" -case case -entry deltaT -value system/controlDict 2>&1)
check case_option "0.005" "$out"

out=$("$DQ" -dict case/system/controlDict -entry deltaT -value 2>&1)
check dict_option "0.005" "$out"
out=$(printf 'x { y (1 2 3); }\n' | "$DQ" -entry x.y -value - 2>&1)
check stdin "(1 2 3)" "$out"

# The whole file: written as parsed, and it reads back to the same text.
"$DQ" case/system/controlDict >whole.txt 2>err.txt
rc=$?
if [ $rc -eq 0 ] && grep -q '^endTime         0.5;$' whole.txt && grep -q '^    probes$' whole.txt; then
    pass whole_dictionary
else
    fail whole_dictionary "rc $rc: $(head -c 300 whole.txt) $(cat err.txt)"
fi
"$DQ" whole.txt >whole2.txt 2>&1
if cmp -s whole.txt whole2.txt; then pass whole_round_trip; else fail whole_round_trip "$(diff whole.txt whole2.txt | head -5)"; fi

# gzip: U.gz found for U
gzip -c case/0/U >case/0/V.gz
out=$("$DQ" -entry internalField -value case/0/V 2>&1)
check gzip_fallback "uniform (0 0 0)" "$out"

# Warnings go to stderr, the output stays clean.
printf 'a 1;\n#includeEtc "caseDicts/setConstraintTypes"\n' >warn.dict
out=$("$DQ" -entry a -value warn.dict 2>warn.err)
if [ "$out" = "1" ] && grep -q 'warn.dict:2: #includeEtc caseDicts/setConstraintTypes ignored' warn.err; then
    pass warning_on_stderr
else
    fail warning_on_stderr "out '$out', err '$(cat warn.err)'"
fi

# Errors: file:line on stderr, exit status 1, nothing on stdout.
expect_error() {   # name, expected stderr substring, args...
    local name=$1 want=$2
    shift 2
    local so se rc
    so=$("$DQ" "$@" 2>err.txt)
    rc=$?
    se=$(cat err.txt)
    if [ $rc -eq 1 ] && [ -z "$so" ] && grep -qF -- "$want" err.txt; then
        pass "$name"
    else
        fail "$name" "rc $rc, stdout '$so', stderr '$se'"
    fi
}
printf 'a 1;\nb (1 2\n' >bad1.dict
expect_error error_unterminated_list "bad1.dict:2: unterminated list started at line 2" bad1.dict
printf 'a 1;\n\nb 2\n}\n' >bad2.dict
expect_error error_missing_semicolon "bad2.dict:3: expected ';' after value of keyword 'b'" bad2.dict
printf 'a $nothere;\n' >bad3.dict
expect_error error_undefined_variable "bad3.dict:1: undefined variable \$nothere" bad3.dict
printf 'a 1;\n#calc "1+1"\n' >bad4.dict
expect_error error_unsupported_directive "bad4.dict:2: directive #calc is not supported" bad4.dict
# issue 9: the FoamFile header is checked as OpenFOAM checks it, and a
# list size is checked where the list is read, not only where it is used
printf 'FoamFile\n{\n    version 2.0;\n    format ascii\n    class dictionary;\n    object x;\n}\na 1;\n' >bad5.dict
expect_error error_header_missing_semicolon "bad5.dict:4: FoamFile header: entry 'format' has 2 excess tokens" bad5.dict
printf 'FoamFile { version 2.0 nan; format ascii; class dictionary; object x; }\na 1;\n' >bad6.dict
expect_error error_header_excess_token "bad6.dict:1: FoamFile header: entry 'version' has 1 excess token (word 'nan'...)" bad6.dict
printf 'FoamFile { version 2.0; format ascii; class dictionary; object x; }\nlist 3 ( 1 2 );\nb 1;\n' >bad7.dict
expect_error error_list_size "bad7.dict:2: keyword 'list': list size 3 does not match the 2 items read" -entry b bad7.dict
expect_error error_missing_entry "entry 'nope' not found" -entry nope case/system/controlDict
expect_error error_missing_file "nosuchfile" nosuchfile
expect_error error_no_file "expected one dictionary file"
expect_error error_keywords_of_value "is not a dictionary" -entry deltaT -keywords case/system/controlDict
head -c 40 /dev/urandom >random.bin
printf '\x00\x01' >>random.bin
"$DQ" random.bin >/dev/null 2>err.txt
rc=$?
if [ $rc -eq 0 ] || { [ $rc -eq 1 ] && grep -q '^random.bin' err.txt; }; then
    pass garbage_input_no_crash
else
    fail garbage_input_no_crash "rc $rc: $(cat err.txt)"
fi
