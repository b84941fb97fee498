//! Several views at once (keys `1`–`4`): the window's own free camera in the top-left
//! quarter, and in the other quarters a camera following a body, a top orthographic
//! view, and what the scene's first depth camera sees. kiss3d 0.47 draws a window
//! through one camera (its per-pass viewports are not implemented), so the other views
//! are drawn off screen, sharing the window's rendering context, and shown as images.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::sensors::DepthCamera;
use ars_core::{ObjectId, Simulation, WindowSettings};
use kiss3d::camera::{FirstPersonCamera3d, OrbitCamera3d, Projection};
use kiss3d::egui;
use kiss3d::scene::SceneNode3d;
use kiss3d::window::{CanvasSetup, NumSamples, OffscreenSurface};

use crate::convert;
use crate::layout::Rect;
use crate::scene::DrawnScene;

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

/// One extra view drawn off screen.
struct Extra {
    kind: ViewportKind,
    surface: OffscreenSurface,
    view: DrawnScene,
    size: (u32, u32),
    /// The image drawn last, not yet given to egui.
    pending: Option<egui::ColorImage>,
    texture: Option<egui::TextureHandle>,
    /// What it shows now, or why it shows nothing.
    caption: String,
}

/// The extra views of a window and their images.
#[derive(Default)]
pub(crate) struct Viewports {
    /// How many views are shown (1 to 4).
    pub(crate) count: usize,
    /// The depth camera the camera view shows, counted from 0 in the order the
    /// sensors were added.
    pub(crate) camera: usize,
    extras: Vec<Extra>,
}

impl Viewports {
    /// One view, the window's.
    pub(crate) fn new() -> Self {
        Viewports { count: 1, camera: 0, extras: Vec::new() }
    }

    /// Draws `id` anew in every extra view (after its colour changed).
    pub(crate) fn redraw(&mut self, id: ObjectId) {
        for extra in &mut self.extras {
            extra.view.mirror.redraw(id);
        }
    }

    /// Forgets every extra view's nodes (after the simulation was rebuilt).
    pub(crate) fn clear(&mut self) {
        for extra in &mut self.extras {
            extra.view.mirror.clear();
        }
    }

    /// Draws the extra views of `sim` off screen, each the size of a quarter of the
    /// window (`free`: the free camera's eye and target).
    pub(crate) async fn render(
        &mut self,
        sim: &Simulation,
        settings: &WindowSettings,
        window: (f32, f32),
        free: (Point3<f64>, Point3<f64>),
        target: Option<Point3<f64>>,
    ) -> crate::Result<()> {
        let size = ((window.0 / 2.0).max(16.0) as u32, (window.1 / 2.0).max(16.0) as u32);
        self.extras.retain(|e| e.size == size);
        for kind in VIEWPORT_KINDS.iter().copied().take(self.count).skip(1) {
            if !self.extras.iter().any(|e| e.kind == kind) {
                let setup = CanvasSetup { vsync: false, samples: NumSamples::One, ..CanvasSetup::default() };
                let mut surface = OffscreenSurface::with_setup(size.0, size.1, setup).await;
                surface.set_background_color(convert::color(settings.background));
                let view = DrawnScene::new(settings, surface.window_mut());
                self.extras.push(Extra {
                    kind,
                    surface,
                    view,
                    size,
                    pending: None,
                    texture: None,
                    caption: String::new(),
                });
            }
        }
        for extra in self.extras.iter_mut().filter(|e| VIEWPORT_KINDS[..self.count].contains(&e.kind)) {
            extra.view.mirror.sync(sim, &mut extra.view.scene)?;
            let image = match camera_of(extra.kind, sim, free, target, self.camera)? {
                Seen::Free => continue,
                Seen::Nothing(why) => {
                    extra.caption = why.into();
                    extra.texture = None;
                    continue;
                }
                Seen::Through(mut camera, caption) => {
                    extra.caption = caption.into();
                    camera.draw(&mut extra.surface, &mut extra.view.scene).await;
                    extra.surface.snap_image()
                }
            };
            let pixels = egui::ColorImage::from_rgb([image.width() as usize, image.height() as usize], image.as_raw());
            extra.pending = Some(pixels);
        }
        Ok(())
    }

    /// Shows the extra views' images in their quarters of the window, with their
    /// captions; returns the rectangles they cover (egui's points).
    pub(crate) fn show(&mut self, ctx: &egui::Context) -> Vec<Rect> {
        let mut covered = Vec::new();
        if self.count < 2 {
            return covered;
        }
        let screen = ctx.viewport_rect();
        let cells = viewports(screen.width(), screen.height(), self.count);
        for (i, kind) in VIEWPORT_KINDS.iter().enumerate().take(self.count).skip(1) {
            let Some(extra) = self.extras.iter_mut().find(|e| e.kind == *kind) else { continue };
            if let Some(pixels) = extra.pending.take() {
                match &mut extra.texture {
                    Some(t) => t.set(pixels, egui::TextureOptions::LINEAR),
                    None => {
                        extra.texture =
                            Some(ctx.load_texture(format!("ars-view-{i}"), pixels, egui::TextureOptions::LINEAR));
                    }
                }
            }
            let [l, t, r, b] = cells[i];
            covered.push(cells[i]);
            egui::Area::new(egui::Id::new(("ars-view", i))).order(egui::Order::Background).fixed_pos([l, t]).show(
                ctx,
                |ui| {
                    let rect = egui::Rect::from_min_max([l, t].into(), [r, b].into());
                    ui.painter().rect_filled(rect, 0.0, egui::Color32::from_gray(40));
                    if let Some(texture) = &extra.texture {
                        ui.put(rect, egui::Image::new((texture.id(), rect.size())));
                    }
                    let caption = ui.painter().layout_no_wrap(
                        extra.caption.clone(),
                        egui::FontId::proportional(16.0),
                        egui::Color32::WHITE,
                    );
                    let at = rect.min + egui::vec2(8.0, 6.0);
                    let back = egui::Rect::from_min_size(at, caption.size()).expand(3.0);
                    ui.painter().rect_filled(back, 3.0, egui::Color32::from_black_alpha(160));
                    ui.painter().galley(at, caption, egui::Color32::WHITE);
                    ui.painter().rect_stroke(
                        rect,
                        0.0,
                        egui::Stroke::new(2.0, egui::Color32::from_gray(60)),
                        egui::StrokeKind::Inside,
                    );
                },
            );
        }
        covered
    }
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
