//! The golden runs: programs whose exact output (CSV bytes) is committed as a sha256
//! hash in `ars-programs/golden.json`, so that any change to the bits ARS computes is
//! seen. The tests recompute them (`tests/golden_hashes.rs`); a user checks an
//! installation with `cargo run --release --example verify` or `python -m ars.verify`.
//!
//! Each entry keeps, besides the hash of the whole output, the hash and the last line
//! of each of about forty blocks of lines: a different output is reported at its first
//! differing block, with the first differing value of that block's last line.
//!
//! Updating the table (`cargo run --release --example verify -- --write`) is a
//! deliberate act: the CHANGELOG says which results changed and why.

use ars_core::nalgebra::Vector3;
use ars_core::sensors::{
    Accelerometer, CsvColumns, Gps, Imu, JointPositions, JointTorque, Lidar, Noisy, Sensor, SensorId, Velometer,
    write_csv_table,
};
use ars_core::world::SpaceKind;
use ars_core::{Mass, PositionServo, Profile, Program, ProgramRunner, Result, Simulation, UrdfOptions};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::{ConicalPendulum, FallingBallSensors, SinusoidalTerrain, SpeedProfile};

/// The committed table, as compiled in.
pub const TABLE: &str = include_str!("../golden.json");

/// The format tag of the table.
const FORMAT: &str = "ars-golden/1";

/// How many blocks an output is cut into for locating a difference.
const BLOCKS: usize = 40;

/// A program whose output is held by the table.
pub struct GoldenRun {
    /// Its name in the table.
    pub name: &'static str,
    /// What it runs.
    pub what: &'static str,
    /// Simulated seconds.
    pub duration: f64,
    run: fn(f64) -> Result<Vec<u8>>,
}

impl GoldenRun {
    /// Runs it: its output, CSV bytes.
    pub fn output(&self) -> Result<Vec<u8>> {
        (self.run)(self.duration)
    }
}

/// The golden runs of the Rust programs (the table also holds the Python package's,
/// checked by `python -m ars.verify`).
pub fn runs() -> Vec<GoldenRun> {
    vec![
        GoldenRun {
            name: "conical_pendulum",
            what: "the thesis' validation arm (IROS example 2), as `--example conical_pendulum --csv`",
            duration: 20.0,
            run: conical_pendulum,
        },
        GoldenRun {
            name: "speed_profile",
            what: "the mobile manipulator tracking its speed profile (IROS example 3), as `--example speed_profile --csv`",
            duration: 15.0,
            run: speed_profile,
        },
        GoldenRun {
            name: "sinusoidal_terrain",
            what: "the vehicle with arm on the sinusoidal terrain, as `--example sinusoidal_terrain --csv`",
            duration: 20.0,
            run: sinusoidal_terrain,
        },
        GoldenRun {
            name: "falling_ball_sensors",
            what: "the thesis' falling ball and its six sensors, as `--example falling_ball_sensors --csv`",
            duration: 2.0,
            run: falling_ball_sensors,
        },
        GoldenRun {
            name: "urdf_arm",
            what: "tests/data/rnea_arm.urdf, fixed base, PD position servos following set-point profiles",
            duration: 3.0,
            run: urdf_arm,
        },
        GoldenRun {
            name: "noisy_sensors",
            what: "a ball bouncing past a box, seen by seeded noisy GPS, velometer, accelerometer, IMU and lidar",
            duration: 2.0,
            run: noisy_sensors,
        },
    ]
}

fn csv(logs: &[(&str, &dyn CsvColumns)]) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    write_csv_table(&mut out, logs, 1).map_err(|e| ars_core::Error::User(format!("writing CSV: {e}")))?;
    Ok(out)
}

/// The CSV of the record a thesis program keeps (what its example's `--csv` writes).
fn program_record<P: Program, S: Sensor>(
    mut program: P,
    duration: f64,
    record: fn(&P) -> Option<SensorId<S>>,
) -> Result<Vec<u8>> {
    let mut runner = ProgramRunner::new(&mut program)?;
    runner.run_for(duration)?;
    let sim = runner.into_simulation();
    record_csv(sim.records(record(&program).ok_or_else(|| ars_core::Error::User("no record was made".into()))?)?)
}

/// The CSV of one record, as a golden run of a thesis program writes it: to compare
/// with the table a run stepped some other way (through the ROS 2 bridge in lock step,
/// for example).
pub fn record_csv(record: &dyn CsvColumns) -> Result<Vec<u8>> {
    csv(&[("", record)])
}

fn conical_pendulum(duration: f64) -> Result<Vec<u8>> {
    program_record(ConicalPendulum::default(), duration, |p| p.record)
}

fn speed_profile(duration: f64) -> Result<Vec<u8>> {
    program_record(SpeedProfile::with_derivative_gain(0.0), duration, |p| p.record)
}

fn sinusoidal_terrain(duration: f64) -> Result<Vec<u8>> {
    program_record(SinusoidalTerrain::default(), duration, |p| p.record)
}

fn falling_ball_sensors(duration: f64) -> Result<Vec<u8>> {
    let mut p = FallingBallSensors::default();
    let mut runner = ProgramRunner::new(&mut p)?;
    runner.run_for(duration)?;
    let sim = runner.into_simulation();
    let missing = || ars_core::Error::User("the program made its sensors".into());
    csv(&[
        ("gps", sim.records(p.gps.ok_or_else(missing)?)?),
        ("velometer", sim.records(p.velometer.ok_or_else(missing)?)?),
        ("accelerometer", sim.records(p.accelerometer.ok_or_else(missing)?)?),
        ("kinetic", sim.records(p.kinetic.ok_or_else(missing)?)?),
        ("potential", sim.records(p.potential.ok_or_else(missing)?)?),
        ("total", sim.records(p.total.ok_or_else(missing)?)?),
    ])
}

/// The URDF of the golden arm, compiled in so that an installed verifier needs no files.
const RNEA_ARM: &str = include_str!("../../tests/data/rnea_arm.urdf");

fn urdf_arm(duration: f64) -> Result<Vec<u8>> {
    let mut sim = Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build()?;
    let robot = sim.load_urdf_text(RNEA_ARM, "rnea_arm.urdf", &UrdfOptions::new().fixed_base(true))?;
    let joints: Vec<_> = robot.joints.iter().map(|(_, id)| *id).collect();
    for (k, id) in joints.iter().enumerate() {
        let target = 0.3 * (k as f64 + 1.0);
        let profile = Profile::new(vec![(0.0, 0.0), (1.0, target), (2.0, -target)])?;
        sim.scene_mut().joint_mut(*id)?.set_controller(PositionServo::pd(profile, 40.0, 4.0))?;
    }
    let positions = JointPositions::new(sim.scene(), &joints)?;
    let positions = sim.add_sensor(positions)?;
    let torque = sim.add_sensor(JointTorque::new(joints[0]))?;
    sim.run_for(duration)?;
    csv(&[("", sim.records(positions)?), ("j1", sim.records(torque)?)])
}

fn noisy_sensors(duration: f64) -> Result<Vec<u8>> {
    let mut sim = Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).seed(7).build()?;
    let ball = sim.scene_mut().add_sphere(0.2, [0.0, 1.5, 0.0], Mass::Total(1.0))?;
    sim.scene_mut().body_mut(ball)?.set_linear_velocity(Vector3::new(0.8, 0.0, 0.3))?;
    sim.scene_mut().add_box([0.5, 0.5, 0.5], [2.0, 0.25, 0.0], Mass::Total(5.0))?;
    let gps = sim.add_sensor(Noisy::new(Gps::new(ball), 0.01, 1)?)?;
    let velometer = sim.add_sensor(Noisy::new(Velometer::new(ball), 0.02, 2)?)?;
    let accelerometer = sim.add_sensor(Noisy::new(Accelerometer::new(ball), 0.1, 3)?)?;
    let imu = sim.add_sensor(Noisy::new(Imu::new(ball), 0.05, 4)?)?;
    let lidar = Lidar::new(36, std::f64::consts::TAU, 5.0)?.on(ball, Default::default());
    let lidar = sim.add_sensor_every(Noisy::new(lidar, 0.005, 5)?, 0.05)?;
    sim.run_for(duration)?;
    let mut out = csv(&[
        ("gps", sim.records(gps)?),
        ("velometer", sim.records(velometer)?),
        ("accelerometer", sim.records(accelerometer)?),
        ("imu", sim.records(imu)?),
    ])?;
    out.extend(csv(&[("lidar", sim.records(lidar)?)])?);
    Ok(out)
}

/// The committed table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GoldenTable {
    /// `"ars-golden/1"`.
    pub format: String,
    /// One entry per golden run, Rust's and Python's.
    pub runs: Vec<GoldenEntry>,
}

/// A run's committed output: its hash, and its blocks for locating a difference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GoldenEntry {
    /// The run's name.
    pub name: String,
    /// Simulated seconds.
    pub duration: f64,
    /// Lines of output.
    pub lines: usize,
    /// sha256 of the whole output, hex.
    pub sha256: String,
    /// The output in blocks of consecutive lines.
    pub blocks: Vec<GoldenBlock>,
}

/// A block of lines of a run's output.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GoldenBlock {
    /// Its first line (0 is the header).
    pub first: usize,
    /// One past its last line.
    pub end: usize,
    /// sha256 of its lines (with their line ends), hex.
    pub sha256: String,
    /// Its last line, as written.
    pub last: String,
}

/// How a run's output compares with the table.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// The same bytes.
    Identical,
    /// Not in the table.
    Unknown,
    /// Different: where, and the first differing value found.
    Differs(String),
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Verdict::Identical => write!(f, "identical"),
            Verdict::Unknown => write!(f, "not in the golden table"),
            Verdict::Differs(detail) => write!(f, "DIFFERENT: {detail}"),
        }
    }
}

/// sha256 of `bytes`, hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// The lines of an output, each with its line end.
fn lines(output: &[u8]) -> Vec<&[u8]> {
    output.split_inclusive(|&b| b == b'\n').collect()
}

impl GoldenEntry {
    /// The entry of an output.
    pub fn of(name: &str, duration: f64, output: &[u8]) -> GoldenEntry {
        let all = lines(output);
        let size = all.len().div_ceil(BLOCKS).max(1);
        let blocks = all
            .chunks(size)
            .enumerate()
            .map(|(k, chunk)| GoldenBlock {
                first: k * size,
                end: k * size + chunk.len(),
                sha256: sha256_hex(&chunk.concat()),
                last: String::from_utf8_lossy(chunk.last().expect("chunks are not empty")).trim_end().to_string(),
            })
            .collect();
        GoldenEntry { name: name.into(), duration, lines: all.len(), sha256: sha256_hex(output), blocks }
    }

    /// How `output` compares with this entry: identical, or where it first differs
    /// and the first differing value among the blocks' last lines from there on (a
    /// difference in the physics carries on to later lines).
    pub fn compare(&self, output: &[u8]) -> Verdict {
        if sha256_hex(output) == self.sha256 {
            return Verdict::Identical;
        }
        let all = lines(output);
        if all.len() != self.lines {
            return Verdict::Differs(format!("the output has {} lines, the table {}", all.len(), self.lines));
        }
        let block_lines = |b: &GoldenBlock| &all[b.first..b.end];
        let Some(first) = self.blocks.iter().position(|b| sha256_hex(&block_lines(b).concat()) != b.sha256) else {
            return Verdict::Differs("the output differs from the table, not in any block (a stale table?)".into());
        };
        let place =
            format!("first in lines {}..{} of {}", self.blocks[first].first + 1, self.blocks[first].end, self.lines);
        for block in &self.blocks[first..] {
            let got = String::from_utf8_lossy(block_lines(block).last().expect("blocks are not empty"));
            let (e, g): (Vec<&str>, Vec<&str>) = (block.last.split(',').collect(), got.trim_end().split(',').collect());
            if let Some(i) = (0..e.len().max(g.len())).find(|&i| e.get(i) != g.get(i)) {
                return Verdict::Differs(format!(
                    "{place}; at t = {} s (line {}), column {:?}: expected {}, got {}",
                    g.first().unwrap_or(&"?"),
                    block.end,
                    cell(all[0], i),
                    e.get(i).unwrap_or(&"(none)"),
                    g.get(i).unwrap_or(&"(none)")
                ));
            }
        }
        Verdict::Differs(format!("{place}; the sampled lines after it are the same"))
    }
}

/// Column `i` of a CSV line.
fn cell(line: &[u8], i: usize) -> String {
    String::from_utf8_lossy(line).trim_end().split(',').nth(i).unwrap_or("?").to_string()
}

impl GoldenTable {
    /// The committed table.
    pub fn committed() -> GoldenTable {
        GoldenTable::parse(TABLE).expect("the committed golden table parses")
    }

    /// A table from its JSON text.
    pub fn parse(text: &str) -> Result<GoldenTable> {
        let table: GoldenTable = serde_json::from_str(text)
            .map_err(|e| ars_core::Error::User(format!("the golden table is not valid: {e}")))?;
        if table.format != FORMAT {
            return Err(ars_core::Error::User(format!("golden table format {:?}, expected {FORMAT:?}", table.format)));
        }
        Ok(table)
    }

    /// An empty table.
    pub fn new() -> GoldenTable {
        GoldenTable { format: FORMAT.into(), runs: Vec::new() }
    }

    /// The entry of run `name`.
    pub fn entry(&self, name: &str) -> Option<&GoldenEntry> {
        self.runs.iter().find(|e| e.name == name)
    }

    /// How run `name`'s `output` compares with the table.
    pub fn compare(&self, name: &str, output: &[u8]) -> Verdict {
        self.entry(name).map_or(Verdict::Unknown, |e| e.compare(output))
    }

    /// Puts `entry` in the table, in place of the one of the same name.
    pub fn set(&mut self, entry: GoldenEntry) {
        match self.runs.iter_mut().find(|e| e.name == entry.name) {
            Some(e) => *e = entry,
            None => self.runs.push(entry),
        }
    }

    /// The table as JSON text (as committed).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a golden table serialises") + "\n"
    }
}

impl Default for GoldenTable {
    fn default() -> Self {
        GoldenTable::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_changed_value_is_reported_with_its_time_and_column() {
        let mut output = String::from("time [s],step,x [m]\n");
        for k in 0..100 {
            output.push_str(&format!("{},{k},{}\n", f64::from(k) * 0.1, f64::from(k) * 0.5));
        }
        let entry = GoldenEntry::of("t", 10.0, output.as_bytes());
        assert_eq!(entry.lines, 101);
        assert_eq!(entry.compare(output.as_bytes()), Verdict::Identical);
        // From k = 50 on, one ulp more: what a changed physics does to later lines.
        let mut diverged = String::from("time [s],step,x [m]\n");
        for k in 0..100 {
            let x = f64::from(k) * 0.5;
            let x = if k >= 50 { f64::from_bits(x.to_bits() + 1) } else { x };
            diverged.push_str(&format!("{},{k},{x}\n", f64::from(k) * 0.1));
        }
        match entry.compare(diverged.as_bytes()) {
            Verdict::Differs(detail) => {
                assert!(detail.contains("first in lines 52..54 of 101"), "{detail}");
                assert!(detail.contains("at t = 5.2 s (line 54)"), "{detail}");
                assert!(detail.contains("column \"x [m]\": expected 26, got 26.000000000000004"), "{detail}");
            }
            other => panic!("{other}"),
        }
        // One inner line alone: located, no value to show.
        let inner = output.replace("\n5,50,25\n", "\n5,50,26\n");
        assert!(
            matches!(entry.compare(inner.as_bytes()), Verdict::Differs(d) if d.contains("sampled lines after it are the same"))
        );
        let shorter = &output[..output.len() - 20];
        assert!(matches!(entry.compare(shorter.as_bytes()), Verdict::Differs(d) if d.contains("lines")));
    }

    #[test]
    fn the_committed_table_parses_and_names_every_rust_run() {
        let table = GoldenTable::committed();
        for run in runs() {
            let entry = table.entry(run.name).unwrap_or_else(|| panic!("{} is not in golden.json", run.name));
            assert_eq!(entry.duration, run.duration, "{}", run.name);
        }
    }
}
