//! The original's vehicles as scene functions: a differential-drive base (two wheels
//! and a ball caster) and the 2-DOF arm it carries, used by the vehicle programs, the
//! IROS examples 3–5, the tests and the viewer alike.

use std::f64::consts::FRAC_PI_2;

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{JointId, Mass, ObjectId, Result, Scene, Shape, Simulation};

/// Parameters of a differential-drive base (the original's `Vehicle2` /
/// `VehicleWithArm` geometry before its offset: wheels at (0, 0, ∓0.5), caster ball at
/// (1, 0, 0), chassis 2 × 0.2 × 1.5 m at (0.5, 0.45, 0)).
#[derive(Clone, Debug)]
pub struct VehicleSpec {
    /// Where the vehicle is moved after its joints are made.
    pub offset: Vector3<f64>,
    /// Mass of each wheel (cylinders of length 0.4 and radius 0.3 along Z).
    pub wheel_mass: Mass,
    /// Capsule wheels instead of cylinders.
    pub capsule_wheels: bool,
    /// Mass of the chassis.
    pub chassis_mass: Mass,
    /// Prefix of the joint names (`w1`, `w2`, `bs`), so that several vehicles can share
    /// a simulation.
    pub prefix: String,
}

impl Default for VehicleSpec {
    fn default() -> Self {
        VehicleSpec {
            offset: Vector3::new(2.0, 0.35, 4.0),
            wheel_mass: Mass::Density(1.0),
            capsule_wheels: false,
            chassis_mass: Mass::Total(6.0),
            prefix: String::new(),
        }
    }
}

/// The bodies and joints of a vehicle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VehicleParts {
    /// The chassis box.
    pub chassis: ObjectId,
    /// The right wheel (−Z side).
    pub wheel_r: ObjectId,
    /// The left wheel (+Z side).
    pub wheel_l: ObjectId,
    /// The caster ball.
    pub ball: ObjectId,
    /// Right wheel joint.
    pub w1: JointId,
    /// Left wheel joint.
    pub w2: JointId,
    /// Caster ball joint.
    pub bs: JointId,
}

/// Builds a vehicle: ball, chassis, right and left wheel, wheel hinges about Z at the
/// wheel centres, the caster's ball joint, then everything moved by `spec.offset`.
pub fn build_vehicle(sim: &mut Simulation, spec: &VehicleSpec) -> Result<VehicleParts> {
    let ball = sim.scene_mut().add_sphere(0.3, [1.0, 0.0, 0.0], Mass::Density(1.0))?;
    let chassis = sim.scene_mut().add_box([2.0, 0.2, 1.5], [0.5, 0.45, 0.0], spec.chassis_mass)?;
    // Named, for the viewer's camera to follow ("chassis", then "chassis/1"...).
    let mut name = "chassis".to_string();
    for i in 1.. {
        if sim.scene().object(name.as_str()).is_err() {
            break;
        }
        name = format!("chassis/{i}");
    }
    sim.scene_mut().set_name(chassis, &name)?;
    let wheel = if spec.capsule_wheels {
        Shape::Capsule { length: 0.4, radius: 0.3 }
    } else {
        Shape::Cylinder { length: 0.4, radius: 0.3 }
    };
    let wheel_r = sim.scene_mut().add_body(wheel.clone(), [0.0, 0.0, -0.5], spec.wheel_mass)?;
    let wheel_l = sim.scene_mut().add_body(wheel, [0.0, 0.0, 0.5], spec.wheel_mass)?;
    let p = &spec.prefix;
    let w1 = sim.scene_mut().add_hinge_joint(&format!("{p}w1"), chassis, wheel_r, None, Vector3::z())?;
    let w2 = sim.scene_mut().add_hinge_joint(&format!("{p}w2"), chassis, wheel_l, None, Vector3::z())?;
    let bs = sim.scene_mut().add_ball_joint(&format!("{p}bs"), chassis, ball, None)?;
    for object in [ball, chassis, wheel_r, wheel_l] {
        sim.scene_mut().offset_by_position(object, spec.offset)?;
    }
    sim.scene_mut().set_color(chassis, [0.8, 0.0, 0.0])?;
    Ok(VehicleParts { chassis, wheel_r, wheel_l, ball, w1, w2, bs })
}

/// The arm on a vehicle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VehicleArm {
    /// First link (capsule 0.8 × 0.1).
    pub link1: ObjectId,
    /// Second link (capsule 0.6 × 0.1).
    pub link2: ObjectId,
    /// Waist (chassis–link1, about Y).
    pub r1: JointId,
    /// Shoulder (link1–link2, about Z); starts upright, an unstable equilibrium.
    pub r2: JointId,
}

/// Builds the 2-DOF arm on `chassis`: link1 (capsule 0.8 × 0.1) upright 0.5 m above
/// the chassis centre, link2 (capsule 0.6 × 0.1) on top of it and 0.2 m to +Z; waist
/// about Y at link1's centre, shoulder about Z 0.3 m below link2's centre.
pub fn build_vehicle_arm(sim: &mut Simulation, chassis: ObjectId, link_mass: Mass, prefix: &str) -> Result<VehicleArm> {
    let link1 = sim.scene_mut().add_capsule(0.1, 0.8, [0.0, 0.0, 0.0], link_mass)?;
    let link2 = sim.scene_mut().add_capsule(0.1, 0.6, [0.0, 0.7, 0.2], link_mass)?;
    sim.scene_mut().rotate(link1, Vector3::x(), FRAC_PI_2)?;
    sim.scene_mut().rotate(link2, Vector3::x(), FRAC_PI_2)?;
    sim.scene_mut().offset_by_object(link1, chassis)?;
    sim.scene_mut().offset_by_position(link1, [0.0, 0.5, 0.0])?;
    sim.scene_mut().offset_by_object(link2, link1)?;
    let r1 = sim.scene_mut().add_hinge_joint(&format!("{prefix}r1"), chassis, link1, None, Vector3::y())?;
    let anchor: Point3<f64> = sim.scene().position(link2)? - Vector3::new(0.0, 0.3, 0.0);
    let r2 = sim.scene_mut().add_hinge_joint(&format!("{prefix}r2"), link1, link2, Some(anchor), Vector3::z())?;
    sim.scene_mut().set_color(link1, [1.0, 1.0, 0.0])?;
    sim.scene_mut().set_color(link2, [0.0, 0.0, 0.5])?;
    Ok(VehicleArm { link1, link2, r1, r2 })
}

/// A vehicle with the arm on its chassis (the joints of the arm get the vehicle's
/// name prefix too).
pub fn build_mobile_manipulator(
    sim: &mut Simulation,
    spec: &VehicleSpec,
    link_mass: Mass,
) -> Result<(VehicleParts, VehicleArm)> {
    let vehicle = build_vehicle(sim, spec)?;
    let arm = build_vehicle_arm(sim, vehicle.chassis, link_mass, &spec.prefix)?;
    Ok((vehicle, arm))
}

/// Speed of the chassis along the ground with the sign of its X velocity, as the
/// original measured it: `sqrt(vx² + vz²) · sign(vx)`, with `sign(0) = −1` as the
/// original's. Computed as the original did (its `length2`: squares, sum, square
/// root), not with `hypot`, which rounds differently in the last digit.
pub fn signed_ground_speed(scene: &Scene, chassis: ObjectId) -> Result<f64> {
    let v = scene.body(chassis)?.linear_velocity();
    let sign = if v.x > 0.0 { 1.0 } else { -1.0 };
    Ok((v.x * v.x + v.z * v.z).sqrt() * sign)
}
