//! Off-screen rendering with no display and no GPU: Mesa's software rasterisers
//! through wgpu (llvmpipe via EGL surfaceless first, lavapipe Vulkan otherwise). The
//! screenshot recorder that writes its frames is `screenshots.rs`.
//!
//! The product description asked for OSMesa; wgpu has no OSMesa backend and Mesa
//! removed OSMesa in 25.1, so Mesa's surfaceless EGL (or lavapipe) is the off-screen path.

use ars_core::nalgebra::Point3;
use ars_core::{Simulation, WindowSettings};
use kiss3d::camera::Camera3d;
use kiss3d::window::{CanvasSetup, NumSamples, OffscreenSurface};

use crate::ViewerOptions;
use crate::convert;
use crate::error::{Result, ViewerError};
use crate::frames::RawFrame;
use crate::scene::{DrawnScene, SceneMirror};
use crate::viewports::{EMPTY_VIEW, Seen, VIEWPORT_KINDS, ViewportKind, camera_of, followed, pixel_cells, place};

thread_local! {
    /// Whether a kiss3d context was made on this thread.
    static CONTEXT_MADE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Whether this thread keeps its context after its last window (see
    /// [`keep_rendering_context`]).
    static KEEP: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// What keeps it: a 1×1 off-screen surface sharing the context, so that kiss3d does
    /// not drop the context when the window closes.
    static KEEPER: std::cell::RefCell<Option<OffscreenSurface>> = const { std::cell::RefCell::new(None) };
}

/// Lets this thread open window after window. kiss3d 0.47 can make one rendering
/// context per thread (see [`ViewerError::SecondContext`]), and drops it with the thread's
/// last window; from now on this thread keeps the context of its next window after
/// that window closes, and its later windows use it.
///
/// The kept context must be given back with [`release_rendering_context`] before the
/// thread ends: wgpu may panic if it is still there while the thread's locals are
/// destroyed. (The Python package releases it when the interpreter exits.)
pub fn keep_rendering_context() {
    KEEP.with(|k| k.set(true));
}

/// Gives back the context [`keep_rendering_context`] kept (it is dropped now if no
/// window uses it), and stops keeping it. Does nothing if none is kept.
pub fn release_rendering_context() {
    KEEP.with(|k| k.set(false));
    let keeper = KEEPER.with(|k| k.borrow_mut().take());
    drop(keeper);
}

/// After a window opened: keeps its context if this thread asked to.
pub(crate) fn keep_context_if_asked() {
    if !KEEP.with(|k| k.get()) || KEEPER.with(|k| k.borrow().is_some()) {
        return;
    }
    // The context exists (the window made or used it): the surface shares it.
    let setup = CanvasSetup { vsync: false, samples: NumSamples::One, ..CanvasSetup::default() };
    let mut surface = kiss3d::pollster::block_on(OffscreenSurface::with_setup(1, 1, setup));
    let window = surface.window_mut();
    window.set_shadows_enabled(false);
    window.set_shadow_atlas_layers(1);
    window.set_shadow_resolution(64);
    KEEPER.with(|k| *k.borrow_mut() = Some(surface));
}

/// Refuses a second kiss3d context on a thread whose first one is gone (with the
/// last window or renderer that used it). kiss3d 0.47 keeps some GPU objects of the
/// first context per thread (its deform bind-group layout), so a second one fails
/// inside kiss3d ("non-existent resource"). A new thread gets a fresh start.
pub(crate) fn check_context_reuse() -> Result<()> {
    if !kiss3d::context::Context::is_initialized() && CONTEXT_MADE.with(|m| m.get()) {
        return Err(ViewerError::SecondContext);
    }
    Ok(())
}

/// Notes that this thread made its kiss3d context.
pub(crate) fn context_made() {
    CONTEXT_MADE.with(|m| m.set(true));
}

/// Creates kiss3d's wgpu context on this thread with a software-friendly adapter:
/// OpenGL ES through EGL (Mesa llvmpipe, the faster software path) first, then any
/// other backend (lavapipe Vulkan). Does nothing if a context already exists.
pub fn init_offscreen_context() -> Result<()> {
    if kiss3d::context::Context::is_initialized() {
        return Ok(());
    }
    check_context_reuse()?;
    kiss3d::pollster::block_on(async {
        let mut reasons = Vec::new();
        for backends in [wgpu::Backends::GL, wgpu::Backends::all()] {
            let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
                backends,
                ..wgpu::InstanceDescriptor::new_without_display_handle()
            });
            let adapter = match instance
                .request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::default(),
                    compatible_surface: None,
                    force_fallback_adapter: false,
                    apply_limit_buckets: false,
                })
                .await
            {
                Ok(a) => a,
                Err(e) => {
                    reasons.push(format!("{backends:?}: {e}"));
                    continue;
                }
            };
            let device = adapter
                .request_device(&wgpu::DeviceDescriptor {
                    label: Some("ars-viewer off-screen device"),
                    required_features: wgpu::Features::empty(),
                    required_limits: adapter.limits(),
                    memory_hints: wgpu::MemoryHints::default(),
                    trace: wgpu::Trace::Off,
                    experimental_features: wgpu::ExperimentalFeatures::disabled(),
                })
                .await;
            match device {
                Ok((device, queue)) => {
                    log::info!("off-screen rendering on {:?}", adapter.get_info());
                    kiss3d::context::Context::init(instance, device, queue, adapter, wgpu::TextureFormat::Rgba8Unorm);
                    context_made();
                    return Ok(());
                }
                Err(e) => reasons.push(format!("{backends:?}: {e}")),
            }
        }
        Err(ViewerError::NoAdapter(reasons.join("; ")))
    })
}

/// Renders a simulation into images, off screen.
pub struct OffscreenRenderer {
    surface: OffscreenSurface,
    view: DrawnScene,
    /// The other views when several are drawn ([`ViewerOptions::views`]); `surface`
    /// then draws the free one, in the top-left quarter.
    views: Option<OffscreenViewports>,
}

impl OffscreenRenderer {
    /// A renderer of `view.size` pixels with the view's camera and background.
    pub fn new(view: &WindowSettings) -> Result<Self> {
        OffscreenRenderer::with_options(view, &ViewerOptions::default())
    }

    /// As [`new`](Self::new), drawing what `options` say.
    pub fn with_options(view: &WindowSettings, options: &ViewerOptions) -> Result<Self> {
        let (w, h) = view.size;
        if w == 0 || h == 0 || w > 8192 || h > 8192 {
            return Err(ViewerError::InvalidSetting(format!("image size {w}×{h} must be between 1 and 8192 pixels")));
        }
        if !(1..=4).contains(&options.views.max(1)) || (options.views > 1 && (w < 2 || h < 2)) {
            return Err(ViewerError::InvalidSetting(format!(
                "{} views in a {w}×{h} image: 1 to 4 views, of at least one pixel each",
                options.views
            )));
        }
        init_offscreen_context()?;
        let mut mirror = SceneMirror::new();
        mirror.show_axes = options.axes;
        mirror.show_forces = options.forces;
        let views = (options.views > 1).then(|| OffscreenViewports::new(view, options.views, &mirror));
        let (w, h) = views.as_ref().map_or((w, h), OffscreenViewports::free_size);
        let (surface, shown) = surface_with_view(view, (w, h), &mirror);
        // The last kiss3d window of a thread, dropped, resets the 2D materials after its
        // textures are gone, making them first if no frame did: a panic (in kiss3d's
        // texture_manager.rs). Made now, a renderer dropped before its first frame (a
        // recording refused once its renderer had started) drops cleanly.
        kiss3d::resource::MaterialManager2d::get_global_manager(|_| ());
        Ok(OffscreenRenderer { surface, view: shown, views })
    }

    /// Renders the simulation as it is now.
    pub fn render(&mut self, sim: &Simulation) -> Result<image::RgbImage> {
        Ok(self.render_raw(sim)?.into_image())
    }

    /// Renders the simulation as it is now, the rows as read back (bottom row first):
    /// the recorder flips them on its writer threads.
    pub(crate) fn render_raw(&mut self, sim: &Simulation) -> Result<RawFrame> {
        self.view.update(sim, self.surface.window_mut())?;
        let DrawnScene { scene, camera, .. } = &mut self.view;
        kiss3d::pollster::block_on(self.surface.render_3d(scene, camera));
        let mut bottom_up = Vec::new();
        self.surface.snap(&mut bottom_up);
        let size = self.surface.size();
        let Some(views) = &mut self.views else {
            return Ok(RawFrame { width: size.x, height: size.y, bottom_up });
        };
        let free = (convert::point_back(self.view.camera.eye()), convert::point_back(self.view.camera.orbit.at()));
        let (width, height) = views.size();
        let bottom_up = views.compose(sim, &bottom_up, free, self.view.follow.as_deref())?;
        Ok(RawFrame { width, height, bottom_up })
    }

    /// Forgets the scene (after the simulation was rebuilt).
    pub fn reset(&mut self) {
        self.view.mirror.clear();
        if let Some(views) = &mut self.views {
            views.clear();
        }
    }
}

/// An off-screen surface of `size` pixels with `settings`' background, and the view of
/// `settings` drawn into it, drawing what `mirror` draws (axes, forces). Needs the
/// rendering context.
pub(crate) fn surface_with_view(
    settings: &WindowSettings,
    (width, height): (u32, u32),
    mirror: &SceneMirror,
) -> (OffscreenSurface, DrawnScene) {
    // One sample: MSAA ×4 renders black on Mesa's GL path.
    let setup = CanvasSetup { vsync: false, samples: NumSamples::One, ..CanvasSetup::default() };
    let mut surface = kiss3d::pollster::block_on(OffscreenSurface::with_setup(width, height, setup));
    surface.set_background_color(convert::color(settings.background));
    let mut view = DrawnScene::new(settings, surface.window_mut());
    view.mirror.show_axes = mirror.show_axes;
    view.mirror.show_forces = mirror.show_forces;
    (surface, view)
}

/// The grey of the lines between views (as in the window).
const BORDER: u8 = 60;

/// One view after the free one in an off-screen image of several views.
struct Cell {
    kind: ViewportKind,
    rect: [u32; 4],
    surface: OffscreenSurface,
    view: DrawnScene,
}

/// The views after the free one of an off-screen renderer of several views (its
/// `--views`): each drawn into its own surface the size of its quarter, then put in
/// its place in the renderer's image.
pub(crate) struct OffscreenViewports {
    cells: Vec<Cell>,
    /// The image's size.
    size: (u32, u32),
    /// The free view's quarter.
    free: [u32; 4],
}

impl OffscreenViewports {
    /// The views 2 to `count` of a `settings.size` image, drawing what `mirror` draws
    /// (axes, forces...). Needs the rendering context.
    pub(crate) fn new(settings: &WindowSettings, count: usize, mirror: &SceneMirror) -> Self {
        let (width, height) = settings.size;
        let rects = pixel_cells(width, height, count);
        let cells = rects
            .iter()
            .zip(VIEWPORT_KINDS)
            .skip(1)
            .map(|(&rect, kind)| {
                let (surface, view) = surface_with_view(settings, (rect[2], rect[3]), mirror);
                Cell { kind, rect, surface, view }
            })
            .collect();
        OffscreenViewports { cells, size: (width, height), free: rects[0] }
    }

    /// The whole image's size.
    pub(crate) fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Forgets every view's nodes (after the simulation was rebuilt).
    pub(crate) fn clear(&mut self) {
        for cell in &mut self.cells {
            cell.view.mirror.clear();
        }
    }

    /// A line between the quarters, drawn on the free view's right and bottom edges and
    /// on the follow and top views' edges next to it (the camera view keeps every pixel
    /// of its image).
    fn draw_borders(&self, image: &mut [u8]) {
        let (width, height) = self.size;
        let [_, _, w, h] = self.free;
        let mut paint = |x: u32, y: u32| {
            let at = 3 * ((height - 1 - y) as usize * width as usize + x as usize);
            image[at..at + 3].fill(BORDER);
        };
        for y in 0..height {
            paint(w - 1, y);
        }
        for x in 0..width {
            paint(x, h - 1);
        }
    }

    /// The free view's size: the renderer draws it through its own camera.
    pub(crate) fn free_size(&self) -> (u32, u32) {
        (self.free[2], self.free[3])
    }

    /// The whole image (bottom row first): the free view's pixels `free_view` (bottom
    /// row first, [`free_size`](Self::free_size)) in the top-left quarter, the others
    /// drawn now from `sim`. `free` is the free camera's eye and target, `follow` the
    /// object it follows.
    pub(crate) fn compose(
        &mut self,
        sim: &Simulation,
        free_view: &[u8],
        free: (Point3<f64>, Point3<f64>),
        follow: Option<&str>,
    ) -> ars_core::Result<Vec<u8>> {
        let (width, height) = self.size;
        let mut image = vec![EMPTY_VIEW; 3 * width as usize * height as usize];
        place(&mut image, width, height, self.free, free_view);
        let target = followed(sim, None, follow);
        let mut pixels = Vec::new();
        for cell in &mut self.cells {
            cell.view.mirror.sync(sim, &mut cell.view.scene)?;
            if let Seen::Through(mut camera, _) = camera_of(cell.kind, sim, free, target, 0)? {
                cell.view.mirror.draw_overlays(sim, cell.surface.window_mut());
                kiss3d::pollster::block_on(camera.draw(&mut cell.surface, &mut cell.view.scene));
                cell.surface.snap(&mut pixels);
                place(&mut image, width, height, cell.rect, &pixels);
            }
        }
        self.draw_borders(&mut image);
        Ok(image)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_renderer_dropped_before_its_first_frame_drops_without_a_panic() {
        // On a thread of its own: dropping a thread's last window resets kiss3d's state.
        let dropped = std::thread::spawn(|| {
            let view = WindowSettings { size: (64, 48), ..WindowSettings::default() };
            drop(OffscreenRenderer::new(&view).expect("Mesa's software renderer"));
        })
        .join();
        assert!(dropped.is_ok(), "dropping an unused renderer panicked");
    }
}
