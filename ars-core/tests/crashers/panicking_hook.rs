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
                if i == 1 && !failed && sim.step_count() >= 2 + point {
                    failed = true;
                    panic!("hook {i} fails at step {}", sim.step_count());
                }
                Ok(())
            };
            if point == 0 { sim.on_pre_step(hook) } else { sim.on_post_step(hook) }
        }
    }
    sim.step_n(2).unwrap();
    let err = sim.step().unwrap_err();
    assert!(
        matches!(&err, Error::Panicked { during, message } if during == "pre-step hook 1" && message.contains("fails")),
        "{err}"
    );
    let err = sim.step().unwrap_err();
    assert!(matches!(&err, Error::Panicked { during, .. } if during == "post-step hook 1"), "{err}");
    let before = calls.load(Ordering::Relaxed);
    sim.step().unwrap();
    assert_eq!(calls.load(Ordering::Relaxed) - before, 6, "all six hooks still run");
}

#[test]
fn a_panicking_program_hook_is_reported() {
    struct Panics;
    impl StepHooks for Panics {
        fn pre_step(&mut self, _: &mut Simulation) -> Result<()> {
            panic!("program hook");
        }
    }
    let mut sim = Simulation::new().unwrap();
    let err = sim.step_with(&mut Panics).unwrap_err();
    assert!(matches!(err, Error::Panicked { .. }), "{err}");
    sim.step().unwrap();
}
