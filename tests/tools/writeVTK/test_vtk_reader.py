#!/usr/bin/python3
"""test_vtk_reader.py: writeVTK's files read back by VTK's own legacy readers.

Cases are written here as OpenFOAM polyMesh files (a graded box, optionally
with pairs of cells merged into one 10-face polyhedron, 2-D or 3-D), with
nonuniform p and U in three time directories.  writeVTK converts them
(binary and ascii); vtkUnstructuredGridReader / vtkPolyDataReader read the
result.  Checks, with tolerances: cell and point counts, cell types (7 in
2-D; 12 for hexahedra, 42 for merged cells in 3-D), every cell volume and
the total (vtkCellSizeFilter; 2-D: area * thickness) against the exact
value (1e-12 relative), field arrays (names, components, values to 1e-12
relative: doubles), TimeValue, 2-D polygons counter-clockwise about +z,
patch values from the boundary conditions, volume-weighted point data, and
the .vtk.series JSON.  If $KIESEL_BIN/blockGrid exists, a blockGrid case is
converted too.  The case writer is also used by test_writeVTK.sh
(write_case).
"""
import json
import math
import os
import subprocess
import sys

BIN = os.environ.get("KIESEL_BIN", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "bin"))
TOL = 1e-12

HEADER = """FoamFile
{
    version     2.0;
    format      ascii;
    class       %s;
    object      %s;
}
"""


def graded(n, lo, hi, ratio):
    """n+1 coordinates from lo to hi, each cell `ratio` times the previous."""
    w = [ratio ** i for i in range(n)]
    s = sum(w)
    x = [lo]
    for wi in w:
        x.append(x[-1] + (hi - lo) * wi / s)
    x[-1] = hi
    return x


class Box:
    """A rectilinear polyMesh; merge lists pairs of +x neighbours (i, j, k)
    to fuse into one cell."""

    def __init__(self, xs, ys, zs, two_d=False, merge=()):
        self.xs, self.ys, self.zs, self.two_d = xs, ys, zs, two_d
        nx, ny, nz = len(xs) - 1, len(ys) - 1, len(zs) - 1
        self.n = (nx, ny, nz)
        key = {}
        for (i, j, k) in merge:
            key[(i + 1, j, k)] = (i, j, k)
        ids, cells = {}, []  # cells: list of lists of (i,j,k)
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    root = key.get((i, j, k), (i, j, k))
                    if root not in ids:
                        ids[root] = len(cells)
                        cells.append([])
                    cells[ids[root]].append((i, j, k))
        self.cells = cells
        self.cell_of = {ijk: ids[key.get(ijk, ijk)] for ijk in
                        ((i, j, k) for k in range(nz) for j in range(ny) for i in range(nx))}
        self.points = [(xs[i], ys[j], zs[k]) for k in range(nz + 1) for j in range(ny + 1)
                       for i in range(nx + 1)]
        self._faces()

    def pid(self, i, j, k):
        nx, ny, _ = self.n
        return i + (nx + 1) * (j + (ny + 1) * k)

    def quad(self, a, i, j, k):
        """Face normal to axis a at low corner (i,j,k), normal +a."""
        p = self.pid
        if a == 0:
            return [p(i, j, k), p(i, j + 1, k), p(i, j + 1, k + 1), p(i, j, k + 1)]
        if a == 1:
            return [p(i, j, k), p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j, k)]
        return [p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k)]

    def _faces(self):
        nx, ny, nz = self.n
        internal, bnd = [], {"left": [], "right": [], "walls": [], "frontAndBack": []}
        side = {(0, 0): "left", (0, 1): "right", (1, 0): "walls", (1, 1): "walls",
                (2, 0): "frontAndBack", (2, 1): "frontAndBack"}
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    c = self.cell_of[(i, j, k)]
                    ijk = (i, j, k)
                    for a in range(3):
                        hi = list(ijk)
                        hi[a] += 1
                        q = self.quad(a, *hi)
                        if hi[a] == self.n[a]:
                            bnd[side[(a, 1)]].append((c, q))
                        elif self.cell_of[tuple(hi)] != c:
                            d = self.cell_of[tuple(hi)]
                            internal.append((c, d, q) if c < d else (d, c, q[::-1]))
                        if ijk[a] == 0:
                            bnd[side[(a, 0)]].append((c, self.quad(a, *ijk)[::-1]))
        internal.sort(key=lambda t: (t[0], t[1]))
        self.internal = internal
        self.patches = []
        for name in ("left", "right", "walls", "frontAndBack"):
            typ = {"left": "patch", "right": "patch", "walls": "wall",
                   "frontAndBack": "empty" if self.two_d else "wall"}[name]
            fs = sorted(bnd[name], key=lambda t: t[0])
            self.patches.append((name, typ, fs))

    def cell_volume(self, c):
        xs, ys, zs = self.xs, self.ys, self.zs
        return sum((xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * (zs[k + 1] - zs[k])
                   for (i, j, k) in self.cells[c])

    def cell_centre(self, c):
        v = self.cell_volume(c)
        xs, ys, zs = self.xs, self.ys, self.zs
        s = [0.0, 0.0, 0.0]
        for (i, j, k) in self.cells[c]:
            w = (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * (zs[k + 1] - zs[k])
            s[0] += w * 0.5 * (xs[i] + xs[i + 1])
            s[1] += w * 0.5 * (ys[j] + ys[j + 1])
            s[2] += w * 0.5 * (zs[k] + zs[k + 1])
        return [x / v for x in s]

    def ncells(self):
        return len(self.cells)

    def write(self, case):
        d = os.path.join(case, "constant", "polyMesh")
        os.makedirs(d, exist_ok=True)
        faces = [q for (_, _, q) in self.internal]
        owner = [o for (o, _, _) in self.internal]
        for (_, _, fs) in self.patches:
            faces += [q for (_, q) in fs]
            owner += [c for (c, _) in fs]
        with open(os.path.join(d, "points"), "w") as f:
            f.write(HEADER % ("vectorField", "points"))
            f.write("%d\n(\n" % len(self.points))
            f.writelines("(%.17g %.17g %.17g)\n" % p for p in self.points)
            f.write(")\n")
        with open(os.path.join(d, "faces"), "w") as f:
            f.write(HEADER % ("faceList", "faces"))
            f.write("%d\n(\n" % len(faces))
            f.writelines("%d(%s)\n" % (len(q), " ".join(map(str, q))) for q in faces)
            f.write(")\n")
        for name, vals in (("owner", owner), ("neighbour", [n for (_, n, _) in self.internal])):
            with open(os.path.join(d, name), "w") as f:
                f.write(HEADER % ("labelList", name))
                f.write("%d\n(\n%s\n)\n" % (len(vals), "\n".join(map(str, vals))))
        with open(os.path.join(d, "boundary"), "w") as f:
            f.write(HEADER % ("polyBoundaryMesh", "boundary"))
            f.write("%d\n(\n" % len(self.patches))
            start = len(self.internal)
            for (name, typ, fs) in self.patches:
                f.write("    %s\n    {\n        type %s;\n        nFaces %d;\n        startFace %d;\n    }\n"
                        % (name, typ, len(fs), start))
                start += len(fs)
            f.write(")\n")


def p_value(x, t):
    return 1.0 / 3.0 + x[0] + 2 * x[1] + 3 * x[2] + t


def u_value(x, t):
    return [x[1] - 0.1 * t, -x[0] / 7.0, x[2] * math.pi]


def write_field(path, cls, name, values, patches, two_d):
    fmt = (lambda v: "%.17g" % v) if cls == "volScalarField" else \
        (lambda v: "(%.17g %.17g %.17g)" % tuple(v))
    kind = "scalar" if cls == "volScalarField" else "vector"
    with open(path, "w") as f:
        f.write(HEADER % (cls, name))
        f.write("dimensions [0 1 -1 0 0 0 0];\n\n")
        f.write("internalField nonuniform List<%s>\n%d\n(\n" % (kind, len(values)))
        f.writelines(fmt(v) + "\n" for v in values)
        f.write(")\n;\n\nboundaryField\n{\n")
        for (pname, ptype, _) in patches:
            if ptype == "empty":
                bc = "type empty;"
            elif pname == "left":
                bc = "type fixedValue; value uniform %s;" % ("2" if kind == "scalar" else "(1 0 0)")
            elif pname == "walls" and kind == "vector":
                bc = "type noSlip;"
            else:
                bc = "type zeroGradient;"
            f.write("    %s { %s }\n" % (pname, bc))
        f.write("}\n")


def write_case(case, box, times=((0.0, "0", None), (0.1, "0.1", 10), (0.25, "0.25", 25))):
    """Mesh, controlDict and p/U at each (time, name, index) (index None: no
    uniform/time).  Returns the exact cell values per time name."""
    box.write(case)
    os.makedirs(os.path.join(case, "system"), exist_ok=True)
    with open(os.path.join(case, "system", "controlDict"), "w") as f:
        f.write(HEADER % ("dictionary", "controlDict"))
        f.write("application none;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 1;\n"
                "deltaT 0.01;\nwriteControl timeStep;\nwriteInterval 1;\nwriteFormat ascii;\n"
                "writePrecision 17;\ntimeFormat general;\ntimePrecision 6;\n")
    schemes = {"fvSchemes": "".join("%s { default none; }\n" % k for k in (
        "ddtSchemes", "gradSchemes", "divSchemes", "laplacianSchemes", "interpolationSchemes",
        "snGradSchemes")), "fvSolution": "solvers { }\n"}
    for sub, body in schemes.items():
        with open(os.path.join(case, "system", sub), "w") as f:
            f.write(HEADER % ("dictionary", sub) + body)
    values = {}
    for (t, name, index) in times:
        d = os.path.join(case, name)
        os.makedirs(d, exist_ok=True)
        cc = [box.cell_centre(c) for c in range(box.ncells())]
        p = [p_value(x, t) for x in cc]
        u = [u_value(x, t) for x in cc]
        write_field(os.path.join(d, "p"), "volScalarField", "p", p, box.patches, box.two_d)
        write_field(os.path.join(d, "U"), "volVectorField", "U", u, box.patches, box.two_d)
        if index is not None:
            os.makedirs(os.path.join(d, "uniform"), exist_ok=True)
            with open(os.path.join(d, "uniform", "time"), "w") as f:
                f.write(HEADER % ("dictionary", "time"))
                f.write('value %.17g;\nname "%s";\nindex %d;\ndeltaT 0.01;\ndeltaT0 0.01;\n' % (t, name, index))
        values[name] = (t, p, u)
    return values


# ---- checks ----

results = []


def check(name, ok, why=""):
    results.append((name, bool(ok), why))
    print(("PASS %s" % name) if ok else ("FAIL %s: %s" % (name, why)))
    sys.stdout.flush()


def close(a, b, tol=TOL):
    return abs(a - b) <= tol * max(1.0, abs(b))


def run_tool(args):
    r = subprocess.run([os.path.join(BIN, "writeVTK")] + args, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def read_grid(path):
    import vtk
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def read_poly(path):
    import vtk
    r = vtk.vtkPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def sizes(grid, what):
    import vtk
    f = vtk.vtkCellSizeFilter()
    f.SetInputData(grid)
    f.Update()
    a = f.GetOutput().GetCellData().GetArray(what)
    return [a.GetValue(i) for i in range(a.GetNumberOfTuples())]


def face_stream_volume(cell):
    """Volume of a polyhedron from its faces alone (divergence theorem,
    sum of x.S/3 over faces with outward area vectors S), and its openness
    |sum S| / sum |S|.  Unlike vtkCellSizeFilter, which triangulates the
    cell's points, this sees a missing or flipped face."""
    vol, tot, area = 0.0, [0.0, 0.0, 0.0], 0.0
    for k in range(cell.GetNumberOfFaces()):
        pts = cell.GetFace(k).GetPoints()
        x = [pts.GetPoint(i) for i in range(pts.GetNumberOfPoints())]
        n = len(x)
        sf = [0.0, 0.0, 0.0]
        for i in range(n):
            a, b = x[i], x[(i + 1) % n]
            sf[0] += 0.5 * (a[1] * b[2] - a[2] * b[1])
            sf[1] += 0.5 * (a[2] * b[0] - a[0] * b[2])
            sf[2] += 0.5 * (a[0] * b[1] - a[1] * b[0])
        vol += sum(x[0][d] * sf[d] for d in range(3)) / 3.0
        tot = [tot[d] + sf[d] for d in range(3)]
        area += math.sqrt(sum(v * v for v in sf))
    return vol, math.sqrt(sum(v * v for v in tot)) / max(area, 1e-300)


def array(data, name):
    a = data.GetArray(name)
    if a is None:
        return None, 0
    nc = a.GetNumberOfComponents()
    return [a.GetTuple(i) for i in range(a.GetNumberOfTuples())], nc


def check_fields(tag, data, p, u):
    pa, pn = array(data, "p")
    ua, un = array(data, "U")
    check(tag + "_arrays", pn == 1 and un == 3 and data.GetNumberOfArrays() == 2,
          "p %d comps, U %d comps, %d arrays" % (pn, un, data.GetNumberOfArrays()))
    if pa is None or ua is None:
        return
    bad = [i for i in range(len(p)) if not close(pa[i][0], p[i])]
    bad += [i for i in range(len(u)) if not all(close(ua[i][k], u[i][k]) for k in range(3))]
    check(tag + "_values", len(pa) == len(p) and not bad, "cells differ: %s" % bad[:5])


def check_case(tag, case, box, values, ascii):
    rc, out, err = run_tool(["-case", case] + (["-ascii"] if ascii else []))
    check(tag + "_runs", rc == 0 and "End" in out, "rc %d: %s" % (rc, err.strip()))
    if rc:
        return
    cname = os.path.basename(os.path.abspath(case))
    nc = box.ncells()
    nx, ny, nz = box.n
    vol_total = (box.xs[-1] - box.xs[0]) * (box.ys[-1] - box.ys[0]) * (box.zs[-1] - box.zs[0])
    index = {"0": 0, "0.1": 10, "0.25": 25}
    for name, (t, p, u) in sorted(values.items()):
        path = os.path.join(case, "VTK", "%s_%d.vtk" % (cname, index[name]))
        g = read_grid(path)
        tt = "%s_t%s" % (tag, name)
        npts = (nx + 1) * (ny + 1) if box.two_d else len(box.points)
        check(tt + "_counts", g.GetNumberOfCells() == nc and g.GetNumberOfPoints() == npts,
              "%d cells %d points, expected %d %d" % (g.GetNumberOfCells(), g.GetNumberOfPoints(), nc, npts))
        types = [g.GetCellType(i) for i in range(g.GetNumberOfCells())]
        if box.two_d:
            want = [7] * nc
        else:
            want = [12 if len(box.cells[c]) == 1 else 42 for c in range(nc)]
        check(tt + "_types", types == want, "types %s" % sorted(set(types)))
        if box.two_d:
            thick = box.zs[1] - box.zs[0]
            vols = [a * thick for a in sizes(g, "Area")]
        else:
            vols = sizes(g, "Volume")
        exact = [box.cell_volume(c) for c in range(nc)]
        bad = [c for c in range(min(nc, len(vols))) if not close(vols[c], exact[c])]
        check(tt + "_cell_volumes", len(vols) == nc and not bad,
              "cells %s: %s vs %s" % (bad[:3], [vols[c] for c in bad[:3]], [exact[c] for c in bad[:3]]))
        if not box.two_d:
            poly = [c for c in range(nc) if types[c] == 42]
            fs = [face_stream_volume(g.GetCell(c)) for c in poly]
            bad = [(c, v, o) for c, (v, o) in zip(poly, fs) if not close(v, exact[c]) or o > TOL]
            check(tt + "_polyhedra_closed_outward", len(poly) == 2 and not bad,
                  "%d polyhedra; (cell, volume, openness) %s" % (len(poly), bad[:3]))
        check(tt + "_total_volume", close(sum(vols), vol_total),
              "%.17g vs %.17g" % (sum(vols), vol_total))
        tv = g.GetFieldData().GetArray("TimeValue")
        check(tt + "_TimeValue", tv is not None and tv.GetValue(0) == t,
              "TimeValue %s" % (tv.GetValue(0) if tv else None))
        check_fields(tt, g.GetCellData(), p, u)
        if box.two_d:
            zmin = min(g.GetPoint(i)[2] for i in range(g.GetNumberOfPoints()))
            zmax = max(g.GetPoint(i)[2] for i in range(g.GetNumberOfPoints()))
            ccw = True
            for c in range(nc):
                ids = g.GetCell(c).GetPointIds()
                pts = [g.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
                a = sum(pts[k][0] * pts[(k + 1) % len(pts)][1] - pts[(k + 1) % len(pts)][0] * pts[k][1]
                        for k in range(len(pts)))
                ccw = ccw and a > 0
            check(tt + "_lower_side_ccw", ccw and zmin == zmax == box.zs[0], "z %g..%g" % (zmin, zmax))
        # patches: left fixedValue (p 2, U (1 0 0)), right zeroGradient, walls noSlip U
        for (pname, ptype, fs) in box.patches:
            ppath = os.path.join(case, "VTK", pname, "%s_%d.vtk" % (pname, index[name]))
            if ptype == "empty":
                check(tt + "_no_" + pname, not os.path.exists(ppath), "empty patch written")
                continue
            pd = read_poly(ppath)
            pp, _ = array(pd.GetCellData(), "p")
            pu, _ = array(pd.GetCellData(), "U")
            ok = pd.GetNumberOfCells() == len(fs) and pp is not None and len(pp) == len(fs)
            for i, (c, _) in enumerate(fs if ok else []):
                wp = 2.0 if pname == "left" else p[c]
                wu = [1, 0, 0] if pname == "left" else [0, 0, 0] if pname == "walls" else u[c]
                ok = ok and close(pp[i][0], wp) and all(close(pu[i][k], wu[k]) for k in range(3))
            check(tt + "_patch_" + pname, ok, "%d polygons for %d faces, or values differ"
                  % (pd.GetNumberOfCells(), len(fs)))
    with open(os.path.join(case, "VTK", cname + ".vtk.series")) as f:
        s = json.load(f)
    want = [{"name": "%s_%d.vtk" % (cname, index[n]), "time": values[n][0]}
            for n in sorted(values, key=lambda n: values[n][0])]
    check(tag + "_series", s.get("file-series-version") == "1.0" and s.get("files") == want,
          "series %s" % s)
    with open(os.path.join(case, "VTK", "left", "left.vtk.series")) as f:
        s = json.load(f)
    check(tag + "_patch_series", [e["name"] for e in s["files"]] == ["left_0.vtk", "left_10.vtk", "left_25.vtk"],
          "series %s" % s)


def check_point_data(tag, case, box, values):
    """-pointData: each point's value is the volume-weighted mean of the
    cells around it (2-D: the cells whose lower face holds it)."""
    rc, out, err = run_tool(["-case", case, "-pointData", "-latestTime", "-noBoundary"])
    check(tag + "_runs", rc == 0, err.strip())
    if rc:
        return
    cname = os.path.basename(os.path.abspath(case))
    g = read_grid(os.path.join(case, "VTK", "%s_25.vtk" % cname))
    t, p, u = values["0.25"]
    acc, wsum = {}, {}
    nx, ny, nz = box.n
    for c in range(box.ncells()):
        pts = set()
        for (i, j, k) in box.cells[c]:
            for dk in ((0,) if box.two_d else (0, 1)):
                for dj in (0, 1):
                    for di in (0, 1):
                        pts.add(box.points[box.pid(i + di, j + dj, k + dk)])
        v = box.cell_volume(c)
        for x in pts:
            acc[x] = acc.get(x, 0.0) + v * p[c]
            wsum[x] = wsum.get(x, 0.0) + v
    pa, pn = array(g.GetPointData(), "p")
    ua, un = array(g.GetPointData(), "U")
    ok = pa is not None and len(pa) == g.GetNumberOfPoints() == len(acc) and un == 3
    bad = []
    for i in range(g.GetNumberOfPoints() if ok else 0):
        x = g.GetPoint(i)
        if not close(pa[i][0], acc[x] / wsum[x]):
            bad.append((x, pa[i][0], acc[x] / wsum[x]))
    check(tag + "_values", ok and not bad, "points %s" % bad[:3])


def blockgrid_case(case):
    """A graded 3-D blockGrid case without fields: cell count, types and
    volume of the mesh alone (time 0, no time directory)."""
    os.makedirs(os.path.join(case, "system"), exist_ok=True)
    with open(os.path.join(case, "system", "blockGridDict"), "w") as f:
        f.write(HEADER % ("dictionary", "blockGridDict"))
        f.write("x { start 0; segments ((1 5 3)); }\ny { start -1; segments ((1 4 0.5)); }\n"
                "z { start 0; segments ((0.5 3 1)); }\n")
    with open(os.path.join(case, "system", "controlDict"), "w") as f:
        f.write(HEADER % ("dictionary", "controlDict"))
        f.write("application none;\nstartTime 0;\nendTime 1;\ndeltaT 1;\nwriteInterval 1;\n")
    r = subprocess.run([os.path.join(BIN, "blockGrid"), "-case", case], capture_output=True, text=True)
    check("blockGrid_case_made", r.returncode == 0, r.stderr.strip())
    if r.returncode:
        return
    rc, out, err = run_tool(["-case", case])
    check("blockGrid_case_runs", rc == 0, err.strip())
    if rc:
        return
    g = read_grid(os.path.join(case, "VTK", "%s_0.vtk" % os.path.basename(case)))
    types = set(g.GetCellType(i) for i in range(g.GetNumberOfCells()))
    vols = sizes(g, "Volume")
    check("blockGrid_case_hexahedra", g.GetNumberOfCells() == 60 and types == {12} and g.GetNumberOfPoints() == 120,
          "%d cells %s, %d points" % (g.GetNumberOfCells(), types, g.GetNumberOfPoints()))
    check("blockGrid_case_volume", close(sum(vols), 1.0 * 2.0 * 0.5), "volume %.17g" % sum(vols))
    check("blockGrid_case_no_fields", g.GetCellData().GetNumberOfArrays() == 0
          and g.GetFieldData().GetArray("TimeValue").GetValue(0) == 0.0, "arrays or time")


def main():
    try:
        import vtk  # noqa: F401
    except ImportError:
        print("SKIP vtk_reader: python3 vtk module missing")
        return 0
    if not os.access(os.path.join(BIN, "writeVTK"), os.X_OK):
        print("FAIL vtk_reader: %s/writeVTK not built" % BIN)
        return 1
    tmp = os.environ.get("KIESEL_TMP") or os.getcwd()
    xs, ys, zs = graded(4, 0.0, 1.0, 1.5), graded(3, -0.5, 0.5, 0.7), graded(2, 0.0, 0.3, 2.0)
    box3 = Box(xs, ys, zs, merge=[(0, 0, 0), (2, 1, 1)])
    box2 = Box(xs, ys, [0.0, 0.125], two_d=True)
    for ascii in (False, True):
        kind = "ascii" if ascii else "binary"
        c3 = os.path.join(tmp, "box3d_" + kind)
        check_case("3d_" + kind, c3, box3, write_case(c3, box3), ascii)
        c2 = os.path.join(tmp, "box2d_" + kind)
        check_case("2d_" + kind, c2, box2, write_case(c2, box2), ascii)
    check_point_data("pointData_3d", os.path.join(tmp, "box3d_binary"), box3,
                     write_case(os.path.join(tmp, "box3d_binary"), box3))
    check_point_data("pointData_2d", os.path.join(tmp, "box2d_ascii"), box2,
                     write_case(os.path.join(tmp, "box2d_ascii"), box2))
    if os.access(os.path.join(BIN, "blockGrid"), os.X_OK):
        blockgrid_case(os.path.join(tmp, "blockGridCase"))
    else:
        print("SKIP blockGrid_case: %s/blockGrid not built" % BIN)
    return 0 if all(ok for (_, ok, _) in results) else 1


if __name__ == "__main__":
    sys.exit(main())
