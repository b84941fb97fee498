//! A ball's or a free joint's `damping` as MuJoCo integrates it: implicitly, the
//! damping force taken from the velocity at the end of the step, stable at any
//! coefficient (a hinge's or a slide's is the joint's own,
//! [`SimJoint::set_damping`](crate::SimJoint::set_damping), made the same way on the
//! motor that holds its armature: one row where two motors would be two).
//!
//! ARS's [`SimJoint::set_viscous_friction`](crate::SimJoint::set_viscous_friction) is
//! the original's explicit friction, from the velocity at the start of the step: it
//! diverges once `damping · dt` outgrows the inertia it acts on, which robot files do
//! all the time (damping 10 N·m·s/rad on a wrist of 3·10⁻⁴ kg·m² at dt 2.5 ms). Here an
//! ODE motor beside the joint, on the same bodies and about the same axes, holds their
//! relative velocity at 0 with constraint force mixing `1 / damping` and no force limit
//! (an infinite one: ODE's LCP factors such unbounded rows with the joints' own at once,
//! where a bounded row costs a pass of its own):
//! ODE then solves its force `λ = −damping · v` with the step's own velocities
//! (`λ = (target − J·v′) / CFM`), MuJoCo's `(M + h·D)·v′ = M·v + h·f`. The joint's own
//! motor stays free for its dry friction (`frictionloss`) and for speeds. A ball's or a
//! free joint's `frictionloss` (their ODE joints have no motor) is such a motor too,
//! at speed 0 with that force limit about each of three axes.

use nalgebra::Vector3;

use super::model::{Joint, JointKind};
use crate::error::Result;
use crate::handle::{BodyHandle, JointHandle};
use crate::scene::Scene;
use crate::world::joint::{AxisFrame, JointBuilder, JointKind as OdeJoint, JointParam};

/// What the motors beside a joint hold against its motion.
pub(super) enum Resisting {
    /// `damping`: a force proportional to the velocity at the end of the step.
    Damping(f64),
    /// `frictionloss` of a ball or free joint (a hinge's or a slide's is the joint's own
    /// dry friction): up to this force or torque about each axis.
    Friction(f64),
}

impl Scene {
    /// The motors beside an MJCF joint `j` (whose axis is `axis` in the simulation's
    /// frame) between `child` and `parent` (`None`: the world) that resist its motion:
    /// one for a hinge, a slide or a ball joint, two (linear and angular) for a free
    /// joint.
    pub(super) fn add_mjcf_joint_motors(
        &mut self,
        j: &Joint,
        axis: Vector3<f64>,
        child: BodyHandle,
        parent: Option<BodyHandle>,
        resisting: Resisting,
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
                builder = builder.param(JointParam::Velocity, axis, 0.0);
                builder = match resisting {
                    Resisting::Damping(damping) => builder.param(JointParam::MaxForce, axis, f64::INFINITY).param(
                        JointParam::Cfm,
                        axis,
                        1.0 / damping,
                    ),
                    Resisting::Friction(most) => builder.param(JointParam::MaxForce, axis, most),
                };
            }
            made.push(self.world_mut().insert_joint(builder)?);
        }
        Ok(made)
    }
}
