//! What the window and the recorder run: a simulation advanced frame by frame, which
//! the viewer's keys and panel can step, rebuild and send keys to. A Rust
//! [`Program`] is driven by its [`ProgramRunner`]; other front ends
//! (the Python package) implement [`Driver`] themselves.

use std::ops::{Deref, DerefMut};
use std::path::PathBuf;

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

/// What a window drives: its program, until a file is opened from the panel; from then
/// on the file's simulation, stepped without the program (its hooks and keys), and
/// `r` opens the file again.
pub(crate) struct Shown<'d, D> {
    program: &'d mut D,
    file: Option<(PathBuf, Simulation)>,
}

/// The simulation of a [`Shown`]: the program's or the file's.
pub(crate) enum ShownSimulation<'a, T> {
    Program(T),
    File(&'a mut Simulation),
}

impl<T: DerefMut<Target = Simulation>> Deref for ShownSimulation<'_, T> {
    type Target = Simulation;
    fn deref(&self) -> &Simulation {
        match self {
            ShownSimulation::Program(sim) => sim,
            ShownSimulation::File(sim) => sim,
        }
    }
}

impl<T: DerefMut<Target = Simulation>> DerefMut for ShownSimulation<'_, T> {
    fn deref_mut(&mut self) -> &mut Simulation {
        match self {
            ShownSimulation::Program(sim) => sim,
            ShownSimulation::File(sim) => sim,
        }
    }
}

impl<'d, D: Driver> Shown<'d, D> {
    /// The program's simulation, shown.
    pub(crate) fn new(program: &'d mut D) -> Self {
        Shown { program, file: None }
    }

    /// Shows `simulation`, opened from `path`, instead.
    pub(crate) fn open(&mut self, path: PathBuf, simulation: Simulation) {
        self.file = Some((path, simulation));
    }
}

impl<D: Driver> Driver for Shown<'_, D> {
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_ {
        match &mut self.file {
            Some((_, sim)) => ShownSimulation::File(sim),
            None => ShownSimulation::Program(self.program.simulation()),
        }
    }
    fn step_frame(&mut self) -> Result<()> {
        match &mut self.file {
            Some((_, sim)) => sim.step_frame(),
            None => self.program.step_frame(),
        }
    }
    fn step(&mut self) -> Result<()> {
        match &mut self.file {
            Some((_, sim)) => sim.step(),
            None => self.program.step(),
        }
    }
    fn reset(&mut self) -> Result<()> {
        match &mut self.file {
            Some((path, sim)) => {
                *sim = Simulation::open(&*path)?.simulation;
                Ok(())
            }
            None => self.program.reset(),
        }
    }
    fn key_down(&mut self, key: Key) -> Result<()> {
        if self.file.is_some() { Ok(()) } else { self.program.key_down(key) }
    }
    fn key_up(&mut self, key: Key) -> Result<()> {
        if self.file.is_some() { Ok(()) } else { self.program.key_up(key) }
    }
    fn wants_to_close(&mut self) -> bool {
        self.program.wants_to_close()
    }
    fn viewer_state(&mut self, state: &ViewerState) {
        self.program.viewer_state(state);
    }
}

/// A simulation driven by nothing but its own frames (and hooks): what the recorders
/// run for front ends with simulations of their own (the Python package).
pub(crate) struct BareSimulation<'a>(pub(crate) &'a mut Simulation);

impl Driver for BareSimulation<'_> {
    fn simulation(&mut self) -> impl DerefMut<Target = Simulation> + '_ {
        &mut *self.0
    }
    fn step_frame(&mut self) -> Result<()> {
        self.0.step_frame()
    }
    fn step_frame_observed(&mut self, after_step: &mut dyn FnMut(&Simulation) -> Result<()>) -> Result<()> {
        self.0.step_frame_observed(after_step)
    }
    fn step(&mut self) -> Result<()> {
        self.0.step()
    }
    fn reset(&mut self) -> Result<()> {
        Err(ars_core::Error::User("a recording does not rebuild a bare simulation".into()))
    }
    fn key_down(&mut self, _: Key) -> Result<()> {
        Ok(())
    }
    fn key_up(&mut self, _: Key) -> Result<()> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ars_core::{Hooks, Mass};

    /// A ball dropped from 1 m, and a count of the frames the program saw.
    struct Drop {
        frames: u32,
    }
    impl Hooks for Drop {
        fn pre_frame(&mut self, _: &mut Simulation) -> Result<()> {
            self.frames += 1;
            Ok(())
        }
    }
    impl Program for Drop {
        fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
            sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0)).map(drop)
        }
    }

    #[test]
    fn an_opened_file_is_shown_stepped_and_reopened_without_the_program() {
        let dir = std::env::temp_dir().join(format!("ars-shown-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("three.json");
        let mut three = Simulation::new().unwrap();
        three.scene_mut().add_sphere(0.1, [0.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
        three.scene_mut().add_sphere(0.1, [1.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
        three.scene_mut().add_sphere(0.1, [2.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
        three.save_scene_to(&path).unwrap();

        let mut program = Drop { frames: 0 };
        let mut runner = ProgramRunner::new(&mut program).unwrap();
        let mut shown = Shown::new(&mut runner);
        shown.step_frame().unwrap();
        let of_program = shown.simulation().scene().objects().count();
        shown.open(path.clone(), Simulation::open(&path).unwrap().simulation);
        assert_eq!(shown.simulation().scene().objects().count(), 3, "the file's scene is shown");
        shown.step_frame().unwrap();
        shown.key_down(Key::Up).unwrap();
        let frame_time = shown.simulation().scene().time();
        assert!(frame_time > 0.0);
        shown.reset().unwrap();
        assert_eq!(shown.simulation().scene().time(), 0.0, "r opens the file again");
        assert_eq!(shown.simulation().scene().objects().count(), 3);
        drop(shown);
        assert_eq!(runner.simulation().scene().objects().count(), of_program, "the program's simulation is kept");
        drop(runner);
        assert_eq!(program.frames, 1, "the program's hooks ran only before the file was opened");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
