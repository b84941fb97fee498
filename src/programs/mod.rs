//! The programs of the thesis, as reusable [`Program`](crate::Program)s: the examples
//! run them headless, the tests check their numbers, the viewer shows them.

mod arm_model;
mod bouncing_ball;
mod centrifugal_force;
mod conical_pendulum;
mod convoy;
mod falling_ball;
mod falling_balls;
mod iros;
mod simple_arm;
mod thesis_table;
mod two_ball_laser;
mod vehicle_programs;
mod vehicles;

pub use arm_model::{ArmParameters, ArmState, ReducedArmModel};
pub use bouncing_ball::BouncingBall;
pub use centrifugal_force::{CentrifugalForce, CentrifugalRow};
pub use conical_pendulum::{ConicalPendulum, PendulumRow};
pub use convoy::Convoy;
pub use falling_ball::{FallingBallSensors, HelloWorld};
pub use falling_balls::FallingBalls;
pub use iros::{DrivingRow, SinusoidalTerrain, SpeedProfile, SpeedProfileRow, TerrainRow, TrackingError, UserDriven};
pub use simple_arm::{ArmParts, ControlRow, ControlledSimpleArm, SimpleArm, build_simple_arm};
pub use thesis_table::thesis_table;
pub use two_ball_laser::TwoBallLaser;
pub use vehicle_programs::{Vehicle1, Vehicle2, VehicleWithArm, VehicleWithControlledArm, WAIST_TORQUE, WHEEL_TORQUE};
pub use vehicles::{
    VehicleArm, VehicleParts, VehicleSpec, build_mobile_manipulator, build_vehicle, build_vehicle_arm,
    signed_ground_speed,
};

/// Programs whose shoulder set-point the 'd' and 'c' keys move, as in the original.
pub trait ShoulderSetpoint {
    /// The set-point, rad.
    fn setpoint_mut(&mut self) -> &mut f64;
}

/// Binds 'd' (raise) and 'c' (lower) to a program's shoulder set-point.
pub(crate) trait SetpointKeys {
    fn add_setpoint_keys(self, step: f64) -> Self;
}

impl<P: ShoulderSetpoint + 'static> SetpointKeys for ars_core::ActionMap<P> {
    fn add_setpoint_keys(self, step: f64) -> Self {
        use ars_core::{Key, Repeat};
        self.add(
            Key::Char('d'),
            move |p: &mut P, _| {
                *p.setpoint_mut() += step;
                Ok(())
            },
            Repeat::Once,
        )
        .add(
            Key::Char('c'),
            move |p: &mut P, _| {
                *p.setpoint_mut() -= step;
                Ok(())
            },
            Repeat::Once,
        )
    }
}
