//! A depth camera: metric depth images, computed exactly from the scene's geometry by
//! casting one ray per pixel (no GPU, no display).

use std::io::{self, Write};
use std::sync::Arc;

use nalgebra::{Isometry3, Vector3};

use super::{Mount, Record, Sensor};
use crate::error::{Error, Result};
use crate::handle::ObjectId;
use crate::limits;
use crate::scene::Scene;
use crate::world::raycast::Ray;

/// A pinhole depth camera. In its own frame it looks along −Z with +Y up and +X to the
/// right (the usual graphics camera: at the identity pose it looks horizontally into
/// the Y-up world). Each pixel holds the depth of the nearest surface along the optical
/// axis (the z-distance, not the ray length), in metres, or +∞ where nothing lies
/// between `near` and `far`. Mounted in the world or on an object (whose own geoms it
/// does not see); sample it at a rate with
/// [`Simulation::add_sensor_every`](crate::Simulation::add_sensor_every).
///
/// ```
/// use ars_core::nalgebra::{Isometry3, Vector3};
/// use ars_core::{Mass, Simulation, sensors::DepthCamera};
///
/// let mut sim = Simulation::builder().gravity(Vector3::zeros()).build()?;
/// sim.scene_mut().add_box([4.0, 4.0, 1.0], [0.0, 0.0, -3.5], Mass::Total(1.0))?; // its face at z = -3
/// let camera = sim.add_sensor(DepthCamera::new(64, 48, 1.0, 0.1, 10.0)?)?;
/// sim.step()?;
/// let image = &sim.records(camera)?.last().unwrap().record;
/// assert!((image.depth(32, 24) - 3.0).abs() < 1e-5, "the centre pixel sees the face 3 m ahead");
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct DepthCamera {
    width: u32,
    height: u32,
    fov_y: f64,
    near: f64,
    far: f64,
    mount: Mount,
    /// Unit ray directions in the camera frame, row by row from the top.
    directions: Arc<[Vector3<f64>]>,
}

impl DepthCamera {
    /// `width` × `height` pixels, a vertical field of view `fov_y` (rad), seeing from
    /// `near` to `far` metres; at the world origin.
    pub fn new(width: u32, height: u32, fov_y: f64, near: f64, far: f64) -> Result<Self> {
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err(Error::OutOfRange {
                what: "camera resolution",
                detail: format!("must be 1 to 4096 pixels each way, got {width} × {height}"),
            });
        }
        let fov_y = limits::in_range("camera field of view", fov_y, 1e-3, std::f64::consts::PI - 1e-3)?;
        let far = limits::size("camera far distance", far)?;
        let near = limits::in_range("camera near distance", near, 0.0, far)?;
        // Pixel centres on the image plane at z = -1.
        let half_h = (fov_y / 2.0).tan();
        let half_w = half_h * f64::from(width) / f64::from(height);
        let directions = (0..height)
            .flat_map(|row| {
                (0..width).map(move |col| {
                    let x = ((f64::from(col) + 0.5) / f64::from(width) * 2.0 - 1.0) * half_w;
                    let y = (1.0 - (f64::from(row) + 0.5) / f64::from(height) * 2.0) * half_h;
                    Vector3::new(x, y, -1.0).normalize()
                })
            })
            .collect();
        Ok(DepthCamera { width, height, fov_y, near, far, mount: Mount::default(), directions })
    }

    /// Placed in the world at `pose`.
    #[must_use]
    pub fn at(mut self, pose: Isometry3<f64>) -> Self {
        self.mount = Mount::World(pose);
        self
    }

    /// Mounted on `object` at `offset` from its origin.
    #[must_use]
    pub fn on(mut self, object: ObjectId, offset: Isometry3<f64>) -> Self {
        self.mount = Mount::Object(object, offset);
        self
    }

    /// Where it is.
    pub fn mount(&self) -> Mount {
        self.mount
    }

    /// The vertical field of view, rad.
    pub fn fov_y(&self) -> f64 {
        self.fov_y
    }

    /// The nearest distance it sees, m.
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The farthest distance it sees, m.
    pub fn far(&self) -> f64 {
        self.far
    }
}

/// One [`DepthCamera`] image.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Depth along the optical axis of each pixel, m, row by row from the top (+∞: nothing).
    pub pixels: Vec<f32>,
}

impl DepthImage {
    /// The depth at column `x`, row `y` (from the top left), m.
    pub fn depth(&self, x: u32, y: u32) -> f32 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Writes the image as a NumPy `.npy` array of `float32`, shape `(height, width)`,
    /// metres (`numpy.load` reads it).
    pub fn write_npy(&self, mut w: impl Write) -> io::Result<()> {
        let mut header =
            format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", self.height, self.width);
        // Magic (6) + version (2) + header length (2) + header + '\n', padded to 64 bytes.
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        w.write_all(b"\x93NUMPY\x01\x00")?;
        w.write_all(&(header.len() as u16).to_le_bytes())?;
        w.write_all(header.as_bytes())?;
        for p in &self.pixels {
            w.write_all(&p.to_le_bytes())?;
        }
        Ok(())
    }
}

impl Record for DepthImage {
    fn columns() -> Vec<&'static str> {
        vec!["width [px]", "height [px]", "centre depth [m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let centre = f64::from(self.depth(self.width / 2, self.height / 2));
        vec![Some(f64::from(self.width)), Some(f64::from(self.height)), centre.is_finite().then_some(centre)]
    }
}

impl Sensor for DepthCamera {
    type Record = DepthImage;

    fn measure(&mut self, scene: &Scene) -> Result<DepthImage> {
        let (pose, ignore) = (self.mount.pose(scene)?, self.mount.own_body(scene)?);
        let origin = nalgebra::Point3::from(pose.translation.vector);
        let rays: Vec<Ray> = self.directions.iter().map(|d| Ray { origin, direction: pose.rotation * d }).collect();
        // The farthest a pixel can see: `far` along the axis is further along its ray.
        let reach = self.directions.iter().map(|d| self.far / -d.z).fold(self.far, f64::max);
        let hits = scene.world().cast_rays(&rays, reach, ignore)?;
        let pixels = hits
            .iter()
            .zip(self.directions.iter())
            .map(|(hit, d)| {
                let depth = hit.map_or(f64::INFINITY, |h| h.distance * -d.z);
                if depth >= self.near && depth <= self.far { depth as f32 } else { f32::INFINITY }
            })
            .collect();
        Ok(DepthImage { width: self.width, height: self.height, pixels })
    }

    fn objects(&self) -> Vec<ObjectId> {
        self.mount.objects()
    }
    fn measures_every_step(&self) -> bool {
        false
    }
    fn settings(&self) -> Option<super::SensorSettings> {
        Some(super::SensorSettings::DepthCamera {
            width: self.width,
            height: self.height,
            fov_y: self.fov_y,
            near: self.near,
            far: self.far,
            pose: self.mount.offset(),
        })
    }
}
