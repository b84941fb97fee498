//! The viewer from Python: a window on a simulation (or on a program in the original's
//! style, which steps its own frames), and off-screen images.
//!
//! The window runs on the calling thread (the main thread: the windowing system wants
//! it there) with the GIL released; it takes the GIL back only to call the program's
//! Python code. Off-screen images are drawn by a thread each [`PyRenderer`] owns: the
//! 3D engine keeps one rendering context per thread, so a renderer of its own thread
//! can be made again and again in one interpreter.

use std::ops::DerefMut;
use std::sync::{Mutex, mpsc};

use ars_core::nalgebra::Point3;
use ars_core::{Error, Key, RenderQuality, Simulation, WindowSettings};
use ars_viewer::{Driver, OffscreenRenderer, ViewerError, image};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Checked, io_file_error, panic_message, raise, to_py};
use crate::simulation::{Int, PySimulation};

/// The Python exception for a viewer error: a bad setting is an `ars.InputError`, no
/// display an `ars.NoDisplayError`, a renderer, encoder or frame-writer thread that
/// died, the H.264 encoder failing or a second rendering context on a thread an
/// `ars.RendererError`, a file that cannot be written an `ars.FileError` (with `errno`
/// and `filename`), no graphics adapter an `ars.ArsError`; the simulation's own errors
/// as everywhere ([`to_py`]).
pub(crate) fn to_py_error(py: Python<'_>, error: ViewerError) -> PyErr {
    let message = error.to_string();
    match error {
        ViewerError::Simulation(e) => to_py(py, e),
        ViewerError::InvalidSetting(_) => raise(py, "InputError", message),
        ViewerError::NoDisplay { .. } => raise(py, "NoDisplayError", message),
        ViewerError::ThreadDied { .. } | ViewerError::Encoder(_) | ViewerError::SecondContext => {
            raise(py, "RendererError", message)
        }
        ViewerError::Write { path, source } => io_file_error(py, &source, message, &path.display().to_string()),
        _ => raise(py, "ArsError", message),
    }
}

/// The viewer's keywords, as every Python entry point takes them (`show`,
/// `show_program`, `Renderer`, `record_video`, `save_replay`): one definition, one
/// default each. The size's default is Rust's [`WindowSettings`] default (the
/// original's window, 1024 × 768), the camera's too.
pub(crate) struct ViewKeywords {
    pub title: String,
    /// Width and height in pixels, as given (checked by `settings`).
    pub size: (i64, i64),
    pub camera: [f64; 3],
    pub look_at: [f64; 3],
    pub background: [f64; 3],
    pub follow: Option<String>,
    pub quality: String,
    /// Draw the world axes (the window's `x` key toggles them).
    pub axes: bool,
}

impl Default for ViewKeywords {
    fn default() -> Self {
        let rust = WindowSettings::default();
        ViewKeywords {
            // The Python package's windows have always been called "ARS".
            title: "ARS".into(),
            size: (i64::from(rust.size.0), i64::from(rust.size.1)),
            camera: rust.camera_position.coords.into(),
            look_at: rust.camera_target.coords.into(),
            background: rust.background.map(f64::from),
            follow: None,
            quality: "auto".into(),
            axes: false,
        }
    }
}

/// Every viewer keyword's name.
pub(crate) const VIEW_KEYWORDS: [&str; 8] =
    ["title", "size", "camera", "look_at", "background", "follow", "quality", "axes"];

/// The viewer keywords a replay takes: it has no followed body, axes or quality.
pub(crate) const REPLAY_KEYWORDS: [&str; 5] = ["title", "size", "camera", "look_at", "background"];

/// The viewer keywords an off-screen renderer and a video take: their size is a
/// parameter of their own (`width` and `height`, `size`), and an image has no title.
pub(crate) const IMAGE_KEYWORDS: [&str; 6] = ["camera", "look_at", "background", "follow", "quality", "axes"];

impl ViewKeywords {
    /// The keywords `function` was given in `given` (its `**view`), each of them one
    /// of `accepted`; the others take their defaults. A keyword not accepted is a
    /// `TypeError` as Python says it, a value of the wrong type a `TypeError` naming
    /// the keyword.
    pub(crate) fn from_kwargs(function: &str, given: Option<&Bound<'_, PyDict>>, accepted: &[&str]) -> PyResult<Self> {
        let mut keywords = ViewKeywords::default();
        let Some(given) = given else { return Ok(keywords) };
        for (key, value) in given.iter() {
            let name: String = key.extract()?;
            if !accepted.contains(&name.as_str()) {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "{function}() got an unexpected keyword argument '{name}'"
                )));
            }
            keywords.set(&name, &value).map_err(|e| {
                // A sequence of the wrong length or an integer out of range is a wrong
                // value (`ars.InputError`), anything else a wrong type.
                let py = value.py();
                match crate::errors::as_input_error(py, &value, e) {
                    e if e.is_instance_of::<pyo3::exceptions::PyTypeError>(py) => {
                        pyo3::exceptions::PyTypeError::new_err(format!("{function}() argument '{name}': {e}"))
                    }
                    e => raise(py, "InputError", format!("{function}() argument '{name}': {e}")),
                }
            })?;
        }
        Ok(keywords)
    }

    /// Sets the keyword `name` (one of [`VIEW_KEYWORDS`]) to `value`.
    fn set(&mut self, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        match name {
            "title" => self.title = value.extract()?,
            "size" => self.size = value.extract()?,
            "camera" => self.camera = value.extract()?,
            "look_at" => self.look_at = value.extract()?,
            "background" => self.background = value.extract()?,
            "follow" => self.follow = value.extract()?,
            "quality" => self.quality = value.extract()?,
            "axes" => self.axes = value.extract()?,
            other => unreachable!("{other} is not a viewer keyword"),
        }
        Ok(())
    }

    /// The viewer's options these keywords ask for.
    pub(crate) fn options(&self) -> ars_viewer::ViewerOptions {
        ars_viewer::ViewerOptions::default().with_axes(self.axes)
    }

    pub(crate) fn settings(self) -> Result<WindowSettings, String> {
        let (w, h) = self.size;
        if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
            return Err(format!("the image size {w}×{h} must be between 1 and 8192 pixels each way"));
        }
        let camera = Point3::from(self.camera);
        let look_at = Point3::from(self.look_at);
        if camera.iter().chain(look_at.iter()).any(|c| !c.is_finite()) {
            return Err(format!("the camera {:?} and what it looks at {:?} must be finite", self.camera, self.look_at));
        }
        if (camera - look_at).norm() == 0.0 {
            return Err(format!("the camera {:?} cannot look at the point it is at", self.camera));
        }
        if self.background.iter().any(|c| !(0.0..=1.0).contains(c)) {
            return Err(format!("the background colour {:?} must be RGB in [0, 1]", self.background));
        }
        let quality = match self.quality.as_str() {
            "auto" => RenderQuality::Auto,
            "fast" => RenderQuality::Fast,
            "fine" => RenderQuality::Fine,
            other => return Err(format!("quality {other:?}: use \"auto\", \"fast\" or \"fine\"")),
        };
        Ok(WindowSettings {
            title: self.title,
            // Checked above: 1 to 8192 each.
            size: (w as u32, h as u32),
            camera_position: camera,
            camera_target: look_at,
            background: self.background.map(|c| c as f32),
            quality,
            follow: self.follow,
        })
    }
}

/// Drives the window from Python: a bare simulation steps its frames itself; a program
/// (an object with `native()`, `frame()`, `step()`, `reset()` and `key(name, down)`)
/// runs its own Python frames. A true result of `key` closes the window.
struct PythonDriver {
    sim: Py<PySimulation>,
    program: Option<Py<PyAny>>,
    /// The exception a Python call raised, to re-raise unchanged.
    raised: Option<PyErr>,
    /// Whether the program asked for the window to close.
    closing: bool,
    /// How many more frames to run before the window closes, if `show` was given a
    /// number of frames.
    frames_left: Option<u64>,
}

impl PythonDriver {
    /// Keeps a Python exception and stops the window with an error naming it.
    fn keep(&mut self, e: PyErr) -> Error {
        let message = format!("a Python call from the viewer raised {e}");
        self.raised = Some(e);
        Error::User(message)
    }

    /// Calls a method of the program (and takes its simulation anew, which a reset
    /// replaces); a true result asks for the window to close.
    fn call_program(&mut self, method: &str, key: Option<(Key, bool)>) -> ars_core::Result<()> {
        let Some(program) = &self.program else { return Ok(()) };
        let outcome = Python::attach(|py| -> PyResult<(Py<PySimulation>, bool)> {
            let result = match key {
                Some((key, down)) => program.bind(py).call_method1(method, (key.to_string(), down))?,
                None => program.bind(py).call_method0(method)?,
            };
            let sim = program.bind(py).call_method0("native")?.cast_into::<PySimulation>()?.unbind();
            Ok((sim, result.is_truthy()?))
        });
        match outcome {
            Ok((sim, close)) => {
                self.sim = sim;
                self.closing |= close;
                Ok(())
            }
            Err(e) => Err(self.keep(e)),
        }
    }

    /// Steps the bare simulation.
    fn advance(&mut self, f: impl FnOnce(&mut Simulation) -> ars_core::Result<()> + Send) -> ars_core::Result<()> {
        let outcome = Python::attach(|py| self.sim.get().advance(py, f));
        outcome.map_err(|e| self.keep(e))
    }
}

impl Driver for PythonDriver {
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_ {
        self.sim.get().locked()
    }
    fn step_frame(&mut self) -> ars_core::Result<()> {
        match &mut self.frames_left {
            Some(0) => return Ok(()),
            Some(left) => *left -= 1,
            None => {}
        }
        if self.program.is_some() { self.call_program("frame", None) } else { self.advance(|sim| sim.step_frame()) }
    }
    fn step(&mut self) -> ars_core::Result<()> {
        if self.program.is_some() { self.call_program("step", None) } else { self.advance(|sim| sim.step()) }
    }
    fn reset(&mut self) -> ars_core::Result<()> {
        if self.program.is_some() {
            self.call_program("reset", None)
        } else {
            eprintln!("ars: a bare simulation cannot be rebuilt (write a Program to have the r key rebuild it)");
            Ok(())
        }
    }
    fn key_down(&mut self, key: Key) -> ars_core::Result<()> {
        self.call_program("key", Some((key, true)))
    }
    fn key_up(&mut self, key: Key) -> ars_core::Result<()> {
        self.call_program("key", Some((key, false)))
    }
    /// Also Ctrl-C: Python's signal handlers run once a drawn frame (the window is on
    /// the main thread, which sees them); the exception one raises closes the window
    /// and comes out of `show`.
    fn wants_to_close(&mut self) -> bool {
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            self.raised.get_or_insert(e);
            return true;
        }
        self.closing || self.frames_left == Some(0)
    }
}

/// Opens a window on `sim` (driven by `program` if given) until it is closed,
/// `duration` wall seconds have passed or the simulation has run `frames` frames (the
/// last one drawn); returns what the run measured.
pub(crate) fn show(
    py: Python<'_>,
    sim: Py<PySimulation>,
    program: Option<Py<PyAny>>,
    duration: Option<f64>,
    frames: Option<Int>,
    view: ViewKeywords,
) -> PyResult<Py<PyDict>> {
    if sim.get().in_own_hook() {
        return Err(raise(py, "BusyError", "a hook cannot show the simulation it runs in".into()));
    }
    let threading = py.import("threading")?;
    if !threading.call_method0("current_thread")?.is(&threading.call_method0("main_thread")?) {
        return Err(raise(
            py,
            "InputError",
            "a window opens on the main thread only (the windowing system's rule); from other threads, draw off \
             screen with ars.Renderer"
                .into(),
        ));
    }
    let limit = match duration {
        None => None,
        Some(d) if d.is_finite() && d > 0.0 => Some(std::time::Duration::from_secs_f64(d)),
        Some(d) => return Err(raise(py, "InputError", format!("the window's duration {d} s must be positive"))),
    };
    let frames_left = match frames {
        None => None,
        Some(Checked(n)) => Some(
            u64::try_from(n)
                .map_err(|_| raise(py, "InputError", format!("the window's number of frames {n} must be 0 or more")))?,
        ),
    };
    let options = view.options();
    let view = view.settings().map_err(|m| raise(py, "InputError", m))?;
    let mut driver = PythonDriver { sim, program, raised: None, closing: false, frames_left };
    let outcome = py.detach(|| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            // Window after window on this thread: its rendering context is kept (and
            // given back when the interpreter exits: `release_viewer`).
            ars_viewer::keep_rendering_context();
            ars_viewer::run_window_with(&mut driver, &view, &options, limit)
        }))
    });
    if let Some(e) = driver.raised.take() {
        return Err(e);
    }
    let report = match outcome {
        Ok(Ok(report)) => report,
        Ok(Err(e)) => return Err(to_py_error(py, e)),
        Err(panic) => return Err(raise(py, "InternalError", format!("ARS panicked: {}", panic_message(&panic)))),
    };
    let dict = PyDict::new(py);
    // "frames_drawn": `show(frames=N)` counts simulation frames, this counts images.
    dict.set_item("frames_drawn", report.frames)?;
    dict.set_item("wall_seconds", report.wall_seconds)?;
    dict.set_item("simulated_seconds", report.simulated_seconds)?;
    dict.set_item("frames_per_second", report.frames_per_second())?;
    dict.set_item("real_time_factor", report.real_time_factor())?;
    Ok(dict.unbind())
}

/// Opens a window on a program in the original's style: `program` has `native()`
/// (its `ars.Simulation` now), `frame()`, `step()`, `reset()` and `key(name, down)`.
#[pyfunction]
#[pyo3(signature = (program, *, duration=None, frames=None, **view))]
pub(crate) fn show_program(
    py: Python<'_>,
    program: Py<PyAny>,
    duration: Option<f64>,
    frames: Option<Int>,
    view: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyDict>> {
    let view = ViewKeywords::from_kwargs("show_program", view, &VIEW_KEYWORDS)?;
    let sim = program.bind(py).call_method0("native")?.cast_into::<PySimulation>()?.unbind();
    show(py, sim, Some(program), duration, frames, view)
}

/// Gives back the rendering context the windows of this thread kept, and waits for
/// the recordings abandoned by Ctrl-C while their renderer started: the package calls
/// it when the interpreter exits, before the thread's locals are destroyed.
#[pyfunction]
#[pyo3(name = "_release_viewer")]
pub(crate) fn release_viewer(py: Python<'_>) -> PyResult<()> {
    py.detach(crate::interrupt::join_abandoned);
    crate::errors::guarded(py, || {
        ars_viewer::release_rendering_context();
        Ok(())
    })
}

/// Whether Mesa's Vulkan device-selection layer would print about `XDG_RUNTIME_DIR`
/// here (`ars_viewer::device_select_would_print`): the package then sets
/// `NODEVICE_SELECT=1` at import.
#[pyfunction]
#[pyo3(name = "_device_select_would_print")]
pub(crate) fn device_select_would_print() -> bool {
    ars_viewer::device_select_would_print()
}

/// Whether a display is reachable (`DISPLAY` or `WAYLAND_DISPLAY` is set).
#[pyfunction]
pub(crate) fn has_display() -> bool {
    ars_viewer::has_display()
}

/// What the renderer's thread is asked: draw this simulation.
struct Request {
    sim: Py<PySimulation>,
    reply: mpsc::SyncSender<Result<image::RgbImage, Failure>>,
}

/// Why an image (or a video) was not made.
pub(crate) enum Failure {
    Viewer(ViewerError),
    Panic(String),
}

impl Failure {
    /// Its Python exception: a panic is an `ars.InternalError`.
    pub(crate) fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            Failure::Viewer(e) => to_py_error(py, e),
            Failure::Panic(m) => raise(py, "InternalError", format!("ARS panicked: {m}")),
        }
    }
}

fn caught<T>(f: impl FnOnce() -> Result<T, ViewerError>) -> Result<T, Failure> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => r.map_err(Failure::Viewer),
        Err(panic) => Err(Failure::Panic(panic_message(&panic))),
    }
}

/// The renderer's thread: makes the renderer, then draws what it is asked until the
/// renderer is dropped.
fn serve(
    view: WindowSettings,
    options: ars_viewer::ViewerOptions,
    ready: mpsc::SyncSender<Result<(), Failure>>,
    requests: mpsc::Receiver<Request>,
) {
    let mut renderer = match caught(|| OffscreenRenderer::with_options(&view, &options)) {
        Ok(r) => r,
        Err(e) => {
            let _ = ready.send(Err(e));
            return;
        }
    };
    if ready.send(Ok(())).is_err() {
        return;
    }
    // The simulation drawn last, kept alive so that its address means it alone.
    let mut last: Option<Py<PySimulation>> = None;
    for Request { sim, reply } in requests {
        if last.as_ref().is_none_or(|l| l.as_ptr() != sim.as_ptr()) {
            renderer.reset();
        }
        let image = caught(|| renderer.render(&sim.get().locked()));
        last = Some(sim);
        let _ = reply.send(image);
    }
}

/// Draws simulations into images, off screen (no display and no GPU needed: Mesa's
/// software rasteriser). Each renderer draws on a thread of its own.
///
/// `Renderer(width=640, height=480, *, camera=(10, 8, 10), look_at=(0, 0, 0),
/// background=(1, 1, 1), follow=None, quality="auto")`; `render(sim)` returns the image
/// as a numpy array of shape (height, width, 3), `uint8`; `save(sim, path)` writes a PNG.
#[pyclass(name = "Renderer", module = "ars", frozen)]
pub struct PyRenderer {
    requests: Mutex<mpsc::Sender<Request>>,
    /// The drawing thread, joined when the renderer goes.
    thread: Option<std::thread::JoinHandle<()>>,
    size: (u32, u32),
}

impl Drop for PyRenderer {
    /// Ends the drawing thread and waits for it: its rendering context (Mesa's threads
    /// with it) is gone before the renderer is. A thread still tearing down while the
    /// interpreter exits raced the process's own teardown of Mesa's libraries (a double
    /// free about once in 25 runs of a script whose renderer was collected at exit).
    fn drop(&mut self) {
        // The thread's loop ends with its channel: replace the sender by one of a
        // channel of its own.
        *self.requests.get_mut().unwrap_or_else(std::sync::PoisonError::into_inner) = mpsc::channel().0;
        if let Some(thread) = self.thread.take() {
            // The thread needs no GIL to end (a simulation it still holds is released
            // through PyO3's pending decrements).
            let _ = thread.join();
        }
    }
}

#[pymethods]
impl PyRenderer {
    /// An off-screen renderer of `width × height` images (by default the window's
    /// 1024 × 768), seen as the viewer keywords say (`camera`, `look_at`,
    /// `background`, `follow`, `quality`, `axes`).
    #[new]
    #[pyo3(signature = (width=None, height=None, **view))]
    pub(crate) fn new(
        py: Python<'_>,
        width: Option<Int>,
        height: Option<Int>,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut args = ViewKeywords::from_kwargs("Renderer", view, &IMAGE_KEYWORDS)?;
        args.size = (width.map_or(args.size.0, |w| w.0), height.map_or(args.size.1, |h| h.0));
        Self::start(py, args)
    }

    /// The image size, (width, height).
    #[getter]
    fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The simulation as it is now, as a numpy array of shape (height, width, 3),
    /// `uint8`: an `ars.Image`, which a notebook shows as a picture.
    fn render<'py>(&self, py: Python<'py>, sim: Py<PySimulation>) -> PyResult<Bound<'py, PyAny>> {
        let image = self.draw(py, sim)?;
        let (w, h) = image.dimensions();
        let array = PyArray1::from_vec(py, image.into_raw()).reshape([h as usize, w as usize, 3])?;
        // An `ars.Image`: a numpy array that a notebook shows as a picture.
        let image_class = py.import("ars.display")?.getattr("Image")?;
        array.call_method1("view", (image_class,))
    }

    /// Writes the simulation as it is now to a PNG file.
    fn save(&self, py: Python<'_>, sim: Py<PySimulation>, path: std::path::PathBuf) -> PyResult<()> {
        let image = self.draw(py, sim)?;
        image.save(&path).map_err(|e| match e {
            image::ImageError::IoError(io) => to_py(py, Error::io("write the PNG file", &path, &io)),
            other => {
                raise(py, "ArsError", format!("cannot write the PNG file {:?}: {other}", path.display().to_string()))
            }
        })
    }

    fn __repr__(&self) -> String {
        format!("<ars.Renderer {}×{}>", self.size.0, self.size.1)
    }
}

impl PyRenderer {
    /// Starts the renderer's thread, drawing as `args` say.
    pub(crate) fn start(py: Python<'_>, args: ViewKeywords) -> PyResult<Self> {
        let options = args.options();
        let view = args.settings().map_err(|m| raise(py, "InputError", m))?;
        let size = view.size;
        let (ready_tx, ready_rx) = mpsc::sync_channel(1);
        let (requests, requests_rx) = mpsc::channel();
        let thread = std::thread::Builder::new()
            .name("ars-renderer".into())
            .spawn(move || serve(view, options, ready_tx, requests_rx))
            .map_err(|e| raise(py, "RendererError", format!("could not start the renderer's thread: {e}")))?;
        let ready = py.detach(move || ready_rx.recv());
        match ready {
            Ok(Ok(())) => Ok(PyRenderer { requests: Mutex::new(requests), thread: Some(thread), size }),
            Ok(Err(failure)) => Err(failure.into_py(py)),
            Err(_) => Err(raise(py, "RendererError", "the renderer's thread ended before it was ready".into())),
        }
    }

    pub(crate) fn draw(&self, py: Python<'_>, sim: Py<PySimulation>) -> PyResult<image::RgbImage> {
        if sim.get().in_own_hook() {
            return Err(raise(
                py,
                "BusyError",
                "a hook cannot render the simulation it runs in: render between steps".into(),
            ));
        }
        let (reply, answer) = mpsc::sync_channel(1);
        let sent = self.requests.lock().unwrap_or_else(std::sync::PoisonError::into_inner).send(Request { sim, reply });
        if sent.is_err() {
            return Err(raise(py, "RendererError", "the renderer's thread has ended".into()));
        }
        match py.detach(move || answer.recv()) {
            Ok(Ok(image)) => Ok(image),
            Ok(Err(failure)) => Err(failure.into_py(py)),
            Err(_) => Err(raise(py, "RendererError", "the renderer's thread ended while drawing".into())),
        }
    }
}

/// `ars.Simulation.show`: the window.
#[pymethods]
impl PySimulation {
    /// Opens a window on the simulation and runs it in real time until the window is
    /// closed (or for `duration` wall seconds, or until it has run `frames` frames, the
    /// last one drawn): mouse to turn the camera, space to pause, `g` for the panel
    /// (speed, plots of the sensors, joints), escape to quit.
    /// Needs a display; returns what the run measured (frames, seconds, real-time
    /// factor). Off screen, use `ars.Renderer`. The viewer keywords: `title`, `size`
    /// (default 1024 × 768), `camera`, `look_at`, `background`, `follow`, `quality`
    /// and `axes`, as `ars.Renderer` takes them.
    #[pyo3(signature = (duration=None, *, frames=None, **view))]
    fn show(
        slf: &Bound<'_, Self>,
        duration: Option<f64>,
        frames: Option<Int>,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Py<pyo3::types::PyDict>> {
        let view = ViewKeywords::from_kwargs("show", view, &VIEW_KEYWORDS)?;
        show(slf.py(), slf.clone().unbind(), None, duration, frames, view)
    }
}
