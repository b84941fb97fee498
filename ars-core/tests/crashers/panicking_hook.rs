//! Cause: a panic in one pre-step or post-step closure unwound out of `step` while the
//! simulation held its hook list outside itself: every hook of that point was lost.
//! Now a panic is contained and reported as `Error::Panicked`, and every hook stays.

use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};

use ars_core::*;

#[test]
fn a_panicking_hook_is_reported_and_no_hook_is_lost() {
    let mut sim = Simulation::new().unwrap();
    let calls = Arc::new(AtomicU32::new(0));
    for point in 0..2 {
        for i in 0..3 {
            let calls = calls.clone();
            let mut failed = false;
            // Hook 1 of each point panics once: the pre-step one in the third step,
            // the post-step one in the step after.
            let hook = move |sim: &mut Simulation| {
                calls.fetch_add(1, Ordering::Relaxed);
                if i == 1 && !failed && sim.scene().step_count() >= 2 + point {
                    failed = true;
                    panic!("hook {i} fails at step {}", sim.scene().step_count());
                }
                Ok(())
            };
            if point == 0 { sim.add_hooks(PreStep(hook)).map(drop) } else { sim.add_hooks(PostStep(hook)).map(drop) }
                .unwrap();
        }
    }
    sim.step_n(2).unwrap();
    let err = sim.step().unwrap_err();
    assert!(
        matches!(&err, Error::Panicked { during, message } if during == "the pre-step hook of hook set 2" && message.contains("fails")),
        "{err}"
    );
    let err = sim.step().unwrap_err();
    assert!(matches!(&err, Error::Panicked { during, .. } if during == "the post-step hook of hook set 2"), "{err}");
    let before = calls.load(Ordering::Relaxed);
    sim.step().unwrap();
    assert_eq!(calls.load(Ordering::Relaxed) - before, 6, "all six hooks still run");
}

#[test]
fn a_panicking_program_hook_is_reported() {
    struct Panics(bool);
    impl Hooks for Panics {
        fn pre_step(&mut self, _: &mut Simulation) -> Result<()> {
            if self.0 {
                panic!("program hook");
            }
            Ok(())
        }
    }
    impl Program for Panics {
        fn create_sim_objects(&mut self, _: &mut Simulation) -> Result<()> {
            Ok(())
        }
    }
    let mut program = Panics(true);
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    let err = runner.step().unwrap_err();
    assert!(matches!(&err, Error::Panicked { during, .. } if during == "the pre-step hook of the program"), "{err}");
    runner.program_mut().0 = false;
    runner.step().unwrap();
}
