//! The bridge on the network, called by another ROS 2 node (ros2-client, with the
//! request identity ROS 2's default middleware uses): lock step through
//! `/ars/step_simulation`, `/clock` and `/joint_states` after it, and quitting through
//! `/ars/set_simulation_state`.

mod common;

use std::time::{Duration, Instant};

use ars_ros::bridge::sim_interfaces::{CallResult, SimulationState};
use ars_ros::bridge::wire::{Clock, JointState, Time, type_names};
use ars_ros::bridge::{BridgeOptions, run};
use common::{Tester, mobile_manipulator, qos};
use ros2_client::Name;

#[test]
fn another_node_steps_the_bridge_in_lock_step_and_ends_it() {
    let domain = 1 + (std::process::id() % 50) as u16;
    let options = BridgeOptions { domain_id: domain, lock_step: true, ..Default::default() };
    let bridge = std::thread::spawn(move || run(mobile_manipulator(), &options).map(|sim| sim.scene().step_count()));

    let mut tester = Tester::on_domain(domain);
    let node = &mut tester.node;
    let clock_topic = node
        .create_topic(&Name::new("/", "clock").expect("a name"), type_names::clock(), &qos(false))
        .expect("a topic");
    let clock = node.create_subscription::<Clock>(&clock_topic, None).expect("a subscription");
    let states_topic = node
        .create_topic(&Name::new("/", "joint_states").expect("a name"), type_names::joint_state(), &qos(true))
        .expect("a topic");
    let joint_states = node.create_subscription::<JointState>(&states_topic, None).expect("a subscription");

    let state = tester.wait_for_bridge();
    assert_eq!((state.state.state, state.result), (SimulationState::PAUSED, CallResult::ok()));
    assert_eq!(tester.step(2500).result, CallResult::ok());
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

    assert_eq!(tester.quit().result, CallResult::ok());
    let steps = bridge.join().expect("no panic").expect("the bridge ended well");
    assert_eq!(steps, 2500);
}
