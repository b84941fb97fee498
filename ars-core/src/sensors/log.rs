//! The records of sensors: a [`SensorLog`] of time-stamped [`Sample`]s, and their CSV
//! columns, one log alone or several joined in one table.

use std::io::{self, Write};

/// One measurement as CSV columns.
pub trait Record: Clone + Send + 'static {
    /// Column headers, each naming its quantity and unit, e.g. `"y [m]"`.
    fn columns() -> Vec<&'static str>;
    /// The values, in column order (`None`: no value, e.g. a laser that hit nothing).
    fn values(&self) -> Vec<Option<f64>>;
    /// The headers of this record, for records whose columns are only known when the
    /// sensor is made (one per joint of a robot, say); by default [`Record::columns`].
    fn headers(&self) -> Vec<String> {
        Self::columns().into_iter().map(String::from).collect()
    }
}

/// A measurement and when it was taken.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample<R> {
    /// Simulated time at the end of the step, s.
    pub time: f64,
    /// Number of the step (1 for the first).
    pub step: u64,
    /// The measurement.
    pub record: R,
}

/// Every sample of one sensor, oldest first.
#[derive(Clone, Debug)]
pub struct SensorLog<R> {
    pub(super) samples: Vec<Sample<R>>,
}

impl<R: Record> SensorLog<R> {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples.len()
    }
    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }
    /// The samples, oldest first.
    pub fn samples(&self) -> &[Sample<R>] {
        &self.samples
    }
    /// Iterates over the samples, oldest first.
    pub fn iter(&self) -> std::slice::Iter<'_, Sample<R>> {
        self.samples.iter()
    }
    /// The newest sample.
    pub fn last(&self) -> Option<&Sample<R>> {
        self.samples.last()
    }
    /// Writes the samples as CSV: a header `time [s],step,<columns>`, then one row per
    /// sample; numbers in Rust's shortest exact form, empty cells for missing values.
    pub fn write_csv(&self, w: impl Write) -> io::Result<()> {
        write_csv_table(w, &[("", self)], 1)
    }
}

impl<R> Default for SensorLog<R> {
    fn default() -> Self {
        SensorLog { samples: Vec::new() }
    }
}

/// A sensor log seen through its CSV columns, whatever its record type: what
/// [`write_csv_table`] joins.
pub trait CsvColumns {
    /// Column headers of the record.
    fn headers(&self) -> Vec<String>;
    /// The samples' times and step numbers.
    fn stamps(&self) -> Vec<(f64, u64)>;
    /// Number of samples.
    fn len(&self) -> usize {
        self.stamps().len()
    }
    /// Whether there is no sample.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Time and step number of sample `i`.
    fn stamp(&self, i: usize) -> (f64, u64) {
        self.stamps()[i]
    }
    /// The values of sample `i`, in column order.
    fn cells(&self, i: usize) -> Vec<Option<f64>>;
}

impl<R: Record> CsvColumns for SensorLog<R> {
    fn headers(&self) -> Vec<String> {
        match self.samples.first() {
            Some(s) => s.record.headers(),
            None => R::columns().into_iter().map(String::from).collect(),
        }
    }
    fn stamps(&self) -> Vec<(f64, u64)> {
        self.samples.iter().map(|s| (s.time, s.step)).collect()
    }
    fn len(&self) -> usize {
        self.samples.len()
    }
    fn stamp(&self, i: usize) -> (f64, u64) {
        (self.samples[i].time, self.samples[i].step)
    }
    fn cells(&self, i: usize) -> Vec<Option<f64>> {
        self.samples[i].record.values()
    }
}

/// Writes several sensors' logs as one CSV table: `time [s],step`, then each log's
/// columns prefixed with its name (`"gps: y [m]"`; no prefix for an empty name), one
/// row per sample (one in every `every`). The logs must hold the same samples (same times and steps: sensors added
/// together, sampled at the same points); otherwise nothing is written and the error
/// says which log differs.
///
/// ```
/// use ars_core::sensors::{Gps, Velometer, write_csv_table};
/// use ars_core::{Mass, Simulation};
///
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.1, [0.0, 10.0, 0.0], Mass::Total(1.0))?;
/// let (gps, vel) = (sim.add_sensor(Gps::new(ball))?, sim.add_sensor(Velometer::new(ball))?);
/// sim.step_n(4)?;
/// let mut csv = Vec::new();
/// write_csv_table(&mut csv, &[("gps", sim.records(gps)?), ("vel", sim.records(vel)?)], 2).unwrap();
/// let csv = String::from_utf8(csv).unwrap();
/// assert!(csv.starts_with("time [s],step,gps: x [m],gps: y [m],gps: z [m],vel: vx [m/s]"), "{csv}");
/// assert_eq!(csv.lines().count(), 1 + 2);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub fn write_csv_table(mut w: impl Write, logs: &[(&str, &dyn CsvColumns)], every: usize) -> io::Result<()> {
    let stamps = logs.first().map(|(_, log)| log.stamps()).unwrap_or_default();
    if let Some((name, _)) = logs.iter().find(|(_, log)| log.stamps() != stamps) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("the samples of {name:?} are not those of {:?}: a table needs the same samples", logs[0].0),
        ));
    }
    let mut header = vec!["time [s]".to_string(), "step".to_string()];
    for (name, log) in logs {
        header.extend(log.headers().into_iter().map(|c| if name.is_empty() { c } else { format!("{name}: {c}") }));
    }
    writeln!(w, "{}", header.join(","))?;
    for (i, (time, step)) in stamps.iter().enumerate().step_by(every.max(1)) {
        write!(w, "{time},{step}")?;
        for (_, log) in logs {
            for v in log.cells(i) {
                match v {
                    Some(x) => write!(w, ",{x}")?,
                    None => write!(w, ",")?,
                }
            }
        }
        writeln!(w)?;
    }
    Ok(())
}

impl<'a, R> IntoIterator for &'a SensorLog<R> {
    type Item = &'a Sample<R>;
    type IntoIter = std::slice::Iter<'a, Sample<R>>;
    fn into_iter(self) -> Self::IntoIter {
        self.samples.iter()
    }
}
