"""gridcheck.py: what the grid tutorials' tests (test_grids.sh,
test_voronoiGrids.sh) check the same way: PASS/FAIL lines, numbers from
the logs, and the VTK file read back by VTK's own reader (in this
Python, or, when it has no VTK module, in ParaView's: see
tests/vtkpython.py).

    python3 gridcheck.py FILE THICK    prints vtk_stats(FILE, THICK)"""
import os
import re
import subprocess
import sys


def _stats_here(path, thick):
    """(cells, sum of polygon areas x thick, polygons not counter-clockwise
    seen from +z) of the legacy VTK file, read by this Python's VTK."""
    import vtk
    vtk.vtkObject.GlobalWarningDisplayOff()
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    grid = r.GetOutput()
    n = grid.GetNumberOfCells()
    v, nonpositive = 0.0, 0
    if thick > 0:
        for i in range(n):
            ids = grid.GetCell(i).GetPointIds()
            p = [grid.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
            a = 0.5 * sum(p[k][0] * p[k - len(p) + 1][1] - p[k - len(p) + 1][0] * p[k][1]
                          for k in range(len(p)))
            nonpositive += a <= 0
            v += a * thick
    return n, v, nonpositive


def vtk_stats(path, thick):
    """_stats_here in this Python, or in another with VTK (ParaView's
    pvpython) when this one has none; ImportError when none has."""
    try:
        import vtk  # noqa: F401
    except ImportError:
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
        import vtkpython
        py = vtkpython.other_python()
        if not py:
            raise
        out = subprocess.run([py, os.path.abspath(__file__), path, repr(thick)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, universal_newlines=True)
        if out.returncode != 0:
            raise RuntimeError("%s: %s" % (py, out.stderr.strip()[-300:]))
        n, v, nonpositive = out.stdout.split()[-3:]
        return int(n), float(v), int(nonpositive)
    return _stats_here(path, thick)


class Check:
    """Reports and logs of one tutorial case: lines "PASS <prefix>_<name>_<check>"."""

    def __init__(self, prefix, case, name):
        self.prefix, self.case, self.name = prefix, case, name

    def report(self, check, ok, why="", note=""):
        tag = "%s_%s_%s" % (self.prefix, self.name, check)
        if ok:
            print("PASS %s%s" % (tag, (": " + note) if note else ""))
        else:
            print("FAIL %s: %s" % (tag, why))

    def log(self, app):
        with open(os.path.join(self.case, "log." + app)) as f:
            return f.read()

    @staticmethod
    def number(pattern, text, what):
        m = re.search(pattern, text, re.M)
        if not m:
            raise ValueError("no %s in the log (pattern %r)" % (what, pattern))
        return m.group(1)

    def vtk_reader(self, ncells, fluid, thick, who):
        """VTK/<name>_0.vtk read by VTK's reader: ncells cells; in 2-D
        (thick > 0) the polygons, counter-clockwise seen from +z, times the
        thickness add up to the fluid volume (shoelace formula on the points
        the reader returns: VTK's own vtkCellSizeFilter gets non-convex
        polygons and polyhedra wrong, so 3-D checks the count only)."""
        try:
            path = os.path.join(self.case, "VTK", "%s_0.vtk" % self.name)
            if not os.path.isfile(path):
                raise OSError("no %s" % path)
            n, v, nonpositive = vtk_stats(path, thick)
            errs, note = [], "%d cells" % n
            if n != ncells or n == 0:
                errs.append("VTK's reader finds %d cells in %s, %s has %d" % (n, os.path.basename(path), who, ncells))
            if thick > 0:
                if nonpositive:
                    errs.append("%d polygons not counter-clockwise seen from +z" % nonpositive)
                if not abs(v - fluid) <= 1e-12 * fluid:
                    errs.append("sum(area) thickness = %.17g, the fluid volume %.17g" % (v, fluid))
                note += ", sum(area) thickness = fluid volume to %.1e" % (abs(v - fluid) / fluid)
            self.report("vtk_reader", not errs, "; ".join(errs), note)
        except ImportError as ex:
            print("SKIP %s_%s_vtk_reader: no VTK module for python3 (%s)" % (self.prefix, self.name, ex))
        except Exception as ex:   # any failure of the reader is a failure of the file
            self.report("vtk_reader", False, "%s: %s" % (type(ex).__name__, ex))


if __name__ == "__main__":
    print(*_stats_here(sys.argv[1], float(sys.argv[2])))
