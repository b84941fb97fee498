//! `ars.step_many`: many simulations stepped at once, on native threads, with the GIL
//! released.
//!
//! Every simulation is checked before any steps (each an `ars.Simulation`, none listed
//! twice, none whose own hook is calling), so a refused call steps nothing. The calling
//! thread steps simulations too, and is the one that looks for Ctrl-C; the others are
//! scoped threads, at most one per core and one per simulation, taking the next
//! simulation not yet stepped until none is left. Each simulation is locked only while
//! it steps, one at a time per thread, so `step_many` waits for (and never deadlocks
//! with) a step of the same simulation on another Python thread.

use std::collections::HashMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::{count, raise};
use crate::simulation::{PySimulation, python_signals};

/// What one simulation's steps came to, by its index in the list.
type Outcome = (usize, std::thread::Result<ars_core::Result<()>>);

/// Steps each simulation of `sims` by `n` steps (as `sim.step(n)` would, bit for bit),
/// on native threads (as many as there are cores, at most one per simulation) with the
/// GIL released except while a Python hook runs.
///
/// Refused before anything steps: an item that is not an `ars.Simulation`
/// (`TypeError`), a simulation listed twice or `n < 0` (`ars.InputError`), a
/// simulation whose own hook is calling (`ars.BusyError`). A simulation whose Python
/// hook raises stops at that step, as with `step`; the others take their `n` steps, and
/// the exception of the first such simulation in the list is raised once all have
/// finished. Ctrl-C stops every simulation between two steps with `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (sims, n=1))]
pub(crate) fn step_many(py: Python<'_>, sims: &Bound<'_, PyAny>, n: i64) -> PyResult<()> {
    let n: u64 = count(py, "the number of steps", n)?;
    let mut list: Vec<Bound<'_, PySimulation>> = Vec::new();
    let mut seen: HashMap<usize, usize> = HashMap::new();
    for (i, item) in sims.try_iter()?.enumerate() {
        let item = item?;
        let kind = item.get_type().name()?.to_string();
        let sim = item.cast_into::<PySimulation>().map_err(|_| {
            PyTypeError::new_err(format!("ars.step_many steps ars.Simulation objects: item {i} is of type {kind}"))
        })?;
        if let Some(first) = seen.insert(sim.as_ptr() as usize, i) {
            return Err(raise(
                py,
                "InputError",
                format!("items {first} and {i} are the same simulation: each may be listed once"),
            ));
        }
        if sim.get().in_own_hook() {
            return Err(raise(py, "BusyError", format!("item {i}: a hook cannot step the simulation it runs in")));
        }
        list.push(sim);
    }
    let refs: Vec<&PySimulation> = list.iter().map(Bound::get).collect();
    let interrupt: Mutex<Option<PyErr>> = Mutex::new(None);
    let mut outcomes = py.detach(|| run_all(&refs, n, &interrupt));
    outcomes.sort_by_key(|(i, _)| *i);
    // Every simulation's exception is taken (none is left for a later call); the first
    // in the list is raised, a Ctrl-C before any.
    let mut first = None;
    for (i, caught) in outcomes {
        if let Err(e) = refs[i].stepped(py, caught) {
            first.get_or_insert(e);
        }
    }
    let interrupt = interrupt.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner);
    match interrupt.or(first) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Steps every simulation `n` steps on up to one thread per core; the calling thread
/// (the main one, which alone sees signals) checks for Ctrl-C and keeps it in
/// `interrupt`.
fn run_all(sims: &[&PySimulation], n: u64, interrupt: &Mutex<Option<PyErr>>) -> Vec<Outcome> {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let threads = cores.min(sims.len());
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let workers: Vec<_> =
            (1..threads).map(|_| scope.spawn(|| work(sims, n, &next, || stop.load(Ordering::Relaxed)))).collect();
        let mut signals = python_signals(interrupt);
        let mut outcomes = work(sims, n, &next, || {
            if signals() {
                stop.store(true, Ordering::Relaxed);
            }
            stop.load(Ordering::Relaxed)
        });
        for worker in workers {
            // `work` catches the panics of stepping; one here would be a bug of its own.
            match worker.join() {
                Ok(more) => outcomes.extend(more),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        outcomes
    })
}

/// Takes the next simulation not yet taken and steps it, until none is left.
fn work(sims: &[&PySimulation], n: u64, next: &AtomicUsize, mut stop: impl FnMut() -> bool) -> Vec<Outcome> {
    let mut outcomes = Vec::new();
    loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        let Some(sim) = sims.get(i) else { return outcomes };
        outcomes.push((i, sim.step_detached(n, &mut stop)));
    }
}
