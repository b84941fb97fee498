//! The thesis' validation robot (IROS example 2, thesis §1.5, fig. 1.11): a 2-DOF arm on
//! a heavy free base; a saturating waist torque against viscous friction swings the
//! free shoulder out into a conical pendulum. Prints the final waist rate and shoulder
//! angle next to the thesis'; `--csv` writes the program's record (time, step, waist
//! and shoulder angles and rates, waist torque: the state the pre-step hook reads at the
//! start of each step, every `--every N` steps),
//! `--plot` the waist rate and shoulder angle of ARS against the reduced-coordinate model.
//!
//! `cargo run --release --example conical_pendulum -- --csv pendulum.csv --every 40 --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars_programs::{ArmParameters, ConicalPendulum, ReducedArmModel};
use common::args::export_csv;
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(20.0);
    let mut program = ConicalPendulum::default();
    let sim = common::args::run(&mut program, &args)?;
    let log = sim.records(program.record.expect("created"))?;
    let last = log.last().expect("at least one step").record;
    let params = ArmParameters::IROS_EXAMPLE_2;
    println!(
        "after {:.2} s of simulated time ({} steps of {} s):",
        sim.scene().time(),
        sim.scene().step_count(),
        sim.scene().time_step()
    );
    println!("  waist rate     {:.4} rad/s   (thesis: almost 4 rad/s; ODE reference 3.9994)", last.q1_rate);
    println!(
        "  shoulder angle {:.4} rad     (ODE reference 0.7115; uniform-rod formula {:.4})",
        last.q2,
        params.steady_shoulder_angle(4.0)
    );
    println!(
        "  in the thesis' DH convention pi/2 - q2 = {:.3} rad (thesis: about 0.87)",
        std::f64::consts::FRAC_PI_2 - last.q2
    );

    if let Some(path) = &args.csv {
        export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let model = ReducedArmModel::trajectory(params, args.duration, 0.01, 0.001);
        let every = (0.01 / sim.scene().time_step()).round() as usize;
        let ars_rate = log.iter().step_by(every).map(|s| (s.time, s.record.q1_rate)).collect();
        let ars_angle = log.iter().step_by(every).map(|s| (s.time, s.record.q2)).collect();
        line_chart(
            dir,
            "fig1_11a_waist_rate.png",
            "Conical pendulum: waist rate (fig. 1.11)",
            "time [s]",
            "waist rate dq1/dt [rad/s]",
            &[
                Series::new("ARS (ODE)", ars_rate),
                Series::new("reduced model (RK4)", model.iter().map(|s| (s.time, s.phi_rate)).collect()),
            ],
        )?;
        line_chart(
            dir,
            "fig1_11b_shoulder_angle.png",
            "Conical pendulum: shoulder angle (fig. 1.11)",
            "time [s]",
            "shoulder angle q2 from hanging [rad]",
            &[
                Series::new("ARS (ODE)", ars_angle),
                Series::new("reduced model (RK4)", model.iter().map(|s| (s.time, s.beta)).collect()),
            ],
        )?;
    }
    Ok(())
}
