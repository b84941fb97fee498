//! Opening the on-screen viewer's window (and keeping Mesa's probe quiet), the viewer's
//! keys, and what a window run measured; the window's loop is its
//! `Session` (`session.rs`, with the `window` feature).

use ars_core::{Program, ProgramRunner};
use kiss3d::window::{CanvasSetup, NumSamples, Window};

use crate::convert;
use crate::error::Result;
use crate::scene::DrawnScene;

/// The viewer's own keys (they are not passed to the program), separated by `", "`.
pub const VIEWER_KEYS: &str = "space: pause/resume, n: one step while paused, r: reset, j: joints, k: contacts, \
     x: axes, f: follow, g: panel, p: screenshot, click: select, ctrl+drag: pull the selected body, \
     shift+drag: turn it, ctrl+s: save the scene, 1-4: views, escape: deselect (quit when nothing is selected)";

/// A window for `view`: without multisampling when it will be drawn fast (4× MSAA costs
/// a software rasteriser more than half its frame rate).
pub(crate) async fn open_window(view: &ars_core::WindowSettings) -> Result<Window> {
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

/// Opens the program's window, runs `frames` frames (one drawn frame each, no real-time
/// pacing), and returns the last frame as the window showed it. For tests and
/// thumbnails; must run on the main thread, with a display.
pub(crate) fn snapshot_window<P: Program>(program: &mut P, frames: u32) -> Result<image::RgbImage> {
    let view = program.window_settings();
    kiss3d::pollster::block_on(async move {
        let mut window = open_window(&view).await?;
        window.set_background_color(convert::color(view.background));
        let mut shown = DrawnScene::new(&view, &mut window);
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
