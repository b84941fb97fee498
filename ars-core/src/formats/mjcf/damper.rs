//! A joint's `damping` as MuJoCo integrates it: implicitly, the damping force taken
//! from the velocity at the end of the step, stable at any coefficient.
//!
//! ARS's [`SimJoint::set_viscous_friction`](crate::SimJoint::set_viscous_friction) is
//! the original's explicit friction, from the velocity at the start of the step: it
//! diverges once `damping · dt` outgrows the inertia it acts on, which robot files do
//! all the time (damping 10 N·m·s/rad on a wrist of 3·10⁻⁴ kg·m² at dt 2.5 ms). Here an
//! ODE motor beside the joint, on the same bodies and about the same axes, holds their
//! relative velocity at 0 with constraint force mixing `1 / damping` and no force limit:
//! ODE then solves its force `λ = −damping · v` with the step's own velocities
//! (`λ = (target − J·v′) / CFM`), MuJoCo's `(M + h·D)·v′ = M·v + h·f`. The joint's own
//! motor stays free for its dry friction (`frictionloss`) and for speeds.

use nalgebra::Vector3;

use super::model::{Joint, JointKind};
use crate::error::Result;
use crate::handle::{BodyHandle, JointHandle};
use crate::limits;
use crate::scene::Scene;
use crate::world::joint::{AxisFrame, JointBuilder, JointKind as OdeJoint, JointParam};

impl Scene {
    /// The motors that damp `joint` (of the MJCF joint `j`, whose axis is `axis` in the
    /// simulation's frame) between `child` and `parent` (`None`: the world): one for a
    /// hinge, a slide or a ball joint, two (linear and angular) for a free joint.
    pub(super) fn add_mjcf_damper(
        &mut self,
        j: &Joint,
        axis: Vector3<f64>,
        child: BodyHandle,
        parent: Option<BodyHandle>,
    ) -> Result<Vec<JointHandle>> {
        let along = |a: Vector3<f64>| vec![(AxisFrame::Body1, a)];
        let every = || {
            vec![(AxisFrame::Body1, Vector3::x()), (AxisFrame::Body1, Vector3::y()), (AxisFrame::Body1, Vector3::z())]
        };
        let motors = match j.kind {
            JointKind::Hinge => vec![OdeJoint::AngularMotor { axes: along(axis) }],
            JointKind::Slide => vec![OdeJoint::LinearMotor { axes: along(axis) }],
            JointKind::Ball => vec![OdeJoint::AngularMotor { axes: every() }],
            JointKind::Free => vec![OdeJoint::LinearMotor { axes: every() }, OdeJoint::AngularMotor { axes: every() }],
        };
        let mut made = Vec::new();
        for kind in motors {
            let mut builder = JointBuilder::new(kind.clone());
            builder = match parent {
                Some(p) => builder.between(child, p),
                None => builder.to_world(child),
            };
            for axis in 0..kind.param_axes() {
                builder = builder
                    .param(JointParam::MaxForce, axis, limits::MAX_FORCE)
                    .param(JointParam::Velocity, axis, 0.0)
                    .param(JointParam::Cfm, axis, 1.0 / j.damping);
            }
            made.push(self.world_mut().insert_joint(builder)?);
        }
        Ok(made)
    }
}
