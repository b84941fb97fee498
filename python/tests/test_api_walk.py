"""One error hierarchy: the whole public API, called with a sequence of the wrong
length, an integer beyond 64 bits or a path in a missing folder, raises nothing but an
``ars.ArsError`` (a path an ``ars.FileError``), never a bare ``ValueError``,
``OverflowError`` or ``OSError``.

Every public method of the package's classes is listed below with a call that works
(``CALLS``), or among those without an argument to vary (``NOTHING_TO_VARY``): a method
added to the API without being listed fails ``test_every_public_method_is_walked``.
Each call's arguments are varied one at a time: a sequence one item short and one item
long (and the same inside a nested sequence), an int ``10**30`` and ``-10**30``, a path
(``Path``) moved into a missing folder. A wrong type is a ``TypeError``, as in Python;
the walk gives none.
"""

import inspect
import os
import pathlib
import tempfile

import numpy as np
import pytest

import ars
from ars.display import Image, Replay

gymnasium = pytest.importorskip("gymnasium")
import ars.gym
from ars.gym.env import float_box

REPO = pathlib.Path(__file__).resolve().parents[2]
ARM = REPO / "tests" / "data" / "rnea_arm.urdf"


class Path:
    """A path argument: ``name`` in the test's folder (a file there first if
    ``content`` is given); varied, ``name`` in a folder that does not exist."""

    def __init__(self, name, content=None):
        self.name, self.content = name, content

    def where(self, folder):
        path = folder / self.name
        if self.content is not None and folder.is_dir():
            path.write_bytes(self.content() if callable(self.content) else self.content)
        return str(path)


def scene():
    """A floor, a ball and a bob on hinges, a box on a slider, a GPS on the ball, a
    hook, an MJCF mocap body."""
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="ball")
    sim.add_box((0.2, 0.2, 0.2), (1.0, 0.1, 0.0), mass=1.0, name="box")
    sim.add_rotary_joint("hinge", "ball", None, (0.0, 1.2, 0.0), (0.0, 0.0, 1.0))
    sim.add_sphere(0.1, (2.0, 1.0, 0.0), mass=1.0, name="bob")
    sim.add_rotary_joint("hinge2", "bob", None, (2.0, 1.2, 0.0), (0.0, 0.0, 1.0))
    sim.add_slider_joint("slide", "box", None, (1.0, 0.0, 0.0))
    sim.add_sensor("gps", "ball")
    sim.add_pre_step(lambda: None)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "mocap.xml")
        with open(path, "w") as f:
            f.write(
                '<mujoco><worldbody><body name="hand" mocap="true" pos="0 0 3"/></worldbody></mujoco>'
            )
        sim.load_mjcf(path)
    sim.step(5)
    return sim


def saved_scene():
    return scene().save_scene().encode()


def snapshot():
    return scene().snapshot()


def saved_sweep():
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "s.npz")
        ars.sweep(lambda p: scene(), [{}], 0.01, progress=False).save(path)
        with open(path, "rb") as f:
            return f.read()


class Pendulum(ars.gym.ArsEnv):
    frame_skip, max_episode_steps, actuators = 2, 10, ("hinge",)
    action_space = float_box([-1.0], [1.0])
    observation_space = float_box([-np.inf], [np.inf])
    render_size = (32, 24)

    def build(self):
        return scene()

    def observe(self):
        return np.array([self.sim.joint("hinge").angle])

    def reward(self, obs, action):
        return 0.0


def gym_id():
    if "test/WalkPendulum-v0" not in gymnasium.registry:
        gymnasium.register(id="test/WalkPendulum-v0", entry_point=Pendulum, max_episode_steps=10)
    return "test/WalkPendulum-v0"


def vector():
    envs = ars.gym.ArsVectorEnv([Pendulum(), Pendulum()])
    envs.reset(seed=0)
    return envs


def reset(env):
    env.reset(seed=0)
    return env


# (name, what is called given a fresh scene, positional arguments, keyword arguments)
SIM = [
    (
        "Simulation",
        lambda s: ars.Simulation,
        (),
        {
            "time_step": 0.001,
            "gravity": (0.0, -9.81, 0.0),
            "steps_per_frame": 10,
            "quick_iterations": 20,
            "seed": 3,
            "stepper": "quick",
        },
    ),
    ("step", None, (5,), {}),
    ("run", None, (0.01,), {}),
    ("step_frame", None, (), {}),
    ("set_stepper", None, ("quick",), {"quick_iterations": 10}),
    ("set_seed", None, (7,), {}),
    ("set_contact_surface", None, (("ball", "floor"),), {"mu": 1.0, "max_contacts": 10}),
    ("contact_surface", None, (("ball", "floor"),), {}),
    ("clear_contact_surface", None, ("ball", "floor"), {}),
    ("exclude_contacts", None, ("ball", "box"), {}),
    ("include_contacts", None, ("ball", "box"), {}),
    (
        "set_geom_contact",
        None,
        ("ball", 0),
        {
            "friction": (1.0, 0.005, 0.0001),
            "condim": 3,
            "solref": (0.02, 1.0),
            "solimp": (0.9, 0.95, 0.001, 0.5, 2.0),
            "priority": 1,
            "solmix": 1.0,
        },
    ),
    ("geom_contact", None, ("ball", 0), {}),
    (
        "set_geom_pair_contact",
        None,
        ("ball", "box", 0, 0),
        {
            "friction": (0.5, 0.005, 0.0001),
            "condim": 3,
            "solref": (0.02, 1.0),
            "solimp": (0.9, 0.95, 0.001, 0.5, 2.0),
        },
    ),
    ("cast_ray", None, ((0.0, 2.0, 0.0), (0.0, -1.0, 0.0), 5.0), {}),
    ("add_sphere", None, (0.1, (0.0, 2.0, 0.0), 1.0), {}),
    ("add_box", None, ((0.1, 0.2, 0.3), (0.0, 2.0, 0.0), 1.0), {}),
    ("add_cylinder", None, (0.2, 0.1, (0.0, 2.0, 0.0), 1.0), {}),
    ("add_capsule", None, (0.2, 0.1, (0.0, 2.0, 0.0), 1.0), {}),
    ("add_cone", None, (0.2, 0.1, (0.0, 2.0, 0.0), 1.0), {}),
    ("add_floor", None, ((0.0, 1.0, 0.0), -1.0), {}),
    (
        "add_trimesh",
        None,
        (
            [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)],
            [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)],
            (0.0, 3.0, 0.0),
        ),
        {},
    ),
    (
        "load_mjcf",
        None,
        (
            Path(
                "m.xml",
                b"<mujoco><worldbody><body><freejoint/>"
                b'<geom type="sphere" size="0.1"/></body></worldbody></mujoco>',
            ),
        ),
        {"base_position": (0.0, 1.0, 0.0)},
    ),
    (
        "load_urdf",
        None,
        (Path("arm.urdf", ARM.read_bytes()),),
        {"fixed_base": True, "base_position": (0.0, 1.0, 0.0), "search_paths": [str(REPO)]},
    ),
    ("set_mocap_pose", None, ("hand", (0.0, 0.0, 2.0), (1.0, 0.0, 0.0, 0.0)), {}),
    ("mocap_pose", None, ("hand",), {}),
    ("remove_object", None, ("box",), {}),
    ("body", None, ("ball",), {}),
    ("add_rotary_joint", None, ("r", "box", None, (1.0, 0.5, 0.0), (0.0, 0.0, 1.0)), {}),
    ("add_slider_joint", None, ("s", "box", None, (1.0, 0.0, 0.0)), {}),
    ("add_ball_socket_joint", None, ("b", "box", None, (1.0, 0.5, 0.0)), {}),
    (
        "add_universal_joint",
        None,
        ("u", "box", None, (1.0, 0.5, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
        {},
    ),
    ("add_piston_joint", None, ("p", "box", None, (1.0, 0.5, 0.0), (1.0, 0.0, 0.0)), {}),
    ("add_fixed_joint", None, ("f", "box", None), {}),
    (
        "add_joint_group",
        None,
        (
            "box",
            None,
            [
                ("gx", "hinge", (1.0, 0.5, 0.0), (1.0, 0.0, 0.0), 0.0),
                ("gy", "hinge", (1.0, 0.5, 0.0), (0.0, 1.0, 0.0), 0.0),
            ],
        ),
        {},
    ),
    ("remove_joint", None, ("hinge",), {}),
    ("joint", None, ("hinge",), {}),
    ("add_sensor", None, ("gps", "box"), {"every": 0.01}),
    (
        "add_lidar",
        None,
        (8, 1.0, 5.0),
        {
            "planes": [0.0, 0.1],
            "position": (0.0, 1.0, 0.0),
            "rotation": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
            "seed": 2,
        },
    ),
    (
        "add_depth_camera",
        None,
        (8, 6, 1.0, 0.1, 10.0),
        {
            "position": (0.0, 1.0, 3.0),
            "rotation": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
        },
    ),
    ("add_pre_step", None, (lambda: None,), {}),
    ("add_post_step", None, (lambda: None,), {}),
    ("remove_hook", None, (1,), {}),
    ("_enable_hook", None, (1, False), {}),
    ("save_scene_to", None, (Path("scene.json"),), {}),
    ("load_scene", lambda s: ars.Simulation.load_scene, (scene().save_scene(),), {}),
    (
        "load_scene_from",
        lambda s: ars.Simulation.load_scene_from,
        (Path("in.json", saved_scene),),
        {},
    ),
    ("open", lambda s: ars.Simulation.open, (Path("in.json", saved_scene),), {}),
    ("from_snapshot", lambda s: ars.Simulation.from_snapshot, (snapshot(),), {}),
    ("restore", None, (snapshot(),), {}),
    (
        "record_video",
        None,
        (Path("v.mp4"), 0.1),
        {
            "fps": 30.0,
            "size": (64, 48),
            "camera": (3.0, 2.0, 3.0),
            "look_at": (0.0, 0.5, 0.0),
            "background": (1.0, 1.0, 1.0),
        },
    ),
    (
        "save_replay",
        None,
        (Path("r.html"), 0.1),
        {"size": (64, 48), "camera": (3.0, 2.0, 3.0), "background": (1.0, 1.0, 1.0)},
    ),
    ("replay", None, (0.1,), {"size": (64, 48), "camera": (3.0, 2.0, 3.0)}),
    ("record_mcap", None, (Path("run.mcap"), 0.1), {"state_rate": 25.0}),
    ("ros", None, (0.01,), {"domain_id": 150, "rate": 50.0}),
    ("show", None, (1.0,), {"frames": 2, "size": (64, 48), "camera": (3.0, 2.0, 3.0)}),
    ("set_gravity", lambda s: lambda g: setattr(s, "gravity", g), ((0.0, -1.0, 0.0),), {}),
]

BODY = [
    (name, args)
    for name, args in [
        ("set_position", ((0.0, 2.0, 0.0),)),
        ("set_rotation", (((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),)),
        ("set_pose", ((0.0, 2.0, 0.0), ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))),
        ("set_linear_velocity", ((1.0, 0.0, 0.0),)),
        ("set_angular_velocity", ((1.0, 0.0, 0.0),)),
        ("add_force", ((1.0, 0.0, 0.0),)),
        ("rotate", ((0.0, 1.0, 0.0), 0.5)),
        ("offset_by_position", ((0.1, 0.0, 0.0),)),
        ("offset_by_object", ("box",)),
        ("set_color", ((0.5, 0.5, 0.5),)),
    ]
]

JOINT = [
    ("set_controller", ("position", 0.5, 10.0, 1.0)),
    ("set_controller", ("position", [(0.0, 0.0), (1.0, 0.5)], 10.0, 1.0)),
    ("set_speed", (1.0, 5.0)),
    ("set_limits", (-1.0, 1.0)),
    ("set_param", ("velocity", 1.0)),
    ("add_torque", (1.0,)),
    ("set_viscous_friction", (0.1,)),
    ("set_dry_friction", (0.1,)),
    ("set_armature", (0.1,)),
    ("set_damping", (0.1,)),
    ("set_spring", (1.0, 0.0)),
    ("set_actuator_limits", (1.0, 1.0)),
    ("set_mimic", ("hinge2", 1.0, 0.0)),
]

CALLS = (
    [(f"Simulation.{n}", target or (lambda s, n=n: getattr(s, n)), a, k) for n, target, a, k in SIM]
    + [(f"Body.{n}", lambda s, n=n: getattr(s.body("ball"), n), a, {}) for n, a in BODY]
    + [(f"Joint.{n}", lambda s, n=n: getattr(s.joint("hinge"), n), a, {}) for n, a in JOINT]
    + [("Joint.add_force", lambda s: s.joint("slide").add_force, (1.0,), {})]
    + [
        ("Sensor.to_csv", lambda s: s.add_sensor("gps", "ball").to_csv, (Path("gps.csv"),), {}),
        (
            "Renderer",
            lambda s: ars.Renderer,
            (32, 24),
            {"camera": (3.0, 2.0, 3.0), "look_at": (0.0, 0.5, 0.0), "background": (1.0, 1.0, 1.0)},
        ),
        (
            "Renderer.save",
            lambda s: lambda p: ars.Renderer(32, 24).save(s, p),
            (Path("f.png"),),
            {},
        ),
        (
            "VideoWriter",
            lambda s: ars.VideoWriter,
            (Path("w.mp4"), 32, 24, 30.0),
            {"camera": (3.0, 2.0, 3.0)},
        ),
        ("step_many", lambda s: lambda n: ars.step_many([s, scene()], n), (5,), {}),
        ("Image.save", lambda s: ars.Renderer(32, 24).render(s).save, (Path("i.png"),), {}),
        ("Replay.save", lambda s: s.replay(0.05).save, (Path("r.html"),), {}),
        (
            "sweep",
            lambda s: ars.sweep,
            (lambda p: scene(), [{}], 0.01),
            {"record": ["ball.position"], "every": 2, "seed": 1, "progress": False},
        ),
        (
            "SweepResults.save",
            lambda s: ars.sweep(lambda p: scene(), [{}], 0.01).save,
            (Path("s.npz"),),
            {},
        ),
        ("load_sweep", lambda s: ars.load_sweep, (Path("in.npz", saved_sweep),), {}),
        ("gym.make_vec", lambda s: ars.gym.make_vec, (gym_id(), 2), {}),
        ("gym.ArsEnv.step", lambda s: reset(Pendulum()).step, ([0.5],), {}),
        ("gym.ArsVectorEnv.reset", lambda s: vector().reset, (), {"seed": [0, 1]}),
        ("gym.ArsVectorEnv.step", lambda s: vector().step, ([[0.5], [0.5]],), {}),
    ]
)

# Public methods that take no argument worth varying (or none at all).
NOTHING_TO_VARY = {
    "Simulation": {
        "excluded_contacts",
        "geom_contacts",
        "geom_pair_contacts",
        "save_scene",
        "snapshot",
        "set_control",
        "control",
        "set_controls",
        "__reduce__",
    },
    "Body": {"_position", "_rotation", "_linear_velocity", "_angular_velocity", "_inertia"},
    "Joint": {"clear_mimic"},
    "Sensor": {"records", "ranges", "points", "images", "clear", "remove"},
    "Renderer": {"render"},
    "VideoWriter": {"add", "finish", "close"},
}


def variants(value):
    """The wrong versions of a value: for a sequence, one item short and one long (and
    the same for a nested sequence's first item); for an int, ±10**30."""
    if isinstance(value, bool):
        return []
    if isinstance(value, int):
        return [10**30, -(10**30)]
    if isinstance(value, (tuple, list)) and value and not isinstance(value[0], dict):
        kind = type(value)
        out = [kind(value[:-1]), kind([*value, value[-1]])]
        if isinstance(value[0], (tuple, list)):
            out += [kind([inner, *value[1:]]) for inner in variants(value[0])[:2]]
        return out
    return []


def resolve(value, folder):
    return value.where(folder) if isinstance(value, Path) else value


def attempt(call, args, kwargs):
    """What the call raised: None, or the exception."""
    try:
        call(*args, **kwargs)
    except BaseException as e:  # noqa: BLE001  (the walk looks at what comes out)
        return e
    return None


@pytest.fixture(autouse=True)
def no_display(monkeypatch):
    """`show` is refused (ars.NoDisplayError) rather than opening a window."""
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)


@pytest.mark.parametrize(("name", "target", "args", "kwargs"), CALLS, ids=[c[0] for c in CALLS])
def test_a_wrong_length_a_huge_integer_or_a_missing_folder_is_an_ars_error(
    tmp_path, name, target, args, kwargs
):
    good = tmp_path / "good"
    good.mkdir()
    missing = tmp_path / "missing"

    def make(args, kwargs, folder):
        sim = scene()
        call = target(sim)
        args = [resolve(a, folder) for a in args]
        return call, args, {k: resolve(v, folder) for k, v in kwargs.items()}

    call, a, k = make(args, kwargs, good)
    base = attempt(call, a, k)
    if name != "Simulation.show":  # no display: refused, but after its arguments
        assert base is None, f"{name} as written failed: {base!r}"
    else:
        assert isinstance(base, ars.NoDisplayError), repr(base)
    wrong = []
    for i, value in enumerate(list(args) + list(kwargs.values())):
        key = i - len(args) if i >= len(args) else None
        if isinstance(value, Path):
            tries = [("missing folder", value, missing, ars.FileError)]
        else:
            tries = [(f"{v!r:.60}", v, good, ars.ArsError) for v in variants(value)]
        for label, v, folder, expected in tries:
            call, a, k = make(args, kwargs, folder)
            if key is None:
                a[i] = resolve(v, folder)
            else:
                k[list(kwargs)[key]] = resolve(v, folder)
            raised = attempt(call, a, k)
            where = f"argument {i if key is None else list(kwargs)[key]!r} = {label}"
            if raised is not None and not isinstance(raised, expected):
                wrong.append(
                    f"{where}: {type(raised).__module__}.{type(raised).__qualname__}: {raised}"
                )
            if isinstance(raised, KeyboardInterrupt):
                raise raised
    assert not wrong, f"{name}:\n" + "\n".join(wrong)
    leftover = [p for p in good.iterdir() if p.name.startswith(".")]
    assert not leftover, leftover


def public_methods(cls):
    return {
        n
        for n, v in vars(cls).items()
        if callable(v) or isinstance(v, (staticmethod, classmethod))
        if not n.startswith("__") or n == "__reduce__"
    } - {"__new__"}


@pytest.mark.parametrize(
    "cls",
    [ars.Simulation, ars.Body, ars.Joint, ars.Sensor, ars.Renderer, ars.VideoWriter],
    ids=lambda c: c.__name__,
)
def test_every_public_method_is_walked(cls):
    walked = {name.split(".", 1)[1] for name, *_ in CALLS if name.startswith(cls.__name__ + ".")}
    methods = {m for m in public_methods(cls) if not inspect.isdatadescriptor(vars(cls)[m])}
    left = methods - walked - NOTHING_TO_VARY[cls.__name__]
    assert not left, f"{cls.__name__}: add these to CALLS or NOTHING_TO_VARY: {sorted(left)}"


def test_a_wrong_type_is_a_type_error():
    sim = scene()
    for call in (
        lambda: sim.step("5"),
        lambda: sim.add_sphere(0.1, "abc"),
        lambda: ars.step_many([sim], "5"),
    ):
        with pytest.raises(TypeError):
            call()


def test_an_image_that_is_not_one_is_an_input_error(tmp_path):
    with pytest.raises(ars.InputError, match="uint8"):
        np.zeros((4, 4, 3), np.float64).view(Image).save(tmp_path / "x.png")
    assert os.listdir(tmp_path) == []


def test_replay_save_is_whole_and_a_file_error_elsewhere(tmp_path):
    replay = Replay("<html></html>", None, 1, 0.0, 0.0)
    replay.save(tmp_path / "r.html")
    assert (tmp_path / "r.html").read_text() == "<html></html>"
    with pytest.raises(ars.FileError) as caught:
        replay.save(tmp_path / "nowhere" / "r.html")
    assert caught.value.filename == str(tmp_path / "nowhere" / "r.html")
    assert os.listdir(tmp_path) == ["r.html"]
