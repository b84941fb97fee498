//! Ctrl-C in the long calls that run a simulation through the viewer's recorders
//! (`record_video`, `save_replay`): the same check as `sim.run`'s
//! ([`python_signals`](crate::simulation::python_signals): Python's signal handlers,
//! run every few milliseconds), asked before every frame through a [`Driver`] of
//! the simulation that stops with [`Error::Interrupted`]. The recorders then drop
//! what they were writing, and with it their hidden partial files: an interrupted
//! recording leaves nothing behind, and the simulation is whole between two frames.

use std::ops::DerefMut;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use ars_core::{Error, Key, Simulation};
use ars_viewer::Driver;
use pyo3::prelude::*;

use crate::simulation::{SIGNAL_CHECK_PERIOD, signal_raised};

/// A bare simulation (its own frames and hooks) that asks `stop` before every frame
/// and ends there with [`Error::Interrupted`] when it says yes.
pub(crate) struct StoppableSimulation<'a, F> {
    pub sim: &'a mut Simulation,
    pub stop: F,
}

impl<F: FnMut() -> bool> StoppableSimulation<'_, F> {
    /// `Err(Interrupted)` if `stop` says so.
    fn check(&mut self) -> ars_core::Result<()> {
        if (self.stop)() {
            let scene = self.sim.scene();
            return Err(Error::Interrupted { time: scene.time(), steps: scene.step_count() });
        }
        Ok(())
    }
}

impl<F: FnMut() -> bool> Driver for StoppableSimulation<'_, F> {
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_ {
        &mut *self.sim
    }
    fn step_frame(&mut self) -> ars_core::Result<()> {
        self.check()?;
        self.sim.step_frame()
    }
    fn step_frame_observed(
        &mut self,
        after_step: &mut dyn FnMut(&Simulation) -> ars_core::Result<()>,
    ) -> ars_core::Result<()> {
        self.check()?;
        self.sim.step_frame_observed(after_step)
    }
    fn step(&mut self) -> ars_core::Result<()> {
        self.check()?;
        self.sim.step()
    }
    fn reset(&mut self) -> ars_core::Result<()> {
        Err(Error::User("a recording does not rebuild a bare simulation".into()))
    }
    fn key_down(&mut self, _: Key) -> ars_core::Result<()> {
        Ok(())
    }
    fn key_up(&mut self, _: Key) -> ars_core::Result<()> {
        Ok(())
    }
}

/// Runs `work` on a thread of its own (named `name`) while the calling thread, which
/// holds no GIL, runs Python's signal handlers every [`SIGNAL_CHECK_PERIOD`] (only the
/// main thread sees them). When one raises (Ctrl-C's `KeyboardInterrupt`), its
/// exception is kept in `raised` and `stop` is set, for `work` to end at its next
/// check. Returns what `work` returned, or its panic; `Err` if the thread could not
/// start.
pub(crate) fn on_thread_watching_signals<R: Send>(
    name: &str,
    stop: &AtomicBool,
    raised: &Mutex<Option<PyErr>>,
    work: impl FnOnce() -> R + Send,
) -> std::io::Result<std::thread::Result<R>> {
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new().name(name.into()).spawn_scoped(scope, work)?;
        while !worker.is_finished() {
            std::thread::sleep(SIGNAL_CHECK_PERIOD.min(Duration::from_millis(5)));
            if stop.load(Ordering::Relaxed) {
                continue;
            }
            if signal_raised(raised) {
                stop.store(true, Ordering::Relaxed);
            }
        }
        Ok(worker.join())
    })
}

/// The stop condition of a recorder's frames: every [`SIGNAL_CHECK_PERIOD`] (the clock
/// is read at every call: a frame takes far longer than reading it) it runs Python's
/// signal handlers; if one raises (Ctrl-C's `KeyboardInterrupt`), the exception is
/// kept in `raised` and the recording stops before the next frame.
pub(crate) fn python_signals_per_frame(raised: &Mutex<Option<PyErr>>) -> impl FnMut() -> bool + Send + '_ {
    let mut last = Instant::now();
    move || {
        if last.elapsed() < SIGNAL_CHECK_PERIOD {
            return false;
        }
        last = Instant::now();
        signal_raised(raised)
    }
}
