//! What a scene keeps of an MJCF model's body tree (a
//! [`RobotDescription`], as of a URDF robot),
//! for those who describe it to others (a ROS bridge's `/tf`): each body's frame on the
//! object that carries it, and which body each hangs from.

use nalgebra::Isometry3;

use super::MjcfModel;
use super::model::{Body, Model};
use crate::formats::urdf::{LinkFrame, RobotDescription, TreeJoint};
use crate::scene::Scene;

/// The body tree of `model`, as `made` put it in `scene` at `world`, before any step.
pub(super) fn body_tree(scene: &Scene, model: &Model, made: &MjcfModel, world: &Isometry3<f64>) -> RobotDescription {
    let mut tree = RobotDescription {
        name: made.name.clone(),
        urdf: None,
        links: Vec::new(),
        joints: Vec::new(),
        roots: Vec::new(),
    };
    for body in &model.bodies {
        add_body(scene, body, None, world, made, &mut tree);
    }
    // Jointless bodies merged into another ride on its object; those welded to the
    // world are static geoms, not links.
    for weld in &made.welded {
        if let (Some(into), Some(object)) = (&weld.into, weld.object) {
            tree.links.push(LinkFrame { name: weld.body.clone(), object, offset: weld.offset });
            let name = format!("{}_weld", weld.body);
            tree.joints.push(TreeJoint { name, parent: into.clone(), child: weld.body.clone(), fixed: true });
        }
    }
    tree
}

/// `body` (at `parent_frame`, under `parent`) and the bodies under it.
fn add_body(
    scene: &Scene,
    body: &Body,
    parent: Option<&str>,
    parent_frame: &Isometry3<f64>,
    made: &MjcfModel,
    tree: &mut RobotDescription,
) {
    let frame = parent_frame * body.frame;
    let object = made.bodies.iter().find(|(n, _)| *n == body.name).map(|(_, id)| *id);
    // Every body made has its pose: the model was just built.
    if let Some((object, pose)) = object.and_then(|o| Some((o, scene.pose(o).ok()?))) {
        let offset = pose.inverse() * frame;
        tree.links.push(LinkFrame { name: body.name.clone(), object, offset });
        match parent {
            Some(parent) => {
                let name = body.joints.last().map_or_else(|| format!("{}_weld", body.name), |j| j.name.clone());
                let fixed = body.joints.is_empty();
                tree.joints.push(TreeJoint { name, parent: parent.to_string(), child: body.name.clone(), fixed });
            }
            None => tree.roots.push(body.name.clone()),
        }
    }
    for child in &body.children {
        add_body(scene, child, Some(&body.name), &frame, made, tree);
    }
}
