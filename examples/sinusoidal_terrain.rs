//! IROS example 4 (IFAC fig. 5): the mobile manipulator drives over a sinusoidal
//! triangle-mesh terrain while PD controllers hold its arm upright. Prints when it
//! falls off the terrain and the arm's largest deviation; `--csv` writes
//! `t,x,y,z,q1,torque1,q2,torque2,wheel_torque` every step, `--plot` the three panels
//! (base height, arm angles, arm torques).
//!
//! `cargo run --release --example sinusoidal_terrain -- --csv ex4.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars::programs::{SinusoidalTerrain, TerrainRow};
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(14.0);
    let mut program = SinusoidalTerrain::default();
    common::args::run(&mut program, &args)?;
    let rows = &program.rows;
    // The terrain ends at x = 29 m; off it, the base falls below the lowest terrain.
    match (SinusoidalTerrain::leaves_terrain(rows), rows.iter().find(|r| r.position.y < -1.0)) {
        (Some(t), Some(r)) => {
            println!(
                "the vehicle drops off the terrain's +X end at {t:.2} s (its wheels pass x = 29 m; the original: near 10.7 s) and falls below it at {:.2} s",
                r.time
            )
        }
        _ => println!("the vehicle is still on the terrain"),
    }
    let deg = |r: &&TerrainRow| r.q1.abs().max(r.q2.abs()).to_degrees();
    let on_terrain: Vec<_> = rows.iter().filter(|r| r.position.y >= -1.0).collect();
    if let Some(worst) = on_terrain.iter().max_by(|a, b| deg(a).total_cmp(&deg(b))) {
        println!(
            "largest arm deviation on the terrain: {:.2} deg at {:.2} s (paper: under 3 deg)",
            deg(worst),
            worst.time
        );
    }
    if let Some(path) = &args.csv {
        let lines = rows.iter().step_by(args.every).map(|r| {
            let p = r.position;
            format!(
                "{},{},{},{},{},{},{},{},{}",
                r.time, p.x, p.y, p.z, r.q1, r.torque1, r.q2, r.torque2, r.wheel_torque
            )
        });
        common::args::write_csv(path, "t,x,y,z,q1,torque1,q2,torque2,wheel_torque", lines)?;
    }
    if let Some(dir) = &args.plot {
        let s = |f: fn(&TerrainRow) -> f64| rows.iter().step_by(40).map(|r| (r.time, f(r))).collect();
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
