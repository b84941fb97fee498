//! Sensors from Python: `sim.add_sensor("gps", "ball")` declares one of ARS's sensors
//! on the simulation; its records come back as a numpy structured array (`time`,
//! `step`, then one field per column, named as in the CSV) or as CSV.

use std::sync::Arc;

use ars_core::sensors::{
    Accelerometer, ContactSensor, CsvColumns, Gps, HingeSensor, Imu, Inclinometer, JointForce, JointPositions,
    JointPower, JointReaction, JointTorque, KineticEnergy, PotentialEnergy, Sensor, SensorId, SystemTotalEnergy,
    TotalEnergy, Velometer,
};
use ars_core::{Error, Simulation};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::simulation::PySimulation;

/// Reads a sensor's log through its CSV columns, whatever its record type.
type LogAccess = Arc<dyn Fn(&Simulation, &mut dyn FnMut(&dyn CsvColumns)) -> ars_core::Result<()> + Send + Sync>;

fn access<S: Sensor>(id: SensorId<S>) -> LogAccess {
    Arc::new(move |sim: &Simulation, f: &mut dyn FnMut(&dyn CsvColumns)| {
        f(sim.records(id)?);
        Ok(())
    })
}

/// The kinds of sensor `add_sensor` knows, and what each reads.
pub(crate) const KINDS: &str = "on an object: gps, velometer, accelerometer, inclinometer, imu, contact, \
     kinetic_energy, potential_energy, total_energy; on a joint: hinge, joint_torque, joint_force, joint_power, \
     joint_reaction; on joints (a list): joint_positions; on the whole simulation: system_total_energy";

fn add<S: Sensor>(sim: &mut Simulation, sensor: S, every: Option<f64>) -> ars_core::Result<LogAccess> {
    let id = match every {
        Some(period) => sim.add_sensor_every(sensor, period)?,
        None => sim.add_sensor(sensor)?,
    };
    Ok(access(id))
}

/// Declares a sensor of `kind` on `targets` (object or joint names).
pub(crate) fn declare(
    sim: &mut Simulation,
    kind: &str,
    targets: &[String],
    every: Option<f64>,
) -> ars_core::Result<LogAccess> {
    let one = |what: &'static str| -> ars_core::Result<&str> {
        match targets {
            [name] => Ok(name.as_str()),
            _ => Err(Error::OutOfRange { what, detail: format!("a {kind} sensor reads one {what}: give its name") }),
        }
    };
    let object = |sim: &Simulation| one("object").and_then(|n| Ok(sim.object(n)?.id()));
    let joint = |sim: &Simulation| one("joint").and_then(|n| Ok(sim.joint(n)?.id()));
    match kind {
        "gps" => add(sim, Gps::new(object(sim)?), every),
        "velometer" => add(sim, Velometer::new(object(sim)?), every),
        "accelerometer" => add(sim, Accelerometer::new(object(sim)?), every),
        "inclinometer" => add(sim, Inclinometer::new(object(sim)?), every),
        "imu" => add(sim, Imu::new(object(sim)?), every),
        "contact" => add(sim, ContactSensor::new(object(sim)?), every),
        "kinetic_energy" => add(sim, KineticEnergy::new(object(sim)?), every),
        "potential_energy" => add(sim, PotentialEnergy::new(object(sim)?), every),
        "total_energy" => add(sim, TotalEnergy::new(object(sim)?), every),
        "system_total_energy" => add(sim, SystemTotalEnergy::new(), every),
        "hinge" => add(sim, HingeSensor::new(joint(sim)?), every),
        "joint_torque" => add(sim, JointTorque::new(joint(sim)?), every),
        "joint_force" => add(sim, JointForce::new(joint(sim)?), every),
        "joint_power" => add(sim, JointPower::new(joint(sim)?), every),
        "joint_reaction" => add(sim, JointReaction::new(joint(sim)?), every),
        "joint_positions" => {
            let ids = targets.iter().map(|n| Ok(sim.joint(n.as_str())?.id())).collect::<ars_core::Result<Vec<_>>>()?;
            let sensor = JointPositions::new(sim, &ids)?;
            add(sim, sensor, every)
        }
        other => Err(Error::OutOfRange { what: "sensor kind", detail: format!("{other:?}; the kinds: {KINDS}") }),
    }
}

/// A sensor declared on a simulation (`sim.add_sensor`): its records, read when
/// asked.
#[pyclass(name = "Sensor", module = "ars", frozen)]
pub struct PySensor {
    sim: Py<PySimulation>,
    kind: String,
    log: LogAccess,
}

impl PySensor {
    pub(crate) fn new(sim: Py<PySimulation>, kind: String, log: LogAccess) -> Self {
        PySensor { sim, kind, log }
    }
}

/// A log's columns: headers, stamps and cells (NaN where a value is missing).
struct Columns {
    headers: Vec<String>,
    times: Vec<f64>,
    steps: Vec<i64>,
    values: Vec<Vec<f64>>,
}

#[pymethods]
impl PySensor {
    /// Its kind.
    #[getter]
    fn kind(&self) -> &str {
        &self.kind
    }

    /// The records so far: a numpy structured array with `time` (s, at the end of the
    /// step), `step`, then one field per column (named as in the CSV, units in
    /// brackets; NaN where a record has no value).
    fn records<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let log = self.log.clone();
        let c = self.sim.get().with(py, move |sim| {
            let mut columns = None;
            log(sim, &mut |log: &dyn CsvColumns| {
                let stamps = log.stamps();
                let headers = log.headers();
                let values = (0..headers.len())
                    .map(|k| (0..stamps.len()).map(|i| log.cells(i)[k].unwrap_or(f64::NAN)).collect())
                    .collect();
                columns = Some(Columns {
                    headers,
                    times: stamps.iter().map(|s| s.0).collect(),
                    steps: stamps.iter().map(|s| s.1 as i64).collect(),
                    values,
                });
            })?;
            Ok(columns.expect("the log was read"))
        })?;
        let numpy = py.import("numpy")?;
        let mut dtype: Vec<(String, &str)> = vec![("time".into(), "f8"), ("step".into(), "i8")];
        dtype.extend(c.headers.iter().map(|h| (h.clone(), "f8")));
        let table = numpy.call_method1("zeros", (c.times.len(), dtype))?;
        table.set_item("time", PyArray1::from_vec(py, c.times))?;
        table.set_item("step", PyArray1::from_vec(py, c.steps))?;
        for (h, v) in c.headers.into_iter().zip(c.values) {
            table.set_item(h, PyArray1::from_vec(py, v))?;
        }
        Ok(table)
    }

    /// Writes the records as CSV to `path` (a header `time [s],step,<columns>`, numbers
    /// in their shortest exact form).
    fn to_csv(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        let log = self.log.clone();
        self.sim.get().with(py, move |sim| {
            let mut written = Ok(());
            log(sim, &mut |log: &dyn CsvColumns| {
                written = std::fs::File::create(&path)
                    .and_then(|f| ars_core::sensors::write_csv_table(std::io::BufWriter::new(f), &[("", log)], 1));
            })?;
            written.map_err(|e| Error::OutOfRange {
                what: "CSV file",
                detail: format!("{}: cannot be written: {e}", path.display()),
            })
        })
    }

    /// Number of records.
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        let log = self.log.clone();
        self.sim.get().with(py, move |sim| {
            let mut n = 0;
            log(sim, &mut |log: &dyn CsvColumns| n = log.stamps().len())?;
            Ok(n)
        })
    }

    fn __repr__(&self) -> String {
        format!("<ars.Sensor {}>", self.kind)
    }
}
