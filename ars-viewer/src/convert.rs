//! nalgebra `f64` (the simulation) to glam `f32` (kiss3d) and back, in one place.

use ars_core::nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use kiss3d::glamx::{Pose3, Quat, Vec3};

/// A point.
pub fn point(p: &Point3<f64>) -> Vec3 {
    Vec3::new(p.x as f32, p.y as f32, p.z as f32)
}

/// A vector.
pub fn vector(v: &Vector3<f64>) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// A rotation.
pub fn rotation(q: &UnitQuaternion<f64>) -> Quat {
    Quat::from_xyzw(q.i as f32, q.j as f32, q.k as f32, q.w as f32)
}

/// A pose.
pub fn pose(iso: &Isometry3<f64>) -> Pose3 {
    Pose3::from_parts(vector(&iso.translation.vector), rotation(&iso.rotation))
}

/// A point back (kiss3d to the simulation: picking rays).
pub fn point_back(p: Vec3) -> Point3<f64> {
    Point3::new(f64::from(p.x), f64::from(p.y), f64::from(p.z))
}

/// A vector back (kiss3d to the simulation).
pub fn vector_back(v: Vec3) -> Vector3<f64> {
    Vector3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// An RGB colour.
pub fn color(rgb: [f32; 3]) -> kiss3d::color::Color {
    kiss3d::color::Color::new(rgb[0], rgb[1], rgb[2], 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pose_maps_points_the_same_way() {
        let iso = Isometry3::new(Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.3, 1.2, -0.7));
        let p = Point3::new(0.4, 0.5, -1.5);
        let expected = point(&(iso * p));
        let got = pose(&iso) * point(&p);
        assert!((expected - got).length() < 1e-5, "{expected} vs {got}");
    }

    #[test]
    fn points_and_vectors_come_back() {
        let p = Point3::new(0.25, -2.5, 1e3);
        assert_eq!(point_back(point(&p)), p);
        let v = Vector3::new(-0.5, 0.125, 8.0);
        assert_eq!(vector_back(vector(&v)), v);
    }
}
