//! Video files from Python: `sim.record_video(path, duration, fps=30, size=(w, h))`
//! runs a simulation off screen into an H.264 MP4 (frame k at k/fps simulated
//! seconds, `ars_viewer::VideoRecorder`), and `VideoWriter` takes frames one by one
//! (the original-style `Program.record_video`, whose frames run in Python).

use std::path::PathBuf;
use std::sync::Mutex;

use ars_viewer::{RecordedVideo, ThreadEnd, VideoRecorder, VideoWriter, ViewerError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{panic_message, raise};
use crate::simulation::PySimulation;
use crate::viewer::{Failure, IMAGE_KEYWORDS, PyRenderer, ViewKeywords, to_py_error};

/// What a finished video holds, as a dict.
fn summary(py: Python<'_>, video: &RecordedVideo) -> PyResult<Py<PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("path", video.path.display().to_string())?;
    dict.set_item("frames", video.frames)?;
    dict.set_item("fps", video.fps)?;
    dict.set_item("duration", video.duration)?;
    dict.set_item("size", video.size)?;
    dict.set_item("bytes", video.bytes)?;
    Ok(dict.unbind())
}

/// `sim.record_video(...)`: checks the settings, then runs the simulation with the GIL
/// released, drawing on a thread of its own (each thread has its own rendering
/// context, so this can be called again and again).
pub(crate) fn record_video(
    py: Python<'_>,
    sim: &PySimulation,
    path: PathBuf,
    duration: f64,
    fps: f64,
    view: ViewKeywords,
) -> PyResult<Py<PyDict>> {
    if sim.in_own_hook() {
        return Err(raise(py, "BusyError", "a hook cannot record the simulation it runs in".into()));
    }
    let options = view.options();
    let view = view.settings().map_err(|m| raise(py, "InputError", m))?;
    let checked = ars_viewer::check_video_settings(fps, view.size.0, view.size.1)
        .and_then(|()| ars_viewer::video_frame_count(duration, fps));
    checked.map_err(|e| to_py_error(py, e))?;
    let recorder = VideoRecorder::new(path).fps(fps).options(options);
    // The recorder's own error (or its thread's panic), kept whole (the step's error
    // type cannot carry it).
    let failure: Mutex<Option<Failure>> = Mutex::new(None);
    let recorded: Mutex<Option<RecordedVideo>> = Mutex::new(None);
    let ran = sim.advance(py, |sim| {
        let outcome = std::thread::scope(|scope| {
            let drawing = std::thread::Builder::new()
                .name("ars-video".into())
                .spawn_scoped(scope, || recorder.record_simulation(sim, &view, duration));
            match drawing.map(|t| t.join()) {
                Ok(Ok(outcome)) => outcome.map_err(Failure::Viewer),
                Ok(Err(panic)) => Err(Failure::Panic(panic_message(&panic))),
                Err(e) => Err(Failure::Viewer(ViewerError::ThreadDied {
                    thread: "the video",
                    end: ThreadEnd::NotStarted,
                    source: Some(e),
                })),
            }
        });
        match outcome {
            Ok(video) => {
                *failure_free(&recorded) = Some(video);
                Ok(())
            }
            Err(Failure::Viewer(ViewerError::Simulation(e))) => Err(e),
            Err(f) => {
                let message = match &f {
                    Failure::Viewer(e) => e.to_string(),
                    Failure::Panic(m) => format!("ARS panicked: {m}"),
                };
                *failure_free(&failure) = Some(f);
                Err(ars_core::Error::User(message))
            }
        }
    });
    if let Some(f) = failure_free(&failure).take() {
        return Err(f.into_py(py));
    }
    ran?;
    let video = failure_free(&recorded).take();
    match video {
        Some(video) => summary(py, &video),
        None => Err(raise(py, "InternalError", "the video was not recorded".into())),
    }
}

/// The value of a mutex nobody panicked with.
fn failure_free<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// An MP4 video written frame by frame: `VideoWriter(path, width, height, fps=30, *,
/// camera, look_at, background, follow, quality, axes)`; `add(sim)` draws the
/// simulation as it is now as the next frame, `finish()` writes the file and returns
/// what it holds. Until `finish`, nothing is at `path`; `close()` (or the writer's
/// end) abandons the video and leaves nothing behind.
#[pyclass(name = "VideoWriter", module = "ars", frozen)]
pub struct PyVideoWriter {
    renderer: PyRenderer,
    writer: Mutex<Option<VideoWriter>>,
}

#[pymethods]
impl PyVideoWriter {
    #[new]
    #[pyo3(signature = (path, width, height, fps=30.0, **view))]
    fn new(
        py: Python<'_>,
        path: PathBuf,
        width: i64,
        height: i64,
        fps: f64,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut view = ViewKeywords::from_kwargs("VideoWriter", view, &IMAGE_KEYWORDS)?;
        view.size = (width, height);
        let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
            return Err(raise(
                py,
                "InputError",
                format!("a video of {width}×{height} pixels: the sizes must be positive"),
            ));
        };
        ars_viewer::check_video_settings(fps, w, h).map_err(|e| to_py_error(py, e))?;
        let renderer = PyRenderer::start(py, view)?;
        let writer = VideoWriter::create(path, w, h, fps).map_err(|e| to_py_error(py, e))?;
        Ok(PyVideoWriter { renderer, writer: Mutex::new(Some(writer)) })
    }

    /// Draws the simulation as it is now as the video's next frame.
    fn add(&self, py: Python<'_>, sim: Py<PySimulation>) -> PyResult<()> {
        let image = self.renderer.draw(py, sim)?;
        let mut writer = failure_free(&self.writer);
        let Some(writer) = writer.as_mut() else {
            return Err(raise(py, "InputError", "the video is already finished or closed".into()));
        };
        writer.add_frame(image).map_err(|e| to_py_error(py, e))
    }

    /// Writes the video file; a dict of what it holds (path, frames, fps, duration,
    /// size, bytes).
    fn finish(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let Some(writer) = failure_free(&self.writer).take() else {
            return Err(raise(py, "InputError", "the video is already finished or closed".into()));
        };
        let video = py.detach(|| writer.finish()).map_err(|e| to_py_error(py, e))?;
        summary(py, &video)
    }

    /// Abandons the video: nothing is left at its path or beside it.
    fn close(&self, py: Python<'_>) {
        let writer = failure_free(&self.writer).take();
        py.detach(|| drop(writer));
    }
}

/// `ars.Simulation.record_video`.
#[pymethods]
impl PySimulation {
    /// Runs `duration` seconds of simulated time off screen into an H.264 MP4 video at
    /// `path`: frame k is the picture at the first step at or after k/fps s (see
    /// `ars._native.VideoWriter` for frames one by one). A dict of what it holds.
    /// The viewer keywords as `ars.Renderer` takes them; `size` defaults to the
    /// window's 1024 × 768 (both sides must be even).
    #[pyo3(signature = (path, duration, fps=30.0, size=None, **view))]
    fn record_video(
        &self,
        py: Python<'_>,
        path: std::path::PathBuf,
        duration: f64,
        fps: f64,
        size: Option<(i64, i64)>,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Py<pyo3::types::PyDict>> {
        let mut view = ViewKeywords::from_kwargs("record_video", view, &IMAGE_KEYWORDS)?;
        view.size = size.unwrap_or(view.size);
        record_video(py, self, path, duration, fps, view)
    }
}
