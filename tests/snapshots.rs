//! Exact snapshots: taken at a seeded random step of a run, restored into a fresh
//! simulation (built by the same code, or from the snapshot alone, in this process or
//! through bytes), every later step is the same to the bit as the uninterrupted run:
//! every body's pose and velocity after every step, and every sensor record.

use ars::sensors::CsvColumns;
use ars::{Program, Simulation, Snapshot};
use ars_programs::ConicalPendulum;

/// Every body's position, quaternion, rotation matrix and velocities, as bits.
fn states(sim: &Simulation) -> Vec<u64> {
    sim.bodies()
        .flat_map(|(_, h)| {
            let b = sim.world().body(h).unwrap();
            let (p, q, r, v, w) =
                (b.position(), b.quaternion(), b.rotation(), b.linear_velocity(), b.angular_velocity());
            [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z]
                .into_iter()
                .chain(r.matrix().iter().copied())
                .map(f64::to_bits)
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Every sensor's records taken after step `after`: its name, then each record's time,
/// step and cells, as bits.
fn records_after(sim: &Simulation, after: u64) -> Vec<(String, Vec<Vec<u64>>)> {
    sim.sensor_tables()
        .into_iter()
        .map(|(name, table): (String, &dyn CsvColumns)| {
            let rows = (0..table.len())
                .filter(|&i| table.stamp(i).1 > after)
                .map(|i| {
                    let (t, step) = table.stamp(i);
                    let cells = table.cells(i).into_iter().map(|c| c.map_or(u64::MAX, f64::to_bits));
                    [t.to_bits(), step].into_iter().chain(cells).collect()
                })
                .collect();
            (name, rows)
        })
        .collect()
}

/// A small seeded generator for the steps at which snapshots are taken.
fn seeded_steps(seed: u64, count: usize, below: u64) -> Vec<u64> {
    let mut rng = ars::random::SplitMix64::new(seed);
    let mut steps: Vec<u64> = (0..count).map(|_| 1 + rng.next_u64() % below).collect();
    steps.sort_unstable();
    steps
}

/// Runs `build()`'s simulation, takes snapshots at `at` (step counts), and for each
/// restores it into a fresh `build()` (directly and through bytes), steps both `run`
/// steps and compares states after every step and the records at the end.
fn resumes_exactly(name: &str, build: impl Fn() -> Simulation, at: &[u64], run: u64) {
    for &k in at {
        let mut original = build();
        original.step_n(k).unwrap();
        let snapshot = original.snapshot().unwrap();
        let bytes = snapshot.to_bytes();
        let mut reference = build();
        reference.restore(&snapshot).unwrap();
        let mut through_bytes = build();
        through_bytes.restore(&Snapshot::from_bytes(&bytes).unwrap()).unwrap();
        assert_eq!(states(&reference), states(&original), "{name}: restored at step {k}");
        let mut ahead = build();
        ahead.restore(&snapshot).unwrap();
        for step in 1..=run {
            ahead.step().unwrap();
            reference.step().unwrap();
            through_bytes.step().unwrap();
            let expected = states(&ahead);
            assert_eq!(states(&reference), expected, "{name}: {step} steps after step {k}");
            assert_eq!(states(&through_bytes), expected, "{name}: through bytes, {step} steps after step {k}");
        }
        // `ahead` is the uninterrupted run from the snapshot on: the original too.
        original.step_n(run).unwrap();
        assert_eq!(states(&original), states(&reference), "{name}: the uninterrupted run, {run} steps after {k}");
        let expected = records_after(&original, k);
        assert_eq!(records_after(&reference, k), expected, "{name}: records after step {k}");
        assert_eq!(records_after(&through_bytes, k), expected, "{name}: records through bytes after step {k}");
    }
}

/// The thesis' conical pendulum with its program's hooks (the waist torque).
fn conical_pendulum() -> Simulation {
    let mut sim = ConicalPendulum::default().create_simulation().unwrap();
    let mut driver = ConicalPendulum::default();
    (driver.waist, driver.shoulder) = (Some(sim.joint("r1").unwrap().id()), Some(sim.joint("r2").unwrap().id()));
    sim.add_hooks(driver).unwrap();
    sim
}

#[test]
fn the_conical_pendulum_resumes_to_the_bit_from_any_step() {
    // 2 s of the pendulum's 0.25 ms steps after each snapshot.
    resumes_exactly("conical pendulum", conical_pendulum, &seeded_steps(1, 3, 20_000), 8000);
}
