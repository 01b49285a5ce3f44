#!/usr/bin/env bash
# test_shared_solver.sh: the velocity components' shared linear solver
# (fv/linsolve.h linsolve_new_shared, linsolve_solve_tracked) and the
# matrix assembled once a step (fv/fvm.h fvm_same_matrix) give the same
# numbers as one solver per component, bit for bit.  Each case runs twice
# from the same start: fvSolution "U.*" (one PETSc solver for all
# components, its preconditioner built once a step when their matrices
# agree) and with Uy (and Uz) given a maxIter of their own (one solver
# each, each preconditioner built for its own solve); the last time
# directories must be identical (cmp of rho, U, p):
#   - shared_noslip: a box rotated 30 degrees, cut and merged, noSlip
#     walls, a density bump (setFields), 60 steps: both components on one
#     matrix and one factorisation;
#   - shared_slip: the same with slip walls, whose inclined normals give
#     each component its own boundary coefficients: the matrix is
#     assembled again for Uy and the shared preconditioner rebuilt;
#   - shared_3d: a sphere (slip) in a box (noSlip), 8^3 cut and merged,
#     30 steps: three components, each matrix its own.
set -u
. "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/lib.sh"
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
cd "${KIESEL_TMP:-$(mktemp -d)}" || exit 1
rm -rf sgs && mkdir sgs && cd sgs || exit 1

H() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "${2:-dictionary}" "$1"; }

# case2d DIR UWALL: the rotated box of test_solveGranular.sh, 16 x 16
case2d() {
    mkdir -p "$1/system" "$1/constant" "$1/0"
    { H blockGridDict
      echo 'x { segments ((1 16 1)); } y { segments ((1 16 1)); } z { start -0.025; segments ((0.05 1 1)); }'
      echo 'boundary { xMin { name walls; type wall; } xMax { name walls; type wall; } yMin { name walls; type wall; }'
      echo '  yMax { name walls; type wall; } zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }'
    } >"$1/system/blockGridDict"
    { H geometryDict
      echo 'surfaces { box { type wall; flow inside; shape box; min (-0.3 -0.3 -1); max (0.3 0.3 1);'
      echo '  rotate { axis (0 0 1); angle 30; } translate (0.5 0.5 0); } }'
    } >"$1/system/geometryDict"
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( boxToCell { box (0.3 0.3 -1) (0.5 0.7 1);'
      echo '  fieldValues ( volScalarFieldValue rho 1.5 ); } );'; } >"$1/system/setFieldsDict"
    fields "$1" "$2" 60
}

# case3d DIR: a ball (slip) in the unit cube (noSlip), 8^3
case3d() {
    mkdir -p "$1/system" "$1/constant" "$1/0"
    { H blockGridDict
      echo 'x { segments ((1 8 1)); } y { segments ((1 8 1)); } z { segments ((1 8 1)); }'
      echo 'boundary { xMin { name walls; type wall; } xMax { name walls; type wall; } yMin { name walls; type wall; }'
      echo '  yMax { name walls; type wall; } zMin { name walls; type wall; } zMax { name walls; type wall; } }'
    } >"$1/system/blockGridDict"
    { H geometryDict
      echo 'surfaces { ball { type wall; flow outside; shape sphere; centre (0.55 0.5 0.45); radius 0.22; } }'
    } >"$1/system/geometryDict"
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( boxToCell { box (0 0 0) (0.3 1 1);'
      echo '  fieldValues ( volScalarFieldValue rho 1.5 ); } );'; } >"$1/system/setFieldsDict"
    fields "$1" noSlip 30
    sed -i 's/"\.\*" { type noSlip; }/".*" { type noSlip; } ball { type slip; }/' "$1/0/U"
}

# fields DIR UWALL STEPS: controlDict, schemes, properties, rho and U
fields() {
    { H controlDict; echo "application solveGranular; startFrom startTime; startTime 0; stopAt endTime; endTime 1000;"
      echo "deltaT 1e-3; adjustTimeStep yes; maxCo 0.25; writeControl timeStep; writeInterval $3; writeFormat binary;"; } \
        >"$1/system/controlDict"
    sed -i 's/stopAt endTime/stopAt nextWrite/' "$1/system/controlDict"
    { H fvSchemes; echo 'divSchemes { default Gauss upwind; } interpolationSchemes { default shepard; }'; } \
        >"$1/system/fvSchemes"
    { H granularProperties; echo 'model Newtonian; NewtonianCoeffs { mu 0.01; RsT 6; }'; } \
        >"$1/constant/granularProperties"
    { H rho volScalarField; echo 'dimensions [1 -3 0 0 0 0 0]; internalField uniform 1;'
      echo 'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }'; } >"$1/0/rho"
    { H U volVectorField; echo 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);'
      echo "boundaryField { \".*\" { type $2; } frontAndBack { type empty; } }"; } >"$1/0/U"
}

# solvers DIR SEPARATE: fvSolution, one entry for all components or (1)
# Uy and Uz with maxIters of their own
solvers() {
    local e='solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0;'
    { H fvSolution
      if [ "$2" = 1 ]; then echo "solvers { \"U.*\" { $e maxIter 1000; } Uy { $e maxIter 999; } Uz { $e maxIter 998; } }"
      else echo "solvers { \"U.*\" { $e maxIter 1000; } }"; fi
    } >"$1/system/fvSolution"
}

lasttime() { (cd "$1" && ls -d [0-9]* | sort -g | tail -n 1); }

# compare NAME MAKER ARGS...: builds the case, runs both ways, compares
compare() {
    local name=$1 maker=$2; shift 2
    local c=$name
    "$maker" "$c" "$@"
    if ! { "$BIN/blockGrid" -case $c && "$BIN/cutCells" -case $c && "$BIN/mergeCells" -case $c &&
           "$BIN/setFields" -case $c; } >$c/log.grid 2>&1; then
        fail "$name" "grid tools failed: $(tail -n 2 $c/log.grid | tr '\n' ' ')"
        return
    fi
    rm -rf ${c}_sep && cp -r $c ${c}_sep
    solvers $c 0
    solvers ${c}_sep 1
    "$BIN/solveGranular" -case $c >$c/log 2>&1; local rc1=$?
    "$BIN/solveGranular" -case ${c}_sep >${c}_sep/log 2>&1; local rc2=$?
    local a b same=yes
    a=$(lasttime $c); b=$(lasttime ${c}_sep)
    for f in rho U p; do cmp -s "$c/$a/$f" "${c}_sep/$b/$f" || same="no ($f differs)"; done
    local steps u
    steps=$(grep -c '^Time = ' $c/log)
    u=$(grep -c 'Solving for Uy' $c/log)
    if [ $rc1$rc2 = 00 ] && [ "$a" = "$b" ] && [ "$a" != 0 ] && [ "$same" = yes ] && [ "$u" -eq "$steps" ]; then
        pass "$name" "time $a after $steps steps, shared and separate solvers identical"
    else
        fail "$name" "rc $rc1 $rc2, times $a and $b, $steps steps, identical: $same"
    fi
}

compare shared_noslip case2d noSlip
compare shared_slip case2d slip
compare shared_3d case3d
