//! IROS example 1: a small ball bouncing on the floor (1 m drop, dt 0.25 ms). Prints
//! the bounce times next to the ideal ones; `--paper` uses the paper's restitution 0.9
//! instead of the code's 0.2. `--csv` writes the program's record (time, step, y, vy:
//! the original's print, at the start of every step), `--plot` draws the height.
//!
//! `cargo run --release --example bouncing_ball -- --paper --duration 4`

#[path = "common/mod.rs"]
mod common;

use ars_programs::BouncingBall;
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let paper = std::env::args().any(|a| a == "--paper");
    let args = common::args::parse_except(if paper { 4.0 } else { 1.0 }, &["--paper"]);
    let mut program = BouncingBall { paper_bounce: paper, ..Default::default() };
    let sim = common::args::run(&mut program, &args)?;
    let log = sim.records(program.record.expect("created"))?;
    let ideal: &[f64] = if paper { &[0.4515, 1.264, 1.996, 2.654, 3.247] } else { &[0.4515, 0.632, 0.668, 0.676] };
    println!("restitution {}: bounces at (ideal: {ideal:?} s)", if paper { "0.9 (paper)" } else { "0.2 (code)" });
    for (i, t) in BouncingBall::bounce_times(log).iter().take(6).enumerate() {
        println!("  bounce {}: {t:.4} s", i + 1);
    }
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let y = log.iter().step_by(40).map(|s| (s.time, s.record.y)).collect();
        line_chart(
            dir,
            "bouncing_ball_height.png",
            "Bouncing ball (IROS example 1)",
            "time [s]",
            "height y [m]",
            &[Series::new("ball centre", y)],
        )?;
    }
    Ok(())
}
