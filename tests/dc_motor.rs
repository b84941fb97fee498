//! The DC motor actuator against its analytic responses: a flywheel on a hinge driven
//! by a voltage step speeds up as `ω∞·(1 − e^(−t/τ))`, with an error proportional to
//! the time step; the winding current of a stalled motor with inductance rises as
//! `V/R·(1 − e^(−t·R/L))`.

use ars::nalgebra::Vector3;
use ars::{DcMotor, JointEnd, Mass, Profile, Simulation};

/// The motor's constants: torque and back-EMF constants, resistance, gear ratio,
/// rotor friction; the step of voltage.
const KT: f64 = 0.05;
const KE: f64 = 0.05;
const R: f64 = 2.0;
const N: f64 = 10.0;
const B: f64 = 1e-4;
const V: f64 = 6.0;
/// The flywheel: a 2 kg disc of radius 0.2 m turning about its axis (I = m·r²/2).
const MASS: f64 = 2.0;
const RADIUS: f64 = 0.2;

/// The largest difference between the simulated joint rate and the analytic
/// first-order response over three time constants, at time step `dt`.
fn largest_error(dt: f64) -> (f64, f64) {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).time_step(dt).build().unwrap();
    let wheel = sim.scene_mut().add_cylinder(RADIUS, 0.05, [0.0, 1.0, 0.0], Mass::Total(MASS)).unwrap();
    let hinge = sim.scene_mut().add_hinge_joint("axle", wheel, JointEnd::World, None, Vector3::z()).unwrap();
    let motor = DcMotor::new(Profile::constant(V).unwrap(), KT, KE, R, N, 0.0).unwrap().with_friction(B).unwrap();
    sim.scene_mut().joint_mut(hinge).unwrap().set_controller(motor).unwrap();
    let inertia = MASS * RADIUS * RADIUS / 2.0;
    let damping = N * N * (KT * KE + R * B);
    let (final_rate, tau) = (N * KT * V / damping, inertia * R / damping);
    let mut worst: f64 = 0.0;
    while sim.scene().time() < 3.0 * tau {
        sim.step().unwrap();
        let analytic = final_rate * (1.0 - (-sim.scene().time() / tau).exp());
        worst = worst.max((sim.scene().joint_rate(hinge).unwrap() - analytic).abs());
    }
    (worst / final_rate, tau)
}

#[test]
fn a_voltage_step_speeds_a_flywheel_up_as_the_analytic_first_order_response() {
    // τ = 0.04 · 2 / (100 · (0.0025 + 0.0002)) ≈ 0.296 s.
    let (coarse, tau) = largest_error(0.004);
    let (fine, _) = largest_error(0.002);
    let (finer, _) = largest_error(0.001);
    assert!((0.29..0.30).contains(&tau), "τ = {tau}");
    eprintln!(
        "τ = {tau:.4} s; largest errors / final rate: {coarse:.3e} (4 ms), {fine:.3e} (2 ms), {finer:.3e} (1 ms)"
    );
    // Within the discretisation error (the torque is held over each step): below 1 %
    // at dt = τ/74, and halving with the step.
    assert!(coarse < 0.01, "largest error {coarse} of the final rate");
    for (a, b) in [(coarse, fine), (fine, finer)] {
        let ratio = a / b;
        assert!((1.8..2.2).contains(&ratio), "errors {a} and {b}: ratio {ratio}, not ∝ dt");
    }
}

#[test]
fn the_current_of_a_stalled_motor_rises_with_the_winding_time_constant() {
    use ars::{JointController, JointState};
    let inductance = 0.01;
    let mut motor =
        DcMotor::new(Profile::constant(V).unwrap(), KT, KE, R, N, 0.0).unwrap().with_inductance(inductance).unwrap();
    let dt = 0.0004;
    let stalled = JointState::default();
    let mut previous = 0.0;
    for k in 1..=100 {
        let torque = motor.output(0.0, stalled, dt);
        let t = f64::from(k) * dt;
        let analytic = V / R * (1.0 - (-t * R / inductance).exp());
        assert!((motor.winding_current() - analytic).abs() < 1e-12, "at {t} s");
        // The step's torque comes from the mean current over the step.
        assert!(torque > N * KT * previous && torque < N * KT * analytic, "at {t} s");
        previous = analytic;
    }
    assert!(DcMotor::new(Profile::constant(V).unwrap(), KT, KE, R, N, 0.0).unwrap().with_inductance(-1.0).is_err());
    assert!(DcMotor::new(Profile::constant(V).unwrap(), KT, KE, R, N, 0.0).unwrap().with_friction(f64::NAN).is_err());
}
