//! The thesis' falling ball with its sensors (thesis §3.1, fig. 3.2): GPS, velometer,
//! accelerometer, potential and kinetic energy, total energy of the system. Prints the
//! impacts; `--csv` writes one row per step with every sensor's columns, `--plot` the
//! four panels of fig. 3.2.
//!
//! `cargo run --release --example falling_ball_sensors -- --csv ball.csv --plot figures`

#[path = "common/mod.rs"]
mod common;

use ars::sensors::{Acceleration, Energy, Kinetic, Position, Potential, Sample, Velocity};
use ars_programs::FallingBallSensors;
use common::args::export_csv_table;
use common::plot::{Series, line_chart, over_time};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(1.0);
    let mut program = FallingBallSensors::default();
    let sim = common::args::run(&mut program, &args)?;
    let logs = (
        sim.records(program.gps.unwrap())?,
        sim.records(program.velometer.unwrap())?,
        sim.records(program.accelerometer.unwrap())?,
        sim.records(program.kinetic.unwrap())?,
        sim.records(program.potential.unwrap())?,
        sim.records(program.total.unwrap())?,
    );
    let (gps, vel, acc, ke, pe, total) =
        (logs.0.samples(), logs.1.samples(), logs.2.samples(), logs.3.samples(), logs.4.samples(), logs.5.samples());

    println!("impacts (last sample before -> first after; thesis: 3.13135, 0.62156, 0.11898 m/s):");
    for (i, w) in vel.windows(2).enumerate().filter(|(_, w)| w[0].record.linear.y < 0.0 && w[1].record.linear.y > 0.0) {
        let (before, after) = (w[0].record.linear.y, w[1].record.linear.y);
        println!(
            "  t = {:.4} s: {:.6} m/s -> {:.6} m/s, restitution {:.6}, acceleration {:.2} m/s^2",
            w[1].time,
            -before,
            after,
            after / -before,
            acc[i + 1].record.linear.y
        );
    }
    println!("final height {:.6} m (thesis: rests at 0.5 m)", gps.last().unwrap().record.position.y);

    if let Some(path) = &args.csv {
        let table: [(&str, &dyn ars::sensors::CsvColumns); 6] = [
            ("gps", logs.0),
            ("velometer", logs.1),
            ("accelerometer", logs.2),
            ("kinetic", logs.3),
            ("potential", logs.4),
            ("total", logs.5),
        ];
        export_csv_table(path, &table, args.every)?;
    }
    if let Some(dir) = &args.plot {
        plot_figures(dir, gps, vel, acc, ke, pe, total)?;
    }
    Ok(())
}

/// The thesis' figure 3.2: height, vertical speed and acceleration, and the energies,
/// as PNG files in `dir`.
fn plot_figures(
    dir: &std::path::Path,
    gps: &[Sample<Position>],
    vel: &[Sample<Velocity>],
    acc: &[Sample<Acceleration>],
    ke: &[Sample<Kinetic>],
    pe: &[Sample<Potential>],
    total: &[Sample<Energy>],
) -> Result<(), Box<dyn std::error::Error>> {
    let height = over_time(gps, |r| r.position.y);
    line_chart(
        dir,
        "fig3_2a_height.png",
        "Falling ball: height (fig. 3.2a)",
        "time [s]",
        "height y [m]",
        &[Series::new("GPS y", height)],
    )?;
    let speed = over_time(vel, |r| r.linear.y);
    line_chart(
        dir,
        "fig3_2b_vertical_speed.png",
        "Falling ball: vertical speed (fig. 3.2b)",
        "time [s]",
        "vertical speed vy [m/s]",
        &[Series::new("velometer vy", speed)],
    )?;
    let accel = over_time(acc, |r| r.linear.y);
    line_chart(
        dir,
        "fig3_2c_vertical_acceleration.png",
        "Falling ball: vertical acceleration (fig. 3.2c)",
        "time [s]",
        "vertical acceleration ay [m/s^2]",
        &[Series::new("accelerometer ay", accel)],
    )?;
    let energies = [
        Series::new("kinetic", over_time(ke, |r| r.total())),
        Series::new("potential", over_time(pe, |r| r.potential)),
        Series::new("total", over_time(total, |r| r.total())),
    ];
    line_chart(dir, "fig3_2d_energies.png", "Falling ball: energies (fig. 3.2d)", "time [s]", "energy [J]", &energies)?;
    Ok(())
}
