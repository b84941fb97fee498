//! IROS example 5: the user drives the mobile manipulator with the arrow keys while a
//! PD controller holds the shoulder ('d'/'c' move its set-point, 'a'/'z' push the
//! waist). Headless, a key script plays the user (`--keys FILE`, lines
//! `TIME down|up KEY`); the default script drives a full circle. `--paper` uses the
//! paper's friction limit (mu 50) instead of the code's 500. Prints the heading turned
//! and the shoulder's largest error; `--csv` writes the program's record of every step,
//! `--plot` the XZ path and the joint errors.
//!
//! `cargo run --release --example user_driven -- --paper --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars::{KeyScript, ProgramRunner};
use ars_programs::{DrivingRow, UserDriven};
use common::plot::{Series, line_chart, unwrapped};

/// A short push forward, then left held (the wheels turn opposite ways: the vehicle
/// spins) until it has turned a little more than once around, then released.
const CIRCLE: &str = "\
0.0 down up
0.6 up up
0.6 down left
7.0 up left
";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let argv: Vec<String> = std::env::args().collect();
    let paper = argv.iter().any(|a| a == "--paper");
    let keys = argv.iter().position(|a| a == "--keys").and_then(|i| argv.get(i + 1)).cloned();
    let mut skip: Vec<&str> = vec!["--paper"];
    if let Some(k) = &keys {
        skip.extend(["--keys", k.as_str()]);
    }
    let args = common::args::parse_except(9.0, &skip);
    let script = match &keys {
        Some(path) => KeyScript::parse(&std::fs::read_to_string(path)?)?,
        None => KeyScript::parse(CIRCLE)?,
    };
    let mut program = UserDriven { paper_friction: paper, ..Default::default() };
    if args.live() {
        return drive_live(&mut program, paper, &args);
    }
    let mut runner = ProgramRunner::new(&mut program)?;
    let chassis = runner.program().vehicle.expect("built").chassis;
    let mut heading = Vec::new();
    let steps_per_frame = u64::from(runner.simulation().scene().steps_per_frame());
    let frames = runner.simulation().scene().steps_in(args.duration)? / steps_per_frame;
    let mut capture = common::args::Capture::new(&args, ars::Program::window_settings(runner.program()))?;
    capture.record_ros(runner.simulation_mut())?;
    for _ in 0..frames {
        capture.frame(runner.simulation())?;
        runner.run_script_frame(&script)?;
        let r = runner.simulation().scene().rotation(chassis)?;
        let x = r * ars::nalgebra::Vector3::x();
        heading.push((runner.simulation().scene().time(), (-x.z).atan2(x.x)));
    }
    capture.finish(runner.simulation())?;
    let turned = unwrapped(heading.clone()).last().map_or(0.0, |h| h.1);
    let record = runner.program().record.expect("created");
    let log = runner.simulation().records(record)?;
    let settled = log.iter().filter(|s| s.time > 1.0);
    let worst = settled.map(|s| (s.record.setpoint - s.record.q2).abs()).fold(0.0, f64::max);
    println!(
        "friction limit {}: heading turned {:.1} deg; shoulder's largest error after 1 s {:.3} deg (paper: under 1.5 deg)",
        if paper { "50 (paper)" } else { "500 (code)" },
        turned.to_degrees(),
        worst.to_degrees()
    );
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        plot_figures(dir, log)?;
    }
    Ok(())
}

/// Live, in a window: the arrow keys drive the vehicle, as in the original; says where
/// it went.
fn drive_live(
    program: &mut UserDriven,
    paper: bool,
    args: &common::args::Args,
) -> Result<(), Box<dyn std::error::Error>> {
    // Live: the arrow keys drive it, as in the original.
    let start = {
        let mut probe = UserDriven { paper_friction: paper, ..Default::default() };
        let sim = ars::Program::create_simulation(&mut probe)?;
        sim.scene().position(probe.vehicle.expect("built").chassis)?
    };
    let sim = common::args::run(program, args)?;
    let chassis = program.vehicle.expect("built").chassis;
    let x = sim.scene().rotation(chassis)? * ars::nalgebra::Vector3::x();
    let p = sim.scene().position(chassis)?;
    println!(
        "after {:.1} s: chassis from ({:.2}, {:.2}) to ({:.2}, {:.2}) m, heading {:.1} deg",
        sim.scene().time(),
        start.x,
        start.z,
        p.x,
        p.z,
        (-x.z).atan2(x.x).to_degrees()
    );
    Ok(())
}

/// The path seen from above and the arm's joint errors, as PNG files in `dir`.
fn plot_figures(dir: &std::path::Path, log: &ars::SensorLog<DrivingRow>) -> Result<(), Box<dyn std::error::Error>> {
    let path: Vec<_> = log.iter().step_by(40).map(|s| (s.record.x, s.record.z)).collect();
    line_chart(
        dir,
        "ex5_path_xz.png",
        "User-driven vehicle: path seen from above",
        "x [m]",
        "z [m]",
        &[Series::new("chassis", path)],
    )?;
    let q1 = log.iter().step_by(40).map(|s| (s.time, s.record.q1.to_degrees())).collect();
    let e2 = log.iter().step_by(40).map(|s| (s.time, (s.record.setpoint - s.record.q2).to_degrees())).collect();
    line_chart(
        dir,
        "ex5_joint_errors.png",
        "User-driven vehicle: arm joint errors",
        "time [s]",
        "error [deg]",
        &[Series::new("waist (free, set-point 0)", q1), Series::new("shoulder (PD)", e2)],
    )?;
    Ok(())
}
