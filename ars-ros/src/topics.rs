//! The topics ARS publishes: names, message types and QoS, and the messages of one
//! moment ([`Outgoing`]) that go to a topic, live or into an MCAP file alike.

use crate::error::RosResult;
use crate::msg::{self, RosMessage};

/// Whether every sample must arrive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reliability {
    /// Resent until received.
    Reliable,
    /// Sent once (sensor data: a late sample is worth nothing).
    BestEffort,
}

/// Whether a subscriber that joins late gets what was sent before.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Durability {
    /// Only what is sent after it joined.
    Volatile,
    /// The last `depth` samples too (`/tf_static`, `/robot_description`: sent once).
    TransientLocal,
}

/// A topic's quality of service, as ROS 2's presets give it (history: keep last
/// `depth`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Qos {
    /// Reliability.
    pub reliability: Reliability,
    /// Durability.
    pub durability: Durability,
    /// How many samples are kept.
    pub depth: u32,
}

impl Qos {
    /// rclcpp's `SensorDataQoS`: best effort, volatile, 5 (`/scan`, `/imu`).
    pub const SENSOR_DATA: Qos =
        Qos { reliability: Reliability::BestEffort, durability: Durability::Volatile, depth: 5 };
    /// rclcpp's `ClockQoS`: best effort, volatile, 1 (`/clock`).
    pub const CLOCK: Qos = Qos { reliability: Reliability::BestEffort, durability: Durability::Volatile, depth: 1 };
    /// The default: reliable, volatile, 10 (`/joint_states`, `/odom`).
    pub const DEFAULT: Qos = Qos { reliability: Reliability::Reliable, durability: Durability::Volatile, depth: 10 };
    /// tf2's `DynamicBroadcasterQoS`: reliable, volatile, 100 (`/tf`).
    pub const TF: Qos = Qos { reliability: Reliability::Reliable, durability: Durability::Volatile, depth: 100 };
    /// tf2's `StaticBroadcasterQoS` and robot_state_publisher's description: reliable,
    /// transient local, 1 (`/tf_static`, `/robot_description`).
    pub const LATCHED: Qos =
        Qos { reliability: Reliability::Reliable, durability: Durability::TransientLocal, depth: 1 };

    /// The profile as `ros2 bag` writes it in a channel's `offered_qos_profiles`
    /// (rmw's numbers: history 1 keep last, reliability 1 reliable / 2 best effort,
    /// durability 1 transient local / 2 volatile; no deadline, lifespan or lease).
    pub fn rosbag_yaml(&self) -> String {
        let reliability = match self.reliability {
            Reliability::Reliable => 1,
            Reliability::BestEffort => 2,
        };
        let durability = match self.durability {
            Durability::TransientLocal => 1,
            Durability::Volatile => 2,
        };
        let infinite = "\n    sec: 2147483647\n    nsec: 4294967295";
        format!(
            "- history: 1\n  depth: {}\n  reliability: {reliability}\n  durability: {durability}\n  deadline:{infinite}\n  \
             lifespan:{infinite}\n  liveliness: 1\n  liveliness_lease_duration:{infinite}\n  \
             avoid_ros_namespace_conventions: false",
            self.depth
        )
    }
}

/// A topic: its name, its message type and its QoS.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Topic {
    /// Its name (`"/joint_states"`).
    pub name: String,
    /// Its message type (`"sensor_msgs/msg/JointState"`).
    pub type_name: &'static str,
    /// Its QoS.
    pub qos: Qos,
}

impl Topic {
    /// The topic `name` of messages `M`.
    pub fn of<M: RosMessage>(name: &str, qos: Qos) -> Topic {
        Topic { name: name.to_string(), type_name: M::TYPE_NAME, qos }
    }
}

/// A message of one of the types ARS publishes.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Message {
    /// `/clock`.
    Clock(msg::Clock),
    /// `/tf` or `/tf_static`.
    Tf(msg::TfMessage),
    /// `/joint_states`.
    JointState(msg::JointState),
    /// `/odom`.
    Odometry(Box<msg::Odometry>),
    /// A lidar's scan.
    LaserScan(msg::LaserScan),
    /// An IMU's reading.
    Imu(msg::Imu),
    /// A depth camera's image.
    Image(Box<msg::Image>),
    /// A depth camera's calibration.
    CameraInfo(Box<msg::CameraInfo>),
    /// `/robot_description`.
    String(msg::StringMessage),
}

impl Message {
    /// Its type's ROS name.
    pub fn type_name(&self) -> &'static str {
        match self {
            Message::Clock(_) => msg::Clock::TYPE_NAME,
            Message::Tf(_) => msg::TfMessage::TYPE_NAME,
            Message::JointState(_) => msg::JointState::TYPE_NAME,
            Message::Odometry(_) => msg::Odometry::TYPE_NAME,
            Message::LaserScan(_) => msg::LaserScan::TYPE_NAME,
            Message::Imu(_) => msg::Imu::TYPE_NAME,
            Message::Image(_) => msg::Image::TYPE_NAME,
            Message::CameraInfo(_) => msg::CameraInfo::TYPE_NAME,
            Message::String(_) => msg::StringMessage::TYPE_NAME,
        }
    }

    /// Its CDR bytes, encapsulation header first.
    pub fn encode(&self) -> RosResult<Vec<u8>> {
        msg::encode(self)
    }
}

/// Serialised as the message it holds (what a DDS writer of its topic sends).
impl serde::Serialize for Message {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Message::Clock(m) => m.serialize(serializer),
            Message::Tf(m) => m.serialize(serializer),
            Message::JointState(m) => m.serialize(serializer),
            Message::Odometry(m) => m.serialize(serializer),
            Message::LaserScan(m) => m.serialize(serializer),
            Message::Imu(m) => m.serialize(serializer),
            Message::Image(m) => m.serialize(serializer),
            Message::CameraInfo(m) => m.serialize(serializer),
            Message::String(m) => m.serialize(serializer),
        }
    }
}

/// A message due on a topic, stamped with the simulated time it is of.
#[derive(Clone, Debug, PartialEq)]
pub struct Outgoing {
    /// The topic's index in [`Publisher::topics`](crate::Publisher::topics).
    pub topic: usize,
    /// Simulated time, ns.
    pub stamp: u64,
    /// The message.
    pub message: Message,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_latched_profile_is_written_as_ros2_bag_writes_it() {
        let yaml = Qos::LATCHED.rosbag_yaml();
        assert!(yaml.starts_with("- history: 1\n  depth: 1\n  reliability: 1\n  durability: 1\n"), "{yaml}");
        assert!(Qos::SENSOR_DATA.rosbag_yaml().contains("reliability: 2\n  durability: 2"));
        assert!(yaml.ends_with("avoid_ros_namespace_conventions: false"));
    }
}
