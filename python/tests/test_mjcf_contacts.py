"""An MJCF file's contact parameters (`friction`, `condim`, `solref`, `solimp`) are its
contacts' in ARS, held against MuJoCo running the same file (issue 37). The mapping
onto ODE's contacts and its limits are in the Rust `GeomContact`'s docs."""

import math

import numpy as np
import pytest
from conftest import corpus_file

import ars

mujoco = pytest.importorskip("mujoco")


def both(tmp_path, text, seconds):
    """Runs the model `text` for `seconds` in MuJoCo and in ARS (`Simulation.open`: the
    file's time step); returns the free body's MuJoCo position path and ARS's, both
    in MuJoCo's axes (ARS's (x, y, z) being MuJoCo's (x, -z, y))."""
    path = tmp_path / "model.xml"
    path.write_text(text)
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    thing = m.body("thing").id
    theirs = []
    while d.time < seconds - 1e-9:
        mujoco.mj_step(m, d)
        theirs.append(d.xpos[thing].copy())
    sim = ars.Simulation.open(str(path))
    ours = []
    body = sim.body("thing")
    for _ in range(len(theirs)):
        sim.step()
        x, y, z = body.position
        ours.append(np.array([x, -z, y]))
    return np.array(theirs), np.array(ours)


INCLINE = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="ramp" euler="{angle} 0 0">
      <geom type="box" size="2 2 0.1" pos="0 0 -0.1" friction="{mu} 0.005 0.0001"/>
    </body>
    <body name="thing" euler="{angle} 0 0" pos="0 0 0">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.05" pos="0 0 0.05" friction="{mu} 0.005 0.0001"/>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.mark.parametrize("mu", [0.3, 0.8])
def test_a_box_on_an_incline_sticks_and_slides_where_mujoco_s_does(tmp_path, mu):
    """A box rests on a ramp tilted about x. Below `tan θ = μ` (at 0.8 of it) it stays
    in both engines (MuJoCo's soft friction creeps a few millimetres); above (at 1.25
    of it) it slides down in both, ARS's distance within 25 % of MuJoCo's after 1 s
    (0.34 m and 0.69 m in MuJoCo, as `½·g·(sin θ − μ·cos θ)·t²`). The friction is Coulomb's, the
    geoms' own `friction`; ARS's default surface (a 500 N force limit) would hold
    the box at any angle."""
    for ratio, slides in [(0.8, False), (1.25, True)]:
        angle = math.atan(ratio * mu)
        text = INCLINE.format(angle=angle, mu=mu).replace(
            "<mujoco>", '<mujoco><compiler angle="radian"/>', 1
        )
        theirs, ours = both(tmp_path, text, 1.0)
        moved_theirs = np.linalg.norm(theirs[-1] - theirs[0])
        moved_ours = np.linalg.norm(ours[-1] - ours[0])
        if slides:
            assert moved_theirs > 0.05, moved_theirs
            assert moved_ours == pytest.approx(moved_theirs, rel=0.25), (
                mu,
                ratio,
                moved_ours,
                moved_theirs,
            )
        else:
            # MuJoCo's soft friction creeps a few millimetres (7 at μ = 0.8).
            assert moved_theirs < 0.02, moved_theirs
            assert moved_ours < 0.02, (mu, ratio, moved_ours)


DROP = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <geom type="plane" size="5 5 0.1" solref="{solref}"/>
    <body name="thing" pos="0 0 0.5">
      <freejoint/>
      <geom type="sphere" size="0.1" solref="{solref}" density="1000"/>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.mark.parametrize("solref", ["0.02 1", "0.05 0.2"])
def test_a_dropped_ball_settles_and_rebounds_as_in_mujoco(tmp_path, solref):
    """A ball dropped 0.4 m onto a plane: critically damped (`solref 0.02 1`) it lands
    and stays; under-damped (`0.05 0.2`) it rebounds. ARS's highest rebound is within
    a third of MuJoCo's (ODE's contact damps the approach itself: see the mapping's
    docs), and both settle at the same depth into the plane, to 0.2 mm."""
    theirs, ours = both(tmp_path, DROP.format(solref=solref), 2.0)
    landing = lambda z: int(np.argmax(np.diff(z) > 0))
    rebound_theirs = theirs[landing(theirs[:, 2]) :, 2].max() - 0.1
    rebound_ours = ours[landing(ours[:, 2]) :, 2].max() - 0.1
    if solref.endswith(" 1"):
        assert rebound_theirs < 0.002 and rebound_ours < 0.002, (rebound_theirs, rebound_ours)
    else:
        assert rebound_theirs > 0.01, rebound_theirs
        assert rebound_ours == pytest.approx(rebound_theirs, rel=1 / 3), (
            rebound_ours,
            rebound_theirs,
        )
    assert ours[-1, 2] == pytest.approx(theirs[-1, 2], abs=2e-4), (ours[-1, 2], theirs[-1, 2])


def test_geom_contacts_are_read_set_and_checked(tmp_path):
    """`load_mjcf` gives each geom the file's parameters (MuJoCo's defaults where not
    given); `set_geom_contact` changes those it is given and keeps the others; bad
    values are `ars.InputError`s naming them."""
    path = tmp_path / "pucks.xml"
    path.write_text(
        """<mujoco><worldbody><geom name="ground" type="plane" size="5 5 .1"/>
        <body name="puck" pos="0 0 0.05"><freejoint/>
          <geom type="box" size=".05 .05 .05" friction="0.3" condim="4" solref="0.01 1"/></body>
        </worldbody></mujoco>"""
    )
    sim = ars.Simulation()
    sim.load_mjcf(str(path))
    puck = sim.geom_contact("puck")
    assert puck == {
        "friction": [0.3, 0.005, 0.0001],
        "condim": 4,
        "solref": [0.01, 1.0],
        "solimp": [0.9, 0.95, 0.001, 0.5, 2.0],
        "priority": 0,
        "solmix": 1.0,
    }
    # The file's unnamed plane is the object "floor".
    assert sorted((name, k) for name, k, _ in sim.geom_contacts()) == [("floor", 0), ("puck", 0)]
    sim.set_geom_contact("puck", friction=(0.0, 0.0, 0.0), priority=2)
    changed = sim.geom_contact("puck")
    assert changed is not None
    assert (changed["friction"], changed["priority"], changed["condim"]) == ([0.0, 0.0, 0.0], 2, 4)
    # Frictionless now, with the highest priority: a push glides on.
    sim.body("puck").set_linear_velocity((1.0, 0.0, 0.0))
    sim.run(0.5)
    assert sim.body("puck").position[0] > 0.45
    for bad, says in [
        ({"condim": 2}, "condim 2"),
        ({"condim": 300}, "condim 300"),
        ({"friction": (1.0, 2.0)}, "friction takes 3 numbers"),
        ({"solref": (0.02, -1.0)}, "solref"),
        ({"priority": 2**40}, "priority"),
    ]:
        with pytest.raises(ars.InputError, match=says):
            sim.set_geom_contact("puck", **bad)
    with pytest.raises(ars.InputError):
        sim.set_geom_contact("puck", 5)
    with pytest.raises(ars.UnknownNameError):
        sim.geom_contact("nobody")


PAIRED = """
<mujoco>
  <compiler angle="radian"/>
  <option timestep="0.002"/>
  <worldbody>
    <body name="ramp" euler="{angle} 0 0">
      <geom name="slope" type="box" size="2 2 0.1" pos="0 0 -0.1" friction="{geoms} 0.005 0.0001"/>
    </body>
    <body name="thing" euler="{angle} 0 0" pos="0 0 0">
      <freejoint/>
      <geom name="crate" type="box" size="0.05 0.05 0.05" pos="0 0 0.05" contype="0" conaffinity="0"
            friction="{geoms} 0.005 0.0001"/>
    </body>
  </worldbody>
  <contact><pair geom1="slope" geom2="crate" friction="{pair} {pair} 0.005 0.0001 0.0001"/></contact>
</mujoco>
"""


@pytest.mark.parametrize(("geoms", "pair"), [(1.0, 0.2), (0.1, 0.6)])
def test_a_pair_s_own_friction_replaces_its_geoms_as_in_mujoco(tmp_path, geoms, pair):
    """A `<pair>`'s own parameters are its contacts', not its geoms' combined: on a
    ramp at `tan θ = 0.4` a crate touching only through the pair slides where the
    pair's friction is below 0.4 (0.2; its geoms' 1.0 would hold it) and stays where
    it is above (0.6; its geoms' 0.1 would let it slide), in both engines; ARS's
    sliding distance within 25 % of MuJoCo's after 1 s. The pair's parameters are
    said used: nothing about them is in the skipped list."""
    text = PAIRED.format(angle=math.atan(0.4), geoms=geoms, pair=pair)
    theirs, ours = both(tmp_path, text, 1.0)
    moved_theirs = np.linalg.norm(theirs[-1] - theirs[0])
    moved_ours = np.linalg.norm(ours[-1] - ours[0])
    if pair < 0.4:
        assert moved_theirs > 0.3, moved_theirs
        assert moved_ours == pytest.approx(moved_theirs, rel=0.25), (moved_ours, moved_theirs)
    else:
        assert moved_theirs < 0.02, moved_theirs
        assert moved_ours < 0.02, moved_ours
    sim = ars.Simulation()
    skipped = sim.load_mjcf(tmp_path / "model.xml")["skipped"]
    assert not [s for s in skipped if "<pair>" in s], skipped
    [(_, first, _, second, own)] = sim.geom_pair_contacts()
    assert (first, second) == (0, 0)
    assert own["friction"] == [pair, 0.005, 0.0001] and own["solref"] == [0.02, 1.0]
    # Set from Python: a pair of ARS's own shapes.
    sim = ars.Simulation()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), name="a")
    sim.add_sphere(0.1, (0.0, 2.0, 0.0), name="b")
    sim.set_geom_pair_contact("a", "b", friction=[0.3, 0.0, 0.0], condim=1)
    [row] = sim.geom_pair_contacts()
    assert row[:4] == ("a", 0, "b", 0)
    own = row[4]
    assert own["condim"] == 1 and own["friction"] == [0.3, 0.0, 0.0]
    with pytest.raises(ars.InputError):
        sim.set_geom_pair_contact("a", "a")


@pytest.mark.parametrize(
    "relative",
    [
        "gymnasium-robotics-1.4.2/gymnasium_robotics/envs/assets/adroit_hand/adroit_door.xml",
        "gymnasium-robotics-1.4.2/gymnasium_robotics/envs/assets/hand/manipulate_block.xml",
    ],
)
def test_published_hands_pairs_take_mujoco_s_parameters(relative):
    """The Adroit and Shadow hands' `<pair>`s (19 each, condim 1 between fingers, from
    an included file, with classes): each pair ARS makes has MuJoCo's compiled
    `pair_friction` (first sliding and torsional), `pair_dim`, `pair_solref` and
    `pair_solimp`, in MuJoCo's order. The files list one pair twice: MuJoCo keeps both
    (their contacts twice), ARS one (the same parameters). Skipped where the corpus is
    not fetched."""
    path = corpus_file(relative)
    if path is None:
        pytest.skip("corpus not fetched")
    m = mujoco.MjModel.from_xml_path(str(path))
    sim = ars.Simulation()
    sim.load_mjcf(path, skip_unsupported=True)
    ours = sim.geom_pair_contacts()
    first = {}
    for i in range(m.npair):
        first.setdefault(frozenset((m.pair_geom1[i], m.pair_geom2[i])), i)
    theirs = sorted(first.values())
    assert m.npair == 19 and len(ours) == len(theirs) == 18
    for i, (_, _, _, _, own) in zip(theirs, ours, strict=True):
        assert own["friction"][:2] == pytest.approx([m.pair_friction[i][0], m.pair_friction[i][2]])
        assert own["condim"] == m.pair_dim[i] == 1
        assert own["solref"] == pytest.approx(m.pair_solref[i])
        assert own["solimp"] == pytest.approx(m.pair_solimp[i])
