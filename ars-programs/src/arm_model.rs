//! An independent model of the conical pendulum: the 2-DOF arm of IROS example 2 in
//! reduced coordinates (waist angle φ, shoulder angle β), from its Lagrangian, with
//! ODE's mass properties, integrated with the classic fourth-order Runge–Kutta method.
//! It shares nothing with ODE but the parameters, so agreement between the two is a
//! check of both.
//!
//! With `m`, `L`, `ρ` the mass, length and radius of each link (solid cylinders: axial
//! inertia `I_a = m ρ²/2`, transverse `I_t = m (3ρ² + L²)/12`), `a1` the shoulder's offset
//! from the waist axis and `d = L/2` the arm's centre of mass below the shoulder:
//!
//! ```text
//! r(β)  = a1 + d sin β                                   (COM distance from the axis)
//! J(β)  = I_a(pole) + m r² + I_a cos²β + I_t sin²β       (inertia about the waist axis)
//! J'(β) = 2 m r d cos β + 2 (I_t − I_a) sin β cos β
//! J φ̈ + J' β̇ φ̇            = τ(t) − c φ̇
//! (m d² + I_t) β̈ − ½ J' φ̇² + m g d sin β = −c β̇
//! ```
//!
//! The base is taken as fixed (in ODE it is a free 5000 kg box resting on the floor).
//! In steady state `φ̇ = τ/c` and `tan β = (φ̇²/g) (a1 + (2L/3 − ρ²/(2L)) sin β)`.

use crate::ConicalPendulum;

/// Parameters of the arm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmParameters {
    /// Mass of each link, kg.
    pub mass: f64,
    /// Length of each link, m.
    pub length: f64,
    /// Radius of each link, m.
    pub radius: f64,
    /// Horizontal offset of the shoulder from the waist axis, m.
    pub offset: f64,
    /// Viscous friction of both joints, N·m·s.
    pub friction: f64,
    /// Gravity, m/s².
    pub gravity: f64,
}

impl ArmParameters {
    /// IROS example 2.
    pub const IROS_EXAMPLE_2: ArmParameters = ArmParameters {
        mass: 10.0,
        length: 1.0,
        radius: 0.141421,
        offset: 0.1,
        friction: ConicalPendulum::FRICTION,
        gravity: 9.81,
    };

    fn axial(&self) -> f64 {
        self.mass * self.radius * self.radius / 2.0
    }

    fn transverse(&self) -> f64 {
        self.mass * (3.0 * self.radius * self.radius + self.length * self.length) / 12.0
    }

    /// Steady shoulder angle at waist rate `omega` (the uniform-rod formula, solved by
    /// fixed-point iteration), rad.
    pub fn steady_shoulder_angle(&self, omega: f64) -> f64 {
        let l = self.length;
        let lever = 2.0 * l / 3.0 - self.radius * self.radius / (2.0 * l);
        let k = omega * omega / self.gravity;
        let mut beta: f64 = 0.5;
        for _ in 0..200 {
            beta = (k * (self.offset + lever * beta.sin())).atan();
        }
        beta
    }
}

/// State of the reduced model.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ArmState {
    /// Time, s.
    pub time: f64,
    /// Waist angle, rad.
    pub phi: f64,
    /// Shoulder angle from hanging (outward positive), rad.
    pub beta: f64,
    /// Waist rate, rad/s.
    pub phi_rate: f64,
    /// Shoulder rate, rad/s.
    pub beta_rate: f64,
}

/// The reduced-coordinate arm, driven by the example's waist torque.
#[derive(Clone, Debug)]
pub struct ReducedArmModel {
    /// Its parameters.
    pub parameters: ArmParameters,
    /// Its current state.
    pub state: ArmState,
}

impl ReducedArmModel {
    /// At rest, hanging, at t = 0.
    pub fn new(parameters: ArmParameters) -> Self {
        ReducedArmModel { parameters, state: ArmState::default() }
    }

    /// `[φ̈, β̈]` at time `t` in state `(β, φ̇, β̇)`.
    fn accelerations(&self, t: f64, beta: f64, phi_rate: f64, beta_rate: f64) -> (f64, f64) {
        let p = &self.parameters;
        let (m, d) = (p.mass, p.length / 2.0);
        let (ia, it) = (p.axial(), p.transverse());
        let (s, c) = beta.sin_cos();
        let r = p.offset + d * s;
        let j = ia + m * r * r + ia * c * c + it * s * s;
        let dj = 2.0 * m * r * d * c + 2.0 * (it - ia) * s * c;
        let tau = ConicalPendulum::waist_torque(t);
        let phi_acc = (tau - p.friction * phi_rate - dj * beta_rate * phi_rate) / j;
        let beta_acc =
            (0.5 * dj * phi_rate * phi_rate - m * p.gravity * d * s - p.friction * beta_rate) / (m * d * d + it);
        (phi_acc, beta_acc)
    }

    /// Advances by `h` seconds with one Runge–Kutta step (4th order).
    pub fn step(&mut self, h: f64) {
        let s = self.state;
        let f = |t: f64, y: [f64; 4]| -> [f64; 4] {
            let (a_phi, a_beta) = self.accelerations(t, y[1], y[2], y[3]);
            [y[2], y[3], a_phi, a_beta]
        };
        let y0 = [s.phi, s.beta, s.phi_rate, s.beta_rate];
        let add = |y: [f64; 4], k: [f64; 4], w: f64| std::array::from_fn::<f64, 4, _>(|i| y[i] + w * k[i]);
        let k1 = f(s.time, y0);
        let k2 = f(s.time + h / 2.0, add(y0, k1, h / 2.0));
        let k3 = f(s.time + h / 2.0, add(y0, k2, h / 2.0));
        let k4 = f(s.time + h, add(y0, k3, h));
        let y: [f64; 4] = std::array::from_fn(|i| y0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        self.state = ArmState { time: s.time + h, phi: y[0], beta: y[1], phi_rate: y[2], beta_rate: y[3] };
    }

    /// States every `sample` seconds from 0 to `duration` inclusive, integrating with
    /// steps of `h` (which must divide `sample`).
    pub fn trajectory(parameters: ArmParameters, duration: f64, sample: f64, h: f64) -> Vec<ArmState> {
        let mut model = ReducedArmModel::new(parameters);
        let per_sample = (sample / h).round() as usize;
        let samples = (duration / sample).round() as usize;
        let mut out = vec![model.state];
        for k in 1..=samples {
            for _ in 0..per_sample {
                model.step(h);
            }
            // Keep the sample times exact multiples (no accumulated drift).
            model.state.time = k as f64 * sample;
            out.push(model.state);
        }
        out
    }
}
