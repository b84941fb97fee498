//! Ctrl-C stops a Rust program cleanly: the example stops between two frames, says so,
//! and writes the CSV of what it ran (the examples install `ars::interrupt`'s handler).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// An example built by `cargo test` beside this test's binary.
fn example(name: &str) -> std::path::PathBuf {
    let exe = std::env::current_exe().expect("this test");
    let dir = exe.parent().and_then(|deps| deps.parent()).expect("the target folder");
    let path = dir.join("examples").join(name);
    assert!(path.is_file(), "the {name} example is not built (cargo test builds the examples)");
    path
}

#[test]
fn ctrl_c_stops_an_example_and_its_csv_is_written() {
    let csv = std::env::temp_dir().join(format!("ars-ctrl-c-{}.csv", std::process::id()));
    let _ = std::fs::remove_file(&csv);
    // A million seconds of simulated time: only Ctrl-C ends it.
    let mut child = Command::new(example("conical_pendulum"))
        .args(["--duration", "1000000", "--every", "50", "--csv"])
        .arg(&csv)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the example starts");
    let (status, stopped, stderr) = interrupt_after(&mut child, Duration::from_millis(1500));
    assert!(status.success(), "the example failed after Ctrl-C: {status}\n{stderr}");
    assert!(stderr.contains("interrupted (Ctrl-C) at t = "), "{stderr}");
    let (lines, last_time) = csv_rows(&csv);
    println!("stopped {stopped:?} after Ctrl-C at t = {last_time} s, {lines} CSV lines");
}

#[cfg(feature = "ros")]
#[test]
fn ctrl_c_ends_an_example_run_as_a_ros_node_and_its_csv_is_written() {
    let csv = std::env::temp_dir().join(format!("ars-ctrl-c-ros-{}.csv", std::process::id()));
    let _ = std::fs::remove_file(&csv);
    // Real time, until Ctrl-C, on a domain of its own.
    let domain = (150 + std::process::id() % 80).to_string();
    let mut child = Command::new(example("conical_pendulum"))
        .args(["--ros", "--domain-id", &domain, "--every", "50", "--csv"])
        .arg(&csv)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the example starts");
    let (status, _, stderr) = interrupt_after(&mut child, Duration::from_millis(2500));
    assert!(status.success(), "the example failed after Ctrl-C: {status}\n{stderr}");
    assert!(stderr.contains(&format!("ars ros: node /ars on ROS domain {domain}, real time")), "{stderr}");
    assert!(stderr.contains("interrupted (Ctrl-C) at t = "), "{stderr}");
    let (lines, last_time) = csv_rows(&csv);
    assert!(last_time > 0.2, "paced to the wall clock for about 2 s, it ran to t = {last_time} s ({lines} lines)");
}

/// Sends Ctrl-C to `child` after `delay`: how it ended, how long it took, its stderr.
fn interrupt_after(child: &mut std::process::Child, delay: Duration) -> (std::process::ExitStatus, Duration, String) {
    std::thread::sleep(delay);
    let sent = Instant::now();
    let kill = Command::new("kill").args(["-INT", &child.id().to_string()]).status().expect("kill runs");
    assert!(kill.success());
    let status = loop {
        if let Some(status) = child.try_wait().expect("the example") {
            break status;
        }
        if sent.elapsed() > Duration::from_secs(20) {
            let _ = child.kill();
            panic!("the example ran on for 20 s after Ctrl-C");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let stopped = sent.elapsed();
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().expect("piped"), &mut stderr).expect("stderr");
    (status, stopped, stderr)
}

/// The CSV's line count and last time, checked to hold data; the file is removed.
fn csv_rows(csv: &std::path::Path) -> (usize, f64) {
    let text = std::fs::read_to_string(csv).expect("the CSV was written");
    let _ = std::fs::remove_file(csv);
    let last_time: f64 = text
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no data row in the CSV:\n{}", &text[..text.len().min(300)]));
    assert!(text.lines().count() > 10 && last_time > 0.0, "{} lines, last at t = {last_time}", text.lines().count());
    (text.lines().count(), last_time)
}
