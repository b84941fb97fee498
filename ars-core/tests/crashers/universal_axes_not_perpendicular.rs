//! Cause: a universal joint whose two axes are not perpendicular was accepted; ODE's
//! universal joint keeps its axes perpendicular by construction, so the joint
//! silently became another one. Now refused (to 1e-6 in the cosine), from a World and
//! from a Simulation.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

#[test]
fn skewed_universal_axes_are_refused() {
    let mut world = World::new();
    let a = world.insert_body(BodyBuilder::new()).unwrap();
    let b = world.insert_body(BodyBuilder::new()).unwrap();
    let skewed = JointBuilder::universal(Point3::origin(), Vector3::x(), Vector3::new(1.0, 1.0, 0.0));
    let err = world.insert_joint(skewed.between(a, b)).unwrap_err();
    assert!(err.to_string().contains("perpendicular"), "{err}");
    world.insert_joint(JointBuilder::universal(Point3::origin(), Vector3::x(), Vector3::y()).between(a, b)).unwrap();

    let mut sim = Simulation::new().unwrap();
    let o1 = sim.add_sphere(0.1, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let o2 = sim.add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let err = sim.add_universal_joint("u", o1, o2, Point3::origin(), [1.0, 0.0, 0.0], [1.0, 0.1, 0.0]).unwrap_err();
    assert!(err.to_string().contains("perpendicular"), "{err}");
}
