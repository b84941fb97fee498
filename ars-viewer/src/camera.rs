//! A camera sensor: colour images rendered off screen (no display, no GPU needed) and
//! metric depth images computed from the geometry, from a pose in the world or on a
//! body.

use std::path::Path;

use ars_core::nalgebra::Isometry3;
use ars_core::sensors::{DepthCamera, DepthImage, Sensor};
use ars_core::{ObjectId, Simulation, WindowSettings};
use kiss3d::window::OffscreenSurface;

use crate::error::{Result, ViewerError};
use crate::offscreen::init_offscreen_context;
use crate::scene::DrawnScene;

/// A camera's image size and lens.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intrinsics {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Vertical field of view, rad.
    pub fov_y: f64,
    /// Nearest distance seen, m.
    pub near: f64,
    /// Farthest distance seen, m.
    pub far: f64,
}

/// One capture: the colour image and the depth image of the same moment.
#[derive(Clone, Debug)]
pub struct CameraFrame {
    /// Colour, 8 bits per channel.
    pub rgb: image::RgbImage,
    /// Depth along the optical axis, m (see [`DepthImage`]).
    pub depth: DepthImage,
}

impl CameraFrame {
    /// The depth in millimetres as a 16-bit grey image (0: nothing seen, or nearer
    /// than 1 mm; saturates at 65.535 m).
    pub fn depth_mm(&self) -> image::ImageBuffer<image::Luma<u16>, Vec<u16>> {
        let mm = self
            .depth
            .pixels
            .iter()
            .map(|d| if d.is_finite() { (f64::from(*d) * 1000.0).round().clamp(0.0, 65535.0) as u16 } else { 0 })
            .collect();
        image::ImageBuffer::from_raw(self.depth.width, self.depth.height, mm).expect("one value per pixel")
    }

    /// Saves `PREFIX_rgb.png`, `PREFIX_depth.png` (16-bit, millimetres) and
    /// `PREFIX_depth.npy` (float32, metres) in `dir`.
    pub fn save(&self, dir: &Path, prefix: &str) -> Result<()> {
        std::fs::create_dir_all(dir).map_err(|e| ViewerError::write(dir, e))?;
        let rgb = dir.join(format!("{prefix}_rgb.png"));
        self.rgb.save(&rgb).map_err(|e| ViewerError::image_write(&rgb, e))?;
        let png = dir.join(format!("{prefix}_depth.png"));
        self.depth_mm().save(&png).map_err(|e| ViewerError::image_write(&png, e))?;
        let npy = dir.join(format!("{prefix}_depth.npy"));
        let file = std::fs::File::create(&npy).map_err(|e| ViewerError::write(&npy, e))?;
        self.depth.write_npy(std::io::BufWriter::new(file)).map_err(|e| ViewerError::write(&npy, e))
    }
}

/// A camera sensor: in its own frame it looks along −Z with +Y up (the depth camera's
/// convention), in both images: a camera rolled about its optical axis sees the world
/// rolled the other way. Rendering happens on
/// the calling thread: call [`capture`](Self::capture) for a frame now, or give the
/// camera a rate ([`every`](Self::every)) and let [`run`](Self::run) step a simulation
/// and capture each frame when it is due (or call
/// [`capture_if_due`](Self::capture_if_due) from your own loop).
pub struct Camera {
    intrinsics: Intrinsics,
    surface: OffscreenSurface,
    view: DrawnScene,
    depth: DepthCamera,
    /// Seconds between frames (`None`: every call).
    period: Option<f64>,
    /// Simulated time of the next frame due.
    next_frame: Option<f64>,
}

impl Camera {
    /// A camera of these intrinsics at the world origin.
    pub fn new(intrinsics: Intrinsics) -> Result<Self> {
        let Intrinsics { width, height, fov_y, near, far } = intrinsics;
        let depth = DepthCamera::new(width, height, fov_y, near, far).map_err(ViewerError::from)?;
        init_offscreen_context()?;
        let settings = WindowSettings { size: (width, height), ..WindowSettings::default() };
        let (surface, view) =
            crate::offscreen::surface_with_view(&settings, (width, height), &crate::SceneMirror::new());
        Ok(Camera { intrinsics, surface, view, depth, period: None, next_frame: None })
    }

    /// Placed in the world at `pose`.
    #[must_use]
    pub fn at(mut self, pose: Isometry3<f64>) -> Self {
        self.depth = self.depth.at(pose);
        self
    }

    /// Mounted on `object` at `offset` from its origin (it does not see that object).
    #[must_use]
    pub fn on(mut self, object: ObjectId, offset: Isometry3<f64>) -> Self {
        self.depth = self.depth.on(object, offset);
        self
    }

    /// Captures a frame every `period` seconds of simulated time (a rate of
    /// `1 / period` frames per second), the first at the first call.
    pub fn every(mut self, period: f64) -> Result<Self> {
        if !(period.is_finite() && period > 0.0) {
            return Err(ViewerError::InvalidSetting(format!("a camera period must be positive, got {period}")));
        }
        self.period = Some(period);
        Ok(self)
    }

    /// A frame of `sim` as it is now if one is due (always, without a period), with its
    /// simulated time.
    pub fn capture_if_due(&mut self, sim: &Simulation) -> Result<Option<(f64, CameraFrame)>> {
        let time = sim.scene().time();
        if let (Some(period), Some(next)) = (self.period, self.next_frame) {
            // Half a step of slack absorbs the drift of the accumulated time, as for
            // the simulation's sensors.
            if time + 0.5 * sim.scene().time_step() < next {
                return Ok(None);
            }
            self.next_frame = Some(next + period);
        } else if let Some(period) = self.period {
            self.next_frame = Some(time + period);
        }
        Ok(Some((time, self.capture(sim)?)))
    }

    /// Steps `sim` for `duration` seconds, handing every frame due (one now, then at the
    /// camera's rate; see [`every`](Self::every)) to `on_frame` with its time.
    pub fn run(
        &mut self,
        sim: &mut Simulation,
        duration: f64,
        mut on_frame: impl FnMut(f64, CameraFrame) -> Result<()>,
    ) -> Result<()> {
        let steps = sim.scene().steps_in(duration).map_err(ViewerError::from)?;
        if let Some((t, frame)) = self.capture_if_due(sim)? {
            on_frame(t, frame)?;
        }
        for _ in 0..steps {
            sim.step().map_err(ViewerError::from)?;
            if let Some((t, frame)) = self.capture_if_due(sim)? {
                on_frame(t, frame)?;
            }
        }
        Ok(())
    }

    /// The camera's intrinsics.
    pub fn intrinsics(&self) -> Intrinsics {
        self.intrinsics
    }

    /// Renders the colour image and computes the depth image of `sim` as it is now.
    pub fn capture(&mut self, sim: &Simulation) -> Result<CameraFrame> {
        // One mount for both images: the depth camera's. The colour image rolls with the
        // camera's own up (its +Y), not the world's, as the depth image does.
        let mut camera = crate::viewports::sensor_camera(&self.depth, sim)?;
        self.view.mirror.sync(sim, &mut self.view.scene).map_err(ViewerError::from)?;
        let rgb = kiss3d::pollster::block_on(self.surface.render_image_3d(&mut self.view.scene, &mut camera));
        let depth = self.depth.measure(sim.scene()).map_err(ViewerError::from)?;
        Ok(CameraFrame { rgb, depth })
    }
}
