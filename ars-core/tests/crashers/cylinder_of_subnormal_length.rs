//! Cause: a cylinder of length 5e-324 touching another reached ODE's cylinder
//! colliders, which assert "Invalid cylinder" (its degenerate axis): SIGABRT. Fixed
//! by the size range (`limits::MIN_SIZE` = 1e-9 m); cylinders at that bound collide
//! with every other shape without failing (a NaN contact that such degenerate pairs
//! yield is dropped: it would turn the step into NaN).

use ars_core::limits::MIN_SIZE;
use ars_core::nalgebra::{Isometry3, Point3, Vector3};
use ars_core::*;

#[test]
fn a_subnormal_cylinder_is_refused() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    for (r, l) in [(1.0, 5e-324), (5e-324, 1.0), (1.0, 1e-20)] {
        let err = world.insert_geom(space, GeomBuilder::cylinder(r, l)).unwrap_err();
        assert!(err.to_string().contains("cylinder"), "{err}");
    }
}

/// As long as the pairs ODE hands to libccd stay within its size ratio.
const BIG: f64 = MIN_SIZE * 1e7;

#[test]
fn cylinders_at_the_smallest_size_collide_with_every_shape() {
    let (mut world, space) = super::common::world_with_floor();
    let others = [
        GeomBuilder::sphere(MIN_SIZE),
        GeomBuilder::box_edges(Vector3::repeat(MIN_SIZE)),
        GeomBuilder::capsule(MIN_SIZE, MIN_SIZE),
        GeomBuilder::cylinder(MIN_SIZE, MIN_SIZE),
        GeomBuilder::cylinder(BIG, MIN_SIZE),
        GeomBuilder::cylinder(MIN_SIZE, BIG),
        GeomBuilder::trimesh(
            vec![Point3::new(-1.0, 0.0, -1.0), Point3::new(1.0, 0.0, -1.0), Point3::new(0.0, 0.0, 1.0)],
            vec![[0, 2, 1]],
        ),
    ];
    for other in others {
        world.insert_geom(space, other.pose(Isometry3::identity())).unwrap();
    }
    for (r, l) in [(MIN_SIZE, MIN_SIZE), (BIG, MIN_SIZE), (MIN_SIZE, BIG)] {
        let b = world.insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.5))).unwrap();
        world.insert_geom(space, GeomBuilder::cylinder(r, l).attached_to(b)).unwrap();
    }
    // Deeply overlapping degenerate shapes: some colliders give NaN normals, which
    // the collision pass drops; the steps go on.
    for _ in 0..10 {
        super::common::step(&mut world, space).unwrap();
    }
}
