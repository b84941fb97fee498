//! The sensor behind `/joint_states`: every named joint that has a position, read at
//! the end of a step, with the efforts put on it during that step (they are cleared
//! once the step's sensors have sampled, so only a sensor sees them).

use std::sync::Arc;

use ars_core::sensors::{Record, Sensor};
use ars_core::{JointId, JointType, Result, Scene};

/// Position, velocity and effort of a list of joints, in the order of their names.
#[derive(Clone, Debug, PartialEq)]
pub struct JointStatesReading {
    /// The joints' names (shared by every reading).
    pub names: Arc<[String]>,
    /// Positions, rad or m (a joint's first degree of freedom).
    pub position: Vec<f64>,
    /// Rates, rad/s or m/s.
    pub velocity: Vec<f64>,
    /// Torques (N·m) or forces (N) put on each during the step: added through the API,
    /// by friction and springs and by controllers (what
    /// [`JointTorque`](ars_core::sensors::JointTorque) records).
    pub effort: Vec<f64>,
}

impl Record for JointStatesReading {
    fn columns() -> Vec<&'static str> {
        Vec::new()
    }
    fn values(&self) -> Vec<Option<f64>> {
        [&self.position, &self.velocity, &self.effort].into_iter().flatten().map(|x| Some(*x)).collect()
    }
    fn headers(&self) -> Vec<String> {
        let columns = [("position", "rad or m"), ("velocity", "rad/s or m/s"), ("effort", "N m or N")];
        columns.iter().flat_map(|(what, unit)| self.names.iter().map(move |n| format!("{n} {what} [{unit}]"))).collect()
    }
}

/// Reads every joint of a scene with a position (hinges, sliders, pistons and
/// universal joints; not fixed or ball joints), in the alphabetical order of their
/// names, as the scene was when the sensor was made.
#[derive(Clone, Debug)]
pub struct JointStates {
    joints: Vec<JointId>,
    names: Arc<[String]>,
}

impl JointStates {
    /// Every joint of `scene` with a position.
    pub fn of(scene: &Scene) -> JointStates {
        let moving =
            |t: JointType| matches!(t, JointType::Hinge | JointType::Slider | JointType::Piston | JointType::Universal);
        let (names, joints): (Vec<String>, Vec<JointId>) = scene
            .joints()
            .filter(|(_, id)| scene.joint(*id).is_ok_and(|j| moving(j.joint_type())))
            .map(|(name, id)| (name.to_string(), id))
            .unzip();
        JointStates { joints, names: names.into() }
    }

    /// The joints' names, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The joints, in the order of [`names`](Self::names).
    pub fn joint_ids(&self) -> &[JointId] {
        &self.joints
    }

    /// The joints' names and ids, in order: what ros2_control's forward command
    /// controllers index (one value per joint of `/joint_states`).
    pub fn named_joints(&self) -> Vec<(String, JointId)> {
        self.names.iter().cloned().zip(self.joints.iter().copied()).collect()
    }
}

impl Sensor for JointStates {
    type Record = JointStatesReading;

    fn measure(&mut self, scene: &Scene) -> Result<JointStatesReading> {
        let n = self.joints.len();
        let mut reading = JointStatesReading {
            names: self.names.clone(),
            position: Vec::with_capacity(n),
            velocity: Vec::with_capacity(n),
            effort: Vec::with_capacity(n),
        };
        for id in &self.joints {
            let state = scene.joint_state(*id)?;
            reading.position.push(state.position);
            reading.velocity.push(state.rate);
            reading.effort.push(scene.joint_efforts(*id)?.total());
        }
        Ok(reading)
    }

    fn joints(&self) -> Vec<JointId> {
        self.joints.clone()
    }

    /// Stateless: measured only when a sample is due (not at every step).
    fn measures_every_step(&self) -> bool {
        false
    }
}
