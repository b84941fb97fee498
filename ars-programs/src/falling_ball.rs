//! The thesis' falling ball: a 1 kg sphere of radius 0.5 m dropped from (1, 1, 1).

use ars_core::nalgebra::Vector3;
use ars_core::sensors::{Accelerometer, Gps, KineticEnergy, PotentialEnergy, SystemTotalEnergy, Velometer};
use ars_core::{Hooks, Mass, ObjectId, Program, Result, SensorId, Simulation, SimulationBuilder, SpaceKind};

/// The thesis' hello world: one ball, nothing else.
#[derive(Clone, Debug, Default)]
pub struct HelloWorld {
    /// The ball, once created.
    pub ball: Option<ObjectId>,
}

impl Hooks for HelloWorld {}

impl Program for HelloWorld {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        self.ball = Some(sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?);
        Ok(())
    }
}

/// The falling ball with the sensors of the thesis' figure 3.2: GPS, velometer,
/// accelerometer, potential and kinetic energy of the ball, total energy of the system.
#[derive(Clone, Debug, Default)]
pub struct FallingBallSensors {
    /// The ball.
    pub ball: Option<ObjectId>,
    /// Its position.
    pub gps: Option<SensorId<Gps>>,
    /// Its velocity.
    pub velometer: Option<SensorId<Velometer>>,
    /// Its acceleration.
    pub accelerometer: Option<SensorId<Accelerometer>>,
    /// Its potential energy (zero at y = 0).
    pub potential: Option<SensorId<PotentialEnergy>>,
    /// Its kinetic energy.
    pub kinetic: Option<SensorId<KineticEnergy>>,
    /// The energy of the whole system.
    pub total: Option<SensorId<SystemTotalEnergy>>,
}

impl Hooks for FallingBallSensors {}

impl Program for FallingBallSensors {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: falling ball with sensors".into(),
            camera_position: ars_core::nalgebra::Point3::new(10.0, 8.0, 10.0),
            ..Default::default()
        }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
        self.ball = Some(ball);
        self.gps = Some(sim.add_sensor(Gps::new(ball))?);
        self.velometer = Some(sim.add_sensor(Velometer::new(ball))?);
        self.accelerometer = Some(sim.add_sensor(Accelerometer::new(ball))?);
        self.potential = Some(sim.add_sensor(PotentialEnergy::new(ball))?);
        self.kinetic = Some(sim.add_sensor(KineticEnergy::new(ball))?);
        self.total = Some(sim.add_sensor(SystemTotalEnergy::new())?);
        Ok(())
    }
}
