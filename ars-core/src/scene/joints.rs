//! Joints of a simulation: named, between two objects or an object and the static
//! world, with torque/force accounting for the joint sensors, viscous and dry
//! friction, attached controllers, actuator limits (effort and velocity) and mimic
//! joints.

use nalgebra::{Point3, Vector3};

use super::Scene;
use crate::control::{JointController, JointState};
use crate::error::{Error, Result};
use crate::handle::{JointHandle, JointId, ObjectId};
use crate::joint::{JointBuilder, JointKind, JointRef};
use crate::limits;

/// The kinds of joint a simulation offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum JointType {
    /// Locks the relative pose.
    Fixed,
    /// One rotation about an axis (the original's rotary joint).
    Hinge,
    /// One translation.
    Slider,
    /// Two rotations about perpendicular axes.
    Universal,
    /// Three rotations about a point (the original's ball-and-socket joint).
    Ball,
    /// A translation along and a rotation about one axis.
    Piston,
}

impl JointType {
    /// Default name of joints of this type.
    pub fn default_name(self) -> &'static str {
        match self {
            JointType::Fixed => "fixed",
            JointType::Hinge => "hinge",
            JointType::Slider => "slider",
            JointType::Universal => "universal",
            JointType::Ball => "ball",
            JointType::Piston => "piston",
        }
    }
}

/// The second end of a joint: another object, or the static world.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointEnd {
    /// Another object (a static object counts as the world).
    Object(ObjectId),
    /// The static world.
    World,
}

impl From<ObjectId> for JointEnd {
    fn from(id: ObjectId) -> Self {
        JointEnd::Object(id)
    }
}

pub(crate) struct JointData {
    pub(crate) name: String,
    pub(crate) kind: JointType,
    pub(crate) handle: JointHandle,
    pub(crate) object1: ObjectId,
    pub(crate) object2: Option<ObjectId>,
    pub(crate) friction: f64,
    pub(super) controller: Option<Box<dyn JointController>>,
    /// Torques (or forces) of the current step.
    pub(crate) efforts: JointEfforts,
    /// The joint as created (anchors and axes as given, in the world frame then).
    pub(crate) creation: JointKind,
    /// Stops set on its first axis, if any.
    pub(crate) limits: Option<(f64, f64)>,
    /// What its actuator can put out (±∞: unlimited).
    pub(crate) actuator: ActuatorLimits,
    /// The most torque (force) its dry friction holds it with (ODE's velocity motor at
    /// speed 0 while no speed is set).
    pub(crate) dry_friction: f64,
    /// The joint whose position it follows, if any.
    pub(crate) mimic: Option<Mimic>,
    /// Its spring: stiffness and rest position (stiffness 0: none).
    pub(crate) spring: (f64, f64),
    /// Its armature, if any (see [`armature`](super::armature)).
    pub(crate) armature: Option<Armature>,
    /// Its place in a joint group, if it is one's (see
    /// [`joint_group`](super::joint_group)).
    pub(crate) member: Option<super::joint_group::GroupMember>,
}

/// A joint's armature and implicit damping, and the motor that holds them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Armature {
    /// kg·m² (hinges) or kg (sliders); 0: none.
    pub(crate) inertia: f64,
    /// N·m·s/rad (hinges) or N·s/m (sliders); 0: none.
    pub(crate) damping: f64,
    /// The motor beside the joint (a joint of the world, saved with it; see
    /// [`armature`](super::armature)).
    pub(crate) motor: JointHandle,
}

/// What a joint's actuator can put out: its controller's output and its speed motor
/// are held within these (URDF's `<limit effort velocity>`). Torques added directly
/// ([`SimJoint::add_torque`](super::SimJoint::add_torque)) are the caller's own and are not limited.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActuatorLimits {
    /// The largest torque (N·m) or force (N) in either direction; `∞` for none.
    pub effort: f64,
    /// The largest rate (rad/s or m/s) the actuator drives at: a speed set is clamped
    /// to it, and a controller puts no effort that speeds up a joint already moving
    /// this fast. `∞` for none.
    pub velocity: f64,
}

impl Default for ActuatorLimits {
    fn default() -> Self {
        ActuatorLimits { effort: f64::INFINITY, velocity: f64::INFINITY }
    }
}

impl ActuatorLimits {
    /// A controller's output as the actuator can put it out at `rate`.
    #[inline]
    fn limit(&self, output: f64, rate: f64) -> f64 {
        if rate.abs() >= self.velocity && output * rate > 0.0 { 0.0 } else { output.clamp(-self.effort, self.effort) }
    }

    /// The speed motor's largest force, within the effort limit and ODE's range.
    fn motor_force(&self) -> f64 {
        self.effort.min(crate::limits::MAX_FORCE)
    }
}

/// A joint that follows another's position: `multiplier · leader + offset` (URDF's
/// `<mimic>`, a gripper's second finger).
///
/// The follower's speed motor drives it, every step, at the leader's rate times the
/// multiplier plus a correction of the position error (at the world's ERP), with at
/// most its effort limit. It is a constraint on the follower only: the leader does
/// not feel the follower's load, as it would through a real gear.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mimic {
    /// The joint followed.
    pub leader: JointId,
    /// Follower position per leader position.
    pub multiplier: f64,
    /// Follower position when the leader is at 0 (rad or m).
    pub offset: f64,
}

/// The torques (hinges) or forces (sliders and pistons) put on a joint during
/// the step being taken, by where they came from; read them from a sensor or a
/// [`Probe`](crate::sensors::Probe) (they are zeroed after the sensors sampled).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct JointEfforts {
    /// Added through the API ([`SimJoint::add_torque`](super::SimJoint::add_torque) or [`add_force`](super::SimJoint::add_force),
    /// from hooks and key actions), summed in call order; N·m or N.
    pub added: f64,
    /// Of the viscous friction (`−coefficient · rate` at the start of the step).
    pub friction: f64,
    /// Of the spring (`−stiffness · (position − rest)` at the start of the step).
    pub spring: f64,
    /// Of the attached controller.
    pub controller: f64,
    /// Friction, spring and controller, as one addition after the pre-step hooks.
    pub driven: f64,
}

impl JointEfforts {
    /// Everything put on the joint in this step: `added + driven`.
    pub fn total(&self) -> f64 {
        self.added + self.driven
    }
}

impl Scene {
    fn default_anchor(&self, object1: ObjectId, object2: JointEnd) -> Result<Point3<f64>> {
        match object2 {
            JointEnd::Object(o) => self.position(o),
            JointEnd::World => self.position(object1),
        }
    }

    /// A fixed joint: locks the pose `object1` has relative to `object2` now.
    pub fn add_fixed_joint(&mut self, name: &str, object1: ObjectId, object2: impl Into<JointEnd>) -> Result<JointId> {
        self.insert_sim_joint(name, JointType::Fixed, object1, object2.into(), JointBuilder::fixed())
    }

    /// A hinge about the world `axis` through `anchor` (default: the
    /// position of `object2`, or of `object1` when attached to the world). An empty
    /// `name` gets the default one.
    pub fn add_hinge_joint(
        &mut self,
        name: &str,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        anchor: Option<Point3<f64>>,
        axis: impl Into<Vector3<f64>>,
    ) -> Result<JointId> {
        let object2 = object2.into();
        let anchor = match anchor {
            Some(a) => a,
            None => self.default_anchor(object1, object2)?,
        };
        self.insert_sim_joint(name, JointType::Hinge, object1, object2, JointBuilder::hinge(anchor, axis.into()))
    }

    /// A slider along the world `axis`.
    pub fn add_slider_joint(
        &mut self,
        name: &str,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        axis: impl Into<Vector3<f64>>,
    ) -> Result<JointId> {
        self.insert_sim_joint(name, JointType::Slider, object1, object2.into(), JointBuilder::slider(axis.into()))
    }

    /// A universal joint at `anchor` with perpendicular axes `axis1` (on `object1`)
    /// and `axis2` (on `object2`).
    pub fn add_universal_joint(
        &mut self,
        name: &str,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        anchor: Point3<f64>,
        axis1: impl Into<Vector3<f64>>,
        axis2: impl Into<Vector3<f64>>,
    ) -> Result<JointId> {
        let builder = JointBuilder::universal(anchor, axis1.into(), axis2.into());
        self.insert_sim_joint(name, JointType::Universal, object1, object2.into(), builder)
    }

    /// A ball joint (ball and socket) at `anchor` (default: the position of `object2`).
    pub fn add_ball_joint(
        &mut self,
        name: &str,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        anchor: Option<Point3<f64>>,
    ) -> Result<JointId> {
        let object2 = object2.into();
        let anchor = match anchor {
            Some(a) => a,
            None => self.default_anchor(object1, object2)?,
        };
        self.insert_sim_joint(name, JointType::Ball, object1, object2, JointBuilder::ball(anchor))
    }

    /// A piston along and about the world `axis` through `anchor`.
    pub fn add_piston_joint(
        &mut self,
        name: &str,
        object1: ObjectId,
        object2: impl Into<JointEnd>,
        anchor: Point3<f64>,
        axis: impl Into<Vector3<f64>>,
    ) -> Result<JointId> {
        self.insert_sim_joint(
            name,
            JointType::Piston,
            object1,
            object2.into(),
            JointBuilder::piston(anchor, axis.into()),
        )
    }

    pub(crate) fn joint_data(&self, id: JointId) -> Result<&JointData> {
        self.joints.get(id.0, JointId::KIND)
    }

    /// Every joint's data, in slot order (creation order when none was removed).
    pub(crate) fn joints_in_creation_order(&self) -> impl Iterator<Item = &JointData> + '_ {
        self.joints.values()
    }

    /// Every joint, by name in alphabetical order.
    pub fn joints(&self) -> impl Iterator<Item = (&str, JointId)> + '_ {
        self.joint_names.iter()
    }

    /// The torques (or forces) put on a joint during the step being taken.
    pub fn joint_efforts(&self, id: JointId) -> Result<JointEfforts> {
        Ok(self.joint_data(id)?.efforts)
    }

    /// The controller attached to a joint, if it is a `C`.
    pub fn joint_controller<C: JointController + 'static>(&self, id: JointId) -> Result<Option<&C>> {
        let d = self.joint_data(id)?;
        Ok(d.controller.as_deref().and_then(|c| (c as &dyn std::any::Any).downcast_ref::<C>()))
    }

    /// The joints removing `id` removes: its group's, or itself.
    pub(crate) fn joints_removed_with(&self, id: JointId) -> Result<Vec<JointId>> {
        Ok(match self.joint_data(id)?.member {
            Some(member) => self.group_members(member)?.to_vec(),
            None => vec![id],
        })
    }

    pub(crate) fn joints_of_object(&self, object: ObjectId) -> Vec<JointId> {
        self.joints
            .iter()
            .filter(|(_, j)| j.object1 == object || j.object2 == Some(object))
            .map(|(h, _)| JointId(h))
            .collect()
    }

    /// Removes a joint (the sensors reading it are the simulation's business:
    /// [`Simulation::remove_joint`](crate::Simulation::remove_joint)).
    pub(crate) fn remove_joint(&mut self, id: JointId) -> Result<()> {
        if let Some(member) = self.joint_data(id)?.member {
            // A group goes as a whole: its constraint holds every joint of it.
            let members = self.remove_group_of(member)?;
            for m in &members {
                self.joints.get_mut(m.0, JointId::KIND)?.member = None;
            }
            for m in members.into_iter().filter(|m| *m != id) {
                self.remove_joint(m)?;
            }
        }
        let data = self.joints.remove(id.0, JointId::KIND)?;
        self.joint_names.remove(&data.name);
        self.driven_joints.retain(|j| *j != id);
        self.actuated_joints.retain(|j| *j != id);
        // Its followers stop following (their motors are left off).
        let followers: Vec<JointId> = self
            .joints
            .iter()
            .filter(|(_, j)| j.mimic.is_some_and(|m| m.leader == id))
            .map(|(h, _)| JointId(h))
            .collect();
        for follower in followers {
            self.joint_mut(follower)?.clear_mimic()?;
        }
        if let Some(armature) = data.armature {
            self.world.remove_joint(armature.motor)?;
        }
        self.world.remove_joint(data.handle)
    }

    /// Controllers, viscous friction and springs, from the state at the start of the
    /// step (one addition per driven joint, after the pre-step hooks).
    #[inline]
    pub(crate) fn apply_joint_drives(&mut self) -> Result<()> {
        if self.groups.is_empty() {
            return if self.driven_joints.is_empty() { Ok(()) } else { self.drive_joints() };
        }
        // Nothing moves while the drives are applied: each group's kinematics are
        // worked out once. After the drives, the groups' rows (and their members'
        // armatures, scaled).
        self.keep_group_kinematics()?;
        let held =
            if self.driven_joints.is_empty() { Ok(()) } else { self.drive_joints() }.and_then(|()| self.hold_groups());
        self.forget_group_kinematics();
        held
    }

    #[inline(never)]
    fn drive_joints(&mut self) -> Result<()> {
        let (time, dt) = (self.time, self.time_step.get());
        for i in 0..self.driven_joints.len() {
            let id = self.driven_joints[i];
            let state = self.joint_state(id)?;
            let data = self.joints.get_mut(id.0, JointId::KIND)?;
            let (kind, handle) = (data.kind, data.handle);
            let friction = -data.friction * state.rate;
            let (mut effort, controller) = match data.controller.as_mut() {
                Some(c) => {
                    let output = data.actuator.limit(c.output(time, state, dt), state.rate);
                    // Exactly the controller's output when there is no friction.
                    (if data.friction == 0.0 { output } else { friction + output }, output)
                }
                None => (friction, 0.0),
            };
            let (stiffness, rest) = data.spring;
            let mut spring = 0.0;
            if stiffness != 0.0 {
                let mut stretch = state.position - rest;
                if matches!(kind, JointType::Hinge | JointType::Universal) {
                    // ODE's angles wrap at ±π: the spring pulls the short way round.
                    stretch = stretch.sin().atan2(stretch.cos());
                }
                spring = -stiffness * stretch;
                // Without a spring, the effort stays exactly the friction and controller's.
                effort += spring;
            }
            data.efforts.friction = friction;
            data.efforts.spring = spring;
            data.efforts.controller = controller;
            let (mimic, armature) = (data.mimic, data.armature);
            if effort != 0.0 || data.friction != 0.0 || data.controller.is_some() || stiffness != 0.0 {
                self.put_effort(id, handle, kind, effort, true)?;
            }
            if let Some(mimic) = mimic {
                self.follow(id, handle, kind, state, mimic)?;
            }
            // Damping alone keeps the target (0) and CFM it was given.
            if let (Some(armature), None) = (armature, self.joint_data(id)?.member)
                && armature.inertia > 0.0
            {
                self.hold_armature(armature, state.rate)?;
            }
        }
        Ok(())
    }

    /// Sets a mimic joint's speed motor for the coming step (see [`Mimic`]).
    fn follow(
        &mut self,
        id: JointId,
        handle: JointHandle,
        kind: JointType,
        state: JointState,
        mimic: Mimic,
    ) -> Result<()> {
        let leader = self.joint_state(mimic.leader)?;
        let mut error = mimic.multiplier * leader.position + mimic.offset - state.position;
        if matches!(kind, JointType::Hinge | JointType::Universal) {
            // ODE's angles wrap at ±π: correct the short way round.
            error = error.sin().atan2(error.cos());
        }
        let speed = mimic.multiplier * leader.rate + self.world.erp() * error / self.time_step.get();
        let data = self.joint_data(id)?;
        let mut max_force = data.actuator.motor_force();
        let speed = speed.clamp(-crate::limits::MAX_SPEED, crate::limits::MAX_SPEED);
        if data.limits.is_some_and(|(low, high)| state.position <= low || state.position >= high) {
            // At a stop, ODE cannot make the motor a constraint beside the stop's: it puts
            // the motor's largest force on the bodies as it is, for the whole step (a
            // gripper's finger of grams resting on its stop took 1e9 N·m and spun at
            // 1e9 rad/s). There the follower gets at most the push that brings its own
            // body to the wanted speed in one step.
            let inertia = match data.member {
                Some(member) => self.member_inertia(member)?,
                None => self.joint_inertia(data.object1, handle, kind)?,
            };
            let needed = inertia * (speed - state.rate).abs() / self.time_step.get();
            max_force = max_force.min(needed);
        }
        self.set_joint_motor(id, speed, max_force)
    }

    /// Sets a joint's speed motor (ODE's, or a group member's, which its group scales
    /// each step).
    pub(crate) fn set_joint_motor(&mut self, id: JointId, speed: f64, max_force: f64) -> Result<()> {
        let data = self.joint_data(id)?;
        if data.member.is_some() {
            return self.set_member_motor(id, speed, max_force);
        }
        let handle = data.handle;
        self.world.joint_mut(handle)?.set_motor(0, speed, max_force)
    }

    /// The inertia (kg·m², hinges) or mass (kg, sliders) of `object`'s body about or
    /// along the joint's axis: what the joint's motor moves at least.
    fn joint_inertia(&self, object: ObjectId, handle: JointHandle, kind: JointType) -> Result<f64> {
        let Some(b) = self.object(object)?.body_handle() else { return Ok(0.0) };
        let body = self.world.body(b)?;
        let joint = self.world.joint(handle)?;
        if !matches!(kind, JointType::Hinge | JointType::Universal) {
            return Ok(body.mass());
        }
        let axis = joint.axis()?;
        let arm = body.position() - joint.anchor()?;
        let across = arm - axis * arm.dot(&axis);
        Ok(axis.dot(&(body.inertia_world() * axis)) + body.mass() * across.norm_squared())
    }

    /// Puts a torque (hinge, universal) or force (slider, piston) on a joint for the
    /// next step and books it.
    #[inline]
    pub(super) fn put_effort(
        &mut self,
        id: JointId,
        handle: JointHandle,
        kind: JointType,
        effort: f64,
        driven: bool,
    ) -> Result<()> {
        // One look-up in each arena (the scene's joint, then the world's, which checks
        // that the world is usable and that the joint was not removed through it).
        let data = self.joints.get_mut(id.0, JointId::KIND)?;
        if let Some(member) = data.member {
            limits::in_range("joint effort", effort, -limits::MAX_FORCE, limits::MAX_FORCE)?;
            self.put_member_effort(member, effort)?;
        } else {
            // The world's add_torque / add_force refuse NaN, infinities and values
            // beyond the limits before anything is booked.
            let mut j = self.world.joint_mut(handle)?;
            match kind {
                JointType::Hinge | JointType::Universal => j.add_torque(effort)?,
                _ => j.add_force(effort)?,
            }
        }
        let efforts = &mut self.joints.get_mut(id.0, JointId::KIND)?.efforts;
        if driven {
            efforts.driven += effort;
        } else {
            efforts.added += effort;
        }
        Ok(())
    }

    /// Keeps the list of joints with friction or a controller.
    pub(super) fn update_driven(&mut self, id: JointId) {
        let driven = self.joint_data(id).is_ok_and(|d| {
            d.friction != 0.0
                || d.spring.0 != 0.0
                || d.controller.is_some()
                || d.mimic.is_some()
                || d.armature.is_some_and(|a| a.inertia > 0.0)
        });
        match (driven, self.driven_joints.iter().position(|j| *j == id)) {
            (true, None) => {
                self.driven_joints.push(id);
                // Drive in joint creation order, whatever the order they were set up in.
                self.driven_joints.sort_by_key(|j| j.0.index);
            }
            (false, Some(i)) => {
                self.driven_joints.remove(i);
            }
            _ => {}
        }
        match (self.actuator_of(id).is_some(), self.actuated_joints.iter().position(|j| *j == id)) {
            (true, None) => self.actuated_joints.push(id),
            (false, Some(i)) => {
                self.actuated_joints.remove(i);
            }
            _ => {}
        }
    }

    /// The efforts of the step are over: every joint's are zero again.
    #[inline]
    pub(crate) fn end_joint_step(&mut self) {
        if self.joints.len() != 0 {
            self.clear_joint_efforts();
        }
    }

    #[inline(never)]
    fn clear_joint_efforts(&mut self) {
        for d in self.joints.values_mut() {
            d.efforts = JointEfforts::default();
        }
    }

    /// The joint's first degree of freedom read with `rotary` (hinge, universal) or
    /// `linear` (slider, piston); a ball or fixed joint has none to read (`operation`
    /// says what was asked).
    fn first_freedom<T>(
        &self,
        id: JointId,
        operation: &'static str,
        rotary: impl FnOnce(&JointRef<'_>) -> Result<T>,
        linear: impl FnOnce(&JointRef<'_>) -> Result<T>,
    ) -> Result<T> {
        let d = self.joint_data(id)?;
        let j = self.world.joint(d.handle)?;
        match d.kind {
            JointType::Hinge | JointType::Universal => rotary(&j),
            JointType::Slider | JointType::Piston => linear(&j),
            JointType::Fixed | JointType::Ball => Err(Error::WrongJointKind { operation, kind: d.kind.default_name() }),
        }
    }

    /// Rate (rad/s or m/s) of the joint's first degree of freedom: the `rate` of
    /// [`joint_state`](Self::joint_state), without computing the position (a hinge's
    /// angle costs an `atan2` and a quaternion product in ODE).
    pub fn joint_rate(&self, id: JointId) -> Result<f64> {
        if let Some(member) = self.joint_data(id)?.member {
            return Ok(self.member_state(member)?.rate);
        }
        self.first_freedom(id, "reading a joint rate", |j| j.angle_rate(), |j| j.position_rate())
    }

    /// Position (angle, rad, or slider position, m) of the joint's first degree of
    /// freedom: the `position` of [`joint_state`](Self::joint_state), without computing
    /// the rate.
    pub fn joint_position(&self, id: JointId) -> Result<f64> {
        if let Some(member) = self.joint_data(id)?.member {
            return Ok(self.member_state(member)?.position);
        }
        self.first_freedom(id, "reading a joint position", |j| j.angle(), |j| j.position())
    }

    /// Position (angle, rad, or slider position, m) and its rate of the joint's first
    /// degree of freedom.
    pub fn joint_state(&self, id: JointId) -> Result<JointState> {
        if let Some(member) = self.joint_data(id)?.member {
            return self.member_state(member);
        }
        self.first_freedom(
            id,
            "reading a joint state",
            |j| Ok(JointState { position: j.angle()?, rate: j.angle_rate()? }),
            |j| Ok(JointState { position: j.position()?, rate: j.position_rate()? }),
        )
    }
}

impl JointKind {
    /// The simulation joint type of an ODE joint kind, if it has one.
    pub fn joint_type(&self) -> Option<JointType> {
        match self {
            JointKind::Fixed => Some(JointType::Fixed),
            JointKind::Hinge { .. } => Some(JointType::Hinge),
            JointKind::Slider { .. } => Some(JointType::Slider),
            JointKind::Universal { .. } => Some(JointType::Universal),
            JointKind::Ball { .. } => Some(JointType::Ball),
            JointKind::Piston { .. } => Some(JointType::Piston),
            _ => None,
        }
    }
}

/// What a snapshot keeps of a simulation joint besides its ODE side (which is in the
/// world's state): its drive (friction, controller with its state, limits, mimic) and
/// the efforts booked for the step being taken.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct JointDriveState {
    name: String,
    kind: JointType,
    creation: JointKind,
    friction: f64,
    controller: Option<crate::control::SavedController>,
    limits: Option<(f64, f64)>,
    /// Effort and velocity limits.
    actuator: (f64, f64),
    dry_friction: f64,
    /// The leader's name, multiplier and offset.
    mimic: Option<(String, f64, f64)>,
    /// Added, friction, controller and driven efforts.
    efforts: (f64, f64, f64, f64),
    /// The spring's stiffness and rest position (snapshots before springs have none).
    #[serde(default)]
    spring: (f64, f64),
    /// The spring's effort.
    #[serde(default)]
    spring_effort: f64,
    /// A group member's speed motor as asked (its ODE motor's is scaled each step).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    member_motor: Option<(f64, f64)>,
}

impl Scene {
    /// Every joint's drive state, in creation order. A controller that cannot be saved
    /// is [`Error::NotCapturable`].
    pub(crate) fn save_joint_drives(&self) -> Result<Vec<JointDriveState>> {
        self.joints_in_creation_order()
            .map(|d| {
                let controller = match &d.controller {
                    None => None,
                    Some(c) => Some(c.saved().ok_or_else(|| Error::NotCapturable {
                        what: format!(
                            "the controller of joint {:?} is of a type of your own that does not say how to save it (JointController::saved)",
                            d.name
                        ),
                    })?),
                };
                let mimic = match d.mimic {
                    Some(m) => Some((self.joint_data(m.leader)?.name.clone(), m.multiplier, m.offset)),
                    None => None,
                };
                let e = d.efforts;
                Ok(JointDriveState {
                    name: d.name.clone(),
                    kind: d.kind,
                    creation: d.creation.clone(),
                    friction: d.friction,
                    controller,
                    limits: d.limits,
                    actuator: (d.actuator.effort, d.actuator.velocity),
                    dry_friction: d.dry_friction,
                    mimic,
                    efforts: (e.added, e.friction, e.controller, e.driven),
                    spring: d.spring,
                    spring_effort: e.spring,
                    member_motor: d.member.map(|m| m.motor),
                })
            })
            .collect()
    }

    /// Checks that `states` are of joints of the same names and types as this scene's.
    pub(crate) fn check_joint_drives_fit(&self, states: &[JointDriveState]) -> Result<()> {
        let mut here: Vec<(&str, JointType)> = self.joints.values().map(|d| (d.name.as_str(), d.kind)).collect();
        let mut there: Vec<(&str, JointType)> = states.iter().map(|s| (s.name.as_str(), s.kind)).collect();
        here.sort_by(|a, b| a.0.cmp(b.0));
        there.sort_by(|a, b| a.0.cmp(b.0));
        if here != there {
            let names = |v: &[(&str, JointType)]| {
                v.iter().map(|(n, k)| format!("{n} ({})", k.default_name())).collect::<Vec<_>>()
            };
            return Err(Error::SnapshotMismatch {
                detail: format!("the snapshot has the joints {:?}, this simulation {:?}", names(&there), names(&here)),
            });
        }
        Ok(())
    }

    /// Puts back every joint's drive state (checked with `check_joint_drives_fit`).
    pub(crate) fn restore_joint_drives(&mut self, states: &[JointDriveState]) -> Result<()> {
        for s in states {
            let id = self.joint_names.get(&s.name)?;
            let mimic = match &s.mimic {
                Some((leader, multiplier, offset)) => {
                    Some(Mimic { leader: self.joint_names.get(leader)?, multiplier: *multiplier, offset: *offset })
                }
                None => None,
            };
            let d = self.joints.get_mut(id.0, JointId::KIND)?;
            d.creation = s.creation.clone();
            d.friction = s.friction;
            d.controller = s.controller.clone().map(crate::control::SavedController::into_controller);
            d.limits = s.limits;
            d.actuator = ActuatorLimits { effort: s.actuator.0, velocity: s.actuator.1 };
            d.dry_friction = s.dry_friction;
            d.mimic = mimic;
            d.spring = s.spring;
            let (added, friction, controller, driven) = s.efforts;
            d.efforts = JointEfforts { added, friction, spring: s.spring_effort, controller, driven };
            if let Some(member) = d.member.as_mut() {
                member.motor = s.member_motor.unwrap_or_default();
                // Its ODE motor set again, scaled, before the next step.
                member.scale = f64::NAN;
            }
            self.update_driven(id);
        }
        Ok(())
    }
}
