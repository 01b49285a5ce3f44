#!/usr/bin/env bash
# test_shearplate.sh: the quick shear plate of thesis §5.2.2 (model
# granular, the parameters of §5.2.2, plates W = 0.04 apart, the upper one
# moving at 1 m/s, periodic along them, t = 1.5): tests/validation/
# shearPlate/run quick, which runs the grid-aligned plate at h = W/4, W/8
# and W/16 (the reference) and the plate rotated to the grid (slope 23/13,
# cut and merged, shepard) at h = W/8 with Gauss upwind and limitedLinear 1,
# and the grid-aligned partialSlip plate (30 degrees) at W/4, W/8 against
# W/16 with the thesis's wall heating and with heatingSchemes wallVelocity
# boundary; it checks
#   - grid-aligned first order in L1 of the velocity along the plates and
#     of T between W/4 and W/8 against W/16 (order >= 0.8; measured 1.54
#     and 1.49);
#   - on the rotated plate, limitedLinear 1's L1 error of velocity at most
#     0.6 times upwind's, of T at most 0.8 times (measured 0.24 and 0.69:
#     upwind's crosswind diffusion drags the bulk; T's ratio was 0.33 with
#     eq. 4.65's heating weight, before the metric Jacobian, doc/validation.md);
#   - partialSlip with wallVelocity boundary: T L1 order >= 0.3 between W/4
#     and W/8 (measured 0.52); with the thesis's u_S in the heating the T
#     error at W/8 at least 3 times that (measured 7.0: the slip jump over
#     h heats the wall cells, and that error grows as h falls, order -0.67).
# About 30 s on a loaded 2-core machine.
set -u
top=${KIESEL_TOP:-$(cd "$(dirname "$0")/../../.." && pwd)}
KIESEL_BIN=${KIESEL_BIN:-$top/bin} KIESEL_TMP=${KIESEL_TMP:-$(mktemp -d)} \
    bash "$top/tests/validation/shearPlate/run" quick
