//! A joint's armature and damping, integrated implicitly as MuJoCo integrates them: an
//! armature is inertia felt by the joint's own motion alone (a motor's rotor seen
//! through its gearbox; MuJoCo's `armature`), damping a force against the joint's rate
//! taken at the end of the step (MuJoCo's `damping`, stable at any coefficient, where
//! [`SimJoint::set_viscous_friction`](crate::SimJoint::set_viscous_friction), the
//! original's, takes the rate at its start).
//!
//! ODE moves bodies, not joint coordinates: it has no place for an inertia only the
//! joint's motion feels. One ODE motor beside the joint supplies both: an angular motor
//! about a hinge's axis (a linear one along a slider's) between the same bodies, with no
//! force limit. For an armature `A` alone its target speed is, each step, the joint's
//! rate `v` at the start of the step, and its constraint force mixing `h / A`; ODE then
//! solves its force `λ = (target − J·v′) / CFM = −A · (v′ − v) / h` with the step's own
//! velocities: the armature resisting the change of the joint's rate, as MuJoCo's
//! `(M + A)·v′ = (M + A)·v + h·f` does in the joint's coordinate. For a damping `c`
//! alone its target is 0 and its CFM `1 / c`: `λ = −c · v′`, MuJoCo's
//! `(M + h·c)·v′ = M·v + h·f`. For both, the one row whose force is their sum,
//! `λ = −c · v′ − A · (v′ − v) / h`: CFM `1 / (c + A/h)`, target `(A/h) · v / (c + A/h)`
//! (one row where two motors would make two: an LCP row costs every step). Adding the
//! armature to the moving body's inertia instead would make it felt by every motion of
//! that body, and by no other: a light leg with a heavy armature becomes a flywheel that
//! turns its torso.

use nalgebra::Vector3;

use super::Scene;
use super::joints::{Armature, JointType};
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, JointHandle, JointId};
use crate::limits;
use crate::world::joint::{AxisFrame, JointBuilder, JointKind as OdeJoint, JointParam};

impl Scene {
    /// Gives joint `id` an armature of `inertia` (0: none), its damping kept; see the
    /// module docs.
    pub(super) fn set_joint_armature(&mut self, id: JointId, inertia: f64) -> Result<()> {
        let damping = self.joint_data(id)?.armature.map_or(0.0, |a| a.damping);
        self.set_joint_resistance(id, ("armature", "an armature"), inertia, damping)
    }

    /// Gives joint `id` an implicit damping of `damping` (0: none), its armature kept;
    /// see the module docs.
    pub(super) fn set_joint_damping(&mut self, id: JointId, damping: f64) -> Result<()> {
        let inertia = self.joint_data(id)?.armature.map_or(0.0, |a| a.inertia);
        self.set_joint_resistance(id, ("damping", "damping"), inertia, damping)
    }

    /// Sets joint `id`'s armature and damping, making or removing the motor that holds
    /// them; `(what, operation)` name the one the caller sets in errors.
    fn set_joint_resistance(
        &mut self,
        id: JointId,
        (what, operation): (&'static str, &'static str),
        inertia: f64,
        damping: f64,
    ) -> Result<()> {
        for value in [inertia, damping] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::OutOfRange { what, detail: format!("must be finite and ≥ 0, got {value}") });
            }
        }
        let data = self.joint_data(id)?;
        let (kind, handle, existing) = (data.kind, data.handle, data.armature);
        if !matches!(kind, JointType::Hinge | JointType::Slider) {
            return Err(Error::WrongJointKind { operation, kind: kind.default_name() });
        }
        if inertia > 0.0 || damping > 0.0 {
            self.check_member_motor(id, operation)?;
        }
        let motor = match (existing, inertia > 0.0 || damping > 0.0) {
            (Some(a), true) => a.motor,
            (Some(a), false) => {
                self.joints.get_mut(id.0, JointId::KIND)?.armature = None;
                self.update_driven(id);
                return self.world.remove_joint(a.motor);
            }
            (None, false) => return Ok(()),
            (None, true) => self.insert_armature_motor(handle, kind)?,
        };
        let armature = Armature { inertia, damping, motor };
        self.joints.get_mut(id.0, JointId::KIND)?.armature = Some(armature);
        self.update_driven(id);
        let rate = self.joint_state(id)?.rate;
        self.hold_armature(armature, rate)
    }

    /// The motor about (along) the axis of the joint `handle`, between its bodies.
    fn insert_armature_motor(&mut self, handle: JointHandle, kind: JointType) -> Result<JointHandle> {
        let joint = self.world.joint(handle)?;
        let axis: Vector3<f64> = joint.axis()?;
        let (body1, body2): (Option<BodyHandle>, Option<BodyHandle>) = joint.bodies();
        let axes = vec![(AxisFrame::Body1, axis)];
        let motor = match kind {
            JointType::Hinge => OdeJoint::AngularMotor { axes },
            _ => OdeJoint::LinearMotor { axes },
        };
        let builder = JointBuilder::new(motor).param(JointParam::MaxForce, 0, f64::INFINITY);
        let builder = match (body1, body2) {
            (Some(a), Some(b)) => builder.between(a, b),
            (Some(a), None) => builder.to_world(a),
            (None, Some(b)) => builder.to_world(b),
            (None, None) => {
                return Err(Error::Invalid { what: "an armature", problem: "its joint joins no body".into() });
            }
        };
        self.world.insert_joint(builder)
    }

    /// Sets an armature's (and damping's) motor for the coming step, the joint turning
    /// at `rate` now.
    #[inline]
    pub(super) fn hold_armature(&mut self, armature: Armature, rate: f64) -> Result<()> {
        self.hold_scaled_armature(armature, rate, 1.0)
    }

    /// [`hold_armature`](Self::hold_armature) on a motor whose unit row is the joint's
    /// rate divided by `scale` (a joint group's dual axis, its force the joint's times
    /// `scale`): target divided by `scale`, CFM by `scale²`.
    pub(super) fn hold_scaled_armature(&mut self, armature: Armature, rate: f64, scale: f64) -> Result<()> {
        let h = self.time_step.get();
        let rate = rate.clamp(-limits::MAX_SPEED, limits::MAX_SPEED);
        let Armature { inertia, damping, .. } = armature;
        let (target, cfm) = if damping == 0.0 {
            (rate, h / inertia)
        } else if inertia == 0.0 {
            (0.0, 1.0 / damping)
        } else {
            let k = inertia / h;
            (k * rate / (damping + k), 1.0 / (damping + k))
        };
        let (target, cfm) = if scale == 1.0 { (target, cfm) } else { (target / scale, cfm / (scale * scale)) };
        let mut motor = self.world.joint_mut(armature.motor)?;
        motor.set_param(JointParam::Velocity, 0, target.clamp(-limits::MAX_SPEED, limits::MAX_SPEED))?;
        motor.set_param(JointParam::Cfm, 0, cfm.min(1e30))
    }
}
