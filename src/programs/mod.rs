//! The programs of the thesis, as reusable [`Program`](crate::Program)s: the examples
//! run them headless, the tests check their numbers, the viewer shows them.

mod arm_model;
mod conical_pendulum;
mod falling_ball;
mod two_ball_laser;

pub use arm_model::{ArmParameters, ArmState, ReducedArmModel};
pub use conical_pendulum::{ConicalPendulum, PendulumRow};
pub use falling_ball::{FallingBallSensors, HelloWorld};
pub use two_ball_laser::TwoBallLaser;
