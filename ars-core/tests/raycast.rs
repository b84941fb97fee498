//! Ray casts computed in Rust against ODE's own ray colliders: the same distances for
//! every shape, from many seeded random rays.

use ars_core::nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use ars_core::random::SplitMix64;
use ars_core::world::raycast::Ray;
use ars_core::{GeomBuilder, Shape, SpaceKind, World};

fn shapes() -> Vec<Shape> {
    let (vertices, triangles) = (
        vec![
            Point3::new(-1.0, -1.0, 0.0),
            Point3::new(1.0, -1.0, 0.2),
            Point3::new(0.0, 1.0, -0.1),
            Point3::new(0.0, 0.0, 1.0),
        ],
        vec![[0, 1, 2], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
    );
    vec![
        Shape::Sphere { radius: 0.7 },
        Shape::Box { edges: Vector3::new(1.2, 0.5, 0.8) },
        Shape::Capsule { radius: 0.3, length: 1.0 },
        Shape::Cylinder { radius: 0.4, length: 1.1 },
        Shape::Cone { radius: 0.5, height: 1.0 },
        Shape::TriMesh { vertices, triangles },
    ]
}

#[test]
fn cast_rays_agree_with_odes_ray_colliders() {
    let mut rng = SplitMix64::new(7);
    let mut u = move || rng.uniform() * 2.0 - 1.0;
    let (mut compared, mut hits) = (0, 0);
    for shape in shapes() {
        for _ in 0..200 {
            let mut world = World::new();
            let space = world.create_space(SpaceKind::Simple).unwrap();
            let rotation = UnitQuaternion::from_euler_angles(3.0 * u(), 3.0 * u(), 3.0 * u());
            let pose = Isometry3::from_parts(Translation3::new(u(), u(), u()), rotation);
            world.insert_geom(space, GeomBuilder::new(shape.clone()).pose(pose)).unwrap();
            // From 4 m away, towards a point near the shape.
            let from = Point3::from(Vector3::new(u(), u(), u()).normalize() * 4.0 + pose.translation.vector);
            let towards = pose.translation.vector + Vector3::new(u(), u(), u()) * 0.8;
            let dir = (Point3::from(towards) - from).normalize();
            let beam = UnitQuaternion::rotation_between(&Vector3::z(), &dir).unwrap();
            let ray = world
                .insert_geom(
                    space,
                    GeomBuilder::ray(10.0).pose(Isometry3::from_parts(Translation3::from(from.coords), beam)),
                )
                .unwrap();
            world.collide(space).unwrap();
            let ode = world.closest_ray_hit(ray).map(|h| h.distance);
            let ours = world.cast_ray(Ray { origin: from, direction: dir }, 10.0, None).unwrap().map(|h| h.distance);
            world.clear_contacts();
            match (ode, ours) {
                (Some(a), Some(b)) => {
                    // ODE's mesh colliders (OPCODE) work in single precision: about 1e-5 m
                    // apart at these distances (seen: 1.1e-5 at 3.6 m).
                    let tolerance = match shape {
                        Shape::Cone { .. } | Shape::TriMesh { .. } => 1e-4,
                        _ => 1e-9,
                    };
                    assert!((a - b).abs() < tolerance, "{}: ODE {a}, cast {b}", shape.kind_name());
                    hits += 1;
                }
                (None, None) => {}
                // A ray grazing an edge may be a hit for one and not the other.
                (a, b) => panic!("{}: ODE {a:?}, cast {b:?}", shape.kind_name()),
            }
            compared += 1;
        }
    }
    assert!(hits > compared / 3, "enough rays hit: {hits} of {compared}");
}

#[test]
fn a_cast_skips_the_ignored_body_and_stops_at_the_floor() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let body = world.insert_body(ars_core::BodyBuilder::new().position(Point3::new(0.0, 2.0, 0.0))).unwrap();
    world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(body)).unwrap();
    let down = Ray { origin: Point3::new(0.0, 2.0, 0.0), direction: -Vector3::y() };
    assert_eq!(world.cast_ray(down, 10.0, None).unwrap().unwrap().distance, 0.0, "inside the sphere");
    let hit = world.cast_ray(down, 10.0, Some(body)).unwrap().unwrap();
    assert!((hit.distance - 2.0).abs() < 1e-12 && hit.position.y.abs() < 1e-12, "{hit:?}");
    assert!(world.cast_ray(down, 1.5, Some(body)).unwrap().is_none(), "out of range");
    assert!(world.cast_ray(Ray { origin: Point3::origin(), direction: Vector3::zeros() }, 1.0, None).is_err());
}
