//! The thesis' numbers next to the ones this project computes, as a Markdown table
//! (the README's table is this function's output).

use std::fmt::Write;

use ars_core::{Program, Result};

use crate::{ConicalPendulum, FallingBallSensors, TwoBallLaser};

/// Runs the falling ball (1 s), the two-ball laser (2 s) and the conical pendulum
/// (20 s) and returns the table `| quantity | thesis | ARS in Rust |`.
pub fn thesis_table() -> Result<String> {
    let mut rows: Vec<(String, String, String)> = Vec::new();

    let mut ball = FallingBallSensors::default();
    let sim = ball.run_headless(1.0)?;
    let vel = sim.records(ball.velometer.expect("created"))?.samples();
    let acc = sim.records(ball.accelerometer.expect("created"))?.samples();
    let bounces: Vec<_> =
        (1..vel.len()).filter(|&k| vel[k - 1].record.linear.y < 0.0 && vel[k].record.linear.y > 0.0).take(3).collect();
    let thesis_speeds = ["3.13135", "0.62156", "0.11898"];
    let thesis_times = ["0.3194", "0.4470", "0.4722"];
    let thesis_acc = ["9394", "1865", "357"];
    for (i, &k) in bounces.iter().enumerate() {
        let (before, after) = (vel[k - 1].record.linear.y, vel[k].record.linear.y);
        let n = i + 1;
        rows.push((
            format!("falling ball: impact {n} speed [m/s]"),
            thesis_speeds[i].into(),
            format!("{:.6}", -before),
        ));
        rows.push((
            format!("falling ball: impact {n} time [s] (end of the bounce step)"),
            thesis_times[i].into(),
            format!("{:.4}", vel[k].time),
        ));
        rows.push((format!("falling ball: restitution {n}"), "0.200000".into(), format!("{:.6}", after / -before)));
        rows.push((
            format!("falling ball: acceleration peak {n} [m/s²]"),
            thesis_acc[i].into(),
            format!("{:.2}", acc[k].record.linear.y),
        ));
    }
    let rest = sim.records(ball.gps.expect("created"))?.last().expect("sampled").record.position.y;
    rows.push(("falling ball: rest height [m]".into(), "0.5".into(), format!("{rest:.6}")));

    let mut laser = TwoBallLaser::default();
    let sim = laser.run_headless(2.0)?;
    let log = sim.records(laser.laser.expect("created"))?;
    if let Some(first) = log.iter().find(|s| s.record.distance.is_some()) {
        rows.push(("laser: first detection time [s]".into(), "0.32".into(), format!("{:.4}", first.time)));
        rows.push((
            "laser: first detection distance [m]".into(),
            "3.5".into(),
            format!("{:.4}", first.record.distance.unwrap_or(f64::NAN)),
        ));
    }
    let resting = log.last().and_then(|s| s.record.distance).unwrap_or(f64::NAN);
    rows.push(("laser: resting distance at 2 s [m]".into(), "0.63397".into(), format!("{resting:.5}")));

    let mut pendulum = ConicalPendulum::default();
    let sim = pendulum.run_headless(20.0)?;
    let last = sim.records(pendulum.record.expect("created"))?.last().expect("stepped").record;
    rows.push((
        "conical pendulum: waist rate at 20 s [rad/s]".into(),
        "almost 4".into(),
        format!("{:.4}", last.q1_rate),
    ));
    rows.push((
        "conical pendulum: shoulder, DH angle π/2 − q2 at 20 s [rad]".into(),
        "about 0.87".into(),
        format!("{:.3}", std::f64::consts::FRAC_PI_2 - last.q2),
    ));
    rows.push(("conical pendulum: shoulder angle q2 from hanging [rad]".into(), "—".into(), format!("{:.4}", last.q2)));

    let mut out = String::from("| quantity | thesis | ARS in Rust |\n| --- | --- | --- |\n");
    for (q, t, o) in rows {
        writeln!(out, "| {q} | {t} | {o} |").expect("writing to a String");
    }
    Ok(out)
}
