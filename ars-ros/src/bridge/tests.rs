//! The bridge without the network, on the thesis' mobile manipulator.

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, Simulation, SpaceKind};
use ars_programs::{VehicleSpec, build_mobile_manipulator};

use super::commands::{CommandGains, CommandKind};
use super::frames::{ARS_WORLD, WORLD};
use super::sim_interfaces::{CallResult, ResetSimulationRequest, SimulationState};
use super::wire::{Float64MultiArray, JointState, Twist, Vector3 as RosVector3};
use super::{BridgeCore, BridgeOptions, prepare};

/// The mobile manipulator on the floor, as the thesis builds it.
fn mobile_manipulator() -> Simulation {
    vehicle(VehicleSpec::default())
}

fn vehicle(spec: VehicleSpec) -> Simulation {
    let mut sim =
        Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build().expect("a simulation");
    build_mobile_manipulator(&mut sim, &spec, Mass::Density(1.0)).expect("the vehicle");
    sim
}

/// A differential drive on two ball wheels (radius 0.2, hinged about Z 0.8 m apart)
/// and a caster ball, named as a URDF robot's would be.
fn ball_wheeled() -> Simulation {
    let mut sim =
        Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build().expect("a simulation");
    let scene = sim.scene_mut();
    let chassis = scene.add_box([1.0, 0.1, 0.6], [0.3, 0.3, 0.0], Mass::Total(2.0)).expect("chassis");
    scene.set_name(chassis, "chassis").expect("a name");
    let left = scene.add_sphere(0.2, [0.0, 0.2, -0.4], Mass::Total(0.5)).expect("left wheel");
    let right = scene.add_sphere(0.2, [0.0, 0.2, 0.4], Mass::Total(0.5)).expect("right wheel");
    let caster = scene.add_sphere(0.1, [0.7, 0.1, 0.0], Mass::Total(0.1)).expect("caster");
    // ARS's +Z is ROS's -Y: the left wheel (ROS +Y) is at ARS -Z.
    scene.add_hinge_joint("left_wheel_joint", chassis, left, None, Vector3::z()).expect("left hinge");
    scene.add_hinge_joint("right_wheel_joint", chassis, right, None, Vector3::z()).expect("right hinge");
    scene.add_ball_joint("caster_joint", chassis, caster, None).expect("caster joint");
    sim
}

fn lock_step() -> BridgeCore {
    lock_step_of(mobile_manipulator())
}

fn lock_step_of(sim: Simulation) -> BridgeCore {
    prepare(sim, &BridgeOptions { lock_step: true, ..Default::default() }).expect("a bridge")
}

fn steps(core: &mut BridgeCore, n: u64) {
    core.check_step_request(n).expect("paused");
    for _ in 0..n {
        assert_eq!(core.step().expect("a step"), Vec::<String>::new());
    }
}

/// `n` steps with `command` on /cmd_vel every 0.1 s (250 steps), as a teleop node sends it.
fn drive_for(core: &mut BridgeCore, command: Twist, n: u64) {
    for _ in 0..n / 250 {
        core.take_twist(command).expect("a good twist");
        steps(core, 250);
    }
}

fn twist(v: f64, w: f64) -> Twist {
    Twist { linear: RosVector3 { x: v, ..Default::default() }, angular: RosVector3 { z: w, ..Default::default() } }
}

/// Joint `name`'s (position, velocity) now.
fn joint(core: &BridgeCore, name: &str) -> (f64, f64) {
    let states = core.frames.joint_states(core.sim().scene()).expect("states");
    let i = states.name.iter().position(|n| n == name).expect(name);
    (states.position[i], states.velocity[i])
}

fn snapshot_bytes(sim: &Simulation) -> Vec<u8> {
    sim.snapshot().expect("a snapshot").to_bytes()
}

#[test]
fn lock_step_gives_the_bits_of_the_headless_run() {
    let mut core = lock_step();
    for n in [1, 10, 489, 500] {
        steps(&mut core, n);
        // What is published reads the scene and changes nothing.
        core.frames.tf(core.sim().scene()).expect("tf");
        core.frames.joint_states(core.sim().scene()).expect("joint states");
    }
    let mut headless = mobile_manipulator();
    headless.step_n(1000).expect("steps");
    assert_eq!(core.sim().scene().step_count(), 1000);
    assert_eq!(snapshot_bytes(core.sim()), snapshot_bytes(&headless));
}

#[test]
fn the_mobile_manipulators_drive_is_found_with_its_wheels() {
    let core = lock_step();
    let drive = core.drive().expect("w1 and w2 make a drive");
    assert_eq!(drive.wheel_radius, 0.3);
    // Forward is the chassis' +X, up its +Y: w1 (at -Z) is on the left.
    let w1 = core.sim().scene().joint("w1").expect("w1").id();
    assert_eq!(drive.left.0, w1);
    assert!((drive.track - 1.0).abs() < 1e-12, "{}", drive.track);
    let names: Vec<&str> = core.frames.joints.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["r1", "r2", "w1", "w2"], "in the order of the scene's names");
}

#[test]
fn cmd_vel_drives_the_vehicle_forward_and_turns_it_left() {
    let chassis = |core: &BridgeCore| core.sim().scene().object("chassis").expect("chassis").id();
    let mut core = lock_step();
    let start = core.sim().scene().position(chassis(&core)).expect("pose");
    drive_for(&mut core, twist(0.5, 0.0), 5000); // 2 s
    let moved = core.sim().scene().position(chassis(&core)).expect("pose") - start;
    assert!(moved.x > 0.3 && moved.z.abs() < 0.1 * moved.x, "forward is the chassis' +X: moved {moved}");

    // The thesis' wheels (cylinders or capsules) touch the floor along their width
    // and, with ARS's 500 N friction limit, scrub rather than turn; ball wheels turn.
    let mut core = lock_step_of(ball_wheeled());
    drive_for(&mut core, twist(0.0, 0.5), 5000);
    let turned = core.sim().scene().rotation(chassis(&core)).expect("rotation") * Vector3::x();
    // Turning left (ROS +Z, ARS +Y): +X swings toward -Z.
    assert!(turned.z < -0.2, "turned left: +X is now {turned}");
}

#[test]
fn the_wheels_stop_when_cmd_vel_stops() {
    let mut core = lock_step();
    core.take_twist(twist(0.5, 0.0)).expect("a good twist");
    steps(&mut core, 2500 * 3);
    let (_, w1) = joint(&core, "w1");
    assert!(w1.abs() < 0.05, "stopped 0.5 s after the last /cmd_vel, w1 turns at {w1}");
}

#[test]
fn bad_commands_are_refused_with_the_reason_and_change_nothing() {
    let mut core = lock_step();
    let nan = core.take_twist(twist(f64::NAN, 0.0)).unwrap_err();
    assert!(nan.contains("not finite"), "{nan}");
    let short = Float64MultiArray { data: vec![1.0], ..Default::default() };
    let why = core.take_forward(CommandKind::Velocity, &short).unwrap_err();
    assert!(why.contains("1 values for 4 joints (r1, r2, w1, w2)"), "{why}");
    let infinite = Float64MultiArray { data: vec![f64::INFINITY, 0.0, 0.0, 0.0], ..Default::default() };
    let why = core.take_forward(CommandKind::Position, &infinite).unwrap_err();
    assert!(why.contains("\"r1\""), "{why}");
    let unknown =
        JointState { name: vec!["r1".into(), "elbow".into()], velocity: vec![1.0, 1.0], ..Default::default() };
    let why = core.take_named(&unknown).unwrap_err();
    assert!(why.contains("unknown joint \"elbow\""), "{why}");
    steps(&mut core, 100);
    let mut headless = mobile_manipulator();
    headless.step_n(100).expect("steps");
    assert_eq!(snapshot_bytes(core.sim()), snapshot_bytes(&headless));
}

#[test]
fn commands_faster_than_steps_are_said_and_the_last_one_wins() {
    let mut core = lock_step();
    core.take_twist(twist(-0.5, 0.0)).expect("the first");
    let why = core.take_twist(twist(0.5, 0.0)).unwrap_err();
    assert!(why.contains("faster than the simulation steps"), "{why}");
    steps(&mut core, 500);
    let (_, w1) = joint(&core, "w1");
    let (expected, _) = core.drive().expect("a drive").wheel_rates(0.5, 0.0);
    assert!((w1 - expected).abs() < 0.2 * expected.abs(), "w1 at {w1}, the last command's {expected}");
}

#[test]
fn joint_commands_move_the_arm() {
    let mut core = lock_step();
    let r1 = JointState { name: vec!["r1".into()], velocity: vec![0.5], ..Default::default() };
    core.take_named(&r1).expect("a good command");
    steps(&mut core, 2500);
    let (_, r1) = joint(&core, "r1");
    assert!((r1 - 0.5).abs() < 0.05, "r1 turns at {r1}");

    let mut core = lock_step();
    let target = Float64MultiArray { data: vec![0.3, 0.0, 0.0, 0.0], ..Default::default() };
    core.take_forward(CommandKind::Position, &target).expect("a good command");
    steps(&mut core, 5000);
    let (r1, _) = joint(&core, "r1");
    assert!((r1 - 0.3).abs() < 0.02, "r1 at {r1}");
}

#[test]
fn the_simulation_interfaces_calls() {
    let mut core = lock_step();
    assert_eq!(core.get_state().state.state, SimulationState::PAUSED);
    steps(&mut core, 10);
    core.take_twist(twist(0.5, 0.0)).expect("a twist");
    steps(&mut core, 10);
    assert_eq!(core.reset(ResetSimulationRequest::SCOPE_TIME).result.result, CallResult::FEATURE_UNSUPPORTED);
    assert_eq!(core.reset(ResetSimulationRequest::SCOPE_DEFAULT).result, CallResult::ok());
    assert_eq!(core.sim().scene().step_count(), 0);
    // After a reset, the run is the start's again (the wheel motors too).
    steps(&mut core, 100);
    let mut headless = mobile_manipulator();
    headless.step_n(100).expect("steps");
    assert_eq!(snapshot_bytes(core.sim()), snapshot_bytes(&headless));

    assert_eq!(core.set_state(SimulationState::PLAYING).result, CallResult::ok());
    let playing = core.check_step_request(1).unwrap_err();
    assert_eq!(playing.result, CallResult::OPERATION_FAILED);
    assert_eq!(core.set_state(SimulationState::PLAYING).result.result, CallResult::ALREADY_IN_TARGET_STATE);
    assert_eq!(core.set_state(5).result.result, CallResult::INCORRECT_TRANSITION);
    assert_eq!(core.set_state(SimulationState::STOPPED).result, CallResult::ok());
    assert_eq!(core.sim().scene().step_count(), 0);
    assert!(core.check_step_request(u64::MAX).is_err(), "a call cannot hold the bridge for ages");
    assert!(core.features().features.features.contains(&32));
    assert_eq!(core.set_state(SimulationState::QUITTING).result, CallResult::ok());
    assert!(core.is_quitting());
}

#[test]
fn frames_follow_the_joint_tree_under_ars_world() {
    let core = lock_step();
    let tf = core.frames.tf(core.sim().scene()).expect("tf");
    let parent = |child: &str| {
        tf.transforms.iter().find(|t| t.child_frame_id == child).map(|t| t.header.frame_id.clone()).expect(child)
    };
    assert_eq!(parent("chassis"), ARS_WORLD);
    // The wheels and the caster on the chassis, the arm's links one on the other.
    for child in ["cylinder", "cylinder/1", "sphere", "capsule"] {
        assert_eq!(parent(child), "chassis", "{child}");
    }
    assert_eq!(parent("capsule/1"), "capsule");
    let chassis = core.sim().scene().position(core.sim().scene().object("chassis").expect("chassis").id()).expect("at");
    let t = tf.transforms.iter().find(|t| t.child_frame_id == "chassis").expect("chassis").transform.translation;
    assert_eq!([t.x, t.y, t.z], [chassis.x, chassis.y, chassis.z], "ARS's own numbers");
    let fixed = core.frames.tf_static(core.sim().scene()).expect("tf_static");
    let up = &fixed.transforms[0];
    assert_eq!((up.header.frame_id.as_str(), up.child_frame_id.as_str()), (WORLD, ARS_WORLD));
    // A quarter turn about X takes ARS's +Y (up) to ROS's +Z.
    let q = up.transform.rotation;
    assert!((q.x - q.w).abs() < 1e-15 && q.y == 0.0 && q.z == 0.0 && (q.w - 0.5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn bad_options_are_refused_before_any_network() {
    let refused = |options: BridgeOptions| prepare(mobile_manipulator(), &options).err().expect("refused").to_string();
    assert!(refused(BridgeOptions { domain_id: 300, ..Default::default() }).contains("0 to 232"));
    assert!(refused(BridgeOptions { rate: 0.0, ..Default::default() }).contains("rate 0"));
    let drive = Some(("left".to_string(), "w1".to_string()));
    assert!(refused(BridgeOptions { drive, ..Default::default() }).contains("no hinge joint named \"left\""));
    let _ = CommandGains::default();
}
