//! Frames per second of the viewer without a GPU (Mesa's software rasteriser), and
//! the memory the process holds: `cargo bench -p ars-benches --bench viewer_fps`.
//!
//! For the conical pendulum and the mobile manipulator on the sinusoidal terrain, off
//! screen at 800×600: the rendering alone (one frame of the simulation, then one image
//! read back) and the recorder's whole path (rendering, then PNG encoding and writing on
//! worker threads), with its ratio to drawing alone. Targets: at least 20 frames/s and
//! under 250 MB resident (issue 9); recording at least 60 frames/s and 0.8x drawing
//! alone on Mesa's llvmpipe with 2 cores (issue 21). And an MP4 video of 5 s at 30
//! frames/s of the conical pendulum: at least as fast as real time (issue 24).

use std::time::Instant;

use ars::viewer::{OffscreenRenderer, ScreenshotRecorder, VideoRecorder};
use ars::{Program, ProgramRunner, WindowSettings};
use ars_programs::{ConicalPendulum, SinusoidalTerrain};

const FRAMES: u32 = 150;
/// Wall-clock seconds each window runs.
const WINDOW_SECONDS: f64 = 10.0;

/// Resident and peak resident memory of this process, MB.
fn memory_mb() -> (f64, f64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<f64>().ok())
            .map_or(f64::NAN, |kb| kb / 1024.0)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

/// Frames per second of drawing alone: a frame of the simulation, then its image
/// read back (what the recorder draws, without encoding or writing it).
fn render_only<P: Program>(name: &str, mut program: P) -> f64 {
    let view = WindowSettings { size: (800, 600), ..program.window_settings() };
    let mut renderer = OffscreenRenderer::new(&view).expect("an off-screen context");
    let mut runner = ProgramRunner::new(&mut program).expect("the program builds");
    renderer.render(runner.simulation()).expect("a first frame");
    let start = Instant::now();
    for _ in 0..FRAMES {
        runner.step_frame().expect("a frame");
        renderer.render(runner.simulation()).expect("an image");
    }
    let fps = f64::from(FRAMES) / start.elapsed().as_secs_f64();
    let (rss, peak) = memory_mb();
    println!("{name}: render off screen 800x600: {fps:.1} frames/s, {rss:.0} MB resident (peak {peak:.0} MB)");
    fps
}

/// Seconds and frames of one recording of `frames` frames (context set-up included).
fn record<P: Program>(mut program: P, frames: u32) -> (f64, usize) {
    let dir = std::env::temp_dir().join(format!("ars-viewer-fps-{}-{frames}", std::process::id()));
    let recorder = ScreenshotRecorder::new(&dir).size(800, 600);
    let duration = f64::from(frames) / 50.0;
    let start = Instant::now();
    let (_, written) = recorder.record(&mut program, duration).expect("recorded");
    let seconds = start.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    (seconds, written.len())
}

/// The recorder's whole path (drawing, PNG encoding and writing): its frame rate once
/// running, from two recordings of different lengths (the longer one's extra frames
/// over its extra time, so the context set-up cancels), and its ratio to drawing alone.
fn recorder<P: Program + Default + Send + 'static>(name: &'static str, drawing_fps: f64) {
    let (short_s, short_n) = on_thread(|| record(P::default(), FRAMES / 5));
    let (long_s, long_n) = on_thread(|| record(P::default(), FRAMES));
    let fps = (long_n - short_n) as f64 / (long_s - short_s);
    println!(
        "{name}: record PNG frames 800x600: {fps:.1} frames/s once running, {:.2}x drawing alone \
         ({long_n} frames in {long_s:.2} s with the context set-up)",
        fps / drawing_fps
    );
}

/// An MP4 video of 5 s at 30 frames/s, 800×600 (context set-up included): its wall
/// time against the 5 s it shows.
fn video<P: Program + Default>(name: &str) {
    let path = std::env::temp_dir().join(format!("ars-viewer-fps-{}.mp4", std::process::id()));
    let recorder = VideoRecorder::new(&path).fps(30.0).size(800, 600);
    let start = Instant::now();
    let (_, made) = recorder.record(&mut P::default(), 5.0).expect("recorded");
    let seconds = start.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(&path);
    println!(
        "{name}: record MP4 video 800x600 at 30 frames/s: {} frames ({} s of video) in {seconds:.2} s, {:.2}x real \
         time, {:.1} frames/s, {} kB",
        made.frames,
        made.duration,
        made.duration / seconds,
        made.frames as f64 / seconds,
        made.bytes / 1000
    );
}

/// Runs `f` on a thread of its own (kiss3d's rendering context is per thread).
fn on_thread<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
    std::thread::spawn(f).join().expect("the measurement ran")
}

fn main() {
    // `cargo bench` passes `--bench`; nothing to parse. A window measurement runs in
    // a process of its own (kiss3d 0.47 makes one context per thread).
    match std::env::var("ARS_VIEWER_FPS_WINDOW").as_deref() {
        Ok("pendulum") => return window("conical pendulum", ConicalPendulum::default()),
        Ok("terrain") => return window("mobile manipulator on terrain", SinusoidalTerrain::default()),
        _ => {}
    }
    let pendulum = on_thread(|| render_only("conical pendulum", ConicalPendulum::default()));
    let terrain = on_thread(|| render_only("mobile manipulator on terrain", SinusoidalTerrain::default()));
    recorder::<ConicalPendulum>("conical pendulum", pendulum);
    recorder::<SinusoidalTerrain>("mobile manipulator on terrain", terrain);
    on_thread(|| video::<ConicalPendulum>("conical pendulum"));
    on_thread(|| video::<SinusoidalTerrain>("mobile manipulator on terrain"));
    let (rss, peak) = memory_mb();
    println!("process: {rss:.0} MB resident, peak {peak:.0} MB");
    // The window where there is a display: run the bench under `xvfb-run -a` to
    // measure it without one.
    if ars::viewer::has_display() {
        for scene in ["pendulum", "terrain"] {
            let exe = std::env::current_exe().expect("this program");
            let status = std::process::Command::new(exe).env("ARS_VIEWER_FPS_WINDOW", scene).status();
            assert!(status.is_ok_and(|s| s.success()), "the {scene} window ran");
        }
    } else {
        println!("window: no display (run under xvfb-run -a to measure it)");
    }
}

fn window<P: Program>(name: &str, mut program: P) {
    use ars::viewer::ProgramViewer;
    let (_, report) = program.show_for(WINDOW_SECONDS).expect("a window");
    let mb = |i: usize| report.resident_mb.get(i).map_or(f64::NAN, |s| s.1);
    println!(
        "{name}: window {}x{}: {:.1} frames/s, {:.2}x real time, {:.0} MB resident after 1 s, {:.0} MB at the end",
        program.window_settings().size.0,
        program.window_settings().size.1,
        report.frames_per_second(),
        report.real_time_factor(),
        mb(1),
        mb(report.resident_mb.len() - 1),
    );
}
