//! A joint's armature: inertia felt by the joint's own motion alone (a motor's rotor
//! seen through its gearbox; MuJoCo's `armature`), integrated implicitly as MuJoCo
//! integrates it.
//!
//! ODE moves bodies, not joint coordinates: it has no place for an inertia only the
//! joint's motion feels. An ODE motor beside the joint supplies it: an angular motor
//! about a hinge's axis (a linear one along a slider's) between the same bodies, with no
//! force limit, whose target speed is, each step, the joint's rate at the start of the
//! step, and whose constraint force mixing is `h / armature`. ODE then solves its force
//! `λ = (target − J·v′) / CFM = −armature · (v′ − v) / h` with the step's own
//! velocities: the armature resisting the change of the joint's rate, as MuJoCo's
//! `(M + A)·v′ = (M + A)·v + h·f` does in the joint's coordinate. Adding the armature
//! to the moving body's inertia instead would make it felt by every motion of that
//! body, and by no other: a light leg with a heavy armature becomes a flywheel that
//! turns its torso.

use nalgebra::Vector3;

use super::Scene;
use super::joints::{Armature, JointType};
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, JointHandle, JointId};
use crate::limits;
use crate::world::joint::{AxisFrame, JointBuilder, JointKind as OdeJoint, JointParam};

impl Scene {
    /// Gives joint `id` an armature of `inertia` (0: none); see the module docs.
    pub(super) fn set_joint_armature(&mut self, id: JointId, inertia: f64) -> Result<()> {
        if !(inertia.is_finite() && inertia >= 0.0) {
            return Err(Error::OutOfRange {
                what: "armature",
                detail: format!("must be finite and ≥ 0, got {inertia}"),
            });
        }
        let data = self.joint_data(id)?;
        let (kind, handle, existing) = (data.kind, data.handle, data.armature);
        if !matches!(kind, JointType::Hinge | JointType::Slider) {
            return Err(Error::WrongJointKind { operation: "an armature", kind: kind.default_name() });
        }
        let motor = match (existing, inertia > 0.0) {
            (Some(a), true) => a.motor,
            (Some(a), false) => {
                self.joints.get_mut(id.0, JointId::KIND)?.armature = None;
                self.update_driven(id);
                return self.world.remove_joint(a.motor);
            }
            (None, false) => return Ok(()),
            (None, true) => self.insert_armature_motor(handle, kind)?,
        };
        self.joints.get_mut(id.0, JointId::KIND)?.armature = Some(Armature { inertia, motor });
        self.update_driven(id);
        let rate = self.joint_state(id)?.rate;
        self.hold_armature(Armature { inertia, motor }, rate)
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

    /// Sets an armature's motor for the coming step, the joint turning at `rate` now.
    #[inline]
    pub(super) fn hold_armature(&mut self, armature: Armature, rate: f64) -> Result<()> {
        let h = self.time_step.get();
        let mut motor = self.world.joint_mut(armature.motor)?;
        motor.set_param(JointParam::Velocity, 0, rate.clamp(-limits::MAX_SPEED, limits::MAX_SPEED))?;
        motor.set_param(JointParam::Cfm, 0, (h / armature.inertia).min(1e30))
    }
}
