//! Robots from URDF: the thesis arm loaded from a file steps exactly as the arm built
//! in code; a Z-up robot lands Y-up; bad files are errors naming the file, the element
//! and the problem.

use ars::nalgebra::{Isometry3, Vector3};
use ars::{Error, Program, ProgramRunner, Simulation, UpAxis, UrdfFile, UrdfOptions};
use ars_programs::ConicalPendulum;

const ARM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/conical_pendulum_arm.urdf");

fn body_state(sim: &Simulation, i: usize) -> [u64; 13] {
    let (_, handle) = sim.scene().bodies().nth(i).unwrap();
    let b = sim.scene().world().body(handle).unwrap();
    let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
    [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z].map(f64::to_bits)
}

#[test]
fn the_thesis_arm_from_urdf_steps_bit_for_bit_as_the_arm_built_in_code() {
    // Built in code: the ConicalPendulum program.
    let mut code = ConicalPendulum::default();
    let mut runner = ProgramRunner::new(&mut code).unwrap();

    // Loaded from the file into the same simulation parameters, driven by the same hooks.
    let mut sim = ConicalPendulum::default().configure(Simulation::builder()).build().unwrap();
    let options =
        UrdfOptions::new().up_axis(UpAxis::Y).self_collision(true).base_pose(Isometry3::translation(1.0, -0.25, 2.0));
    let robot = sim.load_urdf(ARM, &options).unwrap();
    assert_eq!(robot.links.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), ["base", "pole", "arm"]);
    let mut driver = ConicalPendulum::default();
    (driver.waist, driver.shoulder) = (robot.joint("r1"), robot.joint("r2"));
    sim.add_hooks(driver).unwrap();

    for step in 1..=8000 {
        runner.step().unwrap();
        sim.step().unwrap();
        for i in 0..3 {
            assert_eq!(body_state(runner.simulation(), i), body_state(&sim, i), "body {i} after step {step}");
        }
    }
    let rate = sim.scene().joint("r1").unwrap().state().unwrap().rate;
    assert!(rate > 1.0, "the waist spun up: {rate} rad/s");
}

#[test]
fn a_urdf_file_parsed_once_is_inserted_into_two_simulations_that_step_alike() {
    let file = UrdfFile::read(ARM).unwrap();
    assert_eq!(file.name(), "conical_pendulum");
    let options = UrdfOptions::new().up_axis(UpAxis::Y).base_pose(Isometry3::translation(0.0, 0.5, 0.0));
    let mut sims = [0, 1].map(|_| Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap());
    let robots = sims.each_mut().map(|sim| file.insert(sim, &options).unwrap());
    // Handles name their world: compare what was made by name.
    let names = |r: &ars::UrdfRobot| {
        (
            r.links.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>(),
            r.joints.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>(),
        )
    };
    assert_eq!(names(&robots[0]), names(&robots[1]));
    assert_eq!(names(&robots[0]).0, ["base", "pole", "arm"]);
    // What sim.load_urdf makes is what read and insert make.
    let mut loaded = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    assert_eq!(names(&loaded.load_urdf(ARM, &options).unwrap()), names(&robots[0]));
    for sim in sims.iter_mut().chain([&mut loaded]) {
        sim.step_n(500).unwrap();
    }
    for i in 0..3 {
        assert_eq!(body_state(&sims[0], i), body_state(&sims[1], i), "body {i}");
        assert_eq!(body_state(&sims[0], i), body_state(&loaded, i), "body {i}");
    }
    // A bad file is an error at parse time, before any simulation is touched.
    let err = UrdfFile::parse("<robot name=", "broken.urdf").unwrap_err();
    assert!(matches!(&err, Error::Format { format: "URDF", file, .. } if file == "broken.urdf"), "{err:?}");
}

const TWO_LINKS: &str = r#"<robot name="two">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="b"><inertial><origin xyz="0 0 0.5"/><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.5"/><geometry><cylinder radius="0.05" length="1"/></geometry></collision></link>
  <joint name="j" type="revolute"><origin xyz="0 0 0.1"/><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="1"/><dynamics damping="0.3" friction="0"/></joint>
</robot>"#;

#[test]
fn a_z_up_robot_stands_up_in_the_y_up_simulation_with_its_limits_and_damping() {
    let mut sim = Simulation::new().unwrap();
    let options = UrdfOptions::new().fixed_base(true).base_pose(Isometry3::translation(0.0, 1.0, 0.0));
    let robot = sim.load_urdf_text(TWO_LINKS, "two.urdf", &options).unwrap();
    // Link b's centre of mass is 0.6 m up the URDF's Z: the simulation's Y.
    let b = sim.scene().object("b").unwrap().position().unwrap();
    assert!((b - ars::nalgebra::Point3::new(0.0, 1.6, 0.0)).norm() < 1e-12, "{b}");
    // The hinge axis, URDF Y, is the simulation's −Z (ODE's joint runs from the parent
    // to the child about the negated axis, so that its angle is the URDF position).
    let axis = sim.scene().joint("j").unwrap().ode().unwrap().axis().unwrap();
    assert!((axis - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-12, "{axis}");
    // A positive torque turns the child positively about the URDF axis.
    let mut probe = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    probe.load_urdf_text(TWO_LINKS, "two.urdf", &UrdfOptions::new().fixed_base(true)).unwrap();
    probe.scene_mut().joint_mut("j").unwrap().add_torque(1.0).unwrap();
    probe.step().unwrap();
    assert!(probe.scene().joint("j").unwrap().state().unwrap().rate > 0.0);
    let w = probe.scene().object("b").unwrap().body().unwrap().angular_velocity();
    assert!(w.z < 0.0 && w.x.abs() < 1e-12, "about URDF +Y = simulation -Z: {w}");
    assert!(robot.base_joint.is_some(), "fixed to the world");
    // Gravity pulls the free link over to its limit, no further, and the damping slows it.
    sim.run_for(3.0).unwrap();
    let q = sim.scene().joint("j").unwrap().state().unwrap().position;
    assert!(q.abs() < 0.5 + 0.02, "stops at the limit: {q}");
    assert!(sim.scene().object("a").unwrap().position().unwrap().y > 0.99, "the base stays where it was fixed");
}

fn load_error(text: &str) -> (String, String) {
    load_error_with(text, &UrdfOptions::new())
}

fn load_error_with(text: &str, options: &UrdfOptions) -> (String, String) {
    let mut sim = Simulation::new().unwrap();
    match sim.load_urdf_text(text, "bad.urdf", options) {
        Err(Error::Format { format: "URDF", file, element, problem, .. }) => {
            assert_eq!(file, "bad.urdf");
            assert_eq!(sim.scene().objects().count(), 0, "nothing added: {element}: {problem}");
            (element, problem)
        }
        other => panic!("expected a URDF error, got {other:?}"),
    }
}

#[test]
fn bad_urdf_files_are_errors_naming_the_element() {
    let link = |name: &str, mass: &str| {
        format!(
            r#"<link name="{name}"><inertial><mass value="{mass}"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
        )
    };
    let joint = |name: &str, kind: &str, parent: &str, child: &str| {
        format!(
            r#"<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/><axis xyz="0 0 1"/></joint>"#
        )
    };
    let robot = |body: String| format!(r#"<robot name="r">{body}</robot>"#);

    let (element, problem) = load_error(&robot(link("a", "1") + &joint("j", "revolute", "x", "a")));
    assert_eq!(element, r#"joint "j""#);
    assert!(problem.contains("parent link \"x\""), "{problem}");

    let (element, problem) = load_error(&robot(link("a", "1") + &link("b", "-2") + &joint("j", "revolute", "a", "b")));
    assert_eq!(element, r#"link "b""#);
    assert!(problem.contains("mass -2"), "{problem}");

    let loop_ =
        link("a", "1") + &link("b", "1") + &joint("j1", "revolute", "a", "b") + &joint("j2", "revolute", "b", "a");
    let (element, problem) = load_error(&robot(loop_));
    assert!(element.starts_with("joint") || element == "robot", "{element}");
    assert!(problem.contains("loop"), "{problem}");

    // A massless link that moves borrows mass from one that has some (tests/urdf_as_written.rs);
    // without any, it is refused.
    let (element, problem) = load_error(&robot(link("a", "0") + &link("b", "0") + &joint("j", "revolute", "a", "b")));
    assert_eq!(element, r#"link "b""#);
    assert!(problem.contains("no link of the robot has one to lend it"), "{problem}");

    let (element, problem) = load_error(&robot(link("a", "1") + &link("b", "1") + &joint("j", "planar", "a", "b")));
    assert_eq!(element, r#"joint "j""#);
    assert!(problem.contains("Planar"), "{problem}");

    let (element, problem) = load_error(&robot(link("a", "1") + &link("b", "1")));
    assert_eq!(element, "robot");
    assert!(problem.contains("several root links (a, b)"), "{problem}");

    // Found while building: an inertia no body has (refused when asked to be strict;
    // corrected otherwise, see below), and a mesh; nothing stays behind.
    let bad_inertia = r#"<link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#;
    let strict = UrdfOptions::new().strict_inertia(true);
    let (element, problem) =
        load_error_with(&robot(link("a", "1") + bad_inertia + &joint("j", "revolute", "a", "b")), &strict);
    assert_eq!(element, r#"link "b""#);
    assert!(problem.contains("inertia"), "{problem}");
    let mesh = r#"<link name="b"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial><visual><geometry><mesh filename="b.stl"/></geometry></visual></link>"#;
    let (element, problem) = load_error(&robot(link("a", "1") + mesh + &joint("j", "revolute", "a", "b")));
    assert_eq!(element, r#"link "b""#);
    assert!(problem.contains("mesh \"b.stl\""), "{problem}");

    let (element, problem) = load_error("<robot name=\"r\"><link name=\"a\">");
    assert_eq!(element, "robot");
    assert!(problem.contains("not XML"), "{problem}");

    let mut sim = Simulation::new().unwrap();
    let err = sim.load_urdf("/no/such/robot.urdf", &UrdfOptions::new()).unwrap_err();
    assert!(
        matches!(&err, Error::Io { kind: std::io::ErrorKind::NotFound, path, .. } if path == "/no/such/robot.urdf"),
        "{err:?}"
    );
    assert!(err.to_string().starts_with("cannot read the URDF file \"/no/such/robot.urdf\": "), "{err}");
}

const THREE_LINK_ARM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ars_test_robot/three_link_arm.urdf");

#[test]
fn a_robot_with_a_mesh_and_several_collision_elements_loads_and_moves() {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let robot = sim.load_urdf(THREE_LINK_ARM, &UrdfOptions::new().fixed_base(true)).unwrap();
    assert_eq!(robot.joints.len(), 3);
    // The gripper's mesh, found through package://, welded: a box of 8 corners, 12
    // triangles, colliding as its convex hull (the same box).
    let gripper = sim.scene().object("gripper").unwrap();
    match gripper.shape() {
        ars::Shape::ConvexHull { vertices, triangles } => assert_eq!((vertices.len(), triangles.len()), (8, 12)),
        other => panic!("the gripper is a mesh's hull, not {other:?}"),
    }
    // The upper arm has its cylinder and its sphere, the sphere offset from the body.
    assert_eq!(sim.scene().object("upper_arm").unwrap().geoms().count(), 2);
    // Z-up → Y-up: the straight arm stands along +Y, the gripper's centre 1.2 m up.
    let top = sim.scene().object("gripper").unwrap().position().unwrap();
    assert!((top - ars::nalgebra::Point3::new(0.0, 1.2, 0.0)).norm() < 1e-12, "{top}");
    // Tipped over a little, gravity folds it; the shoulder stops at its limit.
    sim.scene_mut().joint_mut("shoulder").unwrap().add_torque(5.0).unwrap();
    sim.run_for(2.0).unwrap();
    let shoulder = sim.scene().joint("shoulder").unwrap().state().unwrap().position;
    assert!(shoulder > 0.5 && shoulder < 2.0 + 0.05, "fell towards its limit: {shoulder}");
    assert!(sim.scene().object("base").unwrap().position().unwrap().y.abs() < 1e-6, "the fixed base stays");
}

#[test]
fn a_missing_collision_mesh_is_skipped_with_a_note_listing_every_path_tried() {
    // As PyBullet loads the link without it (a missing <visual> mesh is an error: see
    // bad_urdf_files_are_errors_naming_the_element).
    let text = std::fs::read_to_string(THREE_LINK_ARM).unwrap().replace("gripper.stl", "lost.stl");
    let file = THREE_LINK_ARM.replace("three_link_arm", "copy");
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(&text, &file, &UrdfOptions::new()).unwrap();
    let [note] = &robot.adjusted[..] else { panic!("{:?}", robot.adjusted) };
    assert!(note.starts_with(r#"link "gripper": a <collision> is skipped"#), "{note}");
    assert!(note.contains("package://ars_test_robot/meshes/lost.stl"), "{note}");
    assert!(note.contains("ars_test_robot/meshes/lost.stl,"), "the folder-named-like-the-package rule: {note}");
    assert_eq!(sim.scene().object("gripper").unwrap().geoms().count(), 0);
}

#[test]
fn initial_positions_pose_the_robot_and_its_joints_read_them() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let options = UrdfOptions::new().fixed_base(true).initial_position("shoulder", 0.3).initial_position("elbow", -0.7);
    sim.load_urdf(THREE_LINK_ARM, &options).unwrap();
    let q = |name: &str| sim.scene().joint(name).unwrap().state().unwrap().position;
    assert!(
        (q("shoulder") - 0.3).abs() < 1e-12 && (q("elbow") + 0.7).abs() < 1e-12,
        "{} {}",
        q("shoulder"),
        q("elbow")
    );
    // The forearm's tip, from the planar chain: shoulder at 0.1 m up, 0.5 m upper arm,
    // the gripper's centre 0.6 m along the forearm direction (URDF Y axis = −Z here).
    let (a, b) = (0.3f64, 0.3f64 - 0.7);
    let expected = ars::nalgebra::Point3::new(0.5 * a.sin() + 0.6 * b.sin(), 0.1 + 0.5 * a.cos() + 0.6 * b.cos(), 0.0);
    let gripper = sim.scene().object("gripper").unwrap().position().unwrap();
    assert!((gripper - expected).norm() < 1e-12, "{gripper} vs {expected}");
    let err = Simulation::new().unwrap().load_urdf(THREE_LINK_ARM, &UrdfOptions::new().initial_position("knee", 1.0));
    assert!(matches!(err, Err(Error::Format { ref element, .. }) if element == r#"joint "knee""#), "{err:?}");
}

const VEHICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/thesis_vehicle.urdf");

#[test]
fn the_thesis_vehicle_from_urdf_drives_bit_for_bit_as_the_vehicle_built_in_code() {
    let with_floor = || Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let spec = ars_programs::VehicleSpec::default();
    let mut code = with_floor();
    ars_programs::build_vehicle(&mut code, &spec).unwrap();
    let mut urdf = with_floor();
    // The thesis' vehicle starts with its wheels a little into the floor: exactly
    // where the code builds it, not raised onto the floor.
    let options = UrdfOptions::new()
        .up_axis(UpAxis::Y)
        .self_collision(true)
        .base_pose(Isometry3::translation(0.5, 0.45, 0.0))
        .exact_base_pose(true);
    let robot = urdf.load_urdf(VEHICLE, &options).unwrap();
    // As the scene function does: joined where built, then moved by the offset.
    for (_, object) in &robot.links {
        urdf.scene_mut().offset_by_position(*object, spec.offset).unwrap();
    }
    for step in 1..=2500 {
        for sim in [&mut code, &mut urdf] {
            sim.scene_mut().joint_mut("w1").unwrap().add_torque(3.0).unwrap();
            sim.scene_mut().joint_mut("w2").unwrap().add_torque(3.0).unwrap();
            sim.step().unwrap();
        }
        for i in 0..4 {
            assert_eq!(body_state(&code, i), body_state(&urdf, i), "body {i} after step {step}");
        }
    }
    let x = urdf.scene().object("chassis").unwrap().position().unwrap().x;
    assert!((x - 2.5).abs() > 0.1, "it drove: chassis x {x}");
}

#[test]
fn links_are_drawn_as_their_visuals_in_their_materials_colours() {
    let text = r#"<robot name="painted">
  <material name="steel"><color rgba="0.5 0.5 0.6 1"/></material>
  <link name="a">
    <inertial><origin xyz="0 0 0.1"/><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry><material name="orange"><color rgba="1 0.5 0 1"/></material></visual>
    <visual><origin xyz="0 0 0.3"/><geometry><sphere radius="0.05"/></geometry><material name="steel"/></visual>
    <collision><geometry><box size="0.3 0.3 0.3"/></geometry></collision>
  </link>
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry><material name="steel"/></visual>
  </link>
  <link name="c">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
</robot>"#;
    let mut sim = Simulation::new().unwrap();
    // Each link an object of its own, to see each one's colour (fused, b and c would
    // be a's).
    sim.load_urdf_text(text, "painted.urdf", &UrdfOptions::new().keep_fixed_links(true)).unwrap();
    assert_eq!(sim.scene().object("a").unwrap().color(), Some([1.0, 0.5, 0.0]), "its own colour");
    assert_eq!(sim.scene().object("b").unwrap().color(), Some([0.5, 0.5, 0.6]), "the robot-level material it names");
    assert_eq!(sim.scene().object("c").unwrap().color(), None, "no visual: the viewer's default");
    // Each visual, relative to the body (the inertial frame, 0.1 m up the link's Z).
    let visuals = sim.scene().object("a").unwrap().visuals().to_vec();
    assert_eq!(visuals.len(), 2);
    assert_eq!(
        (&visuals[0].shape, visuals[0].color),
        (&ars::Shape::Box { edges: Vector3::new(0.2, 0.2, 0.2) }, Some([1.0, 0.5, 0.0]))
    );
    assert_eq!((&visuals[1].shape, visuals[1].color), (&ars::Shape::Sphere { radius: 0.05 }, Some([0.5, 0.5, 0.6])));
    assert!(
        (visuals[0].offset.translation.vector - Vector3::new(0.0, 0.0, -0.1)).norm() < 1e-12,
        "{}",
        visuals[0].offset
    );
    assert!(
        (visuals[1].offset.translation.vector - Vector3::new(0.0, 0.0, 0.2)).norm() < 1e-12,
        "{}",
        visuals[1].offset
    );
    assert!(visuals[1].offset.rotation.angle() < 1e-12);
    assert!(sim.scene().object("c").unwrap().visuals().is_empty(), "drawn as its collision geometry");
    // Ignored on request; and saved in scene files.
    let mut plain = Simulation::new().unwrap();
    plain.load_urdf_text(text, "painted.urdf", &UrdfOptions::new().ignore_visuals(true)).unwrap();
    assert!(plain.scene().object("a").unwrap().visuals().is_empty());
    let loaded = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    assert_eq!(loaded.scene().object("a").unwrap().visuals(), &visuals[..]);
}

#[test]
fn joint_limits_friction_and_mimic_come_from_the_file() {
    const GRIPPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gripper.urdf");
    let mut sim = Simulation::new().unwrap();
    sim.load_urdf(GRIPPER, &UrdfOptions::new().fixed_base(true)).unwrap();
    let left = sim.scene().joint("left_finger_joint").unwrap();
    assert_eq!(left.actuator_limits(), ars::ActuatorLimits { effort: 20.0, velocity: 0.1 });
    assert_eq!(left.dry_friction(), 0.5);
    let left_id = left.id();
    let mimic = sim.scene().joint("right_finger_joint").unwrap().mimic().unwrap();
    assert_eq!((mimic.leader, mimic.multiplier, mimic.offset), (left_id, 1.0, 0.0));

    // Held by its friction, the left finger stays shut under a push it cannot beat.
    sim.scene_mut().joint_mut("left_finger_joint").unwrap().add_force(0.4).unwrap();
    sim.step().unwrap();
    assert!(sim.scene().joint("left_finger_joint").unwrap().state().unwrap().position.abs() < 1e-9);

    // Opened at 1 m/s with 100 N, it goes at its 0.1 m/s limit (with at most 20 N),
    // and the right finger opens with it, the other way in the world.
    sim.scene_mut().joint_mut("left_finger_joint").unwrap().set_speed(1.0, 100.0).unwrap();
    sim.run_for(0.3).unwrap();
    let l = sim.scene().joint("left_finger_joint").unwrap().state().unwrap();
    let r = sim.scene().joint("right_finger_joint").unwrap().state().unwrap();
    assert!((l.rate - 0.1).abs() < 1e-9, "{l:?}");
    assert!((l.position - 0.03).abs() < 1e-3, "{l:?}");
    assert!((r.position - l.position).abs() < 1e-6, "{r:?} follows {l:?}");
    let (lx, rx) = (
        sim.scene().object("left_finger").unwrap().position().unwrap(),
        sim.scene().object("right_finger").unwrap().position().unwrap(),
    );
    assert!((lx.z + rx.z).abs() < 1e-6 && lx.z < -0.05, "apart along the URDF's Y (simulation −Z): {lx} {rx}");

    // A mimic naming no joint of the file is dropped, saying so (PyBullet ignores mimics).
    let text = std::fs::read_to_string(GRIPPER)
        .unwrap()
        .replace(r#"<mimic joint="left_finger_joint""#, r#"<mimic joint="thumb""#);
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(&text, "g.urdf", &UrdfOptions::new()).unwrap();
    let [note] = &robot.adjusted[..] else { panic!("{:?}", robot.adjusted) };
    assert!(
        note.contains("joint \"right_finger_joint\"") && note.contains("\"thumb\"") && note.contains("dropped"),
        "{note}"
    );
    assert!(sim.scene().joint("right_finger_joint").unwrap().mimic().is_none());
}

/// A flange and a tool frame, massless and fixed (as the Panda's `panda_link8` and
/// `panda_grasptarget`), are merged into the arm link they hang from: the robot loads,
/// their names find that link's object, the flange's ball is a geom of the arm's body,
/// and a finger jointed to the tool frame hangs from the arm.
#[test]
fn massless_links_fixed_to_their_parent_are_merged_into_it() {
    let inertia = r#"<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>"#;
    let text = format!(
        r#"<robot name="merged">
          <link name="base"><inertial><mass value="0"/>{inertia}</inertial></link>
          <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>{inertia}</inertial>
            <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry></collision></link>
          <link name="flange"><inertial><mass value="0"/>{inertia}</inertial>
            <collision><geometry><sphere radius="0.05"/></geometry></collision>
            <visual><geometry><sphere radius="0.05"/></geometry><material name="red"><color rgba="1 0 0 1"/></material></visual></link>
          <link name="tool"/>
          <link name="finger"><inertial><origin xyz="0 0 -0.1"/><mass value="0.1"/>{inertia}</inertial></link>
          <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
            <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="0" velocity="0"/></joint>
          <joint name="flange_mount" type="fixed"><parent link="arm"/><child link="flange"/><origin xyz="1 0 0"/></joint>
          <joint name="tool_mount" type="fixed"><parent link="flange"/><child link="tool"/><origin xyz="0 0 -0.1"/></joint>
          <joint name="knuckle" type="revolute"><parent link="tool"/><child link="finger"/>
            <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="0" velocity="0"/></joint>
        </robot>"#
    );
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(&text, "merged.urdf", &UrdfOptions::new()).unwrap();
    let arm = robot.link("arm").unwrap();
    assert_eq!(robot.link("flange"), Some(arm));
    assert_eq!(robot.link("tool"), Some(arm));
    assert_eq!(robot.links.len(), 5);
    assert!(robot.joint("flange_mount").is_none() && robot.joint("tool_mount").is_none());
    let knuckle = robot.joint("knuckle").unwrap();
    // The arm's object: its box and the flange's ball; the flange's look, in red.
    let view = sim.scene().object(arm).unwrap();
    assert_eq!(view.geoms().count(), 2);
    assert_eq!(view.body().unwrap().mass(), 1.0);
    assert_eq!(view.visuals().len(), 1);
    assert_eq!(view.visuals()[0].color, Some([1.0, 0.0, 0.0]));
    // URDF (x, y, z) is (x, z, -y) here: the flange at (1, 1, 0), the ball on it.
    let ball = view.geoms().nth(1).unwrap();
    assert_eq!(sim.scene().world().geom(ball).unwrap().body(), view.body_handle());
    let at = ars::nalgebra::Point3::from(sim.scene().world().geom(ball).unwrap().pose().translation.vector);
    assert!((at - ars::nalgebra::Point3::new(1.0, 1.0, 0.0)).norm() < 1e-12, "{at}");
    // The finger hangs from the tool frame, 0.1 m below the flange, on the arm's body.
    let finger = robot.link("finger").unwrap();
    let finger_at = sim.scene().object(finger).unwrap().position().unwrap();
    assert!((finger_at - ars::nalgebra::Point3::new(1.0, 0.8, 0.0)).norm() < 1e-12, "{finger_at}");
    let joint = sim.scene().joint(knuckle).unwrap();
    assert_eq!(joint.objects().0, arm);
    // Hanging straight down from the knuckle, the finger stays (gravity has no arm
    // about the knuckle's axis), and the whole arm does not fall: its base is static.
    sim.run_for(0.2).unwrap();
    assert!(sim.scene().joint(knuckle).unwrap().state().unwrap().position.abs() < 1e-6);
    let finger_after = sim.scene().object(finger).unwrap().position().unwrap();
    assert!((finger_after - finger_at).norm() < 1e-3, "{finger_after}");
}

/// Inertias no body can have, as public robot files carry them (a link given only
/// its mass, products rounded into a negative moment, moments breaking the triangle
/// inequality), load corrected with a line naming each link; the mass is the file's.
#[test]
fn inertias_no_body_can_have_are_corrected_and_said() {
    let link = |name: &str, inertia: &str| {
        format!(r#"<link name="{name}"><inertial><mass value="2"/><inertia {inertia}/></inertial></link>"#)
    };
    let joint = |name: &str, child: &str| {
        format!(
            r#"<joint name="{name}" type="revolute"><parent link="base"/><child link="{child}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#
        )
    };
    let text = format!(
        r#"<robot name="r">{}{}{}{}{}{}{}</robot>"#,
        link("base", r#"ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0""#)
            .replace("</link>", r#"<visual><geometry><sphere radius="0"/></geometry></visual></link>"#),
        link("zeros", r#"ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0""#),
        link("rounded", r#"ixx="0.01" iyy="0.01" izz="0.02" ixy="0.0100001" ixz="0" iyz="0""#),
        link("unbalanced", r#"ixx="1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0""#),
        joint("j1", "zeros"),
        joint("j2", "rounded"),
        joint("j3", "unbalanced"),
    );
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(&text, "wild.urdf", &UrdfOptions::new()).unwrap();
    assert_eq!(robot.adjusted.len(), 4, "{:#?}", robot.adjusted);
    // A visual with nothing to draw is skipped, not refused.
    assert!(robot.adjusted[0].starts_with(r#"link "base": a <visual> Sphere"#), "{}", robot.adjusted[0]);
    assert!(robot.adjusted[0].ends_with("has nothing to draw: skipped"), "{}", robot.adjusted[0]);
    assert!(sim.scene().object("base").unwrap().visuals().is_empty(), "drawn as its collision shape");
    for (line, name) in robot.adjusted[1..].iter().zip(["zeros", "rounded", "unbalanced"]) {
        assert!(line.starts_with(&format!("link {name:?}: inertia balanced")), "{line}");
    }
    assert!(robot.adjusted[1].contains("solid sphere"), "{}", robot.adjusted[1]);
    assert!(robot.adjusted[3].contains("their mean"), "{}", robot.adjusted[3]);
    for name in ["zeros", "rounded", "unbalanced"] {
        let body = sim.scene().object(name).unwrap().body_handle().unwrap();
        assert_eq!(sim.scene().world().body(body).unwrap().mass(), 2.0, "{name}: the file's mass");
    }
    // The unbalanced link's moments are their mean, 0.4 each, as MuJoCo's balanceinertia.
    let body = sim.scene().object("unbalanced").unwrap().body_handle().unwrap();
    let i = sim.scene().world().body(body).unwrap().inertia();
    assert!((i - ars::nalgebra::Matrix3::identity() * 0.4).amax() < 1e-12, "{i}");
    sim.run_for(0.5).unwrap();
    // Strict: refused, naming the first such link.
    let (element, problem) = load_error_with(&text, &UrdfOptions::new().strict_inertia(true));
    assert_eq!(element, r#"link "zeros""#);
    assert!(problem.contains("positive definite"), "{problem}");
}
