"""What a Rust user of `Simulation` can do, a Python user can: the calls added for
parity (lidar and depth camera, removal, contact surfaces, stepper, space,
orientation), and a walk over the Rust API that lists what Python lacks."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

import ars

ROOT = Path(__file__).resolve().parents[2]


def test_a_lidar_scans_into_a_numpy_array_of_ranges_and_points():
    sim = ars.Simulation()
    sim.add_box((1.0, 1.0, 1.0), (3.0, 0.0, 0.0), mass=1.0)  # its near face 2.5 m along +X
    sim.set_seed(1)
    lidar = sim.add_lidar(360, 2 * math.pi, 10.0)
    sim.step(2)
    ranges = lidar.ranges()
    assert ranges.shape == (2, 360)
    assert ranges[-1, 180] == pytest.approx(2.5, abs=1e-9), "the beam along +X"
    assert math.isinf(ranges[-1, 0]), "nothing behind"
    points = lidar.points()
    assert points.shape == (2, 360, 3)
    assert points[-1, 180] == pytest.approx((2.5, 0.0, 0.0), abs=1e-9)
    assert np.isnan(points[-1, 0]).all()
    records = lidar.records()
    assert len(records) == 2 and records["step"].tolist() == [1, 2]
    assert len(lidar) == 2


def test_a_mounted_noisy_lidar_is_seeded_and_does_not_see_its_own_object():
    def scan(seed):
        sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))
        sim.add_sphere(0.2, (0.0, 0.0, 0.0), mass=1.0, name="robot")
        sim.add_box((1.0, 1.0, 1.0), (3.0, 0.0, 0.0), mass=1.0)
        lidar = sim.add_lidar(8, 2 * math.pi, 10.0, on="robot", noise=0.01, seed=seed, every=0.01)
        sim.run(0.1)
        return lidar.ranges()

    a, b, c = scan(7), scan(7), scan(8)
    assert a.shape == (10, 8), "every 10 ms for 0.1 s"
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c), "another seed, other noise"
    finite = a[np.isfinite(a)]
    assert finite.size > 0 and np.all(np.abs(finite - 2.5) < 0.1), (
        "the box, not the robot's own sphere"
    )


def test_a_depth_camera_gives_float32_images():
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))
    sim.add_box((4.0, 4.0, 0.1), (0.0, 0.0, -2.05), mass=1.0)  # a wall 2 m in front
    camera = sim.add_depth_camera(8, 6, math.radians(60), 0.1, 10.0)
    sim.step()
    images = camera.images()
    assert images.shape == (1, 6, 8) and images.dtype == np.float32
    assert images[0, 3, 4] == pytest.approx(2.0, abs=1e-5)
    with pytest.raises(ars.InputError, match="depth camera"):
        camera.ranges()
    with pytest.raises(ars.InputError, match="lidar"):
        sim.add_sensor("gps", sim.add_sphere(0.1, (5.0, 0.0, 0.0))).ranges()


def test_bad_sensor_arguments_are_clear_errors():
    sim = ars.Simulation()
    with pytest.raises(ars.InputError):
        sim.add_lidar(0, 1.0, 10.0)
    with pytest.raises(ars.InputError):
        sim.add_lidar(10, 1.0, -1.0)
    with pytest.raises(ars.UnknownNameError):
        sim.add_lidar(10, 1.0, 10.0, on="nobody")
    with pytest.raises(ars.InputError, match="rotation"):
        sim.add_lidar(10, 1.0, 10.0, rotation=[[2, 0, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(ars.InputError):
        sim.add_depth_camera(0, 10, 1.0, 0.1, 10.0)


def test_sensors_are_cleared_removed_and_detached():
    sim = ars.Simulation()
    ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    gps = sim.add_sensor("gps", ball)
    sim.step(3)
    gps.clear()
    assert len(gps) == 0
    assert not gps.detached
    sim.remove_object(ball)
    assert gps.detached
    gps.remove()
    with pytest.raises(ars.ArsError):
        len(gps)


def test_objects_and_joints_are_removed_by_name():
    sim = ars.Simulation()
    sim.add_floor()
    a = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="a")
    b = sim.add_sphere(0.1, (0.0, 2.0, 0.0), mass=1.0, name="b")
    sim.add_fixed_joint("weld", a, b)
    sim.add_rotary_joint("pin", b, None, anchor=(0.0, 2.0, 0.0))
    sim.remove_joint("weld")
    assert sim.joints == ["pin"]
    sim.remove_object("b")
    assert sim.objects == ["a", "floor"] and sim.joints == [], "b's joint went with it"
    with pytest.raises(ars.UnknownNameError):
        sim.remove_object("b")
    with pytest.raises(ars.UnknownNameError):
        _ = sim.body("b").position
    sim.add_sphere(0.1, (1.0, 1.0, 0.0), name="b")  # the name is free again
    sim.run(0.1)


def test_contact_surfaces_per_simulation_and_per_pair():
    def slide(**surfaces):
        sim = ars.Simulation()
        sim.add_floor()
        puck = sim.add_box((0.2, 0.1, 0.2), (0.0, 0.05, 0.0), mass=1.0, name="puck")
        for between, surface in surfaces.items():
            sim.set_contact_surface(None if between == "everything" else ("floor", puck), **surface)
        sim.body(puck).set_linear_velocity((1.0, 0.0, 0.0))
        sim.run(0.5)
        return sim, sim.body(puck).position[0]

    sim, x = slide()
    assert x < 0.01, "ARS's default 500 N box friction stops a 1 kg puck at once"
    assert sim.contact_surface() == {
        "mu": 500.0,
        "mu2": None,
        "bounce": 0.2,
        "bounce_velocity": 0.0,
        "soft_erp": None,
        "soft_cfm": None,
        "approx1": False,
        "max_contacts": 150,
    }
    sim, x = slide(everything={"mu": 0.0, "bounce": 0.0})
    assert x == pytest.approx(0.5, abs=1e-3), "no friction anywhere"
    sim, x = slide(pair={"mu": 0.0})
    assert x == pytest.approx(0.5, abs=1e-3), "no friction between the puck and the floor"
    assert sim.contact_surface(("puck", "floor"))["mu"] == 0.0
    assert sim.contact_surface()["mu"] == 500.0, "the default is unchanged"
    sim, x = slide(pair={"mu": 0.5, "approx1": True})
    assert x == pytest.approx(1.0 / (2 * 0.5 * 9.81), rel=0.05), (
        "Coulomb friction 0.5: stops after v²/(2 μ g)"
    )
    sim.clear_contact_surface("floor", "puck")
    assert sim.contact_surface(("floor", "puck"))["mu"] == 500.0
    with pytest.raises(ars.InputError):
        sim.set_contact_surface(mu=-1.0)
    with pytest.raises(ars.InputError):
        sim.set_contact_surface(bounce=2.0)
    with pytest.raises(ars.UnknownNameError):
        sim.set_contact_surface(("floor", "nobody"), mu=1.0)


def test_the_stepper_space_and_world_parameters_are_chosen_and_read():
    sim = ars.Simulation(stepper="quick", quick_iterations=10, space="hash", seed=3)
    assert (sim.stepper, sim.space) == ("quick", "hash")
    sim.set_stepper("exact")
    assert sim.stepper == "exact"
    assert ars.Simulation(space="simple").space == "simple"
    assert ars.Simulation(space="sweep_and_prune").space == "sweep_and_prune"
    assert ars.Simulation().space == "grid", "new simulations scale"
    grid = ars.Simulation(space="grid")
    grid.add_floor()
    ball = grid.add_sphere(0.1, (0.0, 0.5, 0.0), mass=1.0)
    grid.run(1.0)
    assert grid.space == "grid" and grid.body(ball).position[1] == pytest.approx(0.1, abs=1e-3)
    sim.erp, sim.cfm, sim.time_step, sim.gravity = 0.5, 1e-5, 0.001, (0.0, -1.0, 0.0)
    assert (sim.erp, sim.cfm, sim.time_step, sim.gravity) == (0.5, 1e-5, 0.001, (0.0, -1.0, 0.0))
    assert sim.frame_count == 0
    sim.step_frame()
    assert (sim.frame_count, sim.step_count) == (1, sim.steps_per_frame)
    with pytest.raises(ars.InputError, match="space"):
        ars.Simulation(space="octree")
    with pytest.raises(ars.InputError, match="stepper"):
        ars.Simulation(stepper="fast")
    with pytest.raises(ars.InputError, match="quick"):
        ars.Simulation(quick_iterations=5)
    with pytest.raises(ars.InputError):
        sim.erp = 2.0


def test_orientation_is_set_as_a_rotation_matrix_or_a_pose():
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))
    box = sim.body(sim.add_box((1.0, 2.0, 3.0), (0.0, 0.0, 0.0), mass=1.0))
    quarter_turn_about_y = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]
    box.set_rotation(quarter_turn_about_y)
    np.testing.assert_allclose(box.rotation, quarter_turn_about_y, atol=1e-15)
    box.set_pose((1.0, 2.0, 3.0))
    np.testing.assert_allclose(box.rotation, np.eye(3), atol=1e-15)
    np.testing.assert_array_equal(box.position, (1.0, 2.0, 3.0))
    for bad in (
        [[1, 0, 0], [0, 1, 0], [0, 0, -1]],
        [[1, 1, 0], [0, 1, 0], [0, 0, 1]],
        [[math.nan] * 3] * 3,
    ):
        with pytest.raises(ars.InputError, match="rotation"):
            box.set_rotation(bad)
    np.testing.assert_allclose(
        box.rotation, np.eye(3), atol=1e-15, err_msg="a refused rotation changes nothing"
    )
    other = sim.add_sphere(0.1, (1.0, 0.0, 0.0), mass=1.0)
    box.offset_by_object(other)
    np.testing.assert_array_equal(box.position, (2.0, 2.0, 3.0))


def test_joints_have_their_kind_friction_limits_mimic_and_efforts():
    sim = ars.Simulation()
    a = sim.add_box((0.1, 0.1, 0.1), (0.0, 1.0, 0.0), mass=1.0)
    b = sim.add_box((0.1, 0.1, 0.1), (0.0, 2.0, 0.0), mass=1.0)
    c = sim.add_box((0.1, 0.1, 0.1), (0.0, 3.0, 0.0), mass=1.0)
    sim.add_rotary_joint("leader", a, None, anchor=(0.0, 1.0, 0.0))
    sim.add_rotary_joint("follower", b, None, anchor=(0.0, 2.0, 0.0))
    sim.add_piston_joint("piston", c, None, (0.0, 3.0, 0.0), (1.0, 0.0, 0.0))
    assert [sim.joint(n).kind for n in ("leader", "piston")] == ["hinge", "piston"]
    leader, follower = sim.joint("leader"), sim.joint("follower")
    follower.set_mimic("leader", 2.0, 0.0)
    leader.set_dry_friction(0.0)
    leader.set_actuator_limits(effort=5.0)
    leader.add_torque(1.0)
    assert leader.efforts["added"] == 1.0 and leader.efforts["total"] == 1.0
    sim.run(0.2)
    assert follower.angle == pytest.approx(2.0 * leader.angle, abs=1e-3) and leader.angle != 0.0
    follower.clear_mimic()
    with pytest.raises(ars.InputError):
        leader.set_dry_friction(-1.0)
    with pytest.raises(ars.InputError):
        leader.set_actuator_limits(velocity=0.0)


def test_scene_files_are_written_and_read_by_path(tmp_path):
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="ball")
    sim.set_contact_surface(("floor", "ball"), mu=1.0, bounce=0.9)
    path = tmp_path / "scene.json"
    sim.save_scene_to(path)
    loaded = ars.Simulation.load_scene_from(path)
    assert loaded.contact_surface(("ball", "floor"))["bounce"] == 0.9
    sim.run(0.5)
    loaded.run(0.5)
    np.testing.assert_array_equal(sim.body("ball").position, loaded.body("ball").position)


# -- the walk: every public method of the Rust `Simulation` (and of the `Scene` and
# `SimulationBuilder` it is made with, and `SimJoint`), and where Python has it --------

#: Rust method -> the Python attribute that does it ("Class.attr"), for each of them.
PYTHON_FOR_RUST = {
    # SimulationBuilder: keyword arguments of ars.Simulation(...) and setters.
    "SimulationBuilder.gravity": "Simulation.gravity",
    "SimulationBuilder.time_step": "Simulation.time_step",
    "SimulationBuilder.steps_per_frame": "Simulation.steps_per_frame",
    "SimulationBuilder.erp": "Simulation.erp",
    "SimulationBuilder.cfm": "Simulation.cfm",
    "SimulationBuilder.stepper": "Simulation.set_stepper",
    "SimulationBuilder.contact_surface": "Simulation.set_contact_surface",
    "SimulationBuilder.bounce": "Simulation.set_contact_surface",
    "SimulationBuilder.mu": "Simulation.set_contact_surface",
    "SimulationBuilder.space": "Simulation.space",
    "SimulationBuilder.floor": "Simulation.add_floor",
    "SimulationBuilder.floor_plane": "Simulation.add_floor",
    "SimulationBuilder.seed": "Simulation.set_seed",
    "SimulationBuilder.build": "Simulation.__init__",
    # Simulation
    "Simulation.new": "Simulation.__init__",
    "Simulation.builder": "Simulation.__init__",
    "Simulation.scene": "Simulation.objects",
    "Simulation.scene_mut": "Simulation.body",
    "Simulation.add_hooks": "Simulation.add_pre_step",
    "Simulation.remove_hooks": "Simulation.remove_hook",
    "Simulation.step": "Simulation.step",
    "Simulation.step_n": "Simulation.step",
    "Simulation.step_n_until": "Simulation.step",
    "Simulation.step_frame": "Simulation.step_frame",
    "Simulation.run_for": "Simulation.run",
    "Simulation.run_for_until": "Simulation.run",
    "Simulation.remove_object": "Simulation.remove_object",
    "Simulation.remove_joint": "Simulation.remove_joint",
    "Simulation.add_sensor": "Simulation.add_sensor",
    "Simulation.add_sensor_every": "Simulation.add_sensor",
    "Simulation.add_sensor_of_kind": "Simulation.add_sensor",
    "Simulation.remove_sensor": "Sensor.remove",
    "Simulation.remove_any_sensor": "Sensor.remove",
    "Simulation.records": "Sensor.records",
    "Simulation.sensor_table": "Sensor.records",
    "Simulation.clear_records": "Sensor.clear",
    "Simulation.clear_any_records": "Sensor.clear",
    "Simulation.is_sensor_detached": "Sensor.detached",
    "Simulation.is_any_sensor_detached": "Sensor.detached",
    "Simulation.save_scene": "Simulation.save_scene",
    "Simulation.load_scene": "Simulation.load_scene",
    "Simulation.save_scene_to": "Simulation.save_scene_to",
    "Simulation.snapshot": "Simulation.snapshot",
    "Simulation.restore": "Simulation.restore",
    "Simulation.from_snapshot": "Simulation.from_snapshot",
    "Simulation.load_scene_from": "Simulation.load_scene_from",
    "Simulation.open": "Simulation.open",
    "Scene.set_control": "Simulation.set_control",
    "Scene.exclude_contacts": "Simulation.exclude_contacts",
    "Scene.include_contacts": "Simulation.include_contacts",
    "Scene.excluded_contacts": "Simulation.excluded_contacts",
    "Scene.control": "Simulation.control",
    "Scene.actuators": "Simulation.actuators",
    "Scene.set_controls": "Simulation.set_controls",
    "Scene.controls": "Simulation.controls",
    # Scene
    "Scene.add_fixed_joint": "Simulation.add_fixed_joint",
    "Scene.add_hinge_joint": "Simulation.add_rotary_joint",
    "Scene.add_slider_joint": "Simulation.add_slider_joint",
    "Scene.add_universal_joint": "Simulation.add_universal_joint",
    "Scene.add_joint_group": "Simulation.add_joint_group",
    "Scene.add_ball_joint": "Simulation.add_ball_socket_joint",
    "Scene.add_piston_joint": "Simulation.add_piston_joint",
    "Scene.joints": "Simulation.joints",
    "Scene.joint": "Simulation.joint",
    "Scene.joint_mut": "Simulation.joint",
    "Scene.joint_efforts": "Joint.efforts",
    "Scene.joint_controller": "Joint.set_controller",
    "Scene.joint_rate": "Joint.rate",
    "Scene.joint_state": "Joint.angle",
    "Scene.joint_position": "Joint.angle",
    "Scene.space": "Simulation.space",
    "Scene.space_kind": "Simulation.space",
    "Scene.time": "Simulation.time",
    "Scene.time_step": "Simulation.time_step",
    "Scene.set_time_step": "Simulation.time_step",
    "Scene.steps_per_frame": "Simulation.steps_per_frame",
    "Scene.step_count": "Simulation.step_count",
    "Scene.frame_count": "Simulation.frame_count",
    "Scene.gravity": "Simulation.gravity",
    "Scene.add_body": "Simulation.add_sphere",
    "Scene.add_body_with_mass": "Simulation.add_box",
    "Scene.add_sphere": "Simulation.add_sphere",
    "Scene.add_box": "Simulation.add_box",
    "Scene.add_cylinder": "Simulation.add_cylinder",
    "Scene.add_capsule": "Simulation.add_capsule",
    "Scene.add_cone": "Simulation.add_cone",
    "Scene.add_floor_plane": "Simulation.add_floor",
    "Scene.add_trimesh_floor": "Simulation.add_trimesh",
    "Scene.objects": "Simulation.objects",
    "Scene.bodies": "Simulation.objects",
    "Scene.object": "Simulation.body",
    "Scene.body": "Simulation.body",
    "Scene.body_mut": "Simulation.body",
    "Scene.set_color": "Body.set_color",
    "Scene.pose": "Body.rotation",
    "Scene.position": "Body.position",
    "Scene.rotation": "Body.rotation",
    "Scene.set_position": "Body.set_position",
    "Scene.set_rotation": "Body.set_rotation",
    "Scene.set_pose": "Body.set_pose",
    "Scene.rotate": "Body.rotate",
    "Scene.offset_by_position": "Body.offset_by_position",
    "Scene.offset_by_object": "Body.offset_by_object",
    "Scene.set_contact_surface": "Simulation.set_contact_surface",
    "Scene.set_geom_contact": "Simulation.set_geom_contact",
    "Scene.geom_contact": "Simulation.geom_contact",
    "Scene.geom_contacts": "Simulation.geom_contacts",
    "Scene.set_geom_pair_contact": "Simulation.set_geom_pair_contact",
    "Scene.geom_pair_contacts": "Simulation.geom_pair_contacts",
    "Scene.contact_surface": "Simulation.contact_surface",
    "Scene.clear_contact_surface": "Simulation.clear_contact_surface",
    "Scene.contact_surfaces": "Simulation.contact_surface",
    "Simulation.load_urdf": "Simulation.load_urdf",
    "Simulation.load_mjcf": "Simulation.load_mjcf",
    "Simulation.set_mocap_pose": "Simulation.set_mocap_pose",
    "Simulation.mocap_pose": "Simulation.mocap_pose",
    # SimJoint (what `joint_mut` hands out)
    "SimJoint.id": "Joint.name",
    "SimJoint.add_torque": "Joint.add_torque",
    "SimJoint.add_force": "Joint.add_force",
    "SimJoint.set_speed": "Joint.set_speed",
    "SimJoint.set_dry_friction": "Joint.set_dry_friction",
    "SimJoint.set_armature": "Joint.set_armature",
    "SimJoint.armature": "Joint.armature",
    "SimJoint.set_damping": "Joint.set_damping",
    "SimJoint.damping": "Joint.damping",
    "SimJoint.set_actuator_limits": "Joint.set_actuator_limits",
    "SimJoint.set_mimic": "Joint.set_mimic",
    "SimJoint.clear_mimic": "Joint.clear_mimic",
    "SimJoint.set_limits": "Joint.set_limits",
    "SimJoint.set_param": "Joint.set_param",
    "SimJoint.set_viscous_friction": "Joint.set_viscous_friction",
    "SimJoint.set_spring": "Joint.set_spring",
    "SimJoint.set_controller": "Joint.set_controller",
    "SimJoint.clear_controller": "Joint.set_controller",
}

#: Rust methods Python does not have, each named in docs/python.md ("What Python does
#: not have") with its reason.
NOT_IN_PYTHON = {
    "Simulation.hooks",
    "Simulation.hooks_mut",
    "Simulation.sensor",
    "Simulation.sensor_period",
    "Simulation.mocap_bodies",
    "Simulation.sensors_of",
    "Simulation.sensor_ids_of",
    "Scene.robot_descriptions",
    "Simulation.sensor_lines",
    "Simulation.sensor_tables",
    "Simulation.step_frame_observed",
    "Simulation.open_at",
    "Simulation.scene_file",
    "Simulation.from_scene_file",
    "Scene.world",
    "Scene.world_mut",
    "Scene.world_id",
    "Scene.steps_in",
    "Scene.add_static",
    "Scene.set_name",
    "Scene.set_visuals",
    "Simulation.load_urdf_text",
    "Simulation.load_mjcf_text",
    "SimJoint.controller_mut",
}


def rust_methods():
    """`Type.method` for every `pub fn` in the `impl` blocks of the four types."""
    found = set()
    files = [
        path
        for folder in ("scene", "simulation", "formats")
        for path in sorted((ROOT / "ars-core/src" / folder).rglob("*.rs"))
    ]
    for path in files:
        owner = None
        for line in path.read_text().splitlines():
            m = re.match(
                r"^impl(?:<[^>]*>)? (Scene|Simulation|SimulationBuilder|SimJoint)(?:<[^>]*>)? \{",
                line,
            )
            if m:
                owner = m.group(1)
                continue
            if line.startswith("}"):
                owner = None
            m = re.match(r"^    pub fn (\w+)", line)
            if owner and m:
                found.add(f"{owner}.{m.group(1)}")
    return found


def test_every_public_rust_method_has_a_python_counterpart_or_a_documented_reason():
    rust = rust_methods()
    assert len(rust) > 100, "the walk found the Rust API"
    unaccounted = sorted(rust - PYTHON_FOR_RUST.keys() - NOT_IN_PYTHON)
    assert unaccounted == [], (
        f"Rust methods with no Python counterpart and no documented reason: {unaccounted}"
    )
    stale = sorted((PYTHON_FOR_RUST.keys() | NOT_IN_PYTHON) - rust)
    assert stale == [], f"listed here but gone from Rust: {stale}"
    classes = {
        "Simulation": ars.Simulation,
        "Body": ars.Body,
        "Joint": ars.Joint,
        "Sensor": ars.Sensor,
    }
    missing = []
    for rust_name, python_name in PYTHON_FOR_RUST.items():
        cls, attr = python_name.split(".")
        if not hasattr(classes[cls], attr):
            missing.append(f"{rust_name} -> {python_name}")
    assert missing == [], f"Python attributes named here do not exist: {missing}"
    docs = (ROOT / "docs/python.md").read_text()
    section = docs.split("## What Python does not have", 1)[-1].split("\n## ", 1)[0]
    undocumented = sorted(name for name in NOT_IN_PYTHON if f"`{name}`" not in section)
    assert undocumented == [], (
        f"gaps not named in docs/python.md's 'What Python does not have': {undocumented}"
    )
