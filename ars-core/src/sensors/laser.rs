//! The laser range finder: a ray that reports the distance to the closest thing it hits.

use nalgebra::{Isometry3, Point3, Rotation3};

use super::{Record, Sensor};
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{GeomHandle, ObjectId};
use crate::scene::Scene;
use crate::validate;

#[derive(Clone, Debug)]
enum Mount {
    World { position: Point3<f64>, rotation: Rotation3<f64> },
    Body { object: ObjectId, offset: Isometry3<f64> },
}

/// A ray of `max_distance` along its local +Z axis, placed in the world or mounted on
/// an object with an offset. Every step it reports the closest hit of the collision
/// pass of that step (which uses the poses before the step), or `None`.
///
/// ```
/// use ars_core::{Mass, Simulation, sensors::Laser};
/// use ars_core::convert::rotation_about_axis;
/// use nalgebra::{Point3, Vector3};
///
/// let mut sim = Simulation::new()?;
/// sim.scene_mut().add_sphere(1.0, [5.0, 0.0, 0.0], Mass::Total(1.0))?;
/// // Pointing along +X: local +Z turned by π/2 about Y.
/// let along_x = rotation_about_axis(&Vector3::y(), std::f64::consts::FRAC_PI_2);
/// let laser = sim.add_sensor(Laser::new(1000.0).at(Point3::origin(), along_x))?;
/// sim.step()?;
/// let d = sim.records(laser)?.last().unwrap().record.distance.unwrap();
/// assert!((d - 4.0).abs() < 1e-9);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Laser {
    max_distance: f64,
    mount: Mount,
    ray: Option<GeomHandle>,
}

impl Laser {
    /// A laser at the origin pointing along +Z.
    pub fn new(max_distance: f64) -> Self {
        Laser {
            max_distance,
            mount: Mount::World { position: Point3::origin(), rotation: Rotation3::identity() },
            ray: None,
        }
    }

    /// Placed at `position` with `rotation` (the beam points along `rotation · +Z`).
    #[must_use]
    pub fn at(mut self, position: Point3<f64>, rotation: Rotation3<f64>) -> Self {
        self.mount = Mount::World { position, rotation };
        self
    }

    /// Mounted on `object` at `offset` from its origin; it moves with the object and
    /// does not see the object itself.
    #[must_use]
    pub fn mounted_on(mut self, object: ObjectId, offset: Isometry3<f64>) -> Self {
        self.mount = Mount::Body { object, offset };
        self
    }

    /// The ray geom, once the laser is added to a simulation.
    pub fn ray(&self) -> Option<GeomHandle> {
        self.ray
    }

    /// The longest distance it measures, m.
    pub fn max_distance(&self) -> f64 {
        self.max_distance
    }
}

/// A [`Laser`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaserReading {
    /// Distance from the ray origin to the closest hit, m; `None` when nothing is hit.
    pub distance: Option<f64>,
    /// The hit point, world frame.
    pub point: Option<Point3<f64>>,
}

impl Record for LaserReading {
    fn columns() -> Vec<&'static str> {
        vec!["distance [m]", "hit x [m]", "hit y [m]", "hit z [m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let p = self.point;
        vec![self.distance, p.map(|p| p.x), p.map(|p| p.y), p.map(|p| p.z)]
    }
}

impl Sensor for Laser {
    type Record = LaserReading;

    fn attach(&mut self, sim: &mut Scene) -> Result<()> {
        validate::positive("laser max distance", self.max_distance)?;
        let space = sim.space();
        let ray = match &self.mount {
            Mount::World { position, rotation } => {
                validate::point("laser position", position)?;
                validate::rotation("laser rotation", rotation)?;
                let ray = sim.world_mut().insert_geom(space, GeomBuilder::ray(self.max_distance))?;
                let mut g = sim.world_mut().geom_mut(ray)?;
                g.set_position(*position)?;
                g.set_rotation(*rotation)?;
                ray
            }
            Mount::Body { object, offset } => {
                let view = sim.object(*object)?;
                let body = view
                    .body_handle()
                    .ok_or_else(|| Error::NoBody { operation: "a laser mount", object: view.name().to_string() })?;
                let builder = GeomBuilder::ray(self.max_distance).attached_to(body).offset(*offset);
                sim.world_mut().insert_geom(space, builder)?
            }
        };
        self.ray = Some(ray);
        Ok(())
    }

    fn measure(&mut self, sim: &Scene) -> Result<LaserReading> {
        let ray = self.ray.expect("attached when added");
        let hit = sim.world().closest_ray_hit(ray);
        Ok(LaserReading { distance: hit.map(|h| h.distance), point: hit.map(|h| h.position) })
    }

    fn objects(&self) -> Vec<ObjectId> {
        match &self.mount {
            Mount::Body { object, .. } => vec![*object],
            Mount::World { .. } => Vec::new(),
        }
    }
}
