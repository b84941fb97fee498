//! `ars.Simulation`'s methods that declare sensors.

use crate::errors::count;
use pyo3::prelude::*;

use super::{Int, PySimulation, Vec3};
use crate::errors::Checked;

#[pymethods]
impl PySimulation {
    /// A lidar: `beams` beams per plane fanned over `fov` radians, seeing from
    /// `min_range` to `max_range` m, in its own X–Z plane (horizontal when upright in
    /// the Y-up world, azimuth from +X towards −Z) and the planes tilted by
    /// `planes` (elevations, rad). Mounted on the object `on` at `position` with
    /// `rotation` (3×3) relative to it (it does not see that object), or in the world.
    /// Scans after every step or every `every` seconds; `noise` adds seeded Gaussian
    /// noise of that standard deviation (m) to the ranges. `Sensor.ranges()` gives the
    /// scans as an array.
    #[pyo3(signature = (beams, fov, max_range, *, min_range=0.0, planes=None, on=None, position=Checked([0.0; 3]),
                        rotation=None, every=None, noise=None, seed=Checked(0)))]
    fn add_lidar(
        slf: Bound<'_, Self>,
        beams: Int,
        fov: f64,
        max_range: f64,
        min_range: f64,
        planes: Option<Vec<f64>>,
        on: Option<String>,
        position: Vec3,
        rotation: Option<Checked<[[f64; 3]; 3]>>,
        every: Option<f64>,
        noise: Option<f64>,
        seed: Int,
    ) -> PyResult<crate::sensors::PySensor> {
        let beams: u32 = count(slf.py(), "lidar beams", beams)?;
        let seed: u64 = count(slf.py(), "the seed", seed)?;
        let offset = crate::errors::guarded(slf.py(), || crate::views::pose(position, rotation))?;
        let spec =
            crate::sensors::LidarSpec { beams, fov, max_range, min_range, planes, on, offset, every, noise, seed };
        let id = slf.get().with(slf.py(), move |sim| spec.add_to(sim))?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), "lidar".into(), id))
    }

    /// A depth camera: `width` × `height` pixels over the vertical field of view `fov_y`
    /// (rad), depths from `near` to `far` m along its optical axis (its −Z, +Y up in the
    /// image). Mounted as `add_lidar`'s lidar. `Sensor.images()` gives the images as an
    /// array.
    #[pyo3(signature = (width, height, fov_y, near, far, *, on=None, position=Checked([0.0; 3]), rotation=None, every=None))]
    fn add_depth_camera(
        slf: Bound<'_, Self>,
        width: Int,
        height: Int,
        fov_y: f64,
        near: f64,
        far: f64,
        on: Option<String>,
        position: Vec3,
        rotation: Option<Checked<[[f64; 3]; 3]>>,
        every: Option<f64>,
    ) -> PyResult<crate::sensors::PySensor> {
        let (width, height): (u32, u32) =
            (count(slf.py(), "image width", width)?, count(slf.py(), "image height", height)?);
        let offset = crate::errors::guarded(slf.py(), || crate::views::pose(position, rotation))?;
        let id = slf.get().with(slf.py(), move |sim| {
            let camera = ars_core::sensors::DepthCamera::new(width, height, fov_y, near, far)?;
            let camera = match on {
                Some(name) => camera.on(sim.scene().object(name.as_str())?.id(), offset),
                None => camera.at(offset),
            };
            crate::sensors::Typed::add(sim, camera, every, crate::sensors::Typed::Depth)
        })?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), "depth_camera".into(), id))
    }

    /// Declares a sensor of `kind` reading `target` (an object or joint name; a list of
    /// joint names for `"joint_positions"`; nothing for `"system_total_energy"`),
    /// sampled after every step or every `every` seconds; see `Sensor.records`.
    #[pyo3(signature = (kind, target=None, *, every=None))]
    fn add_sensor(
        slf: Bound<'_, Self>,
        kind: &str,
        target: Option<Bound<'_, PyAny>>,
        every: Option<f64>,
    ) -> PyResult<crate::sensors::PySensor> {
        let targets: Vec<String> = match target {
            None => Vec::new(),
            Some(t) => match t.extract::<String>() {
                Ok(name) => vec![name],
                Err(_) => t.extract::<Vec<String>>()?,
            },
        };
        let kind_owned = kind.to_string();
        let log = slf.get().with(slf.py(), move |sim| crate::sensors::declare(sim, &kind_owned, &targets, every))?;
        Ok(crate::sensors::PySensor::new(slf.unbind(), kind.to_string(), crate::sensors::Typed::Table(log)))
    }
}
