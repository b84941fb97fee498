//! The original's joint sensor demos (`joint_torque1`, `joint_power1`, `rotary_joint`)
//! on the centrifugal-force scene: the torque and power the "friction" adds to the
//! cable hinge r2 (once per frame: −500 · rate), and r2's angle and rate every frame.
//! Prints a summary and the last records; `--csv` writes every step
//! (`step,t,torque,power`), `--plot` draws the power.
//!
//! `cargo run --release --example joint_sensors`

#[path = "common/mod.rs"]
mod common;

use ars_programs::CentrifugalForce;
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(5.0);
    let mut program = CentrifugalForce::default();
    let sim = common::args::run(&mut program, &args)?;
    let (torque, power, angle) = program.sensors.expect("created with the simulation");
    let (torque, power, angle) = (sim.records(torque)?, sim.records(power)?, sim.records(angle)?);
    let applied = torque.iter().filter(|s| s.record.value != 0.0).count();
    println!("JointTorque: {} records, {applied} with a torque (one per frame)", torque.len());
    let worst = power.iter().map(|s| s.record.power).fold(0.0, f64::min);
    println!("JointPower: never positive; most negative {worst:.6} W (the friction only takes energy)");
    println!("HingeSensor: {} records (one per frame); the last three:", angle.len());
    for s in &angle.samples()[angle.len().saturating_sub(3)..] {
        println!("  t {:.2} s: angle {:.6} rad, rate {:.6} rad/s", s.time, s.record.position, s.record.rate);
    }
    if let Some(path) = &args.csv {
        common::args::export_csv_table(path, &[("r2 torque", torque), ("r2 power", power)], args.every)?;
    }
    if let Some(dir) = &args.plot {
        let p: Vec<_> = over_time(power.samples(), |r| r.power).into_iter().filter(|p| p.1 != 0.0).collect();
        line_chart(
            dir,
            "joint_power.png",
            "JointPower on the cable hinge",
            "time [s]",
            "power [W]",
            &[Series::new("r2 friction", p)],
        )?;
    }
    Ok(())
}
