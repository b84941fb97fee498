//! The thesis' hello world: a 1 kg ball of radius 0.5 m dropped from (1, 1, 1) onto the
//! floor y = 0 with ARS' defaults (0.4 ms steps). Runs headless and prints the ball's
//! height and vertical speed every 10 ms; `--csv` writes them for every step
//! (`step,t,y,vy`), `--plot` draws the height.
//!
//! `cargo run --release --example hello_world`

#[path = "common/mod.rs"]
mod common;

use ars::nalgebra::Vector3;
use ars::sensors::{Gps, Velometer};
use ars::{Hooks, Mass, Program, Result, SensorId, Simulation, SimulationBuilder, SpaceKind};
use common::plot::{Series, line_chart, over_time};

#[derive(Default)]
struct HelloWorld {
    sensors: Option<(SensorId<Gps>, SensorId<Velometer>)>,
}

impl Hooks for HelloWorld {}

impl Program for HelloWorld {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
        self.sensors = Some((sim.add_sensor(Gps::new(ball))?, sim.add_sensor(Velometer::new(ball))?));
        Ok(())
    }
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(1.0);
    let mut program = HelloWorld::default();
    let sim = common::args::run(&mut program, &args)?;
    let (gps, velometer) = program.sensors.expect("created with the simulation");
    let (gps_log, velometer_log) = (sim.records(gps)?, sim.records(velometer)?);
    let (gps, velometer) = (gps_log.samples(), velometer_log.samples());
    let every_10_ms = (0.01 / sim.scene().time_step()).round() as usize;
    println!("{:>6} {:>10} {:>11}", "t [s]", "y [m]", "vy [m/s]");
    for (p, v) in gps.iter().zip(velometer).skip(every_10_ms - 1).step_by(every_10_ms) {
        println!("{:>6.3} {:>10.6} {:>11.6}", p.time, p.record.position.y, v.record.linear.y);
    }
    if let Some(path) = &args.csv {
        common::args::export_csv_table(path, &[("gps", gps_log), ("velometer", velometer_log)], args.every)?;
    }
    if let Some(dir) = &args.plot {
        let height = Series::new("ball centre", over_time(gps, |r| r.position.y));
        line_chart(
            dir,
            "hello_world_height.png",
            "Hello world: the falling ball",
            "time [s]",
            "height y [m]",
            &[height],
        )?;
    }
    Ok(())
}
