//! Helpers shared by the crashers.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

/// A world with one simple space and the floor plane y = 0.
pub fn world_with_floor() -> (World, SpaceHandle) {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    (world, space)
}

/// A 1 kg ball of radius 0.5 m at `at`, with its geom in `space`.
pub fn ball(world: &mut World, space: SpaceHandle, at: Point3<f64>) -> BodyHandle {
    let b = world.insert_body(BodyBuilder::new().position(at).mass(MassSpec::sphere_total(1.0, 0.5))).unwrap();
    world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(b)).unwrap();
    b
}

/// Collide, step, clear: one step of the usual loop.
pub fn step(world: &mut World, space: SpaceHandle) -> Result<()> {
    let collided = world.collide(space);
    let stepped = collided.and_then(|()| world.step(0.0004));
    world.clear_contacts();
    stepped
}
