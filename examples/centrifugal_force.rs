//! The original's `CentrifugalForceTest`: a 1 kg ball on a 1 m rigid cable swung by a
//! pole turning at 3 rad/s. Prints the original's per-frame tuple (ball position,
//! velocity, angular velocity, cable angle) every 0.5 s and the final cable angle next
//! to the formula's 1.0415 rad; `--csv` writes the record of every frame (time, step,
//! ball position, velocity, angular velocity, cable angle),
//! `--plot` draws the cable angle.
//!
//! `cargo run --release --example centrifugal_force`

#[path = "common/mod.rs"]
mod common;

use ars_programs::CentrifugalForce;
use common::plot::{Series, line_chart};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(20.0);
    let mut program = CentrifugalForce::default();
    let sim = common::args::run(&mut program, &args)?;
    let log = sim.records(program.record.expect("created"))?;
    for s in log.iter().step_by(25) {
        let r = &s.record;
        let (p, v, w) = (r.position, r.velocity, r.angular_velocity);
        println!(
            "t {:6.2} s: ball ({:.4}, {:.4}, {:.4}) m, v ({:.4}, {:.4}, {:.4}) m/s, w ({:.4}, {:.4}, {:.4}) rad/s, theta {:.4} rad",
            s.time, p.x, p.y, p.z, v.x, v.y, v.z, w.x, w.y, w.z, r.theta
        );
    }
    let last = log.last().expect("at least one frame");
    println!(
        "final cable angle {:.4} rad; tan θ / (d + l sin θ) = ω²/g gives {:.4} rad",
        last.record.theta,
        CentrifugalForce::steady_angle(3.0)
    );
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let theta = Series::new("ARS", log.iter().map(|s| (s.time, s.record.theta)).collect());
        let formula = CentrifugalForce::steady_angle(3.0);
        let steady = Series::new("steady-state formula", vec![(0.0, formula), (last.time, formula)]);
        line_chart(
            dir,
            "centrifugal_force_angle.png",
            "CentrifugalForceTest: cable angle",
            "time [s]",
            "cable angle from vertical [rad]",
            &[theta, steady],
        )?;
    }
    Ok(())
}
