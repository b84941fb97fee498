//! A MuJoCo file behaves as its author meant: actuators in the file's order (MuJoCo's
//! `data.ctrl`), kept through snapshots and scene files, and the file's time step when
//! it is opened on its own.

use ars::{MjcfOptions, Simulation, Snapshot};

/// Three hinges made in the order a, b, c; their actuators listed c, a, b.
const CROSSED: &str = r#"
<mujoco model="crossed">
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="a"><joint name="ja" axis="0 0 1"/><geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b" pos="0 1 0"><joint name="jb" axis="0 0 1"/><geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="c" pos="0 2 0"><joint name="jc" axis="0 0 1"/><geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
  </worldbody>
  <actuator>
    <motor name="turn_c" joint="jc" gear="1" ctrlrange="-3 3"/>
    <motor name="turn_a" joint="ja" gear="1" ctrlrange="-3 3"/>
    <motor name="turn_b" joint="jb" gear="1" ctrlrange="-1 1"/>
  </actuator>
</mujoco>"#;

fn crossed() -> Simulation {
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    sim.load_mjcf_text(CROSSED, "crossed.xml", &MjcfOptions::new()).unwrap();
    sim
}

fn actuator_names(sim: &Simulation) -> Vec<String> {
    sim.scene().actuators().map(|(n, _)| n.to_string()).collect()
}

#[test]
fn actuators_are_listed_in_the_files_order_and_set_as_one_vector() {
    let mut sim = crossed();
    assert_eq!(actuator_names(&sim), ["turn_c", "turn_a", "turn_b"], "the file's order, not the joints'");
    // One control vector in that order, clamped to each range as set_control does.
    sim.scene_mut().set_controls(&[2.0, -1.0, 5.0]).unwrap();
    assert_eq!(sim.scene().controls(), [2.0, -1.0, 1.0]);
    assert_eq!(sim.scene().control("turn_c").unwrap(), 2.0);
    assert_eq!(sim.scene().control("turn_a").unwrap(), -1.0);
    // Each control drives its own joint: c turns positive, a negative, b positive.
    sim.run_for(0.1).unwrap();
    let rate = |sim: &Simulation, j: &str| sim.scene().joint(j).unwrap().state().unwrap().rate;
    assert!(rate(&sim, "jc") > 0.0 && rate(&sim, "ja") < 0.0 && rate(&sim, "jb") > 0.0);

    // A vector of the wrong length or with a NaN is refused whole.
    let before = sim.scene().controls();
    let wrong = sim.scene_mut().set_controls(&[1.0, 1.0]).unwrap_err().to_string();
    assert!(wrong.contains("2 values for 3 actuators"), "{wrong}");
    let nan = sim.scene_mut().set_controls(&[0.5, f64::NAN, 0.5]).unwrap_err().to_string();
    assert!(nan.contains("control 1"), "{nan}");
    assert_eq!(sim.scene().controls(), before, "nothing changed");
}

#[test]
fn the_actuators_order_survives_snapshots_and_scene_files() {
    let mut sim = crossed();
    sim.scene_mut().set_controls(&[0.5, 0.25, -0.75]).unwrap();
    sim.step().unwrap();
    let snapshot = Snapshot::from_bytes(&sim.snapshot().unwrap().to_bytes()).unwrap();
    let rebuilt = Simulation::from_snapshot(&snapshot).unwrap();
    assert_eq!(actuator_names(&rebuilt), ["turn_c", "turn_a", "turn_b"]);
    assert_eq!(rebuilt.scene().controls(), [0.5, 0.25, -0.75]);
    let loaded = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    assert_eq!(actuator_names(&loaded), ["turn_c", "turn_a", "turn_b"]);
    assert_eq!(loaded.scene().controls(), [0.5, 0.25, -0.75]);
}

#[test]
fn a_model_opened_alone_steps_at_its_own_time_step() {
    let ant = Simulation::open(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ant.xml")).unwrap().simulation;
    // ant.xml says timestep="0.01": frames of two steps, 20 ms as ARS's.
    assert_eq!((ant.scene().time_step(), ant.scene().steps_per_frame()), (0.01, 2));

    // A model that gives no time step steps at MuJoCo's default.
    let dir = std::env::temp_dir().join(format!("ars-mjcf-as-meant-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("crossed.xml");
    std::fs::write(&path, CROSSED).unwrap();
    let opened = Simulation::open(&path).unwrap().simulation;
    assert_eq!(opened.scene().time_step(), ars::formats::mjcf::MUJOCO_TIMESTEP);
    assert_eq!((opened.scene().time_step(), opened.scene().steps_per_frame()), (0.002, 10));

    // MuJoCo compiles any time step; one ARS cannot step at is the file's error, naming
    // the file and the element.
    for bad in ["0", "-1", "1e9"] {
        let path = dir.join(format!("step_{bad}.xml"));
        std::fs::write(
            &path,
            CROSSED.replace(r#"<option gravity="0 0 0"/>"#, &format!(r#"<option timestep="{bad}"/>"#)),
        )
        .unwrap();
        let e = Simulation::open(&path).unwrap_err().to_string();
        assert!(e.contains(&format!("step_{bad}.xml")) && e.contains("<option timestep>"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A site of size 0 is a point, as MuJoCo takes it: the model loads and a frame sensor
/// on the site reads where it is; a negative size is still refused.
#[test]
fn a_site_of_size_zero_is_a_point() {
    let text = CROSSED
        .replace(
            r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b""#,
            r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/><site name="tip" pos="0.5 0 0" size="0"/></body>
    <body name="b""#,
        )
        .replace("</mujoco>", r#"<sensor><framepos name="tip_at" objtype="site" objname="tip"/></sensor></mujoco>"#);
    assert!(text.contains(r#"size="0"/>"#), "the site is in the text");
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(&text, "point.xml", &MjcfOptions::new()).unwrap();
    assert_eq!(model.sensors.len(), 1);
    sim.step().unwrap();
    let tables = sim.sensor_tables();
    let row: Vec<f64> = tables[0].1.cells(0).into_iter().map(|v| v.unwrap()).collect();
    // Z up becomes Y up: the tip at (0.5, 0, 0) stays at x = 0.5 on the still arm.
    assert!((row[0] - 0.5).abs() < 1e-9 && row[1].abs() < 1e-9 && row[2].abs() < 1e-9, "{row:?}");

    let negative = text.replace(r#"size="0"/>"#, r#"size="-0.1"/>"#);
    let e = Simulation::new().unwrap().load_mjcf_text(&negative, "negative.xml", &MjcfOptions::new()).unwrap_err();
    assert!(e.to_string().contains("size -0.1 must be 0 or more"), "{e}");
}

/// A jointless body given a mass and no inertia (a point mass, `diaginertia="0 0 0"`, as
/// robot files write small parts) loads as MuJoCo loads it. Under a moving body it is
/// part of that body's rigid body: its mass added at its place, nothing to balance.
/// Of the world, it is an ODE body of its own fixed there, which needs an inertia: a
/// solid sphere of its mass at water's density, said in `skipped`; its mass is the
/// file's.
#[test]
fn a_welded_point_mass_loads_with_an_inertia_said_in_skipped() {
    let text = CROSSED.replace(
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b""#,
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/>
      <body name="knob" pos="0.5 0 0"><inertial pos="0 0 0" mass="0.2" diaginertia="0 0 0"/></body></body>
    <body name="weight" pos="0 -1 0"><inertial pos="0 0 0" mass="0.3" diaginertia="0 0 0"/></body>
    <body name="b""#,
    );
    assert!(text.contains("knob") && text.contains("weight"), "both are in the text");
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(&text, "knob.xml", &MjcfOptions::new()).unwrap();
    let balanced =
        |name: &str| model.skipped.iter().filter(|s| s.starts_with(&format!("{name:?}: inertia balanced"))).count();
    assert_eq!((balanced("knob"), balanced("weight")), (0, 1), "{:#?}", model.skipped);
    // The knob is the arm's: one rigid body of both masses.
    assert_eq!(model.body("knob"), model.body("a"));
    let a = sim.scene().body(model.body("a").unwrap()).unwrap().mass();
    // Its geom has no type: MuJoCo's default, a sphere (of radius 0.05, at water's density).
    let sphere = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.05f64.powi(3);
    assert!((a - sphere - 0.2).abs() < 1e-12, "{a}");
    let weight = sim.scene().object(model.body("weight").unwrap()).unwrap().body_handle().unwrap();
    assert_eq!(sim.scene().world().body(weight).unwrap().mass(), 0.3);
    sim.scene_mut().set_controls(&[0.0, 1.0, 0.0]).unwrap();
    sim.run_for(0.2).unwrap();
}

/// A joint's `damping` is integrated as MuJoCo integrates it, implicitly: over one step
/// of `h`, a body of inertia `I` about a fixed hinge turning at `ω` turns at
/// `ω · I / (I + h·c)` after it (`(I + h·c)·ω′ = I·ω`), however large `h·c / I`. Here it
/// is 100 (a wrist of robot files: damping 10, a link of grams): ARS's explicit viscous
/// friction would turn the body back at 99 times its speed each step. A ball joint's
/// and a free joint's damping slow every direction alike.
#[test]
fn joint_damping_is_implicit_and_stable_at_any_coefficient() {
    // A rod along x (capsule, r = 0.01, length 0.1) turning about z at the origin.
    let model_text = |joint: &str| {
        format!(
            r#"<mujoco><option timestep="0.001" gravity="0 0 0"/><worldbody>
                 <body name="rod">{joint}<inertial pos="0 0 0" mass="0.1" diaginertia="1e-4 1e-4 1e-4"/>
                 <geom type="sphere" size="0.01" contype="0" conaffinity="0"/></body>
               </worldbody></mujoco>"#
        )
    };
    let (inertia, damping, h) = (1e-4, 10.0, 0.001);
    let decay = inertia / (inertia + h * damping);
    for joint in [
        r#"<joint name="j" type="hinge" axis="0 0 1" damping="10"/>"#,
        r#"<joint name="j" type="ball" damping="10"/>"#,
        r#"<joint name="j" type="free" damping="10"/>"#,
    ] {
        let text = model_text(joint);
        let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).time_step(h).build().unwrap();
        let model = sim.load_mjcf_text(&text, "rod.xml", &MjcfOptions::new()).unwrap();
        let rod = sim.scene().object(model.body("rod").unwrap()).unwrap().body_handle().unwrap();
        let spin = ars::nalgebra::Vector3::new(0.0, 2.0, 0.0); // about MuJoCo's z: the simulation's y
        sim.scene_mut().world_mut().body_mut(rod).unwrap().set_angular_velocity(spin).unwrap();
        // A free joint's damping acts on its linear and its angular velocity: two motors;
        // a hinge's is its own (the motor that would hold its armature).
        let motors = if joint.contains("free") { 2 } else { usize::from(joint.contains("ball")) };
        assert_eq!(model.joint_motors.len(), motors, "{joint}");
        // ODE's joints: the hinge and its motor, the ball and its motor, the free
        // body's two motors.
        assert_eq!(sim.scene().world().joint_count(), 2, "{joint}");
        for n in 1..=20 {
            sim.step_n(1).unwrap();
            let w = sim.scene().world().body(rod).unwrap().angular_velocity();
            let expected = spin * decay.powi(n);
            assert!((w - expected).norm() <= 1e-9 * spin.norm(), "{joint}, step {n}: {w} against {expected}");
        }
    }
}

/// MuJoCo's legacy binary meshes (`.msh`: dm_control's test assets, robosuite's
/// objects) load as the other mesh files: a cube of 0.1 m written as one weighs its
/// volume at the geom's density.
#[test]
fn a_msh_mesh_loads_with_its_volume_s_mass() {
    let dir = std::env::temp_dir().join(format!("ars-msh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let corners: Vec<f32> =
        (0..8).flat_map(|i| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| 0.1 * b as f32 - 0.05)).collect();
    // Twelve triangles wound outwards (x-, x+, y-, y+, z-, z+ faces).
    let faces: [i32; 36] =
        [0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6];
    let mut bytes: Vec<u8> = [8i32, 0, 0, 12].iter().flat_map(|c| c.to_le_bytes()).collect();
    bytes.extend(corners.iter().flat_map(|f| f.to_le_bytes()));
    bytes.extend(faces.iter().flat_map(|f| f.to_le_bytes()));
    std::fs::write(dir.join("cube.msh"), bytes).unwrap();
    let text = r#"<mujoco><asset><mesh name="cube" file="cube.msh"/></asset><worldbody>
        <body name="box" pos="0 0 1"><freejoint/><geom type="mesh" mesh="cube" density="1000"/></body>
      </worldbody></mujoco>"#;
    std::fs::write(dir.join("cube.xml"), text).unwrap();
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf(dir.join("cube.xml"), &MjcfOptions::new()).unwrap();
    let mass = sim.scene().body(model.body("box").unwrap()).unwrap().mass();
    assert!((mass - 1.0).abs() < 1e-6, "{mass}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A site placed by `fromto` (dm_control's quadruped places its rangefinders so) is
/// centred between its two points with its z axis from the first to the second, as a
/// geom is: a rangefinder on it looks that way. And a body of the file named as ARS
/// names an unnamed world geom (`box`) keeps its name: the world's geoms are made after
/// the bodies (Metaworld's box).
#[test]
fn a_site_placed_by_fromto_looks_along_it_and_a_body_keeps_its_name() {
    let text = r#"<mujoco><worldbody>
        <geom type="box" size="1 1 0.1" pos="0 0 -0.1"/>
        <body name="box" pos="0 0 1"><freejoint/><geom type="sphere" size="0.1"/>
          <site name="eye" type="capsule" size="0.005" fromto="0 0 0 0 0 -0.2"/></body>
      </worldbody>
      <sensor><rangefinder name="range" site="eye"/></sensor></mujoco>"#;
    let mut sim = Simulation::new().unwrap();
    let model = sim.load_mjcf_text(text, "eye.xml", &MjcfOptions::new()).unwrap();
    let body = model.body("box").unwrap();
    assert_eq!(sim.scene().object(body).unwrap().name(), "box");
    let eye = model.site("eye").unwrap();
    // In the body's frame (MuJoCo's axes): half-way down, its z axis pointing down.
    assert!((eye.offset.translation.vector - ars::nalgebra::Vector3::new(0.0, 0.0, -0.1)).norm() < 1e-12);
    let z = eye.offset.rotation * ars::nalgebra::Vector3::z();
    assert!((z - ars::nalgebra::Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12, "{z}");
    let ars::sensors::TouchZone::Capsule { half_length, .. } = eye.zone else { panic!("{:?}", eye.zone) };
    assert!((half_length - 0.1).abs() < 1e-12);
    assert_eq!(model.sensors.len(), 1);
}

/// A geom's `friction`, `condim`, `solref`, `solimp`, `priority` and `solmix` are its
/// contacts' ([`ars::GeomContact`]): read with MuJoCo's defaults where not given, kept by
/// scene files and snapshots, and they decide how the geoms touch: a puck given
/// friction 0 glides on where one of friction 1 stops.
#[test]
fn geom_contact_parameters_are_read_kept_and_used() {
    let text = r#"<mujoco><option timestep="0.002"/><worldbody>
        <geom name="ground" type="plane" size="5 5 .1" friction="0.5"/>
        <body name="slick" pos="0 0 0.05"><freejoint/>
          <geom type="box" size=".05 .05 .05" friction="0" condim="3" priority="1"/></body>
        <body name="rough" pos="0 1 0.05"><freejoint/>
          <geom type="box" size=".05 .05 .05" friction="1 0.01" condim="4" solref="0.01 1" solimp="0.8 0.9 0.002" solmix="2"/></body>
      </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::new(0.0, -9.81, 0.0)).build().unwrap();
    let model = sim.load_mjcf_text(text, "pucks.xml", &MjcfOptions::new()).unwrap();
    let (slick, rough) = (model.body("slick").unwrap(), model.body("rough").unwrap());
    let rough_contact = sim.scene().geom_contact(rough, 0).unwrap().unwrap();
    assert_eq!(rough_contact.friction, [1.0, 0.01, 0.0001]);
    assert_eq!((rough_contact.condim, rough_contact.solref, rough_contact.solmix), (4, [0.01, 1.0], 2.0));
    assert_eq!(rough_contact.solimp, [0.8, 0.9, 0.002, 0.5, 2.0]);
    assert_eq!(sim.scene().geom_contact(slick, 0).unwrap().unwrap().priority, 1);
    assert_eq!(sim.scene().geom_contacts().len(), 3, "the ground's too");
    // Kept by a scene file and by a snapshot.
    let copy = ars::formats::scene_file::SceneFile::parse(&sim.save_scene().unwrap(), "pucks.json").unwrap();
    assert_eq!(copy.build().unwrap().scene().geom_contacts().len(), 3);
    let snapshot = sim.snapshot().unwrap();
    // Both pushed along x at 2 m/s: the slick one glides, the rough one stops.
    for id in [slick, rough] {
        let body = sim.scene().object(id).unwrap().body_handle().unwrap();
        sim.scene_mut().world_mut().body_mut(body).unwrap().set_linear_velocity([2.0, 0.0, 0.0].into()).unwrap();
    }
    sim.run_for(1.0).unwrap();
    let x = |sim: &Simulation, id| sim.scene().object(id).unwrap().position().unwrap().x;
    assert!(x(&sim, slick) > 1.9, "no friction: {}", x(&sim, slick));
    // Coulomb's μ = 1 (the larger of the two): stopped after v² / (2·μ·g) = 0.2 m.
    assert!((x(&sim, rough) - 0.204).abs() < 0.03, "μ = 1: {}", x(&sim, rough));
    sim.restore(&snapshot).unwrap();
    assert_eq!(sim.scene().geom_contacts().len(), 3);
}

/// A ball joint's `frictionloss` (MuJoCo's dry friction on every axis) holds a pendulum
/// whose weight turns it with less torque, and lets a heavier one swing: a motor at speed
/// 0 with that torque limit on each of three axes beside the joint.
#[test]
fn a_ball_joint_s_frictionloss_holds_below_its_torque() {
    // A 1 kg ball 0.5 m out along x from a ball joint: 4.905 N·m of weight about it.
    for (frictionloss, holds) in [(6.0, true), (3.0, false)] {
        let text = format!(
            r#"<mujoco><option timestep="0.001"/><worldbody><body name="bob">
                 <joint type="ball" frictionloss="{frictionloss}"/>
                 <geom type="sphere" size="0.05" pos="0.5 0 0" mass="1" contype="0" conaffinity="0"/>
               </body></worldbody></mujoco>"#
        );
        let mut sim = Simulation::builder().time_step(0.001).build().unwrap();
        let model = sim.load_mjcf_text(&text, "bob.xml", &MjcfOptions::new()).unwrap();
        assert!(model.skipped.is_empty(), "{:?}", model.skipped);
        assert_eq!(model.joint_motors.len(), 1);
        let bob = model.body("bob").unwrap();
        let start = sim.scene().position(bob).unwrap();
        sim.run_for(0.5).unwrap();
        let fell = start.y - sim.scene().position(bob).unwrap().y;
        if holds {
            assert!(fell.abs() < 1e-3, "held: {fell}");
        } else {
            assert!(fell > 0.1, "swings down: {fell}");
        }
    }
}

/// A joint's stops are as soft as its `solreflimit` says: a hinge made 2° outside its
/// range (Gymnasium's humanoid's knees) is eased back at MuJoCo's rate, `h·k / (h·k + b)`
/// of the error per step (0.073 at the defaults and h = 3 ms), not thrown back at ODE's
/// world ERP (0.2: 2.3 rad/s in one step).
#[test]
fn a_joint_outside_its_range_is_eased_back_as_solreflimit_says() {
    let file = |solref: &str| {
        format!(
            r#"<mujoco><option timestep="0.003" gravity="0 0 0"/><worldbody>
  <body name="shin"><joint name="knee" axis="0 1 0" range="-160 -2" {solref}/>
    <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.04"/></body>
</worldbody></mujoco>"#
        )
    };
    let first_rate = |solref: &str| {
        let mut sim = Simulation::builder().time_step(0.003).gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
        sim.load_mjcf_text(&file(solref), "knee.xml", &MjcfOptions::new()).unwrap();
        sim.step().unwrap();
        sim.scene().joint("knee").unwrap().state().unwrap().rate
    };
    let error = 2f64.to_radians();
    let (h, dmax) = (0.003, 0.95);
    let erp = |tc: f64| {
        let (k, b) = (1.0 / (dmax * dmax * tc * tc), 2.0 / (dmax * tc));
        h * k / (h * k + b)
    };
    for (solref, tc) in [("", 0.02), (r#"solreflimit="0.005 1""#, 0.005)] {
        let rate = first_rate(solref);
        let wanted = -erp(tc) * error / h;
        assert!((rate - wanted).abs() < 1e-3 * wanted.abs(), "{solref}: {rate} rad/s, wanted {wanted}");
    }
    assert!((erp(0.02) - 0.073).abs() < 5e-4, "{}", erp(0.02));
}

/// A hinge's `armature` is the joint's own inertia, as MuJoCo's: a torque `τ` on a
/// body of inertia `I` about the hinge turns it at `τ·t / (I + armature)`, and the
/// body keeps MuJoCo's inertia. Below a moving joint, the armature is felt by the
/// joint's motion only: turning the lower hinge does not turn the upper one, where an
/// armature added to the lower body's inertia would spin the light upper body against
/// it (Gymnasium's ant, whose legs of grams carry an armature of 1).
#[test]
fn a_hinge_s_armature_is_the_joint_s_own_inertia() {
    let text = r#"<mujoco><option timestep="0.002" gravity="0 0 0"/><worldbody>
  <body name="upper"><joint name="shoulder" axis="0 0 1"/>
    <inertial pos="0 0 0" mass="0.05" diaginertia="1e-4 1e-4 1e-4"/>
    <body name="lower" pos="0.2 0 0"><joint name="elbow" axis="0 0 1" armature="0.5"/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.02"/></body>
  </body></worldbody>
  <actuator><motor joint="elbow" gear="1"/></actuator></mujoco>"#;
    let mut sim = Simulation::builder().time_step(0.002).gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(text, "arm.xml", &MjcfOptions::new()).unwrap();
    assert!(model.armature.is_empty(), "no inertia added to a body: {:?}", model.armature);
    assert_eq!(sim.scene_mut().joint_mut("elbow").unwrap().armature(), 0.5);
    let lower = sim.scene().body(model.body("lower").unwrap()).unwrap().inertia();
    assert!((lower[(2, 2)] - 0.02).abs() < 1e-12 || (lower[(1, 1)] - 0.02).abs() < 1e-12, "MuJoCo's inertia: {lower}");
    sim.scene_mut().set_controls(&[0.26]).unwrap();
    sim.run_for(0.5).unwrap();
    let rate = |j: &str| sim.scene().joint(j).unwrap().state().unwrap().rate;
    let (elbow, shoulder) = (rate("elbow"), rate("shoulder"));
    // The elbow's torque reacts on the light upper arm through the shoulder, which turns
    // freely. MuJoCo 4.0 on the same file, after 0.5 s: elbow 0.25324 rad/s, shoulder
    // −0.08427 rad/s (without the armature: 9.74 and −3.24). Both integrate the armature
    // implicitly at first order, and here they agree to 7 digits (ARS: 0.2532413,
    // −0.0842733); 1e-4 leaves room for rounding in ODE's body-coordinate solve.
    assert!((elbow - 0.25324128).abs() < 1e-4 * 0.25324128, "elbow {elbow}");
    assert!((shoulder + 0.08427330).abs() < 1e-4 * 0.08427330, "shoulder {shoulder}");
    // Saved mid-run and opened again, the armature's motor is made again with its
    // joint: the run goes on to the bit.
    let path = std::env::temp_dir().join(format!("ars-armature-{}.json", std::process::id()));
    sim.save_scene_to(&path).unwrap();
    let mut copy = Simulation::load_scene_from(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    sim.run_for(0.2).unwrap();
    copy.run_for(0.2).unwrap();
    let state = |s: &Simulation| s.scene().joint("elbow").unwrap().state().unwrap();
    assert_eq!(state(&sim), state(&copy));
}

/// A hinge's `damping` and `armature` are held by one motor beside it (one LCP row, not
/// two) and act as MuJoCo's implicit Euler makes them act: under a torque `τ`, each step
/// `(I + A)·(v′ − v) = h·(τ − c·v′)`. The rate follows that recursion to 1e-9; a saved
/// scene keeps both, and its run goes on to the bit.
#[test]
fn a_hinge_s_damping_and_armature_are_one_implicit_motor() {
    let text = r#"<mujoco><option gravity="0 0 0"/><worldbody>
  <body name="wheel"><joint name="axle" axis="0 0 1" armature="0.5" damping="2"/>
    <inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.02"/></body></worldbody>
  <actuator><motor joint="axle" gear="1"/></actuator></mujoco>"#;
    let h = 0.002;
    let mut sim = Simulation::builder().time_step(h).gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    sim.load_mjcf_text(text, "wheel.xml", &MjcfOptions::new()).unwrap();
    // The hinge and one motor beside it.
    assert_eq!(sim.scene().world().joint_count(), 2);
    let axle = sim.scene_mut().joint_mut("axle").unwrap();
    assert_eq!((axle.armature(), axle.damping()), (0.5, 2.0));
    let (inertia, armature, damping, torque) = (0.02, 0.5, 2.0, 0.3);
    sim.scene_mut().set_controls(&[torque]).unwrap();
    let mut expected = 0.0;
    for _ in 0..250 {
        sim.step().unwrap();
        expected = ((inertia + armature) * expected + h * torque) / (inertia + armature + h * damping);
    }
    let rate = sim.scene().joint("axle").unwrap().state().unwrap().rate;
    assert!((rate - expected).abs() < 1e-9 * expected, "{rate} rad/s, wanted {expected}");
    // Half-way to the terminal rate τ / c: damping and armature both felt.
    assert!(expected > 0.2 * torque / damping && expected < 0.9 * torque / damping, "{expected}");
    let path = std::env::temp_dir().join(format!("ars-damping-{}.json", std::process::id()));
    sim.save_scene_to(&path).unwrap();
    let mut copy = Simulation::load_scene_from(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(copy.scene_mut().joint_mut("axle").unwrap().damping(), 2.0);
    sim.run_for(0.2).unwrap();
    copy.run_for(0.2).unwrap();
    let state = |s: &Simulation| s.scene().joint("axle").unwrap().state().unwrap();
    assert_eq!(state(&sim), state(&copy));
    // Either can go on its own: damping 0 leaves the armature's motor, both 0 none.
    let mut axle = sim.scene_mut().joint_mut("axle").unwrap();
    axle.set_damping(0.0).unwrap();
    assert_eq!((axle.armature(), axle.damping()), (0.5, 0.0));
    axle.set_armature(0.0).unwrap();
    assert!(axle.set_damping(f64::NAN).is_err() && axle.set_damping(-1.0).is_err());
    assert_eq!(sim.scene().world().joint_count(), 1);
}

/// Two copies of one model share a simulation with `MjcfOptions::prefix` (as MuJoCo's
/// `attach`): every name the file gives, and those ARS makes of them (a jointless
/// body's weld), carry the prefix, and each copy's actuators drive its own joints.
#[test]
fn two_copies_of_a_model_share_a_simulation_under_prefixes() {
    let text = CROSSED.replace(
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b""#,
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="post" pos="0 -1 0"><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
    <body name="b""#,
    );
    assert!(text.contains("post"));
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    sim.load_mjcf_text(&text, "crossed.xml", &MjcfOptions::new()).unwrap();
    // A second copy without a prefix: its names are taken.
    let clash = sim.load_mjcf_text(&text, "crossed.xml", &MjcfOptions::new()).unwrap_err().to_string();
    assert!(clash.contains("already taken"), "{clash}");
    let second = MjcfOptions::new().prefix("two/").base_pose(ars::nalgebra::Isometry3::translation(0.0, 0.0, 5.0));
    let model = sim.load_mjcf_text(&text, "crossed.xml", &second).unwrap();
    assert!(model.joint("two/ja").is_some() && model.body("two/post").is_some(), "{:?}", model.joints);
    let post = sim.scene().object(model.body("two/post").unwrap()).unwrap().body_handle().unwrap();
    assert!(sim.scene().world().body(post).unwrap().is_kinematic(), "welded to the world");
    let names = actuator_names(&sim);
    assert_eq!(names, ["turn_c", "turn_a", "turn_b", "two/turn_c", "two/turn_a", "two/turn_b"]);
    // Each copy's actuator drives its own joint.
    sim.scene_mut().set_control("two/turn_a", 1.0).unwrap();
    sim.run_for(0.1).unwrap();
    let rate = |j: &str| sim.scene().joint(j).unwrap().state().unwrap().rate;
    assert!(rate("two/ja") > 0.0 && rate("ja") == 0.0, "{} {}", rate("two/ja"), rate("ja"));
}
