//! The golden hashes: the exact outputs of the thesis programs, a URDF arm and a
//! scene of seeded noisy sensors, held by the sha256 table `ars-programs/golden.json`.
//! A change that alters a single bit of physics fails here, with where the output
//! first differs; updating the table is deliberate (`cargo run --release --example
//! verify -- --write`, and a CHANGELOG line saying which results changed and why).

use ars_programs::golden::{GoldenTable, Verdict, runs, sha256_hex};

#[test]
fn every_golden_run_computes_the_committed_bits() {
    let table = GoldenTable::committed();
    let mut report = Vec::new();
    for run in runs() {
        let output = run.output().unwrap_or_else(|e| panic!("{}: {e}", run.name));
        let verdict = table.compare(run.name, &output);
        if verdict != Verdict::Identical {
            report.push(format!("{} ({}): {verdict}", run.name, run.what));
        }
    }
    assert!(report.is_empty(), "golden runs differ from ars-programs/golden.json:\n{}", report.join("\n"));
}

/// An example built by `cargo test` beside this test's binary.
fn example(name: &str) -> std::path::PathBuf {
    let exe = std::env::current_exe().expect("this test");
    let dir = exe.parent().and_then(|deps| deps.parent()).expect("the target folder");
    dir.join("examples").join(name)
}

#[test]
fn an_examples_csv_is_the_golden_runs_output() {
    // What a user gets from `--csv` is what the table holds.
    let csv = std::env::temp_dir().join(format!("ars-golden-{}.csv", std::process::id()));
    let status = std::process::Command::new(example("falling_ball_sensors"))
        .args(["--duration", "2", "--csv"])
        .arg(&csv)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .expect("the example runs (cargo test builds the examples)");
    assert!(status.success());
    let bytes = std::fs::read(&csv).expect("the CSV");
    let _ = std::fs::remove_file(&csv);
    let entry = GoldenTable::committed().entry("falling_ball_sensors").cloned().expect("in the table");
    assert_eq!(sha256_hex(&bytes), entry.sha256);
}
