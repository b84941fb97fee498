//! MuJoCo's mocap bodies: jointless children of the world that the user moves
//! (MuJoCo's `data.mocap_pos` and `data.mocap_quat`), each a kinematic ODE body. What a
//! `weld` or `connect` joins to one follows it; its geoms push what they touch.
//!
//! Moving one teleports it: its velocity stays zero, as a mocap body's is in MuJoCo,
//! so a contact with it sees a still body, and a weld to it pulls towards its new pose
//! at the joint's error correction.

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};

use crate::error::{Error, Result};
use crate::handle::ObjectId;

/// A mocap body of an MJCF model: its object (a kinematic body) and how the file's
/// pose of the body maps onto the object's pose in the simulation.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfMocap {
    /// The body's name in the file (with the model's prefix).
    pub body: String,
    /// Its object, whose body is kinematic.
    pub object: ObjectId,
    /// The file's world frame in the simulation (the model's placement: MJCF's Z-up
    /// turned to the simulation's Y-up, then the model's base pose).
    pub placement: Isometry3<f64>,
    /// The object's frame in the body's (at the body's centre of mass).
    pub offset: Isometry3<f64>,
}

impl MjcfMocap {
    /// The object's pose in the simulation when the body is at `position`, turned by
    /// `quaternion` (w, x, y, z; normalised, as MuJoCo normalises `mocap_quat`), both
    /// in the file's world frame.
    pub fn object_pose(&self, position: [f64; 3], quaternion: [f64; 4]) -> Result<Isometry3<f64>> {
        let what = "mocap pose";
        let position = crate::validate::vector(what, &Vector3::from(position))?;
        let [w, x, y, z] = quaternion;
        let q = Quaternion::new(w, x, y, z);
        if !q.coords.iter().all(|c| c.is_finite()) {
            return Err(Error::NotFinite { what, value: format!("{quaternion:?}") });
        }
        if q.norm() == 0.0 {
            return Err(Error::Invalid { what, problem: "its quaternion is zero".into() });
        }
        let body = Isometry3::from_parts(Translation3::from(position), UnitQuaternion::from_quaternion(q));
        Ok(self.placement * body * self.offset)
    }

    /// The body's pose in the file's world frame (position, quaternion w, x, y, z) when
    /// its object is at `object`.
    pub fn body_pose(&self, object: &Isometry3<f64>) -> ([f64; 3], [f64; 4]) {
        let body = self.placement.inverse() * object * self.offset.inverse();
        let p: Point3<f64> = body.translation.vector.into();
        let q = body.rotation.into_inner();
        ([p.x, p.y, p.z], [q.w, q.i, q.j, q.k])
    }
}
