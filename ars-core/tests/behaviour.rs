//! What the safe layer does with good input: joints, motors, limits, feedback, rays,
//! contact hooks, kinematic bodies, threads and panics in user hooks.

use std::f64::consts::FRAC_PI_2;

use ars_core::nalgebra::{Isometry3, Point3, Vector3};
use ars_core::*;

const DT: f64 = 0.0004;

fn run(world: &mut World, space: SpaceHandle, steps: usize) {
    for _ in 0..steps {
        world.collide(space).unwrap();
        world.step(DT).unwrap();
        world.clear_contacts();
    }
}

fn falling_ball(world: &mut World, space: SpaceHandle, at: Point3<f64>) -> BodyHandle {
    let b = world.insert_body(BodyBuilder::new().position(at).mass(MassSpec::sphere_total(1.0, 0.5))).unwrap();
    world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(b)).unwrap();
    b
}

#[test]
fn free_fall_follows_semi_implicit_euler() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(0.0, 10.0, 0.0));
    run(&mut world, space, 100);
    let body = world.body(b).unwrap();
    // v_n = -g n dt, y_n = y0 - g dt² n(n+1)/2
    assert!((body.linear_velocity().y + 9.81 * 100.0 * DT).abs() < 1e-12);
    assert!((body.position().y - (10.0 - 9.81 * DT * DT * 5050.0)).abs() < 1e-12);
}

#[test]
fn a_hinged_pendulum_swings_and_its_joint_reports_angle_and_rate() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    // A 1 kg ball on a massless 1 m arm, hinged to the world about Z, starting horizontal.
    let b = falling_ball(&mut world, space, Point3::new(1.0, 5.0, 0.0));
    let j = world.insert_joint(JointBuilder::hinge(Point3::new(0.0, 5.0, 0.0), Vector3::z()).to_world(b)).unwrap();
    assert_eq!(world.joint(j).unwrap().angle().unwrap(), 0.0);
    run(&mut world, space, 500);
    let joint = world.joint(j).unwrap();
    let angle = joint.angle().unwrap();
    // Falling clockwise about +Z: the angle goes negative and keeps the arm length.
    assert!(angle < -0.1, "angle {angle}");
    assert!(joint.angle_rate().unwrap() < 0.0);
    let p = world.body(b).unwrap().position();
    assert!(((p - Point3::new(0.0, 5.0, 0.0)).norm() - 1.0).abs() < 1e-3);
    assert!((joint.anchor().unwrap() - Point3::new(0.0, 5.0, 0.0)).norm() < 1e-3);
}

#[test]
fn a_hinge_torque_turns_body1_positively_about_the_axis() {
    let mut world = World::new();
    world.set_gravity(Vector3::zeros()).unwrap();
    let a = world.insert_body(BodyBuilder::new().mass(MassSpec::box_total(1.0, Vector3::new(1.0, 1.0, 1.0)))).unwrap();
    let j = world.insert_joint(JointBuilder::hinge(Point3::origin(), Vector3::y()).to_world(a)).unwrap();
    for _ in 0..100 {
        world.joint_mut(j).unwrap().add_torque(1.0).unwrap();
        world.step(DT).unwrap();
    }
    let w = world.body(a).unwrap().angular_velocity();
    // I_yy = m (1² + 1²) / 12 = 1/6: ω = τ t / I = 1 · 0.04 · 6 = 0.24 rad/s about +Y.
    assert!((w.y - 0.24).abs() < 1e-9, "{w}");
    assert!((world.joint(j).unwrap().angle_rate().unwrap() - 0.24).abs() < 1e-9);
}

#[test]
fn limits_stop_the_joint_and_motors_reach_their_speed() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(1.0, 5.0, 0.0));
    let stop = -0.3;
    let j = world
        .insert_joint(JointBuilder::hinge(Point3::new(0.0, 5.0, 0.0), Vector3::z()).to_world(b).limits(stop, 0.3))
        .unwrap();
    run(&mut world, space, 2500);
    let angle = world.joint(j).unwrap().angle().unwrap();
    assert!((angle - stop).abs() < 0.02, "held near the stop, angle {angle}");

    // Now a strong motor turns it the other way at 0.5 rad/s. The stops are widened to
    // ±3 rad, not removed: ODE stops testing a hinge's limit once both stops lie
    // beyond ±π and keeps it "at the stop" it last touched (see `set_limits`).
    let mut jm = world.joint_mut(j).unwrap();
    jm.set_limits(0, -3.0, 3.0).unwrap();
    jm.set_motor(0, 0.5, 100.0).unwrap();
    run(&mut world, space, 250);
    let rate = world.joint(j).unwrap().angle_rate().unwrap();
    assert!((rate - 0.5).abs() < 1e-6, "motor rate {rate}");
}

#[test]
fn joint_feedback_reports_the_force_holding_a_body() {
    let mut world = World::new();
    let b = world
        .insert_body(BodyBuilder::new().position(Point3::new(0.0, 1.0, 0.0)).mass(MassSpec::sphere_total(2.0, 0.1)))
        .unwrap();
    let j = world.insert_joint(JointBuilder::ball(Point3::new(0.0, 1.0, 0.0)).to_world(b).feedback()).unwrap();
    assert_eq!(world.joint(j).unwrap().feedback().unwrap().force1, Vector3::zeros());
    world.step(DT).unwrap();
    let f = world.joint(j).unwrap().feedback().unwrap();
    // The joint holds 2 kg against gravity: 19.62 N up on the body, less the share
    // that the global CFM gives way: m g (1/m) / (1/m + CFM/dt).
    let expected = 19.62 * 0.5 / (0.5 + DEFAULT_CFM / DT);
    assert!((f.force1 - Vector3::new(0.0, expected, 0.0)).norm() < 1e-9, "{f:?} vs {expected}");
    assert!(world.body(b).unwrap().linear_velocity().norm() < 1e-6);
}

#[test]
fn a_slider_reports_its_position_and_a_force_moves_it() {
    let mut world = World::new();
    world.set_gravity(Vector3::zeros()).unwrap();
    let b = world.insert_body(BodyBuilder::new().mass(MassSpec::sphere_total(2.0, 0.1))).unwrap();
    let j = world.insert_joint(JointBuilder::slider(Vector3::x()).to_world(b)).unwrap();
    for _ in 0..100 {
        world.joint_mut(j).unwrap().add_force(4.0).unwrap();
        world.step(DT).unwrap();
    }
    let joint = world.joint(j).unwrap();
    // a = 2 m/s², t = 0.04 s: v = 0.08 m/s.
    assert!((joint.position_rate().unwrap() - 0.08).abs() < 1e-9);
    assert!(joint.position().unwrap() > 0.0);
}

#[test]
fn geoms_with_an_offset_collide_where_they_are() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let b = world
        .insert_body(BodyBuilder::new().position(Point3::new(0.0, 2.0, 0.0)).mass(MassSpec::sphere_total(1.0, 0.5)))
        .unwrap();
    // The sphere hangs 1 m below the body origin.
    let offset = Isometry3::translation(0.0, -1.0, 0.0);
    world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(b).offset(offset)).unwrap();
    run(&mut world, space, 5000);
    let y = world.body(b).unwrap().position().y;
    assert!((y - 1.5).abs() < 2e-3, "body rests with its offset sphere on the floor, y = {y}");
}

#[test]
fn rays_record_every_hit_and_the_closest_is_found() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.set_gravity(Vector3::zeros()).unwrap();
    for x in [5.0, 3.0, 8.0] {
        falling_ball(&mut world, space, Point3::new(x, 0.0, 0.0));
    }
    // A ray from the origin along +X (local +Z turned by π/2 about Y), 100 m long.
    let along_x = Isometry3::rotation(Vector3::y() * FRAC_PI_2);
    let ray = world.insert_geom(space, GeomBuilder::ray(100.0).pose(along_x)).unwrap();
    world.collide(space).unwrap();
    assert_eq!(world.ray_hits().len(), 3);
    assert!(world.contacts().is_empty(), "rays make no contact joints");
    let hit = world.closest_ray_hit(ray).unwrap();
    assert!((hit.distance - 2.5).abs() < 1e-12, "{hit:?}");
    assert!((hit.position - Point3::new(2.5, 0.0, 0.0)).norm() < 1e-12);
    world.geom_mut(ray).unwrap().set_ray_length(1.0).unwrap();
    world.collide(space).unwrap();
    assert_eq!(world.closest_ray_hit(ray), None, "too short to reach");
}

#[test]
fn hooks_choose_the_surface_of_each_pair() {
    struct Ghost(GeomHandle);
    impl CollisionHooks for Ghost {
        fn contact_surface(&mut self, pair: &GeomPair, default: &ContactSurface) -> Option<ContactSurface> {
            if pair.geom1 == self.0 || pair.geom2 == self.0 { None } else { Some(*default) }
        }
    }
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let solid = falling_ball(&mut world, space, Point3::new(0.0, 1.0, 0.0));
    let ghost_body = world.insert_body(BodyBuilder::new().position(Point3::new(3.0, 1.0, 0.0))).unwrap();
    let ghost = world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(ghost_body)).unwrap();
    let mut hooks = Ghost(ghost);
    for _ in 0..2500 {
        world.collide_with(space, &mut hooks).unwrap();
        world.step(DT).unwrap();
        world.clear_contacts();
    }
    assert!((world.body(solid).unwrap().position().y - 0.5).abs() < 1e-3);
    assert!(world.body(ghost_body).unwrap().position().y < -1.0, "the ghost fell through the floor");
}

#[test]
fn hooks_are_not_asked_for_a_geom_wholly_above_a_plane_in_any_space() {
    struct Count(usize);
    impl CollisionHooks for Count {
        fn contact_surface(&mut self, _: &GeomPair, default: &ContactSurface) -> Option<ContactSurface> {
            self.0 += 1;
            Some(*default)
        }
    }
    // A simple space leaves the pair out before the near callback (ode-sys's
    // simple_space.c), the others (ODE's own, ARS's grid) in the callback.
    for kind in [SpaceKind::Simple, SpaceKind::HASH, SpaceKind::SWEEP_AND_PRUNE, SpaceKind::Grid] {
        let mut world = World::new();
        let space = world.create_space(kind).unwrap();
        world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
        let ball = falling_ball(&mut world, space, Point3::new(0.0, 0.5 + 1e-9, 0.0));
        let mut hooks = Count(0);
        world.collide_with(space, &mut hooks).unwrap();
        assert_eq!((hooks.0, world.contacts().len()), (0, 0), "{kind:?}: the ball's box is above the floor");
        world.clear_contacts();
        world.body_mut(ball).unwrap().set_position(Point3::new(0.0, 0.5 - 1e-3, 0.0)).unwrap();
        world.collide_with(space, &mut hooks).unwrap();
        assert_eq!(hooks.0, 1, "{kind:?}: asked once the ball's box reaches the floor");
        assert!(!world.contacts().is_empty(), "{kind:?}");
        world.clear_contacts();
    }
}

#[test]
fn jointed_bodies_do_not_collide() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.set_gravity(Vector3::zeros()).unwrap();
    let a = falling_ball(&mut world, space, Point3::new(0.0, 0.0, 0.0));
    let b = falling_ball(&mut world, space, Point3::new(0.5, 0.0, 0.0));
    world.collide(space).unwrap();
    assert!(!world.contacts().is_empty(), "overlapping balls touch");
    world.clear_contacts();
    world.insert_joint(JointBuilder::ball(Point3::new(0.25, 0.0, 0.0)).between(a, b)).unwrap();
    world.collide(space).unwrap();
    assert!(world.contacts().is_empty(), "joined balls do not");
}

#[test]
fn a_panic_in_a_hook_reaches_the_caller_not_ode() {
    struct Boom;
    impl CollisionHooks for Boom {
        fn contact_surface(&mut self, _: &GeomPair, _: &ContactSurface) -> Option<ContactSurface> {
            panic!("boom from a hook");
        }
    }
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(0.0, 0.4, 0.0));
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| world.collide_with(space, &mut Boom)));
    let payload = caught.unwrap_err();
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"boom from a hook"));
    // The world is still whole and usable.
    world.clear_contacts();
    run(&mut world, space, 10);
    assert!(world.body(b).unwrap().position().y.is_finite());
}

#[test]
fn kinematic_bodies_move_with_their_velocity_only() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let k = world.insert_body(BodyBuilder::kinematic().linear_velocity(Vector3::new(1.0, 0.0, 0.0))).unwrap();
    assert!(world.body(k).unwrap().is_kinematic());
    run(&mut world, space, 250);
    let p = world.body(k).unwrap().position();
    assert!((p - Point3::new(0.1, 0.0, 0.0)).norm() < 1e-12, "no gravity on a kinematic body: {p}");
}

#[test]
fn quickstep_is_selectable() {
    // The same pile with each stepper: QuickStep's iterative solver lands somewhere
    // else than dWorldStep's exact one (so `set_stepper` demonstrably did something),
    // and still rests the boxes on the floor.
    let rest = |stepper: Stepper| {
        let mut world = World::new();
        let space = world.create_space(SpaceKind::HASH).unwrap();
        world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
        world.set_stepper(stepper).unwrap();
        assert_eq!(world.stepper(), stepper);
        let size = Vector3::repeat(1.0);
        let boxes: Vec<_> = (0..3)
            .map(|i| {
                let at = Point3::new(0.2 * i as f64, 0.5 + 1.02 * i as f64, 0.0);
                let b =
                    world.insert_body(BodyBuilder::new().position(at).mass(MassSpec::box_total(1.0, size))).unwrap();
                world.insert_geom(space, GeomBuilder::box_edges(size).attached_to(b)).unwrap();
                b
            })
            .collect();
        run(&mut world, space, 2500);
        boxes.iter().map(|&b| world.body(b).unwrap().position()).collect::<Vec<_>>()
    };
    let exact = rest(Stepper::Exact);
    let quick = rest(Stepper::Quick { iterations: 30 });
    assert_ne!(exact, quick, "QuickStep gave dWorldStep's result bit for bit: was it used?");
    assert!((quick[0].y - 0.5).abs() < 5e-3, "the bottom box rests on the floor: {}", quick[0].y);
}

fn trajectory() -> Vec<u64> {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(1.0, 1.0, 1.0));
    (0..2500)
        .map(|_| {
            run(&mut world, space, 1);
            world.body(b).unwrap().position().y.to_bits()
        })
        .collect()
}

/// A pile of boxes whose QuickStep order depends on ODE's random generator, stepped
/// `steps` times; with `disturb`, another QuickStep world steps in between each step.
fn quickstep_pile(steps: usize, seed: u32, disturb: Option<&mut (World, SpaceHandle)>) -> Vec<u64> {
    let mut world = World::new();
    world.set_stepper(Stepper::Quick { iterations: 10 }).unwrap();
    world.set_random_seed(seed);
    let space = world.create_space(SpaceKind::Simple).unwrap();
    world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    let boxes: Vec<_> = (0..6)
        .map(|i| {
            let at = Point3::new(0.1 * i as f64, 0.5 + 1.01 * i as f64, 0.0);
            let b = world
                .insert_body(BodyBuilder::new().position(at).mass(MassSpec::box_total(1.0, Vector3::repeat(1.0))))
                .unwrap();
            world.insert_geom(space, GeomBuilder::box_edges(Vector3::repeat(1.0)).attached_to(b)).unwrap();
            b
        })
        .collect();
    let mut disturb = disturb;
    let mut out = Vec::new();
    for _ in 0..steps {
        run(&mut world, space, 1);
        if let Some((other, other_space)) = disturb.as_deref_mut() {
            run(other, *other_space, 1);
        }
        out.extend(boxes.iter().map(|&b| world.body(b).unwrap().position().x.to_bits()));
    }
    out
}

#[test]
fn quickstep_is_deterministic_per_world_whatever_other_worlds_do() {
    let alone = quickstep_pile(400, 5, None);
    let mut other = World::new();
    other.set_stepper(Stepper::Quick { iterations: 10 }).unwrap();
    other.set_random_seed(99);
    let other_space = other.create_space(SpaceKind::Simple).unwrap();
    other.insert_geom(other_space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
    for i in 0..4 {
        let b = falling_ball(&mut other, other_space, Point3::new(0.3 * i as f64, 0.5 + i as f64, 0.0));
        let _ = b;
    }
    let mut disturbance = (other, other_space);
    assert_eq!(quickstep_pile(400, 5, Some(&mut disturbance)), alone, "another world's QuickSteps change nothing");
    assert_ne!(quickstep_pile(400, 6, None), alone, "the seed matters: the test can see a difference");
}

#[test]
fn worlds_on_different_threads_give_identical_results() {
    let reference = trajectory();
    let handles: Vec<_> = (0..4).map(|_| std::thread::spawn(trajectory)).collect();
    for h in handles {
        assert_eq!(h.join().unwrap(), reference);
    }
    // A world can also be built on one thread and stepped on another.
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(0.0, 1.0, 0.0));
    let y = std::thread::spawn(move || {
        run(&mut world, space, 10);
        world.body(b).unwrap().position().y
    })
    .join()
    .unwrap();
    assert!(y < 1.0);
}

#[test]
fn removing_joints_and_geoms_between_steps() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let b = falling_ball(&mut world, space, Point3::new(0.0, 1.0, 0.0));
    let j = world.insert_joint(JointBuilder::ball(Point3::new(0.0, 1.0, 0.0)).to_world(b)).unwrap();
    run(&mut world, space, 10);
    assert!((world.body(b).unwrap().position().y - 1.0).abs() < 1e-9, "held by the joint");
    world.remove_joint(j).unwrap();
    run(&mut world, space, 10);
    assert!(world.body(b).unwrap().position().y < 1.0, "falls once released");
    let g = world.geoms().next().unwrap();
    world.remove_geom(g).unwrap();
    assert_eq!(world.geom_count(), 0);
    run(&mut world, space, 10);
}

#[test]
fn mass_properties_are_odes() {
    let mut world = World::new();
    let cyl = world.insert_body(BodyBuilder::new().mass(MassSpec::cylinder_total(10.0, 0.141421, 1.0))).unwrap();
    let i = world.body(cyl).unwrap().inertia();
    // m r²/2 about the axis (local Z), m (3r² + L²)/12 across.
    assert!((i[(2, 2)] - 10.0 * 0.141421f64.powi(2) / 2.0).abs() < 1e-12);
    assert!((i[(0, 0)] - 10.0 * (3.0 * 0.141421f64.powi(2) + 1.0) / 12.0).abs() < 1e-12);
    let dense = world
        .insert_body(
            BodyBuilder::new()
                .mass(MassSpec::solid(Shape::Box { edges: Vector3::new(10.0, 0.5, 10.0) }, Mass::Density(100.0))),
        )
        .unwrap();
    assert!((world.body(dense).unwrap().mass() - 5000.0).abs() < 1e-9);
    let default = world.insert_body(BodyBuilder::new()).unwrap();
    assert_eq!(world.body(default).unwrap().mass(), 1.0, "ODE's default mass");
}

#[test]
fn many_worlds_come_and_go() {
    // 200 worlds built, stepped and dropped in turn: each gives the first one's result
    // bit for bit (nothing leaks from one world into the next through ODE's state).
    let mut first = None;
    for _ in 0..200 {
        let mut world = World::new();
        let space = world.create_space(SpaceKind::HASH).unwrap();
        world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0)).unwrap();
        let a = falling_ball(&mut world, space, Point3::new(0.0, 0.5, 0.0));
        let b = falling_ball(&mut world, space, Point3::new(0.9, 0.5, 0.0));
        world
            .insert_joint(JointBuilder::hinge(Point3::new(0.45, 0.5, 0.0), Vector3::z()).between(a, b).feedback())
            .unwrap();
        let verts = vec![Point3::new(-5.0, 0.0, -5.0), Point3::new(5.0, 0.0, -5.0), Point3::new(0.0, 0.0, 5.0)];
        world.insert_geom(space, GeomBuilder::trimesh(verts, vec![[0, 2, 1]])).unwrap();
        run(&mut world, space, 5);
        let state = (world.body(a).unwrap().position().y.to_bits(), world.body(b).unwrap().linear_velocity());
        let joint = world.joints().next().unwrap();
        assert!(world.joint(joint).unwrap().feedback().is_some_and(|f| f.force1.norm() > 0.0));
        assert_eq!(*first.get_or_insert(state), state);
    }
}

#[test]
fn a_kinematic_body_at_rest_holds_what_touches_it_as_a_static_geom_does() {
    // Boxes resting on a slab: the slab a static geom, or a kinematic body at rest,
    // whose contacts are attached to the world so that it does not join what it
    // touches into one island. Each box then moves as if alone on the slab (to the
    // bit), as on a static slab (to 1e-12), and feels the same contact forces; the
    // kinematic slab also touches a static plane, which makes no contact joint.
    let rest = |kinematic: bool, second_box: bool| {
        let mut world = World::new();
        world.set_contact_feedback(true);
        let space = world.create_space(SpaceKind::Simple).unwrap();
        let slab = Vector3::new(4.0, 0.2, 2.0);
        if kinematic {
            let k = world.insert_body(BodyBuilder::kinematic().position(Point3::new(0.0, 0.1, 0.0))).unwrap();
            world.insert_geom(space, GeomBuilder::box_edges(slab).attached_to(k)).unwrap();
            world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.05)).unwrap();
        } else {
            world.insert_geom(space, GeomBuilder::box_edges(slab).pose(Isometry3::translation(0.0, 0.1, 0.0))).unwrap();
        }
        let size = Vector3::repeat(0.5);
        let mut add_box = |x: f64| {
            let at = Point3::new(x, 0.5, 0.0);
            let b = world.insert_body(BodyBuilder::new().position(at).mass(MassSpec::box_total(1.0, size))).unwrap();
            world.insert_geom(space, GeomBuilder::box_edges(size).attached_to(b)).unwrap();
            b
        };
        let b = add_box(-1.0);
        if second_box {
            add_box(1.0);
        }
        let mut forces = Vec::new();
        for _ in 0..600 {
            world.collide(space).unwrap();
            world.step(DT).unwrap();
            let on_b = |c: &&ContactPoint| c.pair.body1 == Some(b) || c.pair.body2 == Some(b);
            forces = world
                .contacts()
                .iter()
                .filter(on_b)
                .map(|c| if c.pair.body1 == Some(b) { c.force } else { -c.force })
                .collect();
            let between_still: Vec<_> = world
                .contacts()
                .iter()
                .filter(|c| c.pair.body1.is_none() || c.pair.body2.is_none())
                .filter(|c| !on_b(c))
                .collect();
            assert_eq!(!between_still.is_empty(), kinematic, "the kinematic slab touches the plane");
            assert!(between_still.iter().all(|c| c.force == Vector3::zeros()), "no joint between them");
            world.clear_contacts();
        }
        (world.body(b).unwrap().position(), forces)
    };
    let (alone, forces_alone) = rest(true, false);
    let (beside, forces_beside) = rest(true, true);
    assert_eq!(alone, beside, "a box on a kinematic slab is an island of its own");
    assert_eq!(forces_alone, forces_beside);
    let (on_static, forces_static) = rest(false, false);
    assert!((alone - on_static).norm() < 1e-12, "{alone} {on_static}");
    // A resting box's four points share its weight in no one way (the LCP's choice):
    // their sum is what must agree.
    let total = |f: &[Vector3<f64>]| f.iter().sum::<Vector3<f64>>();
    assert!((total(&forces_alone) - total(&forces_static)).norm() < 1e-9, "{forces_alone:?} {forces_static:?}");
    // Resting: the slab pushes the box up with its weight.
    let up: f64 = forces_alone.iter().map(|f| f.y).sum();
    assert!((up - 9.81).abs() < 1e-3, "{up} {forces_alone:?}");
}
