//! The browser replay (`ReplayRecorder`, `--html`): a self-contained HTML file that
//! headless Chromium (Debian's `chromium`) plays, with the network disabled, showing
//! the bodies where the simulation had them: its screenshot's silhouette against the
//! off-screen renderer's at the same simulated time. Bad settings leave no file.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use ars::nalgebra::{Point3, Vector3};
use ars::sensors::Gps;
use ars::viewer::image::{self, RgbImage};
use ars::viewer::{OffscreenRenderer, ReplayRecorder};
use ars::{Hooks, JointEnd, Mass, Program, ProgramRunner, Result, Simulation, SimulationBuilder, WindowSettings};

/// Two pendulums of several shapes (a box arm with a ball at its end, a cylinder with
/// a cone, a capsule), swinging about Z, with a GPS on the ball; no floor: the
/// background is all that is not a body.
struct Pendulums;

impl Hooks for Pendulums {}

impl Program for Pendulums {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        builder
    }
    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        let arm = sim.scene_mut().add_box([0.8, 0.08, 0.08], [0.4, 1.8, 0.0], Mass::Total(0.5))?;
        let ball = sim.scene_mut().add_sphere(0.18, [0.85, 1.8, 0.0], Mass::Total(1.0))?;
        sim.scene_mut().set_color(ball, [0.9, 0.2, 0.1])?;
        sim.scene_mut().add_fixed_joint("weld", arm, ball)?;
        sim.scene_mut().add_hinge_joint(
            "pivot",
            arm,
            JointEnd::World,
            Some(Point3::new(0.0, 1.8, 0.0)),
            Vector3::z(),
        )?;
        let drum = sim.scene_mut().add_cylinder(0.15, 0.3, [-0.7, 1.5, 0.0], Mass::Total(1.0))?;
        let tip = sim.scene_mut().add_cone(0.12, 0.3, [-0.7, 1.5, 0.3], Mass::Total(0.2))?;
        sim.scene_mut().add_fixed_joint("cap", drum, tip)?;
        sim.scene_mut().add_hinge_joint(
            "swing",
            drum,
            JointEnd::World,
            Some(Point3::new(-0.3, 1.8, 0.0)),
            Vector3::z(),
        )?;
        let capsule = sim.scene_mut().add_capsule(0.1, 0.4, [0.0, 0.8, 0.0], Mass::Total(1.0))?;
        sim.scene_mut().add_hinge_joint(
            "hang",
            capsule,
            JointEnd::World,
            Some(Point3::new(0.3, 1.1, 0.0)),
            Vector3::z(),
        )?;
        sim.add_sensor(Gps::new(ball)).map(drop)
    }
    fn window_settings(&self) -> WindowSettings {
        WindowSettings {
            size: (320, 240),
            camera_position: Point3::new(1.2, 1.6, 3.6),
            camera_target: Point3::new(0.0, 1.2, 0.0),
            ..WindowSettings::default()
        }
    }
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ars-replay-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Debian's Chromium, which the Makefile's `deps` installs; the test fails without it.
fn chromium() -> PathBuf {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if let Some(dir) =
            std::env::var_os("PATH").iter().flat_map(std::env::split_paths).find(|d| d.join(name).is_file())
        {
            return dir.join(name);
        }
    }
    panic!("headless Chromium is needed for this test: sudo apt-get install chromium (make deps installs it)");
}

/// Runs headless Chromium on `page` with the network disabled (every host resolves to
/// nothing, every request goes to a closed proxy), software WebGL (SwiftShader), and
/// enough virtual time for the page to inflate its data and play; `what` is
/// Chromium's task (`--screenshot=...` or `--dump-dom`). Returns its standard output.
///
/// A run takes 10 to 30 s on a loaded 2-core machine. Now and then (twice in some
/// thirty runs here, with other builds running) headless Chromium never ends a
/// virtual-time run: after 90 s it is stopped and run again, three times at most.
fn run_chromium(page: &Path, hash: &str, size: (u32, u32), what: &str) -> String {
    for attempt in 1..=3 {
        if let Some(out) = try_chromium(page, hash, size, what, Duration::from_secs(90)) {
            return out;
        }
        eprintln!("chromium did not finish {what} within 90 s (attempt {attempt} of 3)");
    }
    panic!("chromium did not finish {what} in three attempts");
}

fn try_chromium(page: &Path, hash: &str, size: (u32, u32), what: &str, limit: Duration) -> Option<String> {
    let profile = page.with_file_name("chromium-profile");
    let _ = std::fs::remove_dir_all(&profile);
    let (out, err) = (page.with_file_name("chromium.out"), page.with_file_name("chromium.err"));
    let url = format!("file://{}#{hash}", page.display());
    let mut child = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu-sandbox",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--force-device-scale-factor=1",
            "--hide-scrollbars",
            "--no-first-run",
            "--disable-extensions",
            "--proxy-server=127.0.0.1:9",
            "--host-resolver-rules=MAP * ~NOTFOUND",
            "--virtual-time-budget=5000",
            &format!("--user-data-dir={}", profile.display()),
            &format!("--window-size={},{}", size.0, size.1),
            what,
            &url,
        ])
        .stdin(Stdio::null())
        // Into files: a pipe nobody reads while waiting would fill and stop it.
        .stdout(Stdio::from(std::fs::File::create(&out).unwrap()))
        .stderr(Stdio::from(std::fs::File::create(&err).unwrap()))
        .spawn()
        .expect("chromium starts");
    let deadline = Instant::now() + limit;
    while child.try_wait().expect("chromium runs").is_none() {
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let status = child.wait().expect("chromium ran");
    assert!(status.success(), "chromium failed: {}", std::fs::read_to_string(&err).unwrap_or_default());
    Some(std::fs::read_to_string(&out).unwrap())
}

/// The pixels that are not the background (white): a body's silhouette.
fn silhouette(image: &RgbImage, width: u32, height: u32) -> Vec<bool> {
    let mut mask = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let [r, g, b] = image.get_pixel(x, y).0;
            mask.push(u32::from(255 - r) + u32::from(255 - g) + u32::from(255 - b) > 60);
        }
    }
    mask
}

/// The screenshot of the replay at `t` (played from the start to `t` through the
/// page's `#until=` API) against the off-screen frame of the same simulated time: the
/// bodies' silhouettes (every pixel not white) overlap by at least 80 % as
/// intersection over union.
#[test]
fn chromium_plays_the_replay_and_shows_the_bodies_where_the_simulation_had_them() {
    let dir = temp_dir("silhouette");
    let page = dir.join("pendulums.html");
    let (sim, replay) = ReplayRecorder::new().plot("Gps 1: y").record_to(&mut Pendulums, 3.0, &page).unwrap();
    assert!((sim.scene().time() - 3.0).abs() < 1e-9);
    let html = std::fs::read_to_string(&page).unwrap();
    assert_eq!(html, replay.html());
    // Nothing to fetch: no address, no external script or style.
    for outside in ["http://", "https://", "src=", "href=", "@import"] {
        assert!(!html.contains(outside), "the page refers to something outside it: {outside:?}");
    }
    // The simulation's frame rate: 50 frames a second.
    assert_eq!(sim.scene().time_step() * f64::from(sim.scene().steps_per_frame()), 0.02);
    assert_eq!(replay.frames(), 151);

    let view = Pendulums.window_settings();
    let (w, h) = view.size;
    // The off-screen frame at t = 1.56 s (78 frames), its silhouettes.
    let mut program = Pendulums;
    let mut runner = ProgramRunner::new(&mut program).unwrap();
    for _ in 0..78 {
        runner.step_frame().unwrap();
    }
    let t = runner.simulation().scene().time();
    assert!((t - 1.56).abs() < 1e-9);
    let mut renderer = OffscreenRenderer::new(&view).unwrap();
    let offscreen = renderer.render(runner.simulation()).unwrap();
    offscreen.save(dir.join("offscreen.png")).unwrap();

    // The page played to t; the screenshot's window is the view's size plus the
    // controls below it: the 3D view is its top-left corner.
    let shot = dir.join("replay.png");
    let hash = format!("until={t}");
    run_chromium(&page, &hash, (w, h + 200), &format!("--screenshot={}", shot.display()));
    let screenshot = image::open(&shot).unwrap().to_rgb8();
    // The page's own word on where it stopped.
    let dom = run_chromium(&page, &hash, (w, h + 200), "--dump-dom");
    assert!(dom.contains(&format!("t = {t:.3} s / 3.000 s")), "the page did not stop at {t}: {dom:.2000}");
    assert!(dom.contains("<div id=\"ars-error\"></div>"), "the page reported an error: {dom:.4000}");

    let a = silhouette(&offscreen, w, h);
    let b = silhouette(&screenshot, w, h);
    let both = a.iter().zip(&b).filter(|(a, b)| **a && **b).count();
    let either = a.iter().zip(&b).filter(|(a, b)| **a || **b).count();
    let off_area = a.iter().filter(|a| **a).count();
    let iou = both as f64 / either as f64;
    eprintln!(
        "silhouettes at t = {t} s: off-screen {off_area} px, replay {} px, intersection {both} px, IoU {iou:.3}, \
         intersection / off-screen {:.3}",
        b.iter().filter(|b| **b).count(),
        both as f64 / off_area as f64
    );
    assert!(off_area > 1500, "the bodies are too small to compare: {off_area} px");
    assert!(iou >= 0.8, "the replay's bodies are not where the simulation had them: IoU {iou:.3}");

    // At the start the pendulums are elsewhere: the comparison can fail.
    renderer.reset();
    let start = silhouette(&renderer.render(&Pendulums.create_simulation().unwrap()).unwrap(), w, h);
    let both = start.iter().zip(&b).filter(|(a, b)| **a && **b).count();
    let either = start.iter().zip(&b).filter(|(a, b)| **a || **b).count();
    assert!((both as f64 / either as f64) < 0.8, "the start and t = {t} s look alike: the test proves nothing");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A minute of a pendulum at the simulation's frame rate is far under 5 MB.
#[test]
fn a_minute_of_a_pendulum_stays_small() {
    let (_, replay) = ReplayRecorder::new().plot("Gps 1: y [m]").record(&mut Pendulums, 60.0).unwrap();
    let bytes = replay.html().len();
    eprintln!("60 s of the pendulums: {} frames, {bytes} bytes", replay.frames());
    assert_eq!(replay.frames(), 3001);
    assert!(bytes < 5_000_000, "{bytes} bytes");
}

#[test]
fn bad_settings_are_refused_and_leave_no_file() {
    let dir = temp_dir("refused");
    let page = dir.join("out.html");
    let refused = |recorder: ReplayRecorder, path: &Path, expected: &str| {
        let e = recorder.record_to(&mut Pendulums, 1.0, path).map(drop).unwrap_err().to_string();
        assert!(e.contains(expected), "{e:?} does not say {expected:?}");
    };
    refused(ReplayRecorder::new().fps(0.0), &page, "frame rate must be positive, got 0");
    refused(ReplayRecorder::new().fps(-5.0), &page, "frame rate must be positive, got -5");
    refused(ReplayRecorder::new().fps(f64::NAN), &page, "frame rate must be positive, got NaN");
    refused(
        ReplayRecorder::new().plot("Gps 2: y"),
        &page,
        "no sensor column \"Gps 2: y\" to plot; the columns are: Gps 1: x [m]",
    );
    refused(ReplayRecorder::new(), &dir.join("missing/out.html"), "missing/out.html");
    refused(ReplayRecorder::new(), &dir, "it is a folder");
    let mut empty = Simulation::new().unwrap();
    let e = ReplayRecorder::new().record_simulation_to(&mut empty, &WindowSettings::default(), 1.0, &page);
    let e = e.map(drop).unwrap_err().to_string();
    assert!(e.contains("nothing to replay: the simulation has no objects"), "{e}");
    let e = ReplayRecorder::new().record_to(&mut Pendulums, 0.0, &page).map(drop).unwrap_err().to_string();
    assert!(e.contains("duration must be positive"), "{e}");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
    // An existing file is replaced only by a complete replay.
    std::fs::write(&page, "before").unwrap();
    refused(ReplayRecorder::new().fps(0.0), &page, "frame rate");
    assert_eq!(std::fs::read_to_string(&page).unwrap(), "before");
    let _ = std::fs::remove_dir_all(&dir);
}
