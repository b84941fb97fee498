//! Actuators and controllers: set-point profiles, PD/PID, velocity and position
//! servos, torque motors and a DC motor model. Use them from hooks, or attach them to
//! a joint with [`SimJoint::set_controller`](crate::SimJoint::set_controller), which
//! applies their output every step after the pre-step hooks.

use crate::error::{Error, Result};

/// Position (rad or m) and rate of a joint's first degree of freedom.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct JointState {
    /// Angle (rad) or position (m).
    pub position: f64,
    /// Its rate, rad/s or m/s.
    pub rate: f64,
}

/// Something that computes a joint torque (or force) every step.
pub trait JointController: Send + std::any::Any {
    /// The torque or force for the step starting at `time`, given the joint's state.
    fn output(&mut self, time: f64, state: JointState, dt: f64) -> f64;

    /// The controller with its state, as a [snapshot](crate::Snapshot) keeps it; `None`
    /// (the default) for a controller that cannot be saved: a snapshot of a
    /// simulation with one is refused with [`Error::NotCapturable`]. ARS's own
    /// controllers are all saved.
    fn saved(&self) -> Option<SavedController> {
        None
    }
}

/// One of ARS's controllers with its settings and state, as a snapshot or scene file
/// keeps it.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum SavedController {
    /// A [`PositionServo`].
    Position(PositionServo),
    /// A [`VelocityServo`].
    Velocity(VelocityServo),
    /// A [`TorqueMotor`].
    Torque(TorqueMotor),
    /// A [`DcMotor`].
    DcMotor(DcMotor),
    /// An [`Actuator`].
    Actuator(Actuator),
}

impl SavedController {
    /// The controller, ready to drive a joint.
    pub fn into_controller(self) -> Box<dyn JointController> {
        match self {
            SavedController::Position(c) => Box::new(c),
            SavedController::Velocity(c) => Box::new(c),
            SavedController::Torque(c) => Box::new(c),
            SavedController::DcMotor(c) => Box::new(c),
            SavedController::Actuator(c) => Box::new(c),
        }
    }
}

/// A set-point that varies with time: piecewise linear through `(time, value)`
/// breakpoints, constant before the first and after the last.
///
/// ```
/// use ars_core::Profile;
/// // The thesis' speed profile: 0 until 1 s, up to 1 m/s at 5 s, hold to 9 s, down at 13 s.
/// let p = Profile::trapezoid(1.0, 5.0, 9.0, 13.0, 0.0, 1.0)?;
/// assert_eq!(p.value(0.5), 0.0);
/// assert_eq!(p.value(3.0), 0.5);
/// assert_eq!(p.value(7.0), 1.0);
/// assert_eq!(p.value(20.0), 0.0);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Profile {
    points: Vec<(f64, f64)>,
}

impl Profile {
    /// Through `points`, whose times must be finite and non-decreasing.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Self> {
        if points.is_empty() {
            return Err(Error::Invalid { what: "a profile", problem: "needs at least one point".into() });
        }
        if points.iter().any(|(t, v)| !t.is_finite() || !v.is_finite()) {
            return Err(Error::NotFinite { what: "profile point", value: format!("{points:?}") });
        }
        if points.windows(2).any(|w| w[1].0 < w[0].0) {
            return Err(Error::Invalid { what: "a profile's times", problem: "must not decrease".into() });
        }
        Ok(Profile { points })
    }

    /// A constant value.
    pub fn constant(value: f64) -> Result<Self> {
        Self::new(vec![(0.0, value)])
    }

    /// `from` until `t0`, a linear ramp to `to` at `t1`, then `to`.
    pub fn ramp(t0: f64, t1: f64, from: f64, to: f64) -> Result<Self> {
        Self::new(vec![(t0, from), (t1, to)])
    }

    /// `low` until `t0`, up to `high` at `t1`, held until `t2`, down to `low` at `t3`.
    pub fn trapezoid(t0: f64, t1: f64, t2: f64, t3: f64, low: f64, high: f64) -> Result<Self> {
        Self::new(vec![(t0, low), (t1, high), (t2, high), (t3, low)])
    }

    /// The value at `time`.
    pub fn value(&self, time: f64) -> f64 {
        let p = &self.points;
        if time <= p[0].0 {
            return p[0].1;
        }
        for w in p.windows(2) {
            let ((t0, v0), (t1, v1)) = (w[0], w[1]);
            if time <= t1 {
                if t1 == t0 {
                    return v1;
                }
                return v0 + (v1 - v0) * (time - t0) / (t1 - t0);
            }
        }
        p[p.len() - 1].1
    }
}

/// A PID controller on `error = setpoint − measured`; the derivative is the backward
/// difference of the error over `dt` with the previous error starting at 0, as in the
/// original ARS' PD controllers.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Pid {
    /// Proportional gain.
    pub kp: f64,
    /// Integral gain.
    pub ki: f64,
    /// Derivative gain.
    pub kd: f64,
    previous_error: f64,
    integral: f64,
}

impl Pid {
    /// A PID controller.
    pub fn new(kp: f64, ki: f64, kd: f64) -> Self {
        Pid { kp, ki, kd, previous_error: 0.0, integral: 0.0 }
    }

    /// A PD controller.
    pub fn pd(kp: f64, kd: f64) -> Self {
        Self::new(kp, 0.0, kd)
    }

    /// The output for this error, advancing the controller's state by `dt`.
    pub fn update(&mut self, error: f64, dt: f64) -> f64 {
        self.integral += error * dt;
        let derivative = if dt > 0.0 { (error - self.previous_error) / dt } else { 0.0 };
        self.previous_error = error;
        self.kp * error + self.ki * self.integral + self.kd * derivative
    }

    /// Forgets the previous error and the integral.
    pub fn reset(&mut self) {
        self.previous_error = 0.0;
        self.integral = 0.0;
    }
}

/// Holds a joint at a set-point position (rad or m) with a PID controller.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct PositionServo {
    /// The set-point over time.
    pub setpoint: Profile,
    /// The controller.
    pub pid: Pid,
}

impl PositionServo {
    /// A PD position servo.
    pub fn pd(setpoint: Profile, kp: f64, kd: f64) -> Self {
        PositionServo { setpoint, pid: Pid::pd(kp, kd) }
    }
}

impl JointController for PositionServo {
    fn output(&mut self, time: f64, state: JointState, dt: f64) -> f64 {
        self.pid.update(self.setpoint.value(time) - state.position, dt)
    }
    fn saved(&self) -> Option<SavedController> {
        Some(SavedController::Position(self.clone()))
    }
}

/// Drives a joint's rate towards a set-point with a proportional gain (what the
/// original's speed-profile example does on the wheels).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct VelocityServo {
    /// The set-point over time (rad/s or m/s).
    pub setpoint: Profile,
    /// Proportional gain (N·m per rad/s, or N per m/s).
    pub gain: f64,
}

impl JointController for VelocityServo {
    fn output(&mut self, time: f64, state: JointState, _dt: f64) -> f64 {
        self.gain * (self.setpoint.value(time) - state.rate)
    }
    fn saved(&self) -> Option<SavedController> {
        Some(SavedController::Velocity(self.clone()))
    }
}

/// What an [`Actuator`]'s force is made of, as in MuJoCo's actuator shortcuts.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum ActuatorKind {
    /// `force = ctrl` (MuJoCo's `motor`).
    Motor,
    /// `force = kp·(ctrl − length) − kv·velocity` (MuJoCo's `position`).
    Position {
        /// Position gain, N·m per rad (or N per m) of actuator length.
        kp: f64,
        /// Damping gain, N·m·s per rad (or N·s per m); 0 for none.
        kv: f64,
    },
    /// `force = kv·(ctrl − velocity)` (MuJoCo's `velocity`).
    Velocity {
        /// Velocity gain, N·m·s per rad (or N·s per m).
        kv: f64,
    },
    /// `force = gain·ctrl + bias[0] + bias[1]·length + bias[2]·velocity` (MuJoCo's
    /// `general` with no activation dynamics, a fixed gain and an affine bias: its
    /// `gainprm[0]` and `biasprm[0..3]`; the shortcuts above are special cases).
    General {
        /// Force per unit of control.
        gain: f64,
        /// The bias: a constant force, then per unit of actuator length and of velocity.
        bias: [f64; 3],
    },
}

/// A named actuator on a joint, as MuJoCo models one: a control input `ctrl` (set
/// with [`Scene::set_control`](crate::Scene::set_control), clamped to `ctrl_range`),
/// an actuator length `gear·q` and velocity `gear·q̇`, a force from [`ActuatorKind`]
/// clamped to `force_range`, and the joint torque (or force) `gear·force`. What an MJCF
/// file's `<motor>`, `<position>`, `<velocity>` and `<general>` become.
///
/// ```
/// use ars_core::{Actuator, ActuatorKind, JointController, JointState};
/// let mut a = Actuator::new("elbow", ActuatorKind::Position { kp: 10.0, kv: 0.0 }, 2.0)?.with_ctrl_range(-1.0, 1.0)?;
/// a.set_ctrl(5.0)?; // clamped to 1
/// // length 2 × 0.25: force 10 × (1 − 0.5) = 5, torque 2 × 5.
/// assert_eq!(a.output(0.0, JointState { position: 0.25, rate: 0.0 }, 1e-3), 10.0);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Actuator {
    name: String,
    kind: ActuatorKind,
    gear: f64,
    ctrl: f64,
    ctrl_range: Option<(f64, f64)>,
    force_range: Option<(f64, f64)>,
}

impl Actuator {
    /// Names it `name` (a model loaded with a prefix).
    pub(crate) fn rename(&mut self, name: String) {
        self.name = name;
    }

    /// An actuator called `name` of this kind and gear, its control at 0, unlimited.
    pub fn new(name: impl Into<String>, kind: ActuatorKind, gear: f64) -> Result<Self> {
        if !gear.is_finite() || gear == 0.0 {
            return Err(Error::Invalid {
                what: "an actuator's gear",
                problem: format!("must be finite and not 0, got {gear}"),
            });
        }
        let gains = match kind {
            ActuatorKind::Motor => vec![],
            ActuatorKind::Position { kp, kv } => vec![kp, kv],
            ActuatorKind::Velocity { kv } => vec![kv],
            // Any sign, as in MuJoCo (a bias that pushes is a spring of negative stiffness).
            ActuatorKind::General { gain, bias } => {
                if let Some(bad) = [gain].iter().chain(&bias).find(|g| !g.is_finite()) {
                    return Err(Error::NotFinite { what: "an actuator's gain or bias", value: bad.to_string() });
                }
                vec![]
            }
        };
        if let Some(bad) = gains.iter().find(|g| !(g.is_finite() && **g >= 0.0)) {
            return Err(Error::OutOfRange {
                what: "an actuator's gain",
                detail: format!("must be finite and ≥ 0, got {bad}"),
            });
        }
        Ok(Actuator { name: name.into(), kind, gear, ctrl: 0.0, ctrl_range: None, force_range: None })
    }

    /// With its control clamped to `[low, high]`.
    pub fn with_ctrl_range(mut self, low: f64, high: f64) -> Result<Self> {
        self.ctrl_range = Some(range("an actuator's control range", low, high)?);
        self.ctrl = self.ctrl.clamp(low, high);
        Ok(self)
    }

    /// With its force clamped to `[low, high]` (before the gear).
    pub fn with_force_range(mut self, low: f64, high: f64) -> Result<Self> {
        self.force_range = Some(range("an actuator's force range", low, high)?);
        Ok(self)
    }

    /// Its name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its kind and gains.
    pub fn kind(&self) -> ActuatorKind {
        self.kind
    }

    /// Its gear: the actuator length per unit of joint position.
    pub fn gear(&self) -> f64 {
        self.gear
    }

    /// Its control now.
    pub fn ctrl(&self) -> f64 {
        self.ctrl
    }

    /// Its control range, if limited.
    pub fn ctrl_range(&self) -> Option<(f64, f64)> {
        self.ctrl_range
    }

    /// Its force range, if limited.
    pub fn force_range(&self) -> Option<(f64, f64)> {
        self.force_range
    }

    /// Sets the control (clamped to the control range), held until set again.
    pub fn set_ctrl(&mut self, ctrl: f64) -> Result<()> {
        if !ctrl.is_finite() {
            return Err(Error::NotFinite { what: "an actuator's control", value: ctrl.to_string() });
        }
        self.ctrl = self.ctrl_range.map_or(ctrl, |(lo, hi)| ctrl.clamp(lo, hi));
        Ok(())
    }
}

/// `[low, high]`, checked.
fn range(what: &'static str, low: f64, high: f64) -> Result<(f64, f64)> {
    if low.is_nan() || high.is_nan() || low > high {
        return Err(Error::Invalid { what, problem: format!("must be low ≤ high, got [{low}, {high}]") });
    }
    Ok((low, high))
}

impl JointController for Actuator {
    fn output(&mut self, _time: f64, state: JointState, _dt: f64) -> f64 {
        let (length, velocity) = (self.gear * state.position, self.gear * state.rate);
        let force = match self.kind {
            ActuatorKind::Motor => self.ctrl,
            ActuatorKind::Position { kp, kv } => kp * (self.ctrl - length) - kv * velocity,
            ActuatorKind::Velocity { kv } => kv * (self.ctrl - velocity),
            ActuatorKind::General { gain, bias } => gain * self.ctrl + bias[0] + bias[1] * length + bias[2] * velocity,
        };
        let force = self.force_range.map_or(force, |(lo, hi)| force.clamp(lo, hi));
        self.gear * force
    }
    fn saved(&self) -> Option<SavedController> {
        Some(SavedController::Actuator(self.clone()))
    }
}

/// Applies a torque (or force) that follows a profile, whatever the joint does.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct TorqueMotor {
    /// The torque over time.
    pub torque: Profile,
}

impl JointController for TorqueMotor {
    fn output(&mut self, time: f64, _state: JointState, _dt: f64) -> f64 {
        self.torque.value(time)
    }
    fn saved(&self) -> Option<SavedController> {
        Some(SavedController::Torque(self.clone()))
    }
}

/// A permanent-magnet DC motor with a gearbox driving the joint, under a voltage
/// profile. With `n` the gear ratio and `ω` the joint rate (the rotor turns at `n·ω`):
///
/// - the winding: `L · di/dt = V − R·i − k_e·n·ω`; over each step the current is
///   integrated exactly with `V` and `ω` held (an exponential of time constant `L/R`;
///   with no inductance the current is `(V − k_e·n·ω)/R` at once), and the step's
///   torque uses its mean over the step;
/// - the shaft: `τ = n·k_t·i − n²·b·ω − n²·J_r·α`, with `b` the rotor's viscous
///   friction and `J_r` its inertia seen through the gearbox (`α` is the joint
///   acceleration of the last step: the reflected inertia acts one step late, which is
///   stable while `n²·J_r` stays below the inertia the joint drives).
///
/// With no inductance, rotor inertia or load, a joint of inertia `I` starting at rest
/// under a voltage step `V` speeds up as `ω(t) = ω∞·(1 − e^(−t/τ))`, with
/// `ω∞ = k_t·V / (n·(k_t·k_e + R·b))` and `τ = I·R / (n²·(k_t·k_e + R·b))`
/// (`tests/dc_motor.rs` checks it, with an error proportional to the time step).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct DcMotor {
    /// Supply voltage over time, V.
    pub voltage: Profile,
    /// Torque constant, N·m/A.
    pub torque_constant: f64,
    /// Back-EMF constant, V·s/rad.
    pub back_emf_constant: f64,
    /// Winding resistance, Ω.
    pub resistance: f64,
    /// Gear ratio (motor turns per joint turn).
    pub gear_ratio: f64,
    /// Rotor inertia, kg·m².
    pub rotor_inertia: f64,
    /// Winding inductance, H (0: none).
    #[serde(default)]
    pub inductance: f64,
    /// Viscous friction of the rotor, N·m·s/rad (at the motor, before the gearbox).
    #[serde(default)]
    pub friction: f64,
    /// The winding current now, A.
    #[serde(default)]
    current: f64,
    previous_rate: Option<f64>,
}

impl DcMotor {
    /// A motor without inductance or friction; every constant must be finite,
    /// resistance and gear ratio positive.
    pub fn new(
        voltage: Profile,
        torque_constant: f64,
        back_emf_constant: f64,
        resistance: f64,
        gear_ratio: f64,
        rotor_inertia: f64,
    ) -> Result<Self> {
        crate::validate::non_negative("torque constant", torque_constant)?;
        crate::validate::non_negative("back-EMF constant", back_emf_constant)?;
        crate::validate::positive("winding resistance", resistance)?;
        crate::validate::positive("gear ratio", gear_ratio)?;
        crate::validate::non_negative("rotor inertia", rotor_inertia)?;
        Ok(DcMotor {
            voltage,
            torque_constant,
            back_emf_constant,
            resistance,
            gear_ratio,
            rotor_inertia,
            inductance: 0.0,
            friction: 0.0,
            current: 0.0,
            previous_rate: None,
        })
    }

    /// The motor with a winding inductance, H (finite, ≥ 0).
    pub fn with_inductance(mut self, inductance: f64) -> Result<Self> {
        self.inductance = crate::validate::non_negative("winding inductance", inductance)?;
        Ok(self)
    }

    /// The motor with a viscous friction of its rotor, N·m·s/rad (finite, ≥ 0).
    pub fn with_friction(mut self, friction: f64) -> Result<Self> {
        self.friction = crate::validate::non_negative("rotor friction", friction)?;
        Ok(self)
    }

    /// Steady winding current at joint rate `rate` and voltage `voltage`, A: what the
    /// current settles to (at once, without inductance).
    pub fn current(&self, voltage: f64, rate: f64) -> f64 {
        (voltage - self.back_emf_constant * self.gear_ratio * rate) / self.resistance
    }

    /// The winding current at the end of the last step, A.
    pub fn winding_current(&self) -> f64 {
        self.current
    }
}

impl JointController for DcMotor {
    fn output(&mut self, time: f64, state: JointState, dt: f64) -> f64 {
        let n = self.gear_ratio;
        let steady = self.current(self.voltage.value(time), state.rate);
        let mean = if self.inductance > 0.0 && dt > 0.0 {
            // i(t) = steady + (i0 − steady)·e^(−t/T), T = L/R, over the step.
            let ratio = self.resistance * dt / self.inductance;
            let decay = (-ratio).exp();
            let mean = steady + (self.current - steady) * (-(-ratio).exp_m1()) / ratio;
            self.current = steady + (self.current - steady) * decay;
            mean
        } else {
            self.current = steady;
            steady
        };
        let accel = match self.previous_rate {
            Some(prev) if dt > 0.0 => (state.rate - prev) / dt,
            _ => 0.0,
        };
        self.previous_rate = Some(state.rate);
        n * self.torque_constant * mean - n * n * (self.friction * state.rate + self.rotor_inertia * accel)
    }
    fn saved(&self) -> Option<SavedController> {
        Some(SavedController::DcMotor(self.clone()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_interpolate_and_refuse_bad_points() {
        let r = Profile::ramp(1.0, 3.0, 0.0, 4.0).unwrap();
        assert_eq!(r.value(0.0), 0.0);
        assert_eq!(r.value(2.0), 2.0);
        assert_eq!(r.value(9.0), 4.0);
        assert!(Profile::new(vec![(1.0, 0.0), (0.5, 1.0)]).is_err());
        assert!(Profile::new(vec![]).is_err());
        assert!(Profile::new(vec![(f64::NAN, 0.0)]).is_err());
    }

    #[test]
    fn pd_uses_the_backward_difference_from_zero() {
        let mut pd = Pid::pd(1.0, 0.5);
        // First call: e = 2, previous 0: 1·2 + 0.5·(2 − 0)/0.1 = 12.
        assert!((pd.update(2.0, 0.1) - 12.0).abs() < 1e-12);
        assert!((pd.update(2.0, 0.1) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn dc_motor_stalls_and_runs_free() {
        let mut m = DcMotor::new(Profile::constant(12.0).unwrap(), 0.1, 0.1, 2.0, 10.0, 0.0).unwrap();
        // Stall: τ = n kt V / R = 10 · 0.1 · 12 / 2 = 6.
        assert!((m.output(0.0, JointState::default(), 0.001) - 6.0).abs() < 1e-12);
        assert!((m.current(12.0, 0.0) - 6.0).abs() < 1e-12);
        // No-load speed: V = ke n ω → ω = 12 rad/s: no torque.
        let free = JointState { position: 0.0, rate: 12.0 };
        let mut m2 = DcMotor::new(Profile::constant(12.0).unwrap(), 0.1, 0.1, 2.0, 10.0, 0.0).unwrap();
        assert!(m2.output(0.0, free, 0.001).abs() < 1e-12);
        // A rotor inertia resists acceleration: 10² · 0.01 · (1 rad/s / 0.1 s) = 10 N·m less.
        let mut m3 = DcMotor::new(Profile::constant(0.0).unwrap(), 0.0, 0.0, 1.0, 10.0, 0.01).unwrap();
        m3.output(0.0, JointState { position: 0.0, rate: 0.0 }, 0.1);
        assert!((m3.output(0.1, JointState { position: 0.0, rate: 1.0 }, 0.1) + 10.0).abs() < 1e-9);
    }
}
