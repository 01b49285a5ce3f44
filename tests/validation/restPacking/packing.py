"""packing.py BIN WORK TOP END N...: a dense granular packing at rest under
gravity in a container rotated 30 degrees to the grid (issue 12, "Rest
and conservation").  The driver of run and tests/tools/solveGranular/test_restpacking.sh.

The 0.6 x 0.6 box rotated 30 degrees in the unit block grid (N cells a
side), cut and merged (M_V = 1/2) or Voronoi; model granular (eta0
0.0035, lambda0 0.00034, eps0 63.4921, cMax 0.64, c0 0.5, T0 0.5, the
thesis's Sec. 5.3 packing), g = (0, -9.81, 0), noSlip walls, U = 0 and T
= Tmin = 1e-12 (a packing at rest is cold: the temperature's limit acts
in every cell of every step, as it must).  c is the continuous rest
state at the cells' nodes: at fixed T the enthalpy h = int dp/c rises by
|g| per metre downwards, above c0 h = (T + B) s(v) + const, s(v) = v +
e^v, v = ln(c/(cMax - c)), B = T0 (1 - c0/cMax) (fv/closure.h), from p =
0.05 at the top corner (c 0.536 .. 0.632: above c0 everywhere, no free
surface).  That is also the discrete rest state of gravitySchemes
wellBalanced (each cell's profile through its node is the same profile),
and not of cellSource (the thesis's c g V).  Prints max |U| at t = END/2
and END for both schemes, with orders for cellSource, and the largest
relative mass change; PASS per run when mass is kept to 1e-12, PASS per
grid kind when wellBalanced keeps max|U| <= 1e-15 at every N, and when
cellSource does not (its creep is > 1e-8: the check can fail both ways).
Then a collapse under a free surface (collapse()): PASS when wellBalanced
leaves the grains (c > 1e-3) slower than cellSource and below 1e-4 m/s,
and with less kinetic energy.
"""
import math, os, shutil, subprocess, sys

BIN, WORK, TOP, END = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
NS = [int(a) for a in sys.argv[5:]] or [16, 32, 64]
sys.path.insert(0, os.path.join(TOP, 'tests/validation/restColumn'))
sys.path.insert(0, os.path.join(TOP, 'tests/validation/inclinedChannel'))
import rest            # nodes()
import channel as ch   # field readers

T0, C0, CMAX, G, TMIN, PTOP = 0.5, 0.5, 0.64, 9.81, 1e-12, 0.05
B = T0 * (1 - C0 / CMAX)
YTOP = 0.5 + 0.3 * (math.cos(math.radians(30)) + math.sin(math.radians(30)))

def H(o, c='dictionary'):
    return 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' % (c, o)

def inv_s(s):
    """v with v + e^v = s (Newton, as fv/closure.c)."""
    v = math.log(s) if s > 1 else s - 1
    for _ in range(64):
        ev = math.exp(v); dv = (v + ev - s) / (1 + ev); v -= dv
        if abs(dv) <= 2.2e-16 * (1 + abs(v)): break
    return v

def rest_c(y):
    vtop = math.log((PTOP + T0 * C0) / (CMAX * (TMIN + B)))
    v = inv_s(vtop + math.exp(vtop) + G * (YTOP - y) / (TMIN + B))
    return CMAX / (1 + math.exp(-v))

def write(path, text):
    with open(path, 'w') as f: f.write(text)

def case(d, n, kind, scheme, end=None, T=TMIN, init=None):
    end = end or END
    init = init or (lambda x: rest_c(x[1]))
    shutil.rmtree(d, ignore_errors=True)
    for s in ('system', 'constant', '0'): os.makedirs(os.path.join(d, s))
    write(d + '/system/blockGridDict', H('blockGridDict') +
          'x { segments ((1 %d 1)); } y { segments ((1 %d 1)); } z { start -0.025; segments ((0.05 1 1)); }\n'
          'boundary { xMin { name walls; type wall; } xMax { name walls; type wall; } yMin { name walls; type wall; }\n'
          '  yMax { name walls; type wall; } zMin { name frontAndBack; type empty; } zMax { name frontAndBack; type empty; } }\n' % (n, n))
    write(d + '/system/geometryDict', H('geometryDict') +
          'surfaces { box { type wall; flow inside; shape box; min (-0.3 -0.3 -1); max (0.3 0.3 1);\n'
          '  rotate { axis (0 0 1); angle 30; } translate (0.5 0.5 0); } }\n')
    write(d + '/system/controlDict', H('controlDict') +
          'application solveGranular; startFrom startTime; startTime 0; stopAt endTime; endTime %.17g; deltaT 1e-5;\n'
          'writeControl adjustableRunTime; writeInterval %.17g; writeFormat ascii; writePrecision 17;\n'
          'adjustTimeStep yes; maxCo 0.25; writeVTK no;\n' % (end, end / 2))
    write(d + '/system/fvSchemes', H('fvSchemes') + 'divSchemes { default Gauss upwind; } '
          'interpolationSchemes { default shepard; } gravitySchemes { default %s; }\n' % scheme)
    write(d + '/system/fvSolution', H('fvSolution') +
          'solvers { "U.*|Theta" { solver PBiCGStab; preconditioner DILU; tolerance 1e-12; relTol 0; } }\n')
    write(d + '/constant/granularProperties', H('granularProperties') +
          'model granular; granularCoeffs { eta0 0.0035; lambda0 0.00034; epsilon0 63.4921; cMax 0.64; c0 0.5; T0 0.5; '
          'Tmin %g; }\n' % TMIN)
    write(d + '/constant/g', H('g', 'uniformDimensionedVectorField') + 'dimensions [0 1 -2 0 0 0 0]; value (0 -9.81 0);\n')
    write(d + '/0/Theta', H('Theta', 'volScalarField') + 'dimensions [0 2 -2 0 0 0 0]; internalField uniform %g;\n'
          'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }\n' % T)
    write(d + '/0/U', H('U', 'volVectorField') + 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);\n'
          'boundaryField { ".*" { type noSlip; } frontAndBack { type empty; } }\n')
    tools = [['blockGrid'], ['voronoiGrid']] if kind == 'voronoi' else [['blockGrid'], ['cutCells'], ['mergeCells']]
    for t in tools:
        r = subprocess.run([os.path.join(BIN, t[0]), '-case', d], capture_output=True, text=True)
        if r.returncode: sys.exit('%s failed: %s' % (t[0], r.stderr))
    X = rest.nodes(d)
    write(d + '/0/alpha', H('alpha', 'volScalarField') + 'dimensions [0 0 0 0 0 0 0];\n'
          'internalField nonuniform List<scalar> %d\n(\n%s\n)\n;\n' % (len(X), '\n'.join('%.17g' % init(x) for x in X)) +
          'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }\n')
    return len(X)

def tdir(d, t):
    return os.path.join(d, ('%.6g' % t))

def run(n, kind, scheme):
    d = os.path.join(WORK, '%s%d_%s' % (kind, n, scheme))
    nc = case(d, n, kind, scheme)
    r = subprocess.run([os.path.join(BIN, 'solveGranular'), '-case', d], capture_output=True, text=True)
    if r.returncode: sys.exit('solveGranular failed (%s): %s' % (d, r.stderr))
    steps = sum(1 for l in r.stdout.splitlines() if l.startswith('Time ='))
    mass = [float(l.split('=')[1].split(',')[0]) for l in r.stdout.splitlines() if l.startswith('Total mass')]
    dm = max(abs(m - mass[0]) / mass[0] for m in mass)
    um = []
    for t in (END / 2, END):
        U = ch.field(os.path.join(tdir(d, t), 'U'), nc)
        um.append(max(math.sqrt(sum(x * x for x in u)) for u in U))
    return nc, steps, um, dm

def collapse(scheme, n=32, end=0.5):
    """Half the box filled with c = 0.58 (y < 0.5), vacuum above, T = 1e-4:
    the packing settles under a free surface.  max|U| over all cells, over
    the cells with c > 1e-3, and the kinetic energy sum c |U|^2 at end."""
    d = os.path.join(WORK, 'collapse_%s' % scheme)
    nc = case(d, n, 'cut', scheme, end, 1e-4, lambda x: 0.58 if x[1] < 0.5 else 0.0)
    r = subprocess.run([os.path.join(BIN, 'solveGranular'), '-case', d], capture_output=True, text=True)
    if r.returncode: sys.exit('solveGranular failed (%s): %s' % (d, r.stderr))
    U = ch.field(os.path.join(tdir(d, end), 'U'), nc)
    c = [x[0] for x in ch.field(os.path.join(tdir(d, end), 'alpha'), nc)]
    sp = [math.sqrt(sum(x * x for x in u)) for u in U]
    return max(sp), max(sp[i] for i in range(nc) if c[i] > 1e-3), sum(c[i] * sp[i] ** 2 for i in range(nc))

def main():
    fails = 0
    print('restPacking: max|U| at t = %g and %g, dense packing at rest, T = Tmin' % (END / 2, END))
    print('| grid | N | cells | steps | wellBalanced t/2 | t | cellSource t/2 | t | order | mass change |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for kind in ('cut', 'voronoi'):
        prev, wb_ok, cs_ok = None, True, True
        for n in NS:
            nc, steps, uw, dmw = run(n, kind, 'wellBalanced')
            _, _, uc, dmc = run(n, kind, 'cellSource')
            order = '%.2f' % math.log2(prev / uc[1]) if prev else '-'
            prev = uc[1]
            print('| %s | %d | %d | %d | %.2e | %.2e | %.2e | %.2e | %s | %.1e |' % (kind, n, nc, steps, uw[0], uw[1], uc[0], uc[1], order, max(dmw, dmc)))
            for s, dm in (('wellBalanced', dmw), ('cellSource', dmc)):
                ok = dm <= 1e-12
                fails += not ok
                print('%s mass_%s%d_%s%s' % ('PASS' if ok else 'FAIL', kind, n, s, '' if ok else ': %.2e' % dm))
            wb_ok &= max(uw) <= 1e-15
            cs_ok &= uc[1] > 1e-8
        for name, ok, what in (('rest_wellBalanced_' + kind, wb_ok, 'max|U| <= 1e-15 at every N'),
                               ('creep_cellSource_' + kind, cs_ok, 'max|U| > 1e-8 at every N')):
            fails += not ok
            print('%s %s%s' % ('PASS' if ok else 'FAIL', name, '' if ok else ': not ' + what))
    res = {s: collapse(s) for s in ('wellBalanced', 'cellSource')}
    print('collapse under a free surface (cut, N = 32, t = 0.5):')
    print('| scheme | max\\|U\\| | max\\|U\\| (c > 1e-3) | sum c\\|U\\|^2 |')
    print('|---|---|---|---|')
    for s_, (a, b, ke) in res.items(): print('| %s | %.3e | %.3e | %.3e |' % (s_, a, b, ke))
    w, c_ = res['wellBalanced'], res['cellSource']
    ok = w[1] <= c_[1] and w[2] <= c_[2] and w[1] <= 1e-4
    fails += not ok
    print('%s collapse_wellBalanced%s' % ('PASS' if ok else 'FAIL', '' if ok else ': the grains move faster than with cellSource, or > 1e-4'))
    return 1 if fails else 0

if __name__ == '__main__':
    sys.exit(main())
