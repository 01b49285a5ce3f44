"""grainStats.py GRID: the grains in the drum at every time of
GRID/VTK/GRID.vtk.series, read with VTK's own reader, to
GRID/postProcessing/grains.csv:

    time, mass, x_cm, y_cm, z_cm, angle, rMean, omega, dense, denseAngle,
    alphaMax

mass = sum of alpha V over the cells (the grains' volume: Kiesel's
masses are divided by the grain density), (x_cm, y_cm, z_cm) their
centre of mass, angle = atan2(y_cm, -z_cm) in degrees: 0 when the grains
lie at the bottom of the drum, positive when the drum (turning about +x,
its bottom moving towards +y) has dragged them up its +y side.  rMean is
the grains' mean distance from the axis (mass-weighted), omega their
mean angular velocity about +x, sum m (y U_z - z U_y) / sum m r^2 (their
angular momentum over their moment of inertia: the drum's 10 pi = 31.4
rad/s for grains turning with it as a rigid body).  dense is the volume
of the cells with alpha >= c0 = 0.3 (the packed fill, yield on),
denseAngle the same angle for their centroid, alphaMax the largest
alpha.  Cell volumes and centroids come from each cell's faces
(tetrahedra on the cell's first point: exact for planar faces), once,
from the first file: the grid does not change.

Needs VTK's Python module (no numpy): the Allrun runs it with the first
of $KIESEL_PYTHON, python3, /usr/bin/python3, pvpython that imports it."""
import json
import math
import os
import sys

import vtk


def read(path):
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.ReadAllScalarsOn()
    r.ReadAllVectorsOn()
    r.Update()
    return r.GetOutput()


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def triple(a, b, c):
    return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0])


def volumes_centroids(g):
    """Each cell's volume and centroid from its faces."""
    vol, cen = [], []
    for i in range(g.GetNumberOfCells()):
        c = g.GetCell(i)
        p = c.GetPoints().GetPoint(0)
        v = 0.0
        m = [0.0, 0.0, 0.0]
        for k in range(c.GetNumberOfFaces()):
            fp = c.GetFace(k).GetPoints()
            x = [fp.GetPoint(j) for j in range(fp.GetNumberOfPoints())]
            for j in range(1, len(x) - 1):
                t = triple(sub(x[0], p), sub(x[j], p), sub(x[j + 1], p)) / 6.0
                v += t
                for d in range(3):
                    m[d] += t * (p[d] + x[0][d] + x[j][d] + x[j + 1][d]) / 4.0
        vol.append(abs(v))
        cen.append([m[d] / v for d in range(3)] if v != 0 else list(p))
    return vol, cen


def angle(y, z):
    return math.degrees(math.atan2(y, -z))


def main():
    grid = sys.argv[1]
    with open(os.path.join(grid, "VTK", grid + ".vtk.series")) as f:
        series = json.load(f)["files"]
    vol = cen = None
    rows = []
    for entry in series:
        g = read(os.path.join(grid, "VTK", entry["name"]))
        if vol is None:
            vol, cen = volumes_centroids(g)
        arr = g.GetCellData().GetArray("alpha")
        uarr = g.GetCellData().GetArray("U")
        mass, dense, amax, rsum, lsum, isum = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        mc = [0.0, 0.0, 0.0]
        dc = [0.0, 0.0, 0.0]
        for i in range(len(vol)):
            a = arr.GetValue(i)
            amax = max(amax, a)
            mass += a * vol[i]
            y, z = cen[i][1], cen[i][2]
            u = uarr.GetTuple3(i)
            rsum += a * vol[i] * math.hypot(y, z)
            lsum += a * vol[i] * (y * u[2] - z * u[1])
            isum += a * vol[i] * (y * y + z * z)
            for d in range(3):
                mc[d] += a * vol[i] * cen[i][d]
            if a >= 0.3:
                dense += vol[i]
                for d in range(3):
                    dc[d] += vol[i] * cen[i][d]
        mc = [q / mass for q in mc]
        da = angle(dc[1], dc[2]) if dense > 0 else float("nan")
        rows.append((entry["time"], mass, mc[0], mc[1], mc[2], angle(mc[1], mc[2]), rsum / mass, lsum / isum, dense, da, amax))
    os.makedirs(os.path.join(grid, "postProcessing"), exist_ok=True)
    out = os.path.join(grid, "postProcessing", "grains.csv")
    with open(out + ".tmp", "w") as f:
        f.write("time,mass,x_cm,y_cm,z_cm,angle,rMean,omega,dense,denseAngle,alphaMax\n")
        for r in rows:
            f.write("%.6g,%.10g,%.6f,%.6f,%.6f,%.3f,%.6f,%.4f,%.6g,%.3f,%.6f\n" % r)
    os.replace(out + ".tmp", out)
    print("%s: %d times, cell volumes sum to %.10g" % (out, len(rows), sum(vol)))


main()
