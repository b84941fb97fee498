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
use std::sync::{Arc, Mutex, MutexGuard, PoisonError, TryLockError};
use std::time::{Duration, Instant};

use ars_core::body::MassSpec;
use ars_core::nalgebra::{Matrix3, Point3, Vector3};
use ars_core::{Error, HookId, HookPoint, Hooks, JointEnd, Mass, ObjectId, Shape, Simulation};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::{count, guarded, outcome, raise};
use crate::views::{Body, Joint};

/// A vector given as any sequence of three numbers.
pub(crate) type Vec3 = [f64; 3];

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
const SIGNAL_CHECK_PERIOD: Duration = Duration::from_millis(5);

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
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => false,
            Err(e) => {
                *lock(raised) = Some(e);
                true
            }
        }
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
        }
    }

    /// Runs `f` on the simulation: the one a hook on this thread was handed, else the
    /// locked one (waiting without the GIL). ARS errors and panics become exceptions.
    pub(crate) fn with<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
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
        let mut sim = lock(&self.sim);
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| sim.step_n_until(n, stop)))
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

    fn object_id(sim: &Simulation, name: &str) -> ars_core::Result<ObjectId> {
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
        steps_per_frame: Option<i64>,
        space: Option<&str>,
        stepper: Option<&str>,
        quick_iterations: Option<i64>,
        seed: Option<i64>,
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
    /// linear in the geoms; 10,000 spaced spheres 2.6 ms a step, 100,000 67 ms),
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
    fn set_stepper(&self, py: Python<'_>, stepper: &str, quick_iterations: Option<i64>) -> PyResult<()> {
        let quick_iterations: Option<u32> = quick_iterations.map(|n| count(py, "quick_iterations", n)).transpose()?;
        let stepper =
            crate::kinds::stepper(Some(stepper), quick_iterations).map_err(|(class, e)| raise(py, class, e))?;
        self.with(py, move |sim| sim.scene_mut().world_mut().set_stepper(stepper))
    }

    /// Seeds the world's own random generator (used by ODE's QuickStep; each world
    /// keeps its own, so a run steps the same in any process).
    fn set_seed(&self, py: Python<'_>, seed: i64) -> PyResult<()> {
        let seed: u32 = count(py, "the seed", seed)?;
        self.with(py, move |sim| {
            sim.scene_mut().world_mut().set_random_seed(seed);
            Ok(())
        })
    }

    /// Takes `n` steps (in native code, without the GIL unless a Python hook runs).
    /// Ctrl-C stops it between two steps with `KeyboardInterrupt`; the simulation can
    /// be stepped on.
    #[pyo3(signature = (n=1))]
    fn step(&self, py: Python<'_>, n: i64) -> PyResult<()> {
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

    /// Opens a window on the simulation and runs it in real time until the window is
    /// closed (or for `duration` wall seconds, or until it has run `frames` frames, the
    /// last one drawn): mouse to turn the camera, space to pause, `g` for the panel
    /// (speed, plots of the sensors, joints), escape to quit.
    /// Needs a display; returns what the run measured (frames, seconds, real-time
    /// factor). Off screen, use `ars.Renderer`.
    #[pyo3(signature = (duration=None, *, frames=None, title="ARS".to_string(), size=(1024, 768), camera=[10.0, 8.0, 10.0], look_at=[0.0; 3], background=[1.0; 3], follow=None, quality="auto".to_string(), axes=false))]
    fn show(
        slf: &Bound<'_, Self>,
        duration: Option<f64>,
        frames: Option<i64>,
        title: String,
        size: (i64, i64),
        camera: Vec3,
        look_at: Vec3,
        background: Vec3,
        follow: Option<String>,
        quality: String,
        axes: bool,
    ) -> PyResult<Py<pyo3::types::PyDict>> {
        let view = crate::viewer::ViewArgs { title, size, camera, look_at, background, follow, quality, axes };
        crate::viewer::show(slf.py(), slf.clone().unbind(), None, duration, frames, view)
    }

    /// Runs for `duration` seconds of simulated time and writes a browser replay of
    /// it to `path` (`None`: kept in memory): one self-contained HTML file (no network
    /// needed) with every object's shape, colour and pose, `fps` samples a second
    /// (default: the frame rate), and plots of the sensor columns `plots` names
    /// (`"Gps 1: y"`: the sensor's type, its number from 1, its column). The camera
    /// starts as a `Renderer`'s with the same keywords. Returns an `ars.Replay`, which
    /// a notebook shows inline. Bad settings are refused before the run, and no file
    /// is left.
    #[pyo3(signature = (path, duration, *, fps=None, plots=Vec::new(), size=(640, 480), camera=[10.0, 8.0, 10.0], look_at=[0.0; 3], background=[1.0; 3], title="ARS".to_string()))]
    fn save_replay(
        &self,
        py: Python<'_>,
        path: Option<std::path::PathBuf>,
        duration: f64,
        fps: Option<f64>,
        plots: Vec<String>,
        size: (i64, i64),
        camera: Vec3,
        look_at: Vec3,
        background: Vec3,
        title: String,
    ) -> PyResult<Py<PyAny>> {
        let view = crate::viewer::ViewArgs::for_replay(title, size, camera, look_at, background);
        crate::replay::record(py, self, path, crate::replay::ReplayArgs { duration, fps, plots, view })
    }

    /// As `save_replay` (the same keywords), kept in memory: an `ars.Replay` to show
    /// in a notebook (or save later).
    #[pyo3(signature = (duration, **options))]
    fn replay(
        slf: &Bound<'_, Self>,
        duration: f64,
        options: Option<&Bound<'_, pyo3::types::PyDict>>,
    ) -> PyResult<Py<PyAny>> {
        Ok(slf.call_method("save_replay", (None::<std::path::PathBuf>, duration), options)?.unbind())
    }

    /// A sphere of `radius` (m) centred at `center`, of total `mass` (kg) or
    /// `density` (kg/m³) (neither: ODE's default body, 1 kg with unit inertia); returns
    /// its name.
    #[pyo3(signature = (radius, center=[0.0; 3], mass=None, density=None, *, name=None))]
    fn add_sphere(
        &self,
        py: Python<'_>,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Sphere { radius }, center, mass, density, name)
    }

    /// A box of full edge lengths `size` (m); see `add_sphere`.
    #[pyo3(signature = (size, center=[0.0; 3], mass=None, density=None, *, name=None))]
    fn add_box(
        &self,
        py: Python<'_>,
        size: Vec3,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Box { edges: Vector3::from(size) }, center, mass, density, name)
    }

    /// A cylinder of `length` and `radius` (m) along its local Z; see `add_sphere`.
    #[pyo3(signature = (length, radius, center=[0.0; 3], mass=None, density=None, *, name=None))]
    fn add_cylinder(
        &self,
        py: Python<'_>,
        length: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Cylinder { radius, length }, center, mass, density, name)
    }

    /// A capsule: a cylinder of `length` (without its caps) and `radius` (m) along its
    /// local Z, capped by hemispheres; see `add_sphere`.
    #[pyo3(signature = (length, radius, center=[0.0; 3], mass=None, density=None, *, name=None))]
    fn add_capsule(
        &self,
        py: Python<'_>,
        length: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Capsule { radius, length }, center, mass, density, name)
    }

    /// A cone of `height` and base `radius` (m) along its local Z, `center` its centre
    /// of mass; see `add_sphere`.
    #[pyo3(signature = (height, radius, center=[0.0; 3], mass=None, density=None, *, name=None))]
    fn add_cone(
        &self,
        py: Python<'_>,
        height: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Cone { radius, height }, center, mass, density, name)
    }

    /// A static plane `normal · x = dist` (the floor); returns its name.
    #[pyo3(signature = (normal=[0.0, 1.0, 0.0], dist=0.0, *, name=None))]
    fn add_floor(&self, py: Python<'_>, normal: Vec3, dist: f64, name: Option<String>) -> PyResult<String> {
        self.with(py, move |sim| {
            let id = sim.scene_mut().add_floor_plane(Vector3::from(normal), dist)?;
            name_object(sim, id, name)
        })
    }

    /// A static triangle mesh (`vertices`: points; `faces`: index triples) at `center`.
    #[pyo3(signature = (vertices, faces, center=[0.0; 3], *, name=None))]
    fn add_trimesh(
        &self,
        py: Python<'_>,
        vertices: Vec<Vec3>,
        faces: Vec<[i64; 3]>,
        center: Vec3,
        name: Option<String>,
    ) -> PyResult<String> {
        let index = |i| count::<u32>(py, "a face's vertex index", i);
        let faces =
            faces.into_iter().map(|[a, b, c]| Ok([index(a)?, index(b)?, index(c)?])).collect::<PyResult<Vec<_>>>()?;
        self.with(py, move |sim| {
            let shape = Shape::TriMesh { vertices: vertices.into_iter().map(Point3::from).collect(), triangles: faces };
            let pose = ars_core::nalgebra::Isometry3::translation(center[0], center[1], center[2]);
            let id = sim.scene_mut().add_static(shape, pose)?;
            name_object(sim, id, name)
        })
    }

    /// A rotary joint (hinge) named `name` between objects `obj1` and `obj2` (`None`:
    /// the world) about the world `axis` through `anchor` (default: `obj2`'s position,
    /// or `obj1`'s when joined to the world).
    #[pyo3(signature = (name, obj1, obj2, anchor=None, axis=[0.0, 0.0, 1.0]))]
    fn add_rotary_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Option<Vec3>,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_hinge_joint(name, a, b, anchor.map(Point3::from), Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A slider along the world `axis`.
    fn add_slider_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_slider_joint(name, a, b, Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A ball-and-socket joint at `anchor` (default: `obj2`'s position).
    #[pyo3(signature = (name, obj1, obj2, anchor=None))]
    fn add_ball_socket_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Option<Vec3>,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_ball_joint(name, a, b, anchor.map(Point3::from))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A universal joint at `anchor` with perpendicular world axes `axis1` (on `obj1`)
    /// and `axis2` (on `obj2`).
    fn add_universal_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Vec3,
        axis1: Vec3,
        axis2: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_universal_joint(
                name,
                a,
                b,
                Point3::from(anchor),
                Vector3::from(axis1),
                Vector3::from(axis2),
            )?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A fixed joint: locks `obj1`'s pose relative to `obj2` (or the world) as it is.
    fn add_fixed_joint(&self, py: Python<'_>, name: &str, obj1: &str, obj2: Option<&str>) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_fixed_joint(name, a, b)?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// The first thing a ray from `origin` along `direction` meets within `length`
    /// (m): `(distance, point)`, or `None`.
    fn cast_ray(&self, py: Python<'_>, origin: Vec3, direction: Vec3, length: f64) -> PyResult<Option<RayHit>> {
        self.with(py, move |sim| {
            let direction = Vector3::from(direction);
            let norm = direction.norm();
            let direction = if norm > 0.0 { direction / norm } else { direction };
            let ray = ars_core::world::raycast::Ray { origin: Point3::from(origin), direction };
            let hit = sim.scene().world().cast_ray(ray, length, None)?;
            Ok(hit.map(|h| (h.distance, (h.position.x, h.position.y, h.position.z))))
        })
    }

    /// Loads a robot from a URDF file (Z up unless `y_up`; see the Rust
    /// `Scene::load_urdf` for the rules). Returns `{"name", "links", "joints",
    /// "base_joint"}`, links and joints by their URDF names in file order.
    #[pyo3(signature = (path, *, fixed_base=false, base_position=[0.0; 3], self_collision=false, y_up=false,
                        initial_positions=None, packages=None, search_paths=None, ignore_visuals=false))]
    fn load_urdf<'py>(
        &self,
        py: Python<'py>,
        path: std::path::PathBuf,
        fixed_base: bool,
        base_position: Vec3,
        self_collision: bool,
        y_up: bool,
        initial_positions: Option<HashMap<String, f64>>,
        packages: Option<HashMap<String, std::path::PathBuf>>,
        search_paths: Option<Vec<std::path::PathBuf>>,
        ignore_visuals: bool,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let mut options = ars_core::UrdfOptions::new()
            .fixed_base(fixed_base)
            .self_collision(self_collision)
            .ignore_visuals(ignore_visuals)
            .base_pose(ars_core::nalgebra::Isometry3::translation(
                base_position[0],
                base_position[1],
                base_position[2],
            ));
        if y_up {
            options = options.up_axis(ars_core::UpAxis::Y);
        }
        let mut positions: Vec<(String, f64)> = initial_positions.unwrap_or_default().into_iter().collect();
        positions.sort_by(|a, b| a.0.cmp(&b.0));
        for (name, q) in positions {
            options = options.initial_position(&name, q);
        }
        for (name, dir) in packages.unwrap_or_default() {
            options = options.package(&name, dir);
        }
        for dir in search_paths.unwrap_or_default() {
            options = options.search_path(dir);
        }
        let (name, links, joints, base) = self.with(py, move |sim| {
            let robot = sim.load_urdf(&path, &options)?;
            let base = robot.base_joint.map(|id| sim.scene().joint(id).map(|j| j.name().to_string())).transpose()?;
            let links: Vec<String> = robot.links.into_iter().map(|(n, _)| n).collect();
            let joints: Vec<String> = robot.joints.into_iter().map(|(n, _)| n).collect();
            Ok((robot.name, links, joints, base))
        })?;
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("name", name)?;
        dict.set_item("links", links)?;
        dict.set_item("joints", joints)?;
        dict.set_item("base_joint", base)?;
        Ok(dict)
    }

    /// Loads a MuJoCo model from an MJCF file (see the Rust `Scene::load_mjcf` for what
    /// is read). Returns `{"name", "bodies", "joints", "timestep", "gravity",
    /// "actuators", "sensors", "sites", "armature", "skipped"}`: bodies and joints by
    /// their MJCF names in file order, the file's time step and gravity (not applied),
    /// the file's sensors made (`ars.Sensor`s by name; see the Rust `MjcfSensor` for the
    /// columns that hold MuJoCo's values), the bodies' named sites (`{name: body}`), the
    /// inertia (3×3, body frame) each object carries for its joint's armature, what was
    /// skipped.
    #[pyo3(signature = (path, *, base_position=[0.0; 3], skip_unsupported=false))]
    fn load_mjcf<'py>(
        slf: Bound<'py, Self>,
        path: std::path::PathBuf,
        base_position: Vec3,
        skip_unsupported: bool,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let py = slf.py();
        let [x, y, z] = base_position;
        let options = ars_core::MjcfOptions::new()
            .base_pose(ars_core::nalgebra::Isometry3::translation(x, y, z))
            .skip_unsupported(skip_unsupported);
        let model = slf.get().with(py, move |sim| sim.load_mjcf(&path, &options))?;
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("name", &model.name)?;
        dict.set_item("bodies", model.bodies.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>())?;
        dict.set_item("joints", model.joints.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>())?;
        dict.set_item("timestep", model.timestep)?;
        dict.set_item("gravity", model.gravity.map(|g| (g.x, g.y, g.z)))?;
        let actuators: Vec<(String, String, String)> =
            model.actuators.iter().map(|a| (a.name.clone(), a.kind.clone(), a.joint.clone())).collect();
        dict.set_item("actuators", actuators)?;
        let sensors = pyo3::types::PyDict::new(py);
        for sensor in &model.sensors {
            let Some(id) = sensor.id else { continue };
            let kind = match sensor.kind.as_str() {
                "jointpos" => "joint_positions",
                "jointvel" => "joint_velocities",
                "framepos" => "gps",
                "framelinvel" => "velometer",
                "framequat" => "orientation",
                "accelerometer" | "gyro" => "imu",
                "touch" => "touch",
                _ => "laser",
            };
            let typed = crate::sensors::Typed::Table(id);
            sensors.set_item(&sensor.name, crate::sensors::PySensor::new(slf.clone().unbind(), kind.into(), typed))?;
        }
        dict.set_item("sensors", sensors)?;
        let sites = pyo3::types::PyDict::new(py);
        for site in &model.sites {
            sites.set_item(&site.name, &site.body)?;
        }
        dict.set_item("sites", sites)?;
        let armature = pyo3::types::PyDict::new(py);
        for (name, inertia) in &model.armature {
            let rows: Vec<Vec<f64>> = (0..3).map(|r| (0..3).map(|c| inertia[(r, c)]).collect()).collect();
            armature.set_item(name, rows)?;
        }
        dict.set_item("armature", armature)?;
        dict.set_item("skipped", &model.skipped)?;
        Ok(dict)
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

    /// The names of the actuators, in joint order.
    #[getter]
    fn actuators(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.with(py, |sim| Ok(sim.scene().actuators().map(|(name, _)| name.to_string()).collect()))
    }

    /// A piston: slides along and turns about the world `axis` through `anchor`.
    #[pyo3(signature = (name, obj1, obj2, anchor, axis))]
    fn add_piston_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Vec3,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_piston_joint(name, a, b, Point3::from(anchor), Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// Removes the object `name` with its body and geoms; the joints attached to it go
    /// too, and the sensors reading it stop sampling (`Sensor.detached`). Its name can
    /// be used again.
    fn remove_object(&self, py: Python<'_>, name: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let id = Self::object_id(sim, name)?;
            sim.remove_object(id)
        })
    }

    /// Removes the joint `name`; the sensors reading it stop sampling.
    fn remove_joint(&self, py: Python<'_>, name: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let id = sim.scene().joint(name)?.id();
            sim.remove_joint(id)
        })
    }

    /// Sets the contact surface: of every pair of objects (`between=None`, the world's
    /// default), or of the contacts between the two objects `between=("a", "b")` only.
    /// The fields not given take the ARS defaults (not their current values):
    /// `mu=500` (N per contact point and direction, ODE's box friction; with
    /// `approx1=True` a Coulomb coefficient; `math.inf`: never slips), `mu2` (another
    /// limit for the second direction), `bounce=0.2` above `bounce_velocity=0` m/s,
    /// `soft_erp`/`soft_cfm` (soft contacts; else the world's), `max_contacts=150`
    /// points per pair.
    #[pyo3(signature = (between=None, *, mu=500.0, mu2=None, bounce=0.2, bounce_velocity=0.0, soft_erp=None,
                        soft_cfm=None, approx1=false, max_contacts=150))]
    fn set_contact_surface(
        &self,
        py: Python<'_>,
        between: Option<(String, String)>,
        mu: f64,
        mu2: Option<f64>,
        bounce: f64,
        bounce_velocity: f64,
        soft_erp: Option<f64>,
        soft_cfm: Option<f64>,
        approx1: bool,
        max_contacts: i64,
    ) -> PyResult<()> {
        let max_contacts: usize = count(py, "max_contacts", max_contacts)?;
        let surface = ars_core::ContactSurface {
            mu,
            mu2,
            bounce: Some((bounce, bounce_velocity)),
            soft_erp,
            soft_cfm,
            approx1,
            max_contacts,
        };
        self.with(py, move |sim| match between {
            None => sim.scene_mut().world_mut().set_default_surface(surface),
            Some((a, b)) => {
                let (a, b) = (Self::object_id(sim, &a)?, Self::object_id(sim, &b)?);
                sim.scene_mut().set_contact_surface(a, b, surface)
            }
        })
    }

    /// The contact surface of every pair (`between=None`) or of the pair `between`, as
    /// a dict of the keywords of `set_contact_surface`.
    #[pyo3(signature = (between=None))]
    fn contact_surface<'py>(
        &self,
        py: Python<'py>,
        between: Option<(String, String)>,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let s = self.with(py, move |sim| match between {
            None => Ok(sim.scene().world().default_surface()),
            Some((a, b)) => {
                let (a, b) = (Self::object_id(sim, &a)?, Self::object_id(sim, &b)?);
                sim.scene().contact_surface(a, b)
            }
        })?;
        let dict = pyo3::types::PyDict::new(py);
        let (bounce, bounce_velocity) = s.bounce.unwrap_or((0.0, 0.0));
        dict.set_item("mu", s.mu)?;
        dict.set_item("mu2", s.mu2)?;
        dict.set_item("bounce", bounce)?;
        dict.set_item("bounce_velocity", bounce_velocity)?;
        dict.set_item("soft_erp", s.soft_erp)?;
        dict.set_item("soft_cfm", s.soft_cfm)?;
        dict.set_item("approx1", s.approx1)?;
        dict.set_item("max_contacts", s.max_contacts)?;
        Ok(dict)
    }

    /// Gives the contacts between objects `a` and `b` the default surface again.
    fn clear_contact_surface(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().clear_contact_surface(a, b)
        })
    }

    /// Objects `a` and `b` never touch (MJCF's `<contact><exclude>`).
    fn exclude_contacts(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().exclude_contacts(a, b)
        })
    }

    /// Objects `a` and `b` touch again.
    fn include_contacts(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().include_contacts(a, b)
        })
    }

    /// The pairs of objects that never touch, by name.
    fn excluded_contacts(&self, py: Python<'_>) -> PyResult<Vec<(String, String)>> {
        self.with(py, |sim| {
            let name = |id| sim.scene().object(id).map(|o| o.name().to_string());
            sim.scene().excluded_contacts().into_iter().map(|(a, b)| Ok((name(a)?, name(b)?))).collect()
        })
    }

    /// Runs one frame: `steps_per_frame` steps, with the hooks per frame.
    fn step_frame(&self, py: Python<'_>) -> PyResult<()> {
        self.advance(py, |sim| sim.step_frame())
    }

    /// Runs `duration` seconds of simulated time off screen into an H.264 MP4 video at
    /// `path`: frame k is the picture at the first step at or after k/fps s (see
    /// `ars._native.VideoWriter` for frames one by one). A dict of what it holds.
    #[pyo3(signature = (path, duration, fps=30.0, size=(800, 600), *, camera=[10.0, 8.0, 10.0], look_at=[0.0; 3], background=[1.0; 3], follow=None, quality="auto".to_string(), axes=false))]
    fn record_video(
        &self,
        py: Python<'_>,
        path: std::path::PathBuf,
        duration: f64,
        fps: f64,
        size: (i64, i64),
        camera: Vec3,
        look_at: Vec3,
        background: Vec3,
        follow: Option<String>,
        quality: String,
        axes: bool,
    ) -> PyResult<Py<pyo3::types::PyDict>> {
        let view =
            crate::viewer::ViewArgs { title: "ARS".into(), size, camera, look_at, background, follow, quality, axes };
        crate::video::record_video(py, self, path, duration, fps, view)
    }

    /// Writes the scene (see `save_scene`) to the file `path`.
    fn save_scene_to(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        self.with(py, move |sim| sim.save_scene_to(&path))
    }

    /// The whole state of the simulation now, as bytes (picklable): `restore` puts it
    /// back, in this simulation or in one built by the same code (in any process), and
    /// every later step is the same to the bit. Hooks' own variables are not in it;
    /// records are cleared by `restore`.
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        let bytes = self.with(py, |sim| sim.snapshot().map(|s| s.to_bytes()))?;
        Ok(pyo3::types::PyBytes::new(py, &bytes))
    }

    /// Puts back the state `snapshot()` returned (see `snapshot`). A snapshot of
    /// another scene raises `ars.SnapshotMismatchError` and changes nothing.
    fn restore(&self, py: Python<'_>, state: &[u8]) -> PyResult<()> {
        let snapshot = guarded(py, || ars_core::Snapshot::from_bytes(state))?;
        self.with(py, move |sim| sim.restore(&snapshot))
    }

    /// A new simulation in the state `snapshot()` returned, built from the scene it
    /// holds (objects, joints, `add_sensor`'s sensors, lidars and depth cameras; a
    /// robot whose links have several collision shapes needs the scene built by your
    /// code, then `restore`).
    #[staticmethod]
    fn from_snapshot(py: Python<'_>, state: &[u8]) -> PyResult<Self> {
        let sim = guarded(py, || ars_core::Snapshot::from_bytes(state).and_then(|s| Simulation::from_snapshot(&s)))?;
        Ok(PySimulation::wrap(sim))
    }

    /// A simulation from a file written by `save_scene_to`.
    #[staticmethod]
    fn load_scene_from(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let sim = guarded(py, || Simulation::load_scene_from(&path))?;
        Ok(PySimulation::wrap(sim))
    }

    /// A simulation from any file ARS reads, by its extension: a scene file (`.json`), a
    /// URDF robot with its root at the origin over a floor (`.urdf`) or a MuJoCo model (`.xml`, `.mjcf`;
    /// what ARS cannot read is skipped, each with a `UserWarning`). What the viewer's
    /// Open button and `ars view FILE` open.
    #[staticmethod]
    fn open(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let opened = guarded(py, || Simulation::open(&path))?;
        for skipped in &opened.skipped {
            let message = std::ffi::CString::new(format!("skipped: {skipped}")).unwrap_or_default();
            PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &message, 1)?;
        }
        Ok(PySimulation::wrap(opened.simulation))
    }

    /// A lidar: `beams` beams per plane fanned over `fov` radians, seeing from
    /// `min_range` to `max_range` m, in its own X–Z plane (horizontal when upright in
    /// the Y-up world, azimuth from +X towards −Z) and the planes tilted by
    /// `planes` (elevations, rad). Mounted on the object `on` at `position` with
    /// `rotation` (3×3) relative to it (it does not see that object), or in the world.
    /// Scans after every step or every `every` seconds; `noise` adds seeded Gaussian
    /// noise of that standard deviation (m) to the ranges. `Sensor.ranges()` gives the
    /// scans as an array.
    #[pyo3(signature = (beams, fov, max_range, *, min_range=0.0, planes=None, on=None, position=[0.0; 3],
                        rotation=None, every=None, noise=None, seed=0))]
    fn add_lidar(
        slf: Bound<'_, Self>,
        beams: i64,
        fov: f64,
        max_range: f64,
        min_range: f64,
        planes: Option<Vec<f64>>,
        on: Option<String>,
        position: Vec3,
        rotation: Option<[[f64; 3]; 3]>,
        every: Option<f64>,
        noise: Option<f64>,
        seed: i64,
    ) -> PyResult<crate::sensors::PySensor> {
        let beams: u32 = count(slf.py(), "lidar beams", beams)?;
        let seed: u64 = count(slf.py(), "the seed", seed)?;
        let offset = crate::errors::guarded(slf.py(), || crate::views::pose(position, rotation))?;
        let spec =
            crate::sensors::LidarSpec { beams, fov, max_range, min_range, planes, on, offset, every, noise, seed };
        let id = slf.get().with(slf.py(), move |sim| spec.add_to(sim))?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), "lidar".into(), id))
    }

    /// A depth camera: `width` × `height` pixels over the vertical field of view `fov_y`
    /// (rad), depths from `near` to `far` m along its optical axis (its −Z, +Y up in the
    /// image). Mounted as `add_lidar`'s lidar. `Sensor.images()` gives the images as an
    /// array.
    #[pyo3(signature = (width, height, fov_y, near, far, *, on=None, position=[0.0; 3], rotation=None, every=None))]
    fn add_depth_camera(
        slf: Bound<'_, Self>,
        width: i64,
        height: i64,
        fov_y: f64,
        near: f64,
        far: f64,
        on: Option<String>,
        position: Vec3,
        rotation: Option<[[f64; 3]; 3]>,
        every: Option<f64>,
    ) -> PyResult<crate::sensors::PySensor> {
        let (width, height): (u32, u32) =
            (count(slf.py(), "image width", width)?, count(slf.py(), "image height", height)?);
        let offset = crate::errors::guarded(slf.py(), || crate::views::pose(position, rotation))?;
        let id = slf.get().with(slf.py(), move |sim| {
            let camera = ars_core::sensors::DepthCamera::new(width, height, fov_y, near, far)?;
            let camera = match on {
                Some(name) => camera.on(sim.scene().object(name.as_str())?.id(), offset),
                None => camera.at(offset),
            };
            crate::sensors::Typed::add(sim, camera, every, crate::sensors::Typed::Depth)
        })?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), "depth_camera".into(), id))
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

    /// The object named `name` (an unknown name raises `ars.UnknownNameError`, with the
    /// names spelled almost the same). Its attributes are copies, read when asked.
    fn body(slf: Bound<'_, Self>, name: &str) -> PyResult<Body> {
        slf.get().with(slf.py(), |sim| Self::object_id(sim, name))?;
        Ok(Body::new(slf.unbind(), name.to_string()))
    }

    /// The joint named `name`; see `body`.
    fn joint(slf: Bound<'_, Self>, name: &str) -> PyResult<Joint> {
        slf.get().with(slf.py(), |sim| sim.scene().joint(name).map(|_| ()))?;
        Ok(Joint::new(slf.unbind(), name.to_string()))
    }

    /// Declares a sensor of `kind` reading `target` (an object or joint name; a list of
    /// joint names for `"joint_positions"`; nothing for `"system_total_energy"`),
    /// sampled after every step or every `every` seconds; see `Sensor.records`.
    #[pyo3(signature = (kind, target=None, *, every=None))]
    fn add_sensor(
        slf: Bound<'_, Self>,
        kind: &str,
        target: Option<Bound<'_, PyAny>>,
        every: Option<f64>,
    ) -> PyResult<crate::sensors::PySensor> {
        let targets: Vec<String> = match target {
            None => Vec::new(),
            Some(t) => match t.extract::<String>() {
                Ok(name) => vec![name],
                Err(_) => t.extract::<Vec<String>>()?,
            },
        };
        let kind_owned = kind.to_string();
        let log = slf.get().with(slf.py(), move |sim| crate::sensors::declare(sim, &kind_owned, &targets, every))?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), kind.to_string(), crate::sensors::Typed::Table(log)))
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
    fn remove_hook(&self, py: Python<'_>, hook: i64) -> PyResult<()> {
        let Some((id, _)) = u64::try_from(hook).ok().and_then(|key| lock(&self.hooks).remove(&key)) else {
            return Err(unknown_hook(py, hook));
        };
        self.with(py, move |sim| sim.remove_hooks(id).map(drop))
    }

    /// Turns a hook added with `add_pre_step` or `add_post_step` off (skipped at each
    /// step without taking the GIL) or back on; for `ars.model`, whose post-step hook
    /// is off while no one listens to its post-step signal.
    fn _enable_hook(&self, py: Python<'_>, hook: i64, enabled: bool) -> PyResult<()> {
        let hooks = lock(&self.hooks);
        let Some((_, switch)) = u64::try_from(hook).ok().and_then(|key| hooks.get(&key)) else {
            return Err(unknown_hook(py, hook));
        };
        switch.store(enabled, Ordering::Relaxed);
        Ok(())
    }

    /// The scene as JSON text (objects, joints, parameters, state).
    fn save_scene(&self, py: Python<'_>) -> PyResult<String> {
        self.with(py, |sim| sim.save_scene())
    }

    /// A simulation from JSON text written by `save_scene`.
    #[staticmethod]
    fn load_scene(py: Python<'_>, text: &str) -> PyResult<Self> {
        let sim = guarded(py, || Simulation::load_scene(text))?;
        Ok(PySimulation::wrap(sim))
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
