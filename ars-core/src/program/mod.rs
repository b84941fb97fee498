//! The `Program` flow of the original ARS: a program builds its objects, hooks into
//! the step loop and maps keys to actions; it runs headless here, or in a window with
//! the viewer.
//!
//! - [`input`]: keys, key scripts and the actions keys are bound to;
//! - [`window`]: the window a program is shown in;
//! - [`runner`]: runs a program's simulation with its hooks and keys.

pub mod input;
pub mod runner;
pub mod window;

use nalgebra::Vector3;

pub use input::{Action, ActionMap, Key, KeyEvent, KeyScript, Repeat};
pub use runner::ProgramRunner;
pub use window::{RenderQuality, WindowSettings};

use crate::error::Result;
use crate::simulation::hooks::Hooks;
use crate::simulation::{Simulation, SimulationBuilder};
use crate::world::SpaceKind;

/// A simulation program: a scene ([`create_sim_objects`](Program::create_sim_objects),
/// the one required method) and the [`Hooks`] that run it (all optional, so
/// `impl Hooks for MyProgram {}` is enough); parameters, view and key bindings are
/// optional too.
///
/// The thesis' hello world:
/// ```
/// use ars_core::{Hooks, Mass, Program, Result, Simulation};
///
/// struct HelloWorld;
/// impl Hooks for HelloWorld {}
/// impl Program for HelloWorld {
///     fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
///         sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).map(drop)
///     }
/// }
///
/// let sim = HelloWorld.run_headless(1.0)?;
/// let ball = sim.scene().object("sphere")?; // named access: a view of the object
/// assert!((ball.position()?.y - 0.5).abs() < 1e-3);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub trait Program: Hooks {
    /// Simulation parameters. The builder given is the original's model: the ARS
    /// defaults with the original's simple space ([`SpaceKind::Simple`], every pair
    /// tested), so that a program steps bit for bit as it did in the original; a
    /// program with many geoms chooses a space that scales
    /// (`.space(SpaceKind::Grid)`, the default of
    /// [`Simulation::new`]). The default adds the floor plane y = 0.
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        builder.floor_plane(Vector3::y(), 0.0)
    }

    /// Adds the program's objects, joints and sensors.
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()>;

    /// Window title, size and camera for the viewer.
    fn window_settings(&self) -> WindowSettings {
        WindowSettings::default()
    }

    /// Key bindings.
    fn key_bindings(&self) -> ActionMap<Self>
    where
        Self: Sized,
    {
        ActionMap::new()
    }

    /// Builds the simulation: `configure` (given the ARS defaults with a simple
    /// space), then `create_sim_objects`.
    fn create_simulation(&mut self) -> Result<Simulation>
    where
        Self: Sized,
    {
        let mut sim = self.configure(Simulation::builder().space(SpaceKind::Simple)).build()?;
        self.create_sim_objects(&mut sim)?;
        Ok(sim)
    }

    /// Builds the simulation and runs it for `duration` seconds of simulated time,
    /// with no graphics; returns the simulation for its records.
    fn run_headless(&mut self, duration: f64) -> Result<Simulation>
    where
        Self: Sized,
    {
        let mut runner = ProgramRunner::new(self)?;
        runner.run_for(duration)?;
        Ok(runner.into_simulation())
    }
}
