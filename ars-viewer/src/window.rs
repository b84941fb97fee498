//! The on-screen viewer: a window that runs a program in real time, with an orbit
//! camera, keyboard control and a text overlay.

use std::time::{Duration, Instant};

use ars_core::nalgebra::{Matrix4, Point3, Vector3};
use ars_core::{HookId, Key, ObjectId, Program, ProgramRunner, Simulation, ViewSettings};
use kiss3d::camera::Camera3d;
use kiss3d::event::{Action, Key as WindowKey, Modifiers, MouseButton, WindowEvent};
use kiss3d::glamx::{Vec2, Vec3};
use kiss3d::text::Font;
use kiss3d::window::{CanvasSetup, NumSamples, Window};

use crate::ViewerOptions;
use crate::convert;
use crate::driver::{Driver, Shown};
use crate::edit::{Edit, apply_edit};
use crate::error::Result;
use crate::gui;
use crate::interact::{DragMode, Grab, Push, pick};
use crate::layout;
use crate::scene::View;
use crate::state::{DragLine, Selected, ViewerState};
use crate::video::WindowVideo;
use crate::views::{self, Views};

/// The viewer's own keys (they are not passed to the program), separated by `", "`.
pub const VIEWER_KEYS: &str = "space: pause/resume, n: one step while paused, r: reset, j: joints, k: contacts, \
     x: axes, f: follow, g: panel, p: screenshot, click: select, ctrl+drag: pull the selected body, \
     shift+drag: turn it, ctrl+s: save the scene, 1-4: views, escape: deselect (quit when nothing is selected)";

/// Frames run per drawn frame at most when the simulation is behind wall time.
const MAX_CATCH_UP_FRAMES: u32 = 4;

fn program_key(key: WindowKey) -> Option<Key> {
    use WindowKey as K;
    Some(match key {
        K::Up => Key::Up,
        K::Down => Key::Down,
        K::Left => Key::Left,
        K::Right => Key::Right,
        K::Space => Key::Space,
        K::A => Key::Char('a'),
        K::B => Key::Char('b'),
        K::C => Key::Char('c'),
        K::D => Key::Char('d'),
        K::E => Key::Char('e'),
        K::F => Key::Char('f'),
        K::G => Key::Char('g'),
        K::H => Key::Char('h'),
        K::I => Key::Char('i'),
        K::J => Key::Char('j'),
        K::K => Key::Char('k'),
        K::L => Key::Char('l'),
        K::M => Key::Char('m'),
        K::N => Key::Char('n'),
        K::O => Key::Char('o'),
        K::P => Key::Char('p'),
        K::Q => Key::Char('q'),
        K::R => Key::Char('r'),
        K::S => Key::Char('s'),
        K::T => Key::Char('t'),
        K::U => Key::Char('u'),
        K::V => Key::Char('v'),
        K::W => Key::Char('w'),
        K::X => Key::Char('x'),
        K::Y => Key::Char('y'),
        K::Z => Key::Char('z'),
        _ => return None,
    })
}

/// The text overlay's sizes, pixels: the status line, the key line.
const STATUS_SIZE: f32 = 28.0;
const KEYS_SIZE: f32 = 16.0;

/// How wide `text` is drawn in `font` at `size` pixels.
fn text_width(font: &Font, size: f32, text: &str) -> f32 {
    let scale = rusttype::Scale::uniform(size);
    font.font()
        .layout(text, scale, rusttype::point(0.0, 0.0))
        .last()
        .map_or(0.0, |g| g.position().x + g.unpositioned().h_metrics().advance_width)
}

/// The height of a line of `font` at `size` pixels, as kiss3d draws lines.
fn line_height(font: &Font, size: f32) -> f32 {
    let v = font.font().v_metrics(rusttype::Scale::uniform(size));
    v.ascent - v.descent
}

/// `text`, a list of items joined by `separator`, in lines no wider than `width`
/// pixels in `font` at `size`; with the number of lines.
fn wrapped(font: &Font, size: f32, text: &str, separator: &str, width: f32) -> (String, usize) {
    let items: Vec<&str> = text.split(separator).collect();
    let lines = layout::wrap_items(&items, separator, width, |s| text_width(font, size, s));
    (lines.join("\n"), lines.len())
}

/// How far the mouse may move between press and release for a click, pixels.
const CLICK_SLOP: f64 = 5.0;

/// What a drag with these modifiers does: Ctrl pulls, Shift or Alt turns.
fn drag_mode(modifiers: Modifiers) -> Option<DragMode> {
    if modifiers.contains(Modifiers::Control) {
        Some(DragMode::Force)
    } else if modifiers.intersects(Modifiers::Shift | Modifiers::Alt) {
        Some(DragMode::Torque)
    } else {
        None
    }
}

/// The modifier keys held down, as the window saw their keys (X11 stamps events with
/// the modifiers only while the window has the focus).
fn held_modifiers(window: &Window) -> Modifiers {
    let down = |keys: [WindowKey; 2]| keys.iter().any(|k| window.get_key(*k) == Action::Press);
    let mut modifiers = Modifiers::empty();
    modifiers.set(Modifiers::Control, down([WindowKey::LControl, WindowKey::RControl]));
    modifiers.set(Modifiers::Shift, down([WindowKey::LShift, WindowKey::RShift]));
    modifiers.set(Modifiers::Alt, down([WindowKey::LAlt, WindowKey::RAlt]));
    modifiers
}

/// The mouse's hold on the simulation: the selected body, and the drag in progress
/// with the hooks that push it while running.
#[derive(Default)]
struct Hand {
    /// The cursor, window pixels.
    cursor: (f64, f64),
    /// Where the left button went down (not for a drag): a click if it comes up there.
    press: Option<(f64, f64)>,
    selected: Option<ObjectId>,
    grab: Option<Grab>,
    /// The hooks pushing the grabbed body (while running).
    push: Option<HookId<Push>>,
    /// Escape went down to deselect: its release must not close the window.
    escape_held: bool,
    /// The cursor when the panel was last drawn (where egui last saw it).
    ui_cursor: (f64, f64),
}

impl Hand {
    /// The picking ray under the cursor.
    fn ray(&self, camera: &layout::FramedCamera, size: Vec2) -> (Point3<f64>, Vector3<f64>) {
        let (o, d) = camera.unproject(Vec2::new(self.cursor.0 as f32, self.cursor.1 as f32), size);
        (convert::point_back(o), convert::vector_back(d))
    }

    /// The left button went down with `modifiers`: a drag of the selected body starts
    /// (at the point under the cursor when it is on the body, else at its centre).
    /// Returns whether a drag started.
    fn press(
        &mut self,
        sim: &Simulation,
        ray: (Point3<f64>, Vector3<f64>),
        view: Vector3<f64>,
        modifiers: Modifiers,
    ) -> bool {
        self.press = Some(self.cursor);
        let (Some(mode), Some(id)) = (drag_mode(modifiers), self.selected) else { return false };
        let at = match pick(sim, ray.0, ray.1) {
            Some((hit, at)) if hit == id => at,
            _ => match sim.scene().body(id) {
                Ok(b) => b.position(),
                Err(_) => return false,
            },
        };
        self.grab = Grab::new(sim, id, at, view, mode).ok();
        self.press = None;
        self.grab.is_some()
    }

    /// The left button came up: the drag ends, or a click selects the body under the
    /// cursor (or nothing, off every body).
    fn release(&mut self, sim: &mut Simulation, ray: (Point3<f64>, Vector3<f64>)) {
        if self.grab.take().is_some() {
            self.stop_pushing(sim);
        } else if let Some((x, y)) = self.press.take()
            && (x - self.cursor.0).hypot(y - self.cursor.1) <= CLICK_SLOP
        {
            self.selected = pick(sim, ray.0, ray.1).map(|(id, _)| id);
        }
    }

    fn stop_pushing(&mut self, sim: &mut Simulation) {
        if let Some(hook) = self.push.take() {
            let _ = sim.remove_hooks(hook);
        }
    }

    /// Forgets the selection and any drag.
    fn deselect(&mut self, sim: &mut Simulation) {
        self.stop_pushing(sim);
        self.grab = None;
        self.selected = None;
    }

    /// Moves the drag's target under the cursor: while running, the hooks push the
    /// body toward it at every step; paused, the body is moved there now.
    fn drag(&mut self, sim: &mut Simulation, ray: (Point3<f64>, Vector3<f64>), paused: bool) -> ars_core::Result<()> {
        let Some(grab) = self.grab.as_mut() else { return Ok(()) };
        if sim.scene().body(grab.object).is_err() {
            self.deselect(sim);
            return Ok(());
        }
        grab.aim(ray.0, ray.1);
        let grab = *grab;
        if paused {
            self.stop_pushing(sim);
            return grab.place(sim);
        }
        match self.push {
            Some(hook) => sim.hooks_mut(hook)?.0 = grab,
            None => self.push = Some(sim.add_hooks(Push(grab))?),
        }
        Ok(())
    }

    /// The selected body outlined (its bounding box), and the drag's line.
    fn draw(&self, sim: &Simulation, window: &mut Window) {
        if let Some(id) = self.selected
            && let Ok(object) = sim.scene().object(id)
        {
            let world = sim.scene().world();
            let boxes: Vec<_> = object.geoms().filter_map(|g| world.geom(g).ok()).map(|g| g.aabb()).collect();
            if let Some((mut low, mut high)) = boxes.first().copied() {
                for (l, h) in &boxes {
                    low = low.inf(l);
                    high = high.sup(h);
                }
                outline(window, convert::point(&low), convert::point(&high));
            }
        }
        if let Some(grab) = &self.grab
            && let Ok(from) = grab.point(sim)
        {
            let colour = match grab.mode {
                DragMode::Force => kiss3d::color::Color::new(1.0, 0.2, 0.6, 1.0),
                DragMode::Torque => kiss3d::color::Color::new(0.2, 0.6, 1.0, 1.0),
            };
            window.draw_line(convert::point(&from), convert::point(&grab.target), colour, 4.0, false);
            window.draw_point(convert::point(&grab.target), colour, 10.0);
        }
    }
}

/// The 12 edges of the box from `low` to `high`, in yellow.
fn outline(window: &mut Window, low: Vec3, high: Vec3) {
    let yellow = kiss3d::color::Color::new(1.0, 0.85, 0.0, 1.0);
    let corner = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { low.x } else { high.x },
            if i & 2 == 0 { low.y } else { high.y },
            if i & 4 == 0 { low.z } else { high.z },
        )
    };
    for i in 0..8u32 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                window.draw_line(corner(i), corner(i | bit), yellow, 3.0, false);
            }
        }
    }
}

/// The world's contact feedback (ODE's forces of the contact points), on while the
/// forces are drawn, and as it was before (a `ContactForces` sensor keeps it on) once
/// they are not.
#[derive(Default)]
struct Feedback {
    /// Whether the world reported the forces before the window asked.
    before: bool,
}

impl Feedback {
    /// Forces drawn (`on`) or not from now on.
    fn show(&mut self, sim: &mut Simulation, on: bool) {
        let world = sim.scene_mut().world_mut();
        if on {
            self.before = world.contact_feedback();
            crate::scene::report_forces(world);
        } else {
            world.set_contact_feedback(self.before);
        }
    }

    /// The simulation was rebuilt: ask the new one for the forces if they are drawn.
    fn rebuilt(&mut self, sim: &mut Simulation, on: bool) {
        if on {
            self.show(sim, true);
        }
    }
}

/// Saves the scene where the panel says, and says how it went.
fn save(sim: &Simulation, panel: &mut gui::Panel) {
    match sim.save_scene_to(&panel.save_path) {
        Ok(()) => {
            eprintln!("scene saved to {}", panel.save_path);
            panel.saved = Some(panel.save_path.clone());
            panel.error = None;
        }
        Err(e) => panel.error = Some(format!("not saved: {e}")),
    }
}

/// The camera's world-to-device matrix, in the simulation's numbers.
fn view_projection(camera: &layout::FramedCamera) -> Matrix4<f64> {
    let m = camera.transformation().to_cols_array().map(f64::from);
    Matrix4::from_column_slice(&m)
}

/// Real-time pacing: simulated time follows wall time while the machine keeps up.
struct Pacer {
    wall_origin: Instant,
    sim_origin: f64,
    /// Simulated seconds per wall-clock second.
    speed: f64,
    /// (wall, sim) a second ago, for the real-time factor.
    window: (Instant, f64),
    factor: f64,
    behind: bool,
}

impl Pacer {
    fn new(sim_time: f64) -> Self {
        Pacer::with_speed(sim_time, 1.0)
    }

    fn with_speed(sim_time: f64, speed: f64) -> Self {
        let now = Instant::now();
        Pacer { wall_origin: now, sim_origin: sim_time, speed, window: (now, sim_time), factor: 0.0, behind: false }
    }

    /// Simulated time to reach now.
    fn target(&self) -> f64 {
        self.sim_origin + self.speed * self.wall_origin.elapsed().as_secs_f64()
    }

    fn measure(&mut self, sim_time: f64) {
        let elapsed = self.window.0.elapsed();
        if elapsed >= Duration::from_millis(500) {
            self.factor = (sim_time - self.window.1) / elapsed.as_secs_f64();
            self.window = (Instant::now(), sim_time);
        }
    }
}

/// Writes what the window shows to `ars-<title>-<n>.png` in the current folder.
fn screenshot(window: &Window, title: &str) {
    let stem = title.to_lowercase().replace(|c: char| !c.is_ascii_alphanumeric(), "_");
    let path = (1..)
        .map(|n| std::path::PathBuf::from(format!("ars-{stem}-{n:03}.png")))
        .find(|p| !p.exists())
        .expect("a free name");
    match window.snap_image().save(&path) {
        Ok(()) => eprintln!("screenshot: {}", path.display()),
        Err(e) => eprintln!("screenshot not written ({}): {e}", path.display()),
    }
}

/// A window for `view`: without multisampling when it will be drawn fast (4× MSAA costs
/// a software rasteriser more than half its frame rate).
async fn open_window(view: &ars_core::ViewSettings) -> Result<Window> {
    crate::offscreen::check_context_reuse()?;
    quiet_wayland_probe();
    // The window's context does not exist yet: ask wgpu for the adapter it will get,
    // when the quality leaves it to the machine.
    let software = view.quality == ars_core::RenderQuality::Auto && software_adapter().await;
    let fast = crate::scene::fast_for(view.quality, || software);
    let (w, h) = view.size;
    let window = if fast {
        let setup = CanvasSetup { samples: NumSamples::One, ..CanvasSetup::default() };
        Window::new_with_setup(&view.title, w, h, setup).await
    } else {
        Window::new_with_size(&view.title, w, h).await
    };
    crate::offscreen::context_made();
    crate::offscreen::keep_context_if_asked();
    Ok(window)
}

/// Keeps Mesa's Vulkan device-selection layer from printing
/// `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` on stderr.
///
/// That implicit layer (`VK_LAYER_MESA_device_select`, installed with
/// mesa-vulkan-drivers; seen with Mesa 22.3) calls libwayland's `wl_display_connect`
/// whenever Vulkan lists its devices, whether or not a Wayland display is named, and
/// libwayland prints that line when `XDG_RUNTIME_DIR` is unset (Xvfb, CI, ssh,
/// containers): four lines per window. With no Wayland display named and no
/// `XDG_RUNTIME_DIR`, the layer's question can only fail, so this turns the layer off
/// with its own switch, `NODEVICE_SELECT=1`, in this process's environment (wgpu still
/// chooses among the same devices). It does nothing when the environment already
/// says how to select a device (`NODEVICE_SELECT`, `MESA_VK_DEVICE_SELECT`,
/// `DRI_PRIME`), and nothing unless the process runs a single thread, the one case
/// where changing the environment is sound (another thread could be reading it).
pub(crate) fn quiet_wayland_probe() {
    if !device_select_would_print() {
        return;
    }
    let threads = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find_map(|l| l.strip_prefix("Threads:").and_then(|n| n.trim().parse::<u32>().ok())));
    if threads == Some(1) {
        // SAFETY: this process runs one thread, this one (checked just above; only
        // this thread could have started another since), so no other thread reads or
        // writes the environment while it changes.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}

/// Whether this process's environment is one where Mesa's Vulkan device-selection
/// layer would print `error: XDG_RUNTIME_DIR is invalid...` (Linux, no Wayland display,
/// no `XDG_RUNTIME_DIR`) and nobody chose a device: where setting `NODEVICE_SELECT=1`
/// before any rendering keeps stderr clean. The window does it itself in a
/// single-threaded program; a host that may run threads (Python) sets it at its own
/// start-up.
pub fn device_select_would_print() -> bool {
    cfg!(target_os = "linux") && needs_quiet_wayland_probe(|name| std::env::var_os(name))
}

/// Whether the environment (`var`) is one where Mesa's device-selection layer would
/// print about `XDG_RUNTIME_DIR`, and where nobody asked for the layer: see
/// [`quiet_wayland_probe`].
fn needs_quiet_wayland_probe(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> bool {
    let set = |name: &str| var(name).is_some_and(|v| !v.is_empty());
    let wayland = set("WAYLAND_DISPLAY") || set("WAYLAND_SOCKET");
    let chosen = set("NODEVICE_SELECT") || set("MESA_VK_DEVICE_SELECT") || set("DRI_PRIME");
    !wayland && !set("XDG_RUNTIME_DIR") && !chosen
}

/// Whether the adapter a window would get is a software rasteriser (no GPU).
async fn software_adapter() -> bool {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let options = wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::default(),
        compatible_surface: None,
        force_fallback_adapter: false,
        apply_limit_buckets: false,
    };
    instance.request_adapter(&options).await.is_ok_and(|a| a.get_info().device_type == wgpu::DeviceType::Cpu)
}

/// Opens the program's window and runs it until the window is closed; returns the
/// simulation as it was then.
pub(crate) fn run_window<P: Program>(program: &mut P, options: &ViewerOptions) -> Result<ars_core::Simulation> {
    run_window_until(program, options, None).map(|(sim, _)| sim)
}

/// What a window run measured ([`ProgramViewer::show_for`](crate::ProgramViewer::show_for)).
#[derive(Clone, Debug, Default)]
pub struct WindowReport {
    /// Frames drawn.
    pub frames: u64,
    /// Wall-clock seconds the window ran.
    pub wall_seconds: f64,
    /// Simulated seconds.
    pub simulated_seconds: f64,
    /// Resident memory of the process (MB), once a second: `(wall seconds, MB)`.
    pub resident_mb: Vec<(f64, f64)>,
}

impl WindowReport {
    /// Frames drawn per wall-clock second.
    pub fn frames_per_second(&self) -> f64 {
        self.frames as f64 / self.wall_seconds
    }
    /// Simulated seconds per wall-clock second.
    pub fn real_time_factor(&self) -> f64 {
        self.simulated_seconds / self.wall_seconds
    }
}

/// Resident memory of this process, MB (NaN where /proc is missing).
pub(crate) fn resident_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("VmRSS:"))?.to_string();
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// The window loop of a program, until the window closes or `limit` of wall time has
/// passed.
pub(crate) fn run_window_until<P: Program>(
    program: &mut P,
    options: &ViewerOptions,
    limit: Option<Duration>,
) -> Result<(ars_core::Simulation, WindowReport)> {
    let view = program.view_settings();
    let mut runner = ProgramRunner::new(program)?;
    let report = drive_window(&mut runner, &view, options, limit, None)?;
    Ok((runner.into_simulation(), report))
}

/// The window loop: shows what `runner` drives until the window closes or `limit` of
/// wall time has passed.
pub(crate) fn drive_window<D: Driver>(
    runner: &mut D,
    view: &ViewSettings,
    options: &ViewerOptions,
    limit: Option<Duration>,
    mut video: Option<&mut WindowVideo>,
) -> Result<WindowReport> {
    kiss3d::pollster::block_on(async move {
        // The program's simulation, or a file opened from the panel (then titled so).
        let mut runner = Shown::new(runner);
        let mut title = view.title.clone();
        let mut window = open_window(view).await?;
        window.rebind_close_key(Some(WindowKey::Escape));
        window.set_background_color(convert::color(view.background));
        let mut shown = View::new(view, &mut window);
        shown.mirror.show_axes = options.axes;
        // A plain left drag orbits; with a modifier it drags the selected body.
        shown.camera.orbit.set_rotate_modifiers(Some(Modifiers::empty()));
        let mut hand = Hand::default();
        let mut feedback = Feedback::default();
        let mut views = Views::new();
        views.count = options.views.clamp(1, 4);
        // Where the extra views were drawn last (their clicks are not the scene's).
        let mut view_covers: Vec<layout::Rect> = Vec::new();
        if options.forces {
            shown.mirror.show_forces = true;
            feedback.show(&mut runner.simulation(), true);
        }
        let font = Font::default();
        let mut paused = false;
        let mut pacer = Pacer::new(runner.simulation().scene().time());
        let mut panel = gui::Panel::default();
        let started = Instant::now();
        let mut report = WindowReport::default();
        // Without multisampling (drawing fast), FXAA smooths the edges for a few
        // milliseconds a frame.
        let mut fxaa = kiss3d::post_processing::Fxaa::new();
        let smooth = shown.mirror.draws_fast();
        // The loop, in a block of its own so that the drag ends however it ends.
        let outcome: Result<()> = async {
            loop {
                let open = if smooth {
                    window.render_3d_with_chain(&mut shown.scene, &mut shown.camera, &mut [&mut fxaa]).await
                } else {
                    window.render_3d(&mut shown.scene, &mut shown.camera).await
                };
                if !open {
                    break;
                }
                let wall = started.elapsed();
                report.frames += 1;
                // The first frame is drawn before the scene is (see `shown.update`).
                if let Some(video) = video.as_deref_mut().filter(|_| report.frames > 1) {
                    let time = runner.simulation().scene().time();
                    video.shown(time, || window.snap_image())?;
                }
                if wall.as_secs_f64() >= report.resident_mb.len() as f64 {
                    report.resident_mb.push((wall.as_secs_f64(), resident_mb()));
                }
                if limit.is_some_and(|l| wall >= l) {
                    break;
                }
                // Keys pressed in this frame's events: under X11 a press sometimes arrives
                // twice in one frame (seen with xdotool); a press of a key already down in
                // the same frame is that copy, not a new press.
                let mut pressed: Vec<WindowKey> = Vec::new();
                // While a text field of the panel has the keyboard, keys are its own; while
                // the pointer is over the panel, clicks are.
                let typing = window.is_egui_capturing_keyboard();
                let egui_pointer = window.is_egui_capturing_mouse();
                let mut panels: Vec<layout::Rect> = panel.covers.map(|(r, _)| r).into_iter().collect();
                panels.extend(panel.editor_covers);
                panels.extend(view_covers.iter().copied());
                let size = Vec2::new(window.width() as f32, window.height() as f32);
                let forward = convert::vector_back(shown.camera.orbit.at() - shown.camera.eye());
                for mut event in window.events().iter() {
                    let (key, action, modifiers) = match event.value {
                        WindowEvent::CursorPos(x, y, _) => {
                            hand.cursor = (x, y);
                            // A drag moves the body, not the camera.
                            event.inhibited = hand.grab.is_some();
                            continue;
                        }
                        WindowEvent::MouseButton(MouseButton::Button1, action, modifiers) => {
                            let over_panel =
                                layout::pointer_on_panel(hand.cursor, hand.ui_cursor, egui_pointer, &panels);
                            if over_panel && hand.grab.is_none() {
                                continue;
                            }
                            let ray = hand.ray(&shown.camera, size);
                            match action {
                                Action::Press => {
                                    let modifiers = modifiers | held_modifiers(&window);
                                    event.inhibited = hand.press(&runner.simulation(), ray, forward, modifiers);
                                }
                                Action::Release => {
                                    event.inhibited = hand.grab.is_some();
                                    hand.release(&mut runner.simulation(), ray);
                                }
                            }
                            continue;
                        }
                        WindowEvent::Key(key, action, modifiers) => (key, action, modifiers),
                        _ => continue,
                    };
                    if key == WindowKey::Escape {
                        // kiss3d closes the window on the close key's release. While a
                        // field is typed in, the press is egui's (it leaves the field);
                        // with a selection, it deselects; either way its release must not
                        // close the window. Otherwise it goes to kiss3d, and closes.
                        match action {
                            Action::Press if typing => hand.escape_held = true,
                            Action::Press if hand.selected.is_some() => {
                                event.inhibited = true;
                                hand.escape_held = true;
                                hand.deselect(&mut runner.simulation());
                            }
                            Action::Release if hand.escape_held => {
                                event.inhibited = true;
                                hand.escape_held = false;
                            }
                            _ => {}
                        }
                        continue;
                    }
                    if typing {
                        // The panel's text field has the keyboard.
                        continue;
                    }
                    // Every other key is the viewer's or the program's, not the camera's.
                    event.inhibited = true;
                    match action {
                        Action::Press if pressed.contains(&key) => continue,
                        Action::Press => pressed.push(key),
                        Action::Release => pressed.retain(|k| *k != key),
                    }
                    if key == WindowKey::S && (modifiers | held_modifiers(&window)).contains(Modifiers::Control) {
                        if action == Action::Press {
                            save(&runner.simulation(), &mut panel);
                        }
                        continue;
                    }
                    match (key, action) {
                        (WindowKey::Space, Action::Press) => {
                            paused = !paused;
                            pacer = Pacer::new(runner.simulation().scene().time());
                        }
                        (WindowKey::N, Action::Press) if paused => runner.step()?,
                        (WindowKey::R, Action::Press) => {
                            hand.deselect(&mut runner.simulation());
                            runner.reset()?;
                            shown.mirror.clear();
                            views.clear();
                            feedback.rebuilt(&mut runner.simulation(), shown.mirror.show_forces);
                            pacer = Pacer::new(runner.simulation().scene().time());
                        }
                        (WindowKey::J, Action::Press) => shown.mirror.show_joints = !shown.mirror.show_joints,
                        (WindowKey::Key1, Action::Press) => views.count = 1,
                        (WindowKey::Key2, Action::Press) => views.count = 2,
                        (WindowKey::Key3, Action::Press) => views.count = 3,
                        (WindowKey::Key4, Action::Press) => views.count = 4,
                        (WindowKey::F, Action::Press) => shown.toggle_follow(&runner.simulation()),
                        (WindowKey::G, Action::Press) => panel.shown = !panel.shown,
                        (WindowKey::K, Action::Press) => shown.mirror.show_contacts = !shown.mirror.show_contacts,
                        (WindowKey::X, Action::Press) => shown.mirror.show_axes = !shown.mirror.show_axes,
                        (WindowKey::P, Action::Press) => screenshot(&window, &title),
                        (k, Action::Press) => {
                            if let Some(k) = program_key(k) {
                                runner.key_down(k)?;
                            }
                        }
                        (k, Action::Release) => {
                            if let Some(k) = program_key(k) {
                                runner.key_up(k)?;
                            }
                        }
                    }
                }
                // Ctrl-C in the terminal closes the window too, once the program asked for
                // it (`ars_core::interrupt::stop_on_ctrl_c`: the examples do).
                if runner.wants_to_close() || ars_core::interrupt::requested() {
                    break;
                }
                {
                    let ray = hand.ray(&shown.camera, size);
                    let dragged = hand.drag(&mut runner.simulation(), ray, paused);
                    if let Err(e) = dragged {
                        panel.error = Some(format!("drag: {e}"));
                        hand.deselect(&mut runner.simulation());
                    }
                }
                if panel.speed != pacer.speed {
                    pacer = Pacer::with_speed(runner.simulation().scene().time(), panel.speed);
                }
                if !paused && panel.fastest {
                    // As fast as the machine can: frames for about 30 ms, then draw.
                    let budget = Instant::now();
                    while budget.elapsed() < Duration::from_millis(30) {
                        runner.step_frame()?;
                    }
                    pacer.measure(runner.simulation().scene().time());
                } else if !paused {
                    let mut frames = 0;
                    while runner.simulation().scene().time() < pacer.target() && frames < MAX_CATCH_UP_FRAMES {
                        runner.step_frame()?;
                        frames += 1;
                    }
                    pacer.behind = runner.simulation().scene().time() < pacer.target() - 0.1 * pacer.speed.max(1.0);
                    if pacer.behind {
                        // Give up on the lost time rather than spiral: keep pacing from now.
                        pacer.wall_origin = Instant::now();
                        pacer.sim_origin = runner.simulation().scene().time();
                    }
                    pacer.measure(runner.simulation().scene().time());
                }
                let status = gui::Status {
                    title: &title,
                    paused,
                    real_time_factor: pacer.factor,
                    following: shown.following,
                    contacts: shown.mirror.show_contacts,
                    forces: shown.mirror.show_forces,
                    views: views.count,
                    camera: views.camera,
                    joints: shown.mirror.show_joints,
                    axes: shown.mirror.show_axes,
                    selected: None,
                };
                let selected = hand.selected.and_then(|id| Selected::of(&runner.simulation(), id));
                if selected.is_none() && hand.selected.is_some() {
                    // The body is gone (removed by the program).
                    hand.deselect(&mut runner.simulation());
                }
                let drawn = selected.as_ref().and_then(|s| shown.mirror.drawn_color(s.id)).unwrap_or([0.5; 3]);
                let status = gui::Status { selected: selected.as_ref().map(|s| (s, drawn)), ..status };
                if views.count > 1 {
                    let sim = runner.simulation();
                    let free = (convert::point_back(shown.camera.eye()), convert::point_back(shown.camera.orbit.at()));
                    let target = views::followed(&sim, hand.selected, shown.follow.as_deref());
                    let size = (window.width() as f32, window.height() as f32);
                    views.render(&sim, view, size, free, target).await?;
                }
                let mut commands = Vec::new();
                window.draw_ui(|ctx| {
                    view_covers = views.show(ctx);
                    commands = panel.draw(ctx, &runner.simulation(), &status);
                });
                hand.ui_cursor = hand.cursor;
                // What the camera looks at appears in the middle of what the panel leaves
                // free (from the next frame on).
                shown.camera.shift = match panel.covers {
                    // Several views: the free one in the top-left quarter.
                    _ if views.count > 1 => {
                        let (w, h) = (window.width() as f32, window.height() as f32);
                        let [l, t, r, b] = views::viewports(w, h, views.count)[0];
                        layout::ndc_shift(w, h, ((l + r) / 2.0, (t + b) / 2.0))
                    }
                    Some((panel_rect, (w, h))) => {
                        let panels: Vec<layout::Rect> =
                            std::iter::once(panel_rect).chain(panel.editor_covers).collect();
                        layout::ndc_shift(w, h, layout::free_centre_of(w, h, &panels))
                    }
                    None => Vec2::ZERO,
                };
                for command in commands {
                    match command {
                        gui::Command::TogglePause => {
                            paused = !paused;
                            pacer = Pacer::with_speed(runner.simulation().scene().time(), panel.speed);
                        }
                        gui::Command::StepFrame => runner.step_frame()?,
                        gui::Command::StepPhysics => runner.step()?,
                        gui::Command::Reset => {
                            hand.deselect(&mut runner.simulation());
                            runner.reset()?;
                            shown.mirror.clear();
                            views.clear();
                            feedback.rebuilt(&mut runner.simulation(), shown.mirror.show_forces);
                            pacer = Pacer::with_speed(runner.simulation().scene().time(), panel.speed);
                        }
                        gui::Command::Screenshot => screenshot(&window, &title),
                        gui::Command::ToggleFollow => shown.toggle_follow(&runner.simulation()),
                        gui::Command::ToggleContacts => shown.mirror.show_contacts = !shown.mirror.show_contacts,
                        gui::Command::ToggleForces => {
                            shown.mirror.show_forces = !shown.mirror.show_forces;
                            feedback.show(&mut runner.simulation(), shown.mirror.show_forces);
                        }
                        gui::Command::ToggleJoints => shown.mirror.show_joints = !shown.mirror.show_joints,
                        gui::Command::ToggleAxes => shown.mirror.show_axes = !shown.mirror.show_axes,
                        gui::Command::Setpoint(joint, value) => {
                            gui::set_setpoint(&mut runner.simulation(), joint, value)?;
                        }
                        gui::Command::Edit(edit) => match apply_edit(&mut runner.simulation(), &edit) {
                            Ok(()) => {
                                panel.error = None;
                                if let Edit::Color(id, _) = edit {
                                    shown.mirror.redraw(id);
                                    views.redraw(id);
                                }
                            }
                            Err(e) => panel.error = Some(e.to_string()),
                        },
                        gui::Command::Save => save(&runner.simulation(), &mut panel),
                        gui::Command::Open => match Simulation::open(panel.open_path.trim()) {
                            Ok(opened) => {
                                hand.deselect(&mut runner.simulation());
                                let path = std::path::PathBuf::from(panel.open_path.trim());
                                eprintln!("opened {}", path.display());
                                for skipped in &opened.skipped {
                                    eprintln!("skipped: {skipped}");
                                }
                                runner.open(path.clone(), opened.simulation);
                                shown.mirror.clear();
                                views.clear();
                                feedback.rebuilt(&mut runner.simulation(), shown.mirror.show_forces);
                                pacer = Pacer::with_speed(runner.simulation().scene().time(), panel.speed);
                                title = format!("ARS: {}", path.display());
                                panel.opened = Some(path.display().to_string());
                                panel.error = opened.skipped.first().map(|first| {
                                    let n = opened.skipped.len();
                                    format!("{n} skipped (listed on the terminal), the first: {first}")
                                });
                            }
                            Err(e) => panel.error = Some(format!("not opened: {e}")),
                        },
                        gui::Command::Views(n) => views.count = n,
                        gui::Command::ViewCamera(i) => views.camera = i,
                        gui::Command::Deselect => hand.deselect(&mut runner.simulation()),
                    }
                }
                shown.mirror.force_scale = panel.force_scale;
                let state = ViewerState {
                    paused,
                    selected: hand.selected.and_then(|id| Selected::of(&runner.simulation(), id)),
                    drag: hand.grab.and_then(|g| {
                        let from = g.point(&runner.simulation()).ok()?;
                        Some(DragLine { mode: g.mode, from, to: g.target })
                    }),
                    error: panel.error.clone(),
                    save_path: panel.save_path.clone().into(),
                    saved: panel.saved.clone().map(Into::into),
                    fields: panel.fields.clone(),
                    window_size: (size.x, size.y),
                    views: views.count,
                    view_projection: view_projection(&shown.camera),
                };
                runner.viewer_state(&state);
                let sim = runner.simulation();
                shown.update(&sim, &mut window)?;
                hand.draw(&sim, &mut window);
                if panel.shown {
                    // The panel says the same.
                    continue;
                }
                let status = if paused {
                    "paused".to_string()
                } else if pacer.behind {
                    format!("x{:.2} real time: slower than real time", pacer.factor)
                } else {
                    format!("x{:.2} real time", pacer.factor)
                };
                // Both lines wrap to the window's width (10 px margins).
                let width = window.width() as f32 - 20.0;
                let text = format!("t = {:.3} s   {status}", sim.scene().time());
                let (text, lines) = wrapped(&font, STATUS_SIZE, &text, "   ", width);
                window.draw_text(
                    &text,
                    Vec2::new(10.0, 10.0),
                    STATUS_SIZE,
                    &font,
                    kiss3d::color::Color::new(0.1, 0.1, 0.1, 1.0),
                );
                let (keys, _) = wrapped(&font, KEYS_SIZE, VIEWER_KEYS, ", ", width);
                window.draw_text(
                    &keys,
                    Vec2::new(10.0, 16.0 + lines as f32 * line_height(&font, STATUS_SIZE)),
                    KEYS_SIZE,
                    &font,
                    kiss3d::color::Color::new(0.3, 0.3, 0.3, 1.0),
                );
            }
            Ok(())
        }
        .await;
        // A drag in progress ends with the window (closed, or stopped by an error): its
        // hooks must not go on pushing the body in the simulation handed back.
        hand.deselect(&mut runner.simulation());
        outcome?;
        report.wall_seconds = started.elapsed().as_secs_f64();
        report.simulated_seconds = runner.simulation().scene().time();
        Ok(report)
    })
}

/// Opens the program's window, runs `frames` frames (one drawn frame each, no real-time
/// pacing), and returns the last frame as the window showed it. For tests and
/// thumbnails; must run on the main thread, with a display.
pub(crate) fn snapshot_window<P: Program>(program: &mut P, frames: u32) -> Result<image::RgbImage> {
    let view = program.view_settings();
    kiss3d::pollster::block_on(async move {
        let mut window = open_window(&view).await?;
        window.set_background_color(convert::color(view.background));
        let mut shown = View::new(&view, &mut window);
        let mut runner = ProgramRunner::new(program)?;
        for frame in 0..frames.max(1) {
            if frame > 0 {
                runner.step_frame()?;
            }
            shown.update(runner.simulation(), &mut window)?;
            if !window.render_3d(&mut shown.scene, &mut shown.camera).await {
                break;
            }
        }
        let image = window.snap_image();
        window.close();
        Ok(image)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_device_selection_layer_is_turned_off_only_where_it_would_print() {
        let env = |vars: &'static [(&'static str, &'static str)]| {
            move |name: &str| vars.iter().find(|(n, _)| *n == name).map(|(_, v)| std::ffi::OsString::from(v))
        };
        // Xvfb in CI: X11, no XDG_RUNTIME_DIR.
        assert!(needs_quiet_wayland_probe(env(&[("DISPLAY", ":99")])));
        assert!(needs_quiet_wayland_probe(env(&[("DISPLAY", ":99"), ("XDG_RUNTIME_DIR", "")])));
        // A desktop session: libwayland finds no socket and says nothing.
        assert!(!needs_quiet_wayland_probe(env(&[("DISPLAY", ":0"), ("XDG_RUNTIME_DIR", "/run/user/1000")])));
        // Wayland: the layer asks the compositor which device it uses.
        assert!(!needs_quiet_wayland_probe(env(&[("WAYLAND_DISPLAY", "wayland-0")])));
        // The user chose a device, or turned the layer off already.
        assert!(!needs_quiet_wayland_probe(env(&[("DISPLAY", ":99"), ("MESA_VK_DEVICE_SELECT", "10005:0")])));
        assert!(!needs_quiet_wayland_probe(env(&[("DISPLAY", ":99"), ("DRI_PRIME", "1")])));
        assert!(!needs_quiet_wayland_probe(env(&[("DISPLAY", ":99"), ("NODEVICE_SELECT", "0")])));
    }
}
