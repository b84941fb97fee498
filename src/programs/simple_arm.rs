//! The original's `SimpleArm` and `ControlledSimpleArm` demos: a two-link arm of
//! capsules on a free base box, the waist driven by keys, the shoulder free or held by
//! a PD controller.

use std::f64::consts::FRAC_PI_2;

use super::{SetpointKeys, ShoulderSetpoint};
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{ActionMap, Hooks, JointId, Key, Mass, ObjectId, Pid, Program, Repeat, Result, Simulation};

/// The arm's bodies and joints.
#[derive(Clone, Copy, Debug)]
pub struct ArmParts {
    /// The base box.
    pub base: ObjectId,
    /// The first link.
    pub link1: ObjectId,
    /// The second link.
    pub link2: ObjectId,
    /// Waist (base–link1, about Y).
    pub r1: JointId,
    /// Shoulder (link1–link2, about Z).
    pub r2: JointId,
}

/// Builds the arm: base box 3 × 0.5 × 3 m (density 1) at (2.5, 0.25, 2.5); capsules of
/// length 0.8 and 0.6, radius 0.1, density 1, turned upright and stacked from
/// (2.5, 1, 2.5); waist about Y at link1's centre, shoulder about Z at (2.5, 1.4, 2.7).
pub fn build_simple_arm(sim: &mut Simulation) -> Result<ArmParts> {
    let offset = Vector3::new(2.5, 1.0, 2.5);
    let base = sim.add_box([3.0, 0.5, 3.0], Point3::new(0.0, -0.75, 0.0) + offset, Mass::Density(1.0))?;
    let link1 = sim.add_capsule(0.8, 0.1, [0.0, 0.0, 0.0], Mass::Density(1.0))?;
    let link2 = sim.add_capsule(0.6, 0.1, [0.0, 0.7, 0.2], Mass::Density(1.0))?;
    for link in [link1, link2] {
        sim.rotate(link, Vector3::x(), FRAC_PI_2)?;
        sim.offset_by_position(link, offset)?;
    }
    let r1 = sim.add_rotary_joint("r1", base, link1, None, Vector3::y())?;
    let anchor = sim.position(link2)? - Vector3::new(0.0, 0.3, 0.0);
    let r2 = sim.add_rotary_joint("r2", link1, link2, Some(anchor), Vector3::z())?;
    Ok(ArmParts { base, link1, link2, r1, r2 })
}

/// `SimpleArm`: keys 'a' and 'z' add ±3 N·m to the waist for one step.
#[derive(Clone, Debug, Default)]
pub struct SimpleArm {
    /// The arm, once built.
    pub parts: Option<ArmParts>,
}

impl SimpleArm {
    /// Torque of one key press, N·m.
    pub const TORQUE: f64 = 3.0;
}

fn push_waist(parts: Option<ArmParts>, sim: &mut Simulation, torque: f64) -> Result<()> {
    let r1 = parts.expect("built").r1;
    sim.joint_mut(r1)?.add_torque(torque)
}

impl Hooks for SimpleArm {}

impl Program for SimpleArm {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        self.parts = Some(build_simple_arm(sim)?);
        Ok(())
    }
    fn key_bindings(&self) -> ActionMap<Self> {
        ActionMap::new()
            .add(Key::Char('a'), |p: &mut Self, sim| push_waist(p.parts, sim, Self::TORQUE), Repeat::Once)
            .add(Key::Char('z'), |p: &mut Self, sim| push_waist(p.parts, sim, -Self::TORQUE), Repeat::Once)
    }
}

/// One line of `ControlledSimpleArm`'s output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlRow {
    /// Time at the start of the step, s.
    pub time: f64,
    /// Shoulder set-point, rad.
    pub setpoint: f64,
    /// Shoulder angle, rad.
    pub angle: f64,
    /// Set-point minus angle, rad.
    pub error: f64,
    /// Shoulder torque, N·m.
    pub torque: f64,
}

/// `ControlledSimpleArm`: the shoulder held at a set-point by a PD controller
/// (Kp 1, Kd 0.5; keys 'd'/'c' move the set-point by ±0.1 rad), viscous friction 0.01
/// on both joints from the current rates; keys 'a'/'z' push the waist as in
/// [`SimpleArm`]. Every step records `time, sp, cv, error, torque`.
#[derive(Clone, Debug)]
pub struct ControlledSimpleArm {
    /// The arm, once built.
    pub parts: Option<ArmParts>,
    /// Shoulder set-point, rad.
    pub setpoint: f64,
    /// The shoulder's controller.
    pub pd: Pid,
    /// Every step's row.
    pub rows: Vec<ControlRow>,
}

impl Default for ControlledSimpleArm {
    fn default() -> Self {
        ControlledSimpleArm { parts: None, setpoint: 0.0, pd: Pid::pd(1.0, 0.5), rows: Vec::new() }
    }
}

impl ControlledSimpleArm {
    /// Friction coefficient of both joints, N·m·s.
    pub const FRICTION: f64 = 0.01;
    /// Set-point change of one key press, rad.
    pub const SETPOINT_STEP: f64 = 0.1;
}

impl Hooks for ControlledSimpleArm {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let p = self.parts.expect("built");
        let cv = sim.joint_state(p.r2)?.position;
        let error = self.setpoint - cv;
        let torque = self.pd.update(error, sim.time_step());
        sim.joint_mut(p.r1)?.add_torque(0.0)?;
        sim.joint_mut(p.r2)?.add_torque(torque)?;
        let (q1, q2) = (sim.joint_state(p.r1)?.rate, sim.joint_state(p.r2)?.rate);
        sim.joint_mut(p.r1)?.add_torque(-Self::FRICTION * q1)?;
        sim.joint_mut(p.r2)?.add_torque(-Self::FRICTION * q2)?;
        self.rows.push(ControlRow { time: sim.time(), setpoint: self.setpoint, angle: cv, error, torque });
        Ok(())
    }
}

impl Program for ControlledSimpleArm {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        self.parts = Some(build_simple_arm(sim)?);
        Ok(())
    }
    fn key_bindings(&self) -> ActionMap<Self> {
        ActionMap::new()
            .add(Key::Char('a'), |p: &mut Self, sim| push_waist(p.parts, sim, SimpleArm::TORQUE), Repeat::Once)
            .add(Key::Char('z'), |p: &mut Self, sim| push_waist(p.parts, sim, -SimpleArm::TORQUE), Repeat::Once)
            .add_setpoint_keys(Self::SETPOINT_STEP)
    }
}

impl ShoulderSetpoint for ControlledSimpleArm {
    fn setpoint_mut(&mut self) -> &mut f64 {
        &mut self.setpoint
    }
}
