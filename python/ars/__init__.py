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

import atexit

from ars import _native
from ars._errors import ArsError, InputError, InternalError, SimulationError, UnknownNameError
from ars._native import Body, Joint, Renderer, Sensor, Simulation, __version__, has_display
from ars.sweeps import RunResult, SweepResults, sweep

# The viewer keeps the rendering context of its windows for the next one; it is given
# back before the interpreter's threads end.
atexit.register(_native._release_viewer)

__all__ = [
    "ArsError",
    "Body",
    "InputError",
    "InternalError",
    "Joint",
    "Renderer",
    "RunResult",
    "Sensor",
    "Simulation",
    "SimulationError",
    "SweepResults",
    "UnknownNameError",
    "__version__",
    "has_display",
    "sweep",
]
