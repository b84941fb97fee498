//! The recorders' one builder, [`Recorder`]: the image size and the viewer's options
//! every recording takes, and the runs every recording has (a [`Program`], a bare
//! [`Simulation`] or any [`Driver`] for a duration of simulated time). What it writes
//! is its output's: numbered PNG frames ([`ScreenshotRecorder`](crate::ScreenshotRecorder))
//! or an MP4 video ([`VideoRecorder`](crate::VideoRecorder)).

use ars_core::{Program, ProgramRunner, Simulation, WindowSettings};

use crate::ViewerOptions;
use crate::driver::{BareSimulation, Driver};
use crate::error::{Result, ViewerError};
use crate::offscreen::OffscreenRenderer;

/// A recording of a simulation into `T` (frames or a video), built step by step:
/// `ScreenshotRecorder::new("frames").every(5).size(800, 600)`.
#[derive(Clone, Debug)]
pub struct Recorder<T> {
    pub(crate) output: T,
    pub(crate) size: Option<(u32, u32)>,
    pub(crate) options: ViewerOptions,
}

/// What a [`Recorder`] writes, and how it records what a driver drives.
pub trait RecordingOutput: Sized {
    /// What a finished recording returns (the files written, the video...).
    type Recorded;
    /// Runs what `driver` drives for `duration` seconds of simulated time (whole
    /// frames), seen as `view` says (at the recorder's size if it has one), into this
    /// output, drawing with `started` (from [`Recorder::start_renderer`]) or with a
    /// renderer of its own when `None`.
    fn record_driven<D: Driver>(
        recorder: &Recorder<Self>,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
        started: Option<OffscreenRenderer>,
    ) -> Result<Self::Recorded>;
}

impl<T> Recorder<T> {
    /// A recorder into `output`, at the window settings' size, drawing with the
    /// default options.
    pub(crate) fn with_output(output: T) -> Self {
        Recorder { output, size: None, options: ViewerOptions::default() }
    }

    /// Images of `width × height` pixels instead of the window settings' size (a
    /// video's must both be even).
    #[must_use]
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = Some((width, height));
        self
    }

    /// Frames drawn as `options` say (the world axes, the forces, several views...).
    #[must_use]
    pub fn options(mut self, options: ViewerOptions) -> Self {
        self.options = options;
        self
    }
}

impl<T: RecordingOutput> Recorder<T> {
    /// Runs `program` for `duration` seconds of simulated time, off screen, seen as
    /// its window settings say; returns the simulation (for its records) and what
    /// was recorded.
    pub fn record<P: Program>(&self, program: &mut P, duration: f64) -> Result<(Simulation, T::Recorded)> {
        run_program(program, |runner, view| self.record_driven(runner, view, duration))
    }

    /// Runs a bare simulation (its own and added hooks, no program) for `duration`
    /// seconds of simulated time, seen as `view` says (what front ends with
    /// simulations of their own, such as the Python package, call).
    pub fn record_simulation(&self, sim: &mut Simulation, view: &WindowSettings, duration: f64) -> Result<T::Recorded> {
        self.record_driven(&mut BareSimulation(sim), view, duration)
    }

    /// Runs what `driver` drives for `duration` seconds of simulated time (whole
    /// frames), seen as `view` says. A stop requested through
    /// [`ars_core::interrupt`] (Ctrl-C) ends the recording after the frame being
    /// drawn, with what was recorded so far.
    pub fn record_driven<D: Driver>(
        &self,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
    ) -> Result<T::Recorded> {
        T::record_driven(self, driver, view, duration, None)
    }

    /// Starts the renderer this recording draws with (`view` at the recorder's size,
    /// its options), before any simulation is taken: the slow part of a recording's
    /// start (the rendering context: half a second to seconds on Mesa's software
    /// rasteriser). Give it to [`record_driven_with`](Self::record_driven_with) on this
    /// thread. A front end that must answer Ctrl-C while it starts (the Python
    /// package) starts it first, and takes the simulation only once it is there.
    pub fn start_renderer(&self, view: &WindowSettings) -> Result<OffscreenRenderer> {
        let mut view = view.clone();
        if let Some(size) = self.size {
            view.size = size;
        }
        OffscreenRenderer::with_options(&view, &self.options)
    }

    /// As [`record_driven`](Self::record_driven), drawing with `renderer`, which
    /// [`start_renderer`](Self::start_renderer) of this recorder made on this thread.
    pub fn record_driven_with<D: Driver>(
        &self,
        renderer: OffscreenRenderer,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
    ) -> Result<T::Recorded> {
        T::record_driven(self, driver, view, duration, Some(renderer))
    }

    /// The renderer this recording draws what `driver` drives with: `started` if
    /// given, else one of `view` at the recorder's size (if it has one), drawing what
    /// its options say; when it draws forces, the simulation is asked to report them
    /// (the contacts' and every joint's).
    pub(crate) fn renderer<D: Driver>(
        &self,
        driver: &mut D,
        view: &WindowSettings,
        started: Option<OffscreenRenderer>,
    ) -> Result<OffscreenRenderer> {
        let renderer = match started {
            Some(renderer) => renderer,
            None => self.start_renderer(view)?,
        };
        if self.options.forces {
            crate::scene::report_forces(driver.simulation().scene_mut().world_mut());
        }
        Ok(renderer)
    }
}

/// The whole frames of `sim` that `duration` seconds of simulated time take (the last
/// one may be cut short by the duration): what every recorder runs.
pub(crate) fn frames_in(sim: &Simulation, duration: f64) -> Result<u64> {
    if !(duration.is_finite() && duration > 0.0) {
        return Err(ViewerError::InvalidSetting(format!("a recording's duration must be positive, got {duration} s")));
    }
    Ok(sim.scene().steps_in(duration)?.div_ceil(u64::from(sim.scene().steps_per_frame())))
}

/// Runs `program` through `record`, seen as its window settings say; returns the
/// simulation (for its records) and what `record` returned: every recorder's
/// `record`.
pub(crate) fn run_program<P: Program, R>(
    program: &mut P,
    record: impl FnOnce(&mut ProgramRunner<'_, P>, &WindowSettings) -> Result<R>,
) -> Result<(Simulation, R)> {
    let view = program.window_settings();
    let mut runner = ProgramRunner::new(program)?;
    let recorded = record(&mut runner, &view)?;
    Ok((runner.into_simulation(), recorded))
}
