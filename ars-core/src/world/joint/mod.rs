//! Joints: their kinds, parameters and builder, and their creation and removal in a
//! world. A live joint is read and changed in `access`.

use nalgebra::{Point3, Vector3};
use ode_sys as ffi;
use serde::{Deserialize, Serialize};

use super::World;
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, JointHandle};
use crate::init::ensure_ode_ready;
use crate::limits;
use crate::validate;

use super::body::ExactPose;

mod access;

/// The frame an angular- or linear-motor axis is expressed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum AxisFrame {
    /// Fixed in the world.
    World = 0,
    /// Fixed to the first body.
    Body1 = 1,
    /// Fixed to the second body.
    Body2 = 2,
}

/// The kind of a joint, with its geometry (world coordinates, at creation time).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum JointKind {
    /// Locks the relative pose the bodies have when the joint is created.
    Fixed,
    /// One rotation about `axis` through `anchor` (ODE hinge).
    Hinge {
        /// Point on the axis, m.
        anchor: Point3<f64>,
        /// Rotation axis.
        axis: Vector3<f64>,
    },
    /// One translation along `axis`.
    Slider {
        /// Sliding axis.
        axis: Vector3<f64>,
    },
    /// Two rotations about perpendicular axes through `anchor`.
    Universal {
        /// Centre, m.
        anchor: Point3<f64>,
        /// First axis (fixed to body 1).
        axis1: Vector3<f64>,
        /// Second axis (fixed to body 2), perpendicular to the first.
        axis2: Vector3<f64>,
    },
    /// Ball and socket at `anchor`.
    Ball {
        /// Centre, m.
        anchor: Point3<f64>,
    },
    /// Steering axis and wheel axis (a car wheel).
    Hinge2 {
        /// Wheel centre, m.
        anchor: Point3<f64>,
        /// Steering axis (fixed to body 1).
        axis1: Vector3<f64>,
        /// Wheel axis (fixed to body 2).
        axis2: Vector3<f64>,
    },
    /// Translation along and rotation about `axis` through `anchor`.
    Piston {
        /// Point on the axis, m.
        anchor: Point3<f64>,
        /// Axis.
        axis: Vector3<f64>,
    },
    /// Angular motor (ODE AMotor, user mode) on up to three axes.
    AngularMotor {
        /// One to three axes, each in its frame.
        axes: Vec<(AxisFrame, Vector3<f64>)>,
    },
    /// Linear motor (ODE LMotor) on up to three axes.
    LinearMotor {
        /// One to three axes, each in its frame.
        axes: Vec<(AxisFrame, Vector3<f64>)>,
    },
}

impl JointKind {
    /// Short name of the kind, as used in error messages.
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Fixed => "fixed",
            JointKind::Hinge { .. } => "hinge",
            JointKind::Slider { .. } => "slider",
            JointKind::Universal { .. } => "universal",
            JointKind::Ball { .. } => "ball",
            JointKind::Hinge2 { .. } => "hinge-2",
            JointKind::Piston { .. } => "piston",
            JointKind::AngularMotor { .. } => "angular motor",
            JointKind::LinearMotor { .. } => "linear motor",
        }
    }

    /// Number of axes that take parameters (limits, motors; for a fixed or ball joint,
    /// one: its ERP and CFM).
    pub(crate) fn param_axes(&self) -> usize {
        match self {
            JointKind::Fixed | JointKind::Ball { .. } => 1,
            JointKind::Hinge { .. } | JointKind::Slider { .. } => 1,
            JointKind::Universal { .. } | JointKind::Hinge2 { .. } | JointKind::Piston { .. } => 2,
            JointKind::AngularMotor { axes } | JointKind::LinearMotor { axes } => axes.len(),
        }
    }

    /// The parameters each of its axes takes, in the order a snapshot keeps them.
    pub(crate) fn params(&self) -> &'static [JointParam] {
        match self {
            JointKind::Fixed | JointKind::Ball { .. } => &JointParam::FIXED,
            _ => &JointParam::ALL,
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        let anchor = |p: &Point3<f64>| limits::point("joint anchor", p).map(drop);
        let axis = |v: &Vector3<f64>| validate::direction("joint axis", v).map(drop);
        match self {
            JointKind::Fixed => Ok(()),
            JointKind::Hinge { anchor: a, axis: x } | JointKind::Piston { anchor: a, axis: x } => {
                anchor(a)?;
                axis(x)
            }
            JointKind::Slider { axis: x } => axis(x),
            JointKind::Ball { anchor: a } => anchor(a),
            JointKind::Universal { anchor: a, axis1, axis2 } => {
                anchor(a)?;
                axis(axis1)?;
                axis(axis2)?;
                // ODE keeps the two axes perpendicular by construction of its
                // constraint; axes that are not give a joint other than the one asked for.
                let (u, v) = (unit(axis1), unit(axis2));
                let cos = u.dot(&v);
                if cos.is_nan() || cos.abs() > 1e-6 {
                    return Err(Error::Invalid {
                        what: "universal joint axes",
                        problem: format!(
                            "must be perpendicular, the angle between them is {:.6}°",
                            cos.clamp(-1.0, 1.0).acos().to_degrees()
                        ),
                    });
                }
                Ok(())
            }
            JointKind::Hinge2 { anchor: a, axis1, axis2 } => {
                anchor(a)?;
                axis(axis1)?;
                axis(axis2)?;
                let sin = unit(axis1).cross(&unit(axis2)).norm();
                if sin.is_nan() || sin <= 1e-9 {
                    return Err(Error::Invalid { what: "hinge-2 joint axes", problem: "must not be parallel".into() });
                }
                Ok(())
            }
            JointKind::AngularMotor { axes } | JointKind::LinearMotor { axes } => {
                if axes.is_empty() || axes.len() > 3 {
                    return Err(Error::OutOfRange {
                        what: "the number of motor axes",
                        detail: format!("must be 1 to 3, got {}", axes.len()),
                    });
                }
                axes.iter().try_for_each(|(_, v)| axis(v))
            }
        }
    }
}

/// Creates an ODE joint of `kind` between `b1` and `b2` (null: the world) and sets its
/// anchors and axes from the bodies' poses as they are now. What
/// [`World::insert_joint`] does before the parameters, and what
/// [`World::restore_state`] does again.
///
/// # Safety
/// `w` is a live world; `b1` a live body of it, `b2` null or another live body of it;
/// `kind` is validated (and a hinge-2 joint has two bodies).
pub(crate) unsafe fn create_ode_joint(
    w: ffi::dWorldID,
    kind: &JointKind,
    b1: ffi::dBodyID,
    b2: ffi::dBodyID,
) -> ffi::dJointID {
    let g = std::ptr::null_mut();
    // SAFETY: (creation) the caller's contract; group 0 means "no group": the
    // caller owns the joint.
    let raw = unsafe {
        match kind {
            JointKind::Fixed => ffi::dJointCreateFixed(w, g),
            JointKind::Hinge { .. } => ffi::dJointCreateHinge(w, g),
            JointKind::Slider { .. } => ffi::dJointCreateSlider(w, g),
            JointKind::Universal { .. } => ffi::dJointCreateUniversal(w, g),
            JointKind::Ball { .. } => ffi::dJointCreateBall(w, g),
            JointKind::Hinge2 { .. } => ffi::dJointCreateHinge2(w, g),
            JointKind::Piston { .. } => ffi::dJointCreatePiston(w, g),
            JointKind::AngularMotor { .. } => ffi::dJointCreateAMotor(w, g),
            JointKind::LinearMotor { .. } => ffi::dJointCreateLMotor(w, g),
        }
    };
    // SAFETY: (geometry) the joint was just created with the kind matched below;
    // the caller's contract for the bodies and the kind.
    unsafe {
        ffi::dJointAttach(raw, b1, b2);
        match kind {
            JointKind::Fixed => ffi::dJointSetFixed(raw),
            JointKind::Hinge { anchor: a, axis: x } => {
                ffi::dJointSetHingeAnchor(raw, a.x, a.y, a.z);
                ffi::dJointSetHingeAxis(raw, x.x, x.y, x.z);
            }
            JointKind::Slider { axis: x } => ffi::dJointSetSliderAxis(raw, x.x, x.y, x.z),
            JointKind::Universal { anchor: a, axis1: x, axis2: y } => {
                ffi::dJointSetUniversalAnchor(raw, a.x, a.y, a.z);
                set_universal_axes(raw, x, y);
            }
            JointKind::Ball { anchor: a } => ffi::dJointSetBallAnchor(raw, a.x, a.y, a.z),
            JointKind::Hinge2 { anchor: a, axis1: x, axis2: y } => {
                ffi::dJointSetHinge2Anchor(raw, a.x, a.y, a.z);
                ffi::dJointSetHinge2Axes(raw, x.as_ptr(), y.as_ptr());
            }
            JointKind::Piston { anchor: a, axis: x } => {
                ffi::dJointSetPistonAnchor(raw, a.x, a.y, a.z);
                ffi::dJointSetPistonAxis(raw, x.x, x.y, x.z);
            }
            JointKind::AngularMotor { axes } => {
                ffi::dJointSetAMotorMode(raw, ffi::dAMotorUser as i32);
                ffi::dJointSetAMotorNumAxes(raw, axes.len() as i32);
                for (i, (frame, x)) in axes.iter().enumerate() {
                    ffi::dJointSetAMotorAxis(raw, i as i32, *frame as i32, x.x, x.y, x.z);
                }
            }
            JointKind::LinearMotor { axes } => {
                ffi::dJointSetLMotorNumAxes(raw, axes.len() as i32);
                for (i, (frame, x)) in axes.iter().enumerate() {
                    ffi::dJointSetLMotorAxis(raw, i as i32, *frame as i32, x.x, x.y, x.z);
                }
            }
        }
    }
    raw
}

/// Sets parameter `param` of axis `axis` of a joint of `kind` as given, unchecked
/// (what [`JointMut::set_param`] does once it has checked the value, and what a
/// snapshot's restore does with values read back from ODE).
///
/// # Safety
/// `raw` is a live joint of `kind`; `axis` is below the kind's parameter axes.
pub(crate) unsafe fn set_raw_param(raw: ffi::dJointID, kind: &JointKind, param: JointParam, axis: usize, value: f64) {
    let p = param.code() + (ffi::dParamGroup as i32) * axis as i32;
    // SAFETY: the caller's contract.
    unsafe {
        match kind {
            JointKind::Hinge { .. } => ffi::dJointSetHingeParam(raw, p, value),
            JointKind::Slider { .. } => ffi::dJointSetSliderParam(raw, p, value),
            JointKind::Universal { .. } => ffi::dJointSetUniversalParam(raw, p, value),
            JointKind::Hinge2 { .. } => ffi::dJointSetHinge2Param(raw, p, value),
            JointKind::Piston { .. } => ffi::dJointSetPistonParam(raw, p, value),
            JointKind::AngularMotor { .. } => ffi::dJointSetAMotorParam(raw, p, value),
            JointKind::LinearMotor { .. } => ffi::dJointSetLMotorParam(raw, p, value),
            JointKind::Fixed => ffi::dJointSetFixedParam(raw, p, value),
            JointKind::Ball { .. } => ffi::dJointSetBallParam(raw, p, value),
        }
    }
}

/// Sets a universal joint's axes so that no intermediate pair is parallel: ODE
/// recomputes the joint's reference rotations after each axis, from the new axis and
/// the other one as it stands, and with parallel axes it reads an uninitialised
/// matrix (seen by valgrind). The usual order (axis 1, then 2) is kept whenever it is
/// safe, so that results stay identical to plain ODE calls.
///
/// # Safety
/// `raw` is a live universal joint, attached; `u` and `v` are finite, non-zero and
/// perpendicular (checked by `JointKind::validate`).
unsafe fn set_universal_axes(raw: ffi::dJointID, u: &Vector3<f64>, v: &Vector3<f64>) {
    let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
    // SAFETY: the caller's contract; each array holds a dVector3.
    unsafe {
        ffi::dJointGetUniversalAxis1(raw, a.as_mut_ptr());
        ffi::dJointGetUniversalAxis2(raw, b.as_mut_ptr());
    }
    let parallel = |p: &Vector3<f64>, q: &[f64; 4]| unit(p).cross(&unit(&Vector3::new(q[0], q[1], q[2]))).norm() < 1e-6;
    let set1 = |w: &Vector3<f64>| {
        // SAFETY: the caller's contract.
        unsafe { ffi::dJointSetUniversalAxis1(raw, w.x, w.y, w.z) }
    };
    let set2 = |w: &Vector3<f64>| {
        // SAFETY: the caller's contract.
        unsafe { ffi::dJointSetUniversalAxis2(raw, w.x, w.y, w.z) }
    };
    if !parallel(u, &b) {
        set1(u);
        set2(v);
    } else if !parallel(v, &a) {
        set2(v);
        set1(u);
    } else {
        // u ∥ b and v ∥ a: pass through w ⟂ both.
        set2(&u.cross(v));
        set1(u);
        set2(v);
    }
}

/// `v` scaled to unit length without overflow (for checks only: ODE gets the axis as
/// given and normalises it itself).
fn unit(v: &Vector3<f64>) -> Vector3<f64> {
    let scaled = v / v.amax();
    scaled / scaled.norm()
}

/// A joint parameter of ODE (`dParam*`), set per axis with [`JointMut::set_param`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum JointParam {
    /// Low stop (angle in rad or position in m); must not exceed the high stop.
    LoStop,
    /// High stop.
    HiStop,
    /// Motor target velocity (rad/s or m/s).
    Velocity,
    /// Maximum motor force or torque (0 turns the motor off), at most
    /// [`MAX_FORCE`](crate::limits::MAX_FORCE), or `f64::INFINITY`: no limit, and a row
    /// that ODE's exact step solves with the joints' own at once (a bounded row takes a
    /// pass of the LCP of its own).
    MaxForce,
    /// Motor fudge factor.
    FudgeFactor,
    /// Bounciness of the stops.
    Bounce,
    /// Constraint force mixing along the axis when not at a stop.
    Cfm,
    /// ERP of the stops.
    StopErp,
    /// CFM of the stops.
    StopCfm,
    /// Error reduction of a fixed joint's three position rows, or of a ball joint's
    /// rows (ODE's `dParamERP`): the joint's own, the world's until set; the only
    /// parameters of those two kinds, with [`Cfm`](Self::Cfm). A fixed joint's three
    /// rotation rows keep the world's ERP and CFM (ODE has no parameter for them).
    Erp,
}

impl JointParam {
    /// Every parameter, in the order a snapshot keeps them.
    pub(crate) const ALL: [JointParam; 9] = [
        JointParam::LoStop,
        JointParam::HiStop,
        JointParam::Velocity,
        JointParam::MaxForce,
        JointParam::FudgeFactor,
        JointParam::Bounce,
        JointParam::Cfm,
        JointParam::StopErp,
        JointParam::StopCfm,
    ];

    /// The parameters of a fixed or ball joint (one "axis" of them), in the order a
    /// snapshot keeps them.
    pub(crate) const FIXED: [JointParam; 2] = [JointParam::Erp, JointParam::Cfm];

    /// Its name, as in errors ("setting the parameter Erp").
    fn name(self) -> &'static str {
        match self {
            JointParam::LoStop => "setting the parameter LoStop",
            JointParam::HiStop => "setting the parameter HiStop",
            JointParam::Velocity => "setting the parameter Velocity",
            JointParam::MaxForce => "setting the parameter MaxForce",
            JointParam::FudgeFactor => "setting the parameter FudgeFactor",
            JointParam::Bounce => "setting the parameter Bounce",
            JointParam::Cfm => "setting the parameter Cfm",
            JointParam::StopErp => "setting the parameter StopErp",
            JointParam::StopCfm => "setting the parameter StopCfm",
            JointParam::Erp => "setting the parameter Erp",
        }
    }

    fn code(self) -> i32 {
        (match self {
            JointParam::LoStop => ffi::dParamLoStop,
            JointParam::HiStop => ffi::dParamHiStop,
            JointParam::Velocity => ffi::dParamVel,
            JointParam::MaxForce => ffi::dParamFMax,
            JointParam::FudgeFactor => ffi::dParamFudgeFactor,
            JointParam::Bounce => ffi::dParamBounce,
            JointParam::Cfm => ffi::dParamCFM,
            JointParam::StopErp => ffi::dParamStopERP,
            JointParam::StopCfm => ffi::dParamStopCFM,
            JointParam::Erp => ffi::dParamERP,
        }) as i32
    }
}

/// Description of a joint to insert with [`World::insert_joint`].
///
/// ODE calls happen in this order: create, attach, set anchor and axes (or lock the
/// pose, for a fixed joint), set the parameters in the order given, enable feedback.
#[derive(Clone, Debug)]
#[must_use]
pub struct JointBuilder {
    kind: JointKind,
    body1: Option<BodyHandle>,
    body2: Option<BodyHandle>,
    params: Vec<(JointParam, usize, f64)>,
    feedback: bool,
}

impl JointBuilder {
    /// A joint of this kind; give its bodies with [`JointBuilder::between`] or
    /// [`JointBuilder::to_world`].
    pub fn new(kind: JointKind) -> Self {
        JointBuilder { kind, body1: None, body2: None, params: Vec::new(), feedback: false }
    }

    /// The kind, with the anchors and axes given.
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }
    /// A fixed joint.
    pub fn fixed() -> Self {
        Self::new(JointKind::Fixed)
    }
    /// A hinge.
    pub fn hinge(anchor: Point3<f64>, axis: Vector3<f64>) -> Self {
        Self::new(JointKind::Hinge { anchor, axis })
    }
    /// A slider.
    pub fn slider(axis: Vector3<f64>) -> Self {
        Self::new(JointKind::Slider { axis })
    }
    /// A universal joint.
    pub fn universal(anchor: Point3<f64>, axis1: Vector3<f64>, axis2: Vector3<f64>) -> Self {
        Self::new(JointKind::Universal { anchor, axis1, axis2 })
    }
    /// A ball joint (ball and socket).
    pub fn ball(anchor: Point3<f64>) -> Self {
        Self::new(JointKind::Ball { anchor })
    }
    /// A hinge-2 joint.
    pub fn hinge2(anchor: Point3<f64>, axis1: Vector3<f64>, axis2: Vector3<f64>) -> Self {
        Self::new(JointKind::Hinge2 { anchor, axis1, axis2 })
    }
    /// A piston joint.
    pub fn piston(anchor: Point3<f64>, axis: Vector3<f64>) -> Self {
        Self::new(JointKind::Piston { anchor, axis })
    }
    /// Connects `body1` and `body2`.
    pub fn between(mut self, body1: BodyHandle, body2: BodyHandle) -> Self {
        self.body1 = Some(body1);
        self.body2 = Some(body2);
        self
    }
    /// Connects `body` to the static world.
    pub fn to_world(mut self, body: BodyHandle) -> Self {
        self.body1 = Some(body);
        self.body2 = None;
        self
    }
    /// Sets a parameter on axis `axis` (0-based) after creation.
    pub fn param(mut self, param: JointParam, axis: usize, value: f64) -> Self {
        self.params.push((param, axis, value));
        self
    }
    /// Limits of the first axis (`low ≤ high`).
    pub fn limits(self, low: f64, high: f64) -> Self {
        self.param(JointParam::LoStop, 0, low).param(JointParam::HiStop, 0, high)
    }
    /// Velocity motor on the first axis.
    pub fn motor(self, velocity: f64, max_force: f64) -> Self {
        self.param(JointParam::Velocity, 0, velocity).param(JointParam::MaxForce, 0, max_force)
    }
    /// Records the constraint forces of every step (read with [`JointRef::feedback`]).
    pub fn feedback(mut self) -> Self {
        self.feedback = true;
        self
    }
}

pub(crate) struct JointData {
    pub(crate) raw: ffi::dJointID,
    pub(crate) kind: JointKind,
    pub(crate) body1: Option<BodyHandle>,
    pub(crate) body2: Option<BodyHandle>,
    pub(crate) feedback: Option<Box<ffi::dJointFeedback>>,
    /// Its place in the world's creation order (see [`World::next_serial`]).
    pub(crate) serial: u64,
    /// Where its bodies were when its anchors and axes were set: ODE keeps them in the
    /// bodies' frames then, so a joint made again with the bodies there is the same
    /// joint to the bit (see [`World::restore_state`]).
    pub(crate) reference: JointReference,
}

/// Forces and torques a joint applied on its bodies during the last step (world
/// frame, at each body's centre of mass).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointFeedback {
    /// Force on body 1, N.
    pub force1: Vector3<f64>,
    /// Torque on body 1, N·m.
    pub torque1: Vector3<f64>,
    /// Force on body 2 (zero when the joint is attached to the world), N.
    pub force2: Vector3<f64>,
    /// Torque on body 2, N·m.
    pub torque2: Vector3<f64>,
}

/// Read access to a joint, from [`World::joint`].
#[derive(Clone, Copy)]
pub struct JointRef<'w> {
    handle: JointHandle,
    data: &'w JointData,
}

/// Write access to a joint, from [`World::joint_mut`].
pub struct JointMut<'w> {
    handle: JointHandle,
    data: &'w mut JointData,
    /// The world's note that forces were added since the last step.
    forces_added: &'w mut bool,
}

impl World {
    /// Creates a joint.
    pub fn insert_joint(&mut self, builder: JointBuilder) -> Result<JointHandle> {
        self.check_usable()?;
        ensure_ode_ready();
        let kind_name = builder.kind.name();
        let body1 = builder.body1.ok_or_else(|| Error::Invalid {
            what: "a joint",
            problem: format!("needs a body (use `between` or `to_world`); this {kind_name} joint has none"),
        })?;
        let b1 = self.body_raw(body1)?;
        let b2 = match builder.body2 {
            Some(b) if b == body1 => {
                return Err(Error::SelfJoint { joint: kind_name, body: "a body".into() });
            }
            Some(b) => self.body_raw(b)?,
            None if matches!(builder.kind, JointKind::Hinge2 { .. }) => {
                // ODE asserts "joint can not be attached to just one body".
                return Err(Error::Invalid {
                    what: "a hinge-2 joint",
                    problem: "connects two bodies; it cannot be attached to the world".into(),
                });
            }
            None => std::ptr::null_mut(),
        };
        builder.kind.validate()?;
        for &(param, axis, value) in &builder.params {
            check_param(&builder.kind, param, axis, value)?;
        }
        check_stop_order(&builder.kind, &builder.params)?;

        // SAFETY: b1 is a live body, b2 null or another live body (looked up above).
        let reference = unsafe { JointReference::of(b1, b2) };
        // SAFETY: the world is live; the bodies are live, distinct, of this world (or
        // null for the world); the kind was validated above.
        let raw = unsafe { create_ode_joint(self.raw, &builder.kind, b1, b2) };
        let serial = self.next_serial();
        let data = JointData {
            raw,
            kind: builder.kind,
            body1: Some(body1),
            body2: builder.body2,
            feedback: None,
            serial,
            reference,
        };
        let handle = JointHandle(self.joints.insert(data));
        let mut joint = self.joint_mut(handle)?;
        for (param, axis, value) in builder.params {
            joint.set_param(param, axis, value)?;
        }
        if builder.feedback {
            joint.enable_feedback();
        }
        Ok(handle)
    }

    /// Removes a joint.
    pub fn remove_joint(&mut self, joint: JointHandle) -> Result<()> {
        self.check_usable()?;
        let data = self.joints.remove(joint.0, JointHandle::KIND)?;
        // SAFETY: the joint was created by this world and is destroyed once; its
        // feedback buffer is freed after it.
        unsafe { ffi::dJointDestroy(data.raw) };
        drop(data);
        Ok(())
    }

    /// Read access to a joint.
    pub fn joint(&self, joint: JointHandle) -> Result<JointRef<'_>> {
        Ok(JointRef { handle: joint, data: self.joints.get(joint.0, JointHandle::KIND)? })
    }

    /// Write access to a joint.
    #[inline]
    pub fn joint_mut(&mut self, joint: JointHandle) -> Result<JointMut<'_>> {
        self.check_usable()?;
        Ok(JointMut {
            handle: joint,
            data: self.joints.get_mut(joint.0, JointHandle::KIND)?,
            forces_added: &mut self.gate.forces_added,
        })
    }

    /// Every joint of the world, in slot order.
    pub fn joints(&self) -> impl Iterator<Item = JointHandle> + '_ {
        self.joints.iter().map(|(h, _)| JointHandle(h))
    }

    pub(crate) fn joints_of_body(&self, body: BodyHandle) -> Vec<JointHandle> {
        self.joints
            .iter()
            .filter(|(_, j)| j.body1 == Some(body) || j.body2 == Some(body))
            .map(|(h, _)| JointHandle(h))
            .collect()
    }
}

fn check_param(kind: &JointKind, param: JointParam, axis: usize, value: f64) -> Result<()> {
    let axes = kind.param_axes();
    if axis >= axes {
        return Err(Error::OutOfRange {
            what: "joint axis index",
            detail: format!(
                "must be below {axes} (the parameter axes of {}), got {axis}",
                crate::error::article(kind.name())
            ),
        });
    }
    if !kind.params().contains(&param) {
        return Err(Error::WrongJointKind { operation: param.name(), kind: kind.name() });
    }
    match param {
        JointParam::LoStop | JointParam::HiStop => {
            if value.is_nan() {
                return Err(Error::NotFinite { what: "joint stop", value: value.to_string() });
            }
        }
        JointParam::MaxForce => {
            // Infinity: a motor without a limit (ODE's unbounded row).
            if value != f64::INFINITY {
                limits::in_range("joint motor max force", value, 0.0, limits::MAX_FORCE)?;
            }
        }
        JointParam::Cfm | JointParam::StopCfm => {
            validate::non_negative("joint CFM", value)?;
        }
        JointParam::Erp | JointParam::StopErp | JointParam::FudgeFactor | JointParam::Bounce => {
            if !(0.0..=1.0).contains(&value) {
                return Err(Error::OutOfRange {
                    what: "joint parameter",
                    detail: format!("{param:?} must be in [0, 1], got {value}"),
                });
            }
        }
        JointParam::Velocity => {
            limits::in_range("joint motor velocity", value, -limits::MAX_SPEED, limits::MAX_SPEED)?;
        }
    }
    Ok(())
}

fn check_stop_order(kind: &JointKind, params: &[(JointParam, usize, f64)]) -> Result<()> {
    for axis in 0..kind.param_axes() {
        let last = |p| params.iter().rev().find(|(q, a, _)| *q == p && *a == axis).map(|(_, _, v)| *v);
        if let (Some(lo), Some(hi)) = (last(JointParam::LoStop), last(JointParam::HiStop))
            && lo > hi
        {
            return Err(Error::OutOfRange {
                what: "joint limits",
                detail: format!("must have low ≤ high, got low {lo} above high {hi}"),
            });
        }
    }
    Ok(())
}

/// Where a joint's bodies were when its anchors and axes were set.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct JointReference {
    pub(super) body1: ExactPose,
    pub(super) body2: Option<ExactPose>,
}

impl JointReference {
    /// The poses of `b1` and `b2` (null: the world) now.
    ///
    /// # Safety
    /// `b1` is a live body, `b2` null or a live body.
    pub(crate) unsafe fn of(b1: ffi::dBodyID, b2: ffi::dBodyID) -> JointReference {
        // SAFETY: the caller's contract.
        unsafe { JointReference { body1: ExactPose::of(b1), body2: (!b2.is_null()).then(|| ExactPose::of(b2)) } }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_motor_s_force_is_limited_within_max_force_or_unlimited() {
        let motor = JointKind::AngularMotor { axes: vec![(AxisFrame::Body1, nalgebra::Vector3::x())] };
        let check = |value| check_param(&motor, JointParam::MaxForce, 0, value);
        for fine in [0.0, 10.0, limits::MAX_FORCE, f64::INFINITY] {
            assert!(check(fine).is_ok(), "{fine}");
        }
        for bad in [-1.0, 2.0 * limits::MAX_FORCE, f64::NAN, f64::NEG_INFINITY] {
            assert!(check(bad).is_err(), "{bad}");
        }
    }

    /// A fixed or ball joint takes its own ERP (within [0, 1]) and CFM and nothing else;
    /// the other kinds have no ERP of their own.
    #[test]
    fn only_fixed_and_ball_joints_take_an_erp() {
        let ball = JointKind::Ball { anchor: Point3::origin() };
        for kind in [JointKind::Fixed, ball] {
            assert!(check_param(&kind, JointParam::Erp, 0, 0.05).is_ok());
            assert!(check_param(&kind, JointParam::Cfm, 0, 1e-5).is_ok());
            for bad in [-0.1, 1.5, f64::NAN] {
                assert!(check_param(&kind, JointParam::Erp, 0, bad).is_err(), "{bad}");
            }
            let err = check_param(&kind, JointParam::LoStop, 0, 0.0).unwrap_err().to_string();
            assert!(err.contains("LoStop") && err.contains("not available"), "{err}");
            assert!(check_param(&kind, JointParam::Erp, 1, 0.05).is_err(), "one axis");
        }
        let hinge = JointKind::Hinge { anchor: Point3::origin(), axis: Vector3::x() };
        assert!(check_param(&hinge, JointParam::Erp, 0, 0.05).is_err());
    }
}
