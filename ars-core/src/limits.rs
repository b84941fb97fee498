//! The range of values the safe layer accepts, and why.
//!
//! ODE works in double precision but aborts (or loops forever) well before the ends
//! of that range: a capsule 1e17 m long makes libccd's penetration search loop
//! forever, a body at x = 1e17 m overflows the integer cells of a hash space, an
//! angular velocity of 1e300 rad/s overflows the quaternion update, a cylinder
//! 5e-324 m long fails ODE's own validity check. Every size, distance, mass, inertia,
//! velocity, force and time step that reaches ODE is therefore held to a documented,
//! physically generous range; anything outside is an [`Error`] naming
//! the value, before ODE is called.
//!
//! | quantity | accepted | reason |
//! | --- | --- | --- |
//! | sizes (radius, length, edge, ray length) | [`MIN_SIZE`] ‥ [`MAX_SIZE`] | ODE's cylinder colliders assert below 4.4e-16 m; physical scales |
//! | cylinder–cylinder and capsule–cylinder pairs | largest / smallest dimension ≤ [`MAX_CONVEX_PAIR_RATIO`], checked when they meet | libccd's search loops forever beyond it |
//! | coordinates (positions, anchors, offsets, plane distance) | each within ±[`MAX_COORDINATE`] | a hash space also needs `coordinate · 2^−min_level` within `int`, checked before it collides |
//! | mass | [`MIN_MASS`] ‥ [`MAX_MASS`] | the inverse mass and inertia stay far from underflow and overflow |
//! | principal moments of inertia | [`MIN_INERTIA`] ‥ [`MAX_INERTIA`], ratio ≤ [`MAX_INERTIA_RATIO`], triangle inequality | a physical body; ODE inverts the inertia in its gyroscopic step (a subnormal determinant gives NaN) |
//! | linear speed | ≤ [`MAX_SPEED`] | |
//! | angular speed | ≤ [`MAX_ANGULAR_SPEED`] | the quaternion update (ω·dt) stays small enough to normalise |
//! | force, torque (per call and accumulated) | ≤ [`MAX_FORCE`], [`MAX_TORQUE`] | one step of acceleration cannot overflow |
//! | time step | [`MIN_TIME_STEP`] ‥ [`MAX_TIME_STEP`] | ERP/dt and dt·F/m stay finite |
//! | gravity | ≤ [`MAX_ACCELERATION`] | |
//! | contacts in one island, exact stepper | ≤ [`DEFAULT_EXACT_STEP_CONTACTS`] (configurable) | the dense solver's time grows with the cube of the contacts (the README's "Bad input, divergence and ODE's own failures" gives a measured time) |
//!
//! After every step, a body whose state left these ranges (or became non-finite) is
//! reported as [`Error::Diverged`], and the world refuses to
//! step until it is reset or removed.

use nalgebra::{Matrix3, Point3, Vector3};

use crate::error::{Error, Result};

/// Smallest size (radius, length, box edge, ray length), m: 1 nm.
pub const MIN_SIZE: f64 = 1e-9;
/// Largest size, m: a million kilometres.
pub const MAX_SIZE: f64 = 1e9;
/// Largest absolute coordinate of a position, anchor, offset or plane distance, m.
pub const MAX_COORDINATE: f64 = 1e9;
/// Smallest mass, kg: a microgram.
pub const MIN_MASS: f64 = 1e-9;
/// Largest mass, kg: a million tonnes.
pub const MAX_MASS: f64 = 1e9;
/// Smallest principal moment of inertia, kg·m² (below that of the smallest, lightest
/// sphere: 0.4 · 1e-9 kg · (1e-9 m)² = 4e-28).
pub const MIN_INERTIA: f64 = 1e-30;
/// Largest principal moment of inertia, kg·m² (above that of the largest, heaviest
/// sphere: 0.4 · 1e9 kg · (1e9 m)² = 4e26).
pub const MAX_INERTIA: f64 = 1e30;
/// Largest ratio between the largest and the smallest principal moment of inertia.
/// ODE's implicit gyroscopic step inverts the inertia; measured: a ratio of 1e16
/// still steps, 1e20 ends in NaN.
pub const MAX_INERTIA_RATIO: f64 = 1e12;
/// Largest linear speed, m/s (a third of the speed of light).
pub const MAX_SPEED: f64 = 1e8;
/// Largest angular speed, rad/s (160,000 turns per second).
pub const MAX_ANGULAR_SPEED: f64 = 1e6;
/// Largest force, N (per call, and accumulated for one step): 100,000 tonnes-force.
pub const MAX_FORCE: f64 = 1e9;
/// Largest torque, N·m (per call, and accumulated for one step).
pub const MAX_TORQUE: f64 = 1e9;
/// Largest ratio between the largest and the smallest dimension (radius, length) of
/// a cylinder–cylinder or capsule–cylinder pair, the pairs ODE hands to libccd:
/// beyond it libccd's portal search can loop forever (measured: no hang in 100,000
/// random pairs up to 1e8; hangs from about 6e9).
pub const MAX_CONVEX_PAIR_RATIO: f64 = 1e8;
/// Most geoms a hash space collides ([`SpaceKind::Hash`](crate::SpaceKind::Hash)).
/// ODE's hash space allocates and clears a table of one bit per pair of geoms at
/// every collision (n²/8 bytes: 1.25 GB and 0.7 s at 100,000 geoms) and indexes it
/// with a C `int`, which overflows beyond about 131,000 geoms (writes outside the
/// table). More geoms: sweep and prune, which has no such table.
pub const MAX_HASH_SPACE_GEOMS: usize = 100_000;
/// Smallest time step, s.
pub const MIN_TIME_STEP: f64 = 1e-9;
/// Largest time step, s.
pub const MAX_TIME_STEP: f64 = 1.0;
/// Largest gravity, m/s².
pub const MAX_ACCELERATION: f64 = 1e9;

/// Default largest number of contact points in one island (a group of bodies linked
/// by contacts) for the exact stepper ([`World::set_exact_step_contact_limit`](crate::World::set_exact_step_contact_limit)).
/// `dWorldStep` solves each island as one dense problem whose cost grows with the
/// cube of its rows (three per contact): past a few hundred contacts a step takes
/// seconds to minutes (the README's "Bad input, divergence and ODE's own failures"
/// gives a measured time).
pub const DEFAULT_EXACT_STEP_CONTACTS: usize = 400;

/// `value` in `[min, max]` (finite). The check is inlined; building the error is not.
#[inline]
pub(crate) fn in_range(what: &'static str, value: f64, min: f64, max: f64) -> Result<f64> {
    // False for NaN, as for anything outside.
    if value >= min && value <= max && value.is_finite() { Ok(value) } else { out_of_range(what, value, min, max) }
}

#[cold]
fn out_of_range(what: &'static str, value: f64, min: f64, max: f64) -> Result<f64> {
    if !value.is_finite() {
        return Err(Error::NotFinite { what, value: value.to_string() });
    }
    if value <= 0.0 && min > 0.0 {
        return Err(Error::NotPositive { what, value });
    }
    Err(Error::OutOfRange { what, detail: format!("must be within [{min:e}, {max:e}], got {value:e}") })
}

/// A size: within [`MIN_SIZE`], [`MAX_SIZE`].
pub(crate) fn size(what: &'static str, value: f64) -> Result<f64> {
    in_range(what, value, MIN_SIZE, MAX_SIZE)
}

/// Every component a valid size.
pub(crate) fn sizes(what: &'static str, v: &Vector3<f64>) -> Result<Vector3<f64>> {
    for c in v.iter() {
        size(what, *c)?;
    }
    Ok(*v)
}

/// A coordinate: finite, within ±[`MAX_COORDINATE`].
pub(crate) fn coordinate(what: &'static str, value: f64) -> Result<f64> {
    in_range(what, value, -MAX_COORDINATE, MAX_COORDINATE)
}

/// A point (or translation) whose coordinates are all valid.
pub(crate) fn point(what: &'static str, p: &Point3<f64>) -> Result<Point3<f64>> {
    vector_within(what, &p.coords, MAX_COORDINATE, "m").map(Point3::from)
}

/// A finite vector whose components are all within ±`max`.
pub(crate) fn vector_within(what: &'static str, v: &Vector3<f64>, max: f64, unit: &str) -> Result<Vector3<f64>> {
    if !v.iter().all(|c| c.is_finite()) {
        return Err(Error::NotFinite { what, value: format!("({}, {}, {})", v.x, v.y, v.z) });
    }
    if v.iter().any(|c| c.abs() > max) {
        return Err(Error::OutOfRange {
            what,
            detail: format!("each component must be within ±{max:e} {unit}, got ({:e}, {:e}, {:e})", v.x, v.y, v.z),
        });
    }
    Ok(*v)
}

/// What is wrong with a part of a body's state or accumulators (non-finite, or a
/// component beyond ±`max`), or `None`: the message of a failed state check.
pub(crate) fn state_problem(what: &str, values: &[f64], max: f64, unit: &str) -> Option<String> {
    // `!(|c| <= max)` is also true for NaN.
    if values.iter().all(|c| c.abs() <= max) {
        return None;
    }
    if values.iter().all(|c| c.is_finite()) {
        Some(format!("{what} {values:?} has a component beyond ±{max:e} {unit}"))
    } else {
        Some(format!("{what} {values:?} is not finite"))
    }
}

/// A mass within [`MIN_MASS`], [`MAX_MASS`].
pub(crate) fn mass(what: &'static str, value: f64) -> Result<f64> {
    in_range(what, value, MIN_MASS, MAX_MASS)
}

/// A time step within [`MIN_TIME_STEP`], [`MAX_TIME_STEP`].
#[inline]
pub(crate) fn time_step(value: f64) -> Result<f64> {
    in_range("time step", value, MIN_TIME_STEP, MAX_TIME_STEP)
}

/// A time step checked by [`time_step`] when it was made: a scene's steps take it
/// without checking it again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TimeStep(f64);

impl TimeStep {
    /// `value` if it is within [`MIN_TIME_STEP`], [`MAX_TIME_STEP`] (see [`time_step`]).
    pub(crate) fn new(value: f64) -> Result<TimeStep> {
        time_step(value).map(TimeStep)
    }

    /// The time step, s.
    #[inline]
    pub(crate) fn get(self) -> f64 {
        self.0
    }
}

/// An inertia tensor (about the centre of mass, body frame) of a physical body:
/// symmetric, principal moments within [`MIN_INERTIA`], [`MAX_INERTIA`], and each
/// moment at most the sum of the other two (the triangle inequality every real mass
/// distribution satisfies).
pub(crate) fn inertia(i: &Matrix3<f64>) -> Result<Matrix3<f64>> {
    const WHAT: &str = "inertia tensor";
    if !i.iter().all(|x| x.is_finite()) {
        return Err(Error::NotFinite { what: WHAT, value: format!("{i:?}") });
    }
    let scale = i.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    // Bounding the entries first keeps the eigen-decomposition finite.
    if scale > MAX_INERTIA {
        return Err(Error::OutOfRange {
            what: WHAT,
            detail: format!("entries must be within ±{MAX_INERTIA:e} kg·m², got one of {scale:e}"),
        });
    }
    if (i - i.transpose()).amax() > 1e-12 * scale {
        return Err(Error::Invalid { what: WHAT, problem: "must be symmetric".into() });
    }
    let mut moments: Vec<f64> = i.symmetric_eigenvalues().iter().copied().collect();
    moments.sort_by(f64::total_cmp);
    let (a, b, c) = (moments[0], moments[1], moments[2]);
    if a.is_nan() || a <= 0.0 {
        return Err(Error::Invalid {
            what: WHAT,
            problem: format!("must be positive definite, its principal moments are {a:e}, {b:e}, {c:e}"),
        });
    }
    if a < MIN_INERTIA || c.is_nan() || c > MAX_INERTIA || c > a * MAX_INERTIA_RATIO {
        return Err(Error::OutOfRange {
            what: WHAT,
            detail: format!(
                "must have principal moments within [{MIN_INERTIA:e}, {MAX_INERTIA:e}] kg·m², at most {MAX_INERTIA_RATIO:e} apart, got {a:e}, {b:e}, {c:e}"
            ),
        });
    }
    // Relative slack for the rounding of the eigenvalues (a thin rod or a flat plate
    // sits exactly on the inequality).
    if c.is_nan() || c > (a + b) * (1.0 + 1e-9) {
        return Err(Error::Invalid {
            what: WHAT,
            problem: format!(
                "breaks the triangle inequality: principal moment {c:e} exceeds the sum of the others ({a:e} + {b:e}); no mass distribution has it"
            ),
        });
    }
    Ok(*i)
}

/// A rotation from a 3×3 matrix given from outside (a file, another language): the
/// matrix itself if it is one (finite, orthonormal, determinant +1, to 1e-6), never a
/// matrix quietly made orthonormal.
pub fn rotation_matrix(what: &'static str, m: Matrix3<f64>) -> Result<nalgebra::Rotation3<f64>> {
    crate::validate::rotation(what, &nalgebra::Rotation3::from_matrix_unchecked(m))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_inclusive_and_named() {
        assert!(size("r", MIN_SIZE).is_ok() && size("r", MAX_SIZE).is_ok());
        assert!(matches!(size("r", 5e-324), Err(Error::OutOfRange { what: "r", .. })));
        assert!(matches!(size("r", -1.0), Err(Error::NotPositive { .. })));
        assert!(matches!(coordinate("x", 1e17), Err(Error::OutOfRange { .. })));
        assert!(coordinate("x", -MAX_COORDINATE).is_ok());
        assert!(mass("m", 1e-300).is_err() && mass("m", 1e300).is_err() && mass("m", 1.0).is_ok());
    }

    #[test]
    fn inertia_must_be_physical() {
        assert!(inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 1.0))).is_ok());
        // A thin rod: (0, m l²/12, m l²/12) is the limit; a flat plate: a + b = c.
        assert!(inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0))).is_ok());
        let broken = inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 3.0))).unwrap_err();
        assert!(broken.to_string().contains("triangle inequality"), "{broken}");
        assert!(inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 1e-300))).is_err());
        assert!(inertia(&Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)).is_err());
    }
}
