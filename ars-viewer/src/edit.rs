//! Changes made in the panel: one [`Edit`] at a time, applied through the safe API by
//! [`apply_edit`] (what the panel calls), which checks everything first, so that an
//! invalid value is an error and changes nothing.

use ars_core::nalgebra::{Point3, UnitQuaternion, Vector3};
use ars_core::{
    Actuator, DcMotor, Error, JointId, JointParam, MassSpec, ObjectId, PositionServo, Profile, Result, Simulation,
    VelocityServo,
};

/// One change to a simulation, as the panel asks for it.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Edit {
    /// An object's colour (channels in [0, 1]).
    Color(ObjectId, [f32; 3]),
    /// A body's total mass, kg: its mass distribution scaled (the inertia with it).
    Mass(ObjectId, f64),
    /// A body's density, kg/m³: its mass set to the density times its shape's volume,
    /// as [`Mass`](Self::Mass) does. Only for a body of one solid shape.
    Density(ObjectId, f64),
    /// A body's position, m (its centre of mass).
    Position(ObjectId, Point3<f64>),
    /// A body's orientation (about its centre of mass).
    Rotation(ObjectId, UnitQuaternion<f64>),
    /// A joint's limits on its first degree of freedom (rad or m; ±∞ for none).
    JointLimits(JointId, f64, f64),
    /// A joint's viscous friction coefficient.
    ViscousFriction(JointId, f64),
    /// A joint's velocity motor: target speed and the most force or torque it uses
    /// (0 turns it off).
    Motor(JointId, f64, f64),
    /// The set-point of a joint's controller, held from now on: a position servo's
    /// position, a velocity servo's speed, a DC motor's voltage.
    Setpoint(JointId, f64),
    /// A position servo's PID gains `kp, ki, kd`, or a velocity servo's gain (the first).
    Gains(JointId, [f64; 3]),
    /// Gravity, m/s².
    Gravity(Vector3<f64>),
    /// The time step, s.
    TimeStep(f64),
    /// The world's error reduction parameter.
    Erp(f64),
    /// The world's constraint force mixing.
    Cfm(f64),
}

/// Applies `edit` to `sim` through its safe API; on an error (a negative or NaN mass,
/// limits crossed, a joint without a controller…) nothing has changed.
///
/// ```
/// use ars_core::{Mass, Simulation};
/// use ars_viewer::{Edit, apply_edit};
///
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(2.0))?;
/// apply_edit(&mut sim, &Edit::Mass(ball, 3.0))?;
/// assert_eq!(sim.scene().body(ball)?.mass(), 3.0);
/// assert!(apply_edit(&mut sim, &Edit::Mass(ball, -1.0)).is_err());
/// assert_eq!(sim.scene().body(ball)?.mass(), 3.0);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub fn apply_edit(sim: &mut Simulation, edit: &Edit) -> Result<()> {
    match *edit {
        Edit::Color(id, rgb) => sim.scene_mut().set_color(id, rgb),
        Edit::Mass(id, mass) => set_mass(sim, id, mass),
        Edit::Density(id, density) => {
            let volume = solid_volume(sim, id)?;
            if !(density.is_finite() && density > 0.0) {
                return Err(Error::NotPositive { what: "density", value: density });
            }
            set_mass(sim, id, density * volume)
        }
        Edit::Position(id, p) => sim.scene_mut().set_position(id, p),
        Edit::Rotation(id, q) => sim.scene_mut().set_rotation(id, q.to_rotation_matrix()),
        Edit::JointLimits(id, low, high) => sim.scene_mut().joint_mut(id)?.set_limits(low, high),
        Edit::ViscousFriction(id, c) => sim.scene_mut().joint_mut(id)?.set_viscous_friction(c),
        Edit::Motor(id, speed, max_force) => sim.scene_mut().joint_mut(id)?.set_speed(speed, max_force),
        Edit::Setpoint(id, value) => {
            let profile = Profile::constant(value)?;
            let mut joint = sim.scene_mut().joint_mut(id)?;
            if let Some(servo) = joint.controller_mut::<PositionServo>() {
                servo.setpoint = profile;
            } else if let Some(servo) = joint.controller_mut::<VelocityServo>() {
                servo.setpoint = profile;
            } else if let Some(motor) = joint.controller_mut::<DcMotor>() {
                motor.voltage = profile;
            } else if let Some(actuator) = joint.controller_mut::<Actuator>() {
                actuator.set_ctrl(value)?;
            } else {
                return Err(no_controller(sim, id));
            }
            Ok(())
        }
        Edit::Gains(id, gains) => {
            if let Some(g) = gains.iter().find(|g| !g.is_finite()) {
                return Err(Error::NotFinite { what: "controller gain", value: g.to_string() });
            }
            let mut joint = sim.scene_mut().joint_mut(id)?;
            if let Some(servo) = joint.controller_mut::<PositionServo>() {
                [servo.pid.kp, servo.pid.ki, servo.pid.kd] = gains;
            } else if let Some(servo) = joint.controller_mut::<VelocityServo>() {
                servo.gain = gains[0];
            } else {
                return Err(no_controller(sim, id));
            }
            Ok(())
        }
        Edit::Gravity(g) => sim.scene_mut().world_mut().set_gravity(g),
        Edit::TimeStep(dt) => sim.scene_mut().set_time_step(dt),
        Edit::Erp(erp) => sim.scene_mut().world_mut().set_erp(erp),
        Edit::Cfm(cfm) => sim.scene_mut().world_mut().set_cfm(cfm),
    }
}

fn no_controller(sim: &Simulation, id: JointId) -> Error {
    let name = sim.scene().joint(id).map(|j| j.name().to_string()).unwrap_or_default();
    Error::Invalid { what: "a set-point or gain", problem: format!("joint {name:?} has no servo or DC motor") }
}

/// A number typed in the panel: `what` names it in the error (`inf`, `-inf` and
/// exponents are numbers; an empty field or `NaN` is not).
pub fn parse_number(what: &str, text: &str) -> std::result::Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if !v.is_nan() => Ok(v),
        _ => Err(format!("{what}: {:?} is not a number", text.trim())),
    }
}

/// The current value of a joint's first-axis ODE parameter, for the panel.
pub(crate) fn joint_param(sim: &Simulation, id: JointId, param: JointParam) -> Option<f64> {
    sim.scene().joint(id).ok()?.ode().ok()?.param(param, 0).ok()
}

/// Sets a body's total mass, scaling its inertia with it.
fn set_mass(sim: &mut Simulation, id: ObjectId, mass: f64) -> Result<()> {
    let body = sim.scene().body(id)?;
    let (old, inertia) = (body.mass(), body.inertia());
    // Checked by the mass spec (range, finite) before anything changes.
    let scale = mass / old;
    sim.scene_mut().body_mut(id)?.set_mass(MassSpec::Custom { mass, inertia: inertia * scale })
}

/// The volume of a body made of one solid shape, m³: what a density multiplies. An
/// error for a static object, a body of several shapes (a robot link's) or a shape that
/// encloses nothing.
pub(crate) fn solid_volume(sim: &Simulation, id: ObjectId) -> Result<f64> {
    let object = sim.scene().object(id)?;
    object.body()?;
    let volume = object.shape().volume().filter(|_| object.geoms().count() == 1);
    volume.filter(|v| *v > 0.0).ok_or_else(|| Error::Invalid {
        what: "a density",
        problem: format!("needs a body of one solid shape, and {:?} is not one", object.name()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ars_core::{JointEnd, JointType, Mass};

    fn arm() -> (Simulation, ObjectId, JointId) {
        let mut sim = Simulation::new().unwrap();
        let link = sim.scene_mut().add_box([0.1, 0.1, 1.0], [0.0, 1.0, 0.5], Mass::Total(2.0)).unwrap();
        let hinge = sim
            .scene_mut()
            .add_hinge_joint("hinge", link, JointEnd::World, Some(Point3::new(0.0, 1.0, 0.0)), [1.0, 0.0, 0.0])
            .unwrap();
        (sim, link, hinge)
    }

    /// Every field of the body and the world after an edit, to check that a refused
    /// edit changed none of them.
    fn everything(sim: &Simulation, id: ObjectId) -> String {
        let b = sim.scene().body(id).unwrap();
        format!(
            "{} {:?} {} {} {:?} {} {} {} {:?}",
            b.mass(),
            b.inertia(),
            b.position(),
            b.linear_velocity(),
            sim.scene().object(id).unwrap().color(),
            sim.scene().gravity(),
            sim.scene().time_step(),
            sim.scene().world().erp(),
            sim.scene().world().cfm()
        )
    }

    #[test]
    fn a_valid_mass_scales_the_inertia_and_an_invalid_one_changes_nothing() {
        let (mut sim, link, _) = arm();
        let inertia = sim.scene().body(link).unwrap().inertia();
        apply_edit(&mut sim, &Edit::Mass(link, 6.0)).unwrap();
        assert_eq!(sim.scene().body(link).unwrap().mass(), 6.0);
        assert!((sim.scene().body(link).unwrap().inertia() - inertia * 3.0).norm() < 1e-12);
        let before = everything(&sim, link);
        for bad in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
            let e = apply_edit(&mut sim, &Edit::Mass(link, bad)).unwrap_err();
            assert!(e.to_string().contains("mass"), "{e}");
            assert_eq!(everything(&sim, link), before, "after a mass of {bad}");
        }
    }

    #[test]
    fn a_density_sets_the_mass_of_a_solid_body_and_a_bad_one_changes_nothing() {
        let (mut sim, link, _) = arm();
        // A 0.1 × 0.1 × 1 m box: 0.01 m³.
        apply_edit(&mut sim, &Edit::Density(link, 700.0)).unwrap();
        assert!((sim.scene().body(link).unwrap().mass() - 7.0).abs() < 1e-12);
        let before = everything(&sim, link);
        for bad in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
            let e = apply_edit(&mut sim, &Edit::Density(link, bad)).unwrap_err();
            assert!(e.to_string().contains("density"), "{e}");
            assert_eq!(everything(&sim, link), before, "after a density of {bad}");
        }
        let id = sim.scene_mut().add_floor_plane(ars_core::nalgebra::Vector3::y(), 0.0).unwrap();
        let e = apply_edit(&mut sim, &Edit::Density(id, 1000.0)).unwrap_err();
        assert!(e.to_string().contains("body"), "{e}");
    }

    #[test]
    fn a_rotation_turns_the_body_about_its_centre() {
        let (mut sim, link, _) = arm();
        let centre = sim.scene().body(link).unwrap().position();
        let turn = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1);
        apply_edit(&mut sim, &Edit::Rotation(link, turn)).unwrap();
        let body = sim.scene().body(link).unwrap();
        assert!(body.quaternion().angle_to(&turn) < 1e-12);
        assert_eq!(body.position(), centre);
    }

    #[test]
    fn world_settings_are_checked() {
        let (mut sim, link, _) = arm();
        apply_edit(&mut sim, &Edit::Gravity(Vector3::new(0.0, -1.62, 0.0))).unwrap();
        apply_edit(&mut sim, &Edit::TimeStep(0.001)).unwrap();
        apply_edit(&mut sim, &Edit::Erp(0.5)).unwrap();
        apply_edit(&mut sim, &Edit::Cfm(1e-5)).unwrap();
        assert_eq!(
            (sim.scene().gravity().y, sim.scene().time_step(), sim.scene().world().erp(), sim.scene().world().cfm()),
            (-1.62, 0.001, 0.5, 1e-5)
        );
        let before = everything(&sim, link);
        for bad in [
            Edit::Gravity(Vector3::new(f64::NAN, 0.0, 0.0)),
            Edit::TimeStep(-0.001),
            Edit::TimeStep(0.0),
            Edit::Erp(1.5),
            Edit::Cfm(-1.0),
            Edit::Color(link, [2.0, 0.0, 0.0]),
            Edit::Position(link, Point3::new(f64::NAN, 0.0, 0.0)),
        ] {
            assert!(apply_edit(&mut sim, &bad).is_err(), "{bad:?} was accepted");
            assert_eq!(everything(&sim, link), before, "after {bad:?}");
        }
        apply_edit(&mut sim, &Edit::Color(link, [0.0, 1.0, 0.0])).unwrap();
        assert_eq!(sim.scene().object(link).unwrap().color(), Some([0.0, 1.0, 0.0]));
        apply_edit(&mut sim, &Edit::Position(link, Point3::new(1.0, 2.0, 3.0))).unwrap();
        assert_eq!(sim.scene().body(link).unwrap().position(), Point3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn joint_edits_go_through_the_joint() {
        let (mut sim, _, hinge) = arm();
        assert_eq!(sim.scene().joint(hinge).unwrap().joint_type(), JointType::Hinge);
        apply_edit(&mut sim, &Edit::JointLimits(hinge, -0.5, 0.5)).unwrap();
        assert_eq!(joint_param(&sim, hinge, JointParam::LoStop), Some(-0.5));
        assert_eq!(joint_param(&sim, hinge, JointParam::HiStop), Some(0.5));
        // Crossed limits are refused, the old ones kept.
        assert!(apply_edit(&mut sim, &Edit::JointLimits(hinge, 1.0, -1.0)).is_err());
        assert_eq!(sim.scene().joint(hinge).unwrap().limits(), Some((-0.5, 0.5)));
        apply_edit(&mut sim, &Edit::ViscousFriction(hinge, 0.3)).unwrap();
        assert_eq!(sim.scene().joint(hinge).unwrap().viscous_friction(), 0.3);
        assert!(apply_edit(&mut sim, &Edit::ViscousFriction(hinge, -0.3)).is_err());
        assert_eq!(sim.scene().joint(hinge).unwrap().viscous_friction(), 0.3);
        apply_edit(&mut sim, &Edit::Motor(hinge, 1.0, 5.0)).unwrap();
        assert_eq!(joint_param(&sim, hinge, JointParam::Velocity), Some(1.0));
        // No controller yet: set-points and gains are errors.
        assert!(apply_edit(&mut sim, &Edit::Setpoint(hinge, 0.2)).is_err());
        assert!(apply_edit(&mut sim, &Edit::Gains(hinge, [1.0, 0.0, 0.0])).is_err());
        let servo = PositionServo::pd(Profile::constant(0.0).unwrap(), 10.0, 1.0);
        sim.scene_mut().joint_mut(hinge).unwrap().set_controller(servo).unwrap();
        apply_edit(&mut sim, &Edit::Setpoint(hinge, 0.2)).unwrap();
        apply_edit(&mut sim, &Edit::Gains(hinge, [20.0, 0.5, 2.0])).unwrap();
        assert!(apply_edit(&mut sim, &Edit::Gains(hinge, [f64::NAN, 0.5, 2.0])).is_err());
        let servo = sim.scene().joint_controller::<PositionServo>(hinge).unwrap().unwrap();
        assert_eq!(servo.setpoint.value(3.0), 0.2);
        assert_eq!((servo.pid.kp, servo.pid.ki, servo.pid.kd), (20.0, 0.5, 2.0));
    }

    #[test]
    fn typed_numbers_are_parsed_or_named_in_the_error() {
        assert_eq!(parse_number("mass", " 2.5 "), Ok(2.5));
        assert_eq!(parse_number("mass", "-1e-3"), Ok(-0.001));
        assert_eq!(parse_number("high", "inf"), Ok(f64::INFINITY));
        assert_eq!(parse_number("mass", "two"), Err("mass: \"two\" is not a number".into()));
        assert!(parse_number("mass", "").is_err());
        assert!(parse_number("mass", "NaN").is_err());
    }
}
