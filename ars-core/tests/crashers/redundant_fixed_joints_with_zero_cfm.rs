//! Cause: `set_cfm(0.0)` with two fixed joints on the same pair of bodies: the
//! redundant rows make ODE's LCP matrix singular, the factorisation divides by zero
//! and ODE asserted: SIGABRT. A CFM of 0 is legitimate ODE input, so it stays
//! accepted; the failure is caught by the guard (`Error::OdeInternal`, poisoned
//! world) or reported as a divergence, never an abort.

use ars_core::nalgebra::Point3;
use ars_core::*;

#[test]
fn two_fixed_joints_on_one_pair_with_zero_cfm_do_not_abort() {
    let mut world = World::new();
    world.set_cfm(0.0).unwrap();
    let a = world.insert_body(BodyBuilder::new()).unwrap();
    let b = world.insert_body(BodyBuilder::new().position(Point3::new(1.0, 0.0, 0.0))).unwrap();
    world.insert_joint(JointBuilder::fixed().between(a, b)).unwrap();
    world.insert_joint(JointBuilder::fixed().between(a, b)).unwrap();
    world.insert_joint(JointBuilder::fixed().to_world(a)).unwrap();
    for _ in 0..1000 {
        match world.step(0.0004) {
            Ok(()) => {}
            Err(Error::OdeInternal { .. } | Error::Diverged { .. }) => break,
            Err(other) => panic!("unexpected {other}"),
        }
    }
}
