//! An MJCF body's several joints made as one joint group
//! ([`Scene::add_joint_group`](crate::Scene::add_joint_group)): a humanoid's hip (three
//! hinges at one point), a shoulder (two), a planar walker's root (two slides and a
//! hinge), a point mass (two slides). MuJoCo moves such a body in as many coordinates
//! as it has joints; a group holds it with a row for each freedom it locks, where a
//! chain of ODE joints through light links takes five rows a joint, a body a link, and
//! the links' mass, which the file does not have.
//!
//! A body's joints that a group cannot take stay a chain (`build.rs`): hinges through
//! different points or about axes that are not perpendicular, a slide after a hinge,
//! slides of a body that is not the world's child, and a planar body's slides with an
//! armature, damping or dry friction (ODE's linear motor would hold the body's centre,
//! not the point the slide moves).

use nalgebra::{Isometry3, Point3};

use super::model::{Body, JointKind};
use crate::scene::{GroupJoint, JointType};

/// The group `body`'s joints make, at the body's world `frame`, if they make one; the
/// body's parent is the world when `of_world`.
pub(super) fn group_of(body: &Body, frame: &Isometry3<f64>, of_world: bool) -> Option<Vec<GroupJoint>> {
    let joints = &body.joints;
    if joints.len() < 2 {
        return None;
    }
    if joints.iter().any(|j| !matches!(j.kind, JointKind::Hinge | JointKind::Slide)) {
        return None;
    }
    // A planar body's slides take no motor (`Scene::check_member_motor`): such slides
    // stay a chain. What else a group takes, `fits` says.
    let slides = joints.iter().take_while(|j| j.kind == JointKind::Slide).count();
    let held = |j: &super::model::Joint| j.armature > 0.0 || j.damping > 0.0 || j.frictionloss > 0.0;
    if slides < joints.len() && joints[..slides].iter().any(held) {
        return None;
    }
    let group: Vec<GroupJoint> = joints
        .iter()
        .map(|j| GroupJoint {
            name: j.name.clone(),
            kind: if j.kind == JointKind::Slide { JointType::Slider } else { JointType::Hinge },
            anchor: frame * Point3::from(j.pos),
            axis: frame.rotation * j.axis,
            reference: j.reference,
        })
        .collect();
    crate::scene::joint_group::fits(&group, !of_world).then_some(group)
}
