"""`<frame>` and `<replicate>` read as MuJoCo reads them: what they place stands where
MuJoCo's compiled model puts it, replicated names are MuJoCo's, and the actuators
and sensors naming a replicated joint or site are repeated as MuJoCo repeats them."""

import numpy as np
import pytest
from test_mjcf import assert_first_order, compare, mujoco_angles_after_one_second

import ars

mujoco = pytest.importorskip("mujoco")

FRAMES = """
<mujoco model="frames">
  <compiler angle="degree"/>
  <default>
    <default class="red"><geom type="box" size=".05 .04 .03" rgba="1 0 0 1"/></default>
  </default>
  <worldbody>
    <frame name="shelf" pos="0.5 0 0.3" euler="0 0 30" childclass="red">
      <geom name="block" pos="0.2 0 0"/>
      <site name="mark" pos="0 0.1 0"/>
      <body name="arm" pos="0 0 0.5" euler="10 0 0">
        <frame pos="0 0 0.1" euler="90 0 0">
          <joint name="shoulder" type="hinge" axis="0 0 1" pos="0 0.05 0"/>
          <inertial pos="0.1 0 0.02" mass="1.5" diaginertia="0.01 0.02 0.03" euler="0 20 0"/>
        </frame>
        <body name="hand" pos="0.2 0 0">
          <joint name="wrist" type="hinge" axis="0 1 0"/>
          <frame pos="0.05 0 0" euler="0 0 45">
            <geom name="palm" size=".03 .02 .01"/>
            <frame pos="0.04 0 0"><geom name="finger" type="capsule" fromto="0 0 0 0.05 0 0" size=".01"/></frame>
          </frame>
        </body>
      </body>
    </frame>
    <replicate count="3" offset="0 0.8 0" euler="0 0 15" sep="_">
      <body name="leg" pos="-1 0 0.4">
        <joint name="knee" type="hinge" axis="1 0.2 0"/>
        <geom type="capsule" fromto="0 0 0 0.1 0 -0.2" size="0.02"/>
        <replicate count="12" offset="0.03 0 0">
          <frame euler="0 45 0"><geom name="toe" type="box" size=".01 .005 .002" pos="0 0.01 -0.25"/></frame>
        </replicate>
        <site name="tip" pos="0 0 -0.2"/>
      </body>
    </replicate>
    <replicate count="2" offset="0 0 0.3" euler="20 0 0">
      <body name="crate" pos="1 1 0.5"><freejoint/><geom type="box" size=".1 .05 .02"/></body>
    </replicate>
  </worldbody>
  <actuator>
    <motor name="kick" joint="knee" gear="2"/>
    <motor name="turn" joint="shoulder"/>
  </actuator>
  <sensor>
    <jointpos name="angle" joint="knee"/>
    <framepos name="where" objtype="site" objname="tip"/>
  </sensor>
</mujoco>"""


def test_frames_and_replicates_place_what_they_hold_as_mujoco_does(tmp_path):
    """Every body's mass, centre and inertia (so every geom and inertial the frames
    and replicates placed in it), the names, the repeated actuators and sensors, the
    sites the sensors read and the static geoms in frames equal MuJoCo's; the hinges
    placed by frames swing as MuJoCo's, to first order in the time step."""
    path = tmp_path / "frames.xml"
    path.write_text(FRAMES)
    sim, model = compare(path)
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)

    def names(kind, count):
        return [mujoco.mj_id2name(m, kind, i) for i in range(count)]

    # Bodies in MuJoCo's order; joints, actuators and sensors too.
    assert model["bodies"] == names(mujoco.mjtObj.mjOBJ_BODY, m.nbody)[1:]
    assert [j for j in model["joints"] if not j.startswith("joint")] == [
        n for n in names(mujoco.mjtObj.mjOBJ_JOINT, m.njnt) if n
    ]
    assert [a[0] for a in model["actuators"]] == names(mujoco.mjtObj.mjOBJ_ACTUATOR, m.nu)
    assert [a[2] for a in model["actuators"]] == [
        mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, m.actuator_trnid[i][0]) for i in range(m.nu)
    ]
    assert list(model["sensors"]) == names(mujoco.mjtObj.mjOBJ_SENSOR, m.nsensor)
    assert model["actuators"][1][0] == "kick_0" and list(model["sensors"])[-1] == "where_2"
    # The replicated sites where MuJoCo has them (framepos after one microsecond).
    sim.time_step = 1e-6
    sim.step()
    for i in range(m.nsensor):
        if m.sensor_type[i] != mujoco.mjtSensor.mjSENS_FRAMEPOS:
            continue
        x, y, z = d.sensordata[m.sensor_adr[i] : m.sensor_adr[i] + 3]
        row = model["sensors"][m.sensor(i).name].records()[-1]
        ours = [float(row[f]) for f in row.dtype.names[2:]]
        assert ours == pytest.approx([x, z, -y], abs=1e-9), m.sensor(i).name
    # The static box in the turned frame: rays cast down hit its top where MuJoCo's do.
    block = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "block")
    rng = np.random.default_rng(3)
    for dx, dy in rng.uniform(-0.03, 0.03, size=(20, 2)):
        x, y = d.geom_xpos[block][:2] + (dx, dy)
        theirs = 10.0 - mujoco.mj_ray(
            m,
            d,
            np.array([x, y, 10.0]),
            np.array([0.0, 0.0, -1.0]),
            None,
            1,
            -1,
            np.zeros(1, np.int32),
        )
        hit = sim.cast_ray((x, 10.0, -y), (0.0, -1.0, 0.0), 20.0)
        assert hit is not None and hit[1][1] == pytest.approx(theirs, abs=1e-9)
    # The hinges the frames turned and moved swing as MuJoCo's.
    joints = ["shoulder", "wrist", "knee_0", "knee_2"]
    assert_first_order(path, joints, mujoco_angles_after_one_second(path, joints), what="frames")


def test_frames_and_replicates_refuse_bad_counts_naming_the_element(tmp_path):
    """A count that is no whole number, and one that would make more elements than ARS
    allows, are refused with the element and line, leaving nothing; a count of 0 makes
    nothing."""
    bad = [
        (
            '<replicate count="2.5" offset="1 0 0"><geom size=".1"/></replicate>',
            "not a whole number",
        ),
        ('<replicate offset="1 0 0"><geom size=".1"/></replicate>', "needs a count"),
        (
            '<replicate count="1000"><replicate count="1000"><geom size=".1"/></replicate></replicate>',
            "more than 100000",
        ),
        (
            '<replicate count="1000000000"><replicate count="1000000000"/></replicate>',
            "more than 100000",
        ),
        ('<frame pos="0 0 nan"><geom size=".1"/></frame>', "nan"),
    ]
    path = tmp_path / "bad.xml"
    for body, text in bad:
        path.write_text(f"<mujoco><worldbody>{body}</worldbody></mujoco>")
        sim = ars.Simulation()
        with pytest.raises(ars.FormatError, match=text) as raised:
            sim.load_mjcf(path)
        assert "line 1" in str(raised.value), raised.value
        assert sim.objects == []
    path.write_text(
        '<mujoco><worldbody><replicate count="0"><body><freejoint/><geom size=".1"/></body>'
        "</replicate></worldbody></mujoco>"
    )
    assert ars.Simulation().load_mjcf(path)["bodies"] == []
