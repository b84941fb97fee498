//! The kinds of ARS sensor by name: the one list that scene files, MJCF models and the
//! Python package read when they make a sensor from a name.

use std::fmt;
use std::str::FromStr;

use crate::error::Error;

/// What a sensor of a [`SensorKind`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorTarget {
    /// One object.
    Object,
    /// One joint.
    Joint,
    /// A list of joints.
    Joints,
    /// A list of objects.
    Objects,
    /// The whole simulation.
    Simulation,
    /// A pose in the world, or on at most one object, given with its settings.
    Mount,
}

/// A kind of ARS sensor, named as its type (`Gps`, `JointPositions`): what
/// [`Simulation::add_sensor_of_kind`](crate::Simulation::add_sensor_of_kind) makes and
/// scene files save. Parsed from its type's name (`"Gps".parse()`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SensorKind {
    /// [`Gps`](super::Gps).
    Gps,
    /// [`Velometer`](super::Velometer).
    Velometer,
    /// [`Velocimeter`](super::Velocimeter).
    Velocimeter,
    /// [`Accelerometer`](super::Accelerometer).
    Accelerometer,
    /// [`Orientation`](super::Orientation).
    Orientation,
    /// [`Inclinometer`](super::Inclinometer).
    Inclinometer,
    /// [`Imu`](super::Imu).
    Imu,
    /// [`ContactSensor`](super::ContactSensor).
    ContactSensor,
    /// [`ContactForces`](super::ContactForces).
    ContactForces,
    /// [`Touch`](super::Touch).
    Touch,
    /// [`KineticEnergy`](super::KineticEnergy).
    KineticEnergy,
    /// [`PotentialEnergy`](super::PotentialEnergy).
    PotentialEnergy,
    /// [`TotalEnergy`](super::TotalEnergy).
    TotalEnergy,
    /// [`SystemTotalEnergy`](super::SystemTotalEnergy).
    SystemTotalEnergy,
    /// [`HingeSensor`](super::HingeSensor).
    HingeSensor,
    /// [`JointTorque`](super::JointTorque).
    JointTorque,
    /// [`JointForce`](super::JointForce).
    JointForce,
    /// [`JointPower`](super::JointPower).
    JointPower,
    /// [`JointReaction`](super::JointReaction).
    JointReaction,
    /// [`JointPositions`](super::JointPositions).
    JointPositions,
    /// [`JointVelocities`](super::JointVelocities).
    JointVelocities,
    /// [`Momentum`](super::Momentum).
    Momentum,
    /// [`Magnetometer`](super::Magnetometer) (in MuJoCo's default field unless its
    /// settings give one).
    Magnetometer,
    /// [`Lidar`](super::Lidar): made from its settings only.
    Lidar,
    /// [`DepthCamera`](super::DepthCamera): made from its settings only.
    DepthCamera,
}

impl SensorKind {
    /// Every kind, in this order.
    pub const ALL: [SensorKind; 25] = [
        SensorKind::Gps,
        SensorKind::Velometer,
        SensorKind::Velocimeter,
        SensorKind::Accelerometer,
        SensorKind::Orientation,
        SensorKind::Inclinometer,
        SensorKind::Imu,
        SensorKind::ContactSensor,
        SensorKind::ContactForces,
        SensorKind::Touch,
        SensorKind::KineticEnergy,
        SensorKind::PotentialEnergy,
        SensorKind::TotalEnergy,
        SensorKind::SystemTotalEnergy,
        SensorKind::HingeSensor,
        SensorKind::JointTorque,
        SensorKind::JointForce,
        SensorKind::JointPower,
        SensorKind::JointReaction,
        SensorKind::JointPositions,
        SensorKind::JointVelocities,
        SensorKind::Momentum,
        SensorKind::Magnetometer,
        SensorKind::Lidar,
        SensorKind::DepthCamera,
    ];

    /// The kinds made from what they read alone, without settings (every kind but
    /// [`Lidar`](Self::Lidar) and [`DepthCamera`](Self::DepthCamera)).
    pub fn from_targets() -> impl Iterator<Item = SensorKind> {
        SensorKind::ALL.into_iter().filter(|k| k.target() != SensorTarget::Mount)
    }

    /// Its sensor type's name, as scene files and sensor tables write it (`"Gps"`).
    pub const fn name(self) -> &'static str {
        match self {
            SensorKind::Gps => "Gps",
            SensorKind::Velometer => "Velometer",
            SensorKind::Velocimeter => "Velocimeter",
            SensorKind::Accelerometer => "Accelerometer",
            SensorKind::Orientation => "Orientation",
            SensorKind::Inclinometer => "Inclinometer",
            SensorKind::Imu => "Imu",
            SensorKind::ContactSensor => "ContactSensor",
            SensorKind::ContactForces => "ContactForces",
            SensorKind::Touch => "Touch",
            SensorKind::KineticEnergy => "KineticEnergy",
            SensorKind::PotentialEnergy => "PotentialEnergy",
            SensorKind::TotalEnergy => "TotalEnergy",
            SensorKind::SystemTotalEnergy => "SystemTotalEnergy",
            SensorKind::HingeSensor => "HingeSensor",
            SensorKind::JointTorque => "JointTorque",
            SensorKind::JointForce => "JointForce",
            SensorKind::JointPower => "JointPower",
            SensorKind::JointReaction => "JointReaction",
            SensorKind::JointPositions => "JointPositions",
            SensorKind::JointVelocities => "JointVelocities",
            SensorKind::Momentum => "Momentum",
            SensorKind::Magnetometer => "Magnetometer",
            SensorKind::Lidar => "Lidar",
            SensorKind::DepthCamera => "DepthCamera",
        }
    }

    /// What a sensor of this kind reads.
    pub const fn target(self) -> SensorTarget {
        match self {
            SensorKind::SystemTotalEnergy => SensorTarget::Simulation,
            SensorKind::HingeSensor
            | SensorKind::JointTorque
            | SensorKind::JointForce
            | SensorKind::JointPower
            | SensorKind::JointReaction => SensorTarget::Joint,
            SensorKind::JointPositions | SensorKind::JointVelocities => SensorTarget::Joints,
            SensorKind::Momentum => SensorTarget::Objects,
            SensorKind::Lidar | SensorKind::DepthCamera => SensorTarget::Mount,
            _ => SensorTarget::Object,
        }
    }

    /// Whether its records can be given Gaussian noise ([`Noisy`](super::Noisy)).
    pub const fn takes_noise(self) -> bool {
        !matches!(self, SensorKind::JointPositions | SensorKind::JointVelocities | SensorKind::DepthCamera)
    }

    /// The kind of a sensor type's name, also when wrapped in noise (`"Gps"` and
    /// `"Noisy<Gps>"`); `None` for a type that is no kind (a laser, your own type).
    pub fn of_type_name(type_name: &str) -> Option<SensorKind> {
        let name = type_name.strip_prefix("Noisy<").and_then(|k| k.strip_suffix('>')).unwrap_or(type_name);
        SensorKind::ALL.into_iter().find(|k| k.name() == name)
    }
}

impl fmt::Display for SensorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SensorKind {
    type Err = Error;

    /// The kind named by its type's name (`"Gps"`); an unknown name is an
    /// [`Error::UnknownKind`] listing the kinds made without settings.
    fn from_str(name: &str) -> Result<SensorKind, Error> {
        SensorKind::ALL.into_iter().find(|k| k.name() == name).ok_or_else(|| Error::UnknownKind {
            what: "sensor kind",
            name: name.to_string(),
            known: SensorKind::from_targets().map(|k| k.name().to_string()).collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_parsed_from_its_name_and_only_lidars_and_cameras_need_settings() {
        for kind in SensorKind::ALL {
            assert_eq!(kind.name().parse::<SensorKind>().unwrap(), kind);
            assert_eq!(SensorKind::of_type_name(&format!("Noisy<{kind}>")), Some(kind));
        }
        let with_settings: Vec<_> = SensorKind::ALL.into_iter().filter(|k| k.target() == SensorTarget::Mount).collect();
        assert_eq!(with_settings, [SensorKind::Lidar, SensorKind::DepthCamera]);
        assert_eq!(SensorKind::from_targets().count(), 23);
        assert!("Gpss".parse::<SensorKind>().is_err());
        assert_eq!(SensorKind::of_type_name("Laser"), None);
    }
}
