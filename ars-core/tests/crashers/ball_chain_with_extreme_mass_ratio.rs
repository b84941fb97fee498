//! Cause: a chain of ball joints whose bodies alternate between 1e-9 and 1e9 kg (each
//! mass valid) makes the constraint system so badly conditioned that ODE's solver
//! produced NaN and asserted inside `dWorldStep`: SIGABRT. Validation cannot foresee
//! this; the guard does: the failure becomes `Error::OdeInternal` (or the state check
//! reports `Error::Diverged`), a poisoned world refuses to go on, and it drops cleanly.

use ars_core::limits::{MAX_MASS, MIN_MASS};
use ars_core::nalgebra::Point3;
use ars_core::*;

fn chain(world: &mut World) {
    let mut previous = None;
    for i in 0..10 {
        let mass = if i % 2 == 0 { MIN_MASS } else { MAX_MASS };
        let at = Point3::new(0.0, 10.0 - i as f64, 0.0);
        let b = world.insert_body(BodyBuilder::new().position(at).mass(MassSpec::sphere_total(mass, 0.1))).unwrap();
        let joint = JointBuilder::ball(at + nalgebra::Vector3::new(0.0, 0.5, 0.0));
        world
            .insert_joint(match previous {
                Some(p) => joint.between(b, p),
                None => joint.to_world(b),
            })
            .unwrap();
        previous = Some(b);
    }
}

#[test]
fn the_chain_ends_in_an_err_or_runs_never_in_an_abort() {
    for stepper in [Stepper::Exact, Stepper::Quick { iterations: 20 }] {
        let mut world = World::new();
        world.set_stepper(stepper).unwrap();
        chain(&mut world);
        let mut outcome = Ok(());
        for _ in 0..2000 {
            outcome = world.step(0.0004);
            if outcome.is_err() {
                break;
            }
        }
        match outcome {
            Ok(()) => assert!(!world.is_poisoned()),
            Err(Error::OdeInternal { during: "step", .. }) => {
                assert!(world.is_poisoned());
                assert!(matches!(world.step(0.0004), Err(Error::Poisoned(_))));
                assert!(matches!(world.insert_body(BodyBuilder::new()), Err(Error::Poisoned(_))));
            }
            Err(Error::Diverged { .. }) => assert!(world.diverged_body().is_some()),
            Err(other) => panic!("unexpected {other}"),
        }
        drop(world);
    }
    // A fresh world in the same process still runs.
    let mut world = World::new();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    world.step(0.0004).unwrap();
    assert!(world.body(b).unwrap().linear_velocity().y < 0.0);
}
