//! sensor_msgs.

use serde::{Deserialize, Serialize};

use super::builtin::Header;
use super::geometry::{Quaternion, Vector3};

/// `sensor_msgs/msg/JointState`: joints by name, with position (rad or m), velocity
/// (rad/s or m/s) and effort (N·m or N), each list in the order of `name`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    /// Stamp (the frame is unused).
    pub header: Header,
    /// Joint names.
    pub name: Vec<String>,
    /// Positions.
    pub position: Vec<f64>,
    /// Velocities.
    pub velocity: Vec<f64>,
    /// Efforts.
    pub effort: Vec<f64>,
}

/// `sensor_msgs/msg/LaserScan`: one planar scan, beam `i` at angle
/// `angle_min + i · angle_increment` about the frame's Z axis from its X axis.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    /// Stamp (of the first beam) and the laser's frame.
    pub header: Header,
    /// Angle of the first beam, rad.
    pub angle_min: f32,
    /// Angle of the last beam, rad.
    pub angle_max: f32,
    /// Angle between beams, rad.
    pub angle_increment: f32,
    /// Time between beams, s.
    pub time_increment: f32,
    /// Time between scans, s.
    pub scan_time: f32,
    /// Nearest range measured, m.
    pub range_min: f32,
    /// Farthest range measured, m.
    pub range_max: f32,
    /// Ranges, m (+∞: nothing within range, as REP 117 says).
    pub ranges: Vec<f32>,
    /// Intensities (empty: none measured).
    pub intensities: Vec<f32>,
}

/// `sensor_msgs/msg/Imu`. A covariance whose first element is −1 says the quantity is
/// not measured (REP 145); all zeros, unknown.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Imu {
    /// Stamp and the IMU's frame.
    pub header: Header,
    /// Orientation of the IMU's frame in the fixed frame.
    pub orientation: Quaternion,
    /// Its covariance, row-major about x, y, z.
    pub orientation_covariance: [f64; 9],
    /// Angular velocity, rad/s, in the IMU's frame.
    pub angular_velocity: Vector3,
    /// Its covariance.
    pub angular_velocity_covariance: [f64; 9],
    /// Linear acceleration (specific force: +9.81 m/s² up at rest), in the IMU's frame.
    pub linear_acceleration: Vector3,
    /// Its covariance.
    pub linear_acceleration_covariance: [f64; 9],
}

/// `sensor_msgs/msg/Image`: pixels row after row.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Image {
    /// Stamp and the camera's optical frame.
    pub header: Header,
    /// Rows.
    pub height: u32,
    /// Columns.
    pub width: u32,
    /// Pixel encoding (`"32FC1"`: one f32 a pixel, a depth in metres).
    pub encoding: String,
    /// 1 if the pixels' bytes are big-endian.
    pub is_bigendian: u8,
    /// Bytes per row.
    pub step: u32,
    /// The pixels.
    pub data: Vec<u8>,
}

/// `sensor_msgs/msg/RegionOfInterest`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RegionOfInterest {
    /// Leftmost pixel.
    pub x_offset: u32,
    /// Topmost pixel.
    pub y_offset: u32,
    /// Rows (0: the whole image).
    pub height: u32,
    /// Columns (0: the whole image).
    pub width: u32,
    /// Whether the region is to be rectified.
    pub do_rectify: bool,
}

/// `sensor_msgs/msg/CameraInfo`: a pinhole camera's calibration.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CameraInfo {
    /// Stamp and the camera's optical frame.
    pub header: Header,
    /// Rows.
    pub height: u32,
    /// Columns.
    pub width: u32,
    /// Distortion model (`"plumb_bob"`).
    pub distortion_model: String,
    /// Distortion parameters (zeros: none).
    pub d: Vec<f64>,
    /// Intrinsic matrix, row-major.
    pub k: [f64; 9],
    /// Rectification rotation, row-major.
    pub r: [f64; 9],
    /// Projection matrix, row-major 3 × 4.
    pub p: [f64; 12],
    /// Horizontal binning.
    pub binning_x: u32,
    /// Vertical binning.
    pub binning_y: u32,
    /// Region of interest.
    pub roi: RegionOfInterest,
}
