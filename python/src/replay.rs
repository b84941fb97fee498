//! Browser replays from Python: `sim.save_replay(path, duration)` and
//! `sim.replay(duration)` run the simulation and record it (see
//! [`ars_viewer::ReplayRecorder`]); the result is an `ars.Replay` (python/ars/display.py),
//! which a notebook shows inline.

use std::path::PathBuf;
use std::sync::{Mutex, PoisonError};

use ars_viewer::{ReplayRecorder, ViewerError};
use pyo3::prelude::*;

use crate::errors::{io_file_error, raise};
use crate::interrupt::{StoppableSimulation, python_signals_per_frame};
use crate::simulation::PySimulation;
use crate::viewer::{REPLAY_KEYWORDS, ViewKeywords, to_py_error};

/// What `save_replay` and `replay` take besides the view.
pub(crate) struct ReplayArgs {
    pub duration: f64,
    /// Past the limits of [`crate::limits`].
    pub allow_long: bool,
    pub fps: Option<f64>,
    pub plots: Vec<String>,
    pub view: ViewKeywords,
}

/// Runs `sim` for the duration, recording it; writes the page to `path` if given
/// (nothing is written, and no file left, when the settings are refused or the run
/// fails, or Ctrl-C stops it: `KeyboardInterrupt` after the frame being run). Returns
/// an `ars.Replay`.
pub(crate) fn record(
    py: Python<'_>,
    sim: &PySimulation,
    path: Option<PathBuf>,
    args: ReplayArgs,
) -> PyResult<Py<PyAny>> {
    let ReplayArgs { duration, allow_long, fps, plots, view } = args;
    let view = view.settings().map_err(|m| raise(py, "InputError", m))?;
    crate::limits::check_recording(duration, None, allow_long).map_err(|m| raise(py, "InputError", m))?;
    let mut recorder = ReplayRecorder::new();
    if let Some(fps) = fps {
        recorder = recorder.fps(fps);
    }
    for column in plots {
        recorder = recorder.plot(column);
    }
    let mut replay = None;
    let mut refused = None;
    let interrupt: Mutex<Option<PyErr>> = Mutex::new(None);
    let ran = sim.advance(py, |sim| {
        let mut driver = StoppableSimulation { sim, stop: python_signals_per_frame(&interrupt) };
        let recorded = match &path {
            Some(path) => recorder.record_driven_to(&mut driver, &view, duration, path),
            None => recorder.record_driven(&mut driver, &view, duration),
        };
        match recorded {
            Ok(r) => replay = Some(r),
            Err(ViewerError::Simulation(e)) => return Err(e),
            Err(other) => refused = Some(other),
        }
        Ok(())
    });
    if let Some(e) = interrupt.into_inner().unwrap_or_else(PoisonError::into_inner) {
        return Err(e);
    }
    ran?;
    if let Some(e) = refused {
        return Err(match e {
            ViewerError::Write { path, source } => {
                let path = path.display().to_string();
                io_file_error(py, &source, format!("cannot write the replay {path:?}: {source}"), &path)
            }
            other => to_py_error(py, other),
        });
    }
    let Some(replay) = replay else {
        return Err(raise(py, "InternalError", "the replay ended with neither a result nor an error".into()));
    };
    let (start, end) = replay.span();
    let class = py.import("ars.display")?.getattr("Replay")?;
    Ok(class.call1((replay.html(), path, replay.frames(), start, end))?.unbind())
}

/// `ars.Simulation`'s browser replays: `save_replay` and `replay`.
#[pymethods]
impl PySimulation {
    /// Runs for `duration` seconds of simulated time and writes a browser replay of
    /// it to `path` (`None`: kept in memory): one self-contained HTML file (no network
    /// needed) with every object's shape, colour and pose, `fps` samples a second
    /// (default: the frame rate), and plots of the sensor columns `plots` names
    /// (`"Gps 1: y"`: the sensor's type, its number from 1, its column). The camera
    /// starts as a `Renderer`'s with the same keywords. Returns an `ars.Replay`, which
    /// a notebook shows inline. Bad settings are refused before the run, and no file
    /// is left. More than an hour of simulated time needs `allow_long=True`. Ctrl-C
    /// stops it after the frame being run with `KeyboardInterrupt`, leaving no file;
    /// the simulation can be run on.
    #[pyo3(signature = (path, duration, *, fps=None, plots=Vec::new(), allow_long=false, **view))]
    fn save_replay(
        &self,
        py: Python<'_>,
        path: Option<std::path::PathBuf>,
        duration: f64,
        fps: Option<f64>,
        plots: Vec<String>,
        allow_long: bool,
        view: Option<&Bound<'_, pyo3::types::PyDict>>,
    ) -> PyResult<Py<PyAny>> {
        let view = ViewKeywords::from_kwargs("save_replay", view, &REPLAY_KEYWORDS)?;
        record(py, self, path, ReplayArgs { duration, allow_long, fps, plots, view })
    }

    /// As `save_replay` (the same keywords), kept in memory: an `ars.Replay` to show
    /// in a notebook (or save later).
    #[pyo3(signature = (duration, **options))]
    fn replay(
        slf: &Bound<'_, Self>,
        duration: f64,
        options: Option<&Bound<'_, pyo3::types::PyDict>>,
    ) -> PyResult<Py<PyAny>> {
        Ok(slf.call_method("save_replay", (None::<std::path::PathBuf>, duration), options)?.unbind())
    }
}
