//! The bridge on the network, called by another ROS 2 node (ros2-client, with the
//! request identity ROS 2's default middleware uses): lock step through
//! `/ars/step_simulation`, `/clock` and `/joint_states` after it, and quitting through
//! `/ars/set_simulation_state`.

use std::time::{Duration, Instant};

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, Simulation, SpaceKind};
use ars_programs::{VehicleSpec, build_mobile_manipulator};
use ars_ros::bridge::sim_interfaces::{
    CallResult, GetSimulationStateRequest, GetSimulationStateResponse, ResultResponse, SetSimulationStateRequest,
    SimulationState, StepSimulationRequest, service_type,
};
use ars_ros::bridge::wire::{Clock, JointState, Time, type_names};
use ars_ros::bridge::{BridgeOptions, run};
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::{Client, Context, ContextOptions, Message, Name, NodeName, NodeOptions, QosProfile, ServiceMapping};

fn mobile_manipulator() -> Simulation {
    let mut sim =
        Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build().expect("a simulation");
    build_mobile_manipulator(&mut sim, &VehicleSpec::default(), Mass::Density(1.0)).expect("the vehicle");
    sim
}

fn qos(reliable: bool) -> QosProfile {
    let reliability =
        if reliable { Reliability::Reliable { when_full: WhenFull::Fail } } else { Reliability::BestEffort };
    QosProfile::default()
        .reliability(reliability)
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth: 100 })
}

/// Calls `client` with `request`, once, waiting up to `timeout` for the answer.
fn call<Q: Message + Clone + 'static, A: Message + 'static>(
    client: &Client<Q, A>,
    request: Q,
    timeout: Duration,
) -> Option<A> {
    let id = client.send_request(request).expect("sent");
    let end = Instant::now() + timeout;
    while Instant::now() < end {
        if let Ok(Some((answered, answer))) = client.receive_response()
            && answered == id
        {
            return Some(answer);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    None
}

#[test]
fn another_node_steps_the_bridge_in_lock_step_and_ends_it() {
    let domain = 1 + (std::process::id() % 50) as u16;
    let options = BridgeOptions { domain_id: domain, lock_step: true, ..Default::default() };
    let bridge = std::thread::spawn(move || run(mobile_manipulator(), &options).map(|sim| sim.scene().step_count()));

    let context = Context::with_options(ContextOptions::new().domain_id(domain)).expect("DDS");
    let mut node = context.new_node(NodeName::new("/", "tester").expect("a name"), NodeOptions::new()).expect("a node");
    let name = |base: &str| Name::new("/ars", base).expect("a name");
    let get_state = node
        .create_client::<GetSimulationStateRequest, GetSimulationStateResponse>(
            ServiceMapping::Enhanced,
            &name("get_simulation_state"),
            &service_type("GetSimulationState"),
            qos(true),
            qos(true),
        )
        .expect("a client");
    let step = node
        .create_client::<StepSimulationRequest, ResultResponse>(
            ServiceMapping::Enhanced,
            &name("step_simulation"),
            &service_type("StepSimulation"),
            qos(true),
            qos(true),
        )
        .expect("a client");
    let set_state = node
        .create_client::<SetSimulationStateRequest, ResultResponse>(
            ServiceMapping::Enhanced,
            &name("set_simulation_state"),
            &service_type("SetSimulationState"),
            qos(true),
            qos(true),
        )
        .expect("a client");
    let clock_topic = node
        .create_topic(&Name::new("/", "clock").expect("a name"), type_names::clock(), &qos(false))
        .expect("a topic");
    let clock = node.create_subscription::<Clock>(&clock_topic, None).expect("a subscription");
    let states_topic = node
        .create_topic(&Name::new("/", "joint_states").expect("a name"), type_names::joint_state(), &qos(true))
        .expect("a topic");
    let joint_states = node.create_subscription::<JointState>(&states_topic, None).expect("a subscription");

    // Discovery: ask for the state until the bridge answers (asking changes nothing).
    let state =
        (0..60).find_map(|_| call(&get_state, GetSimulationStateRequest::default(), Duration::from_millis(500)));
    let state = state.expect("an answer from /ars/get_simulation_state within 30 s");
    assert_eq!((state.state.state, state.result), (SimulationState::PAUSED, CallResult::ok()));

    let stepped = call(&step, StepSimulationRequest { steps: 2500 }, Duration::from_secs(60)).expect("stepped");
    assert_eq!(stepped.result, CallResult::ok());
    // After the call: the state at t = 1 s (2500 steps of 0.4 ms).
    let one_second = Time { sec: 1, nanosec: 0 };
    let end = Instant::now() + Duration::from_secs(10);
    let (mut clock_at, mut states_at) = (None, None);
    while Instant::now() < end && (clock_at != Some(one_second) || states_at != Some(one_second)) {
        while let Ok(Some((c, _))) = clock.take() {
            clock_at = Some(c.clock);
        }
        while let Ok(Some((s, _))) = joint_states.take() {
            assert_eq!(s.name, ["r1", "r2", "w1", "w2"]);
            states_at = Some(s.header.stamp);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!((clock_at, states_at), (Some(one_second), Some(one_second)));

    let quit = SetSimulationStateRequest { state: SimulationState { state: SimulationState::QUITTING } };
    assert_eq!(call(&set_state, quit, Duration::from_secs(10)).expect("answered").result, CallResult::ok());
    let steps = bridge.join().expect("no panic").expect("the bridge ended well");
    assert_eq!(steps, 2500);
}
