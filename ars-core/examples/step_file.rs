//! Opens a model file as `ars view` does and steps it, for profiling one file's step:
//! `step_file FILE STEPS [WARMUP [quick]]` (`quick`: `dWorldQuickStep`, 20 iterations) prints the wall time per step, the contact count
//! and a hash of every body's position and velocity (for checking that a change
//! leaves a file's motion bit for bit the same).
//!
//! With `STEP_FILE_CONTACTS` set in the environment it also lists the last step's
//! contact points by the objects (or geoms) they join.
//!
//! Instructions per step with callgrind (stable on a loaded machine): run it with
//! `STEPS` 0 and N under `valgrind --tool=callgrind` and divide the difference by N.
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).ok_or("usage: step_file FILE STEPS [WARMUP [quick]]")?;
    let steps: usize = args.get(2).map_or(Ok(100), |s| s.parse())?;
    let warmup: usize = args.get(3).map_or(Ok(0), |s| s.parse())?;
    let mut sim = ars_core::Simulation::open(path)?.simulation;
    if args.get(4).is_some_and(|s| s == "quick") {
        sim.scene_mut().world_mut().set_stepper(ars_core::Stepper::Quick { iterations: 20 })?;
    }
    for _ in 0..warmup {
        sim.step()?;
    }
    let start = std::time::Instant::now();
    for _ in 0..steps {
        sim.step()?;
    }
    let wall = start.elapsed().as_secs_f64();
    let world = sim.scene().world();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |x: f64| {
        hash ^= x.to_bits();
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    };
    for b in world.bodies() {
        let body = world.body(b)?;
        let (p, v) = (body.position(), body.linear_velocity());
        [p.x, p.y, p.z, v.x, v.y, v.z].into_iter().for_each(&mut mix);
    }
    let contacts = world.contacts().len();
    if std::env::var_os("STEP_FILE_CONTACTS").is_some() {
        print_contacts(&sim);
    }
    eprintln!("{steps} steps, {:.1} us/step, {contacts} contacts, state {hash:016x}", wall / steps as f64 * 1e6);
    Ok(())
}

/// The last step's contact points, one line per pair of geoms: their objects (by
/// geom; `static` when the geom belongs to none), how many points and the deepest.
fn print_contacts(sim: &ars_core::Simulation) {
    let scene = sim.scene();
    let mut owner = std::collections::HashMap::new();
    for (name, id) in scene.objects() {
        if let Ok(object) = scene.object(id) {
            for g in object.geoms() {
                owner.insert(g, name.to_string());
            }
        }
    }
    let name = |g| owner.get(&g).cloned().unwrap_or_else(|| format!("static {g}"));
    let mut pairs: std::collections::BTreeMap<(String, String), (usize, f64)> = Default::default();
    for c in scene.world().contacts() {
        let entry = pairs.entry((name(c.pair.geom1), name(c.pair.geom2))).or_insert((0, 0.0));
        entry.0 += 1;
        entry.1 = entry.1.max(c.depth);
    }
    for ((a, b), (n, depth)) in pairs {
        eprintln!("  {a} -- {b}: {n} points, deepest {depth:.2e} m");
    }
}
