//! The dynamics of an imported robot against an independent reduced-coordinate model
//! of the same URDF: a recursive Newton–Euler computation (in the URDF's own Z-up
//! frame, from the file parsed separately), integrated with RK4 at a fine step. The
//! robot falls under gravity for 1 s from a bent pose; ODE's gap to the model must be
//! small and shrink in proportion to the time step (`dWorldStep` is first order).

use ars::nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Vector3};
use ars::{Simulation, UrdfOptions};

const ARM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/rnea_arm.urdf");
const Q0: [f64; 3] = [0.4, 0.9, -0.7];

/// One moving link of the chain, as the file describes it.
struct Link {
    /// Joint origin relative to the parent link frame.
    origin: (Rotation3<f64>, Vector3<f64>),
    /// Unit joint axis in the joint (child link) frame.
    axis: Vector3<f64>,
    /// Inertial frame relative to the link frame.
    inertial: (Rotation3<f64>, Vector3<f64>),
    mass: f64,
    /// Inertia tensor in the inertial frame.
    inertia: Matrix3<f64>,
}

fn rpy(r: [f64; 3]) -> Rotation3<f64> {
    Rotation3::from_euler_angles(r[0], r[1], r[2]) // Rz(yaw) Ry(pitch) Rx(roll), as URDF
}

/// The serial chain base → j1 → j2 → j3 read from the URDF with urdf-rs.
fn chain() -> Vec<Link> {
    let robot = urdf_rs::read_file(ARM).unwrap();
    robot
        .joints
        .iter()
        .map(|j| {
            let link = robot.links.iter().find(|l| l.name == j.child.link).unwrap();
            let i = &link.inertial.inertia;
            Link {
                origin: (rpy(j.origin.rpy.0), Vector3::from(j.origin.xyz.0)),
                axis: Vector3::from(j.axis.xyz.0).normalize(),
                inertial: (rpy(link.inertial.origin.rpy.0), Vector3::from(link.inertial.origin.xyz.0)),
                mass: link.inertial.mass.value,
                inertia: Matrix3::new(i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz),
            }
        })
        .collect()
}

/// Joint torques for (q, q̇, q̈) under gravity (0, 0, −9.81), by recursive Newton–Euler
/// in the world frame of a fixed base.
fn rnea(chain: &[Link], q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    let g = Vector3::new(0.0, 0.0, -9.81);
    let n = chain.len();
    let (mut rot, mut pos) = (Rotation3::identity(), Vector3::zeros());
    let (mut w, mut wd, mut acc) = (Vector3::zeros(), Vector3::zeros(), -g); // acceleration of the frame origin
    let mut frames = Vec::new();
    for (k, l) in chain.iter().enumerate() {
        // Joint frame k in the world, then the joint's motion.
        let p_new = pos + rot * l.origin.1;
        let r_joint = rot * l.origin.0;
        let z = r_joint * l.axis;
        let d = p_new - pos;
        acc += wd.cross(&d) + w.cross(&w.cross(&d));
        let w_new = w + z * qd[k];
        wd = wd + z * qdd[k] + w.cross(&(z * qd[k]));
        w = w_new;
        rot = r_joint * Rotation3::from_axis_angle(&ars::nalgebra::Unit::new_normalize(l.axis), q[k]);
        pos = p_new;
        let c = pos + rot * l.inertial.1;
        let r_in = rot * l.inertial.0;
        let inertia = r_in.matrix() * l.inertia * r_in.matrix().transpose();
        let ac = acc + wd.cross(&(c - pos)) + w.cross(&w.cross(&(c - pos)));
        frames.push((pos, z, c, inertia, w, wd, ac));
    }
    let mut tau = vec![0.0; n];
    let (mut f_next, mut n_next, mut p_next) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
    for k in (0..n).rev() {
        let (p, z, c, inertia, w, wd, ac) = frames[k];
        let m = chain[k].mass;
        let f = ac * m + f_next;
        let mut torque = inertia * wd + w.cross(&(inertia * w)) + n_next + (c - p).cross(&(ac * m));
        if k + 1 < n {
            torque += (p_next - p).cross(&f_next);
        }
        tau[k] = torque.dot(&z);
        (f_next, n_next, p_next) = (f, torque, p);
    }
    tau
}

/// q̈ = M(q)⁻¹ (−b(q, q̇)) with no joint torques.
fn forward(chain: &[Link], q: &[f64], qd: &[f64]) -> Vec<f64> {
    let n = q.len();
    let zero = vec![0.0; n];
    let bias = DVector::from_vec(rnea(chain, q, qd, &zero));
    let gravity = rnea(chain, q, &zero, &zero);
    let mut m = DMatrix::zeros(n, n);
    for k in 0..n {
        let mut e = zero.clone();
        e[k] = 1.0;
        let col = rnea(chain, q, &zero, &e);
        for r in 0..n {
            m[(r, k)] = col[r] - gravity[r];
        }
    }
    m.lu().solve(&(-bias)).unwrap().as_slice().to_vec()
}

/// The model's joint angles after `seconds`, RK4 with step `h`.
fn model(seconds: f64, h: f64) -> Vec<f64> {
    let chain = chain();
    let n = chain.len();
    let mut x: Vec<f64> = Q0.iter().copied().chain(std::iter::repeat_n(0.0, n)).collect();
    let f = |x: &[f64]| -> Vec<f64> {
        let (q, qd) = x.split_at(n);
        qd.iter().copied().chain(forward(&chain, q, qd)).collect()
    };
    let axpy = |x: &[f64], k: &[f64], a: f64| -> Vec<f64> { x.iter().zip(k).map(|(x, k)| x + a * k).collect() };
    for _ in 0..(seconds / h).round() as usize {
        let k1 = f(&x);
        let k2 = f(&axpy(&x, &k1, h / 2.0));
        let k3 = f(&axpy(&x, &k2, h / 2.0));
        let k4 = f(&axpy(&x, &k3, h));
        for i in 0..x.len() {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    x[..n].to_vec()
}

/// ODE's joint angles after `seconds` at time step `dt`, the file loaded by ARS.
fn ars(seconds: f64, dt: f64) -> Vec<f64> {
    let mut sim = Simulation::builder().time_step(dt).build().unwrap();
    let mut options = UrdfOptions::new().fixed_base(true);
    for (name, q) in ["j1", "j2", "j3"].iter().zip(Q0) {
        options = options.initial_position(name, q);
    }
    sim.load_urdf(ARM, &options).unwrap();
    sim.run_for(seconds).unwrap();
    ["j1", "j2", "j3"].iter().map(|j| sim.scene().joint(*j).unwrap().state().unwrap().position).collect()
}

#[test]
fn the_imported_arm_falls_as_the_reduced_coordinate_model_says_and_the_gap_shrinks_with_dt() {
    let reference = model(1.0, 2e-4);
    // The model is converged: halving its step changes nothing that matters here.
    let finer = model(1.0, 1e-4);
    let model_error = reference.iter().zip(&finer).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(model_error < 1e-9, "RK4 reference not converged: {model_error}");
    // It moved: every joint left its starting angle.
    assert!(reference.iter().zip(Q0).all(|(q, q0)| (q - q0).abs() > 0.05), "{reference:?}");

    let gap = |dt: f64| ars(1.0, dt).iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let gaps: Vec<(f64, f64)> = [4e-4, 2e-4, 1e-4].iter().map(|&dt| (dt, gap(dt))).collect();
    eprintln!("largest joint-angle gap to the model after 1 s, by time step: {gaps:?}");
    assert!(gaps[0].1 < 0.05, "ODE follows the model: {gaps:?}");
    for w in gaps.windows(2) {
        let ratio = w[0].1 / w[1].1;
        assert!((1.6..2.5).contains(&ratio), "halving dt halves the gap (first order): {gaps:?}");
    }
}
