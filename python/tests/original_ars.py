"""The original ARS 0.5b1, fetched from PyPI, for the tests that run its demos on our
package and compare with what it prints itself.

- ``sdist()`` downloads ``ARS==0.5b1`` once (``pip download``; cached under
  ``$ARS_TEST_CACHE``, default ``~/.cache/ars-tests``) and unpacks it.
- ``demos()`` lists the 30 entries of its ``demo_runner.py`` (read with ``ast``).
- ``run_ours(module, cls, seconds)`` runs one demo, unedited, on our ``ars`` package
  in a child process; ``run_original(...)`` runs it on the original package with
  Debian's PyODE (``python3-pyode``), after the Python 3 syntax fixes its bundled
  PyDispatcher needs and the ``Mass.setCapsule*`` aliases that old PyODE lacks.
"""

import ast
import os
import pathlib
import re
import shutil
import subprocess
import sys
import zipfile

SDIST = "ARS==0.5b1"
ORIGINAL_PYTHON = "/usr/bin/python3"  # Debian's, with python3-pyode and python3-numpy
CACHE = pathlib.Path(os.environ.get("ARS_TEST_CACHE", pathlib.Path.home() / ".cache" / "ars-tests"))


def sdist():
    """The unpacked sdist (its root holds ``ars/``, ``demos/`` and ``demo_runner.py``)."""
    root = CACHE / "ARS-0.5b1"
    if (root / "demo_runner.py").is_file():
        return root
    CACHE.mkdir(parents=True, exist_ok=True)
    archives = list(CACHE.glob("ARS-0.5b1.*"))
    if not archives:
        subprocess.run(
            [
                sys.executable,
                "-m",
                "pip",
                "download",
                "--quiet",
                "--no-deps",
                "--no-binary",
                ":all:",
                SDIST,
                "-d",
                str(CACHE),
            ],
            check=True,
        )
        archives = list(CACHE.glob("ARS-0.5b1.*"))
    with zipfile.ZipFile(archives[0]) as z:
        z.extractall(CACHE)
    return root


def demos():
    """``[(module, class), ...]``: the demo runner's list, in its order."""
    tree = ast.parse((sdist() / "demo_runner.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
            getattr(t, "id", None) == "DEMOS" for t in node.targets
        ):
            return ast.literal_eval(node.value)
    raise AssertionError("demo_runner.py has no DEMOS list")


def demos_only(workdir):
    """A folder holding only the sdist's ``demos`` package (not its ``ars``)."""
    target = pathlib.Path(workdir) / "demos-only"
    if not target.exists():
        shutil.copytree(sdist() / "demos", target / "demos")
    return target


_RUN = """
import importlib, sys
module, name, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
program = getattr(importlib.import_module("demos." + module), name)()
{run}
final = getattr(program, "print_final_data", None)
if final is not None:
    final()
"""

OURS = _RUN.format(run="program.run(seconds)")
ORIGINAL = _RUN.format(
    run="""
for _ in range(round(seconds * program.FPS)):
    program.sim.on_idle()
"""
)

# What the original needs to run headless under Python 3 on Debian's PyODE: a stand-in
# for VTK (its viewer), and two Mass methods under the names this PyODE has.
ORIGINAL_PRELUDE = """
import sys, types
import ode

class _Mass(ode.Mass):
    def setCapsule(self, *a):
        return self.setCappedCylinder(*a)
    def setCapsuleTotal(self, *a):
        return self.setCappedCylinderTotal(*a)

ode.Mass = _Mass

class _Anything:
    def __init__(self, *a, **k):
        pass
    def __getattr__(self, name):
        if name == "GetNextProp3D":
            return lambda *a, **k: None
        return lambda *a, **k: _Anything()

vtk = types.ModuleType("vtk")
vtk.__getattr__ = lambda name: type(name, (_Anything,), {})
sys.modules["vtk"] = vtk
"""

# Python 2 → 3, only the syntax and library renames the demos reach.
FIXES = [
    (
        r"^(\s*)import saferef, robustapply, errors$",
        r"\1from . import saferef, robustapply, errors",
    ),
    (r"^from (dispatcher|robustapply) import", r"from .\1 import"),
    (r"except (\w+), (\w+):", r"except \1 as \2:"),
    (r"for arg in named\.keys\(\):", r"for arg in list(named.keys()):"),
    (r"\.iteritems\(\)", r".items()"),
    (r"itertools\.imap\(", r"map("),
    (r"operator\.div\b", r"operator.truediv"),
    (r"print '''(.*?)'''%\((.*?)\n(\s*)\)", r"print('''\1'''%(\2\n\3))"),
]


def original_tree(workdir):
    """A copy of the sdist with the Python 3 fixes applied."""
    target = pathlib.Path(workdir) / "original"
    if target.exists():
        return target
    shutil.copytree(sdist(), target, ignore=shutil.ignore_patterns("*.pyc", "__pycache__"))
    for path in (target / "ars").rglob("*.py"):
        text = path.read_text()
        fixed = text
        for pattern, replacement in FIXES:
            fixed = re.sub(pattern, replacement, fixed, flags=re.MULTILINE | re.DOTALL)
        if fixed != text:
            path.write_text(fixed)
    return target


def run_ours(module, name, seconds, workdir, env=None):
    return subprocess.run(
        [sys.executable, "-c", OURS, module, name, str(seconds)],
        cwd=demos_only(workdir),
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
        env=env,
    )


# Two bugs of Debian's PyODE 1.2.0.dev15 that ODE's own bindings (which ARS was written
# for) do not have: Mass.setSphereTotal takes the mass as a density (it calls
# dMassSetSphere), and the joint parameter numbers are those of ODE 0.12 (ParamFMax = 3
# is dParamLoVel in ODE 0.16, where dParamFMax is 5), so a motor's force limit is never
# set. Fixed here, the original runs as on the bindings it was written for.
BINDING_FIXES = """
def _set_sphere_total(self, total_mass, radius):
    inertia = 0.4 * total_mass * radius * radius
    self.setParameters(total_mass, 0.0, 0.0, 0.0, inertia, inertia, inertia, 0.0, 0.0, 0.0)

_Mass.setSphereTotal = _set_sphere_total
ode.ParamFMax = 5
"""


def run_original(module, name, seconds, workdir, fixed_bindings=False, env=None):
    """The original on Debian's PyODE (``fixed_bindings``: with its two bugs fixed)."""
    prelude = ORIGINAL_PRELUDE + (BINDING_FIXES if fixed_bindings else "")
    return subprocess.run(
        [ORIGINAL_PYTHON, "-c", prelude + ORIGINAL, module, name, str(seconds)],
        cwd=original_tree(workdir),
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
        env=env,
    )
