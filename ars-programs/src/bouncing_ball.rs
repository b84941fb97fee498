//! IROS example 1: a small ball bouncing on the floor.

use ars_core::nalgebra::Vector3;
use ars_core::sensors::{Probe, Record, SensorId, SensorLog};
use ars_core::{Hooks, Mass, ObjectId, Program, Result, Scene, Simulation, SimulationBuilder, SpaceKind};

/// The ball's height and vertical velocity at the start of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallHeight {
    /// Centre height, m.
    pub y: f64,
    /// Vertical velocity, m/s.
    pub vy: f64,
}

impl Record for BallHeight {
    fn columns() -> Vec<&'static str> {
        vec!["y [m]", "vy [m/s]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.y), Some(self.vy)]
    }
}

/// IROS example 1: a 1 kg ball of radius 0.01 m dropped from 1 m (centre at
/// (1, 1.01, 1)), dt 0.25 ms; its probe records `y, vy` at the start of every step. The
/// code bounces with the default restitution 0.2; the paper's figure needs 0.9: set
/// `paper_bounce`.
#[derive(Clone, Debug, Default)]
pub struct BouncingBall {
    /// Use the paper's restitution (0.9) instead of the code's 0.2.
    pub paper_bounce: bool,
    /// The ball.
    pub ball: Option<ObjectId>,
    /// Height and vertical velocity at the start of every step.
    pub record: Option<SensorId<Probe<BallHeight>>>,
}

impl BouncingBall {
    /// Times at which the ball starts moving up again (the bounces), s.
    pub fn bounce_times(log: &SensorLog<BallHeight>) -> Vec<f64> {
        log.samples().windows(2).filter(|w| w[0].record.vy < 0.0 && w[1].record.vy > 0.0).map(|w| w[1].time).collect()
    }
}

impl Hooks for BouncingBall {}

impl Program for BouncingBall {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        let b = builder
            .space(SpaceKind::Simple)
            .time_step(1.0 / 50.0 / 80.0)
            .steps_per_frame(80)
            .floor_plane(Vector3::y(), 0.0);
        if self.paper_bounce { b.bounce(0.9, 0.0) } else { b }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let ball = sim.scene_mut().add_sphere(0.01, [1.0, 1.01, 1.0], Mass::Total(1.0))?;
        let probe = Probe::at_step_start(move |scene: &Scene| {
            let b = scene.body(ball)?;
            Ok(BallHeight { y: b.position().y, vy: b.linear_velocity().y })
        });
        self.record = Some(sim.add_sensor(probe.reads_objects([ball]))?);
        self.ball = Some(ball);
        Ok(())
    }
}
