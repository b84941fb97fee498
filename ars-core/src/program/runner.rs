//! The runner of a program: its simulation, its hooks, and its keys.

use super::Program;
use super::input::{Action, ActionMap, Key, KeyScript, Repeat};
use crate::error::Result;
use crate::simulation::Simulation;
use crate::simulation::hooks::Hooks;

/// The held-keys decorator: a program's hooks, with the actions of the keys held now
/// run right after its pre-step hook.
struct HeldKeys<'a, P> {
    program: &'a mut P,
    held: &'a [(Key, Action<P>)],
}

impl<P: Program> Hooks for HeldKeys<'_, P> {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.pre_step(sim)?;
        self.held.iter().try_for_each(|(_, action)| action(self.program, sim))
    }
    fn post_step(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.post_step(sim)
    }
    fn pre_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.pre_frame(sim)
    }
    fn post_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        self.program.post_frame(sim)
    }
}

/// Runs a program: its simulation, its hooks and its keys. The viewer drives one of
/// these from the window; headless runs and tests drive it directly.
pub struct ProgramRunner<'p, P: Program> {
    program: &'p mut P,
    sim: Simulation,
    bindings: ActionMap<P>,
    /// The keys held down with their [`Repeat::WhileHeld`] actions, in pressing order.
    held: Vec<(Key, Action<P>)>,
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
    pub fn program(&self) -> &P {
        self.program
    }

    /// The program, mutably.
    pub fn program_mut(&mut self) -> &mut P {
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
            Some((action, Repeat::WhileHeld)) => {
                if !self.held.iter().any(|(k, _)| *k == key) {
                    self.held.push((key, action));
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
        self.held.retain(|(k, _)| *k != key);
    }

    /// The keys held down, in pressing order.
    pub fn held_keys(&self) -> impl Iterator<Item = Key> + '_ {
        self.held.iter().map(|(k, _)| *k)
    }

    /// The program's hooks decorated with the actions of the keys held now.
    fn driven(&mut self) -> (HeldKeys<'_, P>, &mut Simulation) {
        (HeldKeys { program: &mut *self.program, held: &self.held }, &mut self.sim)
    }

    /// `steps` steps in frames, asking `stop` before each frame.
    fn run_steps(&mut self, steps: u64, stop: &mut dyn FnMut() -> bool) -> Result<()> {
        let (mut program, sim) = self.driven();
        sim.run_driven(Some(&mut program), steps, stop)
    }

    /// One step with the program's step hooks (no frame hooks).
    pub fn step(&mut self) -> Result<()> {
        let (mut program, sim) = self.driven();
        sim.step_driven(Some(&mut program))
    }

    /// One frame of `steps_per_frame` steps.
    pub fn step_frame(&mut self) -> Result<()> {
        let n = u64::from(self.sim.scene().steps_per_frame());
        self.run_steps(n, &mut || false)
    }

    /// As [`step_frame`](Self::step_frame), showing the simulation to `after_step`
    /// after each step (see [`Simulation::step_frame_observed`]).
    pub fn step_frame_observed(&mut self, after_step: &mut dyn FnMut(&Simulation) -> Result<()>) -> Result<()> {
        let n = self.sim.scene().steps_per_frame();
        let (mut program, sim) = self.driven();
        sim.frame_observed(Some(&mut program), n, after_step)
    }

    /// Runs for `duration` seconds of simulated time in frames, pressing and releasing
    /// keys as `script` says. As in the original, keys are handled between frames: an
    /// event takes effect before the first frame that starts at or after its time. A
    /// stop requested through [`interrupt`](crate::interrupt) (Ctrl-C) ends it between
    /// two frames with [`Error::Interrupted`](crate::Error::Interrupted).
    pub fn run_script(&mut self, script: &KeyScript, duration: f64) -> Result<()> {
        let mut steps = self.sim.scene().steps_in(duration)?;
        while steps > 0 {
            self.apply_due_events(script)?;
            let n = steps.min(u64::from(self.sim.scene().steps_per_frame()));
            self.run_steps(n, &mut crate::interrupt::requested)?;
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
        let now = self.sim.scene().time() + 0.5 * self.sim.scene().time_step();
        while let Some(e) = script.events().get(self.script_position).filter(|e| e.time <= now) {
            if e.down {
                self.key_down(e.key)?;
            } else {
                self.key_up(e.key);
            }
            self.script_position += 1;
        }
        Ok(())
    }

    /// Runs for `duration` seconds of simulated time, in frames. A stop requested
    /// through [`interrupt`](crate::interrupt) (Ctrl-C) ends it between two frames with
    /// [`Error::Interrupted`](crate::Error::Interrupted); the runner can go on.
    pub fn run_for(&mut self, duration: f64) -> Result<()> {
        let steps = self.sim.scene().steps_in(duration)?;
        self.run_steps(steps, &mut crate::interrupt::requested)
    }
}
