//! Checks that this installation computes the same bits as ours: runs the golden
//! programs (`ars_programs::golden`) and compares each output with the committed
//! sha256 table, printing "identical" or where it first differs, and the platform it
//! ran on. Exits with status 1 if any output differs.
//!
//! `cargo run --release --example verify` (about 10 s); `-- --write` rewrites the
//! table from this machine's outputs (a deliberate act: say in the CHANGELOG which
//! results changed and why).

use std::time::Instant;

use ars_programs::golden::{GoldenEntry, GoldenTable, Verdict, runs};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let write = std::env::args().any(|a| a == "--write");
    let platform = ars::platform::Platform::current();
    println!("ARS {} on {platform}", env!("CARGO_PKG_VERSION"));
    let mut table = GoldenTable::committed();
    let mut different = 0;
    for run in runs() {
        let start = Instant::now();
        let output = run.output()?;
        let verdict = table.compare(run.name, &output);
        println!(
            "  {:<22} {:>5} s simulated, {:>5.1} s: {verdict}",
            run.name,
            run.duration,
            start.elapsed().as_secs_f64()
        );
        if verdict != Verdict::Identical {
            different += 1;
        }
        if write {
            table.set(GoldenEntry::of(run.name, run.duration, &output));
        }
    }
    if write {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("ars-programs/golden.json");
        std::fs::write(&path, table.to_json())?;
        println!("wrote {}", path.display());
    } else if different > 0 {
        println!("{different} of the golden runs differ from the table: see the README's \"The same bits everywhere\"");
        std::process::exit(1);
    } else {
        println!("every golden run is identical to the table");
    }
    Ok(())
}
