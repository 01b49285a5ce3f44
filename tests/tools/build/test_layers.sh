#!/usr/bin/env bash
# test_layers.sh: the layer rule of doc/architecture.md, "nothing below
# app/ prints or exits".  Every object of libkiesel.a (common/) is read
# with nm: an undefined reference to exit, _exit, abort, printf, vprintf,
# puts, putchar, perror, stdout or stderr fails the test, naming the
# object and the symbol.  The one exception is mem.o: mem_alloc and its
# kin end the process on out-of-memory, so that no caller has to test for
# NULL (common/mem.h).  Also: no common/*.c or common/*.h includes a
# header of app/, and no header of app/ shadows one of common/ (an
# include by bare name would otherwise reach the wrong layer).
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
TESTBIN=${KIESEL_TESTBIN:-$TOP/build/release/tests}
LIB=$TESTBIN/../libkiesel.a

FORBIDDEN='exit _exit abort printf vprintf puts putchar perror stdout stderr'
# the allowed exceptions: "object:symbol"
ALLOWED='mem.o:exit'

if [ ! -f "$LIB" ]; then
    fail layers_lib "no library at $LIB (build first)"
else
    bad=$(nm -u -A "$LIB" 2>/dev/null | while IFS= read -r line; do
        # "path/libkiesel.a:object.o:                 U symbol"
        sym=${line##* }
        obj=${line%%: *}; obj=${obj##*:}
        sym=${sym%%@*}
        for f in $FORBIDDEN; do
            if [ "$sym" = "$f" ]; then
                case " $ALLOWED " in *" $obj:$sym "*) ;; *) echo "$obj references $sym";; esac
            fi
        done
    done)
    nobj=$(ar t "$LIB" | grep -c '\.o$')
    if [ "$nobj" -lt 10 ]; then
        fail layers_no_print_exit "only $nobj objects in $LIB"
    elif [ -n "$bad" ]; then
        fail layers_no_print_exit "library objects print or exit (move that code to app/): $(echo "$bad" | tr '\n' ';')"
    else
        pass layers_no_print_exit
    fi
fi

inc=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^">]*/)?app/' "$TOP"/common/*.c "$TOP"/common/*.h 2>/dev/null)
if [ -d "$TOP/app" ]; then
    for h in "$TOP"/app/*.h; do
        [ -f "$h" ] || continue
        b=$(basename "$h")
        inc+=$(grep -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$b\"" "$TOP"/common/*.c "$TOP"/common/*.h 2>/dev/null)
        [ -f "$TOP/common/$b" ] && inc+=" app/$b shadows common/$b"
    done
fi
if [ -n "$inc" ]; then
    fail layers_includes "common/ includes app/ headers: $(echo "$inc" | tr '\n' ';')"
else
    pass layers_includes
fi
