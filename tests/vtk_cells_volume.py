"""vtk_cells_volume.py FILE VOLUME: reads a legacy .vtk file with VTK's
own reader and prints "<cells> <volume> <|volume - VOLUME|>", the volume
summed from every cell's faces by the divergence theorem, so a missing
or flipped face shows.  Used by the grid tools' tests.  Without a VTK
module in this Python it runs itself under ParaView's (vtkpython.py)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtkpython  # noqa: E402

vtkpython.reexec_if_no_vtk()
import vtk  # noqa: E402

r = vtk.vtkUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
g = r.GetOutput()
n = g.GetNumberOfCells()
vol = 0.0
for i in range(n):
    c = g.GetCell(i)
    for k in range(c.GetNumberOfFaces()):
        pts = c.GetFace(k).GetPoints()
        x = [pts.GetPoint(j) for j in range(pts.GetNumberOfPoints())]
        for j in range(len(x)):
            a, b = x[j], x[(j + 1) % len(x)]
            s = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
            vol += sum(x[0][d] * s[d] for d in range(3)) / 6.0
print(n, vol, abs(vol - float(sys.argv[2])))
