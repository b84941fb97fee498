//! Stopping runs early (`ars_core::interrupt` and the `_until` runs). A test binary of
//! its own: the stop request is process-wide, and other tests' runs must not see it.

use ars_core::{Error, Hooks, Mass, Program, ProgramRunner, Result, Simulation, interrupt};

fn ball() -> Simulation {
    let mut sim = Simulation::builder().floor_plane(ars_core::nalgebra::Vector3::y(), 0.0).build().unwrap();
    sim.scene_mut().add_sphere(0.2, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    sim
}

struct Ball;
impl Hooks for Ball {}
impl Program for Ball {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        sim.scene_mut().add_sphere(0.2, [0.0, 1.0, 0.0], Mass::Total(1.0)).map(drop)
    }
}

#[test]
fn runs_stop_between_frames_when_asked_and_go_on_after() {
    // Until a condition: here, after 30 frames asked.
    let mut sim = ball();
    let per_frame = u64::from(sim.scene().steps_per_frame());
    let mut asked = 0;
    let stopped = sim.run_for_until(1000.0, || {
        asked += 1;
        asked > 30
    });
    assert!(matches!(stopped, Err(Error::Interrupted { steps, .. }) if steps == 30 * per_frame), "{stopped:?}");
    assert_eq!(sim.scene().step_count(), 30 * per_frame);
    // The simulation is whole: it runs on, and reaches the same state as one that was
    // never stopped.
    sim.run_for(1.0).unwrap();
    let mut straight = ball();
    straight.step_n(sim.scene().step_count()).unwrap();
    let (a, b) = (sim.scene().objects().next().unwrap().1, straight.scene().objects().next().unwrap().1);
    assert_eq!(sim.scene().position(a).unwrap(), straight.scene().position(b).unwrap());

    // Steps, asked before each one.
    let mut sim = ball();
    let mut asked = 0;
    let stopped = sim.step_n_until(100, || {
        asked += 1;
        asked > 7
    });
    assert!(matches!(stopped, Err(Error::Interrupted { steps: 7, .. })), "{stopped:?}");

    // The process-wide request (what Ctrl-C sets once `stop_on_ctrl_c` is installed):
    // every run stops at once until it is cleared.
    interrupt::stop_on_ctrl_c().unwrap();
    interrupt::stop_on_ctrl_c().unwrap(); // twice is fine
    assert!(!interrupt::requested());
    interrupt::request();
    let mut sim = ball();
    assert!(matches!(sim.run_for(1.0), Err(Error::Interrupted { steps: 0, .. })));
    let mut program = Ball;
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    let stopped = runner.run_for(1.0);
    assert!(matches!(stopped, Err(Error::Interrupted { steps: 0, .. })), "{stopped:?}");
    assert!(stopped.unwrap_err().to_string().contains("interrupted at t = 0 s"));
    // A single frame or step is not a run: it is taken.
    runner.step_frame().unwrap();
    assert!(interrupt::clear());
    assert!(!interrupt::clear());
    runner.run_for(0.1).unwrap();
    assert!(runner.simulation().scene().time() > 0.1);
}
