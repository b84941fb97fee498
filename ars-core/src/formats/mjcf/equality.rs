//! `<equality>`: MuJoCo's equality constraints, read and made as ODE joints.
//!
//! - `connect` (two bodies, or a body and the world, share a point): a ball joint at
//!   the anchor (`anchor` in `body1`'s frame, or where `site1` is).
//! - `weld` (two bodies, or a body and the world, keep their relative pose): a fixed
//!   joint, holding the pose they have in the file.
//! - Either end may be a mocap body (a kinematic body the user moves): what is joined
//!   to it follows it.
//! - `joint` (`joint1 − ref1 = a0 + a1·(joint2 − ref2)`, MuJoCo's `polycoef` of
//!   degree 1): `joint1` [follows](crate::scene::Mimic) `joint2`.
//!
//! A MuJoCo equality is soft (`solref`, `solimp`, 0.02 s and critically damped by
//! default). A `connect`'s ball joint and a `weld`'s fixed joint take the ERP of
//! MuJoCo's reference acceleration at the scene's time step (as a joint's stops do:
//! then ODE's joint lags a moving end as MuJoCo's does, `b / k` per m/s), and the CFM of
//! its impedance for the two bodies' reduced mass (as a contact's); a fixed joint's
//! three rotation rows keep the world's ERP and CFM (ODE's fixed joint has parameters
//! for its position rows only).
//!
//! What the mapping cannot carry is said in the model's `skipped` list:
//! - a `joint` equality's `solref` and `solimp`, and a `weld`'s `torquescale`: a
//!   follower's motor is one-way (the leader does not feel the follower's load);
//! - a `weld`'s `relpose` other than the file's pose, sites that do not coincide in the
//!   file's pose, `polycoef` beyond degree 1, a `joint` without `joint2`, and
//!   `tendon` and `flex` equalities are skipped, as is an equality the file makes
//!   inactive (`active="false"`: ARS cannot switch it on later).

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};

use super::MjcfModel;
use super::defaults::Attrs;
use super::mass::find_body;
use super::model::{Body, Equality, EqualityKind, Joint, JointKind, Model, Place, reference_erp};
use super::problem::{Parsed, problem};
use super::read::Reader;
use crate::error::{Error, Result};
use crate::handle::{JointId, ObjectId};
use crate::joint::JointParam;
use crate::scene::{JointEnd, Scene, impedance_cfm, reduced_mass};

impl Equality {
    fn said(&self, text: impl std::fmt::Display) -> String {
        format!("<{}> at line {}: {text}", self.tag, self.line)
    }
}

/// How far (m, rad) two sites may be apart in the file's pose and still be joined as
/// they are.
const COINCIDENT: f64 = 1e-9;

impl<'a, 'input> Reader<'_, 'a, 'input> {
    /// An `<equality>` section: its `connect`, `weld` and `joint` elements into
    /// `model.equalities`; the others skipped (or refused).
    pub(super) fn equalities(&mut self, node: roxmltree::Node<'a, 'input>, model: &mut Model) -> Parsed<()> {
        for child in self.tree.elements(node) {
            let tag = child.tag_name().name();
            if !["connect", "weld", "joint"].contains(&tag) {
                self.unsupported(&child, &format!("<{tag}> in <equality>"))?;
                continue;
            }
            // Equality defaults are a class's `<equality>`, whatever the kind.
            let class = child.attribute("class").unwrap_or("main");
            let a = Attrs { node: child, class: self.defaults.get(class).and_then(|c| c.get("equality")) };
            let line = problem(&child, "").line;
            if a.get("active") == Some("false") {
                self.skipped.push(format!(
                    "<{tag}> at line {line}: inactive in the file (active=\"false\"): not made (ARS cannot switch it on)"
                ));
                continue;
            }
            // A connect's and a weld's softness is their joint's ERP; a joint coupling's is
            // a one-way motor's, and `torquescale` has no counterpart.
            let unused: &[&str] = if tag == "joint" { &["solref", "solimp", "torquescale"] } else { &["torquescale"] };
            let soft: Vec<&str> = unused.iter().copied().filter(|k| a.get(k).is_some()).collect();
            if !soft.is_empty() {
                let why = if tag == "joint" {
                    "a coupling is a one-way motor, as stiff as every joint"
                } else {
                    "ODE's fixed joint holds turn and position alike"
                };
                self.skipped.push(format!("<{tag}> at line {line}: {} not used ({why})", soft.join(", ")));
            }
            let solref = a.fixed::<2>("solref")?.unwrap_or([0.02, 1.0]);
            let solimp = a.numbers("solimp")?.unwrap_or_default();
            let impedance = [solimp.first().copied().unwrap_or(0.9), solimp.get(1).copied().unwrap_or(0.95)];
            let kind = match tag {
                "joint" => {
                    let follower = a.get("joint1").ok_or_else(|| problem(&child, "needs a joint1"))?.to_string();
                    let mut polycoef = [0.0, 1.0, 0.0, 0.0, 0.0];
                    if let Some(given) = a.numbers("polycoef")? {
                        if given.len() > 5 {
                            return Err(problem(&child, format!("polycoef has {} numbers, at most 5", given.len())));
                        }
                        polycoef[..given.len()].copy_from_slice(&given);
                    }
                    EqualityKind::Joint { follower, leader: a.get("joint2").map(str::to_string), polycoef }
                }
                _ => {
                    let (first, second) = ends(&a)?;
                    if tag == "connect" {
                        let anchor = match (&first, a.fixed::<3>("anchor")?) {
                            (Place::Site(_), _) => Vector3::zeros(),
                            (Place::Body(_), Some(anchor)) => Vector3::from(anchor),
                            (Place::Body(_), None) => {
                                return Err(problem(&child, "a connect of bodies needs an anchor"));
                            }
                        };
                        EqualityKind::Connect { first, second, anchor }
                    } else {
                        EqualityKind::Weld { first, second, relpose: relpose(&a)? }
                    }
                }
            };
            let name = child.attribute("name").map(str::to_string);
            model.equalities.push(Equality { name, kind, softness: (solref, impedance), tag: tag.to_string(), line });
        }
        Ok(())
    }
}

/// A `connect`'s or `weld`'s two ends: `body1` (and `body2`, else the world) or `site1`
/// and `site2`.
fn ends(a: &Attrs<'_, '_>) -> Parsed<(Place, Option<Place>)> {
    match (a.get("site1"), a.get("site2"), a.get("body1")) {
        (Some(s1), Some(s2), _) => Ok((Place::Site(s1.into()), Some(Place::Site(s2.into())))),
        (Some(_), None, _) | (None, Some(_), _) => Err(problem(&a.node, "needs both site1 and site2")),
        (None, None, Some(b1)) => Ok((Place::Body(b1.into()), a.get("body2").map(|b| Place::Body(b.into())))),
        (None, None, None) => Err(problem(&a.node, "needs a body1 (or site1 and site2)")),
    }
}

/// A `weld`'s `relpose` (position, then quaternion w x y z), `None` when its quaternion
/// is all zeros (MuJoCo's default: the pose in the file).
fn relpose(a: &Attrs<'_, '_>) -> Parsed<Option<Isometry3<f64>>> {
    let Some(p) = a.fixed::<7>("relpose")? else { return Ok(None) };
    let q = Quaternion::new(p[3], p[4], p[5], p[6]);
    if q.norm() == 0.0 {
        return Ok(None);
    }
    let turn = UnitQuaternion::from_quaternion(q);
    Ok(Some(Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), turn)))
}

/// Where an end is in the simulation: the object it moves with (`World` for the world
/// and what is welded to it) and the end's frame (a body's frame, or a site's).
struct Located {
    end: JointEnd,
    frame: Isometry3<f64>,
}

impl Scene {
    /// Makes the model's equalities (after its bodies, joints and welds).
    pub(super) fn add_mjcf_equalities(
        &mut self,
        model: &Model,
        world: &Isometry3<f64>,
        made: &mut MjcfModel,
    ) -> Result<()> {
        for eq in &model.equalities {
            let name = eq.name.as_deref().unwrap_or("");
            match &eq.kind {
                EqualityKind::Connect { first, second, anchor } => {
                    let (a, b) = (
                        self.locate(Some(first), model, world, made, eq)?,
                        self.locate(second.as_ref(), model, world, made, eq)?,
                    );
                    let point = a.frame * Point3::from(*anchor);
                    if let (Place::Site(_), Some(Place::Site(_))) = (first, second) {
                        let gap = (b.frame.translation.vector - a.frame.translation.vector).norm();
                        if gap > COINCIDENT {
                            made.skipped.push(
                                eq.said(format!("its sites are {gap:.3e} m apart in the file: joined where site1 is")),
                            );
                        }
                    }
                    match ordered(a.end, b.end) {
                        Some((object, other)) => {
                            let joint = self.add_ball_joint(name, object, other, Some(point))?;
                            self.soften(joint, eq, object, other)?;
                            made.equalities.push(joint);
                        }
                        None => made.skipped.push(eq.said("both ends are on one rigid body: nothing to join")),
                    }
                }
                EqualityKind::Weld { first, second, relpose } => {
                    let (a, b) = (
                        self.locate(Some(first), model, world, made, eq)?,
                        self.locate(second.as_ref(), model, world, made, eq)?,
                    );
                    let kept = a.frame.inverse() * b.frame;
                    let wanted = match (first, relpose) {
                        (Place::Site(_), _) => Some(Isometry3::identity()),
                        (Place::Body(_), pose) => *pose,
                    };
                    if let Some(wanted) = wanted {
                        let off = (kept.translation.vector - wanted.translation.vector).norm()
                            + kept.rotation.angle_to(&wanted.rotation);
                        if off > COINCIDENT {
                            made.skipped.push(eq.say_relpose(off));
                        }
                    }
                    match ordered(a.end, b.end) {
                        Some((object, other)) => {
                            let joint = self.add_fixed_joint(name, object, other)?;
                            self.soften(joint, eq, object, other)?;
                            made.equalities.push(joint);
                        }
                        None => made.skipped.push(eq.said("both ends are on one rigid body: nothing to weld")),
                    }
                }
                EqualityKind::Joint { follower, leader, polycoef } => {
                    self.follow_mjcf_joint(eq, follower, leader.as_deref(), polycoef, model, made)?
                }
            }
        }
        Ok(())
    }

    /// Gives a connect's or weld's joint between `object` and `other` the ERP of its
    /// `solref` (see [`reference_erp`]) at the scene's time step, and the CFM of
    /// MuJoCo's impedance at rest (`solimp`'s `dmin`, as an equality's violation stays
    /// far below its width): `h·(1 − d) / (d·m)`, `m` the two objects' reduced mass (a
    /// contact's CFM, the same approximation: the bodies' own masses, not the chains
    /// they hang in), the world's when an end is the world or kinematic. Without it the
    /// joint is as stiff as every joint, and fights a stop it starts beyond: a
    /// Meta-World arm whose shoulder starts 0.5 rad outside its range and whose hand is
    /// welded to its mocap body whipped at 60 m/s, where MuJoCo's moves at 3 m/s.
    fn soften(&mut self, joint: JointId, eq: &Equality, object: ObjectId, other: JointEnd) -> Result<()> {
        let (solref, [d_min, d_max]) = eq.softness;
        let h = self.time_step();
        if let Some(erp) = reference_erp(solref, d_max, h) {
            self.joint_mut(joint)?.set_param(JointParam::Erp, erp)?;
        }
        let mass = |id: ObjectId| -> Result<f64> {
            let body = self.body(id)?;
            Ok(if body.is_kinematic() { f64::INFINITY } else { body.mass() })
        };
        let m = match other {
            JointEnd::Object(o) => reduced_mass(mass(object)?, mass(o)?),
            JointEnd::World => mass(object)?,
        };
        let cfm = impedance_cfm(h, d_min.clamp(1e-4, 1.0 - 1e-4), m);
        if cfm.is_finite() && cfm > self.world().cfm() {
            self.joint_mut(joint)?.set_param(JointParam::Cfm, cfm)?;
        }
        Ok(())
    }

    /// A `joint` equality of degree 1 as a [`Mimic`](crate::scene::Mimic).
    fn follow_mjcf_joint(
        &mut self,
        eq: &Equality,
        follower: &str,
        leader: Option<&str>,
        polycoef: &[f64; 5],
        model: &Model,
        made: &mut MjcfModel,
    ) -> Result<()> {
        let Some(leader) = leader else {
            made.skipped.push(eq.said("a joint held at a position (no joint2) is not supported"));
            return Ok(());
        };
        if polycoef[2..].iter().any(|c| *c != 0.0) {
            made.skipped.push(eq.said("a polycoef beyond degree 1 is not supported (only linear couplings are)"));
            return Ok(());
        }
        let joint = |name: &str| {
            let id = made.joint(name);
            let read = find_joint(&model.bodies, name);
            match (id, read) {
                (Some(id), Some(j)) => Ok((id, j.reference, j.kind)),
                _ => Err(invalid(eq, format!("names the joint {name:?}, which the model does not have"))),
            }
        };
        let (follower_id, ref1, kind1) = joint(follower)?;
        let (leader_id, ref2, kind2) = joint(leader)?;
        let moving = |k| matches!(k, JointKind::Hinge | JointKind::Slide);
        if !moving(kind1) || kind1 != kind2 {
            made.skipped.push(eq.said("only a hinge following a hinge, or a slide a slide, is supported"));
            return Ok(());
        }
        if self.actuators().any(|(_, j)| j == follower_id) {
            made.skipped.push(
                eq.said(format!("{follower:?} has an actuator: ARS drives a joint with one, not also a coupling")),
            );
            return Ok(());
        }
        let (a0, a1) = (polycoef[0], polycoef[1]);
        self.joint_mut(follower_id)?.set_mimic(leader_id, a1, a0 + ref1 - a1 * ref2)
    }

    /// Where `place` is (see [`Located`]); `None`: the world.
    fn locate(
        &self,
        place: Option<&Place>,
        model: &Model,
        world: &Isometry3<f64>,
        made: &MjcfModel,
        eq: &Equality,
    ) -> Result<Located> {
        match place {
            None => Ok(Located { end: JointEnd::World, frame: *world }),
            Some(Place::Body(name)) if name == "world" => Ok(Located { end: JointEnd::World, frame: *world }),
            Some(Place::Body(name)) => {
                if let Some(w) = made.welded.iter().find(|w| &w.body == name) {
                    return Ok(match w.object {
                        Some(id) => Located { end: JointEnd::Object(id), frame: self.pose(id)? * w.offset },
                        None => Located { end: JointEnd::World, frame: w.offset },
                    });
                }
                let body = find_body(&model.bodies, &|b| &b.name == name);
                let (body, id) = body
                    .zip(made.body(name))
                    .ok_or_else(|| invalid(eq, format!("names the body {name:?}, which the model does not have")))?;
                let frame = self.pose(id)? * Translation3::from(-body.centre_of_mass());
                Ok(Located { end: JointEnd::Object(id), frame })
            }
            Some(Place::Site(name)) => {
                let site = made
                    .site(name)
                    .ok_or_else(|| invalid(eq, format!("names the site {name:?}, which no body of the model has")))?;
                Ok(Located { end: JointEnd::Object(site.object), frame: self.pose(site.object)? * site.offset })
            }
        }
    }
}

impl Equality {
    fn say_relpose(&self, off: f64) -> String {
        self.said(format!(
            "the pose it keeps is {off:.3e} (m + rad) from the file's: ARS keeps the file's pose (relpose, or sites that do not coincide, are not applied)"
        ))
    }
}

/// The two ends as a joint takes them (an object first), `None` when they are the same
/// rigid body (or both the world).
fn ordered(a: JointEnd, b: JointEnd) -> Option<(ObjectId, JointEnd)> {
    match (a, b) {
        (JointEnd::Object(x), JointEnd::Object(y)) if x == y => None,
        (JointEnd::Object(x), other) => Some((x, other)),
        (JointEnd::World, JointEnd::Object(y)) => Some((y, JointEnd::World)),
        (JointEnd::World, JointEnd::World) => None,
    }
}

/// The joint of the file named `name`, wherever it is.
fn find_joint<'b>(bodies: &'b [Body], name: &str) -> Option<&'b Joint> {
    bodies.iter().find_map(|b| b.joints.iter().find(|j| j.name == name).or_else(|| find_joint(&b.children, name)))
}

fn invalid(eq: &Equality, problem: String) -> Error {
    Error::Invalid { what: "an MJCF <equality>", problem: eq.said(problem) }
}
