//! Saving a scene and loading it back: a scene saved before it steps loads into one that
//! steps bit for bit as the original; saved mid-run, every body comes back to the bit.

use ars::{Hooks, Program, Simulation};
use ars_programs::{ConicalPendulum, SpeedProfile};

fn states(sim: &Simulation) -> Vec<u64> {
    sim.scene()
        .bodies()
        .flat_map(|(_, h)| {
            let b = sim.scene().world().body(h).unwrap();
            let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
            [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z].map(f64::to_bits)
        })
        .collect()
}

/// The pendulum's scene and the hooks that drive it, for a simulation of it.
fn driver(sim: &Simulation) -> ConicalPendulum {
    let mut d = ConicalPendulum::default();
    (d.waist, d.shoulder) = (Some(sim.scene().joint("r1").unwrap().id()), Some(sim.scene().joint("r2").unwrap().id()));
    d
}

#[test]
fn a_saved_scene_loads_and_steps_bit_for_bit_as_the_original() {
    let mut original = ConicalPendulum::default().create_simulation().unwrap();
    let text = original.save_scene().unwrap();
    assert!(text.contains("\"format\": \"ars-scene/1\"") && text.contains("\"r2\""), "readable JSON");
    let mut loaded = Simulation::load_scene(&text).unwrap();
    assert_eq!(states(&original), states(&loaded));
    let (a, b) = (driver(&original), driver(&loaded));
    original.add_hooks(a).unwrap();
    loaded.add_hooks(b).unwrap();
    for step in 1..=4000 {
        original.step().unwrap();
        loaded.step().unwrap();
        assert_eq!(states(&original), states(&loaded), "after step {step}");
    }
    // And saving the loaded scene again gives the same file, but for the program's
    // record (a closure sensor), which is named in the file and not saved.
    let first = Simulation::load_scene(&text).unwrap();
    let mut expected = first.scene_file().unwrap();
    assert!(expected.unsaved_sensors.is_empty());
    expected.unsaved_sensors = vec!["Probe<PendulumRow>".into()];
    let mut saved = ConicalPendulum::default().create_simulation().unwrap().scene_file().unwrap();
    // The exact states differ by the record's schedule.
    assert!(saved.state.is_some() && expected.state.is_some());
    (saved.state, expected.state) = (None, None);
    assert_eq!(saved, expected);
    let again = Simulation::load_scene(&first.save_scene().unwrap()).unwrap().save_scene().unwrap();
    assert_eq!(again, first.save_scene().unwrap());
}

#[test]
fn a_scene_saved_mid_run_brings_every_body_back_to_the_bit() {
    let mut program = SpeedProfile::default();
    let mut sim = program.create_simulation().unwrap();
    struct Drive(SpeedProfile);
    impl Hooks for Drive {
        fn pre_step(&mut self, sim: &mut Simulation) -> ars::Result<()> {
            self.0.pre_step(sim)
        }
    }
    sim.add_hooks(Drive(program)).unwrap();
    sim.run_for(1.5).unwrap();
    let path = std::env::temp_dir().join(format!("ars-scene-{}.json", std::process::id()));
    sim.save_scene_to(&path).unwrap();
    let loaded = Simulation::load_scene_from(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(states(&sim), states(&loaded), "bodies, exactly");
    assert_eq!((loaded.scene().time(), loaded.scene().step_count()), (sim.scene().time(), sim.scene().step_count()));
    assert_eq!(loaded.scene().objects().count(), sim.scene().objects().count());
    assert_eq!(loaded.scene().joints().count(), sim.scene().joints().count());
    // Joints are rebuilt where they are now: the same anchors and axes.
    for (name, id) in sim.scene().joints() {
        let (a, b) =
            (sim.scene().joint(id).unwrap().ode().unwrap(), loaded.scene().joint(name).unwrap().ode().unwrap());
        if let (Ok(p), Ok(q)) = (a.anchor(), b.anchor()) {
            assert!((p - q).norm() < 1e-12, "{name}: anchor {p} vs {q}");
        }
        if let (Ok(u), Ok(v)) = (a.axis(), b.axis()) {
            assert!((u - v).norm() < 1e-12, "{name}: axis {u} vs {v}");
        }
    }
    assert!(Simulation::load_scene("{\"format\": \"other\"}").is_err());
}

#[test]
fn motors_friction_actuator_limits_and_mimics_are_saved() {
    const GRIPPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gripper.urdf");
    let mut original = Simulation::new().unwrap();
    original.load_urdf(GRIPPER, &ars::UrdfOptions::new().fixed_base(true)).unwrap();
    original.scene_mut().joint_mut("left_finger_joint").unwrap().set_speed(0.05, 10.0).unwrap();
    let text = original.save_scene().unwrap();
    let mut loaded = Simulation::load_scene(&text).unwrap();
    for name in ["left_finger_joint", "right_finger_joint"] {
        let (a, b) = (original.scene().joint(name).unwrap(), loaded.scene().joint(name).unwrap());
        assert_eq!(a.actuator_limits(), b.actuator_limits(), "{name}");
        assert_eq!(a.dry_friction(), b.dry_friction(), "{name}");
        assert_eq!(a.mimic().is_some(), b.mimic().is_some(), "{name}");
    }
    for step in 1..=1000 {
        original.step().unwrap();
        loaded.step().unwrap();
        assert_eq!(states(&original), states(&loaded), "after step {step}");
    }
    assert!(original.scene().joint("left_finger_joint").unwrap().state().unwrap().position > 0.01, "it moved");
}

#[test]
fn sensors_are_saved_by_kind_and_what_they_read() {
    use ars::sensors::{Gps, JointPositions, Noisy};
    let mut original = ConicalPendulum::default().create_simulation().unwrap();
    let pole = original.scene().object("cylinder").unwrap().id();
    let (r1, r2) = (original.scene().joint("r1").unwrap().id(), original.scene().joint("r2").unwrap().id());
    let gps = original.add_sensor_every(Gps::new(pole), 0.01).unwrap();
    let positions = JointPositions::new(original.scene(), &[r1, r2]).unwrap();
    let joints = original.add_sensor(positions).unwrap();
    original.add_sensor(Noisy::new(Gps::new(pole), 0.01, 3).unwrap()).unwrap();
    let file = original.scene_file().unwrap();
    assert_eq!(file.sensors.len(), 3);
    assert_eq!((file.sensors[0].kind.as_str(), file.sensors[0].period), ("Gps", Some(0.01)));
    assert_eq!(file.sensors[1].joints, ["r1", "r2"]);
    assert_eq!((file.sensors[2].kind.as_str(), file.sensors[2].noise), ("Gps", Some((0.01, 3))));
    assert_eq!(file.unsaved_sensors, ["Probe<PendulumRow>"]);
    let mut loaded = Simulation::from_scene_file(&file).unwrap();
    let (a, b) = (driver(&original), driver(&loaded));
    original.add_hooks(a).unwrap();
    loaded.add_hooks(b).unwrap();
    original.run_for(0.5).unwrap();
    loaded.run_for(0.5).unwrap();
    // The loaded scene's sensors, in the same order, record the same samples.
    let tables = loaded.sensor_tables();
    assert_eq!(tables.len(), 3);
    let same = |(_, a): &(String, &dyn ars::sensors::CsvColumns), (_, b): &(String, &dyn ars::sensors::CsvColumns)| {
        a.stamps() == b.stamps() && (0..a.stamps().len()).all(|i| a.cells(i) == b.cells(i))
    };
    let theirs = original.sensor_tables();
    assert_eq!((theirs[1].0.as_str(), theirs[2].0.as_str()), ("Gps", "JointPositions"));
    assert!(same(&theirs[1], &tables[0]) && same(&theirs[2], &tables[1]) && same(&theirs[3], &tables[2]));
    assert_eq!(original.records(gps).unwrap().len(), 50);
    assert_eq!(original.records(joints).unwrap().len(), 2000);
}

#[test]
fn a_scene_keeps_its_space_and_a_file_without_one_has_the_simple_space() {
    use ars::{AxisOrder, Mass, SpaceKind};
    for space in
        [SpaceKind::Simple, SpaceKind::HASH, SpaceKind::SweepAndPrune { axes: AxisOrder::Zyx }, SpaceKind::Grid]
    {
        let mut sim = Simulation::builder().space(space).build().unwrap();
        sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        let loaded = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
        assert_eq!(loaded.scene().space_kind(), space);
    }
    // The default space is saved too: a loaded scene does not fall back to simple.
    let text = Simulation::new().unwrap().save_scene().unwrap();
    assert!(text.contains("\"space\": \"Grid\""), "{text}");
    assert_eq!(Simulation::load_scene(&text).unwrap().scene().space_kind(), SpaceKind::Grid);
    // A file that names no space: the original's simple space.
    let without = text.replace("  \"space\": \"Grid\",\n", "");
    assert!(!without.contains("space") && without.contains("\"time\""), "{without}");
    let old = Simulation::load_scene(&without).unwrap();
    assert_eq!(old.scene().space_kind(), SpaceKind::Simple);
}

#[test]
fn sensors_at_an_offset_and_touch_zones_are_saved_with_them() {
    use ars::nalgebra::{Isometry3, UnitQuaternion, Vector3};
    use ars::sensors::{Gps, Imu, Orientation, SensorSettings, Touch, TouchZone};
    let mut original = ConicalPendulum::default().create_simulation().unwrap();
    let pole = original.scene().object("cylinder").unwrap().id();
    let turn = UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3);
    let mount = Isometry3::from_parts(Vector3::new(0.0, 0.2, 0.05).into(), turn);
    original.add_sensor(Gps::new(pole).at(Vector3::new(0.0, 0.2, 0.0))).unwrap();
    original.add_sensor(Imu::new(pole).at(mount)).unwrap();
    original.add_sensor(Orientation::new(pole).at(turn)).unwrap();
    original.add_sensor(Orientation::new(pole)).unwrap();
    let zone = TouchZone::Sphere { radius: 0.1 };
    original.add_sensor(Touch::new(pole).within(zone, mount)).unwrap();
    let file = original.scene_file().unwrap();
    let kept: Vec<(&str, Option<&SensorSettings>)> =
        file.sensors.iter().map(|s| (s.kind.as_str(), s.settings.as_ref())).collect();
    assert_eq!(kept[0], ("Gps", Some(&SensorSettings::Offset { pose: Isometry3::translation(0.0, 0.2, 0.0) })));
    assert_eq!(kept[1], ("Imu", Some(&SensorSettings::Offset { pose: mount })));
    assert_eq!(kept[3], ("Orientation", None), "no offset, nothing kept");
    assert_eq!(kept[4], ("Touch", Some(&SensorSettings::Touch { zone, pose: mount })));
    let mut loaded = Simulation::from_scene_file(&file).unwrap();
    let (a, b) = (driver(&original), driver(&loaded));
    original.add_hooks(a).unwrap();
    loaded.add_hooks(b).unwrap();
    original.run_for(0.2).unwrap();
    loaded.run_for(0.2).unwrap();
    // The same readings: the offsets came back.
    let (ours, theirs) = (loaded.sensor_tables(), original.sensor_tables());
    for (i, (name, table)) in ours.iter().enumerate() {
        let other = theirs[i + 1].1;
        let last = table.len() - 1;
        assert_eq!(table.cells(last), other.cells(last), "{name}");
    }
    // Settings a kind cannot take are refused.
    let mut wrong = file.clone();
    wrong.sensors[0].kind = "Inclinometer".into();
    let e = Simulation::from_scene_file(&wrong).unwrap_err().to_string();
    assert!(e.contains("Inclinometer") && e.contains("cannot take"), "{e}");
}
