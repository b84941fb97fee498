//! The original's vehicle demos, driven by a key script instead of a keyboard:
//! `vehicle1`, `vehicle2`, `vehicle_with_arm` (default) or `vehicle_with_controlled_arm`
//! (`--program NAME`), with `--keys FILE` (lines `TIME down|up KEY`; the default drives
//! forward, turns left, then backs up). Prints where the chassis went every second;
//! `--csv` writes `t,x,y,z` of the chassis every frame, `--plot` its path seen from above.
//!
//! `cargo run --release --example vehicles -- --program vehicle2`

#[path = "common/mod.rs"]
mod common;

use ars::sensors::Gps;
use ars::{KeyScript, ObjectId, Program, ProgramRunner};
use ars_programs::{Vehicle1, Vehicle2, VehicleWithArm, VehicleWithControlledArm};
use common::plot::{Series, line_chart};

const DEFAULT_KEYS: &str = "\
0.0 down up
2.0 up up
2.0 down left
3.0 up left
3.0 down down
4.5 up down
";

/// The chassis position after every frame.
type Path = ars::SensorLog<ars::sensors::Position>;

fn drive<P: Program>(
    mut program: P,
    chassis: fn(&P) -> ObjectId,
    script: &KeyScript,
    args: &common::args::Args,
) -> Result<Path, Box<dyn std::error::Error>> {
    if args.live() {
        // Live: the program's keys drive it.
        common::args::run(&mut program, args)?;
        return Ok(Path::default());
    }
    let duration = args.duration;
    let mut capture = common::args::Capture::new(args, program.window_settings())?;
    let mut runner = ProgramRunner::new(&mut program)?;
    let body = chassis(runner.program());
    let sim = runner.simulation_mut();
    let frame = sim.scene().time_step() * f64::from(sim.scene().steps_per_frame());
    let gps = sim.add_sensor_every(Gps::new(body), frame)?;
    capture.record_ros(sim)?;
    let frames = sim.scene().steps_in(duration)? / u64::from(sim.scene().steps_per_frame());
    for _ in 0..frames {
        capture.frame(runner.simulation())?;
        runner.run_script_frame(script)?;
    }
    capture.finish(runner.simulation())?;
    Ok(runner.simulation_mut().remove_sensor(gps)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let argv: Vec<String> = std::env::args().collect();
    let value = |flag: &str| argv.iter().position(|a| a == flag).and_then(|i| argv.get(i + 1)).cloned();
    let (name, keys) = (value("--program").unwrap_or_else(|| "vehicle_with_arm".into()), value("--keys"));
    let mut skip = vec!["--program", name.as_str()];
    if let Some(k) = &keys {
        skip.extend(["--keys", k.as_str()]);
    }
    let args = common::args::parse_except(6.0, &skip);
    let script = KeyScript::parse(&match &keys {
        Some(path) => std::fs::read_to_string(path)?,
        None => DEFAULT_KEYS.to_string(),
    })?;
    let path = match name.as_str() {
        "vehicle1" => drive(Vehicle1::default(), |p| p.chassis.expect("built"), &script, &args)?,
        "vehicle2" => drive(Vehicle2::default(), |p| p.vehicle.expect("built").chassis, &script, &args)?,
        "vehicle_with_arm" => drive(VehicleWithArm::default(), |p| p.vehicle.expect("built").chassis, &script, &args)?,
        "vehicle_with_controlled_arm" => {
            drive(VehicleWithControlledArm::default(), |p| p.vehicle.expect("built").chassis, &script, &args)?
        }
        other => {
            return Err(format!(
                "unknown program {other:?}: vehicle1, vehicle2, vehicle_with_arm, vehicle_with_controlled_arm"
            )
            .into());
        }
    };
    if args.live() {
        return Ok(());
    }
    for (t, p) in path.iter().map(|s| (s.time, s.record.position)) {
        if !((t.fract() < 1e-6 || t.fract() > 1.0 - 1e-6) && t > 0.5) {
            continue;
        }
        println!("{name} at {t:.1} s: chassis at ({:.3}, {:.3}, {:.3}) m", p.x, p.y, p.z);
    }
    if let Some(file) = &args.csv {
        common::args::export_csv(file, &path, args.every)?;
    }
    if let Some(dir) = &args.plot {
        let xz = path.iter().map(|s| (s.record.position.x, s.record.position.z)).collect();
        line_chart(
            dir,
            &format!("{name}_path.png"),
            &format!("{name}: path seen from above"),
            "x [m]",
            "z [m]",
            &[Series::new("chassis", xz)],
        )?;
    }
    Ok(())
}
