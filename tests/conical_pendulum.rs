//! The thesis' validation robot (IROS example 2) against the thesis, the steady-state
//! formula and an independent reduced-coordinate model of the same arm.

use ars::{Hooks, Program, Sample, SimulationBuilder};
use ars_programs::{ArmParameters, ConicalPendulum, PendulumRow, ReducedArmModel};

/// The conical pendulum at a chosen time step (the original's is 0.25 ms).
struct AtTimeStep(ConicalPendulum, f64);

impl Hooks for AtTimeStep {
    fn pre_step(&mut self, sim: &mut ars::Simulation) -> ars::Result<()> {
        self.0.pre_step(sim)
    }
}

impl Program for AtTimeStep {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        self.0.configure(builder).time_step(self.1)
    }
    fn create_sim_objects(&mut self, sim: &mut ars::Simulation) -> ars::Result<()> {
        self.0.create_sim_objects(sim)
    }
}

fn run(dt: f64, seconds: f64) -> Vec<Sample<PendulumRow>> {
    let mut program = AtTimeStep(ConicalPendulum::default(), dt);
    let sim = program.run_headless(seconds).unwrap();
    assert!((sim.scene().time() - seconds).abs() < 1e-6);
    sim.records(program.0.record.unwrap()).unwrap().samples().to_vec()
}

/// Largest |ODE − model| of the shoulder angle and of the waist rate, sampled every
/// 10 ms over the run.
fn gaps(rows: &[Sample<PendulumRow>], dt: f64, model: &[ars_programs::ArmState]) -> (f64, f64) {
    let every = (0.01 / dt).round() as usize;
    let (mut beta, mut rate) = (0.0f64, 0.0f64);
    for (k, m) in model.iter().enumerate() {
        let Some(row) = rows.get(k * every) else { break };
        assert!((row.time - m.time).abs() < 1e-6, "sample times {} vs {}", row.time, m.time);
        beta = beta.max((row.record.q2 - m.beta).abs());
        rate = rate.max((row.record.q1_rate - m.phi_rate).abs());
    }
    (beta, rate)
}

#[test]
fn the_waist_and_shoulder_settle_where_the_thesis_says() {
    let rows = run(0.00025, 20.0);
    let last = rows.last().unwrap().record;
    assert!((last.q1_rate - 3.9994).abs() < 2e-4, "waist rate {}", last.q1_rate);
    assert!((last.q2 - 0.7115).abs() < 5e-4, "shoulder angle {}", last.q2);
    // Thesis: "from π/2 to about 0.87 rad" in its DH convention: π/2 − q2.
    assert!((std::f64::consts::FRAC_PI_2 - last.q2 - 0.859).abs() < 1e-3);

    // The distributed-mass steady state, at the rate ODE reached: 0.7118 rad at 4 rad/s.
    let p = ArmParameters::IROS_EXAMPLE_2;
    assert!((p.steady_shoulder_angle(4.0) - 0.7118).abs() < 1e-4);
    let analytic = p.steady_shoulder_angle(last.q1_rate);
    assert!((last.q2 - analytic).abs() < 5e-4, "ODE {} vs formula {analytic}", last.q2);
    // The thesis' point-mass formula taken literally (tan β / (a1 + a2 sin β) = ω²/g
    // with a2 = 1) gives 0.99 rad: it is not what ODE or the formula above give.
    let point_mass = ArmParameters { radius: 0.0, length: 1.5, ..p }.steady_shoulder_angle(4.0);
    assert!((point_mass - last.q2).abs() > 0.2);
}

#[test]
fn ode_agrees_with_the_reduced_model_and_converges_as_dt_shrinks() {
    let model = ReducedArmModel::trajectory(ArmParameters::IROS_EXAMPLE_2, 20.0, 0.01, 0.001);
    let mut results = Vec::new();
    for dt in [0.0005, 0.00025, 0.000125] {
        let rows = run(dt, 20.0);
        results.push((dt, gaps(&rows, dt, &model)));
    }
    eprintln!("dt, max |β_ODE − β_model| [rad], max |φ̇_ODE − φ̇_model| [rad/s]: {results:?}");
    let (_, (beta, rate)) = results[1];
    assert!(beta < 1e-3, "shoulder gap {beta} rad at dt 0.25 ms");
    assert!(rate < 3e-3, "waist-rate gap {rate} rad/s at dt 0.25 ms");
    // First order in dt: halving dt roughly halves the gap (ratios between 1.5 and 2.5).
    for w in results.windows(2) {
        let (b0, r0) = w[0].1;
        let (b1, r1) = w[1].1;
        assert!((1.5..2.5).contains(&(b0 / b1)), "shoulder gap ratio {} ({results:?})", b0 / b1);
        assert!((1.5..2.5).contains(&(r0 / r1)), "waist gap ratio {} ({results:?})", r0 / r1);
    }
}
