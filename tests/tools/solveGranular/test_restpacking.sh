#!/usr/bin/env bash
# test_restpacking.sh: the short version of tests/validation/restPacking/run (make test): N = 16, to t
# = 0.2, cut and merged and Voronoi, wellBalanced at round-off and
# cellSource's creep, and the collapse under a free surface
# (tests/validation/restPacking/packing.py).  About 15 s.
set -u
top=$(cd "$(dirname "$0")/../../.." && pwd)
bin=${KIESEL_BIN:-$top/bin}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$top/tests/validation/restPacking/packing.py" "$bin" "$work" "$top" 0.2 16
