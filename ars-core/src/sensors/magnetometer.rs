//! A magnetometer: a uniform magnetic field seen in a frame fixed on a body (MuJoCo's
//! `magnetometer`, which reads `<option magnetic>` at a site).

use nalgebra::{Isometry3, Vector3};

use super::{Record, Sensor, SensorSettings};
use crate::error::Result;
use crate::handle::ObjectId;
use crate::scene::Scene;

/// The world's magnetic field `field` (uniform, fixed in the world) in a frame fixed on
/// a body: `Rᵀ field`, `R` the frame's rotation in the world. The frame is the body's
/// own, or the one at [`at`](Self::at) from it.
#[derive(Clone, Debug)]
pub struct Magnetometer {
    object: ObjectId,
    offset: Isometry3<f64>,
    field: Vector3<f64>,
}

impl Magnetometer {
    /// MuJoCo's default field, `(0, −0.5, 0)` in its Z-up world (about the Earth's, in
    /// gauss): `(0, 0, 0.5)` in the simulation's Y-up world.
    pub const MUJOCO_DEFAULT_FIELD: Vector3<f64> = Vector3::new(0.0, 0.0, 0.5);

    /// On `object`, in its own frame, in the world's field `field` (any unit: the
    /// readings are in it).
    pub fn new(object: ObjectId, field: Vector3<f64>) -> Result<Self> {
        let field = crate::validate::vector("magnetic field", &field)?;
        Ok(Magnetometer { object, offset: Isometry3::identity(), field })
    }

    /// Reads in the frame at `offset` from the object's origin (in the object's frame).
    #[must_use]
    pub fn at(mut self, offset: Isometry3<f64>) -> Self {
        self.offset = offset;
        self
    }
}

/// A [`Magnetometer`] measurement: the field in the sensor's frame, in the unit the
/// field was given in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagneticField {
    /// The field.
    pub field: Vector3<f64>,
}

impl Record for MagneticField {
    fn columns() -> Vec<&'static str> {
        vec!["Bx", "By", "Bz"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        self.field.iter().map(|x| Some(*x)).collect()
    }
}

impl Sensor for Magnetometer {
    type Record = MagneticField;
    fn measure(&mut self, sim: &Scene) -> Result<MagneticField> {
        let b = sim.body(self.object)?;
        let turn = b.quaternion() * self.offset.rotation;
        Ok(MagneticField { field: turn.inverse() * self.field })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        Some(SensorSettings::Magnetometer { field: self.field, pose: self.offset })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::Mass;
    use crate::simulation::Simulation;
    use nalgebra::{Rotation3, UnitQuaternion};

    /// A box turned 90° about the world's y reads the field along its own axes; a
    /// second sensor turned back on it reads the world's; a saved scene keeps both.
    #[test]
    fn a_turned_body_reads_the_field_in_its_frame_and_a_saved_scene_keeps_it() {
        let mut sim = Simulation::new().unwrap();
        sim.scene_mut().world_mut().set_gravity([0.0; 3].into()).unwrap();
        let b = sim.scene_mut().add_box([0.1, 0.1, 0.1], [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        let turn = Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
        sim.scene_mut().set_rotation(b, turn).unwrap();
        let field = Vector3::new(0.3, -0.2, 0.5);
        let own = sim.add_sensor(Magnetometer::new(b, field).unwrap()).unwrap();
        let back = UnitQuaternion::from_rotation_matrix(&turn.inverse());
        let world = sim.add_sensor(
            Magnetometer::new(b, field)
                .unwrap()
                .at(Isometry3::from_parts(nalgebra::Translation3::new(0.1, 0.0, 0.0), back)),
        );
        let world = world.unwrap();
        sim.step().unwrap();
        let read = |sim: &Simulation, id: crate::sensors::SensorId<Magnetometer>| {
            sim.records(id).unwrap().last().unwrap().record.field
        };
        // Turned +90° about y: the body's x is the world's −z, its z the world's x.
        assert!((read(&sim, own) - Vector3::new(-0.5, -0.2, 0.3)).norm() < 1e-12, "{}", read(&sim, own));
        assert!((read(&sim, world) - field).norm() < 1e-12);
        let mut again = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
        again.step().unwrap();
        let ids = again.sensor_ids_of::<Magnetometer>();
        assert_eq!(ids.len(), 2, "both kept with their fields and frames");
        for (id, expected) in ids.into_iter().zip([Vector3::new(-0.5, -0.2, 0.3), field]) {
            assert!((read(&again, id) - expected).norm() < 1e-12);
        }
        assert!(Magnetometer::new(b, Vector3::new(f64::NAN, 0.0, 0.0)).is_err());
    }
}
