//! The original's `FallingBalls` demo: three balls of different sizes and masses fall
//! on the floor. Prints when each first touches it; `--csv` writes their heights
//! (`step,t,y1,y2,y3`), `--plot` draws them.
//!
//! `cargo run --release --example falling_balls`

#[path = "common/mod.rs"]
mod common;

use ars_programs::FallingBalls;
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(2.0);
    let mut program = FallingBalls::default();
    let sim = common::args::run(&mut program, &args)?;
    let logs: Vec<_> =
        program.balls.iter().map(|(_, gps)| sim.records(*gps).map(|l| l.samples())).collect::<Result<_, _>>()?;
    for ((ball, _), log) in program.balls.iter().zip(&logs) {
        let object = sim.scene().object(*ball)?;
        let (name, radius) = (object.name(), object.shape().clone());
        let r = match radius {
            ars::Shape::Sphere { radius } => radius,
            _ => unreachable!("the balls are spheres"),
        };
        let landed = log.iter().find(|s| s.record.position.y < r + 1e-3).map(|s| s.time);
        let mass = sim.scene().body(*ball)?.mass();
        match landed {
            Some(t) => println!("{name}: radius {r} m, mass {mass:.4} kg, touches the floor at {t:.4} s"),
            None => println!("{name}: radius {r} m, mass {mass:.4} kg, still falling"),
        }
    }
    if let Some(path) = &args.csv {
        let names = ["ball 1", "ball 2", "ball 3"];
        let table: Vec<(&str, &dyn ars::sensors::CsvColumns)> = program
            .balls
            .iter()
            .zip(names)
            .map(|((_, gps), name)| Ok((name, sim.records(*gps)? as _)))
            .collect::<ars::Result<_>>()?;
        common::args::export_csv_table(path, &table, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let series: Vec<_> = logs
            .iter()
            .enumerate()
            .map(|(i, l)| Series::new(&format!("ball {}", i + 1), over_time(l, |r| r.position.y)))
            .collect();
        line_chart(dir, "falling_balls_heights.png", "Three falling balls", "time [s]", "height y [m]", &series)?;
    }
    Ok(())
}
