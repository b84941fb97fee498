//! Exact snapshots: taken at a seeded random step of a run, restored into a fresh
//! simulation (built by the same code, or from the snapshot alone, in this process or
//! through bytes), every later step is the same to the bit as the uninterrupted run:
//! every body's pose and velocity after every step, and every sensor record.

use ars::sensors::CsvColumns;
use ars::{Program, SensorKind, Simulation, Snapshot};
use ars_programs::ConicalPendulum;

/// Every body's position, quaternion, rotation matrix and velocities, as bits.
fn states(sim: &Simulation) -> Vec<u64> {
    sim.scene()
        .bodies()
        .flat_map(|(_, h)| {
            let b = sim.scene().world().body(h).unwrap();
            let (p, q, r, v, w) =
                (b.position(), b.quaternion(), b.rotation(), b.linear_velocity(), b.angular_velocity());
            [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z]
                .into_iter()
                .chain(r.matrix().iter().copied())
                .map(f64::to_bits)
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Every sensor's records taken after step `after`: its name, then each record's time,
/// step and cells, as bits.
fn records_after(sim: &Simulation, after: u64) -> Vec<(String, Vec<Vec<u64>>)> {
    sim.sensor_tables()
        .into_iter()
        .map(|(name, table): (String, &dyn CsvColumns)| {
            let rows = (0..table.len())
                .filter(|&i| table.stamp(i).1 > after)
                .map(|i| {
                    let (t, step) = table.stamp(i);
                    let cells = table.cells(i).into_iter().map(|c| c.map_or(u64::MAX, f64::to_bits));
                    [t.to_bits(), step].into_iter().chain(cells).collect()
                })
                .collect();
            (name, rows)
        })
        .collect()
}

/// How a scene is built.
type Build = fn() -> Simulation;

/// A scene to test: its name, how it is built, and the step at which it is saved.
type Scene = (&'static str, Build, u64);

/// A small seeded generator for the steps at which snapshots are taken.
fn seeded_steps(seed: u64, count: usize, below: u64) -> Vec<u64> {
    let mut rng = ars::random::SplitMix64::new(seed);
    let mut steps: Vec<u64> = (0..count).map(|_| 1 + rng.next_u64() % below).collect();
    steps.sort_unstable();
    steps
}

/// Runs `build()`'s simulation, takes snapshots at `at` (step counts), and for each
/// restores it into a fresh `build()` (directly and through bytes), steps both `run`
/// steps and compares states after every step and the records at the end.
fn resumes_exactly(name: &str, build: impl Fn() -> Simulation, at: &[u64], run: u64) {
    for &k in at {
        let mut original = build();
        original.step_n(k).unwrap();
        let snapshot = original.snapshot().unwrap();
        let bytes = snapshot.to_bytes();
        let mut reference = build();
        reference.restore(&snapshot).unwrap();
        let mut through_bytes = build();
        through_bytes.restore(&Snapshot::from_bytes(&bytes).unwrap()).unwrap();
        assert_eq!(states(&reference), states(&original), "{name}: restored at step {k}");
        let mut ahead = build();
        ahead.restore(&snapshot).unwrap();
        for step in 1..=run {
            ahead.step().unwrap();
            reference.step().unwrap();
            through_bytes.step().unwrap();
            let expected = states(&ahead);
            assert_eq!(states(&reference), expected, "{name}: {step} steps after step {k}");
            assert_eq!(states(&through_bytes), expected, "{name}: through bytes, {step} steps after step {k}");
        }
        // `ahead` is the uninterrupted run from the snapshot on: the original too.
        original.step_n(run).unwrap();
        let end = states(&original);
        assert_eq!(states(&reference), end, "{name}: the uninterrupted run, {run} steps after {k}");
        let expected = records_after(&original, k);
        assert_eq!(records_after(&reference, k), expected, "{name}: records after step {k}");
        assert_eq!(records_after(&through_bytes, k), expected, "{name}: records through bytes after step {k}");
        // Back in the original, whose bodies have moved on since: its joints are made
        // again where they were made, not where the bodies are.
        original.restore(&snapshot).unwrap();
        original.step_n(run).unwrap();
        assert_eq!(states(&original), end, "{name}: restored into itself after {k}");
        assert_eq!(records_after(&original, k), expected, "{name}: records restored into itself after {k}");
    }
}

/// The thesis' conical pendulum with its program's hooks (the waist torque).
fn conical_pendulum() -> Simulation {
    let mut sim = ConicalPendulum::default().create_simulation().unwrap();
    let mut driver = ConicalPendulum::default();
    (driver.waist, driver.shoulder) =
        (Some(sim.scene().joint("r1").unwrap().id()), Some(sim.scene().joint("r2").unwrap().id()));
    sim.add_hooks(driver).unwrap();
    sim
}

#[test]
fn the_conical_pendulum_resumes_to_the_bit_from_any_step() {
    // 2 s of the pendulum's 0.25 ms steps after each snapshot.
    resumes_exactly("conical pendulum", conical_pendulum, &seeded_steps(1, 3, 20_000), 8000);
}

/// IROS example 4: the vehicle with its servoed arm on the sinusoidal trimesh terrain.
fn sinusoidal_terrain() -> Simulation {
    let mut program = ars_programs::SinusoidalTerrain::default();
    let mut sim = program.create_simulation().unwrap();
    sim.add_hooks(program).unwrap();
    sim
}

#[test]
fn the_vehicle_on_the_sinusoidal_terrain_resumes_to_the_bit() {
    // 2 s of 0.4 ms steps after each snapshot, taken in the first 4 s.
    resumes_exactly("sinusoidal terrain", sinusoidal_terrain, &seeded_steps(2, 2, 10_000), 5000);
}

/// IROS example 3 with the paper's PD variant (its hook keeps the previous error).
fn speed_profile() -> Simulation {
    let mut program = ars_programs::SpeedProfile::with_derivative_gain(0.05);
    let mut sim = program.create_simulation().unwrap();
    sim.add_hooks(program).unwrap();
    sim
}

#[test]
fn the_speed_profile_resumes_to_the_bit() {
    resumes_exactly("speed profile", speed_profile, &seeded_steps(3, 2, 10_000), 5000);
}

const RNEA_ARM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/rnea_arm.urdf");

/// A URDF arm on a fixed base whose three joints are held by PID position servos on
/// moving set-points.
fn urdf_arm() -> Simulation {
    use ars::{Pid, PositionServo, Profile};
    let mut sim = Simulation::builder().floor_plane(ars::nalgebra::Vector3::y(), 0.0).build().unwrap();
    sim.load_urdf(RNEA_ARM, &ars::UrdfOptions::new().fixed_base(true)).unwrap();
    for (i, name) in ["j1", "j2", "j3"].into_iter().enumerate() {
        let target = 0.3 * (i as f64 + 1.0);
        let setpoint = Profile::new(vec![(0.0, 0.0), (1.0, target), (2.0, -target)]).unwrap();
        let servo = PositionServo { setpoint, pid: Pid::new(40.0, 5.0, 2.0) };
        sim.scene_mut().joint_mut(name).unwrap().set_controller(servo).unwrap();
    }
    sim
}

#[test]
fn a_urdf_arm_with_position_servos_resumes_to_the_bit() {
    resumes_exactly("URDF arm", urdf_arm, &seeded_steps(4, 3, 5000), 5000);
}

/// Every joint kind (the scene's, and hinge-2 and an angular motor through the
/// world), every controller kind, noisy sensors, a lidar, contacts on a floor.
fn every_joint_kind_in(builder: ars::SimulationBuilder) -> Simulation {
    use ars::nalgebra::{Isometry3, Point3, Vector3};
    use ars::sensors::{Accelerometer, ContactSensor, Gps, Imu, JointPositions, Lidar, Noisy};
    use ars::{DcMotor, JointBuilder, JointEnd, Mass, Pid, PositionServo, Profile, TorqueMotor, VelocityServo};
    let mut sim = builder.floor_plane(Vector3::y(), 0.0).build().unwrap();
    let m = Mass::Total(1.0);
    let base = sim.scene_mut().add_box([0.4, 0.2, 0.4], [0.0, 1.5, 0.0], m).unwrap();
    sim.scene_mut().add_fixed_joint("anchor", base, JointEnd::World).unwrap();
    let a = sim.scene_mut().add_box([0.1, 0.4, 0.1], [0.3, 1.3, 0.0], m).unwrap();
    let b = sim.scene_mut().add_sphere(0.08, [0.3, 0.9, 0.0], m).unwrap();
    let c = sim.scene_mut().add_capsule(0.05, 0.3, [-0.3, 1.2, 0.0], m).unwrap();
    let d = sim.scene_mut().add_cylinder(0.3, 0.06, [-0.3, 0.8, 0.0], m).unwrap();
    let e = sim.scene_mut().add_box([0.1, 0.1, 0.3], [0.0, 1.0, 0.4], m).unwrap();
    let f = sim.scene_mut().add_sphere(0.1, [0.0, 0.6, 0.4], m).unwrap();
    let g = sim.scene_mut().add_box([0.2, 0.1, 0.2], [0.6, 0.3, 0.6], m).unwrap();
    let h = sim.scene_mut().add_sphere(0.1, [0.0, 0.2, -0.6], m).unwrap();
    let y = Vector3::y();
    let hinge =
        sim.scene_mut().add_hinge_joint("hinge", a, base, Some(Point3::new(0.3, 1.5, 0.0)), Vector3::z()).unwrap();
    let slider = sim.scene_mut().add_slider_joint("slider", b, a, y).unwrap();
    let universal = sim
        .scene_mut()
        .add_universal_joint("universal", c, base, Point3::new(-0.3, 1.4, 0.0), Vector3::x(), Vector3::z())
        .unwrap();
    sim.scene_mut().add_ball_joint("ball", d, c, Some(Point3::new(-0.3, 1.0, 0.0))).unwrap();
    let piston = sim.scene_mut().add_piston_joint("piston", e, base, Point3::new(0.0, 1.2, 0.4), y).unwrap();
    sim.scene_mut().add_fixed_joint("weld", f, e).unwrap();
    let (bf, bh) =
        (sim.scene().object(f).unwrap().body_handle().unwrap(), sim.scene().object(h).unwrap().body_handle().unwrap());
    let bg = sim.scene().object(g).unwrap().body_handle().unwrap();
    let world = sim.scene_mut().world_mut();
    world.insert_joint(JointBuilder::hinge2(Point3::new(0.0, 0.4, 0.0), y, Vector3::x()).between(bf, bh)).unwrap();
    world
        .insert_joint(
            JointBuilder::new(ars::JointKind::AngularMotor { axes: vec![(ars::AxisFrame::World, y)] })
                .to_world(bg)
                .motor(0.7, 0.3),
        )
        .unwrap();
    let profile = |v: f64| Profile::new(vec![(0.0, 0.0), (0.5, v), (1.5, -v)]).unwrap();
    sim.scene_mut()
        .joint_mut(hinge)
        .unwrap()
        .set_controller(PositionServo { setpoint: profile(0.8), pid: Pid::new(30.0, 4.0, 1.0) })
        .unwrap();
    sim.scene_mut()
        .joint_mut(slider)
        .unwrap()
        .set_controller(VelocityServo { setpoint: profile(0.2), gain: 20.0 })
        .unwrap();
    sim.scene_mut().joint_mut(slider).unwrap().set_limits(-0.2, 0.2).unwrap();
    sim.scene_mut()
        .joint_mut(universal)
        .unwrap()
        .set_controller(DcMotor::new(profile(6.0), 0.05, 0.05, 2.0, 10.0, 1e-5).unwrap().with_inductance(1e-3).unwrap())
        .unwrap();
    sim.scene_mut().joint_mut(universal).unwrap().set_viscous_friction(0.01).unwrap();
    sim.scene_mut().joint_mut(piston).unwrap().set_controller(TorqueMotor { torque: profile(3.0) }).unwrap();
    sim.add_sensor(Noisy::new(Gps::new(b), 0.01, 7).unwrap()).unwrap();
    sim.add_sensor_every(Noisy::new(Imu::new(d), 0.02, 8).unwrap(), 0.01).unwrap();
    sim.add_sensor(Accelerometer::new(h)).unwrap();
    sim.add_sensor(ContactSensor::new(g)).unwrap();
    let positions = JointPositions::new(sim.scene(), &[hinge, slider, universal, piston]).unwrap();
    sim.add_sensor_every(positions, 0.005).unwrap();
    let lidar = Lidar::new(90, std::f64::consts::TAU, 3.0).unwrap().on(base, Isometry3::translation(0.0, 0.2, 0.0));
    sim.add_sensor_every(Noisy::new(lidar, 0.005, 9).unwrap(), 0.02).unwrap();
    let camera = ars::sensors::DepthCamera::new(8, 6, 1.0, 0.05, 5.0).unwrap();
    let eye = Isometry3::face_towards(&Point3::new(1.5, 1.0, 1.5), &Point3::new(0.0, 0.8, 0.0), &Vector3::y());
    sim.add_sensor_every(camera.at(eye), 0.05).unwrap();
    sim
}

/// [`every_joint_kind_in`] the default space (the grid) with the exact stepper.
fn every_joint_kind() -> Simulation {
    every_joint_kind_in(Simulation::builder())
}

#[test]
fn every_space_and_quickstep_resume_to_the_bit() {
    use ars::{SpaceKind, Stepper};
    let variants: [(&str, Build); 4] = [
        ("simple space", || every_joint_kind_in(Simulation::builder().space(SpaceKind::Simple))),
        ("hash space", || every_joint_kind_in(Simulation::builder().space(SpaceKind::HASH))),
        ("sweep and prune", || every_joint_kind_in(Simulation::builder().space(SpaceKind::SWEEP_AND_PRUNE))),
        ("QuickStep", || {
            every_joint_kind_in(Simulation::builder().stepper(Stepper::Quick { iterations: 20 }).seed(11))
        }),
    ];
    for (name, build) in variants {
        resumes_exactly(name, build, &seeded_steps(6, 1, 4000), 2500);
    }
}

#[test]
fn every_joint_kind_with_noisy_sensors_and_a_lidar_resumes_to_the_bit() {
    resumes_exactly("every joint kind", every_joint_kind, &seeded_steps(5, 3, 5000), 5000);
}

/// The scene's own joints and sensors of kinds a scene file rebuilds: a snapshot of it
/// rebuilds a simulation of its own ([`Simulation::from_snapshot`]).
fn scene_joints() -> Simulation {
    use ars::nalgebra::{Point3, Vector3};
    use ars::{JointEnd, Mass, Pid, PositionServo, Profile, VelocityServo};
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let m = Mass::Total(1.0);
    let base = sim.scene_mut().add_box([0.4, 0.2, 0.4], [0.0, 1.5, 0.0], m).unwrap();
    sim.scene_mut().add_fixed_joint("anchor", base, JointEnd::World).unwrap();
    let a = sim.scene_mut().add_box([0.1, 0.4, 0.1], [0.3, 1.3, 0.0], m).unwrap();
    let b = sim.scene_mut().add_sphere(0.08, [0.3, 0.9, 0.0], m).unwrap();
    let c = sim.scene_mut().add_capsule(0.05, 0.3, [-0.3, 1.2, 0.0], m).unwrap();
    let d = sim.scene_mut().add_cylinder(0.3, 0.06, [-0.3, 0.8, 0.0], m).unwrap();
    let e = sim.scene_mut().add_box([0.1, 0.1, 0.3], [0.0, 1.0, 0.4], m).unwrap();
    let y = Vector3::y();
    let hinge =
        sim.scene_mut().add_hinge_joint("hinge", a, base, Some(Point3::new(0.3, 1.5, 0.0)), Vector3::z()).unwrap();
    let slider = sim.scene_mut().add_slider_joint("slider", b, a, y).unwrap();
    sim.scene_mut()
        .add_universal_joint("universal", c, base, Point3::new(-0.3, 1.4, 0.0), Vector3::x(), Vector3::z())
        .unwrap();
    sim.scene_mut().add_ball_joint("ball", d, c, Some(Point3::new(-0.3, 1.0, 0.0))).unwrap();
    sim.scene_mut().add_piston_joint("piston", e, base, Point3::new(0.0, 1.2, 0.4), y).unwrap();
    let profile = |v: f64| Profile::new(vec![(0.0, 0.0), (0.5, v), (1.5, -v)]).unwrap();
    let servo = PositionServo { setpoint: profile(0.8), pid: Pid::new(30.0, 4.0, 1.0) };
    sim.scene_mut().joint_mut(hinge).unwrap().set_controller(servo).unwrap();
    sim.scene_mut()
        .joint_mut(slider)
        .unwrap()
        .set_controller(VelocityServo { setpoint: profile(0.2), gain: 20.0 })
        .unwrap();
    sim.scene_mut().joint_mut("universal").unwrap().set_viscous_friction(0.05).unwrap();
    for (kind, object) in [(SensorKind::Gps, b), (SensorKind::Accelerometer, d), (SensorKind::ContactSensor, e)] {
        sim.add_sensor_of_kind(kind, &[object], &[], Some(0.01)).unwrap();
    }
    sim.add_sensor_of_kind(SensorKind::JointPositions, &[], &[hinge, slider], None).unwrap();
    sim
}

/// A free URDF robot whose links have several collision shapes away from their
/// inertial frames, dropped on the floor with a driven wheel.
fn urdf_with_offset_shapes() -> Simulation {
    const URDF: &str = r#"<robot name="cart">
      <link name="body">
        <inertial><origin xyz="0.05 0 0"/><mass value="2"/>
          <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial>
        <collision><origin xyz="0 0 0.05"/><geometry><box size="0.4 0.2 0.05"/></geometry></collision>
        <collision><origin xyz="0.2 0.05 0.1" rpy="0.3 0 0.2"/><geometry><sphere radius="0.06"/></geometry></collision>
        <collision><origin xyz="-0.2 0 0.08" rpy="0 0.5 0"/><geometry><cylinder radius="0.04" length="0.1"/></geometry></collision>
      </link>
      <link name="wheel">
        <inertial><mass value="0.3"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
        <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.08" length="0.04"/></geometry></collision>
        <collision><origin xyz="0 0 0.03"/><geometry><sphere radius="0.03"/></geometry></collision>
      </link>
      <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/>
        <origin xyz="0.15 -0.15 0"/><axis xyz="0 1 0"/></joint>
    </robot>"#;
    let mut sim = Simulation::builder().floor_plane(ars::nalgebra::Vector3::y(), 0.0).build().unwrap();
    let options = ars::UrdfOptions::new().base_pose(ars::nalgebra::Isometry3::translation(0.0, 0.3, 0.0));
    sim.load_urdf_text(URDF, "cart.urdf", &options).unwrap();
    sim.scene_mut().joint_mut("axle").unwrap().set_speed(4.0, 2.0).unwrap();
    sim.add_sensor_of_kind(SensorKind::Gps, &[sim.scene().object("wheel").unwrap().id()], &[], Some(0.01)).unwrap();
    sim
}

#[test]
fn a_snapshot_rebuilds_a_simulation_of_its_own_that_resumes_to_the_bit() {
    let scenes: [Scene; 4] = [
        ("scene joints", scene_joints, 1234),
        ("URDF arm", urdf_arm, 2345),
        ("URDF with offset shapes", urdf_with_offset_shapes, 1500),
        ("every joint kind", every_joint_kind, 3456),
    ];
    for (name, build, k) in scenes {
        let mut original = build();
        original.step_n(k).unwrap();
        let bytes = original.snapshot().unwrap().to_bytes();
        let mut rebuilt = Simulation::from_snapshot(&Snapshot::from_bytes(&bytes).unwrap()).unwrap();
        assert_eq!(states(&rebuilt), states(&original), "{name}");
        for step in 1..=3000 {
            original.step().unwrap();
            rebuilt.step().unwrap();
            assert_eq!(states(&rebuilt), states(&original), "{name}: {step} steps after step {k}");
        }
        assert_eq!(records_after(&rebuilt, k), records_after(&original, k), "{name}: records");
        assert!(records_after(&original, k).iter().all(|(_, rows)| !rows.is_empty()), "{name}: sensors sampled");
    }
}

#[test]
fn a_scene_saved_mid_run_loads_and_resumes_to_the_bit() {
    let scenes: [Scene; 3] = [
        ("scene joints", scene_joints, 777),
        ("every joint kind", every_joint_kind, 1500),
        ("URDF with offset shapes", urdf_with_offset_shapes, 1100),
    ];
    for (name, build, k) in scenes {
        let mut original = build();
        original.step_n(k).unwrap();
        let text = original.save_scene().unwrap();
        let mut loaded = Simulation::load_scene(&text).unwrap();
        for step in 1..=3000 {
            original.step().unwrap();
            loaded.step().unwrap();
            assert_eq!(states(&loaded), states(&original), "{name}: {step} steps after step {k}");
        }
        assert_eq!(records_after(&loaded, k), records_after(&original, k), "{name}: records");
    }
}

#[test]
fn bad_snapshots_are_refused_and_change_nothing() {
    let mut sim = scene_joints();
    sim.step_n(100).unwrap();
    let bytes = sim.snapshot().unwrap().to_bytes();
    let before = states(&sim);
    let other = conical_pendulum().snapshot().unwrap();
    assert!(matches!(sim.restore(&other), Err(ars::Error::SnapshotMismatch { .. })));
    assert_eq!(states(&sim), before, "a refused snapshot changes nothing");
    let truncated = Snapshot::from_bytes(&bytes[..bytes.len() - 10]);
    assert!(matches!(truncated, Err(ars::Error::SnapshotCorrupt { .. })), "{truncated:?}");
    let mut altered = bytes.clone();
    let last = altered.len() - 1;
    altered[last] ^= 1;
    assert!(matches!(Snapshot::from_bytes(&altered), Err(ars::Error::SnapshotCorrupt { .. })));
    let mut newer = bytes.clone();
    newer[8] = 99;
    assert!(matches!(Snapshot::from_bytes(&newer), Err(ars::Error::SnapshotVersion { found: 99, .. })));
    assert!(matches!(Snapshot::from_bytes(b"not a snapshot"), Err(ars::Error::SnapshotCorrupt { .. })));
    sim.step().unwrap();
}

/// A plank across two static supports, in the original's simple space.
fn plank_on_supports() -> Simulation {
    use ars::nalgebra::Isometry3;
    use ars::{Mass, Shape, SpaceKind};
    let mut sim = Simulation::builder().space(SpaceKind::Simple).build().unwrap();
    for x in [-0.5, 0.5] {
        let support = Shape::Box { edges: ars::nalgebra::Vector3::new(0.2, 0.4, 0.3) };
        sim.scene_mut().add_static(support, Isometry3::translation(x, 0.2, 0.0)).unwrap();
    }
    let plank = sim.scene_mut().add_box([1.4, 0.05, 0.2], [0.02, 0.43, 0.01], Mass::Total(2.0)).unwrap();
    sim.scene_mut().body_mut(plank).unwrap().set_angular_velocity([0.3, 0.0, 0.8].into()).unwrap();
    sim
}

/// Static objects moved (in place) just before the snapshot, last first: ODE moves a
/// moved geom to the front of its space's list, and that order is the order of the
/// collision pairs and so of the contact joints; the snapshot puts it back.
#[test]
fn the_order_of_a_space_s_geoms_is_restored() {
    let mut original = plank_on_supports();
    original.step_n(500).unwrap();
    let statics: Vec<_> =
        original.scene().objects().map(|(_, id)| id).filter(|id| original.scene().body(*id).is_err()).collect();
    assert_eq!(statics.len(), 2);
    for id in statics.iter().rev() {
        let pose = original.scene().pose(*id).unwrap();
        original.scene_mut().set_pose(*id, pose).unwrap();
    }
    let snapshot = original.snapshot().unwrap();
    let mut restored = plank_on_supports();
    restored.restore(&snapshot).unwrap();
    for step in 1..=2000 {
        original.step().unwrap();
        restored.step().unwrap();
        assert_eq!(states(&restored), states(&original), "{step} steps after the snapshot");
    }
}

#[test]
fn forces_queued_before_a_snapshot_act_after_the_restore() {
    let mut original = scene_joints();
    original.step_n(300).unwrap();
    let ball = original.scene().object("sphere").unwrap().id();
    original.scene_mut().body_mut(ball).unwrap().add_force([0.0, 30.0, 5.0].into()).unwrap();
    original.scene_mut().joint_mut("hinge").unwrap().add_torque(2.5).unwrap();
    let snapshot = original.snapshot().unwrap();
    let mut restored = scene_joints();
    restored.restore(&snapshot).unwrap();
    let mut without = scene_joints();
    without.restore(&snapshot).unwrap();
    let theirs = without.scene().object("sphere").unwrap().id();
    without.scene_mut().body_mut(theirs).unwrap().clear_forces();
    for _ in 0..1000 {
        original.step().unwrap();
        restored.step().unwrap();
        without.step().unwrap();
    }
    assert_eq!(states(&restored), states(&original));
    assert_ne!(states(&without), states(&original), "the queued force made a difference");
}

#[test]
fn a_diverged_simulation_is_brought_back_by_a_snapshot() {
    let mut sim = scene_joints();
    sim.step_n(200).unwrap();
    let snapshot = sim.snapshot().unwrap();
    let expected = {
        let mut copy = scene_joints();
        copy.restore(&snapshot).unwrap();
        copy.step_n(500).unwrap();
        states(&copy)
    };
    // A light sphere pushed with the largest force the API takes, step after step,
    // runs away: the step that finds it too fast is refused, and so are later ones.
    let ball = sim.scene().object("sphere").unwrap().id();
    let diverged = (0..100).find_map(|_| {
        sim.scene_mut().body_mut(ball).unwrap().add_force([1e9, 0.0, 0.0].into()).unwrap();
        sim.step().err()
    });
    assert!(matches!(diverged, Some(ars::Error::Diverged { .. })), "{diverged:?}");
    assert!(sim.step().is_err());
    sim.restore(&snapshot).unwrap();
    sim.step_n(500).unwrap();
    assert_eq!(states(&sim), expected);
}

/// The scenes by name, for a child process.
fn scene_by_name(name: &str) -> Build {
    match name {
        "conical pendulum" => conical_pendulum,
        "sinusoidal terrain" => sinusoidal_terrain,
        "URDF arm" => urdf_arm,
        "every joint kind" => every_joint_kind,
        other => panic!("no scene {other:?}"),
    }
}

/// In a child process (when `ARS_SNAPSHOT_CHILD` names a snapshot file): builds the
/// scene named by `ARS_SNAPSHOT_SCENE`, restores the snapshot, steps
/// `ARS_SNAPSHOT_STEPS` steps and writes the states beside the snapshot. Does nothing
/// in the test run itself.
#[test]
fn resume_in_a_child_process() {
    let Ok(path) = std::env::var("ARS_SNAPSHOT_CHILD") else { return };
    let scene = std::env::var("ARS_SNAPSHOT_SCENE").unwrap();
    let steps: u64 = std::env::var("ARS_SNAPSHOT_STEPS").unwrap().parse().unwrap();
    let mut sim = scene_by_name(&scene)();
    sim.restore(&Snapshot::from_bytes(&std::fs::read(&path).unwrap()).unwrap()).unwrap();
    sim.step_n(steps).unwrap();
    let bits: Vec<u8> = states(&sim).iter().flat_map(|b| b.to_le_bytes()).collect();
    std::fs::write(format!("{path}.states"), bits).unwrap();
}

#[test]
fn snapshots_resume_to_the_bit_in_another_process() {
    let dir = std::env::temp_dir().join(format!("ars-snapshots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, k, run) in [
        ("conical pendulum", 3000, 8000),
        ("sinusoidal terrain", 2500, 5000),
        ("URDF arm", 1800, 5000),
        ("every joint kind", 2200, 5000),
    ] {
        let mut sim = scene_by_name(name)();
        sim.step_n(k).unwrap();
        let path = dir.join(name.replace(' ', "_"));
        std::fs::write(&path, sim.snapshot().unwrap().to_bytes()).unwrap();
        let child = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", "resume_in_a_child_process", "--test-threads", "1"])
            .env("ARS_SNAPSHOT_CHILD", &path)
            .env("ARS_SNAPSHOT_SCENE", name)
            .env("ARS_SNAPSHOT_STEPS", run.to_string())
            .output()
            .unwrap();
        assert!(child.status.success(), "{name}: {}", String::from_utf8_lossy(&child.stdout));
        sim.step_n(run).unwrap();
        let theirs = std::fs::read(format!("{}.states", path.display())).unwrap();
        let ours: Vec<u8> = states(&sim).iter().flat_map(|b| b.to_le_bytes()).collect();
        assert_eq!(theirs, ours, "{name}: {run} steps after step {k} in another process");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bytes framed as a snapshot (right magic, version, length and checksum) around
/// `payload`.
fn framed(payload: &[u8]) -> Vec<u8> {
    let mut bytes = b"ARSSNAP\0".to_vec();
    bytes.extend_from_slice(&ars::SNAPSHOT_VERSION.to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    let mut crc = 0xFFFF_FFFFu32;
    for &b in payload {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    bytes.extend_from_slice(&(!crc).to_le_bytes());
    bytes.extend_from_slice(payload);
    bytes
}

#[test]
fn crafted_snapshots_with_a_good_checksum_are_refused_not_obeyed() {
    // Lengths of 2^62 (a string, an array): no allocation of that size, an error.
    for payload in [&[0x7b, 0x40, 0, 0, 0, 0, 0, 0, 0][..], &[0x9b, 0x40, 0, 0, 0, 0, 0, 0, 0]] {
        let err = Snapshot::from_bytes(&framed(payload)).unwrap_err();
        assert!(matches!(err, ars::Error::SnapshotCorrupt { .. }), "{err}");
    }
    // A real snapshot whose body was moved to NaN, re-framed with a good checksum: its
    // content decodes, and restoring it is refused before anything changes.
    let mut sim = scene_joints();
    sim.step_n(50).unwrap();
    let bytes = sim.snapshot().unwrap().to_bytes();
    let payload = &bytes[24..];
    // CBOR writes a double as 0xfb and 8 bytes (or 0xf9 and 2 when exact in half
    // precision): make the first number of the last body's linear velocity (the world
    // state comes after the scene) NaN.
    let key = b"linear_velocity";
    let at = payload.windows(key.len()).rposition(|w| w == key).unwrap() + key.len();
    let double = at + payload[at..].iter().position(|b| *b == 0xfb || *b == 0xf9).unwrap();
    let mut bad = payload.to_vec();
    if bad[double] == 0xf9 {
        bad[double + 1..double + 3].copy_from_slice(&[0x7e, 0x00]); // half-precision NaN
    } else {
        bad[double + 1..double + 9].copy_from_slice(&f64::NAN.to_be_bytes());
    }
    let snapshot = Snapshot::from_bytes(&framed(&bad)).unwrap();
    let before = states(&sim);
    let err = sim.restore(&snapshot).unwrap_err();
    assert!(matches!(err, ars::Error::SnapshotCorrupt { .. }), "{err}");
    assert_eq!(states(&sim), before);
    sim.step().unwrap();
}
