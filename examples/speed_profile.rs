//! IROS example 3 (thesis §3.3, fig. 3.4): the mobile manipulator follows a
//! trapezoidal speed profile while its free arm falls from upright and swings. Prints a
//! summary; `--csv` writes the program's record of every step (time, step, x, speed,
//! set-point, arm angles and rates, wheel torque), `--plot` the three panels of
//! fig. 3.4. `--pd` uses the paper's PD variant (Kd 1).
//!
//! `cargo run --release --example speed_profile -- --csv ex3.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars_programs::SpeedProfile;
use common::plot::{Series, line_chart, unwrapped};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let pd = std::env::args().any(|a| a == "--pd");
    let args = common::args::parse_except(20.0, &["--pd"]);
    let mut program = SpeedProfile::with_derivative_gain(if pd { 1.0 } else { 0.0 });
    let sim = common::args::run(&mut program, &args)?;
    let log = sim.records(program.record.expect("created"))?;
    if let Some(e) = SpeedProfile::plateau_error(log) {
        println!(
            "speed error (v - sp) on the 6-9 s plateau: mean {:.2e} m/s, mean |error| {:.2e} m/s, worst {:.2e} m/s",
            e.mean, e.mean_abs, e.worst
        );
    }
    let torque = |s: &&ars::Sample<ars_programs::SpeedProfileRow>| s.record.wheel_torque.abs();
    let peak = log.iter().max_by(|a, b| torque(a).total_cmp(&torque(b))).expect("stepped");
    println!(
        "peak wheel torque {:.4} N m at {:.3} s (shoulder at {:.3} rad then)",
        peak.record.wheel_torque, peak.time, peak.record.q2
    );
    let last = log.last().expect("stepped");
    let r = &last.record;
    println!("at {:.1} s: x {:.3} m, waist q1 {:.4} rad, shoulder q2 {:.4} rad", last.time, r.x, r.q1, r.q2);
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let s = |f: fn(&ars_programs::SpeedProfileRow) -> f64| {
            log.iter().step_by(40).map(|s| (s.time, f(&s.record))).collect()
        };
        line_chart(
            dir,
            "fig3_4a_position_speed.png",
            "Speed profile: base position and speed (fig. 3.4, top)",
            "time [s]",
            "x [m], speed [m/s]",
            &[
                Series::new("position x [m]", s(|r| r.x)),
                Series::new("speed set-point [m/s]", s(|r| r.setpoint)),
                Series::new("speed [m/s]", s(|r| r.speed)),
            ],
        )?;
        line_chart(
            dir,
            "fig3_4b_wheel_torque.png",
            "Speed profile: wheel torque (fig. 3.4, middle)",
            "time [s]",
            "torque on each wheel [N m]",
            &[Series::new("wheel torque", s(|r| r.wheel_torque))],
        )?;
        line_chart(
            dir,
            "fig3_4c_arm_angles.png",
            "Speed profile: arm joint angles (fig. 3.4, bottom)",
            "time [s]",
            "angle [rad]",
            &[Series::new("waist q1", unwrapped(s(|r| r.q1))), Series::new("shoulder q2", unwrapped(s(|r| r.q2)))],
        )?;
    }
    Ok(())
}
