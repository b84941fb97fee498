//! How much an MCAP recording at the default rates slows a headless run of the thesis'
//! mobile manipulator: a measure, not a check (`cargo test --release -p ars-ros --test
//! overhead -- --ignored --nocapture`).

use std::time::Instant;

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, Simulation};
use ars_ros::{RosOptions, record_mcap};

fn manipulator() -> Simulation {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let spec = ars_programs::VehicleSpec::default();
    ars_programs::build_mobile_manipulator(&mut sim, &spec, Mass::Total(1.0)).unwrap();
    sim
}

#[test]
#[ignore = "a measure: run in release with --ignored --nocapture"]
fn recording_overhead_at_the_default_rates() {
    let path = std::env::temp_dir().join(format!("ars-ros-overhead-{}.mcap", std::process::id()));
    let (mut plain, mut recorded) = (Vec::new(), Vec::new());
    for _ in 0..5 {
        let mut sim = manipulator();
        let start = Instant::now();
        sim.run_for(10.0).unwrap();
        plain.push(start.elapsed().as_secs_f64());
        let mut sim = manipulator();
        let options = RosOptions::for_scene(sim.scene());
        let start = Instant::now();
        record_mcap(&mut sim, &path, 10.0, &options, || false).unwrap();
        recorded.push(start.elapsed().as_secs_f64());
    }
    let best = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let (p, r) = (best(&plain), best(&recorded));
    println!(
        "10 s of the mobile manipulator (25,000 steps): headless {p:.4} s, recording MCAP {r:.4} s: {:+.1} %",
        (r / p - 1.0) * 100.0
    );
    std::fs::remove_file(&path).unwrap();
}
