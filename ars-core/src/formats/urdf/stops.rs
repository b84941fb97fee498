//! A URDF joint's limits as stops ODE can hold, and where each joint starts.
//!
//! ODE measures a hinge's angle within ±π: a stop beyond ±π is never reached, and as
//! the angle passes ±π it reads as the opposite side, so a stop on that side finds the
//! joint a whole turn beyond it and throws it back in one step (the Panda's
//! `panda_joint6`, limited to [−0.0175, 3.7525], was flung at 1,500 rad/s when its link
//! swung down past π).
//!
//! A stop also corrects a joint found beyond it within a step or so (at the world's
//! ERP): a joint starting outside its limits is thrown into them (the Panda's
//! `panda_joint4`, limited to [−3.0718, −0.0698], at 35 rad/s from 0; the calves of
//! most quadrupeds, limited to about [−2.7, −0.9], at 450 rad/s). Such a joint starts at
//! its limit nearest 0 instead, unless its start is given.

use std::f64::consts::{PI, TAU};

use super::model;

/// How far inside ±π a hinge's stops are kept: a joint that reaches a stop goes a
/// little past it before the stop holds it (its rate times a step), and must not pass
/// ±π while it does.
pub(super) const HINGE_STOP_MARGIN: f64 = 0.05;

/// A `revolute` or `prismatic` joint's limits, when it has some (not both 0, not
/// crossing, finite).
fn limits(joint: &model::Joint) -> Option<(f64, f64)> {
    let (lower, upper) = (joint.limit.lower, joint.limit.upper);
    let limited = matches!(joint.joint_type, model::JointType::Revolute | model::JointType::Prismatic);
    let some = !(lower == 0.0 && upper == 0.0) && lower <= upper && lower.is_finite() && upper.is_finite();
    (limited && some).then_some((lower, upper))
}

/// The stops a URDF joint that starts at `start` gets (`None`: none): a `revolute` or
/// `prismatic` joint's limits (none when both are 0, or when they cross), a revolute
/// one's made ODE's (see [`hinge_stops`]).
pub(super) fn joint_stops(joint: &model::Joint, start: f64) -> Option<(f64, f64)> {
    let (lower, upper) = limits(joint)?;
    match joint.joint_type {
        model::JointType::Revolute => hinge_stops(lower, upper, start),
        _ => Some((lower, upper)),
    }
}

/// Where each joint starts (by index): its position in `given`; else, for a mimic
/// follower, its leader's start times the multiplier plus the offset; else 0, or the
/// limit nearest 0 when its limits exclude 0 (with a line for
/// [`UrdfRobot::adjusted`](super::UrdfRobot::adjusted)).
pub(super) fn start_positions(robot: &model::Robot, given: &[Option<f64>]) -> (Vec<f64>, Vec<String>) {
    let mut notes = Vec::new();
    let mut start: Vec<f64> = robot
        .joints
        .iter()
        .zip(given)
        .map(|(joint, given)| match (given, limits(joint)) {
            (Some(q), _) => *q,
            (None, Some((lower, upper))) if (lower > 0.0 || upper < 0.0) && joint.mimic.is_none() => {
                let nearest = if lower > 0.0 { lower } else { upper };
                notes.push(format!(
                    "joint {:?}: starts at {nearest}, its limit nearest 0, as its limits [{lower}, {upper}] exclude 0",
                    joint.name
                ));
                nearest
            }
            (None, _) => 0.0,
        })
        .collect();
    for (j, joint) in robot.joints.iter().enumerate() {
        let Some(mimic) = joint.mimic.as_ref().filter(|_| given[j].is_none()) else { continue };
        let Some(leader) = robot.joints.iter().position(|l| l.name == mimic.joint) else { continue };
        start[j] = mimic.multiplier.unwrap_or(1.0) * start[leader] + mimic.offset.unwrap_or(0.0);
    }
    (start, notes)
}

/// A hinge's stops for limits `[lower, upper]` (rad) when it starts at `start`: the
/// limits themselves when they lie within ±(π − [`HINGE_STOP_MARGIN`]); none when they
/// span a turn (every angle is allowed, less what the margins would leave out);
/// otherwise the limits turned by the whole turns that bring `start` within ±π, cut to
/// ±(π − margin): the part of the range on the start's side of ±π, where ODE can stop
/// the joint (the Panda's [−0.0175, 3.7525] becomes [−0.0175, π − 0.05]).
pub(super) fn hinge_stops(lower: f64, upper: f64, start: f64) -> Option<(f64, f64)> {
    let inside = PI - HINGE_STOP_MARGIN;
    if lower >= -inside && upper <= inside {
        return Some((lower, upper));
    }
    if upper - lower >= TAU - 2.0 * HINGE_STOP_MARGIN {
        return None;
    }
    let turns = (start / TAU).round();
    let low = (lower - turns * TAU).clamp(-inside, inside);
    let high = (upper - turns * TAU).clamp(-inside, inside).max(low);
    Some((low, high))
}

/// A line for [`UrdfRobot::adjusted`](super::UrdfRobot::adjusted) for each revolute
/// joint whose stops are not its limits (`start`: the joints' start positions).
pub(super) fn stop_notes(robot: &model::Robot, start: &[f64]) -> Vec<String> {
    robot
        .joints
        .iter()
        .zip(start)
        .filter(|(j, _)| matches!(j.joint_type, model::JointType::Revolute))
        .filter_map(|(joint, &start)| {
            let (lower, upper) = limits(joint)?;
            let what = match joint_stops(joint, start) {
                Some(s) if s == (lower, upper) => return None,
                None => "spans a turn: the joint has no stops".to_string(),
                Some((low, high)) => format!("has its stops at [{low}, {high}]"),
            };
            Some(format!(
                "joint {:?}: limits [{lower}, {upper}] rad reach beyond ±(π − {HINGE_STOP_MARGIN}), within which \
                 ODE measures a hinge's angle; it {what}",
                joint.name
            ))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::urdf::UrdfOptions;
    use crate::simulation::Simulation;

    /// An arm standing up from a fixed base, on a hinge limited as the Panda's joint 6.
    const ARM_PAST_HALF_A_TURN: &str = r#"<robot name="flip">
      <link name="base"><inertial><mass value="10"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="arm"><inertial><origin xyz="0 0 0.5"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
        <limit lower="-0.0175" upper="3.7525" effort="10" velocity="2"/></joint>
    </robot>"#;

    /// A calf hanging from a fixed thigh, on a knee limited as a quadruped's (0
    /// outside), and a toe that mimics the knee, half as far and 0.2 rad on.
    const KNEE_LIMITED_BELOW_ZERO: &str = r#"<robot name="calf">
      <link name="thigh"><inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="calf"><inertial><origin xyz="0 0 -0.1"/><mass value="0.2"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="toe"><inertial><mass value="0.05"/><inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="knee" type="revolute"><parent link="thigh"/><child link="calf"/><axis xyz="0 1 0"/>
        <limit lower="-2.7" upper="-0.9" effort="10" velocity="10"/></joint>
      <joint name="toe" type="revolute"><origin xyz="0 0 -0.2"/><parent link="calf"/><child link="toe"/><axis xyz="0 1 0"/>
        <limit lower="-2" upper="2" effort="10" velocity="10"/><mimic joint="knee" multiplier="0.5" offset="0.2"/></joint>
    </robot>"#;

    #[test]
    fn a_joint_whose_limits_exclude_zero_starts_at_its_nearest_limit_not_thrown_into_it() {
        let mut sim = Simulation::new().unwrap();
        let options = UrdfOptions::new().fixed_base(true);
        let robot = sim.load_urdf_text(KNEE_LIMITED_BELOW_ZERO, "calf.urdf", &options).unwrap();
        assert_eq!(
            robot.adjusted,
            ["joint \"knee\": starts at -0.9, its limit nearest 0, as its limits [-2.7, -0.9] exclude 0"]
        );
        let state = |sim: &Simulation, name: &str| sim.scene().joint(name).unwrap().state().unwrap();
        assert!((state(&sim, "knee").position + 0.9).abs() < 1e-9);
        assert!((state(&sim, "toe").position - (0.5 * -0.9 + 0.2)).abs() < 1e-9, "the follower starts with it");
        // From 0, its stop threw it 0.9 rad in a few steps: at 0.2 · 0.9 / 0.0004 = 450 rad/s.
        let mut fastest = 0.0_f64;
        for _ in 0..500 {
            sim.step().unwrap();
            fastest = fastest.max(state(&sim, "knee").rate.abs()).max(state(&sim, "toe").rate.abs());
        }
        assert!(fastest < 10.0, "{fastest} rad/s");
        // A start given is kept, even outside the limits.
        let mut sim = Simulation::new().unwrap();
        let given = options.initial_position("knee", 0.0).initial_position("toe", 0.0);
        let robot = sim.load_urdf_text(KNEE_LIMITED_BELOW_ZERO, "calf.urdf", &given).unwrap();
        assert!(robot.adjusted.is_empty() && state(&sim, "knee").position.abs() < 1e-12);
    }

    #[test]
    fn hinge_limits_beyond_half_a_turn_do_not_throw_the_joint_back_as_its_angle_passes_pi() {
        let mut sim = Simulation::new().unwrap();
        let options = UrdfOptions::new().fixed_base(true).initial_position("swing", 0.3);
        let robot = sim.load_urdf_text(ARM_PAST_HALF_A_TURN, "flip.urdf", &options).unwrap();
        assert_eq!(robot.adjusted.len(), 1, "{:?}", robot.adjusted);
        assert!(robot.adjusted[0].starts_with("joint \"swing\": limits [-0.0175, 3.7525] rad"));
        // It falls forwards, down past π/2 to its stop short of π. Falling 1 m, its
        // centre (0.5 m out) reaches sqrt(2 g h / I) = 8.7 rad/s; when ODE read the angle
        // past π as −π, a whole turn below the low stop, it was thrown back at 1,500 rad/s.
        let mut fastest = 0.0_f64;
        let mut highest = 0.0_f64;
        for _ in 0..5000 {
            sim.step().unwrap();
            let state = sim.scene().joint("swing").unwrap().state().unwrap();
            fastest = fastest.max(state.rate.abs());
            highest = highest.max(state.position);
        }
        assert!(fastest < 10.0, "{fastest} rad/s");
        assert!(highest > 3.0 && highest < PI, "it swung down to its stop: {highest}");
    }

    #[test]
    fn hinge_limits_within_half_a_turn_are_kept_and_beyond_it_cut_to_what_ode_can_stop() {
        let inside = PI - HINGE_STOP_MARGIN;
        assert_eq!(hinge_stops(-2.8973, 2.8973, 0.0), Some((-2.8973, 2.8973)));
        // The Panda's joint 6: the part of its range on the side of 0.
        assert_eq!(hinge_stops(-0.0175, 3.7525, 0.0), Some((-0.0175, inside)));
        assert_eq!(hinge_stops(-3.7525, 0.0175, 0.0), Some((-inside, 0.0175)));
        // A range beyond π altogether turns by a whole turn.
        let (low, high) = hinge_stops(3.3, 3.6, 3.3).unwrap();
        assert!((low - (3.3 - TAU)).abs() < 1e-12 && (high - (3.6 - TAU)).abs() < 1e-12, "{low} {high}");
        // A turn or more: no stops; ±π exactly is cut by the margin.
        assert_eq!(hinge_stops(-TAU, TAU, 0.0), None);
        assert_eq!(hinge_stops(-PI, PI, 0.0), None);
        assert_eq!(hinge_stops(-PI, 1.0, 0.0), Some((-inside, 1.0)));
        // Limits on both sides of π: the part on the side where the joint starts.
        assert_eq!(hinge_stops(0.82, 5.46, 0.82), Some((0.82, inside)));
        let (low, high) = hinge_stops(0.82, 5.46, 5.0).unwrap();
        assert!(low == -inside && (high - (5.46 - TAU)).abs() < 1e-12, "{low} {high}");
        // A sliver across π: stops that do not cross.
        let (low, high) = hinge_stops(PI - 0.01, PI + 0.01, PI - 0.01).unwrap();
        assert!(low <= high && high.abs() <= inside, "{low} {high}");
    }
}
