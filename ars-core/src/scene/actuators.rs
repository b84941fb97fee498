//! A scene's actuators as MuJoCo lists them: the joints an [`Actuator`] drives, in the
//! order they were attached (an MJCF file's, MuJoCo's `data.ctrl`), each control set by
//! name or all at once as one vector.

use super::Scene;
use crate::control::Actuator;
use crate::error::{Error, Result};
use crate::handle::JointId;

impl Scene {
    /// The [`Actuator`]s driving joints, by name, with their joints, in the order they
    /// were attached: an MJCF file's order, MuJoCo's `data.ctrl` order.
    pub fn actuators(&self) -> impl Iterator<Item = (&str, JointId)> + '_ {
        self.actuated_joints.iter().filter_map(|&id| Some((self.actuator_of(id)?.name(), id)))
    }

    /// Sets every actuator's control at once, `ctrl[i]` the control of the `i`-th of
    /// [`actuators`](Self::actuators) (clamped to its control range): MuJoCo's whole
    /// `data.ctrl`. A vector of another length, or a control that is not finite, is
    /// refused and no control changes.
    pub fn set_controls(&mut self, ctrl: &[f64]) -> Result<()> {
        let count = self.actuated_joints.len();
        if ctrl.len() != count {
            return Err(Error::Invalid {
                what: "the controls",
                problem: format!(
                    "{} values for {count} actuators (one per actuator, in `actuators` order)",
                    ctrl.len()
                ),
            });
        }
        if let Some((i, bad)) = ctrl.iter().enumerate().find(|(_, c)| !c.is_finite()) {
            return Err(Error::NotFinite { what: "an actuator's control", value: format!("{bad} (control {i})") });
        }
        for (k, &c) in ctrl.iter().enumerate() {
            let id = self.actuated_joints[k];
            let mut joint = self.joint_mut(id)?;
            if let Some(actuator) = joint.controller_mut::<Actuator>() {
                actuator.set_ctrl(c)?;
            }
        }
        Ok(())
    }

    /// Every actuator's control, in [`actuators`](Self::actuators) order.
    pub fn controls(&self) -> Vec<f64> {
        self.actuated_joints.iter().filter_map(|&id| self.actuator_of(id)).map(Actuator::ctrl).collect()
    }

    /// The names of the actuated joints, in [`actuators`](Self::actuators) order (what a
    /// snapshot keeps of that order).
    pub(crate) fn actuated_joint_names(&self) -> Vec<String> {
        self.actuated_joints.iter().filter_map(|&id| Some(self.joint_data(id).ok()?.name.clone())).collect()
    }

    /// Puts the actuators in the order of `names` (their joints' names, as
    /// [`actuated_joint_names`](Self::actuated_joint_names) gave them); joints not
    /// named keep their order after those named.
    pub(crate) fn order_actuators(&mut self, names: &[String]) {
        let rank = |scene: &Scene, id: JointId| {
            let name = scene.joint_data(id).map(|d| d.name.as_str()).unwrap_or("");
            names.iter().position(|n| n == name).unwrap_or(names.len())
        };
        let mut ranked: Vec<(usize, JointId)> = self.actuated_joints.iter().map(|&id| (rank(self, id), id)).collect();
        // Stable: the unnamed keep their order.
        ranked.sort_by_key(|(r, _)| *r);
        self.actuated_joints = ranked.into_iter().map(|(_, id)| id).collect();
    }

    /// The actuator of joint `id`, if it is driven by one.
    pub(super) fn actuator_of(&self, id: JointId) -> Option<&Actuator> {
        let c = self.joint_data(id).ok()?.controller.as_deref()?;
        (c as &dyn std::any::Any).downcast_ref::<Actuator>()
    }

    /// The joint of the actuator called `name`.
    fn actuator_joint(&self, name: &str) -> Result<JointId> {
        self.actuators().find(|(n, _)| *n == name).map(|(_, id)| id).ok_or_else(|| Error::UnknownName {
            kind: "actuator",
            name: name.to_string(),
            close_matches: super::names::close_matches(name, self.actuators().map(|(n, _)| n)),
        })
    }

    /// Sets the control of the actuator called `name` (clamped to its control range),
    /// held until set again: MuJoCo's `data.ctrl`.
    pub fn set_control(&mut self, name: &str, ctrl: f64) -> Result<()> {
        let id = self.actuator_joint(name)?;
        let mut joint = self.joint_mut(id)?;
        // Found on this joint just above.
        joint.controller_mut::<Actuator>().map_or(Ok(()), |actuator| actuator.set_ctrl(ctrl))
    }

    /// The control of the actuator called `name`.
    pub fn control(&self, name: &str) -> Result<f64> {
        let id = self.actuator_joint(name)?;
        Ok(self.actuator_of(id).map_or(0.0, Actuator::ctrl))
    }
}
