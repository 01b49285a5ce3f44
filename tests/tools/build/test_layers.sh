#!/usr/bin/env bash
# test_layers.sh: the layer rule of doc/architecture.md, "nothing below
# app/ prints or exits", for common/ (libkiesel.a) and fv/
# (libkieselfv.a).  Every object of each library is read with nm: an
# undefined reference to exit, _exit, abort, printf, vprintf, puts,
# putchar, perror, stdout or stderr fails the test, naming the object and
# the symbol.  The one exception is mem.o: mem_alloc and its kin end the
# process on out-of-memory, so that no caller has to test for NULL
# (common/mem.h).  Also: no file of a layer includes a header of a layer
# above it (common/ nothing of fv/ or app/, fv/ nothing of app/), and no
# header above shadows one below (an include by bare name would otherwise
# reach the wrong layer).
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
TOP=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
TESTBIN=${KIESEL_TESTBIN:-$TOP/build/release/tests}
LIB=$TESTBIN/../libkiesel.a

FORBIDDEN='exit _exit abort printf vprintf puts putchar perror stdout stderr'
# the allowed exceptions: "object:symbol"
ALLOWED='mem.o:exit'

# no_print_exit NAME LIBRARY MINOBJECTS
no_print_exit() {
    local name=$1 lib=$2 min=$3 bad nobj
    if [ ! -f "$lib" ]; then
        fail "$name" "no library at $lib (build first)"
        return
    fi
    bad=$(nm -u -A "$lib" 2>/dev/null | while IFS= read -r line; do
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
    nobj=$(ar t "$lib" | grep -c '\.o$')
    if [ "$nobj" -lt "$min" ]; then
        fail "$name" "only $nobj objects in $lib"
    elif [ -n "$bad" ]; then
        fail "$name" "library objects print or exit (move that code to app/): $(echo "$bad" | tr '\n' ';')"
    else
        pass "$name"
    fi
}
no_print_exit layers_no_print_exit "$LIB" 10
no_print_exit layers_fv_no_print_exit "$TESTBIN/../libkieselfv.a" 1

# includes NAME LOWER UPPER: no file of LOWER/ includes a header of UPPER/
includes() {
    local name=$1 lo=$2 up=$3 inc h b
    inc=$(grep -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]([^\">]*/)?$up/" "$TOP"/"$lo"/*.c "$TOP"/"$lo"/*.h 2>/dev/null)
    if [ -d "$TOP/$up" ]; then
        for h in "$TOP"/"$up"/*.h; do
            [ -f "$h" ] || continue
            b=$(basename "$h")
            inc+=$(grep -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$b\"" "$TOP"/"$lo"/*.c "$TOP"/"$lo"/*.h 2>/dev/null)
            [ -f "$TOP/$lo/$b" ] && inc+=" $up/$b shadows $lo/$b"
        done
    fi
    if [ -n "$inc" ]; then
        fail "$name" "$lo/ includes $up/ headers: $(echo "$inc" | tr '\n' ';')"
    else
        pass "$name"
    fi
}
includes layers_includes common app
includes layers_common_fv common fv
includes layers_fv_app fv app
