//! Every kind of bad input gets an `Err` naming what was wrong, and never reaches ODE
//! (which would abort the process or fill the world with NaN).

use ars_core::nalgebra::{Isometry3, Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use ars_core::*;

fn world_with_space() -> (World, SpaceHandle) {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    (world, space)
}

fn body(world: &mut World) -> BodyHandle {
    world.insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.5))).unwrap()
}

#[test]
fn non_positive_or_non_finite_sizes_are_refused() {
    let (mut world, space) = world_with_space();
    let cases = [
        (GeomBuilder::sphere(-1.0), "sphere radius"),
        (GeomBuilder::sphere(0.0), "sphere radius"),
        (GeomBuilder::sphere(f64::NAN), "sphere radius"),
        (GeomBuilder::box_edges(Vector3::new(1.0, -1.0, 1.0)), "box edges"),
        (GeomBuilder::capsule(0.1, f64::INFINITY), "capsule length"),
        (GeomBuilder::cylinder(0.0, 1.0), "cylinder radius"),
        (GeomBuilder::ray(-3.0), "ray length"),
    ];
    for (builder, expected) in cases {
        match world.insert_geom(space, builder) {
            Err(Error::NotPositive { what, .. } | Error::NotFinite { what, .. }) => assert_eq!(what, expected),
            other => panic!("expected NotPositive or NotFinite for {expected}, got {other:?}"),
        }
    }
    assert_eq!(world.geom_count(), 0, "nothing was created");
}

#[test]
fn bad_masses_are_refused() {
    let mut world = World::new();
    for spec in [
        MassSpec::sphere_total(0.0, 1.0),
        MassSpec::sphere_total(-2.0, 1.0),
        MassSpec::sphere_total(1.0, f64::NAN),
        MassSpec::solid(Shape::Box { edges: Vector3::new(1.0, 1.0, 1.0) }, Mass::Density(-5.0)),
        MassSpec::cylinder_total(1.0, 0.1, 0.0),
        MassSpec::Custom { mass: 1.0, inertia: Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0) },
        MassSpec::Custom { mass: 1.0, inertia: Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0) },
    ] {
        let err = world.insert_body(BodyBuilder::new().mass(spec.clone())).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("mass")
                || text.contains("density")
                || text.contains("radius")
                || text.contains("length")
                || text.contains("inertia"),
            "{spec:?}: {text}"
        );
    }
    assert_eq!(world.body_count(), 0);
}

#[test]
fn nan_and_infinite_poses_velocities_and_forces_are_refused() {
    let mut world = World::new();
    let nan = Point3::new(0.0, f64::NAN, 0.0);
    let err = world.insert_body(BodyBuilder::new().position(nan)).unwrap_err();
    assert!(matches!(err, Error::NotFinite { what: "body position", .. }), "{err}");
    assert_eq!(world.body_count(), 0, "a refused body is not half-created");

    let b = body(&mut world);
    let mut bm = world.body_mut(b).unwrap();
    assert!(matches!(bm.set_position(nan), Err(Error::NotFinite { .. })));
    let inf = Vector3::new(f64::INFINITY, 0.0, 0.0);
    assert!(matches!(bm.set_linear_velocity(inf), Err(Error::NotFinite { what: "linear velocity", .. })));
    assert!(matches!(bm.set_angular_velocity(inf), Err(Error::NotFinite { .. })));
    assert!(matches!(bm.add_force(inf), Err(Error::NotFinite { what: "force", .. })));
    assert!(matches!(bm.add_torque(inf), Err(Error::NotFinite { what: "torque", .. })));
    assert!(matches!(bm.add_force_at_point(Vector3::x(), nan), Err(Error::NotFinite { .. })));
    let bad_q = UnitQuaternion::new_unchecked(ars_core::nalgebra::Quaternion::new(f64::NAN, 0.0, 0.0, 0.0));
    assert!(matches!(bm.set_quaternion(bad_q), Err(Error::NotFinite { .. })));
    let skew = Rotation3::from_matrix_unchecked(Matrix3::new(2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    assert!(matches!(bm.set_rotation(skew), Err(Error::Invalid { .. })));
    // The body is untouched by the refused calls.
    assert_eq!(bm.position(), Point3::origin());
    assert_eq!(bm.force(), Vector3::zeros());
}

#[test]
fn zero_axes_and_normals_are_refused() {
    let (mut world, space) = world_with_space();
    let err = world.insert_geom(space, GeomBuilder::plane(Vector3::zeros(), 0.0)).unwrap_err();
    assert_eq!(err, Error::ZeroVector { what: "plane normal" });
    let a = body(&mut world);
    let b = body(&mut world);
    let err = world.insert_joint(JointBuilder::hinge(Point3::origin(), Vector3::zeros()).between(a, b)).unwrap_err();
    assert_eq!(err, Error::ZeroVector { what: "joint axis" });
    let err = world.insert_joint(JointBuilder::slider(Vector3::zeros()).between(a, b)).unwrap_err();
    assert_eq!(err, Error::ZeroVector { what: "joint axis" });
    let parallel = JointBuilder::universal(Point3::origin(), Vector3::x(), Vector3::x() * 2.0).between(a, b);
    let err = world.insert_joint(parallel).unwrap_err();
    assert!(matches!(err, Error::Invalid { what: "universal joint axes", .. }), "{err}");
    assert!(err.to_string().starts_with("universal joint axes must be perpendicular"), "{err}");
    assert_eq!(world.joint_count(), 0);
}

#[test]
fn a_joint_from_a_body_to_itself_is_refused() {
    let mut world = World::new();
    let a = body(&mut world);
    let err = world.insert_joint(JointBuilder::hinge(Point3::origin(), Vector3::y()).between(a, a)).unwrap_err();
    assert!(matches!(err, Error::SelfJoint { joint: "hinge", .. }), "{err}");
    assert!(err.to_string().contains("to itself"));
    let err = world.insert_joint(JointBuilder::fixed()).unwrap_err();
    assert!(matches!(err, Error::Invalid { what: "a joint", .. }), "{err}");
    assert_eq!(err.to_string(), "a joint needs a body (use `between` or `to_world`); this fixed joint has none");
}

#[test]
fn stale_handles_are_errors_not_crashes() {
    let (mut world, space) = world_with_space();
    let a = body(&mut world);
    let b = body(&mut world);
    let g = world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(a)).unwrap();
    let j = world.insert_joint(JointBuilder::ball(Point3::origin()).between(a, b)).unwrap();
    world.remove_body(a).unwrap();
    // The body went with its geom and its joint.
    assert!(matches!(world.body(a), Err(Error::StaleHandle { kind: "body", .. })));
    assert!(matches!(world.geom(g), Err(Error::StaleHandle { kind: "geom", .. })));
    assert!(matches!(world.joint(j), Err(Error::StaleHandle { kind: "joint", .. })));
    assert!(matches!(world.remove_body(a), Err(Error::StaleHandle { .. })));
    assert!(matches!(
        world.insert_geom(space, GeomBuilder::sphere(1.0).attached_to(a)),
        Err(Error::StaleHandle { .. })
    ));
    // A new body reusing the slot does not revive the old handle.
    let c = body(&mut world);
    assert_ne!(a, c);
    assert!(world.body(a).is_err());
    assert!(world.body(c).is_ok());
    // The world still steps.
    world.collide(space).unwrap();
    world.step(0.001).unwrap();
}

#[test]
fn handles_of_another_world_are_refused() {
    let mut one = World::new();
    let mut two = World::new();
    let a = body(&mut one);
    let space_two = two.create_space(SpaceKind::Simple).unwrap();
    let err = two.body(a).unwrap_err();
    assert!(matches!(err, Error::ForeignHandle { kind: "body", .. }), "{err}");
    assert!(err.to_string().contains("another world"));
    assert!(matches!(one.collide(space_two), Err(Error::ForeignHandle { kind: "space", .. })));
    let b = body(&mut two);
    let mixed = JointBuilder::ball(Point3::origin()).between(b, a);
    assert!(matches!(two.insert_joint(mixed), Err(Error::ForeignHandle { .. })));
}

#[test]
fn triangle_meshes_with_out_of_range_indices_are_refused() {
    let (mut world, space) = world_with_space();
    let vertices = vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    let err = world.insert_geom(space, GeomBuilder::trimesh(vertices.clone(), vec![[0, 1, 3]])).unwrap_err();
    assert!(matches!(&err, Error::InvalidMesh(m) if m.contains("vertex 3")), "{err}");
    assert!(matches!(
        world.insert_geom(space, GeomBuilder::trimesh(vertices.clone(), vec![])),
        Err(Error::InvalidMesh(_))
    ));
    let nan = vec![Point3::new(f64::NAN, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    assert!(matches!(world.insert_geom(space, GeomBuilder::trimesh(nan, vec![[0, 1, 2]])), Err(Error::InvalidMesh(_))));
    assert!(world.insert_geom(space, GeomBuilder::trimesh(vertices, vec![[0, 2, 1]])).is_ok());
}

#[test]
fn operations_a_kind_does_not_have_are_refused() {
    let (mut world, space) = world_with_space();
    let a = body(&mut world);
    let b = body(&mut world);
    let plane = world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    assert!(matches!(world.geom_mut(plane).unwrap().set_position(Point3::origin()), Err(Error::WrongGeomKind { .. })));
    let attached_plane = GeomBuilder::plane(Vector3::y(), 0.0).attached_to(a);
    assert!(matches!(world.insert_geom(space, attached_plane), Err(Error::WrongGeomKind { kind: "plane", .. })));
    let ball = world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(a)).unwrap();
    assert!(world.geom_mut(ball).unwrap().set_position(Point3::origin()).is_err(), "attached geoms follow the body");
    assert!(world.geom_mut(ball).unwrap().set_ray_length(2.0).is_err());

    let slider = world.insert_joint(JointBuilder::slider(Vector3::x()).between(a, b)).unwrap();
    let err = world.joint(slider).unwrap().angle().unwrap_err();
    assert_eq!(err, Error::WrongJointKind { operation: "angle", kind: "slider" });
    assert!(world.joint_mut(slider).unwrap().add_torque(1.0).is_err());
    let fixed = world.insert_joint(JointBuilder::fixed().to_world(a)).unwrap();
    assert!(world.joint_mut(fixed).unwrap().set_motor(0, 1.0, 1.0).is_err());
}

#[test]
fn bad_world_and_joint_parameters_are_refused() {
    let mut world = World::new();
    assert!(world.set_erp(1.5).is_err());
    assert!(world.set_cfm(-1.0).is_err());
    assert!(world.set_gravity(Vector3::new(0.0, f64::NAN, 0.0)).is_err());
    assert!(world.step(0.0).is_err());
    assert!(world.step(f64::NAN).is_err());
    assert!(world.set_stepper(Stepper::Quick { iterations: 0 }).is_err());
    assert!(world.set_default_surface(ContactSurface { mu: -1.0, ..Default::default() }).is_err());
    assert!(world.set_default_surface(ContactSurface { bounce: Some((1.5, 0.0)), ..Default::default() }).is_err());
    assert!(world.set_default_surface(ContactSurface { max_contacts: 151, ..Default::default() }).is_err());
    assert_eq!(world.erp(), DEFAULT_ERP);
    assert_eq!(world.cfm(), DEFAULT_CFM);

    let a = body(&mut world);
    let hinge = JointBuilder::hinge(Point3::origin(), Vector3::z()).to_world(a);
    assert!(matches!(world.insert_joint(hinge.clone().limits(1.0, -1.0)), Err(Error::OutOfRange { .. })));
    assert!(world.insert_joint(hinge.clone().param(JointParam::Velocity, 1, 1.0)).is_err(), "a hinge has one axis");
    assert!(world.insert_joint(hinge.clone().motor(1.0, -5.0)).is_err());
    let h = world.insert_joint(hinge).unwrap();
    let mut j = world.joint_mut(h).unwrap();
    assert!(j.set_limits(0, 0.5, 0.1).is_err());
    assert!(j.add_torque(f64::NAN).is_err());
    j.set_limits(0, -0.5, 0.5).unwrap();
    assert_eq!(j.param(JointParam::LoStop, 0).unwrap(), -0.5);
    assert!(j.set_param(JointParam::HiStop, 0, -1.0).is_err(), "would cross the low stop");
}

#[test]
fn offsets_and_poses_must_fit_the_geom() {
    let (mut world, space) = world_with_space();
    let a = body(&mut world);
    let offset = Isometry3::translation(0.0, 1.0, 0.0);
    assert!(world.insert_geom(space, GeomBuilder::sphere(0.1).offset(offset)).is_err(), "an offset needs a body");
    assert!(world.insert_geom(space, GeomBuilder::sphere(0.1).attached_to(a).pose(offset)).is_err());
    let nan = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(world.insert_geom(space, GeomBuilder::sphere(0.1).pose(nan)).is_err());
}
