//! Cause: `JointBuilder::hinge2(..).to_world(body)` reached ODE's `dJointAttach`, which
//! asserts "joint can not be attached to just one body" for a hinge-2: SIGABRT.
//! Fixed by refusing a hinge-2 without two bodies before ODE is called.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

#[test]
fn a_hinge2_to_the_world_is_refused_and_between_two_bodies_accepted() {
    let mut world = World::new();
    let a = world.insert_body(BodyBuilder::new()).unwrap();
    let b = world.insert_body(BodyBuilder::new().position(Point3::new(1.0, 0.0, 0.0))).unwrap();
    let hinge2 = || JointBuilder::hinge2(Point3::new(1.0, 0.0, 0.0), Vector3::y(), Vector3::x());
    let err = world.insert_joint(hinge2().to_world(a)).unwrap_err();
    assert!(err.to_string().contains("hinge-2"), "{err}");
    assert_eq!(world.joint_count(), 0);
    world.insert_joint(hinge2().between(a, b)).unwrap();
    world.step(0.0004).unwrap();
}

#[test]
fn motors_attached_to_the_world_with_body_relative_axes_step() {
    let mut world = World::new();
    let a = world.insert_body(BodyBuilder::new()).unwrap();
    for frame in [AxisFrame::World, AxisFrame::Body1, AxisFrame::Body2] {
        let axes = vec![(frame, Vector3::x()), (frame, Vector3::y())];
        for kind in [JointKind::AngularMotor { axes: axes.clone() }, JointKind::LinearMotor { axes }] {
            let j = world.insert_joint(JointBuilder::new(kind).to_world(a).motor(1.0, 10.0)).unwrap();
            world.step(0.0004).unwrap();
            world.remove_joint(j).unwrap();
        }
    }
}
