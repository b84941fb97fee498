//! IROS example 4 (IFAC fig. 5): the mobile manipulator drives over a sinusoidal
//! triangle-mesh terrain while PD controllers hold its arm upright. Prints when it
//! falls off the terrain and the arm's largest deviation; `--csv` writes the program's
//! record of every step (time, step, chassis position, wheels x, arm angles and
//! torques, wheel torque), `--plot` the three panels (base height, arm angles, arm
//! torques).
//!
//! `cargo run --release --example sinusoidal_terrain -- --csv ex4.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars::Sample;
use ars_programs::{SinusoidalTerrain, TerrainRow};
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(14.0);
    let mut program = SinusoidalTerrain::default();
    let sim = common::args::run(&mut program, &args)?;
    let log = sim.records(program.record.expect("created"))?;
    // The terrain ends at x = 29 m; off it, the base falls below the lowest terrain.
    match (SinusoidalTerrain::leaves_terrain(log), log.iter().find(|s| s.record.position.y < -1.0)) {
        (Some(t), Some(s)) => {
            println!(
                "the vehicle drops off the terrain's +X end at {t:.2} s (its wheels pass x = 29 m; the original: near 10.7 s) and falls below it at {:.2} s",
                s.time
            )
        }
        _ => println!("the vehicle is still on the terrain"),
    }
    let deg = |s: &&Sample<TerrainRow>| s.record.q1.abs().max(s.record.q2.abs()).to_degrees();
    let on_terrain: Vec<_> = log.iter().filter(|s| s.record.position.y >= -1.0).collect();
    if let Some(worst) = on_terrain.iter().max_by(|a, b| deg(a).total_cmp(&deg(b))) {
        println!(
            "largest arm deviation on the terrain: {:.2} deg at {:.2} s (paper: under 3 deg)",
            deg(worst),
            worst.time
        );
    }
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let s = |f: fn(&TerrainRow) -> f64| log.iter().step_by(40).map(|s| (s.time, f(&s.record))).collect();
        line_chart(
            dir,
            "ex4_a_base_height.png",
            "Sinusoidal terrain: base height (IFAC fig. 5, top)",
            "time [s]",
            "chassis y [m]",
            &[Series::new("chassis y", s(|r| r.position.y))],
        )?;
        line_chart(
            dir,
            "ex4_b_arm_angles.png",
            "Sinusoidal terrain: arm angles (IFAC fig. 5, middle)",
            "time [s]",
            "angle [deg]",
            &[Series::new("waist q1", s(|r| r.q1.to_degrees())), Series::new("shoulder q2", s(|r| r.q2.to_degrees()))],
        )?;
        line_chart(
            dir,
            "ex4_c_arm_torques.png",
            "Sinusoidal terrain: arm torques (IFAC fig. 5, bottom)",
            "time [s]",
            "torque [N m]",
            &[Series::new("waist", s(|r| r.torque1)), Series::new("shoulder", s(|r| r.torque2))],
        )?;
    }
    Ok(())
}
