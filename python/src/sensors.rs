//! Sensors from Python: `sim.add_sensor("gps", "ball")` declares one of ARS's sensors
//! on the simulation; its records come back as a numpy structured array (`time`,
//! `step`, then one field per column, named as in the CSV) or as CSV.

use ars_core::sensors::AnySensorId;
use ars_core::{Error, SENSOR_KINDS, Simulation};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::simulation::PySimulation;

/// The kind of ARS sensor a Python name means: the type's name itself (`"Gps"`), or
/// it in snake case (`"gps"`, `"joint_positions"`), with `"Sensor"` understood
/// (`"hinge"`, `"contact"`).
fn kind_of(name: &str) -> Option<&'static str> {
    let camel: String = name
        .split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next().map(|f| f.to_ascii_uppercase().to_string() + c.as_str()).unwrap_or_default()
        })
        .collect();
    SENSOR_KINDS.iter().copied().find(|k| *k == name || *k == camel || *k == format!("{camel}Sensor"))
}

/// Declares a sensor named `kind` on `targets` (object or joint names, whichever it
/// reads).
pub(crate) fn declare(
    sim: &mut Simulation,
    kind: &str,
    targets: &[String],
    every: Option<f64>,
) -> ars_core::Result<AnySensorId> {
    let Some(kind) = kind_of(kind) else {
        return Err(Error::OutOfRange {
            what: "sensor kind",
            detail: format!("{kind:?}; the kinds (or their snake_case names): {}", SENSOR_KINDS.join(", ")),
        });
    };
    let reads_joints = kind.starts_with("Joint") || kind == "HingeSensor";
    let (mut objects, mut joints) = (Vec::new(), Vec::new());
    for name in targets {
        if reads_joints {
            joints.push(sim.joint(name.as_str())?.id());
        } else {
            objects.push(sim.object(name.as_str())?.id());
        }
    }
    sim.add_sensor_of_kind(kind, &objects, &joints, every)
}

/// A sensor declared on a simulation (`sim.add_sensor`): its records, read when
/// asked.
#[pyclass(name = "Sensor", module = "ars", frozen)]
pub struct PySensor {
    sim: Py<PySimulation>,
    kind: String,
    id: AnySensorId,
}

impl PySensor {
    pub(crate) fn new(sim: Py<PySimulation>, kind: String, id: AnySensorId) -> Self {
        PySensor { sim, kind, id }
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
        let id = self.id;
        let c = self.sim.get().with(py, move |sim| {
            let (_, log) = sim.sensor_table(id)?;
            let stamps = log.stamps();
            let headers = log.headers();
            let rows: Vec<Vec<Option<f64>>> = (0..stamps.len()).map(|i| log.cells(i)).collect();
            let values = (0..headers.len()).map(|k| rows.iter().map(|r| r[k].unwrap_or(f64::NAN)).collect()).collect();
            Ok(Columns {
                headers,
                times: stamps.iter().map(|s| s.0).collect(),
                steps: stamps.iter().map(|s| s.1 as i64).collect(),
                values,
            })
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
        let id = self.id;
        self.sim.get().with(py, move |sim| {
            let (_, log) = sim.sensor_table(id)?;
            std::fs::File::create(&path)
                .and_then(|f| ars_core::sensors::write_csv_table(std::io::BufWriter::new(f), &[("", log)], 1))
                .map_err(|e| Error::OutOfRange {
                    what: "CSV file",
                    detail: format!("{}: cannot be written: {e}", path.display()),
                })
        })
    }

    /// Number of records.
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        let id = self.id;
        self.sim.get().with(py, move |sim| Ok(sim.sensor_table(id)?.1.len()))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Sensor {}>", self.kind)
    }
}
