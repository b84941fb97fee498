//! Joint groups: several joints between the same two objects, made as one ODE
//! constraint, as MuJoCo makes a body with several joints (a humanoid's hip: three
//! hinges at one point; a planar walker's root: two slides and a hinge).
//!
//! A chain of ODE joints through light links would take five rows for each joint (and
//! a body for each link, whose mass the file does not have). A group takes a row for
//! each freedom it locks: an ODE ball at the hinges' common point (three rows; none
//! when the group slides), an angular motor holding the rotations no hinge allows and,
//! for one or two slides, a linear motor holding the translations no slide allows.
//! Those motors correct their drift as ODE's own joints do (the world's ERP). The
//! angular motor's rows are the locked Euler angles' dual axes, turned each step; a
//! group of slides alone, which turns no way, holds its rotation about its frame's
//! fixed axes instead (the world's: slides join the world), set once.
//!
//! Each joint of the group stays a simulation joint of its own ([`JointType::Hinge`]
//! or [`JointType::Slider`]), read and driven as any other: its position and rate are
//! measured from the two bodies' relative pose and velocity (exact and current, as
//! MuJoCo's coordinates: the hinges are the Euler angles of the relative rotation about
//! their axes, the first fixed in the parent, the last in the child), and its efforts
//! act along its dual axis (the direction whose torque moves that joint alone). Its
//! stops, speed motor, dry friction, armature and damping are the rows of a one-axis
//! ODE motor of its own, turned to that direction before each step and scaled by the
//! dual axis' length (so that their forces are the joint's); a slide's stops, which
//! ODE's linear motor does not have, are a one-sided row at the anchor while the
//! slide is at one (an ODE contact with the world, without friction, at the stop's
//! ERP and CFM). Without stops or a motor,
//! that motor has no row. That motor is the joint's ODE joint
//! ([`JointView::ode`](crate::scene::JointView::ode)), and its
//! [`reaction`](crate::scene::JointView::reaction) is that motor's alone (stops, speed motor,
//! dry friction), not the group's constraint. Removing one joint of a group removes the
//! group.
//!
//! What a group takes, checked when it is made: slides first, then hinges; the slides'
//! axes orthonormal, and with slides the second object is the world;
//! the hinges' axes orthonormal and through one point; two slides with a hinge only
//! about the normal of their plane (a planar body), and one slide with no hinge.

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Unit, Vector3};

use super::Scene;
use super::joints::{JointEnd, JointType};
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, JointHandle, JointId, ObjectId};
use crate::joint::{AxisFrame, JointBuilder, JointKind, JointParam};
use crate::limits;

mod motion;

pub(crate) use motion::GroupKinematics;

/// One joint of a group to make: a hinge through `anchor` about `axis`, or a slide along
/// `axis` (world frame, where the objects are when the group is made, where the joint
/// reads `reference`).
#[derive(Clone, Debug, PartialEq)]
pub struct GroupJoint {
    /// Its name (empty: a default one).
    pub name: String,
    /// [`JointType::Hinge`] or [`JointType::Slider`].
    pub kind: JointType,
    /// A point of a hinge's axis (a slide's is not used).
    pub anchor: Point3<f64>,
    /// Its axis.
    pub axis: Vector3<f64>,
    /// Its position (rad or m) where the objects are when the group is made (MuJoCo's
    /// `ref`).
    pub reference: f64,
}

/// A simulation joint's place in its group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GroupMember {
    /// The group, in the scene's list.
    pub(crate) group: usize,
    /// The joint's place in the group (slides first).
    pub(crate) index: usize,
    /// Its speed motor as asked (speed and largest force, in the joint's units), which
    /// its ODE motor gets scaled each step.
    pub(crate) motor: (f64, f64),
    /// The scale its ODE motor's stops and speed motor were last set with (NaN: to be
    /// set).
    pub(crate) scale: f64,
}

/// A group's geometry where every joint of it reads 0, in the parent's frame (the
/// world's without one): each joint's axis, the anchor in the child's frame and in the
/// parent's, and the child's rotation relative to the parent.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GroupRest {
    /// Each joint's axis, in order.
    pub axes: Vec<Vector3<f64>>,
    /// The anchor in the child's frame.
    pub anchor_child: Vector3<f64>,
    /// The anchor in the parent's frame.
    pub anchor_parent: Vector3<f64>,
    /// The child's rotation relative to the parent.
    pub rest: Matrix3<f64>,
}

/// A group as the scene keeps it.
pub(crate) struct JointGroup {
    /// Its joints, slides first.
    pub(crate) members: Vec<JointId>,
    child: BodyHandle,
    parent: Option<BodyHandle>,
    /// The slides' axes (world).
    slides: Vec<Vector3<f64>>,
    /// The world directions no slide allows (one or two slides).
    normals: Vec<Vector3<f64>>,
    /// How many hinges.
    hinges: usize,
    /// Columns: the hinges' axes, then the directions completing a right-handed frame,
    /// in the parent's frame (the world's without one).
    frame: Matrix3<f64>,
    /// `-1` when the third hinge's axis is the frame's third column reversed.
    third_sign: f64,
    /// The anchor in the child's frame, and in the parent's where every joint reads 0.
    anchor_child: Vector3<f64>,
    anchor_parent: Vector3<f64>,
    /// The child's rotation relative to the parent where every joint reads 0.
    rest: Rotation3<f64>,
    /// `restᵀ · frame`, which the hinges' angles are read with.
    rest_frame: Matrix3<f64>,
    /// The ODE joints holding what no joint of the group allows.
    pub(crate) ball: Option<JointHandle>,
    pub(crate) lock_turns: Option<JointHandle>,
    pub(crate) lock_slides: Option<JointHandle>,
}

/// Orthonormal to within this.
const SQUARE: f64 = 1e-9;

fn bad_group(problem: String) -> Error {
    Error::Invalid { what: "a joint group", problem }
}

impl Scene {
    /// Makes `joints` between `object1` and `object2` as one group (see the module
    /// docs for what a group takes); returns their ids, in order.
    pub fn add_joint_group(
        &mut self,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        joints: &[GroupJoint],
    ) -> Result<Vec<JointId>> {
        let object2 = object2.into();
        let (child, parent) = self.group_bodies(object1, object2)?;
        check_group(joints, parent.is_some())?;
        let (child_pose, parent_pose) = self.group_poses(child, parent)?;
        let to_parent = parent_pose.rotation.to_rotation_matrix().inverse();
        let slides = joints.iter().take_while(|j| j.kind == JointType::Slider).count();
        let anchor = joints.get(slides).map_or(child_pose * Point3::origin(), |j| j.anchor);
        // Where every joint reads 0: the anchor back along the slides by their
        // references, the child turned back about the hinges by theirs.
        let slid: Vector3<f64> = joints[..slides].iter().map(|j| j.axis.normalize() * j.reference).sum();
        let turned = joints[slides..]
            .iter()
            .map(|j| Rotation3::from_axis_angle(&Unit::new_normalize(to_parent * j.axis), j.reference))
            .fold(Rotation3::identity(), |turned, r| turned * r);
        let rest = GroupRest {
            axes: joints.iter().map(|j| to_parent * j.axis.normalize()).collect(),
            anchor_child: (child_pose.inverse() * anchor).coords,
            anchor_parent: (parent_pose.inverse() * (anchor - slid)).coords,
            rest: (turned.inverse() * to_parent * child_pose.rotation.to_rotation_matrix()).into_inner(),
        };
        let named: Vec<(String, JointType, JointKind)> = joints
            .iter()
            .map(|j| {
                let creation = match j.kind {
                    JointType::Hinge => JointKind::Hinge { anchor: j.anchor, axis: j.axis },
                    _ => JointKind::Slider { axis: j.axis },
                };
                (j.name.clone(), j.kind, creation)
            })
            .collect();
        self.make_group(object1, object2, &named, rest)
    }

    /// The child's body and the parent's (`None`: the world).
    fn group_bodies(&self, object1: ObjectId, object2: JointEnd) -> Result<(BodyHandle, Option<BodyHandle>)> {
        let first = self.object(object1)?;
        let child =
            first.body_handle().ok_or_else(|| bad_group(format!("its first object {:?} has no body", first.name())))?;
        let parent = match object2 {
            JointEnd::World => None,
            JointEnd::Object(o) if o == object1 => {
                return Err(Error::SelfJoint { joint: "grouped", body: format!("object {:?}", first.name()) });
            }
            JointEnd::Object(o) => self.object(o)?.body_handle(),
        };
        Ok((child, parent))
    }

    /// Makes a group of the joints `named` (name, type, as created) whose geometry is
    /// `rest`: a new one, or one a scene file saved.
    pub(crate) fn make_group(
        &mut self,
        object1: ObjectId,
        object2: JointEnd,
        named: &[(String, JointType, JointKind)],
        rest: GroupRest,
    ) -> Result<Vec<JointId>> {
        let (child, parent) = self.group_bodies(object1, object2)?;
        if named.len() != rest.axes.len() {
            return Err(bad_group(format!("has {} joints and {} axes", named.len(), rest.axes.len())));
        }
        // A rotation (orthonormal, turning right-handed), kept as given: a group made
        // again from a scene file reads to the bit as the one saved.
        let m = rest.rest;
        let orthonormal = (m.transpose() * m - Matrix3::identity()).norm() < 1e-9 && m.determinant() > 0.0;
        let finite = m.iter().chain(rest.anchor_child.iter()).chain(rest.anchor_parent.iter()).all(|v| v.is_finite());
        if !(orthonormal && finite) {
            return Err(bad_group("needs a rotation and finite anchors where its joints read 0".into()));
        }
        let rotation = Rotation3::from_matrix_unchecked(m);
        // Its shape, checked in the parent's frame, where its geometry is.
        let joints: Vec<GroupJoint> = named
            .iter()
            .zip(&rest.axes)
            .map(|((name, kind, _), axis)| GroupJoint {
                name: name.clone(),
                kind: *kind,
                anchor: Point3::from(rest.anchor_parent),
                axis: *axis,
                reference: 0.0,
            })
            .collect();
        let shape = check_group(&joints, parent.is_some())?;
        for (i, (name, _, _)) in named.iter().enumerate() {
            let twice = named[..i].iter().any(|(other, _, _)| other == name);
            if !name.is_empty() && (twice || self.joint_names.get(name).is_ok()) {
                return Err(Error::DuplicateName { kind: "joint", name: name.clone() });
            }
        }
        let (child_pose, parent_pose) = self.group_poses(child, parent)?;
        let anchor = child_pose * Point3::from(rest.anchor_child);
        let joined = |b: JointBuilder| match parent {
            Some(p) => b.between(child, p),
            None => b.to_world(child),
        };
        let (ball, lock_turns, lock_slides) = self.make_group_locks(&shape, anchor, joined)?;
        let group = self.groups.len();
        let mut members = Vec::new();
        for (index, ((name, kind, creation), axis)) in named.iter().zip(&rest.axes).enumerate() {
            let axis = parent_pose.rotation * axis;
            let motor = match kind {
                JointType::Hinge => JointKind::AngularMotor { axes: vec![(AxisFrame::World, axis)] },
                _ => JointKind::LinearMotor { axes: vec![(AxisFrame::World, axis)] },
            };
            let handle = self.world.insert_joint(joined(JointBuilder::new(motor)).feedback())?;
            let other = match object2 {
                JointEnd::Object(o) => Some(o),
                JointEnd::World => None,
            };
            let member = GroupMember { group, index, motor: (0.0, 0.0), scale: f64::NAN };
            let id = self.name_joint(name, *kind, handle, (object1, other), creation.clone(), Some(member))?;
            members.push(id);
        }
        self.groups.push(JointGroup {
            members: members.clone(),
            child,
            parent,
            slides: shape.slides,
            normals: shape.normals,
            hinges: shape.hinges,
            frame: shape.frame,
            third_sign: shape.third_sign,
            anchor_child: rest.anchor_child,
            anchor_parent: rest.anchor_parent,
            rest: rotation,
            rest_frame: rotation.matrix().transpose() * shape.frame,
            ball,
            lock_turns,
            lock_slides,
        });
        // Its rows right from the start (a step of the world alone takes them as they are).
        self.hold_groups()?;
        Ok(members)
    }

    /// The ODE joints of a group of `shape` that hold what none of its joints allows:
    /// a ball at `anchor` (hinges only), the angular and the linear locks; `joined`
    /// attaches a joint to the group's two bodies.
    fn make_group_locks(
        &mut self,
        shape: &GroupShape,
        anchor: Point3<f64>,
        joined: impl Fn(JointBuilder) -> JointBuilder,
    ) -> Result<(Option<JointHandle>, Option<JointHandle>, Option<JointHandle>)> {
        let ball = if shape.slides.is_empty() {
            Some(self.world.insert_joint(joined(JointBuilder::ball(anchor)))?)
        } else {
            None
        };
        let mut lock = |kind: JointKind, n: usize| -> Result<Option<JointHandle>> {
            if n == 0 {
                return Ok(None);
            }
            let mut builder = JointBuilder::new(kind);
            for axis in 0..n {
                builder = builder.param(JointParam::MaxForce, axis, f64::INFINITY);
            }
            Ok(Some(self.world.insert_joint(joined(builder))?))
        };
        let turns = 3 - shape.hinges;
        // Without hinges the rotation is held about the frame's axes (the world's: a
        // group that slides joins the world), which never turn.
        let turn_axes = (shape.hinges..3).map(|i| (AxisFrame::World, shape.frame.column(i).into_owned())).collect();
        let lock_turns = lock(JointKind::AngularMotor { axes: turn_axes }, turns)?;
        let normal_count = if shape.slides.is_empty() { 0 } else { 3 - shape.slides.len() };
        let normals = shape.normals.iter().map(|n| (AxisFrame::World, *n)).collect();
        let lock_slides = lock(JointKind::LinearMotor { axes: normals }, normal_count)?;
        Ok((ball, lock_turns, lock_slides))
    }

    /// The geometry of the group `member` is one of, as a scene file saves it.
    pub(crate) fn group_rest(&self, member: GroupMember) -> Result<GroupRest> {
        let g = self.group(member.group)?;
        let mut axes = g.slides.clone();
        for h in 0..g.hinges {
            let sign = if h == 2 { g.third_sign } else { 1.0 };
            axes.push(g.frame.column(h) * sign);
        }
        Ok(GroupRest { axes, anchor_child: g.anchor_child, anchor_parent: g.anchor_parent, rest: g.rest.into_inner() })
    }

    /// The child's and the parent's poses (the world's frame without a parent).
    fn group_poses(&self, child: BodyHandle, parent: Option<BodyHandle>) -> Result<(Isometry3<f64>, Isometry3<f64>)> {
        let child = self.world.body(child)?.pose();
        let parent = match parent {
            Some(p) => self.world.body(p)?.pose(),
            None => Isometry3::identity(),
        };
        Ok((child, parent))
    }

    fn group(&self, index: usize) -> Result<&JointGroup> {
        self.groups.get(index).ok_or_else(|| bad_group(format!("group {index} is gone")))
    }

    /// Sets a member's speed motor: `speed` and `max_force` in the joint's units.
    pub(crate) fn set_member_motor(&mut self, id: JointId, speed: f64, max_force: f64) -> Result<()> {
        let d = self.joints.get_mut(id.0, JointId::KIND)?;
        if let Some(m) = d.member.as_mut() {
            m.motor = (speed, max_force);
            // Its ODE motor gets it, scaled, before the next step.
            m.scale = f64::NAN;
        }
        Ok(())
    }

    /// A member's stops were set unscaled: scaled again before the next step.
    pub(crate) fn rescale_member(&mut self, id: JointId) -> Result<()> {
        if let Some(m) = self.joints.get_mut(id.0, JointId::KIND)?.member.as_mut() {
            m.scale = f64::NAN;
        }
        Ok(())
    }

    /// Refuses a motor row (`what`) on a slide of a group that also turns: its row would
    /// hold the body's centre, not the anchor the slide moves (ODE's linear motor has
    /// no turning part).
    pub(crate) fn check_member_motor(&self, id: JointId, what: &str) -> Result<()> {
        let d = self.joint_data(id)?;
        let Some(member) = d.member else { return Ok(()) };
        let g = self.group(member.group)?;
        if member.index < g.slides.len() && g.hinges > 0 {
            return Err(Error::Invalid {
                what: "a joint of a group",
                problem: format!(
                    "{what} is not supported on slide {:?}: its group also turns (a planar body), and ODE's \
                     linear motor would hold the body's centre, not the point the slide moves",
                    d.name
                ),
            });
        }
        Ok(())
    }

    /// Removes the group of joint `id` with every joint in it (their sensors are the
    /// simulation's business).
    pub(crate) fn remove_group_of(&mut self, member: GroupMember) -> Result<Vec<JointId>> {
        let g = self.groups.remove(member.group);
        for later in &self.groups[member.group..] {
            for id in &later.members {
                if let Some(m) = self.joints.get_mut(id.0, JointId::KIND)?.member.as_mut() {
                    m.group -= 1;
                }
            }
        }
        for handle in [g.ball, g.lock_turns, g.lock_slides].into_iter().flatten() {
            self.world.remove_joint(handle)?;
        }
        // The stops' rows are made again by the next step's groups, if any are left.
        self.world.set_limit_rows(&[])?;
        Ok(g.members)
    }

    /// The ODE joints of every group besides its members' motors (saved with them).
    pub(crate) fn group_joints(&self) -> Vec<JointHandle> {
        self.groups.iter().flat_map(|g| [g.ball, g.lock_turns, g.lock_slides]).flatten().collect()
    }

    /// The members of the group `member` belongs to, in order.
    pub(crate) fn group_members(&self, member: GroupMember) -> Result<&[JointId]> {
        Ok(&self.group(member.group)?.members)
    }
}

/// Whether `joints` make a group (the second object being another object's body when
/// `has_parent`).
pub(crate) fn fits(joints: &[GroupJoint], has_parent: bool) -> bool {
    check_group(joints, has_parent).is_ok()
}

/// A group's shape, checked: its slides, the normals they leave, its hinges' frame and
/// anchor.
struct GroupShape {
    slides: Vec<Vector3<f64>>,
    normals: Vec<Vector3<f64>>,
    hinges: usize,
    frame: Matrix3<f64>,
    third_sign: f64,
}

/// Checks what a group takes (see the module docs) and works out its frame.
fn check_group(joints: &[GroupJoint], has_parent: bool) -> Result<GroupShape> {
    if joints.len() < 2 || joints.len() > 6 {
        return Err(bad_group(format!("takes 2 to 6 joints, got {}", joints.len())));
    }
    let mut axes = Vec::new();
    for j in joints {
        if !matches!(j.kind, JointType::Hinge | JointType::Slider) {
            return Err(bad_group(format!(
                "holds hinges and slides, not {} joint {:?}",
                j.kind.default_name(),
                j.name
            )));
        }
        limits::point("joint anchor", &j.anchor)?;
        limits::in_range("joint reference", j.reference, -limits::MAX_COORDINATE, limits::MAX_COORDINATE)?;
        let n = j.axis.norm();
        if !(n.is_finite() && n > 1e-12) {
            return Err(bad_group(format!("joint {:?} has no axis ({:?})", j.name, j.axis)));
        }
        axes.push(j.axis / n);
    }
    let slides = joints.iter().take_while(|j| j.kind == JointType::Slider).count();
    if joints[slides..].iter().any(|j| j.kind == JointType::Slider) {
        return Err(bad_group("takes its slides first, then its hinges".into()));
    }
    let hinges = joints.len() - slides;
    if slides > 3 || hinges > 3 {
        return Err(bad_group(format!("takes at most three slides and three hinges, got {slides} and {hinges}")));
    }
    let square =
        |v: &[Vector3<f64>]| v.iter().enumerate().all(|(i, a)| v[i + 1..].iter().all(|b| a.dot(b).abs() < SQUARE));
    let (slide_axes, hinge_axes) = (axes[..slides].to_vec(), axes[slides..].to_vec());
    if !square(&slide_axes) || !square(&hinge_axes) {
        return Err(bad_group("needs its slides' axes, and its hinges' axes, perpendicular to each other".into()));
    }
    let anchor = joints.get(slides).map_or(Point3::origin(), |j| j.anchor);
    for j in &joints[slides..] {
        if (j.anchor - anchor).norm() > 1e-9 * (1.0 + anchor.coords.norm()) {
            return Err(bad_group(format!("needs its hinges through one point: {:?} is not through {anchor}", j.name)));
        }
    }
    if slides > 0 && has_parent {
        return Err(bad_group("with slides, joins an object to the world only".into()));
    }
    let normals = match slides {
        1 => {
            let (u, v) = perpendiculars(&slide_axes[0]);
            vec![u, v]
        }
        2 => vec![slide_axes[0].cross(&slide_axes[1]).normalize()],
        _ => Vec::new(),
    };
    if slides == 1 && hinges > 0 {
        return Err(bad_group("with one slide, takes no hinge".into()));
    }
    if slides == 2 && (hinges > 1 || hinge_axes.iter().any(|a| a.cross(&normals[0]).norm() > SQUARE)) {
        return Err(bad_group("with two slides, takes one hinge at most, about the normal of their plane".into()));
    }
    // The hinges' axes, completed to a right-handed orthonormal frame.
    let first = hinge_axes.first().copied().unwrap_or_else(Vector3::x);
    let second = hinge_axes.get(1).copied().unwrap_or_else(|| perpendiculars(&first).0);
    let cross = first.cross(&second);
    let third_sign = match hinge_axes.get(2) {
        Some(a) if a.dot(&cross) < 0.0 => -1.0,
        _ => 1.0,
    };
    let frame = Matrix3::from_columns(&[first, second, cross]);
    Ok(GroupShape { slides: slide_axes, normals, hinges, frame, third_sign })
}

/// Two unit vectors perpendicular to unit `a` and to each other.
fn perpendiculars(a: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let pick = if a.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    let u = a.cross(&pick).normalize();
    (u, a.cross(&u))
}
