//! Mass and inertia as MuJoCo's compiler computes them: geoms' volumes and densities,
//! a body's mass from its geoms, the inertia a joint's armature adds.

use nalgebra::{Matrix3, Vector3};

use super::model::{Body, Geom, GeomKind, Joint, JointKind};
use crate::shape::Shape;

/// The radius of the sphere a flat mesh's geom (one that never collides: MuJoCo makes
/// no hull for it) is built as in ODE, m.
const FLAT_MESH_STAND_IN: f64 = 1e-6;

impl Geom {
    pub(super) fn volume(&self) -> f64 {
        use std::f64::consts::PI;
        match &self.kind {
            GeomKind::Mesh(mesh) => mesh.mass.volume,
            // Static terrain: nothing to weigh.
            GeomKind::Plane | GeomKind::Hfield(_) => 0.0,
            GeomKind::Sphere(r) => 4.0 / 3.0 * PI * r.powi(3),
            GeomKind::Capsule(r, h) => PI * r * r * 2.0 * h + 4.0 / 3.0 * PI * r.powi(3),
            GeomKind::Cylinder(r, h) => PI * r * r * 2.0 * h,
            GeomKind::Box(s) => 8.0 * s.x * s.y * s.z,
            GeomKind::Ellipsoid(s) => 4.0 / 3.0 * PI * s.x * s.y * s.z,
        }
    }

    pub(super) fn mass(&self) -> f64 {
        self.mass.unwrap_or(self.density * self.volume())
    }

    /// Its centre of mass and its inertia tensor about it, in its frame.
    pub(super) fn mass_distribution(&self) -> (Vector3<f64>, Matrix3<f64>) {
        match &self.kind {
            GeomKind::Mesh(mesh) => (mesh.mass.centre.coords, mesh.mass.inertia * (self.mass() / mesh.mass.volume)),
            _ => (Vector3::zeros(), Matrix3::from_diagonal(&self.inertia())),
        }
    }

    /// Principal moments about the geom's centre, in its frame, as MuJoCo computes them
    /// (a mesh's are [`mass_distribution`](Self::mass_distribution)'s).
    pub(super) fn inertia(&self) -> Vector3<f64> {
        let m = self.mass();
        match &self.kind {
            GeomKind::Plane | GeomKind::Hfield(_) | GeomKind::Mesh(_) => Vector3::zeros(),
            GeomKind::Sphere(r) => Vector3::repeat(0.4 * m * r * r),
            GeomKind::Capsule(r, h) => {
                let height = 2.0 * h;
                let sphere_mass = m * 4.0 * r / (4.0 * r + 3.0 * height);
                let cylinder_mass = m - sphere_mass;
                let across = cylinder_mass * (3.0 * r * r + height * height) / 12.0
                    + 0.4 * sphere_mass * r * r
                    + sphere_mass * height * (3.0 * r + 2.0 * height) / 8.0;
                Vector3::new(across, across, cylinder_mass * r * r / 2.0 + 0.4 * sphere_mass * r * r)
            }
            GeomKind::Cylinder(r, h) => {
                let across = m * (3.0 * r * r + 4.0 * h * h) / 12.0;
                Vector3::new(across, across, m * r * r / 2.0)
            }
            GeomKind::Box(s) => {
                Vector3::new(s.y * s.y + s.z * s.z, s.x * s.x + s.z * s.z, s.x * s.x + s.y * s.y) * (m / 3.0)
            }
            GeomKind::Ellipsoid(s) => {
                Vector3::new(s.y * s.y + s.z * s.z, s.x * s.x + s.z * s.z, s.x * s.x + s.y * s.y) * (m / 5.0)
            }
        }
    }

    /// What it looks like: its mesh's triangles, else its ODE shape.
    pub(super) fn drawn_shape(&self) -> Shape {
        match &self.kind {
            GeomKind::Mesh(mesh) => mesh.shape.clone(),
            _ => self.shape(),
        }
    }

    /// The ODE shape (a mesh as its convex hull, an ellipsoid as the hull of
    /// [`ELLIPSOID_POINTS`] points on it; a flat mesh, in a geom that never collides, as
    /// a point-like sphere).
    pub(super) fn shape(&self) -> Shape {
        match &self.kind {
            GeomKind::Mesh(mesh) => mesh.hull.clone().unwrap_or(Shape::Sphere { radius: FLAT_MESH_STAND_IN }),
            GeomKind::Plane => Shape::Plane { normal: Vector3::z(), distance: 0.0 },
            GeomKind::Hfield(field) => field.shape(),
            GeomKind::Sphere(r) => Shape::Sphere { radius: *r },
            GeomKind::Capsule(r, h) => Shape::Capsule { radius: *r, length: 2.0 * h },
            GeomKind::Cylinder(r, h) => Shape::Cylinder { radius: *r, length: 2.0 * h },
            GeomKind::Box(s) => Shape::Box { edges: *s * 2.0 },
            GeomKind::Ellipsoid(s) => ellipsoid_hull(s),
        }
    }
}

/// How many points on an ellipsoid its hull is made of: the image of an even point set
/// on a sphere (a Fibonacci lattice), so that along any direction the hull reaches
/// within 1.5 % of the ellipsoid (inside it: it touches a little later), whatever the
/// ellipsoid's proportions.
pub(super) const ELLIPSOID_POINTS: usize = 258;

/// The convex hull of [`ELLIPSOID_POINTS`] points on the ellipsoid of half-axes `radii`
/// (ODE has no ellipsoid); a sphere of the same volume should the hull fail, which
/// only degenerate radii could make it do (they are refused when read).
fn ellipsoid_hull(radii: &Vector3<f64>) -> Shape {
    let golden = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    let n = ELLIPSOID_POINTS as f64;
    let points: Vec<nalgebra::Point3<f64>> = (0..ELLIPSOID_POINTS)
        .map(|k| {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / n;
            let across = (1.0 - z * z).sqrt();
            let (sin, cos) = (golden * k as f64).sin_cos();
            // An even point set on the unit sphere, stretched: how far the hull falls
            // short of the surface along a direction, relative to the surface, is the
            // sphere's (a support function's ratio survives a linear map).
            nalgebra::Point3::from(radii.component_mul(&Vector3::new(across * cos, across * sin, z)))
        })
        .collect();
    Shape::convex_hull(&points).unwrap_or(Shape::Sphere { radius: (radii.x * radii.y * radii.z).cbrt() })
}

/// The first body of the tree (depth first, in the file's order) that `wanted` accepts.
pub(super) fn find_body<'b>(bodies: &'b [Body], wanted: &dyn Fn(&Body) -> bool) -> Option<&'b Body> {
    bodies.iter().find_map(|b| if wanted(b) { Some(b) } else { find_body(&b.children, wanted) })
}

/// The mass, centre of mass and inertia about it (body frame) of `geoms`, as MuJoCo's
/// compiler combines them; `None` when they weigh nothing.
pub(super) fn mass_of_geoms(geoms: &[Geom]) -> Option<(f64, Vector3<f64>, Matrix3<f64>)> {
    let solid: Vec<&Geom> = geoms.iter().filter(|g| !matches!(g.kind, GeomKind::Plane)).collect();
    let mass: f64 = solid.iter().map(|g| g.mass()).sum();
    if mass <= 0.0 {
        return None;
    }
    // Each geom's centre of mass and inertia about it, in the body's frame.
    let parts: Vec<(f64, Vector3<f64>, Matrix3<f64>)> = solid
        .iter()
        .map(|g| {
            let (centre, inertia) = g.mass_distribution();
            let r = g.frame.rotation.to_rotation_matrix();
            (g.mass(), (g.frame * nalgebra::Point3::from(centre)).coords, crate::formats::turned_inertia(&r, &inertia))
        })
        .collect();
    let com = parts.iter().map(|(m, c, _)| c * *m).sum::<Vector3<f64>>() / mass;
    let mut inertia = Matrix3::zeros();
    for (m, c, about_centre) in parts {
        let d = c - com;
        inertia += about_centre + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m;
    }
    Some((mass, com, inertia))
}

/// A body's mass and inertia raised to `<compiler boundmass boundinertia>` (`bounds`),
/// as MuJoCo raises every body's: the mass to the first, each principal moment to the
/// second; a body without mass (given `boundmass`) weighs it at its origin.
pub(super) fn bounded(
    mass: Option<(f64, Vector3<f64>, Matrix3<f64>)>,
    (least_mass, least_moment): (f64, f64),
) -> Option<(f64, Vector3<f64>, Matrix3<f64>)> {
    let (mass, centre, inertia) = match mass {
        Some(m) => m,
        None if least_mass > 0.0 => (0.0, Vector3::zeros(), Matrix3::zeros()),
        None => return None,
    };
    let inertia = if least_moment > 0.0 {
        let eigen = inertia.symmetric_eigen();
        let moments = eigen.eigenvalues.map(|m| m.max(least_moment));
        eigen.eigenvectors * Matrix3::from_diagonal(&moments) * eigen.eigenvectors.transpose()
    } else {
        inertia
    };
    Some((mass.max(least_mass), centre, inertia))
}

/// The inertia a ball joint's armature adds to the object it moves, in that object's
/// frame: `armature · 1` (a hinge's and a slide's are the joint's own, held by a motor
/// beside it: [`SimJoint::set_armature`](crate::SimJoint::set_armature); a free
/// joint's is listed as skipped).
pub(super) fn armature_inertia(joint: &Joint) -> Matrix3<f64> {
    match joint.kind {
        JointKind::Ball if joint.armature > 0.0 => Matrix3::identity() * joint.armature,
        _ => Matrix3::zeros(),
    }
}

/// A mass below ARS's least ([`MIN_MASS`](crate::limits::MIN_MASS): a marker of a
/// few milligrams, as in Gymnasium's pusher) raised to it, the inertia scaled alike,
/// with a warning in `skipped`; any other mass as it is.
pub(super) fn at_least_ars_least_mass(
    what: &str,
    mass: f64,
    inertia: Matrix3<f64>,
    skipped: &mut Vec<String>,
) -> (f64, Matrix3<f64>) {
    let least = crate::limits::MIN_MASS;
    if mass > 0.0 && mass < least {
        skipped.push(format!(
            "{what}: a mass of {mass:e} kg is below ARS's least ({least:e} kg): raised to it, the inertia scaled alike"
        ));
        (least, inertia * (least / mass))
    } else {
        (mass, inertia)
    }
}

/// The sum of the bodies' masses, their children's included.
pub(super) fn total_mass(bodies: &[Body]) -> f64 {
    bodies.iter().map(|b| b.mass.map_or(0.0, |m| m.0) + total_mass(&b.children)).sum()
}

/// Scales every body's mass and inertia (its children's too) by `factor`.
pub(super) fn scale_masses(bodies: &mut [Body], factor: f64) {
    for b in bodies {
        if let Some((mass, _, inertia)) = b.mass.as_mut() {
            *mass *= factor;
            *inertia *= factor;
        }
        scale_masses(&mut b.children, factor);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_ellipsoid_collides_as_a_hull_close_to_it_not_as_a_sphere() {
        let radii = Vector3::new(0.1, 0.2, 0.4);
        let Shape::ConvexHull { vertices, .. } = ellipsoid_hull(&radii) else { panic!("not a hull") };
        // Every point on the ellipsoid; the hull reaches to within 1.5 % of it along
        // any direction (its support is the farthest point).
        for v in &vertices {
            let on = (v.x / radii.x).powi(2) + (v.y / radii.y).powi(2) + (v.z / radii.z).powi(2);
            assert!((on - 1.0).abs() < 1e-12, "{v}");
        }
        for k in 0..20_000 {
            // Directions spread over the sphere.
            let z = 1.0 - (2.0 * k as f64 + 1.0) / 20_000.0;
            let (s, c) = (2.4 * k as f64).sin_cos();
            let d = Vector3::new((1.0 - z * z).sqrt() * c, (1.0 - z * z).sqrt() * s, z);
            let support = vertices.iter().map(|v| d.dot(&v.coords)).fold(f64::NEG_INFINITY, f64::max);
            let ellipsoid = (radii.component_mul(&d)).norm();
            assert!(support <= ellipsoid + 1e-12 && support > 0.985 * ellipsoid, "{d}: {support} of {ellipsoid}");
        }
    }
}
