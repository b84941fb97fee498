"""MJCF models against MuJoCo's own compiled model: every body's mass, centre of mass
and principal moments of inertia equal to MuJoCo's to 1e-9 relative; models written
by others (Gymnasium's) load and run."""

import itertools
import os
import pathlib
import re

import numpy as np
import pytest
from conftest import corpus_file

import ars

mujoco = pytest.importorskip("mujoco")

PENDULUM = """
<mujoco model="double pendulum">
  <option timestep="0.001"/>
  <default>
    <joint type="hinge" axis="0 1 0" damping="0.01"/>
    <geom type="capsule" size="0.03" density="500"/>
    <default class="heavy"><geom density="2000"/></default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="upper" pos="0 0 1.5" euler="0 20 0">
      <joint name="shoulder" range="-90 90"/>
      <geom fromto="0 0 0 0 0 -0.5"/>
      <body name="lower" pos="0 0 -0.5" childclass="heavy">
        <joint name="elbow"/>
        <geom fromto="0 0 0 0.4 0 0"/>
        <geom type="box" size="0.05 0.03 0.02" pos="0.4 0 0" euler="10 30 5"/>
        <geom type="cylinder" size="0.02 0.1" pos="0.2 0.05 0" quat="0.9 0.1 0.3 0.2"/>
        <geom type="sphere" size="0.04" pos="0.1 0 0.05" mass="0.3"/>
      </body>
    </body>
  </worldbody>
</mujoco>"""

ARM = """
<mujoco model="arm">
  <compiler angle="radian" eulerseq="zyx"/>
  <worldbody>
    <body name="base" pos="0 0 0.2">
      <joint name="j1" type="hinge" axis="0 0 1"/>
      <inertial pos="0.01 0.02 0.1" quat="0.8 0.2 0.4 0.1" mass="2.5" diaginertia="0.02 0.03 0.01"/>
      <geom type="cylinder" size="0.05 0.1"/>
      <body name="link1" pos="0 0 0.2" euler="0.3 0.2 0.1">
        <joint name="j2" type="hinge" axis="0 1 0"/>
        <inertial pos="0.15 0 0" mass="1.2" fullinertia="0.01 0.02 0.025 0.001 -0.002 0.0005"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
        <body name="link2" pos="0.3 0 0" axisangle="1 1 0 0.4">
          <joint name="j3" type="hinge" axis="0 1 0"/>
          <geom type="box" size="0.12 0.02 0.02" pos="0.12 0 0"/>
          <geom type="ellipsoid" size="0.03 0.04 0.05" pos="0.24 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>"""


def gymnasium_asset(name):
    gymnasium = pytest.importorskip("gymnasium")
    return os.path.join(os.path.dirname(gymnasium.__file__), "envs", "mujoco", "assets", name)


def compare(path):
    """Loads `path` in ARS and in MuJoCo and compares every body's mass, centre of mass
    (in the world, MuJoCo's (x, y, z) being ARS's (x, z, -y)) and inertia. A jointless
    body is welded into its parent (`model["welded"]`), one rigid body with it as in
    MuJoCo: each ARS body is compared with MuJoCo's bodies it holds, combined."""
    sim = ars.Simulation()
    model = sim.load_mjcf(path, skip_unsupported=True)
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    turn = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])

    def index(name):
        i = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name)
        return i if i >= 0 else int(name.removeprefix("body"))  # unnamed: ARS's body{id}

    for name in model["bodies"]:
        held = [index(name)] + [index(w) for w, into in model["welded"].items() if into == name]
        body = sim.body(name)
        # A body lighter than ARS allows (a marker of milligrams) is raised to its
        # least mass, its inertia scaled alike, and said.
        scale = 1.0
        if any(s.startswith(f'"{name}": a mass of') and "raised" in s for s in model["skipped"]):
            scale = 1e-9 / m.body_mass[held[0]]
            assert scale > 1.0 and len(held) == 1, name
        mass = sum(m.body_mass[i] for i in held) * scale
        assert body.mass == pytest.approx(mass, rel=1e-9), name
        centre = sum(m.body_mass[i] * scale * d.xipos[i] for i in held) / mass
        x, y, z = centre
        assert body.position == pytest.approx([x, z, -y], rel=1e-9, abs=1e-12), name
        # MuJoCo's bodies' inertias in the world, about their common centre.
        theirs = np.zeros((3, 3))
        for i in held:
            frame = turn @ d.ximat[i].reshape(3, 3)
            offset = turn @ (d.xipos[i] - centre)
            theirs += frame @ np.diag(m.body_inertia[i] * scale) @ frame.T
            theirs += (
                m.body_mass[i] * scale * (offset @ offset * np.eye(3) - np.outer(offset, offset))
            )
        # The inertia ARS adds for the armature of the joint moving it is MuJoCo's
        # dof_armature, not part of body_inertia.
        inertia = body.inertia - np.array(model["armature"].get(name, np.zeros((3, 3))))
        ours = body.rotation @ inertia @ body.rotation.T
        assert ours == pytest.approx(theirs, rel=1e-9, abs=1e-12 * np.abs(theirs).max()), name
        moments = np.sort(np.linalg.eigvalsh(inertia))
        assert moments == pytest.approx(np.sort(np.linalg.eigvalsh(theirs)), rel=1e-9, abs=1e-15), (
            name
        )
    return sim, model


def mujoco_schema():
    """MuJoCo's schema as {(parent, element): attributes}, from `mj_printSchema`."""
    schema, stack = {}, []
    for line in mujoco.mj_printSchema(False, False).splitlines():
        match = re.match(r"^( *)(\S+) \(.\)\s*(.*)$", line)
        if match:
            depth = len(match.group(1)) // 3
            stack[depth:] = [match.group(2)]
            key = (stack[-2] if depth else None, match.group(2))
            schema[key] = set(match.group(3).split())
        elif line.strip():
            schema[key] |= set(line.split())
    return schema


def test_ars_knows_the_attributes_mujoco_s_schema_gives():
    """ARS refuses an attribute MuJoCo does not know (a typo) and accepts every one it
    does: its list (ars-core/src/formats/mjcf/schema.rs) is MuJoCo's, element by
    element, in the places ARS reads them."""
    source = (
        pathlib.Path(__file__).parents[2] / "ars-core" / "src" / "formats" / "mjcf" / "schema.rs"
    )
    text = source.read_text()
    ours = {
        tag: set(re.findall(r'"(\w+)"', names))
        for tag, names in re.findall(r'\("(\w+)", &\[([^\]]*)\]\)', text)
    }
    common = set(
        re.findall(r'"(\w+)"', re.search(r"SENSOR_ATTRIBUTES: [^=]*= \[([^\]]*)\]", text).group(1))
    )
    schema = mujoco_schema()
    parents = {
        "mujoco": None, "compiler": "mujoco", "option": "mujoco", "default": "mujoco",
        "body": "mujoco", "inertial": "(world)body", "joint": "(world)body",
        "freejoint": "(world)body", "geom": "(world)body", "site": "(world)body",
        "mesh": "asset", "material": "asset", "pair": "contact", "exclude": "contact",
        "motor": "actuator", "position": "actuator", "velocity": "actuator", "general": "actuator",
        "keyframe": "mujoco", "key": "keyframe",
    }  # fmt: skip
    checked = 0
    for tag, attributes in ours.items():
        if tag == "include":  # MuJoCo reads includes before its schema sees the file
            continue
        if tag in parents:
            theirs = schema[(parents[tag], "(world)body" if tag == "body" else tag)]
        else:  # a sensor
            theirs = schema[("sensor", tag)]
            attributes = attributes | common
        assert attributes == theirs, (tag, attributes ^ theirs)
        checked += 1
    assert checked > 25, checked


TETRAHEDRON_OBJ = """v 0 0 0
v 0.5 0 0
v 0 0.25 0
v 0 0 0.75
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
"""

CUBE_OBJ = "".join(f"v {x} {y} {z}\n" for z in (0, 1) for y in (0, 1) for x in (0, 1)) + "".join(
    f"f {a} {b} {c}\n"
    for a, b, c in [
        (1, 3, 2), (2, 3, 4), (5, 6, 7), (6, 8, 7), (1, 2, 5), (2, 6, 5),
        (3, 7, 4), (4, 7, 8), (1, 5, 3), (3, 5, 7), (2, 4, 6), (4, 8, 6),
    ]
)  # fmt: skip

MESHES = """
<mujoco model="meshes">
  <compiler meshdir="parts"/>
  <asset>
    <mesh file="tetra.obj"/>
    <mesh name="brick" file="cube.obj" scale="0.5 0.25 2"/>
  </asset>
  <worldbody>
    <body name="pointed" pos="0 0 1" euler="10 20 30">
      <freejoint/>
      <geom type="mesh" mesh="tetra" pos="0.1 0 0" euler="0 45 0"/>
      <geom type="sphere" size="0.05" pos="-0.2 0 0"/>
    </body>
    <body name="brick" pos="1 0 1">
      <freejoint/>
      <geom type="mesh" mesh="brick" mass="3" quat="0.9 0.1 0.3 0.2"/>
    </body>
  </worldbody>
</mujoco>"""


def test_mesh_geoms_weigh_as_in_mujoco(tmp_path):
    """Mesh geoms (OBJ files in the compiler's meshdir, scaled): their mass, centre and
    inertia tensor, from the closed mesh, as MuJoCo computes them."""
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "tetra.obj").write_text(TETRAHEDRON_OBJ)
    (tmp_path / "parts" / "cube.obj").write_text(CUBE_OBJ)
    path = tmp_path / "meshes.xml"
    path.write_text(MESHES)
    sim, _ = compare(path)
    assert sim.body("brick").mass == pytest.approx(3.0)
    sim.run(0.5)


def test_masses_centres_and_inertias_equal_mujoco_s(tmp_path):
    for name, text in (("pendulum.xml", PENDULUM), ("arm.xml", ARM)):
        path = tmp_path / name
        path.write_text(text)
        compare(path)


GYMNASIUM = [
    "inverted_pendulum.xml",
    "inverted_double_pendulum.xml",
    "reacher.xml",
    "ant.xml",
    "hopper.xml",
    "walker2d.xml",
    "half_cheetah.xml",
    "swimmer.xml",
    "humanoid.xml",
    "humanoidstandup.xml",
    "pusher.xml",
    "pusher_v5.xml",
    "walker2d_v5.xml",
    "point.xml",
]


@pytest.mark.parametrize("asset", GYMNASIUM)
def test_gymnasium_models_load_match_mujoco(asset):
    _, model = compare(gymnasium_asset(asset))
    # Every attribute they use is MuJoCo's.
    assert not [s for s in model["skipped"] if "unknown attribute" in s]


@pytest.mark.parametrize("asset", ["ant.xml", "humanoid.xml", "half_cheetah.xml"])
def test_actuators_are_in_mujoco_s_ctrl_order(asset):
    """`sim.actuators` is MuJoCo's `data.ctrl` order, so a policy's action vector set
    with `set_controls` drives the joints MuJoCo's would."""
    path = gymnasium_asset(asset)
    sim = ars.Simulation()
    model = sim.load_mjcf(path, skip_unsupported=True)
    mj = mujoco.MjModel.from_xml_path(path)
    # An unnamed actuator is `actuator{id}` in ARS, with MuJoCo's id.
    names = [mj.actuator(i).name or f"actuator{i}" for i in range(mj.nu)]
    assert sim.actuators == names
    joints = [mj.joint(mj.actuator_trnid[i, 0]).name for i in range(mj.nu)]
    assert [joint for _, _, joint in model["actuators"]] == joints
    # Inside every control range (the humanoid's are ±0.4), so set exactly.
    action = np.linspace(-0.3, 0.3, mj.nu)
    sim.set_controls(action)
    assert sim.controls == action.tolist()
    assert [sim.control(n) for n in names] == sim.controls
    with pytest.raises(ars.InputError, match=f"{mj.nu - 1} values for {mj.nu} actuators"):
        sim.set_controls(action[:-1])


@pytest.mark.parametrize("asset", GYMNASIUM)
def test_gymnasium_models_run(asset):
    """Models written by others run 2 s, hopper, walker and half-cheetah with their
    planar roots chained. (The pushers run because joint damping is implicit, as
    MuJoCo's: their goal marker weighs milligrams on damped slides, which explicit
    damping would throw back faster each step. The humanoids run because a
    body chained to its parent, as their hips are, does not touch it, as in MuJoCo.)
    Without control they stand or fall, and come to rest: no body rises, none still
    moves fast after 2 s."""
    sim = ars.Simulation()
    model = sim.load_mjcf(gymnasium_asset(asset), skip_unsupported=True)
    assert model["joints"], asset
    start = max(sim.body(name).position[1] for name in model["bodies"])
    sim.run(2.0)
    for name in model["bodies"]:
        body = sim.body(name)
        assert np.isfinite(body.position).all(), (asset, name)
        assert body.position[1] < start + 0.1, (asset, name, body.position)
        assert np.linalg.norm(body.linear_velocity) < 5.0, (asset, name, body.linear_velocity)


SWINGING = """
<mujoco model="swinging">
  <default><geom contype="0" conaffinity="0"/></default>
  <worldbody>
    <body name="p1" pos="0 0 2" euler="0 50 0">
      <joint name="a1" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.03"/>
      <body name="p2" pos="0 0 -0.4" euler="30 0 0">
        <joint name="a2" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 -0.2" size="0.025"/>
      </body>
    </body>
  </worldbody>
</mujoco>"""


def angles_after_one_second(path, joints, dt, controls=None):
    sim = ars.Simulation(time_step=dt)
    sim.load_mjcf(path)
    for name, ctrl in (controls or {}).items():
        sim.set_control(name, ctrl)
    sim.run(1.0)
    return np.array([sim.joint(j).angle for j in joints])


def mujoco_angles_after_one_second(path, joints, controls=None):
    """MuJoCo's joint angles after 1 s, RK4 at 0.1 ms, with these controls."""
    m = mujoco.MjModel.from_xml_path(str(path))
    m.opt.timestep = 1e-4
    m.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    d = mujoco.MjData(m)
    for name, ctrl in (controls or {}).items():
        d.ctrl[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, name)] = ctrl
    while d.time < 1.0 - 1e-9:
        mujoco.mj_step(m, d)
    return np.array(
        [d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, j)]] for j in joints]
    )


def assert_first_order(path, joints, reference, controls=None, what=""):
    """ARS's joint positions after 1 s approach `reference` (MuJoCo's) as the time
    step halves, to first order: each halving about halves the gap."""
    gaps = [
        np.abs(angles_after_one_second(path, joints, dt, controls) - reference).max()
        for dt in (2e-3, 1e-3, 5e-4)
    ]
    assert gaps[0] > gaps[1] > gaps[2], (what, gaps)
    for coarse, fine in itertools.pairwise(gaps):
        assert 1.6 < coarse / fine < 2.5, (what, gaps)


def test_actuated_motion_converges_to_mujoco_s_with_the_time_step(tmp_path):
    """The swinging pendulum with a position servo (kp, kv) on its first joint and a
    geared motor, its control clamped by its range, on the second: the joint angles
    after 1 s approach MuJoCo's to first order in the time step."""
    actuators = """<actuator>
      <position name="hold" joint="a1" kp="20" kv="1"/>
      <motor name="push" joint="a2" gear="2" ctrlrange="-0.1 0.1"/>
    </actuator></mujoco>"""
    path = tmp_path / "actuated.xml"
    path.write_text(SWINGING.replace("</mujoco>", actuators))
    controls = {"hold": 0.3, "push": 1.0}
    reference = mujoco_angles_after_one_second(path, ["a1", "a2"], controls)
    passive = mujoco_angles_after_one_second(path, ["a1", "a2"])
    assert np.abs(reference - passive).max() > 0.1, "the actuators change the motion"
    assert_first_order(path, ["a1", "a2"], reference, controls)
    sim = ars.Simulation()
    sim.load_mjcf(path)
    assert sim.actuators == ["hold", "push"]
    sim.set_control("push", 1.0)
    assert sim.control("push") == 0.1
    with pytest.raises(ars.UnknownNameError, match="hold"):
        sim.set_control("hodl", 0.0)


def test_hinge_armatures_converge_to_mujoco_s_with_the_time_step(tmp_path):
    """A hinge's armature is the joint's own inertia (a motor beside the joint, implicit,
    as MuJoCo's joint-space armature), on the root hinge and on the one below it, whose
    axis moves: the angles after 1 s approach MuJoCo's to first order in the time step,
    and the bodies keep MuJoCo's masses and inertias (`compare`)."""
    plain = tmp_path / "plain.xml"
    plain.write_text(SWINGING)
    path = tmp_path / "armature.xml"
    path.write_text(
        SWINGING.replace(
            'name="a1" type="hinge"', 'name="a1" type="hinge" armature="0.05"'
        ).replace('name="a2" type="hinge"', 'name="a2" type="hinge" armature="0.02"')
    )
    assert path.read_text().count("armature=") == 2
    reference = mujoco_angles_after_one_second(path, ["a1", "a2"])
    assert np.abs(reference - mujoco_angles_after_one_second(plain, ["a1", "a2"])).max() > 0.1
    assert_first_order(path, ["a1", "a2"], reference)
    sim, model = compare(path)
    assert not model["armature"], model["armature"]
    assert not any("armature" in s for s in model["skipped"]), model["skipped"]
    assert (sim.joint("a1").armature, sim.joint("a2").armature) == (0.05, 0.02)
    sim.joint("a2").set_armature(0.0)
    assert sim.joint("a2").armature == 0.0
    with pytest.raises(ars.InputError, match="armature"):
        sim.joint("a1").set_armature(-1.0)


SPRUNG = """
<mujoco model="sprung">
  <default><geom contype="0" conaffinity="0"/></default>
  <worldbody>
    <body name="p1" pos="0 0 2" euler="0 50 0">
      <joint name="a1" type="hinge" axis="0 1 0" ref="20" stiffness="3" springref="35" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.03"/>
      <body name="p2" pos="0 0 -0.4">
        <joint name="s2" type="slide" axis="0 0 1" ref="0.1" stiffness="40" springref="0.15"/>
        <geom type="box" size="0.05 0.05 0.05"/>
      </body>
    </body>
  </worldbody>
</mujoco>"""


def test_reference_positions_and_springs_move_as_mujoco_s(tmp_path):
    """A hinge and a slide with `ref` (their positions in the file's pose) and springs
    (`stiffness` about `springref`): they start at MuJoCo's qpos0, and their positions
    after 1 s approach MuJoCo's to first order in the time step."""
    path = tmp_path / "sprung.xml"
    path.write_text(SPRUNG)
    sim = ars.Simulation()
    sim.load_mjcf(path)
    m = mujoco.MjModel.from_xml_path(str(path))
    assert [sim.joint("a1").angle, sim.joint("s2").position] == pytest.approx(m.qpos0, abs=1e-12)
    assert sim.joint("a1").angle == pytest.approx(np.radians(20), abs=1e-12)
    reference = mujoco_angles_after_one_second(path, ["a1", "s2"])
    still = tmp_path / "still.xml"
    still.write_text(
        SPRUNG.replace('stiffness="3"', 'stiffness="0"').replace('stiffness="40"', 'stiffness="0"')
    )
    assert np.abs(reference - mujoco_angles_after_one_second(still, ["a1", "s2"])).max() > 0.1
    assert_first_order(path, ["a1", "s2"], reference)


def test_a_range_is_of_the_positions_ref_measures(tmp_path):
    """A slide's range is in MuJoCo's coordinates, where the file's pose is at `ref`:
    a spring pulling past the upper end holds it there in both; and a `frictionloss`
    above what gravity pulls with holds a pendulum still (ARS's dry friction)."""
    path = tmp_path / "ranged.xml"
    path.write_text(SPRUNG.replace('springref="0.15"/>', 'springref="0.4" range="0.05 0.12"/>'))
    sim = ars.Simulation()
    sim.load_mjcf(path)
    sim.run(1.0)
    ours = sim.joint("s2").position
    theirs = mujoco_angles_after_one_second(path, ["s2"])[0]
    # ODE's stop is hard; MuJoCo's limit is soft (solref): it sits 2 mm past.
    assert ours == pytest.approx(0.12, abs=1e-3), ours
    assert theirs == pytest.approx(0.12, abs=3e-3), theirs
    held = tmp_path / "held.xml"
    held.write_text(
        SWINGING.replace('name="a1" type="hinge"', 'name="a1" type="hinge" frictionloss="100"')
    )
    sim = ars.Simulation()
    sim.load_mjcf(held)
    sim.run(0.5)
    assert abs(sim.joint("a1").angle) < 1e-3


def test_contact_free_motion_converges_to_mujoco_s_with_the_time_step(tmp_path):
    """From the same state under gravity, ARS's joint angles after 1 s approach
    MuJoCo's (RK4 at 0.1 ms) as the time step shrinks, to first order."""
    # The arm with its collisions off: its last link swings into its base.
    no_contacts = '<default><geom contype="0" conaffinity="0"/></default><worldbody>'
    for name, text, joints in (
        ("swinging.xml", SWINGING, ["a1", "a2"]),
        ("arm.xml", ARM.replace("<worldbody>", no_contacts, 1), ["j1", "j2", "j3"]),
    ):
        path = tmp_path / name
        path.write_text(text)
        m = mujoco.MjModel.from_xml_path(str(path))
        m.opt.timestep = 1e-4
        m.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
        d = mujoco.MjData(m)
        while d.time < 1.0 - 1e-9:
            mujoco.mj_step(m, d)
        reference = np.array(
            [
                d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, j)]]
                for j in joints
            ]
        )
        assert_first_order(path, joints, reference, what=name)
        assert np.abs(reference).max() > 0.1, (name, reference)


def test_sensors_read_what_mujoco_s_read(tmp_path):
    """jointpos and framepos (a body's centre of mass) as MuJoCo computes them: after
    one step of a microsecond from the same state, ARS's records equal MuJoCo's
    sensordata at the start (MuJoCo's (x, y, z) being ARS's (x, z, -y))."""
    sensors = """<sensor>
      <jointpos name="q1" joint="a1"/>
      <jointpos name="q2" joint="a2"/>
      <framepos name="tip" objtype="body" objname="p2"/>
      <jointvel name="w1" joint="a1"/>
    </sensor></mujoco>"""
    path = tmp_path / "sensed.xml"
    path.write_text(SWINGING.replace("</mujoco>", sensors))
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    sim = ars.Simulation(time_step=1e-6)
    model = sim.load_mjcf(path)
    assert list(model["sensors"]) == ["q1", "q2", "tip", "w1"]
    sim.step()

    def last(sensor):
        row = sensor.records()[-1]
        return [float(row[field]) for field in row.dtype.names[2:]]

    ours = {name: last(sensor) for name, sensor in model["sensors"].items()}
    assert ours["q1"] == pytest.approx([d.sensordata[0]], abs=1e-9)
    assert ours["q2"] == pytest.approx([d.sensordata[1]], abs=1e-9)
    x, y, z = d.sensordata[2:5]
    assert ours["tip"] == pytest.approx([x, z, -y], abs=1e-9)
    assert list(ours["tip"]) == list(sim.body("p2").position)
    assert ours["w1"] == [sim.joint("a1").rate]
    assert [s.kind for s in model["sensors"].values()] == [
        "joint_positions",
        "joint_positions",
        "gps",
        "joint_velocities",
    ]


SITE_SENSORS = """
<mujoco model="site sensors">
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="arm" pos="0 0 1.5">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <inertial pos="0.1 0 -0.2" quat="0.9 0.1 0.3 0.2" mass="1.5" diaginertia="0.02 0.03 0.04"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.03"/>
      <site name="tip" pos="0.05 0.02 -0.5" euler="10 20 30"/>
      <site name="down" pos="0.2 0 -0.5" zaxis="0.3 0 -1"/>
      <site name="up" zaxis="0 0 1"/>
    </body>
    <body name="box" pos="1 0 1" euler="20 -10 40">
      <freejoint/>
      <geom type="box" size="0.1 0.08 0.05"/>
      <site name="corner" pos="0.1 0.08 0.05" euler="0 30 0"/>
    </body>
  </worldbody>
  <sensor>
    <gyro name="arm_gyro" site="tip"/>
    <accelerometer name="arm_acc" site="tip"/>
    <framepos name="tip_at" objtype="site" objname="tip"/>
    <framequat name="tip_turn" objtype="site" objname="tip"/>
    <framelinvel name="tip_v" objtype="site" objname="tip"/>
    <framepos name="arm_at" objtype="xbody" objname="arm"/>
    <framequat name="arm_turn" objtype="xbody" objname="arm"/>
    <framequat name="arm_inertia" objtype="body" objname="arm"/>
    <rangefinder name="floor_range" site="down"/>
    <rangefinder name="sky_range" site="up"/>
    <gyro name="box_gyro" site="corner"/>
    <accelerometer name="box_acc" site="corner"/>
    <framepos name="corner_at" objtype="site" objname="corner"/>
    <framelinvel name="corner_v" objtype="site" objname="corner"/>
    <velocimeter name="corner_vel" site="corner"/>
    <velocimeter name="tip_vel" site="tip"/>
    <framequat name="box_turn" objtype="xbody" objname="box"/>
    <magnetometer name="tip_compass" site="tip"/>
    <magnetometer name="corner_compass" site="corner"/>
  </sensor>
</mujoco>"""

# MuJoCo's world (x, y, z) is ARS's (x, z, -y): this turn (-90 degrees about X).
TURN = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
TURN_QUAT = np.array([np.sqrt(0.5), -np.sqrt(0.5), 0.0, 0.0])


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ])  # fmt: skip


def moving_site_sensors(path, dt, duration=None):
    """The model in ARS and in MuJoCo, the arm swinging at 1.5 rad/s and the box flying
    and tumbling, in ARS after `duration` (one step of `dt` by default); MuJoCo's at
    the start (forward)."""
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    d.qvel[0] = 1.5
    d.qvel[1:4] = [0.3, -0.2, 0.5]  # the box's origin (its centre), world frame
    d.qvel[4:7] = [1.0, -2.0, 0.7]  # its angular velocity, its frame
    mujoco.mj_forward(m, d)
    sim = ars.Simulation(time_step=dt)
    model = sim.load_mjcf(path)
    arm, box = sim.body("arm"), sim.body("box")
    spin = TURN @ np.array([0.0, 1.5, 0.0])
    arm.set_angular_velocity(spin)
    arm.set_linear_velocity(np.cross(spin, np.array(arm.position) - TURN @ [0.0, 0.0, 1.5]))
    box.set_linear_velocity(TURN @ d.qvel[1:4])
    box.set_angular_velocity(TURN @ d.xmat[2].reshape(3, 3) @ d.qvel[4:7])
    if duration is None:
        sim.step()
    else:
        sim.run(duration)
    return m, d, sim, model


def last_row(sensor):
    row = sensor.records()[-1]
    return np.array([float(row[field]) for field in row.dtype.names[2:]])


def test_site_sensors_read_what_mujoco_s_read(tmp_path):
    """gyro, framepos, framequat, framelinvel and magnetometer on sites and body frames,
    and rangefinders, as MuJoCo computes them: after one step of a microsecond, ARS's
    records equal MuJoCo's sensordata after the same step to 1e-9 (MuJoCo's (x, y, z)
    being ARS's (x, z, -y); a quaternion turned the same way, up to its sign)."""
    path = tmp_path / "sites.xml"
    path.write_text(SITE_SENSORS)
    m, d, _, model = moving_site_sensors(path, 1e-6)
    assert model["sites"] == {"tip": "arm", "down": "arm", "up": "arm", "corner": "box"}
    # ARS's rays are cast in the collision pass at the start of the step, as MuJoCo's
    # sensordata after mj_step are computed before it integrates.
    ranges = {name: d.sensor(name).data[0] for name in ["floor_range", "sky_range"]}
    # MuJoCo's sensors at the end of the same step.
    m.opt.timestep = 1e-6
    mujoco.mj_step(m, d)
    mujoco.mj_forward(m, d)

    def theirs(name):
        return np.array(d.sensor(name).data)

    ours = {name: last_row(sensor) for name, sensor in model["sensors"].items()}
    kinds = {name: sensor.kind for name, sensor in model["sensors"].items()}
    assert (
        kinds["arm_gyro"] == "imu"
        and kinds["tip_turn"] == "orientation"
        and kinds["floor_range"] == "laser"
    )
    for name in ["arm_gyro", "box_gyro"]:
        # The site's angular velocity in its own frame: the IMU's last three columns.
        assert ours[name][3:] == pytest.approx(theirs(name), abs=1e-9), name
        assert np.abs(theirs(name)).max() > 1.0, name
    for name in ["tip_at", "arm_at", "corner_at"]:
        assert ours[name] == pytest.approx(TURN @ theirs(name), abs=1e-9), name
    # The free box's corner moves as MuJoCo's to 1e-9. The arm's tip not quite: ODE
    # keeps a hinged body's velocity tangent to its path at the start of the step, so
    # it lags MuJoCo's (tangent at the end) by the centripetal acceleration times the
    # step, w^2 r dt (1.5^2 * 0.6 m * 1 us = 1.35e-6 m/s at most on this arm).
    assert ours["corner_v"][:3] == pytest.approx(TURN @ theirs("corner_v"), abs=1e-9)
    assert ours["tip_v"][:3] == pytest.approx(TURN @ theirs("tip_v"), abs=1.5**2 * 0.6 * 1e-6)
    # The same velocities in the sites' own frames (MuJoCo's velocimeter).
    assert kinds["corner_vel"] == "velocimeter"
    assert ours["corner_vel"][:3] == pytest.approx(theirs("corner_vel"), abs=1e-9)
    assert ours["tip_vel"][:3] == pytest.approx(theirs("tip_vel"), abs=1.5**2 * 0.6 * 1e-6)
    assert np.abs(theirs("corner_vel")).max() > 0.1
    for name in ["tip_turn", "arm_turn", "arm_inertia", "box_turn"]:
        q = quat_mul(TURN_QUAT, theirs(name))
        q = q if q[0] >= 0 else -q
        assert ours[name] == pytest.approx(q, abs=1e-9), name
    # MuJoCo's default field, (0, -0.5, 0), in each site's frame.
    for name in ["tip_compass", "corner_compass"]:
        assert kinds[name] == "magnetometer"
        assert ours[name] == pytest.approx(theirs(name), abs=1e-9), name
        assert np.abs(theirs(name)).max() > 0.1, name
    # The inertial frame is not the body's: the two quaternions differ.
    assert np.abs(ours["arm_turn"] - ours["arm_inertia"]).max() > 0.1
    # The ray down meets the floor; the one up meets nothing (MuJoCo's -1, NaN here).
    assert ours["floor_range"][0] == pytest.approx(ranges["floor_range"], abs=1e-9)
    assert ranges["floor_range"] > 0.9
    assert ranges["sky_range"] == -1.0 and np.isnan(ours["sky_range"][0])


def test_accelerometers_converge_to_mujoco_s(tmp_path):
    """MuJoCo's accelerometer is the site's acceleration at an instant, minus gravity,
    in the site's frame (mj_rnePostConstraint: with its centripetal and tangential
    terms); ARS's is the change of the site's velocity over a step, minus gravity.

    On the free box, over one step from the same state, they differ by about the jerk
    times half the step: the gap shrinks tenfold with the step. On the hinged arm, ODE
    keeps the body's velocity tangent to its path at the start of each step and its
    error correction brings the centripetal pull back over the next steps: after a
    quarter second of swinging, the gap to MuJoCo's (run with a 10 us step) halves
    with the step."""
    path = tmp_path / "sites.xml"
    path.write_text(SITE_SENSORS)
    gaps = []
    for dt in [1e-3, 1e-4, 1e-5]:
        m, d, sim, model = moving_site_sensors(path, dt)
        theirs = np.array(d.sensor("box_acc").data)
        gaps.append(np.abs(last_row(model["sensors"]["box_acc"])[:3] - theirs).max())
    for coarse, fine in itertools.pairwise(gaps):
        assert 8 < coarse / fine < 12, gaps
    # The free box feels no gravity: what it reads is its spin's.
    assert gaps[2] < 1e-4 * np.abs(theirs).max() and np.abs(theirs).max() > 0.1, (gaps, theirs)

    m, d, _, _ = moving_site_sensors(path, 1e-5)
    m.opt.timestep = 1e-5
    mujoco.mj_step(m, d, nstep=25000)
    mujoco.mj_forward(m, d)
    theirs = np.array(d.sensor("arm_acc").data)
    gaps = []
    for dt in [1e-3, 5e-4, 2.5e-4]:
        _, _, sim, model = moving_site_sensors(path, dt, duration=0.25)
        assert sim.time == pytest.approx(0.25)
        gaps.append(np.abs(last_row(model["sensors"]["arm_acc"])[:3] - theirs).max())
    for coarse, fine in itertools.pairwise(gaps):
        assert 1.6 < coarse / fine < 2.5, gaps
    assert gaps[2] < 2e-3 * np.abs(theirs).max(), (gaps, theirs)


TOUCHED = """
<mujoco model="touched">
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="box" pos="0 0 0.3" euler="0 0 30">
      <freejoint/>
      <geom type="box" size="0.1 0.08 0.05" mass="2"/>
      <site name="pad" type="box" size="0.11 0.09 0.01" pos="0 0 -0.05"/>
      <site name="lid" type="box" size="0.11 0.09 0.01" pos="0 0 0.05"/>
    </body>
  </worldbody>
  <sensor>
    <touch name="pad" site="pad"/>
    <touch name="lid" site="lid"/>
  </sensor>
</mujoco>"""


def test_touch_reads_a_resting_box_s_weight(tmp_path):
    """A box falls on the floor: its pad (a site around its bottom face) feels nothing
    in the air, then its weight m·g at rest, as MuJoCo's touch does; its lid nothing."""
    path = tmp_path / "touched.xml"
    path.write_text(TOUCHED)
    sim = ars.Simulation(time_step=1e-3)
    model = sim.load_mjcf(path)
    pad, lid = model["sensors"]["pad"], model["sensors"]["lid"]
    sim.step()
    assert list(last_row(pad)) == [0.0, 0.0]
    # The file's contacts are MuJoCo's soft ones (its default solref and solimp): ODE's
    # settles into its resting depth over about 0.4 s at this step (19.6198 N read at
    # 2 s, 19.6199985 N at 4 s), MuJoCo's faster.
    sim.run(4.0)
    weight = 2.0 * 9.81
    contacts, force = last_row(pad)
    # At rest, the contact impulses balance gravity over each step: the weight (19.62 N);
    # MuJoCo's soft contacts settle to it too (19.62000001 N).
    assert force == pytest.approx(weight, rel=1e-6)
    assert contacts >= 4
    assert list(last_row(lid)) == [0.0, 0.0]
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_step(m, d, nstep=int(4.0 / m.opt.timestep))
    assert d.sensor("pad").data[0] == pytest.approx(force, rel=1e-6)
    assert d.sensor("lid").data[0] == 0.0


def test_general_actuators_hold_where_mujoco_holds_and_keyframes_are_listed(tmp_path):
    # A scaled servo (force 500·ctrl − 200·q) on a hinge in zero gravity, with a key.
    text = """
<mujoco>
  <option gravity="0 0 0" timestep="0.002"/>
  <worldbody>
    <body name="arm"><joint name="hinge" axis="0 1 0" damping="5"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.03"/></body>
  </worldbody>
  <actuator>
    <general name="servo" joint="hinge" gainprm="500" biastype="affine" biasprm="0 -200 0"/>
  </actuator>
  <keyframe><key name="home" qpos="0.3" ctrl="0.1"/></keyframe>
</mujoco>"""
    path = tmp_path / "servo.xml"
    path.write_text(text)
    # The file's option is not applied by load_mjcf: the simulation is made so.
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0), time_step=0.002)
    model = sim.load_mjcf(str(path))
    assert model["actuators"] == [("servo", "general", "hinge")]
    assert model["keyframes"] == [
        {
            "name": "home",
            "time": 0.0,
            "qpos": [0.3],
            "qvel": [],
            "ctrl": [0.1],
            "mpos": [],
            "mquat": [],
        }
    ]
    sim.set_control("servo", 0.2)
    sim.run(3.0)
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    d.ctrl[0] = 0.2
    while d.time < 3.0 - 1e-9:
        mujoco.mj_step(m, d)
    # Both settle at 500·0.2 / 200 = 0.5 rad (ARS's hinge angle is MuJoCo's about the
    # simulation's −Z, MuJoCo's Y).
    assert abs(d.qpos[0] - 0.5) < 1e-4
    assert abs(abs(sim.joint("hinge").angle) - d.qpos[0]) < 1e-4


SUBTREE_SENSORS = """
<mujoco model="subtree sensors">
  <worldbody>
    <body name="torso" pos="0 0 1" euler="10 -5 30">
      <freejoint/>
      <geom type="box" size="0.2 0.1 0.05" mass="3"/>
      <body name="leg" pos="0.2 0 0" euler="0 20 0">
        <joint name="hip" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
        <body name="foot" pos="0.3 0 0">
          <joint name="knee" axis="1 0 0"/>
          <geom type="box" size="0.05 0.03 0.02" pos="0.02 0.01 0" mass="0.5"/>
        </body>
      </body>
      <body name="tail" pos="-0.2 0 0"><geom size="0.03" mass="0.2"/></body>
    </body>
  </worldbody>
  <sensor>
    <subtreecom name="all_com" body="torso"/>
    <subtreelinvel name="all_v" body="torso"/>
    <subtreeangmom name="all_L" body="torso"/>
    <subtreecom name="leg_com" body="leg"/>
    <subtreelinvel name="leg_v" body="leg"/>
    <subtreeangmom name="leg_L" body="leg"/>
    <subtreecom name="tail_com" body="tail"/>
  </sensor>
</mujoco>"""


def test_subtree_sensors_read_what_mujoco_s_read(tmp_path):
    """subtreecom, subtreelinvel and subtreeangmom (a body and the bodies below it) as
    ARS's momentum sensor: every body given MuJoCo's velocity from the same joint
    velocities, then one step of a microsecond, after which the records equal MuJoCo's
    sensordata (MuJoCo's (x, y, z) being ARS's (x, z, -y)): the centres of mass and
    the whole model's momentum to 1e-8, the leg's within the lag below. A body merged into its parent has no object of its own:
    its subtree sensor is skipped, and refused strictly."""
    path = tmp_path / "subtree.xml"
    path.write_text(SUBTREE_SENSORS)
    with pytest.raises(ars.InputError, match="tail"):
        ars.Simulation().load_mjcf(path)
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    d.qvel[:] = [0.3, -0.2, 0.5, 1.0, -2.0, 0.7, 1.5, -2.0]
    mujoco.mj_forward(m, d)
    sim = ars.Simulation(time_step=1e-6)
    model = sim.load_mjcf(path, skip_unsupported=True)
    assert any("tail_com" in s or '"tail"' in s for s in model["skipped"]), model["skipped"]
    assert "tail_com" not in model["sensors"]
    for name in ["torso", "leg", "foot"]:
        body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name)
        velocity = np.zeros(6)
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, body, velocity, 0)
        spin, linear = velocity[:3], velocity[3:]
        # mj_objectVelocity gives a body's velocity at its centre of mass; the object's
        # is elsewhere for the torso, which holds the tail's mass too.
        centre = TURN.T @ np.array(sim.body(name).position)
        at_centre = linear + np.cross(spin, centre - d.xipos[body])
        sim.body(name).set_linear_velocity(TURN @ at_centre)
        sim.body(name).set_angular_velocity(TURN @ spin)
    sim.step()
    m.opt.timestep = 1e-6
    mujoco.mj_step(m, d)
    mujoco.mj_forward(m, d)
    ours = {name: last_row(sensor) for name, sensor in model["sensors"].items()}
    assert {sensor.kind for sensor in model["sensors"].values()} == {"momentum"}
    # The whole model's momentum is kept over the step in both engines: 1e-8. The leg's
    # is not (the torso pulls it round): ODE keeps a hinged body's velocity tangent to
    # its path at the start of the step, and lags MuJoCo's by about w^2 r dt (the
    # framelinvel lag above), here at most (4 rad/s)^2 * 0.5 m * 1 us = 8e-6.
    for subtree, lag in [("all", 1e-8), ("leg", 8e-6)]:
        com, v, angular = (np.array(d.sensor(f"{subtree}_{k}").data) for k in ["com", "v", "L"])
        assert ours[f"{subtree}_com"][:3] == pytest.approx(TURN @ com, abs=1e-8), subtree
        assert ours[f"{subtree}_v"][3:6] == pytest.approx(TURN @ v, abs=lag), subtree
        assert ours[f"{subtree}_L"][6:] == pytest.approx(TURN @ angular, abs=lag), subtree
        assert np.abs(angular).max() > 0.01 and np.abs(v).max() > 0.1, subtree


HFIELD = """
<mujoco>
  <asset>
    <hfield name="hill" nrow="5" ncol="7" size="2 1 0.5 0.1"
            elevation="0 1 2 3 4 5 6  2 3 1 0 5 8 9  4 4 4 9 2 1 0  7 3 5 1 0 2 2  1 1 1 1 1 1 13"/>
  </asset>
  <worldbody>
    <geom type="hfield" hfield="hill" pos="0.3 -0.2 0.1" euler="0 0 30"/>
  </worldbody>
</mujoco>"""


def terrain_heights(m, d, sim, points):
    """The terrain's height under each (x, y) of MuJoCo's frame, by a ray cast down in
    each engine (MuJoCo's (x, y, z) being ARS's (x, z, -y))."""
    out = []
    for x, y in points:
        geom = np.zeros(1, np.int32)
        theirs = 10.0 - mujoco.mj_ray(
            m, d, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, geom
        )
        hit = sim.cast_ray((x, 10.0, -y), (0.0, -1.0, 0.0), 20.0)
        out.append((theirs, None if hit is None else hit[1][1]))
    return out


def test_height_fields_stand_where_mujoco_s_do(tmp_path):
    """A height field of `elevation` numbers, turned and moved, and dm_control's height
    field of a PNG picture: under 400 points each, ARS's terrain is at MuJoCo's height
    to 1e-9 (both are the same planar triangles over each cell, when each cell is cut
    along the same diagonal: ARS cuts from its (-x, -y) corner to its (+x, +y) one, and
    MuJoCo answers the same at every point tried; a differing diagonal would show as
    centimetres)."""
    path = tmp_path / "hfield.xml"
    path.write_text(HFIELD)
    rng = np.random.default_rng(7)
    for file in [
        path,
        corpus_file("dm-control-1.0.50/dm_control/mjcf/test_assets/model_with_assets.xml"),
    ]:
        if file is None:
            continue
        m = mujoco.MjModel.from_xml_path(str(file))
        d = mujoco.MjData(m)
        mujoco.mj_forward(m, d)
        sim = ars.Simulation()
        sim.load_mjcf(file, skip_unsupported=True)
        geom = int(np.flatnonzero(m.geom_type == mujoco.mjtGeom.mjGEOM_HFIELD)[0])
        size = m.hfield_size[m.geom_dataid[geom]]
        local = rng.uniform(-0.98, 0.98, size=(400, 2)) * size[:2]
        turn = d.geom_xmat[geom].reshape(3, 3)[:2, :2]
        points = local @ turn.T + d.geom_xpos[geom][:2]
        pairs = terrain_heights(m, d, sim, points)
        assert all(ours is not None for _, ours in pairs), file
        worst = max(abs(theirs - ours) for theirs, ours in pairs)
        assert worst < 1e-9, (file, worst)
        assert np.ptp([theirs for theirs, _ in pairs]) > 0.1 * size[2], "the terrain is not flat"
