//! What MuJoCo never collides or constrains stays out of ODE's step: a joint's damping
//! and armature are unbounded rows of the step's LCP.

use crate::world::joint::JointParam;
use crate::{MjcfOptions, Simulation};

#[test]
fn a_joint_s_damping_and_armature_motors_have_no_force_limit() {
    // ODE's LCP factors the rows without bounds at once and takes each bounded row
    // alone: an unbounded damping row costs a fraction of a bounded one.
    const DAMPED: &str = r#"<mujoco><worldbody>
        <body name="arm" pos="0 0 1"><joint name="hinge" axis="0 1 0" damping="2" armature="0.01"/>
          <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/></body>
      </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(DAMPED, "damped.xml", &MjcfOptions::new()).unwrap();
    let [(_, motor)] = model.joint_motors[..] else { panic!("one damping motor: {:?}", model.joint_motors) };
    let world = sim.scene().world();
    assert_eq!(world.joint(motor).unwrap().param(JointParam::MaxForce, 0).unwrap(), f64::INFINITY);
    // The armature's motor too.
    let hinge = model.joint("hinge").unwrap();
    let armature = sim.scene().joint_data(hinge).unwrap().armature.expect("an armature");
    assert_eq!(world.joint(armature.motor).unwrap().param(JointParam::MaxForce, 0).unwrap(), f64::INFINITY);
    // Released horizontal, it swings down under its damping, as before.
    sim.run_for(0.5).unwrap();
    let rate = sim.scene().joint_state(model.joint("hinge").unwrap()).unwrap().rate;
    assert!(rate.is_finite() && rate.abs() > 0.1, "{rate}");
}
