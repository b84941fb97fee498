"""Sim-to-sim: ARS against MuJoCo on Gymnasium's own MuJoCo models (the ant, the hopper,
the humanoid) and on a hand-written two-finger grasp (issue 37). Each test runs the same
file in both engines side by side (`ars.Simulation.open`: the file's time step and
gravity; MuJoCo with the file's own options, RK4 where the file says so) and compares
what a user would look at: heights, joint angles, when a robot has fallen, where it went.

The engines differ by design, and each tolerance below says which difference it allows
and what was measured (MuJoCo 4.0.0, Gymnasium 1.4.0's assets): ODE solves hard
contacts and joint limits (an LCP, errors corrected by ERP/CFM, mapped from a contact's
`solref`/`solimp` and a stop's `solreflimit`), MuJoCo soft ones (its friction creeps
under load, a few mm/s here); ODE has no contact `margin` (MuJoCo's ant feet rest 2 cm
above the floor). A joint's `armature` is the joint's own in both (ARS: an implicit
motor beside the joint). Where a difference decides the motion, the test is marked
`xfail(strict=True)` with the numbers and the cause. Twin tests remove one cause in both
engines (the hopper's armature, the humanoid's knees starting outside their range) and
were how the armature and the stops' softness were found: they stay, as the cleanest
checks of the rest. What ARS skips in these files (`margin`) warns and is ignored here;
the humanoid's two fixed tendons, which nothing drives or limits, do nothing in either.

MuJoCo's axes are used throughout: ARS's (x, y, z) with Y up is MuJoCo's (x, -z, y);
positions are centres of mass (ARS's bodies are at theirs; MuJoCo's `xipos`)."""

import os
import pathlib
import warnings

import numpy as np
import pytest

import ars

mujoco = pytest.importorskip("mujoco")

# ARS's world (Y up) to MuJoCo's (Z up): a vector's (x, y, z) in ARS is (x, -z, y) in
# MuJoCo, and a body's rotation in MuJoCo is MJ_FROM_ARS @ its rotation in ARS (ARS keeps
# the file's body frames).
MJ_FROM_ARS = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


def gymnasium_asset(name):
    gymnasium = pytest.importorskip("gymnasium")
    return os.path.join(os.path.dirname(gymnasium.__file__), "envs", "mujoco", "assets", name)


def edited(tmp_path, name, *edits):
    """A copy of Gymnasium's `name` with each `(old, new)` text replaced; each `old`
    must be there, so a changed asset fails here rather than testing something else."""
    text = pathlib.Path(gymnasium_asset(name)).read_text()
    for old, new in edits:
        assert old in text, (name, old)
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def open_in_ars(path):
    """`ars.Simulation.open`, its warnings about what it skips (listed above) silenced."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        return ars.Simulation.open(path)


def side_by_side(
    path, seconds, body, joints=(), controls=None, adjust_mujoco=None, adjust_ars=None
):
    """Runs `path` for `seconds` in MuJoCo and in ARS, step for step, `controls(t)` (MuJoCo's
    `data.ctrl` order) set before each step at time t. Returns per step the time, `body`'s
    centre of mass in each engine and the hinge/slide `joints`' positions in each, and
    `body`'s final rotation in each. `adjust_mujoco(model)` changes MuJoCo's model only,
    `adjust_ars(sim)` ARS's simulation only."""
    model = mujoco.MjModel.from_xml_path(path)
    if adjust_mujoco is not None:
        adjust_mujoco(model)
    data = mujoco.MjData(model)
    sim = open_in_ars(path)
    if adjust_ars is not None:
        adjust_ars(sim)
    dt = model.opt.timestep
    # The file's time step, exactly: every time below counts steps of it.
    assert sim.time_step == dt, (sim.time_step, dt)
    theirs_body = model.body(body).id
    addresses = [model.jnt_qposadr[model.joint(name).id] for name in joints]
    ours_body = sim.body(body)
    ours_joints = [sim.joint(name) for name in joints]
    steps = round(seconds / dt)
    run = {key: [] for key in ("time", "mujoco", "ars", "mujoco_joints", "ars_joints")}
    for k in range(steps):
        if controls is not None:
            ctrl = np.asarray(controls(k * dt), dtype=float)
            data.ctrl[:] = ctrl
            sim.set_controls(ctrl)
        mujoco.mj_step(model, data)
        sim.step()
        run["time"].append((k + 1) * dt)
        run["mujoco"].append(data.xipos[theirs_body].copy())
        run["ars"].append(MJ_FROM_ARS @ ours_body.position)
        run["mujoco_joints"].append([data.qpos[a] for a in addresses])
        run["ars_joints"].append(
            [j.position if j.kind == "slider" else j.angle for j in ours_joints]
        )
    run = {key: np.array(value) for key, value in run.items()}
    run["mujoco_rotation"] = data.xmat[theirs_body].reshape(3, 3).copy()
    run["ars_rotation"] = MJ_FROM_ARS @ ours_body.rotation
    run["ars_speed"] = float(np.linalg.norm(ours_body.linear_velocity))
    return run


def crossing(run, engine, height):
    """When `engine`'s body first went below `height` (None: never)."""
    below = np.nonzero(run[engine][:, 2] < height)[0]
    return float(run["time"][below[0]]) if below.size else None


def angle_gap_degrees(a, b):
    """|a − b| in degrees, angles in radians taken modulo a turn (ARS's hinge angles are
    in (−π, π], MuJoCo's unbounded)."""
    return np.abs((np.degrees(np.asarray(a) - np.asarray(b)) + 180.0) % 360.0 - 180.0)


# ---------------------------------------------------------------------------------------
# 1. The ant at rest.

ANT_LEGS = ["hip_1", "ankle_1", "hip_2", "ankle_2", "hip_3", "ankle_3", "hip_4", "ankle_4"]


def without_margins(model):
    model.geom_margin[:] = 0.0


def test_ant_lands_at_mujoco_s_height_and_joint_angles_and_rests():
    """The ant, dropped from its file's pose under zero control, lands on its four feet.
    Its ankles start at 0, outside their ranges (±30°..±70°): both engines push them in,
    the legs spread, and friction catches the feet. Both land alike (compared over
    0.22–0.31 s, step by step); then ARS's ant rests, held by Coulomb friction, while
    MuJoCo's soft friction lets its legs keep folding (about 4° per 0.1 s; after 15 s it
    lies on its ankle limits, at 0.38 m)."""
    path = gymnasium_asset("ant.xml")
    run = side_by_side(path, 1.0, "torso", ANT_LEGS)
    touching = side_by_side(path, 1.0, "torso", ANT_LEGS, adjust_mujoco=without_margins)
    times = run["time"]
    landing = (times >= 0.22 - 1e-9) & (times <= 0.31 + 1e-9)
    ours = run["ars"][landing][:, 2]
    theirs, theirs_touching = run["mujoco"][landing][:, 2], touching["mujoco"][landing][:, 2]
    # Torso height, each step of the landing. The file gives every geom `margin="0.01"`,
    # so MuJoCo's feet act 2 cm above the floor; ARS has no margin and its feet touch
    # it. ARS's torso must lie between MuJoCo's with every margin zeroed, less 8 mm, and
    # MuJoCo's as written, plus 5 mm: measured 6.6 mm below the first at most, 21.5 mm
    # below the second at least (MuJoCo's two runs are 2–2.5 cm apart here). Caught:
    # 20 % less gravity (16.7 mm below), the time step halved (118 mm) or doubled (35 mm).
    assert (theirs_touching - ours).max() < 0.008, (theirs_touching, ours)
    assert (ours - theirs).max() < 0.005, (ours, theirs)
    # Ankles, each step of the landing: 3°. Measured 2.72° at most (ARS holds 69.1–69.2°,
    # MuJoCo passes from 70.2° to 66.3°). Caught: 20 % more gravity (3.09°), the time step
    # halved (19.4°) or doubled (7.8°).
    ankles = slice(1, None, 2)
    gaps = angle_gap_degrees(run["ars_joints"][landing], run["mujoco_joints"][landing])
    assert gaps[:, ankles].max() < 3.0, gaps[:, ankles].max()
    hips = slice(0, None, 2)
    assert np.abs(np.degrees(run["ars_joints"][-1][hips])).max() < 0.1, run["ars_joints"][-1]
    assert np.abs(np.degrees(run["mujoco_joints"][-1][hips])).max() < 0.1
    # After 1 s ARS's ant is at rest, centred.
    assert run["ars_speed"] < 1e-3, run["ars_speed"]
    assert np.abs(run["ars"][-1][:2]).max() < 1e-3, run["ars"][-1]


# ---------------------------------------------------------------------------------------
# 2. The hopper's fall.

HOPPER_JOINTS = ["rooty", "thigh_joint", "leg_joint", "foot_joint"]
HOPPER_WITHOUT_ARMATURE = (
    '<joint armature="1" damping="1" limited="true"/>',
    '<joint armature="0" damping="1" limited="true"/>',
)


def hopper_tap(t):
    """A push on the thigh (the first actuator): −20 N·m from 0.2 s to 0.3 s, once the
    hopper has landed; nothing after."""
    return [-0.1 if 0.2 <= t < 0.3 else 0.0, 0.0, 0.0]


def assert_hopper_rests_as_mujoco_s(run):
    """The fallen hopper's final pose, the same in both: torso within 2 cm of height and
    5 cm along x, every hinge within 5°. It has tumbled onto its back and slid: where it
    stops depends on the contacts' landing impulses and friction, hard in ARS and soft
    in MuJoCo (measured below: up to 7 mm, 3.4 cm and 3.3°). Rests that differ in kind
    (on its folded leg, or over on its head) are 40° to 120° apart."""
    ours, theirs = run["ars"][-1], run["mujoco"][-1]
    assert abs(ours[2] - theirs[2]) < 0.02, (ours, theirs)
    assert abs(ours[0] - theirs[0]) < 0.05, (ours, theirs)
    gaps = angle_gap_degrees(run["ars_joints"][-1], run["mujoco_joints"][-1])
    assert gaps.max() < 5.0, (
        gaps,
        np.degrees(run["ars_joints"][-1]),
        np.degrees(run["mujoco_joints"][-1]),
    )


def test_hopper_pushed_over_falls_when_and_as_mujoco_s_does(tmp_path):
    """The hopper, its armature set to 0 in both engines (see the module's doc), gets one
    push on the thigh and then falls under zero control. It passes 1.1, 0.8 and 0.5 m of
    torso height within 10 ms of MuJoCo's: measured 0.348/0.506/0.616 s against
    0.350/0.508/0.620 s. Gravity 10 % off moves the last crossing by 12-14 ms in either
    engine; the push on the foot instead (the actuators in reverse order) by 0.65 s or more, no
    push by 0.9 s or more. It lands as MuJoCo's does, on its back (−280° about y)."""
    path = edited(tmp_path, "hopper.xml", HOPPER_WITHOUT_ARMATURE)
    run = side_by_side(path, 3.0, "torso", HOPPER_JOINTS, controls=hopper_tap)
    for height in (1.1, 0.8, 0.5):
        ours, theirs = crossing(run, "ars", height), crossing(run, "mujoco", height)
        assert ours is not None and theirs is not None, (height, ours, theirs)
        assert abs(ours - theirs) < 0.01, (height, ours, theirs)
    assert_hopper_rests_as_mujoco_s(run)


def test_hopper_left_alone_falls_backwards_and_rests_as_mujoco_s_does(tmp_path):
    """The hopper (armature 0 in both) under zero control from its file's pose: balanced
    on its foot, it lands from 4 cm, and the landing's small asymmetric impulse grows (an
    unstable equilibrium: e-fold every 0.14 s in both engines) until it falls backwards.
    A soft and a hard contact seed it differently: at 1 s MuJoCo's torso leans back
    4.8°, ARS's 0.026°, about 180 times less, so ARS's falls 0.14 s × ln 180 ≈ 0.73 s
    later (below 0.5 m at 1.552 s in MuJoCo, 2.286 s in ARS). When it falls is therefore
    only bounded here; how it falls and where it rests agree (measured: torso height
    1.2 mm apart, x 2.5 cm, every hinge within 0.5°)."""
    path = edited(tmp_path, "hopper.xml", HOPPER_WITHOUT_ARMATURE)
    run = side_by_side(path, 3.5, "torso", HOPPER_JOINTS)
    for engine in ("mujoco", "ars"):
        fell = crossing(run, engine, 0.5)
        assert fell is not None and 1.0 < fell < 3.0, (engine, fell)
        assert run[engine][-1][0] < -0.1, (engine, run[engine][-1])  # backwards
    assert_hopper_rests_as_mujoco_s(run)


def test_hopper_as_gymnasium_ships_it_pushed_over_falls_when_mujoco_s_does():
    """The shipped hopper (armature 1 on every joint: 10 to 15 times its links' own
    inertia), pushed as above. Its torso passes 1.1/0.8/0.5 m at 0.828/1.170/1.408 s,
    MuJoCo's at 0.828/1.174/1.418 s: 12 ms allowed where its armature-free twin holds
    10 ms, for the last crossing, the torso meeting the ground, where the soft and the
    hard contact part first. (With the armature on the links' inertia, as ARS had it, the
    crossings were 0.36/0.58/0.85 s.)"""
    run = side_by_side(gymnasium_asset("hopper.xml"), 3.0, "torso", HOPPER_JOINTS, hopper_tap)
    for height in (1.1, 0.8, 0.5):
        ours, theirs = crossing(run, "ars", height), crossing(run, "mujoco", height)
        assert ours is not None and theirs is not None, (height, ours, theirs)
        assert abs(ours - theirs) < 0.012, (height, ours, theirs)


def test_hopper_as_gymnasium_ships_it_rests_as_mujoco_s_does():
    """The shipped hopper left alone, compared as above."""
    run = side_by_side(gymnasium_asset("hopper.xml"), 3.5, "torso", HOPPER_JOINTS)
    assert_hopper_rests_as_mujoco_s(run)


# ---------------------------------------------------------------------------------------
# 3. The humanoid's collapse.

HUMANOID_COLLAPSE_HEIGHTS = (1.2, 1.0, 0.8)


def assert_humanoid_collapses_when_mujoco_s_does(run):
    """The torso's centre of mass (1.43 m at first) passes 1.2, 1.0 and 0.8 m within
    20 ms of MuJoCo's. Measured with the knees starting in range (below): 3 ms at most
    (0.603/0.810/1.029 s against 0.600/0.807/1.032 s). Gravity 10 % off moves them by
    36 to 126 ms in both engines. (A doubled or halved time step moves them 3 ms at most,
    the collapse being slow next to it: `side_by_side`'s check of the step catches it.)"""
    for height in HUMANOID_COLLAPSE_HEIGHTS:
        ours, theirs = crossing(run, "ars", height), crossing(run, "mujoco", height)
        assert ours is not None and theirs is not None, (height, ours, theirs)
        assert abs(ours - theirs) < 0.02, (height, ours, theirs)


def test_humanoid_collapses_when_mujoco_s_does(tmp_path):
    """The humanoid under zero control drops 10 cm onto its feet and folds at the hips
    and waist (its knees held straight by their limits) until it sits. Its knees' range
    is made −160°..2° in both engines so that they start inside it (see the next test)."""
    path = edited(tmp_path, "humanoid.xml", ('range="-160 -2"', 'range="-160 2"'))
    assert_humanoid_collapses_when_mujoco_s_does(side_by_side(path, 1.2, "torso"))


def test_humanoid_as_gymnasium_ships_it_collapses_when_mujoco_s_does():
    """The shipped humanoid, its knees starting at 0, 2° outside their range (−160°..−2°),
    compared as above. ARS's stops are as soft as `solreflimit` says (ERP 0.073 at 3 ms):
    with the world's ERP (0.2) the knees were thrown in at 2.3 rad/s, coasted on past
    −2° and buckled first (0.408/0.525/0.603 s against 0.489/0.618/0.699 s)."""
    run = side_by_side(gymnasium_asset("humanoid.xml"), 1.2, "torso")
    assert_humanoid_collapses_when_mujoco_s_does(run)


# ---------------------------------------------------------------------------------------
# 4. The ant driven open loop.


def heading_degrees(rotation):
    """Where the body's x axis points in the ground plane, degrees from MuJoCo's x."""
    return np.degrees(np.arctan2(rotation[1, 0], rotation[0, 0]))


@pytest.mark.xfail(
    strict=True,
    reason="Walking over contacts: the gait's outcome decides on where each foot slips, and "
    "ODE's hard Coulomb friction and missing contact margin (the file's feet act 1 cm "
    "early in MuJoCo) part from MuJoCo's soft contacts within a stride. After 3 s (ARS "
    "against MuJoCo): phase step π/4: travel (−0.67, 0.96) m vs (0.02, 0.16) m, heading "
    "−128° vs −111°; π/2: (0, 0.29) m vs (0, 1.05) m, both straight ahead; 3π/4: (−0.25, "
    "1.22) m vs (1.85, 1.90) m, heading 152° vs 27°; 5π/4: (0.79, −0.95) m vs (0.99, "
    "0.28) m, heading −148° vs −79°. (With the armature on the legs' inertia, as ARS had "
    "it, π/2 went the opposite way: (0, −4.14) m.)",
)
@pytest.mark.parametrize("phase_step", [1, 2, 3, 5], ids=lambda k: f"phase-{k}pi/4")
def test_ant_driven_open_loop_goes_where_mujoco_s_goes(phase_step):
    """A policy-like drive: every actuator, in file order, at 0.4 sin(2πt + i·kπ/4),
    i its index, for 3 s. Walking over contacts diverges between engines, so only the
    gross outcome is compared: the torso's heading and its direction of travel within
    15°, the distance travelled within 25 % (MuJoCo's ant goes 0.16 to 2.7 m). Four
    drives, so that one lucky or unlucky gait decides nothing."""
    phases = np.arange(8) * phase_step * np.pi / 4

    def drive(t):
        return 0.4 * np.sin(2 * np.pi * t + phases)

    run = side_by_side(gymnasium_asset("ant.xml"), 3.0, "torso", controls=drive)
    ours = run["ars"][-1][:2] - run["ars"][0][:2]
    theirs = run["mujoco"][-1][:2] - run["mujoco"][0][:2]
    assert np.linalg.norm(ours) == pytest.approx(np.linalg.norm(theirs), rel=0.25), (ours, theirs)
    direction = np.degrees(np.arctan2(ours[1], ours[0]) - np.arctan2(theirs[1], theirs[0]))
    assert abs((direction + 180) % 360 - 180) < 15, (ours, theirs)
    heading = heading_degrees(run["ars_rotation"]) - heading_degrees(run["mujoco_rotation"])
    assert abs((heading + 180) % 360 - 180) < 15, (
        heading_degrees(run["ars_rotation"]),
        heading_degrees(run["mujoco_rotation"]),
    )


def test_a_floating_ant_s_hip_motor_turns_its_own_leg_only(tmp_path):
    """The cleanest view of the armature: the ant
    floating in zero gravity, one hip's motor on (actuator 0, hip_4, at 0.05: 7.5 N·m).
    MuJoCo's armature is a rotor on the joint: it resists the hip turning, not the
    whole ant turning. Each joint's change is taken against the same run without the
    motor (the ankles start outside their ranges and move in either way). The driven
    hip must turn as in MuJoCo (within 10 %: the file asks MuJoCo for RK4, ARS steps
    semi-implicit Euler), the undriven ones less than 0.1°. Measured: hip_4 8.33° against
    MuJoCo's 7.98°, the others 0.013–0.025° in both. (With the armature on the legs'
    inertia, as ARS had it: 24.6°, and 19.3–19.5° for the undriven hips.)"""
    path = edited(
        tmp_path,
        "ant.xml",
        (
            '<option integrator="RK4" timestep="0.01"/>',
            '<option integrator="RK4" timestep="0.01" gravity="0 0 0"/>',
        ),
    )

    def motor(t):
        return [0.05, 0, 0, 0, 0, 0, 0, 0]

    hips = ["hip_4", "hip_1", "hip_2", "hip_3"]
    on = side_by_side(path, 0.2, "torso", hips, controls=motor)
    off = side_by_side(path, 0.2, "torso", hips)
    ours = np.degrees(on["ars_joints"][-1] - off["ars_joints"][-1])
    theirs = np.degrees(on["mujoco_joints"][-1] - off["mujoco_joints"][-1])
    assert np.abs(theirs[1:]).max() < 0.1 and theirs[0] > 5, theirs
    assert ours[0] == pytest.approx(theirs[0], rel=0.1), (ours, theirs)
    assert np.abs(ours[1:]).max() < 0.1, (ours, theirs)


# ---------------------------------------------------------------------------------------
# 5. A two-finger grasp.

GRASP = """
<mujoco model="two-finger grasp">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="palm" pos="0 0 0.2">
      <joint name="lift" type="slide" axis="0 0 1" damping="80"/>
      <geom type="box" size="0.08 0.03 0.01" mass="0.5" contype="0" conaffinity="0"/>
      <body name="left" pos="-0.06 0 -0.13">
        <joint name="left_slide" type="slide" axis="1 0 0" damping="10"/>
        <geom type="box" size="0.01 0.03 0.06" mass="0.1"/>
      </body>
      <body name="right" pos="0.06 0 -0.13">
        <joint name="right_slide" type="slide" axis="-1 0 0" damping="10"/>
        <geom type="box" size="0.01 0.03 0.06" mass="0.1"/>
      </body>
    </body>
    <body name="box" pos="0 0 0.03">
      <freejoint/>
      <geom type="box" size="0.03 0.03 0.03" mass="0.1"/>
    </body>
  </worldbody>
  <actuator>
    <position name="lift" joint="lift" kp="2000"/>
    <position name="left" joint="left_slide" kp="{kp}"/>
    <position name="right" joint="right_slide" kp="{kp}"/>
  </actuator>
</mujoco>
"""


def grasp_and_lift(t):
    """Close both fingers from 0.1 s (their set point 1 cm inside the box's sides), then
    from 0.5 s raise the palm 15 cm over 0.5 s and hold it there."""
    close = 0.03 if t >= 0.1 else 0.0
    lift = 0.15 * min(max(t - 0.5, 0.0) / 0.5, 1.0)
    return [lift, close, close]


@pytest.mark.parametrize("kp", [40, 52, 58, 80, 500], ids=lambda kp: f"kp-{kp}")
def test_a_two_finger_grasp_holds_the_box_as_mujoco_s_does(tmp_path, kp):
    """Two slide fingers on a palm (a slide joint up) squeeze a 0.1 kg box (0.98 N) with
    position servos and lift it. Each finger stops at the box's side, 9.9 mm short of its
    set point, so it presses with kp · 9.9 mm and friction (μ = 1, MuJoCo's default)
    bears up to 2 · kp · 9.9 mm: from 0.79 N at kp 40 to 9.9 N at kp 500. Lifting takes
    more than the weight (the palm starts up at 0.3 m/s): in both engines the box stays
    on the floor at kp 52 and below (the fingers slide up its sides) and goes up from
    kp 54 (measured: a rise of 0.110 m in ARS, 0.113 m in MuJoCo, the box slipping as
    the palm starts), so a grip is held or lost, and how far it slips, as in MuJoCo. A
    frictionless contact (ARS leaves the box on the floor at every kp), actuators out of
    order (the palm then rises 2.7 cm) or a friction not bounded by the normal force fail."""
    path = tmp_path / "grasp.xml"
    path.write_text(GRASP.format(kp=kp))
    run = side_by_side(str(path), 1.5, "box", ["lift", "left_slide"], grasp_and_lift)
    start, hold = round(0.5 / 0.002) - 1, round(1.0 / 0.002) - 1
    ours = run["ars"][-1][2] - run["ars"][start][2]
    theirs = run["mujoco"][-1][2] - run["mujoco"][start][2]
    # Both engines raise the palm alike (its servo sags 3.4 to 3.9 mm under the load).
    palm = run["ars_joints"][-1][0], run["mujoco_joints"][-1][0]
    assert palm[0] == pytest.approx(palm[1], abs=1e-3) and palm[0] > 0.14, palm
    # The box's rise, within 5 mm of MuJoCo's. Measured (ARS, MuJoCo): kp 40 and 52:
    # 0.0 and 0.0 (left on the floor); kp 58: 0.1342 and 0.1329 m (slipped 1.5 cm as the
    # palm started); kp 80: 0.1495 and 0.1456 m; kp 500: 0.1495 and 0.1472 m. The gap
    # is MuJoCo's soft friction creeping under load: its box keeps sliding down between
    # the held fingers (2.0, 1.5 and 1.0 mm from 1.0 s to 1.5 s at kp 58, 80 and 500),
    # while ARS's hard Coulomb friction, solved exactly, holds it still (0.0 mm measured;
    # 0.5 mm allowed below). A box lost or left behind misses by 13 to 15 cm.
    assert abs(ours - theirs) < 0.005, (ours, theirs)
    lifted = kp >= 54
    assert (ours > 0.1) == lifted and (theirs > 0.1) == lifted, (ours, theirs)
    if lifted:
        slip = run["ars"][:, 2] - run["ars_joints"][:, 0]
        assert abs(slip[-1] - slip[hold]) < 5e-4, (slip[hold], slip[-1])
