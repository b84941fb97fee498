//! Cause: a velocity of 1e300 m/s (valid input: finite) made the next steps overflow to
//! infinity and NaN, and ODE then asserted: SIGABRT. Fixed by the speed range, by a
//! check of every body's state after each step (`Error::Diverged`, naming the body),
//! and by refusing to step again until that body is reset or removed.

use ars_core::limits::MAX_SPEED;
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

#[test]
fn a_huge_velocity_is_refused() {
    let mut world = World::new();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    let err = world.body_mut(b).unwrap().set_linear_velocity(Vector3::new(1e300, 0.0, 0.0)).unwrap_err();
    assert!(matches!(err, Error::OutOfRange { what: "linear velocity", .. }), "{err}");
    assert!(world.body_mut(b).unwrap().set_angular_velocity(Vector3::new(0.0, 1e300, 0.0)).is_err());
}

#[test]
fn a_runaway_body_is_named_and_the_world_waits_until_it_is_reset() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let gps = sim.add_sensor(sensors::Gps::new(ball)).unwrap();
    sim.step_n(3).unwrap();
    // At the speed limit, gravity takes it beyond within a step.
    sim.scene_mut().body_mut(ball).unwrap().set_linear_velocity(Vector3::new(0.0, -MAX_SPEED, 0.0)).unwrap();
    let err = sim.step().unwrap_err();
    match &err {
        Error::Diverged { body, detail, .. } => {
            assert!(body.contains("sphere"), "named: {err}");
            assert!(detail.contains("linear velocity"), "{err}");
        }
        other => panic!("expected Diverged, got {other}"),
    }
    assert_eq!(sim.scene().step_count(), 4, "the step happened");
    assert!(matches!(sim.step(), Err(Error::Diverged { .. })), "refused until reset");
    assert_eq!(sim.records(gps).unwrap().len(), 3, "records so far kept, the diverged state not sampled");
    let mut body = sim.scene_mut().body_mut(ball).unwrap();
    body.set_linear_velocity(Vector3::zeros()).unwrap();
    body.set_position(Point3::new(0.0, 1.0, 0.0)).unwrap();
    sim.step().unwrap();
    assert_eq!(sim.records(gps).unwrap().len(), 4);
}
