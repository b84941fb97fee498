//! The viewer renders what the simulation holds: off screen with no display and no GPU
//! (Mesa's software rasterisers), and in a real window under Xvfb.
//!
//! A test binary of its own with no harness: on-screen windows must be created on the
//! main thread. Prints `N passed, N failed` like the other runners.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use ars::nalgebra::{Matrix4, Point3, Vector3};
use ars::viewer::image::RgbImage;
use ars::viewer::{OffscreenRenderer, ProgramViewer, ScreenshotRecorder};
use ars::{Hooks, Mass, Program, ProgramRunner, Result, Simulation, WindowSettings};

/// The thesis' falling ball, painted red, seen from the original's camera.
struct RedBall;

impl Hooks for RedBall {}

impl Program for RedBall {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
        sim.scene_mut().set_color(ball, [1.0, 0.0, 0.0])
    }
    fn window_settings(&self) -> WindowSettings {
        WindowSettings { size: (320, 240), ..WindowSettings::default() }
    }
}

/// Where `p` lands in the image: the camera looks from `eye` at `target`, Y up, with a
/// vertical field of view of π/4 (kiss3d's orbit camera).
fn project(view: &WindowSettings, p: Point3<f64>) -> (f64, f64) {
    let (w, h) = (view.size.0 as f64, view.size.1 as f64);
    let v = Matrix4::look_at_rh(&view.camera_position, &view.camera_target, &Vector3::y());
    let proj = Matrix4::new_perspective(w / h, std::f64::consts::FRAC_PI_4, 0.1, 1000.0);
    let c = proj * v * p.to_homogeneous();
    let (x, y) = (c.x / c.w, c.y / c.w);
    ((x + 1.0) / 2.0 * w, (1.0 - y) / 2.0 * h)
}

fn reddish(image: &RgbImage, x: f64, y: f64, radius: i64) -> bool {
    let mut red = 0;
    for dx in -radius..=radius {
        for dy in -radius..=radius {
            let (px, py) = (x as i64 + dx, y as i64 + dy);
            if px < 0 || py < 0 || px >= image.width() as i64 || py >= image.height() as i64 {
                continue;
            }
            let [r, g, b] = image.get_pixel(px as u32, py as u32).0;
            if r > 90 && u32::from(r) > 2 * u32::from(g) && u32::from(r) > 2 * u32::from(b) {
                red += 1;
            }
        }
    }
    red > (2 * radius + 1).pow(2) / 2
}

fn offscreen_frames_show_the_ball_where_it_is() -> std::result::Result<(), String> {
    let view = RedBall.window_settings();
    let mut renderer = OffscreenRenderer::new(&view).map_err(|e| e.to_string())?;
    let mut program = RedBall;
    let mut runner = ProgramRunner::new(&mut program).map_err(|e| e.to_string())?;
    let start = renderer.render(runner.simulation()).map_err(|e| e.to_string())?;
    runner.run_for(1.0).map_err(|e| e.to_string())?;
    let ball = runner.simulation().scene().object("sphere").unwrap().id();
    let rest_center = runner.simulation().scene().position(ball).unwrap();
    let rest = renderer.render(runner.simulation()).map_err(|e| e.to_string())?;
    let _ = start.save(std::env::temp_dir().join("ars_viewer_test_start.png"));
    let _ = rest.save(std::env::temp_dir().join("ars_viewer_test_rest.png"));

    let (x0, y0) = project(&view, Point3::new(1.0, 1.0, 1.0));
    let (x1, y1) = project(&view, rest_center);
    if !reddish(&start, x0, y0, 3) {
        return Err(format!("no red ball at ({x0:.0}, {y0:.0}) in the first frame"));
    }
    if !reddish(&rest, x1, y1, 3) {
        return Err(format!("no red ball at ({x1:.0}, {y1:.0}) in the frame at rest"));
    }
    // Far from the ball (top left corner), no red.
    if reddish(&start, 10.0, 10.0, 3) {
        return Err("red where there is no ball".into());
    }
    let changed =
        start.pixels().zip(rest.pixels()).filter(|(a, b)| a.0.iter().zip(b.0).any(|(p, q)| p.abs_diff(q) > 40)).count();
    if changed < 100 {
        return Err(format!("the frame at rest differs from the first in only {changed} pixels"));
    }
    println!("  ball at ({x0:.0}, {y0:.0}) then ({x1:.0}, {y1:.0}); {changed} pixels changed");

    // A second renderer while the first lives shares its context; after the first is
    // gone, kiss3d 0.47 cannot make another on this thread (it panicked inside
    // kiss3d): a clear error instead.
    let mut second = OffscreenRenderer::new(&view).map_err(|e| e.to_string())?;
    let image = second.render(runner.simulation()).map_err(|e| e.to_string())?;
    if !reddish(&image, x1, y1, 3) {
        return Err("no red ball in the second renderer's frame".into());
    }
    drop((renderer, second));
    match OffscreenRenderer::new(&view) {
        Err(e) if e.to_string().contains("one rendering context per thread") => Ok(()),
        Err(e) => Err(format!("a renderer after the last one closed: unexpected error {e}")),
        Ok(_) => Err("a renderer after the last one closed was made; kiss3d 0.47 fails to draw with it".into()),
    }
}

/// Whether a pixel within `radius` of (x, y) is mostly `channel` (0 red, 1 green, 2
/// blue): the world axes' colours.
fn coloured_near(image: &RgbImage, x: f64, y: f64, radius: i64, channel: usize) -> bool {
    (-radius..=radius).flat_map(|dx| (-radius..=radius).map(move |dy| (x as i64 + dx, y as i64 + dy))).any(
        |(px, py)| {
            if px < 0 || py < 0 || px >= image.width() as i64 || py >= image.height() as i64 {
                return false;
            }
            let p = image.get_pixel(px as u32, py as u32).0;
            let others = (0..3).filter(|c| *c != channel).map(|c| u32::from(p[c])).max().unwrap_or(0);
            p[channel] > 100 && u32::from(p[channel]) > 2 * others
        },
    )
}

/// The world axes are drawn off screen only when asked (`ViewerOptions::axes`): the
/// same empty world, once without and once with them, seen from the original's camera.
fn offscreen_axes_are_drawn_only_when_asked() -> std::result::Result<(), String> {
    use ars::viewer::ViewerOptions;
    let view = WindowSettings { size: (320, 240), ..WindowSettings::default() };
    let sim = Simulation::builder().gravity(Vector3::zeros()).build().map_err(|e| e.to_string())?;
    // Both renderers (and the recorder's below) share the first one's context: it
    // lives to the end.
    let mut default = OffscreenRenderer::new(&view).map_err(|e| e.to_string())?;
    let plain = default.render(&sim).map_err(|e| e.to_string())?;
    let options = ViewerOptions::default().with_axes(true);
    let mut renderer = OffscreenRenderer::with_options(&view, &options).map_err(|e| e.to_string())?;
    let axes = renderer.render(&sim).map_err(|e| e.to_string())?;
    let _ = plain.save(std::env::temp_dir().join("ars_viewer_test_no_axes.png"));
    let _ = axes.save(std::env::temp_dir().join("ars_viewer_test_axes.png"));
    // Along each axis, from a fifth to four fifths of its metre.
    for (channel, name, along) in
        [(0, "X (red)", Vector3::x()), (1, "Y (green)", Vector3::y()), (2, "Z (blue)", Vector3::z())]
    {
        for t in [0.2, 0.5, 0.8] {
            let (x, y) = project(&view, Point3::from(along * t));
            if coloured_near(&plain, x, y, 3, channel) {
                return Err(format!("the {name} axis is drawn at ({x:.0}, {y:.0}) by default"));
            }
            if !coloured_near(&axes, x, y, 2, channel) {
                return Err(format!("no {name} axis at ({x:.0}, {y:.0}) when asked for"));
            }
        }
    }
    // The recorder draws them when asked, too: the Y axis, over a program's floor.
    struct Floor;
    impl Hooks for Floor {}
    impl Program for Floor {
        fn create_sim_objects(&mut self, _: &mut Simulation) -> Result<()> {
            Ok(())
        }
        fn window_settings(&self) -> WindowSettings {
            WindowSettings { size: (320, 240), ..WindowSettings::default() }
        }
    }
    let dir = std::env::temp_dir().join(format!("ars_viewer_test_axes_{}", std::process::id()));
    let recorded = |options: ViewerOptions| -> std::result::Result<RgbImage, String> {
        let (_, written) =
            ScreenshotRecorder::new(&dir).options(options).record(&mut Floor, 0.02).map_err(|e| e.to_string())?;
        Ok(ars::viewer::image::open(&written[0]).map_err(|e| e.to_string())?.to_rgb8())
    };
    let (without, with) = (recorded(ViewerOptions::default())?, recorded(options)?);
    let _ = std::fs::remove_dir_all(&dir);
    for t in [0.5, 0.8] {
        let (x, y) = project(&view, Point3::new(0.0, t, 0.0));
        if coloured_near(&without, x, y, 3, 1) || !coloured_near(&with, x, y, 2, 1) {
            return Err(format!("the recorder's Y axis at ({x:.0}, {y:.0}): drawn by default, or not when asked"));
        }
    }
    println!("  axes: none by default, X, Y and Z where they project when asked");
    drop((default, renderer));
    Ok(())
}

/// Contact forces are drawn off screen only when asked (`ViewerOptions::forces`): a red
/// 2 kg box resting on the floor, once without and once with them: cyan arrows stand
/// above its bottom corners, as tall as 0.05 m per newton make them (the four add up to
/// 2 g N, about 0.98 m).
fn offscreen_contact_forces_are_drawn_when_asked() -> std::result::Result<(), String> {
    use ars::viewer::ViewerOptions;
    struct Resting;
    impl Hooks for Resting {}
    impl Program for Resting {
        fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
            let id = sim.scene_mut().add_box([1.0, 1.0, 1.0], [0.0, 0.5, 0.0], Mass::Total(2.0))?;
            sim.scene_mut().set_color(id, [0.8, 0.1, 0.1])
        }
        fn window_settings(&self) -> WindowSettings {
            WindowSettings {
                size: (320, 240),
                camera_position: Point3::new(4.0, 3.0, 5.0),
                ..WindowSettings::default()
            }
        }
    }
    let dir = std::env::temp_dir().join(format!("ars_viewer_test_forces_{}", std::process::id()));
    // Two recordings on this thread: this renderer holds the thread's one rendering
    // context for both, to the end.
    let holder = OffscreenRenderer::new(&Resting.window_settings()).map_err(|e| e.to_string())?;
    let recorded = |options: ViewerOptions| -> std::result::Result<RgbImage, String> {
        let recorder = ScreenshotRecorder::new(&dir).every(25).options(options);
        let (sim, written) = recorder.record(&mut Resting, 1.0).map_err(|e| e.to_string())?;
        if options.forces && !sim.scene().world().contact_feedback() {
            return Err("the recorder drew forces without asking ODE for them".into());
        }
        let last = written.last().ok_or("no frame")?;
        Ok(ars::viewer::image::open(last).map_err(|e| e.to_string())?.to_rgb8())
    };
    let (without, with) = (recorded(ViewerOptions::default()), recorded(ViewerOptions::default().with_forces(true)));
    drop(holder);
    let _ = std::fs::remove_dir_all(&dir);
    let (without, with) = (without?, with?);
    let _ = with.save(std::env::temp_dir().join("ars_viewer_test_forces.png"));
    let cyan = |image: &RgbImage| image.pixels().filter(|p| p.0[0] < 90 && p.0[1] > 120 && p.0[2] > 140).count();
    let (before, after) = (cyan(&without), cyan(&with));
    // A corner's arrow, from the contact point up a quarter of 0.98 m: cyan halfway.
    let view = Resting.window_settings();
    let (x, y) = project(&view, Point3::new(0.5, 0.12, 0.5));
    let near = (-3..=3i64)
        .flat_map(|dx| (-3..=3i64).map(move |dy| (dx, dy)))
        .filter(|(dx, dy)| {
            let p = with.get_pixel((x as i64 + dx) as u32, (y as i64 + dy) as u32).0;
            p[0] < 90 && p[1] > 120 && p[2] > 140
        })
        .count();
    println!(
        "  forces: {before} cyan pixels without, {after} with; {near} at the front corner's arrow ({x:.0}, {y:.0})"
    );
    if before != 0 || after < 40 || near == 0 {
        return Err("no arrows where the forces act, or arrows when not asked".into());
    }
    Ok(())
}

/// The recorder encodes and writes on worker threads: every frame is there, numbered
/// in order, each the same bytes as the image the renderer draws of the same state
/// saved with `RgbImage::save` (what the recorder wrote itself before).
fn the_recorder_writes_every_frame_as_drawn() -> std::result::Result<(), String> {
    let view = RedBall.window_settings();
    // Kept alive across the recording: the recorder's renderer shares its context.
    let mut renderer = OffscreenRenderer::new(&view).map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("ars_viewer_test_recorder_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let frames = 12;
    let (_, written) =
        ScreenshotRecorder::new(&dir).record(&mut RedBall, f64::from(frames) / 50.0).map_err(|e| e.to_string())?;
    if written.len() != frames as usize + 1 {
        return Err(format!("{} files for {frames} frames and the first", written.len()));
    }
    let mut program = RedBall;
    let mut runner = ProgramRunner::new(&mut program).map_err(|e| e.to_string())?;
    let drawn = dir.join("drawn.png");
    for (i, path) in written.iter().enumerate() {
        if path.file_name().and_then(|n| n.to_str()) != Some(&format!("frame_{:05}.png", i + 1)) {
            return Err(format!("frame {} written as {}", i + 1, path.display()));
        }
        if i > 0 {
            runner.step_frame().map_err(|e| e.to_string())?;
        }
        renderer.render(runner.simulation()).map_err(|e| e.to_string())?.save(&drawn).map_err(|e| e.to_string())?;
        let (a, b) =
            (std::fs::read(path).map_err(|e| e.to_string())?, std::fs::read(&drawn).map_err(|e| e.to_string())?);
        if a != b {
            return Err(format!("{} differs from the image drawn of the same state", path.display()));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    println!("  {} frames, each the bytes of the image drawn of its state", written.len());
    Ok(())
}

/// Starts Xvfb on a display it picks itself (`-displayfd`: the first free one, past
/// stale sockets and locks of servers that died) and returns it with its number.
fn start_xvfb() -> Option<(Child, String)> {
    let mut child = Command::new("Xvfb")
        .args(["-displayfd", "1", "-screen", "0", "1024x768x24", "-nolisten", "tcp"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    let stdout = child.stdout.take()?;
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    match rx.recv_timeout(Duration::from_secs(10)) {
        Ok(line) if line.trim().parse::<u32>().is_ok() => Some((child, format!(":{}", line.trim()))),
        _ => {
            stop_xvfb(child);
            None
        }
    }
}

/// Stops Xvfb with SIGTERM, so that it removes its socket and lock file.
fn stop_xvfb(mut child: Child) {
    let terminated = Command::new("kill").arg(child.id().to_string()).status().is_ok_and(|s| s.success());
    if !terminated {
        let _ = child.kill();
    }
    let deadline = Instant::now() + Duration::from_secs(5);
    while Instant::now() < deadline {
        if let Ok(Some(_)) = child.try_wait() {
            return;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// Without Xvfb the window test fails (`make deps` installs it), unless
/// `ARS_SKIP_WINDOW_TEST=1` says to skip it on purpose: a test that quietly passes as
/// "skipped" would hide a broken window.
fn a_real_window_under_xvfb_shows_the_ball() -> std::result::Result<bool, String> {
    let Some((xvfb, display)) = start_xvfb() else {
        if std::env::var_os("ARS_SKIP_WINDOW_TEST").is_some_and(|v| v == "1") {
            println!("  skipped: Xvfb could not start, and ARS_SKIP_WINDOW_TEST=1");
            return Ok(false);
        }
        return Err("Xvfb could not start: install it (make deps), or set ARS_SKIP_WINDOW_TEST=1 to skip".into());
    };
    // SAFETY: the test is single-threaded at this point (the off-screen test's thread
    // has been joined), so no other thread reads the environment.
    unsafe { std::env::set_var("DISPLAY", &display) };
    let result = RedBall.snapshot_in_window(3);
    stop_xvfb(xvfb);
    let image = result.map_err(|e| e.to_string())?;
    let view = RedBall.window_settings();
    let _ = image.save(std::env::temp_dir().join("ars_viewer_test_window.png"));
    let (x, y) = project(&view, Point3::new(1.0, 1.0, 1.0));
    let (sx, sy) = (x * image.width() as f64 / view.size.0 as f64, y * image.height() as f64 / view.size.1 as f64);
    if !reddish(&image, sx, sy, 2) {
        return Err(format!(
            "no red ball at ({sx:.0}, {sy:.0}) in the window's frame ({}×{})",
            image.width(),
            image.height()
        ));
    }
    println!("  window {}×{} on {display}: ball at ({sx:.0}, {sy:.0})", image.width(), image.height());
    Ok(true)
}

/// Xvfb for a window test, or why not: `Ok(None)` to skip when
/// `ARS_SKIP_WINDOW_TEST=1` says so.
fn xvfb_for_test() -> std::result::Result<Option<(Child, String)>, String> {
    match start_xvfb() {
        Some(x) => Ok(Some(x)),
        None if std::env::var_os("ARS_SKIP_WINDOW_TEST").is_some_and(|v| v == "1") => {
            println!("  skipped: Xvfb could not start, and ARS_SKIP_WINDOW_TEST=1");
            Ok(None)
        }
        None => Err("Xvfb could not start: install it (make deps), or set ARS_SKIP_WINDOW_TEST=1 to skip".into()),
    }
}

/// A window drawing for a minute holds the same memory (it once grew 25 MB/s).
fn window_memory_stays_flat_over_a_minute() -> std::result::Result<bool, String> {
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: no other thread runs now (the threaded tests were joined).
    unsafe { std::env::set_var("DISPLAY", &display) };
    let result = RedBall.show_for(60.0);
    stop_xvfb(xvfb);
    let (_, report) = result.map_err(|e| e.to_string())?;
    let settled: Vec<f64> = report.resident_mb.iter().filter(|(t, _)| *t >= 5.0).map(|(_, mb)| *mb).collect();
    let (low, high) = settled.iter().fold((f64::MAX, f64::MIN), |(l, h), &m| (l.min(m), h.max(m)));
    println!(
        "  {} frames in {:.0} s ({:.1} frames/s, {:.2}x real time); resident {low:.0} to {high:.0} MB from 5 s on",
        report.frames,
        report.wall_seconds,
        report.frames_per_second(),
        report.real_time_factor()
    );
    if settled.len() < 50 {
        return Err(format!("only {} memory samples over the minute", settled.len()));
    }
    if high - low > 16.0 {
        return Err(format!("resident memory grew from {low:.0} to {high:.0} MB over the minute"));
    }
    Ok(true)
}

/// Window after window on one thread once it keeps its rendering context; after the
/// context is given back, another window is refused with an error that says why, and
/// the process ends cleanly (its exit code is checked).
fn windows_one_after_another_when_the_context_is_kept() -> std::result::Result<bool, String> {
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: this process runs this test alone, on its main thread.
    unsafe { std::env::set_var("DISPLAY", &display) };
    ars::viewer::keep_rendering_context();
    let mut frames = Vec::new();
    for _ in 0..3 {
        match RedBall.show_for(0.5) {
            Ok((_, report)) => frames.push(report.frames),
            Err(e) => {
                stop_xvfb(xvfb);
                return Err(format!("window {} failed: {e}", frames.len() + 1));
            }
        }
    }
    ars::viewer::release_rendering_context();
    let refused = RedBall.show_for(0.5);
    stop_xvfb(xvfb);
    println!("  three windows on one thread drew {frames:?} frames");
    if frames.iter().any(|&f| f < 3) {
        return Err(format!("a window drew too few frames: {frames:?}"));
    }
    match refused {
        Err(e) if e.to_string().contains("one rendering context per thread") => Ok(true),
        Err(e) => Err(format!("the window after the release failed otherwise: {e}")),
        Ok(_) => Err("a window opened after the context was given back (kiss3d would fail in it)".into()),
    }
}

/// A window recorded to MP4 for a second and a half of wall time: the video has a
/// frame for every 1/10 s of simulated time the window showed, and ffprobe reads it.
fn a_window_records_a_video() -> std::result::Result<bool, String> {
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: this process runs this test alone, on its main thread.
    unsafe { std::env::set_var("DISPLAY", &display) };
    let path = std::env::temp_dir().join(format!("ars-window-video-{}.mp4", std::process::id()));
    let mut program = RedBall;
    let view = program.window_settings();
    let mut runner = ProgramRunner::new(&mut program).map_err(|e| e.to_string())?;
    let recorded = ars::viewer::run_window_recording(
        &mut runner,
        &view,
        &Default::default(),
        Some(Duration::from_secs_f64(1.5)),
        &path,
        10.0,
    );
    stop_xvfb(xvfb);
    let (report, video) = recorded.map_err(|e| e.to_string())?;
    let shown = runner.simulation().scene().time();
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-show_entries", "stream=codec_name,nb_read_frames,width,height"])
        .args(["-of", "csv=p=0", path.to_str().unwrap_or_default()])
        .output()
        .map_err(|e| format!("ffprobe could not run ({e}): install Debian's ffmpeg (make deps)"))?;
    let _ = std::fs::remove_file(&path);
    let probed = String::from_utf8_lossy(&probe.stdout).trim().to_string();
    println!("  {} window frames, {shown:.2} s simulated: {} video frames ({probed})", report.frames, video.frames);
    if probed != format!("h264,320,240,{}", video.frames) {
        return Err(format!("ffprobe read {probed:?} from a video of {} frames", video.frames));
    }
    // Frames from the first picture (after the first window frame) to the last.
    if video.frames < 3 || video.frames as f64 > shown * 10.0 + 1.0 {
        return Err(format!("{} video frames for {shown:.2} s of simulated time at 10 frames/s", video.frames));
    }
    Ok(true)
}

/// The teleoperated example (IROS example 5) in a real window, driven by a person's
/// keys through xdotool: holding Up drives the vehicle forward; Escape ends the
/// process within 2 s. Run as under CI (no `XDG_RUNTIME_DIR`, no Wayland), its stderr
/// holds the key line it prints and nothing else: no line from the graphics stack.
fn the_arrow_keys_drive_the_vehicle_and_escape_quits() -> std::result::Result<bool, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let example = exe.parent().and_then(|deps| deps.parent()).map(|d| d.join("examples").join("user_driven"));
    let Some(example) = example.filter(|e| e.is_file()) else {
        return Err("the user_driven example is not built (cargo test builds the examples)".into());
    };
    if Command::new("xdotool").arg("version").output().is_err() {
        return Err("xdotool is missing: install it (make deps)".into());
    }
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    let xdotool =
        |args: &[&str]| Command::new("xdotool").args(args).env("DISPLAY", &display).output().map_err(|e| e.to_string());
    let mut child = Command::new(&example)
        .arg("--window")
        .env("DISPLAY", &display)
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("NODEVICE_SELECT")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    let outcome = (|| {
        let found = xdotool(&["search", "--sync", "--name", "user-driven"])?;
        let window = String::from_utf8_lossy(&found.stdout).lines().next().unwrap_or_default().to_string();
        if window.is_empty() {
            return Err("the window did not appear".to_string());
        }
        xdotool(&["windowfocus", "--sync", &window])?;
        std::thread::sleep(Duration::from_millis(500));
        xdotool(&["keydown", "--window", &window, "Up"])?;
        std::thread::sleep(Duration::from_secs(2));
        xdotool(&["keyup", "--window", &window, "Up"])?;
        std::thread::sleep(Duration::from_millis(300));
        xdotool(&["key", "--window", &window, "Escape"])?;
        let pressed = Instant::now();
        while pressed.elapsed() < Duration::from_secs(2) {
            if let Ok(Some(_)) = child.try_wait() {
                return Ok(pressed.elapsed());
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        Err("the process was still running 2 s after Escape".to_string())
    })();
    if outcome.is_err() {
        let _ = child.kill();
    }
    let _ = child.wait();
    stop_xvfb(xvfb);
    let quit_after = outcome?;
    let mut out = String::new();
    child.stdout.take().map(|mut o| std::io::Read::read_to_string(&mut o, &mut out));
    let mut err = String::new();
    child.stderr.take().map(|mut e| std::io::Read::read_to_string(&mut e, &mut err));
    let stray: Vec<&str> = err.lines().filter(|l| *l != ars::viewer::VIEWER_KEYS).collect();
    if !stray.is_empty() || !err.contains(ars::viewer::VIEWER_KEYS) {
        return Err(format!("stderr holds more (or less) than the key line: {err:?}"));
    }
    // "after 4.0 s: chassis from (2.50, 4.00) to (9.50, 4.00) m, heading -0.0 deg"
    let numbers: Vec<f64> =
        out.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-')).filter_map(|w| w.parse().ok()).collect();
    let [_, x0, z0, x1, z1, ..] = numbers[..] else { return Err(format!("unexpected output: {out:?}")) };
    if x1 - x0 < 1.0 || (z1 - z0).abs() > 0.3 {
        return Err(format!("holding Up for 2 s moved the chassis from ({x0}, {z0}) to ({x1}, {z1})"));
    }
    println!("  Up held 2 s: chassis from ({x0}, {z0}) to ({x1}, {z1}); Escape ended it in {quit_after:.2?}");
    Ok(true)
}

/// A red box with its near face 2.5 m in front of a camera at the origin (looking along
/// −Z): the depth reads 2.5 m at the centre, the colour image is red there and
/// background at the corners.
fn a_camera_sees_a_box_in_colour_and_depth() -> std::result::Result<(), String> {
    use ars::viewer::{Camera, Intrinsics};
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().map_err(|e| e.to_string())?;
    let cube =
        sim.scene_mut().add_box([1.0, 1.0, 1.0], [0.0, 0.0, -3.0], Mass::Total(1.0)).map_err(|e| e.to_string())?;
    sim.scene_mut().set_color(cube, [1.0, 0.0, 0.0]).map_err(|e| e.to_string())?;
    let intrinsics = Intrinsics { width: 160, height: 120, fov_y: 0.8, near: 0.1, far: 20.0 };
    let mut camera = Camera::new(intrinsics).map_err(|e| e.to_string())?;
    let frame = camera.capture(&sim).map_err(|e| e.to_string())?;
    let centre = frame.depth.depth(80, 60);
    if (f64::from(centre) - 2.5).abs() > 1e-5 {
        return Err(format!("centre depth {centre}, expected 2.5 m"));
    }
    if !frame.depth.depth(0, 0).is_infinite() || frame.depth_mm().get_pixel(80, 60).0[0] != 2500 {
        return Err("the corner must see nothing and the centre 2500 mm".into());
    }
    if !reddish(&frame.rgb, 80.0, 60.0, 3) || reddish(&frame.rgb, 5.0, 5.0, 3) {
        return Err("the box must be red at the centre of the colour image, the corner not".into());
    }
    let dir = std::env::temp_dir().join(format!("ars-camera-{}", std::process::id()));
    frame.save(&dir, "box").map_err(|e| e.to_string())?;
    for name in ["box_rgb.png", "box_depth.png", "box_depth.npy"] {
        if !dir.join(name).is_file() {
            return Err(format!("{name} not written"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);

    // Rolled 90° about its optical axis (its up is the world's −X): a box to the world's
    // right (+X) is below the middle of both images, and nothing is above it.
    let mut side = Simulation::builder().gravity(Vector3::zeros()).build().map_err(|e| e.to_string())?;
    let right =
        side.scene_mut().add_box([1.0, 1.0, 1.0], [1.2, 0.0, -3.0], Mass::Total(1.0)).map_err(|e| e.to_string())?;
    side.scene_mut().set_color(right, [1.0, 0.0, 0.0]).map_err(|e| e.to_string())?;
    let roll = ars::nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
    let mut rolled = Camera::new(intrinsics)
        .map_err(|e| e.to_string())?
        .at(ars::nalgebra::Isometry3::from_parts(Vector3::zeros().into(), roll));
    let frame = rolled.capture(&side).map_err(|e| e.to_string())?;
    let (below, above) = (frame.depth.depth(80, 110), frame.depth.depth(80, 10));
    if (f64::from(below) - 2.5).abs() > 1e-5 || !above.is_infinite() {
        return Err(format!("rolled depth: {below} m below the middle (2.5 expected), {above} above (nothing)"));
    }
    if !reddish(&frame.rgb, 80.0, 110.0, 2) || reddish(&frame.rgb, 80.0, 10.0, 2) {
        return Err("rolled colour: the red box must be below the middle, as in the depth image".into());
    }

    // At a rate: the box moving away at 1 m/s, a frame every 20 ms for 50 ms.
    let mut camera = camera.every(0.02).map_err(|e| e.to_string())?;
    sim.scene_mut()
        .body_mut(cube)
        .and_then(|mut b| b.set_linear_velocity(Vector3::new(0.0, 0.0, -1.0)))
        .map_err(|e| e.to_string())?;
    let mut seen = Vec::new();
    camera
        .run(&mut sim, 0.05, |t, frame| {
            seen.push((t, frame.depth.depth(80, 60)));
            Ok(())
        })
        .map_err(|e| e.to_string())?;
    let times: Vec<f64> = seen.iter().map(|(t, _)| (t * 1e4).round() / 1e4).collect();
    if times != [0.0, 0.02, 0.04] {
        return Err(format!("frames at {times:?}, expected 0, 20 and 40 ms"));
    }
    if let Some((t, d)) = seen.iter().find(|(t, d)| (f64::from(*d) - (2.5 + t)).abs() > 1e-5) {
        return Err(format!("at {t} s the centre depth is {d}, expected {}", 2.5 + t));
    }
    println!("  camera: centre depth {centre} m; at a rate: {seen:?}");
    Ok(())
}

/// The mean absolute difference of two images of one size, in levels per channel.
fn mean_difference(a: &RgbImage, b: &RgbImage) -> f64 {
    let sum: u64 = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| u64::from(x.abs_diff(*y))).sum();
    sum as f64 / a.as_raw().len() as f64
}

/// The fraction of the pixels of two images of one size that differ by more than 30
/// levels in a channel.
fn differing_fraction(a: &RgbImage, b: &RgbImage) -> f64 {
    let differ = a.pixels().zip(b.pixels()).filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 30));
    differ.count() as f64 / f64::from(a.width() * a.height())
}

/// Four views off screen (`--views 4`): a red box 3 m in front of a depth camera at the
/// origin, a blue ball falling beside it. The four quarters of a frame differ from each
/// other, and the camera quarter is what [`ars::viewer::Camera`] sees from the sensor's
/// place with its field of view and range, at the quarter's size.
fn offscreen_views_split_the_frame_and_the_camera_view_sees_as_the_camera() -> std::result::Result<(), String> {
    use ars::viewer::{Camera, Intrinsics, ViewerOptions};
    let e = |e: ars::Error| e.to_string();
    let mut sim = Simulation::new().map_err(e)?;
    let cube = sim.scene_mut().add_box([1.0, 1.0, 1.0], [0.0, 0.0, -3.0], Mass::Total(1.0)).map_err(e)?;
    sim.scene_mut().set_color(cube, [1.0, 0.0, 0.0]).map_err(e)?;
    sim.scene_mut().body_mut(cube).map(|mut b| b.set_kinematic(true)).map_err(e)?;
    let ball = sim.scene_mut().add_sphere(0.4, [2.0, 2.0, 1.0], Mass::Total(1.0)).map_err(e)?;
    sim.scene_mut().set_color(ball, [0.1, 0.2, 0.9]).map_err(e)?;
    let (fov_y, near, far) = (0.9, 0.1, 30.0);
    sim.add_sensor(ars::sensors::DepthCamera::new(32, 24, fov_y, near, far).map_err(e)?).map_err(e)?;
    for _ in 0..100 {
        sim.step().map_err(e)?;
    }
    let view = WindowSettings {
        size: (640, 480),
        camera_position: Point3::new(3.0, 2.5, 3.0),
        camera_target: Point3::new(0.0, 0.0, -1.5),
        ..WindowSettings::default()
    };
    let options = ViewerOptions::default().with_views(4);
    // One rendering context per thread: the renderer lives while the camera renders.
    let mut renderer = OffscreenRenderer::with_options(&view, &options).map_err(|e| e.to_string())?;
    let frame = renderer.render(&sim).map_err(|e| e.to_string())?;
    let _ = frame.save(std::env::temp_dir().join("ars_viewer_test_views.png"));
    if frame.dimensions() != (640, 480) {
        return Err(format!("a {:?} frame, expected 640 × 480", frame.dimensions()));
    }
    let quarter =
        |i: u32| ars::viewer::image::imageops::crop_imm(&frame, 320 * (i % 2), 240 * (i / 2), 320, 240).to_image();
    let quarters: Vec<RgbImage> = (0..4).map(quarter).collect();
    let names = ["free", "follow", "top", "camera"];
    let mut differences = Vec::new();
    for i in 0..4 {
        for j in i + 1..4 {
            let d = 100.0 * differing_fraction(&quarters[i], &quarters[j]);
            if d < 2.0 {
                return Err(format!("the {} and {} views differ in {d:.2} % of their pixels only", names[i], names[j]));
            }
            differences.push(format!("{}/{} {d:.1} %", names[i], names[j]));
        }
    }
    let intrinsics = Intrinsics { width: 320, height: 240, fov_y, near, far };
    let seen = Camera::new(intrinsics).and_then(|mut c| c.capture(&sim)).map_err(|e| e.to_string())?.rgb;
    let gap = mean_difference(&quarters[3], &seen);
    if gap > 0.5 {
        return Err(format!("the camera view differs from the camera's image by {gap:.2} levels"));
    }
    if !reddish(&quarters[3], 160.0, 120.0, 3) {
        return Err("the camera view must see the red box in its middle".into());
    }
    println!(
        "  views: the quarters' pixels differing: {}; camera view against the camera: {gap:.3} levels",
        differences.join(", ")
    );
    Ok(())
}

/// A 1 kg crate on the floor where the camera looks, in a window big enough for the
/// panel and the editor beside it.
struct Crate;

impl Hooks for Crate {}

impl Program for Crate {
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let id = sim.scene_mut().add_box([0.5, 0.5, 0.5], [0.0, 0.25, 0.0], Mass::Total(1.0))?;
        sim.scene_mut().set_name(id, "crate")?;
        sim.scene_mut().set_color(id, [0.2, 0.4, 0.9])?;
        // A depth camera 3 m in front of the crate, looking at it (along −Z), sampled
        // once a second: what the fourth view shows.
        let camera = ars::sensors::DepthCamera::new(64, 48, 1.0, 0.1, 20.0)?
            .at(ars::nalgebra::Isometry3::translation(0.0, 0.5, 3.0));
        sim.add_sensor_every(camera, 1.0).map(drop)
    }
    fn window_settings(&self) -> WindowSettings {
        WindowSettings {
            title: "touch".into(),
            size: (1024, 768),
            camera_position: Point3::new(4.0, 3.0, 4.0),
            camera_target: Point3::new(0.0, 0.25, 0.0),
            ..WindowSettings::default()
        }
    }
}

/// What the window showed last, and the crate as the simulation holds it.
#[derive(Default)]
struct Seen {
    state: Option<ars::viewer::ViewerState>,
    position: Point3<f64>,
    rotation: ars::nalgebra::UnitQuaternion<f64>,
    mass: f64,
    time: f64,
    /// Frames drawn so far.
    frames: u64,
}

/// The crate's program, driven by the window, telling the test what the window shows.
struct Watched<'p> {
    runner: ProgramRunner<'p, Crate>,
    seen: std::sync::Arc<std::sync::Mutex<Seen>>,
}

impl ars::viewer::Driver for Watched<'_> {
    fn simulation(&mut self) -> impl std::ops::DerefMut<Target = Simulation> + '_ {
        self.runner.simulation_mut()
    }
    fn step_frame(&mut self) -> Result<()> {
        ars::viewer::Driver::step_frame(&mut self.runner)
    }
    fn step(&mut self) -> Result<()> {
        ars::viewer::Driver::step(&mut self.runner)
    }
    fn reset(&mut self) -> Result<()> {
        ars::viewer::Driver::reset(&mut self.runner)
    }
    fn key_down(&mut self, key: ars::Key) -> Result<()> {
        ars::viewer::Driver::key_down(&mut self.runner, key)
    }
    fn key_up(&mut self, key: ars::Key) -> Result<()> {
        ars::viewer::Driver::key_up(&mut self.runner, key)
    }
    fn viewer_state(&mut self, state: &ars::viewer::ViewerState) {
        let sim = self.runner.simulation_mut();
        let object = sim.scene().object("crate").expect("the crate");
        let body = object.body().expect("a body");
        let mut seen = self.seen.lock().unwrap();
        (seen.position, seen.mass, seen.time) = (body.position(), body.mass(), sim.scene().time());
        seen.rotation = body.quaternion();
        seen.frames += 1;
        seen.state = Some(state.clone());
    }
}

/// A person at the window, through xdotool: a click selects the crate (the panel's
/// state names it); a Ctrl-drag 250 px up pulls it up by more than 0.5 m (along the
/// camera's up, read from the simulation) and `p` then writes a screenshot showing the
/// outline and the drag line; paused, a Ctrl-drag 150 px right moves it right by more
/// than 0.5 m with the clock stopped, Ctrl+S saves the scene as it is, and a
/// Shift-drag turns the crate about the camera's up; a mass of -5 typed into the
/// editor is refused with an error and the mass stays 1 kg; Escape deselects, and a
/// second Escape quits.
fn a_person_selects_pulls_and_edits_a_body() -> std::result::Result<bool, String> {
    use std::sync::{Arc, Mutex};
    if Command::new("xdotool").arg("version").output().is_err() {
        return Err("xdotool is missing: install it (make deps)".into());
    }
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: this process runs this test alone, on its main thread, before any other
    // thread starts.
    unsafe { std::env::set_var("DISPLAY", &display) };
    // The window cannot quiet Mesa's device-selection layer once the person's thread
    // runs (see the README): turn it off here, before that thread starts.
    // SAFETY: as above, no other thread yet.
    unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    let shots = std::env::temp_dir().join(format!("ars-touch-{}", std::process::id()));
    std::fs::create_dir_all(&shots).map_err(|e| e.to_string())?;
    std::env::set_current_dir(&shots).map_err(|e| e.to_string())?;
    let seen = Arc::new(Mutex::new(Seen::default()));
    let person = {
        let (seen, display) = (seen.clone(), display.clone());
        std::thread::spawn(move || {
            let acted = act(&seen, &display);
            if acted.is_err() {
                // Close the window: deselect, then quit.
                for _ in 0..2 {
                    let _ = Command::new("xdotool").args(["key", "Escape"]).env("DISPLAY", &display).output();
                    std::thread::sleep(Duration::from_millis(500));
                }
            }
            acted
        })
    };
    let mut program = Crate;
    let view = program.window_settings();
    let runner = ProgramRunner::new(&mut program).map_err(|e| e.to_string())?;
    let mut watched = Watched { runner, seen };
    let window = ars::viewer::run_window(&mut watched, &view, Some(Duration::from_secs(90)));
    let closed = Instant::now();
    let acted = person.join().map_err(|_| "the person's thread panicked".to_string());
    stop_xvfb(xvfb);
    window.map_err(|e| e.to_string())?;
    let (lines, escape) = acted??;
    for line in lines {
        println!("  {line}");
    }
    match closed.checked_duration_since(escape) {
        Some(after) if after < Duration::from_secs(3) => {
            println!("  the second Escape closed the window ({after:.2?} later)");
            let _ = std::env::set_current_dir(std::env::temp_dir());
            // ARS_KEEP_TEST_FILES=1 keeps the screenshots and the saved scene.
            if std::env::var_os("ARS_KEEP_TEST_FILES").is_some_and(|v| v == "1") {
                println!("  files kept in {}", shots.display());
            } else {
                let _ = std::fs::remove_dir_all(&shots);
            }
            Ok(true)
        }
        _ => Err("the window did not close on the second Escape".into()),
    }
}

/// The person's side of [`a_person_selects_pulls_and_edits_a_body`]: what they did and
/// saw, and when they pressed the last Escape.
fn act(seen: &std::sync::Mutex<Seen>, display: &str) -> std::result::Result<(Vec<String>, Instant), String> {
    let xdotool = |args: &[&str]| -> std::result::Result<String, String> {
        let out = Command::new("xdotool").args(args).env("DISPLAY", display).output().map_err(|e| e.to_string())?;
        Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
    };
    let wait = |ms: u64| std::thread::sleep(Duration::from_millis(ms));
    let found = xdotool(&["search", "--sync", "--name", "^touch$"])?;
    let window = found.lines().next().unwrap_or_default().to_string();
    if window.is_empty() {
        return Err("the window did not appear".into());
    }
    xdotool(&["windowfocus", "--sync", &window])?;
    let state = || seen.lock().unwrap().state.clone();
    let crate_now = || {
        let s = seen.lock().unwrap();
        (s.position, s.mass, s.time)
    };
    let started = Instant::now();
    while state().is_none() {
        if started.elapsed() > Duration::from_secs(30) {
            return Err("the window drew no frame in 30 s".into());
        }
        wait(100);
    }
    // Let it settle on the floor and the panel take its place.
    wait(2000);
    let mut lines = Vec::new();
    let to_window = |p: &Point3<f64>| -> std::result::Result<(i64, i64), String> {
        let (x, y) = state().unwrap().window_point(p).ok_or("the crate is behind the camera")?;
        Ok((x.round() as i64, y.round() as i64))
    };
    let move_to = |x: i64, y: i64| xdotool(&["mousemove", "--window", &window, &x.to_string(), &y.to_string()]);
    // The camera's up and right, as the test's own geometry says.
    let view = Crate.window_settings();
    let forward = (view.camera_target - view.camera_position).normalize();
    let up = (Vector3::y() - forward * forward.y).normalize();
    let right = forward.cross(&up);

    // Click: selected.
    let (p0, _, _) = crate_now();
    let (x, y) = to_window(&p0)?;
    move_to(x, y)?;
    wait(300);
    xdotool(&["click", "1"])?;
    wait(700);
    let name = state().unwrap().selected.map(|s| s.name);
    if name.as_deref() != Some("crate") {
        return Err(format!("a click at ({x}, {y}) on the crate selected {name:?}"));
    }
    lines.push(format!("click at ({x}, {y}): the panel shows {:?} selected", name.unwrap()));

    // Ctrl-drag up, running.
    let drag = |dx: i64, dy: i64, screenshot: bool| -> std::result::Result<(), String> {
        xdotool(&["keydown", "ctrl"])?;
        wait(100);
        xdotool(&["mousedown", "1"])?;
        wait(200);
        for i in 1..=10 {
            move_to(x + dx * i / 10, y + dy * i / 10)?;
            wait(60);
        }
        if screenshot {
            // While the crate still trails the mouse: the line is long.
            xdotool(&["key", "p"])?;
        }
        wait(1500);
        Ok(())
    };
    let release = || -> std::result::Result<(), String> {
        xdotool(&["mouseup", "1"])?;
        wait(100);
        xdotool(&["keyup", "ctrl"])?;
        wait(300);
        Ok(())
    };
    let (p0, _, t0) = crate_now();
    let held = drag(0, -250, true);
    let (p1, _, t1) = crate_now();
    let line = state().unwrap().drag;
    release()?;
    held?;
    let moved = p1 - p0;
    lines.push(format!(
        "running, Ctrl-drag 250 px up: crate from {:.2?} to {:.2?} ({:.2} m along the camera's up, {:.2} s)",
        p0.coords.as_slice(),
        p1.coords.as_slice(),
        moved.dot(&up),
        t1 - t0
    ));
    if moved.dot(&up) < 0.5 || t1 <= t0 {
        return Err(lines.pop().unwrap());
    }
    if line.is_none() {
        return Err("no drag line while the button was held".into());
    }
    // The screenshot taken during the drag shows the outline (yellow) and the line (pink).
    let shot = std::fs::read_dir(".")
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.extension().is_some_and(|e| e == "png"))
        .ok_or("no screenshot written by p")?;
    let image = ars::viewer::image::open(&shot).map_err(|e| e.to_string())?.to_rgb8();
    let count = |want: [u8; 3]| {
        image.pixels().filter(|p| p.0.iter().zip(want).all(|(a, b)| (i32::from(*a) - i32::from(b)).abs() < 40)).count()
    };
    // As the window draws them (#FFD900 and #FF3399 come out so, shaded).
    let (yellow, pink) = (count([241, 224, 38]), count([239, 109, 188]));
    lines.push(format!("screenshot {}: {yellow} outline pixels, {pink} drag-line pixels", shot.display()));
    if yellow < 100 || pink < 50 {
        return Err(lines.pop().unwrap());
    }
    // Settle, pause, and drag right, with the panel hidden (g): the crate, wherever it
    // fell, is not under it.
    wait(2000);
    xdotool(&["key", "space"])?;
    xdotool(&["key", "g"])?;
    wait(500);
    let (p0, _, t0) = crate_now();
    if !state().unwrap().paused {
        return Err("space did not pause".into());
    }
    let (x, y) = to_window(&p0)?;
    move_to(x, y)?;
    wait(300);
    let (x, y) = (x, y);
    let held = {
        xdotool(&["keydown", "ctrl"])?;
        wait(100);
        xdotool(&["mousedown", "1"])?;
        wait(200);
        let mut r = Ok(());
        for i in 1..=10 {
            r = r.and(move_to(x + 150 * i / 10, y).map(drop));
            wait(60);
        }
        wait(500);
        r
    };
    release()?;
    held?;
    let (p1, _, t1) = crate_now();
    let moved = p1 - p0;
    lines.push(format!(
        "paused, Ctrl-drag 150 px right: crate from {:.2?} to {:.2?} ({:.2} m along the camera's right; clock {t0} s then {t1} s)",
        p0.coords.as_slice(),
        p1.coords.as_slice(),
        moved.dot(&right)
    ));
    if moved.dot(&right) < 0.5 || t1 != t0 {
        return Err(lines.pop().unwrap());
    }

    // Ctrl+S, paused: the saved scene holds the crate where the drag left it.
    xdotool(&["key", "ctrl+s"])?;
    wait(700);
    let saved = state().unwrap().saved.ok_or("Ctrl+S saved nothing")?;
    let loaded = Simulation::load_scene_from(&saved).map_err(|e| format!("{}: {e}", saved.display()))?;
    let there = loaded.scene().object("crate").and_then(|o| o.position()).map_err(|e| e.to_string())?;
    lines.push(format!("Ctrl+S wrote {}: the crate at {:.2?} in it", saved.display(), there.coords.as_slice()));
    if there != p1 {
        return Err(format!("the saved crate is at {there}, the window's at {p1}"));
    }

    // Paused, Shift-drag 100 px right turns it about the camera's up, its centre kept.
    let (p0, q0) = {
        let s = seen.lock().unwrap();
        (s.position, s.rotation)
    };
    let (x, y) = to_window(&p0)?;
    move_to(x, y)?;
    wait(300);
    let held = {
        xdotool(&["keydown", "shift"])?;
        wait(100);
        xdotool(&["mousedown", "1"])?;
        wait(200);
        let mut r = Ok(());
        for i in 1..=10 {
            r = r.and(move_to(x + 100 * i / 10, y).map(drop));
            wait(60);
        }
        wait(500);
        r
    };
    xdotool(&["mouseup", "1"])?;
    wait(100);
    xdotool(&["keyup", "shift"])?;
    wait(300);
    held?;
    let (p1, q1, t2) = {
        let s = seen.lock().unwrap();
        (s.position, s.rotation, s.time)
    };
    let turn = (q1 * q0.inverse()).scaled_axis();
    lines.push(format!(
        "paused, Shift-drag 100 px right: turned {:.2} rad, {:.2} of it about the camera's up; centre moved {:.1e} m",
        turn.norm(),
        turn.dot(&up),
        (p1 - p0).norm()
    ));
    if turn.dot(&up) < 0.3 || (p1 - p0).norm() > 1e-9 || t2 != t1 {
        return Err(lines.pop().unwrap());
    }

    // An invalid mass typed into the editor (shown again).
    xdotool(&["key", "g"])?;
    wait(500);
    let field = state().unwrap().field("mass").ok_or("no mass field in the editor")?;
    let (fx, fy) = (((field[0] + field[2]) / 2.0) as i64, ((field[1] + field[3]) / 2.0) as i64);
    move_to(fx, fy)?;
    wait(200);
    xdotool(&["click", "1"])?;
    wait(300);
    // Clear the field (as a person would: End, then Backspace), then type.
    xdotool(&["key", "End"])?;
    for _ in 0..12 {
        xdotool(&["key", "BackSpace"])?;
    }
    wait(100);
    xdotool(&["type", "--", "-5"])?;
    wait(100);
    xdotool(&["key", "Return"])?;
    wait(700);
    let (_, mass, _) = crate_now();
    let error = state().unwrap().error;
    lines.push(format!("typed -5 into the mass field: mass {mass} kg, the panel says {error:?}"));
    if mass != 1.0 || !error.as_deref().is_some_and(|e| e.contains("mass")) {
        return Err(lines.pop().unwrap());
    }
    // Escape while typing leaves the field: the window stays, the crate selected. (The
    // error line above the fields moved them down.)
    let field = state().unwrap().field("mass").ok_or("no mass field in the editor")?;
    let (fx, fy) = (((field[0] + field[2]) / 2.0) as i64, ((field[1] + field[3]) / 2.0) as i64);
    move_to(fx, fy)?;
    wait(200);
    xdotool(&["click", "1"])?;
    wait(300);
    xdotool(&["key", "Escape"])?;
    wait(700);
    let frames = seen.lock().unwrap().frames;
    wait(500);
    if seen.lock().unwrap().frames == frames {
        return Err("Escape in the mass field closed the window".into());
    }
    if state().unwrap().selected.is_none() {
        return Err("Escape in the mass field deselected the crate".into());
    }
    lines.push("Escape in the mass field: the field left, the crate still selected".into());
    // Key 4: four views, each its own picture: the free camera (under the panel), the
    // crate followed, the top view and the depth camera's, both showing the blue crate.
    // (g hides the panel and the editor over them first.)
    xdotool(&["key", "g"])?;
    xdotool(&["key", "4"])?;
    wait(2500);
    if state().unwrap().views != 4 {
        return Err("key 4 did not show four views".into());
    }
    xdotool(&["key", "p"])?;
    wait(1000);
    let image =
        ars::viewer::image::open("ars-touch-002.png").map_err(|e| format!("the views' screenshot: {e}"))?.to_rgb8();
    let (w, h) = (image.width() / 2, image.height() / 2);
    let quarter = |i: u32| ((i % 2) * w, (i / 2) * h);
    // Pixel by pixel, each pair of quarters differs (mean absolute difference of the
    // channels), and each shows the blue crate.
    for i in 0..4 {
        for j in i + 1..4 {
            let ((ax, ay), (bx, by)) = (quarter(i), quarter(j));
            let mut total = 0u64;
            for x in 0..w {
                for y in 0..h {
                    let (a, b) = (image.get_pixel(ax + x, ay + y).0, image.get_pixel(bx + x, by + y).0);
                    total += (0..3).map(|c| u64::from(a[c].abs_diff(b[c]))).sum::<u64>();
                }
            }
            let difference = total as f64 / f64::from(3 * w * h);
            if difference < 8.0 {
                return Err(format!("views {} and {} look alike: {difference:.1} apart on average", i + 1, j + 1));
            }
        }
    }
    let blue: Vec<usize> = (0..4)
        .map(|i| {
            let (qx, qy) = quarter(i);
            (qx..qx + w)
                .flat_map(|x| (qy..qy + h).map(move |y| (x, y)))
                .filter(|(x, y)| {
                    let [r, g, b] = image.get_pixel(*x, *y).0;
                    u32::from(b) > u32::from(r) + 60 && u32::from(b) > u32::from(g) + 30
                })
                .count()
        })
        .collect();
    lines.push(format!(
        "key 4: four views, each pair different; blue crate pixels in the free, follow, top and camera views: {blue:?}"
    ));
    if blue.iter().any(|&n| n < 50) {
        return Err(lines.pop().unwrap());
    }
    xdotool(&["key", "1"])?;
    xdotool(&["key", "g"])?;
    wait(500);
    // Escape deselects, the next one quits.
    move_to(x, y + 200)?;
    wait(200);
    xdotool(&["key", "Escape"])?;
    wait(700);
    if let Some(s) = state().unwrap().selected {
        return Err(format!("Escape left {:?} selected", s.name));
    }
    lines.push("Escape: nothing selected".into());
    xdotool(&["key", "Escape"])?;
    Ok((lines, Instant::now()))
}

/// What the window showed last of Gymnasium's ant, and its torso as the simulation
/// held it in the same frame.
#[derive(Default)]
struct AntSeen {
    state: Option<ars::viewer::ViewerState>,
    torso: Point3<f64>,
    rotation: ars::nalgebra::UnitQuaternion<f64>,
    time: f64,
    frames: u64,
    /// The person is done: the window closes (whether or not its keys reach it).
    done: bool,
}

/// Gymnasium's ant (tests/data/ant.xml), opened as `ars view` opens it, driven by the
/// window.
struct Ant {
    sim: Simulation,
    seen: std::sync::Arc<std::sync::Mutex<AntSeen>>,
}

impl Ant {
    const FILE: &'static str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ant.xml");
}

impl ars::viewer::Driver for Ant {
    fn simulation(&mut self) -> impl std::ops::DerefMut<Target = Simulation> + '_ {
        &mut self.sim
    }
    fn step_frame(&mut self) -> Result<()> {
        self.sim.step_frame()
    }
    fn step(&mut self) -> Result<()> {
        self.sim.step()
    }
    fn reset(&mut self) -> Result<()> {
        self.sim = Simulation::open(Ant::FILE)?.simulation;
        Ok(())
    }
    fn key_down(&mut self, _: ars::Key) -> Result<()> {
        Ok(())
    }
    fn key_up(&mut self, _: ars::Key) -> Result<()> {
        Ok(())
    }
    fn wants_to_close(&mut self) -> bool {
        self.seen.lock().unwrap().done
    }
    fn viewer_state(&mut self, state: &ars::viewer::ViewerState) {
        let body = self.sim.scene().object("torso").and_then(|o| o.body().map(|b| (b.position(), b.quaternion())));
        let mut seen = self.seen.lock().unwrap();
        if let Ok((p, q)) = body {
            (seen.torso, seen.rotation) = (p, q);
        }
        seen.time = self.sim.scene().time();
        seen.frames += 1;
        seen.state = Some(state.clone());
    }
}

/// A person at the ant's window through xdotool, and what they see.
struct AtTheAnt<'a> {
    seen: &'a std::sync::Mutex<AntSeen>,
    display: &'a str,
    window: String,
}

impl AtTheAnt<'_> {
    fn xdotool(&self, args: &[&str]) -> std::result::Result<String, String> {
        let out =
            Command::new("xdotool").args(args).env("DISPLAY", self.display).output().map_err(|e| e.to_string())?;
        Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
    }
    fn wait(&self, ms: u64) {
        std::thread::sleep(Duration::from_millis(ms));
    }
    fn state(&self) -> ars::viewer::ViewerState {
        self.seen.lock().unwrap().state.clone().unwrap_or_default()
    }
    fn torso(&self) -> Point3<f64> {
        self.seen.lock().unwrap().torso
    }
    fn time(&self) -> f64 {
        self.seen.lock().unwrap().time
    }
    fn move_to(&self, (x, y): (i64, i64)) -> std::result::Result<(), String> {
        self.xdotool(&["mousemove", "--window", &self.window, &x.to_string(), &y.to_string()]).map(drop)
    }
    /// Where the world point `p` is in the window now.
    fn on_screen(&self, p: &Point3<f64>) -> std::result::Result<(i64, i64), String> {
        let (x, y) = self.state().window_point(p).ok_or("behind the camera")?;
        Ok((x.round() as i64, y.round() as i64))
    }
    /// Where the torso is clicked and grabbed: near its top (a leg, toward the camera,
    /// hides its centre).
    fn torso_top(&self) -> std::result::Result<(i64, i64), String> {
        self.on_screen(&(self.torso() + Vector3::y() * 0.15))
    }
    /// A click on the torso selects it.
    fn select_the_torso(&self) -> std::result::Result<String, String> {
        let at = self.torso_top()?;
        self.move_to(at)?;
        self.wait(300);
        self.xdotool(&["click", "1"])?;
        self.wait(700);
        let name = self.state().selected.map(|s| s.name);
        if name.as_deref() != Some("torso") {
            return Err(format!("a click at {at:?} on the torso selected {name:?}"));
        }
        Ok(format!("click at {at:?}: the torso selected"))
    }
    /// Ctrl held, the left button dragged by (dx, dy) pixels from the torso and held
    /// `hold` ms; returns the torso before and while held, and the state while held.
    fn ctrl_drag(
        &self,
        (dx, dy): (i64, i64),
        hold: u64,
    ) -> std::result::Result<(Point3<f64>, Point3<f64>, ars::viewer::ViewerState), String> {
        let p0 = self.torso();
        let (x, y) = self.torso_top()?;
        self.move_to((x, y))?;
        self.wait(200);
        self.xdotool(&["keydown", "ctrl"])?;
        self.wait(100);
        self.xdotool(&["mousedown", "1"])?;
        self.wait(200);
        for i in 1..=10 {
            self.move_to((x + dx * i / 10, y + dy * i / 10))?;
            self.wait(60);
        }
        self.wait(hold);
        let (p1, during) = (self.torso(), self.state());
        self.xdotool(&["mouseup", "1"])?;
        self.wait(100);
        self.xdotool(&["keyup", "ctrl"])?;
        self.wait(200);
        Ok((p0, p1, during))
    }
    /// A point over the editor beside its mass field (on the field's label), where the
    /// pointer rests.
    fn over_the_editor(&self) -> std::result::Result<(i64, i64), String> {
        let field = self.state().field("mass").ok_or("no mass field in the editor")?;
        Ok((((field[0] + field[2]) / 2.0) as i64 - 120, ((field[1] + field[3]) / 2.0) as i64))
    }
}

/// Opens Gymnasium's ant in a window as `ars view` shows it, under Xvfb with no window
/// manager, and lets a person act on it (`focus`: the person first gives the window
/// the keyboard focus with xdotool, as the other window tests do); the window closes
/// when they are done.
fn with_the_ant(
    focus: bool,
    act: fn(&AtTheAnt) -> std::result::Result<Vec<String>, String>,
) -> std::result::Result<bool, String> {
    use std::sync::{Arc, Mutex};
    if Command::new("xdotool").arg("version").output().is_err() {
        return Err("xdotool is missing: install it (make deps)".into());
    }
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: this process runs this test alone, on its main thread, before any other
    // thread starts.
    unsafe { std::env::set_var("DISPLAY", &display) };
    // SAFETY: as above (see a_person_selects_pulls_and_edits_a_body).
    unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    let seen = Arc::new(Mutex::new(AntSeen::default()));
    let person = {
        let (seen, display) = (seen.clone(), display.clone());
        std::thread::spawn(move || {
            let acted = person_at_the_ant(&seen, &display, focus, act);
            seen.lock().unwrap().done = true;
            acted
        })
    };
    let sim = Simulation::open(Ant::FILE).map_err(|e| e.to_string())?.simulation;
    let mut ant = Ant { sim, seen };
    // As `ars view tests/data/ant.xml` shows it.
    let view = WindowSettings {
        title: "ant".into(),
        camera_position: Point3::new(3.0, 2.0, 3.0),
        camera_target: Point3::new(0.0, 0.4, 0.0),
        ..WindowSettings::default()
    };
    let window = ars::viewer::run_window(&mut ant, &view, Some(Duration::from_secs(40)));
    let acted = person.join().map_err(|_| "the person's thread panicked".to_string());
    stop_xvfb(xvfb);
    window.map_err(|e| e.to_string())?;
    for line in acted?? {
        println!("  {line}");
    }
    Ok(true)
}

/// The person's side of [`with_the_ant`]: finds the window, waits for the ant to
/// settle, and acts.
fn person_at_the_ant(
    seen: &std::sync::Mutex<AntSeen>,
    display: &str,
    focus: bool,
    act: fn(&AtTheAnt) -> std::result::Result<Vec<String>, String>,
) -> std::result::Result<Vec<String>, String> {
    let mut person = AtTheAnt { seen, display, window: String::new() };
    let found = person.xdotool(&["search", "--sync", "--name", "^ant$"])?;
    person.window = found.lines().next().unwrap_or_default().to_string();
    if person.window.is_empty() {
        return Err("the window did not appear".into());
    }
    if focus {
        person.xdotool(&["windowfocus", "--sync", &person.window])?;
    }
    let started = Instant::now();
    while seen.lock().unwrap().state.is_none() {
        if started.elapsed() > Duration::from_secs(30) {
            return Err("the window drew no frame in 30 s".into());
        }
        person.wait(100);
    }
    // The ant falls onto its legs and the panels take their places.
    person.wait(2000);
    act(&person)
}

/// Under Xvfb with no window manager, nobody gives the window the keyboard focus (the
/// user who found this drove `ars view` with xdotool and gave it none): a click selects
/// the torso, and a Ctrl-drag 200 px up pulls it up by more than 0.3 m while the camera
/// stays put. The window never saw Ctrl, and a plain drag turned the camera.
fn a_ctrl_drag_pulls_the_ant_in_a_window_given_no_focus() -> std::result::Result<bool, String> {
    with_the_ant(false, |person| {
        let mut lines = vec![person.select_the_torso()?];
        // The camera's view: where a point 2 m to the right of the one it looks at is
        // drawn, from that one (the picture as a whole may shift, with the panels' size).
        let seen_across = |state: &ars::viewer::ViewerState| {
            let (a, b) = (Point3::new(0.0, 0.4, 0.0), Point3::new(1.5, 0.4, -1.5));
            let ((ax, ay), (bx, by)) = (state.window_point(&a)?, state.window_point(&b)?);
            Some((bx - ax, by - ay))
        };
        let before = seen_across(&person.state()).ok_or("the scene is behind the camera")?;
        let (p0, p1, during) = person.ctrl_drag((0, -200), 1500)?;
        let after = seen_across(&during).ok_or("the scene went behind the camera")?;
        let turned = (after.0 - before.0).hypot(after.1 - before.1);
        lines.push(format!(
            "Ctrl-drag 200 px up: torso from {:.2?} to {:.2?}; the view turned by {turned:.1} px; drag line: {}",
            p0.coords.as_slice(),
            p1.coords.as_slice(),
            during.drag.is_some()
        ));
        if p1.y - p0.y < 0.3 || turned > 1.0 || during.drag.is_none() {
            return Err(lines.pop().unwrap());
        }
        Ok(lines)
    })
}

/// Running, the editor's x, y, z, roll, pitch and yaw fields show the selected torso's
/// pose, whole, as it moves (after a Ctrl-drag has thrown it off its rest): each field's
/// text, as much of it as is drawn, reads as the pose of the same frame to the
/// millimetre or thousandth of a degree, twice half a second apart. (The fields were
/// 72 px wide and cut their text: "-0.20" for -0.207, "-93.8" for -93.878.)
fn the_ant_s_pose_fields_show_its_pose_while_it_runs() -> std::result::Result<bool, String> {
    with_the_ant(true, |person| {
        let mut lines = vec![person.select_the_torso()?];
        let (p0, p1, _) = person.ctrl_drag((120, -150), 1500)?;
        if (p1 - p0).norm() < 0.2 {
            return Err(format!("the Ctrl-drag moved the torso from {p0} to {p1} only"));
        }
        for _ in 0..2 {
            person.wait(500);
            let (torso, rotation, state) = {
                let s = person.seen.lock().unwrap();
                (s.torso, s.rotation, s.state.clone().unwrap_or_default())
            };
            if state.paused || state.selected.is_none() {
                return Err("the ant should run with the torso selected".into());
            }
            let (roll, pitch, yaw) = rotation.euler_angles();
            let pose = [torso.x, torso.y, torso.z, roll.to_degrees(), pitch.to_degrees(), yaw.to_degrees()];
            let mut read = Vec::new();
            for (label, value) in ["x", "y", "z", "roll", "pitch", "yaw"].into_iter().zip(pose) {
                let text = state.field_text(label).ok_or_else(|| format!("no {label} field"))?;
                read.push(format!("{label} {text:?} ({value:.4})"));
                if !text.trim().parse::<f64>().is_ok_and(|v| (v - value).abs() <= 6e-4) {
                    return Err(format!("running, the {label} field shows {text:?}; the torso's {label} is {value}"));
                }
            }
            lines.push(format!("t = {:.2} s, the fields show the torso's pose: {}", person.time(), read.join(", ")));
        }
        Ok(lines)
    })
}

/// Keys with no text field focused act wherever the pointer rests, over the editor too,
/// in a window nobody gave the focus (as `ars view` was driven under Xvfb): `r` resets
/// the ant (its clock goes back, the selection goes), Escape deselects the torso, and
/// the window stays open.
fn keys_act_with_the_pointer_over_the_ant_s_editor() -> std::result::Result<bool, String> {
    with_the_ant(false, |person| {
        let mut lines = vec![person.select_the_torso()?];
        person.move_to(person.over_the_editor()?)?;
        person.wait(500);
        let before = person.time();
        person.xdotool(&["key", "r"])?;
        person.wait(700);
        let (after, selected) = (person.time(), person.state().selected);
        lines
            .push(format!("r over the editor: clock {before:.2} s then {after:.2} s, selected {}", selected.is_some()));
        if after >= before || selected.is_some() {
            return Err(lines.pop().unwrap());
        }
        person.wait(1500);
        lines.push(person.select_the_torso()?);
        person.move_to(person.over_the_editor()?)?;
        person.wait(500);
        person.xdotool(&["key", "Escape"])?;
        person.wait(700);
        let frames = person.seen.lock().unwrap().frames;
        person.wait(300);
        if person.seen.lock().unwrap().frames == frames {
            return Err("Escape over the editor closed the window".into());
        }
        if person.state().selected.is_some() {
            return Err("Escape over the editor left the torso selected".into());
        }
        lines.push("Escape over the editor: nothing selected, the window open".into());
        Ok(lines)
    })
}

/// Runs one test and counts it (`threaded`: on a thread of its own, as off-screen
/// rendering wants; windows stay on the main thread).
fn run<T: Send + 'static>(
    name: &str,
    test: fn() -> std::result::Result<T, String>,
    threaded: bool,
    ran: impl Fn(&T) -> bool,
    tally: &mut (u32, u32, u32),
) {
    println!("test {name} ...");
    let outcome = if threaded {
        std::thread::spawn(test).join().map_err(drop)
    } else {
        std::panic::catch_unwind(test).map_err(drop)
    };
    match outcome {
        Ok(Ok(value)) if ran(&value) => {
            println!("test {name} ... ok");
            tally.0 += 1;
        }
        Ok(Ok(_)) => tally.2 += 1,
        Ok(Err(e)) => {
            println!("test {name} ... FAILED: {e}");
            tally.1 += 1;
        }
        Err(()) => {
            println!("test {name} ... FAILED (panicked)");
            tally.1 += 1;
        }
    }
}

/// A pendulum knocking a ball along the floor, with no sensor: `ars` writes every
/// body's position at every step.
struct Knock;

impl Hooks for Knock {}

impl Program for Knock {
    fn configure(&self, builder: ars::SimulationBuilder) -> ars::SimulationBuilder {
        builder.floor_plane(Vector3::y(), 0.0)
    }
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let bob = sim.scene_mut().add_sphere(0.1, [0.6, 0.8, 0.0], Mass::Total(2.0))?;
        sim.scene_mut().add_hinge_joint(
            "pivot",
            bob,
            ars::JointEnd::World,
            Some([0.0, 0.8, 0.0].into()),
            Vector3::z(),
        )?;
        sim.scene_mut().add_sphere(0.05, [0.0, 0.05, 0.0], Mass::Total(0.3)).map(drop)
    }
    fn window_settings(&self) -> WindowSettings {
        WindowSettings {
            title: "knock".into(),
            size: (640, 480),
            camera_position: Point3::new(1.5, 1.0, 2.5),
            camera_target: Point3::new(0.0, 0.3, 0.0),
            ..WindowSettings::default()
        }
    }
}

/// Every body's position after every frame the window stepped, by step count; and the
/// file Ctrl+S wrote.
#[derive(Default)]
struct History {
    positions: Vec<(u64, Vec<Point3<f64>>)>,
    saved: Option<std::path::PathBuf>,
    drawn: bool,
}

/// [`Knock`] driven by the window, keeping its [`History`].
struct Kept<'p> {
    runner: ProgramRunner<'p, Knock>,
    history: std::sync::Arc<std::sync::Mutex<History>>,
}

impl ars::viewer::Driver for Kept<'_> {
    fn simulation(&mut self) -> impl std::ops::DerefMut<Target = Simulation> + '_ {
        self.runner.simulation_mut()
    }
    fn step_frame(&mut self) -> Result<()> {
        ars::viewer::Driver::step_frame(&mut self.runner)?;
        let sim = self.runner.simulation();
        let positions =
            sim.scene().bodies().filter_map(|(id, _)| sim.scene().body(id).ok().map(|b| b.position())).collect();
        self.history.lock().unwrap().positions.push((sim.scene().step_count(), positions));
        Ok(())
    }
    fn step(&mut self) -> Result<()> {
        ars::viewer::Driver::step(&mut self.runner)
    }
    fn reset(&mut self) -> Result<()> {
        ars::viewer::Driver::reset(&mut self.runner)
    }
    fn key_down(&mut self, key: ars::Key) -> Result<()> {
        ars::viewer::Driver::key_down(&mut self.runner, key)
    }
    fn key_up(&mut self, key: ars::Key) -> Result<()> {
        ars::viewer::Driver::key_up(&mut self.runner, key)
    }
    fn viewer_state(&mut self, state: &ars::viewer::ViewerState) {
        let mut history = self.history.lock().unwrap();
        history.drawn = true;
        if history.saved.is_none() {
            history.saved.clone_from(&state.saved);
        }
    }
}

/// Ctrl+S in a running window saves the scene mid-run, and `ars view` opens the file
/// (in a window, under Xvfb) and goes on exactly as the window went on: every body's
/// position 1 s (2500 steps) after the save, as `ars view --csv` writes it, has the
/// same bits as in the window that saved it.
fn a_scene_saved_with_ctrl_s_goes_on_the_same_under_ars_view() -> std::result::Result<bool, String> {
    use std::sync::{Arc, Mutex};
    if Command::new("xdotool").arg("version").output().is_err() {
        return Err("xdotool is missing: install it (make deps)".into());
    }
    let Some((xvfb, display)) = xvfb_for_test()? else { return Ok(false) };
    // SAFETY: this process runs this test alone, on its main thread, before any other
    // thread starts.
    unsafe { std::env::set_var("DISPLAY", &display) };
    // SAFETY: as above, no other thread yet (see a_person_selects_pulls_and_edits_a_body).
    unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    let dir = std::env::temp_dir().join(format!("ars-ctrl-s-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    std::env::set_current_dir(&dir).map_err(|e| e.to_string())?;
    let history = Arc::new(Mutex::new(History::default()));
    let person = {
        let (history, display) = (history.clone(), display.clone());
        std::thread::spawn(move || -> std::result::Result<(), String> {
            let xdotool = |args: &[&str]| {
                Command::new("xdotool").args(args).env("DISPLAY", &display).output().map_err(|e| e.to_string())
            };
            let found = xdotool(&["search", "--sync", "--name", "^knock$"])?;
            let window = String::from_utf8_lossy(&found.stdout).lines().next().unwrap_or_default().to_string();
            let outcome = (|| {
                if window.is_empty() {
                    return Err("the window did not appear".to_string());
                }
                xdotool(&["windowfocus", "--sync", &window])?;
                let started = Instant::now();
                let step_now = || history.lock().unwrap().positions.last().map_or(0, |p| p.0);
                // Mid-run: once the pendulum has knocked the ball (0.6 s).
                while step_now() < 1500 {
                    if started.elapsed() > Duration::from_secs(60) {
                        return Err("the window did not run 0.6 s in a minute".into());
                    }
                    std::thread::sleep(Duration::from_millis(50));
                }
                xdotool(&["key", "ctrl+s"])?;
                while history.lock().unwrap().saved.is_none() {
                    if started.elapsed() > Duration::from_secs(60) {
                        return Err("Ctrl+S saved nothing".into());
                    }
                    std::thread::sleep(Duration::from_millis(50));
                }
                // On for more than a second after the save.
                let after = step_now() + 3000;
                while step_now() < after {
                    if started.elapsed() > Duration::from_secs(120) {
                        return Err("the window stopped running".into());
                    }
                    std::thread::sleep(Duration::from_millis(50));
                }
                Ok(())
            })();
            // Escape closes the window (nothing is selected).
            let _ = xdotool(&["key", "Escape"]);
            outcome
        })
    };
    let mut program = Knock;
    let view = program.window_settings();
    let runner = ProgramRunner::new(&mut program).map_err(|e| e.to_string())?;
    let mut kept = Kept { runner, history: history.clone() };
    let window = ars::viewer::run_window(&mut kept, &view, Some(Duration::from_secs(150)));
    let acted = person.join().map_err(|_| "the person's thread panicked".to_string());
    let outcome = (|| {
        window.map_err(|e| e.to_string())?;
        acted??;
        let history = history.lock().unwrap();
        let saved = history.saved.clone().ok_or("nothing saved")?;
        let at_save = Simulation::load_scene_from(&saved).map_err(|e| e.to_string())?.scene().step_count();
        let then = at_save + 2500;
        let (_, expected) = history
            .positions
            .iter()
            .find(|(step, _)| *step == then)
            .ok_or(format!("the window never stood at step {then}"))?;
        // The saved file opened in a window by `ars view` for 4 s of wall time (well
        // over 1 s of simulated time at real speed), writing every body's position at
        // every step.
        let csv = dir.join("view.csv");
        let out = Command::new(env!("CARGO_BIN_EXE_ars"))
            .args(["view", saved.to_str().unwrap(), "--duration", "4", "--csv", csv.to_str().unwrap()])
            .env("DISPLAY", &display)
            .output()
            .map_err(|e| e.to_string())?;
        if !out.status.success() {
            return Err(format!("ars view failed: {}", String::from_utf8_lossy(&out.stderr)));
        }
        let text = std::fs::read_to_string(&csv).map_err(|e| e.to_string())?;
        let row: Vec<f64> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|c| c.parse::<f64>().unwrap_or(f64::NAN)).collect::<Vec<f64>>())
            .find(|r| r.get(1) == Some(&(then as f64)))
            .ok_or(format!("ars view did not reach step {then}: {}", String::from_utf8_lossy(&out.stdout).trim()))?;
        let viewed: Vec<Point3<f64>> = row[2..].chunks_exact(3).map(|c| Point3::new(c[0], c[1], c[2])).collect();
        let bits = |ps: &[Point3<f64>]| {
            ps.iter().flat_map(|p| p.coords.iter().map(|c| c.to_bits()).collect::<Vec<_>>()).collect::<Vec<_>>()
        };
        if bits(&viewed) != bits(expected) {
            return Err(format!(
                "1 s after the save, ars view has the bodies at {viewed:?}, the window had {expected:?}"
            ));
        }
        println!(
            "  Ctrl+S at step {at_save} ({}); 2500 steps on, ars view and the window agree to the bit: {:?}",
            saved.display(),
            viewed.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>()
        );
        Ok(true)
    })();
    stop_xvfb(xvfb);
    let _ = std::env::set_current_dir(std::env::temp_dir());
    if outcome.is_ok() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    outcome
}

/// Runs `test` in a new process of this program: kiss3d 0.47 makes one rendering
/// context per thread, and windows live on the main thread.
fn in_own_process(name: &str) -> std::result::Result<bool, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = Command::new(exe).env("ARS_VIEWER_TEST_ONLY", name).output().map_err(|e| e.to_string())?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    print!("{}", stdout.lines().filter(|l| l.starts_with("  ")).map(|l| format!("{l}\n")).collect::<String>());
    match out.status.code() {
        Some(0) => Ok(true),
        Some(3) => Ok(false),
        _ => {
            Err(stdout.lines().find_map(|l| l.strip_prefix("error: ")).unwrap_or("the test process failed").to_string())
        }
    }
}

fn main() {
    if let Ok(name) = std::env::var("ARS_VIEWER_TEST_ONLY") {
        let test = match name.as_str() {
            "window_memory_stays_flat_over_a_minute" => window_memory_stays_flat_over_a_minute,
            "windows_one_after_another_when_the_context_is_kept" => windows_one_after_another_when_the_context_is_kept,
            "a_person_selects_pulls_and_edits_a_body" => a_person_selects_pulls_and_edits_a_body,
            "a_scene_saved_with_ctrl_s_goes_on_the_same_under_ars_view" => {
                a_scene_saved_with_ctrl_s_goes_on_the_same_under_ars_view
            }
            "a_window_records_a_video" => a_window_records_a_video,
            "a_ctrl_drag_pulls_the_ant_in_a_window_given_no_focus" => {
                a_ctrl_drag_pulls_the_ant_in_a_window_given_no_focus
            }
            "the_ant_s_pose_fields_show_its_pose_while_it_runs" => the_ant_s_pose_fields_show_its_pose_while_it_runs,
            "keys_act_with_the_pointer_over_the_ant_s_editor" => keys_act_with_the_pointer_over_the_ant_s_editor,
            other => panic!("no test {other}"),
        };
        match test() {
            Ok(true) => std::process::exit(0),
            Ok(false) => std::process::exit(3),
            Err(e) => {
                println!("error: {e}");
                std::process::exit(1);
            }
        }
    }
    let mut tally = (0, 0, 0);
    let always = |_: &()| true;
    run("a_camera_sees_a_box_in_colour_and_depth", a_camera_sees_a_box_in_colour_and_depth, true, always, &mut tally);
    run(
        "offscreen_frames_show_the_ball_where_it_is",
        offscreen_frames_show_the_ball_where_it_is,
        true,
        always,
        &mut tally,
    );
    run("the_recorder_writes_every_frame_as_drawn", the_recorder_writes_every_frame_as_drawn, true, always, &mut tally);
    run(
        "offscreen_views_split_the_frame_and_the_camera_view_sees_as_the_camera",
        offscreen_views_split_the_frame_and_the_camera_view_sees_as_the_camera,
        true,
        always,
        &mut tally,
    );
    run("offscreen_axes_are_drawn_only_when_asked", offscreen_axes_are_drawn_only_when_asked, true, always, &mut tally);
    run(
        "offscreen_contact_forces_are_drawn_when_asked",
        offscreen_contact_forces_are_drawn_when_asked,
        true,
        always,
        &mut tally,
    );
    let shown = |ran: &bool| *ran;
    run("a_real_window_under_xvfb_shows_the_ball", a_real_window_under_xvfb_shows_the_ball, false, shown, &mut tally);
    run(
        "the_arrow_keys_drive_the_vehicle_and_escape_quits",
        the_arrow_keys_drive_the_vehicle_and_escape_quits,
        false,
        shown,
        &mut tally,
    );
    run(
        "window_memory_stays_flat_over_a_minute",
        || in_own_process("window_memory_stays_flat_over_a_minute"),
        false,
        shown,
        &mut tally,
    );
    run(
        "windows_one_after_another_when_the_context_is_kept",
        || in_own_process("windows_one_after_another_when_the_context_is_kept"),
        false,
        shown,
        &mut tally,
    );
    run(
        "a_person_selects_pulls_and_edits_a_body",
        || in_own_process("a_person_selects_pulls_and_edits_a_body"),
        false,
        shown,
        &mut tally,
    );
    run(
        "a_scene_saved_with_ctrl_s_goes_on_the_same_under_ars_view",
        || in_own_process("a_scene_saved_with_ctrl_s_goes_on_the_same_under_ars_view"),
        false,
        shown,
        &mut tally,
    );
    run("a_window_records_a_video", || in_own_process("a_window_records_a_video"), false, shown, &mut tally);
    run(
        "a_ctrl_drag_pulls_the_ant_in_a_window_given_no_focus",
        || in_own_process("a_ctrl_drag_pulls_the_ant_in_a_window_given_no_focus"),
        false,
        shown,
        &mut tally,
    );
    run(
        "the_ant_s_pose_fields_show_its_pose_while_it_runs",
        || in_own_process("the_ant_s_pose_fields_show_its_pose_while_it_runs"),
        false,
        shown,
        &mut tally,
    );
    run(
        "keys_act_with_the_pointer_over_the_ant_s_editor",
        || in_own_process("keys_act_with_the_pointer_over_the_ant_s_editor"),
        false,
        shown,
        &mut tally,
    );
    let (passed, failed, skipped) = tally;
    println!("{passed} passed, {failed} failed, {skipped} skipped");
    if failed > 0 {
        std::process::exit(1);
    }
}
