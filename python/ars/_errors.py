"""The exceptions ARS raises, importable as ``ars.ArsError`` and so on.

One class per cause, each also a Python built-in class where one fits, so that
``except ValueError`` or ``except OSError`` code keeps working:

- ``InputError`` (``ValueError``): a bad value (a negative radius, a NaN pose, a joint
  between an object and itself...); ``FormatError`` and ``UnknownKindError`` are kinds
  of it;
- ``UnknownKindError`` (``InputError``): a kind (of sensor, of controller) that does not
  exist; the message lists those that do;
- ``FormatError`` (``InputError``): a file that was read but is malformed (a scene file
  that is not JSON, a URDF joint without a child); ``filename``, ``position``,
  ``element`` and ``line`` say where;
- ``UnknownNameError`` (``KeyError``): no object or joint has this name (or it was
  removed);
- ``FileError`` (``OSError``): a file or folder that cannot be read or written, with
  ``errno``, ``strerror`` and ``filename`` set;
- ``SimulationError``: the simulation cannot go on (a body diverged, ODE reported an
  error, the simulation is poisoned); the same class every time for the same cause;
- ``BusyError`` (``RuntimeError``): the simulation is busy running the hook that makes
  the call (a hook that steps, shows or renders its own simulation);
- ``NoDisplayError`` (``RuntimeError``): a window cannot be opened: ``DISPLAY`` and
  ``WAYLAND_DISPLAY`` are unset, or the display refused the window (off-screen
  rendering, ``ars.Renderer``, needs no display);
- ``RendererError`` (``RuntimeError``): the renderer, the video encoder or a frame
  writer failed: its thread could not start, stopped or panicked, or the H.264 encoder
  could not start or encode a frame;
- ``InternalError``: a bug in ARS (a Rust panic);
- ``SnapshotError``: a snapshot that cannot be restored or taken, one class per cause:
  ``SnapshotMismatchError`` (a snapshot of another scene), ``SnapshotVersionError``
  (written by a version of ARS that this one does not read), ``SnapshotCorruptError``
  (also a ``ValueError``: truncated or altered bytes, or not a snapshot),
  ``NotCapturableError`` (something a snapshot cannot hold: a joint controller of your
  own type).

They live in an importable module (not in the extension) so that pickling (Ray,
multiprocessing) rebuilds them as the same classes in other processes.
"""

__all__ = [
    "ArsError",
    "BusyError",
    "FileError",
    "FormatError",
    "InputError",
    "InternalError",
    "NoDisplayError",
    "NotCapturableError",
    "RendererError",
    "ReproductionError",
    "SimulationError",
    "SnapshotCorruptError",
    "SnapshotError",
    "SnapshotMismatchError",
    "SnapshotVersionError",
    "UnknownKindError",
    "UnknownNameError",
]


class ArsError(Exception):
    """Base class of every error ARS raises. ``msg`` is its message (the original's
    attribute)."""

    @property
    def msg(self):
        return self.args[0] if self.args else None


class InputError(ArsError, ValueError):
    """Bad input: a negative radius, a NaN pose, a joint between a body and itself..."""


class UnknownKindError(InputError):
    """A kind (of sensor, of controller) that does not exist; the message lists those
    that do."""


class FormatError(InputError):
    """A file (or text) that is not what it should be: ``filename`` is the file (or
    ``"<string>"``), ``position`` where in it as the message says (``"line 3, column
    7"``, ``'joint "elbow"'``, ``"<geom> at line 12"``; empty for the whole file),
    ``element`` the element or named part it is about (``"<geom>"``, ``'link
    "gripper"'``; empty when none) and ``line`` its line, from 1 (``None`` when not
    known)."""

    filename = None
    position = ""
    element = ""
    line = None


class UnknownNameError(ArsError, KeyError):
    """No object or joint has this name; the message lists names spelled almost the same."""

    def __str__(self):
        # KeyError quotes its argument; show the message as written.
        return str(self.args[0]) if self.args else ""


class FileError(ArsError, OSError):
    """A file or folder that cannot be read or written. Built as
    ``FileError(errno, message, filename)``: ``errno`` is the system's error number
    (``None`` when there is none), ``strerror`` the whole message, ``filename`` the
    path."""

    @property
    def msg(self):
        return self.strerror

    def __str__(self):
        # OSError shows "[Errno 2] ...: 'path'"; the message already names both.
        return str(self.strerror) if self.strerror is not None else OSError.__str__(self)


class SimulationError(ArsError):
    """The simulation cannot go on: a body diverged, or ODE reported an internal error
    and the simulation is poisoned (every later step raises this class again)."""


class BusyError(ArsError, RuntimeError):
    """The simulation is busy running the hook that makes the call: a hook cannot step,
    show or render the simulation it runs in (do it between steps)."""


class NoDisplayError(ArsError, RuntimeError):
    """A window cannot be opened: ``DISPLAY`` and ``WAYLAND_DISPLAY`` are unset, or the
    display named would not open one (the message says what it said). Off-screen
    rendering (``ars.Renderer``, ``record_video``, ``save_replay``) needs no display."""


class RendererError(ArsError, RuntimeError):
    """The renderer, the video encoder or a frame writer failed: its thread could not
    start, stopped or panicked, or the H.264 encoder could not start or encode a frame.
    Nothing the caller passed was wrong."""


class InternalError(ArsError):
    """A bug in ARS (a Rust panic), caught before it reached Python: please report it."""


class ReproductionError(ArsError):
    """A run computed other bits than the ones recorded (``ars.rerun``): another
    platform, library or version of ARS; the message names both."""


class SnapshotError(ArsError):
    """A snapshot that cannot be taken or restored (one subclass per cause)."""


class SnapshotMismatchError(SnapshotError):
    """A snapshot of another scene: other objects, joints or sensors, or made in another
    order. Nothing was changed."""


class SnapshotVersionError(SnapshotError):
    """A snapshot written by a version of ARS whose format this one does not read."""


class SnapshotCorruptError(SnapshotError, ValueError):
    """Bytes that are not a whole snapshot: truncated, altered, or not a snapshot."""


class NotCapturableError(SnapshotError):
    """Something a snapshot cannot hold (a joint controller of your own type)."""


for _cls in (
    ArsError,
    InputError,
    UnknownKindError,
    FormatError,
    UnknownNameError,
    FileError,
    SimulationError,
    BusyError,
    NoDisplayError,
    RendererError,
    InternalError,
    ReproductionError,
    SnapshotError,
    SnapshotMismatchError,
    SnapshotVersionError,
    SnapshotCorruptError,
    NotCapturableError,
):
    _cls.__module__ = "ars"
