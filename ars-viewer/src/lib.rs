//! # ars-viewer
//!
//! The ARS 3D viewer, on kiss3d: a window on screen that runs a program in real time
//! (orbit camera with the mouse, the program's keys, pause, single step, reset, a text
//! overlay with the simulated time and the real-time factor), and off-screen rendering
//! with no display and no GPU (Mesa's software rasterisers) for screenshot recording,
//! and browser replays: one self-contained HTML file to play a run back in
//! ([`ReplayRecorder`]).
//!
//! ```no_run
//! use ars_core::{Hooks, Mass, Program, Result, Simulation};
//! use ars_viewer::ProgramViewer;
//!
//! struct HelloWorld;
//! impl Hooks for HelloWorld {}
//! impl Program for HelloWorld {
//!     fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
//!         sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).map(drop)
//!     }
//! }
//! // A window where there is a display; off-screen frames into a folder otherwise.
//! HelloWorld.start().unwrap();
//! ```
//!
//! Y is up, as in the simulation. kiss3d works in glam `f32`; the conversion from the
//! simulation's nalgebra `f64` lives in [`convert`]. Off screen, the product
//! description asked for OSMesa: wgpu has no OSMesa backend and Mesa removed OSMesa in
//! 25.1, so the off-screen path is Mesa's surfaceless EGL (llvmpipe) or lavapipe
//! Vulkan, through wgpu. On Debian: `apt-get install libvulkan1 mesa-vulkan-drivers
//! libegl1 libegl-mesa0 libgl1-mesa-dri` (and `xvfb` for a virtual display).
//!
//! Features (both on by default): `window`, the interactive window with its egui
//! panel, and `video`, the MP4 encoder (OpenH264). A build without them has the same
//! API; the calls that need a missing part return [`ViewerError::NotBuilt`].

// Without the window, its helpers in the shared modules (the scene's follow toggle,
// the layout's panel arithmetic, the driver's shown simulation...) have no caller.
#![cfg_attr(not(feature = "window"), allow(dead_code))]

mod camera;
#[cfg(feature = "window")]
mod command;
pub mod convert;
mod driver;
mod edit;
mod error;
#[cfg(feature = "window")]
mod focus;
mod frames;
#[cfg(feature = "window")]
mod gui;
mod h264;
#[cfg(feature = "window")]
mod hand;
mod interact;
mod layout;
mod look;
mod material;
mod mp4;
mod offscreen;
mod recorder;
mod replay;
mod scene;
mod screenshots;
#[cfg(feature = "window")]
mod session;
#[cfg(not(feature = "window"))]
#[path = "without_window.rs"]
mod session;
mod state;
mod video;
mod viewports;
mod window;
#[cfg(feature = "window")]
mod window_views;

use std::path::PathBuf;
use std::time::Duration;

use ars_core::{Program, WindowSettings};

pub use camera::{Camera, CameraFrame, Intrinsics};
pub use driver::Driver;
pub use edit::{Edit, apply_edit, parse_number};
pub use error::{Result, ThreadEnd, ViewerError};
pub use frames::FrameWriter;
pub use image;
pub use interact::{DragMode, Grab, SPRING_STIFFNESS, pick, ray_plane, spring_force, spring_torque};
pub use offscreen::{OffscreenRenderer, init_offscreen_context, keep_rendering_context, release_rendering_context};
pub use recorder::{Recorder, RecordingOutput};
pub use replay::{Replay, ReplayInProgress, ReplayRecorder};
pub use scene::{DEFAULT_FORCE_SCALE, SceneMirror, force_arrow, joint_force_arrow};
pub use screenshots::{ScreenshotFrames, ScreenshotRecorder};
pub use state::{DragLine, Selected, ViewerState};
pub use video::{
    MAX_VIDEO_FPS, MAX_VIDEO_SIDE, RecordedVideo, VideoFile, VideoRecorder, VideoWriter, check_video_settings,
    video_frame_count,
};
pub use viewports::{VIEWPORT_KINDS, ViewportKind, viewports};
pub use window::{VIEWER_KEYS, WindowReport, device_select_would_print};

/// What the viewer draws besides the simulation, where the program's
/// [`WindowSettings`] do not say: for [`ProgramViewer::show_with`], [`run_window_with`],
/// [`OffscreenRenderer::with_options`] and [`ScreenshotRecorder::options`].
///
/// ```
/// let options = ars_viewer::ViewerOptions::default().with_axes(true);
/// assert!(options.axes);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ViewerOptions {
    /// Draw the world axes at the origin, 1 m long: X red, Y green, Z blue. Off by
    /// default; the window's `x` key (and the panel's Axes button) toggles them.
    pub axes: bool,
    /// Draw the contact forces (cyan) and the joints' reaction forces on their first
    /// body (amber, from the anchor) as arrows ([`DEFAULT_FORCE_SCALE`] metres per
    /// newton). Off by default; the panel's Forces button toggles them. They are the
    /// forces ODE reports: the window and the recorder turn the world's contact feedback
    /// ([`World::set_contact_feedback`](ars_core::World::set_contact_feedback)) and every
    /// joint's on; with an [`OffscreenRenderer`] of your own, turn them on in the
    /// simulation you render.
    pub forces: bool,
    /// How many views, 1 to 4 (0 is taken as 1): with more than one, the image is split
    /// into quarters showing, in reading order, the free camera, a camera following a
    /// body, the top view (orthographic) and what the scene's first depth camera sees
    /// (see [`ViewportKind`]). A window starts with these views (keys `1`–`4` change them);
    /// off screen, every frame is the split image.
    pub views: usize,
}

impl ViewerOptions {
    /// With the world axes drawn or not.
    #[must_use]
    pub fn with_axes(mut self, axes: bool) -> Self {
        self.axes = axes;
        self
    }

    /// With `views` views (1 to 4; see [`views`](Self::views)).
    #[must_use]
    pub fn with_views(mut self, views: usize) -> Self {
        self.views = views;
        self
    }

    /// With the contact forces drawn or not.
    #[must_use]
    pub fn with_forces(mut self, forces: bool) -> Self {
        self.forces = forces;
        self
    }
}

/// Whether a display server is reachable (an X11 or Wayland display is named).
pub fn has_display() -> bool {
    display_named(|name| std::env::var_os(name))
}

/// Whether the environment (`var`) names a display: `DISPLAY` or `WAYLAND_DISPLAY`,
/// not empty.
fn display_named(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|v| var(v).is_some_and(|s| !s.is_empty()))
}

/// [`ViewerError::NoDisplay`] unless the environment (`var`) names a display.
fn require_display_in(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> Result<()> {
    if display_named(&var) {
        return Ok(());
    }
    let display = var("DISPLAY").map(|d| d.to_string_lossy().into_owned()).unwrap_or_default();
    Err(ViewerError::NoDisplay { display, reason: None })
}

/// What a window needs: this build's window ([`ViewerError::NotBuilt`] without the
/// `window` feature), then a display ([`ViewerError::NoDisplay`] unless one is named,
/// [`has_display`]).
fn require_display() -> Result<()> {
    if !cfg!(feature = "window") {
        return Err(ViewerError::NotBuilt { feature: "window", what: "a window" });
    }
    require_display_in(|name| std::env::var_os(name))
}

/// Simulated seconds recorded by [`ProgramViewer::start`] when there is no display.
pub const HEADLESS_FALLBACK_SECONDS: f64 = 10.0;

/// Shows programs: `program.start()`.
pub trait ProgramViewer: Program + Sized {
    /// Opens the program's window and runs it until the window is closed. On a
    /// machine with no display it records [`HEADLESS_FALLBACK_SECONDS`] of simulated
    /// time off screen instead, saying where the frames go.
    fn start(&mut self) -> Result<()> {
        self.show().map(drop)
    }

    /// As [`start`](Self::start), and returns the simulation as it was when the window
    /// closed (or when the off-screen recording ended), for its records.
    fn show(&mut self) -> Result<ars_core::Simulation> {
        self.show_with(&ViewerOptions::default())
    }

    /// As [`show`](Self::show), drawing what `options` say (in the window, or in the
    /// frames recorded without a display).
    fn show_with(&mut self, options: &ViewerOptions) -> Result<ars_core::Simulation> {
        if has_display() || !cfg!(feature = "window") {
            return catch_window_panic(|| session::run_window(self, options));
        }
        let title = self.window_settings().title.to_lowercase().replace(|c: char| !c.is_ascii_alphanumeric(), "_");
        let dir = std::env::temp_dir().join(format!("ars-frames-{title}"));
        eprintln!(
            "no display (DISPLAY and WAYLAND_DISPLAY are unset): recording {HEADLESS_FALLBACK_SECONDS} s off screen, \
             frames into {}",
            dir.display()
        );
        let (sim, written) =
            ScreenshotRecorder::new(&dir).every(5).options(*options).record(self, HEADLESS_FALLBACK_SECONDS)?;
        eprintln!("wrote {} frames into {}", written.len(), dir.display());
        Ok(sim)
    }

    /// Opens the program's window for `seconds` of wall time (or until it is closed)
    /// and returns the simulation and what the run measured: frames drawn, the
    /// real-time factor, the process's memory once a second. Needs a display.
    fn show_for(&mut self, seconds: f64) -> Result<(ars_core::Simulation, WindowReport)> {
        require_display()?;
        if !(seconds.is_finite() && seconds > 0.0) {
            return Err(ViewerError::InvalidSetting(format!("a window run needs a positive duration, got {seconds}")));
        }
        let limit = std::time::Duration::from_secs_f64(seconds);
        catch_window_panic(|| session::run_window_until(self, &ViewerOptions::default(), Some(limit)))
    }

    /// Opens the program's window for `frames` frames and returns the last one as
    /// shown (needs a display; run it on the main thread).
    fn snapshot_in_window(&mut self, frames: u32) -> Result<image::RgbImage> {
        require_display()?;
        catch_window_panic(|| window::snapshot_window(self, frames))
    }

    /// Runs the program for `duration` simulated seconds off screen, writing frames as
    /// `recorder` says; returns the simulation and the files written.
    fn record(&mut self, duration: f64, recorder: &ScreenshotRecorder) -> Result<(ars_core::Simulation, Vec<PathBuf>)> {
        recorder.record(self, duration)
    }
}

impl<P: Program> ProgramViewer for P {}

/// Opens a window on what `driver` drives, seen as `view` says, until it is closed (or
/// `limit` of wall time has passed); returns what the run measured. For front ends
/// with programs of their own (the Python package); Rust programs use
/// [`ProgramViewer::start`]. Needs a display and the main thread; one window per
/// thread, unless the thread keeps its context ([`keep_rendering_context`]).
pub fn run_window<D: Driver>(driver: &mut D, view: &WindowSettings, limit: Option<Duration>) -> Result<WindowReport> {
    run_window_with(driver, view, &ViewerOptions::default(), limit)
}

/// As [`run_window`], drawing what `options` say.
pub fn run_window_with<D: Driver>(
    driver: &mut D,
    view: &WindowSettings,
    options: &ViewerOptions,
    limit: Option<Duration>,
) -> Result<WindowReport> {
    require_display()?;
    if limit.is_some_and(|l| l.is_zero()) {
        return Err(ViewerError::InvalidSetting("a window run needs a positive duration".into()));
    }
    catch_window_panic(|| session::drive_window(driver, view, options, limit, None))
}

/// As [`run_window_with`], recording what the window shows (the panel and the text
/// too) into an MP4 video at `fps` frames a second of simulated time: frame k is the
/// window's picture at the first window frame at or after k/fps simulated seconds
/// from its first picture, at the window's size (`view.size`, both even). A window
/// frame shown longer than 1/fps (the window draws slower than the video's rate, or
/// runs faster than real time) repeats; while paused, the video stands still. The
/// frame rate, size and path are checked before the window opens; the video is
/// written when the window closes, and nothing is left if it fails.
pub fn run_window_recording<D: Driver>(
    driver: &mut D,
    view: &WindowSettings,
    options: &ViewerOptions,
    limit: Option<Duration>,
    path: impl Into<PathBuf>,
    fps: f64,
) -> Result<(WindowReport, RecordedVideo)> {
    require_display()?;
    if limit.is_some_and(|l| l.is_zero()) {
        return Err(ViewerError::InvalidSetting("a window run needs a positive duration".into()));
    }
    // Before the encoder's thread starts: the probe's fix needs a single thread.
    window::quiet_wayland_probe();
    let mut video = video::WindowVideo::new(VideoWriter::create(path, view.size.0, view.size.1, fps)?);
    let report = catch_window_panic(|| session::drive_window(driver, view, options, limit, Some(&mut video)))?;
    Ok((report, video.finish()?))
}

/// The windowing stack panics when it cannot open a window or find a graphics
/// adapter; turn that into an error that says what to install or check.
fn catch_window_panic<T>(open: impl FnOnce() -> Result<T>) -> Result<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(open)) {
        Ok(result) => result,
        Err(payload) => {
            let message = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic".into());
            Err(window_panic_error(message, std::env::var("DISPLAY").unwrap_or_default()))
        }
    }
}

/// The error for a panic of the windowing stack with `message`, `DISPLAY` being
/// `display`: no graphics adapter when the message is about one, no display otherwise
/// (the window could not be opened).
fn window_panic_error(message: String, display: String) -> ViewerError {
    if message.to_lowercase().contains("adapter") {
        ViewerError::NoAdapter(message)
    } else {
        ViewerError::NoDisplay { display, reason: Some(message) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An environment of `vars` only.
    fn env(vars: &'static [(&'static str, &'static str)]) -> impl Fn(&str) -> Option<std::ffi::OsString> {
        move |name: &str| vars.iter().find(|(n, _)| *n == name).map(|(_, v)| std::ffi::OsString::from(v))
    }

    #[test]
    fn no_display_named_is_a_no_display_error() {
        for vars in [&[][..], &[("DISPLAY", "")], &[("DISPLAY", ""), ("WAYLAND_DISPLAY", "")]] {
            let error = require_display_in(env(vars)).unwrap_err();
            assert!(matches!(&error, ViewerError::NoDisplay { reason: None, .. }), "{error:?}");
            assert_eq!(error.to_string(), "no display: DISPLAY and WAYLAND_DISPLAY are unset");
        }
        assert!(require_display_in(env(&[("DISPLAY", ":99")])).is_ok());
        assert!(require_display_in(env(&[("WAYLAND_DISPLAY", "wayland-0")])).is_ok());
    }

    #[test]
    fn a_window_that_does_not_open_is_no_display_and_an_adapter_missing_is_no_adapter() {
        let error = window_panic_error("Failed to open connection to X server".into(), ":12345".into());
        assert!(matches!(&error, ViewerError::NoDisplay { reason: Some(_), display } if display == ":12345"));
        assert_eq!(
            error.to_string(),
            "could not open a window (DISPLAY=\":12345\"): Failed to open connection to X server"
        );
        let error = window_panic_error("Unable to find a GPU adapter".into(), ":0".into());
        assert!(matches!(error, ViewerError::NoAdapter(_)), "{error:?}");
    }
}
