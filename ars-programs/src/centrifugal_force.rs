//! The original's `CentrifugalForceTest` (and the sensor demos built on it): a ball on a
//! 1 m rigid "cable" swung around by a pole turning at a set speed.

use std::f64::consts::FRAC_PI_2;

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::{HingeSensor, JointPower, JointTorque, Probe, Record};
use ars_core::{
    ActionMap, Hooks, JointId, Key, Mass, ObjectId, Program, Repeat, Result, Scene, SensorId, Simulation,
    SimulationBuilder, SpaceKind,
};

/// One frame's reading (at its start): ball position, velocity and angular velocity,
/// and the cable's angle from the vertical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CentrifugalRow {
    /// Ball position, m.
    pub position: Point3<f64>,
    /// Ball velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Ball angular velocity, rad/s.
    pub angular_velocity: Vector3<f64>,
    /// `acos((2 − y + 0.5) / 1)`: the cable's angle from the vertical, rad.
    pub theta: f64,
}

/// Base box 5 × 0.5 × 5 m (density 1) at (2, 0.25, 2); pole cylinder (length 2,
/// radius 0.05, density 1) upright at (2, 1.5, 2); a 1 kg ball of radius 0.01 at
/// (2, 1.5, 3). Waist r1 (base–pole) about Y; r2 (pole–ball) about X at (2, 2.5, 3), so
/// the cable is 1 m long, 1 m from the axis. dt = 1 ms (50 frames/s × 20 steps).
/// Every frame the pole's speed motor is set to the set-point (3 rad/s, 100 N·m) and r2
/// gets a "friction" torque `−500 · rate` (acting for one step of the 20). Keys 'a'/'z'
/// change the set-point by ±0.01 rad/s. The cable settles at θ with
/// `tan θ / (d + l sin θ) = ω²/g`: 1.0415 rad for ω = 3, d = l = 1.
#[derive(Clone, Debug)]
pub struct CentrifugalForce {
    /// Pole speed set-point, rad/s.
    pub speed: f64,
    /// The ball.
    pub ball: Option<ObjectId>,
    /// The waist and the cable hinge.
    pub joints: Option<(JointId, JointId)>,
    /// The sensor demos' sensors on r2: torque, power, angle.
    pub sensors: Option<(SensorId<JointTorque>, SensorId<JointPower>, SensorId<HingeSensor>)>,
    /// The reading at the start of every frame.
    pub record: Option<SensorId<Probe<CentrifugalRow>>>,
}

impl Record for CentrifugalRow {
    fn columns() -> Vec<&'static str> {
        vec![
            "x [m]",
            "y [m]",
            "z [m]",
            "vx [m/s]",
            "vy [m/s]",
            "vz [m/s]",
            "wx [rad/s]",
            "wy [rad/s]",
            "wz [rad/s]",
            "theta [rad]",
        ]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let (p, v, w) = (self.position, self.velocity, self.angular_velocity);
        [p.x, p.y, p.z, v.x, v.y, v.z, w.x, w.y, w.z, self.theta].map(Some).to_vec()
    }
}

impl Default for CentrifugalForce {
    fn default() -> Self {
        CentrifugalForce { speed: 3.0, ball: None, joints: None, sensors: None, record: None }
    }
}

impl CentrifugalForce {
    /// The steady cable angle for pole speed `omega` (d = l = 1 m, g = 9.81), rad.
    pub fn steady_angle(omega: f64) -> f64 {
        let k = omega * omega / 9.81;
        let mut theta: f64 = 1.0;
        for _ in 0..200 {
            theta = (k * (1.0 + theta.sin())).atan();
        }
        theta
    }
}

impl Hooks for CentrifugalForce {
    fn pre_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        let (r1, r2) = self.joints.expect("built");
        sim.scene_mut().joint_mut(r1)?.set_speed(self.speed, 100.0)?;
        let rate = sim.scene().joint_rate(r2)?;
        sim.scene_mut().joint_mut(r2)?.add_torque(-500.0 * rate)
    }
}

impl Program for CentrifugalForce {
    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: centrifugal force".into(),
            camera_position: ars_core::nalgebra::Point3::new(2.0, 5.0, 10.0),
            size: (900, 600),
            camera_target: ars_core::nalgebra::Point3::new(2.0, 1.5, 2.0),
            ..Default::default()
        }
    }

    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).time_step(1.0 / 50.0 / 20.0).steps_per_frame(20).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let offset = Vector3::new(2.0, 0.5, 2.0);
        let base =
            sim.scene_mut().add_box([5.0, 0.5, 5.0], Point3::new(0.0, -0.25, 0.0) + offset, Mass::Density(1.0))?;
        let pole = sim.scene_mut().add_cylinder(0.05, 2.0, [0.0, 1.0, 0.0], Mass::Density(1.0))?;
        sim.scene_mut().rotate(pole, Vector3::x(), FRAC_PI_2)?;
        sim.scene_mut().offset_by_position(pole, offset)?;
        let density = 1.0 / (4.0 / 3.0 * std::f64::consts::PI * 0.01f64.powi(3));
        let ball = sim.scene_mut().add_sphere(0.01, Point3::new(0.0, 1.0, 1.0) + offset, Mass::Density(density))?;
        let r1 = sim.scene_mut().add_hinge_joint("r1", base, pole, None, Vector3::y())?;
        let r2 = sim.scene_mut().add_hinge_joint(
            "r2",
            pole,
            ball,
            Some(Point3::new(0.0, 2.0, 1.0) + offset),
            Vector3::x(),
        )?;
        self.sensors = Some((
            sim.add_sensor(JointTorque::new(r2))?,
            sim.add_sensor(JointPower::new(r2))?,
            sim.add_sensor_every(HingeSensor::new(r2), 1.0 / 50.0)?,
        ));
        let frame = sim.scene().time_step() * f64::from(sim.scene().steps_per_frame());
        let probe = Probe::at_step_start(move |scene: &Scene| {
            let b = scene.body(ball)?;
            let (position, velocity, angular_velocity) = (b.position(), b.linear_velocity(), b.angular_velocity());
            let theta = ((2.0 - position.y + 0.5) / 1.0).clamp(-1.0, 1.0).acos();
            Ok(CentrifugalRow { position, velocity, angular_velocity, theta })
        });
        self.record = Some(sim.add_sensor_every(probe.reads_objects([ball]), frame)?);
        self.ball = Some(ball);
        self.joints = Some((r1, r2));
        Ok(())
    }

    fn key_bindings(&self) -> ActionMap<Self> {
        ActionMap::new()
            .add(
                Key::Char('a'),
                |p: &mut Self, _| {
                    p.speed += 0.01;
                    Ok(())
                },
                Repeat::Once,
            )
            .add(
                Key::Char('z'),
                |p: &mut Self, _| {
                    p.speed -= 0.01;
                    Ok(())
                },
                Repeat::Once,
            )
    }
}
