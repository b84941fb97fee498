"""The simulation of the original ARS API (``ars.model.simulator.Simulation``, also
``ars.app.Simulation``), on ARS's native core.

A frame (``on_idle``) sends ``SIM_PRE_FRAME``, takes ``STEPS_PF`` steps and sends
``SIM_POST_FRAME``. Each step: ``SIM_PRE_STEP`` and the frame's key callbacks, then
collision detection and ODE's ``dWorldStep`` (in native code), ``sim_time += dt``,
then ``SIM_POST_STEP``. An exception in a receiver is logged (``ars.app`` logger), as
the original did, and the simulation goes on.

Objects are kept by name: ``add_sphere`` and friends return the name (``'sphere'``,
``'box(0, 1, 0)'``; a name already taken gets ``'/'`` and the object's ``repr``), and
``get_object(name)`` gives a :class:`SimulatedBody`. Joints likewise
(``get_joint(name).joint`` is the :mod:`ars.model.robot.joints` object).
"""

import functools
import logging
import weakref
from operator import attrgetter

from ars import _native, dispatch
from ars.constants import G_VECTOR
from ars.dispatch import send
from ars.exceptions import ArsError
from ars.model.robot import joints as jo
from ars.model.robot import signals as robot_signals
from ars.model.simulator import signals
from ars.utils import mathematical as mut

__all__ = ["SimulatedBody", "SimulatedJoint", "SimulatedObject", "Simulation", "signals"]

logger = logging.getLogger("ars.app")


class SimulatedObject:
    """An object of the simulation: a name and, with a graphics adapter, an actor."""

    # The simulation it is part of (a weak reference), set when it is added: the
    # dispatcher finds a signal's program through it.
    _sim = None

    def __init__(self, name, actor=None):
        self._name = name
        self._actor = actor

    def get_name(self):
        return self._name

    def set_name(self, name):
        self._name = name

    @property
    def actor(self):
        """What draws it (``None`` without graphics)."""
        return self._actor

    def has_actor(self):
        return bool(self._actor)

    def is_updatable(self):
        return False

    def update_actor(self):
        pass


class PhysicsBody:
    """The physics of a body: what ``SimulatedBody.body`` returns, and where a
    ``SimulatedBody`` forwards what it does not know (``get_mass()``...)."""

    def __init__(self, native):
        self._native = native
        self._saved_velocities = (None, None)

    # The native tuples (``_position``...) are what the original returned: Python
    # floats, no numpy array made on the way.
    def get_position(self):
        return self._native._position()

    def get_rotation(self):
        return self._native._rotation()

    def get_linear_velocity(self):
        return self._native._linear_velocity()

    def get_angular_velocity(self):
        return self._native._angular_velocity()

    def get_mass(self):
        return float(self._native.mass)

    def get_inertia_tensor(self):
        return self._native._inertia()

    def set_position(self, pos):
        self._native.set_position(pos)

    def set_linear_velocity(self, velocity):
        self._native.set_linear_velocity(velocity)

    def set_angular_velocity(self, velocity):
        self._native.set_angular_velocity(velocity)

    def save_velocities(self):
        """Remembers the velocities now (for an accelerometer)."""
        self._saved_velocities = (self.get_linear_velocity(), self.get_angular_velocity())

    def get_saved_velocities(self):
        return self._saved_velocities

    def calc_translation_kinetic_energy(self):
        v = self.get_linear_velocity()
        return self.get_mass() * mut.dot_product(v, v) / 2.0

    def calc_rotation_kinetic_energy(self):
        # The original's formula: the body-frame inertia with the world-frame rate.
        return (
            mut.vector_matrix_vector(self.get_angular_velocity(), self.get_inertia_tensor()) / 2.0
        )

    def calc_potential_energy(self, gravity):
        return -self.get_mass() * mut.dot_product(gravity, self.get_position())


class SimulatedPhysicsObject(SimulatedObject):
    """An object with a pose."""

    def rotate(self, axis, angle):
        """Turns it by ``angle`` (rad) about the world ``axis`` through its centre."""
        self._native.rotate(axis, angle)

    def offset_by_position(self, offset):
        """Moves it by ``offset``."""
        self._native.offset_by_position(offset)

    def offset_by_object(self, obj):
        """Moves it by the position of ``obj``."""
        self.offset_by_position(obj.get_position())

    def get_position(self):
        return self._native._position()

    def get_rotation(self):
        return self._native._rotation()

    def get_pose(self):
        return (self.get_position(), self.get_rotation())


class SimulatedBody(SimulatedPhysicsObject):
    """A body of the simulation (``body`` is ``None`` for a static trimesh floor)."""

    def __init__(self, name, native, actor=None, dynamic=True):
        super().__init__(name, actor)
        self._native = None
        self._body = None
        if native is not None:
            self._attach(native, dynamic)

    def _attach(self, native, dynamic=True):
        """Makes it the object ``native`` (an ``ars.Body``)."""
        self._native = native
        self._body = PhysicsBody(native) if dynamic else None
        # Its pose and velocities are read by the native calls themselves, with no
        # Python frame between (programs read them every step), unless a subclass
        # reads them its own way.
        cls = type(self)
        if cls.get_position is SimulatedPhysicsObject.get_position:
            self.get_position = native._position
        if dynamic and cls.get_linear_velocity is SimulatedBody.get_linear_velocity:
            self.get_linear_velocity = native._linear_velocity
        if dynamic and cls.get_angular_velocity is SimulatedBody.get_angular_velocity:
            self.get_angular_velocity = native._angular_velocity

    @property
    def body(self):
        """Its physics body."""
        return self._body

    def is_updatable(self):
        return self._body is not None

    def update_actor(self):
        if self._actor is not None and hasattr(self._actor, "set_pose"):
            self._actor.set_pose(self.get_position(), self.get_rotation())

    # The physics body's velocities, read here directly: programs read them every step,
    # and reaching them through ``__getattr__`` costs a failed look-up first.
    def get_linear_velocity(self):
        if self._body is None:
            raise AttributeError("get_linear_velocity")
        return self._native._linear_velocity()

    def get_angular_velocity(self):
        if self._body is None:
            raise AttributeError("get_angular_velocity")
        return self._native._angular_velocity()

    def __getattr__(self, attr):
        # The original forwards anything else to the physics body.
        body = self.__dict__.get("_body")
        if body is None:
            raise AttributeError(attr)
        return getattr(body, attr)


def _add_torque_logged(joint, name, torque):
    """``joint.add_torque(torque)``; a failure is logged, not raised (as the original)."""
    try:
        joint.add_torque(torque)
    except Exception:
        logger.exception("Exception when adding torque to joint %r", name)


class SimulatedJoint(SimulatedObject):
    """A joint of the simulation; ``joint`` is its :mod:`ars.model.robot.joints`
    object."""

    def __init__(self, name, joint, actor=None):
        super().__init__(name, actor)
        # Its :mod:`ars.model.robot.joints` object: a plain attribute, read every step.
        self.joint = joint
        # A rotary joint's torque is put by one native call while no one listens to the
        # torque signals (programs put torques every step), unless a subclass puts
        # them its own way.
        if (
            type(joint) is jo.Rotary
            and joint._native is not None
            and type(self).add_torque is SimulatedJoint.add_torque
        ):
            self.add_torque = _native._JointTorque(
                joint._native,
                dispatch._heard,
                [
                    robot_signals.JOINT_PRE_ADD_TORQUE,
                    robot_signals.JOINT_POST_ADD_TORQUE,
                    dispatch.Any,
                ],
                functools.partial(_add_torque_logged, joint, name),
            ).add_torque

    def add_torque(self, torque):
        """Adds a torque to a rotary joint; a failure is logged, not raised (as the
        original)."""
        _add_torque_logged(self.joint, self._name, torque)

    def get_position(self):
        raise NotImplementedError

    def get_rotation(self):
        raise NotImplementedError


class Space:
    """The collision space: where lasers cast their rays (``collision_space``)."""

    def __init__(self, sim):
        self._sim = weakref.ref(sim)
        self.rays = []

    @property
    def simulation(self):
        return self._sim()


# What a simulation's step calls for SIM_PRE_STEP before it is found out.
_UNRESOLVED = object()


class _BeforeTheWorld:
    """The clock of a simulation whose world is not made yet."""

    time = 0.0


class Simulation:
    """A simulation run in frames of ``STEPS_PF`` steps, ``1/FPS`` seconds each."""

    # The program it belongs to (a weak reference), set by ``ars.app.Program``: the
    # program's handlers hear this simulation alone (see ``ars.dispatch``).
    _program = None
    # What ``sim_time`` reads: the native simulation, once made.
    _clock = _BeforeTheWorld

    def __init__(self, FPS, STEPS_PF):
        self._FPS = FPS
        self._DT = 1.0 / FPS
        self._STEPS_PF = STEPS_PF
        self.paused = False
        self._num_iter_offset = 0  # num_iter minus the native steps taken
        self._pre_step_calls = _UNRESOLVED  # see _signals_changed
        self.num_frame = 0
        self._native = None
        self._space = None
        self._objects = {}
        self._joints = {}
        # Looked up by the dicts themselves, with no Python frame between: programs
        # look their objects and joints up by name many times a step (unless a
        # subclass looks them up its own way).
        if type(self).get_object is Simulation.get_object:
            self.get_object = self._objects.__getitem__
        if type(self).get_joint is Simulation.get_joint:
            self.get_joint = self._joints.__getitem__
        self.all_frame_steps_callbacks = []
        self.graph_adapter = None
        self._shown_colors = {}  # the colours given to the viewer, by object

    # -- set-up -------------------------------------------------------------------

    def add_basic_simulation_objects(self, gravity=G_VECTOR):
        """Creates the world (``gravity``, ERP 0.2, CFM 1e-10) and the collision space;
        before any ``add_*``."""
        # The original's simple space (every pair tested), in the original's order, so
        # that its programs print the same numbers as on PyODE.
        self._native = _native.Simulation(
            time_step=self.time_step,
            gravity=tuple(gravity),
            steps_per_frame=self._STEPS_PF,
            space="simple",
        )
        self._clock = self._native
        self._space = Space(self)
        me = weakref.ref(self)  # the native hooks must not keep this object alive

        def pre_step():
            sim = me()
            if sim is None:
                return
            calls = sim._pre_step_calls
            if calls is _UNRESOLVED:
                # Found out once, then at every change (``_signals_changed``); ``None``
                # when some handler takes the signal's values (then it is sent).
                calls = sim._pre_step_calls = dispatch._direct_calls(signals.SIM_PRE_STEP, sim)
            if calls is None or sim.all_frame_steps_callbacks or sim._space.rays:
                sim._pre_step()
                return
            # What sending SIM_PRE_STEP would call, called here: every step of every
            # program goes through this.
            try:
                for target, function in calls:
                    if target is None:
                        function()
                        continue
                    target = target()
                    if target is None:  # gone: found out again at the next step
                        sim._pre_step_calls = _UNRESOLVED
                    elif function is None:
                        target()
                    else:
                        function(target)
            except Exception:
                logger.exception("Exception when executing the pre-step actions")

        def post_step():
            sim = me()
            if sim is not None:
                sim._post_step()

        self._native.add_pre_step(pre_step)
        self._post_step_hook = self._native.add_post_step(post_step)
        dispatch._watch_heard(self._signals_changed)
        self._signals_changed()

    def _signals_changed(self):
        """A receiver was connected or went away, or the simulation's program changed:
        what a step sends is found out again (``_pre_step_calls``), and the post-step
        hook is on only while someone listens to SIM_POST_STEP (a step then costs no
        call into Python after it)."""
        self._pre_step_calls = _UNRESOLVED
        if self._native is not None:
            self._native._enable_hook(self._post_step_hook, dispatch.heard(signals.SIM_POST_STEP))

    @property
    def num_iter(self):
        """Steps taken."""
        steps = 0 if self._native is None else self._native.step_count
        return steps + self._num_iter_offset

    @num_iter.setter
    def num_iter(self, value):
        steps = 0 if self._native is None else self._native.step_count
        self._num_iter_offset = value - steps

    @property
    def native(self):
        """The ``ars.Simulation`` underneath."""
        if self._native is None:
            raise ArsError("call add_basic_simulation_objects() first")
        return self._native

    # -- running ------------------------------------------------------------------

    def _pre_step(self):
        try:
            send(signals.SIM_PRE_STEP, sender=self)
            for callback in self.all_frame_steps_callbacks:
                callback()
        except Exception:
            logger.exception("Exception when executing the pre-step actions")
        for laser in self._space.rays:
            laser._cast()

    def _post_step(self):
        try:
            send(signals.SIM_POST_STEP, sender=self)
        except Exception:
            logger.exception("Exception when executing the post-step actions")

    def on_idle(self):
        """One frame."""
        self.num_frame += 1
        try:
            send(signals.SIM_PRE_FRAME, sender=self)
        except Exception:
            logger.exception("Exception when executing the pre-frame actions")
        self.perform_sim_steps_per_frame()
        try:
            send(signals.SIM_POST_FRAME, sender=self)
        except Exception:
            logger.exception("Exception when executing the post-frame actions")
        self.all_frame_steps_callbacks = []
        self.update_actors()

    def perform_sim_steps_per_frame(self):
        self.native.step(self._STEPS_PF)

    def _sync_colors(self):
        """Gives the viewer the colours the program set on its objects' actors."""
        shown = self._shown_colors
        for key, obj in self._objects.items():
            actor = obj.actor
            color = getattr(actor, "color", None) if actor is not None else None
            if color is None or shown.get(key) == color:
                continue
            shown[key] = color
            try:
                self.native.body(key).set_color(tuple(float(c) for c in color[:3]))
            except (KeyError, ValueError):
                pass  # drawn only (the axes), or not a colour the viewer takes

    def update_actors(self):
        """Moves every drawn body's actor to its pose."""
        for obj in self._objects.values():
            if obj.is_updatable():
                try:
                    obj.update_actor()
                except (ValueError, AttributeError):
                    logger.exception("Exception when updating the actor of %r", obj.get_name())

    @property
    def time_step(self):
        """Seconds per step: ``1/FPS/STEPS_PF``."""
        return self._DT / self._STEPS_PF

    # Read by the native getter through ``attrgetter``, with no Python frame between
    # (programs read it every step); ``_clock`` is the native simulation once made.
    sim_time = property(
        attrgetter("_clock.time"),
        doc="Simulated time, s (accumulated step by step, as the original).",
    )

    @property
    def gravity(self):
        return self.native.gravity

    @property
    def collision_space(self):
        return self._space

    @property
    def actors(self):
        """Every object's actor, by name."""
        return {name: obj.actor for name, obj in self._objects.items() if obj.actor}

    @property
    def objects(self):
        return self._objects

    @property
    def joints(self):
        return self._joints

    # -- objects -------------------------------------------------------------------

    def _graphics(self, factory, *args):
        try:
            return getattr(self.graph_adapter, factory)(*args)
        except AttributeError:
            return None

    def _key(self, name, obj):
        return f"{name}/{obj!r}" if name in self._objects else name

    def _register(self, key, obj):
        """Adds ``obj`` under ``key`` (its name), as part of this simulation."""
        obj.set_name(key)
        obj._sim = weakref.ref(self)
        self._objects[key] = obj
        return key

    def _add_body(self, base, native_add, actor, *args, mass=None, density=None):
        # The key is chosen before the native object exists, so that both share it.
        obj = SimulatedBody(base, None, actor)
        key = self._key(base, obj)
        name = native_add(*args, mass, density, name=key)
        obj._attach(self.native.body(name))
        return self._register(key, obj)

    def add_axes(self):
        """The axes (drawn only)."""
        obj = SimulatedObject("axes", self._graphics("Axes"))
        key = self._key("axes", obj)
        return self._register(key, obj)

    def add_floor(
        self,
        normal=(0, 1, 0),
        dist=0,
        box_size=(5, 0.1, 5),
        box_center=(0, 0, 0),
        color=(0.2, 0.5, 0.5),
    ):
        """A static plane ``normal · x = dist``, drawn as a box."""
        actor = self._graphics("Box", box_size, box_center)
        if actor is not None:
            actor.set_color(color)
        obj = SimulatedObject("floor", actor)
        key = self._key("floor", obj)
        self.native.add_floor(tuple(normal), dist, name=key)
        return self._register(key, obj)

    def add_trimesh_floor(self, vertices, faces, center=(0, 0, 0), color=(0.2, 0.5, 0.5)):
        """A static triangle-mesh floor at ``center``."""
        actor = self._graphics("Trimesh", vertices, faces, center)
        if actor is not None:
            actor.set_color(color)
        obj = SimulatedBody("floor", None, actor, dynamic=False)
        key = self._key("floor", obj)
        self.native.add_trimesh(vertices, faces, tuple(center), name=key)
        obj._attach(self.native.body(key), dynamic=False)
        return self._register(key, obj)

    def add_sphere(self, radius, center, mass=None, density=None):
        actor = self._graphics("Sphere", radius, center)
        return self._add_body(
            "sphere", self.native.add_sphere, actor, radius, center, mass=mass, density=density
        )

    def add_box(self, size, center, mass=None, density=None):
        actor = self._graphics("Box", size, center)
        return self._add_body(
            "box" + str(center),
            self.native.add_box,
            actor,
            size,
            center,
            mass=mass,
            density=density,
        )

    def add_cylinder(self, length, radius, center, mass=None, density=None):
        actor = self._graphics("Cylinder", length, radius, center)
        return self._add_body(
            "cylinder",
            self.native.add_cylinder,
            actor,
            length,
            radius,
            center,
            mass=mass,
            density=density,
        )

    def add_capsule(self, length, radius, center, mass=None, density=None):
        actor = self._graphics("Capsule", length, radius, center)
        return self._add_body(
            "capsule",
            self.native.add_capsule,
            actor,
            length,
            radius,
            center,
            mass=mass,
            density=density,
        )

    def get_object(self, name):
        return self._objects[name]

    def get_bodies(self):
        """The bodies that move (not the axes, not the floors)."""
        return [obj for obj in self._objects.values() if getattr(obj, "body", None)]

    # -- joints --------------------------------------------------------------------

    def _add_joint(self, name, joint_class, create):
        joint = joint_class(None)
        key = f"{name}/{joint!r}" if name in self._joints else name
        native_name = create(key)
        joint._native = self.native.joint(native_name)
        joint._sim = weakref.ref(self)
        self._joints[key] = SimulatedJoint(key, joint)
        self._joints[key]._sim = joint._sim
        return key

    @staticmethod
    def _anchor(anchor, obj2):
        return anchor if anchor else obj2.get_position()

    def add_rotary_joint(self, name, obj1, obj2, anchor, axis):
        """A hinge between two bodies about the world ``axis`` through ``anchor``
        (``obj2``'s position when not given)."""
        anchor = self._anchor(anchor, obj2)
        return self._add_joint(
            name,
            jo.Rotary,
            lambda key: self.native.add_rotary_joint(
                key, obj1.get_name(), obj2.get_name(), anchor, axis
            ),
        )

    def add_ball_socket_joint(self, name, obj1, obj2, anchor):
        anchor = self._anchor(anchor, obj2)
        return self._add_joint(
            name,
            jo.BallSocket,
            lambda key: self.native.add_ball_socket_joint(
                key, obj1.get_name(), obj2.get_name(), anchor
            ),
        )

    def add_universal_joint(self, name, obj1, obj2, anchor, axis1, axis2):
        return self._add_joint(
            name,
            jo.Universal,
            lambda key: self.native.add_universal_joint(
                key, obj1.get_name(), obj2.get_name(), anchor, axis1, axis2
            ),
        )

    def add_slider_joint(self, name, obj1, obj2, axis):
        return self._add_joint(
            name,
            jo.Slider,
            lambda key: self.native.add_slider_joint(key, obj1.get_name(), obj2.get_name(), axis),
        )

    def add_fixed_joint(self, name, obj1, obj2):
        return self._add_joint(
            name,
            jo.Fixed,
            lambda key: self.native.add_fixed_joint(
                key, obj1.get_name(), obj2.get_name() if obj2 else None
            ),
        )

    def get_joint(self, name):
        return self._joints[name]
