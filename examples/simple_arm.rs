//! The original's `SimpleArm` demo: a two-link arm on a free base; in the viewer the
//! keys 'a'/'z' push the waist. Headless, the waist gets one push per frame for the
//! first 0.2 s (as if 'a' were tapped); prints the joint angles every 0.5 s.
//! `--csv` writes the two joints' angle sensors as one table, `--plot` draws them.
//!
//! `cargo run --release --example simple_arm`

#[path = "common/mod.rs"]
mod common;

use ars::sensors::HingeSensor;
use ars::{Key, ProgramRunner};
use ars_programs::SimpleArm;
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(3.0);
    let mut program = SimpleArm::default();
    if args.live() {
        // Live: 'a'/'z' push the waist.
        common::args::run(&mut program, &args)?;
        return Ok(());
    }
    let mut runner = ProgramRunner::new(&mut program)?;
    let parts = runner.program().parts.expect("built");
    let waist = runner.simulation_mut().add_sensor(HingeSensor::new(parts.r1))?;
    let shoulder = runner.simulation_mut().add_sensor(HingeSensor::new(parts.r2))?;
    let steps = runner.simulation().scene().steps_in(args.duration)?;
    let mut capture = common::args::Capture::new(&args, ars::Program::window_settings(runner.program()))?;
    capture.record_ros(runner.simulation_mut())?;
    let spf = u64::from(runner.simulation().scene().steps_per_frame());
    for step in 0..steps {
        if step % spf == 0 {
            capture.frame(runner.simulation())?;
        }
        if step % u64::from(runner.simulation().scene().steps_per_frame()) == 0
            && runner.simulation().scene().time() < 0.2
        {
            runner.key_down(Key::Char('a'))?;
        }
        runner.step()?;
    }
    capture.finish(runner.simulation())?;
    let sim = runner.simulation();
    let (q1, q2) = (sim.records(waist)?, sim.records(shoulder)?);
    let every_half_second = (0.5 / sim.scene().time_step()).round() as usize;
    for (a, b) in q1.iter().zip(q2).skip(every_half_second - 1).step_by(every_half_second) {
        let (t, q1, q2) = (a.time, a.record.position, b.record.position);
        println!("t = {t:.2} s: waist q1 = {q1:+.4} rad, shoulder q2 = {q2:+.4} rad");
    }
    if let Some(path) = &args.csv {
        common::args::export_csv_table(path, &[("waist", q1), ("shoulder", q2)], args.every)?;
    }
    if let Some(dir) = &args.plot {
        let q1 = Series::new("waist q1", over_time(q1.samples(), |r| r.position));
        let q2 = Series::new("shoulder q2", over_time(q2.samples(), |r| r.position));
        line_chart(dir, "simple_arm_angles.png", "SimpleArm: joint angles", "time [s]", "angle [rad]", &[q1, q2])?;
    }
    Ok(())
}
