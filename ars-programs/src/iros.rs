//! The IROS/IFAC mobile-manipulator examples 3, 4 and 5 of the original, with their
//! parameters (ars-original §8.14–8.17). Where the papers and the code disagree, the
//! code's behaviour is the default and the paper's is a flag.

use crate::{SetpointKeys, ShoulderSetpoint, servo_reading};
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::{Probe, Record, SensorId, SensorLog};
use ars_core::{
    ActionMap, HookPoint, Hooks, Key, Mass, PositionServo, Profile, Program, Repeat, Result, Scene, Simulation,
    SimulationBuilder, SpaceKind,
};

use crate::vehicle_programs::{WHEEL_TORQUE, arm_vehicle_bindings, push_waist};
use crate::vehicles::{VehicleArm, VehicleParts, VehicleSpec, build_mobile_manipulator, signed_ground_speed};

/// The original's simple space (the papers' results, bit for bit) and its timing:
/// 50 frames/s × 80 steps, dt = 0.25 ms.
fn iros_timing(builder: SimulationBuilder) -> SimulationBuilder {
    builder.space(SpaceKind::Simple).time_step(1.0 / 50.0 / 80.0).steps_per_frame(80)
}

/// One step of example 3, at its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedProfileRow {
    /// Chassis X, m.
    pub x: f64,
    /// Ground speed of the chassis, signed by its X velocity, m/s.
    pub speed: f64,
    /// Speed set-point, m/s.
    pub setpoint: f64,
    /// Waist angle and rate.
    pub q1: f64,
    /// Waist rate, rad/s.
    pub q1_rate: f64,
    /// Shoulder angle, rad.
    pub q2: f64,
    /// Shoulder rate, rad/s.
    pub q2_rate: f64,
    /// Torque on each wheel, N·m.
    pub wheel_torque: f64,
}

impl Record for SpeedProfileRow {
    fn columns() -> Vec<&'static str> {
        vec![
            "x [m]",
            "speed [m/s]",
            "setpoint [m/s]",
            "q1 [rad]",
            "q1 rate [rad/s]",
            "q2 [rad]",
            "q2 rate [rad/s]",
            "wheel torque [N m]",
        ]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [self.x, self.speed, self.setpoint, self.q1, self.q1_rate, self.q2, self.q2_rate, self.wheel_torque]
            .map(Some)
            .to_vec()
    }
}

/// IROS example 3, "mobile manipulator with freely-coasting 2-DOF arm": the vehicle
/// (at (−4, 0.5, 4), 1 kg links) follows a trapezoidal speed profile (0 until 1 s, up to
/// 1 m/s at 5 s, held to 9 s, down to 0 at 13 s) with the wheel torque
/// `10 · (sp − v)` on both wheels; the arm joints have viscous friction 0.02. The code
/// is proportional only although the thesis calls it PD: `derivative_gain` (default 0)
/// adds the paper's derivative term.
#[derive(Clone, Debug)]
pub struct SpeedProfile {
    /// Proportional gain, N·m per m/s.
    pub gain: f64,
    /// Derivative gain of the paper's PD variant, N·m per m/s² (0: the code's P-only).
    pub derivative_gain: f64,
    /// The speed set-point.
    pub profile: Profile,
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
    /// The arm.
    pub arm: Option<VehicleArm>,
    /// The record of every step (at its start).
    pub record: Option<SensorId<Probe<SpeedProfileRow>>>,
    previous_error: f64,
}

impl Default for SpeedProfile {
    fn default() -> Self {
        SpeedProfile {
            gain: 10.0,
            derivative_gain: 0.0,
            profile: Profile::new(vec![(0.0, 0.0), (1.0, 0.0), (5.0, 1.0), (9.0, 1.0), (13.0, 0.0), (14.0, 0.0)])
                .expect("a valid profile"),
            vehicle: None,
            arm: None,
            record: None,
            previous_error: 0.0,
        }
    }
}

/// How well the speed follows its set-point over a stretch of time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackingError {
    /// Mean of `v − sp`, m/s.
    pub mean: f64,
    /// Mean of `|v − sp|`, m/s.
    pub mean_abs: f64,
    /// Largest `|v − sp|`, m/s.
    pub worst: f64,
}

impl SpeedProfile {
    /// The speed error on the 6–9 s plateau of the profile (1 m/s), if the run got there.
    pub fn plateau_error(log: &SensorLog<SpeedProfileRow>) -> Option<TrackingError> {
        let errors: Vec<f64> =
            log.iter().filter(|s| (6.0..9.0).contains(&s.time)).map(|s| s.record.speed - s.record.setpoint).collect();
        if errors.is_empty() {
            return None;
        }
        let n = errors.len() as f64;
        Some(TrackingError {
            mean: errors.iter().sum::<f64>() / n,
            mean_abs: errors.iter().map(|e| e.abs()).sum::<f64>() / n,
            worst: errors.iter().fold(0.0, |w: f64, e| w.max(e.abs())),
        })
    }

    /// The paper's PD variant, with derivative gain `kd` (N·m per m/s²).
    pub fn with_derivative_gain(kd: f64) -> Self {
        SpeedProfile { derivative_gain: kd, ..Default::default() }
    }

    /// Viscous friction of the arm joints, N·m·s.
    pub const ARM_FRICTION: f64 = 0.02;
    /// Where the vehicle starts.
    pub const OFFSET: Vector3<f64> = Vector3::new(-4.0, 0.5, 4.0);
}

impl Hooks for SpeedProfile {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let (v, a) = (self.vehicle.expect("built"), self.arm.expect("built"));
        let time = sim.scene().time();
        let speed = signed_ground_speed(sim.scene(), v.chassis)?;
        let setpoint = self.profile.value(time);
        let error = setpoint - speed;
        let mut torque = self.gain * error;
        if self.derivative_gain != 0.0 {
            torque += self.derivative_gain * (error - self.previous_error) / sim.scene().time_step();
        }
        self.previous_error = error;
        sim.scene_mut().joint_mut(v.w1)?.add_torque(torque)?;
        sim.scene_mut().joint_mut(v.w2)?.add_torque(torque)?;
        let (rate1, rate2) = (sim.scene().joint_rate(a.r1)?, sim.scene().joint_rate(a.r2)?);
        sim.scene_mut().joint_mut(a.r1)?.add_torque(-Self::ARM_FRICTION * rate1)?;
        sim.scene_mut().joint_mut(a.r2)?.add_torque(-Self::ARM_FRICTION * rate2)
    }
    /// Only the pre-step hook does something (added hooks are not called elsewhere).
    fn runs_at(&self, point: HookPoint) -> bool {
        point == HookPoint::PreStep
    }
    /// The speed error of the previous step (the PD variant's derivative).
    fn save_state(&self) -> Vec<u64> {
        vec![self.previous_error.to_bits()]
    }
    fn restore_state(&mut self, state: &[u64]) -> Result<()> {
        if let [error] = state {
            self.previous_error = f64::from_bits(*error);
        }
        Ok(())
    }
}

impl Program for SpeedProfile {
    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: speed profile (IROS example 3)".into(),
            follow: Some("chassis".into()),
            camera_position: ars_core::nalgebra::Point3::new(0.0, 8.0, 25.0),
            ..Default::default()
        }
    }

    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        iros_timing(builder).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let (vehicle, arm) = build_mobile_manipulator(
            sim,
            &VehicleSpec { offset: Self::OFFSET, ..Default::default() },
            Mass::Total(1.0),
        )?;
        let profile = self.profile.clone();
        let (chassis, w1, r1, r2) = (vehicle.chassis, vehicle.w1, arm.r1, arm.r2);
        let probe = Probe::at_step_start(move |scene: &Scene| {
            let (s1, s2) = (scene.joint_state(r1)?, scene.joint_state(r2)?);
            Ok(SpeedProfileRow {
                x: scene.position(chassis)?.x,
                speed: signed_ground_speed(scene, chassis)?,
                setpoint: profile.value(scene.time()),
                q1: s1.position,
                q1_rate: s1.rate,
                q2: s2.position,
                q2_rate: s2.rate,
                wheel_torque: scene.joint_efforts(w1)?.added,
            })
        });
        self.record = Some(sim.add_sensor(probe.reads_objects([chassis]).reads_joints([w1, r1, r2]))?);
        (self.vehicle, self.arm) = (Some(vehicle), Some(arm));
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        arm_vehicle_bindings!(Self, WHEEL_TORQUE)
    }
}

/// One step of example 4, at its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrainRow {
    /// Chassis position, m.
    pub position: Point3<f64>,
    /// Mean X of the two wheel centres, m.
    pub wheels_x: f64,
    /// Waist angle, rad.
    pub q1: f64,
    /// Waist PD servo torque, N·m.
    pub torque1: f64,
    /// Shoulder angle, rad.
    pub q2: f64,
    /// Shoulder PD servo torque, N·m.
    pub torque2: f64,
    /// Torque on each wheel, N·m.
    pub wheel_torque: f64,
}

impl Record for TerrainRow {
    fn columns() -> Vec<&'static str> {
        vec![
            "x [m]",
            "y [m]",
            "z [m]",
            "wheels x [m]",
            "q1 [rad]",
            "torque1 [N m]",
            "q2 [rad]",
            "torque2 [N m]",
            "wheel torque [N m]",
        ]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let p = self.position;
        [p.x, p.y, p.z, self.wheels_x, self.q1, self.torque1, self.q2, self.torque2, self.wheel_torque]
            .map(Some)
            .to_vec()
    }
}

/// IROS example 4: the vehicle (1 kg links) drives along +X over a 40 × 20 m
/// triangle-mesh terrain `y = 0.7 sin(0.5 x)` placed at (−10, 0, −10), with 4 N·m on
/// each wheel while its speed is under 2 m/s (bang-bang); PD position servos (Kp 20,
/// Kd 15) hold both arm joints at 0 (upright), with viscous friction 0.02.
#[derive(Clone, Debug, Default)]
pub struct SinusoidalTerrain {
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
    /// The arm.
    pub arm: Option<VehicleArm>,
    /// The record of every step (at its start).
    pub record: Option<SensorId<Probe<TerrainRow>>>,
}

impl SinusoidalTerrain {
    /// Where the vehicle starts.
    pub const OFFSET: Vector3<f64> = Vector3::new(-1.05, -0.35, 5.0);
    /// Where the terrain's first vertex is.
    pub const TERRAIN_CENTER: Point3<f64> = Point3::new(-10.0, 0.0, -10.0);
    /// Wheel torque while slower than [`MAX_SPEED`](Self::MAX_SPEED), N·m.
    pub const WHEEL_TORQUE: f64 = 4.0;
    /// Speed above which the wheels coast, m/s.
    pub const MAX_SPEED: f64 = 2.0;
    /// Viscous friction of the arm joints, N·m·s.
    pub const ARM_FRICTION: f64 = 0.02;
    /// Gains of the arm's PD servos.
    pub const GAINS: (f64, f64) = (20.0, 15.0);

    /// X of the terrain's far (+X) edge, m.
    pub const TERRAIN_END_X: f64 = -10.0 + 39.0;

    /// When the wheels pass the terrain's +X edge (the vehicle drops off), if they do.
    pub fn leaves_terrain(log: &SensorLog<TerrainRow>) -> Option<f64> {
        log.iter().find(|s| s.record.wheels_x > Self::TERRAIN_END_X).map(|s| s.time)
    }

    /// The terrain: 40 × 20 vertices on a 1 m grid, `y = 0.7 sin(0.5 x)`.
    pub fn terrain() -> Result<ars_core::Heightfield> {
        ars_core::Heightfield::sinusoidal(40, 20, 0.7, 0.5)
    }
}

impl Hooks for SinusoidalTerrain {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let (v, a) = (self.vehicle.expect("built"), self.arm.expect("built"));
        let vel = sim.scene().body(v.chassis)?.linear_velocity();
        let speed = (vel.x * vel.x + vel.y * vel.y + vel.z * vel.z).sqrt();
        let wheel_torque = if speed < Self::MAX_SPEED { Self::WHEEL_TORQUE } else { 0.0 };
        sim.scene_mut().joint_mut(v.w1)?.add_torque(wheel_torque)?;
        sim.scene_mut().joint_mut(v.w2)?.add_torque(wheel_torque)?;
        let (rate1, rate2) = (sim.scene().joint_rate(a.r1)?, sim.scene().joint_rate(a.r2)?);
        sim.scene_mut().joint_mut(a.r1)?.add_torque(-Self::ARM_FRICTION * rate1)?;
        // The servos add their PD torques after this hook.
        sim.scene_mut().joint_mut(a.r2)?.add_torque(-Self::ARM_FRICTION * rate2)
    }
    /// Only the pre-step hook does something (added hooks are not called elsewhere).
    fn runs_at(&self, point: HookPoint) -> bool {
        point == HookPoint::PreStep
    }
}

impl Program for SinusoidalTerrain {
    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: sinusoidal terrain (IROS example 4)".into(),
            follow: Some("chassis".into()),
            camera_position: ars_core::nalgebra::Point3::new(0.0, 8.0, 30.0),
            camera_target: ars_core::nalgebra::Point3::new(5.0, 0.0, 5.0),
            ..Default::default()
        }
    }

    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        iros_timing(builder)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let terrain = Self::terrain()?;
        let floor = sim.scene_mut().add_trimesh_floor(terrain.vertices(), terrain.triangles(), Self::TERRAIN_CENTER)?;
        sim.scene_mut().set_color(floor, [0.7, 0.7, 0.7])?;
        let (vehicle, arm) = build_mobile_manipulator(
            sim,
            &VehicleSpec { offset: Self::OFFSET, ..Default::default() },
            Mass::Total(1.0),
        )?;
        let (kp, kd) = Self::GAINS;
        for joint in [arm.r1, arm.r2] {
            sim.scene_mut().joint_mut(joint)?.set_controller(PositionServo::pd(Profile::constant(0.0)?, kp, kd))?;
        }
        let (chassis, wheel_r, wheel_l, w1, r1, r2) =
            (vehicle.chassis, vehicle.wheel_r, vehicle.wheel_l, vehicle.w1, arm.r1, arm.r2);
        let probe = Probe::at_step_start(move |scene: &Scene| {
            Ok(TerrainRow {
                position: scene.position(chassis)?,
                wheels_x: 0.5 * (scene.position(wheel_r)?.x + scene.position(wheel_l)?.x),
                q1: scene.joint_state(r1)?.position,
                torque1: scene.joint_efforts(r1)?.controller,
                q2: scene.joint_state(r2)?.position,
                torque2: scene.joint_efforts(r2)?.controller,
                wheel_torque: scene.joint_efforts(w1)?.added,
            })
        });
        let probe = probe.reads_objects([chassis, wheel_r, wheel_l]).reads_joints([w1, r1, r2]);
        self.record = Some(sim.add_sensor(probe)?);
        (self.vehicle, self.arm) = (Some(vehicle), Some(arm));
        Ok(())
    }
}

/// One step of example 5, at its start (after the keys acted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrivingRow {
    /// Chassis X, m.
    pub x: f64,
    /// Chassis Z, m.
    pub z: f64,
    /// Waist angle, rad.
    pub q1: f64,
    /// Shoulder angle, rad.
    pub q2: f64,
    /// Shoulder set-point, rad.
    pub setpoint: f64,
    /// Shoulder PD servo torque, N·m.
    pub torque: f64,
    /// Torques the keys put on the right and left wheels in this step, N·m.
    pub wheel_torques: (f64, f64),
}

impl Record for DrivingRow {
    fn columns() -> Vec<&'static str> {
        vec![
            "x [m]",
            "z [m]",
            "q1 [rad]",
            "q2 [rad]",
            "setpoint [rad]",
            "torque [N m]",
            "right wheel torque [N m]",
            "left wheel torque [N m]",
        ]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let (r, l) = self.wheel_torques;
        [self.x, self.z, self.q1, self.q2, self.setpoint, self.torque, r, l].map(Some).to_vec()
    }
}

/// IROS example 5, the user-driven vehicle: held arrows drive the wheels (±3 N·m, 1 kg
/// wheels), 'd'/'c' move the shoulder set-point by ±0.1 rad, 'a'/'z' push the waist;
/// a PD position servo (Kp 3, Kd 3) holds the shoulder. The paper's figure needs a
/// friction limit of 50 instead of the code's 500: set `paper_friction`.
#[derive(Clone, Debug, Default)]
pub struct UserDriven {
    /// Use the paper's contact friction (mu 50) instead of the code's 500.
    pub paper_friction: bool,
    /// The vehicle.
    pub vehicle: Option<VehicleParts>,
    /// The arm.
    pub arm: Option<VehicleArm>,
    /// The record of every step (at its start).
    pub record: Option<SensorId<Probe<DrivingRow>>>,
}

impl UserDriven {
    /// Gains of the shoulder's PD servo.
    pub const GAINS: (f64, f64) = (3.0, 3.0);

    fn drive(&mut self, sim: &mut Simulation, right: f64, left: f64) -> Result<()> {
        let v = self.vehicle.expect("built");
        sim.scene_mut().joint_mut(v.w1)?.add_torque(right)?;
        sim.scene_mut().joint_mut(v.w2)?.add_torque(left)
    }
}

impl Hooks for UserDriven {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        sim.scene_mut().joint_mut(self.arm.expect("built").r1)?.add_torque(0.0)
    }
}

impl Program for UserDriven {
    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: user-driven vehicle (IROS example 5)".into(),
            follow: Some("chassis".into()),
            camera_position: ars_core::nalgebra::Point3::new(15.0, 10.0, 15.0),
            ..Default::default()
        }
    }

    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        let b = iros_timing(builder).floor_plane(Vector3::y(), 0.0);
        if self.paper_friction { b.mu(50.0) } else { b }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let (vehicle, arm) = build_mobile_manipulator(
            sim,
            &VehicleSpec { wheel_mass: Mass::Total(1.0), ..Default::default() },
            Mass::Density(1.0),
        )?;
        let (kp, kd) = Self::GAINS;
        sim.scene_mut().joint_mut(arm.r2)?.set_controller(PositionServo::pd(Profile::constant(0.0)?, kp, kd))?;
        let (chassis, w1, w2, r1, r2) = (vehicle.chassis, vehicle.w1, vehicle.w2, arm.r1, arm.r2);
        let probe = Probe::at_step_start(move |scene: &Scene| {
            let p = scene.position(chassis)?;
            let servo = servo_reading(scene, r2)?;
            Ok(DrivingRow {
                x: p.x,
                z: p.z,
                q1: scene.joint_state(r1)?.position,
                q2: servo.angle,
                setpoint: servo.setpoint,
                torque: servo.torque,
                wheel_torques: (scene.joint_efforts(w1)?.added, scene.joint_efforts(w2)?.added),
            })
        });
        self.record = Some(sim.add_sensor(probe.reads_objects([chassis]).reads_joints([w1, w2, r1, r2]))?);
        (self.vehicle, self.arm) = (Some(vehicle), Some(arm));
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        let t = WHEEL_TORQUE;
        ActionMap::new()
            .add(Key::Up, move |p: &mut Self, sim| p.drive(sim, t, t), Repeat::WhileHeld)
            .add(Key::Down, move |p: &mut Self, sim| p.drive(sim, -t, -t), Repeat::WhileHeld)
            .add(Key::Left, move |p: &mut Self, sim| p.drive(sim, -t, t), Repeat::WhileHeld)
            .add(Key::Right, move |p: &mut Self, sim| p.drive(sim, t, -t), Repeat::WhileHeld)
            .add_setpoint_keys(0.1)
            .add(Key::Char('a'), |p: &mut Self, sim| push_waist(p.arm, sim, 3.0), Repeat::Once)
            .add(Key::Char('z'), |p: &mut Self, sim| push_waist(p.arm, sim, -3.0), Repeat::Once)
    }
}

impl ShoulderSetpoint for UserDriven {
    fn shoulder(&self) -> Option<ars_core::JointId> {
        self.arm.map(|a| a.r2)
    }
}
