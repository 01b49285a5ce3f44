#!/usr/bin/env bash
# test_foamDictionary.sh: dictQuery against OpenFOAM's own parser.
#
# For real tutorial files (gunzipped copies in the scratch directory) the
# keyword lists (foamDictionary -keywords) and scalar, word and vector
# values (foamDictionary -entry X -value) must agree with dictQuery's.
# Numbers are compared as numbers (foamDictionary reformats 2.0 as 2) and
# lists token by token.  SKIPs when OpenFOAM or its tutorials are absent.
set -u
BIN=${KIESEL_BIN:-$(cd "$(dirname "$0")/../../.." && pwd)/bin}
DQ="$BIN/dictQuery"
TUT=${FOAM_TUTORIALS_DIR:-/usr/share/doc/openfoam-examples/examples}
[ -d /usr/share/openfoam ] && export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
FD=$(command -v foamDictionary || true)
if [ -z "$FD" ]; then
    echo "SKIP foamDictionary_compare: OpenFOAM's foamDictionary is not installed"
    exit 0
fi
if [ ! -d "$TUT" ]; then
    echo "SKIP foamDictionary_compare: no OpenFOAM tutorials at $TUT"
    exit 0
fi
if [ ! -x "$DQ" ]; then
    echo "FAIL foamDictionary_compare: $DQ not built"
    exit 1
fi

# Tokens one per line: brackets split off, numbers normalised.
norm() {
    sed -e 's/[][(){};]/ & /g' | tr -s ' \t\n' '\n\n\n' | grep -v '^$' |
        awk '/^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/ { printf "%.12g\n", $0 + 0; next } { print }'
}

# copy SRC NAME: the tutorial file (or its .gz) as NAME in the scratch dir
copy() {
    if [ -f "$TUT/$1" ]; then cp "$TUT/$1" "$2"
    elif [ -f "$TUT/$1.gz" ]; then gzip -dc "$TUT/$1.gz" >"$2"
    else return 1
    fi
}

compare_keywords() {   # name file [entry]
    local name=$1 f=$2 a b
    if [ $# -ge 3 ]; then
        a=$("$FD" -entry "$3" -keywords "$f" 2>&1)
        b=$("$DQ" -entry "$3" -keywords "$f" 2>&1)
    else
        a=$("$FD" -keywords "$f" 2>&1)
        b=$("$DQ" -keywords "$f" 2>&1)
    fi
    if [ "$a" = "$b" ]; then
        echo "PASS keywords_$name"
    else
        echo "FAIL keywords_$name: foamDictionary: $(echo $a | head -c 300) | dictQuery: $(echo $b | head -c 300)"
    fi
}

compare_value() {   # name file entry
    local name=$1 f=$2 e=$3 a b
    a=$("$FD" -entry "$e" -value "$f" 2>&1 | norm)
    b=$("$DQ" -entry "$e" -value "$f" 2>&1 | norm)
    if [ -n "$a" ] && [ "$a" = "$b" ]; then
        echo "PASS value_${name}_$e"
    else
        echo "FAIL value_${name}_$e: foamDictionary: $(echo $a | head -c 200) | dictQuery: $(echo $b | head -c 200)"
    fi
}

missing=0
need() { copy "$1" "$2" || { echo "SKIP foamDictionary_$2: tutorial file $1 not found"; missing=$((missing + 1)); return 1; }; }

if need incompressible/icoFoam/cavity/cavity/system/controlDict controlDict; then
    compare_keywords controlDict controlDict
    for e in application endTime deltaT runTimeModifiable; do
        compare_value controlDict controlDict "$e"
    done
fi
if need incompressible/icoFoam/cavity/cavity/system/fvSolution fvSolution; then
    compare_keywords fvSolution fvSolution
    compare_keywords fvSolution_pFinal fvSolution solvers.pFinal
    for e in solvers.pFinal.tolerance solvers.pFinal.relTol PISO.pRefValue; do
        compare_value fvSolution fvSolution "$e"
    done
fi
if need incompressible/simpleFoam/pitzDaily/system/fvSolution fvSolution2; then
    compare_keywords fvSolution2_solvers fvSolution2 solvers
    compare_keywords fvSolution2_equations fvSolution2 relaxationFactors.equations
    for e in relaxationFactors.equations.k SIMPLE.consistent; do
        compare_value fvSolution2 fvSolution2 "$e"
    done
fi
if need incompressible/icoFoam/cavity/cavity/system/fvSchemes fvSchemes; then
    compare_keywords fvSchemes fvSchemes
    for e in ddtSchemes.default 'divSchemes.div(phi,U)'; do
        compare_value fvSchemes fvSchemes "$e"
    done
fi
if need incompressible/icoFoam/cavity/cavity/system/blockMeshDict blockMeshDict; then
    compare_keywords blockMeshDict blockMeshDict
    compare_value blockMeshDict blockMeshDict scale
fi
if need incompressible/icoFoam/cavity/cavity/0/U U; then
    compare_keywords U U
    compare_keywords U_boundaryField U boundaryField
    for e in dimensions internalField boundaryField.movingWall.value; do
        compare_value U U "$e"
    done
fi
if need multiphase/interFoam/laminar/damBreak/damBreak/system/setFieldsDict setFieldsDict; then
    compare_keywords setFieldsDict setFieldsDict
    compare_value setFieldsDict setFieldsDict defaultFieldValues
fi
if need multiphase/interFoam/laminar/damBreak/damBreak/constant/transportProperties transportProperties; then
    compare_keywords transportProperties transportProperties
    compare_value transportProperties transportProperties water.nu
fi
if need incompressible/simpleFoam/airFoil2D/constant/polyMesh/boundary boundary; then
    compare_keywords boundary boundary
fi
if need multiphase/twoPhaseEulerFoam/laminar/fluidisedBed/system/controlDict controlDict2; then
    compare_keywords controlDict2 controlDict2
    compare_value controlDict2 controlDict2 maxCo
fi
if [ "$missing" -gt 0 ]; then
    echo "SKIP foamDictionary_files: $missing tutorial files missing"
fi
