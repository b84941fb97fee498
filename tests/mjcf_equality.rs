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
    // ODE holds a joint to its ERP's correction of the step's drift: micrometres here.
    let drift = (bob * (bob0.inverse() * anchor) - anchor).norm();
    assert!(drift < 1e-4, "the pinned point stays: {drift} m");
    let kept = bob.inverse() * rider;
    let moved =
        (kept.translation.vector - relative.translation.vector).norm() + kept.rotation.angle_to(&relative.rotation);
    assert!(moved < 1e-4, "the welded rider keeps its pose on the bob: {moved}");
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
    <weld body1="a" body2="b" solref="0.02 1"/>
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
    assert!(said("solref not used"), "{:#?}", model.skipped);
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

/// A weld to a `mocap` body (Meta-World's hand held by its mocap) is not made: ARS does
/// not move mocap bodies, and made hard, the weld locked the arm's hand through a loop of
/// its joints where MuJoCo's soft weld only pulls it (Meta-World's Sawyer reached
/// 670 m/s). It is said in `skipped`, naming the body.
#[test]
fn a_weld_to_a_mocap_body_is_skipped_and_said() {
    let text = r#"
<mujoco>
  <worldbody>
    <body name="arm" pos="0 0 1"><joint name="shoulder" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
      <body name="hand" pos="0.3 0 0"><joint name="wrist" axis="0 1 0"/><geom size="0.04"/></body>
    </body>
    <body name="target" mocap="true" pos="0.5 0 1"><geom size="0.01" contype="0" conaffinity="0"/></body>
  </worldbody>
  <equality><weld body1="target" body2="hand"/></equality>
</mujoco>"#;
    let (mut sim, model) = load(text, &MjcfOptions::new()).unwrap();
    assert!(model.equalities.is_empty());
    assert!(model.skipped.iter().any(|s| s.contains("\"target\" is a mocap body")), "{:#?}", model.skipped);
    sim.run_for(0.5).unwrap();
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
