//! Cause: a body at x = 1e17 (or 1e300) in a hash space: `dSpaceCollide` converts the
//! geom's bounds to integer cells of 2^min_level m, overflows `int` and asserts in
//! `aabbBound`: SIGABRT. Fixed twice: coordinates beyond ±1e9 m are refused when set,
//! and before colliding a hash space, every geom must fit its integer cells (at the
//! default min_level −3: ±2.68e8 m), or the collision is an `Err` naming the geom.

use ars_core::nalgebra::{Isometry3, Point3, Vector3};
use ars_core::*;

#[test]
fn far_positions_are_refused_when_set() {
    let mut world = World::new();
    for x in [1e17, 1e300, 3e9] {
        let err = world.insert_body(BodyBuilder::new().position(Point3::new(x, 0.0, 0.0))).unwrap_err();
        assert!(matches!(err, Error::OutOfRange { what: "body position", .. }), "{err}");
    }
}

#[test]
fn a_geom_beyond_the_hash_cells_is_an_err_and_the_world_goes_on() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::HASH).unwrap();
    let far = Point3::new(5e8, 0.0, 0.0);
    let body = world.insert_body(BodyBuilder::new().position(far).mass(MassSpec::sphere_total(1.0, 0.5))).unwrap();
    let geom = world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(body)).unwrap();
    let err = world.collide(space).unwrap_err();
    assert!(err.to_string().contains(&geom.to_string()), "the geom is named: {err}");
    assert!(!world.is_poisoned());
    world.body_mut(body).unwrap().set_position(Point3::new(1e8, 0.0, 0.0)).unwrap();
    world.collide(space).unwrap();
    world.step(0.0004).unwrap();

    // A static geom far away, too.
    let pose = Isometry3::translation(0.0, -4e8, 0.0);
    world.insert_geom(space, GeomBuilder::box_edges(Vector3::new(1.0, 1.0, 1.0)).pose(pose)).unwrap();
    assert!(world.collide(space).is_err());
    // A simple space has no integer cells: the same geoms collide there.
    let simple = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(simple, GeomBuilder::box_edges(Vector3::new(1.0, 1.0, 1.0)).pose(pose)).unwrap();
    world.collide(simple).unwrap();
}

/// Steps in a world without a hash space do not measure how far the bodies are (only
/// hash spaces need it); a hash space made afterwards must still refuse a body beyond
/// its cells on its first collision, not hand it to ODE.
#[test]
fn a_hash_space_made_after_steps_still_refuses_a_far_body() {
    let mut world = World::new();
    let simple = world.create_space(SpaceKind::Simple).unwrap();
    let body = world
        .insert_body(BodyBuilder::new().position(Point3::new(5e8, 0.0, 0.0)).mass(MassSpec::sphere_total(1.0, 0.5)))
        .unwrap();
    world.insert_geom(simple, GeomBuilder::sphere(0.5).attached_to(body)).unwrap();
    for _ in 0..3 {
        world.collide(simple).unwrap();
        world.step(0.0004).unwrap();
        world.clear_contacts();
    }
    let hash = world.create_space(SpaceKind::HASH).unwrap();
    let geom = world.insert_geom(hash, GeomBuilder::sphere(0.5).attached_to(body)).unwrap();
    let err = world.collide(hash).unwrap_err();
    assert!(err.to_string().contains(&geom.to_string()), "the geom is named: {err}");
    assert!(!world.is_poisoned());
}
