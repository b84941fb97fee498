//! Seeded random sequences of public API calls with hostile values (see
//! `api_sequences/mod.rs`), each batch in a child process, so that an abort, a
//! segfault or a hang is reported as a failure naming its seed instead of killing the
//! test run.
//!
//! By default it runs for at most about 60 s (`ARS_SEQUENCE_SECONDS` changes that).
//! Reproduce a failure with `ARS_SEQUENCE_SEEDS=N cargo test -p ars-core --test
//! random_api_sequences -- --exact run_seeds_from_env --nocapture`.

mod api_sequences;

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Seeds per child process.
const BATCH: u64 = 10;
/// API calls per sequence.
const CALLS: usize = 400;
/// A batch that takes longer than this is a hang.
const BATCH_TIMEOUT: Duration = Duration::from_secs(120);

/// The bytes of sequence `seed` (xorshift64*: the same on every machine).
fn sequence(seed: u64) -> Vec<u8> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..8 * CALLS)
        .map(|_| {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            (x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8
        })
        .collect()
}

/// The child: runs the seeds of `ARS_SEQUENCE_SEEDS` ("N" or "A..B"), printing each
/// seed before running it. Without the variable it does nothing.
#[test]
fn run_seeds_from_env() {
    let Ok(spec) = std::env::var("ARS_SEQUENCE_SEEDS") else { return };
    let (start, end) = match spec.split_once("..") {
        Some((a, b)) => (a.parse().expect("seed range start"), b.parse().expect("seed range end")),
        None => {
            let n: u64 = spec.parse().expect("a seed");
            (n, n + 1)
        }
    };
    // Hooks that panic are contained by the simulation; keep their messages quiet.
    std::panic::set_hook(Box::new(|_| {}));
    for seed in start..end {
        println!("seed {seed}");
        api_sequences::Harness::run(&sequence(seed), CALLS, true);
    }
    println!("batch done");
}

/// Replays every input of a fuzz corpus or crash directory (`ARS_REPLAY_DIR`, e.g.
/// `fuzz/corpus/api_calls`) in this process, as the fuzz target runs them: for
/// valgrind, and to reproduce a fuzzer's crash without libFuzzer. Without the variable
/// it does nothing.
#[test]
fn replay_inputs_from_env() {
    let Ok(dir) = std::env::var("ARS_REPLAY_DIR") else { return };
    let mut files: Vec<_> = std::fs::read_dir(&dir).expect("a readable directory").map(|e| e.unwrap().path()).collect();
    files.sort();
    for file in &files {
        api_sequences::Harness::run(&std::fs::read(file).expect("a readable input"), 300, false);
    }
    println!("replayed {} inputs from {dir}", files.len());
}

#[test]
fn random_api_sequences_never_abort_crash_or_hang() {
    let budget =
        Duration::from_secs(std::env::var("ARS_SEQUENCE_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(60));
    let exe = std::env::current_exe().expect("the test binary");
    let started = Instant::now();
    let mut next = 0u64;
    let mut slowest_batch = Duration::ZERO;
    while started.elapsed() + slowest_batch < budget {
        let range = format!("{next}..{}", next + BATCH);
        let mut child = Command::new(&exe)
            .args(["--exact", "run_seeds_from_env", "--nocapture", "--test-threads=1"])
            .env("ARS_SEQUENCE_SEEDS", &range)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawning the child test process");
        let stdout = child.stdout.take().expect("piped stdout");
        let (lines_tx, lines) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if lines_tx.send(line).is_err() {
                    break;
                }
            }
        });
        let batch_started = Instant::now();
        let mut last_seed = None;
        let mut done = false;
        loop {
            match lines.recv_timeout(Duration::from_millis(200)) {
                Ok(line) => {
                    if let Some(seed) = line.strip_prefix("seed ") {
                        last_seed = seed.parse::<u64>().ok();
                    }
                    done |= line == "batch done";
                }
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            }
            if batch_started.elapsed() > BATCH_TIMEOUT {
                let _ = child.kill();
                let _ = child.wait();
                panic!(
                    "seed {last_seed:?} hung (no progress for {BATCH_TIMEOUT:?}); reproduce with ARS_SEQUENCE_SEEDS={}",
                    last_seed.unwrap_or(next)
                );
            }
        }
        let status = child.wait().expect("waiting for the child");
        assert!(
            status.success() && done,
            "seed {last_seed:?} killed its process ({status}); reproduce with ARS_SEQUENCE_SEEDS={} cargo test -p ars-core --test random_api_sequences -- --exact run_seeds_from_env --nocapture",
            last_seed.unwrap_or(next)
        );
        slowest_batch = slowest_batch.max(batch_started.elapsed());
        next += BATCH;
    }
    println!("{next} random API sequences of {CALLS} calls ran in {:.0?}: no abort, crash or hang", started.elapsed());
}
