//! Cause: `add_force(f64::MAX)` every step was accepted (it is finite); the sums and
//! the integration overflowed to infinity, and ODE asserted: SIGABRT. Fixed by the
//! force range per call, a check of the accumulated force and torque before each
//! step, and the state check after it.

use ars_core::limits::MAX_FORCE;
use ars_core::nalgebra::Vector3;
use ars_core::*;

#[test]
fn an_f64_max_force_is_refused() {
    let mut world = World::new();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    let err = world.body_mut(b).unwrap().add_force(Vector3::new(f64::MAX, 0.0, 0.0)).unwrap_err();
    assert!(matches!(err, Error::OutOfRange { what: "force", .. }), "{err}");
}

#[test]
fn an_accumulated_force_beyond_the_limit_is_refused_before_the_step() {
    let mut world = World::new();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    for _ in 0..10 {
        world.body_mut(b).unwrap().add_force(Vector3::new(MAX_FORCE, 0.0, 0.0)).unwrap();
    }
    let err = world.step(0.0004).unwrap_err();
    assert!(err.to_string().contains("accumulated force"), "{err}");
    assert_eq!(world.time(), 0.0, "nothing happened");
    world.body_mut(b).unwrap().clear_forces();
    world.step(0.0004).unwrap();
}

#[test]
fn the_largest_force_every_step_ends_in_an_err() {
    let mut world = World::new();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    let mut result = Ok(());
    // 1e9 N on 1 kg: 4e5 m/s more every step, beyond the speed limit within 250 steps.
    for _ in 0..1000 {
        world.body_mut(b).unwrap().add_force(Vector3::new(MAX_FORCE, -MAX_FORCE, 0.0)).unwrap();
        result = world.step(0.0004);
        if result.is_err() {
            break;
        }
    }
    assert!(matches!(result, Err(Error::Diverged { .. })), "{result:?}");
}
