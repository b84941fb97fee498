//! What the bridge takes from ROS: `/cmd_vel` for a differential drive and joint
//! commands as ros2_control's forward command controllers take them. Each message is
//! checked first; one that cannot be applied (a NaN, a wrong length, an unknown joint)
//! is refused whole with the reason, which the bridge logs as a warning.

use ars_core::nalgebra::Vector3;
use ars_core::{JointId, JointType, ObjectId, Result, Scene, Shape, Simulation};

use super::wire::{Float64MultiArray, JointState, Twist};

/// How a joint is commanded: what a forward command controller of that kind holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CommandKind {
    /// A position (rad or m), reached by the joint's velocity motor.
    Position,
    /// A velocity (rad/s or m/s), the joint's velocity motor.
    Velocity,
    /// A torque or force (N·m or N), put on the joint before every step.
    Effort,
}

impl CommandKind {
    /// The three kinds, in the order of their controllers.
    pub const ALL: [CommandKind; 3] = [CommandKind::Position, CommandKind::Velocity, CommandKind::Effort];

    /// The forward command controller's name: its topic is `/<name>/commands`.
    pub fn controller(self) -> &'static str {
        match self {
            CommandKind::Position => "position_controller",
            CommandKind::Velocity => "velocity_controller",
            CommandKind::Effort => "effort_controller",
        }
    }
}

/// The gains of the commanded joints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CommandGains {
    /// Position commands: the velocity motor's speed is this times the error, 1/s.
    pub position_gain: f64,
    /// The most torque (N·m) or force (N) a position or velocity command's motor
    /// puts out (and never more than the joint's own actuator limit).
    pub max_effort: f64,
}

impl Default for CommandGains {
    fn default() -> Self {
        CommandGains { position_gain: 10.0, max_effort: 100.0 }
    }
}

/// The commands held on joints (the last one given for each), applied before every step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HeldCommands {
    /// Joint, kind and value, in the order first commanded (the order they are applied).
    held: Vec<(JointId, CommandKind, f64)>,
}

impl HeldCommands {
    /// The command `kind` with `data` (one value per joint of `joints`, in order), as a
    /// forward command controller takes a `Float64MultiArray`.
    pub fn forward(
        &mut self,
        kind: CommandKind,
        joints: &[(String, JointId)],
        message: &Float64MultiArray,
    ) -> CheckResult {
        if message.data.len() != joints.len() {
            return Err(format!(
                "/{}/commands: {} values for {} joints ({}); ignored",
                kind.controller(),
                message.data.len(),
                joints.len(),
                names(joints)
            ));
        }
        if let Some(i) = message.data.iter().position(|v| !v.is_finite()) {
            return Err(format!(
                "/{}/commands: value {} (joint {:?}) is {}; ignored",
                kind.controller(),
                i,
                joints[i].0,
                message.data[i]
            ));
        }
        for ((_, id), value) in joints.iter().zip(&message.data) {
            self.hold(*id, kind, *value);
        }
        Ok(())
    }

    /// Named commands in a `sensor_msgs/JointState`: for each name, its position if the
    /// message has positions, else its velocity, else its effort.
    pub fn named(&mut self, joints: &[(String, JointId)], message: &JointState) -> CheckResult {
        let n = message.name.len();
        let (kind, values) = [
            (CommandKind::Position, &message.position),
            (CommandKind::Velocity, &message.velocity),
            (CommandKind::Effort, &message.effort),
        ]
        .into_iter()
        .find(|(_, v)| !v.is_empty())
        .ok_or("/joint_commands: no position, velocity or effort; ignored")?;
        if values.len() != n {
            return Err(format!("/joint_commands: {} names but {} values; ignored", n, values.len()));
        }
        let mut found = Vec::with_capacity(n);
        for (name, value) in message.name.iter().zip(values) {
            let Some((_, id)) = joints.iter().find(|(known, _)| known == name) else {
                return Err(format!("/joint_commands: unknown joint {name:?} (known: {}); ignored", names(joints)));
            };
            if !value.is_finite() {
                return Err(format!("/joint_commands: joint {name:?} given {value}; ignored"));
            }
            found.push((*id, *value));
        }
        for (id, value) in found {
            self.hold(id, kind, value);
        }
        Ok(())
    }

    /// Puts the held commands on the joints for the next step. A joint that refuses
    /// its command (one that mimics another) loses it, with the reason.
    pub fn apply(&mut self, sim: &mut Simulation, gains: CommandGains) -> Vec<String> {
        let mut refused = Vec::new();
        self.held.retain(|(id, kind, value)| {
            let applied = apply_one(sim, *id, *kind, *value, gains);
            if let Err(e) = &applied {
                refused.push(format!("joint command dropped: {e}"));
            }
            applied.is_ok()
        });
        refused
    }

    fn hold(&mut self, id: JointId, kind: CommandKind, value: f64) {
        match self.held.iter_mut().find(|(held, _, _)| *held == id) {
            Some(entry) => *entry = (id, kind, value),
            None => self.held.push((id, kind, value)),
        }
    }

    /// Drops every command (on a reset).
    pub fn clear(&mut self) {
        self.held.clear();
    }

    /// Whether no command is held.
    pub fn is_empty(&self) -> bool {
        self.held.is_empty()
    }
}

fn apply_one(sim: &mut Simulation, id: JointId, kind: CommandKind, value: f64, gains: CommandGains) -> Result<()> {
    let sliding = matches!(sim.scene().joint(id)?.joint_type(), JointType::Slider | JointType::Piston);
    let position = sim.scene().joint_state(id)?.position;
    let mut joint = sim.scene_mut().joint_mut(id)?;
    match kind {
        CommandKind::Position => joint.set_speed(gains.position_gain * (value - position), gains.max_effort),
        CommandKind::Velocity => joint.set_speed(value, gains.max_effort),
        CommandKind::Effort if sliding => joint.add_force(value),
        CommandKind::Effort => joint.add_torque(value),
    }
}

/// A check of a message: `Err` says why it is ignored.
pub type CheckResult = std::result::Result<(), String>;

fn names(joints: &[(String, JointId)]) -> String {
    let list: Vec<&str> = joints.iter().map(|(n, _)| n.as_str()).collect();
    if list.is_empty() { "none".into() } else { list.join(", ") }
}

/// A differential drive: two wheel hinges that `/cmd_vel` turns, through their
/// velocity motors, as ROS's `diff_drive_controller` would.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffDrive {
    /// The body the wheels turn on (published as a vehicle: `/odom`).
    pub chassis: ObjectId,
    /// Left wheel's joint and the sign of its rate that rolls the vehicle forward.
    pub left: (JointId, f64),
    /// Right wheel's joint and its forward sign.
    pub right: (JointId, f64),
    /// Wheel radius, m.
    pub wheel_radius: f64,
    /// Distance between the wheels, m.
    pub track: f64,
    /// The most torque each wheel's motor puts out, N·m.
    pub max_torque: f64,
}

impl DiffDrive {
    /// The drive whose wheel joints are named `names`, or, without names, the one found
    /// by name: ARS's vehicles' `w1` and `w2`, or one hinge named with "left" and
    /// "wheel" and one with "right" and "wheel". Which wheel is on the left is found
    /// from where they are (left of the chassis' +X, with Y up). `Ok(None)`: no drive.
    pub fn find(
        scene: &Scene,
        names: Option<(&str, &str)>,
        max_torque: f64,
    ) -> std::result::Result<Option<DiffDrive>, String> {
        let hinges: Vec<(&str, JointId)> = scene
            .joints()
            .filter(|(_, id)| scene.joint(*id).is_ok_and(|j| j.joint_type() == JointType::Hinge))
            .collect();
        let pick = |wanted: &dyn Fn(&str) -> bool| -> Option<JointId> {
            let found: Vec<JointId> = hinges.iter().filter(|(n, _)| wanted(n)).map(|(_, id)| *id).collect();
            if let [one] = found[..] { Some(one) } else { None }
        };
        let (left, right) = match names {
            Some((l, r)) => {
                let exact = |name: &str| {
                    pick(&|n: &str| n == name).ok_or(format!("--drive: no hinge joint named {name:?} in the scene"))
                };
                (exact(l)?, exact(r)?)
            }
            None => {
                let named = |side: &str| {
                    let side = side.to_string();
                    move |n: &str| {
                        let n = n.to_lowercase();
                        n.contains(&side) && n.contains("wheel")
                    }
                };
                match (pick(&|n| n == "w1"), pick(&|n| n == "w2")) {
                    (Some(l), Some(r)) => (l, r),
                    _ => match (pick(&named("left")), pick(&named("right"))) {
                        (Some(l), Some(r)) => (l, r),
                        _ => return Ok(None),
                    },
                }
            }
        };
        Self::of_wheels(scene, left, right, max_torque).map(Some).map_err(|e| format!("the drive's wheels: {e}"))
    }

    fn of_wheels(scene: &Scene, one: JointId, other: JointId, max_torque: f64) -> Result<DiffDrive> {
        let (chassis, _) = scene.joint(one)?.objects();
        let rotation = scene.rotation(chassis)?;
        let (forward, up) = (rotation * Vector3::x(), rotation * Vector3::y());
        let wheel = |id: JointId| -> Result<(f64, f64, Vector3<f64>)> {
            let joint = scene.joint(id)?;
            let (first, second) = joint.objects();
            let axis = joint.ode()?.axis()?;
            // ODE's hinge rate is body 1's spin less body 2's about the axis.
            let (wheel, spin) = match second {
                Some(w) if w != chassis || first == chassis => (w, -axis),
                _ => (first, axis),
            };
            let radius = match scene.object(wheel)?.shape() {
                Shape::Cylinder { radius, .. } | Shape::Capsule { radius, .. } | Shape::Sphere { radius } => *radius,
                // Resting on the floor y = 0, a wheel's centre is a radius up.
                _ => scene.position(wheel)?.y.abs(),
            };
            // Rolling without slipping, the vehicle moves at spin × (radius · up).
            let sign = if spin.cross(&up).dot(&forward) >= 0.0 { 1.0 } else { -1.0 };
            Ok((sign, radius, scene.position(wheel)?.coords))
        };
        let (mut left, mut right) = (one, other);
        let (mut left_sign, mut left_radius, mut left_at) = wheel(left)?;
        let (mut right_sign, mut right_radius, mut right_at) = wheel(right)?;
        if (left_at - right_at).dot(&up.cross(&forward)) < 0.0 {
            std::mem::swap(&mut left, &mut right);
            std::mem::swap(&mut left_sign, &mut right_sign);
            std::mem::swap(&mut left_radius, &mut right_radius);
            std::mem::swap(&mut left_at, &mut right_at);
        }
        Ok(DiffDrive {
            chassis,
            left: (left, left_sign),
            right: (right, right_sign),
            wheel_radius: 0.5 * (left_radius + right_radius),
            track: (left_at - right_at).norm(),
            max_torque,
        })
    }

    /// Checks a `/cmd_vel`: only its forward speed (`linear.x`) and turn rate
    /// (`angular.z`) are used, and they must be finite.
    pub fn check(twist: &Twist) -> CheckResult {
        let used = [twist.linear.x, twist.angular.z];
        if used.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(format!("/cmd_vel: linear.x = {}, angular.z = {}: not finite; ignored", used[0], used[1]))
        }
    }

    /// The wheel joints' rates (left, right), rad/s, for forward speed `v` (m/s) and
    /// turn rate `w` (rad/s, left positive).
    pub fn wheel_rates(&self, v: f64, w: f64) -> (f64, f64) {
        let left = (v - w * self.track / 2.0) / self.wheel_radius;
        let right = (v + w * self.track / 2.0) / self.wheel_radius;
        (left * self.left.1, right * self.right.1)
    }

    /// Sets the wheel motors for `twist` (checked with [`check`](Self::check)).
    pub fn drive(&self, sim: &mut Simulation, twist: &Twist) -> Result<()> {
        let (left, right) = self.wheel_rates(twist.linear.x, twist.angular.z);
        sim.scene_mut().joint_mut(self.left.0)?.set_speed(left, self.max_torque)?;
        sim.scene_mut().joint_mut(self.right.0)?.set_speed(right, self.max_torque)
    }
}
