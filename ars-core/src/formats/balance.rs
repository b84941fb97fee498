//! Inertias as people write them, made physical: MuJoCo's `balanceinertia`, extended
//! to tensors that are not positive definite.
//!
//! Robot files often carry inertias no body can have: moments left at zero (a link
//! whose author gave only its mass), products of inertia rounded so that a principal
//! moment turns slightly negative, or moments that break the triangle inequality
//! (each at most the sum of the other two). ARS refuses those in a body
//! ([`limits::inertia`](crate::limits)); a file reader can correct them instead, in
//! the tensor's principal frame, the mass and the centre of mass untouched:
//! 1. no moment worth the name (an inertia of zeros, or one whose largest moment is
//!    below a millionth of that sphere's: iCub's links of 0.27 kg with 1e-20 kg·m²,
//!    which ODE turns into infinite spins): the inertia of a solid sphere of the body's
//!    mass at water's density, `0.4 m r²` with `r = (3m / 4πρ)^⅓`. This applies to
//!    an inertia ARS would otherwise take as it is, too;
//! 2. moments below a millionth of the largest (zero or negative included): raised to
//!    that millionth;
//! 3. a moment above the sum of the other two: all three set to their mean, as
//!    MuJoCo's `balanceinertia` does.

use nalgebra::{Matrix3, Vector3};

use crate::limits::{MAX_INERTIA, MIN_INERTIA};

/// Water's density, kg/m³: the sphere that stands for a body given no inertia.
const WATER_DENSITY: f64 = 1000.0;

/// The smallest principal moment kept, as a fraction of the largest.
const LEAST_MOMENT_FRACTION: f64 = 1e-6;

/// A largest moment below this fraction of the water sphere's is no moment: its radius
/// of gyration is a thousandth of the sphere's (a tungsten ball's is a third of it).
const NEGLIGIBLE_MOMENT_FRACTION: f64 = 1e-6;

/// An inertia that was corrected, and how.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Balanced {
    /// The corrected tensor, in the same frame as the one given.
    pub inertia: Matrix3<f64>,
    /// What was wrong and what was done, in a sentence.
    pub note: String,
}

/// `inertia` (about the centre of mass of a body of `mass` kg) corrected as the
/// module says, or `None` when ARS takes it as it is, or when no correction applies
/// (a mass that is not positive, entries not finite or beyond [`MAX_INERTIA`]): the
/// body's own checks then say what is wrong.
pub(crate) fn balance_inertia(mass: f64, inertia: &Matrix3<f64>) -> Option<Balanced> {
    let usable = mass.is_finite() && mass > 0.0 && inertia.iter().all(|x| x.is_finite() && x.abs() <= MAX_INERTIA);
    if !usable {
        return None;
    }
    let radius = (3.0 * mass / (4.0 * std::f64::consts::PI * WATER_DENSITY)).cbrt();
    let sphere = 0.4 * mass * radius * radius;
    let symmetric = (inertia + inertia.transpose()) / 2.0;
    let eigen = symmetric.symmetric_eigen();
    let given = sorted(eigen.eigenvalues);
    let largest = given[2];
    let negligible = largest <= MIN_INERTIA.max(sphere * NEGLIGIBLE_MOMENT_FRACTION);
    if !negligible && crate::limits::inertia(inertia).is_ok() {
        return None;
    }
    let (moments, why) = if negligible {
        (
            Vector3::repeat(sphere),
            format!(
                "no moment worth the name for {mass:e} kg: a solid sphere of its mass at water's density (radius {radius:.3e} m)"
            ),
        )
    } else {
        let least = largest * LEAST_MOMENT_FRACTION;
        let raised = eigen.eigenvalues.map(|m| m.max(least));
        let s = sorted(raised);
        if s[2] > (s[0] + s[1]) * (1.0 + 1e-9) {
            let mean = raised.sum() / 3.0;
            (
                Vector3::repeat(mean),
                "a moment above the sum of the others: all three set to their mean (MuJoCo's balanceinertia)".into(),
            )
        } else {
            (raised, format!("moments below a millionth of the largest raised to {least:e}"))
        }
    };
    let corrected = eigen.eigenvectors * Matrix3::from_diagonal(&moments) * eigen.eigenvectors.transpose();
    // Exactly symmetric, as a body's inertia must be.
    let corrected = (corrected + corrected.transpose()) / 2.0;
    crate::limits::inertia(&corrected).ok()?;
    let after = sorted(moments);
    Some(Balanced {
        inertia: corrected,
        note: format!(
            "inertia balanced: principal moments {:e}, {:e}, {:e} kg·m² became {:e}, {:e}, {:e} ({why})",
            given[0], given[1], given[2], after[0], after[1], after[2]
        ),
    })
}

/// The three values, smallest first.
fn sorted(v: Vector3<f64>) -> [f64; 3] {
    let mut s = [v.x, v.y, v.z];
    s.sort_by(f64::total_cmp);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moments(i: &Matrix3<f64>) -> [f64; 3] {
        sorted(i.symmetric_eigenvalues())
    }

    #[test]
    fn a_physical_inertia_is_left_as_it_is() {
        assert_eq!(balance_inertia(1.0, &Matrix3::from_diagonal(&Vector3::new(0.1, 0.2, 0.25))), None);
        // A thin rod sits on the triangle inequality: physical, kept.
        assert_eq!(balance_inertia(1.0, &Matrix3::from_diagonal(&Vector3::new(1e-6, 1.0, 1.0))), None);
    }

    #[test]
    fn zeros_become_a_sphere_of_the_mass_at_waters_density() {
        let b = balance_inertia(1000.0, &Matrix3::zeros()).unwrap();
        // 1000 kg of water: a sphere of radius (3 / 4π)^⅓ m.
        let r = (3.0 / (4.0 * std::f64::consts::PI)).cbrt();
        for m in moments(&b.inertia) {
            assert!((m - 0.4 * 1000.0 * r * r).abs() < 1e-9, "{m}");
        }
        assert!(b.note.contains("solid sphere"), "{}", b.note);
    }

    #[test]
    fn moments_far_too_small_for_the_mass_become_the_sphere_too() {
        // example-robot-data's iCub: 0.2675 kg, principal moments ±1.355e-20 (not positive
        // definite), and 0.746 kg with 1e-20-ish moments that ARS would have taken.
        let ankle = Matrix3::new(0.0, 0.0, 1.35525e-20, 0.0, 0.0, 0.0, 1.35525e-20, 0.0, 0.0);
        let tiny = Matrix3::from_diagonal(&Vector3::new(2.7e-20, 5.4e-20, 4.0e-20));
        for (mass, given) in [(0.2675, ankle), (0.746, tiny)] {
            let b = balance_inertia(mass, &given).unwrap();
            let r = (3.0 * mass / (4.0 * std::f64::consts::PI * 1000.0)).cbrt();
            for m in moments(&b.inertia) {
                assert!((m - 0.4 * mass * r * r).abs() < 1e-15, "{m}");
            }
            assert!(b.note.contains("no moment worth the name"), "{}", b.note);
        }
        // A light foot's own small inertia is its own (0.06 kg, 9.6e-6 kg·m²).
        assert_eq!(balance_inertia(0.06, &Matrix3::from_diagonal(&Vector3::repeat(9.6e-6))), None);
    }

    #[test]
    fn a_zero_or_negative_moment_is_raised_and_the_frame_kept() {
        // Principal moments -1e-9, 1, 1 about axes turned 30° about z.
        let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 0.5);
        let given = turn.matrix() * Matrix3::from_diagonal(&Vector3::new(-1e-9, 1.0, 1.0)) * turn.matrix().transpose();
        let b = balance_inertia(2.0, &given).unwrap();
        let m = moments(&b.inertia);
        assert!((m[0] - 1e-6).abs() < 1e-15 && (m[1] - 1.0).abs() < 1e-12 && (m[2] - 1.0).abs() < 1e-12, "{m:?}");
        // The small moment stays about the same axis.
        let axis = turn * Vector3::x();
        assert!(((b.inertia * axis).norm() - 1e-6).abs() < 1e-12);
        assert!(crate::limits::inertia(&b.inertia).is_ok());
    }

    #[test]
    fn a_broken_triangle_inequality_takes_the_mean_as_mujoco_does() {
        let given = Matrix3::from_diagonal(&Vector3::new(0.001, 0.01, 0.1));
        let b = balance_inertia(1.0, &given).unwrap();
        for m in moments(&b.inertia) {
            assert!((m - 0.111 / 3.0).abs() < 1e-15, "{m}");
        }
        assert!(b.note.contains("balanceinertia"), "{}", b.note);
    }

    #[test]
    fn what_cannot_be_corrected_is_left_to_the_bodys_checks() {
        let bad = Matrix3::zeros();
        assert_eq!(balance_inertia(0.0, &bad), None, "no mass");
        assert_eq!(balance_inertia(1.0, &Matrix3::repeat(f64::NAN)), None);
        assert_eq!(balance_inertia(1.0, &Matrix3::from_diagonal(&Vector3::new(1e31, 1.0, 1.0))), None);
    }
}
