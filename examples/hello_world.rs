//! The thesis' hello world: a 1 kg ball of radius 0.5 m dropped from (1, 1, 1) onto the
//! floor y = 0 with ARS' defaults (0.4 ms steps). Runs headless for one second and
//! prints the ball's height and vertical speed every 10 ms.
//!
//! `cargo run --release --example hello_world`

use ars::sensors::{Gps, Velometer};
use ars::{Mass, Program, Result, SensorId, Simulation};

#[derive(Default)]
struct HelloWorld {
    sensors: Option<(SensorId<Gps>, SensorId<Velometer>)>,
}

impl Program for HelloWorld {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let ball = sim.add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
        let gps = sim.add_sensor_every(Gps::new(ball), 0.01)?;
        let velometer = sim.add_sensor_every(Velometer::new(ball), 0.01)?;
        self.sensors = Some((gps, velometer));
        Ok(())
    }
}

fn main() -> Result<()> {
    let mut program = HelloWorld::default();
    let sim = program.run_headless(1.0)?;
    let (gps, velometer) = program.sensors.expect("created with the simulation");
    println!("{:>6} {:>10} {:>11}", "t [s]", "y [m]", "vy [m/s]");
    for (p, v) in sim.records(gps)?.iter().zip(sim.records(velometer)?) {
        println!("{:>6.3} {:>10.6} {:>11.6}", p.time, p.record.position.y, v.record.linear.y);
    }
    Ok(())
}
