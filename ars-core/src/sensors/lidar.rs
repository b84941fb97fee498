//! The scanning range finder: beams fanned over a field of view, in one plane or
//! several, cast on demand at each scan.

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Vector3};

use super::noise::Perturb;
use super::{Mount, Record, Sensor};
use crate::error::{Error, Result};
use crate::handle::ObjectId;
use crate::limits;
use crate::scene::Scene;
use crate::world::raycast::Ray;

/// A scanning range finder (lidar). In its own frame the beams fan out in the X–Z
/// plane (horizontal when the sensor is upright in the Y-up world), from azimuth
/// `−fov/2` to `+fov/2` measured from +X towards −Z (counter-clockwise seen from above);
/// extra planes tilt the fan by their elevation towards +Y. Mounted in the world or on
/// an object (whose own geoms it does not see). Each scan is one record: every beam's
/// range (∞ when nothing is within `[min_range, max_range]`) and hit point. Sample it at
/// a rate with [`Simulation::add_sensor_every`](crate::Simulation::add_sensor_every);
/// wrap it in [`Noisy`](super::Noisy) for seeded Gaussian range noise.
///
/// ```
/// use ars_core::{Mass, Simulation, sensors::Lidar};
///
/// let mut sim = Simulation::new()?;
/// sim.scene_mut().add_box([1.0, 1.0, 1.0], [3.0, 0.0, 0.0], Mass::Total(1.0))?; // 2.5 m ahead
/// let lidar = sim.add_sensor(Lidar::new(360, std::f64::consts::TAU, 10.0)?)?;
/// sim.step()?;
/// let scan = &sim.records(lidar)?.last().unwrap().record;
/// assert_eq!(scan.ranges.len(), 360);
/// assert!((scan.ranges[180] - 2.5).abs() < 1e-9, "the beam along +X: {}", scan.ranges[180]);
/// assert!(scan.ranges[0].is_infinite(), "nothing behind");
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Lidar {
    beams: u32,
    fov: f64,
    min_range: f64,
    max_range: f64,
    elevations: Vec<f64>,
    mount: Mount,
    /// Beam directions in the sensor frame, and their CSV headers.
    directions: Vec<Vector3<f64>>,
    headers: Arc<[String]>,
}

impl Lidar {
    /// `beams` beams per plane over `fov` radians (a full turn, 2π, spaces them evenly
    /// without repeating the first), seeing up to `max_range` metres; at the world
    /// origin, in the horizontal plane.
    pub fn new(beams: u32, fov: f64, max_range: f64) -> Result<Self> {
        if !(1..=100_000).contains(&beams) {
            return Err(Error::OutOfRange { what: "lidar beams", detail: format!("must be 1 to 100000, got {beams}") });
        }
        let fov = limits::in_range("lidar field of view", fov, 0.0, std::f64::consts::TAU)?;
        let max_range = limits::size("lidar range", max_range)?;
        let mut lidar = Lidar {
            beams,
            fov,
            min_range: 0.0,
            max_range,
            elevations: vec![0.0],
            mount: Mount::default(),
            directions: Vec::new(),
            headers: Arc::from(Vec::new()),
        };
        lidar.fan();
        Ok(lidar)
    }

    /// Hits nearer than `min_range` are not seen (∞), as a real sensor's blind zone.
    pub fn min_range(mut self, min_range: f64) -> Result<Self> {
        self.min_range = limits::in_range("lidar minimum range", min_range, 0.0, self.max_range)?;
        Ok(self)
    }

    /// Several scan planes, by elevation (rad, towards +Y); the default is `[0]`.
    pub fn planes(mut self, elevations: &[f64]) -> Result<Self> {
        if elevations.is_empty() {
            return Err(Error::Invalid { what: "a lidar", problem: "needs at least one plane".into() });
        }
        for e in elevations {
            limits::in_range("lidar plane elevation", *e, -std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2)?;
        }
        self.elevations = elevations.to_vec();
        self.fan();
        Ok(self)
    }

    /// Placed in the world at `pose`.
    #[must_use]
    pub fn at(mut self, pose: Isometry3<f64>) -> Self {
        self.mount = Mount::World(pose);
        self
    }

    /// Mounted on `object` at `offset` from its origin (it moves with it).
    #[must_use]
    pub fn on(mut self, object: ObjectId, offset: Isometry3<f64>) -> Self {
        self.mount = Mount::Object(object, offset);
        self
    }

    /// The beams' azimuths, rad, in scan order within a plane.
    pub fn azimuths(&self) -> Vec<f64> {
        let full = self.fov >= std::f64::consts::TAU - 1e-12;
        let n = f64::from(self.beams);
        let step = if full {
            self.fov / n
        } else if self.beams > 1 {
            self.fov / (n - 1.0)
        } else {
            0.0
        };
        let start = if self.beams == 1 { 0.0 } else { -self.fov / 2.0 };
        (0..self.beams).map(|i| start + step * f64::from(i)).collect()
    }

    fn fan(&mut self) {
        let azimuths = self.azimuths();
        self.directions = self
            .elevations
            .iter()
            .flat_map(|e| azimuths.iter().map(move |a| Vector3::new(e.cos() * a.cos(), e.sin(), -e.cos() * a.sin())))
            .collect();
        let many = self.elevations.len() > 1;
        self.headers = self
            .elevations
            .iter()
            .enumerate()
            .flat_map(|(p, _)| {
                (0..self.beams).map(move |b| if many { format!("range {p}.{b} [m]") } else { format!("range {b} [m]") })
            })
            .collect();
    }
}

/// One [`Lidar`] scan.
#[derive(Clone, Debug, PartialEq)]
pub struct Scan {
    /// Each beam's range, m, plane after plane (∞: nothing seen).
    pub ranges: Vec<f64>,
    /// Each beam's hit point, world frame (`None`: nothing seen).
    pub points: Vec<Option<Point3<f64>>>,
    /// Where the sensor was, world frame.
    pub origin: Point3<f64>,
    headers: Arc<[String]>,
}

impl Record for Scan {
    fn columns() -> Vec<&'static str> {
        Vec::new()
    }
    fn values(&self) -> Vec<Option<f64>> {
        self.ranges.iter().map(|r| r.is_finite().then_some(*r)).collect()
    }
    fn headers(&self) -> Vec<String> {
        self.headers.to_vec()
    }
}

impl Perturb for Scan {
    fn perturb(&mut self, noise: &mut dyn FnMut() -> f64) {
        for r in self.ranges.iter_mut().filter(|r| r.is_finite()) {
            *r = (*r + noise()).max(0.0);
        }
    }
}

impl Sensor for Lidar {
    type Record = Scan;

    fn measure(&mut self, scene: &Scene) -> Result<Scan> {
        let pose = self.mount.pose(scene)?;
        let origin = Point3::from(pose.translation.vector);
        let ignore = self.mount.own_body(scene)?;
        let rays: Vec<Ray> = self.directions.iter().map(|d| Ray { origin, direction: pose.rotation * d }).collect();
        let hits = scene.world().cast_rays(&rays, self.max_range, ignore)?;
        let (mut ranges, mut points) = (Vec::with_capacity(hits.len()), Vec::with_capacity(hits.len()));
        for hit in hits {
            match hit.filter(|h| h.distance >= self.min_range) {
                Some(h) => {
                    ranges.push(h.distance);
                    points.push(Some(h.position));
                }
                None => {
                    ranges.push(f64::INFINITY);
                    points.push(None);
                }
            }
        }
        Ok(Scan { ranges, points, origin, headers: self.headers.clone() })
    }

    fn objects(&self) -> Vec<ObjectId> {
        self.mount.objects()
    }
    fn measures_every_step(&self) -> bool {
        false
    }
    fn settings(&self) -> Option<super::SensorSettings> {
        Some(super::SensorSettings::Lidar {
            beams: self.beams,
            fov: self.fov,
            min_range: self.min_range,
            max_range: self.max_range,
            elevations: self.elevations.clone(),
            pose: self.mount.offset(),
        })
    }

    /// Each beam that hit something, from the sensor to the hit.
    fn lines(scan: &Scan) -> Vec<(Point3<f64>, Point3<f64>)> {
        scan.points.iter().flatten().map(|p| (scan.origin, *p)).collect()
    }
}
