"""Sensors of the original ARS API (``from ars.model.robot import sensors``).

A source sensor measures when told to: ``sensor.on_change(time)`` puts one
:class:`SensorData` in ``sensor.data_queue`` (and sends ``SENSOR_PRE_ON_CHANGE`` /
``SENSOR_POST_ON_CHANGE``). A signal sensor (``JointTorque``, ``JointForce``,
``JointPower``) records every torque or force put on its joint, stamped with the
simulation's time. Records are keyword values (``'position'``, ``'torque'``...), in
the units of the simulation (m, s, rad, N, J, W).
"""

import time as _time

from ars.dispatch import Any, connect, send
from ars.model.robot import signals
from ars.utils import mathematical as mut
from ars.utils.geometry import calc_rotation_matrix

__all__ = [
    "GPS",
    "Accelerometer",
    "BaseSignalSensor",
    "BaseSourceSensor",
    "BodySensor",
    "Inclinometer",
    "JointForce",
    "JointPower",
    "JointTorque",
    "KineticEnergy",
    "Laser",
    "PotentialEnergy",
    "RotaryJointSensor",
    "SensorData",
    "SensorDataQueue",
    "SystemTotalEnergy",
    "TotalEnergy",
    "Velometer",
]


class SensorData:
    """One record: positional and keyword values, and the time it was taken."""

    def __init__(self, *args, **kwargs):
        self._time = None
        self._args = args
        self._kwargs = kwargs

    def get_time(self):
        return self._time

    def set_time(self, time):
        self._time = time

    def get_args(self):
        return self._args

    def get_kwargs(self):
        return self._kwargs

    def get_arg(self, index):
        return self._args[index]

    def get_kwarg(self, key):
        return self._kwargs[key]

    def __str__(self):
        line = "|" if self._time is None else f" {self._time:f} |"
        for arg in self._args:
            line += f" {arg} |"
        for key, value in self._kwargs.items():
            line += f" {key}: {value} |"
        return line


class SensorDataQueue:
    """Records in the order taken."""

    def __init__(self):
        self._items = []

    def put(self, item):
        self._items.append(item)

    def pull(self):
        """Takes out and returns the oldest record."""
        if not self._items:
            raise IndexError("no elements are present")
        return self._items.pop(0)

    def is_empty(self):
        return not self._items

    def count(self):
        return len(self._items)

    def clear(self):
        self._items.clear()

    def convert_to_list(self):
        return list(self._items)

    def __str__(self):
        return "".join(f"{item}\n" for item in self._items)


class BaseSourceSensor:
    """A sensor that measures its source when :meth:`on_change` is called."""

    def __init__(self, source):
        self._source = source
        self.data_queue = SensorDataQueue()

    @property
    def source(self):
        return self._source

    def on_change(self, time=None):
        """Measures now; the record's time is ``time`` (the computer's clock if
        ``None``)."""
        send(signals.SENSOR_PRE_ON_CHANGE, sender=self, time=time)
        if time is None:
            time = _time.time()
        data = self._build_data()
        data.set_time(time)
        self.data_queue.put(data)
        send(signals.SENSOR_POST_ON_CHANGE, sender=self, data=data)

    def get_measurement(self):
        return self._build_data()

    def _build_data(self):
        raise NotImplementedError


class BodySensor(BaseSourceSensor):
    """Measures a body (a ``SimulatedBody``)."""

    @property
    def body(self):
        return self._source


class JointSensor(BaseSourceSensor):
    """Measures a joint (``sim.get_joint(name).joint``)."""

    @property
    def joint(self):
        return self._source


class SimulationSensor(BaseSourceSensor):
    """Measures a whole simulation."""

    @property
    def sim(self):
        return self._source


class GPS(BodySensor):
    """Position, m."""

    def _build_data(self):
        return SensorData(position=self.body.get_position())


class Velometer(BodySensor):
    """Linear (m/s) and angular (rad/s) velocity, world frame."""

    def _build_data(self):
        return SensorData(
            **{
                "linear velocity": self.body.get_linear_velocity(),
                "angular velocity": self.body.get_angular_velocity(),
            }
        )


class Accelerometer(BodySensor):
    """Linear (m/s²) and angular (rad/s²) acceleration, from the change of velocity
    since the previous measurement over ``time_step`` (``None`` the first time)."""

    def __init__(self, body, time_step):
        super().__init__(body)
        self._time_step = time_step

    def _build_data(self):
        linear0, angular0 = self.body.get_saved_velocities()
        linear1, angular1 = self.body.get_linear_velocity(), self.body.get_angular_velocity()
        self.body.save_velocities()
        return SensorData(
            **{
                "linear acceleration": mut.calc_acceleration(self._time_step, linear0, linear1),
                "angular acceleration": mut.calc_acceleration(self._time_step, angular0, angular1),
            }
        )


class Inclinometer(BodySensor):
    """Pitch and roll, rad: the angles the body's local X and Z axes make with the
    horizontal plane (Y up)."""

    def _build_data(self):
        rot = self.body.get_rotation()
        x_axis, z_axis = (rot[0], rot[3], rot[6]), (rot[2], rot[5], rot[8])
        pitch = mut.pi / 2 - mut.acos_dot3(x_axis, (0.0, 1.0, 0.0))
        roll = mut.pi / 2 - mut.acos_dot3(z_axis, (0.0, 1.0, 0.0))
        return SensorData(pitch=pitch, roll=roll)


class KineticEnergy(BodySensor):
    """Translational and rotational kinetic energy, J."""

    def _build_data(self):
        return SensorData(
            **{
                "translation energy": self.body.calc_translation_kinetic_energy(),
                "rotation energy": self.body.calc_rotation_kinetic_energy(),
            }
        )


class PotentialEnergy(BodySensor):
    """Potential energy in ``gravity``, J (zero at the origin's height)."""

    def __init__(self, body, gravity):
        super().__init__(body)
        self._gravity = gravity

    def _build_data(self):
        return SensorData(**{"potential energy": self.body.calc_potential_energy(self._gravity)})


def _energies(body, gravity):
    kinetic = body.calc_translation_kinetic_energy() + body.calc_rotation_kinetic_energy()
    return body.calc_potential_energy(gravity), kinetic


class TotalEnergy(BodySensor):
    """Potential plus kinetic energy, J (apart with ``disaggregate``)."""

    def __init__(self, body, gravity, disaggregate=False):
        super().__init__(body)
        self._gravity = gravity
        self._disaggregate = disaggregate

    def _build_data(self):
        potential, kinetic = _energies(self.body, self._gravity)
        if self._disaggregate:
            return SensorData(**{"potential energy": potential, "kinetic energy": kinetic})
        return SensorData(**{"total energy": potential + kinetic})


class SystemTotalEnergy(SimulationSensor):
    """The total energy of every body of the simulation, J."""

    def __init__(self, sim, disaggregate=False):
        super().__init__(sim)
        self._disaggregate = disaggregate

    def _build_data(self):
        gravity = self.sim.gravity
        potential = kinetic = 0.0
        for body in self.sim.get_bodies():
            p, k = _energies(body, gravity)
            potential += p
            kinetic += k
        if self._disaggregate:
            return SensorData(**{"potential energy": potential, "kinetic energy": kinetic})
        return SensorData(**{"total energy": potential + kinetic})


class RotaryJointSensor(JointSensor):
    """Angle (rad) and its rate (rad/s) of a rotary joint."""

    def _build_data(self):
        return SensorData(angle=self.joint.angle, angle_rate=self.joint.angle_rate)


class Ray:
    """A laser's ray: a position and a rotation; it points along its local +Z."""

    def __init__(self, space, length):
        self._space = space
        self._sim = space._sim  # the simulation it is part of (for the dispatcher)
        self.length = length
        self._position = (0.0, 0.0, 0.0)
        self._rotation = calc_rotation_matrix((1.0, 0.0, 0.0), 0.0)
        self.hit = None

    def get_position(self):
        return self._position

    def set_position(self, pos):
        self._position = tuple(pos)

    def get_rotation(self):
        return self._rotation

    def set_rotation(self, rot):
        self._rotation = tuple(rot)

    def clear_contacts(self):
        self.hit = None


class Laser(BaseSourceSensor):
    """A ray of ``max_distance`` (m): the distance to what it meets (``None`` if
    nothing), measured on the poses the step's collision detection sees."""

    def __init__(self, space, max_distance=10.0):
        self._ray = Ray(space, max_distance)
        super().__init__(self._ray)
        space.rays.append(self)

    def _cast(self):
        # Called by the simulation right before each step's collision detection.
        ray = self._ray
        sim = ray._space.simulation
        if sim is None:
            return
        direction = mut.z_axis(ray.get_rotation())
        hit = sim.native.cast_ray(ray.get_position(), direction, ray.length)
        if hit is not None:
            ray.hit = hit[0]

    def on_change(self, time=None):
        super().on_change(time)
        self._ray.clear_contacts()

    def set_position(self, pos):
        self._ray.set_position(pos)

    def set_rotation(self, rot):
        self._ray.set_rotation(rot)

    def get_ray(self):
        return self._ray

    def _build_data(self):
        return SensorData(distance=self._ray.hit)


class BaseSignalSensor:
    """A sensor that records a signal sent by ``sender`` (``Any``: every sender)."""

    any_sender = Any

    def __init__(self, sender=Any, autotime=False):
        self._sender = sender
        self._autotime = autotime
        self.data_queue = SensorDataQueue()

    @property
    def sender(self):
        return self._sender

    def on_send(self, sender, *args, **kwargs):
        data = self._build_data(sender, *args, **kwargs)
        time = self._get_time()
        if time is not None:
            data.set_time(time)
        self.data_queue.put(data)

    def _get_time(self):
        return _time.time() if self._autotime else None

    def _build_data(self, sender, *args, **kwargs):
        raise NotImplementedError


class _JointSignalSensor(BaseSignalSensor):
    signals_heard = ()

    def __init__(self, sim_joint, sim):
        super().__init__(sender=sim_joint.joint)
        self._sim = sim
        for signal in self.signals_heard:
            connect(self.on_send, signal=signal, sender=self._sender)

    def _get_time(self):
        return self._sim.sim_time


class JointTorque(_JointSignalSensor):
    """Every torque added to a rotary joint, N·m."""

    signal = signals.JOINT_POST_ADD_TORQUE
    signals_heard = (signal,)

    def _build_data(self, sender, *args, **kwargs):
        return SensorData(torque=kwargs.get("torque"))


class JointForce(_JointSignalSensor):
    """Every force added to a slider, N."""

    signal = signals.JOINT_POST_ADD_FORCE
    signals_heard = (signal,)

    def _build_data(self, sender, *args, **kwargs):
        return SensorData(force=kwargs.get("force"))


class JointPower(_JointSignalSensor):
    """The power of every torque (or force) added to a joint, W: torque × rate."""

    signals_heard = (JointTorque.signal, JointForce.signal)

    def _build_data(self, sender, *args, **kwargs):
        power = 0.0
        torque, force = kwargs.get("torque"), kwargs.get("force")
        if torque is not None:
            power += torque * sender.angle_rate
        if force is not None:
            power += force * sender.position_rate
        return SensorData(power=power)
