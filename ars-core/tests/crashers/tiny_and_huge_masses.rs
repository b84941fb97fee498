//! Cause: masses and inertias far outside physical scales (radius or mass 1e300, mass
//! 1e-300, 1e-200 or 1e-103, inertia diag(1, 1, 1e-300)) were accepted; the inverse
//! inertia overflowed, and the first step with a torque asserted in `dxNormalize4`
//! (the quaternion update became infinite): SIGABRT. Fixed by the mass range (1e-9 to
//! 1e9 kg) and inertia range (principal moments 1e-30 to 1e30 kg·m²); bodies at those
//! bounds, pushed as hard as the limits allow, step without failing.

use ars_core::limits::{MAX_MASS, MAX_TORQUE, MIN_INERTIA, MIN_MASS};
use ars_core::nalgebra::{Matrix3, Vector3};
use ars_core::*;

#[test]
fn extreme_masses_and_inertias_are_refused() {
    let mut world = World::new();
    for spec in [
        MassSpec::sphere_total(1.0, 1e300),
        MassSpec::sphere_total(1e300, 1.0),
        MassSpec::sphere_total(1e-300, 1.0),
        MassSpec::sphere_total(1e-200, 1.0),
        MassSpec::sphere_total(1e-103, 1.0),
        MassSpec::Custom { mass: 1.0, inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 1e-300)) },
    ] {
        let err = world.insert_body(BodyBuilder::new().mass(spec.clone())).unwrap_err();
        assert!(matches!(err, Error::OutOfRange { .. } | Error::NotPositive { .. }), "{spec:?}: {err}");
    }
    assert_eq!(world.body_count(), 0);
}

#[test]
fn bodies_at_the_mass_bounds_take_the_largest_torque_without_failing() {
    let mut world = World::new();
    let light = MassSpec::Custom { mass: MIN_MASS, inertia: Matrix3::from_diagonal(&Vector3::repeat(MIN_INERTIA)) };
    let heavy = MassSpec::sphere_total(MAX_MASS, 1.0);
    let bodies: Vec<_> = [light, heavy].map(|m| world.insert_body(BodyBuilder::new().mass(m)).unwrap()).into();
    for _ in 0..3 {
        for &b in &bodies {
            if world.body(b).is_ok() {
                world.body_mut(b).unwrap().add_torque(Vector3::new(MAX_TORQUE, 0.0, MAX_TORQUE)).unwrap();
            }
        }
        match world.step(0.0004) {
            Ok(()) => {}
            Err(Error::Diverged { .. }) => {
                // The light body spins beyond the speed limit: named, then removed.
                let b = world.diverged_body().expect("the diverged body is known");
                world.remove_body(b).unwrap();
            }
            Err(other) => panic!("unexpected {other}"),
        }
    }
}
