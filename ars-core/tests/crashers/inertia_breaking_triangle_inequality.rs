//! Cause: an inertia tensor whose principal moments break the triangle inequality
//! (diag(1, 1, 3): no mass distribution has it) was accepted; ODE integrates it
//! without complaint and the rotation is unphysical. Now refused with the moments named.

use ars_core::nalgebra::{Matrix3, Vector3};
use ars_core::*;

#[test]
fn an_unphysical_inertia_is_refused() {
    let mut world = World::new();
    let spec = MassSpec::Custom { mass: 1.0, inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 3.0)) };
    let err = world.insert_body(BodyBuilder::new().mass(spec)).unwrap_err();
    assert!(err.to_string().contains("triangle inequality"), "{err}");
    // A flat plate sits exactly on the bound (Izz = Ixx + Iyy) and is accepted.
    let plate = MassSpec::Custom { mass: 1.0, inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)) };
    world.insert_body(BodyBuilder::new().mass(plate)).unwrap();
}
