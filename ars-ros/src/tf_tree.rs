//! The frame tree of a simulation, as `/tf` and `/tf_static` publish it.
//!
//! - URDF robots and MJCF models ([`Scene::robot_descriptions`]): a frame per link
//!   (MJCF: per body), named after it, at the link's own frame (its URDF origin, the
//!   MJCF body's frame; not its body's centre of mass). Each joint gives its child link
//!   relative to its parent link: on `/tf_static` for a fixed joint (a jointless MJCF
//!   body), on `/tf` otherwise; the root links are given in `map` (on `/tf_static` when
//!   static).
//! - Every other object (free bodies, MJCF bodies, static shapes; not planes): a frame
//!   named after it, at its body's origin with its ROS axes
//!   ([`ros_axes`]: Z up for an upright object). A moving body joined to another by a
//!   joint whose first object is that other body is given in that body's frame (the
//!   joint tree: an MJCF child body in its parent, a thesis vehicle's wheel in its
//!   chassis); the others in `map` (on `/tf_static` when static).
//! - A vehicle's chassis is given in `odom` instead, `odom` in `map` (the identity: the
//!   simulation's odometry is exact).
//! - Sensors: a frame each on the frame of the object they are mounted on, or in `map`,
//!   on `/tf_static`.
//!
//! Objects and links are published as they were when the tree was made: one added
//! later is not, one removed since is left out.

use std::collections::HashMap;

use ars_core::scene::Scene;
use ars_core::{ObjectId, Result, Shape};
use nalgebra::Isometry3;

use crate::frames::{ros_axes, world_pose_to_ros};

/// The world frame.
pub const MAP: &str = "map";
/// The frame vehicles' odometry is given in.
pub const ODOM: &str = "odom";

/// Where a frame is on an object: the object and the frame's pose in the object's frame.
type OnObject = (ObjectId, Isometry3<f64>);

/// A moving edge of the tree.
#[derive(Clone, Debug)]
enum Moving {
    /// A frame given in `map` (or `odom`: the same).
    InWorld(OnObject),
    /// A frame given relative to another on another object.
    Between(OnObject, OnObject),
}

/// The frame tree (see the [module docs](self)).
#[derive(Clone, Debug, Default)]
pub struct FrameTree {
    /// The objects of URDF robots (their frames are Z-up links, not turned).
    links: std::collections::HashSet<ObjectId>,
    /// (parent, child, how its pose is found), for `/tf`.
    moving: Vec<(String, String, Moving)>,
    /// (parent, child, pose), for `/tf_static`.
    fixed: Vec<(String, String, Isometry3<f64>)>,
    /// Each object's frame: its name, and where it is on the object.
    object_frames: HashMap<ObjectId, (String, Isometry3<f64>)>,
}

impl FrameTree {
    /// The tree of `scene` now; `vehicles` are given in `odom`.
    pub fn of(scene: &Scene, vehicles: &[ObjectId]) -> Result<FrameTree> {
        let mut tree = FrameTree::default();
        tree.add_robots(scene, vehicles)?;
        let mut own = Vec::new();
        for (name, id) in scene.objects() {
            let plane = matches!(scene.object(id)?.shape(), Shape::Plane { .. });
            if tree.object_frames.contains_key(&id) || plane {
                continue;
            }
            tree.object_frames.insert(id, (name.to_string(), ros_axes()));
            own.push((name, id));
        }
        let parents = joint_parents(scene)?;
        for (name, id) in own {
            match parents.get(&id).and_then(|p| Some((*p, tree.object_frames.get(p)?.clone()))) {
                Some((parent, (parent_frame, on_parent))) if !vehicles.contains(&id) => {
                    let edge = Moving::Between((parent, on_parent), (id, ros_axes()));
                    tree.moving.push((parent_frame, name.to_string(), edge));
                }
                _ => {
                    let parent = if vehicles.contains(&id) { ODOM } else { MAP };
                    tree.add_in_world(scene, parent, name, (id, ros_axes()))?;
                }
            }
        }
        if !vehicles.is_empty() {
            tree.fixed.push((MAP.into(), ODOM.into(), Isometry3::identity()));
        }
        Ok(tree)
    }

    /// Every URDF robot's links, by its joint tree (a root that is a vehicle's chassis
    /// in `odom`).
    fn add_robots(&mut self, scene: &Scene, vehicles: &[ObjectId]) -> Result<()> {
        for robot in scene.robot_descriptions() {
            // Links whose object was removed since are left out.
            let links: Vec<_> = robot.links.iter().filter(|l| scene.object(l.object).is_ok()).collect();
            let on: HashMap<&str, OnObject> = links.iter().map(|l| (l.name.as_str(), (l.object, l.offset))).collect();
            for link in links {
                self.links.insert(link.object);
                // An object is named after the link it was made for; links merged into
                // it are frames of their own on it.
                let own = scene.object(link.object).is_ok_and(|o| o.name() == link.name);
                if own || !self.object_frames.contains_key(&link.object) {
                    self.object_frames.insert(link.object, (link.name.clone(), link.offset));
                }
            }
            for root in &robot.roots {
                if let Some(&on_root) = on.get(root.as_str()) {
                    let parent = if vehicles.contains(&on_root.0) { ODOM } else { MAP };
                    self.add_in_world(scene, parent, root, on_root)?;
                }
            }
            for joint in &robot.joints {
                let (Some(&parent), Some(&child)) = (on.get(joint.parent.as_str()), on.get(joint.child.as_str()))
                else {
                    continue;
                };
                let edge = (joint.parent.clone(), joint.child.clone());
                if joint.fixed || parent.0 == child.0 {
                    let pose = relative(scene, parent, child)?;
                    self.fixed.push((edge.0, edge.1, pose));
                } else {
                    self.moving.push((edge.0, edge.1, Moving::Between(parent, child)));
                }
            }
        }
        Ok(())
    }

    /// A frame given in the world: fixed if its object is static.
    fn add_in_world(&mut self, scene: &Scene, parent: &str, child: &str, on: OnObject) -> Result<()> {
        if scene.object(on.0)?.body_handle().is_some() {
            self.moving.push((parent.into(), child.into(), Moving::InWorld(on)));
        } else {
            self.fixed.push((parent.into(), child.into(), world_pose_to_ros(&(scene.pose(on.0)? * on.1))));
        }
        Ok(())
    }

    /// A sensor's frame `name` on `object` at `offset` from its origin (in the world
    /// at `offset` when `None`), `turn` composed after (a lidar's ROS frame).
    pub fn add_sensor(&mut self, name: &str, object: Option<ObjectId>, offset: Isometry3<f64>, turn: Isometry3<f64>) {
        match object.and_then(|o| self.object_frames.get(&o)) {
            Some((parent, frame_on_object)) => {
                let pose = frame_on_object.inverse() * offset * turn;
                self.fixed.push((parent.clone(), name.into(), pose));
            }
            None => self.fixed.push((MAP.into(), name.into(), world_pose_to_ros(&offset) * turn)),
        }
    }

    /// Whether `object` was built in ARS's Y-up world (not a URDF link's): a sensor on
    /// it gets ROS axes turned from its own.
    pub fn is_ars_built(&self, object: ObjectId) -> bool {
        !self.links.contains(&object)
    }

    /// The frame an object's pose is published as: its name and where it is on the
    /// object.
    pub fn object_frame(&self, object: ObjectId) -> Option<&(String, Isometry3<f64>)> {
        self.object_frames.get(&object)
    }

    /// The fixed edges: (parent, child, pose of the child in the parent).
    pub fn fixed(&self) -> &[(String, String, Isometry3<f64>)] {
        &self.fixed
    }

    /// The moving edges now: (parent, child, pose of the child in the parent); an edge
    /// whose object was removed is left out.
    pub fn moving<'t>(&'t self, scene: &'t Scene) -> impl Iterator<Item = (&'t str, &'t str, Isometry3<f64>)> + 't {
        self.moving.iter().filter_map(move |(parent, child, how)| {
            let pose = match how {
                Moving::InWorld((id, offset)) => world_pose_to_ros(&(scene.pose(*id).ok()? * offset)),
                Moving::Between(p, c) => relative(scene, *p, *c).ok()?,
            };
            Some((parent.as_str(), child.as_str(), pose))
        })
    }
}

/// Each moving object's parent along the joint tree: the first object of a joint whose
/// second it is, both moving bodies (the first such joint, in the order of the joints'
/// names; none that would close a loop).
fn joint_parents(scene: &Scene) -> Result<HashMap<ObjectId, ObjectId>> {
    let mut parent: HashMap<ObjectId, ObjectId> = HashMap::new();
    let moving = |o: ObjectId| scene.object(o).is_ok_and(|v| v.body_handle().is_some());
    for (_, id) in scene.joints() {
        let (first, second) = scene.joint(id)?.objects();
        let Some(child) = second else { continue };
        if moving(first) && moving(child) && !parent.contains_key(&child) && !is_above(&parent, child, first) {
            parent.insert(child, first);
        }
    }
    Ok(parent)
}

/// Whether `ancestor` is `object` or above it in the tree `parent`.
fn is_above(parent: &HashMap<ObjectId, ObjectId>, ancestor: ObjectId, mut object: ObjectId) -> bool {
    loop {
        if object == ancestor {
            return true;
        }
        match parent.get(&object) {
            Some(p) => object = *p,
            None => return false,
        }
    }
}

/// The frame `child` in the frame `parent`, both on objects.
fn relative(scene: &Scene, parent: OnObject, child: OnObject) -> Result<Isometry3<f64>> {
    let parent_pose = scene.pose(parent.0)? * parent.1;
    let child_pose = scene.pose(child.0)? * child.1;
    Ok(parent_pose.inverse() * child_pose)
}
