//! The frame tree of a simulation, as `/tf` and `/tf_static` publish it.
//!
//! - URDF robots ([`Scene::robot_descriptions`]): a frame per link, named after it,
//!   at the link's own frame (its URDF origin, not its body's centre of mass). Each
//!   URDF joint gives its child link relative to its parent link: on `/tf_static` for a
//!   fixed joint, on `/tf` otherwise; the root link is given in `map` (on `/tf_static`
//!   when it is static).
//! - Every other object (free bodies, MJCF bodies, static shapes; not planes): a frame
//!   named after it, at its body's origin with its ROS axes
//!   ([`ros_axes`]: Z up for an upright object), given in `map`
//!   (on `/tf_static` when it is static).
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
        tree.add_robots(scene)?;
        for (name, id) in scene.objects() {
            let plane = matches!(scene.object(id)?.shape(), Shape::Plane { .. });
            if tree.object_frames.contains_key(&id) || plane {
                continue;
            }
            tree.object_frames.insert(id, (name.to_string(), ros_axes()));
            let parent = if vehicles.contains(&id) { ODOM } else { MAP };
            tree.add_in_world(scene, parent, name, (id, ros_axes()))?;
        }
        if !vehicles.is_empty() {
            tree.fixed.push((MAP.into(), ODOM.into(), Isometry3::identity()));
        }
        Ok(tree)
    }

    /// Every URDF robot's links, by its joint tree.
    fn add_robots(&mut self, scene: &Scene) -> Result<()> {
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
            if let Some(&root) = on.get(robot.root.as_str()) {
                self.add_in_world(scene, MAP, &robot.root, root)?;
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

/// The frame `child` in the frame `parent`, both on objects.
fn relative(scene: &Scene, parent: OnObject, child: OnObject) -> Result<Isometry3<f64>> {
    let parent_pose = scene.pose(parent.0)? * parent.1;
    let child_pose = scene.pose(child.0)? * child.1;
    Ok(parent_pose.inverse() * child_pose)
}
