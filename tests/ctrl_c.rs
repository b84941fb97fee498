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
    std::thread::sleep(Duration::from_millis(1500));
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
    assert!(status.success(), "the example failed after Ctrl-C: {status}\n{stderr}");
    assert!(stderr.contains("interrupted (Ctrl-C) at t = "), "{stderr}");
    let text = std::fs::read_to_string(&csv).expect("the CSV was written");
    let _ = std::fs::remove_file(&csv);
    let last_time: f64 = text
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no data row in the CSV:\n{}", &text[..text.len().min(300)]));
    assert!(text.lines().count() > 10 && last_time > 0.0, "{} lines, last at t = {last_time}", text.lines().count());
    println!("stopped {stopped:?} after Ctrl-C at t = {last_time} s, {} CSV lines", text.lines().count());
}
