//! The Rust port against native ODE: the same scene written in plain C (`tests/c`) and
//! through `ars-core` must produce bit-identical trajectories, step by step.

use ars_reference_scenes::{BodyState, CScene, RustScene, SimScene};

/// Steps both scenes one at a time for `steps` steps and compares every body's
/// position, orientation and velocities bit for bit after each step.
fn assert_bit_identical(name: &str, mut c: CScene, mut rust: RustScene, steps: usize) -> Vec<BodyState> {
    assert_eq!(c.body_count(), rust.bodies.len(), "{name}: body count");
    let mut last = Vec::new();
    for step in 1..=steps {
        c.step(1);
        rust.step(1);
        last.clear();
        for i in 0..c.body_count() {
            let (cs, rs) = (c.body_state(i), rust.body_state(i));
            let same = cs.iter().zip(&rs).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{name}: body {i} differs from native ODE after step {step}:\n C   {cs:?}\n Rust {rs:?}");
            last.push(rs);
        }
    }
    last
}

#[test]
fn falling_sphere_is_bit_identical_to_native_ode_for_one_second() {
    let end = assert_bit_identical("falling sphere", CScene::falling_sphere(), RustScene::falling_sphere(), 2500);
    // And the trajectory is the physical one: the ball ends at rest on the floor.
    assert!((end[0][1] - 0.5).abs() < 1e-3, "rest height {}", end[0][1]);
}

#[test]
fn hinge_chain_is_bit_identical_to_native_ode_for_one_second() {
    let end = assert_bit_identical("hinge chain", CScene::hinge_chain(), RustScene::hinge_chain(), 2500);
    // The chain has swung: the second link is no longer at its start height.
    assert!((end[1][1] - 1.9).abs() > 0.1, "second link y {}", end[1][1]);
}

#[test]
fn drop_pile_in_a_hash_space_is_bit_identical_to_native_ode() {
    assert_bit_identical("drop pile", CScene::drop_pile(100), RustScene::drop_pile(100), 500);
}

/// A reference scene: its name, its C twin, its `Simulation` and how many steps to run.
type SimCase = (&'static str, fn() -> CScene, fn() -> SimScene, usize);

/// The four reference scenes through the `Simulation` layer, the 100-body pile run for
/// `pile_steps` steps.
fn reference_sim_scenes(pile_steps: usize) -> [SimCase; 4] {
    [
        ("falling sphere", CScene::falling_sphere, SimScene::falling_sphere, 2500),
        ("drop pile", || CScene::drop_pile(100), || SimScene::drop_pile(100), pile_steps),
        ("conical pendulum", CScene::conical_pendulum, SimScene::conical_pendulum, 2500),
        ("mobile manipulator", CScene::speed_profile, SimScene::mobile_manipulator, 2500),
    ]
}

#[test]
fn the_simulation_layer_bench_scenes_are_bit_identical_to_native_ode() {
    // What `benches/step_cost.rs` measures must be the same work as its C twin.
    let cases = reference_sim_scenes(300);
    for (name, c, sim, steps) in cases {
        let (mut c, mut sim) = (c(), sim());
        assert_eq!(c.body_count(), sim.sim.scene().bodies().count(), "{name}: body count");
        for step in 1..=steps {
            c.step(1);
            sim.step(1);
            for i in 0..c.body_count() {
                let (cs, rs) = (c.body_state(i), sim.body_state(i));
                assert!(same_bits(&cs, &rs), "{name}: body {i} differs after step {step}:\n C   {cs:?}\n Rust {rs:?}");
            }
        }
    }
}

/// The near callback is written twice: in C (`plain_near` in ode-sys's `guard.c`, the
/// path a plain `Simulation` step takes) and in Rust (`World::near`, taken when a world
/// has rays, collision hooks or contact feedback). Every reference scene is run here
/// through the Rust one (contact feedback on: it only records forces) against its
/// native C twin, as the test above runs them through the C one: both paths are held to
/// native ODE's bits on the same scenes.
#[test]
fn the_rust_near_callback_steps_every_reference_scene_as_native_ode_does() {
    // The pile long enough for its bodies to land (contacts through the callback).
    let cases = reference_sim_scenes(1500);
    for (name, c, sim, steps) in cases {
        let (mut c, mut sim) = (c(), sim());
        sim.sim.scene_mut().world_mut().set_contact_feedback(true);
        let mut touched = false;
        for step in 1..=steps {
            c.step(1);
            sim.step(1);
            touched |= !sim.sim.scene().world().contacts().is_empty();
            for i in 0..c.body_count() {
                let (cs, rs) = (c.body_state(i), sim.body_state(i));
                assert!(same_bits(&cs, &rs), "{name}: body {i} differs after step {step}:\n C   {cs:?}\n Rust {rs:?}");
            }
        }
        assert!(touched || name == "conical pendulum", "{name}: the scene's contacts went through the Rust callback");
    }
}

#[test]
fn the_comparison_notices_a_difference_of_one_part_in_a_trillion() {
    // A negative control: the same ball started 1e-12 m higher must not pass as identical.
    let mut c = CScene::falling_sphere();
    let mut rust = RustScene::falling_sphere();
    let ball = rust.bodies[0];
    let mut body = rust.world.body_mut(ball).unwrap();
    let p = body.position();
    body.set_position(p + ars_core::nalgebra::Vector3::new(0.0, 1e-12, 0.0)).unwrap();
    c.step(1);
    rust.step(1);
    assert_ne!(c.body_state(0)[1].to_bits(), rust.body_state(0)[1].to_bits());
}

fn body_state(sim: &ars::Simulation, object: ars::ObjectId) -> BodyState {
    let b = sim.scene().body(object).unwrap();
    let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
    [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z]
}

fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn two_ball_laser_program_is_bit_identical_to_native_ode_for_two_seconds() {
    use ars_programs::TwoBallLaser;
    let mut program = TwoBallLaser::default();
    let mut runner = ars::ProgramRunner::new(&mut program).unwrap();
    let mut c = CScene::two_ball_laser();
    let laser = runner.program().laser.unwrap();
    let balls = [runner.program().ball1.unwrap(), runner.program().ball2.unwrap()];
    let mut hits = 0;
    for step in 1..=5000 {
        runner.step().unwrap();
        c.step(1);
        let sim = runner.simulation();
        for (i, ball) in balls.iter().enumerate() {
            let (rs, cs) = (body_state(sim, *ball), c.body_state(i));
            assert!(same_bits(&rs, &cs), "ball {i} differs after step {step}:\n C    {cs:?}\n Rust {rs:?}");
        }
        let reading = sim.records(laser).unwrap().last().unwrap().record.distance;
        assert_eq!(reading.map(f64::to_bits), c.ray_distance().map(f64::to_bits), "laser after step {step}");
        assert_eq!(sim.scene().time().to_bits(), c.time().to_bits());
        hits += usize::from(reading.is_some());
    }
    assert!(hits > 4000, "the laser sees the balls most of the time ({hits} steps)");
}

#[test]
fn conical_pendulum_program_is_bit_identical_to_native_ode_for_two_seconds() {
    use ars_programs::ConicalPendulum;
    let mut program = ConicalPendulum::default();
    let mut runner = ars::ProgramRunner::new(&mut program).unwrap();
    let mut c = CScene::conical_pendulum();
    let p = runner.program();
    let bodies = [p.base.unwrap(), p.pole.unwrap(), p.arm.unwrap()];
    for step in 1..=8000 {
        runner.step().unwrap();
        c.step(1);
        for (i, body) in bodies.iter().enumerate() {
            let (rs, cs) = (body_state(runner.simulation(), *body), c.body_state(i));
            assert!(same_bits(&rs, &cs), "body {i} differs after step {step}:\n C    {cs:?}\n Rust {rs:?}");
        }
    }
    // The waist has spun up: 2 s of a torque ramping to 20 N·m against 5 N·m·s friction.
    let record = runner.program().record.unwrap();
    let last = runner.simulation().records(record).unwrap().last().unwrap().record;
    assert!(last.q1_rate.abs() > 1.0, "{last:?}");
}

#[test]
fn falling_ball_program_is_bit_identical_to_native_ode() {
    use ars_programs::FallingBallSensors;
    let mut program = FallingBallSensors::default();
    let mut runner = ars::ProgramRunner::new(&mut program).unwrap();
    let mut c = CScene::falling_sphere();
    let ball = runner.program().ball.unwrap();
    for step in 1..=2500 {
        runner.step().unwrap();
        c.step(1);
        let (rs, cs) = (body_state(runner.simulation(), ball), c.body_state(0));
        assert!(same_bits(&rs, &cs), "after step {step}:\n C    {cs:?}\n Rust {rs:?}");
    }
}

fn assert_rows_bit_identical<P: ars::Program>(
    name: &str,
    mut program: P,
    mut c: CScene,
    seconds: f64,
    row: impl Fn(&ars::Simulation, &P) -> [f64; 9],
) {
    let mut runner = ars::ProgramRunner::new(&mut program).unwrap();
    let steps = runner.simulation().scene().steps_in(seconds).unwrap();
    for step in 1..=steps {
        runner.step().unwrap();
        c.step(1);
        let (rust, native) = (row(runner.simulation(), runner.program()), c.row());
        assert!(same_bits(&rust, &native), "{name}: CSV row of step {step} differs:\n C    {native:?}\n Rust {rust:?}");
        for i in 0..c.body_count() {
            let b = runner.simulation().scene().world().bodies().nth(i).unwrap();
            let body = runner.simulation().scene().world().body(b).unwrap();
            let (p, v) = (body.position(), body.linear_velocity());
            let rs = [p.x, p.y, p.z, v.x, v.y, v.z];
            let cs = c.body_state(i);
            let cs = [cs[0], cs[1], cs[2], cs[7], cs[8], cs[9]];
            assert!(same_bits(&rs, &cs), "{name}: body {i} differs after step {step}");
        }
    }
}

#[test]
fn example_3_speed_profile_csv_is_bit_identical_to_native_ode_for_three_seconds() {
    use ars_programs::SpeedProfile;
    assert_rows_bit_identical("example 3", SpeedProfile::default(), CScene::speed_profile(), 3.0, |sim, p| {
        let s = sim.records(p.record.unwrap()).unwrap().last().unwrap();
        let r = s.record;
        [s.time, r.x, r.setpoint, r.speed, r.wheel_torque, r.q1, r.q1_rate, r.q2, r.q2_rate]
    });
}

#[test]
fn example_4_sinusoidal_terrain_csv_is_bit_identical_to_native_ode_for_three_seconds() {
    use ars_programs::SinusoidalTerrain;
    assert_rows_bit_identical(
        "example 4",
        SinusoidalTerrain::default(),
        CScene::sinusoidal_terrain(),
        3.0,
        |sim, p| {
            let s = sim.records(p.record.unwrap()).unwrap().last().unwrap();
            let r = s.record;
            [s.time, r.position.x, r.position.y, r.position.z, r.q1, r.torque1, r.q2, r.torque2, r.wheel_torque]
        },
    );
}

/// The thesis programs choose the original's simple space themselves, whatever builder
/// they are given (a new simulation's default is the grid, whose pair order
/// differs): this is what keeps the programs above bit for bit with their C twins.
#[test]
fn every_thesis_program_builds_the_simple_space_from_any_builder() {
    use ars::{Program, Simulation, SpaceKind};
    use ars_programs::*;
    fn check<P: Program>(name: &str, mut program: P) {
        for builder in [Simulation::builder(), Simulation::builder().space(SpaceKind::SWEEP_AND_PRUNE)] {
            let sim = program.configure(builder).build().unwrap();
            assert_eq!(sim.scene().space_kind(), SpaceKind::Simple, "{name}");
        }
        assert_eq!(program.create_simulation().unwrap().scene().space_kind(), SpaceKind::Simple, "{name}");
    }
    check("HelloWorld", HelloWorld::default());
    check("FallingBallSensors", FallingBallSensors::default());
    check("FallingBalls", FallingBalls::default());
    check("TwoBallLaser", TwoBallLaser::default());
    check("SimpleArm", SimpleArm::default());
    check("ControlledSimpleArm", ControlledSimpleArm::default());
    check("CentrifugalForce", CentrifugalForce::default());
    check("ConicalPendulum", ConicalPendulum::default());
    check("BouncingBall", BouncingBall::default());
    check("Vehicle1", Vehicle1::default());
    check("Vehicle2", Vehicle2::default());
    check("VehicleWithArm", VehicleWithArm::default());
    check("VehicleWithControlledArm", VehicleWithControlledArm::default());
    check("SpeedProfile", SpeedProfile::default());
    check("SinusoidalTerrain", SinusoidalTerrain::default());
    check("UserDriven", UserDriven::default());
    check("Convoy", Convoy::default());
}
