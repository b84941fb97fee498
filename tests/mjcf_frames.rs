//! MJCF `<frame>` and `<replicate>`: what they hold placed and named as MuJoCo places
//! and names it (python/tests/test_mjcf_frames.py holds the same against MuJoCo's
//! compiled model); hostile counts refused with nothing left.

use ars::nalgebra::Vector3;
use ars::{MjcfOptions, Simulation};

fn load(text: &str) -> ars::Result<(Simulation, ars::MjcfModel)> {
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf_text(text, "frames.xml", &MjcfOptions::new())?;
    Ok((sim, model))
}

#[test]
fn a_frame_places_its_bodies_and_an_included_leg_as_its_parent_s_child() {
    // MyoSuite's legs: a <frame> in a body around an <include>.
    let dir = std::env::temp_dir().join(format!("ars-mjcf-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("leg.xml"),
        r#"<mujocoinclude><body name="thigh" pos="0 0 -0.1"><joint name="hip" axis="0 1 0"/>
             <geom type="sphere" size="0.05"/></body></mujocoinclude>"#,
    )
    .unwrap();
    std::fs::write(
        dir.join("model.xml"),
        r#"<mujoco><compiler angle="radian"/><worldbody>
             <body name="pelvis" pos="0 0 1"><freejoint/><geom type="sphere" size="0.1"/>
               <frame pos="0.2 0 0" euler="0 0 1.5707963267948966"><include file="leg.xml"/></frame>
             </body></worldbody></mujoco>"#,
    )
    .unwrap();
    let mut sim = Simulation::builder().build().unwrap();
    let model = sim.load_mjcf(dir.join("model.xml"), &MjcfOptions::new()).unwrap();
    let thigh = sim.scene().body(model.body("thigh").unwrap()).unwrap().position();
    // MuJoCo (0.2, 0, 0.9) is ARS's (0.2, 0.9, 0).
    assert!((thigh.coords - Vector3::new(0.2, 0.9, 0.0)).norm() < 1e-12, "{thigh}");
    // The hinge's y axis, turned 90° about z by the frame, is along −x.
    let hip = sim.scene().joint("hip").unwrap().ode().unwrap().axis().unwrap();
    assert!((hip - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12, "{hip}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn replicated_names_take_their_copy_s_suffix_and_their_actuators_repeat() {
    let (_, model) = load(
        r#"<mujoco><worldbody>
             <body name="hub"><joint name="spin"/><geom size="0.1"/></body>
             <replicate count="11" offset="1 0 0" sep="-">
               <body name="wheel" pos="0 0 1"><joint name="axle"/><geom size="0.1"/></body>
             </replicate></worldbody>
           <actuator><motor name="drive" joint="axle"/><motor name="turn" joint="spin"/></actuator></mujoco>"#,
    )
    .unwrap();
    let bodies: Vec<&str> = model.bodies.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(bodies.len(), 12);
    assert_eq!(&bodies[..3], ["hub", "wheel-00", "wheel-01"]);
    assert_eq!(bodies[11], "wheel-10");
    // MuJoCo's order: what names nothing replicated first, then copy by copy.
    let actuators: Vec<(&str, &str)> = model.actuators.iter().map(|a| (a.name.as_str(), a.joint.as_str())).collect();
    assert_eq!(actuators[..3], [("turn", "spin"), ("drive-00", "axle-00"), ("drive-01", "axle-01")]);
    assert_eq!(actuators.len(), 12);
}

#[test]
fn replicate_counts_past_the_limit_or_not_whole_are_refused_with_nothing_left() {
    for (body, text) in [
        (r#"<replicate count="400"><replicate count="400"><geom size=".1"/></replicate></replicate>"#, "more than"),
        (r#"<replicate count="9999999999"><replicate count="9999999999"/></replicate>"#, "more than"),
        (r#"<replicate count="two"><geom size=".1"/></replicate>"#, "not a whole number"),
        (r#"<frame pos="0 0 inf"><body><freejoint/><geom size=".1"/></body></frame>"#, "inf"),
        // A few lines naming a body replicated 40,000 times: 120,000 exclusions.
        (
            r#"<replicate count="40000"><body name="b"><geom size=".1"/></body></replicate></worldbody><contact>
               <exclude body1="b" body2="kept"/><exclude body1="kept" body2="b"/><exclude body1="b" body2="kept"/>
               </contact><worldbody>"#,
            "more than 100000",
        ),
        // MuJoCo 4.0: "joint cannot be a direct child of replicate", in a frame of one too.
        (r#"<body><geom size=".1"/><replicate count="2"><joint axis="0 0 1"/></replicate></body>"#, "direct child"),
        (
            r#"<body><geom size=".1"/><replicate count="2"><frame><freejoint/></frame></replicate></body>"#,
            "direct child",
        ),
    ] {
        let mut sim = Simulation::builder().build().unwrap();
        let file = format!(
            "<mujoco><worldbody><body name='kept'><freejoint/><geom size='.1'/></body>{body}</worldbody></mujoco>"
        );
        let error = sim.load_mjcf_text(&file, "bad.xml", &MjcfOptions::new()).unwrap_err().to_string();
        assert!(error.contains(text) && error.contains("line 1"), "{body}: {error}");
        assert_eq!(sim.scene().objects().count(), 0, "{body}");
    }
    // A count of 0 (or less: MuJoCo's too) makes nothing.
    let (_, model) = load(r#"<mujoco><worldbody><replicate count="-1"><body><freejoint/><geom size=".1"/></body></replicate></worldbody></mujoco>"#).unwrap();
    assert!(model.bodies.is_empty());
}

#[test]
fn exclusions_pairs_and_equalities_naming_a_replicated_element_repeat_per_copy() {
    // MuJoCo 4.0 compiles this with two exclusions (base with leg0, leg1), two pairs
    // (foot0, foot1 with the ground) and two equalities (knee0 follows hip0, knee1
    // hip1): each is repeated for every copy of what it names.
    let (mut sim, _) = load(
        r#"<mujoco><worldbody><geom name="ground" type="plane" size="1 1 .1"/>
        <body name="base" pos="0 0 1"><geom size=".1"/>
          <replicate count="2" offset=".3 0 0">
            <body name="leg" pos="0 0 -.3"><joint name="hip" axis="0 1 0"/><geom name="foot" pos=".1 0 0" size=".05"/>
              <body name="shin" pos="0 0 -.2"><joint name="knee" axis="0 1 0"/><geom pos=".1 0 0" size=".05"/></body>
            </body>
          </replicate>
        </body></worldbody>
        <equality><joint joint1="knee" joint2="hip"/></equality>
        <contact><exclude body1="base" body2="leg"/><pair geom1="foot" geom2="ground" friction=".5 .5 .005 .0001 .0001"/></contact>
        </mujoco>"#,
    )
    .unwrap();
    // Each knee follows its own copy's hip (MuJoCo: 0.89 rad for all four at 0.3 s).
    sim.run_for(0.3).unwrap();
    let angle = |name: &str| sim.scene().joint(name).unwrap().state().unwrap().position;
    for (hip, knee) in [("hip0", "knee0"), ("hip1", "knee1")] {
        assert!(angle(hip) > 0.3, "{hip} swings: {}", angle(hip));
        assert!((angle(knee) - angle(hip)).abs() < 0.05, "{knee} follows {hip}: {} and {}", angle(knee), angle(hip));
    }
    let scene = sim.scene();
    let name = |id| scene.object(id).map(|o| o.name().to_string()).unwrap();
    let excluded: Vec<(String, String)> =
        scene.excluded_contacts().into_iter().map(|(a, b)| (name(a), name(b))).collect();
    assert!(excluded.contains(&("base".into(), "leg0".into())), "{excluded:?}");
    assert!(excluded.contains(&("base".into(), "leg1".into())), "{excluded:?}");
    assert_eq!(scene.geom_pair_contacts().len(), 2, "one pair per foot");
}
