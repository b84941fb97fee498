//! Cause: a URDF file whose joints make a loop of links apart from the root (base
//! alone; fore → turret → upper → fore) passed the checks for one root and one parent
//! joint a link, and the frames' walk from the root then panicked ("a tree reaches
//! every link"). Found by the `robot_files` fuzz target. Fixed by checking that the
//! walk up from every link ends at the root.

use ars_core::*;

#[test]
fn a_loop_of_links_apart_from_the_root_is_refused_naming_a_link() {
    let link = |name: &str| {
        format!(
            r#"<link name="{name}"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
        )
    };
    let joint = |name: &str, parent: &str, child: &str| {
        format!(
            r#"<joint name="{name}" type="continuous"><parent link="{parent}"/><child link="{child}"/><axis xyz="0 0 1"/></joint>"#
        )
    };
    let file = format!(
        r#"<robot name="r">{}{}{}{}{}{}{}</robot>"#,
        link("base"),
        link("turret"),
        link("upper"),
        link("fore"),
        joint("j1", "fore", "turret"),
        joint("j2", "turret", "upper"),
        joint("j3", "upper", "fore"),
    );
    let mut sim = Simulation::new().unwrap();
    let error = sim.load_urdf_text(&file, "loop.urdf", &UrdfOptions::new()).unwrap_err().to_string();
    assert!(error.contains("link \"turret\"") && error.contains("loop"), "{error}");
    assert_eq!(sim.scene().objects().count(), 0, "nothing left");
}
