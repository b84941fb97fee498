//! How much publishing slows a headless run of the thesis' mobile manipulator at the
//! default rates: an MCAP recording, and the live bridge in lock step. Measures, not
//! checks (`cargo test --release -p ars-ros --test overhead -- --ignored --nocapture
//! --test-threads 1`).

mod common;

use std::time::Instant;

use ars_ros::bridge::sim_interfaces::CallResult;
use ars_ros::bridge::{BridgeOptions, run};
use ars_ros::{RosOptions, record_mcap};
use common::{Tester, mobile_manipulator};

/// 10 simulated seconds of 0.4 ms steps.
const STEPS: u64 = 25_000;
const RUNS: usize = 5;

fn best(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

/// This process's CPU time (user and system, every thread), s.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap();
    let fields: Vec<&str> = stat.rsplit_once(')').unwrap().1.split_whitespace().collect();
    // utime and stime, fields 14 and 15 of the line, in clock ticks (100 a second).
    (fields[11].parse::<f64>().unwrap() + fields[12].parse::<f64>().unwrap()) / 100.0
}

#[test]
#[ignore = "a measure: run in release with --ignored --nocapture"]
fn recording_overhead_at_the_default_rates() {
    let path = std::env::temp_dir().join(format!("ars-ros-overhead-{}.mcap", std::process::id()));
    // Headless runs and recordings taken in turn, so that both see the same machine.
    let (mut plain, mut recorded) = (Vec::new(), Vec::new());
    for _ in 0..RUNS {
        let mut sim = mobile_manipulator();
        let start = Instant::now();
        sim.step_n(STEPS).unwrap();
        plain.push(start.elapsed().as_secs_f64());
        let mut sim = mobile_manipulator();
        let options = RosOptions::for_scene(sim.scene());
        let start = Instant::now();
        record_mcap(&mut sim, &path, 10.0, &options, || false).unwrap();
        recorded.push(start.elapsed().as_secs_f64());
    }
    let (p, r) = (best(&plain), best(&recorded));
    println!(
        "10 s of the mobile manipulator ({STEPS} steps): headless {p:.4} s, recording MCAP {r:.4} s: {:+.1} %",
        (r / p - 1.0) * 100.0
    );
    std::fs::remove_file(&path).unwrap();
}

#[test]
#[ignore = "a measure: run in release with --ignored --nocapture"]
fn bridge_overhead_in_lock_step_at_the_default_rates() {
    let domain = 51 + (std::process::id() % 50) as u16;
    let options = BridgeOptions { domain_id: domain, lock_step: true, ..Default::default() };
    let bridge = std::thread::spawn(move || run(mobile_manipulator(), &options).map(|sim| sim.scene().step_count()));
    let tester = Tester::on_domain(domain);
    tester.wait_for_bridge();
    // Headless runs and calls taken in turn, so that both see the same machine.
    let (mut plain, mut calls, mut cpu) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..RUNS {
        let mut sim = mobile_manipulator();
        let start = Instant::now();
        sim.step_n(STEPS).unwrap();
        plain.push(start.elapsed().as_secs_f64());
        let (start, cpu_start) = (Instant::now(), cpu_seconds());
        assert_eq!(tester.step(STEPS).result, CallResult::ok());
        calls.push(start.elapsed().as_secs_f64());
        cpu.push(cpu_seconds() - cpu_start);
    }
    assert_eq!(tester.quit().result, CallResult::ok());
    assert_eq!(bridge.join().unwrap().unwrap(), RUNS as u64 * STEPS);
    let (p, b) = (best(&plain), best(&calls));
    println!(
        "10 s of the mobile manipulator ({STEPS} steps): headless {p:.4} s; one StepSimulation call of them through \
         the bridge (the state published at 50 Hz, no subscriber) {b:.4} s: {:+.1} %; the process's CPU time during \
         the call (every thread: the bridge's, its publishing thread, DDS's, the calling node's) {:.2} s",
        (b / p - 1.0) * 100.0,
        best(&cpu)
    );
}
