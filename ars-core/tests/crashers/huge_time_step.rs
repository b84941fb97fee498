//! Cause: a time step of 1e300 s was accepted: the first step returned `Ok` with a NaN
//! state and the next one asserted: SIGABRT. Fixed by the time-step range (1e-9 to
//! 1 s), on `World::step` and on every way a simulation takes its time step.

use ars_core::limits::MAX_TIME_STEP;
use ars_core::*;

#[test]
fn a_huge_time_step_is_refused_everywhere() {
    let (mut world, space) = super::common::world_with_floor();
    super::common::ball(&mut world, space, [0.0, 1.0, 0.0].into());
    for dt in [1e300, 2.0, 1e-300, 0.0] {
        assert!(matches!(world.step(dt), Err(Error::OutOfRange { .. } | Error::NotPositive { .. })), "{dt}");
        assert!(Simulation::builder().time_step(dt).build().is_err(), "{dt}");
        assert!(Simulation::new().unwrap().scene_mut().set_time_step(dt).is_err(), "{dt}");
    }
    for _ in 0..10 {
        world.collide(space).unwrap();
        let stepped = world.step(MAX_TIME_STEP);
        world.clear_contacts();
        assert!(matches!(stepped, Ok(()) | Err(Error::Diverged { .. })), "{stepped:?}");
    }
}
