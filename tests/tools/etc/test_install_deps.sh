#!/usr/bin/env bash
# Tests of etc/install-deps with stand-ins for dpkg-query, apt-get, id and
# sudo on PATH, so nothing is installed and no network is used.
#
# The stand-in dpkg-query reports every package installed except those
# listed in $MISSING (until the stand-in apt-get "installs" them); apt-get
# appends its arguments and DEBIAN_FRONTEND to ./apt.log, except for a
# simulation (-s), which goes to ./sim.log and prints "Remv VICTIM" for
# each package given that $REMOVES lists as "PKG=VICTIM".
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
deps=$top/etc/install-deps
scratch=$PWD

mkdir -p "$scratch/stub"
cat > "$scratch/stub/dpkg-query" <<'EOF'
#!/bin/sh
for a; do p=$a; done
for m in $MISSING; do
    if [ "$m" = "$p" ] && ! grep -qx "$p" "$STUB/installed" 2>/dev/null; then exit 1; fi
done
printf installed
EOF
cat > "$scratch/stub/apt-get" <<'EOF'
#!/bin/sh
for a; do
    if [ "$a" = -s ]; then
        echo "$* [$DEBIAN_FRONTEND]" >> "$STUB/sim.log"
        for p; do
            echo "Inst $p (1.0 Debian:12/stable [amd64])"
            for r in ${REMOVES:-}; do
                [ "${r%%=*}" = "$p" ] && echo "Remv ${r#*=} [1.0]"
            done
        done
        exit 0
    fi
done
echo "$* [$DEBIAN_FRONTEND]" >> "$STUB/apt.log"
if [ "$1" = install ]; then
    for a; do echo "$a" >> "$STUB/installed"; done
fi
EOF
cat > "$scratch/stub/id" <<'EOF'
#!/bin/sh
echo "${FAKE_UID:-0}"
EOF
cat > "$scratch/stub/sudo" <<'EOF'
#!/bin/sh
[ -n "${SUDO_WORKS:-}" ] || exit 1
[ "$1" = -n ] && shift
"$@"
EOF
chmod +x "$scratch/stub/"*
export STUB=$scratch/stub

run() {   # run ARGS...: install-deps with the stubs; output in out.txt
    rm -f "$STUB/apt.log" "$STUB/sim.log" "$STUB/installed"
    PATH="$STUB:$PATH" "$deps" "$@" > "$scratch/out.txt" 2>&1
}

# Everything present: exit 0 at once, no apt-get at all (not even update).
MISSING="" run; rc=$?
if [ "$rc" -ne 0 ] || [ -e "$STUB/apt.log" ]; then
    fail nothing_missing "rc=$rc, apt-get called: $(cat "$STUB/apt.log" 2>/dev/null)"
else
    pass nothing_missing
fi

# As root: one update, then one install of exactly the missing packages
# (python3-paraview missing too: no VTK at all).
MISSING="libgsl-dev python3-vtk9 python3-paraview" run; rc=$?
want="update [noninteractive]
install -y --no-install-recommends libgsl-dev python3-vtk9 [noninteractive]"
if [ "$rc" -ne 0 ] || [ "$(cat "$STUB/apt.log" 2>/dev/null)" != "$want" ]; then
    fail root_installs_missing "rc=$rc, apt.log: '$(cat "$STUB/apt.log" 2>/dev/null)'"
else
    pass root_installs_missing
fi

# A fresh Debian with only git and make: the compiler is installed too.
MISSING="build-essential gcc libc6-dev" run; rc=$?
if [ "$rc" -ne 0 ] || ! grep -q 'install .* gcc libc6-dev ' "$STUB/apt.log" 2>/dev/null; then
    fail installs_compiler "rc=$rc, apt.log: '$(cat "$STUB/apt.log" 2>/dev/null)'"
else
    pass installs_compiler
fi

# gnuplot satisfied by another flavour.
MISSING="gnuplot-nox gnuplot-x11" run; rc=$?
if [ "$rc" -ne 0 ] || [ -e "$STUB/apt.log" ]; then
    fail gnuplot_flavour "rc=$rc (gnuplot-qt counts as gnuplot)"
else
    pass gnuplot_flavour
fi

# OpenFOAM, its examples and strace by default; --minimal skips them;
# clang only with --fuzz; --openfoam is still accepted.
extras="clang openfoam openfoam-examples strace"
MISSING=$extras run --minimal; rc1=$?
log1=$(cat "$STUB/apt.log" 2>/dev/null)
MISSING=$extras run; rc2=$?
log2=$(grep install "$STUB/apt.log" 2>/dev/null)
MISSING=$extras run --fuzz --openfoam; rc3=$?
log3=$(grep install "$STUB/apt.log" 2>/dev/null)
if [ "$rc1" -ne 0 ] || [ -n "$log1" ] || [ "$rc2" -ne 0 ] || [ "$rc3" -ne 0 ] \
    || [ "$log2" != "install -y --no-install-recommends openfoam openfoam-examples strace [noninteractive]" ] \
    || [ "$log3" != "install -y --no-install-recommends openfoam openfoam-examples strace clang [noninteractive]" ]; then
    fail optional_groups "rc=$rc1/$rc2/$rc3, --minimal: '$log1', default: '$log2', --fuzz --openfoam: '$log3'"
else
    pass optional_groups
fi

# ParaView's Python installed: its vtk module serves the tests, so
# python3-vtk9 (which conflicts with it) is not installed, nothing runs.
MISSING="python3-vtk9" run; rc=$?
if [ "$rc" -ne 0 ] || [ -e "$STUB/apt.log" ] || [ -e "$STUB/sim.log" ]; then
    fail paraview_vtk "rc=$rc, apt-get called: $(cat "$STUB/apt.log" "$STUB/sim.log" 2>/dev/null)"
else
    pass paraview_vtk
fi

# A package whose installation would remove another is held back, with
# the reason; the rest is installed; nothing is ever removed.
REMOVES="python3-vtk9=python3-paraview" MISSING="libgsl-dev python3-vtk9 python3-paraview" run; rc=$?
inst=$(grep '^install' "$STUB/apt.log" 2>/dev/null)
if [ "$rc" -ne 0 ] || [ "$inst" != "install -y --no-install-recommends libgsl-dev [noninteractive]" ] \
    || grep -q 'remove\|purge' "$STUB/apt.log" \
    || ! grep -q 'not installing python3-vtk9: apt would remove python3-paraview' "$scratch/out.txt"; then
    fail removal_held_back "rc=$rc, apt.log: '$(cat "$STUB/apt.log" 2>/dev/null)', output: $(cat "$scratch/out.txt")"
else
    pass removal_held_back "$(grep -m1 'not installing' "$scratch/out.txt")"
fi

# Held back and needed by the build: reported, exit non-zero, no install.
REMOVES="libgmsh-dev=libvtk9-dev" MISSING="libgmsh-dev" run; rc=$?
if [ "$rc" -eq 0 ] || grep -q '^install' "$STUB/apt.log" 2>/dev/null \
    || ! grep -q 'the build needs libgmsh-dev' "$scratch/out.txt"; then
    fail removal_build_package "rc=$rc, apt.log: '$(cat "$STUB/apt.log" 2>/dev/null)', output: $(cat "$scratch/out.txt")"
else
    pass removal_build_package
fi

# Not root and no working sudo: prints the command, exits non-zero, no apt-get.
FAKE_UID=1000 MISSING="zlib1g-dev" run; rc=$?
if [ "$rc" -eq 0 ] || [ -e "$STUB/apt.log" ] \
    || ! grep -q "apt-get install -y --no-install-recommends zlib1g-dev" "$scratch/out.txt"; then
    fail user_without_sudo "rc=$rc, output: $(cat "$scratch/out.txt")"
else
    pass user_without_sudo
fi

# Not root, passwordless sudo: installs through sudo.
SUDO_WORKS=1 FAKE_UID=1000 MISSING="zlib1g-dev" run; rc=$?
if [ "$rc" -ne 0 ] || ! grep -q 'install .*zlib1g-dev' "$STUB/apt.log" 2>/dev/null; then
    fail user_with_sudo "rc=$rc, output: $(cat "$scratch/out.txt")"
else
    pass user_with_sudo
fi

# --check reports and installs nothing; a bad option is refused.
MISSING="libgmsh-dev" run --check; rc=$?
if [ "$rc" -ne 1 ] || [ -e "$STUB/apt.log" ] || ! grep -q 'missing: libgmsh-dev' "$scratch/out.txt"; then
    fail check_only "rc=$rc, output: $(cat "$scratch/out.txt")"
else
    MISSING="" run --bogus; rc=$?
    if [ "$rc" -ne 2 ]; then fail check_only "bad option gave status $rc"; else pass check_only; fi
fi
