//! Several views at once (keys `1`–`4`): the window's own free camera in the top-left
//! quarter, and in the other quarters a camera following a body, a top orthographic
//! view, and what the scene's first depth camera sees. kiss3d 0.47 draws a window
//! through one camera (its per-pass viewports are not implemented), so the other views
//! are drawn off screen, sharing the window's rendering context, and shown as images.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::DepthCamera;
use ars_core::{ObjectId, Simulation};
use kiss3d::camera::{FirstPersonCamera3d, OrbitCamera3d, Projection};
use kiss3d::scene::SceneNode3d;
use kiss3d::window::OffscreenSurface;

use crate::convert;
use crate::layout::Rect;

/// What a viewport shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewportKind {
    /// The window's camera, moved with the mouse.
    Free,
    /// A camera 5 m from the selected body (or the followed one, or the first moving
    /// one), looking at it from the free camera's side.
    Follow,
    /// Straight down on what the free camera looks at, orthographic.
    Top,
    /// What one of the scene's depth cameras sees (the first, unless another is
    /// chosen in the panel).
    Sensor,
}

/// The kinds of the viewports, in the order keys `1`–`4` add them.
pub const VIEWPORT_KINDS: [ViewportKind; 4] =
    [ViewportKind::Free, ViewportKind::Follow, ViewportKind::Top, ViewportKind::Sensor];

/// The viewports of `count` views (1 to 4; more or fewer are clamped) in a `width ×
/// height` window: the whole window for one, else the quarters of a 2 × 2 grid in
/// reading order (top left, top right, bottom left, bottom right).
pub fn viewports(width: f32, height: f32, count: usize) -> Vec<Rect> {
    let count = count.clamp(1, 4);
    if count == 1 {
        return vec![[0.0, 0.0, width, height]];
    }
    let (w, h) = (width / 2.0, height / 2.0);
    (0..count)
        .map(|i| {
            let (x, y) = ((i % 2) as f32 * w, (i / 2) as f32 * h);
            [x, y, x + w, y + h]
        })
        .collect()
}

/// The point a follow view looks at: the selected body, else the followed object,
/// else the first moving body.
pub(crate) fn followed(sim: &Simulation, selected: Option<ObjectId>, follow: Option<&str>) -> Option<Point3<f64>> {
    let by_id = |id: ObjectId| sim.scene().body(id).ok().map(|b| b.position());
    selected
        .and_then(by_id)
        .or_else(|| follow.and_then(|name| sim.scene().object(name).ok()).and_then(|o| o.position().ok()))
        .or_else(|| sim.scene().bodies().next().and_then(|(id, _)| by_id(id)))
}

/// What a view shows.
pub(crate) enum Seen {
    /// The free view: the window's (or the renderer's) own camera.
    Free,
    /// The scene through this camera, with the view's caption.
    Through(Box<ViewportCamera>, &'static str),
    /// Nothing, for this reason.
    Nothing(&'static str),
}

/// The camera of a view other than the free one.
pub(crate) enum ViewportCamera {
    /// Following a body, or from above (orthographic).
    Orbit(OrbitCamera3d),
    /// Through a camera sensor's eye.
    Eye(FirstPersonCamera3d),
}

impl ViewportCamera {
    /// Draws `scene` through this camera into `surface`.
    pub(crate) async fn draw(&mut self, surface: &mut OffscreenSurface, scene: &mut SceneNode3d) {
        match self {
            ViewportCamera::Orbit(camera) => surface.render_3d(scene, camera).await,
            ViewportCamera::Eye(camera) => surface.render_3d(scene, camera).await,
        }
    }
}

/// What the view of `kind` shows of `sim`: `free` is the free camera's eye and target,
/// `target` the point a follow view looks at ([`followed`]), `camera` the depth camera
/// a camera view shows (counted from 0; the last if there are fewer).
pub(crate) fn camera_of(
    kind: ViewportKind,
    sim: &Simulation,
    free: (Point3<f64>, Point3<f64>),
    target: Option<Point3<f64>>,
    camera: usize,
) -> ars_core::Result<Seen> {
    let (eye, at) = free;
    Ok(match kind {
        ViewportKind::Free => Seen::Free,
        ViewportKind::Follow => {
            let Some(target) = target else { return Ok(Seen::Nothing("2 follow: no moving body")) };
            let side = (eye - at).try_normalize(1e-9).unwrap_or_else(Vector3::z);
            let camera = OrbitCamera3d::new(convert::point(&(target + side * 5.0)), convert::point(&target));
            Seen::Through(Box::new(ViewportCamera::Orbit(camera)), "2 follow")
        }
        ViewportKind::Top => {
            let height = (eye - at).norm().max(1.0);
            let above = at + Vector3::new(0.0, height, 1e-3 * height);
            let mut camera = OrbitCamera3d::new(convert::point(&above), convert::point(&at));
            camera.set_projection(Projection::Orthographic);
            Seen::Through(Box::new(ViewportCamera::Orbit(camera)), "3 top")
        }
        ViewportKind::Sensor => {
            let cameras = sim.sensors_of::<DepthCamera>().count();
            let Some(sensor) = sim.sensors_of::<DepthCamera>().nth(camera.min(cameras.saturating_sub(1))) else {
                return Ok(Seen::Nothing("4 camera: no depth camera in the scene"));
            };
            Seen::Through(Box::new(ViewportCamera::Eye(sensor_camera(sensor, sim)?)), "4 camera")
        }
    })
}

/// The colour camera at a depth camera's place, with its field of view and range, its
/// image rolling with it: what [`Camera`](crate::Camera) renders.
pub(crate) fn sensor_camera(sensor: &DepthCamera, sim: &Simulation) -> ars_core::Result<FirstPersonCamera3d> {
    let pose = sensor.mount().pose(sim.scene())?;
    let eye = Point3::from(pose.translation.vector);
    let at = eye + pose.rotation * -Vector3::z();
    let mut camera = FirstPersonCamera3d::new_with_frustum(
        sensor.fov_y() as f32,
        sensor.near() as f32,
        sensor.far() as f32,
        convert::point(&eye),
        convert::point(&at),
    );
    camera.set_up_axis(convert::vector(&(pose.rotation * Vector3::y())));
    Ok(camera)
}

/// The pixel rectangles (left, top, width, height) of `count` views in a `width ×
/// height` image: [`viewports`] rounded to whole pixels, covering the image exactly.
pub(crate) fn pixel_cells(width: u32, height: u32, count: usize) -> Vec<[u32; 4]> {
    viewports(width as f32, height as f32, count)
        .into_iter()
        .map(|[l, t, r, b]| {
            let (l, t, r, b) = (l.round() as u32, t.round() as u32, r.round() as u32, b.round() as u32);
            [l, t, r - l, b - t]
        })
        .collect()
}

/// Copies `cell` (RGB rows of `rect`'s size, bottom row first, as read back) into its
/// place in `image` (RGB rows of `width × height`, bottom row first).
pub(crate) fn place(image: &mut [u8], width: u32, height: u32, rect: [u32; 4], cell: &[u8]) {
    let [left, top, w, h] = rect;
    let row = 3 * w as usize;
    // The cell's bottom row is the image's row `height - top - h`, counted from the bottom.
    let first = (height - top - h) as usize;
    for (i, source) in cell.chunks_exact(row).take(h as usize).enumerate() {
        let start = 3 * ((first + i) * width as usize + left as usize);
        image[start..start + row].copy_from_slice(source);
    }
}

/// The colour of a view that shows nothing (as in the window).
pub(crate) const EMPTY_VIEW: u8 = 40;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_view_fills_the_window_and_more_share_its_quarters() {
        assert_eq!(viewports(800.0, 600.0, 1), [[0.0, 0.0, 800.0, 600.0]]);
        assert_eq!(viewports(800.0, 600.0, 0), [[0.0, 0.0, 800.0, 600.0]]);
        let four = viewports(800.0, 600.0, 4);
        assert_eq!(
            four,
            [
                [0.0, 0.0, 400.0, 300.0],
                [400.0, 0.0, 800.0, 300.0],
                [0.0, 300.0, 400.0, 600.0],
                [400.0, 300.0, 800.0, 600.0]
            ]
        );
        assert_eq!(viewports(800.0, 600.0, 3), four[..3]);
        assert_eq!(viewports(800.0, 600.0, 9), four);
    }

    #[test]
    fn a_follow_view_looks_at_the_selection_first() {
        use ars_core::Mass;
        let mut sim = Simulation::new().unwrap();
        assert_eq!(followed(&sim, None, None), None);
        let a = sim.scene_mut().add_sphere(0.1, [1.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
        let b = sim.scene_mut().add_sphere(0.1, [2.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
        sim.scene_mut().set_name(b, "b").unwrap();
        assert_eq!(followed(&sim, None, None), Some(Point3::new(1.0, 0.0, 0.0)));
        assert_eq!(followed(&sim, None, Some("b")), Some(Point3::new(2.0, 0.0, 0.0)));
        assert_eq!(followed(&sim, Some(a), Some("b")), Some(Point3::new(1.0, 0.0, 0.0)));
    }
}
