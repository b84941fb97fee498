//! Depth cameras as ROS publishes cameras: a `sensor_msgs/Image` of `32FC1` depths
//! (metres along the optical axis, +∞ where nothing is seen, as REP 118 says) and its
//! `sensor_msgs/CameraInfo`, in an optical frame (REP 103's camera convention: z
//! forward, x right, y down). ARS's [`DepthCamera`] looks along its −Z with +Y up, so
//! its optical frame is its own turned 180° about X.

use ars_core::sensors::{DepthCamera, DepthImage, Mount};
use ars_core::{SensorId, Simulation};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};

use crate::error::RosResult;
use crate::msg::{self, Header, Time, nanos_of};
use crate::tf_tree::FrameTree;
use crate::topics::{Message, Outgoing};

/// A depth camera's topics.
#[derive(Debug)]
pub(crate) struct CameraTopics {
    sensor: SensorId<DepthCamera>,
    image_topic: usize,
    info_topic: usize,
    frame: String,
    sent: usize,
    info: msg::CameraInfo,
}

/// The optical frame in a depth camera's own frame: 180° about X.
pub fn optical_frame() -> Isometry3<f64> {
    Isometry3::from_parts(
        Vector3::zeros().into(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    )
}

/// The calibration of a pinhole camera of `width` × `height` pixels and vertical field
/// of view `fov_y`, as ARS casts its rays (through the pixels' centres; square pixels).
pub fn camera_info(width: u32, height: u32, fov_y: f64) -> msg::CameraInfo {
    let f = f64::from(height) / (2.0 * (fov_y / 2.0).tan());
    let (cx, cy) = (f64::from(width) / 2.0 - 0.5, f64::from(height) / 2.0 - 0.5);
    msg::CameraInfo {
        height,
        width,
        distortion_model: "plumb_bob".into(),
        d: vec![0.0; 5],
        k: [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0],
        r: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        p: [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
        ..Default::default()
    }
}

impl CameraTopics {
    /// A depth camera's topics (indices `image_topic` and `image_topic + 1`) and frame.
    pub(crate) fn new(
        sim: &Simulation,
        sensor: SensorId<DepthCamera>,
        frame: String,
        image_topic: usize,
        tree: &mut FrameTree,
    ) -> RosResult<CameraTopics> {
        let camera = sim.sensor(sensor)?;
        let (object, offset) = match camera.mount() {
            Mount::World(pose) => (None, pose),
            Mount::Object(object, offset) => (Some(object), offset),
        };
        tree.add_sensor(&frame, object, offset, optical_frame());
        let settings = ars_core::sensors::Sensor::settings(camera);
        let Some(ars_core::sensors::SensorSettings::DepthCamera { width, height, .. }) = settings else {
            unreachable!("a depth camera has its settings");
        };
        let info = camera_info(width, height, camera.fov_y());
        Ok(CameraTopics { sensor, image_topic, info_topic: image_topic + 1, frame, sent: 0, info })
    }

    /// Starts over (the records were cleared).
    pub(crate) fn restart(&mut self) {
        self.sent = 0;
    }

    /// Every image since the last call, each with its calibration.
    pub(crate) fn push(&mut self, sim: &Simulation, out: &mut Vec<Outgoing>) -> RosResult<()> {
        let log = sim.records(self.sensor)?;
        for sample in log.samples().iter().skip(self.sent) {
            let stamp = nanos_of(sample.time);
            let header = Header { stamp: Time::from_nanos(stamp), frame_id: self.frame.clone() };
            let image = image(header.clone(), &sample.record);
            out.push(Outgoing { topic: self.image_topic, stamp, message: Message::Image(Box::new(image)) });
            let info = msg::CameraInfo { header, ..self.info.clone() };
            out.push(Outgoing { topic: self.info_topic, stamp, message: Message::CameraInfo(Box::new(info)) });
        }
        self.sent = log.len();
        Ok(())
    }
}

/// A depth image as a `32FC1` image, little-endian.
pub fn image(header: Header, depth: &DepthImage) -> msg::Image {
    msg::Image {
        header,
        height: depth.height,
        width: depth.width,
        encoding: "32FC1".into(),
        is_bigendian: 0,
        step: 4 * depth.width,
        data: depth.pixels.iter().flat_map(|d| d.to_le_bytes()).collect(),
    }
}
