//! A two-link arm whose shoulder and elbow are driven by DC motors under voltage
//! profiles (the thesis' future work: motors instead of torques). Prints, every 0.5 s,
//! each joint's angle, rate and winding current; `--csv` writes the joints' sensors
//! (angle and rate, torque) every `--every` steps.
//!
//! `cargo run --release --example dc_motor_arm -- --duration 4 --csv dc_motor_arm.csv`

#[path = "common/mod.rs"]
mod common;

use ars::nalgebra::{Point3, Vector3};
use ars::{DcMotor, JointEnd, Mass, Profile, SensorKind, Simulation};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = common::args::parse(4.0);
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build()?;
    let upper = sim.scene_mut().add_box([0.05, 0.4, 0.05], [0.0, 1.0, 0.0], Mass::Total(1.0))?;
    let lower = sim.scene_mut().add_box([0.04, 0.4, 0.04], [0.0, 0.6, 0.0], Mass::Total(0.6))?;
    let shoulder = sim.scene_mut().add_hinge_joint(
        "shoulder",
        upper,
        JointEnd::World,
        Some(Point3::new(0.0, 1.2, 0.0)),
        Vector3::z(),
    )?;
    let elbow =
        sim.scene_mut().add_hinge_joint("elbow", lower, upper, Some(Point3::new(0.0, 0.8, 0.0)), Vector3::z())?;
    // A small gearmotor: 0.03 N·m/A, 1.5 Ω, 2 mH, gear 50:1, rotor 5e-7 kg·m².
    let motor = |volts: Vec<(f64, f64)>| -> ars::Result<DcMotor> {
        DcMotor::new(Profile::new(volts)?, 0.03, 0.03, 1.5, 50.0, 5e-7)?.with_inductance(0.002)?.with_friction(2e-6)
    };
    let shoulder_volts = vec![(0.0, 0.0), (0.5, 0.0), (0.6, 6.0), (2.0, 6.0), (2.1, -4.0), (3.5, -4.0), (3.6, 0.0)];
    let elbow_volts = vec![(0.0, 0.0), (1.0, 0.0), (1.1, 4.0), (3.0, 4.0), (3.1, 0.0)];
    sim.scene_mut().joint_mut(shoulder)?.set_controller(motor(shoulder_volts)?)?;
    sim.scene_mut().joint_mut(elbow)?.set_controller(motor(elbow_volts)?)?;
    for joint in [shoulder, elbow] {
        sim.add_sensor_of_kind(SensorKind::HingeSensor, &[], &[joint], None)?;
        sim.add_sensor_of_kind(SensorKind::JointTorque, &[], &[joint], None)?;
    }
    let steps = sim.scene().steps_in(args.duration)?;
    let every = (0.5 / sim.scene().time_step()).round() as u64;
    let view = ars::WindowSettings {
        camera_position: Point3::new(0.0, 1.0, 3.0),
        camera_target: Point3::new(0.0, 0.8, 0.0),
        ..Default::default()
    };
    let mut capture = common::args::Capture::new(&args, view)?;
    capture.record_ros(&mut sim)?;
    let spf = u64::from(sim.scene().steps_per_frame());
    for step in 1..=steps {
        if (step - 1) % spf == 0 {
            capture.frame(&sim)?;
        }
        sim.step()?;
        if step % every == 0 {
            let mut line = format!("t = {:.2} s", sim.scene().time());
            for (name, joint) in [("shoulder", shoulder), ("elbow", elbow)] {
                let state = sim.scene().joint_state(joint)?;
                let current = sim.scene().joint_controller::<DcMotor>(joint)?.map_or(0.0, DcMotor::winding_current);
                line += &format!(", {name}: {:+.3} rad, {:+.3} rad/s, {:+.3} A", state.position, state.rate, current);
            }
            println!("{line}");
        }
    }
    capture.finish(&sim)?;
    if let Some(path) = &args.csv {
        let tables = sim.sensor_tables();
        let names = ["shoulder", "shoulder torque", "elbow", "elbow torque"];
        let logs: Vec<(&str, &dyn ars::sensors::CsvColumns)> =
            names.iter().zip(&tables).map(|(name, (_, table))| (*name, *table)).collect();
        common::args::export_csv_table(path, &logs, args.every)?;
    }
    Ok(())
}
