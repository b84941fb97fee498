//! Cause (found by `cargo fuzz`, a 33 s timeout): 21 deeply overlapping bodies made
//! 1,640 contact points in one island; `dWorldStep` solves an island as one dense
//! problem whose cost grows with the cube of its size, and the one step took 43 s:
//! to a user, a hang. Now the exact stepper refuses an island of more than
//! `limits::DEFAULT_EXACT_STEP_CONTACTS` contacts with an `Err` that says what to do
//! (QuickStep, fewer contacts per pair, or a higher limit); separate islands with as
//! many contacts in all are unaffected.

use ars_core::limits::DEFAULT_EXACT_STEP_CONTACTS;
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

fn boxes(world: &mut World, space: SpaceHandle, at: impl Iterator<Item = Point3<f64>>) {
    for p in at {
        let b = world
            .insert_body(BodyBuilder::new().position(p).mass(MassSpec::box_total(1.0, Vector3::repeat(1.0))))
            .unwrap();
        world.insert_geom(space, GeomBuilder::box_edges(Vector3::repeat(1.0)).attached_to(b)).unwrap();
    }
}

#[test]
fn one_island_of_too_many_contacts_is_an_err_for_the_exact_stepper() {
    let (mut world, space) = super::common::world_with_floor();
    // 24 unit boxes overlapping within a 0.2 m cube: one island, about 8 contacts a pair.
    boxes(&mut world, space, (0..24).map(|i| Point3::new(0.01 * i as f64, 0.45 + 0.008 * i as f64, 0.005 * i as f64)));
    world.collide(space).unwrap();
    assert!(world.contacts().len() > DEFAULT_EXACT_STEP_CONTACTS, "{} contacts", world.contacts().len());
    let err = world.step(0.0004).unwrap_err();
    assert!(err.to_string().contains("contacts in one island"), "{err}");
    assert_eq!(world.time(), 0.0);
    // QuickStep takes it (linear in the contacts).
    world.set_stepper(Stepper::Quick { iterations: 20 }).unwrap();
    world.step(0.0004).unwrap();
    world.clear_contacts();
}

#[test]
fn many_contacts_in_separate_islands_are_fine() {
    let (mut world, space) = super::common::world_with_floor();
    // 150 boxes resting apart on the floor: 4 contacts each, 600 in all, islands of one.
    boxes(&mut world, space, (0..150).map(|i| Point3::new(2.0 * (i % 15) as f64, 0.499, 2.0 * (i / 15) as f64)));
    world.collide(space).unwrap();
    assert!(world.contacts().len() > DEFAULT_EXACT_STEP_CONTACTS, "{} contacts", world.contacts().len());
    world.step(0.0004).unwrap();
}
