//! What a simulation publishes: the frame tree of a small URDF robot, joint states and
//! laser scans equal to ARS's own sensor records of the same run, odometry, and the
//! Z-up world.

use ars_core::formats::urdf::UrdfOptions;
use ars_core::nalgebra::{Isometry3, UnitQuaternion, Vector3};
use ars_core::sensors::{JointPositions, JointTorque, JointVelocities, Lidar};
use ars_core::{Mass, Simulation};
use ars_ros::msg::{JointState, LaserScan, TfMessage, TransformStamped, nanos_of};
use ars_ros::{Message, Outgoing, Publisher, RosOptions};

const ARM: &str = r#"<robot name="arm">
  <link name="base"><inertial><origin xyz="0 0 0.1"/><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="upper"><inertial><origin xyz="0.2 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><dynamics damping="0.3"/></joint>
  <joint name="flange" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0.1 0 0"/></joint>
</robot>"#;

/// A fixed arm that swings down under gravity, and a ball falling beside it.
fn arm_and_ball() -> Simulation {
    let mut sim = Simulation::new().unwrap();
    let options = UrdfOptions::new().fixed_base(true).exact_base_pose(true);
    sim.load_urdf_text(ARM, "arm.urdf", &options).unwrap();
    sim.scene_mut().add_sphere(0.1, [1.0, 2.0, 3.0], Mass::Total(1.0)).unwrap();
    sim
}

fn on<'a>(out: &'a [Outgoing], publisher: &Publisher, topic: &str) -> Vec<&'a Outgoing> {
    out.iter().filter(|o| publisher.topics()[o.topic].name == topic).collect()
}

fn transforms(out: &[Outgoing], publisher: &Publisher, topic: &str) -> Vec<TransformStamped> {
    on(out, publisher, topic)
        .iter()
        .flat_map(|o| match &o.message {
            Message::Tf(TfMessage { transforms }) => transforms.clone(),
            other => panic!("{topic} carries {other:?}"),
        })
        .collect()
}

fn find<'a>(transforms: &'a [TransformStamped], parent: &str, child: &str) -> &'a TransformStamped {
    transforms
        .iter()
        .find(|t| t.header.frame_id == parent && t.child_frame_id == child)
        .unwrap_or_else(|| panic!("no {parent} -> {child} in {transforms:#?}"))
}

fn isometry(t: &TransformStamped) -> Isometry3<f64> {
    let (v, q) = (&t.transform.translation, &t.transform.rotation);
    Isometry3::from_parts(
        Vector3::new(v.x, v.y, v.z).into(),
        UnitQuaternion::new_normalize(ars_core::nalgebra::Quaternion::new(q.w, q.x, q.y, q.z)),
    )
}

#[test]
fn a_urdf_robots_frames_follow_its_joint_tree_and_free_objects_are_in_map() {
    let mut sim = arm_and_ball();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    let first = publisher.poll(&sim).unwrap();
    let fixed = transforms(&first, &publisher, "/tf_static");
    // The merged tool link is 0.1 m along the upper arm's X, fixed.
    let tool = isometry(find(&fixed, "upper", "tool"));
    assert!((tool.translation.vector - Vector3::new(0.1, 0.0, 0.0)).norm() < 1e-12, "{tool}");
    let description = on(&first, &publisher, "/robot_description");
    assert!(matches!(&description[0].message, Message::String(s) if s.data == ARM));
    sim.run_for(0.3).unwrap();
    let out = publisher.poll(&sim).unwrap();
    let moving = transforms(&out, &publisher, "/tf");
    // The shoulder: 0.5 m up the base's Z, turned about Y by the joint's angle.
    let angle = sim.scene().joint_position(sim.scene().joint("shoulder").unwrap().id()).unwrap();
    assert!(angle.abs() > 0.1, "the arm swung: {angle}");
    let shoulder = isometry(find(&moving, "base", "upper"));
    let expected = Isometry3::new(Vector3::new(0.0, 0.0, 0.5), Vector3::y() * angle);
    // ODE holds the hinge's two anchors together within its constraint error (1.6 µm
    // here, after 0.3 s of swinging): the published frames are the bodies' as they are.
    let gap = (shoulder.translation.vector - expected.translation.vector).norm();
    assert!(gap < 1e-5, "{shoulder} vs {expected}: {gap:e}");
    let turn = shoulder.rotation.to_rotation_matrix().matrix() - expected.rotation.to_rotation_matrix().matrix();
    assert!(turn.norm() < 1e-6, "{shoulder} vs {expected}: {}", turn.norm());
    // The base stands in map as its file says: Z up, at the origin.
    let base = isometry(find(&moving, "map", "base"));
    assert!(base.translation.vector.norm() < 1e-6 && base.rotation.angle() < 1e-6, "{base}");
    // The ball, at ARS (x, y, z), is at (x, −z, y) in map.
    let ball = sim.scene().position(sim.scene().object("sphere").unwrap().id()).unwrap();
    let in_map = isometry(find(&moving, "map", "sphere")).translation.vector;
    assert_eq!(in_map, Vector3::new(ball.x, -ball.z, ball.y));
    assert!(ball.y < 2.0, "it fell");
}

#[test]
fn joint_states_equal_the_joint_sensors_records_of_the_same_run() {
    let mut sim = arm_and_ball();
    let shoulder = sim.scene().joint("shoulder").unwrap().id();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    let period = 1.0 / 50.0;
    let q = sim.add_sensor_every(JointPositions::new(sim.scene(), &[shoulder]).unwrap(), period).unwrap();
    let v = sim.add_sensor_every(JointVelocities::new(sim.scene(), &[shoulder]).unwrap(), period).unwrap();
    let e = sim.add_sensor_every(JointTorque::new(shoulder), period).unwrap();
    let mut out = Vec::new();
    for _ in 0..10 {
        sim.step_frame().unwrap();
        out.extend(publisher.poll(&sim).unwrap());
    }
    let states: Vec<(u64, JointState)> = on(&out, &publisher, "/joint_states")
        .iter()
        .map(|o| match &o.message {
            Message::JointState(s) => (o.stamp, s.clone()),
            other => panic!("{other:?}"),
        })
        .collect();
    let (q, v, e) = (sim.records(q).unwrap(), sim.records(v).unwrap(), sim.records(e).unwrap());
    assert_eq!(states.len(), q.len());
    assert!(states.len() >= 9);
    for (k, (stamp, state)) in states.iter().enumerate() {
        assert_eq!(state.name, ["shoulder"]);
        assert_eq!(*stamp, nanos_of(q.samples()[k].time));
        assert_eq!(state.header.stamp.nanos(), *stamp);
        assert_eq!(state.position, q.samples()[k].record.values);
        assert_eq!(state.velocity, v.samples()[k].record.values);
        assert_eq!(state.effort, [e.samples()[k].record.value]);
    }
    assert!(states.iter().any(|(_, s)| s.effort[0] != 0.0), "the damping put efforts");
}

#[test]
fn laser_scans_equal_the_lidars_records_each_sample_once() {
    let mut sim = Simulation::new().unwrap();
    sim.scene_mut().add_box([1.0, 1.0, 1.0], [3.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().world_mut().set_gravity(Vector3::zeros()).unwrap();
    let lidar = Lidar::new(90, std::f64::consts::PI, 10.0).unwrap().min_range(0.05).unwrap();
    let lidar = sim.add_sensor_every(lidar, 0.01).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    let mut out = publisher.poll(&sim).unwrap();
    for _ in 0..3 {
        sim.step_frame().unwrap();
        out.extend(publisher.poll(&sim).unwrap());
    }
    let scans: Vec<(u64, LaserScan)> = on(&out, &publisher, "/scan")
        .iter()
        .map(|o| match &o.message {
            Message::LaserScan(s) => (o.stamp, s.clone()),
            other => panic!("{other:?}"),
        })
        .collect();
    let records = sim.records(lidar).unwrap();
    assert_eq!(scans.len(), records.len());
    assert_eq!(scans.len(), 6, "every 10 ms over 60 ms");
    let azimuths = sim.sensor(lidar).unwrap().azimuths();
    for ((stamp, scan), sample) in scans.iter().zip(records.samples()) {
        assert_eq!(*stamp, nanos_of(sample.time));
        assert_eq!(scan.header.frame_id, "laser");
        let expected: Vec<f32> = sample.record.ranges.iter().map(|r| *r as f32).collect();
        assert_eq!(scan.ranges, expected);
        assert_eq!((scan.angle_min, scan.angle_max), (azimuths[0] as f32, azimuths[89] as f32));
        assert_eq!((scan.range_min, scan.range_max), (0.05, 10.0));
        assert_eq!(scan.scan_time, 0.01, "the lidar's own period");
    }
    // The beam along ARS's +X (azimuth 0, the middle one) sees the box 2.5 m away.
    assert!((scans[0].1.ranges[45] - 2.5).abs() < 1e-3 || (scans[0].1.ranges[44] - 2.5).abs() < 0.1);
    // Its frame: in map, turned so that ROS's laser axes are ARS's lidar axes turned.
    let fixed = transforms(&out, &publisher, "/tf_static");
    let laser = isometry(find(&fixed, "map", "laser"));
    assert!(laser.rotation.angle() < 1e-12, "a lidar upright at the origin is map's axes: {laser}");
}

#[test]
fn a_vehicles_odometry_is_its_pose_in_odom_and_its_velocity_in_its_own_frame() {
    let mut sim = Simulation::new().unwrap();
    sim.scene_mut().world_mut().set_gravity(Vector3::zeros()).unwrap();
    let chassis = sim.scene_mut().add_box([1.0, 0.2, 0.5], [0.0, 0.3, 0.0], Mass::Total(1.0)).unwrap();
    // Turned 90° about up: its X points along ARS's −Z; moving that way at 2 m/s.
    sim.scene_mut().rotate(chassis, Vector3::y(), std::f64::consts::FRAC_PI_2).unwrap();
    sim.scene_mut().body_mut(chassis).unwrap().set_linear_velocity(Vector3::new(0.0, 0.0, -2.0)).unwrap();
    let options = RosOptions { vehicles: vec![chassis], ..Default::default() };
    let mut publisher = Publisher::attach(&mut sim, &options).unwrap();
    let first = publisher.poll(&sim).unwrap();
    find(&transforms(&first, &publisher, "/tf_static"), "map", "odom");
    sim.step_frame().unwrap();
    let out = publisher.poll(&sim).unwrap();
    find(&transforms(&out, &publisher, "/tf"), "odom", "box");
    let odometry = match &on(&out, &publisher, "/odom")[0].message {
        Message::Odometry(o) => (**o).clone(),
        other => panic!("{other:?}"),
    };
    assert_eq!((odometry.header.frame_id.as_str(), odometry.child_frame_id.as_str()), ("odom", "box"));
    let twist = odometry.twist.twist.linear;
    assert!((twist.x - 2.0).abs() < 1e-9 && twist.y.abs() < 1e-9 && twist.z.abs() < 1e-9, "{twist:?}");
    // ARS's −Z is map's +Y: it drove 2 m/s × 20 ms along +Y, 0.3 m up.
    let p = odometry.pose.pose.position;
    assert!((p.y - 0.04).abs() < 1e-9 && p.x.abs() < 1e-9 && (p.z - 0.3).abs() < 1e-9, "{p:?}");
}

#[test]
fn a_state_rate_out_of_range_is_refused_naming_it() {
    let mut sim = Simulation::new().unwrap();
    let err = Publisher::attach(&mut sim, &RosOptions { state_rate: 0.0, ..Default::default() }).unwrap_err();
    assert!(err.to_string().contains("ROS state rate"), "{err}");
}

#[test]
fn an_imu_on_an_ars_object_reads_z_up_with_its_records_values() {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let crate_ = sim.scene_mut().add_box([0.4, 0.2, 0.4], [0.0, 0.1, 0.0], Mass::Total(1.0)).unwrap();
    let imu = sim.add_sensor_every(ars_core::sensors::Imu::new(crate_), 0.02).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    sim.run_for(0.5).unwrap();
    let out = publisher.poll(&sim).unwrap();
    let readings: Vec<_> = on(&out, &publisher, "/imu")
        .iter()
        .map(|o| match &o.message {
            Message::Imu(m) => m.clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    let records = sim.records(imu).unwrap();
    assert_eq!(readings.len(), records.len());
    for (message, sample) in readings.iter().zip(records.samples()) {
        // ARS's (x, y, z) in the IMU's ROS axes: (x, −z, y).
        let (f, a) = (sample.record.specific_force, &message.linear_acceleration);
        assert_eq!((a.x, a.y, a.z), (f.x, -f.z, f.y));
        let (w, g) = (sample.record.angular_velocity, &message.angular_velocity);
        assert_eq!((g.x, g.y, g.z), (w.x, -w.z, w.y));
        assert_eq!(message.header.frame_id, "imu");
    }
    // At rest on the floor: +9.81 m/s² along its ROS Z, level in map.
    let last = readings.last().unwrap();
    assert!((last.linear_acceleration.z - 9.81).abs() < 1e-3, "{:?}", last.linear_acceleration);
    let q = &last.orientation;
    assert!(q.x.abs() < 1e-6 && q.y.abs() < 1e-6 && q.z.abs() < 1e-6, "{q:?}");
    let first = publisher.poll(&sim).unwrap();
    assert!(on(&first, &publisher, "/tf_static").is_empty(), "sent once");
}

#[test]
fn the_thesis_mobile_manipulator_is_a_vehicle_whose_joints_and_odometry_are_published() {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let spec = ars_programs::VehicleSpec::default();
    let (vehicle, _) = ars_programs::build_mobile_manipulator(&mut sim, &spec, Mass::Total(1.0)).unwrap();
    let options = RosOptions::for_scene(sim.scene());
    assert_eq!(options.vehicles, [vehicle.chassis]);
    let mut publisher = Publisher::attach(&mut sim, &options).unwrap();
    assert_eq!(publisher.topics().iter().filter(|t| t.name == "/odom").count(), 1);
    sim.run_for(0.1).unwrap();
    let out = publisher.poll(&sim).unwrap();
    let state = match &on(&out, &publisher, "/joint_states").last().unwrap().message {
        Message::JointState(s) => s.clone(),
        other => panic!("{other:?}"),
    };
    assert_eq!(state.name, ["r1", "r2", "w1", "w2"], "hinges by name; the caster's ball joint has no position");
    for (name, position) in state.name.iter().zip(&state.position) {
        let id = sim.scene().joint(name.as_str()).unwrap().id();
        assert_eq!(*position, sim.scene().joint_position(id).unwrap(), "{name}");
    }
    let odometry = match &on(&out, &publisher, "/odom")[0].message {
        Message::Odometry(o) => (**o).clone(),
        other => panic!("{other:?}"),
    };
    // Upright, the chassis is a Z-up frame in odom: (nearly) level.
    let q = odometry.pose.pose.orientation;
    assert!(q.x.abs() < 0.05 && q.y.abs() < 0.05, "{q:?}");
}

#[test]
fn frames_follow_the_joint_tree_of_ars_built_and_mjcf_bodies() {
    // The thesis' mobile manipulator: its chassis in odom, the wheels and the caster on
    // the chassis, the arm's links one on the other.
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let spec = ars_programs::VehicleSpec::default();
    ars_programs::build_mobile_manipulator(&mut sim, &spec, Mass::Total(1.0)).unwrap();
    let options = RosOptions::for_scene(sim.scene());
    let mut publisher = Publisher::attach(&mut sim, &options).unwrap();
    sim.run_for(0.2).unwrap();
    let tf = transforms(&publisher.poll(&sim).unwrap(), &publisher, "/tf");
    let parent = |child: &str| tf.iter().find(|t| t.child_frame_id == child).expect(child).header.frame_id.clone();
    assert_eq!(parent("chassis"), "odom");
    for child in ["cylinder", "cylinder/1", "sphere", "capsule"] {
        assert_eq!(parent(child), "chassis", "{child}");
    }
    assert_eq!(parent("capsule/1"), "capsule");
    // The pose on /tf is the child's in its parent's frame, both with ROS axes.
    let scene = sim.scene();
    let pose = |name: &str| scene.pose(scene.object(name).unwrap().id()).unwrap();
    let expected = pose("capsule").inverse() * pose("capsule/1");
    let published = isometry(tf.iter().find(|t| t.child_frame_id == "capsule/1").unwrap());
    let ros_axes = ars_ros::frames::ros_axes();
    let ars_relative = ros_axes * published * ros_axes.inverse();
    assert!((ars_relative.translation.vector - expected.translation.vector).norm() < 1e-12);
    assert!(ars_relative.rotation.angle_to(&expected.rotation) < 1e-9);

    // An MJCF chain: each body in its parent's frame, with the file's own (Z-up) axes.
    let mut sim = Simulation::new().unwrap();
    let chain = r#"<mujoco><worldbody><body name="upper" pos="0 0 1"><joint name="j1" type="hinge" axis="0 1 0"/>
        <geom type="capsule" size="0.05" fromto="0 0 0 0.3 0 0"/>
        <body name="lower" pos="0.3 0 0"><joint name="j2" type="hinge" axis="0 1 0"/>
        <geom type="capsule" size="0.04" fromto="0 0 0 0.3 0 0"/></body></body></worldbody></mujoco>"#;
    sim.load_mjcf_text(chain, "chain.xml", &Default::default()).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    sim.step().unwrap();
    let tf = transforms(&publisher.poll(&sim).unwrap(), &publisher, "/tf");
    let parent = |child: &str| tf.iter().find(|t| t.child_frame_id == child).expect(child).header.frame_id.clone();
    assert_eq!((parent("upper"), parent("lower")), ("map".to_string(), "upper".to_string()));
    let frame = |child: &str| isometry(tf.iter().find(|t| t.child_frame_id == child).expect(child));
    // One 2 ms step from rest: the chain has barely moved.
    let (upper, lower) = (frame("upper"), frame("lower"));
    assert!((upper.translation.vector - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-4, "{upper}");
    assert!(upper.rotation.angle() < 1e-3, "{upper}");
    assert!((lower.translation.vector - Vector3::new(0.3, 0.0, 0.0)).norm() < 1e-4, "{lower}");
}

#[test]
fn a_urdf_vehicles_root_link_is_given_in_odom() {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/thesis_vehicle.urdf");
    sim.load_urdf(file, &UrdfOptions::new()).unwrap();
    let options = RosOptions::for_scene(sim.scene());
    assert_eq!(options.vehicles.len(), 1, "its root link is named chassis");
    let mut publisher = Publisher::attach(&mut sim, &options).unwrap();
    sim.step().unwrap();
    let out = publisher.poll(&sim).unwrap();
    let tf = transforms(&out, &publisher, "/tf");
    find(&tf, "odom", "chassis");
    let fixed = transforms(&out, &publisher, "/tf_static");
    find(&fixed, "map", "odom");
}

#[test]
fn a_depth_cameras_images_are_its_records_with_a_pinhole_calibration() {
    use ars_core::sensors::DepthCamera;
    let mut sim = Simulation::new().unwrap();
    sim.scene_mut().world_mut().set_gravity(Vector3::zeros()).unwrap();
    // A wall 3 m ahead of a camera at the origin looking along ARS's −Z.
    sim.scene_mut().add_box([4.0, 4.0, 1.0], [0.0, 0.0, -3.5], Mass::Total(1.0)).unwrap();
    let camera = sim.add_sensor_every(DepthCamera::new(8, 6, 1.0, 0.1, 10.0).unwrap(), 0.01).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    let mut out = publisher.poll(&sim).unwrap();
    sim.step_frame().unwrap();
    out.extend(publisher.poll(&sim).unwrap());
    let images: Vec<_> = on(&out, &publisher, "/camera/depth/image_raw")
        .iter()
        .map(|o| match &o.message {
            Message::Image(m) => (**m).clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    let infos = on(&out, &publisher, "/camera/depth/camera_info");
    let records = sim.records(camera).unwrap();
    assert_eq!((images.len(), infos.len()), (records.len(), records.len()));
    for (image, sample) in images.iter().zip(records.samples()) {
        assert_eq!((image.encoding.as_str(), image.width, image.height, image.step), ("32FC1", 8, 6, 32));
        let depths: Vec<f32> = image.data.chunks(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
        assert_eq!(depths, sample.record.pixels);
        assert!((depths[3 * 8 + 4] - 3.0).abs() < 1e-5);
    }
    // The optical frame looks along map's −Y (ARS's −Z), its y (down) along map's −Z.
    let fixed = transforms(&out, &publisher, "/tf_static");
    let optical = isometry(find(&fixed, "map", "camera_optical"));
    let forward = optical.rotation * Vector3::z();
    assert!((forward - Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-12, "ARS's −Z is map's +Y: {forward}");
    let down = optical.rotation * Vector3::y();
    assert!((down - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12, "{down}");
    // The centre pixel's ray is the optical axis: cx = 3.5, cy = 2.5, f = 3 / tan(0.5).
    match &infos[0].message {
        Message::CameraInfo(info) => {
            let f = 3.0 / 0.5f64.tan();
            assert_eq!(info.k, [f, 0.0, 3.5, 0.0, f, 2.5, 0.0, 0.0, 1.0]);
            assert_eq!(info.header.frame_id, "camera_optical");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_lasers_readings_are_one_beam_scans_along_its_ray() {
    use ars_core::nalgebra::{Point3, Rotation3};
    use ars_core::sensors::Laser;
    let mut sim = Simulation::new().unwrap();
    sim.scene_mut().world_mut().set_gravity(Vector3::zeros()).unwrap();
    sim.scene_mut().add_sphere(1.0, [5.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    let along_x = Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
    let laser = sim.add_sensor(Laser::new(100.0).at(Point3::origin(), along_x)).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    let mut out = publisher.poll(&sim).unwrap();
    sim.step_n(3).unwrap();
    out.extend(publisher.poll(&sim).unwrap());
    let scans: Vec<LaserScan> = on(&out, &publisher, "/range")
        .iter()
        .map(|o| match &o.message {
            Message::LaserScan(s) => s.clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    let records = sim.records(laser).unwrap();
    assert_eq!(scans.len(), 3);
    for (scan, sample) in scans.iter().zip(records.samples()) {
        assert_eq!(scan.ranges, [sample.record.distance.unwrap() as f32]);
        assert_eq!((scan.angle_min, scan.angle_max, scan.range_max), (0.0, 0.0, 100.0));
    }
    assert!((scans[0].ranges[0] - 4.0).abs() < 1e-6);
    // Its beam (the frame's +X) points along ARS's +X: map's +X.
    let frame = isometry(find(&transforms(&out, &publisher, "/tf_static"), "map", "range"));
    assert!((frame.rotation * Vector3::x() - Vector3::x()).norm() < 1e-12, "{frame}");
}

#[test]
fn a_robot_link_removed_before_publishing_is_left_out() {
    let mut sim = arm_and_ball();
    let upper = sim.scene().object("upper").unwrap().id();
    sim.remove_object(upper).unwrap();
    let mut publisher = Publisher::attach(&mut sim, &RosOptions::default()).unwrap();
    sim.step().unwrap();
    let out = publisher.poll(&sim).unwrap();
    let moving = transforms(&out, &publisher, "/tf");
    find(&moving, "map", "base");
    assert!(moving.iter().all(|t| t.child_frame_id != "upper" && t.child_frame_id != "tool"), "{moving:?}");
}
