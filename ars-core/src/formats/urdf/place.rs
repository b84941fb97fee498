//! Where a robot starts: a floating robot whose collision geometry would reach into a
//! floor of the scene at the pose asked for is raised to rest on it (see the rule in
//! [the module docs](super)).

use nalgebra::{Isometry3, Vector3};

use super::UrdfOptions;
use super::frame::Frame;
use super::meshes::Meshes;
use super::model;
use crate::scene::Scene;
use crate::shape::Shape;

/// A floor plane `normal · x = offset` (`normal` a unit vector), by its object's name.
struct FloorPlane {
    name: String,
    normal: Vector3<f64>,
    offset: f64,
}

/// How a robot was raised onto a floor.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Raise {
    /// How far up (+Y), m.
    pub(super) height: f64,
    /// The floor it rests on.
    pub(super) floor: String,
    /// How far its collision geometry reached into that floor (along its normal), m.
    pub(super) depth: f64,
}

impl Raise {
    /// The line said in [`UrdfRobot::adjusted`](super::UrdfRobot::adjusted).
    pub(super) fn note(&self, robot: &str) -> String {
        format!(
            "robot {robot:?}: raised {:.6} m to rest on {:?}: at the base pose asked for, its collision geometry \
             reached {:.6} m into it (UrdfOptions::exact_base_pose, Python's exact_base_pose=True, keeps the pose)",
            self.height, self.floor, self.depth
        )
    }
}

impl Scene {
    /// The planes that are floors: static planes of the scene facing up, their normal
    /// within 45° of +Y (walls and ceilings are not).
    fn floor_planes(&self) -> Vec<FloorPlane> {
        self.objects_in_creation_order()
            .filter(|(_, data)| data.body.is_none())
            .filter_map(|(_, data)| match &data.shape {
                Shape::Plane { normal, distance } => {
                    let length = normal.norm();
                    let (normal, offset) = (normal / length, distance / length);
                    let facing_up = normal.y >= std::f64::consts::FRAC_1_SQRT_2;
                    (length.is_finite() && length > 0.0 && facing_up).then(|| FloorPlane {
                        name: data.name.clone(),
                        normal,
                        offset,
                    })
                }
                _ => None,
            })
            .collect()
    }

    /// How far up a robot whose links start at `link_frames` must go for none of its
    /// collision elements to reach into a floor of the scene: `None` when it need not
    /// move, or when it is not free to (a fixed base) or [`UrdfOptions::exact_base_pose`]
    /// keeps it where asked. Under a massless root (static) only the links with bodies
    /// count.
    pub(super) fn floor_raise(
        &self,
        robot: &model::Robot,
        root: usize,
        link_frames: &[Frame],
        options: &UrdfOptions,
        meshes: &mut Meshes<'_>,
    ) -> Option<Raise> {
        if options.fixed_base || options.exact_base_pose {
            return None;
        }
        // A massless root is static, with the massless links fixed to it: what is static
        // does not collide with a floor, every body does.
        let hosts = super::build::merge_hosts(robot, root);
        let static_root = robot.links[root].inertial.mass.value <= 0.0;
        let counted: Vec<bool> =
            (0..robot.links.len()).map(|i| !(static_root && (i == root || hosts[i] == Some(root)))).collect();
        let floors = self.floor_planes();
        if floors.is_empty() {
            return None;
        }
        // Each collision element placed where it starts (a mesh that cannot be loaded
        // is left out here: building the link says what is wrong with it).
        let mut placed = Vec::new();
        for ((link, frame), _) in robot.links.iter().zip(link_frames).zip(&counted).filter(|(_, counted)| **counted) {
            for collision in &link.collision {
                if let Ok(shape) = meshes.shape(&collision.geometry) {
                    placed.push((shape, frame.then(&Frame::from_pose(&collision.origin)).isometry()));
                }
            }
        }
        let mut raise: Option<Raise> = None;
        for floor in &floors {
            let lowest = placed
                .iter()
                .filter_map(|(shape, pose)| least_along(shape, pose, &floor.normal))
                .fold(f64::INFINITY, f64::min);
            let depth = floor.offset - lowest;
            // Raising by h moves every point by h·normal.y along the normal.
            let height = depth / floor.normal.y;
            if depth > 0.0 && height.is_finite() && raise.as_ref().is_none_or(|r| height > r.height) {
                raise = Some(Raise { height, floor: floor.name.clone(), depth });
            }
        }
        raise
    }
}

/// The least `direction · x` over the points of `shape` at `pose` (`direction` a unit
/// vector in the world frame); `None` for what has no solid (a plane, a ray).
pub(super) fn least_along(shape: &Shape, pose: &Isometry3<f64>, direction: &Vector3<f64>) -> Option<f64> {
    // The direction in the shape's frame, and how far the shape reaches against it
    // from its origin.
    let d = pose.rotation.inverse() * direction;
    let across = (d.x * d.x + d.y * d.y).sqrt();
    let reach = match shape {
        Shape::Sphere { radius } => *radius,
        Shape::Box { edges } => 0.5 * (edges.x * d.x.abs() + edges.y * d.y.abs() + edges.z * d.z.abs()),
        Shape::Capsule { radius, length } => radius + 0.5 * length * d.z.abs(),
        Shape::Cylinder { radius, length } => radius * across + 0.5 * length * d.z.abs(),
        // Apex 3/4 of the height above the origin, base circle 1/4 below.
        Shape::Cone { radius, height } => (-0.75 * height * d.z).max(0.25 * height * d.z + radius * across),
        Shape::TriMesh { vertices, .. } | Shape::ConvexHull { vertices, .. } => {
            vertices.iter().map(|v| -d.dot(&v.coords)).fold(f64::NEG_INFINITY, f64::max)
        }
        Shape::Plane { .. } | Shape::Ray { .. } => return None,
    };
    Some(direction.dot(&pose.translation.vector) - reach)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::urdf::{UrdfOptions, UrdfRobot};
    use crate::simulation::Simulation;
    use nalgebra::{Point3, UnitQuaternion};

    /// A ball of radius 0.5 whose centre is its root frame (pybullet_data's
    /// `sphere2.urdf`), and, when `massless`, its root without mass (static).
    fn ball(massless: bool) -> String {
        let mass = if massless { 0.0 } else { 1.0 };
        format!(
            r#"<robot name="ball"><link name="ball"><inertial><mass value="{mass}"/>
            <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
            <collision><geometry><sphere radius="0.5"/></geometry></collision></link></robot>"#
        )
    }

    /// A box body with a 1 m leg on a hinge about Y, pointing up (Z) at 0.
    const LEG: &str = r#"<robot name="leg">
      <link name="hip"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
        <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
      <link name="shin"><inertial><origin xyz="0 0 0.5"/><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
        <collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 1"/></geometry></collision></link>
      <joint name="knee" type="revolute"><parent link="hip"/><child link="shin"/><axis xyz="0 1 0"/>
        <limit lower="-3.1" upper="3.1" effort="10" velocity="1"/></joint>
    </robot>"#;

    fn load(floor: Option<(Vector3<f64>, f64)>, text: &str, options: &UrdfOptions) -> (Simulation, UrdfRobot) {
        let mut sim = Simulation::new().unwrap();
        if let Some((normal, distance)) = floor {
            sim.scene_mut().add_floor_plane(normal, distance).unwrap();
        }
        let robot = sim.load_urdf_text(text, "test.urdf", options).unwrap();
        (sim, robot)
    }

    fn position(sim: &Simulation, name: &str) -> Point3<f64> {
        sim.scene().object(name).unwrap().position().unwrap()
    }

    const FLOOR: Option<(Vector3<f64>, f64)> = Some((UP, 0.0));

    #[test]
    fn a_robot_centred_on_the_floor_is_raised_to_rest_on_it_and_is_not_shot_out() {
        let (mut sim, robot) = load(FLOOR, &ball(false), &UrdfOptions::new());
        assert_eq!(position(&sim, "ball"), Point3::new(0.0, 0.5, 0.0));
        assert_eq!(robot.adjusted.len(), 1, "{:?}", robot.adjusted);
        assert!(robot.adjusted[0].starts_with("robot \"ball\": raised 0.500000 m to rest on \"floor\""));
        let mut fastest = 0.0_f64;
        for _ in 0..1000 {
            sim.step().unwrap();
            let body = sim.scene().object("ball").unwrap().body().unwrap();
            fastest = fastest.max(body.linear_velocity().norm());
        }
        // Half buried, ODE pushed it out at 250 m/s.
        assert!(fastest < 0.1, "it rests: {fastest} m/s");
        assert!((position(&sim, "ball").y - 0.5).abs() < 1e-3);
    }

    /// pybullet_data's `cube_no_rotation.urdf`, shortened: a 1 m cube centred at the
    /// origin, moved from a massless `world` link by a prismatic joint along Z.
    const CUBE_ON_A_SLIDER: &str = r#"<robot name="cube"><link name="world"/>
      <link name="cube"><inertial><mass value="0.1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
        <collision><geometry><box size="1 1 1"/></geometry></collision></link>
      <joint name="z" type="prismatic"><parent link="world"/><child link="cube"/><axis xyz="0 0 1"/>
        <limit effort="0" lower="1" upper="-1" velocity="1000"/></joint>
    </robot>"#;

    #[test]
    fn a_static_root_whose_moving_links_reach_into_the_floor_is_raised_with_them() {
        let (mut sim, robot) = load(FLOOR, CUBE_ON_A_SLIDER, &UrdfOptions::new());
        // Z up turned to Y up: 0.5 to the last bit or so.
        assert!((position(&sim, "cube") - Point3::new(0.0, 0.5, 0.0)).norm() < 1e-12);
        assert!(
            robot.adjusted.iter().any(|a| a.starts_with("robot \"cube\": raised 0.500000 m")),
            "{:?}",
            robot.adjusted
        );
        let mut fastest = 0.0_f64;
        for _ in 0..1000 {
            sim.step().unwrap();
            fastest = fastest.max(sim.scene().object("cube").unwrap().body().unwrap().linear_velocity().norm());
        }
        // Half buried, ODE pushed it out at 250 m/s.
        assert!(fastest < 0.1, "it rests: {fastest} m/s");
    }

    #[test]
    fn a_body_welded_to_a_static_root_counts_as_it_collides_with_the_floor() {
        // example-robot-data's simple_humanoid: a massless `base_link`, a fixed joint to
        // a 27 kg body whose 1 m cylinder reaches 0.5 m into the floor.
        let text = r#"<robot name="welded"><link name="base_link"/>
          <link name="body"><inertial><mass value="27"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
            <collision><geometry><cylinder radius="1" length="1"/></geometry></collision></link>
          <joint name="waist" type="fixed"><parent link="base_link"/><child link="body"/></joint>
        </robot>"#;
        let (mut sim, robot) = load(FLOOR, text, &UrdfOptions::new());
        assert!(robot.adjusted.iter().any(|a| a.contains("raised 0.500000 m")), "{:?}", robot.adjusted);
        for _ in 0..500 {
            sim.step().unwrap();
        }
        assert!((position(&sim, "body").y - 0.5).abs() < 1e-3, "{}", position(&sim, "body"));
    }

    #[test]
    fn exact_base_pose_a_fixed_base_a_massless_root_or_no_floor_keep_the_pose() {
        let origin = Point3::origin();
        let exact = UrdfOptions::new().exact_base_pose(true);
        for (floor, text, options) in [
            (FLOOR, ball(false), exact),
            (FLOOR, ball(false), UrdfOptions::new().fixed_base(true)),
            (FLOOR, ball(true), UrdfOptions::new()),
            (None, ball(false), UrdfOptions::new()),
            // A wall (facing +X) and a floor 1 m below are not reached into.
            (Some((Vector3::x(), -0.1)), ball(false), UrdfOptions::new()),
            (Some((UP, -1.0)), ball(false), UrdfOptions::new()),
        ] {
            let (sim, robot) = load(floor, &text, &options);
            assert_eq!(position(&sim, "ball"), origin, "{floor:?} {options:?}");
            assert!(robot.adjusted.is_empty(), "{:?}", robot.adjusted);
        }
    }

    #[test]
    fn a_base_pose_above_the_floor_is_kept_and_one_in_it_only_raised() {
        let at = |x, y, z| UrdfOptions::new().base_pose(Isometry3::translation(x, y, z));
        let (sim, _) = load(FLOOR, &ball(false), &at(1.0, 2.0, 3.0));
        assert_eq!(position(&sim, "ball"), Point3::new(1.0, 2.0, 3.0));
        let (sim, robot) = load(FLOOR, &ball(false), &at(1.0, 0.2, 3.0));
        assert_eq!(position(&sim, "ball"), Point3::new(1.0, 0.5, 3.0));
        assert!(robot.adjusted[0].contains("raised 0.300000 m"), "{:?}", robot.adjusted);
        // A floor 1 m up, and one tilted 30° (its normal in the XY plane): the lowest
        // point touches each.
        let (sim, _) = load(Some((UP * 2.0, 2.0)), &ball(false), &UrdfOptions::new());
        assert!((position(&sim, "ball").y - 1.5).abs() < 1e-12);
        let tilted = Vector3::new(0.5, 3f64.sqrt() / 2.0, 0.0);
        let (sim, _) = load(Some((tilted, 0.0)), &ball(false), &UrdfOptions::new());
        let centre = position(&sim, "ball");
        assert!((tilted.dot(&centre.coords) - 0.5).abs() < 1e-12, "{centre}");
        assert_eq!((centre.x, centre.z), (0.0, 0.0));
    }

    #[test]
    fn the_robot_rests_on_the_floor_in_its_initial_joint_positions() {
        // Upright, the leg is above the hip: the hip's box reaches 0.1 m down.
        let (sim, _) = load(FLOOR, LEG, &UrdfOptions::new());
        assert!((position(&sim, "hip").y - 0.1).abs() < 1e-12);
        // Swung down by 3 rad, the shin reaches below the hip: its far corner rests on
        // the floor.
        let (sim, robot) = load(FLOOR, LEG, &UrdfOptions::new().initial_position("knee", 3.0));
        let (sin, cos) = 3f64.sin_cos();
        let lowest = 0.5 * cos - 0.5 * (0.1 * sin.abs() + cos.abs());
        assert!((position(&sim, "hip").y + lowest).abs() < 1e-12, "{:?}", robot.adjusted);
        assert!((sim.scene().joint("knee").unwrap().state().unwrap().position - 3.0).abs() < 1e-9);
    }

    const UP: Vector3<f64> = Vector3::new(0.0, 1.0, 0.0);

    fn at(x: f64, y: f64, z: f64, axis_angle: Vector3<f64>) -> Isometry3<f64> {
        Isometry3::from_parts(Vector3::new(x, y, z).into(), UnitQuaternion::from_scaled_axis(axis_angle))
    }

    #[test]
    fn the_lowest_point_of_each_primitive_is_found_turned() {
        let upright = at(0.0, 2.0, 0.0, Vector3::zeros());
        // Local Z turned onto the world's Y: a cylinder or capsule along Z stands up.
        let standing = at(0.0, 2.0, 0.0, Vector3::new(-std::f64::consts::FRAC_PI_2, 0.0, 0.0));
        let lowest = |shape: Shape, pose: &Isometry3<f64>| least_along(&shape, pose, &UP).unwrap();
        assert_eq!(lowest(Shape::Sphere { radius: 0.5 }, &upright), 1.5);
        assert_eq!(lowest(Shape::Box { edges: Vector3::new(1.0, 3.0, 5.0) }, &upright), 0.5);
        assert!((lowest(Shape::Cylinder { radius: 0.3, length: 1.0 }, &standing) - 1.5).abs() < 1e-12);
        assert!((lowest(Shape::Cylinder { radius: 0.3, length: 1.0 }, &upright) - 1.7).abs() < 1e-12);
        assert!((lowest(Shape::Capsule { radius: 0.3, length: 1.0 }, &standing) - 1.2).abs() < 1e-12);
        // A cone standing on its base: the base is a quarter of the height below its origin.
        assert!((lowest(Shape::Cone { radius: 0.3, height: 1.0 }, &standing) - 1.75).abs() < 1e-12);
        let box45 = at(0.0, 2.0, 0.0, Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_4));
        let corner = 2.0 - 0.5 * std::f64::consts::SQRT_2;
        assert!((lowest(Shape::Box { edges: Vector3::new(1.0, 1.0, 1.0) }, &box45) - corner).abs() < 1e-12);
        let points = vec![Point3::new(0.0, -0.25, 0.0), Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 0.0, 0.0)];
        assert_eq!(lowest(Shape::TriMesh { vertices: points, triangles: vec![[0, 1, 2]] }, &upright), 1.75);
        assert_eq!(least_along(&Shape::Ray { length: 1.0 }, &upright, &UP), None);
    }
}
