//! Sensors made from a kind's name and what they read: how scene files save sensors
//! and how the Python package declares them, in one place.

use super::Simulation;
use crate::error::{Error, Result};
use crate::handle::{JointId, ObjectId};
use crate::sensors::{
    Accelerometer, AnySensorId, ContactForces, ContactSensor, CsvColumns, DepthCamera, Gps, HingeSensor, Imu,
    Inclinometer, JointForce, JointPositions, JointPower, JointReaction, JointTorque, JointVelocities, KineticEnergy,
    Lidar, Magnetometer, Momentum, Noisy, Orientation, Perturb, PotentialEnergy, Sensor, SensorKind, SensorSettings,
    SystemTotalEnergy, TotalEnergy, Touch, Velocimeter, Velometer,
};

impl Simulation {
    /// Adds a sensor of `kind` reading `objects` and `joints` (as the kind's
    /// [`target`](SensorKind::target) says), sampled after every step or every `period`
    /// seconds. A lidar or a depth camera needs its settings: make it with
    /// [`add_sensor`](Self::add_sensor).
    pub fn add_sensor_of_kind(
        &mut self,
        kind: SensorKind,
        objects: &[ObjectId],
        joints: &[JointId],
        period: Option<f64>,
    ) -> Result<AnySensorId> {
        self.add_sensor_described(kind, objects, joints, period, None, None)
    }

    /// [`add_sensor_of_kind`](Self::add_sensor_of_kind), and also lidars and depth
    /// cameras from their `settings`, each wrapped in seeded noise when `noise` (standard
    /// deviation, generator state) is given: what scene files rebuild.
    // table: one match arm per sensor kind (and its settings), each a constructor call
    pub(crate) fn add_sensor_described(
        &mut self,
        kind: SensorKind,
        objects: &[ObjectId],
        joints: &[JointId],
        period: Option<f64>,
        noise: Option<(f64, u64)>,
        settings: Option<&SensorSettings>,
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
        if noise.is_some() && !kind.takes_noise() {
            return Err(Error::Invalid { what: "a sensor", problem: format!("of kind {kind} cannot be given noise") });
        }
        use SensorKind as K;
        match (kind, settings) {
            (K::Lidar, Some(SensorSettings::Lidar { beams, fov, min_range, max_range, elevations, pose })) => {
                let lidar = Lidar::new(*beams, *fov, *max_range)?.min_range(*min_range)?.planes(elevations)?;
                let lidar = match objects {
                    [] => lidar.at(*pose),
                    [o] => lidar.on(*o, *pose),
                    _ => return Err(wrong("at most one object")),
                };
                self.add_noisy(lidar, period, noise)
            }
            (K::DepthCamera, Some(SensorSettings::DepthCamera { width, height, fov_y, near, far, pose })) => {
                let camera = DepthCamera::new(*width, *height, *fov_y, *near, *far)?;
                let camera = match objects {
                    [] => camera.at(*pose),
                    [o] => camera.on(*o, *pose),
                    _ => return Err(wrong("at most one object")),
                };
                self.add_any(camera, period)
            }
            (K::Gps, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Gps::new(object()?).at(pose.translation.vector), period, noise)
            }
            (K::Velometer, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Velometer::new(object()?).at(pose.translation.vector), period, noise)
            }
            (K::Velocimeter, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Velocimeter::new(object()?).at(*pose), period, noise)
            }
            (K::Accelerometer, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Accelerometer::new(object()?).at(pose.translation.vector), period, noise)
            }
            (K::Orientation, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Orientation::new(object()?).at(pose.rotation), period, noise)
            }
            (K::Imu, Some(SensorSettings::Offset { pose })) => {
                self.add_noisy(Imu::new(object()?).at(*pose), period, noise)
            }
            (K::Magnetometer, Some(SensorSettings::Magnetometer { field, pose })) => {
                self.add_noisy(Magnetometer::new(object()?, *field)?.at(*pose), period, noise)
            }
            (K::Touch, Some(SensorSettings::Touch { zone, pose })) => {
                self.add_noisy(Touch::new(object()?).within(*zone, *pose), period, noise)
            }
            (_, Some(settings)) => Err(Error::Invalid {
                what: "a sensor",
                problem: format!("of kind {kind} cannot take the settings {settings:?}"),
            }),
            (K::Gps, _) => self.add_noisy(Gps::new(object()?), period, noise),
            (K::Velometer, _) => self.add_noisy(Velometer::new(object()?), period, noise),
            (K::Velocimeter, _) => self.add_noisy(Velocimeter::new(object()?), period, noise),
            (K::Accelerometer, _) => self.add_noisy(Accelerometer::new(object()?), period, noise),
            (K::Inclinometer, _) => self.add_noisy(Inclinometer::new(object()?), period, noise),
            (K::Imu, _) => self.add_noisy(Imu::new(object()?), period, noise),
            (K::Orientation, _) => self.add_noisy(Orientation::new(object()?), period, noise),
            (K::Touch, _) => self.add_noisy(Touch::new(object()?), period, noise),
            (K::Magnetometer, _) => {
                self.add_noisy(Magnetometer::new(object()?, Magnetometer::MUJOCO_DEFAULT_FIELD)?, period, noise)
            }
            (K::ContactSensor, _) => self.add_noisy(ContactSensor::new(object()?), period, noise),
            (K::ContactForces, _) => self.add_noisy(ContactForces::new(object()?), period, noise),
            (K::KineticEnergy, _) => self.add_noisy(KineticEnergy::new(object()?), period, noise),
            (K::PotentialEnergy, _) => self.add_noisy(PotentialEnergy::new(object()?), period, noise),
            (K::TotalEnergy, _) => self.add_noisy(TotalEnergy::new(object()?), period, noise),
            (K::SystemTotalEnergy, _) if objects.is_empty() && joints.is_empty() => {
                self.add_noisy(SystemTotalEnergy::new(), period, noise)
            }
            (K::SystemTotalEnergy, _) => Err(wrong("nothing")),
            (K::HingeSensor, _) => self.add_noisy(HingeSensor::new(joint()?), period, noise),
            (K::JointTorque, _) => self.add_noisy(JointTorque::new(joint()?), period, noise),
            (K::JointForce, _) => self.add_noisy(JointForce::new(joint()?), period, noise),
            (K::JointPower, _) => self.add_noisy(JointPower::new(joint()?), period, noise),
            (K::JointReaction, _) => self.add_noisy(JointReaction::new(joint()?), period, noise),
            (K::JointPositions, _) if objects.is_empty() => {
                let sensor = JointPositions::new(&self.scene, joints)?;
                self.add_any(sensor, period)
            }
            (K::JointPositions, _) => Err(wrong("joints only")),
            (K::JointVelocities, _) if objects.is_empty() => {
                let sensor = JointVelocities::new(&self.scene, joints)?;
                self.add_any(sensor, period)
            }
            (K::JointVelocities, _) => Err(wrong("joints only")),
            (K::Momentum, _) if joints.is_empty() => self.add_noisy(Momentum::new(objects)?, period, noise),
            (K::Momentum, _) => Err(wrong("objects only")),
            (K::Lidar | K::DepthCamera, None) => Err(Error::Invalid {
                what: "a sensor",
                problem: format!("of kind {kind} is made from its settings (range, field of view, pose)"),
            }),
        }
    }

    /// `sensor`, wrapped in noise when `noise` (standard deviation, generator state) is given.
    fn add_noisy<S: Sensor>(&mut self, sensor: S, period: Option<f64>, noise: Option<(f64, u64)>) -> Result<AnySensorId>
    where
        S::Record: Perturb,
    {
        match noise {
            None => self.add_any(sensor, period),
            Some((std_dev, seed)) => self.add_any(Noisy::new(sensor, std_dev, seed)?, period),
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
