//! Sensors from Python: `sim.add_sensor("gps", "ball")` declares one of ARS's sensors
//! on the simulation; its records come back as a numpy structured array (`time`,
//! `step`, then one field per column, named as in the CSV) or as CSV.

use ars_core::nalgebra::Isometry3;
use ars_core::sensors::SensorTarget;
use ars_core::sensors::{AnySensorId, DepthCamera, Lidar, Noisy, Sensor, SensorId};
use ars_core::{Error, SensorKind, Simulation};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;

use crate::simulation::PySimulation;

/// The kind of ARS sensor a Python name means: the type's name itself (`"Gps"`), or
/// it in snake case (`"gps"`, `"joint_positions"`), with `"Sensor"` understood
/// (`"hinge"`, `"contact"`); lidars and depth cameras have calls of their own.
fn kind_of(name: &str) -> Option<SensorKind> {
    let camel: String = name
        .split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next().map(|f| f.to_ascii_uppercase().to_string() + c.as_str()).unwrap_or_default()
        })
        .collect();
    SensorKind::from_targets().find(|k| {
        let k = k.name();
        k == name || k == camel || k == format!("{camel}Sensor")
    })
}

/// `CamelCase` in snake case: `"JointPositions"` → `"joint_positions"`.
pub(crate) fn snake_case(name: &str) -> String {
    let mut snake = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                snake.push('_');
            }
            snake.push(c.to_ascii_lowercase());
        } else {
            snake.push(c);
        }
    }
    snake
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
        return Err(Error::UnknownKind {
            what: "sensor kind",
            name: kind.to_string(),
            known: SensorKind::from_targets().map(|k| snake_case(k.name())).collect(),
        });
    };
    let reads_joints = matches!(kind.target(), SensorTarget::Joint | SensorTarget::Joints);
    let (mut objects, mut joints) = (Vec::new(), Vec::new());
    for name in targets {
        if reads_joints {
            joints.push(sim.scene().joint(name.as_str())?.id());
        } else {
            objects.push(sim.scene().object(name.as_str())?.id());
        }
    }
    sim.add_sensor_of_kind(kind, &objects, &joints, every)
}

/// A sensor's id, with its type where Python reads more than its CSV columns.
#[derive(Clone, Copy)]
pub(crate) enum Typed {
    /// Read through its CSV columns only.
    Table(AnySensorId),
    Lidar(SensorId<Lidar>),
    NoisyLidar(SensorId<Noisy<Lidar>>),
    Depth(SensorId<DepthCamera>),
}

impl Typed {
    fn any(self) -> AnySensorId {
        match self {
            Typed::Table(id) => id,
            Typed::Lidar(id) => id.into(),
            Typed::NoisyLidar(id) => id.into(),
            Typed::Depth(id) => id.into(),
        }
    }

    /// Adds `sensor`, sampled after every step or every `every` seconds.
    pub(crate) fn add<S: Sensor>(
        sim: &mut Simulation,
        sensor: S,
        every: Option<f64>,
        typed: fn(SensorId<S>) -> Typed,
    ) -> ars_core::Result<Typed> {
        let id = match every {
            Some(p) => sim.add_sensor_every(sensor, p)?,
            None => sim.add_sensor(sensor)?,
        };
        Ok(typed(id))
    }

    /// Every scan's ranges (a row per scan), for a lidar.
    fn scans(self, sim: &Simulation) -> Option<ars_core::Result<Vec<&ars_core::sensors::Scan>>> {
        match self {
            Typed::Lidar(id) => Some(sim.records(id).map(|log| log.iter().map(|s| &s.record).collect())),
            Typed::NoisyLidar(id) => Some(sim.records(id).map(|log| log.iter().map(|s| &s.record).collect())),
            _ => None,
        }
    }
}

/// What `add_lidar` was given.
pub(crate) struct LidarSpec {
    pub(crate) beams: u32,
    pub(crate) fov: f64,
    pub(crate) max_range: f64,
    pub(crate) min_range: f64,
    pub(crate) planes: Option<Vec<f64>>,
    pub(crate) on: Option<String>,
    pub(crate) offset: Isometry3<f64>,
    pub(crate) every: Option<f64>,
    pub(crate) noise: Option<f64>,
    pub(crate) seed: u64,
}

impl LidarSpec {
    pub(crate) fn add_to(self, sim: &mut Simulation) -> ars_core::Result<Typed> {
        let mut lidar = Lidar::new(self.beams, self.fov, self.max_range)?.min_range(self.min_range)?;
        if let Some(planes) = &self.planes {
            lidar = lidar.planes(planes)?;
        }
        let lidar = match self.on {
            Some(name) => lidar.on(sim.scene().object(name.as_str())?.id(), self.offset),
            None => lidar.at(self.offset),
        };
        match self.noise {
            None => Typed::add(sim, lidar, self.every, Typed::Lidar),
            Some(sd) => Typed::add(sim, Noisy::new(lidar, sd, self.seed)?, self.every, Typed::NoisyLidar),
        }
    }
}

/// A sensor declared on a simulation (`sim.add_sensor`, `add_lidar`,
/// `add_depth_camera`): its records, read when asked.
#[pyclass(name = "Sensor", module = "ars", frozen)]
pub struct PySensor {
    sim: Py<PySimulation>,
    kind: String,
    id: AnySensorId,
    typed: Typed,
}

impl PySensor {
    pub(crate) fn new(sim: Py<PySimulation>, kind: String, typed: Typed) -> Self {
        PySensor { sim, kind, id: typed.any(), typed }
    }

    /// `row(scan)` for each of a lidar's scans; for other sensors an `ars.InputError`
    /// saying they have no `what`.
    fn per_scan<T: Send>(
        &self,
        py: Python<'_>,
        what: &str,
        row: impl Fn(&ars_core::sensors::Scan) -> T + Send,
    ) -> PyResult<Vec<T>> {
        let typed = self.typed;
        let rows = self.sim.get().with(py, move |sim| match typed.scans(sim) {
            Some(scans) => Ok(Some(scans?.into_iter().map(&row).collect::<Vec<_>>())),
            None => Ok(None),
        })?;
        rows.ok_or_else(|| {
            let kind = self.kind.replace('_', " ");
            crate::errors::raise(py, "InputError", format!("a {kind} sensor has no {what} (a lidar has)"))
        })
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
                .map_err(|e| Error::io("write the CSV file", &path, &e))
        })
    }

    /// Number of records.
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        let id = self.id;
        self.sim.get().with(py, move |sim| Ok(sim.sensor_table(id)?.1.len()))
    }

    /// A lidar's scans: an array of shape `(records, beams × planes)`, m, plane after
    /// plane (`inf`: nothing seen). For other sensors, an `ars.InputError`.
    fn ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = self.per_scan(py, "ranges", |s| s.ranges.clone())?;
        rows_to_array(py, rows)
    }

    /// A lidar's hit points: an array of shape `(records, beams × planes, 3)`, world
    /// frame, m (NaN where a beam saw nothing).
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let rows = self.per_scan(py, "points", |s| {
            s.points.iter().map(|p| p.map_or(vec![f64::NAN; 3], |p| vec![p.x, p.y, p.z])).collect::<Vec<_>>()
        })?;
        PyArray3::from_vec3(py, &rows).map_err(Into::into)
    }

    /// A depth camera's images: an array of `float32`, shape `(records, height,
    /// width)`, m along the optical axis, rows from the top (`inf`: nothing seen).
    fn images<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let Typed::Depth(id) = self.typed else {
            return Err(crate::errors::raise(
                py,
                "InputError",
                format!("a {} sensor has no images (a depth camera has)", self.kind.replace('_', " ")),
            ));
        };
        let (shape, pixels) = self.sim.get().with(py, move |sim| {
            let log = sim.records(id)?;
            let (w, h) = log.last().map_or((0, 0), |s| (s.record.width as usize, s.record.height as usize));
            let pixels: Vec<f32> = log.iter().flat_map(|s| s.record.pixels.iter().copied()).collect();
            Ok(((log.len(), h, w), pixels))
        })?;
        let flat = PyArray1::from_vec(py, pixels);
        flat.reshape([shape.0, shape.1, shape.2])
    }

    /// Forgets the records so far.
    fn clear(&self, py: Python<'_>) -> PyResult<()> {
        let id = self.id;
        self.sim.get().with(py, move |sim| sim.clear_any_records(id))
    }

    /// Removes the sensor from its simulation (with its records).
    fn remove(&self, py: Python<'_>) -> PyResult<()> {
        let id = self.id;
        self.sim.get().with(py, move |sim| sim.remove_any_sensor(id))
    }

    /// Whether it stopped sampling because an object or joint it reads was removed.
    #[getter]
    fn detached(&self, py: Python<'_>) -> PyResult<bool> {
        let id = self.id;
        self.sim.get().with(py, move |sim| sim.is_any_sensor_detached(id))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Sensor {}>", self.kind)
    }
}

/// Rows of equal length as a 2-D array (shape `(0, 0)` when there is none).
fn rows_to_array(py: Python<'_>, rows: Vec<Vec<f64>>) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let (n, m) = (rows.len(), rows.first().map_or(0, Vec::len));
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    PyArray1::from_vec(py, flat).reshape([n, m])
}
