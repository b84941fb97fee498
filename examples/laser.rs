//! The thesis' laser example (thesis §3.2, fig. 3.3): two balls fall past a laser beam
//! pointing +X. Prints the first hit and the resting distance; `--csv` writes one row
//! per step (`step,t,x1,y1,vy1,x2,y2,vy2,distance,ke,pe,e_total`, `distance` empty when
//! the beam hits nothing), `--plot` the system's energies and the laser distance.
//!
//! `cargo run --release --example laser -- --csv laser.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars::programs::TwoBallLaser;
use common::args::{cell, write_csv};
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(2.0);
    let mut program = TwoBallLaser::default();
    let sim = common::args::run(&mut program, &args)?;
    let (g1, g2) = program.gps.unwrap();
    let (v1, v2) = program.velometers.unwrap();
    let (g1, g2) = (sim.records(g1)?.samples(), sim.records(g2)?.samples());
    let (v1, v2) = (sim.records(v1)?.samples(), sim.records(v2)?.samples());
    let laser = sim.records(program.laser.unwrap())?.samples();
    let energy = sim.records(program.energy.unwrap())?.samples();

    match laser.iter().find(|s| s.record.distance.is_some()) {
        Some(s) => println!(
            "first hit in the step ending at {:.4} s, at {:.4} m (thesis: 0.32 s, 3.5 m)",
            s.time,
            s.record.distance.unwrap()
        ),
        None => println!("the laser hit nothing"),
    }
    let last = laser.last().unwrap();
    println!("distance at {:.2} s: {} m (thesis: rests at 0.63397 m)", last.time, cell(last.record.distance));

    if let Some(path) = &args.csv {
        let rows = (0..laser.len()).step_by(args.every).map(|k| {
            let (p1, p2) = (g1[k].record.position, g2[k].record.position);
            let e = energy[k].record;
            format!(
                "{},{},{},{},{},{},{},{},{},{},{},{}",
                laser[k].step,
                laser[k].time,
                p1.x,
                p1.y,
                v1[k].record.linear.y,
                p2.x,
                p2.y,
                v2[k].record.linear.y,
                cell(laser[k].record.distance),
                e.kinetic,
                e.potential,
                e.total()
            )
        });
        write_csv(path, "step,t,x1,y1,vy1,x2,y2,vy2,distance,ke,pe,e_total", rows)?;
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
