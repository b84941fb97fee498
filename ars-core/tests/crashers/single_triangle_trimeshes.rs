//! Cause: two overlapping triangle meshes of one triangle each (two one-triangle
//! `add_trimesh_floor`s, say) crashed in OPCODE's trimesh–trimesh collider
//! (`dCollideTTL`): SIGSEGV, an invalid read at 0x10. OPCODE's AABB tree of a single
//! triangle is one leaf without children, and the tree–tree query reads a child of
//! it. (One such mesh against a mesh of two or more triangles is fine.) Fixed by
//! handing ODE a one-triangle mesh with its triangle twice: a two-leaf tree, the same
//! surface.

use ars_core::nalgebra::{Isometry3, Point3};
use ars_core::*;

fn triangle() -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
    (vec![Point3::new(-1.0, 0.0, -1.0), Point3::new(1.0, 0.0, -1.0), Point3::new(0.0, 0.0, 1.0)], vec![[0, 2, 1]])
}

#[test]
fn two_overlapping_one_triangle_meshes_collide_safely() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let (v, t) = triangle();
    world.insert_geom(space, GeomBuilder::trimesh(v.clone(), t.clone()).pose(Isometry3::identity())).unwrap();
    world.insert_geom(space, GeomBuilder::trimesh(v.clone(), t.clone()).pose(Isometry3::identity())).unwrap();
    let body = world.insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.5))).unwrap();
    world.insert_geom(space, GeomBuilder::trimesh(v, t).attached_to(body)).unwrap();
    for _ in 0..10 {
        world.collide(space).unwrap();
        world.step(0.0004).unwrap();
        world.clear_contacts();
    }
}

#[test]
fn two_one_triangle_floors_in_a_simulation() {
    let mut sim = Simulation::new().unwrap();
    let (v, t) = triangle();
    sim.scene_mut().add_trimesh_floor(v.clone(), t.clone(), [0.0, 0.0, 0.0]).unwrap();
    sim.scene_mut().add_trimesh_floor(v, t, [0.1, 0.0, 0.0]).unwrap();
    let ball = sim.scene_mut().add_sphere(0.2, [0.0, 0.5, 0.0], Mass::Total(1.0)).unwrap();
    sim.run_for(1.0).unwrap();
    let y = sim.scene().body(ball).unwrap().position().y;
    assert!((y - 0.2).abs() < 1e-3, "the ball rests on the triangle: y = {y}");
}
