//! The Rust port against native ODE, measured in the same run.
//!
//! Each reference scene of `tests/c` runs once in plain C against libode and once
//! through `ars-core` (the same ODE calls in the same order, see `tests/native_ode.rs`),
//! so the difference is the cost of the safe layer. Criterion measures both; then an
//! interleaved run (C, Rust, C, Rust...) prints the median ratio Rust / C per scene.
//!
//! `cargo bench -p ars-benches --bench native_comparison`

use std::hint::black_box;
use std::time::{Duration, Instant};

use ars_reference_scenes::{CScene, RustScene};
use criterion::{BatchSize, Criterion};

struct Case {
    name: &'static str,
    steps: usize,
    native: fn() -> CScene,
    rust: fn() -> RustScene,
}

const CASES: [Case; 3] = [
    Case {
        name: "falling sphere, 2500 steps",
        steps: 2500,
        native: CScene::falling_sphere,
        rust: RustScene::falling_sphere,
    },
    Case {
        name: "100 spheres and boxes in a hash space, 500 steps",
        steps: 500,
        native: || CScene::drop_pile(100),
        rust: || RustScene::drop_pile(100),
    },
    Case { name: "hinge chain, 2500 steps", steps: 2500, native: CScene::hinge_chain, rust: RustScene::hinge_chain },
];

fn criterion_benches(c: &mut Criterion) {
    for case in &CASES {
        let mut group = c.benchmark_group(case.name);
        group.bench_function("native C", |b| {
            b.iter_batched_ref(case.native, |s| s.step(black_box(case.steps)), BatchSize::LargeInput)
        });
        group.bench_function("ars-core", |b| {
            b.iter_batched_ref(case.rust, |s| s.step(black_box(case.steps)), BatchSize::LargeInput)
        });
        group.finish();
    }
}

fn time(f: impl FnOnce()) -> Duration {
    let start = Instant::now();
    f();
    start.elapsed()
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// Alternates the two implementations so that both see the same machine conditions.
fn ratios(rounds: usize) {
    println!("\nRust / C, median of {rounds} interleaved runs (scene built outside the timing):");
    println!("{:<52} {:>12} {:>12} {:>8}", "scene", "C", "Rust", "ratio");
    for case in &CASES {
        let (mut c_times, mut r_times) = (Vec::new(), Vec::new());
        for _ in 0..rounds {
            let mut c = (case.native)();
            c_times.push(time(|| c.step(black_box(case.steps))));
            let mut r = (case.rust)();
            r_times.push(time(|| r.step(black_box(case.steps))));
        }
        let (c, r) = (median(c_times), median(r_times));
        println!("{:<52} {:>12.3?} {:>12.3?} {:>8.3}", case.name, c, r, r.as_secs_f64() / c.as_secs_f64());
    }
}

fn main() {
    let mut criterion = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4))
        .configure_from_args();
    criterion_benches(&mut criterion);
    criterion.final_summary();
    // `cargo test --benches` runs the bench in test mode: one quick pass is enough there.
    let test_mode = std::env::args().any(|a| a == "--test");
    ratios(if test_mode { 1 } else { 31 });
}
