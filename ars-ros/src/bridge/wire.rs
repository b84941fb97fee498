//! The ROS 2 messages the bridge sends and takes: [`msg`](crate::msg)'s (the same ones
//! MCAP recordings hold), and the joint commands' `Float64MultiArray`, which only the
//! bridge takes; each a ros2-client [`Message`] with its ROS type name.

use ros2_client::{Message, MessageTypeName};
use serde::{Deserialize, Serialize};

pub use crate::msg::{
    CameraInfo, Clock, Image, Imu, JointState, LaserScan, Odometry, StringMessage, TfMessage, Time, Twist,
};

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

// What the bridge takes, and what it sends (for other ros2-client nodes to take).
impl Message for JointState {}
impl Message for Twist {}
impl Message for Float64MultiArray {}
impl Message for Clock {}
impl Message for TfMessage {}
impl Message for Odometry {}
impl Message for LaserScan {}
impl Message for Imu {}
impl Message for Image {}
impl Message for CameraInfo {}
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
    /// `geometry_msgs/Twist`.
    pub fn twist() -> MessageTypeName {
        MessageTypeName::new("geometry_msgs", "Twist")
    }
    /// `std_msgs/Float64MultiArray`.
    pub fn float64_multi_array() -> MessageTypeName {
        MessageTypeName::new("std_msgs", "Float64MultiArray")
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
