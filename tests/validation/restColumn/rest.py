"""A closed box at rest under gravity, initialised with the discrete
hydrostatic state rho = exp(-g y / RsT) at the cells' nodes (the
centroids; the seeds on a Voronoi grid); the spurious velocities at
t = T/2 and T under refinement.

usage: rest.py BIN WORKDIR INCLINEDCHANNELDIR [N ...]

Environment: RESTCOLUMN_ENDTIME (T, default 2), RESTCOLUMN_SCHEME
(fvSchemes' gravitySchemes: wellBalanced, the default, or cellSource),
RESTCOLUMN_INIT (rest, the default, or uniform: rho = 1, which must relax
to rest).  The functions are shared with
tests/tools/solveGranular/test_wellbalanced.sh.
"""
import math, os, re, shutil, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'inclinedChannel'))
import channel as ch   # polyMesh and field readers

G, MU, RST, ANGLE = 9.81, 0.25, 6.0, 30.0
T = int(os.environ.get('RESTCOLUMN_ENDTIME', '2'))   # end time; max |U| is reported at T/2 and T
SCHEME = os.environ.get('RESTCOLUMN_SCHEME', 'wellBalanced')
INIT = os.environ.get('RESTCOLUMN_INIT', 'rest')
KINDS = [('cartesian', 'shepard'), ('cartesian', 'multilinear'), ('cut', 'shepard'), ('cut', 'multilinear'),
         ('voronoi', 'shepard')]
def hdr(o, c='dictionary'):
    return 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' % (c, o)

def centroids(d):
    """Cell centroids: each face fanned into triangles from its vertex mean,
    each triangle with the cell's face-centre mean a signed tetrahedron."""
    pm = os.path.join(d, 'constant/polyMesh')
    pts, faces = ch.tuples(pm + '/points'), ch.tuples(pm + '/faces')
    own, nei = ch.labels(pm + '/owner'), ch.labels(pm + '/neighbour')
    n = max(own) + 1
    cf = [[] for _ in range(n)]
    fc = []
    for f, fa in enumerate(faces):
        x = [pts[int(i)] for i in fa]
        fc.append([sum(p[k] for p in x) / len(x) for k in range(3)])
        cf[own[f]].append(f)
        if f < len(nei): cf[nei[f]].append(f)
    C = []
    for c in range(n):
        a = [sum(fc[f][k] for f in cf[c]) / len(cf[c]) for k in range(3)]
        vt, m = 0.0, [0.0, 0.0, 0.0]
        for f in cf[c]:
            s = 1 if own[f] == c else -1
            x = [pts[int(i)] for i in faces[f]]
            for i in range(len(x)):
                p, q, r = fc[f], x[i], x[(i + 1) % len(x)]
                u = [p[k] - a[k] for k in range(3)]
                v = [q[k] - a[k] for k in range(3)]
                w = [r[k] - a[k] for k in range(3)]
                dv = s * (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                          + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6
                vt += dv
                for k in range(3): m[k] += dv * (a[k] + p[k] + q[k] + r[k]) / 4
        C.append([m[k] / vt for k in range(3)])
    return C

def nodes(d):
    """The cells' nodes as the solver takes them (mesh_cell_node): the
    Voronoi seeds of constant/polyMesh/cellSeed, else the centroids."""
    seed = os.path.join(d, 'constant/polyMesh/cellSeed')
    return ch.tuples(seed) if os.path.exists(seed) else centroids(d)

def write_case(d, n, kind, interp, scheme, control):
    for s in ('system', 'constant', '0'): os.makedirs(os.path.join(d, s), exist_ok=True)
    def w(f, s): open(os.path.join(d, f), 'w').write(s)
    h = 1.0 / n
    walls = ('boundary { xMin { name walls; type wall; } xMax { name walls; type wall; } yMin { name walls; type wall; } '
             'yMax { name walls; type wall; } zMin { name frontAndBack; type empty; } '
             'zMax { name frontAndBack; type empty; } }\n')
    nb, lb = (n, 1.0) if kind == 'cartesian' else (int(round(1.5 * n)), 1.5)
    w('system/blockGridDict', hdr('blockGridDict') +
      'x { segments ((%r %d 1)); } y { segments ((%r %d 1)); } z { start %r; segments ((%r 1 1)); }\n'
      % (lb, nb, lb, nb, -h / 2, h) + walls)
    if kind != 'cartesian':
        w('system/geometryDict', hdr('geometryDict') +
          'surfaces { box { type wall; flow inside; shape box; min (-0.5 -0.5 -1); max (0.5 0.5 1); '
          'rotate { axis (0 0 1); angle %r; } translate (0.75 0.75 0); } }\n' % ANGLE)
        w('system/mergeCellsDict', hdr('mergeCellsDict') + 'threshold 0.5;\n')
    w('constant/g', hdr('g', 'uniformDimensionedVectorField') + 'dimensions [0 1 -2 0 0 0 0]; value (0 %r 0);\n' % -G)
    w('constant/granularProperties', hdr('granularProperties') +
      'model Newtonian; NewtonianCoeffs { mu %r; RsT %r; }\n' % (MU, RST))
    w('system/controlDict', hdr('controlDict') +
      'application solveGranular; startFrom latestTime; startTime 0; stopAt endTime; writeFormat ascii; '
      'writePrecision 17; %s\n' % control)
    w('system/fvSchemes', hdr('fvSchemes') +
      'divSchemes { default Gauss upwind; } interpolationSchemes { default %s; } gravitySchemes { default %s; }\n'
      % (interp, scheme))
    w('system/fvSolution', hdr('fvSolution') +
      'solvers { "U.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; } }\n')
    w('0/U', hdr('U', 'volVectorField') + 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0); '
      'boundaryField { ".*" { type noSlip; } frontAndBack { type empty; } }\n')

def write_rho(d, init):
    """0/rho: the discrete rest state exp(-g y/RsT) at the nodes, or 1."""
    C = nodes(d)
    rho = ['%.17g' % (math.exp(-G * c[1] / RST) if init == 'rest' else 1.0) for c in C]
    open(os.path.join(d, '0/rho'), 'w').write(
        hdr('rho', 'volScalarField') + 'dimensions [1 -3 0 0 0 0 0];\ninternalField nonuniform List<scalar> %d\n(\n%s\n)\n;\n'
        % (len(rho), '\n'.join(rho)) + 'boundaryField { ".*" { type zeroGradient; } frontAndBack { type empty; } }\n')
    return len(C)

def max_u(d, t, n):
    return max(math.sqrt(sum(x * x for x in u)) for u in ch.field(os.path.join(d, t, 'U'), n))

def run(binp, d, n, kind, interp, scheme=None, init=None, control=None, times=None):
    """Grid, fields, solveGranular in a fresh d; max |U| at each of times
    (time directory names; default T/2 and T) in u, the steps, the
    largest relative mass change dm, the solver's seconds."""
    scheme, init = scheme or SCHEME, init or INIT
    control = control or ('endTime %d; deltaT 1e-4; adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; '
                          'writeInterval %g;' % (T, T / 2.0))
    times = times or ['%g' % (T / 2.0), '%g' % T]
    shutil.rmtree(d, ignore_errors=True)
    write_case(d, n, kind, interp, scheme, control)
    tools = {'cartesian': ['blockGrid'], 'cut': ['blockGrid', 'cutCells', 'mergeCells'],
             'voronoi': ['blockGrid', 'voronoiGrid']}[kind]
    def call(tool):
        with open(os.path.join(d, 'log.' + tool), 'w') as log:
            if subprocess.call([os.path.join(binp, tool), '-case', d], stdout=log, stderr=subprocess.STDOUT):
                return '%s failed in %s' % (tool, d)
    for tool in tools:
        e = call(tool)
        if e: return dict(err=e)
    nc = write_rho(d, init)
    t0 = time.time()
    e = call('solveGranular')
    secs = time.time() - t0
    if e: return dict(err=e)
    log = open(os.path.join(d, 'log.solveGranular')).read()
    return dict(err=None, cells=nc, u=[max_u(d, t, nc) for t in times], steps=len(re.findall(r'^Time = ', log, re.M)),
                dm=max(abs(float(x)) for x in re.findall(r'change since start = (\S+)', log)), secs=secs)

def main():
    binp, work = sys.argv[1], sys.argv[2]
    ns = [int(x) for x in sys.argv[4:]] or [16, 32, 64]
    print('Rest column: closed 1 x 1 box, g = (0 -%g 0), mu = %g, RsT = %g, noSlip, U = 0, %s, to t = %d, '
          'gravitySchemes %s' % (G, MU, RST, 'rho = exp(-g y/RsT) at the nodes' if INIT == 'rest' else 'rho = 1',
                                 T, SCHEME))
    print('  grid        interp       N   cells  steps  max|U| t=%-3g max|U| t=%-3d  order  mass change  time' % (T / 2.0, T))
    nfail = 0
    res = {}
    for kind, interp in KINDS:
        prev = None
        for n in ns:
            r = run(binp, os.path.join(work, '%s_%s_%d' % (kind, interp, n)), n, kind, interp)
            res[(kind, interp, n)] = r
            if r['err']:
                print('  %-10s  %-11s  %3d  %s' % (kind, interp, n, r['err']))
                prev = None
                continue
            r['u1'], r['u2'] = r['u']
            o = math.log(prev / r['u2']) / math.log(2) if prev and r['u2'] > 0 else None
            print('  %-10s  %-11s  %3d  %6d  %5d  %.3e    %.3e    %s  %.1e      %5.1f s' % (
                kind, interp, n, r['cells'], r['steps'], r['u1'], r['u2'], '%5.2f' % o if o is not None else '    -',
                r['dm'], r['secs']))
            prev = r['u2']
        sys.stdout.flush()
    print()
    for kind, interp in KINDS:
        rs = [res[(kind, interp, n)] for n in ns]
        bad = [r['err'] for r in rs if r['err']]
        if bad:
            nfail += 1
            print('FAIL restColumn_%s_%s: %s' % (kind, interp, bad[0]))
            continue
        dm = max(r['dm'] for r in rs)
        ok = dm <= 1e-12
        nfail += not ok
        print('%s restColumn_%s_%s_mass: largest relative mass change %.1e over N = %s (tolerance 1e-12)' % (
            'PASS' if ok else 'FAIL', kind, interp, dm, ', '.join(map(str, ns))))
        if INIT == 'rest':
            u = max(r['u2'] for r in rs)
            ok = u <= 1e-12
            nfail += not ok
            print('%s restColumn_%s_%s_rest: max|U| at t = %d is %s for N = %s (goal: round-off, <= 1e-12)' % (
                'PASS' if ok else 'FAIL', kind, interp, T, ', '.join('%.2e' % r['u2'] for r in rs),
                ', '.join(map(str, ns))))
        else:
            ok = all(r['u2'] < 0.5 * r['u1'] for r in rs)
            nfail += not ok
            print('%s restColumn_%s_%s_relax: max|U| at t = %g and %d: %s for N = %s (relaxing to rest: '
                  'at most half between them)' % ('PASS' if ok else 'FAIL', kind, interp, T / 2.0, T,
                  ', '.join('%.2e, %.2e' % (r['u1'], r['u2']) for r in rs), ', '.join(map(str, ns))))
    return 1 if nfail else 0

if __name__ == '__main__':
    sys.exit(main())
