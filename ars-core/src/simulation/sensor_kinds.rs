//! Sensors made from a kind's name and what they read: how scene files save sensors
//! and how the Python package declares them, in one place.

use super::Simulation;
use crate::error::{Error, Result};
use crate::handle::{JointId, ObjectId};
use crate::sensors::{
    Accelerometer, AnySensorId, ContactSensor, CsvColumns, Gps, HingeSensor, Imu, Inclinometer, JointForce,
    JointPositions, JointPower, JointReaction, JointTorque, KineticEnergy, PotentialEnergy, Sensor, SystemTotalEnergy,
    TotalEnergy, Velometer,
};

/// The kinds [`Simulation::add_sensor_of_kind`] makes (the sensors' type names): on
/// one object, on one joint, on a list of joints (`JointPositions`), or on the whole
/// simulation (`SystemTotalEnergy`).
pub const SENSOR_KINDS: [&str; 16] = [
    "Gps",
    "Velometer",
    "Accelerometer",
    "Inclinometer",
    "Imu",
    "ContactSensor",
    "KineticEnergy",
    "PotentialEnergy",
    "TotalEnergy",
    "SystemTotalEnergy",
    "HingeSensor",
    "JointTorque",
    "JointForce",
    "JointPower",
    "JointReaction",
    "JointPositions",
];

impl Simulation {
    /// Adds a sensor of `kind` (one of [`SENSOR_KINDS`]) reading `objects` and `joints`,
    /// sampled after every step or every `period` seconds.
    pub fn add_sensor_of_kind(
        &mut self,
        kind: &str,
        objects: &[ObjectId],
        joints: &[JointId],
        period: Option<f64>,
    ) -> Result<AnySensorId> {
        let wrong = |what: &str| Error::Invalid {
            what: "a sensor",
            problem: format!(
                "of kind {kind} reads {what}; it was given {} objects and {} joints",
                objects.len(),
                joints.len()
            ),
        };
        let object = || match objects {
            [o] if joints.is_empty() => Ok(*o),
            _ => Err(wrong("one object")),
        };
        let joint = || match joints {
            [j] if objects.is_empty() => Ok(*j),
            _ => Err(wrong("one joint")),
        };
        match kind {
            "Gps" => self.add_any(Gps::new(object()?), period),
            "Velometer" => self.add_any(Velometer::new(object()?), period),
            "Accelerometer" => self.add_any(Accelerometer::new(object()?), period),
            "Inclinometer" => self.add_any(Inclinometer::new(object()?), period),
            "Imu" => self.add_any(Imu::new(object()?), period),
            "ContactSensor" => self.add_any(ContactSensor::new(object()?), period),
            "KineticEnergy" => self.add_any(KineticEnergy::new(object()?), period),
            "PotentialEnergy" => self.add_any(PotentialEnergy::new(object()?), period),
            "TotalEnergy" => self.add_any(TotalEnergy::new(object()?), period),
            "SystemTotalEnergy" if objects.is_empty() && joints.is_empty() => {
                self.add_any(SystemTotalEnergy::new(), period)
            }
            "SystemTotalEnergy" => Err(wrong("nothing")),
            "HingeSensor" => self.add_any(HingeSensor::new(joint()?), period),
            "JointTorque" => self.add_any(JointTorque::new(joint()?), period),
            "JointForce" => self.add_any(JointForce::new(joint()?), period),
            "JointPower" => self.add_any(JointPower::new(joint()?), period),
            "JointReaction" => self.add_any(JointReaction::new(joint()?), period),
            "JointPositions" if objects.is_empty() => {
                let sensor = JointPositions::new(self, joints)?;
                self.add_any(sensor, period)
            }
            "JointPositions" => Err(wrong("joints only")),
            other => Err(Error::UnknownKind {
                what: "sensor kind",
                name: other.to_string(),
                known: SENSOR_KINDS.iter().map(|k| k.to_string()).collect(),
            }),
        }
    }

    fn add_any<S: Sensor>(&mut self, sensor: S, period: Option<f64>) -> Result<AnySensorId> {
        let id = match period {
            Some(p) => self.add_sensor_every(sensor, p)?,
            None => self.add_sensor(sensor)?,
        };
        Ok(id.into())
    }

    /// One sensor's records, whatever its type: the type's name (`"Gps"`) and its log
    /// seen through its CSV columns.
    pub fn sensor_table(&self, id: impl Into<AnySensorId>) -> Result<(String, &dyn CsvColumns)> {
        self.sensors.table(id.into())
    }

    /// Removes a sensor, whatever its type, with its records (a typed id's records
    /// come back from [`remove_sensor`](Self::remove_sensor)).
    pub fn remove_any_sensor(&mut self, id: impl Into<AnySensorId>) -> Result<()> {
        self.sensors.remove_any(id.into())
    }

    /// Forgets a sensor's records so far, whatever its type.
    pub fn clear_any_records(&mut self, id: impl Into<AnySensorId>) -> Result<()> {
        self.sensors.clear_any(id.into())
    }

    /// Whether a sensor, whatever its type, stopped sampling because an object or
    /// joint it reads was removed.
    pub fn is_any_sensor_detached(&self, id: impl Into<AnySensorId>) -> Result<bool> {
        self.sensors.is_detached_any(id.into())
    }
}
