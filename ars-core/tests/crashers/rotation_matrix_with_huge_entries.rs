//! Cause (found by `cargo fuzz`): a "rotation" matrix with entries of ±f64::MAX passed
//! the orthonormality check, because `M·Mᵀ − I` overflowed to ∞ − ∞ = NaN and
//! `NaN > 1e-6` is false; ODE's `dBodySetRotation` then asserted in
//! `dxOrthogonalizeR` (`!row1_norm_fault`): SIGABRT. Fixed by bounding the entries
//! first and writing the comparisons so that NaN fails them.

use ars_core::nalgebra::{Matrix3, Rotation3};
use ars_core::*;

#[test]
fn a_matrix_of_huge_entries_is_not_a_rotation() {
    let max = f64::MAX;
    let m = Matrix3::new(-max, 0.0, -max, 0.0, 1.25, 5e-324, -max, 0.0, -10.0);
    let mut world = World::new();
    let err = world.insert_body(BodyBuilder::new().rotation(Rotation3::from_matrix_unchecked(m))).unwrap_err();
    assert!(err.to_string().contains("body rotation"), "{err}");
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    assert!(world.body_mut(b).unwrap().set_rotation(Rotation3::from_matrix_unchecked(m)).is_err());
    let nan = Matrix3::from_element(f64::NAN);
    assert!(world.body_mut(b).unwrap().set_rotation(Rotation3::from_matrix_unchecked(nan)).is_err());
}
