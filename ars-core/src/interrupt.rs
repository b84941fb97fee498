//! Stopping a run early: Ctrl-C for programs, any condition for embedders.
//!
//! A program calls [`stop_on_ctrl_c`] once. From then on, the first Ctrl-C (SIGINT)
//! asks every run to stop: [`Simulation::run_for`](crate::Simulation::run_for),
//! [`ProgramRunner::run_for`](crate::ProgramRunner::run_for) and
//! [`run_script`](crate::ProgramRunner::run_script) end at the next frame boundary
//! with [`Error::Interrupted`], the simulation whole and
//! usable (its records so far are there to be written), and the viewer's recorder
//! stops after the frame it is writing. The request stays until [`clear`]: later runs
//! stop at once. A second Ctrl-C ends the process at once (exit status 130), as Ctrl-C
//! does without a handler, for a program stuck elsewhere.
//!
//! Nothing is installed unless asked: a library user or an interpreter (Python has its
//! own SIGINT handler) keeps its own. Embedders stop a run on a condition of their own
//! with [`Simulation::run_for_until`](crate::Simulation::run_for_until).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

use crate::error::{Error, Result};

/// The request flag the signal handler sets (an `Arc`: signal-hook keeps a clone).
fn flag() -> &'static Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(Arc::default)
}

/// Installs the Ctrl-C (SIGINT) handler described in the [module docs](self); calling
/// it again does nothing. `Err` if the operating system refuses the handler.
pub fn stop_on_ctrl_c() -> Result<()> {
    static INSTALLED: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    let installed = INSTALLED.get_or_init(|| {
        let flag = flag();
        const SIGINT: i32 = signal_hook::consts::SIGINT;
        // The shutdown handler runs first and sees the flag as the previous Ctrl-C left it.
        signal_hook::flag::register_conditional_shutdown(SIGINT, 130, Arc::clone(flag))
            .and_then(|_| signal_hook::flag::register(SIGINT, Arc::clone(flag)))
            .map(drop)
            .map_err(|e| e.to_string())
    });
    installed.clone().map_err(|e| Error::User(format!("the Ctrl-C handler could not be installed: {e}")))
}

/// Whether a stop was requested (by Ctrl-C or [`request`]) and not [cleared](clear).
#[inline]
pub fn requested() -> bool {
    flag().load(Ordering::Relaxed)
}

/// Requests a stop, as Ctrl-C does (for tests, or a program's own stop button).
pub fn request() {
    flag().store(true, Ordering::Relaxed);
}

/// Withdraws the request; returns whether there was one.
pub fn clear() -> bool {
    flag().swap(false, Ordering::Relaxed)
}
