//! The original's vehicle demos: `Vehicle1`, `Vehicle2`, `VehicleWithArm` and
//! `VehicleWithControlledArm`, driven with the arrow keys.

use crate::{SetpointKeys, ShoulderSetpoint, hold_shoulder};
use ars_core::nalgebra::Vector3;
use ars_core::sensors::{Probe, Record, SensorId};
use ars_core::{
    ActionMap, Hooks, JointId, Key, Mass, ObjectId, Program, Repeat, Result, Scene, Simulation, SimulationBuilder,
    SpaceKind,
};

use crate::simple_arm::ControlRow;
use crate::vehicles::{VehicleArm, VehicleParts, VehicleSpec, build_mobile_manipulator, build_vehicle};

fn torques(sim: &mut Simulation, pairs: &[(JointId, f64)]) -> Result<()> {
    pairs.iter().try_for_each(|&(j, t)| sim.scene_mut().joint_mut(j)?.add_torque(t))
}

/// `Vehicle1`: four thin cylinder wheels (length 0.1, radius 0.2, density 1) hinged
/// about Z to a box chassis (1.3 × 0.2 × 0.6 m, density 10), one metre up. The arrow
/// keys add 500 N·m (turning: ±250) to the wheels for one step.
#[derive(Clone, Debug, Default)]
pub struct Vehicle1 {
    /// The chassis.
    pub chassis: Option<ObjectId>,
    /// Wheel joints r1..r4.
    pub wheels: Vec<JointId>,
}

impl Vehicle1 {
    /// Torque of one key press, N·m.
    pub const TORQUE: f64 = 500.0;

    fn drive(&self, sim: &mut Simulation, t: [f64; 4]) -> Result<()> {
        let w = &self.wheels;
        torques(sim, &[(w[0], t[0]), (w[1], t[1]), (w[2], t[2]), (w[3], t[3])])
    }
}

impl Hooks for Vehicle1 {}

impl Program for Vehicle1 {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let first = Vector3::new(1.0, 1.0, 1.0);
        let offsets = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0]];
        let mut wheels = Vec::new();
        for o in offsets {
            wheels.push(sim.scene_mut().add_cylinder(
                0.2,
                0.1,
                [o[0] + first.x, o[1] + first.y, o[2] + first.z],
                Mass::Density(1.0),
            )?);
        }
        let chassis = sim.scene_mut().add_box([1.3, 0.2, 0.6], [1.5, 1.0, 1.5], Mass::Density(10.0))?;
        for (i, w) in wheels.iter().enumerate() {
            let j = sim.scene_mut().add_hinge_joint(&format!("r{}", i + 1), chassis, *w, None, Vector3::z())?;
            self.wheels.push(j);
        }
        self.chassis = Some(chassis);
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        let t = Self::TORQUE;
        ActionMap::new()
            .add(Key::Up, move |p: &mut Self, sim| p.drive(sim, [t, t, 0.0, 0.0]), Repeat::Once)
            .add(Key::Down, move |p: &mut Self, sim| p.drive(sim, [-t, -t, 0.0, 0.0]), Repeat::Once)
            .add(Key::Left, move |p: &mut Self, sim| p.drive(sim, [-t / 2.0, t / 2.0, -t / 2.0, t / 2.0]), Repeat::Once)
            .add(
                Key::Right,
                move |p: &mut Self, sim| p.drive(sim, [t / 2.0, -t / 2.0, t / 2.0, -t / 2.0]),
                Repeat::Once,
            )
    }
}

/// `Vehicle2`: a differential-drive base (two cylinder wheels, a caster ball, a 6 kg
/// chassis) dropped from 0.7 m at (3, 1, 3); the arrow keys, held, drive the wheels
/// with ±30 N·m in every step. (The original named the wheel joints r1 and r2; here
/// they are w1 and w2 as on every vehicle.)
#[derive(Clone, Debug, Default)]
pub struct Vehicle2 {
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
}

impl Vehicle2 {
    /// Wheel torque while a key is held, N·m.
    pub const TORQUE: f64 = 30.0;
}

pub(crate) fn drive(vehicle: Option<VehicleParts>, sim: &mut Simulation, right: f64, left: f64) -> Result<()> {
    let v = vehicle.expect("built");
    torques(sim, &[(v.w1, right), (v.w2, left)])
}

impl Hooks for Vehicle2 {}

impl Program for Vehicle2 {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let spec = VehicleSpec {
            offset: Vector3::new(3.0, 1.0, 3.0),
            chassis_mass: Mass::Density(10.0),
            ..Default::default()
        };
        self.vehicle = Some(build_vehicle(sim, &spec)?);
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        let t = Self::TORQUE;
        ActionMap::new()
            .add(Key::Up, move |p: &mut Self, sim| drive(p.vehicle, sim, t, t), Repeat::WhileHeld)
            .add(Key::Down, move |p: &mut Self, sim| drive(p.vehicle, sim, -t, -t), Repeat::WhileHeld)
            .add(Key::Left, move |p: &mut Self, sim| drive(p.vehicle, sim, -t, t), Repeat::WhileHeld)
            .add(Key::Right, move |p: &mut Self, sim| drive(p.vehicle, sim, t, -t), Repeat::WhileHeld)
    }
}

/// `VehicleWithArm`: the differential-drive base at (2, 0.35, 4) carrying the 2-DOF arm
/// (links of density 1), 0.1 ms steps. Held arrows drive the wheels with ±3 N·m; 'a'/'z'
/// push the waist with ±3 N·m for one step. The original's default is a frictionless
/// arm; `arm_friction` adds `−0.01 · rate` on both arm joints. Records the arm's rates
/// at the start of every step.
#[derive(Clone, Debug, Default)]
pub struct VehicleWithArm {
    /// Capsule wheels instead of cylinders.
    pub capsule_wheels: bool,
    /// Viscous friction on the arm joints (the original's `frictionless_arm = False`).
    pub arm_friction: bool,
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
    /// The arm.
    pub arm: Option<VehicleArm>,
    /// The arm's rates at the start of every step.
    pub record: Option<SensorId<Probe<ArmRates>>>,
}

/// The rates of an arm's two joints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmRates {
    /// Waist rate, rad/s.
    pub q1_rate: f64,
    /// Shoulder rate, rad/s.
    pub q2_rate: f64,
}

impl Record for ArmRates {
    fn columns() -> Vec<&'static str> {
        vec!["q1 rate [rad/s]", "q2 rate [rad/s]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.q1_rate), Some(self.q2_rate)]
    }
}

/// Wheel torque of the arm vehicles while an arrow is held, N·m.
pub const WHEEL_TORQUE: f64 = 3.0;
/// Waist torque of one 'a'/'z' press, N·m.
pub const WAIST_TORQUE: f64 = 3.0;

/// Pushes the waist of `arm` with `torque` (and adds nothing to the shoulder), as the
/// original's 'a'/'z' keys did.
pub(crate) fn push_waist(arm: Option<VehicleArm>, sim: &mut Simulation, torque: f64) -> Result<()> {
    let a = arm.expect("built");
    torques(sim, &[(a.r1, torque), (a.r2, 0.0)])
}

/// The key bindings shared by the arm vehicles: held arrows drive the wheels with
/// `$torque`, 'a'/'z' push the waist for one step.
macro_rules! arm_vehicle_bindings {
    ($ty:ty, $torque:expr) => {{
        let t: f64 = $torque;
        ars_core::ActionMap::<$ty>::new()
            .add(
                Key::Up,
                move |p: &mut $ty, sim| $crate::vehicle_programs::drive(p.vehicle, sim, t, t),
                Repeat::WhileHeld,
            )
            .add(
                Key::Down,
                move |p: &mut $ty, sim| $crate::vehicle_programs::drive(p.vehicle, sim, -t, -t),
                Repeat::WhileHeld,
            )
            .add(
                Key::Left,
                move |p: &mut $ty, sim| $crate::vehicle_programs::drive(p.vehicle, sim, -t, t),
                Repeat::WhileHeld,
            )
            .add(
                Key::Right,
                move |p: &mut $ty, sim| $crate::vehicle_programs::drive(p.vehicle, sim, t, -t),
                Repeat::WhileHeld,
            )
            .add(
                Key::Char('a'),
                |p: &mut $ty, sim| $crate::vehicle_programs::push_waist(p.arm, sim, $crate::WAIST_TORQUE),
                Repeat::Once,
            )
            .add(
                Key::Char('z'),
                |p: &mut $ty, sim| $crate::vehicle_programs::push_waist(p.arm, sim, -$crate::WAIST_TORQUE),
                Repeat::Once,
            )
    }};
}
pub(crate) use arm_vehicle_bindings;

impl Hooks for VehicleWithArm {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let a = self.arm.expect("built");
        let (q1, q2) = (sim.scene().joint_rate(a.r1)?, sim.scene().joint_rate(a.r2)?);
        if self.arm_friction {
            torques(sim, &[(a.r1, -0.01 * q1), (a.r2, -0.01 * q2)])?;
        }
        Ok(())
    }
}

impl Program for VehicleWithArm {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder
            .space(SpaceKind::Simple)
            .time_step(1.0 / 50.0 / 200.0)
            .steps_per_frame(200)
            .floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let spec = VehicleSpec { capsule_wheels: self.capsule_wheels, ..Default::default() };
        let (vehicle, arm) = build_mobile_manipulator(sim, &spec, Mass::Density(1.0))?;
        let (r1, r2) = (arm.r1, arm.r2);
        let probe = Probe::at_step_start(move |scene: &Scene| {
            Ok(ArmRates { q1_rate: scene.joint_rate(r1)?, q2_rate: scene.joint_rate(r2)? })
        });
        self.record = Some(sim.add_sensor(probe.reads_joints([r1, r2]))?);
        (self.vehicle, self.arm) = (Some(vehicle), Some(arm));
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        arm_vehicle_bindings!(Self, WHEEL_TORQUE)
    }
}

/// `VehicleWithControlledArm`: [`VehicleWithArm`] whose shoulder is held at a
/// set-point by a PD position servo (Kp 1, Kd 0.5; 'd'/'c' move the set-point by
/// ±0.1 rad). As in the original, no arm friction is applied. Records set-point, angle,
/// error and servo torque at the start of every step.
#[derive(Clone, Debug, Default)]
pub struct VehicleWithControlledArm {
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
    /// The arm.
    pub arm: Option<VehicleArm>,
    /// What the shoulder's servo does, at the start of every step.
    pub record: Option<SensorId<Probe<ControlRow>>>,
}

impl Hooks for VehicleWithControlledArm {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        sim.scene_mut().joint_mut(self.arm.expect("built").r1)?.add_torque(0.0)
    }
}

impl Program for VehicleWithControlledArm {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        VehicleWithArm::default().configure(builder)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let (vehicle, arm) = build_mobile_manipulator(sim, &VehicleSpec::default(), Mass::Density(1.0))?;
        self.record = Some(hold_shoulder(sim, arm.r2, 1.0, 0.5)?);
        (self.vehicle, self.arm) = (Some(vehicle), Some(arm));
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        arm_vehicle_bindings!(Self, WHEEL_TORQUE).add_setpoint_keys(0.1)
    }
}

impl ShoulderSetpoint for VehicleWithControlledArm {
    fn shoulder(&self) -> Option<JointId> {
        self.arm.map(|a| a.r2)
    }
}
