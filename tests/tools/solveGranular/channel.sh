# tests/tools/solveGranular/channel.sh: the channel case the solveGranular
# tests share, sourced after tests/lib.sh (BIN set):
#     . "${KIESEL_TOP:-$(dirname "$0")/../../..}/tests/tools/solveGranular/channel.sh"
# A 2-D channel [0,1] x [0,0.2], 20 x 4 cells, one cell thick; patches
# inlet (x = 0), outlet (x = 1), walls, frontAndBack (empty); model
# Newtonian with mu 0.01, RsT 6; the well-posed open pair (fv/bc_open.c):
# inlet fixedValue U (1 0 0) with zeroGradient rho, outlet fixedValue rho 1
# with zeroGradient U; slip walls; rho = 1, U = (1 0 0) at the start.

# H OBJECT [CLASS]: a one-line FoamFile header
H() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "${2:-dictionary}" "$1"; }

# channel_case DIR CONTROL [DIVSCHEMES]: the case in DIR and its grid;
# CONTROL the controlDict's entries after "application solveGranular;",
# DIVSCHEMES the divSchemes entries (default Gauss upwind).
channel_case() {
    mkdir -p "$1/system" "$1/constant" "$1/0"
    { H blockGridDict
      echo 'x { segments ((1 20 1)); } y { segments ((0.2 4 1)); } z { start -0.025; segments ((0.05 1 1)); }'
      echo 'boundary { xMin { name inlet; } xMax { name outlet; } yMin { name walls; type wall; } yMax { name walls; type wall; }'
      echo '  zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }'
    } >"$1/system/blockGridDict"
    { H controlDict; echo "application solveGranular; $2"; } >"$1/system/controlDict"
    { H fvSchemes; echo "divSchemes { ${3:-default Gauss upwind;} } interpolationSchemes { default shepard; }"; } \
        >"$1/system/fvSchemes"
    { H fvSolution; echo 'solvers { "U.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; } }'; } \
        >"$1/system/fvSolution"
    { H granularProperties; echo 'model Newtonian; NewtonianCoeffs { mu 0.01; RsT 6; }'; } >"$1/constant/granularProperties"
    { H rho volScalarField; echo 'dimensions [1 -3 0 0 0 0 0]; internalField uniform 1;'
      echo 'boundaryField { inlet { type zeroGradient; } outlet { type fixedValue; value uniform 1; } walls { type zeroGradient; } frontAndBack { type empty; } }'; } >"$1/0/rho"
    { H U volVectorField; echo 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (1 0 0);'
      echo 'boundaryField { inlet { type fixedValue; value uniform (1 0 0); } outlet { type zeroGradient; } walls { type slip; } frontAndBack { type empty; } }'; } >"$1/0/U"
    "$BIN/blockGrid" -case "$1" >"$1/log.blockGrid" 2>&1
}

# channel_bump DIR: setFields puts rho 1.2 for 0.3 < x < 0.5
channel_bump() {
    { H setFieldsDict
      echo 'defaultFieldValues ( volScalarFieldValue rho 1 ); regions ( boxToCell { box (0.3 -1 -1) (0.5 1 1);'
      echo '  fieldValues ( volScalarFieldValue rho 1.2 ); } );'; } >"$1/system/setFieldsDict"
    "$BIN/setFields" -case "$1" >"$1/log.setFields" 2>&1
}
