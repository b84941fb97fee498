"""Types of the native module `ars._native` (built from `python/src/*.rs`).

Every name the module and its classes have is here (`python/tests/test_docs.py`
checks it); the docstrings are in the module itself (`help(ars.Simulation)`).
"""

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any, Literal, TypeAlias, TypedDict, Unpack, final

import numpy as np
import numpy.typing as npt

from ars.display import Image, Replay

__all__ = [
    "Body",
    "Joint",
    "Renderer",
    "Sensor",
    "Simulation",
    "VideoWriter",
    "_JointTorque",
    "__version__",
    "_panic_for_tests",
    "_release_viewer",
    "has_display",
    "show_program",
    "step_many",
]

__version__: str

_Path: TypeAlias = str | os.PathLike[str]
# Any sequence of three numbers (a tuple, a list, a numpy array).
_Vec3: TypeAlias = Sequence[float] | npt.NDArray[np.floating[Any]]
# A 3×3 rotation matrix, rows first.
_Mat3: TypeAlias = Sequence[Sequence[float]] | npt.NDArray[np.floating[Any]]
_Quality: TypeAlias = Literal["auto", "fast", "fine"]

# The viewer keywords (python/src/viewer.rs, `ViewKeywords`): one set, one default each
# (the size 1024 × 768, the camera at (10, 8, 10) looking at the origin, white).
class _ImageView(TypedDict, total=False):
    camera: _Vec3
    look_at: _Vec3
    background: _Vec3
    follow: str | None
    quality: _Quality
    axes: bool

class _WindowView(_ImageView, total=False):
    title: str
    size: tuple[int, int]

class _ReplayView(TypedDict, total=False):
    title: str
    size: tuple[int, int]
    camera: _Vec3
    look_at: _Vec3
    background: _Vec3

class _ShowReport(TypedDict):
    frames_drawn: int
    wall_seconds: float
    simulated_seconds: float
    frames_per_second: float
    real_time_factor: float

class _UrdfRobot(TypedDict):
    name: str
    links: list[str]
    joints: list[str]
    base_joint: str | None
    adjusted: list[str]

class _ContactSurface(TypedDict):
    mu: float
    mu2: float | None
    bounce: float
    bounce_velocity: float
    soft_erp: float | None
    soft_cfm: float | None
    approx1: bool
    max_contacts: int

class _GeomContact(TypedDict):
    friction: list[float]
    condim: int
    solref: list[float]
    solimp: list[float]
    priority: int
    solmix: float

class _Efforts(TypedDict):
    added: float
    controller: float
    friction: float
    total: float

@final
class Simulation:
    def __new__(
        cls,
        *,
        time_step: float | None = None,
        gravity: _Vec3 | None = None,
        erp: float | None = None,
        cfm: float | None = None,
        steps_per_frame: int | None = None,
        space: Literal["simple", "hash"] | None = None,
        stepper: Literal["exact", "quick"] | None = None,
        quick_iterations: int | None = None,
        seed: int | None = None,
    ) -> Simulation: ...
    # Time and stepping.
    @property
    def time(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    @property
    def frame_count(self) -> int: ...
    @property
    def time_step(self) -> float: ...
    @time_step.setter
    def time_step(self, value: float) -> None: ...
    @property
    def steps_per_frame(self) -> int: ...
    def step(self, n: int = 1) -> None: ...
    def step_frame(self) -> None: ...
    def run(self, duration: float) -> None: ...
    # The world.
    @property
    def gravity(self) -> tuple[float, float, float]: ...
    @gravity.setter
    def gravity(self, value: _Vec3) -> None: ...
    @property
    def erp(self) -> float: ...
    @erp.setter
    def erp(self, value: float) -> None: ...
    @property
    def cfm(self) -> float: ...
    @cfm.setter
    def cfm(self, value: float) -> None: ...
    @property
    def space(self) -> str: ...
    @property
    def stepper(self) -> str: ...
    def set_stepper(
        self, stepper: Literal["exact", "quick"], quick_iterations: int | None = None
    ) -> None: ...
    def set_seed(self, seed: int) -> None: ...
    def set_contact_surface(
        self,
        between: tuple[str, str] | None = None,
        *,
        mu: float = 500.0,
        mu2: float | None = None,
        bounce: float = 0.2,
        bounce_velocity: float = 0.0,
        soft_erp: float | None = None,
        soft_cfm: float | None = None,
        approx1: bool = False,
        max_contacts: int = ...,
    ) -> None: ...
    def contact_surface(self, between: tuple[str, str] | None = None) -> _ContactSurface: ...
    def clear_contact_surface(self, a: str, b: str) -> None: ...
    def exclude_contacts(self, a: str, b: str) -> None: ...
    def include_contacts(self, a: str, b: str) -> None: ...
    def excluded_contacts(self) -> list[tuple[str, str]]: ...
    def set_geom_contact(
        self,
        name: str,
        geom: int = 0,
        *,
        friction: Sequence[float] | None = None,
        condim: int | None = None,
        solref: Sequence[float] | None = None,
        solimp: Sequence[float] | None = None,
        priority: int | None = None,
        solmix: float | None = None,
    ) -> None: ...
    def geom_contact(self, name: str, geom: int = 0) -> _GeomContact | None: ...
    def geom_contacts(self) -> list[tuple[str, int, _GeomContact]]: ...
    def set_geom_pair_contact(
        self,
        a: str,
        b: str,
        a_geom: int = 0,
        b_geom: int = 0,
        *,
        friction: Sequence[float] | None = None,
        condim: int | None = None,
        solref: Sequence[float] | None = None,
        solimp: Sequence[float] | None = None,
    ) -> None: ...
    def geom_pair_contacts(self) -> list[tuple[str, int, str, int, _GeomContact]]: ...
    def cast_ray(
        self, origin: _Vec3, direction: _Vec3, length: float
    ) -> tuple[float, tuple[float, float, float]] | None: ...
    # Objects.
    def add_sphere(
        self,
        radius: float,
        center: _Vec3 = ...,
        mass: float | None = None,
        density: float | None = None,
        *,
        name: str | None = None,
    ) -> str: ...
    def add_box(
        self,
        size: _Vec3,
        center: _Vec3 = ...,
        mass: float | None = None,
        density: float | None = None,
        *,
        name: str | None = None,
    ) -> str: ...
    def add_cylinder(
        self,
        length: float,
        radius: float,
        center: _Vec3 = ...,
        mass: float | None = None,
        density: float | None = None,
        *,
        name: str | None = None,
    ) -> str: ...
    def add_capsule(
        self,
        length: float,
        radius: float,
        center: _Vec3 = ...,
        mass: float | None = None,
        density: float | None = None,
        *,
        name: str | None = None,
    ) -> str: ...
    def add_cone(
        self,
        height: float,
        radius: float,
        center: _Vec3 = ...,
        mass: float | None = None,
        density: float | None = None,
        *,
        name: str | None = None,
    ) -> str: ...
    def add_floor(
        self, normal: _Vec3 = ..., dist: float = 0.0, *, name: str | None = None
    ) -> str: ...
    def add_trimesh(
        self,
        vertices: Sequence[_Vec3] | npt.NDArray[np.floating[Any]],
        faces: Sequence[Sequence[int]] | npt.NDArray[np.integer[Any]],
        center: _Vec3 = ...,
        *,
        name: str | None = None,
    ) -> str: ...
    def load_mjcf(
        self,
        path: _Path,
        *,
        base_position: _Vec3 = (0.0, 0.0, 0.0),
        skip_unsupported: bool = False,
        prefix: str = "",
    ) -> dict[str, Any]: ...
    def set_mocap_pose(
        self,
        body: str,
        position: _Vec3,
        quaternion: tuple[float, float, float, float] | Sequence[float] = (1.0, 0.0, 0.0, 0.0),
    ) -> None: ...
    def mocap_pose(self, body: str) -> tuple[list[float], list[float]]: ...
    def load_urdf(
        self,
        path: _Path,
        *,
        fixed_base: bool = False,
        base_position: _Vec3 = ...,
        self_collision: bool = False,
        y_up: bool = False,
        initial_positions: Mapping[str, float] | None = None,
        packages: Mapping[str, _Path] | None = None,
        search_paths: Sequence[_Path] | None = None,
        ignore_visuals: bool = False,
        strict_inertia: bool = False,
        triangle_mesh_collisions: bool = False,
        exact_base_pose: bool = False,
        keep_fixed_links: bool = False,
    ) -> _UrdfRobot: ...
    def remove_object(self, name: str) -> None: ...
    @property
    def objects(self) -> list[str]: ...
    def body(self, name: str) -> Body: ...
    # Joints.
    def add_rotary_joint(
        self,
        name: str,
        obj1: str,
        obj2: str | None,
        anchor: _Vec3 | None = None,
        axis: _Vec3 = ...,
    ) -> str: ...
    def add_slider_joint(self, name: str, obj1: str, obj2: str | None, axis: _Vec3) -> str: ...
    def add_ball_socket_joint(
        self, name: str, obj1: str, obj2: str | None, anchor: _Vec3 | None = None
    ) -> str: ...
    def add_universal_joint(
        self,
        name: str,
        obj1: str,
        obj2: str | None,
        anchor: _Vec3,
        axis1: _Vec3,
        axis2: _Vec3,
    ) -> str: ...
    def add_piston_joint(
        self, name: str, obj1: str, obj2: str | None, anchor: _Vec3, axis: _Vec3
    ) -> str: ...
    def add_joint_group(
        self,
        obj1: str,
        obj2: str | None,
        joints: list[tuple[str, str, _Vec3, _Vec3, float]],
    ) -> list[str]: ...
    def add_fixed_joint(self, name: str, obj1: str, obj2: str | None) -> str: ...
    def remove_joint(self, name: str) -> None: ...
    @property
    def joints(self) -> list[str]: ...
    def joint(self, name: str) -> Joint: ...
    # Sensors.
    def add_sensor(
        self, kind: str, target: str | Sequence[str] | None = None, *, every: float | None = None
    ) -> Sensor: ...
    def add_lidar(
        self,
        beams: int,
        fov: float,
        max_range: float,
        *,
        min_range: float = 0.0,
        planes: Sequence[float] | None = None,
        on: str | None = None,
        position: _Vec3 = ...,
        rotation: _Mat3 | None = None,
        every: float | None = None,
        noise: float | None = None,
        seed: int = 0,
    ) -> Sensor: ...
    def add_depth_camera(
        self,
        width: int,
        height: int,
        fov_y: float,
        near: float,
        far: float,
        *,
        on: str | None = None,
        position: _Vec3 = ...,
        rotation: _Mat3 | None = None,
        every: float | None = None,
    ) -> Sensor: ...
    # Hooks.
    def add_pre_step(self, function: Callable[[], object]) -> int: ...
    def add_post_step(self, function: Callable[[], object]) -> int: ...
    def remove_hook(self, hook: int) -> None: ...
    def _enable_hook(self, hook: int, enabled: bool) -> None: ...
    # Scene files.
    def save_scene(self) -> str: ...
    def save_scene_to(self, path: _Path) -> None: ...
    # Video files.
    def record_video(
        self,
        path: _Path,
        duration: float,
        fps: float = 30.0,
        size: tuple[int, int] | None = None,
        *,
        allow_long: bool = False,
        **view: Unpack[_ImageView],
    ) -> _RecordedVideo: ...
    @staticmethod
    def load_scene(text: str) -> Simulation: ...
    @staticmethod
    def load_scene_from(path: _Path) -> Simulation: ...
    @staticmethod
    def open(path: _Path) -> Simulation: ...
    # Actuators (MJCF's).
    def set_control(self, name: str, ctrl: float) -> None: ...
    def control(self, name: str) -> float: ...
    @property
    def actuators(self) -> list[str]: ...
    def set_controls(self, ctrl: Sequence[float] | npt.NDArray[np.floating[Any]]) -> None: ...
    @property
    def controls(self) -> list[float]: ...
    # Exact snapshots.
    def snapshot(self) -> bytes: ...
    def restore(self, state: bytes) -> None: ...
    @staticmethod
    def from_snapshot(state: bytes) -> Simulation: ...
    # The window.
    def show(
        self,
        duration: float | None = None,
        *,
        frames: int | None = None,
        **view: Unpack[_WindowView],
    ) -> _ShowReport: ...
    def save_replay(
        self,
        path: _Path | None,
        duration: float,
        *,
        fps: float | None = None,
        plots: Sequence[str] = ...,
        allow_long: bool = False,
        **view: Unpack[_ReplayView],
    ) -> Replay: ...
    def replay(self, duration: float, **options: Any) -> Replay: ...
    # ROS 2 recordings.
    def record_mcap(
        self,
        path: _Path,
        duration: float,
        *,
        state_rate: float = 50.0,
        allow_long: bool = False,
    ) -> dict[str, Any]: ...
    # The live ROS 2 bridge.
    def ros(
        self,
        duration: float | None = None,
        *,
        lock_step: bool = False,
        rate: float | None = None,
        domain_id: int | None = None,
        node_name: str = "ars",
        services: str | None = None,
        drive: tuple[str, str] | None = None,
        wheel_torque: float | None = None,
    ) -> _RosSummary: ...

@final
class Body:
    @property
    def name(self) -> str: ...
    @property
    def position(self) -> npt.NDArray[np.float64]: ...
    @property
    def rotation(self) -> npt.NDArray[np.float64]: ...
    @property
    def linear_velocity(self) -> npt.NDArray[np.float64]: ...
    @property
    def angular_velocity(self) -> npt.NDArray[np.float64]: ...
    @property
    def mass(self) -> float: ...
    @property
    def inertia(self) -> npt.NDArray[np.float64]: ...
    def set_position(self, position: _Vec3) -> None: ...
    def set_rotation(self, rotation: _Mat3) -> None: ...
    def set_pose(self, position: _Vec3, rotation: _Mat3 | None = None) -> None: ...
    def set_linear_velocity(self, velocity: _Vec3) -> None: ...
    def set_angular_velocity(self, velocity: _Vec3) -> None: ...
    def add_force(self, force: _Vec3) -> None: ...
    def rotate(self, axis: _Vec3, angle: float) -> None: ...
    def offset_by_position(self, offset: _Vec3) -> None: ...
    def offset_by_object(self, other: str) -> None: ...
    def set_color(self, color: _Vec3) -> None: ...
    # For ars.model (the original API): tuples, no numpy array made.
    def _position(self) -> tuple[float, float, float]: ...
    def _rotation(self) -> tuple[float, float, float, float, float, float, float, float, float]: ...
    def _linear_velocity(self) -> tuple[float, float, float]: ...
    def _angular_velocity(self) -> tuple[float, float, float]: ...
    def _inertia(
        self,
    ) -> tuple[
        tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]
    ]: ...

@final
class _JointTorque:
    def __new__(
        cls, joint: Joint, heard: set[Any], signals: list[Any], fallback: Callable[[float], None]
    ) -> _JointTorque: ...
    def add_torque(self, torque: float) -> None: ...

@final
class Joint:
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> Literal["hinge", "slider", "universal", "ball", "piston", "fixed"]: ...
    @property
    def angle(self) -> float: ...
    @property
    def position(self) -> float: ...
    @property
    def rate(self) -> float: ...
    @property
    def efforts(self) -> _Efforts: ...
    def add_torque(self, torque: float) -> None: ...
    def add_force(self, force: float) -> None: ...
    def set_speed(self, speed: float, max_force: float) -> None: ...
    def set_limits(self, low: float, high: float) -> None: ...
    def set_param(
        self,
        name: Literal[
            "lo_stop",
            "hi_stop",
            "velocity",
            "max_force",
            "fudge_factor",
            "bounce",
            "cfm",
            "stop_erp",
            "stop_cfm",
        ],
        value: float,
    ) -> None: ...
    def set_viscous_friction(self, coefficient: float) -> None: ...
    def set_dry_friction(self, max_effort: float) -> None: ...
    def set_armature(self, inertia: float) -> None: ...
    @property
    def armature(self) -> float: ...
    def set_damping(self, coefficient: float) -> None: ...
    @property
    def damping(self) -> float: ...
    def set_spring(self, stiffness: float, rest: float = 0.0) -> None: ...
    def set_actuator_limits(self, effort: float = ..., velocity: float = ...) -> None: ...
    def set_controller(
        self,
        kind: Literal["torque", "position", "velocity", "dc_motor"] | None,
        setpoint: float | Sequence[tuple[float, float]] | None = None,
        kp: float = 0.0,
        kd: float = 0.0,
        *,
        torque_constant: float | None = None,
        back_emf_constant: float | None = None,
        resistance: float | None = None,
        gear_ratio: float = 1.0,
        rotor_inertia: float = 0.0,
        inductance: float = 0.0,
        friction: float = 0.0,
    ) -> None: ...
    def set_mimic(self, leader: str, multiplier: float = 1.0, offset: float = 0.0) -> None: ...
    def clear_mimic(self) -> None: ...

@final
class Sensor:
    @property
    def kind(self) -> str: ...
    @property
    def detached(self) -> bool: ...
    def __len__(self) -> int: ...
    def records(self) -> npt.NDArray[np.void]: ...
    def to_csv(self, path: _Path) -> None: ...
    def ranges(self) -> npt.NDArray[np.float64]: ...
    def points(self) -> npt.NDArray[np.float64]: ...
    def images(self) -> npt.NDArray[np.float32]: ...
    def clear(self) -> None: ...
    def remove(self) -> None: ...

@final
class Renderer:
    def __new__(
        cls,
        width: int | None = None,
        height: int | None = None,
        **view: Unpack[_ImageView],
    ) -> Renderer: ...
    @property
    def size(self) -> tuple[int, int]: ...
    def render(self, sim: Simulation) -> Image: ...
    def save(self, sim: Simulation, path: _Path) -> None: ...

class _RosSummary(TypedDict):
    end_time: float
    steps: int

class _RecordedVideo(TypedDict):
    path: str
    frames: int
    fps: float
    duration: float
    size: tuple[int, int]
    bytes: int

@final
class VideoWriter:
    def __new__(
        cls,
        path: _Path,
        width: int,
        height: int,
        fps: float = 30.0,
        **view: Unpack[_ImageView],
    ) -> VideoWriter: ...
    def add(self, sim: Simulation) -> None: ...
    def finish(self) -> _RecordedVideo: ...
    def close(self) -> None: ...

def has_display() -> bool: ...
def step_many(sims: Iterable[Simulation], n: int = 1) -> None: ...
def show_program(
    program: object,
    *,
    duration: float | None = None,
    frames: int | None = None,
    **view: Unpack[_WindowView],
) -> _ShowReport: ...
def _release_viewer() -> None: ...
def _panic_for_tests(message: str) -> None: ...
def _platform() -> dict[str, str]: ...
def _golden_runs() -> list[tuple[str, str, float]]: ...
def _golden_output(name: str) -> bytes: ...
def _golden_compare(name: str, output: bytes, table: str | None = None) -> str: ...
def _golden_with(name: str, duration: float, output: bytes, table: str | None = None) -> str: ...
def _device_select_would_print() -> bool: ...
