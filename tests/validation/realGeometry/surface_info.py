"""surface_info.py FILE: bounding box and enclosed volume of a closed
triangulated surface (STL ascii/binary, OBJ; optionally gzipped), for the
real-geometry study.  Prints: xmin ymin zmin xmax ymax zmax volume.
The volume is the divergence-theorem sum over the triangles (OBJ polygons
fanned), so it is exact for the polyhedron the file describes."""
import gzip, struct, sys

def opener(path):
    return gzip.open(path, 'rb') if path.endswith('.gz') else open(path, 'rb')

def triangles_obj(data):
    v, tris = [], []
    for line in data.decode('latin-1').splitlines():
        w = line.split()
        if not w: continue
        if w[0] == 'v': v.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == 'f':
            idx = [int(t.split('/')[0]) for t in w[1:]]
            idx = [i - 1 if i > 0 else len(v) + i for i in idx]
            for k in range(1, len(idx) - 1): tris.append((v[idx[0]], v[idx[k]], v[idx[k + 1]]))
    return tris

def triangles_stl(data):
    if len(data) >= 84:
        n = struct.unpack('<I', data[80:84])[0]
        if 84 + 50 * n == len(data):
            out = []
            for i in range(n):
                f = struct.unpack('<12f', data[84 + 50 * i:84 + 50 * i + 48])
                out.append((f[3:6], f[6:9], f[9:12]))
            return out
    pts = [tuple(float(x) for x in l.split()[1:4]) for l in data.decode('latin-1').splitlines() if l.strip().startswith('vertex')]
    return [tuple(pts[i:i + 3]) for i in range(0, len(pts), 3)]

path = sys.argv[1]
data = opener(path).read()
tris = triangles_obj(data) if '.obj' in path else triangles_stl(data)
lo = [min(p[k] for t in tris for p in t) for k in range(3)]
hi = [max(p[k] for t in tris for p in t) for k in range(3)]
vol = 0.0
for a, b, c in tris:
    vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
print(*lo, *hi, abs(vol))
