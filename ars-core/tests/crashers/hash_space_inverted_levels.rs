//! Cause: `SpaceKind::Hash { min_level: 5, max_level: -5 }` reached ODE's
//! `dHashSpaceSetLevels`, which asserts `minlevel <= maxlevel`: SIGABRT, from a World
//! and from a Simulation. Fixed by checking the levels (ordered, within ±30).

use ars_core::*;

#[test]
fn inverted_or_extreme_hash_levels_are_refused() {
    let mut world = World::new();
    for (min_level, max_level) in [(5, -5), (0, 31), (-31, 0), (i32::MIN, i32::MAX)] {
        let err = world.create_space(SpaceKind::Hash { min_level, max_level }).unwrap_err();
        assert!(err.to_string().contains("hash space levels"), "{err}");
        let err = Simulation::builder().space(SpaceKind::Hash { min_level, max_level }).build().unwrap_err();
        assert!(err.to_string().contains("hash space levels"), "{err}");
    }
    world.create_space(SpaceKind::Hash { min_level: -5, max_level: 5 }).unwrap();
    world.create_space(SpaceKind::Hash { min_level: 2, max_level: 2 }).unwrap();
}
