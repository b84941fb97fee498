//! `ars.Simulation`: a simulation usable from any Python thread, stepped with the GIL
//! released, with Python callables as hooks.
//!
//! The simulation sits in a mutex. While it steps, the thread stepping holds the lock
//! and runs without the GIL (or, when a Python hook runs at every step, with it: see
//! `PySimulation::advance`); a Python hook takes the GIL back and may call this same
//! object (to read a body or push a joint): such calls, on the stepping thread, reach
//! the simulation through the reference the hook was handed (see [`HookContext`]).
//! Other threads wait for the step to end, without holding the GIL.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, PoisonError, TryLockError};
use std::time::{Duration, Instant};

use ars_core::body::MassSpec;
use ars_core::nalgebra::{Matrix3, Point3, Vector3};
use ars_core::{Error, HookId, HookPoint, Hooks, JointEnd, Mass, ObjectId, Shape, Simulation};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::{Checked, count, guarded, outcome, raise};

mod building;
mod contacts;
mod files;
mod sensing;

/// A vector given as any sequence of three numbers (another length is an
/// `ars.InputError`).
pub(crate) type Vec3 = Checked<[f64; 3]>;

/// An integer argument (one beyond 64 bits is an `ars.InputError`).
pub(crate) type Int = Checked<i64>;

impl From<Vec3> for Point3<f64> {
    fn from(v: Vec3) -> Self {
        Point3::from(v.0)
    }
}

impl From<Vec3> for Vector3<f64> {
    fn from(v: Vec3) -> Self {
        Vector3::from(v.0)
    }
}

/// A ray's hit: distance (m) and point.
type RayHit = (f64, (f64, f64, f64));

/// Where a running hook's simulation can be reached from Python calls on the same
/// thread.
#[derive(Default)]
pub(crate) struct HookContext {
    /// The thread running a Python hook ([`thread_mark`]; 0: none) and the simulation
    /// it was handed (its address). Only the thread that wrote them can find its own
    /// mark here, so plain atomics do: no lock on every call from a hook.
    thread: AtomicUsize,
    sim: AtomicUsize,
    /// The exception a Python hook raised, to re-raise unchanged from `step`/`run`.
    raised: Mutex<Option<PyErr>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // A panic is caught where it happens and reported; the data stays usable.
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

thread_local! {
    static THREAD_MARK: u8 = const { 0 };
}

/// A number naming the calling thread while it runs (the address of its own
/// thread-local byte): cheaper than `std::thread::current().id()`, and never 0.
fn thread_mark() -> usize {
    THREAD_MARK.with(|mark| mark as *const u8 as usize)
}

impl HookContext {
    /// The simulation handed to the hook running on this thread, if any.
    #[inline]
    fn current(&self) -> Option<*mut Simulation> {
        (self.thread.load(Ordering::Relaxed) == thread_mark())
            .then(|| self.sim.load(Ordering::Relaxed) as *mut Simulation)
    }

    /// Publishes `sim` as the simulation a hook on this thread was handed, until the
    /// returned guard is dropped.
    fn publish(&self, sim: &mut Simulation) -> impl Drop + '_ {
        self.sim.store(sim as *mut Simulation as usize, Ordering::Relaxed);
        self.thread.store(thread_mark(), Ordering::Relaxed);
        struct Clear<'a>(&'a HookContext);
        impl Drop for Clear<'_> {
            fn drop(&mut self) {
                self.0.thread.store(0, Ordering::Relaxed);
            }
        }
        Clear(self)
    }
}

/// How often a long `step`/`run` takes the GIL back to let Python handle its signals.
pub(crate) const SIGNAL_CHECK_PERIOD: Duration = Duration::from_millis(5);

/// Runs Python's signal handlers (taking the GIL); if one raises (Ctrl-C's
/// `KeyboardInterrupt`), keeps the exception in `raised` and says so.
pub(crate) fn signal_raised(raised: &Mutex<Option<PyErr>>) -> bool {
    match Python::attach(|py| py.check_signals()) {
        Ok(()) => false,
        Err(e) => {
            *lock(raised) = Some(e);
            true
        }
    }
}

/// The stop condition of a long `step`/`run` (called between steps or frames): every
/// [`SIGNAL_CHECK_PERIOD`] it runs Python's signal handlers; if one raises (Ctrl-C's
/// `KeyboardInterrupt`), the exception is kept in `raised` for the caller to raise and
/// the run stops, the simulation whole between two steps.
pub(crate) fn python_signals(raised: &Mutex<Option<PyErr>>) -> impl FnMut() -> bool + Send + '_ {
    let mut last = Instant::now();
    let mut calls = 0u32;
    move || {
        // The clock is read every 16th call: a step can take under a microsecond.
        calls = calls.wrapping_add(1);
        if !calls.is_multiple_of(16) || last.elapsed() < SIGNAL_CHECK_PERIOD {
            return false;
        }
        last = Instant::now();
        signal_raised(raised)
    }
}

/// A Python hook as the simulation keeps it: its id in the core, and its switch.
type AddedHook = (HookId<PyHook>, Arc<AtomicBool>);

/// A Python callable run before or after every step, while enabled.
struct PyHook {
    callable: Py<PyAny>,
    after_step: bool,
    context: Arc<HookContext>,
    /// Off: skipped without taking the GIL (`Simulation._enable_hook`).
    enabled: Arc<AtomicBool>,
}

impl PyHook {
    fn call(&self, sim: &mut Simulation) -> ars_core::Result<()> {
        if !self.enabled.load(Ordering::Relaxed) {
            return Ok(());
        }
        let context = &self.context;
        // Cleared however the call ends.
        let _published = context.publish(sim);
        // While Python runs, `sim` is reached only through the address published above
        // (by calls on this thread); it is not used here until the call returns.
        Python::attach(|py| match self.callable.call0(py) {
            Ok(_) => Ok(()),
            Err(e) => {
                let message = format!("a Python hook raised {e}");
                *lock(&context.raised) = Some(e);
                Err(Error::User(message))
            }
        })
    }
}

impl Hooks for PyHook {
    fn pre_step(&mut self, sim: &mut Simulation) -> ars_core::Result<()> {
        if self.after_step { Ok(()) } else { self.call(sim) }
    }
    fn post_step(&mut self, sim: &mut Simulation) -> ars_core::Result<()> {
        if self.after_step { self.call(sim) } else { Ok(()) }
    }
    fn runs_at(&self, point: HookPoint) -> bool {
        point == if self.after_step { HookPoint::PostStep } else { HookPoint::PreStep }
    }
}

/// A physics simulation: objects and joints by name, stepped in native code.
///
/// Usable from any thread; not picklable (build simulations inside workers: see
/// `ars.sweep`).
#[pyclass(name = "Simulation", module = "ars", frozen)]
pub struct PySimulation {
    sim: Mutex<Simulation>,
    context: Arc<HookContext>,
    /// The Python hooks by the id Python knows them by.
    hooks: Mutex<HashMap<u64, AddedHook>>,
    next_hook: Mutex<u64>,
    /// Why the simulation is gone, if it is: `sim.ros` hands the simulation to the
    /// ROS 2 bridge, which drops it when it fails (see `crate::ros`); `sim` then holds
    /// an empty stand-in, and every later call is refused with this reason.
    lost: OnceLock<String>,
}

impl PySimulation {
    /// Whether a Python hook is on (runs at every step).
    fn runs_python_every_step(&self) -> bool {
        lock(&self.hooks).values().any(|(_, enabled)| enabled.load(Ordering::Relaxed))
    }

    fn wrap(sim: Simulation) -> Self {
        PySimulation {
            sim: Mutex::new(sim),
            context: Arc::default(),
            hooks: Mutex::default(),
            next_hook: Mutex::new(1),
            lost: OnceLock::new(),
        }
    }

    /// Runs `f` on the simulation: the one a hook on this thread was handed, else the
    /// locked one (waiting without the GIL). ARS errors and panics become exceptions.
    pub(crate) fn with<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
        self.check_not_lost(py)?;
        if let Some(sim) = self.context.current() {
            // SAFETY: `sim` is the `&mut Simulation` a hook running on this thread was
            // handed (PyHook::call); that hook does not use it until its Python call
            // returns, and this call finishes before it does, so this is the only
            // access. Stepping is refused here (see `step`), so the borrow does not nest.
            let sim = unsafe { &mut *sim };
            return guarded(py, || f(sim));
        }
        // Without the GIL: a step on another thread may need it for its hooks.
        let caught = py.detach(|| {
            let mut sim = lock(&self.sim);
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(&mut sim)))
        });
        outcome(py, caught)
    }

    /// Refuses the call if the simulation was lost (see [`mark_lost`](Self::mark_lost)):
    /// an `ars.SimulationError` naming why.
    pub(crate) fn check_not_lost(&self, py: Python<'_>) -> PyResult<()> {
        match self.lost.get() {
            Some(why) => Err(raise(py, "SimulationError", format!("this simulation is gone: {why}; build a new one"))),
            None => Ok(()),
        }
    }

    /// Records that the simulation was lost (`sim` holds a stand-in): every later call
    /// is refused with `why`. Call it while holding the lock of `sim`.
    pub(crate) fn mark_lost(&self, why: String) {
        let _ = self.lost.set(why);
    }

    /// Whether a Python hook of this simulation is running on this thread (the
    /// simulation is then locked by this thread's step).
    pub(crate) fn in_own_hook(&self) -> bool {
        self.context.current().is_some()
    }

    /// The simulation, locked (call it without the GIL, and never from one of its own
    /// hooks: see [`in_own_hook`](Self::in_own_hook)).
    pub(crate) fn locked(&self) -> MutexGuard<'_, Simulation> {
        lock(&self.sim)
    }

    /// Steps with the GIL released, unless a Python hook runs at every step; a Python
    /// hook's exception comes back unchanged.
    ///
    /// A Python hook takes the GIL back at every step: stepping while holding it then
    /// spares two hand-overs of the GIL per step, and other Python threads still run
    /// during the hooks' Python code (the interpreter switches threads there). When
    /// the simulation is busy on another thread, this waits for it without the GIL.
    pub(crate) fn advance(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation) -> ars_core::Result<()> + Send,
    ) -> PyResult<()> {
        self.check_not_lost(py)?;
        if self.context.current().is_some() {
            return Err(raise(py, "BusyError", "a hook cannot step the simulation it runs in".into()));
        }
        let held = if self.runs_python_every_step() {
            match self.sim.try_lock() {
                Ok(sim) => Some(sim),
                Err(TryLockError::Poisoned(poisoned)) => Some(poisoned.into_inner()),
                Err(TryLockError::WouldBlock) => None,
            }
        } else {
            None
        };
        let result = match held {
            Some(mut sim) => guarded(py, || f(&mut sim)),
            None => self.with(py, f),
        };
        match lock(&self.context.raised).take() {
            Some(e) => Err(e),
            None => result,
        }
    }

    /// Takes `n` steps on the calling thread, which holds no GIL (Python hooks take
    /// it back), asking `stop` before each step; what `ars.step_many` runs on its
    /// threads. The outcome goes to [`stepped`](Self::stepped), with the GIL.
    pub(crate) fn step_detached(
        &self,
        n: u64,
        stop: impl FnMut() -> bool,
    ) -> std::thread::Result<ars_core::Result<()>> {
        if let Some(why) = self.lost.get() {
            return Ok(Err(Error::User(format!("this simulation is gone: {why}; build a new one"))));
        }
        let mut sim = lock(&self.sim);
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| sim.step_n_until(n, stop)))
    }

    /// The exception a Python hook of this simulation raised and nobody took yet
    /// (taken: a later call does not see it).
    pub(crate) fn take_hook_exception(&self) -> Option<PyErr> {
        lock(&self.context.raised).take()
    }

    /// The exception for the outcome of [`step_detached`](Self::step_detached): the
    /// one a Python hook raised, unchanged, else the ARS error or panic, if any.
    pub(crate) fn stepped(&self, py: Python<'_>, caught: std::thread::Result<ars_core::Result<()>>) -> PyResult<()> {
        let result = outcome(py, caught);
        match lock(&self.context.raised).take() {
            Some(e) => Err(e),
            None => result,
        }
    }

    fn add_body(
        &self,
        py: Python<'_>,
        shape: Shape,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        let spec = match (mass, density) {
            (Some(_), Some(_)) => {
                return Err(raise(py, "InputError", "both mass and density were given: give one".into()));
            }
            (Some(m), None) => MassSpec::solid(shape.clone(), Mass::Total(m)),
            (None, Some(d)) => MassSpec::solid(shape.clone(), Mass::Density(d)),
            // ODE's default body, as the original made it.
            (None, None) => MassSpec::Custom { mass: 1.0, inertia: Matrix3::identity() },
        };
        self.with(py, move |sim| {
            let id = sim.scene_mut().add_body_with_mass(shape, Point3::from(center), spec)?;
            name_object(sim, id, name)
        })
    }

    pub(crate) fn object_id(sim: &Simulation, name: &str) -> ars_core::Result<ObjectId> {
        Ok(sim.scene().object(name)?.id())
    }

    fn end(sim: &Simulation, name: Option<&str>) -> ars_core::Result<JointEnd> {
        Ok(match name {
            Some(n) => JointEnd::Object(Self::object_id(sim, n)?),
            None => JointEnd::World,
        })
    }
}

/// Renames a new object if a name is given; returns its name.
fn name_object(sim: &mut Simulation, id: ObjectId, name: Option<String>) -> ars_core::Result<String> {
    if let Some(name) = name
        && let Err(e) = sim.scene_mut().set_name(id, &name)
    {
        sim.remove_object(id)?;
        return Err(e);
    }
    Ok(sim.scene().object(id)?.name().to_string())
}

#[pymethods]
impl PySimulation {
    /// A simulation with the ARS defaults (Y up, g = 9.81 m/s², time step 0.4 ms, ERP
    /// 0.2, CFM 1e-10), any of which can be given.
    #[new]
    #[pyo3(signature = (*, time_step=None, gravity=None, erp=None, cfm=None, steps_per_frame=None, space=None,
                        stepper=None, quick_iterations=None, seed=None))]
    fn new(
        py: Python<'_>,
        time_step: Option<f64>,
        gravity: Option<Vec3>,
        erp: Option<f64>,
        cfm: Option<f64>,
        steps_per_frame: Option<Int>,
        space: Option<&str>,
        stepper: Option<&str>,
        quick_iterations: Option<Int>,
        seed: Option<Int>,
    ) -> PyResult<Self> {
        let steps_per_frame: Option<u32> = steps_per_frame.map(|n| count(py, "steps_per_frame", n)).transpose()?;
        let quick_iterations: Option<u32> = quick_iterations.map(|n| count(py, "quick_iterations", n)).transpose()?;
        let seed: Option<u32> = seed.map(|n| count(py, "the seed", n)).transpose()?;
        let space = space.map(crate::kinds::space).transpose().map_err(|(class, e)| raise(py, class, e))?;
        let stepper = crate::kinds::stepper(stepper, quick_iterations).map_err(|(class, e)| raise(py, class, e))?;
        let sim = guarded(py, || {
            let mut b = Simulation::builder().stepper(stepper);
            if let Some(space) = space {
                b = b.space(space);
            }
            if let Some(seed) = seed {
                b = b.seed(seed);
            }
            if let Some(dt) = time_step {
                b = b.time_step(dt);
            }
            if let Some(g) = gravity {
                b = b.gravity(Vector3::from(g));
            }
            if let Some(e) = erp {
                b = b.erp(e);
            }
            if let Some(c) = cfm {
                b = b.cfm(c);
            }
            if let Some(n) = steps_per_frame {
                b = b.steps_per_frame(n);
            }
            b.build()
        })?;
        Ok(PySimulation::wrap(sim))
    }

    fn __reduce__(&self) -> PyResult<()> {
        Err(PyTypeError::new_err(
            "an ars.Simulation cannot be pickled: send parameters and build the simulation where it runs \
             (ars.sweep does this for parameter sweeps)",
        ))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        self.with(py, |sim| {
            Ok(format!(
                "<ars.Simulation t={} s, {} objects, {} joints>",
                sim.scene().time(),
                sim.scene().objects().count(),
                sim.scene().joints().count()
            ))
        })
    }

    /// Simulated time, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> PyResult<f64> {
        self.with(py, |sim| Ok(sim.scene().time()))
    }

    /// Steps taken.
    #[getter]
    fn step_count(&self, py: Python<'_>) -> PyResult<u64> {
        self.with(py, |sim| Ok(sim.scene().step_count()))
    }

    /// The time step, s.
    #[getter]
    fn time_step(&self, py: Python<'_>) -> PyResult<f64> {
        self.with(py, |sim| Ok(sim.scene().time_step()))
    }

    /// Gravity, m/s², as a tuple.
    #[getter]
    fn gravity(&self, py: Python<'_>) -> PyResult<(f64, f64, f64)> {
        self.with(py, |sim| {
            let g = sim.scene().world().gravity();
            Ok((g.x, g.y, g.z))
        })
    }

    /// Sets gravity, m/s².
    #[setter]
    fn set_gravity(&self, py: Python<'_>, gravity: Vec3) -> PyResult<()> {
        self.with(py, move |sim| sim.scene_mut().world_mut().set_gravity(Vector3::from(gravity)))
    }

    /// Changes the time step for the next steps, s.
    #[setter]
    fn set_time_step(&self, py: Python<'_>, dt: f64) -> PyResult<()> {
        self.with(py, move |sim| sim.scene_mut().set_time_step(dt))
    }

    /// Steps per frame (of `show`, of the original's programs and of hooks per frame).
    #[getter]
    fn steps_per_frame(&self, py: Python<'_>) -> PyResult<u32> {
        self.with(py, |sim| Ok(sim.scene().steps_per_frame()))
    }

    /// Frames started so far.
    #[getter]
    fn frame_count(&self, py: Python<'_>) -> PyResult<u64> {
        self.with(py, |sim| Ok(sim.scene().frame_count()))
    }

    /// The global error reduction parameter (ERP), in [0, 1].
    #[getter]
    fn erp(&self, py: Python<'_>) -> PyResult<f64> {
        self.with(py, |sim| Ok(sim.scene().world().erp()))
    }

    #[setter]
    fn set_erp(&self, py: Python<'_>, erp: f64) -> PyResult<()> {
        self.with(py, move |sim| sim.scene_mut().world_mut().set_erp(erp))
    }

    /// The global constraint force mixing (CFM), ≥ 0.
    #[getter]
    fn cfm(&self, py: Python<'_>) -> PyResult<f64> {
        self.with(py, |sim| Ok(sim.scene().world().cfm()))
    }

    #[setter]
    fn set_cfm(&self, py: Python<'_>, cfm: f64) -> PyResult<()> {
        self.with(py, move |sim| sim.scene_mut().world_mut().set_cfm(cfm))
    }

    /// The broad phase that finds the pairs of geoms that may touch, chosen when the
    /// simulation is made (`Simulation(space=...)`): `"grid"` (the default, ARS's own:
    /// linear in the geoms; docs/python.md gives measured times),
    /// `"sweep_and_prune"` (ODE's), `"hash"` (a hash grid; up to 100,000 geoms) or
    /// `"simple"` (every pair, as the original ARS: its programs keep
    /// it, to give the original's numbers bit for bit).
    #[getter]
    fn space(&self, py: Python<'_>) -> PyResult<String> {
        self.with(py, |sim| Ok(crate::kinds::space_name(sim.scene().space_kind())))
    }

    /// The stepper: `"exact"` (`dWorldStep`, the ARS default) or `"quick"`
    /// (`dWorldQuickStep`, iterative, faster on large scenes, approximate).
    #[getter]
    fn stepper(&self, py: Python<'_>) -> PyResult<String> {
        self.with(py, |sim| Ok(crate::kinds::stepper_name(sim.scene().world().stepper())))
    }

    /// Chooses the stepper for the next steps: `"exact"` or `"quick"` with
    /// `quick_iterations` iterations per step (default 20).
    #[pyo3(signature = (stepper, quick_iterations=None))]
    fn set_stepper(&self, py: Python<'_>, stepper: &str, quick_iterations: Option<Int>) -> PyResult<()> {
        let quick_iterations: Option<u32> = quick_iterations.map(|n| count(py, "quick_iterations", n)).transpose()?;
        let stepper =
            crate::kinds::stepper(Some(stepper), quick_iterations).map_err(|(class, e)| raise(py, class, e))?;
        self.with(py, move |sim| sim.scene_mut().world_mut().set_stepper(stepper))
    }

    /// Seeds the world's own random generator (used by ODE's QuickStep; each world
    /// keeps its own, so a run steps the same in any process).
    fn set_seed(&self, py: Python<'_>, seed: Int) -> PyResult<()> {
        let seed: u32 = count(py, "the seed", seed)?;
        self.with(py, move |sim| {
            sim.scene_mut().world_mut().set_random_seed(seed);
            Ok(())
        })
    }

    /// Takes `n` steps (in native code, without the GIL unless a Python hook runs).
    /// Ctrl-C stops it between two steps with `KeyboardInterrupt`; the simulation can
    /// be stepped on.
    #[pyo3(signature = (n=Checked(1)))]
    fn step(&self, py: Python<'_>, n: Int) -> PyResult<()> {
        let n: u64 = count(py, "the number of steps", n)?;
        let context = Arc::clone(&self.context);
        self.advance(py, move |sim| sim.step_n_until(n, python_signals(&context.raised)))
    }

    /// Runs for `duration` seconds of simulated time (whole steps). Ctrl-C stops it
    /// between two frames with `KeyboardInterrupt`; the simulation can be run on.
    fn run(&self, py: Python<'_>, duration: f64) -> PyResult<()> {
        let context = Arc::clone(&self.context);
        self.advance(py, move |sim| sim.run_for_until(duration, python_signals(&context.raised)))
    }

    /// Sets the control of the actuator called `name` (an MJCF `<motor>`,
    /// `<position>` or `<velocity>`), clamped to its control range and held until set
    /// again: MuJoCo's `data.ctrl`.
    fn set_control(&self, py: Python<'_>, name: &str, ctrl: f64) -> PyResult<()> {
        self.with(py, |sim| sim.scene_mut().set_control(name, ctrl))
    }

    /// The control of the actuator called `name`.
    fn control(&self, py: Python<'_>, name: &str) -> PyResult<f64> {
        self.with(py, |sim| sim.scene().control(name))
    }

    /// The names of the actuators, in the order they were made: an MJCF file's order,
    /// MuJoCo's `data.ctrl` order.
    #[getter]
    fn actuators(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.with(py, |sim| Ok(sim.scene().actuators().map(|(name, _)| name.to_string()).collect()))
    }

    /// Sets every actuator's control at once (MuJoCo's whole `data.ctrl`): `ctrl[i]`
    /// is the control of `actuators[i]`, clamped to its range. A sequence (or numpy
    /// array) of another length, or a value that is not finite, is an
    /// `ars.InputError` and no control changes.
    fn set_controls(&self, py: Python<'_>, ctrl: Vec<f64>) -> PyResult<()> {
        self.with(py, |sim| sim.scene_mut().set_controls(&ctrl))
    }

    /// Every actuator's control, in `actuators` order.
    #[getter]
    fn controls(&self, py: Python<'_>) -> PyResult<Vec<f64>> {
        self.with(py, |sim| Ok(sim.scene().controls()))
    }

    /// Runs one frame: `steps_per_frame` steps, with the hooks per frame.
    fn step_frame(&self, py: Python<'_>) -> PyResult<()> {
        self.advance(py, |sim| sim.step_frame())
    }

    /// The names of the objects, in alphabetical order.
    #[getter]
    fn objects(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.with(py, |sim| Ok(sim.scene().objects().map(|(n, _)| n.to_string()).collect()))
    }

    /// The names of the joints, in alphabetical order.
    #[getter]
    fn joints(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.with(py, |sim| Ok(sim.scene().joints().map(|(n, _)| n.to_string()).collect()))
    }

    /// Calls `function()` before every step (after the earlier hooks); returns an id
    /// for `remove_hook`. An exception it raises stops the step and comes out of
    /// `step`/`run` unchanged.
    fn add_pre_step(&self, py: Python<'_>, function: Py<PyAny>) -> PyResult<u64> {
        self.add_hook(py, function, false)
    }

    /// Calls `function()` after every step; see `add_pre_step`.
    fn add_post_step(&self, py: Python<'_>, function: Py<PyAny>) -> PyResult<u64> {
        self.add_hook(py, function, true)
    }

    /// Removes a hook added with `add_pre_step` or `add_post_step`.
    fn remove_hook(&self, py: Python<'_>, hook: Int) -> PyResult<()> {
        let hook = hook.0;
        let Some((id, _)) = u64::try_from(hook).ok().and_then(|key| lock(&self.hooks).remove(&key)) else {
            return Err(unknown_hook(py, hook));
        };
        self.with(py, move |sim| sim.remove_hooks(id).map(drop))
    }

    /// Turns a hook added with `add_pre_step` or `add_post_step` off (skipped at each
    /// step without taking the GIL) or back on; for `ars.model`, whose post-step hook
    /// is off while no one listens to its post-step signal.
    fn _enable_hook(&self, py: Python<'_>, hook: Int, enabled: bool) -> PyResult<()> {
        let hook = hook.0;
        let hooks = lock(&self.hooks);
        let Some((_, switch)) = u64::try_from(hook).ok().and_then(|key| hooks.get(&key)) else {
            return Err(unknown_hook(py, hook));
        };
        switch.store(enabled, Ordering::Relaxed);
        Ok(())
    }
}

impl PySimulation {
    fn add_hook(&self, py: Python<'_>, function: Py<PyAny>, after_step: bool) -> PyResult<u64> {
        if !function.bind(py).is_callable() {
            return Err(raise(py, "InputError", "a hook must be callable".into()));
        }
        let enabled = Arc::new(AtomicBool::new(true));
        let hook = PyHook { callable: function, after_step, context: self.context.clone(), enabled: enabled.clone() };
        let id = self.with(py, move |sim| sim.add_hooks(hook))?;
        let mut next = lock(&self.next_hook);
        let key = *next;
        *next += 1;
        lock(&self.hooks).insert(key, (id, enabled));
        Ok(key)
    }
}

/// The error for a hook id this simulation does not have.
fn unknown_hook(py: Python<'_>, hook: i64) -> PyErr {
    raise(py, "UnknownNameError", format!("no hook {hook} in this simulation (removed, or never added)"))
}
