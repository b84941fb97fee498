//! The window's extra views (keys `1`–`4`): each drawn off screen, sharing the
//! window's rendering context, and shown in its quarter of the window as an egui image
//! with a caption. What each view shows is [`viewports`](mod@crate::viewports)'.

use ars_core::nalgebra::Point3;
use ars_core::{ObjectId, Simulation, WindowSettings};
use kiss3d::egui;
use kiss3d::window::{CanvasSetup, NumSamples, OffscreenSurface};

use crate::convert;
use crate::layout::Rect;
use crate::scene::DrawnScene;
use crate::viewports::{Seen, VIEWPORT_KINDS, ViewportKind, camera_of, viewports};

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
