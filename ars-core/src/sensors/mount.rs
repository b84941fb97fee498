//! Where a sensor that looks around is placed: in the world, or on an object.

use nalgebra::Isometry3;

use crate::error::Result;
use crate::handle::{BodyHandle, ObjectId};
use crate::scene::Scene;

/// Where a scanning sensor (a lidar, a camera) sits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mount {
    /// Fixed in the world at this pose.
    World(Isometry3<f64>),
    /// On an object, at this offset from its origin: it moves with the object, and does
    /// not see the object's own body.
    Object(ObjectId, Isometry3<f64>),
}

impl Default for Mount {
    fn default() -> Self {
        Mount::World(Isometry3::identity())
    }
}

impl Mount {
    /// The sensor's pose in the world now.
    pub fn pose(&self, scene: &Scene) -> Result<Isometry3<f64>> {
        match self {
            Mount::World(pose) => Ok(*pose),
            Mount::Object(object, offset) => Ok(scene.pose(*object)? * offset),
        }
    }

    /// The body the sensor is on (its rays skip it).
    pub fn own_body(&self, scene: &Scene) -> Result<Option<BodyHandle>> {
        match self {
            Mount::World(_) => Ok(None),
            Mount::Object(object, _) => Ok(scene.object(*object)?.body_handle()),
        }
    }

    /// The pose in the world, or relative to the object it is on.
    pub fn offset(&self) -> Isometry3<f64> {
        match self {
            Mount::World(pose) | Mount::Object(_, pose) => *pose,
        }
    }

    /// The objects the sensor reads (for [`Sensor::objects`](super::Sensor::objects)).
    pub fn objects(&self) -> Vec<ObjectId> {
        match self {
            Mount::World(_) => Vec::new(),
            Mount::Object(object, _) => vec![*object],
        }
    }
}
