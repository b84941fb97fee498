//! The `Program` flow of the original ARS: a program builds its objects, hooks into
//! the step loop and maps keys to actions; it runs headless here, or in a window with
//! the viewer.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

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

impl Key {
    /// A key from its name: `up`, `down`, `left`, `right`, `space`, or one character.
    pub fn from_name(name: &str) -> Option<Key> {
        match name {
            "up" => Some(Key::Up),
            "down" => Some(Key::Down),
            "left" => Some(Key::Left),
            "right" => Some(Key::Right),
            "space" => Some(Key::Space),
            _ => {
                let mut chars = name.chars();
                match (chars.next(), chars.next()) {
                    (Some(c), None) => Some(Key::Char(c.to_ascii_lowercase())),
                    _ => None,
                }
            }
        }
    }
}

/// A key going down or up at a moment of simulated time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeyEvent {
    /// Simulated time, s.
    pub time: f64,
    /// The key.
    pub key: Key,
    /// `true` when the key goes down.
    pub down: bool,
}

/// Timed key events that drive a program without a keyboard (headless runs, tests).
///
/// The text form has one event per line, `TIME down|up KEY`, with `#` comments:
/// ```
/// use ars_core::{Key, KeyScript};
/// let script = KeyScript::parse("# drive, then turn\n0.5 down up\n2.0 down left\n4 up left\n4 up up\n")?;
/// assert_eq!(script.events().len(), 4);
/// assert_eq!(script.events()[1].key, Key::Left);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KeyScript {
    events: Vec<KeyEvent>,
}

impl KeyScript {
    /// A script of these events (sorted by time; equal times keep their order).
    pub fn new(mut events: Vec<KeyEvent>) -> Result<Self> {
        if let Some(e) = events.iter().find(|e| !e.time.is_finite() || e.time < 0.0) {
            return Err(crate::Error::OutOfRange { what: "key event time", detail: format!("{} s", e.time) });
        }
        events.sort_by(|a, b| a.time.total_cmp(&b.time));
        Ok(KeyScript { events })
    }

    /// Parses the text form (see the type's docs).
    pub fn parse(text: &str) -> Result<Self> {
        let mut events = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let bad = |why: &str| crate::Error::OutOfRange {
                what: "key script",
                detail: format!("line {}: {why}: {line:?} (expected `TIME down|up KEY`)", n + 1),
            };
            let parts: Vec<&str> = line.split_whitespace().collect();
            let [time, action, key] = parts[..] else { return Err(bad("three fields needed")) };
            let time: f64 = time.parse().map_err(|_| bad("bad time"))?;
            let down = match action {
                "down" => true,
                "up" => false,
                _ => return Err(bad("the action is `down` or `up`")),
            };
            let key = Key::from_name(key).ok_or_else(|| bad("unknown key"))?;
            events.push(KeyEvent { time, key, down });
        }
        Self::new(events)
    }

    /// The events, by time.
    pub fn events(&self) -> &[KeyEvent] {
        &self.events
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
pub type Action<P> = Arc<dyn Fn(&mut P, &mut Simulation) -> Result<()> + Send + Sync>;

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
    pub fn add(
        mut self,
        key: Key,
        action: impl Fn(&mut P, &mut Simulation) -> Result<()> + Send + Sync + 'static,
        repeat: Repeat,
    ) -> Self {
        self.actions.insert(key, (Arc::new(action), repeat));
        self
    }
    /// The action bound to `key`.
    pub fn get(&self, key: Key) -> Option<(Action<P>, Repeat)> {
        self.actions.get(&key).map(|(a, r)| (Arc::clone(a), *r))
    }
    /// The bound keys.
    pub fn keys(&self) -> impl Iterator<Item = Key> + '_ {
        self.actions.keys().copied()
    }
}

/// How a program wants to be shown (the viewer's window and camera); the defaults
/// are the original's: 1024 × 768, camera at (10, 8, 10) looking at the origin, white
/// background.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSettings {
    /// Window title.
    pub title: String,
    /// Window (or off-screen image) size, pixels.
    pub size: (u32, u32),
    /// Where the camera is.
    pub camera_position: nalgebra::Point3<f64>,
    /// What it looks at.
    pub camera_target: nalgebra::Point3<f64>,
    /// Background colour (RGB in [0, 1]).
    pub background: [f32; 3],
}

impl Default for ViewSettings {
    fn default() -> Self {
        ViewSettings {
            title: "Autonomous Robot Simulator".into(),
            size: (1024, 768),
            camera_position: nalgebra::Point3::new(10.0, 8.0, 10.0),
            camera_target: nalgebra::Point3::origin(),
            background: [1.0, 1.0, 1.0],
        }
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

    /// Window title, size and camera for the viewer.
    fn view_settings(&self) -> ViewSettings {
        ViewSettings::default()
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
    script_position: usize,
}

impl<'p, P: Program> ProgramRunner<'p, P> {
    /// Builds the program's simulation.
    pub fn new(program: &'p mut P) -> Result<Self> {
        let sim = program.create_simulation()?;
        let bindings = program.key_bindings();
        Ok(ProgramRunner { program, sim, bindings, held: Vec::new(), script_position: 0 })
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
        self.script_position = 0;
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

    /// The program's hooks, with the actions of the keys held now.
    fn hooks(&mut self) -> (ProgramHooks<'_, P>, &mut Simulation) {
        let held_actions = self.held.iter().filter_map(|k| self.bindings.get(*k).map(|(a, _)| a)).collect();
        (ProgramHooks { program: &mut *self.program, held_actions }, &mut self.sim)
    }

    fn run_steps(&mut self, steps: u64) -> Result<()> {
        let (mut hooks, sim) = self.hooks();
        sim.run_steps_in_frames(&mut hooks, steps)
    }

    /// One step with the program's step hooks (no frame hooks).
    pub fn step(&mut self) -> Result<()> {
        let (mut hooks, sim) = self.hooks();
        sim.step_with(&mut hooks)
    }

    /// One frame of `steps_per_frame` steps.
    pub fn step_frame(&mut self) -> Result<()> {
        let n = u64::from(self.sim.steps_per_frame());
        self.run_steps(n)
    }

    /// Runs for `duration` seconds of simulated time in frames, pressing and releasing
    /// keys as `script` says. As in the original, keys are handled between frames: an
    /// event takes effect before the first frame that starts at or after its time.
    pub fn run_script(&mut self, script: &KeyScript, duration: f64) -> Result<()> {
        let mut steps = self.sim.steps_in(duration)?;
        while steps > 0 {
            self.apply_due_events(script)?;
            let n = steps.min(u64::from(self.sim.steps_per_frame()));
            self.run_steps(n)?;
            steps -= n;
        }
        Ok(())
    }

    /// One frame of a scripted run (see [`run_script`](Self::run_script)).
    pub fn run_script_frame(&mut self, script: &KeyScript) -> Result<()> {
        self.apply_due_events(script)?;
        self.step_frame()
    }

    /// Applies the script's events that are due at the current time and not yet applied.
    fn apply_due_events(&mut self, script: &KeyScript) -> Result<()> {
        let now = self.sim.time() + 0.5 * self.sim.time_step();
        while let Some(e) = script.events.get(self.script_position).filter(|e| e.time <= now) {
            if e.down {
                self.key_down(e.key)?;
            } else {
                self.key_up(e.key);
            }
            self.script_position += 1;
        }
        Ok(())
    }

    /// Runs for `duration` seconds of simulated time, in frames.
    pub fn run_for(&mut self, duration: f64) -> Result<()> {
        let steps = self.sim.steps_in(duration)?;
        self.run_steps(steps)
    }
}
