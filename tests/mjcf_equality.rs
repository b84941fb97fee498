//! MuJoCo's `<equality>` constraints as ODE joints: a `connect` keeps a point of a body
//! where it was, a `weld` keeps two bodies' relative pose, a `joint` equality couples
//! two hinges linearly (with their `ref`s, as MuJoCo's `qpos0`); what ARS cannot carry is
//! skipped and said.

use ars::nalgebra::{Isometry3, Point3};
use ars::{MjcfOptions, Simulation};

fn load(text: &str, options: &MjcfOptions) -> ars::Result<(Simulation, ars::MjcfModel)> {
    let mut sim = Simulation::new()?;
    let model = sim.load_mjcf_text(text, "equality.xml", options)?;
    Ok((sim, model))
}

fn pose(sim: &Simulation, model: &ars::MjcfModel, body: &str) -> Isometry3<f64> {
    sim.scene().pose(model.body(body).unwrap()).unwrap()
}

/// A free ball pinned to the world at a point beside it, and a second ball welded to it.
const PENDULUM: &str = r#"
<mujoco>
  <worldbody>
    <body name="bob" pos="0.3 0 1"><freejoint/><geom size="0.05" mass="1"/></body>
    <body name="rider" pos="0.3 0.2 1"><freejoint/><geom type="box" size="0.02 0.02 0.02" mass="0.5"/></body>
  </worldbody>
  <equality>
    <connect name="pin" body1="bob" anchor="-0.3 0 0"/>
    <weld body1="bob" body2="rider"/>
  </equality>
</mujoco>"#;

#[test]
fn a_connect_keeps_its_anchor_and_a_weld_keeps_the_relative_pose() {
    let (mut sim, model) = load(PENDULUM, &MjcfOptions::new()).unwrap();
    assert_eq!(model.equalities.len(), 2, "a ball joint and a fixed joint");
    assert!(model.skipped.is_empty(), "{:#?}", model.skipped);
    let (bob0, rider0) = (pose(&sim, &model, "bob"), pose(&sim, &model, "rider"));
    // The anchor: 0.3 m beside the bob in MuJoCo's x, at the world's origin height 1 m
    // (the simulation's y up).
    let anchor = bob0 * Point3::new(-0.3, 0.0, 0.0);
    let relative = bob0.inverse() * rider0;
    sim.run_for(0.5).unwrap();
    let (bob, rider) = (pose(&sim, &model, "bob"), pose(&sim, &model, "rider"));
    assert!((bob.translation.vector - bob0.translation.vector).norm() > 0.05, "the bob swung: {bob:?}");
    // As soft as MuJoCo's (solref 0.02 s by default): the joints take the ERP of its
    // reference acceleration. MuJoCo 4.0's pin drifts 0.54–0.78 mm and its weld
    // 0.73–0.79 mm on this pendulum over the same 0.5 s (at 2 and 0.4 ms).
    let drift = (bob * (bob0.inverse() * anchor) - anchor).norm();
    assert!(drift < 1e-3, "the pinned point stays: {drift} m");
    let kept = bob.inverse() * rider;
    let moved =
        (kept.translation.vector - relative.translation.vector).norm() + kept.rotation.angle_to(&relative.rotation);
    assert!(moved < 1e-3, "the welded rider keeps its pose on the bob: {moved}");
    // The ERP of MuJoCo's default solref at the simulation's 0.4 ms: h·k / (h·k + b).
    let (k, b) = (1.0 / (0.95f64 * 0.95 * 0.02 * 0.02), 2.0 / (0.95 * 0.02));
    let erp = 0.0004 * k / (0.0004 * k + b);
    for joint in &model.equalities {
        let got = sim.scene().joint(*joint).unwrap().ode().unwrap().param(ars::JointParam::Erp, 0).unwrap();
        assert!((got - erp).abs() < 1e-12, "{got} against {erp}");
    }
}

/// Two arms; the second's hinge follows the first's: `j2 − ref2 = 0.05 + 0.5·(j1 − ref1)`,
/// the `ref`s in degrees (the compiler's default angle), `polycoef` in radians.
const COUPLED: &str = r#"
<mujoco>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="a"><joint name="j1" axis="0 0 1" ref="20"/><geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b" pos="0 1 0"><joint name="j2" axis="0 0 1" ref="10"/><geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/></body>
  </worldbody>
  <equality><joint joint1="j2" joint2="j1" polycoef="0.05 0.5 0 0 0"/></equality>
  <actuator><motor joint="j1" gear="1"/></actuator>
</mujoco>"#;

#[test]
fn a_joint_equality_couples_two_hinges_as_mujoco_does() {
    let (mut sim, model) = load(COUPLED, &MjcfOptions::new()).unwrap();
    assert!(model.equalities.is_empty(), "a coupling is no joint of its own");
    let (ref1, ref2) = (20f64.to_radians(), 10f64.to_radians());
    sim.scene_mut().set_controls(&[0.5]).unwrap();
    sim.run_for(1.0).unwrap();
    let position = |sim: &Simulation, j: &str| sim.scene().joint(j).unwrap().state().unwrap().position;
    let (j1, j2) = (position(&sim, "j1"), position(&sim, "j2"));
    assert!(j1 - ref1 > 0.2 && j1 < 3.0, "the driven hinge turned (not round): {j1}");
    // The follower's motor corrects the error at the world's ERP each step: it trails
    // the leader's motion by a small part of a step's turn.
    let wanted = ref2 + 0.05 + 0.5 * (j1 - ref1);
    assert!((j2 - wanted).abs() < 1e-3, "j2 {j2}, wanted {wanted}");
}

#[test]
fn what_an_equality_cannot_carry_is_skipped_and_said() {
    let text = COUPLED.replace(
        r#"<equality><joint joint1="j2" joint2="j1" polycoef="0.05 0.5 0 0 0"/></equality>"#,
        r#"<equality>
    <joint joint1="j2" joint2="j1" polycoef="0 1 0.3 0 0"/>
    <joint joint1="j2"/>
    <tendon tendon1="t"/>
    <weld body1="a" body2="b" active="false"/>
    <weld body1="a" body2="b" solref="0.02 1" torquescale="2"/>
  </equality>"#,
    );
    // Strictly, the tendon equality is refused, naming the way to load the rest.
    let strict = load(&text, &MjcfOptions::new()).err().unwrap().to_string();
    assert!(strict.contains("<tendon>") && strict.contains("skip_unsupported"), "{strict}");
    let (_, model) = load(&text, &MjcfOptions::new().skip_unsupported(true)).unwrap();
    let said = |what: &str| model.skipped.iter().any(|s| s.contains(what));
    assert!(said("beyond degree 1"), "{:#?}", model.skipped);
    assert!(said("no joint2"), "{:#?}", model.skipped);
    assert!(said("<tendon> in <equality>"), "{:#?}", model.skipped);
    assert!(said("active=\"false\""), "{:#?}", model.skipped);
    assert!(said("torquescale not used") && !said("solref"), "{:#?}", model.skipped);
    assert_eq!(model.equalities.len(), 1, "the active weld only");
}

#[test]
fn an_equality_naming_what_the_model_lacks_is_an_error_naming_it() {
    for (bad, named) in [
        (r#"<connect body1="ghost" anchor="0 0 0"/>"#, "\"ghost\""),
        (r#"<weld site1="nowhere" site2="nowhere"/>"#, "\"nowhere\""),
        (r#"<joint joint1="j2" joint2="j9"/>"#, "\"j9\""),
        (r#"<connect body1="a"/>"#, "needs an anchor"),
    ] {
        let text = COUPLED.replace(r#"<joint joint1="j2" joint2="j1" polycoef="0.05 0.5 0 0 0"/>"#, bad);
        let mut sim = Simulation::new().unwrap();
        let error = sim.load_mjcf_text(&text, "bad.xml", &MjcfOptions::new()).err().unwrap().to_string();
        assert!(error.contains(named), "{bad}: {error}");
        assert_eq!(sim.scene().objects().count(), 0, "{bad}: nothing left");
    }
}

/// At a stop, ODE puts a motor's largest force on the bodies as it is: a coupled finger
/// of 50 g resting on its stop, its coupling's force unbounded, was spun to 1e9 rad/s
/// in 6 ms (robosuite's Robotiq gripper, whose scissor joints start on their stops).
#[test]
fn a_coupled_finger_resting_on_its_stop_stays_bounded() {
    let text = r#"
<mujoco>
  <worldbody>
    <body name="palm" pos="0 0 1">
      <body name="f1" pos="0 0.05 0"><joint name="s1" axis="0 1 0" range="-0.29 0.29" ref="0.29" damping="0.1"/>
        <geom type="box" size="0.01 0.01 0.03" pos="0 0 -0.03" mass="0.05"/></body>
      <body name="f2" pos="0 -0.05 0"><joint name="s2" axis="0 1 0" range="-0.29 0.29" ref="-0.29" damping="0.1"/>
        <geom type="box" size="0.01 0.01 0.03" pos="0 0 -0.03" mass="0.05"/></body>
    </body>
  </worldbody>
  <compiler angle="radian" autolimits="true"/>
  <equality><joint joint1="s2" joint2="s1" polycoef="0 -1 0 0 0"/></equality>
  <actuator><position joint="s1" kp="20" ctrlrange="-0.29 0.29"/></actuator>
</mujoco>"#;
    let (mut sim, _) = load(text, &MjcfOptions::new()).unwrap();
    let position = |sim: &Simulation, j: &str| sim.scene().joint(j).unwrap().state().unwrap().position;
    sim.run_for(0.2).unwrap();
    // Driven to 0, s1 leaves its stop, and s2 follows it off its own.
    sim.scene_mut().set_controls(&[0.0]).unwrap();
    sim.run_for(1.0).unwrap();
    let (s1, s2) = (position(&sim, "s1"), position(&sim, "s2"));
    assert!(s1.abs() < 0.05, "s1 went to its control: {s1}");
    assert!((s2 + s1).abs() < 1e-3, "s2 follows off its stop: {s2} for {s1}");
}

/// An arm whose hand is welded to a `mocap` body (Meta-World's Sawyer is held so).
const MOCAP_ARM: &str = r#"
<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="arm" pos="0 0 1"><joint name="shoulder" axis="0 1 0" damping="0.5"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
      <body name="hand" pos="0.3 0 0"><joint name="wrist" axis="0 1 0" damping="0.5"/><geom size="0.04"/></body>
    </body>
    <body name="target" mocap="true" pos="0.3 0 1"><geom size="0.01" contype="0" conaffinity="0"/></body>
  </worldbody>
  <equality><weld body1="target" body2="hand"/></equality>
</mujoco>"#;

/// A mocap body is a kinematic body: gravity leaves it (and the hand welded to it)
/// where the file puts it; `set_mocap_pose` moves it, in the file's frame, and the
/// hand follows, as far as its arm reaches.
#[test]
fn a_mocap_body_stays_where_it_is_put_and_the_hand_welded_to_it_follows() {
    let (mut sim, model) = load(MOCAP_ARM, &MjcfOptions::new()).unwrap();
    assert_eq!(model.equalities.len(), 1, "{:#?}", model.skipped);
    assert_eq!(model.mocap.len(), 1);
    assert_eq!(sim.mocap_bodies()[0].body, "target");
    let target = model.body("target").unwrap();
    assert!(sim.scene().body(target).unwrap().is_kinematic());
    let hand0 = pose(&sim, &model, "hand");
    sim.run_for(1.0).unwrap();
    // Held against gravity by the weld alone (the joints are free but for damping).
    let sag = (pose(&sim, &model, "hand").translation.vector - hand0.translation.vector).norm();
    assert!(sag < 1e-3, "the hand sagged {sag} m");
    assert_eq!(sim.mocap_pose("target").unwrap(), ([0.3, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]));
    // Swung 20° down about the shoulder (on the circle the hand can reach) and turned
    // 30° about MuJoCo's y, which the wrist allows.
    let down = 20f64.to_radians();
    let goal = [0.3 * down.cos(), 0.0, 1.0 - 0.3 * down.sin()];
    let half = 15f64.to_radians();
    let turn = [half.cos(), 0.0, half.sin(), 0.0];
    let kept = hand0.inverse() * sim.scene().pose(target).unwrap();
    sim.set_mocap_pose("target", goal, turn).unwrap();
    let (at, quat) = sim.mocap_pose("target").unwrap();
    for (a, b) in at.iter().zip(goal).chain(quat.iter().zip(turn)) {
        assert!((a - b).abs() < 1e-12, "{at:?} {quat:?}");
    }
    sim.run_for(2.0).unwrap();
    let hand = pose(&sim, &model, "hand");
    let now = hand.inverse() * sim.scene().pose(target).unwrap();
    let off = (kept.translation.vector - now.translation.vector).norm() + kept.rotation.angle_to(&now.rotation);
    assert!(off < 1e-3, "the hand keeps its pose to the mocap body within {off}");
    // MuJoCo's (x, y, z) is the simulation's (x, z, -y).
    let reached = hand.translation.vector - ars::nalgebra::Vector3::new(goal[0], goal[2], -goal[1]);
    assert!(reached.norm() < 1e-3, "the hand went with it: {hand:?}");
}

#[test]
fn set_mocap_pose_refuses_an_unknown_body_and_bad_numbers_and_moves_nothing() {
    let (mut sim, model) = load(MOCAP_ARM, &MjcfOptions::new()).unwrap();
    let before = pose(&sim, &model, "target");
    let err = sim.set_mocap_pose("targte", [0.0; 3], [1.0, 0.0, 0.0, 0.0]).unwrap_err();
    assert!(err.to_string().contains("no mocap body named \"targte\""), "{err}");
    assert!(err.to_string().contains("target"), "a close match is suggested: {err}");
    assert!(sim.set_mocap_pose("hand", [0.0; 3], [1.0, 0.0, 0.0, 0.0]).is_err(), "not a mocap body");
    for (p, q) in [
        ([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
        ([0.0; 3], [0.0; 4]),
        ([0.0; 3], [f64::INFINITY, 0.0, 0.0, 0.0]),
        ([1e308, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
    ] {
        assert!(sim.set_mocap_pose("target", p, q).is_err(), "{p:?} {q:?}");
        assert_eq!(pose(&sim, &model, "target"), before);
    }
    sim.run_for(0.1).unwrap();
    // A mocap body removed since: an error naming a stale object, not a panic.
    sim.remove_object(model.body("target").unwrap()).unwrap();
    let err = sim.set_mocap_pose("target", [0.0; 3], [1.0, 0.0, 0.0, 0.0]).unwrap_err();
    assert!(matches!(err, ars::Error::StaleHandle { .. }), "{err}");
    assert!(sim.mocap_pose("target").is_err());
    sim.run_for(0.1).unwrap();
}

/// A mocap body must be a jointless child of the world, as MuJoCo requires.
#[test]
fn a_mocap_body_with_joints_or_inside_another_body_is_refused() {
    let jointed = MOCAP_ARM.replace(r#"mocap="true" pos="0.3 0 1">"#, r#"mocap="true" pos="0.3 0 1"><freejoint/>"#);
    let err = load(&jointed, &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("a mocap body cannot have joints") && err.contains("line"), "{err}");
    let nested = MOCAP_ARM
        .replace(r#"<geom size="0.04"/></body>"#, r#"<geom size="0.04"/><body name="m" mocap="true"/></body>"#);
    let err = load(&nested, &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("must be a child of the world body"), "{err}");
}

/// Two copies of a model with a mocap body, prefixed, each moved by its own name.
#[test]
fn prefixed_copies_move_their_own_mocap_bodies() {
    let mut sim = Simulation::new().unwrap();
    let a = sim.load_mjcf_text(MOCAP_ARM, "a.xml", &MjcfOptions::new().prefix("a/")).unwrap();
    let b = sim.load_mjcf_text(MOCAP_ARM, "b.xml", &MjcfOptions::new().prefix("b/")).unwrap();
    sim.set_mocap_pose("b/target", [0.3, 0.0, 0.95], [1.0, 0.0, 0.0, 0.0]).unwrap();
    sim.run_for(1.0).unwrap();
    let y = |m: &ars::MjcfModel| {
        pose(&sim, m, &format!("{}hand", if m.mocap[0].body.starts_with('a') { "a/" } else { "b/" }))
            .translation
            .vector
            .y
    };
    // Each hand where its own mocap body is, give or take the sag of a soft weld.
    assert!((y(&a) - 1.0).abs() < 5e-3 && (y(&b) - 0.95).abs() < 5e-3, "{} {}", y(&a), y(&b));
    assert!(y(&a) - y(&b) > 0.04, "b went down, a did not");
}

/// Hostile numbers in an equality: an anchor at 1e308 m, a coupling of 1e308 per radian.
/// Each is refused with an error, or loads and steps without harm; nothing aborts.
#[test]
fn an_equality_of_huge_numbers_is_refused_or_harmless() {
    for bad in
        [r#"<connect body1="a" anchor="1e308 0 0"/>"#, r#"<joint joint1="j2" joint2="j1" polycoef="0 1e308 0 0 0"/>"#]
    {
        let text = COUPLED.replace(r#"<joint joint1="j2" joint2="j1" polycoef="0.05 0.5 0 0 0"/>"#, bad);
        let mut sim = Simulation::new().unwrap();
        if sim.load_mjcf_text(&text, "huge.xml", &MjcfOptions::new()).is_ok() {
            let _ = sim.run_for(0.01);
        }
    }
}

/// A saved scene keeps a mocap body kinematic (its state holds the flag) and the weld
/// to it: the reloaded arm hangs from it as the original does, step for step.
#[test]
fn a_saved_scene_keeps_the_mocap_body_kinematic_and_the_hand_welded() {
    let (mut sim, model) = load(MOCAP_ARM, &MjcfOptions::new()).unwrap();
    sim.set_mocap_pose("target", [0.3, 0.0, 0.98], [1.0, 0.0, 0.0, 0.0]).unwrap();
    let mut again = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    let target = again.scene().object("target").unwrap().id();
    assert!(again.scene().body(target).unwrap().is_kinematic());
    sim.run_for(0.5).unwrap();
    again.run_for(0.5).unwrap();
    let hand = again.scene().object("hand").unwrap().id();
    assert_eq!(again.scene().pose(hand).unwrap(), pose(&sim, &model, "hand"));
}

/// Hostile softness on a weld: time constants of 1e-300 and 1e300 s, negative ones, an
/// impedance outside (0, 1). Each loads and steps with finite bodies, or is refused.
#[test]
fn a_weld_of_hostile_softness_is_refused_or_harmless() {
    for (solref, solimp) in [
        ("1e-300 1", "0.9 0.95"),
        ("1e300 1", "0.9 0.95"),
        ("-1e308 -1e308", "2 -5"),
        ("0.02 -1", "0 0"),
        ("0.02 1", "1e308 1e308"),
    ] {
        let text = MOCAP_ARM.replace(
            r#"<weld body1="target" body2="hand"/>"#,
            &format!(r#"<weld body1="target" body2="hand" solref="{solref}" solimp="{solimp}"/>"#),
        );
        let Ok((mut sim, model)) = load(&text, &MjcfOptions::new()) else { continue };
        sim.set_mocap_pose("target", [0.2, 0.0, 0.9], [1.0, 0.0, 0.0, 0.0]).unwrap();
        sim.run_for(0.2).unwrap();
        let hand = pose(&sim, &model, "hand").translation.vector;
        assert!(hand.iter().all(|x| x.is_finite()), "{solref} / {solimp}: {hand:?}");
    }
}
