//! ARS's Y-up world seen from ROS's Z-up one (REP 103: x forward, y left, z up).
//!
//! ARS's world frame has Y up; ROS tools (RViz, Foxglove, Nav2) expect Z up. The world
//! frame ARS publishes, `map`, is ARS's world turned +90° about X: a point (x, y, z) of
//! ARS is (x, −z, y) in `map`, so ARS's up (+Y) is `map`'s +Z, and the ground plane
//! y = 0 is z = 0. It is the inverse of the turn that loads a Z-up URDF file into ARS,
//! so a URDF robot's root link stands in `map` as its file says.
//!
//! A frame on something built in ARS's Y-up world (an object of a scene, a lidar, an
//! IMU on such an object) is given the same way: its ROS axes are its ARS axes turned
//! +90° about X ([`ros_axes`]), so that its X stays, its ARS up (+Y) is its ROS +Z, and
//! an upright object is upright in ROS (a vehicle's chassis is a Z-up `base_link`).
//! A lidar's beams fan in its X–Z plane from +X towards −Z; a `LaserScan` fans in its
//! frame's X–Y plane from +X towards +Y: in its ROS axes the scan's angles are ARS's
//! azimuths unchanged. A URDF link's frame is its file's, Z-up already: it is not
//! turned, and transforms between two links are ARS's unchanged.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};

use crate::msg;

/// The turn from ARS's world to `map`: +90° about X, (x, y, z) ↦ (x, −z, y).
pub fn ars_to_ros() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
}

/// A pose in ARS's world as a pose in `map` (its position exactly: coordinates are
/// swapped, not multiplied).
pub fn world_pose_to_ros(pose: &Isometry3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(world_vector_to_ros(&pose.translation.vector).into(), ars_to_ros() * pose.rotation)
}

/// A vector in ARS's world as a vector in `map`: (x, y, z) ↦ (x, −z, y), exactly.
pub fn world_vector_to_ros(v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.x, -v.z, v.y)
}

/// The ROS axes of a frame built in ARS's Y-up world, in that frame (see the [module
/// docs](self)): what an ARS object's pose, a lidar's mount and an IMU's mount are
/// composed with. A vector `v` in the ARS frame is `ars_to_ros() * v` in the ROS one.
pub fn ros_axes() -> Isometry3<f64> {
    Isometry3::from_parts(Vector3::zeros().into(), ars_to_ros().inverse())
}

/// A vector as a message.
pub fn vector(v: &Vector3<f64>) -> msg::Vector3 {
    msg::Vector3 { x: v.x, y: v.y, z: v.z }
}

/// A rotation as a message (`w` last).
pub fn quaternion(q: &UnitQuaternion<f64>) -> msg::Quaternion {
    msg::Quaternion { x: q.i, y: q.j, z: q.k, w: q.w }
}

/// A pose as a transform message.
pub fn transform(pose: &Isometry3<f64>) -> msg::Transform {
    msg::Transform { translation: vector(&pose.translation.vector), rotation: quaternion(&pose.rotation) }
}

/// A pose as a pose message.
pub fn pose(pose: &Isometry3<f64>) -> msg::Pose {
    let t = pose.translation.vector;
    msg::Pose { position: msg::Point { x: t.x, y: t.y, z: t.z }, orientation: quaternion(&pose.rotation) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ars_up_is_ros_up_and_ars_minus_z_is_ros_y() {
        let near = |a: Vector3<f64>, b: Vector3<f64>| (a - b).norm() < 1e-15;
        assert!(near(world_vector_to_ros(&Vector3::y()), Vector3::z()));
        assert!(near(world_vector_to_ros(&Vector3::new(1.0, 2.0, 3.0)), Vector3::new(1.0, -3.0, 2.0)));
        let v = Vector3::new(0.3, -1.7, 2.9);
        assert!(near(world_vector_to_ros(&v), ars_to_ros() * v), "the swap is the turn");
        // A body 2 m up and turned 90° about ARS's up (Y) is 2 m up in map, turned 90°
        // about map's up (Z).
        let up = Isometry3::new(Vector3::new(0.0, 2.0, 0.0), Vector3::y() * std::f64::consts::FRAC_PI_2);
        let ros = world_pose_to_ros(&up);
        assert!(near(ros.translation.vector, Vector3::new(0.0, 0.0, 2.0)));
        // The body's own X axis: in ARS it points to −Z after the turn; in map that is +Y.
        assert!(near(ros.rotation * Vector3::x(), Vector3::y()), "{}", ros.rotation * Vector3::x());
    }

    #[test]
    fn a_lidar_beam_at_azimuth_a_is_at_angle_a_in_its_ros_frame() {
        for a in [0.0, 0.4, -1.2, 2.5] {
            let beam_ars = Vector3::new(f64::cos(a), 0.0, -f64::sin(a));
            let in_ros_frame = ros_axes().inverse() * beam_ars;
            let expected = Vector3::new(f64::cos(a), f64::sin(a), 0.0);
            assert!((in_ros_frame - expected).norm() < 1e-15, "{a}: {in_ros_frame}");
        }
    }
}
