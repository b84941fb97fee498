//! The simulation layer: names, objects, joints, hooks and their timing, sensors,
//! controllers, removal, programs and keys, threads, and bad input.

use std::f64::consts::FRAC_PI_2;
use std::sync::{Arc, Mutex};

use ars_core::nalgebra::{Isometry3, Point3, Vector3};
use ars_core::sensors::*;
use ars_core::*;

fn with_floor() -> Simulation {
    Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap()
}

#[test]
fn names_are_unique_deterministic_and_looked_up() {
    let mut sim = with_floor();
    let a = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let b = sim.scene_mut().add_sphere(0.5, [2.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let c = sim.scene_mut().add_sphere(0.5, [4.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    assert_eq!(
        [
            sim.scene().object(a).map(|o| o.name()).unwrap(),
            sim.scene().object(b).map(|o| o.name()).unwrap(),
            sim.scene().object(c).map(|o| o.name()).unwrap()
        ],
        ["sphere", "sphere/1", "sphere/2"]
    );
    assert_eq!(
        sim.scene().object("floor").unwrap().id(),
        sim.scene().objects().find(|(n, _)| *n == "floor").unwrap().1
    );
    sim.scene_mut().set_name(b, "arm").unwrap();
    assert_eq!(sim.scene().object("arm").unwrap().id(), b);
    assert_eq!(sim.scene().object(b).unwrap().name(), "arm", "by id as by name");
    assert!(sim.scene().object("sphere/1").is_err(), "the old name is free again");
    let err = sim.scene().object("amr").unwrap_err();
    assert!(matches!(&err, Error::UnknownName { close_matches, .. } if close_matches == &["arm"]), "{err}");
    assert!(err.to_string().contains("did you mean arm?"));
    assert!(matches!(sim.scene_mut().set_name(a, "arm"), Err(Error::DuplicateName { .. })));
    let j = sim.scene_mut().add_hinge_joint("", a, c, None, Vector3::z()).unwrap();
    let k = sim.scene_mut().add_hinge_joint("", c, JointEnd::World, None, Vector3::z()).unwrap();
    assert_eq!(
        (sim.scene().joint(j).map(|j| j.name()).unwrap(), sim.scene().joint(k).map(|j| j.name()).unwrap()),
        ("hinge", "hinge/1")
    );
    assert_eq!(sim.scene().joint("hinge/1").unwrap().id(), k);
    assert!(matches!(sim.scene().joint("rotery"), Err(Error::UnknownName { kind: "joint", .. })));
    assert!(matches!(
        sim.scene_mut().add_hinge_joint("hinge", a, c, None, Vector3::y()),
        Err(Error::DuplicateName { .. })
    ));
}

#[test]
fn bad_input_is_refused_with_a_clear_error() {
    let mut sim = with_floor();
    let objects_before = sim.scene().objects().count();
    let err = sim.scene_mut().add_sphere(-1.0, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(matches!(err, Error::NotPositive { what: "sphere radius", .. }), "{err}");
    let err = sim.scene_mut().add_box([1.0, 1.0, 1.0], [f64::NAN, 0.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(matches!(err, Error::NotFinite { .. }), "{err}");
    assert!(sim.scene_mut().add_capsule(0.1, 1.0, [0.0, 0.0, 0.0], Mass::Density(-3.0)).is_err());
    assert!(sim.scene_mut().add_cone(0.1, 0.0, [0.0, 0.0, 0.0], Mass::Total(1.0)).is_err());
    assert_eq!(sim.scene().objects().count(), objects_before, "refused objects leave nothing behind");
    assert_eq!(sim.scene().world().body_count(), 0);

    let a = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let err = sim.scene_mut().add_hinge_joint("self", a, a, None, Vector3::y()).unwrap_err();
    assert!(matches!(err, Error::SelfJoint { .. }), "{err}");
    let floor = sim.scene().object("floor").unwrap().id();
    assert!(sim.scene_mut().add_hinge_joint("", floor, a, None, Vector3::y()).is_err(), "a static first object");
    assert!(sim.scene_mut().rotate(a, Vector3::zeros(), 1.0).is_err());
    assert!(sim.scene_mut().rotate(a, Vector3::x(), f64::NAN).is_err());
    assert!(sim.scene_mut().set_color(a, [2.0, 0.0, 0.0]).is_err());
    assert!(Simulation::builder().time_step(-1.0).build().is_err());
    assert!(Simulation::builder().steps_per_frame(0).build().is_err());
    assert!(Simulation::builder().bounce(1.5, 0.0).build().is_err());

    sim.remove_object(a).unwrap();
    assert!(matches!(sim.scene().body(a), Err(Error::StaleHandle { kind: "object", .. })));
    assert!(matches!(sim.remove_object(a), Err(Error::StaleHandle { .. })));
    assert!(sim.scene().object("sphere").is_err());
    let other = Simulation::new().unwrap();
    let b = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    assert!(matches!(other.scene().body(b), Err(Error::ForeignHandle { .. })));
    sim.step().unwrap();
}

#[test]
fn rotate_turns_about_a_world_axis_and_offsets_add() {
    let mut sim = Simulation::new().unwrap();
    let c = sim.scene_mut().add_capsule(0.1, 1.0, [0.0, 0.0, 0.0], Mass::Density(1.0)).unwrap();
    sim.scene_mut().rotate(c, Vector3::x(), FRAC_PI_2).unwrap();
    // Local Z now points down the world's −Y, as the original's idiom intends.
    let z = sim.scene().rotation(c).unwrap() * Vector3::z();
    assert!((z - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
    sim.scene_mut().rotate(c, Vector3::y(), FRAC_PI_2).unwrap();
    let x = sim.scene().rotation(c).unwrap() * Vector3::x();
    assert!((x - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-15, "a second turn is about the world axis: {x}");
    sim.scene_mut().offset_by_position(c, [1.0, 2.0, 3.0]).unwrap();
    sim.scene_mut().offset_by_position(c, [1.0, 0.0, 0.0]).unwrap();
    assert_eq!(sim.scene().position(c).unwrap(), Point3::new(2.0, 2.0, 3.0));
}

#[test]
fn hooks_see_the_time_at_the_start_and_at_the_end_of_the_step() {
    let mut sim = Simulation::builder().steps_per_frame(4).build().unwrap();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let (pre, post, frame) = (seen.clone(), seen.clone(), seen.clone());
    sim.add_hooks(PreStep(move |s| {
        pre.lock().unwrap().push(("pre", s.scene().time()));
        Ok(())
    }))
    .unwrap();
    sim.add_hooks(PostStep(move |s| {
        post.lock().unwrap().push(("post", s.scene().time()));
        Ok(())
    }))
    .unwrap();
    sim.add_hooks(PreFrame(move |s| {
        frame.lock().unwrap().push(("frame", s.scene().time()));
        Ok(())
    }))
    .unwrap();
    sim.step_frame().unwrap();
    let dt = sim.scene().time_step();
    let log = seen.lock().unwrap().clone();
    assert_eq!(log[0], ("frame", 0.0));
    assert_eq!(log[1], ("pre", 0.0));
    assert_eq!(log[2], ("post", dt));
    assert_eq!(log[3], ("pre", dt));
    assert_eq!(log.len(), 1 + 2 * 4);
    assert_eq!((sim.scene().step_count(), sim.scene().frame_count()), (4, 1));
    // Time is accumulated by repeated addition, as in the original.
    let mut t = 0.0;
    for _ in 0..4 {
        t += dt;
    }
    assert_eq!(sim.scene().time(), t);
    // An error in a hook stops the run and reaches the caller.
    sim.add_hooks(PreStep(|s| if s.scene().step_count() >= 6 { Err(Error::User("stop".into())) } else { Ok(()) }))
        .unwrap();
    assert_eq!(sim.run_for(1.0), Err(Error::User("stop".into())));
    assert_eq!(sim.scene().step_count(), 6);
}

#[test]
fn joints_to_the_static_world_friction_and_controllers() {
    let mut sim = Simulation::new().unwrap();
    // A 1 kg ball on a 1 m massless arm, hinged to the world at the origin.
    let ball = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let hinge =
        sim.scene_mut().add_hinge_joint("hinge", ball, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    sim.scene_mut().joint_mut(hinge).unwrap().set_viscous_friction(2.0).unwrap();
    let torque = sim.add_sensor(JointTorque::new(hinge)).unwrap();
    let power = sim.add_sensor(JointPower::new(hinge)).unwrap();
    sim.run_for(10.0).unwrap();
    // Friction brings the pendulum to rest hanging straight down.
    let s = sim.scene().joint_state(hinge).unwrap();
    assert!((s.position + FRAC_PI_2).abs() < 1e-3, "{s:?}");
    assert!(s.rate.abs() < 1e-3);
    // The friction torque is what the sensors saw: always −2 · rate, dissipating power.
    let (t, p) = (sim.records(torque).unwrap(), sim.records(power).unwrap());
    assert!(p.iter().all(|s| s.record.power <= 0.0));
    assert!(t.iter().any(|s| s.record.value.abs() > 0.1));

    // A PD position servo lifts it to horizontal.
    let servo = PositionServo::pd(Profile::constant(0.0).unwrap(), 200.0, 20.0);
    sim.scene_mut().joint_mut(hinge).unwrap().set_controller(servo).unwrap();
    sim.run_for(5.0).unwrap();
    let q = sim.scene().joint_state(hinge).unwrap().position;
    // Steady-state error of a PD against gravity: m g l / kp ≈ 0.049 rad.
    assert!((q + 9.81 / 200.0).abs() < 2e-3, "servo holds near 0 rad: {q}");

    // A velocity servo spins it at 1 rad/s.
    let mut joint = sim.scene_mut().joint_mut(hinge).unwrap();
    joint.set_viscous_friction(0.0).unwrap();
    joint.set_controller(VelocityServo { setpoint: Profile::constant(1.0).unwrap(), gain: 1000.0 }).unwrap();
    sim.run_for(2.0).unwrap();
    let rate = sim.scene().joint_state(hinge).unwrap().rate;
    assert!((rate - 1.0).abs() < 0.02, "{rate}");
}

#[test]
fn hinge_speed_motor_limits_slider_and_reactions() {
    let mut sim = Simulation::new().unwrap();
    let wheel = sim.scene_mut().add_cylinder(0.3, 0.1, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let axle = sim.scene_mut().add_hinge_joint("axle", wheel, JointEnd::World, None, Vector3::z()).unwrap();
    sim.scene_mut().joint_mut(axle).unwrap().set_speed(2.0, 50.0).unwrap();
    sim.run_for(0.5).unwrap();
    assert!((sim.scene().joint_state(axle).unwrap().rate - 2.0).abs() < 1e-6);
    // The hinge holds the wheel's weight: 9.81 N up on it.
    let reaction = sim.add_sensor(JointReaction::new(axle)).unwrap();
    sim.step().unwrap();
    let f = sim.records(reaction).unwrap().last().unwrap().record.force;
    assert!((f.y - 9.81).abs() < 1e-3, "{f}");

    let block = sim.scene_mut().add_box([0.2, 0.2, 0.2], [5.0, 0.0, 0.0], Mass::Total(2.0)).unwrap();
    let rail = sim.scene_mut().add_slider_joint("rail", block, JointEnd::World, Vector3::x()).unwrap();
    sim.scene_mut().joint_mut(rail).unwrap().set_limits(-0.1, 0.1).unwrap();
    let force = sim.add_sensor(JointForce::new(rail)).unwrap();
    sim.add_hooks(PreStep(move |s| s.scene_mut().joint_mut(rail)?.add_force(4.0))).unwrap();
    sim.run_for(1.0).unwrap();
    let x = sim.scene().joint(rail).and_then(|j| j.ode()).unwrap().position().unwrap();
    assert!((x - 0.1).abs() < 1e-3, "stops at the high limit: {x}");
    assert!(sim.records(force).unwrap().iter().all(|s| s.record.value == 4.0));
    assert!(sim.scene_mut().joint_mut(rail).unwrap().add_torque(1.0).is_err(), "a slider takes forces");
    assert!(sim.add_sensor(HingeSensor::new(rail)).is_err(), "a rotary sensor on a slider");
}

#[test]
fn removing_objects_and_joints_between_steps() {
    let mut sim = with_floor();
    let a = sim.scene_mut().add_sphere(0.2, [0.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
    let b = sim.scene_mut().add_sphere(0.2, [1.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
    let j = sim.scene_mut().add_ball_joint("link", a, b, None).unwrap();
    let gps = sim.add_sensor(Gps::new(a)).unwrap();
    sim.run_for(0.1).unwrap();
    sim.remove_joint(j).unwrap();
    assert!(sim.scene().joint("link").is_err());
    sim.add_hooks(PostStep(move |s| if s.scene().step_count() == 300 { s.remove_object(a) } else { Ok(()) })).unwrap();
    sim.run_for(0.2).unwrap();
    assert!(sim.scene().body(a).is_err());
    assert!(sim.is_sensor_detached(gps).unwrap(), "the GPS stops with its object");
    assert_eq!(sim.records(gps).unwrap().len(), 300);
    assert!(sim.scene().body(b).is_ok());
    // And new objects can be dropped in at run time.
    let c = sim.scene_mut().add_box([0.3, 0.3, 0.3], [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.run_for(1.0).unwrap();
    assert!((sim.scene().position(c).unwrap().y - 0.15).abs() < 2e-3);
}

#[test]
fn energies_use_the_world_frame_inertia() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let slab = sim.scene_mut().add_box([2.0, 0.2, 1.0], [0.0, 0.0, 0.0], Mass::Total(3.0)).unwrap();
    sim.scene_mut().rotate(slab, Vector3::new(1.0, 1.0, 0.0), 0.7).unwrap();
    let w = Vector3::new(0.3, -1.0, 2.0);
    sim.scene_mut().body_mut(slab).unwrap().set_angular_velocity(w).unwrap();
    let ke = sim.add_sensor(KineticEnergy::new(slab)).unwrap();
    sim.step().unwrap();
    let b = sim.scene().body(slab).unwrap();
    let r = b.rotation();
    let w_now = b.angular_velocity();
    let w_body = r.inverse() * w_now;
    let expected = 0.5 * w_body.dot(&(b.inertia() * w_body));
    let got = sim.records(ke).unwrap().last().unwrap().record.rotational;
    assert!((got - expected).abs() < 1e-12, "{got} vs {expected}");
    // The original's formula (body inertia with world ω) differs for a rotated slab.
    let wrong = 0.5 * w_now.dot(&(b.inertia() * w_now));
    assert!((wrong - expected).abs() > 1e-3);
}

#[test]
fn potential_energy_reference_inclinometer_imu_contacts_and_periods() {
    let mut sim = with_floor();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 0.5, 0.0], Mass::Total(2.0)).unwrap();
    let pe = sim.add_sensor(PotentialEnergy::new(ball).reference_height(0.5)).unwrap();
    let imu = sim.add_sensor(Imu::new(ball)).unwrap();
    let touch = sim.add_sensor(ContactSensor::new(ball)).unwrap();
    let slow = sim.add_sensor_every(Gps::new(ball), 0.01).unwrap();
    sim.run_for(1.0).unwrap();
    assert!(sim.records(pe).unwrap().last().unwrap().record.potential.abs() < 1e-3);
    let f = sim.records(imu).unwrap().last().unwrap().record.specific_force;
    assert!((f - Vector3::new(0.0, 9.81, 0.0)).norm() < 1e-3, "at rest an IMU feels +g up: {f}");
    assert!(sim.records(touch).unwrap().last().unwrap().record.touching());
    let slow = sim.records(slow).unwrap();
    assert_eq!(slow.len(), 100);
    assert!((slow.samples()[0].time - 0.01).abs() < 1e-9);

    let tilted = sim.scene_mut().add_box([1.0, 1.0, 1.0], [5.0, 5.0, 5.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().rotate(tilted, Vector3::z(), 0.3).unwrap();
    sim.scene_mut().rotate(tilted, Vector3::x(), -0.2).unwrap();
    let inc = sim.add_sensor(Inclinometer::new(tilted)).unwrap();
    sim.step().unwrap();
    let i = sim.records(inc).unwrap().last().unwrap().record;
    assert!((i.pitch - 0.3).abs() < 1e-3 && (i.roll + 0.2).abs() < 1e-3, "{i:?}");
}

#[test]
fn lasers_mount_on_bodies_and_report_the_closest_hit() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let robot = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    for x in [6.0, 3.0, 9.0, 4.5] {
        sim.scene_mut().add_sphere(0.5, [x, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    }
    // Mounted 0.1 m ahead of the robot, pointing +X.
    let offset = Isometry3::new(Vector3::new(0.1, 0.0, 0.0), Vector3::y() * FRAC_PI_2);
    let laser = sim.add_sensor(Laser::new(100.0).mounted_on(robot, offset)).unwrap();
    sim.step().unwrap();
    let r = sim.records(laser).unwrap().last().unwrap().record;
    assert!((r.distance.unwrap() - 2.4).abs() < 1e-9, "{r:?}");
    assert!((r.point.unwrap() - Point3::new(2.5, 0.0, 0.0)).norm() < 1e-9);
    // Turned around, it sees nothing.
    sim.scene_mut().rotate(robot, Vector3::y(), std::f64::consts::PI).unwrap();
    sim.step().unwrap();
    assert_eq!(sim.records(laser).unwrap().last().unwrap().record.distance, None);
    let mut csv = Vec::new();
    sim.records(laser).unwrap().write_csv(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    assert!(csv.starts_with("time [s],step,distance [m],hit x [m],hit y [m],hit z [m]\n"));
    assert!(csv.lines().nth(2).unwrap().ends_with(",2,,,,"), "{csv}");
}

#[test]
fn terrain_cones_and_static_objects_collide() {
    let mut sim = Simulation::new().unwrap();
    let field = Heightfield::constant(6, 6, 0.3).unwrap();
    sim.scene_mut().add_trimesh_floor(field.vertices(), field.triangles(), [-2.5, 0.0, -2.5]).unwrap();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.5, 0.0], Mass::Total(1.0)).unwrap();
    let cone = sim.scene_mut().add_cone(0.3, 0.6, [1.0, 1.5, 1.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().rotate(cone, Vector3::x(), -FRAC_PI_2).unwrap();
    let wall = sim
        .scene_mut()
        .add_static(Shape::Box { edges: Vector3::new(0.2, 2.0, 4.0) }, Isometry3::translation(-1.0, 0.0, 0.0))
        .unwrap();
    assert!(sim.scene().body(wall).is_err(), "static objects have no body");
    sim.run_for(2.0).unwrap();
    assert!((sim.scene().position(ball).unwrap().y - 0.8).abs() < 2e-3, "rests on the terrain at 0.3 m");
    // The cone stands on its base: centre of mass a quarter of its height up.
    let y = sim.scene().position(cone).unwrap().y;
    assert!((y - (0.3 + 0.15)).abs() < 5e-3, "cone centre at {y}");
    let axis = sim.scene().rotation(cone).unwrap() * Vector3::z();
    assert!(axis.y > 0.99, "standing upright: {axis}");
}

struct Driver {
    pushes: u32,
}

impl Hooks for Driver {}

impl Program for Driver {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        builder.gravity(Vector3::zeros()).steps_per_frame(10)
    }
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        sim.scene_mut().add_sphere(0.1, [0.0, 0.0, 0.0], Mass::Total(1.0)).map(drop)
    }
    fn key_bindings(&self) -> ActionMap<Self> {
        ActionMap::new()
            .add(
                Key::Char('a'),
                |p: &mut Driver, sim: &mut Simulation| {
                    p.pushes += 1;
                    let ball = sim.scene().object("sphere")?.id();
                    sim.scene_mut().body_mut(ball)?.add_force(Vector3::new(100.0, 0.0, 0.0))
                },
                Repeat::Once,
            )
            .add(
                Key::Up,
                |_, sim| {
                    let ball = sim.scene().object("sphere")?.id();
                    sim.scene_mut().body_mut(ball)?.add_force(Vector3::new(0.0, 0.0, 10.0))
                },
                Repeat::WhileHeld,
            )
    }
}

#[test]
fn programs_bind_keys_once_or_while_held_and_reset() {
    let mut program = Driver { pushes: 0 };
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    assert!(runner.key_down(Key::Char('a')).unwrap());
    assert!(!runner.key_down(Key::Char('q')).unwrap(), "unbound keys are ignored");
    runner.step_frame().unwrap();
    let ball = runner.simulation().scene().object("sphere").unwrap().id();
    let dt = runner.simulation().scene().time_step();
    // A one-shot push acts for a single step: v = F dt / m.
    let v = runner.simulation().scene().body(ball).unwrap().linear_velocity();
    assert!((v.x - 100.0 * dt).abs() < 1e-12);
    runner.key_down(Key::Up).unwrap();
    runner.step_frame().unwrap();
    runner.key_up(Key::Up);
    runner.step_frame().unwrap();
    // Held for one frame of 10 steps: v = 10 N · 10 dt.
    let v = runner.simulation().scene().body(ball).unwrap().linear_velocity();
    assert!((v.z - 10.0 * 10.0 * dt).abs() < 1e-12, "{v}");
    runner.reset().unwrap();
    assert_eq!(runner.simulation().scene().time(), 0.0);
    assert_eq!(runner.program().pushes, 1);
}

fn pendulum_trajectory() -> Vec<u64> {
    let mut sim = with_floor();
    let a = sim.scene_mut().add_cylinder(0.1, 1.0, [0.5, 1.5, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().rotate(a, Vector3::y(), FRAC_PI_2).unwrap();
    sim.scene_mut().add_hinge_joint("", a, JointEnd::World, Some(Point3::new(0.0, 1.5, 0.0)), Vector3::z()).unwrap();
    let gps = sim.add_sensor(Gps::new(a)).unwrap();
    sim.run_for(1.0).unwrap();
    sim.records(gps).unwrap().iter().map(|s| s.record.position.y.to_bits()).collect()
}

#[test]
fn simulations_run_independently_on_several_threads() {
    let reference = pendulum_trajectory();
    let threads: Vec<_> = (0..3).map(|_| std::thread::spawn(pendulum_trajectory)).collect();
    for t in threads {
        assert_eq!(t.join().unwrap(), reference);
    }
    // A simulation can be moved to another thread, too.
    let mut sim = with_floor();
    sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let t = std::thread::spawn(move || {
        sim.run_for(0.1).unwrap();
        sim.scene().time()
    });
    assert!((t.join().unwrap() - 0.1).abs() < 1e-9);
}

#[test]
fn noisy_sensors_add_seeded_gaussian_noise() {
    let run = |seed: u64| {
        let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
        let still = sim.scene_mut().add_sphere(0.5, [0.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
        let gps = sim.add_sensor(Noisy::new(Gps::new(still), 0.05, seed).unwrap()).unwrap();
        sim.run_for(1.0).unwrap();
        sim.records(gps).unwrap().iter().map(|s| s.record.position.y - 2.0).collect::<Vec<_>>()
    };
    let errors = run(1);
    let n = errors.len() as f64;
    let mean = errors.iter().sum::<f64>() / n;
    let sd = (errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / n).sqrt();
    assert!(mean.abs() < 0.005 && (sd - 0.05).abs() < 0.005, "mean {mean}, sd {sd}");
    assert_eq!(errors, run(1), "the same seed, the same noise");
    assert_ne!(errors, run(2));
    assert!(Noisy::new(Gps::new(sim_object()), -1.0, 0).is_err());
}

fn sim_object() -> ObjectId {
    let mut sim = Simulation::new().unwrap();
    sim.scene_mut().add_sphere(0.1, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap()
}

#[test]
fn hooks_are_added_read_and_removed_by_id_and_run_in_the_order_added() {
    #[derive(Default)]
    struct Counter {
        steps: u32,
        frames: u32,
    }
    impl Hooks for Counter {
        fn pre_step(&mut self, _: &mut Simulation) -> Result<()> {
            self.steps += 1;
            Ok(())
        }
        fn post_frame(&mut self, _: &mut Simulation) -> Result<()> {
            self.frames += 1;
            Ok(())
        }
    }
    let mut sim = Simulation::builder().steps_per_frame(5).build().unwrap();
    let counter = sim.add_hooks(Counter::default()).unwrap();
    sim.step_frame().unwrap();
    assert_eq!((sim.hooks(counter).unwrap().steps, sim.hooks(counter).unwrap().frames), (5, 1));
    sim.hooks_mut(counter).unwrap().steps = 100;
    sim.step().unwrap();
    assert_eq!(sim.remove_hooks(counter).unwrap().steps, 101);
    assert!(matches!(sim.hooks(counter), Err(Error::StaleHandle { .. })));
    assert!(sim.remove_hooks(counter).is_err());

    // Slots are reused, the order is still the order added: b, then c in a's old slot.
    let seen = Arc::new(Mutex::new(String::new()));
    let tag = |c: char| {
        let seen = seen.clone();
        PreStep(move |_: &mut Simulation| {
            seen.lock().unwrap().push(c);
            Ok(())
        })
    };
    let a = sim.add_hooks(tag('a')).unwrap();
    sim.add_hooks(tag('b')).unwrap();
    sim.remove_hooks(a).unwrap();
    sim.add_hooks(tag('c')).unwrap();
    sim.step().unwrap();
    assert_eq!(*seen.lock().unwrap(), "bc");

    // A running hook cannot reach itself through the simulation, but can add others.
    struct Selfish {
        me: Option<HookId<Selfish>>,
        seen: Arc<Mutex<String>>,
    }
    impl Hooks for Selfish {
        fn post_step(&mut self, sim: &mut Simulation) -> Result<()> {
            assert!(sim.remove_hooks(self.me.unwrap()).is_err(), "removing itself while running");
            assert!(sim.hooks(self.me.unwrap()).is_err(), "reading itself while running");
            let seen = self.seen.clone();
            sim.add_hooks(PostFrame(move |_: &mut Simulation| {
                seen.lock().unwrap().push('f');
                Ok(())
            }))
            .map(drop)
        }
    }
    let selfish = sim.add_hooks(Selfish { me: None, seen: seen.clone() }).unwrap();
    sim.hooks_mut(selfish).unwrap().me = Some(selfish);
    seen.lock().unwrap().clear();
    sim.step_frame().unwrap();
    assert_eq!(*seen.lock().unwrap(), "bcbcbcbcbcfffff", "five steps, then five post-frame hooks");
    sim.remove_hooks(selfish).unwrap();
}

/// A 1 kg ball on a 1 m massless arm, hinged to the world at the origin about Z, in
/// a world without gravity unless `gravity`.
fn hinged_ball(gravity: bool) -> (Simulation, JointId) {
    let g = if gravity { Vector3::new(0.0, -9.81, 0.0) } else { Vector3::zeros() };
    let mut sim = Simulation::builder().gravity(g).build().unwrap();
    let ball = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let hinge =
        sim.scene_mut().add_hinge_joint("hinge", ball, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    (sim, hinge)
}

#[test]
fn actuator_limits_hold_controller_output_and_motor_speed() {
    // A constant 10 N·m torque motor, limited to 2 N·m and 3 rad/s.
    let (mut sim, hinge) = hinged_ball(false);
    let mut joint = sim.scene_mut().joint_mut(hinge).unwrap();
    joint.set_controller(TorqueMotor { torque: Profile::constant(10.0).unwrap() }).unwrap();
    joint.set_actuator_limits(ActuatorLimits { effort: 2.0, velocity: 3.0 }).unwrap();
    let torque = sim.add_sensor(JointTorque::new(hinge)).unwrap();
    sim.run_for(0.5).unwrap();
    // I = 1 kg·m² (+ the ball's own 0.004): 2 N·m gives about 2 rad/s² while below 3 rad/s.
    let early = sim.scene().joint_state(hinge).unwrap().rate;
    assert!((early - 0.5 * 2.0 / 1.004).abs() < 1e-3, "{early}");
    assert!(sim.records(torque).unwrap().iter().all(|s| s.record.value == 2.0));
    sim.run_for(3.0).unwrap();
    let rate = sim.scene().joint_state(hinge).unwrap().rate;
    // At the velocity limit the actuator stops pushing: the rate stays within one
    // step's acceleration of it.
    assert!((3.0..=3.0 + 2.0 * 0.0004).contains(&rate), "{rate}");
    assert_eq!(sim.scene().joint(hinge).unwrap().efforts().controller, 0.0);

    // The speed motor is held to the limits too.
    let (mut sim, hinge) = hinged_ball(false);
    let mut joint = sim.scene_mut().joint_mut(hinge).unwrap();
    joint.set_actuator_limits(ActuatorLimits { effort: 1.0, velocity: 0.5 }).unwrap();
    joint.set_speed(10.0, 100.0).unwrap();
    sim.run_for(0.25).unwrap();
    // Accelerating at 1 N·m: not yet at 0.5 rad/s after 0.25 s.
    let rate = sim.scene().joint_state(hinge).unwrap().rate;
    assert!((rate - 0.25 / 1.004).abs() < 1e-3, "{rate}");
    sim.run_for(1.0).unwrap();
    assert!((sim.scene().joint_state(hinge).unwrap().rate - 0.5).abs() < 1e-9);
    assert_eq!(sim.scene().joint(hinge).unwrap().actuator_limits(), ActuatorLimits { effort: 1.0, velocity: 0.5 });

    let mut joint = sim.scene_mut().joint_mut(hinge).unwrap();
    for bad in [0.0, -1.0, f64::NAN] {
        let err = joint.set_actuator_limits(ActuatorLimits { effort: bad, velocity: 1.0 }).unwrap_err();
        assert!(err.to_string().contains("effort limit"), "{err}");
    }
}

#[test]
fn dry_friction_holds_a_joint_until_the_load_exceeds_it() {
    // Gravity pulls the horizontal arm with 9.81 N·m.
    let (mut sim, hinge) = hinged_ball(true);
    sim.scene_mut().joint_mut(hinge).unwrap().set_dry_friction(10.0).unwrap();
    sim.run_for(1.0).unwrap();
    let q = sim.scene().joint_state(hinge).unwrap().position;
    assert!(q.abs() < 1e-6, "held: {q}");
    assert_eq!(sim.scene().joint(hinge).unwrap().dry_friction(), 10.0);

    let (mut sim, hinge) = hinged_ball(true);
    sim.scene_mut().joint_mut(hinge).unwrap().set_dry_friction(9.0).unwrap();
    sim.run_for(0.2).unwrap();
    // Net 0.81 N·m on about 1.004 kg·m²: q ≈ −½ · 0.807 · 0.2².
    let q = sim.scene().joint_state(hinge).unwrap().position;
    assert!((q + 0.5 * 0.81 / 1.004 * 0.04).abs() < 2e-3, "slips: {q}");

    // A speed replaces it; turning the speed off brings it back.
    let (mut sim, hinge) = hinged_ball(true);
    let mut joint = sim.scene_mut().joint_mut(hinge).unwrap();
    joint.set_dry_friction(10.0).unwrap();
    joint.set_speed(1.0, 50.0).unwrap();
    sim.run_for(0.5).unwrap();
    assert!((sim.scene().joint_state(hinge).unwrap().rate - 1.0).abs() < 1e-6);
    sim.scene_mut().joint_mut(hinge).unwrap().set_speed(0.0, 0.0).unwrap();
    sim.run_for(0.5).unwrap();
    assert!(sim.scene().joint_state(hinge).unwrap().rate.abs() < 1e-9, "held again");
    assert!(sim.scene_mut().joint_mut(hinge).unwrap().set_dry_friction(-1.0).is_err());
}

#[test]
fn a_mimic_joint_follows_its_leader() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let a = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let b = sim.scene_mut().add_sphere(0.1, [-1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let leader =
        sim.scene_mut().add_hinge_joint("leader", a, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    let follower =
        sim.scene_mut().add_hinge_joint("follower", b, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    sim.scene_mut().joint_mut(follower).unwrap().set_mimic("leader", -0.5, 0.2).unwrap();
    sim.scene_mut()
        .joint_mut(leader)
        .unwrap()
        .set_controller(TorqueMotor { torque: Profile::constant(1.0).unwrap() })
        .unwrap();
    let mut worst: f64 = 0.0;
    for _ in 0..2500 {
        sim.step().unwrap();
        let (l, f) = (sim.scene().joint_state(leader).unwrap(), sim.scene().joint_state(follower).unwrap());
        if sim.scene().time() > 0.1 {
            worst = worst.max((f.position - (-0.5 * l.position + 0.2)).abs());
        }
    }
    let l = sim.scene().joint_state(leader).unwrap().position;
    assert!(l > 0.4, "the leader turned: {l}");
    // The motor follows the leader's rate and corrects the error at ERP per step: the
    // error left is one step's change in the leader's acceleration.
    assert!(worst < 1e-6, "{worst}");
    assert_eq!(
        sim.scene().joint(follower).unwrap().mimic().map(|m| (m.leader, m.multiplier, m.offset)),
        Some((leader, -0.5, 0.2))
    );
    // The leader is not held back: it moves bit for bit as it does with no follower.
    let mut alone = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let a2 = alone.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let lone =
        alone.scene_mut().add_hinge_joint("leader", a2, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    alone
        .scene_mut()
        .joint_mut(lone)
        .unwrap()
        .set_controller(TorqueMotor { torque: Profile::constant(1.0).unwrap() })
        .unwrap();
    alone.step_n(2500).unwrap();
    assert_eq!(l.to_bits(), alone.scene().joint_state(lone).unwrap().position.to_bits());

    // Bad pairs are refused; removing the leader frees the follower.
    let slider = sim.scene_mut().add_slider_joint("rail", b, a, Vector3::x()).unwrap();
    let err = sim.scene_mut().joint_mut(slider).unwrap().set_mimic(leader, 1.0, 0.0).unwrap_err();
    assert!(err.to_string().contains("slider joint cannot follow a hinge"), "{err}");
    assert!(sim.scene_mut().joint_mut(leader).unwrap().set_mimic(leader, 1.0, 0.0).is_err());
    assert!(sim.scene_mut().joint_mut(follower).unwrap().set_speed(1.0, 1.0).is_err(), "its motor is the mimic's");
    sim.remove_joint(leader).unwrap();
    assert_eq!(sim.scene().joint(follower).unwrap().mimic(), None);
    sim.step().unwrap();
}

#[test]
fn hooks_run_only_at_the_points_they_say_and_leave_every_list_when_removed() {
    let seen = Arc::new(Mutex::new(String::new()));
    struct Tagged {
        tag: char,
        at: HookPoint,
        seen: Arc<Mutex<String>>,
    }
    impl Tagged {
        fn note(&self, point: char) -> Result<()> {
            self.seen.lock().unwrap().push_str(&format!("{}{point} ", self.tag));
            Ok(())
        }
    }
    impl Hooks for Tagged {
        fn pre_step(&mut self, _: &mut Simulation) -> Result<()> {
            self.note('<')
        }
        fn post_step(&mut self, _: &mut Simulation) -> Result<()> {
            self.note('>')
        }
        fn pre_frame(&mut self, _: &mut Simulation) -> Result<()> {
            self.note('[')
        }
        fn post_frame(&mut self, _: &mut Simulation) -> Result<()> {
            self.note(']')
        }
        fn runs_at(&self, point: HookPoint) -> bool {
            point == self.at
        }
    }
    let mut sim = Simulation::builder().steps_per_frame(1).build().unwrap();
    let tagged = |tag, at| Tagged { tag, at, seen: seen.clone() };
    // Every method is written, but each hook is called only where it says it runs.
    sim.add_hooks(tagged('a', HookPoint::PostStep)).unwrap();
    let b = sim.add_hooks(tagged('b', HookPoint::PreFrame)).unwrap();
    sim.add_hooks(tagged('c', HookPoint::PreStep)).unwrap();
    sim.step_frame().unwrap();
    assert_eq!(std::mem::take(&mut *seen.lock().unwrap()), "b[ c< a> ");
    sim.remove_hooks(b).unwrap();
    sim.step_frame().unwrap();
    assert_eq!(*seen.lock().unwrap(), "c< a> ");
}

#[test]
fn sensors_sampled_at_the_end_of_the_step_sample_again_after_others_come_and_go() {
    let mut sim = with_floor();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
    let start = sim
        .add_sensor(Probe::at_step_start(move |s: &Scene| Ok(Position { position: s.body(ball)?.position() })))
        .unwrap();
    let gps = sim.add_sensor(Gps::new(ball)).unwrap();
    sim.step().unwrap();
    sim.remove_sensor(gps).unwrap();
    sim.step().unwrap();
    let gps = sim.add_sensor(Gps::new(ball)).unwrap();
    let other = sim.add_sensor(Gps::new(ball)).unwrap();
    sim.remove_sensor(other).unwrap();
    sim.step().unwrap();
    assert_eq!(sim.records(start).unwrap().len(), 3);
    let log = sim.records(gps).unwrap();
    assert_eq!((log.len(), log.last().unwrap().step), (1, 3));
}

#[test]
fn sensors_are_removed_and_cleared_whatever_their_type() -> Result<()> {
    let mut sim = with_floor();
    let ball = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0))?;
    let gps = sim.add_sensor_of_kind(ars_core::SensorKind::Gps, &[ball], &[], None)?;
    let energy = sim.add_sensor_of_kind(ars_core::SensorKind::KineticEnergy, &[ball], &[], None)?;
    sim.step_n(3)?;
    sim.clear_any_records(gps)?;
    assert_eq!(sim.sensor_table(gps)?.1.len(), 0);
    assert_eq!(sim.sensor_table(energy)?.1.len(), 3, "the other sensor keeps its records");
    sim.remove_any_sensor(energy)?;
    assert!(sim.sensor_table(energy).is_err(), "a removed sensor is gone");
    assert!(sim.remove_any_sensor(energy).is_err(), "and cannot be removed twice");
    assert!(!sim.is_any_sensor_detached(gps)?);
    sim.remove_object(ball)?;
    assert!(sim.is_any_sensor_detached(gps)?);
    sim.step()?;
    assert_eq!(sim.sensor_table(gps)?.1.len(), 0, "a detached sensor samples no more");
    Ok(())
}

#[test]
fn a_joint_position_is_its_state_s_position_without_the_rate() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let hinge =
        sim.scene_mut().add_hinge_joint("hinge", ball, JointEnd::World, Some(Point3::origin()), Vector3::z()).unwrap();
    let block = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 3.0, 0.0], Mass::Total(1.0)).unwrap();
    let rail = sim.scene_mut().add_slider_joint("rail", block, JointEnd::World, Vector3::new(1.0, 1.0, 0.0)).unwrap();
    let other = sim.scene_mut().add_sphere(0.1, [0.0, -3.0, 0.0], Mass::Total(1.0)).unwrap();
    let socket = sim.scene_mut().add_ball_joint("socket", other, JointEnd::World, None).unwrap();
    sim.run_for(0.3).unwrap();
    for joint in [hinge, rail] {
        let position = sim.scene().joint_position(joint).unwrap();
        assert_ne!(position, 0.0, "it moved");
        assert_eq!(position.to_bits(), sim.scene().joint_state(joint).unwrap().position.to_bits());
    }
    let err = sim.scene().joint_position(socket).unwrap_err();
    assert!(matches!(err, Error::WrongJointKind { kind: "ball", .. }), "{err}");
}
