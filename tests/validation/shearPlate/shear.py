"""The granular shear plate of thesis §5.2.2 (Tables 5.5, 5.6, 5.7).

Model granular with the parameters of §5.2.2 (eta0 = 0.00102573,
epsilon0 = 216.649, lambda0 = 0.00034, cMax 0.8, c0 0.3, T0 0: no yield;
c(0) = 0.6, T(0) = 0.01, u(0) = 0), K_T = 2/3, between two plates W = 0.04
apart, periodic along them (cyclic), to t = 1.5.  Four variants:

  noSlip       the upper plate moves at 1 m/s along itself, the lower rests;
  partialSlip  the same with Coulomb walls of 30 degrees (eq. 2.35);
  partialSlipUB  the same with heatingSchemes { wallVelocity boundary; }
               (ours: the thesis's heating with the wall velocity u_S
               heats a sliding wall's cells by eta (jump / h)^2: T does not
               converge);
  gravity      both plates noSlip at rest, gravity 1 m/s^2 along them.

Each on a grid-aligned block grid (5 cells along the plates, W/h across)
and rotated to the grid: the channel of inclinedChannel (slope 23/13, one
period of 13 cells, cyclic with the translation (13 h, 23 h) of whole
cells), cut and merged (M_V = 1/2), modified Shepard interpolation
(ICCM^MC_MS as the thesis), with divSchemes Gauss upwind (the thesis's)
and Gauss limitedLinear 1.  The reference of every run is the
grid-aligned upwind run at the finest h_ref: its cell values against the
distance from the resting wall, interpolated linearly (extrapolated
linearly over the half cell next to each wall).  Errors of the velocity
along the plates and of T: L1 = sum V |e| / sum V, Linf = max |e|, with
observed orders beside the thesis's.

usage: shear.py BIN WORKDIR [quick | noSlip partialSlip partialSlipUB gravity] [jacobian=NAME]
  partialSlipUB is partialSlip with heatingSchemes { wallVelocity boundary; }
  (ours: the heating at the walls from U's boundary values u_B, not u_S).
  quick: the test of make test (see quick()).
  jacobian=NAME: heatingSchemes' jacobian (faceMetric, the default;
  leastSquares; faceWeight, eq. 4.65's weight).
"""
import math, os, re, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'inclinedChannel'))
from channel import DELTA, hdr, body, tuples, labels, field, order, write_grid  # noqa: E402  readers, the grid

W, P, Q, TEND = 0.04, 23, 13, 1.5
N = math.hypot(P, Q)
TX, TY = Q / N, P / N                    # along the plates (rotated)
# The references' h: gravity's as the thesis's (Table 5.7: Cartesian h =
# 0.00125), because at 0.000625 it takes 1.3e6 steps (11 minutes)
HREF = {'noSlip': 0.000625, 'partialSlip': 0.000625, 'partialSlipUB': 0.000625, 'gravity': 0.00125}
GRAV = 1.0
COEFFS = ('eta0 0.00102573; epsilon0 216.649; lambda0 0.00034; cMax 0.8; c0 0.3; T0 0; KT 0.666667; deltaC %g;')
INTERP = 'shepard'                       # ICCM^MC_MS, the thesis's granular tests
JACOBIAN = 'faceMetric'                  # heatingSchemes' jacobian (argument jacobian=NAME)
DELTAC = 1e-6                            # the default: c <= cMax - 1e-6 (the cold bulk packs to it)
SCHEMES = [('upwind', 'Gauss upwind'), ('limitedLinear 1', 'Gauss limitedLinear 1')]
SCHEMES_FULL = SCHEMES + [('vanLeer', 'Gauss vanLeer')]   # the study's (quick() runs SCHEMES)
# Thesis Tables 5.5-5.7: h -> (Cart vel L1, Linf, ICCM vel L1, Linf, Cart T L1, Linf, ICCM T L1, Linf)
THESIS = {  # partialSlipUB (our wall heating) beside the thesis's Table 5.6 too
    'noSlip': {0.01: (0.00278, 0.054, 0.0142, 0.475, 1.22e-4, 0.00735, 1.62e-4, 0.00827),
               0.005: (0.00206, 0.0538, 0.0146, 0.281, 7.28e-5, 0.00568, 1.42e-4, 0.00792),
               0.0025: (0.00099, 0.0259, 0.0077, 0.209, 2.95e-5, 0.00302, 1.12e-4, 0.00678),
               0.00125: (None, None, 0.00844, 0.282, None, None, 1.12e-4, 0.00726)},
    'partialSlip': {0.02: (0.00784, 0.677, 0.0101, 0.821, 1.59e-4, 0.0112, 1.75e-4, 0.0121),
                    0.01: (0.00552, 0.431, 0.00863, 0.75, 1.16e-4, 0.00829, 1.49e-4, 0.00992),
                    0.005: (0.00363, 0.218, 0.00697, 0.643, 8.33e-5, 0.00595, 1.09e-4, 0.0072),
                    0.0025: (0.00149, 0.0621, 0.00517, 0.497, 3.71e-5, 0.00198, 9.6e-5, 0.0114),
                    0.00125: (None, None, 0.00341, 0.328, None, None, 9.07e-5, 0.017)},
    'gravity': {0.02: (0.0208, 1.01, 0.0637, 1.67, 9.39e-4, 0.0427, 1.15e-3, 0.0468),
                0.01: (0.0115, 0.318, 0.0663, 1.35, 8.10e-4, 0.0396, 1.02e-3, 0.0429),
                0.005: (0.01, 0.195, 0.0566, 0.904, 6.01e-4, 0.0353, 8.61e-4, 0.0371),
                0.0025: (0.00574, 0.132, 0.0347, 0.462, 3.31e-4, 0.0225, 6.29e-4, 0.028)},
}


def u_bc(variant, moving, t):
    """U's entry of one plate: t is the unit vector along the plates."""
    if variant.startswith('partialSlip'):
        return ('{ type partialSlip; frictionAngle 30; %s}' %
                ('wallVelocity (%.17g %.17g 0); ' % t if moving else ''))
    if moving and variant == 'noSlip':
        return '{ type movingWall; value uniform (%.17g %.17g 0); }' % t
    return '{ type noSlip; }'


def write_case(d, h, variant, rotated, scheme):
    for s in ('system', 'constant', '0'):
        os.makedirs(os.path.join(d, s), exist_ok=True)

    def w(f, s):
        open(os.path.join(d, f), 'w').write(s)
    write_grid(w, h, W, rotated)
    t = (TX, TY) if rotated else (1.0, 0.0)
    if variant == 'gravity':
        w('constant/g', hdr('g', 'uniformDimensionedVectorField') +
          'dimensions [0 1 -2 0 0 0 0]; value (%.17g %.17g 0);\n' % (GRAV * t[0], GRAV * t[1]))
    w('constant/granularProperties', hdr('granularProperties') +
      'model granular; granularCoeffs { %s }\n' % (COEFFS % DELTAC))
    w('system/controlDict', hdr('controlDict') +
      'application solveGranular; startFrom latestTime; startTime 0; stopAt endTime; endTime %r; deltaT 1e-5; '
      'adjustTimeStep yes; maxCo 0.25; writeControl adjustableRunTime; writeInterval %r; writeFormat ascii; '
      'writePrecision 17; writeVTK no;\n' % (TEND, TEND))
    heat = ('wallVelocity boundary; ' if variant == 'partialSlipUB' else '') + 'jacobian %s;' % JACOBIAN
    w('system/fvSchemes', hdr('fvSchemes') +
      'divSchemes { default %s; } interpolationSchemes { default %s; } heatingSchemes { %s }\n' % (
          scheme, INTERP, heat))
    w('system/fvSolution', hdr('fvSolution') +
      'solvers { "U.*|Theta" { solver PBiCGStab; preconditioner DILU; tolerance 1e-12; relTol 0; } }\n')
    walls = 'box { type zeroGradient; } ' if rotated else ''
    rest = 'left { type cyclic; } right { type cyclic; } frontAndBack { type empty; } }\n'
    for f, v in (('alpha', '0.6'), ('Theta', '0.01')):
        w('0/' + f, hdr(f, 'volScalarField') + 'dimensions [0 %d %d 0 0 0 0]; internalField uniform %s; '
          'boundaryField { lowerWall { type zeroGradient; } upperWall { type zeroGradient; } %s%s'
          % (2 if f == 'Theta' else 0, -2 if f == 'Theta' else 0, v, walls, rest))
    w('0/U', hdr('U', 'volVectorField') + 'dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0); '
      'boundaryField { lowerWall %s upperWall %s %s%s' % (
          u_bc(variant, False, t), u_bc(variant, True, t), 'box { type noSlip; } ' if rotated else '', rest))
    return t


def geometry(d):
    """Each cell's volume and centroid (signed pyramids on the faces)."""
    pm = os.path.join(d, 'constant/polyMesh')
    pts, faces = tuples(pm + '/points'), tuples(pm + '/faces')
    own, nei = labels(pm + '/owner'), labels(pm + '/neighbour')
    n = max(own) + 1
    V, M = [0.0] * n, [[0.0] * 3 for _ in range(n)]
    for f, fa in enumerate(faces):
        x = [pts[int(i)] for i in fa]
        c = [sum(p[k] for p in x) / len(x) for k in range(3)]
        for i in range(len(x)):
            a, b = x[i], x[(i + 1) % len(x)]
            # tetrahedron (origin, c, a, b): signed volume and centroid
            dv = (c[0] * (a[1] * b[2] - a[2] * b[1]) + c[1] * (a[2] * b[0] - a[0] * b[2]) +
                  c[2] * (a[0] * b[1] - a[1] * b[0])) / 6
            g = [(c[k] + a[k] + b[k]) / 4 for k in range(3)]
            for cell, s in ((own[f], 1), (nei[f] if f < len(nei) else -1, -1)):
                if cell < 0:
                    continue
                V[cell] += s * dv
                for k in range(3):
                    M[cell][k] += s * dv * g[k]
    return V, [[m / v for m in mm] for mm, v in zip(M, V)]


def run(binp, d, h, variant, rotated, scheme):
    write_case(d, h, variant, rotated, scheme)
    tools = ['blockGrid', 'cutCells', 'mergeCells'] if rotated else ['blockGrid']
    t0 = time.time()
    for tool in tools + ['solveGranular']:
        with open(os.path.join(d, 'log.' + tool), 'w') as log:
            if subprocess.call([os.path.join(binp, tool), '-case', d], stdout=log, stderr=subprocess.STDOUT):
                sys.exit('FAIL shearPlate: %s failed in %s' % (tool, d))
    if not os.path.isdir(os.path.join(d, '%g' % TEND)):  # stopped early (a signal): the log says why
        sys.exit('FAIL shearPlate: solveGranular stopped before t = %g in %s: %s' % (
            TEND, d, open(os.path.join(d, 'log.solveGranular')).read().strip().split('\n')[-2:]))
    return load(d, h, rotated, time.time() - t0)


def load(d, h, rotated, secs=0.0):
    """A finished run's cells: volume, distance from the resting plate, u
    along the plates, T at TEND."""
    t = (TX, TY) if rotated else (1.0, 0.0)
    V, X = geometry(d)
    tdir = os.path.join(d, '%g' % TEND)
    U, T = field(tdir + '/U', len(V)), field(tdir + '/Theta', len(V))
    dl = DELTA * h if rotated else 0.0
    dist = [-x[0] * t[1] + (x[1] - dl) * t[0] for x in X]
    ut = [u[0] * t[0] + u[1] * t[1] for u in U]
    steps = len(re.findall(r'^Time = ', open(os.path.join(d, 'log.solveGranular')).read(), re.M))
    return dict(h=h, n=len(V), V=V, d=dist, u=ut, T=[x[0] for x in T], secs=secs, steps=steps)


def profile(ref):
    """The reference as sorted (distance, u, T), one entry per distinct distance."""
    rows = {}
    for d, u, T in zip(ref['d'], ref['u'], ref['T']):
        rows.setdefault(round(d, 12), []).append((u, T))
    return [(d, sum(r[0] for r in v) / len(v), sum(r[1] for r in v) / len(v)) for d, v in sorted(rows.items())]


def interp(prof, d, k):
    """Column k of the profile at distance d: linear, extrapolated linearly at the ends."""
    i = 0
    while i < len(prof) - 2 and prof[i + 1][0] < d:
        i += 1
    a, b = prof[i], prof[i + 1]
    s = (d - a[0]) / (b[0] - a[0])
    return a[k] + s * (b[k] - a[k])


def errors(run, prof):
    vt = sum(run['V'])
    out = {}
    for key, k in (('u', 1), ('T', 2)):
        e = [v - interp(prof, d, k) for v, d in zip(run[key], run['d'])]
        out[key + '1'] = sum(v * abs(x) for v, x in zip(run['V'], e)) / vt
        out[key + 'i'] = max(abs(x) for x in e)
    # the T error next to each wall (cells within h of it), for the wall anomaly
    for name, near in (('Tlow', lambda d: d < run['h']), ('Tup', lambda d: d > W - run['h'])):
        sel = [(v, abs(T - interp(prof, d, 2))) for v, T, d in zip(run['V'], run['T'], run['d']) if near(d)]
        out[name] = sum(v * x for v, x in sel) / sum(v for v, _ in sel)
    return out


def fmt(v):
    return '%9.3e' % v if v is not None else '        -'


def ordfmt(o):
    return '%6.2f' % o if o is not None else '     -'


def table(title, rows, thesis, col):
    """One grid family's errors with observed orders; col 0 Cartesian, 1 ICCM in the thesis's columns."""
    print(title)
    print('  h         cells  steps   time    vel L1    ord   vel Linf  ord   T L1      ord   T Linf    ord  '
          ' T L1 lower/upper wall  | thesis vel L1 ord, Linf ord; T L1 ord, Linf ord')
    prev = None
    orders = []
    for r in rows:
        e = r['e']
        o = {}
        th = thesis.get(r['h']) if thesis else None
        tho = {}
        for key in ('u1', 'ui', 'T1', 'Ti'):
            o[key] = order(prev['e'][key], e[key], prev['h'], r['h']) if prev else None
        thv = None
        if th:
            idx = {'u1': 0, 'ui': 1, 'T1': 4, 'Ti': 5}
            pth = thesis.get(prev['h']) if prev else None
            for key, i in idx.items():
                a = th[i + 2 * col]
                b = pth[i + 2 * col] if pth else None
                tho[key] = order(b, a, prev['h'], r['h']) if (a and b) else None
            thv = [th[i + 2 * col] for i in (0, 1, 4, 5)]
        orders.append((r['h'], o))
        print('  %-8g  %5d  %6d  %5.1fs  %s %s  %s %s  %s %s  %s %s  %s %s  | %s' % (
            r['h'], r['n'], r['steps'], r['secs'], fmt(e['u1']), ordfmt(o['u1']), fmt(e['ui']), ordfmt(o['ui']),
            fmt(e['T1']), ordfmt(o['T1']), fmt(e['Ti']), ordfmt(o['Ti']), fmt(e['Tlow']), fmt(e['Tup']),
            '%s %s, %s %s; %s %s, %s %s' % tuple(x for k, v in zip(('u1', 'ui', 'T1', 'Ti'), thv)
                                                  for x in (fmt(v), ordfmt(tho.get(k)))) if thv else '-'))
        prev = r
    print()
    return orders


def study(binp, work, variant, hs_aligned, hs_rot, href, schemes):
    ref = run(binp, os.path.join(work, '%s_aligned_%g' % (variant, href)), href, variant, False, 'Gauss upwind')
    prof = profile(ref)
    res = {}
    rows = []
    for h in hs_aligned:
        r = run(binp, os.path.join(work, '%s_aligned_%g' % (variant, h)), h, variant, False, 'Gauss upwind')
        r['e'] = errors(r, prof)
        rows.append(r)
    res['aligned'] = rows
    for k, scheme in schemes:
        rows = []
        for h in hs_rot:
            tag = k.split()[0]
            r = run(binp, os.path.join(work, '%s_rotated_%s_%g' % (variant, tag, h)), h, variant, True, scheme)
            r['e'] = errors(r, prof)
            rows.append(r)
        res[k] = rows
    return ref, res


def report(variant, ref, res, table_no):
    th = THESIS[variant.replace('UB', '')]
    print('=== Table %s, %s: reference grid-aligned upwind h = %g (%d cells, %d steps, %.1f s); '
          'u along the plates, T at t = %g' % (table_no, variant, ref['h'], ref['n'], ref['steps'], ref['secs'], TEND))
    o = {'aligned': table('grid-aligned, Gauss upwind (thesis: Cartesian)', res['aligned'], th, 0)}
    for k in res:
        if k != 'aligned':
            o[k] = table('rotated 23/13, cut + merged, shepard, Gauss %s (thesis: ICCM^MC_MS, upwind)' % k, res[k],
                         th, 1)
    return o


def plot(work, variant, ref, res):
    """WORK/<variant>_profiles.dat (the reference's and the finest rotated
    runs' cells: distance, u, T) and, with gnuplot, <variant>_profiles.png."""
    dat = os.path.join(work, variant + '_profiles.dat')
    blocks = [('aligned h = %g (reference)' % ref['h'], ref)] + [
        ('rotated %s h = %g' % (k, rows[-1]['h']), rows[-1]) for k, rows in res.items() if k != 'aligned' and rows]
    with open(dat, 'w') as f:
        for name, r in blocks:
            f.write('# %s: distance from the resting plate, u along the plates, T\n' % name)
            for d, u, T in sorted(zip(r['d'], r['u'], r['T'])):
                f.write('%.6g %.6g %.6g\n' % (d, u, T))
            f.write('\n\n')
    png = os.path.join(work, variant + '_profiles.png')
    styles = ['lines lw 2 lc rgb "black"', 'points pt 6 ps 0.5 lc rgb "red"', 'points pt 7 ps 0.4 lc rgb "blue"',
              'points pt 5 ps 0.3 lc rgb "dark-green"']
    cmds = ['set terminal pngcairo size 900,420 font ",9"', 'set output "%s"' % png, 'set multiplot layout 1,2',
            'set xlabel "distance from the resting plate [m]"', 'set key top left', 'set xrange [0:%g]' % W]
    for col, label in ((2, 'velocity along the plates [m/s]'), (3, 'granular temperature T [m^2/s^2]')):
        cmds += ['set title "%s, t = %g: %s"' % (variant, TEND, label.split(' [')[0]), 'set ylabel "%s"' % label,
                 'plot ' + ', '.join('"%s" index %d using 1:%d with %s title "%s"' % (dat, i, col, styles[i % 4], n)
                                     for i, (n, _) in enumerate(blocks))]
    cmds.append('unset multiplot')
    try:
        subprocess.run(['gnuplot'], input='\n'.join(cmds) + '\n', text=True, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        print('Profiles: %s (%s)' % (png, dat))
    except (OSError, subprocess.CalledProcessError):
        print('Profiles: %s (no gnuplot: no plot)' % dat)
    print()


def judge(name, ok, what):
    print('%s shearPlate_%s: %s' % ('PASS' if ok else 'FAIL', name, what))
    return 0 if ok else 1


def mean_order(rows, key):
    """The order between the coarsest and the finest h of rows."""
    a, b = rows[0], rows[-1]
    return order(a['e'][key], b['e'][key], a['h'], b['h'])


def quick(binp, work):
    """make test's study (about 30 s): noSlip aligned W/4, W/8 against W/16
    and rotated W/8 with both schemes; partialSlip aligned W/4, W/8 against
    W/16 with the thesis's wall heating and with wallVelocity boundary."""
    nfail = 0
    ref, res = study(binp, work, 'noSlip', [W / 4, W / 8], [W / 8], W / 16, SCHEMES)
    report('noSlip', ref, res, '5.5 (quick)')
    a, b = res['aligned']
    for key, what in (('u1', 'velocity L1'), ('T1', 'T L1')):
        o = order(a['e'][key], b['e'][key], a['h'], b['h'])
        nfail += judge('quick_aligned_%s_order' % key, o >= 0.8,
                       'grid-aligned %s order %.3f between h = W/4 and W/8 (want >= 0.8)' % (what, o))
        # velocity: measured 0.24 of upwind's; T: 0.69 with the heating's
        # metric Jacobian (0.33 with eq. 4.65's weight, doc/validation.md)
        up, ll = res['upwind'][0]['e'][key], res['limitedLinear 1'][0]['e'][key]
        bound = 0.6 if key == 'u1' else 0.8
        nfail += judge('quick_rotated_%s_limitedLinear' % key, ll <= bound * up,
                       'rotated h = W/8: %s limitedLinear 1 %.3e, upwind %.3e (want <= %g x upwind)'
                       % (what, ll, up, bound))
    err = {}
    for variant in ('partialSlip', 'partialSlipUB'):
        ref, res = study(binp, work, variant, [W / 4, W / 8], [], W / 16, [])
        report(variant, ref, res, '5.6 (quick)')
        err[variant] = res['aligned']
    a, b = err['partialSlipUB']
    o = order(a['e']['T1'], b['e']['T1'], a['h'], b['h'])
    nfail += judge('quick_partialSlip_boundary_T1_order', o >= 0.3,
                   'grid-aligned partialSlip, heatingSchemes wallVelocity boundary: T L1 order %.3f between h = W/4 '
                   'and W/8 (want >= 0.3)' % o)
    tw, tb = err['partialSlip'][1]['e']['T1'], b['e']['T1']
    nfail += judge('quick_partialSlip_wall_heating', tw >= 3 * tb,
                   'grid-aligned partialSlip at W/8: T L1 %.3e with the wall velocity u_S in the heating (the '
                   'thesis\'s), %.3e with u_B (want the first >= 3 x the second: the slip jump over h heats)' % (tw, tb))
    return nfail


def main():
    global JACOBIAN
    binp, work = sys.argv[1], sys.argv[2]
    args = [a for a in sys.argv[3:] if not a.startswith('jacobian=')]
    for a in sys.argv[3:]:
        if a.startswith('jacobian='):
            JACOBIAN = a.split('=', 1)[1]
    if args == ['quick']:
        return 1 if quick(binp, work) else 0
    nfail = 0
    hs = [0.01, 0.005, 0.0025]
    variants = [(v, no) for v, no in (('noSlip', '5.5'), ('partialSlip', '5.6'), ('partialSlipUB', '5.6, ours'),
                                      ('gravity', '5.7')) if not args or v in args]
    for variant, no in variants:
        ref, res = study(binp, work, variant, hs, hs, HREF[variant], SCHEMES_FULL)
        orders = report(variant, ref, res, no)
        plot(work, variant, ref, res)
        if variant == 'partialSlipUB':  # printed beside partialSlip, not judged (doc/validation.md)
            continue
        # grid-aligned: first order in L1 at the finest pair (T: not with
        # the thesis's wall heating at a sliding wall, which does not converge)
        for key, what in (('u1', 'velocity L1'), ('T1', 'T L1')):
            if variant == 'partialSlip' and key == 'T1':
                continue
            oa = orders['aligned'][-1][1][key]
            nfail += judge('%s_aligned_%s_order' % (variant, key), oa >= 0.8,
                           'grid-aligned %s order %.3f at h = %g (want >= 0.8)' % (what, oa, hs[-1]))
        # rotated, limitedLinear 1 and vanLeer: the velocity first order in
        # L1 over the range, and both errors at most half of upwind's at the
        # finest h
        for sk, tag in (('limitedLinear 1', 'limitedLinear'), ('vanLeer', 'vanLeer')):
            ou = mean_order(res[sk], 'u1')
            nfail += judge('%s_rotated_%s_u1_order' % (variant, tag), ou >= 0.8,
                           'rotated %s velocity L1 order %.3f from h = %g to %g (want >= 0.8)'
                           % (sk, ou, hs[0], hs[-1]))
            for key, what in (('u1', 'velocity L1'), ('T1', 'T L1')):
                up, ll = res['upwind'][-1]['e'][key], res[sk][-1]['e'][key]
                nfail += judge('%s_rotated_%s_%s_vs_upwind' % (variant, tag, key), ll <= 0.5 * up,
                               'rotated h = %g: %s %s %.3e, upwind %.3e (want <= 0.5 x upwind)'
                               % (hs[-1], what, sk, ll, up))
            print('rotated %s T L1 order from h = %g to %g: %.3f (not judged)' % (
                sk, hs[0], hs[-1], mean_order(res[sk], 'T1')))
        print()
    return 1 if nfail else 0


if __name__ == '__main__':
    sys.exit(main())
