//! The standard ROS 2 messages ARS publishes, as plain Rust structs with ROS's field
//! names and types, each knowing its ROS name and its `ros2msg` schema; and their CDR
//! encoding (what DDS and MCAP's `cdr` message encoding carry).
//!
//! Field types follow the ROS IDL mapping: `float64` is `f64`, `float32` `f32`,
//! `string` `String`, `T[]` `Vec<T>`, `T[N]` `[T; N]` (the 36-element covariances are
//! [`Covariance6`]).

mod builtin;
mod cdr;
mod definitions;
mod geometry;
mod sensor;

pub use builtin::{Clock, Header, StringMessage, Time, nanos_of};
pub use cdr::{CDR_LE_HEADER, decode, encode};
pub use definitions::schema;
pub use geometry::{
    Covariance6, Odometry, Point, Pose, PoseWithCovariance, Quaternion, TfMessage, Transform, TransformStamped, Twist,
    TwistWithCovariance, Vector3,
};
pub use sensor::{CameraInfo, Image, Imu, JointState, LaserScan, RegionOfInterest};

/// A ROS 2 message type: its name and schema.
pub trait RosMessage: serde::Serialize {
    /// Its full ROS name, as a channel's schema and a DDS type name give it
    /// (`"sensor_msgs/msg/JointState"`).
    const TYPE_NAME: &'static str;

    /// Its `ros2msg` schema: its definition, then each type it uses (see [`schema`]).
    fn schema() -> String {
        schema(Self::TYPE_NAME).expect("every message type of this module has a definition")
    }
}

macro_rules! ros_message {
    ($($ty:ty => $name:literal),* $(,)?) => {
        $(impl RosMessage for $ty {
            const TYPE_NAME: &'static str = $name;
        })*
    };
}

ros_message! {
    Time => "builtin_interfaces/msg/Time",
    Header => "std_msgs/msg/Header",
    StringMessage => "std_msgs/msg/String",
    Clock => "rosgraph_msgs/msg/Clock",
    Vector3 => "geometry_msgs/msg/Vector3",
    Quaternion => "geometry_msgs/msg/Quaternion",
    Point => "geometry_msgs/msg/Point",
    Pose => "geometry_msgs/msg/Pose",
    Twist => "geometry_msgs/msg/Twist",
    Transform => "geometry_msgs/msg/Transform",
    TransformStamped => "geometry_msgs/msg/TransformStamped",
    PoseWithCovariance => "geometry_msgs/msg/PoseWithCovariance",
    TwistWithCovariance => "geometry_msgs/msg/TwistWithCovariance",
    TfMessage => "tf2_msgs/msg/TFMessage",
    JointState => "sensor_msgs/msg/JointState",
    LaserScan => "sensor_msgs/msg/LaserScan",
    Imu => "sensor_msgs/msg/Imu",
    Image => "sensor_msgs/msg/Image",
    CameraInfo => "sensor_msgs/msg/CameraInfo",
    RegionOfInterest => "sensor_msgs/msg/RegionOfInterest",
    Odometry => "nav_msgs/msg/Odometry",
}
