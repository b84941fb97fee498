//! The original's `ControlledSimpleArm` demo: the shoulder held upright by a PD
//! controller; in the viewer 'd'/'c' move its set-point. Headless, the set-point is
//! raised by 0.1 rad (a 'd' press) at 1 s and 2 s. Prints the original's line
//! (`time, sp, cv, error, torque`) every 0.25 s; `--csv` writes the program's record
//! of every step (time, step, set-point, angle, error, torque), `--plot` draws set-point
//! and angle.
//!
//! `cargo run --release --example controlled_simple_arm`

#[path = "common/mod.rs"]
mod common;

use ars::{Key, ProgramRunner};
use ars_programs::ControlledSimpleArm;
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(6.0);
    let mut program = ControlledSimpleArm::default();
    if args.live() {
        // Live: the program's keys move the set-point.
        common::args::run(&mut program, &args)?;
        return Ok(());
    }
    let mut runner = ProgramRunner::new(&mut program)?;
    let steps = runner.simulation().scene().steps_in(args.duration)?;
    let dt = runner.simulation().scene().time_step();
    let mut capture = common::args::Capture::new(&args, ars::Program::window_settings(runner.program()))?;
    capture.record_ros(runner.simulation_mut())?;
    let spf = u64::from(runner.simulation().scene().steps_per_frame());
    for step in 0..steps {
        if step % spf == 0 {
            capture.frame(runner.simulation())?;
        }
        if step == (1.0 / dt).round() as u64 || step == (2.0 / dt).round() as u64 {
            runner.key_down(Key::Char('d'))?;
        }
        runner.step()?;
    }
    capture.finish(runner.simulation())?;
    let record = runner.program().record.expect("created");
    let log = runner.simulation().records(record)?;
    let every = (0.25 / dt).round() as usize;
    for s in log.iter().step_by(every) {
        let r = &s.record;
        println!(
            "time: {:.6}, sp: {:.6}, cv: {:.6}, error: {:.6}, torque: {:.6}",
            s.time, r.setpoint, r.angle, r.error, r.torque
        );
    }
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let sp = Series::new("set-point", log.iter().map(|s| (s.time, s.record.setpoint)).collect());
        let cv = Series::new("shoulder angle", log.iter().map(|s| (s.time, s.record.angle)).collect());
        line_chart(
            dir,
            "controlled_simple_arm.png",
            "ControlledSimpleArm: PD shoulder",
            "time [s]",
            "angle [rad]",
            &[sp, cv],
        )?;
    }
    Ok(())
}
