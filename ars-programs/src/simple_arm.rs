//! The original's `SimpleArm` and `ControlledSimpleArm` demos: a two-link arm of
//! capsules on a free base box, the waist driven by keys, the shoulder free or held by
//! a PD controller.

use std::f64::consts::FRAC_PI_2;

use crate::{SetpointKeys, ShoulderSetpoint, hold_shoulder};
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::{Probe, Record, SensorId};
use ars_core::{
    ActionMap, Hooks, JointId, Key, Mass, ObjectId, Program, Repeat, Result, Simulation, SimulationBuilder, SpaceKind,
};

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
    let base = sim.scene_mut().add_box([3.0, 0.5, 3.0], Point3::new(0.0, -0.75, 0.0) + offset, Mass::Density(1.0))?;
    let link1 = sim.scene_mut().add_capsule(0.1, 0.8, [0.0, 0.0, 0.0], Mass::Density(1.0))?;
    let link2 = sim.scene_mut().add_capsule(0.1, 0.6, [0.0, 0.7, 0.2], Mass::Density(1.0))?;
    for link in [link1, link2] {
        sim.scene_mut().rotate(link, Vector3::x(), FRAC_PI_2)?;
        sim.scene_mut().offset_by_position(link, offset)?;
    }
    let r1 = sim.scene_mut().add_hinge_joint("r1", base, link1, None, Vector3::y())?;
    let anchor = sim.scene().position(link2)? - Vector3::new(0.0, 0.3, 0.0);
    let r2 = sim.scene_mut().add_hinge_joint("r2", link1, link2, Some(anchor), Vector3::z())?;
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
    sim.scene_mut().joint_mut(r1)?.add_torque(torque)
}

impl Hooks for SimpleArm {}

impl Program for SimpleArm {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

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

/// One line of `ControlledSimpleArm`'s output, at the start of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlRow {
    /// Shoulder set-point, rad.
    pub setpoint: f64,
    /// Shoulder angle, rad.
    pub angle: f64,
    /// Set-point minus angle, rad.
    pub error: f64,
    /// Torque of the shoulder's servo, N·m.
    pub torque: f64,
}

impl Record for ControlRow {
    fn columns() -> Vec<&'static str> {
        vec!["setpoint [rad]", "angle [rad]", "error [rad]", "torque [N m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [self.setpoint, self.angle, self.error, self.torque].map(Some).to_vec()
    }
}

/// `ControlledSimpleArm`: the shoulder held at a set-point by a PD position servo
/// (Kp 1, Kd 0.5; keys 'd'/'c' move the set-point by ±0.1 rad), viscous friction 0.01
/// on both joints from the current rates; keys 'a'/'z' push the waist as in
/// [`SimpleArm`]. Every step records set-point, angle, error and servo torque.
#[derive(Clone, Debug, Default)]
pub struct ControlledSimpleArm {
    /// The arm, once built.
    pub parts: Option<ArmParts>,
    /// What the shoulder's servo does, at the start of every step.
    pub record: Option<SensorId<Probe<ControlRow>>>,
}

impl ControlledSimpleArm {
    /// Friction coefficient of both joints, N·m·s.
    pub const FRICTION: f64 = 0.01;
    /// Set-point change of one key press, rad.
    pub const SETPOINT_STEP: f64 = 0.1;
    /// Gains of the shoulder's PD servo.
    pub const GAINS: (f64, f64) = (1.0, 0.5);
}

impl Hooks for ControlledSimpleArm {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let p = self.parts.expect("built");
        sim.scene_mut().joint_mut(p.r1)?.add_torque(0.0)?;
        let (q1, q2) = (sim.scene().joint_rate(p.r1)?, sim.scene().joint_rate(p.r2)?);
        sim.scene_mut().joint_mut(p.r1)?.add_torque(-Self::FRICTION * q1)?;
        sim.scene_mut().joint_mut(p.r2)?.add_torque(-Self::FRICTION * q2)
    }
}

impl ShoulderSetpoint for ControlledSimpleArm {
    fn shoulder(&self) -> Option<JointId> {
        self.parts.map(|p| p.r2)
    }
}

impl Program for ControlledSimpleArm {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let parts = build_simple_arm(sim)?;
        let (kp, kd) = Self::GAINS;
        self.record = Some(hold_shoulder(sim, parts.r2, kp, kd)?);
        self.parts = Some(parts);
        Ok(())
    }
    fn key_bindings(&self) -> ActionMap<Self> {
        ActionMap::new()
            .add(Key::Char('a'), |p: &mut Self, sim| push_waist(p.parts, sim, SimpleArm::TORQUE), Repeat::Once)
            .add(Key::Char('z'), |p: &mut Self, sim| push_waist(p.parts, sim, -SimpleArm::TORQUE), Repeat::Once)
            .add_setpoint_keys(Self::SETPOINT_STEP)
    }
}
