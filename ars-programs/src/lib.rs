//! The programs of the thesis, as reusable [`Program`](ars_core::Program)s: the examples
//! run them headless, the tests check their numbers, the viewer shows them.

mod arm_model;
mod bouncing_ball;
mod centrifugal_force;
mod conical_pendulum;
mod convoy;
mod falling_ball;
mod falling_balls;
pub mod golden;
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

/// Programs whose shoulder is held by a [`PositionServo`](ars_core::PositionServo),
/// whose set-point the 'd' and 'c' keys move, as in the original.
pub trait ShoulderSetpoint {
    /// The shoulder joint (once built).
    fn shoulder(&self) -> Option<ars_core::JointId>;
}

/// Binds 'd' (raise) and 'c' (lower) to a program's shoulder set-point.
pub(crate) trait SetpointKeys {
    fn add_setpoint_keys(self, step: f64) -> Self;
}

impl<P: ShoulderSetpoint + 'static> SetpointKeys for ars_core::ActionMap<P> {
    fn add_setpoint_keys(self, step: f64) -> Self {
        use ars_core::{Key, Repeat};
        self.add(Key::Char('d'), move |p: &mut P, sim| shift_setpoint(sim, p.shoulder(), step), Repeat::Once).add(
            Key::Char('c'),
            move |p: &mut P, sim| shift_setpoint(sim, p.shoulder(), -step),
            Repeat::Once,
        )
    }
}

/// Moves the set-point of the servo on `joint` by `delta`, from its value now.
fn shift_setpoint(
    sim: &mut ars_core::Simulation,
    joint: Option<ars_core::JointId>,
    delta: f64,
) -> ars_core::Result<()> {
    let now = sim.scene().time();
    let mut joint = sim.scene_mut().joint_mut(joint.expect("built"))?;
    let servo = joint.controller_mut::<ars_core::PositionServo>().expect("the shoulder has a position servo");
    servo.setpoint = ars_core::Profile::constant(servo.setpoint.value(now) + delta)?;
    Ok(())
}

/// Holds `shoulder` at 0 rad with a PD [`PositionServo`](ars_core::PositionServo) and
/// records what it does at the start of every step (its set-point, the angle, the error
/// and the servo's torque).
pub(crate) fn hold_shoulder(
    sim: &mut ars_core::Simulation,
    shoulder: ars_core::JointId,
    kp: f64,
    kd: f64,
) -> ars_core::Result<ars_core::SensorId<ars_core::Probe<ControlRow>>> {
    use ars_core::{PositionServo, Probe, Profile, Scene};
    sim.scene_mut().joint_mut(shoulder)?.set_controller(PositionServo::pd(Profile::constant(0.0)?, kp, kd))?;
    let probe = Probe::at_step_start(move |scene: &Scene| servo_reading(scene, shoulder));
    sim.add_sensor(probe.reads_joints([shoulder]))
}

/// What the position servo on `joint` does in the step being taken.
pub(crate) fn servo_reading(scene: &ars_core::Scene, joint: ars_core::JointId) -> ars_core::Result<ControlRow> {
    let servo = scene.joint_controller::<ars_core::PositionServo>(joint)?.expect("the joint has a position servo");
    let setpoint = servo.setpoint.value(scene.time());
    let angle = scene.joint_state(joint)?.position;
    Ok(ControlRow { setpoint, angle, error: setpoint - angle, torque: scene.joint_efforts(joint)?.controller })
}
