#!/usr/bin/env python3
"""siloDischarge: the grains above and below the orifice at every time.

Usage: python3 hopperMass.py [CASE]   (default: the current directory)

Reads the case's constant/polyMesh (ascii: points, faces, owner,
neighbour) and alpha of every time directory, and prints one line per
time, sorted:
    t  hopper  bin  total
where hopper is the integral of alpha over the cells whose centroid lies
above the orifice plane y = Y_ORIFICE, bin over the others and total over
all, each divided by the grid's thickness in z: grain area per unit depth
(m^2), the 2-D mass over the grains' density.  Cell volumes and centroids
are exact for the cut grid's planar faces: each face is a fan of
triangles about its first corner (area vector and centroid), each cell a
set of pyramids on its faces about the mean of its face centroids.
Python's standard library only.
"""
import os
import re
import sys

Y_ORIFICE = 0.44  # the orifice plane (constant/geometry/silo.geo)


def foam_list(path):
    """The tokens of the first list of an OpenFOAM ascii file: the text
    after the FoamFile header from the count up to the matching ')'."""
    with open(path) as f:
        text = f.read()
    text = re.sub(r"//.*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    i = text.find("FoamFile")
    if i >= 0:
        text = text[text.index("}", i) + 1:]
    m = re.search(r"(\d+)\s*\(", text)
    if not m:
        raise SystemExit(f"{path}: no list found")
    return int(m.group(1)), text[m.end():]


def read_points(path):
    n, body = foam_list(path)
    v = [float(x) for x in re.findall(r"[-+0-9.eE]+", body.split("\n)")[0])]
    return [tuple(v[3 * i:3 * i + 3]) for i in range(n)]


def read_faces(path):
    n, body = foam_list(path)
    faces = [[int(x) for x in m.split()] for m in re.findall(r"\d+\s*\(([^)]*)\)", body)[:n]]
    if len(faces) != n:
        raise SystemExit(f"{path}: {len(faces)} faces read, {n} announced")
    return faces


def read_labels(path):
    n, body = foam_list(path)
    return [int(x) for x in body.split(")")[0].split()[:n]]


def face_geometry(pts, face):
    """Area vector and centroid of a planar polygon (fan about corner 0)."""
    p0 = pts[face[0]]
    s = [0.0, 0.0, 0.0]
    c = [0.0, 0.0, 0.0]
    a_sum = 0.0
    for k in range(1, len(face) - 1):
        p1, p2 = pts[face[k]], pts[face[k + 1]]
        u = [p1[i] - p0[i] for i in range(3)]
        w = [p2[i] - p0[i] for i in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        a = 0.5 * (n[0] ** 2 + n[1] ** 2 + n[2] ** 2) ** 0.5
        for i in range(3):
            s[i] += 0.5 * n[i]
            c[i] += a * (p0[i] + p1[i] + p2[i]) / 3
        a_sum += a
    return s, [ci / a_sum for ci in c]


def cells(mesh):
    pts = read_points(os.path.join(mesh, "points"))
    faces = read_faces(os.path.join(mesh, "faces"))
    owner = read_labels(os.path.join(mesh, "owner"))
    neigh = read_labels(os.path.join(mesh, "neighbour"))
    ncell = max(owner) + 1
    geo = [face_geometry(pts, f) for f in faces]
    cell_faces = [[] for _ in range(ncell)]
    for f, o in enumerate(owner):
        cell_faces[o].append((f, 1.0))
    for f, nb in enumerate(neigh):
        cell_faces[nb].append((f, -1.0))
    vol, yc = [], []
    for cf in cell_faces:
        x0 = [sum(geo[f][1][i] for f, _ in cf) / len(cf) for i in range(3)]
        v_sum, y_sum = 0.0, 0.0
        for f, sign in cf:
            s, c = geo[f]
            v = sign * sum(s[i] * (c[i] - x0[i]) for i in range(3)) / 3  # pyramid on the face
            v_sum += v
            y_sum += v * (0.75 * c[1] + 0.25 * x0[1])
        vol.append(v_sum)
        yc.append(y_sum / v_sum)
    zs = [p[2] for p in pts]
    return vol, yc, max(zs) - min(zs)


def read_alpha(path, ncell):
    with open(path) as f:
        text = f.read()
    m = re.search(r"internalField\s+uniform\s+([-+0-9.eE]+)", text)
    if m:
        return [float(m.group(1))] * ncell
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(([^)]*)\)", text)
    if not m or int(m.group(1)) != ncell:
        raise SystemExit(f"{path}: no internalField of {ncell} values")
    return [float(x) for x in m.group(2).split()]


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "."
    vol, yc, dz = cells(os.path.join(case, "constant", "polyMesh"))
    times = []
    for d in os.listdir(case):
        try:
            times.append((float(d), d))
        except ValueError:
            continue
    print("# t hopper bin total   (grain area per unit depth, m^2; hopper: cells above y = %g)" % Y_ORIFICE)
    for t, d in sorted(times):
        path = os.path.join(case, d, "alpha")
        if not os.path.exists(path):
            continue
        a = read_alpha(path, len(vol))
        top = sum(ai * vi for ai, vi, y in zip(a, vol, yc) if y > Y_ORIFICE) / dz
        low = sum(ai * vi for ai, vi, y in zip(a, vol, yc) if y <= Y_ORIFICE) / dz
        print("%-8s %.10g %.10g %.10g" % (d, top, low, top + low))


if __name__ == "__main__":
    main()
