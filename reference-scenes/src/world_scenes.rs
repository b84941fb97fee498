//! The reference scenes through `ars-core`, call for call as in `tests/c`.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{
    BodyBuilder, BodyHandle, GeomBuilder, JointBuilder, JointHandle, MassSpec, SpaceHandle, SpaceKind, World,
    convert::rotation_about_axis,
};

use crate::native::{BodyState, drop_pile_position};

/// A world, its space, its bodies in creation order and an optional hinge torque.
pub struct RustScene {
    /// The world.
    pub world: World,
    /// Its one space (with the floor plane y = 0).
    pub space: SpaceHandle,
    /// The bodies, in creation order (the C scene's order).
    pub bodies: Vec<BodyHandle>,
    /// Time step, s.
    pub dt: f64,
    /// A hinge and the torque added to it before every step.
    pub torque: Option<(JointHandle, f64)>,
}

impl RustScene {
    fn new(kind: SpaceKind) -> Self {
        let mut world = World::new();
        let space = world.create_space(kind).unwrap();
        world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
        RustScene { world, space, bodies: Vec::new(), dt: 0.0004, torque: None }
    }

    /// The thesis' falling ball.
    pub fn falling_sphere() -> Self {
        let mut s = Self::new(SpaceKind::Simple);
        let ball = s
            .world
            .insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(1.0, 0.5)).position(Point3::new(1.0, 1.0, 1.0)))
            .unwrap();
        s.world.insert_geom(s.space, GeomBuilder::sphere(0.5).attached_to(ball)).unwrap();
        s.bodies.push(ball);
        s
    }

    /// Two hinged cylinders with a torque on the first hinge.
    pub fn hinge_chain() -> Self {
        let mut s = Self::new(SpaceKind::Simple);
        let along_x = rotation_about_axis(&Vector3::y(), std::f64::consts::FRAC_PI_2);
        for cx in [0.5, 1.5] {
            let b = s
                .world
                .insert_body(
                    BodyBuilder::new()
                        .mass(MassSpec::cylinder_total(1.0, 0.1, 1.0))
                        .position(Point3::new(cx, 1.9, 0.0))
                        .rotation(along_x),
                )
                .unwrap();
            s.world.insert_geom(s.space, GeomBuilder::cylinder(0.1, 1.0).attached_to(b)).unwrap();
            s.bodies.push(b);
        }
        let (a, b) = (s.bodies[0], s.bodies[1]);
        let j1 =
            s.world.insert_joint(JointBuilder::hinge(Point3::new(0.0, 1.9, 0.0), Vector3::z()).to_world(a)).unwrap();
        s.world.insert_joint(JointBuilder::hinge(Point3::new(1.0, 1.9, 0.0), Vector3::z()).between(a, b)).unwrap();
        s.torque = Some((j1, 2.0));
        s
    }

    /// `count` spheres and boxes dropped in a hash space.
    pub fn drop_pile(count: usize) -> Self {
        let mut s = Self::new(SpaceKind::HASH);
        for i in 0..count {
            let [x, y, z] = drop_pile_position(i);
            let (mass, geom) = if i % 2 == 0 {
                (MassSpec::sphere_total(1.0, 0.2), GeomBuilder::sphere(0.2))
            } else {
                let size = Vector3::new(0.3, 0.3, 0.3);
                (MassSpec::box_total(1.0, size), GeomBuilder::box_edges(size))
            };
            let b = s.world.insert_body(BodyBuilder::new().mass(mass).position(Point3::new(x, y, z))).unwrap();
            s.world.insert_geom(s.space, geom.attached_to(b)).unwrap();
            s.bodies.push(b);
        }
        s
    }

    /// Runs `n` steps: pre-step torque, collide, step, clear contacts.
    pub fn step(&mut self, n: usize) {
        for _ in 0..n {
            if let Some((j, t)) = self.torque {
                self.world.joint_mut(j).unwrap().add_torque(t).unwrap();
            }
            self.world.collide(self.space).unwrap();
            self.world.step(self.dt).unwrap();
            self.world.clear_contacts();
        }
    }

    /// State of body `i`, laid out as [`BodyState`].
    pub fn body_state(&self, i: usize) -> BodyState {
        let b = self.world.body(self.bodies[i]).unwrap();
        let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
        [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z]
    }
}
