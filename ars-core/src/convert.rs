//! Conversions between ODE's arrays and the nalgebra types of the public API, in one
//! place. ODE stores quaternions as `[w, x, y, z]` and rotation matrices as 3×4
//! row-major arrays (`dMatrix3`, the fourth column is padding).

use nalgebra::{Matrix3, Point3, Quaternion, Rotation3, UnitQuaternion, Vector3};
use ode_sys::{dMatrix3, dQuaternion, dReal, dVector3};

/// nalgebra vector from the first three entries of an ODE vector.
pub fn vector_from_ode(v: &[dReal]) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2])
}

/// nalgebra point from the first three entries of an ODE vector.
pub fn point_from_ode(v: &[dReal]) -> Point3<f64> {
    Point3::new(v[0], v[1], v[2])
}

/// ODE `dVector3` (padded with a zero) from a nalgebra vector.
pub fn vector_to_ode(v: &Vector3<f64>) -> dVector3 {
    [v.x, v.y, v.z, 0.0]
}

/// Unit quaternion from ODE's `[w, x, y, z]`.
pub fn quaternion_from_ode(q: &[dReal]) -> UnitQuaternion<f64> {
    UnitQuaternion::new_unchecked(Quaternion::new(q[0], q[1], q[2], q[3]))
}

/// ODE's `[w, x, y, z]` from a unit quaternion.
pub fn quaternion_to_ode(q: &UnitQuaternion<f64>) -> dQuaternion {
    [q.w, q.i, q.j, q.k]
}

/// Rotation from ODE's row-major 3×4 `dMatrix3`.
pub fn rotation_from_ode(r: &[dReal]) -> Rotation3<f64> {
    Rotation3::from_matrix_unchecked(Matrix3::new(
        r[0], r[1], r[2], //
        r[4], r[5], r[6], //
        r[8], r[9], r[10],
    ))
}

/// ODE's row-major 3×4 `dMatrix3` from a rotation.
pub fn rotation_to_ode(r: &Rotation3<f64>) -> dMatrix3 {
    let m = r.matrix();
    [m[(0, 0)], m[(0, 1)], m[(0, 2)], 0.0, m[(1, 0)], m[(1, 1)], m[(1, 2)], 0.0, m[(2, 0)], m[(2, 1)], m[(2, 2)], 0.0]
}

/// Inertia tensor from ODE's `dMatrix3` (body frame, about the centre of mass).
pub fn matrix_from_ode(r: &[dReal]) -> Matrix3<f64> {
    *rotation_from_ode(r).matrix()
}

/// Rotation of `angle` radians about `axis` (Rodrigues' formula), computed term by term
/// as the original ARS did, so that rotations built from the same axis and angle are
/// bit-identical with the original and with the C reference scenes. `axis` must be a
/// unit vector (it is not normalised, exactly as in the original).
pub fn rotation_about_axis(axis: &Vector3<f64>, angle: f64) -> Rotation3<f64> {
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let c = angle.cos();
    let s = angle.sin();
    let t = 1.0 - c;
    Rotation3::from_matrix_unchecked(Matrix3::new(
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternion_round_trip() {
        let q = UnitQuaternion::from_euler_angles(0.3, -1.1, 2.0);
        let back = quaternion_from_ode(&quaternion_to_ode(&q));
        assert_eq!(q, back);
        assert_eq!(quaternion_to_ode(&UnitQuaternion::identity()), [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn rotation_round_trip_is_row_major() {
        let r = Rotation3::from_euler_angles(0.1, 0.2, 0.3);
        let ode = rotation_to_ode(&r);
        assert_eq!(ode[1], r.matrix()[(0, 1)]);
        assert_eq!(ode[4], r.matrix()[(1, 0)]);
        assert_eq!(rotation_from_ode(&ode), r);
    }

    #[test]
    fn vector_round_trip() {
        let v = Vector3::new(1.5, -2.0, 3.25);
        assert_eq!(vector_from_ode(&vector_to_ode(&v)), v);
    }

    #[test]
    fn rodrigues_matches_nalgebra() {
        let axis = Vector3::new(0.0, 1.0, 0.0);
        let r = rotation_about_axis(&axis, std::f64::consts::FRAC_PI_2);
        let expected = Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
        assert!((r.matrix() - expected.matrix()).norm() < 1e-15);
        // +Z turns into +X, as the laser of the thesis expects.
        assert!((r * Vector3::z() - Vector3::x()).norm() < 1e-15);
    }
}
