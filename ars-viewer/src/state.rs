//! What the window shows besides the scene, as data: the selected body and what the
//! panel says about it, the drag in progress, the panel's last error and where the
//! scene was saved. The window hands it to its [`Driver`](crate::Driver) every frame
//! ([`Driver::viewer_state`](crate::Driver::viewer_state)), for front ends that mirror
//! it and for tests that drive the window as a person would.

use std::path::PathBuf;

use ars_core::nalgebra::{Matrix4, Point3, UnitQuaternion, Vector3};
use ars_core::{ObjectId, Simulation};

use crate::interact::DragMode;

/// The selected body, as the panel shows it.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Selected {
    /// The object.
    pub id: ObjectId,
    /// Its name.
    pub name: String,
    /// Its mass, kg.
    pub mass: f64,
    /// The volume of its one solid shape, m³ (`None` for a body of several shapes):
    /// what its density is reckoned on.
    pub volume: Option<f64>,
    /// Its position (centre of mass), m.
    pub position: Point3<f64>,
    /// Its orientation.
    pub rotation: UnitQuaternion<f64>,
    /// Its velocity, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Its angular velocity, rad/s.
    pub angular_velocity: Vector3<f64>,
}

impl Selected {
    /// The body `id` of `sim` as it is now (`None` when it has no body, or is gone).
    pub fn of(sim: &Simulation, id: ObjectId) -> Option<Self> {
        let object = sim.scene().object(id).ok()?;
        let body = object.body().ok()?;
        Some(Selected {
            id,
            name: object.name().to_string(),
            mass: body.mass(),
            volume: crate::edit::solid_volume(sim, id).ok(),
            position: body.position(),
            rotation: body.quaternion(),
            linear_velocity: body.linear_velocity(),
            angular_velocity: body.angular_velocity(),
        })
    }
}

/// A drag in progress: from the grabbed point to the point under the mouse (the line
/// the window draws).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DragLine {
    /// Force (Ctrl) or torque (Shift).
    pub mode: DragMode,
    /// The grabbed point, world frame.
    pub from: Point3<f64>,
    /// The point under the mouse, on the plane through the grabbed point facing the
    /// camera.
    pub to: Point3<f64>,
}

/// What the window shows besides the scene, this frame.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct ViewerState {
    /// Whether the simulation is paused.
    pub paused: bool,
    /// The selected body (a click on it; Escape deselects).
    pub selected: Option<Selected>,
    /// The drag in progress.
    pub drag: Option<DragLine>,
    /// The error the panel shows: the last edit refused, or a save that failed
    /// (cleared by the next edit that succeeds).
    pub error: Option<String>,
    /// Where `Ctrl+S` (or the panel's Save button) saves the scene.
    pub save_path: PathBuf,
    /// Where the scene was saved last.
    pub saved: Option<PathBuf>,
    /// The editor's number fields drawn this frame, by label (`"mass"`, `"x"`,
    /// `"gravity y"`, `"time step"`…), with their rectangles `[left, top, right,
    /// bottom]` in window pixels.
    pub fields: Vec<(String, [f32; 4])>,
    /// What each of those fields shows, by label: the characters drawn whole (a text
    /// wider than its field would be cut).
    pub field_texts: Vec<(String, String)>,
    /// The window's size, pixels.
    pub window_size: (f32, f32),
    /// How many views the window shows (1 to 4: keys `1`–`4`, see
    /// [`viewports`](fn@crate::viewports)).
    pub views: usize,
    /// World to normalised device coordinates, as the camera draws.
    pub(crate) view_projection: Matrix4<f64>,
}

impl ViewerState {
    /// Where the world point `p` appears in the window (pixels from the top left), as
    /// the camera draws it now; `None` behind the camera.
    pub fn window_point(&self, p: &Point3<f64>) -> Option<(f64, f64)> {
        let c = self.view_projection * p.to_homogeneous();
        if c.w <= 0.0 {
            return None;
        }
        let (w, h) = (f64::from(self.window_size.0), f64::from(self.window_size.1));
        Some(((c.x / c.w + 1.0) / 2.0 * w, (1.0 - c.y / c.w) / 2.0 * h))
    }

    /// The rectangle of the editor's field `label`, if drawn this frame.
    pub fn field(&self, label: &str) -> Option<[f32; 4]> {
        self.fields.iter().find(|(l, _)| l == label).map(|(_, r)| *r)
    }

    /// The text the editor's field `label` shows, if drawn this frame: as much of it as
    /// is drawn whole.
    pub fn field_text(&self, label: &str) -> Option<&str> {
        self.field_texts.iter().find(|(l, _)| l == label).map(|(_, t)| t.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_points_follow_the_projection() {
        let mut state = ViewerState { window_size: (800.0, 600.0), ..ViewerState::default() };
        state.view_projection = Matrix4::identity();
        assert_eq!(state.window_point(&Point3::origin()), Some((400.0, 300.0)));
        // x right, y up in device coordinates; y down in the window.
        assert_eq!(state.window_point(&Point3::new(0.5, 0.5, 0.0)), Some((600.0, 150.0)));
        state.view_projection[(3, 3)] = -1.0;
        assert_eq!(state.window_point(&Point3::origin()), None);
    }
}
