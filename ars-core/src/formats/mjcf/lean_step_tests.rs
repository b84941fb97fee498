//! What MuJoCo never collides or constrains stays out of ODE's step: bodies welded to
//! the world do not touch the world or each other, a pair of geoms touches at no more
//! points than MuJoCo's, and a joint's damping and armature are unbounded rows of the
//! step's LCP.

use crate::world::joint::JointParam;
use crate::{MjcfOptions, Simulation};

/// A table sunk 1 cm into the floor, a cabinet sunk 10 cm into the table (both
/// jointless children of the world with mass: kinematic ODE bodies) and a
/// block falling onto the table.
const FURNITURE: &str = r#"<mujoco><option timestep="0.002"/><worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="table" pos="0 0 0.19"><geom type="box" size="0.5 0.5 0.2" mass="50"/></body>
    <body name="cabinet" pos="0.6 0 0.3"><geom type="box" size="0.2 0.2 0.3" mass="20"/></body>
    <body name="block" pos="0 0 0.45"><freejoint/><geom type="box" size="0.05 0.05 0.05" mass="1"/></body>
  </worldbody></mujoco>"#;

#[test]
fn bodies_welded_to_the_world_touch_neither_the_world_nor_each_other() {
    let mut sim = Simulation::builder().time_step(0.002).build().unwrap();
    let model = sim.load_mjcf_text(FURNITURE, "furniture.xml", &MjcfOptions::new()).unwrap();
    let (table, cabinet, block) =
        (model.body("table").unwrap(), model.body("cabinet").unwrap(), model.body("block").unwrap());
    let floor = model.world_geoms[0];
    let excluded = sim.scene().excluded_contacts();
    for pair in [(table, cabinet), (table, floor), (cabinet, floor)] {
        assert!(excluded.contains(&pair) || excluded.contains(&(pair.1, pair.0)), "{pair:?} in {excluded:?}");
    }
    assert!(!excluded.iter().any(|(a, b)| *a == block || *b == block), "the block touches everything");
    let block_body = sim.scene().object(block).unwrap().body_handle();
    sim.run_for(0.4).unwrap();
    let contacts = sim.scene().world().contacts();
    assert!(!contacts.is_empty(), "the block rests on the table");
    for c in contacts {
        assert!(c.pair.body1 == block_body || c.pair.body2 == block_body, "only the block touches: {c:?}");
    }
    let z = sim.scene().position(block).unwrap();
    assert!((z.y - 0.44).abs() < 0.01, "on the table top (0.39 m) with its half height: {z}");
}

#[test]
fn a_joint_s_damping_and_armature_are_one_motor_without_force_limit() {
    // ODE's LCP factors the rows without bounds at once and takes each bounded row
    // alone: an unbounded damping row costs a fraction of a bounded one, and one row
    // for both a fraction of two.
    const DAMPED: &str = r#"<mujoco><worldbody>
        <body name="arm" pos="0 0 1"><joint name="hinge" axis="0 1 0" damping="2" armature="0.01"/>
          <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/></body>
      </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(DAMPED, "damped.xml", &MjcfOptions::new()).unwrap();
    assert!(model.joint_motors.is_empty(), "a hinge's damping is its own: {:?}", model.joint_motors);
    let hinge = model.joint("hinge").unwrap();
    let held = sim.scene().joint_data(hinge).unwrap().armature.expect("an armature");
    assert_eq!((held.inertia, held.damping), (0.01, 2.0));
    let world = sim.scene().world();
    assert_eq!(world.joint_count(), 2, "the hinge and one motor");
    assert_eq!(world.joint(held.motor).unwrap().param(JointParam::MaxForce, 0).unwrap(), f64::INFINITY);
    // Released horizontal, it swings down under its damping, as before.
    sim.run_for(0.5).unwrap();
    let rate = sim.scene().joint_state(model.joint("hinge").unwrap()).unwrap().rate;
    assert!(rate.is_finite() && rate.abs() > 0.1, "{rate}");
}

#[test]
fn a_pair_touches_at_most_at_mujoco_s_four_points_around_its_footprint() {
    // A can on a tray: ODE's cylinder–box collider finds 8 points around the rim,
    // MuJoCo keeps 4. A tilted can rests on its rim's lowest points: the deepest is kept.
    const CAN: &str = r#"<mujoco><option timestep="0.002"/><worldbody>
        <geom name="tray" type="box" size="0.5 0.5 0.1" pos="0 0 -0.1"/>
        <body name="can" pos="0 0 0.05"><freejoint/><geom type="cylinder" size="0.1 0.05" mass="1"/></body>
      </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().time_step(0.002).build().unwrap();
    let model = sim.load_mjcf_text(CAN, "can.xml", &MjcfOptions::new()).unwrap();
    let can = model.body("can").unwrap();
    for _ in 0..150 {
        sim.step().unwrap();
        let contacts = sim.scene().world().contacts();
        assert!(contacts.len() <= 4, "{} points", contacts.len());
    }
    let contacts = sim.scene().world().contacts();
    assert_eq!(contacts.len(), 4, "the can rests on its rim");
    // Spread over the rim: the points span most of its 0.2 m diameter both ways.
    let span = |f: fn(&crate::ContactPoint) -> f64| {
        let v: Vec<f64> = contacts.iter().map(f).collect();
        v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min)
    };
    assert!(span(|c| c.position.x) > 0.15 && span(|c| c.position.z) > 0.15, "{contacts:?}");
    let y = sim.scene().position(can).unwrap().y;
    assert!((y - 0.05).abs() < 0.005, "it rests upright on the tray: {y}");
}
