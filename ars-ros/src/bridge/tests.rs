//! The bridge without the network, on the thesis' mobile manipulator.

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, ProgramRunner, Simulation, SpaceKind};
use ars_programs::golden::{GoldenTable, Verdict, record_csv};
use ars_programs::{SpeedProfile, VehicleSpec, build_mobile_manipulator};

use super::commands::{CommandGains, CommandKind};
use super::sim_interfaces::{CallResult, ResetSimulationRequest, SimulationState};
use super::wire::{Float64MultiArray, JointState, Twist};
use super::{BridgeCore, BridgeOptions, prepare};
use crate::mcap::FrameStepper;
use crate::msg::Vector3 as RosVector3;
use crate::topics::{Message, Outgoing};
use crate::{Publisher, RosOptions};

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
    scene.set_name(chassis, "base_link").expect("a name");
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

fn lock_step_of<S: FrameStepper>(sim: S) -> BridgeCore<S> {
    prepare(sim, &BridgeOptions { lock_step: true, ..Default::default() }).expect("a bridge")
}

/// A `StepSimulation` of `n` steps, as the node takes it: the messages it sends.
fn steps<S: FrameStepper>(core: &mut BridgeCore<S>, n: u64) -> Vec<Outgoing> {
    core.check_step_request(n).expect("paused");
    let mut sent = Vec::new();
    for _ in 0..n {
        assert_eq!(core.step().expect("a step"), Vec::<String>::new());
        if core.state_due() {
            sent.extend(core.poll().expect("messages"));
        }
    }
    sent.extend(core.poll_with_state_now().expect("messages"));
    sent
}

/// The messages of topic `name` in `sent`.
fn on<'a>(core: &BridgeCore, sent: &'a [Outgoing], name: &str) -> Vec<&'a Message> {
    let index = core.topics().iter().position(|t| t.name == name).expect(name);
    sent.iter().filter(|o| o.topic == index).map(|o| &o.message).collect()
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
    let scene = core.sim().scene();
    let state = scene.joint_state(scene.joint(name).expect(name).id()).expect("a state");
    (state.position, state.rate)
}

fn snapshot_bytes(sim: &Simulation) -> Vec<u8> {
    sim.snapshot().expect("a snapshot").to_bytes()
}

/// The mobile manipulator with the publisher's sensor, as the bridge has it.
fn published_mobile_manipulator() -> Simulation {
    let mut sim = mobile_manipulator();
    let options = RosOptions::for_scene(sim.scene());
    Publisher::attach(&mut sim, &options).expect("a publisher");
    sim
}

#[test]
fn lock_step_gives_the_bits_of_the_headless_run() {
    let mut core = lock_step();
    for n in [1, 10, 489, 500] {
        steps(&mut core, n);
    }
    // The same simulation with the same sensors, stepped headless.
    let mut headless = published_mobile_manipulator();
    headless.step_n(1000).expect("steps");
    assert_eq!(core.sim().scene().step_count(), 1000);
    assert_eq!(snapshot_bytes(core.sim()), snapshot_bytes(&headless));
}

#[test]
fn lock_step_gives_the_golden_hash_of_the_headless_program() {
    // The mobile manipulator tracking its speed profile (the golden run
    // `speed_profile`: its program's hooks each step), stepped through the bridge in
    // calls of uneven lengths, publishing at every state period and after each call.
    let mut program = SpeedProfile::with_derivative_gain(0.0);
    let runner = ProgramRunner::new(&mut program).expect("the program");
    let mut core = lock_step_of(runner);
    let steps_in_15_s = core.sim().scene().steps_in(15.0).expect("15 s");
    let (mut done, mut sent) = (0, 0);
    for n in [1, 7, 49, 500, 4_999].iter().cycle() {
        let n = (*n).min(steps_in_15_s - done);
        sent += steps(&mut core, n).len();
        done += n;
        if done == steps_in_15_s {
            break;
        }
    }
    assert!(sent > 750, "{sent} messages: the state every 20 ms");
    let sim = core.into_stepper().into_simulation();
    let csv = record_csv(sim.records(program.record.expect("the record")).expect("records")).expect("CSV");
    match GoldenTable::committed().compare("speed_profile", &csv) {
        Verdict::Identical => {}
        other => panic!("the lock-stepped run is not the golden one: {other:?}"),
    }
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
    let names: Vec<&str> = core.joints().iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["r1", "r2", "w1", "w2"], "in the order of the scene's names");
}

#[test]
fn cmd_vel_drives_the_vehicle_forward_and_turns_it_left() {
    let chassis = |core: &BridgeCore| core.drive().expect("a drive").chassis;
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
    let mut headless = published_mobile_manipulator();
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
    let mut headless = published_mobile_manipulator();
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
fn what_the_bridge_sends_is_what_an_mcap_recording_holds() {
    let mut core = lock_step();
    let first = steps(&mut core, 0);
    let tf_static = on(&core, &first, "/tf_static");
    let Message::Tf(fixed) = tf_static[0] else { panic!("a TF message") };
    assert!(
        fixed.transforms.iter().any(|t| (t.header.frame_id.as_str(), t.child_frame_id.as_str()) == ("map", "odom"))
    );
    // 1 s at 50 Hz, then 1 step: the state every 20 ms, and where the call ended.
    let sent = steps(&mut core, 2501);
    let stamps: Vec<u64> = on(&core, &sent, "/clock")
        .iter()
        .map(|m| match m {
            Message::Clock(c) => c.clock.sec as u64 * 1_000_000_000 + u64::from(c.clock.nanosec),
            _ => panic!("a clock"),
        })
        .collect();
    assert_eq!(stamps.len(), 51, "{stamps:?}");
    assert!(stamps[..50].iter().enumerate().all(|(k, s)| *s == 20_000_000 * (k as u64 + 1)), "{stamps:?}");
    assert_eq!(stamps[50], 1_000_400_000);
    // The vehicle (found by its drive) has its odometry; the last is where it is now.
    let odom = on(&core, &sent, "/odom");
    assert_eq!(odom.len(), 51);
    let Message::Odometry(last) = odom[50] else { panic!("odometry") };
    let at = core.sim().scene().position(core.drive().expect("a drive").chassis).expect("at");
    let p = last.pose.pose.position;
    assert_eq!([p.x, p.y, p.z], [at.x, -at.z, at.y], "ARS's Y-up numbers, swapped into map's Z-up");
    // /joint_states: the sensor's samples with their efforts, then the state now
    // without efforts.
    let states = on(&core, &sent, "/joint_states");
    let Message::JointState(now) = states[states.len() - 1] else { panic!("joint states") };
    assert_eq!(now.name, ["r1", "r2", "w1", "w2"]);
    assert_eq!(now.position[2], joint(&core, "w1").0);
    assert!(now.effort.is_empty());
    let Message::JointState(sampled) = states[0] else { panic!("joint states") };
    assert_eq!(sampled.effort.len(), 4);
}

#[test]
fn a_vehicle_found_by_its_drive_has_its_odometry_whatever_its_name() {
    let mut core = lock_step_of(ball_wheeled());
    let sent = steps(&mut core, 50);
    let Message::Odometry(odom) = on(&core, &sent, "/odom")[0] else { panic!("odometry") };
    assert_eq!((odom.header.frame_id.as_str(), odom.child_frame_id.as_str()), ("odom", "base_link"));
}

#[test]
fn bad_options_are_refused_before_any_network() {
    let refused = |options: BridgeOptions| prepare(mobile_manipulator(), &options).err().expect("refused").to_string();
    assert!(refused(BridgeOptions { domain_id: 300, ..Default::default() }).contains("0 to 232"));
    let rate = refused(BridgeOptions { rate: 0.0, ..Default::default() });
    assert!(rate.contains("state rate") && rate.contains("got 0"), "{rate}");
    let drive = Some(("left".to_string(), "w1".to_string()));
    assert!(refused(BridgeOptions { drive, ..Default::default() }).contains("no hinge joint named \"left\""));
    // What a front end asks before it hands a simulation over: the same refusal.
    let sim = mobile_manipulator();
    let drive = Some(("left".to_string(), "w1".to_string()));
    let asked = super::check(sim.scene(), &BridgeOptions { drive, ..Default::default() }).unwrap_err().to_string();
    assert!(asked.contains("no hinge joint named \"left\""), "{asked}");
    let _ = CommandGains::default();
}
