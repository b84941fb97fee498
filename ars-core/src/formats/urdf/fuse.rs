//! Links held by fixed joints fused into one body, as MuJoCo's compiler does for URDF
//! (`fusestatic`).
//!
//! A link with mass on a `fixed` joint moves with its parent: one rigid body. Made as
//! two ODE bodies and a fixed joint, it costs six constraint rows that ODE's exact
//! solver pays for cubically, and it is rigid only as nearly as the solver holds it (a
//! 60 g foot on a 0.17 kg calf shook loose). So its mass is moved into the link it is
//! fixed to (combined about their common centre); the link is then massless and fixed,
//! which the builder merges into that body as it merges any massless fixed link: its
//! geoms and visuals on that body, its name naming that body's object.
//!
//! A static root (massless: a `world` link) takes no mass: a link with mass fixed to it
//! stays a body of its own, held by a fixed joint, so the robot weighs what its file
//! says. [`UrdfOptions::keep_fixed_links`](super::UrdfOptions::keep_fixed_links) turns
//! this off.

use std::collections::HashMap;

use nalgebra::Vector3;

use super::frame::Frame;
use super::model;
use crate::formats::{RigidMass, combined_mass, inertia_tensor, moved_mass};

/// The robot with every link that has mass and a fixed parent joint fused into the
/// link it is fixed to (see the module docs), and the line that says so; `None` when
/// no link is fused, or the tree is not one (the plan says what is wrong with it).
pub(super) fn fuse_fixed_links(robot: &model::Robot) -> Option<(model::Robot, String)> {
    let index: HashMap<&str, usize> = robot.links.iter().enumerate().map(|(k, l)| (l.name.as_str(), k)).collect();
    let mut parent_joint = vec![None; robot.links.len()];
    for (j, joint) in robot.joints.iter().enumerate() {
        let child = *index.get(joint.child.link.as_str())?;
        index.get(joint.parent.link.as_str())?;
        if parent_joint[child].replace(j).is_some() {
            return None;
        }
    }
    let mut roots = (0..robot.links.len()).filter(|&k| parent_joint[k].is_none());
    let (root, None) = (roots.next()?, roots.next()) else { return None };
    let static_root = robot.links[root].inertial.mass.value <= 0.0;
    // Each link's host: itself, or the host of the link it is fixed to (not a static
    // root). Walked up at most as many links as there are (a loop gives up).
    let host_of = |mut k: usize| -> Option<(usize, Frame)> {
        let mut to_host = Frame::from_pose(&model::Pose::default());
        for _ in 0..robot.links.len() {
            let Some(j) = parent_joint[k] else { return Some((k, to_host)) };
            let joint = &robot.joints[j];
            let parent = index[joint.parent.link.as_str()];
            if joint.joint_type != model::JointType::Fixed || (parent == root && static_root) {
                return Some((k, to_host));
            }
            to_host = Frame::from_pose(&joint.origin).then(&to_host);
            k = parent;
        }
        None
    };
    let mut fused = robot.clone();
    let mut masses: Vec<Option<RigidMass>> = vec![None; robot.links.len()];
    let mut said = Vec::new();
    for (k, link) in robot.links.iter().enumerate() {
        let (host, to_host) = host_of(k)?;
        if host == k || link.inertial.mass.value <= 0.0 {
            continue;
        }
        let at = to_host.then(&Frame::from_pose(&link.inertial.origin)).isometry();
        let own = rigid_mass(&link.inertial);
        let host_own = rigid_mass(&robot.links[host].inertial);
        let host_at = Frame::from_pose(&robot.links[host].inertial.origin).isometry();
        let so_far = masses[host].or_else(|| (host_own.0 > 0.0).then(|| moved_mass(host_own, &host_at)));
        masses[host] = Some(combined_mass(so_far, moved_mass(own, &at)));
        fused.links[k].inertial = model::Inertial::default();
        said.push(format!("{:?} into {:?}", link.name, robot.links[host].name));
    }
    if said.is_empty() {
        return None;
    }
    for (host, mass) in masses.into_iter().enumerate() {
        let Some((mass, com, inertia)) = mass else { continue };
        let i = &mut fused.links[host].inertial;
        i.mass.value = mass;
        i.origin = model::Pose { xyz: model::Vec3(com.into()), rpy: model::Vec3([0.0; 3]) };
        (i.inertia.ixx, i.inertia.iyy, i.inertia.izz) = (inertia[(0, 0)], inertia[(1, 1)], inertia[(2, 2)]);
        (i.inertia.ixy, i.inertia.ixz, i.inertia.iyz) = (inertia[(0, 1)], inertia[(0, 2)], inertia[(1, 2)]);
    }
    let line = format!(
        "{} link(s) with mass on fixed joints fused into the body they are fixed to, one rigid body each \
         (MuJoCo's fusestatic; UrdfOptions::keep_fixed_links keeps them apart): {}",
        said.len(),
        said.join(", ")
    );
    Some((fused, line))
}

/// A link's mass, centre and inertia in its inertial frame.
fn rigid_mass(inertial: &model::Inertial) -> RigidMass {
    let i = &inertial.inertia;
    (inertial.mass.value, Vector3::zeros(), inertia_tensor([i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz]))
}

#[cfg(test)]
mod tests {
    use crate::formats::urdf::{UrdfOptions, UrdfRobot};
    use crate::simulation::Simulation;

    /// A 1 kg base (unit inertia) with a 1 kg box fixed 1 m along its x, and a hinge
    /// to an arm; with `static_root`, all of it under a massless `world` link on a
    /// fixed joint.
    fn file(static_root: bool) -> String {
        let world = if static_root {
            r#"<link name="world"/><joint name="bolt" type="fixed"><parent link="world"/><child link="base"/></joint>"#
        } else {
            ""
        };
        format!(
            r#"<robot name="r">{world}
            <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
            <link name="box"><inertial><origin rpy="0 0 1.5707963267948966"/><mass value="1"/>
              <inertia ixx="1" iyy="2" izz="3" ixy="0" ixz="0" iyz="0"/></inertial>
              <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
            <joint name="weld" type="fixed"><origin xyz="1 0 0"/><parent link="base"/><child link="box"/></joint>
            <link name="arm"><inertial><mass value="0.5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
            <joint name="elbow" type="revolute"><parent link="box"/><child link="arm"/><axis xyz="0 0 1"/>
              <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
            </robot>"#
        )
    }

    fn load(text: &str, options: &UrdfOptions) -> (Simulation, UrdfRobot) {
        let mut sim = Simulation::new().unwrap();
        let robot = sim.load_urdf_text(text, "test.urdf", options).unwrap();
        (sim, robot)
    }

    #[test]
    fn a_link_with_mass_on_a_fixed_joint_is_one_body_with_its_parent() {
        let (sim, robot) = load(&file(false), &UrdfOptions::new().exact_base_pose(true));
        let base = robot.link("base").unwrap();
        assert_eq!(robot.link("box"), Some(base), "the box names its host's object");
        assert!(robot.joint("weld").is_none());
        assert!(robot.joint("elbow").is_some());
        let body = sim.scene().object(base).unwrap().body().unwrap();
        assert_eq!(body.mass(), 2.0);
        // Centre halfway (1 m along the file's x: ARS's x too, Z up turned to Y up).
        assert!((body.position() - nalgebra::Point3::new(0.5, 0.0, 0.0)).norm() < 1e-12);
        // About the common centre, in the file's axes: the box turned 90° about z swaps
        // its x and y moments (2, 1, 3), plus 1 kg at ±0.5 m across y and z: 0.25 each.
        let expected = [1.0 + 2.0, 1.0 + 1.0 + 0.5, 1.0 + 3.0 + 0.5];
        let inertia = body.inertia_world();
        // File x, y, z are ARS x, -z, y.
        let got = [inertia[(0, 0)], inertia[(2, 2)], inertia[(1, 1)]];
        for (g, e) in got.iter().zip(expected) {
            assert!((g - e).abs() < 1e-12, "{got:?} against {expected:?}");
        }
        assert!(
            robot.adjusted.iter().any(|a| a.contains("fused") && a.contains("\"box\" into \"base\"")),
            "{:?}",
            robot.adjusted
        );
    }

    #[test]
    fn keep_fixed_links_keeps_them_apart_and_a_static_root_takes_no_mass() {
        let (sim, robot) = load(&file(false), &UrdfOptions::new().keep_fixed_links(true));
        assert_ne!(robot.link("box"), robot.link("base"));
        assert!(robot.joint("weld").is_some());
        assert!(!robot.adjusted.iter().any(|a| a.contains("fused")));
        drop(sim);
        // Under a static root the base keeps its own body and its fixed joint to the
        // root; the box is fused into the base. The robot weighs its 2.5 kg.
        let (sim, robot) = load(&file(true), &UrdfOptions::new());
        let base = robot.link("base").unwrap();
        assert_ne!(robot.link("world"), Some(base));
        assert!(robot.joint("bolt").is_some());
        assert_eq!(robot.link("box"), Some(base));
        let total: f64 = [base, robot.link("arm").unwrap()]
            .iter()
            .map(|id| sim.scene().object(*id).unwrap().body().unwrap().mass())
            .sum();
        assert_eq!(total, 2.5);
    }

    #[test]
    fn fusing_hostile_masses_is_refused_or_finite_never_a_panic() {
        // Two masses whose sum overflows, two far below ARS's least, and one link's
        // inertia of 1e308: fused or not, a clear answer.
        for (mass, inertia) in [("1e308", "1"), ("1e-300", "1e-300"), ("1", "1e308")] {
            let link = |name: &str| {
                format!(
                    r#"<link name="{name}"><inertial><mass value="{mass}"/><inertia ixx="{inertia}" iyy="{inertia}" izz="{inertia}" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
                )
            };
            let text = format!(
                r#"<robot name="r">{}{}<joint name="weld" type="fixed"><origin xyz="1 0 0"/><parent link="a"/><child link="b"/></joint></robot>"#,
                link("a"),
                link("b")
            );
            let mut sim = Simulation::new().unwrap();
            match sim.load_urdf_text(&text, "hostile.urdf", &UrdfOptions::new()) {
                Ok(robot) => {
                    let body = sim.scene().object(robot.link("a").unwrap()).unwrap().body().unwrap();
                    assert!(body.mass().is_finite() && body.inertia().iter().all(|x| x.is_finite()), "{mass}");
                    sim.step().unwrap();
                }
                Err(e) => {
                    assert!(e.to_string().contains("hostile.urdf"), "{e}");
                    assert_eq!(sim.scene().objects().count(), 0, "nothing left behind: {e}");
                }
            }
        }
    }
}
