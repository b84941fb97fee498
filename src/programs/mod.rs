//! The programs of the thesis, as reusable [`Program`](crate::Program)s: the examples
//! run them headless, the tests check their numbers, the viewer shows them.

mod arm_model;
mod centrifugal_force;
mod conical_pendulum;
mod falling_ball;
mod falling_balls;
mod simple_arm;
mod thesis_table;
mod two_ball_laser;

pub use arm_model::{ArmParameters, ArmState, ReducedArmModel};
pub use centrifugal_force::{CentrifugalForce, CentrifugalRow};
pub use conical_pendulum::{ConicalPendulum, PendulumRow};
pub use falling_ball::{FallingBallSensors, HelloWorld};
pub use falling_balls::FallingBalls;
pub use simple_arm::{ArmParts, ControlRow, ControlledSimpleArm, SimpleArm, build_simple_arm};
pub use thesis_table::thesis_table;
pub use two_ball_laser::TwoBallLaser;
