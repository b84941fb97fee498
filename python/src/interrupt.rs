//! Ctrl-C in the long calls that run a simulation through the viewer's recorders
//! (`record_video`, `save_replay`): the same check as `sim.run`'s
//! ([`python_signals`](crate::simulation::python_signals): Python's signal handlers,
//! run every few milliseconds), asked before every frame through a [`Driver`] of
//! the simulation that stops with [`Error::Interrupted`]. The recorders then drop
//! what they were writing, and with it their hidden partial files: an interrupted
//! recording leaves nothing behind, and the simulation is whole between two frames.

use std::ops::DerefMut;
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

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

/// The threads of [`starting_on_thread_watching_signals`] abandoned while they
/// started, not yet joined: [`join_abandoned`] waits for them.
static ABANDONED: Mutex<Vec<std::thread::JoinHandle<()>>> = Mutex::new(Vec::new());

/// Waits, at most [`ABANDONED_WAIT`], for the threads abandoned by Ctrl-C while they
/// started (each ends once its renderer is up, within seconds): the package calls it when the interpreter exits,
/// so that no thread is still starting a rendering context while the process tears
/// down (which can crash it).
pub(crate) fn join_abandoned() {
    let threads = std::mem::take(&mut *ABANDONED.lock().unwrap_or_else(PoisonError::into_inner));
    // Bounded: a renderer that never comes up (a broken graphics driver) must not hang
    // the interpreter's exit; such a thread is left to the process's end.
    let deadline = Instant::now() + ABANDONED_WAIT;
    while threads.iter().any(|t| !t.is_finished()) && Instant::now() < deadline {
        std::thread::sleep(SIGNAL_CHECK_PERIOD);
    }
    for thread in threads.into_iter().filter(|t| t.is_finished()) {
        let _ = thread.join();
    }
}

/// The longest [`join_abandoned`] waits for the abandoned threads at exit (a
/// renderer starts in well under this, even on a busy machine).
const ABANDONED_WAIT: std::time::Duration = std::time::Duration::from_secs(20);

/// Where the work of [`starting_on_thread_watching_signals`] stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// `start` runs: Ctrl-C abandons the work and the caller returns at once.
    Starting,
    /// `run` runs: Ctrl-C asks it to stop, and the caller waits for it.
    Running,
    /// Ctrl-C came while starting: the thread ends once `start` returns.
    Abandoned,
}

/// Runs `start`, then `run` with what it made, on a thread of its own (named `name`,
/// not joined) while the calling thread, which holds no GIL, runs Python's signal
/// handlers every [`SIGNAL_CHECK_PERIOD`]. When one raises (Ctrl-C's
/// `KeyboardInterrupt`), its exception is kept in `raised` and:
/// - while `start` runs (a renderer starting: up to seconds on Mesa's software
///   rasteriser), this returns `Ok(None)` at once; the thread ends when `start`
///   returns, without calling `run` (and is joined by [`join_abandoned`] at exit at
///   the latest). So `start` must not touch what the caller holds;
/// - once `run` began, `stop` is set for `run` to end at its next check, and this
///   waits for it.
///
/// Otherwise the thread is joined before this returns what `run` returned (or a
/// panic of either); `Err` if the thread could not start.
pub(crate) fn starting_on_thread_watching_signals<S: 'static, R: Send + 'static>(
    name: &str,
    stop: &AtomicBool,
    raised: &Mutex<Option<PyErr>>,
    start: impl FnOnce() -> S + Send + 'static,
    run: impl FnOnce(S) -> R + Send + 'static,
) -> std::io::Result<Option<std::thread::Result<R>>> {
    let phase = Arc::new(Mutex::new(Phase::Starting));
    let (sender, outcome) = std::sync::mpsc::channel();
    let worker_phase = Arc::clone(&phase);
    let worker = std::thread::Builder::new().name(name.into()).spawn(move || {
        let started = std::panic::catch_unwind(AssertUnwindSafe(start));
        {
            let mut now = worker_phase.lock().unwrap_or_else(PoisonError::into_inner);
            if *now == Phase::Abandoned {
                return;
            }
            *now = Phase::Running;
        }
        let done = started.and_then(|s| std::panic::catch_unwind(AssertUnwindSafe(|| run(s))));
        let _ = sender.send(done);
    })?;
    loop {
        match outcome.recv_timeout(SIGNAL_CHECK_PERIOD) {
            // Joined: the thread's rendering context is gone before the caller goes on
            // (and before the interpreter may exit).
            Ok(done) => {
                let _ = worker.join();
                return Ok(Some(done));
            }
            Err(RecvTimeoutError::Disconnected) => {
                let _ = worker.join();
                return Ok(Some(Err(Box::new(format!("{name} ended without its result")))));
            }
            Err(RecvTimeoutError::Timeout) => {
                if stop.load(Ordering::Relaxed) || !signal_raised(raised) {
                    continue;
                }
                stop.store(true, Ordering::Relaxed);
                let mut now = phase.lock().unwrap_or_else(PoisonError::into_inner);
                if *now == Phase::Starting {
                    *now = Phase::Abandoned;
                    ABANDONED.lock().unwrap_or_else(PoisonError::into_inner).push(worker);
                    return Ok(None);
                }
            }
        }
    }
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
