//! MJCF models: bodies, geoms, joints and defaults read as MuJoCo reads them; bad files
//! refused with the element and line, and nothing left behind.

use ars::nalgebra::{Isometry3, Vector3};
use ars::{Error, MjcfOptions, Simulation};

const DOUBLE_PENDULUM: &str = r#"
<mujoco model="double pendulum">
  <compiler angle="degree"/>
  <option timestep="0.001" gravity="0 0 -9.81"/>
  <default>
    <joint type="hinge" axis="0 1 0" damping="0.01"/>
    <geom type="capsule" size="0.03" density="500"/>
    <default class="heavy"><geom density="2000" rgba="0.8 0.2 0.2 1"/></default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="upper" pos="0 0 1.5" euler="0 20 0">
      <joint name="shoulder" range="-90 90"/>
      <geom fromto="0 0 0 0 0 -0.5"/>
      <body pos="0 0 -0.5" childclass="heavy">
        <joint name="elbow"/>
        <geom fromto="0 0 0 0.4 0 0"/>
        <geom type="box" size="0.05 0.05 0.05" pos="0.4 0 0"/>
      </body>
    </body>
    <body name="ball" pos="1 0 0.5"><freejoint/><geom type="sphere" size="0.1"/></body>
  </worldbody>
  <actuator><motor joint="shoulder" gear="10"/></actuator>
</mujoco>"#;

#[test]
fn a_double_pendulum_loads_with_its_names_masses_and_limits() {
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(DOUBLE_PENDULUM, "pendulum.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.name, "double pendulum");
    assert_eq!(model.timestep, Some(0.001));
    // MuJoCo's Z-up gravity comes out along −Y.
    let g = model.gravity.unwrap();
    assert!((g - Vector3::new(0.0, -9.81, 0.0)).norm() < 1e-12, "{g}");
    let names: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["upper", "body2", "ball"], "unnamed bodies take MuJoCo's id");
    assert!(model.joint("shoulder").is_some() && model.joint("elbow").is_some());
    assert_eq!(model.actuators.len(), 1);
    // Capsule: ρ·(π r² L + 4/3 π r³) with the default density 500.
    let upper = sim.scene().body(model.body("upper").unwrap()).unwrap().mass();
    let expected = 500.0 * std::f64::consts::PI * (0.03f64.powi(2) * 0.5 + 4.0 / 3.0 * 0.03f64.powi(3));
    assert!((upper - expected).abs() < 1e-12 * expected, "{upper} vs {expected}");
    // The class "heavy" (childclass) makes the lower link four times as dense.
    let lower = sim.scene().body(model.body("body2").unwrap()).unwrap().mass();
    let capsule = 2000.0 * std::f64::consts::PI * (0.03f64.powi(2) * 0.4 + 4.0 / 3.0 * 0.03f64.powi(3));
    assert!((lower - (capsule + 2000.0 * 0.001)).abs() < 1e-9, "{lower}");
    let shoulder = sim.scene().joint("shoulder").unwrap().ode().unwrap();
    let (lo, hi) =
        (shoulder.param(ars::JointParam::LoStop, 0).unwrap(), shoulder.param(ars::JointParam::HiStop, 0).unwrap());
    assert!((lo + std::f64::consts::FRAC_PI_2).abs() < 1e-12 && (hi - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    // It swings and the ball falls to the floor.
    sim.run_for(1.0).unwrap();
    assert!(sim.scene().joint("elbow").unwrap().state().unwrap().position.abs() > 0.01);
    let ball = sim.scene().body(model.body("ball").unwrap()).unwrap().position();
    assert!((ball.y - 0.1).abs() < 0.01 && (ball.x - 1.0).abs() < 1e-6, "{ball}");
}

#[test]
fn a_base_pose_places_the_model() {
    let mut sim = Simulation::builder().build().unwrap();
    let options = MjcfOptions::new().base_pose(Isometry3::translation(2.0, 0.0, 0.0));
    let model = sim.load_mjcf_text(DOUBLE_PENDULUM, "pendulum.xml", &options).unwrap();
    let mut at_origin = Simulation::builder().build().unwrap();
    let there = at_origin.load_mjcf_text(DOUBLE_PENDULUM, "pendulum.xml", &MjcfOptions::new()).unwrap();
    for name in ["upper", "body2", "ball"] {
        let moved = sim.scene().body(model.body(name).unwrap()).unwrap().position();
        let origin = at_origin.scene().body(there.body(name).unwrap()).unwrap().position();
        assert!((moved - origin - Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-12, "{name}: {moved} vs {origin}");
    }
}

#[test]
fn bad_files_are_refused_naming_element_and_line_and_leave_nothing() {
    let cases = [
        ("<mujoco><worldbody><body>", "not XML"),
        ("<robot/>", "<mujoco>"),
        (
            "<mujoco><worldbody><body><geom size='0.1' mass='-1'/></body></worldbody></mujoco>",
            "mass must not be negative",
        ),
        (
            "<mujoco><worldbody><body><geom type='box' size='0.1 0 0.1'/></body></worldbody></mujoco>",
            "must be positive",
        ),
        (
            "<mujoco><worldbody><body><joint limited='true' range='10 -10'/><geom size='.1'/></body></worldbody></mujoco>",
            "reversed",
        ),
        (
            "<mujoco><tendon><spatial/></tendon></mujoco>",
            "a <spatial> tendon is not supported (skip_unsupported skips what ARS cannot read",
        ),
        (
            "<mujoco><tendon><fixed range='-1 1'><joint joint='j' coef='1'/></fixed></tendon></mujoco>",
            "a fixed tendon with a limit is not supported",
        ),
        ("<mujoco><worldbody><body><geom type='hfield' size='1'/></body></worldbody></mujoco>", "hfield"),
        ("<mujoco><worldbody><body><joint axis='0 0 0'/><geom size='.1'/></body></worldbody></mujoco>", "axis is zero"),
        ("<mujoco><worldbody><body><geom type='mesh' mesh='m'/></body></worldbody></mujoco>", "no <mesh> asset"),
        (
            "<mujoco><worldbody><body><joint type='ball' stiffness='3'/><geom size='.1'/></body></worldbody></mujoco>",
            "stiffness on a ball or free joint",
        ),
        (
            "<mujoco><worldbody><body><joint frictionloss='-1'/><geom size='.1'/></body></worldbody></mujoco>",
            "must not be negative",
        ),
        // A typo: MuJoCo's <geom> has no such attribute (nor has MuJoCo's schema).
        (
            "<mujoco><worldbody><body><geom size='.1' sise='.2'/></body></worldbody></mujoco>",
            "unknown attribute \"sise\"",
        ),
        ("<mujoco><default><joint dampin='1'/></default><worldbody/></mujoco>", "unknown attribute \"dampin\""),
        (
            "<mujoco><asset><mesh file='/nonexistent/m.stl'/></asset>\
             <worldbody><body><geom type='mesh' mesh='m'/></body></worldbody></mujoco>",
            "/nonexistent/m.stl",
        ),
    ];
    for (text, says) in cases {
        let mut sim = Simulation::builder().build().unwrap();
        let err = sim.load_mjcf_text(text, "bad.xml", &MjcfOptions::new()).unwrap_err();
        let message = err.to_string();
        let Error::Format { format: "MJCF", element, line, .. } = &err else { panic!("{message}") };
        // A caller can match the element and the line, not only read them.
        assert!(element.starts_with('<') && line.is_some_and(|l| l >= 1), "{element:?} {line:?}: {message}");
        assert!(message.contains(says) && message.contains("bad.xml") && message.contains("line"), "{message}");
        assert_eq!(sim.scene().objects().count(), 0, "nothing left behind: {message}");
    }
    // With skip_unsupported, what cannot be read is listed instead; a tendon's own
    // elements are not a body's, and their attributes are not checked as if they were.
    let mut sim = Simulation::builder().build().unwrap();
    let text = "<mujoco><tendon><fixed stiffness='2'><joint joint='j' coef='1'/></fixed></tendon>\
                <worldbody><body><geom size='.1' sise='1'/></body></worldbody></mujoco>";
    let model = sim.load_mjcf_text(text, "skip.xml", &MjcfOptions::new().skip_unsupported(true)).unwrap();
    assert!(model.skipped.iter().any(|s| s.contains("a fixed tendon with a spring")), "{:?}", model.skipped);
    assert!(
        model.skipped.iter().any(|s| s.starts_with("<geom> at line 1") && s.contains("sise")),
        "{:?}",
        model.skipped
    );
    assert!(!model.skipped.iter().any(|s| s.contains("coef")), "{:?}", model.skipped);
    // The contact parameters ODE has no place for (margin, gap) are said unused, without
    // skip_unsupported too; friction is used.
    let text =
        "<mujoco><worldbody><body><geom size='.1' friction='1 0.1 0.1' margin='0.01'/></body></worldbody></mujoco>";
    let model = Simulation::new().unwrap().load_mjcf_text(text, "friction.xml", &MjcfOptions::new()).unwrap();
    assert!(model.skipped.iter().any(|s| s.contains(": margin not used")), "{:?}", model.skipped);
    assert!(!model.skipped.iter().any(|s| s.contains("friction")), "{:?}", model.skipped);
    // Bad contact parameters are the file's errors.
    for (geom, says) in [
        ("condim='2'", "condim 2 must be 1, 3, 4 or 6"),
        ("friction='-1'", "friction -1 must be"),
        ("solref='0.02 -1'", "solref"),
        ("friction='1 2 3 4'", "friction takes 1 to 3 numbers"),
    ] {
        let text = format!("<mujoco><worldbody><body><geom size='.1' {geom}/></body></worldbody></mujoco>");
        let e = Simulation::new().unwrap().load_mjcf_text(&text, "bad.xml", &MjcfOptions::new()).unwrap_err();
        assert!(e.to_string().contains(says) && e.to_string().contains("<geom>"), "{e}");
    }
    assert_eq!(sim.scene().objects().count(), 1);
    let missing = sim.load_mjcf("/nonexistent/model.xml", &MjcfOptions::new()).unwrap_err();
    assert!(matches!(missing, Error::Io { .. }), "{missing}");
}

#[test]
fn several_joints_in_one_body_are_one_group_as_in_mujoco() {
    const PLANAR: &str = r#"<mujoco><worldbody><geom type="plane" size="5 5 .1"/>
        <body name="torso" pos="0 0 1" euler="0 30 0">
          <joint name="rootx" type="slide" axis="1 0 0"/>
          <joint name="rootz" type="slide" axis="0 0 1"/>
          <joint name="rooty" type="hinge" axis="0 1 0"/>
          <geom type="capsule" fromto="0 0 -0.3 0 0 0.3" size="0.05"/>
        </body></worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(PLANAR, "planar.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.joints.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), ["rootx", "rootz", "rooty"]);
    // One group: no light link, no body but the torso.
    assert!(model.chain_links.is_empty());
    assert_eq!(sim.scene().world().bodies().count(), 1);
    let torso = model.body("torso").unwrap();
    // The tilted capsule falls, lands and tips over in its plane: it moves along x and
    // turns about the hinge, and never leaves the plane z = 0.
    sim.run_for(1.5).unwrap();
    let p = sim.scene().body(torso).unwrap().position();
    assert!(p.z.abs() < 1e-6, "{p}");
    let rooty = sim.scene().joint("rooty").unwrap().state().unwrap().position;
    assert!(rooty.abs() > 0.3, "{rooty}");
}

#[test]
fn joints_a_group_cannot_take_are_chained_through_light_links() {
    // Two hinges through different points: a chain, its light link a fraction of the
    // body's mass.
    const OFFSET: &str = r#"<mujoco><worldbody>
        <body name="arm" pos="0 0 1">
          <joint name="a" axis="1 0 0"/><joint name="b" pos="0 0 -0.1" axis="0 1 0"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.05"/>
        </body></worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(OFFSET, "offset.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.chain_links.len(), 1);
    let arm = model.body("arm").unwrap();
    let link = sim.scene().body(model.chain_links[0]).unwrap().mass();
    assert!((link - sim.scene().body(arm).unwrap().mass() * ars::formats::mjcf::CHAIN_LINK_FRACTION).abs() < 1e-15);
    sim.run_for(0.2).unwrap();
}

#[test]
fn a_body_chained_to_its_parent_does_not_touch_it() {
    // A hip of two hinges, its thigh overlapping the pelvis as a humanoid's does: they
    // are jointed through a light link, and MuJoCo ignores a body's contacts with its
    // parent, so they must not push each other apart.
    const HIP: &str = r#"<mujoco><worldbody>
        <body name="pelvis" pos="0 0 1"><geom type="capsule" fromto="-0.1 0 0 0.1 0 0" size="0.09"/>
          <body name="thigh" pos="0.05 0 -0.05">
            <joint name="hip_x" axis="1 0 0"/><joint name="hip_y" axis="0 1 0"/>
            <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.06"/>
          </body>
        </body></worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(HIP, "hip.xml", &MjcfOptions::new()).unwrap();
    let (pelvis, thigh) = (model.body("pelvis").unwrap(), model.body("thigh").unwrap());
    assert_eq!(sim.scene().excluded_contacts(), [(pelvis, thigh)]);
    sim.run_for(0.2).unwrap();
    assert!(sim.scene().world().contacts().is_empty(), "the overlapping capsules do not touch");
    // It hangs and swings from its pivot; nothing ejects it.
    let speed = sim.scene().body(thigh).unwrap().linear_velocity().norm();
    assert!(speed < 2.0, "{speed}");
}

#[test]
fn a_body_lighter_than_ars_allows_is_raised_and_one_too_heavy_refused_by_name() {
    // 1e-5 kg/m³ in a 1 cm ball weighs 4e-11 kg, below ARS's 1e-9 kg (Gymnasium's
    // pusher has such markers): raised to 1e-9 kg, its inertia scaled alike, and said.
    const FEATHER: &str = r#"<mujoco><worldbody><body name="feather"><freejoint/>
        <geom type="sphere" size="0.01" density="1e-5"/></body></worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(FEATHER, "feather.xml", &MjcfOptions::new()).unwrap();
    let body = sim.scene().body(model.body("feather").unwrap()).unwrap();
    assert_eq!(body.mass(), ars::limits::MIN_MASS);
    let ball = 2.0 / 5.0 * ars::limits::MIN_MASS * 0.01 * 0.01;
    assert!((body.inertia()[(0, 0)] - ball).abs() < 1e-12 * ball, "{}", body.inertia());
    assert!(model.skipped.iter().any(|s| s.contains("\"feather\"") && s.contains("raised")), "{:?}", model.skipped);
    // 1e10 kg is above ARS's most: refused, naming the body, leaving nothing.
    let mut sim = Simulation::builder().build().unwrap();
    let heavy = FEATHER.replace(r#"density="1e-5""#, r#"mass="1e10""#);
    let err = sim.load_mjcf_text(&heavy, "heavy.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("\"feather\"") && err.contains("mass"), "{err}");
    assert_eq!(sim.scene().objects().count(), 0);
}

#[test]
fn includes_are_read_in_place_and_their_errors_name_their_file() {
    let dir = std::env::temp_dir().join(format!("ars-mjcf-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
    write(
        "scene.xml",
        r#"<mujoco model="scene"><include file="parts/classes.xml"/><include file="parts/robot.xml"/></mujoco>"#,
    );
    write("parts/classes.xml", r#"<mujoco><default><geom density="300"/></default></mujoco>"#);
    write(
        "parts/robot.xml",
        r#"<mujoco><worldbody><body name="bob" pos="0 0 1"><joint name="pivot" pos="0 0 0.5"/>
           <geom type="sphere" size="0.1"/></body></worldbody></mujoco>"#,
    );
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf(dir.join("scene.xml"), &MjcfOptions::new()).unwrap();
    assert_eq!(model.name, "scene");
    // The included class's density (not MuJoCo's 1000) weighs the included body.
    let mass = sim.scene().body(model.body("bob").unwrap()).unwrap().mass();
    assert!((mass - 300.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-3).abs() < 1e-12, "{mass}");
    // Includes below the top level: in a class, in the world body and in a body, read in
    // place (MuJoCo allows them anywhere), and an include inside an included file.
    write(
        "nested.xml",
        r#"<mujoco model="nested">
             <default><include file="parts/heavy.xml"/></default>
             <worldbody>
               <include file="parts/arm.xml"/>
             </worldbody>
           </mujoco>"#,
    );
    write("parts/heavy.xml", r#"<mujoco><geom density="2000"/></mujoco>"#);
    write(
        "parts/arm.xml",
        // Relative to the model's file (nested.xml), not to arm.xml: as MuJoCo reads it.
        r#"<mujoco><body name="arm" pos="0 0 1"><joint name="shoulder"/>
           <include file="parts/hand.xml"/></body></mujoco>"#,
    );
    write(
        "parts/hand.xml",
        r#"<mujoco><geom type="sphere" size="0.1"/><body name="finger"><geom type="sphere" size="0.05" pos="0.2 0 0"/></body></mujoco>"#,
    );
    let mut nested = Simulation::builder().build().unwrap();
    let model = nested.load_mjcf(dir.join("nested.xml"), &MjcfOptions::new()).unwrap();
    let ball = |r: f64| 2000.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    // The finger has no joint: it is welded into the arm, one rigid body of both masses.
    assert_eq!(model.body("finger"), model.body("arm"));
    let arm = nested.scene().body(model.body("arm").unwrap()).unwrap().mass();
    assert!((arm - ball(0.1) - ball(0.05)).abs() < 1e-12, "{arm}");
    // An error there names the deepest file.
    write(
        "parts/hand.xml",
        r#"<mujoco>
      <geom type="box" size="0.1 0.1"/></mujoco>"#,
    );
    let err = nested.load_mjcf(dir.join("nested.xml"), &MjcfOptions::new()).unwrap_err();
    let Error::Format { file, element, line, .. } = &err else { panic!("{err}") };
    assert!(file.ends_with("hand.xml") && element == "<geom>" && *line == Some(2), "{err}");
    // An error in an included file names that file and its line.
    write("parts/robot.xml", r#"<mujoco><worldbody><body><geom size="-1"/></body></worldbody></mujoco>"#);
    let err = sim.load_mjcf(dir.join("scene.xml"), &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("robot.xml") && err.contains("line 1") && err.contains("positive"), "{err}");
    // A cycle, and a file that is not there.
    write("a.xml", r#"<mujoco><include file="b.xml"/></mujoco>"#);
    write("b.xml", r#"<mujoco><include file="a.xml"/></mujoco>"#);
    let err = sim.load_mjcf(dir.join("a.xml"), &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("cycle") && err.contains("b.xml"), "{err}");
    write("c.xml", r#"<mujoco><include file="nowhere.xml"/></mujoco>"#);
    let err = sim.load_mjcf(dir.join("c.xml"), &MjcfOptions::new()).unwrap_err().to_string();
    assert!(err.contains("nowhere.xml") && err.contains("<include>"), "{err}");
    assert_eq!(sim.scene().objects().count(), 1, "only the first model's body");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Three single-hinge arms in zero gravity, each with one kind of actuator.
const ACTUATED: &str = r#"
<mujoco model="actuated">
  <option gravity="0 0 0"/>
  <default>
    <joint type="hinge" axis="0 1 0"/>
    <geom type="capsule" size="0.03" contype="0" conaffinity="0"/>
    <general ctrlrange="-1 1"/>
  </default>
  <worldbody>
    <body name="a"><joint name="ja"/><geom fromto="0 0 0 0.5 0 0"/></body>
    <body name="b" pos="0 1 0"><joint name="jb"/><geom fromto="0 0 0 0.5 0 0"/></body>
    <body name="c" pos="0 2 0"><joint name="jc"/><geom fromto="0 0 0 0.5 0 0"/></body>
  </worldbody>
  <actuator>
    <motor name="push" joint="ja" gear="10"/>
    <position name="hold" joint="jb" kp="30" kv="3" forcerange="-5 5"/>
    <velocity name="spin" joint="jc" kv="2" gear="2" ctrllimited="false"/>
  </actuator>
</mujoco>"#;

#[test]
fn actuators_drive_their_joints_as_mujoco_defines_them() {
    // The file's gravity (none) is returned, not applied: the simulation is built so.
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(ACTUATED, "actuated.xml", &MjcfOptions::new()).unwrap();
    let names: Vec<&str> = sim.scene().actuators().map(|(n, _)| n).collect();
    assert_eq!(names, ["push", "hold", "spin"]);
    let push = &model.actuators[0].actuator;
    // A class's <general> sets every actuator kind's defaults, as in MuJoCo.
    assert_eq!((push.gear(), push.ctrl_range()), (10.0, Some((-1.0, 1.0))), "the class's default");
    assert_eq!(model.actuators[1].actuator.ctrl_range(), Some((-1.0, 1.0)), "the class's default");
    assert_eq!(model.actuators[2].actuator.ctrl_range(), None, "ctrllimited=\"false\" wins");
    assert_eq!(model.actuators[1].actuator.force_range(), Some((-5.0, 5.0)));
    assert_eq!(sim.scene().control("push").unwrap(), 0.0);

    // The motor: 5 is clamped to 1, a torque of gear × 1 = 10 N·m from rest.
    sim.scene_mut().set_control("push", 5.0).unwrap();
    assert_eq!(sim.scene().control("push").unwrap(), 1.0);
    sim.scene_mut().set_control("hold", 0.4).unwrap();
    sim.scene_mut().set_control("spin", 3.0).unwrap();
    // The inertia of arm a about its hinge: MuJoCo's Y axis through the origin is the
    // simulation's −Z; the capsule's centre is 0.25 m out along X.
    let i_a = {
        let b = sim.scene().body(model.body("a").unwrap()).unwrap();
        let axis = Vector3::z();
        let p = b.position().coords;
        let r = (p - axis * p.dot(&axis)).norm();
        let about_centre = b.rotation().matrix() * b.inertia() * b.rotation().matrix().transpose();
        axis.dot(&(about_centre * axis)) + b.mass() * r * r
    };
    sim.step().unwrap();
    let rate = sim.scene().joint("ja").unwrap().state().unwrap().rate;
    // MuJoCo's qacc for this model is 75.2208 rad/s² (mj_forward).
    let expected = 10.0 / i_a * sim.scene().time_step();
    assert!((rate.abs() - expected).abs() < 1e-6 * expected, "{rate} vs {expected}");
    assert!((expected / sim.scene().time_step() - 75.2208).abs() < 1e-3);

    // The position servo settles at its control (gear 1), the velocity servo at
    // ctrl / gear.
    sim.run_for(5.0).unwrap();
    let hold = sim.scene().joint("jb").unwrap().state().unwrap().position;
    assert!((hold.abs() - 0.4).abs() < 1e-3, "held at {hold}");
    let spin = sim.scene().joint("jc").unwrap().state().unwrap().rate;
    assert!((spin.abs() - 1.5).abs() < 1e-3, "spins at {spin}");

    // Kept by scene files and snapshots.
    let copy = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    assert_eq!(copy.scene().control("push").unwrap(), 1.0);
    assert_eq!(copy.scene().control("spin").unwrap(), 3.0);

    // Unknown names and bad values are said.
    let e = sim.scene_mut().set_control("pusj", 0.0).unwrap_err();
    assert!(e.to_string().contains("push"), "a close match is suggested: {e}");
    assert!(sim.scene_mut().set_control("hold", f64::NAN).is_err());
    assert_eq!(sim.scene().control("hold").unwrap(), 0.4);
}

/// [`ACTUATED`]'s three arms driven by `<general>` actuators written as MuJoCo expands
/// its shortcuts (`motor`: gain 1; `position`: gain kp, bias 0 −kp −kv; `velocity`:
/// gain kv, bias 0 0 −kv), and a fourth arm with a scaled servo (gain 500, bias
/// 0 −200 0: it holds at 2.5 × its control).
fn general_actuated() -> String {
    ACTUATED
        .replace(
            r#"<body name="c" pos="0 2 0"><joint name="jc"/><geom fromto="0 0 0 0.5 0 0"/></body>"#,
            r#"<body name="c" pos="0 2 0"><joint name="jc"/><geom fromto="0 0 0 0.5 0 0"/></body>
    <body name="d" pos="0 3 0"><joint name="jd" damping="5"/><geom fromto="0 0 0 0.5 0 0"/></body>"#,
        )
        .replace(r#"<motor name="push" joint="ja" gear="10"/>"#, r#"<general name="push" joint="ja" gear="10"/>"#)
        .replace(
            r#"<position name="hold" joint="jb" kp="30" kv="3" forcerange="-5 5"/>"#,
            r#"<general name="hold" joint="jb" gainprm="30" biastype="affine" biasprm="0 -30 -3" forcerange="-5 5"/>"#,
        )
        .replace(
            r#"<velocity name="spin" joint="jc" kv="2" gear="2" ctrllimited="false"/>"#,
            r#"<general name="spin" joint="jc" gainprm="2" biastype="affine" biasprm="0 0 -2" gear="2" ctrllimited="false"/>
    <general name="scaled" joint="jd" gainprm="500 0 0" biastype="affine" biasprm="0 -200 0"/>"#,
        )
}

#[test]
fn general_actuators_move_their_joints_as_the_shortcuts_they_expand_and_a_scaled_servo_holds() {
    let run = |text: &str| {
        let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
        sim.load_mjcf_text(text, "actuated.xml", &MjcfOptions::new()).unwrap();
        for (name, ctrl) in [("push", 0.3), ("hold", 0.4), ("spin", 3.0)] {
            sim.scene_mut().set_control(name, ctrl).unwrap();
        }
        if sim.scene().control("scaled").is_ok() {
            sim.scene_mut().set_control("scaled", 0.2).unwrap();
        }
        sim.run_for(2.0).unwrap();
        let state = |j: &str| sim.scene().joint(j).unwrap().state().unwrap();
        let shortcuts: Vec<(u64, u64)> =
            ["ja", "jb", "jc"].iter().map(|j| (state(j).position.to_bits(), state(j).rate.to_bits())).collect();
        (shortcuts, sim.scene().joint("jd").ok().map(|_| state("jd").position))
    };
    let (shortcuts, _) = run(ACTUATED);
    let (general, held) = run(&general_actuated());
    assert_eq!(general, shortcuts, "a <general> written as a shortcut moves its joint bit for bit as the shortcut");
    // 500·0.2 − 200·q = 0 at q = 0.5 rad (the sign: MuJoCo's Y axis is ARS's −Z).
    let held = held.unwrap();
    assert!((held.abs() - 0.5).abs() < 1e-6, "held at {held}");

    // Activation dynamics are not modelled: refused naming them, or skipped.
    let filtered = general_actuated().replace(r#"gainprm="500 0 0""#, r#"dyntype="filter" gainprm="500 0 0""#);
    let mut sim = Simulation::builder().build().unwrap();
    let e = sim.load_mjcf_text(&filtered, "f.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(e.contains("dyntype=\"filter\"") && e.contains("skip_unsupported"), "{e}");
    let model = sim.load_mjcf_text(&filtered, "f.xml", &MjcfOptions::new().skip_unsupported(true)).unwrap();
    assert_eq!(model.actuators.len(), 3);
    assert!(model.skipped.iter().any(|s| s.contains("dyntype")), "{:?}", model.skipped);
}

#[test]
fn keyframes_are_read_and_listed_not_applied_as_mujoco_compiles_them() {
    let with_keys = ACTUATED.replace(
        "</mujoco>",
        r#"<keyframe>
    <key name="bent" qpos="0.5 -0.25 1" ctrl="1 0.4 0"/>
    <key time="2" qvel="0 0 3"/>
  </keyframe>
</mujoco>"#,
    );
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(&with_keys, "keys.xml", &MjcfOptions::new()).unwrap();
    assert!(model.skipped.is_empty(), "{:?}", model.skipped);
    let names: Vec<(&str, f64)> = model.keyframes.iter().map(|k| (k.name.as_str(), k.time)).collect();
    assert_eq!(names, [("bent", 0.0), ("key1", 2.0)]);
    assert_eq!(model.keyframes[0].qpos, [0.5, -0.25, 1.0]);
    assert_eq!(model.keyframes[0].ctrl, [1.0, 0.4, 0.0]);
    assert_eq!(model.keyframes[1].qvel, [0.0, 0.0, 3.0]);
    assert!(model.keyframes[1].qpos.is_empty());
    // Not applied: the joints start at 0 and the controls at 0, as MuJoCo's reset.
    assert_eq!(sim.scene().joint("ja").unwrap().state().unwrap().position, 0.0);
    assert_eq!(sim.scene().control("hold").unwrap(), 0.0);

    // A bad number or an unknown attribute is said, with its line.
    let bad = with_keys.replace(r#"qpos="0.5 -0.25 1""#, r#"qpos="0.5 nan 1""#);
    let e = sim.load_mjcf_text(&bad, "keys.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(e.contains("qpos") && e.contains("line"), "{e}");
    let typo = with_keys.replace(r#"qvel="0 0 3""#, r#"qvle="0 0 3""#);
    let e = sim.load_mjcf_text(&typo, "keys.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(e.contains("qvle"), "{e}");
}

#[test]
fn an_actuator_on_a_missing_joint_is_refused_and_leaves_nothing() {
    let mut sim = Simulation::builder().build().unwrap();
    let text = ACTUATED.replace(r#"joint="jc""#, r#"joint="jz""#);
    let e = sim.load_mjcf_text(&text, "actuated.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("\"jz\""), "{e}");
    assert_eq!(sim.scene().objects().count(), 0);
    assert_eq!(sim.scene().joints().count(), 0);
}

#[test]
fn excluded_bodies_pass_through_each_other_and_files_keep_it() {
    // A ball dropped on a fixed plate, and a second ball on a second plate, with the
    // first pair excluded.
    let text = r#"
<mujoco>
  <worldbody>
    <body name="plate"><geom type="box" size="0.5 0.5 0.05"/></body>
    <body name="ball" pos="0 0 0.5"><freejoint/><geom type="sphere" size="0.1"/></body>
    <body name="plate2" pos="2 0 0"><geom type="box" size="0.5 0.5 0.05"/></body>
    <body name="ball2" pos="2 0 0.5"><freejoint/><geom type="sphere" size="0.1"/></body>
  </worldbody>
  <contact><exclude body1="plate" body2="ball"/></contact>
</mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(text, "exclude.xml", &MjcfOptions::new()).unwrap();
    let (plate, ball) = (model.body("plate").unwrap(), model.body("ball").unwrap());
    // With the file's pair, the two plates: both welded to the world, which MuJoCo
    // never collides.
    let plate2 = model.body("plate2").unwrap();
    assert_eq!(sim.scene().excluded_contacts(), [(ball, plate), (plate, plate2)]);
    let copy = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    for mut s in [sim, copy] {
        s.run_for(1.0).unwrap();
        let y = |name: &str| s.scene().object(name).unwrap().position().unwrap().y;
        assert!(y("ball") < -1.0, "the excluded ball fell through its plate: {}", y("ball"));
        assert!((y("ball2") - 0.15).abs() < 0.01, "the other rests on its plate: {}", y("ball2"));
    }
    let bad = text.replace(r#"body2="ball""#, r#"body2="bal""#);
    let mut sim = Simulation::builder().build().unwrap();
    let e = sim.load_mjcf_text(&bad, "exclude.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("\"bal\""), "{e}");
    assert_eq!(sim.scene().objects().count(), 0);
}

#[test]
fn a_contact_pair_touches_whatever_its_bits_say_and_nothing_else_does() {
    // Two balls over a plate whose contype and conaffinity are 0: only the ball paired
    // with it lands; the other falls through. A ball's own bits are unchanged, so the
    // two balls, side by side and overlapping, never touch each other either way.
    let text = r#"
<mujoco>
  <worldbody>
    <geom name="plate" type="box" size="1 0.5 0.05" contype="0" conaffinity="0"/>
    <body name="held" pos="0 0 0.5"><freejoint/><geom name="held" type="sphere" size="0.1" contype="0" conaffinity="0"/></body>
    <body name="loose" pos="0.15 0 0.5"><freejoint/><geom type="sphere" size="0.1" contype="0" conaffinity="0"/></body>
  </worldbody>
  <contact><pair geom1="held" geom2="plate" condim="3" friction="0.7 0.7 0.005 0.0001 0.0001" solref="0.01 1" margin="0.001"/></contact>
</mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(text, "pair.xml", &MjcfOptions::new()).unwrap();
    // Its own parameters are the pair's contacts' (MuJoCo's defaults for the rest);
    // its margin is said unused.
    let pairs = sim.scene().geom_pair_contacts();
    let [((held, 0), (plate, 0), contact)] = pairs[..] else { panic!("{pairs:?}") };
    assert_eq!((held, plate), (model.body("held").unwrap(), model.world_geoms[0]));
    assert_eq!((contact.friction, contact.solref, contact.condim), ([0.7, 0.005, 0.0001], [0.01, 1.0], 3));
    assert_eq!(contact.solimp, ars::GeomContact::default().solimp);
    assert!(model.skipped.iter().any(|s| s.starts_with("<pair>") && s.contains(": margin ")), "{:?}", model.skipped);
    // Kept by a scene file and by a snapshot.
    let copy = ars::formats::scene_file::SceneFile::parse(&sim.save_scene().unwrap(), "pair.json").unwrap();
    let copied = copy.build().unwrap().scene().geom_pair_contacts();
    assert_eq!((copied.len(), copied[0].0.1, copied[0].1.1, copied[0].2), (1, 0, 0, contact), "another world's ids");
    let snapshot = sim.snapshot().unwrap();
    sim.restore(&snapshot).unwrap();
    assert_eq!(sim.scene().geom_pair_contacts(), pairs);
    // A geom cannot pair with itself; a bad index or bad parameters are refused.
    let scene = sim.scene_mut();
    assert!(scene.set_geom_pair_contact((held, 0), (held, 0), contact).is_err());
    assert!(scene.set_geom_pair_contact((held, 0), (plate, 3), contact).is_err());
    let bad = ars::GeomContact { condim: 2, ..contact };
    assert!(scene.set_geom_pair_contact((held, 0), (plate, 0), bad).is_err());
    assert_eq!(scene.geom_pair_contacts(), pairs);
    sim.run_for(1.0).unwrap();
    let y = |name: &str| sim.scene().object(name).unwrap().position().unwrap().y;
    assert!((y("held") - 0.15).abs() < 0.01, "the paired ball rests on the plate: {}", y("held"));
    assert!(y("loose") < -1.0, "the other falls through: {}", y("loose"));

    // An unknown geom is refused and leaves nothing; so is a contype beyond 32 bits.
    let mut sim = Simulation::builder().build().unwrap();
    let bad = text.replace(r#"geom2="plate""#, r#"geom2="plat""#);
    let e = sim.load_mjcf_text(&bad, "pair.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("\"plat\""), "{e}");
    assert_eq!(sim.scene().objects().count(), 0);
    let bad = text.replace(r#"size="1 0.5 0.05" contype="0""#, r#"size="1 0.5 0.05" contype="4294967296""#);
    let e = sim.load_mjcf_text(&bad, "pair.xml", &MjcfOptions::new()).unwrap_err();
    let Error::Format { element, line, .. } = &e else { panic!("{e}") };
    assert!(element == "<geom>" && *line == Some(4) && e.to_string().contains("32 bits"), "{e}");
}

#[test]
fn a_geom_takes_its_material_s_colour_unless_it_has_its_own() {
    let text = r#"<mujoco>
      <asset><material name="red" rgba="1 0 0 1"/><material name="green" rgba="0 1 0 1"/></asset>
      <default><default class="blue"><geom rgba="0 0 1 1"/></default></default>
      <worldbody>
        <body name="red"><freejoint/><geom size=".1" material="red"/></body>
        <body name="own" pos="1 0 0"><freejoint/><geom size=".1" material="red" rgba="1 1 0 1"/></body>
        <body name="class" pos="2 0 0"><freejoint/><geom class="blue" size=".1" material="green"/></body>
      </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    sim.load_mjcf_text(text, "materials.xml", &MjcfOptions::new()).unwrap();
    let color = |name: &str| sim.scene().object(name).unwrap().color().unwrap();
    assert_eq!(color("red"), [1.0, 0.0, 0.0]);
    assert_eq!(color("own"), [1.0, 1.0, 0.0], "its own rgba wins");
    assert_eq!(color("class"), [0.0, 0.0, 1.0], "its class's rgba wins too");
}

#[test]
fn a_flat_mesh_is_refused_as_mujoco_refuses_it() {
    let dir = std::env::temp_dir().join(format!("ars-mjcf-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // One triangle: no volume, and no convex hull to collide as (MuJoCo: "mesh has
    // coplanar vertices, cannot compute convex hull").
    std::fs::write(dir.join("flat.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let text = "<mujoco><asset><mesh file='flat.obj'/></asset>\
                <worldbody><body><geom type='mesh' mesh='flat'/></body></worldbody></mujoco>";
    let path = dir.join("flat.xml");
    std::fs::write(&path, text).unwrap();
    let mut sim = Simulation::builder().build().unwrap();
    let e = sim.load_mjcf(&path, &MjcfOptions::new()).unwrap_err().to_string();
    assert!(e.contains("no convex hull") && e.contains("\"flat\"") && e.contains("line 1"), "{e}");
    assert_eq!(sim.scene().objects().count(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sensors_read_their_joints_and_bodies() {
    let text = ACTUATED.replace(
        "</mujoco>",
        r#"<sensor>
    <jointpos name="a_angle" joint="ja"/>
    <jointvel joint="ja"/>
    <framepos name="c_at" objtype="body" objname="c"/>
    <framelinvel objtype="body" objname="c"/>
  </sensor></mujoco>"#,
    );
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(&text, "sensed.xml", &MjcfOptions::new()).unwrap();
    let names: Vec<&str> = model.sensors.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["a_angle", "sensor1", "c_at", "sensor3"]);
    assert!(model.sensors.iter().all(|s| s.id.is_some()));
    sim.scene_mut().set_control("push", 0.5).unwrap();
    sim.scene_mut().set_control("spin", 3.0).unwrap();
    sim.run_for(0.2).unwrap();
    // Each sensor's last row is the joint's or body's state after the last step.
    let tables = sim.sensor_tables();
    let last = |i: usize| {
        let table = tables[i].1;
        table.cells(table.len() - 1).into_iter().map(|v| v.unwrap()).collect::<Vec<f64>>()
    };
    let ja = sim.scene().joint("ja").unwrap().state().unwrap();
    assert_eq!(last(0), [ja.position]);
    assert_eq!(last(1), [ja.rate]);
    let c = sim.scene().body(model.body("c").unwrap()).unwrap();
    assert_eq!(last(2), c.position().coords.as_slice());
    // A velometer reads the angular velocity too, after the linear one.
    assert_eq!(last(3)[..3], *c.linear_velocity().as_slice());
    assert!(ja.rate.abs() > 0.1);

    // What ARS cannot read is said, naming the element and line.
    let geom = ACTUATED.replace("</mujoco>", r#"<sensor><framepos objtype="geom" objname="g"/></sensor></mujoco>"#);
    let e = Simulation::new().unwrap().load_mjcf_text(&geom, "geom.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("objtype geom") && e.to_string().contains("<framepos>"), "{e}");
    let missing = ACTUATED.replace("</mujoco>", r#"<sensor><jointpos joint="nope"/></sensor></mujoco>"#);
    let mut sim = Simulation::new().unwrap();
    let e = sim.load_mjcf_text(&missing, "missing.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("\"nope\""), "{e}");
    assert_eq!(sim.scene().objects().count(), 0);
}

/// A box resting on the floor with sites for every sensor read on sites, and a free
/// ball above it.
const SITES: &str = r#"
<mujoco model="sites">
  <default><site type="sphere" size="0.01"/><default class="pad"><site type="box"/></default></default>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <site name="in_the_world" pos="0 0 2"/>
    <body name="box" pos="0 0 0.05">
      <freejoint/>
      <geom type="box" size="0.2 0.1 0.05" mass="2"/>
      <geom type="sphere" size="0.02" pos="0.15 0 0.05" mass="0.5"/>
      <site name="top" pos="0 0.08 0.05" euler="0 0 90"/>
      <site name="bottom" class="pad" size="0.21 0.11 0.01" pos="0 0 -0.05"/>
      <site name="down" pos="0.1 0 0" zaxis="0 0 -1"/>
      <site/>
    </body>
    <body name="ball" pos="0 0 1"><freejoint/><geom type="sphere" size="0.05" mass="1"/>
      <site name="ball_pad" size="0.06"/>
    </body>
  </worldbody>
  <sensor>
    <accelerometer name="acc" site="top"/>
    <gyro name="gyro" site="top"/>
    <touch name="touch" site="bottom"/>
    <touch name="ball_touch" site="ball_pad"/>
    <rangefinder name="range" site="down"/>
    <rangefinder name="sky" site="top"/>
    <framepos name="top_at" objtype="site" objname="top"/>
    <framequat name="box_turn" objtype="xbody" objname="box"/>
    <framelinvel name="ball_v" objtype="xbody" objname="ball"/>
  </sensor>
</mujoco>"#;

#[test]
fn sites_carry_sensors_that_read_a_resting_box_as_mujoco_would() {
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(SITES, "sites.xml", &MjcfOptions::new()).unwrap();
    // Named sites only; each placed relative to its body's centre of mass.
    let names: Vec<&str> = model.sites.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["top", "bottom", "down", "ball_pad"]);
    // The box's centre of mass: 2 kg at 0 and 0.5 kg at x = 0.15, z = 0.05.
    let com = Vector3::new(0.5 * 0.15 / 2.5, 0.0, 0.5 * 0.05 / 2.5);
    let top = model.site("top").unwrap();
    assert_eq!(top.body, "box");
    assert!((top.offset.translation.vector - (Vector3::new(0.0, 0.08, 0.05) - com)).norm() < 1e-12);
    assert!((top.offset.rotation.angle() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert_eq!(
        model.site("bottom").unwrap().zone,
        ars::sensors::TouchZone::Box { half_extents: Vector3::new(0.21, 0.11, 0.01) },
        "the class's type, the site's size"
    );
    assert!(
        matches!(model.site("ball_pad").unwrap().zone, ars::sensors::TouchZone::Sphere { radius } if radius == 0.06)
    );
    let kinds: Vec<&str> = model.sensors.iter().map(|s| s.kind.as_str()).collect();
    assert_eq!(
        kinds,
        [
            "accelerometer",
            "gyro",
            "touch",
            "touch",
            "rangefinder",
            "rangefinder",
            "framepos",
            "framequat",
            "framelinvel"
        ]
    );
    assert!(model.sensors.iter().all(|s| s.id.is_some() && s.mount.is_some()));

    sim.run_for(1.0).unwrap();
    let tables = sim.sensor_tables();
    let last = |name: &str| {
        let i = model.sensors.iter().position(|s| s.name == name).unwrap();
        let table = tables[i].1;
        table.cells(table.len() - 1)
    };
    let g = 9.81;
    // At rest: the accelerometer feels g up the box's Z, which is the site's Z (the site
    // is turned about Z only); the gyro reads nothing.
    let acc: Vec<f64> = last("acc")[..3].iter().map(|v| v.unwrap()).collect();
    assert!((acc[0].abs() + acc[1].abs()) < 1e-3 && (acc[2] - g).abs() < 1e-3, "{acc:?}");
    let gyro: Vec<f64> = last("gyro")[3..].iter().map(|v| v.unwrap()).collect();
    assert!(gyro.iter().all(|w| w.abs() < 1e-3), "{gyro:?}");
    // The floor carries the box and the ball on it: the pad under the box feels both.
    let touch = last("touch")[1].unwrap();
    assert!((touch - 3.5 * g).abs() < 1e-3 * 3.5 * g, "{touch}");
    assert!(last("touch")[0].unwrap() >= 3.0, "the box rests on several contact points");
    // The ball, fallen on the box, is pressed by it from below and presses nothing.
    let ball_touch = last("ball_touch")[1].unwrap();
    assert!((ball_touch - g).abs() < 1e-2 * g, "{ball_touch}");
    // The ray down from the box's mid-height, not seeing the box, meets the floor.
    let range = last("range")[0].unwrap();
    assert!((range - 0.05).abs() < 1e-3, "{range}");
    // Up from the top, nothing: MuJoCo's −1, an empty cell here.
    assert_eq!(last("sky")[0], None);
    // The site's position is the box's pose applied to its offset.
    let pose = sim.scene().pose(model.body("box").unwrap()).unwrap();
    let at = pose * ars::nalgebra::Point3::from(top.offset.translation.vector);
    let read: Vec<f64> = last("top_at").iter().map(|v| v.unwrap()).collect();
    assert!((Vector3::from_column_slice(&read) - at.coords).norm() < 1e-12);
    // The box's frame (xbody) has the model's turn: −90° about X.
    let q: Vec<f64> = last("box_turn").iter().map(|v| v.unwrap()).collect();
    let half = std::f64::consts::FRAC_1_SQRT_2;
    assert!((q[0] - half).abs() < 1e-3 && (q[1] + half).abs() < 1e-3, "{q:?}");
}

#[test]
fn a_sensor_on_a_site_the_model_lacks_is_refused_with_its_line() {
    let text = SITES.replace(r#"<gyro name="gyro" site="top"/>"#, r#"<accelerometer site="nowhere"/>"#);
    let mut sim = Simulation::new().unwrap();
    let e = sim.load_mjcf_text(&text, "sites.xml", &MjcfOptions::new()).unwrap_err();
    let line = text.lines().position(|l| l.contains("nowhere")).unwrap() + 1;
    let Error::Format { element, line: Some(at), problem, .. } = &e else { panic!("{e:?}") };
    assert_eq!((element.as_str(), *at as usize), ("<accelerometer>", line), "{e}");
    assert!(problem.contains("site \"nowhere\""), "{e}");
    assert_eq!(sim.scene().objects().count(), 0, "nothing is left behind");

    // What is not supported is refused, or skipped and said.
    let text = SITES.replace(
        "</sensor>",
        r#"<force site="top"/>
    <framequat objtype="body" objname="box"/>
    <gyro site="in_the_world"/>
    <framepos objtype="geom" objname="floor"/>
    <rangefinder site="down" cutoff="1"/>
    <rangefinder site="down" data="normal"/>
  </sensor>"#,
    );
    let mut sim = Simulation::new().unwrap();
    let e = sim.load_mjcf_text(&text, "sites.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(e.contains("<force>"), "{e}");
    let model = sim.load_mjcf_text(&text, "sites.xml", &MjcfOptions::new().skip_unsupported(true)).unwrap();
    assert_eq!(model.sensors.len(), 9, "the supported ones only");
    for what in ["<force>", "inertial frame", "world body", "objtype geom", "cutoff", "other than \"dist\""] {
        assert!(model.skipped.iter().any(|s| s.contains(what)), "{what} in {:?}", model.skipped);
    }
}

#[test]
fn reference_positions_and_springs_survive_a_scene_file_and_a_snapshot() {
    const SPRUNG: &str = r#"<mujoco><option gravity="0 0 -9.81"/><worldbody>
        <body name="arm" pos="0 0 2" euler="0 50 0">
          <joint name="hinge" axis="0 1 0" ref="20" stiffness="3" springref="35" frictionloss="0.01"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.03"/>
          <body name="slider" pos="0 0 -0.4">
            <joint name="slide" type="slide" axis="0 0 1" ref="0.1" stiffness="40" springref="0.15"/>
            <geom type="box" size="0.05 0.05 0.05"/>
          </body>
        </body></worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    sim.load_mjcf_text(SPRUNG, "sprung.xml", &MjcfOptions::new()).unwrap();
    let position = |sim: &Simulation, name: &str| sim.scene().joint(name).unwrap().state().unwrap().position;
    // In the file's pose each joint reads its ref, as MuJoCo's qpos0.
    assert!((position(&sim, "hinge") - 20f64.to_radians()).abs() < 1e-12);
    assert!((position(&sim, "slide") - 0.1).abs() < 1e-12);
    assert_eq!(sim.scene().joint("slide").unwrap().spring(), (40.0, 0.15));
    assert_eq!(sim.scene().joint("hinge").unwrap().dry_friction(), 0.01);
    sim.run_for(0.2).unwrap();
    let copy = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    let snapshot = sim.snapshot().unwrap();
    let mut restored = Simulation::builder().build().unwrap();
    restored.load_mjcf_text(SPRUNG, "sprung.xml", &MjcfOptions::new()).unwrap();
    restored.restore(&snapshot).unwrap();
    sim.run_for(0.3).unwrap();
    let expected = [position(&sim, "hinge"), position(&sim, "slide")];
    for mut other in [copy, restored] {
        assert_eq!(other.scene().joint("slide").unwrap().spring(), (40.0, 0.15));
        other.run_for(0.3).unwrap();
        // The same bits: the references, springs and dry friction came back.
        assert_eq!([position(&other, "hinge"), position(&other, "slide")], expected);
    }
    // Bad springs are refused.
    let mut joint = sim.scene_mut().joint_mut("slide").unwrap();
    for (stiffness, rest) in [(-1.0, 0.0), (f64::NAN, 0.0), (1.0, f64::INFINITY)] {
        let e = joint.set_spring(stiffness, rest).unwrap_err().to_string();
        assert!(e.contains("spring"), "{e}");
    }
}

/// `MjcfFile`: Gymnasium's ant read once and inserted into two simulations makes the same
/// bodies, joints, actuators and sensors as `load_mjcf`, and the three step to the same
/// bits; a broken file is refused when read, before any simulation is touched.
#[test]
fn an_mjcf_file_read_once_is_inserted_into_two_simulations_that_step_alike() {
    use ars::MjcfFile;
    let ant = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ant.xml");
    let options = MjcfOptions::new().skip_unsupported(true).base_pose(Isometry3::translation(0.0, 0.75, 0.0));
    let file = MjcfFile::read(ant, &options).unwrap();
    assert_eq!(file.name(), "ant");
    assert!(!file.skipped().is_empty(), "the ant's contact parameters are said");
    let floor = || Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let mut sims = [floor(), floor(), floor()];
    let [first, second, loaded] = &mut sims;
    let models = [file.insert(first, &options).unwrap(), file.insert(second, &options).unwrap()];
    let by_load = loaded.load_mjcf(ant, &options).unwrap();
    let names = |m: &ars::MjcfModel| {
        let bodies: Vec<String> = m.bodies.iter().map(|(n, _)| n.clone()).collect();
        let joints: Vec<String> = m.joints.iter().map(|(n, _)| n.clone()).collect();
        let actuators: Vec<String> = m.actuators.iter().map(|a| a.name.clone()).collect();
        (bodies, joints, actuators, m.sensors.len(), m.skipped.clone())
    };
    assert_eq!(names(&models[0]), names(&models[1]));
    assert_eq!(names(&models[0]), names(&by_load));
    // 13 bodies, of which the four `*_leg` bodies have no joint: welded into the torso,
    // as MuJoCo's compiler makes them one rigid body with it.
    assert_eq!(models[0].bodies.len(), 9, "{:?}", names(&models[0]).0);
    assert_eq!(models[0].welded.len(), 4, "{:?}", models[0].welded);
    for sim in &mut sims {
        for actuator in &by_load.actuators {
            sim.scene_mut().set_control(&actuator.name, 0.5).unwrap();
        }
        sim.step_n(500).unwrap();
    }
    let state = |sim: &Simulation, m: &ars::MjcfModel| -> Vec<u64> {
        m.bodies
            .iter()
            .flat_map(|(_, id)| {
                let object = sim.scene().object(*id).unwrap();
                let (p, v) = (object.position().unwrap(), object.body().unwrap().linear_velocity());
                [p.x, p.y, p.z, v.x, v.y, v.z].map(f64::to_bits)
            })
            .collect()
    };
    assert_eq!(state(&sims[0], &models[0]), state(&sims[1], &models[1]));
    assert_eq!(state(&sims[0], &models[0]), state(&sims[2], &by_load));
    let err = MjcfFile::parse("<mujoco><worldbody>", "broken.xml", &MjcfOptions::new()).unwrap_err();
    assert!(matches!(&err, Error::Format { format: "MJCF", file, .. } if file == "broken.xml"), "{err:?}");
}

/// As MuJoCo reads them (checked with MuJoCo 3): an included file's root may be
/// `<mujocoinclude>` (or any name), and a nested include's path is relative to the
/// model's own file, not to the file that includes it. 93 of 356 public models
/// (robot suites' scenes) include files this way.
#[test]
fn mujocoinclude_roots_and_paths_relative_to_the_model_load_as_in_mujoco() {
    let dir = std::env::temp_dir().join(format!("ars-mujocoinclude-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
    write("main.xml", r#"<mujoco model="m"><worldbody><include file="sub/first.xml"/></worldbody></mujoco>"#);
    let ball = |name: &str, x: f64| {
        format!(r#"<body name="{name}" pos="{x} 0 1"><freejoint/><geom type="sphere" size="0.1"/></body>"#)
    };
    write(
        "sub/first.xml",
        &format!(r#"<mujocoinclude>{}<include file="second.xml"/></mujocoinclude>"#, ball("a", 0.0)),
    );
    // second.xml is looked for beside main.xml; a copy beside first.xml must not be read.
    write("second.xml", &format!("<anything>{}</anything>", ball("b_beside_the_model", 1.0)));
    write("sub/second.xml", &format!("<mujocoinclude>{}</mujocoinclude>", ball("b_beside_the_includer", 1.0)));
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf(dir.join("main.xml"), &MjcfOptions::new()).unwrap();
    let names: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["a", "b_beside_the_model"]);
    // The model's own file is still a <mujoco>.
    let err = sim.load_mjcf(dir.join("sub/first.xml"), &MjcfOptions::new()).unwrap_err();
    assert!(err.to_string().contains("the root element must be <mujoco>"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `<option><flag contact="disable">` turns every contact off, as in MuJoCo (dm-control's
/// cartpole and reacher rely on it: their parts overlap); `gravity="disable"` gives the
/// model no gravity; `constraint` (contacts, limits, dry friction, equalities), `damper`
/// and their kin turn those off; a flag at MuJoCo's default is silent; any other flag
/// is read and said unused, not passed over in silence.
#[test]
fn option_flags_disable_contacts_and_gravity_and_others_are_said_unused() {
    let model = |flags: &str| {
        format!(
            r#"<mujoco><option>{flags}</option><worldbody><geom type="plane" size="5 5 0.1"/>
               <body name="box" pos="0 0 0.5"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
               <body name="pair" pos="1 0 0.5"><freejoint/><geom type="sphere" size="0.1"/></body>
               </worldbody><contact><pair geom1="box_geom" geom2="pair_geom"/></contact></mujoco>"#
        )
        .replace(r#"type="box" size"#, r#"name="box_geom" type="box" size"#)
        .replace(r#"type="sphere" size"#, r#"name="pair_geom" type="sphere" size"#)
    };
    let height_after_a_second = |flags: &str| {
        let mut sim = Simulation::new().unwrap();
        let m = sim.load_mjcf_text(&model(flags), "flags.xml", &MjcfOptions::new()).unwrap();
        sim.run_for(1.0).unwrap();
        (sim.scene().object(m.body("box").unwrap()).unwrap().position().unwrap().y, m)
    };
    let (resting, _) = height_after_a_second("");
    assert!((resting - 0.1).abs() < 0.01, "the box rests on the plane: {resting}");
    let (fallen, _) = height_after_a_second(r#"<flag contact="disable"/>"#);
    assert!(fallen < -3.0, "with contacts off the box falls through the plane: {fallen}");
    let (_, weightless) =
        height_after_a_second(r#"<flag gravity="disable" energy="enable" warmstart="enable" sleep="disable"/>"#);
    assert_eq!(weightless.gravity, Some(Vector3::zeros()));
    // A flag at MuJoCo's default (warmstart on, sleep off) changes nothing and is not
    // said; any other that ARS does not apply is.
    let flags: Vec<&String> = weightless.skipped.iter().filter(|l| l.starts_with("<flag>")).collect();
    assert_eq!(flags.len(), 1, "{flags:?}");
    assert!(flags[0].contains(r#"energy="enable" is not used"#), "{flags:?}");
    // `constraint` turns off contacts, limits, dry friction and equalities; `spring` and
    // `damper` a joint's stiffness and damping. A limited, sprung, damped, rubbing hinge:
    let hinge = r#"<mujoco><option><flag FLAGS/></option><worldbody>
        <body name="arm" pos="0 0 1"><joint name="j" axis="0 1 0" range="-10 10" stiffness="5" damping="2" frictionloss="0.1"/>
          <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/></body></worldbody></mujoco>"#;
    let hinge_after = |flags: &str| {
        let mut sim = Simulation::new().unwrap();
        sim.load_mjcf_text(&hinge.replace("FLAGS", flags), "hinge.xml", &MjcfOptions::new()).unwrap();
        let ode = sim.scene().joint("j").unwrap().ode().unwrap();
        // Dry friction is the hinge's own motor at speed 0 with that force limit.
        let (lo, friction) =
            (ode.param(ars::JointParam::LoStop, 0).unwrap(), ode.param(ars::JointParam::MaxForce, 0).unwrap());
        (lo, sim.scene_mut().joint_mut("j").unwrap().damping(), friction)
    };
    let (lo, damping, friction) = hinge_after(r#"warmstart="enable""#);
    assert!((lo + 10f64.to_radians()).abs() < 1e-12 && damping == 2.0 && friction == 0.1, "{lo} {damping} {friction}");
    let (lo, damping, friction) = hinge_after(r#"constraint="disable" damper="disable""#);
    assert!(lo == f64::NEG_INFINITY && damping == 0.0 && friction == 0.0, "{lo} {damping} {friction}");
}

/// MuJoCo's world (x, y, z) in the simulation's frame: (x, z, −y).
fn from_mujoco(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, z, -y)
}

/// A table that weighs nothing (a mass-0 geom) under the world, with a site, a cup of
/// its own mass on it, and a ball falling onto it.
const STATIC_TABLE: &str = r#"
<mujoco model="table">
  <worldbody>
    <body name="table" pos="0 0 0.5">
      <geom name="top" type="box" size="1 1 0.05" mass="0"/>
      <site name="corner" pos="1 1 0.05"/>
      <body name="cup" pos="0.5 0 0.1"><geom type="sphere" size="0.05"/></body>
    </body>
    <body name="ball" pos="0 0 1"><freejoint/><geom type="sphere" size="0.1"/></body>
  </worldbody>
</mujoco>"#;

/// As MuJoCo welds it (checked with MuJoCo 4: body_mass 0, 0.5236, 4.1888, body_weldid
/// of the table and the cup 0): a massless jointless body of the world is no object; its
/// geom is a static one where MuJoCo has it, which a falling ball lands on; the cup on
/// it keeps its own mass, a kinematic body; the masses sum to MuJoCo's.
#[test]
fn a_massless_body_of_the_world_is_welded_to_it_its_geoms_static() {
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(STATIC_TABLE, "table.xml", &MjcfOptions::new()).unwrap();
    let names: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["cup", "ball"]);
    assert_eq!(model.welded.len(), 1);
    let table = &model.welded[0];
    assert_eq!((table.body.as_str(), table.into.as_deref(), table.object), ("table", None, None));
    assert!((table.offset.translation.vector - from_mujoco(0.0, 0.0, 0.5)).norm() < 1e-12);
    assert_eq!(model.body("table"), None);
    // Its geom: a static object at the table's place.
    assert_eq!(model.world_geoms.len(), 1);
    let top = sim.scene().object(model.world_geoms[0]).unwrap();
    assert!(top.body_handle().is_none());
    assert!((top.position().unwrap().coords - from_mujoco(0.0, 0.0, 0.5)).norm() < 1e-12);
    // The cup: its own mass where MuJoCo has it, welded to the world.
    let cup = sim.scene().body(model.body("cup").unwrap()).unwrap();
    let sphere = |r: f64| 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    assert!((cup.mass() - sphere(0.05)).abs() < 1e-12);
    assert!((cup.position().coords - from_mujoco(0.5, 0.0, 0.6)).norm() < 1e-12);
    // Held by nothing: a kinematic body, which no force moves and the step solves for
    // no row of (a fixed joint would add six).
    assert!(sim.scene().joint("cup_weld").is_err());
    let cup_body = sim.scene().object(model.body("cup").unwrap()).unwrap().body_handle().unwrap();
    assert!(sim.scene().world().body(cup_body).unwrap().is_kinematic());
    let total: f64 = model.bodies.iter().map(|(_, id)| sim.scene().body(*id).unwrap().mass()).sum();
    assert!((total - 4.71238898038469).abs() < 1e-12, "MuJoCo's body_mass.sum(): {total}");
    // The ball lands on the table top (z = 0.55) and rests there; the cup stays put.
    sim.run_for(1.5).unwrap();
    let ball = sim.scene().body(model.body("ball").unwrap()).unwrap().position();
    assert!((ball.y - 0.65).abs() < 5e-3 && ball.x.abs() < 1e-6, "{ball}");
    let cup = sim.scene().body(model.body("cup").unwrap()).unwrap().position();
    assert!((cup.coords - from_mujoco(0.5, 0.0, 0.6)).norm() < 1e-3, "{cup}");
}

/// An arm whose hand hangs from a massless mount (a plate of mass 0, a site, turned 90°
/// about Z), on a wrist of its own.
const MOUNTED_HAND: &str = r#"
<mujoco model="mount">
  <option timestep="0.0005"/>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05"/>
      <body name="mount" pos="0.5 0 0" euler="0 0 90">
        <geom name="plate" type="box" size="0.03 0.03 0.01" mass="0"/>
        <site name="tip" pos="0.1 0 0"/>
        <body name="hand" pos="0.1 0 0">
          <joint name="wrist" axis="1 0 0"/>
          <geom type="sphere" size="0.05"/>
        </body>
      </body>
    </body>
  </worldbody>
  <sensor>
    <framepos name="mount_at" objtype="xbody" objname="mount"/>
    <framepos name="tip_at" objtype="site" objname="tip"/>
  </sensor>
</mujoco>"#;

/// A massless mount between two moving bodies is merged into the arm's object: its
/// plate rides on the arm's ODE body, its site and the sensor on its frame are placed
/// through it, and the hand's wrist joins the hand to the arm. The arm swings as
/// MuJoCo's (checked with MuJoCo 4, same step: after 0.3 s the shoulder is at 1.09669
/// rad and the mount at (0.22976, 0, 0.55592)).
#[test]
fn a_massless_mount_between_moving_bodies_rides_on_its_parent() {
    let mut sim = Simulation::builder().time_step(0.0005).build().unwrap();
    let model = sim.load_mjcf_text(MOUNTED_HAND, "mount.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.timestep, Some(0.0005));
    let names: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["arm", "hand"]);
    let arm = model.body("arm").unwrap();
    assert_eq!(model.body("mount"), Some(arm));
    assert_eq!(model.welded[0].into.as_deref(), Some("arm"));
    assert_eq!(sim.scene().joint("wrist").unwrap().objects(), (model.body("hand").unwrap(), Some(arm)));
    assert!(sim.scene().joint("mount_weld").is_err(), "no fixed joint: no body to fix");
    // The arm's object carries the capsule and the plate; its mass is the capsule's.
    let capsule = 1000.0 * std::f64::consts::PI * 0.05f64.powi(2) * (0.5 + 4.0 / 3.0 * 0.05);
    let body = sim.scene().body(arm).unwrap();
    assert!((body.mass() - capsule).abs() < 1e-12, "{}", body.mass());
    assert!((body.mass() - 4.45058959).abs() < 1e-8, "MuJoCo's body_mass of the arm");
    let geoms: Vec<_> = sim.scene().object(arm).unwrap().geoms().collect();
    assert_eq!(geoms.len(), 2);
    let plate = |sim: &Simulation| sim.scene().world().geom(geoms[1]).unwrap().pose();
    assert!((plate(&sim).translation.vector - from_mujoco(0.5, 0.0, 1.0)).norm() < 1e-12);
    // The site: on the arm's object, where MuJoCo's is.
    let tip = model.site("tip").unwrap();
    assert_eq!((tip.body.as_str(), tip.object), ("mount", arm));
    let at = sim.scene().pose(arm).unwrap() * ars::nalgebra::Point3::from(tip.offset.translation.vector);
    assert!((at.coords - from_mujoco(0.5, 0.1, 1.0)).norm() < 1e-12, "{at}");

    sim.run_for(0.3).unwrap();
    let shoulder = sim.scene().joint("shoulder").unwrap().state().unwrap().position;
    assert!((shoulder - 1.09669251).abs() < 2e-3, "{shoulder}");
    let tables = sim.sensor_tables();
    let last = |i: usize| {
        let table = tables[i].1;
        Vector3::from_iterator(table.cells(table.len() - 1).into_iter().map(|v| v.unwrap()))
    };
    let mount = from_mujoco(0.22976314, 0.0, 0.55591791);
    assert!((last(0) - mount).norm() < 2e-3, "{}", last(0));
    // The plate moved with the arm, at the mount's frame; the tip's site 0.1 m off it.
    assert!((plate(&sim).translation.vector - last(0)).norm() < 1e-9);
    assert!((last(1) - (mount + from_mujoco(0.0, 0.1, 0.0))).norm() < 2e-3, "{}", last(1));
}

/// A wheeled base whose free body weighs nothing (an <inertial> of mass 0): its
/// jointless chassis carries the mass, a marker of mass 0 rides along, the wheel turns
/// on a joint of its own.
const MASSLESS_BASE: &str = r#"
<mujoco model="base">
  <worldbody>
    <geom type="plane" size="5 5 0.1"/>
    <body name="base" pos="0 0 0.5">
      <freejoint/>
      <inertial pos="0 0 0" mass="0" diaginertia="0 0 0"/>
      <body name="chassis" pos="0.1 0 0"><geom type="box" size="0.2 0.1 0.05" mass="3"/></body>
      <body name="marker" pos="0 0 0.1">
        <inertial pos="0 0 0" mass="0" diaginertia="1e-3 1e-3 1e-3"/>
        <geom type="sphere" size="0.01" contype="0" conaffinity="0"/>
      </body>
      <body name="wheel" pos="0.1 0.15 0">
        <joint name="axle" axis="0 1 0"/>
        <geom type="cylinder" size="0.05 0.02" mass="0.5" zaxis="0 1 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>"#;

/// A zero-mass <inertial> is a massless body, as MuJoCo reads it (checked with MuJoCo
/// 4: body_mass 0, 0, 3, 0, 0.5, summing to 3.5; chassis and marker welded to the
/// base). A moving body that weighs nothing takes in its jointless children, their
/// masses combined: the base's object weighs the chassis's 3 kg at the chassis's
/// centre; the wheel keeps its own. The base falls and rests on the chassis and wheel.
#[test]
fn a_zero_mass_inertial_is_a_massless_body_and_a_moving_one_takes_in_its_welded_children() {
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(MASSLESS_BASE, "base.xml", &MjcfOptions::new()).unwrap();
    let names: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["base", "wheel"]);
    let welded: Vec<(&str, Option<&str>)> = model.welded.iter().map(|w| (w.body.as_str(), w.into.as_deref())).collect();
    assert_eq!(welded, [("chassis", Some("base")), ("marker", Some("base"))]);
    let base = sim.scene().body(model.body("base").unwrap()).unwrap();
    assert_eq!(base.mass(), 3.0);
    assert!((base.position().coords - from_mujoco(0.1, 0.0, 0.5)).norm() < 1e-12);
    // The box's own inertia about its centre (m/3 (b² + c²), ...), in the object's
    // frame, which is turned as the MJCF body.
    let diagonal = base.inertia().diagonal();
    assert!((diagonal - Vector3::new(0.0125, 0.0425, 0.05)).norm() < 1e-12, "{diagonal}");
    let total: f64 = model.bodies.iter().map(|(_, id)| sim.scene().body(*id).unwrap().mass()).sum();
    assert_eq!(total, 3.5, "MuJoCo's body_mass.sum()");
    assert_eq!(sim.scene().joint("axle").unwrap().objects().1, model.body("base"));
    sim.run_for(1.5).unwrap();
    let at = sim.scene().body(model.body("base").unwrap()).unwrap().position();
    assert!((at.y - 0.05).abs() < 5e-3, "the chassis rests on the floor: {at}");
}

/// MuJoCo refuses a moving body whose mass is in bodies that move on joints of their
/// own, or whose own <inertial> weighs nothing ("mass and inertia of moving bodies must
/// be larger than mjMINVAL", checked with MuJoCo 4); ARS too, naming the body, and
/// leaves nothing behind.
#[test]
fn a_moving_body_that_weighs_nothing_is_refused_as_mujoco_refuses_it() {
    let cases = [
        r#"<body name="b"><joint/><body name="c" pos="1 0 0"><joint/><geom size=".1"/></body></body>"#,
        r#"<body name="b"><joint/><inertial pos="0 0 0" mass="0" diaginertia="0 0 0"/><geom size=".1"/></body>"#,
        r#"<body name="b"><joint type="slide"/><body name="m"><geom size=".1" mass="0"/></body></body>"#,
        r#"<body name="b"><joint/><inertial pos="0 0 0" mass="1e-16" diaginertia="1 1 1"/></body>"#,
    ];
    for body in cases {
        let text = format!("<mujoco><worldbody><geom type='plane' size='1 1 1'/>{body}</worldbody></mujoco>");
        let mut sim = Simulation::new().unwrap();
        let err = sim.load_mjcf_text(&text, "moving.xml", &MjcfOptions::new().skip_unsupported(true)).unwrap_err();
        let message = err.to_string();
        assert!(message.contains("\"b\"") && message.contains("mjMINVAL"), "{message}");
        assert_eq!(sim.scene().objects().count(), 0, "{message}");
    }
    // A negative mass is no MJCF body's.
    let text =
        r#"<mujoco><worldbody><body><inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/></body></worldbody></mujoco>"#;
    let err = Simulation::new().unwrap().load_mjcf_text(text, "negative.xml", &MjcfOptions::new()).unwrap_err();
    assert!(err.to_string().contains("mass -1 must not be negative"), "{err}");
}

/// `<compiler inertiagrouprange>`: only geoms in those groups weigh (Meta-World's
/// scenes keep visual walls in group 0 and weigh groups 4 and 5). Checked with MuJoCo 4:
/// the wall body weighs 0 and is welded to the world, the puck 2 kg.
#[test]
fn only_geoms_in_the_inertia_group_range_weigh() {
    let text = r#"<mujoco><compiler inertiagrouprange="4 5"/><worldbody>
      <body name="wall"><geom type="box" size="1 0.1 0.1"/></body>
      <body name="puck" pos="0 0 1"><freejoint/>
        <geom type="sphere" size="0.1" group="1"/><geom type="box" size="0.1 0.1 0.1" mass="2" group="4"/>
      </body></worldbody></mujoco>"#;
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(text, "groups.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.welded.iter().map(|w| w.body.as_str()).collect::<Vec<_>>(), ["wall"]);
    assert_eq!(sim.scene().body(model.body("puck").unwrap()).unwrap().mass(), 2.0);
    assert_eq!(sim.scene().object(model.body("puck").unwrap()).unwrap().geoms().count(), 2, "both still collide");
}

/// A 3 × 4 height field of `elevation` numbers (MuJoCo's first row at +y), 4 m × 2 m,
/// 0.5 m high, and a crate.
const HFIELD: &str = r#"
<mujoco>
  <asset>
    <hfield name="hill" nrow="3" ncol="4" size="2 1 0.5 0.1" elevation="0 1 2 3  4 5 6 7  8 9 10 20"/>
  </asset>
  <worldbody>
    <geom name="terrain" type="hfield" hfield="hill" pos="0 0 0.2"/>
    <body name="crate" pos="0.1 0.1 1.5"><freejoint/><geom type="box" size="0.05 0.05 0.05"/></body>
  </worldbody>
</mujoco>"#;

/// A height field is static terrain with MuJoCo's heights: the elevations scaled to
/// [0, 1] over their span, times the size's top, the file's first row at +y (the heights
/// at the corners are MuJoCo's, read with its own ray); a crate dropped on it comes to
/// rest on its slope.
#[test]
fn a_height_field_is_terrain_at_mujoco_s_heights() {
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(HFIELD, "hfield.xml", &MjcfOptions::new()).unwrap();
    assert!(model.skipped.is_empty(), "{:#?}", model.skipped);
    // MuJoCo's (x, y) is the simulation's (x, −z); heights are its y.
    let height = |sim: &Simulation, x: f64, y: f64| {
        let ray = ars::world::raycast::Ray { origin: [x, 5.0, -y].into(), direction: Vector3::new(0.0, -1.0, 0.0) };
        let hit = sim.scene().world().cast_ray(ray, 10.0, None).unwrap().expect("the terrain is there");
        hit.position.y
    };
    // Corners: (−2, −1) holds the last row's first number (8 of 0..20: 0.4), (2, −1) the
    // last (20: 1), (−2, 1) the first (0), (2, 1) 3 (0.15); each times 0.5, plus 0.2.
    for (x, y, expected) in [(-2.0, -1.0, 0.4), (2.0, -1.0, 1.0), (-2.0, 1.0, 0.0), (2.0, 1.0, 0.15)] {
        let got = height(&sim, x * 0.9999, y * 0.9999);
        assert!((got - (0.2 + 0.5 * expected)).abs() < 1e-3, "({x}, {y}): {got}");
    }
    sim.run_for(1.0).unwrap();
    let crate_ = model.body("crate").unwrap();
    let at = sim.scene().position(crate_).unwrap();
    // Just beside it (a ray down on it would stop at its top): the slope there is 0.04.
    let ground = height(&sim, at.x + 0.08, -at.z);
    assert!((at.y - 0.05 - ground).abs() < 0.01, "the crate rests on the terrain: {at:?} over {ground}");
    assert!(sim.scene().body(crate_).unwrap().linear_velocity().norm() < 1e-3, "and stays");
}

#[test]
fn a_bad_height_field_is_refused_naming_it() {
    for (bad, said) in [
        (r#"nrow="3" ncol="4" size="2 1 0.5 0.1" elevation="1 2 3""#, "elevation has 3 numbers"),
        (r#"nrow="3" ncol="4" size="2 1 -0.5 0.1""#, "must be three positive numbers"),
        (r#"nrow="1" ncol="4" size="2 1 0.5 0.1""#, "nrow 1 must be a whole number of at least 2"),
        (r#"nrow="100000" ncol="100000" size="2 1 0.5 0.1""#, "more than"),
        (r#"nrow="3" ncol="4" size="2 1 0.5 0.1" elevation="0 1 2 3 4 5 6 7 8 9 10 nan""#, "finite numbers"),
        (r#"file="missing.png" size="2 1 0.5 0.1""#, "cannot open"),
    ] {
        let text =
            HFIELD.replace(r#"nrow="3" ncol="4" size="2 1 0.5 0.1" elevation="0 1 2 3  4 5 6 7  8 9 10 20""#, bad);
        let mut sim = Simulation::new().unwrap();
        let err = sim.load_mjcf_text(&text, "hfield.xml", &MjcfOptions::new()).unwrap_err().to_string();
        assert!(err.contains(said) && err.contains("line"), "{bad}: {err}");
        assert_eq!(sim.scene().objects().count(), 0, "nothing left");
    }
    // On a moving body: refused by name.
    let moving =
        HFIELD.replace(r#"<geom type="box" size="0.05 0.05 0.05"/>"#, r#"<geom type="hfield" hfield="hill"/>"#);
    let err = Simulation::new().unwrap().load_mjcf_text(&moving, "h.xml", &MjcfOptions::new()).unwrap_err();
    assert!(err.to_string().contains("\"crate\": an hfield geom on a body"), "{err}");
}

/// A file's magnetometers read its `<option magnetic>`, MuJoCo's `(0, −0.5, 0)` when it
/// gives none: in the simulation's frame, the field Python's magnetometers read.
#[test]
fn the_magnetic_field_is_the_file_s_or_mujoco_s_default() {
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(HFIELD, "field.xml", &MjcfOptions::new()).unwrap();
    // The turn to Y-up leaves 1e-16 where MuJoCo's y was.
    assert!((model.magnetic - ars::sensors::Magnetometer::MUJOCO_DEFAULT_FIELD).norm() < 1e-15, "{}", model.magnetic);
    let given = HFIELD.replace("<asset>", r#"<option magnetic="0.1 0.2 0.3"/><asset>"#);
    let model = Simulation::new().unwrap().load_mjcf_text(&given, "field.xml", &MjcfOptions::new()).unwrap();
    assert!((model.magnetic - Vector3::new(0.1, 0.3, -0.2)).norm() < 1e-15, "{}", model.magnetic);
}

/// A height field whose file is not a PNG is refused naming the file and the element.
#[test]
fn a_height_field_of_a_file_that_is_no_png_is_refused() {
    let folder = std::env::temp_dir().join(format!("ars-hfield-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("terrain.png"), b"not a picture at all").unwrap();
    std::fs::write(folder.join("empty.png"), b"").unwrap();
    for file in ["terrain.png", "empty.png"] {
        let text = HFIELD.replace(
            r#"nrow="3" ncol="4" size="2 1 0.5 0.1" elevation="0 1 2 3  4 5 6 7  8 9 10 20""#,
            &format!(r#"file="{file}" size="2 1 0.5 0.1""#),
        );
        let path = folder.join("model.xml");
        std::fs::write(&path, text).unwrap();
        let mut sim = Simulation::new().unwrap();
        let err = sim.load_mjcf(&path, &MjcfOptions::new()).unwrap_err().to_string();
        assert!(err.contains(file) && err.contains("not a PNG") && err.contains("<hfield>"), "{err}");
        assert_eq!(sim.scene().objects().count(), 0);
    }
    std::fs::remove_dir_all(&folder).unwrap();
}
