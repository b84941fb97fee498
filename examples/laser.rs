//! The thesis' laser example (thesis §3.2, fig. 3.3): two balls fall past a laser beam
//! pointing +X. Prints the first hit and the resting distance; `--csv` writes one row
//! per step with every sensor's columns (the laser's empty when the beam hits nothing),
//! `--plot` the system's energies and the laser distance.
//!
//! `cargo run --release --example laser -- --csv laser.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars_programs::TwoBallLaser;
use common::args::export_csv_table;
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(2.0);
    let mut program = TwoBallLaser::default();
    let sim = common::args::run(&mut program, &args)?;
    let (g1, g2) = program.gps.unwrap();
    let (v1, v2) = program.velometers.unwrap();
    let (g1, g2) = (sim.records(g1)?, sim.records(g2)?);
    let (v1, v2) = (sim.records(v1)?, sim.records(v2)?);
    let laser_log = sim.records(program.laser.unwrap())?;
    let energy_log = sim.records(program.energy.unwrap())?;
    let (laser, energy) = (laser_log.samples(), energy_log.samples());

    match laser.iter().find(|s| s.record.distance.is_some()) {
        Some(s) => println!(
            "first hit in the step ending at {:.4} s, at {:.4} m (thesis: 0.32 s, 3.5 m)",
            s.time,
            s.record.distance.unwrap()
        ),
        None => println!("the laser hit nothing"),
    }
    let last = laser.last().unwrap();
    let distance = last.record.distance.map_or("none".into(), |d| d.to_string());
    println!("distance at {:.2} s: {distance} m (thesis: rests at 0.63397 m)", last.time);

    if let Some(path) = &args.csv {
        let table: [(&str, &dyn ars::sensors::CsvColumns); 6] = [
            ("ball 1", g1),
            ("ball 1", v1),
            ("ball 2", g2),
            ("ball 2", v2),
            ("laser", laser_log),
            ("energy", energy_log),
        ];
        export_csv_table(path, &table, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let energies = [
            Series::new("kinetic", over_time(energy, |e| e.kinetic)),
            Series::new("potential", over_time(energy, |e| e.potential)),
            Series::new("total", over_time(energy, |e| e.total())),
        ];
        line_chart(
            dir,
            "fig3_3a_two_ball_energies.png",
            "Two balls: system energies (fig. 3.3a)",
            "time [s]",
            "energy [J]",
            &energies,
        )?;
        let distance: Vec<_> = laser.iter().filter_map(|s| s.record.distance.map(|d| (s.time, d))).collect();
        line_chart(
            dir,
            "fig3_3b_laser_distance.png",
            "Laser distance (fig. 3.3b)",
            "time [s]",
            "distance to the closest hit [m]",
            &[Series::new("laser", distance)],
        )?;
    }
    Ok(())
}
