"""ARS: a physically accurate robotics simulator on the Open Dynamics Engine.

>>> import ars
>>> sim = ars.Simulation()
>>> sim.add_floor()
'floor'
>>> ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
>>> sim.run(0.1)
>>> bool(sim.body(ball).position[1] < 1.0)
True
"""

# Imported under private names: `dir(ars)` and completion show ARS's own names only.
import atexit as _atexit
import importlib as _importlib
import os as _os

from ars import _native
from ars._errors import (
    ArsError,
    BusyError,
    FileError,
    FormatError,
    InputError,
    InternalError,
    NoDisplayError,
    NotCapturableError,
    RendererError,
    ReproductionError,
    SimulationError,
    SnapshotCorruptError,
    SnapshotError,
    SnapshotMismatchError,
    SnapshotVersionError,
    UnknownKindError,
    UnknownNameError,
)
from ars._native import (
    Body,
    Joint,
    Renderer,
    Sensor,
    Simulation,
    VideoWriter,
    __version__,
    has_display,
    step_many,
)

# Not `from typing import TYPE_CHECKING`: typing takes a fifth of the package's import
# time, and no program needs it at run time (type checkers read this name as true).
TYPE_CHECKING = False
if TYPE_CHECKING:
    from ars.display import Image, Replay
    from ars.sweeps import RunResult, SweepResults, load_sweep, rerun, sweep

# Imported when first used: both import numpy, which takes longer than the rest of
# the package (a program that never makes an image or a sweep does not wait for it).
_LATER = {
    "Image": "ars.display",
    "Replay": "ars.display",
    "RunResult": "ars.sweeps",
    "SweepResults": "ars.sweeps",
    "load_sweep": "ars.sweeps",
    "rerun": "ars.sweeps",
    "sweep": "ars.sweeps",
}


def __getattr__(name: str) -> object:
    module = _LATER.get(name)
    if module is None:
        raise AttributeError(f"module 'ars' has no attribute {name!r}")
    value = getattr(_importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    # The public names, the submodules imported and the module's dunders; not the
    # private helpers (`_native`, `_os`...) nor TYPE_CHECKING.
    names = set(globals()) | set(_LATER)
    return sorted(
        n for n in names if (n.startswith("__") or not n.startswith("_")) and n != "TYPE_CHECKING"
    )


# Mesa's Vulkan device-selection layer asks libwayland for a display whenever Vulkan
# lists its devices; with no Wayland display and no XDG_RUNTIME_DIR (Xvfb, CI, ssh -X)
# libwayland prints "error: XDG_RUNTIME_DIR is invalid..." four times per renderer or
# window. The viewer's own switch-off only runs in a single-threaded program; a Python
# process may run threads, so the package applies it here, before any rendering.
if _native._device_select_would_print():
    _os.environ["NODEVICE_SELECT"] = "1"

# The viewer keeps the rendering context of its windows for the next one; it is given
# back before the interpreter's threads end.
_atexit.register(_native._release_viewer)

__all__ = [
    "ArsError",
    "Body",
    "BusyError",
    "FileError",
    "FormatError",
    "Image",
    "InputError",
    "InternalError",
    "Joint",
    "NoDisplayError",
    "NotCapturableError",
    "Renderer",
    "RendererError",
    "Replay",
    "ReproductionError",
    "RunResult",
    "Sensor",
    "Simulation",
    "SimulationError",
    "SnapshotCorruptError",
    "SnapshotError",
    "SnapshotMismatchError",
    "SnapshotVersionError",
    "SweepResults",
    "UnknownKindError",
    "UnknownNameError",
    "VideoWriter",
    "__version__",
    "has_display",
    "load_sweep",
    "rerun",
    "step_many",
    "sweep",
]
