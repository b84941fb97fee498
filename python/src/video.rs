//! Video files from Python: `sim.record_video(path, duration, fps=30, size=(w, h))`
//! runs a simulation off screen into an H.264 MP4 (frame k at k/fps simulated
//! seconds, `ars_viewer::VideoRecorder`), and `VideoWriter` takes frames one by one
//! (the original-style `Program.record_video`, whose frames run in Python).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use ars_core::WindowSettings;

use ars_viewer::{OffscreenRenderer, RecordedVideo, ThreadEnd, VideoRecorder, VideoWriter, ViewerError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Checked, panic_message, raise};
use crate::interrupt::{StoppableSimulation, starting_on_thread_watching_signals};
use crate::simulation::{Int, PySimulation};
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

/// `sim.record_video(...)`: checks the settings, then, with the GIL released, starts a
/// renderer on a thread of its own (each thread has its own rendering context, so
/// this can be called again and again) and runs the simulation there, while the
/// calling thread looks for Ctrl-C: `KeyboardInterrupt` at once while the renderer
/// starts (the simulation not yet taken, nothing written), after the frame being
/// drawn once it records; no file left either way.
pub(crate) fn record_video(
    py: Python<'_>,
    slf: &Bound<'_, PySimulation>,
    path: PathBuf,
    duration: f64,
    fps: f64,
    view: ViewKeywords,
    allow_long: bool,
) -> PyResult<Py<PyDict>> {
    let sim = slf.get();
    if sim.in_own_hook() {
        return Err(raise(py, "BusyError", "a hook cannot record the simulation it runs in".into()));
    }
    check_video_path(&path).map_err(|m| raise(py, "InputError", m))?;
    let options = view.options();
    let view = view.settings().map_err(|m| raise(py, "InputError", m))?;
    let checked = ars_viewer::check_video_settings(fps, view.size.0, view.size.1)
        .and_then(|()| ars_viewer::video_frame_count(duration, fps));
    let frames = checked.map_err(|e| to_py_error(py, e))?;
    crate::limits::check_recording(duration, Some(frames), allow_long).map_err(|m| raise(py, "InputError", m))?;
    let stop = Arc::new(AtomicBool::new(false));
    let interrupt: Mutex<Option<PyErr>> = Mutex::new(None);
    // The renderer starts first, on the recording's thread, before the simulation is
    // taken: Ctrl-C while it starts returns at once, and nothing was written.
    let recorder = VideoRecorder::new(path).fps(fps).options(options);
    let start = {
        let (recorder, view) = (recorder.clone(), view.clone());
        move || recorder.start_renderer(&view).map(|renderer| (recorder, view, renderer))
    };
    let owner = slf.clone().unbind();
    let watched = Arc::clone(&stop);
    let run = move |started: ars_viewer::Result<(VideoRecorder, WindowSettings, OffscreenRenderer)>| {
        let (recorder, view, renderer) = started?;
        let mut locked = owner.get().locked();
        let mut driver = StoppableSimulation { sim: &mut locked, stop: || watched.load(Ordering::Relaxed) };
        recorder.record_driven_with(renderer, &mut driver, &view, duration)
    };
    let outcome = py.detach(|| starting_on_thread_watching_signals("ars-video", &stop, &interrupt, start, run));
    // Ctrl-C first, then a Python hook's own exception, then the recorder's error.
    if let Some(e) = failure_free(&interrupt).take() {
        sim.take_hook_exception();
        return Err(e);
    }
    if let Some(e) = sim.take_hook_exception() {
        return Err(e);
    }
    let outcome = match outcome {
        Ok(Some(Ok(outcome))) => outcome.map_err(Failure::Viewer),
        Ok(Some(Err(panic))) => Err(Failure::Panic(panic_message(&panic))),
        // Abandoned while starting: only Ctrl-C does that, and it was raised above.
        Ok(None) => Err(Failure::Panic("the video was abandoned with no Ctrl-C".into())),
        Err(e) => Err(Failure::Viewer(ViewerError::ThreadDied {
            thread: "the video",
            end: ThreadEnd::NotStarted,
            source: Some(e),
        })),
    };
    match outcome {
        Ok(video) => summary(py, &video),
        Err(f) => Err(f.into_py(py)),
    }
}

/// Refuses a path whose suffix says another format than the MP4 written.
fn check_video_path(path: &std::path::Path) -> Result<(), String> {
    let suffix = path.extension().map(|s| s.to_string_lossy().to_ascii_lowercase());
    match suffix.as_deref() {
        Some("mp4" | "m4v") => Ok(()),
        _ => Err(format!(
            "a video is written as H.264 in MP4: give its path the suffix .mp4 (or .m4v), got {:?}",
            path.display().to_string()
        )),
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
        width: Int,
        height: Int,
        fps: f64,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut view = ViewKeywords::from_kwargs("VideoWriter", view, &IMAGE_KEYWORDS)?;
        let (width, height) = (width.0, height.0);
        view.size = (width, height);
        let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
            return Err(raise(
                py,
                "InputError",
                format!("a video of {width}×{height} pixels: the sizes must be positive"),
            ));
        };
        ars_viewer::check_video_settings(fps, w, h).map_err(|e| to_py_error(py, e))?;
        check_video_path(&path).map_err(|m| raise(py, "InputError", m))?;
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
    /// window's 1024 × 768 (both sides must be even). The path ends in `.mp4` (or
    /// `.m4v`); more than an hour of simulated time or 108,000 frames needs
    /// `allow_long=True`. Ctrl-C stops it after the frame being drawn with
    /// `KeyboardInterrupt`, leaving no file; the simulation can be run on.
    #[pyo3(signature = (path, duration, fps=30.0, size=None, *, allow_long=false, **view))]
    fn record_video(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        path: std::path::PathBuf,
        duration: f64,
        fps: f64,
        size: Option<Checked<(i64, i64)>>,
        allow_long: bool,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Py<pyo3::types::PyDict>> {
        let mut view = ViewKeywords::from_kwargs("record_video", view, &IMAGE_KEYWORDS)?;
        view.size = size.map_or(view.size, |s| s.0);
        record_video(py, slf, path, duration, fps, view, allow_long)
    }
}
