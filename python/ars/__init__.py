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

from ars._errors import ArsError, InputError, InternalError, SimulationError, UnknownNameError
from ars._native import Body, Joint, Renderer, Sensor, Simulation, __version__, has_display
from ars.sweeps import RunResult, SweepResults, sweep

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
