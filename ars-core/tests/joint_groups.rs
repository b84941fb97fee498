//! Joint groups: several hinges and slides between two objects as one ODE constraint
//! (`Scene::add_joint_group`, what MJCF bodies with several joints are made as).

use ars_core::{GroupJoint, JointEnd, JointType, Mass, ObjectId, Simulation};
use nalgebra::{Point3, Rotation3, Vector3};

fn hinge(name: &str, anchor: [f64; 3], axis: [f64; 3]) -> GroupJoint {
    GroupJoint {
        name: name.into(),
        kind: JointType::Hinge,
        anchor: Point3::from(anchor),
        axis: Vector3::from(axis),
        reference: 0.0,
    }
}

fn slide(name: &str, axis: [f64; 3]) -> GroupJoint {
    GroupJoint {
        name: name.into(),
        kind: JointType::Slider,
        anchor: Point3::origin(),
        axis: Vector3::from(axis),
        reference: 0.0,
    }
}

/// A box hanging from the world by three hinges at (0, 2, 0), its centre 0.5 m out
/// along x, swinging under gravity.
fn gimbal() -> (Simulation, ObjectId) {
    gimbal_in(Simulation::builder().build().unwrap())
}

/// The box of [`gimbal`] in `sim`.
fn gimbal_in(mut sim: Simulation) -> (Simulation, ObjectId) {
    let arm = sim.scene_mut().add_box([1.0, 0.1, 0.2], [0.5, 2.0, 0.0], Mass::Total(2.0)).unwrap();
    let joints = [
        hinge("a", [0.0, 2.0, 0.0], [0.0, 1.0, 0.0]),
        hinge("b", [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]),
        hinge("c", [0.0, 2.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap();
    (sim, arm)
}

fn state(sim: &Simulation, name: &str) -> (f64, f64) {
    let s = sim.scene().joint(name).unwrap().state().unwrap();
    (s.position, s.rate)
}

#[test]
fn three_hinges_at_a_point_read_the_euler_angles_of_the_relative_rotation() {
    let (mut sim, arm) = gimbal();
    sim.scene_mut().body_mut(arm).unwrap().set_angular_velocity(Vector3::new(0.3, 0.2, -0.4)).unwrap();
    sim.step_n(500).unwrap();
    let (a, b, c) = (state(&sim, "a").0, state(&sim, "b").0, state(&sim, "c").0);
    // The body's rotation is R(y, a)·R(z, b)·R(x, c) (it was made unturned).
    let made = Rotation3::from_axis_angle(&Vector3::y_axis(), a)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), b)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), c);
    let rotation = sim.scene().body(arm).unwrap().rotation();
    assert!((made.matrix() - rotation.matrix()).norm() < 1e-9, "{a} {b} {c}: {made:?} against {rotation:?}");
    assert!(b.abs() > 0.05, "the middle hinge moved: {b}");
    // The point stays where the hinges are (to an ODE ball joint's drift).
    let anchor = sim.scene().body(arm).unwrap().pose() * Point3::new(-0.5, 0.0, 0.0);
    assert!((anchor - Point3::new(0.0, 2.0, 0.0)).norm() < 1e-5, "{anchor}");
}

#[test]
fn each_hinge_s_rate_is_its_angle_s_derivative() {
    // Spinning free (no gravity), the middle angle off 0: a rate measured along the
    // hinges' axes instead of their dual axes would be off by about 0.05 rad/s.
    let (mut sim, arm) = gimbal_in(Simulation::builder().gravity(Vector3::zeros()).build().unwrap());
    sim.scene_mut().body_mut(arm).unwrap().set_angular_velocity(Vector3::new(0.3, 0.2, -0.4)).unwrap();
    sim.step_n(300).unwrap();
    let h = sim.scene().time_step();
    for name in ["a", "b", "c"] {
        let before = state(&sim, name).0;
        sim.step().unwrap();
        let (after, rate) = state(&sim, name);
        // ODE turns the bodies by their velocities after the step; the dual axes turn
        // with them within the step (a few 1e-6 rad/s).
        let derivative = (after - before) / h;
        assert!((derivative - rate).abs() < 1e-4, "{name}: {derivative} against {rate}");
        assert!(rate.abs() > 0.04, "{name} turns: {rate}");
    }
}

#[test]
fn a_torque_on_one_hinge_is_that_hinge_s_effort_alone() {
    // Without gravity and at rest, a torque on "b" starts "b" alone turning: its dual
    // axis does no work on "a" or "c".
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let arm = sim.scene_mut().add_box([0.3, 0.3, 0.3], [0.0, 2.0, 0.0], Mass::Total(2.0)).unwrap();
    let tilted = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.6);
    sim.scene_mut().body_mut(arm).unwrap().set_rotation(tilted).unwrap();
    let joints = [
        hinge("a", [0.0, 2.0, 0.0], [0.0, 1.0, 0.0]),
        hinge("b", [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]),
        hinge("c", [0.0, 2.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap();
    sim.scene_mut().joint_mut("c").unwrap().add_torque(0.5).unwrap();
    sim.step().unwrap();
    let (a, b, c) = (state(&sim, "a").1, state(&sim, "b").1, state(&sim, "c").1);
    assert!(c > 1e-3, "c turns: {c}");
    // A cube's inertia is the same about every axis: the joints' coordinates are
    // coupled only through the rotation, which is 0.6 rad about b.
    assert!(a.abs() < 1e-9 && b.abs() < 1e-9, "a {a} and b {b} stay");
}

#[test]
fn stops_hold_a_hinge_of_the_group() {
    let (mut sim, _) = gimbal();
    sim.scene_mut().joint_mut("b").unwrap().set_limits(-0.3, 0.3).unwrap();
    sim.step_n(3000).unwrap();
    let b = state(&sim, "b").0;
    assert!(b > -0.32, "the arm falls about z, held at -0.3: {b}");
    assert!(b < -0.25, "it rests on its stop: {b}");
}

#[test]
fn a_planar_body_slides_and_turns_in_its_plane_only() {
    let mut sim = Simulation::builder().build().unwrap();
    let body = sim.scene_mut().add_box([0.4, 0.2, 0.2], [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let joints =
        [slide("x", [1.0, 0.0, 0.0]), slide("y", [0.0, 1.0, 0.0]), hinge("turn", [0.1, 1.0, 0.0], [0.0, 0.0, 1.0])];
    sim.scene_mut().add_joint_group(body, JointEnd::World, &joints).unwrap();
    {
        let mut b = sim.scene_mut().body_mut(body).unwrap();
        b.set_linear_velocity(Vector3::new(1.0, 0.5, 0.7)).unwrap();
        b.set_angular_velocity(Vector3::new(0.4, -0.3, 2.0)).unwrap();
    }
    sim.step_n(1000).unwrap();
    let pose = sim.scene().body(body).unwrap().pose();
    // Out of the plane: held (the velocity given out of it is taken away at once).
    assert!(pose.translation.z.abs() < 1e-3, "{pose}");
    let (x, y, turn) = (state(&sim, "x").0, state(&sim, "y").0, state(&sim, "turn").0);
    // Falling under gravity along -y, moving along x, turning about z.
    assert!(y < -0.3 && x.abs() > 0.1 && turn.abs() > 0.1, "{x} {y} {turn}");
    // The anchor is where the slides put it.
    let anchor = pose * Point3::new(0.1, 0.0, 0.0);
    assert!((anchor - Point3::new(0.1 + x, 1.0 + y, 0.0)).norm() < 1e-3, "{anchor} against {x} {y}");
}

#[test]
fn a_body_on_slides_alone_never_turns_and_slides_as_pushed() {
    // Two slides (a point mass in a plane, as dm_control's): the rotation is held about
    // fixed axes. A force off its centre and a torque would turn a free body.
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let body = sim.scene_mut().add_box([0.4, 0.2, 0.2], [0.0, 1.0, 0.0], Mass::Total(2.0)).unwrap();
    let joints = [slide("x", [1.0, 0.0, 0.0]), slide("z", [0.0, 0.0, 1.0])];
    sim.scene_mut().add_joint_group(body, JointEnd::World, &joints).unwrap();
    // Given a spin and a push out of the plane: both taken away at once.
    {
        let mut b = sim.scene_mut().body_mut(body).unwrap();
        b.set_angular_velocity(Vector3::new(0.5, -1.0, 2.0)).unwrap();
        b.set_linear_velocity(Vector3::new(0.0, 0.3, 0.0)).unwrap();
    }
    let steps = 2000;
    for _ in 0..steps {
        let mut b = sim.scene_mut().body_mut(body).unwrap();
        b.add_force_at_point(Vector3::new(1.0, 0.0, 0.5), Point3::new(0.2, 1.1, 0.1)).unwrap();
        b.add_torque(Vector3::new(0.3, -0.2, 0.4)).unwrap();
        sim.step().unwrap();
    }
    let b = sim.scene().body(body).unwrap();
    let turned = b.rotation().angle();
    assert!(turned < 1e-4, "turned by {turned} rad");
    assert!(b.angular_velocity().norm() < 1e-6, "{}", b.angular_velocity());
    // The force moves it as it would move its mass: x = F t² / 2m along each slide.
    let t = steps as f64 * sim.scene().time_step();
    let (x, z) = (state(&sim, "x").0, state(&sim, "z").0);
    assert!((x - 1.0 * t * t / 4.0).abs() < 1e-2 * x, "{x} against {}", t * t / 4.0);
    assert!((z - 0.5 * t * t / 4.0).abs() < 1e-2 * z, "{z} against {}", 0.5 * t * t / 4.0);
    assert!((b.position().y - 1.0).abs() < 1e-3, "{}", b.position());
}

#[test]
fn a_scene_file_and_a_snapshot_make_the_group_again_to_the_bit() {
    let (mut sim, arm) = gimbal();
    sim.scene_mut().joint_mut("b").unwrap().set_limits(-0.3, 0.3).unwrap();
    sim.scene_mut().joint_mut("a").unwrap().set_damping(0.2).unwrap();
    sim.scene_mut().joint_mut("c").unwrap().set_speed(0.5, 1.0).unwrap();
    sim.step_n(200).unwrap();
    let snapshot = sim.snapshot().unwrap();
    let mut copy = Simulation::from_snapshot(&snapshot).unwrap();
    sim.step_n(500).unwrap();
    copy.step_n(500).unwrap();
    let copied = copy.scene().object("box").unwrap().id();
    let (p, q) = (sim.scene().body(arm).unwrap().pose(), copy.scene().body(copied).unwrap().pose());
    assert_eq!(p, q);
    for name in ["a", "b", "c"] {
        assert_eq!(state(&sim, name), state(&copy, name), "{name}");
    }
    // Saved after steps, the joints read where they are.
    let reloaded = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    for name in ["a", "b", "c"] {
        assert!((state(&sim, name).0 - state(&reloaded, name).0).abs() < 1e-12, "{name}");
    }
}

#[test]
fn removing_one_joint_of_a_group_removes_the_group() {
    let (mut sim, arm) = gimbal();
    let b = sim.scene().joint("b").unwrap().id();
    sim.remove_joint(b).unwrap();
    assert!(sim.scene().joint("a").is_err() && sim.scene().joint("c").is_err());
    sim.step_n(500).unwrap();
    // The arm falls free.
    assert!(sim.scene().body(arm).unwrap().position().y < 1.99);
    // And an object with a group goes with it.
    let (mut sim, arm) = gimbal();
    sim.remove_object(arm).unwrap();
    sim.step().unwrap();
}

#[test]
fn what_a_group_cannot_take_is_refused() {
    let cases: Vec<(Vec<GroupJoint>, &str)> = vec![
        (vec![hinge("a", [0.0; 3], [0.0, 1.0, 0.0]), hinge("b", [0.0; 3], [0.0, 1.0, 1.0])], "perpendicular"),
        (vec![hinge("a", [0.0; 3], [0.0, 1.0, 0.0]), hinge("b", [0.1, 0.0, 0.0], [1.0, 0.0, 0.0])], "one point"),
        (vec![hinge("a", [0.0; 3], [0.0, 1.0, 0.0]), slide("b", [1.0, 0.0, 0.0])], "slides first"),
        (vec![slide("a", [1.0, 0.0, 0.0]), hinge("b", [0.0; 3], [0.0, 1.0, 0.0])], "one slide"),
        (
            vec![slide("a", [1.0, 0.0, 0.0]), slide("b", [0.0, 1.0, 0.0]), hinge("c", [0.0; 3], [1.0, 0.0, 0.0])],
            "normal of their plane",
        ),
        (vec![hinge("a", [0.0; 3], [f64::NAN, 1.0, 0.0]), hinge("b", [0.0; 3], [1.0, 0.0, 0.0])], "axis"),
        (vec![hinge("a", [0.0; 3], [0.0, 1.0, 0.0])], "2 to 6"),
    ];
    for (joints, says) in cases {
        let mut sim = Simulation::builder().build().unwrap();
        let arm = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        let error = sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap_err().to_string();
        assert!(error.contains(says), "{error:?} should say {says:?}");
        assert_eq!(sim.scene().joints().count(), 0, "nothing made");
        assert_eq!(sim.scene().world().joints().count(), 0, "nothing made in ODE");
        sim.step().unwrap();
    }
    // Slides join an object to the world only.
    let mut sim = Simulation::builder().build().unwrap();
    let base = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let arm = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 2.0, 0.0], Mass::Total(1.0)).unwrap();
    let joints = [slide("a", [1.0, 0.0, 0.0]), slide("b", [0.0, 1.0, 0.0])];
    let error = sim.scene_mut().add_joint_group(arm, base, &joints).unwrap_err().to_string();
    assert!(error.contains("world only"), "{error}");
    // A slide of a planar body takes no motor.
    let joints =
        [slide("x", [1.0, 0.0, 0.0]), slide("y", [0.0, 1.0, 0.0]), hinge("t", [0.0, 2.0, 0.0], [0.0, 0.0, 1.0])];
    sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap();
    let error = sim.scene_mut().joint_mut("x").unwrap().set_damping(1.0).unwrap_err().to_string();
    assert!(error.contains("planar"), "{error}");
    sim.scene_mut().joint_mut("t").unwrap().set_damping(1.0).unwrap();
    sim.step_n(10).unwrap();
}

#[test]
fn a_group_steps_through_gimbal_lock() {
    // The middle hinge exactly at 90°: the first and last axes line up, and the group
    // still steps and reads finite positions.
    let mut sim = Simulation::builder().build().unwrap();
    let arm = sim.scene_mut().add_box([1.0, 0.1, 0.2], [0.0, 2.5, 0.0], Mass::Total(2.0)).unwrap();
    let joints = [
        GroupJoint { reference: 0.0, ..hinge("a", [0.0, 2.0, 0.0], [0.0, 1.0, 0.0]) },
        GroupJoint { reference: std::f64::consts::FRAC_PI_2, ..hinge("b", [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]) },
        hinge("c", [0.0, 2.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap();
    sim.scene_mut().joint_mut("a").unwrap().set_damping(0.5).unwrap();
    sim.scene_mut().joint_mut("c").unwrap().set_limits(-0.5, 0.5).unwrap();
    let b = state(&sim, "b").0;
    // (At 90° the angle comes from a cosine near 0: to about the root of the epsilon.)
    assert!((b - std::f64::consts::FRAC_PI_2).abs() < 1e-7, "{b}");
    sim.step_n(200).unwrap();
    for name in ["a", "b", "c"] {
        let (p, r) = state(&sim, name);
        assert!(p.is_finite() && r.is_finite(), "{name}: {p} {r}");
    }
}

#[test]
fn a_child_turned_half_round_from_its_parent_makes_a_group() {
    // Found on the fruit fly's legs: the child's rotation where the joints read 0 is
    // 180° from the parent's (a rotation an iterative fit from the identity misses).
    let mut sim = Simulation::builder().build().unwrap();
    let arm = sim.scene_mut().add_box([1.0, 0.1, 0.2], [0.5, 2.0, 0.0], Mass::Total(2.0)).unwrap();
    let half = Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI);
    sim.scene_mut().body_mut(arm).unwrap().set_rotation(half).unwrap();
    let joints = [hinge("a", [0.0, 2.0, 0.0], [0.0, 1.0, 0.0]), hinge("b", [0.0, 2.0, 0.0], [0.0, 0.0, 1.0])];
    sim.scene_mut().add_joint_group(arm, JointEnd::World, &joints).unwrap();
    assert_eq!(state(&sim, "a").0, 0.0);
    sim.step_n(100).unwrap();
    let copy = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    assert!((state(&sim, "b").0 - state(&copy, "b").0).abs() < 1e-12);
}

#[test]
fn a_slide_of_a_group_rests_on_its_stop_and_leaves_it_freely() {
    // A point mass sliding in a vertical plane, its height held above -0.5 m.
    let mut sim = Simulation::builder().build().unwrap();
    let mass = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let joints = [slide("x", [1.0, 0.0, 0.0]), slide("y", [0.0, 1.0, 0.0])];
    sim.scene_mut().add_joint_group(mass, JointEnd::World, &joints).unwrap();
    sim.scene_mut().joint_mut("y").unwrap().set_limits(-0.5, 0.5).unwrap();
    sim.scene_mut().body_mut(mass).unwrap().set_linear_velocity(Vector3::new(0.3, 0.0, 0.0)).unwrap();
    sim.step_n(2000).unwrap();
    let (x, y) = (state(&sim, "x"), state(&sim, "y"));
    assert!((y.0 + 0.5).abs() < 1e-3 && y.1.abs() < 1e-3, "rests on its stop: {y:?}");
    // Sliding along x without friction from the stop.
    assert!((x.1 - 0.3).abs() < 1e-9, "{x:?}");
    // Thrown up, it leaves the stop: a stop pushes, never pulls.
    sim.scene_mut().body_mut(mass).unwrap().set_linear_velocity(Vector3::new(0.0, 2.0, 0.0)).unwrap();
    sim.step().unwrap();
    assert!(state(&sim, "y").1 > 1.9, "{:?}", state(&sim, "y"));
    // Up to the upper stop, which holds it below 0.5 m.
    sim.scene_mut().body_mut(mass).unwrap().set_linear_velocity(Vector3::new(0.0, 20.0, 0.0)).unwrap();
    sim.step_n(500).unwrap();
    let highest = (0..500)
        .map(|_| {
            sim.step().unwrap();
            state(&sim, "y").0
        })
        .fold(f64::MIN, f64::max);
    assert!(highest < 0.52, "{highest}");
}
