//! What the bridge publishes about a scene: `/joint_states` and the `/tf` tree.
//!
//! ARS is Y up and ROS (REP 103) Z up. Rather than converting every pose, the bridge
//! publishes ARS's world as a frame of its own, [`ARS_WORLD`], placed once on
//! `/tf_static` under ROS's [`WORLD`] by a quarter turn about X; the bodies' poses on
//! `/tf` are then ARS's own numbers (equal to its sensor records), and RViz, with
//! `world` as its fixed frame, shows the scene upright.
//!
//! Frames follow the joint tree: a body joined to another by a joint whose first
//! object is that other body is placed relative to it (a URDF child link relative to
//! its parent link); a body with no such joint is placed in [`ARS_WORLD`].

use std::collections::HashMap;

use ars_core::nalgebra::{Isometry3, UnitQuaternion};
use ars_core::{JointId, JointType, ObjectId, Result, Scene};

use super::wire::{Header, JointState, Quaternion, TfMessage, Time, Transform, TransformStamped, Vector3};

/// ROS's fixed world frame (Z up).
pub const WORLD: &str = "world";
/// ARS's world frame (Y up), a quarter turn about X from [`WORLD`].
pub const ARS_WORLD: &str = "ars_world";

/// The joints and frames of a scene, worked out once when the bridge starts.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneFrames {
    /// The joints with one position (hinges, sliders, pistons): `/joint_states`'
    /// names and the forward command controllers' order.
    pub joints: Vec<(String, JointId)>,
    /// Every moving body, with its name and its parent body (`None`: [`ARS_WORLD`]).
    pub bodies: Vec<(String, ObjectId, Option<ObjectId>)>,
    /// Objects that never move (no body), with their names.
    pub fixed: Vec<(String, ObjectId)>,
}

impl SceneFrames {
    /// The joints and frames of `scene`.
    pub fn of(scene: &Scene) -> Result<SceneFrames> {
        let joints = scene
            .joints()
            .filter(|(_, id)| {
                scene
                    .joint(*id)
                    .is_ok_and(|j| matches!(j.joint_type(), JointType::Hinge | JointType::Slider | JointType::Piston))
            })
            .map(|(name, id)| (name.to_string(), id))
            .collect();
        let mut parent: HashMap<ObjectId, ObjectId> = HashMap::new();
        for (_, id) in scene.joints() {
            let (first, second) = scene.joint(id)?.objects();
            let Some(child) = second else { continue };
            let both_bodies = [first, child].iter().all(|o| scene.object(*o).is_ok_and(|v| v.body_handle().is_some()));
            if both_bodies && !parent.contains_key(&child) && !is_ancestor(&parent, child, first) {
                parent.insert(child, first);
            }
        }
        let mut bodies = Vec::new();
        let mut fixed = Vec::new();
        for (name, id) in scene.objects() {
            if scene.object(id)?.body_handle().is_some() {
                bodies.push((name.to_string(), id, parent.get(&id).copied()));
            } else {
                fixed.push((name.to_string(), id));
            }
        }
        Ok(SceneFrames { joints, bodies, fixed })
    }

    /// `/joint_states` now: position, velocity and effort (what was put on the joint
    /// in the last step: added torques, friction, spring, controller) of every joint.
    pub fn joint_states(&self, scene: &Scene) -> Result<JointState> {
        let mut message = JointState { header: header(scene.time(), ""), ..Default::default() };
        for (name, id) in &self.joints {
            let state = scene.joint_state(*id)?;
            message.name.push(name.clone());
            message.position.push(state.position);
            message.velocity.push(state.rate);
            message.effort.push(scene.joint_efforts(*id)?.total());
        }
        Ok(message)
    }

    /// `/tf` now: every moving body in its parent's frame.
    pub fn tf(&self, scene: &Scene) -> Result<TfMessage> {
        let names: HashMap<ObjectId, &str> = self.bodies.iter().map(|(n, id, _)| (*id, n.as_str())).collect();
        let mut transforms = Vec::with_capacity(self.bodies.len());
        for (name, id, parent) in &self.bodies {
            let pose = scene.pose(*id)?;
            let (frame, relative) = match parent {
                Some(p) => (names.get(p).copied().unwrap_or(ARS_WORLD), scene.pose(*p)?.inverse() * pose),
                None => (ARS_WORLD, pose),
            };
            transforms.push(stamped(scene.time(), frame, name, &relative));
        }
        Ok(TfMessage { transforms })
    }

    /// `/tf_static`: [`ARS_WORLD`] in [`WORLD`], and the objects that never move.
    pub fn tf_static(&self, scene: &Scene) -> Result<TfMessage> {
        let y_up_in_z_up = Isometry3::from_parts(
            Default::default(),
            UnitQuaternion::from_axis_angle(&ars_core::nalgebra::Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
        );
        let mut transforms = vec![stamped(scene.time(), WORLD, ARS_WORLD, &y_up_in_z_up)];
        for (name, id) in &self.fixed {
            transforms.push(stamped(scene.time(), ARS_WORLD, name, &scene.pose(*id)?));
        }
        Ok(TfMessage { transforms })
    }
}

/// Whether `ancestor` is `object` or above it in the tree `parent`.
fn is_ancestor(parent: &HashMap<ObjectId, ObjectId>, ancestor: ObjectId, mut object: ObjectId) -> bool {
    for _ in 0..=parent.len() {
        if object == ancestor {
            return true;
        }
        match parent.get(&object) {
            Some(p) => object = *p,
            None => return false,
        }
    }
    true
}

/// A header stamped with simulated time `time`.
pub fn header(time: f64, frame: &str) -> Header {
    Header { stamp: Time::from_seconds(time), frame_id: frame.to_string() }
}

fn stamped(time: f64, frame: &str, child: &str, pose: &Isometry3<f64>) -> TransformStamped {
    let t = pose.translation.vector;
    let q = pose.rotation.quaternion();
    TransformStamped {
        header: header(time, frame),
        child_frame_id: child.to_string(),
        transform: Transform {
            translation: Vector3 { x: t.x, y: t.y, z: t.z },
            rotation: Quaternion { x: q.i, y: q.j, z: q.k, w: q.w },
        },
    }
}
