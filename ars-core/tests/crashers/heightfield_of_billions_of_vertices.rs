//! Cause (found reading the API for sizes that allocate): `Heightfield::constant(u32::MAX,
//! u32::MAX, 0.0)` multiplied the sizes in `u32` (a panic in debug builds, a wrong
//! capacity in release) and `heightfield_triangles(100_000, 100_000)` allocated 2e10
//! faces: an out-of-memory abort. Fixed by a grid limit (`MAX_GRID_VERTICES`, a
//! 2048 × 2048 grid), checked in `u64`. Likewise, QuickStep iterations are bounded so
//! that one step ends in finite time.

use ars_core::*;

#[test]
fn grids_beyond_the_limit_are_refused() {
    for (x, z) in [(u32::MAX, u32::MAX), (100_000, 100_000), (2, u32::MAX)] {
        let err = Heightfield::constant(x, z, 0.0).unwrap_err();
        assert!(err.to_string().contains("heightfield size"), "{err}");
        assert!(heightfield_triangles(x, z).is_err());
    }
    let field = Heightfield::constant(2048, 2048, 0.0).unwrap();
    assert_eq!(field.triangles().len(), 2 * 2047 * 2047);
}

#[test]
fn quickstep_iterations_are_bounded() {
    let mut world = World::new();
    for iterations in [0, 100_001, u32::MAX] {
        assert!(world.set_stepper(Stepper::Quick { iterations }).is_err(), "{iterations}");
    }
    world.set_stepper(Stepper::Quick { iterations: 100_000 }).unwrap();
}
