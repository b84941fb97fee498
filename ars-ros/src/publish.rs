//! What a simulation publishes: the [`Publisher`] turns a [`Simulation`] at its current
//! time into the ROS 2 messages due, for a live bridge or an MCAP file alike.
//!
//! | topic | type | QoS | when |
//! |---|---|---|---|
//! | `/clock` | `rosgraph_msgs/msg/Clock` | [`Qos::CLOCK`] | every state period |
//! | `/tf` | `tf2_msgs/msg/TFMessage` | [`Qos::TF`] | every state period |
//! | `/tf_static` | `tf2_msgs/msg/TFMessage` | [`Qos::LATCHED`] | once, first |
//! | `/robot_description` | `std_msgs/msg/String` | [`Qos::LATCHED`] | once per URDF robot, first |
//! | `/joint_states` | `sensor_msgs/msg/JointState` | [`Qos::DEFAULT`] | every state period |
//! | `/odom` (`/odom_1`...) | `nav_msgs/msg/Odometry` | [`Qos::DEFAULT`] | every state period, per vehicle |
//! | `/scan` (`/scan_1`...) | `sensor_msgs/msg/LaserScan` | [`Qos::SENSOR_DATA`] | every sample of each [`Lidar`] |
//! | `/range` (`/range_1`...) | `sensor_msgs/msg/LaserScan` (one beam) | [`Qos::SENSOR_DATA`] | every sample of each [`Laser`] |
//! | `/camera/depth/image_raw` (`/camera_1/...`) | `sensor_msgs/msg/Image` (`32FC1`) | [`Qos::SENSOR_DATA`] | every sample of each [`DepthCamera`] |
//! | `/camera/depth/camera_info` (`/camera_1/...`) | `sensor_msgs/msg/CameraInfo` | [`Qos::SENSOR_DATA`] | with each image |
//! | `/imu` (`/imu_1`...) | `sensor_msgs/msg/Imu` | [`Qos::SENSOR_DATA`] | every sample of each [`Imu`] |
//!
//! The state period is [`RosOptions::state_rate`] (50 Hz: an ARS frame of 20 ms).
//! Sensors are published at their own rate: each of their samples once, stamped
//! with its time. Frames are those of [`FrameTree`]; the world is turned Z-up as
//! [`frames`] says.

use ars_core::sensors::{DepthCamera, Imu, Laser, Lidar, SensorSettings};
use ars_core::{ObjectId, SensorId, Simulation};
use nalgebra::{Isometry3, UnitQuaternion};

use crate::camera::CameraTopics;
use crate::error::RosResult;
use crate::frames::{self, ros_axes, world_pose_to_ros};
use crate::joint_states::JointStates;
use crate::msg::{self, Header, Time, nanos_of};
use crate::tf_tree::{FrameTree, ODOM};
use crate::topics::{Message, Outgoing, Qos, Topic};

/// How a simulation is published.
#[derive(Clone, Debug, PartialEq)]
pub struct RosOptions {
    /// How often `/clock`, `/tf`, `/joint_states` and `/odom` are published, per
    /// simulated second (default 50).
    pub state_rate: f64,
    /// The chassis of each vehicle: its odometry goes on `/odom` (the first) and its
    /// frame is given in `odom`.
    pub vehicles: Vec<ObjectId>,
}

impl Default for RosOptions {
    fn default() -> Self {
        RosOptions { state_rate: 50.0, vehicles: Vec::new() }
    }
}

impl RosOptions {
    /// The defaults, with every vehicle ARS builds in `scene` as a vehicle: the objects
    /// named `chassis`, `chassis/1`... (the thesis' vehicles and mobile manipulators,
    /// `ars_programs::build_vehicle`). What the `ars` command, the examples and Python
    /// record with.
    pub fn for_scene(scene: &ars_core::Scene) -> RosOptions {
        let chassis =
            |name: &str| name == "chassis" || name.strip_prefix("chassis/").is_some_and(|n| n.parse::<u32>().is_ok());
        let vehicles = scene.objects().filter(|(name, _)| chassis(name)).map(|(_, id)| id).collect();
        RosOptions { vehicles, ..RosOptions::default() }
    }

    /// Refuses a state rate outside 0.001 to 10⁶ a second, naming it.
    pub fn check(&self) -> RosResult<()> {
        let rate = self.state_rate;
        if !(1e-3..=1e6).contains(&rate) {
            let detail = format!("must be 0.001 to 1e6 messages per simulated second, got {rate}");
            return Err(ars_core::Error::OutOfRange { what: "ROS state rate", detail }.into());
        }
        Ok(())
    }
}

/// A lidar's topic.
#[derive(Debug)]
struct LidarTopic {
    sensor: SensorId<Lidar>,
    topic: usize,
    frame: String,
    sent: usize,
    /// The scan's settings that do not change.
    template: msg::LaserScan,
    beams: usize,
}

/// A laser range finder's topic: a scan of one beam.
#[derive(Debug)]
struct LaserTopic {
    sensor: SensorId<Laser>,
    topic: usize,
    sent: usize,
    template: msg::LaserScan,
}

/// An IMU's topic.
#[derive(Debug)]
struct ImuTopic {
    sensor: SensorId<Imu>,
    topic: usize,
    frame: String,
    sent: usize,
    object: ObjectId,
    /// Its ROS axes in the body's frame (its mount, turned Z-up on an ARS-built object).
    turn: UnitQuaternion<f64>,
    /// Whether its ROS axes are its ARS axes turned ((x, y, z) ↦ (x, −z, y)).
    turned: bool,
}

/// The topics' indices that every publisher has.
const CLOCK: usize = 0;
const TF: usize = 1;
const TF_STATIC: usize = 2;
const ROBOT_DESCRIPTION: usize = 3;
const JOINT_STATES: usize = 4;

/// Turns a simulation into ROS 2 messages (see the [module docs](self)).
#[derive(Debug)]
pub struct Publisher {
    topics: Vec<Topic>,
    tree: FrameTree,
    joint_states: SensorId<JointStates>,
    joint_states_sent: usize,
    lidars: Vec<LidarTopic>,
    imus: Vec<ImuTopic>,
    lasers: Vec<LaserTopic>,
    cameras: Vec<CameraTopics>,
    /// (chassis, topic) of each vehicle.
    vehicles: Vec<(ObjectId, usize)>,
    period: f64,
    next_state: f64,
    /// The time of the last state published, ns.
    last_state: Option<u64>,
    started: bool,
}

impl Publisher {
    /// Publishes `sim` from now on: its frames, joints, vehicles and the lidars and
    /// IMUs it has now. Adds a sensor to it that reads the joints' states (and the
    /// efforts of each step, which only a sensor sees) at the state rate.
    pub fn attach(sim: &mut Simulation, options: &RosOptions) -> RosResult<Publisher> {
        options.check()?;
        let period = 1.0 / options.state_rate;
        let mut tree = FrameTree::of(sim.scene(), &options.vehicles)?;
        let joint_states = sim.add_sensor_every(JointStates::of(sim.scene()), period)?;
        let mut topics = vec![
            Topic::of::<msg::Clock>("/clock", Qos::CLOCK),
            Topic::of::<msg::TfMessage>("/tf", Qos::TF),
            Topic::of::<msg::TfMessage>("/tf_static", Qos::LATCHED),
            Topic::of::<msg::StringMessage>("/robot_description", Qos::LATCHED),
            Topic::of::<msg::JointState>("/joint_states", Qos::DEFAULT),
        ];
        let numbered = |base: &str, k: usize| if k == 0 { base.to_string() } else { format!("{base}_{k}") };
        let mut vehicles = Vec::new();
        for (k, chassis) in options.vehicles.iter().enumerate() {
            vehicles.push((*chassis, topics.len()));
            topics.push(Topic::of::<msg::Odometry>(&numbered("/odom", k), Qos::DEFAULT));
        }
        let mut lidars = Vec::new();
        for (k, id) in sim.sensor_ids_of::<Lidar>().into_iter().enumerate() {
            let (frame, topic) = (numbered("laser", k), topics.len());
            topics.push(Topic::of::<msg::LaserScan>(&numbered("/scan", k), Qos::SENSOR_DATA));
            lidars.push(lidar_topic(sim, id, frame, topic, &mut tree)?);
        }
        let mut imus = Vec::new();
        for (k, id) in sim.sensor_ids_of::<Imu>().into_iter().enumerate() {
            let (frame, topic) = (numbered("imu", k), topics.len());
            topics.push(Topic::of::<msg::Imu>(&numbered("/imu", k), Qos::SENSOR_DATA));
            imus.push(imu_topic(sim, id, frame, topic, &mut tree)?);
        }
        let mut lasers = Vec::new();
        for (k, id) in sim.sensor_ids_of::<Laser>().into_iter().enumerate() {
            let (frame, topic) = (numbered("range", k), topics.len());
            topics.push(Topic::of::<msg::LaserScan>(&numbered("/range", k), Qos::SENSOR_DATA));
            lasers.push(laser_topic(sim, id, frame, topic, &mut tree)?);
        }
        let mut cameras = Vec::new();
        for (k, id) in sim.sensor_ids_of::<DepthCamera>().into_iter().enumerate() {
            let (name, topic) = (numbered("camera", k), topics.len());
            topics.push(Topic::of::<msg::Image>(&format!("/{name}/depth/image_raw"), Qos::SENSOR_DATA));
            topics.push(Topic::of::<msg::CameraInfo>(&format!("/{name}/depth/camera_info"), Qos::SENSOR_DATA));
            cameras.push(CameraTopics::new(sim, id, format!("{name}_optical"), topic, &mut tree)?);
        }
        let next_state = sim.scene().time();
        Ok(Publisher {
            topics,
            tree,
            joint_states,
            joint_states_sent: 0,
            lidars,
            imus,
            lasers,
            cameras,
            vehicles,
            period,
            next_state,
            last_state: None,
            started: false,
        })
    }

    /// The topics, in the order [`Outgoing::topic`] indexes them.
    pub fn topics(&self) -> &[Topic] {
        &self.topics
    }

    /// The frame tree.
    pub fn frame_tree(&self) -> &FrameTree {
        &self.tree
    }

    /// The id of the sensor behind `/joint_states`.
    pub fn joint_states_sensor(&self) -> SensorId<JointStates> {
        self.joint_states
    }

    /// Whether the state (`/clock`, `/tf`, `/odom`) is due now: a caller that polls
    /// only then, and at the end of each frame, loses nothing (the sensors' samples
    /// wait in their records) and spares a poll at every step.
    pub fn state_due(&self, sim: &Simulation) -> bool {
        !self.started || sim.scene().time() + 0.5 * sim.scene().time_step() >= self.next_state
    }

    /// The messages due since the last call (the first call: also `/tf_static` and
    /// `/robot_description`), oldest first within each topic. Call it after every step
    /// (or every frame: the sensors' samples are all there, each stamped with its own
    /// time; the state is as it is now).
    pub fn poll(&mut self, sim: &Simulation) -> RosResult<Vec<Outgoing>> {
        let mut out = Vec::new();
        let now = sim.scene().time();
        if !self.started {
            self.started = true;
            self.push_latched(sim, &mut out);
        }
        if self.state_due(sim) {
            while self.next_state <= now + 0.5 * sim.scene().time_step() {
                self.next_state += self.period;
            }
            self.push_state(sim, &mut out)?;
        }
        self.push_joint_states(sim, &mut out)?;
        for lidar in &mut self.lidars {
            push_scans(sim, lidar, &mut out)?;
        }
        for imu in &mut self.imus {
            push_imu(sim, imu, &mut out)?;
        }
        for laser in &mut self.lasers {
            push_range(sim, laser, &mut out)?;
        }
        for camera in &mut self.cameras {
            camera.push(sim, &mut out)?;
        }
        Ok(out)
    }

    /// [`poll`](Self::poll), and the state now if it is not on the state period's grid:
    /// `/clock`, `/tf` and `/odom` as they are, and `/joint_states` with the joints'
    /// positions and velocities now and no efforts (a step's efforts are seen only by
    /// the sensor, at the state period). What a lock-step bridge sends after each
    /// `StepSimulation`, so that a client sees where its steps ended.
    pub fn poll_with_state_now(&mut self, sim: &Simulation) -> RosResult<Vec<Outgoing>> {
        let mut out = self.poll(sim)?;
        let stamp = nanos_of(sim.scene().time());
        if self.last_state != Some(stamp) {
            self.push_state(sim, &mut out)?;
            let sensor = sim.sensor(self.joint_states)?;
            let name = sensor.names().to_vec();
            let mut state = msg::JointState { header: header(stamp, ""), name, ..Default::default() };
            for id in sensor.joint_ids() {
                let joint = sim.scene().joint_state(*id)?;
                state.position.push(joint.position);
                state.velocity.push(joint.rate);
            }
            out.push(Outgoing { topic: JOINT_STATES, stamp, message: Message::JointState(state) });
        }
        Ok(out)
    }

    /// Starts over after the simulation was put back (a [`Simulation::restore`], which
    /// clears the records): the next poll sends `/tf_static` and `/robot_description`
    /// again, then the state from the simulation's time on its grid.
    pub fn restart(&mut self, sim: &Simulation) {
        self.joint_states_sent = 0;
        self.lidars.iter_mut().for_each(|t| t.sent = 0);
        self.imus.iter_mut().for_each(|t| t.sent = 0);
        self.lasers.iter_mut().for_each(|t| t.sent = 0);
        self.cameras.iter_mut().for_each(CameraTopics::restart);
        self.next_state = sim.scene().time();
        self.last_state = None;
        self.started = false;
    }

    /// `/tf_static` and `/robot_description`.
    fn push_latched(&self, sim: &Simulation, out: &mut Vec<Outgoing>) {
        let stamp = nanos_of(sim.scene().time());
        let transforms = self.tree.fixed().iter().map(|(p, c, pose)| transform(stamp, p, c, pose)).collect();
        out.push(Outgoing { topic: TF_STATIC, stamp, message: Message::Tf(msg::TfMessage { transforms }) });
        for urdf in sim.scene().robot_descriptions().iter().filter_map(|r| r.urdf.as_ref()) {
            let text = msg::StringMessage { data: urdf.to_string() };
            out.push(Outgoing { topic: ROBOT_DESCRIPTION, stamp, message: Message::String(text) });
        }
    }

    /// `/clock`, `/tf` and `/odom` now.
    fn push_state(&mut self, sim: &Simulation, out: &mut Vec<Outgoing>) -> RosResult<()> {
        let stamp = nanos_of(sim.scene().time());
        self.last_state = Some(stamp);
        out.push(Outgoing {
            topic: CLOCK,
            stamp,
            message: Message::Clock(msg::Clock { clock: Time::from_nanos(stamp) }),
        });
        let transforms = self.tree.moving(sim.scene()).map(|(p, c, pose)| transform(stamp, p, c, &pose)).collect();
        out.push(Outgoing { topic: TF, stamp, message: Message::Tf(msg::TfMessage { transforms }) });
        for (chassis, topic) in &self.vehicles {
            if let Some(odometry) = self.odometry(sim, *chassis, stamp)? {
                out.push(Outgoing { topic: *topic, stamp, message: Message::Odometry(Box::new(odometry)) });
            }
        }
        Ok(())
    }

    /// A vehicle's odometry: its frame's pose in `odom` (exact: `odom` is `map`), its
    /// velocities in its own frame; `None` once it is removed.
    fn odometry(&self, sim: &Simulation, chassis: ObjectId, stamp: u64) -> RosResult<Option<msg::Odometry>> {
        let (Some((frame, on_object)), Ok(body)) = (self.tree.object_frame(chassis), sim.scene().body(chassis)) else {
            return Ok(None);
        };
        let pose = body.pose() * on_object;
        let point = pose.translation.vector.into();
        let (linear, angular) = (body.point_velocity(point), body.angular_velocity());
        let to_frame = pose.rotation.inverse();
        let mut odometry =
            msg::Odometry { header: header(stamp, ODOM), child_frame_id: frame.clone(), ..Default::default() };
        odometry.pose.pose = frames::pose(&world_pose_to_ros(&pose));
        odometry.twist.twist.linear = frames::vector(&(to_frame * linear));
        odometry.twist.twist.angular = frames::vector(&(to_frame * angular));
        Ok(Some(odometry))
    }

    /// Every `/joint_states` sample since the last call.
    fn push_joint_states(&mut self, sim: &Simulation, out: &mut Vec<Outgoing>) -> RosResult<()> {
        let log = sim.records(self.joint_states)?;
        for sample in log.samples().iter().skip(self.joint_states_sent) {
            let stamp = nanos_of(sample.time);
            let r = &sample.record;
            let state = msg::JointState {
                header: header(stamp, ""),
                name: r.names.to_vec(),
                position: r.position.clone(),
                velocity: r.velocity.clone(),
                effort: r.effort.clone(),
            };
            out.push(Outgoing { topic: JOINT_STATES, stamp, message: Message::JointState(state) });
        }
        self.joint_states_sent = log.len();
        Ok(())
    }
}

/// A lidar's topic and frame (its mount, turned to ROS's laser axes).
fn lidar_topic(
    sim: &Simulation,
    sensor: SensorId<Lidar>,
    frame: String,
    topic: usize,
    tree: &mut FrameTree,
) -> RosResult<LidarTopic> {
    let lidar = sim.sensor(sensor)?;
    let azimuths = lidar.azimuths();
    let Some(SensorSettings::Lidar { min_range, max_range, pose, .. }) = ars_core::sensors::Sensor::settings(lidar)
    else {
        unreachable!("a lidar has its settings");
    };
    let object = ars_core::sensors::Sensor::objects(lidar).first().copied();
    tree.add_sensor(&frame, object, pose, ros_axes());
    let increment = if azimuths.len() > 1 { azimuths[1] - azimuths[0] } else { 0.0 };
    let template = msg::LaserScan {
        header: header(0, &frame),
        angle_min: azimuths[0] as f32,
        angle_max: azimuths[azimuths.len() - 1] as f32,
        angle_increment: increment as f32,
        time_increment: 0.0,
        // The time between two scans: the lidar's sampling period.
        scan_time: sim.sensor_period(sensor)?.unwrap_or(sim.scene().time_step()) as f32,
        range_min: min_range as f32,
        range_max: max_range as f32,
        ranges: Vec::new(),
        intensities: Vec::new(),
    };
    Ok(LidarTopic { sensor, topic, frame, sent: 0, template, beams: azimuths.len() })
}

/// Every scan of a lidar since the last call: its first plane (a `LaserScan` is planar).
fn push_scans(sim: &Simulation, lidar: &mut LidarTopic, out: &mut Vec<Outgoing>) -> RosResult<()> {
    let log = sim.records(lidar.sensor)?;
    for sample in log.samples().iter().skip(lidar.sent) {
        let stamp = nanos_of(sample.time);
        let mut scan = lidar.template.clone();
        scan.header = header(stamp, &lidar.frame);
        scan.ranges = sample.record.ranges.iter().take(lidar.beams).map(|r| *r as f32).collect();
        out.push(Outgoing { topic: lidar.topic, stamp, message: Message::LaserScan(scan) });
    }
    lidar.sent = log.len();
    Ok(())
}

/// A laser's topic and frame: its ray's, turned so that ROS's beam (+X) is ARS's (+Z).
fn laser_topic(
    sim: &Simulation,
    sensor: SensorId<Laser>,
    frame: String,
    topic: usize,
    tree: &mut FrameTree,
) -> RosResult<LaserTopic> {
    let laser = sim.sensor(sensor)?;
    let ray = laser.ray().expect("a laser added to a simulation has its ray");
    let ray_pose = sim.scene().world().geom(ray)?.pose();
    let object = ars_core::sensors::Sensor::objects(laser).first().copied();
    let offset = match object {
        Some(o) => sim.scene().pose(o)?.inverse() * ray_pose,
        None => ray_pose,
    };
    let beam_along_x = Isometry3::rotation(nalgebra::Vector3::y() * -std::f64::consts::FRAC_PI_2);
    tree.add_sensor(&frame, object, offset, beam_along_x);
    let template = msg::LaserScan {
        header: header(0, &frame),
        range_max: laser.max_distance() as f32,
        ranges: Vec::new(),
        ..Default::default()
    };
    Ok(LaserTopic { sensor, topic, sent: 0, template })
}

/// Every reading of a laser since the last call, as a scan of one beam (+∞: no hit).
fn push_range(sim: &Simulation, laser: &mut LaserTopic, out: &mut Vec<Outgoing>) -> RosResult<()> {
    let log = sim.records(laser.sensor)?;
    for sample in log.samples().iter().skip(laser.sent) {
        let stamp = nanos_of(sample.time);
        let mut scan = laser.template.clone();
        scan.header.stamp = Time::from_nanos(stamp);
        scan.ranges = vec![sample.record.distance.map_or(f32::INFINITY, |d| d as f32)];
        out.push(Outgoing { topic: laser.topic, stamp, message: Message::LaserScan(scan) });
    }
    laser.sent = log.len();
    Ok(())
}

/// An IMU's topic and frame (its object's frame, turned by its mount, with ROS axes on
/// an ARS-built object: see [`frames`]).
fn imu_topic(
    sim: &Simulation,
    sensor: SensorId<Imu>,
    frame: String,
    topic: usize,
    tree: &mut FrameTree,
) -> RosResult<ImuTopic> {
    let imu = sim.sensor(sensor)?;
    let offset = match ars_core::sensors::Sensor::settings(imu) {
        Some(SensorSettings::Offset { pose }) => pose,
        _ => Isometry3::identity(),
    };
    let object = ars_core::sensors::Sensor::objects(imu)[0];
    let axes = if tree.is_ars_built(object) { ros_axes() } else { Isometry3::identity() };
    tree.add_sensor(&frame, Some(object), offset, axes);
    let turned = tree.is_ars_built(object);
    Ok(ImuTopic { sensor, topic, frame, sent: 0, object, turn: offset.rotation * axes.rotation, turned })
}

/// Every reading of an IMU since the last call, with its orientation in `map` now.
fn push_imu(sim: &Simulation, imu: &mut ImuTopic, out: &mut Vec<Outgoing>) -> RosResult<()> {
    let log = sim.records(imu.sensor)?;
    let orientation = sim.scene().body(imu.object).map(|b| frames::ars_to_ros() * b.quaternion() * imu.turn);
    // The same swap as the world's, exact.
    let in_axes = |v| if imu.turned { frames::world_vector_to_ros(&v) } else { v };
    for sample in log.samples().iter().skip(imu.sent) {
        let stamp = nanos_of(sample.time);
        let mut message = msg::Imu {
            header: header(stamp, &imu.frame),
            angular_velocity: frames::vector(&in_axes(sample.record.angular_velocity)),
            linear_acceleration: frames::vector(&in_axes(sample.record.specific_force)),
            ..Default::default()
        };
        match &orientation {
            Ok(q) => message.orientation = frames::quaternion(q),
            Err(_) => message.orientation_covariance[0] = -1.0,
        }
        out.push(Outgoing { topic: imu.topic, stamp, message: Message::Imu(message) });
    }
    imu.sent = log.len();
    Ok(())
}

/// A header at `stamp` ns in `frame`.
fn header(stamp: u64, frame: &str) -> Header {
    Header { stamp: Time::from_nanos(stamp), frame_id: frame.to_string() }
}

/// A transform message.
fn transform(stamp: u64, parent: &str, child: &str, pose: &Isometry3<f64>) -> msg::TransformStamped {
    msg::TransformStamped {
        header: header(stamp, parent),
        child_frame_id: child.to_string(),
        transform: frames::transform(pose),
    }
}
