#!/usr/bin/env bash
# test_replay.sh: replays the fuzz seed corpora and every stored fuzz
# reproducer (tests/fuzz/crashes/<harness>-*) through the readers, built
# with gcc (and with the sanitizers when the suite runs under SANITIZE=1,
# since the harnesses link the same library).  One PASS per harness.
set -u
top=${KIESEL_TOP:?}
lib=$(cd "${KIESEL_TESTBIN:?}/.." && pwd)/libkiesel.a
san=""
case "$KIESEL_TESTBIN" in *asan*) san="-fsanitize=address,undefined -fno-sanitize-recover=undefined";; esac
for h in "$top"/tests/fuzz/fuzz_*.c; do
    name=$(basename "$h" .c); name=${name#fuzz_}
    exe=./replay_$name
    if ! gcc -std=c11 -D_POSIX_C_SOURCE=200809L -O1 -g $san -I"$top/common" \
        "$h" "$top/tests/fuzz/replay_main.c" "$lib" -lgmsh -lgsl -lgslcblas -lz -lm -o "$exe" 2> build_$name.log; then
        echo "FAIL replay_$name: harness does not build:"; sed 's/^/  /' build_$name.log | head -5
        continue
    fi
    files=()
    for f in "$top"/tests/fuzz/corpus/"$name"/* "$top"/tests/fuzz/crashes/"$name"-*; do
        [ -f "$f" ] && files+=("$f")
    done
    if [ ${#files[@]} -eq 0 ]; then
        echo "FAIL replay_$name: no inputs found"
        continue
    fi
    scratch=$(mktemp -d ./scratch.XXXXXX)
    if out=$(FUZZ_SCRATCH=$scratch "$exe" "${files[@]}" 2>&1); then
        echo "PASS replay_$name (${#files[@]} inputs)"
    else
        echo "FAIL replay_$name: $(tail -n 3 <<<"$out" | tr '\n' ' ')"
    fi
done
