//! `ars.step_many`: many simulations stepped at once, on native threads, with the GIL
//! released.
//!
//! Every simulation is checked before any steps (each an `ars.Simulation`, none listed
//! twice, none whose own hook is calling), so a refused call steps nothing. The
//! simulations are then stepped by the calling thread and by the workers of one pool
//! per process (one thread fewer than there are cores, started on first use and kept:
//! a vector environment calls `step_many` at every step, and starting threads each
//! time costs a sizeable part of a pendulum's 80 steps). Each takes the next simulation not yet taken until none is left, so the
//! calling thread takes on the work alone when the workers are busy with another
//! call (it then waits for them to get to this one and find nothing left). The
//! calling thread is the one that looks for Ctrl-C. Each simulation is
//! locked only while it steps, one at a time per thread, so `step_many` waits for (and
//! never deadlocks with) a step of the same simulation on another Python thread.
//!
//! A `step_many` from a pool worker (a hook of a simulation it steps) runs on that
//! thread alone: a worker never waits for another worker.

use std::cell::Cell;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::{Duration, Instant};

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::{Checked, count, raise};
use crate::simulation::{Int, PySimulation, SIGNAL_CHECK_PERIOD, python_signals};

/// What one simulation's steps came to, by its index in the list.
type Outcome = (usize, std::thread::Result<ars_core::Result<()>>);

/// One call's simulations, shared by the threads stepping them.
struct Job {
    sims: Vec<Py<PySimulation>>,
    n: u64,
    /// The index of the next simulation not yet taken.
    next: AtomicUsize,
    /// Set when Ctrl-C stops the call: every thread stops between two steps.
    stop: AtomicBool,
}

impl Job {
    /// Takes the next simulation not yet taken and steps it, until none is left.
    fn work(&self, mut stop: impl FnMut() -> bool) -> Vec<Outcome> {
        let mut outcomes = Vec::new();
        loop {
            let i = self.next.fetch_add(1, Ordering::Relaxed);
            let Some(sim) = self.sims.get(i) else { return outcomes };
            outcomes.push((i, sim.get().step_detached(self.n, &mut stop)));
        }
    }
}

/// A job for a worker, and where to send what it stepped.
type Task = (Arc<Job>, Sender<Vec<Outcome>>);

/// The workers: one channel of tasks each.
struct Pool {
    workers: Vec<Mutex<Sender<Task>>>,
}

thread_local! {
    /// Whether this thread is a pool worker.
    static IN_POOL: Cell<bool> = const { Cell::new(false) };
}

impl Pool {
    /// The process's pool: one worker per core but one (none on one core).
    fn get() -> &'static Pool {
        static POOL: OnceLock<Pool> = OnceLock::new();
        POOL.get_or_init(|| {
            let cores = std::thread::available_parallelism().map_or(1, usize::from);
            let workers = (1..cores)
                .filter_map(|i| {
                    let (tasks, received) = mpsc::channel::<Task>();
                    std::thread::Builder::new()
                        .name(format!("ars-step-many-{i}"))
                        .spawn(move || serve(received))
                        .ok()
                        .map(|_| Mutex::new(tasks))
                })
                .collect();
            Pool { workers }
        })
    }
}

/// How long a thread waiting for a message polls before it sleeps. A vector
/// environment calls `step_many` again soon after the last call ended, sooner than a
/// sleeping thread wakes on a virtual machine: a worker that still
/// polls takes the next call at once, and a caller whose worker finishes just after it
/// does not sleep either.
const SPIN: Duration = Duration::from_micros(200);

/// The next message of `channel`: polled for [`SPIN`], then waited for asleep; `None`
/// when the channel is closed.
fn receive<T>(channel: &Receiver<T>) -> Option<T> {
    let start = Instant::now();
    loop {
        match channel.try_recv() {
            Ok(message) => return Some(message),
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) if start.elapsed() < SPIN => std::hint::spin_loop(),
            Err(TryRecvError::Empty) => return channel.recv().ok(),
        }
    }
}

/// A worker's life: step the simulations of each task it gets, then send back what
/// they came to (after letting the job go, so that the caller holds its last
/// reference and drops its Python objects with the GIL).
fn serve(tasks: Receiver<Task>) {
    IN_POOL.with(|flag| flag.set(true));
    while let Some((job, done)) = receive(&tasks) {
        let outcomes = job.work(|| job.stop.load(Ordering::Relaxed));
        drop(job);
        let _ = done.send(outcomes);
    }
}

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
#[pyo3(signature = (sims, n=Checked(1)))]
pub(crate) fn step_many(py: Python<'_>, sims: &Bound<'_, PyAny>, n: Int) -> PyResult<()> {
    let n: u64 = count(py, "the number of steps", n)?;
    let mut list: Vec<Py<PySimulation>> = Vec::new();
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
        list.push(sim.unbind());
    }
    let job = Arc::new(Job { sims: list, n, next: AtomicUsize::new(0), stop: AtomicBool::new(false) });
    let interrupt: Mutex<Option<PyErr>> = Mutex::new(None);
    let mut outcomes = py.detach(|| run_all(&job, &interrupt));
    outcomes.sort_by_key(|(i, _)| *i);
    // Every simulation's exception is taken (none is left for a later call); the first
    // in the list is raised, a Ctrl-C before any.
    let mut first = None;
    for (i, caught) in outcomes {
        if let Err(e) = job.sims[i].get().stepped(py, caught) {
            first.get_or_insert(e);
        }
    }
    let interrupt = interrupt.into_inner().unwrap_or_else(PoisonError::into_inner);
    match interrupt.or(first) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Steps every simulation of `job` on the calling thread and as many pool workers as
/// there are simulations but one; the calling thread (the main one, which alone sees
/// signals) checks for Ctrl-C and keeps it in `interrupt`.
fn run_all(job: &Arc<Job>, interrupt: &Mutex<Option<PyErr>>) -> Vec<Outcome> {
    let helpers: &[Mutex<Sender<Task>>] = if IN_POOL.with(Cell::get) || job.sims.len() < 2 {
        &[]
    } else {
        let workers = &Pool::get().workers;
        &workers[..workers.len().min(job.sims.len() - 1)]
    };
    let (done, results) = mpsc::channel();
    let mut sent = 0;
    for worker in helpers {
        let tasks = worker.lock().unwrap_or_else(PoisonError::into_inner);
        if tasks.send((Arc::clone(job), done.clone())).is_ok() {
            sent += 1;
        }
    }
    drop(done);
    let mut signals = python_signals(interrupt);
    let mut outcomes = job.work(|| {
        if signals() {
            job.stop.store(true, Ordering::Relaxed);
        }
        job.stop.load(Ordering::Relaxed)
    });
    // A worker that is gone sends nothing: its share was taken by the others. While
    // the workers step on, the calling thread still looks for Ctrl-C.
    for _ in 0..sent {
        let more = receive_watching(&results, || {
            if signals() {
                job.stop.store(true, Ordering::Relaxed);
            }
        });
        match more {
            Some(more) => outcomes.extend(more),
            None => break,
        }
    }
    outcomes
}

/// As [`receive`], calling `watch` every [`SIGNAL_CHECK_PERIOD`] while it waits.
fn receive_watching<T>(channel: &Receiver<T>, mut watch: impl FnMut()) -> Option<T> {
    let start = Instant::now();
    loop {
        match channel.try_recv() {
            Ok(message) => return Some(message),
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) if start.elapsed() < SPIN => std::hint::spin_loop(),
            Err(TryRecvError::Empty) => break,
        }
    }
    loop {
        match channel.recv_timeout(SIGNAL_CHECK_PERIOD) {
            Ok(message) => return Some(message),
            Err(RecvTimeoutError::Disconnected) => return None,
            Err(RecvTimeoutError::Timeout) => watch(),
        }
    }
}
