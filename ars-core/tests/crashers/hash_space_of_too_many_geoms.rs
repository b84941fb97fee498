//! Cause: ODE's hash space allocates and clears a table of one bit per pair of geoms
//! at every collision (n²/8 bytes: 1.25 GB and 0.7 s a step at 100,000 spheres, found
//! measuring the scale bench) and indexes it with a C `int`, which overflows beyond
//! about 131,000 geoms: writes outside the table once two of them overlap. Fixed by
//! refusing to collide a hash space of more than `limits::MAX_HASH_SPACE_GEOMS`
//! geoms, with an `Err` that names sweep and prune, which has no such table.

use ars_core::nalgebra::Isometry3;
use ars_core::*;

#[test]
fn a_hash_space_of_too_many_geoms_is_an_err_and_sweep_and_prune_takes_them() {
    let mut world = World::new();
    let hash = world.create_space(SpaceKind::HASH).unwrap();
    let sap = world.create_space(SpaceKind::SWEEP_AND_PRUNE).unwrap();
    let n = limits::MAX_HASH_SPACE_GEOMS + 1;
    for i in 0..n {
        let pose = Isometry3::translation((i % 1000) as f64, 0.0, (i / 1000) as f64);
        for space in [hash, sap] {
            world.insert_geom(space, GeomBuilder::sphere(0.1).pose(pose)).unwrap();
        }
    }
    // Two of them overlap: the pair the hash space would have written for.
    world.insert_geom(hash, GeomBuilder::sphere(0.1)).unwrap();
    let err = world.collide(hash).unwrap_err();
    assert!(matches!(err, Error::OutOfRange { what: "geoms in a hash space", .. }), "{err}");
    assert!(err.to_string().contains("SWEEP_AND_PRUNE"), "{err}");
    assert!(!world.is_poisoned());
    world.collide(sap).unwrap();
    world.clear_contacts();
}
