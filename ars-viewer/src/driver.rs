//! What the window and the recorder run: a simulation advanced frame by frame, which
//! the viewer's keys and panel can step, rebuild and send keys to. A Rust
//! [`Program`](ars_core::Program) is driven by its [`ProgramRunner`]; other front ends
//! (the Python package) implement [`Driver`] themselves.

use std::ops::DerefMut;

use ars_core::{Key, Program, ProgramRunner, Result, Simulation};

use crate::state::ViewerState;

/// A simulation the viewer shows and drives.
pub trait Driver {
    /// The simulation as it is now (after [`reset`](Self::reset), the new one).
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_;
    /// One frame: the simulation's `steps_per_frame` steps, with whatever the program
    /// does around them.
    fn step_frame(&mut self) -> Result<()>;
    /// As [`step_frame`](Self::step_frame), showing the simulation to `after_step`
    /// after each step: the video recorder takes its pictures at the steps it wants.
    /// By default the frame runs whole and `after_step` sees it once, at its end (for
    /// front ends whose frames run out of reach, the Python package's programs).
    fn step_frame_observed(&mut self, after_step: &mut dyn FnMut(&Simulation) -> Result<()>) -> Result<()> {
        self.step_frame()?;
        after_step(&self.simulation())
    }
    /// One physics step.
    fn step(&mut self) -> Result<()>;
    /// Rebuilds the simulation from scratch (the `r` key).
    fn reset(&mut self) -> Result<()>;
    /// A key the viewer does not use went down.
    fn key_down(&mut self, key: Key) -> Result<()>;
    /// That key went up.
    fn key_up(&mut self, key: Key) -> Result<()>;
    /// Whether the program asked for its window to close (the original's `e` and `q`
    /// keys do in the Python package); checked after every frame's keys. By default
    /// only the window's own close (Escape, the close button) closes it.
    fn wants_to_close(&mut self) -> bool {
        false
    }
    /// What the window shows besides the scene (the selected body, the drag in
    /// progress, the panel's error and save path), once a frame after it is drawn. By
    /// default ignored; a front end can mirror it, a test can read it.
    fn viewer_state(&mut self, state: &ViewerState) {
        let _ = state;
    }
}

impl<P: Program> Driver for ProgramRunner<'_, P> {
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_ {
        self.simulation_mut()
    }
    fn step_frame(&mut self) -> Result<()> {
        ProgramRunner::step_frame(self)
    }
    fn step_frame_observed(&mut self, after_step: &mut dyn FnMut(&Simulation) -> Result<()>) -> Result<()> {
        ProgramRunner::step_frame_observed(self, after_step)
    }
    fn step(&mut self) -> Result<()> {
        ProgramRunner::step(self)
    }
    fn reset(&mut self) -> Result<()> {
        ProgramRunner::reset(self)
    }
    fn key_down(&mut self, key: Key) -> Result<()> {
        ProgramRunner::key_down(self, key).map(drop)
    }
    fn key_up(&mut self, key: Key) -> Result<()> {
        ProgramRunner::key_up(self, key);
        Ok(())
    }
}
