//! What a scene keeps of each URDF robot and MJCF model it loaded, for those who
//! describe it to others (a ROS bridge's `/robot_description` and `/tf`): a URDF file's
//! text, the joint tree, and where each link's (or MJCF body's) frame is on the object
//! that carries it.
//!
//! A link's object is a body at the link's inertial frame (ODE's body frame is the
//! centre of mass), or the body of the link it was merged into, or static geometry; the
//! link's own frame (its URDF origin, what `robot_state_publisher` and RViz place meshes
//! at) is at a fixed offset from that object: [`LinkFrame::offset`].

use std::sync::Arc;

use nalgebra::Isometry3;

use crate::handle::ObjectId;

/// A URDF robot or an MJCF model of a scene, as ROS describes it: what
/// [`Scene::robot_descriptions`](crate::scene::Scene::robot_descriptions) lists. Its
/// links' frames are their URDF origins (what `robot_state_publisher` and RViz place
/// meshes at), or an MJCF model's body frames, each at a fixed
/// [`offset`](LinkFrame::offset) from the object that carries it (a body at the link's
/// inertial frame, or the body it was merged into).
#[derive(Clone, Debug, PartialEq)]
pub struct RobotDescription {
    /// The robot's name.
    pub name: String,
    /// The URDF file's text, as read (`None` for an MJCF model: ROS's
    /// `/robot_description` is URDF).
    pub urdf: Option<Arc<str>>,
    /// Every link of the file (MJCF: every body but those welded to the world), in
    /// file order.
    pub links: Vec<LinkFrame>,
    /// Every joint of the file, in file order (also those of merged links, which have
    /// no joint in the simulation); an MJCF body's is its last joint's name, or
    /// `<body>_weld` for a body with none.
    pub joints: Vec<TreeJoint>,
    /// The root links' names: a URDF robot's one, an MJCF model's top bodies.
    pub roots: Vec<String>,
}

/// A URDF link (or an MJCF body) and where its frame is.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkFrame {
    /// The link's name.
    pub name: String,
    /// The object that carries it (its own, or the one it was merged into).
    pub object: ObjectId,
    /// The link's frame in the object's frame (constant: the link moves with it).
    pub offset: Isometry3<f64>,
}

/// A URDF joint (or an MJCF body's joints) as an edge of the link tree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TreeJoint {
    /// The joint's name.
    pub name: String,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// Whether it is a `fixed` joint (the child never moves relative to the parent).
    pub fixed: bool,
}

#[cfg(test)]
mod tests {
    use nalgebra::{UnitQuaternion, Vector3};

    use crate::Simulation;
    use crate::formats::urdf::UrdfOptions;

    const ARM: &str = r#"<robot name="arm">
      <link name="base"><inertial><origin xyz="0 0 0.1"/><mass value="1"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="upper"><inertial><origin xyz="0.2 0 0" rpy="0 0.3 0"/><mass value="1"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="tool"/>
      <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
        <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="flange" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0.1 0 0"/></joint>
    </robot>"#;

    #[test]
    fn a_scene_keeps_each_urdf_robots_text_tree_and_link_frames_on_their_objects() {
        let mut sim = Simulation::new().unwrap();
        let options = UrdfOptions::new().fixed_base(true).exact_base_pose(true);
        let robot = sim.load_urdf_text(ARM, "arm.urdf", &options).unwrap();
        let [description] = sim.scene().robot_descriptions() else { panic!("one robot") };
        assert_eq!(description.urdf.as_deref(), Some(ARM));
        assert_eq!((description.name.as_str(), description.roots.as_slice()), ("arm", ["base".to_string()].as_slice()));
        let tree: Vec<_> = description
            .joints
            .iter()
            .map(|j| (j.name.as_str(), j.parent.as_str(), j.child.as_str(), j.fixed))
            .collect();
        assert_eq!(tree, [("shoulder", "base", "upper", false), ("flange", "upper", "tool", true)]);
        // The merged tool link rides on the upper arm's object.
        assert_eq!(description.links[2].object, robot.link("upper").unwrap());
        // Each link's frame in the world: Z-up turned Y-up (−90° about X), the joint
        // origins along the file's Z (the world's Y), not the inertial frames.
        let turn = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -std::f64::consts::FRAC_PI_2);
        let world = |k: usize| sim.scene().pose(description.links[k].object).unwrap() * description.links[k].offset;
        for (k, position) in [(0, [0.0, 0.0, 0.0]), (1, [0.0, 0.5, 0.0]), (2, [0.1, 0.5, 0.0])] {
            let frame = world(k);
            assert!((frame.translation.vector - Vector3::from(position)).norm() < 1e-12, "link {k}: {frame}");
            assert!(frame.rotation.angle_to(&turn) < 1e-12, "link {k}: {frame}");
        }
    }
}
