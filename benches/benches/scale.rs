//! How the cost of a step grows with the scene, for each broad-phase space.
//!
//! `cargo bench -p ars-benches --no-default-features --bench scale` prints the
//! milliseconds per `Simulation::step` (the median of a few steps after two warm-up
//! steps) of:
//!
//! - 1,000, 10,000 and 100,000 spheres (radius 0.1 m, 1 kg) on a square grid 0.5 m
//!   apart, 2 m above the floor plane y = 0: nothing touches while they are measured
//!   (they would reach the floor after 0.6 s), so the cost is the broad phase, the
//!   near callback's rejections, the step and the state checks; `dWorldStep`;
//! - a pile of 1,015 spheres (radius 0.1 m) on the floor, a square pyramid of 14
//!   layers, each sphere resting in the hollow of four below, its bottom layer walled
//!   in by four static boxes, settled for 250 steps (0.1 s) before it is measured:
//!   about 3,500 contact points a step. QuickStep (20 iterations): the exact stepper
//!   refuses an island of more than 400 contacts;
//!
//! in a simple space (every pair; not at 100,000 spheres, where one step would take
//! minutes), a hash space (ODE's default levels; not at 100,000 spheres and a floor,
//! beyond `limits::MAX_HASH_SPACE_GEOMS`) a sweep-and-prune space (X, Z, Y) and the grid, with the ratios 10k/1k and 100k/10k (10 is linear). `--test` (what
//! `cargo test --benches` passes) runs 100 spheres and a 3-layer pile once;
//! `--run SPACE N STEPS` (SPACE `simple`, `hash`, `sap` or `grid`) steps N spaced spheres
//! (N = 0: the pile), for a profiler.

use std::hint::black_box;
use std::time::Instant;

use ars_core::nalgebra::Isometry3;
use ars_core::{Mass, Shape, Simulation, SpaceKind, Stepper, limits};

/// The spaces measured, with their names in the table.
const SPACES: [(&str, SpaceKind); 4] = [
    ("simple", SpaceKind::Simple),
    ("hash", SpaceKind::HASH),
    ("sweep and prune", SpaceKind::SWEEP_AND_PRUNE),
    ("grid", SpaceKind::Grid),
];

/// Sphere radius, m.
const RADIUS: f64 = 0.1;

/// `n` spheres on a square grid 0.5 m apart, 2 m above the floor.
fn spaced_spheres(space: SpaceKind, n: usize) -> Simulation {
    let mut sim = Simulation::builder().space(space).floor_plane([0.0, 1.0, 0.0].into(), 0.0).build().unwrap();
    let side = (n as f64).sqrt().ceil() as usize;
    for k in 0..n {
        let (i, j) = (k % side, k / side);
        let p = [0.5 * i as f64, 2.0, 0.5 * j as f64];
        sim.scene_mut().add_sphere(RADIUS, p, Mass::Total(1.0)).unwrap();
    }
    sim
}

/// A square pyramid of `layers` layers of touching spheres on the floor (14 layers:
/// 1,015 spheres), walled in at the bottom, settled for `settle` steps.
fn pile(space: SpaceKind, layers: usize, settle: usize) -> Simulation {
    let mut sim = Simulation::builder()
        .space(space)
        .stepper(Stepper::Quick { iterations: 20 })
        .floor_plane([0.0, 1.0, 0.0].into(), 0.0)
        .build()
        .unwrap();
    // Four walls around the bottom layer keep it from rolling apart.
    let half = layers as f64 * RADIUS;
    for (x, z, edges) in [
        (half + 0.05, 0.0, [0.1, 4.0 * RADIUS, 2.0 * half + 0.2]),
        (-half - 0.05, 0.0, [0.1, 4.0 * RADIUS, 2.0 * half + 0.2]),
        (0.0, half + 0.05, [2.0 * half + 0.2, 4.0 * RADIUS, 0.1]),
        (0.0, -half - 0.05, [2.0 * half + 0.2, 4.0 * RADIUS, 0.1]),
    ] {
        let pose = Isometry3::translation(x, 2.0 * RADIUS, z);
        sim.scene_mut().add_static(Shape::Box { edges: edges.into() }, pose).unwrap();
    }
    for layer in 0..layers {
        let n = layers - layer;
        let y = RADIUS + layer as f64 * RADIUS * std::f64::consts::SQRT_2;
        for i in 0..n {
            for j in 0..n {
                let centre = |k: usize| 2.0 * RADIUS * (k as f64 - (n as f64 - 1.0) / 2.0);
                sim.scene_mut().add_sphere(RADIUS, [centre(i), y, centre(j)], Mass::Total(1.0)).unwrap();
            }
        }
    }
    for _ in 0..settle {
        sim.step().unwrap();
    }
    sim
}

/// Median milliseconds of one step, over `steps` steps after two warm-up steps.
fn ms_per_step(sim: &mut Simulation, steps: usize) -> f64 {
    for _ in 0..2 {
        sim.step().unwrap();
    }
    let mut t: Vec<f64> = (0..steps)
        .map(|_| {
            let start = Instant::now();
            sim.step().unwrap();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    black_box(&sim);
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// One row of the table: ms per step at each size (`None`: not measured), the pile.
struct Row {
    name: &'static str,
    sizes: Vec<Option<f64>>,
    pile: f64,
}

fn cell(v: Option<f64>) -> String {
    match v {
        Some(ms) if ms >= 100.0 => format!("{ms:.0}"),
        Some(ms) if ms >= 10.0 => format!("{ms:.1}"),
        Some(ms) => format!("{ms:.2}"),
        None => "–".into(),
    }
}

fn main() {
    if std::env::args().any(|a| a == "--test") {
        for (_, space) in SPACES {
            let mut sim = spaced_spheres(space, 100);
            ms_per_step(&mut sim, 1);
            let mut sim = pile(space, 3, 2);
            ms_per_step(&mut sim, 1);
            assert!(sim.scene().world().contacts().len() >= 14, "the pile rests on its contacts");
        }
        return;
    }
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--run") {
        // `--run SPACE N STEPS`: one case, for a profiler (SPACE: simple, hash, sap, grid;
        // N = 0: the pile).
        let space = match args[i + 1].as_str() {
            "simple" => SpaceKind::Simple,
            "hash" => SpaceKind::HASH,
            "grid" => SpaceKind::Grid,
            _ => SpaceKind::SWEEP_AND_PRUNE,
        };
        let (n, steps) = (args[i + 2].parse().expect("a sphere count"), args[i + 3].parse().expect("a step count"));
        let mut sim = if n == 0 { pile(space, 14, 1000) } else { spaced_spheres(space, n) };
        println!("{:.2} ms/step", ms_per_step(&mut sim, steps));
        return;
    }
    let sizes = [1_000usize, 10_000, 100_000];
    println!("ms per step (median), {} cores; spaced spheres with dWorldStep, the pile with QuickStep", cores());
    let mut rows = Vec::new();
    for (name, space) in SPACES {
        let mut row = Row { name, sizes: Vec::new(), pile: 0.0 };
        for &n in &sizes {
            if space == SpaceKind::Simple && n > 10_000 || space == SpaceKind::HASH && n >= limits::MAX_HASH_SPACE_GEOMS
            {
                row.sizes.push(None);
                continue;
            }
            let start = Instant::now();
            let mut sim = spaced_spheres(space, n);
            let built = start.elapsed().as_secs_f64();
            let steps = if n >= 100_000 || space == SpaceKind::Simple && n >= 10_000 { 5 } else { 15 };
            let ms = ms_per_step(&mut sim, steps);
            eprintln!("{name}: {n} spheres: {ms:.2} ms/step (median of {steps}; built in {built:.2} s)");
            row.sizes.push(Some(ms));
        }
        let mut sim = pile(space, 14, 250);
        assert_eq!(sim.scene().world().body_count(), 1015);
        row.pile = ms_per_step(&mut sim, 15);
        let contacts = sim.scene().world().contacts().len();
        eprintln!("{name}: pile of 1,015 spheres: {:.2} ms/step, {contacts} contacts", row.pile);
        rows.push(row);
    }
    println!();
    println!("| space | 1k | 10k | 100k | pile 1k | 10k / 1k | 100k / 10k |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for r in &rows {
        let ratio = |a: Option<f64>, b: Option<f64>| cell(a.zip(b).map(|(a, b)| b / a));
        println!(
            "| {} | {} | {} | {} | {} | {} | {} |",
            r.name,
            cell(r.sizes[0]),
            cell(r.sizes[1]),
            cell(r.sizes[2]),
            cell(Some(r.pile)),
            ratio(r.sizes[0], r.sizes[1]),
            ratio(r.sizes[1], r.sizes[2]),
        );
    }
    println!("(– simple at 100k: every pair, 5·10⁹ tests a step, not run; hash at 100k: beyond its geom limit)");
}

/// Cores available to this process.
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}
