//! The thesis' validation robot (IROS example 2): a 2-DOF arm on a heavy free base,
//! whose waist is driven by a saturating torque against viscous friction, so that the
//! free shoulder swings out into a conical pendulum.

use std::f64::consts::FRAC_PI_2;

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::{Probe, Record, SensorId};
use ars_core::{
    HookPoint, Hooks, JointId, Mass, ObjectId, Program, Result, Scene, Simulation, SimulationBuilder, SpaceKind,
};

/// One record of the pendulum: the state the pre-step hook reads at the start of a
/// step, and the waist torque it applies (without friction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PendulumRow {
    /// Waist angle, rad.
    pub q1: f64,
    /// Waist rate, rad/s.
    pub q1_rate: f64,
    /// Shoulder angle from hanging, rad.
    pub q2: f64,
    /// Shoulder rate, rad/s.
    pub q2_rate: f64,
    /// Waist torque applied in this step (without friction), N·m.
    pub torque: f64,
}

/// IROS example 2 exactly (thesis §1.5, original `example2_conical_pendulum.py`):
/// base box 10 × 0.5 × 10 m of density 100 (5000 kg) resting free on the plane
/// y = −0.5; pole and arm cylinders (length 1, radius 0.141421, 10 kg) turned to hang
/// along −Y; waist hinge (base–pole) about Y at (1, 0.51, 2), shoulder hinge (pole–arm)
/// about X at (1, 1.01, 2.1). 50 frames/s × 80 steps: dt = 0.25 ms. Before every step
/// the waist gets `20 t` N·m (saturating at 20 N·m after 1 s) and both joints a viscous
/// friction of `−5 · rate`, with the rates read in the previous step.
#[derive(Clone, Debug, Default)]
pub struct ConicalPendulum {
    /// The base box.
    pub base: Option<ObjectId>,
    /// The pole (first link).
    pub pole: Option<ObjectId>,
    /// The arm (second link).
    pub arm: Option<ObjectId>,
    /// The waist joint.
    pub waist: Option<JointId>,
    /// The shoulder joint.
    pub shoulder: Option<JointId>,
    previous_rates: (f64, f64),
    /// The record of every step (at its start).
    pub record: Option<SensorId<Probe<PendulumRow>>>,
}

impl Record for PendulumRow {
    fn columns() -> Vec<&'static str> {
        vec!["q1 [rad]", "q1 rate [rad/s]", "q2 [rad]", "q2 rate [rad/s]", "waist torque [N m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [self.q1, self.q1_rate, self.q2, self.q2_rate, self.torque].map(Some).to_vec()
    }
}

impl ConicalPendulum {
    /// Frames per second of the original.
    pub const FPS: f64 = 50.0;
    /// Steps per frame of the original.
    pub const STEPS_PER_FRAME: u32 = 80;
    /// Viscous friction on both joints: 50e-3 N·m·s × gear ratio 100.
    pub const FRICTION: f64 = 50e-3 * 100.0;
    /// Saturation of the waist torque, N·m.
    pub const MAX_TORQUE: f64 = 20.0;
    /// Time the waist torque takes to saturate, s.
    pub const SATURATION_TIME: f64 = 1.0;

    /// The waist torque at `time`.
    pub fn waist_torque(time: f64) -> f64 {
        if time < Self::SATURATION_TIME { Self::MAX_TORQUE * time / Self::SATURATION_TIME } else { Self::MAX_TORQUE }
    }
}

impl Hooks for ConicalPendulum {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let (waist, shoulder) = (self.waist.expect("created"), self.shoulder.expect("created"));
        let time = sim.scene().time();
        let torque = Self::waist_torque(time);
        let (q1_prev, q2_prev) = self.previous_rates;
        {
            let mut r1 = sim.scene_mut().joint_mut(waist)?;
            r1.add_torque(torque)?;
            r1.add_torque(-Self::FRICTION * q1_prev)?;
        }
        sim.scene_mut().joint_mut(shoulder)?.add_torque(-Self::FRICTION * q2_prev)?;
        self.previous_rates = (sim.scene().joint_rate(waist)?, sim.scene().joint_rate(shoulder)?);
        Ok(())
    }
    /// Only the pre-step hook does something (added hooks are not called elsewhere).
    fn runs_at(&self, point: HookPoint) -> bool {
        point == HookPoint::PreStep
    }
    /// The rates read in the previous step (the next step's friction).
    fn save_state(&self) -> Vec<u64> {
        vec![self.previous_rates.0.to_bits(), self.previous_rates.1.to_bits()]
    }
    fn restore_state(&mut self, state: &[u64]) -> Result<()> {
        if let [q1, q2] = state {
            self.previous_rates = (f64::from_bits(*q1), f64::from_bits(*q2));
        }
        Ok(())
    }
}

impl Program for ConicalPendulum {
    fn window_settings(&self) -> ars_core::WindowSettings {
        ars_core::WindowSettings {
            title: "ARS: conical pendulum (IROS example 2)".into(),
            camera_position: ars_core::nalgebra::Point3::new(6.0, 3.0, 6.0),
            camera_target: ars_core::nalgebra::Point3::new(1.0, 0.5, 2.0),
            ..Default::default()
        }
    }

    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder
            .space(SpaceKind::Simple)
            .time_step(1.0 / Self::FPS / f64::from(Self::STEPS_PER_FRAME))
            .steps_per_frame(Self::STEPS_PER_FRAME)
            .floor_plane(Vector3::y(), -0.5)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let offset = Vector3::new(1.0, 0.0, 2.0);
        let radius = 0.141421;
        let base =
            sim.scene_mut().add_box([10.0, 0.5, 10.0], Point3::new(0.0, -0.25, 0.0) + offset, Mass::Density(100.0))?;
        let pole = sim.scene_mut().add_cylinder(radius, 1.0, [0.0, 0.51, 0.0], Mass::Total(10.0))?;
        let arm = sim.scene_mut().add_cylinder(radius, 1.0, [0.0, 0.51, 0.1], Mass::Total(10.0))?;
        for link in [pole, arm] {
            sim.scene_mut().rotate(link, Vector3::x(), FRAC_PI_2)?;
            sim.scene_mut().offset_by_position(link, offset)?;
        }
        sim.scene_mut().set_color(base, [0.55, 0.6, 0.65])?;
        sim.scene_mut().set_color(pole, ars_core::colors::YELLOW)?;
        sim.scene_mut().set_color(arm, ars_core::colors::NAVY)?;
        let waist = sim.scene_mut().add_hinge_joint("r1", base, pole, None, Vector3::y())?;
        let shoulder = sim.scene_mut().add_hinge_joint(
            "r2",
            pole,
            arm,
            Some(Point3::new(0.0, 1.01, 0.1) + offset),
            Vector3::x(),
        )?;
        (self.base, self.pole, self.arm) = (Some(base), Some(pole), Some(arm));
        (self.waist, self.shoulder) = (Some(waist), Some(shoulder));
        let probe = Probe::at_step_start(move |scene: &Scene| {
            let (s1, s2) = (scene.joint_state(waist)?, scene.joint_state(shoulder)?);
            let torque = Self::waist_torque(scene.time());
            Ok(PendulumRow { q1: s1.position, q1_rate: s1.rate, q2: s2.position, q2_rate: s2.rate, torque })
        });
        self.record = Some(sim.add_sensor(probe.reads_joints([waist, shoulder]))?);
        Ok(())
    }
}
