//! Joint sensors: angle and rate, the torque, force and power applied through the API,
//! and the reaction the joint exerts.

use nalgebra::Vector3;

use super::{Record, Sensor};
use crate::control::JointState;
use crate::error::{Error, Result};
use crate::handle::JointId;
use crate::scene::{JointType, Scene};

/// Angle and rate of a hinge (after the step).
#[derive(Clone, Debug)]
pub struct HingeSensor {
    joint: JointId,
}

impl HingeSensor {
    /// On `joint`.
    pub fn new(joint: JointId) -> Self {
        HingeSensor { joint }
    }
}

/// A [`HingeSensor`] measurement.
pub type HingeReading = JointState;

impl Record for JointState {
    fn columns() -> Vec<&'static str> {
        vec!["angle [rad]", "angle rate [rad/s]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.position), Some(self.rate)]
    }
}

impl Sensor for HingeSensor {
    type Record = JointState;
    fn attach(&mut self, sim: &mut Scene) -> Result<()> {
        expect_type(sim, self.joint, &[JointType::Hinge], "a hinge sensor")
    }
    fn measure(&mut self, sim: &Scene) -> Result<JointState> {
        sim.joint_state(self.joint)
    }
    fn joints(&self) -> Vec<JointId> {
        vec![self.joint]
    }
}

fn expect_type(sim: &Scene, joint: JointId, types: &[JointType], operation: &'static str) -> Result<()> {
    let t = sim.joint(joint)?.joint_type();
    if types.contains(&t) { Ok(()) } else { Err(Error::WrongJointKind { operation, kind: t.default_name() }) }
}

/// Torque (hinge) or force (slider) added through the API during a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effort {
    /// N·m for a hinge, N for a slider.
    pub value: f64,
}

/// The torque added to a hinge during each step through
/// [`SimJoint::add_torque`](crate::SimJoint::add_torque), its friction and its
/// controller, summed (the original recorded each call).
#[derive(Clone, Debug)]
pub struct JointTorque {
    joint: JointId,
}

impl JointTorque {
    /// On `joint`.
    pub fn new(joint: JointId) -> Self {
        JointTorque { joint }
    }
}

impl Sensor for JointTorque {
    type Record = Effort;
    fn attach(&mut self, sim: &mut Scene) -> Result<()> {
        expect_type(sim, self.joint, &[JointType::Hinge, JointType::Universal], "a joint torque sensor")
    }
    fn measure(&mut self, sim: &Scene) -> Result<Effort> {
        Ok(Effort { value: sim.joint_efforts(self.joint)?.total() })
    }
    fn joints(&self) -> Vec<JointId> {
        vec![self.joint]
    }
}

/// The force added to a slider during each step through the API.
#[derive(Clone, Debug)]
pub struct JointForce {
    joint: JointId,
}

impl JointForce {
    /// On `joint`.
    pub fn new(joint: JointId) -> Self {
        JointForce { joint }
    }
}

impl Record for Effort {
    fn columns() -> Vec<&'static str> {
        vec!["torque or force [N m or N]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.value)]
    }
}

impl Sensor for JointForce {
    type Record = Effort;
    fn attach(&mut self, sim: &mut Scene) -> Result<()> {
        expect_type(sim, self.joint, &[JointType::Slider, JointType::Piston], "a joint force sensor")
    }
    fn measure(&mut self, sim: &Scene) -> Result<Effort> {
        Ok(Effort { value: sim.joint_efforts(self.joint)?.total() })
    }
    fn joints(&self) -> Vec<JointId> {
        vec![self.joint]
    }
}

/// Power of the torques (forces) put on a joint during a step (added through the API,
/// by friction and by its controller): their sum times the joint rate at the start of
/// the step.
#[derive(Clone, Debug)]
pub struct JointPower {
    joint: JointId,
    rate_before: f64,
}

impl JointPower {
    /// On `joint`.
    pub fn new(joint: JointId) -> Self {
        JointPower { joint, rate_before: 0.0 }
    }
}

/// A [`JointPower`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Power {
    /// Power, W.
    pub power: f64,
}

impl Record for Power {
    fn columns() -> Vec<&'static str> {
        vec!["power [W]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.power)]
    }
}

impl Sensor for JointPower {
    type Record = Power;
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        self.rate_before = sim.joint_state(self.joint)?.rate;
        Ok(())
    }
    fn measure(&mut self, sim: &Scene) -> Result<Power> {
        Ok(Power { power: sim.joint_efforts(self.joint)?.total() * self.rate_before })
    }
    fn joints(&self) -> Vec<JointId> {
        vec![self.joint]
    }
}

/// Force and torque a joint exerted on its first object during the last step (world
/// frame, at the object's centre of mass): a force-torque sensor.
#[derive(Clone, Debug)]
pub struct JointReaction {
    joint: JointId,
}

impl JointReaction {
    /// On `joint`.
    pub fn new(joint: JointId) -> Self {
        JointReaction { joint }
    }
}

/// A [`JointReaction`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reaction {
    /// Force on the first object, N.
    pub force: Vector3<f64>,
    /// Torque on the first object, N·m.
    pub torque: Vector3<f64>,
}

impl Record for Reaction {
    fn columns() -> Vec<&'static str> {
        vec!["fx [N]", "fy [N]", "fz [N]", "tx [N m]", "ty [N m]", "tz [N m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let (f, t) = (self.force, self.torque);
        vec![Some(f.x), Some(f.y), Some(f.z), Some(t.x), Some(t.y), Some(t.z)]
    }
}

impl Sensor for JointReaction {
    type Record = Reaction;
    fn measure(&mut self, sim: &Scene) -> Result<Reaction> {
        let fb = sim.joint(self.joint)?.reaction()?;
        Ok(Reaction { force: fb.force1, torque: fb.torque1 })
    }
    fn joints(&self) -> Vec<JointId> {
        vec![self.joint]
    }
}

/// The positions (angles, rad, or slider positions, m) of several joints, one column
/// per joint named after it: a robot's configuration.
///
/// ```
/// use ars_core::nalgebra::Vector3;
/// use ars_core::sensors::JointPositions;
/// use ars_core::{JointEnd, Mass, Simulation};
///
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0))?;
/// let pivot = sim.scene_mut().add_hinge_joint("pivot", ball, JointEnd::World, Some([0.0, 0.0, 0.0].into()), Vector3::z())?;
/// let q = sim.add_sensor(JointPositions::new(sim.scene(), &[pivot])?)?;
/// sim.step_n(100)?;
/// let mut csv = Vec::new();
/// sim.records(q)?.write_csv(&mut csv).unwrap();
/// assert!(String::from_utf8(csv).unwrap().starts_with("time [s],step,pivot\n"));
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct JointPositions(JointList);

impl JointPositions {
    /// Of `joints`, in this order (hinges, sliders, pistons, universals).
    pub fn new(scene: &Scene, joints: &[JointId]) -> Result<Self> {
        JointList::new(scene, joints).map(JointPositions)
    }
}

/// Joints read together, one column each named after it: what [`JointPositions`] and
/// [`JointVelocities`] share.
#[derive(Clone, Debug)]
struct JointList {
    joints: Vec<JointId>,
    names: std::sync::Arc<[String]>,
}

impl JointList {
    fn new(scene: &Scene, joints: &[JointId]) -> Result<Self> {
        let names = joints.iter().map(|j| Ok(scene.joint(*j)?.name().to_string())).collect::<Result<Vec<_>>>()?;
        Ok(JointList { joints: joints.to_vec(), names: names.into() })
    }

    /// What `read` takes of each joint's state, in order.
    fn read(&self, scene: &Scene, read: impl Fn(crate::control::JointState) -> f64) -> Result<Vec<f64>> {
        self.joints.iter().map(|j| Ok(read(scene.joint_state(*j)?))).collect()
    }
}

/// A [`JointPositions`] measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Positions {
    /// The positions, in the sensor's joint order.
    pub values: Vec<f64>,
    names: std::sync::Arc<[String]>,
}

impl Record for Positions {
    fn columns() -> Vec<&'static str> {
        Vec::new()
    }
    fn values(&self) -> Vec<Option<f64>> {
        self.values.iter().copied().map(Some).collect()
    }
    fn headers(&self) -> Vec<String> {
        self.names.to_vec()
    }
}

impl Sensor for JointPositions {
    type Record = Positions;
    fn measure(&mut self, sim: &Scene) -> Result<Positions> {
        Ok(Positions { values: self.0.read(sim, |s| s.position)?, names: self.0.names.clone() })
    }
    fn joints(&self) -> Vec<JointId> {
        self.0.joints.clone()
    }
}

/// The rates (rad/s, or m/s for a slider) of several joints, one column per joint named
/// after it: a robot's joint velocities (MJCF's `jointvel`).
///
/// ```
/// use ars_core::nalgebra::Vector3;
/// use ars_core::sensors::JointVelocities;
/// use ars_core::{JointEnd, Mass, Simulation};
///
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0))?;
/// let pivot = sim.scene_mut().add_hinge_joint("pivot", ball, JointEnd::World, Some([0.0, 0.0, 0.0].into()), Vector3::z())?;
/// let rates = sim.add_sensor(JointVelocities::new(sim.scene(), &[pivot])?)?;
/// sim.step_n(100)?;
/// let last = sim.records(rates)?.last().unwrap().record.values[0];
/// assert_eq!(last, sim.scene().joint(pivot)?.state()?.rate);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct JointVelocities(JointList);

impl JointVelocities {
    /// Of `joints`, in this order (hinges, sliders, pistons, universals).
    pub fn new(scene: &Scene, joints: &[JointId]) -> Result<Self> {
        JointList::new(scene, joints).map(JointVelocities)
    }
}

/// A [`JointVelocities`] measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Rates {
    /// The rates, in the sensor's joint order.
    pub values: Vec<f64>,
    names: std::sync::Arc<[String]>,
}

impl Record for Rates {
    fn columns() -> Vec<&'static str> {
        Vec::new()
    }
    fn values(&self) -> Vec<Option<f64>> {
        self.values.iter().copied().map(Some).collect()
    }
    fn headers(&self) -> Vec<String> {
        self.names.to_vec()
    }
}

impl Sensor for JointVelocities {
    type Record = Rates;
    fn measure(&mut self, sim: &Scene) -> Result<Rates> {
        Ok(Rates { values: self.0.read(sim, |s| s.rate)?, names: self.0.names.clone() })
    }
    fn joints(&self) -> Vec<JointId> {
        self.0.joints.clone()
    }
}
