//! What the tests over DDS share: the thesis' mobile manipulator, and another ROS 2
//! node (ros2-client, with the request identity ROS 2's default middleware uses) that
//! calls the bridge's Simulation Interfaces services.

#![allow(dead_code)] // each test uses its part

use std::time::{Duration, Instant};

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, Simulation, SpaceKind};
use ars_programs::{VehicleSpec, build_mobile_manipulator};
use ars_ros::bridge::sim_interfaces::{
    GetSimulationStateRequest, GetSimulationStateResponse, ResultResponse, SetSimulationStateRequest, SimulationState,
    StepSimulationRequest, service_type,
};
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::{
    Client, Context, ContextOptions, Message, Name, Node, NodeName, NodeOptions, QosProfile, ServiceMapping,
};

/// The mobile manipulator on the floor, as the thesis builds it.
pub fn mobile_manipulator() -> Simulation {
    let mut sim =
        Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build().expect("a simulation");
    build_mobile_manipulator(&mut sim, &VehicleSpec::default(), Mass::Density(1.0)).expect("the vehicle");
    sim
}

/// Volatile, keep last 100, reliable or best effort.
pub fn qos(reliable: bool) -> QosProfile {
    let reliability =
        if reliable { Reliability::Reliable { when_full: WhenFull::Fail } } else { Reliability::BestEffort };
    QosProfile::default()
        .reliability(reliability)
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth: 100 })
}

/// Calls `client` with `request`, once, waiting up to `timeout` for the answer.
pub fn call<Q: Message + Clone + 'static, A: Message + 'static>(
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
        std::thread::sleep(Duration::from_millis(1));
    }
    None
}

/// A node on `domain` with clients of the bridge `/ars`'s state and step services.
pub struct Tester {
    /// The node (to make subscriptions on).
    pub node: Node,
    /// `/ars/get_simulation_state`.
    pub get_state: Client<GetSimulationStateRequest, GetSimulationStateResponse>,
    /// `/ars/step_simulation`.
    pub step: Client<StepSimulationRequest, ResultResponse>,
    /// `/ars/set_simulation_state`.
    pub set_state: Client<SetSimulationStateRequest, ResultResponse>,
}

impl Tester {
    /// The node and its clients.
    pub fn on_domain(domain: u16) -> Tester {
        let context = Context::with_options(ContextOptions::new().domain_id(domain)).expect("DDS");
        let mut node =
            context.new_node(NodeName::new("/", "tester").expect("a name"), NodeOptions::new()).expect("a node");
        let name = |base: &str| Name::new("/ars", base).expect("a name");
        macro_rules! client {
            ($base:literal, $type:literal) => {
                node.create_client(ServiceMapping::Enhanced, &name($base), &service_type($type), qos(true), qos(true))
                    .expect("a client")
            };
        }
        let get_state = client!("get_simulation_state", "GetSimulationState");
        let step = client!("step_simulation", "StepSimulation");
        let set_state = client!("set_simulation_state", "SetSimulationState");
        Tester { node, get_state, step, set_state }
    }

    /// Asks for the state until the bridge answers (discovery; asking changes nothing).
    pub fn wait_for_bridge(&self) -> GetSimulationStateResponse {
        let answer = (0..60)
            .find_map(|_| call(&self.get_state, GetSimulationStateRequest::default(), Duration::from_millis(500)));
        answer.expect("an answer from /ars/get_simulation_state within 30 s")
    }

    /// Steps the bridge `steps` steps; its answer.
    pub fn step(&self, steps: u64) -> ResultResponse {
        call(&self.step, StepSimulationRequest { steps }, Duration::from_secs(600)).expect("stepped")
    }

    /// Asks the bridge to quit; its answer.
    pub fn quit(&self) -> ResultResponse {
        let quit = SetSimulationStateRequest { state: SimulationState { state: SimulationState::QUITTING } };
        call(&self.set_state, quit, Duration::from_secs(10)).expect("answered")
    }
}
