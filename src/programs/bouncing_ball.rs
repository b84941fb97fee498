//! IROS example 1: a small ball bouncing on the floor.

use ars_core::nalgebra::Vector3;
use ars_core::{Hooks, Mass, ObjectId, Program, Result, Simulation, SimulationBuilder};

/// IROS example 1: a 1 kg ball of radius 0.01 m dropped from 1 m (centre at
/// (1, 1.01, 1)), dt 0.25 ms; the pre-step hook records `(time, y, vy)` every step. The
/// code bounces with the default restitution 0.2; the paper's figure needs 0.9: set
/// `paper_bounce`.
#[derive(Clone, Debug, Default)]
pub struct BouncingBall {
    /// Use the paper's restitution (0.9) instead of the code's 0.2.
    pub paper_bounce: bool,
    /// The ball.
    pub ball: Option<ObjectId>,
    /// `(time, y, vy)` at the start of every step.
    pub rows: Vec<(f64, f64, f64)>,
}

impl BouncingBall {
    /// Times at which the ball starts moving up again (the bounces), s.
    pub fn bounce_times(&self) -> Vec<f64> {
        self.rows.windows(2).filter(|w| w[0].2 < 0.0 && w[1].2 > 0.0).map(|w| w[1].0).collect()
    }
}

impl Hooks for BouncingBall {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let b = sim.body(self.ball.expect("created"))?;
        let (y, vy) = (b.position().y, b.linear_velocity().y);
        self.rows.push((sim.time(), y, vy));
        Ok(())
    }
}

impl Program for BouncingBall {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        let b = builder.time_step(1.0 / 50.0 / 80.0).steps_per_frame(80).floor_plane(Vector3::y(), 0.0);
        if self.paper_bounce { b.bounce(0.9, 0.0) } else { b }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        self.ball = Some(sim.add_sphere(0.01, [1.0, 1.01, 1.0], Mass::Total(1.0))?);
        Ok(())
    }
}
