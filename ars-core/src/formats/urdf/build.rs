//! Building a URDF robot into a scene: the plan checked first, then its links (merged
//! through fixed joints where they can be), geometry and joints.

use std::collections::HashMap;

use nalgebra::{Isometry3, Point3, Vector3};

use super::frame::{Frame, z_up_to_y_up};
use super::meshes::Meshes;
use super::model;
use super::{UpAxis, UrdfOptions, UrdfRobot};
use crate::body::{BodyBuilder, MassSpec};
use crate::convert::rotation_about_axis;
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{JointId, ObjectId};
use crate::joint::JointBuilder;
use crate::scene::{JointEnd, NewObject, ObjectName, Scene};
use crate::shape::Shape;

/// A problem with a link (the file and the line are named by the caller).
pub(super) fn link_error(link: &model::Link, problem: String) -> Error {
    Error::Format {
        format: "URDF",
        file: String::new(),
        element: format!("link {:?}", link.name),
        line: None,
        column: None,
        problem,
    }
}

/// A robot checked before anything is built.
#[derive(Clone)]
pub(super) struct Plan<'r> {
    robot: &'r model::Robot,
    /// Index of the root link.
    root: usize,
    /// World frame of each link (at zero joint positions).
    link_frames: Vec<Frame>,
    /// World frame of each joint.
    joint_frames: Vec<Frame>,
    /// World frame of each link at the joints' start positions, if any is not 0.
    posed_link_frames: Option<Vec<Frame>>,
    /// Each joint's start position (see [`start_positions`](super::stops::start_positions)).
    start: Vec<f64>,
    /// A line for [`UrdfRobot::adjusted`] for each joint that does not start where
    /// the file and the options say.
    start_notes: Vec<String>,
}

impl Plan<'_> {
    /// The plan with every frame `height` higher (+Y): the robot built there.
    fn raised(&self, height: f64) -> Self {
        let up = |frames: &[Frame]| -> Vec<Frame> {
            frames.iter().map(|f| Frame { translation: f.translation + Vector3::y() * height, ..*f }).collect()
        };
        Plan {
            link_frames: up(&self.link_frames),
            joint_frames: up(&self.joint_frames),
            posed_link_frames: self.posed_link_frames.as_deref().map(up),
            ..self.clone()
        }
    }
}

impl Scene {
    /// Builds the planned robot: its links (a massless link fixed to its parent merged
    /// into it), joints, mimics, fixed base and initial pose. On an error, what was made
    /// is removed and the error names its element.
    // The element with the error: internal, and only on the error path, so its size
    // costs nothing on a robot that loads.
    #[allow(clippy::result_large_err)]
    pub(super) fn build_urdf(
        &mut self,
        plan: &Plan<'_>,
        options: &UrdfOptions,
        meshes: &mut Meshes<'_>,
    ) -> std::result::Result<UrdfRobot, (String, Error)> {
        let start = plan.posed_link_frames.as_ref().unwrap_or(&plan.link_frames);
        let raise = self.floor_raise(plan.robot, plan.root, start, options, meshes);
        let raised = raise.as_ref().map(|r| plan.raised(r.height));
        let mut created = Vec::new();
        let mut built = self.build_urdf_parts(raised.as_ref().unwrap_or(plan), options, meshes, &mut created);
        match &mut built {
            Err(_) => {
                for (id, _) in created.iter().rev() {
                    let _ = self.remove_object_with_joints(*id);
                }
            }
            Ok(robot) => robot.adjusted.extend(raise.map(|r| r.note(&robot.name))),
        }
        built
    }

    /// A category bit no other robot of this scene uses (1 to 62; 63 is everything else).
    pub(super) fn next_robot_bit(&mut self) -> u64 {
        self.robots_loaded = (self.robots_loaded % 62) + 1;
        1u64 << self.robots_loaded
    }

    /// Makes a link that is not merged into another: a body at its inertial frame, or
    /// static geometry for a massless root; with its geoms and visuals.
    pub(super) fn add_link(
        &mut self,
        robot: &model::Robot,
        link: &model::Link,
        frame: &Frame,
        root: bool,
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
    ) -> Result<MadeLink> {
        let (collisions, looks) = link_geometry(robot, link, frame, meshes)?;
        let mass = link.inertial.mass.value;
        // A link without collision geometry is drawn as a small sphere and collides with nothing.
        let drawn = collisions.first().map_or(Shape::Sphere { radius: 1e-3 }, |(shape, _)| shape.clone());
        if mass == 0.0 && root {
            return self.add_static_link(link, collisions, &looks, drawn, bits);
        }
        if mass.is_nan() || mass <= 0.0 {
            return Err(link_error(
                link,
                format!(
                    "mass {mass}: a moving link needs a positive mass, and no link of the robot has one to lend it \
                     (a massless link is merged into its parent only when a fixed joint holds it)"
                ),
            ));
        }
        self.add_link_body(link, frame, collisions, &looks, drawn, bits)
    }

    /// A massless root link: static, its geometry collides and nothing moves it.
    fn add_static_link(
        &mut self,
        link: &model::Link,
        collisions: Vec<(Shape, Frame)>,
        looks: &[Look],
        drawn: Shape,
        bits: Option<u64>,
    ) -> Result<MadeLink> {
        let geoms = collisions
            .into_iter()
            .map(|(shape, at)| with_robot_bits(GeomBuilder::new(shape).pose(at.isometry()), bits))
            .collect();
        let id = self.insert_object(NewObject::with_geoms(ObjectName::Unique(&link.name), drawn, None, geoms))?;
        let object_pose = self.pose(id).unwrap_or_else(|_| Isometry3::identity());
        self.set_visuals(id, visuals_of(looks, object_pose))?;
        Ok((id, None))
    }

    /// A moving link: its body at its inertial frame (`frame` is the link's), its geoms
    /// on it.
    fn add_link_body(
        &mut self,
        link: &model::Link,
        frame: &Frame,
        collisions: Vec<(Shape, Frame)>,
        looks: &[Look],
        drawn: Shape,
        bits: Option<u64>,
    ) -> Result<MadeLink> {
        let mass = link.inertial.mass.value;
        let inertial = frame.then(&Frame::from_pose(&link.inertial.origin));
        let i = &link.inertial.inertia;
        let inertia = crate::formats::inertia_tensor([i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz]);
        let spec = MassSpec::Custom { mass, inertia };
        let mut builder = BodyBuilder::new().mass(spec).position(Point3::from(inertial.translation));
        if inertial.rotation.is_some() {
            builder = builder.rotation(inertial.rotation3());
        }
        let body = self.world_mut().insert_body(builder)?;
        let geoms = collisions
            .into_iter()
            .map(|(shape, at)| {
                let g = GeomBuilder::new(shape).attached_to(body);
                let g = if at.same_as(&inertial) { g } else { g.offset(inertial.relative(&at)) };
                with_robot_bits(g, bits)
            })
            .collect();
        let id = self.insert_object(NewObject::with_geoms(ObjectName::Unique(&link.name), drawn, Some(body), geoms))?;
        self.set_visuals(id, visuals_of(looks, inertial.isometry()))?;
        Ok((id, Some(body)))
    }

    /// Adds a merged link's geometry and looks to its host's object: geoms on the host's
    /// body (static with a static host), visuals relative to the host object's pose.
    /// `host_frame` is the host body's frame (its inertial frame), or the static host
    /// link's frame.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn merge_link(
        &mut self,
        robot: &model::Robot,
        link: &model::Link,
        frame: &Frame,
        (host, body): (ObjectId, Option<crate::handle::BodyHandle>),
        host_frame: &Frame,
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
    ) -> Result<()> {
        let (collisions, looks) = link_geometry(robot, link, frame, meshes)?;
        let geoms = collisions
            .into_iter()
            .map(|(shape, at)| {
                let g = GeomBuilder::new(shape);
                let g = match body {
                    Some(body) => g.attached_to(body).offset(host_frame.relative(&at)),
                    None => g.pose(at.isometry()),
                };
                with_robot_bits(g, bits)
            })
            .collect();
        self.attach_geoms(host, geoms)?;
        if !looks.is_empty() {
            let host_pose = match body {
                Some(_) => host_frame.isometry(),
                None => self.pose(host).unwrap_or_else(|_| Isometry3::identity()),
            };
            let to_host = host_pose.inverse();
            let mut visuals = self.object(host)?.visuals().to_vec();
            visuals.extend(looks.into_iter().map(|(shape, at, color)| crate::scene::Visual {
                shape,
                offset: to_host * at,
                color,
            }));
            self.set_visuals(host, visuals)?;
        }
        Ok(())
    }

    /// Makes a URDF joint at `frame` (world), its stops around where it starts
    /// (`start`, its position).
    pub(super) fn add_urdf_joint(
        &mut self,
        joint: &model::Joint,
        (frame, start): (&Frame, f64),
        child: (ObjectId, Option<crate::handle::BodyHandle>),
        parent: (ObjectId, Option<crate::handle::BodyHandle>),
    ) -> Result<JointId> {
        let anchor = Point3::from(frame.translation);
        let axis = frame.rotate(&Vector3::from(joint.axis.xyz.0));
        // ODE measures a hinge's angle (a slider's position) as body 1 relative to body
        // 2 about (along) the axis; URDF as the child relative to the parent. Between
        // two bodies: parent first, about the negated axis, so that ODE's angle is the
        // URDF position and a positive effort turns the child positively.
        let (object1, object2, axis) = match (child, parent) {
            ((c, Some(_)), (p, Some(_))) => (p, JointEnd::Object(c), -axis),
            ((c, Some(_)), (_, None)) => (c, JointEnd::World, axis),
            ((_, None), _) => {
                return Err(Error::Invalid { what: "the joint's child link", problem: "has no mass".into() });
            }
        };
        use model::JointType as U;
        let (kind, builder) = match joint.joint_type {
            U::Revolute | U::Continuous => (crate::scene::JointType::Hinge, JointBuilder::hinge(anchor, axis)),
            U::Prismatic => (crate::scene::JointType::Slider, JointBuilder::slider(axis)),
            U::Fixed => (crate::scene::JointType::Fixed, JointBuilder::fixed()),
            U::Spherical => (crate::scene::JointType::Ball, JointBuilder::ball(anchor)),
            _ => unreachable!("refused when planned"),
        };
        let id = self.insert_sim_joint(&joint.name, kind, object1, object2, builder)?;
        if let Some((low, high)) = super::stops::joint_stops(joint, start) {
            self.joint_mut(id)?.set_limits(low, high)?;
        }
        let moving = matches!(joint.joint_type, U::Revolute | U::Continuous | U::Prismatic);
        if let Some(d) = &joint.dynamics
            && moving
        {
            if d.damping > 0.0 {
                self.joint_mut(id)?.set_viscous_friction(d.damping)?;
            }
            if d.friction > 0.0 {
                self.joint_mut(id)?.set_dry_friction(d.friction)?;
            }
        }
        // URDF requires effort and velocity on revolute and prismatic joints; a 0 (or
        // an absent <limit>, for continuous joints) reads as no limit, as in pybullet.
        let positive_or_none = |x: f64| if x > 0.0 { x } else { f64::INFINITY };
        let (effort, velocity) = (positive_or_none(joint.limit.effort), positive_or_none(joint.limit.velocity));
        if moving && (effort.is_finite() || velocity.is_finite()) {
            self.joint_mut(id)?.set_actuator_limits(crate::scene::ActuatorLimits { effort, velocity })?;
        }
        Ok(id)
    }
}

// The build's steps: each error names its element (internal, and only on the error
// path, so its size costs nothing on a robot that loads).
#[allow(clippy::result_large_err)]
impl Scene {
    /// [`build_urdf`](Self::build_urdf) without the removal on an error: the links made
    /// themselves go in `created`, as they are made.
    fn build_urdf_parts(
        &mut self,
        plan: &Plan<'_>,
        options: &UrdfOptions,
        meshes: &mut Meshes<'_>,
        created: &mut Vec<MadeLink>,
    ) -> std::result::Result<UrdfRobot, (String, Error)> {
        let robot = plan.robot;
        // Self-collision off: the robot's geoms share one category they do not collide with.
        let bits = if options.self_collision { None } else { Some(self.next_robot_bit()) };
        let hosts = merge_hosts(robot, plan.root);
        let mut made = self.make_urdf_links(plan, &hosts, bits, meshes, created)?;
        self.merge_urdf_links(plan, &hosts, &mut made, bits, meshes)?;
        let made: Vec<MadeLink> = made.into_iter().map(|m| m.expect("every link is made or merged")).collect();
        let links = robot.links.iter().zip(&made).map(|(link, (id, _))| (link.name.clone(), *id)).collect();
        let joints = self.make_urdf_joints(plan, &hosts, &made)?;
        self.set_urdf_mimics(robot, &joints)?;
        let base_joint = self.fix_urdf_base(plan, options, &made)?;
        if let Some(posed) = &plan.posed_link_frames {
            self.pose_urdf_links(robot, posed, &hosts, &made)?;
        }
        let mut adjusted = plan.start_notes.clone();
        adjusted.extend(super::stops::stop_notes(robot, &plan.start));
        let frames = plan.posed_link_frames.as_ref().unwrap_or(&plan.link_frames);
        let link_offsets = made
            .iter()
            .zip(frames)
            .map(|((id, _), frame)| Ok(self.pose(*id)?.inverse() * frame.isometry()))
            .collect::<Result<_>>()
            .map_err(|e| ("robot".to_string(), e))?;
        Ok(UrdfRobot { name: robot.name.clone(), links, joints, base_joint, link_offsets, adjusted })
    }

    /// Makes the links that are not merged into another, with their colours; each link
    /// made goes in `created` and at its index in the result.
    fn make_urdf_links(
        &mut self,
        plan: &Plan<'_>,
        hosts: &[Option<usize>],
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
        created: &mut Vec<MadeLink>,
    ) -> std::result::Result<Vec<Option<MadeLink>>, (String, Error)> {
        let robot = plan.robot;
        let mut made = vec![None; robot.links.len()];
        for (i, link) in robot.links.iter().enumerate() {
            if hosts[i].is_some() {
                continue;
            }
            let result = self.add_link(robot, link, &plan.link_frames[i], i == plan.root, bits, meshes);
            let made_link = result
                .and_then(|(id, body)| {
                    if let Some(color) = link_color(robot, link) {
                        self.set_color(id, color)?;
                    }
                    Ok((id, body))
                })
                .map_err(|e| (link_element(&link.name), e))?;
            created.push(made_link);
            made[i] = Some(made_link);
        }
        Ok(made)
    }

    /// Merges each massless link fixed to its parent into its host (made by now): the
    /// link's index in `made` gets the host's object.
    fn merge_urdf_links(
        &mut self,
        plan: &Plan<'_>,
        hosts: &[Option<usize>],
        made: &mut [Option<MadeLink>],
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
    ) -> std::result::Result<(), (String, Error)> {
        let robot = plan.robot;
        for (i, link) in robot.links.iter().enumerate() {
            let Some(host) = hosts[i] else { continue };
            let host_made = made[host].expect("a host is made in the first pass");
            let host_frame = match host_made.1 {
                Some(_) => plan.link_frames[host].then(&Frame::from_pose(&robot.links[host].inertial.origin)),
                None => plan.link_frames[host],
            };
            self.merge_link(robot, link, &plan.link_frames[i], host_made, &host_frame, bits, meshes)
                .map_err(|e| (link_element(&link.name), e))?;
            made[i] = Some(host_made);
        }
        Ok(())
    }

    /// Makes the joints (not those of merged links), by name.
    fn make_urdf_joints(
        &mut self,
        plan: &Plan<'_>,
        hosts: &[Option<usize>],
        made: &[MadeLink],
    ) -> std::result::Result<Vec<(String, JointId)>, (String, Error)> {
        let robot = plan.robot;
        let mut joints = Vec::new();
        for (j, joint) in robot.joints.iter().enumerate() {
            let parent = robot.links.iter().position(|l| l.name == joint.parent.link).expect("checked");
            let child = robot.links.iter().position(|l| l.name == joint.child.link).expect("checked");
            if hosts[child].is_some() {
                continue; // merged: its link is part of its parent's body
            }
            let id = self
                .add_urdf_joint(joint, (&plan.joint_frames[j], plan.start[j]), made[child], made[parent])
                .map_err(|e| (format!("joint {:?}", joint.name), e))?;
            joints.push((joint.name.clone(), id));
        }
        Ok(joints)
    }

    /// Makes each joint with a `<mimic>` follow its leader (`joints`: the joints made,
    /// by name).
    fn set_urdf_mimics(
        &mut self,
        robot: &model::Robot,
        joints: &[(String, JointId)],
    ) -> std::result::Result<(), (String, Error)> {
        for joint in &robot.joints {
            let Some(mimic) = &joint.mimic else { continue };
            let find = |name: &str| joints.iter().find(|(n, _)| n == name).map(|(_, id)| *id).expect("checked");
            let (follower, leader) = (find(&joint.name), find(&mimic.joint));
            let (multiplier, offset) = (mimic.multiplier.unwrap_or(1.0), mimic.offset.unwrap_or(0.0));
            self.joint_mut(follower)
                .and_then(|mut j| j.set_mimic(leader, multiplier, offset))
                .map_err(|e| (format!("joint {:?}", joint.name), e))?;
        }
        Ok(())
    }

    /// With a fixed base, the joint that holds the root link (when it has a body) to
    /// the world.
    fn fix_urdf_base(
        &mut self,
        plan: &Plan<'_>,
        options: &UrdfOptions,
        made: &[MadeLink],
    ) -> std::result::Result<Option<JointId>, (String, Error)> {
        match (options.fixed_base, made[plan.root]) {
            (true, (root, Some(_))) => {
                let name = format!("{}/base", plan.robot.name);
                let fixed = crate::scene::JointType::Fixed;
                match self.insert_sim_joint(&name, fixed, root, JointEnd::World, JointBuilder::fixed()) {
                    Ok(id) => Ok(Some(id)),
                    Err(e) => Err(("robot".into(), e)),
                }
            }
            _ => Ok(None),
        }
    }

    /// Moves the bodies of the links made themselves to their frames at the initial
    /// joint positions (`posed`, the links' frames).
    fn pose_urdf_links(
        &mut self,
        robot: &model::Robot,
        posed: &[Frame],
        hosts: &[Option<usize>],
        made: &[MadeLink],
    ) -> std::result::Result<(), (String, Error)> {
        for (i, link) in robot.links.iter().enumerate() {
            let Some(body) = made[i].1.filter(|_| hosts[i].is_none()) else { continue };
            let at = posed[i].then(&Frame::from_pose(&link.inertial.origin));
            self.world_mut()
                .body_mut(body)
                .and_then(|mut b| {
                    b.set_position(Point3::from(at.translation))?;
                    b.set_rotation(at.rotation3())
                })
                .map_err(|e| (link_element(&link.name), e))?;
        }
        Ok(())
    }
}

/// A link as made: its object, and its body (`None`: static).
type MadeLink = (ObjectId, Option<crate::handle::BodyHandle>);

/// What a link looks like: a visual's shape, world pose and colour.
type Look = (Shape, Isometry3<f64>, Option<crate::scene::Color>);

/// How an error names a link.
fn link_element(name: &str) -> String {
    format!("link {name:?}")
}

/// A geom in the robot's own category, colliding with everything else, when
/// self-collision is off (`bits`, that category).
fn with_robot_bits(g: GeomBuilder, bits: Option<u64>) -> GeomBuilder {
    match bits {
        Some(b) => g.category_bits(b).collide_bits(!b),
        None => g,
    }
}

/// Looks as the visuals of an object at `object_pose`.
fn visuals_of(looks: &[Look], object_pose: Isometry3<f64>) -> Vec<crate::scene::Visual> {
    let to_object = object_pose.inverse();
    looks
        .iter()
        .map(|(shape, at, color)| crate::scene::Visual { shape: shape.clone(), offset: to_object * at, color: *color })
        .collect()
}

/// A link's collision shapes with their world frames, and its looks (shape, world
/// pose, colour) unless visuals are ignored.
#[allow(clippy::type_complexity)]
pub(super) fn link_geometry(
    robot: &model::Robot,
    link: &model::Link,
    frame: &Frame,
    meshes: &mut Meshes<'_>,
) -> Result<(Vec<(Shape, Frame)>, Vec<(Shape, Isometry3<f64>, Option<crate::scene::Color>)>)> {
    let urdf_err = |problem: String| link_error(link, problem);
    let mut collisions = Vec::new();
    for c in &link.collision {
        if let Some(missing) = meshes.missing(&c.geometry) {
            // PyBullet loads the link without it; so does ARS, saying so.
            meshes.notes.push(format!("link {:?}: a <collision> is skipped: {missing}", link.name));
            continue;
        }
        let mut shape = meshes.shape(&c.geometry).map_err(urdf_err)?;
        if let (Shape::TriMesh { vertices, .. }, false) = (&shape, meshes.options.triangle_mesh_collisions) {
            // Collided as its convex hull, as PyBullet does; one that bounds no solid
            // stays a triangle mesh.
            match Shape::convex_hull(vertices) {
                Ok(hull) => shape = hull,
                Err(e) => {
                    meshes.notes.push(format!("link {:?}: a collision mesh stays a triangle mesh: {e}", link.name))
                }
            }
        }
        collisions.push((shape, frame.then(&Frame::from_pose(&c.origin))));
    }
    let mut looks = Vec::new();
    if !meshes.options.ignore_visuals {
        for v in &link.visual {
            let shape = meshes.shape(&v.geometry).map_err(|problem| {
                urdf_err(format!(
                    "{problem} (a <visual>: UrdfOptions::ignore_visuals draws the collision geometry instead)"
                ))
            })?;
            // Checked before anything is created, so that setting them cannot fail.
            shape.validate().map_err(|e| urdf_err(format!("a <visual>: {e}")))?;
            let color = v.material.as_ref().and_then(|m| material_color(robot, m));
            looks.push((shape, frame.then(&Frame::from_pose(&v.origin)).isometry(), color));
        }
    }
    Ok((collisions, looks))
}

/// For each link, the link it is merged into: a massless link fixed to its parent goes
/// into the nearest ancestor that is not such a link (`None`: it is made itself).
pub(super) fn merge_hosts(robot: &model::Robot, root: usize) -> Vec<Option<usize>> {
    let index: HashMap<&str, usize> = robot.links.iter().enumerate().map(|(i, l)| (l.name.as_str(), i)).collect();
    let mut parent: Vec<Option<(usize, bool)>> = vec![None; robot.links.len()];
    for joint in &robot.joints {
        let fixed = matches!(joint.joint_type, model::JointType::Fixed);
        parent[index[joint.child.link.as_str()]] = Some((index[joint.parent.link.as_str()], fixed));
    }
    let merged = |i: usize| i != root && robot.links[i].inertial.mass.value == 0.0 && parent[i].is_some_and(|p| p.1);
    (0..robot.links.len())
        .map(|i| {
            let mut host = i;
            // The tree has no loop (checked): this walk ends at the root at the latest.
            while merged(host) {
                host = parent[host].expect("merged links have a parent").0;
            }
            (host != i).then_some(host)
        })
        .collect()
}

/// The world frame of every link and of every joint, from the root outwards, with the
/// joints at positions `q` (at zero when `None`: then no motion is composed at all, so
/// the frames are the file's numbers exactly).
pub(super) fn frames(
    robot: &model::Robot,
    link_index: &HashMap<&str, usize>,
    root: usize,
    root_frame: Frame,
    q: Option<&[f64]>,
) -> (Vec<Frame>, Vec<Frame>) {
    let mut links: Vec<Option<Frame>> = vec![None; robot.links.len()];
    let mut joints = vec![Frame::IDENTITY; robot.joints.len()];
    links[root] = Some(root_frame);
    let mut queue = vec![root];
    while let Some(parent) = queue.pop() {
        let parent_frame = links[parent].expect("set before queued");
        for (j, joint) in robot.joints.iter().enumerate() {
            if joint.parent.link != robot.links[parent].name {
                continue;
            }
            let child = link_index[joint.child.link.as_str()];
            let frame = parent_frame.then(&Frame::from_pose(&joint.origin));
            joints[j] = frame;
            let position = q.map_or(0.0, |q| q[j]);
            let axis = Vector3::from(joint.axis.xyz.0).normalize();
            links[child] = Some(match joint.joint_type {
                _ if position == 0.0 => frame,
                model::JointType::Prismatic => frame.then(&Frame { rotation: None, translation: axis * position }),
                model::JointType::Spherical | model::JointType::Fixed => frame,
                _ => frame.then(&Frame {
                    rotation: Some(*rotation_about_axis(&axis, position).matrix()),
                    translation: Vector3::zeros(),
                }),
            });
            queue.push(child);
        }
    }
    (links.into_iter().map(|f| f.expect("a tree reaches every link")).collect(), joints)
}

/// The colour of a link's first visual with a material: its own `<color>`, or that of
/// the robot-level material it names (URDF allows both).
pub(super) fn link_color(robot: &model::Robot, link: &model::Link) -> Option<crate::scene::Color> {
    link.visual.iter().filter_map(|v| v.material.as_ref()).find_map(|m| material_color(robot, m))
}

/// A material's colour: its own `<color>`, or that of the robot-level material it names.
pub(super) fn material_color(robot: &model::Robot, m: &model::Material) -> Option<crate::scene::Color> {
    let rgba = match &m.color {
        Some(c) => c.rgba.0,
        None => robot.materials.iter().find(|r| r.name == m.name)?.color.as_ref()?.rgba.0,
    };
    Some([rgba[0], rgba[1], rgba[2]].map(|c| c.clamp(0.0, 1.0) as f32))
}

/// Checks the tree (names, parents, one root, no loop, supported joints) and computes
/// every frame.
pub(super) fn plan<'r>(
    robot: &'r model::Robot,
    options: &UrdfOptions,
) -> std::result::Result<Plan<'r>, (String, String)> {
    let mut link_index = HashMap::new();
    for (i, link) in robot.links.iter().enumerate() {
        if link_index.insert(link.name.as_str(), i).is_some() {
            return Err((format!("link {:?}", link.name), "two links have this name".into()));
        }
    }
    if robot.links.is_empty() {
        return Err(("robot".into(), "it has no link".into()));
    }
    let (joint_names, parent_joint) = check_joints(robot, &link_index)?;
    let root = root_link(robot, &parent_joint)?;
    check_hung_from_root(robot, &link_index, &parent_joint)?;
    for link in &robot.links {
        let element = format!("link {:?}", link.name);
        let m = link.inertial.mass.value;
        if !m.is_finite() || m < 0.0 {
            return Err((element, format!("mass {m}: must be positive")));
        }
    }
    // Frames, from the root outwards.
    let base = Frame::from_isometry(&options.base_pose);
    let root_frame = match options.up_axis {
        UpAxis::Z => base.then(&z_up_to_y_up()),
        UpAxis::Y => base,
    };
    let (link_frames, joint_frames) = frames(robot, &link_index, root, root_frame, None);
    let given = initial_positions(robot, options, &joint_names)?;
    let (start, start_notes) = super::stops::start_positions(robot, &given);
    let posed_link_frames =
        start.iter().any(|&q| q != 0.0).then(|| frames(robot, &link_index, root, root_frame, Some(&start)).0);
    Ok(Plan { robot, root, link_frames, joint_frames, posed_link_frames, start, start_notes })
}

/// Checks every joint (a name of its own, links in the file, a link's only parent
/// joint, a type ARS loads, its mimic's leader, its axis): the joints' indices by name,
/// and each link's parent joint (`None`: the root).
#[allow(clippy::type_complexity)]
fn check_joints<'r>(
    robot: &'r model::Robot,
    link_index: &HashMap<&str, usize>,
) -> std::result::Result<(HashMap<&'r str, usize>, Vec<Option<usize>>), (String, String)> {
    let mut joint_names = HashMap::new();
    let mut parent_joint = vec![None; robot.links.len()];
    for (j, joint) in robot.joints.iter().enumerate() {
        let element = format!("joint {:?}", joint.name);
        if joint_names.insert(joint.name.as_str(), j).is_some() {
            return Err((element, "two joints have this name".into()));
        }
        let Some(&parent) = link_index.get(joint.parent.link.as_str()) else {
            return Err((element, format!("its parent link {:?} is not in the file", joint.parent.link)));
        };
        let Some(&child) = link_index.get(joint.child.link.as_str()) else {
            return Err((element, format!("its child link {:?} is not in the file", joint.child.link)));
        };
        if parent == child {
            return Err((element, format!("link {:?} is both its parent and its child", joint.parent.link)));
        }
        if let Some(other) = parent_joint[child] {
            let other: &model::Joint = &robot.joints[other];
            return Err((
                element,
                format!("link {:?} is already the child of joint {:?}: a loop", joint.child.link, other.name),
            ));
        }
        parent_joint[child] = Some(j);
        check_joint_kind(robot, joint).map_err(|problem| (element, problem))?;
    }
    Ok((joint_names, parent_joint))
}

/// Checks a joint's type (one ARS loads), its mimic's leader (in the file) and its axis
/// (a direction, but for fixed and spherical joints).
fn check_joint_kind(robot: &model::Robot, joint: &model::Joint) -> std::result::Result<(), String> {
    use model::JointType as U;
    match joint.joint_type {
        U::Revolute | U::Continuous | U::Prismatic | U::Fixed | U::Spherical => {}
        ref other => {
            return Err(format!(
                "type {other:?}: ARS loads revolute, continuous, prismatic, fixed and spherical joints"
            ));
        }
    }
    if let Some(mimic) = &joint.mimic
        && !robot.joints.iter().any(|j| j.name == mimic.joint)
    {
        return Err(format!("<mimic> names joint {:?}, which is not in the file", mimic.joint));
    }
    let axis = Vector3::from(joint.axis.xyz.0);
    let directed = axis.iter().all(|x| x.is_finite()) && axis.norm() > 1e-9;
    if !matches!(joint.joint_type, U::Fixed | U::Spherical) && !directed {
        return Err(format!("axis {:?} has no direction", joint.axis.xyz.0));
    }
    Ok(())
}

/// Every link hangs from the root: the walk up from it, joint by joint, ends (at the
/// one root). A loop of links apart from the root passes the checks of one root and one
/// parent a link: it never ends.
fn check_hung_from_root(
    robot: &model::Robot,
    link_index: &HashMap<&str, usize>,
    parent_joint: &[Option<usize>],
) -> std::result::Result<(), (String, String)> {
    // Each link walked up once in all (linear in the links however deep the tree):
    // `hung` marks the links known to reach the root, `walk` the walk under way.
    let (mut hung, mut walk) = (vec![false; robot.links.len()], vec![usize::MAX; robot.links.len()]);
    let mut path = Vec::new();
    for (start, link) in robot.links.iter().enumerate() {
        path.clear();
        let mut at = start;
        while !hung[at] {
            if walk[at] == start {
                return Err((
                    format!("link {:?}", link.name),
                    "its joints form a loop that does not reach the root link: one tree is needed".into(),
                ));
            }
            walk[at] = start;
            path.push(at);
            match parent_joint[at] {
                Some(j) => at = link_index[robot.joints[j].parent.link.as_str()],
                None => break, // the root
            }
        }
        for &l in &path {
            hung[l] = true;
        }
    }
    Ok(())
}

/// The root: the one link that is no joint's child.
fn root_link(robot: &model::Robot, parent_joint: &[Option<usize>]) -> std::result::Result<usize, (String, String)> {
    let roots: Vec<usize> = (0..robot.links.len()).filter(|&i| parent_joint[i].is_none()).collect();
    match roots[..] {
        [root] => Ok(root),
        [] => Err(("robot".into(), "every link has a parent: the joints form a loop".into())),
        _ => {
            let names: Vec<&str> = roots.iter().map(|&i| robot.links[i].name.as_str()).collect();
            Err(("robot".into(), format!("several root links ({}): one tree is needed", names.join(", "))))
        }
    }
}

/// The joint positions the options give (`None` for the others), each checked: a
/// moving joint of the file, a finite value.
fn initial_positions(
    robot: &model::Robot,
    options: &UrdfOptions,
    joint_names: &HashMap<&str, usize>,
) -> std::result::Result<Vec<Option<f64>>, (String, String)> {
    let mut q = vec![None; robot.joints.len()];
    for (name, value) in &options.initial_positions {
        let element = format!("joint {name:?}");
        let Some(&j) = joint_names.get(name.as_str()) else {
            return Err((element, "an initial position is given, but the file has no such joint".into()));
        };
        let fixed = matches!(robot.joints[j].joint_type, model::JointType::Fixed | model::JointType::Spherical);
        if fixed || !value.is_finite() {
            return Err((element, format!("initial position {value}: needs a moving joint and a finite value")));
        }
        q[j] = Some(*value);
    }
    Ok(q)
}
