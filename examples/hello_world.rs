//! The thesis' hello world: a 1 kg ball of radius 0.5 m dropped from (1, 1, 1) onto the
//! floor y = 0, stepped at 0.4 ms with ARS' defaults. Prints its height and vertical
//! speed every 10 ms for one second (headless).
//!
//! `cargo run --release --example hello_world`

use ars::nalgebra::{Point3, Vector3};
use ars::{BodyBuilder, GeomBuilder, MassSpec, SpaceKind, World};

fn main() -> Result<(), ars::Error> {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple);
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0))?;
    let ball = world
        .insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.5)).position(Point3::new(1.0, 1.0, 1.0)))?;
    world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(ball))?;

    let dt = 0.0004;
    let mut t = 0.0;
    println!("{:>6} {:>10} {:>11}", "t [s]", "y [m]", "vy [m/s]");
    for step in 1..=2500 {
        world.collide(space)?;
        world.step(dt)?;
        world.clear_contacts();
        t += dt;
        if step % 25 == 0 {
            let body = world.body(ball)?;
            println!("{t:>6.3} {:>10.6} {:>11.6}", body.position().y, body.linear_velocity().y);
        }
    }
    Ok(())
}
