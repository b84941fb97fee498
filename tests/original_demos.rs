//! The original's other demos (ars-original §8.2–8.5, §8.18) run and behave as their
//! documentation says.

use ars::{Key, Program, ProgramRunner};
use ars_programs::{CentrifugalForce, ControlledSimpleArm, FallingBalls, SimpleArm};

#[test]
fn falling_balls_land_when_free_fall_says() {
    let mut program = FallingBalls::default();
    let sim = program.run_headless(1.5).unwrap();
    // Drop height = start − radius; first contact at sqrt(2 h / g).
    for ((ball, gps), (y0, r)) in program.balls.iter().zip([(6.0, 0.3), (4.0, 0.5), (2.0, 0.2)]) {
        let log = sim.records(*gps).unwrap();
        let landed = log.iter().find(|s| s.record.position.y < r + 1e-3).map(|s| s.time);
        let expected = (2.0 * (y0 - r) / 9.81f64).sqrt();
        // Every ball lands within the 1.5 s run (the highest at 1.08 s).
        let landed = landed.unwrap_or_else(|| panic!("ball from {y0} never landed"));
        assert!((landed - expected).abs() < 0.01, "ball from {y0}: {landed} vs {expected}");
        assert!(sim.scene().body(*ball).is_ok());
    }
    let masses: Vec<f64> = program.balls.iter().map(|(b, _)| sim.scene().body(*b).unwrap().mass()).collect();
    assert!((masses[0] - 0.1131).abs() < 1e-4 && (masses[1] - 0.2618).abs() < 1e-4 && masses[2] == 5.0, "{masses:?}");
}

#[test]
fn the_centrifugal_ball_settles_at_the_cable_angle_of_the_formula() {
    let mut program = CentrifugalForce::default();
    let sim = program.run_headless(30.0).unwrap();
    let expected = CentrifugalForce::steady_angle(3.0);
    assert!((expected - 1.0415).abs() < 1e-4, "{expected}");
    let frames = sim.records(program.record.unwrap()).unwrap();
    assert_eq!(frames.len(), 30 * 50, "one record per frame");
    assert!(frames.iter().enumerate().all(|(k, s)| s.step == 20 * k as u64), "at the start of each frame");
    let last = frames.last().unwrap().record;
    assert!((last.theta - expected).abs() < 0.01, "θ = {} vs {expected}", last.theta);
    // The sensor demos: the friction torque acts on the first step of each frame only,
    // and its power is never positive.
    let (torque, power, angle) = program.sensors.unwrap();
    let t = sim.records(torque).unwrap();
    let nonzero = t.iter().filter(|s| s.record.value != 0.0).count();
    assert!(nonzero <= t.len() / 20 + 1, "{nonzero} of {}", t.len());
    assert!(sim.records(power).unwrap().iter().all(|s| s.record.power <= 0.0));
    assert_eq!(sim.records(angle).unwrap().len(), 30 * 50, "one angle per frame");
}

#[test]
fn the_simple_arm_turns_when_a_key_pushes_it() {
    let mut program = SimpleArm::default();
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    runner.run_for(0.5).unwrap();
    let r1 = runner.program().parts.unwrap().r1;
    let still = runner.simulation().scene().joint_state(r1).unwrap().rate;
    for _ in 0..10 {
        runner.key_down(Key::Char('a')).unwrap();
        runner.step_frame().unwrap();
    }
    let turned = runner.simulation().scene().joint_state(r1).unwrap().rate;
    assert!(still.abs() < 1e-6 && turned.abs() > 0.1, "waist rate {still} then {turned}");
}

#[test]
fn the_controlled_arm_holds_and_follows_its_shoulder_set_point() {
    let mut program = ControlledSimpleArm::default();
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    runner.run_for(3.0).unwrap();
    let r2 = runner.program().parts.unwrap().r2;
    let q = runner.simulation().scene().joint_state(r2).unwrap().position;
    assert!(q.abs() < 0.05, "held near upright: {q}");
    for _ in 0..3 {
        runner.key_down(Key::Char('d')).unwrap();
    }
    runner.run_for(10.0).unwrap();
    let q = runner.simulation().scene().joint_state(r2).unwrap().position;
    let record = runner.program().record.unwrap();
    let last = runner.simulation().records(record).unwrap().last().unwrap().record;
    assert!((last.setpoint - 0.3).abs() < 1e-12, "three 'd' presses: {last:?}");
    assert!((q - 0.3).abs() < 0.1, "follows the set-point 0.3: {q} ({last:?})");
}

#[test]
fn the_bouncing_ball_bounces_when_the_code_and_the_paper_say() {
    use ars_programs::BouncingBall;
    let mut code = BouncingBall::default();
    let code_sim = code.run_headless(0.7).unwrap();
    let mut paper = BouncingBall { paper_bounce: true, ..Default::default() };
    let paper_sim = paper.run_headless(3.5).unwrap();
    for (program, sim, ideal) in [
        (&code, &code_sim, &[0.4515, 0.632, 0.668][..]),
        (&paper, &paper_sim, &[0.4515, 1.264, 1.996, 2.654, 3.247][..]),
    ] {
        let times = BouncingBall::bounce_times(sim.records(program.record.unwrap()).unwrap());
        assert!(times.len() >= ideal.len(), "{times:?}");
        for (t, i) in times.iter().zip(ideal) {
            assert!((t - i).abs() < 2e-3, "bounce at {t} s, ideal {i} s");
        }
    }
}
