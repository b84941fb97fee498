//! [`SimJoint`]: what a program does to one joint of a scene (efforts, speeds,
//! friction, limits, mimicry, controllers).

use super::Scene;
use super::joints::{ActuatorLimits, JointData, JointType, Mimic};
use super::views::JointKey;
use crate::control::JointController;
use crate::error::{Error, Result};
use crate::handle::{JointHandle, JointId};
use crate::joint::JointParam;
use crate::{limits, validate};

/// Actions on one joint of a simulation, from [`Scene::joint_mut`] (to read it,
/// [`Scene::joint`]).
pub struct SimJoint<'s> {
    sim: &'s mut Scene,
    id: JointId,
    kind: JointType,
    handle: JointHandle,
}

impl Scene {
    /// Actions on a joint: torques, forces, motors, limits, friction, controllers.
    #[inline]
    pub fn joint_mut(&mut self, key: impl JointKey) -> Result<SimJoint<'_>> {
        let id = key.joint_id(self)?;
        let data = self.joint_data(id)?;
        let (kind, handle) = (data.kind, data.handle);
        Ok(SimJoint { sim: self, id, kind, handle })
    }
}

impl SimJoint<'_> {
    fn data_mut(&mut self) -> &mut JointData {
        let id = self.id;
        self.sim.joints.get_mut(id.0, JointId::KIND).expect("checked when the view was made")
    }

    fn wrong(&self, operation: &'static str) -> Error {
        Error::WrongJointKind { operation, kind: self.kind.default_name() }
    }

    /// Its id.
    pub fn id(&self) -> JointId {
        self.id
    }

    /// Adds a torque about a hinge's axis for the next step (`+torque` on the
    /// first object, `−torque` on the second). Joint sensors see it.
    #[inline]
    pub fn add_torque(&mut self, torque: f64) -> Result<()> {
        match self.kind {
            JointType::Hinge | JointType::Universal => {
                self.sim.put_effort(self.id, self.handle, self.kind, torque, false)
            }
            _ => Err(self.wrong("adding a torque")),
        }
    }

    /// Adds a force along a slider's or piston's axis for the next step.
    #[inline]
    pub fn add_force(&mut self, force: f64) -> Result<()> {
        match self.kind {
            JointType::Slider | JointType::Piston => self.sim.put_effort(self.id, self.handle, self.kind, force, false),
            _ => Err(self.wrong("adding a force")),
        }
    }

    /// Drives the joint at `speed` (rad/s or m/s) with at most `max_force` (N·m or N),
    /// ODE's built-in velocity motor; it stays on until changed. `max_force = 0` turns
    /// it off (back to the dry friction, if any). (The original's `set_speed` without a
    /// force did nothing: ODE's default limit is 0.) Both are held within the
    /// joint's [`ActuatorLimits`].
    pub fn set_speed(&mut self, speed: f64, max_force: f64) -> Result<()> {
        match self.kind {
            JointType::Hinge | JointType::Slider | JointType::Universal | JointType::Piston => {}
            _ => return Err(self.wrong("setting a speed")),
        }
        if self.data_mut().mimic.is_some() {
            return Err(Error::Invalid {
                what: "a joint speed",
                problem: format!(
                    "cannot be set on joint {:?}: it mimics another joint, whose motion drives its speed motor",
                    self.data_mut().name
                ),
            });
        }
        validate::finite("joint speed", speed)?;
        validate::non_negative("joint motor max force", max_force)?;
        let data = self.data_mut();
        let (speed, max_force) = if max_force == 0.0 {
            (0.0, data.dry_friction)
        } else {
            (speed.clamp(-data.actuator.velocity, data.actuator.velocity), max_force.min(data.actuator.effort))
        };
        if max_force > 0.0 {
            self.sim.check_member_motor(self.id, "a speed motor or dry friction")?;
        }
        self.sim.set_joint_motor(self.id, speed, max_force)
    }

    /// Dry (Coulomb) friction: the joint is held, against anything that would move it,
    /// with up to `max_effort` (N·m or N), by ODE's velocity motor at speed 0 (URDF's
    /// `<dynamics friction>`; the way pybullet and Gazebo model it). A speed set with
    /// [`set_speed`](Self::set_speed) replaces it until turned off. `0` removes it.
    pub fn set_dry_friction(&mut self, max_effort: f64) -> Result<()> {
        match self.kind {
            JointType::Hinge | JointType::Slider | JointType::Universal | JointType::Piston => {}
            _ => return Err(self.wrong("dry friction")),
        }
        limits::in_range("dry friction", max_effort, 0.0, limits::MAX_FORCE)?;
        self.data_mut().dry_friction = max_effort;
        self.set_speed(0.0, 0.0)
    }

    /// Limits what the joint's actuator puts out (see [`ActuatorLimits`]); each must
    /// be positive (`f64::INFINITY` for none).
    pub fn set_actuator_limits(&mut self, limits: ActuatorLimits) -> Result<()> {
        match self.kind {
            JointType::Fixed | JointType::Ball => return Err(self.wrong("actuator limits")),
            _ => {}
        }
        for (what, value) in [("effort limit", limits.effort), ("velocity limit", limits.velocity)] {
            if value.is_nan() || value <= 0.0 {
                return Err(Error::OutOfRange {
                    what, detail: format!("must be positive (∞ for none), got {value}")
                });
            }
        }
        self.data_mut().actuator = limits;
        Ok(())
    }

    /// Gives a hinge (a slider) an armature: `inertia` kg·m² (kg) that only the joint's
    /// own motion feels, as a motor's rotor seen through its gearbox (MuJoCo's joint
    /// `armature`), integrated implicitly (0 removes it). An ODE motor beside the joint
    /// holds it, a joint of the world (see the `armature` module).
    pub fn set_armature(&mut self, inertia: f64) -> Result<()> {
        let id = self.id;
        self.sim.set_joint_armature(id, inertia)
    }

    /// Its armature (0: none), kg·m² or kg.
    pub fn armature(&self) -> f64 {
        self.sim.joint_data(self.id).ok().and_then(|d| d.armature).map_or(0.0, |a| a.inertia)
    }

    /// Gives a hinge (a slider) a viscous damping of `coefficient` N·m·s/rad (N·s/m)
    /// integrated implicitly, from the joint's rate at the end of the step, as MuJoCo's
    /// joint `damping`: stable at any coefficient (0 removes it). The original's
    /// [`set_viscous_friction`](Self::set_viscous_friction) takes the rate at the
    /// start of the step, and diverges once `coefficient · dt` outgrows the inertia it
    /// acts on. The motor beside the joint that holds an armature holds it too (see
    /// the `armature` module).
    pub fn set_damping(&mut self, coefficient: f64) -> Result<()> {
        let id = self.id;
        self.sim.set_joint_damping(id, coefficient)
    }

    /// Its implicit damping (0: none; see [`set_damping`](Self::set_damping)).
    pub fn damping(&self) -> f64 {
        self.sim.joint_data(self.id).ok().and_then(|d| d.armature).map_or(0.0, |a| a.damping)
    }

    /// Makes the joint follow `leader` (see [`Mimic`]): a hinge follows a hinge, a
    /// slider a slider.
    pub fn set_mimic(&mut self, leader: impl JointKey, multiplier: f64, offset: f64) -> Result<()> {
        let leader = leader.joint_id(self.sim)?;
        validate::finite("mimic multiplier", multiplier)?;
        validate::finite("mimic offset", offset)?;
        let leader_kind = self.sim.joint_data(leader)?.kind;
        let rotational = |k| matches!(k, JointType::Hinge | JointType::Universal);
        let moving = |k| !matches!(k, JointType::Fixed | JointType::Ball);
        if leader == self.id {
            return Err(Error::Invalid { what: "a mimic joint", problem: "cannot follow itself".into() });
        }
        if !moving(self.kind) || !moving(leader_kind) || rotational(self.kind) != rotational(leader_kind) {
            return Err(Error::Invalid {
                what: "a mimic joint and its leader",
                problem: format!(
                    "must move alike: a {} joint cannot follow a {} joint (a rotation follows a rotation, a translation a translation)",
                    self.kind.default_name(),
                    leader_kind.default_name()
                ),
            });
        }
        self.data_mut().mimic = Some(Mimic { leader, multiplier, offset });
        self.sim.update_driven(self.id);
        Ok(())
    }

    /// Stops following (the speed motor goes back to the dry friction, if any).
    pub fn clear_mimic(&mut self) -> Result<()> {
        if self.data_mut().mimic.take().is_none() {
            return Ok(());
        }
        self.sim.update_driven(self.id);
        self.set_speed(0.0, 0.0)
    }

    /// Limits of the first degree of freedom (rad or m; ±∞ for none). See
    /// [`JointMut::set_limits`](crate::JointMut::set_limits) for ODE's behaviour when
    /// stops are removed from an axis resting at one.
    pub fn set_limits(&mut self, low: f64, high: f64) -> Result<()> {
        let handle = self.handle;
        match self.kind {
            JointType::Fixed | JointType::Ball => Err(self.wrong("setting limits")),
            _ => {
                self.sim.world.joint_mut(handle)?.set_limits(0, low, high)?;
                self.data_mut().limits = Some((low, high));
                // A group's joint: its stops scaled to its dual axis before the next step.
                self.sim.rescale_member(self.id)
            }
        }
    }

    /// A joint parameter of the first axis (ODE's `dParam*`).
    pub fn set_param(&mut self, param: JointParam, value: f64) -> Result<()> {
        let handle = self.handle;
        self.sim.world.joint_mut(handle)?.set_param(param, 0, value)
    }

    /// Viscous friction: a torque (or force) of `−coefficient · rate` is added in every
    /// step, from the rate at the start of the step. `0` turns it off.
    pub fn set_viscous_friction(&mut self, coefficient: f64) -> Result<()> {
        validate::non_negative("viscous friction coefficient", coefficient)?;
        match self.kind {
            JointType::Fixed | JointType::Ball => return Err(self.wrong("viscous friction")),
            _ => {}
        }
        self.data_mut().friction = coefficient;
        self.sim.update_driven(self.id);
        Ok(())
    }

    /// A spring: a torque (or force) of `−stiffness · (position − rest)` is added in
    /// every step, from the position at the start of the step (for a hinge, the angle
    /// from `rest` the short way round). Stiffness in N·m/rad or N/m; `0` turns it off.
    pub fn set_spring(&mut self, stiffness: f64, rest: f64) -> Result<()> {
        limits::in_range("spring stiffness", stiffness, 0.0, limits::MAX_FORCE)?;
        limits::in_range("spring rest position", rest, -limits::MAX_COORDINATE, limits::MAX_COORDINATE)?;
        match self.kind {
            JointType::Fixed | JointType::Ball => return Err(self.wrong("a spring")),
            _ => {}
        }
        self.data_mut().spring = (stiffness, rest);
        self.sim.update_driven(self.id);
        Ok(())
    }

    /// Attaches a controller whose output (torque or force) is added in every step,
    /// after the pre-step hooks. Replaces any previous controller.
    pub fn set_controller(&mut self, controller: impl JointController + 'static) -> Result<()> {
        match self.kind {
            JointType::Fixed | JointType::Ball => return Err(self.wrong("a controller")),
            _ => {}
        }
        self.data_mut().controller = Some(Box::new(controller));
        self.sim.update_driven(self.id);
        Ok(())
    }

    /// The attached controller, if it is a `C` (to change its set-point, say).
    pub fn controller_mut<C: JointController + 'static>(&mut self) -> Option<&mut C> {
        let c = self.data_mut().controller.as_deref_mut()?;
        (c as &mut dyn std::any::Any).downcast_mut::<C>()
    }

    /// Detaches the controller.
    pub fn clear_controller(&mut self) {
        self.data_mut().controller = None;
        self.sim.update_driven(self.id);
    }
}
