"""The exceptions of the original ARS API (``import ars.exceptions as exc``), in the one
hierarchy under ``ars.ArsError``."""

from ars._errors import ArsError, InputError, InternalError, SimulationError, UnknownNameError

__all__ = [
    "ArsError",
    "InputError",
    "InternalError",
    "JointError",
    "PhysicsEngineException",
    "PhysicsObjectCreationError",
    "SimulationError",
    "UnknownNameError",
]


class PhysicsEngineException(ArsError):
    """An error of the physics engine."""


class JointError(PhysicsEngineException):
    """An error acting on ``joint``."""

    def __init__(self, joint, msg=None):
        super().__init__(msg)
        self.joint = joint


class PhysicsObjectCreationError(PhysicsEngineException):
    """An object of type ``type_`` could not be created."""

    def __init__(self, type_, msg=None):
        super().__init__(msg)
        self.type = type_


for _cls in (PhysicsEngineException, JointError, PhysicsObjectCreationError):
    _cls.__module__ = "ars.exceptions"
