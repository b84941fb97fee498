//! MCAP recordings read back with the `mcap` crate: channels as `ros2 bag` writes them,
//! messages stamped with simulated time, and values equal to the sensor records.

use std::path::PathBuf;

use ars_core::formats::urdf::UrdfOptions;
use ars_core::nalgebra::Isometry3;
use ars_core::sensors::Lidar;
use ars_core::{Mass, Simulation};
use ars_ros::msg::{self, Clock, JointState, LaserScan, TfMessage};
use ars_ros::{JointStates, RosOptions, record_mcap};

const PENDULUM: &str = r#"<robot name="pendulum">
  <link name="base"/>
  <link name="bob"><inertial><origin xyz="0.3 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="pivot" type="continuous"><parent link="base"/><child link="bob"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/></joint>
</robot>"#;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ars-ros-mcap-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("run.mcap")
}

fn pendulum_with_lidar() -> (Simulation, ars_core::SensorId<Lidar>) {
    let mut sim = Simulation::new().unwrap();
    sim.load_urdf_text(PENDULUM, "pendulum.urdf", &UrdfOptions::new()).unwrap();
    sim.scene_mut().add_box([0.2, 0.2, 0.2], [2.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let lidar = Lidar::new(16, 1.0, 5.0).unwrap().at(Isometry3::translation(0.0, 1.0, 0.0));
    let lidar = sim.add_sensor_every(lidar, 0.05).unwrap();
    (sim, lidar)
}

#[test]
fn a_recording_reads_back_as_ros2_bag_writes_it_with_the_records_values() {
    let (mut sim, lidar) = pendulum_with_lidar();
    let path = scratch("round-trip");
    let summary = record_mcap(&mut sim, &path, 0.1, &RosOptions::default(), || false).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let mut by_topic: std::collections::BTreeMap<String, Vec<(u64, Vec<u8>)>> = Default::default();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        let channel = &message.channel;
        let schema = channel.schema.as_ref().unwrap();
        assert_eq!((schema.encoding.as_str(), channel.message_encoding.as_str()), ("ros2msg", "cdr"));
        assert_eq!(std::str::from_utf8(&schema.data).unwrap(), msg::schema(&schema.name).unwrap());
        assert!(channel.metadata["offered_qos_profiles"].starts_with("- history: 1\n"));
        assert_eq!(message.log_time, message.publish_time);
        by_topic.entry(channel.topic.clone()).or_default().push((message.log_time, message.data.to_vec()));
    }
    let count = |topic: &str| by_topic.get(topic).map_or(0, Vec::len);
    assert_eq!(summary.total(), by_topic.values().map(|v| v.len() as u64).sum::<u64>());
    // 0.1 s at 50 Hz: t = 0, 0.02 ... 0.1.
    assert_eq!(count("/clock"), 6);
    assert_eq!(count("/tf"), 6);
    assert_eq!((count("/tf_static"), count("/robot_description")), (1, 1));
    for (stamp, data) in &by_topic["/clock"] {
        assert_eq!(msg::decode::<Clock>(data).unwrap().clock.nanos(), *stamp);
    }
    let tf: TfMessage = msg::decode(&by_topic["/tf"][5].1).unwrap();
    assert!(tf.transforms.iter().any(|t| t.header.frame_id == "base" && t.child_frame_id == "bob"), "{tf:?}");
    // Joint states: the publisher's sensor's records, bit for bit.
    let states = sim.records(sim.sensor_ids_of::<JointStates>()[0]).unwrap();
    assert_eq!(count("/joint_states"), states.len());
    for ((stamp, data), sample) in by_topic["/joint_states"].iter().zip(states.samples()) {
        let state: JointState = msg::decode(data).unwrap();
        assert_eq!(*stamp, msg::nanos_of(sample.time));
        assert_eq!((state.name, state.position), (vec!["pivot".to_string()], sample.record.position.clone()));
    }
    // Scans: the lidar's records, every 50 ms.
    let scans = sim.records(lidar).unwrap();
    assert_eq!(count("/scan"), scans.len());
    assert_eq!(scans.len(), 2);
    for ((stamp, data), sample) in by_topic["/scan"].iter().zip(scans.samples()) {
        let scan: LaserScan = msg::decode(data).unwrap();
        assert_eq!(*stamp, msg::nanos_of(sample.time));
        assert_eq!(scan.ranges, sample.record.ranges.iter().map(|r| *r as f32).collect::<Vec<_>>());
        assert!(scan.ranges.iter().any(|r| r.is_finite()), "the box is seen");
    }
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
}

#[test]
fn a_stopped_recording_is_a_finished_file_of_what_was_recorded() {
    let (mut sim, _) = pendulum_with_lidar();
    let path = scratch("stopped");
    let mut asked = 0;
    let stopped = record_mcap(&mut sim, &path, 1.0, &RosOptions::default(), || {
        asked += 1;
        asked > 2
    });
    assert!(matches!(stopped, Err(ars_ros::RosError::Simulation(ars_core::Error::Interrupted { .. }))), "{stopped:?}");
    let bytes = std::fs::read(&path).unwrap();
    let clocks = mcap::MessageStream::new(&bytes).unwrap().filter(|m| m.as_ref().unwrap().channel.topic == "/clock");
    assert_eq!(clocks.count(), 3, "t = 0 and two frames");
    assert!(mcap::read::Summary::read(&bytes).unwrap().is_some(), "the file was finished");
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
}

#[test]
fn a_folder_that_does_not_exist_is_an_io_error_naming_the_file() {
    let mut sim = Simulation::new().unwrap();
    let path = std::env::temp_dir().join("ars-ros-no-such-folder").join("run.mcap");
    let err = record_mcap(&mut sim, &path, 0.1, &RosOptions::default(), || false).unwrap_err();
    assert!(matches!(err, ars_ros::RosError::Simulation(ars_core::Error::Io { .. })), "{err:?}");
    assert!(err.to_string().contains("run.mcap"), "{err}");
}

#[test]
fn a_state_rate_out_of_range_is_refused_before_the_file_is_made() {
    let mut sim = Simulation::new().unwrap();
    let path = scratch("rate");
    let options = RosOptions { state_rate: f64::NAN, ..Default::default() };
    let err = record_mcap(&mut sim, &path, 0.1, &options, || false).unwrap_err();
    assert!(err.to_string().contains("ROS state rate"), "{err}");
    assert!(!path.exists());
    assert!(sim.sensor_tables().is_empty(), "no sensor was added");
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
}
