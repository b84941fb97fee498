//! The `Program` flow of the original ARS: a program builds its objects, hooks into
//! the step loop and maps keys to actions; it runs headless here, or in a window with
//! the viewer.

use std::collections::BTreeMap;
use std::fmt;

use nalgebra::Vector3;

use crate::error::Result;
use crate::simulation::{Simulation, SimulationBuilder, StepHooks};

/// A key of the keyboard, as the viewer reports it and as programs bind them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Key {
    /// A character key, lower case (`'a'`, `'z'`, `'r'`...).
    Char(char),
    /// Arrow up.
    Up,
    /// Arrow down.
    Down,
    /// Arrow left.
    Left,
    /// Arrow right.
    Right,
    /// Space bar.
    Space,
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Key::Char(c) => write!(f, "{c}"),
            Key::Up => write!(f, "up"),
            Key::Down => write!(f, "down"),
            Key::Left => write!(f, "left"),
            Key::Right => write!(f, "right"),
            Key::Space => write!(f, "space"),
        }
    }
}

/// When a bound action runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Repeat {
    /// Once when the key goes down, between steps (a torque added then acts for one
    /// step, as in the original).
    Once,
    /// In every step while the key is held, after the pre-step hooks.
    WhileHeld,
}

/// What a key does to a program and its simulation.
pub type Action<P> = fn(&mut P, &mut Simulation) -> Result<()>;

/// Keys bound to actions of a program `P`.
pub struct ActionMap<P> {
    actions: BTreeMap<Key, (Action<P>, Repeat)>,
}

impl<P> Default for ActionMap<P> {
    fn default() -> Self {
        ActionMap { actions: BTreeMap::new() }
    }
}

impl<P> fmt::Debug for ActionMap<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_map().entries(self.actions.iter().map(|(k, (_, r))| (k, r))).finish()
    }
}

impl<P> ActionMap<P> {
    /// No bindings.
    pub fn new() -> Self {
        ActionMap::default()
    }
    /// Binds `key` (replacing an earlier binding).
    pub fn add(mut self, key: Key, action: Action<P>, repeat: Repeat) -> Self {
        self.actions.insert(key, (action, repeat));
        self
    }
    /// The action bound to `key`.
    pub fn get(&self, key: Key) -> Option<(Action<P>, Repeat)> {
        self.actions.get(&key).copied()
    }
    /// The bound keys.
    pub fn keys(&self) -> impl Iterator<Item = Key> + '_ {
        self.actions.keys().copied()
    }
}

/// A simulation program: [`create_sim_objects`](Program::create_sim_objects) is the
/// one required method; hooks, parameters and key bindings are optional.
///
/// The thesis' hello world:
/// ```
/// use ars_core::{Mass, Program, Result, Simulation};
///
/// struct HelloWorld;
/// impl Program for HelloWorld {
///     fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
///         sim.add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).map(drop)
///     }
/// }
///
/// let sim = HelloWorld.run_headless(1.0)?;
/// let ball = sim.object("sphere")?;
/// assert!((sim.body(ball)?.position().y - 0.5).abs() < 1e-3);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub trait Program {
    /// Simulation parameters. The default is the original's: ARS defaults and the floor
    /// plane y = 0.
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        builder.floor_plane(Vector3::y(), 0.0)
    }

    /// Adds the program's objects, joints and sensors.
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()>;

    /// Before every step (time at the start of the step).
    fn on_pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// After every step (time at the end of the step).
    fn on_post_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// Before every frame.
    fn on_pre_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// After every frame.
    fn on_post_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }

    /// Key bindings.
    fn key_bindings(&self) -> ActionMap<Self>
    where
        Self: Sized,
    {
        ActionMap::new()
    }

    /// Builds the simulation: `configure`, then `create_sim_objects`.
    fn create_simulation(&mut self) -> Result<Simulation>
    where
        Self: Sized,
    {
        let mut sim = self.configure(Simulation::builder()).build()?;
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

/// Adapts a program's hooks to the simulation's; the actions of held keys run right
/// after the program's pre-step hook.
struct ProgramHooks<'p, P> {
    program: &'p mut P,
    held_actions: Vec<Action<P>>,
}

impl<P: Program> StepHooks for ProgramHooks<'_, P> {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.on_pre_step(sim)?;
        self.held_actions.iter().try_for_each(|action| action(self.program, sim))
    }
    fn post_step(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.on_post_step(sim)
    }
    fn pre_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.on_pre_frame(sim)
    }
    fn post_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.on_post_frame(sim)
    }
}

/// Runs a program: its simulation, its hooks and its keys. The viewer drives one of
/// these from the window; headless runs and tests drive it directly.
pub struct ProgramRunner<'p, P: Program> {
    program: &'p mut P,
    sim: Simulation,
    bindings: ActionMap<P>,
    held: Vec<Key>,
}

impl<'p, P: Program> ProgramRunner<'p, P> {
    /// Builds the program's simulation.
    pub fn new(program: &'p mut P) -> Result<Self> {
        let sim = program.create_simulation()?;
        let bindings = program.key_bindings();
        Ok(ProgramRunner { program, sim, bindings, held: Vec::new() })
    }

    /// The simulation.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }

    /// The simulation, mutably.
    pub fn simulation_mut(&mut self) -> &mut Simulation {
        &mut self.sim
    }

    /// The program.
    pub fn program(&mut self) -> &mut P {
        self.program
    }

    /// Gives the simulation back.
    pub fn into_simulation(self) -> Simulation {
        self.sim
    }

    /// Rebuilds the simulation from scratch (the original's 'r' key).
    pub fn reset(&mut self) -> Result<()> {
        self.sim = self.program.create_simulation()?;
        self.held.clear();
        Ok(())
    }

    /// A key went down: a [`Repeat::Once`] action runs now; a [`Repeat::WhileHeld`] one
    /// runs in every step until [`key_up`](Self::key_up). Returns whether the key is bound.
    pub fn key_down(&mut self, key: Key) -> Result<bool> {
        match self.bindings.get(key) {
            Some((action, Repeat::Once)) => {
                action(self.program, &mut self.sim)?;
                Ok(true)
            }
            Some((_, Repeat::WhileHeld)) => {
                if !self.held.contains(&key) {
                    self.held.push(key);
                }
                Ok(true)
            }
            None => {
                log::debug!("key {key} is not bound");
                Ok(false)
            }
        }
    }

    /// A key went up.
    pub fn key_up(&mut self, key: Key) {
        self.held.retain(|k| *k != key);
    }

    /// The keys held down.
    pub fn held_keys(&self) -> &[Key] {
        &self.held
    }

    fn run_steps(&mut self, steps: u64) -> Result<()> {
        let held_actions = self.held.iter().filter_map(|k| self.bindings.get(*k).map(|(a, _)| a)).collect();
        let mut hooks = ProgramHooks { program: &mut *self.program, held_actions };
        self.sim.run_steps_in_frames(&mut hooks, steps)
    }

    /// One step with the program's step hooks (no frame hooks).
    pub fn step(&mut self) -> Result<()> {
        let held_actions = self.held.iter().filter_map(|k| self.bindings.get(*k).map(|(a, _)| a)).collect();
        let mut hooks = ProgramHooks { program: &mut *self.program, held_actions };
        self.sim.step_with(&mut hooks)
    }

    /// One frame of `steps_per_frame` steps.
    pub fn step_frame(&mut self) -> Result<()> {
        let n = u64::from(self.sim.steps_per_frame());
        self.run_steps(n)
    }

    /// Runs for `duration` seconds of simulated time, in frames.
    pub fn run_for(&mut self, duration: f64) -> Result<()> {
        let steps = self.sim.steps_in(duration)?;
        self.run_steps(steps)
    }
}
