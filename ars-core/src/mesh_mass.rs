//! The mass of the solid a closed triangle mesh bounds: what mesh shapes, their convex
//! hulls and the importers weigh.

use nalgebra::{Point3, Vector3};

/// A mesh's vertices and triangles (three vertex indices each).
pub(crate) type Triangles = (Vec<Point3<f64>>, Vec<[u32; 3]>);

/// The mass properties of the solid a closed triangle mesh bounds (counter-clockwise
/// triangles seen from outside), at a density of 1: its volume, its centre of mass,
/// and its inertia tensor about that centre, in the mesh's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshMass {
    /// Volume, m³ (the mass at a density of 1 kg/m³).
    pub volume: f64,
    /// Centre of mass, m.
    pub centre: Point3<f64>,
    /// Inertia tensor about the centre of mass per kg/m³ of density, kg·m² per kg/m³.
    pub inertia: nalgebra::Matrix3<f64>,
}

/// The [`MeshMass`] of a mesh: `None` when it encloses no volume (open, flat, or wound
/// the wrong way round) or a triangle names a vertex it does not have. Exact for a
/// closed mesh: each triangle's tetrahedron from the origin, with its signed volume and
/// second moments.
///
/// ```
/// use ars_core::shape::mass_properties;
/// use nalgebra::Point3;
/// // The unit cube [0, 1]³, two triangles a face, wound outwards.
/// let v: Vec<Point3<f64>> = (0..8).map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect();
/// let t = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
///          [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]];
/// let m = mass_properties(&v, &t).unwrap();
/// assert!((m.volume - 1.0).abs() < 1e-12);
/// assert!((m.centre - Point3::new(0.5, 0.5, 0.5)).norm() < 1e-12);
/// assert!((m.inertia[(0, 0)] - 1.0 / 6.0).abs() < 1e-12 && m.inertia[(0, 1)].abs() < 1e-12);
/// ```
pub fn mass_properties(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Option<MeshMass> {
    use nalgebra::Matrix3;
    // ∫ x xᵀ over a tetrahedron (0, a, b, c) is det/120 · (A·K·Aᵀ) with A = [a b c] and
    // K = [[2,1,1],[1,2,1],[1,1,2]].
    let canonical = Matrix3::new(2.0, 1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 2.0);
    let (mut volume, mut first, mut second) = (0.0, Vector3::zeros(), Matrix3::zeros());
    for t in triangles {
        let corner = |k: u32| vertices.get(k as usize).map(|p| p.coords);
        let (a, b, c) = (corner(t[0])?, corner(t[1])?, corner(t[2])?);
        let columns = Matrix3::from_columns(&[a, b, c]);
        let det = columns.determinant();
        volume += det / 6.0;
        first += (a + b + c) * (det / 24.0);
        second += columns * canonical * columns.transpose() * (det / 120.0);
    }
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let centre = first / volume;
    // Second moments about the centre, then the inertia tensor tr(C)·1 − C.
    let about_centre = second - centre * centre.transpose() * volume;
    let inertia = Matrix3::identity() * about_centre.trace() - about_centre;
    Some(MeshMass { volume, centre: Point3::from(centre), inertia })
}
