"""The exceptions ARS raises, importable as ``ars.ArsError`` and so on.

They live in an importable module (not in the extension) so that pickling (Ray,
multiprocessing) rebuilds them as the same classes in other processes.
"""

__all__ = [
    "ArsError",
    "InputError",
    "InternalError",
    "ReproductionError",
    "SimulationError",
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


class UnknownNameError(ArsError, KeyError):
    """No object or joint has this name; the message lists names spelled almost the same."""

    def __str__(self):
        # KeyError quotes its argument; show the message as written.
        return str(self.args[0]) if self.args else ""


class SimulationError(ArsError):
    """The simulation cannot go on (a body diverged, ODE reported an error)."""


class InternalError(ArsError):
    """A bug in ARS (a Rust panic), caught before it reached Python: please report it."""


class ReproductionError(ArsError):
    """A run computed other bits than the ones recorded (``ars.rerun``): another
    platform, library or version of ARS; the message names both."""


for _cls in (
    ArsError,
    InputError,
    UnknownNameError,
    SimulationError,
    InternalError,
    ReproductionError,
):
    _cls.__module__ = "ars"
