"""Joints of the original ARS API, reached as ``sim.get_joint(name).joint``: each sends
its signals around the torques, forces and speeds put on it."""

from operator import attrgetter

from ars.dispatch import heard, send
from ars.exceptions import JointError
from ars.model.robot import signals


class Joint:
    """A joint of a simulation (``native`` is its ``ars.Joint``)."""

    def __init__(self, native):
        self._native = native

    @property
    def name(self):
        return self._native.name


class Fixed(Joint):
    """Locks two bodies together."""


class BallSocket(Joint):
    """Three rotations about a point."""


class Universal(Joint):
    """Two rotations about perpendicular axes."""


class _Actuated(Joint):
    def _act(self, pre, post, key, value, action):
        """``action(value)``, between the signals ``pre`` and ``post`` (sent with
        ``key=value``) when someone hears either: a torque put every step with nobody
        listening costs the native call alone."""
        listened = heard(pre) or heard(post)
        if listened:
            send(pre, sender=self, **{key: value})
        try:
            action(value)
        except Exception as e:
            raise JointError(self, f"could not {key} {value!r}: {e}") from e
        if listened:
            send(post, sender=self, **{key: value})


class Rotary(_Actuated):
    """A hinge."""

    # Read by the native getters through ``attrgetter``, with no Python frame between:
    # a program reads its joints every step.
    angle = property(attrgetter("_native.angle"), doc="Angle, rad, in (−π, π].")
    angle_rate = property(attrgetter("_native.rate"), doc="Rate of the angle, rad/s.")

    def add_torque(self, torque):
        """Adds ``torque`` (N·m) about the axis for the next step."""
        # (A program's ``sim.get_joint(name).add_torque`` is one native call instead,
        # while nobody listens: see ``ars.model.simulator.SimulatedJoint``.)
        self._act(
            signals.JOINT_PRE_ADD_TORQUE,
            signals.JOINT_POST_ADD_TORQUE,
            "torque",
            torque,
            self._native.add_torque,
        )

    def set_speed(self, speed, max_force=None):
        """Drives the joint at ``speed`` (rad/s), with at most ``max_force`` (N·m; left
        as it was when ``None``)."""

        def drive(speed):
            if max_force is not None:
                self._native.set_param("max_force", max_force)
            self._native.set_param("velocity", speed)

        self._act(signals.JOINT_PRE_SET_SPEED, signals.JOINT_POST_SET_SPEED, "speed", speed, drive)


class Slider(_Actuated):
    """A prismatic joint."""

    @property
    def position(self):
        """Position along the axis, m."""
        return self._native.position

    @property
    def position_rate(self):
        """Its rate, m/s."""
        return self._native.rate

    def add_force(self, force):
        """Adds ``force`` (N) along the axis for the next step."""
        self._act(
            signals.JOINT_PRE_ADD_FORCE,
            signals.JOINT_POST_ADD_FORCE,
            "force",
            force,
            self._native.add_force,
        )
