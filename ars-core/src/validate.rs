//! Checks applied to user input before it reaches ODE (which aborts on some bad
//! arguments and silently produces NaN on others).

use nalgebra::{Point3, Rotation3, UnitQuaternion, Vector3};

use crate::error::{Error, Result};

/// `value` must be finite.
pub fn finite(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() { Ok(value) } else { Err(Error::NotFinite { what, value: value.to_string() }) }
}

/// `value` must be finite and > 0.
pub fn positive(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(Error::NotPositive { what, value }) }
}

/// `value` must be finite and ≥ 0.
pub fn non_negative(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::OutOfRange { what, detail: format!("must be finite and at least 0, got {value}") })
    }
}

/// Every component finite.
pub fn vector(what: &'static str, v: &Vector3<f64>) -> Result<Vector3<f64>> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(*v)
    } else {
        Err(Error::NotFinite { what, value: format!("({}, {}, {})", v.x, v.y, v.z) })
    }
}

/// Every coordinate finite.
pub fn point(what: &'static str, p: &Point3<f64>) -> Result<Point3<f64>> {
    vector(what, &p.coords).map(Point3::from)
}

/// Finite and not the zero vector (ODE normalises axes itself and asserts on zero).
pub fn direction(what: &'static str, v: &Vector3<f64>) -> Result<Vector3<f64>> {
    let v = vector(what, v)?;
    if v.norm_squared() > 0.0 { Ok(v) } else { Err(Error::ZeroVector { what }) }
}

/// A finite unit quaternion (nalgebra's `UnitQuaternion` can still hold NaN).
pub fn quaternion(what: &'static str, q: &UnitQuaternion<f64>) -> Result<UnitQuaternion<f64>> {
    let c = q.coords;
    if !c.iter().all(|x| x.is_finite()) {
        return Err(Error::NotFinite { what, value: format!("{q:?}") });
    }
    let norm_err = (c.norm() - 1.0).abs();
    if norm_err.is_nan() || norm_err > 1e-6 {
        return Err(Error::Invalid { what, problem: format!("must be a unit quaternion, its norm is {}", c.norm()) });
    }
    Ok(*q)
}

/// A finite rotation matrix that is orthonormal with determinant +1 (to 1e-6).
pub fn rotation(what: &'static str, r: &Rotation3<f64>) -> Result<Rotation3<f64>> {
    let m = r.matrix();
    if !m.iter().all(|x| x.is_finite()) {
        return Err(Error::NotFinite { what, value: format!("{m:?}") });
    }
    // Entries of a rotation are within [-1, 1]; checking that first keeps the products
    // below from overflowing to ∞ − ∞ = NaN, which no comparison would catch.
    let err = if m.iter().all(|x| x.abs() <= 1.0 + 1e-6) {
        (m * m.transpose() - nalgebra::Matrix3::identity()).norm()
    } else {
        f64::INFINITY
    };
    let det_err = (m.determinant() - 1.0).abs();
    if err.is_nan() || err > 1e-6 || det_err.is_nan() || det_err > 1e-6 {
        return Err(Error::Invalid { what, problem: "must be a rotation matrix (orthonormal, determinant +1)".into() });
    }
    Ok(*r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_what_it_should() {
        assert!(finite("x", f64::NAN).is_err());
        assert!(positive("r", 0.0).is_err());
        assert!(positive("r", -1.0).is_err());
        assert!(positive("r", f64::INFINITY).is_err());
        assert!(direction("axis", &Vector3::zeros()).is_err());
        assert!(vector("v", &Vector3::new(0.0, f64::NEG_INFINITY, 0.0)).is_err());
        assert!(positive("r", 1e-300).is_ok());
        let skew =
            Rotation3::from_matrix_unchecked(nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0));
        assert!(rotation("r", &skew).is_err());
    }
}
