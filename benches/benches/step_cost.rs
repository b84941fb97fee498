//! Instructions per step of the reference scenes, in plain C against native ODE,
//! through `ars-core`'s `World` and through its `Simulation`, counted by valgrind's
//! callgrind (instruction counts are repeatable on a noisy machine, unlike times).
//!
//! `cargo bench -p ars-benches --bench step_cost` prints, for each scene, the instructions per step of
//! each layer and their ratios to C (it needs `valgrind`). Only the stepping is
//! counted (`--toggle-collect` on `measured_steps`), not building the scene.
//! `step_cost --run SCENE LAYER STEPS` runs one case (what callgrind is given). It
//! also times creating 10,000 named spheres through the `Simulation` and through the
//! `World` (median of 5).

use std::hint::black_box;
use std::path::Path;
use std::process::Command;

use ars_reference_scenes::{CScene, RustScene, SimScene};

/// A scene, its step count, and which layers have it.
struct Case {
    scene: &'static str,
    steps: usize,
    has_world: bool,
}

const CASES: [Case; 4] = [
    Case { scene: "falling_sphere", steps: 2500, has_world: true },
    Case { scene: "drop_pile", steps: 500, has_world: true },
    Case { scene: "conical_pendulum", steps: 2500, has_world: false },
    Case { scene: "mobile_manipulator", steps: 2500, has_world: false },
];

const LAYERS: [&str; 3] = ["c", "world", "simulation"];

enum Scene {
    C(CScene),
    World(Box<RustScene>),
    Sim(Box<SimScene>),
}

fn build(scene: &str, layer: &str) -> Scene {
    match (scene, layer) {
        ("falling_sphere", "c") => Scene::C(CScene::falling_sphere()),
        ("falling_sphere", "world") => Scene::World(Box::new(RustScene::falling_sphere())),
        ("falling_sphere", "simulation") => Scene::Sim(Box::new(SimScene::falling_sphere())),
        ("drop_pile", "c") => Scene::C(CScene::drop_pile(100)),
        ("drop_pile", "world") => Scene::World(Box::new(RustScene::drop_pile(100))),
        ("drop_pile", "simulation") => Scene::Sim(Box::new(SimScene::drop_pile(100))),
        ("conical_pendulum", "c") => Scene::C(CScene::conical_pendulum()),
        ("conical_pendulum", "simulation") => Scene::Sim(Box::new(SimScene::conical_pendulum())),
        ("mobile_manipulator", "c") => Scene::C(CScene::speed_profile()),
        ("mobile_manipulator", "simulation") => Scene::Sim(Box::new(SimScene::mobile_manipulator())),
        _ => panic!("no scene {scene:?} in layer {layer:?}"),
    }
}

/// The stepping callgrind counts (by this name).
#[inline(never)]
fn measured_steps(scene: &mut Scene, steps: usize) {
    match scene {
        Scene::C(s) => s.step(black_box(steps)),
        Scene::World(s) => s.step(black_box(steps)),
        Scene::Sim(s) => s.step(black_box(steps)),
    }
}

/// Instructions callgrind counted in `measured_steps` for one case.
fn count(exe: &Path, scene: &str, layer: &str, steps: usize) -> Result<u64, String> {
    let out = std::env::temp_dir().join(format!("ars-step-cost-{}-{scene}-{layer}.out", std::process::id()));
    let status = Command::new("valgrind")
        .args(["--tool=callgrind", "--toggle-collect=*measured_steps*"])
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(exe)
        .args(["--run", scene, layer, &steps.to_string()])
        .output()
        .map_err(|e| format!("valgrind could not start ({e}): install it (apt-get install valgrind)"))?;
    if !status.status.success() {
        return Err(format!("valgrind failed on {scene}/{layer}: {}", String::from_utf8_lossy(&status.stderr)));
    }
    let text = std::fs::read_to_string(&out).map_err(|e| format!("reading {}: {e}", out.display()))?;
    let _ = std::fs::remove_file(&out);
    text.lines()
        .find_map(|l| l.strip_prefix("totals:").or_else(|| l.strip_prefix("summary:")))
        .and_then(|n| n.split_whitespace().next()?.parse().ok())
        .ok_or_else(|| format!("no totals in {}", out.display()))
}

/// Median seconds of one 360-beam lidar scan (full turn, 20 m) in the middle of the
/// 100-body pile (settled for 0.2 s).
fn lidar_scan_seconds(scans: usize) -> f64 {
    use ars_core::nalgebra::Isometry3;
    use ars_core::sensors::{Lidar, Sensor};
    let mut pile = SimScene::drop_pile(100);
    pile.step(500);
    let mut lidar = Lidar::new(360, std::f64::consts::TAU, 20.0).unwrap().at(Isometry3::translation(4.5, 0.3, 4.5));
    let mut t: Vec<f64> = (0..scans)
        .map(|_| {
            let start = std::time::Instant::now();
            black_box(lidar.measure(pile.sim.scene()).unwrap());
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// Median seconds of one 360-beam lidar scan (full turn, 20 m) from inside a closed
/// sphere of 5 m radius made of 20,000 triangles (a scanned room), where every beam
/// hits the mesh.
fn mesh_lidar_scan_seconds(scans: usize) -> f64 {
    use ars_core::nalgebra::Point3;
    use ars_core::sensors::{Lidar, Sensor};
    use ars_core::{Simulation, SpaceKind};
    let (rings, segments) = (100u32, 100u32);
    let mut vertices = Vec::new();
    for i in 0..=rings {
        let polar = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let azimuth = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            vertices.push(Point3::new(
                5.0 * polar.sin() * azimuth.cos(),
                5.0 * polar.cos(),
                5.0 * polar.sin() * azimuth.sin(),
            ));
        }
    }
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let k = |i: u32, j: u32| i * segments + j % segments;
            triangles.push([k(i, j), k(i + 1, j), k(i + 1, j + 1)]);
            triangles.push([k(i, j), k(i + 1, j + 1), k(i, j + 1)]);
        }
    }
    let mut sim = Simulation::builder().space(SpaceKind::HASH).build().unwrap();
    sim.scene_mut().add_trimesh_floor(vertices, triangles, [0.0, 0.0, 0.0]).unwrap();
    let mut lidar = Lidar::new(360, std::f64::consts::TAU, 20.0).unwrap();
    let mut t: Vec<f64> = (0..scans)
        .map(|_| {
            let start = std::time::Instant::now();
            black_box(lidar.measure(sim.scene()).unwrap());
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// Seconds to create `n` spheres: named objects of a `Simulation`, or bodies and geoms
/// of a `World` (median of 5 runs).
fn creation_seconds(n: usize) -> (f64, f64) {
    use ars_core::nalgebra::Point3;
    use ars_core::{BodyBuilder, GeomBuilder, Mass, MassSpec, Simulation, SpaceKind, World};
    let median = |f: &dyn Fn()| {
        let mut t: Vec<f64> = (0..5)
            .map(|_| {
                let start = std::time::Instant::now();
                f();
                start.elapsed().as_secs_f64()
            })
            .collect();
        t.sort_by(f64::total_cmp);
        t[2]
    };
    let sim = median(&|| {
        let mut sim = Simulation::builder().space(SpaceKind::HASH).build().unwrap();
        for i in 0..n {
            sim.scene_mut().add_sphere(0.1, [i as f64, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        }
        black_box(sim);
    });
    let world = median(&|| {
        let mut world = World::new();
        let space = world.create_space(SpaceKind::HASH).unwrap();
        for i in 0..n {
            let b = world
                .insert_body(
                    BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.1)).position(Point3::new(i as f64, 1.0, 0.0)),
                )
                .unwrap();
            world.insert_geom(space, GeomBuilder::sphere(0.1).attached_to(b)).unwrap();
        }
        black_box(world);
    });
    (sim, world)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--run") {
        let (scene, layer) = (&args[i + 1], &args[i + 2]);
        let steps: usize = args[i + 3].parse().expect("a step count");
        let mut s = build(scene, layer);
        measured_steps(&mut s, steps);
        return;
    }
    if args.iter().any(|a| a == "--test") {
        // `cargo test --benches`: every case builds and steps.
        creation_seconds(100);
        lidar_scan_seconds(1);
        mesh_lidar_scan_seconds(1);
        for case in &CASES {
            for layer in LAYERS.into_iter().filter(|l| *l != "world" || case.has_world) {
                measured_steps(&mut build(case.scene, layer), 10);
            }
        }
        return;
    }
    let exe = std::env::current_exe().expect("the bench binary");
    println!("instructions per step (callgrind), and the ratio to native C:");
    println!(
        "{:<20} {:>7} {:>12} {:>12} {:>8} {:>12} {:>8}",
        "scene", "steps", "C", "World", "ratio", "Simulation", "ratio"
    );
    for case in &CASES {
        let per_step = |layer| count(&exe, case.scene, layer, case.steps).map(|n| n as f64 / case.steps as f64);
        let c = per_step("c").unwrap_or_else(|e| panic!("{e}"));
        let world = if case.has_world { Some(per_step("world").unwrap_or_else(|e| panic!("{e}"))) } else { None };
        let sim = per_step("simulation").unwrap_or_else(|e| panic!("{e}"));
        let (w, wr) = match world {
            Some(w) => (format!("{w:.0}"), format!("{:.3}", w / c)),
            None => ("-".into(), "-".into()),
        };
        println!("{:<20} {:>7} {:>12.0} {:>12} {:>8} {:>12.0} {:>8.3}", case.scene, case.steps, c, w, wr, sim, sim / c);
    }
    let (sim, world) = creation_seconds(10_000);
    println!(
        "\n10,000 named spheres: {:.1} ms through the Simulation, {:.1} ms through the World ({:.2}x)",
        sim * 1e3,
        world * 1e3,
        sim / world
    );
    println!("a 360-beam lidar scan in the 100-body pile: {:.0} µs (median of 200)", lidar_scan_seconds(200) * 1e6);
    println!(
        "a 360-beam lidar scan inside a 20,000-triangle mesh: {:.0} µs (median of 200)",
        mesh_lidar_scan_seconds(200) * 1e6
    );
}
