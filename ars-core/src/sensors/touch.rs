//! The touch sensor: how hard a body is pressed, anywhere or within a zone of it.

use nalgebra::{Isometry3, Point3, Vector3};

use super::{Record, Sensor, SensorSettings};
use crate::error::{Error, Result};
use crate::handle::ObjectId;
use crate::scene::Scene;

/// A volume fixed on a body, in its own frame (centred on its origin, its axis along
/// local Z), where a [`Touch`] sensor feels contacts.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum TouchZone {
    /// A ball.
    Sphere {
        /// Its radius, m.
        radius: f64,
    },
    /// A cylinder with half-balls at its ends.
    Capsule {
        /// Its radius, m.
        radius: f64,
        /// Half the length of its cylinder, m.
        half_length: f64,
    },
    /// A cylinder.
    Cylinder {
        /// Its radius, m.
        radius: f64,
        /// Half its length, m.
        half_length: f64,
    },
    /// A box.
    Box {
        /// Half its edges along X, Y and Z, m.
        half_extents: Vector3<f64>,
    },
    /// An ellipsoid.
    Ellipsoid {
        /// Its semi-axes along X, Y and Z, m.
        radii: Vector3<f64>,
    },
}

impl TouchZone {
    /// Whether `p` (in the zone's frame) is inside the zone or on its surface.
    pub fn contains(&self, p: &Point3<f64>) -> bool {
        match self {
            TouchZone::Sphere { radius } => p.coords.norm() <= *radius,
            TouchZone::Capsule { radius, half_length } => {
                let along = p.z.clamp(-half_length, *half_length);
                (p.coords - Vector3::new(0.0, 0.0, along)).norm() <= *radius
            }
            TouchZone::Cylinder { radius, half_length } => p.z.abs() <= *half_length && p.x.hypot(p.y) <= *radius,
            TouchZone::Box { half_extents } => p.coords.iter().zip(half_extents.iter()).all(|(x, h)| x.abs() <= *h),
            TouchZone::Ellipsoid { radii } => p.coords.component_div(radii).norm_squared() <= 1.0,
        }
    }

    /// Refuses sizes that are not positive and finite.
    fn validate(&self) -> Result<()> {
        let sizes: Vec<f64> = match self {
            TouchZone::Sphere { radius } => vec![*radius],
            TouchZone::Capsule { radius, half_length } | TouchZone::Cylinder { radius, half_length } => {
                vec![*radius, *half_length]
            }
            TouchZone::Box { half_extents: v } | TouchZone::Ellipsoid { radii: v } => v.iter().copied().collect(),
        };
        if sizes.iter().all(|s| s.is_finite() && *s > 0.0) {
            Ok(())
        } else {
            Err(Error::Invalid { what: "a touch zone", problem: format!("{self:?} needs positive, finite sizes") })
        }
    }
}

/// The normal forces pressing on an object in the last step: the sum of the normal
/// components of the forces of its contacts (each counted when it pushes, as MuJoCo's
/// `touch`), all of them or only those whose contact point lies in a zone fixed on the
/// object ([`within`](Self::within)). Attaching it turns on the world's contact
/// feedback, as [`ContactForces`](super::ContactForces) does. The contact points are
/// those of the collision pass at the start of the step; the zone is placed with the
/// object's pose at the end of it.
#[derive(Clone, Debug)]
pub struct Touch {
    object: ObjectId,
    zone: Option<(TouchZone, Isometry3<f64>)>,
}

impl Touch {
    /// A touch sensor feeling every contact on `object`.
    pub fn new(object: ObjectId) -> Self {
        Touch { object, zone: None }
    }

    /// Feels only the contacts whose point lies in `zone`, placed at `offset` from the
    /// object's origin (its centre of mass), in the object's frame.
    #[must_use]
    pub fn within(mut self, zone: TouchZone, offset: Isometry3<f64>) -> Self {
        self.zone = Some((zone, offset));
        self
    }
}

/// A [`Touch`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TouchReading {
    /// Contact points counted.
    pub contacts: usize,
    /// The sum of their normal forces, N (never negative).
    pub normal_force: f64,
}

impl Record for TouchReading {
    fn columns() -> Vec<&'static str> {
        vec!["contacts [1]", "normal force [N]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.contacts as f64), Some(self.normal_force)]
    }
}

impl Sensor for Touch {
    type Record = TouchReading;
    fn attach(&mut self, scene: &mut Scene) -> Result<()> {
        if let Some((zone, _)) = &self.zone {
            zone.validate()?;
        }
        scene.world_mut().set_contact_feedback(true);
        Ok(())
    }
    fn measure(&mut self, sim: &Scene) -> Result<TouchReading> {
        let object = sim.object(self.object)?;
        // The zone in the world, as the map from the world into it.
        let into_zone = match &self.zone {
            Some((zone, offset)) => Some((zone, (sim.pose(self.object)? * offset).inverse())),
            None => None,
        };
        let mut reading = TouchReading { contacts: 0, normal_force: 0.0 };
        for c in sim.world().contacts() {
            let (first, second) = super::body::sides_touched(c, &object);
            // The force on geom 1 along the normal into it, or the same on geom 2: the
            // push between the two.
            let push = c.force.dot(&c.normal);
            if !(first || second) || push <= 0.0 {
                continue;
            }
            if let Some((zone, into)) = &into_zone
                && !zone.contains(&(into * c.position))
            {
                continue;
            }
            reading.contacts += 1;
            reading.normal_force += push;
        }
        Ok(reading)
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        self.zone.map(|(zone, pose)| SensorSettings::Touch { zone, pose })
    }
}

#[cfg(test)]
mod tests {
    use super::TouchZone;
    use nalgebra::{Point3, Vector3};

    #[test]
    fn zones_hold_what_is_inside_them_with_their_axis_along_z() {
        let inside_outside = |zone: TouchZone, inside: [f64; 3], outside: [f64; 3]| {
            assert!(zone.contains(&Point3::from(inside)), "{zone:?} holds {inside:?}");
            assert!(!zone.contains(&Point3::from(outside)), "{zone:?} lacks {outside:?}");
        };
        inside_outside(TouchZone::Sphere { radius: 1.0 }, [0.6, 0.6, 0.5], [0.6, 0.6, 0.6]);
        let capsule = TouchZone::Capsule { radius: 0.5, half_length: 1.0 };
        inside_outside(capsule, [0.0, 0.0, 1.45], [0.4, 0.0, 1.4]);
        let cylinder = TouchZone::Cylinder { radius: 0.5, half_length: 1.0 };
        inside_outside(cylinder, [0.3, 0.39, 0.99], [0.0, 0.0, 1.01]);
        let block = TouchZone::Box { half_extents: Vector3::new(1.0, 2.0, 3.0) };
        inside_outside(block, [-1.0, 2.0, -3.0], [0.0, 2.01, 0.0]);
        let ellipsoid = TouchZone::Ellipsoid { radii: Vector3::new(1.0, 2.0, 3.0) };
        inside_outside(ellipsoid, [0.0, 0.0, 2.99], [0.8, 1.4, 0.0]);
        assert!(TouchZone::Sphere { radius: 0.0 }.validate().is_err());
    }
}
