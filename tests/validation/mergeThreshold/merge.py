"""Table 5.3 (thesis §5.1.4): the merge threshold M_V on the periodic
inclined channel.  The case is inclinedChannel/channel.py's (imported),
with system/mergeCellsDict's threshold set to M_V; each run with divSchemes
Gauss upwind (the thesis's convection, the PASS/FAIL lines) and again with
Gauss limitedLinear 1 (channel.SCHEMES; printed only).

usage: merge.py BIN WORKDIR INCLINEDCHANNELDIR
"""
import os, re, subprocess, sys, time

sys.path.insert(0, sys.argv[3])
import channel as ch

HDR = 'FoamFile { version 2.0; format ascii; class dictionary; object mergeCellsDict; }\n'
# (h, M_V): thesis L2, Linf, u_max, CPU ms (spec §5.1.4, Table 5.3)
RUNS = [(0.1, 2), (0.1, 16), (0.05, 2)]
THESIS = {(0.1, 2): (2.680e-4, 1.189e-2, 1.131, 1133), (0.05, 2): (3.309e-5, 4.966e-3, 1.173, 9493),
          (0.1, 16): (1.123e-4, 4.793e-3, 1.125, 9541)}

def courant_length(V, A):
    """min over cells of V / sum |S_f| (A: ch.cells): the length
    solveGranular's Courant rule (doc/tools/solveGranular.md) scales the
    step with; with the sound speed dominating |u_f . S_f| the step ratio
    of two grids is the ratio of their lengths."""
    return min(v / a for v, a in zip(V, A))

def run(binp, d, h, inv, scheme):
    ch.write_case(d, h, False, scheme)
    open(os.path.join(d, 'system/mergeCellsDict'), 'w').write(HDR + 'threshold %r;\n' % (1.0 / inv))
    secs = 0.0
    for tool in ('blockGrid', 'cutCells', 'mergeCells', 'solveGranular'):
        t0 = time.time()
        with open(os.path.join(d, 'log.' + tool), 'w') as log:
            if subprocess.call([os.path.join(binp, tool), '-case', d], stdout=log, stderr=subprocess.STDOUT):
                sys.exit('FAIL mergeThreshold: %s failed in %s' % (tool, d))
        secs = time.time() - t0
    log = open(os.path.join(d, 'log.solveGranular')).read()
    steps = len(re.findall(r'^Time = ', log, re.M))
    dts = [float(x) for x in re.findall(r'^deltaT = (\S+)', log, re.M)]
    dm = max(abs(float(x)) for x in re.findall(r'change since start = (\S+)', log))
    m = re.search(r'unresolved cells:\s+(\d+)', open(os.path.join(d, 'log.mergeCells')).read())
    V, A = ch.cells(d)
    return dict(ch.errors(d, V), lc=courant_length(V, A), secs=secs, steps=steps, dtend=dts[-1],
                vmin=min(V) / (h * h * h), dm=dm, unres=int(m.group(1)) if m else 0)

def table(res, label):
    print('  %s' % label)
    print('  h      M_V    cells  min V/h^3  L2N (thesis L2)         L2          Linf (thesis)           u_max (thesis)    '
          'steps  dt(t=2)    solveGranular s (thesis CPU s)')
    for h, inv in RUNS:
        r, t = res[(h, inv)], THESIS[(h, inv)]
        print('  %-5g  1/%-3d  %5d  %.4f     %.3e (%.3e)   %.3e   %.3e (%.3e)   %.4f (%.3f)   %5d  %.3e  %6.2f (%.3f)%s' % (
            h, inv, r['n'], r['vmin'], r['l2n'], t[0], r['l2'], r['li'], t[1], r['umax'], t[2], r['steps'], r['dtend'],
            r['secs'], t[3] / 1000.0, '  (%d unmerged cells)' % r['unres'] if r['unres'] else ''))
    a, b, c = res[(0.1, 2)], res[(0.1, 16)], res[(0.05, 2)]
    print()
    print('  steps M_V 1/16 : 1/2 at h = 0.1: %.2f; dt(t=2) ratio %.2f; smallest cell ratio %.2f '
          '(thesis: dt about 8x smaller; CPU 9541/1133 = %.2f)' % (
        b['steps'] / a['steps'], a['dtend'] / b['dtend'], a['vmin'] / b['vmin'], 9541 / 1133.0))
    print('  steps h 0.05 : h 0.1 at M_V 1/2: %.2f; time %.2f (thesis CPU %.2f)' % (
        c['steps'] / a['steps'], c['secs'] / a['secs'], 9493 / 1133.0))
    print('  time M_V 1/16 : h 0.05 (thesis: about equal, 9541/9493 = %.2f): %.2f' % (9541 / 9493.0, b['secs'] / c['secs']))
    print()

def main():
    binp, work = sys.argv[1], sys.argv[2]
    res = {k: {} for k, _ in ch.SCHEMES}
    for k, scheme in ch.SCHEMES:
        tag = '' if k == 'upwind' else '_' + scheme.split()[1]
        for h, inv in RUNS:
            res[k][(h, inv)] = run(binp, os.path.join(work, 'h%g_MV1_%d%s' % (h, inv, tag)), h, inv, scheme)
    print('Table 5.3: merge threshold M_V, periodic inclined channel (slope %d/%d, multilinear, maxCo 0.25, t = 2)'
          % (ch.P, ch.Q))
    for k, scheme in ch.SCHEMES:
        table(res[k], 'divSchemes %s%s' % (scheme, ' (the thesis\'s convection)' if k == 'upwind' else ''))
    up = res['upwind']
    a, b = up[(0.1, 2)], up[(0.1, 16)]
    ratio, pred = b['steps'] / a['steps'], a['lc'] / b['lc']
    nfail = 0
    ok = abs(ratio / pred - 1) <= 0.1
    nfail += not ok
    print('%s mergeThreshold_step_ratio: steps(M_V 1/16) / steps(M_V 1/2) = %d / %d = %.2f, the Courant rule\'s '
          'min V/sum|S_f| ratio %.4e / %.4e = %.2f (tolerance 10 %%; the thesis: 8, a step proportional to the '
          'smallest volume fraction, %.2f here)' % ('PASS' if ok else 'FAIL', b['steps'], a['steps'], ratio,
                                                     a['lc'], b['lc'], pred, a['vmin'] / b['vmin']))
    dm = max(r['dm'] for rk in res.values() for r in rk.values())
    ok = dm <= 1e-12
    nfail += not ok
    print('%s mergeThreshold_mass: largest relative mass change over all steps of the %d runs %.1e (tolerance 1e-12)'
          % ('PASS' if ok else 'FAIL', sum(len(rk) for rk in res.values()), dm))
    return 1 if nfail else 0

if __name__ == '__main__':
    sys.exit(main())
