//! The ROS 2 messages the bridge sends and takes, as plain serde structs with the ROS
//! field names and order (CDR encodes them field by field, so the order is the wire
//! layout). Only what the bridge needs; each says its ROS type.

use ros2_client::{Message, MessageTypeName};
use serde::{Deserialize, Serialize};

/// `builtin_interfaces/Time`: seconds and nanoseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Time {
    /// Whole seconds.
    pub sec: i32,
    /// Nanoseconds, 0 ≤ nanosec < 10⁹.
    pub nanosec: u32,
}

impl Time {
    /// A simulated time in seconds, to the nearest nanosecond (saturating past
    /// `i32::MAX` seconds, about 68 years; a negative or NaN time is 0).
    pub fn from_seconds(seconds: f64) -> Time {
        let nanos = (seconds * 1e9).round();
        if nanos.is_nan() || nanos <= 0.0 {
            return Time::default();
        }
        let nanos = nanos.min(i32::MAX as f64 * 1e9) as u64;
        Time { sec: (nanos / 1_000_000_000) as i32, nanosec: (nanos % 1_000_000_000) as u32 }
    }
}

/// `std_msgs/Header`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// When the data was taken (simulated time).
    pub stamp: Time,
    /// The frame the data is in.
    pub frame_id: String,
}

/// `rosgraph_msgs/Clock`: the simulated time on `/clock`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Clock {
    /// The simulated time.
    pub clock: Time,
}

/// `sensor_msgs/JointState`: named joints' positions, velocities and efforts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    /// Stamp (simulated time); no frame.
    pub header: Header,
    /// Joint names.
    pub name: Vec<String>,
    /// rad or m, one per name (or empty).
    pub position: Vec<f64>,
    /// rad/s or m/s, one per name (or empty).
    pub velocity: Vec<f64>,
    /// N·m or N, one per name (or empty).
    pub effort: Vec<f64>,
}

/// `geometry_msgs/Vector3`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Vector3 {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/Quaternion` (x, y, z, w on the wire).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// i.
    pub x: f64,
    /// j.
    pub y: f64,
    /// k.
    pub z: f64,
    /// The real part.
    pub w: f64,
}

/// `geometry_msgs/Transform`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Transform {
    /// m.
    pub translation: Vector3,
    /// A unit quaternion.
    pub rotation: Quaternion,
}

/// `geometry_msgs/TransformStamped`: `child_frame_id`'s pose in `header.frame_id`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransformStamped {
    /// Stamp and parent frame.
    pub header: Header,
    /// The frame placed.
    pub child_frame_id: String,
    /// Its pose in the parent frame.
    pub transform: Transform,
}

/// `tf2_msgs/TFMessage`: what `/tf` and `/tf_static` carry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TfMessage {
    /// The transforms.
    pub transforms: Vec<TransformStamped>,
}

/// `geometry_msgs/Twist`: what `/cmd_vel` carries.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// m/s (x forward).
    pub linear: Vector3,
    /// rad/s (z: turning left).
    pub angular: Vector3,
}

/// `std_msgs/MultiArrayDimension`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MultiArrayDimension {
    /// The dimension's name.
    pub label: String,
    /// Its size.
    pub size: u32,
    /// Its stride.
    pub stride: u32,
}

/// `std_msgs/MultiArrayLayout`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MultiArrayLayout {
    /// The dimensions (empty for a flat array).
    pub dim: Vec<MultiArrayDimension>,
    /// Padding at the start of the data.
    pub data_offset: u32,
}

/// `std_msgs/Float64MultiArray`: what ros2_control's forward command controllers take.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Float64MultiArray {
    /// Layout (ignored by the forward controllers, and by the bridge).
    pub layout: MultiArrayLayout,
    /// One value per joint of the controller, in its order.
    pub data: Vec<f64>,
}

/// `std_msgs/String`: what `/robot_description` carries.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StringMessage {
    /// The text.
    pub data: String,
}

impl Message for Clock {}
impl Message for JointState {}
impl Message for TfMessage {}
impl Message for Twist {}
impl Message for Float64MultiArray {}
impl Message for StringMessage {}

/// The ROS type names of the messages (`package/Name`), for the DDS topics.
pub mod type_names {
    use super::MessageTypeName;

    /// `rosgraph_msgs/Clock`.
    pub fn clock() -> MessageTypeName {
        MessageTypeName::new("rosgraph_msgs", "Clock")
    }
    /// `sensor_msgs/JointState`.
    pub fn joint_state() -> MessageTypeName {
        MessageTypeName::new("sensor_msgs", "JointState")
    }
    /// `tf2_msgs/TFMessage`.
    pub fn tf() -> MessageTypeName {
        MessageTypeName::new("tf2_msgs", "TFMessage")
    }
    /// `geometry_msgs/Twist`.
    pub fn twist() -> MessageTypeName {
        MessageTypeName::new("geometry_msgs", "Twist")
    }
    /// `std_msgs/Float64MultiArray`.
    pub fn float64_multi_array() -> MessageTypeName {
        MessageTypeName::new("std_msgs", "Float64MultiArray")
    }
    /// `std_msgs/String`.
    pub fn string() -> MessageTypeName {
        MessageTypeName::new("std_msgs", "String")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simulated_seconds_become_a_stamp_to_the_nanosecond() {
        assert_eq!(Time::from_seconds(2.0004), Time { sec: 2, nanosec: 400_000 });
        assert_eq!(Time::from_seconds(0.0), Time::default());
        assert_eq!(Time::from_seconds(f64::NAN), Time::default());
        assert_eq!(Time::from_seconds(-1.0), Time::default());
        assert_eq!(Time::from_seconds(1e30).sec, i32::MAX);
    }
}
