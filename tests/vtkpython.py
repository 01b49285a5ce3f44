"""vtkpython.py: which Python reads VTK files for the tests.

VTK's Python module comes either from python3-vtk9 or from ParaView
(Debian's python3-paraview, which conflicts with python3-vtk9 and also
gives /usr/bin/python3 a `vtk` module; or a ParaView install whose
`pvpython` is on PATH).  The tests must use whichever is there and never
make the user swap one for the other.  The choice, in order:
$KIESEL_PYTHON if set, this interpreter when it imports vtk, `pvpython`
on PATH when it does; else this interpreter (the VTK checks then SKIP).

    python3 tests/vtkpython.py      prints the chosen interpreter (tests/run)

From a test script: `reexec_if_no_vtk()` before `import vtk` runs the
script again under the chosen interpreter when this one has no VTK;
`other_python()` names it for a subprocess (scripts read from stdin
cannot be re-executed)."""
import os
import shutil
import subprocess
import sys
import tempfile

_PROBE = "import vtk\nvtk.vtkUnstructuredGridReader()\n"


def _has_vtk(python):
    """True when python (a path) imports vtk.  The probe is a file, not -c:
    pvpython runs scripts like python but does not take every option."""
    with tempfile.TemporaryDirectory() as d:
        probe = os.path.join(d, "probe.py")
        with open(probe, "w") as f:
            f.write(_PROBE)
        try:
            return subprocess.run([python, probe], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                  timeout=120).returncode == 0
        except (OSError, subprocess.SubprocessError):
            return False


def _this_has_vtk():
    try:
        import vtk  # noqa: F401
        return True
    except ImportError:
        return False


def other_python():
    """An interpreter other than this one that imports vtk, or None."""
    for cand in (os.environ.get("KIESEL_PYTHON"), shutil.which("pvpython")):
        if cand and os.path.realpath(cand) != os.path.realpath(sys.executable) and _has_vtk(cand):
            return cand
    return None


def choose():
    """The interpreter the VTK checks run with (see the module comment)."""
    if os.environ.get("KIESEL_PYTHON"):
        return os.environ["KIESEL_PYTHON"]
    if _this_has_vtk():
        return sys.executable
    return other_python() or sys.executable


def reexec_if_no_vtk():
    """Runs the calling script again under other_python() when this
    interpreter has no VTK (once: KIESEL_VTK_REEXEC guards a loop);
    returns when this one has VTK or no other does."""
    if _this_has_vtk() or os.environ.get("KIESEL_VTK_REEXEC"):
        return
    py = other_python()
    if py:
        os.environ["KIESEL_VTK_REEXEC"] = "1"
        sys.stdout.flush()
        os.execv(py, [py, os.path.abspath(sys.argv[0])] + sys.argv[1:])


if __name__ == "__main__":
    print(choose())
