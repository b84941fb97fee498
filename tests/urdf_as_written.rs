//! URDF files as people write them (issue 37): what PyBullet loads from the wild, ARS
//! loads too, saying in `UrdfRobot::adjusted` what it read leniently or skipped; what
//! cannot be read is an error naming the file, the element and the line. Each test is
//! named after the cause found in a public file, and uses a small hand-written one.

use ars::{Error, Simulation, UrdfOptions, UrdfRobot};

const INERTIA: &str = r#"<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>"#;

fn link(name: &str, mass: f64) -> String {
    format!(r#"<link name="{name}"><inertial><mass value="{mass}"/>{INERTIA}</inertial></link>"#)
}

fn hinge(name: &str, parent: &str, child: &str) -> String {
    format!(
        r#"<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#
    )
}

fn load(text: &str) -> (Simulation, UrdfRobot) {
    load_in(text, "robot.urdf")
}

fn load_in(text: &str, file: &str) -> (Simulation, UrdfRobot) {
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(text, file, &UrdfOptions::new()).unwrap();
    (sim, robot)
}

/// Loaded with each link its own body, to see where a fixed joint puts it (fused, the
/// links of these robots would be one body).
fn load_apart(text: &str) -> (Simulation, UrdfRobot) {
    let mut sim = Simulation::new().unwrap();
    let robot = sim.load_urdf_text(text, "robot.urdf", &UrdfOptions::new().keep_fixed_links(true)).unwrap();
    (sim, robot)
}

/// The error's element, line and problem; nothing was added.
fn refusal(text: &str) -> (String, Option<u32>, String) {
    let mut sim = Simulation::new().unwrap();
    match sim.load_urdf_text(text, "bad.urdf", &UrdfOptions::new()) {
        Err(Error::Format { format: "URDF", file, element, line, problem, .. }) => {
            assert_eq!(file, "bad.urdf");
            assert_eq!(sim.scene().objects().count(), 0);
            (element, line, problem)
        }
        other => panic!("expected a URDF error, got {other:?}"),
    }
}

fn noted(robot: &UrdfRobot, words: &[&str]) -> bool {
    robot.adjusted.iter().any(|line| words.iter().all(|w| line.contains(w)))
}

fn total_mass(sim: &Simulation) -> f64 {
    let scene = sim.scene();
    scene.bodies().map(|(_, body)| scene.world().body(body).unwrap().mass()).sum()
}

#[test]
fn vectors_written_with_commas_read_as_with_spaces() {
    // pybullet_data/bicycle/bike.urdf: xyz="0.07, 0, -0.69".
    let text = format!(
        r#"<robot name="r">{}{}<joint name="j" type="fixed"><origin xyz="0.07, 0, -0.69"/><parent link="a"/><child link="b"/></joint></robot>"#,
        link("a", 1.0),
        link("b", 1.0)
    );
    let (sim, _) = load_apart(&text);
    let a = sim.scene().object("a").unwrap().position().unwrap();
    let b = sim.scene().object("b").unwrap().position().unwrap();
    // URDF (x, y, z) is (x, z, -y) in the simulation.
    assert!(((b - a) - ars::nalgebra::Vector3::new(0.07, -0.69, 0.0)).norm() < 1e-12, "{}", b - a);
}

#[test]
fn extra_numbers_in_a_vector_are_cut_to_three_with_a_note() {
    // pybullet_data/quadruped/microtaur: rpy="-3.14159 1.57079 0 0"; racecar_differential:
    // scale="1 1 1 1".
    let text = format!(
        r#"<robot name="r">{}{}<joint name="j" type="revolute"><origin rpy="0 0 0 0"/><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>"#,
        link("a", 1.0),
        link("b", 1.0)
    );
    let (_, robot) = load(&text);
    assert!(noted(&robot, &["joint \"j\"", "rpy=\"0 0 0 0\"", "line 1", "has 4 numbers"]), "{:?}", robot.adjusted);
}

#[test]
fn xacro_optenv_left_in_a_file_reads_as_its_default() {
    // pybullet_data/husky/husky.urdf: rpy="$(optenv HUSKY_IMU_RPY 0 -1.5708 3.1416)".
    let text = format!(
        r#"<robot name="r">{}{}<joint name="imu" type="fixed"><origin xyz="$(optenv ARS_TEST_UNSET_VARIABLE 0.19 0 0.149)"/><parent link="a"/><child link="b"/></joint></robot>"#,
        link("a", 1.0),
        link("b", 1.0)
    );
    let (sim, robot) = load_apart(&text);
    let a = sim.scene().object("a").unwrap().position().unwrap();
    let b = sim.scene().object("b").unwrap().position().unwrap();
    assert!(((b - a) - ars::nalgebra::Vector3::new(0.19, 0.149, 0.0)).norm() < 1e-12, "{}", b - a);
    assert!(noted(&robot, &["joint \"imu\"", "$(optenv)", "\"0.19 0 0.149\""]), "{:?}", robot.adjusted);
}

#[test]
fn a_number_that_is_none_is_refused_naming_file_link_attribute_and_line() {
    let text = format!(
        "<robot name=\"r\">\n{}\n<link name=\"b\">\n<inertial><mass value=\"1..5\"/>{INERTIA}</inertial></link>\n{}</robot>",
        link("a", 1.0),
        hinge("j", "a", "b")
    );
    let (element, line, problem) = refusal(&text);
    assert_eq!((element.as_str(), line), ("link \"b\"", Some(4)));
    assert!(problem.contains("<mass> value=\"1..5\": is not a number"), "{problem}");
}

#[test]
fn a_xacro_expression_left_in_a_file_is_refused_saying_so() {
    let text = format!(
        "<robot name=\"r\">{}{}\n<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/>\n<origin xyz=\"0 0 ${{wheel_radius}}\"/></joint></robot>",
        link("a", 1.0),
        link("b", 1.0)
    );
    let (element, line, problem) = refusal(&text);
    assert_eq!((element.as_str(), line), ("joint \"j\"", Some(3)));
    assert!(problem.contains("xyz=\"0 0 ${wheel_radius}\"") && problem.contains("run xacro"), "{problem}");
    let (_, _, problem) = refusal(&text.replace("0 0 ${wheel_radius}", "0 0"));
    assert!(problem.contains("needs 3 numbers, has 2"), "{problem}");
}

#[test]
fn a_limit_without_velocity_or_effort_reads_as_no_such_limit() {
    // pybullet_data/spherical_joint_limit.urdf and others: <limit> without velocity.
    let text = format!(
        r#"<robot name="r">{}{}<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/><limit lower="-0.5" upper="0.8"/></joint></robot>"#,
        link("a", 1.0),
        link("b", 1.0)
    );
    let (sim, _) = load(&text);
    assert_eq!(sim.scene().joint("j").unwrap().limits(), Some((-0.5, 0.8)));
}

#[test]
fn a_second_axis_is_ignored_with_a_note() {
    // pybullet_data/quadruped/spirit40newer.urdf: two <axis> in a joint.
    let text = format!(
        "<robot name=\"r\">{}{}<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/>\n<axis xyz=\"1 0 0\"/></joint></robot>",
        link("a", 1.0),
        link("b", 1.0)
    );
    let (_, robot) = load(&text);
    assert!(noted(&robot, &["joint \"j\"", "second <axis> at line 2"]), "{:?}", robot.adjusted);
}

#[test]
fn a_material_inside_a_geometry_and_a_texture_without_file_are_ignored() {
    // pybullet_data/racecar/racecar.urdf (<material> after <box> in <geometry>);
    // icub.urdf (<texture />).
    let text = r#"<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
        <visual><geometry><box size="1 1 1"/><material name="grey"/></geometry><material name="m"><color rgba="1 0 0 1"/><texture/></material></visual></link></robot>"#;
    let (sim, _) = load(text);
    assert_eq!(sim.scene().object("a").unwrap().visuals()[0].color, Some([1.0, 0.0, 0.0]));
}

#[test]
fn plane_and_cdf_collisions_are_skipped_with_a_note() {
    // pybullet_data/plane_implicit.urdf (<plane normal>) and toys/concave_box.urdf (<cdf>).
    let text = r#"<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
        <collision><geometry><plane normal="0 0 1"/></geometry></collision>
        <collision><geometry><sphere radius="0.1"/></geometry></collision></link></robot>"#;
    let (sim, robot) = load(text);
    assert_eq!(sim.scene().object("a").unwrap().geoms().count(), 1);
    assert!(noted(&robot, &["link \"a\"", "<plane> at line 2", "skipped"]), "{:?}", robot.adjusted);
}

/// A folder of its own in the temporary folder, made empty.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ars-urdf-as-written-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const TETRAHEDRON: &str = "solid t
facet normal 0 0 -1
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal -1 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 1 1 1
outer loop
vertex 1 0 0
vertex 0 1 0
vertex 0 0 1
endloop
endfacet
endsolid t
";

fn mesh_link(name: &str, filename: &str) -> String {
    format!(
        r#"<link name="{name}"><inertial><mass value="2"/>{INERTIA}</inertial><collision><geometry><mesh filename="{filename}"/></geometry></collision></link>"#
    )
}

#[test]
fn a_collision_mesh_that_is_not_there_is_skipped_keeping_the_link_and_its_mass() {
    // pybullet_data/kuka_iiwa/model_for_sdf.urdf names meshes/coarse/*.stl, absent.
    let text = format!(r#"<robot name="r">{}</robot>"#, mesh_link("a", "meshes/coarse/none.stl"));
    let dir = scratch("missing");
    let (sim, robot) = load_in(&text, &dir.join("r.urdf").display().to_string());
    assert_eq!(sim.scene().object("a").unwrap().geoms().count(), 0);
    assert_eq!(total_mass(&sim), 2.0);
    assert!(noted(&robot, &["link \"a\"", "<collision> is skipped", "none.stl\" not found"]), "{:?}", robot.adjusted);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_package_mesh_is_found_in_a_folder_above_the_urdf() {
    // rtb-data's abb_irb140_description/urdf/irb140.urdf names
    // package://abb_irb140_support/meshes/...: in abb_irb140_description/meshes. And
    // example-robot-data's talos_full_v2_box.urdf: package:///example-robot-data/robots/...
    let root = scratch("package");
    std::fs::create_dir_all(root.join("arm_description/urdf")).unwrap();
    std::fs::create_dir_all(root.join("arm_description/meshes")).unwrap();
    std::fs::write(root.join("arm_description/meshes/base.stl"), TETRAHEDRON).unwrap();
    let file = root.join("arm_description/urdf/arm.urdf").display().to_string();
    for filename in ["package://arm_support/meshes/base.stl", "package:///arm_description/meshes/base.stl"] {
        let (sim, robot) = load_in(&format!(r#"<robot name="r">{}</robot>"#, mesh_link("a", filename)), &file);
        assert_eq!(sim.scene().object("a").unwrap().geoms().count(), 1, "{filename}: {:?}", robot.adjusted);
    }
    let _ = std::fs::remove_dir_all(root);
}

#[test]
fn a_mimic_of_a_fixed_joint_or_of_a_joint_not_in_the_file_is_dropped_with_a_note() {
    // talos_left_arm.urdf: a fixed joint with a <mimic> of a hinge; alex_psyonic_hands.urdf:
    // a <mimic> naming a joint of another file.
    let text = format!(
        r#"<robot name="r">{}{}{}{}{}<joint name="f" type="fixed"><parent link="a"/><child link="c"/><mimic joint="j"/></joint>
           <joint name="k" type="revolute"><parent link="b"/><child link="d"/><mimic joint="elsewhere"/></joint></robot>"#,
        link("a", 1.0),
        link("b", 1.0),
        link("c", 1.0),
        link("d", 1.0),
        hinge("j", "a", "b"),
    );
    let (sim, robot) = load(&text);
    assert!(
        noted(&robot, &["joint \"f\"", "fixed joint cannot follow joint \"j\"", "dropped"]),
        "{:?}",
        robot.adjusted
    );
    assert!(
        noted(&robot, &["joint \"k\"", "\"elsewhere\", which is not in the file", "dropped"]),
        "{:?}",
        robot.adjusted
    );
    assert!(sim.scene().joint("k").unwrap().mimic().is_none());
}

#[test]
fn massless_links_between_hinges_borrow_mass_and_the_total_stays_the_files() {
    // human.urdf: *_virtual links without <inertial> between the hinges of a hip.
    let text = format!(
        r#"<robot name="r">{}<link name="virtual"/>{}{}{}</robot>"#,
        link("pelvis", 10.0),
        link("thigh", 7.0),
        hinge("hip_z", "pelvis", "virtual"),
        hinge("hip_x", "virtual", "thigh"),
    );
    let (sim, robot) = load(&text);
    assert!((total_mass(&sim) - 17.0).abs() <= 1e-12 * 17.0, "{}", total_mass(&sim));
    let virtual_mass = sim.scene().object("virtual").unwrap().body().unwrap().mass();
    assert_eq!(virtual_mass, 10.0 * 1e-3);
    assert!(noted(&robot, &["link \"virtual\"", "by link \"pelvis\""]), "{:?}", robot.adjusted);
}

#[test]
fn a_nul_byte_after_the_document_is_ignored() {
    // pybullet_data/humanoid/humanoid.urdf ends with "</robot>\r\n\0".
    let text = format!("<robot name=\"r\">{}</robot>\r\n\0", link("a", 1.0));
    let (_, robot) = load(&text);
    assert!(robot.link("a").is_some());
}
