//! One run of 25,000 steps (10 simulated s) of the thesis' mobile manipulator, headless
//! or published, for instruction counts that a loaded machine does not blur:
//!
//! ```sh
//! cargo build --release -p ars-ros --example publishing_cost
//! valgrind --tool=callgrind --separate-threads=yes target/release/examples/publishing_cost headless
//! valgrind --tool=callgrind --separate-threads=yes target/release/examples/publishing_cost bridge
//! ```
//!
//! `headless`: the steps alone. `mcap`: recorded into an MCAP file. `bridge`: stepped
//! through the bridge in lock step by one `StepSimulation` call from another node in
//! this process (the state published at the default 50 Hz, no subscriber). Compare the
//! stepping thread's count (callgrind's file of the thread that ran the steps: the main
//! thread for `headless` and `mcap`, the `bridge` thread for `bridge`) with the others'.

#[path = "../tests/common/mod.rs"]
mod common;

use ars_ros::bridge::{BridgeOptions, run};
use ars_ros::{RosOptions, record_mcap};
use common::{Tester, mobile_manipulator};

const STEPS: u64 = 25_000;

fn bridge() {
    let domain = 101 + (std::process::id() % 100) as u16;
    let options = BridgeOptions { domain_id: domain, lock_step: true, ..Default::default() };
    std::thread::Builder::new()
        .name("bridge".into())
        .spawn(move || run(mobile_manipulator(), &options).map(|sim| sim.scene().step_count()))
        .unwrap();
    let tester = Tester::on_domain(domain);
    tester.wait_for_bridge();
    let answer = tester.step(STEPS);
    println!("stepped: {:?}", answer.result);
    std::process::exit(0);
}

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("headless") => {
            let mut sim = mobile_manipulator();
            sim.step_n(STEPS).unwrap();
            println!("t = {} s", sim.scene().time());
        }
        Some("mcap") => {
            let mut sim = mobile_manipulator();
            let path = std::env::temp_dir().join(format!("publishing-cost-{}.mcap", std::process::id()));
            let options = RosOptions::for_scene(sim.scene());
            let duration = STEPS as f64 * sim.scene().time_step();
            record_mcap(&mut sim, &path, duration, &options, || false).unwrap();
            std::fs::remove_file(path).unwrap();
        }
        Some("bridge") => bridge(),
        _ => eprintln!("usage: publishing_cost headless|mcap|bridge"),
    }
}
