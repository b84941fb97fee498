//! A live joint read and changed through [`JointRef`] and [`JointMut`]: angles,
//! rates, limits, motors, efforts and feedback forces.

use nalgebra::{Point3, Vector3};
use ode_sys as ffi;

use super::{JointFeedback, JointKind, JointMut, JointParam, JointRef, check_param, set_raw_param};
use crate::convert;
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, JointHandle};
use crate::limits;

macro_rules! joint_getters {
    () => {
        /// The handle of this joint.
        pub fn handle(&self) -> JointHandle {
            self.handle
        }

        /// Its kind and creation geometry.
        pub fn kind(&self) -> &JointKind {
            &self.data.kind
        }

        /// The bodies it connects (`None` is the static world).
        pub fn bodies(&self) -> (Option<BodyHandle>, Option<BodyHandle>) {
            (self.data.body1, self.data.body2)
        }

        fn wrong(&self, operation: &'static str) -> Error {
            Error::WrongJointKind { operation, kind: self.data.kind.name() }
        }

        /// Angle of a hinge (first axis of a universal or hinge-2, rotation of a
        /// piston), rad, zero at creation, positive when body 1 turns positively about
        /// the axis relative to body 2.
        pub fn angle(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Hinge { .. } => ffi::dJointGetHingeAngle(j),
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAngle1(j),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Angle1(j),
                    JointKind::Piston { .. } => ffi::dJointGetPistonAngle(j),
                    _ => return Err(self.wrong("angle")),
                }
            })
        }

        /// Rate of [`angle`](Self::angle), rad/s.
        pub fn angle_rate(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Hinge { .. } => ffi::dJointGetHingeAngleRate(j),
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAngle1Rate(j),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Angle1Rate(j),
                    JointKind::Piston { .. } => ffi::dJointGetPistonAngleRate(j),
                    _ => return Err(self.wrong("angle rate")),
                }
            })
        }

        /// Second angle of a universal or hinge-2 joint, rad.
        pub fn angle2(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAngle2(j),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Angle2(j),
                    _ => return Err(self.wrong("second angle")),
                }
            })
        }

        /// Rate of the second angle of a universal or hinge-2 joint, rad/s.
        pub fn angle2_rate(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAngle2Rate(j),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Angle2Rate(j),
                    _ => return Err(self.wrong("second angle rate")),
                }
            })
        }

        /// Position of a slider or piston along its axis, m, zero at creation.
        pub fn position(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Slider { .. } => ffi::dJointGetSliderPosition(j),
                    JointKind::Piston { .. } => ffi::dJointGetPistonPosition(j),
                    _ => return Err(self.wrong("position")),
                }
            })
        }

        /// Rate of [`position`](Self::position), m/s.
        pub fn position_rate(&self) -> Result<f64> {
            let j = self.data.raw;
            // SAFETY: the joint is live and of the kind matched.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Slider { .. } => ffi::dJointGetSliderPositionRate(j),
                    JointKind::Piston { .. } => ffi::dJointGetPistonPositionRate(j),
                    _ => return Err(self.wrong("position rate")),
                }
            })
        }

        /// Current world anchor (on body 1) of a hinge, universal, ball, hinge-2 or piston.
        pub fn anchor(&self) -> Result<Point3<f64>> {
            let j = self.data.raw;
            let mut a = [0.0; 4];
            // SAFETY: the joint is live and of the kind matched; `a` holds a dVector3.
            unsafe {
                match self.data.kind {
                    JointKind::Hinge { .. } => ffi::dJointGetHingeAnchor(j, a.as_mut_ptr()),
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAnchor(j, a.as_mut_ptr()),
                    JointKind::Ball { .. } => ffi::dJointGetBallAnchor(j, a.as_mut_ptr()),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Anchor(j, a.as_mut_ptr()),
                    JointKind::Piston { .. } => ffi::dJointGetPistonAnchor(j, a.as_mut_ptr()),
                    _ => return Err(self.wrong("anchor")),
                }
            }
            Ok(convert::point_from_ode(&a))
        }

        /// Current world direction of the (first) axis of a hinge, slider, universal,
        /// hinge-2, piston or motor.
        pub fn axis(&self) -> Result<Vector3<f64>> {
            let j = self.data.raw;
            let mut a = [0.0; 4];
            // SAFETY: the joint is live and of the kind matched; `a` holds a dVector3.
            unsafe {
                match self.data.kind {
                    JointKind::Hinge { .. } => ffi::dJointGetHingeAxis(j, a.as_mut_ptr()),
                    JointKind::Slider { .. } => ffi::dJointGetSliderAxis(j, a.as_mut_ptr()),
                    JointKind::Universal { .. } => ffi::dJointGetUniversalAxis1(j, a.as_mut_ptr()),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Axis1(j, a.as_mut_ptr()),
                    JointKind::Piston { .. } => ffi::dJointGetPistonAxis(j, a.as_mut_ptr()),
                    JointKind::AngularMotor { .. } => ffi::dJointGetAMotorAxis(j, 0, a.as_mut_ptr()),
                    JointKind::LinearMotor { .. } => ffi::dJointGetLMotorAxis(j, 0, a.as_mut_ptr()),
                    _ => return Err(self.wrong("axis")),
                }
            }
            Ok(convert::vector_from_ode(&a))
        }

        /// A parameter of axis `axis` (0-based).
        pub fn param(&self, param: JointParam, axis: usize) -> Result<f64> {
            check_param(&self.data.kind, param, axis, 0.0).or_else(|e| match e {
                Error::OutOfRange { what: "joint axis index", .. } | Error::WrongJointKind { .. } => Err(e),
                _ => Ok(()),
            })?;
            let j = self.data.raw;
            let p = param.code() + (ffi::dParamGroup as i32) * axis as i32;
            // SAFETY: the joint is live and of the kind matched; the axis index is in range.
            Ok(unsafe {
                match self.data.kind {
                    JointKind::Hinge { .. } => ffi::dJointGetHingeParam(j, p),
                    JointKind::Slider { .. } => ffi::dJointGetSliderParam(j, p),
                    JointKind::Universal { .. } => ffi::dJointGetUniversalParam(j, p),
                    JointKind::Hinge2 { .. } => ffi::dJointGetHinge2Param(j, p),
                    JointKind::Piston { .. } => ffi::dJointGetPistonParam(j, p),
                    JointKind::AngularMotor { .. } => ffi::dJointGetAMotorParam(j, p),
                    JointKind::LinearMotor { .. } => ffi::dJointGetLMotorParam(j, p),
                    JointKind::Fixed => ffi::dJointGetFixedParam(j, p),
                    JointKind::Ball { .. } => ffi::dJointGetBallParam(j, p),
                }
            })
        }

        /// Constraint forces of the last step, when feedback was enabled.
        pub fn feedback(&self) -> Option<JointFeedback> {
            self.data.feedback.as_ref().map(|f| JointFeedback {
                force1: convert::vector_from_ode(&f.f1),
                torque1: convert::vector_from_ode(&f.t1),
                force2: convert::vector_from_ode(&f.f2),
                torque2: convert::vector_from_ode(&f.t2),
            })
        }
    };
}

impl JointRef<'_> {
    joint_getters!();
}

impl JointMut<'_> {
    joint_getters!();

    /// Sets a parameter of axis `axis` (0-based).
    pub fn set_param(&mut self, param: JointParam, axis: usize, value: f64) -> Result<()> {
        check_param(&self.data.kind, param, axis, value)?;
        let lo_hi_conflict = match param {
            JointParam::LoStop => self.param(JointParam::HiStop, axis)? < value,
            JointParam::HiStop => self.param(JointParam::LoStop, axis)? > value,
            _ => false,
        };
        if lo_hi_conflict {
            return Err(Error::OutOfRange {
                what: "joint limits",
                detail: format!("must not cross: {param:?} {value} would cross the other stop (set_limits moves both)"),
            });
        }
        // SAFETY: the joint is live and of its kind; axis and value checked.
        unsafe { set_raw_param(self.data.raw, &self.data.kind, param, axis, value) };
        Ok(())
    }

    /// Sets both stops of axis `axis` (`low ≤ high`; ±∞ for none).
    ///
    /// ODE quirk, kept as is: on a rotational axis ODE tests the stops only while one
    /// of them lies within ±π. An axis that rests at a stop and then gets stops beyond
    /// ±π (or ±∞) stays "at the stop" (a motor on it then pushes without its speed
    /// limit). To free such an axis, widen its stops to just inside ±π (for example
    /// ±3.1) rather than removing them.
    pub fn set_limits(&mut self, axis: usize, low: f64, high: f64) -> Result<()> {
        if low.is_nan() || high.is_nan() || low > high {
            return Err(Error::OutOfRange {
                what: "joint limits",
                detail: format!("must have low ≤ high, got [{low}, {high}]"),
            });
        }
        // Widen first so that neither intermediate state crosses.
        self.set_param(JointParam::LoStop, axis, f64::NEG_INFINITY)?;
        self.set_param(JointParam::HiStop, axis, f64::INFINITY)?;
        self.set_param(JointParam::LoStop, axis, low)?;
        self.set_param(JointParam::HiStop, axis, high)
    }

    /// Drives axis `axis` towards `velocity` with at most `max_force` (N or N·m);
    /// `max_force = 0` turns the motor off.
    pub fn set_motor(&mut self, axis: usize, velocity: f64, max_force: f64) -> Result<()> {
        self.set_param(JointParam::MaxForce, axis, max_force)?;
        self.set_param(JointParam::Velocity, axis, velocity)
    }

    /// Adds a torque about the axis of a hinge (about the first axis of a universal or
    /// hinge-2, about a piston's axis), for the next step: `+torque·axis` on body 1,
    /// `−torque·axis` on body 2.
    #[inline]
    pub fn add_torque(&mut self, torque: f64) -> Result<()> {
        limits::in_range("joint torque", torque, -limits::MAX_TORQUE, limits::MAX_TORQUE)?;
        *self.forces_added = true;
        let j = self.data.raw;
        // SAFETY: the joint is live and of the kind matched.
        unsafe {
            match self.data.kind {
                JointKind::Hinge { .. } => ffi::dJointAddHingeTorque(j, torque),
                JointKind::Universal { .. } => ffi::dJointAddUniversalTorques(j, torque, 0.0),
                JointKind::Hinge2 { .. } => ffi::dJointAddHinge2Torques(j, torque, 0.0),
                JointKind::AngularMotor { .. } => ffi::dJointAddAMotorTorques(j, torque, 0.0, 0.0),
                _ => return Err(self.wrong("adding a torque")),
            }
        }
        Ok(())
    }

    /// Adds torques about both axes of a universal or hinge-2 joint.
    pub fn add_torques(&mut self, torque1: f64, torque2: f64) -> Result<()> {
        limits::in_range("joint torque", torque1, -limits::MAX_TORQUE, limits::MAX_TORQUE)?;
        limits::in_range("joint torque", torque2, -limits::MAX_TORQUE, limits::MAX_TORQUE)?;
        *self.forces_added = true;
        let j = self.data.raw;
        // SAFETY: the joint is live and of the kind matched.
        unsafe {
            match self.data.kind {
                JointKind::Universal { .. } => ffi::dJointAddUniversalTorques(j, torque1, torque2),
                JointKind::Hinge2 { .. } => ffi::dJointAddHinge2Torques(j, torque1, torque2),
                _ => return Err(self.wrong("adding two torques")),
            }
        }
        Ok(())
    }

    /// Adds a force along the axis of a slider or piston, for the next step:
    /// `+force·axis` on body 1, `−force·axis` on body 2.
    #[inline]
    pub fn add_force(&mut self, force: f64) -> Result<()> {
        limits::in_range("joint force", force, -limits::MAX_FORCE, limits::MAX_FORCE)?;
        *self.forces_added = true;
        let j = self.data.raw;
        // SAFETY: the joint is live and of the kind matched.
        unsafe {
            match self.data.kind {
                JointKind::Slider { .. } => ffi::dJointAddSliderForce(j, force),
                JointKind::Piston { .. } => ffi::dJointAddPistonForce(j, force),
                JointKind::LinearMotor { .. } => return Err(self.wrong("adding a force (use a motor velocity)")),
                _ => return Err(self.wrong("adding a force")),
            }
        }
        Ok(())
    }

    /// Turns axis `index` of an angular or linear motor to the world direction `axis`
    /// (ODE keeps it as a unit vector, in the world's frame from now on), for the
    /// motors whose rows follow a changing direction (a joint group's, each step).
    pub fn set_motor_axis(&mut self, index: usize, axis: Vector3<f64>) -> Result<()> {
        let count = match &self.data.kind {
            JointKind::AngularMotor { axes } | JointKind::LinearMotor { axes } => axes.len(),
            _ => return Err(self.wrong("turning a motor axis")),
        };
        if index >= count {
            return Err(Error::OutOfRange { what: "motor axis", detail: format!("{index} of {count}") });
        }
        let length = axis.norm();
        if !(length.is_finite() && length > 1e-12) {
            return Err(Error::OutOfRange {
                what: "motor axis",
                detail: format!("must be finite and not zero, got {axis:?}"),
            });
        }
        let (j, x) = (self.data.raw, axis / length);
        // SAFETY: the joint is live and of the kind matched; the index is below its
        // number of axes; the direction is a finite unit vector (rel 0: the world).
        unsafe {
            match self.data.kind {
                JointKind::AngularMotor { .. } => ffi::dJointSetAMotorAxis(j, index as i32, 0, x.x, x.y, x.z),
                _ => ffi::dJointSetLMotorAxis(j, index as i32, 0, x.x, x.y, x.z),
            }
        }
        Ok(())
    }

    /// Sets the angle ODE tests the stops of axis `index` of an angular motor against
    /// (its user mode: ODE does not measure it).
    pub fn set_motor_angle(&mut self, index: usize, angle: f64) -> Result<()> {
        let JointKind::AngularMotor { axes } = &self.data.kind else {
            return Err(self.wrong("setting a motor angle"));
        };
        if index >= axes.len() {
            return Err(Error::OutOfRange { what: "motor axis", detail: format!("{index} of {}", axes.len()) });
        }
        limits::in_range("motor angle", angle, -limits::MAX_COORDINATE, limits::MAX_COORDINATE)?;
        // SAFETY: the joint is a live angular motor; the index is below its number of
        // axes and the angle finite.
        unsafe { ffi::dJointSetAMotorAngle(self.data.raw, index as i32, angle) };
        Ok(())
    }

    /// Starts recording the constraint forces (see [`JointRef::feedback`]).
    pub fn enable_feedback(&mut self) {
        if self.data.feedback.is_none() {
            let mut buf = Box::new(ffi::dJointFeedback::default());
            // SAFETY: the joint is live; the buffer is boxed (stable address) and kept
            // in the joint's data, which outlives the ODE joint (dropped after it).
            unsafe { ffi::dJointSetFeedback(self.data.raw, &mut *buf) };
            self.data.feedback = Some(buf);
        }
    }
}
