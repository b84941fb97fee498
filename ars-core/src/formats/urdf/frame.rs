//! Frames as URDF writes them: an origin's xyz and rpy, composed exactly.

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};

use super::model;
use crate::convert::rotation_about_axis;
use crate::scene::objects::multiply;

/// A rigid frame; `identity` rotations are kept apart so that composing with them does
/// no arithmetic (a file's frames then give exactly the numbers written).
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    pub(super) rotation: Option<Matrix3<f64>>,
    pub(super) translation: Vector3<f64>,
}

impl Frame {
    pub(super) const IDENTITY: Frame = Frame { rotation: None, translation: Vector3::new(0.0, 0.0, 0.0) };

    pub(super) fn from_pose(pose: &model::Pose) -> Frame {
        Frame { rotation: rpy_matrix(pose.rpy.0), translation: Vector3::from(pose.xyz.0) }
    }

    pub(super) fn from_isometry(pose: &Isometry3<f64>) -> Frame {
        let identity = pose.rotation == UnitQuaternion::identity();
        Frame {
            rotation: (!identity).then(|| *pose.rotation.to_rotation_matrix().matrix()),
            translation: pose.translation.vector,
        }
    }

    pub(super) fn rotate(&self, v: &Vector3<f64>) -> Vector3<f64> {
        match &self.rotation {
            None => *v,
            Some(r) => Vector3::new(
                r[(0, 0)] * v.x + r[(0, 1)] * v.y + r[(0, 2)] * v.z,
                r[(1, 0)] * v.x + r[(1, 1)] * v.y + r[(1, 2)] * v.z,
                r[(2, 0)] * v.x + r[(2, 1)] * v.y + r[(2, 2)] * v.z,
            ),
        }
    }

    /// `self ∘ child`: the child frame, given relative to this one.
    pub(super) fn then(&self, child: &Frame) -> Frame {
        let rotation = match (&self.rotation, &child.rotation) {
            (None, r) | (r, None) => *r,
            (Some(a), Some(b)) => Some(multiply(a, b)),
        };
        Frame { rotation, translation: self.translation + self.rotate(&child.translation) }
    }

    /// `self⁻¹ ∘ other`: `other` relative to this frame.
    pub(super) fn relative(&self, other: &Frame) -> Isometry3<f64> {
        let a = self.isometry();
        a.inverse() * other.isometry()
    }

    pub(super) fn same_as(&self, other: &Frame) -> bool {
        self.rotation == other.rotation && self.translation == other.translation
    }

    pub(super) fn rotation3(&self) -> Rotation3<f64> {
        Rotation3::from_matrix_unchecked(self.rotation.unwrap_or_else(Matrix3::identity))
    }

    pub(super) fn isometry(&self) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(self.translation),
            UnitQuaternion::from_rotation_matrix(&self.rotation3()),
        )
    }
}

/// `Rz(yaw) · Ry(pitch) · Rx(roll)`, URDF's fixed-axis convention; `None` for no turn.
pub(super) fn rpy_matrix([roll, pitch, yaw]: [f64; 3]) -> Option<Matrix3<f64>> {
    let turns = [(Vector3::z(), yaw), (Vector3::y(), pitch), (Vector3::x(), roll)];
    turns.iter().filter(|(_, angle)| *angle != 0.0).fold(None, |acc, (axis, angle)| {
        let turn = *rotation_about_axis(axis, *angle).matrix();
        Some(match acc {
            None => turn,
            Some(m) => multiply(&m, &turn),
        })
    })
}

/// −90° about X, exactly: URDF (x, y, z) → simulation (x, z, −y).
pub(super) fn z_up_to_y_up() -> Frame {
    Frame { rotation: Some(crate::formats::z_up_to_y_up().into_inner()), translation: Vector3::zeros() }
}
