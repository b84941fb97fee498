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
/// robot files write small parts) loads as MuJoCo loads it: its ODE body, welded to its
/// parent, takes the inertia of a solid sphere of that mass at water's density, said
/// in `skipped`; its mass is the file's.
#[test]
fn a_welded_point_mass_loads_with_an_inertia_said_in_skipped() {
    let text = CROSSED.replace(
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/></body>
    <body name="b""#,
        r#"<geom fromto="0 0 0 0.5 0 0" size="0.05"/>
      <body name="knob" pos="0.5 0 0"><inertial pos="0 0 0" mass="0.2" diaginertia="0 0 0"/></body></body>
    <body name="b""#,
    );
    assert!(text.contains("knob"), "the knob is in the text");
    let mut sim = Simulation::builder().gravity(ars::nalgebra::Vector3::zeros()).build().unwrap();
    let model = sim.load_mjcf_text(&text, "knob.xml", &MjcfOptions::new()).unwrap();
    let said: Vec<&String> = model.skipped.iter().filter(|s| s.starts_with("\"knob\": inertia balanced")).collect();
    assert_eq!(said.len(), 1, "{:#?}", model.skipped);
    let knob = sim.scene().object(model.body("knob").unwrap()).unwrap().body_handle().unwrap();
    assert_eq!(sim.scene().world().body(knob).unwrap().mass(), 0.2);
    sim.scene_mut().set_controls(&[0.0, 1.0, 0.0]).unwrap();
    sim.run_for(0.2).unwrap();
}
