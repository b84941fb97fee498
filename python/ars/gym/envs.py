"""The registered environments: the thesis' conical pendulum and mobile manipulator,
and a URDF arm reaching for a point."""

from __future__ import annotations

import functools
import math
import xml.etree.ElementTree as ET
from importlib import resources
from typing import Any, NamedTuple

import numpy as np

import ars
from ars.gym.env import Array, ArsEnv, float_box

INF = math.inf


class ConicalPendulumEnv(ArsEnv):
    """`ars/ConicalPendulum-v0`: the thesis' validation robot (IROS example 2), a
    waist turning a pole about the vertical and an arm hinged to it, free, that swings
    out into a cone as the waist spins. Drive the arm to a target cone angle with the
    waist torque.

    - Scene: as the thesis builds it (two cylinders of 10 kg, 1 m long, on a 10 × 10 m
      base; 50 frames/s of 80 steps: dt = 1/4000 s), with viscous friction 5 N·m·s on
      both joints (applied on the current rate, native; the thesis applies it on the
      previous step's rate, in Python).
    - Action: `Box(-20, 20, (1,))`, the waist torque (N·m; the thesis' 20 N·m at most),
      held for one frame (`frame_skip` = 80 steps, 0.02 s).
    - Observation (6, float64): cos and sin of the waist angle, the waist rate (rad/s),
      the arm's cone angle from the vertical (rad, ≥ 0), its rate (rad/s), the target
      cone angle (rad).
    - Reward: `-(cone - target)² - 0.001·(torque/20)²`.
    - Episode: the target is drawn uniformly in [0.1, 0.6] rad at each reset (a held
      torque of 15 N·m settles at 0.22 rad, one of 20 N·m passes 0.6 rad after 4 s
      and settles at 0.71 rad); never terminated, truncated after 500 steps (10 s).
    """

    frame_skip = 80
    max_episode_steps = 500
    actuators = ("r1",)
    camera = (4.5, 3.0, 6.5)
    look_at = (1.0, 0.6, 2.0)
    MAX_TORQUE = 20.0
    FRICTION = 5.0
    TARGET_RANGE = (0.1, 0.6)

    def __init__(self, render_mode: str | None = None, max_episode_steps: int | None = None):
        self.action_space = float_box([-self.MAX_TORQUE], [self.MAX_TORQUE])
        self.observation_space = float_box(
            [-1.0, -1.0, -INF, 0.0, -INF, 0.0], [1.0, 1.0, INF, math.pi, INF, math.pi]
        )
        self.target = 0.3
        super().__init__(render_mode, max_episode_steps)

    def build(self) -> ars.Simulation:
        sim = ars.Simulation(time_step=1.0 / 50.0 / 80.0, steps_per_frame=80, space="simple")
        sim.add_floor((0.0, 1.0, 0.0), -0.5)
        offset = (1.0, 0.0, 2.0)
        radius = 0.141421
        base = sim.add_box((10.0, 0.5, 10.0), (1.0, -0.25, 2.0), density=100.0, name="base")
        pole = sim.add_cylinder(1.0, radius, (0.0, 0.51, 0.0), mass=10.0, name="pole")
        arm = sim.add_cylinder(1.0, radius, (0.0, 0.51, 0.1), mass=10.0, name="arm")
        for link in (pole, arm):
            sim.body(link).rotate((1.0, 0.0, 0.0), math.pi / 2)
            sim.body(link).offset_by_position(offset)
        sim.add_rotary_joint("r1", base, pole, None, (0.0, 1.0, 0.0))
        sim.add_rotary_joint("r2", pole, arm, (1.0, 1.01, 2.1), (1.0, 0.0, 0.0))
        for joint in ("r1", "r2"):
            sim.joint(joint).set_viscous_friction(self.FRICTION)
        sim.body(base).set_color((0.6, 0.6, 0.6))
        sim.body(arm).set_color((0.1, 0.3, 0.9))
        return sim

    def randomize(self, rng: np.random.Generator) -> None:
        self.target = float(rng.uniform(*self.TARGET_RANGE))

    def observe(self) -> Array:
        r1, r2 = self.sim.joint("r1"), self.sim.joint("r2")
        waist, shoulder = r1.angle, r2.angle
        # The arm swings out to one side; its cone angle is the shoulder's angle
        # from the vertical whichever the sign.
        sign = 1.0 if shoulder >= 0.0 else -1.0
        cone = min(abs(shoulder), math.pi)
        return np.array(
            [math.cos(waist), math.sin(waist), r1.rate, cone, sign * r2.rate, self.target],
            dtype=np.float64,
        )

    def reward(self, obs: Array, action: Array) -> float:
        return float(-((obs[3] - self.target) ** 2) - 1e-3 * (action[0] / self.MAX_TORQUE) ** 2)

    def info(self) -> dict[str, Any]:
        return {"target": self.target, "time": self.sim.time}


def trapezoid(t: float, peak: float) -> float:
    """The thesis' speed profile (IROS example 3) with plateau `peak` (m/s): 0 until
    1 s, up to `peak` at 5 s, held until 9 s, down to 0 at 13 s, then 0."""
    if t <= 1.0 or t >= 13.0:
        return 0.0
    if t < 5.0:
        return peak * (t - 1.0) / 4.0
    if t <= 9.0:
        return peak
    return peak * (13.0 - t) / 4.0


class SpeedProfileEnv(ArsEnv):
    """`ars/SpeedProfile-v0`: the thesis' mobile manipulator (IROS example 3), a
    differential-drive vehicle carrying a free 2-DOF arm, tracking a trapezoidal speed
    profile with its two wheel torques while the arm falls from upright and swings.

    - Scene: as the thesis builds it (2 × 0.2 × 1.5 m chassis of 6 kg, wheels of radius
      0.3 m, a caster ball, 1 kg capsule links on a waist and a shoulder with viscous
      friction 0.02 N·m·s, the floor y = 0; dt = 1/4000 s).
    - Action: `Box(-10, 10, (2,))`, the torques on the right and left wheels (N·m;
      positive drives forward, +X), held for one frame (`frame_skip` = 80 steps, 0.02 s).
      The thesis' controller puts `10·(setpoint − speed)` on both.
    - Observation (13, float64): the chassis' ground speed signed by its X velocity
      (m/s, as the thesis measures it), the set-point now and 1 s ahead (m/s), the time
      (s), the chassis' heading (cos and sin of its turn about Y) and yaw rate (rad/s),
      cos and sin of the waist and shoulder angles and their rates (rad/s).
    - Reward: `-(speed - setpoint)² - 0.001·Σ(torque/10)²`.
    - Episode: the profile is the thesis' (0 until 1 s, up at 5 s, held to 9 s, 0 at
      13 s) with a plateau drawn uniformly in [0.5, 1.5] m/s at each reset
      (`peak_speed=1.0` fixes the thesis' own). Terminated if the chassis tips over
      (its up axis more than 60° from the vertical); truncated after 700 steps (14 s).
    """

    frame_skip = 80
    max_episode_steps = 700
    actuators = ("w1", "w2")
    follow = "chassis"
    camera = (0.0, 3.0, 8.0)
    MAX_TORQUE = 10.0
    OFFSET = (-4.0, 0.5, 4.0)
    PEAK_RANGE = (0.5, 1.5)

    def __init__(
        self,
        render_mode: str | None = None,
        max_episode_steps: int | None = None,
        peak_speed: float | None = None,
    ):
        if peak_speed is not None and not (math.isfinite(peak_speed) and peak_speed > 0.0):
            raise ars.InputError(f"peak_speed must be a positive number of m/s, got {peak_speed}")
        self.fixed_peak = peak_speed
        self.peak = 1.0 if peak_speed is None else float(peak_speed)
        self.action_space = float_box([-self.MAX_TORQUE] * 2, [self.MAX_TORQUE] * 2)
        self.observation_space = float_box(
            [-INF, 0.0, 0.0, 0.0, -1.0, -1.0, -INF, -1.0, -1.0, -INF, -1.0, -1.0, -INF],
            [INF, INF, INF, INF, 1.0, 1.0, INF, 1.0, 1.0, INF, 1.0, 1.0, INF],
        )
        super().__init__(render_mode, max_episode_steps)

    def build(self) -> ars.Simulation:
        sim = ars.Simulation(time_step=1.0 / 50.0 / 80.0, steps_per_frame=80, space="simple")
        sim.add_floor()
        # The vehicle (ars-programs' build_vehicle): ball, chassis, right and left wheel.
        ball = sim.add_sphere(0.3, (1.0, 0.0, 0.0), density=1.0, name="ball")
        chassis = sim.add_box((2.0, 0.2, 1.5), (0.5, 0.45, 0.0), mass=6.0, name="chassis")
        wheel_r = sim.add_cylinder(0.4, 0.3, (0.0, 0.0, -0.5), density=1.0, name="wheel_r")
        wheel_l = sim.add_cylinder(0.4, 0.3, (0.0, 0.0, 0.5), density=1.0, name="wheel_l")
        sim.add_rotary_joint("w1", chassis, wheel_r, None, (0.0, 0.0, 1.0))
        sim.add_rotary_joint("w2", chassis, wheel_l, None, (0.0, 0.0, 1.0))
        sim.add_ball_socket_joint("bs", chassis, ball, None)
        for name in (ball, chassis, wheel_r, wheel_l):
            sim.body(name).offset_by_position(self.OFFSET)
        sim.body(chassis).set_color((0.8, 0.0, 0.0))
        # The arm (build_vehicle_arm): two capsules, a waist about Y, a shoulder about Z.
        link1 = sim.add_capsule(0.8, 0.1, (0.0, 0.0, 0.0), mass=1.0, name="link1")
        link2 = sim.add_capsule(0.6, 0.1, (0.0, 0.7, 0.2), mass=1.0, name="link2")
        sim.body(link1).rotate((1.0, 0.0, 0.0), math.pi / 2)
        sim.body(link2).rotate((1.0, 0.0, 0.0), math.pi / 2)
        sim.body(link1).offset_by_object(chassis)
        sim.body(link1).offset_by_position((0.0, 0.5, 0.0))
        sim.body(link2).offset_by_object(link1)
        sim.add_rotary_joint("r1", chassis, link1, None, (0.0, 1.0, 0.0))
        anchor = sim.body(link2).position - np.array([0.0, 0.3, 0.0])
        sim.add_rotary_joint("r2", link1, link2, tuple(anchor), (0.0, 0.0, 1.0))
        sim.body(link1).set_color((1.0, 1.0, 0.0))
        sim.body(link2).set_color((0.0, 0.0, 0.5))
        for joint in ("r1", "r2"):
            sim.joint(joint).set_viscous_friction(0.02)
        return sim

    def randomize(self, rng: np.random.Generator) -> None:
        self.peak = (
            self.fixed_peak if self.fixed_peak is not None else float(rng.uniform(*self.PEAK_RANGE))
        )

    def setpoint(self, t: float) -> float:
        """The speed set-point at time `t` (m/s)."""
        return trapezoid(t, self.peak)

    def observe(self) -> Array:
        sim = self.sim
        chassis = sim.body("chassis")
        v = chassis.linear_velocity
        # The original's measure: sqrt(vx² + vz²) with the sign of vx (sign(0) = −1).
        speed = math.sqrt(v[0] * v[0] + v[2] * v[2]) * (1.0 if v[0] > 0.0 else -1.0)
        forward = chassis.rotation[:, 0]
        heading = math.atan2(-forward[2], forward[0])
        r1, r2 = sim.joint("r1"), sim.joint("r2")
        t = sim.time
        return np.array(
            [
                speed,
                self.setpoint(t),
                self.setpoint(t + 1.0),
                t,
                math.cos(heading),
                math.sin(heading),
                chassis.angular_velocity[1],
                math.cos(r1.angle),
                math.sin(r1.angle),
                r1.rate,
                math.cos(r2.angle),
                math.sin(r2.angle),
                r2.rate,
            ],
            dtype=np.float64,
        )

    def reward(self, obs: Array, action: Array) -> float:
        effort = float(np.sum((action / self.MAX_TORQUE) ** 2))
        return float(-((obs[0] - obs[1]) ** 2) - 1e-3 * effort)

    def terminated(self, obs: Array) -> bool:
        return bool(self.sim.body("chassis").rotation[1, 1] < 0.5)

    def info(self) -> dict[str, Any]:
        return {"peak_speed": self.peak, "x": float(self.sim.body("chassis").position[0])}


# ReachEnv's arm is defined once, in its URDF: the simulation loads it, and the forward
# kinematics its targets are drawn with read their joints and end effector from it.
_ARM_URDF = "reach_arm.urdf"


class _ArmJoint(NamedTuple):
    """A joint of the chain from the arm's base to `fore`, as its URDF gives it."""

    name: str
    type: str
    xyz: tuple[float, float, float]  # origin in the parent link's frame
    rpy: tuple[float, float, float]
    axis: tuple[float, float, float]


def _triple(
    element: ET.Element | None, attribute: str, default: tuple[float, float, float]
) -> tuple[float, float, float]:
    """An `element`'s three-number attribute, or URDF's default where it is absent."""
    text = None if element is None else element.get(attribute)
    if text is None:
        return default
    values = tuple(float(v) for v in text.split())
    if len(values) != 3:
        raise ValueError(f"{attribute}={text!r} is not three numbers")
    return values[0], values[1], values[2]


def _parse_arm(
    urdf: str | bytes, joints: tuple[str, ...], tip: str = "fore", source: str = _ARM_URDF
) -> tuple[tuple[_ArmJoint, ...], tuple[float, float, float]]:
    """The chain of joints from the root link to the link `tip` in the URDF text `urdf`,
    followed by parent and child links (not by file order), and the origin of `tip`'s
    <inertial> (its centre of mass) in `tip`'s frame. Raises `ValueError`, naming
    `source`, if a link or joint of the chain is missing or the chain's joints are not
    the rotary `joints`, in that order."""
    robot = ET.fromstring(urdf)
    links = {link.get("name"): link for link in robot.iter("link")}
    by_child: dict[str | None, ET.Element] = {}
    for joint in robot.iter("joint"):
        child = joint.find("child")
        child_link = None if child is None else child.get("link")
        if child_link in by_child:
            raise ValueError(f"{source}: two joints have the child link {child_link!r}")
        by_child[child_link] = joint
    if tip not in links:
        raise ValueError(f"{source} has no link {tip!r}")
    if links[tip].find("inertial") is None:
        raise ValueError(f"{source}: the link {tip!r} has no <inertial> (centre of mass)")
    com = _triple(links[tip].find("inertial/origin"), "xyz", (0.0, 0.0, 0.0))
    chain: list[_ArmJoint] = []
    link: str | None = tip
    while link in by_child and len(chain) < len(joints):
        joint = by_child[link]
        name = joint.get("name", "")
        parent = joint.find("parent")
        link = None if parent is None else parent.get("link")
        if link not in links:
            raise ValueError(f"{source}: the parent link {link!r} of the joint {name!r} is missing")
        origin = joint.find("origin")
        chain.append(
            _ArmJoint(
                name,
                joint.get("type", ""),
                _triple(origin, "xyz", (0.0, 0.0, 0.0)),
                _triple(origin, "rpy", (0.0, 0.0, 0.0)),
                _triple(joint.find("axis"), "xyz", (1.0, 0.0, 0.0)),
            )
        )
    if link in by_child:
        raise ValueError(f"{source}: more than {len(joints)} joints lead to the link {tip!r}")
    chain.reverse()
    names = tuple(joint.name for joint in chain)
    rotary = all(joint.type in ("revolute", "continuous") for joint in chain)
    if names != joints or not rotary:
        found = ", ".join(f"{joint.name} ({joint.type})" for joint in chain)
        raise ValueError(
            f"{source}: the joints from the link {link!r} to {tip!r} are [{found}], "
            f"not the revolute or continuous {', '.join(joints)}"
        )
    return tuple(chain), com


@functools.cache
def _reach_arm() -> tuple[tuple[_ArmJoint, ...], tuple[float, float, float]]:
    """`ReachEnv`'s arm as its URDF `reach_arm.urdf` gives it, parsed once."""
    urdf = (resources.files("ars.gym") / _ARM_URDF).read_bytes()
    return _parse_arm(urdf, ReachEnv.actuators)


def _rpy(r: float, p: float, y: float) -> Array:
    """URDF's roll-pitch-yaw: Rz(y)·Ry(p)·Rx(r)."""
    return (
        _axis_angle((0.0, 0.0, 1.0), y)
        @ _axis_angle((0.0, 1.0, 0.0), p)
        @ _axis_angle((1.0, 0.0, 0.0), r)
    )


def _axis_angle(axis: Any, angle: float) -> Array:
    """The rotation by `angle` about `axis` (Rodrigues)."""
    k = np.asarray(axis, dtype=np.float64)
    k = k / np.linalg.norm(k)
    cross = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    rotation: Array = (
        np.eye(3) + math.sin(angle) * cross + (1.0 - math.cos(angle)) * (cross @ cross)
    )
    return rotation


def arm_end_effector(q: Any, base: Any = (0.0, 0.0, 0.0)) -> Array:
    """Where the end effector of `ReachEnv`'s arm (the centre of mass of its link
    `fore`) is at joint angles `q` (rad), in ARS's Y-up world, with the base at `base`."""
    return _end_effector(_reach_arm(), q, base)


def _end_effector(
    arm: tuple[tuple[_ArmJoint, ...], tuple[float, float, float]], q: Any, base: Any
) -> Array:
    """`arm_end_effector` for the chain and centre of mass `arm` (`_parse_arm`'s)."""
    joints, com = arm
    rotation, position = np.eye(3), np.zeros(3)
    for joint, angle in zip(joints, q):
        position = position + rotation @ np.asarray(joint.xyz)
        rotation = rotation @ _rpy(*joint.rpy) @ _axis_angle(joint.axis, float(angle))
    z_up = position + rotation @ np.asarray(com)
    # URDF is Z-up: turned −90° about X into the Y-up world.
    y_up: Array = np.array([z_up[0], z_up[2], -z_up[1]]) + np.asarray(base, dtype=np.float64)
    return y_up


class ReachEnv(ArsEnv):
    """`ars/Reach-v0`: a 3-joint URDF arm brings its end effector to a seeded target
    point, under gravity, with its joint torques. The arm is ARS's test arm
    `tests/data/rnea_arm.urdf` (a turret about the vertical, a shoulder and a tilted
    elbow, links with offset centres of mass and products of inertia), shipped in the
    package as `reach_arm.urdf` with shapes for the renderer to draw.

    - Scene: the arm loaded with a fixed base at the origin, joints with viscous
      friction 0.5 N·m·s; dt = 1 ms, 50 environment steps per second.
    - Action: `Box([-4, -12, -3], [4, 12, 3])`, the torques on the joints `j1`, `j2`,
      `j3` (N·m), held for `frame_skip` = 20 steps (0.02 s).
    - Observation (18, float64): cos and sin of the three joint angles, their rates
      (rad/s), the end effector's position (the centre of mass of the link `fore`, m),
      the target's, and the target minus the end effector.
    - Reward: `-|target - end effector| - 0.001·Σ(torque/limit)²`.
    - Episode: the target is where the end effector would be at joint angles drawn
      uniformly in [-π, π] × [-1.2, 1.2] × [-1.2, 1.2] at each reset (so it can be
      reached); never terminated, truncated after 200 steps (4 s).
    """

    frame_skip = 20
    max_episode_steps = 200
    actuators = ("j1", "j2", "j3")
    camera = (1.0, 0.9, 1.2)
    look_at = (0.0, 0.35, 0.0)
    MAX_TORQUES = (4.0, 12.0, 3.0)
    TARGET_ANGLES = ((-math.pi, math.pi), (-1.2, 1.2), (-1.2, 1.2))
    FRICTION = 0.5

    def __init__(self, render_mode: str | None = None, max_episode_steps: int | None = None):
        limits = np.asarray(self.MAX_TORQUES)
        self.action_space = float_box(-limits, limits)
        low = [-1.0] * 6 + [-INF] * 12
        high = [1.0] * 6 + [INF] * 12
        self.observation_space = float_box(low, high)
        self.target = arm_end_effector((0.0, 0.0, 0.0))
        super().__init__(render_mode, max_episode_steps)

    def build(self) -> ars.Simulation:
        sim = ars.Simulation(time_step=0.001)
        with resources.as_file(resources.files("ars.gym") / _ARM_URDF) as path:
            sim.load_urdf(str(path), fixed_base=True)
        for joint in self.actuators:
            sim.joint(joint).set_viscous_friction(self.FRICTION)
        return sim

    def randomize(self, rng: np.random.Generator) -> None:
        q = [rng.uniform(low, high) for low, high in self.TARGET_ANGLES]
        self.target = arm_end_effector(q)

    def end_effector(self) -> Array:
        """The end effector's position now (the centre of mass of `fore`), m."""
        return self.sim.body("fore").position

    def observe(self) -> Array:
        joints = [self.sim.joint(name) for name in self.actuators]
        q = np.array([j.angle for j in joints])
        rates = np.array([j.rate for j in joints])
        effector = self.end_effector()
        return np.concatenate(
            [np.cos(q), np.sin(q), rates, effector, self.target, self.target - effector]
        ).astype(np.float64)

    def reward(self, obs: Array, action: Array) -> float:
        effort = float(np.sum((action / np.asarray(self.MAX_TORQUES)) ** 2))
        return float(-np.linalg.norm(obs[15:18]) - 1e-3 * effort)

    def info(self) -> dict[str, Any]:
        return {"distance": float(np.linalg.norm(self.target - self.end_effector()))}
