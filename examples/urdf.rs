//! Loads any URDF robot and runs it: headless, in a window, or off screen.
//!
//! `cargo run --release --example urdf -- FILE [--fixed-base] [--y-up] [--q0 NAME=VALUE,...]
//!  [--duration S] [--csv OUT] [--every N] [--screenshots DIR] [--window]`
//!
//! The robot stands on the floor plane y = 0 (the URDF's Z up becomes the simulation's
//! Y up; `--y-up` for a file written Y-up), its root at the origin, fixed there with
//! `--fixed-base`. `--q0` sets starting joint positions (rad or m). `--csv` writes the
//! positions of its moving joints, one column per joint in URDF order, one row per step.
//!
//! `cargo run --release --example urdf -- tests/data/ars_test_robot/three_link_arm.urdf --fixed-base --q0 shoulder=0.3 --csv arm.csv`

#[path = "common/mod.rs"]
mod common;

use std::path::PathBuf;

use ars::nalgebra::{Point3, Vector3};
use ars::sensors::JointPositions;
use ars::{
    Hooks, JointType, Program, Result, SensorId, Simulation, SimulationBuilder, SpaceKind, UpAxis, UrdfOptions,
    WindowSettings,
};

/// A URDF robot as a program: the file's robot on the floor, recording its joint positions.
struct UrdfProgram {
    path: PathBuf,
    options: UrdfOptions,
    positions: Option<SensorId<JointPositions>>,
    summary: String,
}

impl Hooks for UrdfProgram {}

impl Program for UrdfProgram {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space, as every example (a robot has few geoms).
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn window_settings(&self) -> WindowSettings {
        WindowSettings {
            title: format!("ARS: {}", self.path.display()),
            camera_position: Point3::new(2.5, 1.8, 2.5),
            camera_target: Point3::new(0.0, 0.5, 0.0),
            ..Default::default()
        }
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let robot = sim.load_urdf(&self.path, &self.options)?;
        let moving: Vec<_> = robot
            .joints
            .iter()
            .filter(|(_, id)| sim.scene().joint(*id).is_ok_and(|j| j.joint_type() != JointType::Fixed))
            .map(|(_, id)| *id)
            .collect();
        self.positions = Some(sim.add_sensor(JointPositions::new(sim.scene(), &moving)?)?);
        self.summary = format!(
            "robot {:?}: {} links, {} joints ({} moving){}",
            robot.name,
            robot.links.len(),
            robot.joints.len(),
            moving.len(),
            if robot.base_joint.is_some() { ", fixed base" } else { "" }
        );
        Ok(())
    }
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let argv: Vec<String> = std::env::args().collect();
    let usage = "usage: urdf FILE [--fixed-base] [--y-up] [--q0 NAME=VALUE,...] [--duration S] [--csv OUT] [--every N] [--screenshots DIR] [--window]";
    let Some(file) = argv.get(1).filter(|a| !a.starts_with("--")).cloned() else {
        eprintln!("{usage}");
        std::process::exit(2);
    };
    let q0 = argv.iter().position(|a| a == "--q0").map(|i| argv.get(i + 1).cloned().unwrap_or_default());
    let mut skip = vec![file.as_str(), "--fixed-base", "--y-up"];
    if let Some(q) = &q0 {
        skip.extend(["--q0", q.as_str()]);
    }
    let args = common::args::parse_except(5.0, &skip);
    let mut options = UrdfOptions::new().fixed_base(argv.iter().any(|a| a == "--fixed-base"));
    if argv.iter().any(|a| a == "--y-up") {
        options = options.up_axis(UpAxis::Y);
    }
    for pair in q0.iter().flat_map(|q| q.split(',')).filter(|p| !p.is_empty()) {
        let parsed = pair.split_once('=').and_then(|(n, v)| Some((n, v.parse::<f64>().ok()?)));
        let Some((name, value)) = parsed else {
            return Err(format!("--q0 takes NAME=VALUE pairs separated by commas, got {pair:?}").into());
        };
        options = options.initial_position(name, value);
    }
    let mut program = UrdfProgram { path: PathBuf::from(&file), options, positions: None, summary: String::new() };
    let sim = common::args::run(&mut program, &args)?;
    println!("{}", program.summary);
    let log = sim.records(program.positions.expect("created"))?;
    if let Some(last) = log.last() {
        let names = ars::Record::headers(&last.record);
        let at: Vec<String> = names.iter().zip(&last.record.values).map(|(n, q)| format!("{n} {q:+.4}")).collect();
        println!("after {:.2} s: {}", last.time, at.join(", "));
    }
    if let Some(path) = &args.csv {
        common::args::export_csv(path, log, args.every)?;
    }
    Ok(())
}
