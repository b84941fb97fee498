//! The thesis' laser example: two balls fall past a laser beam pointing +X.

use std::f64::consts::FRAC_PI_2;

use ars_core::convert::rotation_about_axis;
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::{Gps, Laser, SystemTotalEnergy, Velometer};
use ars_core::{Hooks, Mass, ObjectId, Program, Result, SensorId, Simulation, SimulationBuilder, SpaceKind};

/// Two balls (radius 1 m, 1 kg, at (3, 4, 1) then (5, 3, 1)) and a laser at
/// (1.5, 1.5, 1) pointing +X (local +Z turned π/2 about Y), 1000 m long, floor y = 0.
#[derive(Clone, Debug, Default)]
pub struct TwoBallLaser {
    /// The first ball (higher, nearer the laser).
    pub ball1: Option<ObjectId>,
    /// The second ball.
    pub ball2: Option<ObjectId>,
    /// The laser.
    pub laser: Option<SensorId<Laser>>,
    /// Positions of the balls.
    pub gps: Option<(SensorId<Gps>, SensorId<Gps>)>,
    /// Velocities of the balls.
    pub velometers: Option<(SensorId<Velometer>, SensorId<Velometer>)>,
    /// Energy of the system.
    pub energy: Option<SensorId<SystemTotalEnergy>>,
}

impl TwoBallLaser {
    /// Where the laser is.
    pub const LASER_POSITION: Point3<f64> = Point3::new(1.5, 1.5, 1.0);
}

impl Hooks for TwoBallLaser {}

impl Program for TwoBallLaser {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: two balls and a laser".into(),
            camera_position: ars_core::nalgebra::Point3::new(-8.0, 6.0, 16.0),
            camera_target: ars_core::nalgebra::Point3::new(3.0, 1.5, 1.0),
            ..Default::default()
        }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let b1 = sim.scene_mut().add_sphere(1.0, [3.0, 4.0, 1.0], Mass::Total(1.0))?;
        let b2 = sim.scene_mut().add_sphere(1.0, [5.0, 3.0, 1.0], Mass::Total(1.0))?;
        let along_x = rotation_about_axis(&Vector3::y(), FRAC_PI_2);
        self.laser = Some(sim.add_sensor(Laser::new(1000.0).at(Self::LASER_POSITION, along_x))?);
        self.gps = Some((sim.add_sensor(Gps::new(b1))?, sim.add_sensor(Gps::new(b2))?));
        self.velometers = Some((sim.add_sensor(Velometer::new(b1))?, sim.add_sensor(Velometer::new(b2))?));
        self.energy = Some(sim.add_sensor(SystemTotalEnergy::new())?);
        (self.ball1, self.ball2) = (Some(b1), Some(b2));
        Ok(())
    }
}
