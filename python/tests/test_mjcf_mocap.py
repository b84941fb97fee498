"""MuJoCo's mocap bodies in ARS, against MuJoCo: a kinematic body moved by
`set_mocap_pose` (MuJoCo's `data.mocap_pos`/`mocap_quat`), and what a weld joins to it
following it."""

import math

import numpy as np
import pytest
from conftest import corpus_file

import ars

mujoco = pytest.importorskip("mujoco")

# A two-link planar arm whose hand is welded to a mocap body, as Meta-World holds its
# Sawyer's hand; and a free box on the floor that the mocap "pusher" can push.
ARM = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="arm" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0" damping="0.5"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
      <body name="hand" pos="0.3 0 0">
        <joint name="wrist" axis="0 1 0" damping="0.5"/>
        <geom size="0.04"/>
      </body>
    </body>
    <body name="target" mocap="true" pos="0.3 0 1">
      <geom size="0.01" contype="0" conaffinity="0"/>
    </body>
    <body name="pusher" mocap="true" pos="-1 0 0.05">
      <geom type="box" size="0.05 0.2 0.1"/>
    </body>
    <body name="crate" pos="-0.7 0 0.05">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.2"/>
    </body>
  </worldbody>
  <equality><weld body1="target" body2="hand"/></equality>
</mujoco>"""


def mujoco_of(path):
    m = mujoco.MjModel.from_xml_path(str(path))
    return m, mujoco.MjData(m)


def in_mujoco_frame(position):
    """ARS's (x, y, z) is MuJoCo's (x, -z, y)."""
    x, y, z = position
    return np.array([x, -z, y])


def goal_at(t):
    """The mocap body's path: swung down about the shoulder along the circle the hand
    can reach (0.3 m), turned with it about y, over the first second; then held."""
    angle = math.radians(40.0) * min(t, 1.0)
    position = [0.3 * math.cos(angle), 0.0, 1.0 - 0.3 * math.sin(angle)]
    quaternion = [math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0]
    return position, quaternion


@pytest.fixture
def arm(tmp_path):
    path = tmp_path / "mocap_arm.xml"
    path.write_text(ARM)
    return path


def test_a_mocap_body_is_listed_and_moved_in_the_file_s_frame(arm):
    sim = ars.Simulation(time_step=0.002)
    model = sim.load_mjcf(arm)
    assert model["mocap"] == ["target", "pusher"]
    position, quaternion = sim.mocap_pose("target")
    assert position == pytest.approx([0.3, 0.0, 1.0], abs=1e-12)
    assert quaternion == pytest.approx([1.0, 0.0, 0.0, 0.0], abs=1e-12)
    sim.run(0.5)
    # Kinematic: gravity does not move it.
    assert sim.mocap_pose("target")[0] == pytest.approx([0.3, 0.0, 1.0], abs=1e-12)
    sim.set_mocap_pose("target", (0.1, 0.2, 0.3), (2.0, 0.0, 0.0, 0.0))
    position, quaternion = sim.mocap_pose("target")
    assert position == pytest.approx([0.1, 0.2, 0.3], abs=1e-12)
    assert quaternion == pytest.approx([1.0, 0.0, 0.0, 0.0], abs=1e-12), "normalised, as MuJoCo's"
    assert list(sim.body("target").position) == pytest.approx([0.1, 0.3, -0.2], abs=1e-12)


def test_set_mocap_pose_refuses_bad_input_and_moves_nothing(arm):
    sim = ars.Simulation()
    sim.load_mjcf(arm)
    before = sim.mocap_pose("target")
    with pytest.raises(ars.UnknownNameError, match="mocap body"):
        sim.set_mocap_pose("hand", (0.0, 0.0, 0.0))
    for position, quaternion in [
        ((math.nan, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0)),
        ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)),
        ((0.0, 0.0, 0.0), (math.inf, 0.0, 0.0, 0.0)),
    ]:
        with pytest.raises(ars.InputError):
            sim.set_mocap_pose("target", position, quaternion)
    with pytest.raises((ars.InputError, TypeError)):
        sim.set_mocap_pose("target", (0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
    assert sim.mocap_pose("target") == before


def test_a_hand_welded_to_a_moving_mocap_body_follows_it_as_in_mujoco(arm):
    """The mocap body is moved along a path at every step (0.21 m/s at the hand), as a
    controller moves Meta-World's. Both hands lag it while it moves, MuJoCo's by
    8.3 mm: its weld is soft (solref 0.02 s, critically damped). ARS's fixed joint
    takes the ERP of that reference acceleration (0.05 at 2 ms) and lags by 8.0 mm;
    with the world's ERP (0.2) it lagged by 1.7 mm. What is left between them is
    MuJoCo's impedance (its weld gives a little under the arm's weight) and the
    weld's rotation rows, which keep the world's ERP in ODE. The hands are compared
    every 0.1 s: within 1.5 mm while moving (measured 0.4 to 0.7 mm), within 1 mm
    once held (0.1 to 0.4 mm)."""
    m, d = mujoco_of(arm)
    hand_id = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "hand")
    target = m.body_mocapid[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "target")]
    sim = ars.Simulation(time_step=0.002)
    sim.load_mjcf(arm)
    steps = 1000
    worst_moving, worst_held = 0.0, 0.0
    for k in range(steps):
        position, quaternion = goal_at(k * 0.002)
        d.mocap_pos[target] = position
        d.mocap_quat[target] = quaternion
        mujoco.mj_step(m, d)
        sim.set_mocap_pose("target", position, quaternion)
        sim.step()
        if (k + 1) % 50 == 0:
            gap = np.linalg.norm(in_mujoco_frame(sim.body("hand").position) - d.xpos[hand_id])
            if k * 0.002 < 1.0:
                worst_moving = max(worst_moving, gap)
            else:
                worst_held = max(worst_held, gap)
    assert worst_moving < 1.5e-3, worst_moving
    assert worst_held < 1e-3, worst_held
    # And both reached the goal.
    goal = np.array(goal_at(2.0)[0])
    assert np.linalg.norm(in_mujoco_frame(sim.body("hand").position) - goal) < 1e-3
    assert np.linalg.norm(d.xpos[hand_id] - goal) < 1e-3


def test_a_moving_mocap_body_pushes_what_it_meets_and_not_the_floor(arm):
    """The pusher starts inside the floor: a mocap body touches nothing static, in
    MuJoCo as in ARS. Moved 0.5 m along x in 1 s, it pushes the crate ahead of it in
    both, to within 2 cm of each other (the crate slides at MuJoCo's friction 1 in
    both; what separates them is how each engine's contact lets go)."""
    m, d = mujoco_of(arm)
    pusher = m.body_mocapid[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "pusher")]
    crate = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "crate")
    sim = ars.Simulation(time_step=0.002)
    sim.load_mjcf(arm)
    for k in range(750):
        x = -1.0 + 0.5 * min((k + 1) * 0.002, 1.0)
        d.mocap_pos[pusher] = [x, 0.0, 0.05]
        mujoco.mj_step(m, d)
        sim.set_mocap_pose("pusher", (x, 0.0, 0.05))
        sim.step()
    ours, theirs = in_mujoco_frame(sim.body("crate").position), d.xpos[crate]
    assert theirs[0] > -0.46 and ours[0] > -0.46, (ours, theirs)
    assert abs(ours[0] - theirs[0]) < 0.02, (ours, theirs)
    assert abs(ours[2] - theirs[2]) < 2e-3, "the crate stays on the floor"
    assert sim.mocap_pose("pusher")[0] == pytest.approx([-0.5, 0.0, 0.05], abs=1e-12)


def test_meta_world_s_sawyer_is_held_by_its_mocap_weld_as_in_mujoco():
    """Meta-World's Sawyer hangs from its mocap body by a soft weld, and its shoulder
    (right_j1, range -3.8 to -0.5 rad) starts at 0, outside its range. MuJoCo lets the
    shoulder go to its stop within about 0.3 s, its links at most 3 m/s, the hand held.
    So does ARS (3.5 m/s measured): the weld's ERP and CFM are MuJoCo's softness. As
    stiff as every joint, it fought the stop and whipped the arm at 30 to 130 m/s; with
    the ERP alone, at 30 to 60 m/s."""
    path = corpus_file("metaworld-3.1.1/metaworld/assets/sawyer_xyz/sawyer_reach_v3.xml")
    if path is None:
        pytest.skip("the corpus is not fetched (test_corpus.py fetches it)")
    m, d = mujoco_of(path)
    mujoco.mj_forward(m, d)
    link = m.body("right_l6").id
    link0 = d.xipos[link].copy()
    while d.time < 2.0:
        mujoco.mj_step(m, d)
    sim = ars.Simulation.open(path)
    ours0 = np.array(sim.body("right_l6").position)
    bodies = [sim.body(name) for name in sim.objects if name.startswith("right_l")]
    fastest = 0.0
    for _ in range(20):
        sim.run(0.1)
        fastest = max(fastest, *(np.linalg.norm(b.linear_velocity) for b in bodies))
    assert fastest < 6.0, fastest
    j1 = sim.joint("right_j1").position
    assert j1 == pytest.approx(d.qpos[m.joint("right_j1").qposadr[0]], abs=0.01)
    # Where the two differ: the shoulder's stop and the weld cannot both hold (the arm
    # has one spare degree of freedom), and each engine gives way where its constraints
    # are softest. MuJoCo's weld gives in position and in turn alike: its last link
    # turns 10 to 16 degrees and moves 3 cm. ODE's fixed joint has no softness for its
    # rotation rows, so ARS's gives in position only: the link keeps its turn and moves
    # 6.2 cm. Held here so that a change of either is seen.
    theirs = np.linalg.norm(d.xipos[link] - link0)
    ours = np.linalg.norm(np.array(sim.body("right_l6").position) - ours0)
    assert 0.02 < theirs < 0.04 and ours < 0.07, (ours, theirs)
