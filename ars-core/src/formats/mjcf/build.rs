//! Building a read model in a scene: objects, joints, actuators, contact pairs and
//! exclusions, placed at the model's base pose.

use std::collections::HashMap;

use nalgebra::{Isometry3, Matrix3, Translation3, Unit, UnitQuaternion, Vector3};

use super::damper::Resisting;
use super::mass::{armature_inertia, at_least_ars_least_mass, find_body};
use super::model::{Body, Geom, GeomKind, Joint, JointKind, Model, Pair};
use super::read::read;
use super::{CHAIN_LINK_FRACTION, MjcfMocap, MjcfModel, MjcfOptions, MjcfWeld};
use crate::body::{BodyBuilder, MassSpec};
use crate::error::{Error, Result};
use crate::formats::balance::balance_inertia;
use crate::geom::GeomBuilder;
use crate::handle::{BodyHandle, GeomHandle, JointId, ObjectId};
use crate::scene::JointEnd;
use crate::scene::{NewObject, ObjectName, Scene, Visual};
use crate::shape::Shape;
use crate::world::joint::JointParam;

/// MuJoCo (x, y, z) → simulation (x, z, −y), then the base pose.
pub(super) fn placement(options: &MjcfOptions) -> Isometry3<f64> {
    let turn = UnitQuaternion::from_rotation_matrix(&crate::formats::z_up_to_y_up());
    options.base_pose * Isometry3::from_parts(Translation3::identity(), turn)
}

/// The model of an MJCF file's text (`file` names it in errors), read as `options`
/// say (`skip_unsupported`).
pub(super) fn read_mjcf(text: &str, file: &str, options: &MjcfOptions) -> Result<Model> {
    read(file, text, options).map_err(|p| Error::Format {
        format: "MJCF",
        file: p.file.unwrap_or_else(|| file.to_string()),
        element: format!("<{}>", p.element),
        line: Some(p.line),
        column: None,
        problem: p.text,
    })
}

impl Scene {
    /// Makes the bodies, joints and actuators of a read MJCF model, not its sensors (a
    /// scene has none), at `options.base_pose`.
    pub(super) fn insert_mjcf_model(&mut self, model: &Model, options: &MjcfOptions) -> Result<MjcfModel> {
        let prefixed;
        let model = if options.prefix.is_empty() {
            model
        } else {
            let mut copy = model.clone();
            super::prefix::prefix_names(&mut copy, &options.prefix);
            prefixed = copy;
            &prefixed
        };
        // Built in one go; on an error everything made so far is removed.
        let mut made = MjcfModel {
            name: model.name.clone(),
            timestep: model.timestep,
            gravity: model.gravity.map(|g| placement(options).rotation * g),
            magnetic: placement(options).rotation * model.magnetic,
            actuators: model.actuators.clone(),
            keyframes: model.keyframes.clone(),
            skipped: model.skipped.clone(),
            ..MjcfModel::default()
        };
        let built = self.build_mjcf(model, options, &mut made);
        if let Err(e) = built {
            let ids: Vec<ObjectId> = made
                .bodies
                .iter()
                .map(|(_, id)| *id)
                .chain(made.chain_links.iter().copied())
                .chain(made.world_geoms.iter().copied())
                .collect();
            for (_, motor) in made.joint_motors.iter().rev() {
                let _ = self.world_mut().remove_joint(*motor);
            }
            for id in ids.into_iter().rev() {
                // Its joints go with it; what was made is removed whatever the error.
                let _ = self.remove_object_with_joints(id);
            }
            return Err(e);
        }
        self.robot_descriptions.push(super::tree::body_tree(self, model, &made, &placement(options)));
        self.mocap_bodies.extend(made.mocap.iter().cloned());
        Ok(made)
    }

    pub(super) fn build_mjcf(&mut self, model: &Model, options: &MjcfOptions, made: &mut MjcfModel) -> Result<()> {
        let world = placement(options);
        // Geoms by name, for `<contact><pair>`.
        let mut named = HashMap::new();
        for body in &model.bodies {
            self.add_mjcf_body(body, &world, None, made, &mut named)?;
        }
        // The world's geoms after the bodies: unnamed, they are named by their shape
        // (`box`, `sphere`...), and so would take a body's name of the file.
        for g in &model.world_geoms {
            let pose = world * g.frame;
            let id = match g.kind {
                GeomKind::Plane => {
                    let normal = pose.rotation * Vector3::z();
                    self.add_static(Shape::Plane { normal, distance: normal.dot(&pose.translation.vector) }, pose)?
                }
                _ => self.add_static(g.shape(), pose)?,
            };
            if matches!(g.kind, GeomKind::Mesh(_)) {
                // Seen as its mesh, collided as its hull (as in MuJoCo).
                let color = g.rgba.map(|c| [c[0] as f32, c[1] as f32, c[2] as f32]);
                let visual = Visual { shape: g.drawn_shape(), offset: Isometry3::identity(), color };
                self.set_visuals(id, vec![visual])?;
            }
            if let Some(c) = g.rgba {
                self.set_color(id, [c[0] as f32, c[1] as f32, c[2] as f32])?;
            }
            self.set_geom_contact(id, 0, g.contact)?;
            if let Some(handle) = self.object(id)?.geom_handle() {
                let mut geom = self.world_mut().geom_mut(handle)?;
                geom.set_category_bits(g.bits.0);
                geom.set_collide_bits(g.bits.1);
                if let Some(name) = &g.name {
                    named.insert(name.clone(), (handle, g.bits));
                }
            }
            made.world_geoms.push(id);
        }
        made.welded = welds(model, &world, made)?;
        self.add_mjcf_equalities(model, &world, made)?;
        self.add_mjcf_pairs(model, &mut named)?;
        self.place_mjcf_sensors(model, made)?;
        self.exclude_mjcf_contacts(model, made)?;
        self.exclude_welded_to_world(model, made)?;
        for a in &model.actuators {
            let joint = made.joint(&a.joint).ok_or_else(|| Error::Invalid {
                what: "an MJCF actuator",
                problem: format!("{:?} drives the joint {:?}, which the model does not have", a.name, a.joint),
            })?;
            if self.actuators().any(|(_, j)| j == joint) {
                made.skipped.push(format!(
                    "actuator {:?}: the joint {:?} has an actuator already (ARS drives a joint with one)",
                    a.name, a.joint
                ));
                continue;
            }
            self.joint_mut(joint)?.set_controller(a.actuator.clone()).map_err(|e| Error::Invalid {
                what: "an MJCF actuator",
                problem: format!("{:?} on the joint {:?}: {e}", a.name, a.joint),
            })?;
        }
        Ok(())
    }

    /// `<contact><pair>`s: each pair of geoms touches whatever their bits say, with the
    /// pair's own parameters.
    fn add_mjcf_pairs(&mut self, model: &Model, named: &mut HashMap<String, (GeomHandle, (u64, u64))>) -> Result<()> {
        for (k, Pair { geom1: a, geom2: b, contact }) in model.pairs.iter().enumerate() {
            let unknown = |name: &str| Error::Invalid {
                what: "an MJCF contact pair",
                problem: format!("names the geom {name:?}, which the model does not have"),
            };
            // A bit of its own in one's category and the other's collide bits: these
            // two touch, and nothing else gains a contact.
            let bit = 1u64 << (32 + k);
            let (first, bits) = named.get_mut(a).ok_or_else(|| unknown(a))?;
            bits.0 |= bit;
            let (first, category) = (*first, bits.0);
            let (second, bits) = named.get_mut(b).ok_or_else(|| unknown(b))?;
            bits.1 |= bit;
            let (second, collide) = (*second, bits.1);
            self.world_mut().geom_mut(first)?.set_category_bits(category);
            self.world_mut().geom_mut(second)?.set_collide_bits(collide);
            // Its own parameters (every MJCF geom has its own, so each has its place).
            let place = |g| self.geom_place(g).ok_or_else(|| unknown(if g == first { a } else { b }));
            let (first, second) = (place(first)?, place(second)?);
            self.set_geom_pair_contact(first, second, *contact)?;
        }
        Ok(())
    }

    /// `<contact><exclude>`: each pair of bodies (their objects) never touch.
    fn exclude_mjcf_contacts(&mut self, model: &Model, made: &mut MjcfModel) -> Result<()> {
        for (a, b) in &model.excluded {
            let body = |name: &str| match made.body(name) {
                Some(id) => Ok(Some(id)),
                // Welded to the world: its geoms are static objects.
                None if made.welded.iter().any(|w| w.body == name) => Ok(None),
                None => Err(Error::Invalid {
                    what: "an MJCF contact exclusion",
                    problem: format!("names the body {name:?}, which the model does not have"),
                }),
            };
            match (body(a)?, body(b)?) {
                // Two bodies merged into one object never touch.
                (Some(x), Some(y)) if x == y => {}
                (Some(x), Some(y)) => self.exclude_contacts(x, y)?,
                _ => made.skipped.push(format!(
                    "<exclude> of {a:?} and {b:?}: a body welded to the world (its geoms static) is not \
                     excluded from contacts"
                )),
            }
        }
        Ok(())
    }

    /// MuJoCo never collides two geoms that are both welded to the world (`body_weldid`
    /// 0: the world body's own geoms, and those of its jointless children and their
    /// jointless descendants). A jointless child of the world that has mass is a
    /// kinematic ODE body (see the `weld` module), which ODE would collide with the
    /// world's static geoms and with every other such body: a table resting on the
    /// floor, a cabinet against the table, contacts between bodies that no force moves.
    /// Those pairs are excluded here, as MuJoCo excludes them.
    fn exclude_welded_to_world(&mut self, model: &Model, made: &MjcfModel) -> Result<()> {
        let welded: Vec<ObjectId> =
            model.bodies.iter().filter(|b| b.joints.is_empty()).filter_map(|b| made.body(&b.name)).collect();
        for (k, &a) in welded.iter().enumerate() {
            for &b in welded[k + 1..].iter().chain(&made.world_geoms) {
                self.exclude_contacts(a, b)?;
            }
        }
        Ok(())
    }

    /// Makes an MJCF body (its object, the light links chaining its joints, and those
    /// joints to `parent`), then its children.
    pub(super) fn add_mjcf_body(
        &mut self,
        body: &Body,
        parent_frame: &Isometry3<f64>,
        parent: Option<ObjectId>,
        made: &mut MjcfModel,
        named: &mut HashMap<String, (GeomHandle, (u64, u64))>,
    ) -> Result<()> {
        let frame = parent_frame * body.frame;
        if body.geoms.iter().any(|g| matches!(g.kind, GeomKind::Hfield(_))) {
            return Err(body_error(format!(
                "{:?}: an hfield geom on a body of its own (one that moves, or has mass) is not supported: ARS makes \
                 height fields as static terrain, in the world body",
                body.name
            )));
        }
        let grouped = super::group::group_of(body, &frame, parent.is_none());
        let grouped_none = grouped.is_none();
        let masses = body_masses(body, grouped_none, made)?;
        let (id, body_frame) = self.add_mjcf_object(body, &frame, &masses, made, named)?;
        let mut end = parent.map_or(JointEnd::World, JointEnd::Object);
        // MuJoCo ignores contacts between a body and its parent (filterparent). ODE
        // skips them for bodies one joint joins; a chain's links hide that.
        if let (Some(parent), true) = (parent, body.joints.len() > 1) {
            self.exclude_contacts(parent, id)?;
        }
        if body.joints.is_empty() {
            self.make_jointless_body(body, id, parent_frame, &masses, made)?;
        }
        if let Some(group) = grouped {
            // Several joints as MuJoCo makes them: one constraint (see `group.rs`).
            let ids = self.add_joint_group(id, end, &group)?;
            for (j, joint) in body.joints.iter().zip(ids) {
                self.set_mjcf_joint(j, joint)?;
                made.joints.push((j.name.clone(), joint));
            }
        }
        for (k, j) in body.joints.iter().enumerate().filter(|_| grouped_none) {
            if j.kind == JointKind::Free {
                self.damp_mjcf_joint(j, Vector3::zeros(), id, JointEnd::World, made)?;
                continue;
            }
            // Several joints in one body: a chain through light links at the body's
            // frame, the first joint nearest the parent (MuJoCo's order).
            let child = if k + 1 < body.joints.len() {
                let inertia = masses.link_inertia + masses.links_armature[k];
                self.add_chain_link(body, j, &body_frame, masses.link_mass, inertia)?
            } else {
                id
            };
            let joint = self.add_mjcf_joint(j, &frame, child, end)?;
            self.damp_mjcf_joint(j, frame.rotation * j.axis, child, end, made)?;
            made.joints.push((j.name.clone(), joint));
            if child != id {
                made.chain_links.push(child);
            }
            end = JointEnd::Object(child);
        }
        for child in &body.children {
            self.add_mjcf_body(child, &frame, Some(id), made, named)?;
        }
        Ok(())
    }

    /// Makes jointless MJCF `body` (object `id`) kinematic: welded to the world, or a
    /// mocap body moved by the user (`made.mocap`).
    fn make_jointless_body(
        &mut self,
        body: &Body,
        id: ObjectId,
        parent_frame: &Isometry3<f64>,
        masses: &BodyMasses,
        made: &mut MjcfModel,
    ) -> Result<()> {
        // Welded to the world (a jointless body of the world that has mass, its
        // jointless descendants merged into it: the `weld` module) or moved by the
        // user only (a mocap body, `set_mocap_pose`): a kinematic ODE body, as
        // MuJoCo's has no degree of freedom. It keeps its mass, which it never
        // feels, and adds no row to the step, where a fixed joint would add six.
        let handle = self.object(id)?.body_handle().ok_or_else(|| body_error(format!("{:?}: no body", body.name)))?;
        let mut ode = self.world_mut().body_mut(handle)?;
        ode.set_kinematic(true);
        if !body.mocap {
            // It never moves: ODE leaves it out of the step (its geoms are not
            // moved, its contacts hold the bodies touching it as the world's
            // would), unless a joint joins it to a body that moves.
            ode.set_enabled(false);
        }
        if body.mocap {
            made.mocap.push(MjcfMocap {
                body: body.name.clone(),
                object: id,
                placement: *parent_frame,
                offset: Isometry3::translation(masses.com.x, masses.com.y, masses.com.z),
            });
        }
        Ok(())
    }

    /// Makes an MJCF body's ODE body (at its centre of mass, turned as the MJCF body),
    /// its geoms and its object; returns the object and the ODE body's frame.
    fn add_mjcf_object(
        &mut self,
        body: &Body,
        frame: &Isometry3<f64>,
        masses: &BodyMasses,
        made: &mut MjcfModel,
        named: &mut HashMap<String, (GeomHandle, (u64, u64))>,
    ) -> Result<(ObjectId, Isometry3<f64>)> {
        let (mass, inertia) = (masses.mass, masses.inertia);
        let body_frame =
            Isometry3::from_parts(Translation3::from(frame * nalgebra::Point3::from(masses.com)), frame.rotation);
        let handle =
            self.insert_body_at(&body_frame, mass, inertia).map_err(|e| body_error(format!("{:?}: {e}", body.name)))?;
        let drawn = body.geoms.first().map_or(Shape::Sphere { radius: 0.01 }, Geom::shape);
        let geoms = mjcf_geoms(body, frame, &body_frame, handle);
        let count = geoms.len();
        let id =
            self.insert_object(NewObject::with_geoms(ObjectName::Unique(&body.name), drawn, Some(handle), geoms))?;
        let handles: Vec<GeomHandle> = self.object(id)?.geoms().collect();
        let made_geoms = body.geoms.iter().filter(|g| !matches!(g.kind, GeomKind::Plane));
        for (g, handle) in made_geoms.zip(handles) {
            if let Some(name) = &g.name {
                named.insert(name.clone(), (handle, g.bits));
            }
        }
        // The geoms made, in order (planes are the world's), with their own parameters.
        let made_geoms = body.geoms.iter().filter(|g| !matches!(g.kind, GeomKind::Plane));
        for (k, g) in made_geoms.enumerate().take(count) {
            self.set_geom_contact(id, k, g.contact)?;
        }
        if let Some(c) = body.geoms.iter().find_map(|g| g.rgba) {
            self.set_color(id, [c[0] as f32, c[1] as f32, c[2] as f32])?;
        }
        if body.geoms.iter().any(|g| matches!(g.kind, GeomKind::Mesh(_))) {
            // Its meshes are seen as they are, and collide as their hulls (as in MuJoCo).
            let visuals = body
                .geoms
                .iter()
                .filter(|g| !matches!(g.kind, GeomKind::Plane))
                .map(|g| Visual {
                    shape: g.drawn_shape(),
                    offset: body_frame.inverse() * frame * g.frame,
                    color: g.rgba.map(|c| [c[0] as f32, c[1] as f32, c[2] as f32]),
                })
                .collect();
            self.set_visuals(id, visuals)?;
        }
        made.bodies.push((self.object(id)?.name().to_string(), id));
        Ok((id, body_frame))
    }

    /// An ODE body of `mass` and `inertia` (about its centre) whose frame is `frame`.
    fn insert_body_at(&mut self, frame: &Isometry3<f64>, mass: f64, inertia: Matrix3<f64>) -> Result<BodyHandle> {
        self.world_mut().insert_body(
            BodyBuilder::new()
                .mass(MassSpec::Custom { mass, inertia })
                .position(nalgebra::Point3::from(frame.translation.vector))
                .rotation(frame.rotation.to_rotation_matrix()),
        )
    }

    /// A light link of the chain through a body's joints, at the body's frame, moved by
    /// `joint`.
    fn add_chain_link(
        &mut self,
        body: &Body,
        joint: &Joint,
        body_frame: &Isometry3<f64>,
        mass: f64,
        inertia: Matrix3<f64>,
    ) -> Result<ObjectId> {
        let name = format!("{}/{}", body.name, joint.name);
        let link = self
            .insert_body_at(body_frame, mass, inertia)
            .map_err(|e| body_error(format!("{name:?}, the light link chaining {:?}: {e}", joint.name)))?;
        let drawn = Shape::Sphere { radius: 0.01 };
        self.insert_object(NewObject::with_geoms(ObjectName::Unique(&name), drawn, Some(link), Vec::new()))
    }

    /// A joint's `damping`, and a ball's or free joint's `frictionloss`, when it has
    /// them: the motors beside it (see `damper.rs`), listed in
    /// [`MjcfModel::joint_motors`].
    fn damp_mjcf_joint(
        &mut self,
        j: &Joint,
        axis: Vector3<f64>,
        child: ObjectId,
        end: JointEnd,
        made: &mut MjcfModel,
    ) -> Result<()> {
        let mut resisting = Vec::new();
        // A hinge's or a slide's damping is its own (`add_mjcf_joint`).
        if j.damping > 0.0 && matches!(j.kind, JointKind::Ball | JointKind::Free) {
            resisting.push(Resisting::Damping(j.damping));
        }
        if j.frictionloss > 0.0 && matches!(j.kind, JointKind::Ball | JointKind::Free) {
            resisting.push(Resisting::Friction(j.frictionloss));
        }
        if resisting.is_empty() {
            return Ok(());
        }
        let body = |scene: &Self, id: ObjectId| scene.object(id).map(|o| o.body_handle());
        let child = body(self, child)?.ok_or_else(|| body_error(format!("the joint {:?} moves no body", j.name)))?;
        let parent = match end {
            JointEnd::Object(id) => body(self, id)?,
            JointEnd::World => None,
        };
        for r in resisting {
            for motor in self.add_mjcf_joint_motors(j, axis, child, parent, r)? {
                made.joint_motors.push((j.name.clone(), motor));
            }
        }
        Ok(())
    }

    /// Makes an MJCF joint moving `child` relative to `end` (at the joint's `ref`),
    /// with its range, spring and dry friction (its damping: `damp_mjcf_joint`).
    fn add_mjcf_joint(&mut self, j: &Joint, frame: &Isometry3<f64>, child: ObjectId, end: JointEnd) -> Result<JointId> {
        let anchor = frame * nalgebra::Point3::from(j.pos);
        let axis = frame.rotation * j.axis;
        // ODE measures a joint from where its bodies are when it is made: made with
        // the child moved back by `ref`, it reads `ref` in the file's pose.
        let moved = self.object(child)?.body_handle().filter(|_| j.reference != 0.0);
        let before = match moved {
            Some(b) => {
                let body = self.world_mut().body(b)?;
                let (position, rotation) = (body.position(), body.rotation());
                let back = match j.kind {
                    JointKind::Hinge => {
                        let turn = UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), -j.reference);
                        Isometry3::rotation_wrt_point(turn, anchor)
                    }
                    _ => Isometry3::from_parts(Translation3::from(axis * -j.reference), UnitQuaternion::identity()),
                };
                let mut body = self.world_mut().body_mut(b)?;
                body.set_position(back * position)?;
                body.set_rotation(back.rotation.to_rotation_matrix() * rotation)?;
                Some((b, position, rotation))
            }
            None => None,
        };
        let joint = match j.kind {
            JointKind::Hinge => self.add_hinge_joint(&j.name, child, end, Some(anchor), axis),
            JointKind::Slide => self.add_slider_joint(&j.name, child, end, axis),
            _ => self.add_ball_joint(&j.name, child, end, Some(anchor)),
        };
        if let Some((b, position, rotation)) = before {
            // Put back as it was made: ODE keeps the rotation matrix as set.
            let mut body = self.world_mut().body_mut(b)?;
            body.set_position(position)?;
            body.set_rotation(rotation)?;
        }
        let joint = joint?;
        self.set_mjcf_joint(j, joint)?;
        Ok(joint)
    }

    /// Gives an MJCF hinge or slide `joint` its range, spring, dry friction, armature
    /// and damping.
    pub(super) fn set_mjcf_joint(&mut self, j: &Joint, joint: JointId) -> Result<()> {
        if let Some((lo, hi)) = j.range {
            self.joint_mut(joint)?.set_limits(lo, hi)?;
            if let Some(erp) = j.stop_erp(self.time_step()) {
                let handle = self.joint_data(joint)?.handle;
                self.world_mut().joint_mut(handle)?.set_param(JointParam::StopErp, 0, erp)?;
            }
        }
        if j.spring.0 > 0.0 {
            self.joint_mut(joint)?.set_spring(j.spring.0, j.spring.1)?;
        }
        if j.frictionloss > 0.0 && matches!(j.kind, JointKind::Hinge | JointKind::Slide) {
            self.joint_mut(joint)?.set_dry_friction(j.frictionloss)?;
        }
        if matches!(j.kind, JointKind::Hinge | JointKind::Slide) {
            // The joint's own inertia and its damping, held by one motor made right
            // after the joint (as a scene file makes it again).
            if j.armature > 0.0 {
                self.joint_mut(joint)?.set_armature(j.armature)?;
            }
            if j.damping > 0.0 {
                self.joint_mut(joint)?.set_damping(j.damping)?;
            }
        }
        Ok(())
    }
}

/// Where each body merged into another (or into the world) went.
fn welds(model: &Model, world: &Isometry3<f64>, made: &MjcfModel) -> Result<Vec<MjcfWeld>> {
    let mut welds = Vec::new();
    for w in &model.welded {
        let (object, offset) = match &w.into {
            None => (None, world * w.frame),
            Some(into) => {
                let body = find_body(&model.bodies, &|b| &b.name == into);
                let (body, object) = body
                    .zip(made.body(into))
                    .ok_or_else(|| body_error(format!("{:?} was welded into {into:?}, which was not made", w.name)))?;
                (Some(object), Isometry3::from(-body.centre_of_mass()) * w.frame)
            }
        };
        welds.push(MjcfWeld { body: w.name.clone(), into: w.into.clone(), object, offset });
    }
    Ok(welds)
}

/// The masses of an MJCF body and of the light links chaining its joints, each at
/// least ARS's least mass.
struct BodyMasses {
    /// The body's mass.
    mass: f64,
    /// Its centre of mass in its frame.
    com: Vector3<f64>,
    /// Its inertia, its last joint's armature added.
    inertia: Matrix3<f64>,
    /// Each light link's mass.
    link_mass: f64,
    /// Each light link's inertia, without its joint's armature.
    link_inertia: Matrix3<f64>,
    /// The armature each light link carries (one per joint but the last).
    links_armature: Vec<Matrix3<f64>>,
}

/// An MJCF body's masses and its links' (a fraction of its own), with their joints'
/// armatures; what is raised to ARS's least mass or added by an armature is noted in
/// `made`.
fn body_masses(body: &Body, chained: bool, made: &mut MjcfModel) -> Result<BodyMasses> {
    // Jointless bodies without mass were merged into their parent (`weld`): a body
    // still without one moves, as one lighter than MuJoCo's least, which MuJoCo refuses.
    let (mass, com, inertia) = match body.mass {
        Some(mass) => mass,
        // A massless mocap body still needs an ODE body to be moved: the least ARS
        // takes, which its kinematic body never feels.
        None if body.mocap => {
            (crate::limits::MIN_MASS, Vector3::zeros(), Matrix3::identity() * crate::limits::MIN_MASS)
        }
        None => (0.0, Vector3::zeros(), Matrix3::zeros()),
    };
    if !body.joints.is_empty() && (mass < MJ_MINVAL || inertia.trace() < MJ_MINVAL) {
        return Err(body_error(format!(
            "{:?} moves (it has joints) but its mass {mass:e} kg or its inertia (trace {:e} kg·m²), with its \
             jointless children's, is below {MJ_MINVAL:e}: mass and inertia of moving bodies must be larger \
             than mjMINVAL, as MuJoCo refuses it too (a body's mass is its <inertial>, else its geoms')",
            body.name,
            inertia.trace()
        )));
    }
    let (link_mass, link_inertia) = if chained && body.joints.len() > 1 {
        let what = format!("the light links chaining {:?}", body.name);
        at_least_ars_least_mass(&what, mass * CHAIN_LINK_FRACTION, inertia * CHAIN_LINK_FRACTION, &mut made.skipped)
    } else {
        (mass * CHAIN_LINK_FRACTION, inertia * CHAIN_LINK_FRACTION)
    };
    let (mass, inertia) = at_least_ars_least_mass(&format!("{:?}", body.name), mass, inertia, &mut made.skipped);
    // A jointless body with mass left after welding (one of the world) is a kinematic
    // ODE body of its own, which ODE makes only with an inertia a body can have;
    // MuJoCo takes any (a point mass: `diaginertia="0 0 0"`), the body static.
    let inertia = match body.joints.is_empty().then(|| balance_inertia(mass, &inertia)).flatten() {
        Some(balanced) => {
            made.skipped.push(format!("{:?}: {} (a welded body of its own needs one)", body.name, balanced.note));
            balanced.inertia
        }
        None => inertia,
    };
    // The body is moved by its last joint, a chain link by its joint: each carries
    // its joint's armature.
    let links_armature: Vec<Matrix3<f64>> = body.joints[..body.joints.len().saturating_sub(1)]
        .iter()
        .map(|j| joint_armature(&format!("{}/{}", body.name, j.name), Some(j), made))
        .collect();
    let inertia = inertia + joint_armature(&body.name, body.joints.last(), made);
    Ok(BodyMasses { mass, com, inertia, link_mass, link_inertia, links_armature })
}

/// The inertia a ball joint's armature adds to `object`, which the joint moves; what
/// was added is noted in `made`.
fn joint_armature(object: &str, joint: Option<&Joint>, made: &mut MjcfModel) -> Matrix3<f64> {
    let Some(joint) = joint else { return Matrix3::zeros() };
    let added = armature_inertia(joint);
    if added != Matrix3::zeros() {
        made.armature.push((object.to_string(), added));
    }
    added
}

/// MuJoCo's `mjMINVAL`: the least mass and inertia (trace) of a moving body.
const MJ_MINVAL: f64 = 1e-15;

/// A problem with an MJCF body.
fn body_error(problem: String) -> Error {
    Error::Invalid { what: "an MJCF body", problem }
}

/// An MJCF body's geoms (not its planes) on its ODE body `handle`, whose frame is
/// `body_frame`.
fn mjcf_geoms(
    body: &Body,
    frame: &Isometry3<f64>,
    body_frame: &Isometry3<f64>,
    handle: BodyHandle,
) -> Vec<GeomBuilder> {
    let to_body = body_frame.inverse() * frame;
    body.geoms
        .iter()
        .filter(|g| !matches!(g.kind, GeomKind::Plane))
        .map(|g| {
            let offset = to_body * g.frame;
            let geom = GeomBuilder::new(g.shape()).attached_to(handle).category_bits(g.bits.0).collide_bits(g.bits.1);
            if offset == Isometry3::identity() { geom } else { geom.offset(offset) }
        })
        .collect()
}
