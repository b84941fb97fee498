//! The original's `FallingBalls` demo: three balls of different sizes and masses.

use ars_core::nalgebra::Vector3;
use ars_core::sensors::Gps;
use ars_core::{Hooks, Mass, ObjectId, Program, Result, SensorId, Simulation, SimulationBuilder, SpaceKind};

/// Three spheres: radius 0.3 m at (1, 6, 1) with density 1; radius 0.5 m at (2, 4, 2)
/// with density 0.5; radius 0.2 m at (3, 2, 3) with mass 5 kg; floor y = 0.
#[derive(Clone, Debug, Default)]
pub struct FallingBalls {
    /// The balls and a GPS on each.
    pub balls: Vec<(ObjectId, SensorId<Gps>)>,
}

impl Hooks for FallingBalls {}

impl Program for FallingBalls {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let specs = [
            (0.3, [1.0, 6.0, 1.0], Mass::Density(1.0)),
            (0.5, [2.0, 4.0, 2.0], Mass::Density(0.5)),
            (0.2, [3.0, 2.0, 3.0], Mass::Total(5.0)),
        ];
        for (radius, center, mass) in specs {
            let ball = sim.scene_mut().add_sphere(radius, center, mass)?;
            let gps = sim.add_sensor(Gps::new(ball))?;
            self.balls.push((ball, gps));
        }
        Ok(())
    }
}
