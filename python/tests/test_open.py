"""`ars.Simulation.open`: any file ARS reads, by its extension, as the viewer's Open
button and `ars view FILE` open it."""

import os
import warnings

import pytest

import ars

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def test_a_scene_file_opens_where_it_was_saved(tmp_path):
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="ball")
    sim.run(0.2)
    path = tmp_path / "ball.json"
    sim.save_scene_to(path)
    opened = ars.Simulation.open(path)
    for s in (sim, opened):
        s.run(0.3)
    assert (opened.body("ball").position == sim.body("ball").position).all()


def test_a_urdf_robot_stands_on_a_floor():
    sim = ars.Simulation.open(os.path.join(ROOT, "tests", "data", "gripper.urdf"))
    sim.run(0.5)
    assert sim.body("palm").position[1] > 0.0


def test_an_mjcf_model_opens_and_says_what_it_skipped():
    gymnasium = pytest.importorskip("gymnasium")
    ant = os.path.join(os.path.dirname(gymnasium.__file__), "envs", "mujoco", "assets", "ant.xml")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sim = ars.Simulation.open(ant)
    # The geoms' margins ARS cannot use, counted in one warning.
    said = [str(w.message) for w in caught]
    assert len(said) == 1 and "contact parameters of" in said[0] and "<geom>" in said[0], said
    sim.run(0.1)
    assert sim.body("torso").position[1] > 0.0


def test_other_files_are_refused_by_name(tmp_path):
    with pytest.raises(ars.UnknownKindError, match=r"\.json, \.urdf, \.xml, \.mjcf"):
        ars.Simulation.open(tmp_path / "robot.sdf")
    with pytest.raises(ars.FileError, match="missing.json"):
        ars.Simulation.open(tmp_path / "missing.json")


def test_excluded_objects_pass_through_each_other():
    sim = ars.Simulation()
    floor = sim.add_floor()
    ghost = sim.add_sphere(0.1, (0.0, 0.5, 0.0), mass=1.0, name="ghost")
    ball = sim.add_sphere(0.1, (1.0, 0.5, 0.0), mass=1.0, name="ball")
    sim.exclude_contacts(floor, ghost)
    assert sim.excluded_contacts() == [(floor, ghost)]
    sim.run(1.0)
    assert sim.body(ghost).position[1] < -1.0
    assert abs(sim.body(ball).position[1] - 0.1) < 0.01
    sim.include_contacts(floor, ghost)
    assert sim.excluded_contacts() == []
    with pytest.raises(ars.InputError, match="twice"):
        sim.exclude_contacts(ball, ball)


WILD_URDF = """<robot name="wild">
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><sphere radius="0"/></geometry></visual>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
</robot>"""


def test_a_urdf_inertia_no_body_can_have_is_corrected_with_a_warning(tmp_path):
    """A link given only its mass loads, its inertia a sphere of that mass, and the
    correction and the skipped empty visual are each said; strict loading refuses."""
    path = tmp_path / "wild.urdf"
    path.write_text(WILD_URDF)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sim = ars.Simulation.open(path)
    said = [str(w.message) for w in caught]
    assert any(s.startswith('adjusted: link "base": inertia balanced') for s in said), said
    assert any("has nothing to draw: skipped" in s for s in said), said
    assert sim.body("base").mass == 2.0
    robot = ars.Simulation().load_urdf(path)
    assert len(robot["adjusted"]) == 2 and "solid sphere" in robot["adjusted"][1]
    with pytest.raises(ars.FormatError, match="positive definite"):
        ars.Simulation().load_urdf(path, strict_inertia=True)


def test_a_link_with_mass_on_a_fixed_joint_is_fused_unless_kept_apart(tmp_path):
    inertia = '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>'
    link = '<link name="{0}"><inertial><mass value="1"/>' + inertia + "</inertial></link>"
    path = tmp_path / "welded.urdf"
    path.write_text(
        '<robot name="r">'
        + link.format("a")
        + link.format("b")
        + '<joint name="weld" type="fixed"><origin xyz="1 0 0"/>'
        '<parent link="a"/><child link="b"/></joint></robot>'
    )
    fused = ars.Simulation()
    robot = fused.load_urdf(str(path))
    assert "b" not in fused.objects and fused.body("a").mass == 2.0
    assert any("fused" in line for line in robot["adjusted"]), robot["adjusted"]
    apart = ars.Simulation()
    apart.load_urdf(str(path), keep_fixed_links=True)
    assert apart.body("a").mass == 1.0 and apart.body("b").mass == 1.0


def test_what_a_mujoco_file_skips_is_one_warning(tmp_path):
    """Opening an MJCF file whose geoms carry parameters ARS cannot use says so in one
    warning counting them by kind, not a warning per geom (issue 37: 36 lines for
    Gymnasium's humanoid); `load_mjcf` lists each."""
    path = tmp_path / "margins.xml"
    geoms = "".join(
        f'<geom type="sphere" size="0.1" pos="{k} 0 1" margin="0.01"/>' for k in range(5)
    )
    path.write_text(f"<mujoco><worldbody>{geoms}</worldbody></mujoco>")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ars.Simulation.open(path)
    said = [str(w.message) for w in caught]
    assert len(said) == 1, said
    assert (
        said[0].startswith("skipped 5 unsupported MJCF items")
        and "skip_unsupported=True" in said[0]
    ), said
    assert len(ars.Simulation().load_mjcf(path, skip_unsupported=True)["skipped"]) == 5
